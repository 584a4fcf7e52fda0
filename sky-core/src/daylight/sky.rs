//! The clear sky's radiance per view direction, for rendering and for a skylight panel's cone of
//! view: three 6-24-3 neural skies (seed 000's network, [`NeuralSky`]), for the day (sun zenith
//! 0° to 90°), dusk (84° to 98°) and night (94° to 108°), each fading into the next linearly in
//! the sun zenith over [`BLENDS`]. `sky-train daylight-sky` trained them on the physical
//! atmosphere's radiance divided by its own diffuse horizontal illuminance (the sky's **shape**:
//! π L_c(ω) / E_d,c per CIE X, Y, Z channel); sky-core multiplies by the diffuse illuminance of
//! [`Daylight`]'s tables (the **brightness**, which spans eight orders of magnitude from noon to
//! the end of twilight).

#[cfg(target_arch = "x86_64")]
mod avx2;

use glam::Vec3;

use super::Daylight;
use crate::color;
use crate::geom::{self, Sun};
use crate::math;
use crate::neural::{NeuralSky, NeuralWeights, STEP_BY_STEP, pretrained};

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

/// Directions evaluated together by [`DaylightSky::xyz_batch`]: those of
/// [`NeuralSky::rgb_batch`] (32, each step for every lane before the next; in WebAssembly 16,
/// one direction's chain after another).
const LANES: usize = if STEP_BY_STEP { 32 } else { 16 };

impl DaylightSky {
    /// CIE 1931 X, Y, Z radiance towards `dir` (+z up, any length), cd/m² (Y is the
    /// luminance). Zero below the horizon (the ground, not the sky: the crate's rule,
    /// [`geom::below_horizon`](crate::geom::below_horizon)) and for a zero or non-finite `dir`. Finite and non-negative for every input; the error bound is the type's.
    #[must_use]
    pub fn xyz(&self, dir: Vec3) -> Vec3 {
        let [x, y, z] = self.xyz_lanes::<1>([dir.x], [dir.y], [dir.z]);
        Vec3::new(x[0], y[0], z[0])
    }

    /// Linear sRGB radiance towards `dir`, cd/m² scale: [`Self::xyz`] through the sRGB matrix.
    /// Twilight's deep blue lies outside the sRGB gamut: a channel may be negative there, as the
    /// colour is (clamp for display).
    #[must_use]
    pub fn rgb(&self, dir: Vec3) -> Vec3 {
        let [r, g, b] = srgb_lanes(self.xyz_lanes::<1>([dir.x], [dir.y], [dir.z]));
        Vec3::new(r[0], g[0], b[0])
    }

    /// [`xyz`](Self::xyz) for many directions: fills `out[i]` for every `i` below
    /// `min(dirs.len(), out.len())`, with the same results as `xyz` bit for bit (X, Y, Z,
    /// cd/m²; zero below the horizon and for zero or non-finite directions). Directions are
    /// evaluated in the lanes of [`NeuralSky::rgb_batch`]: one network outside the [`BLENDS`],
    /// two inside them.
    ///
    /// On x86-64 CPUs with AVX2 and FMA, [`xyz_batch_avx2`](Self::xyz_batch_avx2) is faster
    /// (three times this function built for the baseline, twice it built for AVX2: `sky-train
    /// bench`), with the same accuracy but not the same bits.
    ///
    /// ```
    /// use sky_core::daylight::Daylight;
    /// use sky_core::{geom, Sun, Vec3};
    ///
    /// // The sun 2° above the horizon: inside the day-to-dusk blend, two networks mixed.
    /// let sky = Daylight::clear(Sun::new(88f32.to_radians(), 0.0)?).sky();
    /// let dirs: Vec<Vec3> = (0..100).map(|i| geom::direction(0.016 * i as f32, 0.3)).collect();
    /// let mut out = vec![Vec3::ZERO; dirs.len()];
    /// sky.xyz_batch(&dirs, &mut out);
    /// assert_eq!(out[42], sky.xyz(dirs[42]));
    /// assert_eq!(out[99], Vec3::ZERO); // 1.584 rad: below the horizon
    ///
    /// // The AVX2 + FMA kernel where the CPU has it (on x86-64):
    /// # #[cfg(target_arch = "x86_64")]
    /// if is_x86_feature_detected!("avx2") && is_x86_feature_detected!("fma") {
    ///     let mut fast = vec![Vec3::ZERO; dirs.len()];
    ///     // SAFETY: the CPU has AVX2 and FMA.
    ///     unsafe { sky.xyz_batch_avx2(&dirs, &mut fast) };
    ///     let one = sky.xyz(dirs[42]);
    ///     assert!((fast[42] - one).abs().max_element() <= 4e-4 * one.max_element());
    ///     assert_eq!(fast[99], Vec3::ZERO);
    /// }
    /// # Ok::<(), sky_core::SkyError>(())
    /// ```
    #[inline(always)]
    pub fn xyz_batch(&self, dirs: &[Vec3], out: &mut [Vec3]) {
        self.batch::<false>(dirs, out);
    }

    /// [`rgb`](Self::rgb) for many directions: [`xyz_batch`](Self::xyz_batch) through the sRGB
    /// matrix, the same results as `rgb` bit for bit.
    #[inline(always)]
    pub fn rgb_batch(&self, dirs: &[Vec3], out: &mut [Vec3]) {
        self.batch::<true>(dirs, out);
    }

    /// The sky's parts, in the order [`xyz`](Self::xyz) sums them: per part a network (its
    /// output the sky's shape per CIE X, Y, Z; `None` for a uniform shape of 1, which the
    /// shipped weights never give) and its factor, E_d,c / π times the network's blend weight
    /// (X, Y, Z, cd/m²). The second part's factor is zero outside the [`BLENDS`]. For GPU
    /// shaders (sky-gpu) that take these as uniforms and evaluate the networks per direction.
    #[must_use]
    pub fn shares(&self) -> [(Option<&NeuralSky<HIDDEN>>, Vec3); 2] {
        self.shares.each_ref().map(|(n, s)| (n.as_ref(), *s))
    }

    /// Fills `out` with [`Self::xyz_lanes`] (through [`srgb_lanes`] if `SRGB`), [`LANES`]
    /// directions at a time, the last group padded with zero directions (each lane's result
    /// is its own, so the padding changes nothing, and the batch needs no second copy of the
    /// kernel for single directions: 1.2 KB of WebAssembly).
    #[inline(always)]
    fn batch<const SRGB: bool>(&self, dirs: &[Vec3], out: &mut [Vec3]) {
        let n = dirs.len().min(out.len());
        for (d, o) in dirs[..n].chunks(LANES).zip(out[..n].chunks_mut(LANES)) {
            let (mut x, mut y, mut z) = ([0.0; LANES], [0.0; LANES], [0.0; LANES]);
            for (i, dir) in d.iter().enumerate() {
                (x[i], y[i], z[i]) = (dir.x, dir.y, dir.z);
            }
            let xyz = self.xyz_lanes(x, y, z);
            let [a, b, c] = if SRGB { srgb_lanes(xyz) } else { xyz };
            for (i, slot) in o.iter_mut().enumerate() {
                *slot = Vec3::new(a[i], b[i], c[i]);
            }
        }
    }

    /// X, Y, Z for `L` directions given as coordinate lanes, without a branch on the data:
    /// every lane performs the same operations in the same order whatever `L` is, so one
    /// direction and a batch give identical results.
    #[inline(always)]
    fn xyz_lanes<const L: usize>(&self, x: [f32; L], y: [f32; L], z: [f32; L]) -> [[f32; L]; 3] {
        // A direction only where |dir|² is finite and positive; brought to unit length
        // (within 3e-7: the networks normalise it once more), so that any length is one; the
        // sky only where it is not below the horizon (`geom::below_horizon`: z ≥ −1e-6).
        let mut norm2 = [0.0; L];
        for i in 0..L {
            norm2[i] = x[i] * x[i] + y[i] * y[i] + z[i] * z[i];
        }
        let inv = math::rsqrt_lanes(norm2);
        let (mut vx, mut vy, mut vz) = ([0.0; L], [0.0; L], [0.0; L]);
        let mut sky = [false; L];
        for i in 0..L {
            let valid = norm2[i] > 0.0 && norm2[i] < f32::INFINITY;
            (vx[i], vy[i], vz[i]) = if valid {
                (x[i] * inv[i], y[i] * inv[i], z[i] * inv[i])
            } else {
                (0.0, 0.0, 0.0)
            };
            sky[i] = valid && vz[i] >= -geom::HORIZON_TOLERANCE;
        }
        // The shares: each network's output times its E_d,c / π times its weight.
        let mut sum = [[0.0; L]; 3];
        for (network, scale) in &self.shares {
            match network {
                Some(n) => {
                    let shape = n.rgb_lanes::<L, STEP_BY_STEP>(vx, vy, vz);
                    for c in 0..3 {
                        for i in 0..L {
                            sum[c][i] += shape[c][i] * scale[c];
                        }
                    }
                }
                None => {
                    for c in 0..3 {
                        for i in 0..L {
                            sum[c][i] += scale[c];
                        }
                    }
                }
            }
        }
        for channel in &mut sum {
            for i in 0..L {
                channel[i] = if sky[i] { channel[i] } else { 0.0 };
            }
        }
        sum
    }
}

/// Linear sRGB from X, Y, Z lanes: [`color::XYZ_TO_LINEAR_SRGB`] (seed 002 eq. 28), each
/// channel summed in the order of the matrix's columns, as `Mat3 * Vec3` does.
#[inline(always)]
fn srgb_lanes<const L: usize>([x, y, z]: [[f32; L]; 3]) -> [[f32; L]; 3] {
    let m = color::XYZ_TO_LINEAR_SRGB;
    let mut out = [[0.0; L]; 3];
    for (c, channel) in out.iter_mut().enumerate() {
        let (mx, my, mz) = (m.x_axis[c], m.y_axis[c], m.z_axis[c]);
        for i in 0..L {
            channel[i] = mx * x[i] + my * y[i] + mz * z[i];
        }
    }
    out
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

    /// The batch gives what one direction gives, bit for bit, for suns outside the blends (by
    /// day, at night and below −18°), inside both blends and at their ends, and for directions
    /// at the zenith, on and just below the horizon, below it, unnormalised, zero, infinite and
    /// NaN, spread over whole lane groups and a remainder.
    #[test]
    fn batch_equals_one_direction_bit_for_bit() {
        let special = [
            Vec3::Z,
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.3, -0.7, -0.0),
            Vec3::new(0.6, 0.8, -1e-7),
            Vec3::new(0.0, 0.0, -1.0),
            Vec3::new(3.0, -2.0, 5.0),
            Vec3::new(1e-20, 0.0, 1e-20),
            Vec3::new(1e20, 0.0, 1e20),
            Vec3::new(1e19, 0.0, -1e-40),
            Vec3::ZERO,
            Vec3::splat(f32::NAN),
            Vec3::new(f32::INFINITY, 0.0, 1.0),
        ];
        // 150 directions: four lane groups of 32 (nine of 16 in WebAssembly) and a remainder.
        #[allow(clippy::cast_precision_loss)]
        let dirs: [Vec3; 150] = core::array::from_fn(|i| match i % 5 {
            4 => special[(i / 5) % special.len()],
            _ => geom::direction(0.011 * i as f32, 0.7 * i as f32),
        });
        let zeniths = [
            0.0, 40.0, 85.0, 86.0, 88.0, 89.99, 90.0, 93.0, 96.0, 97.0, 98.0, 103.0, 108.0, 150.0,
        ];
        let bits = |v: Vec3| v.to_array().map(f32::to_bits);
        for zenith in zeniths {
            for aod in [0.05, 0.43] {
                let s = sky(zenith * DEG, aod);
                let (mut xyz, mut rgb) = ([Vec3::ONE; 150], [Vec3::ONE; 150]);
                s.xyz_batch(&dirs, &mut xyz);
                s.rgb_batch(&dirs, &mut rgb);
                for (i, d) in dirs.iter().enumerate() {
                    assert_eq!(bits(xyz[i]), bits(s.xyz(*d)), "{zenith} {aod} {d}");
                    assert_eq!(bits(rgb[i]), bits(s.rgb(*d)), "{zenith} {aod} {d}");
                }
                // The horizon is the sky's, not the ground's, down to the crate's tolerance
                // (z = -1e-7 is on it); below it, nothing. (Direction 5k + 4 is special[k].)
                assert!(xyz[4].y > 0.0, "zenith, {zenith}");
                assert!(
                    xyz[9].y > 0.0 && xyz[14].y > 0.0 && xyz[19].y > 0.0,
                    "horizon, {zenith}"
                );
                assert_eq!(xyz[24], Vec3::ZERO, "below, {zenith}");
            }
        }
        // A shorter output fills only its own length.
        let s = sky(88.0 * DEG, 0.2);
        let mut short = [Vec3::ONE; 3];
        s.rgb_batch(&dirs, &mut short);
        assert_eq!(short.map(bits), [0, 1, 2].map(|i| bits(s.rgb(dirs[i]))));
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
