//! The aesthetic principles of seed 004 §3.3, as the fields of [`Style`], and the named presets
//! that reproduce the paper's figures.

use core::f32::consts::{FRAC_PI_2, PI};

use glam::Vec3;

use super::clouds::CloudShapes;
use crate::error::{SkyError, check_range};
use crate::geom::{self, Sun};
use crate::math;

/// The largest ambiguity neighbourhood l_pt accepted (relative to the distance of the fragment).
pub const MAX_AMBIGUITY: f32 = 0.5;
/// The smallest cloud-noise size accepted (relative to the distance of the fragment).
pub const MIN_NOISE_SIZE: f32 = 0.01;
/// The largest cloud-noise size accepted.
pub const MAX_NOISE_SIZE: f32 = 10.0;
/// The largest sky-hue component accepted (the physical values, 1/λ⁴ with λ in µm, are 5.6 to
/// 19.6).
pub const MAX_SKY_HUE: f32 = 100.0;
/// The earliest time of day accepted, in hours (sunrise of [`DayCycle::TimeOfDay`]).
pub const SUNRISE_HOURS: f32 = 6.0;
/// The latest time of day accepted, in hours (sunset).
pub const SUNSET_HOURS: f32 = 18.0;
/// The lowest noon elevation of the sun accepted, in radians (1°).
pub const MIN_NOON_ELEVATION: f32 = 1.0 * PI / 180.0;

/// Ambiguity in the sky pattern (seed 004 §3.3, eqs. 5-6): each fragment is shaded with the sky
/// colour of a random fragment in its neighbourhood, so the sky's colours stay plausible while
/// its pattern blurs and sparkles (Fig. 9).
///
/// Eq. 6 moves the fragment by `(rand(l_pt), rand(l_pt), rand(l_pt))`, each uniform in
/// [−l_pt, l_pt]; eq. 5 takes the view direction towards the moved fragment. Here the fragment
/// is the point at unit distance from the viewer along the view (every fragment on the way
/// gives the same direction, eq. 1), so `neighbourhood` is l_pt relative to the fragment's
/// distance: about the perturbation's angle in radians. The random numbers come from a hash of
/// the fragment's direction and `seed`: a frame is reproducible, and another seed gives another
/// pattern.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Ambiguity {
    /// l_pt of eq. 6, in [0, [`MAX_AMBIGUITY`]].
    pub neighbourhood: f32,
    /// The seed of the per-fragment random generator (any value).
    pub seed: u32,
}

/// Cloud complexity in the sky pattern (seed 004 §3.3, eqs. 7-8): Improved Perlin noise (Perlin
/// 2002) scales the saturation of the sky colour in HSV (Fig. 10).
///
/// The noise is sampled at the fragment's position on the unit sphere around the viewer divided
/// by `size`: smaller sizes give smaller, more complex clouds. Eq. 8 multiplies the saturation
/// by the noise mapped to [0, 1], `(1 + noise)/2`; `strength` blends between no change (0) and
/// eq. 8 as written (1): saturation × (1 − strength · (1 − (1 + noise)/2)).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct CloudNoise {
    /// S_noise of eq. 7: the noise's feature size, in [[`MIN_NOISE_SIZE`], [`MAX_NOISE_SIZE`]],
    /// relative to the fragment's distance (about radians for small sizes).
    pub size: f32,
    /// How much the noise desaturates, in [0, 1].
    pub strength: f32,
}

/// The day cycle of the sky hue (seed 004 §3.3, Fig. 12): where the sun is.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DayCycle {
    /// The sun in this direction (zenith angle at most π/2).
    Sun(Sun),
    /// The sun at a time of day on a simple circular path: it rises due east (+x) at 6 h, culminates
    /// due south (−y) at 12 h at `noon_elevation` and sets due west at 18 h, moving uniformly on
    /// the great circle through those three points. A stylistic path, not an ephemeris.
    TimeOfDay {
        /// Hours since midnight, in [[`SUNRISE_HOURS`], [`SUNSET_HOURS`]].
        hours: f32,
        /// The sun's elevation at noon in radians, in [[`MIN_NOON_ELEVATION`], π/2].
        noon_elevation: f32,
    },
}

impl DayCycle {
    /// The sun this day cycle puts in the sky.
    ///
    /// # Errors
    /// [`SkyError::OutOfRange`] for a time or noon elevation outside its range;
    /// [`SkyError::SunBelowHorizon`] for a sun zenith above π/2.
    ///
    /// ```
    /// use sky_core::aoas::DayCycle;
    /// let noon = DayCycle::TimeOfDay { hours: 12.0, noon_elevation: 1.0 }.sun()?;
    /// assert!((noon.zenith() - (core::f32::consts::FRAC_PI_2 - 1.0)).abs() < 1e-6);
    /// assert!(noon.direction().y < 0.0); // due south
    /// # Ok::<(), sky_core::SkyError>(())
    /// ```
    pub fn sun(&self) -> Result<Sun, SkyError> {
        let sun = match *self {
            Self::Sun(sun) => sun,
            Self::TimeOfDay {
                hours,
                noon_elevation,
            } => {
                let hours = check_range(
                    "day_cycle.time_of_day [h]",
                    hours,
                    SUNRISE_HOURS,
                    SUNSET_HOURS,
                )?;
                let e = check_range(
                    "day_cycle.noon_elevation [rad]",
                    noon_elevation,
                    MIN_NOON_ELEVATION,
                    FRAC_PI_2,
                )?;
                // ω: 0 at sunrise, π/2 at noon, π at sunset.
                let w = PI * (hours - SUNRISE_HOURS) / 12.0;
                let (sw, cw) = (math::sin(w), math::cos(w));
                let dir = Vec3::new(cw, -sw * math::cos(e), sw * math::sin(e));
                let (zenith, azimuth) = geom::zenith_azimuth(dir);
                // The f32 zenith of a sun exactly on the horizon may round a hair past π/2.
                Sun::new(zenith.min(FRAC_PI_2), azimuth)?
            }
        };
        if sun.zenith() > FRAC_PI_2 {
            return Err(SkyError::SunBelowHorizon {
                zenith: sun.zenith(),
            });
        }
        Ok(sun)
    }
}

/// A sky style: the aesthetic principles of seed 004 §3.3, each one field. `None` (or no cloud
/// shapes) leaves a principle off; a style with every principle off and the physical hue is
/// O'Neil's physically based sky.
///
/// Hue principles change what is scattered (they cost nothing per direction); pattern principles
/// change the colour per fragment. Values are checked by [`AoasSky::new`](super::AoasSky::new),
/// which returns a typed error for any of them out of range.
#[derive(Debug, Clone, PartialEq)]
pub struct Style {
    /// Ambiguity in the sky pattern (eqs. 5-6), or `None`.
    pub ambiguity: Option<Ambiguity>,
    /// Cloud complexity in the sky pattern (eqs. 7-8), or `None`.
    pub cloud_noise: Option<CloudNoise>,
    /// Cloud shapes in the sky pattern.
    pub cloud_shapes: CloudShapes,
    /// More colours for the sky hue: the Rayleigh scattering constants, per channel (R, G, B),
    /// replaced by this vector, each component in [0, [`MAX_SKY_HUE`]]; `None` keeps the
    /// physical 1/λ⁴ of the [`Scattering`](super::Scattering) wavelengths.
    pub sky_hue: Option<Vec3>,
    /// The day cycle: the sun's direction or a time of day.
    pub day_cycle: DayCycle,
}

impl Default for Style {
    /// The physical sky at noon: [`Preset::Physical`].
    fn default() -> Self {
        Preset::Physical.style()
    }
}

impl Style {
    /// The named preset `preset`.
    #[must_use]
    pub fn preset(preset: Preset) -> Self {
        preset.style()
    }

    /// Checks every principle's parameters and returns the sun of the day cycle.
    pub(crate) fn validate(&self) -> Result<Sun, SkyError> {
        if let Some(a) = self.ambiguity {
            check_range(
                "ambiguity.neighbourhood",
                a.neighbourhood,
                0.0,
                MAX_AMBIGUITY,
            )?;
        }
        if let Some(n) = self.cloud_noise {
            check_range("cloud_noise.size", n.size, MIN_NOISE_SIZE, MAX_NOISE_SIZE)?;
            check_range("cloud_noise.strength", n.strength, 0.0, 1.0)?;
        }
        if let Some(h) = self.sky_hue {
            check_range("sky_hue.red", h.x, 0.0, MAX_SKY_HUE)?;
            check_range("sky_hue.green", h.y, 0.0, MAX_SKY_HUE)?;
            check_range("sky_hue.blue", h.z, 0.0, MAX_SKY_HUE)?;
        }
        self.day_cycle.sun()
    }
}

/// Named styles that reproduce the figures of seed 004.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum Preset {
    /// O'Neil's physical sky at noon, every principle off (Fig. 1, "a naturally beautiful sky").
    Physical,
    /// The physical sky just after sunrise, the sun 2° above the eastern horizon (Fig. 12, top
    /// row; Fig. 1).
    Sunrise,
    /// The physical sky just before sunset, the sun 2° above the western horizon (Fig. 12,
    /// bottom row).
    Sunset,
    /// A grey sky: equal Rayleigh constants in every channel (Fig. 11, first).
    Grey,
    /// A yellow sky (Fig. 11, second; Fig. 1).
    Yellow,
    /// A deeper blue sky than the physical one (Fig. 11, third).
    Blue,
    /// A coral sky (Fig. 11, fourth; Fig. 1).
    Coral,
    /// A yellow sky with a smiley-shaped cloud (Fig. 1, top fourth).
    Smiley,
    /// A yellow sky with a heart-shaped cloud (Fig. 1, bottom first).
    Heart,
    /// A yellow sky with subtly turbulent noise clouds (Fig. 1, top third; Fig. 10).
    Turbulent,
    /// An ambiguous coral sky (Fig. 1, bottom third; Fig. 9).
    Ambiguous,
}

/// The noon elevation of the sun in every preset's day cycle: 60°.
const PRESET_NOON_ELEVATION: f32 = PI / 3.0;

/// Sky hues of the presets (Rayleigh constants per channel R, G, B; the physical ones are
/// 5.60, 9.47, 19.64).
const GREY: Vec3 = Vec3::new(9.0, 9.0, 9.0);
const YELLOW: Vec3 = Vec3::new(16.0, 13.0, 2.5);
const BLUE: Vec3 = Vec3::new(2.0, 7.0, 30.0);
const CORAL: Vec3 = Vec3::new(22.0, 7.5, 4.5);

impl Preset {
    /// Every preset, in the order of the gallery's strip (`sky-train gallery`, docs/aoas_presets.png).
    pub const ALL: [Self; 11] = [
        Self::Physical,
        Self::Sunrise,
        Self::Sunset,
        Self::Grey,
        Self::Yellow,
        Self::Blue,
        Self::Coral,
        Self::Smiley,
        Self::Heart,
        Self::Turbulent,
        Self::Ambiguous,
    ];

    /// The preset's name, as the command line spells it (lower case).
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Self::Physical => "physical",
            Self::Sunrise => "sunrise",
            Self::Sunset => "sunset",
            Self::Grey => "grey",
            Self::Yellow => "yellow",
            Self::Blue => "blue",
            Self::Coral => "coral",
            Self::Smiley => "smiley",
            Self::Heart => "heart",
            Self::Turbulent => "turbulent",
            Self::Ambiguous => "ambiguous",
        }
    }

    /// The preset called `name` (as [`name`](Self::name) spells it; "gray" is also accepted).
    ///
    /// ```
    /// use sky_core::aoas::Preset;
    /// assert_eq!(Preset::from_name("coral"), Some(Preset::Coral));
    /// assert_eq!(Preset::from_name("mauve"), None);
    /// ```
    #[must_use]
    pub fn from_name(name: &str) -> Option<Self> {
        if name == "gray" {
            return Some(Self::Grey);
        }
        Self::ALL.into_iter().find(|p| p.name() == name)
    }

    /// The preset's style.
    #[must_use]
    pub fn style(self) -> Style {
        let at = |hours: f32| DayCycle::TimeOfDay {
            hours,
            noon_elevation: PRESET_NOON_ELEVATION,
        };
        let mut style = Style {
            ambiguity: None,
            cloud_noise: None,
            cloud_shapes: CloudShapes::new(),
            sky_hue: None,
            day_cycle: at(12.0),
        };
        match self {
            Self::Physical => {}
            Self::Sunrise => style.day_cycle = at(6.15),
            Self::Sunset => style.day_cycle = at(17.85),
            Self::Grey => style.sky_hue = Some(GREY),
            Self::Yellow => style.sky_hue = Some(YELLOW),
            Self::Blue => style.sky_hue = Some(BLUE),
            Self::Coral => style.sky_hue = Some(CORAL),
            Self::Smiley => {
                style.sky_hue = Some(YELLOW);
                style.cloud_shapes = smiley();
            }
            Self::Heart => {
                style.sky_hue = Some(YELLOW);
                style.cloud_shapes = heart();
            }
            Self::Turbulent => {
                style.sky_hue = Some(YELLOW);
                style.cloud_noise = Some(CloudNoise {
                    size: 0.12,
                    strength: 0.8,
                });
            }
            Self::Ambiguous => {
                style.sky_hue = Some(CORAL);
                style.ambiguity = Some(Ambiguity {
                    neighbourhood: 0.06,
                    seed: 2019,
                });
            }
        }
        style
    }
}

/// Where the preset cloud drawings sit: due north (away from the presets' noon sun), 30° above
/// the horizon.
const DRAWING_AZIMUTH: f32 = FRAC_PI_2;
const DRAWING_ELEVATION: f32 = PI / 6.0;

/// The direction of the point (u, v) of a drawing (radians, u to the right and v up as seen by
/// a viewer facing the drawing), by the gnomonic projection about the drawing's centre.
fn drawing_point(u: f32, v: f32) -> Vec3 {
    let centre = geom::direction(FRAC_PI_2 - DRAWING_ELEVATION, DRAWING_AZIMUTH);
    let right = centre.cross(Vec3::Z).normalize();
    let up = right.cross(centre);
    centre + right * u + up * v
}

/// Points of the circular arc of radius `r` about (u, v), from angle `a0` to `a1` (radians,
/// counter-clockwise from the right), as `N` points.
fn arc<const N: usize>(cu: f32, cv: f32, r: f32, a0: f32, a1: f32) -> [Vec3; N] {
    #[allow(clippy::cast_precision_loss)] // small N
    core::array::from_fn(|k| {
        let a = a0 + (a1 - a0) * k as f32 / (N - 1) as f32;
        drawing_point(cu + r * math::cos(a), cv + r * math::sin(a))
    })
}

/// Fig. 1's smiley: a face, two eyes and a smile (21 + 1 + 1 + 9 points: 30 segments).
fn smiley() -> CloudShapes {
    let mut c = CloudShapes::new();
    let (line, fade) = (0.02, 0.03);
    // The presets' shapes fit the capacity, and their parameters are valid (a unit test checks
    // both), so these pushes cannot fail.
    let _ = c.push_polyline(&arc::<21>(0.0, 0.0, 0.25, 0.0, 2.0 * PI), line, fade);
    let _ = c.push_point(drawing_point(-0.085, 0.07), 0.025, fade);
    let _ = c.push_point(drawing_point(0.085, 0.07), 0.025, fade);
    let _ = c.push_polyline(&arc::<9>(0.0, 0.02, 0.15, 1.15 * PI, 1.85 * PI), line, fade);
    c
}

/// Fig. 1's heart: the curve (16 sin³t, 13 cos t − 5 cos 2t − 2 cos 3t − cos 4t), 25 points.
fn heart() -> CloudShapes {
    const N: usize = 25;
    let scale = 0.26 / 16.0;
    #[allow(clippy::cast_precision_loss)] // small N
    let points: [Vec3; N] = core::array::from_fn(|k| {
        let t = 2.0 * PI * k as f32 / (N - 1) as f32;
        let s = math::sin(t);
        let x = 16.0 * s * s * s;
        let y = 13.0 * math::cos(t)
            - 5.0 * math::cos(2.0 * t)
            - 2.0 * math::cos(3.0 * t)
            - math::cos(4.0 * t);
        drawing_point(scale * x, scale * (y + 2.0))
    });
    let mut c = CloudShapes::new();
    // Fits and is valid (unit test).
    let _ = c.push_polyline(&points, 0.02, 0.035);
    c
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip() {
        for p in Preset::ALL {
            assert_eq!(Preset::from_name(p.name()), Some(p));
        }
        assert_eq!(Preset::from_name("gray"), Some(Preset::Grey));
        assert_eq!(Preset::from_name("Physical"), None);
    }

    #[test]
    fn every_preset_is_valid_and_drawings_are_complete() {
        for p in Preset::ALL {
            if let Err(e) = p.style().validate() {
                panic!("{}: {e}", p.name());
            }
        }
        assert_eq!(smiley().len(), 20 + 1 + 1 + 8);
        assert_eq!(heart().len(), 24);
    }

    #[test]
    fn time_of_day_follows_the_sun_path() {
        let sun = |hours| {
            DayCycle::TimeOfDay {
                hours,
                noon_elevation: 0.5,
            }
            .sun()
        };
        let rise = sun(6.0).expect("valid").direction();
        assert!((rise - Vec3::X).length() < 1e-6, "{rise}");
        let set = sun(18.0).expect("valid").direction();
        assert!((set + Vec3::X).length() < 1e-6, "{set}");
        let noon = sun(12.0).expect("valid");
        assert!((noon.zenith() - (FRAC_PI_2 - 0.5)).abs() < 1e-6);
        assert!((noon.azimuth() - 1.5 * PI).abs() < 1e-6);
        // Symmetric about noon.
        let (a, b) = (sun(9.0).expect("valid"), sun(15.0).expect("valid"));
        assert!((a.zenith() - b.zenith()).abs() < 1e-6);
        for (hours, e) in [(5.9, 1.0), (18.1, 1.0), (f32::NAN, 1.0)] {
            assert!(matches!(
                DayCycle::TimeOfDay {
                    hours,
                    noon_elevation: e
                }
                .sun(),
                Err(SkyError::OutOfRange {
                    parameter: "day_cycle.time_of_day [h]",
                    ..
                })
            ));
        }
        for e in [0.0, 1.6, f32::NAN] {
            assert!(matches!(
                DayCycle::TimeOfDay {
                    hours: 12.0,
                    noon_elevation: e
                }
                .sun(),
                Err(SkyError::OutOfRange {
                    parameter: "day_cycle.noon_elevation [rad]",
                    ..
                })
            ));
        }
        let low = Sun::new(1.7, 0.0).expect("valid sun");
        assert_eq!(
            DayCycle::Sun(low).sun(),
            Err(SkyError::SunBelowHorizon { zenith: 1.7 })
        );
    }
}
