//! The daylight sky's batch kernel for x86-64 CPUs with AVX2 and FMA:
//! [`DaylightSky::xyz_batch_avx2`] and [`DaylightSky::rgb_batch_avx2`].
//!
//! It evaluates what [`DaylightSky::xyz`] evaluates, eight directions per 256-bit register and
//! four registers at a time, in the way of the neural sky's kernel
//! ([`NeuralSky::rgb_batch_avx2`](crate::NeuralSky::rgb_batch_avx2)): every multiply-add of the
//! networks fused, d = |v − s| from the CPU's reciprocal square root estimate and one Newton
//! step. In addition:
//!
//! * the view direction is normalised once, by the CPU's square root and division (exact to
//!   half an ulp, so the networks need not normalise it again), with [`DaylightSky::xyz`]'s
//!   rule for which directions have sky (|dir|² finite and positive, z ≥ 0 after
//!   normalising), and d is computed once for both networks of a blend (they share the sun);
//! * each network's ½ output scale and the share's E_d,c / π are multiplied once per sky, and
//!   the shares' radiance is summed by fused multiply-adds;
//! * [`rgb_batch_avx2`](DaylightSky::rgb_batch_avx2) applies the sRGB matrix in registers.
//!
//! The results differ from [`DaylightSky::xyz`] in the last bits, with the same accuracy
//! against the networks evaluated exactly (bounded in the methods' docs).

use core::arch::x86_64::{
    __m256, _CMP_GE_OQ, _CMP_GT_OQ, _CMP_LT_OQ, _mm256_add_ps, _mm256_and_ps, _mm256_cmp_ps,
    _mm256_div_ps, _mm256_fmadd_ps, _mm256_min_ps, _mm256_mul_ps, _mm256_set1_ps, _mm256_sqrt_ps,
    _mm256_sub_ps,
};

use bytemuck::{must_cast, must_cast_mut, must_cast_ref};
use glam::Vec3;

use super::{DaylightSky, HIDDEN};
use crate::color::XYZ_TO_LINEAR_SRGB;
use crate::neural::FoldedNetwork;
use crate::neural::avx2::{deinterleave, interleave, rsqrt};

/// Registers evaluated together: four of eight lanes (32 directions a step), as the neural
/// sky's kernel.
const GROUP: usize = 4;
/// Directions a step.
const STEP: usize = 8 * GROUP;

/// One share of the sky as the kernel evaluates it: the network folded
/// ([`NeuralSky::folded`](crate::NeuralSky::folded)) and, per channel, its ½ output scale
/// times the share's E_d,c / π, so that the share's radiance is `scale[c] · z_c²`.
#[derive(Clone, Copy)]
struct Term {
    network: FoldedNetwork<HIDDEN>,
    scale: [f32; 3],
}

/// Everything a step needs, prepared once per call.
struct Kernel {
    /// The shares with a network: the first `count`.
    terms: [Term; 2],
    count: usize,
    /// The summed scales of the shares without a network (a uniform sky; none in practice).
    uniform: Vec3,
    /// The rows of the matrix applied to X, Y, Z (`None`: X, Y, Z out).
    matrix: Option<[Vec3; 3]>,
}

impl DaylightSky {
    /// [`xyz_batch`](Self::xyz_batch) with AVX2 and fused multiply-add, for x86-64: fills
    /// `out[i]` (X, Y, Z, cd/m²) for every `i` below `min(dirs.len(), out.len())`.
    ///
    /// It evaluates the networks as [`NeuralSky::rgb_batch_avx2`](crate::NeuralSky::rgb_batch_avx2)
    /// does (every multiply-add fused; d = |v − s| from the CPU's reciprocal square root estimate
    /// and one Newton step), normalises the view once by the CPU's square root, computes d once
    /// for both networks of a blend, and folds the share's E_d,c / π into the networks' output
    /// scale. It therefore rounds differently from [`xyz`](Self::xyz) but is as accurate: against the networks and the blend evaluated in f64, both stay within
    /// 4e-4 of the direction's largest channel over the upper hemisphere, by day, in both blends
    /// and through twilight (tested in `tests/tests/daylight.rs`). The same directions are
    /// zero as for `xyz` (below the horizon, zero or non-finite); the results are finite and
    /// non-negative for every input.
    ///
    /// # Safety
    /// The CPU must have AVX2 and FMA. The function is safe to call from code compiled with the
    /// `avx2` and `fma` target features; elsewhere, check the CPU first (as the example of
    /// [`xyz_batch`](Self::xyz_batch) does).
    #[target_feature(enable = "avx2,fma")]
    pub fn xyz_batch_avx2(&self, dirs: &[Vec3], out: &mut [Vec3]) {
        self.kernel(None).run(dirs, out);
    }

    /// [`rgb_batch`](Self::rgb_batch) with AVX2 and fused multiply-add: linear sRGB, cd/m²
    /// scale, [`xyz_batch_avx2`](Self::xyz_batch_avx2) through the sRGB matrix. Within 4e-4 of
    /// the direction's largest X, Y, Z channel of [`rgb`](Self::rgb) (a channel may be
    /// negative in twilight, as `rgb`'s).
    ///
    /// # Safety
    /// As [`xyz_batch_avx2`](Self::xyz_batch_avx2): the CPU must have AVX2 and FMA.
    #[target_feature(enable = "avx2,fma")]
    pub fn rgb_batch_avx2(&self, dirs: &[Vec3], out: &mut [Vec3]) {
        let m = XYZ_TO_LINEAR_SRGB;
        self.kernel(Some([m.row(0), m.row(1), m.row(2)]))
            .run(dirs, out);
    }

    fn kernel(&self, matrix: Option<[Vec3; 3]>) -> Kernel {
        let mut uniform = Vec3::ZERO;
        let mut count = 0;
        // Unused terms: a network of zeros with a zero scale (never evaluated).
        let idle = Term {
            network: FoldedNetwork {
                sun: Vec3::Z,
                constant: [0.0; HIDDEN],
                coeff_x: [0.0; HIDDEN],
                coeff_y: [0.0; HIDDEN],
                coeff_z: [0.0; HIDDEN],
                coeff_d: [0.0; HIDDEN],
                output: [[0.0; HIDDEN]; 3],
                output_bias: [0.0; 3],
                half_scale: [0.0; 3],
            },
            scale: [0.0; 3],
        };
        let mut terms = [idle, idle];
        for (network, scale) in &self.shares {
            match network {
                Some(n) => {
                    let network = n.folded();
                    let scale = core::array::from_fn(|c| network.half_scale[c] * scale[c]);
                    if let Some(term) = terms.get_mut(count) {
                        *term = Term { network, scale };
                        count += 1;
                    }
                }
                None => uniform += *scale,
            }
        }
        Kernel {
            terms,
            count,
            uniform,
            matrix,
        }
    }
}

impl Kernel {
    /// The steps, compiled for the number of networks (so that the loop over them unrolls).
    #[target_feature(enable = "avx2,fma")]
    fn run(&self, dirs: &[Vec3], out: &mut [Vec3]) {
        match self.count {
            0 => self.run_with::<0>(dirs, out),
            1 => self.run_with::<1>(dirs, out),
            _ => self.run_with::<2>(dirs, out),
        }
    }

    /// [`Self::run`] with the first `N` terms.
    #[target_feature(enable = "avx2,fma")]
    fn run_with<const N: usize>(&self, dirs: &[Vec3], out: &mut [Vec3]) {
        let n = dirs.len().min(out.len());
        let (dirs, out) = (&dirs[..n], &mut out[..n]);
        let (d_steps, d_rest) = dirs.as_chunks::<STEP>();
        let (o_steps, o_rest) = out.as_chunks_mut::<STEP>();
        for (d, o) in d_steps.iter().zip(o_steps) {
            self.step::<N>(d, o);
        }
        if !d_rest.is_empty() {
            // The last directions, padded to a whole step with the zenith.
            let mut d = [Vec3::Z; STEP];
            let mut o = [Vec3::ZERO; STEP];
            d[..d_rest.len()].copy_from_slice(d_rest);
            self.step::<N>(&d, &mut o);
            o_rest.copy_from_slice(&o[..o_rest.len()]);
        }
    }

    /// One step of directions, the first `N` terms.
    #[target_feature(enable = "avx2,fma")]
    fn step<const N: usize>(&self, dirs: &[Vec3; STEP], out: &mut [Vec3; STEP]) {
        let splat = _mm256_set1_ps;
        let zero = splat(0.0);
        let horizon = splat(-crate::geom::HORIZON_TOLERANCE);
        let groups: &[[[f32; 8]; 3]; GROUP] = must_cast_ref(dirs);
        let (mut x, mut y, mut z) = ([zero; GROUP], [zero; GROUP], [zero; GROUP]);
        let mut sky = [zero; GROUP];
        for i in 0..GROUP {
            let [dx, dy, dz] = deinterleave(groups[i].map(must_cast));
            // `DaylightSky::xyz`'s rule, unfused as it computes |dir|²: a direction only where
            // |dir|² is finite and positive; the sky only where the unit direction is not below
            // the horizon (`geom::below_horizon`: z ≥ −1e-6).
            let norm2 = _mm256_add_ps(
                _mm256_add_ps(_mm256_mul_ps(dx, dx), _mm256_mul_ps(dy, dy)),
                _mm256_mul_ps(dz, dz),
            );
            let rcp = _mm256_div_ps(splat(1.0), _mm256_sqrt_ps(norm2));
            let valid = _mm256_and_ps(
                _mm256_cmp_ps::<_CMP_LT_OQ>(norm2, splat(f32::INFINITY)),
                _mm256_cmp_ps::<_CMP_GT_OQ>(norm2, zero),
            );
            // Other directions are zero (a finite input to the networks, masked at the end).
            x[i] = _mm256_and_ps(valid, _mm256_mul_ps(dx, rcp));
            y[i] = _mm256_and_ps(valid, _mm256_mul_ps(dy, rcp));
            z[i] = _mm256_and_ps(valid, _mm256_mul_ps(dz, rcp));
            sky[i] = _mm256_and_ps(valid, _mm256_cmp_ps::<_CMP_GE_OQ>(z[i], horizon));
        }
        let mut sum = [self.uniform.x, self.uniform.y, self.uniform.z].map(|u| [splat(u); GROUP]);
        // d = |v − s| (the networks of a blend share the sun: computed once).
        let mut d_sun = self.terms[0].network.sun;
        let mut d = distance(d_sun, &x, &y, &z);
        for term in self.terms.iter().take(N) {
            let net = &term.network;
            if net.sun != d_sun {
                d_sun = net.sun;
                d = distance(d_sun, &x, &y, &z);
            }
            // The hidden layer (eqs. 4-5 of seed 000) and the output sums (eq. 6).
            let [mut r, mut g, mut b] = net.output_bias.map(|bias| [splat(bias); GROUP]);
            let one = splat(1.0);
            for j in 0..HIDDEN {
                let (c, cx, cy) = (
                    splat(net.constant[j]),
                    splat(net.coeff_x[j]),
                    splat(net.coeff_y[j]),
                );
                let (cz, cd) = (splat(net.coeff_z[j]), splat(net.coeff_d[j]));
                // (Indexed, not `output.map`: that copies the 288-byte array every neuron.)
                let [wr, wg, wb] = [0, 1, 2].map(|c| splat(net.output[c][j]));
                for i in 0..GROUP {
                    let h = _mm256_fmadd_ps(cx, x[i], c);
                    let h = _mm256_fmadd_ps(cy, y[i], h);
                    let h = _mm256_fmadd_ps(cz, z[i], h);
                    let h = _mm256_fmadd_ps(cd, d[i], h);
                    let a = _mm256_div_ps(one, _mm256_fmadd_ps(h, h, one));
                    r[i] = _mm256_fmadd_ps(wr, a, r[i]);
                    g[i] = _mm256_fmadd_ps(wg, a, g[i]);
                    b[i] = _mm256_fmadd_ps(wb, a, b[i]);
                }
            }
            // Eq. 7 as ½ z² (see the module docs of `neural`), times the share's E_d,c / π.
            for (c, zc) in [r, g, b].iter().enumerate() {
                let s = splat(term.scale[c]);
                for i in 0..GROUP {
                    sum[c][i] = _mm256_fmadd_ps(_mm256_mul_ps(s, zc[i]), zc[i], sum[c][i]);
                }
            }
        }
        let max = splat(f32::MAX);
        let out: &mut [[[f32; 8]; 3]; GROUP] = must_cast_mut(out);
        for i in 0..GROUP {
            let xyz = [0, 1, 2].map(|c| _mm256_min_ps(sum[c][i], max));
            let channels = match &self.matrix {
                Some(rows) => rows.map(|m| {
                    let v = _mm256_mul_ps(splat(m.x), xyz[0]);
                    let v = _mm256_fmadd_ps(splat(m.y), xyz[1], v);
                    _mm256_fmadd_ps(splat(m.z), xyz[2], v)
                }),
                None => xyz,
            };
            // Zero where `xyz` is zero (below the horizon, no direction).
            let channels = channels.map(|v| _mm256_and_ps(sky[i], v));
            out[i] = interleave(channels).map(must_cast);
        }
    }
}

/// d = |v − s| in each lane (the input of eq. 4), from the CPU's reciprocal square root
/// estimate and one Newton step, as the neural sky's kernel.
#[target_feature(enable = "avx2,fma")]
fn distance(
    sun: Vec3,
    x: &[__m256; GROUP],
    y: &[__m256; GROUP],
    z: &[__m256; GROUP],
) -> [__m256; GROUP] {
    let (sx, sy, sz) = (
        _mm256_set1_ps(sun.x),
        _mm256_set1_ps(sun.y),
        _mm256_set1_ps(sun.z),
    );
    let q: [__m256; GROUP] = core::array::from_fn(|i| {
        let (dx, dy, dz) = (
            _mm256_sub_ps(x[i], sx),
            _mm256_sub_ps(y[i], sy),
            _mm256_sub_ps(z[i], sz),
        );
        _mm256_fmadd_ps(dz, dz, _mm256_fmadd_ps(dy, dy, _mm256_mul_ps(dx, dx)))
    });
    let inv = rsqrt(q);
    core::array::from_fn(|i| _mm256_mul_ps(q[i], inv[i]))
}
