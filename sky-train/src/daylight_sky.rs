//! The neural skies of sky-core's daylight (`sky_core::daylight`): three 6-H-3 networks (seed
//! 000), for the day (sun zenith 0° to 90°), dusk (84° to 98°) and night (94° to 108°), trained
//! with the project's trainer ([`crate::train`]) on the physical atmosphere's sky radiance over
//! the aerosol optical depths of [`crate::daylight_tables::AOD_NODES`]. Fewer networks over the
//! same range missed the bound (NRMSE 0.02 per image), docs/daylight.md.
//!
//! The network learns the sky's **shape**, not its brightness, which spans eight orders of
//! magnitude from noon to the end of twilight: each channel's target is the radiance over the
//! diffuse horizontal illuminance of the same channel, π L_c(ω) / E_d,c (so a uniform sky is 1
//! everywhere and the cosine-weighted integral of every channel is π). The channels are CIE
//! X, Y, Z rather than linear sRGB, since the twilight sky leaves the sRGB gamut. The network's
//! "turbidity" input √t carries √τ₅₅₀ (the aerosol optical depth at 550 nm). sky-core
//! multiplies the output by its diffuse table's E_d,c / π.

use std::sync::Arc;

use anyhow::Result;
use rand::{Rng, SeedableRng};
use rayon::prelude::*;
use sky_core::Vec3;

use crate::physical::{PhysicalAtmosphere, PhysicalSky};
use crate::train::dataset::{self, DataSet, SkyCase, TestImage};

/// The largest sun zenith angle trained on, degrees (the sun 18° below the horizon).
pub const MAX_SUN_ZENITH_DEG: f64 = 108.0;

/// Which of the two networks.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Part {
    /// Sun zenith 0° to 90°.
    Day,
    /// Sun zenith 84° to 98° (6° above the horizon to 8° below it: sunset and civil twilight).
    Dusk,
    /// Sun zenith 94° to 108° (nautical and astronomical twilight).
    Night,
}

impl Part {
    /// The sun zenith angles trained on, degrees (both ends included).
    #[must_use]
    pub fn zenith_range(self) -> (f64, f64) {
        match self {
            Self::Day => (0.0, 90.0),
            Self::Dusk => (84.0, 98.0),
            Self::Night => (94.0, MAX_SUN_ZENITH_DEG),
        }
    }

    /// The number of training sun zeniths over [`Self::zenith_range`] the shipped networks were
    /// trained with (2.5° apart by day, 0.5° at dusk, 1° at night).
    #[must_use]
    pub fn sun_zeniths(self) -> usize {
        match self {
            Self::Day => 37,
            Self::Dusk => 29,
            Self::Night => 15,
        }
    }

    /// The source name written into the weight file.
    #[must_use]
    pub fn source(self) -> &'static str {
        match self {
            Self::Day => "physical day, XYZ / diffuse",
            Self::Dusk => "physical dusk, XYZ / diffuse",
            Self::Night => "physical night, XYZ / diffuse",
        }
    }
}

/// One training example: a view direction and its normalised X, Y, Z.
type Example = ([f64; 3], [f64; 3]);

/// One atmosphere of the data set: its aerosol optical depth and tables.
pub type Atmospheres = [(f64, Arc<PhysicalAtmosphere>)];

/// The normalised X, Y, Z of `sky` towards unit `dir`, π L_c / E_d,c (module docs).
fn normalised(sky: &PhysicalSky, scale: &[f64; 3], dir: [f64; 3]) -> [f64; 3] {
    let c = sky.radiance_xyzm(dir);
    std::array::from_fn(|k| c[k] * scale[k])
}

/// π / E_d,c of `sky`'s diffuse horizontal illuminance.
fn scale_of(sky: &PhysicalSky) -> [f64; 3] {
    let e = sky.daylight().diffuse.xyz;
    e.map(|v| std::f64::consts::PI / v.max(f64::MIN_POSITIVE))
}

/// The training set: every atmosphere × sun zenith (degrees, sun azimuth π as trained), each
/// with `strata.0 × strata.1` views jittered in their (θ, φ) strata over the upper hemisphere.
///
/// # Errors
/// For a sun zenith the reference refuses.
pub fn training_set(
    atmospheres: &Atmospheres,
    zeniths_deg: &[f64],
    strata: (usize, usize),
    seed: u64,
) -> Result<DataSet> {
    let cases: Vec<(usize, f64)> = (0..atmospheres.len())
        .flat_map(|a| zeniths_deg.iter().map(move |&z| (a, z)))
        .collect();
    let (nz, na) = strata;
    let per_case: Vec<Result<Vec<Example>>> = cases
        .par_iter()
        .enumerate()
        .map(|(k, &(a, z))| {
            let sky = atmospheres[a].1.sky(z, 180.0)?;
            let scale = scale_of(&sky);
            let mut rng = rand::rngs::StdRng::seed_from_u64(seed ^ ((k as u64) << 20));
            let mut out = Vec::with_capacity(nz * na);
            for i in 0..nz {
                for j in 0..na {
                    #[allow(clippy::cast_precision_loss)]
                    let theta =
                        std::f64::consts::FRAC_PI_2 * (i as f64 + rng.random::<f64>()) / nz as f64;
                    #[allow(clippy::cast_precision_loss)]
                    let phi = std::f64::consts::TAU * (j as f64 + rng.random::<f64>()) / na as f64;
                    let v = [
                        theta.sin() * phi.cos(),
                        theta.sin() * phi.sin(),
                        theta.cos(),
                    ];
                    out.push((v, normalised(&sky, &scale, v)));
                }
            }
            Ok(out)
        })
        .collect();
    let mut set = DataSet::default();
    for (k, samples) in per_case.into_iter().enumerate() {
        let (a, z) = cases[k];
        let case = SkyCase {
            turbidity: atmospheres[a].0,
            sun_zenith: z.to_radians(),
        };
        set.cases.push(case);
        for (v, t) in samples? {
            set.inputs
                .push(dataset::input(case.turbidity, case.sun_zenith, v));
            set.targets.push(t);
            set.case.push(k);
        }
    }
    Ok(set)
}

/// Images of the normalised reference on [`dataset::test_directions`] with the sun at
/// [`dataset::TEST_SUN_AZIMUTH`], for every atmosphere × sun zenith (degrees).
///
/// # Errors
/// For a sun zenith the reference refuses.
pub fn images(atmospheres: &Atmospheres, zeniths_deg: &[f64]) -> Result<Vec<TestImage>> {
    let dirs = dataset::test_directions();
    let cases: Vec<(usize, f64)> = (0..atmospheres.len())
        .flat_map(|a| zeniths_deg.iter().map(move |&z| (a, z)))
        .collect();
    cases
        .par_iter()
        .map(|&(a, z)| {
            let sky = atmospheres[a]
                .1
                .sky(z, dataset::TEST_SUN_AZIMUTH.to_degrees())?;
            let scale = scale_of(&sky);
            #[allow(clippy::cast_possible_truncation)]
            let reference = dirs
                .iter()
                .map(|d| {
                    let v = [d.x, d.y, d.z].map(f64::from);
                    Vec3::from_array(normalised(&sky, &scale, v).map(|x| x as f32))
                })
                .collect();
            Ok(TestImage {
                case: SkyCase {
                    turbidity: atmospheres[a].0,
                    sun_zenith: z.to_radians(),
                },
                reference,
            })
        })
        .collect()
}

/// `n` sun zenith angles uniform over `part`'s range, both ends included, degrees.
#[must_use]
pub fn zeniths(part: Part, n: usize) -> Vec<f64> {
    let (lo, hi) = part.zenith_range();
    #[allow(clippy::cast_precision_loss)]
    (0..n)
        .map(|i| lo + (hi - lo) * i as f64 / (n.max(2) - 1) as f64)
        .collect()
}
