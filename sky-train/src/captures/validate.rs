//! Training a neural sky on a capture sequence, and seed 000 §IV-A's cross-validation: "an
//! image from the database was chosen and a network was trained with the images in the database
//! except for that chosen image. The chosen image was then used to test against the output of
//! the ANN using normalized RMSE. For each image in the database this process is repeated and
//! the mean of all obtained errors is calculated." Beside each left-out frame's NRMSE: its
//! irradiance (eq. 11) and, for frames with a neighbour on each side, the NRMSE of plain linear
//! blending of those two captures (what one would do without the network, §IV-B).

use std::fmt::Write as _;
use std::time::Instant;

use anyhow::Result;
use sky_core::Vec3;

use super::{Frame, Sequence, masked_nrmse};
use crate::train::{self, TrainConfig, Trained, Validation};

/// Seed 000's Table 1 figure for the Kider sequence (12 frames): mean NRMSE 0.0118.
pub const PAPER_KIDER_NRMSE: f64 = 0.0118;
/// Seed 000's Table 1 figure for the Egypt sequence (6 frames): mean NRMSE 0.0038.
pub const PAPER_EGYPT_NRMSE: f64 = 0.0038;

/// The training configuration for captured skies: the paper's 6-12-3 network, LM, NRMSE only
/// (the views sample the visible sky uniformly in solid angle, not the whole hemisphere the
/// irradiance residual of [`crate::train`] assumes).
#[must_use]
pub fn config() -> TrainConfig {
    TrainConfig {
        max_iterations: 150,
        max_seconds: 60.0,
        patience: 20,
        irradiance_weight: 0.0,
        // The rest as for the other sky without a turbidity input (AOAS); its `sampling` is
        // not used: captured views come from the frames.
        ..TrainConfig::new(crate::sources::ModelKind::Aoas)
    }
}

/// Every this-many-th pixel of a frame's evaluation grid is used for early stopping.
const VALIDATION_STRIDE: usize = 5;

/// Early stopping on some frames of a sequence (every [`VALIDATION_STRIDE`]-th pixel of their
/// evaluation grids).
struct Frames<'a> {
    frames: Vec<&'a Frame>,
}

impl Validation for Frames<'_> {
    fn mean_nrmse(&self, trained: &Trained) -> f64 {
        let sum: f64 = self
            .frames
            .iter()
            .map(|f| {
                let keep: Vec<usize> = (0..f.eval.dirs.len()).step_by(VALIDATION_STRIDE).collect();
                let dirs: Vec<Vec3> = keep.iter().map(|&i| f.eval.dirs[i]).collect();
                let reference: Vec<Vec3> = keep.iter().map(|&i| f.eval.values[i]).collect();
                let valid: Vec<bool> = keep.iter().map(|&i| f.eval.valid[i]).collect();
                let predicted = trained.predict(f.case(), &dirs, f.sun.azimuth);
                masked_nrmse(&reference, &predicted, &valid)
            })
            .sum();
        #[allow(clippy::cast_precision_loss)]
        let n = self.frames.len().max(1) as f64;
        sum / n
    }
}

/// Trains one network on every frame of `seq` except `left_out`.
///
/// # Errors
/// When training fails (a checkpoint cannot be written).
pub fn train_frames(
    seq: &Sequence,
    config: &TrainConfig,
    left_out: Option<usize>,
) -> Result<Trained> {
    let set = seq.data_set(|k| Some(k) != left_out);
    let validation = Frames {
        frames: seq
            .frames
            .iter()
            .enumerate()
            .filter(|(k, _)| Some(*k) != left_out)
            .map(|(_, f)| f)
            .collect(),
    };
    train::train(config, &set, &validation)
}

/// The network's radiance at a frame's evaluation pixels, in the frame's coordinates (the sun
/// at the azimuth found in the image, eq. 10).
#[must_use]
pub fn predict(trained: &Trained, frame: &Frame) -> Vec<Vec3> {
    trained.predict(frame.case(), &frame.eval.dirs, frame.sun.azimuth)
}

/// Linear blending of `seq`'s frames `k − 1` and `k + 1` at frame `k`'s time (halfway when the
/// sequence has no times), and the pixels where all three frames are usable sky.
#[must_use]
pub fn blend_neighbours(seq: &Sequence, k: usize) -> Option<(Vec<Vec3>, Vec<bool>)> {
    let (prev, frame, next) = (
        seq.frames.get(k.checked_sub(1)?)?,
        &seq.frames[k],
        seq.frames.get(k + 1)?,
    );
    let w = match (prev.time, frame.time, next.time) {
        (Some(a), Some(t), Some(b)) => (t.0 - a.0) / (b.0 - a.0),
        _ => 0.5,
    };
    #[allow(clippy::cast_possible_truncation)]
    let w = w as f32;
    let values = prev
        .eval
        .values
        .iter()
        .zip(&next.eval.values)
        .map(|(a, b)| *a * (1.0 - w) + *b * w)
        .collect();
    let valid = (0..frame.eval.valid.len())
        .map(|i| prev.eval.valid[i] && frame.eval.valid[i] && next.eval.valid[i])
        .collect();
    Some((values, valid))
}

/// One left-out frame.
#[derive(Debug, Clone)]
pub struct FrameResult {
    /// The frame's file name.
    pub name: String,
    /// The sun's zenith angle, degrees.
    pub sun_zenith_deg: f64,
    /// NRMSE of the network trained without this frame, over the frame's usable sky.
    pub nrmse: f64,
    /// Irradiance of the frame over its usable sky (eq. 11), in the frames' units.
    pub irradiance_reference: f64,
    /// The same of the network.
    pub irradiance_network: f64,
    /// With a neighbour on each side: (network NRMSE, linear blending NRMSE), both over the
    /// pixels usable in all three frames.
    pub blend: Option<(f64, f64)>,
    /// The network trained without this frame.
    pub trained: Trained,
}

/// Leave-one-out cross-validation of a sequence.
#[derive(Debug, Clone)]
pub struct CrossValidation {
    /// Per frame, in order.
    pub frames: Vec<FrameResult>,
    /// Wall seconds.
    pub seconds: f64,
}

impl CrossValidation {
    /// Mean NRMSE over the frames (seed 000 Table 1).
    #[must_use]
    pub fn mean_nrmse(&self) -> f64 {
        mean(self.frames.iter().map(|f| f.nrmse))
    }

    /// Mean relative irradiance difference |I_net − I| / I (seed 000 Table 2, relative).
    #[must_use]
    pub fn mean_irradiance_relative(&self) -> f64 {
        mean(self.frames.iter().map(|f| {
            (f.irradiance_network - f.irradiance_reference).abs() / f.irradiance_reference
        }))
    }

    /// Mean (network, linear blending) NRMSE over the frames with two neighbours.
    #[must_use]
    pub fn mean_blend(&self) -> (f64, f64) {
        let b: Vec<(f64, f64)> = self.frames.iter().filter_map(|f| f.blend).collect();
        (mean(b.iter().map(|x| x.0)), mean(b.iter().map(|x| x.1)))
    }

    /// The per-frame table and the means.
    #[must_use]
    pub fn report(&self) -> String {
        let mut s = String::from(
            "leave-one-out cross-validation (seed 000 IV-A): each frame against the network trained on the others\n\
             frame                      sun_zenith_deg  nrmse     irradiance_ref  irradiance_net  rel_diff   blend: network_nrmse  linear_nrmse  ratio\n",
        );
        for f in &self.frames {
            let rel = (f.irradiance_network - f.irradiance_reference) / f.irradiance_reference;
            let blend = f.blend.map_or_else(
                || "(no neighbour on one side)".to_string(),
                |(n, l)| format!("{n:.5}               {l:.5}       {:.2}", n / l),
            );
            let _ = writeln!(
                s,
                "{:<26} {:>14.2}  {:.5}   {:>14.6}  {:>14.6}  {:>+8.3}%  {blend}",
                f.name,
                f.sun_zenith_deg,
                f.nrmse,
                f.irradiance_reference,
                f.irradiance_network,
                100.0 * rel
            );
        }
        let (n, l) = self.mean_blend();
        let _ = writeln!(
            s,
            "LOO mean NRMSE {:.5} over {} frames (seed 000 Table 1: Kider {PAPER_KIDER_NRMSE}, Egypt {PAPER_EGYPT_NRMSE})",
            self.mean_nrmse(),
            self.frames.len()
        );
        let _ = writeln!(
            s,
            "mean irradiance difference {:.3}% (eq. 11, over the visible sky)",
            100.0 * self.mean_irradiance_relative()
        );
        let _ = writeln!(
            s,
            "left-out frames with two neighbours: network NRMSE {n:.5}, linear blending of the neighbours {l:.5} (network / blending {:.2})",
            n / l
        );
        s
    }
}

fn mean(values: impl Iterator<Item = f64>) -> f64 {
    let (sum, n) = values.fold((0.0, 0usize), |(s, n), v| (s + v, n + 1));
    #[allow(clippy::cast_precision_loss)]
    let n = n.max(1) as f64;
    sum / n
}

/// Seed 000 §IV-A's leave-one-out protocol over `seq` (one training per frame).
///
/// # Errors
/// When a training fails.
pub fn cross_validate(seq: &Sequence, config: &TrainConfig) -> Result<CrossValidation> {
    let start = Instant::now();
    let bar = if config.progress {
        super::progress_bar(seq.frames.len(), "leave-one-out")
    } else {
        indicatif::ProgressBar::hidden()
    };
    let quiet = TrainConfig {
        progress: false,
        ..config.clone()
    };
    let mut frames = Vec::with_capacity(seq.frames.len());
    for (k, frame) in seq.frames.iter().enumerate() {
        bar.set_message(format!("leaving out {}", frame.name()));
        let trained = train_frames(seq, &quiet, Some(k))?;
        let predicted = predict(&trained, frame);
        let eval = &frame.eval;
        let blend = blend_neighbours(seq, k).map(|(blended, both)| {
            (
                masked_nrmse(&eval.values, &predicted, &both),
                masked_nrmse(&eval.values, &blended, &both),
            )
        });
        frames.push(FrameResult {
            name: frame.name(),
            sun_zenith_deg: frame.sun_zenith.to_degrees(),
            nrmse: masked_nrmse(&eval.values, &predicted, &eval.valid),
            irradiance_reference: eval.irradiance(&eval.values, &eval.valid),
            irradiance_network: eval.irradiance(&predicted, &eval.valid),
            blend,
            trained,
        });
        bar.inc(1);
    }
    bar.finish_and_clear();
    Ok(CrossValidation {
        frames,
        seconds: start.elapsed().as_secs_f64(),
    })
}
