//! Any bytes as a frame of a capture sequence (an OpenEXR file): headers and pixels are checked
//! and reduced as `sky-train captures` does; no input panics or allocates past the loader's
//! limits (libFuzzer's -malloc_limit_mb in scripts/fuzz.sh), and an accepted frame yields
//! finite samples inside the upper hemisphere.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    let Ok(frame) = sky_train::captures::load::frame_from_bytes(data) else {
        return;
    };
    assert!(frame.sun_zenith.is_finite() && frame.sun_zenith < std::f64::consts::FRAC_PI_2);
    for (v, t) in frame.views.iter().zip(&frame.targets) {
        assert!(v.iter().chain(t).all(|x| x.is_finite()), "{v:?} {t:?}");
        assert!(v[2] >= 0.0, "a sample below the horizon: {v:?}");
    }
});
