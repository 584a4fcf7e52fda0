//! The shader descriptions mean what sky-core computes: an f32 interpreter of the description
//! language (written here, independent of the printers) runs each model's `sky_radiance` with
//! one sky's packed parameters and is compared with sky-core's own evaluation over the sphere.
//! (The GPU's results are compared with sky-core by sky-wasm's browser tests.)

use std::collections::HashMap;

use sky_core::aoas::{AoasSky, Preset, Scattering};
use sky_core::daylight::Daylight;
use sky_core::neural::pretrained;
use sky_core::sh::ShSky;
use sky_core::{NeuralSky, PreethamSky, Sun, Vec3, geom};
use sky_gpu::ir::{BinOp, Builtin, Expr, Function, Stmt};
use sky_gpu::models::{aoas, daylight, neural, preetham, sh};
use sky_gpu::{Model, Shader};

#[derive(Debug, Clone, Copy)]
enum V {
    F(f32),
    I(i32),
    B(bool),
    /// A vector of 3 or 4 floats.
    Vec(usize, [f32; 4]),
}

impl V {
    fn f(self) -> f32 {
        match self {
            V::F(x) => x,
            other => panic!("not a float: {other:?}"),
        }
    }
    fn i(self) -> i32 {
        match self {
            V::I(x) => x,
            other => panic!("not an int: {other:?}"),
        }
    }
    fn lanes(self) -> (usize, [f32; 4]) {
        match self {
            V::F(x) => (1, [x; 4]),
            V::Vec(n, v) => (n, v),
            other => panic!("not numeric: {other:?}"),
        }
    }
}

/// Per component, broadcasting scalars as both languages do.
fn zip(a: V, b: V, f: impl Fn(f32, f32) -> f32) -> V {
    let ((na, va), (nb, vb)) = (a.lanes(), b.lanes());
    let n = na.max(nb);
    let mut out = [0.0; 4];
    for k in 0..n {
        out[k] = f(
            va[if na == 1 { 0 } else { k }],
            vb[if nb == 1 { 0 } else { k }],
        );
    }
    if n == 1 { V::F(out[0]) } else { V::Vec(n, out) }
}

fn map(a: V, f: impl Fn(f32) -> f32) -> V {
    zip(a, V::F(0.0), |x, _| f(x))
}

struct Interpreter<'a> {
    functions: HashMap<&'a str, &'a Function>,
    params: (&'a str, Vec<[f32; 4]>),
}

impl Interpreter<'_> {
    fn call(&self, f: &str, args: Vec<V>) -> V {
        let func = self.functions[f];
        let mut env: HashMap<String, V> = func
            .params
            .iter()
            .map(|(n, _)| n.clone())
            .zip(args)
            .collect();
        self.block(&func.body, &mut env).expect("function returns")
    }

    fn block(&self, body: &[Stmt], env: &mut HashMap<String, V>) -> Option<V> {
        for s in body {
            match s {
                Stmt::Let(n, _, e) | Stmt::Var(n, _, e) => {
                    let v = self.expr(e, env);
                    env.insert(n.clone(), v);
                }
                Stmt::Assign(n, op, e) => {
                    let v = self.expr(e, env);
                    let v = match op {
                        None => v,
                        Some(op) => binary(*op, env[n], v),
                    };
                    env.insert(n.clone(), v);
                }
                Stmt::For(i, count, body) => {
                    let count = self.expr(count, env).i();
                    for k in 0..count {
                        env.insert(i.clone(), V::I(k));
                        if let Some(r) = self.block(body, env) {
                            return Some(r);
                        }
                    }
                }
                Stmt::Return(e) => return Some(self.expr(e, env)),
            }
        }
        None
    }

    fn expr(&self, e: &Expr, env: &HashMap<String, V>) -> V {
        match e {
            Expr::Float(x) => V::F(*x),
            Expr::Int(x) => V::I(*x),
            Expr::Name(n) => *env.get(n).unwrap_or_else(|| panic!("unbound {n}")),
            Expr::Binary(op, a, b) => binary(*op, self.expr(a, env), self.expr(b, env)),
            Expr::Neg(a) => map(self.expr(a, env), |x| -x),
            Expr::Call(f, args) => {
                let a: Vec<V> = args.iter().map(|x| self.expr(x, env)).collect();
                builtin(*f, &a)
            }
            Expr::CallFn(f, args) => self.call(f, args.iter().map(|x| self.expr(x, env)).collect()),
            Expr::Swizzle(x, c) => {
                let (_, v) = self.expr(x, env).lanes();
                let mut out = [0.0; 4];
                for (k, ch) in c.chars().enumerate() {
                    out[k] = v["xyzw".find(ch).expect("component")];
                }
                if c.len() == 1 {
                    V::F(out[0])
                } else {
                    V::Vec(c.len(), out)
                }
            }
            Expr::Index(x, i) => {
                let Expr::Name(n) = x.as_ref() else {
                    panic!("index of a non-name")
                };
                assert_eq!(n, self.params.0, "only the parameter array is indexed");
                let i = usize::try_from(self.expr(i, env).i()).expect("index ≥ 0");
                V::Vec(4, self.params.1[i])
            }
            Expr::Construct(ty, args) => {
                let a: Vec<V> = args.iter().map(|x| self.expr(x, env)).collect();
                match ty {
                    sky_gpu::ir::Ty::I32 =>
                    {
                        #[allow(clippy::cast_possible_truncation)]
                        V::I(a[0].f() as i32)
                    }
                    sky_gpu::ir::Ty::F32 => a[0],
                    t => {
                        let n = if *t == sky_gpu::ir::Ty::Vec3 { 3 } else { 4 };
                        let mut flat = Vec::new();
                        for v in &a {
                            let (k, lanes) = v.lanes();
                            flat.extend_from_slice(&lanes[..k]);
                        }
                        if flat.len() == 1 {
                            flat = vec![flat[0]; n];
                        }
                        assert_eq!(flat.len(), n, "constructor arity");
                        let mut out = [0.0; 4];
                        out[..n].copy_from_slice(&flat);
                        V::Vec(n, out)
                    }
                }
            }
            #[allow(clippy::cast_precision_loss)]
            Expr::ToFloat(x) => V::F(self.expr(x, env).i() as f32),
            Expr::Select {
                condition,
                if_true,
                if_false,
            } => match self.expr(condition, env) {
                V::B(true) => self.expr(if_true, env),
                V::B(false) => self.expr(if_false, env),
                other => panic!("condition {other:?}"),
            },
        }
    }
}

fn binary(op: BinOp, a: V, b: V) -> V {
    match (op, a, b) {
        (BinOp::Add, V::I(x), V::I(y)) => V::I(x + y),
        (BinOp::Mul, V::I(x), V::I(y)) => V::I(x * y),
        (BinOp::Less, V::I(x), V::I(y)) => V::B(x < y),
        (BinOp::Less, x, y) => V::B(x.f() < y.f()),
        (BinOp::GreaterEqual, x, y) => V::B(x.f() >= y.f()),
        (BinOp::Add, x, y) => zip(x, y, |p, q| p + q),
        (BinOp::Sub, x, y) => zip(x, y, |p, q| p - q),
        (BinOp::Mul, x, y) => zip(x, y, |p, q| p * q),
        (BinOp::Div, x, y) => zip(x, y, |p, q| p / q),
    }
}

fn builtin(f: Builtin, a: &[V]) -> V {
    let dot = |x: V, y: V| {
        let ((n, u), (_, v)) = (x.lanes(), y.lanes());
        (0..n).map(|k| u[k] * v[k]).sum::<f32>()
    };
    match f {
        Builtin::Exp2 => map(a[0], f32::exp2),
        Builtin::Sqrt => map(a[0], f32::sqrt),
        Builtin::InverseSqrt => map(a[0], |x| 1.0 / x.sqrt()),
        Builtin::Atan2 => V::F(a[0].f().atan2(a[1].f())),
        Builtin::Max => zip(a[0], a[1], f32::max),
        Builtin::Min => zip(a[0], a[1], f32::min),
        Builtin::Clamp => zip(zip(a[0], a[1], f32::max), a[2], f32::min),
        Builtin::Dot => V::F(dot(a[0], a[1])),
        Builtin::Cross => {
            let ((_, u), (_, v)) = (a[0].lanes(), a[1].lanes());
            V::Vec(
                3,
                [
                    u[1] * v[2] - u[2] * v[1],
                    u[2] * v[0] - u[0] * v[2],
                    u[0] * v[1] - u[1] * v[0],
                    0.0,
                ],
            )
        }
    }
}

/// The description's `sky_radiance(dir)` for packed `params`.
fn radiance(shader: &Shader, params: &[f32], dir: Vec3) -> Vec3 {
    let interpreter = Interpreter {
        functions: shader
            .functions
            .iter()
            .map(|f| (f.name.as_str(), f))
            .collect(),
        params: (
            shader.model.params_name(),
            params
                .chunks_exact(4)
                .map(|c| [c[0], c[1], c[2], c[3]])
                .collect(),
        ),
    };
    let (n, v) = interpreter
        .call("sky_radiance", vec![V::Vec(3, [dir.x, dir.y, dir.z, 0.0])])
        .lanes();
    assert_eq!(n, 3);
    Vec3::new(v[0], v[1], v[2])
}

/// The largest relative difference per channel over directions of the upper hemisphere (the
/// sky; below it the networks are untrained and the SH series rings) where sky-core's radiance
/// is above 1e-3 of the channel's largest (the browser tests' measure).
fn worst(shader: &Shader, params: &[f32], cpu: impl Fn(Vec3) -> Vec3) -> f32 {
    let dirs: Vec<Vec3> = (0..20)
        .flat_map(|i| {
            (0..48).map(move |k| geom::direction(0.04 + 0.08 * i as f32, 0.131 * k as f32))
        })
        .collect();
    let want: Vec<Vec3> = dirs.iter().map(|d| cpu(*d)).collect();
    let peak = want.iter().fold(Vec3::ZERO, |m, w| m.max(*w));
    let mut worst = 0.0f32;
    for (d, w) in dirs.iter().zip(&want) {
        let got = radiance(shader, params, *d);
        for c in 0..3 {
            if w[c] > 1e-3 * peak[c] {
                let e = (got[c] - w[c]).abs() / w[c];
                if e > worst && std::env::var("SKY_DEBUG").is_ok() {
                    println!("  {d} c{c}: {} vs {} (peak {})", got[c], w[c], peak[c]);
                }
                worst = worst.max(e);
            }
        }
    }
    worst
}

#[test]
fn each_description_evaluates_to_sky_cores_values() {
    let suns = [(0.2, 0.5), (0.9, 2.0), (1.45, -1.0)];
    for (zenith, azimuth) in suns {
        let sun = Sun::new(zenith, azimuth).expect("valid sun");
        let p = PreethamSky::new(sun, 3.5).expect("valid");
        let e = worst(&Model::Preetham.shader(), &preetham::params(&p), |d| {
            p.rgb(d)
        });
        println!("preetham, sun ({zenith}, {azimuth}): {e:.2e}");
        assert!(e < 2e-5, "preetham {e}");
        for (name, weights) in [
            ("preetham", &pretrained::PREETHAM),
            ("hosek", &pretrained::HOSEK),
        ] {
            let n = NeuralSky::new(weights, sun, 3.5).expect("valid");
            let e = worst(&Model::Neural.shader(), &neural::params(&n), |d| n.rgb(d));
            println!("neural {name}, sun ({zenith}, {azimuth}): {e:.2e}");
            // The network's sums cancel: the inputs' last-bit differences (sqrt and
            // inverseSqrt here for sky-core's polynomial 1/√x) grow to 1e-4 with a low sun.
            assert!(e < 3e-4, "neural {e}");
        }
        for bands in [3, 7] {
            let s = ShSky::new(sun, 3.5, bands).expect("valid");
            let e = worst(&Model::Sh.shader(), &sh::params(&s), |d| s.radiance(d));
            println!("sh {bands} bands, sun ({zenith}, {azimuth}): {e:.2e}");
            assert!(e < 2e-5, "sh {e}");
        }
    }
    for preset in Preset::ALL {
        let a = AoasSky::new(&Scattering::default(), &preset.style()).expect("valid");
        match aoas::params(&a) {
            Ok(params) => {
                let e = worst(&Model::Aoas.shader(), &params, |d| a.rgb(d));
                println!("aoas {}: {e:.2e}", preset.name());
                assert!(e < 2e-5, "aoas {} {e}", preset.name());
            }
            Err(_) => assert!(a.has_pattern_or_ambiguity(), "{}", preset.name()),
        }
    }
}

/// The daylight sky's description against sky-core's `DaylightSky::rgb`: by day, in both
/// blends (day to dusk, dusk to night), in civil and nautical twilight, at −18° and below it,
/// for the clearest, the default and the haziest atmosphere of sky-core's tables.
#[test]
fn the_daylight_description_evaluates_to_sky_cores_values() {
    let shader = Model::Daylight.shader();
    let mut worst_all = 0.0f32;
    for elevation in [70.0f32, 30.0, 2.0, -3.0, -7.0, -12.0, -18.0, -30.0] {
        for aod in [
            sky_core::daylight::MIN_AOD,
            sky_core::daylight::DEFAULT_AOD,
            sky_core::daylight::MAX_AOD,
        ] {
            let sun = Sun::new((90.0 - elevation).to_radians(), 2.2).expect("valid sun");
            let sky = Daylight::new(sun, aod).expect("valid").sky();
            let e = worst(&shader, &daylight::params(&sky), |d| sky.rgb(d));
            println!("daylight, sun {elevation}°, aod {aod}: {e:.2e}");
            worst_all = worst_all.max(e);
        }
    }
    // As the neural sky's (above): the sums cancel, the inputs' last bits grow.
    assert!(worst_all < 3e-4, "daylight {worst_all}");
}

/// sky-core's one below-horizon rule (its crate docs, "Conventions") in every description: the
/// shader and sky-core both give exactly 0 for directions below the horizon (from 1e-5 below it
/// to the nadir, every azimuth), and both give the sky's value on it (the f32 nearest π/2,
/// whose cos θ is −4.4e-8, inside the tolerance).
#[test]
fn each_description_is_black_below_the_horizon_as_sky_core() {
    let sun = Sun::new(1.2, 0.4).expect("valid sun");
    let below: Vec<Vec3> = [1e-5f32, 1e-3, 0.1, 0.7, 1.0]
        .iter()
        .flat_map(|&z| {
            (0..12).map(move |k| {
                let phi = core::f32::consts::FRAC_PI_6 * k as f32;
                let r = (1.0 - z * z).sqrt();
                Vec3::new(r * phi.cos(), r * phi.sin(), -z)
            })
        })
        .collect();
    let on: Vec<Vec3> = (0..12)
        .map(|k| {
            geom::direction(
                core::f32::consts::FRAC_PI_2,
                core::f32::consts::FRAC_PI_6 * k as f32,
            )
        })
        .collect();
    assert!(on.iter().all(|d| d.z < 0.0 && !geom::below_horizon(*d)));
    let p = PreethamSky::new(sun, 3.0).expect("valid");
    let n = NeuralSky::new(&pretrained::HOSEK, sun, 3.0).expect("valid");
    let s = ShSky::new(sun, 3.0, 7).expect("valid");
    let a = AoasSky::new(&Scattering::default(), &Preset::Physical.style()).expect("valid");
    let day = Daylight::clear(sun).sky();
    let dusk = Daylight::clear(Sun::new(97f32.to_radians(), 0.4).expect("valid sun")).sky();
    type Case<'a> = (&'a str, Shader, Vec<f32>, &'a dyn Fn(Vec3) -> Vec3);
    let cases: [Case; 6] = [
        (
            "preetham",
            Model::Preetham.shader(),
            preetham::params(&p).to_vec(),
            &|d| p.rgb(d),
        ),
        ("neural", Model::Neural.shader(), neural::params(&n), &|d| {
            n.rgb(d)
        }),
        ("sh", Model::Sh.shader(), sh::params(&s).to_vec(), &|d| {
            s.radiance(d)
        }),
        (
            "aoas",
            Model::Aoas.shader(),
            aoas::params(&a).expect("no pattern").to_vec(),
            &|d| a.rgb(d),
        ),
        (
            "daylight",
            Model::Daylight.shader(),
            daylight::params(&day),
            &|d| day.rgb(d),
        ),
        (
            "daylight in a blend",
            Model::Daylight.shader(),
            daylight::params(&dusk),
            &|d| dusk.rgb(d),
        ),
    ];
    for (name, shader, params, cpu) in &cases {
        for d in &below {
            assert_eq!(cpu(*d), Vec3::ZERO, "{name}: sky-core at {d}");
            assert_eq!(
                radiance(shader, params, *d),
                Vec3::ZERO,
                "{name}: shader at {d}"
            );
        }
        for d in &on {
            let (want, got) = (cpu(*d), radiance(shader, params, *d));
            assert!(
                want.max_element() > 0.0,
                "{name}: sky-core on the horizon at {d}: {want}"
            );
            assert!(
                got.max_element() > 0.0,
                "{name}: shader on the horizon at {d}: {got}"
            );
        }
    }
}
