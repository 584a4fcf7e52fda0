//! Line charts drawn by `plotters` (its bitmap backend) and written as PNG: an integer x axis, a
//! logarithmic y axis, lines with markers, a legend. The text is DejaVu Sans, vendored in
//! `sky-train/fonts/` with its licence and compiled in (plotters' `ab_glyph` feature), so a
//! chart looks the same on any machine and needs no system font.

use std::path::Path;
use std::sync::OnceLock;

use anyhow::{Result, anyhow};
use plotters::prelude::*;

use crate::image_io;

/// The font family name the charts use, registered once from the vendored file.
pub(crate) const FONT: &str = "sans-serif";

/// DejaVu Sans 2.37 (Bitstream Vera licence, `sky-train/fonts/LICENSE`).
static FONT_FILE: &[u8] = include_bytes!("../fonts/DejaVuSans.ttf");

/// Registers the vendored font as [`FONT`] (once).
///
/// # Errors
/// The font file does not load.
pub(crate) fn register_font() -> Result<()> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let ok = *REGISTERED
        .get_or_init(|| plotters::style::register_font(FONT, FontStyle::Normal, FONT_FILE).is_ok());
    if ok {
        Ok(())
    } else {
        Err(anyhow!("the vendored chart font does not load"))
    }
}

/// One line of a chart.
#[derive(Debug, Clone)]
pub struct Series {
    /// The legend text.
    pub label: String,
    /// sRGB colour, 8 bits per channel.
    pub colour: [u8; 3],
    /// `(x, y)` points; y must be positive and finite (log axis); others are skipped.
    pub points: Vec<(i32, f64)>,
    /// Square markers (else round).
    pub square: bool,
}

/// A chart with an integer x axis and a logarithmic y axis.
#[derive(Debug, Clone)]
pub struct LogChart {
    /// The title, above the plot.
    pub title: String,
    /// The x axis label, with its unit.
    pub x_label: String,
    /// The y axis label, with its unit.
    pub y_label: String,
    /// Integer x ticks from `x_range.0` to `x_range.1`.
    pub x_range: (i32, i32),
    /// The lines.
    pub series: Vec<Series>,
}

impl LogChart {
    /// Draws the chart as `width` × `height` 8-bit sRGB pixels, row by row (white background).
    ///
    /// # Errors
    /// A size below 200 × 150 pixels, or a drawing error of plotters.
    pub fn draw(&self, width: u32, height: u32) -> Result<Vec<u8>> {
        if width < 200 || height < 150 {
            return Err(anyhow!(
                "a chart needs at least 200 x 150 pixels, not {width} x {height}"
            ));
        }
        register_font()?;
        let mut pixels = vec![255u8; 3 * width as usize * height as usize];
        {
            let root = BitMapBackend::with_buffer(&mut pixels, (width, height)).into_drawing_area();
            root.fill(&WHITE)?;
            let (lo, hi) = self.y_bounds();
            let (x0, x1) = self.x_range;
            let mut chart = ChartBuilder::on(&root)
                .caption(&self.title, (FONT, 20))
                .margin(12)
                .x_label_area_size(48)
                .y_label_area_size(72)
                // A quarter step beyond the ends, so that the end markers show whole.
                .build_cartesian_2d(
                    f64::from(x0) - 0.25..f64::from(x1) + 0.25,
                    (lo..hi).log_scale(),
                )?;
            chart
                .configure_mesh()
                .x_labels(usize::try_from(x1 - x0 + 1).unwrap_or(1))
                .x_label_formatter(&|v| {
                    if (v - v.round()).abs() < 1e-6 {
                        format!("{v:.0}")
                    } else {
                        String::new()
                    }
                })
                .x_desc(&self.x_label)
                .y_desc(&self.y_label)
                .y_label_formatter(&|v| format!("{v}"))
                .label_style((FONT, 14))
                .axis_desc_style((FONT, 16))
                .light_line_style(WHITE)
                .draw()?;
            for s in &self.series {
                let colour = RGBColor(s.colour[0], s.colour[1], s.colour[2]);
                let points: Vec<(f64, f64)> = s
                    .points
                    .iter()
                    .filter(|p| p.1 > 0.0 && p.1.is_finite())
                    .map(|&(x, y)| (f64::from(x), y))
                    .collect();
                let line = chart.draw_series(LineSeries::new(
                    points.iter().copied(),
                    colour.stroke_width(2),
                ))?;
                let swatch = move |(x, y): (i32, i32)| {
                    PathElement::new(vec![(x - 10, y), (x + 10, y)], colour.stroke_width(2))
                };
                if s.square {
                    line.label(&s.label).legend(move |p| {
                        EmptyElement::at(p)
                            + swatch((0, 0))
                            + Rectangle::new([(-4, -4), (4, 4)], colour.filled())
                    });
                    chart.draw_series(points.iter().map(|&p| {
                        EmptyElement::at(p) + Rectangle::new([(-4, -4), (4, 4)], colour.filled())
                    }))?;
                } else {
                    line.label(&s.label).legend(move |p| {
                        EmptyElement::at(p)
                            + swatch((0, 0))
                            + Circle::new((0, 0), 4, colour.filled())
                    });
                    chart
                        .draw_series(points.iter().map(|&p| Circle::new(p, 4, colour.filled())))?;
                }
            }
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::UpperRight)
                .label_font((FONT, 14))
                .background_style(WHITE.mix(0.9))
                .border_style(BLACK)
                .draw()?;
            root.present()?;
        }
        Ok(pixels)
    }

    /// Draws the chart and writes it to `path` as PNG (atomically).
    ///
    /// # Errors
    /// As [`draw`](Self::draw), or a failed write.
    pub fn write_png(&self, path: &Path, width: u32, height: u32) -> Result<()> {
        let pixels = self.draw(width, height)?;
        image_io::write_png_srgb8(path, width, height, &pixels)
    }

    /// The y range: whole decades around the data, one more above for the legend.
    #[allow(clippy::cast_possible_truncation)] // decade exponents of finite f64
    fn y_bounds(&self) -> (f64, f64) {
        let (lo, hi) = self
            .series
            .iter()
            .flat_map(|s| s.points.iter().map(|p| p.1))
            .filter(|y| *y > 0.0 && y.is_finite())
            .fold((f64::INFINITY, 0.0f64), |(a, b), y| (a.min(y), b.max(y)));
        let (d0, d1) = if lo.is_finite() {
            (lo.log10().floor() as i32, hi.log10().ceil() as i32)
        } else {
            (-1, 0)
        };
        (10f64.powi(d0), 10f64.powi(d1.max(d0 + 1) + 1))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn chart() -> LogChart {
        LogChart {
            title: "test chart".into(),
            x_label: "bands N".into(),
            y_label: "error, %".into(),
            x_range: (1, 7),
            series: vec![
                Series {
                    label: "rising".into(),
                    colour: [200, 0, 0],
                    points: (1..=7).map(|x| (x, 10f64.powi(x - 4))).collect(),
                    square: true,
                },
                Series {
                    label: "flat".into(),
                    colour: [0, 0, 200],
                    points: (1..=7).map(|x| (x, 0.5)).collect(),
                    square: false,
                },
            ],
        }
    }

    fn count(pixels: &[u8], colour: [u8; 3]) -> usize {
        pixels.chunks(3).filter(|p| *p == colour).count()
    }

    #[test]
    fn draws_each_series_its_markers_and_text() {
        let (w, h) = (640u32, 400u32);
        let pixels = chart().draw(w, h).expect("chart");
        assert_eq!(pixels.len(), 3 * (w * h) as usize);
        // Two lines across the plot (2 px wide, ~500 px long) and markers in their colours.
        assert!(
            count(&pixels, [200, 0, 0]) > 800,
            "{}",
            count(&pixels, [200, 0, 0])
        );
        assert!(
            count(&pixels, [0, 0, 200]) > 800,
            "{}",
            count(&pixels, [0, 0, 200])
        );
        // The title's glyphs: dark pixels in the top band, where no axis is.
        let top_dark = pixels[..3 * (w * 30) as usize]
            .chunks(3)
            .filter(|p| p.iter().all(|&c| c < 128))
            .count();
        assert!(top_dark > 50, "{top_dark} dark pixels in the title band");
    }

    #[test]
    fn the_flat_line_is_one_horizontal_band() {
        let (w, h) = (640u32, 400u32);
        let pixels = chart().draw(w, h).expect("chart");
        // The rows the blue line runs along: one band of at most 4 rows (2 px stroke, anti-aliased).
        let rows: Vec<usize> = (0..h as usize)
            .filter(|&y| {
                (0..w as usize)
                    .filter(|&x| pixels[3 * (y * w as usize + x)..][..3] == [0, 0, 200])
                    .count()
                    > 300
            })
            .collect();
        assert!(!rows.is_empty() && rows.len() <= 4, "{rows:?}");
    }

    #[test]
    fn refuses_a_tiny_chart() {
        assert!(chart().draw(100, 100).is_err());
    }
}
