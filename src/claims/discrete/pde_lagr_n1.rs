//! `eq:PDE-Lagr-N-1`, the discrete Lagrangian equations of section 3, and
//! its complementarity `(∂_w X̃_N − 1) Λ_N = 0`: as printed, corrected, and
//! with the multipliers re-indexed to the gap of their pair.

use super::{abs, augmented, augmented_jumps, states, R};
use crate::claims::{Case, FromPaper, Violation};
use crate::scalar::Scalar;

/// `eq:PDE-Lagr-N-1#complementarity`, as printed: `(∂_w X̃_N − 1) Λ_N = 0`;
/// on `((i−1)/N, i/N]` this is `(N(x_i − x_{i−1}) − 1) λ_i = 0`.
pub fn lagr_n1_printed<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "eq:PDE-Lagr-N-1#complementarity";
    let n = S::from_usize(case.n());
    for a in states(case, ID)? {
        for i in 1..=case.n() {
            let slope = n.clone() * &(a.x[i].clone() - &a.x[i - 1]);
            if !a.lambda[i].is_zero() && slope != S::one() {
                return Err(Violation::new(
                    ID,
                    format!(
                        "t = {}, w ∈ ({}/N, {i}/N]: Λ_N = λ[{}] = {} but ∂_w X̃_N − 1 = N(x[{}] − x[{}]) − 1 = {}",
                        a.t.render(),
                        i - 1,
                        FromPaper(i),
                        a.lambda[i].render(),
                        FromPaper(i),
                        FromPaper(i - 1),
                        (slope.clone() - &S::one()).render()
                    ),
                )
                .at(a.t.render())
                .indices(&[i - 1])
                .sides(
                    "(∂_w X̃_N − 1) Λ_N",
                    ((slope - &S::one()) * &a.lambda[i]).render(),
                    "0",
                    "0",
                ));
            }
        }
    }
    Ok(())
}

/// Corrected: `(∂_w X̃_N(t, w + 1/N) − 1) Λ_N(t, w) = 0`, i.e.
/// `(N(x_{i+1} − x_i) − 1) λ_i = 0` — `λ_i` lives on the pair `(i, i+1)`,
/// whose slope is that of the next interval.
pub fn lagr_n1_corrected<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "eq:PDE-Lagr-N-1#complementarity (corrected)";
    let n = S::from_usize(case.n());
    for a in states(case, ID)? {
        for i in 1..case.n() {
            let slope = n.clone() * &(a.x[i + 1].clone() - &a.x[i]);
            if !a.lambda[i].is_zero() && slope != S::one() {
                return Err(Violation::new(
                    ID,
                    format!(
                        "t = {}, pair ({}, {i}): λ[{}] = {}, N(x[{i}] − x[{}]) = {}",
                        a.t.render(),
                        i - 1,
                        i - 1,
                        a.lambda[i].render(),
                        i - 1,
                        slope.render()
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// The one re-indexing that makes three printed statements exact: define
/// `Λ_N := λ_{i−1}` on `((i−1)/N, i/N]` (so `P_N = ∂_t Λ_N := p_{i−1}`;
/// `Λ̃_N`, hence `eq:PDE-Lagr-N-1`'s first line, is unchanged). Then, on
/// every interval, `λ_{i−1}` and the slope `N(x_i − x_{i−1})` belong to the
/// same pair `(i−1, i)`, and
/// * `eq:PDE-Lagr-N-1#complementarity`: `(∂_w X̃_N − 1) Λ_N = 0`;
/// * `lem:discPDE2#exclusion`: `(∂_w X̃_N − 1) P_N = 0` (at every collision);
/// * `eq:diffLambda_N`: `|Λ̃_N − Λ_N| = |N(λ_i − λ_{i−1})(w − (i−1)/N)|`
///   (at `w = (i−1)/N + k/(4N)`, `k = 1 … 4`),
///
/// all as printed.
pub fn reindexed<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "eq:PDE-Lagr-N-1#complementarity (corrected)";
    let n = S::from_usize(case.n());
    for a in states(case, ID)? {
        for i in 1..=case.n() {
            let slope = n.clone() * &(a.x[i].clone() - &a.x[i - 1]);
            if !a.lambda[i - 1].is_zero() && slope != S::one() {
                return Err(Violation::new(
                    ID,
                    format!(
                        "t = {}, w ∈ ({}/N, {i}/N]: Λ_N := λ[{}] = {} but ∂_w X̃_N − 1 = {}",
                        a.t.render(),
                        i - 1,
                        FromPaper(i - 1),
                        a.lambda[i - 1].render(),
                        (slope - &S::one()).render()
                    ),
                ));
            }
            let d = a.lambda[i].clone() - &a.lambda[i - 1];
            for k in 1..=4 {
                let s = S::from_i64(k) / S::from_i64(4);
                let tilde = d.clone() * &s + &a.lambda[i - 1];
                let actual = abs(tilde - &a.lambda[i - 1]);
                let printed = abs(d.clone() * &s);
                if actual != printed {
                    return Err(Violation::new(
                        ID,
                        format!(
                            "t = {}, w ∈ ({}/N, {i}/N], k = {k}: |Λ̃_N − Λ_N| = {} ≠ {}",
                            a.t.render(),
                            i - 1,
                            actual.render(),
                            printed.render()
                        ),
                    ));
                }
            }
        }
    }
    for imp in case.impulse_spread() {
        let jumps = augmented_jumps(case.n(), imp);
        let s = case
            .state(&imp.t)
            .map_err(|e| Violation::new(ID, e.to_string()))?;
        let a = augmented(case, &s);
        for i in 1..=case.n() {
            let slope = n.clone() * &(a.x[i].clone() - &a.x[i - 1]);
            if !jumps[i - 1].is_zero() && slope != S::one() {
                return Err(Violation::new(
                    ID,
                    format!(
                        "collision at t = {}: P_N := p[{}] carries {} on ({}/N, {i}/N] but ∂_w X̃_N − 1 = {}",
                        imp.t.render(),
                        FromPaper(i - 1),
                        jumps[i - 1].render(),
                        i - 1,
                        (slope - &S::one()).render()
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// `eq:PDE-Lagr-N-1`: `∂_t X_N = U⁰_N − ∂_w Λ̃_N` (i.e.
/// `u_i = u⁰_i − N(λ_i − λ_{i−1})` on each interval), `∂_w X̃_N ≥ 1`,
/// `Λ_N ≥ 0`.
pub fn lagr_n1<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "eq:PDE-Lagr-N-1";
    let n = S::from_usize(case.n());
    let u0 = case.data().velocities();
    for a in states(case, ID)? {
        for i in 1..=case.n() {
            let rhs = u0[i - 1].clone() - &(n.clone() * &(a.lambda[i].clone() - &a.lambda[i - 1]));
            let slope = n.clone() * &(a.x[i].clone() - &a.x[i - 1]);
            if a.u[i] != rhs || slope < S::one() || a.lambda[i] < S::zero() {
                return Err(Violation::new(
                    ID,
                    format!(
                        "t = {}, particle [{}] (i = {i} in the paper's numbering): u_i = {}, u⁰_i − NΔλ = {}, ∂_w X̃_N = {}, λ_i = {}",
                        a.t.render(),
                        i - 1,
                        a.u[i].render(),
                        rhs.render(),
                        slope.render(),
                        a.lambda[i].render()
                    ),
                ));
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::initial::InitialData;

    use crate::rational::ratio as q;

    /// The re-indexed statements hold with 2r = 1/N and fail when the
    /// radius is not the paper's (slope N·2r = 2 at the contact).
    #[test]
    fn reindexed_holds_and_can_fail() {
        let paper = InitialData::with_paper_radius(vec![q(0, 1), q(1, 1)], vec![q(1, 1), q(-1, 1)]);
        reindexed(&Case::new(paper.unwrap(), None)).unwrap();
        let wide = InitialData::new(q(1, 2), vec![q(0, 1), q(2, 1)], vec![q(1, 1), q(-1, 1)]);
        assert!(reindexed(&Case::new(wide.unwrap(), None)).is_err());
    }
}
