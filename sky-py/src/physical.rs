//! sky-train's physical spectral atmosphere ([`sky_train::physical`], the `physical` feature):
//! the reference that sky-core's daylight is distilled from, with its spectra.

use std::path::PathBuf;
use std::sync::Arc;

use numpy::{AllowTypeChange, PyArray1, PyArrayLikeDyn, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::exceptions::PyOSError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use sky_train::physical::cache::{self, CacheDir};
use sky_train::physical::constituents::{N_WAVELENGTHS, Spectrum, wavelengths_nm};
use sky_train::physical::sky::MAX_SUN_ZENITH_DEG;
use sky_train::physical::{self, Atmosphere, AtmosphereError, PhysicalSky, Resolution};

use crate::value_error;

/// The Python keyword of each of [`Atmosphere::RANGES`]' flags.
fn keyword(flag: &str) -> String {
    flag.trim_start_matches("--").replace('-', "_")
}

/// A precomputed clear atmosphere of sky-train's physical model (f64; Bruneton-style
/// precomputed multiple scattering over 47 bins of 10 nm, 360-830 nm; docs/daylight.md): the
/// reference sky-core's `daylight` is distilled from. The parameters are sky-train's
/// (`sky-train physical --help`); None keeps the default atmosphere's (the measured clear-sky
/// record's: aerosol optical depth 0.38 at 550 nm, Ångström exponent 1.3, ozone 300 DU, ground
/// albedo 0.2):
///
/// `aod` (0 to 5), `angstrom` (0 to 3), `aerosol_ssa` (single-scattering albedo, 0 to 1),
/// `aerosol_g` (Henyey-Greenstein asymmetry, -0.95 to 0.95), `aerosol_scale_height` (m, 100 to
/// 20000), `ozone_du` (Dobson units, 0 to 1000), `albedo` (the ground's, 0 to 1), `elevation`
/// (the ground's above sea level, m, -500 to 6000: the air and ozone above it).
///
/// The precomputation takes half a minute or more (28 s on a quiet 2-core machine), with the
/// GIL released; it is kept on disk in `cache_dir` (None: sky-train's, `$SKY_TRAIN_CACHE_DIR`
/// or `~/.cache/sky-train`; False: not kept) and read back from there. `resolution="coarse"`
/// is a handful of cells, precomputed in milliseconds: for tests only, not a sky to look at.
/// Sun zenith angles are radians, 0 to 108° (the sun 18° below the horizon).
#[pyclass(frozen, module = "skymodels", name = "PhysicalAtmosphere")]
pub(crate) struct PhysicalAtmosphere {
    atmosphere: Arc<physical::PhysicalAtmosphere>,
}

impl PhysicalAtmosphere {
    /// The sky for the sun at `zenith`, `azimuth` (radians).
    fn sky(&self, zenith: f64, azimuth: f64, name: &str) -> PyResult<PhysicalSky> {
        self.atmosphere
            .sky(zenith.to_degrees(), azimuth.to_degrees())
            .map_err(|e| {
                value_error(
                    name,
                    format!(
                        "the sun at zenith {zenith} rad ({:.3}°), azimuth {azimuth} rad: the \
                         zenith angle must be within [0, {MAX_SUN_ZENITH_DEG}°] ({:.6} rad) and \
                         the azimuth finite",
                        e.zenith_deg,
                        MAX_SUN_ZENITH_DEG.to_radians()
                    ),
                )
            })
    }
}

/// Spectra as a float64 array of shape `leading` + (47,).
fn spectra<'py>(
    py: Python<'py>,
    rows: &[Spectrum],
    mut leading: Vec<usize>,
) -> PyResult<Bound<'py, PyAny>> {
    leading.push(N_WAVELENGTHS);
    let flat: Vec<f64> = rows.iter().flatten().copied().collect();
    Ok(PyArray1::from_vec(py, flat).reshape(leading)?.into_any())
}

/// Sun zenith angles (radians, any shape), flattened, with their shape.
fn zeniths(zenith: &PyArrayLikeDyn<'_, f64, AllowTypeChange>) -> (Vec<usize>, Vec<f64>) {
    (
        zenith.shape().to_vec(),
        zenith.as_array().iter().copied().collect(),
    )
}

#[pymethods]
impl PhysicalAtmosphere {
    #[new]
    #[pyo3(signature = (aod = None, *, angstrom = None, aerosol_ssa = None, aerosol_g = None,
                        aerosol_scale_height = None, ozone_du = None, albedo = None,
                        elevation = None,
                        resolution = "default", cache_dir = None))]
    #[allow(clippy::too_many_arguments)] // the atmosphere's parameters, as keywords
    fn new(
        py: Python<'_>,
        aod: Option<f64>,
        angstrom: Option<f64>,
        aerosol_ssa: Option<f64>,
        aerosol_g: Option<f64>,
        aerosol_scale_height: Option<f64>,
        ozone_du: Option<f64>,
        albedo: Option<f64>,
        elevation: Option<f64>,
        resolution: &str,
        cache_dir: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let d = Atmosphere::default();
        let atmosphere = Atmosphere {
            aod_550: aod.unwrap_or(d.aod_550),
            angstrom: angstrom.unwrap_or(d.angstrom),
            aerosol_ssa: aerosol_ssa.unwrap_or(d.aerosol_ssa),
            aerosol_g: aerosol_g.unwrap_or(d.aerosol_g),
            aerosol_scale_height_m: aerosol_scale_height.unwrap_or(d.aerosol_scale_height_m),
            ozone_du: ozone_du.unwrap_or(d.ozone_du),
            ground_albedo: albedo.unwrap_or(d.ground_albedo),
            site_elevation_m: elevation.unwrap_or(d.site_elevation_m),
        };
        let describe = |e: AtmosphereError| {
            value_error(
                "",
                format!(
                    "{} = {} is outside the valid range [{}, {}]",
                    keyword(e.flag),
                    e.value,
                    e.range.0,
                    e.range.1
                ),
            )
        };
        atmosphere.validate().map_err(describe)?;
        let resolution = match resolution {
            "default" => Resolution::default(),
            "coarse" => cache::small_resolution(),
            other => {
                return Err(value_error(
                    "resolution",
                    format!("{other:?} is not \"default\" or \"coarse\" (for tests)"),
                ));
            }
        };
        let dir = match cache_dir {
            None => Some(CacheDir::default_dir()),
            Some(v) if v.is_instance_of::<pyo3::types::PyBool>() && !v.extract::<bool>()? => None,
            Some(v) => Some(CacheDir {
                path: v.extract::<PathBuf>()?,
                origin: "cache_dir",
            }),
        };
        let atmosphere = py
            .detach(|| cache::load_or_build_in(&atmosphere, &resolution, dir.as_ref(), false))
            .map_err(|e| match e.downcast::<AtmosphereError>() {
                Ok(e) => describe(e),
                Err(e) => PyOSError::new_err(format!("{e:#}")),
            })?;
        Ok(Self { atmosphere })
    }

    /// The wavelength bins' centres, nm: float64 (47,), 365 to 825.
    #[getter]
    fn wavelengths<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &wavelengths_nm())
    }

    /// The spectral irradiance with the sun at each of `sun_zenith` (radians, 0 to 108°; any
    /// shape), at 1 AU: a dict of float64 arrays of shape `sun_zenith.shape + (47,)`, W m⁻²
    /// nm⁻¹ per bin: `global`, `diffuse` and `direct_horizontal` on the horizontal plane,
    /// `direct_normal` on a plane facing the sun (the visible part of its disc).
    fn irradiance<'py>(
        &self,
        py: Python<'py>,
        sun_zenith: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let (shape, zenith) = zeniths(&sun_zenith);
        let rows = py.detach(|| -> PyResult<Vec<_>> {
            zenith
                .iter()
                .map(|&z| Ok(self.sky(z, 0.0, "sun_zenith")?.irradiance()))
                .collect()
        })?;
        let dict = PyDict::new(py);
        for (name, pick) in [
            (
                "global",
                (|e| e.global) as fn(&physical::Irradiance) -> Spectrum,
            ),
            ("diffuse", |e| e.diffuse),
            ("direct_horizontal", |e| e.direct_horizontal),
            ("direct_normal", |e| e.direct_normal),
        ] {
            let column: Vec<Spectrum> = rows.iter().map(pick).collect();
            dict.set_item(name, spectra(py, &column, shape.clone())?)?;
        }
        Ok(dict)
    }

    /// The daylight of the spectra of `irradiance` (sky-train's photometry, f64): a dict of
    /// float64 arrays of `sun_zenith`'s shape, as `skymodels.daylight`'s:
    /// `global_illuminance`, `diffuse_illuminance`, `direct_illuminance` (lx), `x`, `y`,
    /// `cct` (K), `duv` (NaN off the locus), `melanopic_edi` (lx) of the global light.
    fn daylight<'py>(
        &self,
        py: Python<'py>,
        sun_zenith: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let (shape, zenith) = zeniths(&sun_zenith);
        let rows = py.detach(|| -> PyResult<Vec<[f64; 8]>> {
            zenith
                .iter()
                .map(|&z| {
                    let d = self.sky(z, 0.0, "sun_zenith")?.daylight();
                    let (kelvin, duv) = d.global.cct_duv.unwrap_or((f64::NAN, f64::NAN));
                    Ok([
                        d.global.xyz[1],
                        d.diffuse.xyz[1],
                        d.direct.xyz[1],
                        d.global.xy.0,
                        d.global.xy.1,
                        kelvin,
                        duv,
                        d.global.melanopic_edi,
                    ])
                })
                .collect()
        })?;
        let dict = PyDict::new(py);
        let names = [
            "global_illuminance",
            "diffuse_illuminance",
            "direct_illuminance",
            "x",
            "y",
            "cct",
            "duv",
            "melanopic_edi",
        ];
        for (k, name) in names.into_iter().enumerate() {
            let column: Vec<f64> = rows.iter().map(|r| r[k]).collect();
            dict.set_item(name, PyArray1::from_vec(py, column).reshape(shape.clone())?)?;
        }
        Ok(dict)
    }

    /// Spectral sky radiance with the sun at `sun_zenith` (0 to 108°) and `sun_azimuth`
    /// (radians, from +x, east, towards +y, north) towards each view direction of `dirs`
    /// (shape (..., 3): x east, y north, z up, any length): float64 of shape (..., 47),
    /// W m⁻² sr⁻¹ nm⁻¹ per bin; 0 below the horizon.
    fn spectral_radiance<'py>(
        &self,
        py: Python<'py>,
        sun_zenith: f64,
        sun_azimuth: f64,
        dirs: PyArrayLikeDyn<'py, f64, AllowTypeChange>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let shape = dirs.shape().to_vec();
        let Some((&3, leading)) = shape.split_last() else {
            return Err(value_error(
                "dirs",
                format!("shape {shape:?}: the last axis must hold x, y, z (length 3)"),
            ));
        };
        let flat: Vec<f64> = dirs.as_array().iter().copied().collect();
        let sky = self.sky(sun_zenith, sun_azimuth, "sun_zenith, sun_azimuth")?;
        let rows: Vec<Spectrum> = py.detach(|| {
            flat.chunks_exact(3)
                .map(|d| sky.spectral_radiance([d[0], d[1], d[2]]))
                .collect()
        });
        spectra(py, &rows, leading.to_vec())
    }
}
