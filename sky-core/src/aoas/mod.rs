//! Aesthetically-Oriented Atmospheric Scattering (AOAS, seed 004): a physically based
//! single-scattering sky rendered inside one skydome, plus aesthetic principles that change the
//! sky's hue and pattern while its gradient stays physical.
//!
//! # The scattering (seed 004 §3.2)
//!
//! Rayleigh and Mie single scattering after Nishita et al. 1993, with the real-time
//! simplification of O'Neil, "Accurate Atmospheric Scattering" (GPU Gems 2, ch. 16, 2005): a
//! planet of radius 10 inside an atmosphere of radius 10.25 (2.5 % thicker), density falling
//! exponentially with a scale depth of 25 % of the atmosphere's thickness, the optical depth from
//! a point to space approximated by O'Neil's fitted "scale" function
//! `scale(cos θ) = 0.25 · exp(−0.00287 + x(0.459 + x(3.83 + x(−6.80 + 5.25 x))))`, x = 1 − cos θ,
//! and the in-scattering integral (eq. 4) by the midpoint rule over `samples` points of the view
//! ray (eq. 3).
//!
//! AOAS removes O'Neil's planet skydome: the viewer stands in the atmosphere skydome at `Pvs`,
//! which eq. 2 moves to Earth space, `Pv = Pvs + r (Pvs − O)/|Pvs − O|`, with r the ratio of the
//! planet's radius to the atmosphere's thickness (40) and lengths in atmosphere thicknesses; the
//! view direction is the same in both spaces (eq. 1). The ray runs from `Pv` to the outer
//! sphere, so the colour depends on the view direction only, not on the size or shape of the
//! skydome mesh (Fig. 7).
//!
//! # The style (seed 004 §3.3)
//!
//! [`Style`] holds the aesthetic principles: [`Ambiguity`] (eqs. 5-6), [`CloudNoise`] (eqs. 7-8),
//! [`CloudShapes`], the sky hue (the Rayleigh constants replaced by any RGB vector) and the
//! [`DayCycle`]. [`Preset`] names the styles of the paper's figures.
//!
//! ```
//! use sky_core::aoas::{AoasSky, Preset, Scattering, Style};
//! use sky_core::geom;
//!
//! let sky = AoasSky::new(&Scattering::default(), &Style::preset(Preset::Sunset))?;
//! // Towards the setting sun, due west (azimuth π), 2° above the horizon.
//! let rgb = sky.rgb(geom::direction(88f32.to_radians(), core::f32::consts::PI));
//! assert!(rgb.x > 2.0 * rgb.z); // orange
//! # Ok::<(), sky_core::SkyError>(())
//! ```

mod clouds;
mod noise;
mod style;

use core::f32::consts::{LOG2_E, PI};

use glam::Vec3;

pub use clouds::{CloudShapes, MAX_CLOUD_ANGLE, MIN_CLOUD_FADE};
pub use style::{
    Ambiguity, CloudNoise, DayCycle, MAX_AMBIGUITY, MAX_NOISE_SIZE, MAX_SKY_HUE, MIN_NOISE_SIZE,
    MIN_NOON_ELEVATION, Preset, SUNRISE_HOURS, SUNSET_HOURS, Style,
};

use crate::error::{SkyError, check_range};
use crate::geom::Sun;
use crate::math;

/// The planet's radius in atmosphere thicknesses: O'Neil's inner radius 10 over his atmosphere
/// thickness 10.25 − 10 (the r of seed 004, eq. 2). The optical-depth fit holds for this ratio
/// only, so it is fixed.
pub const PLANET_RADIUS: f32 = 40.0;
/// The scale depth in atmosphere thicknesses: the density falls by e every quarter of the
/// thickness (O'Neil's fScaleDepth). Fixed for the same reason.
pub const SCALE_DEPTH: f32 = 0.25;
/// The most ray-marching samples accepted.
pub const MAX_SAMPLES: u32 = 64;
/// The highest viewer accepted, in atmosphere thicknesses above the ground.
pub const MAX_VIEWER_ALTITUDE: f32 = 0.9;
/// The largest Rayleigh or Mie constant accepted.
pub const MAX_SCATTERING_CONSTANT: f32 = 0.1;
/// The largest sun intensity accepted.
pub const MAX_SUN_INTENSITY: f32 = 1000.0;
/// The largest |g| accepted for the Mie phase function.
pub const MAX_MIE_G: f32 = 0.999;
/// The shortest wavelength accepted, in µm.
pub const MIN_WAVELENGTH: f32 = 0.38;
/// The longest wavelength accepted, in µm.
pub const MAX_WAVELENGTH: f32 = 0.78;

/// Views down to this far below the viewer's horizon (in cos θ) still count as on it:
/// [`geom::HORIZON_TOLERANCE`](crate::geom::HORIZON_TOLERANCE), the crate's one below-horizon
/// rule (crate docs, "Conventions"), applied to the viewer's own horizon (tilted when the
/// viewer stands away from the origin, eq. 2).
pub const HORIZON_TOLERANCE: f32 = crate::geom::HORIZON_TOLERANCE;

/// Directions evaluated together by the batch path: the lanes of its loops.
const CHUNK: usize = 32;

/// O'Neil's single-scattering parameters ("Accurate Atmospheric Scattering", GPU Gems 2 ch. 16),
/// with his values as the [`Default`].
///
/// The three colour channels are the wavelengths `wavelengths`; Rayleigh scattering goes as
/// 1/λ⁴ (λ in µm), Mie scattering is the same in every channel.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scattering {
    /// Kr, the Rayleigh scattering constant, in [0, [`MAX_SCATTERING_CONSTANT`]]. O'Neil: 0.0025.
    pub kr: f32,
    /// Km, the Mie scattering constant, in [0, [`MAX_SCATTERING_CONSTANT`]]. O'Neil: 0.0010.
    pub km: f32,
    /// ESun, the sun's intensity, in [0, [`MAX_SUN_INTENSITY`]]: the output scales with it.
    /// O'Neil: 20.
    pub sun_intensity: f32,
    /// g, the asymmetry of the Mie phase function, in [−[`MAX_MIE_G`], [`MAX_MIE_G`]]: positive
    /// scatters forwards (a bright halo around the sun). Here the phase function's angle is the
    /// angle between the view and the sun, cos θ = view · sun, so the forward peak is at the sun
    /// for g > 0; O'Neil's shader measures it against the reversed view, so his g = −0.990 is
    /// this g = 0.990.
    pub mie_g: f32,
    /// The wavelengths of the red, green and blue channels in µm, each in
    /// [[`MIN_WAVELENGTH`], [`MAX_WAVELENGTH`]]. O'Neil: 0.650, 0.570, 0.475.
    pub wavelengths: [f32; 3],
    /// Points of the view ray at which the in-scattering is sampled, in [1, [`MAX_SAMPLES`]].
    /// O'Neil's shaders used 2 to 5; the default here is 8, the fewest whose largest error
    /// against the exact integral is within 10 % of the floor set by the optical-depth fit
    /// (2.3 % against 2.2 % in luminance, see [`AoasSky`]); 5 samples give 3.4 %.
    pub samples: u32,
    /// The viewer's position `Pvs` in skydome space, in atmosphere thicknesses, with the skydome
    /// centred at the origin: |Pvs| is the viewer's altitude, at most [`MAX_VIEWER_ALTITUDE`],
    /// and its direction the viewer's apex (eq. 2), +z for the origin. A viewer off the +z axis
    /// sees the horizon tilted towards it, as eq. 2 prescribes. Default: the origin, on the
    /// ground.
    pub viewer: Vec3,
}

impl Default for Scattering {
    /// O'Neil's parameters, 8 samples, the viewer on the ground.
    fn default() -> Self {
        Self {
            kr: 0.0025,
            km: 0.0010,
            sun_intensity: 20.0,
            mie_g: 0.990,
            wavelengths: [0.650, 0.570, 0.475],
            samples: 8,
            viewer: Vec3::ZERO,
        }
    }
}

impl Scattering {
    /// The Rayleigh factor 1/λ⁴ (λ in µm) of each channel, the `v3InvWavelength` of O'Neil.
    #[must_use]
    pub fn inverse_wavelength4(&self) -> Vec3 {
        let f = |l: f32| {
            let l2 = l * l;
            1.0 / (l2 * l2)
        };
        Vec3::new(
            f(self.wavelengths[0]),
            f(self.wavelengths[1]),
            f(self.wavelengths[2]),
        )
    }

    fn validate(&self) -> Result<(), SkyError> {
        let k = MAX_SCATTERING_CONSTANT;
        check_range("scattering.kr", self.kr, 0.0, k)?;
        check_range("scattering.km", self.km, 0.0, k)?;
        check_range(
            "scattering.sun_intensity",
            self.sun_intensity,
            0.0,
            MAX_SUN_INTENSITY,
        )?;
        check_range("scattering.mie_g", self.mie_g, -MAX_MIE_G, MAX_MIE_G)?;
        let names = [
            "scattering.wavelengths.red [um]",
            "scattering.wavelengths.green [um]",
            "scattering.wavelengths.blue [um]",
        ];
        for (name, l) in names.into_iter().zip(self.wavelengths) {
            check_range(name, l, MIN_WAVELENGTH, MAX_WAVELENGTH)?;
        }
        #[allow(clippy::cast_precision_loss)] // exact for these small counts
        if !(1..=MAX_SAMPLES).contains(&self.samples) {
            return Err(SkyError::OutOfRange {
                parameter: "scattering.samples",
                value: self.samples as f32,
                min: 1.0,
                max: MAX_SAMPLES as f32,
            });
        }
        if !self.viewer.is_finite() {
            return Err(SkyError::NotFinite {
                parameter: "scattering.viewer",
            });
        }
        check_range(
            "scattering.viewer (altitude)",
            self.viewer.length(),
            0.0,
            MAX_VIEWER_ALTITUDE,
        )?;
        Ok(())
    }
}

/// log₂ of O'Neil's optical-depth fit without its factor 0.25:
/// `log₂ e · (−0.00287 + x(0.459 + x(3.83 + x(−6.80 + 5.25 x))))`, x = 1 − cos θ. The optical
/// depth from a point at the planet's surface to space, along a ray at angle θ from the
/// vertical, is `0.25 · 2^this` atmosphere thicknesses (times the density there for other
/// altitudes). Fitted for θ in [0°, 90°]; beyond, it grows quickly (to 2⁶⁶ at 180°), which
/// makes light from below the horizon vanish and stays finite.
#[inline(always)]
fn scale_log2(cos: f32) -> f32 {
    let [c0, c1, c2, c3, c4] = SCALE_FIT_LOG2;
    let x = 1.0 - cos;
    c0 + x * (c1 + x * (c2 + x * (c3 + x * c4)))
}

/// The coefficients of O'Neil's optical-depth fit in log₂ units, lowest power first: the
/// polynomial in x = 1 − cos θ that `scale_log2` evaluates (O'Neil's −0.00287, 0.459, 3.83,
/// −6.80, 5.25, each times log₂e).
pub const SCALE_FIT_LOG2: [f32; 5] = [
    -0.00287 * LOG2_E,
    0.459 * LOG2_E,
    3.83 * LOG2_E,
    -6.80 * LOG2_E,
    5.25 * LOG2_E,
];

/// What [`AoasSky`]'s ray march reads ([`AoasSky::kernel_constants`]); lengths in atmosphere
/// thicknesses, the planet's radius being [`PLANET_RADIUS`] and the scale depth [`SCALE_DEPTH`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KernelConstants {
    /// Unit apex direction of the viewer (eq. 2).
    pub apex: Vec3,
    /// Unit direction towards the sun.
    pub sun: Vec3,
    /// The viewer's distance from the planet's centre, R + h.
    pub camera_radius: f32,
    /// (R + h)² − R².
    pub camera_lift: f32,
    /// (R + 1)² − (R + h)².
    pub far_lift: f32,
    /// log₂ of the density at the viewer.
    pub camera_density_log2: f32,
    /// sun · apex.
    pub sun_apex: f32,
    /// 4π (Kr K_c + Km) log₂e per channel: the extinction in log₂ units.
    pub extinction_log2: [f32; 3],
    /// ESun Kr K_c per channel.
    pub rayleigh: [f32; 3],
    /// ESun Km.
    pub mie: f32,
    /// 1.5 (1 − g²)/(2 + g²), (1 − g)², 2g, (1 − |g|)²: the Mie phase function's constants.
    pub mie_phase: [f32; 4],
    /// Ray-marching samples.
    pub samples: u32,
}

/// The geometry and start of one view ray, shared by the one-direction and batch paths.
#[derive(Debug, Clone, Copy)]
struct RayStart {
    /// The unit view direction the fragment is shaded for (NaN-free), before ambiguity.
    dir: Vec3,
    /// 1 above the viewer's horizon, 0 below.
    above: f32,
    /// cos of the ray's angle from the apex, in [0, 1] (the ray is lifted to the horizon).
    mu: f32,
    /// cos of the angle between the ray and the sun.
    nu: f32,
    /// 1 − cos of that angle, as |v − s|²/2: accurate near the sun, where 1 − ν cancels.
    one_minus_nu: f32,
    /// Length of one ray-marching step, atmosphere thicknesses.
    step: f32,
    /// Optical depth from the viewer to space along the ray (O'Neil's fStartOffset).
    start_offset: f32,
}

/// The sky of AOAS (seed 004) for one set of scattering parameters and one style.
///
/// Construct it once with [`AoasSky::new`]; then evaluate any number of view directions with
/// [`rgb`](Self::rgb), [`rgb_fragment`](Self::rgb_fragment) or [`rgb_batch`](Self::rgb_batch).
///
/// **Axes**: skydome space, +z up, as in the rest of the crate; the viewer's apex is +z unless
/// [`Scattering::viewer`] puts the viewer off the axis. **Output**: linear RGB in O'Neil's
/// relative units (the channels are the three wavelengths, used as linear sRGB primaries, as
/// O'Neil displays them), proportional to [`Scattering::sun_intensity`]; a noon sky is about
/// 0.1-1.5, the sun's halo much brighter. O'Neil's display mapping is `1 − exp(−exposure · c)`.
/// Always finite and non-negative. **Below the horizon** (views more than 1e-6 in cos θ below
/// the viewer's horizon) the sky is black.
/// **Accuracy** (held by `tests/tests/aoas.rs` against the f64 references of
/// `sky_train::reference::aoas`): against the exact single-scattering integral (optical depths
/// integrated numerically, the planet's shadow included), over the upper hemisphere for sun
/// zenith angles 0-85°, the largest relative luminance error of the physical sky is 16 % with
/// 2 samples, 3.4 % with 5, 2.3 % with the default 8 (RMS 1.1 %, chromaticity within 0.003 in
/// xy) and 2.2 % with 64: from 8 samples on it is the error of O'Neil's optical-depth fit, largest
/// near the horizon. With the sun within 1° of the horizon it reaches 27 % near the horizon away
/// from the sun, where the planet's shadow, which the fit ignores, falls on the ray. This f32
/// evaluation agrees with the same approximation in f64 to 2e-5 per channel, near the sun too
/// (1 − cos γ is taken as |v − s|²/2, so the Mie peak does not amplify the rounding of cos γ).
///
/// ```
/// use sky_core::aoas::{AoasSky, Scattering, Style};
/// use sky_core::Vec3;
///
/// let sky = AoasSky::new(&Scattering::default(), &Style::default())?; // physical, noon
/// let zenith = sky.rgb(Vec3::Z);
/// assert!(zenith.z > zenith.y && zenith.y > zenith.x); // blue
/// // A fragment of any skydome, in skydome space: only its direction from the viewer counts.
/// assert!((sky.rgb_fragment(Vec3::new(0.0, 0.0, 250.0)) - zenith).abs().max_element() < 1e-6);
/// # Ok::<(), sky_core::SkyError>(())
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct AoasSky {
    scattering: Scattering,
    style: Style,
    sun: Sun,
    /// Unit apex direction of the viewer (eq. 2).
    apex: Vec3,
    /// The viewer's distance from the planet's centre, R + h (thicknesses).
    camera_radius: f32,
    /// (R + h)² − R² = h (2R + h).
    camera_lift: f32,
    /// (R + 1)² − (R + h)²: what the view ray's far end adds to the camera's squared radius.
    far_lift: f32,
    /// log₂ of the density at the viewer, −h/H log₂ e.
    camera_density_log2: f32,
    /// sun · apex.
    sun_apex: f32,
    /// 4π (Kr K_c + Km) log₂ e per channel: the extinction, in log₂ units.
    extinction_log2: [f32; 3],
    /// ESun Kr K_c per channel: the Rayleigh weight (K_c = 1/λ⁴ or the sky hue).
    rayleigh: [f32; 3],
    /// ESun Km.
    mie: f32,
    /// 1.5 (1 − g²)/(2 + g²), (1 − g)², 2g, (1 − |g|)²: the Mie phase function's constants.
    mie_phase: [f32; 4],
    samples: u32,
}

impl AoasSky {
    /// The sky for `scattering` and `style`.
    ///
    /// # Errors
    /// [`SkyError::OutOfRange`] or [`SkyError::NotFinite`] naming the first parameter out of its
    /// documented range (the name is its field path, such as `scattering.samples` or
    /// `cloud_noise.size`); [`SkyError::SunBelowHorizon`] for a day cycle whose sun is below
    /// the horizon.
    pub fn new(scattering: &Scattering, style: &Style) -> Result<Self, SkyError> {
        scattering.validate()?;
        let sun = style.validate()?;
        let s = *scattering;
        let h = s.viewer.length();
        let apex = if h > 0.0 { s.viewer / h } else { Vec3::Z };
        let r = PLANET_RADIUS;
        let camera_radius = r + h;
        let hue = style.sky_hue.unwrap_or_else(|| s.inverse_wavelength4());
        let hue = [hue.x, hue.y, hue.z];
        let g = s.mie_g;
        Ok(Self {
            scattering: s,
            style: style.clone(),
            sun,
            apex,
            camera_radius,
            camera_lift: h * (2.0 * r + h),
            far_lift: (1.0 - h) * (2.0 * r + 1.0 + h),
            camera_density_log2: -h / SCALE_DEPTH * LOG2_E,
            sun_apex: sun.direction().dot(apex),
            extinction_log2: hue.map(|k| 4.0 * PI * (s.kr * k + s.km) * LOG2_E),
            rayleigh: hue.map(|k| s.sun_intensity * s.kr * k),
            mie: s.sun_intensity * s.km,
            mie_phase: [
                1.5 * (1.0 - g * g) / (2.0 + g * g),
                (1.0 - g) * (1.0 - g),
                2.0 * g,
                (1.0 - g.abs()) * (1.0 - g.abs()),
            ],
            samples: s.samples,
        })
    }

    /// The scattering parameters this sky was built with.
    #[must_use]
    pub fn scattering(&self) -> &Scattering {
        &self.scattering
    }

    /// The style this sky was built with.
    #[must_use]
    pub fn style(&self) -> &Style {
        &self.style
    }

    /// The constants of the ray march, exactly as [`rgb`](Self::rgb) uses them: for GPU shaders
    /// (sky-gpu) that take these values as uniforms. They cover the physical sky and the sky
    /// hue and day cycle of any style; the pattern principles (cloud noise and shapes) and
    /// ambiguity are not among them (see [`has_pattern_or_ambiguity`](Self::has_pattern_or_ambiguity)).
    #[must_use]
    pub fn kernel_constants(&self) -> KernelConstants {
        KernelConstants {
            apex: self.apex,
            sun: self.sun.direction(),
            camera_radius: self.camera_radius,
            camera_lift: self.camera_lift,
            far_lift: self.far_lift,
            camera_density_log2: self.camera_density_log2,
            sun_apex: self.sun_apex,
            extinction_log2: self.extinction_log2,
            rayleigh: self.rayleigh,
            mie: self.mie,
            mie_phase: self.mie_phase,
            samples: self.samples,
        }
    }

    /// Whether the style has a principle beyond the scattering, sky hue and day cycle: cloud
    /// noise, cloud shapes or ambiguity ([`kernel_constants`](Self::kernel_constants) leaves
    /// them out).
    #[must_use]
    pub fn has_pattern_or_ambiguity(&self) -> bool {
        self.has_pattern() || self.style.ambiguity.is_some()
    }

    /// The sun of the style's day cycle.
    #[must_use]
    pub fn sun(&self) -> Sun {
        self.sun
    }

    /// Linear RGB (relative units, see [`AoasSky`]) seen along the view direction `dir` in
    /// skydome space (eq. 1: the same as in Earth space), with every principle of the style
    /// applied.
    ///
    /// `dir` need not be normalised if its length lies in [1e-18, 1e18]; the zero vector and
    /// non-finite vectors give a finite, meaningless value.
    #[inline]
    #[must_use]
    pub fn rgb(&self, dir: Vec3) -> Vec3 {
        let ray = match self.style.ambiguity {
            Some(a) => self.ray_start::<true>(dir, a),
            None => self.ray_start::<false>(dir, NO_AMBIGUITY),
        };
        let mut acc = [0.0; 3];
        for i in 0..self.samples {
            let s = self.sample(&ray, i);
            for c in 0..3 {
                acc[c] += s[c];
            }
        }
        let rgb = self.in_scattered(&ray, acc);
        if !self.has_pattern() {
            return rgb;
        }
        let mut keep = 1.0;
        if !self.style.cloud_shapes.is_empty() {
            keep = 1.0 - self.style.cloud_shapes.density(ray.dir);
        }
        if let Some(n) = self.style.cloud_noise {
            keep *= noise_keep(n, ray.dir);
        }
        desaturate(rgb, keep)
    }

    /// [`rgb`](Self::rgb) for the skydome fragment at `fragment` (skydome space, the same units
    /// as [`Scattering::viewer`]): the view direction is `fragment − Pvs` (eq. 1), so any skydome
    /// mesh, of any size or shape around the viewer, shows the same sky (Fig. 7).
    #[inline]
    #[must_use]
    pub fn rgb_fragment(&self, fragment: Vec3) -> Vec3 {
        self.rgb(fragment - self.scattering.viewer)
    }

    /// [`rgb`](Self::rgb) for many directions: fills `out[i]` for every `i` below
    /// `min(dirs.len(), out.len())`, with the same results as `rgb` bit for bit. The directions
    /// go through the ray march 32 at a time, sample by sample, so that the loops compile to
    /// SIMD code.
    #[inline(always)]
    pub fn rgb_batch(&self, dirs: &[Vec3], out: &mut [Vec3]) {
        let n = dirs.len().min(out.len());
        for (d, o) in dirs[..n].chunks(CHUNK).zip(out[..n].chunks_mut(CHUNK)) {
            self.rgb_chunk(d, o);
        }
    }

    /// Whether a pattern principle changes the colour (cloud noise or shapes).
    #[inline(always)]
    fn has_pattern(&self) -> bool {
        self.style.cloud_noise.is_some() || !self.style.cloud_shapes.is_empty()
    }

    /// Up to [`CHUNK`] directions: the scalar path's operations, in the same order per lane, with
    /// the loop over lanes innermost and no branch inside it (the style's choices are made once
    /// per chunk), so that each loop compiles to SIMD code. Lanes past the end repeat the first
    /// direction.
    #[inline(always)]
    #[allow(clippy::needless_range_loop)] // lanes index several arrays at once
    fn rgb_chunk(&self, dirs: &[Vec3], out: &mut [Vec3]) {
        let Some(&first) = dirs.first() else {
            return;
        };
        let mut lane_dirs = [first; CHUNK];
        for (l, d) in lane_dirs.iter_mut().zip(dirs) {
            *l = *d;
        }
        // Structure of arrays: one array per quantity, one element per lane.
        let mut rays = Lanes::default();
        match self.style.ambiguity {
            Some(a) => {
                for k in 0..CHUNK {
                    rays.set(k, self.ray_start::<true>(lane_dirs[k], a));
                }
            }
            None => {
                for k in 0..CHUNK {
                    rays.set(k, self.ray_start::<false>(lane_dirs[k], NO_AMBIGUITY));
                }
            }
        }
        let mut acc = [[0.0f32; CHUNK]; 3];
        for i in 0..self.samples {
            for k in 0..CHUNK {
                let s = self.sample(&rays.get(k), i);
                for c in 0..3 {
                    acc[c][k] += s[c];
                }
            }
        }
        let mut rgb = [[0.0f32; CHUNK]; 3];
        for k in 0..CHUNK {
            let c = self.in_scattered(&rays.get(k), [acc[0][k], acc[1][k], acc[2][k]]);
            (rgb[0][k], rgb[1][k], rgb[2][k]) = (c.x, c.y, c.z);
        }
        if self.has_pattern() {
            let mut keep = [1.0f32; CHUNK];
            if !self.style.cloud_shapes.is_empty() {
                let mut density = [0.0f32; CHUNK];
                self.style.cloud_shapes.density_lanes(
                    &rays.dir[0],
                    &rays.dir[1],
                    &rays.dir[2],
                    &mut density,
                );
                for k in 0..CHUNK {
                    keep[k] = 1.0 - density[k];
                }
            }
            if let Some(n) = self.style.cloud_noise {
                // Perlin's permutation table: lookups, not SIMD.
                for k in 0..CHUNK {
                    keep[k] *= noise_keep(n, rays.get(k).dir);
                }
            }
            for k in 0..CHUNK {
                let c = desaturate(Vec3::new(rgb[0][k], rgb[1][k], rgb[2][k]), keep[k]);
                (rgb[0][k], rgb[1][k], rgb[2][k]) = (c.x, c.y, c.z);
            }
        }
        for (k, o) in out.iter_mut().enumerate().take(CHUNK) {
            *o = Vec3::new(rgb[0][k], rgb[1][k], rgb[2][k]);
        }
    }

    /// Eq. 1 (normalisation), the ambiguity of eqs. 5-6, eq. 2's geometry and the start of
    /// O'Neil's march: everything per direction before the samples.
    #[inline(always)]
    fn ray_start<const AMBIGUOUS: bool>(&self, dir: Vec3, ambiguity: Ambiguity) -> RayStart {
        // normalize_or_zero with the kernel rsqrt; then NaN components become -1 (max/min map
        // NaN to the bound), so everything after is finite.
        let d = dir * math::rsqrt(dir.length_squared());
        #[allow(clippy::manual_clamp)] // clamp would pass NaN through
        let d = Vec3::new(
            d.x.max(-1.0).min(1.0),
            d.y.max(-1.0).min(1.0),
            d.z.max(-1.0).min(1.0),
        );
        let above = if d.dot(self.apex) >= -HORIZON_TOLERANCE {
            1.0
        } else {
            0.0
        };
        // Eqs. 5-6: shade with the direction towards a random point of the fragment's
        // neighbourhood (the fragment at unit distance from the viewer).
        let mut v = d;
        if AMBIGUOUS {
            let r = noise::fragment_draws(d.x, d.y, d.z, ambiguity.seed);
            v = d + Vec3::new(r[0], r[1], r[2]) * ambiguity.neighbourhood;
        }
        // Lift a ray below the horizon onto it (the sky is black there, but the march must stay
        // finite, and an ambiguous ray near the horizon takes the horizon's colour).
        let below = v.dot(self.apex);
        let v = v + self.apex * (below.max(0.0) - below);
        let v = v * math::rsqrt(v.length_squared());
        #[allow(clippy::manual_clamp)]
        let mu = v.dot(self.apex).max(0.0).min(1.0);
        #[allow(clippy::manual_clamp)]
        let nu = v.dot(self.sun.direction()).max(-1.0).min(1.0);
        // 1 − ν = |v − s|²/2 for unit v and s, without the cancellation of 1 − ν near the sun
        // (where the Mie peak would amplify it).
        let one_minus_nu = 0.5 * (v - self.sun.direction()).length_squared();
        // Eq. 3's ray from Pv to the outer sphere: t² + 2 (R+h) μ t − far_lift = 0, solved
        // without cancellation (b ≥ 0).
        let b = self.camera_radius * mu;
        let far = self.far_lift / (b + math::sqrt_kernel(b * b + self.far_lift));
        #[allow(clippy::cast_precision_loss)] // at most 64
        let step = far / self.samples as f32;
        // O'Neil's fStartOffset: the viewer's density times scale(angle of the ray at the viewer).
        let start_offset = SCALE_DEPTH * math::exp2(self.camera_density_log2 + scale_log2(mu));
        RayStart {
            dir: d,
            above,
            mu,
            nu,
            one_minus_nu,
            step,
            start_offset,
        }
    }

    /// Sample `i` of O'Neil's march (eq. 3's P_i at the middle of step i; eq. 4's integrand) per
    /// channel: the attenuation towards the sun and back to the viewer, times the density.
    #[inline(always)]
    fn sample(&self, ray: &RayStart, i: u32) -> [f32; 3] {
        #[allow(clippy::cast_precision_loss)] // at most 64
        let t = (i as f32 + 0.5) * ray.step;
        let r = PLANET_RADIUS;
        // |P|² = (R+h)² + t (2 (R+h) μ + t); its excess over R², without cancellation.
        let along = t * (2.0 * self.camera_radius * ray.mu + t);
        let radius2 = self.camera_radius * self.camera_radius + along;
        let inv_radius = math::rsqrt(radius2);
        let radius = radius2 * inv_radius;
        let altitude = (self.camera_lift + along) / (radius + r);
        let density_log2 = altitude * (-LOG2_E / SCALE_DEPTH);
        let light_cos = (self.camera_radius * self.sun_apex + t * ray.nu) * inv_radius;
        let camera_cos = (self.camera_radius * ray.mu + t) * inv_radius;
        // density × scale(angle): the optical depth from P to space towards the sun, and along
        // the ray; O'Neil's fScatter = fStartOffset + depth (scale(light) − scale(camera)).
        let to_sun = math::exp2(density_log2 + scale_log2(light_cos));
        let to_space = math::exp2(density_log2 + scale_log2(camera_cos));
        let scatter = ray.start_offset + SCALE_DEPTH * (to_sun - to_space);
        self.extinction_log2
            .map(|e| math::exp2(density_log2 - scatter * e))
    }

    /// The phase functions and constants applied to the accumulated samples: Rayleigh
    /// 0.75 (1 + cos²) and O'Neil's Mie 1.5 (1 − g²)/(2 + g²) (1 + cos²)/(1 + g² − 2g cos)^1.5.
    #[inline(always)]
    fn in_scattered(&self, ray: &RayStart, acc: [f32; 3]) -> Vec3 {
        let nu = ray.nu;
        let one_plus_cos2 = 1.0 + nu * nu;
        let rayleigh_phase = 0.75 * one_plus_cos2;
        let [mie_a, one_minus_g2, two_g, q_min] = self.mie_phase;
        // 1 + g² − 2g cos = (1 − g)² + 2g (1 − cos): no cancellation near the sun for g > 0;
        // never below its true minimum (1 − |g|)², which rounding could cross for g < 0.
        let q = (one_minus_g2 + two_g * ray.one_minus_nu).max(q_min);
        let rq = math::rsqrt(q);
        let mie_phase = mie_a * one_plus_cos2 * (rq * rq * rq);
        let w = ray.step * ray.above;
        let c = |k: usize| acc[k] * w * (self.rayleigh[k] * rayleigh_phase + self.mie * mie_phase);
        Vec3::new(c(0), c(1), c(2))
    }
}

/// The ambiguity of a style without it (never read: `ray_start::<false>` ignores it).
const NO_AMBIGUITY: Ambiguity = Ambiguity {
    neighbourhood: 0.0,
    seed: 0,
};

/// The fraction of the saturation the cloud noise keeps towards the unit direction `dir`
/// (eqs. 7-8): Improved Perlin noise at the fragment's position on the unit sphere around the
/// viewer over S_noise, mapped to [0, 1] and blended by the strength.
#[inline(always)]
fn noise_keep(n: CloudNoise, dir: Vec3) -> f32 {
    let inv = 1.0 / n.size;
    let value = noise::improved_perlin(dir.x * inv, dir.y * inv, dir.z * inv);
    #[allow(clippy::manual_clamp)] // clamp would pass NaN through
    let unit = (0.5 + 0.5 * value).max(0.0).min(1.0);
    1.0 - n.strength * (1.0 - unit)
}

/// [`RayStart`] for [`CHUNK`] lanes, one array per quantity.
#[derive(Default)]
struct Lanes {
    dir: [[f32; CHUNK]; 3],
    above: [f32; CHUNK],
    mu: [f32; CHUNK],
    nu: [f32; CHUNK],
    one_minus_nu: [f32; CHUNK],
    step: [f32; CHUNK],
    start_offset: [f32; CHUNK],
}

impl Lanes {
    #[inline(always)]
    fn set(&mut self, k: usize, r: RayStart) {
        (self.dir[0][k], self.dir[1][k], self.dir[2][k]) = (r.dir.x, r.dir.y, r.dir.z);
        (self.above[k], self.mu[k], self.nu[k]) = (r.above, r.mu, r.nu);
        self.one_minus_nu[k] = r.one_minus_nu;
        (self.step[k], self.start_offset[k]) = (r.step, r.start_offset);
    }

    #[inline(always)]
    fn get(&self, k: usize) -> RayStart {
        RayStart {
            dir: Vec3::new(self.dir[0][k], self.dir[1][k], self.dir[2][k]),
            above: self.above[k],
            mu: self.mu[k],
            nu: self.nu[k],
            one_minus_nu: self.one_minus_nu[k],
            step: self.step[k],
            start_offset: self.start_offset[k],
        }
    }
}

/// Eq. 8 in closed form: HSV saturation × `keep`, hue and value unchanged. In HSV each channel
/// is c = V (1 − S f(H)) with V the largest channel, so scaling S by `keep` gives
/// c' = V − keep (V − c): the same colour as converting to HSV, scaling and converting back,
/// without the six-way branch on the hue.
#[inline(always)]
fn desaturate(rgb: Vec3, keep: f32) -> Vec3 {
    let v = rgb.max_element();
    Vec3::splat(v) - (Vec3::splat(v) - rgb) * keep
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom;

    fn sky(style: &Style) -> AoasSky {
        AoasSky::new(&Scattering::default(), style).expect("valid")
    }

    /// Directions on a grid over the whole sphere, plus awkward ones.
    fn directions() -> [Vec3; 300] {
        core::array::from_fn(|k| match k {
            0 => Vec3::ZERO,
            1 => Vec3::NAN,
            2 => Vec3::new(f32::INFINITY, 0.0, 1.0),
            3 => Vec3::new(0.0, 0.0, -1e30),
            4 => Vec3::new(1.0, 0.0, 0.0),
            _ => {
                #[allow(clippy::cast_precision_loss)]
                let k = k as f32;
                geom::direction(k * 0.0107, k * 0.377) * (1.0 + k)
            }
        })
    }

    #[test]
    fn scale_fit_is_o_neils() {
        // scale(1) = 0.25 exp(-0.00287); scale(0) = 0.25 exp(-0.00287 + 0.459 + 3.83 - 6.80 + 5.25).
        let s = |c: f32| 0.25 * libm::exp2f(scale_log2(c));
        assert!((s(1.0) - 0.25 * libm::expf(-0.00287)).abs() < 1e-7);
        assert!((s(0.0) / (0.25 * libm::expf(2.736_13)) - 1.0).abs() < 1e-6);
    }

    #[test]
    fn batch_equals_one_direction_bit_for_bit() {
        let dirs = directions();
        for preset in Preset::ALL {
            let sky = sky(&preset.style());
            let mut out = [Vec3::NAN; 300];
            sky.rgb_batch(&dirs, &mut out);
            for (d, o) in dirs.iter().zip(out) {
                let one = sky.rgb(*d);
                assert_eq!(
                    o.to_array().map(f32::to_bits),
                    one.to_array().map(f32::to_bits),
                    "{} at {d}",
                    preset.name()
                );
            }
        }
    }

    #[test]
    fn finite_non_negative_and_black_below() {
        for preset in Preset::ALL {
            let sky = sky(&preset.style());
            for d in directions() {
                let c = sky.rgb(d);
                assert!(
                    c.is_finite() && c.min_element() >= 0.0,
                    "{} {d}: {c}",
                    preset.name()
                );
                if d.z < -1e-3 && d.is_finite() {
                    assert_eq!(c, Vec3::ZERO, "{} {d}", preset.name());
                }
            }
        }
    }

    #[test]
    fn desaturate_is_the_hsv_round_trip() {
        // RGB -> HSV -> scale S -> RGB, written out (Agoston 2005, as cited by seed 004).
        fn hsv_round_trip(c: [f32; 3], keep: f32) -> [f32; 3] {
            let v = c[0].max(c[1]).max(c[2]);
            let m = c[0].min(c[1]).min(c[2]);
            let delta = v - m;
            if v <= 0.0 || delta <= 0.0 {
                return c;
            }
            let s = delta / v;
            let h = if v == c[0] {
                ((c[1] - c[2]) / delta).rem_euclid(6.0)
            } else if v == c[1] {
                (c[2] - c[0]) / delta + 2.0
            } else {
                (c[0] - c[1]) / delta + 4.0
            };
            let s = s * keep;
            let chroma = v * s;
            let x = chroma * (1.0 - ((h % 2.0) - 1.0).abs());
            let (r, g, b) = match h as u32 {
                0 => (chroma, x, 0.0),
                1 => (x, chroma, 0.0),
                2 => (0.0, chroma, x),
                3 => (0.0, x, chroma),
                4 => (x, 0.0, chroma),
                _ => (chroma, 0.0, x),
            };
            let m = v - chroma;
            [r + m, g + m, b + m]
        }
        for c in [
            [0.2, 0.5, 0.9],
            [0.9, 0.3, 0.1],
            [0.4, 0.4, 0.1],
            [0.3, 0.3, 0.3],
            [0.0, 0.7, 0.2],
        ] {
            for keep in [0.0, 0.3, 1.0] {
                let want = hsv_round_trip(c, keep);
                let got = desaturate(Vec3::from_array(c), keep);
                for k in 0..3 {
                    assert!(
                        (got[k] - want[k]).abs() < 1e-6,
                        "{c:?} x {keep}: {got} vs {want:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn every_parameter_out_of_range_is_a_typed_error() {
        let ok = Scattering::default();
        let style = Style::default();
        let cases: [(Scattering, &str); 11] = [
            (Scattering { kr: -0.1, ..ok }, "scattering.kr"),
            (Scattering { km: 0.5, ..ok }, "scattering.km"),
            (
                Scattering {
                    sun_intensity: f32::NAN,
                    ..ok
                },
                "scattering.sun_intensity",
            ),
            (Scattering { mie_g: 1.0, ..ok }, "scattering.mie_g"),
            (
                Scattering {
                    wavelengths: [0.2, 0.57, 0.475],
                    ..ok
                },
                "scattering.wavelengths.red [um]",
            ),
            (
                Scattering {
                    wavelengths: [0.65, 0.9, 0.475],
                    ..ok
                },
                "scattering.wavelengths.green [um]",
            ),
            (
                Scattering {
                    wavelengths: [0.65, 0.57, f32::NAN],
                    ..ok
                },
                "scattering.wavelengths.blue [um]",
            ),
            (Scattering { samples: 0, ..ok }, "scattering.samples"),
            (Scattering { samples: 65, ..ok }, "scattering.samples"),
            (
                Scattering {
                    viewer: Vec3::new(0.0, 0.0, 0.95),
                    ..ok
                },
                "scattering.viewer (altitude)",
            ),
            (
                Scattering {
                    viewer: Vec3::new(0.0, 0.5, -0.8),
                    ..ok
                },
                "scattering.viewer (altitude)",
            ),
        ];
        for (s, name) in cases {
            match AoasSky::new(&s, &style) {
                Err(SkyError::OutOfRange { parameter, .. }) => assert_eq!(parameter, name),
                other => panic!("{name}: {other:?}"),
            }
        }
        assert_eq!(
            AoasSky::new(
                &Scattering {
                    viewer: Vec3::NAN,
                    ..ok
                },
                &style
            ),
            Err(SkyError::NotFinite {
                parameter: "scattering.viewer"
            })
        );
        let styles: [(Style, &str); 9] = [
            (
                Style {
                    ambiguity: Some(Ambiguity {
                        neighbourhood: 0.6,
                        seed: 0,
                    }),
                    ..Style::default()
                },
                "ambiguity.neighbourhood",
            ),
            (
                Style {
                    ambiguity: Some(Ambiguity {
                        neighbourhood: -0.1,
                        seed: 0,
                    }),
                    ..Style::default()
                },
                "ambiguity.neighbourhood",
            ),
            (
                Style {
                    cloud_noise: Some(CloudNoise {
                        size: 0.0,
                        strength: 1.0,
                    }),
                    ..Style::default()
                },
                "cloud_noise.size",
            ),
            (
                Style {
                    cloud_noise: Some(CloudNoise {
                        size: 11.0,
                        strength: 1.0,
                    }),
                    ..Style::default()
                },
                "cloud_noise.size",
            ),
            (
                Style {
                    cloud_noise: Some(CloudNoise {
                        size: 1.0,
                        strength: 1.5,
                    }),
                    ..Style::default()
                },
                "cloud_noise.strength",
            ),
            (
                Style {
                    sky_hue: Some(Vec3::new(-1.0, 1.0, 1.0)),
                    ..Style::default()
                },
                "sky_hue.red",
            ),
            (
                Style {
                    sky_hue: Some(Vec3::new(1.0, f32::NAN, 1.0)),
                    ..Style::default()
                },
                "sky_hue.green",
            ),
            (
                Style {
                    sky_hue: Some(Vec3::new(1.0, 1.0, 101.0)),
                    ..Style::default()
                },
                "sky_hue.blue",
            ),
            (
                Style {
                    day_cycle: DayCycle::TimeOfDay {
                        hours: 20.0,
                        noon_elevation: 1.0,
                    },
                    ..Style::default()
                },
                "day_cycle.time_of_day [h]",
            ),
        ];
        for (s, name) in styles {
            match AoasSky::new(&ok, &s) {
                Err(SkyError::OutOfRange { parameter, .. }) => assert_eq!(parameter, name),
                other => panic!("{name}: {other:?}"),
            }
        }
    }
}
