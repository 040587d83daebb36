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
use std::collections::hash_map::DefaultHasher;
use std::collections::HashMap;
use std::hash::{Hash, Hasher};
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::time::{Duration, Instant};

use num_rational::BigRational;
use num_traits::{Signed, Zero};

use super::budget;
use super::eliminate::{Atom, Constraint};
use super::lift::Quotient;
use super::poly::Poly;
use super::smt::{Sat, Solver, SolverError, SolverLimits};
use crate::progress::Progress;

mod ask;

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
/// comparison (to detect a program that does not replay identically) and
/// the outcome taken.
/// The outcome's bit `IMPLIED` is set when it was the only feasible one.
type Decision = (u64, u8);

/// The flag of a [`Decision`] whose outcome the path condition implied.
const IMPLIED: u8 = 0x80;

/// The state of one run of the program along one path.
struct PathState {
    forced: Vec<Decision>,
    taken: Vec<Decision>,
    branches: Vec<(Vec<Decision>, Option<Vec<BigRational>>)>,
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

impl PathState {
    /// Takes the outcome `rel` of the comparison of `p` (normalised `np`):
    /// recorded in the sign masks and the path condition, and kept as a
    /// constraint of the path.
    fn keep(&mut self, np: &Poly, flipped: bool, p: &Poly, rel: Rel, ptext: &str, implied: bool) {
        self.record(np, flipped, rel, Some(rel.smt(ptext)), implied);
        self.cons.push(Constraint::Atom(Atom {
            poly: p.clone(),
            rel,
        }));
    }

    fn record(&mut self, np: &Poly, flipped: bool, rel: Rel, text: Option<String>, implied: bool) {
        let m = if flipped {
            flip(rel.mask())
        } else {
            rel.mask()
        };
        let e = self.masks.entry(np.clone()).or_insert(NEG | ZERO | POS);
        *e &= m;
        if let Some(t) = text {
            if !implied {
                self.pc.push(t.clone());
            }
            self.full_pc.push(t);
        }
    }

    fn decide(&mut self, p: &Poly, outcomes: &[Rel]) -> usize {
        if let Some(c) = p.as_constant() {
            let b = sign_bit(&c);
            return outcomes.iter().position(|r| r.mask() & b != 0).unwrap_or(0);
        }
        let (np, lead) = p.normalized();
        let flipped = lead.is_negative();
        let known = self.masks.get(&np).copied().unwrap_or(NEG | ZERO | POS);
        let known = if flipped { flip(known) } else { known };
        let candidates: Vec<usize> = (0..outcomes.len())
            .filter(|&k| outcomes[k].mask() & known != 0)
            .collect();
        match candidates.len() {
            0 => {
                self.error
                    .get_or_insert_with(|| "inconsistent path condition".into());
                return 0;
            }
            1 => {
                let k = candidates[0];
                self.record(&np, flipped, outcomes[k], None, true);
                return k;
            }
            _ => {}
        }
        let text = np.smt(&self.names);
        let fingerprint = {
            let mut h = DefaultHasher::new();
            text.hash(&mut h);
            flipped.hash(&mut h);
            outcomes.len().hash(&mut h);
            h.finish()
        };
        // The polynomial as written, so that the sign conditions read right.
        let ptext = p.smt(&self.names);
        let pos = self.taken.len();
        if pos < self.forced.len() {
            let (f, taken) = self.forced[pos];
            let (k, implied) = (taken & !IMPLIED, taken & IMPLIED != 0);
            if f != fingerprint || usize::from(k) >= outcomes.len() {
                self.error.get_or_insert_with(|| {
                    "the program did not replay identically (non-deterministic decision)".into()
                });
            }
            let k = usize::from(k).min(outcomes.len() - 1);
            self.taken.push((fingerprint, taken));
            self.keep(&np, flipped, p, outcomes[k], &ptext, implied);
            return k;
        }
        // The outcome the current model takes is feasible: no query.
        let model_k = self.model.as_ref().and_then(|m| {
            let b = sign_bit(&p.eval(m));
            candidates
                .iter()
                .copied()
                .find(|&k| outcomes[k].mask() & b != 0)
        });
        let mut feasible: Vec<(usize, Option<Vec<BigRational>>)> = Vec::new();
        if let Some(k0) = model_k {
            feasible.push((k0, self.model.clone()));
        }
        // The outcomes the model does not take: usually all infeasible (the
        // path condition decides the comparison). One query on their union
        // settles that case; otherwise each is asked as before.
        let others: Vec<usize> = candidates
            .iter()
            .copied()
            .filter(|&k| Some(k) != model_k)
            .collect();
        if let (Some(k0), true) = (model_k, others.len() >= 2) {
            if let Some(union) = union_rel(others.iter().map(|&k| outcomes[k])) {
                self.queries += 1;
                let q = union.smt(&ptext);
                let extra = Atom {
                    poly: p.clone(),
                    rel: union,
                };
                match self.ask(&extra, &q, Model::NotNeeded).map(|(a, _)| a) {
                    Ok(Sat::Unsat) => {
                        // None of them is feasible: the model's outcome is
                        // the only one, as a query on each would answer.
                        self.take(&np, flipped, fingerprint, k0, outcomes, p);
                        return k0;
                    }
                    Ok(_) => {}
                    Err(e) => {
                        self.error.get_or_insert(e.0);
                    }
                }
            }
        }
        for (i, &k) in candidates.iter().enumerate() {
            if Some(k) == model_k {
                continue;
            }
            if model_k.is_none() && i + 1 == candidates.len() && feasible.is_empty() {
                // The path condition is satisfiable and the outcomes cover
                // every sign: the last one must be feasible.
                feasible.push((k, None));
                continue;
            }
            let q = outcomes[k].smt(&ptext);
            self.queries += 1;
            let extra = Atom {
                poly: p.clone(),
                rel: outcomes[k],
            };
            match self.ask(&extra, &q, Model::Wanted) {
                Ok((Sat::Sat, m)) => feasible.push((k, m)),
                Ok((Sat::Unsat, _)) => {}
                Ok((Sat::Unknown, _)) => match self.check_reduced(Some(extra)) {
                    Ok((Sat::Sat, m)) => feasible.push((k, m)),
                    Ok((Sat::Unsat, _)) => {}
                    Ok((Sat::Unknown, _)) => {
                        self.unknown_answers += 1;
                        feasible.push((k, None));
                    }
                    Err(e) => {
                        self.error.get_or_insert(e.0);
                        feasible.push((k, None));
                    }
                },
                Err(e) => {
                    self.error.get_or_insert(e.0);
                    feasible.push((k, None));
                }
            }
        }
        let mut feasible = feasible.into_iter();
        let Some((k, model)) = feasible.next() else {
            self.error
                .get_or_insert_with(|| "no feasible outcome".into());
            return 0;
        };
        self.model = model;
        // The only feasible outcome: the path condition implies it.
        let implied = feasible.as_slice().is_empty();
        for (alt, m) in feasible {
            let mut prefix = self.taken.clone();
            prefix.push((fingerprint, alt as u8));
            self.branches.push((prefix, m));
        }
        let flag = if implied { IMPLIED } else { 0 };
        self.taken.push((fingerprint, k as u8 | flag));
        self.keep(&np, flipped, p, outcomes[k], &ptext, implied);
        k
    }

    /// Takes the model's outcome `k` (the only feasible one) without
    /// branching: the end of [`PathState::decide`] with no alternative.
    fn take(
        &mut self,
        np: &Poly,
        flipped: bool,
        fingerprint: u64,
        k: usize,
        outcomes: &[Rel],
        p: &Poly,
    ) {
        let ptext = p.smt(&self.names);
        self.taken.push((fingerprint, k as u8 | IMPLIED));
        self.keep(np, flipped, p, outcomes[k], &ptext, true);
    }
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
        let b = sign_bit(&c);
        return outcomes.iter().position(|r| r.mask() & b != 0).unwrap_or(0);
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
/// attempt, the symbolic algebra ([`budget`]) as well as the solver
/// ([`SolverLimits`]).
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

/// Explores every path of `program` over the variables `names` under
/// `hypotheses` (see the module documentation). `program` must be
/// deterministic: it is replayed from the start for each path.
///
/// The attempt ends by `limits.time` (plus the time to kill the solver):
/// the deadline is enforced inside the symbolic algebra, on every answer
/// awaited from the solver, and between paths. `progress` is told of every
/// path (the paths explored and the time left) and asked between paths
/// whether to stop.
pub fn explore(
    names: &[String],
    hypotheses: &[Hypothesis],
    limits: Limits,
    program: &dyn Fn() -> PathEnd,
    progress: &dyn Progress,
) -> Result<Exploration, SolverError> {
    let start = Instant::now();
    // The work stops a little before the budget, leaving the rest to wind
    // down (unwinding and freeing a large path, killing the solver): 2 % of
    // the budget, at most 2 s.
    let reserve = (limits.time / 50).min(Duration::from_secs(2));
    let deadline = start + limits.time - reserve;
    let _budget = budget::install(deadline, limits.max_terms);
    let mut solver = Solver::start(
        names,
        SolverLimits {
            query_ms: limits.query_ms,
            deadline,
            memory_mb: limits.solver_memory_mb,
        },
    )?;
    NAMES.with(|n| *n.borrow_mut() = names.to_vec());
    let mut base_pc = Vec::new();
    let mut base_masks = HashMap::new();
    let mut base_cons = Vec::new();
    for h in hypotheses {
        match h {
            Hypothesis::Sign(p, rel) => {
                let (np, lead) = p.normalized();
                let m = if lead.is_negative() {
                    flip(rel.mask())
                } else {
                    rel.mask()
                };
                *base_masks.entry(np).or_insert(NEG | ZERO | POS) &= m;
                base_pc.push(rel.smt(&p.smt(names)));
                base_cons.push(Constraint::Atom(Atom {
                    poly: p.clone(),
                    rel: *rel,
                }));
            }
            Hypothesis::Any(atoms) => {
                let c = Constraint::Any(
                    atoms
                        .iter()
                        .map(|(p, rel)| Atom {
                            poly: p.clone(),
                            rel: *rel,
                        })
                        .collect(),
                );
                base_pc.push(c.smt(names));
                base_cons.push(c);
            }
        }
    }
    let mut result = Exploration {
        paths: 0,
        queries: 0,
        excluded: 0,
        seconds: 0.0,
        verdict: Verdict::Proved,
    };
    // The hypotheses must be satisfiable, or everything is vacuous.
    result.queries += 1;
    let base_model = match solver.check(&base_pc, None)? {
        Sat::Sat => solver.model(names)?,
        other => {
            result.verdict = Verdict::Unknown(format!("hypotheses not satisfiable ({other:?})"));
            return Ok(result);
        }
    };
    let mut stack: Vec<(Vec<Decision>, Option<Vec<BigRational>>)> = vec![(Vec::new(), base_model)];
    let mut state = Some(PathState {
        forced: Vec::new(),
        taken: Vec::new(),
        branches: Vec::new(),
        model: None,
        masks: base_masks.clone(),
        pc: base_pc.clone(),
        full_pc: base_pc.clone(),
        cons: base_cons.clone(),
        quotients: Vec::new(),
        squares: Vec::new(),
        solver,
        names: names.to_vec(),
        queries: 0,
        unknown_answers: 0,
        fault: None,
        error: None,
    });
    let mut unknown_total = 0;
    while let Some((prefix, model)) = stack.pop() {
        if result.paths >= limits.max_paths {
            result.verdict = Verdict::Unknown(format!(
                "path limit reached ({} paths, {} still queued)",
                result.paths,
                stack.len() + 1
            ));
            break;
        }
        if progress.cancelled() {
            result.verdict = Verdict::Unknown(format!(
                "interrupted after {} paths ({} still queued)",
                result.paths,
                stack.len() + 1
            ));
            break;
        }
        if Instant::now() > deadline {
            result.verdict = Verdict::Unknown(format!(
                "the time budget of {} s ran out between paths, after {} paths ({} still queued)",
                limits.time.as_secs(),
                result.paths,
                stack.len() + 1
            ));
            break;
        }
        let Some(mut st) = state.take() else { break };
        st.forced = prefix;
        st.model = model;
        st.taken.clear();
        st.branches.clear();
        st.masks = base_masks.clone();
        st.pc = base_pc.clone();
        st.full_pc = base_pc.clone();
        st.cons = base_cons.clone();
        st.quotients.clear();
        st.squares.clear();
        st.queries = 0;
        st.unknown_answers = 0;
        st.fault = None;
        st.error = None;
        STATE.with(|s| *s.borrow_mut() = Some(st));
        let end = catch_unwind(AssertUnwindSafe(program));
        let Some(mut st) = STATE.with(|s| s.borrow_mut().take()) else {
            result.verdict = Verdict::Unknown("the oracle state was lost".into());
            break;
        };
        if let Err(payload) = &end {
            if let Some(why) = budget::overrun(payload.as_ref()) {
                result.queries += st.queries;
                result.verdict = Verdict::Unknown(format!(
                    "{why}: path {} abandoned after {} complete paths ({} still queued)",
                    result.paths + 1,
                    result.paths,
                    stack.len() + st.branches.len()
                ));
                state = Some(st);
                break;
            }
        }
        result.paths += 1;
        result.queries += st.queries;
        progress.advance(1);
        progress.note(&format!(
            "{} paths, {} s left",
            result.paths,
            deadline.saturating_duration_since(Instant::now()).as_secs()
        ));
        unknown_total += st.unknown_answers;
        // Depth first: the last alternative found is explored next.
        stack.append(&mut st.branches);
        if let Some(e) = st.error.take() {
            result.verdict = Verdict::Unknown(e);
            state = Some(st);
            break;
        }
        let end = match end {
            Ok(e) => e,
            Err(panic) => {
                let msg = panic
                    .downcast_ref::<&str>()
                    .map(|s| s.to_string())
                    .or_else(|| panic.downcast_ref::<String>().cloned())
                    .unwrap_or_else(|| "panic".into());
                PathEnd::Violated(format!("the engine panicked: {msg}"))
            }
        };
        let end = match (st.fault.take(), end) {
            (Some(f), PathEnd::Holds) => PathEnd::Violated(format!("engine fault: {f}")),
            (_, e) => e,
        };
        match end {
            PathEnd::Holds => {}
            PathEnd::Excluded(_) => result.excluded += 1,
            PathEnd::Violated(message) => {
                result.queries += 1;
                let mut reduced_point = None;
                let answer = match st.solver.check(&st.full_pc, None) {
                    Ok(Sat::Unknown) => {
                        st.queries = 0;
                        let r = st.check_reduced(None);
                        result.queries += st.queries;
                        match r {
                            Ok((a, point)) => {
                                reduced_point = point;
                                a
                            }
                            Err(e) => {
                                result.verdict = Verdict::Unknown(format!(
                                    "{e} (deciding a path to a violation: {message})"
                                ));
                                state = Some(st);
                                break;
                            }
                        }
                    }
                    Ok(a) => a,
                    Err(e) => {
                        result.verdict = Verdict::Unknown(format!(
                            "{e} (deciding a path to a violation: {message})"
                        ));
                        state = Some(st);
                        break;
                    }
                };
                match answer {
                    Sat::Unsat => {} // an infeasible path let through by an `unknown`
                    Sat::Unknown => {
                        result.verdict = Verdict::Unknown(format!(
                            "a path to a violation could not be decided by the solver: {message}"
                        ));
                        state = Some(st);
                        break;
                    }
                    Sat::Sat => {
                        let pc = st.full_pc.clone();
                        // A completed model of the reduced query satisfies
                        // the path condition when checked exactly.
                        let exact = reduced_point.filter(|m| satisfies(&st.cons, m));
                        let point = match exact {
                            Some(m) => Ok(Some(m)),
                            None => st.solver.rational_model(&pc, names),
                        };
                        result.queries += 2 * names.len();
                        result.verdict = match point {
                            Ok(Some(point)) => Verdict::Counterexample { message, point },
                            Ok(None) => Verdict::Unknown(format!(
                                "a feasible path to a violation, but no rational point on it was found: {message}"
                            )),
                            Err(e) => Verdict::Unknown(format!(
                                "{e} (building a rational point on a path to a violation: {message})"
                            )),
                        };
                        state = Some(st);
                        break;
                    }
                }
            }
        }
        state = Some(st);
    }
    if matches!(result.verdict, Verdict::Proved) && unknown_total > 0 {
        result.verdict = Verdict::Unknown(format!(
            "{unknown_total} solver queries timed out (answered `unknown`)"
        ));
    }
    drop(state);
    NAMES.with(|n| n.borrow_mut().clear());
    result.seconds = start.elapsed().as_secs_f64();
    Ok(result)
}

#[cfg(test)]
mod tests;
