//! The paper's error measures (seed 000 §IV-A): NRMSE per test image averaged over the test set
//! (Table 1) and irradiance per sun position (eq. 11, Table 2), for any network against its
//! reference model; and reference / network / difference images like Figs. 6-7.

use std::fmt::Write as _;
use std::path::Path;

use anyhow::Result;
use rayon::prelude::*;
use sky_core::Vec3;
use sky_core::geom::{Equirect, Extent};

use crate::image_io::{self, RgbImage};
use crate::render;
use crate::sources::{self, ModelKind, SkyParams, SkySource};
use crate::train::dataset::{self, PaperFigures, SkyCase, TEST_SUN_AZIMUTH};

/// One test image's figures.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImageResult {
    /// The sky.
    pub case: SkyCase,
    /// Its NRMSE.
    pub nrmse: f64,
    /// Reference irradiance (eq. 11, luminance, the model's units).
    pub irradiance_reference: f64,
    /// Network irradiance.
    pub irradiance_network: f64,
}

/// A network's figures on the paper's test protocol.
#[derive(Debug, Clone, PartialEq)]
pub struct Evaluation {
    /// The reference model.
    pub model: ModelKind,
    /// Per test image.
    pub images: Vec<ImageResult>,
}

impl Evaluation {
    /// Mean NRMSE over the test images (Table 1).
    #[must_use]
    pub fn mean_nrmse(&self) -> f64 {
        mean(self.images.iter().map(|r| r.nrmse))
    }

    /// Mean over test images of |I_network − I_reference| / I_reference (Table 2, relative).
    #[must_use]
    pub fn mean_irradiance_relative(&self) -> f64 {
        mean(self.images.iter().map(|r| {
            (r.irradiance_network - r.irradiance_reference).abs() / r.irradiance_reference
        }))
    }

    /// Seed 000's Tables 1 and 2 beside ours.
    #[must_use]
    pub fn report(&self) -> String {
        report(self.model, &[("ours", self)])
    }
}

/// One of an evaluation's figures, as [`Evaluation::mean_nrmse`].
type Figure = fn(&Evaluation) -> f64;

/// Seed 000's Tables 1 and 2 for `model` beside one column per labelled evaluation (labels of at
/// most 10 characters keep the columns aligned).
#[must_use]
pub fn report(model: ModelKind, columns: &[(&str, &Evaluation)]) -> String {
    let mut s = String::new();
    let paper = PaperFigures::of(model);
    let images = columns.first().map_or(0, |(_, e)| e.images.len());
    let _ = writeln!(
        s,
        "{model}: {images} test images ({} directions each, upper hemisphere 128x32, sun azimuth {TEST_SUN_AZIMUTH} rad)",
        128 * 32
    );
    let p = |f: Option<f64>| f.map_or_else(|| "-".into(), |v| format!("{v:.5}"));
    let _ = write!(s, "{:<44} {:>10}", "", "paper");
    for (label, _) in columns {
        let _ = write!(s, " {label:>10}");
    }
    let rows: [(&str, Option<f64>, Figure); 2] = [
        (
            "Table 1: mean NRMSE",
            paper.map(|f| f.nrmse),
            Evaluation::mean_nrmse,
        ),
        (
            "Table 2: mean |irradiance difference| / ref",
            paper.map(|f| f.irradiance_relative()),
            Evaluation::mean_irradiance_relative,
        ),
    ];
    for (name, figure, of) in rows {
        let _ = write!(s, "\n{name:<44} {:>10}", p(figure));
        for (_, evaluation) in columns {
            let _ = write!(s, " {:>10.5}", of(evaluation));
        }
    }
    s.push('\n');
    s
}

fn mean(values: impl Iterator<Item = f64>) -> f64 {
    let (sum, n) = values.fold((0.0, 0usize), |(s, n), v| (s + v, n + 1));
    #[allow(clippy::cast_precision_loss)]
    if n == 0 { 0.0 } else { sum / n as f64 }
}

/// Evaluates `network` (a sky source per test case) against `model` on the paper's test set.
///
/// # Errors
/// When a case is rejected by either model.
pub fn evaluate(
    model: ModelKind,
    network: &(dyn Fn(&SkyParams) -> Result<Box<dyn SkySource>> + Sync),
) -> Result<Evaluation> {
    let test = dataset::paper_test_set(model)?;
    let dirs = dataset::test_directions();
    let images = test
        .par_iter()
        .map(|image| {
            let params = params_of(model, image.case);
            let source = network(&params)?;
            let mut predicted = vec![Vec3::ZERO; dirs.len()];
            source.rgb_batch(&dirs, &mut predicted);
            Ok(ImageResult {
                case: image.case,
                nrmse: dataset::nrmse(&image.reference, &predicted),
                irradiance_reference: dataset::irradiance(&image.reference),
                irradiance_network: dataset::irradiance(&predicted),
            })
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(Evaluation { model, images })
}

fn params_of(model: ModelKind, case: SkyCase) -> SkyParams {
    SkyParams::for_model(
        model,
        case.sun_zenith.to_degrees(),
        TEST_SUN_AZIMUTH.to_degrees(),
        case.turbidity,
    )
}

/// Writes reference | network | 10 × |difference| side by side, like seed 000's Figs. 6-7, for
/// one sky, as a PNG of the upper hemisphere `width` pixels wide per panel.
///
/// # Errors
/// On I/O errors or rejected parameters.
pub fn write_comparison(
    path: &Path,
    model: ModelKind,
    network: &dyn SkySource,
    params: &SkyParams,
    width: u32,
) -> Result<()> {
    let grid = Equirect::new(width, (width / 4).max(1), Extent::UpperHemisphere)?;
    let reference = sources::build(model, params)?;
    let r = render::equirect(&*reference, &grid);
    let n = render::equirect(network, &grid);
    let scale = render::auto_exposure(&r, &grid);
    let (w, h) = (r.width, r.height);
    let mut sheet = RgbImage {
        width: 3 * w,
        height: h,
        pixels: vec![Vec3::ZERO; 3 * w * h],
    };
    for y in 0..h {
        for x in 0..w {
            let (a, b) = (r.get(x, y), n.get(x, y));
            let row = y * 3 * w;
            sheet.pixels[row + x] = a * scale;
            sheet.pixels[row + w + x] = b * scale;
            sheet.pixels[row + 2 * w + x] = (a - b).abs() * scale * 10.0;
        }
    }
    image_io::write_png(path, &sheet, 1.0)
}
