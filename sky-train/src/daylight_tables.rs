//! sky-core's daylight tables (`sky-core/src/daylight/tables.rs`), distilled from the physical
//! atmosphere ([`crate::physical`]) in two steps:
//!
//! 1. **sample** (slow: one precomputed atmosphere per aerosol optical depth of
//!    [`AOD_NODES`], about a minute each, cached): the diffuse horizontal illuminance X, Y, Z
//!    and melanopic EDI at the reference's own sun-angle nodes from −18° to 90° (its ground
//!    tables' sun grid, between whose nodes the reference itself is log-linear), written to
//!    [`DATA_PATH`];
//! 2. **tables** (fast, what the regeneration test reruns): the Rust source of the diffuse
//!    table from that file, and the direct beam's spectral constants, computed afresh from the
//!    reference's constituents and its transmittance table (a fraction of a second): per 10 nm
//!    bin the extraterrestrial irradiance times the X, Y, Z and melanopic weights, the vertical
//!    Rayleigh, aerosol (per unit optical depth at 550 nm) and ozone (per Dobson unit) optical
//!    depths, and the relative optical air masses of the three constituents against
//!    x = √(sin h) on the reference's own transmittance coordinate.
//!
//! sky-core evaluates the direct beam by Beer-Lambert's law per bin, so it is exact in the
//! aerosol optical depth, the ozone column and the surface pressure (the Rayleigh depth scales
//! with it); only the diffuse light is tabulated against the optical depth.
//!
//! The site's axes (`--sample` also writes [`SITE_DATA_PATH`]): the diffuse light's
//! sensitivity to the surface pressure, d ln E / d(P / P₀) per optical depth and sun node, from
//! the reference at [`PRESSURE_NODE_ELEVATION_M`] against sea level, and to the ozone column,
//! d ln E / d(O₃ / 100 DU) per sun node (one optical depth, [`OZONE_NODE_AOD`]: it hardly depends
//! on it), from [`OZONE_NODE_DU`] against 300 DU; sky-core adds them to ln E linearly. The same
//! file holds held-out samples of the reference ([`SITE_CHECKS`]) that the tests compare sky-core
//! with. The tables are stored as 16-bit integers (ln E in steps of 1/2048, the sensitivities in
//! steps of 1/4096) to keep them within the firmware's flash.

use std::fmt::Write as _;
use std::io::Write as _;
use std::path::Path;

use anyhow::Result;

use crate::image_io::write_atomically;
use crate::physical::constituents::{EARTH_RADIUS_M, N_WAVELENGTHS as NW, wavelength_nm};
use crate::physical::photometry::channel_weights;
use crate::physical::transport::{Medium, Transmittance};
use crate::physical::{Atmosphere, Resolution, cache};
use crate::sampled_grid;

/// The aerosol optical depths at 550 nm the diffuse table is sampled at (a factor 2 apart;
/// Preetham's turbidity 2 to 9 lies within).
pub const AOD_NODES: [f64; 5] = [0.05, 0.1, 0.2, 0.4, 0.8];

/// The sampled reference, relative to the repository root.
pub const DATA_PATH: &str = "sky-train/data/daylight_diffuse.csv";
/// The generated tables, relative to the repository root.
pub const TABLES_PATH: &str = "sky-core/src/daylight/tables.rs";
/// The command that regenerates [`TABLES_PATH`] from [`DATA_PATH`].
pub const COMMAND: &str = "sky-train daylight-tables --data sky-train/data/daylight_diffuse.csv --site-data sky-train/data/daylight_site.csv --out sky-core/src/daylight/tables.rs";

/// The site's samples, relative to the repository root.
pub const SITE_DATA_PATH: &str = "sky-train/data/daylight_site.csv";

/// The elevation of the pressure sensitivity's second node, m (sea level is the first).
pub const PRESSURE_NODE_ELEVATION_M: f64 = 3000.0;
/// The ozone column of the ozone sensitivity's second node, DU (300, the tables', the first).
pub const OZONE_NODE_DU: f64 = 400.0;
/// The optical depth the ozone sensitivity is sampled at.
pub const OZONE_NODE_AOD: f64 = 0.2;

/// Held-out samples of the reference for the tests: (aerosol optical depth, site elevation in
/// m, ozone in DU), none of them a node: inside the pressure nodes, beyond them (4,000 m), the
/// ozone sensitivity at another optical depth, and everything at once.
pub const SITE_CHECKS: [(f64, f64, f64); 4] = [
    (0.3, 1500.0, 300.0),
    (0.15, 4000.0, 300.0),
    (0.8, 0.0, 400.0),
    (0.1, 2300.0, 250.0),
];

/// The scale of the stored ln E: steps of 1 / 2048.
pub const LN_SCALE: f64 = 2048.0;
/// The scale of the stored sensitivities: steps of 1 / 4096.
pub const SENSITIVITY_SCALE: f64 = 4096.0;

/// Nodes of the air-mass table, uniform in x = √(sin h) from 0 (horizon) to 1 (zenith): the
/// reference's own transmittance coordinate at the ground, node for node, so that sky-core's
/// linear interpolation is the reference's.
#[must_use]
pub fn airmass_nodes() -> usize {
    Resolution::default().transmittance_mu
}

/// The lowest sun elevation tabulated, degrees (the end of astronomical twilight).
pub const LOWEST_ELEVATION_DEG: f64 = -18.0;

/// The atmosphere of aerosol optical depth `aod`: the default atmosphere's constituents.
#[must_use]
pub fn atmosphere(aod: f64) -> Atmosphere {
    Atmosphere {
        aod_550: aod,
        ..Atmosphere::default()
    }
}

/// The atmosphere of aerosol optical depth `aod` at `site_elevation_m` with `ozone_du`: the
/// default atmosphere's other constituents.
#[must_use]
pub fn site_atmosphere(aod: f64, site_elevation_m: f64, ozone_du: f64) -> Atmosphere {
    Atmosphere {
        aod_550: aod,
        site_elevation_m,
        ozone_du,
        ..Atmosphere::default()
    }
}

/// The surface pressure over sea level's, P / P₀, at `elevation_m` (US Standard Atmosphere 1976).
#[must_use]
pub fn pressure_ratio(elevation_m: f64) -> f64 {
    crate::physical::constituents::us76(elevation_m).1 / 101_325.0
}

/// Every (optical depth, site elevation, ozone) of [`SITE_DATA_PATH`], in its order: the
/// pressure nodes, the ozone node, then the checks.
#[must_use]
pub fn site_grid() -> Vec<(f64, f64, f64)> {
    let mut g: Vec<(f64, f64, f64)> = AOD_NODES
        .iter()
        .map(|&a| (a, PRESSURE_NODE_ELEVATION_M, 300.0))
        .collect();
    g.push((OZONE_NODE_AOD, 0.0, OZONE_NODE_DU));
    g.extend(SITE_CHECKS);
    g
}

/// One sample of the reference at a site: its atmosphere and the diffuse light.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SiteSample {
    /// Aerosol optical depth at 550 nm.
    pub aod: f64,
    /// Site elevation, m.
    pub site_elevation_m: f64,
    /// Ozone column, DU.
    pub ozone_du: f64,
    /// Geometric sun elevation, degrees.
    pub elevation_deg: f64,
    /// X, Y, Z (lux) and melanopic EDI (lux) of the diffuse light.
    pub xyzm: [f64; 4],
    /// The direct normal illuminance (Y, lux), to check sky-core's beam against.
    pub direct_normal_lux: f64,
}

/// The slow step of the site's axes: every atmosphere of [`site_grid`] at every
/// [`elevation_nodes`] elevation.
///
/// # Errors
/// When an atmosphere cannot be built or cached.
pub fn sample_site(cache_dir: &cache::CacheDir, progress: bool) -> Result<Vec<SiteSample>> {
    let elevations = elevation_nodes();
    let mut out = Vec::new();
    for (aod, z, o3) in site_grid() {
        let atm = cache::load_or_build_in(
            &site_atmosphere(aod, z, o3),
            &Resolution::default(),
            Some(cache_dir),
            progress,
        )?;
        for &h in &elevations {
            let sky = atm.sky(90.0 - h, 0.0)?;
            let d = sky.daylight().diffuse;
            let dn = crate::physical::photometry::Colorimetry::of(&sky.direct_normal());
            out.push(SiteSample {
                aod,
                site_elevation_m: z,
                ozone_du: o3,
                elevation_deg: h,
                xyzm: [d.xyz[0], d.xyz[1], d.xyz[2], d.melanopic_edi],
                direct_normal_lux: dn.xyz[1],
            });
        }
    }
    Ok(out)
}

const SITE_HEADER: &str = "aod,site_elevation_m,ozone_du,sun_elevation_deg,x_lux,y_lux,z_lux,melanopic_edi_lux,direct_normal_y_lux";

/// Writes the site's `samples` as CSV to `path`, atomically.
///
/// # Errors
/// When the file cannot be written.
pub fn write_site_samples(path: &Path, samples: &[SiteSample]) -> Result<()> {
    write_atomically(path, |f| {
        let mut s = format!("{SITE_HEADER}\n");
        for r in samples {
            let _ = write!(
                s,
                "{},{},{},{}",
                r.aod, r.site_elevation_m, r.ozone_du, r.elevation_deg
            );
            for v in r.xyzm {
                let _ = write!(s, ",{v:.9e}");
            }
            let _ = writeln!(s, ",{:.9e}", r.direct_normal_lux);
        }
        f.write_all(s.as_bytes())?;
        Ok(())
    })
}

/// Reads the site's samples of `path` and checks they are [`site_grid`] × [`elevation_nodes`]
/// in that order, with finite values in (0, 2e5] lux.
///
/// # Errors
/// A [`crate::args::ParamError`] naming the file and line of the first bad row.
pub fn read_site_samples(path: &Path) -> Result<Vec<SiteSample>> {
    use crate::args::ParamError;
    let bad =
        |line: usize, what: String| ParamError(format!("{}: line {line}: {what}", path.display()));
    let input = crate::csv_input::read_lines(path, MAX_DATA_BYTES)
        .map_err(|e| ParamError(format!("cannot read {}: {e}", path.display())))?;
    let elevations = elevation_nodes();
    let grid = site_grid();
    let total = grid.len() * elevations.len();
    let mut expected = grid
        .into_iter()
        .flat_map(|g| elevations.iter().map(move |&h| (g, h)));
    let mut out = Vec::new();
    for (n, line) in input.enumerate() {
        let line = line.map_err(|e| bad(n + 1, e.to_string()))?;
        if n == 0 {
            if line.trim() != SITE_HEADER {
                return Err(bad(1, format!("expected the header {SITE_HEADER}")).into());
            }
            continue;
        }
        let v: Vec<f64> = line
            .split(',')
            .map(|v| v.trim().parse::<f64>())
            .collect::<Result<_, _>>()
            .map_err(|_| bad(n + 1, "not numbers".into()))?;
        let Some(((aod, z, o3), h)) = expected.next() else {
            return Err(bad(n + 1, "more rows than the grid".into()).into());
        };
        let (lo, hi) = SAMPLE_RANGE_LUX;
        if !(v.len() == 9
            && v[0] == aod
            && v[1] == z
            && v[2] == o3
            && (v[3] - h).abs() < 1e-9
            && v[4..8].iter().all(|x| *x > lo && *x <= hi)
            && (0.0..=hi).contains(&v[8]))
        {
            return Err(bad(
                n + 1,
                format!(
                    "expected aod {aod}, site elevation {z}, ozone {o3}, sun elevation {h}, four illuminances in ({lo}, {hi}] lux and a direct normal one in [0, {hi}] lux"
                ),
            )
            .into());
        }
        out.push(SiteSample {
            aod,
            site_elevation_m: z,
            ozone_du: o3,
            elevation_deg: h,
            xyzm: [v[4], v[5], v[6], v[7]],
            direct_normal_lux: v[8],
        });
    }
    if out.len() != total {
        return Err(ParamError(format!(
            "{}: {} rows of the {total} the grid has",
            path.display(),
            out.len()
        ))
        .into());
    }
    Ok(out)
}

/// The sun elevations of the diffuse table, ascending, degrees: the reference's ground sun
/// grid from −18° to 90°.
#[must_use]
pub fn elevation_nodes() -> Vec<f64> {
    let grid = Resolution::default().ground_sun;
    let mut h: Vec<f64> = (0..grid.len())
        .map(|i| 90.0 - grid.angle_deg(i))
        .filter(|&h| h >= LOWEST_ELEVATION_DEG - 1e-9)
        .collect();
    h.reverse();
    h
}

/// One sample of the reference: the diffuse horizontal light at one optical depth and sun
/// elevation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DiffuseSample {
    /// Aerosol optical depth at 550 nm.
    pub aod: f64,
    /// Geometric sun elevation, degrees.
    pub elevation_deg: f64,
    /// X, Y, Z (lux) and melanopic EDI (lux).
    pub xyzm: [f64; 4],
}

/// The slow step: every optical depth of [`AOD_NODES`] at every [`elevation_nodes`] elevation,
/// each atmosphere precomputed (or read from `cache_dir`), with a progress bar when `progress`.
///
/// # Errors
/// When an atmosphere cannot be built or cached.
pub fn sample(cache_dir: &cache::CacheDir, progress: bool) -> Result<Vec<DiffuseSample>> {
    sampled_grid::sample(
        (cache_dir, progress),
        (&AOD_NODES, atmosphere),
        &elevation_nodes(),
        |aod, h, sky| {
            let d = sky.daylight().diffuse;
            DiffuseSample {
                aod,
                elevation_deg: h,
                xyzm: [d.xyz[0], d.xyz[1], d.xyz[2], d.melanopic_edi],
            }
        },
    )
}

/// The longest `--data` file read: the grid's rows take some 70 bytes each.
pub const MAX_DATA_BYTES: u64 = 1 << 20;

const HEADER: &str = "aod,sun_elevation_deg,x_lux,y_lux,z_lux,melanopic_edi_lux";

/// Writes `samples` as CSV to `path`, atomically.
///
/// # Errors
/// When the file cannot be written.
pub fn write_samples(path: &Path, samples: &[DiffuseSample]) -> Result<()> {
    sampled_grid::write(
        path,
        HEADER,
        samples
            .iter()
            .map(|r| (r.aod, r.elevation_deg, r.xyzm.as_slice())),
    )
}

/// The range every illuminance of [`DATA_PATH`] must lie in, lux: positive, and at most
/// 2e5 lx, above the sun's own illuminance outside the atmosphere (1.33e5 lx) on every
/// channel (X, Y, Z, melanopic EDI), which no diffuse light at the ground reaches.
pub const SAMPLE_RANGE_LUX: (f64, f64) = (0.0, 2e5);

/// Reads the samples of `path` and checks they are the grid [`sample`] writes: every
/// optical depth of [`AOD_NODES`] at every [`elevation_nodes`] elevation, in that order, with
/// finite values in (0, 2e5] lux ([`SAMPLE_RANGE_LUX`]).
///
/// # Errors
/// A [`crate::args::ParamError`] (bad input, exit status 2) naming the file and line of the
/// first bad row or field, and for a file without the header or rows; a plain error when it
/// cannot be read.
pub fn read_samples(path: &Path) -> Result<Vec<DiffuseSample>> {
    let (lo, hi) = SAMPLE_RANGE_LUX;
    let grid = sampled_grid::grid(&AOD_NODES, &elevation_nodes());
    let rows = sampled_grid::read(path, MAX_DATA_BYTES, HEADER, &grid, |column, v| {
        (!(v > lo && v <= hi)).then(|| {
            format!(
                "{column} = {} is outside the valid range ({lo}, {}] lux",
                crate::csv_output::compact(v),
                crate::csv_output::compact(hi)
            )
        })
    })?;
    Ok(rows
        .into_iter()
        .map(|r| DiffuseSample {
            aod: r.aod,
            elevation_deg: r.elevation_deg,
            xyzm: [r.values[0], r.values[1], r.values[2], r.values[3]],
        })
        .collect())
}

/// The direct beam's constants (module docs).
#[derive(Debug, Clone, PartialEq)]
pub struct Beam {
    /// Per bin: extraterrestrial irradiance (1 AU) times the X, Y, Z and melanopic weights,
    /// lux per unit transmittance.
    pub sun_channels: [[f64; 4]; NW],
    /// Vertical Rayleigh optical depth per bin.
    pub rayleigh: [f64; NW],
    /// Vertical aerosol optical depth per bin for an optical depth of 1 at 550 nm.
    pub aerosol: [f64; NW],
    /// Vertical ozone optical depth per bin per Dobson unit.
    pub ozone: [f64; NW],
    /// Relative optical air masses (air, aerosol, ozone) at x = √(sin h) = j / (n − 1).
    pub airmass: Vec<[f64; 3]>,
}

/// The direct beam's constants from the reference's constituents and transmittance table.
#[must_use]
pub fn beam() -> Beam {
    let atm = atmosphere(1.0);
    let medium = Medium::new(&atm);
    let trans = Transmittance::build(&medium, &Resolution::default());
    let vertical = trans.to_top(EARTH_RADIUS_M, 1.0);
    let c = &medium.coefficients;
    let w = channel_weights();
    #[allow(clippy::cast_precision_loss)]
    let n = airmass_nodes();
    let airmass = (0..n)
        .map(|j| {
            let x = j as f64 / (n - 1) as f64;
            let cols = trans.to_top(EARTH_RADIUS_M, x * x);
            std::array::from_fn(|k| cols[k] / vertical[k])
        })
        .collect();
    Beam {
        sun_channels: std::array::from_fn(|l| std::array::from_fn(|k| w[k][l] * medium.solar[l])),
        rayleigh: std::array::from_fn(|l| c.rayleigh[l] * vertical[0]),
        aerosol: std::array::from_fn(|l| c.aerosol_extinction[l] * vertical[1]),
        ozone: std::array::from_fn(|l| c.ozone[l] * vertical[2] / atm.ozone_du),
        airmass,
    }
}

#[allow(clippy::cast_possible_truncation)]
fn f32s(v: impl IntoIterator<Item = f64>) -> String {
    v.into_iter()
        .map(|x| format!("{:?}", x as f32))
        .collect::<Vec<_>>()
        .join(", ")
}

/// `v` × `scale` rounded to an i16 (saturating).
#[allow(clippy::cast_possible_truncation)]
fn q16(v: f64, scale: f64) -> i16 {
    (v * scale)
        .round()
        .clamp(f64::from(i16::MIN), f64::from(i16::MAX)) as i16
}

fn i16s(v: impl IntoIterator<Item = f64>, scale: f64) -> String {
    v.into_iter()
        .map(|x| q16(x, scale).to_string())
        .collect::<Vec<_>>()
        .join(", ")
}

/// The site's sensitivities from the sea-level `samples` and the `site` samples (both as read):
/// d ln E / d(P / P₀) per optical depth, sun elevation and channel, and d ln E / d(O₃ / 100 DU)
/// per sun elevation and channel.
#[must_use]
pub fn sensitivities(
    samples: &[DiffuseSample],
    site: &[SiteSample],
) -> (Vec<Vec<[f64; 4]>>, Vec<[f64; 4]>) {
    let ne = elevation_nodes().len();
    let dp = pressure_ratio(PRESSURE_NODE_ELEVATION_M) - 1.0;
    let pressure = AOD_NODES
        .iter()
        .enumerate()
        .map(|(a, _)| {
            (0..ne)
                .map(|e| {
                    let sea = &samples[a * ne + e].xyzm;
                    let high = &site[a * ne + e].xyzm;
                    std::array::from_fn(|k| (high[k].ln() - sea[k].ln()) / dp)
                })
                .collect()
        })
        .collect();
    let ia = AOD_NODES
        .iter()
        .position(|&a| a == OZONE_NODE_AOD)
        .unwrap_or(0);
    let d_o3 = (OZONE_NODE_DU - 300.0) / 100.0;
    let ozone = (0..ne)
        .map(|e| {
            let sea = &samples[ia * ne + e].xyzm;
            let o = &site[AOD_NODES.len() * ne + e].xyzm;
            std::array::from_fn(|k| (o[k].ln() - sea[k].ln()) / d_o3)
        })
        .collect();
    (pressure, ozone)
}

/// The Rust source of `sky-core/src/daylight/tables.rs` from the diffuse `samples` and the
/// site's samples (as [`read_samples`] and [`read_site_samples`] checked them) and the beam
/// constants.
#[must_use]
#[allow(clippy::cast_possible_truncation)]
pub fn rust_source(samples: &[DiffuseSample], site: &[SiteSample], beam: &Beam) -> String {
    let elevations = elevation_nodes();
    let (na, ne) = (AOD_NODES.len(), elevations.len());
    let atm = Atmosphere::default();
    let mut s = String::new();
    let _ = writeln!(s, "// Generated by `{COMMAND}`; do not edit.");
    let _ = writeln!(s, "//");
    let _ = writeln!(
        s,
        "// sky-train's physical atmosphere (docs/daylight.md): Ångström {}, aerosol single-scattering albedo {},",
        atm.angstrom, atm.aerosol_ssa
    );
    let _ = writeln!(
        s,
        "// asymmetry {}, scale height {} m, ozone {} DU, ground albedo {}, 1 AU; 10 nm bins {}-{} nm.\n",
        atm.aerosol_g,
        atm.aerosol_scale_height_m,
        atm.ozone_du,
        atm.ground_albedo,
        wavelength_nm(0) - 5.0,
        wavelength_nm(NW - 1) + 5.0
    );
    for (name, doc, value) in [
        (
            "DEFAULT_AOD",
            "The default atmosphere's aerosol optical depth at 550 nm (sky-train's `Atmosphere::default()`).",
            atm.aod_550,
        ),
        (
            "OZONE_DU",
            "The ozone column of every table, Dobson units.",
            atm.ozone_du,
        ),
        (
            "GROUND_ALBEDO",
            "The ground's Lambertian albedo of every table.",
            atm.ground_albedo,
        ),
        (
            "SUN_ANGULAR_RADIUS",
            "The sun's angular radius, radians.",
            crate::physical::solar::SUN_ANGULAR_RADIUS,
        ),
    ] {
        let _ = writeln!(s, "/// {doc}");
        let _ = writeln!(s, "pub(crate) const {name}: f32 = {:?};\n", value as f32);
    }
    let _ = writeln!(
        s,
        "/// Aerosol optical depths at 550 nm of the diffuse table's rows."
    );
    let _ = writeln!(
        s,
        "pub(crate) const AOD: [f32; {na}] = [{}];\n",
        f32s(AOD_NODES)
    );
    let _ = writeln!(
        s,
        "/// Sun elevations of the diffuse table's columns, degrees, ascending."
    );
    let _ = writeln!(s, "#[rustfmt::skip]");
    let _ = writeln!(
        s,
        "pub(crate) const ELEVATION_DEG: [f32; {ne}] = [{}];\n",
        f32s(elevations.iter().copied())
    );
    let _ = writeln!(
        s,
        "/// The steps of [`LN_DIFFUSE`]: ln E = LN_DIFFUSE / LN_SCALE.\npub(crate) const LN_SCALE: f32 = {LN_SCALE:?};\n"
    );
    let _ = writeln!(
        s,
        "/// The steps of [`PRESSURE_SENSITIVITY`] and [`OZONE_SENSITIVITY`].\npub(crate) const SENSITIVITY_SCALE: f32 = {SENSITIVITY_SCALE:?};\n"
    );
    let _ = writeln!(
        s,
        "/// ln of the diffuse horizontal X, Y, Z (lux) and melanopic EDI (lux) at sea level, 300 DU, times [`LN_SCALE`], [optical depth][elevation]."
    );
    let _ = writeln!(s, "#[rustfmt::skip]");
    let _ = writeln!(
        s,
        "pub(crate) const LN_DIFFUSE: [[[i16; 4]; {ne}]; {na}] = ["
    );
    for row in samples.chunks(ne) {
        let _ = writeln!(s, "    [");
        for r in row {
            let _ = writeln!(s, "        [{}],", i16s(r.xyzm.map(f64::ln), LN_SCALE));
        }
        let _ = writeln!(s, "    ],");
    }
    let _ = writeln!(s, "];\n");
    let (pressure, ozone) = sensitivities(samples, site);
    let _ = writeln!(
        s,
        "/// d ln E / d(P / P₀) of [`LN_DIFFUSE`]'s channels (sea level against {PRESSURE_NODE_ELEVATION_M} m), times [`SENSITIVITY_SCALE`], [optical depth][elevation]."
    );
    let _ = writeln!(s, "#[rustfmt::skip]");
    let _ = writeln!(
        s,
        "pub(crate) const PRESSURE_SENSITIVITY: [[[i16; 4]; {ne}]; {na}] = ["
    );
    for row in &pressure {
        let _ = writeln!(s, "    [");
        for r in row {
            let _ = writeln!(s, "        [{}],", i16s(*r, SENSITIVITY_SCALE));
        }
        let _ = writeln!(s, "    ],");
    }
    let _ = writeln!(s, "];\n");
    let _ = writeln!(
        s,
        "/// d ln E / d(O₃ / 100 DU) of [`LN_DIFFUSE`]'s channels (300 against {OZONE_NODE_DU} DU at optical depth {OZONE_NODE_AOD}), times [`SENSITIVITY_SCALE`], [elevation]."
    );
    let _ = writeln!(s, "#[rustfmt::skip]");
    let _ = writeln!(
        s,
        "pub(crate) const OZONE_SENSITIVITY: [[i16; 4]; {ne}] = ["
    );
    for r in &ozone {
        let _ = writeln!(s, "    [{}],", i16s(*r, SENSITIVITY_SCALE));
    }
    let _ = writeln!(s, "];\n");
    let _ = writeln!(
        s,
        "/// Per bin: extraterrestrial irradiance times the X, Y, Z and melanopic weights, lux at transmittance 1."
    );
    let _ = writeln!(s, "#[rustfmt::skip]");
    let _ = writeln!(s, "#[allow(clippy::excessive_precision)]");
    let _ = writeln!(s, "pub(crate) const SUN_CHANNELS: [[f32; 4]; {NW}] = [");
    for c in &beam.sun_channels {
        let _ = writeln!(s, "    [{}],", f32s(*c));
    }
    let _ = writeln!(s, "];\n");
    for (name, doc, v) in [
        (
            "RAYLEIGH_DEPTH",
            "Vertical Rayleigh optical depth per bin.",
            &beam.rayleigh,
        ),
        (
            "AEROSOL_DEPTH",
            "Vertical aerosol optical depth per bin at an optical depth of 1 at 550 nm.",
            &beam.aerosol,
        ),
        (
            "OZONE_DEPTH",
            "Vertical ozone optical depth per bin per Dobson unit.",
            &beam.ozone,
        ),
    ] {
        let _ = writeln!(s, "/// {doc}");
        let _ = writeln!(s, "#[rustfmt::skip]");
        let _ = writeln!(s, "#[allow(clippy::excessive_precision)]");
        let _ = writeln!(
            s,
            "pub(crate) const {name}: [f32; {NW}] = [{}];\n",
            f32s(v.iter().copied())
        );
    }
    let nm = beam.airmass.len();
    let _ = writeln!(
        s,
        "/// Relative optical air masses of air, aerosol and ozone at x = √(sin h) = j / {}.",
        nm - 1
    );
    let _ = writeln!(s, "#[rustfmt::skip]");
    let _ = writeln!(s, "#[allow(clippy::excessive_precision)]");
    let _ = writeln!(s, "pub(crate) const AIRMASS: [[f32; 3]; {nm}] = [");
    for m in &beam.airmass {
        let _ = writeln!(s, "    [{}],", f32s(*m));
    }
    let _ = writeln!(s, "];");
    s
}
