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
//! aerosol optical depth and the ozone column; only the diffuse light is tabulated against
//! the optical depth.

use std::fmt::Write as _;
use std::path::Path;

use anyhow::Result;

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
pub const COMMAND: &str = "sky-train daylight-tables --data sky-train/data/daylight_diffuse.csv --out sky-core/src/daylight/tables.rs";

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

/// The Rust source of `sky-core/src/daylight/tables.rs` from the diffuse `samples` (as
/// [`read_samples`] checked them) and the beam constants.
#[must_use]
#[allow(clippy::cast_possible_truncation)]
pub fn rust_source(samples: &[DiffuseSample], beam: &Beam) -> String {
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
        "/// ln of the diffuse horizontal X, Y, Z (lux) and melanopic EDI (lux), [optical depth][elevation]."
    );
    let _ = writeln!(s, "#[rustfmt::skip]");
    let _ = writeln!(s, "#[allow(clippy::excessive_precision)]");
    let _ = writeln!(
        s,
        "pub(crate) const LN_DIFFUSE: [[[f32; 4]; {ne}]; {na}] = ["
    );
    for row in samples.chunks(ne) {
        let _ = writeln!(s, "    [");
        for r in row {
            let _ = writeln!(s, "        [{}],", f32s(r.xyzm.map(f64::ln)));
        }
        let _ = writeln!(s, "    ],");
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
