//! The explorer's loop: every queued path replayed from the start, depth
//! first, until none is left, a path reaches a violation, or a limit stops
//! the attempt.

use std::any::Any;
use std::collections::HashMap;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::time::{Duration, Instant};

use num_traits::Signed;

use super::{
    flip, satisfies, Branch, Exploration, Hypothesis, Limits, NamesGuard, PathEnd, PathState,
    Verdict, NEG, POS, STATE, ZERO,
};
use crate::progress::Progress;
use crate::prove::budget;
use crate::prove::eliminate::{Atom, Constraint};
use crate::prove::poly::Poly;
use crate::prove::smt::{Sat, Solver, SolverError, SolverLimits};

/// The hypotheses as the path condition every path starts from.
struct Base {
    /// As SMT-LIB text.
    pc: Vec<String>,
    /// The signs they leave possible for each normalised polynomial.
    masks: HashMap<Poly, u8>,
    /// As polynomial constraints.
    cons: Vec<Constraint>,
}

impl Base {
    fn of(hypotheses: &[Hypothesis], names: &[String]) -> Base {
        let mut base = Base {
            pc: Vec::new(),
            masks: HashMap::new(),
            cons: Vec::new(),
        };
        for h in hypotheses {
            match h {
                Hypothesis::Sign(p, rel) => {
                    let (np, lead) = p.normalized();
                    let m = if lead.is_negative() {
                        flip(rel.mask())
                    } else {
                        rel.mask()
                    };
                    *base.masks.entry(np).or_insert(NEG | ZERO | POS) &= m;
                    base.pc.push(rel.smt(&p.smt(names)));
                    base.cons.push(Constraint::Atom(Atom {
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
                    base.pc.push(c.smt(names));
                    base.cons.push(c);
                }
            }
        }
        base
    }
}

impl PathState {
    fn start(solver: Solver, names: &[String], base: &Base) -> Self {
        PathState {
            forced: Vec::new(),
            taken: Vec::new(),
            branches: Vec::new(),
            model: None,
            masks: base.masks.clone(),
            pc: base.pc.clone(),
            full_pc: base.pc.clone(),
            cons: base.cons.clone(),
            quotients: Vec::new(),
            squares: Vec::new(),
            solver,
            names: names.to_vec(),
            queries: 0,
            unknown_answers: 0,
            fault: None,
            error: None,
        }
    }

    /// Back to the hypotheses alone, to replay `branch` (the solver process
    /// is kept).
    fn reset(&mut self, branch: Branch, base: &Base) {
        self.forced = branch.prefix;
        self.model = branch.model;
        self.taken.clear();
        self.branches.clear();
        self.masks = base.masks.clone();
        self.pc = base.pc.clone();
        self.full_pc = base.pc.clone();
        self.cons = base.cons.clone();
        self.quotients.clear();
        self.squares.clear();
        self.queries = 0;
        self.unknown_answers = 0;
        self.fault = None;
        self.error = None;
    }
}

/// Whether the loop goes on after a path.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Step {
    /// The next queued path.
    Next,
    /// The verdict is in (or the attempt gave up).
    Stop,
}

/// The loop's state: the paths still queued and what was found so far.
struct Explorer<'a> {
    base: Base,
    names: &'a [String],
    limits: Limits,
    deadline: Instant,
    stack: Vec<Branch>,
    result: Exploration,
    /// Queries answered `unknown` and counted feasible, over every path.
    unknown_total: usize,
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
    let _names = NamesGuard::install(names);
    let base = Base::of(hypotheses, names);
    let mut result = Exploration {
        paths: 0,
        // The hypotheses must be satisfiable, or everything is vacuous.
        queries: 1,
        excluded: 0,
        seconds: 0.0,
        verdict: Verdict::Proved,
    };
    let base_model = match solver.check(&base.pc, None)? {
        Sat::Sat => solver.model(names)?,
        other => {
            result.verdict = Verdict::Unknown(format!("hypotheses not satisfiable ({other:?})"));
            return Ok(result);
        }
    };
    let state = PathState::start(solver, names, &base);
    let mut explorer = Explorer {
        base,
        names,
        limits,
        deadline,
        stack: vec![Branch {
            prefix: Vec::new(),
            model: base_model,
        }],
        result,
        unknown_total: 0,
    };
    let state = explorer.run(state, program, progress);
    // Kills the solver before the time is taken.
    drop(state);
    let mut result = explorer.finish();
    result.seconds = start.elapsed().as_secs_f64();
    Ok(result)
}

impl Explorer<'_> {
    /// Runs the queued paths until a verdict; hands back the path state
    /// (its solver process) when it was not lost.
    fn run(
        &mut self,
        state: PathState,
        program: &dyn Fn() -> PathEnd,
        progress: &dyn Progress,
    ) -> Option<PathState> {
        let mut state = Some(state);
        while let Some(branch) = self.stack.pop() {
            if let Some(why) = self.stop_reason(progress) {
                self.result.verdict = Verdict::Unknown(why);
                break;
            }
            let mut st = state.take()?;
            st.reset(branch, &self.base);
            STATE.with(|s| *s.borrow_mut() = Some(st));
            let end = catch_unwind(AssertUnwindSafe(program));
            let Some(mut st) = STATE.with(|s| s.borrow_mut().take()) else {
                self.result.verdict = Verdict::Unknown("the oracle state was lost".into());
                return None;
            };
            let step = self.after_path(&mut st, end, progress);
            state = Some(st);
            if step == Step::Stop {
                break;
            }
        }
        state
    }

    /// Why the attempt stops before the next path (its branch just popped),
    /// if it does: the path limit, an interruption, the deadline.
    fn stop_reason(&self, progress: &dyn Progress) -> Option<String> {
        let paths = self.result.paths;
        let queued = self.stack.len() + 1;
        if paths >= self.limits.max_paths {
            Some(format!(
                "path limit reached ({paths} paths, {queued} still queued)"
            ))
        } else if progress.cancelled() {
            Some(format!(
                "interrupted after {paths} paths ({queued} still queued)"
            ))
        } else if Instant::now() > self.deadline {
            Some(format!(
                "the time budget of {} s ran out between paths, after {paths} paths ({queued} still queued)",
                self.limits.time.as_secs()
            ))
        } else {
            None
        }
    }

    /// Counts the path just run, queues its branches and reads how it ended.
    fn after_path(
        &mut self,
        st: &mut PathState,
        end: std::thread::Result<PathEnd>,
        progress: &dyn Progress,
    ) -> Step {
        if let Err(payload) = &end {
            if let Some(why) = budget::overrun(payload.as_ref()) {
                self.result.queries += st.queries;
                return self.stop_unknown(format!(
                    "{why}: path {} abandoned after {} complete paths ({} still queued)",
                    self.result.paths + 1,
                    self.result.paths,
                    self.stack.len() + st.branches.len()
                ));
            }
        }
        self.result.paths += 1;
        self.result.queries += st.queries;
        progress.advance(1);
        progress.note(&format!(
            "{} paths, {} s left",
            self.result.paths,
            self.deadline
                .saturating_duration_since(Instant::now())
                .as_secs()
        ));
        self.unknown_total += st.unknown_answers;
        // Depth first: the last alternative found is explored next.
        self.stack.append(&mut st.branches);
        if let Some(e) = st.error.take() {
            return self.stop_unknown(e);
        }
        let end = end.unwrap_or_else(|panic| {
            PathEnd::Violated(format!("the engine panicked: {}", panic_message(&*panic)))
        });
        let end = match (st.fault.take(), end) {
            (Some(f), PathEnd::Holds) => PathEnd::Violated(format!("engine fault: {f}")),
            (_, e) => e,
        };
        match end {
            PathEnd::Holds => Step::Next,
            PathEnd::Excluded(_) => {
                self.result.excluded += 1;
                Step::Next
            }
            PathEnd::Violated(message) => self.settle_violation(st, message),
        }
    }

    /// A path ended in a violation: is it feasible (not let through by an
    /// `unknown`)? If so, the counterexample is an exact rational point on it.
    fn settle_violation(&mut self, st: &mut PathState, message: String) -> Step {
        self.result.queries += 1;
        let mut reduced_point = None;
        let answer = match st.solver.check(&st.full_pc, None) {
            Ok(Sat::Unknown) => {
                st.queries = 0;
                let r = st.check_reduced(None);
                self.result.queries += st.queries;
                match r {
                    Ok((a, point)) => {
                        reduced_point = point;
                        a
                    }
                    Err(e) => {
                        return self.stop_unknown(format!(
                            "{e} (deciding a path to a violation: {message})"
                        ))
                    }
                }
            }
            Ok(a) => a,
            Err(e) => {
                return self
                    .stop_unknown(format!("{e} (deciding a path to a violation: {message})"))
            }
        };
        match answer {
            // An infeasible path let through by an `unknown`.
            Sat::Unsat => Step::Next,
            Sat::Unknown => self.stop_unknown(format!(
                "a path to a violation could not be decided by the solver: {message}"
            )),
            Sat::Sat => {
                // A completed model of the reduced query satisfies the path
                // condition when checked exactly.
                let exact = reduced_point.filter(|m| satisfies(&st.cons, m));
                let point = match exact {
                    Some(m) => Ok(Some(m)),
                    None => st.solver.rational_model(&st.full_pc, self.names),
                };
                self.result.queries += 2 * self.names.len();
                self.result.verdict = match point {
                    Ok(Some(point)) => Verdict::Counterexample { message, point },
                    Ok(None) => Verdict::Unknown(format!(
                        "a feasible path to a violation, but no rational point on it was found: {message}"
                    )),
                    Err(e) => Verdict::Unknown(format!(
                        "{e} (building a rational point on a path to a violation: {message})"
                    )),
                };
                Step::Stop
            }
        }
    }

    fn stop_unknown(&mut self, why: String) -> Step {
        self.result.verdict = Verdict::Unknown(why);
        Step::Stop
    }

    /// The result, an unproved claim if any query was let through by an
    /// `unknown` answer.
    fn finish(self) -> Exploration {
        let mut result = self.result;
        if matches!(result.verdict, Verdict::Proved) && self.unknown_total > 0 {
            result.verdict = Verdict::Unknown(format!(
                "{} solver queries timed out (answered `unknown`)",
                self.unknown_total
            ));
        }
        result
    }
}

/// The message of a caught panic.
fn panic_message(panic: &(dyn Any + Send)) -> String {
    panic
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| panic.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "panic".into())
}
