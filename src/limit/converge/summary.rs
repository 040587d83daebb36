//! The plain-text summary of a study: one line per N, the rates, the
//! continuum and the engine check.

use std::fmt::Write as _;

use super::{ConvergenceReport, Quantity};
use crate::scalar::Scalar;

impl ConvergenceReport {
    /// A plain-text table: one line per N, then the rates and the
    /// continuum.
    pub fn summary(&self) -> String {
        let mut s = String::new();
        let _ = writeln!(
            s,
            "scene {} — T = {}, δ = {}, sample times 0, T(3j−1)/{}, T",
            self.scene,
            self.t_end.render(),
            self.delta.render(),
            3 * self.times.len().saturating_sub(2)
        );
        let cols = [
            Quantity::XL2,
            Quantity::UL1,
            Quantity::LambdaL2,
            Quantity::PressureMass,
            Quantity::PressureMassError,
            Quantity::BvX,
            Quantity::TvU,
            Quantity::TvUError,
            Quantity::ResidualMomentum,
            Quantity::Complementarity,
            Quantity::Oleinik,
            Quantity::NLambda,
        ];
        let _ = write!(s, "{:>7} {:>6} {:>8}", "N", "engine", "seconds");
        for c in cols {
            let _ = write!(s, " {:>12}", c.key());
        }
        let _ = writeln!(s);
        for r in &self.rows {
            let _ = write!(s, "{:>7} {:>6} {:>8.3}", r.n, r.engine.name(), r.seconds);
            for c in cols {
                let v = r.get(c).map_or(f64::NAN, |m| m.value);
                let _ = write!(s, " {:>12.5e}", v);
            }
            let _ = writeln!(s);
        }
        let _ = writeln!(s, "rates (least-squares log-log slope; tail = N ≥ 256):");
        for r in &self.rates {
            let _ = writeln!(
                s,
                "  {:<20} slope(all) {:>7.3}  slope(tail) {:>7.3}  {}",
                r.quantity.key(),
                r.slope_all,
                r.slope_tail,
                r.verdict
            );
        }
        let c = &self.continuum;
        let _ = writeln!(
            s,
            "continuum: {} profile; plateaus per sample {:?}; ∫Λ(T) = {} ; max ρ = {} ; t·sup ∂ₓu = {} ; max |Λ| off plateaus = {}",
            if c.rational { "rational" } else { "irrational (quadratic surds)" },
            c.plateaus,
            c.pressure_mass.exact.clone().unwrap_or_else(|| format!("{:.12}", c.pressure_mass.value)),
            c.max_density.exact.clone().unwrap_or_else(|| format!("{:.12}", c.max_density.value)),
            c.oleinik.map_or("∞ (violated)".to_string(), |v| format!("{v:.6}")),
            c.complementarity_defect.value
        );
        let worst = |k: usize| {
            c.residuals
                .iter()
                .map(|r| if k == 0 { r.0 } else { r.1 })
                .fold((0.0f64, 0.0f64), |(v, e), q| {
                    (v.max(q.value.abs()), e.max(q.error))
                })
        };
        if !c.residuals.is_empty() {
            let (mv, me) = worst(0);
            let (pv, pe) = worst(1);
            let _ = writeln!(
                s,
                "continuum residuals (quadrature): max |mass| = {mv:.3e} (error est. {me:.1e}), max |momentum| = {pv:.3e} (error est. {pe:.1e})"
            );
        }
        if let Some(e) = &self.engine_check {
            let worst = e.differences.iter().map(|d| d.1).fold(0.0, f64::max);
            let _ = writeln!(s, "engine check at N = {}: max relative |exact − f64| over the quantities = {worst:.3e}", e.n);
        }
        s
    }
}
