//! One step of a daylight-following luminaire's schedule: from a UTC time and a site to the sun's
//! position, the clear sky's horizontal illuminance and colour temperature, and the drive levels
//! of an RGBW luminaire that reproduce that colour.
//!
//! The one definition shared by `sky-train schedule` on the host and the controller firmware
//! example (`firmware/src/bin/controller.rs`, checked against this same function run on the
//! host), so that the two cannot drift apart.

use glam::Vec3;

use crate::cct::{self, Cct};
use crate::color::{self, Xyy};
use crate::error::SkyError;
use crate::led::{Channel, Drive, Luminaire};
use crate::photometry::Photometry;
use crate::solar::{Site, SunPosition, UtcTime};
use crate::twilight::Daylight;

/// The example RGBW luminaire: typical LED chromaticities (CIE 1931 x, y) and outputs in lumens
/// at full drive: red 625 nm (0.700, 0.295; 300 lm), green 525 nm (0.170, 0.700; 600 lm), royal
/// blue 450 nm (0.135, 0.060; 100 lm) and a 3000 K white (0.4369, 0.4041; 900 lm).
///
/// # Errors
/// None in practice (the channels are valid); the [`Luminaire::rgbw`] checks are kept.
pub fn example_luminaire() -> Result<Luminaire<4>, SkyError> {
    let ch = |x, y, full_output| Channel { x, y, full_output };
    Luminaire::rgbw(
        ch(0.700, 0.295, 300.0),
        ch(0.170, 0.700, 600.0),
        ch(0.135, 0.060, 100.0),
        ch(0.4369, 0.4041, 900.0),
    )
}

/// What the controller computes at one time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Step {
    /// The sun (SPA: geometric and apparent zenith, compass azimuth).
    pub sun: SunPosition,
    /// The clear sky's illuminance on a horizontal plane, CIE XYZ with Y in lux
    /// ([`Daylight`], defined from −18° elevation up; [`Photometry::horizontal_illuminance`]).
    pub illuminance: Vec3,
    /// CCT and Duv of that illuminance's chromaticity.
    pub cct: Cct,
    /// The luminaire's levels reproducing the sky's chromaticity, at a luminous output
    /// proportional to the illuminance: full output (all channels' lumens) at `full_scale_lux`.
    pub drive: Drive<4>,
}

/// The controller's step at `time` for `site`: the clear sky of Preetham `turbidity` (2 to 6),
/// blended into twilight below the horizon ([`Daylight`]), its horizontal illuminance and CCT,
/// and `lamp`'s drive levels (levels clip at full output when the sky is brighter than
/// `full_scale_lux`, keeping the chromaticity).
///
/// ```
/// use sky_core::controller::{example_luminaire, step};
/// use sky_core::solar::{Site, UtcTime};
///
/// let vienna = Site::new(48.21, 16.37, 190.0)?;
/// let lamp = example_luminaire()?;
/// let noon = step(&UtcTime::new(2026, 3, 20, 11, 0, 0.0)?, &vienna, 3.0, 10_000.0, &lamp)?;
/// assert!(noon.illuminance.y > 10_000.0);            // diffuse sky light, in lux
/// assert!(noon.cct.kelvin > 5_000.0);                // a blue sky
/// let pwm = noon.drive.quantise(12)?;                // 12-bit duty cycles, R, G, B, W
/// assert!(pwm.iter().any(|&d| d == 4095));           // brighter than full scale: clipped
/// # Ok::<(), sky_core::SkyError>(())
/// ```
///
/// # Errors
/// [`SkyError::OutOfRange`] for a turbidity outside 2-6, a `full_scale_lux` that is not
/// positive and finite, or a sky colour without a CCT (not seen for the clear sky).
pub fn step(
    time: &UtcTime,
    site: &Site,
    turbidity: f32,
    full_scale_lux: f32,
    lamp: &Luminaire<4>,
) -> Result<Step, SkyError> {
    if !(full_scale_lux > 0.0 && full_scale_lux.is_finite()) {
        return Err(SkyError::OutOfRange {
            parameter: "full-scale illuminance [lx]",
            value: full_scale_lux,
            min: f32::MIN_POSITIVE,
            max: f32::MAX,
        });
    }
    let sun = SunPosition::new(time, site)?;
    let illuminance = Daylight::new(sun.sun(), turbidity)?.horizontal_illuminance();
    let colour = color::xyz_to_xyy(illuminance);
    let cct = cct::cct_duv(colour.x, colour.y)?;
    let full_output: f32 = lamp.channels().iter().map(|c| c.full_output).sum();
    let drive = lamp.drive(Xyy {
        luminance: full_output * illuminance.y / full_scale_lux,
        ..colour
    });
    Ok(Step {
        sun,
        illuminance,
        cct,
        drive,
    })
}
