//! The path oracle and the explorer: symbolic execution by replay.
//!
//! The program under proof (the generic engine and a claim's checker,
//! unchanged) is run on [`Sym`](super::sym::Sym) inputs. Each comparison it
//! makes arrives here as "which of these sign conditions holds for the
//! polynomial `p`?". If the path condition (the hypotheses and every
//! decision taken so far) decides it, the answer is given; otherwise the
//! solver is asked, for each outcome, whether the path condition and the
//! outcome are satisfiable together. The first feasible outcome is taken
//! and every other feasible one is queued: the explorer later replays the
//! program from the start with that decision sequence (depth first). When
//! every queued sequence has been run, every real input satisfying the
//! hypotheses has followed one of the paths explored.

use std::cell::RefCell;
use std::collections::HashMap;
use std::time::Duration;

use num_rational::BigRational;
use num_traits::{Signed, Zero};

use super::eliminate::Constraint;
use super::lift::Quotient;
use super::poly::Poly;
use super::smt::Solver;

mod ask;
mod path;
mod run;

/// A sign condition on a polynomial `p`: `p < 0`, `p ≤ 0`, …
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Rel {
    /// `p < 0`.
    Lt,
    /// `p ≤ 0`.
    Le,
    /// `p = 0`.
    Eq,
    /// `p ≠ 0`.
    Ne,
    /// `p > 0`.
    Gt,
    /// `p ≥ 0`.
    Ge,
}

const NEG: u8 = 1;
const ZERO: u8 = 2;
const POS: u8 = 4;

impl Rel {
    /// The signs `{−, 0, +}` allowed, as a bit set.
    fn mask(self) -> u8 {
        match self {
            Rel::Lt => NEG,
            Rel::Le => NEG | ZERO,
            Rel::Eq => ZERO,
            Rel::Ne => NEG | POS,
            Rel::Gt => POS,
            Rel::Ge => ZERO | POS,
        }
    }
    /// `true` when the constant `q` satisfies `q rel 0`.
    pub fn holds_for(self, q: &BigRational) -> bool {
        self.mask() & sign_bit(q) != 0
    }
    /// The condition as SMT-LIB text on the term `p`.
    pub fn smt(self, p: &str) -> String {
        match self {
            Rel::Lt => format!("(< {p} 0.0)"),
            Rel::Le => format!("(<= {p} 0.0)"),
            Rel::Eq => format!("(= {p} 0.0)"),
            Rel::Ne => format!("(not (= {p} 0.0))"),
            Rel::Gt => format!("(> {p} 0.0)"),
            Rel::Ge => format!("(>= {p} 0.0)"),
        }
    }
}

fn flip(mask: u8) -> u8 {
    (mask & ZERO) | ((mask & NEG) << 2) | ((mask & POS) >> 2)
}

fn sign_bit(q: &BigRational) -> u8 {
    if q.is_negative() {
        NEG
    } else if q.is_zero() {
        ZERO
    } else {
        POS
    }
}

/// One decision the solver was consulted for: a fingerprint of the
/// comparison (to detect a program that does not replay identically), the
/// outcome taken, and whether the path condition implied it (it was the
/// only feasible outcome).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Decision {
    fingerprint: u64,
    outcome: u8,
    entailment: Entailment,
}

/// How a decision was reached: what its sign condition adds to the queries.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Entailment {
    /// The only feasible outcome: the path condition implies it, so its
    /// condition is left out of later queries.
    Implied,
    /// One of several feasible outcomes (the others queued as branches):
    /// its condition is sent with every later query of the path.
    Branched,
}

/// A path still to run: the decisions that lead to it and, when known, a
/// point on it (the solver's model, from which its replay starts).
struct Branch {
    prefix: Vec<Decision>,
    model: Option<Vec<BigRational>>,
}

/// The state of one run of the program along one path.
struct PathState {
    forced: Vec<Decision>,
    taken: Vec<Decision>,
    branches: Vec<Branch>,
    /// A point satisfying the path condition (the solver's last model),
    /// when known and rational: the outcome it takes is feasible without a
    /// query.
    model: Option<Vec<BigRational>>,
    /// Signs still possible for each normalised polynomial.
    masks: HashMap<Poly, u8>,
    /// The path condition as SMT-LIB text (hypotheses first), as sent
    /// with each query: without the decisions it already implied (their
    /// other outcomes were all infeasible), which change no answer and
    /// only slow the solver down.
    pc: Vec<String>,
    /// The whole path condition, implied decisions included (for deciding
    /// and solving a path to a violation, as asked before the lean `pc`).
    full_pc: Vec<String>,
    /// The same path condition as polynomial constraints (for
    /// [`eliminate`](super::eliminate), when the solver cannot decide a query on `pc`).
    cons: Vec<Constraint>,
    /// The quotients compared on the path ([`lift`](super::lift)).
    quotients: Vec<Quotient>,
    /// The polynomials squared on the path ([`relax::linearize`](super::relax::linearize)).
    squares: Vec<Poly>,
    solver: Solver,
    names: Vec<String>,
    queries: usize,
    unknown_answers: usize,
    fault: Option<String>,
    error: Option<String>,
}

thread_local! {
    static STATE: RefCell<Option<PathState>> = const { RefCell::new(None) };
    static NAMES: RefCell<Vec<String>> = const { RefCell::new(Vec::new()) };
}

/// The variable names of the exploration running on this thread, installed
/// for as long as the guard lives: dropping it clears them, on every exit
/// of [`explore`] (an early `?` included).
struct NamesGuard;

impl NamesGuard {
    fn install(names: &[String]) -> Self {
        NAMES.with(|n| *n.borrow_mut() = names.to_vec());
        NamesGuard
    }
}

impl Drop for NamesGuard {
    fn drop(&mut self) {
        NAMES.with(|n| n.borrow_mut().clear());
    }
}

/// The names of the variables of the exploration running on this thread.
pub fn names() -> Vec<String> {
    NAMES.with(|n| n.borrow().clone())
}

/// Records a fault of the current path (a division by zero): the path ends
/// as a counterexample even if the checker passes.
pub fn fault(what: &str) {
    STATE.with(|s| {
        if let Some(st) = s.borrow_mut().as_mut() {
            st.fault.get_or_insert_with(|| what.to_string());
        }
    });
}

/// The sign condition allowing exactly the signs allowed by one of
/// `rels` (`Le` for `Lt` and `Eq`, …), when there is one.
fn union_rel(rels: impl Iterator<Item = Rel>) -> Option<Rel> {
    let mask = rels.fold(0, |m, r| m | r.mask());
    [Rel::Lt, Rel::Le, Rel::Eq, Rel::Ne, Rel::Gt, Rel::Ge]
        .into_iter()
        .find(|r| r.mask() == mask)
}

/// Whether a query's model is read back (a `sat` outcome becomes a
/// branch, whose replay starts from the model).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Model {
    /// Read the model after `sat`.
    Wanted,
    /// Only the answer counts.
    NotNeeded,
}

/// Records a quotient `num / den` the program compares (a collision
/// instant), for [`lift`](super::lift) on the path running on this thread.
pub fn note_quotient(num: &Poly, den: &Poly) {
    STATE.with(|s| {
        if let Some(st) = s.borrow_mut().as_mut() {
            let q = Quotient {
                num: num.clone(),
                den: den.clone(),
            };
            if !st.quotients.contains(&q) {
                st.quotients.push(q);
            }
        }
    });
}

/// The most squared polynomials kept for [`relax::linearize`](super::relax::linearize) on one path.
const MAX_SQUARES: usize = 8;

/// Records a polynomial the program squares (a displacement whose square
/// it bounds), for [`relax::linearize`](super::relax::linearize) on the path running on this thread.
pub fn note_square(base: &Poly) {
    STATE.with(|s| {
        if let Some(st) = s.borrow_mut().as_mut() {
            if st.squares.len() < MAX_SQUARES && !st.squares.contains(base) {
                st.squares.push(base.clone());
            }
        }
    });
}

/// `true` when the exact point satisfies every constraint.
fn satisfies(constraints: &[Constraint], point: &[BigRational]) -> bool {
    constraints.iter().all(|c| {
        let atoms = match c {
            Constraint::Atom(a) => std::slice::from_ref(a),
            Constraint::Any(atoms) => atoms.as_slice(),
        };
        atoms.iter().any(|a| a.rel.holds_for(&a.poly.eval(point)))
    })
}

/// `Some(true)` when the path condition is known (without asking the
/// solver) to make `p > 0`, `Some(false)` for `p < 0`, `None` otherwise.
pub fn known_strict_sign(p: &Poly) -> Option<bool> {
    if let Some(c) = p.as_constant() {
        return match sign_bit(&c) {
            POS => Some(true),
            NEG => Some(false),
            _ => None,
        };
    }
    let (np, lead) = p.normalized();
    STATE.with(|s| {
        let s = s.borrow();
        let st = s.as_ref()?;
        let known = st.masks.get(&np).copied()?;
        let known = if lead.is_negative() {
            flip(known)
        } else {
            known
        };
        match known {
            POS => Some(true),
            NEG => Some(false),
            _ => None,
        }
    })
}

/// Which of `outcomes` (sign conditions covering every sign of `p`) holds:
/// the path oracle behind every comparison of the symbolic scalar. Without
/// an exploration running, a non-constant comparison answers the first
/// outcome.
pub fn decide(p: &Poly, outcomes: &[Rel]) -> usize {
    if let Some(c) = p.as_constant() {
        return path::constant_outcome(&c, outcomes);
    }
    STATE.with(|s| match s.borrow_mut().as_mut() {
        Some(st) => st.decide(p, outcomes),
        None => 0,
    })
}

/// A hypothesis on the inputs, asserted before the program runs.
#[derive(Debug, Clone)]
pub enum Hypothesis {
    /// A sign condition on a polynomial (also known to the oracle's cache).
    Sign(Poly, Rel),
    /// At least one of these sign conditions holds.
    Any(Vec<(Poly, Rel)>),
}

/// How a path ended.
#[derive(Debug, Clone)]
pub enum PathEnd {
    /// The checker passed.
    Holds,
    /// The checker failed (or the engine faulted): the message.
    Violated(String),
    /// The input was refused by the program's own validation (does not
    /// happen when the hypotheses imply it).
    Excluded(String),
}

/// The result of an exploration.
#[derive(Debug, Clone)]
pub struct Exploration {
    /// Paths run to the end.
    pub paths: usize,
    /// Satisfiability queries asked.
    pub queries: usize,
    /// Paths whose input was refused by the program's validation.
    pub excluded: usize,
    /// Wall-clock time.
    pub seconds: f64,
    /// What was found.
    pub verdict: Verdict,
}

/// The outcome of an exploration.
#[derive(Debug, Clone)]
pub enum Verdict {
    /// Every feasible path was run and ended in [`PathEnd::Holds`] (or
    /// [`PathEnd::Excluded`]).
    Proved,
    /// A feasible path ends in a violation: the message and an exact
    /// rational point (in the order of the variable names) on that path.
    Counterexample {
        /// The checker's message on the symbolic path.
        message: String,
        /// An exact input taking that path.
        point: Vec<BigRational>,
    },
    /// Neither: why.
    Unknown(String),
}

/// Limits of one exploration: all of them are enforced on the whole
/// attempt, the symbolic algebra ([`budget`](super::budget)) as well as the solver
/// ([`SolverLimits`](super::smt::SolverLimits)).
#[derive(Debug, Clone, Copy)]
pub struct Limits {
    /// Most paths run.
    pub max_paths: usize,
    /// Wall-clock budget of the whole attempt.
    pub time: Duration,
    /// Per query, milliseconds.
    pub query_ms: u64,
    /// The solver's memory cap, megabytes (z3's `-memory:`).
    pub solver_memory_mb: u64,
    /// The most terms a polynomial of the symbolic algebra may have (the
    /// memory bound of our side).
    pub max_terms: usize,
}

impl Default for Limits {
    fn default() -> Self {
        Limits {
            max_paths: 200_000,
            time: Duration::from_secs(600),
            query_ms: 20_000,
            solver_memory_mb: 2048,
            max_terms: 200_000,
        }
    }
}

pub use run::explore;

#[cfg(test)]
mod tests;
