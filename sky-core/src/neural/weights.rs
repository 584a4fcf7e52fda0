//! Neural-sky weights and their binary file format, decoded and encoded without allocation.
//!
//! # File format, version 1 (all numbers little-endian)
//!
//! | offset | bytes | field |
//! |---:|---:|---|
//! | 0 | 4 | magic `SKYN` |
//! | 4 | 2 | format version, `1` |
//! | 6 | 1 | inputs, `6` |
//! | 7 | 1 | hidden neurons H (1-255) |
//! | 8 | 1 | outputs, `3` |
//! | 9 | 1 | flags: bit 0 = the turbidity input is used; other bits 0 |
//! | 10 | 2 | reserved, must be 0 |
//! | 12 | 24 | input offsets, 6 × f32 |
//! | 36 | 24 | input scales, 6 × f32 |
//! | 60 | 12 | output scales, 3 × f32 (> 0) |
//! | 72 | 8 | trained turbidity range, 2 × f32 (min ≤ max) |
//! | 80 | 8 | trained sun-zenith range in radians, 2 × f32 (0 ≤ min ≤ max ≤ π) |
//! | 88 | 32 | source model, printable ASCII (space to `~`), NUL-padded (e.g. `preetham`) |
//! | 120 | 4 | training seed, u32 |
//! | 124 | 4 | held-out NRMSE reached in training, f32 |
//! | 128 | 4 · (6H + H + 3H + 3) | hidden weights H × 6 (row per neuron, inputs in V's order), hidden biases H, output weights 3 × H (row per channel), output biases 3 |
//! | end − 4 | 4 | CRC-32 (IEEE 802.3, as zlib) of every byte before it |
//!
//! Every float must be finite. A file for H = 12 is 128 + 492 + 4 = 624 bytes.

use core::fmt;

use super::{INPUTS, OUTPUTS};
use crate::error::{write_decimal, write_hex32};

/// The file's magic number.
pub const MAGIC: [u8; 4] = *b"SKYN";
/// The format version this crate reads and writes.
pub const VERSION: u16 = 1;
/// Header bytes before the weights.
pub const HEADER_LEN: usize = 128;

/// CRC-32 (IEEE 802.3 polynomial, reflected, as zlib and PNG) of `bytes`: the weight file's
/// checksum.
///
/// Computed four bits at a time from a 16-entry table (64 bytes), not the 1-16 KB tables of
/// the fast crates: a weight file is checked once, and on firmware and in the .wasm the flash
/// matters more than the microseconds.
///
/// ```
/// // The CRC-32 check value (the checksum of the ASCII digits 1 to 9).
/// assert_eq!(sky_core::neural::weights::crc32(b"123456789"), 0xCBF4_3926);
/// ```
#[must_use]
pub fn crc32(bytes: &[u8]) -> u32 {
    /// The remainder of each nibble, reflected polynomial 0xEDB88320.
    const TABLE: [u32; 16] = {
        let mut table = [0; 16];
        let mut n = 0;
        while n < 16 {
            let mut c = n as u32;
            let mut k = 0;
            while k < 4 {
                c = if c & 1 == 1 {
                    0xEDB8_8320 ^ (c >> 1)
                } else {
                    c >> 1
                };
                k += 1;
            }
            table[n] = c;
            n += 1;
        }
        table
    };
    let mut crc = !0u32;
    for &b in bytes {
        crc = TABLE[((crc ^ u32::from(b)) & 0xF) as usize] ^ (crc >> 4);
        crc = TABLE[((crc ^ (u32::from(b) >> 4)) & 0xF) as usize] ^ (crc >> 4);
    }
    !crc
}

/// Whether `source` is a model name as the file stores it: printable ASCII (space to `~`), then
/// NUL padding to the end. A name never holds a control character (it is printed and written
/// into generated source), nor anything after its first NUL.
fn is_model_name(source: &[u8; 32]) -> bool {
    let end = source.iter().position(|&b| b == 0).unwrap_or(source.len());
    source[..end].iter().all(|b| (b' '..=b'~').contains(b)) && source[end..].iter().all(|&b| b == 0)
}

/// The size in bytes of a weight file for `hidden` neurons.
#[must_use]
pub const fn encoded_len(hidden: usize) -> usize {
    HEADER_LEN + 4 * (INPUTS * hidden + hidden + OUTPUTS * hidden + OUTPUTS) + 4
}

/// Why a weight file could not be decoded (or encoded).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum WeightsError {
    /// The data ends before the file does.
    Truncated {
        /// Bytes the file needs.
        needed: usize,
        /// Bytes given.
        got: usize,
    },
    /// More bytes than the file's shape accounts for.
    TrailingBytes {
        /// Bytes the file needs.
        needed: usize,
        /// Bytes given.
        got: usize,
    },
    /// The first four bytes are not `SKYN`.
    BadMagic([u8; 4]),
    /// A format version this crate does not read.
    UnsupportedVersion(u16),
    /// The layer sizes differ from the network type's.
    WrongShape {
        /// Inputs, hidden neurons and outputs in the file.
        found: [u8; 3],
        /// Inputs, hidden neurons and outputs expected.
        expected: [usize; 3],
    },
    /// The stored CRC-32 does not match the data.
    ChecksumMismatch {
        /// The checksum in the file.
        stored: u32,
        /// The checksum of the data.
        computed: u32,
    },
    /// A float field is NaN or infinite.
    NonFinite {
        /// Which field.
        field: &'static str,
    },
    /// A header field holds an invalid value (unknown flag bits, a reversed range, a
    /// non-positive output scale, a model name with a control or non-ASCII character or with
    /// bytes after its NUL padding).
    InvalidHeader {
        /// Which field.
        field: &'static str,
    },
    /// The output buffer given to [`NeuralWeights::encode`] is too small.
    BufferTooSmall {
        /// Bytes needed.
        needed: usize,
    },
}

impl WeightsError {
    /// Writes the message (the text of [`Display`](fmt::Display)) into `out` without
    /// `core::fmt`'s formatting machinery (integers digit by digit): a size-bound build, such
    /// as the browser's, gets the message without linking it. (`out` is a trait object: the
    /// message code is compiled once, in this crate.)
    ///
    /// ```
    /// use sky_core::neural::WeightsError;
    ///
    /// let e = WeightsError::Truncated { needed: 624, got: 10 };
    /// let mut text = String::new();
    /// e.write_message(&mut text)?;
    /// assert_eq!(text, "weight file truncated: 10 bytes, needs 624");
    /// assert_eq!(text, e.to_string());
    /// # Ok::<(), core::fmt::Error>(())
    /// ```
    ///
    /// # Errors
    /// What `out` returns.
    pub fn write_message(&self, out: &mut dyn fmt::Write) -> fmt::Result {
        let decimal = |out: &mut dyn fmt::Write, n: usize| write_decimal(out, n as u64);
        match *self {
            Self::Truncated { needed, got } => {
                out.write_str("weight file truncated: ")?;
                decimal(out, got)?;
                out.write_str(" bytes, needs ")?;
                decimal(out, needed)
            }
            Self::TrailingBytes { needed, got } => {
                out.write_str("weight file has ")?;
                decimal(out, got)?;
                out.write_str(" bytes, ")?;
                decimal(out, got.saturating_sub(needed))?;
                out.write_str(" more than its ")?;
                decimal(out, needed)?;
                out.write_str("-byte shape")
            }
            Self::BadMagic(m) => {
                // The magic as `{m:?}` writes it: `[83, 75, 89, 78]`.
                out.write_str("not a weight file: magic [")?;
                for (k, b) in m.iter().enumerate() {
                    if k > 0 {
                        out.write_str(", ")?;
                    }
                    decimal(out, usize::from(*b))?;
                }
                out.write_str("], expected \"SKYN\"")
            }
            Self::UnsupportedVersion(v) => {
                out.write_str("weight file version ")?;
                decimal(out, usize::from(v))?;
                out.write_str(" is not supported (only ")?;
                decimal(out, usize::from(VERSION))?;
                out.write_str(")")
            }
            Self::WrongShape { found, expected } => {
                out.write_str("weight file is a ")?;
                for (k, n) in found
                    .iter()
                    .map(|&n| usize::from(n))
                    .chain(expected)
                    .enumerate()
                {
                    out.write_str(match k {
                        0 => "",
                        3 => " network, expected ",
                        _ => "-",
                    })?;
                    decimal(out, n)?;
                }
                Ok(())
            }
            Self::ChecksumMismatch { stored, computed } => {
                out.write_str("weight file checksum mismatch: stored ")?;
                write_hex32(out, stored)?;
                out.write_str(", data gives ")?;
                write_hex32(out, computed)
            }
            Self::NonFinite { field } => {
                out.write_str("weight file field ")?;
                out.write_str(field)?;
                out.write_str(" is not finite")
            }
            Self::InvalidHeader { field } => {
                out.write_str("weight file header field ")?;
                out.write_str(field)?;
                out.write_str(" is invalid")
            }
            Self::BufferTooSmall { needed } => {
                out.write_str("output buffer too small: ")?;
                decimal(out, needed)?;
                out.write_str(" bytes needed")
            }
        }
    }
}

impl fmt::Display for WeightsError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.write_message(f)
    }
}

impl core::error::Error for WeightsError {}

/// The weights of a 6-H-3 neural sky, its input/output normalisation and its training domain.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct NeuralWeights<const H: usize = 12> {
    /// Hidden-layer weights: row j holds neuron j's weights for the normalised inputs
    /// u = (√t, θ_sun, v_x, v_y, v_z, d).
    pub hidden: [[f32; INPUTS]; H],
    /// Hidden-layer biases.
    pub hidden_bias: [f32; H],
    /// Output-layer weights: row c holds channel c's weights (R, G, B).
    pub output: [[f32; H]; OUTPUTS],
    /// Output-layer biases.
    pub output_bias: [f32; OUTPUTS],
    /// u_k = (V_k − input_offset_k) · input_scale_k.
    pub input_offset: [f32; INPUTS],
    /// See [`input_offset`](Self::input_offset).
    pub input_scale: [f32; INPUTS],
    /// Radiance of channel c = output_scale_c · L_s(y_c) (eq. 7).
    pub output_scale: [f32; OUTPUTS],
    /// Whether the network reads turbidity (false: input 0 is zeroed, as for captured skies).
    pub uses_turbidity: bool,
    /// The turbidities the network was trained on, inclusive.
    pub turbidity_range: (f32, f32),
    /// The sun zenith angles (radians) the network was trained on, inclusive.
    pub sun_zenith_range: (f32, f32),
    /// The source model's name, printable ASCII, NUL-padded.
    pub source: [u8; 32],
    /// The training run's random seed.
    pub seed: u32,
    /// The held-out NRMSE the training reached.
    pub nrmse: f32,
}

/// Reads little-endian values from a byte slice whose length was checked beforehand.
struct Reader<'a> {
    bytes: &'a [u8],
    pos: usize,
}

impl Reader<'_> {
    fn take<const N: usize>(&mut self) -> [u8; N] {
        let mut out = [0u8; N];
        if let Some(src) = self.bytes.get(self.pos..self.pos + N) {
            out.copy_from_slice(src);
        }
        self.pos += N;
        out
    }

    fn f32(&mut self, field: &'static str) -> Result<f32, WeightsError> {
        let v = f32::from_le_bytes(self.take());
        if v.is_finite() {
            Ok(v)
        } else {
            Err(WeightsError::NonFinite { field })
        }
    }

    fn f32s<const N: usize>(&mut self, field: &'static str) -> Result<[f32; N], WeightsError> {
        let mut out = [0.0; N];
        self.fill(&mut out, field)?;
        Ok(out)
    }

    /// Reads `out.len()` floats into `out`. Never inlined and not generic: compiled once.
    #[inline(never)]
    fn fill(&mut self, out: &mut [f32], field: &'static str) -> Result<(), WeightsError> {
        for v in out {
            *v = self.f32(field)?;
        }
        Ok(())
    }
}

/// A weight file's header fields, checked: everything but the weights.
struct Header {
    flags: u8,
    input_offset: [f32; INPUTS],
    input_scale: [f32; INPUTS],
    output_scale: [f32; OUTPUTS],
    turbidity_range: (f32, f32),
    sun_zenith_range: (f32, f32),
    source: [u8; 32],
    seed: u32,
    nrmse: f32,
}

impl Header {
    /// Checks `bytes` as a weight file of a network with `hidden` neurons (its length, magic,
    /// version, shape and checksum) and reads its header; returns the header and the reader at
    /// the first weight. Not generic over the network size and never inlined, so that it is
    /// compiled once, at this crate's optimisation level, rather than into every caller of
    /// [`NeuralWeights::decode`] (the .wasm's code is built for speed where it draws, not here).
    #[inline(never)]
    fn decode(bytes: &[u8], hidden: usize) -> Result<(Self, Reader<'_>), WeightsError> {
        let needed = encoded_len(hidden);
        if bytes.len() < HEADER_LEN.min(needed) || bytes.len() < 12 {
            return Err(WeightsError::Truncated {
                needed,
                got: bytes.len(),
            });
        }
        let mut r = Reader { bytes, pos: 0 };
        let magic: [u8; 4] = r.take();
        if magic != MAGIC {
            return Err(WeightsError::BadMagic(magic));
        }
        let version = u16::from_le_bytes(r.take());
        if version != VERSION {
            return Err(WeightsError::UnsupportedVersion(version));
        }
        let shape: [u8; 3] = r.take();
        if [
            usize::from(shape[0]),
            usize::from(shape[1]),
            usize::from(shape[2]),
        ] != [INPUTS, hidden, OUTPUTS]
        {
            return Err(WeightsError::WrongShape {
                found: shape,
                expected: [INPUTS, hidden, OUTPUTS],
            });
        }
        if bytes.len() < needed {
            return Err(WeightsError::Truncated {
                needed,
                got: bytes.len(),
            });
        }
        if bytes.len() > needed {
            return Err(WeightsError::TrailingBytes {
                needed,
                got: bytes.len(),
            });
        }
        let (body, crc) = bytes.split_at(needed - 4);
        let stored = u32::from_le_bytes([crc[0], crc[1], crc[2], crc[3]]);
        let computed = crc32(body);
        if stored != computed {
            return Err(WeightsError::ChecksumMismatch { stored, computed });
        }
        let [flags]: [u8; 1] = r.take();
        if flags & !1 != 0 {
            return Err(WeightsError::InvalidHeader { field: "flags" });
        }
        let reserved: [u8; 2] = r.take();
        if reserved != [0, 0] {
            return Err(WeightsError::InvalidHeader { field: "reserved" });
        }
        let input_offset = r.f32s("input offsets")?;
        let input_scale = r.f32s("input scales")?;
        let output_scale: [f32; OUTPUTS] = r.f32s("output scales")?;
        if output_scale.iter().any(|&s| s <= 0.0) {
            return Err(WeightsError::InvalidHeader {
                field: "output scales",
            });
        }
        let [tmin, tmax] = r.f32s("turbidity range")?;
        if tmin > tmax {
            return Err(WeightsError::InvalidHeader {
                field: "turbidity range",
            });
        }
        let [zmin, zmax] = r.f32s("sun zenith range")?;
        if !(0.0 <= zmin && zmin <= zmax && zmax <= core::f32::consts::PI) {
            return Err(WeightsError::InvalidHeader {
                field: "sun zenith range",
            });
        }
        let source: [u8; 32] = r.take();
        if !is_model_name(&source) {
            return Err(WeightsError::InvalidHeader {
                field: "source model",
            });
        }
        let seed = u32::from_le_bytes(r.take());
        let nrmse = r.f32("training NRMSE")?;
        let header = Self {
            flags,
            input_offset,
            input_scale,
            output_scale,
            turbidity_range: (tmin, tmax),
            sun_zenith_range: (zmin, zmax),
            source,
            seed,
            nrmse,
        };
        Ok((header, r))
    }
}

/// Writes little-endian values into a byte slice whose length was checked beforehand.
struct Writer<'a> {
    bytes: &'a mut [u8],
    pos: usize,
}

impl Writer<'_> {
    fn put(&mut self, src: &[u8]) {
        if let Some(dst) = self.bytes.get_mut(self.pos..self.pos + src.len()) {
            dst.copy_from_slice(src);
        }
        self.pos += src.len();
    }

    fn f32s(&mut self, values: &[f32]) {
        for v in values {
            self.put(&v.to_le_bytes());
        }
    }
}

impl<const H: usize> NeuralWeights<H> {
    /// The size of this network's weight file in bytes.
    pub const ENCODED_LEN: usize = encoded_len(H);

    /// The source model's name (up to the first NUL).
    #[must_use]
    pub fn source_name(&self) -> &str {
        let end = self
            .source
            .iter()
            .position(|&b| b == 0)
            .unwrap_or(self.source.len());
        core::str::from_utf8(&self.source[..end]).unwrap_or("")
    }

    /// Decodes a weight file (see the module docs for the format).
    ///
    /// # Errors
    /// A [`WeightsError`] for every malformed input: truncated or overlong data, bad magic,
    /// unknown version, layer sizes other than 6-H-3, a checksum mismatch, non-finite floats
    /// and invalid header values.
    pub fn decode(bytes: &[u8]) -> Result<Self, WeightsError> {
        let (header, mut r) = Header::decode(bytes, H)?;
        let mut hidden = [[0.0; INPUTS]; H];
        r.fill(hidden.as_flattened_mut(), "hidden weights")?;
        let hidden_bias = r.f32s("hidden biases")?;
        let mut output = [[0.0; H]; OUTPUTS];
        r.fill(output.as_flattened_mut(), "output weights")?;
        let output_bias = r.f32s("output biases")?;
        Ok(Self {
            hidden,
            hidden_bias,
            output,
            output_bias,
            input_offset: header.input_offset,
            input_scale: header.input_scale,
            output_scale: header.output_scale,
            uses_turbidity: header.flags & 1 == 1,
            turbidity_range: header.turbidity_range,
            sun_zenith_range: header.sun_zenith_range,
            source: header.source,
            seed: header.seed,
            nrmse: header.nrmse,
        })
    }

    /// Encodes the weights into `buf` (at least [`Self::ENCODED_LEN`] bytes) and returns the
    /// number of bytes written.
    ///
    /// # Errors
    /// [`WeightsError::BufferTooSmall`] when `buf` is too short; [`WeightsError::WrongShape`]
    /// when H exceeds 255; [`WeightsError::InvalidHeader`] for a source name the decoder would
    /// refuse (see the module docs).
    pub fn encode(&self, buf: &mut [u8]) -> Result<usize, WeightsError> {
        let needed = Self::ENCODED_LEN;
        let Ok(hidden) = u8::try_from(H) else {
            return Err(WeightsError::WrongShape {
                found: [6, 255, 3],
                expected: [INPUTS, H, OUTPUTS],
            });
        };
        let Some(buf) = buf.get_mut(..needed) else {
            return Err(WeightsError::BufferTooSmall { needed });
        };
        if !is_model_name(&self.source) {
            return Err(WeightsError::InvalidHeader {
                field: "source model",
            });
        }
        let mut w = Writer { bytes: buf, pos: 0 };
        w.put(&MAGIC);
        w.put(&VERSION.to_le_bytes());
        w.put(&[6, hidden, 3, u8::from(self.uses_turbidity), 0, 0]);
        w.f32s(&self.input_offset);
        w.f32s(&self.input_scale);
        w.f32s(&self.output_scale);
        w.f32s(&[self.turbidity_range.0, self.turbidity_range.1]);
        w.f32s(&[self.sun_zenith_range.0, self.sun_zenith_range.1]);
        w.put(&self.source);
        w.put(&self.seed.to_le_bytes());
        w.f32s(&[self.nrmse]);
        for row in &self.hidden {
            w.f32s(row);
        }
        w.f32s(&self.hidden_bias);
        for row in &self.output {
            w.f32s(row);
        }
        w.f32s(&self.output_bias);
        let crc = crc32(&w.bytes[..needed - 4]);
        w.put(&crc.to_le_bytes());
        Ok(needed)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Deterministic, varied weights (no training needed to test the format).
    fn sample() -> NeuralWeights<12> {
        let v = |i: usize| ((i * 7919 % 1000) as f32 - 500.0) / 250.0;
        NeuralWeights {
            hidden: core::array::from_fn(|j| core::array::from_fn(|k| v(j * 6 + k))),
            hidden_bias: core::array::from_fn(|j| v(100 + j)),
            output: core::array::from_fn(|c| core::array::from_fn(|j| v(200 + c * 12 + j))),
            output_bias: [0.1, -0.2, 0.3],
            input_offset: [1.9, 0.8, 0.0, 0.0, 0.5, 1.2],
            input_scale: [2.0, 1.5, 1.4, 1.4, 3.0, 1.1],
            output_scale: [9000.0, 9500.0, 12000.0],
            uses_turbidity: true,
            turbidity_range: (2.0, 6.0),
            sun_zenith_range: (0.0, core::f32::consts::FRAC_PI_2),
            source: *b"preetham\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0\0",
            seed: 42,
            nrmse: 0.0061,
        }
    }

    fn encoded() -> [u8; encoded_len(12)] {
        let mut buf = [0u8; encoded_len(12)];
        assert_eq!(sample().encode(&mut buf), Ok(624));
        buf
    }

    /// Rewrites the checksum after a deliberate change, so the decoder reaches the field check.
    fn reseal(buf: &mut [u8]) {
        let n = buf.len();
        let crc = crc32(&buf[..n - 4]);
        buf[n - 4..].copy_from_slice(&crc.to_le_bytes());
    }

    /// The nibble-table CRC against crc32fast (an independent implementation) over lengths 0 to
    /// 700 of pseudo-random bytes.
    #[test]
    fn crc32_agrees_with_crc32fast() {
        let bytes: [u8; 700] = core::array::from_fn(|i| (i.wrapping_mul(2_654_435_761) >> 7) as u8);
        for n in 0..=bytes.len() {
            assert_eq!(
                crc32(&bytes[..n]),
                crc32fast::hash(&bytes[..n]),
                "length {n}"
            );
        }
    }

    #[test]
    fn round_trip_and_size() {
        assert_eq!(NeuralWeights::<12>::ENCODED_LEN, 624);
        assert_eq!(4 * (6 * 12 + 12 + 3 * 12 + 3), 492, "the paper's 492 bytes");
        let buf = encoded();
        assert_eq!(&buf[..4], b"SKYN");
        assert_eq!(NeuralWeights::<12>::decode(&buf), Ok(sample()));
        assert_eq!(sample().source_name(), "preetham");
    }

    #[test]
    fn every_malformed_input_has_its_error() {
        let good = encoded();
        let decode = NeuralWeights::<12>::decode;
        assert_eq!(
            decode(&good[..600]),
            Err(WeightsError::Truncated {
                needed: 624,
                got: 600
            })
        );
        assert!(matches!(
            decode(&good[..5]),
            Err(WeightsError::Truncated { .. })
        ));
        assert!(matches!(decode(&[]), Err(WeightsError::Truncated { .. })));
        let mut long = [0u8; 625];
        long[..624].copy_from_slice(&good);
        assert_eq!(
            decode(&long),
            Err(WeightsError::TrailingBytes {
                needed: 624,
                got: 625
            })
        );
        let mut b = good;
        b[0] = b'X';
        assert_eq!(decode(&b), Err(WeightsError::BadMagic(*b"XKYN")));
        let mut b = good;
        b[4] = 2;
        assert_eq!(decode(&b), Err(WeightsError::UnsupportedVersion(2)));
        let mut b = good;
        b[7] = 24;
        assert_eq!(
            decode(&b),
            Err(WeightsError::WrongShape {
                found: [6, 24, 3],
                expected: [6, 12, 3]
            })
        );
        assert!(matches!(
            NeuralWeights::<24>::decode(&good),
            Err(WeightsError::WrongShape { .. })
        ));
        let mut b = good;
        b[300] ^= 1;
        assert!(matches!(
            decode(&b),
            Err(WeightsError::ChecksumMismatch { .. })
        ));
        let mut b = good;
        b[128..132].copy_from_slice(&f32::NAN.to_le_bytes());
        reseal(&mut b);
        assert_eq!(
            decode(&b),
            Err(WeightsError::NonFinite {
                field: "hidden weights"
            })
        );
        let mut b = good;
        b[60..64].copy_from_slice(&(-1.0f32).to_le_bytes());
        reseal(&mut b);
        assert_eq!(
            decode(&b),
            Err(WeightsError::InvalidHeader {
                field: "output scales"
            })
        );
        let mut b = good;
        b[11] = 0x80;
        reseal(&mut b);
        assert_eq!(
            decode(&b),
            Err(WeightsError::InvalidHeader { field: "reserved" })
        );
        let mut b = good;
        b[9] = 0b10;
        reseal(&mut b);
        assert_eq!(
            decode(&b),
            Err(WeightsError::InvalidHeader { field: "flags" })
        );
        let mut b = good;
        b[72..76].copy_from_slice(&7.0f32.to_le_bytes());
        reseal(&mut b);
        assert_eq!(
            decode(&b),
            Err(WeightsError::InvalidHeader {
                field: "turbidity range"
            })
        );
        let mut b = good;
        b[84..88].copy_from_slice(&4.0f32.to_le_bytes());
        reseal(&mut b);
        assert_eq!(
            decode(&b),
            Err(WeightsError::InvalidHeader {
                field: "sun zenith range"
            })
        );
        let mut b = good;
        b[90] = 0xff;
        reseal(&mut b);
        assert_eq!(
            decode(&b),
            Err(WeightsError::InvalidHeader {
                field: "source model"
            })
        );
        // Control characters (an escape sequence for a terminal, a newline for generated
        // source) and bytes after the padding starts are refused by both sides.
        for (at, byte) in [(90, 0x1b), (88, b'\n'), (100, b'x'), (88, 0x7f)] {
            let mut b = good;
            b[at] = byte;
            reseal(&mut b);
            assert_eq!(
                decode(&b),
                Err(WeightsError::InvalidHeader {
                    field: "source model"
                }),
                "byte {byte:#x} at {at}"
            );
            let mut w = sample();
            w.source[at - 88] = byte;
            assert_eq!(
                w.encode(&mut [0u8; 624]),
                Err(WeightsError::InvalidHeader {
                    field: "source model"
                })
            );
        }
        let mut small = [0u8; 100];
        assert_eq!(
            sample().encode(&mut small),
            Err(WeightsError::BufferTooSmall { needed: 624 })
        );
    }

    /// The messages, written without `core::fmt`'s formatting, against the same text written
    /// by `format!` with the integer, hexadecimal and `Debug` formats that the messages stand
    /// for.
    #[test]
    fn messages_match_core_fmt() {
        extern crate std;
        use std::format;
        use std::string::ToString;

        let (stored, computed) = (0xDEAD_BEEF_u32, 0x0000_01F0_u32);
        let cases = [
            (
                WeightsError::Truncated {
                    needed: 624,
                    got: 0,
                },
                format!("weight file truncated: {} bytes, needs {}", 0, 624),
            ),
            (
                WeightsError::TrailingBytes {
                    needed: 624,
                    got: 100_000_007,
                },
                format!(
                    "weight file has {} bytes, {} more than its {}-byte shape",
                    100_000_007,
                    100_000_007 - 624,
                    624
                ),
            ),
            (
                WeightsError::BadMagic(*b"\0K\xffN"),
                format!(
                    "not a weight file: magic {:?}, expected \"SKYN\"",
                    *b"\0K\xffN"
                ),
            ),
            (
                WeightsError::UnsupportedVersion(65_535),
                format!(
                    "weight file version {} is not supported (only {VERSION})",
                    65_535
                ),
            ),
            (
                WeightsError::WrongShape {
                    found: [6, 255, 3],
                    expected: [6, 12, 3],
                },
                format!(
                    "weight file is a {}-{}-{} network, expected {}-{}-{}",
                    6, 255, 3, 6, 12, 3
                ),
            ),
            (
                WeightsError::ChecksumMismatch { stored, computed },
                format!(
                    "weight file checksum mismatch: stored {stored:#010x}, data gives {computed:#010x}"
                ),
            ),
            (
                WeightsError::NonFinite {
                    field: "hidden weights",
                },
                format!("weight file field {} is not finite", "hidden weights"),
            ),
            (
                WeightsError::InvalidHeader { field: "flags" },
                format!("weight file header field {} is invalid", "flags"),
            ),
            (
                WeightsError::BufferTooSmall { needed: 10 },
                format!("output buffer too small: {} bytes needed", 10),
            ),
        ];
        for (error, expected) in cases {
            assert_eq!(error.to_string(), expected);
        }
    }
}
