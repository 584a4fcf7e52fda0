//! The fixed-point neural sky against the f32 one (issue 8, part 5): within 1 % relative, per
//! channel, over the upper hemisphere and the trained domain, for both shipped networks; the
//! quantised constants regenerate from the weight files; no input makes it panic.

use std::path::Path;

use sky_core::neural::fixed::{self, FixedNeuralSky, FixedNeuralWeights};
use sky_core::neural::{NeuralSky, NeuralWeights, pretrained};
use sky_core::{Sun, geom};
use sky_tests::reference;
use sky_train::export;

/// The bound of issue 8: 1 % relative, per channel.
const RELATIVE_BOUND: f64 = 0.01;
/// Where the relative bound applies: radiance at least this fraction of the channel's largest
/// radiance in that sky (a dynamic range of 10⁴). Below it the network's output z of eq. 6
/// passes near 0, where no finite precision gives a relative bound: there the f32 network
/// itself is off its own f64 evaluation by up to 21 % (measured and printed below), and the test holds the
/// absolute difference instead, [`ABSOLUTE_BOUND`] of the channel's largest radiance.
const FLOOR: f64 = 1e-4;
/// The bound on the absolute difference below [`FLOOR`], as a fraction of the channel's largest
/// radiance in that sky.
const ABSOLUTE_BOUND: f64 = 1e-6;

/// What the comparison over the domain found.
#[derive(Default)]
struct Comparison {
    /// Largest relative difference fixed vs f32 at or above the floor, and where.
    relative: (f64, String),
    /// Largest difference fixed vs f32 below the floor, relative to the channel's peak.
    absolute: f64,
    /// Largest relative difference f32 vs the f64 reference below the floor.
    f32_vs_f64_below_floor: f64,
    /// Samples (per channel) at or above and below the floor.
    above: usize,
    below: usize,
}

fn network(w: &NeuralWeights<12>) -> reference::neural::Network<12> {
    let f = |v: &[f32]| v.iter().map(|&x| f64::from(x)).collect::<Vec<_>>();
    reference::neural::Network {
        hidden: w.hidden.map(|row| row.map(f64::from)),
        hidden_bias: w.hidden_bias.map(f64::from),
        output: w.output.map(|row| row.map(f64::from)),
        output_bias: w.output_bias.map(f64::from),
        input_offset: f(&w.input_offset).try_into().expect("6"),
        input_scale: f(&w.input_scale).try_into().expect("6"),
        output_scale: w.output_scale.map(f64::from),
    }
}

/// Compares the fixed-point and the f32 sky over a grid of the trained domain (sun zenith,
/// turbidity, sun azimuth) and of the upper hemisphere (view zenith 0-90° every 5°, azimuth
/// every 7.5°).
fn compare(weights: &NeuralWeights<12>, quantised: &FixedNeuralWeights<12>) -> Comparison {
    let (t0, t1) = weights.turbidity_range;
    let (z0, z1) = weights.sun_zenith_range;
    #[allow(clippy::cast_precision_loss)] // a power of two
    let unit = (1u64 << quantised.radiance_frac) as f64;
    let reference = network(weights);
    let mut result = Comparison::default();
    for si in 0..=9 {
        let sun_zenith = z0 + (z1 - z0) * si as f32 / 9.0;
        for ti in 0..=4 {
            let turbidity = t0 + (t1 - t0) * ti as f32 / 4.0;
            let sun_azimuth = 0.7 * (si * 5 + ti) as f32; // varied, to exercise eq. 10
            let sun = Sun::new(sun_zenith, sun_azimuth).expect("valid sun");
            let sky = NeuralSky::new(weights, sun, turbidity).expect("trained domain");
            let fixed = FixedNeuralSky::new(quantised, sun, turbidity).expect("trained domain");
            let mut samples = Vec::new();
            for vi in 0..=18 {
                let view_zenith = (90.0 * vi as f32 / 18.0).to_radians();
                for ai in 0..48 {
                    let view_azimuth = (7.5 * ai as f32).to_radians();
                    let dir = geom::direction(view_zenith, view_azimuth);
                    let want = sky.rgb(dir).to_array().map(f64::from);
                    let got = fixed
                        .rgb(fixed::direction_q15(dir))
                        .map(|v| v as f64 / unit);
                    let exact = reference.rgb(
                        f64::from(sun_zenith),
                        f64::from(sun_azimuth),
                        f64::from(turbidity),
                        dir.to_array().map(f64::from),
                    );
                    samples.push((view_zenith, view_azimuth, want, got, exact));
                }
            }
            for c in 0..3 {
                let peak = samples.iter().fold(0.0f64, |m, s| m.max(s.2[c]));
                for &(vz, va, want, got, exact) in &samples {
                    let difference = (got[c] - want[c]).abs();
                    if want[c] >= FLOOR * peak {
                        result.above += 1;
                        let e = difference / want[c];
                        if e > result.relative.0 || e.is_nan() {
                            let at = format!(
                                "sun zenith {:.1}°, azimuth {sun_azimuth:.2}, T {turbidity}, \
                                 view {:.1}°/{:.1}°, channel {c}: f32 {}, fixed {}",
                                sun_zenith.to_degrees(),
                                vz.to_degrees(),
                                va.to_degrees(),
                                want[c],
                                got[c]
                            );
                            result.relative = (e, at);
                        }
                    } else {
                        result.below += 1;
                        result.absolute = result.absolute.max(difference / peak);
                        let f32_error = (want[c] - exact[c]).abs() / exact[c];
                        result.f32_vs_f64_below_floor =
                            result.f32_vs_f64_below_floor.max(f32_error);
                    }
                }
            }
        }
    }
    result
}

#[test]
fn fixed_point_is_within_one_percent_of_f32() {
    for (name, weights, quantised) in [
        (
            "PREETHAM",
            &pretrained::PREETHAM,
            &pretrained::PREETHAM_FIXED,
        ),
        ("HOSEK", &pretrained::HOSEK, &pretrained::HOSEK_FIXED),
    ] {
        let r = compare(weights, quantised);
        println!(
            "{name}: fixed point vs f32, max relative difference per channel {:.3e} over {} \
             samples (at {}); below 1e-4 of the peak ({} samples): max difference {:.3e} of the \
             peak (f32 vs f64 there: up to {:.3e} relative)",
            r.relative.0, r.above, r.relative.1, r.below, r.absolute, r.f32_vs_f64_below_floor
        );
        assert!(
            r.relative.0 <= RELATIVE_BOUND,
            "{name}: relative difference {} > {RELATIVE_BOUND} at {}",
            r.relative.0,
            r.relative.1
        );
        assert!(
            r.absolute <= ABSOLUTE_BOUND,
            "{name}: below the floor, difference {} of the peak > {ABSOLUTE_BOUND}",
            r.absolute
        );
    }
}

/// The generated constants are exactly what `sky-train export --format fixed` makes of the
/// committed weight files.
#[test]
fn quantised_constants_regenerate_from_the_weight_files() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    for (file, name, source, constant) in [
        (
            "preetham.skyn",
            "PREETHAM_FIXED",
            "preetham_fixed.rs",
            &pretrained::PREETHAM_FIXED,
        ),
        (
            "hosek.skyn",
            "HOSEK_FIXED",
            "hosek_fixed.rs",
            &pretrained::HOSEK_FIXED,
        ),
    ] {
        let weights_path = root.join("sky-core/weights").join(file);
        let weights = export::read_weights::<12>(&weights_path).expect("weight file decodes");
        let quantised = FixedNeuralWeights::quantise(&weights).expect("weights fit Q7.24");
        assert_eq!(
            &quantised, constant,
            "{file} and the {name} constant differ"
        );
        let generated = export::pretrained_fixed_source(&weights, name, &weights_path)
            .expect("weights fit Q7.24");
        let committed =
            std::fs::read_to_string(root.join("sky-core/src/neural/pretrained").join(source))
                .expect("generated file exists");
        assert!(
            generated == committed,
            "sky-core/src/neural/pretrained/{source} is not what `sky-train export --format fixed` makes of {file}: regenerate it"
        );
    }
}

/// Extreme weights and directions: no panic (tests build with overflow checks), no wrap-around.
#[test]
fn extreme_inputs_never_panic() {
    let extreme = |v: i32| FixedNeuralWeights::<12> {
        hidden: [[v; 6]; 12],
        hidden_bias: [v; 12],
        output: [[v; 12]; 3],
        output_bias: [v; 3],
        radiance_frac: 63,
        radiance_factor: [u64::MAX; 3],
        factor_shift: 0,
        uses_turbidity: true,
        turbidity_range: (0.0, f32::MAX),
        sun_zenith_range: (0.0, core::f32::consts::PI),
    };
    let directions = [
        [0, 0, 0],
        [i16::MIN, i16::MIN, i16::MIN],
        [i16::MAX, i16::MAX, i16::MAX],
        [i16::MIN, 0, i16::MAX],
        [1, 0, 0],
        [0, 0, -1],
    ];
    for weights in [
        extreme(i32::MAX),
        extreme(i32::MIN),
        extreme(0),
        extreme(-1),
    ] {
        for (zenith, turbidity) in [(0.0, 0.0), (3.1, f32::MAX), (1.0, 1e30)] {
            let sun = Sun::new(zenith, 2.0).expect("valid sun");
            let sky = FixedNeuralSky::new(&weights, sun, turbidity).expect("in range");
            for dir in directions {
                let _ = sky.rgb(dir);
            }
        }
    }
    // Saturation, not wrap-around: huge weights give the largest radiance, not a small one.
    let sky = FixedNeuralSky::new(&extreme(i32::MAX), Sun::new(0.5, 0.0).expect("valid"), 2.0)
        .expect("in range");
    assert_eq!(sky.rgb([0, 0, 1]), [u64::MAX; 3]);
    // Bad parameters are errors, as for the f32 sky.
    let sun = Sun::new(0.5, 0.0).expect("valid");
    assert!(FixedNeuralSky::new(&pretrained::PREETHAM_FIXED, sun, 7.0).is_err());
    assert!(FixedNeuralSky::new(&pretrained::PREETHAM_FIXED, sun, f32::NAN).is_err());
}

/// Weights that do not fit Q7.24 are refused with an error naming the value.
#[test]
fn quantise_refuses_weights_out_of_range() {
    let mut weights = pretrained::PREETHAM;
    weights.output[1][3] = 200.0;
    let error = FixedNeuralWeights::quantise(&weights).expect_err("200 does not fit ±128");
    assert!(error.to_string().contains("output weight"), "{error}");
    weights = pretrained::PREETHAM;
    weights.output_scale[0] = -1.0;
    assert!(FixedNeuralWeights::quantise(&weights).is_err());
}
