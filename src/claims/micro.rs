//! Claims of section 2 (microscopic dynamics) checked on one trajectory.

use super::Violation;
use crate::cluster::Cluster;
use crate::contact::{multipliers, Impulse};
use crate::initial::InitialData;
use crate::projection::state_at;
use crate::scalar::Scalar;
use crate::state::State;
use crate::trajectory::Trajectory;

/// `prop:proj-micro` (`eq:proj-micro-x`, `eq:proj-u-micro`): the event-driven
/// sticky history equals the projection formula at time `t` — positions,
/// right-derivative velocities, multipliers and contact clusters, exactly.
/// Returns the (common) state.
pub fn projection_formula<S: Scalar>(traj: &Trajectory<S>, t: &S) -> Result<State<S>, Violation> {
    const ID: &str = "prop:proj-micro";
    let events = traj
        .at(t)
        .map_err(|e| Violation::new(ID, format!("event engine refused t = {}: {e}", t.render())))?;
    let proj = state_at(traj.data(), t)
        .map_err(|e| Violation::new(ID, format!("projection refused t = {}: {e}", t.render())))?;
    if events == proj {
        return Ok(proj);
    }
    let field = if events.positions != proj.positions {
        "positions"
    } else if events.velocities != proj.velocities {
        "velocities"
    } else if events.clusters != proj.clusters {
        "clusters"
    } else {
        "multipliers"
    };
    Err(Violation::new(
        ID,
        format!(
            "at t = {}: {field} differ: event-driven {:?} vs projection {:?}",
            t.render(),
            render_state(&events),
            render_state(&proj)
        ),
    ))
}

fn render_state<S: Scalar>(s: &State<S>) -> String {
    let r = |v: &[S]| v.iter().map(|x| x.render()).collect::<Vec<_>>().join(", ");
    format!(
        "x = [{}], u = [{}], λ = [{}], clusters = {:?}",
        r(&s.positions),
        r(&s.velocities),
        r(&s.multipliers),
        s.clusters
            .iter()
            .map(|c: &Cluster| (c.first, c.size))
            .collect::<Vec<_>>()
    )
}

/// `eq:dyn-micro`: `λ_0 = λ_N = 0`, `λ_i ≥ 0` and
/// `λ_i (x_{i+1} − x_i − 2r) = 0` for the state `s` of the data `data`.
pub fn multiplier_signs<S: Scalar>(data: &InitialData<S>, s: &State<S>) -> Result<(), Violation> {
    const ID: &str = "eq:dyn-micro";
    let (lambda, lambda_n) = multipliers(data.velocities(), &s.velocities);
    if !lambda_n.is_zero() {
        return Err(Violation::new(
            ID,
            format!("λ_N = {} ≠ 0 at t = {}", lambda_n.render(), s.t.render()),
        ));
    }
    let two_r = data.two_r();
    for (i, l) in lambda.iter().enumerate() {
        if l.total_cmp(&S::zero()).is_lt() {
            return Err(Violation::new(
                ID,
                format!("λ_{} = {} < 0 at t = {}", i + 1, l.render(), s.t.render()),
            ));
        }
        let slack = s.positions[i + 1].clone() - &s.positions[i] - &two_r;
        if !l.is_zero() && !slack.is_zero() {
            return Err(Violation::new(
                ID,
                format!(
                    "λ_{} = {} > 0 but x_{} − x_{} − 2r = {} ≠ 0 at t = {}",
                    i + 1,
                    l.render(),
                    i + 2,
                    i + 1,
                    slack.render(),
                    s.t.render()
                ),
            ));
        }
    }
    Ok(())
}

/// `prop:micro-pressure`: `p_i = dλ_i/dt ≥ 0`, i.e. every jump of `λ_i` at a
/// collision is non-negative.
pub fn pressure_sign<S: Scalar>(imp: &Impulse<S>) -> Result<(), Violation> {
    const ID: &str = "prop:micro-pressure";
    for (k, j) in imp.jumps().iter().enumerate() {
        if j.total_cmp(&S::zero()).is_lt() {
            return Err(Violation::new(
                ID,
                format!(
                    "λ_{} jumps by {} < 0 at t = {}",
                    imp.cluster.first + k + 1,
                    j.render(),
                    imp.t.render()
                ),
            ));
        }
    }
    Ok(())
}

/// The times at which a trajectory is worth checking: 0, the distinct
/// collision times, the midpoint of every pair of consecutive collision
/// times, and a time after the last collision. With `limit = Some(k)`, only
/// `k` collision instants spread evenly over the history (always including
/// the first and the last) and their midpoints are kept.
pub fn probe_times<S: Scalar>(traj: &Trajectory<S>, limit: Option<usize>) -> Vec<S> {
    let mut instants: Vec<&S> = Vec::new();
    for imp in traj.impulses() {
        if instants.last() != Some(&&imp.t) {
            instants.push(&imp.t);
        }
    }
    let keep: Vec<usize> = match limit {
        Some(k) if instants.len() > k && k >= 2 => {
            let m = instants.len() - 1;
            let mut idx: Vec<usize> = (0..k).map(|j| j * m / (k - 1)).collect();
            idx.dedup();
            idx
        }
        _ => (0..instants.len()).collect(),
    };
    let mut times = vec![S::zero()];
    for &j in &keep {
        let before = if j == 0 {
            S::zero()
        } else {
            instants[j - 1].clone()
        };
        times.push((before + instants[j]) / S::from_i64(2));
        times.push(instants[j].clone());
    }
    let last = instants.last().map_or_else(S::zero, |t| (*t).clone());
    times.push(last + &S::one());
    times
}

/// Runs every section-2 checker of this module on one trajectory at the
/// probe times (all of them, or a spread of `limit` collision instants);
/// returns the number of checks made.
pub fn check_trajectory<S: Scalar>(
    traj: &Trajectory<S>,
    limit: Option<usize>,
) -> Result<usize, Violation> {
    let mut count = 0;
    for t in probe_times(traj, limit) {
        let s = projection_formula(traj, &t)?;
        multiplier_signs(traj.data(), &s)?;
        count += 2;
    }
    for imp in traj.impulses() {
        pressure_sign(imp)?;
        count += 1;
    }
    Ok(count)
}
