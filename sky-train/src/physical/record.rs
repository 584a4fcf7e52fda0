//! The measured clear-sky record the model is validated against, and the fit of the aerosol
//! optical depth to it (the default atmosphere's, docs/daylight.md).

use std::sync::Arc;

use super::{PhysicalAtmosphere, SunError};

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

/// The elevations the aerosol optical depth is fitted over ([`fit_aod`]): 0° to 90°, 1° apart.
#[must_use]
pub fn fit_elevations() -> Vec<f64> {
    (0..=90).map(f64::from).collect()
}

/// ln(E / E_USNO) of the global horizontal illuminance E of `atm` at each elevation of `list`
/// (degrees), as (elevation, log ratio).
///
/// # Errors
/// An elevation outside the atmosphere's sun angles.
pub fn usno_log_ratios(
    atm: &Arc<PhysicalAtmosphere>,
    list: &[f64],
) -> Result<Vec<(f64, f64)>, SunError> {
    list.iter()
        .map(|&h| {
            let e = atm.sky(90.0 - h, 0.0)?.daylight().global.xyz[1];
            Ok((h, (e / usno_illuminance(h)).ln()))
        })
        .collect()
}

/// The result of [`fit_aod`].
#[derive(Debug, Clone, PartialEq)]
pub struct AodFit {
    /// The fitted aerosol optical depth at 550 nm.
    pub aod_550: f64,
    /// Every (optical depth, cost) evaluated, in order.
    pub evaluations: Vec<(f64, f64)>,
}

/// The optical depths [`fit_aod`] starts from and the interval it keeps to.
pub const FIT_START: [f64; 3] = [0.2, 0.4, 0.6];
/// The interval of optical depths [`fit_aod`] searches.
pub const FIT_RANGE: (f64, f64) = (0.0, 2.0);

/// Minimises `cost(τ)` over [`FIT_RANGE`] by successive parabolic interpolation (the
/// parabola through the three best points so far, its vertex the next point) from
/// [`FIT_START`], until the vertex moves less than `tolerance` or after `max_evaluations`.
/// Made for a cost that is nearly quadratic in τ, as the sum of squared log ratios of
/// illuminances that change smoothly with the optical depth is.
///
/// # Errors
/// The cost's own errors; a cost that is not convex around the points (no minimum to
/// interpolate), or no convergence within `max_evaluations`.
pub fn fit_aod(
    mut cost: impl FnMut(f64) -> anyhow::Result<f64>,
    tolerance: f64,
    max_evaluations: usize,
) -> anyhow::Result<AodFit> {
    let mut evaluations = Vec::new();
    for tau in FIT_START {
        evaluations.push((tau, cost(tau)?));
    }
    while evaluations.len() < max_evaluations {
        let mut best = evaluations.clone();
        best.sort_by(|a, b| a.1.total_cmp(&b.1));
        let [(x0, f0), (x1, f1), (x2, f2)] = [best[0], best[1], best[2]];
        // The vertex of the parabola through the three points (divided differences).
        let d01 = (f1 - f0) / (x1 - x0);
        let d12 = (f2 - f1) / (x2 - x1);
        let curvature = (d12 - d01) / (x2 - x0);
        if curvature.is_nan() || curvature <= 0.0 {
            anyhow::bail!("the cost is not convex around {best:?}: no minimum to fit");
        }
        let vertex = (0.5 * (x0 + x1 - d01 / curvature)).clamp(FIT_RANGE.0, FIT_RANGE.1);
        if evaluations
            .iter()
            .any(|e| (e.0 - vertex).abs() < 0.1 * tolerance)
        {
            return Ok(AodFit {
                aod_550: vertex,
                evaluations,
            });
        }
        evaluations.push((vertex, cost(vertex)?));
        if (vertex - x0).abs() < tolerance {
            return Ok(AodFit {
                aod_550: vertex,
                evaluations,
            });
        }
    }
    anyhow::bail!("no convergence within {max_evaluations} evaluations: {evaluations:?}")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The minimiser finds a known minimum of a cost like the fit's (a sum of squares of
    /// smooth, non-linear functions of τ), to its tolerance.
    #[test]
    fn fit_finds_a_known_minimum() {
        // Σ (ln(a_i + b_i τ) − c_i)², its minimum found by a fine scan.
        let terms = [(1.0, 0.5, 0.2), (0.8, 1.5, 0.1), (1.2, -0.3, 0.0)];
        let cost = |t: f64| -> f64 {
            terms
                .iter()
                .map(|(a, b, c)| ((a + b * t).ln() - c).powi(2))
                .sum()
        };
        let scan = (0..=200_000)
            .map(|k| f64::from(k) * 1e-5)
            .min_by(|a, b| cost(*a).total_cmp(&cost(*b)))
            .expect("scan");
        let fit = fit_aod(|t| Ok(cost(t)), 1e-4, 20).expect("fit");
        assert!((fit.aod_550 - scan).abs() < 1e-3, "{fit:?} vs {scan}");
        assert!(fit.evaluations.len() < 12, "{fit:?}");
    }
}
