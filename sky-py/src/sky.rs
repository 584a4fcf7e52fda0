//! The sky models ([`Sky`]: one class, a constructor per sky-core model), their radiance at
//! arrays of view directions and their equirectangular images, and the direction helpers.
//!
//! Angles are sky-core's: radians, the zenith angle from +z (up), the azimuth φ from +x (east)
//! towards +y (north). View directions are arrays of shape (..., 3) of x, y, z (east, north,
//! up; any length); results have the same leading shape.

use numpy::{AllowTypeChange, PyArray1, PyArrayLikeDyn, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::exceptions::PyOverflowError;
use pyo3::prelude::*;
use pyo3::types::PyBytes;
use sky_core::aoas::{AoasSky, DayCycle, Preset, Scattering};
use sky_core::daylight::{self, Daylight, DaylightSky};
use sky_core::geom::{self, Equirect, Extent};
use sky_core::measurement::Measurement;
use sky_core::neural::{NeuralWeights, pretrained};
use sky_core::perez::SkyCondition;
use sky_core::sh::ShSky;
use sky_core::{CieSky, NeuralSky, PerezSky, Photometry, PreethamSky, Sun, Vec3, color};

use crate::{collect, value_error};

/// The model behind a [`Sky`].
// One per Python `Sky`; the large states are boxed.
#[derive(Debug, Clone)]
enum Model {
    Preetham(PreethamSky),
    Neural(Box<NeuralSky>),
    Daylight(Box<DaylightSky>),
    Cie(CieSky),
    Perez(PerezSky),
    Aoas(Box<AoasSky>),
    Sh(Box<ShSky>),
}

/// What [`Model::evaluate`] computes per direction.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Quantity {
    /// Linear sRGB, the model's units.
    Rgb,
    /// CIE 1931 XYZ, Y in cd/m².
    Xyz,
    /// The luminance: XYZ's Y, cd/m².
    Luminance,
}

impl Quantity {
    fn new(name: &str) -> PyResult<Self> {
        match name {
            "rgb" => Ok(Self::Rgb),
            "xyz" => Ok(Self::Xyz),
            "luminance" => Ok(Self::Luminance),
            other => Err(value_error(
                "quantity",
                format!("{other:?} is not \"rgb\", \"xyz\" or \"luminance\""),
            )),
        }
    }

    /// Values per direction.
    fn channels(self) -> usize {
        if self == Self::Luminance { 1 } else { 3 }
    }
}

impl Model {
    fn name(&self) -> &'static str {
        match self {
            Self::Preetham(_) => "preetham",
            Self::Neural(_) => "neural",
            Self::Daylight(_) => "daylight",
            Self::Cie(_) => "cie",
            Self::Perez(_) => "perez",
            Self::Aoas(_) => "aoas",
            Self::Sh(_) => "sh",
        }
    }

    /// Linear sRGB at `dirs` into `out`: each model's batch path where it has one (the same
    /// values as its one-direction `rgb`, bit for bit), else its XYZ through sky-core's sRGB
    /// matrix.
    fn rgb(&self, dirs: &[Vec3], out: &mut [Vec3]) {
        match self {
            Self::Preetham(s) => s.rgb_batch(dirs, out),
            Self::Neural(s) => s.rgb_batch(dirs, out),
            Self::Daylight(s) => s.rgb_batch(dirs, out),
            Self::Aoas(s) => s.rgb_batch(dirs, out),
            Self::Sh(s) => {
                for (o, d) in out.iter_mut().zip(dirs) {
                    *o = s.radiance(*d);
                }
            }
            Self::Cie(s) => photometric_rgb(s, dirs, out),
            Self::Perez(s) => photometric_rgb(s, dirs, out),
        }
    }

    /// CIE XYZ (cd/m²) at `dirs` into `out`, by sky-core's [`Photometry`] for every model that
    /// has photometric units.
    ///
    /// # Errors
    /// The AOAS sky (O'Neil's relative units) and the SH lighting (an RGB series), which have
    /// no XYZ.
    fn xyz(&self, dirs: &[Vec3], out: &mut [Vec3]) -> PyResult<()> {
        match self {
            Self::Preetham(s) => {
                for (o, d) in out.iter_mut().zip(dirs) {
                    *o = s.xyz(*d);
                }
            }
            Self::Neural(s) => {
                s.rgb_batch(dirs, out);
                for o in out.iter_mut() {
                    *o = color::linear_srgb_to_xyz(*o);
                }
            }
            Self::Daylight(s) => s.xyz_batch(dirs, out),
            Self::Cie(s) => photometric_xyz(s, dirs, out),
            Self::Perez(s) => photometric_xyz(s, dirs, out),
            Self::Aoas(_) | Self::Sh(_) => {
                return Err(value_error(
                    "quantity",
                    format!(
                        "the {} sky has linear RGB only (no photometric units): use \"rgb\"",
                        self.name()
                    ),
                ));
            }
        }
        Ok(())
    }

    /// `quantity` at `dirs`, flattened: 3 or 1 values per direction.
    fn evaluate(&self, quantity: Quantity, dirs: &[Vec3]) -> PyResult<Vec<f32>> {
        let mut out = filled(dirs.len(), Vec3::ZERO)?;
        match quantity {
            Quantity::Rgb => self.rgb(dirs, &mut out),
            Quantity::Xyz | Quantity::Luminance => self.xyz(dirs, &mut out)?,
        }
        let mut values = filled(out.len() * quantity.channels(), 0.0)?;
        if quantity == Quantity::Luminance {
            for (v, o) in values.iter_mut().zip(&out) {
                *v = o.y;
            }
        } else {
            for (v, o) in values.chunks_exact_mut(3).zip(&out) {
                v.copy_from_slice(&o.to_array());
            }
        }
        Ok(values)
    }
}

fn photometric_xyz(sky: &impl Photometry, dirs: &[Vec3], out: &mut [Vec3]) {
    for (o, d) in out.iter_mut().zip(dirs) {
        *o = sky.xyz(*d);
    }
}

fn photometric_rgb(sky: &impl Photometry, dirs: &[Vec3], out: &mut [Vec3]) {
    for (o, d) in out.iter_mut().zip(dirs) {
        *o = color::xyz_to_linear_srgb(sky.xyz(*d));
    }
}

/// The whole number `value` of the parameter `name` within [`min`, `max`], or sky-core's
/// out-of-range error (Python integers are unbounded; the Rust types are not).
fn whole<T: TryFrom<i64>>(name: &'static str, value: i64, min: i64, max: i64) -> PyResult<T> {
    match T::try_from(value) {
        Ok(v) if (min..=max).contains(&value) => Ok(v),
        #[allow(clippy::cast_precision_loss)] // for the message
        _ => Err(value_error(
            "",
            sky_core::SkyError::OutOfRange {
                parameter: name,
                value: value as f32,
                min: min as f32,
                max: max as f32,
            },
        )),
    }
}

/// The Python int `value` of the parameter `name` within [`min`, `max`] ([`whole`]); an int
/// beyond i64 is out of that range too (a `ValueError`, not Python's `OverflowError`).
fn whole_arg<T: TryFrom<i64>>(
    name: &'static str,
    value: &Bound<'_, PyAny>,
    min: i64,
    max: i64,
) -> PyResult<T> {
    match value.extract::<i64>() {
        Ok(v) => whole(name, v, min, max),
        Err(e) if e.is_instance_of::<PyOverflowError>(value.py()) => Err(value_error(
            "",
            format!("{name} = {value} is outside the valid range [{min}, {max}]"),
        )),
        Err(e) => Err(e),
    }
}

/// The most pixels of an image from [`Sky::render`] or [`equirect_directions`]: 8192 × 4096
/// (as `sky-train render`'s largest), 384 MiB of float32 RGB.
const MAX_PIXELS: u64 = 1 << 25;

/// A `width` × `height` grid of at most [`MAX_PIXELS`].
fn image_size(width: &Bound<'_, PyAny>, height: &Bound<'_, PyAny>) -> PyResult<(u32, u32)> {
    let max = i64::from(Equirect::MAX_SIZE);
    let width: u32 = whole_arg("image width [px]", width, 1, max)?;
    let height: u32 = whole_arg("image height [px]", height, 1, max)?;
    if u64::from(width) * u64::from(height) > MAX_PIXELS {
        return Err(value_error(
            "width, height",
            format!("{width} × {height} pixels: at most {MAX_PIXELS} (8192 × 4096) in one image"),
        ));
    }
    Ok((width, height))
}

/// A vector of `n` copies of `value`, or Python's `MemoryError`.
fn filled<T: Clone>(n: usize, value: T) -> PyResult<Vec<T>> {
    collect(n, core::iter::repeat_n(value, n))
}

/// The sun at `zenith`, `azimuth` (radians).
fn sun(zenith: f32, azimuth: f32) -> PyResult<Sun> {
    Sun::new(zenith, azimuth).map_err(|e| value_error("", e))
}

/// The rows of an array of shape (..., 3) as directions, with the leading shape.
fn directions(
    dirs: &PyArrayLikeDyn<'_, f32, AllowTypeChange>,
    name: &str,
) -> PyResult<(Vec<usize>, Vec<Vec3>)> {
    let shape = dirs.shape().to_vec();
    let Some((&3, leading)) = shape.split_last() else {
        return Err(value_error(
            name,
            format!("shape {shape:?}: the last axis must hold x, y, z (length 3)"),
        ));
    };
    let n = leading.iter().product();
    let mut flat = dirs.as_array().into_iter().copied();
    let mut next = || flat.next().unwrap_or(f32::NAN); // the shape holds 3 n of them
    let dirs = collect(n, (0..n).map(|_| Vec3::new(next(), next(), next())))?;
    Ok((leading.to_vec(), dirs))
}

/// `values` as a float32 array of shape `leading` (+ 3 when there are 3 values per item).
fn shaped<'py>(
    py: Python<'py>,
    values: Vec<f32>,
    mut leading: Vec<usize>,
    channels: usize,
) -> PyResult<Bound<'py, PyAny>> {
    if channels > 1 {
        leading.push(channels);
    }
    Ok(PyArray1::from_vec(py, values).reshape(leading)?.into_any())
}

/// The grid's extent by name.
fn extent(name: &str) -> PyResult<Extent> {
    match name {
        "upper" => Ok(Extent::UpperHemisphere),
        "sphere" => Ok(Extent::Sphere),
        other => Err(value_error(
            "extent",
            format!("{other:?} is not \"upper\" (the upper hemisphere) or \"sphere\""),
        )),
    }
}

/// The directions through the pixel centres of a `width` × `height` equirectangular grid, row
/// by row from the top.
fn grid(width: u32, height: u32, extent: Extent) -> PyResult<Vec<Vec3>> {
    let grid = Equirect::new(width, height, extent).map_err(|e| value_error("", e))?;
    let mut dirs = filled(width as usize * height as usize, Vec3::ZERO)?;
    for (k, d) in dirs.iter_mut().enumerate() {
        #[allow(clippy::cast_possible_truncation)] // below MAX_PIXELS
        let (i, j) = ((k % width as usize) as u32, (k / width as usize) as u32);
        *d = grid.direction(i, j);
    }
    Ok(dirs)
}

/// One sky of one of sky-core's models, built once from its parameters by a constructor per
/// model (`Sky.preetham`, `Sky.neural`, `Sky.daylight`, `Sky.cie`, `Sky.perez`,
/// `Sky.perez_from_irradiance`, `Sky.aoas`, `Sky.sh`), then evaluated at arrays of view
/// directions (`rgb`, `xyz`, `luminance`) or over an equirectangular image (`render`).
///
/// Angles are radians in sky-core's frame: the zenith angle from +z (up), the azimuth from +x
/// (east) towards +y (north), so that a compass azimuth A (from north, clockwise, as pvlib's)
/// is φ = 90° − A; `skymodels.sun_position` gives the sun in both (`sun_zenith`,
/// `sun_azimuth` are what these constructors take). View directions are float arrays of shape
/// (..., 3): x (east), y (north), z (up), any length; every model is 0 below the horizon.
///
/// Units: the Preetham, neural, daylight, CIE and Perez skies in cd/m² (linear sRGB on the
/// cd/m² scale, XYZ with Y the luminance); AOAS and the SH lighting in linear RGB of their own
/// scale (O'Neil's relative units; the SH lighting of the Preetham sky in cd/m²).
///
/// A parameter out of its range raises `ValueError` with sky-core's message, naming the
/// parameter and its valid range.
#[pyclass(frozen, module = "skymodels", name = "Sky")]
#[derive(Debug, Clone)]
pub(crate) struct Sky {
    model: Model,
    sun: Sun,
}

#[pymethods]
impl Sky {
    /// The Preetham sky (the Perez distribution with Preetham, Shirley & Smits's 1999
    /// coefficients) for a sun at `sun_zenith` in [0, π/2] and `sun_azimuth` (radians), and
    /// `turbidity` in [2, 6].
    #[staticmethod]
    fn preetham(sun_zenith: f32, sun_azimuth: f32, turbidity: f32) -> PyResult<Self> {
        let sun = sun(sun_zenith, sun_azimuth)?;
        let sky = PreethamSky::new(sun, turbidity).map_err(|e| value_error("", e))?;
        Ok(Self {
            model: Model::Preetham(sky),
            sun,
        })
    }

    /// The neural sky (Satilmis et al.'s 6-12-3 network, 492 bytes of weights) for a sun at
    /// `sun_zenith` in [0, π/2] and `sun_azimuth` (radians) and `turbidity` in the weights'
    /// trained range. `weights`: "preetham" (trained on the Preetham sky, turbidity 2-6),
    /// "hosek" (on the Hosek-Wilkie sky, 1-10), or the bytes of a weight file as `sky-train
    /// train` writes it. Linear sRGB in cd/m².
    #[staticmethod]
    #[pyo3(signature = (sun_zenith, sun_azimuth, turbidity, weights = None))]
    fn neural(
        sun_zenith: f32,
        sun_azimuth: f32,
        turbidity: f32,
        weights: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let decoded;
        let weights: &NeuralWeights = match weights {
            None => &pretrained::PREETHAM,
            Some(w) if w.is_instance_of::<PyBytes>() => {
                let bytes = w.cast::<PyBytes>()?.as_bytes();
                decoded = NeuralWeights::decode(bytes).map_err(|e| value_error("weights", e))?;
                &decoded
            }
            Some(w) => match w.extract::<String>()?.as_str() {
                "preetham" => &pretrained::PREETHAM,
                "hosek" => &pretrained::HOSEK,
                other => {
                    return Err(value_error(
                        "weights",
                        format!(
                            "{other:?} is not a shipped neural sky (\"preetham\" or \"hosek\") \
                             nor the bytes of a weight file"
                        ),
                    ));
                }
            },
        };
        let sun = sun(sun_zenith, sun_azimuth)?;
        let sky = NeuralSky::new(weights, sun, turbidity).map_err(|e| value_error("", e))?;
        Ok(Self {
            model: Model::Neural(Box::new(sky)),
            sun,
        })
    }

    /// The clear sky of sky-core's daylight (the physical atmosphere's radiance distilled into
    /// three neural networks, `DaylightSky`) for a sun at `sun_zenith` in [0, π] (below the
    /// horizon too: twilight, down to 108°, lower suns drawing the 108° sky) and `sun_azimuth`
    /// (radians), under an aerosol optical depth `aod` at 550 nm in [`MIN_AOD`, `MAX_AOD`]
    /// (None: `DEFAULT_AOD`). XYZ and linear sRGB in cd/m²; in deep twilight an sRGB channel
    /// may be negative (the colour is outside the sRGB gamut).
    #[staticmethod]
    #[pyo3(signature = (sun_zenith, sun_azimuth, aod = None))]
    fn daylight(sun_zenith: f32, sun_azimuth: f32, aod: Option<f32>) -> PyResult<Self> {
        let sun = sun(sun_zenith, sun_azimuth)?;
        let day = Daylight::new(sun, aod.unwrap_or(daylight::DEFAULT_AOD))
            .map_err(|e| value_error("aod", e))?;
        Ok(Self {
            model: Model::Daylight(Box::new(day.sky())),
            sun,
        })
    }

    /// One of the 15 CIE standard general skies (ISO 15469:2004 / CIE S 011/E:2003),
    /// `sky_type` 1 (overcast) to 15 (cloudless), for a sun at `sun_zenith` in [0, π/2] and
    /// `sun_azimuth` (radians), scaled by exactly one of `zenith_luminance` (cd/m², 0 to 1e10)
    /// or `diffuse_illuminance` (its horizontal illuminance, lux, 0 to 1e9), with the CIE 1931
    /// `chromaticity` (x, y) everywhere (None: D65).
    #[staticmethod]
    #[pyo3(signature = (sky_type, sun_zenith, sun_azimuth, *, zenith_luminance = None,
                        diffuse_illuminance = None, chromaticity = None))]
    fn cie(
        sky_type: &Bound<'_, PyAny>,
        sun_zenith: f32,
        sun_azimuth: f32,
        zenith_luminance: Option<f32>,
        diffuse_illuminance: Option<f32>,
        chromaticity: Option<[f32; 2]>,
    ) -> PyResult<Self> {
        let sky_type = whole_arg("CIE sky type", sky_type, 1, 15)?;
        let sun = sun(sun_zenith, sun_azimuth)?;
        let sky = match (zenith_luminance, diffuse_illuminance) {
            (Some(l), None) => CieSky::new(sky_type, sun, l),
            (None, Some(e)) => CieSky::from_diffuse_illuminance(sky_type, sun, e),
            _ => {
                return Err(value_error(
                    "zenith_luminance",
                    "give exactly one of zenith_luminance (cd/m²) and diffuse_illuminance (lx)",
                ));
            }
        };
        let mut sky = sky.map_err(|e| value_error("", e))?;
        if let Some([x, y]) = chromaticity {
            sky = sky
                .with_chromaticity(x, y)
                .map_err(|e| value_error("chromaticity", e))?;
        }
        Ok(Self {
            model: Model::Cie(sky),
            sun,
        })
    }

    /// The Perez all-weather sky (Perez, Seals & Michalsky 1993) for a sun at `sun_zenith` in
    /// [0, π/2] and `sun_azimuth` (radians), sky clearness `clearness` (ε, at least 1) and sky
    /// brightness `brightness` (Δ, at least 0), scaled to the horizontal illuminance
    /// `diffuse_illuminance` (lux), with the CIE 1931 `chromaticity` (x, y) everywhere (None:
    /// D65).
    #[staticmethod]
    #[pyo3(signature = (sun_zenith, sun_azimuth, clearness, brightness, diffuse_illuminance, *,
                        chromaticity = None))]
    fn perez(
        sun_zenith: f32,
        sun_azimuth: f32,
        clearness: f32,
        brightness: f32,
        diffuse_illuminance: f32,
        chromaticity: Option<[f32; 2]>,
    ) -> PyResult<Self> {
        let sun = sun(sun_zenith, sun_azimuth)?;
        let condition = SkyCondition::new(clearness, brightness).map_err(|e| value_error("", e))?;
        let sky =
            PerezSky::new(sun, condition, diffuse_illuminance).map_err(|e| value_error("", e))?;
        Self::perez_coloured(sky, sun, chromaticity)
    }

    /// The Perez all-weather sky of a measurement: global and diffuse horizontal irradiance
    /// `ghi`, `dhi` (W/m²) taken with the sun at `sun_zenith` in [0, π/2] and `sun_azimuth`
    /// (radians) on day `day_of_year` (1-366): the reading's sky condition (ε, Δ), scaled to
    /// its diffuse illuminance (the diffuse irradiance times Perez's diffuse efficacy).
    #[staticmethod]
    #[pyo3(signature = (sun_zenith, sun_azimuth, ghi, dhi, day_of_year, *, chromaticity = None))]
    fn perez_from_irradiance(
        sun_zenith: f32,
        sun_azimuth: f32,
        ghi: f32,
        dhi: f32,
        day_of_year: &Bound<'_, PyAny>,
        chromaticity: Option<[f32; 2]>,
    ) -> PyResult<Self> {
        let day_of_year = whole_arg("day of the year", day_of_year, 1, 366)?;
        let sun = sun(sun_zenith, sun_azimuth)?;
        let reading = Measurement::Irradiance {
            global: ghi,
            diffuse: dhi,
        }
        .read(sun.zenith(), day_of_year)
        .map_err(|e| value_error("ghi, dhi", e))?;
        let sky = PerezSky::from_reading(sun, &reading).map_err(|e| value_error("", e))?;
        Self::perez_coloured(sky, sun, chromaticity)
    }

    /// The stylised single-scattering sky (O'Neil's scattering with the AOAS paper's aesthetic
    /// principles) of the style preset `preset` (`Sky.aoas_presets()`), with the preset's own
    /// sun, or one at `sun_zenith` in [0, π/2] and `sun_azimuth` (radians) when given. Linear
    /// RGB in O'Neil's relative units.
    #[staticmethod]
    #[pyo3(signature = (preset, sun_zenith = None, sun_azimuth = 0.0))]
    fn aoas(preset: &str, sun_zenith: Option<f32>, sun_azimuth: f32) -> PyResult<Self> {
        let mut style = Preset::from_name(preset)
            .ok_or_else(|| {
                value_error(
                    "preset",
                    format!(
                        "{preset:?} is not an AOAS style preset (one of: {})",
                        Self::aoas_presets().join(", ")
                    ),
                )
            })?
            .style();
        if let Some(zenith) = sun_zenith {
            style.day_cycle = DayCycle::Sun(sun(zenith, sun_azimuth)?);
        }
        let sky = AoasSky::new(&Scattering::default(), &style).map_err(|e| value_error("", e))?;
        let sun = sky.sun();
        Ok(Self {
            model: Model::Aoas(Box::new(sky)),
            sun,
        })
    }

    /// The names of the AOAS style presets.
    #[staticmethod]
    fn aoas_presets() -> Vec<&'static str> {
        Preset::ALL.iter().map(|p| p.name()).collect()
    }

    /// The spherical-harmonics lighting of the Preetham sky (Habel et al. 2008: polynomial
    /// tables in sun zenith and turbidity, the ringing filter, rotated to the sun's azimuth)
    /// with `bands` bands (1-7), for a sun at `sun_zenith` in [0, π/2] and `sun_azimuth`
    /// (radians) and `turbidity` in [2.5, 6]. Linear sRGB, cd/m² scale.
    #[staticmethod]
    #[pyo3(signature = (sun_zenith, sun_azimuth, turbidity, bands = None),
           text_signature = "(sun_zenith, sun_azimuth, turbidity, bands=3)")]
    fn sh(
        sun_zenith: f32,
        sun_azimuth: f32,
        turbidity: f32,
        bands: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let bands = match bands {
            Some(b) => whole_arg("SH bands", b, 1, 7)?,
            None => 3,
        };
        let sun = sun(sun_zenith, sun_azimuth)?;
        let sky = ShSky::new(sun, turbidity, bands).map_err(|e| value_error("", e))?;
        Ok(Self {
            model: Model::Sh(Box::new(sky)),
            sun,
        })
    }

    /// The model's name: "preetham", "neural", "daylight", "cie", "perez", "aoas" or "sh".
    #[getter]
    fn model(&self) -> &'static str {
        self.model.name()
    }

    /// The sun's zenith angle, radians.
    #[getter]
    fn sun_zenith(&self) -> f32 {
        self.sun.zenith()
    }

    /// The sun's azimuth, radians (from +x, east, towards +y, north).
    #[getter]
    fn sun_azimuth(&self) -> f32 {
        self.sun.azimuth()
    }

    fn __repr__(&self) -> String {
        format!(
            "<skymodels.Sky {}: sun zenith {} rad, azimuth {} rad>",
            self.model.name(),
            self.sun.zenith(),
            self.sun.azimuth()
        )
    }

    /// Linear sRGB radiance towards each view direction of `dirs` (shape (..., 3): x east,
    /// y north, z up, any length): float32 of shape (..., 3), cd/m² scale (AOAS: relative
    /// units). 0 below the horizon.
    fn rgb<'py>(
        &self,
        py: Python<'py>,
        dirs: PyArrayLikeDyn<'py, f32, AllowTypeChange>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.evaluate(py, Quantity::Rgb, &dirs)
    }

    /// CIE 1931 XYZ radiance towards each view direction of `dirs` (shape (..., 3)): float32 of
    /// shape (..., 3), Y the luminance in cd/m². Not for AOAS and SH (RGB only).
    fn xyz<'py>(
        &self,
        py: Python<'py>,
        dirs: PyArrayLikeDyn<'py, f32, AllowTypeChange>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.evaluate(py, Quantity::Xyz, &dirs)
    }

    /// Luminance towards each view direction of `dirs` (shape (..., 3)): float32 of shape
    /// (...), cd/m² (XYZ's Y). Not for AOAS and SH.
    fn luminance<'py>(
        &self,
        py: Python<'py>,
        dirs: PyArrayLikeDyn<'py, f32, AllowTypeChange>,
    ) -> PyResult<Bound<'py, PyAny>> {
        self.evaluate(py, Quantity::Luminance, &dirs)
    }

    /// An equirectangular image `width` × `height` (1 to 65536 each, at most 2²⁵ pixels) of `quantity` ("rgb",
    /// "xyz" or "luminance"): float32 of shape (height, width, 3) or (height, width). Row j
    /// has the zenith angle θ_max (j + ½) / height, θ_max = π/2 for `extent="upper"` (the
    /// upper hemisphere) or π for "sphere"; column i the azimuth 2π (i + ½) / width (from +x,
    /// east, towards +y, north; `equirect_directions` gives every pixel's direction).
    #[pyo3(signature = (width, height, *, extent = "upper", quantity = "rgb"))]
    fn render<'py>(
        &self,
        py: Python<'py>,
        width: &Bound<'py, PyAny>,
        height: &Bound<'py, PyAny>,
        extent: &str,
        quantity: &str,
    ) -> PyResult<Bound<'py, PyAny>> {
        let (width, height) = image_size(width, height)?;
        let extent = self::extent(extent)?;
        let quantity = Quantity::new(quantity)?;
        let values = py.detach(|| -> PyResult<_> {
            let dirs = grid(width, height, extent)?;
            self.model.evaluate(quantity, &dirs)
        })?;
        shaped(
            py,
            values,
            vec![height as usize, width as usize],
            quantity.channels(),
        )
    }
}

impl Sky {
    fn perez_coloured(sky: PerezSky, sun: Sun, chromaticity: Option<[f32; 2]>) -> PyResult<Self> {
        let sky = match chromaticity {
            Some([x, y]) => sky
                .with_chromaticity(x, y)
                .map_err(|e| value_error("chromaticity", e))?,
            None => sky,
        };
        Ok(Self {
            model: Model::Perez(sky),
            sun,
        })
    }

    fn evaluate<'py>(
        &self,
        py: Python<'py>,
        quantity: Quantity,
        dirs: &PyArrayLikeDyn<'py, f32, AllowTypeChange>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let (leading, dirs) = directions(dirs, "dirs")?;
        let values = py.detach(|| self.model.evaluate(quantity, &dirs))?;
        shaped(py, values, leading, quantity.channels())
    }
}

/// Unit view directions (x east, y north, z up) of zenith angles `zenith` and azimuths
/// `azimuth` (radians; azimuth from +x, east, towards +y, north), sky-core's
/// `geom::direction`: arrays of one shape, the result float32 of that shape + (3,).
#[pyfunction]
pub(crate) fn direction<'py>(
    py: Python<'py>,
    zenith: PyArrayLikeDyn<'py, f32, AllowTypeChange>,
    azimuth: PyArrayLikeDyn<'py, f32, AllowTypeChange>,
) -> PyResult<Bound<'py, PyAny>> {
    let shape = zenith.shape().to_vec();
    if azimuth.shape() != shape.as_slice() {
        return Err(value_error(
            "azimuth",
            format!(
                "shape {:?} differs from the zenith angles' {shape:?}",
                azimuth.shape()
            ),
        ));
    }
    let values = collect(
        3 * zenith.len(),
        zenith
            .as_array()
            .iter()
            .zip(azimuth.as_array().iter())
            .flat_map(|(&t, &p)| geom::direction(t, p).to_array()),
    )?;
    shaped(py, values, shape, 3)
}

/// The unit directions through the pixel centres of a `width` × `height` equirectangular
/// image (the grid of `Sky.render`): float32 of shape (height, width, 3).
#[pyfunction]
#[pyo3(signature = (width, height, *, extent = "upper"))]
pub(crate) fn equirect_directions<'py>(
    py: Python<'py>,
    width: &Bound<'py, PyAny>,
    height: &Bound<'py, PyAny>,
    extent: &str,
) -> PyResult<Bound<'py, PyAny>> {
    let (width, height) = image_size(width, height)?;
    let extent = self::extent(extent)?;
    let dirs = py.detach(|| grid(width, height, extent))?;
    let values = collect(3 * dirs.len(), dirs.iter().flat_map(|d| d.to_array()))?;
    shaped(py, values, vec![height as usize, width as usize], 3)
}
