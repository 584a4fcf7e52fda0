//! The command line: the top-level parser and the dispatch to [`crate::commands`], one module
//! per subcommand. Callable in-process: the binary is a thin wrapper, and tests drive
//! [`execute`] directly.

use std::io::{BufRead, Write};

use anyhow::Result;
use clap::{Parser, Subcommand};

use crate::commands::{
    self, SkyArgs, bench::BenchArgs, daylight::DaylightArgs, daylight_planes::DaylightPlanesArgs,
    daylight_sky::DaylightSkyArgs, daylight_tables::DaylightTablesArgs, eval::EvalArgs,
    export::ExportArgs, fit_aod::FitAodArgs, fit_sh::FitShArgs, gallery::GalleryArgs,
    locus_table::LocusTableArgs, render::RenderArgs, schedule::ScheduleArgs,
    showcase::ShowcaseArgs, site::SiteArgs, size_study::SizeStudyArgs, spectrum::SpectrumArgs,
    train::TrainArgs,
};

/// The `sky-train` command line.
#[derive(Parser)]
#[command(
    name = "sky-train",
    version,
    about = "Render, sample and benchmark the sky models."
)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Subcommand)]
pub enum Command {
    /// Render an equirectangular image of a sky to OpenEXR (linear float RGB) or PNG (sRGB).
    Render(RenderArgs),
    /// Evaluate a sky at view directions read from stdin (`view_zenith_deg,view_azimuth_deg`
    /// lines; a header line is allowed) and write CSV
    /// `view_zenith_deg,view_azimuth_deg,Y,x,y,R,G,B` to stdout (RGB linear sRGB and Y on the
    /// same scale: cd/m² for preetham, O'Neil's relative units for aoas).
    Sample(SkyArgs),
    /// Print ns/direction of each evaluator over a hemisphere grid, single-threaded, with ratios.
    Bench(BenchArgs),
    /// Render a set of default skies (Preetham: sun positions x turbidities; AOAS: every style
    /// preset) to a folder (the first part of `showcase`).
    Gallery(GalleryArgs),
    /// The main job: the gallery, then a Preetham neural sky trained from scratch and compared
    /// with seed 000's Tables 1-2, weights and images written to the folder.
    Showcase(ShowcaseArgs),
    /// Train a neural sky on a model (seed 000 §III) and write its weight file.
    Train(TrainArgs),
    /// Evaluate a neural sky on seed 000's test protocol: Tables 1 and 2 beside the paper's,
    /// and reference / network / difference images like Figs. 6-7.
    Eval(EvalArgs),
    /// Write the Rust source of a weight file for compile-time embedding in sky-core, or a sky
    /// model's GPU shader (GLSL ES 3.00 or WGSL, sky-gpu) or sky-wasm's module of them all.
    Export(ExportArgs),
    /// Seed 000's 6-12-3 network against 6-6-3, 6-24-3, 6-48-3 and 6-12-12-3, each trained the
    /// same way: mean NRMSE and irradiance on the paper's protocol, bytes, ns/direction (a
    /// Markdown table on stdout).
    SizeStudy(SizeStudyArgs),
    /// Fit a model's spherical-harmonics coefficients as polynomials in sun zenith and
    /// turbidity (seed 001) and write them as a Rust table for sky-core.
    FitSh(FitShArgs),
    /// Write the Planckian locus (Planck's law against the CIE 1931 colour-matching functions,
    /// 10-1000 mired) as the Rust table of cubic pieces that sky-core's CCT searches.
    LocusTable(LocusTableArgs),
    /// A lighting controller's day: every --step minutes of a UTC date, the sun's position
    /// (NREL SPA), the clear sky's CCT, Duv and horizontal illuminance, and the levels of an
    /// example RGBW luminaire, as CSV on stdout; or, with --measurements, one row per reading
    /// of an outdoor sensor (its columns under --measurements).
    ///
    /// Columns: utc (RFC 3339); sun_zenith_deg: the topocentric GEOMETRIC zenith angle (no
    /// refraction; the sky's light is computed for it, the sun's beam for the apparent one);
    /// sun_azimuth_deg: from north, clockwise, east = 90;
    /// sun_elevation_deg = 90 - zenith; apparent_zenith_deg: refraction-corrected for 1013.25 hPa
    /// and 15 C; cct_k and duv (CIE 1960 uv distance from the Planckian locus, positive above
    /// it as in ANSI C78.377; empty where |Duv| > 0.05) of the light followed; horizontal_lux:
    /// the light followed on a horizontal plane, the clear sky's global light of sun and sky
    /// (the physical daylight distilled into sky-core's tables, twilight included), or the sky
    /// alone with --sky-only; red, green, blue, white: levels in [0, 1] of an RGBW luminaire
    /// (red 300 lm at x,y 0.700,0.295; green 600 lm at 0.170,0.700; blue 100 lm at
    /// 0.135,0.060; white 900 lm at 0.4369,0.4041) reproducing that colour, at full output at
    /// --full-scale-lux; global_lux, diffuse_lux, direct_lux: the clear sky's; x, y and
    /// melanopic_edi_lux: of the light followed.
    Schedule(ScheduleArgs),
    /// Captured skies (seed 000 §III-D, §IV-A, §IV-B): train a neural sky on a sequence of
    /// HDR environment maps, fill the gaps between them, synthesize test sequences.
    Captures {
        /// What to do with captures.
        #[command(subcommand)]
        command: commands::captures::CapturesCommand,
    },
    /// Read CIE 1931 `x,y` lines on stdin (a header line is allowed) and write
    /// `x,y,cct_k,duv`: correlated colour temperature (1000-100000 K) and Duv (positive above
    /// the Planckian locus, ANSI C78.377).
    ///
    /// cct_k and duv are empty where |Duv| > 0.05 (CIE 015:2018: no CCT so far from the
    /// locus) or the chromaticity is outside the spectrum locus (no light has it, e.g. 0.6,0.6),
    /// the rule `daylight` follows.
    Cct,
    /// The physical atmosphere's spectral irradiance at the ground for one sun position: CSV
    /// `wavelength_nm,global_horizontal,diffuse_horizontal,direct_horizontal,direct_normal` in
    /// W m⁻² nm⁻¹ (10 nm bins 360-830 nm, named by their centres). Precomputes the atmosphere
    /// on first use (cached).
    Spectrum(SpectrumArgs),
    /// Horizontal illuminance against geometric sun elevation: CSV
    /// `sun_elevation_deg,global_lux,diffuse_lux,direct_lux,x,y,cct_k,duv,melanopic_edi_lux`
    /// (x, y of the global light; cct_k and duv empty where |Duv| > 0.05). --model physical:
    /// the spectral atmosphere, sun and sky; --model preetham: today's sky-only figures.
    Daylight(DaylightArgs),
    /// sky-core's daylight tables (diffuse light against sun elevation and aerosol optical
    /// depth; the direct beam's spectral constants) from the physical atmosphere: --sample
    /// samples the reference into --data (slow), then the Rust tables are written from it.
    DaylightTables(DaylightTablesArgs),
    /// sky-core's table of the sky's light on vertical planes (against sun elevation, aerosol
    /// optical depth and the plane's azimuth from the sun's) from the physical atmosphere:
    /// --sample samples the reference into --data (slow), then the Rust table is written from it.
    DaylightPlanes(DaylightPlanesArgs),
    /// Train sky-core's daylight neural sky on the physical atmosphere's radiance over its
    /// diffuse illuminance (sun zenith 0-108 deg, the tables' optical depths) and write its
    /// weight file.
    DaylightSky(DaylightSkyArgs),
    /// Fit the physical atmosphere's aerosol optical depth at 550 nm to the USNO clear-sky
    /// record (least squares of ln(E / E_USNO), 0-90 deg) and print it, the ratio bands and
    /// the ratio table at the rounded fit (`--atmosphere record`'s value). Precomputes one
    /// atmosphere per evaluation, not cached: minutes.
    FitAod(FitAodArgs),
    /// A site's clear atmosphere month by month, as CSV
    /// `month,aod_550,angstrom,ozone_du,water_vapour_cm,linke_turbidity,elevation_m,pressure_hpa`:
    /// the aerosol optical depth at 550 nm from the SoDa Linke turbidity climatology (Remund et
    /// al. 2003, 1-degree cells) by Ineichen 2008's conversion, Angstrom exponent 1.3, ozone by
    /// Van Heuklon 1979, precipitable water from the AFGL reference atmospheres by latitude and
    /// season, the surface pressure of the US Standard Atmosphere at the elevation. schedule,
    /// daylight and spectrum use the site's month unless --atmosphere or a constituent's flag
    /// says otherwise.
    Site(SiteArgs),
}

/// Runs `command`, reading `sample`'s and `cct`'s input from `input` and writing its output to
/// `output`.
///
/// # Errors
/// Bad parameters as a [`crate::args::ParamError`] (exit status 2), anything else as a plain
/// error.
pub fn execute(command: Command, input: &mut dyn BufRead, output: &mut dyn Write) -> Result<()> {
    match command {
        Command::Render(args) => commands::render::run(&args),
        Command::Sample(args) => commands::sample::run(&args, input, output),
        Command::Bench(args) => commands::bench::run(&args, output),
        Command::Gallery(args) => commands::gallery::run(&args, output),
        Command::Showcase(args) => commands::showcase::run(&args, output),
        Command::Train(args) => commands::train::run(&args, output),
        Command::Eval(args) => commands::eval::run(&args, output),
        Command::Export(args) => commands::export::run(&args, output),
        Command::SizeStudy(args) => commands::size_study::run(&args, output),
        Command::FitSh(args) => commands::fit_sh::run(&args, output),
        Command::LocusTable(args) => commands::locus_table::run(&args, output),
        Command::Schedule(args) => commands::schedule::run(&args, output),
        Command::Captures { command } => commands::captures::run(&command, output),
        Command::Cct => commands::cct::run(input, output),
        Command::Spectrum(args) => commands::spectrum::run(&args, output),
        Command::Daylight(args) => commands::daylight::run(&args, output),
        Command::DaylightTables(args) => commands::daylight_tables::run(&args, output),
        Command::DaylightPlanes(args) => commands::daylight_planes::run(&args, output),
        Command::DaylightSky(args) => commands::daylight_sky::run(&args, output),
        Command::FitAod(args) => commands::fit_aod::run(&args, output),
        Command::Site(args) => commands::site::run(&args, output),
    }
}

/// The binary's stdout as the commands' `output`: it remembers the first write error, so that
/// `main` can tell a failure of stdout (a closed pipe, a full disk) from a failure of the work,
/// whatever context a command wrapped the error in.
pub struct Stdout<W: Write> {
    inner: W,
    error: Option<std::io::Error>,
}

impl<W: Write> Stdout<W> {
    /// Wraps `inner`.
    pub fn new(inner: W) -> Self {
        Self { inner, error: None }
    }

    /// The first error a write or flush returned, if any.
    #[must_use]
    pub fn error(&self) -> Option<&std::io::Error> {
        self.error.as_ref()
    }

    fn keep<T>(&mut self, r: std::io::Result<T>) -> std::io::Result<T> {
        if let Err(e) = &r
            && self.error.is_none()
            && e.kind() != std::io::ErrorKind::Interrupted
        {
            self.error = Some(std::io::Error::new(e.kind(), e.to_string()));
        }
        r
    }
}

impl<W: Write> Write for Stdout<W> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let r = self.inner.write(buf);
        self.keep(r)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        let r = self.inner.flush();
        self.keep(r)
    }
}
