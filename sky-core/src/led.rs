//! LED drive levels: the channel levels of a luminaire that reproduce a target colour.
//!
//! A channel at level ℓ ∈ [0, 1] emits ℓ times its full output, whose chromaticity does not
//! change with the level (the usual model of PWM dimming). Additive mixing is linear in CIE
//! XYZ, so the levels reproducing a target XYZ solve a linear system:
//!
//! * **RGB**: the 3 × 3 system of the primaries, exact inside their gamut.
//! * **RGBW**: the white channel takes as much of the target as the RGB remainder allows
//!   (the largest w ≤ 1 leaving non-negative RGB levels), which maximises efficacy.
//! * **Warm + cool white**: only the chromaticities on the line between the two are reachable;
//!   the target goes to the nearest point of that segment (in CIE 1931 xy), luminance kept.
//!
//! **Gamut clipping keeps the hue**: a target outside the RGB gamut is mixed, at its own
//! luminance, with the luminaire's white (all channels at full) until it is inside. Additive
//! mixtures lie on straight lines of the xy diagram, so the clipped chromaticity lies on the
//! segment from the luminaire's white to the target: its hue angle about that white is the
//! target's, only its saturation drops. A target brighter than the luminaire can give is then
//! dimmed, all levels by one factor, which keeps the chromaticity.
//!
//! Luminance is in whatever unit the channels' full outputs are given in (lumens, or cd/m² of
//! a panel), and targets must use the same.

use glam::{Mat3, Vec3};

use crate::color::{self, Xyy};
use crate::error::SkyError;
use crate::math;

/// One channel: the chromaticity of its light and its luminous output at full drive.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Channel {
    /// CIE 1931 chromaticity x.
    pub x: f32,
    /// CIE 1931 chromaticity y.
    pub y: f32,
    /// Luminous output at level 1 (the unit of the targets: lm, or cd/m²).
    pub full_output: f32,
}

impl Channel {
    /// XYZ at full drive, after checking the channel.
    fn xyz(&self, parameter: &'static str) -> Result<Vec3, SkyError> {
        let ok = self.x >= 0.0
            && self.y > 0.0
            && self.x + self.y <= 1.0
            && self.full_output > 0.0
            && self.full_output.is_finite();
        if !ok {
            return Err(SkyError::OutOfRange {
                parameter,
                value: if self.full_output > 0.0 {
                    self.y
                } else {
                    self.full_output
                },
                min: 0.0,
                max: 1.0,
            });
        }
        Ok(color::xyy_to_xyz(Xyy {
            x: self.x,
            y: self.y,
            luminance: self.full_output,
        }))
    }
}

/// The levels for one target.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct Drive<const N: usize> {
    /// Each channel's level in [0, 1], in the order the luminaire was built with.
    pub levels: [f32; N],
    /// The colour these levels produce (the target, unless clipped).
    pub output: Xyy,
    /// Whether the chromaticity was out of gamut and moved towards the luminaire's white.
    pub chromaticity_clipped: bool,
    /// Whether the target was brighter than the luminaire can give at that chromaticity.
    pub luminance_clipped: bool,
}

impl<const N: usize> Drive<N> {
    /// The levels quantised to `bits` (1 to 16; 8, 12 and 16 are usual for PWM), rounded to
    /// the nearest step: level · (2^bits − 1).
    ///
    /// # Errors
    /// [`SkyError::OutOfRange`] for `bits` outside 1-16.
    pub fn quantise(&self, bits: u8) -> Result<[u16; N], SkyError> {
        if !(1..=16).contains(&bits) {
            return Err(SkyError::OutOfRange {
                parameter: "PWM resolution [bits]",
                value: f32::from(bits),
                min: 1.0,
                max: 16.0,
            });
        }
        let full = f32::from(u16::MAX >> (16 - bits));
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)] // in [0, 65535]
        Ok(self
            .levels
            .map(|l| math::floor(l.clamp(0.0, 1.0) * full + 0.5) as u16))
    }
}

/// A luminaire of `N` channels: RGB ([`Luminaire::rgb`]), RGBW ([`Luminaire::rgbw`]) or warm +
/// cool white ([`Luminaire::tunable_white`]).
///
/// ```
/// use sky_core::color::Xyy;
/// use sky_core::led::{Channel, Luminaire};
///
/// let ch = |x, y, full_output| Channel { x, y, full_output };
/// let lamp = Luminaire::rgbw(
///     ch(0.700, 0.295, 300.0), // red, 300 lm
///     ch(0.170, 0.700, 600.0), // green
///     ch(0.135, 0.060, 100.0), // blue
///     ch(0.4369, 0.4041, 900.0), // white, 3000 K
/// )?;
/// let drive = lamp.drive(Xyy { x: 0.3127, y: 0.3290, luminance: 500.0 }); // D65, 500 lm
/// assert!((drive.output.x - 0.3127).abs() < 1e-5 && (drive.output.luminance - 500.0).abs() < 1e-2);
/// let pwm = drive.quantise(12)?;                    // 12-bit duty cycles
/// # Ok::<(), sky_core::SkyError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Luminaire<const N: usize> {
    channels: [Channel; N],
    /// XYZ of each channel at full drive.
    xyz: [Vec3; N],
    /// XYZ → levels of the first three channels (RGB and RGBW).
    inverse: Mat3,
}

/// Levels (in the primaries' coordinates) from mixing the target `t` with the white `w` (both
/// at the target's luminance) just enough that none is negative: the hue-keeping clip.
fn clip_towards_white(t: Vec3, w: Vec3) -> (Vec3, bool) {
    if t.min_element() >= 0.0 {
        return (t, false);
    }
    let mut keep = 1.0f32;
    for i in 0..3 {
        if t[i] < 0.0 {
            keep = keep.min(w[i] / (w[i] - t[i]));
        }
    }
    ((keep * t + (1.0 - keep) * w).max(Vec3::ZERO), true)
}

/// The target as XYZ, or `None` when it is black or not a colour.
fn target_xyz(target: Xyy) -> Option<Vec3> {
    let ok = target.luminance > 0.0
        && target.luminance.is_finite()
        && target.x >= 0.0
        && target.y > 0.0
        && target.x + target.y <= 1.0;
    ok.then(|| color::xyy_to_xyz(target))
}

impl<const N: usize> Luminaire<N> {
    /// The channels, in order.
    #[must_use]
    pub fn channels(&self) -> &[Channel; N] {
        &self.channels
    }

    /// The colour produced by `levels` (each clamped to [0, 1]).
    #[must_use]
    pub fn output(&self, levels: &[f32; N]) -> Xyy {
        let xyz = levels
            .iter()
            .zip(&self.xyz)
            .fold(Vec3::ZERO, |acc, (l, c)| acc + l.clamp(0.0, 1.0) * *c);
        color::xyz_to_xyy(xyz)
    }

    fn build(channels: [Channel; N], names: [&'static str; N]) -> Result<Self, SkyError> {
        let mut xyz = [Vec3::ZERO; N];
        for i in 0..N {
            xyz[i] = channels[i].xyz(names[i])?;
        }
        let inverse = if N >= 3 {
            let m = Mat3::from_cols(xyz[0], xyz[1], xyz[2]);
            // Primaries on one line of the xy diagram span no gamut.
            let det = m.determinant() / (xyz[0].y * xyz[1].y * xyz[2].y);
            if det.is_nan() || det.abs() <= 1e-4 {
                return Err(SkyError::OutOfRange {
                    parameter: "primaries' gamut (determinant per unit luminance)",
                    value: det,
                    min: 1e-4,
                    max: f32::INFINITY,
                });
            }
            m.inverse()
        } else {
            Mat3::ZERO
        };
        Ok(Self {
            channels,
            xyz,
            inverse,
        })
    }

    /// Scales `levels` so that none exceeds 1, and builds the result.
    fn finish(&self, mut levels: [f32; N], chromaticity_clipped: bool) -> Drive<N> {
        let max = levels.iter().copied().fold(0.0f32, f32::max);
        let luminance_clipped = max > 1.0;
        if luminance_clipped {
            levels = levels.map(|l| l / max);
        }
        levels = levels.map(|l| l.clamp(0.0, 1.0));
        Drive {
            output: self.output(&levels),
            levels,
            chromaticity_clipped,
            luminance_clipped,
        }
    }

    fn black(&self) -> Drive<N> {
        self.finish([0.0; N], false)
    }
}

impl Luminaire<3> {
    /// An RGB luminaire.
    ///
    /// # Errors
    /// [`SkyError::OutOfRange`] for a channel whose chromaticity lies outside x ≥ 0, y > 0,
    /// x + y ≤ 1 or whose full output is not positive and finite, or for primaries on one line.
    pub fn rgb(red: Channel, green: Channel, blue: Channel) -> Result<Self, SkyError> {
        Self::build(
            [red, green, blue],
            ["red channel", "green channel", "blue channel"],
        )
    }

    /// The levels reproducing `target` (module docs). A black or invalid target (non-finite,
    /// luminance ≤ 0, chromaticity outside the diagram's triangle) gives all levels 0.
    #[must_use]
    pub fn drive(&self, target: Xyy) -> Drive<3> {
        let Some(t) = target_xyz(target) else {
            return self.black();
        };
        let a = self.inverse * t;
        // The white (all channels at full) at the target's luminance, in levels: (s, s, s).
        let s = t.y / (self.xyz[0].y + self.xyz[1].y + self.xyz[2].y);
        let (a, clipped) = clip_towards_white(a, Vec3::splat(s));
        self.finish(a.to_array(), clipped)
    }
}

impl Luminaire<4> {
    /// An RGBW luminaire; the white's chromaticity must lie inside the RGB gamut.
    ///
    /// # Errors
    /// As [`Luminaire::rgb`], and [`SkyError::OutOfRange`] for a white outside the RGB gamut.
    pub fn rgbw(
        red: Channel,
        green: Channel,
        blue: Channel,
        white: Channel,
    ) -> Result<Self, SkyError> {
        let lamp = Self::build(
            [red, green, blue, white],
            [
                "red channel",
                "green channel",
                "blue channel",
                "white channel",
            ],
        )?;
        let b = lamp.inverse * lamp.xyz[3];
        if b.min_element() < 0.0 {
            return Err(SkyError::OutOfRange {
                parameter: "white channel (RGB levels of its colour)",
                value: b.min_element(),
                min: 0.0,
                max: f32::INFINITY,
            });
        }
        Ok(lamp)
    }

    /// The levels reproducing `target` (module docs), red, green, blue, white. A black or
    /// invalid target gives all levels 0.
    #[must_use]
    pub fn drive(&self, target: Xyy) -> Drive<4> {
        let Some(t) = target_xyz(target) else {
            return self.black();
        };
        // The white channel in RGB levels, and the luminaire's white (all four at full).
        let b = self.inverse * self.xyz[3];
        let full = Vec3::ONE + b;
        let y_full = self.xyz.iter().map(|c| c.y).sum::<f32>();
        let (a, clipped) = clip_towards_white(self.inverse * t, full * (t.y / y_full));
        // The largest white level w ≤ 1 leaving a − w b ≥ 0.
        let mut w = 1.0f32;
        for i in 0..3 {
            if b[i] > 0.0 {
                w = w.min(a[i] / b[i]);
            }
        }
        let w = w.max(0.0);
        let rgb = (a - w * b).max(Vec3::ZERO);
        self.finish([rgb.x, rgb.y, rgb.z, w], clipped)
    }
}

impl Luminaire<2> {
    /// A tunable-white luminaire of a warm and a cool white channel.
    ///
    /// # Errors
    /// [`SkyError::OutOfRange`] for a channel as in [`Luminaire::rgb`], or two channels of the
    /// same chromaticity.
    pub fn tunable_white(warm: Channel, cool: Channel) -> Result<Self, SkyError> {
        let lamp = Self::build([warm, cool], ["warm channel", "cool channel"])?;
        let gap = Vec3::new(warm.x - cool.x, warm.y - cool.y, 0.0).length();
        if gap.is_nan() || gap <= 1e-3 {
            return Err(SkyError::OutOfRange {
                parameter: "distance between the warm and cool chromaticities",
                value: gap,
                min: 1e-3,
                max: 1.0,
            });
        }
        Ok(lamp)
    }

    /// The levels (warm, cool) reproducing the point of the warm-cool segment nearest to
    /// `target`'s chromaticity, at the target's luminance (module docs). A black or invalid
    /// target gives both levels 0.
    #[must_use]
    pub fn drive(&self, target: Xyy) -> Drive<2> {
        if target_xyz(target).is_none() {
            return self.black();
        }
        let [w, c] = self.channels;
        let (dx, dy) = (c.x - w.x, c.y - w.y);
        let along = ((target.x - w.x) * dx + (target.y - w.y) * dy) / (dx * dx + dy * dy);
        let s = along.clamp(0.0, 1.0);
        let (px, py) = (w.x + s * dx, w.y + s * dy);
        let clipped = Vec3::new(px - target.x, py - target.y, 0.0).length() > 1e-5;
        // A mixture's chromaticity is the (X+Y+Z)-weighted mean of the channels': with
        // q = level · (X+Y+Z) per channel, s = q_c / (q_w + q_c), and Y = Σ q · y.
        let k = target.luminance / ((1.0 - s) * w.y + s * c.y);
        let sum = |v: Vec3| v.x + v.y + v.z;
        let levels = [(1.0 - s) * k / sum(self.xyz[0]), s * k / sum(self.xyz[1])];
        self.finish(levels, clipped)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ch(x: f32, y: f32, full_output: f32) -> Channel {
        Channel { x, y, full_output }
    }

    #[test]
    fn bad_luminaires_are_errors() {
        let r = ch(0.7, 0.3, 100.0);
        let g = ch(0.17, 0.7, 100.0);
        assert!(Luminaire::rgb(r, g, ch(0.135, 0.06, 0.0)).is_err());
        assert!(Luminaire::rgb(r, g, ch(0.435, 0.5, 10.0)).is_err()); // on the R-G line
        assert!(Luminaire::rgbw(r, g, ch(0.135, 0.06, 10.0), ch(0.05, 0.9, 10.0)).is_err());
        assert!(Luminaire::tunable_white(r, r).is_err());
    }

    #[test]
    fn quantisation_steps() {
        let d = Drive::<2> {
            levels: [1.0, 0.5],
            output: Xyy::default(),
            chromaticity_clipped: false,
            luminance_clipped: false,
        };
        assert_eq!(d.quantise(8).expect("valid"), [255, 128]);
        assert_eq!(d.quantise(12).expect("valid"), [4095, 2048]);
        assert_eq!(d.quantise(16).expect("valid"), [65535, 32768]);
        assert!(d.quantise(0).is_err() && d.quantise(17).is_err());
    }
}
