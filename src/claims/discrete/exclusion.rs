//! The exclusion of section 3: the pressure lives where the particles
//! touch, `(∂_w X̃_N − 1) P = 0` at every collision instant (`lem:discPDE2`,
//! `prop:pressure-bound`), and its pairing with a test function
//! (`prop:2ndorder-LagrPDE`).

use super::{augmented, augmented_jumps, R};
use crate::claims::bump::Bump;
use crate::claims::{Case, FromPaper, Violation};
use crate::scalar::Scalar;

/// The interpolant of the pressure in `w` that an exclusion statement
/// multiplies by `∂_w X̃_N − 1`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Interpolant {
    /// `P_N = p_i` on `((i−1)/N, i/N]` (`lem:discPDE2`): cell `i` carries
    /// the jump of `p_i` alone.
    PiecewiseConstant,
    /// `P̃_N`, affine from `p_{i−1}` to `p_i` on cell `i`
    /// (`prop:pressure-bound`): cell `i` carries both jumps.
    PiecewiseAffine,
}

fn exclusion<S: Scalar>(case: &Case<S>, id: &'static str, pressure: Interpolant) -> R {
    let n = S::from_usize(case.n());
    for imp in case.impulse_spread() {
        let (t, jumps) = (imp.t.clone(), augmented_jumps(case.n(), imp));
        let s = case
            .state(&t)
            .map_err(|e| Violation::new(id, e.to_string()))?;
        let a = augmented(case, &s);
        for i in 1..=case.n() {
            let slope = n.clone() * &(a.x[i].clone() - &a.x[i - 1]);
            let carried = match pressure {
                Interpolant::PiecewiseAffine => !jumps[i].is_zero() || !jumps[i - 1].is_zero(),
                Interpolant::PiecewiseConstant => !jumps[i].is_zero(),
            };
            if carried && slope != S::one() {
                return Err(Violation::new(
                    id,
                    format!(
                        "collision at t = {}: on ({}/N, {i}/N] the pressure carries the jumps p[{}] = {}·δ, p[{}] = {}·δ but ∂_w X̃_N − 1 = {} ≠ 0",
                        t.render(),
                        i - 1,
                        FromPaper(i - 1),
                        jumps[i - 1].render(),
                        FromPaper(i),
                        jumps[i].render(),
                        (slope - &S::one()).render()
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// `lem:discPDE2#exclusion`, as printed: `(∂_w X̃_N − 1) P_N = 0` with `P_N`
/// piecewise constant (`P_N = p_i` on `((i−1)/N, i/N]`).
pub fn disc_pde2_printed<S: Scalar>(case: &Case<S>) -> R {
    exclusion(
        case,
        "lem:discPDE2#exclusion",
        Interpolant::PiecewiseConstant,
    )
}

/// `prop:pressure-bound#exclusion`, as used in the proof:
/// `(∂_w X̃_N − 1) P̃_N = 0` with `P̃_N` piecewise affine.
pub fn pressure_bound_exclusion_printed<S: Scalar>(case: &Case<S>) -> R {
    exclusion(
        case,
        "prop:pressure-bound#exclusion",
        Interpolant::PiecewiseAffine,
    )
}

/// The pairings at one collision instant `t_k` (the pressure is a Dirac mass
/// in time there, with the jumps `[λ_i]_{t_k}` as weights) against
/// `(∂_w X̃_N − 1)Ψ` for `Ψ = 1` on `(0, 1)`: `(P̃_N, P_N)` with `P̃_N`
/// affine from `p_{i−1}` to `p_i` on cell `i` (mean `(p_{i−1} + p_i)/2`) and
/// the re-indexed `P_N := p_{i−1}`, the pressure of the pair `(i−1, i)`
/// whose gap is that cell's.
fn pairings<S: Scalar>(
    case: &Case<S>,
    imp: &crate::contact::Impulse<S>,
    id: &'static str,
) -> Result<(S, S), Violation> {
    let n = S::from_usize(case.n());
    let jumps = augmented_jumps(case.n(), imp);
    let s = case
        .state(&imp.t)
        .map_err(|e| Violation::new(id, e.to_string()))?;
    let a = augmented(case, &s);
    let (mut affine, mut reindexed) = (S::zero(), S::zero());
    for i in 1..=case.n() {
        let excess = n.clone() * &(a.x[i].clone() - &a.x[i - 1]) - &S::one();
        let mean = (jumps[i - 1].clone() + &jumps[i]) / &S::from_i64(2);
        affine = affine + &(excess.clone() * &mean / &n);
        reindexed = reindexed + &(excess * &jumps[i - 1] / &n);
    }
    Ok((affine, reindexed))
}

/// `prop:2ndorder-LagrPDE#exclusion-pairing`, as printed in the proof:
/// "for Ψ ∈ C¹_c((0,T)×(0,1)), we have 0 = ⟨P̃_N, (∂_w X̃_N − 1)Ψ⟩",
/// tested with an explicit bump: at the first collision `t_k` (of a spread
/// of 40) where a cell `i` carries pressure (`[λ_{i−1}]` or `[λ_i]` ≠ 0)
/// with slope `≠ 1`, `Ψ(t,w) = ϕ(t)ψ(w)`, `ϕ` the bump on
/// `[t_k/2, (t_k + T)/2]` (`T` = last collision + 1) and `ψ` the bump on the
/// middle half of cell `i`, both `((· − a)(b − ·))²` (`C¹`, compact support
/// inside `(0,T)×(0,1)`). The pairing is `Σ_j ϕ(t_j)(N(x_i − x_{i−1}) − 1)
/// ∫ P̃_j ψ dw` over every collision `t_j`, each term `≥ 0`.
pub fn pairing_printed<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "prop:2ndorder-LagrPDE#exclusion-pairing";
    let n = S::from_usize(case.n());
    let Some(last) = case.traj.impulses().last().map(|imp| imp.t.clone()) else {
        return Ok(());
    };
    let t_end = last + &S::one();
    let excess_at = |t: &S, i: usize| -> Result<S, Violation> {
        let s = case
            .state(t)
            .map_err(|e| Violation::new(ID, e.to_string()))?;
        let a = augmented(case, &s);
        Ok(n.clone() * &(a.x[i].clone() - &a.x[i - 1]) - &S::one())
    };
    for imp in case.impulse_spread() {
        let jumps = augmented_jumps(case.n(), imp);
        for i in 1..=case.n() {
            if (jumps[i].is_zero() && jumps[i - 1].is_zero()) || excess_at(&imp.t, i)?.is_zero() {
                continue;
            }
            let two = S::from_i64(2);
            let phi = Bump::new(imp.t.clone() / &two, (imp.t.clone() + &t_end) / &two);
            let cell = S::from_usize(i - 1) / &n;
            let quarter = S::one() / (S::from_i64(4) * &n);
            let psi = Bump::new(
                cell.clone() + &quarter,
                cell + &(quarter.clone() * &S::from_i64(3)),
            );
            let mut pairing = S::zero();
            for other in case.traj.impulses() {
                let weight = phi.phi(&other.t);
                if weight.is_zero() {
                    continue;
                }
                let j = augmented_jumps(case.n(), other);
                // P̃ on cell i: j[i−1] + (j[i] − j[i−1])(N w − (i − 1)).
                let slope = j[i].clone() - &j[i - 1];
                let affine = [
                    j[i - 1].clone() - &(slope.clone() * &S::from_usize(i - 1)),
                    slope * &n,
                ];
                pairing =
                    pairing + &(weight * &excess_at(&other.t, i)? * &psi.integral_times(&affine));
            }
            if !pairing.is_zero() {
                let test = format!(
                    "Ψ(t,w) = ϕ(t)ψ(w), ϕ(t) = {}, ψ(w) = {}",
                    phi.describe("t"),
                    psi.describe("w")
                );
                return Err(Violation::new(
                    ID,
                    format!(
                        "collision at t = {}, cell ({}/N, {i}/N] (slope N(x[{}] − x[{}]) ≠ 1, artificial particle x[−1] = x[0] − 1/N − 1): ⟨P̃_N, (∂_w X̃_N − 1)Ψ⟩ = {} ≠ 0 for {test}",
                        imp.t.render(),
                        i - 1,
                        FromPaper(i),
                        FromPaper(i - 1),
                        pairing.render()
                    ),
                )
                .at(imp.t.render())
                .indices(&[i - 1])
                .test_function(test)
                .sides("⟨P̃_N, (∂_w X̃_N − 1)Ψ⟩", pairing.render(), "0", "0"));
            }
        }
    }
    Ok(())
}

/// The corrected step: with the re-indexed `P_N := p_{i−1}` on cell `i`,
/// `⟨P_N, (∂_w X̃_N − 1)Ψ⟩ = 0` exactly at every collision, so
/// `⟨P̃_N, (∂_w X̃_N − 1)Ψ⟩ = ⟨(∂_w X̃_N − 1)(P̃_N − P_N), Ψ⟩ = −⟨R¹_N, Ψ⟩`
/// (checked as an identity of the two computed pairings).
pub fn pairing_reindexed<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "prop:2ndorder-LagrPDE#exclusion-pairing (corrected)";
    let n = S::from_usize(case.n());
    for imp in case.impulse_spread() {
        let (affine, reindexed) = pairings(case, imp, ID)?;
        if !reindexed.is_zero() {
            return Err(Violation::new(
                ID,
                format!(
                    "collision at t = {}: ⟨P_N, (∂_w X̃_N − 1)·1⟩ = {} ≠ 0 with P_N := p_{{i−1}}",
                    imp.t.render(),
                    reindexed.render()
                ),
            ));
        }
        // −⟨R¹_N, 1⟩ = Σ_i (N gap_i − 1)([λ_i] − [λ_{i−1}])/(2N), computed
        // apart from the pairing.
        let jumps = augmented_jumps(case.n(), imp);
        let s = case
            .state(&imp.t)
            .map_err(|e| Violation::new(ID, e.to_string()))?;
        let a = augmented(case, &s);
        let mut r1 = S::zero();
        for i in 1..=case.n() {
            let excess = n.clone() * &(a.x[i].clone() - &a.x[i - 1]) - &S::one();
            r1 = r1
                + &(excess * &(jumps[i].clone() - &jumps[i - 1]) / &(n.clone() * &S::from_i64(2)));
        }
        if r1 != affine {
            return Err(Violation::new(
                ID,
                format!(
                    "collision at t = {}: ⟨P̃_N, (∂_w X̃_N − 1)⟩ = {} but −⟨R¹_N, 1⟩ = {}",
                    imp.t.render(),
                    affine.render(),
                    r1.render()
                ),
            ));
        }
    }
    Ok(())
}
