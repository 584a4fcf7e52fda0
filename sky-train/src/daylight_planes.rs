//! sky-core's table of the sky's light on vertical planes (`sky-core/src/daylight/plane_tables.rs`),
//! the anisotropic sky of `Daylight::tilted`, from the physical atmosphere
//! ([`crate::physical`]) in two steps, as [`crate::daylight_tables`] makes the diffuse table:
//!
//! 1. **sample** (slow: the atmospheres of [`AOD_NODES`], cached, then some 45 ms a sun
//!    position): at every optical depth of [`AOD_NODES`] and sun elevation of
//!    [`elevation_nodes`], the reference's own integral of its sky over a vertical plane
//!    ([`PhysicalSky::sky_irradiance`]) whose normal lies at each azimuth of
//!    [`AZIMUTH_NODES_DEG`] from the sun's, over the diffuse horizontal illuminance of the same
//!    sky, per CIE X, Y, Z channel (the ratio V, 0.5 for a uniform sky), written to
//!    [`DATA_PATH`];
//! 2. **table** (fast, what the regeneration test reruns): the Rust source of the table, ln V
//!    in fixed point ([`LN_SCALE`]), from that file.
//!
//! sky-core multiplies V by its own diffuse illuminance, so the vertical plane's sky has the
//! diffuse table's optical-depth interpolation (quadratic in ln τ through the same nodes).

use std::fmt::Write as _;
use std::path::Path;

use anyhow::Result;

use crate::daylight_tables::{self, AOD_NODES, atmosphere};
use crate::physical::photometry::Colorimetry;
use crate::physical::{PhysicalSky, cache};
use crate::sampled_grid;

/// The sampled reference, relative to the repository root.
pub const DATA_PATH: &str = "sky-train/data/daylight_planes.csv";
/// The generated table, relative to the repository root.
pub const TABLES_PATH: &str = "sky-core/src/daylight/plane_tables.rs";
/// The command that regenerates [`TABLES_PATH`] from [`DATA_PATH`].
pub const COMMAND: &str = "sky-train daylight-planes --data sky-train/data/daylight_planes.csv --out sky-core/src/daylight/plane_tables.rs";

/// Azimuths of the plane's normal from the sun's, degrees: 0 faces the sun, 180 faces away.
/// Every vertical plane's sky has a kink at 90° (where the sun's aureole crosses the plane), so
/// sky-core interpolates each side, 0°-90° and 90°-180°, on its own (cubic in the cosine of the
/// azimuth through its four nodes).
pub const AZIMUTH_NODES_DEG: [f64; 7] = [0.0, 30.0, 60.0, 90.0, 120.0, 150.0, 180.0];

/// The fixed point of the table: ln V × 2¹² as an i16 (V from e⁻⁸ to e⁸, steps of 2.4·10⁻⁴ in
/// ln V).
pub const LN_SCALE: f64 = 4096.0;

/// The range every ratio V of [`DATA_PATH`] must lie in: the table's fixed point holds
/// e^(±8); a vertical plane's sky is within a factor 50 of half the horizontal's.
pub const RATIO_RANGE: (f64, f64) = (1e-2, 1e2);

/// The sun elevations of the table, ascending, degrees: the reference's own sun nodes from −6°
/// to 90° (0.5° at dusk, 2° to 30°, 5° above; the reference is log-linear between them), and
/// every 2° below −6°, where the sky is dim (under 3 lx) and the reference's ratio V itself
/// alternates by a few per cent from one of its 0.5° nodes to the next.
#[must_use]
pub fn elevation_nodes() -> Vec<f64> {
    daylight_tables::elevation_nodes()
        .into_iter()
        .filter(|&h| h >= -6.0 || (h.fract() == 0.0 && (h as i64) % 2 == 0))
        .collect()
}

/// One row of samples: the ratios V of the sky's light on vertical planes at every azimuth of
/// [`AZIMUTH_NODES_DEG`] to the diffuse horizontal light, at one optical depth and sun
/// elevation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlaneSample {
    /// Aerosol optical depth at 550 nm.
    pub aod: f64,
    /// Geometric sun elevation, degrees.
    pub elevation_deg: f64,
    /// V per azimuth node, X, Y, Z.
    pub ratios: [[f64; 3]; AZIMUTH_NODES_DEG.len()],
}

/// The unit normal of a vertical plane facing `azimuth_deg` from the sun at azimuth 0.
#[must_use]
pub fn vertical_normal(azimuth_deg: f64) -> [f64; 3] {
    let a = azimuth_deg.to_radians();
    [a.cos(), a.sin(), 0.0]
}

/// The ratios V of `sky` (its sun at azimuth 0) at the azimuths of [`AZIMUTH_NODES_DEG`]: the
/// X, Y, Z of [`PhysicalSky::sky_irradiance`] over those of its diffuse horizontal irradiance.
#[must_use]
pub fn ratios(sky: &PhysicalSky) -> [[f64; 3]; AZIMUTH_NODES_DEG.len()] {
    let diffuse = Colorimetry::of(&sky.irradiance().diffuse).xyz;
    let planes = sky.sky_irradiance(AZIMUTH_NODES_DEG.map(vertical_normal));
    planes.map(|e| {
        let xyz = Colorimetry::of(&e).xyz;
        std::array::from_fn(|c| xyz[c] / diffuse[c])
    })
}

/// The slow step: every optical depth of [`AOD_NODES`] at every [`elevation_nodes`] elevation,
/// each atmosphere precomputed (or read from `cache_dir`), with a progress bar when `progress`.
///
/// # Errors
/// When an atmosphere cannot be built or cached.
pub fn sample(cache_dir: &cache::CacheDir, progress: bool) -> Result<Vec<PlaneSample>> {
    sampled_grid::sample(
        (cache_dir, progress),
        (&AOD_NODES, atmosphere),
        &elevation_nodes(),
        |aod, h, sky| PlaneSample {
            aod,
            elevation_deg: h,
            ratios: ratios(sky),
        },
    )
}

/// The longest `--data` file read: the grid's rows take some 300 bytes each.
pub const MAX_DATA_BYTES: u64 = 1 << 20;

/// The CSV header: the optical depth, the elevation and V per azimuth node and channel.
#[must_use]
pub fn header() -> String {
    let mut s = String::from("aod,sun_elevation_deg");
    for a in AZIMUTH_NODES_DEG {
        for c in ["x", "y", "z"] {
            let _ = write!(s, ",v{a}_{c}");
        }
    }
    s
}

/// Writes `samples` as CSV to `path`, atomically.
///
/// # Errors
/// When the file cannot be written.
pub fn write_samples(path: &Path, samples: &[PlaneSample]) -> Result<()> {
    let flat: Vec<Vec<f64>> = samples
        .iter()
        .map(|r| r.ratios.iter().flatten().copied().collect())
        .collect();
    sampled_grid::write(
        path,
        &header(),
        samples
            .iter()
            .zip(&flat)
            .map(|(r, v)| (r.aod, r.elevation_deg, v.as_slice())),
    )
}

/// Reads the samples of `path` and checks they are the grid [`sample`] writes: every optical
/// depth of [`AOD_NODES`] at every [`elevation_nodes`] elevation, in that order, with finite
/// ratios in [`RATIO_RANGE`].
///
/// # Errors
/// A [`crate::args::ParamError`] (bad input, exit status 2) naming the file and line of the
/// first bad row or field, and for a file without the header or rows; a plain error when it
/// cannot be read.
pub fn read_samples(path: &Path) -> Result<Vec<PlaneSample>> {
    let grid = sampled_grid::grid(&AOD_NODES, &elevation_nodes());
    let (lo, hi) = RATIO_RANGE;
    let rows = sampled_grid::read(path, MAX_DATA_BYTES, &header(), &grid, |column, v| {
        (!(lo..=hi).contains(&v)).then(|| {
            format!(
                "{column} = {} is outside the valid range [{}, {}]",
                crate::csv_output::compact(v),
                crate::csv_output::compact(lo),
                crate::csv_output::compact(hi)
            )
        })
    })?;
    Ok(rows
        .into_iter()
        .map(|r| PlaneSample {
            aod: r.aod,
            elevation_deg: r.elevation_deg,
            ratios: std::array::from_fn(|a| std::array::from_fn(|c| r.values[3 * a + c])),
        })
        .collect())
}

/// ln `v` in the table's fixed point ([`LN_SCALE`]), rounded to nearest.
#[must_use]
#[allow(clippy::cast_possible_truncation)]
pub fn fixed(v: f64) -> i16 {
    (v.ln() * LN_SCALE).round().clamp(-32767.0, 32767.0) as i16
}

/// The Rust source of `sky-core/src/daylight/plane_tables.rs` from `samples` (as [`read_samples`]
/// checked them).
#[must_use]
pub fn rust_source(samples: &[PlaneSample]) -> String {
    let elevations = elevation_nodes();
    let (na, ne, nz) = (AOD_NODES.len(), elevations.len(), AZIMUTH_NODES_DEG.len());
    let mut s = String::new();
    let _ = writeln!(s, "// Generated by `{COMMAND}`; do not edit.");
    let _ = writeln!(s, "//");
    let _ = writeln!(
        s,
        "// sky-train's physical atmosphere at the diffuse table's optical depths (tables.rs): the sky's light on"
    );
    let _ = writeln!(
        s,
        "// vertical planes over its diffuse horizontal light (sky-train/src/daylight_planes.rs).\n"
    );
    let _ = writeln!(
        s,
        "/// Sun elevations of the table's rows, degrees, ascending."
    );
    let _ = writeln!(s, "#[rustfmt::skip]");
    #[allow(clippy::cast_possible_truncation)]
    let list = elevations
        .iter()
        .map(|h| format!("{:?}", *h as f32))
        .collect::<Vec<_>>()
        .join(", ");
    let _ = writeln!(
        s,
        "pub(crate) const PLANE_ELEVATION_DEG: [f32; {ne}] = [{list}];\n"
    );
    let _ = writeln!(
        s,
        "/// 1 / the fixed point of [`LN_VERTICAL`]: ln V = value × this."
    );
    let _ = writeln!(
        s,
        "pub(crate) const LN_VERTICAL_STEP: f32 = 1.0 / {LN_SCALE:?};\n"
    );
    let _ = writeln!(
        s,
        "/// ln V, the sky's X, Y, Z on a vertical plane over the diffuse horizontal X, Y, Z, in fixed point,"
    );
    let _ = writeln!(
        s,
        "/// [optical depth][elevation][channel][the plane's azimuth from the sun's: {}°].",
        AZIMUTH_NODES_DEG
            .iter()
            .map(|a| format!("{a}"))
            .collect::<Vec<_>>()
            .join(", ")
    );
    let _ = writeln!(s, "#[rustfmt::skip]");
    let _ = writeln!(
        s,
        "pub(crate) const LN_VERTICAL: [[[[i16; {nz}]; 3]; {ne}]; {na}] = ["
    );
    for row in samples.chunks(ne) {
        let _ = writeln!(s, "    [");
        for r in row {
            let channels: Vec<String> = (0..3)
                .map(|c| {
                    let v: Vec<String> = r.ratios.iter().map(|a| fixed(a[c]).to_string()).collect();
                    format!("[{}]", v.join(", "))
                })
                .collect();
            let _ = writeln!(s, "        [{}],", channels.join(", "));
        }
        let _ = writeln!(s, "    ],");
    }
    let _ = writeln!(s, "];");
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The shipped samples read back; a ratio out of range or a short row is refused naming
    /// the file, the line and the column.
    #[test]
    fn samples_are_range_checked() {
        let shipped = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/daylight_planes.csv");
        let good = std::fs::read_to_string(&shipped).expect("shipped data");
        assert_eq!(
            read_samples(&shipped).expect("shipped").len(),
            AOD_NODES.len() * elevation_nodes().len()
        );
        let dir = tempfile::tempdir().expect("temp dir");
        let data = dir.path().join("d.csv");
        let mut lines: Vec<String> = good.lines().map(str::to_owned).collect();
        let mut fields: Vec<String> = lines[4].split(',').map(str::to_owned).collect();
        fields[7] = "0".into();
        lines[4] = fields.join(",");
        std::fs::write(&data, lines.join("\n")).expect("data");
        let e = read_samples(&data).expect_err("zero ratio").to_string();
        assert!(e.contains("line 5") && e.contains("v30_z = 0"), "{e}");
        let short: Vec<&str> = good.lines().take(9).collect();
        std::fs::write(&data, short.join("\n")).expect("data");
        let e = read_samples(&data).expect_err("short file").to_string();
        assert!(e.contains("before the grid does"), "{e}");
    }
}
