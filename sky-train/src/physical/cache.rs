//! The on-disk cache of precomputed atmospheres.
//!
//! One file per atmosphere and resolution, `physical-<key>.bin` in the cache directory
//! ([`default_dir`]), written atomically (temporary file + rename). The key is a 64-bit FNV-1a
//! hash of the format version, the atmosphere's parameters, the table resolution and the
//! computed constants themselves (every bin's cross-sections and phase terms, the
//! extraterrestrial spectrum, the density profiles sampled every 500 m, the planet's radii and
//! the sun's disc), so that changing any constant or resolution rebuilds the tables. The file
//! ends with an FNV-1a checksum of its contents; a file that fails to read is rebuilt.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use anyhow::{Context, Result, bail};
use indicatif::ProgressBar;

use super::atmosphere::Atmosphere;
use super::constituents::{self, N_WAVELENGTHS as NW, Spectrum};
use super::grid::SunGrid;
use super::sky::PhysicalAtmosphere;
use super::solar;
use super::transport::{GroundTables, Medium, OrderReport, Resolution, Table3, Transmittance};

/// The file format's version (bumped with any change of layout or method).
pub const FORMAT_VERSION: u32 = 3;
const MAGIC: &[u8; 8] = b"SKYPHYS\0";

/// The environment variable that overrides the cache directory.
pub const CACHE_ENV: &str = "SKY_TRAIN_CACHE_DIR";

/// `$SKY_TRAIN_CACHE_DIR`, else `$XDG_CACHE_HOME/sky-train`, else `~/.cache/sky-train`, else
/// `.sky-train-cache` in the working directory.
#[must_use]
pub fn default_dir() -> PathBuf {
    let env = |k: &str| {
        std::env::var_os(k)
            .filter(|v| !v.is_empty())
            .map(PathBuf::from)
    };
    env(CACHE_ENV)
        .or_else(|| env("XDG_CACHE_HOME").map(|d| d.join("sky-train")))
        .or_else(|| env("HOME").map(|d| d.join(".cache").join("sky-train")))
        .unwrap_or_else(|| PathBuf::from(".sky-train-cache"))
}

/// 64-bit FNV-1a.
#[derive(Debug, Clone, Copy)]
struct Fnv(u64);

impl Fnv {
    fn new() -> Self {
        Self(0xcbf2_9ce4_8422_2325)
    }
    fn bytes(&mut self, b: &[u8]) {
        for &x in b {
            self.0 ^= u64::from(x);
            self.0 = self.0.wrapping_mul(0x0100_0000_01b3);
        }
    }
    fn f64(&mut self, v: f64) {
        self.bytes(&v.to_le_bytes());
    }
}

/// The version key of `atmosphere` at `resolution`.
#[must_use]
pub fn version_key(atmosphere: &Atmosphere, resolution: &Resolution) -> u64 {
    let mut h = Fnv::new();
    h.bytes(&FORMAT_VERSION.to_le_bytes());
    h.bytes(format!("{atmosphere:?}{resolution:?}").as_bytes());
    let c = atmosphere.coefficients();
    for l in 0..NW {
        for v in [
            c.rayleigh[l],
            c.aerosol_extinction[l],
            c.aerosol_scattering[l],
            c.ozone[l],
            c.rayleigh_phase[l].0,
            c.rayleigh_phase[l].1,
            solar::extraterrestrial()[l],
        ] {
            h.f64(v);
        }
    }
    for k in 0..=200 {
        let z = f64::from(k) * 500.0;
        h.f64(constituents::air_number_density(z));
        h.f64(constituents::ozone_shape(z));
    }
    for v in [
        constituents::EARTH_RADIUS_M,
        constituents::TOP_RADIUS_M,
        solar::SUN_ANGULAR_RADIUS,
        super::transport::PROFILE_STEP_M,
    ] {
        h.f64(v);
    }
    h.0
}

/// The cache file of `atmosphere` at `resolution` in `dir`.
#[must_use]
pub fn path(dir: &Path, atmosphere: &Atmosphere, resolution: &Resolution) -> PathBuf {
    dir.join(format!(
        "physical-{:016x}.bin",
        version_key(atmosphere, resolution)
    ))
}

/// The atmosphere from the cache in `dir` when it holds it, else precomputed (with a progress
/// bar on stderr when `progress`) and written there. `dir = None` neither reads nor writes.
///
/// # Errors
/// A parameter out of range ([`super::AtmosphereError`]), or the cache cannot be written.
pub fn load_or_build(
    atmosphere: &Atmosphere,
    resolution: &Resolution,
    dir: Option<&Path>,
    progress: bool,
) -> Result<Arc<PhysicalAtmosphere>> {
    atmosphere.validate()?;
    let file = dir.map(|d| path(d, atmosphere, resolution));
    if let Some(f) = &file
        && let Ok(bytes) = std::fs::read(f)
        && let Ok(atm) = decode(&bytes, atmosphere, resolution)
    {
        return Ok(Arc::new(atm));
    }
    let bar = if progress {
        let bar = ProgressBar::new(1);
        bar.set_style(
            indicatif::ProgressStyle::with_template(
                "{spinner} {elapsed:>4} [{bar:30}] {percent:>3}% precomputing the atmosphere: {msg}",
            )
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar())
            .progress_chars("=> "),
        );
        bar
    } else {
        ProgressBar::hidden()
    };
    let atm = PhysicalAtmosphere::build(atmosphere, resolution, &bar)?;
    if let (Some(d), Some(f)) = (dir, &file) {
        std::fs::create_dir_all(d)
            .with_context(|| format!("cannot create the cache directory {}", d.display()))?;
        let bytes = encode(&atm, version_key(atmosphere, resolution));
        crate::image_io::write_atomically(f, |out| Ok(out.write_all(&bytes)?))?;
    }
    Ok(Arc::new(atm))
}

fn put_u64(out: &mut Vec<u8>, v: u64) {
    out.extend_from_slice(&v.to_le_bytes());
}

fn put_f64(out: &mut Vec<u8>, v: f64) {
    out.extend_from_slice(&v.to_le_bytes());
}

fn put_table(out: &mut Vec<u8>, t: &Table3) {
    put_u64(out, t.data.len() as u64);
    for v in &t.data {
        out.extend_from_slice(&v.to_le_bytes());
    }
}

/// The cache file's bytes.
#[must_use]
pub fn encode(atm: &PhysicalAtmosphere, key: u64) -> Vec<u8> {
    let mut out = Vec::new();
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
    put_u64(&mut out, key);
    let t = &atm.transmittance;
    put_u64(&mut out, t.nr as u64);
    put_u64(&mut out, t.nmu as u64);
    for c in &t.columns {
        for v in c {
            put_f64(&mut out, *v);
        }
    }
    let g = &atm.ground;
    for table in [&g.rayleigh, &g.aerosol, &g.multiple] {
        put_table(&mut out, table);
    }
    put_u64(&mut out, g.diffuse.len() as u64);
    for s in &g.diffuse {
        for v in s {
            put_f64(&mut out, *v);
        }
    }
    put_u64(&mut out, g.orders.len() as u64);
    for o in &g.orders {
        put_u64(&mut out, o.order as u64);
        for v in [o.max_change, o.at_elevation_deg, o.change_at_minus_12] {
            put_f64(&mut out, v);
        }
    }
    let mut h = Fnv::new();
    h.bytes(&out);
    put_u64(&mut out, h.0);
    out
}

struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl Reader<'_> {
    fn take(&mut self, n: usize) -> Result<&[u8]> {
        let end = self.at.checked_add(n).filter(|&e| e <= self.bytes.len());
        let Some(end) = end else {
            bail!("truncated cache file");
        };
        let s = &self.bytes[self.at..end];
        self.at = end;
        Ok(s)
    }
    fn u64(&mut self) -> Result<u64> {
        Ok(u64::from_le_bytes(self.take(8)?.try_into()?))
    }
    fn len(&mut self, expected: usize) -> Result<usize> {
        let n = usize::try_from(self.u64()?)?;
        if n != expected {
            bail!("cache file holds {n} values where {expected} were expected");
        }
        Ok(n)
    }
    fn f64(&mut self) -> Result<f64> {
        Ok(f64::from_le_bytes(self.take(8)?.try_into()?))
    }
    fn table(&mut self, sun: SunGrid, nmu: usize, nphi: usize) -> Result<Table3> {
        let mut t = Table3 {
            sun,
            nmu,
            nphi,
            data: Vec::new(),
        };
        let n = self.len(t.cells() * NW)?;
        t.data = self
            .take(4 * n)?
            .chunks_exact(4)
            .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
            .collect();
        Ok(t)
    }
}

/// Reads a cache file written for `atmosphere` at `resolution`.
///
/// # Errors
/// A wrong magic, version, key, size or checksum.
pub fn decode(
    bytes: &[u8],
    atmosphere: &Atmosphere,
    resolution: &Resolution,
) -> Result<PhysicalAtmosphere> {
    if bytes.len() < 28 || &bytes[..8] != MAGIC {
        bail!("not a sky-train atmosphere cache file");
    }
    let (body, sum) = bytes.split_at(bytes.len() - 8);
    let mut h = Fnv::new();
    h.bytes(body);
    if h.0.to_le_bytes() != sum {
        bail!("cache file checksum mismatch");
    }
    let mut r = Reader { bytes: body, at: 8 };
    if r.take(4)? != FORMAT_VERSION.to_le_bytes() {
        bail!("cache file of another format version");
    }
    if r.u64()? != version_key(atmosphere, resolution) {
        bail!("cache file of another atmosphere or resolution");
    }
    let res = resolution;
    let nr = r.len(res.transmittance_r)?;
    let nmu = r.len(res.transmittance_mu)?;
    let mut columns = Vec::with_capacity(nr * nmu);
    for _ in 0..nr * nmu {
        columns.push([r.f64()?, r.f64()?, r.f64()?]);
    }
    let rayleigh = r.table(res.ground_sun, res.ground_mu, res.ground_phi)?;
    let aerosol = r.table(res.ground_sun, res.ground_mu, res.ground_phi)?;
    let multiple = r.table(res.ground_sun, res.ground_mu, res.ground_phi)?;
    let n = r.len(res.ground_sun.len())?;
    let mut diffuse = Vec::with_capacity(n);
    for _ in 0..n {
        let mut s: Spectrum = [0.0; NW];
        for v in &mut s {
            *v = r.f64()?;
        }
        diffuse.push(s);
    }
    let n = usize::try_from(r.u64()?)?;
    if n > 1000 {
        bail!("cache file with {n} orders");
    }
    let mut orders = Vec::with_capacity(n);
    for _ in 0..n {
        orders.push(OrderReport {
            order: usize::try_from(r.u64()?)?,
            max_change: r.f64()?,
            at_elevation_deg: r.f64()?,
            change_at_minus_12: r.f64()?,
        });
    }
    Ok(PhysicalAtmosphere::from_parts(
        atmosphere,
        resolution,
        Medium::new(atmosphere),
        Transmittance { nr, nmu, columns },
        GroundTables {
            rayleigh,
            aerosol,
            multiple,
            diffuse,
            orders,
        },
    ))
}
