//! The weather models in f64, written from the papers, with their own copies of the tables:
//! the CIE standard general sky (ISO 15469:2004 / CIE S 011/E:2003), the Perez all-weather sky
//! (Perez, Seals, Michalsky 1993), the Perez 1990 luminous efficacies, Erbs et al. 1982's
//! diffuse fraction, Kasten's air mass and Spencer's eccentricity correction.
//!
//! The tables here are laid out differently from sky-core's and taken from other sources, so
//! that a transcription error in either shows: the CIE skies from Darula & Kittler's six
//! gradation and six indicatrix groups (*CIE general sky standard defining luminance
//! distributions*, eSim 2002), the Perez tables from the per-coefficient arrays of the CitySim
//! solver's `cPerezSkyModel` (which cites Perez et al. 1990 and 1993).
//!
//! Angles: zenith angles from +z, azimuths in radians; the angle between a view and the sun by
//! the spherical law of cosines.

use std::f64::consts::{FRAC_PI_2, PI};

/// Darula & Kittler 2002: gradation groups I-VI, (a, b).
const GRADATION: [(f64, f64); 6] = [
    (4.0, -0.70),
    (1.1, -0.80),
    (0.0, -1.00),
    (-1.0, -0.55),
    (-1.0, -0.32),
    (-1.0, -0.15),
];

/// Darula & Kittler 2002: indicatrix groups 1-6, (c, d, e).
const INDICATRIX: [(f64, f64, f64); 6] = [
    (0.0, -1.0, 0.0),
    (2.0, -1.5, 0.15),
    (5.0, -2.5, 0.30),
    (10.0, -3.0, 0.45),
    (16.0, -3.0, 0.30),
    (24.0, -2.8, 0.15),
];

/// The (gradation group, indicatrix group) of each standard type 1-15, counted from 1.
const CIE_TYPES: [(usize, usize); 15] = [
    (1, 1),
    (1, 2),
    (2, 1),
    (2, 2),
    (3, 1),
    (3, 2),
    (3, 3),
    (3, 4),
    (4, 2),
    (4, 3),
    (4, 4),
    (5, 4),
    (5, 5),
    (6, 5),
    (6, 6),
];

/// The angle between the directions (θ₁, φ₁) and (θ₂, φ₂).
#[must_use]
pub fn angular_distance(theta1: f64, phi1: f64, theta2: f64, phi2: f64) -> f64 {
    (theta1.cos() * theta2.cos() + theta1.sin() * theta2.sin() * (phi1 - phi2).cos())
        .clamp(-1.0, 1.0)
        .acos()
}

/// The CIE standard general sky of type `sky_type` (1-15): luminance relative to the zenith's at
/// zenith angle `theta`, azimuth `phi`, with the sun at (`sun_theta`, `sun_phi`).
#[must_use]
pub fn cie_relative(sky_type: usize, theta: f64, phi: f64, sun_theta: f64, sun_phi: f64) -> f64 {
    let (g, i) = CIE_TYPES[sky_type - 1];
    let (a, b) = GRADATION[g - 1];
    let (c, d, e) = INDICATRIX[i - 1];
    let gradation = |z: f64| {
        if z >= FRAC_PI_2 {
            1.0
        } else {
            1.0 + a * (b / z.cos()).exp()
        }
    };
    let indicatrix =
        |chi: f64| 1.0 + c * ((d * chi).exp() - (d * FRAC_PI_2).exp()) + e * chi.cos().powi(2);
    let chi = angular_distance(theta, phi, sun_theta, sun_phi);
    indicatrix(chi) * gradation(theta) / (indicatrix(sun_theta) * gradation(0.0))
}

/// CitySim `cPerezSkyModel`: the Perez 1993 Table 1 coefficients, one array per coefficient over
/// the eight sky-clearness bins.
const A1: [f64; 8] = [
    1.3525, -1.2219, -1.1000, -0.5484, -0.6000, -1.0156, -1.0000, -1.0500,
];
const A2: [f64; 8] = [
    -0.2576, -0.7730, -0.2515, -0.6654, -0.3566, -0.3670, 0.0211, 0.0289,
];
const A3: [f64; 8] = [
    -0.2690, 1.4148, 0.8952, -0.2672, -2.5000, 1.0078, 0.5025, 0.4260,
];
const A4: [f64; 8] = [
    -1.4366, 1.1016, 0.0156, 0.7117, 2.3250, 1.4051, -0.5119, 0.3590,
];
const B1: [f64; 8] = [
    -0.7670, -0.2054, 0.2782, 0.7234, 0.2937, 0.2875, -0.3000, -0.3250,
];
const B2: [f64; 8] = [
    0.0007, 0.0367, -0.1812, -0.6219, 0.0496, -0.5328, 0.1922, 0.1156,
];
const B3: [f64; 8] = [
    1.2734, -3.9128, -4.5000, -5.6812, -5.6812, -3.8500, 0.7023, 0.7781,
];
const B4: [f64; 8] = [
    -0.1233, 0.9156, 1.1766, 2.6297, 1.8415, 3.3750, -1.6317, 0.0025,
];
const C1: [f64; 8] = [
    2.8000, 6.9750, 24.7219, 33.3389, 21.0000, 14.0000, 19.0000, 31.0625,
];
const C2: [f64; 8] = [
    0.6004, 0.1774, -13.0812, -18.3000, -4.7656, -0.9999, -5.0000, -14.5000,
];
const C3: [f64; 8] = [
    1.2375, 6.4477, -37.7000, -62.2500, -21.5906, -7.1406, 1.2438, -46.1148,
];
const C4: [f64; 8] = [
    1.0000, -0.1239, 34.8438, 52.0781, 7.2492, 7.5469, -1.9094, 55.3750,
];
const D1: [f64; 8] = [
    1.8734, -1.5798, -5.0000, -3.5000, -3.5000, -3.4000, -4.0000, -7.2312,
];
const D2: [f64; 8] = [
    0.6297, -0.5081, 1.5218, 0.0016, -0.1554, -0.1078, 0.0250, 0.4050,
];
const D3: [f64; 8] = [
    0.9738, -1.7812, 3.9229, 1.1477, 1.4062, -1.0750, 0.3844, 13.3500,
];
const D4: [f64; 8] = [
    0.2809, 0.1080, -2.6204, 0.1062, 0.3988, 1.5702, 0.2656, 0.6234,
];
const E1: [f64; 8] = [
    0.0356, 0.2624, -0.0156, 0.4659, 0.0032, -0.0672, 1.0468, 1.5000,
];
const E2: [f64; 8] = [
    -0.1246, 0.0672, 0.1597, -0.3296, 0.0766, 0.4016, -0.3788, -0.6426,
];
const E3: [f64; 8] = [
    -0.5718, -0.2190, 0.4199, -0.0876, -0.0656, 0.3017, -2.4517, 1.8564,
];
const E4: [f64; 8] = [
    0.9938, -0.4285, -0.5562, -0.0329, -0.1294, -0.4844, 1.4656, 0.5636,
];

/// The upper edges of the sky-clearness bins 1-7 (Perez et al. 1990, Table 1).
const BIN_EDGES: [f64; 7] = [1.065, 1.23, 1.5, 1.95, 2.8, 4.5, 6.2];

/// CitySim `cPerezSkyModel`: the Perez 1990 Table 4 efficacies, a, b, c, d per bin.
const GLOBAL_A: [f64; 8] = [96.63, 107.54, 98.73, 92.72, 86.73, 88.34, 78.63, 99.65];
const GLOBAL_B: [f64; 8] = [-0.47, 0.79, 0.70, 0.56, 0.98, 1.39, 1.47, 1.86];
const GLOBAL_C: [f64; 8] = [11.5, 1.79, 4.4, 8.36, 7.1, 6.06, 4.93, -4.46];
const GLOBAL_D: [f64; 8] = [-9.16, -1.19, -6.95, -8.31, -10.94, -7.6, -11.37, -3.15];
const DIFFUSE_A: [f64; 8] = [
    97.24, 107.22, 104.97, 102.39, 100.71, 106.42, 141.88, 152.23,
];
const DIFFUSE_B: [f64; 8] = [-0.46, 1.15, 2.96, 5.59, 5.94, 3.83, 1.90, 0.35];
const DIFFUSE_C: [f64; 8] = [12.0, 0.59, -5.53, -13.95, -22.75, -36.15, -53.24, -45.27];
const DIFFUSE_D: [f64; 8] = [-8.91, -3.95, -8.77, -13.9, -23.74, -28.83, -14.03, -7.98];
const BEAM_A: [f64; 8] = [57.2, 98.99, 109.83, 110.34, 106.36, 107.19, 105.75, 101.18];
const BEAM_B: [f64; 8] = [-4.55, -3.46, -4.90, -5.84, -3.97, -1.25, 0.77, 1.58];
const BEAM_C: [f64; 8] = [-2.98, -1.21, -1.71, -1.99, -1.75, -1.51, -1.26, -1.10];
const BEAM_D: [f64; 8] = [117.12, 12.38, -8.81, -4.56, -6.16, -26.73, -34.44, -8.29];

/// The sky-clearness bin of ε, 0-7 (counted from 0 here).
#[must_use]
pub fn bin(epsilon: f64) -> usize {
    BIN_EDGES.iter().take_while(|&&e| epsilon >= e).count()
}

/// Sky clearness ε (Perez et al. 1990, eq. 1).
#[must_use]
pub fn sky_clearness(diffuse: f64, direct_normal: f64, sun_zenith: f64) -> f64 {
    let k = 1.041 * sun_zenith.powi(3);
    ((diffuse + direct_normal) / diffuse + k) / (1.0 + k)
}

/// Kasten 1966's relative air mass.
#[must_use]
pub fn air_mass(sun_zenith: f64) -> f64 {
    1.0 / (sun_zenith.cos() + 0.15 * (93.885 - sun_zenith.to_degrees()).powf(-1.253))
}

/// Spencer 1971's eccentricity correction times the solar constant 1367 W/m².
#[must_use]
pub fn extraterrestrial(day_of_year: u32) -> f64 {
    let g = 2.0 * PI * f64::from(day_of_year - 1) / 365.0;
    1367.0
        * (1.00011
            + 0.034221 * g.cos()
            + 0.00128 * g.sin()
            + 0.000719 * (2.0 * g).cos()
            + 0.000077 * (2.0 * g).sin())
}

/// Sky brightness Δ (Perez et al. 1990, eq. 2).
#[must_use]
pub fn sky_brightness(diffuse: f64, sun_zenith: f64, day_of_year: u32) -> f64 {
    diffuse * air_mass(sun_zenith) / extraterrestrial(day_of_year)
}

/// The clamps sky-core documents for the all-weather model, applied to Δ: [0.01, 0.6], at
/// least 0.2 for 1.065 < ε < 2.8, at least 0.08 for 2.8 ≤ ε < 4.5.
#[must_use]
pub fn luminance_delta(epsilon: f64, delta: f64) -> f64 {
    let d = delta.clamp(0.01, 0.6);
    if epsilon > 1.065 && epsilon < 2.8 {
        d.max(0.2)
    } else if (2.8..4.5).contains(&epsilon) {
        d.max(0.08)
    } else {
        d
    }
}

/// The all-weather coefficients a-e (Perez et al. 1993, eqs. 6-8), with b at most 0.
#[must_use]
pub fn all_weather(epsilon: f64, delta: f64, z: f64) -> [f64; 5] {
    let k = bin(epsilon);
    let d = luminance_delta(epsilon, delta);
    let lin = |x1: &[f64; 8], x2: &[f64; 8], x3: &[f64; 8], x4: &[f64; 8]| {
        x1[k] + x2[k] * z + d * (x3[k] + x4[k] * z)
    };
    let a = lin(&A1, &A2, &A3, &A4);
    let b = lin(&B1, &B2, &B3, &B4).min(0.0);
    let e = lin(&E1, &E2, &E3, &E4);
    let (c, dd) = if k == 0 {
        (
            (d * (C1[0] + C2[0] * z)).powf(C3[0]).exp() - C4[0],
            -(d * (D1[0] + D2[0] * z)).exp() + D3[0] + d * D4[0],
        )
    } else {
        (lin(&C1, &C2, &C3, &C4), lin(&D1, &D2, &D3, &D4))
    };
    [a, b, c, dd, e]
}

/// The all-weather relative luminance (seed 002 eq. 1), negative values clamped to 0, at
/// (θ, φ) with the sun at (θs, φs).
#[must_use]
pub fn all_weather_luminance(
    coefficients: [f64; 5],
    theta: f64,
    phi: f64,
    sun_theta: f64,
    sun_phi: f64,
) -> f64 {
    let [a, b, c, d, e] = coefficients;
    let gamma = angular_distance(theta, phi, sun_theta, sun_phi);
    let gradation = if theta >= FRAC_PI_2 {
        1.0
    } else {
        1.0 + a * (b / theta.cos()).exp()
    };
    (gradation * (1.0 + c * (d * gamma).exp() + e * gamma.cos().powi(2))).max(0.0)
}

/// The Perez 1990 global, diffuse and direct efficacies (lm/W) for ε, Δ (clamped to
/// [0.01, 0.6]), sun zenith `z` and precipitable water `w` cm.
#[must_use]
pub fn efficacies(epsilon: f64, delta: f64, z: f64, w: f64) -> [f64; 3] {
    let k = bin(epsilon);
    let d = delta.clamp(0.01, 0.6);
    [
        GLOBAL_A[k] + GLOBAL_B[k] * w + GLOBAL_C[k] * z.cos() + GLOBAL_D[k] * d.ln(),
        DIFFUSE_A[k] + DIFFUSE_B[k] * w + DIFFUSE_C[k] * z.cos() + DIFFUSE_D[k] * d.ln(),
        (BEAM_A[k] + BEAM_B[k] * w + BEAM_C[k] * (5.73 * z - 5.0).exp() + BEAM_D[k] * d).max(0.0),
    ]
}

/// The bin centres of sky-core's continuous efficacies (docs/weather.md): the middle of Perez's
/// bins 1-7 (edges 1, 1.065, 1.23, 1.5, 1.95, 2.8, 4.5, 6.2) and 6.2 + (6.2 − 4.5) / 2 for the
/// open bin 8.
pub const CENTRES: [f64; 8] = [
    (1.0 + 1.065) / 2.0,
    (1.065 + 1.23) / 2.0,
    (1.23 + 1.5) / 2.0,
    (1.5 + 1.95) / 2.0,
    (1.95 + 2.8) / 2.0,
    (2.8 + 4.5) / 2.0,
    (4.5 + 6.2) / 2.0,
    6.2 + (6.2 - 4.5) / 2.0,
];

/// The reference's (binned, Perez 1990 Table 4) efficacies interpolated linearly in ε between
/// [`CENTRES`], constant beyond the first and last: the documented rule, in f64. Linear in the
/// coefficients, so equal to interpolating the efficacies (before the direct one's max(0, ·)).
#[must_use]
pub fn interpolated_efficacies(epsilon: f64, delta: f64, z: f64, w: f64) -> [f64; 3] {
    let at = |e: f64| efficacies(e, delta, z, w);
    if epsilon <= CENTRES[0] {
        return at(CENTRES[0]);
    }
    if epsilon >= CENTRES[7] {
        return at(CENTRES[7]);
    }
    let j = (0..7).rfind(|&j| CENTRES[j] <= epsilon).unwrap_or(0);
    let t = (epsilon - CENTRES[j]) / (CENTRES[j + 1] - CENTRES[j]);
    // The direct efficacy's max(0, ·) is taken after the interpolation.
    let parts = |e: f64| {
        let [g, d, _] = at(e);
        [g, d, direct_efficacy_unclamped(e, delta, z, w)]
    };
    let (a, b) = (parts(CENTRES[j]), parts(CENTRES[j + 1]));
    let lerp = |i: usize| a[i] + t * (b[i] - a[i]);
    [lerp(0), lerp(1), lerp(2).max(0.0)]
}

/// The Perez 1990 direct efficacy (lm/W) of [`efficacies`] before its max(0, ·).
#[must_use]
pub fn direct_efficacy_unclamped(epsilon: f64, delta: f64, z: f64, w: f64) -> f64 {
    let k = bin(epsilon);
    let d = delta.clamp(0.01, 0.6);
    BEAM_A[k] + BEAM_B[k] * w + BEAM_C[k] * (5.73 * z - 5.0).exp() + BEAM_D[k] * d
}

/// Erbs et al. 1982, eq. 1: the hourly diffuse fraction at clearness index `kt`.
#[must_use]
pub fn erbs(kt: f64) -> f64 {
    if kt <= 0.22 {
        1.0 - 0.09 * kt
    } else if kt <= 0.8 {
        0.9511 - 0.1604 * kt + 4.388 * kt.powi(2) - 16.638 * kt.powi(3) + 12.336 * kt.powi(4)
    } else {
        0.165
    }
}
