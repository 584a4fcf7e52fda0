//! Any text as a capture manifest (`captures.toml`): parsing and checking never panic; every
//! time an accepted manifest holds converts and prints, and with a site gives a sun position.
#![no_main]

use libfuzzer_sys::fuzz_target;
use sky_train::captures::manifest::{Manifest, UnixTime};

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(m) = Manifest::parse(text, std::path::Path::new("captures.toml")) else {
        return;
    };
    let site = match (m.latitude, m.longitude) {
        (Some(lat), Some(lon)) => {
            sky_core::solar::Site::new(lat, lon, m.elevation.unwrap_or(0.0)).ok()
        }
        _ => None,
    };
    for f in &m.frames {
        if let Some(t) = &f.time {
            let t = UnixTime::parse(t).expect("checked by parse");
            let _ = t.rfc3339();
            if let Some(site) = &site {
                let _ = t.sun_position(site);
            }
        }
    }
});
