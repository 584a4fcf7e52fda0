//! The measured clear-sky record the model is validated against.

/// Total (sun + sky) horizontal illuminance of the clear sky, lux, against the sun's geometric
/// altitude `h` in degrees (−18° to 90°): USNO Circular 171 (Janiczek & DeYoung 1987,
/// "Computer programs for sun and moon illuminance with contingent tables and diagrams",
/// after Brown 1952), as reproduced in E. O. Ofek's MATLAB astronomy package
/// (`celestial.SolarSys.sunlight`): log10(E / lx) = L0 + L1 X + L2 X² + L3 X³ with X = h / 90°,
/// one set of coefficients per interval. The break at −0.8° is sunrise (the upper limb on the
/// horizon with 34′ of refraction), so h is the centre's geometric altitude.
#[must_use]
pub fn usno_illuminance(h: f64) -> f64 {
    let c: [f64; 4] = if h > 20.0 {
        [3.74, 3.97, -4.07, 1.47]
    } else if h > 5.0 {
        [3.05, 13.28, -45.98, 64.33]
    } else if h > -0.8 {
        [2.88, 22.26, -207.64, 1034.30]
    } else if h > -5.0 {
        [2.88, 21.81, -258.11, -858.36]
    } else if h > -12.0 {
        [2.70, 12.17, -431.69, -1899.83]
    } else {
        [13.84, 262.72, 1447.42, 2797.93]
    };
    let x = h / 90.0;
    10f64.powf(c[0] + c[1] * x + c[2] * x * x + c[3] * x * x * x)
}
