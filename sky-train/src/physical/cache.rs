//! The on-disk cache of precomputed atmospheres.
//!
//! One file per atmosphere and resolution, `physical-<key>.bin` in the cache directory
//! ([`CacheDir`]), written atomically (temporary file + rename). The key is a 64-bit FNV-1a
//! hash of the format version, the atmosphere's parameters, the table resolution and the
//! computed constants themselves (every bin's cross-sections and phase terms, the
//! extraterrestrial spectrum, the density profiles sampled every 500 m, the planet's radii and
//! the sun's disc), so that changing any constant or resolution rebuilds the tables. The file
//! ends with an FNV-1a checksum of its contents.
//!
//! What the cache trusts, and what it does not:
//!
//! - The parameters are normalised first ([`normalised`]): −0 and magnitudes below 10⁻⁹ are 0,
//!   others are rounded to 9 significant digits. `--aod -0`, `--aod 1e-320` and `--aod 0` are
//!   one atmosphere and one entry, not three 50 MB precomputations.
//! - An entry is read through the bounded reader ([`crate::csv_input::open`]): a regular file
//!   (links followed) of at most the length its resolution implies. An entry path that is a
//!   folder, a FIFO or a device is an error before any work, naming the path and where the
//!   cache folder came from ([`CacheDir::origin`]).
//! - A file that does not decode, or decodes to a value that is not finite or out of range
//!   (negative column densities, radiances or irradiances; NaN anywhere), is rebuilt.
//! - A cache folder that holds the atmosphere is only read: it need not be writable. One that
//!   does not is checked to take new files before the minute of precomputation.
//! - The folder is capped at [`MAX_CACHE_BYTES`]: whenever the cache is used, the least
//!   recently used entries (by modification time, which every read renews) are removed until
//!   the entries fit, never the one in use. Only files named `physical-<16 hex digits>.bin`
//!   count and are removed.

use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::SystemTime;

use anyhow::{Result, bail};
use indicatif::ProgressBar;

use super::atmosphere::Atmosphere;
use super::constituents::{self, N_WAVELENGTHS as NW, Spectrum};
use super::grid::SunGrid;
use super::sky::PhysicalAtmosphere;
use super::solar;
use super::transport::{GroundTables, Medium, OrderReport, Resolution, Table3, Transmittance};
use crate::args::ParamError;

/// The file format's version (bumped with any change of layout or method).
pub const FORMAT_VERSION: u32 = 5;
const MAGIC: &[u8; 8] = b"SKYPHYS\0";

/// The environment variable that overrides the cache directory.
pub const CACHE_ENV: &str = "SKY_TRAIN_CACHE_DIR";

/// The largest the cache folder's entries may take together: 1 GiB, some twenty atmospheres
/// at the default resolution (an entry is about 50 MB).
pub const MAX_CACHE_BYTES: u64 = 1 << 30;

/// The most scattering orders a cache file may list.
const MAX_ORDERS: usize = 1000;

/// `$SKY_TRAIN_CACHE_DIR`, else `$XDG_CACHE_HOME/sky-train`, else `~/.cache/sky-train`, else
/// `.sky-train-cache` in the working directory.
#[must_use]
pub fn default_dir() -> PathBuf {
    CacheDir::default_dir().path
}

/// A cache folder and where its path came from, for messages.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CacheDir {
    /// The folder.
    pub path: PathBuf,
    /// Where the path came from: `--cache-dir`, `$SKY_TRAIN_CACHE_DIR`,
    /// `$XDG_CACHE_HOME/sky-train`, `$HOME/.cache/sky-train` or `./.sky-train-cache`.
    pub origin: &'static str,
}

impl CacheDir {
    /// The folder `--cache-dir` names, else [`default_dir`]'s.
    #[must_use]
    pub fn new(flag: Option<&Path>) -> Self {
        flag.map_or_else(Self::default_dir, |p| Self {
            path: p.to_path_buf(),
            origin: "--cache-dir",
        })
    }

    /// The default folder ([`default_dir`]) with its origin.
    #[must_use]
    pub fn default_dir() -> Self {
        let env = |k: &str| {
            std::env::var_os(k)
                .filter(|v| !v.is_empty())
                .map(PathBuf::from)
        };
        if let Some(p) = env(CACHE_ENV) {
            Self {
                path: p,
                origin: "$SKY_TRAIN_CACHE_DIR",
            }
        } else if let Some(p) = env("XDG_CACHE_HOME") {
            Self {
                path: p.join("sky-train"),
                origin: "$XDG_CACHE_HOME/sky-train",
            }
        } else if let Some(p) = env("HOME") {
            Self {
                path: p.join(".cache").join("sky-train"),
                origin: "$HOME/.cache/sky-train",
            }
        } else {
            Self {
                path: PathBuf::from(".sky-train-cache"),
                origin: "./.sky-train-cache",
            }
        }
    }

    /// How messages name the folder: `--cache-dir /x`, `$SKY_TRAIN_CACHE_DIR /x`, ...
    #[must_use]
    pub fn shown(&self) -> String {
        format!("{} {}", self.origin, self.path.display())
    }

    /// `what` as a [`ParamError`] about this folder.
    fn error(&self, what: &str) -> ParamError {
        ParamError(format!("{}: {what}", self.shown()))
    }
}

/// `v` as the cache keys it: −0 and magnitudes below 10⁻⁹ are 0, others are rounded to 9
/// significant digits (far below any parameter's meaning; a `NaN` stays, for validation).
fn normalised_value(v: f64) -> f64 {
    if v.is_nan() {
        v
    } else if v.abs() < 1e-9 {
        0.0
    } else {
        format!("{v:.8e}").parse().unwrap_or(v)
    }
}

/// `atmosphere` with every parameter normalised as the cache keys it (module docs): the
/// atmosphere [`load_or_build`] computes and stores.
#[must_use]
pub fn normalised(atmosphere: &Atmosphere) -> Atmosphere {
    let n = normalised_value;
    Atmosphere {
        aod_550: n(atmosphere.aod_550),
        angstrom: n(atmosphere.angstrom),
        aerosol_ssa: n(atmosphere.aerosol_ssa),
        aerosol_g: n(atmosphere.aerosol_g),
        aerosol_scale_height_m: n(atmosphere.aerosol_scale_height_m),
        ozone_du: n(atmosphere.ozone_du),
        ground_albedo: n(atmosphere.ground_albedo),
        site_elevation_m: n(atmosphere.site_elevation_m),
    }
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

/// The version key of `atmosphere` (normalised first, [`normalised`]) at `resolution`.
#[must_use]
pub fn version_key(atmosphere: &Atmosphere, resolution: &Resolution) -> u64 {
    let atmosphere = &normalised(atmosphere);
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
/// The folder is named as `--cache-dir` in messages; [`load_or_build_in`] names its origin.
///
/// # Errors
/// As [`load_or_build_in`].
pub fn load_or_build(
    atmosphere: &Atmosphere,
    resolution: &Resolution,
    dir: Option<&Path>,
    progress: bool,
) -> Result<Arc<PhysicalAtmosphere>> {
    let dir = dir.map(|d| CacheDir::new(Some(d)));
    load_or_build_in(atmosphere, resolution, dir.as_ref(), progress)
}

/// The atmosphere ([`normalised`]) from the cache folder `dir` when it holds it, else
/// precomputed (with a progress bar on stderr when `progress`) and written there; `dir = None`
/// neither reads nor writes. Everything that can be checked is checked before the
/// precomputation (module docs).
///
/// # Errors
/// A parameter out of range ([`super::AtmosphereError`]); a [`ParamError`] naming the folder
/// and its origin when the entry's path is not a regular file or the folder cannot take the
/// new entry; a failed write.
pub fn load_or_build_in(
    atmosphere: &Atmosphere,
    resolution: &Resolution,
    dir: Option<&CacheDir>,
    progress: bool,
) -> Result<Arc<PhysicalAtmosphere>> {
    let atmosphere = &normalised(atmosphere);
    atmosphere.validate()?;
    let file = dir.map(|d| path(&d.path, atmosphere, resolution));
    if let (Some(d), Some(f)) = (dir, &file) {
        match read_entry(f, atmosphere, resolution) {
            Ok(Some(atm)) => {
                // Renewed as used, for the least-recently-used eviction.
                if let Ok(entry) = std::fs::File::options().write(true).open(f) {
                    let _ = entry.set_modified(SystemTime::now());
                }
                evict(&d.path, f);
                return Ok(Arc::new(atm));
            }
            Ok(None) => {}
            Err(Unusable::NotAFile(why)) => {
                return Err(d
                    .error(&format!("the cache entry {} {why}: remove it", f.display()))
                    .into());
            }
            Err(Unusable::Invalid(why)) => {
                if progress {
                    eprintln!(
                        "the cache entry {} is not usable ({why}); precomputing it again",
                        f.display()
                    );
                }
            }
        }
        // The precomputed atmosphere is written there after a minute's work.
        crate::output_path::folder(d.origin, &d.path)?;
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
        std::fs::create_dir_all(&d.path)
            .map_err(|e| d.error(&format!("cannot create the folder ({e})")))?;
        let bytes = encode(&atm, version_key(atmosphere, resolution));
        crate::image_io::write_atomically(f, |out| Ok(out.write_all(&bytes)?))?;
        evict(&d.path, f);
    }
    Ok(Arc::new(atm))
}

/// Why a cache entry is not used.
enum Unusable {
    /// Its path is a folder, a FIFO, a device or a socket (what it is): an error.
    NotAFile(String),
    /// It does not decode or holds bad values (why): rebuilt.
    Invalid(String),
}

/// The entry `f` decoded, `None` when there is none.
fn read_entry(
    f: &Path,
    atmosphere: &Atmosphere,
    resolution: &Resolution,
) -> Result<Option<PhysicalAtmosphere>, Unusable> {
    let mut file = match crate::csv_input::open(f, max_file_bytes(resolution)) {
        Ok(file) => file,
        // No entry (a path through a file is checked as a folder before the work).
        Err(e)
            if matches!(
                e.kind(),
                std::io::ErrorKind::NotFound | std::io::ErrorKind::NotADirectory
            ) =>
        {
            return Ok(None);
        }
        Err(e) if e.kind() == std::io::ErrorKind::InvalidInput => {
            return Err(Unusable::NotAFile(e.to_string()));
        }
        Err(e) => return Err(Unusable::Invalid(e.to_string())),
    };
    let mut bytes = Vec::new();
    file.read_to_end(&mut bytes)
        .map_err(|e| Unusable::Invalid(e.to_string()))?;
    decode(&bytes, atmosphere, resolution)
        .map(Some)
        .map_err(|e| Unusable::Invalid(format!("{e:#}")))
}

/// Whether `name` is a cache entry's: `physical-`, 16 hexadecimal digits, `.bin`.
fn is_entry_name(name: &std::ffi::OsStr) -> bool {
    name.to_str()
        .and_then(|n| n.strip_prefix("physical-"))
        .and_then(|n| n.strip_suffix(".bin"))
        .is_some_and(|k| k.len() == 16 && k.bytes().all(|b| b.is_ascii_hexdigit()))
}

/// Removes the least recently used entries of `dir` until they take at most
/// [`MAX_CACHE_BYTES`] together, never `keep` (module docs); what cannot be removed stays.
fn evict(dir: &Path, keep: &Path) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let mut found: Vec<(SystemTime, u64, PathBuf)> = entries
        .flatten()
        .filter(|e| is_entry_name(&e.file_name()))
        .filter_map(|e| {
            let m = std::fs::symlink_metadata(e.path()).ok()?;
            let used = m.modified().ok()?;
            m.is_file().then(|| (used, m.len(), e.path()))
        })
        .collect();
    let mut total: u64 = found.iter().map(|(_, len, _)| len).sum();
    found.sort();
    for (_, len, p) in found {
        if total <= MAX_CACHE_BYTES {
            break;
        }
        if p.file_name() != keep.file_name() && std::fs::remove_file(&p).is_ok() {
            total -= len;
        }
    }
}

/// The longest cache file of `resolution`: its tables, and the most orders a file may list.
#[must_use]
pub fn max_file_bytes(resolution: &Resolution) -> u64 {
    let r = resolution;
    let cells = r.ground_sun.len() * r.ground_mu * r.ground_phi;
    let words = 8 + 4 + 8 // magic, version, key
        + 16 + 24 * r.transmittance_r * r.transmittance_mu
        + 3 * (8 + 4 * cells * NW)
        + 8 + 8 * NW * r.ground_sun.len()
        + 8 + 32 * MAX_ORDERS
        + 8; // checksum
    words as u64
}

/// `body` made a cache file of the atmosphere `key`: the magic, the format version and
/// the key in front, the checksum behind (the fuzz target's way to reach the tables).
#[must_use]
pub fn seal(body: &[u8], key: u64) -> Vec<u8> {
    let mut out = Vec::with_capacity(body.len() + 28);
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
    put_u64(&mut out, key);
    out.extend_from_slice(body);
    let mut h = Fnv::new();
    h.bytes(&out);
    put_u64(&mut out, h.0);
    out
}

/// A resolution of the default's layout with the fewest cells (2 × 2 transmittance cells,
/// 4 sun angles of 2 × 2 ground cells): cache files of some 11 kB for the fuzz target and
/// tests. Not for skies anyone looks at.
#[must_use]
pub fn small_resolution() -> Resolution {
    let sun = SunGrid {
        day_step: 60.0,
        dusk_step: 24.0,
        twilight_step: 26.0,
        max_deg: 110.0,
    };
    Resolution {
        transmittance_r: 2,
        transmittance_mu: 2,
        transmittance_steps: 8,
        orders_r: 2,
        orders_mu_half: 2,
        orders_phi: 2,
        orders_sun: sun,
        ground_mu: 2,
        ground_phi: 2,
        ground_sun: sun,
        single_steps: 4,
        multiple_steps: 4,
        irradiance_theta: 4,
        max_orders: 2,
        ..Resolution::default()
    }
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

/// Checks a decoded file's values: column densities, single- and multiple-scattering
/// radiances and diffuse irradiances finite and non-negative (each is a sum or integral of
/// non-negative terms), the orders' reports finite.
fn check_values(
    columns: &[[f64; 3]],
    tables: [&Table3; 3],
    diffuse: &[Spectrum],
    orders: &[OrderReport],
) -> Result<()> {
    let ok = |v: f64| v.is_finite() && v >= 0.0;
    if let Some(i) = columns.iter().flatten().position(|&v| !ok(v)) {
        bail!(
            "cache file with a column density of {} (value {i})",
            columns.as_flattened()[i]
        );
    }
    for (name, t) in ["single Rayleigh", "single aerosol", "multiple"]
        .iter()
        .zip(tables)
    {
        if let Some(v) = t.data.iter().find(|v| !ok(f64::from(**v))) {
            bail!("cache file with a {name} scattering radiance of {v}");
        }
    }
    if let Some(v) = diffuse.iter().flatten().find(|v| !ok(**v)) {
        bail!("cache file with a diffuse irradiance of {v}");
    }
    for o in orders {
        if ![o.max_change, o.at_elevation_deg, o.change_at_minus_12]
            .iter()
            .all(|v| v.is_finite())
        {
            bail!(
                "cache file with a report of order {} that is not finite",
                o.order
            );
        }
    }
    Ok(())
}

/// Reads a cache file written for `atmosphere` at `resolution`, and checks its values (module
/// docs).
///
/// # Errors
/// A wrong magic, version, key, size or checksum; trailing bytes; a value not finite or out of
/// range.
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
    if n > MAX_ORDERS {
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
    if r.at != body.len() {
        bail!(
            "cache file with {} bytes after its tables",
            body.len() - r.at
        );
    }
    check_values(
        &columns,
        [&rayleigh, &aerosol, &multiple],
        &diffuse,
        &orders,
    )?;
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The small resolution's default atmosphere, built once.
    fn small() -> &'static (PhysicalAtmosphere, Vec<u8>) {
        static SMALL: std::sync::OnceLock<(PhysicalAtmosphere, Vec<u8>)> =
            std::sync::OnceLock::new();
        SMALL.get_or_init(|| {
            let res = small_resolution();
            let atm = Atmosphere::default();
            let built = PhysicalAtmosphere::build(&atm, &res, &ProgressBar::hidden())
                .expect("small atmosphere");
            let bytes = encode(&built, version_key(&atm, &res));
            (built, bytes)
        })
    }

    /// `bytes` with the f64 at `at` replaced by `v` and the checksum made valid again.
    fn poked(bytes: &[u8], at: usize, v: f64) -> Vec<u8> {
        let mut body = bytes[20..bytes.len() - 8].to_vec();
        body[at - 20..at - 12].copy_from_slice(&v.to_le_bytes());
        seal(
            &body,
            u64::from_le_bytes(bytes[12..20].try_into().expect("key")),
        )
    }

    #[test]
    fn a_valid_file_with_values_out_of_range_is_refused() {
        let (_, bytes) = small();
        let (atm, res) = (Atmosphere::default(), small_resolution());
        assert!(decode(bytes, &atm, &res).is_ok(), "the file as written");
        assert!(bytes.len() as u64 <= max_file_bytes(&res));
        // The first transmittance column density: after magic, version, key, nr and nmu.
        let first_column = 8 + 4 + 8 + 16;
        for bad in [f64::NAN, f64::INFINITY, -1.0] {
            let e = decode(&poked(bytes, first_column, bad), &atm, &res).expect_err("refused");
            assert!(e.to_string().contains("column density"), "{e}");
        }
        // The last diffuse irradiance: before the orders (a count and 32 bytes each).
        let orders = small().0.ground.orders.len();
        let last_diffuse = bytes.len() - 8 - 8 - 32 * orders - 8;
        let e = decode(&poked(bytes, last_diffuse, f64::NAN), &atm, &res).expect_err("NaN");
        assert!(e.to_string().contains("diffuse irradiance"), "{e}");
        // A byte more than the tables.
        let mut longer = bytes[20..bytes.len() - 8].to_vec();
        longer.push(0);
        let e = decode(&seal(&longer, version_key(&atm, &res)), &atm, &res).expect_err("long");
        assert!(e.to_string().contains("after its tables"), "{e}");
    }

    /// Writes the fuzz target's seeds (`fuzz/corpus/physical_cache/`): the small resolution's
    /// default atmosphere as a whole file, and its body alone (which the target seals).
    #[test]
    #[ignore = "regenerates fuzz seeds: cargo test -p sky-train --lib write_fuzz_seeds -- --ignored"]
    fn write_fuzz_seeds() {
        let (_, bytes) = small();
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../fuzz/corpus/physical_cache");
        std::fs::create_dir_all(&dir).expect("corpus folder");
        std::fs::write(dir.join("small_default.bin"), bytes).expect("seed");
        std::fs::write(
            dir.join("small_default_body.bin"),
            &bytes[20..bytes.len() - 8],
        )
        .expect("seed");
    }

    #[test]
    fn parameters_that_are_the_same_atmosphere_share_a_key() {
        let res = Resolution::default();
        let base = Atmosphere {
            aod_550: 0.0,
            ..Atmosphere::default()
        };
        let key = version_key(&base, &res);
        for aod in [-0.0, 1e-320, 5e-10] {
            let a = Atmosphere {
                aod_550: aod,
                ..base
            };
            assert_eq!(version_key(&a, &res), key, "aod {aod:e}");
        }
        let near = Atmosphere {
            aod_550: 0.151 + 1e-15,
            ..base
        };
        let clean = Atmosphere {
            aod_550: 0.151,
            ..base
        };
        assert_eq!(version_key(&near, &res), version_key(&clean, &res));
        // Different atmospheres stay apart.
        let other = Atmosphere {
            aod_550: 0.1510001,
            ..base
        };
        assert_ne!(version_key(&other, &res), version_key(&clean, &res));
        assert_ne!(version_key(&clean, &res), key);
    }

    #[test]
    fn only_entry_names_count() {
        for (name, entry) in [
            ("physical-0123456789abcdef.bin", true),
            ("physical-0123456789ABCDEF.bin", true),
            ("physical-0123456789abcde.bin", false),
            ("physical-0123456789abcdefg.bin", false),
            ("physical-0123456789abcdef.bin.bak", false),
            ("notes.bin", false),
        ] {
            assert_eq!(is_entry_name(std::ffi::OsStr::new(name)), entry, "{name}");
        }
    }
}
