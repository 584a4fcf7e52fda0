//! `sky-train fit-sh`: a model's spherical-harmonics coefficients fitted as polynomials in sun
//! zenith and turbidity (seed 001), written as a Rust table for sky-core.

use std::io::Write;
use std::path::PathBuf;

use anyhow::{Context, Result};
use clap::Args;

use crate::args::ParamError;
use crate::image_io;
use crate::output_path::{self, Folder};
use crate::sh::{Degrees, FitConfig, ShFit, export, report};
use crate::sources::ModelKind;

/// `fit-sh`'s arguments.
#[derive(Args)]
pub struct FitShArgs {
    /// The sky model to fit (any model; it is treated as a black box).
    #[arg(long, value_enum, default_value_t = ModelKind::Preetham)]
    model: ModelKind,
    /// Polynomial degree in sun zenith of bands 0-4 (0 to 30; the paper: 13).
    #[arg(long, value_name = "D", default_value_t = 18)]
    degree_theta: usize,
    /// Polynomial degree in turbidity of bands 0-4 (0 to 30; the paper: 7).
    #[arg(long, value_name = "D", default_value_t = 13)]
    degree_turbidity: usize,
    /// Polynomial degree in sun zenith of bands 5-6 (0 to 30; the paper: 13).
    #[arg(long, value_name = "D", default_value_t = 12)]
    degree_theta_high: usize,
    /// Polynomial degree in turbidity of bands 5-6 (0 to 30; the paper: 7).
    #[arg(long, value_name = "D", default_value_t = 6)]
    degree_turbidity_high: usize,
    /// Chebyshev sample points in sun zenith (more than the degrees).
    #[arg(long, value_name = "N", default_value_t = 38)]
    nodes_theta: usize,
    /// Chebyshev sample points in turbidity (more than the degrees).
    #[arg(long, value_name = "N", default_value_t = 28)]
    nodes_turbidity: usize,
    /// Smallest turbidity fitted (the paper's 2.5; the fit worsens fast below).
    #[arg(long, value_name = "T", default_value_t = 2.5)]
    turbidity_min: f32,
    /// Largest turbidity fitted.
    #[arg(long, value_name = "T", default_value_t = 6.0)]
    turbidity_max: f32,
    /// The generated Rust file (written atomically); default `out/sh/<model>_table.rs`.
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
    /// Also measure the errors (eqs. 2-3) off the fit grid and write the table, the chart and
    /// the worst-case renders into this folder.
    #[arg(long, value_name = "DIR")]
    report: Option<PathBuf>,
}

/// Fits the tables, writes the Rust file and, with `--report`, the error report.
///
/// # Errors
/// `--model sh`, a failed fit or write.
pub fn run(args: &FitShArgs, output: &mut dyn Write) -> Result<()> {
    if args.model == ModelKind::Sh {
        return Err(ParamError(
            "--model sh is the fitted representation itself; fit the model it approximates".into(),
        )
        .into());
    }
    let out = args.out.clone().unwrap_or_else(|| {
        PathBuf::from("out/sh").join(format!(
            "{}_table.rs",
            args.model.to_string().replace('-', "_")
        ))
    });
    output_path::file("--out", &out, Folder::Created)?;
    if let Some(dir) = &args.report {
        output_path::folder("--report", dir)?;
    }
    let config = FitConfig {
        low: Degrees {
            theta: args.degree_theta,
            tau: args.degree_turbidity,
        },
        high: Degrees {
            theta: args.degree_theta_high,
            tau: args.degree_turbidity_high,
        },
        nodes_theta: args.nodes_theta,
        nodes_tau: args.nodes_turbidity,
        turbidity: [args.turbidity_min, args.turbidity_max],
        ..FitConfig::shipped(args.model)
    };
    config.validate()?;
    let start = std::time::Instant::now();
    let fit = ShFit::run(&config)?;
    if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).with_context(|| format!("cannot create {}", dir.display()))?;
    }
    image_io::write_text(&out, &export::rust_source(&fit))?;
    writeln!(
        output,
        "fit-sh {}: {} skies projected (at most {} x {} quadrature nodes), symmetry residual {:.1e}, \
         condition number {:.4} (raw monomials {:.2e}), {:.1} s",
        args.model,
        fit.samples,
        fit.max_rows,
        2 * fit.max_rows,
        fit.asymmetry,
        fit.condition,
        fit.condition_monomial,
        start.elapsed().as_secs_f64()
    )?;
    writeln!(output, "  wrote {}", out.display())?;
    if let Some(dir) = &args.report {
        // The paper's uniform degrees, for comparison.
        let paper = ShFit::run(&FitConfig {
            turbidity: config.turbidity,
            ..FitConfig::paper(args.model)
        })?;
        let (errors, paper_errors, paths) = report::write(&fit, Some(&paper), dir)?;
        writeln!(
            output,
            "errors (eqs. 2-3) over {} skies off the fit grid:",
            errors.skies
        )?;
        write!(output, "{}", report::markdown(&fit, &errors))?;
        if let Some(p) = paper_errors {
            writeln!(output, "with the paper's degrees (13, 7) for every band:")?;
            write!(output, "{}", report::markdown(&paper, &p))?;
        }
        for p in paths {
            writeln!(output, "  wrote {}", p.display())?;
        }
    }
    Ok(())
}
