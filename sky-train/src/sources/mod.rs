//! Sky models the host can sample, behind one trait.
//!
//! Each source evaluates whole slices of directions at once (the fast path of every model), in
//! sky-core's conventions: +z up, luminance in cd/m², linear sRGB on the same scale.

mod preetham;
mod sh;

use std::fmt;

use sky_core::Vec3;
use sky_core::color::{self, Xyy};

pub use preetham::Preetham;
pub use sh::Sh;

/// A sky model evaluated over many view directions.
pub trait SkySource: Send + Sync {
    /// A one-line description: the model and its parameters.
    fn describe(&self) -> String;

    /// Linear sRGB for each direction of `dirs`, into the same index of `out`.
    fn rgb_batch(&self, dirs: &[Vec3], out: &mut [Vec3]);

    /// Luminance (cd/m²) and chromaticity for each direction. By default derived from
    /// [`rgb_batch`](Self::rgb_batch); models whose native output is xyY override it.
    fn xyy_batch(&self, dirs: &[Vec3], out: &mut [Xyy]) {
        let mut rgb = vec![Vec3::ZERO; dirs.len().min(out.len())];
        self.rgb_batch(dirs, &mut rgb);
        for (o, c) in out.iter_mut().zip(rgb) {
            *o = color::xyz_to_xyy(color::linear_srgb_to_xyz(c));
        }
    }
}

/// The models the command line can name with `--model`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum ModelKind {
    /// The Perez/Preetham analytic sky (sky-core).
    Preetham,
    /// The spherical-harmonics lighting of the Preetham sky, reconstructed from sky-core's
    /// polynomial tables (`--bands`, `--no-ringing-filter`).
    Sh,
}

impl ModelKind {
    /// The sun zenith angles the model accepts, in degrees.
    #[must_use]
    pub fn sun_zenith_range_deg(self) -> (f64, f64) {
        match self {
            Self::Preetham | Self::Sh => (0.0, 90.0),
        }
    }
}

impl fmt::Display for ModelKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Self::Preetham => "preetham",
            Self::Sh => "sh",
        })
    }
}

/// The parameters that select one sky: the sun and the atmosphere.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SkyParams {
    /// Sun zenith angle in degrees.
    pub sun_zenith_deg: f64,
    /// Sun azimuth in degrees (sky-core's convention: from +x towards +y).
    pub sun_azimuth_deg: f64,
    /// Atmospheric turbidity.
    pub turbidity: f64,
    /// Spherical-harmonics bands (`sh` only): 1 to 7.
    pub bands: usize,
    /// Whether the `sh` model applies the ringing filter (seed 001, eq. 5).
    pub ringing_filter: bool,
}

impl Default for SkyParams {
    /// Sun at the zenith, azimuth 0, turbidity 3, 7 SH bands with the ringing filter.
    fn default() -> Self {
        Self {
            sun_zenith_deg: 0.0,
            sun_azimuth_deg: 0.0,
            turbidity: 3.0,
            bands: 7,
            ringing_filter: true,
        }
    }
}

/// A parameter the user gave that the model rejects, phrased in the command line's terms.
#[derive(Debug, Clone, PartialEq)]
pub struct ParamError(pub String);

impl fmt::Display for ParamError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for ParamError {}

/// Builds the sky `kind` for `params`.
///
/// # Errors
/// A [`ParamError`] naming the command-line argument, its value and the valid range.
pub fn build(kind: ModelKind, params: &SkyParams) -> Result<Box<dyn SkySource>, ParamError> {
    match kind {
        ModelKind::Preetham => Ok(Box::new(Preetham::new(params)?)),
        ModelKind::Sh => Ok(Box::new(Sh::new(params)?)),
    }
}

/// Rewrites a sky-core error in the command line's terms (argument names, degrees).
pub(crate) fn param_error(kind: ModelKind, e: sky_core::SkyError) -> ParamError {
    use sky_core::SkyError as E;
    let (lo, hi) = kind.sun_zenith_range_deg();
    let sun_zenith = |value: f32| {
        format!(
            "--sun-zenith {} deg is outside the valid range [{lo}, {hi}] deg for --model {kind}",
            value.to_degrees()
        )
    };
    let msg = match e {
        E::OutOfRange {
            parameter: "sun zenith [rad]",
            value,
            ..
        }
        | E::SunBelowHorizon { zenith: value } => sun_zenith(value),
        E::NotFinite { parameter } => format!("{} must be a finite number", flag(parameter)),
        E::OutOfRange {
            parameter,
            value,
            min,
            max,
        } => {
            let (value, min, max, unit) = if parameter.ends_with("[rad]") {
                (
                    value.to_degrees(),
                    min.to_degrees(),
                    max.to_degrees(),
                    " deg",
                )
            } else {
                (value, min, max, "")
            };
            format!(
                "{} {value}{unit} is outside the valid range [{min}, {max}]{unit} for --model {kind}",
                flag(parameter)
            )
        }
        other => other.to_string(),
    };
    ParamError(msg)
}

fn flag(parameter: &str) -> &str {
    match parameter {
        "turbidity" => "--turbidity",
        "sun zenith [rad]" => "--sun-zenith",
        "sun azimuth [rad]" => "--sun-azimuth",
        "SH bands" => "--bands",
        other => other,
    }
}

/// The sun of `params` for `kind`, with sky-core's error rewritten in the command line's terms.
pub(crate) fn sun(kind: ModelKind, params: &SkyParams) -> Result<sky_core::Sun, ParamError> {
    sky_core::Sun::new(
        radians(params.sun_zenith_deg),
        radians(params.sun_azimuth_deg),
    )
    .map_err(|e| param_error(kind, e))
}

/// Converts degrees to radians in f64 and rounds once to f32.
#[allow(clippy::cast_possible_truncation)] // the point of the function
#[must_use]
pub fn radians(deg: f64) -> f32 {
    deg.to_radians() as f32
}
