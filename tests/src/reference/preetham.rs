//! The Preetham clear sky (seed 002, eqs. 10-19), the spherical distance of eq. 26 and the
//! colour conversions of eqs. 27-29, in f64.
//!
//! Conventions are those of the seed's "additional computations": a view direction is given by
//! its zenith angle θ (from +z) and azimuth ψ; the elevation is φ = π/2 − θ (eq. 23). Luminance
//! is in cd/m², that is 1000 × eq. 16's kcd/m².

use std::f64::consts::{FRAC_PI_2, PI};

/// Eq. 13: Perez coefficients A-E of luminance Y as `[slope, intercept]` in turbidity T.
const LUMINANCE_COEFFICIENTS: [[f64; 2]; 5] = [
    [0.1787, -1.4630],
    [-0.3554, 0.4275],
    [-0.0227, 5.3251],
    [0.1206, -2.5771],
    [-0.0670, 0.3703],
];

/// Eq. 14: Perez coefficients A-E of chromaticity x.
const X_COEFFICIENTS: [[f64; 2]; 5] = [
    [-0.0193, -0.2592],
    [-0.0665, 0.0008],
    [-0.0004, 0.2125],
    [-0.0641, -0.8989],
    [-0.0033, 0.0452],
];

/// Eq. 15: Perez coefficients A-E of chromaticity y.
const Y_COEFFICIENTS: [[f64; 2]; 5] = [
    [-0.0167, -0.2608],
    [-0.0950, 0.0092],
    [-0.0079, 0.2102],
    [-0.0441, -1.6537],
    [-0.0109, 0.0529],
];

/// Eq. 18: zenith chromaticity x = [T² T 1] M [θs³ θs² θs 1]ᵀ; rows of M.
const ZENITH_X: [[f64; 4]; 3] = [
    [0.0017, -0.0037, 0.0021, 0.000],
    [-0.0290, 0.0638, -0.0320, 0.0039],
    [0.1169, -0.2120, 0.0605, 0.2589],
];

/// Eq. 19: zenith chromaticity y; rows of M.
const ZENITH_Y: [[f64; 4]; 3] = [
    [0.0028, -0.0061, 0.0032, 0.000],
    [-0.0421, 0.0897, -0.0415, 0.0052],
    [0.1535, -0.2676, 0.0667, 0.2669],
];

/// Eq. 28: CIE XYZ → linear sRGB, rows.
pub const XYZ_TO_LINEAR_SRGB: [[f64; 3]; 3] = [
    [3.240_625_5, -1.537_207_3, -0.498_628_6],
    [-0.968_930_7, 1.875_756_1, 0.041_517_5],
    [0.055_710_1, -0.204_021_1, 1.056_995_9],
];

/// The five Perez coefficients of one channel, eq. 10.
#[derive(Debug, Clone, Copy)]
pub struct Perez {
    /// Horizon darkening/brightening.
    pub a: f64,
    /// Horizon gradient.
    pub b: f64,
    /// Circumsolar intensity.
    pub c: f64,
    /// Circumsolar width.
    pub d: f64,
    /// Backscattering.
    pub e: f64,
}

impl Perez {
    /// Eqs. 13-15: the coefficients at turbidity `t`.
    fn from_table(table: &[[f64; 2]; 5], t: f64) -> Self {
        let v = table.map(|[slope, intercept]| slope * t + intercept);
        Self {
            a: v[0],
            b: v[1],
            c: v[2],
            d: v[3],
            e: v[4],
        }
    }

    /// `[A, B, C, D, E]`.
    pub fn to_array(self) -> [f64; 5] {
        [self.a, self.b, self.c, self.d, self.e]
    }

    /// Eq. 10: F(θ, γ) = (1 + A e^{B / cos θ}) (1 + C e^{D γ} + E cos² γ).
    ///
    /// At θ = π/2 (and below, which callers avoid) B / cos θ → −∞ because B < 0 (eq. 2), so
    /// the first factor is 1 (eq. 4).
    pub fn f(self, theta: f64, gamma: f64) -> f64 {
        let cos_theta = theta.cos();
        let gradation = if cos_theta > 0.0 {
            1.0 + self.a * (self.b / cos_theta).exp()
        } else {
            1.0
        };
        let cos_gamma = gamma.cos();
        let indicatrix = 1.0 + self.c * (self.d * gamma).exp() + self.e * cos_gamma * cos_gamma;
        gradation * indicatrix
    }
}

/// Eqs. 16-17: zenith luminance in cd/m² (eq. 16 gives kcd/m²).
pub fn zenith_luminance(t: f64, theta_s: f64) -> f64 {
    let chi = (4.0 / 9.0 - t / 120.0) * (PI - 2.0 * theta_s);
    1000.0 * ((4.0453 * t - 4.9710) * chi.tan() - 0.2155 * t + 2.4192)
}

/// Eqs. 18-19: `[T² T 1] M [θs³ θs² θs 1]ᵀ`.
fn zenith_chromaticity(m: &[[f64; 4]; 3], t: f64, theta_s: f64) -> f64 {
    let tv = [t * t, t, 1.0];
    let sv = [theta_s.powi(3), theta_s.powi(2), theta_s, 1.0];
    let mut sum = 0.0;
    for (row, ti) in m.iter().zip(tv) {
        for (mij, sj) in row.iter().zip(sv) {
            sum += ti * mij * sj;
        }
    }
    sum
}

/// Eq. 26 (Vincenty): the angle between the directions at elevations `phi`, `phi_s` whose
/// azimuths differ by `d_psi`.
pub fn spherical_distance(phi: f64, phi_s: f64, d_psi: f64) -> f64 {
    let (sp, cp) = phi.sin_cos();
    let (sps, cps) = phi_s.sin_cos();
    let (sd, cd) = d_psi.sin_cos();
    let a = cps * sd;
    let b = cp * sps - sp * cps * cd;
    (a * a + b * b).sqrt().atan2(sp * sps + cp * cps * cd)
}

/// Zenith angle θ in [0, π] and azimuth ψ of a (not necessarily unit) vector.
pub fn zenith_azimuth(v: [f64; 3]) -> (f64, f64) {
    (v[0].hypot(v[1]).atan2(v[2]), v[1].atan2(v[0]))
}

/// The unit vector with zenith angle `theta` and azimuth `psi`: (sin θ cos ψ, sin θ sin ψ,
/// cos θ), i.e. (cos φ cos ψ, cos φ sin ψ, sin φ) with elevation φ = π/2 − θ.
pub fn direction(theta: f64, psi: f64) -> [f64; 3] {
    let (st, ct) = theta.sin_cos();
    let (sp, cp) = psi.sin_cos();
    [st * cp, st * sp, ct]
}

/// The angle between two (not necessarily unit) vectors by eq. 26.
pub fn angle_between(a: [f64; 3], b: [f64; 3]) -> f64 {
    let (ta, pa) = zenith_azimuth(a);
    let (tb, pb) = zenith_azimuth(b);
    spherical_distance(FRAC_PI_2 - ta, FRAC_PI_2 - tb, pa - pb)
}

/// A colour as chromaticity and luminance.
#[derive(Debug, Clone, Copy)]
pub struct Xyy {
    /// Chromaticity x.
    pub x: f64,
    /// Chromaticity y.
    pub y: f64,
    /// Luminance, cd/m².
    pub luminance: f64,
}

/// The sky of one sun position and turbidity.
#[derive(Debug, Clone, Copy)]
pub struct Sky {
    theta_s: f64,
    psi_s: f64,
    /// Perez coefficients of Y, x, y (eqs. 13-15).
    pub perez: [Perez; 3],
    /// Zenith Y (cd/m²), x, y (eqs. 16-19).
    pub zenith: [f64; 3],
}

impl Sky {
    /// The sky for turbidity `t` and the sun at zenith angle `theta_s`, azimuth `psi_s`.
    pub fn new(t: f64, theta_s: f64, psi_s: f64) -> Self {
        Self {
            theta_s,
            psi_s,
            perez: [
                Perez::from_table(&LUMINANCE_COEFFICIENTS, t),
                Perez::from_table(&X_COEFFICIENTS, t),
                Perez::from_table(&Y_COEFFICIENTS, t),
            ],
            zenith: [
                zenith_luminance(t, theta_s),
                zenith_chromaticity(&ZENITH_X, t, theta_s),
                zenith_chromaticity(&ZENITH_Y, t, theta_s),
            ],
        }
    }

    /// Eqs. 11-12 at view zenith angle `theta` ∈ [0, π/2] and angle `gamma` from the sun.
    pub fn xyy_at(&self, theta: f64, gamma: f64) -> Xyy {
        // F(0, θs): the zenith, whose angle from the sun is θs.
        let channel = |k: usize| {
            self.zenith[k] * self.perez[k].f(theta, gamma) / self.perez[k].f(0.0, self.theta_s)
        };
        Xyy {
            x: channel(1),
            y: channel(2),
            luminance: channel(0),
        }
    }

    /// The sky towards the (not necessarily unit) vector `v`. Below the horizon (z < 0) the
    /// luminance is 0 and the chromaticity that of the horizon (θ = π/2) at the same angle
    /// from the sun.
    pub fn xyy(&self, v: [f64; 3]) -> Xyy {
        let (theta, psi) = zenith_azimuth(v);
        let gamma = spherical_distance(
            FRAC_PI_2 - theta,
            FRAC_PI_2 - self.theta_s,
            psi - self.psi_s,
        );
        if v[2] < 0.0 {
            Xyy {
                luminance: 0.0,
                ..self.xyy_at(FRAC_PI_2, gamma)
            }
        } else {
            self.xyy_at(theta, gamma)
        }
    }
}

/// Eq. 27: xyY → XYZ.
pub fn xyy_to_xyz(c: Xyy) -> [f64; 3] {
    let s = c.luminance / c.y;
    [c.x * s, c.luminance, (1.0 - c.x - c.y) * s]
}

/// Eq. 28: XYZ → linear sRGB.
pub fn xyz_to_linear_srgb(xyz: [f64; 3]) -> [f64; 3] {
    XYZ_TO_LINEAR_SRGB.map(|row| row[0] * xyz[0] + row[1] * xyz[1] + row[2] * xyz[2])
}

/// Eq. 29: the sRGB transfer function of one linear component in [0, 1].
pub fn srgb_encode(c: f64) -> f64 {
    if c <= 0.003_130_8 {
        12.92 * c
    } else {
        1.055 * c.powf(1.0 / 2.4) - 0.055
    }
}
