//! Dropping the nonlinear constraints of a query the solver could not
//! decide (issue 29): a weaker system, so an `unsat` answer on it is an
//! `unsat` answer on the query, and nothing else is concluded from it.
//!
//! A path condition through several collisions carries the orderings of
//! their times, cross-multiplied: degree-4 polynomials in `(x⁰, u⁰)` that
//! make z3's `nlsat` slow, while the decision at hand often follows from the
//! hypotheses and the linear facts alone. At N = 3 `prop:Linf-micro` asks
//! whether `(x⁰_N − x⁰_0) + 2T sup|u⁰| > (1 + 2T)C'_0` can hold on a path
//! with three such constraints: 30 s without an answer as asked; with only
//! the linear constraints and the question, `unsat` in 0.1 s.

use super::eliminate::{Atom, Constraint};

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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::prove::explore::Rel;
    use crate::prove::poly::Poly;
    use crate::rational::ratio as q;

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
