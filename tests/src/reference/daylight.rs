//! The CIE daylight illuminants D_T in f64 (CIE 015:2004 §3.1): the daylight locus x_D(T),
//! y_D(x_D), the weights M1, M2 and the spectrum S0 + M1 S1 + M2 S2, on sky-train's 10 nm
//! bins (360-830 nm), for the melanopic content of daylight (`tests/overcast.rs`).
//!
//! The basis S0, S1, S2 is the CIE's table (CIE 015:2004 Table T.2; Wyszecki & Stiles, *Color
//! Science*, 2nd ed., 2000, pp. 145-146) at its 10 nm rows, as tabulated by colour-science
//! (`colour/colorimetry/datasets/illuminants/sds_d_illuminant_series.py`); the CIE's 5 nm
//! rows between are linear interpolations, so a 10 nm bin's average of the table is the mean
//! of its two ends.

/// S0, S1, S2 at 360, 370, ..., 830 nm.
const BASIS: [[f64; 48]; 3] = [
    [
        61.5, 68.8, 63.4, 65.8, 94.8, 104.8, 105.9, 96.8, 113.9, 125.6, 125.5, 121.3, 121.3, 113.5,
        113.1, 110.8, 106.5, 108.8, 105.3, 104.4, 100.0, 96.0, 95.1, 89.1, 90.5, 90.3, 88.4, 84.0,
        85.1, 81.9, 82.6, 84.9, 81.3, 71.9, 74.3, 76.4, 63.3, 71.7, 77.0, 65.2, 47.7, 68.6, 65.0,
        66.0, 61.0, 53.3, 58.9, 61.9,
    ],
    [
        38.0, 42.4, 38.5, 35.0, 43.4, 46.3, 43.9, 37.1, 36.7, 35.9, 32.6, 27.9, 24.3, 20.1, 16.2,
        13.2, 8.6, 6.1, 4.2, 1.9, 0.0, -1.6, -3.5, -3.5, -5.8, -7.2, -8.6, -9.5, -10.9, -10.7,
        -12.0, -14.0, -13.6, -12.0, -13.3, -12.9, -10.6, -11.6, -12.2, -10.2, -7.8, -11.2, -10.4,
        -10.6, -9.7, -8.3, -9.3, -9.8,
    ],
    [
        5.3, 6.1, 3.0, 1.2, -1.1, -0.5, -0.7, -1.2, -2.6, -2.9, -2.8, -2.6, -2.6, -1.8, -1.5, -1.3,
        -1.2, -1.0, -0.5, -0.3, 0.0, 0.2, 0.5, 2.1, 3.2, 4.1, 4.7, 5.1, 6.7, 7.3, 8.6, 9.8, 10.2,
        8.3, 9.6, 8.5, 7.0, 7.6, 8.0, 6.7, 5.2, 7.4, 6.8, 7.0, 6.4, 5.5, 6.1, 6.5,
    ],
];

/// The basis function `i` (0, 1, 2) averaged over each 10 nm bin [360, 370), ..., [820, 830).
#[must_use]
pub fn basis_bins(i: usize) -> [f64; 47] {
    std::array::from_fn(|b| 0.5 * (BASIS[i][b] + BASIS[i][b + 1]))
}

/// The daylight locus (CIE 015:2004 §3.1): chromaticity (x_D, y_D) of D_T, T in 4,000-25,000 K.
#[must_use]
pub fn locus(kelvin: f64) -> (f64, f64) {
    let t = kelvin;
    let x = if t <= 7000.0 {
        -4.6070e9 / t.powi(3) + 2.9678e6 / t.powi(2) + 0.09911e3 / t + 0.244063
    } else {
        -2.0064e9 / t.powi(3) + 1.9018e6 / t.powi(2) + 0.24748e3 / t + 0.237040
    };
    (x, -3.000 * x * x + 2.870 * x - 0.275)
}

/// The weights (M1, M2) of S1 and S2 in D_T (CIE 015:2004 §3.1), unrounded.
#[must_use]
pub fn weights(kelvin: f64) -> (f64, f64) {
    let (x, y) = locus(kelvin);
    let m = 0.0241 + 0.2562 * x - 0.7341 * y;
    (
        (-1.3515 - 1.7703 * x + 5.9114 * y) / m,
        (0.0300 - 31.4424 * x + 30.0717 * y) / m,
    )
}

/// The relative spectrum of D_T on the 10 nm bins (S0 + M1 S1 + M2 S2; 100 at 560 nm).
#[must_use]
pub fn spectrum(kelvin: f64) -> [f64; 47] {
    let (m1, m2) = weights(kelvin);
    let (s0, s1, s2) = (basis_bins(0), basis_bins(1), basis_bins(2));
    std::array::from_fn(|b| s0[b] + m1 * s1[b] + m2 * s2[b])
}
