//! The crate's one below-horizon rule (crate docs, "Conventions"): every sky model's radiance
//! is 0 for view directions whose unit vector has z < −`geom::HORIZON_TOLERANCE`, in the
//! one-direction and the batch paths, and the sky's own (non-zero) value on the horizon itself
//! (the f32 nearest π/2, whose cos θ is −4.4e-8). Before the rule, the neural sky gave tens of
//! thousands of cd/m² below the horizon (issue 26: 88,398 / 15,731 / 7,775 at θ = 170°).

use sky_core::aoas::{AoasSky, Preset, Scattering};
use sky_core::cie::CieSky;
use sky_core::daylight::Daylight;
use sky_core::neural::{FixedNeuralSky, fixed::direction_q15, pretrained};
use sky_core::perez::{PerezSky, SkyCondition};
use sky_core::sh::ShSky;
use sky_core::{NeuralSky, PreethamSky, Sun, Vec3, geom};

const TAU: f32 = core::f32::consts::TAU;

/// Directions below the horizon, from 2e-6 below it (just past the tolerance) to the nadir,
/// at 16 azimuths, unit length and 3.7 times longer (the models take any length).
fn below() -> Vec<Vec3> {
    let mut dirs = Vec::new();
    for z in [2e-6f32, 1e-5, 1e-3, 0.05, 0.3, 0.7, 0.98, 1.0] {
        for k in 0..16 {
            let phi = TAU * k as f32 / 16.0;
            let r = (1.0 - z * z).sqrt();
            let d = Vec3::new(r * phi.cos(), r * phi.sin(), -z);
            assert!(geom::below_horizon(d.normalize()), "{d}");
            dirs.push(d);
            dirs.push(3.7 * d);
        }
    }
    dirs
}

/// The horizon at 16 azimuths, as `geom::direction(π/2, φ)` gives it (z a hair below 0).
fn on_the_horizon() -> Vec<Vec3> {
    (0..16)
        .map(|k| geom::direction(core::f32::consts::FRAC_PI_2, TAU * k as f32 / 16.0))
        .inspect(|d| assert!(!geom::below_horizon(*d), "{d}"))
        .collect()
}

/// `eval` is 0 at every direction below the horizon and positive somewhere on it.
fn holds(name: &str, eval: &dyn Fn(Vec3) -> Vec3) {
    for d in below() {
        assert_eq!(eval(d), Vec3::ZERO, "{name} at {d}");
    }
    let horizon = on_the_horizon();
    assert!(
        horizon.iter().all(|d| eval(*d).max_element() > 0.0),
        "{name}: black on the horizon"
    );
}

/// `batch` gives 0 for every direction below the horizon, mixed with directions above it so
/// that the batch's lanes hold both.
fn batch_holds(name: &str, batch: &dyn Fn(&[Vec3], &mut [Vec3])) {
    let below = below();
    let mut dirs = Vec::new();
    for (i, d) in below.iter().enumerate() {
        dirs.push(*d);
        if i % 3 == 0 {
            dirs.push(geom::direction(0.3 + 0.01 * i as f32, 0.1 * i as f32));
        }
    }
    let mut out = vec![Vec3::splat(-1.0); dirs.len()];
    batch(&dirs, &mut out);
    for (d, o) in dirs.iter().zip(&out) {
        if geom::below_horizon(d.normalize()) {
            assert_eq!(*o, Vec3::ZERO, "{name} batch at {d}");
        } else {
            assert!(
                o.max_element() > 0.0,
                "{name} batch above the horizon at {d}: {o}"
            );
        }
    }
}

#[test]
fn preetham() {
    for zenith in [0.3, 1.2, 1.55] {
        let sky = PreethamSky::new(Sun::new(zenith, 0.5).expect("valid"), 3.0).expect("valid");
        holds("preetham", &|d| sky.rgb(d));
        batch_holds("preetham", &|d, o| sky.rgb_batch(d, o));
    }
}

#[test]
fn neural_every_shipped_network() {
    let sun = Sun::new(1.2, 0.5).expect("valid");
    for (name, weights) in [
        ("preetham", &pretrained::PREETHAM),
        ("hosek", &pretrained::HOSEK),
    ] {
        let sky = NeuralSky::new(weights, sun, 3.0).expect("valid");
        holds(name, &|d| sky.rgb(d));
        batch_holds(name, &|d, o| sky.rgb_batch(d, o));
        #[cfg(target_arch = "x86_64")]
        if is_x86_feature_detected!("avx2") && is_x86_feature_detected!("fma") {
            // SAFETY: the CPU has AVX2 and FMA.
            #[allow(unsafe_code)]
            batch_holds(name, &|d, o| unsafe { sky.rgb_batch_avx2(d, o) });
        }
    }
    // The daylight sky's networks, one by one (each at a sun of its own range).
    for (name, weights, zenith) in [
        ("daylight day", &pretrained::DAYLIGHT_DAY, 1.0),
        ("daylight dusk", &pretrained::DAYLIGHT_DUSK, 1.62),
        ("daylight night", &pretrained::DAYLIGHT_NIGHT, 1.82),
    ] {
        let sky =
            NeuralSky::new(weights, Sun::new(zenith, 0.5).expect("valid"), 0.2).expect("valid");
        holds(name, &|d| sky.rgb(d));
        batch_holds(name, &|d, o| sky.rgb_batch(d, o));
    }
}

#[test]
fn fixed_point_neural() {
    let sky = FixedNeuralSky::new(
        &pretrained::PREETHAM_FIXED,
        Sun::new(1.2, 0.5).expect("valid"),
        3.0,
    )
    .expect("valid");
    // The Q1.15 directions of those at least 1e-3 below the horizon (2e-6 rounds onto it).
    for d in below().into_iter().filter(|d| d.normalize().z <= -1e-3) {
        assert_eq!(sky.rgb(direction_q15(d)), [0; 3], "fixed at {d}");
    }
    for d in on_the_horizon() {
        assert!(
            sky.rgb(direction_q15(d)).iter().any(|c| *c > 0),
            "fixed on the horizon at {d}"
        );
    }
}

#[test]
fn spherical_harmonics_radiance() {
    for bands in [3, 5, 7] {
        let sky = ShSky::new(Sun::new(1.0, 0.5).expect("valid"), 3.0, bands).expect("valid");
        holds("sh", &|d| sky.radiance(d));
    }
}

#[test]
fn aoas() {
    for preset in [Preset::Physical, Preset::Coral] {
        let sky = AoasSky::new(&Scattering::default(), &preset.style()).expect("valid");
        holds(preset.name(), &|d| sky.rgb(d));
        batch_holds(preset.name(), &|d, o| sky.rgb_batch(d, o));
    }
}

#[test]
fn cie_and_perez() {
    let sun = Sun::new(0.9, 0.5).expect("valid");
    for sky_type in [1, 7, 12] {
        let sky = CieSky::from_diffuse_illuminance(sky_type, sun, 20_000.0).expect("valid");
        holds("cie", &|d| Vec3::splat(sky.luminance(d)));
    }
    let sky =
        PerezSky::new(sun, SkyCondition::new(7.0, 0.12).expect("valid"), 12_000.0).expect("valid");
    holds("perez", &|d| Vec3::splat(sky.luminance(d)));
}

#[test]
fn daylight_sky_by_day_and_in_twilight() {
    for elevation in [40f32, 5.0, -3.0, -10.0, -17.0] {
        let sky =
            Daylight::clear(Sun::new((90.0 - elevation).to_radians(), 0.5).expect("valid")).sky();
        holds("daylight", &|d| sky.xyz(d));
    }
}
