//! The shipped neural skies on seed 000's test protocol (§IV-A), and the generated constants
//! against the committed weight files. Nothing here trains: the committed weights are evaluated.

use std::path::Path;

use sky_core::neural::{NeuralSky, NeuralWeights, pretrained};
use sky_core::{Sun, Vec3};
use sky_train::eval::{self, Evaluation};
use sky_train::sources::{ModelKind, Neural, SkyParams, SkySource};
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
// README "Neural sky"), so that a worse network fails. Of the goals (Preetham NRMSE
// 0.007, irradiance 0.1 %; Hosek-Wilkie NRMSE 0.020, irradiance 2 %) only the Hosek-Wilkie
// irradiance is reached, and its bound is the goal's; seed 000's own figures are 0.0145 / 0.26 %
// (Preetham) and 0.0395 / 4.5 % (Hosek-Wilkie).
const PREETHAM_NRMSE_BOUND: f64 = 0.0088;
const PREETHAM_IRRADIANCE_BOUND: f64 = 0.0022;
const HOSEK_NRMSE_BOUND: f64 = 0.0245;
const HOSEK_IRRADIANCE_BOUND: f64 = 0.02;

/// The generated constants are exactly what `sky-train export` makes of the committed weight
/// files, and decode to the same weights.
#[test]
fn pretrained_constants_regenerate_from_the_weight_files() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    for (file, name, source, constant) in [
        (
            "preetham.skyn",
            "PREETHAM",
            "preetham.rs",
            &pretrained::PREETHAM,
        ),
        ("hosek.skyn", "HOSEK", "hosek.rs", &pretrained::HOSEK),
    ] {
        let weights_path = root.join("sky-core/weights").join(file);
        let weights = export::read_weights::<12>(&weights_path).expect("weight file decodes");
        assert_eq!(&weights, constant, "{file} and the {name} constant differ");
        let generated = export::pretrained_source(&weights, name, &weights_path);
        let committed =
            std::fs::read_to_string(root.join("sky-core/src/neural/pretrained").join(source))
                .expect("generated file exists");
        assert!(
            generated == committed,
            "sky-core/src/neural/pretrained/{source} is not what `sky-train export` makes of {file}: regenerate it"
        );
    }
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
