//! Deterministic randomness for the style principles: Improved Perlin noise (Perlin 2002) for
//! cloud complexity (seed 004, eq. 7) and a hash-based generator for ambiguity (eq. 6).
//!
//! Both are pure functions of their inputs: no state, no allocation, the same values on every
//! target, so a frame renders the same every time.

use crate::math;

/// Ken Perlin's permutation of 0..=255 ("Improving Noise", SIGGRAPH 2002, and its reference
/// implementation). The reference doubles it to 512 entries; indexing modulo 256 is the same.
const PERMUTATION: [u8; 256] = [
    151, 160, 137, 91, 90, 15, 131, 13, 201, 95, 96, 53, 194, 233, 7, 225, 140, 36, 103, 30, 69,
    142, 8, 99, 37, 240, 21, 10, 23, 190, 6, 148, 247, 120, 234, 75, 0, 26, 197, 62, 94, 252, 219,
    203, 117, 35, 11, 32, 57, 177, 33, 88, 237, 149, 56, 87, 174, 20, 125, 136, 171, 168, 68, 175,
    74, 165, 71, 134, 139, 48, 27, 166, 77, 146, 158, 231, 83, 111, 229, 122, 60, 211, 133, 230,
    220, 105, 92, 41, 55, 46, 245, 40, 244, 102, 143, 54, 65, 25, 63, 161, 1, 216, 80, 73, 209, 76,
    132, 187, 208, 89, 18, 169, 200, 196, 135, 130, 116, 188, 159, 86, 164, 100, 109, 198, 173,
    186, 3, 64, 52, 217, 226, 250, 124, 123, 5, 202, 38, 147, 118, 126, 255, 82, 85, 212, 207, 206,
    59, 227, 47, 16, 58, 17, 182, 189, 28, 42, 223, 183, 170, 213, 119, 248, 152, 2, 44, 154, 163,
    70, 221, 153, 101, 155, 167, 43, 172, 9, 129, 22, 39, 253, 19, 98, 108, 110, 79, 113, 224, 232,
    178, 185, 112, 104, 218, 246, 97, 228, 251, 34, 242, 193, 238, 210, 144, 12, 191, 179, 162,
    241, 81, 51, 145, 235, 249, 14, 239, 107, 49, 192, 214, 31, 181, 199, 106, 157, 184, 84, 204,
    176, 115, 121, 50, 45, 127, 4, 150, 254, 138, 236, 205, 93, 222, 114, 67, 29, 24, 72, 243, 141,
    128, 195, 78, 66, 215, 61, 156, 180,
];

/// Inputs are clamped to ±this (NaN to its negative), so the lattice index stays exact and the
/// result finite; the noise repeats every 256 units, so nothing is lost.
const MAX_COORDINATE: f32 = 1.0e6;

#[inline(always)]
fn perm(i: i32) -> i32 {
    #[allow(clippy::cast_sign_loss)] // masked to 0..=255
    i32::from(PERMUTATION[(i & 255) as usize])
}

/// Perlin 2002's fade curve 6t⁵ − 15t⁴ + 10t³ (its first and second derivatives vanish at 0
/// and 1, the first of the paper's two improvements).
#[inline(always)]
fn fade(t: f32) -> f32 {
    t * t * t * (t * (t * 6.0 - 15.0) + 10.0)
}

#[inline(always)]
fn lerp(t: f32, a: f32, b: f32) -> f32 {
    a + t * (b - a)
}

/// The dot product of (x, y, z) with one of the 12 directions to the edge midpoints of a cube
/// (the paper's second improvement), chosen by the low 4 bits of `hash` (16 cases, 4 repeated).
#[inline(always)]
fn grad(hash: i32, x: f32, y: f32, z: f32) -> f32 {
    let h = hash & 15;
    let u = if h < 8 { x } else { y };
    let v = if h < 4 {
        y
    } else if h == 12 || h == 14 {
        x
    } else {
        z
    };
    (if h & 1 == 0 { u } else { -u }) + (if h & 2 == 0 { v } else { -v })
}

/// Improved Perlin noise at (x, y, z), in [-1, 1] (Perlin 2002). Zero at every integer lattice
/// point; continuous with continuous first and second derivatives; period 256 in each axis.
/// Agrees with Perlin's f64 reference implementation to 1e-6 (tested at published values).
/// NaN and huge inputs give a finite value.
#[allow(clippy::cast_possible_truncation, clippy::many_single_char_names)]
pub(crate) fn improved_perlin(x: f32, y: f32, z: f32) -> f32 {
    #[allow(clippy::manual_clamp)] // clamp would pass NaN through
    let clamp = |v: f32| v.max(-MAX_COORDINATE).min(MAX_COORDINATE);
    let (x, y, z) = (clamp(x), clamp(y), clamp(z));
    let (fx, fy, fz) = (math::floor(x), math::floor(y), math::floor(z));
    // The unit cube that contains the point (exact: |fx| ≤ 1e6 < 2²⁴), and the point in it.
    let (cx, cy, cz) = (fx as i32 & 255, fy as i32 & 255, fz as i32 & 255);
    let (x, y, z) = (x - fx, y - fy, z - fz);
    let (u, v, w) = (fade(x), fade(y), fade(z));
    // Hashes of the cube's 8 corners, as in the reference implementation.
    let a = perm(cx) + cy;
    let aa = perm(a) + cz;
    let ab = perm(a + 1) + cz;
    let b = perm(cx + 1) + cy;
    let ba = perm(b) + cz;
    let bb = perm(b + 1) + cz;
    let near = lerp(
        v,
        lerp(u, grad(perm(aa), x, y, z), grad(perm(ba), x - 1.0, y, z)),
        lerp(
            u,
            grad(perm(ab), x, y - 1.0, z),
            grad(perm(bb), x - 1.0, y - 1.0, z),
        ),
    );
    let far = lerp(
        v,
        lerp(
            u,
            grad(perm(aa + 1), x, y, z - 1.0),
            grad(perm(ba + 1), x - 1.0, y, z - 1.0),
        ),
        lerp(
            u,
            grad(perm(ab + 1), x, y - 1.0, z - 1.0),
            grad(perm(bb + 1), x - 1.0, y - 1.0, z - 1.0),
        ),
    );
    lerp(w, near, far)
}

/// A 32-bit integer hash with good avalanche ("lowbias32": two multiply–xorshift rounds).
/// Only integer operations, so a loop over directions still vectorises.
#[inline(always)]
pub(crate) fn hash(mut x: u32) -> u32 {
    x ^= x >> 16;
    x = x.wrapping_mul(0x7feb_352d);
    x ^= x >> 15;
    x = x.wrapping_mul(0x846c_a68b);
    x ^ (x >> 16)
}

/// A number uniform in [-1, 1) from a hash: its top 24 bits, scaled.
#[inline(always)]
pub(crate) fn signed_unit(h: u32) -> f32 {
    #[allow(clippy::cast_possible_wrap, clippy::cast_precision_loss)] // < 2²⁴: exact
    let top = (h >> 8) as i32 as f32;
    top * (1.0 / 8_388_608.0) - 1.0
}

/// Three numbers uniform in [-1, 1) for the fragment whose unit view direction is `d` and the
/// frame `seed`: `rand(l_pt)/l_pt` of eq. 6, seeded per fragment.
///
/// The fragment's key is its direction rounded to a grid of 2⁻¹² (0.014°, finer than a pixel of a
/// 16 384-pixel-wide panorama), so the draws are a pure function of where the fragment is and of
/// the seed: the same frame renders the same, and a skydome of another size, whose fragments lie
/// in the same directions, draws the same numbers except where a direction sits on a grid line.
#[inline(always)]
pub(crate) fn fragment_draws(dx: f32, dy: f32, dz: f32, seed: u32) -> [f32; 3] {
    const GRID: f32 = 4096.0;
    let kx = math::round_key(dx * GRID);
    let ky = math::round_key(dy * GRID);
    let kz = math::round_key(dz * GRID);
    let key = hash(seed ^ hash(kx ^ hash(ky ^ hash(kz))));
    [
        signed_unit(hash(key)),
        signed_unit(hash(key.wrapping_add(0x9e37_79b9))),
        signed_unit(hash(key.wrapping_add(0x3c6e_f372))),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Values of Ken Perlin's reference implementation (f64), as published with it and used as
    /// the check value of the Rosetta Code "Perlin noise" task.
    #[test]
    #[allow(clippy::approx_constant)] // 3.14 is the published test point, not π
    fn perlin_matches_the_reference_implementation() {
        for (p, want) in [
            ((3.14, 42.0, 7.0), 0.136_919_958_784_000_12_f64),
            ((-4.20, 10.0, 6.0), 0.142_080_000_000_000_43),
            ((0.5, 0.5, 0.5), -0.25),
        ] {
            let got = f64::from(improved_perlin(p.0, p.1, p.2));
            // f32 inputs: 3.14 and -4.2 are rounded by up to 1.2e-7, the rest by f32 arithmetic.
            assert!((got - want).abs() < 1e-6, "noise{p:?} = {got}, want {want}");
        }
    }

    #[test]
    fn perlin_is_zero_on_the_lattice_and_bounded() {
        for i in -5..5 {
            for j in -3..3 {
                let (x, y, z) = (i as f32, j as f32, (i * j) as f32);
                assert_eq!(improved_perlin(x, y, z), 0.0, "({x}, {y}, {z})");
            }
        }
        let mut lo = 0.0f32;
        let mut hi = 0.0f32;
        for k in 0..20_000 {
            let t = k as f32 * 0.0137;
            let n = improved_perlin(t, 1.7 * t + 0.3, -0.6 * t + 5.1);
            lo = lo.min(n);
            hi = hi.max(n);
        }
        assert!(lo >= -1.0 && hi <= 1.0, "range [{lo}, {hi}]");
        assert!(
            lo < -0.3 && hi > 0.3,
            "range [{lo}, {hi}] is suspiciously narrow"
        );
        for bad in [f32::NAN, f32::INFINITY, -1e30] {
            assert!(improved_perlin(bad, 0.5, bad).is_finite());
        }
    }

    #[test]
    fn perlin_is_continuous() {
        // The gradient of the noise is bounded (by about 2.5), so steps of 1e-3 change it by less
        // than 3e-3, also across lattice planes.
        let mut prev = improved_perlin(-2.0, 0.25, 0.75);
        for k in 1..4000 {
            let x = -2.0 + k as f32 * 1e-3;
            let n = improved_perlin(x, 0.25, 0.75);
            assert!((n - prev).abs() < 3e-3, "jump at x = {x}");
            prev = n;
        }
    }

    #[test]
    fn permutation_is_a_permutation() {
        let mut seen = [false; 256];
        for p in PERMUTATION {
            assert!(!seen[usize::from(p)], "{p} twice");
            seen[usize::from(p)] = true;
        }
    }

    #[test]
    fn draws_are_uniform_and_reproducible() {
        let mut sum = [0.0f64; 3];
        let mut lo = 1.0f32;
        let mut hi = -1.0f32;
        let n = 20_000;
        for k in 0..n {
            let a = k as f32 * 0.000_31;
            let d = [libm::cosf(a), libm::sinf(a), 0.3];
            let r = fragment_draws(d[0], d[1], d[2], 7);
            assert_eq!(r, fragment_draws(d[0], d[1], d[2], 7));
            for c in 0..3 {
                sum[c] += f64::from(r[c]);
                lo = lo.min(r[c]);
                hi = hi.max(r[c]);
            }
        }
        for s in sum {
            // The mean of n uniforms on [-1, 1) has standard deviation 1/sqrt(3n) = 0.004.
            assert!((s / f64::from(n)).abs() < 0.02, "mean {}", s / f64::from(n));
        }
        assert!(
            lo >= -1.0 && hi < 1.0 && lo < -0.99 && hi > 0.99,
            "[{lo}, {hi}]"
        );
        assert_ne!(
            fragment_draws(0.6, 0.0, 0.8, 1),
            fragment_draws(0.6, 0.0, 0.8, 2),
            "the seed changes the draws"
        );
    }
}
