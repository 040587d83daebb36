//! Observed rates: the least-squares slope of `ln y` against `ln x`, the
//! one fit behind the convergence rates of the hydrodynamic limit
//! (`thm:main` (iii)), the "independent of N" verdicts of the scaling
//! claims and the cost scaling of `sticky bench --scaling`.

/// Least-squares slope of `ln y` against `ln x` over `points` (`(x, y)`,
/// both positive); `NaN` with fewer than two points.
pub fn log_log_slope(points: &[(f64, f64)]) -> f64 {
    if points.len() < 2 {
        return f64::NAN;
    }
    let k = points.len() as f64;
    let xs: Vec<f64> = points.iter().map(|(x, _)| x.ln()).collect();
    let ys: Vec<f64> = points.iter().map(|(_, y)| y.ln()).collect();
    let mx = xs.iter().sum::<f64>() / k;
    let my = ys.iter().sum::<f64>() / k;
    let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xs.iter().map(|x| (x - mx).powi(2)).sum();
    sxy / sxx
}

#[cfg(test)]
mod tests {
    use super::log_log_slope;

    #[test]
    fn a_power_law_has_its_exponent_as_slope() {
        let pts: Vec<(f64, f64)> = [2.0f64, 4.0, 8.0, 16.0]
            .iter()
            .map(|&n| (n, 3.0 / (n * n)))
            .collect();
        assert!((log_log_slope(&pts) + 2.0).abs() < 1e-12);
        assert!(log_log_slope(&pts[..1]).is_nan());
    }
}
