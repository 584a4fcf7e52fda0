//! Time series: the daylight ([`sky_core::daylight::Daylight`]), the sun
//! ([`sky_core::solar::SunPosition`]) and the controller ([`sky_core::controller::step`]) at
//! each of an array of times, computed with the GIL released. The Python package's
//! `daylight`, `daylight_at_sun`, `sun_position` and `controller_step` call these with the times
//! as microseconds since 1970 UTC and document them; each returns a dict of float64 arrays (the
//! f32 results of sky-core widened exactly), one per quantity.

use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use sky_core::controller::{self, Decomposition, Light, Measurement, Settings, Step};
use sky_core::daylight::{ClearAtmosphere, Daylight};
use sky_core::led::{Channel, Luminaire};
use sky_core::solar::SunAlgorithm;
use sky_core::{SkyError, Sun};

use crate::time::{self, element};
use crate::{collect, reserve, value_error};

/// The elements of a 1-D array, copied (the GIL is then released), or `MemoryError`.
fn elements<T: numpy::Element + Copy>(array: &PyReadonlyArray1<'_, T>) -> PyResult<Vec<T>> {
    let view = array.as_array();
    collect(view.len(), view.iter().copied())
}

/// An f32 parameter given once for every time (length 1) or per time (the times' length).
struct Broadcast {
    name: &'static str,
    values: Vec<f32>,
    /// Whether messages name the parameter without an index.
    scalar: bool,
}

impl Broadcast {
    /// `values` for `n` times.
    ///
    /// # Errors
    /// A `ValueError` naming `name` for another length.
    fn new(name: &'static str, values: &PyReadonlyArray1<'_, f32>, n: usize) -> PyResult<Self> {
        let values = elements(values)?;
        if values.len() != 1 && values.len() != n {
            return Err(value_error(
                name,
                format!(
                    "{} values for {n} times: give one value, or one per time",
                    values.len()
                ),
            ));
        }
        Ok(Self {
            name,
            scalar: values.len() == 1,
            values,
        })
    }

    /// The value for time `i`.
    fn at(&self, i: usize) -> f32 {
        let i = if self.scalar { 0 } else { i };
        self.values.get(i).copied().unwrap_or(f32::NAN)
    }

    /// The name of the value for time `i`, for messages.
    fn element(&self, i: usize) -> String {
        element(self.name, i, self.scalar)
    }
}

/// Columns of f64 values, one per name, filled one time at a time.
struct Columns<const N: usize> {
    names: [&'static str; N],
    data: [Vec<f64>; N],
}

impl<const N: usize> Columns<N> {
    fn new(names: [&'static str; N], capacity: usize) -> PyResult<Self> {
        let mut data: [Vec<f64>; N] = core::array::from_fn(|_| Vec::new());
        for column in &mut data {
            reserve(column, capacity)?;
        }
        Ok(Self { names, data })
    }

    fn push(&mut self, row: [f64; N]) {
        for (column, v) in self.data.iter_mut().zip(row) {
            column.push(v);
        }
    }

    /// The columns as a dict of 1-D float64 arrays, added to `dict`.
    fn into_dict(self, dict: &Bound<'_, PyDict>) -> PyResult<()> {
        for (name, column) in self.names.into_iter().zip(self.data) {
            dict.set_item(name, PyArray1::from_vec(dict.py(), column))?;
        }
        Ok(())
    }
}

/// Arrays shorter than this are computed on one thread: a thread's start costs tens of
/// microseconds, a time's daylight about one.
const MIN_CHUNK: usize = 8192;

/// `row(i, item)` for every item of `items`, as columns in the items' order: the items split
/// into one contiguous chunk per core (std threads, for arrays of at least [`MIN_CHUNK`] per
/// thread). The values do not depend on the split; an error is the first by index, as one
/// thread would find it.
/// [`columns`] on this thread, one item after the other (`row` may keep state).
fn in_order<T, const N: usize>(
    names: [&'static str; N],
    items: &[T],
    mut row: impl FnMut(usize, &T) -> PyResult<[f64; N]>,
) -> PyResult<Columns<N>> {
    let mut out = Columns::new(names, items.len())?;
    for (k, item) in items.iter().enumerate() {
        out.push(row(k, item)?);
    }
    Ok(out)
}

fn columns<T: Sync, const N: usize>(
    names: [&'static str; N],
    items: &[T],
    row: impl Fn(usize, &T) -> PyResult<[f64; N]> + Sync,
) -> PyResult<Columns<N>> {
    let chunk_of = |start: usize, chunk: &[T]| -> PyResult<Columns<N>> {
        in_order(names, chunk, |k, item| row(start + k, item))
    };
    let cores = std::thread::available_parallelism().map_or(1, std::num::NonZero::get);
    let threads = cores.min(items.len() / MIN_CHUNK).max(1);
    if threads == 1 {
        return chunk_of(0, items);
    }
    let size = items.len().div_ceil(threads);
    let parts: Vec<PyResult<Columns<N>>> = std::thread::scope(|scope| {
        let workers: Vec<_> = items
            .chunks(size)
            .enumerate()
            .map(|(t, chunk)| {
                let start = t * size;
                let worker =
                    std::thread::Builder::new().spawn_scoped(scope, move || chunk_of(start, chunk));
                (start, chunk, worker)
            })
            .collect();
        workers
            .into_iter()
            .map(|(start, chunk, worker)| match worker {
                Ok(w) => w.join().unwrap_or_else(|_| {
                    Err(pyo3::exceptions::PyRuntimeError::new_err(
                        "a worker thread failed",
                    ))
                }),
                // No thread to be had: this one computes the chunk.
                Err(_) => chunk_of(start, chunk),
            })
            .collect()
    });
    let mut all = Columns::new(names, items.len())?;
    for part in parts {
        for (column, values) in all.data.iter_mut().zip(part?.data) {
            column.extend_from_slice(&values);
        }
    }
    Ok(all)
}

/// [`columns`] with the GIL released, as a dict of float64 arrays.
fn series<'py, T: Sync, const N: usize>(
    py: Python<'py>,
    names: [&'static str; N],
    items: &[T],
    row: impl Fn(usize, &T) -> PyResult<[f64; N]> + Sync,
) -> PyResult<Bound<'py, PyDict>> {
    let row = &row;
    let columns = py.detach(|| columns(names, items, row))?;
    let dict = PyDict::new(py);
    columns.into_dict(&dict)?;
    Ok(dict)
}

/// The CCT in kelvin and Duv of a [`sky_core::cct::Cct`], NaN where there is none.
fn cct_columns(cct: Option<sky_core::cct::Cct>) -> (f64, f64) {
    cct.map_or((f64::NAN, f64::NAN), |c| {
        (f64::from(c.kelvin), f64::from(c.duv))
    })
}

const DAYLIGHT: [&str; 9] = [
    "global_illuminance",
    "diffuse_illuminance",
    "direct_illuminance",
    "direct_normal_illuminance",
    "x",
    "y",
    "cct",
    "duv",
    "melanopic_edi",
];

/// One row of the daylight's columns ([`DAYLIGHT`]).
fn daylight_row(day: &Daylight) -> [f64; 9] {
    let (x, y) = day.chromaticity();
    let (kelvin, duv) = cct_columns(day.cct());
    [
        f64::from(day.global().y),
        f64::from(day.diffuse().y),
        f64::from(day.direct().y),
        f64::from(day.direct_normal().y),
        f64::from(x),
        f64::from(y),
        kelvin,
        duv,
        f64::from(day.melanopic_edi()),
    ]
}

/// The clear-sky daylight at each of `times` (microseconds since 1970 UTC) at a site: the
/// Python package's `daylight`. The controller's clear sky there ([`Daylight::refracted`] with
/// [`controller::clear_atmosphere`]): the site's surface pressure, the ozone column, the sun's
/// beam refracted.
#[pyfunction]
#[pyo3(signature = (latitude, longitude, times, aod, elevation, ozone_du, algorithm, scalar))]
#[allow(clippy::too_many_arguments)] // the Python signature's keywords
pub(crate) fn daylight_series<'py>(
    py: Python<'py>,
    latitude: f64,
    longitude: f64,
    times: PyReadonlyArray1<'py, i64>,
    aod: PyReadonlyArray1<'py, f32>,
    elevation: f64,
    ozone_du: Option<f32>,
    algorithm: &str,
    scalar: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let site = time::site(latitude, longitude, elevation)?;
    let algorithm = time::algorithm(algorithm)?;
    let defaults = Settings::default();
    let settings = Settings {
        ozone_du: ozone_du.unwrap_or(defaults.ozone_du),
        ..defaults
    };
    // The site's atmosphere (its elevation and ozone) is checked once, before any time, and
    // its errors name the keyword as `controller_step`'s do.
    let site_atmosphere = controller::clear_atmosphere(&site, &settings);
    site_atmosphere.validate().map_err(|e| {
        let keyword = match e {
            SkyError::OutOfRange { parameter, .. } if parameter.starts_with("ozone") => "ozone_du",
            _ => "elevation",
        };
        value_error(keyword, e)
    })?;
    let times = elements(&times)?;
    let aod = Broadcast::new("aod", &aod, times.len())?;
    series(py, DAYLIGHT, &times, |i, &t| {
        let sun = time::sun_at(algorithm, t, &site, i, scalar)?;
        let day_of_year = time::utc_time(t, i, scalar)?.day_of_year();
        let atmosphere = ClearAtmosphere {
            aerosol_optical_depth: aod.at(i),
            ..site_atmosphere
        };
        let day = Daylight::refracted(&sun, &atmosphere)
            .map_err(|e| value_error(&aod.element(i), e))?
            .on_day(day_of_year);
        Ok(daylight_row(&day))
    })
}

/// The clear-sky daylight for each sun zenith angle of `sun_zenith` (radians): the Python
/// package's `daylight_at_sun`.
#[pyfunction]
#[pyo3(signature = (sun_zenith, aod, scalar))]
pub(crate) fn daylight_at_sun<'py>(
    py: Python<'py>,
    sun_zenith: PyReadonlyArray1<'py, f32>,
    aod: PyReadonlyArray1<'py, f32>,
    scalar: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let zenith = elements(&sun_zenith)?;
    let aod = Broadcast::new("aod", &aod, zenith.len())?;
    series(py, DAYLIGHT, &zenith, |i, &z| {
        let sun =
            Sun::new(z, 0.0).map_err(|e| value_error(&element("sun_zenith", i, scalar), e))?;
        let day = Daylight::new(sun, aod.at(i)).map_err(|e| value_error(&aod.element(i), e))?;
        Ok(daylight_row(&day))
    })
}

/// The sun's position at each of `times`: the Python package's `sun_position`.
#[pyfunction]
#[pyo3(signature = (latitude, longitude, times, elevation, algorithm, scalar))]
pub(crate) fn sun_position_series<'py>(
    py: Python<'py>,
    latitude: f64,
    longitude: f64,
    times: PyReadonlyArray1<'py, i64>,
    elevation: f64,
    algorithm: &str,
    scalar: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let site = time::site(latitude, longitude, elevation)?;
    let algorithm = time::algorithm(algorithm)?;
    let times = elements(&times)?;
    let names = [
        "zenith",
        "apparent_zenith",
        "elevation",
        "azimuth",
        "sun_zenith",
        "sun_azimuth",
    ];
    series(py, names, &times, |i, &t| {
        let p = time::sun_at(algorithm, t, &site, i, scalar)?;
        Ok([
            p.zenith_deg(),
            p.apparent_zenith_deg(),
            p.elevation_deg(),
            p.azimuth_deg(),
            f64::from(p.sun().zenith()),
            f64::from(p.sun().azimuth()),
        ])
    })
}

/// The followed light by name.
fn light(name: &str) -> PyResult<Light> {
    match name {
        "global" => Ok(Light::Global),
        "sky" => Ok(Light::Sky),
        other => Err(value_error(
            "light",
            format!("{other:?} is not \"global\" (sun and sky) or \"sky\" (the sky alone)"),
        )),
    }
}

/// The separation model by name; None: sky-core's default ([`Decomposition::default`]).
fn decomposition(name: Option<&str>) -> PyResult<Decomposition> {
    let Some(name) = name else {
        return Ok(Decomposition::default());
    };
    match name {
        "dirint" => Ok(Decomposition::Dirint),
        "dirindex" => Ok(Decomposition::Dirindex),
        "erbs" => Ok(Decomposition::Erbs),
        "engerer2" => Ok(Decomposition::Engerer2),
        "engerer2-global" => Ok(Decomposition::Engerer2Global),
        other => Err(value_error(
            "decomposition",
            format!(
                "{other:?} is not a separation model: \"dirint\" (Perez et al. 1992), \"dirindex\" \
                 (Perez et al. 2002), \"erbs\" (Erbs et al. 1982), \"engerer2\" (Engerer 2015) \
                 or \"engerer2-global\" (Bright & Engerer 2019, 1-minute)"
            ),
        )),
    }
}

/// The luminaire of four (x, y, lumens) channels, red, green, blue and white, or sky-core's
/// example RGBW luminaire.
fn luminaire(channels: Option<[(f32, f32, f32); 4]>) -> PyResult<Luminaire<4>> {
    let lamp = match channels {
        None => controller::example_luminaire(),
        Some(c) => {
            let ch = |(x, y, full_output): (f32, f32, f32)| Channel { x, y, full_output };
            Luminaire::rgbw(ch(c[0]), ch(c[1]), ch(c[2]), ch(c[3]))
        }
    };
    lamp.map_err(|e| value_error("luminaire", e))
}

/// What was measured at each time, from the keywords `lux`, `ghi` and `dhi`.
enum Readings {
    None,
    Lux(Broadcast),
    Global(Broadcast),
    GlobalDiffuse(Broadcast, Broadcast),
}

impl Readings {
    fn new(
        lux: Option<PyReadonlyArray1<'_, f32>>,
        ghi: Option<PyReadonlyArray1<'_, f32>>,
        dhi: Option<PyReadonlyArray1<'_, f32>>,
        n: usize,
    ) -> PyResult<Self> {
        Ok(match (lux, ghi, dhi) {
            (None, None, None) => Self::None,
            (Some(lux), None, None) => Self::Lux(Broadcast::new("lux", &lux, n)?),
            (None, Some(ghi), None) => Self::Global(Broadcast::new("ghi", &ghi, n)?),
            (None, Some(ghi), Some(dhi)) => Self::GlobalDiffuse(
                Broadcast::new("ghi", &ghi, n)?,
                Broadcast::new("dhi", &dhi, n)?,
            ),
            (None, None, Some(_)) => {
                return Err(value_error(
                    "dhi",
                    "a diffuse irradiance needs the global one (ghi) beside it",
                ));
            }
            (Some(_), Some(_), _) | (Some(_), None, Some(_)) => {
                return Err(value_error(
                    "lux",
                    "give an illuminance (lux) or irradiances (ghi, optionally dhi), not both",
                ));
            }
        })
    }

    /// The measurement at time `i`, and the names of its values for messages.
    fn at(&self, i: usize) -> (Option<Measurement>, String) {
        match self {
            Self::None => (None, String::new()),
            Self::Lux(l) => (Some(Measurement::GlobalIlluminance(l.at(i))), l.element(i)),
            Self::Global(g) => (Some(Measurement::GlobalIrradiance(g.at(i))), g.element(i)),
            Self::GlobalDiffuse(g, d) => (
                Some(Measurement::Irradiance {
                    global: g.at(i),
                    diffuse: d.at(i),
                }),
                format!("{}, {}", g.element(i), d.element(i)),
            ),
        }
    }
}

const STEP: [&str; 6] = ["illuminance", "x", "y", "cct", "duv", "melanopic_edi"];
const WEATHER: [&str; 8] = [
    "sky_type",
    "clear_sky_index",
    "overcast_fraction",
    "global_irradiance",
    "diffuse_irradiance",
    "direct_normal_irradiance",
    "clear_sky_illuminance",
    "diffuse_illuminance",
];

/// Every column of the controller's rows: [`STEP`], [`WEATHER`], the four drive levels and
/// whether the luminance was clipped (1 or 0).
const CONTROLLER: [&str; 19] = [
    "illuminance",
    "x",
    "y",
    "cct",
    "duv",
    "melanopic_edi",
    "sky_type",
    "clear_sky_index",
    "overcast_fraction",
    "global_irradiance",
    "diffuse_irradiance",
    "direct_normal_irradiance",
    "clear_sky_illuminance",
    "diffuse_illuminance",
    "level_red",
    "level_green",
    "level_blue",
    "level_white",
    "luminance_clipped",
];

/// One row of the step's columns ([`STEP`]).
fn step_row(s: &Step) -> [f64; 6] {
    let (x, y) = sky_core::daylight::chromaticity(s.illuminance);
    let (kelvin, duv) = cct_columns(s.cct);
    [
        f64::from(s.illuminance.y),
        f64::from(x),
        f64::from(y),
        kelvin,
        duv,
        f64::from(s.melanopic_edi),
    ]
}

/// One row of the measurement's columns ([`WEATHER`]): NaN without a measurement.
fn weather_row(s: &Step) -> [f64; 8] {
    s.weather.map_or([f64::NAN; 8], |w| {
        [
            f64::from(w.sky_type),
            w.clear_sky_index.map_or(f64::NAN, f64::from),
            f64::from(w.overcast_fraction),
            f64::from(w.global_irradiance),
            f64::from(w.diffuse_irradiance),
            f64::from(w.direct_normal_irradiance),
            f64::from(w.clear_sky.y),
            f64::from(w.diffuse_illuminance),
        ]
    })
}

/// The controller's step at each of `times`: the Python package's `controller_step`.
#[pyfunction]
#[pyo3(signature = (latitude, longitude, times, aod, elevation, ozone_du, precipitable_water,
                    algorithm, light, full_scale_lux, decomposition, lux, ghi, dhi, luminaire,
                    history, scalar))]
#[allow(clippy::too_many_arguments)] // the Python signature's keywords
pub(crate) fn controller_series<'py>(
    py: Python<'py>,
    latitude: f64,
    longitude: f64,
    times: PyReadonlyArray1<'py, i64>,
    aod: PyReadonlyArray1<'py, f32>,
    elevation: f64,
    ozone_du: Option<f32>,
    precipitable_water: Option<f32>,
    algorithm: &str,
    light: &str,
    full_scale_lux: f32,
    decomposition: Option<&str>,
    lux: Option<PyReadonlyArray1<'py, f32>>,
    ghi: Option<PyReadonlyArray1<'py, f32>>,
    dhi: Option<PyReadonlyArray1<'py, f32>>,
    luminaire: Option<[(f32, f32, f32); 4]>,
    history: bool,
    scalar: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let site = time::site(latitude, longitude, elevation)?;
    let times = elements(&times)?;
    if history && let Some(i) = (1..times.len()).find(|&i| times[i] <= times[i - 1]) {
        return Err(value_error(
            &element("times", i, scalar),
            format!(
                "{} is not after times[{}] = {} (history=True takes one sensor's readings in time order)",
                time::iso(times[i]),
                i - 1,
                time::iso(times[i - 1])
            ),
        ));
    }
    let aod = Broadcast::new("aod", &aod, times.len())?;
    let defaults = Settings::default();
    // sky-core counts water outside its range as the nearer end; a caller's value outside it
    // is an error here, as it is on the command line (`schedule --water-vapour`).
    let (dry, wettest) = sky_core::efficacy::PRECIPITABLE_WATER_RANGE_CM;
    let precipitable_water = match precipitable_water {
        None => defaults.precipitable_water,
        Some(w) if (dry..=wettest).contains(&w) => w,
        Some(w) => {
            return Err(value_error(
                "precipitable_water",
                format!("{w} cm is outside [{dry}, {wettest}] cm"),
            ));
        }
    };
    // Every field (a new one in sky-core is a compile error here, to be exposed or defaulted).
    let settings = Settings {
        aerosol_optical_depth: aod.at(0),
        ozone_du: ozone_du.unwrap_or(defaults.ozone_du),
        precipitable_water,
        light: self::light(light)?,
        full_scale_lux,
        sun: time::algorithm(algorithm)?,
        decomposition: self::decomposition(decomposition)?,
    };
    let lamp = self::luminaire(luminaire)?;
    let readings = Readings::new(lux, ghi, dhi, times.len())?;
    let measured = !matches!(readings, Readings::None);
    let one = |i: usize, t: i64, history: &mut Option<controller::History>| {
        let time = time::utc_time(t, i, scalar)?;
        let settings = Settings {
            aerosol_optical_depth: aod.at(i),
            ..settings
        };
        let (measurement, measured_names) = readings.at(i);
        let stepped = match history {
            Some(h) => {
                controller::step_with_history(&time, &site, &settings, &lamp, measurement, h)
            }
            None => controller::step(&time, &site, &settings, &lamp, measurement),
        };
        let s = stepped.map_err(|e| {
            // The step checks the settings, the sun's years, then the measurement.
            let context = match e {
                SkyError::OutOfRange { parameter, .. } if parameter.starts_with("aerosol") => {
                    aod.element(i)
                }
                SkyError::OutOfRange { parameter, .. } if parameter.starts_with("ozone") => {
                    "ozone_du".to_owned()
                }
                SkyError::OutOfRange { parameter, .. } if parameter.starts_with("full-scale") => {
                    "full_scale_lux".to_owned()
                }
                SkyError::OutOfRange { parameter, .. }
                    if parameter.starts_with("site elevation") =>
                {
                    "elevation".to_owned()
                }
                SkyError::OutOfRange { parameter, .. } if parameter.starts_with("year") => {
                    let hint = if settings.sun == SunAlgorithm::Fast {
                        " (algorithm=\"spa\" takes the years 1-2999)"
                    } else {
                        ""
                    };
                    let at = format!("{} = {}", element("times", i, scalar), time::iso(t));
                    return value_error(&at, format!("{e}{hint}"));
                }
                _ => measured_names.clone(),
            };
            value_error(&context, e)
        })?;
        let mut row = [0.0; CONTROLLER.len()];
        let (step, rest) = row.split_at_mut(STEP.len());
        let (weather, rest) = rest.split_at_mut(WEATHER.len());
        let (levels, clipped) = rest.split_at_mut(4);
        step.copy_from_slice(&step_row(&s));
        weather.copy_from_slice(&weather_row(&s));
        levels.copy_from_slice(&s.drive.levels.map(f64::from));
        clipped.fill(f64::from(u8::from(s.drive.luminance_clipped)));
        Ok(row)
    };
    let columns = py.detach(|| {
        if history {
            // One series in time order: each step after the one before, on this thread.
            let mut h = Some(controller::History::new());
            in_order(CONTROLLER, &times, |i, &t| one(i, t, &mut h))
        } else {
            columns(CONTROLLER, &times, |i, &t| one(i, t, &mut None))
        }
    })?;
    let dict = PyDict::new(py);
    let mut data = columns.data.into_iter();
    for name in STEP {
        dict.set_item(
            name,
            PyArray1::from_vec(py, data.next().unwrap_or_default()),
        )?;
    }
    for name in WEATHER {
        let column = data.next().unwrap_or_default();
        if measured {
            dict.set_item(name, PyArray1::from_vec(py, column))?;
        }
    }
    let levels: Vec<Vec<f64>> = data.by_ref().take(4).collect();
    let clipped: Vec<bool> = data
        .next()
        .unwrap_or_default()
        .into_iter()
        .map(|c| c != 0.0)
        .collect();
    let n = clipped.len();
    let mut interleaved = Vec::new();
    reserve(&mut interleaved, 4 * n)?;
    for k in 0..n {
        interleaved.extend(levels.iter().map(|c| c.get(k).copied().unwrap_or(f64::NAN)));
    }
    dict.set_item(
        "levels",
        PyArray1::from_vec(py, interleaved).reshape([n, 4])?,
    )?;
    dict.set_item("luminance_clipped", PyArray1::from_vec(py, clipped))?;
    Ok(dict)
}
