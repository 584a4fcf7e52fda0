//! The Preetham sky and the neural sky that learned it, side by side along one meridian.
//!
//! `cargo run -p sky-core --example preetham`

use sky_core::neural::pretrained;
use sky_core::{NeuralSky, PreethamSky, SkyError, Sun, geom};

fn main() -> Result<(), SkyError> {
    let sun = Sun::new(60f32.to_radians(), 0.0)?; // 30° above the horizon, azimuth 0
    let preetham = PreethamSky::new(sun, 3.0)?; // turbidity 3: a clear day
    let neural = NeuralSky::new(&pretrained::PREETHAM, sun, 3.0)?;
    println!("view zenith   Preetham Y (cd/m²)   x       y       neural R, G, B (linear sRGB)");
    for zenith_deg in (0..=90).step_by(15) {
        let view = geom::direction((zenith_deg as f32).to_radians(), 0.0);
        let c = preetham.xyy(view);
        let n = neural.rgb(view);
        println!(
            "{zenith_deg:>8}°   {:>14.1}   {:.4}  {:.4}   {:.1}, {:.1}, {:.1}",
            c.luminance, c.x, c.y, n.x, n.y, n.z
        );
    }
    Ok(())
}
