//! The brute-force check: a Monte Carlo path tracer in the same spherical shell, sharing only
//! the constituents' definitions ([`super::constituents`], [`Atmosphere::coefficients`]) with
//! the tables: densities straight from the US Standard Atmosphere formulae, exact ray-sphere
//! geometry, free paths by delta tracking, next-event estimation towards a point sampled
//! uniformly on the sun's disc with ratio-tracking transmittance, phase-function sampling,
//! a Lambertian ground, Russian roulette. One wavelength bin at a time.
//!
//! It estimates what a viewer on the ground sees: the sky radiance in a direction and the
//! diffuse horizontal irradiance (π times the mean radiance of cosine-distributed directions).

use std::f64::consts::PI;

use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use rayon::prelude::*;

use super::atmosphere::Atmosphere;
use super::constituents::{
    self, EARTH_RADIUS_M as R, TOP_RADIUS_M as RT, air_number_density, ozone_shape,
};
use super::solar::{self, SUN_ANGULAR_RADIUS};

type V3 = [f64; 3];

fn dot(a: V3, b: V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn add(a: V3, b: V3, t: f64) -> V3 {
    [a[0] + t * b[0], a[1] + t * b[1], a[2] + t * b[2]]
}

fn normalise(a: V3) -> V3 {
    let n = dot(a, a).sqrt();
    [a[0] / n, a[1] / n, a[2] / n]
}

/// An orthonormal basis around unit `n`.
fn basis(n: V3) -> (V3, V3) {
    let a = if n[2].abs() < 0.9 {
        [0.0, 0.0, 1.0]
    } else {
        [1.0, 0.0, 0.0]
    };
    let t = normalise([
        a[1] * n[2] - a[2] * n[1],
        a[2] * n[0] - a[0] * n[2],
        a[0] * n[1] - a[1] * n[0],
    ]);
    let b = [
        n[1] * t[2] - n[2] * t[1],
        n[2] * t[0] - n[0] * t[2],
        n[0] * t[1] - n[1] * t[0],
    ];
    (t, b)
}

/// The direction at angle acos(`mu`) from `n` and azimuth `phi` around it.
fn around(n: V3, mu: f64, phi: f64) -> V3 {
    let (t, b) = basis(n);
    let s = (1.0 - mu * mu).max(0.0).sqrt();
    normalise([
        mu * n[0] + s * (phi.cos() * t[0] + phi.sin() * b[0]),
        mu * n[1] + s * (phi.cos() * t[1] + phi.sin() * b[1]),
        mu * n[2] + s * (phi.cos() * t[2] + phi.sin() * b[2]),
    ])
}

/// The nearest positive distance from `p` along unit `d` to the sphere of radius `radius`.
fn to_sphere(p: V3, d: V3, radius: f64) -> Option<f64> {
    let b = dot(p, d);
    let c = dot(p, p) - radius * radius;
    let disc = b * b - c;
    if disc < 0.0 {
        return None;
    }
    let s = disc.sqrt();
    [-b - s, -b + s].into_iter().find(|&t| t > 1e-6)
}

/// The strata of the sun's zenith cosine in [`MonteCarlo::top_outgoing_fraction`].
pub const OUTGOING_STRATA: usize = 16;

/// The path tracer for one wavelength bin of an atmosphere.
#[derive(Debug, Clone)]
pub struct MonteCarlo {
    rayleigh: f64,
    aerosol_ext: f64,
    aerosol_sca: f64,
    ozone: f64,
    ozone_peak: f64,
    scale_height: f64,
    site_elevation_m: f64,
    phase_r: (f64, f64),
    g: f64,
    albedo: f64,
    solar: f64,
    majorant: f64,
    max_events: usize,
}

/// An estimate and its standard error.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Estimate {
    /// The mean.
    pub mean: f64,
    /// Its standard error.
    pub std_error: f64,
}

impl MonteCarlo {
    /// The tracer for bin `bin` (0 to 46) of `atmosphere`.
    #[must_use]
    pub fn new(atmosphere: &Atmosphere, bin: usize) -> Self {
        let c = atmosphere.coefficients();
        let l = bin.min(constituents::N_WAVELENGTHS - 1);
        let ozone_peak = atmosphere.ozone_peak_density();
        let majorant = c.rayleigh[l] * atmosphere.air_density(0.0)
            + c.aerosol_extinction[l]
            + c.ozone[l] * ozone_peak;
        Self {
            rayleigh: c.rayleigh[l],
            aerosol_ext: c.aerosol_extinction[l],
            aerosol_sca: c.aerosol_scattering[l],
            ozone: c.ozone[l],
            ozone_peak,
            scale_height: atmosphere.aerosol_scale_height_m,
            site_elevation_m: atmosphere.site_elevation_m,
            phase_r: c.rayleigh_phase[l],
            g: atmosphere.aerosol_g,
            albedo: atmosphere.ground_albedo,
            solar: solar::extraterrestrial()[l],
            majorant,
            max_events: 200,
        }
    }

    /// The same tracer counting only paths of at most `n` scattering events and ground
    /// reflections (1: single scattering), to check the orders one by one.
    #[must_use]
    pub fn with_max_events(mut self, n: usize) -> Self {
        self.max_events = n.max(1);
        self
    }

    /// (Rayleigh scattering, aerosol scattering, extinction) at `p`, m⁻¹.
    fn coefficients(&self, p: V3) -> (f64, f64, f64) {
        let z = dot(p, p).sqrt() - R;
        let br = self.rayleigh * air_number_density(z + self.site_elevation_m);
        let a = (-z / self.scale_height).exp();
        let bo = self.ozone * self.ozone_peak * ozone_shape(z + self.site_elevation_m);
        (br, self.aerosol_sca * a, br + self.aerosol_ext * a + bo)
    }

    /// Transmittance from `p` along `d` to the top of the atmosphere (0 if the ray hits the
    /// ground), by ratio tracking.
    fn transmittance(&self, p: V3, d: V3, rng: &mut StdRng) -> f64 {
        if dot(p, d) < 0.0 && to_sphere(p, d, R).is_some() {
            return 0.0;
        }
        let Some(end) = to_sphere(p, d, RT) else {
            return 1.0;
        };
        let (mut t, mut tr) = (0.0, 1.0);
        loop {
            t -= (1.0 - rng.random::<f64>()).ln() / self.majorant;
            if t >= end {
                return tr;
            }
            tr *= 1.0 - self.coefficients(add(p, d, t)).2 / self.majorant;
        }
    }

    /// A direction towards a uniformly sampled point of the sun's disc around `sun`.
    fn sun_sample(sun: V3, rng: &mut StdRng) -> V3 {
        let cos_max = SUN_ANGULAR_RADIUS.cos();
        let mu = 1.0 - rng.random::<f64>() * (1.0 - cos_max);
        around(sun, mu, 2.0 * PI * rng.random::<f64>())
    }

    fn rayleigh_phase(&self, nu: f64) -> f64 {
        self.phase_r.0 + self.phase_r.1 * nu * nu
    }

    /// The radiance one path from a viewer at `p0` along `d0` brings back with the sun at each
    /// of `suns`, added to `out` (one walk serves every sun: the walk does not depend on the
    /// sun, only the next-event estimates towards it do).
    fn path(&self, p0: V3, d0: V3, suns: &[V3], rng: &mut StdRng, out: &mut [f64]) {
        let mut p = p0;
        let mut d = d0;
        let mut throughput = 1.0;
        for bounce in 0..self.max_events {
            let ground = if dot(p, d) < 0.0 {
                to_sphere(p, d, R)
            } else {
                None
            };
            let top = to_sphere(p, d, RT).unwrap_or(0.0);
            let end = ground.unwrap_or(top);
            // Delta tracking to the next real collision.
            let mut t = 0.0;
            let collision = loop {
                t -= (1.0 - rng.random::<f64>()).ln() / self.majorant;
                if t >= end {
                    break None;
                }
                let q = add(p, d, t);
                let (br, ba, bt) = self.coefficients(q);
                if rng.random::<f64>() * self.majorant < bt {
                    break Some((q, br, ba, bt));
                }
            };
            match collision {
                Some((q, br, ba, bt)) => {
                    throughput *= (br + ba) / bt;
                    for (sun, radiance) in suns.iter().zip(out.iter_mut()) {
                        let s = Self::sun_sample(*sun, rng);
                        let nu = dot(d, s);
                        let phase = (br * self.rayleigh_phase(nu)
                            + ba * constituents::henyey_greenstein(self.g, nu))
                            / (br + ba);
                        *radiance +=
                            throughput * phase * self.solar * self.transmittance(q, s, rng);
                    }
                    // Scatter: choose the constituent, then the new direction from its phase.
                    let mu = if rng.random::<f64>() * (br + ba) < br {
                        loop {
                            let m = 2.0 * rng.random::<f64>() - 1.0;
                            let (a, b) = self.phase_r;
                            if rng.random::<f64>() * (a + b) < a + b * m * m {
                                break m;
                            }
                        }
                    } else {
                        let g = self.g;
                        if g.abs() < 1e-6 {
                            2.0 * rng.random::<f64>() - 1.0
                        } else {
                            let k = (1.0 - g * g) / (1.0 - g + 2.0 * g * rng.random::<f64>());
                            ((1.0 + g * g - k * k) / (2.0 * g)).clamp(-1.0, 1.0)
                        }
                    };
                    // The light arrives along −d' and leaves along −d: cos = d·d'.
                    d = around(d, mu, 2.0 * PI * rng.random::<f64>());
                    p = q;
                }
                None if ground.is_some() => {
                    let q = add(p, d, end);
                    let n = normalise(q);
                    throughput *= self.albedo;
                    for (sun, radiance) in suns.iter().zip(out.iter_mut()) {
                        let s = Self::sun_sample(*sun, rng);
                        let c = dot(n, s);
                        if c > 0.0 {
                            *radiance += throughput / PI
                                * c
                                * self.solar
                                * self.transmittance(add(q, n, 1e-3), s, rng);
                        }
                    }
                    let mu = rng.random::<f64>().sqrt();
                    d = around(n, mu, 2.0 * PI * rng.random::<f64>());
                    p = add(q, n, 1e-3);
                }
                None => return,
            }
            if bounce >= 4 {
                let survive = throughput.clamp(0.05, 1.0);
                if rng.random::<f64>() >= survive {
                    return;
                }
                throughput /= survive;
            }
        }
    }

    /// `paths` samples of `n` quantities at once (`sample` adds each path's to its slice),
    /// their means and standard errors.
    fn estimates(
        &self,
        paths: usize,
        seed: u64,
        n: usize,
        sample: impl Fn(&mut StdRng, &mut [f64]) + Sync,
    ) -> Vec<Estimate> {
        let chunks = 64;
        let per = paths.div_ceil(chunks);
        let sums: Vec<Vec<(f64, f64)>> = (0..chunks)
            .into_par_iter()
            .map(|c| {
                let mut rng = StdRng::seed_from_u64(seed ^ (c as u64).wrapping_mul(0x9e37_79b9));
                let mut sums = vec![(0.0, 0.0); n];
                let mut x = vec![0.0; n];
                for _ in 0..per {
                    x.fill(0.0);
                    sample(&mut rng, &mut x);
                    for (s, &x) in sums.iter_mut().zip(&x) {
                        s.0 += x;
                        s.1 += x * x;
                    }
                }
                sums
            })
            .collect();
        #[allow(clippy::cast_precision_loss)]
        let count = (per * chunks) as f64;
        (0..n)
            .map(|k| {
                let (s, s2) = sums
                    .iter()
                    .fold((0.0, 0.0), |a, b| (a.0 + b[k].0, a.1 + b[k].1));
                let mean = s / count;
                Estimate {
                    mean,
                    std_error: ((s2 / count - mean * mean).max(0.0) / count).sqrt(),
                }
            })
            .collect()
    }

    fn estimate(
        &self,
        paths: usize,
        seed: u64,
        sample: impl Fn(&mut StdRng, &mut [f64]) + Sync,
    ) -> Estimate {
        self.estimates(paths, seed, 1, sample)[0]
    }

    fn sun(zenith_deg: f64) -> V3 {
        let z = zenith_deg.to_radians();
        [z.sin(), 0.0, z.cos()]
    }

    /// Sky radiance seen from the ground towards `dir` (+z up) with the sun at `zenith_deg`
    /// (azimuth 0, towards +x), W m⁻² sr⁻¹ nm⁻¹.
    #[must_use]
    pub fn radiance(&self, zenith_deg: f64, dir: V3, paths: usize, seed: u64) -> Estimate {
        let (sun, d) = (Self::sun(zenith_deg), normalise(dir));
        self.estimate(paths, seed, |rng, out| {
            self.path([0.0, 0.0, R], d, &[sun], rng, out);
        })
    }

    /// Diffuse horizontal irradiance at the ground with the sun at `zenith_deg`, W m⁻² nm⁻¹.
    #[must_use]
    pub fn diffuse_irradiance(&self, zenith_deg: f64, paths: usize, seed: u64) -> Estimate {
        self.diffuse_irradiances(&[zenith_deg], paths, seed)[0]
    }

    /// Diffuse horizontal irradiance at the ground with the sun at each of `zeniths_deg`,
    /// W m⁻² nm⁻¹, from the same `paths` walks (next-event estimates towards each sun): each
    /// estimate is what [`Self::diffuse_irradiance`] gives for its sun (the same for one sun and
    /// the same seed), at a fraction of the cost of separate runs; their errors are correlated.
    #[must_use]
    pub fn diffuse_irradiances(
        &self,
        zeniths_deg: &[f64],
        paths: usize,
        seed: u64,
    ) -> Vec<Estimate> {
        let suns: Vec<V3> = zeniths_deg.iter().map(|&z| Self::sun(z)).collect();
        self.estimates(paths, seed, suns.len(), |rng, out| {
            let mu = rng.random::<f64>().sqrt();
            let d = around([0.0, 0.0, 1.0], mu, 2.0 * PI * rng.random::<f64>());
            self.path([0.0, 0.0, R], d, &suns, rng, out);
        })
        .into_iter()
        .map(|e| Estimate {
            mean: PI * e.mean,
            std_error: PI * e.std_error,
        })
        .collect()
    }

    /// The sunlight the atmosphere and the ground send back out through the top of the
    /// atmosphere, over the whole sphere, as a fraction of the sunlight entering it (π R_top²
    /// F₀): the outgoing flux ∫∫ L μ dω dA over the top's sphere, its points uniform in area
    /// (the sun's zenith angle there uniform in cosine over [−1, 1], the night side included)
    /// and the directions cosine-distributed downwards. What crosses the limb unscattered is
    /// not in it (a path that escapes never counts the sun's disc).
    /// Stratified in the sun's zenith cosine: [`OUTGOING_STRATA`] equal strata, `paths` in all.
    #[must_use]
    pub fn top_outgoing_fraction(&self, paths: usize, seed: u64) -> Estimate {
        let n = OUTGOING_STRATA;
        let (mut mean, mut variance) = (0.0, 0.0);
        for k in 0..n {
            #[allow(clippy::cast_precision_loss)]
            let (lo, width) = (-1.0 + 2.0 * k as f64 / n as f64, 2.0 / n as f64);
            let e = self.estimate(paths / n, seed.wrapping_add(k as u64), |rng, out| {
                let cos_zenith = lo + width * rng.random::<f64>();
                let sun = around([0.0, 0.0, 1.0], cos_zenith, 0.0);
                let mu = -rng.random::<f64>().sqrt();
                let d = around([0.0, 0.0, 1.0], mu, 2.0 * PI * rng.random::<f64>());
                self.path([0.0, 0.0, RT], d, &[sun], rng, out);
            });
            #[allow(clippy::cast_precision_loss)]
            let share = 1.0 / n as f64;
            mean += share * e.mean;
            variance += (share * e.std_error).powi(2);
        }
        // ∫∫ L μ dω dA = 4π R_top² · π · E[L], over π R_top² F₀.
        let scale = 4.0 * PI / self.solar;
        Estimate {
            mean: scale * mean,
            std_error: scale * variance.sqrt(),
        }
    }

    /// The extraterrestrial irradiance of this bin at 1 AU, W m⁻² nm⁻¹.
    #[must_use]
    pub fn solar_irradiance(&self) -> f64 {
        self.solar
    }
}
