//! The lighting-controller outputs against independent references: sun position against pvlib's
//! SPA, CCT/Duv against colour-science's Ohno 2013 (both fixtures written by
//! `tests/reference/gen_fixtures.py`), illuminance against brute-force f64 integrals, LED drive
//! levels against a mixture computed here. (The daylight over every sun elevation, finite and monotone: `daylight.rs`.)

use std::f64::consts::{FRAC_PI_2, PI};

use sky_core::color::Xyy;
use sky_core::led::{Channel, Luminaire};
use sky_core::neural::{NeuralSky, pretrained};
use sky_core::photometry::Photometry;
use sky_core::solar::{Site, SunPosition};
use sky_core::{PreethamSky, Sun, Vec3, cct};
use sky_tests::fixtures::{self, num};
use sky_tests::reference::preetham as reference;

mod common;
use common::utc;

/// Sun position within 0.01° of pvlib's SPA (geometric zenith, refracted zenith, azimuth) over
/// 420 instants 1950-2100 at 14 sites: polar (both), tropical, mid-latitude, both hemispheres.
#[test]
fn sun_position_agrees_with_pvlib_spa() {
    let rows = fixtures::rows("spa.csv");
    assert!(rows.len() >= 400);
    let (mut zenith, mut apparent, mut azimuth) = (0.0f64, 0.0f64, 0.0f64);
    for r in &rows {
        let site = Site::new(num(&r[2]), num(&r[3]), num(&r[4])).expect("valid site");
        let p = SunPosition::new(&utc(&r[1]), &site).expect("computes");
        zenith = zenith.max((p.zenith_deg() - num(&r[5])).abs());
        apparent = apparent.max((p.apparent_zenith_deg() - num(&r[6])).abs());
        // Azimuth is undefined at the zenith; weigh its error by the sun's distance from it.
        let da = (p.azimuth_deg() - num(&r[7]) + 540.0).rem_euclid(360.0) - 180.0;
        azimuth = azimuth.max(da.abs() * p.zenith_deg().to_radians().sin());
        // The Sun handed to the models: the same zenith, azimuth φ = 90° − compass azimuth.
        let sun = p.sun();
        let east = f64::from(sun.direction().x);
        let want_east = num(&r[7]).to_radians().sin() * num(&r[5]).to_radians().sin();
        assert!((east - want_east).abs() < 1e-4, "{r:?}");
    }
    println!(
        "SPA vs pvlib over {} instants: max |dzenith| {zenith:.2e} deg, refracted {apparent:.2e} deg, azimuth {azimuth:.2e} deg",
        rows.len()
    );
    assert!(zenith < 0.01 && apparent < 0.01 && azimuth < 0.01);
}

/// CCT within 2 K below 10,000 K and 0.1 % above, Duv within 1e-4, against colour-science's
/// Ohno 2013 along and off the Planckian locus (Duv −0.03 to 0.03, 1,700-25,000 K).
#[test]
fn cct_and_duv_agree_with_colour_science() {
    let rows = fixtures::rows("cct.csv");
    assert!(rows.len() >= 400);
    let (mut below, mut above, mut duv) = (0.0f64, 0.0f64, 0.0f64);
    for r in &rows {
        #[allow(clippy::cast_possible_truncation)]
        let (x, y) = (num(&r[0]) as f32, num(&r[1]) as f32);
        let want_t = num(&r[2]);
        let got = cct::cct_duv(x, y).unwrap_or_else(|e| panic!("{r:?}: {e}"));
        let dt = (f64::from(got.kelvin) - want_t).abs();
        if want_t < 10_000.0 {
            below = below.max(dt);
        } else {
            above = above.max(dt / want_t);
        }
        duv = duv.max((f64::from(got.duv) - num(&r[3])).abs());
    }
    println!(
        "CCT vs colour-science over {} chromaticities: max |dT| {below:.3} K below 10,000 K, {:.4} % above; max |dDuv| {duv:.2e}",
        rows.len(),
        above * 100.0
    );
    assert!(below <= 2.0 && above <= 1e-3 && duv <= 1e-4);
}

/// Calls `f(direction, solid angle)` for every cell of the upper hemisphere on a 0.1° grid
/// (midpoints; each row's solid angle exact), in f64.
fn for_each_hemisphere_cell(mut f: impl FnMut([f64; 3], f64)) {
    let (rows, cols) = (900usize, 3600usize);
    let (dt, dp) = (FRAC_PI_2 / rows as f64, 2.0 * PI / cols as f64);
    for j in 0..rows {
        let theta = (j as f64 + 0.5) * dt;
        let omega = dp * ((theta - 0.5 * dt).cos() - (theta + 0.5 * dt).cos());
        for i in 0..cols {
            let phi = (i as f64 + 0.5) * dp;
            let d = [
                theta.sin() * phi.cos(),
                theta.sin() * phi.sin(),
                theta.cos(),
            ];
            f(d, omega);
        }
    }
}

/// Brute-force ∫ Y (n · ω)⁺ dω over the upper hemisphere by the midpoint rule on a 0.1° grid in
/// f64, for every normal at once.
fn brute_force(luminance: &dyn Fn([f64; 3]) -> f64, normals: &[[f64; 3]]) -> Vec<f64> {
    let mut sums = vec![0.0; normals.len()];
    for_each_hemisphere_cell(|d, omega| {
        let l = luminance(d);
        for (s, n) in sums.iter_mut().zip(normals) {
            let c = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
            if c > 0.0 {
                *s += l * c * omega;
            }
        }
    });
    sums
}

const NORMALS: [[f64; 3]; 5] = [
    [0.0, 0.0, 1.0],                             // horizontal
    [1.0, 0.0, 0.0],                             // a window facing east (+x)
    [0.0, -1.0, 0.0],                            // a window facing south (−y)
    [0.5, 0.5, std::f64::consts::FRAC_1_SQRT_2], // a roof tilted 45° to the north-east
    [-0.766_044, 0.0, -0.642_788],               // a panel facing 40° below the horizon, west
];

fn as_vec3(n: [f64; 3]) -> Vec3 {
    #[allow(clippy::cast_possible_truncation)]
    Vec3::new(n[0] as f32, n[1] as f32, n[2] as f32)
}

/// Illuminance of the Preetham sky on horizontal and tilted planes within 0.5 % of a
/// brute-force f64 integral of the f64 reference implementation of the same model.
#[test]
fn preetham_illuminance_agrees_with_brute_force() {
    let mut worst = 0.0f64;
    for (turbidity, zenith_deg, azimuth_deg) in [
        (2.0, 0.0, 0.0),
        (3.0, 30.0, 45.0),
        (4.5, 60.0, 200.0),
        (6.0, 85.0, 300.0),
        (3.0, 90.0, 90.0),
    ] {
        let (zs, az) = (f64::to_radians(zenith_deg), f64::to_radians(azimuth_deg));
        let reference = reference::Sky::new(turbidity, zs, az);
        let want = brute_force(&|d| reference.xyy(d).luminance, &NORMALS);
        #[allow(clippy::cast_possible_truncation)]
        let sky = PreethamSky::new(
            Sun::new(zs as f32, az as f32).expect("sun"),
            turbidity as f32,
        )
        .expect("sky");
        for (n, w) in NORMALS.iter().zip(&want) {
            let got = f64::from(sky.plane_illuminance(as_vec3(*n)).expect("plane").y);
            let rel = (got - w).abs() / w;
            println!(
                "T {turbidity} sun {zenith_deg}/{azimuth_deg}: normal {n:?}: {got:.1} lx vs {w:.1} lx ({rel:.2e})"
            );
            worst = worst.max(rel);
        }
        let zenith = f64::from(sky.zenith_luminance());
        assert!((zenith - reference.xyy([0.0, 0.0, 1.0]).luminance).abs() / zenith < 1e-5);
    }
    println!("Preetham illuminance: max relative error {worst:.2e} (bound 5e-3)");
    assert!(worst < 5e-3);
}

/// The mean colour over a cone of view against a brute-force f64 sum of the reference's XYZ
/// over the cone's part of the sky (0.1° grid): chromaticity within 1e-3, mean luminance
/// within 1 %.
#[test]
fn cone_mean_agrees_with_brute_force() {
    let mut worst = (0.0f64, 0.0f64);
    for (turbidity, zenith_deg, axis, half_deg) in [
        (3.0, 40.0, [0.0, 0.0, 1.0], 30.0),
        (2.0, 70.0, [0.6, 0.0, 0.8], 10.0),
        (5.0, 20.0, [0.0, 1.0, 0.0], 45.0), // a window: half of its cone is ground
    ] {
        let reference = reference::Sky::new(turbidity, f64::to_radians(zenith_deg), 0.0);
        let cos_half = f64::to_radians(half_deg).cos();
        let mut sum = [0.0f64; 3];
        for_each_hemisphere_cell(|d, omega| {
            if d[0] * axis[0] + d[1] * axis[1] + d[2] * axis[2] >= cos_half {
                let xyz = reference::xyy_to_xyz(reference.xyy(d));
                for k in 0..3 {
                    sum[k] += xyz[k] * omega;
                }
            }
        });
        let total = sum[0] + sum[1] + sum[2];
        let (want_x, want_y) = (sum[0] / total, sum[1] / total);
        let want_lum = sum[1] / (2.0 * PI * (1.0 - cos_half));
        #[allow(clippy::cast_possible_truncation)]
        let sky = PreethamSky::new(
            Sun::new(zenith_deg.to_radians() as f32, 0.0).expect("sun"),
            turbidity as f32,
        )
        .expect("sky");
        let got = sky
            .cone_mean(as_vec3(axis), (half_deg as f32).to_radians())
            .expect("cone");
        let dxy = (f64::from(got.x) - want_x)
            .abs()
            .max((f64::from(got.y) - want_y).abs());
        let dl = (f64::from(got.luminance) - want_lum).abs() / want_lum;
        println!(
            "cone {axis:?} {half_deg} deg: xy ({:.4}, {:.4}) vs ({want_x:.4}, {want_y:.4}), Y {:.0} vs {want_lum:.0}: |dxy| {dxy:.1e}, |dY|/Y {dl:.1e}",
            got.x, got.y, got.luminance
        );
        worst = (worst.0.max(dxy), worst.1.max(dl));
    }
    println!(
        "cone mean: max |dxy| {:.2e}, max |dY|/Y {:.2e}",
        worst.0, worst.1
    );
    assert!(worst.0 < 1e-3 && worst.1 < 1e-2);
}

/// The same for the shipped neural sky, against a brute-force f64 sum of its own f32 values.
#[test]
fn neural_illuminance_agrees_with_brute_force() {
    let mut worst = 0.0f64;
    for (turbidity, zenith_deg) in [(2.5f32, 20f32), (5.0, 70.0)] {
        let sky = NeuralSky::new(
            &pretrained::PREETHAM,
            Sun::new(zenith_deg.to_radians(), 1.0).expect("sun"),
            turbidity,
        )
        .expect("sky");
        let want = brute_force(
            &|d| f64::from(Photometry::xyz(&sky, as_vec3(d)).y),
            &NORMALS[..3],
        );
        for (n, w) in NORMALS.iter().zip(&want) {
            let got = f64::from(sky.plane_illuminance(as_vec3(*n)).expect("plane").y);
            worst = worst.max((got - w).abs() / w);
        }
    }
    println!("neural sky illuminance: max relative error {worst:.2e} (bound 5e-3)");
    assert!(worst < 5e-3);
}

/// XYZ of a chromaticity and luminance, in f64 (eq. 27 of seed 002, written again here).
fn xyz64(x: f64, y: f64, big_y: f64) -> [f64; 3] {
    [x * big_y / y, big_y, (1.0 - x - y) * big_y / y]
}

fn ch(x: f32, y: f32, full_output: f32) -> Channel {
    Channel { x, y, full_output }
}

/// The mixture of channels at `levels`, summed here in f64: (x, y, Y).
fn mixture(channels: &[Channel], levels: &[f64]) -> (f64, f64, f64) {
    let mut sum = [0.0; 3];
    for (c, l) in channels.iter().zip(levels) {
        let v = xyz64(f64::from(c.x), f64::from(c.y), f64::from(c.full_output));
        for k in 0..3 {
            sum[k] += l * v[k];
        }
    }
    let s = sum[0] + sum[1] + sum[2];
    (sum[0] / s, sum[1] / s, sum[1])
}

/// Hue angle about a white point in the xy diagram.
fn hue(x: f64, y: f64, white: (f64, f64, f64)) -> f64 {
    (y - white.1).atan2(x - white.0)
}

/// Channels, levels, whether clipped, 12-bit levels.
type Case<'a> = (&'a [Channel], Vec<f32>, bool, Vec<u16>);

/// RGB and RGBW: in-gamut targets come back within 1e-5 in xy and 1e-4 relative in Y (12-bit
/// quantised: 3e-3 in xy, 1 % in Y, for targets from 2.6 % of full output); out-of-gamut targets
/// keep their hue angle about the luminaire's white within 1e-4 rad; too-bright targets keep
/// their chromaticity.
#[test]
fn led_levels_reproduce_targets_and_keep_hue() {
    let (r, g, b, w) = (
        ch(0.700, 0.295, 300.0),
        ch(0.170, 0.700, 600.0),
        ch(0.135, 0.060, 100.0),
        ch(0.4369, 0.4041, 900.0),
    );
    let rgb = Luminaire::rgb(r, g, b).expect("rgb");
    let rgbw = Luminaire::rgbw(r, g, b, w).expect("rgbw");
    let (mut exact, mut quantised_xy, mut quantised_y, mut hue_error) =
        (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    for i in 0..=20 {
        for j in 0..=20 {
            let (x, y) = (
                0.15 + 0.55 * f64::from(i) / 20.0,
                0.05 + 0.65 * f64::from(j) / 20.0,
            );
            if x + y > 0.95 {
                continue;
            }
            for lum in [50.0, 400.0] {
                #[allow(clippy::cast_possible_truncation)]
                let target = Xyy {
                    x: x as f32,
                    y: y as f32,
                    luminance: lum as f32,
                };
                let cases: [Case; 2] = {
                    let d3 = rgb.drive(target);
                    let d4 = rgbw.drive(target);
                    [
                        (
                            &[r, g, b],
                            d3.levels.to_vec(),
                            d3.chromaticity_clipped || d3.luminance_clipped,
                            d3.quantise(12).expect("bits").to_vec(),
                        ),
                        (
                            &[r, g, b, w],
                            d4.levels.to_vec(),
                            d4.chromaticity_clipped || d4.luminance_clipped,
                            d4.quantise(12).expect("bits").to_vec(),
                        ),
                    ]
                };
                for (channels, levels, clipped, q) in cases {
                    let levels: Vec<f64> = levels.iter().map(|&l| f64::from(l)).collect();
                    assert!(levels.iter().all(|l| (0.0..=1.0).contains(l)), "{levels:?}");
                    let got = mixture(channels, &levels);
                    let full = mixture(channels, &vec![1.0; channels.len()]);
                    if clipped {
                        // Same hue about the luminaire's white (unless the target is the white).
                        if (x - full.0).hypot(y - full.1) > 1e-3 {
                            let dh = (hue(got.0, got.1, full) - hue(x, y, full) + 3.0 * PI)
                                .rem_euclid(2.0 * PI)
                                - PI;
                            hue_error = hue_error.max(dh.abs());
                        }
                        continue;
                    }
                    exact = exact
                        .max((got.0 - x).abs())
                        .max((got.1 - y).abs())
                        .max((got.2 - lum).abs() / lum * 0.1);
                    let ql: Vec<f64> = q.iter().map(|&v| f64::from(v) / 4095.0).collect();
                    let gq = mixture(channels, &ql);
                    quantised_xy = quantised_xy.max((gq.0 - x).abs()).max((gq.1 - y).abs());
                    quantised_y = quantised_y.max((gq.2 - lum).abs() / lum);
                }
            }
        }
    }
    println!(
        "LED drive: in gamut max |dxy| or |dY|/Y/10 {exact:.2e}; 12-bit: |dxy| {quantised_xy:.2e}, |dY|/Y {quantised_y:.2e}; clipped hue error {hue_error:.2e} rad"
    );
    assert!(exact < 1e-5, "{exact}");
    assert!(quantised_xy < 3e-3 && quantised_y < 1e-2);
    assert!(hue_error < 1e-4, "{hue_error}");
    // Too bright: dimmed at the same chromaticity.
    let d = rgbw.drive(Xyy {
        x: 0.3127,
        y: 0.329,
        luminance: 1e5,
    });
    let got = mixture(&[r, g, b, w], &d.levels.map(f64::from));
    assert!(d.luminance_clipped && (got.0 - 0.3127).abs() < 1e-5 && (got.1 - 0.329).abs() < 1e-5);
}

/// Warm + cool white: chromaticities between the two come back exactly; others go to the
/// nearest point of the segment; luminance is kept.
#[test]
fn tunable_white_follows_the_segment() {
    let (warm, cool) = (ch(0.4769, 0.4137, 800.0), ch(0.3135, 0.3237, 900.0)); // 2700 K, 6500 K
    let lamp = Luminaire::tunable_white(warm, cool).expect("lamp");
    for s in [0.0f64, 0.25, 0.5, 0.9, 1.0] {
        let (x, y) = (
            0.4769 + s * (0.3135 - 0.4769),
            0.4137 + s * (0.3237 - 0.4137),
        );
        #[allow(clippy::cast_possible_truncation)]
        let d = lamp.drive(Xyy {
            x: x as f32,
            y: y as f32,
            luminance: 300.0,
        });
        let got = mixture(&[warm, cool], &d.levels.map(f64::from));
        assert!(
            (got.0 - x).abs() < 1e-5 && (got.1 - y).abs() < 1e-5,
            "{s}: {got:?}"
        );
        assert!((got.2 - 300.0).abs() < 1e-2);
        assert!(!d.chromaticity_clipped);
    }
    // Off the segment, above its middle: projected onto it.
    let d = lamp.drive(Xyy {
        x: 0.40,
        y: 0.42,
        luminance: 300.0,
    });
    let got = mixture(&[warm, cool], &d.levels.map(f64::from));
    let (dx, dy) = (0.3135 - 0.4769, 0.3237 - 0.4137);
    let cross = (got.0 - 0.4769) * dy - (got.1 - 0.4137) * dx;
    assert!(d.chromaticity_clipped && cross.abs() < 1e-6 && (got.2 - 300.0).abs() < 1e-2);
}
