//! sky-core's physical daylight sky ([`DaylightSky`]) per direction: the one or two 6-24-3
//! networks that share the sky at this sun (day, dusk, night, blended linearly in the sun
//! zenith over sky-core's `BLENDS`), each folded for the sun and the aerosol optical depth as
//! [`NeuralSky::folded`](sky_core::NeuralSky::folded) folds it, times its factor (the diffuse
//! illuminance of sky-core's tables over π times the network's blend weight), summed in CIE X,
//! Y, Z and turned into linear sRGB (seed 002 eq. 28). Everything that depends on the sun and
//! the optical depth is a parameter ([`params`], from [`DaylightSky::shares`]), so the shader
//! text is the same for every sky and every set of weights of this shape.

use sky_core::Vec3;
use sky_core::daylight::{DaylightSky, HIDDEN};

use crate::ir::{
    BinOp, Body, Builtin, Expr, Function, Ty, call, call_fn, float, int, name, splat3,
};
use crate::models::neural::{self, output_sums};
use crate::models::preetham::{linear_srgb, normalised};
use crate::{Model, Shader, param};

/// vec4s of one network's parameters ([`neural::params`]' layout).
const NETWORK: usize = neural::params_len(HIDDEN);

/// vec4s of parameters: the two parts' factors and the two networks.
pub const PARAMS: usize = 2 + 2 * NETWORK;

/// The name of the shader's function that evaluates one network.
const NETWORK_FN: &str = "daylight_network";

/// The shader: `sky_radiance(dir)`, linear sRGB in cd/m².
#[must_use]
pub fn shader() -> Shader {
    // usize → i32 of small constants (51, 104).
    let (hidden, network) = (
        i32::try_from(HIDDEN).unwrap_or(i32::MAX),
        i32::try_from(NETWORK).unwrap_or(i32::MAX),
    );
    let p = |i: i32| param(Model::Daylight, i);
    let mut b = Body::new();
    let d = normalised(&mut b);
    b.var("xyz", Ty::Vec3, splat3(float(0.0)));
    // Part k: network k (at 2 + k · NETWORK) times its factor [k].xyz, in sky-core's order.
    b.for_(
        "k",
        Expr::Construct(Ty::I32, vec![p(0).swizzle("w")]),
        |b, k| {
            let base = int(2) + k.clone() * int(network);
            let factor = name(Model::Daylight.params_name()).at(k).swizzle("xyz");
            b.add_assign("xyz", call_fn(NETWORK_FN, [d.clone(), base]) * factor);
        },
    );
    // 0 below the horizon (sky-core's rule).
    b.return_(crate::ir::select(
        super::above_horizon(d),
        linear_srgb(name("xyz")),
        splat3(float(0.0)),
    ));
    Shader {
        model: Model::Daylight,
        params_len: PARAMS,
        doc: format!(
            "sky-core's daylight sky (DaylightSky: the physical atmosphere's radiance through day, dusk\n\
             and night 6-{HIDDEN}-3 networks of seed 000, blended in the sun zenith, times the diffuse\n\
             illuminance of sky-core's daylight tables): sky_radiance(dir) is linear sRGB in cd/m² towards\n\
             the view direction dir (sky-core's frame: +z up; any length), 0 below the horizon (sky-core's\n\
             rule); in deep twilight a channel may be negative (outside the sRGB gamut, as sky-core's).\n\
             Parameters (sky-core's DaylightSky::shares): [0].xyz and [1].xyz the two parts' factors\n\
             (E_d / π times the blend weight, X, Y, Z, cd/m²), [0].w the number of parts (1 or 2);\n\
             part k's network at [2 + {NETWORK} k] in the neural sky's layout (NeuralSky::folded, for the\n\
             sun and the aerosol optical depth): [+0].xyz the unit direction towards the sun, [+1].xyz\n\
             the output biases, [+2].xyz half the output scales; for each hidden neuron j, [+3 + j] its\n\
             coefficients of v_x, v_y, v_z and d, [+3 + {HIDDEN} + j].xyz its output weights (X, Y, Z)\n\
             and .w the constant part of its pre-activation."
        ),
        functions: vec![network_function(hidden), Function::sky_radiance(b.finish())],
    }
}

/// `daylight_network(d, base)`: the network whose parameters start at `base` towards the unit
/// direction `d`, its output ½ scale z² (eq. 7), as sky-core's `NeuralSky` computes it (the
/// direction normalised once more, the scale applied before the second factor z).
fn network_function(hidden: i32) -> Function {
    let mut b = Body::new();
    let d = name("d");
    let u = b.let_(
        "u",
        Ty::Vec3,
        d.clone() * call(Builtin::InverseSqrt, [call(Builtin::Dot, [d.clone(), d])]),
    );
    let array = name(Model::Daylight.params_name());
    let base = name("base");
    // Element `base + i`, written `base + a + b` for an offset `a + b`.
    let at = |i: Expr| match i {
        Expr::Int(0) => array.clone().at(base.clone()),
        Expr::Binary(BinOp::Add, l, r) => array.clone().at(base.clone() + *l + *r),
        i => array.clone().at(base.clone() + i),
    };
    let z = output_sums(&mut b, hidden, u, &at);
    let half_scale = at(int(2)).swizzle("xyz");
    b.return_(call(
        Builtin::Min,
        [half_scale * z.clone() * z, splat3(float(f32::MAX))],
    ));
    Function {
        name: NETWORK_FN.into(),
        doc: "One network of the sky: its output (the sky's shape, X, Y, Z) towards the unit direction d,\n\
              its parameters at sky_daylight[base]."
            .into(),
        params: vec![("d".into(), Ty::Vec3), ("base".into(), Ty::I32)],
        result: Ty::Vec3,
        body: b.finish(),
    }
}

/// The parameters of `sky` in the layout of [`shader`]: its parts' factors and folded networks
/// ([`DaylightSky::shares`]). A part without a network (a uniform shape, which the shipped
/// weights never give) is packed as a network whose output is exactly 1.
#[must_use]
pub fn params(sky: &DaylightSky) -> Vec<f32> {
    let shares = sky.shares();
    let parts = if shares[1].1 == Vec3::ZERO { 1.0 } else { 2.0 };
    let mut out = Vec::with_capacity(4 * PARAMS);
    for (k, (_, factor)) in shares.iter().enumerate() {
        out.extend(factor.to_array());
        out.push(if k == 0 { parts } else { 0.0 });
    }
    for (network, _) in shares {
        out.extend(network.map_or_else(uniform_network, neural::params::<HIDDEN>));
    }
    out
}

/// A network's parameters whose output is exactly 1 in every direction: z = 1 (the output
/// biases, no hidden weight), ½ scale 1.
fn uniform_network() -> Vec<f32> {
    let mut out = vec![0.0; 4 * NETWORK];
    out[4..7].copy_from_slice(&[1.0; 3]);
    out[8..11].copy_from_slice(&[1.0; 3]);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_layout_has_its_length_for_one_and_two_parts() {
        use sky_core::Sun;
        use sky_core::daylight::Daylight;
        for (zenith, parts) in [(40.0f32, 1.0), (88.0, 2.0), (97.0, 2.0), (104.0, 1.0)] {
            let sky = Daylight::clear(Sun::new(zenith.to_radians(), 0.3).expect("valid")).sky();
            let p = params(&sky);
            assert_eq!(p.len(), 4 * PARAMS, "{zenith}");
            assert_eq!(p[3], parts, "{zenith}");
        }
        assert_eq!(uniform_network().len(), 4 * NETWORK);
    }
}
