//! `sky-train spectrum`: the spectral irradiance at the ground of the physical atmosphere for
//! one sun position, as CSV.

use std::io::{BufWriter, Write};

use anyhow::Result;
use clap::Args;

use super::{AtmosphereArgs, ClimateArgs};
use crate::args::ParamError;
use crate::physical::constituents::wavelength_nm;
use crate::physical::solar;
use crate::sources::ModelKind;

/// `spectrum`'s arguments.
#[derive(Args)]
pub struct SpectrumArgs {
    /// The model: physical (the only spectral one).
    #[arg(long, value_enum, default_value_t = ModelKind::Physical)]
    model: ModelKind,
    /// Sun zenith angle in degrees, geometric (0 to 108: 18 deg below the horizon).
    #[arg(long, value_name = "DEG", allow_negative_numbers = true)]
    sun_zenith: f64,
    /// Preetham turbidity, 1 to 10, as aerosol optical depth (excludes --aod).
    #[arg(long, value_name = "T", allow_negative_numbers = true)]
    turbidity: Option<f64>,
    /// The date, YYYY-MM-DD, for the Earth-Sun distance (default: 1 AU).
    #[arg(long, value_name = "YYYY-MM-DD", value_parser = crate::args::date)]
    date: Option<(i32, u32, u32)>,
    #[command(flatten)]
    atmosphere: AtmosphereArgs,
    #[command(flatten)]
    site: ClimateArgs,
}

/// The CSV header of `spectrum`.
pub const HEADER: &str =
    "wavelength_nm,global_horizontal,diffuse_horizontal,direct_horizontal,direct_normal";

/// Writes the irradiance spectra (W m⁻² nm⁻¹, 10 nm bins named by their centres) to `output`.
///
/// # Errors
/// Bad parameters as a [`ParamError`], a failed write.
pub fn run(args: &SpectrumArgs, output: &mut dyn Write) -> Result<()> {
    if args.model != ModelKind::Physical {
        return Err(ParamError(format!(
            "--model {}: spectrum takes --model physical (the only spectral model)",
            args.model
        ))
        .into());
    }
    let max = crate::physical::sky::MAX_SUN_ZENITH_DEG;
    if !(0.0..=max).contains(&args.sun_zenith) {
        return Err(ParamError(format!(
            "--sun-zenith {} deg is outside the valid range [0, {max}] deg for --model physical",
            args.sun_zenith
        ))
        .into());
    }
    let atm = args
        .site
        .apply(args.atmosphere.options(), args.date)?
        .load(args.turbidity)?;
    let scale = args.date.map_or(1.0, |(y, m, d)| {
        solar::eccentricity_correction(solar::day_of_year(y, m, d))
    });
    let sky = atm
        .sky(args.sun_zenith, 0.0)
        .map_err(|e| ParamError(e.to_string()))?
        .with_irradiance_scale(scale);
    let e = sky.irradiance();
    let mut out = BufWriter::new(output);
    writeln!(out, "{HEADER}")?;
    for l in 0..e.global.len() {
        let fields = [
            wavelength_nm(l),
            e.global[l],
            e.diffuse[l],
            e.direct_horizontal[l],
            e.direct_normal[l],
        ]
        .map(crate::csv_output::number);
        writeln!(out, "{}", fields.join(","))?;
    }
    out.flush()?;
    Ok(())
}
