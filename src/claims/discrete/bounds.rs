//! The bounds of section 3 on the interpolations, uniform in N: the gap
//! to the artificial particle, `L¹` and `BV` bounds, the one-sided Oleinik
//! bound, and the distance between the two interpolations of `Λ`.

use super::{abs, augmented, delta, states, total_variation, Augmented, R};
use crate::claims::{Case, FromPaper, Violation};
use crate::scalar::Scalar;

/// `prop:pressure-bound#gap-delta`: `(x_N(t) − x_0(t)) − 1 ≥ δ`.
pub fn gap_delta<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "prop:pressure-bound#gap-delta";
    let n = case.n();
    for a in states(case, ID)? {
        let lhs = a.x[n].clone() - &a.x[0] - &S::one();
        if lhs < delta::<S>() {
            return Err(Violation::new(
                ID,
                format!(
                    "t = {}: x[N−1] − x[−1] − 1 = {} < δ = 1",
                    a.t.render(),
                    lhs.render()
                ),
            ));
        }
    }
    Ok(())
}

/// `prop:cvg1#XN-L1`: `∫_0^1 |X̃_N − X_N| dw = (1/2N) Σ_{i=0}^{N−1}
/// (x_{i+1} − x_i) = (x_N − x_0)/(2N)` (each interval contributes the area of
/// a triangle of base `1/N` and height `x_i − x_{i−1}`).
pub fn xn_l1<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "prop:cvg1#XN-L1";
    let n = case.n();
    let two_n = S::from_usize(2 * n);
    for a in states(case, ID)? {
        let integral = (1..=n).fold(S::zero(), |acc, i| {
            acc + &(abs(a.x[i].clone() - &a.x[i - 1]) / &two_n)
        });
        let closed = (a.x[n].clone() - &a.x[0]) / &two_n;
        if integral != closed {
            return Err(Violation::new(
                ID,
                format!(
                    "t = {}: ∫|X̃_N − X_N| = {} ≠ (x[N−1] − x[−1])/(2N) = {}",
                    a.t.render(),
                    integral.render(),
                    closed.render()
                ),
            ));
        }
    }
    Ok(())
}

/// `eq:diffLambda_N`, as printed: for `w ∈ ((i−1)/N, i/N]`,
/// `|Λ̃_N − Λ_N| = |N(λ_i − λ_{i−1})(w − (i−1)/N)|` — evaluated at
/// `w = (i−1)/N + 1/(4N)`.
pub fn diff_lambda_printed<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "eq:diffLambda_N";
    let n = S::from_usize(case.n());
    let quarter = S::one() / S::from_i64(4);
    // Both sides are continuous in w on the cell: a failure at w = 1/4 and
    // at w = 3/4 of the cell is a failure on a set of positive measure.
    let side = |a: &Augmented<S>, i: usize, s: &S| {
        let d = a.lambda[i].clone() - &a.lambda[i - 1];
        // Λ̃_N(w) = N d (w − (i−1)/N) + λ_{i−1} with N(w − (i−1)/N) = s.
        let tilde = d.clone() * s + &a.lambda[i - 1];
        (abs(tilde - &a.lambda[i]), abs(d * s))
    };
    let three_quarters = S::from_i64(3) / S::from_i64(4);
    for a in states(case, ID)? {
        for i in 1..=case.n() {
            let (actual, printed) = side(&a, i, &quarter);
            let (actual3, printed3) = side(&a, i, &three_quarters);
            if actual != printed && actual3 != printed3 {
                return Err(Violation::new(
                    ID,
                    format!(
                        "t = {}, w = {}/N + 1/(4N), N = {}: |Λ̃_N − Λ_N| = {} but |N(λ_i − λ_{{i−1}})(w − (i−1)/N)| = {}",
                        a.t.render(),
                        i - 1,
                        n.render(),
                        actual.render(),
                        printed.render()
                    ) + &format!(
                        "; at w = {}/N + 3/(4N): {} but {} (both sides continuous in w on the cell: they differ on an open set)",
                        i - 1,
                        actual3.render(),
                        printed3.render()
                    ),
                )
                .at(a.t.render())
                .indices(&[i - 1])
                .w(vec![
                    ((S::from_usize(4 * (i - 1) + 1)) / (S::from_i64(4) * &n)).render(),
                    ((S::from_usize(4 * (i - 1) + 3)) / (S::from_i64(4) * &n)).render(),
                ])
                .sides(
                    "|Λ̃_N − Λ_N| at the two w",
                    format!("{}, {}", actual.render(), actual3.render()),
                    "|N(λ_i − λ_{i−1})(w − (i−1)/N)| at the two w",
                    format!("{}, {}", printed.render(), printed3.render()),
                ));
            }
        }
    }
    Ok(())
}

/// Corrected `eq:diffLambda_N`: `|Λ̃_N − Λ_N| = |λ_i − λ_{i−1}| ·
/// |1 − N(w − (i−1)/N)| ≤ |λ_i − λ_{i−1}| ≤ 2 sup|u⁰|/N` (checked at
/// `w = (i−1)/N + k/(4N)`, `k = 1 … 4`).
pub fn diff_lambda_corrected<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "eq:diffLambda_N (corrected)";
    let n = S::from_usize(case.n());
    let c0 = case
        .data()
        .velocities()
        .iter()
        .fold(S::zero(), |m, x| S::min_of(m.clone(), -abs(x.clone())));
    let bound = -(c0 * S::from_i64(2)) / &n;
    for a in states(case, ID)? {
        for i in 1..=case.n() {
            let d = a.lambda[i].clone() - &a.lambda[i - 1];
            for k in 1..=4 {
                let s = S::from_i64(k) / S::from_i64(4);
                let tilde = d.clone() * &s + &a.lambda[i - 1];
                let actual = abs(tilde - &a.lambda[i]);
                let formula = abs(d.clone()) * &abs(S::one() - &s);
                if actual != formula || actual > abs(d.clone()) || abs(d.clone()) > bound {
                    return Err(Violation::new(
                        ID,
                        format!(
                            "t = {}, w ∈ ({}/N, {i}/N], k = {k}: {} vs {} (bound {})",
                            a.t.render(),
                            i - 1,
                            actual.render(),
                            formula.render(),
                            bound.render()
                        ),
                    ));
                }
            }
        }
    }
    Ok(())
}

/// `prop:2ndorder-LagrPDE#UN-L1`, as printed:
/// `∫|Ũ_N − U_N| = (1/2N) Σ_{i=1}^N |u_i − u_{i−1}| = (1/2N)|u_N − u_0|`.
pub fn un_l1_printed<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "prop:2ndorder-LagrPDE#UN-L1";
    let n = case.n();
    for a in states(case, ID)? {
        let tv = total_variation(&a.u);
        let ends = abs(a.u[n].clone() - &a.u[0]);
        if tv != ends {
            return Err(Violation::new(
                ID,
                format!(
                    "t = {}: Σ|u_i − u_{{i−1}}| = {} but |u[N−1] − u[−1]| = {} (u = [{}])",
                    a.t.render(),
                    tv.render(),
                    ends.render(),
                    a.u[1..]
                        .iter()
                        .map(|v| v.render())
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
            )
            .at(a.t.render())
            .sides(
                "Σ|u_i − u_{i−1}|",
                tv.render(),
                "|u_N − u_0|",
                ends.render(),
            ));
        }
    }
    Ok(())
}

/// Corrected: `∫|Ũ_N − U_N| = (1/2N) Σ |u_i − u_{i−1}| ≤ TV(u⁰)/(2N)` —
/// the total variation of `u(t)` never exceeds that of `u⁰` (cluster means
/// do not create variation), which is what makes `Ũ_N − U_N → 0`.
pub fn un_l1_corrected<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "prop:2ndorder-LagrPDE#UN-L1 (corrected)";
    let u0 = case.data().velocities();
    let tv0 = total_variation(u0);
    for a in states(case, ID)? {
        let tv = total_variation(&a.u);
        if tv > tv0 {
            return Err(Violation::new(
                ID,
                format!(
                    "t = {}: TV(u(t)) = {} > TV(u⁰) = {}",
                    a.t.render(),
                    tv.render(),
                    tv0.render()
                ),
            ));
        }
    }
    Ok(())
}

/// `eq:Oleinik-tUN`: `∂_w Ũ_N < ∂_w X̃_N / t`, i.e.
/// `t(u_i − u_{i−1}) < x_i − x_{i−1}` for `i = 1 … N` (artificial particle
/// included), `t > 0`.
pub fn oleinik_tun<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "eq:Oleinik-tUN";
    for a in states(case, ID)? {
        if a.t.total_cmp(&S::zero()).is_le() {
            continue;
        }
        for i in 1..=case.n() {
            let lhs = a.t.clone() * &(a.u[i].clone() - &a.u[i - 1]);
            let rhs = a.x[i].clone() - &a.x[i - 1];
            if lhs >= rhs {
                return Err(Violation::new(
                    ID,
                    format!(
                        "t = {}, pair ({p}, {q}): t(u[{q}] − u[{p}]) = {} ≥ x[{q}] − x[{p}] = {}",
                        a.t.render(),
                        lhs.render(),
                        rhs.render(),
                        p = FromPaper(i - 1),
                        q = FromPaper(i)
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// `pwUN-L1` (proof): `‖∂_w Ũ_N(t)‖_{L¹} = Σ|u_i − u_{i−1}| ≤
/// (2/t)(x_N − x_0) − (Ũ_N(t,1) − Ũ_N(t,0))` for `t > 0`.
pub fn pw_un_l1<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "pwUN-L1";
    let n = case.n();
    for a in states(case, ID)? {
        if a.t.total_cmp(&S::zero()).is_le() {
            continue;
        }
        let tv = total_variation(&a.u);
        let rhs = S::from_i64(2) / &a.t * &(a.x[n].clone() - &a.x[0]) - &(a.u[n].clone() - &a.u[0]);
        if tv > rhs {
            return Err(Violation::new(
                ID,
                format!(
                    "t = {}: ‖∂_w Ũ_N‖_L¹ = {} > {}",
                    a.t.render(),
                    tv.render(),
                    rhs.render()
                ),
            ));
        }
    }
    Ok(())
}

/// `eq:BV_XN` (proof):
/// `∫|∂_w X̃_N(t)| = x_N(t) − x_0(t) ≤ (x_N(0) − x_0(0)) + t (sup_{[0,t]}|u_N| + sup_{[0,t]}|u_1|)`.
pub fn bv_xn<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "eq:BV_XN";
    let n = case.n();
    let all = states(case, ID)?;
    // Velocities are piecewise constant: the sup over [0, t] is the max over
    // the states at 0 and at the collision instants up to t (a spread of 40
    // instants when there are more: the bound checked is then a lower
    // estimate of the paper's right-hand side's sup, i.e. harder to meet).
    let mut impulse_states = Vec::new();
    for imp in case.impulse_spread() {
        let s = case
            .state(&imp.t)
            .map_err(|e| Violation::new(ID, e.to_string()))?;
        impulse_states.push(augmented(case, &s));
    }
    let first = &all[0];
    for a in &all {
        let mut sup_n = abs(first.u[n].clone());
        let mut sup_1 = abs(first.u[1].clone());
        for b in impulse_states.iter().filter(|b| b.t <= a.t) {
            sup_n = if abs(b.u[n].clone()) > sup_n {
                abs(b.u[n].clone())
            } else {
                sup_n
            };
            sup_1 = if abs(b.u[1].clone()) > sup_1 {
                abs(b.u[1].clone())
            } else {
                sup_1
            };
        }
        let integral = (1..=n).fold(S::zero(), |acc, i| acc + &abs(a.x[i].clone() - &a.x[i - 1]));
        let spread = a.x[n].clone() - &a.x[0];
        let bound = first.x[n].clone() - &first.x[0] + &(a.t.clone() * &(sup_n + &sup_1));
        if integral != spread || spread > bound {
            return Err(Violation::new(
                ID,
                format!(
                    "t = {}: ∫|∂_w X̃_N| = {}, x[N−1] − x[−1] = {}, bound = {}",
                    a.t.render(),
                    integral.render(),
                    spread.render(),
                    bound.render()
                ),
            ));
        }
    }
    Ok(())
}
