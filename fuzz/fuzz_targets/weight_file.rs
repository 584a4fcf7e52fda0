//! Any bytes as a 6-12-3 weight file, as they are and with a valid checksum: decoding never
//! panics; whatever decodes encodes back to the same bytes, makes skies (f32 and fixed point)
//! wherever its header says it was trained (or is refused for weights so large that the
//! network folded for the sky overflows f32), and they are finite and non-negative in every
//! direction.
#![no_main]

use libfuzzer_sys::fuzz_target;
use sky_core::neural::{FixedNeuralSky, FixedNeuralWeights, NeuralSky, NeuralWeights};
use sky_core::{SkyError, Sun, Vec3};

fuzz_target!(|data: &[u8]| {
    check(data);
    // The same bytes with their checksum made valid, so that the fields behind it are reached.
    if data.len() >= 4 {
        let mut sealed = data.to_vec();
        let n = sealed.len();
        let crc = sky_core::neural::weights::crc32(&sealed[..n - 4]);
        sealed[n - 4..].copy_from_slice(&crc.to_le_bytes());
        check(&sealed);
    }
});

fn check(data: &[u8]) {
    let Ok(w) = NeuralWeights::<12>::decode(data) else {
        return;
    };
    let mut again = vec![0; NeuralWeights::<12>::ENCODED_LEN];
    w.encode(&mut again).expect("decoded weights encode");
    assert_eq!(again, data, "decoded weights re-encode differently");
    let (z0, z1) = w.sun_zenith_range;
    let (t0, t1) = w.turbidity_range;
    let fixed = FixedNeuralWeights::quantise(&w).ok();
    for (zenith, turbidity) in [(z0, t0), (z1, t1), (0.5 * (z0 + z1), 0.5 * (t0 + t1))] {
        let Ok(sun) = Sun::new(zenith, 1.0) else {
            continue;
        };
        let sky = match NeuralSky::new(&w, sun, turbidity) {
            Ok(sky) => sky,
            Err(SkyError::NotFinite {
                parameter: "network weights",
            }) => continue,
            Err(e) => panic!("inside the trained domain, yet {e}"),
        };
        let fixed_sky = fixed
            .as_ref()
            .map(|f| FixedNeuralSky::new(f, sun, turbidity));
        for dir in [
            Vec3::Z,
            Vec3::new(0.3, -0.2, 0.9),
            Vec3::new(-1.0, 0.0, 0.0),
            -Vec3::Z,
        ] {
            let rgb = sky.rgb(dir);
            assert!(rgb.is_finite() && rgb.min_element() >= 0.0, "{rgb}");
            if let Some(Ok(f)) = &fixed_sky {
                let _ = f.rgb([0, 0, 1000]);
            }
        }
    }
    // sky-train reads the same bytes from a file through the same decoder.
    let _ = w.source_name();
}
