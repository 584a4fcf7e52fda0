//! sky-core's contract as properties over the whole f32 input space (issue 19): for every public
//! constructor and evaluation function of the sky models, any inputs (NaN, ±∞, subnormals,
//! huge values, every bit pattern of the weights) never panic; a constructor either refuses
//! them or builds a sky whose every output is finite, and whose radiance (RGB for the models
//! that compute RGB, luminance for the Preetham sky, whose RGB is a colour conversion that may
//! leave the sRGB gamut) is never negative.

use proptest::prelude::*;
use proptest::test_runner::Config;
use sky_core::aoas::{AoasSky, Preset, Scattering};
use sky_core::daylight::Daylight;
use sky_core::neural::{FixedNeuralSky, FixedNeuralWeights, NeuralSky, NeuralWeights, pretrained};
use sky_core::sh::ShSky;
use sky_core::{PreethamSky, Sun, Vec3, cct, color};

/// Any f32: every class proptest knows (normal, subnormal, zero, infinite, NaN), both signs.
fn any_f32() -> impl Strategy<Value = f32> {
    prop::num::f32::ANY
}

/// Any direction: three arbitrary f32.
fn any_dir() -> impl Strategy<Value = Vec3> {
    [any_f32(), any_f32(), any_f32()].prop_map(Vec3::from_array)
}

/// A sun from arbitrary angles half of the time, from valid ones the other half (so that the
/// skies are built often enough to test their evaluation).
fn sun_angles() -> impl Strategy<Value = (f32, f32)> {
    prop_oneof![
        (any_f32(), any_f32()),
        (0.0f32..=std::f32::consts::FRAC_PI_2, -10.0f32..10.0),
    ]
}

/// A turbidity: arbitrary, or inside the models' ranges.
fn turbidity() -> impl Strategy<Value = f32> {
    prop_oneof![any_f32(), 1.0f32..10.0]
}

fn finite(v: Vec3) -> bool {
    v.is_finite()
}

fn radiance_ok(v: Vec3) -> bool {
    v.is_finite() && v.min_element() >= 0.0
}

/// Weights with every float arbitrary.
fn any_weights() -> impl Strategy<Value = NeuralWeights<12>> {
    (
        prop::collection::vec(any_f32(), 6 * 12 + 12 + 3 * 12 + 3),
        prop::collection::vec(any_f32(), 6 + 6 + 3 + 4),
        any::<bool>(),
    )
        .prop_map(|(w, h, uses_turbidity)| NeuralWeights {
            hidden: std::array::from_fn(|j| std::array::from_fn(|k| w[j * 6 + k])),
            hidden_bias: std::array::from_fn(|j| w[72 + j]),
            output: std::array::from_fn(|c| std::array::from_fn(|j| w[84 + c * 12 + j])),
            output_bias: std::array::from_fn(|c| w[120 + c]),
            input_offset: std::array::from_fn(|k| h[k]),
            input_scale: std::array::from_fn(|k| h[6 + k]),
            output_scale: std::array::from_fn(|c| h[12 + c]),
            uses_turbidity,
            turbidity_range: (h[15], h[16]),
            sun_zenith_range: (h[17], h[18]),
            source: *b"fuzz\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0",
            seed: 0,
            nrmse: 0.0,
        })
}

proptest! {
    #![proptest_config(Config { cases: 10_000, ..Config::default() })]

    #[test]
    fn preetham_sky_is_finite_with_non_negative_luminance(
        (z, a) in sun_angles(), t in turbidity(), d in any_dir()
    ) {
        if let Ok(sun) = Sun::new(z, a) {
            prop_assert!(finite(sun.direction()));
            if let Ok(sky) = PreethamSky::new(sun, t) {
                let c = sky.xyy(d);
                prop_assert!(c.luminance.is_finite() && c.luminance >= 0.0, "{c:?}");
                prop_assert!(c.x.is_finite() && c.y.is_finite(), "{c:?}");
                prop_assert!(finite(sky.rgb(d)) && finite(sky.xyz(d)));
                let mut out = [Vec3::ZERO; 3];
                sky.rgb_batch(&[d, -d, d * 0.5], &mut out);
                prop_assert!(out.iter().all(|v| finite(*v)));
                prop_assert!(sky.zenith().luminance >= 0.0);
            }
        }
    }

    #[test]
    fn daylight_is_finite_and_non_negative(
        (z, a) in prop_oneof![(any_f32(), any_f32()), (0.0f32..=std::f32::consts::PI, -10.0f32..10.0)],
        aod in prop_oneof![any_f32(), 0.05f32..=0.8],
        d in any_dir()
    ) {
        if let Ok(sun) = Sun::new(z, a) {
            if let Ok(day) = Daylight::new(sun, aod) {
                for v in [day.global(), day.diffuse(), day.direct(), day.direct_normal(), day.tilted(d)] {
                    prop_assert!(v.is_finite() && v.min_element() >= 0.0, "{v:?}");
                }
                prop_assert!(day.melanopic_edi().is_finite() && day.melanopic_edi() > 0.0);
                prop_assert!(day.melanopic_der().is_finite());
                let (x, y) = day.chromaticity();
                prop_assert!(x.is_finite() && y.is_finite());
                if let Some(c) = day.cct() {
                    prop_assert!(c.kelvin.is_finite() && c.duv.abs() <= 0.05);
                }
            }
            let _ = Daylight::clear(sun).global();
        }
    }

    #[test]
    fn shipped_neural_skies_give_non_negative_radiance(
        (z, a) in sun_angles(), t in turbidity(), d in any_dir()
    ) {
        let Ok(sun) = Sun::new(z, a) else { return Ok(()) };
        for w in [pretrained::PREETHAM, pretrained::HOSEK] {
            if let Ok(sky) = NeuralSky::new(&w, sun, t) {
                prop_assert!(radiance_ok(sky.rgb(d)), "{d} -> {}", sky.rgb(d));
                let mut out = [Vec3::ZERO; 40];
                sky.rgb_batch(&[d; 40], &mut out);
                prop_assert!(out.iter().all(|v| radiance_ok(*v)));
            }
        }
        for w in [pretrained::PREETHAM_FIXED, pretrained::HOSEK_FIXED] {
            if let Ok(sky) = FixedNeuralSky::new(&w, sun, t) {
                #[allow(clippy::cast_possible_truncation)]
                let _ = sky.rgb([d.x as i16, d.y as i16, d.z as i16]);
            }
        }
    }

    /// Weights built by hand (every field public) rather than decoded: the constructor refuses
    /// what the decoder would (a NaN or an infinity anywhere), and whatever it accepts evaluates
    /// finitely and non-negatively.
    #[test]
    fn any_neural_weights_are_refused_or_give_non_negative_radiance(
        w in any_weights(), (z, a) in sun_angles(), t in turbidity(), d in any_dir()
    ) {
        let Ok(sun) = Sun::new(z, a) else { return Ok(()) };
        let finite = w.hidden.iter().flatten()
            .chain(&w.hidden_bias)
            .chain(w.output.iter().flatten())
            .chain(&w.output_bias)
            .chain(&w.input_offset)
            .chain(&w.input_scale)
            .chain(&w.output_scale)
            .all(|x| x.is_finite());
        if !finite {
            prop_assert!(NeuralSky::new(&w, sun, t).is_err(), "weights with a NaN or infinity accepted");
        }
        if let Ok(sky) = NeuralSky::new(&w, sun, t) {
            prop_assert!(radiance_ok(sky.rgb(d)), "{d} -> {}", sky.rgb(d));
        }
        if let Ok(fixed) = FixedNeuralWeights::quantise(&w)
            && let Ok(sky) = FixedNeuralSky::new(&fixed, sun, t)
        {
            let _ = sky.rgb([1, 2, 3]);
        }
    }

    #[test]
    fn sh_sky_gives_non_negative_radiance_and_irradiance(
        (z, a) in sun_angles(), t in turbidity(), bands in 0usize..9, filtered in any::<bool>(),
        d in any_dir()
    ) {
        let Ok(sun) = Sun::new(z, a) else { return Ok(()) };
        let sky = if filtered { ShSky::new(sun, t, bands) } else { ShSky::new_unfiltered(sun, t, bands) };
        if let Ok(sky) = sky {
            prop_assert!(radiance_ok(sky.radiance(d)), "{d} -> {}", sky.radiance(d));
            prop_assert!(radiance_ok(sky.irradiance(d)), "{d} -> {}", sky.irradiance(d));
            prop_assert!(finite(sky.series(d)));
        }
    }

    #[test]
    fn aoas_sky_gives_non_negative_radiance(
        s in [any_f32(), any_f32(), any_f32(), any_f32(), any_f32(), any_f32(), any_f32()],
        samples in 0u32..40, viewer in any_dir(), preset in 0usize..Preset::ALL.len(),
        d in any_dir()
    ) {
        let scattering = scattering_of(s, samples, viewer);
        for scattering in [scattering, Scattering::default()] {
            if let Ok(sky) = AoasSky::new(&scattering, &Preset::ALL[preset].style()) {
                prop_assert!(radiance_ok(sky.rgb(d)), "{d} -> {}", sky.rgb(d));
                let mut out = [Vec3::ZERO; 9];
                sky.rgb_batch(&[d; 9], &mut out);
                prop_assert!(out.iter().all(|v| radiance_ok(*v)));
            }
        }
    }

    #[test]
    fn colour_and_cct_functions_are_total(x in any_f32(), y in any_f32(), v in any_dir()) {
        if let Ok(c) = cct::cct_duv(x, y) {
            prop_assert!(c.kelvin.is_finite() && c.duv.is_finite(), "{c:?}");
        }
        let _ = color::srgb_encode(x);
        let _ = color::srgb_decode(x);
        let xyy = color::xyz_to_xyy(v);
        let _ = color::xyy_to_xyz(xyy);
        let _ = color::luminance(color::xyz_to_linear_srgb(v));
    }
}

/// O'Neil's parameters from seven arbitrary floats.
fn scattering_of(s: [f32; 7], samples: u32, viewer: Vec3) -> Scattering {
    Scattering {
        kr: s[0],
        km: s[1],
        sun_intensity: s[2],
        mie_g: s[3],
        wavelengths: [s[4], s[5], s[6]],
        samples,
        viewer,
    }
}
