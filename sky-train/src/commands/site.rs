//! `sky-train site`: a site's clear atmosphere month by month ([`crate::site`]), as CSV.

use std::io::{BufWriter, Write};

use anyhow::Result;
use clap::Args;

use crate::args::{latitude, longitude};
use crate::csv_output::number;

/// `site`'s arguments.
#[derive(Args)]
pub struct SiteArgs {
    /// Latitude in degrees, north positive (-90 to 90).
    #[arg(long, value_name = "DEG", allow_negative_numbers = true, value_parser = latitude)]
    pub lat: f64,
    /// Longitude in degrees, east positive (-180 to 180).
    #[arg(long, value_name = "DEG", allow_negative_numbers = true, value_parser = longitude)]
    pub lon: f64,
    /// Elevation of the site in metres above sea level (-500 to 6000; default the 1-degree
    /// grid's mean elevation, a coarse stand-in: give it).
    #[arg(long, value_name = "M", allow_negative_numbers = true)]
    pub elevation: Option<f64>,
}

/// The CSV header of `site`.
pub const HEADER: &str =
    "month,aod_550,angstrom,ozone_du,water_vapour_cm,linke_turbidity,elevation_m,pressure_hpa";

/// Writes the site's twelve months to `output`: the aerosol optical depth at 550 nm and its
/// Ångström exponent, the ozone column, the precipitable water, the climatology's Linke
/// turbidity the aerosol comes from, the elevation and the surface pressure.
///
/// # Errors
/// A [`crate::args::ParamError`] for a value out of range, a failed write.
pub fn run(args: &SiteArgs, output: &mut dyn Write) -> Result<()> {
    let months = (1..=12)
        .map(|m| crate::site::site_month(args.lat, args.lon, args.elevation, m))
        .collect::<Result<Vec<_>, _>>()?;
    let mut out = BufWriter::new(output);
    writeln!(out, "{HEADER}")?;
    for s in months {
        let fields = [
            s.aod_550,
            s.angstrom,
            s.ozone_du,
            s.water_vapour_cm,
            s.linke_turbidity,
            s.elevation_m,
            s.pressure_hpa,
        ]
        .map(number);
        writeln!(out, "{},{}", s.month, fields.join(","))?;
    }
    out.flush()?;
    Ok(())
}
