//! Rotation of SH coefficients about the zenith (seed 001, §3.2, eq. 4).
//!
//! Turning a sky by the angle α about +z (so that what was at azimuth φ moves to φ + α, e.g. a
//! sun at azimuth 0 to azimuth α) maps the coefficients of the basis in
//! [`basis`](super::basis) as
//!
//! ```text
//! c'_lm = c_lm cos(|m| α) − sgn(m) c_l,−m sin(|m| α),   m ≠ 0     (eq. 4)
//! ```
//!
//! and leaves the zonal coefficients (m = 0) alone. Derivation for this basis: the turned
//! function is `f(θ, φ − α)`; with `Y_lm ∝ cos mφ` and `Y_l,−m ∝ sin mφ` (m > 0),
//! `cos m(φ − α) = cos mφ cos mα + sin mφ sin mα` and `sin m(φ − α) = sin mφ cos mα − cos mφ sin mα`,
//! so `c'_lm = c_lm cos mα − c_l,−m sin mα` and `c'_l,−m = c_l,−m cos mα + c_lm sin mα`, which is
//! eq. 4 for both signs of m. No error is introduced beyond f32 rounding.

use glam::Vec3;

use super::basis::{MAX_BANDS, MAX_COEFFICIENTS, index};
use crate::math;

/// Turns the first `bands` bands of `c` by `angle` radians about +z, in place (eq. 4).
///
/// ```
/// use sky_core::Vec3;
/// use sky_core::sh::{basis::index, rotation::rotate_about_zenith};
/// let mut c = [Vec3::ZERO; 49];
/// c[index(1, 1)] = Vec3::ONE; // a lobe towards +x
/// rotate_about_zenith(&mut c, 2, core::f32::consts::FRAC_PI_2);
/// assert!((c[index(1, -1)] - Vec3::ONE).length() < 1e-6); // now towards +y
/// assert!(c[index(1, 1)].length() < 1e-6);
/// ```
#[inline]
pub fn rotate_about_zenith(c: &mut [Vec3; MAX_COEFFICIENTS], bands: usize, angle: f32) {
    let bands = bands.min(MAX_BANDS);
    let (s1, c1) = (math::sin(angle), math::cos(angle));
    // cos mα + i sin mα = (cos α + i sin α)^m.
    let (mut cm, mut sm) = (1.0f32, 0.0f32);
    for m in 1..bands {
        (cm, sm) = (cm * c1 - sm * s1, sm * c1 + cm * s1);
        #[allow(clippy::cast_possible_wrap)] // m ≤ 6
        let mi = m as isize;
        for l in m..bands {
            let (pos, neg) = (index(l, mi), index(l, -mi));
            let (a, b) = (c[pos], c[neg]);
            c[pos] = a * cm - b * sm;
            c[neg] = b * cm + a * sm;
        }
    }
}
