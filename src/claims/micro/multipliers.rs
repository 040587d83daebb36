//! The multipliers `λ` of `eq:dyn-micro`: signs and complementarity, and
//! the bounds of `prop:bound-micro` and `eq:sup-micro-u-L` on `λ` and its
//! increments `ΔL`.

use super::{norm2, state, sub, R};
use crate::claims::coq::Statement;
use crate::claims::{Case, FromPaper, Violation};
use crate::initial::InitialData;
use crate::scalar::Scalar;
use crate::state::State;

/// `eq:dyn-micro` for the state `s` of the data `data`, on the engine's own
/// multipliers `s.multipliers` (not recomputed from `u`, which would make the
/// identity true by construction): `u_i − u⁰_i = −N(λ_i − λ_{i−1})` for
/// `i = 1 … N` with `λ_0 = λ_N = 0`, `λ_i ≥ 0` and
/// `λ_i (x_{i+1} − x_i − 2r) = 0`.
pub fn multiplier_signs<S: Scalar>(data: &InitialData<S>, s: &State<S>) -> R {
    const ID: &str = "eq:dyn-micro";
    let n = data.n();
    if s.multipliers.len() != n.saturating_sub(1) {
        return Err(Violation::new(
            ID,
            format!(
                "{} multipliers for N = {n} at t = {}",
                s.multipliers.len(),
                s.t.render()
            ),
        ));
    }
    let lambda = augmented_lambda(s);
    let nn = S::from_usize(n);
    for i in 1..=n {
        let lhs = s.velocities[i - 1].clone() - &data.velocities()[i - 1];
        let rhs = -(nn.clone() * &(lambda[i].clone() - &lambda[i - 1]));
        if lhs != rhs {
            return Err(Violation::new(
                ID,
                format!(
                    "u[{}] − u⁰[{}] = {} but −N(λ[{}] − λ[{}]) = {} at t = {} (λ[−1] = λ[N−1] = 0)",
                    i - 1,
                    i - 1,
                    lhs.render(),
                    i - 1,
                    FromPaper(i - 1),
                    rhs.render(),
                    s.t.render()
                ),
            ));
        }
    }
    let two_r = data.two_r();
    for (i, l) in s.multipliers.iter().enumerate() {
        if l.total_cmp(&S::zero()).is_lt() {
            return Err(Violation::new(
                ID,
                format!("λ[{i}] = {} < 0 at t = {}", l.render(), s.t.render()),
            ));
        }
        let slack = s.positions[i + 1].clone() - &s.positions[i] - &two_r;
        if !l.is_zero() && !slack.is_zero() {
            return Err(Violation::new(
                ID,
                format!(
                    "λ[{i}] = {} > 0 but x[{}] − x[{i}] − 2r = {} ≠ 0 at t = {}",
                    l.render(),
                    i + 1,
                    slack.render(),
                    s.t.render()
                ),
            ));
        }
    }
    Ok(())
}

/// `(λ_0, λ_1, …, λ_{N−1}, λ_N)` with `λ_0 = λ_N = 0` and the engine's
/// `λ_1 … λ_{N−1}` (`s.multipliers`) in between.
pub(crate) fn augmented_lambda<S: Scalar>(s: &State<S>) -> Vec<S> {
    let mut l = Vec::with_capacity(s.multipliers.len() + 2);
    l.push(S::zero());
    l.extend(s.multipliers.iter().cloned());
    l.push(S::zero());
    l
}

/// `λ(t)` at each of the (increasing) probe times of `case`, computed from
/// the event history alone: the sum of the jumps of `λ` at the collisions up
/// to `t` ([`crate::contact::Impulse::jumps`], from the pre- and
/// post-collision cluster velocities), in one sweep. Independent of the
/// recurrence `λ_i = λ_{i−1} + (u⁰_i − u_i)/N` that builds `State::multipliers`.
pub fn lambda_from_history<S: Scalar>(case: &Case<S>) -> Vec<Vec<S>> {
    let mut acc = vec![S::zero(); case.n().saturating_sub(1)];
    let impulses = case.traj.impulses();
    let mut next = 0;
    let mut out = Vec::with_capacity(case.times.len());
    for t in &case.times {
        while next < impulses.len() && impulses[next].t <= *t {
            let imp = &impulses[next];
            for (k, j) in imp.jumps().into_iter().enumerate() {
                let i = imp.cluster.first + k;
                acc[i] = acc[i].clone() + &j;
            }
            next += 1;
        }
        out.push(acc.clone());
    }
    out
}

/// `eq:dyn-micro` for the state `s` against multipliers `lambda` computed
/// independently of `s` (`λ_1 … λ_{N−1}`): the state's own multipliers equal
/// `lambda`, and [`multiplier_signs`] (the identity
/// `u_i = u⁰_i − N(λ_i − λ_{i−1})` with `λ_0 = λ_N = 0`, the signs and the
/// complementarity) holds for them, hence for `lambda`.
pub fn dyn_micro_at<S: Scalar>(data: &InitialData<S>, s: &State<S>, lambda: &[S]) -> R {
    const ID: &str = "eq:dyn-micro";
    if s.multipliers.as_slice() != lambda {
        return Err(Violation::new(
            ID,
            format!(
                "t = {}: the state's λ = {} but the collision history gives λ = {}",
                s.t.render(),
                super::render_vec(&s.multipliers),
                super::render_vec(lambda)
            ),
        ));
    }
    multiplier_signs(data, s)
}

/// `eq:dyn-micro` at every probe time, with `λ` from the collision history
/// ([`lambda_from_history`]): the identity is tested, not used as a
/// definition.
pub fn dyn_micro<S: Scalar>(case: &Case<S>) -> R {
    let history = lambda_from_history(case);
    for (t, lambda) in case.times.iter().zip(&history) {
        let s = state(case, t, "eq:dyn-micro")?;
        dyn_micro_at(case.data(), &s, lambda)?;
    }
    Ok(())
}

/// `(λ_1 − λ_0, …, λ_N − λ_{N−1})` and `L = (λ_1, …, λ_N)` at state `s`,
/// from the engine's multipliers (`λ_0 = λ_N = 0`).
fn delta_l<S: Scalar>(s: &State<S>) -> (Vec<S>, Vec<S>) {
    let mut l = augmented_lambda(s);
    l.remove(0);
    let mut prev = S::zero();
    let d = l
        .iter()
        .map(|x| {
            let v = x.clone() - &prev;
            prev = x.clone();
            v
        })
        .collect();
    (d, l)
}

/// `prop:bound-micro#delta-lambda`: `‖ΔL‖² = Σ (1/N)(λ_i − λ_{i−1})²
/// = Σ (1/N³)(u_i − u⁰_i)² ≤ (4/N²)‖u⁰‖²`.
pub fn delta_lambda<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "prop:bound-micro#delta-lambda";
    let n = S::from_usize(case.n());
    let n3 = n.clone() * &n * &n;
    for t in &case.times {
        let s = state(case, t, ID)?;
        let (dl, _) = delta_l(&s);
        let lhs = norm2(&dl);
        let mid = sub(&s.velocities, case.data().velocities())
            .iter()
            .fold(S::zero(), |a, x| a + &(x.clone() * x))
            / &n3;
        let rhs = S::from_i64(4) / (n.clone() * &n) * norm2(case.data().velocities());
        if lhs != mid || mid > rhs {
            return Err(Violation::new(
                ID,
                format!(
                    "t = {}: ‖ΔL‖² = {}, Σ(u_i − u⁰_i)²/N³ = {}, (4/N²)‖u⁰‖² = {}",
                    t.render(),
                    lhs.render(),
                    mid.render(),
                    rhs.render()
                ),
            ));
        }
    }
    Ok(())
}

/// `prop:bound-micro#lambda-cauchy-schwarz`: `|λ_i| ≤ N‖ΔL‖` and
/// `‖L‖² ≤ N²‖ΔL‖² ≤ 4‖u⁰‖²`.
pub fn lambda_cs<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "prop:bound-micro#lambda-cauchy-schwarz";
    let n = S::from_usize(case.n());
    for t in &case.times {
        let s = state(case, t, ID)?;
        let (dl, l) = delta_l(&s);
        let bound = n.clone() * &n * norm2(&dl);
        for (i, li) in l.iter().enumerate() {
            if li.clone() * li > bound {
                return Err(Violation::new(
                    ID,
                    format!(
                        "t = {}: λ[{i}]² = {} > N²‖ΔL‖² = {}",
                        t.render(),
                        (li.clone() * li).render(),
                        bound.render()
                    ),
                ));
            }
        }
        let four = S::from_i64(4) * norm2(case.data().velocities());
        if norm2(&l) > bound || bound > four {
            return Err(Violation::new(
                ID,
                format!(
                    "t = {}: ‖L‖² = {}, N²‖ΔL‖² = {}, 4‖u⁰‖² = {}",
                    t.render(),
                    norm2(&l).render(),
                    bound.render(),
                    four.render()
                ),
            ));
        }
    }
    Ok(())
}

/// `prop:bound-micro#multiplier-relation`: the proofs of `prop:bound-micro`
/// and `prop:Linf-micro` use `N(λ_i(t) − λ_{i−1}(t)) = u_i(t) − u⁰_i`.
pub fn multiplier_relation_printed<S: Scalar>(case: &Case<S>) -> R {
    multiplier_relation(
        case,
        "prop:bound-micro#multiplier-relation",
        Statement::Printed,
    )
}

/// The relation with the sign of `eq:dyn-micro`:
/// `N(λ_i − λ_{i−1}) = u⁰_i − u_i`.
pub fn multiplier_relation_corrected<S: Scalar>(case: &Case<S>) -> R {
    multiplier_relation(
        case,
        "prop:bound-micro#multiplier-relation (corrected)",
        Statement::Corrected,
    )
}

/// `N(λ_i − λ_{i−1})` against `u_i − u⁰_i` (printed) or `u⁰_i − u_i`
/// (corrected).
fn multiplier_relation<S: Scalar>(case: &Case<S>, id: &'static str, statement: Statement) -> R {
    let n = S::from_usize(case.n());
    for t in &case.times {
        let s = state(case, t, id)?;
        let (dl, _) = delta_l(&s);
        for i in 0..case.n() {
            let lhs = n.clone() * &dl[i];
            let (u, u0) = (&s.velocities[i], &case.data().velocities()[i]);
            let (rhs, name) = match statement {
                Statement::Printed => (u.clone() - u0, "u_i − u⁰_i"),
                Statement::Corrected => (u0.clone() - u, "u⁰_i − u_i"),
            };
            if lhs != rhs {
                return Err(Violation::new(
                    id,
                    format!(
                        "t = {}, particle [{i}] (i = {} in the paper's numbering): N(λ_i − λ_{{i−1}}) = {} but {name} = {}",
                        t.render(),
                        i + 1,
                        lhs.render(),
                        rhs.render()
                    ),
                )
                .at(t.render())
                .indices(&[i])
                .sides("N(λ_i − λ_{i−1})", lhs.render(), name, rhs.render()));
            }
        }
    }
    Ok(())
}

fn sup_abs<S: Scalar>(v: &[S]) -> S {
    v.iter().fold(S::zero(), |m, x| {
        let a = if x.total_cmp(&S::zero()).is_lt() {
            -x.clone()
        } else {
            x.clone()
        };
        if a > m {
            a
        } else {
            m
        }
    })
}

/// `eq:sup-micro-u-L#velocity-and-increments`: the first two terms of
/// `eq:sup-micro-u-L` for fixed N: `sup_i |u_i(t)| ≤ sup_i |u⁰_i|` and
/// `sup_i |N(λ_i − λ_{i−1})| ≤ 2 sup_i |u⁰_i|`.
pub fn sup_u_and_increments<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "eq:sup-micro-u-L#velocity-and-increments";
    let c0 = sup_abs(case.data().velocities());
    let n = S::from_usize(case.n());
    for t in &case.times {
        let s = state(case, t, ID)?;
        let (dl, _) = delta_l(&s);
        let su = sup_abs(&s.velocities);
        let sd = n.clone() * sup_abs(&dl);
        if su > c0 || sd > S::from_i64(2) * &c0 {
            return Err(Violation::new(
                ID,
                format!(
                    "t = {}: sup|u| = {}, sup|N Δλ| = {}, sup|u⁰| = {}",
                    t.render(),
                    su.render(),
                    sd.render(),
                    c0.render()
                ),
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::multipliers;
    use num_rational::BigRational;

    use crate::rational::ratio as q;

    /// 2r = 1, x⁰ = (0, 2, 4), u⁰ = (2, 0, −1): particles 1, 2 meet at
    /// t = 1/2, particle 3 joins at t = 3/4.
    fn case() -> Case<BigRational> {
        let x = vec![q(0, 1), q(2, 1), q(4, 1)];
        let u = vec![q(2, 1), q(0, 1), q(-1, 1)];
        Case::new(InitialData::new(q(1, 2), x, u).unwrap(), None)
    }

    /// The three mutants of the audit each fail `eq:dyn-micro`: λ with its
    /// sign flipped, λ not divided by N, and a cluster velocity that leaves
    /// one particle out of the mean (with λ rebuilt from it, as a mutated
    /// engine would).
    #[test]
    fn mutants_fail_dyn_micro() {
        let c = case();
        dyn_micro(&c).unwrap();
        let history = lambda_from_history(&c);
        let (t, lambda) = (c.times.last().unwrap(), history.last().unwrap());
        let s = state(&c, t, "test").unwrap();
        assert!(lambda.iter().all(|l| *l > q(0, 1)), "a case with pressure");
        dyn_micro_at(c.data(), &s, lambda).unwrap();

        let mut flipped = s.clone();
        flipped.multipliers = s.multipliers.iter().map(|l| -l.clone()).collect();
        assert!(dyn_micro_at(c.data(), &flipped, lambda).is_err());

        let mut undivided = s.clone();
        undivided.multipliers = s.multipliers.iter().map(|l| l * q(3, 1)).collect();
        assert!(dyn_micro_at(c.data(), &undivided, lambda).is_err());
        let undivided_history: Vec<_> = lambda.iter().map(|l| l * q(3, 1)).collect();
        assert!(dyn_micro_at(c.data(), &s, &undivided_history).is_err());

        let mut short = s.clone();
        let u0 = c.data().velocities();
        let mean = (u0[0].clone() + &u0[1]) / q(2, 1);
        short.velocities = vec![mean; 3];
        short.multipliers = multipliers(u0, &short.velocities).0;
        assert!(dyn_micro_at(c.data(), &short, lambda).is_err());
    }
}
