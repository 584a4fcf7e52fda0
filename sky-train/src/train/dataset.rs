//! Training and test sets of the neural sky (seed 000 §III-D and §IV-A).

use rand::{Rng, SeedableRng};
use rayon::prelude::*;
use sky_core::Vec3;
use sky_core::color;
use sky_core::geom::{self, Equirect, Extent};

use crate::sources::{self, ModelKind, SkyParams};

/// One case's views (f64 unit vectors) and the model's radiance there.
type CaseSamples = (Vec<[f64; 3]>, Vec<Vec3>);

/// One sky of a data set: a model at one turbidity and sun zenith (sun azimuth π, as trained).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SkyCase {
    /// Turbidity.
    pub turbidity: f64,
    /// Sun zenith angle in radians.
    pub sun_zenith: f64,
}

/// Examples: network inputs V = {√t, θ_sun, v_x, v_y, v_z, d} (seed 000 §III-B), linear RGB
/// targets, and the case each came from.
#[derive(Debug, Clone, Default)]
pub struct DataSet {
    /// Inputs, one row per example.
    pub inputs: Vec<[f64; 6]>,
    /// Targets, linear RGB in the model's units.
    pub targets: Vec<[f64; 3]>,
    /// The index into `cases` of each example.
    pub case: Vec<usize>,
    /// The skies.
    pub cases: Vec<SkyCase>,
}

/// How training examples are drawn (seed 000 §III-D's choices are the defaults).
#[derive(Debug, Clone, PartialEq)]
pub struct Sampling {
    /// Turbidities of the training skies.
    pub turbidities: Vec<f64>,
    /// Number of sun zenith angles, uniform over [0, π/2] inclusive.
    pub sun_zeniths: usize,
    /// View strata in zenith angle over [0, π/2].
    pub view_zeniths: usize,
    /// View strata in azimuth over [0, 2π).
    pub view_azimuths: usize,
    /// Seed of the view jitter.
    pub seed: u64,
}

impl Sampling {
    /// Seed 000's sampling for `model`: its turbidity range in steps of 1 and its upper end
    /// (2..6 for Preetham, 1..10 for Hosek; 2.5, 3.5, 4.5, 5.5, 6 for the SH tables' 2.5..6),
    /// 20 sun zeniths, 10 × 20 stratified views.
    #[must_use]
    pub fn paper(model: ModelKind) -> Self {
        let (lo, hi) = model.turbidity_range();
        let mut turbidities: Vec<f64> = (0..=MAX_DEFAULT_TURBIDITIES)
            .map(|i| lo + f64::from(i))
            .take_while(|t| *t < hi)
            .collect();
        turbidities.push(hi);
        Self {
            turbidities,
            sun_zeniths: 20,
            view_zeniths: 10,
            view_azimuths: 20,
            seed: 1,
        }
    }
}

/// At most this many turbidities besides the upper end in [`Sampling::paper`] (`train`
/// refuses the one model without a finite range, `neural`, before sampling).
const MAX_DEFAULT_TURBIDITIES: u32 = 100;

/// `n` values uniform over [0, π/2], both ends included.
#[must_use]
pub fn sun_zeniths(n: usize) -> Vec<f64> {
    #[allow(clippy::cast_precision_loss)]
    (0..n)
        .map(|i| std::f64::consts::FRAC_PI_2 * i as f64 / (n.max(2) - 1) as f64)
        .collect()
}

/// The input vector V for a view `v` (unit) under a sun at zenith `theta_s` and azimuth π.
#[must_use]
pub fn input(turbidity: f64, theta_s: f64, v: [f64; 3]) -> [f64; 6] {
    let s = [-theta_s.sin(), 0.0, theta_s.cos()]; // azimuth π
    let d = ((v[0] - s[0]).powi(2) + (v[1] - s[1]).powi(2) + (v[2] - s[2]).powi(2)).sqrt();
    [turbidity.sqrt(), theta_s, v[0], v[1], v[2], d]
}

/// Evaluates `model` for `case` at `views` (unit vectors), sun azimuth π.
fn evaluate(model: ModelKind, case: SkyCase, views: &[Vec3]) -> anyhow::Result<Vec<Vec3>> {
    let source = sources::build(
        model,
        &SkyParams::for_model(model, case.sun_zenith.to_degrees(), 180.0, case.turbidity),
    )?;
    let mut out = vec![Vec3::ZERO; views.len()];
    source.rgb_batch(views, &mut out);
    Ok(out)
}

impl DataSet {
    /// Seed 000's training set: every turbidity × sun zenith of `sampling`, each with
    /// `view_zeniths × view_azimuths` views, one jittered view per stratum of (θ, φ) over the
    /// upper hemisphere.
    ///
    /// # Errors
    /// When the model rejects a case.
    pub fn training(model: ModelKind, sampling: &Sampling) -> anyhow::Result<Self> {
        let mut cases = Vec::new();
        for &t in &sampling.turbidities {
            for theta in sun_zeniths(sampling.sun_zeniths) {
                cases.push(SkyCase {
                    turbidity: t,
                    sun_zenith: theta,
                });
            }
        }
        let (nz, na) = (sampling.view_zeniths, sampling.view_azimuths);
        let per_case: Vec<anyhow::Result<CaseSamples>> = cases
            .par_iter()
            .enumerate()
            .map(|(k, &case)| {
                let mut rng = rand::rngs::StdRng::seed_from_u64(sampling.seed ^ (k as u64) << 20);
                let mut views = Vec::with_capacity(nz * na);
                for i in 0..nz {
                    for j in 0..na {
                        #[allow(clippy::cast_precision_loss)]
                        let theta = std::f64::consts::FRAC_PI_2 * (i as f64 + rng.random::<f64>())
                            / nz as f64;
                        #[allow(clippy::cast_precision_loss)]
                        let phi =
                            std::f64::consts::TAU * (j as f64 + rng.random::<f64>()) / na as f64;
                        views.push([
                            theta.sin() * phi.cos(),
                            theta.sin() * phi.sin(),
                            theta.cos(),
                        ]);
                    }
                }
                #[allow(clippy::cast_possible_truncation)]
                let dirs: Vec<Vec3> = views
                    .iter()
                    .map(|v| Vec3::new(v[0] as f32, v[1] as f32, v[2] as f32))
                    .collect();
                let rgb = evaluate(model, case, &dirs)?;
                Ok((views, rgb))
            })
            .collect();
        let mut set = Self {
            cases: cases.clone(),
            ..Self::default()
        };
        for (k, r) in per_case.into_iter().enumerate() {
            let (views, rgb) = r?;
            for (v, c) in views.iter().zip(rgb) {
                set.inputs
                    .push(input(cases[k].turbidity, cases[k].sun_zenith, *v));
                set.targets.push([c.x, c.y, c.z].map(f64::from));
                set.case.push(k);
            }
        }
        Ok(set)
    }
}

/// A test image: one sky over a hemisphere grid (seed 000 §IV-A: "test sets ... 7 sun
/// directions" per turbidity), with its reference radiance.
#[derive(Debug, Clone)]
pub struct TestImage {
    /// The sky.
    pub case: SkyCase,
    /// Reference linear RGB per grid direction.
    pub reference: Vec<Vec3>,
}

/// The view grid of the test images: the upper hemisphere, 128 × 32 pixel centres of an
/// equirectangular grid (azimuth × zenith, seed 002 eqs. 20-21).
///
/// # Panics
/// Never: the grid size is a valid constant.
#[must_use]
pub fn test_grid() -> Equirect {
    Equirect::new(128, 32, Extent::UpperHemisphere).unwrap_or_else(|_| unreachable!())
}

/// The directions of [`test_grid`], row by row, with the sun at azimuth `sun_azimuth`: the test
/// sun sits away from the training azimuth (π) so that the rotation of eq. 10 is exercised.
#[must_use]
pub fn test_directions() -> Vec<Vec3> {
    let grid = test_grid();
    (0..grid.height())
        .flat_map(|j| (0..grid.width()).map(move |i| grid.direction(i, j)))
        .collect()
}

/// The sun azimuth of the test images (radians), not the training azimuth π.
pub const TEST_SUN_AZIMUTH: f64 = 0.7;

/// Seed 000 §IV-A's test set for `model`: turbidities 2.5..5.5 (Preetham) or 1.5..9.5 (Hosek)
/// in steps of 1, each with 7 sun zeniths uniform over [0, π/2]; none is a training sky.
///
/// # Errors
/// When the model rejects a case.
pub fn paper_test_set(model: ModelKind) -> anyhow::Result<Vec<TestImage>> {
    if !model.uses_turbidity() {
        // One atmosphere: the 7 test sun zeniths, 5 of which are not training ones.
        return test_set(model, &[0.0], &sun_zeniths(7));
    }
    let (lo, hi) = model.turbidity_range();
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let n = (hi - lo).round() as u32;
    let turbidities: Vec<f64> = (0..n).map(|i| lo + 0.5 + f64::from(i)).collect();
    test_set(model, &turbidities, &sun_zeniths(7))
}

/// Seed 000's Table 1 (cross-validation NRMSE) and Table 2 (mean irradiance: reference,
/// network, absolute difference) for a model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PaperFigures {
    /// Table 1.
    pub nrmse: f64,
    /// Table 2: reference irradiance.
    pub irradiance_reference: f64,
    /// Table 2: network irradiance.
    pub irradiance_network: f64,
}

impl PaperFigures {
    /// The paper's figures for `model`, if it reports any.
    #[must_use]
    pub fn of(model: ModelKind) -> Option<Self> {
        match model {
            ModelKind::Preetham => Some(Self {
                nrmse: 0.0145,
                irradiance_reference: 0.11665,
                irradiance_network: 0.11695,
            }),
            ModelKind::Hosek => Some(Self {
                nrmse: 0.0395,
                irradiance_reference: 0.03671,
                irradiance_network: 0.03838,
            }),
            _ => None,
        }
    }

    /// The relative irradiance difference of Table 2.
    #[must_use]
    pub fn irradiance_relative(&self) -> f64 {
        (self.irradiance_network - self.irradiance_reference).abs() / self.irradiance_reference
    }
}

/// Test images for every turbidity × sun zenith given.
///
/// # Errors
/// When the model rejects a case.
pub fn test_set(
    model: ModelKind,
    turbidities: &[f64],
    sun_zeniths: &[f64],
) -> anyhow::Result<Vec<TestImage>> {
    let dirs = test_directions();
    let mut cases = Vec::new();
    for &t in turbidities {
        for &z in sun_zeniths {
            cases.push(SkyCase {
                turbidity: t,
                sun_zenith: z,
            });
        }
    }
    cases
        .par_iter()
        .map(|&case| {
            let source = sources::build(
                model,
                &SkyParams::for_model(
                    model,
                    case.sun_zenith.to_degrees(),
                    TEST_SUN_AZIMUTH.to_degrees(),
                    case.turbidity,
                ),
            )?;
            let mut reference = vec![Vec3::ZERO; dirs.len()];
            source.rgb_batch(&dirs, &mut reference);
            Ok(TestImage { case, reference })
        })
        .collect()
}

/// Normalised RMSE of one image (seed 000 §IV-A): the RMSE over all directions and the three
/// linear RGB channels, divided by (max − min) of the reference over the same values.
#[must_use]
pub fn nrmse(reference: &[Vec3], predicted: &[Vec3]) -> f64 {
    let (mut sum, mut n) = (0.0f64, 0usize);
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for (r, p) in reference.iter().zip(predicted) {
        for c in 0..3 {
            let (r, p) = (f64::from(r[c]), f64::from(p[c]));
            sum += (p - r) * (p - r);
            n += 1;
            lo = lo.min(r);
            hi = hi.max(r);
        }
    }
    #[allow(clippy::cast_precision_loss)]
    let rmse = (sum / n.max(1) as f64).sqrt();
    if hi > lo { rmse / (hi - lo) } else { rmse }
}

/// Irradiance of an image on the [`test_grid`] (seed 000 eq. 11): ∫ L(ω) cos θ dω over the
/// upper hemisphere, by the midpoint rule on the grid's cells (exact solid angles), applied to
/// the luminance of the linear RGB radiance.
#[must_use]
pub fn irradiance(image: &[Vec3]) -> f64 {
    let grid = test_grid();
    let w = grid.width() as usize;
    let mut sum = 0.0;
    for (j, row) in image.chunks(w).enumerate() {
        let j = u32::try_from(j).unwrap_or(u32::MAX);
        let cos_theta = f64::from(geom::direction(grid.zenith(j), 0.0).z);
        let weight = f64::from(grid.solid_angle(j)) * cos_theta;
        sum += weight
            * row
                .iter()
                .map(|p| f64::from(color::luminance(*p)))
                .sum::<f64>();
    }
    sum
}
