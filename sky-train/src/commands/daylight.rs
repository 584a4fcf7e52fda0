//! `sky-train daylight`: horizontal illuminance, chromaticity, CCT and melanopic EDI against
//! the sun's elevation, as CSV: the physical atmosphere (global = diffuse + direct) or, for
//! comparison, today's Preetham sky with sky-core's twilight (sky only, direct 0).

use std::io::{BufWriter, Write};
use std::path::PathBuf;

use anyhow::Result;
use clap::{Args, ValueEnum};

use super::{AtmosphereArgs, ClimateArgs};
use crate::args::{ParamError, radians};
use crate::output_path;
use crate::physical::atmosphere::Preset;
use crate::physical::photometry::Colorimetry;
use crate::physical::solar;
use crate::sources::ModelKind;

/// The sun elevations `daylight` covers, degrees (geometric; −18° ends astronomical twilight).
pub const ELEVATION_RANGE: (f64, f64) = (-18.0, 90.0);

/// `daylight`'s arguments.
#[derive(Args)]
pub struct DaylightArgs {
    /// The model: physical, or preetham (sky only, as `schedule` computes it).
    #[arg(long, value_enum, default_value_t = ModelKind::Physical)]
    model: ModelKind,
    /// Geometric sun elevations FROM:TO:STEP in degrees (-18 to 90; STEP > 0; at most 10,000
    /// rows), e.g. -18:90:1.
    #[arg(long, value_name = "FROM:TO:STEP", allow_hyphen_values = true, value_parser = elevations)]
    elevations: (f64, f64, f64),
    /// Turbidity: Preetham's (2 to 6, default 3) for preetham; for physical 1 to 10, mapped to
    /// the aerosol optical depth (excludes --aod).
    #[arg(long, value_name = "T", allow_negative_numbers = true)]
    turbidity: Option<f64>,
    /// The date, YYYY-MM-DD, for the Earth-Sun distance (physical; default: 1 AU).
    #[arg(long, value_name = "YYYY-MM-DD", value_parser = crate::args::date)]
    date: Option<(i32, u32, u32)>,
    #[command(flatten)]
    atmosphere: AtmosphereArgs,
    #[command(flatten)]
    site: ClimateArgs,
    /// Also draw global, diffuse and direct illuminance against elevation (log scale) beside
    /// the USNO clear-sky record and Preetham's sky-only curve (turbidity 3), and the global
    /// curve of the other preset, as PNG (physical only).
    #[arg(long, value_name = "FILE.png")]
    plot_illuminance: Option<PathBuf>,
    /// Also draw the CCT of the global light against elevation beside Preetham's, as PNG
    /// (physical only).
    #[arg(long, value_name = "FILE.png")]
    plot_cct: Option<PathBuf>,
}

type Row = (f64, f64, f64, Colorimetry);

fn physical_rows(args: &DaylightArgs, list: &[f64]) -> Result<Vec<Row>, ParamError> {
    let options = args.site.apply(args.atmosphere.options(), args.date)?;
    rows_of(&options, args.turbidity, args, list)
}

fn rows_of(
    options: &crate::sources::PhysicalOptions,
    turbidity: Option<f64>,
    args: &DaylightArgs,
    list: &[f64],
) -> Result<Vec<Row>, ParamError> {
    let atm = options.load(turbidity)?;
    let scale = args.date.map_or(1.0, |(y, m, d)| {
        solar::eccentricity_correction(solar::day_of_year(y, m, d))
    });
    list.iter()
        .map(|&h| {
            let sky = atm
                .sky(90.0 - h, 0.0)
                .map_err(|e| ParamError(e.to_string()))?
                .with_irradiance_scale(scale);
            let d = sky.daylight();
            Ok((h, d.diffuse.xyz[1], d.direct.xyz[1], d.global))
        })
        .collect()
}

fn preset_name(p: Preset) -> String {
    p.to_possible_value()
        .map_or_else(String::new, |v| v.get_name().to_owned())
}

/// Knots of the previous sky-only model's twilight decay (sun elevation in degrees, log10 of
/// the luminance factor): the clear-sky horizontal illuminances of the American
/// Meteorological Society's *Glossary of Meteorology* ("civil twilight", "astronomical
/// twilight"), each range's geometric mean over 490 lx at sunset.
const TWILIGHT_KNOTS: [(f64, f64); 4] = [
    (0.0, 0.0),
    (-6.0, -2.2676),
    (-12.0, -4.7871),
    (-18.0, -5.9120),
];

/// The previous model's luminance factor: 1 by day, log-linear through the knots, constant
/// below −18°.
fn twilight_factor(h: f64) -> f64 {
    if h >= 0.0 {
        return 1.0;
    }
    let mut log10 = TWILIGHT_KNOTS[3].1;
    for pair in TWILIGHT_KNOTS.windows(2) {
        let ((h0, k0), (h1, k1)) = (pair[0], pair[1]);
        if h < h0 && h >= h1 {
            log10 = k0 + (k1 - k0) * (h - h0) / (h1 - h0);
        }
    }
    10f64.powf(log10)
}

/// The previous sky-only figures, for comparison: sky-core's Preetham sky (the sun on the
/// horizon below it) scaled by the glossary's twilight decay.
fn preetham_rows(list: &[f64], turbidity: f64) -> Result<Vec<Row>, ParamError> {
    use sky_core::photometry::Photometry;
    list.iter()
        .map(|&h| {
            let sun = sky_core::Sun::new(radians(90.0 - h.clamp(0.0, 90.0)), 0.0)
                .map_err(|e| ParamError(format!("--elevations {h}: {e}")))?;
            #[allow(clippy::cast_possible_truncation)]
            let e = sky_core::PreethamSky::new(sun, turbidity as f32)
                .map_err(|e| ParamError(format!("--turbidity {turbidity}: {e}")))?
                .horizontal_illuminance();
            let k = twilight_factor(h);
            let (x, y, z) = (f64::from(e.x) * k, f64::from(e.y) * k, f64::from(e.z) * k);
            // No spectrum, so no melanopic EDI.
            Ok((h, y, 0.0, Colorimetry::from_channels([x, y, z, f64::NAN])))
        })
        .collect()
}

fn plots(args: &DaylightArgs, rows: &[Row]) -> Result<()> {
    use super::daylight_plot::{Curve, chart};
    use plotters::style::RGBColor;
    let list: Vec<f64> = rows.iter().map(|r| r.0).collect();
    let preetham = preetham_rows(&list, 3.0)?;
    let curve = |name: &str, color, points_only, f: &dyn Fn(&Row) -> f64, rows: &[Row]| Curve {
        name: name.to_owned(),
        color,
        points_only,
        points: rows.iter().map(|r| (r.0, f(r))).collect(),
    };
    let usno = RGBColor(0, 0, 0);
    if let Some(path) = &args.plot_illuminance {
        // The global curve of each preset whose atmosphere is not the one drawn, the other
        // flags as given.
        let options = args.site.apply(args.atmosphere.options(), args.date)?;
        let drawn = options.atmosphere(args.turbidity)?;
        let mut presets = Vec::new();
        for preset in [Preset::Record, Preset::Clean] {
            let other = crate::sources::PhysicalOptions {
                preset: Some(preset),
                aod: None,
                ..options.clone()
            };
            if other.atmosphere(None)? != drawn {
                presets.push((preset, rows_of(&other, None, args, &list)?));
            }
        }
        let record: Vec<Row> = list
            .iter()
            .map(|&h| {
                (
                    h,
                    crate::physical::record::usno_illuminance(h),
                    0.0,
                    Colorimetry::from_channels([0.0; 4]),
                )
            })
            .collect();
        chart(
            path,
            "Horizontal illuminance of the clear sky",
            "illuminance (lx)",
            chart_range("--plot-illuminance", &list, ELEVATION_RANGE.0)?,
            (1e-4, 3e5),
            true,
            &[
                curve(
                    "USNO Circular 171 (measured, Brown 1952)",
                    usno,
                    false,
                    &|r| r.1,
                    &record,
                ),
                curve(
                    "physical: global",
                    RGBColor(200, 30, 30),
                    false,
                    &|r| r.3.xyz[1],
                    rows,
                ),
                curve(
                    "physical: diffuse (sky)",
                    RGBColor(30, 90, 220),
                    false,
                    &|r| r.1,
                    rows,
                ),
                curve(
                    "physical: direct (sun)",
                    RGBColor(230, 150, 0),
                    false,
                    &|r| r.2,
                    rows,
                ),
                curve(
                    "Preetham + twilight, sky only (T = 3)",
                    RGBColor(130, 130, 130),
                    false,
                    &|r| r.1,
                    &preetham,
                ),
            ]
            .into_iter()
            .chain(presets.iter().map(|(p, rows)| {
                curve(
                    &format!("physical: global, --atmosphere {}", preset_name(*p)),
                    RGBColor(150, 40, 160),
                    false,
                    &|r| r.3.xyz[1],
                    rows,
                )
            }))
            .collect::<Vec<_>>(),
        )?;
    }
    if let Some(path) = &args.plot_cct {
        let cct = |r: &Row| r.3.cct_duv.map_or(f64::NAN, |c| c.0);
        // The landmarks issue 15 states after measured twilight spectra (Spitschan et al. 2016,
        // Hernández-Andrés et al. 2001): about 6,000 K at 20°, at least 9,000 K at 0° and
        // 12,000 K at −4°.
        let marks: Vec<Row> = [(20.0, 6_000.0), (0.0, 9_000.0), (-4.0, 12_000.0)]
            .iter()
            .map(|&(h, k)| (h, k, 0.0, Colorimetry::from_channels([0.0; 4])))
            .collect();
        chart(
            path,
            "CCT of the global horizontal light",
            "CCT (K)",
            chart_range("--plot-cct", &list, CCT_CHART_LOWEST)?,
            (3_000.0, 30_000.0),
            true,
            &[
                curve("physical", RGBColor(200, 30, 30), false, &cct, rows),
                curve(
                    "Preetham + twilight (T = 3)",
                    RGBColor(130, 130, 130),
                    false,
                    &cct,
                    &preetham,
                ),
                curve(
                    "issue 15's landmarks after measured twilight",
                    usno,
                    true,
                    &|r| r.1,
                    &marks,
                ),
            ],
        )?;
    }
    Ok(())
}

/// The CSV header of `daylight`.
pub const HEADER: &str =
    "sun_elevation_deg,global_lux,diffuse_lux,direct_lux,x,y,cct_k,duv,melanopic_edi_lux";

/// Parses FROM:TO:STEP.
///
/// # Errors
/// Not three numbers, outside [`ELEVATION_RANGE`], a step that is not positive or gives more
/// than 10,000 rows.
pub fn elevations(s: &str) -> Result<(f64, f64, f64), String> {
    let (lo, hi) = ELEVATION_RANGE;
    let bad = || {
        format!(
            "expected FROM:TO:STEP in degrees with FROM and TO in [{lo}, {hi}] and STEP > 0 (at most 10000 rows), e.g. -18:90:1"
        )
    };
    let v: Vec<f64> = s
        .split(':')
        .map(|p| p.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|_| bad())?;
    let [from, to, step] = v[..] else {
        return Err(bad());
    };
    let ok = (lo..=hi).contains(&from)
        && (lo..=hi).contains(&to)
        && step > 0.0
        && step.is_finite()
        && ((to - from).abs() / step) < 10_000.0;
    if ok { Ok((from, to, step)) } else { Err(bad()) }
}

/// The elevations of FROM:TO:STEP, from FROM towards TO.
#[must_use]
pub fn elevation_list((from, to, step): (f64, f64, f64)) -> Vec<f64> {
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let n = ((to - from).abs() / step + 1e-9).floor() as usize + 1;
    let sign = if to >= from { 1.0 } else { -1.0 };
    #[allow(clippy::cast_precision_loss)]
    (0..n).map(|k| from + sign * step * k as f64).collect()
}

fn field(v: Option<f64>) -> String {
    v.map_or_else(String::new, crate::csv_output::number)
}

/// The elevation range (lowest, highest) a chart draws, or the error that names why it would
/// be empty: a chart needs at least two elevations within its axis (the CCT chart's starts at
/// [`CCT_CHART_LOWEST`]).
fn chart_range(flag: &str, list: &[f64], lowest: f64) -> Result<(f64, f64), ParamError> {
    let drawn: Vec<f64> = list.iter().copied().filter(|&h| h >= lowest).collect();
    let (lo, hi) = (
        drawn.iter().copied().fold(f64::INFINITY, f64::min),
        drawn.iter().copied().fold(f64::NEG_INFINITY, f64::max),
    );
    if drawn.len() < 2 || hi <= lo {
        let within = if lowest > ELEVATION_RANGE.0 {
            format!(" at or above {lowest} deg")
        } else {
            String::new()
        };
        return Err(ParamError(format!(
            "{flag} draws a curve against elevation: it needs at least two different --elevations{within}, and these give {}",
            drawn.len()
        )));
    }
    Ok((lo, hi))
}

/// The lowest sun elevation the CCT chart draws, degrees: below it the global light's
/// chromaticity is too far from the Planckian locus for a CCT (|Duv| > 0.05).
pub const CCT_CHART_LOWEST: f64 = -8.0;

/// Checks before any work that the charts asked for can be drawn and go to two files.
fn check_plots(args: &DaylightArgs, list: &[f64]) -> Result<(), ParamError> {
    if let Some(p) = &args.plot_illuminance {
        output_path::file_ending("--plot-illuminance", p, &["png"])?;
        chart_range("--plot-illuminance", list, ELEVATION_RANGE.0)?;
    }
    if let Some(p) = &args.plot_cct {
        output_path::file_ending("--plot-cct", p, &["png"])?;
        chart_range("--plot-cct", list, CCT_CHART_LOWEST)?;
    }
    if let (Some(a), Some(b)) = (&args.plot_illuminance, &args.plot_cct)
        && same_file(a, b)
    {
        return Err(ParamError(format!(
            "--plot-illuminance and --plot-cct name the same file {}: give each chart its own",
            b.display()
        )));
    }
    Ok(())
}

/// Whether `a` and `b` name the same file: the same path once their folders are resolved.
fn same_file(a: &std::path::Path, b: &std::path::Path) -> bool {
    let resolve = |p: &std::path::Path| {
        let dir = p
            .parent()
            .filter(|d| !d.as_os_str().is_empty())
            .unwrap_or(std::path::Path::new("."));
        std::fs::canonicalize(p)
            .ok()
            .or_else(|| Some(std::fs::canonicalize(dir).ok()?.join(p.file_name()?)))
    };
    a == b || matches!((resolve(a), resolve(b)), (Some(x), Some(y)) if x == y)
}

/// Writes one row per elevation to `output`.
///
/// # Errors
/// Bad parameters as a [`ParamError`], a failed write.
pub fn run(args: &DaylightArgs, output: &mut dyn Write) -> Result<()> {
    let list = elevation_list(args.elevations);
    let plotting = args.plot_illuminance.is_some() || args.plot_cct.is_some();
    check_plots(args, &list)?;
    let rows = match args.model {
        ModelKind::Physical => physical_rows(args, &list)?,
        ModelKind::Preetham => {
            if args.site.given() {
                return Err(ParamError(
                    "--lat/--lon/--elevation do not apply to --model preetham (only to --model physical)".into(),
                )
                .into());
            }
            if let Some(flag) = args.atmosphere.options().first_flag() {
                return Err(ParamError(format!(
                    "{flag} does not apply to --model preetham (only to --model physical)"
                ))
                .into());
            }
            if args.date.is_some() || plotting {
                return Err(ParamError(
                    "--date and --plot-* do not apply to --model preetham (only to --model physical)".into(),
                )
                .into());
            }
            let t = args.turbidity.unwrap_or(3.0);
            if !(2.0..=6.0).contains(&t) {
                return Err(ParamError(format!(
                    "--turbidity {} is outside the valid range [2, 6] for --model preetham",
                    crate::csv_output::compact(t)
                ))
                .into());
            }
            preetham_rows(&list, t)?
        }
        other => {
            return Err(ParamError(format!(
                "--model {other}: daylight takes --model physical or --model preetham"
            ))
            .into());
        }
    };
    if plotting {
        plots(args, &rows)?;
    }
    let mut out = BufWriter::new(output);
    writeln!(out, "{HEADER}")?;
    for (h, diffuse, direct, g) in rows {
        let cct = g.cct_duv;
        let melanopic = Some(g.melanopic_edi).filter(|_| args.model == ModelKind::Physical);
        let fields = [
            Some(h),
            Some(g.xyz[1]),
            Some(diffuse),
            Some(direct),
            Some(g.xy.0),
            Some(g.xy.1),
            cct.map(|c| c.0),
            cct.map(|c| c.1),
            melanopic,
        ]
        .map(field);
        writeln!(out, "{}", fields.join(","))?;
    }
    out.flush()?;
    Ok(())
}
