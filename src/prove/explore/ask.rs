//! The query ladder of the path oracle: each query is asked of `nlsat`
//! within a short first try, then of cheap sound over-approximations
//! (the elimination of the variables the path's equalities determine, the
//! linear part, the monomials read as variables), then with the query's
//! own limit, then reduced and lifted (the path's quotients as variables).
//! An over-approximation's `unsat` is the query's; its `sat` says nothing.

use num_rational::BigRational;

use super::{Model, PathState, ZERO};
use crate::prove::eliminate::{self, Atom, Constraint, Reduced};
use crate::prove::lift;
use crate::prove::poly::{Poly, Var};
use crate::prove::relax;
use crate::prove::smt::{Sat, Solver, SolverError};

/// The first try of every query, in milliseconds: `nlsat` answers most of
/// them within it ([`PathState::ask`]).
const FIRST_TRY_MS: u64 = 200;

/// The time given to each cheap over-approximation of a query `nlsat` did
/// not answer within [`FIRST_TRY_MS`] (they are linear, or nearly).
const RELAXED_MS: u64 = 500;

/// The most quotients lifted to variables in one query.
const MAX_LIFTED: usize = 8;

impl PathState {
    /// Is `path condition ∧ extra` satisfiable (`text`: `extra` as
    /// SMT-LIB)? Asked of `nlsat` as before, with the query's own limit,
    /// but first within [`FIRST_TRY_MS`]: most queries are answered there,
    /// and the others are first given to the cheap over-approximations
    /// ([`PathState::refuted_cheaply`]), whose `unsat` is the query's. The
    /// answer is the one the single long query would give, or `unsat` where
    /// it would have given `unknown`, in less time when a relaxation
    /// settles it (the figures that chose this ladder are in
    /// `docs/journal.md`).
    pub(super) fn ask(
        &mut self,
        extra: &Atom,
        text: &str,
        model: Model,
    ) -> Result<(Sat, Option<Vec<BigRational>>), SolverError> {
        let full = self.solver.limits.query_ms;
        if full > FIRST_TRY_MS {
            let first = self.ask_nlsat(text, model, FIRST_TRY_MS)?;
            if first.0 != Sat::Unknown {
                return Ok(first);
            }
            if self.refuted_cheaply(extra)? {
                return Ok((Sat::Unsat, None));
            }
            self.queries += 1;
        }
        self.ask_nlsat(text, model, full)
    }

    /// `path condition ∧ text` asked of `nlsat` within `ms` milliseconds.
    pub(super) fn ask_nlsat(
        &mut self,
        text: &str,
        model: Model,
        ms: u64,
    ) -> Result<(Sat, Option<Vec<BigRational>>), SolverError> {
        match model {
            Model::Wanted => self
                .solver
                .check_with_model_within(&self.pc, text, &self.names, ms),
            Model::NotNeeded => Ok((self.solver.check_within(&self.pc, Some(text), ms)?, None)),
        }
    }

    /// `true` when a cheap over-approximation of `path condition ∧ extra`
    /// is unsatisfiable (then so is the query): the elimination of the
    /// variables the path's equalities determine ([`eliminate`]), then
    /// [`PathState::refuted_by_relaxation`], each solver call given
    /// [`RELAXED_MS`]. `false` says nothing.
    pub(super) fn refuted_cheaply(&mut self, extra: &Atom) -> Result<bool, SolverError> {
        let mut system = self.cons.clone();
        system.push(Constraint::Atom(extra.clone()));
        let (answer, _) = self.check_eliminated(&system, RELAXED_MS, Model::NotNeeded)?;
        if answer == Sat::Unsat {
            return Ok(true);
        }
        self.refuted_by_relaxation(&system, Some(extra), RELAXED_MS)
    }

    /// `a ≠ 0` on the path: the path condition excludes the sign 0 of `a`
    /// (up to a constant factor).
    pub(super) fn nonzero_on_path(&self, a: &Poly) -> bool {
        let (np, _) = a.normalized();
        self.masks.get(&np).is_some_and(|m| m & ZERO == 0)
    }

    /// `system` (the path condition and `extra`) with the variables that
    /// its equalities determine eliminated ([`eliminate::reduce`]), where
    /// the path condition shows the leading coefficient non-zero, asked
    /// within `ms` milliseconds: `unsat` when the algebra alone refutes it;
    /// with `sat`, the model (when wanted) completed with the eliminated
    /// values (exact, so it satisfies the path condition whenever the
    /// solver's values are rational); `unknown` when nothing was
    /// eliminated or the solver did not answer.
    pub(super) fn check_eliminated(
        &mut self,
        system: &[Constraint],
        ms: u64,
        model: Model,
    ) -> Result<(Sat, Option<Vec<BigRational>>), SolverError> {
        let reduced = eliminate::reduce(system, &|a| self.nonzero_on_path(a), self.names.len());
        let Reduced::System {
            constraints,
            eliminated,
        } = &reduced
        else {
            return Ok((Sat::Unsat, None));
        };
        if eliminated.is_empty() {
            return Ok((Sat::Unknown, None));
        }
        let text: Vec<String> = constraints.iter().map(|c| c.smt(&self.names)).collect();
        self.queries += 1;
        let answer = self.solver.check_within(&text, None, ms)?;
        let values = match (answer, model) {
            (Sat::Sat, Model::Wanted) => self
                .solver
                .model(&self.names)?
                .and_then(|m| reduced.complete(&m)),
            _ => None,
        };
        Ok((answer, values))
    }

    /// `true` when a weaker system than `system` (the path condition and
    /// `extra`) is unsatisfiable within `ms` milliseconds: its linear part
    /// and `extra` ([`relax::linear_part`]), then its monomials read as
    /// variables ([`relax::linearize`]). `false` says nothing.
    pub(super) fn refuted_by_relaxation(
        &mut self,
        system: &[Constraint],
        extra: Option<&Atom>,
        ms: u64,
    ) -> Result<bool, SolverError> {
        let weaker = relax::linear_part(&self.cons, extra);
        let text: Vec<String> = weaker.iter().map(|c| c.smt(&self.names)).collect();
        self.queries += 1;
        if self.solver.check_within(&text, None, ms)? == Sat::Unsat {
            return Ok(true);
        }
        let first = Var::try_from(self.names.len()).unwrap_or(Var::MAX);
        if let Some(lin) = relax::linearize(system, &self.squares, first) {
            let mut names = self.names.clone();
            names.extend((0..lin.monomials.len()).map(|k| format!("mono{k}")));
            let text: Vec<String> = lin.constraints.iter().map(|c| c.smt(&names)).collect();
            self.queries += 1;
            let mut solver = Solver::start(&names, self.solver.limits)?;
            if solver.check_within(&text, None, ms)? == Sat::Unsat {
                return Ok(true);
            }
        }
        Ok(false)
    }

    /// The query `path condition ∧ extra` asked again after eliminating the
    /// variables that equalities of the path condition determine
    /// ([`eliminate`]), for a query the solver answered `unknown` on as
    /// asked: `unsat` when the algebra alone refutes it; with `sat`, the
    /// model completed with the eliminated values (exact, so it satisfies
    /// the path condition whenever the solver's values are rational).
    /// Failing that, the linear part of the system and `extra` are asked
    /// ([`relax`]): `unsat` there is `unsat` here. Otherwise `unknown`.
    pub(super) fn check_reduced(
        &mut self,
        extra: Option<Atom>,
    ) -> Result<(Sat, Option<Vec<BigRational>>), SolverError> {
        let mut system = self.cons.clone();
        system.extend(extra.clone().map(Constraint::Atom));
        let full = self.solver.limits.query_ms;
        match self.check_eliminated(&system, full, Model::Wanted)? {
            (Sat::Unknown, _) => {}
            answer => return Ok(answer),
        }
        if self.refuted_by_relaxation(&system, extra.as_ref(), full)? {
            return Ok((Sat::Unsat, None));
        }
        self.check_lifted(&system)
    }

    /// The query with the path's quotients as variables of their own
    /// ([`lift`]), asked of a solver process that declares them; a model
    /// is cut back to the original variables.
    pub(super) fn check_lifted(
        &mut self,
        system: &[Constraint],
    ) -> Result<(Sat, Option<Vec<BigRational>>), SolverError> {
        let first = Var::try_from(self.names.len()).unwrap_or(Var::MAX);
        // As for the elimination: `den ≠ 0` when the path excludes sign 0.
        let nonzero = |a: &Poly| self.nonzero_on_path(a);
        let lifted = lift::lift(system, &self.quotients, &nonzero, first, MAX_LIFTED);
        if lifted.fresh.is_empty() {
            return Ok((Sat::Unknown, None));
        }
        let mut names = self.names.clone();
        names.extend((0..lifted.fresh.len()).map(|k| format!("tau{k}")));
        let text: Vec<String> = lifted.constraints.iter().map(|c| c.smt(&names)).collect();
        let mut solver = Solver::start(&names, self.solver.limits)?;
        self.queries += 1;
        match solver.check(&text, None)? {
            Sat::Sat => {
                let model = solver.model(&self.names)?;
                Ok((Sat::Sat, model))
            }
            other => Ok((other, None)),
        }
    }
}
