//! Any bytes as a physical-atmosphere cache file (sky-train's `physical/cache.rs`), as they are
//! and sealed (the magic, format version and key of the default atmosphere in front, a valid
//! checksum behind), so that the tables behind the header are reached. The resolution is a
//! small one (a file of some 11 kB, within `-max_len`) of the same layout as the default's.
//! Decoding never panics; whatever decodes holds only finite, non-negative tables (the checks
//! a load applies, so that a bad file is rebuilt rather than used) and encodes back to the
//! same bytes.
#![no_main]

use libfuzzer_sys::fuzz_target;
use sky_train::physical::cache;
use sky_train::physical::{Atmosphere, Resolution};

fuzz_target!(|data: &[u8]| {
    let atmosphere = Atmosphere::default();
    let resolution = cache::small_resolution();
    check(data, &atmosphere, &resolution);
    let sealed = cache::seal(data, cache::version_key(&atmosphere, &resolution));
    check(&sealed, &atmosphere, &resolution);
});

fn check(bytes: &[u8], atmosphere: &Atmosphere, resolution: &Resolution) {
    let Ok(atm) = cache::decode(bytes, atmosphere, resolution) else {
        return;
    };
    let again = cache::encode(&atm, cache::version_key(atmosphere, resolution));
    assert_eq!(again, bytes, "a decoded cache file re-encodes differently");
    let t = &atm.transmittance;
    assert!(
        t.columns
            .iter()
            .flatten()
            .all(|v| v.is_finite() && *v >= 0.0)
    );
    let g = &atm.ground;
    for table in [&g.rayleigh, &g.aerosol, &g.multiple] {
        assert!(table.data.iter().all(|v| v.is_finite() && *v >= 0.0));
    }
    assert!(
        g.diffuse
            .iter()
            .flatten()
            .all(|v| v.is_finite() && *v >= 0.0)
    );
}
