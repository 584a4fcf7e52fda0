//! `sky-train bench`: nanoseconds per direction of each evaluator, single-threaded, with ratios
//! against peers measured in the same run (timings on a shared machine drift; ratios much less).

use std::hint::black_box;
use std::time::{Duration, Instant};

use anyhow::Result;
use sky_core::aoas::{AoasSky, Preset, Scattering, Style};
use sky_core::color::{self, Xyy};
use sky_core::geom::{Equirect, Extent};
use sky_core::neural::{FixedNeuralSky, NeuralSky, fixed, pretrained};
use sky_core::preetham::PerezCoefficients;
use sky_core::sh::{PREETHAM, ShSky};
use sky_core::{PreethamSky, Sun, Vec3};

use crate::dispatch;
use crate::planckian;
use crate::reference::aoas::{Quadrature, SingleScattering};

/// One measured evaluator.
#[derive(Debug, Clone)]
pub struct Measurement {
    /// What was measured.
    pub name: String,
    /// Median nanoseconds per direction.
    pub ns_per_direction: f64,
    /// The index (in the same run's results) of the peer its ratio is taken against.
    pub peer: usize,
    /// A second peer measured in the same run, whose ratio is printed too (the daylight sky's
    /// lines: the neural 6-12-3 sky on the same instruction set).
    pub also: Option<usize>,
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
pub(crate) fn per_direction(t: Duration, n: usize) -> f64 {
    t.as_secs_f64() * 1e9 / n.max(1) as f64
}

/// Measures every evaluator over `dirs`, `runs` times each.
///
/// # Errors
/// Never in practice: the benchmark's sky parameters are valid constants.
pub fn run(dirs: &[Vec3], runs: usize) -> Result<Vec<Measurement>> {
    let mut results = Vec::new();
    preetham(dirs, runs, &mut results)?;
    neural(dirs, runs, &mut results)?;
    daylight(dirs, runs, &mut results)?;
    aoas(dirs, runs, &mut results)?;
    Ok(results)
}

/// Times `eval` filling an output from `dirs` (every `stride`-th direction) and records it under
/// `name` with the ratio against `peer` (an index into `results`; `None`: itself).
fn measure(
    results: &mut Vec<Measurement>,
    dirs: &[Vec3],
    stride: usize,
    runs: usize,
    name: String,
    peer: Option<usize>,
    eval: &mut dyn FnMut(&[Vec3], &mut [Vec3]),
) -> usize {
    let dirs: Vec<Vec3> = dirs.iter().step_by(stride.max(1)).copied().collect();
    let mut out = vec![Vec3::ZERO; dirs.len()];
    let t = median_time(runs, || {
        eval(black_box(&dirs), &mut out);
        black_box(&out);
    });
    let index = results.len();
    results.push(Measurement {
        name,
        ns_per_direction: per_direction(t, dirs.len()),
        peer: peer.unwrap_or(index),
        also: None,
    });
    index
}

fn preetham(dirs: &[Vec3], runs: usize, results: &mut Vec<Measurement>) -> Result<()> {
    let sky = PreethamSky::new(Sun::new(0.9, 0.3)?, 3.0)?;
    let straightforward = Straightforward::new(&sky);
    let mut m = |name: &str, peer, eval: &mut dyn FnMut(&[Vec3], &mut [Vec3])| {
        measure(results, dirs, 1, runs, name.to_owned(), peer, eval)
    };
    let peer = m(
        "preetham, straightforward scalar peer",
        None,
        &mut |d, o| {
            for (o, d) in o.iter_mut().zip(d) {
                *o = straightforward.rgb(*d);
            }
        },
    );
    m(
        "preetham rgb, one direction a call",
        Some(peer),
        &mut |d, o| {
            for (o, d) in o.iter_mut().zip(d) {
                *o = sky.rgb(black_box(*d));
            }
        },
    );
    let sh = ShSky::new(sky.sun(), sky.turbidity(), 7)?;
    m(
        "sh radiance (7 bands), one direction a call",
        Some(peer),
        &mut |d, o| {
            for (o, d) in o.iter_mut().zip(d) {
                *o = sh.radiance(black_box(*d));
            }
        },
    );
    m(
        "preetham rgb_batch (baseline SIMD)",
        Some(peer),
        &mut |d, o| {
            sky.rgb_batch(d, o);
        },
    );
    m(
        &format!("preetham rgb_batch ({})", dispatch::describe()),
        Some(peer),
        &mut |d, o| {
            dispatch::fastest(
                #[inline(always)]
                || sky.rgb_batch(d, o),
            );
        },
    );
    Ok(())
}

/// The neural sky against the Hosek-Wilkie sky of the `hw-skymodel` crate (seed 000 §IV-C
/// compares it with Hosek and Preetham in the same way).
fn neural(dirs: &[Vec3], runs: usize, results: &mut Vec<Measurement>) -> Result<()> {
    let hosek = crate::sources::Hosek::new(&crate::sources::SkyParams::sun_and_turbidity(
        f64::from(0.9f32.to_degrees()),
        17.0,
        3.0,
    ))
    .map_err(|e| anyhow::anyhow!("{e}"))?;
    let sky = NeuralSky::new(&pretrained::PREETHAM, Sun::new(0.9, 0.3)?, 3.0)?;
    let mut m = |name: &str, peer, eval: &mut dyn FnMut(&[Vec3], &mut [Vec3])| {
        measure(results, dirs, 1, runs, name.to_owned(), peer, eval)
    };
    let peer = m(
        "hosek-wilkie (hw-skymodel crate) peer",
        None,
        &mut |d, o| {
            for (o, d) in o.iter_mut().zip(d) {
                *o = hosek.rgb(*d);
            }
        },
    );
    let scalar = m(
        "neural 6-12-3 rgb, one direction a call",
        Some(peer),
        &mut |d, o| {
            for (o, d) in o.iter_mut().zip(d) {
                *o = sky.rgb(black_box(*d));
            }
        },
    );
    // The fixed-point sky, against the f32 one a direction at a time: integer directions are
    // made before timing, as firmware would hold them.
    let fixed_sky = FixedNeuralSky::new(&pretrained::PREETHAM_FIXED, Sun::new(0.9, 0.3)?, 3.0)?;
    let fixed_dirs: Vec<[i16; 3]> = dirs.iter().map(|&d| fixed::direction_q15(d)).collect();
    m(
        "neural fixed point (Q7.24, integer only) rgb",
        Some(scalar),
        &mut |_, o| {
            for (o, d) in o.iter_mut().zip(&fixed_dirs) {
                let [r, g, b] = fixed_sky.rgb(black_box(*d));
                #[allow(clippy::cast_precision_loss)] // kept only so the work is not dropped
                {
                    *o = Vec3::new(r as f32, g as f32, b as f32);
                }
            }
        },
    );
    m(
        "neural 6-12-3 rgb_batch (baseline SIMD)",
        Some(peer),
        &mut |d, o| sky.rgb_batch(d, o),
    );
    m(
        &format!("neural 6-12-3 rgb_batch ({})", dispatch::describe()),
        Some(peer),
        &mut |d, o| {
            dispatch::fastest(
                #[inline(always)]
                || sky.rgb_batch(d, o),
            );
        },
    );
    if dispatch::has_avx2_fma() {
        m(
            "neural 6-12-3 rgb_batch_avx2 (AVX2 + FMA)",
            Some(peer),
            &mut |d, o| dispatch::neural_batch(&sky, d, o),
        );
    }
    Ok(())
}

/// The daylight sky (three 6-24-3 networks, two mixed inside the blends) for a sun outside the
/// blends (50° high) and inside the day-to-dusk one (2° high): one direction a call
/// (the peer), the portable batch and the AVX2 + FMA kernel, each also against the neural 6-12-3
/// sky's line for the same instruction set measured just before.
fn daylight(dirs: &[Vec3], runs: usize, results: &mut Vec<Measurement>) -> Result<()> {
    use sky_core::daylight::Daylight;
    let neural = |name: &str| results.iter().position(|m| m.name == name);
    let peers = [
        neural("neural 6-12-3 rgb, one direction a call"),
        neural("neural 6-12-3 rgb_batch (baseline SIMD)"),
        neural(&format!(
            "neural 6-12-3 rgb_batch ({})",
            dispatch::describe()
        )),
        neural("neural 6-12-3 rgb_batch_avx2 (AVX2 + FMA)"),
    ];
    for (what, zenith) in [("sun 50° up", 40f32), ("sun 2° up, blend", 88.0)] {
        let sky = Daylight::new(Sun::new(zenith.to_radians(), 0.3)?, 0.2)?.sky();
        let mut m = |name: String, peer, also, eval: &mut dyn FnMut(&[Vec3], &mut [Vec3])| {
            let i = measure(results, dirs, 1, runs, name, peer, eval);
            results[i].also = also;
            i
        };
        let one = m(
            format!("daylight rgb, one a call, {what}"),
            None,
            peers[0],
            &mut |d, o| {
                for (o, d) in o.iter_mut().zip(d) {
                    *o = sky.rgb(black_box(*d));
                }
            },
        );
        m(
            format!("daylight rgb_batch (baseline SIMD), {what}"),
            Some(one),
            peers[1],
            &mut |d, o| sky.rgb_batch(d, o),
        );
        m(
            format!("daylight rgb_batch ({}), {what}", dispatch::describe()),
            Some(one),
            peers[2],
            &mut |d, o| {
                dispatch::fastest(
                    #[inline(always)]
                    || sky.rgb_batch(d, o),
                );
            },
        );
        if dispatch::has_avx2_fma() {
            m(
                format!("daylight rgb_batch_avx2 (AVX2+FMA), {what}"),
                Some(one),
                peers[3],
                &mut |d, o| dispatch::daylight_batch(&sky, d, o),
            );
        }
    }
    Ok(())
}

/// AOAS: the f64 references as peers of the physical preset, and the physical preset as the
/// peer of each style principle turned on alone (the extra cost of the principle).
fn aoas(dirs: &[Vec3], runs: usize, results: &mut Vec<Measurement>) -> Result<()> {
    let scattering = Scattering::default();
    let physical = AoasSky::new(&scattering, &Style::preset(Preset::Physical))?;
    let samples = scattering.samples;
    let sun = physical.sun().direction();
    let reference = SingleScattering::o_neil_defaults([sun.x, sun.y, sun.z].map(f64::from));
    let to_f32 = |c: [f64; 3]| {
        #[allow(clippy::cast_possible_truncation)]
        Vec3::new(c[0] as f32, c[1] as f32, c[2] as f32)
    };
    let exact = measure(
        results,
        dirs,
        256,
        runs.min(3),
        "aoas exact integral, f64 (1/256 of dirs)".into(),
        None,
        &mut |d, o| {
            for (o, d) in o.iter_mut().zip(d) {
                let v = [d.x, d.y, d.z].map(f64::from);
                *o = to_f32(reference.exact(v, Quadrature::FINE));
            }
        },
    );
    let o_neil = measure(
        results,
        dirs,
        16,
        runs,
        format!("aoas O'Neil {samples} samples, f64 scalar peer"),
        Some(exact),
        &mut |d, o| {
            for (o, d) in o.iter_mut().zip(d) {
                let v = [d.x, d.y, d.z].map(f64::from);
                *o = to_f32(reference.o_neil(v, samples as usize));
            }
        },
    );
    let mut m = |name: String, peer, eval: &mut dyn FnMut(&[Vec3], &mut [Vec3])| {
        measure(results, dirs, 1, runs, name, Some(peer), eval)
    };
    m(
        "aoas physical rgb, one direction a call".into(),
        o_neil,
        &mut |d, o| {
            for (o, d) in o.iter_mut().zip(d) {
                *o = physical.rgb(black_box(*d));
            }
        },
    );
    m(
        "aoas physical rgb_batch (baseline SIMD)".into(),
        o_neil,
        &mut |d, o| physical.rgb_batch(d, o),
    );
    let lanes = dispatch::describe();
    let base = m(
        format!("aoas physical rgb_batch ({lanes})"),
        o_neil,
        &mut |d, o| {
            dispatch::fastest(
                #[inline(always)]
                || physical.rgb_batch(d, o),
            );
        },
    );
    let physical_style = Style::preset(Preset::Physical);
    let principles = [
        (
            "ambiguity",
            Style {
                ambiguity: Preset::Ambiguous.style().ambiguity,
                ..physical_style.clone()
            },
        ),
        (
            "cloud noise",
            Style {
                cloud_noise: Preset::Turbulent.style().cloud_noise,
                ..physical_style.clone()
            },
        ),
        (
            "cloud shapes (smiley)",
            Style {
                cloud_shapes: Preset::Smiley.style().cloud_shapes,
                ..physical_style.clone()
            },
        ),
        (
            "sky hue (coral)",
            Style {
                sky_hue: Preset::Coral.style().sky_hue,
                ..physical_style.clone()
            },
        ),
        (
            "day cycle (sunset)",
            Style {
                day_cycle: Preset::Sunset.style().day_cycle,
                ..physical_style.clone()
            },
        ),
    ];
    for (what, style) in principles {
        let sky = AoasSky::new(&scattering, &style)?;
        m(format!("aoas + {what} ({lanes})"), base, &mut |d, o| {
            dispatch::fastest(
                #[inline(always)]
                || sky.rgb_batch(d, o),
            );
        });
    }
    Ok(())
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

/// Formats measurements as aligned lines, each with its ratio to its peer (and, for a style
/// principle, its extra nanoseconds over the physical sky).
#[must_use]
pub fn report(results: &[Measurement], width: u32, height: u32) -> String {
    let mut s = format!("{width}x{height} directions, single thread, median of runs\n");
    for m in results {
        let peer = results.get(m.peer).unwrap_or(m);
        // A style principle's line: its extra cost over the physical sky.
        let extra = if m.name.starts_with("aoas +") {
            format!(" ({:+.2} ns)", m.ns_per_direction - peer.ns_per_direction)
        } else {
            String::new()
        };
        // A daylight line: its ratio to the neural 6-12-3 sky too.
        let also = m
            .also
            .and_then(|i| results.get(i))
            .map_or(String::new(), |n| {
                format!(
                    "; {:.2}x vs {}",
                    n.ns_per_direction / m.ns_per_direction,
                    n.name
                )
            });
        s += &format!(
            "{:<52} {:>10.2} ns/direction  {:>7.2}x vs {}{extra}{also}\n",
            m.name,
            m.ns_per_direction,
            peer.ns_per_direction / m.ns_per_direction,
            peer.name,
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

/// One measured CCT method.
#[derive(Debug, Clone)]
pub struct CctMeasurement {
    /// What was measured.
    pub name: String,
    /// Median nanoseconds per call.
    pub ns_per_call: f64,
}

/// Times CCT and Duv of 500 chromaticities along and off the Planckian locus (1,000-100,000 K
/// in 50 log steps, Duv −0.05 to 0.05 in 10 steps) by the exact minimisation (f64, the locus
/// summed at every step: [`planckian::exact_cct_duv`], the peer, `runs` up to 5) and by
/// sky-core's table method (`cct::cct_duv`, f32), after checking that the two agree within
/// 0.15 K below 10,000 K and 0.01 % above.
///
/// # Errors
/// If either method finds no CCT, or they disagree.
pub fn cct(runs: usize) -> Result<Vec<CctMeasurement>> {
    let inputs: Vec<(f32, f32)> = (0..50)
        .flat_map(|i| {
            let kelvin = 1001.0 * 99.8f64.powf(f64::from(i) / 49.0);
            (0..10).map(move |j| planckian::off_locus(kelvin, -0.05 + f64::from(j) / 90.0))
        })
        .map(|(x, y)| {
            #[allow(clippy::cast_possible_truncation)]
            (x as f32, y as f32)
        })
        .collect();
    for &(x, y) in &inputs {
        let exact = planckian::exact_cct_duv(f64::from(x), f64::from(y));
        let table = sky_core::cct::cct_duv(x, y);
        let (Some((want, _)), Ok(got)) = (exact, table) else {
            anyhow::bail!("no CCT for ({x}, {y})");
        };
        let bound = if want < 10_000.0 { 0.15 } else { 1e-4 * want };
        anyhow::ensure!(
            (f64::from(got.kelvin) - want).abs() <= bound,
            "({x}, {y}): {got:?} vs {want} K"
        );
    }
    let mut failed = false;
    let exact = median_time(runs.min(5), || {
        for &(x, y) in &inputs {
            let (x, y) = black_box((f64::from(x), f64::from(y)));
            failed |= black_box(planckian::exact_cct_duv(x, y)).is_none();
        }
    });
    let table = median_time(runs, || {
        for &(x, y) in &inputs {
            failed |= black_box(sky_core::cct::cct_duv(black_box(x), black_box(y))).is_err();
        }
    });
    anyhow::ensure!(!failed, "a CCT failed");
    #[allow(clippy::cast_precision_loss)]
    let per_call = |t: Duration| t.as_secs_f64() * 1e9 / inputs.len() as f64;
    Ok(vec![
        CctMeasurement {
            name: "cct exact minimisation (f64) peer".into(),
            ns_per_call: per_call(exact),
        },
        CctMeasurement {
            name: "cct_duv (locus table, Newton; f32)".into(),
            ns_per_call: per_call(table),
        },
    ])
}

/// Formats CCT measurements as aligned lines, each with its speed-up over the first (the
/// exact minimisation).
#[must_use]
pub fn cct_report(results: &[CctMeasurement]) -> String {
    let mut s = String::from(
        "cct and duv of 500 chromaticities, 1,000-100,000 K, |Duv| <= 0.05, median of runs\n",
    );
    if let Some(peer) = results.first() {
        for m in results {
            s += &format!(
                "{:<52} {:>10.1} ns/call       {:>7.1}x vs {}\n",
                m.name,
                m.ns_per_call,
                peer.ns_per_call / m.ns_per_call,
                peer.name,
            );
        }
    }
    s
}

/// The physical atmosphere's costs: its precomputation (wall time on all cores, against the
/// 60 s budget, with the machine's load average beside it), the sky of one sun position, and
/// the radiance per direction (against the straightforward Preetham peer of the same run,
/// `results[0]`, when given).
///
/// # Errors
/// When the default atmosphere cannot be built.
pub fn physical(dirs: &[Vec3], runs: usize, results: &[Measurement]) -> Result<String> {
    use crate::physical::{Atmosphere, PhysicalAtmosphere, Resolution};
    let load = || {
        crate::csv_input::read_text(std::path::Path::new("/proc/loadavg"), "/proc/loadavg", 4096)
            .ok()
            .and_then(|s| s.split_whitespace().next().map(str::to_owned))
            .unwrap_or_else(|| "?".into())
    };
    let (load_before, start) = (load(), Instant::now());
    let atm = std::sync::Arc::new(PhysicalAtmosphere::build(
        &Atmosphere::default(),
        &Resolution::default(),
        &indicatif::ProgressBar::hidden(),
    )?);
    let seconds = start.elapsed().as_secs_f64();
    let mut s = format!(
        "physical precompute (default atmosphere, {} threads, {} orders) {seconds:>8.1} s wall  {:>7.2}x vs the 60 s budget (load average {load_before} before, {} after, on {} cores)\n",
        rayon::current_num_threads(),
        atm.ground.orders.len(),
        60.0 / seconds,
        load(),
        std::thread::available_parallelism().map_or(0, std::num::NonZero::get),
    );
    let t = median_time(runs, || {
        black_box(atm.sky(black_box(51.6), 17.2).ok());
    });
    s += &format!(
        "{:<52} {:>10.2} us/sky\n",
        "physical sky (one sun position)",
        t.as_secs_f64() * 1e6
    );
    let sky = atm.sky(51.6, 17.2)?;
    let v = |d: &Vec3| [f64::from(d.x), f64::from(d.y), f64::from(d.z)];
    let mut sum = 0.0;
    let fast = median_time(runs, || {
        for d in black_box(dirs) {
            sum += sky.radiance_xyzm(v(d))[1];
        }
        black_box(sum);
    });
    let sparse: Vec<Vec3> = dirs.iter().step_by(16).copied().collect();
    let spectral = median_time(runs, || {
        for d in black_box(&sparse) {
            sum += sky.spectral_radiance(v(d))[20];
        }
        black_box(sum);
    });
    let own = [
        (
            "physical radiance_xyzm, one direction a call",
            per_direction(fast, dirs.len()),
        ),
        (
            "physical spectral_radiance (47 bins), one a call",
            per_direction(spectral, sparse.len()),
        ),
    ];
    for (name, ns) in own {
        let peer = results.first();
        let ratio = peer.map_or(String::new(), |p| {
            format!("  {:>7.2}x vs {}", p.ns_per_direction / ns, p.name)
        });
        s += &format!("{name:<52} {ns:>10.2} ns/direction{ratio}\n");
    }
    Ok(s)
}
