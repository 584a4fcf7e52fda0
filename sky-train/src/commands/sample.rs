//! `sky-train sample`: a sky at view directions read from stdin, as CSV.

use std::io::{BufRead, BufWriter, Write};

use anyhow::Result;
use sky_core::Vec3;
use sky_core::color::Xyy;

use super::SkyArgs;
use crate::args::ParamError;

/// Rows read, evaluated and written at a time: memory stays bounded however long stdin is.
const BLOCK: usize = 4096;

/// The unit vector of view zenith `zenith_deg` and azimuth `azimuth_deg`, computed in f64 and
/// rounded once: at exactly 90° its z is +6e-17, on the horizon, where f32's cos(π/2) is
/// −4.4e-8 and the skies that are 0 below the horizon (CIE, Perez, daylight) gave 0.
#[allow(clippy::cast_possible_truncation)]
fn view_direction(zenith_deg: f64, azimuth_deg: f64) -> Vec3 {
    let (st, ct) = zenith_deg.to_radians().sin_cos();
    let (sp, cp) = azimuth_deg.to_radians().sin_cos();
    Vec3::new((st * cp) as f32, (st * sp) as f32, ct as f32)
}

/// Evaluates the sky of `args` at the `view_zenith_deg,view_azimuth_deg` lines of `input` and
/// writes `view_zenith_deg,view_azimuth_deg,Y,x,y,R,G,B` to `output`, streaming: `BLOCK`
/// rows at a time, so that a bad line among the first `BLOCK` leaves nothing written, and a
/// later one leaves the blocks before it (the exit status says the output is incomplete).
///
/// # Errors
/// Bad parameters as a [`crate::args::ParamError`], a bad line (named by its number), a failed
/// write.
pub fn run(args: &SkyArgs, input: &mut dyn BufRead, output: &mut dyn Write) -> Result<()> {
    let source = args.source()?;
    let mut out = BufWriter::new(output);
    let mut lines = crate::csv_input::rows(input, ["view_zenith_deg", "view_azimuth_deg"]);
    let mut rows: Vec<(String, String)> = Vec::with_capacity(BLOCK);
    let mut dirs: Vec<Vec3> = Vec::with_capacity(BLOCK);
    let mut xyy = vec![Xyy::default(); BLOCK];
    let mut rgb = vec![Vec3::ZERO; BLOCK];
    let mut header = true;
    loop {
        rows.clear();
        dirs.clear();
        for row in lines.by_ref().take(BLOCK) {
            let row = row?;
            let [zv, av] = row.values;
            if !(0.0..=180.0).contains(&zv) {
                return Err(ParamError(format!(
                    "stdin line {}: view_zenith_deg = {zv} is outside [0, 180]",
                    row.line
                ))
                .into());
            }
            dirs.push(view_direction(zv, av));
            let [z, a] = row.text;
            rows.push((z, a));
        }
        if header {
            writeln!(out, "view_zenith_deg,view_azimuth_deg,Y,x,y,R,G,B")?;
            header = false;
        }
        let n = dirs.len();
        source.xyy_batch(&dirs, &mut xyy[..n]);
        source.rgb_batch(&dirs, &mut rgb[..n]);
        for ((z, a), (c, p)) in rows.iter().zip(xyy.iter().zip(&rgb)) {
            let mut line = format!("{z},{a}");
            for v in [c.luminance, c.x, c.y, p.x, p.y, p.z] {
                line.push(',');
                crate::csv_output::push_number(&mut line, f64::from(v));
            }
            writeln!(out, "{line}")?;
        }
        // Each block reaches the reader before the next is read.
        out.flush()?;
        if n < BLOCK {
            break;
        }
    }
    Ok(())
}
