//! `sky-train fuzz-weights`: a mutation fuzzer for sky-core's weight-file decoder, run by the
//! test command for a bounded time.
//!
//! Inputs are derived from a valid file by random byte flips, overwrites with interesting
//! values (NaN, ∞, 0, 0xff…), truncations, extensions and splices, half of them with the
//! checksum repaired so that the decoder's later checks are reached. Every input must decode
//! to `Ok` or a `WeightsError` without panicking, and whatever decodes must encode back to the
//! same bytes and evaluate to finite, non-negative radiance.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::time::{Duration, Instant};

use anyhow::{Result, bail};
use rand::{Rng, SeedableRng};
use sky_core::neural::{NeuralSky, NeuralWeights, pretrained};
use sky_core::{Sun, Vec3};

/// What a fuzzing run did.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct FuzzStats {
    /// Inputs tried.
    pub inputs: u64,
    /// Inputs that decoded.
    pub accepted: u64,
}

fn mutate(rng: &mut impl Rng, base: &[u8], other: &[u8]) -> Vec<u8> {
    let mut b = base.to_vec();
    for _ in 0..rng.random_range(1..=4) {
        match rng.random_range(0..6) {
            0 if !b.is_empty() => {
                let i = rng.random_range(0..b.len());
                b[i] ^= 1 << rng.random_range(0..8);
            }
            1 if b.len() >= 4 => {
                let i = rng.random_range(0..=b.len() - 4);
                let special: [[u8; 4]; 6] = [
                    f32::NAN.to_le_bytes(),
                    f32::INFINITY.to_le_bytes(),
                    0f32.to_le_bytes(),
                    (-1f32).to_le_bytes(),
                    [0xff; 4],
                    f32::MAX.to_le_bytes(),
                ];
                b[i..i + 4].copy_from_slice(&special[rng.random_range(0..special.len())]);
            }
            2 => b.truncate(rng.random_range(0..=b.len())),
            3 => b.extend((0..rng.random_range(1..16)).map(|_| rng.random::<u8>())),
            4 if !other.is_empty() && !b.is_empty() => {
                let i = rng.random_range(0..b.len());
                let j = rng.random_range(0..other.len());
                let n = rng.random_range(1..=(b.len() - i).min(other.len() - j));
                b[i..i + n].copy_from_slice(&other[j..j + n]);
            }
            _ if !b.is_empty() => {
                let i = rng.random_range(0..b.len());
                b[i] = rng.random();
            }
            _ => {}
        }
    }
    if b.len() >= 4 && rng.random_bool(0.5) {
        let n = b.len();
        let crc = sky_core::neural::weights::crc32(&b[..n - 4]);
        b[n - 4..].copy_from_slice(&crc.to_le_bytes());
    }
    b
}

/// Checks one input: no panic; accepted weights re-encode identically and evaluate finitely.
fn check(bytes: &[u8]) -> Result<bool> {
    let outcome = catch_unwind(AssertUnwindSafe(|| -> Result<bool> {
        let Ok(w) = NeuralWeights::<12>::decode(bytes) else {
            return Ok(false);
        };
        let mut again = vec![0; NeuralWeights::<12>::ENCODED_LEN];
        w.encode(&mut again).map_err(|e| anyhow::anyhow!("{e}"))?;
        if again != bytes {
            bail!("decoded weights re-encode differently");
        }
        let (z0, z1) = w.sun_zenith_range;
        let (t0, t1) = w.turbidity_range;
        if let Ok(sun) = Sun::new(0.5 * (z0 + z1), 1.0)
            && let Ok(sky) = NeuralSky::new(&w, sun, 0.5 * (t0 + t1))
        {
            let rgb = sky.rgb(Vec3::new(0.3, 0.2, 0.9));
            if !(rgb.is_finite() && rgb.min_element() >= 0.0) {
                bail!("accepted weights give radiance {rgb}");
            }
        }
        Ok(true)
    }));
    match outcome {
        Ok(r) => r,
        Err(_) => bail!("the decoder panicked"),
    }
}

/// Fuzzes the decoder for `duration` from `seed`.
///
/// # Errors
/// On the first input that breaks a property; the message holds the input in hex.
pub fn fuzz_weights(duration: Duration, seed: u64) -> Result<FuzzStats> {
    let mut valid = vec![0; NeuralWeights::<12>::ENCODED_LEN];
    pretrained::PREETHAM
        .encode(&mut valid)
        .map_err(|e| anyhow::anyhow!("{e}"))?;
    let mut other = vec![0; NeuralWeights::<12>::ENCODED_LEN];
    pretrained::HOSEK
        .encode(&mut other)
        .map_err(|e| anyhow::anyhow!("{e}"))?;
    let mut rng = rand::rngs::StdRng::seed_from_u64(seed);
    let mut stats = FuzzStats::default();
    let start = Instant::now();
    while start.elapsed() < duration {
        let input = mutate(&mut rng, &valid, &other);
        stats.inputs += 1;
        match check(&input) {
            Ok(accepted) => stats.accepted += u64::from(accepted),
            Err(e) => {
                let hex: String = input.iter().map(|b| format!("{b:02x}")).collect();
                bail!("{e} on input {hex}");
            }
        }
    }
    Ok(stats)
}
