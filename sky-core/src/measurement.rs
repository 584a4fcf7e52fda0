//! An outdoor measurement of daylight and what it tells: the global illuminance and irradiance,
//! their diffuse and direct parts, and the sky condition of Perez's parametrisation.
//!
//! * W/m² become lux by Perez's global efficacy ([`crate::efficacy`]) with the precipitable
//!   water [`DEFAULT_PRECIPITABLE_WATER`];
//! * a global reading alone is split into diffuse and direct by Erbs's correlation
//!   ([`Measurement::read`]) or another separation model ([`Measurement::read_with`],
//!   [`crate::decomposition`]);
//! * a lux reading alone is turned into irradiance by iterating: irradiance = lux / efficacy,
//!   whose sky condition (from the split) gives the next efficacy, [`EFFICACY_ITERATIONS`]
//!   times from a first efficacy of 110 lm/W (the global efficacy depends on the sky by a few
//!   per cent, continuously in ε: [`crate::efficacy`]).

use core::f32::consts::FRAC_PI_2;

use crate::decomposition::{
    self, MAX_BEAM_ZENITH, MAX_CLEARNESS_INDEX, MIN_COS_ZENITH, Separation,
};
use crate::efficacy::{DEFAULT_PRECIPITABLE_WATER, Efficacy};
use crate::error::{SkyError, check_range};
use crate::math;
use crate::perez::SkyCondition;
use crate::solar;

/// An outdoor measurement of daylight on a horizontal plane.
///
/// **Readings as stations deliver them** (one rule for every reading, the same for the CLI's
/// `sample --model perez` and `schedule --measurements`):
///
/// * NaN or infinite values are [`SkyError::NotFinite`];
/// * a negative value down to [`THERMAL_OFFSET_LIMIT`] W/m² (a pyranometer's thermal offset,
///   −1.8 to −9.2 W/m² at night in the SURFRAD and MIDC files read here, down to −15 W/m² for
///   a ventilated, shaded PSP under a clear sky) or [`THERMAL_OFFSET_LIMIT_LUX`] lx
///   counts as 0; a value below it is [`SkyError::OutOfRange`] naming the reading (a sensor
///   fault, not an offset); values below `f32::MIN_POSITIVE` (subnormal) count as 0 too;
/// * a diffuse above the global by at most [`DIFFUSE_EXCESS_TOLERANCE`] W/m² or
///   [`DIFFUSE_EXCESS_FRACTION`] of the global, whichever is larger (two sensors' offsets and
///   cosine errors near the horizon: up to 5.9 W/m², at zenith 89.3°, in NOAA SURFRAD's
///   Alamosa record of 1 January 2016), counts as equal to the global; above that it is
///   [`SkyError::OutOfRange`] naming the diffuse;
/// * a diffuse of 0 with a global above 0 is used as an all-diffuse reading when the sun is down
///   or the global is at most [`ZERO_DIFFUSE_MAX_GLOBAL`] (a shaded sensor's offset at night and
///   dawn); with the sun up and a larger global it is [`SkyError::OutOfRange`] naming the
///   diffuse as given (a sun without a sky is a shading or wiring fault);
/// * a global above [`MAX_CLEARNESS_INDEX`] times the extraterrestrial horizontal irradiance
///   (cos Z taken as at least [`MIN_COS_ZENITH`], so the bound stays above 129 W/m² or about
///   14 klx at night) is [`SkyError::OutOfRange`] naming the reading.
///
/// With the sun below the horizon a reading is used as it is (night readings are not refused):
/// there is no sky type, and W/m² become lux with the efficacy of the sun on the horizon.
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
    /// Diffuse horizontal irradiance, W/m² (measured, or the separation model's split of the
    /// global).
    pub diffuse_irradiance: f32,
    /// Direct normal irradiance, W/m² (0 with the sun more than 87° from the zenith).
    pub direct_normal_irradiance: f32,
    /// Sky clearness ε and brightness Δ, with the sun above the horizon.
    pub condition: Option<SkyCondition>,
    /// The precipitable water, cm, Perez's efficacies were taken at
    /// ([`crate::efficacy::DEFAULT_PRECIPITABLE_WATER`] unless given:
    /// [`Measurement::read_with_water`]).
    pub precipitable_water: f32,
}

impl Reading {
    /// The global illuminance's diffuse and direct parts on the horizontal plane, lx, with the
    /// sun at zenith angle `sun_zenith` (radians): the global illuminance apportioned in the
    /// ratio of the diffuse irradiance times Perez's diffuse efficacy to the direct horizontal
    /// irradiance (DNI cos Z) times his direct efficacy, so that the parts sum to the global
    /// (to rounding) and neither exceeds it. Perez et al. 1990 fitted the three efficacies
    /// separately, and the diffuse and direct fits alone sum to the global fit's lux only
    /// within a few per cent; the global illuminance is the reading of a lux sensor, or the
    /// irradiance through the fit made for it, and its parts keep it. With the sun down (or
    /// more than 87° from the zenith, no beam) the global is all diffuse.
    ///
    /// ```
    /// use sky_core::measurement::Measurement;
    /// let z = 40f32.to_radians();
    /// let r = Measurement::Irradiance { global: 700.0, diffuse: 120.0 }.read(z, 172)?;
    /// let (diffuse, direct) = r.parts_illuminance(z);
    /// assert!((diffuse + direct - r.global_illuminance).abs() <= 1e-3 * r.global_illuminance);
    /// assert!(diffuse > 0.15 * r.global_illuminance && diffuse < 0.25 * r.global_illuminance);
    /// let dull = Measurement::Irradiance { global: 80.0, diffuse: 80.0 }.read(z, 172)?;
    /// assert_eq!(dull.parts_illuminance(z), (dull.global_illuminance, 0.0));
    /// # Ok::<(), sky_core::SkyError>(())
    /// ```
    #[must_use]
    pub fn parts_illuminance(&self, sun_zenith: f32) -> (f32, f32) {
        let g = self.global_illuminance;
        let (diffuse, direct) = match self.condition {
            Some(c) if sun_zenith <= FRAC_PI_2 => {
                let z = sun_zenith.max(0.0);
                let k = Efficacy::new(&c, z, self.precipitable_water);
                (
                    self.diffuse_irradiance * k.diffuse,
                    self.direct_normal_irradiance * math::cos(z) * k.direct,
                )
            }
            _ => (self.diffuse_irradiance, 0.0),
        };
        let sum = diffuse + direct;
        if direct > 0.0 && sum.is_finite() {
            let d = g * (diffuse / sum);
            (d, (g - d).max(0.0))
        } else {
            (g, 0.0)
        }
    }
}

/// Fixed-point iterations from a global illuminance to the irradiance whose Perez efficacy
/// gives it back (module docs).
pub const EFFICACY_ITERATIONS: usize = 8;

/// A first guess of the global efficacy, lm/W.
pub const FIRST_EFFICACY: f32 = 110.0;

/// The most negative irradiance reading taken for a sensor's thermal offset and counted as 0,
/// W/m² (as a magnitude: readings down to −20 W/m² count as 0; [`Measurement`]). A
/// ventilated, shaded Eppley PSP's offset reaches −15 W/m² under a clear sky, its night
/// signal −10 W/m² (Haeffelin, Kato, Smith, Rutledge, Charlock, Mahan, *Determination of the
/// thermal offset of the Eppley precision spectral pyranometer*, Applied Optics, 2001);
/// the limit leaves an unventilated sensor a margin beyond that (NREL MIDC's NWTC M2 PSP logs
/// −9.2 W/m² at night in pvlib's `midc_20181014.txt`). Below it a reading is a fault.
pub const THERMAL_OFFSET_LIMIT: f32 = 20.0;

/// The same for a lux sensor, lx: [`THERMAL_OFFSET_LIMIT`] at the first-guess efficacy of
/// 110 lm/W, so that both kinds of reading follow one rule.
pub const THERMAL_OFFSET_LIMIT_LUX: f32 = THERMAL_OFFSET_LIMIT * FIRST_EFFICACY;

/// The largest global reading, W/m², with which a diffuse of 0 is read as all diffuse while the
/// sun is up (a shaded sensor's offset at dawn; [`Measurement`]); above it such a reading is
/// refused.
pub const ZERO_DIFFUSE_MAX_GLOBAL: f32 = 10.0;

/// A diffuse reading above the global by at most this much, W/m², counts as the global
/// ([`Measurement`]): two sensors' offsets and cosine errors near the horizon, up to 5.9 W/m² in
/// SURFRAD Alamosa's record of 1 January 2016.
pub const DIFFUSE_EXCESS_TOLERANCE: f32 = 10.0;

/// A diffuse reading above the global by at most this fraction of the global counts as the
/// global, when that is more than [`DIFFUSE_EXCESS_TOLERANCE`] ([`Measurement`]).
pub const DIFFUSE_EXCESS_FRACTION: f32 = 0.05;

/// A finite reading, a thermal offset down to `-offset` (and a subnormal value) counted as 0.
fn non_negative(parameter: &'static str, value: f32, offset: f32) -> Result<f32, SkyError> {
    if !value.is_finite() {
        Err(SkyError::NotFinite { parameter })
    } else if value < -offset {
        Err(SkyError::OutOfRange {
            parameter,
            value,
            min: -offset,
            max: f32::MAX,
        })
    } else if value < f32::MIN_POSITIVE {
        Ok(0.0)
    } else {
        Ok(value)
    }
}

/// The diffuse reading `diffuse` (its thermal offset already counted as 0) with a global
/// `global`: at most the global, within the tolerance of [`Measurement`].
///
/// # Errors
/// [`SkyError::OutOfRange`] naming the diffuse, `given` being the value as read.
pub fn diffuse_within_global(diffuse: f32, global: f32, given: f32) -> Result<f32, SkyError> {
    let tolerance = DIFFUSE_EXCESS_TOLERANCE.max(DIFFUSE_EXCESS_FRACTION * global);
    if diffuse <= global {
        Ok(diffuse)
    } else if diffuse <= global + tolerance {
        Ok(global)
    } else {
        Err(SkyError::OutOfRange {
            parameter: "diffuse irradiance [W/m²]",
            value: given,
            min: 0.0,
            max: global + tolerance,
        })
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
        self.read_with(sun_zenith, day_of_year, &Separation::Erbs)
    }

    /// [`Measurement::read`] with a global reading alone split by `separation` (DIRINT,
    /// DIRINDEX, Erbs's correlation or Engerer2, with what each needs:
    /// [`crate::decomposition`]).
    ///
    /// ```
    /// use sky_core::decomposition::{Separation, ENGERER2_2015};
    /// use sky_core::measurement::Measurement;
    /// let engerer2 = Separation::Engerer2 {
    ///     clear_global: 820.0,
    ///     solar_time: 12.5,
    ///     coefficients: ENGERER2_2015,
    /// };
    /// let r = Measurement::GlobalIrradiance(800.0).read_with(40f32.to_radians(), 172, &engerer2)?;
    /// assert!(r.diffuse_irradiance < 0.2 * 800.0);
    /// # Ok::<(), sky_core::SkyError>(())
    /// ```
    ///
    /// # Errors
    /// The bad readings of [`Measurement`], and a bad clear sky, solar time or pressure
    /// ([`decomposition::engerer2`], [`decomposition::dirint`], [`decomposition::dirindex`]).
    pub fn read_with(
        self,
        sun_zenith: f32,
        day_of_year: u32,
        separation: &Separation,
    ) -> Result<Reading, SkyError> {
        self.read_with_water(
            sun_zenith,
            day_of_year,
            separation,
            DEFAULT_PRECIPITABLE_WATER,
        )
    }

    /// [`Measurement::read_with`] with Perez's efficacies at `precipitable_water` cm (the
    /// site's: a dry site's clear light has more lumens per watt; NaN or negative counts as 0,
    /// more than 10 cm as 10, as [`Efficacy::new`] takes it).
    ///
    /// # Errors
    /// As [`Measurement::read_with`].
    pub fn read_with_water(
        self,
        sun_zenith: f32,
        day_of_year: u32,
        separation: &Separation,
        precipitable_water: f32,
    ) -> Result<Reading, SkyError> {
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
        let efficacy = |c: &SkyCondition| Efficacy::new(c, z, precipitable_water).global;
        // Global irradiance → (diffuse, direct normal): the separation by day, all diffuse at
        // night.
        let split = |g: f32| -> Result<(f32, f32), SkyError> {
            if up {
                let parts = decomposition::split(separation, g, z, i0)?;
                Ok((parts.diffuse, parts.direct_normal))
            } else {
                Ok((check_range("global irradiance [W/m²]", g, 0.0, limit)?, 0.0))
            }
        };
        let (lux, global, diffuse, direct, c) = match self {
            Self::GlobalIrradiance(g) => {
                let g = non_negative("global irradiance [W/m²]", g, THERMAL_OFFSET_LIMIT)?;
                let (d, i) = split(g)?;
                let c = condition(d, i)?;
                (g * efficacy(&c), g, d, i, c)
            }
            Self::Irradiance { global, diffuse } => {
                let g = non_negative("global irradiance [W/m²]", global, THERMAL_OFFSET_LIMIT)?;
                let d = non_negative("diffuse irradiance [W/m²]", diffuse, THERMAL_OFFSET_LIMIT)?;
                check_range("global irradiance [W/m²]", g, 0.0, limit)?;
                let mut d = diffuse_within_global(d, g, diffuse)?;
                if d == 0.0 && g > 0.0 {
                    if up && g > ZERO_DIFFUSE_MAX_GLOBAL {
                        return Err(SkyError::OutOfRange {
                            parameter: "diffuse irradiance [W/m²]",
                            value: diffuse,
                            min: f32::MIN_POSITIVE,
                            max: g,
                        });
                    }
                    // A shaded sensor's offset at night or dawn: all of it diffuse.
                    d = g;
                }
                let i = if up && z <= MAX_BEAM_ZENITH {
                    ((g - d) / math::cos(z)).max(0.0)
                } else {
                    0.0
                };
                let c = condition(if up { d } else { g }, i)?;
                (g * efficacy(&c), g, d, i, c)
            }
            Self::GlobalIlluminance(lux) => {
                let lux = non_negative("global illuminance [lx]", lux, THERMAL_OFFSET_LIMIT_LUX)?;
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
            precipitable_water,
        })
    }
}
