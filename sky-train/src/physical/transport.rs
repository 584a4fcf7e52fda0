//! Light transport by precomputed scattering orders (Bruneton & Neyret 2008; Bruneton 2017,
//! "Precomputed atmospheric scattering: a new implementation"), vectorised over wavelength:
//! every table cell holds the whole spectrum as its innermost, contiguous dimension.
//!
//! 1. Transmittance: the three column densities (air molecules, aerosol, ozone) from (r, μ) to
//!    the top of the atmosphere; T(λ) = exp(−Σ σ_i(λ) N_i) (Bruneton 2017, eqs. for
//!    `ComputeOpticalLengthToTopAtmosphereBoundary`).
//! 2. Single scattering, Rayleigh and aerosol apart with their phase functions applied at
//!    lookup: S(λ) = ∫ T(x→p) β_s(p) V(p) T(p→sun) E_sun dt, V the visible fraction of the sun's
//!    disc (the Earth's shadow with the disc's penumbra).
//! 3. Orders n ≥ 2 on 4-D tables (r, μs, μ, φ): the scattering density
//!    J_n(r, ω) = Σ_c β_c(r) ∫ P_c(ω·ω') [L_{n−1}(r, ω') + T ρ/π E_{n−2}] dω' by a sphere
//!    quadrature on the table's own direction nodes (a matrix product per (r, μs)), then
//!    L_n = ∫ T J_n dt along each ray, and the ground irradiance E_n = ∫ L_n μ dω. The
//!    aerosol's once-scattered light L_1 is divided by the quadrature's reading of its phase
//!    function's integral about the sun (its forward peak is narrower than the nodes near the
//!    zenith: `aerosol_peak_quadrature`).
//!    Orders are added until one more changes the global horizontal illuminance at the ground
//!    by less than [`Resolution::convergence`] at every sun elevation down to −12°.
//! 4. For the viewer on the ground, single scattering and Σ_{n≥2} J_n integrated again on a
//!    finer 3-D table (μs, μ, φ), and the diffuse horizontal irradiance per sun angle by a fine
//!    hemisphere quadrature of that radiance.

use std::f64::consts::PI;

use indicatif::ProgressBar;
use rayon::prelude::*;

use super::atmosphere::Atmosphere;
use super::constituents::{
    self, Coefficients, EARTH_RADIUS_M as R, N_WAVELENGTHS as NW, Spectrum, TOP_ALTITUDE_M,
    henyey_greenstein,
};
use super::grid::{self, SunGrid, split};
use super::solar;

/// The resolution of every table and quadrature: part of the cache's version key.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Resolution {
    /// Transmittance table: radii.
    pub transmittance_r: usize,
    /// Transmittance table: view cosines above the horizon.
    pub transmittance_mu: usize,
    /// Simpson intervals per transmittance ray.
    pub transmittance_steps: usize,
    /// Scattering-order tables: radii.
    pub orders_r: usize,
    /// Scattering-order tables: view cosines per half (below / above the horizon).
    pub orders_mu_half: usize,
    /// Scattering-order tables: relative azimuths in [0, π].
    pub orders_phi: usize,
    /// Scattering-order tables: sun angles.
    pub orders_sun: SunGrid,
    /// Ground tables: view cosines in [0, 1].
    pub ground_mu: usize,
    /// Ground tables: relative azimuths in [0, π].
    pub ground_phi: usize,
    /// Ground tables: sun angles.
    pub ground_sun: SunGrid,
    /// Ray-march samples for single scattering.
    pub single_steps: usize,
    /// Ray-march samples for the orders n ≥ 2.
    pub multiple_steps: usize,
    /// Hemisphere quadrature of the diffuse irradiance: zenith bins (azimuth bins are twice).
    pub irradiance_theta: usize,
    /// The largest number of scattering orders.
    pub max_orders: usize,
    /// Stop when one more order changes the global illuminance by less than this fraction.
    pub convergence: f64,
}

impl Default for Resolution {
    fn default() -> Self {
        Self {
            transmittance_r: 64,
            transmittance_mu: 256,
            transmittance_steps: 500,
            orders_r: 16,
            orders_mu_half: 16,
            orders_phi: 8,
            orders_sun: SunGrid {
                day_step: 5.0,
                dusk_step: 2.0,
                twilight_step: 1.0,
                max_deg: 120.0,
            },
            ground_mu: 48,
            ground_phi: 24,
            ground_sun: SunGrid {
                day_step: 5.0,
                dusk_step: 2.0,
                twilight_step: 0.5,
                max_deg: 110.0,
            },
            single_steps: 64,
            multiple_steps: 32,
            irradiance_theta: 90,
            max_orders: 12,
            convergence: 0.005,
        }
    }
}

/// Column densities along a ray: air molecules (m⁻²), aerosol (m of sea-level-equivalent
/// path), ozone molecules (m⁻²).
pub type Columns = [f64; 3];

/// The atmosphere as the transport sees it: coefficients per wavelength and the density
/// profiles tabulated every [`PROFILE_STEP_M`].
#[derive(Debug, Clone)]
pub struct Medium {
    /// The parameters.
    pub atmosphere: Atmosphere,
    /// The per-wavelength coefficients.
    pub coefficients: Coefficients,
    /// The extraterrestrial spectrum, W m⁻² nm⁻¹.
    pub solar: Spectrum,
    profile: Vec<Columns>,
}

/// Altitude step of the tabulated density profiles, m (linear interpolation: below 10⁻⁵
/// relative error for the 1.2 km aerosol scale height).
pub const PROFILE_STEP_M: f64 = 10.0;

impl Medium {
    /// The medium of `atmosphere`.
    #[must_use]
    pub fn new(atmosphere: &Atmosphere) -> Self {
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let n = (TOP_ALTITUDE_M / PROFILE_STEP_M) as usize + 2;
        let profile = (0..n)
            .map(|k| {
                #[allow(clippy::cast_precision_loss)]
                let z = k as f64 * PROFILE_STEP_M;
                [
                    atmosphere.air_density(z),
                    (-z / atmosphere.aerosol_scale_height_m).exp(),
                    atmosphere.ozone_density(z),
                ]
            })
            .collect();
        Self {
            atmosphere: *atmosphere,
            coefficients: atmosphere.coefficients(),
            solar: solar::extraterrestrial(),
            profile,
        }
    }

    /// Densities at radius `r`: air (m⁻³), aerosol (relative to sea level), ozone (m⁻³).
    #[must_use]
    #[inline]
    pub fn densities(&self, r: f64) -> Columns {
        let f = ((r - R) / PROFILE_STEP_M).max(0.0);
        let (i, w) = split(f, self.profile.len());
        let (a, b) = (self.profile[i], self.profile[i + 1]);
        std::array::from_fn(|c| a[c] + w * (b[c] - a[c]))
    }

    /// Optical depth of bin `l` for `cols`.
    #[must_use]
    #[inline]
    pub fn optical_depth(&self, l: usize, cols: &Columns) -> f64 {
        let c = &self.coefficients;
        c.rayleigh[l] * cols[0] + c.aerosol_extinction[l] * cols[1] + c.ozone[l] * cols[2]
    }

    /// Transmittance per wavelength for `cols`.
    #[must_use]
    pub fn transmittance(&self, cols: &Columns) -> Spectrum {
        std::array::from_fn(|l| (-self.optical_depth(l, cols)).exp())
    }

    /// Column densities from (r, μ) to the top (a ray that does not hit the ground), by
    /// Simpson's rule with `steps` intervals.
    #[must_use]
    pub fn columns_to_top(&self, r: f64, mu: f64, steps: usize) -> Columns {
        let d = grid::distance_to_top(r, mu);
        let steps = steps.max(2) & !1;
        #[allow(clippy::cast_precision_loss)]
        let dt = d / steps as f64;
        let mut sum = [0.0; 3];
        for k in 0..=steps {
            #[allow(clippy::cast_precision_loss)]
            let t = k as f64 * dt;
            let rt = (t * t + 2.0 * r * mu * t + r * r).sqrt();
            let w = if k == 0 || k == steps {
                1.0
            } else if k % 2 == 1 {
                4.0
            } else {
                2.0
            };
            let dens = self.densities(rt);
            for c in 0..3 {
                sum[c] += w * dens[c];
            }
        }
        sum.map(|s| s * dt / 3.0)
    }
}

/// Column densities to the top of the atmosphere on an (r, μ) grid, μ from the horizon up.
#[derive(Debug, Clone)]
pub struct Transmittance {
    /// Radii.
    pub nr: usize,
    /// View cosines.
    pub nmu: usize,
    /// Columns per (r, μ), μ fastest.
    pub columns: Vec<Columns>,
}

impl Transmittance {
    /// Integrates every cell's ray.
    #[must_use]
    pub fn build(medium: &Medium, res: &Resolution) -> Self {
        let (nr, nmu) = (res.transmittance_r, res.transmittance_mu);
        let columns = (0..nr * nmu)
            .into_par_iter()
            .map(|k| {
                let (ir, im) = (k / nmu, k % nmu);
                let r = grid::r_at(unit(ir, nr));
                let mu = grid::mu_at(r, unit(im, nmu), true);
                medium.columns_to_top(r, mu, res.transmittance_steps)
            })
            .collect();
        Self { nr, nmu, columns }
    }

    /// Columns from (r, μ) to the top; μ below the horizon is clamped to it.
    #[must_use]
    #[inline]
    pub fn to_top(&self, r: f64, mu: f64) -> Columns {
        let (ir, wr) = split(grid::r_coord(r) * last(self.nr), self.nr);
        #[allow(clippy::cast_precision_loss)]
        let (im, wm) = split(grid::mu_coord(r, mu, true) * last(self.nmu), self.nmu);
        let at = |i: usize, j: usize| &self.columns[i * self.nmu + j];
        std::array::from_fn(|c| {
            let a = at(ir, im)[c] + wm * (at(ir, im + 1)[c] - at(ir, im)[c]);
            let b = at(ir + 1, im)[c] + wm * (at(ir + 1, im + 1)[c] - at(ir + 1, im)[c]);
            a + wr * (b - a)
        })
    }

    /// Columns from (r, μ) to the ground along a ray that hits it, as the difference of two
    /// rays to the top seen from the ground point and from (r, μ), both reversed.
    #[must_use]
    pub fn to_ground(&self, r: f64, mu: f64) -> Columns {
        let d = grid::distance_to_ground(r, mu);
        let (rg, mug, _) = grid::along(r, mu, 0.0, 0.0, d);
        let a = self.to_top(rg.max(R), -mug);
        let b = self.to_top(r, -mu);
        std::array::from_fn(|c| (a[c] - b[c]).max(0.0))
    }

    /// The columns to the sun from (r, μs) and the visible fraction of its disc (0 in the
    /// Earth's shadow; the disc's angular radius gives the penumbra).
    #[must_use]
    #[inline]
    pub fn to_sun(&self, r: f64, mus: f64) -> (Columns, f64) {
        let h = grid::mu_horizon(r);
        let alpha = mus.clamp(-1.0, 1.0).asin() + (-h).asin();
        let v = solar::disc_fraction_above(alpha);
        if v <= 0.0 {
            return ([0.0; 3], 0.0);
        }
        (self.to_top(r, mus.max(h)), v)
    }
}

#[allow(clippy::cast_precision_loss)]
fn unit(i: usize, n: usize) -> f64 {
    if n < 2 {
        0.0
    } else {
        i as f64 / (n - 1) as f64
    }
}

#[allow(clippy::cast_precision_loss)]
fn last(n: usize) -> f64 {
    n.saturating_sub(1) as f64
}

/// A 4-D spectral table over (r, μs, μ, φ), μ in two halves (lower: rays that hit the ground,
/// node 0 at the nadir; upper: node `half` at the horizon), f32, wavelength innermost.
#[derive(Debug, Clone)]
pub struct Table4 {
    /// Radii.
    pub nr: usize,
    /// Sun angles.
    pub sun: SunGrid,
    /// View cosines per half.
    pub half: usize,
    /// Relative azimuths.
    pub nphi: usize,
    /// The values.
    pub data: Vec<f32>,
}

/// A table node's geometry: r, μs, μ, φ, and whether μ is in the upper half.
#[derive(Debug, Clone, Copy)]
pub struct Node {
    /// Radius, m.
    pub r: f64,
    /// Sun cosine.
    pub mus: f64,
    /// View cosine.
    pub mu: f64,
    /// Relative azimuth, rad.
    pub phi: f64,
    /// Whether the view ray reaches the top of the atmosphere (else the ground).
    pub upper: bool,
}

impl Table4 {
    fn zeros(res: &Resolution) -> Self {
        let mut t = Self {
            nr: res.orders_r,
            sun: res.orders_sun,
            half: res.orders_mu_half,
            nphi: res.orders_phi,
            data: Vec::new(),
        };
        t.data = vec![0.0; t.cells() * NW];
        t
    }

    fn nmu(&self) -> usize {
        2 * self.half
    }

    /// The number of cells.
    #[must_use]
    pub fn cells(&self) -> usize {
        self.nr * self.sun.len() * self.nmu() * self.nphi
    }

    /// Directions per (r, μs) slab.
    fn directions(&self) -> usize {
        self.nmu() * self.nphi
    }

    /// The geometry of cell `k`.
    #[must_use]
    pub fn node(&self, k: usize) -> Node {
        let ip = k % self.nphi;
        let im = (k / self.nphi) % self.nmu();
        let is = (k / self.directions()) % self.sun.len();
        let ir = k / (self.directions() * self.sun.len());
        let r = grid::r_at(unit(ir, self.nr));
        let (mu, upper) = self.mu_node(r, im);
        #[allow(clippy::cast_precision_loss)]
        Node {
            r,
            mus: self.sun.mus(is),
            mu,
            phi: PI * unit(ip, self.nphi),
            upper,
        }
    }

    fn mu_node(&self, r: f64, im: usize) -> (f64, bool) {
        if im < self.half {
            (grid::mu_at(r, 1.0 - unit(im, self.half), false), false)
        } else {
            (grid::mu_at(r, unit(im - self.half, self.half), true), true)
        }
    }

    /// Adds `weight` times the table at (r, μ, μs, φ) (multilinear, within μ's half) to `out`.
    #[inline]
    #[allow(clippy::too_many_arguments)]
    pub fn lookup_add(
        &self,
        r: f64,
        mu: f64,
        mus: f64,
        phi: f64,
        upper: bool,
        weight: f64,
        out: &mut Spectrum,
    ) {
        let (ir, wr) = split(grid::r_coord(r) * last(self.nr), self.nr);
        let (is, ws) = split(self.sun.index_of_mus(mus), self.sun.len());
        let x = grid::mu_coord(r, mu, upper);
        let (im, wm) = if upper {
            let (i, w) = split(x * last(self.half), self.half);
            (i + self.half, w)
        } else {
            split((1.0 - x) * last(self.half), self.half)
        };
        let (ip, wp) = split(phi / PI * last(self.nphi), self.nphi);
        let ns = self.sun.len();
        let nmu = self.nmu();
        for (dr, fr) in [(0, 1.0 - wr), (1, wr)] {
            for (ds, fs) in [(0, 1.0 - ws), (1, ws)] {
                for (dm, fm) in [(0, 1.0 - wm), (1, wm)] {
                    for (dp, fp) in [(0, 1.0 - wp), (1, wp)] {
                        let w = weight * fr * fs * fm * fp;
                        if w == 0.0 {
                            continue;
                        }
                        let cell =
                            (((ir + dr) * ns + is + ds) * nmu + im + dm) * self.nphi + ip + dp;
                        let v = &self.data[cell * NW..(cell + 1) * NW];
                        for (o, x) in out.iter_mut().zip(v) {
                            *o += w * f64::from(*x);
                        }
                    }
                }
            }
        }
    }
}

/// A 3-D spectral table for the viewer on the ground over (μs, μ, φ), μ = x² with x uniform in
/// [0, 1], f32, wavelength innermost.
#[derive(Debug, Clone, PartialEq)]
pub struct Table3 {
    /// Sun angles.
    pub sun: SunGrid,
    /// View cosines.
    pub nmu: usize,
    /// Relative azimuths.
    pub nphi: usize,
    /// The values.
    pub data: Vec<f32>,
}

impl Table3 {
    /// The number of cells.
    #[must_use]
    pub fn cells(&self) -> usize {
        self.sun.len() * self.nmu * self.nphi
    }

    /// (μs, μ, φ) of cell `k`.
    #[must_use]
    pub fn node(&self, k: usize) -> (f64, f64, f64) {
        let ip = k % self.nphi;
        let im = (k / self.nphi) % self.nmu;
        let is = k / (self.nphi * self.nmu);
        let x = unit(im, self.nmu);
        (self.sun.mus(is), x * x, PI * unit(ip, self.nphi))
    }

    /// The spectrum of cell (sun node, μ node, φ node).
    #[must_use]
    #[inline]
    pub fn cell(&self, is: usize, im: usize, ip: usize) -> &[f32] {
        let k = (is * self.nmu + im) * self.nphi + ip;
        &self.data[k * NW..(k + 1) * NW]
    }

    /// The fractional (μ, φ) node indices of a direction.
    #[must_use]
    #[inline]
    pub fn view_index(&self, mu: f64, phi: f64) -> ((usize, f64), (usize, f64)) {
        (
            split(mu.clamp(0.0, 1.0).sqrt() * last(self.nmu), self.nmu),
            split(phi / PI * last(self.nphi), self.nphi),
        )
    }

    /// Adds `weight` times the bilinear (μ, φ) interpolation at sun node `is` to `out`.
    #[inline]
    pub fn lookup_add(&self, is: usize, mu: f64, phi: f64, weight: f64, out: &mut Spectrum) {
        let ((im, wm), (ip, wp)) = self.view_index(mu, phi);
        for (dm, fm) in [(0, 1.0 - wm), (1, wm)] {
            for (dp, fp) in [(0, 1.0 - wp), (1, wp)] {
                let w = weight * fm * fp;
                for (o, x) in out.iter_mut().zip(self.cell(is, im + dm, ip + dp)) {
                    *o += w * f64::from(*x);
                }
            }
        }
    }
}

/// Ray-march sample distances t_k = d u_k², u_k = k / n (dense near the viewer, where the
/// aerosol's 1.2 km scale height is), their quadrature weights, and the distance from the
/// sample before. The weights are Simpson's rule in u on ∫ f(t) dt = ∫ f(d u²) 2 d u du: the
/// trapezoid rule in t on the same samples overestimated the orders n ≥ 2 by about 1 % (the
/// integrand, exponential in altitude, is convex; found with the Monte Carlo, docs/daylight.md).
/// `n` is rounded up to even.
fn march(d: f64, n: usize) -> impl Iterator<Item = (f64, f64, f64)> {
    let n = (n.max(2) + 1) & !1;
    #[allow(clippy::cast_precision_loss)]
    let u = move |k: usize| k as f64 / n as f64;
    let t = move |k: usize| d * u(k) * u(k);
    #[allow(clippy::cast_precision_loss)]
    let h = 1.0 / n as f64;
    (0..=n).map(move |k| {
        let simpson = if k == 0 || k == n {
            1.0
        } else if k % 2 == 1 {
            4.0
        } else {
            2.0
        };
        let prev = if k == 0 { 0.0 } else { t(k) - t(k - 1) };
        (t(k), simpson * h / 3.0 * 2.0 * d * u(k), prev)
    })
}

/// A point of a view ray's march: radius, μ and μs there, the densities, the column
/// densities from the viewer, and the sample's quadrature weight (m).
struct Sample {
    r: f64,
    mu: f64,
    mus: f64,
    densities: Columns,
    view: Columns,
    weight: f64,
}

/// A view ray from radius `r` along `mu` with the sun at `mus` and `nu`, to the top of the
/// atmosphere when `upper`, else to the ground.
#[derive(Debug, Clone, Copy)]
pub struct Ray {
    /// Radius of the viewer, m.
    pub r: f64,
    /// Cosine of the view's zenith angle.
    pub mu: f64,
    /// Cosine of the sun's zenith angle.
    pub mus: f64,
    /// Cosine between the view and the sun.
    pub nu: f64,
    /// Whether the ray reaches the top of the atmosphere (else the ground).
    pub upper: bool,
}

impl Ray {
    fn of(n: &Node) -> Self {
        Self {
            r: n.r,
            mu: n.mu,
            mus: n.mus,
            nu: grid::nu_of(n.mu, n.mus, n.phi),
            upper: n.upper,
        }
    }
}

/// Marches `ray`, calling `f` at each sample of positive weight.
fn march_ray(medium: &Medium, ray: &Ray, steps: usize, mut f: impl FnMut(&Sample)) {
    let Ray {
        r,
        mu,
        mus,
        nu,
        upper,
    } = *ray;
    let d = if upper {
        grid::distance_to_top(r, mu)
    } else {
        grid::distance_to_ground(r, mu)
    };
    if d <= 0.0 {
        return;
    }
    let mut view = [0.0; 3];
    let mut prev = medium.densities(r);
    for (t, weight, dt) in march(d, steps) {
        let (rt, mut_, must) = grid::along(r, mu, mus, nu, t);
        let dens = medium.densities(rt);
        for k in 0..3 {
            view[k] += 0.5 * (dens[k] + prev[k]) * dt;
        }
        prev = dens;
        if weight > 0.0 {
            f(&Sample {
                r: rt,
                mu: mut_,
                mus: must,
                densities: dens,
                view,
                weight,
            });
        }
    }
}

/// Single scattering towards the viewer of `ray`: the Rayleigh and aerosol spectra without
/// their phase functions, W m⁻² sr⁻¹ nm⁻¹ per unit phase (sr⁻¹).
#[must_use]
pub fn single_scattering(
    medium: &Medium,
    trans: &Transmittance,
    ray: &Ray,
    steps: usize,
) -> (Spectrum, Spectrum) {
    let (mut sr, mut sa) = ([0.0; NW], [0.0; NW]);
    let c = &medium.coefficients;
    march_ray(medium, ray, steps, |p| {
        let (sun, v) = trans.to_sun(p.r, p.mus);
        if v <= 0.0 {
            return;
        }
        let cols: Columns = std::array::from_fn(|k| p.view[k] + sun[k]);
        for l in 0..NW {
            let tw = p.weight * v * (-medium.optical_depth(l, &cols)).exp();
            sr[l] += tw * p.densities[0] * c.rayleigh[l];
            sa[l] += tw * p.densities[1] * c.aerosol_scattering[l];
        }
    });
    for l in 0..NW {
        sr[l] *= medium.solar[l];
        sa[l] *= medium.solar[l];
    }
    (sr, sa)
}

/// Radiance ∫ T J dt towards the viewer of `ray`, J from `density`,
/// which holds J / β_s (the phase-weighted mean radiance, smooth in altitude where J itself
/// follows the 1.2 km aerosol scale height between radius nodes kilometres apart: linear
/// interpolation of J overestimated the aerosol's multiple scattering by 5-9 %).
#[must_use]
pub fn scattered(medium: &Medium, density: &Table4, ray: &Ray, steps: usize) -> Spectrum {
    let mut out = [0.0; NW];
    let mut j = [0.0; NW];
    let c = &medium.coefficients;
    march_ray(medium, ray, steps, |p| {
        j.fill(0.0);
        let phi = grid::phi_of(p.mu, p.mus, ray.nu);
        density.lookup_add(p.r, p.mu, p.mus, phi, ray.upper, 1.0, &mut j);
        for l in 0..NW {
            let bs = p.densities[0] * c.rayleigh[l] + p.densities[1] * c.aerosol_scattering[l];
            out[l] += p.weight * (-medium.optical_depth(l, &p.view)).exp() * bs * j[l];
        }
    });
    out
}

/// What each scattering order added: the largest change of the global horizontal illuminance
/// at the ground over sun elevations down to −12°, and the change at −12° itself.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OrderReport {
    /// The order (2 = twice scattered, ...).
    pub order: usize,
    /// max over sun elevations ≥ −12° of ΔE_v / E_v (E_v the global illuminance through this
    /// order).
    pub max_change: f64,
    /// The sun elevation of that maximum, degrees.
    pub at_elevation_deg: f64,
    /// ΔE_v / E_v at −12°.
    pub change_at_minus_12: f64,
}

/// The precomputed tables for the viewer on the ground: what [`super::PhysicalAtmosphere`] is
/// made of and what the cache stores.
#[derive(Debug, Clone)]
pub struct GroundTables {
    /// Rayleigh single scattering without its phase function.
    pub rayleigh: Table3,
    /// Aerosol single scattering without its phase function.
    pub aerosol: Table3,
    /// Orders n ≥ 2, phase functions included.
    pub multiple: Table3,
    /// Diffuse horizontal irradiance per ground sun node, W m⁻² nm⁻¹.
    pub diffuse: Vec<Spectrum>,
    /// What each order added.
    pub orders: Vec<OrderReport>,
}

/// Names the stage of the precomputation on the progress bar.
fn stage(bar: &ProgressBar, msg: &str) {
    bar.set_message(msg.to_owned());
}

/// The direct horizontal irradiance at the ground with the sun at μs, W m⁻² nm⁻¹ (at 1 AU).
#[must_use]
pub fn direct_horizontal(medium: &Medium, trans: &Transmittance, mus: f64) -> Spectrum {
    let (cols, v) = trans.to_sun(R, mus);
    let t = medium.transmittance(&cols);
    std::array::from_fn(|l| medium.solar[l] * t[l] * v * mus.max(0.0))
}

/// The sphere quadrature on a table's direction nodes at radius `r`: each node's (μ, φ) and
/// its weight, the trapezoid rule in μ within each half times the trapezoid rule in φ over
/// [0, π]; a node stands for the two directions at ±φ (the weights sum to 2π, 4π over ±φ).
struct SphereNodes {
    /// (μ, φ) per direction node, φ fastest.
    dirs: Vec<(f64, f64)>,
    /// The weight of each node (of each of its two directions ±φ).
    weights: Vec<f64>,
}

impl SphereNodes {
    fn of(table: &Table4, r: f64) -> Self {
        let dirs: Vec<(f64, f64)> = (0..table.nmu())
            .flat_map(|im| {
                let mu = table.mu_node(r, im).0;
                (0..table.nphi).map(move |ip| (mu, PI * unit(ip, table.nphi)))
            })
            .collect();
        let lower: Vec<f64> = (0..table.half).map(|im| table.mu_node(r, im).0).collect();
        let upper: Vec<f64> = (table.half..table.nmu())
            .map(|im| table.mu_node(r, im).0)
            .collect();
        let mut wmu = grid::trapezoid_weights(&lower);
        wmu.extend(grid::trapezoid_weights(&upper));
        let phis: Vec<f64> = (0..table.nphi)
            .map(|ip| PI * unit(ip, table.nphi))
            .collect();
        let wphi = grid::trapezoid_weights(&phis);
        let weights = (0..dirs.len())
            .map(|i| wmu[i / table.nphi] * wphi[i % table.nphi])
            .collect();
        Self { dirs, weights }
    }
}

/// The sphere quadrature's reading of the aerosol phase function's integral about the sun,
/// Σ_i w_i (P(ν_i⁺) + P(ν_i⁻)) over the direction nodes at `nodes`' radius with the sun at
/// `mus` (ν_i± the cosine between the sun, at azimuth 0, and the node at ±φ: equal), which is
/// ∫ P dω = 1 exactly. The once-scattered light the orders n ≥ 2 gather carries the aerosol's
/// forward peak about the sun (Henyey-Greenstein g 0.703: half its peak value 16° from it),
/// narrower than the nodes near the zenith (μ = 1, 0.87, 0.75 at the ground: 0°, 29°, 41°), so
/// the quadrature reads it 24 % high with the sun overhead, 2 % low at 25°, within 1 % from 30°
/// to 60° and up to 2 % high near the horizon, where the azimuth nodes are 26° apart (at the
/// default resolution and the ground; docs/daylight.md). Dividing the tables'
/// aerosol single scattering by this reading makes the gathered once-scattered aerosol light
/// carry its true energy: the phase-function renormalisation of discrete-ordinate codes, here
/// for the gathered light's peak, as the kernels' rows already are for the scattering phase.
fn aerosol_peak_quadrature(nodes: &SphereNodes, mus: f64, g: f64) -> f64 {
    nodes
        .dirs
        .iter()
        .zip(&nodes.weights)
        .map(|(&(mu, phi), w)| 2.0 * w * henyey_greenstein(g, grid::nu_of(mu, mus, phi)))
        .sum()
}

/// Kernel matrices of the sphere quadrature at radius `r` on the table's direction nodes:
/// 2·D rows (Rayleigh then aerosol) by D columns, K[o][i] = w_i (P(o·i⁺) + P(o·i⁻)) with i±
/// the node at ±φ, each row normalised to sum 1 (the discrete operator conserves energy).
fn kernels(table: &Table4, nodes: &SphereNodes, rayleigh: (f64, f64), g: f64) -> Vec<f32> {
    let d = table.directions();
    let dirs = &nodes.dirs;
    let mut k = vec![0.0f32; 2 * d * d];
    for (o, &(mo, po)) in dirs.iter().enumerate() {
        let so = (1.0 - mo * mo).max(0.0).sqrt();
        let (mut sum_r, mut sum_a) = (0.0, 0.0);
        let mut row_r = vec![0.0; d];
        let mut row_a = vec![0.0; d];
        for (i, (&(mi, pi_), &w)) in dirs.iter().zip(&nodes.weights).enumerate() {
            let si = (1.0 - mi * mi).max(0.0).sqrt();
            let (mut pr, mut pa) = (0.0, 0.0);
            for sign in [1.0, -1.0] {
                let c = (mo * mi + so * si * (po - sign * pi_).cos()).clamp(-1.0, 1.0);
                pr += rayleigh.0 + rayleigh.1 * c * c;
                pa += henyey_greenstein(g, c);
            }
            row_r[i] = w * pr;
            row_a[i] = w * pa;
            sum_r += w * pr;
            sum_a += w * pa;
        }
        for i in 0..d {
            #[allow(clippy::cast_possible_truncation)]
            {
                k[o * d + i] = (row_r[i] / sum_r) as f32;
                k[(d + o) * d + i] = (row_a[i] / sum_a) as f32;
            }
        }
    }
    k
}

/// `c = a · b` for row-major a (m × k), b (k × n), c (m × n), f32.
fn gemm(m: usize, k: usize, n: usize, a: &[f32], b: &[f32], c: &mut [f32]) {
    assert!(a.len() >= m * k && b.len() >= k * n && c.len() >= m * n);
    let s = |x: usize| isize::try_from(x).unwrap_or(isize::MAX);
    // SAFETY: the three buffers hold at least m·k, k·n and m·n values (checked above), read and
    // written with row strides k, n, n and column stride 1; c is a distinct allocation.
    #[allow(unsafe_code)]
    unsafe {
        matrixmultiply::sgemm(
            m,
            k,
            n,
            1.0,
            a.as_ptr(),
            s(k),
            1,
            b.as_ptr(),
            s(n),
            1,
            0.0,
            c.as_mut_ptr(),
            s(n),
            1,
        );
    }
}

/// Irradiance at the ground per sun node of the order tables from the r = R slab of `l`:
/// E(μs) = ∫ L μ dω over the upper half's nodes.
fn ground_irradiance(l: &Table4) -> Vec<Spectrum> {
    let upper: Vec<f64> = (l.half..l.nmu()).map(|im| l.mu_node(R, im).0).collect();
    let wmu = grid::trapezoid_weights(&upper);
    let phis: Vec<f64> = (0..l.nphi).map(|ip| PI * unit(ip, l.nphi)).collect();
    let wphi = grid::trapezoid_weights(&phis);
    (0..l.sun.len())
        .map(|is| {
            let mut e = [0.0; NW];
            for (j, &mu) in upper.iter().enumerate() {
                for (ip, &wp) in wphi.iter().enumerate() {
                    let cell = (is * l.nmu() + l.half + j) * l.nphi + ip;
                    let w = 2.0 * wmu[j] * wp * mu;
                    for (o, x) in e.iter_mut().zip(&l.data[cell * NW..(cell + 1) * NW]) {
                        *o += w * f64::from(*x);
                    }
                }
            }
            e
        })
        .collect()
}

/// Interpolates a per-sun-node spectrum table at μs, log-linearly in the sun angle.
#[must_use]
pub fn sun_lerp(sun: &SunGrid, table: &[Spectrum], mus: f64) -> Spectrum {
    let (i, w) = split(sun.index_of_mus(mus), sun.len());
    std::array::from_fn(|l| log_lerp(table[i][l], table[i + 1][l], w))
}

/// exp((1 − w) ln a + w ln b) for positive a, b; linear where either is 0.
#[must_use]
#[inline]
pub fn log_lerp(a: f64, b: f64, w: f64) -> f64 {
    if a > 0.0 && b > 0.0 {
        a * (b / a).powf(w)
    } else {
        a + w * (b - a)
    }
}

fn photopic(e: &Spectrum) -> f64 {
    super::photometry::channels(e)[1]
}

/// Runs the whole precomputation for `medium`, reporting progress on `bar` (one unit per
/// table cell computed).
#[must_use]
#[allow(clippy::too_many_lines)]
pub fn precompute(
    medium: &Medium,
    res: &Resolution,
    bar: &ProgressBar,
) -> (Transmittance, GroundTables) {
    stage(bar, "transmittance");
    let trans = Transmittance::build(medium, res);
    let albedo = medium.atmosphere.ground_albedo;
    let g = medium.atmosphere.aerosol_g;
    let c = &medium.coefficients;
    let phase = |nu: f64| -> Spectrum {
        std::array::from_fn(|l| c.rayleigh_phase[l].0 + c.rayleigh_phase[l].1 * nu * nu)
    };

    // Order 1 on the 4-D tables.
    let mut l_table = Table4::zeros(res);
    let cells = l_table.cells();
    let ground = Table3 {
        sun: res.ground_sun,
        nmu: res.ground_mu,
        nphi: res.ground_phi,
        data: Vec::new(),
    };
    let ground_cells = ground.cells();
    let orders_estimate = 4;
    bar.set_length((cells * (1 + 2 * orders_estimate) + 2 * ground_cells) as u64);
    stage(bar, "single scattering");
    // The sphere quadrature on the direction nodes per radius, and its reading of the aerosol
    // phase function about the sun per (r, μs) slab, which the aerosol's once-scattered light
    // is divided by (`aerosol_peak_quadrature`).
    let nodes: Vec<SphereNodes> = (0..l_table.nr)
        .map(|ir| SphereNodes::of(&l_table, grid::r_at(unit(ir, l_table.nr))))
        .collect();
    let dirs = l_table.directions();
    let ns = l_table.sun.len();
    let peak: Vec<f64> = (0..l_table.nr * ns)
        .map(|slab| aerosol_peak_quadrature(&nodes[slab / ns], l_table.sun.mus(slab % ns), g))
        .collect();
    let l1: Vec<f32> = (0..cells)
        .into_par_iter()
        .flat_map_iter(|k| {
            let ray = Ray::of(&l_table.node(k));
            let (sr, sa) = single_scattering(medium, &trans, &ray, res.single_steps);
            let pr = phase(ray.nu);
            let pa = henyey_greenstein(g, ray.nu) / peak[k / dirs];
            if k % 4096 == 0 {
                bar.inc(4096);
            }
            #[allow(clippy::cast_possible_truncation)]
            (0..NW).map(move |l| (pr[l] * sr[l] + pa * sa[l]) as f32)
        })
        .collect();
    l_table.data = l1;

    // Direct irradiance at the ground per order sun node (E_0), and the ground's reflection.
    let sun4 = res.orders_sun;
    let e_direct: Vec<Spectrum> = (0..sun4.len())
        .map(|is| direct_horizontal(medium, &trans, sun4.mus(is)))
        .collect();
    let mut e_prev = e_direct.clone(); // E_{n−2} for J_n
    let mut e_last = ground_irradiance(&l_table); // E_{n−1}
    let mut global: Vec<f64> = (0..sun4.len())
        .map(|is| photopic(&e_direct[is]) + photopic(&e_last[is]))
        .collect();

    // Transmittance from each lower-half node to the ground, per (r, μ node).
    let nmu = l_table.nmu();
    let to_ground: Vec<Spectrum> = (0..l_table.nr * nmu)
        .map(|k| {
            let (ir, im) = (k / nmu, k % nmu);
            let r = grid::r_at(unit(ir, l_table.nr));
            let (mu, upper) = l_table.mu_node(r, im);
            if upper {
                [0.0; NW]
            } else {
                medium.transmittance(&trans.to_ground(r, mu))
            }
        })
        .collect();
    let rayleigh_550 = constituents::rayleigh_phase_550();
    let kernel: Vec<Vec<f32>> = nodes
        .iter()
        .map(|n| kernels(&l_table, n, rayleigh_550, g))
        .collect();

    let mut j_total = Table4::zeros(res);
    let mut orders = Vec::new();
    for order in 2..=res.max_orders.max(2) {
        stage(bar, &format!("scattering order {order}"));
        // J_n per (r, μs) slab: K · (L_{n−1} + T ρ/π E_{n−2}).
        let mut j_table = Table4::zeros(res);
        j_table
            .data
            .par_chunks_mut(dirs * NW)
            .enumerate()
            .for_each(|(slab, out)| {
                let (ir, is) = (slab / ns, slab % ns);
                let r = grid::r_at(unit(ir, l_table.nr));
                let mus = sun4.mus(is);
                let base = slab * dirs * NW;
                let mut lin: Vec<f32> = l_table.data[base..base + dirs * NW].to_vec();
                for im in 0..l_table.half {
                    let (mu, _) = l_table.mu_node(r, im);
                    let d = grid::distance_to_ground(r, mu);
                    let tg = &to_ground[ir * nmu + im];
                    for ip in 0..l_table.nphi {
                        let nu = grid::nu_of(mu, mus, PI * unit(ip, l_table.nphi));
                        let mus_g = ((r * mus + d * nu) / R).clamp(-1.0, 1.0);
                        let e = sun_lerp(&sun4, &e_prev, mus_g);
                        let cell = (im * l_table.nphi + ip) * NW;
                        for l in 0..NW {
                            #[allow(clippy::cast_possible_truncation)]
                            {
                                lin[cell + l] += (tg[l] * albedo / PI * e[l]) as f32;
                            }
                        }
                    }
                }
                let mut prod = vec![0.0f32; 2 * dirs * NW];
                gemm(2 * dirs, dirs, NW, &kernel[ir], &lin, &mut prod);
                // Stored divided by the scattering coefficient β_s(r, λ) (see `scattered`).
                let dens = medium.densities(r);
                for o in 0..dirs {
                    for l in 0..NW {
                        let (br, ba) = (dens[0] * c.rayleigh[l], dens[1] * c.aerosol_scattering[l]);
                        let jr = f64::from(prod[o * NW + l]) * br;
                        let ja = f64::from(prod[(dirs + o) * NW + l]) * ba;
                        let bs = br + ba;
                        #[allow(clippy::cast_possible_truncation)]
                        {
                            out[o * NW + l] = if bs > 0.0 {
                                ((jr + ja) / bs) as f32
                            } else {
                                0.0
                            };
                        }
                    }
                }
            });
        bar.inc(cells as u64);
        // L_n by ray integrals of J_n.
        let ln: Vec<f32> = (0..cells)
            .into_par_iter()
            .flat_map_iter(|k| {
                let ray = Ray::of(&j_table.node(k));
                let s = scattered(medium, &j_table, &ray, res.multiple_steps);
                if k % 4096 == 0 {
                    bar.inc(4096);
                }
                #[allow(clippy::cast_possible_truncation)]
                s.into_iter().map(|x| x as f32)
            })
            .collect();
        for (t, x) in j_total.data.iter_mut().zip(&j_table.data) {
            *t += x;
        }
        l_table.data = ln;
        let e_n = ground_irradiance(&l_table);
        // Convergence: this order's share of the global illuminance.
        let mut report = OrderReport {
            order,
            max_change: 0.0,
            at_elevation_deg: 90.0,
            change_at_minus_12: 0.0,
        };
        for is in 0..ns {
            global[is] += photopic(&e_n[is]);
            let elevation = 90.0 - sun4.angle_deg(is);
            if elevation < -12.0 - 1e-9 {
                continue;
            }
            let change = if global[is] > 0.0 {
                photopic(&e_n[is]) / global[is]
            } else {
                0.0
            };
            if change > report.max_change {
                report.max_change = change;
                report.at_elevation_deg = elevation;
            }
            if (elevation + 12.0).abs() < 1e-9 {
                report.change_at_minus_12 = change;
            }
        }
        orders.push(report);
        e_prev = std::mem::replace(&mut e_last, e_n);
        if report.max_change < res.convergence {
            break;
        }
    }

    // The viewer on the ground: finer tables.
    stage(bar, "ground tables");
    let single: Vec<(Spectrum, Spectrum, Spectrum)> = (0..ground_cells)
        .into_par_iter()
        .map(|k| {
            let (mus, mu, phi) = ground.node(k);
            let ray = Ray {
                r: R,
                mu,
                mus,
                nu: grid::nu_of(mu, mus, phi),
                upper: true,
            };
            let (sr, sa) = single_scattering(medium, &trans, &ray, res.single_steps);
            let m = scattered(medium, &j_total, &ray, res.multiple_steps);
            if k % 1024 == 0 {
                bar.inc(2048);
            }
            (sr, sa, m)
        })
        .collect();
    #[allow(clippy::cast_possible_truncation)]
    let take = |f: fn(&(Spectrum, Spectrum, Spectrum)) -> &Spectrum| Table3 {
        data: single
            .iter()
            .flat_map(|s| f(s).iter().map(|&x| x as f32))
            .collect(),
        ..ground.clone()
    };
    let rayleigh = take(|s| &s.0);
    let aerosol = take(|s| &s.1);
    let multiple = take(|s| &s.2);
    stage(bar, "diffuse irradiance");
    let diffuse = (0..ground.sun.len())
        .into_par_iter()
        .map(|is| {
            diffuse_at_node(
                &rayleigh,
                &aerosol,
                &multiple,
                c,
                g,
                is,
                res.irradiance_theta,
            )
        })
        .collect();
    bar.finish_and_clear();
    (
        trans,
        GroundTables {
            rayleigh,
            aerosol,
            multiple,
            diffuse,
            orders,
        },
    )
}

/// Diffuse horizontal irradiance at ground sun node `is`: the midpoint rule over `n` zenith
/// and 2n azimuth bins of the interpolated tables with the phase functions evaluated exactly.
fn diffuse_at_node(
    rayleigh: &Table3,
    aerosol: &Table3,
    multiple: &Table3,
    c: &Coefficients,
    g: f64,
    is: usize,
    n: usize,
) -> Spectrum {
    let mus = rayleigh.sun.mus(is);
    let mut e = [0.0; NW];
    #[allow(clippy::cast_precision_loss)]
    let (dt, dp) = (0.5 * PI / n as f64, PI / (2 * n) as f64);
    let (mut sr, mut sa, mut m) = ([0.0; NW], [0.0; NW], [0.0; NW]);
    for i in 0..n {
        #[allow(clippy::cast_precision_loss)]
        let theta = (i as f64 + 0.5) * dt;
        let mu = theta.cos();
        let w_theta = mu * theta.sin() * dt * dp * 2.0;
        for k in 0..2 * n {
            #[allow(clippy::cast_precision_loss)]
            let phi = (k as f64 + 0.5) * dp;
            let nu = grid::nu_of(mu, mus, phi);
            sr.fill(0.0);
            sa.fill(0.0);
            m.fill(0.0);
            rayleigh.lookup_add(is, mu, phi, 1.0, &mut sr);
            aerosol.lookup_add(is, mu, phi, 1.0, &mut sa);
            multiple.lookup_add(is, mu, phi, 1.0, &mut m);
            let pa = henyey_greenstein(g, nu);
            for l in 0..NW {
                let pr = c.rayleigh_phase[l].0 + c.rayleigh_phase[l].1 * nu * nu;
                e[l] += w_theta * (pr * sr[l] + pa * sa[l] + m[l]);
            }
        }
    }
    e
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sphere quadrature's reading of the aerosol phase function's integral about the sun
    /// is a discretisation error: it tends to ∫ P dω = 1 as the direction nodes get finer
    /// (within 0.2 % at 16 times the default's nodes per half and azimuths), and at the default
    /// resolution it is furthest from 1 with the sun overhead, where the forward peak sits on
    /// the zenith node.
    #[test]
    fn aerosol_peak_quadrature_tends_to_one() {
        let g = Atmosphere::default().aerosol_g;
        let reading = |half: usize, nphi: usize, zenith: f64| {
            let res = Resolution::default();
            let table = Table4 {
                nr: res.orders_r,
                sun: res.orders_sun,
                half,
                nphi,
                data: Vec::new(),
            };
            aerosol_peak_quadrature(&SphereNodes::of(&table, R), zenith.to_radians().cos(), g)
        };
        let res = Resolution::default();
        let (half, nphi) = (res.orders_mu_half, res.orders_phi);
        let overhead = reading(half, nphi, 0.0);
        for zenith in [0.0, 5.0, 10.0, 30.0, 60.0, 90.0] {
            let coarse = reading(half, nphi, zenith);
            let fine = reading(16 * half, 16 * nphi, zenith);
            assert!((fine - 1.0).abs() < 0.002, "{zenith} deg: {fine}");
            assert!(
                (coarse - 1.0).abs() <= (overhead - 1.0).abs(),
                "{zenith} deg: {coarse}"
            );
        }
        assert!(overhead > 1.2, "{overhead}");
    }
}
