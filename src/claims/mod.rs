//! The claims ledger: one checker per claim of the paper.
//!
//! Every checker is a plain function returning `Result<(), Violation>`; the
//! [`Violation`] names the claim by the paper's `\label` (plus `#step` for a
//! step inside a proof) and carries the exact witness. The ledger runner
//! ([`ledger`]), the unit tests, proptest (`prop_*`), quickcheck (`qc_*`), the
//! bounded-exhaustive proofs (`verify_*`) and the fuzz targets all iterate
//! the same [`registry`](fn@registry), so every engine checks every claim with the same
//! code (Firecracker reuses one `is_valid()`; memchr runs one oracle battery
//! against every implementation).
//!
//! A claim found false stays reported false: its [`Claim::correction`] (a
//! corrected statement, itself checked by every engine) is what the test
//! suites require to hold; the original's status is computed by the ledger.

// The checkers index vectors with the paper's subscripts (`x_i`, `λ_{i−1}`,
// pairs `(i, i+1)`), which reads closer to the statements than iterators.
#![allow(clippy::needless_range_loop)]

use crate::error::Error;
use crate::initial::InitialData;
use crate::projection::state_at;
use crate::scalar::Scalar;
use crate::state::State;
use crate::trajectory::Trajectory;

pub(crate) mod bump;
#[cfg(feature = "json")]
pub mod campaign;
pub mod continuum;
pub mod coq;
pub mod density;
pub mod discrete;
pub mod domain;
pub mod eulerian;
pub mod fuzz;
pub mod inclusion;
#[cfg(feature = "json")]
pub mod json;
pub mod ledger;
pub mod linf;
pub mod macro_data;
mod macro_measures;
pub mod micro;
pub mod momentum;
pub mod paper_domains;
pub mod proved;
pub mod registry;
pub mod sampling;
pub mod scaling;
pub mod test_pressure;
pub mod weak_pressure;
pub mod witness;

pub use registry::registry;

pub use crate::violation::Violation;

/// A subscript in the paper's numbering (particles `1 … N`; `0` is the
/// artificial particle `x_0` of section 3, or the end multiplier `λ_0`),
/// displayed as the index every program output uses: from 0, so `i − 1`,
/// and the paper's `0` is `−1`. The ledger's texts print `x[i]`, `u⁰[i]`,
/// `λ[i]` (the multiplier of the pair `(i, i+1)`, the paper's `λ_{i+1}`)
/// with this; the paper's own statements, quoted, keep `1 … N`.
pub(crate) struct FromPaper(pub usize);

impl std::fmt::Display for FromPaper {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        // i − 1 without a cast: the paper's 0 (x_0, λ_0) prints as −1,
        // with the minus sign of the ledger's other −1 indices (`x[−1]`).
        match self.0.checked_sub(1) {
            Some(i) => write!(f, "{i}"),
            None => f.write_str("−1"),
        }
    }
}

/// A deliberate corruption of the state the engines compute, applied by
/// [`Case::state`] and [`Case::history_state`] after the engine ran. Only
/// for `tests/claims_mutants.rs`, which shows with hand-written mutants that
/// every checker of the registry can fail; no real case carries one.
#[doc(hidden)]
pub type Tamper<S> = fn(&InitialData<S>, &mut State<S>);

/// How a case computes the state at `t` of a datum: the projection formula
/// `x(t) = P_K(x⁰ + t u⁰)` (`eq:proj-micro-x`) by one exact engine — the
/// generic [`state_at`] by default, or the same formula on integers
/// ([`crate::fast::kernel`], equal field by field) set by the ledger with
/// [`Case::with_engine`].
pub type StateEngine<S> = fn(&InitialData<S>, &S) -> Result<State<S>, Error>;

/// One initial datum with its whole sticky history and the times at which
/// claims are evaluated (0, collision instants, midpoints, after the last).
#[derive(Debug, Clone)]
pub struct Case<S> {
    /// The exact trajectory.
    pub traj: Trajectory<S>,
    /// The probe times, increasing.
    pub times: Vec<S>,
    engine: StateEngine<S>,
    tamper: Option<Tamper<S>>,
}

impl<S: Scalar> Case<S> {
    /// The case for `data`, probing every collision instant (`limit = None`)
    /// or a spread of `limit` of them.
    pub fn new(data: InitialData<S>, limit: Option<usize>) -> Self {
        let traj = Trajectory::new(data);
        let times = micro::probe_times(&traj, limit);
        Self::with_times(traj, times)
    }
    /// The case for a computed trajectory, probed at the given times.
    pub fn with_times(traj: Trajectory<S>, times: Vec<S>) -> Self {
        Case {
            traj,
            times,
            engine: state_at,
            tamper: None,
        }
    }
    /// The same case with its states computed by `engine` (another exact
    /// engine of the projection formula: the same states, faster).
    pub fn with_engine(mut self, engine: StateEngine<S>) -> Self {
        self.engine = engine;
        self
    }
    /// The same case with every state the checkers read corrupted by
    /// `tamper` (a hand-written mutant of the engines' output; test hook).
    #[doc(hidden)]
    pub fn tampered(mut self, tamper: Tamper<S>) -> Self {
        self.tamper = Some(tamper);
        self
    }
    /// The state at `t` from the projection formula
    /// ([`state_at`], `eq:proj-micro-x`; computed by the case's
    /// [`StateEngine`]): the state the checkers read.
    pub fn state(&self, t: &S) -> Result<State<S>, Error> {
        self.state_of(self.data(), t)
    }
    /// The state at `t` of another datum, computed by the same engine as
    /// [`Case::state`] (a second solution, as in a uniqueness argument).
    pub fn state_of(&self, data: &InitialData<S>, t: &S) -> Result<State<S>, Error> {
        let mut s = (self.engine)(data, t)?;
        if let Some(f) = self.tamper {
            f(data, &mut s);
        }
        Ok(s)
    }
    /// The state at `t` from the recorded history ([`Trajectory::at`]).
    pub fn history_state(&self, t: &S) -> Result<State<S>, Error> {
        let mut s = self.traj.at(t)?;
        if let Some(f) = self.tamper {
            f(self.data(), &mut s);
        }
        Ok(s)
    }
    /// The initial data.
    pub fn data(&self) -> &InitialData<S> {
        self.traj.data()
    }
    /// N.
    pub fn n(&self) -> usize {
        self.traj.data().n()
    }
    /// The collisions to check one by one: all of them, or a spread of 40
    /// (first and last included) when there are more.
    pub fn impulse_spread(&self) -> Vec<&crate::contact::Impulse<S>> {
        let all = self.traj.impulses();
        if all.len() <= 40 {
            return all.iter().collect();
        }
        let m = all.len() - 1;
        let mut idx: Vec<usize> = (0..40).map(|j| j * m / 39).collect();
        idx.dedup();
        idx.into_iter().map(|i| &all[i]).collect()
    }
    /// Σ of the sizes of the clusters formed by collisions: the cost of
    /// materialising every pressure jump.
    pub fn jump_work(&self) -> usize {
        self.traj.impulses().iter().map(|i| i.cluster.size).sum()
    }
    /// `true` when the radius is the paper's, `2r = 1/N` (section 3 needs it).
    pub fn paper_radius(&self) -> bool {
        self.data().two_r() * S::from_usize(self.n()) == S::one()
    }
}

/// A checker run on one case.
pub type CaseCheck<S> = fn(&Case<S>) -> Result<(), Violation>;

/// How a claim is checked.
pub enum Kind<S> {
    /// On every case (random initial data, shipped scenes, exhaustive
    /// domains, fuzz inputs).
    Case(CaseCheck<S>),
    /// Across N on quantile-sampled macroscopic data: a bound "independent
    /// of N" ([`scaling`]).
    Scaling(scaling::ScalingCheck),
    /// A fixed formula printed in the paper, checked exactly once.
    Formula(fn() -> Result<(), Violation>),
    /// Not checkable by a computer, with the reason.
    NotCheckable(&'static str),
}

/// A corrected statement for a claim found false as printed.
pub struct Correction<S> {
    /// The corrected statement.
    pub statement: &'static str,
    /// Its checker (run by every engine, required to hold).
    pub check: Kind<S>,
    /// Whether the enclosing result's conclusion survives, and why.
    pub conclusion: &'static str,
}

/// One claim of the paper.
pub struct Claim<S> {
    /// `\label` or `\label#step`.
    pub id: &'static str,
    /// Where it is (section or appendix).
    pub section: &'static str,
    /// The statement, quoted from the paper (LaTeX simplified).
    pub statement: &'static str,
    /// How it is checked.
    pub kind: Kind<S>,
    /// Only cases satisfying this are checked (e.g. `2r = 1/N`).
    pub applies: fn(&Case<S>) -> bool,
    /// What the statement quantifies over (times, N, test functions,
    /// datum): the ledger accepts only witnesses inside it.
    pub domain: domain::Domain,
    /// For a claim known to fail as printed: the corrected statement.
    pub correction: Option<Correction<S>>,
    /// For a claim that holds for any path whatever the dynamics (its
    /// checker cannot fail on a consistent trajectory): why. The ledger
    /// reports it as an identity, outside the "holds" count.
    pub identity: Option<&'static str>,
}

impl<S> Claim<S> {
    /// The checker of one of the claim's statements: its own as printed,
    /// its correction's when corrected (`None` without a correction).
    pub fn checker(&self, statement: coq::Statement) -> Option<&Kind<S>> {
        match statement {
            coq::Statement::Printed => Some(&self.kind),
            coq::Statement::Corrected => self.correction.as_ref().map(|c| &c.check),
        }
    }

    /// The domain the witnesses of one of its statements must lie in: the
    /// claim's own as printed; a correction must hold on every case, at
    /// every probe time (`ledger::CORRECTION_DOMAIN`).
    pub fn domain_of(&self, statement: coq::Statement) -> &domain::Domain {
        match statement {
            coq::Statement::Printed => &self.domain,
            coq::Statement::Corrected => &ledger::CORRECTION_DOMAIN,
        }
    }
}

/// `applies` for claims valid for every admissible datum.
pub fn always<S: Scalar>(_: &Case<S>) -> bool {
    true
}

/// `applies` for section 3's claims, which assume `2r = 1/N`.
pub fn paper_radius<S: Scalar>(c: &Case<S>) -> bool {
    c.paper_radius()
}

/// Runs every [`Kind::Case`] claim (and correction) of the registry that
/// applies to `case`. Returns the original claims found violated (reported,
/// not an error) or the first violation of a claim that must hold (a claim
/// without correction, or a correction).
pub fn check_case<S: Scalar>(
    claims: &[Claim<S>],
    case: &Case<S>,
) -> Result<Vec<Violation>, Violation> {
    let mut reported = Vec::new();
    for claim in claims {
        if !(claim.applies)(case) {
            continue;
        }
        if let Kind::Case(check) = &claim.kind {
            match (check(case), &claim.correction) {
                (Ok(()), _) => {}
                (Err(v), Some(_)) => reported.push(v),
                (Err(v), None) => return Err(v),
            }
        }
        if let Some(Correction {
            check: Kind::Case(check),
            ..
        }) = &claim.correction
        {
            check(case)?;
        }
    }
    Ok(reported)
}
