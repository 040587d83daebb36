//! Errors of a floating-point result, measured exactly.
//!
//! Every `f64` of an [`Output`] is converted to the rational it denotes
//! ([`Scalar::to_big_rational`], exact: an `f64` is a dyadic rational) and
//! compared with the exact solution at the exact time: `x(t)` and the right
//! derivative `u(t)` from [`crate::projection::state_at`]
//! (`eq:proj-micro-x`, `eq:proj-u-micro`), `λ(t)` of `eq:dyn-micro`, and
//! Appendix A's `μ(t)` ([`crate::contact::kkt_multipliers`] of the exact
//! projection). No error is ever rounded before it is reported: [`Errors`]
//! holds rationals, and [`Errors::to_f64`] is a view for tables and charts.
//!
//! Measured:
//!
//! * max position, velocity, `λ` and `μ` errors (`max_i |a_i − b_i|`);
//! * cluster structure: the pairs the method reports in contact but the exact
//!   solution does not (spurious) and the converse (missed), against the
//!   exact contact set `Ω_{x(t)}` (`df:Omega-micro`);
//! * the worst constraint value `min_i (x_{i+1} − x_i − 2r)` of the method's
//!   positions (`df:KN`; negative = overlap);
//! * signs: the smallest `λ_i` (`eq:dyn-micro` wants `λ ≥ 0`) and the
//!   smallest pressure jump the method reports (`prop:micro-pressure` wants
//!   `p ≥ 0`);
//! * `prop:Oleinik` (`(u_i − u_{i−1})/(x_i − x_{i−1}) < 1/t` for `t > 0`):
//!   the number of pairs of the method's result that violate it, checked
//!   exactly as `t (u_i − u_{i−1}) ≥ x_i − x_{i−1}`; a pair whose order is
//!   lost (`x_i ≤ x_{i−1}`) counts as a violation.
//!
//! [`compare`] measures another solver's answer already
//! read as rationals (`sticky compare`): the same metrics, plus the `L²`
//! errors, which pairs overlap and by how much, which clusters are wrong,
//! and the sign and complementarity of its `λ`.

use num_rational::BigRational;
use num_traits::{Signed, Zero};

use crate::contact::kkt_multipliers;
use crate::initial::InitialData;
use crate::projection::{project_at, state_at};
use crate::reduced::{difference, product};
use crate::scalar::Scalar;
use crate::state::State;

use super::{Output, SolverError};

mod comparison;

pub use comparison::{
    candidate_gaps, compare, compare_with_gaps, Candidate, CompareError, Comparison, MaxError,
    Overlap, PairValue,
};

/// The exact errors of one [`Output`].
#[derive(Debug, Clone, PartialEq)]
pub struct Errors {
    /// `max_i |x_i − x_i(t)|`.
    pub position: BigRational,
    /// `max_i |u_i − u_i(t)|` against the right derivative (`None` when the
    /// method gives no velocities).
    pub velocity: Option<BigRational>,
    /// `max_i |λ_i − λ_i(t)|` (`eq:dyn-micro`; `None` when not given or
    /// `N = 1`).
    pub lambda: Option<BigRational>,
    /// `max_i |μ_i − μ_i(t)|` (Appendix A; `None` when not given or `N = 1`).
    pub kkt: Option<BigRational>,
    /// Pairs in contact in the exact solution that the method does not
    /// report in contact.
    pub missed_contacts: usize,
    /// Pairs the method reports in contact that are not in contact in the
    /// exact solution.
    pub spurious_contacts: usize,
    /// `min_i (x_{i+1} − x_i − 2r)` of the method's positions (negative =
    /// overlap, `df:KN` violated; `None` when `N = 1`).
    pub min_gap: Option<BigRational>,
    /// The smallest `λ_i` the method reports (`None` when not given or
    /// `N = 1`).
    pub min_lambda: Option<BigRational>,
    /// The smallest pressure jump the method reports
    /// ([`Output::min_pressure_jump`]).
    pub min_pressure_jump: Option<BigRational>,
    /// Pairs violating `prop:Oleinik` (`None` when `t = 0` or no velocities).
    pub oleinik_violations: Option<usize>,
}

impl Errors {
    /// Missed plus spurious contacts: the number of pairs whose contact
    /// status differs from the exact one.
    pub fn cluster_mismatch(&self) -> usize {
        self.missed_contacts + self.spurious_contacts
    }

    /// The nearest-`f64` view, for reports.
    pub fn to_f64(&self) -> ErrorsF64 {
        let f = |q: &BigRational| q.to_f64_lossy();
        ErrorsF64 {
            position: f(&self.position),
            velocity: self.velocity.as_ref().map(f),
            lambda: self.lambda.as_ref().map(f),
            kkt: self.kkt.as_ref().map(f),
            missed_contacts: self.missed_contacts,
            spurious_contacts: self.spurious_contacts,
            min_gap: self.min_gap.as_ref().map(f),
            min_lambda: self.min_lambda.as_ref().map(f),
            min_pressure_jump: self.min_pressure_jump.as_ref().map(f),
            oleinik_violations: self.oleinik_violations,
        }
    }
}

impl ErrorsF64 {
    /// Missed plus spurious contacts.
    pub fn cluster_mismatch(&self) -> usize {
        self.missed_contacts + self.spurious_contacts
    }
}

/// [`Errors`] rounded to `f64` (for tables and charts only). In JSON (the
/// atlas's shard files) each double is its bit pattern
/// (`campaign::bits`, with the `json` feature).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "json", derive(serde::Serialize, serde::Deserialize))]
pub struct ErrorsF64 {
    /// See [`Errors::position`].
    #[cfg_attr(feature = "json", serde(with = "crate::campaign::bits::one"))]
    pub position: f64,
    /// See [`Errors::velocity`].
    #[cfg_attr(feature = "json", serde(with = "crate::campaign::bits::maybe"))]
    pub velocity: Option<f64>,
    /// See [`Errors::lambda`].
    #[cfg_attr(feature = "json", serde(with = "crate::campaign::bits::maybe"))]
    pub lambda: Option<f64>,
    /// See [`Errors::kkt`].
    #[cfg_attr(feature = "json", serde(with = "crate::campaign::bits::maybe"))]
    pub kkt: Option<f64>,
    /// See [`Errors::missed_contacts`].
    pub missed_contacts: usize,
    /// See [`Errors::spurious_contacts`].
    pub spurious_contacts: usize,
    /// See [`Errors::min_gap`].
    #[cfg_attr(feature = "json", serde(with = "crate::campaign::bits::maybe"))]
    pub min_gap: Option<f64>,
    /// See [`Errors::min_lambda`].
    #[cfg_attr(feature = "json", serde(with = "crate::campaign::bits::maybe"))]
    pub min_lambda: Option<f64>,
    /// See [`Errors::min_pressure_jump`].
    #[cfg_attr(feature = "json", serde(with = "crate::campaign::bits::maybe"))]
    pub min_pressure_jump: Option<f64>,
    /// See [`Errors::oleinik_violations`].
    pub oleinik_violations: Option<usize>,
}

/// The exact rational value of every number of `f64` initial data: the
/// exact problem the `f64` solver was actually given. `Err` when a number is
/// not finite or when the exact values are not admissible (a rounding that
/// `f64` validation could not see, e.g. an overlap of less than one ulp).
pub fn exact_input(data: &InitialData<f64>) -> Result<InitialData<BigRational>, SolverError> {
    match data.convert::<BigRational>() {
        None => Err(SolverError::NonFiniteInput {
            what: "data",
            index: 0,
        }),
        Some(Err(e)) => Err(SolverError::Exact {
            message: e.to_string(),
        }),
        Some(Ok(d)) => Ok(d),
    }
}

fn exact(v: &[f64], what: &'static str, len: usize) -> Result<Vec<BigRational>, SolverError> {
    if v.len() != len {
        return Err(SolverError::Mismatch {
            what,
            expected: len,
            found: v.len(),
        });
    }
    v.iter()
        .enumerate()
        .map(|(index, x)| {
            x.to_big_rational()
                .ok_or(SolverError::NonFiniteOutput { what, index })
        })
        .collect()
}

fn max_abs_diff(a: &[BigRational], b: &[BigRational]) -> Option<BigRational> {
    a.iter().zip(b).map(|(p, q)| (p - q).abs()).max()
}

/// The contact set `Ω_{x(t)}` of an exact state (`df:Omega-micro`) as flags
/// on the `N − 1` pairs: `flags[j]` when particles `j` and `j + 1` are in one
/// cluster.
pub fn contact_flags(state: &State<BigRational>) -> Vec<bool> {
    let mut flags = vec![false; state.positions.len().saturating_sub(1)];
    for c in &state.clusters {
        for flag in &mut flags[c.first..c.end() - 1] {
            *flag = true;
        }
    }
    flags
}

/// A result in exact numbers: the method's own values, to be compared with
/// the exact state.
struct Exact<'a> {
    positions: &'a [BigRational],
    velocities: Option<&'a [BigRational]>,
    lambda: Option<&'a [BigRational]>,
    contacts: &'a [bool],
    min_pressure_jump: Option<BigRational>,
}

/// Every metric of [`Errors`] but `kkt` (given), of `own` against the exact
/// state `exact` at time `t` for the radius `2r = two_r`.
fn errors(
    own: Exact<'_>,
    exact: &State<BigRational>,
    kkt: Option<BigRational>,
    two_r: &BigRational,
    t: &BigRational,
) -> Errors {
    let x = own.positions;
    let n = x.len();
    let pairs = n.saturating_sub(1);
    let position = max_abs_diff(x, &exact.positions).unwrap_or_else(<BigRational as Zero>::zero);
    let velocity = own
        .velocities
        .map(|u| max_abs_diff(u, &exact.velocities).unwrap_or_else(<BigRational as Zero>::zero));
    let lambda = own.lambda.and_then(|l| max_abs_diff(l, &exact.multipliers));
    let min_lambda = own.lambda.and_then(|l| l.iter().min().cloned());
    let exact_contact = contact_flags(exact);
    let missed_contacts = (0..pairs)
        .filter(|&j| exact_contact[j] && !own.contacts[j])
        .count();
    let spurious_contacts = (0..pairs)
        .filter(|&j| !exact_contact[j] && own.contacts[j])
        .count();
    let min_gap = (0..pairs).map(|j| x[j + 1].clone() - &x[j] - two_r).min();
    let oleinik_violations = match own.velocities {
        Some(u) if t.is_positive() => Some(oleinik_violations(x, u, t).len()),
        _ => None,
    };
    Errors {
        position,
        velocity,
        lambda,
        kkt,
        missed_contacts,
        spurious_contacts,
        min_gap,
        min_lambda,
        min_pressure_jump: own.min_pressure_jump,
        oleinik_violations,
    }
}

/// Measures `out` exactly against the exact solution at time `t` of `data`
/// (pass [`exact_input`] of the solver's input to measure the method alone,
/// or the original rational data to include the rounding of the input).
pub fn measure(
    out: &Output,
    data: &InitialData<BigRational>,
    t: &BigRational,
) -> Result<Errors, SolverError> {
    let exact_err = |e: crate::Error| SolverError::Exact {
        message: e.to_string(),
    };
    let n = data.n();
    let pairs = n.saturating_sub(1);
    let state = state_at(data, t).map_err(exact_err)?;

    let x = exact(&out.positions, "positions", n)?;
    let u = match &out.velocities {
        Some(v) => Some(exact(v, "velocities", n)?),
        None => None,
    };
    let lambda = match &out.lambda {
        Some(l) => Some(exact(l, "lambda", pairs)?),
        None => None,
    };
    let kkt = match &out.kkt {
        Some(m) => {
            let m = exact(m, "kkt", pairs)?;
            let projected = project_at(data, t);
            let (exact_mu, _) = kkt_multipliers(&projected.shifted_free, &projected.shifted);
            max_abs_diff(&m, &exact_mu)
        }
        None => None,
    };
    if out.contacts.len() != pairs {
        return Err(SolverError::Mismatch {
            what: "contacts",
            expected: pairs,
            found: out.contacts.len(),
        });
    }
    let min_pressure_jump = match out.min_pressure_jump {
        Some(p) => Some(p.to_big_rational().ok_or(SolverError::NonFiniteOutput {
            what: "min_pressure_jump",
            index: 0,
        })?),
        None => None,
    };
    let own = Exact {
        positions: &x,
        velocities: u.as_deref(),
        lambda: lambda.as_deref(),
        contacts: &out.contacts,
        min_pressure_jump,
    };
    Ok(errors(own, &state, kkt, &data.two_r(), t))
}

/// Measures one exact engine's state `own` against another's, `exact`, both
/// at time `t` of data of radius `2r = two_r`, with the same metrics as
/// [`measure`] (`kkt` is not measured: `None`). `min_pressure_jump` is the
/// smallest pressure jump `own`'s engine reports, if any. The atlas measures
/// its exact engines this way, each against the other: their errors are `0`
/// because the two agree, not by assumption.
pub fn measure_state(
    own: &State<BigRational>,
    exact: &State<BigRational>,
    two_r: &BigRational,
    t: &BigRational,
    min_pressure_jump: Option<BigRational>,
) -> Errors {
    let contacts = contact_flags(own);
    let own = Exact {
        positions: &own.positions,
        velocities: Some(&own.velocities),
        lambda: Some(&own.multipliers),
        contacts: &contacts,
        min_pressure_jump,
    };
    errors(own, exact, None, two_r, t)
}

/// `prop:Oleinik` checked exactly on positions `x` and velocities `u` at time
/// `t > 0`: the indices `i` (0-based, for the pair `(i − 1, i)`) with
/// `t (u_i − u_{i−1}) ≥ x_i − x_{i−1}`, i.e. where
/// `(u_i − u_{i−1})/(x_i − x_{i−1}) < 1/t` fails; a pair whose order is lost
/// (`x_i ≤ x_{i−1}`) counts as a violation. Empty for `t ≤ 0`.
pub fn oleinik_violations(x: &[BigRational], u: &[BigRational], t: &BigRational) -> Vec<usize> {
    if !t.is_positive() {
        return Vec::new();
    }
    (1..x.len().min(u.len()))
        .filter(|&i| {
            let dx = difference(&x[i], &x[i - 1]);
            if !dx.is_positive() {
                return true;
            }
            let du = difference(&u[i], &u[i - 1]);
            du.is_positive() && !exceeds(&dx, &product(t, &du))
        })
        .collect()
}

/// `a > b`, by one cross multiplication (denominators are positive):
/// `BigRational`'s own order takes a continued fraction, divisions each.
pub(crate) fn exceeds(a: &BigRational, b: &BigRational) -> bool {
    if a.denom() == b.denom() {
        return a.numer() > b.numer();
    }
    a.numer() * b.denom() > b.numer() * a.denom()
}

/// The largest of `values` (`None` when empty), by [`exceeds`].
pub(crate) fn largest<'a>(
    values: impl IntoIterator<Item = &'a BigRational>,
) -> Option<&'a BigRational> {
    values.into_iter().fold(None, |best, v| match best {
        Some(b) if !exceeds(v, b) => Some(b),
        _ => Some(v),
    })
}
