//! A daylight luminaire's day: every two hours of the 2026 June solstice in Vienna, the sun's
//! elevation, the global daylight's horizontal illuminance and colour temperature, and the levels of an
//! example RGBW luminaire (`sky_core::controller::step`, as the firmware computes it).
//!
//! `cargo run -p sky-core --example controller`

use sky_core::SkyError;
use sky_core::controller::{Settings, example_luminaire, step};
use sky_core::solar::{Site, UtcTime};

fn main() -> Result<(), SkyError> {
    let site = Site::new(48.21, 16.37, 190.0)?; // latitude, longitude (deg), elevation (m)
    let lamp = example_luminaire()?;
    println!("UTC    sun elevation   horizontal lux   CCT (K)   R     G     B     W");
    for hour in (0..24).step_by(2) {
        let time = UtcTime::new(2026, 6, 21, hour, 0, 0.0)?;
        // The default atmosphere, the global light, full output at 10,000 lx.
        let s = step(&time, &site, &Settings::default(), &lamp, None)?;
        let cct = s.cct.map_or(f32::NAN, |c| c.kelvin); // none in nautical twilight
        let [r, g, b, w] = s.drive.levels;
        println!(
            "{hour:02}:00  {:>10.2}°   {:>14.1}   {:>7.0}   {r:.3} {g:.3} {b:.3} {w:.3}",
            s.sun.elevation_deg(),
            s.illuminance.y,
            cct
        );
    }
    Ok(())
}
