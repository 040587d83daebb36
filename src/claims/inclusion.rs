//! Appendix C, "Monotone inclusion and uniqueness for eq:Lagr-1"
//! (unlabelled proposition of `app:uniqueness`), in its discrete form on the
//! particles: `ξ := ∂_w Λ̃_N = N(λ_i − λ_{i−1})` (`λ_0 = λ_N = 0`, the
//! boundary condition `Λ(t,0) = Λ(t,1) = 0`) satisfies
//!
//! * `∂_t X + ξ = U⁰`: `ξ = u⁰ − u(t)` (right derivatives);
//! * `ξ ∈ ∂I_{K^N}(x(t))`: `⟨ξ, y − x(t)⟩ ≤ 0` for every `y ∈ K^N`, by the
//!   proof's summation by parts `⟨ξ, y − x⟩ = −N Σ_i λ_i((y_{i+1} − y_i) −
//!   (x_{i+1} − x_i))` (checked as an identity), each term `≥ 0` because
//!   `λ_i ≥ 0`, `y_{i+1} − y_i ≥ 2r` and `λ_i(x_{i+1} − x_i − 2r) = 0` —
//!   on pseudo-random `y ∈ K^N` (gaps `2r + g`, `g ∈ {0, r/2, r, 2r}`, some
//!   touching) and on the generators of `T_{x(t)}K^N` (`±(1, …, 1)`;
//!   `s_j = Σ_{k>j} e_k` at a contact, `±s_j` for a pair apart:
//!   `⟨ξ, s_j⟩ = −Nλ_j` by the tail sums);
//! * uniqueness by monotonicity: for a second solution with the same `u⁰`
//!   and another `x⁰` (three of them: `x⁰` translated by 1; `x⁰` with every
//!   slack `x⁰_{i+1} − x⁰_i − 2r` halved; `x⁰` with the gaps widened by
//!   `0, r, 2r` in turn), `⟨ξ¹ − ξ², x¹ − x²⟩ ≥ 0` and `‖x¹(t) − x²(t)‖`
//!   non-increasing on `[0, T]`: on each interval `[a, b]` between
//!   consecutive event times of the two histories (and probe times) both
//!   move with constant velocities, `(d/dt)‖x¹ − x²‖²` is affine there, and
//!   it is checked `≤ 0` at both ends, with `‖x¹(b) − x²(b)‖ ≤ ‖x¹(a) − x²(a)‖`
//!   read from the states at `b`.
//!
//! It differs from the entries it resembles: `eq:ineg-projortho` tests
//! `u⁰ − u` on the generators only; `prop:proj-micro#uniqueness-identity`
//! tests the derivative identity for one second datum at the probe times;
//! `prop:bound-micro#position-contraction` and `eq:semigroup` are about one
//! solution at fixed times. Here `ξ` is read from the multipliers `λ` (the
//! discrete `∂_w Λ`), and the contraction is checked on the whole interval.

use super::micro::{augmented_lambda, dot, sub, tangent_cone_violation};
use super::{Case, Violation};
use crate::generate::SplitMix64;
use crate::initial::InitialData;
use crate::scalar::Scalar;
use crate::state::State;

type R = Result<(), Violation>;

const ID: &str = "app:uniqueness#monotone-inclusion";

fn fail<T>(what: String) -> Result<T, Violation> {
    Err(Violation::new(ID, what))
}

/// `ξ_i = N(λ_i − λ_{i−1})`, `i = 1 … N`, from the state's multipliers.
fn xi<S: Scalar>(s: &State<S>) -> Vec<S> {
    let l = augmented_lambda(s);
    let n = S::from_usize(s.positions.len());
    (1..l.len())
        .map(|i| n.clone() * &(l[i].clone() - &l[i - 1]))
        .collect()
}

/// `⟨ξ, d⟩ = N Σ_i (λ_i − λ_{i−1}) d_i` as `N(⟨λ_{1…N}, d⟩ − ⟨λ_{0…N−1}, d⟩)`:
/// the same value as `dot(&xi(s), d)`, without the differences.
fn xi_dot<S: Scalar>(s: &State<S>, d: &[S]) -> S {
    let l = augmented_lambda(s);
    let n = l.len() - 1;
    S::from_usize(n) * &(dot(&l[1..], d) - &dot(&l[..n], d))
}

fn state<S: Scalar>(case: &Case<S>, data: &InitialData<S>, t: &S) -> Result<State<S>, Violation> {
    case.state_of(data, t)
        .map_err(|e| Violation::new(ID, e.to_string()))
}

/// Three points of `K^N` near `x` (pseudo-random gaps, fixed seed).
fn points_of_k<S: Scalar>(x: &[S], two_r: &S) -> Vec<Vec<S>> {
    let mut rng = SplitMix64::new(0xC0DE);
    let half = two_r.clone() / &S::from_i64(2);
    (0..3)
        .map(|k| {
            let mut y = vec![x[0].clone() + &S::from_i64(k - 1)];
            for _ in 1..x.len() {
                let g = match rng.next_u64() % 4 {
                    0 => S::zero(),
                    1 => half.clone() / &S::from_i64(2),
                    2 => half.clone(),
                    _ => two_r.clone(),
                };
                let next = y[y.len() - 1].clone() + two_r + &g;
                y.push(next);
            }
            y
        })
        .collect()
}

/// The inclusion `ξ ∈ ∂I_K(x)` and `ξ = u⁰ − u` at one state.
fn inclusion_at<S: Scalar>(case: &Case<S>, s: &State<S>) -> R {
    let t = s.t.render();
    let x = &s.positions;
    let two_r = case.data().two_r();
    let n = S::from_usize(x.len());
    let xi = xi(s);
    let lambda = augmented_lambda(s);
    let expected = sub(case.data().velocities(), &s.velocities);
    if xi != expected {
        return fail(format!(
            "t = {t}: ξ = N(λ_i − λ_{{i−1}}) = {:?} but u⁰ − u(t) = {:?} (∂_t X + ∂_w Λ = U⁰ fails)",
            xi.iter().map(|v| v.render()).collect::<Vec<_>>(),
            expected.iter().map(|v| v.render()).collect::<Vec<_>>()
        ));
    }
    for (k, y) in points_of_k(x, &two_r).iter().enumerate() {
        let lhs = dot(&xi, &sub(y, x));
        let mut by_parts = S::zero();
        for i in 1..x.len() {
            let term =
                lambda[i].clone() * &((y[i].clone() - &y[i - 1]) - &(x[i].clone() - &x[i - 1]));
            if term < S::zero() {
                return fail(format!(
                    "t = {t}, y #{k}: λ[{}]((y[{i}] − y[{}]) − (x[{i}] − x[{}])) = {} < 0",
                    i - 1,
                    i - 1,
                    i - 1,
                    term.render()
                ));
            }
            by_parts = by_parts + &term;
        }
        let by_parts = -(n.clone() * &by_parts);
        if lhs != by_parts || lhs > S::zero() {
            return fail(format!(
                "t = {t}, y #{k}: ⟨ξ, y − x⟩ = {} (by parts: {}) must be ≤ 0",
                lhs.render(),
                by_parts.render()
            ));
        }
    }
    // Generators of T_x K: ⟨ξ, ±1⟩ = 0, ⟨ξ, s_j⟩ = −Nλ_j ≤ 0 at a
    // contact, = 0 for a pair apart.
    match tangent_cone_violation("ξ", &xi, x, &two_r) {
        Some(what) => fail(format!("t = {t}: {what}")),
        None => Ok(()),
    }
}

/// The second initial positions (same `u⁰`, same radius).
fn second_data<S: Scalar>(data: &InitialData<S>) -> Vec<(&'static str, InitialData<S>)> {
    let x = data.positions();
    let two_r = data.two_r();
    let r = data.radius().clone();
    let translated: Vec<S> = x.iter().map(|v| v.clone() + &S::one()).collect();
    let mut halved = vec![x[0].clone()];
    let mut widened = vec![x[0].clone()];
    for i in 1..x.len() {
        let gap = x[i].clone() - &x[i - 1];
        let h = two_r.clone() + &((gap.clone() - &two_r) / &S::from_i64(2));
        let last = halved[i - 1].clone() + &h;
        halved.push(last);
        let w = gap + &(r.clone() * &S::from_usize(i % 3));
        let last = widened[i - 1].clone() + &w;
        widened.push(last);
    }
    [
        ("x⁰ + 1", translated),
        ("x⁰ with halved slack", halved),
        ("x⁰ with widened gaps", widened),
    ]
    .into_iter()
    .filter_map(|(name, x2)| {
        InitialData::new(r.clone(), x2, data.velocities().to_vec())
            .ok()
            .map(|d| (name, d))
    })
    .collect()
}

/// Contraction: `‖x¹(t) − x²(t)‖` non-increasing on `[0, T]` and
/// `⟨ξ¹ − ξ², x¹ − x²⟩ ≥ 0` at every event and probe time.
fn contraction<S: Scalar>(case: &Case<S>, name: &str, other: &InitialData<S>) -> R {
    let Some(t_end) = case.times.last() else {
        return Ok(());
    };
    let traj2 = crate::trajectory::Trajectory::new(other.clone());
    let mut times: Vec<S> = vec![S::zero()];
    times.extend(case.times.iter().cloned());
    for imp in case.traj.impulses().iter().chain(traj2.impulses()) {
        if imp.t <= *t_end {
            times.push(imp.t.clone());
        }
    }
    times.sort_by(|a, b| a.total_cmp(b));
    times.dedup();
    let data = case.data();
    // The previous time's states, `x¹ − x²` and `‖x¹ − x²‖²` there.
    struct Prev<S> {
        s1: State<S>,
        s2: State<S>,
        d: Vec<S>,
        norm: S,
    }
    let mut prev: Option<Prev<S>> = None;
    for t in &times {
        let s1 = state(case, data, t)?;
        let s2 = state(case, other, t)?;
        let d = sub(&s1.positions, &s2.positions);
        // ⟨ξ¹ − ξ², d⟩ = ⟨ξ¹, d⟩ − ⟨ξ², d⟩.
        let mono = xi_dot(&s1, &d) - &xi_dot(&s2, &d);
        if mono < S::zero() {
            return fail(format!(
                "second solution from {name}, t = {}: ⟨ξ¹ − ξ², x¹ − x²⟩ = {} < 0",
                t.render(),
                mono.render()
            ));
        }
        let nb = dot(&d, &d);
        if let Some(Prev {
            s1: a1,
            s2: a2,
            d: da,
            norm: na,
        }) = &prev
        {
            let v = sub(&a1.velocities, &a2.velocities);
            let h = t.clone() - &a1.t;
            // ⟨da + h v, v⟩: the slope at the right end.
            let slope_end = dot(da, &v) + &(h * &dot(&v, &v));
            if slope_end > S::zero() || nb > *na {
                return fail(format!(
                    "second solution from {name}: on [{}, {}], (1/2) d/dt‖x¹ − x²‖² at the right end = {}, ‖x¹ − x²‖² goes from {} to {}",
                    a1.t.render(),
                    t.render(),
                    slope_end.render(),
                    na.render(),
                    nb.render()
                ));
            }
        }
        prev = Some(Prev {
            s1,
            s2,
            d,
            norm: nb,
        });
    }
    Ok(())
}

/// `app:uniqueness#monotone-inclusion` (see the module documentation).
pub fn monotone_inclusion<S: Scalar>(case: &Case<S>) -> R {
    for t in &case.times {
        let s = state(case, case.data(), t)?;
        inclusion_at(case, &s)?;
    }
    for (name, other) in second_data(case.data()) {
        contraction(case, name, &other)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rational::ratio as q;
    use num_rational::BigRational as Q;

    fn case() -> Case<Q> {
        let data = InitialData::with_paper_radius(
            vec![q(0, 1), q(1, 1), q(3, 1)],
            vec![q(1, 1), q(-1, 1), q(-2, 1)],
        )
        .unwrap();
        Case::new(data, None)
    }

    #[test]
    fn the_inclusion_and_the_contraction_hold() {
        monotone_inclusion(&case()).unwrap();
        assert_eq!(second_data(case().data()).len(), 3);
        let c = case();
        for t in &c.times {
            let s = c.state(t).unwrap();
            let d: Vec<Q> = (0..3).map(|i| q(i * i - 2, i + 1)).collect();
            assert_eq!(xi_dot(&s, &d), dot(&xi(&s), &d));
        }
    }

    #[test]
    fn a_flipped_multiplier_leaves_the_normal_cone() {
        let c = case();
        let t = c.times.last().unwrap().clone();
        let mut s = c.state(&t).unwrap();
        for l in &mut s.multipliers {
            *l = -l.clone();
        }
        s.velocities = (0..3)
            .map(|i| c.data().velocities()[i].clone() - &xi(&s)[i])
            .collect();
        assert!(inclusion_at(&c, &s).is_err());
    }

    #[test]
    fn an_expanding_pair_is_caught() {
        // Velocities of the second solution replaced by u⁰ (unprojected): the
        // distance to the first solution grows.
        fn unprojected(d: &InitialData<Q>, s: &mut State<Q>) {
            if d.positions()[0] != q(0, 1) {
                s.positions = crate::projection::free_flight(d, &s.t);
                s.velocities = d.velocities().to_vec();
            }
        }
        let c = case().tampered(unprojected);
        let other = &second_data(c.data())[0].1;
        assert!(contraction(&c, "x⁰ + 1", other).is_err());
    }
}
