//! Reading a capture sequence (seed 000 §III-D): every frame is checked, read, reduced to its
//! training samples and a small evaluation grid, and dropped before the next one is read, so
//! memory holds one full-resolution frame at a time (a 4096 × 2048 frame is 96 MiB as RGB f32).
//! Frames are at most [`MAX_IMAGE_PIXELS`](crate::image_io::MAX_IMAGE_PIXELS) (8192 × 4096), a
//! limit checked from every header before any frame is read.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use indicatif::ProgressBar;
use rand::{Rng, SeedableRng};
use rayon::prelude::*;
use sky_core::Vec3;
use sky_core::color;
use sky_core::geom::{Equirect, Extent};

use super::manifest::{MANIFEST, Manifest, UnixTime};
use super::mask::{self, SkyMask};
use super::sun::{self, SunEstimate, pixel_direction};
use super::{EvalGrid, Frame, Sequence};

/// How frames are sampled.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadConfig {
    /// Training samples drawn per frame (stratified, uniform in solid angle over the visible
    /// sky).
    pub samples_per_frame: usize,
    /// Largest width of the evaluation grid (the frame's pixels at a stride).
    pub eval_width: usize,
    /// Seed of the sampling jitter.
    pub seed: u64,
    /// Show a progress bar.
    pub progress: bool,
}

impl Default for LoadConfig {
    fn default() -> Self {
        Self {
            samples_per_frame: 2048,
            eval_width: 256,
            seed: 1,
            progress: true,
        }
    }
}

/// The frames of `dir` with their manifest entries: (path, time, exposure).
type FrameList = Vec<(PathBuf, Option<UnixTime>, f64)>;

/// Lists the frames of `dir`: the manifest's, or every `.exr` file in name order.
///
/// # Errors
/// When the folder cannot be read, has no frames, or the manifest is invalid.
pub fn list(dir: &Path) -> Result<(Option<Manifest>, FrameList)> {
    if !dir.is_dir() {
        bail!("{}: not a folder", dir.display());
    }
    let manifest = Manifest::read(dir)?;
    let frames: FrameList = match &manifest {
        Some(m) if !m.frames.is_empty() => m
            .frames
            .iter()
            .map(|f| {
                let time = f.time.as_deref().map(UnixTime::parse).transpose()?;
                Ok((dir.join(&f.file), time, f.exposure.unwrap_or(1.0)))
            })
            .collect::<Result<_>>()?,
        _ => {
            let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
                .with_context(|| format!("cannot read the folder {}", dir.display()))?
                .filter_map(|e| e.ok().map(|e| e.path()))
                .filter(|p| p.extension().is_some_and(|e| e.eq_ignore_ascii_case("exr")))
                .collect();
            files.sort();
            files.into_iter().map(|p| (p, None, 1.0)).collect()
        }
    };
    if frames.is_empty() {
        bail!(
            "{}: no frames (no .exr files, and no [[frame]] in a {MANIFEST})",
            dir.display()
        );
    }
    if frames.len() < 2 {
        bail!(
            "{}: one frame only; a sequence needs at least two",
            dir.display()
        );
    }
    if let Some(w) = frames.windows(2).find(|w| match (w[0].1, w[1].1) {
        (Some(a), Some(b)) => b.0 <= a.0,
        _ => false,
    }) {
        bail!(
            "{}: frame {} is not later than {} (frames must be in time order)",
            dir.join(MANIFEST).display(),
            w[1].0.display(),
            w[0].0.display()
        );
    }
    Ok((manifest, frames))
}

/// Checks an OpenEXR file's header: readable, at most
/// [`MAX_IMAGE_PIXELS`](crate::image_io::MAX_IMAGE_PIXELS), R, G and B channels, a 2:1
/// latitude-longitude image. Returns its size.
///
/// # Errors
/// A message naming the file and what is wrong.
pub fn check_header(path: &Path) -> Result<(usize, usize)> {
    check_meta(
        &path.display().to_string(),
        exr::meta::MetaData::read_from_file(path, false),
    )
}

/// [`check_header`] of the header read from the file named `p`.
fn check_meta(
    p: &str,
    meta: std::result::Result<exr::meta::MetaData, exr::error::Error>,
) -> Result<(usize, usize)> {
    let meta = meta.map_err(|e| match e {
        exr::error::Error::Io(io) if io.kind() != std::io::ErrorKind::UnexpectedEof => {
            anyhow::anyhow!("{p}: cannot read: {io}")
        }
        other => {
            anyhow::anyhow!("{p}: not a readable OpenEXR file (truncated or corrupt): {other}")
        }
    })?;
    let Some(header) = meta.headers.first() else {
        bail!("{p}: the OpenEXR file has no image");
    };
    let names: Vec<String> = header
        .channels
        .list
        .iter()
        .map(|c| c.name.to_string())
        .collect();
    let missing: Vec<&str> = ["R", "G", "B"]
        .into_iter()
        .filter(|c| !names.iter().any(|n| n == c))
        .collect();
    if !missing.is_empty() {
        bail!(
            "{p}: missing channel(s) {} (the file has {}); frames need R, G and B",
            missing.join(", "),
            if names.is_empty() {
                "none".to_string()
            } else {
                names.join(", ")
            }
        );
    }
    for header in &meta.headers {
        crate::image_io::check_image_size(header.layer_size.width(), header.layer_size.height())
            .with_context(|| p.to_string())?;
    }
    let (w, h) = (header.layer_size.width(), header.layer_size.height());
    if w != 2 * h || h < 8 {
        bail!(
            "{p}: {w}x{h} pixels is not a latitude-longitude panorama (width must be twice the height, at least 16x8)"
        );
    }
    Ok((w, h))
}

/// Loads the sequence in `dir` (see the module docs).
///
/// # Errors
/// For any bad frame, mask or manifest, with a message naming the file and the problem.
pub fn load(dir: &Path, config: &LoadConfig) -> Result<Sequence> {
    let (manifest, list) = list(dir)?;
    // Every header first: a bad file is reported before any long work.
    let mut size = None;
    for (path, _, _) in &list {
        let s = check_header(path)?;
        match size {
            None => size = Some((s, path.clone())),
            Some(((w, h), ref first)) if (w, h) != s => bail!(
                "{}: {}x{} pixels, but {} is {w}x{h}: all frames must have the same size",
                path.display(),
                s.0,
                s.1,
                first.display()
            ),
            Some(_) => {}
        }
    }
    let (width, height) = size.map_or((0, 0), |(s, _)| s);
    let mask = match manifest.as_ref().and_then(|m| m.mask.as_ref()) {
        Some(file) => {
            let path = dir.join(file);
            let m = SkyMask::read(&path)?;
            m.check_size(&path, &list[0].0, width, height)?;
            Some(m)
        }
        None => None,
    };
    let site = match manifest.as_ref() {
        Some(Manifest {
            latitude: Some(lat),
            longitude: Some(lon),
            elevation,
            ..
        }) => Some(
            sky_core::solar::Site::new(*lat, *lon, elevation.unwrap_or(0.0))
                .map_err(|e| anyhow::anyhow!("{}: {e}", dir.join(MANIFEST).display()))?,
        ),
        _ => None,
    };
    let grid = Equirect::new(to_u32(width), to_u32(height), Extent::Sphere)
        .map_err(|e| anyhow::anyhow!("{e}"))?;
    let bar = if config.progress {
        super::progress_bar(list.len(), "reading frames")
    } else {
        ProgressBar::hidden()
    };
    let mut frames = Vec::with_capacity(list.len());
    for (k, (path, time, exposure)) in list.iter().enumerate() {
        let image = crate::image_io::read_exr(path).map_err(|e| {
            anyhow::anyhow!(
                "{}: truncated or corrupt OpenEXR data: {}",
                path.display(),
                e.root_cause()
            )
        })?;
        let frame = reduce_frame(
            &image,
            path,
            *time,
            *exposure,
            site.as_ref(),
            mask.as_ref(),
            &grid,
            config,
            k,
        )?;
        frames.push(frame);
        bar.inc(1);
    }
    bar.finish_and_clear();
    Ok(Sequence {
        dir: dir.to_path_buf(),
        width,
        height,
        site,
        frames,
    })
}

fn to_u32(k: usize) -> u32 {
    u32::try_from(k).unwrap_or(u32::MAX)
}

/// One frame from the bytes of an OpenEXR file, checked, read and reduced as [`load`] does
/// with each file of a folder without a manifest (exposure 1, no site, the skyline estimate,
/// 64 samples): what the fuzz target `capture_frame` runs on every input.
///
/// # Errors
/// As [`load`] for a bad frame.
pub fn frame_from_bytes(bytes: &[u8]) -> Result<Frame> {
    let name = Path::new("frame.exr");
    let (width, height) = check_meta(
        "frame.exr",
        exr::meta::MetaData::read_from_buffered(bytes, false),
    )?;
    let image = crate::image_io::read_exr_from(std::io::Cursor::new(bytes))
        .map_err(|e| anyhow::anyhow!("frame.exr: truncated or corrupt OpenEXR data: {e}"))?;
    if (image.width, image.height) != (width, height) {
        bail!("frame.exr: the first RGB layer is not the header's size");
    }
    let grid = Equirect::new(to_u32(width), to_u32(height), Extent::Sphere)
        .map_err(|e| anyhow::anyhow!("{e}"))?;
    let config = LoadConfig {
        samples_per_frame: 64,
        progress: false,
        ..LoadConfig::default()
    };
    reduce_frame(&image, name, None, 1.0, None, None, &grid, &config, 0)
}

/// A frame's image reduced to its samples and evaluation grid (see the module docs).
#[allow(clippy::too_many_arguments)]
fn reduce_frame(
    image: &crate::image_io::RgbImage,
    path: &Path,
    time: Option<UnixTime>,
    exposure: f64,
    site: Option<&sky_core::solar::Site>,
    mask: Option<&SkyMask>,
    grid: &Equirect,
    config: &LoadConfig,
    index: usize,
) -> Result<Frame> {
    let p = path.display();
    let (w, h) = (image.width, image.height);
    let luminance: Vec<f32> = image
        .pixels
        .par_iter()
        .map(|&c| color::luminance(c))
        .collect();
    if let Some(i) = image.pixels.iter().position(|c| !c.is_finite()) {
        bail!(
            "{p}: pixel ({}, {}) is not finite ({:?}); frames must hold finite radiance",
            i % w,
            i / w,
            image.pixels[i].to_array()
        );
    }
    let found: SunEstimate =
        sun::find(&luminance, grid).map_err(|e| anyhow::anyhow!("{p}: {e}"))?;
    let solar = match (time, site) {
        (Some(t), Some(s)) => Some(t.sun_position(s).with_context(|| p.to_string())?),
        _ => None,
    };
    // The sun's zenith: from the time and place when known (NREL SPA, geometric), else from
    // the image; its azimuth always from the image (the camera's heading is not known).
    let sun_zenith = solar.map_or(found.zenith, |s| s.zenith_deg().to_radians());
    if sun_zenith >= std::f64::consts::FRAC_PI_2 {
        bail!(
            "{p}: the sun is {:.2} degrees below the horizon at {}; frames need the sun up",
            sun_zenith.to_degrees() - 90.0,
            time.map_or_else(String::new, UnixTime::rfc3339)
        );
    }
    // Valid pixels: sky by the mask or the skyline, and away from the sun.
    let mut valid = match mask {
        Some(m) => m.sky.clone(),
        None => mask::skyline(&luminance, w, h),
    };
    drop(luminance);
    let exclusion = mask::SUN_EXCLUSION * found.radius + std::f64::consts::PI / h as f64;
    let cos_exclusion = exclusion.cos();
    let rows = h / 2;
    valid.truncate(rows * w);
    valid.par_chunks_mut(w).enumerate().for_each(|(y, row)| {
        for (x, v) in row.iter_mut().enumerate() {
            if *v {
                let d = pixel_direction(grid, x, y);
                *v = f64::from(d.dot(found.direction)) < cos_exclusion;
            }
        }
    });
    let valid_count = valid.iter().filter(|v| **v).count();
    if valid_count * 20 < rows * w {
        bail!(
            "{p}: only {valid_count} of {} upper-hemisphere pixels are usable sky (mask, skyline and sun taken out)",
            rows * w
        );
    }
    #[allow(clippy::cast_possible_truncation)]
    let scale = (1.0 / exposure) as f32;
    // Radiance is f32 from here on (samples, the network, the weight file).
    if let Some(i) = image
        .pixels
        .iter()
        .position(|c| !(*c * scale).is_finite() || (c.max_element() > 0.0 && scale == 0.0))
    {
        bail!(
            "{p}: exposure {exposure:e} makes pixel ({}, {}) {:?} a radiance outside f32's range \
             (pixel values are divided by the manifest's exposure)",
            i % w,
            i / w,
            image.pixels[i].to_array()
        );
    }
    // Eq. 10: rotate every view so that the sun's azimuth is π.
    let rotate = found.azimuth - std::f64::consts::PI;
    let (sr, cr) = rotate.sin_cos();
    let rotated = |d: Vec3| -> [f64; 3] {
        let (x0, y0, z0) = (f64::from(d.x), f64::from(d.y), f64::from(d.z));
        [x0 * cr + y0 * sr, y0 * cr - x0 * sr, z0]
    };
    // Training samples: strata uniform in solid angle (cos θ × φ) over the upper hemisphere,
    // each drawing up to 8 jittered points until one lands on a valid pixel; the sample is that
    // pixel's centre and value.
    let nz = ((config.samples_per_frame as f64 / 2.0).sqrt().ceil() as usize).max(1);
    let na = 2 * nz;
    let mut rng = rand::rngs::StdRng::seed_from_u64(config.seed ^ ((index as u64) << 24));
    let mut views = Vec::with_capacity(nz * na);
    let mut targets = Vec::with_capacity(nz * na);
    for i in 0..nz {
        for j in 0..na {
            for _ in 0..8 {
                let cos_t = (i as f64 + rng.random::<f64>()) / nz as f64;
                let phi = std::f64::consts::TAU * (j as f64 + rng.random::<f64>()) / na as f64;
                let theta = cos_t.clamp(0.0, 1.0).acos();
                let x = ((phi / std::f64::consts::TAU * w as f64) as usize).min(w - 1);
                let y = ((theta / std::f64::consts::PI * h as f64) as usize).min(rows - 1);
                if valid[y * w + x] {
                    views.push(rotated(pixel_direction(grid, x, y)));
                    targets.push((image.pixels[y * w + x] * scale).to_array().map(f64::from));
                    break;
                }
            }
        }
    }
    // The evaluation grid: every `stride`-th pixel of the upper hemisphere.
    let stride = w.div_ceil(config.eval_width).max(1);
    let eval = EvalGrid::sample(image, &valid, stride, scale);
    Ok(Frame {
        file: path.to_path_buf(),
        time,
        exposure,
        sun: found,
        sun_zenith,
        solar_zenith: solar.map(|s| s.zenith_deg().to_radians()),
        solar_azimuth: solar.map(|s| s.sun().azimuth().into()),
        views,
        targets,
        eval,
    })
}
