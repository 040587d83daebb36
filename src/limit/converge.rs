//! The convergence study `N → ∞` (`thm:main` (iii), §3): for quantile
//! samplings of one `[macro]` datum with `N = n_min, 2 n_min, …, n_max`,
//! the distances between the particle interpolations and the exact
//! continuum solution ([`super::continuum`]), the uniform bounds of §3.2–3.3
//! and the weak residuals of `eq:macro-euler` ([`super::eulerian`]), with
//! least-squares log-log rates.
//!
//! **Engines.** `N ≤ exact_max` runs the exact engine
//! (`Trajectory<BigRational>`); larger `N` run the same generic code on
//! `f64` (`Trajectory::<f64>` on `data.convert::<f64>()`). Each row says
//! which. Comparisons with the continuum are exact (`BigRational`) when the
//! engine is exact and the continuum profile is rational at every sample
//! time; otherwise they are computed in `f64` from the exactly computed
//! profile rounded with a rigorous bound (see [`Measure::bound`]). The `f64`
//! engine has no rigorous bound: it is validated by running both engines at
//! `N = exact_max` ([`EngineCheck`]).
//!
//! **Sample times.** `0`, `t_j = T(3j − 1)/(3K)` for `j = 1 … K`
//! (`K = time_samples`), and `T`. The off-grid times keep the plateau ends
//! of the (dyadic) shipped scenes off the particle grid `i/N`, where some
//! errors vanish by accident. Sups over `[0, T]` (or `[α, T]`, `α = t_1`)
//! are maxima over these times, except the pressure mass, which is exact
//! over `[0, T]`.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use num_bigint::BigInt;
use num_rational::BigRational;

use super::continuum::{Continuum, Profile};
use super::eulerian::{
    complementarity_defect, continuum_residuals, oleinik_margin, particle_complementarity,
    particle_momentum_residuals, support_window, test_family, Quadrature, TestFunction,
};
use super::interpolation::{abs, max_of, PressureMeasure, Snapshot};
use super::surd::Surd;
use crate::error::Error;
use crate::quantile::MacroDatum;
use crate::scalar::Scalar;
use crate::scene::{Scene, SceneKind};
use crate::trajectory::Trajectory;

/// Options of [`converge`].
#[derive(Debug, Clone, PartialEq)]
pub struct ConvergeOptions {
    /// Smallest N (rounded up to a power of two, at least 2).
    pub n_min: usize,
    /// Largest N.
    pub n_max: usize,
    /// Largest N run by the exact engine.
    pub exact_max: usize,
    /// The horizon `T` (default: the scene's `t_end`, else 1).
    pub t_end: Option<BigRational>,
    /// `K`: the sample times are `0`, `T(3j − 1)/(3K)` (`j = 1 … K`), `T`.
    pub time_samples: usize,
    /// `δ` of the artificial particle (`df:x0`).
    pub delta: BigRational,
    /// Panels of the time quadrature of the continuum residuals (0: skip
    /// the continuum residuals).
    pub panels: usize,
}

impl Default for ConvergeOptions {
    fn default() -> Self {
        ConvergeOptions {
            n_min: 8,
            n_max: 1 << 16,
            exact_max: 1 << 12,
            t_end: None,
            time_samples: 8,
            delta: BigRational::from_integer(1.into()),
            panels: 16,
        }
    }
}

/// Which engine computed a row.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Engine {
    /// `BigRational`, exact.
    Exact,
    /// `f64`.
    Float,
}

impl Engine {
    /// `"exact"` or `"f64"`.
    pub fn name(self) -> &'static str {
        match self {
            Engine::Exact => "exact",
            Engine::Float => "f64",
        }
    }
}

/// One measured number.
#[derive(Debug, Clone, PartialEq)]
pub struct Measure {
    /// The value (nearest double of the exact value when there is one).
    pub value: f64,
    /// A bound on `|value − true value|` from the rounding of the
    /// continuum profile to doubles (`3β` for coefficients within `β`, plus
    /// `√e·(jump + 2·slope·e)` in `L²`, `e·(jump + 2·slope·e)` in `L¹`, for
    /// each breakpoint rounded by `e`), the rounding of exact particle
    /// values (`2ε·max|X|`) and the `f64` summation (`(n + 20)ε` times the
    /// value); 0 for an exact value (the rounding of the exact value to a
    /// double aside).
    /// It does not cover the `f64` particle engine (see [`EngineCheck`]).
    pub bound: f64,
    /// The exact value, when exact and short (a rational `p/q`, or
    /// `sqrt(p/q)` for a norm whose square is rational).
    pub exact: Option<String>,
}

impl Measure {
    fn float(value: f64, bound: f64) -> Self {
        Measure {
            value,
            bound,
            exact: None,
        }
    }
}

/// The quantities of one row.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
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
pub struct Row {
    /// N.
    pub n: usize,
    /// The engine.
    pub engine: Engine,
    /// `true` when the comparisons with the continuum were exact.
    pub exact_comparisons: bool,
    /// Wall-clock seconds for this row.
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

/// The continuum side of the study.
#[derive(Debug, Clone, PartialEq)]
pub struct ContinuumSummary {
    /// `true` when the profile was rational at every sample time.
    pub rational: bool,
    /// Number of plateaus at each sample time.
    pub plateaus: Vec<usize>,
    /// `∫_0^1 Λ(T, w) dw`, the pressure mass on `[0, T]`.
    pub pressure_mass: Measure,
    /// `X(t_j,1) − X(t_j,0⁺)` at each sample time.
    pub spread: Vec<f64>,
    /// `TV(U(t_j))` at each sample time.
    pub tv_u: Vec<f64>,
    /// `∫_0^1 Λ(t_j)`: the pressure mass on `[0, t_j]`, at each sample time.
    pub lambda_integral: Vec<f64>,
    /// `max ρ` over the sample times (≤ 1, `lem:density`).
    pub max_density: Measure,
    /// `max_j t_j sup ∂_x u` (`< 1`; `None` if `u` jumps up without a gap).
    pub oleinik: Option<f64>,
    /// `max |Λ|` outside the plateaus (0: `(∂_w X − 1)Λ = 0`, so
    /// `(1 − ρ)p = 0`).
    pub complementarity_defect: Measure,
    /// Per test function: `(mass residual, momentum residual)`, by
    /// quadrature (exact value 0).
    pub residuals: Vec<(Quadrature, Quadrature)>,
}

/// Both engines at one N: the difference of each quantity.
#[derive(Debug, Clone, PartialEq)]
pub struct EngineCheck {
    /// The N.
    pub n: usize,
    /// `|exact − f64| / max(|exact|, 10⁻³⁰⁰)` per quantity.
    pub differences: Vec<(Quantity, f64)>,
}

/// Everything [`converge`] measured.
#[derive(Debug, Clone, PartialEq)]
pub struct ConvergenceReport {
    /// The scene's name.
    pub scene: String,
    /// `T`.
    pub t_end: BigRational,
    /// The sample times.
    pub times: Vec<BigRational>,
    /// `δ`.
    pub delta: BigRational,
    /// The test functions, by name.
    pub test_functions: Vec<String>,
    /// One row per N.
    pub rows: Vec<Row>,
    /// Per test function and row: `R_mom^N(φ)`.
    pub particle_residuals: Vec<Vec<f64>>,
    /// Fitted rates.
    pub rates: Vec<Rate>,
    /// The continuum.
    pub continuum: ContinuumSummary,
    /// Exact vs f64 engine at `exact_max`, when both ran.
    pub engine_check: Option<EngineCheck>,
}

/// A profile at one sample time, in every form the comparisons need.
struct Sample {
    exact: Option<Profile<BigRational>>,
    float: Profile<f64>,
    /// Rounding bounds of the f64 profile for `X` (L²), `U` (L¹), `Λ` (L²).
    bound_x: f64,
    bound_u: f64,
    bound_l: f64,
    range: f64,
    spread: f64,
    spread_q: Option<BigRational>,
    tv: f64,
    tv_q: Option<BigRational>,
}

impl Sample {
    /// The rounding bounds: every coefficient of the f64 profile is within
    /// `β` of the exact one (`|w| ≤ 1`, so a segment's values are within
    /// `3β`); a breakpoint rounded by `e` moves the values on a set of
    /// measure `e`, by at most the jump there plus `2·slope·e`, which costs
    /// `√e·(jump + 2·slope·e)` in `L²` and `e·(jump + 2·slope·e)` in `L¹`.
    fn new(p: &Profile<Surd>) -> Self {
        let exact = p.to_rational();
        let (float, _) = p.to_f64();
        let mut beta = 0.0f64;
        let mut slope = 0.0f64;
        let mut range = 0.0f64;
        for (s, f) in p.segments.iter().zip(&float.segments) {
            for c in s.x.iter().chain(&s.u).chain(&s.lambda) {
                beta = beta.max(c.to_f64_bounded().1);
            }
            slope = slope
                .max(f.x[1].abs())
                .max(f.u[1].abs())
                .max(f.lambda[1].abs() + 2.0 * f.lambda[2].abs());
            for w in [f.w0, f.w1] {
                let x = f.x[0] + f.x[1] * w;
                range = range.max(x.abs());
            }
        }
        let (mut bound_x, mut bound_u, mut bound_l) = (3.0 * beta, 3.0 * beta, 3.0 * beta);
        for k in 1..float.segments.len() {
            let e = p.segments[k].w0.to_f64_bounded().1;
            if e == 0.0 {
                continue;
            }
            let (a, b) = (&float.segments[k - 1], &float.segments[k]);
            let w = b.w0;
            let jx = (b.x[0] + b.x[1] * w - a.x[0] - a.x[1] * w).abs();
            let ju = (b.u[0] + b.u[1] * w - a.u[0] - a.u[1] * w).abs();
            let lam = |s: &super::continuum::Segment<f64>| {
                s.lambda[0] + s.lambda[1] * w + s.lambda[2] * w * w
            };
            let jl = (lam(b) - lam(a)).abs();
            // The exact jump is within 6β of the rounded one.
            let extra = 6.0 * beta + 2.0 * slope * e;
            bound_x += e.sqrt() * (jx + extra);
            bound_u += e * (ju + extra);
            bound_l += e.sqrt() * (jl + extra);
        }
        Sample {
            spread: float.spread(),
            tv: float.u_total_variation(),
            spread_q: exact.as_ref().map(|e| e.spread()),
            tv_q: exact.as_ref().map(|e| e.u_total_variation()),
            exact,
            float,
            bound_x,
            bound_u,
            bound_l,
            range,
        }
    }
    fn conversion_bound(&self) -> f64 {
        self.bound_x.max(self.bound_u).max(self.bound_l)
    }
}

/// `∫_0^1 (X_N − X)²`, exact on exact inputs: cells `((i−1)/N, i/N]`
/// against the profile's affine pieces (`∫ g² = h(g₀² + g₀g₁ + g₁²)/3`).
pub fn x_l2_squared<V: Scalar>(x: &[V], profile: &Profile<V>) -> V {
    let three = V::from_i64(3);
    overlap_sum(x.len(), profile, |i, lo, hi, s| {
        let g0 = x[i - 1].clone() - &(s.x[0].clone() + &(s.x[1].clone() * lo));
        let g1 = x[i - 1].clone() - &(s.x[0].clone() + &(s.x[1].clone() * hi));
        (hi.clone() - lo) * &(g0.clone() * &g0 + &(g0 * &g1) + &(g1.clone() * &g1)) / &three
    })
}

/// `∫_0^1 (U_N − U)²`, exact on exact inputs (as [`x_l2_squared`]).
pub fn u_l2_squared<V: Scalar>(u: &[V], profile: &Profile<V>) -> V {
    let three = V::from_i64(3);
    overlap_sum(u.len(), profile, |i, lo, hi, s| {
        let g0 = u[i - 1].clone() - &(s.u[0].clone() + &(s.u[1].clone() * lo));
        let g1 = u[i - 1].clone() - &(s.u[0].clone() + &(s.u[1].clone() * hi));
        (hi.clone() - lo) * &(g0.clone() * &g0 + &(g0 * &g1) + &(g1.clone() * &g1)) / &three
    })
}

/// `∫_0^1 |U_N − U|`, exact on exact inputs (an affine `g` on `[lo, hi]`:
/// `h|g₀ + g₁|/2` without a sign change, `h(g₀² + g₁²)/(2|g₀ − g₁|)` with one).
pub fn u_l1<V: Scalar>(u: &[V], profile: &Profile<V>) -> V {
    let two = V::from_i64(2);
    overlap_sum(u.len(), profile, |i, lo, hi, s| {
        let g0 = u[i - 1].clone() - &(s.u[0].clone() + &(s.u[1].clone() * lo));
        let g1 = u[i - 1].clone() - &(s.u[0].clone() + &(s.u[1].clone() * hi));
        let h = hi.clone() - lo;
        let s0 = g0.total_cmp(&V::zero());
        let s1 = g1.total_cmp(&V::zero());
        if s0.is_ge() == s1.is_ge() || s0.is_eq() || s1.is_eq() {
            h * &abs(g0 + &g1) / &two
        } else {
            h * &(g0.clone() * &g0 + &(g1.clone() * &g1)) / &(two.clone() * &abs(g0 - &g1))
        }
    })
}

/// `∫_0^1 (Λ_N − Λ)²` with `Λ_N = λ_i` on cell `i` (`λ_N = 0`), exact on
/// exact inputs (`h(g₀² + g₀g₁ + g₁²)/3` where `Λ` is affine, Boole's rule —
/// exact for the degree-4 integrand — where it is quadratic).
pub fn lambda_l2_squared<V: Scalar>(lambda: &[V], profile: &Profile<V>) -> V {
    let c = [7, 32, 12, 32, 7].map(V::from_i64);
    let ninety = V::from_i64(90);
    let four = V::from_i64(4);
    let three = V::from_i64(3);
    overlap_sum(lambda.len(), profile, |i, lo, hi, s| {
        let h = hi.clone() - lo;
        let at = |w: &V| {
            lambda[i - 1].clone()
                - &(s.lambda[0].clone()
                    + &(s.lambda[1].clone() * w)
                    + &(s.lambda[2].clone() * w * w))
        };
        if s.lambda[2].is_zero() {
            let (g0, g1) = (at(lo), at(hi));
            return h * &(g0.clone() * &g0 + &(g0 * &g1) + &(g1.clone() * &g1)) / &three;
        }
        let mut acc = V::zero();
        for (k, ck) in c.iter().enumerate() {
            let g = at(&(lo.clone() + &(h.clone() * &V::from_usize(k) / &four)));
            acc = acc + &(ck.clone() * &g * &g);
        }
        h * &acc / &ninety
    })
}

/// `Σ_i Σ_segments f(i, lo, hi, segment)` over the overlaps of the cells
/// `((i−1)/N, i/N]` with the segments (two pointers, O(N + segments)).
fn overlap_sum<V: Scalar>(
    n: usize,
    profile: &Profile<V>,
    mut f: impl FnMut(usize, &V, &V, &super::continuum::Segment<V>) -> V,
) -> V {
    let nn = V::from_usize(n);
    let segs = &profile.segments;
    let mut total = V::zero();
    let mut k = 0usize;
    for i in 1..=n {
        let lo_c = V::from_usize(i - 1) / &nn;
        let hi_c = V::from_usize(i) / &nn;
        while k < segs.len() && segs[k].w1.total_cmp(&lo_c).is_le() {
            k += 1;
        }
        let mut kk = k;
        while kk < segs.len() && segs[kk].w0.total_cmp(&hi_c).is_lt() {
            let s = &segs[kk];
            let lo = max_of(lo_c.clone(), s.w0.clone());
            let hi = if s.w1.total_cmp(&hi_c).is_lt() {
                s.w1.clone()
            } else {
                hi_c.clone()
            };
            if hi.total_cmp(&lo).is_gt() {
                total = total + &f(i, &lo, &hi, s);
            }
            kk += 1;
        }
    }
    total
}

fn short(q: &BigRational) -> Option<String> {
    let s = q.render();
    (s.len() <= 60).then_some(s)
}

/// A rational measure.
fn exact_measure<S: Scalar>(v: &S) -> Measure {
    let q = if S::EXACT { v.to_big_rational() } else { None };
    Measure {
        value: v.to_f64_lossy(),
        bound: 0.0,
        exact: q.as_ref().and_then(short),
    }
}

/// A norm from its square.
fn norm_measure<S: Scalar>(sq: &S, bound: f64) -> Measure {
    let q = if S::EXACT { sq.to_big_rational() } else { None };
    Measure {
        value: sq.to_f64_lossy().max(0.0).sqrt(),
        bound,
        exact: q.as_ref().and_then(short).map(|s| format!("sqrt({s})")),
    }
}

/// The study's context: datum, continuum samples, test functions.
struct Context {
    datum: MacroDatum,
    times: Vec<BigRational>,
    samples: Vec<Sample>,
    t_end: BigRational,
    delta: BigRational,
    tests: Vec<TestFunction<BigRational>>,
    lambda_end: BigRational,
    lambda_end_f: (f64, f64),
}

/// The particle-side numbers of one row, in the engine's scalar.
struct ParticleSide<S> {
    snaps: Vec<Snapshot<S>>,
    pressure_mass: S,
    residuals: Vec<S>,
    complementarity: Vec<S>,
    rounding: f64,
    collisions: usize,
}

fn particle_side<S: Scalar>(traj: &Trajectory<S>, ctx: &Context) -> Result<ParticleSide<S>, Error> {
    let conv = |q: &BigRational| {
        S::from_big_rational(q).ok_or_else(|| Error::Unsupported {
            message: format!("{} does not fit the engine's scalar", q.render()),
        })
    };
    let delta = conv(&ctx.delta)?;
    let t_end = conv(&ctx.t_end)?;
    let mut snaps = Vec::with_capacity(ctx.times.len());
    for t in &ctx.times {
        let s = traj.at(&conv(t)?)?;
        snaps.push(Snapshot::new(&s, traj.data().velocities(), delta.clone())?);
    }
    let tests: Vec<TestFunction<S>> = ctx
        .tests
        .iter()
        .map(|f| {
            f.convert::<S>().ok_or_else(|| Error::Unsupported {
                message: "test function does not fit the engine's scalar".to_string(),
            })
        })
        .collect::<Result<_, _>>()?;
    let pressure_mass = PressureMeasure::new(traj).mass_until(&t_end);
    let residuals = particle_momentum_residuals(traj, &tests, &t_end)?;
    let complementarity = particle_complementarity(traj, &tests, &t_end, &delta);
    let rounding = residuals.rounding_bound.max(complementarity.rounding_bound);
    let (residuals, complementarity) = (residuals.values, complementarity.values);
    let collisions = traj
        .impulses()
        .iter()
        .filter(|i| i.t.total_cmp(&t_end).is_le())
        .count();
    Ok(ParticleSide {
        snaps,
        pressure_mass,
        residuals,
        complementarity,
        rounding,
        collisions,
    })
}

fn snap_f64<S: Scalar>(s: &Snapshot<S>) -> Snapshot<f64> {
    let f = |v: &[S]| v.iter().map(|x| x.to_f64_lossy()).collect::<Vec<f64>>();
    Snapshot {
        t: s.t.to_f64_lossy(),
        n: s.n,
        delta: s.delta.to_f64_lossy(),
        x: f(&s.x),
        u: f(&s.u),
        u0: f(&s.u0),
        lambda: f(&s.lambda),
    }
}

/// The comparisons `(x_l2², u_l1, λ_l2²)` at one sample, exact when
/// possible.
fn compare<S: Scalar>(snap: &Snapshot<S>, sample: &Sample) -> (Measure, Measure, Measure) {
    let n = snap.n;
    if S::EXACT {
        if let Some(p) = &sample.exact {
            let q = |v: &[S]| -> Option<Vec<BigRational>> {
                v.iter().map(|x| x.to_big_rational()).collect()
            };
            if let (Some(x), Some(u), Some(l)) =
                (q(&snap.x[1..]), q(&snap.u[1..]), q(&snap.lambda[1..]))
            {
                return (
                    norm_measure(&x_l2_squared(&x, p), 0.0),
                    exact_measure(&u_l1(&u, p)),
                    norm_measure(&lambda_l2_squared(&l, p), 0.0),
                );
            }
        }
    }
    let f = snap_f64(snap);
    let p = &sample.float;
    // Summation of n terms, and the rounding of the particle values (an
    // absolute ε·|x| on each) when they come from the exact engine.
    let round = (n as f64 + 20.0) * f64::EPSILON;
    let input = 2.0 * f64::EPSILON * sample.range.max(1.0);
    let x2 = x_l2_squared(&f.x[1..], p);
    let u1 = u_l1(&f.u[1..], p);
    let l2 = lambda_l2_squared(&f.lambda[1..], p);
    (
        Measure::float(
            x2.max(0.0).sqrt(),
            sample.bound_x + input + round * x2.max(0.0).sqrt(),
        ),
        Measure::float(u1, sample.bound_u + input + round * u1),
        Measure::float(
            l2.max(0.0).sqrt(),
            sample.bound_l + input + round * l2.max(0.0).sqrt(),
        ),
    )
}

fn max_measure(a: Measure, b: Measure) -> Measure {
    if b.value > a.value {
        Measure {
            bound: a.bound.max(b.bound),
            ..b
        }
    } else {
        Measure {
            bound: a.bound.max(b.bound),
            ..a
        }
    }
}

fn row_from<S: Scalar>(
    ps: &ParticleSide<S>,
    ctx: &Context,
    n: usize,
    engine: Engine,
    seconds: f64,
) -> Row {
    let zero = || Measure {
        value: 0.0,
        bound: 0.0,
        exact: Some("0".to_string()),
    };
    let (mut xl2, mut ul1, mut ll2) = (zero(), zero(), zero());
    let mut xl2_end = zero();
    let mut bv = S::zero();
    let (mut bv_err, mut tv_err) = (zero(), zero());
    let mut tv = S::zero();
    let mut ole = S::zero();
    let mut dens = S::zero();
    let mut nlambda = S::zero();
    let mut exact_cmp = S::EXACT;
    let delta_f = ctx.delta.to_f64_lossy();
    for (j, (snap, sample)) in ps.snaps.iter().zip(&ctx.samples).enumerate() {
        exact_cmp &= sample.exact.is_some();
        let (x, u, l) = compare(snap, sample);
        if j + 1 == ps.snaps.len() {
            xl2_end = x.clone();
        }
        xl2 = max_measure(xl2, x);
        bv = max_of(bv, snap.bv_x());
        dens = max_of(dens, snap.max_density());
        nlambda = snap.lambda.iter().fold(nlambda, |m, l| {
            max_of(m, abs(l.clone()) * &S::from_usize(n))
        });
        // eq:BV_XN against its limit X(t,1) − X(t,0⁺) + δ.
        let bv_e = match (&sample.spread_q, S::EXACT, snap.bv_x().to_big_rational()) {
            (Some(sq), true, Some(b)) => exact_measure(&abs(b - sq - &ctx.delta)),
            _ => Measure::float(
                (snap.bv_x().to_f64_lossy() - sample.spread - delta_f).abs(),
                sample.conversion_bound() + 4.0 * f64::EPSILON,
            ),
        };
        bv_err = max_measure(bv_err, bv_e);
        if j == 0 {
            continue;
        }
        ul1 = max_measure(ul1, u);
        ll2 = max_measure(ll2, l);
        tv = max_of(tv, snap.tv_u());
        ole = max_of(ole, snap.oleinik_margin());
        let tv_e = match (&sample.tv_q, S::EXACT, snap.tv_u().to_big_rational()) {
            (Some(tq), true, Some(b)) => exact_measure(&abs(b - tq)),
            _ => Measure::float(
                (snap.tv_u().to_f64_lossy() - sample.tv).abs(),
                sample.conversion_bound() + (n as f64 + 20.0) * f64::EPSILON * sample.tv,
            ),
        };
        tv_err = max_measure(tv_err, tv_e);
    }
    let pm = exact_measure(&ps.pressure_mass);
    let pm_err = if S::EXACT {
        match ps.pressure_mass.to_big_rational() {
            Some(p) if ctx.samples.last().is_some_and(|s| s.exact.is_some()) => {
                exact_measure(&abs(p - &ctx.lambda_end))
            }
            _ => Measure::float(
                (ps.pressure_mass.to_f64_lossy() - ctx.lambda_end_f.0).abs(),
                ctx.lambda_end_f.1,
            ),
        }
    } else {
        Measure::float(
            (ps.pressure_mass.to_f64_lossy() - ctx.lambda_end_f.0).abs(),
            ctx.lambda_end_f.1 + (ps.collisions as f64 + 20.0) * f64::EPSILON * pm.value,
        )
    };
    let resid = ps
        .residuals
        .iter()
        .fold(S::zero(), |m, r| max_of(m, abs(r.clone())));
    let compl = ps
        .complementarity
        .iter()
        .fold(S::zero(), |m, r| max_of(m, abs(r.clone())));
    let float_bound = |v: &S| {
        if S::EXACT {
            ps.rounding
        } else {
            (ps.collisions as f64 + 20.0) * 16.0 * f64::EPSILON * v.to_f64_lossy().abs()
        }
    };
    let values = vec![
        (Quantity::XL2, xl2),
        (Quantity::XL2End, xl2_end),
        (Quantity::UL1, ul1),
        (Quantity::LambdaL2, ll2),
        (Quantity::PressureMass, pm),
        (Quantity::PressureMassError, pm_err),
        (Quantity::BvX, exact_measure(&bv)),
        (Quantity::BvXError, bv_err),
        (Quantity::TvU, exact_measure(&tv)),
        (Quantity::TvUError, tv_err),
        (Quantity::ResidualMass, zero()),
        (
            Quantity::ResidualMomentum,
            Measure {
                bound: float_bound(&resid),
                ..exact_measure(&resid)
            },
        ),
        (
            Quantity::Complementarity,
            Measure {
                bound: float_bound(&compl),
                ..exact_measure(&compl)
            },
        ),
        (Quantity::Oleinik, exact_measure(&ole)),
        (
            Quantity::MaxDensity,
            Measure {
                // f64: a contact gap 1/N between positions of size ≲ bv_x
                // is computed with an error ≤ 2ε·bv_x, i.e. a relative
                // error ≤ 2ε·N·bv_x on the density.
                bound: if S::EXACT {
                    0.0
                } else {
                    4.0 * f64::EPSILON * n as f64 * bv.to_f64_lossy().abs().max(1.0)
                },
                ..exact_measure(&dens)
            },
        ),
        (Quantity::NLambda, exact_measure(&nlambda)),
    ];
    Row {
        n,
        engine,
        exact_comparisons: exact_cmp,
        seconds,
        collisions: ps.collisions,
        values,
    }
}

fn run_n(ctx: &Context, n: usize, engine: Engine) -> Result<(Row, Vec<f64>), Error> {
    let start = Instant::now();
    let data = ctx.datum.sample(n)?;
    match engine {
        Engine::Exact => {
            let traj = Trajectory::new(data);
            let ps = particle_side(&traj, ctx)?;
            let res = ps.residuals.iter().map(|r| r.to_f64_lossy()).collect();
            Ok((
                row_from(&ps, ctx, n, engine, start.elapsed().as_secs_f64()),
                res,
            ))
        }
        Engine::Float => {
            let data = data.convert::<f64>().ok_or_else(|| Error::Unsupported {
                message: format!("the sample with N = {n} does not fit f64"),
            })??;
            let traj = Trajectory::new(data);
            let ps = particle_side(&traj, ctx)?;
            let res = ps.residuals.clone();
            Ok((
                row_from(&ps, ctx, n, engine, start.elapsed().as_secs_f64()),
                res,
            ))
        }
    }
}

/// Least-squares slope of `ln v` against `ln n` (also used for the cost
/// scaling of `sticky bench --scaling`).
pub(crate) fn fit(points: &[(usize, f64)]) -> f64 {
    if points.len() < 2 {
        return f64::NAN;
    }
    let k = points.len() as f64;
    let xs: Vec<f64> = points.iter().map(|(n, _)| (*n as f64).ln()).collect();
    let ys: Vec<f64> = points.iter().map(|(_, v)| v.ln()).collect();
    let mx = xs.iter().sum::<f64>() / k;
    let my = ys.iter().sum::<f64>() / k;
    let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xs.iter().map(|x| (x - mx).powi(2)).sum();
    sxy / sxx
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

/// The powers of two from `n_min` to `n_max`.
pub fn n_values(opts: &ConvergeOptions) -> Vec<usize> {
    let mut n = opts.n_min.max(2).next_power_of_two();
    let mut out = Vec::new();
    while n <= opts.n_max {
        out.push(n);
        n *= 2;
    }
    out
}

/// Runs the study on a `[macro]` scene (see the module documentation).
pub fn converge(scene: &Scene, opts: &ConvergeOptions) -> Result<ConvergenceReport, Error> {
    converge_with_progress(scene, opts, &mut |_| {})
}

/// [`converge`], calling `progress` after each row.
pub fn converge_with_progress(
    scene: &Scene,
    opts: &ConvergeOptions,
    progress: &mut dyn FnMut(&Row),
) -> Result<ConvergenceReport, Error> {
    let SceneKind::Macro { datum, .. } = &scene.kind else {
        return Err(Error::Unsupported {
            message: "the convergence study needs a [macro] scene (a macroscopic datum to sample)"
                .to_string(),
        });
    };
    if opts.n_max > crate::scene::MAX_MACRO_PARTICLES {
        return Err(Error::Unsupported {
            message: format!(
                "N = {} exceeds the limit of {} particles",
                opts.n_max,
                crate::scene::MAX_MACRO_PARTICLES
            ),
        });
    }
    let t_end = opts
        .t_end
        .clone()
        .or_else(|| scene.t_end.clone())
        .unwrap_or_else(|| BigRational::from_integer(1.into()));
    if t_end <= BigRational::from_integer(0.into()) {
        return Err(Error::Unsupported {
            message: format!("the horizon T must be positive, got {}", t_end.render()),
        });
    }
    if opts.delta <= BigRational::from_integer(0.into()) {
        return Err(Error::Unsupported {
            message: format!("δ must be positive, got {}", opts.delta.render()),
        });
    }
    let k = opts.time_samples.max(1);
    let mut times = vec![BigRational::from_integer(0.into())];
    times.extend(
        (1..=k).map(|j| &t_end * BigRational::new(BigInt::from(3 * j - 1), BigInt::from(3 * k))),
    );
    times.push(t_end.clone());
    let continuum = Continuum::new(datum);
    let profiles: Vec<Profile<Surd>> = times
        .iter()
        .map(|t| continuum.profile(t))
        .collect::<Result<_, _>>()?;
    let samples: Vec<Sample> = profiles.iter().map(Sample::new).collect();
    let (center, scale) = support_window(&continuum, &t_end);
    let tests = test_family(&t_end, &center, &scale);
    let last = samples.last().ok_or_else(|| Error::Unsupported {
        message: "no sample time".to_string(),
    })?;
    let lambda_end = last.exact.as_ref().map(|p| p.lambda_integral());
    let lambda_end_f = {
        let v = last.float.lambda_integral();
        (
            v,
            last.conversion_bound() * 2.0 + 64.0 * f64::EPSILON * v.abs(),
        )
    };
    let ctx = Context {
        datum: datum.clone(),
        times: times.clone(),
        samples,
        t_end: t_end.clone(),
        delta: opts.delta.clone(),
        tests,
        lambda_end: lambda_end
            .clone()
            .unwrap_or_else(|| BigRational::from_integer(0.into())),
        lambda_end_f,
    };
    let ns = n_values(opts);
    if ns.is_empty() {
        return Err(Error::Unsupported {
            message: format!("no power of two N with {} ≤ N ≤ {}", opts.n_min, opts.n_max),
        });
    }
    let mut rows = Vec::new();
    let mut residual_columns = Vec::new();
    for n in ns {
        let engine = if n <= opts.exact_max {
            Engine::Exact
        } else {
            Engine::Float
        };
        let (row, res) = run_n(&ctx, n, engine)?;
        progress(&row);
        rows.push(row);
        residual_columns.push(res);
    }
    let engine_check = match rows.iter().rev().find(|r| r.engine == Engine::Exact) {
        Some(r) if opts.n_max > opts.exact_max => {
            let (f, _) = run_n(&ctx, r.n, Engine::Float)?;
            let differences = Quantity::ALL
                .iter()
                .filter_map(|&q| {
                    let (a, b) = (r.get(q)?.value, f.get(q)?.value);
                    Some((q, (a - b).abs() / a.abs().max(1e-300)))
                })
                .collect();
            Some(EngineCheck {
                n: r.n,
                differences,
            })
        }
        _ => None,
    };
    let particle_residuals = (0..ctx.tests.len())
        .map(|k| {
            residual_columns
                .iter()
                .map(|c| c.get(k).copied().unwrap_or(f64::NAN))
                .collect()
        })
        .collect();
    // The continuum side.
    let rational = ctx.samples.iter().all(|s| s.exact.is_some());
    let mut max_density = Measure::float(0.0, 0.0);
    let mut oleinik = Some(0.0f64);
    let mut defect = Measure::float(0.0, 0.0);
    for (s, p) in ctx.samples.iter().zip(&profiles) {
        let m = match &s.exact {
            Some(e) => exact_measure(&e.max_density()),
            None => Measure::float(s.float.max_density(), s.conversion_bound()),
        };
        max_density = max_measure(max_density, m);
        let d = match &s.exact {
            Some(e) => exact_measure(&complementarity_defect(e)),
            None => Measure::float(complementarity_defect(&s.float), s.conversion_bound()),
        };
        defect = max_measure(defect, d);
        let t = p.t.to_f64_lossy();
        let tol = 4.0 * s.conversion_bound() + 16.0 * f64::EPSILON * s.range;
        oleinik = match (oleinik, oleinik_margin(&s.float, &t, &tol)) {
            (Some(a), Some(b)) => Some(a.max(b)),
            _ => None,
        };
    }
    let residuals = if opts.panels > 0 {
        continuum_residuals(&continuum, &ctx.tests, opts.panels)?
    } else {
        Vec::new()
    };
    let pressure_mass = match &lambda_end {
        Some(q) => exact_measure(q),
        None => Measure::float(ctx.lambda_end_f.0, ctx.lambda_end_f.1),
    };
    let summary = ContinuumSummary {
        rational,
        plateaus: profiles.iter().map(|p| p.plateaus.len()).collect(),
        pressure_mass,
        spread: ctx.samples.iter().map(|s| s.spread).collect(),
        tv_u: ctx.samples.iter().map(|s| s.tv).collect(),
        lambda_integral: ctx
            .samples
            .iter()
            .map(|s| s.float.lambda_integral())
            .collect(),
        max_density,
        oleinik,
        complementarity_defect: defect,
        residuals,
    };
    Ok(ConvergenceReport {
        scene: scene.name.clone().unwrap_or_else(|| "scene".to_string()),
        t_end,
        times,
        delta: opts.delta.clone(),
        test_functions: ctx.tests.iter().map(|f| f.name()).collect(),
        rates: rates(&rows),
        rows,
        particle_residuals,
        continuum: summary,
        engine_check,
    })
}

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

/// Writes `contents` to `dir/name` whole (a temporary name, then a rename).
fn write_whole(dir: &Path, name: &str, contents: &str) -> Result<PathBuf, Error> {
    let io = |e: std::io::Error| Error::Io {
        message: format!("{}: {e}", dir.join(name).display()),
    };
    std::fs::create_dir_all(dir).map_err(io)?;
    let path = dir.join(name);
    let tmp = dir.join(format!(".{name}.tmp-{}", std::process::id()));
    std::fs::write(&tmp, contents).map_err(io)?;
    std::fs::rename(&tmp, &path).map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        io(e)
    })?;
    Ok(path)
}

fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// Writes `convergence.csv` (one row per N: every quantity with its bound
/// and exact form), `rates.csv`, `continuum.csv` (per sample time) and
/// `residuals.csv` (per test function: the continuum residuals and
/// `R_mom^N` for every N) into `dir`; returns the paths written.
pub fn write_csv(report: &ConvergenceReport, dir: &Path) -> Result<Vec<PathBuf>, Error> {
    let mut out = Vec::new();
    let mut c = String::from("n,engine,exact_comparisons,seconds,collisions");
    for q in Quantity::ALL {
        let _ = write!(c, ",{k},{k}_bound,{k}_exact", k = q.key());
    }
    c.push('\n');
    for r in &report.rows {
        let _ = write!(
            c,
            "{},{},{},{:.6},{}",
            r.n,
            r.engine.name(),
            r.exact_comparisons,
            r.seconds,
            r.collisions
        );
        for q in Quantity::ALL {
            match r.get(q) {
                Some(m) => {
                    let _ = write!(
                        c,
                        ",{:e},{:e},{}",
                        m.value,
                        m.bound,
                        csv_field(m.exact.as_deref().unwrap_or(""))
                    );
                }
                None => c.push_str(",,,"),
            }
        }
        c.push('\n');
    }
    out.push(write_whole(dir, "convergence.csv", &c)?);
    let mut r = String::from("quantity,label,points,slope_all,slope_tail,verdict\n");
    for rate in &report.rates {
        let _ = writeln!(
            r,
            "{},{},{},{},{},{}",
            rate.quantity.key(),
            csv_field(rate.quantity.label()),
            rate.points,
            rate.slope_all,
            rate.slope_tail,
            csv_field(&rate.verdict)
        );
    }
    out.push(write_whole(dir, "rates.csv", &r)?);
    let cs = &report.continuum;
    let mut t = String::from("t,plateaus,spread,tv_u,lambda_integral\n");
    for (j, time) in report.times.iter().enumerate() {
        let _ = writeln!(
            t,
            "{},{},{:e},{:e},{:e}",
            time.render(),
            cs.plateaus.get(j).copied().unwrap_or(0),
            cs.spread.get(j).copied().unwrap_or(f64::NAN),
            cs.tv_u.get(j).copied().unwrap_or(f64::NAN),
            cs.lambda_integral.get(j).copied().unwrap_or(f64::NAN)
        );
    }
    out.push(write_whole(dir, "continuum.csv", &t)?);
    let mut s = String::from("test_function,continuum_mass,continuum_mass_error,continuum_momentum,continuum_momentum_error");
    for row in &report.rows {
        let _ = write!(s, ",particles_N{}", row.n);
    }
    s.push('\n');
    for (k, name) in report.test_functions.iter().enumerate() {
        let (m, p) = cs
            .residuals
            .get(k)
            .map_or((f64::NAN, f64::NAN), |r| (r.0.value, r.1.value));
        let (me, pe) = cs
            .residuals
            .get(k)
            .map_or((f64::NAN, f64::NAN), |r| (r.0.error, r.1.error));
        let _ = write!(s, "{},{m:e},{me:e},{p:e},{pe:e}", csv_field(name));
        for v in report.particle_residuals.get(k).into_iter().flatten() {
            let _ = write!(s, ",{v:e}");
        }
        s.push('\n');
    }
    out.push(write_whole(dir, "residuals.csv", &s)?);
    Ok(out)
}
