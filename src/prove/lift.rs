//! Quotients as variables of their own (issue 29): a query the solver could
//! not decide is asked again with one fresh variable `τ` per quotient
//! `num / den` the program compared on the path, bound by its defining
//! equation `τ·den − num = 0`.
//!
//! The quotients are the collision instants: the engine compares
//! `τ = gap / closing speed` with the probe times and with the other
//! collision instants, and the path condition holds those comparisons
//! cross-multiplied (`gap − t·closing`, `gap₁·closing₂ − gap₂·closing₁`),
//! polynomials of degree up to 4 in `(x⁰, u⁰)` without the instant itself.
//! At N = 3 `lem:density`'s coupling bound through a triple collision in
//! `(s, t)` is such a query: z3's `nlsat` does not answer it as asked, and
//! answers `unsat` at once with the two collision instants declared and
//! defined (timings in `docs/journal.md`; the variable `τ` gives the
//! projection the instant the bound is piecewise linear in,
//! `|x_i(t) − x_i(s)| ≤ (t − s) sup|u|` piece by piece).
//!
//! **Soundness.** Where every `den` is non-zero — required: a quotient is
//! lifted only when the path condition excludes `den = 0` — the lifted
//! system and the original one have the same points on the original
//! variables: a point of the original extends by `τ = num/den`, and a point
//! of the lifted system satisfies every original constraint (they are all
//! kept). So `unsat` lifted is `unsat` as asked, and a lifted model cut to
//! the original variables is a model as asked. A quotient whose denominator
//! may vanish would not be sound (`den = 0 ∧ num ≠ 0` would lose its points):
//! it is refused.

use super::eliminate::{Atom, Constraint};
use super::explore::Rel;
use super::poly::{Poly, Var};

/// A quotient `num / den` the program compared on the path.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Quotient {
    /// The numerator.
    pub num: Poly,
    /// The denominator (not constant).
    pub den: Poly,
}

/// A system with the quotients lifted to fresh variables.
#[derive(Debug, Clone)]
pub struct Lifted {
    /// The original constraints followed by one defining equation
    /// `τ·den − num = 0` per lifted quotient.
    pub constraints: Vec<Constraint>,
    /// The fresh variables, in order (`first`, `first + 1`, …), one per
    /// lifted quotient.
    pub fresh: Vec<Var>,
}

/// Lifts the quotients whose denominator `nonzero` accepts (it must answer
/// `true` only when every point of `system` has `den ≠ 0`): fresh variables
/// from `first` on, at most `max` of them (see the module documentation).
pub fn lift(
    system: &[Constraint],
    quotients: &[Quotient],
    nonzero: &dyn Fn(&Poly) -> bool,
    first: Var,
    max: usize,
) -> Lifted {
    let mut constraints = system.to_vec();
    let mut fresh: Vec<Var> = Vec::new();
    let mut seen: Vec<&Quotient> = Vec::new();
    for q in quotients {
        if fresh.len() >= max {
            break;
        }
        if q.den.as_constant().is_some() || seen.contains(&q) || !nonzero(&q.den) {
            continue;
        }
        let Some(tau) = Var::try_from(fresh.len())
            .ok()
            .and_then(|k| first.checked_add(k))
        else {
            break;
        };
        debug_assert!(
            system
                .iter()
                .all(|c| atoms(c).iter().all(|a| a.poly.degree_in(tau) == 0)),
            "the fresh variable is not used by the system"
        );
        seen.push(q);
        constraints.push(Constraint::Atom(Atom {
            poly: Poly::var(tau).mul(&q.den).sub(&q.num),
            rel: Rel::Eq,
        }));
        fresh.push(tau);
    }
    Lifted { constraints, fresh }
}

fn atoms(c: &Constraint) -> &[Atom] {
    match c {
        Constraint::Atom(a) => std::slice::from_ref(a),
        Constraint::Any(atoms) => atoms,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rational::ratio as q;
    use num_rational::BigRational;
    use num_traits::Zero;

    fn holds(system: &[Constraint], point: &[BigRational]) -> bool {
        system.iter().all(|c| {
            atoms(c)
                .iter()
                .any(|a| a.rel.holds_for(&a.poly.eval(point)))
        })
    }

    fn atom(poly: Poly, rel: Rel) -> Constraint {
        Constraint::Atom(Atom { poly, rel })
    }

    /// A collision instant `τ = (x − 1)/u` compared with `t`: the system
    /// `u > 0 ∧ x − 1 − t·u < 0` (τ < t). On a grid of `(x, u, t)`, the
    /// original holds exactly where the lifted system holds with
    /// `τ = (x − 1)/u`, and no other `τ` satisfies the defining equation:
    /// the two systems have the same points on the original variables.
    #[test]
    fn a_lifted_system_has_the_same_points() {
        let (x, u, t) = (Poly::var(0), Poly::var(1), Poly::var(2));
        let sys = vec![
            atom(u.clone(), Rel::Gt),
            atom(x.sub(&Poly::constant(q(1, 1))).sub(&t.mul(&u)), Rel::Lt),
        ];
        let quotient = Quotient {
            num: x.sub(&Poly::constant(q(1, 1))),
            den: u.clone(),
        };
        let nonzero = |p: &Poly| *p == u;
        let lifted = lift(&sys, &[quotient], &nonzero, 3, 4);
        assert_eq!(lifted.fresh, vec![3]);
        let mut agree = [0usize; 2];
        for xn in -3..=3 {
            for un in 1..=3 {
                for tn in 0..=3 {
                    let (xv, uv, tv) = (q(xn, 1), q(un, 2), q(tn, 1));
                    let tau = (xv.clone() - q(1, 1)) / uv.clone();
                    let orig = holds(&sys, &[xv.clone(), uv.clone(), tv.clone()]);
                    let point = vec![xv.clone(), uv.clone(), tv.clone(), tau.clone()];
                    assert_eq!(orig, holds(&lifted.constraints, &point));
                    agree[usize::from(orig)] += 1;
                    let off = vec![xv, uv, tv, tau + q(1, 7)];
                    assert!(!holds(&lifted.constraints, &off), "τ is determined");
                }
            }
        }
        assert!(agree[0] > 0 && agree[1] > 0, "both outcomes exercised");
    }

    /// The mutant: a quotient whose denominator may vanish. `u = 0 ∧ x = 1`
    /// is satisfiable, but with `τ·u − (x − 2) = 0` added it is not (at
    /// `u = 0` the equation says `x = 2`): lifting it would turn a
    /// satisfiable query into an `unsat` answer. It is refused unless the
    /// caller vouches for `u ≠ 0`, and the lifting a careless caller would
    /// get is shown unsound at the point.
    #[test]
    fn a_denominator_that_may_vanish_is_refused() {
        let (x, u) = (Poly::var(0), Poly::var(1));
        let sys = vec![
            atom(u.clone(), Rel::Eq),
            atom(x.sub(&Poly::constant(q(1, 1))), Rel::Eq),
        ];
        let quotient = Quotient {
            num: x.sub(&Poly::constant(q(2, 1))),
            den: u.clone(),
        };
        let point = [q(1, 1), BigRational::zero()];
        assert!(holds(&sys, &point));
        let refused = lift(&sys, std::slice::from_ref(&quotient), &|_| false, 2, 4);
        assert!(refused.fresh.is_empty());
        assert_eq!(refused.constraints, sys);
        // What a caller that wrongly vouched for u ≠ 0 would get: no τ
        // extends the point.
        let careless = lift(&sys, &[quotient], &|_| true, 2, 4);
        assert_eq!(careless.fresh, vec![2]);
        for tn in -5..=5 {
            let mut p = point.to_vec();
            p.push(q(tn, 1));
            assert!(!holds(&careless.constraints, &p));
        }
    }

    /// Constant denominators, repeats and the cap `max` lift nothing more.
    #[test]
    fn repeats_constants_and_the_cap() {
        let (x, u, w) = (Poly::var(0), Poly::var(1), Poly::var(2));
        let a = Quotient {
            num: x.clone(),
            den: u.clone(),
        };
        let b = Quotient {
            num: x.clone(),
            den: w.clone(),
        };
        let c = Quotient {
            num: x.clone(),
            den: Poly::constant(q(2, 1)),
        };
        let all = |_: &Poly| true;
        let l = lift(&[], &[a.clone(), c, a.clone(), b.clone()], &all, 3, 4);
        assert_eq!(l.fresh, vec![3, 4]);
        assert_eq!(l.constraints.len(), 2);
        let capped = lift(&[], &[a, b], &all, 3, 1);
        assert_eq!(capped.fresh, vec![3]);
    }
}
