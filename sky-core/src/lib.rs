//! Sky models that run the same on a microcontroller, in a browser and on a workstation.
//!
//! `sky-core` is `#![no_std]`, never allocates, never panics on any input and contains no
//! `unsafe` code. Every model follows one pattern: a constructor validates the parameters and
//! precomputes everything that depends only on the sun and the atmosphere
//! ([`PreethamSky::new`] returns `Result<_, SkyError>`); evaluation per view direction is then
//! infallible and cheap.
//!
//! ```
//! use sky_core::{geom, PreethamSky, Sun};
//!
//! let sun = Sun::new(60f32.to_radians(), 0.0)?; // 30° above the horizon, azimuth 0
//! let sky = PreethamSky::new(sun, 3.0)?;        // turbidity 3: a clear day
//! let zenith = sky.xyy(geom::direction(0.0, 0.0));
//! assert!(zenith.luminance > 1000.0);            // cd/m²
//! let rgb = sky.rgb(geom::direction(80f32.to_radians(), 1.0)); // linear sRGB, cd/m² scale
//! assert!(rgb.min_element() > 0.0);
//! # Ok::<(), sky_core::SkyError>(())
//! ```
//!
//! # Conventions
//!
//! These hold for every model and every function in the crate.
//!
//! * **Angles** are in radians, `f32`.
//! * **Axes**: a right-handed frame with **+z up** (the zenith). When the frame is tied to the
//!   ground it is east-north-up: +x east, +y north.
//! * **Zenith angle** θ is measured from +z: 0 at the zenith, π/2 on the horizon, π at the nadir.
//! * **Azimuth** φ is measured in the horizontal plane from +x towards +y (counter-clockwise seen
//!   from above), so a unit direction is `(sin θ cos φ, sin θ sin φ, cos θ)`; see
//!   [`geom::direction`]. Only azimuth *differences* matter to the sky models.
//! * **Directions** are [`glam::Vec3`] unit vectors pointing *from* the viewer *towards* the sky.
//! * **Units**: luminance `Y` in cd/m²; linear sRGB triples are on the same scale (their `Y` is the
//!   luminance). Chromaticity `x, y` is CIE 1931. The AOAS sky is the exception: its linear RGB
//!   is in O'Neil's relative units, proportional to the sun's intensity parameter.
//! * **Below the horizon** every sky model's radiance (and luminance) is **0**: the ground, not
//!   the sky. One rule decides where that is, for every model, on the CPU (one direction and
//!   the `*_batch` paths) and in the generated GPU shaders (sky-gpu): a view direction is below
//!   the horizon when its unit vector's z is below −[`geom::HORIZON_TOLERANCE`] (1e-6, so that
//!   the f32 nearest π/2 still counts as the horizon); see [`geom::below_horizon`]. This holds
//!   for [`PreethamSky`], [`NeuralSky`] (and [`neural::FixedNeuralSky`]), [`sh::ShSky`]'s
//!   radiance, [`AoasSky`] (its viewer's horizon), [`CieSky`], [`PerezSky`] and
//!   [`daylight::DaylightSky`]. [`sh::ShSky::irradiance`] integrates the coefficients, not the
//!   evaluated radiance, and is not affected.
//!
//! # Models
//!
//! | model | type | source |
//! |---|---|---|
//! | Perez all-weather luminance distribution with Preetham's coefficients | [`PreethamSky`] | Perez et al. 1993; Preetham, Shirley, Smits 1999 (seed 002, eqs. 1-19) |
//! | neural sky: a 6-H-3 network (492 bytes of weights at H = 12) | [`NeuralSky`] | Satilmis et al., *A Machine Learning Driven Sky Model* (seed 000, eqs. 4-10) |
//! | spherical-harmonics lighting of the Preetham sky, from polynomial tables | [`sh::ShSky`] | Habel, Mustata, Wimmer 2008 (seed 001, eqs. 1-5); Ramamoorthi, Hanrahan 2001 |
//! | single-scattering skydome with aesthetic principles (AOAS) | [`AoasSky`] | seed 004, eqs. 1-8; O'Neil, "Accurate Atmospheric Scattering", GPU Gems 2 ch. 16 |
//! | the 15 CIE standard general skies, overcast to cloudless (relative luminance, scaled to a zenith luminance or a diffuse illuminance) | [`CieSky`] | ISO 15469:2004 / CIE S 011/E:2003 |
//! | the Perez all-weather sky driven by measured irradiance (sky clearness ε, brightness Δ) | [`PerezSky`] | Perez, Seals, Michalsky 1993; Perez et al. 1990 |
//!
//! ```
//! use sky_core::aoas::{AoasSky, Preset, Scattering, Style};
//!
//! let sky = AoasSky::new(&Scattering::default(), &Style::preset(Preset::Coral))?;
//! let rgb = sky.rgb(sky_core::Vec3::Z); // linear RGB, O'Neil's relative units
//! assert!(rgb.x > rgb.y && rgb.y > rgb.z); // a coral zenith
//! # Ok::<(), sky_core::SkyError>(())
//! ```
//!
//! # Lighting-controller outputs
//!
//! What a daylight-simulating luminaire needs every few seconds, without allocation:
//!
//! | what | where |
//! |---|---|
//! | the sun's position from UTC time and place (NREL SPA), as a [`Sun`] for any model | [`solar`] |
//! | zenith luminance, horizontal and tilted-plane illuminance (lux), mean colour over a cone of view | [`photometry::Photometry`] |
//! | correlated colour temperature and Duv (ANSI C78.377 sign) | [`cct`] |
//! | the daylight at any sun elevation, twilight and night included: global, diffuse and direct illuminance (lux), colour, melanopic EDI, the sun's light, the light on a window or tilted plane (the anisotropic sky) | [`daylight::Daylight`] |
//! | the clear sky's radiance per view direction from −18° to 90° (CIE XYZ, cd/m²), for rendering or a skylight panel's cone of view | [`daylight::DaylightSky`] |
//! | LED channel levels (RGB, RGBW, warm + cool white), hue-keeping gamut clipping, PWM quantisation | [`led`] |
//! | all of these for one time and place, as `sky-train schedule` and the firmware compute it, optionally driven by an outdoor sensor | [`controller::step`] |
//! | W/m² to lux (Perez 1990 global, diffuse and direct efficacy) | [`efficacy`] |
//! | a global reading split into diffuse and direct (DIRINT, Perez et al. 1992, the default; DIRINDEX, Perez et al. 2002; Erbs et al. 1982; Engerer2, Engerer 2015) | [`decomposition`] |
//! | the colour of daylight from clear to overcast (fitted to measured spectra, Balakrishnan 2019); the melanopic DER of daylight (CIE S 026) | [`overcast`] |
//! | clear periods in a GHI series (Reno & Hansen 2016); the site's clear-sky level learned from them | [`clear_period`], [`self_calibration`] |
//!
//! ```
//! use sky_core::solar::{Site, SunPosition, UtcTime};
//! use sky_core::daylight::Daylight;
//!
//! let site = Site::new(51.48, 0.0, 45.0)?;                       // Greenwich
//! let sun = SunPosition::new(&UtcTime::new(2026, 3, 20, 16, 0, 0.0)?, &site)?;
//! let day = Daylight::clear(sun.sun());
//! let e = day.global();                                          // XYZ, Y in lux
//! let cct = day.cct().expect("on the locus");
//! assert!(e.y > 1_000.0 && cct.kelvin > 3_000.0);
//! # Ok::<(), sky_core::SkyError>(())
//! ```
//!
//! # Features
//!
//! `sky-core` has no default features. Math goes through one private front: [`libm`] for what
//! is computed once per sky, and branch-free polynomial kernels (exp, atan2, 1/√x, √x; errors
//! of a few ulp, stated and tested) for what is computed per direction, so that loops over
//! directions vectorise. Fixed-capacity collections (AOAS cloud shapes) are [`heapless`]'s.
//! Results are identical, bit for bit, on every target (the firmware example checks this on a
//! Cortex-M4F).
//!
//! * **`micromath`** (off by default; enable it only in a final binary, such as firmware, never
//!   in a library): sin, cos, tan, atan2 and floor (run once per sky, and in [`geom`]'s
//!   angle conversions) come from the
//!   `micromath` crate instead of libm, for less flash (7.7 KB less in the Cortex-M4F firmware
//!   example) at a cost in accuracy, against the f64 references: Preetham 1.0e-2 relative per
//!   channel (libm: 4.3e-6), neural 1.7e-2 (libm: 8.2e-4), AOAS 1.1e-2 more than 10° from the
//!   sun but up to 0.53 within 2-10° of it (libm: 1.2e-4), held by `tests/tests/micromath.rs`.
//!   Per-direction code is the same in both builds.
//! * **`defmt`** (off by default): `defmt::Format` for the public errors, parameters and
//!   results ([`SkyError`], [`Sun`], [`color::Xyy`], [`cct::Cct`], [`solar::UtcTime`],
//!   [`solar::Site`], …), for firmware that logs with `defmt`; not for the sky states, which
//!   hold glam vectors. Additive: it changes no value.
//!
//! Parts without an FPU evaluate the neural sky in integers with
//! [`neural::FixedNeuralSky`] (the firmware checks it on a Cortex-M3 and a Cortex-M0).
//!
//! # Batch evaluation
//!
//! The `*_batch` methods evaluate slices of directions with the same results as the
//! one-direction methods; their loops compile to SIMD code for the build's target (SSE2 on
//! x86-64). A host program can compile them once more for a wider instruction set chosen at run
//! time, as `sky-train` does for AVX2.

#![no_std]
#![forbid(unsafe_code)]
#![warn(missing_docs)]

pub mod aoas;
pub mod cct;
pub mod cie;
pub mod clear_period;
pub mod color;
pub mod controller;
pub mod daylight;
pub mod decomposition;
pub mod efficacy;
mod error;
pub mod geom;
pub mod led;
mod math;
pub mod measurement;
pub mod neural;
pub mod overcast;
pub mod perez;
pub mod photometry;
pub mod preetham;
pub mod self_calibration;
pub mod sh;
pub mod solar;

pub use aoas::AoasSky;
pub use cie::CieSky;
pub use error::SkyError;
pub use geom::Sun;
pub use glam::Vec3;
pub use neural::NeuralSky;
pub use perez::PerezSky;
pub use photometry::Photometry;
pub use preetham::PreethamSky;
