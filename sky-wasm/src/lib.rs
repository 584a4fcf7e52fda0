//! sky-core for browsers, through wasm-bindgen.
//!
//! Two classes reach JavaScript (TypeScript types come out of the build):
//!
//! * [`Sky`]: one sky of any sky-core model, built once from its parameters (a constructor per
//!   model; errors become JavaScript exceptions carrying sky-core's message), then evaluated per
//!   direction with [`Sky::rgb`].
//! * [`Renderer`]: a fisheye dome or a panorama of a given size, whose pixel directions are
//!   computed once; each frame is one call that writes the whole image into a caller-provided
//!   `Uint8ClampedArray` (8-bit sRGB, for a canvas's `ImageData`) or `Float32Array` (linear
//!   RGB), so no pixel crosses between JavaScript and WebAssembly on its own.
//!
//! ```js
//! import init, { Sky, Renderer } from "./pkg/sky_wasm.js";
//! await init();
//! const sky = Sky.preetham(60 * Math.PI / 180, 0, 3);      // sun zenith, azimuth (rad), turbidity
//! const dome = Renderer.fisheye(512, 512);
//! const image = new ImageData(512, 512);
//! dome.renderSrgb(sky, image.data, sky.autoExposure());    // one call per frame
//! canvas.getContext("2d").putImageData(image, 0, 0);
//! ```
//!
//! Units and axes are sky-core's: radians, +z up, azimuth from +x (east) towards +y (north);
//! linear RGB in cd/m² for the Preetham, neural and daylight skies, O'Neil's relative units for
//! AOAS.
//! The values are sky-core's, bit for bit: the same code compiled for wasm32 (the wasm-bindgen
//! tests in `tests/wasm.rs` check every model against the native build to 1e-6 relative).
//!
//! # Features
//!
//! Each model is a feature, so that a page's build can leave out the models it does not draw
//! (the .wasm's size per build: `docs/browser.md`, "Size"); all are on by default.
//!
//! | feature | what it adds |
//! |---|---|
//! | `preetham` | [`Sky::preetham`] |
//! | `neural` | [`Sky::neural`] (both shipped weight sets) |
//! | `neural-file` | [`Sky::neural_from_bytes`] (a weight file: sky-core's decoder; needs `neural`) |
//! | `aoas` | [`Sky::aoas`], [`Sky::aoas_with_sun`], [`aoas_presets`] |
//! | `sh` | [`Sky::sh`], [`Sky::sh_unfiltered`], [`Sky::irradiance`], [`Renderer::sphere`] |
//! | `daylight` | [`Sky::daylight`] and the optical depth range (`daylightMinAod`, ...) |
//! | `daylight-day` | `DaylightDay` (the day's daylight) and the optical depth range |
//! | `sun-position` | `SunPosition` (NREL's SPA) |
//!
//! A build needs at least one model (`preetham`, `neural`, `aoas`, `sh` or `daylight`).

#[cfg(not(any(
    feature = "preetham",
    feature = "neural",
    feature = "aoas",
    feature = "sh",
    feature = "daylight"
)))]
compile_error!("sky-wasm needs at least one model feature: preetham, neural, aoas, sh or daylight");

#[cfg(any(feature = "daylight", feature = "daylight-day"))]
pub mod daylight;
pub mod number;
pub mod projection;
pub mod srgb8;

#[cfg(feature = "neural")]
use sky_core::NeuralSky;
#[cfg(feature = "preetham")]
use sky_core::PreethamSky;
#[cfg(feature = "aoas")]
use sky_core::aoas::{AoasSky, DayCycle, Preset, Scattering, Style};
#[cfg(feature = "daylight")]
use sky_core::daylight::{Daylight, DaylightSky};
#[cfg(feature = "neural")]
use sky_core::neural::{NeuralWeights, pretrained};
#[cfg(feature = "sh")]
use sky_core::sh::ShSky;
#[cfg(feature = "sun-position")]
use sky_core::solar;
use sky_core::{Sun, Vec3, color, geom};
use wasm_bindgen::prelude::*;

use projection::{Kind, Projection};
use srgb8::Srgb8;

/// Directions evaluated together: a multiple of every sky-core batch width (8 and 32).
const CHUNK: usize = 256;

/// The mean luminance automatic exposure maps to (middle grey), as `sky-train render` does.
const MIDDLE_GREY: f32 = 0.18;

/// Side of the fisheye whose pixels (equal solid angles) average the sky for
/// [`Sky::auto_exposure`]: 32 × 32 gives 812 directions.
const EXPOSURE_GRID: u32 = 32;

use number::{js_error, push_decimal};

/// The allocator of the .wasm: lol_alloc's free list (first fit; a freed block merges with its
/// free neighbours), about 1 KB of code where std's dlmalloc takes 5 KB (docs/browser.md,
/// "Size"). The pages allocate a few buffers per image and per sky, never per pixel.
#[cfg(target_arch = "wasm32")]
#[global_allocator]
static ALLOCATOR: lol_alloc::LockedAllocator<lol_alloc::FreeListAllocator> =
    lol_alloc::LockedAllocator::new(lol_alloc::FreeListAllocator::new());

/// The model behind a [`Sky`].
// One per JavaScript `Sky`: 424 bytes are nothing to save; the AOAS sky (its style holds up to 64
// cloud segments) is boxed.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone)]
enum Model {
    #[cfg(feature = "preetham")]
    Preetham(PreethamSky),
    #[cfg(feature = "neural")]
    Neural(NeuralSky),
    #[cfg(feature = "aoas")]
    Aoas(Box<AoasSky>),
    #[cfg(feature = "sh")]
    Sh(Box<ShSky>),
    #[cfg(feature = "daylight")]
    Daylight(Box<DaylightSky>),
}

// Not inlined: each call site would hold its own copy of every model's kernels (the .wasm
// has a 200 KB budget); a call per direction or per chunk of 256 costs nothing measurable.
impl Model {
    /// One direction through [`rgb_batch`](Self::rgb_batch): every sky-core batch gives its
    /// model's `rgb` bit for bit, and a second copy of the kernels would cost 8 KB of .wasm.
    fn rgb(&self, dir: Vec3) -> Vec3 {
        let mut out = [Vec3::ZERO];
        self.rgb_batch(&[dir], &mut out);
        out[0]
    }

    #[inline(never)]
    fn rgb_batch(&self, dirs: &[Vec3], out: &mut [Vec3]) {
        match self {
            #[cfg(feature = "preetham")]
            Self::Preetham(s) => s.rgb_batch(dirs, out),
            #[cfg(feature = "neural")]
            Self::Neural(s) => s.rgb_batch(dirs, out),
            #[cfg(feature = "aoas")]
            Self::Aoas(s) => s.rgb_batch(dirs, out),
            #[cfg(feature = "sh")]
            Self::Sh(s) => {
                for (o, d) in out.iter_mut().zip(dirs) {
                    *o = s.radiance(*d);
                }
            }
            #[cfg(feature = "daylight")]
            Self::Daylight(s) => s.rgb_batch(dirs, out),
        }
    }
}

/// A sky of one of sky-core's models, for one sun (and turbidity or style).
#[wasm_bindgen]
#[derive(Debug, Clone)]
pub struct Sky {
    model: Model,
    sun: Sun,
}

#[wasm_bindgen]
impl Sky {
    #[cfg(feature = "preetham")]
    /// The Preetham sky (Perez distribution with Preetham's coefficients) for a sun at
    /// `sun_zenith` in [0, π/2] and `sun_azimuth` (radians) and `turbidity` in [2, 6].
    ///
    /// # Errors
    /// sky-core's message for a parameter out of range.
    pub fn preetham(sun_zenith: f32, sun_azimuth: f32, turbidity: f32) -> Result<Sky, JsError> {
        let sun = Sun::new(sun_zenith, sun_azimuth).map_err(js_error)?;
        let sky = PreethamSky::new(sun, turbidity).map_err(js_error)?;
        Ok(Self {
            model: Model::Preetham(sky),
            sun,
        })
    }

    #[cfg(feature = "neural")]
    /// The neural sky with the shipped weights `weights` ("preetham": trained on the Preetham
    /// sky, turbidity 2-6; "hosek": on the Hosek-Wilkie sky, turbidity 1-10), for a sun at
    /// `sun_zenith` in [0, π/2] and `sun_azimuth` (radians) and `turbidity`.
    ///
    /// # Errors
    /// An unknown weights name, or sky-core's message for a parameter out of the trained range.
    pub fn neural(
        weights: &str,
        sun_zenith: f32,
        sun_azimuth: f32,
        turbidity: f32,
    ) -> Result<Sky, JsError> {
        let weights = match weights {
            "preetham" => &pretrained::PREETHAM,
            "hosek" => &pretrained::HOSEK,
            other => {
                return Err(JsError::new(
                    &[
                        "weights = \"",
                        other,
                        "\" is not a shipped neural sky (\"preetham\" or \"hosek\")",
                    ]
                    .concat(),
                ));
            }
        };
        Self::neural_with(weights, sun_zenith, sun_azimuth, turbidity)
    }

    #[cfg(feature = "neural-file")]
    /// The neural sky of a weight file (sky-core's format, as `sky-train train` writes it) for
    /// a sun at `sun_zenith` and `sun_azimuth` (radians) and `turbidity`.
    ///
    /// # Errors
    /// sky-core's message for a malformed file or a parameter out of the trained range.
    #[wasm_bindgen(js_name = neuralFromBytes)]
    pub fn neural_from_bytes(
        bytes: &[u8],
        sun_zenith: f32,
        sun_azimuth: f32,
        turbidity: f32,
    ) -> Result<Sky, JsError> {
        let weights = NeuralWeights::<12>::decode(bytes).map_err(number::weights_error)?;
        Self::neural_with(&weights, sun_zenith, sun_azimuth, turbidity)
    }

    #[cfg(feature = "neural")]
    fn neural_with(
        weights: &NeuralWeights,
        sun_zenith: f32,
        sun_azimuth: f32,
        turbidity: f32,
    ) -> Result<Sky, JsError> {
        let sun = Sun::new(sun_zenith, sun_azimuth).map_err(js_error)?;
        let sky = NeuralSky::new(weights, sun, turbidity).map_err(js_error)?;
        Ok(Self {
            model: Model::Neural(sky),
            sun,
        })
    }

    #[cfg(feature = "aoas")]
    /// The AOAS sky (O'Neil's single scattering with seed 004's aesthetic principles) of the
    /// style preset `preset` (see [`aoas_presets`]), with the preset's own sun.
    ///
    /// # Errors
    /// An unknown preset name.
    pub fn aoas(preset: &str) -> Result<Sky, JsError> {
        Self::aoas_sky(&Self::preset(preset)?)
    }

    #[cfg(feature = "aoas")]
    /// The AOAS sky of the style preset `preset` with the sun moved to `sun_zenith` in
    /// [0, π/2] and `sun_azimuth` (radians).
    ///
    /// # Errors
    /// An unknown preset name, or sky-core's message for a sun out of range.
    #[wasm_bindgen(js_name = aoasWithSun)]
    pub fn aoas_with_sun(preset: &str, sun_zenith: f32, sun_azimuth: f32) -> Result<Sky, JsError> {
        let mut style = Self::preset(preset)?;
        style.day_cycle = DayCycle::Sun(Sun::new(sun_zenith, sun_azimuth).map_err(js_error)?);
        Self::aoas_sky(&style)
    }

    #[cfg(feature = "aoas")]
    fn preset(name: &str) -> Result<Style, JsError> {
        Preset::from_name(name).map(Preset::style).ok_or_else(|| {
            JsError::new(
                &[
                    "preset = \"",
                    name,
                    "\" is not an AOAS style preset (one of: ",
                    &aoas_presets().join(", "),
                    ")",
                ]
                .concat(),
            )
        })
    }

    #[cfg(feature = "aoas")]
    fn aoas_sky(style: &Style) -> Result<Sky, JsError> {
        let sky = AoasSky::new(&Scattering::default(), style).map_err(js_error)?;
        Ok(Self {
            sun: sky.sun(),
            model: Model::Aoas(Box::new(sky)),
        })
    }

    #[cfg(feature = "sh")]
    /// The spherical-harmonics lighting of the Preetham sky (seed 001: polynomial tables in sun
    /// zenith and turbidity, ringing filter, rotation to the sun's azimuth) with `bands` bands
    /// (1 to 7), for a sun at `sun_zenith` in [0, π/2] and `sun_azimuth` (radians) and
    /// `turbidity` in the tables' range [2.5, 6]. Its `rgb` is the SH radiance; a sphere lit by
    /// it is drawn by [`Renderer::sphere`].
    ///
    /// # Errors
    /// sky-core's message for a parameter out of range.
    pub fn sh(
        sun_zenith: f32,
        sun_azimuth: f32,
        turbidity: f32,
        bands: u32,
    ) -> Result<Sky, JsError> {
        let sun = Sun::new(sun_zenith, sun_azimuth).map_err(js_error)?;
        let sky = ShSky::new(sun, turbidity, bands as usize).map_err(js_error)?;
        Ok(Self {
            model: Model::Sh(Box::new(sky)),
            sun,
        })
    }

    #[cfg(feature = "sh")]
    /// The spherical-harmonics lighting of [`sh`](Self::sh) without the ringing filter of
    /// seed 001, eq. 5: the plain fitted coefficients, whose first three bands are the
    /// radiance coefficients a three.js `LightProbe` takes (its irradiance needs no filter).
    ///
    /// # Errors
    /// sky-core's message for a parameter out of range.
    #[wasm_bindgen(js_name = shUnfiltered)]
    pub fn sh_unfiltered(
        sun_zenith: f32,
        sun_azimuth: f32,
        turbidity: f32,
        bands: u32,
    ) -> Result<Sky, JsError> {
        let sun = Sun::new(sun_zenith, sun_azimuth).map_err(js_error)?;
        let sky = ShSky::new_unfiltered(sun, turbidity, bands as usize).map_err(js_error)?;
        Ok(Self {
            model: Model::Sh(Box::new(sky)),
            sun,
        })
    }

    #[cfg(feature = "daylight")]
    /// The sky of sky-core's clear-sky daylight (the physical atmosphere's radiance through
    /// three neural networks, `DaylightSky`) for a sun at `sun_zenith` in [0, π] (below the
    /// horizon too: twilight; beyond 108°, the sun 18° down, it draws the 108° sky) and
    /// `sun_azimuth` (radians), under an atmosphere of aerosol optical depth `aod` at 550 nm
    /// ([`daylight_min_aod`](daylight::daylight_min_aod) to
    /// [`daylight_max_aod`](daylight::daylight_max_aod)). Its `rgb` is linear sRGB in cd/m²;
    /// a channel may be negative in deep twilight (outside the sRGB gamut), which the 8-bit
    /// images clamp to 0. Zero below the horizon.
    ///
    /// # Errors
    /// sky-core's message for a parameter out of range.
    pub fn daylight(sun_zenith: f32, sun_azimuth: f32, aod: f32) -> Result<Sky, JsError> {
        let sun = Sun::new(sun_zenith, sun_azimuth).map_err(js_error)?;
        let light = Daylight::new(sun, aod).map_err(js_error)?;
        Ok(Self {
            model: Model::Daylight(Box::new(light.sky())),
            sun,
        })
    }

    /// The parameters of this sky's GPU shader (sky-gpu; the texts are the package's
    /// `shaders.js`, per [`model`](Self::model)): the uniform array `sky_<model>` as 4 floats
    /// per `vec4`. For an SH sky, the RGB coefficient c_lm is at `4 (l² + l + m)`; for a
    /// daylight sky, its one or two networks folded for the sun and the aerosol optical depth,
    /// their blend weights and the diffuse illuminance of sky-core's tables (so a new sun or
    /// optical depth is new parameters, never a new shader).
    ///
    /// # Errors
    /// An AOAS style with cloud noise, cloud shapes or ambiguity (the shader has none).
    #[wasm_bindgen(js_name = shaderParams)]
    #[cfg_attr(
        not(any(
            feature = "preetham",
            feature = "neural",
            feature = "aoas",
            feature = "sh"
        )),
        allow(unused_imports, unreachable_code) // the daylight sky alone: no shader
    )]
    pub fn shader_params(&self) -> Result<Vec<f32>, JsError> {
        use sky_gpu::models;
        Ok(match &self.model {
            #[cfg(feature = "preetham")]
            Model::Preetham(s) => models::preetham::params(s).to_vec(),
            #[cfg(feature = "neural")]
            Model::Neural(s) => models::neural::params(s),
            #[cfg(feature = "aoas")]
            Model::Aoas(s) => models::aoas::params(s)
                .map_err(|e| JsError::new(e.0))?
                .to_vec(),
            #[cfg(feature = "sh")]
            Model::Sh(s) => models::sh::params(s).to_vec(),
            #[cfg(feature = "daylight")]
            Model::Daylight(s) => models::daylight::params(s),
        })
    }

    #[cfg(feature = "sh")]
    /// The irradiance of an SH sky on a surface whose normal has zenith angle `normal_zenith`
    /// and azimuth `normal_azimuth` (radians): sky-core's `ShSky::irradiance`, linear sRGB on
    /// the sky's radiance scale times steradians (lux scale for Preetham).
    ///
    /// # Errors
    /// A sky that is not an SH sky.
    pub fn irradiance(&self, normal_zenith: f32, normal_azimuth: f32) -> Result<Vec<f32>, JsError> {
        #[allow(unreachable_patterns)] // a build with the SH sky alone
        match &self.model {
            Model::Sh(s) => Ok(s
                .irradiance(geom::direction(normal_zenith, normal_azimuth))
                .to_array()
                .to_vec()),
            _ => Err(JsError::new(
                "irradiance is defined for SH skies (Sky.sh, Sky.shUnfiltered)",
            )),
        }
    }

    /// The model's name: "preetham", "neural", "aoas", "sh" or "daylight".
    #[wasm_bindgen(getter)]
    #[must_use]
    pub fn model(&self) -> String {
        match self.model {
            #[cfg(feature = "preetham")]
            Model::Preetham(_) => "preetham",
            #[cfg(feature = "neural")]
            Model::Neural(_) => "neural",
            #[cfg(feature = "aoas")]
            Model::Aoas(_) => "aoas",
            #[cfg(feature = "sh")]
            Model::Sh(_) => "sh",
            #[cfg(feature = "daylight")]
            Model::Daylight(_) => "daylight",
        }
        .into()
    }

    /// The sun's zenith angle in radians.
    #[wasm_bindgen(getter, js_name = sunZenith)]
    #[must_use]
    pub fn sun_zenith(&self) -> f32 {
        self.sun.zenith()
    }

    /// The sun's azimuth in radians.
    #[wasm_bindgen(getter, js_name = sunAzimuth)]
    #[must_use]
    pub fn sun_azimuth(&self) -> f32 {
        self.sun.azimuth()
    }

    /// Linear RGB `[r, g, b]` towards the view direction with zenith angle `view_zenith` and
    /// azimuth `view_azimuth` (radians), in the model's units; exactly sky-core's `rgb` of
    /// `geom::direction(view_zenith, view_azimuth)`.
    #[must_use]
    pub fn rgb(&self, view_zenith: f32, view_azimuth: f32) -> Vec<f32> {
        self.model
            .rgb(geom::direction(view_zenith, view_azimuth))
            .to_array()
            .to_vec()
    }

    /// Linear RGB at many view directions: `dirs` holds x, y, z per direction (sky-core's
    /// frame, +z up; any length), the result r, g, b per direction in the model's units
    /// (sky-core's `rgb_batch`, the values [`rgb`](Self::rgb) gives). A trailing partial
    /// triple is ignored.
    #[wasm_bindgen(js_name = rgbBatch)]
    #[must_use]
    pub fn rgb_batch(&self, dirs: &[f32]) -> Vec<f32> {
        let dirs: Vec<Vec3> = dirs
            .chunks_exact(3)
            .map(|d| Vec3::new(d[0], d[1], d[2]))
            .collect();
        let mut rgb = vec![Vec3::ZERO; dirs.len()];
        self.model.rgb_batch(&dirs, &mut rgb);
        rgb.iter().flat_map(|c| c.to_array()).collect()
    }

    /// The exposure (a factor on linear RGB) that maps this sky's mean luminance over the upper
    /// hemisphere to middle grey (0.18), as `sky-train render` exposes PNGs; 1 for a black sky.
    #[wasm_bindgen(js_name = autoExposure)]
    #[must_use]
    pub fn auto_exposure(&self) -> f32 {
        let Ok(grid) = Projection::new(Kind::Fisheye, EXPOSURE_GRID, EXPOSURE_GRID) else {
            return 1.0;
        };
        let mut rgb = vec![Vec3::ZERO; grid.directions().len()];
        self.model.rgb_batch(grid.directions(), &mut rgb);
        let sum: f32 = rgb.iter().map(|&c| color::luminance(c)).sum();
        #[allow(clippy::cast_precision_loss)] // below 2^24
        let mean = sum / rgb.len() as f32;
        if mean > 0.0 && mean.is_finite() {
            MIDDLE_GREY / mean
        } else {
            1.0
        }
    }
}

#[cfg(feature = "aoas")]
/// The AOAS style presets' names, in the order of the gallery's strip (`sky-train gallery`, docs/aoas_presets.png).
#[wasm_bindgen(js_name = aoasPresets)]
#[must_use]
pub fn aoas_presets() -> Vec<String> {
    Preset::ALL.iter().map(|p| p.name().to_owned()).collect()
}

#[cfg(feature = "sun-position")]
/// The sun's position at a UTC date and time seen from a place on the Earth: sky-core's
/// [`solar`] (NREL's Solar Position Algorithm, within 0.01° of pvlib's).
///
/// ```js
/// const p = SunPosition.at(2026, 6, 21, 11, 0, 0, 48.21, 16.37, 190); // Vienna, summer noon
/// const sky = Sky.preetham(p.zenith, p.azimuth, 3);                  // radians, as the skies take
/// console.log(p.elevationDeg, p.compassAzimuthDeg);                  // ≈ 65°, ≈ 180° (south)
/// ```
#[wasm_bindgen]
#[derive(Debug, Clone, Copy)]
pub struct SunPosition {
    position: solar::SunPosition,
}

#[cfg(feature = "sun-position")]
#[wasm_bindgen]
impl SunPosition {
    /// The sun at `year-month-day hour:minute:second` UTC (years 1-2999; `second` in [0, 60))
    /// seen from `latitude` (degrees, −90 to 90, north positive), `longitude` (degrees, −180 to
    /// 180, east positive) and `elevation` (metres above sea level, −500 to 10 000).
    ///
    /// # Errors
    /// A field outside its range, named with the range in the message.
    #[allow(clippy::too_many_arguments)] // the fields of a date, a time and a place
    pub fn at(
        year: i32,
        month: u32,
        day: u32,
        hour: u32,
        minute: u32,
        second: f64,
        latitude: f64,
        longitude: f64,
        elevation: f64,
    ) -> Result<SunPosition, JsError> {
        let time = solar::UtcTime::new(year, month, day, hour, minute, second).map_err(js_error)?;
        let site = solar::Site::new(latitude, longitude, elevation).map_err(js_error)?;
        let position = solar::SunPosition::new(&time, &site).map_err(js_error)?;
        Ok(Self { position })
    }

    /// The geometric zenith angle in radians, [0, π] (what the [`Sky`] constructors take; the
    /// sun is below the horizon above π/2).
    #[wasm_bindgen(getter)]
    #[must_use]
    pub fn zenith(&self) -> f32 {
        self.position.sun().zenith()
    }

    /// The azimuth in radians in sky-core's convention: from +x (east) towards +y (north).
    #[wasm_bindgen(getter)]
    #[must_use]
    pub fn azimuth(&self) -> f32 {
        self.position.sun().azimuth()
    }

    /// The geometric elevation above the horizon in degrees, 90 − zenith.
    #[wasm_bindgen(getter, js_name = elevationDeg)]
    #[must_use]
    pub fn elevation_deg(&self) -> f64 {
        self.position.elevation_deg()
    }

    /// The compass azimuth in degrees: from north, clockwise (east 90), in [0, 360).
    #[wasm_bindgen(getter, js_name = compassAzimuthDeg)]
    #[must_use]
    pub fn compass_azimuth_deg(&self) -> f64 {
        self.position.azimuth_deg()
    }
}

/// An image of the sky (a fisheye dome or a panorama) of a fixed size; renders any [`Sky`].
///
/// The image is computed into buffers inside the WebAssembly memory and copied into the
/// caller's typed array once per call.
#[wasm_bindgen]
#[derive(Debug, Clone)]
pub struct Renderer {
    projection: Projection,
    table: Srgb8,
    /// RGBA bytes of the last sRGB frame; pixels outside the projection stay 0.
    srgb: Vec<u8>,
    /// RGB floats of the last linear frame; pixels outside the projection stay 0.
    linear: Vec<f32>,
}

#[wasm_bindgen]
impl Renderer {
    /// A `width` × `height` fisheye of the upper hemisphere: the disc inscribed in the image,
    /// seen from below (zenith in the centre, north up, east left), Lambert's equal-area
    /// projection (every pixel covers the same solid angle). Pixels outside the disc are
    /// transparent black.
    ///
    /// # Errors
    /// A width or height of 0 or above 4096.
    pub fn fisheye(width: u32, height: u32) -> Result<Renderer, JsError> {
        Self::new(Kind::Fisheye, width, height)
    }

    /// A `width` × `height` panorama of the upper hemisphere: azimuth 0 to 2π from left to
    /// right, the zenith along the top row and the horizon along the bottom.
    ///
    /// # Errors
    /// A width or height of 0 or above 4096.
    pub fn panorama(width: u32, height: u32) -> Result<Renderer, JsError> {
        Self::new(Kind::Panorama, width, height)
    }

    #[cfg(feature = "sh")]
    /// A `size` × `size` image of a white diffuse sphere (albedo 1) lit by an SH sky
    /// ([`Sky::sh`]), seen from the south looking north: east right, the zenith up. Each pixel
    /// is the sphere's radiance E(n)/π for its normal n, with E sky-core's SH irradiance
    /// (seed 001's clamped-cosine convolution), on the sky's radiance scale. Pixels off the
    /// sphere are transparent black.
    ///
    /// # Errors
    /// A size of 0 or above 4096.
    pub fn sphere(size: u32) -> Result<Renderer, JsError> {
        Self::new(Kind::Sphere, size, size)
    }

    fn new(kind: Kind, width: u32, height: u32) -> Result<Renderer, JsError> {
        let projection = Projection::new(kind, width, height).map_err(js_error)?;
        let n = projection.pixel_count();
        Ok(Self {
            projection,
            table: Srgb8::new(),
            srgb: vec![0; n * 4],
            linear: Vec::new(),
        })
    }

    /// Image width in pixels.
    #[wasm_bindgen(getter)]
    #[must_use]
    pub fn width(&self) -> u32 {
        self.projection.size().0
    }

    /// Image height in pixels.
    #[wasm_bindgen(getter)]
    #[must_use]
    pub fn height(&self) -> u32 {
        self.projection.size().1
    }

    fn check_len(&self, len: u32, per_pixel: usize, what: &str) -> Result<(), JsError> {
        let want = self.projection.pixel_count() * per_pixel;
        if len as usize == want {
            return Ok(());
        }
        // The message by hand: `format!` would link core::fmt's integer formatting.
        let mut text = String::from(what);
        let numbers = [
            (" has length ", len as usize),
            (", but a ", self.width() as usize),
            ("x", self.height() as usize),
            (" image needs ", want),
            (" (", per_pixel),
        ];
        for (words, n) in numbers {
            text.push_str(words);
            push_decimal(&mut text, n);
        }
        text.push_str(" per pixel)");
        Err(JsError::new(&text))
    }

    /// Renders `sky` as 8-bit sRGB RGBA into `out` (a `Uint8ClampedArray` of width × height × 4
    /// bytes, row-major, such as a canvas `ImageData`'s `data`), after multiplying linear RGB by
    /// `exposure` (see [`Sky::auto_exposure`]). Values above 1 clip to white.
    ///
    /// # Errors
    /// `out` of the wrong length.
    #[wasm_bindgen(js_name = renderSrgb)]
    pub fn render_srgb(
        &mut self,
        sky: &Sky,
        out: &js_sys::Uint8ClampedArray,
        exposure: f32,
    ) -> Result<(), JsError> {
        self.check_len(out.length(), 4, "out")?;
        #[allow(unreachable_patterns)] // a build with the SH sky alone
        let source = match (&sky.model, self.projection.kind()) {
            #[cfg(feature = "sh")]
            (Model::Sh(sh), Kind::Sphere) => Source::LitSphere(sh),
            (_, Kind::Sphere) => {
                return Err(JsError::new(
                    "the sphere is lit by a spherical-harmonics sky: build it with Sky.sh",
                ));
            }
            _ => Source::Sky(&sky.model),
        };
        self.fill_srgb(&source, exposure);
        out.copy_from(&self.srgb);
        Ok(())
    }

    /// Renders |`a` − `b`| per channel (linear) times `exposure` as 8-bit sRGB RGBA into `out`
    /// (as [`render_srgb`](Self::render_srgb)): black where the two skies agree.
    ///
    /// # Errors
    /// `out` of the wrong length.
    #[wasm_bindgen(js_name = renderDifferenceSrgb)]
    pub fn render_difference_srgb(
        &mut self,
        a: &Sky,
        b: &Sky,
        out: &js_sys::Uint8ClampedArray,
        exposure: f32,
    ) -> Result<(), JsError> {
        self.check_len(out.length(), 4, "out")?;
        self.fill_srgb(&Source::Difference(&a.model, &b.model), exposure);
        out.copy_from(&self.srgb);
        Ok(())
    }

    /// Renders `sky` as linear RGB into `out` (a `Float32Array` of width × height × 3 floats,
    /// row-major, the model's units); pixels outside the fisheye's disc are 0.
    ///
    /// # Errors
    /// `out` of the wrong length.
    #[wasm_bindgen(js_name = renderLinear)]
    pub fn render_linear(&mut self, sky: &Sky, out: &js_sys::Float32Array) -> Result<(), JsError> {
        self.check_len(out.length(), 3, "out")?;
        self.linear.resize(self.projection.pixel_count() * 3, 0.0);
        let mut rgb = [Vec3::ZERO; CHUNK];
        let p = &self.projection;
        for (dirs, pixels) in p.directions().chunks(CHUNK).zip(p.pixels().chunks(CHUNK)) {
            let rgb = &mut rgb[..dirs.len()];
            sky.model.rgb_batch(dirs, rgb);
            for (c, &pixel) in rgb.iter().zip(pixels) {
                let at = pixel as usize * 3;
                if let Some(px) = self.linear.get_mut(at..at + 3) {
                    px.copy_from_slice(&c.to_array());
                }
            }
        }
        out.copy_from(&self.linear);
        Ok(())
    }
}

/// What a frame of [`Renderer`] shows per pixel.
enum Source<'a> {
    /// The sky's radiance.
    Sky(&'a Model),
    /// |a − b| per channel.
    Difference(&'a Model, &'a Model),
    /// A white diffuse sphere's radiance, E(n)/π, lit by the SH sky.
    #[cfg(feature = "sh")]
    LitSphere(&'a ShSky),
}

impl Renderer {
    /// The 8-bit sRGB RGBA frame of `source` × `exposure` in `self.srgb`: one copy of the
    /// loop for every source (the .wasm has a size budget; the match per chunk of 256 pixels
    /// costs nothing measurable).
    #[inline(never)]
    fn fill_srgb(&mut self, source: &Source, exposure: f32) {
        let (mut rgb, mut other) = ([Vec3::ZERO; CHUNK], [Vec3::ZERO; CHUNK]);
        let p = &self.projection;
        for (dirs, pixels) in p.directions().chunks(CHUNK).zip(p.pixels().chunks(CHUNK)) {
            let rgb = &mut rgb[..dirs.len()];
            match source {
                Source::Sky(m) => m.rgb_batch(dirs, rgb),
                Source::Difference(a, b) => {
                    let other = &mut other[..dirs.len()];
                    a.rgb_batch(dirs, rgb);
                    b.rgb_batch(dirs, other);
                    for (x, y) in rgb.iter_mut().zip(other.iter()) {
                        *x = (*x - *y).abs();
                    }
                }
                #[cfg(feature = "sh")]
                Source::LitSphere(sh) => {
                    for (o, n) in rgb.iter_mut().zip(dirs) {
                        *o = sh.irradiance(*n) * core::f32::consts::FRAC_1_PI;
                    }
                }
            }
            write_srgb(&self.table, &mut self.srgb, pixels, rgb, exposure);
        }
    }
}

/// Writes the 8-bit sRGB RGBA of `rgb` × `exposure` at `pixels` in `out` (at most [`CHUNK`]
/// pixels): the table keys of all channels first, in a loop that vectorises, then the lookups.
#[inline(always)]
fn write_srgb(table: &Srgb8, out: &mut [u8], pixels: &[u32], rgb: &[Vec3], exposure: f32) {
    let mut keys = [[0u32; 3]; CHUNK];
    for (k, c) in keys.iter_mut().zip(rgb) {
        let c = *c * exposure;
        *k = [Srgb8::key(c.x), Srgb8::key(c.y), Srgb8::key(c.z)];
    }
    for (k, &pixel) in keys.iter().zip(pixels) {
        let at = pixel as usize * 4;
        if let Some(px) = out.get_mut(at..at + 4) {
            px.copy_from_slice(&[table.code(k[0]), table.code(k[1]), table.code(k[2]), 255]);
        }
    }
}
