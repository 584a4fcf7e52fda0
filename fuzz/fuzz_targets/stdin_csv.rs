//! Any bytes on stdin for the CSV readers: rows are two finite numbers or one-line errors, and
//! `cct`'s whole pipeline (parse, CCT/Duv, output) never panics.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    for row in sky_train::csv_input::rows(&mut &data[..], ["view_zenith_deg", "view_azimuth_deg"]) {
        match row {
            Ok(r) => assert!(r.values.iter().all(|v| v.is_finite())),
            Err(e) => assert!(
                !e.0.contains('\n') && e.0.starts_with("stdin line")
                    || e.0.starts_with("cannot read")
            ),
        }
    }
    let mut out = Vec::new();
    let _ = sky_train::commands::cct::run(&mut &data[..], &mut out);
});
