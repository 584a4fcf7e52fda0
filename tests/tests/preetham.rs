//! End-to-end tests of `sky-core`'s Preetham sky, geometry and colour conversions against an
//! independent f64 evaluation of seed 002 (eqs. 10-29, in `sky_tests::reference::preetham`), plus
//! properties over the whole valid domain and every constructor error.

use std::f64::consts::{FRAC_PI_2, PI, TAU};

use proptest::prelude::*;
use sky_core::color::{self, Xyy};
use sky_core::geom::{self, Equirect, Extent};
use sky_core::{PreethamSky, SkyError, Sun, Vec3};
use sky_tests::reference::preetham as reference;

mod common;
use common::proptest_config;

// ---------------------------------------------------------------------------------------------
// Shared test machinery
// ---------------------------------------------------------------------------------------------

/// The promised agreement of the scalar evaluation with the f64 reference (relative).
const SCALAR_BOUND: f64 = 1e-5;
/// The promised agreement of the batch evaluation with the scalar one (relative).
const BATCH_BOUND: f64 = 2e-6;

fn to_f32(v: [f64; 3]) -> Vec3 {
    #[allow(clippy::cast_possible_truncation)] // rounding to the f32 input is the point
    Vec3::new(v[0] as f32, v[1] as f32, v[2] as f32)
}

fn to_f64(v: Vec3) -> [f64; 3] {
    [f64::from(v.x), f64::from(v.y), f64::from(v.z)]
}

/// Rounds an f64 to the nearest f32.
fn round(x: f64) -> f32 {
    #[allow(clippy::cast_possible_truncation)]
    let r = x as f32;
    r
}

fn relative(got: f64, want: f64) -> f64 {
    (got - want).abs() / want.abs()
}

/// The largest component error of `got` relative to the largest component of `want`.
fn relative_to_max(got: Vec3, want: [f64; 3]) -> f64 {
    let scale = want.iter().fold(0.0_f64, |m, w| m.max(w.abs()));
    let g = to_f64(got);
    (0..3).fold(0.0_f64, |m, k| m.max((g[k] - want[k]).abs())) / scale
}

/// The largest error seen and where: NaN errors count as infinite.
#[derive(Debug)]
struct MaxError {
    what: &'static str,
    value: f64,
    at: String,
}

impl MaxError {
    fn new(what: &'static str) -> Self {
        Self {
            what,
            value: 0.0,
            at: String::from("nowhere"),
        }
    }

    fn update(&mut self, error: f64, at: impl FnOnce() -> String) {
        if error.is_nan() || error > self.value {
            self.value = if error.is_nan() { f64::INFINITY } else { error };
            self.at = at();
        }
    }

    fn check(&self, bound: f64) {
        eprintln!("max {}: {:.3e} at {}", self.what, self.value, self.at);
        assert!(
            self.value <= bound,
            "max {} {:.3e} exceeds the bound {bound:.1e}, at {}",
            self.what,
            self.value,
            self.at
        );
    }
}

/// One sky of the deterministic grid, in f32 as given to `sky-core`.
#[derive(Debug, Clone, Copy)]
struct SkyParams {
    turbidity: f32,
    sun_zenith: f32,
    sun_azimuth: f32,
}

impl SkyParams {
    fn sky(self) -> PreethamSky {
        let sun = Sun::new(self.sun_zenith, self.sun_azimuth).expect("valid sun");
        PreethamSky::new(sun, self.turbidity).expect("valid sky")
    }

    fn reference(self) -> reference::Sky {
        reference::Sky::new(
            f64::from(self.turbidity),
            f64::from(self.sun_zenith),
            f64::from(self.sun_azimuth),
        )
    }
}

/// Turbidity 2 to 6 by 0.5; sun zenith 0 to 85° by 5°, plus 0.01°, 89.5° and 90°; sun azimuths
/// cycling through values on both sides of the seam and a large one.
fn sky_grid() -> Vec<SkyParams> {
    let mut zeniths: Vec<f64> = (0..=17).map(|k| f64::from(k) * 5.0).collect();
    zeniths.extend([0.01, 89.5, 90.0]);
    let azimuths = [0.0, 1.0, 2.5, -0.7, 4.0, 6.2, 100.0];
    let mut grid = Vec::new();
    for k in 0..=8_u8 {
        let turbidity = 2.0 + 0.5 * f32::from(k);
        for (n, zenith) in zeniths.iter().enumerate() {
            grid.push(SkyParams {
                turbidity,
                sun_zenith: round(zenith.to_radians()),
                sun_azimuth: azimuths[(n + usize::from(k)) % azimuths.len()],
            });
        }
    }
    grid
}

/// View directions over the whole upper hemisphere around the sun of `p`, as f64 unit vectors:
/// zenith 0 to 90° by 2.5° and at the sun's zenith ± 0, 1e-3, 1e-2 rad; azimuth relative to the
/// sun 0 to 355° by 5° (so the sun's own direction and the antisolar azimuth are included) and
/// ± 1e-3, 1e-2 rad; and the horizon with z exactly 0.
fn view_grid(p: SkyParams) -> Vec<[f64; 3]> {
    let theta_s = f64::from(p.sun_zenith);
    let psi_s = f64::from(p.sun_azimuth);
    let mut zeniths: Vec<f64> = (0..=36)
        .map(|k| (f64::from(k) * 2.5).to_radians())
        .collect();
    for d in [0.0, 1e-3, -1e-3, 1e-2, -1e-2] {
        let t = theta_s + d;
        if (0.0..=FRAC_PI_2).contains(&t) {
            zeniths.push(t);
        }
    }
    let mut offsets: Vec<f64> = (0..72).map(|k| (f64::from(k) * 5.0).to_radians()).collect();
    offsets.extend([1e-3, -1e-3, 1e-2, -1e-2]);
    let mut dirs = Vec::with_capacity(zeniths.len() * offsets.len() * 2);
    for &theta in &zeniths {
        for &d in &offsets {
            dirs.push(reference::direction(theta, psi_s + d));
        }
    }
    for &d in &offsets {
        let (s, c) = (psi_s + d).sin_cos();
        dirs.push([c, s, 0.0]);
    }
    dirs
}

fn sky_strategy() -> impl Strategy<Value = (f32, f32, f32)> {
    let turbidity = prop_oneof![1 => Just(2.0_f32), 1 => Just(6.0_f32), 8 => 2.0_f32..=6.0];
    let sun_zenith = prop_oneof![
        1 => Just(0.0_f32),
        1 => Just(core::f32::consts::FRAC_PI_2),
        8 => 0.0_f32..=core::f32::consts::FRAC_PI_2,
    ];
    let sun_azimuth = prop_oneof![
        2 => -7.0_f32..7.0,
        1 => -1e4_f32..1e4,
        1 => Just(0.0_f32),
    ];
    (turbidity, sun_zenith, sun_azimuth)
}

fn make_sky(t: f32, zenith: f32, azimuth: f32) -> PreethamSky {
    PreethamSky::new(Sun::new(zenith, azimuth).expect("valid sun"), t).expect("valid sky")
}

fn xyy_relative(a: Xyy, b: Xyy) -> f64 {
    let r = |p: f32, q: f32| relative(f64::from(p), f64::from(q));
    r(a.luminance, b.luminance)
        .max(r(a.x, b.x))
        .max(r(a.y, b.y))
}

/// `sky-core` counts views whose normalised z lies in `[-HORIZON_BAND, 0)` as on the horizon
/// (so that `geom::direction(FRAC_PI_2, φ)`, whose z is −4.4e-8, is not dark), although its docs
/// say that every view with z < 0 is black. The properties accept either value in this band.
const HORIZON_BAND: f32 = 1e-6;

fn finite_xyy(c: Xyy) -> bool {
    c.x.is_finite() && c.y.is_finite() && c.luminance.is_finite()
}

// ---------------------------------------------------------------------------------------------
// Scalar evaluation against the f64 reference
// ---------------------------------------------------------------------------------------------

#[test]
fn zenith_values_and_perez_coefficients_match_eqs_13_to_19() {
    let mut coefficients = MaxError::new("Perez coefficient absolute error (eqs. 13-15)");
    let mut zenith = MaxError::new("zenith Y, x, y relative error (eqs. 16-19)");
    for p in sky_grid() {
        let sky = p.sky();
        let want = p.reference();
        for (got, want) in sky.perez_coefficients().iter().zip(want.perez) {
            let got = [got.a, got.b, got.c, got.d, got.e].map(f64::from);
            for (g, w) in got.iter().zip(want.to_array()) {
                // The coefficients are O(1) and some are near 0: absolute error.
                coefficients.update((g - w).abs(), || format!("{p:?}: got {got:?}, want {w}"));
            }
        }
        let z = sky.zenith();
        for (g, w) in [z.luminance, z.x, z.y].iter().zip(want.zenith) {
            zenith.update(relative(f64::from(*g), w), || {
                format!("{p:?}: got {z:?}, want {:?}", want.zenith)
            });
        }
    }
    coefficients.check(1e-6);
    zenith.check(SCALAR_BOUND);
}

#[test]
fn scalar_matches_f64_reference_over_upper_hemisphere() {
    let mut lum = MaxError::new("relative error of Y");
    let mut cx = MaxError::new("relative error of x");
    let mut cy = MaxError::new("relative error of y");
    let mut xyz = MaxError::new("XYZ error relative to max |component|");
    let mut rgb = MaxError::new("linear sRGB error relative to max |component|");
    let mut count = 0_usize;
    for p in sky_grid() {
        let sky = p.sky();
        let reference = p.reference();
        for v in view_grid(p) {
            let dir = to_f32(v);
            let want = reference.xyy(to_f64(dir));
            let got = sky.xyy(dir);
            let at = || format!("{p:?}, dir {dir:?}: got {got:?}, want {want:?}");
            lum.update(relative(f64::from(got.luminance), want.luminance), at);
            cx.update(relative(f64::from(got.x), want.x), at);
            cy.update(relative(f64::from(got.y), want.y), at);
            let want_xyz = reference::xyy_to_xyz(want);
            let got_xyz = sky.xyz(dir);
            xyz.update(relative_to_max(got_xyz, want_xyz), || {
                format!("{p:?}, dir {dir:?}: got {got_xyz}, want {want_xyz:?}")
            });
            let want_rgb = reference::xyz_to_linear_srgb(want_xyz);
            let got_rgb = sky.rgb(dir);
            rgb.update(relative_to_max(got_rgb, want_rgb), || {
                format!("{p:?}, dir {dir:?}: got {got_rgb}, want {want_rgb:?}")
            });
            count += 1;
        }
    }
    eprintln!("{count} directions compared");
    lum.check(SCALAR_BOUND);
    cx.check(SCALAR_BOUND);
    cy.check(SCALAR_BOUND);
    xyz.check(SCALAR_BOUND);
    // Eq. 28 mixes X, Y, Z with coefficients up to 3.24 and cancellation between them, so the
    // 1e-5 errors of x, y and Y can grow by a few times in the components.
    rgb.check(5.0 * SCALAR_BOUND);
}

#[test]
fn below_horizon_is_black_with_the_horizon_chromaticity() {
    let mut chroma = MaxError::new("relative error of below-horizon x, y");
    for p in sky_grid().into_iter().step_by(3) {
        let sky = p.sky();
        let reference = p.reference();
        for k in 1..=36 {
            let theta = FRAC_PI_2 + (f64::from(k) * 2.5).to_radians();
            for a in 0..36 {
                let psi = f64::from(p.sun_azimuth) + (f64::from(a) * 10.0).to_radians();
                let dir = to_f32(reference::direction(theta, psi));
                let got = sky.xyy(dir);
                assert!(
                    got.luminance == 0.0 && sky.rgb(dir) == Vec3::ZERO,
                    "{p:?}, dir {dir:?}: below the horizon, got {got:?} and rgb {}",
                    sky.rgb(dir)
                );
                let want = reference.xyy(to_f64(dir));
                let at = || format!("{p:?}, dir {dir:?}: got {got:?}, want {want:?}");
                chroma.update(relative(f64::from(got.x), want.x), at);
                chroma.update(relative(f64::from(got.y), want.y), at);
            }
        }
    }
    chroma.check(SCALAR_BOUND);
}

// ---------------------------------------------------------------------------------------------
// Batch evaluation against the scalar one
// ---------------------------------------------------------------------------------------------

#[test]
fn batch_matches_scalar() {
    let mut xyy_err = MaxError::new("xyy_batch relative error vs xyy");
    let mut rgb_err = MaxError::new("rgb_batch error vs rgb, relative to max |component|");
    for p in sky_grid().into_iter().step_by(2) {
        let sky = p.sky();
        let mut dirs: Vec<Vec3> = view_grid(p).into_iter().map(to_f32).collect();
        // A few below the horizon and degenerate ones, so the lanes see every branch.
        dirs.extend([
            Vec3::new(0.3, 0.2, -0.5),
            Vec3::new(1.0, 0.0, -1e-30),
            Vec3::ZERO,
            Vec3::new(f32::NAN, 0.0, 1.0),
            Vec3::new(3.0, -4.0, 12.0),
        ]);
        // Every length from 0 to 25 at several starting offsets, and the whole grid (whose
        // length is not a multiple of 8).
        let mut slices: Vec<(usize, usize)> = Vec::new();
        for len in 0..=25 {
            for start in [0, 1, 5, 11] {
                slices.push((start, len));
            }
        }
        slices.push((0, dirs.len()));
        slices.push((3, dirs.len() - 3));
        for (start, len) in slices {
            let part = &dirs[start..start + len];
            let mut out_xyy = vec![Xyy::default(); len];
            let mut out_rgb = vec![Vec3::ZERO; len];
            sky.xyy_batch(part, &mut out_xyy);
            sky.rgb_batch(part, &mut out_rgb);
            for (k, &dir) in part.iter().enumerate() {
                let want = sky.xyy(dir);
                let got = out_xyy[k];
                if want.luminance == 0.0 || !dir.is_finite() || dir == Vec3::ZERO {
                    // Below the horizon or degenerate: only finiteness and black are promised
                    // to match.
                    assert!(finite_xyy(got), "{p:?}, dir {dir:?}: batch gave {got:?}");
                    if dir.is_finite() && dir.z < 0.0 {
                        assert!(got.luminance == 0.0, "{p:?}, dir {dir:?}: {got:?}");
                    }
                    continue;
                }
                xyy_err.update(xyy_relative(got, want), || {
                    format!("{p:?}, slice {start}+{len}, dir {dir:?}: got {got:?}, want {want:?}")
                });
                let want_rgb = sky.rgb(dir);
                let got_rgb = out_rgb[k];
                rgb_err.update(relative_to_max(got_rgb, to_f64(want_rgb)), || {
                    format!("{p:?}, dir {dir:?}: got {got_rgb}, want {want_rgb}")
                });
            }
        }
    }
    xyy_err.check(BATCH_BOUND);
    // rgb is a fixed linear map of xyY: a few times the xyY bound (see the scalar test).
    rgb_err.check(5.0 * BATCH_BOUND);
}

#[test]
fn batch_fills_only_the_common_prefix() {
    let sky = make_sky(3.0, 0.6, 1.0);
    let dirs: Vec<Vec3> = (0..21)
        .map(|k| geom::direction(0.05 * f32::from(u8::try_from(k).expect("small")), 0.3))
        .collect();
    let sentinel = Xyy {
        x: -1.0,
        y: -2.0,
        luminance: -3.0,
    };
    let rgb_sentinel = Vec3::splat(-7.0);
    for out_len in [0, 1, 5, 8, 13, 20, 21, 22, 30] {
        let mut out = vec![sentinel; out_len];
        let mut out_rgb = vec![rgb_sentinel; out_len];
        sky.xyy_batch(&dirs, &mut out);
        sky.rgb_batch(&dirs, &mut out_rgb);
        for k in 0..out_len {
            if k < dirs.len() {
                let want = sky.xyy(dirs[k]);
                assert!(
                    xyy_relative(out[k], want) <= BATCH_BOUND,
                    "out.len() {out_len}, k {k}: batch {:?}, scalar {want:?}",
                    out[k]
                );
                let want_rgb = sky.rgb(dirs[k]);
                assert!(
                    relative_to_max(out_rgb[k], to_f64(want_rgb)) <= 5.0 * BATCH_BOUND,
                    "out.len() {out_len}, k {k}: batch {}, scalar {want_rgb}",
                    out_rgb[k]
                );
            } else {
                assert!(
                    out[k] == sentinel && out_rgb[k] == rgb_sentinel,
                    "out.len() {out_len} > dirs.len() {}: out[{k}] was overwritten: {:?}, {}",
                    dirs.len(),
                    out[k],
                    out_rgb[k]
                );
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Properties over the whole valid domain
// ---------------------------------------------------------------------------------------------

/// Special component values for degenerate direction vectors.
const SPECIAL: [f32; 11] = [
    0.0,
    -0.0,
    1.0,
    -1.0,
    f32::NAN,
    f32::INFINITY,
    f32::NEG_INFINITY,
    f32::MAX,
    f32::MIN,
    f32::MIN_POSITIVE,
    1e-45,
];

#[test]
fn degenerate_directions_give_finite_values() {
    for (t, zenith, azimuth) in [(2.0, 0.0, 0.0), (4.5, 1.0, 2.0), (6.0, 1.570_796_4, -3.0)] {
        let sky = make_sky(t, zenith, azimuth);
        let mut dirs = Vec::new();
        for x in SPECIAL {
            for y in SPECIAL {
                for z in SPECIAL {
                    dirs.push(Vec3::new(x, y, z));
                }
            }
        }
        let mut out = vec![Xyy::default(); dirs.len()];
        let mut out_rgb = vec![Vec3::ZERO; dirs.len()];
        sky.xyy_batch(&dirs, &mut out);
        sky.rgb_batch(&dirs, &mut out_rgb);
        for (k, &dir) in dirs.iter().enumerate() {
            let c = sky.xyy(dir);
            assert!(
                finite_xyy(c),
                "sky ({t}, {zenith}, {azimuth}), dir {dir:?}: {c:?}"
            );
            assert!(
                sky.xyz(dir).is_finite(),
                "dir {dir:?}: xyz {}",
                sky.xyz(dir)
            );
            assert!(
                sky.rgb(dir).is_finite(),
                "dir {dir:?}: rgb {}",
                sky.rgb(dir)
            );
            assert!(finite_xyy(out[k]), "dir {dir:?}: xyy_batch {:?}", out[k]);
            assert!(
                out_rgb[k].is_finite(),
                "dir {dir:?}: rgb_batch {}",
                out_rgb[k]
            );
        }
    }
}

proptest! {
    #![proptest_config(proptest_config(1024))]

    #[test]
    fn prop_finite_positive_above_black_below(
        (t, zs, az) in sky_strategy(),
        theta in prop_oneof![
            8 => 0.0..=PI,
            1 => Just(FRAC_PI_2),
            1 => FRAC_PI_2 - 1e-6..FRAC_PI_2 + 1e-6,
        ],
        psi in 0.0..TAU,
    ) {
        let sky = make_sky(t, zs, az);
        let dir = to_f32(reference::direction(theta, psi));
        let c = sky.xyy(dir);
        let xyz = sky.xyz(dir);
        let rgb = sky.rgb(dir);
        prop_assert!(finite_xyy(c) && xyz.is_finite() && rgb.is_finite(),
            "dir {dir:?}: {c:?}, xyz {xyz}, rgb {rgb}");
        prop_assert!(c.x > 0.0 && c.x < 1.0 && c.y > 0.0 && c.y < 1.0,
            "chromaticity outside (0, 1): dir {dir:?}: {c:?}");
        if dir.z >= 0.0 {
            prop_assert!(c.luminance > 0.0, "dir {dir:?} above the horizon: {c:?}");
            prop_assert!(xyz.min_element() > 0.0, "dir {dir:?}: xyz {xyz}");
        } else if dir.z < -HORIZON_BAND {
            prop_assert!(c.luminance == 0.0, "dir {dir:?} below the horizon: {c:?}");
            prop_assert!(rgb == Vec3::ZERO, "dir {dir:?} below the horizon: rgb {rgb}");
        } else {
            // Within HORIZON_BAND below the horizon: black, or the value on the horizon.
            let horizon = sky.xyy(Vec3::new(dir.x, dir.y, 0.0));
            prop_assert!(c.luminance == 0.0 || xyy_relative(c, horizon) <= SCALAR_BOUND,
                "dir {dir:?} just below the horizon: {c:?}, on the horizon {horizon:?}");
        }
    }

    #[test]
    fn prop_symmetric_about_the_sun_vertical_plane(
        (t, zs, az) in sky_strategy(),
        theta in 0.0..=FRAC_PI_2,
        delta in prop_oneof![8 => 0.0..=PI, 1 => 0.0..1e-3],
    ) {
        let sky = make_sky(t, zs, az);
        let psi_s = f64::from(az);
        let left = to_f32(reference::direction(theta, psi_s + delta));
        let right = to_f32(reference::direction(theta, psi_s - delta));
        let (a, b) = (sky.xyy(left), sky.xyy(right));
        let err = xyy_relative(a, b);
        prop_assert!(err <= SCALAR_BOUND,
            "mirror images differ by {err:.2e}: {left:?} -> {a:?}, {right:?} -> {b:?}");
    }

    #[test]
    fn prop_continuous_across_the_azimuth_seam(
        (t, zs, az) in prop_oneof![
            sky_strategy(),
            (2.0_f32..=6.0, 0.0_f32..=core::f32::consts::FRAC_PI_2, -1e-3_f32..1e-3),
        ],
        theta in 0.0..=FRAC_PI_2,
        eps in prop_oneof![1e-7..1e-5, 1e-5..1e-3],
    ) {
        let sky = make_sky(t, zs, az);
        let before = to_f32(reference::direction(theta, TAU - eps));
        let after = to_f32(reference::direction(theta, eps));
        let (a, b) = (sky.xyy(before), sky.xyy(after));
        // The directions are 2 eps sin(theta) apart; |d ln F / d gamma| < 3 for every channel
        // over the valid turbidities (|D| < 2.4, E small), so the values may differ by that much.
        let allowed = 3.0 * 2.0 * eps * theta.sin() + SCALAR_BOUND;
        let err = xyy_relative(a, b);
        prop_assert!(err <= allowed,
            "across the seam: {before:?} -> {a:?}, {after:?} -> {b:?}: {err:.2e} > {allowed:.2e}");

        // The same direction given with azimuth phi and phi + 2 pi, and the same sun given with
        // azimuth az and az ± 2 pi.
        let phi = eps * 1e3;
        let d1 = geom::direction(round(theta), round(phi));
        let d2 = geom::direction(round(theta), round(phi + TAU));
        let err = xyy_relative(sky.xyy(d1), sky.xyy(d2));
        prop_assert!(err <= SCALAR_BOUND, "phi {phi} vs phi + 2 pi: {err:.2e}");
        // Only where az ± 2 pi is nearly exact in f32 (ulp 2e-6 at 16).
        let shifts = [f64::from(az) + TAU, f64::from(az) - TAU];
        for shifted in shifts.into_iter().filter(|_| az.abs() < 10.0) {
            let other = make_sky(t, zs, round(shifted));
            let (a, b) = (sky.xyy(d1), other.xyy(d1));
            let err = xyy_relative(a, b);
            prop_assert!(err <= SCALAR_BOUND,
                "sun azimuth {az} vs {shifted}: {a:?} vs {b:?} ({err:.2e})");
        }
    }

    #[test]
    fn prop_unnormalised_directions_give_the_normalised_value(
        (t, zs, az) in sky_strategy(),
        theta in 0.0..=PI,
        psi in 0.0..TAU,
        // |v|² must stay a normal f32: see the report on scales beyond 1e±18.
        log_scale in -18.0..18.0_f64,
    ) {
        let sky = make_sky(t, zs, az);
        let unit = reference::direction(theta, psi);
        let scale = 10.0_f64.powf(log_scale);
        let scaled = to_f32(unit.map(|c| c * scale));
        let normalised = to_f32(reference::direction(theta, psi));
        let (a, b) = (sky.xyy(scaled), sky.xyy(normalised));
        if normalised.z < -HORIZON_BAND {
            prop_assert!(a.luminance == 0.0 && b.luminance == 0.0, "{a:?} {b:?}");
            let err = xyy_relative(Xyy { luminance: 1.0, ..a }, Xyy { luminance: 1.0, ..b });
            prop_assert!(err <= SCALAR_BOUND, "{scaled:?} -> {a:?}, {normalised:?} -> {b:?}");
        } else {
            let err = xyy_relative(a, b);
            prop_assert!(err <= SCALAR_BOUND,
                "scale {scale:e}: {scaled:?} -> {a:?}, {normalised:?} -> {b:?} ({err:.2e})");
        }
    }

    #[test]
    fn prop_finite_for_any_direction_bits(
        (t, zs, az) in sky_strategy(),
        x in proptest::num::f32::ANY,
        y in proptest::num::f32::ANY,
        z in proptest::num::f32::ANY,
    ) {
        let sky = make_sky(t, zs, az);
        let dir = Vec3::new(x, y, z);
        let c = sky.xyy(dir);
        let rgb = sky.rgb(dir);
        prop_assert!(finite_xyy(c) && rgb.is_finite(), "dir {dir:?}: {c:?}, rgb {rgb}");
        let mut out = [Xyy::default(); 3];
        sky.xyy_batch(&[dir, dir, dir], &mut out);
        prop_assert!(out.iter().all(|&c| finite_xyy(c)), "dir {dir:?}: batch {out:?}");
    }

    #[test]
    fn prop_any_finite_sun_azimuth_gives_finite_values(
        t in 2.0_f32..=6.0,
        zs in 0.0_f32..=core::f32::consts::FRAC_PI_2,
        az in proptest::num::f32::NORMAL | proptest::num::f32::ZERO | proptest::num::f32::SUBNORMAL,
        theta in 0.0..=FRAC_PI_2,
        psi in 0.0..TAU,
    ) {
        let sky = make_sky(t, zs, az);
        let dir = to_f32(reference::direction(theta, psi));
        let c = sky.xyy(dir);
        prop_assert!(finite_xyy(c) && c.luminance > 0.0, "sun azimuth {az}, dir {dir:?}: {c:?}");
    }
}

// ---------------------------------------------------------------------------------------------
// Constructor errors
// ---------------------------------------------------------------------------------------------

/// Bitwise equality: the error fields are exact copies of the bounds.
fn same(a: f32, b: f32) -> bool {
    a.to_bits() == b.to_bits()
}

fn sun_ok() -> Sun {
    Sun::new(0.5, 0.0).expect("valid sun")
}

#[test]
fn turbidity_errors() {
    for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        let err = PreethamSky::new(sun_ok(), bad).expect_err("non-finite turbidity");
        assert!(
            matches!(err, SkyError::OutOfRange { parameter, min, max, .. }
                if parameter.contains("turbidity") && same(min, 2.0) && same(max, 6.0)),
            "turbidity {bad}: {err:?}"
        );
        let text = err.to_string();
        assert!(
            text.contains("turbidity") && text.contains("[2, 6]"),
            "turbidity {bad}: {text}"
        );
    }
    for bad in [1.99_f32, 6.01, 0.0, -3.0, 1e30] {
        let err = PreethamSky::new(sun_ok(), bad).expect_err("turbidity out of range");
        assert!(
            matches!(err, SkyError::OutOfRange { parameter, value, min, max }
                if parameter.contains("turbidity") && value.to_bits() == bad.to_bits()
                    && same(min, 2.0) && same(max, 6.0)),
            "turbidity {bad}: {err:?}"
        );
        let text = err.to_string();
        assert!(
            text.contains("turbidity")
                && text.contains(&bad.to_string())
                && text.contains("[2, 6]"),
            "turbidity {bad}: {text}"
        );
    }
    for good in [2.0_f32, 6.0, 3.7] {
        assert!(
            PreethamSky::new(sun_ok(), good).is_ok(),
            "turbidity {good} is valid"
        );
    }
}

#[test]
fn sun_errors() {
    for bad in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        let err = Sun::new(bad, 0.0).expect_err("non-finite zenith");
        assert!(
            matches!(err, SkyError::OutOfRange { parameter, min, max, .. }
                if parameter.contains("sun zenith") && same(min, 0.0)
                    && same(max, core::f32::consts::PI)),
            "zenith {bad}: {err:?}"
        );
        assert!(
            err.to_string().contains("sun zenith"),
            "zenith {bad}: {err}"
        );
        let err = Sun::new(0.5, bad).expect_err("non-finite azimuth");
        assert!(
            matches!(err, SkyError::NotFinite { parameter } if parameter.contains("sun azimuth")),
            "azimuth {bad}: {err:?}"
        );
        let text = err.to_string();
        assert!(
            text.contains("sun azimuth") && text.contains("finite"),
            "azimuth {bad}: {text}"
        );
    }
    let pi = core::f32::consts::PI;
    let above_pi = f32::from_bits(pi.to_bits() + 1);
    for bad in [-1e-6_f32, -0.5, above_pi, 3.5, 1e9] {
        let err = Sun::new(bad, 0.0).expect_err("zenith outside [0, pi]");
        assert!(
            matches!(err, SkyError::OutOfRange { parameter, min, max, .. }
                if parameter.contains("sun zenith") && same(min, 0.0) && same(max, pi)),
            "zenith {bad}: {err:?}"
        );
        let text = err.to_string();
        assert!(
            text.contains("sun zenith") && text.contains("[0, 3.14159"),
            "zenith {bad}: {text}"
        );
    }
    for good in [0.0_f32, -0.0, 1.0, pi] {
        assert!(Sun::new(good, 0.0).is_ok(), "zenith {good} is valid");
    }
    for good in [0.0_f32, -1e30, f32::MAX, f32::MIN] {
        assert!(
            Sun::new(0.3, good).is_ok(),
            "any finite azimuth is valid: {good}"
        );
    }
}

#[test]
fn sun_below_horizon_error() {
    let half_pi = core::f32::consts::FRAC_PI_2;
    let just_below = f32::from_bits(half_pi.to_bits() + 1);
    for zenith in [just_below, 1.6, 2.5, core::f32::consts::PI] {
        let sun = Sun::new(zenith, 0.0).expect("a sun below the horizon is a valid Sun");
        let err = PreethamSky::new(sun, 3.0).expect_err("sun below the horizon");
        assert!(
            matches!(err, SkyError::SunBelowHorizon { zenith: z } if z.to_bits() == zenith.to_bits()),
            "zenith {zenith}: {err:?}"
        );
        let text = err.to_string();
        assert!(
            text.contains("sun")
                && text.contains("zenith")
                && text.contains(&zenith.to_string())
                && text.contains("pi/2"),
            "zenith {zenith}: {text}"
        );
    }
    // The horizon itself (pi/2 rounded to f32 lies just above pi/2) is accepted.
    assert!(PreethamSky::new(Sun::new(half_pi, 0.0).expect("sun"), 3.0).is_ok());
}

#[test]
fn equirect_size_errors() {
    let max = Equirect::MAX_SIZE;
    for extent in [Extent::UpperHemisphere, Extent::Sphere] {
        for (w, h, name) in [
            (0, 10, "width"),
            (10, 0, "height"),
            (0, 0, "width"),
            (max + 1, 10, "width"),
            (10, max + 1, "height"),
            (u32::MAX, 10, "width"),
        ] {
            let err = Equirect::new(w, h, extent).expect_err("bad size");
            assert!(
                matches!(err, SkyError::OutOfRange { parameter, min, max: m, .. }
                    if parameter.contains(name) && same(min, 1.0) && same(m, 65536.0)),
                "{w} x {h}: {err:?}"
            );
            let text = err.to_string();
            assert!(
                text.contains(name) && text.contains("[1, 65536]"),
                "{w} x {h}: {text}"
            );
        }
        for (w, h) in [(1, 1), (max, max), (max, 1)] {
            assert!(Equirect::new(w, h, extent).is_ok(), "{w} x {h} is valid");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Geometry
// ---------------------------------------------------------------------------------------------

#[test]
fn direction_and_zenith_azimuth_round_trip() {
    let mut dir_err = MaxError::new("direction() error vs f64");
    let mut angle_err = MaxError::new("zenith_azimuth(direction()) angle error");
    for a in 0..=180 {
        let theta = round(f64::from(a).to_radians());
        for b in 0..360 {
            let phi = round((f64::from(b) + 0.25).to_radians());
            let d = geom::direction(theta, phi);
            let want = reference::direction(f64::from(theta), f64::from(phi));
            dir_err.update(relative_to_max(d, want), || {
                format!("({theta}, {phi}): {d}")
            });
            let (t, p) = geom::zenith_azimuth(d);
            assert!(
                (0.0..=core::f32::consts::PI).contains(&t)
                    && (0.0..core::f32::consts::TAU).contains(&p),
                "zenith_azimuth({d}) = ({t}, {p}) out of range"
            );
            angle_err.update(f64::from((t - theta).abs()), || {
                format!("({theta}, {phi}) -> ({t}, {p})")
            });
            if a != 0 && a != 180 {
                // The azimuth is defined away from the poles: its error is an angle on a circle.
                let dp = f64::from(p) - f64::from(phi);
                let dp = (dp + PI).rem_euclid(TAU) - PI;
                angle_err.update(dp.abs() * f64::from(theta).sin(), || {
                    format!("({theta}, {phi}) -> ({t}, {p})")
                });
            }
        }
    }
    dir_err.check(2e-7);
    angle_err.check(5e-7);
    // Non-unit vectors and the zero vector.
    let (t, p) = geom::zenith_azimuth(Vec3::new(0.0, -2.0, -2.0));
    let want = (3.0 * PI / 4.0, 3.0 * PI / 2.0);
    assert!(
        (f64::from(t) - want.0).abs() < 1e-6 && (f64::from(p) - want.1).abs() < 1e-6,
        "zenith_azimuth((0, -2, -2)) = ({t}, {p}), want {want:?}"
    );
    let (t, p) = geom::zenith_azimuth(Vec3::ZERO);
    assert!(t.is_finite() && p.is_finite(), "zero vector: ({t}, {p})");
    let (t, p) = geom::zenith_azimuth(Vec3::new(1.0, -1e-30, 0.0));
    assert!(
        (0.0..core::f32::consts::TAU).contains(&p) && t.is_finite(),
        "azimuth just below 2 pi must stay in [0, 2 pi): ({t}, {p})"
    );
}

#[test]
fn angle_between_is_accurate_near_zero_and_pi() {
    let mut small = MaxError::new("angle_between relative error, angles 1e-4 to 1e-2");
    let mut all = MaxError::new("angle_between absolute error [rad]");
    let mut naive = MaxError::new("f32 acos(a . b) absolute error [rad] (for contrast)");
    let deltas = [
        1e-4,
        3e-4,
        1e-3,
        1e-2,
        0.1,
        1.0,
        2.0,
        3.0,
        PI - 1e-2,
        PI - 1e-3,
        PI - 1e-4,
    ];
    for a in 0..=12 {
        let theta = f64::from(a) * 15.0_f64.to_radians();
        for b in 0..12 {
            let psi = f64::from(b) * 30.0_f64.to_radians() + 0.1;
            let p = reference::direction(theta, psi);
            // A unit tangent at p (the direction of increasing zenith angle) and the point at
            // angle delta from p along the great circle through it.
            let tangent = reference::direction(theta + FRAC_PI_2, psi);
            for delta in deltas {
                let (s, c) = f64::sin_cos(delta);
                let q = [0, 1, 2].map(|k| c * p[k] + s * tangent[k]);
                let (pf, qf) = (to_f32(p), to_f32(q));
                // The exact angle between the f32 vectors actually passed.
                let want = reference::angle_between(to_f64(pf), to_f64(qf));
                let got = f64::from(geom::angle_between(pf, qf));
                let at = || format!("{pf:?}, {qf:?}: got {got}, want {want}");
                all.update((got - want).abs(), at);
                naive.update(
                    (f64::from(pf.dot(qf).clamp(-1.0, 1.0).acos()) - want).abs(),
                    at,
                );
                if delta <= 1e-2 {
                    small.update(relative(got, want), at);
                }
            }
        }
    }
    // acos of the f32 dot product is off by up to ~3e-4 rad near 0 and pi (the dot product of
    // vectors less than 2.4e-4 rad apart rounds to 1): these bounds are far tighter.
    small.check(1e-3);
    all.check(5e-7);
    eprintln!(
        "for contrast, {}: {:.3e} at {}",
        naive.what, naive.value, naive.at
    );
    assert!(
        naive.value > 1e3 * all.value,
        "the test vectors should defeat the naive acos formula: {naive:?}"
    );
}

#[test]
fn equirect_directions_follow_eqs_20_21() {
    let mut err = MaxError::new("Equirect direction error vs eqs. 20-21");
    for (w, big_h) in [
        (1_u32, 2_u32),
        (4, 2),
        (16, 8),
        (7, 10),
        (360, 180),
        (1000, 62),
    ] {
        // Eq. 20 covers the upper hemisphere with rows j < H/2.
        let grid = Equirect::new(w, big_h / 2, Extent::UpperHemisphere).expect("grid");
        for j in 0..big_h / 2 {
            for i in 0..w {
                let u = (f64::from(i) + 0.5) / f64::from(w);
                let v = f64::from(2 * j + 1) / f64::from(big_h);
                let psi = TAU * u; // eq. 21
                let phi = FRAC_PI_2 * (1.0 - v); // eq. 21: elevation
                let want = [phi.cos() * psi.cos(), phi.cos() * psi.sin(), phi.sin()];
                let got = grid.direction(i, j);
                err.update(relative_to_max(got, want), || {
                    format!("{w} x {big_h}, pixel ({i}, {j}): got {got}, want {want:?}")
                });
                err.update(
                    (f64::from(grid.zenith(j)) - (FRAC_PI_2 - phi)).abs(),
                    || format!("{w} x {big_h}, row {j}: zenith {}", grid.zenith(j)),
                );
                err.update((f64::from(grid.azimuth(i)) - psi).abs() / TAU, || {
                    format!("{w} x {big_h}, column {i}: azimuth {}", grid.azimuth(i))
                });
            }
        }
    }
    // The f32 azimuth 2 pi u (up to 2 pi, ulp 4.8e-7) carries a few rounding errors.
    err.check(1e-6);
}

#[test]
fn equirect_pixel_inverts_direction() {
    for extent in [Extent::UpperHemisphere, Extent::Sphere] {
        for (w, h) in [
            (1, 1),
            (2, 1),
            (3, 2),
            (16, 8),
            (17, 9),
            (360, 90),
            (512, 256),
        ] {
            let grid = Equirect::new(w, h, extent).expect("grid");
            for j in 0..h {
                for i in 0..w {
                    let d = grid.direction(i, j);
                    assert_eq!(grid.pixel(d), Some((i, j)), "{w} x {h} {extent:?}: {d}");
                    assert_eq!(
                        grid.pixel(d * 37.5),
                        Some((i, j)),
                        "{w} x {h} {extent:?}: scaled {d}"
                    );
                }
            }
        }
        // The largest grid, sampled.
        let max = Equirect::MAX_SIZE;
        let grid = Equirect::new(max, max, extent).expect("grid");
        for j in [0, 1, 2, 1000, max / 2 - 1, max / 2, max - 2, max - 1] {
            for i in [0, 1, 12_345, max / 2, max - 1] {
                let d = grid.direction(i, j);
                assert_eq!(grid.pixel(d), Some((i, j)), "max grid {extent:?}: {d}");
            }
        }
        for bad in [Vec3::ZERO, Vec3::NAN, Vec3::new(f32::INFINITY, 0.0, 1.0)] {
            assert_eq!(grid.pixel(bad), None, "{bad} is not a direction");
        }
    }
    let hemisphere = Equirect::new(8, 4, Extent::UpperHemisphere).expect("grid");
    assert_eq!(
        hemisphere.pixel(Vec3::new(0.3, 0.1, -0.5)),
        None,
        "below the horizon is outside an upper-hemisphere grid"
    );
}

/// The exact solid angle of a pixel of row `j` of a `w` × `h` grid spanning zenith angles 0 to
/// `theta_max`: Δφ (cos θ_top − cos θ_bottom).
fn band_solid_angle(w: u32, h: u32, theta_max: f64, j: u32) -> f64 {
    let edge = |r: u32| theta_max * f64::from(r) / f64::from(h);
    // cos a − cos b = 2 sin((a + b)/2) sin((b − a)/2), well conditioned in f64.
    TAU / f64::from(w)
        * 2.0
        * ((edge(j) + edge(j + 1)) / 2.0).sin()
        * ((edge(j + 1) - edge(j)) / 2.0).sin()
}

const SOLID_ANGLE_GRIDS: [(u32, u32); 6] = [
    (1, 1),
    (4, 2),
    (7, 3),
    (360, 180),
    (4096, 2048),
    (65_536, 65_536),
];

#[test]
fn equirect_solid_angles_sum_to_the_covered_area() {
    let mut rows =
        MaxError::new("Equirect row solid angle relative error (rows above the horizon)");
    for (extent, area, theta_max) in [
        (Extent::UpperHemisphere, TAU, FRAC_PI_2),
        (Extent::Sphere, 2.0 * TAU, PI),
    ] {
        for (w, h) in SOLID_ANGLE_GRIDS {
            let grid = Equirect::new(w, h, extent).expect("grid");
            let total: f64 = (0..h)
                .map(|j| f64::from(w) * f64::from(grid.solid_angle(j)))
                .sum();
            let err = relative(total, area);
            eprintln!("{w} x {h} {extent:?}: total solid angle rel. error {err:.2e}");
            assert!(
                err <= 1e-5,
                "{w} x {h} {extent:?}: solid angles sum to {total}, want {area} (rel. error {err:.2e})"
            );
            // Each row against the exact area of its band, for the rows of the upper hemisphere
            // (see `equirect_sphere_solid_angles_are_accurate_near_the_nadir` for the others).
            for j in (0..h).filter(|&j| f64::from(grid.zenith(j)) <= FRAC_PI_2) {
                let want = band_solid_angle(w, h, theta_max, j);
                let got = f64::from(grid.solid_angle(j));
                rows.update(relative(got, want), || {
                    format!("{w} x {h} {extent:?}: row {j} solid angle {got}, want {want}")
                });
            }
        }
    }
    rows.check(1e-6);
}

#[test]
fn equirect_sphere_solid_angles_are_accurate_near_the_nadir() {
    let mut rows = MaxError::new("Equirect sphere row solid angle relative error");
    for (w, h) in SOLID_ANGLE_GRIDS {
        let grid = Equirect::new(w, h, Extent::Sphere).expect("grid");
        for j in 0..h {
            let want = band_solid_angle(w, h, PI, j);
            let got = f64::from(grid.solid_angle(j));
            rows.update(relative(got, want), || {
                format!("{w} x {h}: row {j} solid angle {got}, want {want}")
            });
        }
    }
    rows.check(1e-6);
}

// ---------------------------------------------------------------------------------------------
// Colour
// ---------------------------------------------------------------------------------------------

#[test]
fn xyy_to_linear_srgb_matches_eqs_27_28() {
    let mut err = MaxError::new("xyY -> linear sRGB error relative to max |component|");
    let mut xyz_err = MaxError::new("xyY -> XYZ error relative to max |component|");
    for a in 1..=80 {
        for b in 1..=90 {
            let x = f64::from(a) * 0.01;
            let y = f64::from(b) * 0.01 - 0.003;
            if x + y > 1.0 {
                continue;
            }
            for luminance in [1e-3, 1.0, 37.0, 1.5e4] {
                let c = Xyy {
                    x: round(x),
                    y: round(y),
                    luminance: round(luminance),
                };
                let want_xyz = reference::xyy_to_xyz(reference::Xyy {
                    x: f64::from(c.x),
                    y: f64::from(c.y),
                    luminance: f64::from(c.luminance),
                });
                let got_xyz = color::xyy_to_xyz(c);
                xyz_err.update(relative_to_max(got_xyz, want_xyz), || {
                    format!("{c:?}: got {got_xyz}, want {want_xyz:?}")
                });
                let want = reference::xyz_to_linear_srgb(want_xyz);
                let got = color::xyz_to_linear_srgb(got_xyz);
                err.update(relative_to_max(got, want), || {
                    format!("{c:?}: got {got}, want {want:?}")
                });
            }
        }
    }
    xyz_err.check(5e-7);
    err.check(2e-6);
    // Eq. 27 is undefined for y = 0: black, not NaN.
    let black = color::xyy_to_xyz(Xyy {
        x: 0.3,
        y: 0.0,
        luminance: 5.0,
    });
    assert!(black == Vec3::ZERO, "y = 0 must give black, got {black}");
}

#[test]
fn srgb_transfer_function_matches_eq_29() {
    let mut err = MaxError::new("sRGB encode absolute error vs eq. 29");
    let mut values: Vec<f32> = (0..=100_000)
        .map(|k| round(f64::from(k) / 100_000.0))
        .collect();
    // Around the knee at 0.0031308, and tiny values.
    values.extend((-50..=50).map(|k| round(0.003_130_8 * (1.0 + f64::from(k) * 1e-6))));
    values.extend([1e-30, 1e-10, 1e-5, f32::MIN_POSITIVE]);
    for c in values {
        let want = reference::srgb_encode(f64::from(c));
        let got = f64::from(color::srgb_encode(c));
        err.update((got - want).abs(), || {
            format!("encode({c}) = {got}, want {want}")
        });
    }
    err.check(3e-7);
    // The standard's reference points: eq. 29's two branches meet at 0.0031308 -> 0.04045
    // (to 1e-6), and 1 encodes to 1.
    let knee = f64::from(color::srgb_encode(0.003_130_8));
    assert!((knee - 0.040_45).abs() < 1e-6, "encode(0.0031308) = {knee}");
    let one = f64::from(color::srgb_encode(1.0));
    assert!((one - 1.0).abs() < 1e-7, "encode(1) = {one}");
    // Decoding inverts eq. 29.
    let mut inverse = MaxError::new("sRGB decode(encode) relative round-trip error");
    for k in 1..=10_000 {
        let c = f64::from(k) / 10_000.0;
        let encoded = round(reference::srgb_encode(c));
        let back = f64::from(color::srgb_decode(encoded));
        // The exact inverse of eq. 29 at the f32 input.
        let e = f64::from(encoded);
        let want = if e <= 12.92 * 0.003_130_8 {
            e / 12.92
        } else {
            ((e + 0.055) / 1.055).powf(2.4)
        };
        inverse.update(relative(back, want), || {
            format!("decode({encoded}) = {back}, want {want}")
        });
    }
    inverse.check(1e-6);
}
