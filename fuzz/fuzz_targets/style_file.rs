//! Any text as an AOAS style file: parsing never panics; an accepted style makes a sky
//! (`style_file::parse` promises it), finite and non-negative in every direction.
#![no_main]

use libfuzzer_sys::fuzz_target;
use sky_core::Vec3;
use sky_core::aoas::AoasSky;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok((scattering, style)) = sky_train::style_file::parse("fuzz.toml", text) else {
        return;
    };
    let sky = AoasSky::new(&scattering, &style).expect("parse checks every value");
    for dir in [
        Vec3::Z,
        Vec3::new(0.6, 0.0, 0.8),
        Vec3::new(0.0, -1.0, 0.01),
        -Vec3::Z,
    ] {
        let rgb = sky.rgb(dir);
        assert!(rgb.is_finite() && rgb.min_element() >= 0.0, "{rgb}");
    }
});
