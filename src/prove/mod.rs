//! Proofs for all real data at a fixed N: the same generic engine and the
//! same claim checkers, run on a symbolic scalar and discharged by an SMT
//! solver (`sticky prove`, issue 11).
//!
//! * [`sym::Sym`] — a rational function of the inputs `x⁰ᵢ`, `u⁰ᵢ` and the
//!   times `t`, `s` with exact rational coefficients (`2r = 1/N` fixed);
//! * [`mod@explore`] — the path oracle (every comparison of the engine or the
//!   checker is a branch point unless the path condition decides it) and
//!   the depth-first explorer that replays the program from the start for
//!   every feasible decision sequence;
//! * [`smt`] — z3 over SMT-LIB through a pipe (`z3 -in`, nonlinear real
//!   arithmetic by `nlsat`).
//!
//! A claim is **proved** at N when every feasible path was run to the end
//! and the checker passed on each: then every real input satisfying the
//! hypotheses (they are printed with the result) passes the checker, since
//! every input follows exactly one of the paths. It is **refuted** when a
//! feasible path ends in a violation: the solver's model becomes an exact
//! rational scene that is replayed through the ordinary `BigRational`
//! checker, which must fail too. Anything else (solver time-outs, limits)
//! is **unknown**, with the reason.
//!
//! What runs symbolically: `InitialData::new` (the validation), the event
//! merge [`crate::trajectory::Trajectory::new`] and [`Trajectory::at`], the
//! projection [`crate::projection::state_at`] (PAVA with its
//! right-derivative tie-break) and the claim's checker from
//! [`crate::claims::registry()`] — unchanged. The fast integer engines are
//! not run symbolically: they are tied to these two by the oracle battery
//! (exact equality on every test input).
//!
//! [`Trajectory::at`]: crate::trajectory::Trajectory::at

pub mod budget;
#[cfg(feature = "json")]
pub mod campaign;
pub mod eliminate;
pub mod explore;
#[cfg(feature = "json")]
pub mod json;
pub mod lift;
pub mod poly;
#[cfg(feature = "json")]
pub mod record;
pub mod relax;
pub mod smt;
pub mod sym;
pub mod telescope;

use num_rational::BigRational;
use num_traits::{One, Zero};

use crate::claims::coq::Statement;
use crate::claims::domain::{Domain, InTime};
use crate::claims::ledger::CORRECTION_DOMAIN;
use crate::claims::{registry, Case, Claim, Kind};
use crate::initial::InitialData;
use crate::progress::{Progress, Silent};
use crate::scalar::Scalar;
use crate::trajectory::Trajectory;

use explore::{explore, Hypothesis, Limits, PathEnd, Rel, Verdict};
use poly::{Poly, Var};
use sym::Sym;

pub use explore::Limits as ProofLimits;
pub use smt::available as solver_available;

/// The inputs of one run: initial data and the probe times.
#[derive(Debug, Clone)]
pub struct Input<S> {
    /// `x⁰`.
    pub positions: Vec<S>,
    /// `u⁰`.
    pub velocities: Vec<S>,
    /// `r` (`1/(2N)`).
    pub radius: S,
    /// The times at which the claim is checked: `[t]`, or `[s, t]` with
    /// `0 ≤ s ≤ t` for claims about two times.
    pub times: Vec<S>,
}

impl<S: Scalar> Input<S> {
    /// The initial data (`InitialData::new`: its validation is part of the
    /// program run, so an inadmissible input ends the path as excluded).
    pub fn data(&self) -> Result<InitialData<S>, crate::error::Error> {
        InitialData::new(
            self.radius.clone(),
            self.positions.clone(),
            self.velocities.clone(),
        )
    }
}

/// A program to prove: generic over the scalar, deterministic, returning how
/// the path ended. Run on [`Sym`] for the proof and on [`BigRational`] to
/// replay a counterexample.
pub trait Program {
    /// Runs the program on `input`.
    fn run<S: Scalar>(&self, input: &Input<S>) -> PathEnd;

    /// The times a counterexample is shown at, given the solver's
    /// replayed `input` (violated at `input.times`): the same times by
    /// default; a statement quantified "for a.e. t" asks for a second time
    /// of the same open interval between collisions, and a measure in `t`
    /// for the last collision instant ([`Target`]). `Err`
    /// says why no admissible witness was found (the attempt ends unknown).
    fn witness_times(&self, input: &Input<BigRational>) -> Result<Vec<BigRational>, String> {
        Ok(input.times.clone())
    }
}

/// The status of a claim at one N.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[cfg_attr(
    feature = "json",
    derive(serde::Serialize, serde::Deserialize),
    serde(rename_all = "lowercase")
)]
#[cfg_attr(all(test, feature = "json"), derive(schemars::JsonSchema))]
pub enum Status {
    /// Holds for every real input satisfying the hypotheses.
    Proved,
    /// A counterexample was found and replayed exactly.
    Refuted,
    /// Neither could be established.
    Unknown,
}

impl Status {
    /// `"proved"`, `"refuted"` or `"unknown"`.
    pub fn as_str(self) -> &'static str {
        match self {
            Status::Proved => "proved",
            Status::Refuted => "refuted",
            Status::Unknown => "unknown",
        }
    }
}

/// The result of one proof attempt (one claim, one N).
#[derive(Debug, Clone)]
pub struct ProofResult {
    /// Claim id (`\label`, `#step`, ` (corrected)` for a correction).
    pub id: String,
    /// N.
    pub n: usize,
    /// The status.
    pub status: Status,
    /// Paths explored.
    pub paths: usize,
    /// Solver queries.
    pub queries: usize,
    /// Wall-clock seconds.
    pub seconds: f64,
    /// The hypotheses, in words.
    pub hypotheses: String,
    /// The counterexample as a scene (TOML), replayed exactly.
    pub witness: Option<String>,
    /// Why the status is `unknown`, or the checker's message on the
    /// counterexample.
    pub note: Option<String>,
}

/// The times a claim is quantified over: section 2's statements hold at
/// every `t ≥ 0`, the semigroup and contraction ones compare two times
/// `0 ≤ s ≤ t`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Times {
    /// Every real `t ≥ 0`.
    One,
    /// Every real `0 ≤ s ≤ t` (the checker gets the times `[s, t]`).
    Two,
}

/// The variable names for N particles: `x1 … xN`, `u1 … uN`, `t`, `s`.
pub fn variable_names(n: usize, times: Times) -> Vec<String> {
    let mut names: Vec<String> = (1..=n).map(|i| format!("x{i}")).collect();
    names.extend((1..=n).map(|i| format!("u{i}")));
    names.push("t".into());
    if times == Times::Two {
        names.push("s".into());
    }
    names
}

fn var(i: usize) -> Var {
    Var::try_from(i).unwrap_or(Var::MAX)
}

/// The hypotheses of section 2 at N: `x⁰ ∈ K^N`, `u⁰ ∈ C_{x⁰}`, `2r = 1/N`,
/// `t ≥ 0` (and `0 ≤ s ≤ t`).
fn hypotheses(n: usize, times: Times) -> (Vec<Hypothesis>, String) {
    let two_r = BigRational::new(1.into(), (n as i64).into());
    let mut hs = Vec::new();
    for i in 0..n.saturating_sub(1) {
        // gap − 2r ≥ 0, and gap = 2r ⇒ u_i ≤ u_{i+1}.
        let gap = Poly::var(var(i + 1))
            .sub(&Poly::var(var(i)))
            .sub(&Poly::constant(two_r.clone()));
        let closing = Poly::var(var(n + i)).sub(&Poly::var(var(n + i + 1)));
        hs.push(Hypothesis::Sign(gap.clone(), Rel::Ge));
        hs.push(Hypothesis::Any(vec![(gap, Rel::Gt), (closing, Rel::Le)]));
    }
    let t = Poly::var(var(2 * n));
    if times == Times::Two {
        let s = Poly::var(var(2 * n + 1));
        hs.push(Hypothesis::Sign(s.clone(), Rel::Ge));
        hs.push(Hypothesis::Sign(t.sub(&s), Rel::Ge));
    }
    hs.push(Hypothesis::Sign(t, Rel::Ge));
    let times = match times {
        Times::Two => "all real 0 ≤ s ≤ t (checked at the times [s, t])",
        Times::One => "all real t ≥ 0",
    };
    let text = format!(
        "N = {n}, 2r = 1/N; all real x⁰ ∈ K^N (x⁰_(i+1) − x⁰_i ≥ 2r) and u⁰ ∈ C_x⁰ (u⁰_i ≤ u⁰_(i+1) where x⁰_(i+1) − x⁰_i = 2r); {times}"
    );
    (hs, text)
}

fn symbolic_input(n: usize, times: Times) -> Input<Sym> {
    let radius = Sym::constant(BigRational::new(1.into(), (2 * n as i64).into()));
    let t = Sym::var(var(2 * n));
    Input {
        positions: (0..n).map(|i| Sym::var(var(i))).collect(),
        velocities: (0..n).map(|i| Sym::var(var(n + i))).collect(),
        radius,
        times: match times {
            Times::Two => vec![Sym::var(var(2 * n + 1)), t],
            Times::One => vec![t],
        },
    }
}

fn concrete_input(n: usize, times: Times, point: &[BigRational]) -> Input<BigRational> {
    let at = |i: usize| {
        point
            .get(i)
            .cloned()
            .unwrap_or_else(<BigRational as Zero>::zero)
    };
    Input {
        positions: (0..n).map(at).collect(),
        velocities: (0..n).map(|i| at(n + i)).collect(),
        radius: <BigRational as One>::one() / BigRational::from_integer((2 * n as i64).into()),
        times: match times {
            Times::Two => vec![at(2 * n + 1), at(2 * n)],
            Times::One => vec![at(2 * n)],
        },
    }
}

/// The counterexample as a scene file: the particles, and the times in
/// `t_end` and a comment.
fn witness_toml(id: &str, input: &Input<BigRational>) -> String {
    use crate::rational::render_exact;
    let data = input.data();
    let times: Vec<String> = input.times.iter().map(render_exact).collect();
    let body = match data {
        Ok(d) => crate::scene::particles_toml(&d, Some(&format!("counterexample to {id}"))),
        Err(e) => format!("# not admissible: {e}\n"),
    };
    let (head, tail) = body.split_once("\n[particles]").unwrap_or((&body, ""));
    let t_end = input.times.last().map(render_exact).unwrap_or_default();
    format!(
        "{head}\ndescription = \"symbolic prover witness: the checker fails at the times [{}]\"\nt_end = \"{t_end}\"\n\n[particles]{tail}",
        times.join(", ")
    )
}

/// Proves `program` for N particles (see the module documentation).
pub fn prove_program<P: Program>(
    id: &str,
    n: usize,
    times: Times,
    program: &P,
    limits: Limits,
) -> ProofResult {
    prove_program_observed(id, n, times, program, limits, &Silent)
}

/// [`prove_program`], telling `progress` of every path explored (and
/// stopping `unknown` when it answers that the watcher cancelled).
pub fn prove_program_observed<P: Program>(
    id: &str,
    n: usize,
    times: Times,
    program: &P,
    limits: Limits,
    progress: &dyn Progress,
) -> ProofResult {
    let start = std::time::Instant::now();
    let names = variable_names(n, times);
    let (hyps, hyp_text) = hypotheses(n, times);
    let sym = symbolic_input(n, times);
    let run = || program.run(&sym);
    let mut result = ProofResult {
        id: id.to_string(),
        n,
        status: Status::Unknown,
        paths: 0,
        queries: 0,
        seconds: 0.0,
        hypotheses: hyp_text,
        witness: None,
        note: None,
    };
    let exploration = match explore(&names, &hyps, limits, &run, progress) {
        Ok(e) => e,
        Err(e) => {
            result.note = Some(e.0);
            result.seconds = start.elapsed().as_secs_f64();
            return result;
        }
    };
    result.paths = exploration.paths;
    result.queries = exploration.queries;
    match exploration.verdict {
        Verdict::Proved => {
            result.status = Status::Proved;
            if exploration.excluded > 0 {
                result.note = Some(format!(
                    "{} paths refused by the input validation or outside the statement's domain",
                    exploration.excluded
                ));
            }
        }
        Verdict::Unknown(why) => result.note = Some(why),
        Verdict::Counterexample { message, point } => {
            let mut input = concrete_input(n, times, &point);
            match program.run(&input) {
                PathEnd::Violated(exact) => match program.witness_times(&input) {
                    Ok(shown_at) => {
                        input.times = shown_at;
                        result.status = Status::Refuted;
                        result.witness = Some(witness_toml(id, &input));
                        result.note = Some(exact);
                    }
                    Err(why) => result.note = Some(why),
                },
                other => {
                    result.note = Some(format!(
                        "the solver's point did not reproduce the violation exactly ({other:?}); symbolic message: {message}"
                    ));
                }
            }
        }
    }
    result.seconds = start.elapsed().as_secs_f64();
    result
}

/// A claim of the registry that the prover handles.
#[derive(Debug, Clone)]
pub struct Target {
    /// The id reported: the registry id, plus ` (corrected)`.
    pub id: String,
    /// The registry id.
    pub registry_id: &'static str,
    /// The claim as printed or its correction.
    pub statement: Statement,
    /// `true` when the ledger reports the printed claim false (so the
    /// prover is expected to refute it at some N).
    pub erratum: bool,
    /// The times the claim is quantified over.
    pub times: Times,
    /// What the statement quantifies over (`\\label` and words): a path
    /// outside it (`N` below the least `N`, a datum outside the
    /// hypothesis, a collision instant or `t = 0` for an a.e.-in-`t`
    /// statement) is excluded, and a refutation is shown where the ledger's
    /// shrinker would accept it ([`Domain::admits`]).
    pub domain: Domain,
}

impl Program for Target {
    fn run<S: Scalar>(&self, input: &Input<S>) -> PathEnd {
        let data = match input.data() {
            Ok(d) => d,
            Err(e) => return PathEnd::Excluded(e.to_string()),
        };
        let case = Case::with_times(Trajectory::new(data), input.times.clone());
        if let Err(outside) = self.domain.admits_datum(&case.traj) {
            return PathEnd::Excluded(outside.to_string());
        }
        for t in &input.times {
            if let Err(outside) = self.domain.admits_time(&case.traj, t) {
                return PathEnd::Excluded(outside.to_string());
            }
        }
        let claims: Vec<Claim<S>> = registry();
        let Some(claim) = claims.iter().find(|c| c.id == self.registry_id) else {
            return PathEnd::Excluded(format!("no claim {}", self.registry_id));
        };
        if !(claim.applies)(&case) {
            return PathEnd::Holds;
        }
        if self.registry_id == IDENTITY_ARGUMENT && self.statement == Statement::Printed {
            // The identity argument (`telescope`): where the engine's history
            // is a free flight between the cuts the residual is 0 without
            // being built; elsewhere the checker runs.
            if telescope::mass_telescopes(&case).is_ok() {
                return PathEnd::Holds;
            }
        }
        match claim.checker(self.statement) {
            Some(Kind::Case(check)) => match check(&case) {
                Ok(()) => PathEnd::Holds,
                Err(v) => PathEnd::Violated(v.to_string()),
            },
            _ => PathEnd::Excluded("not a per-case claim".into()),
        }
    }

    fn witness_times(&self, input: &Input<BigRational>) -> Result<Vec<BigRational>, String> {
        match self.domain.time {
            InTime::AlmostEvery => self.second_failing_time(input),
            InTime::Measure => self.history_end(input),
            _ => Ok(input.times.clone()),
        }
    }
}

impl Target {
    /// The witness time of a measure-in-`t` statement: its checker reads
    /// the measure (Dirac masses at the collision instants) over the whole
    /// history, whatever the solver's probe time, so the failure is shown
    /// up to the last collision instant (the solver's time when nothing
    /// collides). The checker is run again there: it must still fail, and
    /// the time passes [`Domain::admits_times`].
    fn history_end(&self, input: &Input<BigRational>) -> Result<Vec<BigRational>, String> {
        let data = input.data().map_err(|e| e.to_string())?;
        let traj = Trajectory::new(data);
        let Some(last) = traj.last_collision() else {
            return Ok(input.times.clone());
        };
        let times = vec![last.clone()];
        self.domain
            .admits_times(&traj, &times)
            .map_err(|why| format!("witness time refused: {why}"))?;
        let shown = Input {
            times: times.clone(),
            ..input.clone()
        };
        match self.run(&shown) {
            PathEnd::Violated(_) => Ok(times),
            other => Err(format!(
                "the checker fails at t = {} but not when shown up to the last collision at t = {} ({other:?})",
                input
                    .times
                    .last()
                    .map(crate::rational::render_exact)
                    .unwrap_or_default(),
                crate::rational::render_exact(last)
            )),
        }
    }

    /// A second failing time for an a.e.-in-`t` statement: the solver's
    /// time `t` lies strictly inside an open interval between collision
    /// instants (the collision instants themselves are excluded paths);
    /// times are tried toward each end of that interval, halving the step,
    /// until the checker fails there too. The two times are returned in
    /// increasing order and pass [`Domain::admits_times`].
    fn second_failing_time(&self, input: &Input<BigRational>) -> Result<Vec<BigRational>, String> {
        let [t] = input.times.as_slice() else {
            return Ok(input.times.clone());
        };
        let data = input.data().map_err(|e| e.to_string())?;
        let traj = Trajectory::new(data);
        let (lo, hi) = crate::claims::domain::interval_of(&traj, t);
        let two = BigRational::from_integer(2.into());
        let right = match hi {
            Some(h) => h - t,
            None => <BigRational as One>::one(),
        };
        let left = t - &lo;
        let at = |c: &BigRational| {
            let probe = Input {
                times: vec![c.clone()],
                ..input.clone()
            };
            matches!(self.run(&probe), PathEnd::Violated(_))
        };
        for k in 1..=SECOND_TIME_HALVINGS {
            let scale = num_traits::pow(two.clone(), k);
            for candidate in [t + &(right.clone() / &scale), t - &(left.clone() / &scale)] {
                if candidate != *t && at(&candidate) {
                    let mut times = vec![t.clone(), candidate];
                    times.sort();
                    self.domain
                        .admits_times(&traj, &times)
                        .map_err(|why| format!("second witness time refused: {why}"))?;
                    return Ok(times);
                }
            }
        }
        Err(format!(
            "the checker fails at t = {} but at no other time tried in its interval between collisions ({SECOND_TIME_HALVINGS} halvings each way): not shown on a set of positive measure",
            crate::rational::render_exact(t)
        ))
    }
}

/// How many times the step toward each end of the interval is halved in
/// the search for a second failing time.
const SECOND_TIME_HALVINGS: usize = 24;

/// The claim decided by its identity argument ([`telescope`]) on every
/// path where the argument's condition holds (the checker's residual is
/// computed on the others).
pub const IDENTITY_ARGUMENT: &str = "prop:eulerian-formulation#mass";

/// The note of a claim proved by [`IDENTITY_ARGUMENT`]'s route.
const IDENTITY_NOTE: &str = "decided by the identity argument (src/prove/telescope.rs): the checker's integrand on each piece is the exact τ-derivative of B(t)·Σ_i Q(x_i(a) + (t − a)u_i(a)) and its bump vanishes at both ends of each window (identities of its code, proved symbolically by the module's tests); on every path of the dynamics the engine's positions at each cut are the free flight x_i(a) + (b − a)u_i(a) = x_i(b) from the piece before, so R_mass^N(φ) telescopes to 0; where that fails on a path, the checker's own residual is computed there";

/// Claims checked at two times (`Ω` grows, the semigroup identities, the
/// coupling bound of `lem:density`).
const TWO_TIMES: [&str; 4] = [
    "lem:density",
    "eq:semigroup",
    "eq:projortho-sg",
    "df:H-micro#contacts-grow",
];

/// Corrected statements whose checker is beyond the prover, with the
/// reason (they are checked exactly on every numeric case by the other
/// engines; their printed statements are still refuted symbolically).
pub const NOT_SYMBOLIC: [(&str, &str); 2] = [
    (
        "eq:test-pressure-bound",
        "the test function ϕ(t) = (t − a)²(b − t)² with a, b built from the collision times, integrated piece by piece, gives rational functions of degree 7 or more in the data that z3's nlsat does not decide within the limits (unknown at N = 2)",
    ),
    (
        "prop:pressure-bound#test-function",
        "its correction is checked by eq:test-pressure-bound's corrected checker (see there)",
    ),
];

/// Every per-case claim of the registry (section 2, Appendix A, the
/// discrete claims of section 3), printed and corrected, in registry order
/// (corrected statements of [`NOT_SYMBOLIC`] left out).
pub fn targets() -> Vec<Target> {
    let mut out = Vec::new();
    for c in registry::<BigRational>() {
        if !matches!(c.kind, Kind::Case(_)) {
            continue;
        }
        let symbolic = !NOT_SYMBOLIC.iter().any(|(id, _)| *id == c.id);
        let times = if TWO_TIMES.contains(&c.id) {
            Times::Two
        } else {
            Times::One
        };
        match &c.correction {
            None => out.push(Target {
                id: c.id.to_string(),
                registry_id: c.id,
                statement: Statement::Printed,
                erratum: false,
                times,
                domain: c.domain,
            }),
            Some(corr) => {
                out.push(Target {
                    id: c.id.to_string(),
                    registry_id: c.id,
                    statement: Statement::Printed,
                    erratum: true,
                    times,
                    domain: c.domain,
                });
                if symbolic && matches!(corr.check, Kind::Case(_)) {
                    out.push(Target {
                        id: format!("{} (corrected)", c.id),
                        registry_id: c.id,
                        statement: Statement::Corrected,
                        erratum: false,
                        times,
                        domain: CORRECTION_DOMAIN,
                    });
                }
            }
        }
    }
    out
}

/// Proves one registry target at N.
pub fn prove_target(target: &Target, n: usize, limits: Limits) -> ProofResult {
    prove_target_observed(target, n, limits, &Silent)
}

/// [`prove_target`], telling `progress` of every path explored.
pub fn prove_target_observed(
    target: &Target,
    n: usize,
    limits: Limits,
    progress: &dyn Progress,
) -> ProofResult {
    let mut result = prove_program_observed(&target.id, n, target.times, target, limits, progress);
    if target.registry_id == IDENTITY_ARGUMENT
        && target.statement == Statement::Printed
        && result.status == Status::Proved
    {
        let how = IDENTITY_NOTE.to_string();
        result.note = Some(match result.note.take() {
            Some(other) => format!("{how}; {other}"),
            None => how,
        });
    }
    result
}
