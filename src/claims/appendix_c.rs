//! Appendix C (`app:uniqueness`): the two-block example, its two
//! continuations (sticky and rebound) checked exactly as printed against the
//! second-order Lagrangian system `eq:PDE-Lagr-2` and the Oleinik inequality
//! `eq:Oleinik-Lagr`, and the sticky one against the particle system.
//!
//! Data: `X⁰(w) = w` on `[0, 1/2)`, `w + η` on `[1/2, 1]`; `U⁰ = 1` then
//! `−1`; collision at `t* = η/2`. The pressures are Dirac masses in time at
//! `t*` with a weight `P(w)`; `∂_t U + ∂_w P = 0` then says
//! `P'(w) = U⁰(w) − U(t*⁺, w)` on each side, with `P(0) = P(1) = 0` and `P`
//! continuous (no Dirac mass in `w`), and `P ≥ 0`.

use num_rational::BigRational;

use super::Violation;
use crate::scalar::Scalar;
use crate::scene;
use crate::trajectory::Trajectory;

type R = Result<(), Violation>;

fn q(n: i64, d: i64) -> BigRational {
    BigRational::from_i64(n) / BigRational::from_i64(d)
}

/// A pressure weight on `[0, 1]`: the formula on `[0, 1/2)` and on
/// `[1/2, 1]`, and their derivatives.
struct Weight {
    name: &'static str,
    left: fn(&BigRational) -> BigRational,
    right: fn(&BigRational) -> BigRational,
    left_slope: fn(&BigRational) -> BigRational,
    right_slope: fn(&BigRational) -> BigRational,
}

impl Weight {
    fn value(&self, w: &BigRational) -> BigRational {
        if *w < q(1, 2) {
            (self.left)(w)
        } else {
            (self.right)(w)
        }
    }
    fn slope(&self, w: &BigRational) -> BigRational {
        if *w < q(1, 2) {
            (self.left_slope)(w)
        } else {
            (self.right_slope)(w)
        }
    }
}

fn u0(w: &BigRational) -> BigRational {
    if *w < q(1, 2) {
        q(1, 1)
    } else {
        q(-1, 1)
    }
}

/// The sample points: `k/16`, `k = 0 … 16`.
fn grid() -> Vec<BigRational> {
    (0..=16).map(|k| q(k, 16)).collect()
}

fn check_weight(id: &'static str, p: &Weight, u_after: fn(&BigRational) -> BigRational) -> R {
    for w in grid() {
        let v = p.value(&w);
        if v < BigRational::zero() {
            return Err(Violation::new(
                id,
                format!(
                    "{}: P({}) = {} < 0 (P ≥ 0 fails)",
                    p.name,
                    w.render(),
                    v.render()
                ),
            ));
        }
        let expected = u0(&w) - u_after(&w);
        if p.slope(&w) != expected {
            return Err(Violation::new(
                id,
                format!(
                    "{}: ∂_w P({}) = {} but −[U]_{{t*}} = U⁰ − U(t*⁺) = {} (∂_t U + ∂_w P = 0 fails)",
                    p.name,
                    w.render(),
                    p.slope(&w).render(),
                    expected.render()
                ),
            ));
        }
    }
    let half = q(1, 2);
    if (p.left)(&half) != (p.right)(&half) {
        return Err(Violation::new(
            id,
            format!(
                "{}: P jumps at w = 1/2 (left limit {}, right value {}): ∂_w P has a Dirac mass there",
                p.name,
                (p.left)(&half).render(),
                (p.right)(&half).render()
            ),
        ));
    }
    for end in [q(0, 1), q(1, 1)] {
        if !p.value(&end).is_zero() {
            return Err(Violation::new(
                id,
                format!(
                    "{}: P({}) = {} ≠ 0",
                    p.name,
                    end.render(),
                    p.value(&end).render()
                ),
            ));
        }
    }
    Ok(())
}

fn zero(_: &BigRational) -> BigRational {
    q(0, 1)
}

/// `app:uniqueness#sticky-pressure`, as printed:
/// `P¹ = [w 1_{[0,1/2)} − (1 − w) 1_{[1/2,1]}] δ_{t = t*}` with `U¹ = 0`.
pub fn sticky_pressure_printed() -> R {
    check_weight(
        "app:uniqueness#sticky-pressure",
        &Weight {
            name: "P¹ as printed",
            left: |w| w.clone(),
            right: |w| -(q(1, 1) - w),
            left_slope: |_| q(1, 1),
            right_slope: |_| q(1, 1),
        },
        zero,
    )
}

/// Corrected: `P¹ = [w 1_{[0,1/2)} + (1 − w) 1_{[1/2,1]}] δ_{t = t*}`; and it
/// is the limit of the particles: for the quantile sampling with N = 16 and
/// 64, the jump of `λ_i` at `t*` is exactly `P¹(i/N)`, and after `t*` the
/// particles sit at `X¹(t, i/N) = i/N + η/2` with `U¹ = 0`.
pub fn sticky_pressure_corrected() -> R {
    const ID: &str = "app:uniqueness#sticky-pressure (corrected)";
    let p = Weight {
        name: "P¹ corrected",
        left: |w| w.clone(),
        right: |w| q(1, 1) - w,
        left_slope: |_| q(1, 1),
        right_slope: |_| q(-1, 1),
    };
    check_weight(ID, &p, zero)?;
    let text = scene::shipped("appendix-c-two-blocks")
        .ok_or_else(|| Violation::new(ID, "the Appendix C scene is not shipped"))?;
    let sc = scene::parse(text).map_err(|e| Violation::new(ID, e.to_string()))?;
    let scene::SceneKind::Macro { datum, .. } = sc.kind else {
        return Err(Violation::new(
            ID,
            "the Appendix C scene is not a macro scene",
        ));
    };
    let eta = q(1, 4);
    let t_star = eta.clone() / q(2, 1);
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
            if *j != p.value(&w) {
                return Err(Violation::new(
                    ID,
                    format!(
                        "N = {n}: jump of λ_{} = {} ≠ P¹({}) = {}",
                        k + 1,
                        j.render(),
                        w.render(),
                        p.value(&w).render()
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
        &Weight {
            name: "P² as printed",
            left: |w| q(2, 1) * w - w.clone() * w,
            right: |w| -(w.clone() * w - q(1, 1)),
            left_slope: |w| q(2, 1) - q(2, 1) * w,
            right_slope: |w| -(q(2, 1) * w),
        },
        |w| q(2, 1) * w - q(1, 1),
    )
}

/// `app:uniqueness#rebound-oleinik`: `∂_w U² = 2`, `∂_w X²(t, w) = 1 +
/// 2(t − t*)`, and `∂_w U² < ∂_w X² / t` for all `t > t*` when `η < 1`
/// (checked for `η ∈ {1/4, 1/2, 3/4}` at `t = t* + k/8`, `k = 1 … 40`), and
/// `∂_w X² ≥ 1`.
pub fn rebound_oleinik() -> R {
    const ID: &str = "app:uniqueness#rebound-oleinik";
    for eta in [q(1, 4), q(1, 2), q(3, 4)] {
        let t_star = eta.clone() / q(2, 1);
        for k in 1..=40 {
            let t = t_star.clone() + q(k, 8);
            // X²(t, w) = w + η/2 + (t − t*)(2w − 1): slope in w.
            let dx = q(1, 1) + q(2, 1) * &(t.clone() - &t_star);
            let du = q(2, 1);
            if du.clone() >= dx.clone() / &t || dx < q(1, 1) {
                return Err(Violation::new(
                    ID,
                    format!(
                        "η = {}, t = {}: ∂_w U² = 2, ∂_w X²/t = {}",
                        eta.render(),
                        t.render(),
                        (dx / t).render()
                    ),
                ));
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
        let t_star = eta.clone() / q(2, 1);
        for w in grid() {
            let x0 = if w < q(1, 2) {
                w.clone()
            } else {
                w.clone() + &eta
            };
            let xf = x0 + &(t_star.clone() * u0(&w));
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
