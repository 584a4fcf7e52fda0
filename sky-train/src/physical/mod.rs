//! A physically based, spectral, multiple-scattering model of the clear atmosphere (f64, host):
//! the reference for daylight that sky-core's compact daylight models are distilled from and
//! that is itself validated against the measured clear-sky record (docs/daylight.md).
//!
//! - [`constituents`]: the planet's shell, air (Bodhaine et al. 1999 Rayleigh cross-sections,
//!   US Standard Atmosphere 1976), ozone (Serdyuchenko/Gorshelev 2014 cross-sections, a layer
//!   peaking at 25 km), aerosol (Ångström law, single-scattering albedo, Henyey-Greenstein);
//! - [`solar`]: ASTM G-173-03's extraterrestrial spectrum, the Earth-Sun distance, the disc;
//! - [`atmosphere`]: the parameters, the presets (the clear-sky record's, the default, and
//!   today's clean sky) and Preetham's turbidity as aerosol optical depth;
//! - [`transport`]: Bruneton-style precomputed scattering orders, vectorised over 47
//!   wavelength bins (360-830 nm);
//! - [`sky`]: [`PhysicalAtmosphere`] (the precomputed tables) and [`PhysicalSky`] (one sun:
//!   radiance per direction, irradiance, the sun's transmitted spectrum);
//! - [`photometry`]: CIE 1931 XYZ, CCT/Duv, melanopic EDI (CIE S 026:2018);
//! - [`cache`]: the tables on disk;
//! - [`montecarlo`]: a brute-force path tracer in the same shell, to check the tables.
//!
//! Geometry is geometric (no refraction): the sun's elevation is its geometric elevation, as
//! `sky-train schedule` prints it.
//!
//! ```no_run
//! use sky_train::physical::{Atmosphere, Resolution, cache};
//! let atm = cache::load_or_build(&Atmosphere::default(), &Resolution::default(),
//!     Some(&cache::default_dir()), true)?;
//! let sky = atm.sky(60.0, 0.0)?; // sun 30° above the horizon
//! let daylight = sky.daylight();
//! println!("{:.0} lx", daylight.global.xyz[1]);
//! # Ok::<(), anyhow::Error>(())
//! ```

pub mod atmosphere;
pub mod cache;
pub mod constituents;
pub mod grid;
pub mod montecarlo;
pub mod photometry;
pub mod record;
pub mod sky;
pub mod solar;
pub mod spectra;
pub mod transport;

pub use atmosphere::{Atmosphere, AtmosphereError};
pub use sky::{Daylight, Irradiance, PhysicalAtmosphere, PhysicalSky, SunError};
pub use transport::Resolution;
