//! The charts of `sky-train daylight --plot-illuminance / --plot-cct` (docs/daylight.md), drawn
//! by plotters' bitmap backend in the vendored font ([`crate::plot`]) and written atomically
//! as PNG.

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

/// An x-axis tick's label: its value to a millionth of a degree, shortest form (`10.5`, not
/// `10` for every tick of a one-degree axis).
#[must_use]
pub fn tick_label(v: f64) -> String {
    crate::csv_output::compact((v * 1e6).round() / 1e6)
}

/// The charts' size in pixels.
pub const SIZE: (u32, u32) = (1200, 750);

/// Draws `curves` against sun elevation over `x` (points outside it left out), on a log y
/// axis over `y` when `log`, to the PNG file `path`.
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
    use crate::plot::{FONT, register_font};
    register_font()?;
    let (width, height) = SIZE;
    let mut pixels = vec![255u8; 3 * width as usize * height as usize];
    {
        let root = BitMapBackend::with_buffer(&mut pixels, SIZE).into_drawing_area();
        root.fill(&WHITE).map_err(|e| anyhow!("{e}"))?;
        let mut builder = ChartBuilder::on(&root);
        builder
            .caption(title, (FONT, 24))
            .margin(16)
            .x_label_area_size(52)
            .y_label_area_size(96);
        macro_rules! draw {
            ($chart:expr) => {{
                let mut chart = $chart;
                chart
                    .configure_mesh()
                    .x_desc("sun elevation (degrees, geometric)")
                    .y_desc(y_desc)
                    .x_label_formatter(&|v| tick_label(*v))
                    .y_label_formatter(&|v| {
                        if *v >= 1.0 {
                            format!("{v:.0}")
                        } else {
                            format!("{v}")
                        }
                    })
                    .label_style((FONT, 15))
                    .axis_desc_style((FONT, 17))
                    .draw()
                    .map_err(|e| anyhow!("{e}"))?;
                for c in curves {
                    let color = c.color;
                    let pts = c.points.iter().copied().filter(|p| {
                        p.1.is_finite() && (!log || p.1 > 0.0) && (x.0..=x.1).contains(&p.0)
                    });
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
                    .label_font((FONT, 15))
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
    crate::image_io::write_png_srgb8(path, width, height, &pixels)
}
