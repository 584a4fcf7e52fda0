//! The clear sky's radiance per view direction, for rendering and for a skylight panel's cone of
//! view: three 6-24-3 neural skies (seed 000's network, [`NeuralSky`]), for the day (sun zenith
//! 0° to 90°), dusk (84° to 98°) and night (94° to 108°), each fading into the next linearly in
//! the sun zenith over [`BLENDS`]. `sky-train daylight-sky` trained them on the physical
//! atmosphere's radiance divided by its own diffuse horizontal illuminance (the sky's **shape**:
//! π L_c(ω) / E_d,c per CIE X, Y, Z channel); sky-core multiplies by the diffuse illuminance of
//! [`Daylight`]'s tables (the **brightness**, which spans eight orders of magnitude from noon to
//! the end of twilight).

use glam::Vec3;

use super::Daylight;
use crate::color;
use crate::geom::Sun;
use crate::math;
use crate::neural::{NeuralSky, NeuralWeights, pretrained};

/// Hidden neurons of each shipped network ([`pretrained::DAYLIGHT_DAY`],
/// [`pretrained::DAYLIGHT_DUSK`], [`pretrained::DAYLIGHT_NIGHT`]; `docs/daylight.md` has the
/// size study that chose them).
pub const HIDDEN: usize = 24;

const DEG: f32 = core::f32::consts::PI / 180.0;

/// The sun zenith intervals, radians, over which the day's network hands over to dusk's (86° to
/// 90°) and dusk's to night's (96° to 98°).
pub const BLENDS: [(f32, f32); 2] = [(86.0 * DEG, 90.0 * DEG), (96.0 * DEG, 98.0 * DEG)];

/// The largest sun zenith angle the networks were trained for, radians (108°: the sun 18° below
/// the horizon, the end of astronomical twilight); lower suns draw its sky, as [`Daylight`]
/// keeps its −18° values.
pub const MAX_SUN_ZENITH: f32 = 108.0 * DEG;

/// The networks in order of the sun zenith.
const NETWORKS: [&NeuralWeights<HIDDEN>; 3] = [
    &pretrained::DAYLIGHT_DAY,
    &pretrained::DAYLIGHT_DUSK,
    &pretrained::DAYLIGHT_NIGHT,
];

/// One network's part of a sky: the network (`None` were it to fail: a uniform sky) and
/// E_d,c / π times its blend weight, cd/m².
type Share = (Option<NeuralSky<HIDDEN>>, Vec3);

/// The sky of one [`Daylight`] (sun and aerosol optical depth): [`Daylight::sky`].
///
/// Error against sky-train's physical reference at sun elevations and optical depths not
/// trained on (`tests/tests/daylight.rs`): NRMSE per image (each normalised by its own range,
/// as seed 000 does) at most 0.02 from −6° to 90°.
///
/// ```
/// use sky_core::daylight::Daylight;
/// use sky_core::{geom, Sun};
///
/// let day = Daylight::clear(Sun::new(40f32.to_radians(), 0.0)?);
/// let sky = day.sky();
/// let zenith = sky.xyz(geom::direction(0.0, 0.0)); // CIE X, Y, Z, cd/m²
/// assert!(zenith.y > 2_000.0 && zenith.z > zenith.y); // a bright, blue sky
/// let towards = sky.xyz(geom::direction(60f32.to_radians(), 0.0)); // the sun's azimuth
/// let away = sky.xyz(geom::direction(60f32.to_radians(), 3.1));
/// assert!(towards.y > away.y, "{towards} {away}");
/// assert_eq!(sky.xyz(geom::direction(2.0, 0.0)), sky_core::Vec3::ZERO); // below the horizon
/// # Ok::<(), sky_core::SkyError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DaylightSky {
    /// The one or two networks with a positive weight at this sun; the second's scale is zero
    /// when one suffices.
    shares: [Share; 2],
}

impl Daylight {
    /// The sky's radiance for this sun and atmosphere ([`DaylightSky`]).
    #[must_use]
    pub fn sky(&self) -> DaylightSky {
        let sun = self.sun();
        let zenith = math::at_most(sun.zenith(), MAX_SUN_ZENITH);
        // The blend interval the sun is in or past: network `i` alone before interval i,
        // networks i and i + 1 inside it.
        let mut i = 0;
        while i < BLENDS.len() && zenith >= BLENDS[i].1 {
            i += 1;
        }
        let w = BLENDS.get(i).map_or(0.0, |&(lo, hi)| {
            math::at_most(math::at_least((zenith - lo) / (hi - lo), 0.0), 1.0)
        });
        let aod = self.aerosol_optical_depth();
        let scale = self.diffuse() * core::f32::consts::FRAC_1_PI;
        // The shipped weights are finite and `Daylight` holds an optical depth and a sun in
        // their ranges, so no network fails; were one to, its share of the sky is uniform.
        let share = |k: usize, weight: f32| -> Share {
            let network = NETWORKS.get(k).and_then(|weights| {
                Sun::new(zenith, sun.azimuth())
                    .and_then(|s| NeuralSky::new(weights, s, aod))
                    .ok()
            });
            (network, scale * weight)
        };
        DaylightSky {
            shares: if w > 0.0 {
                [share(i, 1.0 - w), share(i + 1, w)]
            } else {
                [share(i, 1.0), (None, Vec3::ZERO)]
            },
        }
    }
}

impl DaylightSky {
    /// CIE 1931 X, Y, Z radiance towards `dir` (+z up, any length), cd/m² (Y is the
    /// luminance). Zero below the horizon (dir.z < 0: the ground, not the sky) and for a zero or
    /// non-finite `dir`. Finite and non-negative for every input; the error bound is the type's.
    #[must_use]
    pub fn xyz(&self, dir: Vec3) -> Vec3 {
        let dir = dir.normalize_or_zero();
        if dir.z < 0.0 || dir == Vec3::ZERO {
            return Vec3::ZERO;
        }
        self.shares
            .iter()
            .fold(Vec3::ZERO, |sum, (network, scale)| {
                sum + match network {
                    Some(n) => n.rgb(dir) * *scale,
                    None => *scale,
                }
            })
    }

    /// Linear sRGB radiance towards `dir`, cd/m² scale: [`Self::xyz`] through the sRGB matrix.
    /// Twilight's deep blue lies outside the sRGB gamut: a channel may be negative there, as the
    /// colour is (clamp for display).
    #[must_use]
    pub fn rgb(&self, dir: Vec3) -> Vec3 {
        color::xyz_to_linear_srgb(self.xyz(dir))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom;

    fn sky(zenith: f32, aod: f32) -> DaylightSky {
        Sun::new(zenith, 0.4)
            .and_then(|s| Daylight::new(s, aod))
            .map(|d| d.sky())
            .unwrap_or_else(|_| unreachable!("in range"))
    }

    /// Every sun zenith 0° to 180° and optical depth of the range, every kind of direction:
    /// finite, non-negative radiance, and every network builds.
    #[test]
    fn finite_and_non_negative_everywhere() {
        let dirs = [
            geom::direction(0.0, 0.0),
            geom::direction(1.0, 2.0),
            geom::direction(1.57, -1.0),
            Vec3::new(1e-20, 0.0, 1e-20),
            Vec3::new(1e20, 0.0, 1e20),
            Vec3::ZERO,
            Vec3::splat(f32::NAN),
            Vec3::new(f32::INFINITY, 0.0, 1.0),
        ];
        for i in 0..=360 {
            #[allow(clippy::cast_precision_loss)]
            let zenith = 0.5 * DEG * i as f32;
            for aod in [0.05, 0.3, 0.8] {
                let s = sky(zenith, aod);
                assert!(s.shares.iter().all(|(n, _)| n.is_some()) || s.shares[1].1 == Vec3::ZERO);
                assert!(s.shares[0].0.is_some(), "{zenith} {aod}");
                for d in dirs {
                    let c = s.xyz(d);
                    assert!(
                        c.is_finite() && c.min_element() >= 0.0,
                        "{zenith} {aod} {d}: {c}"
                    );
                }
            }
        }
    }

    /// The blend leaves no step in the sky's shape (its radiance over its diffuse illuminance:
    /// the brightness itself falls by up to 0.1 % over 2e-5 rad in twilight) as the sun crosses
    /// the ends of each blend interval: within 0.1 % over 2e-5 rad, where handing over abruptly
    /// would jump by the networks' difference (a few per cent).
    #[test]
    fn continuous_across_the_blends() {
        let shape = |z: f32, d: Vec3| {
            let day = Sun::new(z, 0.4)
                .and_then(|s| Daylight::new(s, 0.2))
                .unwrap_or_else(|_| unreachable!("in range"));
            day.sky().xyz(d) / day.diffuse().y
        };
        for (lo, hi) in BLENDS {
            for z in [lo, hi] {
                for d in [geom::direction(0.3, 0.0), geom::direction(1.5, 0.4)] {
                    let (ca, cb) = (shape(z - 1e-5, d), shape(z + 1e-5, d));
                    assert!((ca - cb).length() <= 1e-3 * ca.length(), "{z}: {ca} {cb}");
                }
            }
        }
    }
}
