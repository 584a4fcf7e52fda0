//! Captured skies (seed 000 §III-D, §IV-A, §IV-B, Figs. 1, 8, 9): one neural sky learned from a
//! sparse sequence of HDR environment maps, which then renders the sky at any sun position in
//! between.
//!
//! * [`load`](mod@load): a folder of latitude-longitude OpenEXR frames and an optional
//!   [`manifest`] (times, site, mask). Per frame: the sun found ([`sun`]), non-sky and sun pixels
//!   left out ([`mask`]), views rotated so the sun's azimuth is π (eq. 10) and sampled uniformly
//!   in solid angle; inputs {0, θ_sun, v_x, v_y, v_z, d} (§III-B).
//! * [`validate`]: training on the whole sequence and §IV-A's leave-one-out cross-validation
//!   (NRMSE and eq. 11's irradiance per frame), with plain linear blending of the neighbouring
//!   captures as the baseline the network must beat.
//! * [`interpolate`](mod@interpolate): the gap-filling frames, one EXR per time step.
//! * [`synthesize`](mod@synthesize): capture-like test sequences from the Hosek-Wilkie sky, with
//!   what real captures have (varying exposure, noise, a clipped sun, a skyline, camera
//!   rotation), and their manifest.

pub mod interpolate;
pub mod load;
pub mod manifest;
pub mod mask;
pub mod sun;
pub mod synthesize;
pub mod validate;

use std::path::PathBuf;

use indicatif::{ProgressBar, ProgressStyle};
use sky_core::Vec3;

use crate::image_io::RgbImage;
use crate::train::dataset::{self, DataSet, SkyCase};
use manifest::UnixTime;

/// A loaded capture sequence: per frame, its sun, samples and evaluation grid (the pixels
/// themselves are not kept).
#[derive(Debug, Clone)]
pub struct Sequence {
    /// The folder.
    pub dir: PathBuf,
    /// Frame width in pixels.
    pub width: usize,
    /// Frame height in pixels.
    pub height: usize,
    /// The site, when the manifest gives it.
    pub site: Option<sky_core::solar::Site>,
    /// The frames in time order.
    pub frames: Vec<Frame>,
}

/// One frame of a sequence.
#[derive(Debug, Clone)]
pub struct Frame {
    /// Its file.
    pub file: PathBuf,
    /// Its capture time, when the manifest gives it.
    pub time: Option<UnixTime>,
    /// Camera units per unit radiance (pixel values were divided by it).
    pub exposure: f64,
    /// The sun found in the image.
    pub sun: sun::SunEstimate,
    /// The sun's zenith angle used (radians): from the time and place when known, else the
    /// image's.
    pub sun_zenith: f64,
    /// The sun's zenith from the time and place (NREL SPA), radians.
    pub solar_zenith: Option<f64>,
    /// The sun's azimuth from the time and place, sky-core's convention (from east towards
    /// north), radians.
    pub solar_azimuth: Option<f64>,
    /// Training views, rotated so the sun's azimuth is π (eq. 10).
    pub views: Vec<[f64; 3]>,
    /// Their radiance, linear RGB, exposure removed.
    pub targets: Vec<[f64; 3]>,
    /// The frame at a stride, for evaluation.
    pub eval: EvalGrid,
}

impl Frame {
    /// The frame's name (its file name).
    #[must_use]
    pub fn name(&self) -> String {
        self.file.file_name().map_or_else(
            || self.file.display().to_string(),
            |n| n.to_string_lossy().into_owned(),
        )
    }

    /// The sky case the network sees: no turbidity, the sun's zenith.
    #[must_use]
    pub fn case(&self) -> SkyCase {
        SkyCase {
            turbidity: 0.0,
            sun_zenith: self.sun_zenith,
        }
    }
}

/// Every `stride`-th pixel of a frame's upper hemisphere, in the frame's own coordinates:
/// radiance (exposure removed), validity, and the pixel's direction and solid angle. Grids of
/// frames of one sequence are aligned pixel for pixel.
#[derive(Debug, Clone, Default)]
pub struct EvalGrid {
    /// Grid columns.
    pub columns: usize,
    /// Grid rows.
    pub rows: usize,
    /// Directions (pixel centres).
    pub dirs: Vec<Vec3>,
    /// Radiance, linear RGB.
    pub values: Vec<Vec3>,
    /// Whether the pixel is usable sky.
    pub valid: Vec<bool>,
    /// Solid angle each grid pixel stands for (its own times stride²), steradians.
    pub solid_angle: Vec<f64>,
}

impl EvalGrid {
    /// Samples `image` (full sphere) at `stride`, validity from `valid` (upper hemisphere).
    #[must_use]
    pub fn sample(image: &RgbImage, valid: &[bool], stride: usize, scale: f32) -> Self {
        let (w, h) = (image.width, image.height);
        let grid = sky_core::geom::Equirect::new(
            u32::try_from(w).unwrap_or(u32::MAX),
            u32::try_from(h).unwrap_or(u32::MAX),
            sky_core::geom::Extent::Sphere,
        )
        .unwrap_or_else(|_| unreachable!("checked by the loader"));
        let mut out = Self {
            columns: (stride / 2..w).step_by(stride).len(),
            rows: (stride / 2..h / 2).step_by(stride).len(),
            ..Self::default()
        };
        #[allow(clippy::cast_precision_loss)]
        let cells = (stride * stride) as f64;
        for y in (stride / 2..h / 2).step_by(stride) {
            let omega = f64::from(grid.solid_angle(u32::try_from(y).unwrap_or(u32::MAX))) * cells;
            for x in (stride / 2..w).step_by(stride) {
                out.dirs.push(sun::pixel_direction(&grid, x, y));
                out.values.push(image.pixels[y * w + x] * scale);
                out.valid.push(valid[y * w + x]);
                out.solid_angle.push(omega);
            }
        }
        out
    }

    /// Irradiance over the valid pixels (seed 000 eq. 11, restricted to the visible sky):
    /// Σ luminance · cos θ · Ω, with `values` in place of the frame's own when given.
    #[must_use]
    pub fn irradiance(&self, values: &[Vec3], use_pixel: &[bool]) -> f64 {
        (0..self.dirs.len())
            .filter(|&i| use_pixel[i])
            .map(|i| {
                f64::from(sky_core::color::luminance(values[i]))
                    * f64::from(self.dirs[i].z).max(0.0)
                    * self.solid_angle[i]
            })
            .sum()
    }
}

/// NRMSE (seed 000 §IV-A, as [`dataset::nrmse`]) of `predicted` against `reference` over the
/// pixels where `use_pixel` holds.
#[must_use]
pub fn masked_nrmse(reference: &[Vec3], predicted: &[Vec3], use_pixel: &[bool]) -> f64 {
    let pick = |v: &[Vec3]| -> Vec<Vec3> {
        v.iter()
            .zip(use_pixel)
            .filter(|(_, u)| **u)
            .map(|(p, _)| *p)
            .collect()
    };
    dataset::nrmse(&pick(reference), &pick(predicted))
}

impl Sequence {
    /// The training set of the frames for which `include(k)` holds: inputs
    /// {0, θ_sun, v_x, v_y, v_z, d} (seed 000 §III-B, turbidity input zeroed), one case per
    /// frame.
    #[must_use]
    pub fn data_set(&self, include: impl Fn(usize) -> bool) -> DataSet {
        let mut set = DataSet::default();
        for (_, frame) in self.frames.iter().enumerate().filter(|(k, _)| include(*k)) {
            let case = set.cases.len();
            set.cases.push(frame.case());
            for (v, t) in frame.views.iter().zip(&frame.targets) {
                set.inputs.push(dataset::input(0.0, frame.sun_zenith, *v));
                set.targets.push(*t);
                set.case.push(case);
            }
        }
        set
    }

    /// The range of sun zenith angles of the frames, radians.
    #[must_use]
    pub fn sun_zenith_range(&self) -> (f64, f64) {
        self.frames
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), f| {
                (lo.min(f.sun_zenith), hi.max(f.sun_zenith))
            })
    }
}

/// A progress bar of `len` steps labelled `what`.
pub(crate) fn progress_bar(len: usize, what: &str) -> ProgressBar {
    let bar = ProgressBar::new(len as u64);
    bar.set_style(
        ProgressStyle::with_template("{spinner} {elapsed:>4} [{bar:30}] {pos}/{len} {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
    );
    bar.set_message(what.to_string());
    bar
}
