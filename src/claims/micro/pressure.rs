//! The pressure (`prop:micro-pressure`): the atoms `p_i` at collisions,
//! their sign and complementarity, and `∫_0^t λ`.

use super::{render_vec, state, R};
use crate::claims::{Case, Violation};
use crate::contact::Impulse;
use crate::scalar::Scalar;
use crate::trajectory::Trajectory;

/// `prop:micro-pressure`: `p_i = dλ_i/dt ≥ 0` and
/// `(x_{i+1} − x_i − 2r) p_i = 0`: every jump of `λ_i` is `≥ 0` and happens
/// on a pair in contact at that instant; and `λ(t)` is the sum of the jumps
/// up to `t` (so `p` is exactly this sum of Dirac masses). With more than 40
/// collisions, a spread of 40 is checked one by one.
pub fn micro_pressure<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "prop:micro-pressure";
    let two_r = case.data().two_r();
    for imp in case.impulse_spread() {
        pressure_sign(imp)?;
        let s = state(case, &imp.t, ID)?;
        for (k, j) in imp.jumps().iter().enumerate() {
            let i = imp.cluster.first + k;
            let slack = s.positions[i + 1].clone() - &s.positions[i] - &two_r;
            if !j.is_zero() && !slack.is_zero() {
                return Err(Violation::new(
                    ID,
                    format!(
                        "λ[{i}] jumps by {} at t = {} but x[{}] − x[{i}] − 2r = {}",
                        j.render(),
                        imp.t.render(),
                        i + 1,
                        slack.render()
                    ),
                ));
            }
        }
    }
    // λ(t) = Σ of the jumps up to t: checked when materialising every jump
    // stays cheap (Σ of the merged cluster sizes ≤ 20 000).
    if case.jump_work() > 20_000 {
        return Ok(());
    }
    for t in &case.times {
        let s = state(case, t, ID)?;
        let mut acc = vec![S::zero(); case.n().saturating_sub(1)];
        for imp in case.traj.impulses().iter().filter(|i| i.t <= *t) {
            for (k, j) in imp.jumps().into_iter().enumerate() {
                let i = imp.cluster.first + k;
                acc[i] = acc[i].clone() + &j;
            }
        }
        if acc != s.multipliers {
            return Err(Violation::new(
                ID,
                format!(
                    "t = {}: Σ jumps = {} but λ(t) = {}",
                    t.render(),
                    render_vec(&acc),
                    render_vec(&s.multipliers)
                ),
            ));
        }
    }
    Ok(())
}

/// `prop:micro-pressure` for one impulse: every jump of `λ` is `≥ 0`.
pub fn pressure_sign<S: Scalar>(imp: &Impulse<S>) -> R {
    const ID: &str = "prop:micro-pressure";
    for (k, j) in imp.jumps().iter().enumerate() {
        if j.total_cmp(&S::zero()).is_lt() {
            return Err(Violation::new(
                ID,
                format!(
                    "λ[{}] jumps by {} < 0 at t = {}",
                    imp.cluster.first + k,
                    j.render(),
                    imp.t.render()
                ),
            ));
        }
    }
    Ok(())
}

/// `∫_0^t λ(s) ds`, exactly: `λ` is piecewise constant, with the jumps of
/// the impulses.
pub fn lambda_integral<S: Scalar>(traj: &Trajectory<S>, t: &S) -> Vec<S> {
    let mut acc = vec![S::zero(); traj.data().n().saturating_sub(1)];
    for imp in traj.impulses().iter().filter(|i| i.t <= *t) {
        let dt = t.clone() - &imp.t;
        for (k, j) in imp.jumps().into_iter().enumerate() {
            let i = imp.cluster.first + k;
            acc[i] = acc[i].clone() + &(j * &dt);
        }
    }
    acc
}
