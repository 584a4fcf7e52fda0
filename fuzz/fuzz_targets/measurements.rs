//! Any bytes as a measurement file (`schedule --measurements`): rows are finite, non-negative,
//! in strictly increasing time, the diffuse part not above the global, or the error is one
//! line naming the file and a line; the schedule driven by the rows never panics.
#![no_main]

use libfuzzer_sys::fuzz_target;
use sky_core::measurement::Measurement;
use sky_train::controller::{ScheduleConfig, parse_measurements, schedule_measured};

const SOURCE: &str = "--measurements fuzz.csv";

fuzz_target!(|data: &[u8]| {
    let rows = match parse_measurements(&mut &data[..], SOURCE) {
        Ok(rows) => rows,
        Err(e) => {
            assert!(e.0.starts_with(SOURCE) && !e.0.contains('\n'), "{}", e.0);
            return;
        }
    };
    let valid = |v: f32| v.is_finite() && v >= 0.0;
    for pair in rows.windows(2) {
        assert!(pair[0].unix.0 < pair[1].unix.0);
    }
    for r in &rows {
        match r.measurement {
            Measurement::GlobalIlluminance(v) | Measurement::GlobalIrradiance(v) => {
                assert!(valid(v));
            }
            Measurement::Irradiance { global, diffuse } => {
                assert!(valid(global) && valid(diffuse) && diffuse <= global);
            }
        }
    }
    let config = ScheduleConfig {
        latitude: 48.21,
        longitude: 16.37,
        elevation: 0.0,
        date: (2026, 6, 21),
        step_minutes: 10,
        settings: sky_core::controller::Settings::default(),
    };
    let mut out = Vec::new();
    let _ = schedule_measured(&config, &rows, std::path::Path::new("fuzz.csv"), &mut out);
});
