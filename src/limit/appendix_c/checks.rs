//! The ledger's checks of Appendix C (`app:uniqueness`), each a
//! `Result<(), Violation>` the claims registry calls: the printed formulas
//! of [`TwoBlocks`] (the one definition of `X⁰`, `U⁰`, `X^f`, the two
//! continuations and their pressure weights) against `eq:PDE-Lagr-2` and
//! `eq:Oleinik-Lagr`, the sticky one against the particle system, and the
//! projection principle against both.
//!
//! The pressures are Dirac masses in time at `t*` with a weight `P(w)`;
//! `∂_t U + ∂_w P = 0` then says `P'(w) = U⁰(w) − U(t*⁺, w)` on each side,
//! with `P(0) = P(1) = 0` and `P` continuous (no Dirac mass in `w`), and
//! `P ≥ 0`: checked at the grid points `k/16`, the first failing point
//! being the witness.

use num_rational::BigRational;
use num_traits::Signed;

use super::{q, Continuation, Printing, TwoBlocks, Q};
use crate::limit::continuum::Continuum;
use crate::scalar::Scalar;
use crate::scene;
use crate::trajectory::Trajectory;
use crate::violation::Violation;

type R = Result<(), Violation>;

fn violation(id: &'static str, e: impl std::fmt::Display) -> Violation {
    Violation::new(id, e.to_string())
}

/// The example with `η = 1/4`, the shipped scene's (the pressure weights
/// do not depend on `η`).
fn quarter(id: &'static str) -> Result<TwoBlocks, Violation> {
    TwoBlocks::new(q(1, 4)).map_err(|e| violation(id, e))
}

/// The sample points: `k/16`, `k = 0 … 16`.
fn grid() -> Vec<BigRational> {
    (0..=16).map(|k| q(k, 16)).collect()
}

/// `eq:PDE-Lagr-2` for the pressure `P = W(w) δ_{t*}` of continuation `c`
/// (weight `p`, called `name` in the witness): `P ≥ 0` and
/// `∂_w P = U⁰ − U(t*⁺)` at the grid points, `P` continuous at `1/2` and
/// `P(0) = P(1) = 0`.
fn check_weight(id: &'static str, name: &str, c: Continuation, p: Printing) -> R {
    let tb = quarter(id)?;
    let weight = tb.pressure_weight(c, p);
    let slope = weight.deriv();
    let u0 = tb.u0();
    let u_after = tb.u(c, &tb.t_star());
    for w in grid() {
        let v = weight.eval(&w);
        if v < BigRational::zero() {
            return Err(Violation::new(
                id,
                format!(
                    "{name}: P({}) = {} < 0 (P ≥ 0 fails)",
                    w.render(),
                    v.render()
                ),
            ));
        }
        let expected = u0.eval(&w) - u_after.eval(&w);
        if slope.eval(&w) != expected {
            return Err(Violation::new(
                id,
                format!(
                    "{name}: ∂_w P({}) = {} but −[U]_{{t*}} = U⁰ − U(t*⁺) = {} (∂_t U + ∂_w P = 0 fails)",
                    w.render(),
                    slope.eval(&w).render(),
                    expected.render()
                ),
            ));
        }
    }
    let half = q(1, 2);
    let jump = weight.jump_at_half();
    if !jump.is_zero() {
        let right = weight.eval(&half);
        return Err(Violation::new(
            id,
            format!(
                "{name}: P jumps at w = 1/2 (left limit {}, right value {}): ∂_w P has a Dirac mass there",
                (right.clone() - &jump).render(),
                right.render()
            ),
        ));
    }
    for end in [q(0, 1), q(1, 1)] {
        if !weight.eval(&end).is_zero() {
            return Err(Violation::new(
                id,
                format!(
                    "{name}: P({}) = {} ≠ 0",
                    end.render(),
                    weight.eval(&end).render()
                ),
            ));
        }
    }
    Ok(())
}

/// `app:uniqueness#sticky-pressure`, as printed:
/// `P¹ = [w 1_{[0,1/2)} − (1 − w) 1_{[1/2,1]}] δ_{t = t*}` with `U¹ = 0`.
pub fn sticky_pressure_printed() -> R {
    check_weight(
        "app:uniqueness#sticky-pressure",
        "P¹ as printed",
        Continuation::Sticky,
        Printing::AsPrinted,
    )
}

/// Corrected: `P¹ = [w 1_{[0,1/2)} + (1 − w) 1_{[1/2,1]}] δ_{t = t*}`; and it
/// is the limit of the particles: for the quantile sampling of the shipped
/// scene with N = 16 and 64, the jump of `λ_i` at `t*` is exactly `P¹(i/N)`,
/// and after `t*` the particles sit at `X¹(t, i/N) = i/N + η/2` with
/// `U¹ = 0`.
pub fn sticky_pressure_corrected() -> R {
    const ID: &str = "app:uniqueness#sticky-pressure (corrected)";
    check_weight(
        ID,
        "P¹ corrected",
        Continuation::Sticky,
        Printing::Corrected,
    )?;
    let tb = quarter(ID)?;
    let p = tb.pressure_weight(Continuation::Sticky, Printing::Corrected);
    let text = scene::shipped("appendix-c-two-blocks")
        .ok_or_else(|| Violation::new(ID, "the Appendix C scene is not shipped"))?;
    let sc = scene::parse(text).map_err(|e| Violation::new(ID, e.to_string()))?;
    let scene::SceneKind::Macro { datum, .. } = sc.kind else {
        return Err(Violation::new(
            ID,
            "the Appendix C scene is not a macro scene",
        ));
    };
    let t_star = tb.t_star();
    for n in [16usize, 64] {
        let traj = Trajectory::new(
            datum
                .sample(n)
                .map_err(|e| Violation::new(ID, e.to_string()))?,
        );
        let imps = traj.impulses();
        if imps.len() != 1 || imps[0].t != t_star {
            return Err(Violation::new(
                ID,
                format!(
                    "N = {n}: expected one collision at t* = 1/8, got {}",
                    imps.len()
                ),
            ));
        }
        let nn = BigRational::from_usize(n);
        for (k, j) in imps[0].jumps().iter().enumerate() {
            let w = BigRational::from_usize(k + 1) / &nn;
            if *j != p.eval(&w) {
                return Err(Violation::new(
                    ID,
                    format!(
                        "N = {n}: jump of λ_{} = {} ≠ P¹({}) = {}",
                        k + 1,
                        j.render(),
                        w.render(),
                        p.eval(&w).render()
                    ),
                ));
            }
        }
        for t in [t_star.clone(), q(1, 1)] {
            let s = traj.at(&t).map_err(|e| Violation::new(ID, e.to_string()))?;
            for (i, (x, u)) in s.positions.iter().zip(&s.velocities).enumerate() {
                let w = BigRational::from_usize(i + 1) / &nn;
                if *x != w.clone() + &t_star || !u.is_zero() {
                    return Err(Violation::new(
                        ID,
                        format!(
                            "N = {n}, t = {}: x_{} = {}, u = {} (X¹ = {})",
                            t.render(),
                            i + 1,
                            x.render(),
                            u.render(),
                            (w + &t_star).render()
                        ),
                    ));
                }
            }
        }
    }
    Ok(())
}

/// `app:uniqueness#rebound-pressure`: `U² = 2w − 1` after `t*` and
/// `P² = [(2w − w²) 1_{[0,1/2)} − (w² − 1) 1_{[1/2,1]}] δ_{t = t*}`.
pub fn rebound_pressure() -> R {
    check_weight(
        "app:uniqueness#rebound-pressure",
        "P² as printed",
        Continuation::Rebound,
        Printing::AsPrinted,
    )
}

/// `app:uniqueness#rebound-oleinik`: `∂_w U² = 2`, `∂_w X²(t, w) = 1 +
/// 2(t − t*)`, and `∂_w U² < ∂_w X² / t` for all `t > t*` when `η < 1`
/// (checked for `η ∈ {1/4, 1/2, 3/4}` at `t = t* + k/8`, `k = 1 … 40`, at
/// the grid points), and `∂_w X² ≥ 1`.
pub fn rebound_oleinik() -> R {
    const ID: &str = "app:uniqueness#rebound-oleinik";
    for eta in [q(1, 4), q(1, 2), q(3, 4)] {
        let tb = TwoBlocks::new(eta.clone()).map_err(|e| violation(ID, e))?;
        let t_star = tb.t_star();
        for k in 1..=40 {
            let t = t_star.clone() + q(k, 8);
            // X²(t, w) = w + η/2 + (t − t*)(2w − 1): its slope in w.
            let x = tb.x(Continuation::Rebound, &t).deriv();
            let u = tb.u(Continuation::Rebound, &t).deriv();
            for w in grid() {
                let (dx, du) = (x.eval(&w), u.eval(&w));
                if du >= dx.clone() / &t || dx < q(1, 1) {
                    return Err(Violation::new(
                        ID,
                        format!(
                            "η = {}, t = {}: ∂_w U² = {}, ∂_w X²/t = {}",
                            eta.render(),
                            t.render(),
                            du.render(),
                            (dx / t).render()
                        ),
                    ));
                }
            }
        }
    }
    Ok(())
}

/// `app:uniqueness#free-collision`: `X^f(t*, w) = X⁰(w) + t* U⁰(w) = w + η/2`
/// at `t* = η/2`.
pub fn free_collision() -> R {
    const ID: &str = "app:uniqueness#free-collision";
    for eta in [q(1, 4), q(1, 2), q(3, 4)] {
        let tb = TwoBlocks::new(eta.clone()).map_err(|e| violation(ID, e))?;
        let t_star = tb.t_star();
        let x_free = tb.x_free(&t_star);
        for w in grid() {
            let xf = x_free.eval(&w);
            if xf != w.clone() + &t_star {
                return Err(Violation::new(
                    ID,
                    format!(
                        "η = {}, w = {}: X^f = {}",
                        eta.render(),
                        w.render(),
                        xf.render()
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// `app:uniqueness#projection-selects-sticky`: for `η ∈ {1/4, 1/2, 3/4}`,
/// both continuations (sticky with the corrected `P¹`) solve
/// `eq:PDE-Lagr-2` with `P ≥ 0`, complementarity and `eq:Oleinik-Lagr`;
/// only the sticky one satisfies the projection principle
/// `eq:velocity-projection` and the projection formula `X = P_K(X⁰ + tU⁰)`.
pub fn projection_selects_sticky() -> Result<(), Violation> {
    const ID: &str = "app:uniqueness#projection-selects-sticky";
    for eta in [q(1, 4), q(1, 2), q(3, 4)] {
        let tb = TwoBlocks::new(eta.clone()).map_err(|e| violation(ID, e))?;
        let sticky = tb
            .findings(Continuation::Sticky, Printing::Corrected)
            .map_err(|e| violation(ID, e))?;
        let rebound = tb
            .findings(Continuation::Rebound, Printing::AsPrinted)
            .map_err(|e| violation(ID, e))?;
        if let Some(f) = sticky.iter().find(|f| !f.holds) {
            return Err(violation(
                ID,
                format!(
                    "η = {}: sticky fails {}: {}",
                    eta.render(),
                    f.claim,
                    f.detail
                ),
            ));
        }
        for f in &rebound {
            let expected = !matches!(
                f.claim,
                "eq:velocity-projection" | "eq:Lagr-1" | "eq:Lagr-1 (X(t) = P_K(X⁰ + tU⁰))"
            );
            if f.holds != expected {
                return Err(violation(
                    ID,
                    format!(
                        "η = {}: rebound {} {} ({})",
                        eta.render(),
                        if f.holds {
                            "unexpectedly satisfies"
                        } else {
                            "fails"
                        },
                        f.claim,
                        f.detail
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// `app:uniqueness#particle-limit`: for `η = 1/4`, `t = 1`, the quantile
/// samplings with `N = 8 … 512` satisfy `‖X_N − X¹‖² = 1/(3N²)` exactly
/// (→ 0) while `‖X_N − X²‖² → (t − t*)²/3 > 0` (within `1/N`): the sticky
/// continuation is the `N → ∞` limit, the rebound is not.
pub fn sticky_is_particle_limit() -> Result<(), Violation> {
    const ID: &str = "app:uniqueness#particle-limit";
    let tb = TwoBlocks::new(q(1, 4)).map_err(|e| violation(ID, e))?;
    let t = q(1, 1);
    let ns = [8usize, 16, 32, 64, 128, 256, 512];
    let d = tb
        .particle_distances(&ns, &t)
        .map_err(|e| violation(ID, e))?;
    particle_limit_on(&tb, &t, &d)
}

/// [`sticky_is_particle_limit`] on given distances `(N, ‖X_N − X¹‖²,
/// ‖X_N − X²‖²)` at `t` ([`TwoBlocks::particle_distances`];
/// `tests/claims_selfcheck.rs` passes distances of corrupted positions).
pub fn particle_limit_on(tb: &TwoBlocks, t: &Q, d: &[(usize, Q, Q)]) -> Result<(), Violation> {
    const ID: &str = "app:uniqueness#particle-limit";
    if d.is_empty() {
        return Err(violation(ID, "vacuous: no N measured"));
    }
    let gap = (t - tb.t_star()) * (t - tb.t_star()) / q(3, 1);
    for (n, d1, d2) in d {
        let nn = Q::from_integer((*n).into());
        if *d1 != (q(3, 1) * &nn * &nn).recip() {
            return Err(violation(
                ID,
                format!("N = {n}: ‖X_N − X¹‖² = {} ≠ 1/(3N²)", d1.render()),
            ));
        }
        if (d2 - &gap).abs() > nn.recip() {
            return Err(violation(
                ID,
                format!(
                    "N = {n}: ‖X_N − X²‖² = {} is not within 1/N of (t − t*)²/3 = {}",
                    d2.render(),
                    gap.render()
                ),
            ));
        }
    }
    Ok(())
}

/// `app:uniqueness#sticky-pressure-is-continuum`: the corrected `P¹` weight
/// is the jump at `t*` of the continuum multiplier `Λ` (from
/// `∂_t X = U⁰ − ∂_w Λ`, `Λ(t,0) = Λ(t,1) = 0`), for `η ∈ {1/4, 1/2, 3/4}`.
pub fn sticky_pressure_is_continuum() -> Result<(), Violation> {
    const ID: &str = "app:uniqueness#sticky-pressure-is-continuum";
    for eta in [q(1, 4), q(1, 2), q(3, 4)] {
        let tb = TwoBlocks::new(eta.clone()).map_err(|e| violation(ID, e))?;
        let c = Continuum::new(&tb.datum().map_err(|e| violation(ID, e))?);
        let before = c
            .profile(&(tb.t_star() / q(2, 1)))
            .map_err(|e| violation(ID, e))?;
        let at = c.profile(&tb.t_star()).map_err(|e| violation(ID, e))?;
        pressure_is_continuum_on(&tb, &before, &at)?;
    }
    Ok(())
}

/// [`sticky_pressure_is_continuum`] for one `η` on given continuum profiles
/// before and at `t*` (`tests/claims_selfcheck.rs` passes corrupted ones).
pub fn pressure_is_continuum_on(
    tb: &TwoBlocks,
    before: &crate::limit::continuum::Profile<crate::limit::surd::Surd>,
    at: &crate::limit::continuum::Profile<crate::limit::surd::Surd>,
) -> Result<(), Violation> {
    const ID: &str = "app:uniqueness#sticky-pressure-is-continuum";
    let w = tb.pressure_weight(Continuation::Sticky, Printing::Corrected);
    for k in 0..=32 {
        let wq = q(k, 32);
        let l0 = before
            .lambda_exact(&wq)
            .and_then(|s| s.as_rational().cloned());
        let l1 = at.lambda_exact(&wq).and_then(|s| s.as_rational().cloned());
        let jump = match (l0, l1) {
            (Some(a), Some(b)) => b - a,
            _ => return Err(violation(ID, "irrational Λ")),
        };
        if jump != w.eval(&wq) {
            return Err(violation(
                ID,
                format!(
                    "η = {}, w = {}: [Λ]_{{t*}} = {} but P¹ (corrected) = {}",
                    tb.eta().render(),
                    wq.render(),
                    jump.render(),
                    w.eval(&wq).render()
                ),
            ));
        }
    }
    Ok(())
}
