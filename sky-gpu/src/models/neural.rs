//! The neural sky of seed 000 (eqs. 4-7) per direction; the network of one sky, with √t,
//! θ_sun, eq. 10's rotation and the input scaling folded into its first layer, comes from
//! [`NeuralSky::folded`].

use sky_core::NeuralSky;

use crate::ir::{Body, Builtin, Expr, Function, Ty, call, float, int, select, splat3};
use crate::models::preetham::normalised;
use crate::{Model, Shader, param};

/// vec4s of parameters of a network with `hidden` neurons: the sun, the output biases, the
/// output scales and two per neuron.
#[must_use]
pub const fn params_len(hidden: usize) -> usize {
    3 + 2 * hidden
}

/// The shader of a 6-`hidden`-3 network: `sky_radiance(dir)`, linear sRGB in the units of the
/// training data (cd/m² for the shipped skies).
#[must_use]
pub fn shader(hidden: usize) -> Shader {
    let h = i32::try_from(hidden).unwrap_or(i32::MAX);
    let p = |i: i32| param(Model::Neural, i);
    let mut b = Body::new();
    let d = normalised(&mut b);
    let z = output_sums(&mut b, h, d.clone(), &param_at);
    // Eq. 7 through eq. 6's output activation: ½ scale z² (sky-core's module docs); 0 below
    // the horizon (sky-core's rule).
    b.return_(select(
        super::above_horizon(d),
        call(
            Builtin::Min,
            [
                p(2).swizzle("xyz") * (z.clone() * z),
                splat3(float(f32::MAX)),
            ],
        ),
        splat3(float(0.0)),
    ));
    Shader {
        model: Model::Neural,
        params_len: params_len(hidden),
        doc: format!(
            "The neural sky of seed 000 (a 6-{hidden}-3 network, eqs. 4-7): sky_radiance(dir) is linear\n\
             sRGB in the units of the training data (cd/m² for the shipped skies) towards the view\n\
             direction dir (sky-core's frame: +z up; any length), 0 below the horizon (sky-core's rule).\n\
             Parameters (sky-core's NeuralSky::folded): [0].xyz the unit direction towards the sun,\n\
             [1].xyz the output biases, [2].xyz half the output scales; for each hidden neuron j,\n\
             [3 + j] its coefficients of v_x, v_y, v_z and d, [3 + {hidden} + j].xyz its output weights\n\
             (R, G, B) and .w the constant part of its pre-activation (√t, θ_sun, eq. 10's rotation\n\
             and the input scaling folded in)."
        ),
        functions: vec![Function::sky_radiance(b.finish())],
    }
}

fn param_at(i: Expr) -> Expr {
    crate::ir::name(Model::Neural.params_name()).at(i)
}

/// One network's output sums (eq. 6) towards the unit view direction `d`, as statements of
/// `b` (`let q`, `let v`, `var z` and the loop over the `hidden` neurons), its parameter `i`
/// (the layout of [`params`]) read as `at(i)`; returns `z`.
pub(crate) fn output_sums(b: &mut Body, hidden: i32, d: Expr, at: &dyn Fn(Expr) -> Expr) -> Expr {
    let q = b.let_("q", Ty::Vec3, d.clone() - at(int(0)).swizzle("xyz"));
    // The inputs of eq. 4 that vary per direction: v and d = |v − s|.
    let v = b.let_(
        "v",
        Ty::Vec4,
        Expr::Construct(
            Ty::Vec4,
            vec![d, call(Builtin::Sqrt, [call(Builtin::Dot, [q.clone(), q])])],
        ),
    );
    b.var("z", Ty::Vec3, at(int(1)).swizzle("xyz"));
    b.for_("j", int(hidden), |b, j| {
        // [3 + H + j]: output weights (R, G, B) and the constant part of h_j.
        let o = b.let_("o", Ty::Vec4, at(int(3 + hidden) + j.clone()));
        // Eq. 4 (scaling and rotation folded in), summed in sky-core's order, then eq. 5's
        // activation into eq. 6's sums.
        let c = b.let_("c", Ty::Vec4, at(int(3) + j));
        let term = |k: &'static str| c.clone().swizzle(k) * v.clone().swizzle(k);
        let hj = b.let_(
            "h",
            Ty::F32,
            o.clone().swizzle("w") + term("x") + term("y") + term("z") + term("w"),
        );
        let a = b.let_("a", Ty::F32, 1.0 / (1.0 + hj.clone() * hj));
        b.add_assign("z", o.swizzle("xyz") * a);
    });
    crate::ir::name("z")
}

/// The parameters of `sky` in the layout of [`shader`]`(H)`.
#[must_use]
pub fn params<const H: usize>(sky: &NeuralSky<H>) -> Vec<f32> {
    let n = sky.folded();
    let mut out = Vec::with_capacity(4 * params_len(H));
    out.extend([n.sun.x, n.sun.y, n.sun.z, 0.0]);
    out.extend(n.output_bias);
    out.push(0.0);
    out.extend(n.half_scale);
    out.push(0.0);
    for j in 0..H {
        out.extend([n.coeff_x[j], n.coeff_y[j], n.coeff_z[j], n.coeff_d[j]]);
    }
    for j in 0..H {
        out.extend([
            n.output[0][j],
            n.output[1][j],
            n.output[2][j],
            n.constant[j],
        ]);
    }
    out
}
