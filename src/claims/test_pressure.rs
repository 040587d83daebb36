//! The test of the proof of `prop:pressure-bound`, exactly, per trajectory
//! (`2r = 1/N`, artificial particle `x_0 = x_1 − 1/N − δ`, `δ = 1`,
//! `u_0 = u_1`): the momentum equation `∂_t U_N + ∂_w P̃_N = 0`
//! (`eq:PDE-Lagr-N-2`) tested against
//! `φ(t,w) = ((x_N(t) − x_0(t)) w − X̃_N(t,w)) ϕ(t)` with the polynomial
//! `ϕ(t) = (t − a)²(b − t)²` on `[a, b] ⊂ (0, T)` (C¹, compact support).
//!
//! Left side: `P̃_N(dt, w) = Σ_k δ_{t_k} J̃_k(w)`, `J̃_k` the affine
//! interpolation of the jumps `[λ_i]` at `t_k`, so
//! `LHS = Σ_k ϕ(t_k) Σ_i ((x_N − x_0) − N(x_i − x_{i−1}))([λ_{i−1}] + [λ_i])/(2N)`.
//! Right side: between collisions `U_N` is constant and `X̃_N` affine in
//! `t`; with `A = ∫_0^1 U_N (c w − Ũ_N) dw` and
//! `B(t) = ∫_0^1 U_N ((x_N − x_0)w − X̃_N) dw` (`B' = A` for
//! `c = u_N − u_0`), each piece `[α, β]` contributes
//! `−(A_c ∫_α^β ϕ + B(α)(ϕ(β) − ϕ(α)) + A((β − α)ϕ(β) − ∫_α^β ϕ))`,
//! where the printed identity has `c = U_N(t,0) − U_N(t,1) = u_0 − u_N`
//! and the corrected one `c = u_N − u_0` (the `∂_t φ` of the proof).

use super::bump::Bump;
use super::coq::Statement;
use super::discrete::{abs, augmented, augmented_jumps, Augmented};
use super::{Case, Violation};
use crate::scalar::Scalar;

type R = Result<(), Violation>;

/// `∫_0^1 U_N (c w − Ũ_N) dw = c ∫_0^1 U_N w dw − ∫_0^1 U_N Ũ_N dw` is
/// affine in `c`: its two integrals, and
/// `B = ∫_0^1 U_N ((x_N − x_0) w − X̃_N) dw`, on an augmented state
/// (`U_N = u_i`, `w`, `Ũ_N`, `X̃_N` affine on `((i−1)/N, i/N)`: their cell
/// integrals are `(2i − 1)/(2N²)`, `(u_{i−1} + u_i)/(2N)`, `(x_{i−1} + x_i)/(2N)`).
struct Integrals<S> {
    u_w: S,
    u_tu: S,
    b: S,
}

impl<S: Scalar> Integrals<S> {
    fn of(s: &Augmented<S>) -> Self {
        let n = s.x.len() - 1;
        let nn = S::from_usize(n);
        let spread = s.x[n].clone() - &s.x[0];
        // Σ_i u_i (2i − 1), Σ_i u_i (u_{i−1} + u_i), Σ_i u_i (x_{i−1} + x_i).
        let odd: Vec<S> = (1..=n).map(|i| S::from_usize(2 * i - 1)).collect();
        let (u, x) = (&s.u[1..], &s.x[1..]);
        let dot = S::sum_of_products;
        let uw = dot(u, &odd);
        let utu = dot(u, &s.u[..n]) + &dot(u, u);
        let ux = dot(u, &s.x[..n]) + &dot(u, x);
        let two_n = S::from_i64(2) * &nn;
        let u_w = uw / &(two_n.clone() * &nn);
        let b = spread * &u_w - &(ux / &two_n);
        Integrals {
            u_w,
            u_tu: utu / &two_n,
            b,
        }
    }
    /// `∫_0^1 U_N (c w − Ũ_N) dw`.
    fn a(&self, c: &S) -> S {
        c.clone() * &self.u_w - &self.u_tu
    }
}

/// Both sides of the tested identity for the bump `ϕ`, with the printed
/// or the corrected coefficient of `w` (`statement`); and the bound
/// `2‖ϕ‖_{L¹} sup‖U_N‖²_∞ + ‖ϕ'‖_{L¹} sup_t ‖U_N‖_∞ ((x_N − x_0) + max(|x_0|, |x_N|))`
/// that the corrected right side gives.
fn sides<S: Scalar>(
    case: &Case<S>,
    bump: &Bump<S>,
    statement: Statement,
    id: &'static str,
) -> Result<(S, S, S), Violation> {
    let n = case.n();
    let nn = S::from_usize(n);
    let mut cuts = vec![bump.a.clone()];
    for imp in case.traj.impulses() {
        if imp.t > bump.a && imp.t < bump.b && cuts.last() != Some(&imp.t) {
            cuts.push(imp.t.clone());
        }
    }
    cuts.push(bump.b.clone());
    let (mut lhs, mut rhs) = (S::zero(), S::zero());
    let (mut sup_u, mut sup_um) = (S::zero(), S::zero());
    let at = |t: &S| {
        case.state(t)
            .map(|st| augmented(case, &st))
            .map_err(|e| Violation::new(id, e.to_string()))
    };
    // The state at the end of a piece is the one at the start of the next.
    let mut next = at(&cuts[0])?;
    for w in cuts.windows(2) {
        let (alpha, beta) = (&w[0], &w[1]);
        let s = std::mem::replace(&mut next, at(beta)?);
        let e = &next;
        // Collision at α (inside (a, b)): a Dirac mass of P̃_N.
        if alpha > &bump.a {
            let mut jumps = vec![S::zero(); n + 1];
            for imp in case.traj.impulses().iter().filter(|i| i.t == *alpha) {
                for (k, j) in augmented_jumps(n, imp).into_iter().enumerate() {
                    jumps[k] = jumps[k].clone() + &j;
                }
            }
            let spread = s.x[n].clone() - &s.x[0];
            let mut sum = S::zero();
            for i in 1..=n {
                if jumps[i - 1].is_zero() && jumps[i].is_zero() {
                    continue; // a zero term
                }
                let weight = spread.clone() - &(nn.clone() * &(s.x[i].clone() - &s.x[i - 1]));
                sum = sum
                    + &(weight * &((jumps[i - 1].clone() + &jumps[i]) / (S::from_i64(2) * &nn)));
            }
            lhs = lhs + &(bump.phi(alpha) * &sum);
        }
        let true_c = s.u[n].clone() - &s.u[0];
        let c = match statement {
            Statement::Printed => -true_c.clone(),
            Statement::Corrected => true_c.clone(),
        };
        let integrals = Integrals::of(&s);
        let (a_true, b_alpha) = (integrals.a(&true_c), integrals.b.clone());
        let a_c = integrals.a(&c);
        let int_phi = bump.big_phi(beta) - &bump.big_phi(alpha);
        let piece = a_c * &int_phi
            + &(b_alpha * &(bump.phi(beta) - &bump.phi(alpha)))
            + &(a_true * &((beta.clone() - alpha) * &bump.phi(beta) - &int_phi));
        rhs = rhs - &piece;
        let um = s.u[1..].iter().fold(S::zero(), |m, v| {
            if abs(v.clone()) > m {
                abs(v.clone())
            } else {
                m
            }
        });
        if um > sup_u {
            sup_u = um.clone();
        }
        for p in [&s, e] {
            let spread = p.x[n].clone() - &p.x[0];
            let big = if abs(p.x[0].clone()) > abs(p.x[n].clone()) {
                abs(p.x[0].clone())
            } else {
                abs(p.x[n].clone())
            };
            let m = um.clone() * &(spread + &big);
            if m > sup_um {
                sup_um = m;
            }
        }
    }
    let mid = (bump.a.clone() + &bump.b) / S::from_i64(2);
    let l1_phi = bump.big_phi(&bump.b);
    let l1_dphi = S::from_i64(2) * &bump.phi(&mid);
    let bound = S::from_i64(2) * &l1_phi * &sup_u * &sup_u + &(l1_dphi * &sup_um);
    Ok((lhs, rhs, bound))
}

/// The bumps of a case: `[a, b]` over (a prefix of at most 400 of) the
/// collision instants, and `[a, c]` ending between the first two.
fn bumps<S: Scalar>(case: &Case<S>) -> Vec<Bump<S>> {
    let mut instants: Vec<&S> = Vec::new();
    for imp in case.traj.impulses() {
        if instants.last() != Some(&&imp.t) {
            instants.push(&imp.t);
        }
    }
    let Some(first) = instants.first() else {
        return vec![Bump::new(S::one(), S::from_i64(2))];
    };
    let two = S::from_i64(2);
    let a = (*first).clone() / &two;
    let last = instants[instants.len().min(400) - 1].clone();
    let next = instants
        .get(1)
        .map_or(last.clone() + &S::one(), |t| (*t).clone());
    vec![
        Bump::new(a.clone(), last + &S::one()),
        Bump::new(a, ((*first).clone() + &next) / &two),
    ]
}

fn identity<S: Scalar>(case: &Case<S>, statement: Statement, id: &'static str) -> R {
    for bump in bumps(case) {
        let (lhs, rhs, bound) = sides(case, &bump, statement, id)?;
        let sup = if abs(lhs.clone()) > bound {
            Some(&bound)
        } else {
            None
        };
        if lhs != rhs || (statement == Statement::Corrected && sup.is_some()) {
            return Err(Violation::new(
                id,
                format!(
                    "ϕ = (t − a)²(b − t)² on [a, b] = [{}, {}]: ∫∫((x[N−1] − x[−1]) − ∂_w X̃_N)ϕ P̃_N = {} but the right side = {} (bound {})",
                    bump.a.render(),
                    bump.b.render(),
                    lhs.render(),
                    rhs.render(),
                    bound.render()
                ),
            ));
        }
    }
    Ok(())
}

/// `eq:test-pressure-bound` as printed: the identity obtained "using
/// eq:PDE-Lagr-N-2", with `(U_N(t,0) − U_N(t,1))w`.
pub fn test_identity_printed<S: Scalar>(case: &Case<S>) -> R {
    identity(case, Statement::Printed, "eq:test-pressure-bound")
}

/// Corrected: the identity with `(u_N − u_0)w` (`∂_t φ` of the proof),
/// exactly, and the bound it gives.
pub fn test_identity_corrected<S: Scalar>(case: &Case<S>) -> R {
    identity(
        case,
        Statement::Corrected,
        "eq:test-pressure-bound (corrected)",
    )
}

/// `prop:pressure-bound#test-function`: "at the boundaries φ(t,0) = φ(t,1)
/// = 0", with the normalisation `x⁰_0 = 0` of `prop:Linf-micro`: `φ(t,0) =
/// −X̃_N(t,0)ϕ(t) = −x_0(t)ϕ(t)` and `φ(t,1) = −x_0(t)ϕ(t)`, checked at the
/// probe times `t > 0` (any `ϕ ≥ 0` with `ϕ(t) > 0`).
pub fn test_function_boundary<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "prop:pressure-bound#test-function";
    let n = case.n();
    let initial = case
        .state(&S::zero())
        .map_err(|e| Violation::new(ID, e.to_string()))?;
    let origin = augmented(case, &initial).x[0].clone();
    for t in &case.times {
        let st = case
            .state(t)
            .map_err(|e| Violation::new(ID, e.to_string()))?;
        let s = augmented(case, &st);
        let at0 = -(s.x[0].clone() - &origin);
        let at1 = (s.x[n].clone() - &s.x[0]) - &(s.x[n].clone() - &origin);
        if !at0.is_zero() || !at1.is_zero() {
            return Err(Violation::new(
                ID,
                format!(
                    "t = {} (x⁰[−1] = 0): φ(t,0)/ϕ(t) = {}, φ(t,1)/ϕ(t) = {}",
                    t.render(),
                    at0.render(),
                    at1.render()
                ),
            )
            .at(t.render())
            .sides(
                "φ(t,0)/ϕ(t), φ(t,1)/ϕ(t)",
                format!("{}, {}", at0.render(), at1.render()),
                "0, 0",
                "0, 0",
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::initial::InitialData;

    use crate::rational::ratio as q;

    #[test]
    fn the_bump_integrates_exactly() {
        let b = Bump::new(q(0, 1), q(1, 1));
        assert_eq!(b.phi(&q(1, 2)), q(1, 16));
        assert_eq!(b.big_phi(&q(1, 1)), q(1, 30));
        assert_eq!(b.phi(&q(2, 1)), q(0, 1));
    }

    /// N = 3, 2r = 1/3, u⁰ = (2, 0, −1): the corrected identity holds, the
    /// printed one does not (u_N ≠ u_0 before the last collision), nor does
    /// the boundary claim (x_0 moves).
    #[test]
    fn identity_holds_corrected_and_fails_printed() {
        let data = InitialData::with_paper_radius(
            vec![q(0, 1), q(1, 1), q(2, 1)],
            vec![q(2, 1), q(0, 1), q(-1, 1)],
        )
        .unwrap();
        let case = Case::new(data, None);
        test_identity_corrected(&case).unwrap();
        assert!(test_identity_printed(&case).is_err());
        assert!(test_function_boundary(&case).is_err());
        let bump = &bumps(&case)[0];
        let (lhs, rhs, _) = sides(&case, bump, Statement::Corrected, "test").unwrap();
        assert_eq!(lhs, rhs);
        assert!(lhs > q(0, 1), "the pressure is seen");
    }
}
