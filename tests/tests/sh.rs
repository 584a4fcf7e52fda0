//! End-to-end tests of the spherical-harmonics sky lighting (seed 001): the generated tables
//! are what the fit produces, the reconstruction meets the paper's error bounds on skies off
//! the fit grid, the rotation (eq. 4) agrees with projecting a turned sky, and the irradiance
//! agrees with a brute-force cosine-weighted integral of the independent f64 Preetham sky.
//!
//! The reference side is `sky-train`'s projection (converged quadrature, f64) and
//! `sky_tests::reference::preetham`; the side under test is `sky_core::sh`.

mod common;
use common::run;

use std::f64::consts::PI;

use proptest::prelude::*;
use proptest::test_runner::FileFailurePersistence;
use sky_core::sh::{PREETHAM, ShSky, basis, rotation};
use sky_core::{SkyError, Sun, Vec3, geom};
use sky_tests::reference::preetham as reference;
use sky_train::sh::eval::{self, WorstCase};
use sky_train::sh::projection::{BANDS, COEFFICIENTS, Coefficients, Integrator};
use sky_train::sh::{FitConfig, ShFit, export, fit, project_all};
use sky_train::sources::ModelKind;

/// The paper's bounds (§3.2): E_mean below 1.5 % at 7 bands and 0.005 % up to 5 bands.
const E_MEAN_7_BANDS: f64 = 0.015;
const E_MEAN_5_BANDS: f64 = 0.000_05;
/// The 7-band table must fit in 64 KB (the paper's: 131 KB).
const TABLE_BYTES: usize = 64 * 1024;

#[allow(clippy::cast_possible_truncation)]
fn round(x: f64) -> f32 {
    x as f32
}

fn to_f64(c: &[Vec3; COEFFICIENTS]) -> Coefficients {
    c.map(|v| [f64::from(v.x), f64::from(v.y), f64::from(v.z)])
}

/// Skies off the fit grid: sun zenith 0° to 90° every 7.5° and turbidity 2.5 to 6 every 0.5
/// (the fitted domain's edges included); none is a Chebyshev point of the fit (checked).
fn test_points(config: &FitConfig) -> Vec<(f64, f64)> {
    let mut points = Vec::new();
    for i in 0..=12 {
        for j in 0..=7 {
            let theta = f64::from(round((7.5 * f64::from(i)).to_radians()));
            let theta = theta.min(f64::from(config.sun_zenith[1]));
            points.push((theta, 2.5 + 0.5 * f64::from(j)));
        }
    }
    let fit_theta = fit::chebyshev_points(
        config.nodes_theta,
        f64::from(config.sun_zenith[0]),
        f64::from(config.sun_zenith[1]),
    );
    let fit_tau = fit::chebyshev_points(
        config.nodes_tau,
        f64::from(config.turbidity[0]),
        f64::from(config.turbidity[1]),
    );
    for &(t, u) in &points {
        let dt = fit_theta
            .iter()
            .map(|x| (x - t).abs())
            .fold(f64::INFINITY, f64::min);
        let du = fit_tau
            .iter()
            .map(|x| (x - u).abs())
            .fold(f64::INFINITY, f64::min);
        assert!(dt > 1e-3 || du > 1e-3, "({t}, {u}) is a fit point");
    }
    points
}

#[test]
fn generated_table_is_reproduced_by_the_fit() {
    let fit = ShFit::run(&FitConfig::shipped(ModelKind::Preetham)).expect("fit");
    let generated = export::rust_source(&fit);
    let committed = include_str!("../../sky-core/src/sh/preetham_table.rs");
    assert_eq!(
        export::default_path(&fit),
        "sky-core/src/sh/preetham_table.rs"
    );
    if generated != committed {
        let line = generated
            .lines()
            .zip(committed.lines())
            .position(|(a, b)| a != b)
            .unwrap_or_else(|| generated.lines().count().min(committed.lines().count()));
        panic!(
            "sky-core/src/sh/preetham_table.rs differs from the fit at line {}: regenerate it with \
             `cargo run --release -p sky-train -- {}`",
            line + 1,
            export::command(&fit).trim_start_matches("sky-train ")
        );
    }
    eprintln!(
        "fit: {} skies, condition number {:.4} (monomials {:.2e}), symmetry residual {:.1e}",
        fit.samples, fit.condition, fit.condition_monomial, fit.asymmetry
    );
    assert!(
        fit.condition < 2.0 + 1e-9,
        "condition number {}",
        fit.condition
    );
    assert!(fit.asymmetry < 1e-6, "symmetry residual {}", fit.asymmetry);
}

#[test]
fn reconstruction_error_meets_the_papers_bounds_off_the_fit_grid() {
    let config = FitConfig::shipped(ModelKind::Preetham);
    let points = test_points(&config);
    let samples =
        project_all(&config, &Integrator::new(config.tolerance), &points).expect("projection");
    let mut worst = WorstCase::default();
    for s in &samples {
        let sun = Sun::new(round(s.theta), 0.0).expect("sun");
        let sky = ShSky::new_unfiltered(sun, round(s.tau), 7).expect("sky");
        let e = eval::band_errors(&s.coefficients, &to_f64(sky.coefficients()), s.l_min);
        worst.update(&e, (s.theta, s.tau));
    }
    for n in 0..BANDS {
        let (mean, (t, u)) = worst.mean[n];
        let (max, _) = worst.max[n];
        eprintln!(
            "{} bands: worst E_mean {:.3e} % at ({:.1} deg, T {u}), worst E_max {:.3e} %",
            n + 1,
            100.0 * mean,
            t.to_degrees(),
            100.0 * max
        );
    }
    assert!(
        worst.mean[6].0 <= E_MEAN_7_BANDS,
        "7 bands: {:?}",
        worst.mean[6]
    );
    for n in 0..5 {
        assert!(
            worst.mean[n].0 <= E_MEAN_5_BANDS,
            "{} bands: {:?}",
            n + 1,
            worst.mean[n]
        );
    }
    // Every byte of the tables: the rows of each width and the row widths.
    let (low, high) = (&PREETHAM.low, &PREETHAM.high);
    let data = std::mem::size_of_val(low.f32_rows)
        + std::mem::size_of_val(low.i16_rows)
        + std::mem::size_of_val(low.i8_rows)
        + std::mem::size_of_val(high.f32_rows)
        + std::mem::size_of_val(high.i16_rows)
        + std::mem::size_of_val(high.i8_rows);
    assert_eq!(PREETHAM.bytes_for_bands(7), data);
    let bytes = data + std::mem::size_of_val(&low.widths) + std::mem::size_of_val(&high.widths);
    eprintln!("7-band tables: {bytes} bytes");
    assert!(bytes <= TABLE_BYTES, "{bytes} bytes");
}

/// The projection of a sky with the sun at azimuth φ.
fn projection_at(theta: f64, azimuth_deg: f64, tau: f64) -> (Coefficients, f64) {
    let params =
        sky_train::sources::SkyParams::sun_and_turbidity(theta.to_degrees(), azimuth_deg, tau);
    let source = sky_train::sources::build(ModelKind::Preetham, &params).expect("sky");
    let l_min = sky_train::sh::projection::minimum_luminance(&*source);
    let p = Integrator::new(2e-6)
        .project(&*source, theta, azimuth_deg.to_radians(), l_min)
        .expect("converges");
    (p.coefficients, l_min)
}

/// Σ_lm |a − b| / L_min, the largest over channels (eq. 2's measure).
fn distance(a: &Coefficients, b: &Coefficients, l_min: f64) -> f64 {
    (0..3)
        .map(|k| {
            a.iter()
                .zip(b)
                .map(|(x, y)| (x[k] - y[k]).abs())
                .sum::<f64>()
                / l_min
        })
        .fold(0.0, f64::max)
}

#[test]
fn rotation_matches_the_projection_of_the_turned_sky() {
    for &(theta_deg, azimuth_deg, tau) in
        &[(35.0, 73.0, 3.0), (80.0, -140.0, 5.5), (60.0, 200.0, 2.7)]
    {
        let theta = f64::to_radians(theta_deg);
        let (at_zero, l_min) = projection_at(theta, 0.0, tau);
        let (turned, _) = projection_at(theta, azimuth_deg, tau);
        // Eq. 4 applied to the projection at azimuth 0 (f32, as sky-core computes it).
        let mut c = at_zero.map(|v| Vec3::new(round(v[0]), round(v[1]), round(v[2])));
        rotation::rotate_about_zenith(&mut c, 7, round(azimuth_deg.to_radians()));
        let d = distance(&to_f64(&c), &turned, l_min);
        eprintln!("rotation by {azimuth_deg} deg: eq. 2 distance {d:.2e}");
        assert!(d < 1e-5, "rotation by {azimuth_deg} deg: {d}");
        // ShSky end to end: the fit's error, no more.
        let sun = Sun::new(round(theta), round(azimuth_deg.to_radians())).expect("sun");
        let sky = ShSky::new_unfiltered(sun, round(tau), 7).expect("sky");
        let d = distance(&to_f64(sky.coefficients()), &turned, l_min);
        assert!(d < 0.05, "ShSky at azimuth {azimuth_deg} deg: {d}");
    }
}

/// Normals spread over the whole sphere (a Fibonacci lattice) plus the poles and the horizon.
fn normals(n: u32) -> Vec<[f64; 3]> {
    let golden = PI * (3.0 - 5f64.sqrt());
    let mut v: Vec<[f64; 3]> = (0..n)
        .map(|k| {
            let z = 1.0 - 2.0 * (f64::from(k) + 0.5) / f64::from(n);
            let r = (1.0 - z * z).sqrt();
            let a = golden * f64::from(k);
            [r * a.cos(), r * a.sin(), z]
        })
        .collect();
    v.extend([
        [0.0, 0.0, 1.0],
        [0.0, 0.0, -1.0],
        [1.0, 0.0, 0.0],
        [0.0, -1.0, 0.0],
    ]);
    v
}

/// Brute-force irradiance of the f64 reference sky (zero below the horizon) for each normal:
/// the midpoint rule over the upper hemisphere in (cos θ, φ) with `rows` × 2 `rows` cells.
fn brute_force_irradiance(sky: &reference::Sky, normals: &[[f64; 3]], rows: u32) -> Vec<[f64; 3]> {
    let cols = 2 * rows;
    let cell = (1.0 / f64::from(rows)) * (2.0 * PI / f64::from(cols));
    let mut samples = Vec::with_capacity((rows * cols) as usize);
    for i in 0..rows {
        let mu = (f64::from(i) + 0.5) / f64::from(rows);
        for j in 0..cols {
            let phi = 2.0 * PI * (f64::from(j) + 0.5) / f64::from(cols);
            let d = reference::direction(mu.acos(), phi);
            let rgb = reference::xyz_to_linear_srgb(reference::xyy_to_xyz(sky.xyy(d)));
            samples.push((d, rgb.map(|c| c * cell)));
        }
    }
    normals
        .iter()
        .map(|n| {
            let mut e = [0.0; 3];
            for (d, l) in &samples {
                let c = n[0] * d[0] + n[1] * d[1] + n[2] * d[2];
                if c > 0.0 {
                    for k in 0..3 {
                        e[k] += c * l[k];
                    }
                }
            }
            e
        })
        .collect()
}

/// The irradiance bound of the issue: 1 % of the largest irradiance over the normals (per
/// channel), for normals over the whole sphere. The errors of every band count are printed;
/// the bound is held from 5 bands on, for `ShSky::new` (whose irradiance ignores the ringing
/// filter) and `new_unfiltered` alike.
const IRRADIANCE_BOUND: f64 = 0.01;

#[test]
fn irradiance_matches_a_brute_force_integral_of_the_sky() {
    let normals = normals(120);
    // [filtered][bands − 1]: the worst error and where.
    let mut worst = vec![vec![(0.0f64, String::new()); 7]; 2];
    for &(theta_deg, azimuth_deg, tau) in &[
        (0.0, 0.0, 2.5),
        (30.0, 40.0, 3.0),
        (60.0, 250.0, 4.5),
        (85.0, 100.0, 6.0),
        (90.0, -30.0, 2.5),
    ] {
        let (theta, azimuth) = (f64::to_radians(theta_deg), f64::to_radians(azimuth_deg));
        let sky = reference::Sky::new(tau, theta, azimuth);
        let want = brute_force_irradiance(&sky, &normals, 300);
        // The scale: the largest irradiance over the normals, per channel.
        let scale: [f64; 3] =
            std::array::from_fn(|k| want.iter().map(|e| e[k]).fold(0.0, f64::max));
        let sun = Sun::new(round(theta), round(azimuth)).expect("sun");
        for (filtered, row) in worst.iter_mut().enumerate() {
            for (b, slot) in row.iter_mut().enumerate() {
                let sh = if filtered == 1 {
                    ShSky::new(sun, round(tau), b + 1)
                } else {
                    ShSky::new_unfiltered(sun, round(tau), b + 1)
                }
                .expect("sky");
                for (n, w) in normals.iter().zip(&want) {
                    let got = sh.irradiance(Vec3::new(round(n[0]), round(n[1]), round(n[2])));
                    for (k, g) in got.to_array().into_iter().enumerate() {
                        let e = (f64::from(g) - w[k]).abs() / scale[k];
                        if e > slot.0 {
                            *slot = (
                                e,
                                format!(
                                    "sun {theta_deg}°/{azimuth_deg}°, T {tau}, normal {n:.3?}, \
                                     channel {k}: {g} vs {:.3}",
                                    w[k]
                                ),
                            );
                        }
                    }
                }
            }
        }
    }
    for (filtered, row) in worst.iter().enumerate() {
        for (b, (e, at)) in row.iter().enumerate() {
            let what = if filtered == 1 {
                "filtered"
            } else {
                "unfiltered"
            };
            eprintln!(
                "irradiance, {} bands {what}: worst {:.3e} of the largest, at {at}",
                b + 1,
                e
            );
        }
    }
    for row in &worst {
        for slot in &row[4..] {
            assert!(slot.0 <= IRRADIANCE_BOUND, "{slot:?}");
        }
    }
}

#[test]
fn constructor_rejects_bad_parameters() {
    let sun = Sun::new(0.5, 0.0).expect("sun");
    // The Preetham sky accepts 2 to 6; the tables cover the paper's 2.5 to 6.
    assert!(matches!(
        ShSky::new(sun, 2.4, 3),
        Err(SkyError::OutOfRange {
            parameter: "turbidity",
            ..
        })
    ));
    assert!(matches!(
        ShSky::new(sun, f32::NAN, 3),
        Err(SkyError::OutOfRange { .. })
    ));
    assert!(matches!(
        ShSky::new(sun, 3.0, 0),
        Err(SkyError::OutOfRange {
            parameter: "SH bands",
            ..
        })
    ));
    assert!(matches!(
        ShSky::new(sun, 3.0, usize::MAX),
        Err(SkyError::OutOfRange { .. })
    ));
    let low = Sun::new(1.6, 0.0).expect("sun");
    assert!(matches!(
        ShSky::new(low, 3.0, 3),
        Err(SkyError::SunBelowHorizon { .. })
    ));
    assert!(ShSky::from_coefficients([Vec3::ONE; 49], 8).is_err());
}

#[test]
fn filter_reduces_ringing_below_the_horizon() {
    // The lower hemisphere should be black; the filtered expansion stays closer to it.
    for &(theta, tau) in &[(1.5f32, 6.0f32), (0.3, 2.5), (1.0, 4.0)] {
        let sun = Sun::new(theta, 0.0).expect("sun");
        let (raw, filtered) = (
            ShSky::new_unfiltered(sun, tau, 7).expect("sky"),
            ShSky::new(sun, tau, 7).expect("sky"),
        );
        let (mut e_raw, mut e_filtered) = (0.0f32, 0.0f32);
        for i in 0..18 {
            for j in 0..36 {
                let d = geom::direction(
                    (95.0 + 5.0 * i as f32).to_radians(),
                    (10.0 * j as f32).to_radians(),
                );
                e_raw += sky_core::color::luminance(raw.series(d)).abs();
                e_filtered += sky_core::color::luminance(filtered.series(d)).abs();
            }
        }
        eprintln!(
            "sun {theta}, T {tau}: |Y| below the horizon, filtered / unfiltered = {}",
            e_filtered / e_raw
        );
        assert!(
            e_filtered < e_raw,
            "sun {theta}, T {tau}: filtered {e_filtered}, raw {e_raw}"
        );
    }
}

#[test]
fn basis_matches_the_f64_projection_basis() {
    // sky-core's f32 basis against sky-train's f64 one (written differently: trigonometry
    // and explicit associated Legendre functions).
    for i in 0..40 {
        let (t, p) = (0.08 * f64::from(i), 0.37 * f64::from(i));
        let want = sky_train::sh::projection::basis(t.cos(), p);
        let got = basis::evaluate(geom::direction(round(t), round(p)), 7);
        for (k, (g, w)) in got.iter().zip(want).enumerate() {
            assert!(
                (f64::from(*g) - w).abs() < 2e-6,
                "Y[{k}]({t}, {p}): {g} vs {w}"
            );
        }
    }
}

fn sky_strategy() -> impl Strategy<Value = (f32, f32, f32, usize)> {
    (
        0.0f32..=core::f32::consts::FRAC_PI_2,
        -10.0f32..10.0,
        2.5f32..=6.0,
        1usize..=7,
    )
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 64,
        failure_persistence: Some(Box::new(FileFailurePersistence::WithSource("proptest-regressions"))),
        ..ProptestConfig::default()
    })]

    #[test]
    fn radiance_and_irradiance_are_finite_and_symmetric(
        (theta, phi, tau, bands) in sky_strategy(),
        (vt, vp) in (0.0f32..core::f32::consts::PI, 0.0f32..6.3),
    ) {
        let sky = ShSky::new(Sun::new(theta, phi).expect("sun"), tau, bands).expect("sky");
        let d = geom::direction(vt, phi + vp);
        let mirrored = geom::direction(vt, phi - vp);
        let (a, b) = (sky.radiance(d), sky.radiance(mirrored));
        prop_assert!(a.is_finite() && sky.irradiance(d).is_finite());
        // Symmetric about the sun's vertical plane.
        let scale = sky.coefficients()[0].abs().max_element();
        prop_assert!((a - b).abs().max_element() <= 2e-5 * scale, "{a} vs {b}");
        // Continuous across the azimuth seam.
        let eps = 1e-4f32;
        let s0 = sky.radiance(geom::direction(vt, -eps));
        let s1 = sky.radiance(geom::direction(vt, core::f32::consts::TAU - eps));
        prop_assert!((s0 - s1).abs().max_element() <= 1e-4 * scale);
    }

    #[test]
    fn any_input_gives_a_finite_value_or_an_error(
        theta in proptest::num::f32::ANY,
        tau in proptest::num::f32::ANY,
        bands in 0usize..20,
        d in proptest::array::uniform3(proptest::num::f32::ANY),
    ) {
        if let Ok(sun) = Sun::new(theta, 0.0)
            && let Ok(sky) = ShSky::new(sun, tau, bands)
        {
            let v = Vec3::from_array(d);
            prop_assert!(sky.radiance(v).is_finite() && sky.irradiance(v).is_finite());
        }
    }
}

#[test]
fn sample_and_render_show_the_sh_reconstruction() {
    let csv = run(
        &[
            "sample",
            "--model",
            "sh",
            "--bands",
            "5",
            "--sun-zenith",
            "40",
            "--sun-azimuth",
            "30",
            "--turbidity",
            "3",
        ],
        "0,0\n45,90\n120,200\n",
    );
    let sun = Sun::new(round(40f64.to_radians()), round(30f64.to_radians())).expect("sun");
    let sky = ShSky::new(sun, 3.0, 5).expect("sky");
    let rows: Vec<Vec<f64>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|f| f.parse().expect("number")).collect())
        .collect();
    assert_eq!(rows.len(), 3);
    for row in &rows {
        let d = geom::direction(round(row[0].to_radians()), round(row[1].to_radians()));
        let want = sky.radiance(d);
        for (got, want) in row[5..8].iter().zip(want.to_array()) {
            assert!(
                (got - f64::from(want)).abs() <= 1e-6 * f64::from(want.abs()).max(1.0),
                "{row:?}: {want}"
            );
        }
    }
    // render: an EXR of the unfiltered 7-band expansion, read back.
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("sh.exr");
    run(
        &[
            "render",
            "--model",
            "sh",
            "--no-ringing-filter",
            "--sun-zenith",
            "60",
            "--turbidity",
            "4",
            "--width",
            "64",
            "--out",
            out.to_str().expect("UTF-8"),
        ],
        "",
    );
    let img = sky_train::image_io::read_exr(&out).expect("EXR");
    let sun = Sun::new(round(60f64.to_radians()), 0.0).expect("sun");
    let sky = ShSky::new_unfiltered(sun, 4.0, 7).expect("sky");
    let grid = geom::Equirect::new(64, 32, geom::Extent::Sphere).expect("grid");
    for &(i, j) in &[(0u32, 0u32), (10, 5), (40, 20), (63, 31)] {
        let want = sky.radiance(grid.direction(i, j));
        let got = img.get(i as usize, j as usize);
        assert!(
            (got - want).abs().max_element() <= 1e-3 * want.abs().max_element().max(1.0),
            "({i}, {j}): {got} vs {want}"
        );
    }
}

#[test]
fn fit_sh_writes_tables_of_other_degrees() {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("table.rs");
    let report = run(
        &[
            "fit-sh",
            "--model",
            "preetham",
            "--degree-theta",
            "3",
            "--degree-turbidity",
            "2",
            "--degree-theta-high",
            "2",
            "--degree-turbidity-high",
            "1",
            "--nodes-theta",
            "6",
            "--nodes-turbidity",
            "4",
            "--out",
            out.to_str().expect("UTF-8"),
        ],
        "",
    );
    assert!(report.contains("24 skies projected"), "{report}");
    let source = std::fs::read_to_string(&out).expect("table written");
    assert!(
        source.starts_with("// generated by `sky-train fit-sh --model preetham --degree-theta 3"),
        "{source}"
    );
    assert!(source.contains("pub const PREETHAM: PolynomialTable<4, 3, 3, 2> = PolynomialTable {"));
    // 4 × 3 low rows of 15 RGB triples and 3 × 2 high rows of 13.
    assert_eq!(source.matches("], [").count(), 12 * 14 + 6 * 12);
}
