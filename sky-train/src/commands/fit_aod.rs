//! `sky-train fit-aod`: the aerosol optical depth that brings the physical atmosphere's global
//! horizontal illuminance closest to the USNO clear-sky record (the default atmosphere's,
//! docs/daylight.md), with the ratio table at the fit.

use std::io::{BufWriter, Write};

use anyhow::Result;
use clap::Args;

use super::AtmosphereArgs;
use crate::args::ParamError;
use crate::physical::record::{self, usno_illuminance};
use crate::physical::{Resolution, cache};

/// `fit-aod`'s arguments.
#[derive(Args)]
pub struct FitAodArgs {
    /// The other constituents (their defaults the preset's; --aod is what is fitted).
    #[command(flatten)]
    atmosphere: AtmosphereArgs,
    /// Not for fit-aod (the optical depth, which turbidity names, is what is fitted); here so
    /// that the atmosphere flags' exclusions hold.
    #[arg(long, value_name = "T", hide = true, allow_negative_numbers = true)]
    turbidity: Option<f64>,
    /// Stop when the optical depth moves less than this (0.0001 to 0.1).
    #[arg(long, value_name = "TAU", default_value_t = 0.002)]
    tolerance: f64,
}

/// Fits, then writes the evaluations, the fitted τ₅₅₀, the ratio bands and the ratio table.
///
/// # Errors
/// Bad parameters as a [`ParamError`]; a fit that does not converge; a failed write.
pub fn run(args: &FitAodArgs, output: &mut dyn Write) -> Result<()> {
    let options = args.atmosphere.options();
    if let Some(flag) = [
        (options.aod.is_some(), "--aod"),
        (args.turbidity.is_some(), "--turbidity"),
    ]
    .into_iter()
    .find_map(|(given, flag)| given.then_some(flag))
    {
        return Err(ParamError(format!(
            "{flag} does not apply to fit-aod (it is what is fitted)"
        ))
        .into());
    }
    if !(1e-4..=0.1).contains(&args.tolerance) {
        return Err(ParamError(format!(
            "--tolerance {} is outside the valid range [0.0001, 0.1]",
            args.tolerance
        ))
        .into());
    }
    if options.cache_dir.is_some() {
        // Refused before the minutes of work: it would be ignored.
        return Err(ParamError(
            "--cache-dir does not apply to fit-aod (the atmospheres of its evaluations are not cached)"
                .into(),
        )
        .into());
    }
    let base = options.atmosphere(None)?;
    let list = record::fit_elevations();
    let mut out = BufWriter::new(output);
    writeln!(
        out,
        "# aerosol optical depth at 550 nm fitted to USNO Circular 171: least squares of ln(E / E_USNO), global horizontal illuminance, sun elevations 0-90 deg in 1 deg steps"
    )?;
    writeln!(out, "# evaluation,tau_550,rms_log_ratio")?;
    let mut k = 0;
    let fit = record::fit_aod(
        |tau| {
            let atm = crate::physical::Atmosphere {
                aod_550: tau,
                ..base
            };
            let tables = cache::load_or_build(&atm, &Resolution::default(), None, true)?;
            let r = record::usno_log_ratios(&tables, &list)?;
            let cost = r.iter().map(|(_, l)| l * l).sum::<f64>();
            k += 1;
            #[allow(clippy::cast_precision_loss)]
            let rms = (cost / r.len() as f64).sqrt();
            eprintln!("fit-aod: evaluation {k}: tau_550 {tau:.5}, rms log ratio {rms:.5}");
            Ok(cost)
        },
        args.tolerance,
        12,
    )?;
    #[allow(clippy::cast_precision_loss)]
    for (k, (tau, cost)) in fit.evaluations.iter().enumerate() {
        writeln!(
            out,
            "# {},{tau:.5},{:.5}",
            k + 1,
            (cost / list.len() as f64).sqrt()
        )?;
    }
    let tau = (fit.aod_550 * 100.0).round() / 100.0;
    writeln!(out, "# fitted tau_550 {:.4}, rounded {tau:.2}", fit.aod_550)?;
    let atm = crate::physical::Atmosphere {
        aod_550: tau,
        ..base
    };
    let tables = cache::load_or_build(&atm, &Resolution::default(), None, true)?;
    let all: Vec<f64> = (-18..=90).map(f64::from).collect();
    let ratios = record::usno_log_ratios(&tables, &all)?;
    for (from, to) in [
        (-18.0, -12.0),
        (-12.0, -6.0),
        (-6.0, 0.0),
        (0.0, 10.0),
        (10.0, 90.0),
    ] {
        let band = ratios
            .iter()
            .filter(|(h, _)| (from..=to).contains(h))
            .map(|(_, l)| l.exp());
        let (lo, hi) = band.fold((f64::INFINITY, 0.0_f64), |(lo, hi), r| {
            (lo.min(r), hi.max(r))
        });
        writeln!(
            out,
            "# at tau_550 {tau:.2}: ratio {lo:.3} to {hi:.3} over {from} to {to} deg"
        )?;
    }
    writeln!(out, "sun_elevation_deg,global_lux,usno_lux,ratio")?;
    for (h, l) in ratios {
        let usno = usno_illuminance(h);
        let fields = [h, usno * l.exp(), usno, l.exp()].map(crate::csv_output::number);
        writeln!(out, "{}", fields.join(","))?;
    }
    out.flush()?;
    Ok(())
}
