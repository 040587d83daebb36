//! `prop:eulerian-formulation#mass` decided by its identity argument, on
//! each path of the dynamics, with no residual built.
//!
//! The checker ([`crate::claims::eulerian::mass`]) computes, for each test
//! function `φ = B(t) Q(x)` and each piece `[a, b]` between consecutive
//! cuts (`mass_cuts`), the integral over `τ ∈ [0, b − a]` of its
//! `piece_integrand` `B_a'(τ) S_a(τ) + B_a(τ) S_a'(τ)`, where
//! `B_a(τ) = B(a + τ)` is `bump`'s polynomial and
//! `S_a(τ) = Σ_i Q(x_i(a) + τ u_i(a))` comes from the state at `a`. Three
//! identities of the checker's code, true for all reals and proved as
//! identities of polynomials by this module's tests (on the symbolic
//! scalar, every quantity a free variable):
//!
//! 1. the piece's integral is `B_a(b − a) S_a(b − a) − B_a(0) S_a(0)` (the
//!    integrand is the exact `τ`-derivative of `B_a S_a`);
//! 2. `B_a(h) = B_{a+h}(0)` (each piece's bump is the same `B`, shifted);
//! 3. `B_{t₀}(0) = 0` and `B_a(t₁ − a) = 0` (`B` vanishes at both ends).
//!
//! So the pieces telescope to `B(t₁) S(t₁) − B(t₀) S(t₀) = 0` as soon as,
//! at every cut `b` inside the window, every particle's position is the
//! free flight from the piece's start, `x_i(a) + (b − a) u_i(a) = x_i(b)`
//! (then `S_a(b − a) = S_b(0)`). That is a property of the engine's
//! history, not of the checker: [`window_telescopes`] checks it with the
//! scalar's comparisons, so on the symbolic scalar the path oracle decides
//! it (identically true, or decided by the path condition, or the path
//! splits); where it fails, the prover computes the checker's own residual
//! on that path instead.

use crate::claims::eulerian::{mass_cuts, mass_tests};
use crate::claims::Case;
use crate::scalar::Scalar;
use crate::state::State;

/// Why the identity argument does not apply on a path (the residual must
/// then be computed).
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum Break {
    /// The engine refused a state at a cut: the message.
    State(String),
    /// A particle's position at a cut is not the free flight from the
    /// piece's start.
    Flight {
        /// Index of the cut in its window (1 … pieces − 1).
        cut: usize,
        /// Index of the particle, from 0.
        particle: usize,
    },
}

impl std::fmt::Display for Break {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Break::State(e) => write!(f, "no state at a cut: {e}"),
            Break::Flight { cut, particle } => write!(
                f,
                "x[{particle}] at cut {cut} is not the free flight from the piece before it"
            ),
        }
    }
}

/// The condition of the identity argument on one window's `cuts`, with the
/// state at each cut but the last given by `state` (the checker's
/// [`Case::state`] in the prover, a corrupted one in the tests): `Ok` means
/// the checker's residual over the window is exactly 0.
pub fn window_telescopes<S: Scalar>(
    cuts: &[S],
    state: &mut dyn FnMut(&S) -> Result<State<S>, String>,
) -> Result<(), Break> {
    debug_assert!(cuts.len() >= 2, "a window has a start and an end");
    let interior = cuts.len().saturating_sub(1);
    let Some(first) = cuts.first() else {
        return Ok(());
    };
    let mut before = state(first).map_err(Break::State)?;
    for (cut, b) in cuts.iter().enumerate().take(interior).skip(1) {
        let h = b.clone() - &before.t;
        let after = state(b).map_err(Break::State)?;
        let flights = before.positions.iter().zip(&before.velocities);
        for (particle, ((x, u), y)) in flights.zip(&after.positions).enumerate() {
            if x.clone() + &(h.clone() * u) != *y {
                return Err(Break::Flight { cut, particle });
            }
        }
        before = after;
    }
    Ok(())
}

/// [`window_telescopes`] for every test function of the checker on `case`:
/// `Ok(pieces)` (the pieces summed, over all windows) when
/// `R_mass^N(φ) = 0` follows by the identity argument for each of them.
pub fn mass_telescopes<S: Scalar>(case: &Case<S>) -> Result<usize, Break> {
    let mut pieces = 0;
    for f in mass_tests(case) {
        let cuts = mass_cuts(case, &f);
        pieces += cuts.len() - 1;
        let mut state = |t: &S| case.state(t).map_err(|e| e.to_string());
        window_telescopes(&cuts, &mut state)?;
    }
    Ok(pieces)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::claims::eulerian::{bump, mass, piece_integrand, power_sums};
    use crate::initial::InitialData;
    use crate::limit::eulerian::TestFunction;
    use crate::limit::poly::{eval, integral, mul};
    use crate::prove::sym::Sym;
    use crate::rational::ratio as q;
    use num_rational::BigRational;

    type Q = BigRational;

    fn three() -> Case<Q> {
        // Collisions: (0, 1) at t = 1/6, then the pair with particle 2.
        let data = InitialData::new(
            q(1, 6),
            vec![q(0, 1), q(2, 3), q(5, 3)],
            vec![q(2, 1), q(0, 1), q(-1, 1)],
        )
        .expect("admissible");
        Case::new(data, None)
    }

    /// `a − b` is the zero rational function (its numerator is the zero
    /// polynomial): an identity for all reals, no path oracle involved.
    fn identical(a: &Sym, b: &Sym) -> bool {
        (a.clone() - b).num().is_zero()
    }

    /// The three identities of the module documentation, on the checker's
    /// own functions with every quantity a free variable: window ends
    /// `t₀, t₁`, piece start `a`, length `h`, centre, scale, and three
    /// particles' positions and velocities at `a`.
    #[test]
    fn the_checker_integrates_an_exact_derivative_of_one_bump() {
        let v = |i: u16| Sym::var(i);
        let (t0, t1, a, h, c, l) = (v(0), v(1), v(2), v(3), v(4), v(5));
        let state = State {
            t: a.clone(),
            positions: vec![v(6), v(7), v(8)],
            velocities: vec![v(9), v(10), v(11)],
            multipliers: Vec::new(),
            clusters: Vec::new(),
        };
        for degree in [2u32, 3] {
            let f = TestFunction {
                t0: t0.clone(),
                t1: t1.clone(),
                center: c.clone(),
                scale: l.clone(),
                degree,
            };
            let zero = Sym::zero();
            let (b, _) = bump(&f, &a);
            // 2. one bump, shifted; 3. zero at both ends.
            assert!(identical(&eval(&b, &h), &bump(&f, &(a.clone() + &h)).0[0]));
            assert!(identical(&bump(&f, &t0).0[0], &zero));
            assert!(identical(&eval(&b, &(t1.clone() - &a)), &zero));
            // 1. the piece's integral is B_a S_a at its ends.
            let sums = power_sums(&state, &f.center, degree as usize);
            let s_a: Vec<Sym> = {
                // S_a(τ) = Σ_i ((x_i + τ u_i − c)/l)^m, as a polynomial in τ.
                let mut total = vec![Sym::zero()];
                for (x, u) in state.positions.iter().zip(&state.velocities) {
                    let linear = [(x.clone() - &c) / &l, u.clone() / &l];
                    let mut power = vec![Sym::one()];
                    for _ in 0..degree {
                        power = mul(&power, &linear);
                    }
                    crate::limit::poly::add_into(&mut total, &power);
                }
                total
            };
            let integrand = piece_integrand(&f, &sums, &a, degree);
            let ends = eval(&b, &h) * eval(&s_a, &h) - eval(&b, &zero) * eval(&s_a, &zero);
            assert!(identical(&integral(&integrand, &h), &ends), "m = {degree}");
        }
    }

    /// The identity test above refuses a false identity: the same integral
    /// with the bump's derivative doubled is not `B_a S_a` at the ends.
    #[test]
    fn the_identity_test_refuses_a_wrong_integrand() {
        let v = |i: u16| Sym::var(i);
        let (a, h) = (v(2), v(3));
        let f = TestFunction {
            t0: v(0),
            t1: v(1),
            center: Sym::zero(),
            scale: Sym::one(),
            degree: 2,
        };
        let (b, db) = bump(&f, &a);
        let s: Vec<Sym> = vec![v(6) * &v(6), v(6) * &v(9) * &Sym::from_i64(2), v(9) * &v(9)];
        let ds: Vec<Sym> = vec![
            v(6) * &v(9) * &Sym::from_i64(2),
            v(9) * &v(9) * &Sym::from_i64(2),
        ];
        let wrong_db: Vec<Sym> = db.iter().map(|c| c.clone() * &Sym::from_i64(2)).collect();
        let ends = eval(&b, &h) * eval(&s, &h) - eval(&b, &Sym::zero()) * eval(&s, &Sym::zero());
        let mut right = mul(&db, &s);
        crate::limit::poly::add_into(&mut right, &mul(&b, &ds));
        assert!(identical(&integral(&right, &h), &ends));
        let mut wrong = mul(&wrong_db, &s);
        crate::limit::poly::add_into(&mut wrong, &mul(&b, &ds));
        assert!(!identical(&integral(&wrong, &h), &ends));
        // And a shifted bump is not the same bump.
        let (b2, _) = bump(&f, &(a.clone() + &Sym::one()));
        assert!(!identical(&eval(&b, &h), &eval(&b2, &h)));
    }

    #[test]
    fn a_real_history_telescopes_and_its_residual_is_zero() {
        let case = three();
        assert!(case.traj.impulses().len() >= 2);
        let pieces = mass_telescopes(&case).expect("telescopes");
        assert!(
            pieces > 4,
            "{pieces} pieces: the collisions cut the windows"
        );
        assert!(mass(&case).is_ok());
    }

    /// Mutant: a history whose positions jump after the first collision is
    /// refused (and the checker's residual on it is not 0).
    #[test]
    fn a_broken_history_is_refused() {
        fn jump(_: &InitialData<Q>, s: &mut State<Q>) {
            if s.t > q(1, 6) {
                s.positions[2] = s.positions[2].clone() + q(1, 100);
            }
        }
        let case = three().tampered(jump);
        assert!(matches!(
            mass_telescopes(&case),
            Err(Break::Flight { particle: 2, .. })
        ));
        assert!(mass(&case).is_err(), "the checker sees it too");
    }
}
