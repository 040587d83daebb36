//! Eliminating a variable by an equality of the path condition that is
//! linear in it, before a query the solver could not decide (issue 29).
//!
//! On a path through a tie (two collision times equal, a collision at the
//! probe time), the path condition holds equalities such as
//! `2(u₃ − u₂) x₁ + q(x₂, x₃, u) = 0`. z3's `nlsat` does not always decide a
//! query with them: at N = 3 `lem:density`'s coupling bound under a triple
//! collision is not answered, while the same query with `x₁` replaced by
//! `−q/(2(u₃ − u₂))` is `unsat` at once (timings in `docs/journal.md`).
//!
//! **The step.** Let `a·v + b = 0` be an equality of the system with `a`, `b`
//! free of `v` and `a ≠ 0` implied by the system (a non-zero constant, or a
//! polynomial whose sign the path condition fixes away from 0 — the caller's
//! `nonzero`). On the points of the system `v = −b/a`, so each other
//! constraint `q rel 0` of degree `d` in `v` is replaced by
//! `q(−b/a) · a^e rel 0` with `e = d` rounded up to an even number: `a^e > 0`,
//! so the sign, and the relation, is unchanged. The system without `v` is
//! satisfiable exactly when the original one is: a solution of the original
//! one is a solution of the reduced one (drop `v`), and a solution of the
//! reduced one gives a solution of the original one with `v = −b/a` (`a ≠ 0`
//! there, since `a` does not involve `v` and the system implied it). A
//! constraint that becomes a constant is decided at once: true, it is
//! dropped; false, the system is unsatisfiable. The eliminated values are
//! recovered from a model of the reduced system ([`Reduced::complete`]).

use num_rational::BigRational;
use num_traits::Zero;

use super::explore::Rel;
use super::poly::{Poly, Var};

/// A sign condition `poly rel 0`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Atom {
    /// The polynomial.
    pub poly: Poly,
    /// Its sign condition.
    pub rel: Rel,
}

/// One constraint of a path condition.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Constraint {
    /// A sign condition.
    Atom(Atom),
    /// At least one of these sign conditions holds.
    Any(Vec<Atom>),
}

impl Constraint {
    /// The constraint as SMT-LIB text.
    pub fn smt(&self, names: &[String]) -> String {
        match self {
            Constraint::Atom(a) => a.rel.smt(&a.poly.smt(names)),
            Constraint::Any(atoms) => {
                let parts: Vec<String> = atoms
                    .iter()
                    .map(|a| a.rel.smt(&a.poly.smt(names)))
                    .collect();
                format!("(or {})", parts.join(" "))
            }
        }
    }
    fn atoms(&self) -> &[Atom] {
        match self {
            Constraint::Atom(a) => std::slice::from_ref(a),
            Constraint::Any(atoms) => atoms,
        }
    }
}

/// A variable eliminated: `var = −rest / coefficient`.
#[derive(Debug, Clone)]
pub struct Elimination {
    /// The variable.
    pub var: Var,
    /// `a`, non-zero on the system.
    pub coefficient: Poly,
    /// `b`.
    pub rest: Poly,
}

/// The system after the eliminations.
#[derive(Debug, Clone)]
pub enum Reduced {
    /// A constraint became a false constant: no real point satisfies it.
    Unsatisfiable,
    /// An equivalent system over the variables not eliminated.
    System {
        /// The remaining constraints.
        constraints: Vec<Constraint>,
        /// The eliminations, in the order done.
        eliminated: Vec<Elimination>,
    },
}

impl Reduced {
    /// A point of the original system from a point of the reduced one: the
    /// eliminated variables set to `−b/a`, last eliminated first. `None`
    /// when a coefficient vanishes at the point (not a point of the reduced
    /// system).
    pub fn complete(&self, point: &[BigRational]) -> Option<Vec<BigRational>> {
        let Reduced::System { eliminated, .. } = self else {
            return None;
        };
        let mut point = point.to_vec();
        for e in eliminated.iter().rev() {
            let a = e.coefficient.eval(&point);
            if a.is_zero() {
                return None;
            }
            let value = -e.rest.eval(&point) / a;
            *point.get_mut(usize::from(e.var))? = value;
        }
        Some(point)
    }
}

/// The truth of `c rel 0` for a constant `c`.
fn constant_holds(c: &BigRational, rel: Rel) -> bool {
    rel.holds_for(c)
}

/// Replaces `v` by `−b/a` in one atom (see the module documentation):
/// `Ok(None)` when it became true, `Err(())` when it became false.
fn substitute(atom: &Atom, e: &Elimination) -> Result<Option<Atom>, ()> {
    let d = atom.poly.degree_in(e.var);
    let poly = if d == 0 {
        atom.poly.clone()
    } else {
        let even = d + d % 2;
        atom.poly
            .substitute(e.var, &e.rest.neg(), &e.coefficient, even)
    };
    match poly.as_constant() {
        Some(c) if constant_holds(&c, atom.rel) => Ok(None),
        Some(_) => Err(()),
        None => Ok(Some(Atom {
            poly,
            rel: atom.rel,
        })),
    }
}

/// Applies one elimination to a constraint: `Ok(None)` when it became
/// true, `Err(())` when false.
fn apply(c: &Constraint, e: &Elimination) -> Result<Option<Constraint>, ()> {
    match c {
        Constraint::Atom(a) => Ok(substitute(a, e)?.map(Constraint::Atom)),
        Constraint::Any(atoms) => {
            let mut kept = Vec::with_capacity(atoms.len());
            for a in atoms {
                match substitute(a, e) {
                    Ok(None) => return Ok(None),
                    Ok(Some(a)) => kept.push(a),
                    Err(()) => {}
                }
            }
            match kept.len() {
                0 => Err(()),
                1 => Ok(kept.pop().map(Constraint::Atom)),
                _ => Ok(Some(Constraint::Any(kept))),
            }
        }
    }
}

/// The equality to eliminate next: of the equalities linear in some
/// variable with a coefficient `nonzero` accepts, the one of least total
/// degree (then the first).
fn pick(
    constraints: &[Constraint],
    nonzero: &dyn Fn(&Poly) -> bool,
) -> Option<(usize, Elimination)> {
    let mut best: Option<(usize, usize, Elimination)> = None;
    for (k, c) in constraints.iter().enumerate() {
        let Constraint::Atom(Atom { poly, rel: Rel::Eq }) = c else {
            continue;
        };
        if best.as_ref().is_some_and(|(_, d, _)| *d <= poly.degree()) {
            continue;
        }
        let mut vars: Vec<Var> = poly.variables();
        vars.sort_unstable();
        for v in vars {
            if poly.degree_in(v) != 1 {
                continue;
            }
            let mut cs = poly.coefficients_in(v);
            let (Some(a), Some(b)) = (cs.pop(), cs.pop()) else {
                continue;
            };
            if a.as_constant().is_some_and(|c| c.is_zero()) {
                continue;
            }
            if a.as_constant().is_some() || nonzero(&a) {
                best = Some((
                    k,
                    poly.degree(),
                    Elimination {
                        var: v,
                        coefficient: a,
                        rest: b,
                    },
                ));
                break;
            }
        }
    }
    best.map(|(k, _, e)| (k, e))
}

/// Eliminates variables from `constraints` while an equality allows it (see
/// the module documentation). `nonzero(a)` must answer `true` only when
/// every point of `constraints` has `a ≠ 0` (the caller reads it from the
/// path condition); at most `max` variables are eliminated.
pub fn reduce(constraints: &[Constraint], nonzero: &dyn Fn(&Poly) -> bool, max: usize) -> Reduced {
    let mut system: Vec<Constraint> = constraints.to_vec();
    let mut eliminated: Vec<Elimination> = Vec::new();
    while eliminated.len() < max {
        let Some((k, e)) = pick(&system, nonzero) else {
            break;
        };
        let mut next = Vec::with_capacity(system.len());
        for (j, c) in system.iter().enumerate() {
            if j == k {
                continue;
            }
            match apply(c, &e) {
                Ok(Some(c)) => {
                    if !next.contains(&c) {
                        next.push(c);
                    }
                }
                Ok(None) => {}
                Err(()) => return Reduced::Unsatisfiable,
            }
        }
        debug_assert!(
            next.iter()
                .flat_map(Constraint::atoms)
                .all(|a| a.poly.degree_in(e.var) == 0),
            "the eliminated variable is gone"
        );
        system = next;
        eliminated.push(e);
    }
    Reduced::System {
        constraints: system,
        eliminated,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rational::ratio as q;

    fn atom(poly: Poly, rel: Rel) -> Constraint {
        Constraint::Atom(Atom { poly, rel })
    }
    fn c(n: i64, d: i64) -> Poly {
        Poly::constant(q(n, d))
    }
    fn never(_: &Poly) -> bool {
        false
    }

    /// The truth of a system at a point.
    fn holds(system: &[Constraint], point: &[BigRational]) -> bool {
        system.iter().all(|c| {
            c.atoms()
                .iter()
                .any(|a| a.rel.holds_for(&a.poly.eval(point)))
        })
    }

    /// `x − 1 = 0 ∧ x − 2 > 0` is decided unsatisfiable by the algebra;
    /// the mutant `x − 1 = 0 ∧ x − 1/2 > 0` is not (it is true).
    #[test]
    fn a_constant_contradiction_is_found_and_a_true_one_is_not() {
        let x = Poly::var(0);
        let sys = [
            atom(x.sub(&c(1, 1)), Rel::Eq),
            atom(x.sub(&c(2, 1)), Rel::Gt),
        ];
        assert!(matches!(reduce(&sys, &never, 4), Reduced::Unsatisfiable));
        let mutant = [
            atom(x.sub(&c(1, 1)), Rel::Eq),
            atom(x.sub(&c(1, 2)), Rel::Gt),
        ];
        match reduce(&mutant, &never, 4) {
            Reduced::System {
                constraints,
                eliminated,
            } => {
                assert!(constraints.is_empty());
                assert_eq!(eliminated.len(), 1);
            }
            Reduced::Unsatisfiable => panic!("x = 1 > 1/2 is satisfiable"),
        }
    }

    /// `u·x + 1 = 0` is not used while `u ≠ 0` is not known: `u = 0` would
    /// make it false whatever `x`, and eliminating `x = −1/u` would lose that.
    #[test]
    fn an_unknown_coefficient_is_refused() {
        let (x, u) = (Poly::var(0), Poly::var(1));
        let sys = [atom(u.mul(&x).add(&c(1, 1)), Rel::Eq), atom(x, Rel::Gt)];
        let Reduced::System { eliminated, .. } = reduce(&sys, &never, 4) else {
            panic!("nothing to decide without the coefficient's sign");
        };
        assert!(eliminated.is_empty());
    }

    /// With `u < 0` known, `u·x + 1 = 0` gives `x = −1/u > 0`: `x < 0` must
    /// become a condition false wherever `u < 0` — a relation flipped by an odd
    /// power of the negative coefficient would keep it true. The reduced and
    /// the original systems agree at every point of a grid.
    #[test]
    fn a_negative_coefficient_keeps_the_relations() {
        let (x, u) = (Poly::var(0), Poly::var(1));
        let sys = vec![
            atom(u.mul(&x).add(&c(1, 1)), Rel::Eq),
            atom(u.clone(), Rel::Lt),
            atom(x.clone(), Rel::Lt),
        ];
        let nonzero = |p: &Poly| *p == u;
        let reduced = reduce(&sys, &nonzero, 4);
        let Reduced::System {
            constraints,
            eliminated,
        } = &reduced
        else {
            panic!("a system remains")
        };
        assert_eq!(eliminated.len(), 1);
        for un in -4..=4 {
            let point = vec![q(0, 1), q(un, 2)];
            if holds(constraints, &point) {
                let full = reduced.complete(&point).expect("u ≠ 0 on the system");
                assert!(holds(&sys, &full), "a point of the reduced system extends");
            }
            if un != 0 {
                let full = vec![q(-2, un), q(un, 2)];
                assert_eq!(holds(&sys, &full), holds(constraints, &full));
            }
        }
        // Nowhere true: u < 0 and x = −1/u < 0 contradict.
        assert!((-4..=4).all(|un| !holds(constraints, &[q(0, 1), q(un, 2)])));
    }

    /// A quadratic constraint in the eliminated variable, and a disjunction:
    /// `2y·x − 3 = 0` with `y > 0` known, `x² − 1 ≥ 0`, `x < 1/4 ∨ y > 5`. The
    /// reduced system agrees with the original one on a grid, and its
    /// completion recovers `x = 3/(2y)`.
    #[test]
    fn substitution_is_an_equivalence_on_a_grid() {
        let (x, y) = (Poly::var(0), Poly::var(1));
        let sys = vec![
            atom(y.mul(&x).scale(&q(2, 1)).sub(&c(3, 1)), Rel::Eq),
            atom(y.clone(), Rel::Gt),
            atom(x.mul(&x).sub(&c(1, 1)), Rel::Ge),
            Constraint::Any(vec![
                Atom {
                    poly: x.sub(&c(1, 4)),
                    rel: Rel::Gt,
                },
                Atom {
                    poly: y.sub(&c(5, 1)),
                    rel: Rel::Gt,
                },
            ]),
        ];
        let two_y = y.scale(&q(2, 1));
        let nonzero = |p: &Poly| *p == two_y;
        let reduced = reduce(&sys, &nonzero, 4);
        let Reduced::System { constraints, .. } = &reduced else {
            panic!("satisfiable: y = 1, x = 3/2")
        };
        let mut seen_true = 0;
        for yn in 1..=40 {
            let yv = q(yn, 4);
            let xv = q(3, 1) / (q(2, 1) * &yv);
            let full = vec![xv.clone(), yv.clone()];
            let reduced_holds = holds(constraints, &full);
            assert_eq!(holds(&sys, &full), reduced_holds, "y = {yv}");
            if reduced_holds {
                seen_true += 1;
                assert_eq!(reduced.complete(&[q(7, 1), yv]), Some(full));
            }
        }
        assert!(
            seen_true > 0 && seen_true < 40,
            "both outcomes are exercised"
        );
    }
}
