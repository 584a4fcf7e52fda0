//! The sun's position from a UTC time and a place on the Earth.
//!
//! Computed by NREL's Solar Position Algorithm (SPA; Reda & Andreas, *Solar position algorithm
//! for solar radiation applications*, Solar Energy 76(5), 2004) as implemented by the
//! [`solar_positioning`] crate (pure Rust, `libm`, no allocation). SPA's stated uncertainty is
//! ±0.0003° for the years −2000 to 6000; this crate accepts the years 1 to 2999, where ΔT
//! (TT − UT) has an estimate (Espenak & Meeus polynomials, through the same crate). A test holds
//! it within 0.01° of pvlib's independent SPA over dates 1950-2100 at polar, tropical and
//! mid-latitude sites of both hemispheres. The fast path, [`grena`] (Grena 2012's algorithm 5
//! in f32 with the large linear terms reduced exactly; the years 2000-2110, 0.0028° at most from
//! pvlib's SPA over 2000-2100 at latitudes ±80°, tested to 0.01°), is the controller's default ([`SunAlgorithm`]).
//!
//! # Conventions
//!
//! * **Zenith angle**: the topocentric **geometric** zenith angle (no atmospheric refraction) is
//!   what the sky models take; the refraction-corrected (apparent) one, for a standard
//!   atmosphere of 1013.25 hPa and 15 °C, is given beside it.
//! * **Compass azimuth** A: from north, clockwise seen from above, east = 90°, in `[0°, 360°)`.
//!   The crate's azimuth φ runs from +x (east) towards +y (north), so **φ = 90° − A** (mod 360°):
//!   north A = 0° is φ = 90°, east A = 90° is φ = 0°, south A = 180° is φ = 270°.

use solar_positioning::time::JulianDate;
use solar_positioning::{Location, RefractionCorrection, SolarPositions, delta_t};

use crate::error::SkyError;
use crate::geom::Sun;
use crate::math;

pub mod grena;

/// A UTC instant in the proleptic Gregorian calendar, validated.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct UtcTime {
    year: i32,
    month: u32,
    day: u32,
    hour: u32,
    minute: u32,
    second: f64,
}

/// The number of days of `month` (1-12) in `year` (proleptic Gregorian).
#[must_use]
pub fn days_in_month(year: i32, month: u32) -> u32 {
    match month {
        2 if (year % 4 == 0 && year % 100 != 0) || year % 400 == 0 => 29,
        2 => 28,
        4 | 6 | 9 | 11 => 30,
        _ => 31,
    }
}

impl UtcTime {
    /// The first year accepted.
    pub const MIN_YEAR: i32 = 1;
    /// The last year accepted (the ΔT estimate ends with the year 3000).
    pub const MAX_YEAR: i32 = 2999;

    /// The instant `year-month-day hour:minute:second` UTC; `second` in `[0, 60)` (leap seconds
    /// are not represented).
    ///
    /// # Errors
    /// [`SkyError::OutOfRange`] naming the first field outside its range (year 1-2999, month
    /// 1-12, day 1 to the month's length, hour 0-23, minute 0-59, second 0 to below 60).
    #[allow(clippy::cast_precision_loss)] // small integers, exact in f32
    pub fn new(
        year: i32,
        month: u32,
        day: u32,
        hour: u32,
        minute: u32,
        second: f64,
    ) -> Result<Self, SkyError> {
        let whole = |parameter, value: i64, min: i64, max: i64| {
            if (min..=max).contains(&value) {
                Ok(())
            } else {
                Err(SkyError::OutOfRange {
                    parameter,
                    value: value as f32,
                    min: min as f32,
                    max: max as f32,
                })
            }
        };
        whole(
            "year",
            i64::from(year),
            i64::from(Self::MIN_YEAR),
            i64::from(Self::MAX_YEAR),
        )?;
        whole("month", i64::from(month), 1, 12)?;
        whole(
            "day",
            i64::from(day),
            1,
            i64::from(days_in_month(year, month)),
        )?;
        whole("hour", i64::from(hour), 0, 23)?;
        whole("minute", i64::from(minute), 0, 59)?;
        if !(0.0..60.0).contains(&second) {
            #[allow(clippy::cast_possible_truncation)] // only for the message
            return Err(SkyError::OutOfRange {
                parameter: "second",
                value: second as f32,
                min: 0.0,
                max: 60.0,
            });
        }
        Ok(Self {
            year,
            month,
            day,
            hour,
            minute,
            second,
        })
    }

    /// The day of the year, 1 (1 January) to 365 or 366.
    ///
    /// ```
    /// use sky_core::solar::UtcTime;
    /// assert_eq!(UtcTime::new(2024, 12, 31, 0, 0, 0.0)?.day_of_year(), 366);
    /// # Ok::<(), sky_core::SkyError>(())
    /// ```
    #[must_use]
    pub fn day_of_year(&self) -> u32 {
        (1..self.month)
            .map(|m| days_in_month(self.year, m))
            .sum::<u32>()
            + self.day
    }

    /// The year.
    #[must_use]
    pub fn year(&self) -> i32 {
        self.year
    }

    /// The month, 1-12.
    #[must_use]
    pub fn month(&self) -> u32 {
        self.month
    }

    /// The day of the month, from 1.
    #[must_use]
    pub fn day(&self) -> u32 {
        self.day
    }

    /// The hour, 0-23.
    #[must_use]
    pub fn hour(&self) -> u32 {
        self.hour
    }

    /// The minute, 0-59.
    #[must_use]
    pub fn minute(&self) -> u32 {
        self.minute
    }

    /// The second, in `[0, 60)`.
    #[must_use]
    pub fn second(&self) -> f64 {
        self.second
    }
}

/// A place on the Earth: geodetic latitude and longitude in degrees, elevation in metres.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Site {
    latitude: f64,
    longitude: f64,
    elevation: f64,
}

impl Site {
    /// The lowest elevation accepted, in metres (the Dead Sea shore is at −430 m).
    pub const MIN_ELEVATION: f64 = -500.0;
    /// The highest elevation accepted, in metres.
    pub const MAX_ELEVATION: f64 = 10_000.0;

    /// A site at `latitude` in `[-90, 90]` degrees (north positive), `longitude` in
    /// `[-180, 180]` degrees (east positive) and `elevation` in
    /// [[`Self::MIN_ELEVATION`], [`Self::MAX_ELEVATION`]] metres above sea level.
    ///
    /// # Errors
    /// [`SkyError::OutOfRange`] naming the first parameter out of its range (or NaN).
    #[allow(clippy::cast_possible_truncation)] // f32 only for the error message
    pub fn new(latitude: f64, longitude: f64, elevation: f64) -> Result<Self, SkyError> {
        for (parameter, value, min, max) in [
            ("latitude [deg]", latitude, -90.0, 90.0),
            ("longitude [deg]", longitude, -180.0, 180.0),
            (
                "elevation [m]",
                elevation,
                Self::MIN_ELEVATION,
                Self::MAX_ELEVATION,
            ),
        ] {
            if !(min..=max).contains(&value) {
                return Err(SkyError::OutOfRange {
                    parameter,
                    value: value as f32,
                    min: min as f32,
                    max: max as f32,
                });
            }
        }
        Ok(Self {
            latitude,
            longitude,
            elevation,
        })
    }

    /// Latitude in degrees, north positive.
    #[must_use]
    pub fn latitude(&self) -> f64 {
        self.latitude
    }

    /// Longitude in degrees, east positive.
    #[must_use]
    pub fn longitude(&self) -> f64 {
        self.longitude
    }

    /// Elevation in metres above sea level.
    #[must_use]
    pub fn elevation(&self) -> f64 {
        self.elevation
    }
}

/// Where the sun is, seen from a site at an instant (see the module docs for the conventions).
///
/// ```
/// use sky_core::solar::{Site, SunPosition, UtcTime};
///
/// let vienna = Site::new(48.21, 16.37, 190.0)?;
/// let noon = UtcTime::new(2026, 6, 21, 11, 0, 0.0)?;
/// let p = SunPosition::new(&noon, &vienna)?;
/// assert!((p.zenith_deg() - 25.0).abs() < 1.0);          // high summer sun
/// assert!((p.azimuth_deg() - 180.0).abs() < 15.0);      // roughly south
/// let sun = p.sun();                                    // for the sky models
/// assert!((sun.zenith().to_degrees() - p.zenith_deg() as f32).abs() < 1e-3);
/// # Ok::<(), sky_core::SkyError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SunPosition {
    zenith: f64,
    /// zenith − apparent zenith, radians in f32 (what the daylight's beam takes).
    refraction: f32,
    azimuth: f64,
    sun: Sun,
}

impl SunPosition {
    /// The sun's position at `time` seen from `site`, by SPA (geometric, and refracted for a
    /// standard atmosphere). Accuracy: within 0.01° of pvlib's SPA (tested), SPA's own
    /// uncertainty being 0.0003°.
    ///
    /// # Errors
    /// Only if the algorithm fails on validated input ([`SkyError::NotFinite`] naming the sun
    /// position), which the tests have not seen.
    pub fn new(time: &UtcTime, site: &Site) -> Result<Self, SkyError> {
        let failed = |_| SkyError::NotFinite {
            parameter: "sun position (SPA)",
        };
        let dt = delta_t::estimate_from_date(time.year, time.month).map_err(failed)?;
        let jd = JulianDate::from_utc(
            time.year,
            time.month,
            time.day,
            time.hour,
            time.minute,
            time.second,
            dt,
        )
        .map_err(failed)?;
        let prepared = SolarPositions::new()
            .for_time_from_julian(jd)
            .map_err(failed)?;
        let location = Location {
            latitude: site.latitude,
            longitude: site.longitude,
        };
        let geometric = prepared
            .at(location, site.elevation, None)
            .map_err(failed)?;
        let apparent = prepared
            .at(
                location,
                site.elevation,
                Some(RefractionCorrection::standard()),
            )
            .map_err(failed)?;
        Self::from_degrees(
            geometric.zenith_angle(),
            apparent.zenith_angle(),
            geometric.azimuth(),
        )
    }

    /// The position of geometric and apparent zenith and compass azimuth in degrees, with its
    /// [`Sun`] for the sky models.
    #[allow(clippy::cast_possible_truncation)] // f64 degrees to the f32 sky models
    fn from_degrees(zenith: f64, apparent_zenith: f64, azimuth: f64) -> Result<Self, SkyError> {
        let sun = Sun::new(
            (zenith as f32).to_radians(),
            (compass_to_azimuth(azimuth) as f32).to_radians(),
        )?;
        #[allow(clippy::cast_possible_truncation)] // under a degree, to f32 radians
        let refraction = (zenith - apparent_zenith).to_radians() as f32;
        Ok(Self {
            zenith,
            refraction,
            azimuth,
            sun,
        })
    }

    /// The position of geometric zenith `zenith` in `[0, π]`, refraction `refraction` (the
    /// zenith less the apparent one) and compass azimuth `azimuth` in `[0, 2π]` (2π read as 0),
    /// radians in f32 (the fast path, [`grena`]): the [`Sun`] is computed in f32 from them, the
    /// degrees widened to f64.
    fn from_radians_f32(zenith: f32, refraction: f32, azimuth: f32) -> Result<Self, SkyError> {
        let azimuth_deg = azimuth.to_degrees();
        let azimuth_deg = if azimuth_deg >= 360.0 {
            0.0
        } else {
            azimuth_deg
        };
        // φ = 90° − A, in [0, 2π).
        let phi = core::f32::consts::FRAC_PI_2 - azimuth;
        let phi = if phi < 0.0 {
            phi + core::f32::consts::TAU
        } else {
            phi
        };
        Ok(Self {
            zenith: f64::from(zenith.to_degrees()),
            refraction,
            azimuth: f64::from(azimuth_deg),
            sun: Sun::new(zenith, phi)?,
        })
    }

    /// The topocentric geometric zenith angle in degrees, `[0, 180]`.
    #[must_use]
    pub fn zenith_deg(&self) -> f64 {
        self.zenith
    }

    /// The refraction-corrected (apparent) zenith angle in degrees, for 1013.25 hPa and 15 °C:
    /// [`Self::zenith_deg`] less [`Self::refraction`] (kept in f32 radians: SPA's refraction
    /// within 1e-7°).
    #[must_use]
    pub fn apparent_zenith_deg(&self) -> f64 {
        self.zenith - f64::from(self.refraction).to_degrees()
    }

    /// The atmospheric refraction of the sun's position, radians: the geometric zenith angle
    /// less the apparent one ([`Self::apparent_zenith_deg`]), by Sæmundsson's formula for
    /// 1013.25 hPa and 15 °C as SPA writes it (Reda & Andreas 2004, eq. 42): at most 0.62°
    /// (at −0.83°), 0.48° at the horizon, a hair below 0 with the sun overhead; 0 with the sun
    /// below −0.83°. [`Daylight::refracted`](crate::daylight::Daylight::refracted) raises the
    /// beam by it.
    #[must_use]
    pub fn refraction(&self) -> f32 {
        self.refraction
    }

    /// The geometric elevation above the horizon in degrees, 90 − zenith.
    #[must_use]
    pub fn elevation_deg(&self) -> f64 {
        90.0 - self.zenith
    }

    /// The compass azimuth in degrees: from north, clockwise, east = 90, in `[0, 360)`.
    #[must_use]
    pub fn azimuth_deg(&self) -> f64 {
        self.azimuth
    }

    /// The [`Sun`] for the sky models: the geometric zenith, and the azimuth in the crate's
    /// convention (φ = 90° − compass azimuth), in radians. It feeds
    /// [`PreethamSky::new`](crate::PreethamSky::new), [`NeuralSky::new`](crate::NeuralSky::new),
    /// [`Daylight::new`](crate::daylight::Daylight::new) (any elevation) and the AOAS sky's
    /// [`DayCycle::Sun`](crate::aoas::DayCycle::Sun); the first two reject a sun below the
    /// horizon.
    #[must_use]
    pub fn sun(&self) -> Sun {
        self.sun
    }
}

/// Which algorithm gives the sun's position.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SunAlgorithm {
    /// Grena 2012's algorithm 5 ([`grena::sun_position`]), without f64: the years 2000-2110
    /// only, within 0.003° of SPA (tested against pvlib's over 2000-2100, bound 0.01°), about
    /// 8,000 instructions on a Cortex-M4F (docs/controller.md).
    #[default]
    Fast,
    /// NREL's SPA ([`SunPosition::new`]): the years 1-2999, ±0.0003°.
    Spa,
}

impl SunAlgorithm {
    /// The sun's position at `time` seen from `site` by this algorithm.
    ///
    /// # Errors
    /// [`SkyError::OutOfRange`] for [`Self::Fast`] outside its years
    /// ([`grena::MIN_YEAR`]-[`grena::MAX_YEAR`]); as [`SunPosition::new`] for [`Self::Spa`].
    pub fn position(self, time: &UtcTime, site: &Site) -> Result<SunPosition, SkyError> {
        match self {
            Self::Fast => grena::sun_position(time, site),
            Self::Spa => SunPosition::new(time, site),
        }
    }
}

/// The crate's azimuth φ in degrees, `[0, 360)`, from a compass azimuth in degrees (from north,
/// clockwise): φ = 90° − A, wrapped.
#[must_use]
pub fn compass_to_azimuth(compass_deg: f64) -> f64 {
    let phi = libm::fmod(90.0 - compass_deg, 360.0);
    if phi < 0.0 { phi + 360.0 } else { phi }
}

/// The solar constant, W/m²: the value of the World Radiation Centre that Perez et al. 1990
/// and Erbs et al. 1982 worked with (and Radiance's gendaylit and gendaymtx use).
pub const SOLAR_CONSTANT: f32 = 1367.0;

/// The extraterrestrial irradiance on a plane facing the sun, W/m², on day `day_of_year`
/// (1-366; other values wrap): [`SOLAR_CONSTANT`] times [`earth_sun_distance_factor`].
/// Between 1322 W/m² (early July) and 1415 W/m² (early January).
///
/// ```
/// let january = sky_core::solar::extraterrestrial_irradiance(3);
/// assert!((january - 1415.0).abs() < 1.0);
/// ```
#[must_use]
pub fn extraterrestrial_irradiance(day_of_year: u32) -> f32 {
    SOLAR_CONSTANT * earth_sun_distance_factor(day_of_year)
}

/// The eccentricity correction (R₀/R)² on day `day_of_year` (1-366; other values wrap): how
/// much more sunlight reaches the top of the atmosphere than at the mean Earth-Sun distance
/// R₀ (1 AU), by Spencer's Fourier series (Spencer, *Fourier series representation of the
/// position of the sun*, Search 2(5), 1971), with the day angle Γ = 2π (n − 1) / 365:
/// 1.000110 + 0.034221 cos Γ + 0.001280 sin Γ + 0.000719 cos 2Γ + 0.000077 sin 2Γ. From
/// 0.967 (early July, aphelion) to 1.035 (early January, perihelion).
///
/// ```
/// let january = sky_core::solar::earth_sun_distance_factor(3);
/// let july = sky_core::solar::earth_sun_distance_factor(185);
/// assert!((january - 1.035).abs() < 1e-3 && (july - 0.9666).abs() < 1e-3);
/// ```
#[must_use]
#[allow(clippy::cast_precision_loss)] // day numbers are small
pub fn earth_sun_distance_factor(day_of_year: u32) -> f32 {
    let gamma = core::f32::consts::TAU * (day_of_year.saturating_sub(1) % 366) as f32 / 365.0;
    // One libm call (its f32 sine and cosine evaluate in soft f64 on an f32-only FPU): sin Γ
    // from cos Γ, its sign from the half of the year.
    let c1 = math::cos(gamma);
    let s1 = math::sqrt(math::at_least(1.0 - c1 * c1, 0.0));
    let s1 = if gamma > core::f32::consts::PI {
        -s1
    } else {
        s1
    };
    let (s2, c2) = (2.0 * s1 * c1, c1 * c1 - s1 * s1);
    1.000_11 + 0.034_221 * c1 + 0.001_280 * s1 + 0.000_719 * c2 + 0.000_077 * s2
}

/// The relative optical air mass at sun zenith angle `zenith` (radians), by Kasten's formula
/// (Kasten, *A new table and approximation formula for the relative optical air mass*, Arch.
/// Meteorol. Geophys. Bioklimatol. B 14, 1966), the one Perez et al. 1990 use:
/// m = 1 / (cos Z + 0.15 (93.885 − Z°)^−1.253). 1 at the zenith, 36.5 with the sun on the
/// horizon; the zenith is clamped to [0°, 90°] (NaN gives the horizon's value), so the result is
/// always finite.
///
/// ```
/// let m = sky_core::solar::relative_air_mass(60f32.to_radians());
/// assert!((m - 1.993).abs() < 0.001);
/// ```
#[must_use]
pub fn relative_air_mass(zenith: f32) -> f32 {
    let z = if zenith >= 0.0 {
        zenith.min(core::f32::consts::FRAC_PI_2)
    } else if zenith < 0.0 {
        0.0
    } else {
        core::f32::consts::FRAC_PI_2
    };
    1.0 / (math::cos(z) + 0.15 * math::powf(93.885 - z.to_degrees(), -1.253))
}

#[cfg(test)]
mod tests {
    /// Spencer's series with one libm cosine and the sine from it, against the series in f64
    /// with both (every day of a leap year).
    #[test]
    fn earth_sun_distance_factor_matches_the_series_in_f64() {
        for day in 1..=366u32 {
            let g = core::f64::consts::TAU * f64::from(day - 1) / 365.0;
            let f = 1.000_11
                + 0.034_221 * g.cos()
                + 0.001_280 * g.sin()
                + 0.000_719 * (2.0 * g).cos()
                + 0.000_077 * (2.0 * g).sin();
            let got = f64::from(earth_sun_distance_factor(day));
            assert!((got - f).abs() < 1e-6, "day {day}: {got} against {f}");
        }
    }

    use super::*;

    #[test]
    fn compass_mapping() {
        assert_eq!(compass_to_azimuth(0.0), 90.0); // north is +y
        assert_eq!(compass_to_azimuth(90.0), 0.0); // east is +x
        assert_eq!(compass_to_azimuth(180.0), 270.0); // south is -y
        assert_eq!(compass_to_azimuth(270.0), 180.0); // west is -x
    }

    #[test]
    fn calendar_validation() {
        assert!(UtcTime::new(2024, 2, 29, 0, 0, 0.0).is_ok());
        assert!(UtcTime::new(2023, 2, 29, 0, 0, 0.0).is_err());
        assert!(UtcTime::new(2100, 2, 29, 0, 0, 0.0).is_err());
        assert!(UtcTime::new(2000, 2, 29, 0, 0, 0.0).is_ok());
        assert!(UtcTime::new(2024, 4, 31, 0, 0, 0.0).is_err());
        assert!(UtcTime::new(2024, 1, 1, 24, 0, 0.0).is_err());
        assert!(UtcTime::new(2024, 1, 1, 0, 0, 60.0).is_err());
        assert!(UtcTime::new(2024, 1, 1, 0, 0, f64::NAN).is_err());
        assert!(UtcTime::new(3000, 1, 1, 0, 0, 0.0).is_err());
        assert!(Site::new(90.5, 0.0, 0.0).is_err());
        assert!(Site::new(0.0, f64::NAN, 0.0).is_err());
        assert!(Site::new(0.0, 0.0, 1e5).is_err());
    }

    #[test]
    fn every_accepted_instant_has_a_position() {
        // The ends of the accepted years, the poles and the date line.
        for (y, m, d, h) in [(1, 1, 1, 0), (2999, 12, 31, 23), (1582, 10, 10, 12)] {
            for (lat, lon) in [(90.0, 180.0), (-90.0, -180.0), (0.0, 0.0)] {
                let time = UtcTime::new(y, m, d, h, 59, 59.999).expect("valid");
                let site = Site::new(lat, lon, 0.0).expect("valid");
                assert!(SunPosition::new(&time, &site).is_ok(), "{time:?} {site:?}");
            }
        }
    }

    #[test]
    fn equinox_noon_at_the_equator() {
        // At the March equinox 2024 (03:06 UTC on 20 March) the declination is 0; at local solar
        // noon on the equator the sun is then nearly overhead (within the day's drift of 0.4°
        // and the equation of time's effect on the hour, about -7.5 min on that date).
        let p = SunPosition::new(
            &UtcTime::new(2024, 3, 20, 12, 7, 30.0).expect("valid"),
            &Site::new(0.0, 0.0, 0.0).expect("valid"),
        )
        .expect("computes");
        assert!(p.zenith_deg() < 0.5, "{p:?}");
    }
}
