//! `sky-train cct`: correlated colour temperature and Duv of chromaticities read from stdin.

use std::io::{BufRead, BufWriter, Write};

use anyhow::Result;
use sky_core::cct;

use crate::args::ParamError;
use crate::physical::photometry::MAX_DUV;

/// Reads `x,y` lines from `input` and writes `x,y,cct_k,duv` to `output`: the chromaticity as
/// given, its CCT and Duv where it has one. **The rule**, the same as `daylight`'s: a
/// chromaticity has a CCT only within [`MAX_DUV`] (0.05 in CIE 1960 uv) of the Planckian
/// locus, the limit of CIE 015:2018 §9.5 and ANSI C78.377, and only if it is a colour at all
/// (inside the spectrum locus of the CIE 1931 observer and its purple line); otherwise (a
/// saturated colour, or (0.6, 0.6), which no light has: x + y > 1) `cct_k` and `duv` are
/// empty. (Every chromaticity `daylight` computes is a spectrum's, so inside.) Numbers are written by [`crate::csv_output::number`].
///
/// # Errors
/// A line that is not two finite numbers, or a chromaticity outside x in [0, 1], y in
/// (0, 1] or without a CCT in 1,000-100,000 K (named by its line number); a failed write.
pub fn run(input: &mut dyn BufRead, output: &mut dyn Write) -> Result<()> {
    let mut out = BufWriter::new(output);
    writeln!(out, "x,y,cct_k,duv")?;
    for row in crate::csv_input::rows(input, ["x", "y"]) {
        let row = row?;
        #[allow(clippy::cast_possible_truncation)] // sky-core's chromaticities are f32
        let [x, y] = row.values.map(|v| v as f32);
        let c = cct::cct_duv(x, y).map_err(|e| {
            ParamError(format!(
                "stdin line {}: {} (x in [0, 1], y in (0, 1], CCT between {} and {} K)",
                row.line,
                crate::args::describe(e, str::to_owned, " = "),
                cct::MIN_CCT,
                cct::MAX_CCT
            ))
        })?;
        let [xs, ys] = &row.text;
        let (kelvin, duv) = if f64::from(c.duv.abs()) <= MAX_DUV
            && inside_spectrum_locus(row.values[0], row.values[1])
        {
            (
                crate::csv_output::number(f64::from(c.kelvin)),
                crate::csv_output::number(f64::from(c.duv)),
            )
        } else {
            (String::new(), String::new())
        };
        writeln!(out, "{xs},{ys},{kelvin},{duv}")?;
    }
    out.flush()?;
    Ok(())
}

/// Whether the chromaticity (`x`, `y`) lies inside the spectrum locus of the CIE 1931 2°
/// observer (360-830 nm, [`sky_core::cct::cmf::CMF`]) closed by the purple line: the
/// chromaticities of real lights. The even-odd rule over that polygon.
#[must_use]
pub fn inside_spectrum_locus(x: f64, y: f64) -> bool {
    let locus: Vec<(f64, f64)> = sky_core::cct::cmf::CMF
        .iter()
        .filter_map(|[a, b, c]| {
            let sum = a + b + c;
            (sum > 0.0).then(|| (a / sum, b / sum))
        })
        .collect();
    let mut inside = false;
    for (k, &(x1, y1)) in locus.iter().enumerate() {
        let (x0, y0) = locus[(k + locus.len() - 1) % locus.len()];
        if (y0 > y) != (y1 > y) && x < x0 + (y - y0) * (x1 - x0) / (y1 - y0) {
            inside = !inside;
        }
    }
    inside
}
