//! The shipped neural skies on seed 000's test protocol (§IV-A), and the generated constants
//! against the committed weight files. Nothing here trains: the committed weights are evaluated.

use std::path::Path;

use sky_core::neural::{NeuralWeights, pretrained};
use sky_train::eval::{self, Evaluation};
use sky_train::export;
use sky_train::sources::{ModelKind, Neural, SkyParams, SkySource};

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
