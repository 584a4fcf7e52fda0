//! A small line chart drawn straight into an [`RgbImage`] (no font or plotting dependency): log
//! y axis, integer x axis, lines with markers, and labels in a built-in 5 × 7 pixel font.

use sky_core::Vec3;

use crate::image_io::RgbImage;

/// One line of a chart.
#[derive(Debug, Clone)]
pub struct Series {
    /// The legend text.
    pub label: String,
    /// Linear RGB colour.
    pub colour: Vec3,
    /// `(x, y)` points; y must be positive (log axis); others are skipped.
    pub points: Vec<(f64, f64)>,
    /// Square markers (else round).
    pub square: bool,
}

/// A chart with a logarithmic y axis.
#[derive(Debug, Clone)]
pub struct LogChart {
    /// The title, above the plot.
    pub title: String,
    /// The x axis label.
    pub x_label: String,
    /// The y axis label (written above the axis).
    pub y_label: String,
    /// Integer x ticks from `x_range.0` to `x_range.1`.
    pub x_range: (i32, i32),
    /// The lines.
    pub series: Vec<Series>,
}

const SCALE: usize = 2; // font pixels per glyph pixel
const GLYPH_W: usize = 6 * SCALE; // advance: 5 columns and a gap

impl LogChart {
    /// Draws the chart into a `width` × `height` image (white background).
    #[must_use]
    #[allow(
        clippy::cast_precision_loss,
        clippy::cast_possible_truncation,
        clippy::cast_sign_loss,
        clippy::cast_possible_wrap
    )]
    pub fn draw(&self, width: usize, height: usize) -> RgbImage {
        let mut img = RgbImage {
            width,
            height,
            pixels: vec![Vec3::ONE; width * height],
        };
        let (left, right, top, bottom) = (110usize, 30usize, 70usize, 70usize);
        let (pw, ph) = (width - left - right, height - top - bottom);
        let ys = self
            .series
            .iter()
            .flat_map(|s| s.points.iter().map(|p| p.1))
            .filter(|y| *y > 0.0 && y.is_finite());
        let (lo, hi) = ys.fold((f64::INFINITY, 0.0f64), |(a, b), y| (a.min(y), b.max(y)));
        let (d0, d1) = if lo.is_finite() {
            (lo.log10().floor() as i32, hi.log10().ceil() as i32)
        } else {
            (-1, 0)
        };
        // One decade of headroom above the data for the legend.
        let d1 = d1.max(d0 + 1) + 1;
        let (x0, x1) = (f64::from(self.x_range.0), f64::from(self.x_range.1));
        let px = |x: f64| left as f64 + (x - x0) / (x1 - x0) * pw as f64;
        let py = |y: f64| top as f64 + (f64::from(d1) - y.log10()) / f64::from(d1 - d0) * ph as f64;
        let grey = Vec3::splat(0.8);
        let black = Vec3::ZERO;
        // Grid and y labels at every decade.
        for d in d0..=d1 {
            let y = py(10f64.powi(d)) as usize;
            line(
                &mut img,
                (left as f64, y as f64),
                ((left + pw) as f64, y as f64),
                grey,
                1,
            );
            let label = format!("1e{d}");
            text(
                &mut img,
                left - 10 - label.len() * GLYPH_W,
                y - 7,
                &label,
                black,
            );
        }
        for x in self.x_range.0..=self.x_range.1 {
            let xp = px(f64::from(x));
            line(&mut img, (xp, top as f64), (xp, (top + ph) as f64), grey, 1);
            let label = x.to_string();
            text(
                &mut img,
                xp as usize - label.len() * GLYPH_W / 2,
                top + ph + 10,
                &label,
                black,
            );
        }
        // Axes.
        let (l, r, t, b) = (
            left as f64,
            (left + pw) as f64,
            top as f64,
            (top + ph) as f64,
        );
        for (a, c) in [
            ((l, t), (l, b)),
            ((l, b), (r, b)),
            ((r, t), (r, b)),
            ((l, t), (r, t)),
        ] {
            line(&mut img, a, c, black, 1);
        }
        text(
            &mut img,
            left + pw / 2 - self.x_label.len() * GLYPH_W / 2,
            top + ph + 35,
            &self.x_label,
            black,
        );
        text(&mut img, 10, top - 25, &self.y_label, black);
        text(
            &mut img,
            width / 2 - self.title.len() * GLYPH_W / 2,
            15,
            &self.title,
            black,
        );
        // Lines, markers and the legend.
        for (k, s) in self.series.iter().enumerate() {
            let pts: Vec<(f64, f64)> = s
                .points
                .iter()
                .filter(|p| p.1 > 0.0 && p.1.is_finite())
                .map(|&(x, y)| (px(x), py(y)))
                .collect();
            for w in pts.windows(2) {
                line(&mut img, w[0], w[1], s.colour, 2);
            }
            for &(x, y) in &pts {
                marker(&mut img, x, y, s.colour, s.square);
            }
            let ly = top + 12 + 22 * k;
            let lx = left + 20;
            line(
                &mut img,
                (lx as f64, ly as f64 + 7.0),
                (lx as f64 + 30.0, ly as f64 + 7.0),
                s.colour,
                2,
            );
            marker(
                &mut img,
                lx as f64 + 15.0,
                ly as f64 + 7.0,
                s.colour,
                s.square,
            );
            text(&mut img, lx + 40, ly, &s.label, black);
        }
        img
    }
}

fn put(img: &mut RgbImage, x: i64, y: i64, c: Vec3) {
    if let (Ok(x), Ok(y)) = (usize::try_from(x), usize::try_from(y))
        && x < img.width
        && y < img.height
    {
        img.pixels[y * img.width + x] = c;
    }
}

#[allow(clippy::cast_possible_truncation)]
fn line(img: &mut RgbImage, a: (f64, f64), b: (f64, f64), c: Vec3, thickness: i64) {
    let steps = ((b.0 - a.0).abs().max((b.1 - a.1).abs()).ceil() as i64).max(1);
    for i in 0..=steps {
        #[allow(clippy::cast_precision_loss)]
        let t = i as f64 / steps as f64;
        let (x, y) = (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1));
        for dx in 0..thickness {
            for dy in 0..thickness {
                put(img, x.round() as i64 + dx, y.round() as i64 + dy, c);
            }
        }
    }
}

#[allow(clippy::cast_possible_truncation)]
fn marker(img: &mut RgbImage, x: f64, y: f64, c: Vec3, square: bool) {
    let (x, y) = (x.round() as i64, y.round() as i64);
    for dx in -5..=5i64 {
        for dy in -5..=5i64 {
            if square || dx * dx + dy * dy <= 25 {
                put(img, x + dx, y + dy, c);
            }
        }
    }
}

/// Writes `s` with its top-left corner at (`x`, `y`); unknown characters are left blank.
#[allow(clippy::cast_possible_wrap)]
fn text(img: &mut RgbImage, x: usize, y: usize, s: &str, c: Vec3) {
    for (k, ch) in s.chars().enumerate() {
        let Some(rows) = glyph(ch) else { continue };
        for (r, bits) in rows.iter().enumerate() {
            for (col, b) in bits.bytes().enumerate() {
                if b == b'#' {
                    for sy in 0..SCALE {
                        for sx in 0..SCALE {
                            put(
                                img,
                                (x + k * GLYPH_W + col * SCALE + sx) as i64,
                                (y + r * SCALE + sy) as i64,
                                c,
                            );
                        }
                    }
                }
            }
        }
    }
}

/// The 5 × 7 bitmap of `ch`, for the characters the charts use.
#[allow(clippy::too_many_lines)]
fn glyph(ch: char) -> Option<[&'static str; 7]> {
    Some(match ch {
        '0' => [
            " ### ", "#   #", "#  ##", "# # #", "##  #", "#   #", " ### ",
        ],
        '1' => [
            "  #  ", " ##  ", "  #  ", "  #  ", "  #  ", "  #  ", " ### ",
        ],
        '2' => [
            " ### ", "#   #", "    #", "   # ", "  #  ", " #   ", "#####",
        ],
        '3' => [
            "#####", "   # ", "  #  ", "   # ", "    #", "#   #", " ### ",
        ],
        '4' => [
            "   # ", "  ## ", " # # ", "#  # ", "#####", "   # ", "   # ",
        ],
        '5' => [
            "#####", "#    ", "#### ", "    #", "    #", "#   #", " ### ",
        ],
        '6' => [
            "  ## ", " #   ", "#    ", "#### ", "#   #", "#   #", " ### ",
        ],
        '7' => [
            "#####", "    #", "   # ", "  #  ", " #   ", " #   ", " #   ",
        ],
        '8' => [
            " ### ", "#   #", "#   #", " ### ", "#   #", "#   #", " ### ",
        ],
        '9' => [
            " ### ", "#   #", "#   #", " ####", "    #", "   # ", " ##  ",
        ],
        '-' => [
            "     ", "     ", "     ", "#####", "     ", "     ", "     ",
        ],
        '.' => [
            "     ", "     ", "     ", "     ", "     ", " ##  ", " ##  ",
        ],
        ',' => [
            "     ", "     ", "     ", "     ", " ##  ", "  #  ", " #   ",
        ],
        ':' => [
            "     ", " ##  ", " ##  ", "     ", " ##  ", " ##  ", "     ",
        ],
        '%' => [
            "##   ", "##  #", "   # ", "  #  ", " #   ", "#  ##", "   ##",
        ],
        '(' => [
            "   # ", "  #  ", " #   ", " #   ", " #   ", "  #  ", "   # ",
        ],
        ')' => [
            " #   ", "  #  ", "   # ", "   # ", "   # ", "  #  ", " #   ",
        ],
        '=' => [
            "     ", "     ", "#####", "     ", "#####", "     ", "     ",
        ],
        ' ' => ["     "; 7],
        'E' => [
            "#####", "#    ", "#    ", "#### ", "#    ", "#    ", "#####",
        ],
        'H' => [
            "#   #", "#   #", "#   #", "#####", "#   #", "#   #", "#   #",
        ],
        'N' => [
            "#   #", "#   #", "##  #", "# # #", "#  ##", "#   #", "#   #",
        ],
        'P' => [
            "#### ", "#   #", "#   #", "#### ", "#    ", "#    ", "#    ",
        ],
        'S' => [
            " ####", "#    ", "#    ", " ### ", "    #", "    #", "#### ",
        ],
        'a' => [
            "     ", "     ", " ### ", "    #", " ####", "#   #", " ####",
        ],
        'b' => [
            "#    ", "#    ", "# ## ", "##  #", "#   #", "#   #", "#### ",
        ],
        'c' => [
            "     ", "     ", " ### ", "#    ", "#    ", "#   #", " ### ",
        ],
        'd' => [
            "    #", "    #", " ## #", "#  ##", "#   #", "#   #", " ####",
        ],
        'e' => [
            "     ", "     ", " ### ", "#   #", "#####", "#    ", " ### ",
        ],
        'f' => [
            "  ## ", " #  #", " #   ", "###  ", " #   ", " #   ", " #   ",
        ],
        'g' => [
            "     ", " ####", "#   #", "#   #", " ####", "    #", " ### ",
        ],
        'h' => [
            "#    ", "#    ", "# ## ", "##  #", "#   #", "#   #", "#   #",
        ],
        'i' => [
            "  #  ", "     ", " ##  ", "  #  ", "  #  ", "  #  ", " ### ",
        ],
        'l' => [
            " ##  ", "  #  ", "  #  ", "  #  ", "  #  ", "  #  ", " ### ",
        ],
        'm' => [
            "     ", "     ", "## # ", "# # #", "# # #", "#   #", "#   #",
        ],
        'n' => [
            "     ", "     ", "# ## ", "##  #", "#   #", "#   #", "#   #",
        ],
        'o' => [
            "     ", "     ", " ### ", "#   #", "#   #", "#   #", " ### ",
        ],
        'p' => [
            "     ", "#### ", "#   #", "#   #", "#### ", "#    ", "#    ",
        ],
        'r' => [
            "     ", "     ", "# ## ", "##  #", "#    ", "#    ", "#    ",
        ],
        's' => [
            "     ", "     ", " ####", "#    ", " ### ", "    #", "#### ",
        ],
        't' => [
            " #   ", " #   ", "###  ", " #   ", " #   ", " #  #", "  ## ",
        ],
        'u' => [
            "     ", "     ", "#   #", "#   #", "#   #", "#  ##", " ## #",
        ],
        'v' => [
            "     ", "     ", "#   #", "#   #", "#   #", " # # ", "  #  ",
        ],
        'w' => [
            "     ", "     ", "#   #", "#   #", "# # #", "# # #", " # # ",
        ],
        'x' => [
            "     ", "     ", "#   #", " # # ", "  #  ", " # # ", "#   #",
        ],
        'y' => [
            "     ", "     ", "#   #", "#   #", " ####", "    #", " ### ",
        ],
        'z' => [
            "     ", "     ", "#####", "   # ", "  #  ", " #   ", "#####",
        ],
        'k' => [
            "#    ", "#    ", "#  # ", "# #  ", "##   ", "# #  ", "#  # ",
        ],
        'T' => [
            "#####", "  #  ", "  #  ", "  #  ", "  #  ", "  #  ", "  #  ",
        ],
        'R' => [
            "#### ", "#   #", "#   #", "#### ", "# #  ", "#  # ", "#   #",
        ],
        'G' => [
            " ### ", "#   #", "#    ", "# ###", "#   #", "#   #", " ####",
        ],
        'B' => [
            "#### ", "#   #", "#   #", "#### ", "#   #", "#   #", "#### ",
        ],
        '_' => [
            "     ", "     ", "     ", "     ", "     ", "     ", "#####",
        ],
        _ => return None,
    })
}
