//! sky-core's own values for the `skymodels` tests (sky-py/tests): reads a JSON list of cases on
//! stdin, computes each with sky-core directly (no Python, no binding), and prints a JSON list
//! of results in the same order. The tests compare the wheel's values with these, bit for bit.
//!
//! Inputs are JSON numbers (exact: serde_json's `float_roundtrip`; view directions as the bits of
//! their f32, so that NaN and infinities pass), times as calendar fields
//! (the tests derive them with Python's own `datetime`, the binding from microseconds since
//! 1970); f32 results are printed as their bits (`u32`), f64 results as theirs (`u64`). A case
//! that sky-core refuses gives `{"error": message}`.
//!
//! Each quantity is computed the way sky-core offers it for one direction or one time: the
//! model's own `rgb`, `xyz` or luminance per direction (not the batch paths the binding uses),
//! `controller::step`, `Daylight::new`, `SunAlgorithm::position`.

use std::io::Read;

use serde_json::{Value, json};
use sky_core::aoas::{AoasSky, DayCycle, Preset, Scattering};
use sky_core::controller::{self, Decomposition, Light, Measurement, Settings};
use sky_core::daylight::{self, ClearAtmosphere, Daylight};
use sky_core::geom::{self, Equirect, Extent};
use sky_core::led::{Channel, Luminaire};
use sky_core::neural::pretrained;
use sky_core::perez::SkyCondition;
use sky_core::sh::ShSky;
use sky_core::solar::{Site, SunAlgorithm, UtcTime};
use sky_core::{CieSky, NeuralSky, PerezSky, Photometry, PreethamSky, SkyError, Sun, Vec3, color};

/// A malformed case (the tests' fault, not sky-core's).
#[derive(Debug)]
struct BadCase(String);

type Outcome = Result<Result<Value, SkyError>, BadCase>;

fn num(case: &Value, key: &str) -> Result<f64, BadCase> {
    case.get(key)
        .and_then(Value::as_f64)
        .ok_or_else(|| BadCase(format!("{key}: a number is missing in {case}")))
}

#[allow(clippy::cast_possible_truncation)] // the tests send f32 values as exact f64
fn num32(case: &Value, key: &str) -> Result<f32, BadCase> {
    num(case, key).map(|v| v as f32)
}

fn text<'a>(case: &'a Value, key: &str) -> Result<&'a str, BadCase> {
    case.get(key)
        .and_then(Value::as_str)
        .ok_or_else(|| BadCase(format!("{key}: a string is missing in {case}")))
}

fn bits(v: f32) -> Value {
    json!(v.to_bits())
}

fn bits3(v: Vec3) -> Value {
    json!([v.x.to_bits(), v.y.to_bits(), v.z.to_bits()])
}

fn site(case: &Value) -> Result<Result<Site, SkyError>, BadCase> {
    Ok(Site::new(
        num(case, "latitude")?,
        num(case, "longitude")?,
        num(case, "elevation")?,
    ))
}

#[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)] // small whole numbers
fn time(case: &Value) -> Result<Result<UtcTime, SkyError>, BadCase> {
    let f = case
        .get("time")
        .and_then(Value::as_array)
        .filter(|f| f.len() == 6)
        .ok_or_else(|| BadCase(format!("time: six calendar fields are missing in {case}")))?;
    let n = |i: usize| f[i].as_f64().unwrap_or(f64::NAN);
    Ok(UtcTime::new(
        n(0) as i32,
        n(1) as u32,
        n(2) as u32,
        n(3) as u32,
        n(4) as u32,
        n(5),
    ))
}

fn algorithm(case: &Value) -> Result<SunAlgorithm, BadCase> {
    match text(case, "algorithm")? {
        "fast" => Ok(SunAlgorithm::Fast),
        "spa" => Ok(SunAlgorithm::Spa),
        other => Err(BadCase(format!("algorithm {other}"))),
    }
}

fn cct(c: Option<sky_core::cct::Cct>) -> (Value, Value) {
    c.map_or((Value::Null, Value::Null), |c| {
        (bits(c.kelvin), bits(c.duv))
    })
}

fn daylight_values(day: &Daylight) -> Value {
    let (x, y) = day.chromaticity();
    let (kelvin, duv) = cct(day.cct());
    json!({
        "global_illuminance": bits(day.global().y),
        "diffuse_illuminance": bits(day.diffuse().y),
        "direct_illuminance": bits(day.direct().y),
        "direct_normal_illuminance": bits(day.direct_normal().y),
        "x": bits(x),
        "y": bits(y),
        "cct": kelvin,
        "duv": duv,
        "melanopic_edi": bits(day.melanopic_edi()),
    })
}

/// The daylight at a site: its pressure (elevation), the ozone column (the default unless the
/// case gives one), the sun's beam refracted.
fn daylight_case(case: &Value) -> Outcome {
    let aod = num32(case, "aod")?;
    let ozone_du = if case["ozone_du"].is_null() {
        daylight::OZONE_DU
    } else {
        num32(case, "ozone_du")?
    };
    let algorithm = algorithm(case)?;
    let (site, time) = (site(case)?, time(case)?);
    Ok((|| {
        let (time, site) = (time?, site?);
        let sun = algorithm.position(&time, &site)?;
        #[allow(clippy::cast_possible_truncation)]
        let atmosphere = ClearAtmosphere {
            aerosol_optical_depth: aod,
            elevation_m: site.elevation() as f32,
            ozone_du,
        };
        Ok(daylight_values(
            &Daylight::refracted(&sun, &atmosphere)?.on_day(time.day_of_year()),
        ))
    })())
}

fn daylight_at_sun_case(case: &Value) -> Outcome {
    let (zenith, aod) = (num32(case, "sun_zenith")?, num32(case, "aod")?);
    Ok((|| {
        Ok(daylight_values(&Daylight::new(
            Sun::new(zenith, 0.0)?,
            aod,
        )?))
    })())
}

fn sun_case(case: &Value) -> Outcome {
    let algorithm = algorithm(case)?;
    let (site, time) = (site(case)?, time(case)?);
    Ok((|| {
        let p = algorithm.position(&time?, &site?)?;
        Ok(json!({
            "zenith": p.zenith_deg().to_bits(),
            "apparent_zenith": p.apparent_zenith_deg().to_bits(),
            "elevation": p.elevation_deg().to_bits(),
            "azimuth": p.azimuth_deg().to_bits(),
            "sun_zenith": bits(p.sun().zenith()),
            "sun_azimuth": bits(p.sun().azimuth()),
        }))
    })())
}

/// The series' histories: a `step` case with `"history": name` is a step of that series, after
/// the cases of the same name before it (`controller::step_with_history`).
type Histories = std::collections::HashMap<String, controller::History>;

fn step_case(case: &Value, histories: &mut Histories) -> Outcome {
    let light = match text(case, "light")? {
        "global" => Light::Global,
        "sky" => Light::Sky,
        other => return Err(BadCase(format!("light {other}"))),
    };
    let decomposition = match case["decomposition"].as_str() {
        None => Decomposition::default(),
        Some("dirint") => Decomposition::Dirint,
        Some("dirindex") => Decomposition::Dirindex,
        Some("erbs") => Decomposition::Erbs,
        Some("engerer2") => Decomposition::Engerer2,
        Some("engerer2-global") => Decomposition::Engerer2Global,
        Some(other) => return Err(BadCase(format!("decomposition {other}"))),
    };
    let defaults = Settings::default();
    let or_default = |key: &str, default: f32| {
        if case[key].is_null() {
            Ok(default)
        } else {
            num32(case, key)
        }
    };
    let settings = Settings {
        aerosol_optical_depth: num32(case, "aod")?,
        ozone_du: or_default("ozone_du", defaults.ozone_du)?,
        precipitable_water: or_default("precipitable_water", defaults.precipitable_water)?,
        light,
        full_scale_lux: num32(case, "full_scale_lux")?,
        sun: algorithm(case)?,
        decomposition,
    };
    let m = &case["measurement"];
    let measurement = if m.is_null() {
        None
    } else if m.get("lux").is_some() {
        Some(Measurement::GlobalIlluminance(num32(m, "lux")?))
    } else if m.get("dhi").is_some() {
        Some(Measurement::Irradiance {
            global: num32(m, "ghi")?,
            diffuse: num32(m, "dhi")?,
        })
    } else {
        Some(Measurement::GlobalIrradiance(num32(m, "ghi")?))
    };
    let lamp = match case["luminaire"].as_array() {
        None => controller::example_luminaire(),
        Some(c) if c.len() == 4 => {
            let ch = |v: &Value| -> Result<Channel, BadCase> {
                let f = |i: usize| {
                    v.get(i)
                        .and_then(Value::as_f64)
                        .map(|x| x as f32)
                        .ok_or_else(|| BadCase(format!("luminaire channel {v}")))
                };
                Ok(Channel {
                    x: f(0)?,
                    y: f(1)?,
                    full_output: f(2)?,
                })
            };
            Luminaire::rgbw(ch(&c[0])?, ch(&c[1])?, ch(&c[2])?, ch(&c[3])?)
        }
        Some(_) => return Err(BadCase("luminaire: four channels".to_owned())),
    };
    let (site, time) = (site(case)?, time(case)?);
    Ok((|| {
        let (time, site, lamp) = (time?, site?, lamp?);
        let s = match case["history"].as_str() {
            Some(name) => controller::step_with_history(
                &time,
                &site,
                &settings,
                &lamp,
                measurement,
                histories.entry(name.to_owned()).or_default(),
            )?,
            None => controller::step(&time, &site, &settings, &lamp, measurement)?,
        };
        let (x, y) = daylight::chromaticity(s.illuminance);
        let (kelvin, duv) = cct(s.cct);
        let mut out = json!({
            "illuminance": bits(s.illuminance.y),
            "x": bits(x),
            "y": bits(y),
            "cct": kelvin,
            "duv": duv,
            "melanopic_edi": bits(s.melanopic_edi),
            "levels": s.drive.levels.map(f32::to_bits).to_vec(),
            "luminance_clipped": s.drive.luminance_clipped,
        });
        if let Some(w) = s.weather {
            let fields = [
                ("sky_type", json!(w.sky_type)),
                (
                    "clear_sky_index",
                    w.clear_sky_index.map_or(Value::Null, bits),
                ),
                ("overcast_fraction", bits(w.overcast_fraction)),
                ("global_irradiance", bits(w.global_irradiance)),
                ("diffuse_irradiance", bits(w.diffuse_irradiance)),
                ("direct_normal_irradiance", bits(w.direct_normal_irradiance)),
                ("clear_sky_illuminance", bits(w.clear_sky.y)),
                ("diffuse_illuminance", bits(w.diffuse_illuminance)),
            ];
            for (k, v) in fields {
                out[k] = v;
            }
        }
        Ok(out)
    })())
}

/// A sky of any model, with its per-direction functions (one per case: its size is no matter).
#[allow(clippy::large_enum_variant)]
enum Model {
    Preetham(PreethamSky),
    Neural(NeuralSky),
    Daylight(sky_core::daylight::DaylightSky),
    Cie(CieSky),
    Perez(PerezSky),
    Aoas(Box<AoasSky>),
    Sh(Box<ShSky>),
}

impl Model {
    /// The model `case["model"]` with the parameters of `case`, as the binding's constructors
    /// take them.
    fn new(case: &Value) -> Result<Result<Self, SkyError>, BadCase> {
        let z = num32(case, "sun_zenith")?;
        let a = num32(case, "sun_azimuth")?;
        let chromaticity = |sky_x: &Value| -> Result<Option<(f32, f32)>, BadCase> {
            match sky_x.as_array() {
                None => Ok(None),
                Some(c) => Ok(Some((
                    c.first().and_then(Value::as_f64).unwrap_or(f64::NAN) as f32,
                    c.get(1).and_then(Value::as_f64).unwrap_or(f64::NAN) as f32,
                ))),
            }
        };
        let model = text(case, "model")?;
        let params: Box<dyn FnOnce(Sun) -> Result<Self, SkyError>> = match model {
            "preetham" => {
                let t = num32(case, "turbidity")?;
                Box::new(move |sun| Ok(Self::Preetham(PreethamSky::new(sun, t)?)))
            }
            "neural" => {
                let t = num32(case, "turbidity")?;
                let weights = match text(case, "weights")? {
                    "preetham" => &pretrained::PREETHAM,
                    "hosek" => &pretrained::HOSEK,
                    other => return Err(BadCase(format!("weights {other}"))),
                };
                Box::new(move |sun| Ok(Self::Neural(NeuralSky::new(weights, sun, t)?)))
            }
            "daylight" => {
                let aod = num32(case, "aod")?;
                Box::new(move |sun| Ok(Self::Daylight(Daylight::new(sun, aod)?.sky())))
            }
            "cie" => {
                #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
                let sky_type = num(case, "sky_type")? as u8;
                let scale = num32(case, "zenith_luminance");
                let diffuse = num32(case, "diffuse_illuminance");
                let colour = chromaticity(&case["chromaticity"])?;
                Box::new(move |sun| {
                    let sky = match (scale, diffuse) {
                        (Ok(l), _) => CieSky::new(sky_type, sun, l)?,
                        (_, Ok(e)) => CieSky::from_diffuse_illuminance(sky_type, sun, e)?,
                        _ => CieSky::new(sky_type, sun, f32::NAN)?,
                    };
                    Ok(Self::Cie(match colour {
                        Some((x, y)) => sky.with_chromaticity(x, y)?,
                        None => sky,
                    }))
                })
            }
            "perez" => {
                let (eps, delta) = (num32(case, "clearness")?, num32(case, "brightness")?);
                let e = num32(case, "diffuse_illuminance")?;
                Box::new(move |sun| {
                    let c = SkyCondition::new(eps, delta)?;
                    Ok(Self::Perez(PerezSky::new(sun, c, e)?))
                })
            }
            "perez_from_irradiance" => {
                let (ghi, dhi) = (num32(case, "ghi")?, num32(case, "dhi")?);
                #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
                let day = num(case, "day_of_year")? as u32;
                Box::new(move |sun| {
                    let reading = Measurement::Irradiance {
                        global: ghi,
                        diffuse: dhi,
                    }
                    .read(sun.zenith(), day)?;
                    Ok(Self::Perez(PerezSky::from_reading(sun, &reading)?))
                })
            }
            "aoas" => {
                let preset = Preset::from_name(text(case, "preset")?)
                    .ok_or_else(|| BadCase(format!("preset in {case}")))?;
                Box::new(move |sun| {
                    let mut style = preset.style();
                    style.day_cycle = DayCycle::Sun(sun);
                    Ok(Self::Aoas(Box::new(AoasSky::new(
                        &Scattering::default(),
                        &style,
                    )?)))
                })
            }
            "sh" => {
                let t = num32(case, "turbidity")?;
                #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
                let bands = num(case, "bands")? as usize;
                Box::new(move |sun| Ok(Self::Sh(Box::new(ShSky::new(sun, t, bands)?))))
            }
            other => return Err(BadCase(format!("model {other}"))),
        };
        Ok(Sun::new(z, a).and_then(params))
    }

    /// `quantity` towards `d` by the model's own one-direction function.
    fn value(&self, quantity: &str, d: Vec3) -> Result<Value, BadCase> {
        Ok(match (quantity, self) {
            ("rgb", Self::Preetham(s)) => bits3(s.rgb(d)),
            ("rgb", Self::Neural(s)) => bits3(s.rgb(d)),
            ("rgb", Self::Daylight(s)) => bits3(s.rgb(d)),
            ("rgb", Self::Aoas(s)) => bits3(s.rgb(d)),
            ("rgb", Self::Sh(s)) => bits3(s.radiance(d)),
            ("rgb", Self::Cie(s)) => bits3(color::xyz_to_linear_srgb(s.xyz(d))),
            ("rgb", Self::Perez(s)) => bits3(color::xyz_to_linear_srgb(s.xyz(d))),
            ("xyz", Self::Preetham(s)) => bits3(s.xyz(d)),
            ("xyz", Self::Neural(s)) => bits3(Photometry::xyz(s, d)),
            ("xyz", Self::Daylight(s)) => bits3(s.xyz(d)),
            ("xyz", Self::Cie(s)) => bits3(Photometry::xyz(s, d)),
            ("xyz", Self::Perez(s)) => bits3(Photometry::xyz(s, d)),
            ("luminance", Self::Preetham(s)) => bits(s.xyy(d).luminance),
            ("luminance", Self::Neural(s)) => bits(Photometry::xyz(s, d).y),
            ("luminance", Self::Daylight(s)) => bits(s.xyz(d).y),
            ("luminance", Self::Cie(s)) => bits(s.luminance(d)),
            ("luminance", Self::Perez(s)) => bits(s.luminance(d)),
            (q, _) => return Err(BadCase(format!("quantity {q} of this model"))),
        })
    }
}

/// A direction given as the bits of its three f32 (so that NaN and infinities pass JSON).
#[allow(clippy::cast_possible_truncation)] // u32 bits
fn dir(v: &Value) -> Result<Vec3, BadCase> {
    let c = |i: usize| {
        v.get(i)
            .and_then(Value::as_u64)
            .map(|b| f32::from_bits(b as u32))
            .ok_or_else(|| BadCase(format!("direction {v}")))
    };
    Ok(Vec3::new(c(0)?, c(1)?, c(2)?))
}

fn sky_case(case: &Value) -> Outcome {
    let quantity = text(case, "quantity")?;
    let dirs = case["dir_bits"]
        .as_array()
        .ok_or_else(|| BadCase("dir_bits".to_owned()))?
        .iter()
        .map(dir)
        .collect::<Result<Vec<_>, _>>()?;
    let model = match Model::new(case)? {
        Ok(m) => m,
        Err(e) => return Ok(Err(e)),
    };
    let values = dirs
        .iter()
        .map(|d| model.value(quantity, *d))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(Ok(json!({ "values": values })))
}

#[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)] // image sizes
fn render_case(case: &Value) -> Outcome {
    let quantity = text(case, "quantity")?;
    let (width, height) = (num(case, "width")? as u32, num(case, "height")? as u32);
    let extent = match text(case, "extent")? {
        "upper" => Extent::UpperHemisphere,
        "sphere" => Extent::Sphere,
        other => return Err(BadCase(format!("extent {other}"))),
    };
    let model = match Model::new(case)? {
        Ok(m) => m,
        Err(e) => return Ok(Err(e)),
    };
    let grid = match Equirect::new(width, height, extent) {
        Ok(g) => g,
        Err(e) => return Ok(Err(e)),
    };
    let mut values = Vec::new();
    for j in 0..height {
        for i in 0..width {
            values.push(model.value(quantity, grid.direction(i, j))?);
        }
    }
    Ok(Ok(json!({ "values": values })))
}

fn direction_case(case: &Value) -> Outcome {
    let d = geom::direction(num32(case, "zenith")?, num32(case, "azimuth")?);
    Ok(Ok(bits3(d)))
}

/// The physical atmosphere's cases (`physical_irradiance`, `physical_daylight`,
/// `physical_radiance`): the atmosphere of the case's parameters (sky-train's defaults for those
/// missing) at the coarse resolution, no cache; spectra as the bits of their f64.
#[cfg(feature = "physical")]
fn physical_case(case: &Value, kind: &str) -> Outcome {
    use sky_train::physical::{Atmosphere, cache};
    let d = Atmosphere::default();
    let get = |k: &str, default: f64| case.get(k).and_then(Value::as_f64).unwrap_or(default);
    let atmosphere = Atmosphere {
        aod_550: get("aod", d.aod_550),
        angstrom: get("angstrom", d.angstrom),
        aerosol_ssa: get("aerosol_ssa", d.aerosol_ssa),
        aerosol_g: get("aerosol_g", d.aerosol_g),
        aerosol_scale_height_m: get("aerosol_scale_height", d.aerosol_scale_height_m),
        ozone_du: get("ozone_du", d.ozone_du),
        ground_albedo: get("albedo", d.ground_albedo),
        site_elevation_m: get("elevation", d.site_elevation_m),
    };
    let atm = cache::load_or_build_in(&atmosphere, &cache::small_resolution(), None, false)
        .map_err(|e| BadCase(format!("atmosphere: {e:#}")))?;
    let sky = atm
        .sky(
            num(case, "sun_zenith")?.to_degrees(),
            num(case, "sun_azimuth")?.to_degrees(),
        )
        .map_err(|e| BadCase(format!("sun: {e:?}")))?;
    let bits = |s: &[f64]| s.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    Ok(Ok(match kind {
        "physical_irradiance" => {
            let e = sky.irradiance();
            json!({
                "global": bits(&e.global),
                "diffuse": bits(&e.diffuse),
                "direct_horizontal": bits(&e.direct_horizontal),
                "direct_normal": bits(&e.direct_normal),
            })
        }
        "physical_daylight" => {
            let d = sky.daylight();
            let (kelvin, duv) = d.global.cct_duv.unwrap_or((f64::NAN, f64::NAN));
            json!({
                "global_illuminance": d.global.xyz[1].to_bits(),
                "diffuse_illuminance": d.diffuse.xyz[1].to_bits(),
                "direct_illuminance": d.direct.xyz[1].to_bits(),
                "x": d.global.xy.0.to_bits(),
                "y": d.global.xy.1.to_bits(),
                "cct": kelvin.to_bits(),
                "duv": duv.to_bits(),
                "melanopic_edi": d.global.melanopic_edi.to_bits(),
            })
        }
        _ => {
            let dirs = case["dirs"]
                .as_array()
                .ok_or_else(|| BadCase("dirs".to_owned()))?
                .iter()
                .map(|d| {
                    let c = |i: usize| d.get(i).and_then(Value::as_f64).unwrap_or(f64::NAN);
                    bits(&sky.spectral_radiance([c(0), c(1), c(2)]))
                })
                .collect::<Vec<_>>();
            json!({ "values": dirs })
        }
    }))
}

fn run(case: &Value, histories: &mut Histories) -> Result<Value, BadCase> {
    let outcome = match text(case, "kind")? {
        "daylight" => daylight_case(case)?,
        "daylight_at_sun" => daylight_at_sun_case(case)?,
        "sun" => sun_case(case)?,
        "step" => step_case(case, histories)?,
        "sky" => sky_case(case)?,
        "render" => render_case(case)?,
        "direction" => direction_case(case)?,
        #[cfg(feature = "physical")]
        kind @ ("physical_irradiance" | "physical_daylight" | "physical_radiance") => {
            physical_case(case, kind)?
        }
        other => return Err(BadCase(format!("kind {other}"))),
    };
    Ok(outcome.unwrap_or_else(|e| json!({ "error": e.to_string() })))
}

fn main() -> Result<(), String> {
    let mut input = String::new();
    std::io::stdin()
        .read_to_string(&mut input)
        .map_err(|e| format!("stdin: {e}"))?;
    let cases: Vec<Value> = serde_json::from_str(&input).map_err(|e| format!("stdin: {e}"))?;
    let mut histories = Histories::new();
    let results = cases
        .iter()
        .map(|c| run(c, &mut histories))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|BadCase(e)| format!("bad case: {e}"))?;
    println!("{}", Value::Array(results));
    Ok(())
}
