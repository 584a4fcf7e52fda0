//! `sky-train sample`: a sky at view directions read from stdin, as CSV.

use std::io::{BufRead, BufWriter, Write};

use anyhow::Result;
use sky_core::Vec3;
use sky_core::color::Xyy;
use sky_core::geom;

use super::SkyArgs;
use crate::args::{ParamError, radians};

/// Evaluates the sky of `args` at the `view_zenith_deg,view_azimuth_deg` lines of `input` and
/// writes `view_zenith_deg,view_azimuth_deg,Y,x,y,R,G,B` to `output`.
///
/// # Errors
/// Bad parameters as a [`crate::args::ParamError`], a bad line (named by its number), a failed
/// write.
pub fn run(args: &SkyArgs, input: &mut dyn BufRead, output: &mut dyn Write) -> Result<()> {
    let source = args.source()?;
    let mut rows: Vec<(String, String)> = Vec::new();
    let mut dirs: Vec<Vec3> = Vec::new();
    for row in crate::csv_input::rows(input, ["view_zenith_deg", "view_azimuth_deg"]) {
        let row = row?;
        let [zv, av] = row.values;
        if !(0.0..=180.0).contains(&zv) {
            return Err(ParamError(format!(
                "stdin line {}: view_zenith_deg = {zv} is outside [0, 180]",
                row.line
            ))
            .into());
        }
        dirs.push(geom::direction(radians(zv), radians(av)));
        let [z, a] = row.text;
        rows.push((z, a));
    }
    let mut xyy = vec![Xyy::default(); dirs.len()];
    let mut rgb = vec![Vec3::ZERO; dirs.len()];
    source.xyy_batch(&dirs, &mut xyy);
    source.rgb_batch(&dirs, &mut rgb);
    let mut out = BufWriter::new(output);
    writeln!(out, "view_zenith_deg,view_azimuth_deg,Y,x,y,R,G,B")?;
    for ((z, a), (c, p)) in rows.iter().zip(xyy.iter().zip(&rgb)) {
        writeln!(
            out,
            "{z},{a},{},{},{},{},{},{}",
            c.luminance, c.x, c.y, p.x, p.y, p.z
        )?;
    }
    out.flush()?;
    Ok(())
}
