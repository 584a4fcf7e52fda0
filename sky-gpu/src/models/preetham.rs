//! The Preetham sky (seed 002, eqs. 10-12 and 27-28) per direction; the Perez coefficients
//! and zenith factors of one sky come from [`PreethamSky::kernel_constants`].

use sky_core::PreethamSky;
use sky_core::color::XYZ_TO_LINEAR_SRGB;
use sky_core::preetham::MIN_COS_THETA;

use crate::ir::{Body, Builtin, Expr, Function, Ty, call, float, select, vec3};
use crate::{Model, Shader, param};

/// vec4s of parameters: A, B', C, D', E, scale (each over Y, x, y) and the sun direction.
pub const PARAMS: usize = 7;

const LAYOUT: &str = "\
[0].xyz A, [1].xyz B log2(e), [2].xyz C, [3].xyz D log2(e), [4].xyz E: the Perez
coefficients of eq. 10 for Y, x and y; [5].xyz zenith value / F(0, sun zenith) (eqs. 11-12);
[6].xyz the unit direction towards the sun.";

/// The shader: `sky_radiance(dir)`, linear sRGB in cd/m².
#[must_use]
pub fn shader() -> Shader {
    let p = |i: i32| param(Model::Preetham, i);
    let mut b = Body::new();
    let d = normalised(&mut b);
    let s = b.let_("s", Ty::Vec3, p(6).swizzle("xyz"));
    let cos_gamma = b.let_(
        "cos_gamma",
        Ty::F32,
        call(
            Builtin::Clamp,
            [
                call(Builtin::Dot, [d.clone(), s.clone()]),
                float(-1.0),
                float(1.0),
            ],
        ),
    );
    let c = b.let_("c", Ty::Vec3, call(Builtin::Cross, [d.clone(), s]));
    let gamma = b.let_(
        "gamma",
        Ty::F32,
        call(
            Builtin::Atan2,
            [
                call(Builtin::Sqrt, [call(Builtin::Dot, [c.clone(), c])]),
                cos_gamma.clone(),
            ],
        ),
    );
    let inv_cos_theta = b.let_(
        "inv_cos_theta",
        Ty::F32,
        1.0 / call(Builtin::Max, [d.clone().swizzle("z"), float(MIN_COS_THETA)]),
    );
    // Eq. 10 for Y, x and y at once, times the factors of eqs. 11-12.
    let f = b.let_(
        "f",
        Ty::Vec3,
        p(5).swizzle("xyz")
            * ((1.0
                + p(0).swizzle("xyz")
                    * call(Builtin::Exp2, [p(1).swizzle("xyz") * inv_cos_theta]))
                * (1.0
                    + p(2).swizzle("xyz") * call(Builtin::Exp2, [p(3).swizzle("xyz") * gamma])
                    + p(4).swizzle("xyz") * (cos_gamma.clone() * cos_gamma))),
    );
    // Below the horizon the luminance is 0 and the chromaticity the horizon's.
    let lum = b.let_(
        "luminance",
        Ty::F32,
        select(super::above_horizon(d), f.clone().swizzle("x"), float(0.0)),
    );
    let (x, y) = (f.clone().swizzle("y"), f.swizzle("z"));
    // Eq. 27, with black for y <= 0 as sky-core's xyy_to_xyz.
    let positive = float(0.0).less(y.clone());
    let k = b.let_(
        "k",
        Ty::F32,
        select(positive.clone(), lum.clone() / y.clone(), float(0.0)),
    );
    let xyz = b.let_(
        "xyz",
        Ty::Vec3,
        vec3(
            x.clone() * k.clone(),
            select(positive, lum, float(0.0)),
            (1.0 - x - y) * k,
        ),
    );
    b.return_(linear_srgb(xyz));
    Shader {
        model: Model::Preetham,
        params_len: PARAMS,
        doc: format!(
            "The Preetham sky (Perez distribution with Preetham's coefficients, seed 002 eqs. 10-12,\n\
             27-28): sky_radiance(dir) is linear sRGB in cd/m² towards the view direction dir\n\
             (sky-core's frame: +z up; any length), 0 in luminance below the horizon.\n\
             Parameters: {LAYOUT}"
        ),
        functions: vec![Function::sky_radiance(b.finish())],
    }
}

/// `let d = dir * inverseSqrt(dot(dir, dir));`: the view direction normalised.
pub(crate) fn normalised(b: &mut Body) -> Expr {
    let dir = crate::ir::name("dir");
    b.let_(
        "d",
        Ty::Vec3,
        dir.clone()
            * call(
                Builtin::InverseSqrt,
                [call(Builtin::Dot, [dir.clone(), dir])],
            ),
    )
}

/// XYZ → linear sRGB (seed 002 eq. 28, sky-core's matrix), as three dot products.
pub(crate) fn linear_srgb(xyz: Expr) -> Expr {
    let row = |r: usize| {
        let m = XYZ_TO_LINEAR_SRGB.row(r);
        call(
            Builtin::Dot,
            [vec3(float(m.x), float(m.y), float(m.z)), xyz.clone()],
        )
    };
    vec3(row(0), row(1), row(2))
}

/// The parameters of `sky` in the layout of [`shader`].
#[must_use]
pub fn params(sky: &PreethamSky) -> [f32; 4 * PARAMS] {
    let k = sky.kernel_constants();
    let [y, x, yy] = k.perez_log2;
    let s = sky.sun().direction();
    let rows = [
        [y.a, x.a, yy.a],
        [y.b, x.b, yy.b],
        [y.c, x.c, yy.c],
        [y.d, x.d, yy.d],
        [y.e, x.e, yy.e],
        k.scale,
        [s.x, s.y, s.z],
    ];
    let mut out = [0.0; 4 * PARAMS];
    for (i, r) in rows.iter().enumerate() {
        out[4 * i..4 * i + 3].copy_from_slice(r);
    }
    out
}
