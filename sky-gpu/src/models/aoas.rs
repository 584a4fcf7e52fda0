//! The AOAS sky (seed 004 §3.2: O'Neil's single scattering inside one skydome) per direction;
//! the constants of one sky come from [`AoasSky::kernel_constants`]. The shader covers the
//! physical sky and any style's sky hue and day cycle; the pattern principles (cloud noise and
//! shapes) and ambiguity are CPU-only.

use core::f32::consts::LOG2_E;

use sky_core::AoasSky;
use sky_core::aoas::{HORIZON_TOLERANCE, PLANET_RADIUS, SCALE_DEPTH, SCALE_FIT_LOG2};

use crate::ir::{Body, Builtin, Expr, Function, Ty, call, call_fn, float, name, select, splat3};
use crate::models::preetham::normalised;
use crate::{Model, Shader, UnsupportedSky, param};

/// vec4s of parameters.
pub const PARAMS: usize = 6;

/// `sky_aoas_scale_log2(cos)`: O'Neil's optical-depth fit in log₂ units.
fn scale_log2() -> Function {
    let [c0, c1, c2, c3, c4] = SCALE_FIT_LOG2;
    let mut b = Body::new();
    let x = b.let_("x", Ty::F32, 1.0 - name("cos_angle"));
    b.return_(
        float(c0)
            + x.clone()
                * (float(c1) + x.clone() * (float(c2) + x.clone() * (float(c3) + x * float(c4)))),
    );
    Function {
        name: "sky_aoas_scale_log2".into(),
        doc: "O'Neil's optical-depth fit, log2 of scale(cos) / 0.25 (sky-core's scale_log2)."
            .into(),
        params: vec![("cos_angle".into(), Ty::F32)],
        result: Ty::F32,
        body: b.finish(),
    }
}

/// The shader: `sky_radiance(dir)`, linear RGB in O'Neil's relative units.
#[must_use]
pub fn shader() -> Shader {
    let p = |i: i32| param(Model::Aoas, i);
    let scale = |x: Expr| call_fn("sky_aoas_scale_log2", [x]);
    let (apex, camera_radius) = (p(0).swizzle("xyz"), p(0).swizzle("w"));
    let (sun, sun_apex) = (p(1).swizzle("xyz"), p(1).swizzle("w"));
    let (camera_lift, far_lift) = (p(2).swizzle("x"), p(2).swizzle("y"));
    let camera_density_log2 = p(2).swizzle("z");
    let (extinction, mie) = (p(3).swizzle("xyz"), p(3).swizzle("w"));
    let rayleigh = p(4).swizzle("xyz");
    let mie_phase = |c| p(5).swizzle(c);

    let mut b = Body::new();
    let d = normalised(&mut b);
    let d = b.let_(
        "dc",
        Ty::Vec3,
        call(Builtin::Clamp, [d, splat3(float(-1.0)), splat3(float(1.0))]),
    );
    let up = b.let_("up", Ty::F32, call(Builtin::Dot, [d.clone(), apex.clone()]));
    let above = b.let_(
        "above",
        Ty::F32,
        select(
            up.clone().greater_equal(float(-HORIZON_TOLERANCE)),
            float(1.0),
            float(0.0),
        ),
    );
    // A ray below the horizon lifted onto it (black there, but the march stays finite).
    let lifted = b.let_(
        "lifted",
        Ty::Vec3,
        d + apex.clone() * (call(Builtin::Max, [up.clone(), float(0.0)]) - up),
    );
    let v = b.let_(
        "v",
        Ty::Vec3,
        lifted.clone()
            * call(
                Builtin::InverseSqrt,
                [call(Builtin::Dot, [lifted.clone(), lifted])],
            ),
    );
    let mu = b.let_(
        "mu",
        Ty::F32,
        call(
            Builtin::Clamp,
            [
                call(Builtin::Dot, [v.clone(), apex]),
                float(0.0),
                float(1.0),
            ],
        ),
    );
    let nu = b.let_(
        "nu",
        Ty::F32,
        call(
            Builtin::Clamp,
            [
                call(Builtin::Dot, [v.clone(), sun.clone()]),
                float(-1.0),
                float(1.0),
            ],
        ),
    );
    // 1 − ν as |v − s|²/2, accurate near the sun (where the Mie peak amplifies 1 − ν's error).
    let vs = b.let_("vs", Ty::Vec3, v - sun);
    let one_minus_nu = b.let_(
        "one_minus_nu",
        Ty::F32,
        0.5 * call(Builtin::Dot, [vs.clone(), vs]),
    );
    // Eq. 3's ray from Pv to the outer sphere, without cancellation.
    let bb = b.let_("b", Ty::F32, camera_radius.clone() * mu.clone());
    let far = b.let_(
        "far_len",
        Ty::F32,
        far_lift.clone() / (bb.clone() + call(Builtin::Sqrt, [bb.clone() * bb + far_lift])),
    );
    let samples = b.let_(
        "samples",
        Ty::I32,
        Expr::Construct(Ty::I32, vec![p(2).swizzle("w")]),
    );
    let step = b.let_("step_len", Ty::F32, far / samples.clone().to_float());
    let start_offset = b.let_(
        "start_offset",
        Ty::F32,
        SCALE_DEPTH * call(Builtin::Exp2, [camera_density_log2 + scale(mu.clone())]),
    );
    b.var("acc", Ty::Vec3, splat3(float(0.0)));
    b.for_("i", samples, |b, i| {
        // Sample i at the middle of step i (eq. 3's P_i; eq. 4's integrand).
        let t = b.let_("t", Ty::F32, (i.to_float() + 0.5) * step.clone());
        let along = b.let_(
            "along",
            Ty::F32,
            t.clone() * (2.0 * camera_radius.clone() * mu.clone() + t.clone()),
        );
        let radius2 = b.let_(
            "radius2",
            Ty::F32,
            camera_radius.clone() * camera_radius.clone() + along.clone(),
        );
        let inv_radius = b.let_(
            "inv_radius",
            Ty::F32,
            call(Builtin::InverseSqrt, [radius2.clone()]),
        );
        let radius = b.let_("radius", Ty::F32, radius2 * inv_radius.clone());
        let altitude = b.let_(
            "altitude",
            Ty::F32,
            (camera_lift.clone() + along) / (radius + PLANET_RADIUS),
        );
        let density_log2 = b.let_("density_log2", Ty::F32, altitude * (-LOG2_E / SCALE_DEPTH));
        let light_cos = b.let_(
            "light_cos",
            Ty::F32,
            (camera_radius.clone() * sun_apex.clone() + t.clone() * nu.clone())
                * inv_radius.clone(),
        );
        let camera_cos = b.let_(
            "camera_cos",
            Ty::F32,
            (camera_radius.clone() * mu.clone() + t) * inv_radius,
        );
        let to_sun = b.let_(
            "to_sun",
            Ty::F32,
            call(Builtin::Exp2, [density_log2.clone() + scale(light_cos)]),
        );
        let to_space = b.let_(
            "to_space",
            Ty::F32,
            call(Builtin::Exp2, [density_log2.clone() + scale(camera_cos)]),
        );
        let scatter = b.let_(
            "scatter",
            Ty::F32,
            start_offset.clone() + SCALE_DEPTH * (to_sun - to_space),
        );
        b.add_assign(
            "acc",
            call(Builtin::Exp2, [density_log2 - scatter * extinction.clone()]),
        );
    });
    // The phase functions: Rayleigh 0.75 (1 + cos²), O'Neil's Mie with its constants.
    let one_plus_cos2 = b.let_("one_plus_cos2", Ty::F32, 1.0 + nu.clone() * nu.clone());
    let q = b.let_(
        "q",
        Ty::F32,
        call(
            Builtin::Max,
            [
                mie_phase("y") + mie_phase("z") * one_minus_nu,
                mie_phase("w"),
            ],
        ),
    );
    let rq = b.let_("rq", Ty::F32, call(Builtin::InverseSqrt, [q]));
    let mie_weight = b.let_(
        "mie_phase",
        Ty::F32,
        mie_phase("x") * one_plus_cos2.clone() * (rq.clone() * rq.clone() * rq),
    );
    let w = b.let_("w", Ty::F32, step * above);
    b.return_(name("acc") * w * (rayleigh * (0.75 * one_plus_cos2) + mie * mie_weight));
    Shader {
        model: Model::Aoas,
        params_len: PARAMS,
        doc: "The AOAS sky (seed 004 §3.2: O'Neil's single scattering inside one skydome, eqs. 1-4):\n\
              sky_radiance(dir) is linear RGB in O'Neil's relative units (proportional to the sun's\n\
              intensity) towards the view direction dir (skydome space: +z up; any length), black\n\
              below the viewer's horizon. Styles without cloud noise, cloud shapes or ambiguity.\n\
              Parameters (sky-core's AoasSky::kernel_constants): [0].xyz the viewer's apex, .w R + h;\n\
              [1].xyz the sun, .w sun . apex; [2] (R + h)² − R², (R + 1)² − (R + h)², log2 of the\n\
              density at the viewer, samples; [3].xyz the extinction 4π (Kr K + Km) log2(e), .w ESun Km;\n\
              [4].xyz ESun Kr K; [5] the Mie phase constants 1.5 (1 − g²)/(2 + g²), (1 − g)², 2g,\n\
              (1 − |g|)²."
            .into(),
        functions: vec![
            scale_log2(),
            Function::sky_radiance(b.finish()),
        ],
    }
}

/// The parameters of `sky` in the layout of [`shader`].
///
/// # Errors
/// [`UnsupportedSky`] for a style with cloud noise, cloud shapes or ambiguity.
pub fn params(sky: &AoasSky) -> Result<[f32; 4 * PARAMS], UnsupportedSky> {
    if sky.has_pattern_or_ambiguity() {
        return Err(UnsupportedSky(
            "the AOAS shader draws styles without cloud noise, cloud shapes or ambiguity",
        ));
    }
    let k = sky.kernel_constants();
    #[allow(clippy::cast_precision_loss)] // at most 64
    let samples = k.samples as f32;
    let e = k.extinction_log2;
    let r = k.rayleigh;
    Ok([
        k.apex.x,
        k.apex.y,
        k.apex.z,
        k.camera_radius,
        k.sun.x,
        k.sun.y,
        k.sun.z,
        k.sun_apex,
        k.camera_lift,
        k.far_lift,
        k.camera_density_log2,
        samples,
        e[0],
        e[1],
        e[2],
        k.mie,
        r[0],
        r[1],
        r[2],
        0.0,
        k.mie_phase[0],
        k.mie_phase[1],
        k.mie_phase[2],
        k.mie_phase[3],
    ])
}
