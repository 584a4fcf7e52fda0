//! Capture-like test sequences, since no captured sequence can be downloaded here: the
//! Hosek-Wilkie sky (hw-skymodel, ground albedo 0.5) at a site and date every few minutes, the
//! sun from the time and place (NREL SPA), as a real camera would record it:
//!
//! * **exposure** varying between frames: pixel values are radiance × exposure, the exposure
//!   chosen so the sky's brightest point sits near 5 % of the sensor's clip level, times a random
//!   2^±0.5; the manifest records it (as EXIF data would), and the loader divides it out;
//! * **sensor noise**: Gaussian, variance a·v + b² in camera units (shot and read noise, about
//!   1 % of the sky's level);
//! * a **clipped sun**: the disc and its lens glare, a Gaussian of σ = 1° peaking at 1000 times
//!   the sky's brightest point, integrated over each pixel and clipped at 1.0 like every
//!   channel;
//! * a **skyline**: a dark silhouette of hills and buildings up to 8° high, fixed in the world;
//! * a slight **camera-azimuth offset**: each frame's camera turned by a random ±2°.
//!
//! The manifest gives the site, each frame's time and exposure; the ground truth of a frame is
//! exactly the Hosek-Wilkie sky for its time (the tests compute it independently).

use std::f64::consts::{PI, TAU};
use std::fmt::Write as _;
use std::path::Path;

use anyhow::{Context, Result};
use rand::{Rng, SeedableRng};
use rayon::prelude::*;
use sky_core::Vec3;
use sky_core::geom::{self, Equirect, Extent};

use super::manifest::{MANIFEST, UnixTime};
use crate::args::ParamError;
use crate::image_io::{self, RgbImage};
use crate::sources::{self, ModelKind, SkyParams};

/// What to synthesize.
#[derive(Debug, Clone, PartialEq)]
pub struct SynthConfig {
    /// Latitude, degrees north.
    pub latitude: f64,
    /// Longitude, degrees east.
    pub longitude: f64,
    /// The UTC date.
    pub date: (i32, u32, u32),
    /// First frame, minutes after 00:00 UTC (default: the first step with the sun high enough).
    pub start_minutes: Option<u32>,
    /// Number of frames (default: every step while the sun is high enough).
    pub frames: Option<usize>,
    /// Minutes between frames.
    pub step_minutes: u32,
    /// Frame width in pixels (height = width / 2).
    pub width: usize,
    /// Hosek-Wilkie turbidity (1 to 10).
    pub turbidity: f64,
    /// The lowest sun elevation of a frame, degrees (the skyline reaches 8°).
    pub min_elevation_deg: f64,
    /// Seed of the exposure, noise, skyline and camera offsets.
    pub seed: u64,
}

impl Default for SynthConfig {
    /// Vienna (48.21° N, 16.37° E) on the 2026 June solstice, every 15 minutes, 1024 × 512.
    fn default() -> Self {
        Self {
            latitude: 48.21,
            longitude: 16.37,
            date: (2026, 6, 21),
            start_minutes: None,
            frames: None,
            step_minutes: 15,
            width: 1024,
            turbidity: 3.0,
            min_elevation_deg: 12.0,
            seed: 1,
        }
    }
}

/// The sensor's clip level in camera units.
const CLIP: f32 = 1.0;
/// Camera-azimuth offset of a frame: uniform in ±this, degrees.
const CAMERA_OFFSET_DEG: f64 = 2.0;
/// Lens glare around the sun: Gaussian σ (degrees) and peak (times the sky's brightest point).
const GLARE_SIGMA_DEG: f64 = 1.0;
const GLARE_PEAK: f32 = 1000.0;

/// One synthesized frame's description.
#[derive(Debug, Clone, PartialEq)]
pub struct SynthFrame {
    /// File name.
    pub file: String,
    /// Capture time.
    pub time: UnixTime,
    /// Camera units per unit radiance.
    pub exposure: f64,
}

/// The times of the frames: every step of the date (from `start_minutes` when given) with the
/// sun at least `min_elevation_deg` high, `frames` of them when given.
///
/// # Errors
/// When the site or date is invalid, or fewer than two frames result.
pub fn times(config: &SynthConfig) -> Result<Vec<(UnixTime, sky_core::solar::SunPosition)>> {
    let site = sky_core::solar::Site::new(config.latitude, config.longitude, 0.0)
        .map_err(|e| ParamError(format!("--lat/--lon: {e}")))?;
    let (y, m, d) = config.date;
    let midnight = UnixTime::from_civil(y, m, d, 0, 0, 0.0);
    let step = f64::from(config.step_minutes) * 60.0;
    let mut out = Vec::new();
    let first = config.start_minutes.map_or(0.0, |s| f64::from(s) * 60.0);
    let mut t = first;
    while t < 86_400.0 + first {
        let time = UnixTime(midnight.0 + t);
        let sun = time.sun_position(&site)?;
        let high = sun.elevation_deg() >= config.min_elevation_deg;
        if high {
            out.push((time, sun));
        } else if config.start_minutes.is_some() || !out.is_empty() {
            if config.frames.is_some_and(|n| out.len() < n) {
                return Err(ParamError(format!(
                    "--frames {}: the sun is only {:.1} deg high at {} (--min-elevation {} deg): fewer frames fit",
                    config.frames.unwrap_or(0),
                    sun.elevation_deg(),
                    time.rfc3339(),
                    config.min_elevation_deg,
                ))
                .into());
            }
            break;
        }
        if config.frames.is_some_and(|n| out.len() >= n) {
            break;
        }
        t += step;
    }
    if out.len() < 2 {
        return Err(ParamError(format!(
            "--min-elevation {} deg: fewer than two frames of the day have the sun that high",
            config.min_elevation_deg
        ))
        .into());
    }
    Ok(out)
}

/// The skyline's elevation (radians) towards world azimuth `phi`: rolling hills and a few
/// buildings, from `seed`.
struct Skyline {
    hills: [(f64, f64, f64); 3],
    buildings: Vec<(f64, f64, f64)>,
}

impl Skyline {
    fn new(seed: u64) -> Self {
        let mut rng = rand::rngs::StdRng::seed_from_u64(seed ^ 0x5b1e);
        let hills = [(1.0, 2.0), (3.0, 1.2), (7.0, 0.6)]
            .map(|(freq, amp)| (freq, amp, rng.random_range(0.0..TAU)));
        let buildings = (0..5)
            .map(|_| {
                (
                    rng.random_range(0.0..TAU),
                    rng.random_range(3.0f64..12.0).to_radians(),
                    rng.random_range(4.0f64..8.0).to_radians(),
                )
            })
            .collect();
        Self { hills, buildings }
    }

    fn elevation(&self, phi: f64) -> f64 {
        let hills = 3.0
            + self
                .hills
                .iter()
                .map(|(f, a, p)| a * (f * phi + p).sin())
                .sum::<f64>();
        let building = self
            .buildings
            .iter()
            .filter(|(centre, width, _)| {
                let d = (phi - centre).rem_euclid(TAU);
                d.min(TAU - d) < 0.5 * width
            })
            .map(|b| b.2)
            .fold(0.0, f64::max);
        hills.max(0.0).to_radians().max(building)
    }
}

/// Writes the sequence to `out` (created if missing): the frames, then the manifest.
///
/// # Errors
/// When a parameter is out of range or a file cannot be written.
pub fn synthesize(config: &SynthConfig, out: &Path, progress: bool) -> Result<Vec<SynthFrame>> {
    if config.width < 16 || !config.width.is_multiple_of(2) || config.width > 16384 {
        return Err(ParamError(format!(
            "--width {}: expected an even number of pixels in [16, 16384]",
            config.width
        ))
        .into());
    }
    // The sky's parameters, before the folder is made.
    sources::build(
        ModelKind::Hosek,
        &SkyParams::for_model(ModelKind::Hosek, 0.0, 0.0, config.turbidity),
    )?;
    let times = times(config)?;
    std::fs::create_dir_all(out).with_context(|| format!("cannot create {}", out.display()))?;
    let (w, h) = (config.width, config.width / 2);
    let grid =
        Equirect::new(to_u32(w), to_u32(h), Extent::Sphere).map_err(|e| anyhow::anyhow!("{e}"))?;
    let skyline = Skyline::new(config.seed);
    let bar = if progress {
        super::progress_bar(times.len(), "synthesizing frames")
    } else {
        indicatif::ProgressBar::hidden()
    };
    let mut written = Vec::new();
    for (k, (time, sun)) in times.iter().enumerate() {
        let mut rng =
            rand::rngs::StdRng::seed_from_u64(config.seed.wrapping_mul(0x9e37_79b9) ^ k as u64);
        let offset = rng
            .random_range(-CAMERA_OFFSET_DEG..=CAMERA_OFFSET_DEG)
            .to_radians();
        let relative_exposure = rng.random_range(-0.5f64..=0.5).exp2();
        let world = sun.sun();
        let (_, _, _, hh, mm, _) = time.to_civil();
        let file = format!("sky_{hh:02}{mm:02}.exr");
        let image = frame(
            config,
            &grid,
            &skyline,
            k,
            world.zenith(),
            f64::from(world.azimuth()),
            offset,
            relative_exposure,
        )?;
        image_io::write_exr(&out.join(&file), &image.0)?;
        written.push(SynthFrame {
            file,
            time: *time,
            exposure: image.1,
        });
        bar.inc(1);
    }
    bar.finish_and_clear();
    let mut manifest = format!(
        "# A synthesized capture sequence: sky-train captures synthesize (Hosek-Wilkie, turbidity {}, seed {}).\n\
         latitude = {}\nlongitude = {}\n",
        config.turbidity, config.seed, config.latitude, config.longitude
    );
    for f in &written {
        let _ = write!(
            manifest,
            "\n[[frame]]\nfile = \"{}\"\ntime = \"{}\"\nexposure = {:e}\n",
            f.file,
            f.time.rfc3339(),
            f.exposure
        );
    }
    image_io::write_text(&out.join(MANIFEST), &manifest)?;
    Ok(written)
}

fn to_u32(k: usize) -> u32 {
    u32::try_from(k).unwrap_or(u32::MAX)
}

/// One frame in camera units, and its exposure.
#[allow(clippy::too_many_arguments, clippy::cast_possible_truncation)]
fn frame(
    config: &SynthConfig,
    grid: &Equirect,
    skyline: &Skyline,
    index: usize,
    sun_zenith: f32,
    sun_azimuth_world: f64,
    camera_offset: f64,
    relative_exposure: f64,
) -> Result<(RgbImage, f64)> {
    let (w, h) = (grid.width() as usize, grid.height() as usize);
    // The camera is turned by `camera_offset`: image azimuth φ looks towards world φ + offset.
    let sun_azimuth = sun_azimuth_world - camera_offset;
    let params = SkyParams::for_model(
        ModelKind::Hosek,
        f64::from(sun_zenith).to_degrees(),
        sun_azimuth.to_degrees(),
        config.turbidity,
    );
    let sky = sources::build(ModelKind::Hosek, &params)?;
    let mut pixels = vec![Vec3::ZERO; w * h];
    pixels.par_chunks_mut(w).enumerate().for_each(|(y, row)| {
        let dirs: Vec<Vec3> = (0..w)
            .map(|x| grid.direction(to_u32(x), to_u32(y)))
            .collect();
        sky.rgb_batch(&dirs, row);
    });
    let brightest = pixels
        .iter()
        .map(|p| sky_core::color::luminance(*p))
        .fold(0.0f32, f32::max);
    let zenith_sky = sky_core::color::luminance(pixels[w / 2]);
    let exposure = f64::from(0.05 * CLIP / brightest) * relative_exposure;
    let sun_dir = geom::direction(sun_zenith, sun_azimuth as f32);
    let sun_colour = {
        let mut c = [Vec3::ZERO];
        sky.rgb_batch(&[sun_dir], &mut c);
        c[0] / sky_core::color::luminance(c[0]).max(f32::MIN_POSITIVE)
    };
    let glare_peak = sun_colour * (GLARE_PEAK * brightest);
    let two_sigma2 = 2.0 * GLARE_SIGMA_DEG.to_radians().powi(2);
    let silhouette = Vec3::new(0.6, 0.8, 0.5) * (0.02 * zenith_sky);
    let ground = Vec3::new(0.5, 0.4, 0.3) * (0.2 * zenith_sky);
    let (shot, read) = (5e-6 * CLIP, 1e-4 * CLIP);
    let (pixel_dt, pixel_dp) = (PI / h as f64, TAU / w as f64);
    let glare_reach = 6.0 * GLARE_SIGMA_DEG.to_radians() + 1.5 * pixel_dp;
    let seed = config.seed;
    pixels.par_chunks_mut(w).enumerate().for_each(|(y, row)| {
        let mut rng = rand::rngs::StdRng::seed_from_u64(
            seed.wrapping_mul(0x2545_f491) ^ ((index as u64) << 32) ^ y as u64,
        );
        let elevation = 0.5 * PI - f64::from(grid.zenith(to_u32(y)));
        for (x, p) in row.iter_mut().enumerate() {
            let d = grid.direction(to_u32(x), to_u32(y));
            let world_phi = f64::from(grid.azimuth(to_u32(x))) + camera_offset;
            let radiance = if elevation < 0.0 {
                ground
            } else if elevation < skyline.elevation(world_phi) {
                silhouette
            } else if f64::from(geom::angle_between(d, sun_dir)) > glare_reach {
                *p
            } else {
                // The glare integrated over the pixel, as a sensor does (8 × 8 sub-samples).
                let mut sum = 0.0;
                for sy in 0..8 {
                    for sx in 0..8 {
                        let zenith = pixel_dt * (y as f64 + (f64::from(sy) + 0.5) / 8.0);
                        let azimuth = pixel_dp * (x as f64 + (f64::from(sx) + 0.5) / 8.0);
                        let v = geom::direction(zenith as f32, azimuth as f32);
                        let gamma = f64::from(geom::angle_between(v, sun_dir));
                        sum += (-gamma * gamma / two_sigma2).exp();
                    }
                }
                *p + glare_peak * ((sum / 64.0) as f32)
            };
            let v = radiance * exposure as f32;
            *p = Vec3::from_array(v.to_array().map(|c| {
                let sigma = (shot * c.max(0.0) + read * read).sqrt();
                (c + sigma * gaussian(&mut rng)).clamp(0.0, CLIP)
            }));
        }
    });
    Ok((
        RgbImage {
            width: w,
            height: h,
            pixels,
        },
        exposure,
    ))
}

/// A standard normal deviate (Box-Muller).
#[allow(clippy::cast_possible_truncation)]
fn gaussian(rng: &mut impl Rng) -> f32 {
    let u1: f64 = rng.random_range(f64::MIN_POSITIVE..1.0);
    let u2: f64 = rng.random();
    ((-2.0 * u1.ln()).sqrt() * (TAU * u2).cos()) as f32
}
