//! The shipped neural skies on seed 000's test protocol (§IV-A), and the generated constants
//! against the committed weight files. Nothing here trains: the committed weights are evaluated.

use std::path::Path;

use sky_core::neural::{NeuralSky, NeuralWeights, pretrained};
use sky_core::{Sun, Vec3};
use sky_train::eval::{self, Evaluation};
use sky_train::sources::{ModelKind, Neural, SkyParams, SkySource};
use sky_train::train::{dataset, net::Scratch};
use sky_train::{bench, dispatch, export};

fn evaluate(weights: &'static NeuralWeights<12>, model: ModelKind, kind: ModelKind) -> Evaluation {
    let network = move |p: &SkyParams| -> anyhow::Result<Box<dyn SkySource>> {
        Ok(Box::new(Neural::new(weights, kind, p)?))
    };
    eval::evaluate(model, &network).expect("evaluation runs")
}

/// Preetham: mean NRMSE and mean relative irradiance difference (eq. 11) on the paper's test
/// set (turbidity 2.5-5.5, 7 sun zeniths, sun azimuth away from the training one).
#[test]
fn neural_preetham_on_the_papers_protocol() {
    let e = evaluate(
        &pretrained::PREETHAM,
        ModelKind::Preetham,
        ModelKind::NeuralPreetham,
    );
    print!("{}", e.report());
    assert_eq!(e.images.len(), 4 * 7);
    let (nrmse, irradiance) = (e.mean_nrmse(), e.mean_irradiance_relative());
    assert!(nrmse <= PREETHAM_NRMSE_BOUND, "mean NRMSE {nrmse:.5}");
    assert!(
        irradiance <= PREETHAM_IRRADIANCE_BOUND,
        "irradiance difference {irradiance:.5}"
    );
}

/// Hosek-Wilkie: the same on turbidity 1.5-9.5.
#[test]
fn neural_hosek_on_the_papers_protocol() {
    let e = evaluate(&pretrained::HOSEK, ModelKind::Hosek, ModelKind::NeuralHosek);
    print!("{}", e.report());
    assert_eq!(e.images.len(), 9 * 7);
    let (nrmse, irradiance) = (e.mean_nrmse(), e.mean_irradiance_relative());
    assert!(nrmse <= HOSEK_NRMSE_BOUND, "mean NRMSE {nrmse:.5}");
    assert!(
        irradiance <= HOSEK_IRRADIANCE_BOUND,
        "irradiance difference {irradiance:.5}"
    );
}

// The bounds hold what the shipped weights reach, a little above the measured figures (see
// docs/training.md), so that a worse network fails. Of the goals (Preetham NRMSE
// 0.007, irradiance 0.1 %; Hosek-Wilkie NRMSE 0.020, irradiance 2 %) only the Hosek-Wilkie
// irradiance is reached, and its bound is the goal's; seed 000's own figures are 0.0145 / 0.26 %
// (Preetham) and 0.0395 / 4.5 % (Hosek-Wilkie).
const PREETHAM_NRMSE_BOUND: f64 = 0.0088;
const PREETHAM_IRRADIANCE_BOUND: f64 = 0.0022;
const HOSEK_NRMSE_BOUND: f64 = 0.0245;
const HOSEK_IRRADIANCE_BOUND: f64 = 0.02;

/// The generated constant `name` (in `source`) is exactly what `sky-train export` makes of the
/// committed weight file `file`, and decodes to the same weights.
fn check_generated<const H: usize>(
    file: &str,
    name: &str,
    source: &str,
    constant: &sky_core::neural::NeuralWeights<H>,
) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let weights_path = root.join("sky-core/weights").join(file);
    let weights = export::read_weights::<H>(&weights_path).expect("weight file decodes");
    assert_eq!(&weights, constant, "{file} and the {name} constant differ");
    let generated =
        export::pretrained_source(&weights, name, &weights_path).expect("a constant's name");
    let committed =
        std::fs::read_to_string(root.join("sky-core/src/neural/pretrained").join(source))
            .expect("generated file exists");
    assert!(
        generated == committed,
        "sky-core/src/neural/pretrained/{source} is not what `sky-train export` makes of {file}: regenerate it"
    );
}

/// Every shipped network's constant regenerates from its weight file.
#[test]
fn pretrained_constants_regenerate_from_the_weight_files() {
    check_generated(
        "preetham.skyn",
        "PREETHAM",
        "preetham.rs",
        &pretrained::PREETHAM,
    );
    check_generated("hosek.skyn", "HOSEK", "hosek.rs", &pretrained::HOSEK);
    check_generated(
        "daylight_day.skyn",
        "DAYLIGHT_DAY",
        "daylight_day.rs",
        &pretrained::DAYLIGHT_DAY,
    );
    check_generated(
        "daylight_dusk.skyn",
        "DAYLIGHT_DUSK",
        "daylight_dusk.rs",
        &pretrained::DAYLIGHT_DUSK,
    );
    check_generated(
        "daylight_night.skyn",
        "DAYLIGHT_NIGHT",
        "daylight_night.rs",
        &pretrained::DAYLIGHT_NIGHT,
    );
}

/// `rgb_batch` compiled for the widest vectors this CPU has (AVX2 where present, as `sky-train`
/// runs it) and for the baseline gives what `rgb` gives, bit for bit, over the benchmark's
/// hemisphere and directions that are not unit, zero, infinite or NaN.
#[test]
fn batch_equals_one_direction_bit_for_bit_on_every_instruction_set() {
    let mut dirs = bench::hemisphere_directions(256, 128);
    for (i, d) in [
        Vec3::ZERO,
        Vec3::splat(f32::NAN),
        Vec3::new(f32::INFINITY, 0.0, 1.0),
        Vec3::new(0.0, f32::NEG_INFINITY, -1.0),
        Vec3::new(1e-30, 0.0, 0.0),
        Vec3::new(3e20, -1e20, 2e20),
        Vec3::new(0.3, -0.2, -0.9),
    ]
    .into_iter()
    .cycle()
    .take(300)
    .enumerate()
    {
        dirs.insert(i * 97 % dirs.len(), d);
    }
    for weights in [&pretrained::PREETHAM, &pretrained::HOSEK] {
        let sky = NeuralSky::new(weights, Sun::new(0.9, 0.3).expect("valid"), 3.0).expect("valid");
        let one: Vec<Vec3> = dirs.iter().map(|&d| sky.rgb(d)).collect();
        let mut baseline = vec![Vec3::ZERO; dirs.len()];
        sky.rgb_batch(&dirs, &mut baseline);
        let mut widest = vec![Vec3::ZERO; dirs.len()];
        dispatch::fastest(
            #[inline(always)]
            || sky.rgb_batch(&dirs, &mut widest),
        );
        for (i, d) in dirs.iter().enumerate() {
            let bits = |v: Vec3| v.to_array().map(f32::to_bits);
            assert_eq!(bits(baseline[i]), bits(one[i]), "baseline, {d}");
            assert_eq!(
                bits(widest[i]),
                bits(one[i]),
                "{}, {d}",
                dispatch::describe()
            );
            assert!(one[i].is_finite() && one[i].min_element() >= 0.0, "{d}");
        }
    }
}

/// The AVX2 + FMA kernel (which `sky-train` runs where the CPU has it) is as accurate as `rgb`:
/// against the same network evaluated in f64 (the trainer's forward pass), both stay within
/// 4e-4 of the direction's largest channel over the upper hemisphere (both measure 2e-4 at
/// worst, where the output sum z of eq. 6 nearly cancels), for both shipped skies
/// over their trained suns and turbidities. Its results are finite and non-negative for
/// directions that are not unit, zero, infinite or NaN.
#[test]
fn avx2_kernel_is_as_accurate_as_one_direction() {
    if !dispatch::has_avx2_fma() {
        eprintln!("this CPU has no AVX2 + FMA: nothing to compare");
        return;
    }
    let mut dirs = bench::hemisphere_directions(256, 128);
    let upper = dirs.len();
    dirs.extend([
        Vec3::ZERO,
        Vec3::splat(f32::NAN),
        Vec3::new(f32::INFINITY, 0.0, 1.0),
        Vec3::new(0.0, f32::NEG_INFINITY, -1.0),
        Vec3::new(1e-30, 0.0, 0.0),
        Vec3::new(3e20, -1e20, -2e20),
    ]);
    let mut scratch = Scratch::default();
    let (mut worst_fast, mut worst_one) = (0f64, 0f64);
    for (weights, turbidities) in [
        (&pretrained::PREETHAM, [2.0, 4.0, 6.0]),
        (&pretrained::HOSEK, [1.0, 5.0, 10.0]),
    ] {
        let (net, scaling) = export::from_weights(weights).expect("one output scale");
        for zenith in [0.0f32, 0.5, 1.0, 1.5, std::f32::consts::FRAC_PI_2] {
            for t in turbidities {
                // Sun azimuth π: eq. 10's rotation is the identity, as in training.
                let sun = Sun::new(zenith, std::f32::consts::PI).expect("valid sun");
                let sky = NeuralSky::new(weights, sun, t).expect("trained domain");
                let mut fast = vec![Vec3::ZERO; dirs.len()];
                dispatch::neural_batch(&sky, &dirs, &mut fast);
                for (i, d) in dirs.iter().enumerate() {
                    let f = fast[i];
                    assert!(f.is_finite() && f.min_element() >= 0.0, "{d}: {f}");
                    if i >= upper {
                        continue;
                    }
                    let v = d.to_array().map(f64::from);
                    let norm = v.iter().map(|c| c * c).sum::<f64>().sqrt();
                    let v = v.map(|c| c / norm);
                    let input = dataset::input(f64::from(t), f64::from(zenith), v);
                    let z = net.forward(&scaling.apply(&input), &mut scratch);
                    let exact = z.map(|z| 0.5 * scaling.output_scale * z * z);
                    let peak = exact.iter().copied().fold(0.0, f64::max);
                    let error = |rgb: Vec3| {
                        (0..3)
                            .map(|c| (f64::from(rgb[c]) - exact[c]).abs())
                            .fold(0.0, f64::max)
                            / peak
                    };
                    let (e_fast, e_one) = (error(f), error(sky.rgb(*d)));
                    worst_fast = worst_fast.max(e_fast);
                    worst_one = worst_one.max(e_one);
                    assert!(
                        e_fast <= 4e-4 && e_one <= 4e-4,
                        "{d}, sun zenith {zenith}, t {t}: AVX2 {e_fast:.2e}, rgb {e_one:.2e}"
                    );
                }
            }
        }
    }
    eprintln!(
        "largest error against f64, of the direction's largest channel: AVX2 + FMA {worst_fast:.2e}, rgb {worst_one:.2e}"
    );
}
