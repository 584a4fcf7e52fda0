//! What sky-core's `micromath` feature costs in accuracy, per model (issue 8, part 6): each
//! model against its independent f64 reference, over the upper hemisphere and the model's
//! domain. This file runs in both builds: `cargo test -p sky-tests --test micromath` holds the
//! default (libm) build's error, `cargo test -p sky-tests --features micromath --test
//! micromath` the micromath build's (scripts/test.sh runs both); the difference between the two
//! is the error micromath adds over libm. Bounds are the measured values rounded up.

use sky_core::aoas::{AoasSky, DayCycle, Scattering, Style};
use sky_core::neural::{NeuralSky, NeuralWeights, pretrained};
use sky_core::{PreethamSky, Sun, Vec3, geom};
use sky_tests::reference;
use sky_train::reference::aoas::SingleScattering;

const MICROMATH: bool = cfg!(feature = "micromath");

fn to_f64(v: Vec3) -> [f64; 3] {
    v.to_array().map(f64::from)
}

/// The largest per-channel relative difference of `got` from `want`, counting only channels
/// at least `floor` of the largest `want` channel seen by the caller.
fn relative(got: [f64; 3], want: [f64; 3], floor: f64) -> f64 {
    (0..3)
        .filter(|&c| want[c] >= floor)
        .fold(0.0, |m, c| m.max((got[c] - want[c]).abs() / want[c]))
}

/// View directions over the upper hemisphere: zenith 0-88° by 4°, azimuth every 10°.
fn hemisphere() -> Vec<Vec3> {
    (0..=22)
        .flat_map(|z| {
            (0..36).map(move |a| {
                geom::direction(
                    (4.0 * z as f32).to_radians(),
                    (10.0 * a as f32 + 0.3).to_radians(),
                )
            })
        })
        .collect()
}

fn report(model: &str, worst: f64, bound: f64) {
    let backend = if MICROMATH { "micromath" } else { "libm" };
    println!("{model} ({backend}): max relative error per channel against f64 {worst:.3e}");
    assert!(worst <= bound, "{model} ({backend}): {worst} > {bound}");
}

/// Preetham: linear sRGB against the f64 evaluation of seed 002, turbidity 2-6, sun zenith
/// 0-85°.
#[test]
fn preetham_error() {
    let mut worst = 0.0f64;
    for t in [2.0f32, 3.0, 4.5, 6.0] {
        for sun_zenith in [0.0f32, 20.0, 45.0, 70.0, 85.0] {
            let sun_azimuth = 0.4 * t;
            let sun = Sun::new(sun_zenith.to_radians(), sun_azimuth).expect("valid sun");
            let sky = PreethamSky::new(sun, t).expect("valid sky");
            let reference = reference::preetham::Sky::new(
                f64::from(t),
                f64::from(sun_zenith.to_radians()),
                f64::from(sun_azimuth),
            );
            for dir in hemisphere() {
                let want = reference::preetham::xyz_to_linear_srgb(
                    reference::preetham::xyy_to_xyz(reference.xyy(to_f64(dir))),
                );
                worst = worst.max(relative(to_f64(sky.rgb(dir)), want, 0.0));
            }
        }
    }
    report("Preetham", worst, if MICROMATH { 2e-2 } else { 1e-5 });
}

fn network(w: &NeuralWeights<12>) -> reference::neural::Network<12> {
    reference::neural::Network {
        hidden: w.hidden.map(|row| row.map(f64::from)),
        hidden_bias: w.hidden_bias.map(f64::from),
        output: w.output.map(|row| row.map(f64::from)),
        output_bias: w.output_bias.map(f64::from),
        input_offset: w.input_offset.map(f64::from),
        input_scale: w.input_scale.map(f64::from),
        output_scale: w.output_scale.map(f64::from),
    }
}

/// The shipped neural skies against their f64 evaluation, over their trained domain, where the
/// radiance is at least 10⁻³ of the sky's largest (below, the output z of eq. 6 nears 0 and
/// even f32 itself is far off in relative terms; see `neural_fixed.rs`).
#[test]
fn neural_error() {
    let mut worst = 0.0f64;
    for weights in [&pretrained::PREETHAM, &pretrained::HOSEK] {
        let reference = network(weights);
        let (t0, t1) = weights.turbidity_range;
        for si in 0..=6 {
            let sun_zenith = (15.0 * si as f32).to_radians();
            for t in [t0, 0.5 * (t0 + t1), t1] {
                let sun_azimuth = 0.9 * si as f32;
                let sun = Sun::new(sun_zenith, sun_azimuth).expect("valid sun");
                let sky = NeuralSky::new(weights, sun, t).expect("trained domain");
                let pairs: Vec<_> = hemisphere()
                    .into_iter()
                    .map(|d| {
                        let want = reference.rgb(
                            f64::from(sun_zenith),
                            f64::from(sun_azimuth),
                            f64::from(t),
                            to_f64(d),
                        );
                        (to_f64(sky.rgb(d)), want)
                    })
                    .collect();
                let peak = pairs
                    .iter()
                    .fold(0.0f64, |m, p| m.max(p.1[0].max(p.1[1]).max(p.1[2])));
                for (got, want) in pairs {
                    worst = worst.max(relative(got, want, 1e-3 * peak));
                }
            }
        }
    }
    report("neural", worst, if MICROMATH { 2e-2 } else { 1e-3 });
}

/// AOAS (physical style, 8 samples) against O'Neil's approximation in f64: sun zenith 0-89°,
/// views more than 2° from the sun (as in `aoas.rs`) and, apart, more than 10°. Near the sun
/// the Mie peak (g ≈ −0.99) magnifies any error in cos γ; with micromath the sun's direction,
/// from micromath's sin and cos, is off unit length by up to about 2e-3, which is what moves
/// the peak.
#[test]
fn aoas_error() {
    let (near, far) = aoas_worst(&[0.0, 30.0, 60.0, 80.0, 89.0]);
    report(
        "AOAS, views 2-10 deg from the sun included",
        near,
        if MICROMATH { 0.6 } else { 5e-4 },
    );
    report(
        "AOAS, views over 10 deg from the sun",
        far,
        if MICROMATH { 2e-2 } else { 5e-4 },
    );
}

/// The largest error more than 2° and more than 10° from the sun.
fn aoas_worst(zeniths: &[f32]) -> (f64, f64) {
    let (mut near, mut far) = (0.0f64, 0.0f64);
    for &sun_zenith in zeniths {
        let sun = Sun::new(sun_zenith.to_radians(), 1.0).expect("valid sun");
        let style = Style {
            day_cycle: DayCycle::Sun(sun),
            ..Style::default()
        };
        let scattering = Scattering {
            samples: 8,
            ..Scattering::default()
        };
        let sky = AoasSky::new(&scattering, &style).expect("valid sky");
        let reference = SingleScattering::o_neil_defaults(to_f64(sky.sun().direction()));
        let sun_dir = sky.sun().direction();
        for dir in hemisphere() {
            let cos_gamma = dir.dot(sun_dir);
            if cos_gamma > 2f32.to_radians().cos() {
                continue;
            }
            let e = relative(to_f64(sky.rgb(dir)), reference.o_neil(to_f64(dir), 8), 0.0);
            near = near.max(e);
            if cos_gamma < 10f32.to_radians().cos() {
                far = far.max(e);
            }
        }
    }
    (near, far)
}
