//! `fit-sh --report DIR`: the errors of eqs. 2-3 over the whole parameter domain on points off
//! the fit grid (a table and a chart like the paper's Fig. 3), and renders of the worst case
//! like its Figs. 2 and 4.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use anyhow::Result;
use sky_core::Vec3;
use sky_core::geom::{Equirect, Extent};
use sky_core::sh::{ShSky, filter};

use super::eval::{self, WorstCase};
use super::projection::{BANDS, COEFFICIENTS, Coefficients, Integrator};
use super::{FitConfig, ShFit, project_all};
use crate::image_io::{self, RgbImage};
use crate::plot::{LogChart, Series};
use crate::render;
use crate::sources::SkySource;

/// The evaluation grid: sun zenith every 2.5° over the fitted range and turbidity every 0.25,
/// both ends included (37 × 17 points for Preetham); none of them is a Chebyshev point of the
/// fit grid.
#[must_use]
pub fn test_points(config: &FitConfig) -> Vec<(f64, f64)> {
    let (t0, t1) = (
        f64::from(config.sun_zenith[0]),
        f64::from(config.sun_zenith[1]),
    );
    let (u0, u1) = (
        f64::from(config.turbidity[0]),
        f64::from(config.turbidity[1]),
    );
    let grid = |lo: f64, hi: f64, step: f64| -> Vec<f64> {
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let n = ((hi - lo) / step).round() as usize;
        #[allow(clippy::cast_precision_loss)]
        (0..=n)
            .map(|k| lo + (hi - lo) * k as f64 / n as f64)
            .collect()
    };
    let thetas = grid(t0, t1, 2.5f64.to_radians());
    let taus = grid(u0, u1, 0.25);
    thetas
        .iter()
        .flat_map(|&t| taus.iter().map(move |&u| (t, u)))
        .collect()
}

/// The errors of a fit over a set of skies.
#[derive(Debug, Clone)]
pub struct ErrorReport {
    /// The worst case per band count.
    pub worst: WorstCase,
    /// The same measures between the f32 fit and the stored tables (whose integer rows are
    /// rounded to whole steps): the quantisation's own error.
    pub quantisation: WorstCase,
    /// Skies evaluated.
    pub skies: usize,
}

/// Projects the skies at `points` and measures eqs. 2-3 against the fit's reconstruction.
///
/// # Errors
/// As [`project_all`].
pub fn errors(fit: &ShFit, points: &[(f64, f64)]) -> Result<ErrorReport> {
    let integrator = Integrator::new(fit.config.tolerance);
    let samples = project_all(&fit.config, &integrator, points)?;
    let (mut worst, mut quantisation) = (WorstCase::default(), WorstCase::default());
    for s in &samples {
        let stored = fit.evaluate(s.theta, s.tau);
        let e = eval::band_errors(&s.coefficients, &stored, s.l_min);
        worst.update(&e, (s.theta, s.tau));
        let q = eval::band_errors(&fit.evaluate_fitted(s.theta, s.tau), &stored, s.l_min);
        quantisation.update(&q, (s.theta, s.tau));
    }
    Ok(ErrorReport {
        worst,
        quantisation,
        skies: samples.len(),
    })
}

/// The errors as a Markdown table, one row per band count.
#[must_use]
pub fn markdown(fit: &ShFit, report: &ErrorReport) -> String {
    let mut s = String::new();
    writeln!(
        s,
        "| bands N | worst E_mean (eq. 3) | at (sun zenith, T) | worst E_max (eq. 2) | at (sun zenith, T) | quantisation alone: worst E_mean, E_max | table bytes |"
    )
    .ok();
    writeln!(s, "|---|---|---|---|---|---|---|").ok();
    for n in 0..BANDS {
        let (mean, (tm, um)) = report.worst.mean[n];
        let (max, (tx, ux)) = report.worst.max[n];
        writeln!(
            s,
            "| {} | {:.2e} % | {:.1}°, {:.2} | {:.2e} % | {:.1}°, {:.2} | {:.2e} %, {:.2e} % | {} |",
            n + 1,
            100.0 * mean,
            tm.to_degrees(),
            um,
            100.0 * max,
            tx.to_degrees(),
            ux,
            100.0 * report.quantisation.mean[n].0,
            100.0 * report.quantisation.max[n].0,
            fit.bytes_for_bands(n + 1)
        )
        .ok();
    }
    s
}

/// The chart of the worst E_mean and E_max per band count (like the paper's Fig. 3), in
/// percent, with the same for a second fit (`paper`: the paper's uniform degrees) in lighter
/// colours.
#[must_use]
pub fn chart(fit: &ShFit, report: &ErrorReport, paper: Option<&ErrorReport>) -> LogChart {
    LogChart {
        title: format!(
            "{} sky in SH: worst relative error over sun zenith and turbidity",
            title_case(&fit.config.model.to_string())
        ),
        x_label: "SH bands N (N\u{b2} coefficients per channel)".into(),
        y_label: "relative error, % (max over R, G, B)".into(),
        x_range: (1, 7),
        series: paper
            .into_iter()
            .flat_map(|p| {
                pair(
                    p,
                    ", the paper's degrees (13, 7)",
                    [255, 178, 149],
                    [159, 203, 255],
                )
            })
            .chain(pair(
                report,
                ", shipped tables",
                [231, 63, 28],
                [28, 89, 231],
            ))
            .collect(),
    }
}

/// The E_max and E_mean series of `report` in percent, labelled with `suffix`.
fn pair(report: &ErrorReport, suffix: &str, max: [u8; 3], mean: [u8; 3]) -> [Series; 2] {
    let points = |v: &[(f64, (f64, f64)); BANDS]| -> Vec<(i32, f64)> {
        (1..).zip(v).map(|(n, e)| (n, 100.0 * e.0)).collect()
    };
    [
        Series {
            label: format!("E_max, eq. 2{suffix}"),
            colour: max,
            points: points(&report.worst.max),
            square: true,
        },
        Series {
            label: format!("E_mean, eq. 3{suffix}"),
            colour: mean,
            points: points(&report.worst.mean),
            square: false,
        },
    ]
}

/// [`ShSky`] (any coefficients) as a [`SkySource`], for rendering.
struct Lighting(ShSky, &'static str);

impl SkySource for Lighting {
    fn describe(&self) -> String {
        self.1.to_owned()
    }

    fn rgb_batch(&self, dirs: &[Vec3], out: &mut [Vec3]) {
        for (o, d) in out.iter_mut().zip(dirs) {
            *o = self.0.series(*d);
        }
    }
}

#[allow(clippy::cast_possible_truncation)]
fn to_f32(c: &Coefficients) -> [Vec3; COEFFICIENTS] {
    c.map(|v| Vec3::new(v[0] as f32, v[1] as f32, v[2] as f32))
}

/// Stacks images of the same width vertically, each multiplied by its factor.
fn stack(images: &[(&RgbImage, f32)]) -> RgbImage {
    let width = images.first().map_or(0, |i| i.0.width);
    let mut pixels = Vec::new();
    for (img, f) in images {
        pixels.extend(img.pixels.iter().map(|p| *p * *f));
    }
    RgbImage {
        width,
        height: pixels.len() / width.max(1),
        pixels,
    }
}

/// Renders the worst case at 7 bands (by E_mean) over the whole sphere: `sh_worst_case.png`
/// like Fig. 2 (the projection's 7-band expansion, the reconstruction, and their difference
/// × `DIFFERENCE_GAIN`), and `sh_ringing.png` like Fig. 4 (the reconstruction without and with
/// the ringing filter of eq. 5, over the original sky).
///
/// # Errors
/// On a sky the model rejects or a file that cannot be written.
pub fn renders(fit: &ShFit, report: &ErrorReport, dir: &Path) -> Result<Vec<PathBuf>> {
    const DIFFERENCE_GAIN: f32 = 100.0;
    let (theta, tau) = report.worst.mean[BANDS - 1].1;
    let original = fit.config.source(theta, tau)?;
    let l_min = super::projection::minimum_luminance(&*original);
    let projected = Integrator::new(fit.config.tolerance).project(&*original, theta, 0.0, l_min)?;
    let reconstructed = to_f32(&fit.evaluate(theta, tau));
    let mut filtered = reconstructed;
    filter::apply(&mut filtered, BANDS);
    let exact = to_f32(&projected.coefficients);
    let difference: [Vec3; COEFFICIENTS] = std::array::from_fn(|i| reconstructed[i] - exact[i]);
    let grid = Equirect::new(512, 256, Extent::Sphere)?;
    let draw = |c: [Vec3; COEFFICIENTS], name| -> Result<RgbImage> {
        Ok(render::equirect(
            &Lighting(ShSky::from_coefficients(c, BANDS)?, name),
            &grid,
        ))
    };
    let sky = render::equirect(&*original, &grid);
    let scale = render::auto_exposure(&sky, &grid);
    let exact_img = draw(exact, "projection")?;
    let rec_img = draw(reconstructed, "reconstruction")?;
    let mut diff_img = draw(difference, "difference")?;
    diff_img.pixels.iter_mut().for_each(|p| *p = p.abs());
    let filtered_img = draw(filtered, "filtered")?;
    let fig2 = dir.join("sh_worst_case.png");
    image_io::write_png(
        &fig2,
        &stack(&[
            (&exact_img, scale),
            (&rec_img, scale),
            (&diff_img, scale * DIFFERENCE_GAIN),
        ]),
        1.0,
    )?;
    let fig4 = dir.join("sh_ringing.png");
    image_io::write_png(
        &fig4,
        &stack(&[(&sky, scale), (&rec_img, scale), (&filtered_img, scale)]),
        1.0,
    )?;
    Ok(vec![fig2, fig4])
}

/// Writes `sh_errors.md` and `sh_errors.png` (and the renders) into `dir`, comparing with
/// `paper` (the same model fitted with the paper's degrees) when given; returns the reports
/// and the paths.
///
/// # Errors
/// On a file that cannot be written, or as [`errors`].
pub fn write(
    fit: &ShFit,
    paper: Option<&ShFit>,
    dir: &Path,
) -> Result<(ErrorReport, Option<ErrorReport>, Vec<PathBuf>)> {
    std::fs::create_dir_all(dir)?;
    let report = errors(fit, &test_points(&fit.config))?;
    let paper_report = paper
        .map(|p| errors(p, &test_points(&p.config)))
        .transpose()?;
    let md = dir.join("sh_errors.md");
    let mut text = markdown(fit, &report);
    if let (Some(p), Some(r)) = (paper, &paper_report) {
        text += &format!(
            "\nWith the paper's degrees (13, 7) for every band ({} x {} points):\n\n{}",
            p.config.nodes_theta,
            p.config.nodes_tau,
            markdown(p, r)
        );
    }
    image_io::write_text(&md, &text)?;
    let png = dir.join("sh_errors.png");
    chart(fit, &report, paper_report.as_ref()).write_png(&png, 800, 500)?;
    let mut paths = vec![md, png];
    paths.extend(renders(fit, &report, dir)?);
    Ok((report, paper_report, paths))
}

fn title_case(s: &str) -> String {
    let mut c = s.chars();
    c.next()
        .map(|f| f.to_uppercase().chain(c).collect())
        .unwrap_or_default()
}
