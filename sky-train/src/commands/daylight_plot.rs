//! The charts of `sky-train daylight --plot-illuminance / --plot-cct` (docs/daylight.md), drawn
//! by plotters as SVG and written atomically.

use std::path::Path;

use anyhow::{Result, anyhow};
use plotters::prelude::*;

/// One curve: a name, a colour, whether dashed, and its (elevation, value) points.
pub struct Curve {
    /// The legend's text.
    pub name: String,
    /// Its colour.
    pub color: RGBColor,
    /// Drawn as points instead of a line.
    pub points_only: bool,
    /// (sun elevation in degrees, value).
    pub points: Vec<(f64, f64)>,
}

/// Draws `curves` against sun elevation over `x`, on a log y axis over `y` when `log`, to the
/// SVG file `path`.
///
/// # Errors
/// A drawing error, or the file cannot be written.
pub fn chart(
    path: &Path,
    title: &str,
    y_desc: &str,
    x: (f64, f64),
    y: (f64, f64),
    log: bool,
    curves: &[Curve],
) -> Result<()> {
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (960, 600)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| anyhow!("{e}"))?;
        let mut builder = ChartBuilder::on(&root);
        builder
            .caption(title, ("sans-serif", 22))
            .margin(16)
            .x_label_area_size(44)
            .y_label_area_size(80);
        macro_rules! draw {
            ($chart:expr) => {{
                let mut chart = $chart;
                chart
                    .configure_mesh()
                    .x_desc("sun elevation (degrees, geometric)")
                    .y_desc(y_desc)
                    .draw()
                    .map_err(|e| anyhow!("{e}"))?;
                for c in curves {
                    let color = c.color;
                    let pts = c
                        .points
                        .iter()
                        .copied()
                        .filter(|p| p.1.is_finite() && (!log || p.1 > 0.0));
                    if c.points_only {
                        chart
                            .draw_series(pts.map(|p| Circle::new(p, 5, color.filled())))
                            .map_err(|e| anyhow!("{e}"))?
                            .label(&c.name)
                            .legend(move |(x, y)| Circle::new((x + 10, y), 5, color.filled()));
                    } else {
                        chart
                            .draw_series(LineSeries::new(pts, color.stroke_width(2)))
                            .map_err(|e| anyhow!("{e}"))?
                            .label(&c.name)
                            .legend(move |(x, y)| {
                                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                            });
                    }
                }
                chart
                    .configure_series_labels()
                    .position(SeriesLabelPosition::LowerRight)
                    .background_style(WHITE.mix(0.85))
                    .border_style(BLACK)
                    .draw()
                    .map_err(|e| anyhow!("{e}"))?;
            }};
        }
        if log {
            draw!(
                builder
                    .build_cartesian_2d(x.0..x.1, (y.0..y.1).log_scale())
                    .map_err(|e| anyhow!("{e}"))?
            );
        } else {
            draw!(
                builder
                    .build_cartesian_2d(x.0..x.1, y.0..y.1)
                    .map_err(|e| anyhow!("{e}"))?
            );
        }
        root.present().map_err(|e| anyhow!("{e}"))?;
    }
    crate::image_io::write_text(path, &svg)
}
