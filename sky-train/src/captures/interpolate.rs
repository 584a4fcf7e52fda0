//! Filling the gaps between captures (seed 000 §IV-B, Figs. 1 and 9): the trained network
//! rendered at every time step between the first and the last capture.
//!
//! The sun of a step: with the capture times and the site, its zenith from NREL SPA and its
//! azimuth in the image from SPA's azimuth turned by the camera's heading (the circular mean,
//! over the frames, of SPA's azimuth minus the azimuth found in the image); with times but no
//! site, or with neither (frames taken as evenly spaced), zenith and image azimuth are
//! interpolated linearly between the neighbouring captures.

use std::f64::consts::{PI, TAU};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use rayon::prelude::*;
use sky_core::Vec3;
use sky_core::geom::{Equirect, Extent};
use sky_core::neural::{NeuralSky, NeuralWeights};

use super::Sequence;
use super::manifest::UnixTime;
use crate::args::ParamError;
use crate::image_io::{self, RgbImage};

/// One output step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Step {
    /// Minutes after the first capture.
    pub minutes: f64,
    /// The UTC time, when the captures have times.
    pub time: Option<UnixTime>,
    /// Sun zenith angle, radians.
    pub sun_zenith: f64,
    /// Sun azimuth in the frames' image coordinates, radians.
    pub sun_azimuth: f64,
}

/// The steps every `step_minutes` from the first capture to the last; `interval_minutes` is the
/// spacing assumed between captures that have no times.
///
/// # Errors
/// When the step is not positive or SPA fails.
pub fn steps(seq: &Sequence, step_minutes: f64, interval_minutes: f64) -> Result<Vec<Step>> {
    if !(step_minutes > 0.0 && step_minutes.is_finite()) {
        return Err(ParamError("--step must be a positive duration".into()).into());
    }
    let frames = &seq.frames;
    // Minutes of each capture after the first.
    let at: Vec<f64> = match (frames[0].time, frames.iter().all(|f| f.time.is_some())) {
        (Some(t0), true) => frames
            .iter()
            .map(|f| f.time.map_or(0.0, |t| (t.0 - t0.0) / 60.0))
            .collect(),
        _ => (0..frames.len())
            .map(|k| {
                #[allow(clippy::cast_precision_loss)]
                let k = k as f64;
                k * interval_minutes
            })
            .collect(),
    };
    let last = at[at.len() - 1];
    // Circular mean of (SPA azimuth − image azimuth): the camera's heading.
    let heading = {
        let (s, c) = frames
            .iter()
            .filter_map(|f| f.solar_azimuth.map(|a| a - f.sun.azimuth))
            .fold((0.0, 0.0), |(s, c), d| (s + d.sin(), c + d.cos()));
        (s != 0.0 || c != 0.0).then(|| s.atan2(c))
    };
    let n = (last / step_minutes + 1e-9).floor();
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let n = n as usize;
    let mut out = Vec::with_capacity(n + 1);
    for i in 0..=n {
        #[allow(clippy::cast_precision_loss)]
        let minutes = i as f64 * step_minutes;
        let time = frames[0].time.map(|t0| UnixTime(t0.0 + minutes * 60.0));
        let (sun_zenith, sun_azimuth) = match (time, seq.site.as_ref(), heading) {
            (Some(t), Some(site), Some(heading)) => {
                let p = t.sun_position(site)?;
                (
                    p.zenith_deg().to_radians(),
                    (f64::from(p.sun().azimuth()) - heading).rem_euclid(TAU),
                )
            }
            _ => {
                let k = at.partition_point(|&a| a <= minutes).clamp(1, at.len() - 1);
                let w = (minutes - at[k - 1]) / (at[k] - at[k - 1]);
                let (a, b) = (&frames[k - 1], &frames[k]);
                let turn = (b.sun.azimuth - a.sun.azimuth + PI).rem_euclid(TAU) - PI;
                (
                    a.sun_zenith + w * (b.sun_zenith - a.sun_zenith),
                    (a.sun.azimuth + w * turn).rem_euclid(TAU),
                )
            }
        };
        out.push(Step {
            minutes,
            time,
            sun_zenith,
            sun_azimuth,
        });
    }
    Ok(out)
}

/// The network's sky for `step` on a `width` × `width/2` latitude-longitude grid (the frames'
/// coordinates); below the horizon, where no capture showed sky, it is black.
///
/// # Errors
/// When the sun lies outside the weights' trained range.
pub fn render(weights: &NeuralWeights<12>, step: &Step, width: usize) -> Result<RgbImage> {
    let height = width / 2;
    #[allow(clippy::cast_possible_truncation)]
    let sun = sky_core::Sun::new(step.sun_zenith as f32, step.sun_azimuth as f32)
        .map_err(|e| anyhow::anyhow!("{e}"))?;
    let sky = NeuralSky::new(weights, sun, 0.0).map_err(|e| outside_the_weights(step, e))?;
    let grid = Equirect::new(to_u32(width), to_u32(height), Extent::Sphere)
        .map_err(|e| anyhow::anyhow!("{e}"))?;
    let mut pixels = vec![Vec3::ZERO; width * height];
    pixels
        .par_chunks_mut(width)
        .take(height / 2)
        .enumerate()
        .for_each(|(y, row)| {
            let dirs: Vec<Vec3> = (0..width)
                .map(|x| grid.direction(to_u32(x), to_u32(y)))
                .collect();
            crate::dispatch::fastest(
                #[inline(always)]
                || sky.rgb_batch(&dirs, row),
            );
        });
    Ok(RgbImage {
        width,
        height,
        pixels,
    })
}

fn to_u32(k: usize) -> u32 {
    u32::try_from(k).unwrap_or(u32::MAX)
}

/// Checks an output width: even, at least 16 pixels.
///
/// # Errors
/// A [`ParamError`] naming `--width`.
pub fn check_width(width: usize) -> Result<(), ParamError> {
    if width < 16 || !width.is_multiple_of(2) {
        return Err(ParamError(format!(
            "--width {width}: expected an even number of pixels, at least 16"
        )));
    }
    Ok(())
}

/// The weights refuse the sun of `step` (bad input: weights trained on other captures), in
/// degrees.
fn outside_the_weights(step: &Step, e: sky_core::SkyError) -> ParamError {
    ParamError(format!(
        "--weights: the sun at {:.1} min is outside the weights' trained range: {}",
        step.minutes,
        crate::args::describe(e, str::to_owned, " ")
    ))
}

/// The file name of output step `i`.
#[must_use]
pub fn file_name(i: usize) -> String {
    format!("interp_{i:04}.exr")
}

/// The list of written frames, beside them.
pub const LIST: &str = "interpolated.toml";

/// Renders every step to `out/interp_NNNN.exr` (atomically; frames in parallel), then lists
/// them in `out/interpolated.toml` with their times and suns (what a renderer needs to add the
/// direct sun), and returns the paths. Files written before an error are complete and stay.
///
/// # Errors
/// When a sun lies outside the weights' range or a file cannot be written.
pub fn write_steps(
    weights: &NeuralWeights<12>,
    steps: &[Step],
    width: usize,
    out: &Path,
    progress: bool,
) -> Result<Vec<PathBuf>> {
    check_width(width)?;
    // Every sun is checked before the first file is written.
    for s in steps {
        #[allow(clippy::cast_possible_truncation)]
        let sun = sky_core::Sun::new(s.sun_zenith as f32, s.sun_azimuth as f32)
            .map_err(|e| outside_the_weights(s, e))?;
        NeuralSky::new(weights, sun, 0.0).map_err(|e| outside_the_weights(s, e))?;
    }
    std::fs::create_dir_all(out).with_context(|| format!("cannot create {}", out.display()))?;
    let bar = if progress {
        super::progress_bar(steps.len(), "rendering")
    } else {
        indicatif::ProgressBar::hidden()
    };
    let paths = steps
        .par_iter()
        .enumerate()
        .map(|(i, s)| {
            let path = out.join(file_name(i));
            image_io::write_exr(&path, &render(weights, s, width)?)?;
            bar.inc(1);
            Ok(path)
        })
        .collect::<Result<Vec<_>>>()?;
    bar.finish_and_clear();
    let mut list = String::from(
        "# Frames rendered by sky-train captures interpolate. Sun zenith and azimuth in degrees, \n\
         # the azimuth in the frames' own coordinates (sky-core's convention: from +x towards +y).\n",
    );
    for (i, s) in steps.iter().enumerate() {
        let _ = write!(
            list,
            "\n[[frame]]\nfile = \"{}\"\nminutes = {}\n{}sun_zenith_deg = {:?}\nsun_azimuth_deg = {:?}\n",
            file_name(i),
            s.minutes,
            s.time
                .map_or_else(String::new, |t| format!("time = \"{}\"\n", t.rfc3339())),
            s.sun_zenith.to_degrees(),
            s.sun_azimuth.to_degrees()
        );
    }
    image_io::write_text(&out.join(LIST), &list)?;
    Ok(paths)
}

/// A strip of thumbnails like seed 000's Fig. 1: the upper hemispheres of the first `captures`
/// captures on the top row, each in the column of its time with `between` empty columns (the
/// gaps) after it, and the network's sky at every column on the bottom row; one exposure for
/// all, from the captures' median.
///
/// # Errors
/// When a sun lies outside the weights' range.
pub fn strip(
    seq: &Sequence,
    weights: &NeuralWeights<12>,
    captures: usize,
    between: usize,
    thumb_width: usize,
) -> Result<RgbImage> {
    let captures = captures.clamp(2, seq.frames.len());
    let interval = 15.0;
    let all = steps(seq, 1.0, interval)?;
    let frames = &seq.frames[..captures];
    let at: Vec<f64> = match frames[0].time {
        Some(t0) => frames
            .iter()
            .map(|f| f.time.map_or(0.0, |t| (t.0 - t0.0) / 60.0))
            .collect(),
        None => (0..captures)
            .map(|k| {
                #[allow(clippy::cast_precision_loss)]
                let k = k as f64;
                k * interval
            })
            .collect(),
    };
    let columns = (captures - 1) * (between + 1) + 1;
    let (tw, th) = (thumb_width, thumb_width / 4);
    let gap = 4;
    let mut image = RgbImage {
        width: columns * (tw + gap) - gap,
        height: 2 * th + gap,
        pixels: vec![Vec3::ZERO; (columns * (tw + gap) - gap) * (2 * th + gap)],
    };
    // Empty cells (the gaps between captures) are dark grey.
    for (col, row) in (0..columns).flat_map(|c| [(c, 0), (c, 1)]) {
        for y in 0..th {
            let start = (row * (th + gap) + y) * image.width + col * (tw + gap);
            image.pixels[start..start + tw].fill(Vec3::splat(0.02));
        }
    }
    // The network is rendered at a whole multiple of the thumbnail's width (up to 4, for the
    // box filter; at least 1 whatever the captures' width), so that every thumbnail pixel
    // averages its own f × f pixels of the whole panorama.
    let factor = (seq.width / tw).clamp(1, 4);
    // Every thumbnail is turned by the same whole number of columns, so that the first
    // capture's sun is in the middle.
    #[allow(
        clippy::cast_possible_truncation,
        clippy::cast_sign_loss,
        clippy::cast_precision_loss
    )]
    let shift = (((frames[0].sun.azimuth - PI) / TAU).rem_euclid(1.0) * tw as f64).round() as usize;
    let mut blit = |col: usize, row: usize, thumb: &[Vec3]| {
        for y in 0..th {
            for x in 0..tw {
                let (ix, iy) = (col * (tw + gap) + x, row * (th + gap) + y);
                image.pixels[iy * image.width + ix] = thumb[y * tw + (x + shift) % tw];
            }
        }
    };
    let mut exposure_samples = Vec::new();
    for (k, f) in frames.iter().enumerate() {
        let thumb = thumbnail_of_eval(f, tw);
        exposure_samples.extend(thumb.iter().map(|p| sky_core::color::luminance(*p)));
        blit(k * (between + 1), 0, &thumb);
    }
    for col in 0..columns {
        let k = col / (between + 1);
        #[allow(clippy::cast_precision_loss)]
        let minutes = if k + 1 < captures {
            at[k] + (at[k + 1] - at[k]) * (col % (between + 1)) as f64 / (between + 1) as f64
        } else {
            at[k]
        };
        let nearest = all
            .iter()
            .min_by(|a, b| {
                (a.minutes - minutes)
                    .abs()
                    .total_cmp(&(b.minutes - minutes).abs())
            })
            .copied()
            .unwrap_or(all[0]);
        let step = Step { minutes, ..nearest };
        let full = render(weights, &step, factor * tw)?;
        blit(col, 1, &downsample_upper(&full, tw));
    }
    let mid = exposure_samples.len() / 2;
    let median = *exposure_samples
        .select_nth_unstable_by(mid, f32::total_cmp)
        .1;
    let scale = 0.18 / median.max(f32::MIN_POSITIVE);
    for p in &mut image.pixels {
        if *p != Vec3::splat(0.02) {
            *p *= scale;
        }
    }
    Ok(image)
}

/// The upper hemisphere of a whole-sphere image whose width is a multiple of `tw`,
/// box-filtered to `tw` × `tw/4`.
fn downsample_upper(full: &RgbImage, tw: usize) -> Vec<Vec3> {
    let th = tw / 4;
    let f = full.width / tw;
    debug_assert!(f >= 1 && full.width == f * tw && full.height >= f * th);
    let mut out = vec![Vec3::ZERO; tw * th];
    for y in 0..th {
        for x in 0..tw {
            let mut sum = Vec3::ZERO;
            for dy in 0..f {
                for dx in 0..f {
                    sum += full.get(x * f + dx, y * f + dy);
                }
            }
            #[allow(clippy::cast_precision_loss)]
            let n = (f * f) as f32;
            out[y * tw + x] = sum / n;
        }
    }
    out
}

/// A capture's evaluation grid (its upper hemisphere at a stride) as a `tw` × `tw/4`
/// thumbnail, nearest neighbour.
fn thumbnail_of_eval(frame: &super::Frame, tw: usize) -> Vec<Vec3> {
    let th = tw / 4;
    let (gw, gh) = (frame.eval.columns, frame.eval.rows);
    let mut out = vec![Vec3::ZERO; tw * th];
    for y in 0..th {
        for x in 0..tw {
            out[y * tw + x] = frame.eval.values[(y * gh / th) * gw + x * gw / tw];
        }
    }
    out
}
