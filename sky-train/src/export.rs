//! Weight files and generated Rust source for sky-core.

use std::fmt::Write as _;
use std::path::Path;

use anyhow::{Context, Result, bail};
use sky_core::neural::{FixedNeuralWeights, NeuralWeights};

use crate::image_io::write_atomically;
use crate::sources::ModelKind;
use crate::train::Trained;

/// What a weight file says about the data its network learned (the header fields besides the
/// weights, see `sky_core::neural::NeuralWeights`).
#[derive(Debug, Clone, PartialEq)]
pub struct TrainedOn {
    /// The source's name (at most 32 bytes are kept), e.g. `hosek` or `captures`.
    pub source: String,
    /// Whether input 0 is √turbidity (false: it is zeroed, seed 000 §III-B).
    pub uses_turbidity: bool,
    /// The turbidities trained on.
    pub turbidity_range: (f64, f64),
    /// The sun zenith angles trained on, radians.
    pub sun_zenith_range: (f64, f64),
}

impl TrainedOn {
    /// A model's skies: its turbidity range, sun zenith 0 to π/2.
    #[must_use]
    pub fn model(model: ModelKind) -> Self {
        Self {
            source: model.to_string(),
            uses_turbidity: model.uses_turbidity(),
            turbidity_range: model.turbidity_range(),
            sun_zenith_range: (0.0, std::f64::consts::FRAC_PI_2),
        }
    }
}

/// The f32 weights sky-core evaluates, from a trained single-hidden-layer network of `H`
/// neurons trained on `model`'s skies.
///
/// # Errors
/// When the network is not 6-H-3.
pub fn to_weights<const H: usize>(
    trained: &Trained,
    model: ModelKind,
    seed: u32,
) -> Result<NeuralWeights<H>> {
    to_weights_of(trained, &TrainedOn::model(model), seed)
}

/// The f32 weights sky-core evaluates, from a trained single-hidden-layer network of `H`
/// neurons, with the header of `trained_on`.
///
/// # Errors
/// When the network is not 6-H-3.
#[allow(clippy::cast_possible_truncation)]
pub fn to_weights_of<const H: usize>(
    trained: &Trained,
    trained_on: &TrainedOn,
    seed: u32,
) -> Result<NeuralWeights<H>> {
    if trained.net.sizes != [6, H, 3] {
        bail!("a {:?} network is not 6-{H}-3", trained.net.sizes);
    }
    let p = &trained.net.params;
    let f = |x: f64| x as f32;
    let hidden = std::array::from_fn(|j| std::array::from_fn(|k| f(p[j * 6 + k])));
    let hidden_bias = std::array::from_fn(|j| f(p[6 * H + j]));
    let base = 7 * H;
    let output = std::array::from_fn(|c| std::array::from_fn(|j| f(p[base + c * H + j])));
    let output_bias = std::array::from_fn(|c| f(p[base + 3 * H + c]));
    let (tmin, tmax) = trained_on.turbidity_range;
    let (zmin, zmax) = trained_on.sun_zenith_range;
    let mut source = [0u8; 32];
    let name = trained_on.source.as_bytes();
    let n = name.len().min(32);
    source[..n].copy_from_slice(&name[..n]);
    let s = &trained.scaling;
    Ok(NeuralWeights {
        hidden,
        hidden_bias,
        output,
        output_bias,
        input_offset: s.input_offset.map(f),
        input_scale: s.input_scale.map(f),
        output_scale: [f(s.output_scale); 3],
        uses_turbidity: trained_on.uses_turbidity,
        turbidity_range: (f(tmin), f(tmax)),
        sun_zenith_range: (f(zmin), f(zmax)),
        source,
        seed,
        nrmse: f(trained.validation_nrmse),
    })
}

/// The trainer's f64 network and scaling of `weights` (the inverse of [`to_weights_of`]), to
/// continue training from a weight file.
///
/// # Errors
/// When the output scale differs between channels (the trainer has one).
pub fn from_weights<const H: usize>(
    weights: &NeuralWeights<H>,
) -> Result<(crate::train::net::Net, crate::train::Scaling)> {
    let [r, g, b] = weights.output_scale;
    if r != g || g != b {
        bail!("the weights scale their channels differently ({r}, {g}, {b})");
    }
    let mut params = Vec::with_capacity(crate::train::net::Net::param_count(&[6, H, 3]));
    params.extend(weights.hidden.iter().flatten().map(|&w| f64::from(w)));
    params.extend(weights.hidden_bias.map(f64::from));
    params.extend(weights.output.iter().flatten().map(|&w| f64::from(w)));
    params.extend(weights.output_bias.map(f64::from));
    Ok((
        crate::train::net::Net {
            sizes: vec![6, H, 3],
            params,
        },
        crate::train::Scaling {
            input_offset: weights.input_offset.map(f64::from),
            input_scale: weights.input_scale.map(f64::from),
            output_scale: f64::from(r),
        },
    ))
}

/// Encodes `weights` to bytes.
///
/// # Errors
/// Only for networks wider than 255 neurons.
pub fn encode<const H: usize>(weights: &NeuralWeights<H>) -> Result<Vec<u8>> {
    let mut bytes = vec![0u8; NeuralWeights::<H>::ENCODED_LEN];
    weights
        .encode(&mut bytes)
        .map_err(|e| anyhow::anyhow!("{e}"))?;
    Ok(bytes)
}

/// Writes `weights` as a weight file, atomically: the bytes are decoded again and written only
/// when they decode (every float finite, a valid header) and make a sky at both ends and the
/// middle of the trained domain, so that a file a reader would refuse never replaces the one
/// at `path`.
///
/// # Errors
/// When the weights do not make a valid file (nothing is written then), or on I/O errors.
pub fn write_weights<const H: usize>(path: &Path, weights: &NeuralWeights<H>) -> Result<()> {
    let not_written = |e: &dyn std::fmt::Display| {
        anyhow::anyhow!(
            "{}: not written: the network does not make a valid weight file ({e})",
            path.display()
        )
    };
    let bytes = encode(weights)?;
    let decoded = NeuralWeights::<H>::decode(&bytes).map_err(|e| not_written(&e))?;
    let (z0, z1) = decoded.sun_zenith_range;
    let (t0, t1) = decoded.turbidity_range;
    for (zenith, turbidity) in [(z0, t0), (0.5 * (z0 + z1), 0.5 * (t0 + t1)), (z1, t1)] {
        let sun = sky_core::Sun::new(zenith, 0.0).map_err(|e| not_written(&e))?;
        sky_core::NeuralSky::new(&decoded, sun, turbidity).map_err(|e| not_written(&e))?;
    }
    write_atomically(path, |f| Ok(std::io::Write::write_all(f, &bytes)?))
}

/// Reads a weight file of a 6-H-3 network.
///
/// # Errors
/// When the file cannot be read or does not decode (the error says why).
pub fn read_weights<const H: usize>(path: &Path) -> Result<NeuralWeights<H>> {
    use std::io::Read;
    let needed = NeuralWeights::<H>::ENCODED_LEN;
    if let Ok(len) = std::fs::metadata(path).map(|m| m.len())
        && len > needed as u64
    {
        bail!(
            "{}: {len} bytes, but a 6-{H}-3 weight file has {needed}",
            path.display()
        );
    }
    // The bounded reader: a regular file, read to at most one byte more than a file of this
    // shape (a growing file is stopped), so that a longer file is never read whole.
    let mut file = crate::csv_input::open(path, needed as u64)
        .with_context(|| format!("cannot read {}", path.display()))?;
    let mut bytes = Vec::new();
    file.read_to_end(&mut bytes)
        .with_context(|| format!("cannot read {}", path.display()))?;
    NeuralWeights::decode(&bytes).map_err(|e| anyhow::anyhow!("{}: {e}", path.display()))
}

/// Rust source declaring `weights` as `pub const {name}: NeuralWeights<H>`, headed by a
/// "generated, do not edit" line naming `command`, and documented by `doc` lines.
#[must_use]
pub fn rust_source<const H: usize>(
    weights: &NeuralWeights<H>,
    name: &str,
    command: &str,
    doc: &[String],
) -> String {
    let floats = |v: &[f32]| {
        v.iter()
            .map(|x| format!("{x:?}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let mut s = source_head("NeuralWeights", command, doc);
    let _ = writeln!(
        s,
        "#[allow(clippy::approx_constant, clippy::excessive_precision)] // trained values, as printed"
    );
    let _ = writeln!(s, "pub const {name}: NeuralWeights<{H}> = NeuralWeights {{");
    let _ = writeln!(s, "    hidden: [");
    for row in &weights.hidden {
        let _ = writeln!(s, "        [{}],", floats(row));
    }
    let _ = writeln!(s, "    ],");
    let _ = writeln!(s, "    hidden_bias: [{}],", floats(&weights.hidden_bias));
    let _ = writeln!(s, "    output: [");
    for row in &weights.output {
        let _ = writeln!(s, "        [{}],", floats(row));
    }
    let _ = writeln!(s, "    ],");
    let _ = writeln!(s, "    output_bias: [{}],", floats(&weights.output_bias));
    let _ = writeln!(s, "    input_offset: [{}],", floats(&weights.input_offset));
    let _ = writeln!(s, "    input_scale: [{}],", floats(&weights.input_scale));
    let _ = writeln!(s, "    output_scale: [{}],", floats(&weights.output_scale));
    let _ = writeln!(s, "    uses_turbidity: {},", weights.uses_turbidity);
    let (t0, t1) = weights.turbidity_range;
    let (z0, z1) = weights.sun_zenith_range;
    let _ = writeln!(s, "    turbidity_range: ({t0:?}, {t1:?}),");
    let _ = writeln!(s, "    sun_zenith_range: ({z0:?}, {z1:?}),");
    let _ = writeln!(s, "    source: *b\"{}\",", escape_source(&weights.source));
    let _ = writeln!(s, "    seed: {},", weights.seed);
    let _ = writeln!(s, "    nrmse: {:?},", weights.nrmse);
    let _ = writeln!(s, "}};");
    s
}

/// The start of a generated constant's file: the "generated, do not edit" line naming
/// `command`, the import of `ty` and the `doc` lines.
fn source_head(ty: &str, command: &str, doc: &[String]) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "// Generated by `{command}`; do not edit.\n");
    let _ = writeln!(s, "use crate::neural::{ty};\n");
    for line in doc {
        let _ = writeln!(s, "/// {line}");
    }
    let _ = writeln!(s, "#[rustfmt::skip]");
    s
}

/// Rust source declaring quantised `weights` as `pub const {name}: FixedNeuralWeights<H>`,
/// headed like [`rust_source`]'s.
#[must_use]
pub fn fixed_rust_source<const H: usize>(
    weights: &FixedNeuralWeights<H>,
    name: &str,
    command: &str,
    doc: &[String],
) -> String {
    let ints = |v: &[i32]| {
        v.iter()
            .map(ToString::to_string)
            .collect::<Vec<_>>()
            .join(", ")
    };
    let mut s = source_head("FixedNeuralWeights", command, doc);
    let _ = writeln!(
        s,
        "#[allow(clippy::unreadable_literal)] // quantised values, as printed"
    );
    let _ = writeln!(
        s,
        "pub const {name}: FixedNeuralWeights<{H}> = FixedNeuralWeights {{"
    );
    let _ = writeln!(s, "    hidden: [");
    for row in &weights.hidden {
        let _ = writeln!(s, "        [{}],", ints(row));
    }
    let _ = writeln!(s, "    ],");
    let _ = writeln!(s, "    hidden_bias: [{}],", ints(&weights.hidden_bias));
    let _ = writeln!(s, "    output: [");
    for row in &weights.output {
        let _ = writeln!(s, "        [{}],", ints(row));
    }
    let _ = writeln!(s, "    ],");
    let _ = writeln!(s, "    output_bias: [{}],", ints(&weights.output_bias));
    let _ = writeln!(s, "    radiance_frac: {},", weights.radiance_frac);
    let [f0, f1, f2] = weights.radiance_factor;
    let _ = writeln!(s, "    radiance_factor: [{f0}, {f1}, {f2}],");
    let _ = writeln!(s, "    factor_shift: {},", weights.factor_shift);
    let _ = writeln!(s, "    uses_turbidity: {},", weights.uses_turbidity);
    let (t0, t1) = weights.turbidity_range;
    let (z0, z1) = weights.sun_zenith_range;
    let _ = writeln!(s, "    turbidity_range: ({t0:?}, {t1:?}),");
    let _ = writeln!(s, "    sun_zenith_range: ({z0:?}, {z1:?}),");
    let _ = writeln!(s, "}};");
    s
}

/// The source name as the contents of a Rust byte string: NUL as `\0`, every other byte that
/// is not printable ASCII, and `"` and `\`, escaped (`escape_ascii`), so that no weight file
/// can end the string.
fn escape_source(source: &[u8; 32]) -> String {
    source
        .iter()
        .map(|&b| {
            if b == 0 {
                "\\0".to_string()
            } else {
                b.escape_ascii().to_string()
            }
        })
        .collect()
}

/// Checks that `name` can be a generated constant's name: an upper-case Rust identifier
/// (`A`-`Z`, then `A`-`Z`, `0`-`9` or `_`, at most 64 characters), so that it is written into
/// the source as it is and never changes the code around it.
///
/// # Errors
/// Otherwise, naming `--name` and what it may hold.
pub fn check_const_name(name: &str) -> Result<()> {
    let mut chars = name.chars();
    let valid = chars.next().is_some_and(|c| c.is_ascii_uppercase())
        && chars.all(|c| c.is_ascii_uppercase() || c.is_ascii_digit() || c == '_')
        && name.len() <= 64;
    if !valid {
        return Err(crate::args::ParamError(format!(
            "--name {:?}: expected an upper-case Rust identifier (A-Z, then A-Z, 0-9 or _, at most 64 characters), e.g. PREETHAM",
            name
        ))
        .into());
    }
    Ok(())
}

/// The generated file of a shipped network: [`rust_source`] with the provenance and the
/// command that regenerates it.
///
/// # Errors
/// When `name` is not a constant's name ([`check_const_name`]).
pub fn pretrained_source<const H: usize>(
    weights: &NeuralWeights<H>,
    name: &str,
    weights_path: &Path,
) -> Result<String> {
    check_const_name(name)?;
    let file = file_name(weights_path);
    Ok(rust_source(
        weights,
        name,
        &format!(
            "sky-train export --weights sky-core/weights/{file} --name {name} --out <this file>"
        ),
        &provenance(weights, &file),
    ))
}

/// The generated file of a shipped network quantised for [`sky_core::neural::FixedNeuralSky`]:
/// [`fixed_rust_source`] with the provenance and the command that regenerates it.
///
/// # Errors
/// When `name` is not a constant's name ([`check_const_name`]) or the weights do not fit the
/// fixed-point format (the error names the value).
pub fn pretrained_fixed_source<const H: usize>(
    weights: &NeuralWeights<H>,
    name: &str,
    weights_path: &Path,
) -> Result<String> {
    check_const_name(name)?;
    let fixed = FixedNeuralWeights::quantise(weights).map_err(|e| {
        crate::args::ParamError(format!(
            "--weights {}: cannot quantise to Q7.24: {}",
            weights_path.display(),
            crate::args::describe(e, str::to_owned, " ")
        ))
    })?;
    let file = file_name(weights_path);
    let mut doc = provenance(weights, &file);
    doc.push(format!(
        "Quantised to Q7.24 by `FixedNeuralWeights::quantise`; radiance in units of 2^-{}.",
        fixed.radiance_frac
    ));
    Ok(fixed_rust_source(
        &fixed,
        name,
        &format!(
            "sky-train export --format fixed --weights sky-core/weights/{file} --name {name} --out <this file>"
        ),
        &doc,
    ))
}

/// The file name of `path` for a generated comment: anything but printable ASCII escaped (a
/// newline in a file name would end the comment and start code).
fn file_name(path: &Path) -> String {
    path.file_name().map_or_else(String::new, |f| {
        f.to_string_lossy()
            .chars()
            .flat_map(char::escape_default)
            .collect()
    })
}

/// The doc lines of a shipped network's constant: what it was trained on, and from which file.
fn provenance<const H: usize>(weights: &NeuralWeights<H>, file: &str) -> Vec<String> {
    let (t0, t1) = weights.turbidity_range;
    let (z0, z1) = weights.sun_zenith_range;
    vec![
        format!(
            "A 6-{H}-3 neural sky trained on the {} sky, turbidity {t0} to {t1}, sun zenith",
            weights.source_name()
        ),
        format!(
            "{:.0} to {:.0} degrees (seed {}; validation NRMSE {:.5}), from `sky-core/weights/{file}`.",
            z0.to_degrees(),
            z1.to_degrees(),
            weights.seed,
            weights.nrmse
        ),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;
    use sky_core::neural::pretrained;

    /// A shipped weight set goes to the trainer's network and back unchanged.
    #[test]
    fn weights_round_trip_through_the_trainer() {
        for (weights, model) in [
            (pretrained::PREETHAM, ModelKind::Preetham),
            (pretrained::HOSEK, ModelKind::Hosek),
        ] {
            let (net, scaling) = from_weights(&weights).expect("one output scale");
            let trained = Trained {
                net,
                scaling,
                validation_nrmse: f64::from(weights.nrmse),
                iterations: 0,
                seconds: 0.0,
                examples: 0,
                milestone: None,
            };
            let back = to_weights::<12>(&trained, model, weights.seed).expect("6-12-3");
            assert_eq!(back.hidden, weights.hidden);
            assert_eq!(back.hidden_bias, weights.hidden_bias);
            assert_eq!(back.output, weights.output);
            assert_eq!(back.output_bias, weights.output_bias);
            assert_eq!(back.input_offset, weights.input_offset);
            assert_eq!(back.input_scale, weights.input_scale);
            assert_eq!(back.output_scale, weights.output_scale);
        }
    }
}
