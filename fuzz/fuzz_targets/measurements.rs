//! Any bytes as a measurement file (`schedule --measurements`) in any of its formats (CSV,
//! SURFRAD, MIDC, SRML, BSRN; the first byte chooses, modulo 5: the seeds start with `U`, CSV,
//! `G`, SURFRAD, `H`, MIDC (its raw data and its web download), `D`, SRML, or `E`, BSRN): the
//! rows handed on are finite and in strictly
//! increasing time, or the error is one line naming the file; the controller step that each
//! row drives (as `schedule` runs it) never panics, and a step it accepts is finite.
#![no_main]

use libfuzzer_sys::fuzz_target;
use sky_core::controller::{Settings, example_luminaire, step};
use sky_core::measurement::Measurement;
use sky_core::solar::Site;
use sky_train::controller::{MeasurementFormat, parse_measurements};

const SOURCE: &str = "--measurements fuzz.csv";

fuzz_target!(|data: &[u8]| {
    let Some((&first, text)) = data.split_first() else {
        return;
    };
    let format = match first % 5 {
        0 => MeasurementFormat::Csv,
        1 => MeasurementFormat::Surfrad,
        2 => MeasurementFormat::Midc,
        3 => MeasurementFormat::Srml,
        _ => MeasurementFormat::Bsrn,
    };
    let site = Site::new(48.21, 16.37, 0.0).expect("a valid site");
    let lamp = example_luminaire().expect("the example luminaire");
    let settings = Settings::default();
    let mut previous: Option<f64> = None;
    let parsed = parse_measurements(&mut &text[..], SOURCE, format, &mut |r| {
        if let Some(t) = previous {
            assert!(t < r.unix.0, "times not increasing");
        }
        previous = Some(r.unix.0);
        match r.measurement {
            Measurement::GlobalIlluminance(v) | Measurement::GlobalIrradiance(v) => {
                assert!(v.is_finite());
            }
            Measurement::Irradiance { global, diffuse } => {
                assert!(global.is_finite() && diffuse.is_finite());
            }
        }
        // The step `schedule` runs for the row: an error (a reading sky-core refuses) or
        // finite values.
        if let Ok(s) = step(&r.time, &site, &settings, &lamp, Some(r.measurement)) {
            assert!(s.illuminance.is_finite() && s.melanopic_edi.is_finite());
            assert!(s.drive.levels.iter().all(|l| l.is_finite()));
        }
        Ok(())
    });
    if let Err(e) = parsed {
        let message = format!("{e:#}");
        assert!(
            message.starts_with(SOURCE) && !message.contains('\n'),
            "{message}"
        );
    }
});
