//! The precomputed atmosphere and the sky of one sun position: radiance per direction (XYZ +
//! melanopic fast, spectral slower), irradiance (global, diffuse, direct; horizontal and
//! tilted) and the sun's transmitted spectrum.

use std::f64::consts::PI;
use std::sync::Arc;

use super::atmosphere::Atmosphere;
use super::constituents::{EARTH_RADIUS_M as R, N_WAVELENGTHS as NW, Spectrum, henyey_greenstein};
use super::grid;
use super::photometry::{self, Colorimetry};
use super::transport::{self, GroundTables, Medium, Resolution, Transmittance, log_lerp};

/// The largest sun zenith angle a [`PhysicalSky`] accepts, degrees (the sun 18° below the
/// horizon: the end of astronomical twilight).
pub const MAX_SUN_ZENITH_DEG: f64 = 108.0;

/// Channels of the fast radiance tables per ground-table cell: for X, Y, Z and melanopic,
/// the Rayleigh isotropic and cos² terms, the aerosol term (times its phase function at
/// lookup) and the multiple scattering.
const CHANNELS: usize = 16;
/// Floor of the logarithms in the fast tables.
const TINY: f64 = 1e-30;

/// A precomputed clear atmosphere, for any sun position: build it with
/// [`PhysicalAtmosphere::build`] (or [`super::cache::load_or_build`], which keeps it on disk),
/// then ask [`PhysicalAtmosphere::sky`] for a sun.
#[derive(Debug)]
pub struct PhysicalAtmosphere {
    /// The parameters.
    pub atmosphere: Atmosphere,
    /// The table resolution.
    pub resolution: Resolution,
    /// The medium (coefficients and profiles).
    pub medium: Medium,
    /// Column densities to the top of the atmosphere.
    pub transmittance: Transmittance,
    /// The viewer-on-the-ground tables.
    pub ground: GroundTables,
    /// ln of the 16 fast channels per ground cell.
    fast: Vec<[f32; CHANNELS]>,
}

impl PhysicalAtmosphere {
    /// Precomputes `atmosphere` at `resolution`, showing progress on `bar`.
    ///
    /// # Errors
    /// When a parameter is out of range.
    pub fn build(
        atmosphere: &Atmosphere,
        resolution: &Resolution,
        bar: &indicatif::ProgressBar,
    ) -> Result<Self, super::atmosphere::AtmosphereError> {
        atmosphere.validate()?;
        let medium = Medium::new(atmosphere);
        let (transmittance, ground) = transport::precompute(&medium, resolution, bar);
        Ok(Self::from_parts(
            atmosphere,
            resolution,
            medium,
            transmittance,
            ground,
        ))
    }

    /// Assembles an atmosphere from its tables (computed or read from the cache).
    #[must_use]
    pub fn from_parts(
        atmosphere: &Atmosphere,
        resolution: &Resolution,
        medium: Medium,
        transmittance: Transmittance,
        ground: GroundTables,
    ) -> Self {
        let w = photometry::channel_weights();
        let phase = medium.coefficients.rayleigh_phase;
        let cells = ground.rayleigh.cells();
        let fast = (0..cells)
            .map(|k| {
                let range = k * NW..(k + 1) * NW;
                let (sr, sa, m) = (
                    &ground.rayleigh.data[range.clone()],
                    &ground.aerosol.data[range.clone()],
                    &ground.multiple.data[range],
                );
                let mut ch = [0.0f64; CHANNELS];
                for c in 0..4 {
                    for l in 0..NW {
                        let s = f64::from(sr[l]);
                        ch[c] += w[c][l] * phase[l].0 * s;
                        ch[4 + c] += w[c][l] * phase[l].1 * s;
                        ch[8 + c] += w[c][l] * f64::from(sa[l]);
                        ch[12 + c] += w[c][l] * f64::from(m[l]);
                    }
                }
                #[allow(clippy::cast_possible_truncation)]
                ch.map(|v| v.max(TINY).ln() as f32)
            })
            .collect();
        Self {
            atmosphere: *atmosphere,
            resolution: *resolution,
            medium,
            transmittance,
            ground,
            fast,
        }
    }

    /// The sky with the sun at `zenith_deg` (0 to [`MAX_SUN_ZENITH_DEG`]) and `azimuth_deg`
    /// (sky-core's convention: from +x towards +y), at 1 AU.
    ///
    /// # Errors
    /// When the zenith angle is out of range or an angle is not finite.
    pub fn sky(
        self: &Arc<Self>,
        zenith_deg: f64,
        azimuth_deg: f64,
    ) -> Result<PhysicalSky, SunError> {
        PhysicalSky::new(Arc::clone(self), zenith_deg, azimuth_deg)
    }
}

/// A sun position [`PhysicalAtmosphere::sky`] refuses.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SunError {
    /// The zenith angle given, degrees.
    pub zenith_deg: f64,
    /// The azimuth given, degrees.
    pub azimuth_deg: f64,
}

impl std::fmt::Display for SunError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.azimuth_deg.is_finite() {
            write!(
                f,
                "--sun-zenith {} deg is outside the valid range [0, {MAX_SUN_ZENITH_DEG}] deg for --model physical",
                self.zenith_deg
            )
        } else {
            write!(f, "--sun-azimuth must be a finite number")
        }
    }
}

impl std::error::Error for SunError {}

/// Spectral irradiance on a horizontal plane at the ground, W m⁻² nm⁻¹ per bin.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Irradiance {
    /// Global = diffuse + direct horizontal.
    pub global: Spectrum,
    /// From the sky (every scattering order).
    pub diffuse: Spectrum,
    /// From the sun's disc, on the horizontal plane.
    pub direct_horizontal: Spectrum,
    /// From the sun's disc, on a plane facing it.
    pub direct_normal: Spectrum,
}

/// The sky of one sun position over a [`PhysicalAtmosphere`].
#[derive(Debug, Clone)]
pub struct PhysicalSky {
    atmosphere: Arc<PhysicalAtmosphere>,
    zenith_deg: f64,
    azimuth_deg: f64,
    sun: [f64; 3],
    mus: f64,
    scale: f64,
    sun_index: (usize, f64),
    /// The 16 channels per (μ, φ) node, interpolated to this sun.
    slab: Vec<[f32; CHANNELS]>,
}

impl PhysicalSky {
    fn new(
        atmosphere: Arc<PhysicalAtmosphere>,
        zenith_deg: f64,
        azimuth_deg: f64,
    ) -> Result<Self, SunError> {
        if !(0.0..=MAX_SUN_ZENITH_DEG).contains(&zenith_deg) || !azimuth_deg.is_finite() {
            return Err(SunError {
                zenith_deg,
                azimuth_deg,
            });
        }
        let (z, a) = (zenith_deg.to_radians(), azimuth_deg.to_radians());
        let sun = [z.sin() * a.cos(), z.sin() * a.sin(), z.cos()];
        let g = &atmosphere.ground.rayleigh;
        let sun_index = grid::split(g.sun.index(zenith_deg), g.sun.len());
        let (is, w) = sun_index;
        let per = g.nmu * g.nphi;
        let slab = (0..per)
            .map(|k| {
                let (a, b) = (
                    &atmosphere.fast[is * per + k],
                    &atmosphere.fast[(is + 1) * per + k],
                );
                #[allow(clippy::cast_possible_truncation)]
                std::array::from_fn(|c| {
                    let (la, lb) = (f64::from(a[c]), f64::from(b[c]));
                    (la + w * (lb - la)).exp() as f32
                })
            })
            .collect();
        Ok(Self {
            mus: z.cos(),
            atmosphere,
            zenith_deg,
            azimuth_deg,
            sun,
            scale: 1.0,
            sun_index,
            slab,
        })
    }

    /// The same sky with the extraterrestrial irradiance scaled by `factor` (the eccentricity
    /// correction (r₀ / r)² of a date: [`super::solar::eccentricity_correction`]).
    #[must_use]
    pub fn with_irradiance_scale(mut self, factor: f64) -> Self {
        self.scale = factor;
        self
    }

    /// The sun's zenith angle, degrees.
    #[must_use]
    pub fn sun_zenith_deg(&self) -> f64 {
        self.zenith_deg
    }

    /// The sun's azimuth, degrees.
    #[must_use]
    pub fn sun_azimuth_deg(&self) -> f64 {
        self.azimuth_deg
    }

    /// The atmosphere.
    #[must_use]
    pub fn atmosphere(&self) -> &PhysicalAtmosphere {
        &self.atmosphere
    }

    fn view(&self, dir: [f64; 3]) -> Option<(f64, f64, f64)> {
        let n = (dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]).sqrt();
        if !(n > 0.0 && n.is_finite()) {
            return None;
        }
        let mu = dir[2] / n;
        if mu < 0.0 {
            return None;
        }
        let nu = ((dir[0] * self.sun[0] + dir[1] * self.sun[1] + dir[2] * self.sun[2]) / n)
            .clamp(-1.0, 1.0);
        Some((mu, nu, grid::phi_of(mu, self.mus, nu)))
    }

    /// Sky radiance towards `dir` (+z up, any length; below the horizon 0) as X, Y, Z (cd/m²)
    /// and melanopic equivalent daylight luminance (cd/m²): bilinear lookups of the fast tables
    /// with the phase functions evaluated exactly.
    #[must_use]
    #[inline]
    pub fn radiance_xyzm(&self, dir: [f64; 3]) -> [f64; 4] {
        let Some((mu, nu, phi)) = self.view(dir) else {
            return [0.0; 4];
        };
        let g = &self.atmosphere.ground.rayleigh;
        let ((im, wm), (ip, wp)) = g.view_index(mu, phi);
        let mut ch = [0.0f64; CHANNELS];
        for (dm, fm) in [(0, 1.0 - wm), (1, wm)] {
            for (dp, fp) in [(0, 1.0 - wp), (1, wp)] {
                let w = fm * fp;
                let cell = &self.slab[(im + dm) * g.nphi + ip + dp];
                for (o, x) in ch.iter_mut().zip(cell) {
                    *o += w * f64::from(*x);
                }
            }
        }
        let pa = henyey_greenstein(self.atmosphere.atmosphere.aerosol_g, nu);
        let nu2 = nu * nu;
        std::array::from_fn(|c| {
            self.scale * (ch[c] + nu2 * ch[4 + c] + pa * ch[8 + c] + ch[12 + c]).max(0.0)
        })
    }

    /// Spectral sky radiance towards `dir`, W m⁻² sr⁻¹ nm⁻¹ per bin (the slow path: every
    /// wavelength interpolated, log-linearly in the sun angle).
    #[must_use]
    pub fn spectral_radiance(&self, dir: [f64; 3]) -> Spectrum {
        let Some((mu, nu, phi)) = self.view(dir) else {
            return [0.0; NW];
        };
        let t = &self.atmosphere.ground;
        let (is, w) = self.sun_index;
        let at = |table: &transport::Table3, i: usize| {
            let mut s = [0.0; NW];
            table.lookup_add(i, mu, phi, 1.0, &mut s);
            s
        };
        let lerp = |table: &transport::Table3| -> Spectrum {
            let (a, b) = (at(table, is), at(table, is + 1));
            std::array::from_fn(|l| log_lerp(a[l], b[l], w))
        };
        let (sr, sa, m) = (lerp(&t.rayleigh), lerp(&t.aerosol), lerp(&t.multiple));
        let c = &self.atmosphere.medium.coefficients;
        let pa = henyey_greenstein(self.atmosphere.atmosphere.aerosol_g, nu);
        std::array::from_fn(|l| {
            let pr = c.rayleigh_phase[l].0 + c.rayleigh_phase[l].1 * nu * nu;
            self.scale * (pr * sr[l] + pa * sa[l] + m[l])
        })
    }

    /// The sun's spectrum at the ground on a plane facing it (direct normal irradiance), with
    /// the visible fraction of its disc, W m⁻² nm⁻¹.
    #[must_use]
    pub fn direct_normal(&self) -> Spectrum {
        let atm = &self.atmosphere;
        let (cols, v) = atm.transmittance.to_sun(R, self.mus);
        let t = atm.medium.transmittance(&cols);
        std::array::from_fn(|l| self.scale * atm.medium.solar[l] * t[l] * v)
    }

    /// Spectral irradiance on the horizontal plane.
    #[must_use]
    pub fn irradiance(&self) -> Irradiance {
        let atm = &self.atmosphere;
        let g = &atm.ground;
        let (is, w) = self.sun_index;
        let diffuse: Spectrum = std::array::from_fn(|l| {
            self.scale * log_lerp(g.diffuse[is][l], g.diffuse[is + 1][l], w)
        });
        let direct_normal = self.direct_normal();
        let direct_horizontal = direct_normal.map(|e| e * self.mus.max(0.0));
        Irradiance {
            global: std::array::from_fn(|l| diffuse[l] + direct_horizontal[l]),
            diffuse,
            direct_horizontal,
            direct_normal,
        }
    }

    /// Spectral global irradiance on a plane with unit normal `normal` (+z up) over a
    /// Lambertian ground of the atmosphere's albedo: the direct beam times the cosine of
    /// incidence, the sky's share ([`Self::sky_irradiance`]) and the ground's reflection of
    /// the global horizontal irradiance seen over the lower half, ρ E_g (1 − n_z) / 2 (a
    /// uniform ground of radiance ρ E_g / π). A zero or non-finite normal gives zero.
    #[must_use]
    pub fn tilted_irradiance(&self, normal: [f64; 3]) -> Spectrum {
        let [e] = self.tilted_irradiances([normal]);
        e
    }

    /// [`Self::tilted_irradiance`] for several planes at once (the sky's radiance evaluated
    /// once for all of them).
    #[must_use]
    pub fn tilted_irradiances<const N: usize>(&self, normals: [[f64; 3]; N]) -> [Spectrum; N] {
        let unit = normals.map(|normal| {
            let n = (normal[0].powi(2) + normal[1].powi(2) + normal[2].powi(2)).sqrt();
            (n > 0.0 && n.is_finite()).then(|| normal.map(|x| x / n))
        });
        let h = self.irradiance();
        let albedo = self.atmosphere.atmosphere.ground_albedo;
        // A bad normal sees nothing (the zero vector: every cosine is zero).
        let sky = self.sky_irradiance(unit.map(|u| u.unwrap_or([0.0; 3])));
        std::array::from_fn(|k| {
            let Some(nrm) = unit[k] else {
                return [0.0; NW];
            };
            let cos_i =
                (nrm[0] * self.sun[0] + nrm[1] * self.sun[1] + nrm[2] * self.sun[2]).max(0.0);
            std::array::from_fn(|l| {
                h.direct_normal[l] * cos_i * f64::from(u8::from(self.mus > 0.0))
                    + albedo * h.global[l] * (1.0 - nrm[2]) / 2.0
                    + sky[k][l]
            })
        })
    }

    /// The sky's share of the spectral irradiance on planes with unit normals `normals` (+z
    /// up), W m⁻² nm⁻¹: ∫ L(ω) (n · ω) dω over the directions above the horizon in front of
    /// each plane, by a midpoint rule over 90 × 180 directions of the upper hemisphere
    /// (uniform in zenith angle and azimuth) of [`Self::spectral_radiance`], evaluated once
    /// for every plane. Without the sun's disc and without the ground.
    #[must_use]
    pub fn sky_irradiance<const N: usize>(&self, normals: [[f64; 3]; N]) -> [Spectrum; N] {
        let mut e = [[0.0; NW]; N];
        let (nt, np) = (90usize, 180usize);
        #[allow(clippy::cast_precision_loss)]
        let (dt, dp) = (0.5 * PI / nt as f64, 2.0 * PI / np as f64);
        for i in 0..nt {
            #[allow(clippy::cast_precision_loss)]
            let theta = (i as f64 + 0.5) * dt;
            for k in 0..np {
                #[allow(clippy::cast_precision_loss)]
                let phi = (k as f64 + 0.5) * dp;
                let d = [
                    theta.sin() * phi.cos(),
                    theta.sin() * phi.sin(),
                    theta.cos(),
                ];
                let mut l = None;
                for (nrm, e) in normals.iter().zip(e.iter_mut()) {
                    let c = d[0] * nrm[0] + d[1] * nrm[1] + d[2] * nrm[2];
                    if c <= 0.0 {
                        continue;
                    }
                    let l = l.get_or_insert_with(|| self.spectral_radiance(d));
                    let w = c * theta.sin() * dt * dp;
                    for (o, x) in e.iter_mut().zip(l.iter()) {
                        *o += w * x;
                    }
                }
            }
        }
        e
    }

    /// Illuminance and colour of the global, diffuse and direct horizontal light.
    #[must_use]
    pub fn daylight(&self) -> Daylight {
        let e = self.irradiance();
        Daylight {
            global: Colorimetry::of(&e.global),
            diffuse: Colorimetry::of(&e.diffuse),
            direct: Colorimetry::of(&e.direct_horizontal),
        }
    }
}

/// The colorimetry of a sky's horizontal light.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Daylight {
    /// Global horizontal.
    pub global: Colorimetry,
    /// Diffuse horizontal.
    pub diffuse: Colorimetry,
    /// Direct horizontal.
    pub direct: Colorimetry,
}
