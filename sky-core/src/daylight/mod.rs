//! The daylight at a time and place: global, diffuse and direct horizontal illuminance with
//! their colour, the melanopic EDI, the sun's direct normal light and the light on a tilted
//! plane, from the sun's elevation −18° to 90° and the aerosol optical depth, distilled from
//! sky-train's spectral, multiple-scattering physical atmosphere (`docs/daylight.md`).
//!
//! Three parts, each chosen by its error and its bytes (`docs/daylight.md`, "The sky-core
//! model"):
//!
//! * **The diffuse light** (the sky's): ln X, ln Y, ln Z and ln melanopic EDI against the sun
//!   elevation at the reference's own sun-angle nodes (5° by day, 2° at dusk, 0.5° through
//!   twilight, −18° to 90°: 73 nodes) and against the aerosol optical depth τ₅₅₀ at 0.05, 0.1,
//!   0.2, 0.4 and 0.8 (linear in elevation, quadratic in ln τ₅₅₀), plus the site's terms:
//!   (P / P₀ − 1) times the sensitivity of ln E to the surface pressure (per optical depth and
//!   sun node, from the reference at 3,000 m) and (O₃ − 300 DU) / 100 DU times its sensitivity
//!   to the ozone column (per sun node); all as 16-bit integers (6.4 KB).
//! * **The direct beam** (the sun's): Beer-Lambert's law per 10 nm bin, 360-830 nm, with the
//!   reference's vertical Rayleigh, aerosol and ozone optical depths and its relative air
//!   masses on its own coordinate x = √(sin h) (256 nodes; spherical Earth, no refraction),
//!   times the visible fraction of the sun's disc (its 959.63″ radius: a half disc at h = 0°,
//!   none below −0.27°). Exact in τ₅₅₀, the ozone column and the pressure (the Rayleigh depth
//!   scales with it); 4.4 KB.
//! * **The sky on vertical planes** ([`Daylight::tilted`]): ln of the sky's X, Y, Z on a vertical
//!   plane over the diffuse horizontal X, Y, Z, against the sun elevation (the reference's nodes
//!   from −6° to 90°, every 2° below), the same optical depths and the plane's azimuth from the
//!   sun's (0° to 180°, 30° apart), 16-bit; 11.8 KB.
//!
//! The tables hold the reference's default constituents (Ångström exponent, aerosol albedo and
//! asymmetry, 1 AU, ground albedo [`GROUND_ALBEDO`]); a site's clear atmosphere
//! ([`ClearAtmosphere`]) sets the aerosol optical depth ([`MIN_AOD`] to [`MAX_AOD`], default
//! [`DEFAULT_AOD`], sky-train's `Atmosphere::default()` when the tables were generated), the
//! site's elevation (its surface pressure, [`ELEVATION_RANGE_M`]) and the ozone column
//! ([`OZONE_RANGE_DU`], default [`OZONE_DU`]). Below −18° (astronomical night) every quantity
//! keeps its −18° value.
//!
//! The reference's sun is geometric (no refraction), as [`Daylight::with_atmosphere`] gives it;
//! [`Daylight::refracted`] takes the beam from the sun's apparent position instead, the light a
//! sensor on the ground sees (the controller's clear sky).
//!
//! Error against the reference at elevations and optical depths between the nodes
//! (`tests/tests/daylight.rs`): illuminance within 2 % from 0° to 90° and 5 % from −12° to 0°,
//! chromaticity within 0.002, melanopic EDI within 2 %; at held-out site elevations and ozone
//! columns the bounds `docs/daylight.md` states.
//!
//! ```
//! use sky_core::daylight::Daylight;
//! use sky_core::Sun;
//!
//! let noon = Daylight::clear(Sun::new(30f32.to_radians(), 0.0)?);
//! assert!(noon.global().y > 70_000.0 && noon.global().y < 120_000.0); // lux
//! assert!(noon.direct().y > noon.diffuse().y);
//! let dusk = Daylight::clear(Sun::new(94f32.to_radians(), 0.0)?); // sun 4° below
//! assert_eq!(dusk.direct().y, 0.0);
//! let c = dusk.cct().expect("on the locus at -4 deg");
//! assert!(c.kelvin > 10_000.0); // the blue hour
//! # Ok::<(), sky_core::SkyError>(())
//! ```

mod plane_tables;
mod sky;
mod tables;

pub use sky::{BLENDS, DaylightSky, HIDDEN, MAX_SUN_ZENITH};

use glam::Vec3;

use crate::cct::{self, Cct};
use crate::error::SkyError;
use crate::geom::Sun;
use crate::math;
use crate::solar::SunPosition;

/// The smallest aerosol optical depth at 550 nm of the tables.
pub const MIN_AOD: f32 = tables::AOD[0];
/// The largest aerosol optical depth at 550 nm of the tables.
pub const MAX_AOD: f32 = tables::AOD[tables::AOD.len() - 1];
/// The default atmosphere's aerosol optical depth at 550 nm ([`Daylight::clear`]).
pub const DEFAULT_AOD: f32 = tables::DEFAULT_AOD;
/// The ozone column of the tables' nodes, Dobson units: the default.
pub const OZONE_DU: f32 = tables::OZONE_DU;
/// The site elevations [`ClearAtmosphere`] takes, m (their surface pressure is the US Standard
/// Atmosphere 1976's: 1.06 to 0.54 of sea level's).
pub const ELEVATION_RANGE_M: (f32, f32) = (-500.0, 5000.0);
/// The ozone columns [`ClearAtmosphere`] takes, Dobson units.
pub const OZONE_RANGE_DU: (f32, f32) = (200.0, 500.0);
/// The ground's Lambertian albedo of the tables (the diffuse light includes its reflection
/// back from the sky; [`Daylight::tilted`] adds its reflection onto a tilted plane).
pub const GROUND_ALBEDO: f32 = tables::GROUND_ALBEDO;
/// The lowest sun elevation tabulated, degrees (the end of astronomical twilight); lower suns
/// give its values.
pub const LOWEST_ELEVATION_DEG: f32 = tables::ELEVATION_DEG[0];
/// The largest |Duv| at which [`Daylight::cct`] reports a colour temperature (nautical twilight
/// leaves the locus).
pub const MAX_DUV: f32 = 0.05;

/// A site's clear atmosphere: what the daylight tables take besides the sun.
///
/// ```
/// use sky_core::daylight::{ClearAtmosphere, Daylight};
/// use sky_core::Sun;
///
/// let sun = Sun::new(40f32.to_radians(), 0.0)?;
/// // Alamosa, Colorado (2,317 m) in January: a clean, thin atmosphere.
/// let site = ClearAtmosphere { aerosol_optical_depth: 0.06, elevation_m: 2317.0, ozone_du: 310.0 };
/// let high = Daylight::with_atmosphere(sun, &site)?;
/// let sea = Daylight::with_atmosphere(sun, &ClearAtmosphere { elevation_m: 0.0, ..site })?;
/// assert!(high.direct().y > sea.direct().y && high.diffuse().y < sea.diffuse().y);
/// # Ok::<(), sky_core::SkyError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClearAtmosphere {
    /// Aerosol optical depth at 550 nm ([`MIN_AOD`] to [`MAX_AOD`]).
    pub aerosol_optical_depth: f32,
    /// The site's elevation above sea level, m ([`ELEVATION_RANGE_M`]): its surface pressure
    /// ([`Self::pressure_ratio`]) scales the air's share of the light.
    pub elevation_m: f32,
    /// Total ozone column, Dobson units ([`OZONE_RANGE_DU`]).
    pub ozone_du: f32,
}

impl Default for ClearAtmosphere {
    /// The default atmosphere: [`DEFAULT_AOD`] at sea level, [`OZONE_DU`].
    fn default() -> Self {
        Self {
            aerosol_optical_depth: DEFAULT_AOD,
            elevation_m: 0.0,
            ozone_du: OZONE_DU,
        }
    }
}

impl ClearAtmosphere {
    /// The surface pressure over sea level's, P / P₀, at [`Self::elevation_m`]: the US
    /// Standard Atmosphere 1976's troposphere, (T / T₀)^(g₀ M / R L) with T = T₀ − L H,
    /// T₀ = 288.15 K, L = 6.5 K/km, exponent 5.25588, H the geopotential height
    /// r₀ z / (r₀ + z), r₀ = 6,356.766 km.
    #[must_use]
    pub fn pressure_ratio(&self) -> f32 {
        let z = self.elevation_m;
        let h = 6_356_766.0 * z / (6_356_766.0 + z);
        math::exp_libm(5.255_88 * math::ln(1.0 - 6.5e-3 / 288.15 * h))
    }

    /// Checks every parameter against its range (NaN is out of range).
    ///
    /// # Errors
    /// [`SkyError::OutOfRange`] naming the first parameter out of its range.
    pub fn validate(&self) -> Result<(), SkyError> {
        let check = |parameter, value: f32, (min, max): (f32, f32)| {
            if (min..=max).contains(&value) {
                Ok(())
            } else {
                Err(SkyError::OutOfRange {
                    parameter,
                    value,
                    min,
                    max,
                })
            }
        };
        check(
            "aerosol optical depth",
            self.aerosol_optical_depth,
            (MIN_AOD, MAX_AOD),
        )?;
        check("site elevation [m]", self.elevation_m, ELEVATION_RANGE_M)?;
        check("ozone column [DU]", self.ozone_du, OZONE_RANGE_DU)
    }
}

/// The clear-sky daylight for one sun position and atmosphere (module docs). All illuminances
/// are CIE 1931 X, Y, Z in lux (Y is the illuminance), melanopic EDI in lux (CIE S 026:2018,
/// D65-equivalent).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Daylight {
    sun: Sun,
    /// The zenith angle the beam comes from, radians: the sun's, or less its refraction
    /// ([`Self::refracted`]).
    beam_zenith: f32,
    atmosphere: ClearAtmosphere,
    /// sin h of the beam's sun, clamped at 0.
    sin_elevation: f32,
    diffuse: [f32; 4],
    direct_normal: [f32; 4],
}

impl Daylight {
    /// The daylight for `sun` (any zenith angle in [0, π]) under an atmosphere of aerosol
    /// optical depth `aod` at 550 nm.
    ///
    /// # Errors
    /// [`SkyError::OutOfRange`] for `aod` outside [[`MIN_AOD`], [`MAX_AOD`]] (NaN included).
    pub fn new(sun: Sun, aod: f32) -> Result<Self, SkyError> {
        Self::with_atmosphere(
            sun,
            &ClearAtmosphere {
                aerosol_optical_depth: aod,
                ..ClearAtmosphere::default()
            },
        )
    }

    /// The daylight for `sun` (any zenith angle in [0, π]) under a site's clear `atmosphere`.
    ///
    /// # Errors
    /// [`SkyError::OutOfRange`] for a parameter of `atmosphere` outside its range
    /// ([`ClearAtmosphere::validate`]).
    pub fn with_atmosphere(sun: Sun, atmosphere: &ClearAtmosphere) -> Result<Self, SkyError> {
        atmosphere.validate()?;
        Ok(Self::of(sun, 0.0, *atmosphere))
    }

    /// The daylight of the sun at `position` under a site's clear `atmosphere`, with the
    /// sun's beam refracted by the air: the beam comes from the sun's apparent position (its
    /// zenith angle less [`SunPosition::refraction`], scaled from 1013.25 hPa to the site's
    /// pressure), so its air mass, its angle on a plane
    /// ([`Self::direct`], [`Self::tilted`]) and the visible part of its disc are the apparent
    /// sun's. The sky's light ([`Self::diffuse`], [`Self::sky`]) stays the geometric sun's: the
    /// rays lighting the sky are bent less the higher they pass, which the tables do not know.
    /// This is the light a sensor on the ground sees; [`Self::with_atmosphere`] is the
    /// reference's geometric sky.
    ///
    /// The refraction is Sæmundsson's (1986) formula as the sun algorithms give it (at sea
    /// level and 15 °C 0.48° at the horizon, 0.16° at 5°, 0.09° at 10°), held within 0.002° of
    /// it at the site's pressure by a test (`tests/tests/daylight.rs`): at 2,317 m under τ₅₅₀
    /// 0.05, with the sun at 5°, the direct light is 5.3 % and the global 2.2 % above the
    /// geometric sun's. The algorithms refract from a geometric elevation of −0.83° up (the
    /// refracted disc's upper edge on the horizon), where the beam on a horizontal plane is 0
    /// either way, so the light is continuous in time (tested through a sunrise).
    ///
    /// ```
    /// use sky_core::daylight::{ClearAtmosphere, Daylight};
    /// use sky_core::solar::{Site, SunAlgorithm, UtcTime};
    ///
    /// let site = Site::new(37.70, -105.92, 2317.0)?;
    /// let time = UtcTime::new(2016, 1, 1, 15, 30, 0.0)?; // the sun a few degrees up
    /// let position = SunAlgorithm::Fast.position(&time, &site)?;
    /// let atmosphere = ClearAtmosphere { elevation_m: 2317.0, ..ClearAtmosphere::default() };
    /// let seen = Daylight::refracted(&position, &atmosphere)?;
    /// let geometric = Daylight::with_atmosphere(position.sun(), &atmosphere)?;
    /// assert!(seen.direct().y > geometric.direct().y);   // a higher sun, a shorter path
    /// assert_eq!(seen.diffuse(), geometric.diffuse());    // the sky's light is the same
    /// # Ok::<(), sky_core::SkyError>(())
    /// ```
    ///
    /// # Errors
    /// [`SkyError::OutOfRange`] for a parameter of `atmosphere` outside its range
    /// ([`ClearAtmosphere::validate`]).
    #[inline] // into the controller's step: on the Cortex-M0 that keeps it in its flash budget
    pub fn refracted(
        position: &SunPosition,
        atmosphere: &ClearAtmosphere,
    ) -> Result<Self, SkyError> {
        atmosphere.validate()?;
        let sun = position.sun();
        Ok(Self::of(sun, position.refraction(), *atmosphere))
    }

    /// The daylight for `sun` under the default atmosphere ([`DEFAULT_AOD`] at sea level).
    #[must_use]
    pub fn clear(sun: Sun) -> Self {
        Self::of(sun, 0.0, ClearAtmosphere::default())
    }

    /// The daylight of a validated atmosphere: the sky's light of `sun`, the beam raised by
    /// `refraction` (radians at 1013.25 hPa: [`SunPosition::refraction`], or 0) times the
    /// pressure ratio.
    fn of(sun: Sun, refraction: f32, atmosphere: ClearAtmosphere) -> Self {
        let elevation = core::f32::consts::FRAC_PI_2 - sun.zenith();
        let pressure = atmosphere.pressure_ratio();
        // Without refraction every value is the geometric sun's, bit for bit.
        let beam_zenith = sun.zenith() - refraction * pressure;
        Self {
            sun,
            beam_zenith,
            atmosphere,
            sin_elevation: math::at_least(math::cos(beam_zenith), 0.0),
            diffuse: diffuse(elevation.to_degrees(), pressure, &atmosphere),
            direct_normal: direct_normal(
                core::f32::consts::FRAC_PI_2 - beam_zenith,
                pressure,
                &atmosphere,
            ),
        }
    }

    /// The same daylight on day `day_of_year` (1-366; other values wrap) instead of at the
    /// mean Earth-Sun distance: every illuminance and the melanopic EDI times (R₀/R)²
    /// ([`crate::solar::earth_sun_distance_factor`], Spencer 1971), 1.035 in early January and
    /// 0.967 in early July. The tables, like the reference they hold, are at 1 AU, as
    /// [`Self::with_atmosphere`] gives them; a measured day's light is not (the controller's
    /// clear sky is on the day of its step).
    ///
    /// ```
    /// use sky_core::daylight::Daylight;
    /// use sky_core::Sun;
    ///
    /// let mean = Daylight::clear(Sun::new(60f32.to_radians(), 0.0)?);
    /// let january = mean.on_day(3);
    /// assert!((january.global().y / mean.global().y - 1.035).abs() < 1e-3);
    /// # Ok::<(), sky_core::SkyError>(())
    /// ```
    #[must_use]
    pub fn on_day(self, day_of_year: u32) -> Self {
        let f = crate::solar::earth_sun_distance_factor(day_of_year);
        Self {
            diffuse: self.diffuse.map(|e| e * f),
            direct_normal: self.direct_normal.map(|e| e * f),
            ..self
        }
    }

    /// The sun as given (geometric).
    #[must_use]
    pub fn sun(&self) -> Sun {
        self.sun
    }

    /// The sun whose beam reaches the ground: [`Self::sun`], or its apparent position for
    /// [`Self::refracted`].
    #[must_use]
    pub fn beam_sun(&self) -> Sun {
        Sun::new(self.beam_zenith, self.sun.azimuth()).unwrap_or(self.sun)
    }

    /// The aerosol optical depth at 550 nm.
    #[must_use]
    pub fn aerosol_optical_depth(&self) -> f32 {
        self.atmosphere.aerosol_optical_depth
    }

    /// The clear atmosphere as given.
    #[must_use]
    pub fn atmosphere(&self) -> ClearAtmosphere {
        self.atmosphere
    }

    /// The diffuse (sky) horizontal illuminance, X, Y, Z in lux.
    #[must_use]
    pub fn diffuse(&self) -> Vec3 {
        Vec3::new(self.diffuse[0], self.diffuse[1], self.diffuse[2])
    }

    /// The direct (sun) horizontal illuminance, X, Y, Z in lux: [`Self::direct_normal`] × sin h.
    #[must_use]
    pub fn direct(&self) -> Vec3 {
        self.direct_normal() * self.sin_elevation
    }

    /// The global horizontal illuminance (sun and sky), X, Y, Z in lux.
    #[must_use]
    pub fn global(&self) -> Vec3 {
        self.diffuse() + self.direct()
    }

    /// The sun's transmitted light on a plane facing it (direct normal illuminance), X, Y, Z in
    /// lux, with the visible fraction of its disc: a renderer's directional light. Its
    /// chromaticity is the sun's colour.
    #[must_use]
    pub fn direct_normal(&self) -> Vec3 {
        let d = self.direct_normal;
        Vec3::new(d[0], d[1], d[2])
    }

    /// The melanopic EDI of the global horizontal light, lux (CIE S 026:2018).
    #[must_use]
    pub fn melanopic_edi(&self) -> f32 {
        self.diffuse[3] + self.direct_normal[3] * self.sin_elevation
    }

    /// The melanopic EDI of the diffuse (sky) horizontal light, lux (CIE S 026:2018).
    #[must_use]
    pub fn diffuse_melanopic_edi(&self) -> f32 {
        self.diffuse[3]
    }

    /// The melanopic daylight efficacy ratio of the global horizontal light (melanopic EDI over
    /// illuminance; 1 for D65); 0 where there is no light.
    #[must_use]
    pub fn melanopic_der(&self) -> f32 {
        let e = self.global().y;
        if e > 0.0 {
            self.melanopic_edi() / e
        } else {
            0.0
        }
    }

    /// The CIE 1931 (x, y) chromaticity of the global horizontal light.
    #[must_use]
    pub fn chromaticity(&self) -> (f32, f32) {
        chromaticity(self.global())
    }

    /// CCT and Duv of the global horizontal light; `None` where |Duv| > [`MAX_DUV`] (the
    /// night-blue sky of nautical twilight) or the CCT is out of [`cct::cct_duv`]'s range.
    #[must_use]
    pub fn cct(&self) -> Option<Cct> {
        cct_of(self.global())
    }

    /// Illuminance on a plane with unit normal `normal` (+z up, any length; a window's or a
    /// panel's), X, Y, Z in lux: the sum of
    ///
    /// * the sun's beam by its incidence angle, [`Self::direct_normal`] × max(0, n·s), s
    ///   towards [`Self::beam_sun`];
    /// * the sky's light in front of the plane, from the anisotropic sky: on a **vertical**
    ///   plane, its table (the physical reference's own integral of its sky over the plane,
    ///   against sun elevation, optical depth and the plane's azimuth from the sun's, over its
    ///   diffuse light) times [`Self::diffuse`]; on a horizontal plane facing up
    ///   [`Self::diffuse`], facing down none; on a **tilted** plane, the daylight sky's radiance
    ///   ([`Self::sky`]) integrated over the plane by the rule of
    ///   [`Photometry::plane_illuminance`](crate::photometry::Photometry::plane_illuminance),
    ///   scaled to agree with the horizontal and the vertical plane's values (the scale goes
    ///   from the horizontal's to the vertical's as sin β for a plane tilted by β ≤ 90°, and is
    ///   the vertical's below);
    /// * the ground's light, ρ E_g (1 − n_z) / 2 with ρ = [`GROUND_ALBEDO`] and E_g =
    ///   [`Self::global`]: a uniform Lambertian ground, the reference's and its tables' (whose
    ///   diffuse light already holds the ground's reflection back down from the sky).
    ///
    /// Error of the illuminance against the reference's own tilted irradiance (sky-train's
    /// `PhysicalSky::tilted_irradiance`, the same sun, ground and sky) at sun elevations and
    /// optical depths between the tables' nodes (`tests/tests/daylight.rs`): from 0° to 90°
    /// within 2 % on vertical planes and 3 % on tilted ones, from −6° to 0° within 3 %, below
    /// −6° (under 3 lx) within 8 %; chromaticity within 0.005 (measured worst cases in
    /// `docs/daylight.md`). A zero or non-finite normal gives zero.
    ///
    /// Cost: a vertical or horizontal plane reads the tables (a few hundred multiplications);
    /// a tilted one also evaluates the daylight sky 512 or 768 times (two or three
    /// 256-direction quadratures).
    #[must_use]
    pub fn tilted(&self, normal: Vec3) -> Vec3 {
        let length = normal.length();
        if !(length > 0.0 && length.is_finite()) {
            return Vec3::ZERO;
        }
        let n = normal / length;
        let incidence = math::at_least(n.dot(self.beam_direction()), 0.0);
        self.direct_normal() * incidence
            + self.sky_on_plane(n)
            + self.global() * (GROUND_ALBEDO * 0.5 * (1.0 - n.z))
    }

    /// The unit direction the beam comes from: the sun's, raised to [`Self::beam_sun`]'s zenith
    /// angle at the same azimuth (one cosine and two square roots, not a new [`Sun`]'s four
    /// sines and cosines).
    fn beam_direction(&self) -> Vec3 {
        let d = self.sun.direction();
        if self.beam_zenith == self.sun.zenith() {
            return d; // the geometric sun's daylight: nothing more to compute
        }
        let across = math::sqrt(d.x * d.x + d.y * d.y);
        if across <= 0.0 {
            return d;
        }
        let c = math::cos(self.beam_zenith);
        let s = math::sqrt(math::at_least(1.0 - c * c, 0.0)) / across;
        Vec3::new(d.x * s, d.y * s, c)
    }

    /// The sky's share of [`Self::tilted`] on the plane of unit normal `n`.
    fn sky_on_plane(&self, n: Vec3) -> Vec3 {
        let across = math::sqrt(n.x * n.x + n.y * n.y); // sin β (n is a finite unit vector)
        if across <= 0.0 {
            return if n.z > 0.0 {
                self.diffuse()
            } else {
                Vec3::ZERO
            };
        }
        let facing = Vec3::new(n.x / across, n.y / across, 0.0);
        let vertical = self.diffuse() * self.vertical_share(facing);
        if n.z == 0.0 {
            return vertical;
        }
        let sky = self.sky();
        let integral = |m: Vec3| crate::photometry::plane_integral(&sky, m);
        let ratio = |a: Vec3, b: Vec3| {
            Vec3::from_array(core::array::from_fn(|c| {
                if b[c] > 0.0 { a[c] / b[c] } else { 0.0 }
            }))
        };
        let scale_vertical = ratio(vertical, integral(facing));
        let scale = if n.z > 0.0 {
            let scale_horizontal = ratio(self.diffuse(), integral(Vec3::Z));
            scale_horizontal + (scale_vertical - scale_horizontal) * across
        } else {
            scale_vertical
        };
        integral(n) * scale
    }

    /// V per channel: the sky's X, Y, Z on the vertical plane facing the horizontal unit
    /// vector `facing` over the diffuse horizontal X, Y, Z ([`plane_tables::LN_VERTICAL`]):
    /// ln V linear in the sun's elevation between the table's nodes, quadratic in ln τ as the
    /// diffuse table, and cubic in the cosine of the plane's azimuth from the sun's on each
    /// side of 90° (where the sun's aureole crosses the plane).
    fn vertical_share(&self, facing: Vec3) -> Vec3 {
        let sun = self.sun.direction();
        let sun_across = math::sqrt(sun.x * sun.x + sun.y * sun.y);
        // An overhead sun (or one straight below) has no azimuth: its sky is the same on every
        // vertical plane at 90° (and below −18° the table keeps its −18° row anyway).
        let x = if sun_across > 0.0 {
            math::at_most(
                math::at_least((facing.x * sun.x + facing.y * sun.y) / sun_across, -1.0),
                1.0,
            )
        } else {
            1.0
        };
        // The four azimuth nodes of x's side (the table's 0°, 30°, 60°, 90° or 90°, 120°, 150°,
        // 180°), at cos 0°, cos 30°, cos 60°, cos 90° mirrored, and their Lagrange weights.
        let (first, nodes) = if x >= 0.0 {
            (0, [1.0, 0.866_025_4, 0.5, 0.0])
        } else {
            (3, [0.0, -0.5, -0.866_025_4, -1.0])
        };
        let azimuth: [f32; 4] = core::array::from_fn(|i| {
            let mut w = 1.0;
            for j in 0..4 {
                if j != i {
                    w *= (x - nodes[j]) / (nodes[i] - nodes[j]);
                }
            }
            w
        });
        let elevation = core::f32::consts::FRAC_PI_2 - self.sun.zenith();
        let (ie, we) = bracket(&plane_tables::PLANE_ELEVATION_DEG, elevation.to_degrees());
        let (fa, wa) = aod_stencil(self.atmosphere.aerosol_optical_depth);
        Vec3::from_array(core::array::from_fn(|c| {
            let mut ln_v = 0.0;
            for (k, w_aod) in wa.iter().enumerate() {
                let t = &plane_tables::LN_VERTICAL[fa + k];
                for (row, w_h) in [(ie, 1.0 - we), (ie + 1, we)] {
                    let v = &t[row][c];
                    let mut s = 0.0;
                    for (i, w) in azimuth.iter().enumerate() {
                        s += w * f32::from(v[first + i]);
                    }
                    ln_v += w_aod * w_h * s;
                }
            }
            math::exp_libm(ln_v * plane_tables::LN_VERTICAL_STEP)
        }))
    }
}

/// The CIE 1931 (x, y) of `xyz`; (0, 0) for no light.
#[must_use]
pub fn chromaticity(xyz: Vec3) -> (f32, f32) {
    let sum = xyz.x + xyz.y + xyz.z;
    if sum > 0.0 && sum.is_finite() {
        (xyz.x / sum, xyz.y / sum)
    } else {
        (0.0, 0.0)
    }
}

/// CCT and Duv of the light `xyz` where |Duv| ≤ [`MAX_DUV`], else `None`.
#[must_use]
pub fn cct_of(xyz: Vec3) -> Option<Cct> {
    let (x, y) = chromaticity(xyz);
    cct::cct_duv(x, y).ok().filter(|c| c.duv.abs() <= MAX_DUV)
}

/// The node interval of `v` in the ascending `nodes` and the weight of its upper node, clamped
/// to the ends (NaN gives the first node).
fn bracket(nodes: &[f32], v: f32) -> (usize, f32) {
    let last = nodes.len() - 1;
    let mut i = 0;
    while i + 1 < last && v >= nodes[i + 1] {
        i += 1;
    }
    let w = (v - nodes[i]) / (nodes[i + 1] - nodes[i]);
    (i, math::at_most(math::at_least(w, 0.0), 1.0))
}

/// The diffuse X, Y, Z and melanopic EDI at sun elevation `h_deg` under `atmosphere`: the
/// logarithms linear in elevation and quadratic in ln τ ([`aod_stencil`]), each node's ln E plus
/// (P / P₀ − 1) times its pressure sensitivity, plus (O₃ − 300) / 100 times the ozone
/// sensitivity (linear in elevation); `pressure` is P / P₀ ([`ClearAtmosphere::pressure_ratio`]).
fn diffuse(h_deg: f32, pressure: f32, atmosphere: &ClearAtmosphere) -> [f32; 4] {
    let dp = pressure - 1.0;
    let d_ozone = (atmosphere.ozone_du - OZONE_DU) / 100.0;
    let (ie, we) = bracket(&tables::ELEVATION_DEG, h_deg);
    let (first, weights) = aod_stencil(atmosphere.aerosol_optical_depth);
    let along = |t: &[[i16; 4]], k: usize| -> f32 {
        let (a, b) = (f32::from(t[ie][k]), f32::from(t[ie + 1][k]));
        a + we * (b - a)
    };
    core::array::from_fn(|k| {
        let mut ln_e = 0.0;
        for (n, w) in weights.iter().enumerate() {
            ln_e += w
                * (along(&tables::LN_DIFFUSE[first + n], k) / tables::LN_SCALE
                    + dp * along(&tables::PRESSURE_SENSITIVITY[first + n], k)
                        / tables::SENSITIVITY_SCALE);
        }
        ln_e += d_ozone * along(&tables::OZONE_SENSITIVITY, k) / tables::SENSITIVITY_SCALE;
        math::exp_libm(ln_e)
    })
}

/// The diffuse table's stencil in the optical depth `aod`: its first node and the Lagrange
/// weights, quadratic in ln τ, of it and the next two (the interval's ends and the node before
/// it, or after it for the first interval: the interpolant passes through every node, so it
/// is continuous in τ). Every table against τ shares it (inlined: the controller's step
/// calls it once, through [`Daylight::new`]).
#[inline(always)]
fn aod_stencil(aod: f32) -> (usize, [f32; 3]) {
    let ln_aod = tables::AOD.map(math::ln);
    let (ia, _) = bracket(&ln_aod, math::ln(aod));
    let first = ia.saturating_sub(1).min(ln_aod.len() - 3);
    let x = math::at_most(
        math::at_least(math::ln(aod), ln_aod[0]),
        ln_aod[ln_aod.len() - 1],
    );
    // Lagrange's weights on the stencil first, first + 1, first + 2.
    let weight = |i: usize| {
        let mut w = 1.0;
        for j in first..first + 3 {
            if j != i {
                w *= (x - ln_aod[j]) / (ln_aod[i] - ln_aod[j]);
            }
        }
        w
    };
    (first, [weight(first), weight(first + 1), weight(first + 2)])
}

/// The visible fraction of the sun's disc with its centre at `elevation` radians (a circular
/// segment above a straight horizon).
fn disc_fraction(elevation: f32) -> f32 {
    let s = elevation / tables::SUN_ANGULAR_RADIUS;
    if s >= 1.0 {
        1.0
    } else if s > -1.0 {
        (math::acos(-s) + s * math::sqrt(1.0 - s * s)) / core::f32::consts::PI
    } else {
        0.0 // NaN too: never NaN out
    }
}

/// The direct normal X, Y, Z and melanopic EDI at sun elevation `elevation` radians under
/// `atmosphere` (module docs), whose P / P₀ is `pressure`.
fn direct_normal(elevation: f32, pressure: f32, atmosphere: &ClearAtmosphere) -> [f32; 4] {
    let aod = atmosphere.aerosol_optical_depth;
    let v = disc_fraction(elevation);
    if v <= 0.0 {
        return [0.0; 4];
    }
    let n = tables::AIRMASS.len();
    #[allow(clippy::cast_precision_loss)]
    let last = (n - 1) as f32;
    let x = math::sqrt(math::at_least(math::sin(elevation), 0.0)) * last;
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let j = (math::at_most(math::floor(x), last - 1.0)) as usize;
    #[allow(clippy::cast_precision_loss)]
    let w = math::at_most(x - j as f32, 1.0);
    let m: [f32; 3] = core::array::from_fn(|c| {
        tables::AIRMASS[j][c] + w * (tables::AIRMASS[j + 1][c] - tables::AIRMASS[j][c])
    });
    let mut out = [0.0; 4];
    for l in 0..tables::SUN_CHANNELS.len() {
        let tau = pressure * tables::RAYLEIGH_DEPTH[l] * m[0]
            + aod * tables::AEROSOL_DEPTH[l] * m[1]
            + atmosphere.ozone_du * tables::OZONE_DEPTH[l] * m[2];
        let t = math::exp_libm(-tau) * v;
        for (o, s) in out.iter_mut().zip(tables::SUN_CHANNELS[l]) {
            *o += s * t;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn beam_direction_is_the_beam_suns() {
        use crate::solar::{Site, SunAlgorithm, UtcTime};
        let site = Site::new(37.70, -105.92, 2317.0).expect("site");
        let atmosphere = ClearAtmosphere {
            elevation_m: 2317.0,
            ..ClearAtmosphere::default()
        };
        let mut raised = 0;
        for minute in (0..24 * 60).step_by(7) {
            let time = UtcTime::new(2016, 1, 1, minute / 60, minute % 60, 0.0).expect("time");
            let position = SunAlgorithm::Fast.position(&time, &site).expect("sun");
            let d = Daylight::refracted(&position, &atmosphere).expect("in range");
            let (a, b) = (d.beam_direction(), d.beam_sun().direction());
            assert!(
                (a - b).length() < 2e-6,
                "{a} against {b} at minute {minute}"
            );
            raised += usize::from(d.beam_sun().zenith() < position.sun().zenith());
        }
        assert!(raised > 50, "{raised} raised beams");
    }

    #[test]
    fn disc_fraction_ends() {
        assert!((disc_fraction(0.0) - 0.5).abs() < 1e-6);
        assert_eq!(disc_fraction(0.01), 1.0);
        assert_eq!(disc_fraction(-0.01), 0.0);
    }

    /// The US Standard Atmosphere 1976's Table I: 845.59 hPa at 1,500 m and 701.21 hPa at
    /// 3,000 m (geometric), over 1013.25 hPa.
    #[test]
    fn pressure_ratio_is_the_standard_atmosphere() {
        for (z, p) in [(1500.0, 845.59), (3000.0, 701.21), (0.0, 1013.25)] {
            let a = ClearAtmosphere {
                elevation_m: z,
                ..ClearAtmosphere::default()
            };
            let r = a.pressure_ratio();
            assert!((r - p / 1013.25).abs() < 2e-4, "{z} m: {r}");
        }
    }

    #[test]
    fn atmosphere_out_of_range_is_named() {
        let sun = Sun::new(0.5, 0.0).expect("sun");
        for (a, name) in [
            (
                ClearAtmosphere {
                    elevation_m: 5001.0,
                    ..ClearAtmosphere::default()
                },
                "site elevation [m]",
            ),
            (
                ClearAtmosphere {
                    ozone_du: f32::NAN,
                    ..ClearAtmosphere::default()
                },
                "ozone column [DU]",
            ),
            (
                ClearAtmosphere {
                    aerosol_optical_depth: 0.9,
                    ..ClearAtmosphere::default()
                },
                "aerosol optical depth",
            ),
        ] {
            match Daylight::with_atmosphere(sun, &a) {
                Err(SkyError::OutOfRange { parameter, .. }) => assert_eq!(parameter, name),
                other => panic!("{other:?}"),
            }
        }
    }

    fn day(elevation_deg: f32, aod: f32) -> Daylight {
        Sun::new((90.0 - elevation_deg).to_radians(), 0.7)
            .and_then(|s| Daylight::new(s, aod))
            .unwrap_or_else(|_| unreachable!("in range"))
    }

    /// A horizontal plane facing up gets the global light, one facing down the ground's only;
    /// a vertical plane's sky is the table's at its nodes (facing the sun, 5°: V from the
    /// table's first optical depth, read back).
    #[test]
    fn tilted_horizontal_and_vertical_identities() {
        let d = day(30.0, 0.2);
        let up = d.tilted(Vec3::Z);
        assert!(
            (up - d.global()).abs().max_element() <= 1e-3 * d.global().y,
            "{up}"
        );
        let down = d.tilted(-Vec3::Z);
        let ground = d.global() * GROUND_ALBEDO;
        assert!(
            (down - ground).abs().max_element() <= 1e-3 * ground.y,
            "{down}"
        );
        let node = day(5.0, MIN_AOD);
        let toward = node.sun().direction();
        let facing = Vec3::new(toward.x, toward.y, 0.0).normalize();
        let v = node.vertical_share(facing);
        let row = plane_tables::PLANE_ELEVATION_DEG
            .iter()
            .position(|&h| h == 5.0)
            .unwrap_or_else(|| unreachable!("5 deg is a node"));
        for c in 0..3 {
            let table = math::exp_libm(
                f32::from(plane_tables::LN_VERTICAL[0][row][c][0]) * plane_tables::LN_VERTICAL_STEP,
            );
            assert!((v[c] / table - 1.0).abs() < 1e-3, "{c}: {} {table}", v[c]);
        }
    }

    /// The sky on a plane is continuous as its normal passes the vertical (from the tables to
    /// the scaled quadrature) and the horizontal, and symmetric about the sun's vertical plane.
    #[test]
    fn tilted_continuous_and_symmetric() {
        for (h, aod) in [(3.0, 0.1), (25.0, 0.38), (60.0, 0.8), (-4.0, 0.3)] {
            let d = day(h, aod);
            for azimuth in [0.0f32, 0.5, 1.6, 2.4, 3.1] {
                let a = 0.7 + azimuth;
                let normal = |tilt: f32| crate::geom::direction(tilt, a);
                let vertical = d.tilted(normal(core::f32::consts::FRAC_PI_2));
                for tilt in [
                    core::f32::consts::FRAC_PI_2 - 1e-3,
                    core::f32::consts::FRAC_PI_2 + 1e-3,
                ] {
                    let near = d.tilted(normal(tilt));
                    let e = (near - vertical).abs().max_element() / vertical.max_element();
                    assert!(e < 3e-3, "{h} {aod} {azimuth} {tilt}: {near} {vertical}");
                }
                let near_up = d.tilted(normal(1e-3));
                let e = (near_up - d.global()).abs().max_element() / d.global().max_element();
                assert!(e < 3e-3, "{h} {aod} {azimuth}: {near_up} {}", d.global());
                let mirror = d.tilted(crate::geom::direction(1.1, 0.7 - azimuth));
                let this = d.tilted(crate::geom::direction(1.1, a));
                let e = (mirror - this).abs().max_element() / this.max_element();
                assert!(e < 1e-3, "{h} {aod} {azimuth}: {mirror} {this}");
            }
        }
    }

    #[test]
    fn bracket_clamps() {
        let nodes = [0.0, 1.0, 3.0];
        assert_eq!(bracket(&nodes, -1.0), (0, 0.0));
        assert_eq!(bracket(&nodes, 2.0), (1, 0.5));
        assert_eq!(bracket(&nodes, 9.0), (1, 1.0));
        assert_eq!(bracket(&nodes, f32::NAN), (0, 0.0));
    }
}
