//! Dropping the nonlinear constraints of a query the solver could not
//! decide (issue 29): a weaker system, so an `unsat` answer on it is an
//! `unsat` answer on the query, and nothing else is concluded from it.
//!
//! A path condition through several collisions carries the orderings of
//! their times, cross-multiplied: degree-4 polynomials in `(x⁰, u⁰)` that
//! make z3's `nlsat` slow, while the decision at hand often follows from the
//! hypotheses and the linear facts alone. At N = 3 `prop:Linf-micro` asks
//! whether `(x⁰_N − x⁰_0) + 2T sup|u⁰| > (1 + 2T)C'_0` can hold on a path
//! with three such constraints: `nlsat` does not answer it as asked, and
//! answers `unsat` at once with only the linear constraints and the
//! question (timings in `docs/journal.md`).

//!
//! A second relaxation ([`linearize`]) keeps every constraint but reads
//! each monomial of degree ≥ 2 as a variable of its own: linear arithmetic
//! on the same atoms. At N = 3 `lem:density`'s summed bound is a positive
//! combination of its per-cell bounds, which the path condition already
//! holds, term by term: refuted by linear arithmetic, while `nlsat` does
//! not decide it through the path's degree-4 orderings.

use std::collections::BTreeMap;

use super::eliminate::{Atom, Constraint};
use super::explore::Rel;
use super::poly::{Poly, Var};

/// The constraints of `system` whose polynomials all have total degree at
/// most 1, followed by `question` (kept whatever its degree): every point
/// of `system ∧ question` satisfies the result.
pub fn linear_part(system: &[Constraint], question: Option<&Atom>) -> Vec<Constraint> {
    let linear = |a: &Atom| a.poly.degree() <= 1;
    let mut out: Vec<Constraint> = system
        .iter()
        .filter(|c| match c {
            Constraint::Atom(a) => linear(a),
            Constraint::Any(atoms) => atoms.iter().all(linear),
        })
        .cloned()
        .collect();
    out.extend(question.cloned().map(Constraint::Atom));
    out
}

/// A system with its monomials of degree ≥ 2 read as fresh variables.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Linearized {
    /// The constraints, linear in the original and the fresh variables,
    /// then `m ≥ 0` for each fresh monomial `m` that is a square.
    pub constraints: Vec<Constraint>,
    /// The monomial each fresh variable stands for, the `k`-th being the
    /// variable `first + k`.
    pub monomials: Vec<Vec<Var>>,
}

/// `system` with every monomial of degree ≥ 2 replaced by a fresh variable
/// (numbered from `first`, one per distinct monomial), and `m ≥ 0` added
/// for the monomials that are squares (every variable to an even power);
/// first the squares of `squared`, their sums and differences in pairs
/// are added as non-negative (true of every point).
/// An over-approximation: a point of `system` gives, with each fresh
/// variable set to its monomial's value, a point of the result; so the
/// result's `unsat` is `system`'s, and its `sat` says nothing. `None` when
/// there is no such monomial (nothing to gain: [`linear_part`] already
/// asked the linear constraints) or the fresh variables would not fit in
/// [`Var`].
pub fn linearize(system: &[Constraint], squared: &[Poly], first: Var) -> Option<Linearized> {
    // Facts of every real point: `p² ≥ 0` for the polynomials the program
    // squared, `(p − q)² ≥ 0` and `(p + q)² ≥ 0` for each pair of them
    // (`pq ≤ (p² + q²)/2`, the step from `p², q² ≤ B` to
    // `(p² + pq + q²)/3 ≤ B`, which the monomials alone do not see).
    let mut with_facts = system.to_vec();
    for (i, p) in squared.iter().enumerate() {
        let mut bases = vec![p.clone()];
        for q in &squared[i + 1..] {
            bases.push(p.sub(q));
            bases.push(p.add(q));
        }
        with_facts.extend(bases.iter().map(|b| {
            Constraint::Atom(Atom {
                poly: b.mul(b),
                rel: Rel::Ge,
            })
        }));
    }
    let system = &with_facts[..];
    let mut fresh: BTreeMap<Vec<Var>, Var> = BTreeMap::new();
    let mut monomials: Vec<Vec<Var>> = Vec::new();
    let mut linear = |p: &Poly| -> Option<Poly> {
        let mut out = Poly::zero();
        for (m, c) in p.terms() {
            let term = if m.len() <= 1 {
                m.iter()
                    .fold(Poly::constant(c.clone()), |acc, &v| acc.mul(&Poly::var(v)))
            } else {
                let v = match fresh.get(m) {
                    Some(&v) => v,
                    None => {
                        let k = Var::try_from(monomials.len()).ok()?;
                        let v = first.checked_add(k)?;
                        fresh.insert(m.to_vec(), v);
                        monomials.push(m.to_vec());
                        v
                    }
                };
                Poly::var(v).scale(c)
            };
            out = out.add(&term);
        }
        Some(out)
    };
    let mut atom = |a: &Atom| -> Option<Atom> {
        Some(Atom {
            poly: linear(&a.poly)?,
            rel: a.rel,
        })
    };
    let mut constraints = Vec::with_capacity(system.len());
    for c in system {
        constraints.push(match c {
            Constraint::Atom(a) => Constraint::Atom(atom(a)?),
            Constraint::Any(atoms) => {
                Constraint::Any(atoms.iter().map(&mut atom).collect::<Option<_>>()?)
            }
        });
    }
    if monomials.is_empty() {
        return None;
    }
    for m in &monomials {
        let square = m.chunk_by(|a, b| a == b).all(|run| run.len() % 2 == 0);
        if square {
            constraints.push(Constraint::Atom(Atom {
                poly: Poly::var(fresh[m]),
                rel: Rel::Ge,
            }));
        }
    }
    Some(Linearized {
        constraints,
        monomials,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::prove::explore::Rel;
    use crate::prove::poly::Poly;
    use crate::prove::smt::{available, Sat, Solver, SolverLimits};
    use crate::rational::ratio as q;
    use num_rational::BigRational;
    use std::time::{Duration, Instant};

    fn atom(poly: Poly, rel: Rel) -> Constraint {
        Constraint::Atom(Atom { poly, rel })
    }

    fn holds(system: &[Constraint], point: &[BigRational]) -> bool {
        system.iter().all(|c| match c {
            Constraint::Atom(a) => a.rel.holds_for(&a.poly.eval(point)),
            Constraint::Any(atoms) => atoms.iter().any(|a| a.rel.holds_for(&a.poly.eval(point))),
        })
    }

    /// z3's answer on `system` over `vars` variables; `None` without z3
    /// (on CI, where z3 is installed, a missing z3 fails the test).
    fn ask(system: &[Constraint], vars: usize) -> Option<Sat> {
        if available().is_none() {
            assert!(std::env::var_os("CI").is_none(), "z3 is missing on CI");
            eprintln!("skipped: the SMT solver z3 is not installed");
            return None;
        }
        let names: Vec<String> = (0..vars).map(|k| format!("v{k}")).collect();
        let limits = SolverLimits {
            query_ms: 10_000,
            deadline: Instant::now() + Duration::from_secs(60),
            memory_mb: 1024,
        };
        let mut solver = Solver::start(&names, limits).unwrap();
        let text: Vec<String> = system.iter().map(|c| c.smt(&names)).collect();
        Some(solver.check(&text, None).unwrap())
    }

    fn lin(system: &[Constraint], vars: Var) -> (Linearized, usize) {
        let l = linearize(system, &[], vars).unwrap();
        let total = usize::from(vars) + l.monomials.len();
        (l, total)
    }

    /// A point of the system, with every fresh variable set to its
    /// monomial's value, is a point of the linearized system.
    #[test]
    fn a_point_of_the_system_is_a_point_of_its_linearization() {
        let (x, y) = (Poly::var(0), Poly::var(1));
        let xy = x.mul(&y);
        let system = [
            atom(xy.sub(&Poly::constant(q(1, 1))), Rel::Ge),
            atom(x.mul(&x).mul(&y).scale(&q(-3, 2)).add(&y), Rel::Gt),
            Constraint::Any(vec![
                Atom {
                    poly: y.mul(&y).sub(&Poly::constant(q(5, 1))),
                    rel: Rel::Gt,
                },
                Atom {
                    poly: x.clone(),
                    rel: Rel::Le,
                },
            ]),
        ];
        let point = [q(-1, 1), q(-2, 1)];
        assert!(holds(&system, &point));
        let (l, _) = lin(&system, 2);
        assert_eq!(l.monomials, vec![vec![0, 1], vec![0, 0, 1], vec![1, 1]]);
        let mut lifted = point.to_vec();
        lifted.extend(l.monomials.iter().map(|m| {
            m.iter()
                .fold(q(1, 1), |acc, &v| acc * &point[usize::from(v)])
        }));
        assert!(holds(&l.constraints, &lifted));
        // A linear system has nothing to linearize.
        assert_eq!(linearize(&[atom(x.add(&y), Rel::Lt)], &[], 2), None);
    }

    /// The summed bound of `lem:density` in miniature: two nonlinear
    /// bounds on the path and their positive combination asked. The
    /// linear part alone is satisfiable; the linearization is `unsat`.
    #[test]
    fn a_positive_combination_of_nonlinear_bounds_is_refuted() {
        let (x, y) = (Poly::var(0), Poly::var(1));
        let one = Poly::constant(q(1, 1));
        let a = x.mul(&x).add(&x.mul(&y)); // a ≤ 1
        let b = y.mul(&y).mul(&x).scale(&q(2, 1)).sub(&x.mul(&y)); // b ≤ 1
        let path = [atom(a.sub(&one), Rel::Le), atom(b.sub(&one), Rel::Le)];
        // 3a + 5b > 8 contradicts the path (3·1 + 5·1 = 8).
        let question = Atom {
            poly: a
                .scale(&q(3, 1))
                .add(&b.scale(&q(5, 1)))
                .sub(&Poly::constant(q(8, 1))),
            rel: Rel::Gt,
        };
        let mut system = path.to_vec();
        system.push(Constraint::Atom(question.clone()));
        if ask(&linear_part(&path, Some(&question)), 2) == Some(Sat::Unsat) {
            panic!("the linear part should not decide this");
        }
        let (l, vars) = lin(&system, 2);
        if let Some(answer) = ask(&l.constraints, vars) {
            assert_eq!(answer, Sat::Unsat);
        }
    }

    /// The cell step of `lem:density` in miniature: `g², h² ≤ z` on the
    /// path, `g² + gh + h² > 3z` asked. Refuted only with `g`, `h` noted
    /// as squared (`(g − h)² ≥ 0` added); without, the linearization is
    /// satisfiable.
    #[test]
    fn the_squared_bases_give_the_cell_step() {
        // (g − h)² = (x − w)²: not a sum of monomial squares.
        let (x, y, w, z) = (Poly::var(0), Poly::var(1), Poly::var(2), Poly::var(3));
        let g = x.add(&y);
        let h = y.add(&w);
        let system = [
            atom(g.mul(&g).sub(&z), Rel::Le),
            atom(h.mul(&h).sub(&z), Rel::Le),
            atom(
                g.mul(&g)
                    .add(&g.mul(&h))
                    .add(&h.mul(&h))
                    .sub(&z.scale(&q(3, 1))),
                Rel::Gt,
            ),
        ];
        let (l, vars) = lin(&system, 4);
        if let Some(answer) = ask(&l.constraints, vars) {
            assert_ne!(answer, Sat::Unsat);
        }
        let l = linearize(&system, &[g.clone(), h.clone()], 4).unwrap();
        let vars = 4 + l.monomials.len();
        if let Some(answer) = ask(&l.constraints, vars) {
            assert_eq!(answer, Sat::Unsat);
        }
    }

    /// A satisfiable system is not called `unsat` (here `x·y ≥ 1`,
    /// `x, y ≤ 0`: the point (−1, −1)), and a square is non-negative:
    /// `x² < 0` is refuted only through the added `m ≥ 0`.
    #[test]
    fn a_satisfiable_system_is_not_refuted_and_squares_are_non_negative() {
        let (x, y) = (Poly::var(0), Poly::var(1));
        let sat = [
            atom(x.mul(&y).sub(&Poly::constant(q(1, 1))), Rel::Ge),
            atom(x.clone(), Rel::Le),
            atom(y.clone(), Rel::Le),
        ];
        let (l, vars) = lin(&sat, 2);
        if let Some(answer) = ask(&l.constraints, vars) {
            assert_ne!(answer, Sat::Unsat);
        }
        let (l, vars) = lin(&[atom(x.mul(&x).mul(&y).mul(&y), Rel::Lt)], 2);
        if let Some(answer) = ask(&l.constraints, vars) {
            assert_eq!(answer, Sat::Unsat);
        }
    }

    /// The quadratic constraint goes, the linear ones and the question stay
    /// (a question of degree 2 included): the result is weaker, never
    /// stronger — a mutant that also dropped the question, or kept only it,
    /// would change the list checked here.
    #[test]
    fn only_nonlinear_constraints_are_dropped() {
        let (x, t) = (Poly::var(0), Poly::var(1));
        let linear = Constraint::Atom(Atom {
            poly: x.sub(&Poly::constant(q(1, 3))),
            rel: Rel::Gt,
        });
        let quadratic = Constraint::Atom(Atom {
            poly: x.mul(&t),
            rel: Rel::Lt,
        });
        let mixed = Constraint::Any(vec![
            Atom {
                poly: t.clone(),
                rel: Rel::Ge,
            },
            Atom {
                poly: t.mul(&t),
                rel: Rel::Le,
            },
        ]);
        let question = Atom {
            poly: x.mul(&t).add(&t),
            rel: Rel::Gt,
        };
        let system = [linear.clone(), quadratic, mixed];
        assert_eq!(
            linear_part(&system, Some(&question)),
            vec![linear.clone(), Constraint::Atom(question)]
        );
        assert_eq!(linear_part(&system, None), vec![linear]);
    }
}
