//! `sky-train bench`: nanoseconds per direction of each evaluator, single-threaded, with ratios
//! against peers measured in the same run (timings on a shared machine drift; ratios much less).

use std::hint::black_box;
use std::time::{Duration, Instant};

use anyhow::Result;
use sky_core::color::{self, Xyy};
use sky_core::geom::{Equirect, Extent};
use sky_core::preetham::PerezCoefficients;
use sky_core::sh::{PREETHAM, ShSky};
use sky_core::{PreethamSky, Sun, Vec3};

use crate::dispatch;

/// One measured evaluator.
#[derive(Debug, Clone)]
pub struct Measurement {
    /// What was measured.
    pub name: String,
    /// Median nanoseconds per direction.
    pub ns_per_direction: f64,
}

/// The directions of a `width` × `height` upper-hemisphere grid (seed 000 §IV-C times 1024 × 512
/// directions "around the hemisphere").
#[must_use]
pub fn hemisphere_directions(width: u32, height: u32) -> Vec<Vec3> {
    let Ok(grid) = Equirect::new(width, height, Extent::UpperHemisphere) else {
        return Vec::new();
    };
    (0..height)
        .flat_map(|j| (0..width).map(move |i| grid.direction(i, j)))
        .collect()
}

/// Runs `f` `runs` times after one warm-up run and returns the median duration.
fn median_time(runs: usize, mut f: impl FnMut()) -> Duration {
    f();
    let mut times: Vec<Duration> = (0..runs.max(1))
        .map(|_| {
            let start = Instant::now();
            f();
            start.elapsed()
        })
        .collect();
    times.sort();
    times[times.len() / 2]
}

#[allow(clippy::cast_precision_loss)]
fn per_direction(t: Duration, n: usize) -> f64 {
    t.as_secs_f64() * 1e9 / n.max(1) as f64
}

/// Measures every evaluator over `dirs`, `runs` times each.
///
/// # Errors
/// Never in practice: the benchmark's sky parameters are valid constants.
pub fn run(dirs: &[Vec3], runs: usize) -> Result<Vec<Measurement>> {
    let sky = PreethamSky::new(Sun::new(0.9, 0.3)?, 3.0)?;
    let peer = Straightforward::new(&sky);
    let mut results = Vec::new();
    // Times `eval` filling `out` from `dirs` and records it under `name`.
    let mut measure = |name: String, eval: &mut dyn FnMut(&[Vec3], &mut [Vec3])| {
        let mut out = vec![Vec3::ZERO; dirs.len()];
        let t = median_time(runs, || {
            eval(black_box(dirs), &mut out);
            black_box(&out);
        });
        results.push(Measurement {
            name,
            ns_per_direction: per_direction(t, dirs.len()),
        });
    };
    measure(
        "preetham, straightforward scalar peer".into(),
        &mut |d, o| {
            for (o, d) in o.iter_mut().zip(d) {
                *o = peer.rgb(*d);
            }
        },
    );
    measure("preetham rgb, one direction a call".into(), &mut |d, o| {
        for (o, d) in o.iter_mut().zip(d) {
            *o = sky.rgb(black_box(*d));
        }
    });
    let sh = ShSky::new(sky.sun(), sky.turbidity(), 7)?;
    measure(
        "sh radiance (7 bands), one direction".into(),
        &mut |d, o| {
            for (o, d) in o.iter_mut().zip(d) {
                *o = sh.radiance(black_box(*d));
            }
        },
    );
    measure("preetham rgb_batch (baseline SIMD)".into(), &mut |d, o| {
        sky.rgb_batch(d, o);
    });
    measure(
        format!("preetham rgb_batch ({})", dispatch::describe()),
        &mut |d, o| {
            dispatch::fastest(
                #[inline(always)]
                || sky.rgb_batch(d, o),
            );
        },
    );
    Ok(results)
}

/// The peer: eqs. 10-12 as one would first write them: the zenith normalisation Z / F(0, θs)
/// precomputed once per sky, then per direction γ = acos(v · s) and six `expf`, all libm.
struct Straightforward {
    sun: Vec3,
    perez: [PerezCoefficients; 3],
    factor: [f32; 3],
}

impl Straightforward {
    fn perez(p: &PerezCoefficients, cos_theta: f32, gamma: f32, cos_gamma: f32) -> f32 {
        (1.0 + p.a * libm::expf(p.b / cos_theta.max(1e-6)))
            * (1.0 + p.c * libm::expf(p.d * gamma) + p.e * cos_gamma * cos_gamma)
    }

    fn new(sky: &PreethamSky) -> Self {
        let sun = sky.sun();
        let perez = sky.perez_coefficients();
        let z = sky.zenith();
        let cos_s = libm::cosf(sun.zenith());
        let zenith = [z.luminance, z.x, z.y];
        let factor =
            std::array::from_fn(|c| zenith[c] / Self::perez(&perez[c], 1.0, sun.zenith(), cos_s));
        Self {
            sun: sun.direction(),
            perez,
            factor,
        }
    }

    fn rgb(&self, dir: Vec3) -> Vec3 {
        let cos_gamma = dir.dot(self.sun).clamp(-1.0, 1.0);
        let gamma = libm::acosf(cos_gamma);
        let v = |c: usize| self.factor[c] * Self::perez(&self.perez[c], dir.z, gamma, cos_gamma);
        let xyy = Xyy {
            luminance: v(0),
            x: v(1),
            y: v(2),
        };
        color::xyz_to_linear_srgb(color::xyy_to_xyz(xyy))
    }
}

/// Formats measurements as aligned lines, each with its ratio to the first.
#[must_use]
pub fn report(results: &[Measurement], width: u32, height: u32) -> String {
    let base = results.first().map_or(1.0, |m| m.ns_per_direction);
    let mut s = format!("{width}x{height} directions, single thread, median of runs\n");
    for m in results {
        s += &format!(
            "{:<40} {:>8.2} ns/direction  {:>6.2}x vs {}\n",
            m.name,
            m.ns_per_direction,
            base / m.ns_per_direction,
            results.first().map_or("", |m| m.name.as_str()),
        );
    }
    s
}

/// One measured SH reconstruction.
#[derive(Debug, Clone)]
pub struct ShMeasurement {
    /// What was measured.
    pub name: String,
    /// Median nanoseconds per `ShSky::new` (eq. 1 for every coefficient, filter, rotation).
    pub ns_per_sky: f64,
    /// Table bytes the reconstruction reads.
    pub table_bytes: usize,
}

/// Times `ShSky::new` for 1 to 7 bands (`runs` runs of 2000 skies over the whole domain).
///
/// # Errors
/// Never in practice: the parameters are valid constants.
#[allow(clippy::cast_precision_loss)]
pub fn sh_reconstruction(runs: usize) -> Result<Vec<ShMeasurement>> {
    const SKIES: usize = 2000;
    let params: Vec<(Sun, f32)> = (0..SKIES)
        .map(|k| {
            let f = k as f32 / SKIES as f32;
            Ok((Sun::new(1.57 * f, 6.0 * f)?, 2.5 + 3.5 * ((7.0 * f) % 1.0)))
        })
        .collect::<Result<_, sky_core::SkyError>>()?;
    let mut results = Vec::new();
    for bands in 1..=7 {
        let mut failed = false;
        let t = median_time(runs, || {
            for &(sun, t) in &params {
                failed |= black_box(ShSky::new(black_box(sun), black_box(t), bands)).is_err();
            }
        });
        anyhow::ensure!(!failed, "ShSky::new failed");
        results.push(ShMeasurement {
            name: format!(
                "sh ShSky::new, {bands} band{}",
                if bands == 1 { "" } else { "s" }
            ),
            ns_per_sky: t.as_secs_f64() * 1e9 / SKIES as f64,
            table_bytes: PREETHAM.bytes_for_bands(bands),
        });
    }
    // The same 7-band reconstruction compiled for the CPU's widest vectors (as the batch
    // evaluators run in `sky-train`).
    let mut failed = false;
    let t = median_time(runs, || {
        dispatch::fastest(
            #[inline(always)]
            || {
                for &(sun, t) in &params {
                    let sky = ShSky::from_table(&PREETHAM, black_box(sun), black_box(t), 7, true);
                    failed |= black_box(sky).is_err();
                }
            },
        );
    });
    anyhow::ensure!(!failed, "ShSky::from_table failed");
    results.push(ShMeasurement {
        name: format!("sh ShSky::new, 7 bands ({})", dispatch::describe()),
        ns_per_sky: t.as_secs_f64() * 1e9 / SKIES as f64,
        table_bytes: PREETHAM.bytes_for_bands(7),
    });
    Ok(results)
}

/// Formats SH measurements as aligned lines.
#[must_use]
pub fn sh_report(results: &[ShMeasurement]) -> String {
    let mut s = String::from(
        "sh reconstruction (ShSky::new: eq. 1, filter eq. 5, rotation eq. 4), median of runs\n",
    );
    for m in results {
        s += &format!(
            "{:<40} {:>8.1} ns/sky      table {:>6} bytes\n",
            m.name, m.ns_per_sky, m.table_bytes
        );
    }
    s
}
