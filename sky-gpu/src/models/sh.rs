//! The spherical-harmonics sky (seed 001) per direction: `Σ c_lm Y_lm(dir)` over seven bands,
//! the real basis of sky-core's [`basis`] unrolled (its recurrence and constants, in the same
//! order of operations); the coefficients of one sky come from [`ShSky::coefficients`] (zero
//! beyond the bands it uses).

use sky_core::sh::ShSky;
use sky_core::sh::basis::{
    self, DOUBLE_FACTORIAL, MAX_BANDS, MAX_COEFFICIENTS, NORMALISATION, RECURRENCE,
};

use crate::ir::{Body, Builtin, Expr, Function, Ty, call, float, name, select, splat3};
use crate::models::preetham::normalised;
use crate::{Model, Shader, param};

/// vec4s of parameters: one RGB coefficient per (l, m) of seven bands.
pub const PARAMS: usize = MAX_COEFFICIENTS;

/// The shader: `sky_radiance(dir)`, linear sRGB on the model's scale (cd/m² for Preetham).
#[must_use]
pub fn shader() -> Shader {
    let mut b = Body::new();
    let d = normalised(&mut b);
    let (x, y, z) = (
        d.clone().swizzle("x"),
        d.clone().swizzle("y"),
        d.clone().swizzle("z"),
    );
    // (x + i y)^m = sin^m θ (cos mφ + i sin mφ), m = 1..6 (m = 0 is 1 + 0 i).
    let mut re: Vec<Expr> = vec![float(1.0)];
    let mut im: Vec<Expr> = vec![float(0.0)];
    for m in 1..MAX_BANDS {
        let (r, i) = (re[m - 1].clone(), im[m - 1].clone());
        let (nr, ni) = if m == 1 {
            (x.clone(), y.clone())
        } else {
            (
                x.clone() * r.clone() - y.clone() * i.clone(),
                x.clone() * i + y.clone() * r,
            )
        };
        re.push(b.let_(&format!("re{m}"), Ty::F32, nr));
        im.push(b.let_(&format!("im{m}"), Ty::F32, ni));
    }
    let mut y_lm: Vec<Option<Expr>> = vec![None; MAX_COEFFICIENTS];
    for m in 0..MAX_BANDS {
        // q_l = P_l^m(z) / sin^m θ by the recurrence in l.
        let mut q_prev: Option<Expr> = None;
        let mut q = float(DOUBLE_FACTORIAL[m]);
        for l in m..MAX_BANDS {
            if l > m {
                let [a, c] = RECURRENCE[l][m];
                // (The first step's q_{l−2} is 0: sky-core's `− b · 0` changes nothing.)
                let next = match &q_prev {
                    Some(prev) => a * z.clone() * q.clone() - c * prev.clone(),
                    None => a * z.clone() * q.clone(),
                };
                q_prev = Some(q);
                q = b.let_(&format!("q{l}_{m}"), Ty::F32, next);
            }
            let n = NORMALISATION[l][m] * q.clone();
            #[allow(clippy::cast_possible_wrap)] // m ≤ 6
            let mi = m as isize;
            y_lm[basis::index(l, mi)] = Some(n.clone() * re[m].clone());
            if m > 0 {
                y_lm[basis::index(l, -mi)] = Some(n * im[m].clone());
            }
        }
    }
    b.var("sum", Ty::Vec3, splat3(float(0.0)));
    for (i, y) in y_lm.into_iter().enumerate() {
        let y = y.unwrap_or_else(|| float(0.0));
        let yi = b.let_(&format!("y{i}"), Ty::F32, y);
        #[allow(clippy::cast_possible_truncation, clippy::cast_possible_wrap)] // i < 49
        b.add_assign("sum", param(Model::Sh, i as i32).swizzle("xyz") * yi);
    }
    // sky-core's ShSky::radiance: the series clamped at zero, 0 below the horizon (its rule).
    b.return_(select(
        super::above_horizon(d),
        call(Builtin::Max, [name("sum"), splat3(float(0.0))]),
        splat3(float(0.0)),
    ));
    Shader {
        model: Model::Sh,
        params_len: PARAMS,
        doc: "The spherical-harmonics sky (seed 001): sky_radiance(dir) = max(Σ c_lm Y_lm(dir), 0) over\n\
              seven bands (sky-core's ShSky::radiance), 0 below the horizon, linear sRGB on the\n\
              model's scale (cd/m² for the Preetham sky) towards the view direction dir (sky-core's\n\
              frame: +z up; any length). Real orthonormal SH without the\n\
              Condon-Shortley phase (sky-core's sh::basis).\n\
              Parameters (sky-core's ShSky::coefficients): [l² + l + m].xyz the RGB coefficient c_lm,\n\
              0 beyond the sky's bands."
            .into(),
        functions: vec![Function::sky_radiance(b.finish())],
    }
}

/// The coefficients of `sky` in the layout of [`shader`].
#[must_use]
pub fn params(sky: &ShSky) -> [f32; 4 * PARAMS] {
    let mut out = [0.0; 4 * PARAMS];
    for (o, c) in out.chunks_exact_mut(4).zip(sky.coefficients()) {
        o[..3].copy_from_slice(&c.to_array());
    }
    out
}
