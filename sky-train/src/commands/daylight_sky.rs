//! `sky-train daylight-sky`: the neural sky of sky-core's daylight, trained on the physical
//! atmosphere's normalised radiance ([`crate::daylight_sky`]), and its weight file.

use std::io::Write;
use std::path::PathBuf;

use anyhow::{Result, bail};
use clap::Args;

use crate::args::{ParamError, seconds};
use crate::daylight_sky::{self, Part};
use crate::daylight_tables::{AOD_NODES, atmosphere};
use crate::export::{self, TrainedOn};
use crate::physical::{Resolution, cache};
use crate::sources::ModelKind;
use crate::train::{self, TrainConfig, Trained};

/// `daylight-sky`'s arguments.
#[derive(Args)]
pub struct DaylightSkyArgs {
    /// Which network: the day's (sun zenith 0-90 deg), dusk's (84-98 deg) or night's
    /// (94-108 deg).
    #[arg(long, value_enum)]
    part: Part,
    /// Hidden neurons of the 6-H-3 network: 6, 12, 24 or 48.
    #[arg(long, default_value_t = 12)]
    hidden: usize,
    /// Random seed.
    #[arg(long, default_value_t = 1)]
    seed: u32,
    /// Wall-time budget in seconds (1 to 86400).
    #[arg(long, default_value_t = 600.0, value_parser = seconds)]
    max_seconds: f64,
    /// Iteration budget (LM steps, 1 to 1000000).
    #[arg(long, default_value_t = 1000, value_parser = clap::value_parser!(u32).range(1..=1_000_000))]
    max_iterations: u32,
    /// Training sun zeniths, uniform over the part's range, both ends included (2 to 1000;
    /// default 37 by day, 2.5 deg apart, 29 at dusk, 0.5 deg apart, 15 at night, 1 deg apart).
    #[arg(long, value_parser = clap::value_parser!(u16).range(2..=1000))]
    sun_zeniths: Option<u16>,
    /// View strata per sky: zenith bands x azimuth sectors, one jittered view each
    /// (1 to 100 each).
    #[arg(long, default_value_t = 10, value_parser = clap::value_parser!(u16).range(1..=100))]
    view_zeniths: u16,
    /// See --view-zeniths.
    #[arg(long, default_value_t = 20, value_parser = clap::value_parser!(u16).range(1..=100))]
    view_azimuths: u16,
    /// Weight file to write, atomically.
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
    /// Folder of precomputed atmospheres (default $SKY_TRAIN_CACHE_DIR, else
    /// $XDG_CACHE_HOME/sky-train, else ~/.cache/sky-train).
    #[arg(long, value_name = "DIR")]
    cache_dir: Option<PathBuf>,
}

fn write<const H: usize>(
    trained: &Trained,
    part: Part,
    seed: u32,
    path: &std::path::Path,
) -> Result<()> {
    let (lo, hi) = part.zenith_range();
    let on = TrainedOn {
        source: part.source().into(),
        uses_turbidity: true,
        turbidity_range: (AOD_NODES[0], AOD_NODES[AOD_NODES.len() - 1]),
        sun_zenith_range: (lo.to_radians(), hi.to_radians()),
    };
    export::write_weights(path, &export::to_weights_of::<H>(trained, &on, seed)?)
}

/// Trains as `args` say, reports the validation NRMSE (mean and worst image from −6° to 90°)
/// and writes the weight file.
///
/// # Errors
/// Bad parameters as a [`ParamError`], a failed precomputation, training or write.
pub fn run(args: &DaylightSkyArgs, output: &mut dyn Write) -> Result<()> {
    if ![6, 12, 24, 48].contains(&args.hidden) {
        return Err(ParamError(format!(
            "--hidden {}: expected 6, 12, 24 or 48 (the layouts sky-core ships)",
            args.hidden
        ))
        .into());
    }
    if let Some(out) = &args.out {
        crate::args::check_output("--out", out, "skyn")?;
    }
    let dir = cache::CacheDir::new(args.cache_dir.as_deref());
    let atmospheres = AOD_NODES
        .iter()
        .map(|&aod| {
            Ok((
                aod,
                cache::load_or_build_in(
                    &atmosphere(aod),
                    &Resolution::default(),
                    Some(&dir),
                    true,
                )?,
            ))
        })
        .collect::<Result<Vec<_>>>()?;
    let mut config = TrainConfig::new(ModelKind::Physical);
    config.hidden = vec![args.hidden];
    config.seed = u64::from(args.seed);
    config.max_seconds = args.max_seconds;
    config.max_iterations = args.max_iterations as usize;
    let n_zeniths = args
        .sun_zeniths
        .map_or(args.part.sun_zeniths(), usize::from);
    let zeniths = daylight_sky::zeniths(args.part, n_zeniths);
    let strata = (
        usize::from(args.view_zeniths),
        usize::from(args.view_azimuths),
    );
    let set = daylight_sky::training_set(&atmospheres, &zeniths, strata, config.seed)?;
    // Validation: between the training zeniths, every atmosphere.
    let (lo, hi) = args.part.zenith_range();
    #[allow(clippy::cast_precision_loss)]
    let step = (hi - lo) / (n_zeniths - 1) as f64;
    let between: Vec<f64> = zeniths
        .windows(2)
        .step_by(3)
        .map(|w| 0.5 * (w[0] + w[1]))
        .collect();
    let validation = daylight_sky::images(&atmospheres, &between)?;
    let trained = train::train(&config, &set, validation.as_slice())?;
    writeln!(
        output,
        "trained {:?} on {} skies ({} examples, zenith step {step:.1} deg): {} iterations, {:.1} s",
        trained.net.sizes,
        set.cases.len(),
        trained.examples,
        trained.iterations,
        trained.seconds
    )?;
    let dirs = train::dataset::test_directions();
    let (mut worst, mut at) = (0.0f64, (0.0, 0.0));
    for im in validation
        .iter()
        .filter(|im| im.case.sun_zenith.to_degrees() <= 96.0)
    {
        let p = trained.predict(im.case, &dirs, train::dataset::TEST_SUN_AZIMUTH);
        let e = train::dataset::nrmse(&im.reference, &p);
        if e > worst {
            (worst, at) = (e, (im.case.turbidity, im.case.sun_zenith.to_degrees()));
        }
    }
    writeln!(
        output,
        "validation NRMSE mean {:.5} ({} images), worst from -6 to 90 deg elevation {worst:.5} (aod {}, sun zenith {:.1} deg)",
        trained.validation_nrmse,
        validation.len(),
        at.0,
        at.1
    )?;
    if let Some(path) = &args.out {
        match args.hidden {
            6 => write::<6>(&trained, args.part, args.seed, path)?,
            12 => write::<12>(&trained, args.part, args.seed, path)?,
            24 => write::<24>(&trained, args.part, args.seed, path)?,
            48 => write::<48>(&trained, args.part, args.seed, path)?,
            _ => bail!("unreachable layout"),
        }
        writeln!(output, "wrote {}", path.display())?;
    }
    Ok(())
}
