//! What the study measures: one [`Measure`] per [`Quantity`] and N (a
//! [`Row`]), and the fitted log-log [`Rate`] of each quantity across N.

use crate::rate::log_log_slope;

use super::Engine;

/// One measured number.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "json", derive(serde::Serialize, serde::Deserialize))]
pub struct Measure {
    /// The value (nearest double of the exact value when there is one).
    #[cfg_attr(feature = "json", serde(with = "crate::campaign::bits::one"))]
    pub value: f64,
    /// A bound on `|value − true value|` from the rounding of the
    /// continuum profile to doubles (`3β` for coefficients within `β`, plus
    /// `√e·(jump + 2·slope·e)` in `L²`, `e·(jump + 2·slope·e)` in `L¹`, for
    /// each breakpoint rounded by `e`), the rounding of exact particle
    /// values (`2ε·max|X|`) and the `f64` summation (`(n + 20)ε` times the
    /// value); 0 for an exact value (the rounding of the exact value to a
    /// double aside).
    /// It does not cover the `f64` particle engine (see
    /// [`EngineCheck`](super::EngineCheck)).
    #[cfg_attr(feature = "json", serde(with = "crate::campaign::bits::one"))]
    pub bound: f64,
    /// The exact value, when exact and short (a rational `p/q`, or
    /// `sqrt(p/q)` for a norm whose square is rational).
    pub exact: Option<String>,
}

impl Measure {
    pub(super) fn float(value: f64, bound: f64) -> Self {
        Measure {
            value,
            bound,
            exact: None,
        }
    }
}

/// The quantities of one row.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "json", derive(serde::Serialize, serde::Deserialize))]
pub enum Quantity {
    /// `max_j ‖X_N(t_j) − X(t_j)‖_{L²(0,1)}`.
    XL2,
    /// `‖X_N(T) − X(T)‖_{L²(0,1)}`.
    XL2End,
    /// `max_{j≥1} ‖U_N(t_j) − U(t_j)‖_{L¹(0,1)}`.
    UL1,
    /// `max_{j≥1} ‖Λ_N(t_j) − Λ(t_j)‖_{L²(0,1)}`.
    LambdaL2,
    /// `‖P̃_N‖_{M(0,T;L¹)}`: the total pressure mass on `[0, T]`
    /// (`prop:pressure-bound`).
    PressureMass,
    /// `|‖P̃_N‖ − ∫_0^1 Λ(T)|`: distance to the continuum pressure mass.
    PressureMassError,
    /// `max_j ∫|∂_w X̃_N(t_j)| = max_j (x_N − x_0)(t_j)` (`eq:BV_XN`).
    BvX,
    /// `max_j |(x_N − x_0)(t_j) − (X(t_j,1) − X(t_j,0⁺) + δ)|`.
    BvXError,
    /// `max_{j≥1} ‖∂_w Ũ_N(t_j)‖_{L¹}` (`pwUN-L1`, `α = T/K`).
    TvU,
    /// `max_{j≥1} |‖∂_w Ũ_N(t_j)‖_{L¹} − TV(U(t_j))|`.
    TvUError,
    /// `max_φ |R_mass^N(φ)|` (identically 0 for the particles).
    ResidualMass,
    /// `max_φ |R_mom^N(φ)|` over the test family.
    ResidualMomentum,
    /// `max_φ |⟨(1 − ρ_N) p_N, φ⟩|` (paper's representative).
    Complementarity,
    /// `max_{j≥1} max_i t(u_i − u_{i−1})/(x_i − x_{i−1})` (must be `< 1`,
    /// `eq:Oleinik-tUN`).
    Oleinik,
    /// `max_j max ρ̃_N(t_j)` (must be `≤ 1`).
    MaxDensity,
    /// `max_j max_i N|λ_i(t_j)|`: `eq:sup-micro-u-L` claims it bounded
    /// independently of N.
    NLambda,
}

impl Quantity {
    /// Every quantity, in column order.
    pub const ALL: [Quantity; 16] = [
        Quantity::XL2,
        Quantity::XL2End,
        Quantity::UL1,
        Quantity::LambdaL2,
        Quantity::PressureMass,
        Quantity::PressureMassError,
        Quantity::BvX,
        Quantity::BvXError,
        Quantity::TvU,
        Quantity::TvUError,
        Quantity::ResidualMass,
        Quantity::ResidualMomentum,
        Quantity::Complementarity,
        Quantity::Oleinik,
        Quantity::MaxDensity,
        Quantity::NLambda,
    ];
    /// The CSV column name.
    pub fn key(self) -> &'static str {
        match self {
            Quantity::XL2 => "x_l2",
            Quantity::XL2End => "x_l2_end",
            Quantity::UL1 => "u_l1",
            Quantity::LambdaL2 => "lambda_l2",
            Quantity::PressureMass => "pressure_mass",
            Quantity::PressureMassError => "pressure_mass_error",
            Quantity::BvX => "bv_x",
            Quantity::BvXError => "bv_x_error",
            Quantity::TvU => "tv_u",
            Quantity::TvUError => "tv_u_error",
            Quantity::ResidualMass => "residual_mass",
            Quantity::ResidualMomentum => "residual_momentum",
            Quantity::Complementarity => "complementarity",
            Quantity::Oleinik => "oleinik",
            Quantity::MaxDensity => "max_density",
            Quantity::NLambda => "n_lambda",
        }
    }
    /// A chart title, with the paper's label.
    pub fn label(self) -> &'static str {
        match self {
            Quantity::XL2 => "max_t ‖X_N − X‖_L² (prop:cvg1)",
            Quantity::XL2End => "‖X_N(T) − X(T)‖_L²",
            Quantity::UL1 => "max_t ‖U_N − U‖_L¹ (prop:2ndorder-LagrPDE)",
            Quantity::LambdaL2 => "max_t ‖Λ_N − Λ‖_L² (prop:cvg1)",
            Quantity::PressureMass => "‖P̃_N‖_M(0,T;L¹) (prop:pressure-bound)",
            Quantity::PressureMassError => "|‖P̃_N‖ − ∫Λ(T)| (prop:pressure-bound)",
            Quantity::BvX => "max_t ∫|∂_w X̃_N| (eq:BV_XN)",
            Quantity::BvXError => "|∫|∂_w X̃_N| − (spread + δ)| (eq:BV_XN)",
            Quantity::TvU => "max_t ‖∂_w Ũ_N‖_L¹ (pwUN-L1)",
            Quantity::TvUError => "|‖∂_w Ũ_N‖_L¹ − TV(U)| (pwUN-L1)",
            Quantity::ResidualMass => "max_φ |mass residual| (eq:macro-euler)",
            Quantity::ResidualMomentum => "max_φ |momentum residual| (eq:macro-euler)",
            Quantity::Complementarity => "max_φ |⟨(1−ρ_N)p_N, φ⟩| (eq:macro-euler)",
            Quantity::Oleinik => "max t ∂_w Ũ_N/∂_w X̃_N (eq:Oleinik-tUN, < 1)",
            Quantity::MaxDensity => "max ρ̃_N (≤ 1)",
            Quantity::NLambda => "max_t max_i N|λ_i| (eq:sup-micro-u-L)",
        }
    }
    /// `true` for the quantities expected to tend to 0 (whose rate is fitted).
    pub fn tends_to_zero(self) -> bool {
        !matches!(
            self,
            Quantity::PressureMass
                | Quantity::BvX
                | Quantity::TvU
                | Quantity::Oleinik
                | Quantity::MaxDensity
                | Quantity::NLambda
        )
    }
}

/// One N.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "json", derive(serde::Serialize, serde::Deserialize))]
pub struct Row {
    /// N.
    pub n: usize,
    /// The engine.
    pub engine: Engine,
    /// `true` when the comparisons with the continuum were exact.
    pub exact_comparisons: bool,
    /// Wall-clock seconds for this row.
    #[cfg_attr(feature = "json", serde(with = "crate::campaign::bits::one"))]
    pub seconds: f64,
    /// Number of collisions up to `T`.
    pub collisions: usize,
    /// The measured quantities, in [`Quantity::ALL`] order.
    pub values: Vec<(Quantity, Measure)>,
}

impl Row {
    /// The measure of `q`.
    pub fn get(&self, q: Quantity) -> Option<&Measure> {
        self.values.iter().find(|(k, _)| *k == q).map(|(_, m)| m)
    }
}

/// A fitted log-log rate.
#[derive(Debug, Clone, PartialEq)]
pub struct Rate {
    /// The quantity.
    pub quantity: Quantity,
    /// Number of points used (values > 0 and above 100 × their bound).
    pub points: usize,
    /// Least-squares slope of `ln q` against `ln N` over all points.
    pub slope_all: f64,
    /// The same over the points with `N ≥ 256` (the asymptotic range).
    pub slope_tail: f64,
    /// What the numbers say.
    pub verdict: String,
}

/// Least-squares slope of `ln v` against `ln N` ([`log_log_slope`]).
fn fit(points: &[(usize, f64)]) -> f64 {
    let pts: Vec<(f64, f64)> = points.iter().map(|&(n, v)| (n as f64, v)).collect();
    log_log_slope(&pts)
}

/// The fitted rates of every quantity.
pub fn rates(rows: &[Row]) -> Vec<Rate> {
    let mut out = Vec::new();
    for q in Quantity::ALL {
        let all: Vec<(usize, f64)> = rows
            .iter()
            .filter_map(|r| r.get(q).map(|m| (r.n, m)))
            .filter(|(_, m)| m.value > 0.0 && m.value > 100.0 * m.bound)
            .map(|(n, m)| (n, m.value))
            .collect();
        let tail: Vec<(usize, f64)> = all.iter().copied().filter(|(n, _)| *n >= 256).collect();
        let slope_all = fit(&all);
        let slope_tail = fit(&tail);
        let zeros = rows.iter().filter_map(|r| r.get(q)).all(|m| m.value == 0.0);
        // The first N from which the value is 0 for every larger N.
        let zero_from = rows
            .iter()
            .rev()
            .take_while(|r| r.get(q).is_some_and(|m| m.value == 0.0))
            .last()
            .map(|r| r.n);
        let s = if slope_tail.is_nan() {
            slope_all
        } else {
            slope_tail
        };
        let verdict = if zeros {
            "exactly 0 for every N".to_string()
        } else if let Some(n0) = zero_from {
            format!("exactly 0 for N ≥ {n0} (at the sample times)")
        } else if s.is_nan() {
            "too few points above the error bound to fit".to_string()
        } else if !q.tends_to_zero() {
            if s.abs() < 0.05 {
                format!("bounded, converges to a positive limit (log-log slope {s:.3})")
            } else if s < 0.0 {
                format!("decreasing (log-log slope {s:.3})")
            } else {
                format!("grows like N^{s:.2}")
            }
        } else if s < -0.1 {
            format!("converges to 0 at rate N^{s:.2}")
        } else if s.abs() <= 0.1 {
            format!("does not converge (log-log slope {s:.3})")
        } else {
            format!("grows like N^{s:.2}")
        };
        out.push(Rate {
            quantity: q,
            points: all.len(),
            slope_all,
            slope_tail,
            verdict,
        });
    }
    out
}
