//! An outdoor measurement of daylight and what it tells: the global illuminance and irradiance,
//! their diffuse and direct parts, and the sky condition of Perez's parametrisation.
//!
//! * W/m² become lux by Perez's global efficacy ([`crate::efficacy`]) with the precipitable
//!   water [`DEFAULT_PRECIPITABLE_WATER`];
//! * a global reading alone is split into diffuse and direct by Erbs's correlation
//!   ([`crate::decomposition`]);
//! * a lux reading alone is turned into irradiance by iterating: irradiance = lux / efficacy,
//!   whose sky condition (from Erbs's split) gives the next efficacy, [`EFFICACY_ITERATIONS`]
//!   times from a first efficacy of 110 lm/W (the global efficacy depends on the sky, by a few
//!   per cent, and steps at the sky-clearness bins' edges, so the iteration may settle on
//!   either side of an edge).

use core::f32::consts::FRAC_PI_2;

use crate::decomposition::{self, MAX_BEAM_ZENITH, MAX_CLEARNESS_INDEX, MIN_COS_ZENITH};
use crate::efficacy::{DEFAULT_PRECIPITABLE_WATER, Efficacy};
use crate::error::{SkyError, check_range};
use crate::math;
use crate::perez::SkyCondition;
use crate::solar;

/// An outdoor measurement of daylight on a horizontal plane.
///
/// **Bad readings**: NaN or infinite values are [`SkyError::NotFinite`]; negative values (a
/// sensor's dark offset) count as 0; a diffuse above the global is [`SkyError::OutOfRange`]
/// naming the diffuse; a global above [`MAX_CLEARNESS_INDEX`] times the extraterrestrial
/// horizontal irradiance (cos Z taken as at least [`MIN_COS_ZENITH`], so the bound stays above
/// 129 W/m² or about 14 klx at night) is [`SkyError::OutOfRange`] naming the reading. With the sun
/// below the horizon a reading is used as it is: there is no sky type, and W/m² become lux with
/// the efficacy of the sun on the horizon.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Measurement {
    /// Global horizontal illuminance from a lux sensor, lx.
    GlobalIlluminance(f32),
    /// Global horizontal irradiance from a pyranometer, W/m².
    GlobalIrradiance(f32),
    /// Global and diffuse horizontal irradiance (a pyranometer and a shaded one), W/m².
    Irradiance {
        /// Global horizontal irradiance, W/m².
        global: f32,
        /// Diffuse horizontal irradiance, W/m².
        diffuse: f32,
    },
}

/// A measurement in both units, with its parts and the sky condition when the sun is up.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reading {
    /// Global horizontal illuminance, lx (measured, or the irradiance times Perez's global
    /// efficacy).
    pub global_illuminance: f32,
    /// Global horizontal irradiance, W/m² (measured, or the illuminance over the efficacy).
    pub global_irradiance: f32,
    /// Diffuse horizontal irradiance, W/m² (measured, or Erbs's split of the global).
    pub diffuse_irradiance: f32,
    /// Direct normal irradiance, W/m² (0 with the sun more than 87° from the zenith).
    pub direct_normal_irradiance: f32,
    /// Sky clearness ε and brightness Δ, with the sun above the horizon.
    pub condition: Option<SkyCondition>,
}

impl Reading {
    /// The diffuse horizontal illuminance, lx: the diffuse irradiance times Perez's diffuse
    /// efficacy (with the sun at zenith angle `sun_zenith`, radians; the overcast bin when the
    /// sun is down).
    #[must_use]
    pub fn diffuse_illuminance(&self, sun_zenith: f32) -> f32 {
        let overcast = SkyCondition::new(1.0, 0.0);
        let k = match (self.condition, overcast) {
            (Some(c), _) | (None, Ok(c)) => {
                Efficacy::new(&c, sun_zenith, DEFAULT_PRECIPITABLE_WATER).diffuse
            }
            (None, Err(_)) => 0.0,
        };
        self.diffuse_irradiance * k
    }
}

/// Fixed-point iterations from a global illuminance to the irradiance whose Perez efficacy
/// gives it back (module docs).
pub const EFFICACY_ITERATIONS: usize = 8;

/// A first guess of the global efficacy, lm/W.
const FIRST_EFFICACY: f32 = 110.0;

/// A finite reading, negative values counted as 0.
fn non_negative(parameter: &'static str, value: f32) -> Result<f32, SkyError> {
    if value.is_finite() {
        Ok(value.max(0.0))
    } else {
        Err(SkyError::NotFinite { parameter })
    }
}

impl Measurement {
    /// What the measurement tells with the sun at zenith angle `sun_zenith` (radians, any value
    /// in [0, π]; above π/2 the sun is down) on day `day_of_year` (for the extraterrestrial
    /// irradiance), by the rules of [`Measurement`].
    ///
    /// ```
    /// use sky_core::measurement::Measurement;
    /// let r = Measurement::GlobalIrradiance(800.0).read(40f32.to_radians(), 172)?;
    /// assert!(r.global_illuminance > 80_000.0 && r.global_illuminance < 95_000.0);
    /// assert!(r.diffuse_irradiance < 0.2 * 800.0);   // a sunny reading, by Erbs's split
    /// assert_eq!(r.condition.map(|c| c.bin()), Some(7));
    /// # Ok::<(), sky_core::SkyError>(())
    /// ```
    ///
    /// # Errors
    /// The bad readings of [`Measurement`].
    pub fn read(self, sun_zenith: f32, day_of_year: u32) -> Result<Reading, SkyError> {
        let up = sun_zenith <= FRAC_PI_2;
        let z = if up { sun_zenith.max(0.0) } else { FRAC_PI_2 };
        let day = day_of_year;
        let i0 = solar::extraterrestrial_irradiance(day);
        let limit = MAX_CLEARNESS_INDEX * i0 * math::cos(z).max(MIN_COS_ZENITH);
        // The condition of a diffuse and a direct normal irradiance (no diffuse: overcast).
        let condition = |diffuse: f32, direct_normal: f32| -> Result<SkyCondition, SkyError> {
            if diffuse > 0.0 {
                SkyCondition::from_irradiance(diffuse, direct_normal, z, day)
            } else {
                SkyCondition::new(1.0, 0.0)
            }
        };
        let efficacy = |c: &SkyCondition| Efficacy::new(c, z, DEFAULT_PRECIPITABLE_WATER).global;
        // Global irradiance → (diffuse, direct normal): Erbs's split by day, all diffuse at night.
        let split = |g: f32| -> Result<(f32, f32), SkyError> {
            if up {
                let parts = decomposition::erbs(g, z, i0)?;
                Ok((parts.diffuse, parts.direct_normal))
            } else {
                Ok((check_range("global irradiance [W/m²]", g, 0.0, limit)?, 0.0))
            }
        };
        let (lux, global, diffuse, direct, c) = match self {
            Self::GlobalIrradiance(g) => {
                let g = non_negative("global irradiance [W/m²]", g)?;
                let (d, i) = split(g)?;
                let c = condition(d, i)?;
                (g * efficacy(&c), g, d, i, c)
            }
            Self::Irradiance { global, diffuse } => {
                let g = non_negative("global irradiance [W/m²]", global)?;
                let d = non_negative("diffuse irradiance [W/m²]", diffuse)?;
                check_range("global irradiance [W/m²]", g, 0.0, limit)?;
                check_range("diffuse irradiance [W/m²]", d, 0.0, g)?;
                if d == 0.0 && g > 0.0 {
                    return Err(SkyError::OutOfRange {
                        parameter: "diffuse irradiance [W/m²]",
                        value: d,
                        min: f32::MIN_POSITIVE,
                        max: g,
                    });
                }
                let i = if up && z <= MAX_BEAM_ZENITH {
                    (g - d) / math::cos(z)
                } else {
                    0.0
                };
                let c = condition(if up { d } else { g }, i)?;
                (g * efficacy(&c), g, d, i, c)
            }
            Self::GlobalIlluminance(lux) => {
                let lux = non_negative("global illuminance [lx]", lux)?;
                let mut k = FIRST_EFFICACY;
                let (mut g, mut d, mut i) = (lux / k, lux / k, 0.0);
                let mut c = condition(d, i)?;
                for _ in 0..EFFICACY_ITERATIONS {
                    check_range("global illuminance [lx]", lux, 0.0, limit * k)?;
                    g = lux / k;
                    (d, i) = split(g.min(limit))?;
                    c = condition(d, i)?;
                    k = efficacy(&c);
                }
                (lux, g, d, i, c)
            }
        };
        Ok(Reading {
            global_illuminance: lux,
            global_irradiance: global,
            diffuse_irradiance: diffuse,
            direct_normal_irradiance: direct,
            condition: up.then_some(c),
        })
    }
}
