//! Claims of section 2 (microscopic dynamics) and Appendix A (KKT), checked
//! on one [`Case`]: statements and the steps of their proofs, literally as
//! printed, with the paper's normalisations (`‖x‖² = (1/N) Σ x_i²`,
//! `⟨x, y⟩ = Σ x_i y_i`).

use super::{Case, Violation};
use crate::cluster::{contact_clusters, project_h, Cluster};
use crate::contact::{kkt_multipliers, multipliers, Impulse};
use crate::initial::{shift, InitialData};
use crate::projection::{project_k, state_at};
use crate::scalar::Scalar;
use crate::state::State;
use crate::trajectory::Trajectory;

type R = Result<(), Violation>;

fn render_vec<S: Scalar>(v: &[S]) -> String {
    format!(
        "[{}]",
        v.iter().map(|x| x.render()).collect::<Vec<_>>().join(", ")
    )
}

fn render_state<S: Scalar>(s: &State<S>) -> String {
    format!(
        "x = {}, u = {}, λ = {}, clusters = {:?}",
        render_vec(&s.positions),
        render_vec(&s.velocities),
        render_vec(&s.multipliers),
        s.clusters
            .iter()
            .map(|c: &Cluster| (c.first, c.size))
            .collect::<Vec<_>>()
    )
}

/// `⟨a, b⟩ = Σ a_i b_i` (the paper's non-rescaled inner product).
pub fn dot<S: Scalar>(a: &[S], b: &[S]) -> S {
    a.iter()
        .zip(b)
        .fold(S::zero(), |acc, (x, y)| acc + &(x.clone() * y))
}

/// `‖a‖² = (1/N) Σ a_i²` (the paper's rescaled norm).
pub fn norm2<S: Scalar>(a: &[S]) -> S {
    dot(a, a) / S::from_usize(a.len().max(1))
}

fn sub<S: Scalar>(a: &[S], b: &[S]) -> Vec<S> {
    a.iter().zip(b).map(|(x, y)| x.clone() - y).collect()
}

/// `y = x⁰ + t u⁰`.
pub fn free_flight<S: Scalar>(data: &InitialData<S>, t: &S) -> Vec<S> {
    data.positions()
        .iter()
        .zip(data.velocities())
        .map(|(x, u)| x.clone() + &(t.clone() * u))
        .collect()
}

fn state<S: Scalar>(case: &Case<S>, t: &S, id: &'static str) -> Result<State<S>, Violation> {
    state_at(case.data(), t).map_err(|e| Violation::new(id, e.to_string()))
}

fn positive_times<S: Scalar>(case: &Case<S>) -> impl Iterator<Item = &S> {
    case.times
        .iter()
        .filter(|t| t.total_cmp(&S::zero()).is_gt())
}

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
    Err(Violation::new(
        ID,
        format!(
            "at t = {}: event-driven {} vs projection {}",
            t.render(),
            render_state(&events),
            render_state(&proj)
        ),
    ))
}

/// `prop:proj-micro` on every probe time of the case.
pub fn proj_micro<S: Scalar>(case: &Case<S>) -> R {
    for t in &case.times {
        projection_formula(&case.traj, t)?;
    }
    Ok(())
}

/// `df:KN`: `x(t) ∈ K^N` at every probe time.
pub fn admissible<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "df:KN";
    let two_r = case.data().two_r();
    for t in &case.times {
        let s = state(case, t, ID)?;
        for i in 0..s.positions.len().saturating_sub(1) {
            let gap = s.positions[i + 1].clone() - &s.positions[i];
            if gap < two_r {
                return Err(Violation::new(
                    ID,
                    format!(
                        "t = {}: x_{} − x_{} = {} < 2r = {}",
                        t.render(),
                        i + 2,
                        i + 1,
                        gap.render(),
                        two_r.render()
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// `prop:proj-micro#u-in-H`: `u(t) ∈ H_{x(t)}` for (almost every) `t > 0`.
pub fn u_in_h<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "prop:proj-micro#u-in-H";
    let two_r = case.data().two_r();
    for t in positive_times(case) {
        let s = state(case, t, ID)?;
        if let Some(j) = crate::cluster::h_violation(&s.positions, &s.velocities, &two_r) {
            return Err(Violation::new(
                ID,
                format!(
                    "t = {}: particles {} and {} touch but u = {} ≠ {}",
                    t.render(),
                    j + 1,
                    j + 2,
                    s.velocities[j].render(),
                    s.velocities[j + 1].render()
                ),
            ));
        }
    }
    Ok(())
}

/// `eq:proj-micro-u`: `u(t) = P_{H_{x(t)}}(u⁰)` (cluster means) for `t > 0`.
pub fn u_projection<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "eq:proj-micro-u";
    let two_r = case.data().two_r();
    for t in positive_times(case) {
        let s = state(case, t, ID)?;
        let expected = project_h(
            case.data().velocities(),
            &contact_clusters(&s.positions, &two_r),
        );
        if expected != s.velocities {
            return Err(Violation::new(
                ID,
                format!(
                    "t = {}: u(t) = {} but P_H(u⁰) = {}",
                    t.render(),
                    render_vec(&s.velocities),
                    render_vec(&expected)
                ),
            ));
        }
    }
    Ok(())
}

/// `eq:proj-u-micro`, read literally: with `Ω` split into runs of pair
/// indices `J_k = ⟦j_k, j_k + L_k⟧`, `u_i = u⁰_i` if `i ∉ Ω` and
/// `u_i = (1/L_k) Σ_{l=1}^{L_k} u⁰_{j_k + l}` if `i ∈ J_k`.
pub fn proj_u_micro_literal<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "eq:proj-u-micro";
    let two_r = case.data().two_r();
    let u0 = case.data().velocities();
    for t in positive_times(case) {
        let s = state(case, t, ID)?;
        let omega = crate::cluster::contact_set(&s.positions, &two_r); // 0-based pairs
                                                                       // Runs of consecutive pair indices, 1-based as in the paper.
        let runs = crate::cluster::runs(omega.len(), |k| omega[k + 1] == omega[k] + 1);
        for i in 1..=s.positions.len() {
            let run = runs
                .iter()
                .find(|r| omega[r.first] < i && i <= omega[r.end() - 1] + 1);
            let printed = match run {
                None => u0[i - 1].clone(),
                Some(r) => {
                    let j_k = omega[r.first] + 1;
                    let l_k = r.size - 1;
                    if l_k == 0 {
                        return Err(Violation::new(
                            ID,
                            format!(
                                "t = {}: particle {i} is in J_k = ⟦{j_k}, {j_k}⟧, L_k = 0: the printed mean (1/L_k) Σ_{{l=1}}^{{L_k}} is 0/0, while u_{i}(t) = {}",
                                t.render(),
                                s.velocities[i - 1].render()
                            ),
                        ));
                    }
                    let sum = (1..=l_k).fold(S::zero(), |a, l| a + &u0[j_k + l - 1]);
                    sum / S::from_usize(l_k)
                }
            };
            if printed != s.velocities[i - 1] {
                return Err(Violation::new(
                    ID,
                    format!(
                        "t = {}: printed formula gives u_{i} = {} but u_{i}(t) = {}",
                        t.render(),
                        printed.render(),
                        s.velocities[i - 1].render()
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// Indicator vectors of the contact clusters of `x`: a basis of `H_x`.
fn h_basis<S: Scalar>(x: &[S], two_r: &S) -> Vec<Vec<S>> {
    contact_clusters(x, two_r)
        .into_iter()
        .map(|c| {
            (0..x.len())
                .map(|i| {
                    if c.range().contains(&i) {
                        S::one()
                    } else {
                        S::zero()
                    }
                })
                .collect()
        })
        .collect()
}

fn orthogonal_to_h<S: Scalar>(case: &Case<S>, id: &'static str, subtract_x: bool) -> R {
    let two_r = case.data().two_r();
    for t in &case.times {
        let s = state(case, t, id)?;
        let mut v = free_flight(case.data(), t);
        if subtract_x {
            v = sub(&v, &s.positions);
        }
        for w in h_basis(&s.positions, &two_r) {
            let d = dot(&v, &w);
            if !d.is_zero() {
                let first = w.iter().position(|x| !x.is_zero()).unwrap_or(0);
                let size = w.iter().filter(|x| !x.is_zero()).count();
                return Err(Violation::new(
                    id,
                    format!(
                        "t = {}: w = indicator of the cluster of particles {}..{} ∈ H_x(t), ⟨{}, w⟩ = {} ≠ 0",
                        t.render(),
                        first + 1,
                        first + size,
                        if subtract_x { "x⁰ + t u⁰ − x(t)" } else { "x⁰ + t u⁰" },
                        d.render()
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// `lem:incl-HSN`: `H_{x(t)} ⊂ [x⁰ + t u⁰ − x(t)]^⊥` (checked on a basis of
/// `H`; the inclusion in the tangent cone is immediate).
pub fn incl_hsn<S: Scalar>(case: &Case<S>) -> R {
    orthogonal_to_h(case, "lem:incl-HSN", true)
}

/// `lem:incl-HSN#proof-second-inclusion`: the proof announces
/// "H_{x̃(t)} ⊂ [x⁰ + t u⁰]^⊥".
pub fn incl_hsn_printed<S: Scalar>(case: &Case<S>) -> R {
    orthogonal_to_h(case, "lem:incl-HSN#proof-second-inclusion", false)
}

/// `eq:w-Hs-perp`: `⟨x⁰ + t u⁰, w⟩ = 0` for `w ∈ H_{x(t)}`, as printed.
pub fn w_hs_perp<S: Scalar>(case: &Case<S>) -> R {
    orthogonal_to_h(case, "eq:w-Hs-perp", false)
}

/// `prop:proj-velo-micro#step1`: `⟨u⁰ − u(t), u(t)⟩ ≥ 0`.
pub fn velo_step1<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "prop:proj-velo-micro#step1";
    for t in &case.times {
        let s = state(case, t, ID)?;
        let d = dot(&sub(case.data().velocities(), &s.velocities), &s.velocities);
        if d < S::zero() {
            return Err(Violation::new(
                ID,
                format!("t = {}: ⟨u⁰ − u, u⟩ = {} < 0", t.render(), d.render()),
            ));
        }
    }
    Ok(())
}

/// `eq:ineg-projortho`: `⟨u⁰ − u(t), y − x(t)⟩ ≤ 0` for all `y ∈ K^N`,
/// checked exactly on the generators of the tangent cone `T_{x(t)}K`:
/// `±(1, …, 1)`, `±s_j` for pairs not in contact and `s_j` for contacts,
/// where `s_j = Σ_{k > j} e_k`.
pub fn ineg_projortho<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "eq:ineg-projortho";
    let two_r = case.data().two_r();
    for t in &case.times {
        let s = state(case, t, ID)?;
        let g = sub(case.data().velocities(), &s.velocities);
        let total = g.iter().fold(S::zero(), |a, x| a + x);
        if !total.is_zero() {
            return Err(Violation::new(
                ID,
                format!("t = {}: ⟨u⁰ − u, ±1⟩ = ±{} ≠ 0", t.render(), total.render()),
            ));
        }
        let mut tail = total; // Σ_{k > j} g_k, for j = 0 first
        for j in 0..g.len().saturating_sub(1) {
            tail = tail - &g[j];
            let contact = s.positions[j + 1].clone() - &s.positions[j] == two_r;
            let bad = if contact {
                tail > S::zero()
            } else {
                !tail.is_zero()
            };
            if bad {
                return Err(Violation::new(
                    ID,
                    format!(
                        "t = {}: ⟨u⁰ − u, s_{}⟩ = {} with particles {} and {} {}",
                        t.render(),
                        j + 1,
                        tail.render(),
                        j + 1,
                        j + 2,
                        if contact { "in contact" } else { "apart" }
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// `prop:proj-micro#orthogonality`: `⟨u(t) − u⁰, x̃(t)⟩ = 0` (proof of
/// `prop:proj-micro`, "Definition and properties of the multipliers").
pub fn orthogonality<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "prop:proj-micro#orthogonality";
    let two_r = case.data().two_r();
    for t in &case.times {
        let s = state(case, t, ID)?;
        let d = dot(
            &sub(&s.velocities, case.data().velocities()),
            &shift(&s.positions, &two_r),
        );
        if !d.is_zero() {
            return Err(Violation::new(
                ID,
                format!("t = {}: ⟨u − u⁰, x̃⟩ = {} ≠ 0", t.render(), d.render()),
            ));
        }
    }
    Ok(())
}

/// `eq:dyn-micro`: `λ_0 = λ_N = 0`, `λ_i ≥ 0` and
/// `λ_i (x_{i+1} − x_i − 2r) = 0` for the state `s` of the data `data`.
pub fn multiplier_signs<S: Scalar>(data: &InitialData<S>, s: &State<S>) -> R {
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

/// `eq:dyn-micro` at every probe time.
pub fn dyn_micro<S: Scalar>(case: &Case<S>) -> R {
    for t in &case.times {
        let s = state(case, t, "eq:dyn-micro")?;
        multiplier_signs(case.data(), &s)?;
    }
    Ok(())
}

/// `prop:bound-micro#position-contraction`: `‖x(t)‖ ≤ ‖x⁰ + t u⁰‖`.
pub fn position_contraction<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "prop:bound-micro#position-contraction";
    for t in &case.times {
        let s = state(case, t, ID)?;
        let y = free_flight(case.data(), t);
        let (lhs, rhs) = (norm2(&s.positions), norm2(&y));
        if lhs > rhs {
            return Err(Violation::new(
                ID,
                format!(
                    "t = {}: ‖x(t)‖² = {} > ‖x⁰ + t u⁰‖² = {} (x⁰ + t u⁰ = {}, x(t) = {})",
                    t.render(),
                    lhs.render(),
                    rhs.render(),
                    render_vec(&y),
                    render_vec(&s.positions)
                ),
            ));
        }
    }
    Ok(())
}

/// Correction of `prop:bound-micro#position-contraction`: `P_K` is
/// non-expansive, so `‖x(t) − P_K(0)‖ ≤ ‖x⁰ + t u⁰ − P_K(0)‖`, and
/// `‖P_K(0)‖² = (2r)²(N² − 1)/12` (independent of N when `2r = 1/N`).
pub fn position_nonexpansive<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "prop:bound-micro#position-contraction (corrected)";
    let two_r = case.data().two_r();
    let n = case.n();
    let p0 = project_k(&vec![S::zero(); n], &two_r);
    let expected = two_r.clone() * &two_r * S::from_usize(n * n - 1) / S::from_i64(12);
    if norm2(&p0) != expected {
        return Err(Violation::new(
            ID,
            format!(
                "‖P_K(0)‖² = {} ≠ (2r)²(N²−1)/12 = {}",
                norm2(&p0).render(),
                expected.render()
            ),
        ));
    }
    for t in &case.times {
        let s = state(case, t, ID)?;
        let y = free_flight(case.data(), t);
        let (lhs, rhs) = (norm2(&sub(&s.positions, &p0)), norm2(&sub(&y, &p0)));
        if lhs > rhs {
            return Err(Violation::new(
                ID,
                format!(
                    "t = {}: ‖x − P_K(0)‖² = {} > {}",
                    t.render(),
                    lhs.render(),
                    rhs.render()
                ),
            ));
        }
    }
    Ok(())
}

/// `prop:bound-micro#velocity-bound`: `‖u(t)‖ ≤ ‖u⁰‖`.
pub fn velocity_bound<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "prop:bound-micro#velocity-bound";
    let rhs = norm2(case.data().velocities());
    for t in &case.times {
        let s = state(case, t, ID)?;
        let lhs = norm2(&s.velocities);
        if lhs > rhs {
            return Err(Violation::new(
                ID,
                format!(
                    "t = {}: ‖u‖² = {} > ‖u⁰‖² = {}",
                    t.render(),
                    lhs.render(),
                    rhs.render()
                ),
            ));
        }
    }
    Ok(())
}

/// `(λ_1 − λ_0, …, λ_N − λ_{N−1})` and `L = (λ_1, …, λ_N)` at state `s`.
fn delta_l<S: Scalar>(data: &InitialData<S>, s: &State<S>) -> (Vec<S>, Vec<S>) {
    let (mut l, ln) = multipliers(data.velocities(), &s.velocities);
    l.push(ln);
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
        let (dl, _) = delta_l(case.data(), &s);
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
        let (dl, l) = delta_l(case.data(), &s);
        let bound = n.clone() * &n * norm2(&dl);
        for (i, li) in l.iter().enumerate() {
            if li.clone() * li > bound {
                return Err(Violation::new(
                    ID,
                    format!(
                        "t = {}: λ_{}² = {} > N²‖ΔL‖² = {}",
                        t.render(),
                        i + 1,
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
    const ID: &str = "prop:bound-micro#multiplier-relation";
    let n = S::from_usize(case.n());
    for t in &case.times {
        let s = state(case, t, ID)?;
        let (dl, _) = delta_l(case.data(), &s);
        for i in 0..case.n() {
            let lhs = n.clone() * &dl[i];
            let rhs = s.velocities[i].clone() - &case.data().velocities()[i];
            if lhs != rhs {
                return Err(Violation::new(
                    ID,
                    format!(
                        "t = {}, i = {}: N(λ_i − λ_{{i−1}}) = {} but u_i − u⁰_i = {}",
                        t.render(),
                        i + 1,
                        lhs.render(),
                        rhs.render()
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// The relation with the sign of `eq:dyn-micro`:
/// `N(λ_i − λ_{i−1}) = u⁰_i − u_i`.
pub fn multiplier_relation_corrected<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "prop:bound-micro#multiplier-relation (corrected)";
    let n = S::from_usize(case.n());
    for t in &case.times {
        let s = state(case, t, ID)?;
        let (dl, _) = delta_l(case.data(), &s);
        for i in 0..case.n() {
            let lhs = n.clone() * &dl[i];
            let rhs = case.data().velocities()[i].clone() - &s.velocities[i];
            if lhs != rhs {
                return Err(Violation::new(
                    ID,
                    format!(
                        "t = {}, i = {}: {} ≠ {}",
                        t.render(),
                        i + 1,
                        lhs.render(),
                        rhs.render()
                    ),
                ));
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
        let (dl, _) = delta_l(case.data(), &s);
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

/// `prop:Oleinik` (`eq:Oleinik-micro`): `(u_i − u_{i−1})/(x_i − x_{i−1}) < 1/t`
/// for `t > 0` and `i = 2 … N`, i.e. `t(u_i − u_{i−1}) < x_i − x_{i−1}`.
pub fn oleinik<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "prop:Oleinik";
    for t in positive_times(case) {
        let s = state(case, t, ID)?;
        for i in 1..case.n() {
            let lhs = t.clone() * &(s.velocities[i].clone() - &s.velocities[i - 1]);
            let rhs = s.positions[i].clone() - &s.positions[i - 1];
            if lhs >= rhs {
                return Err(Violation::new(
                    ID,
                    format!(
                        "t = {}, i = {}: t(u_i − u_{{i−1}}) = {} ≥ x_i − x_{{i−1}} = {}",
                        t.render(),
                        i + 1,
                        lhs.render(),
                        rhs.render()
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// `prop:Oleinik#backward-characteristics`: if particles `i−1` and `i` are
/// not in contact at `t`, then `x_{i−1}(t) − t u_{i−1}(t) ≤ x_{i−1}(0)` and
/// `x_i(t) − t u_i(t) ≥ x_i(0)`.
pub fn oleinik_characteristics<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "prop:Oleinik#backward-characteristics";
    let two_r = case.data().two_r();
    let x0 = case.data().positions();
    for t in positive_times(case) {
        let s = state(case, t, ID)?;
        for i in 1..case.n() {
            if s.positions[i].clone() - &s.positions[i - 1] == two_r {
                continue;
            }
            let xl = s.positions[i - 1].clone() - &(t.clone() * &s.velocities[i - 1]);
            let xr = s.positions[i].clone() - &(t.clone() * &s.velocities[i]);
            if xl > x0[i - 1] || xr < x0[i] {
                return Err(Violation::new(
                    ID,
                    format!(
                        "t = {}, i = {}: x_ℓ = {} (x_{{i−1}}(0) = {}), x_r = {} (x_i(0) = {})",
                        t.render(),
                        i + 1,
                        xl.render(),
                        x0[i - 1].render(),
                        xr.render(),
                        x0[i].render()
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// `eq:semigroup` and `eq:projortho-sg`: for probe times `s < t`,
/// `x(t) = P_K(x(s) + (t − s)u(s))` and `u(t) = P_{H_{x(t)}}(u(s))`.
fn semigroup_both<S: Scalar>(case: &Case<S>, check_x: bool) -> R {
    let id = if check_x {
        "eq:semigroup"
    } else {
        "eq:projortho-sg"
    };
    let two_r = case.data().two_r();
    let states: Vec<State<S>> = case
        .times
        .iter()
        .map(|t| state(case, t, id))
        .collect::<Result<_, _>>()?;
    for (a, s) in states.iter().enumerate() {
        for st in &states[a + 1..] {
            if st.t <= s.t {
                continue;
            }
            let dt = st.t.clone() - &s.t;
            if check_x {
                let y: Vec<S> = s
                    .positions
                    .iter()
                    .zip(&s.velocities)
                    .map(|(x, u)| x.clone() + &(dt.clone() * u))
                    .collect();
                let x = project_k(&y, &two_r);
                if x != st.positions {
                    return Err(Violation::new(
                        id,
                        format!(
                            "s = {}, t = {}: P_K(x(s) + (t−s)u(s)) = {} but x(t) = {}",
                            s.t.render(),
                            st.t.render(),
                            render_vec(&x),
                            render_vec(&st.positions)
                        ),
                    ));
                }
            } else {
                let u = project_h(&s.velocities, &contact_clusters(&st.positions, &two_r));
                if u != st.velocities {
                    return Err(Violation::new(
                        id,
                        format!(
                            "s = {}, t = {}: P_H(u(s)) = {} but u(t) = {}",
                            s.t.render(),
                            st.t.render(),
                            render_vec(&u),
                            render_vec(&st.velocities)
                        ),
                    ));
                }
            }
        }
    }
    Ok(())
}

/// `eq:semigroup`.
pub fn semigroup<S: Scalar>(case: &Case<S>) -> R {
    semigroup_both(case, true)
}

/// `eq:projortho-sg`.
pub fn projortho_sg<S: Scalar>(case: &Case<S>) -> R {
    semigroup_both(case, false)
}

fn contacts_grow<S: Scalar>(case: &Case<S>, id: &'static str, from_zero: bool) -> R {
    let two_r = case.data().two_r();
    let h0 = crate::cluster::h_violation(case.data().positions(), case.data().velocities(), &two_r)
        .is_none();
    let times: Vec<&S> = case
        .times
        .iter()
        .filter(|t| from_zero || t.total_cmp(&S::zero()).is_gt() || h0)
        .collect();
    let mut prev: Option<(&S, Vec<usize>)> = None;
    for t in times {
        let s = state(case, t, id)?;
        let omega = crate::cluster::contact_set(&s.positions, &two_r);
        if let Some((ps, pomega)) = &prev {
            if let Some(j) = pomega.iter().find(|j| !omega.contains(j)) {
                return Err(Violation::new(
                    id,
                    format!(
                        "particles {} and {} are in contact at s = {} but not at t = {} (u⁰ ∈ C_x⁰ \\ H_x⁰: u⁰_{} = {} < u⁰_{} = {})",
                        j + 1,
                        j + 2,
                        ps.render(),
                        t.render(),
                        j + 1,
                        case.data().velocities()[*j].render(),
                        j + 2,
                        case.data().velocities()[j + 1].render()
                    ),
                ));
            }
        }
        prev = Some((t, omega));
    }
    Ok(())
}

/// `df:H-micro#contacts-grow`: "the set of active constraints is
/// non-decreasing in time … N_{x(s)}K ⊂ N_{x(t)}K for all s ≤ t" (stated
/// for data `x⁰ ∈ K`, `u⁰ ∈ C_{x⁰}`).
pub fn contacts_grow_printed<S: Scalar>(case: &Case<S>) -> R {
    contacts_grow(case, "df:H-micro#contacts-grow", true)
}

/// Corrected: `Ω_{x(s)} ⊂ Ω_{x(t)}` for `0 < s ≤ t`, and from `s = 0` when
/// `u⁰ ∈ H_{x⁰}`.
pub fn contacts_grow_corrected<S: Scalar>(case: &Case<S>) -> R {
    contacts_grow(case, "df:H-micro#contacts-grow (corrected)", false)
}

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
                        "λ_{} jumps by {} at t = {} but x_{} − x_{} − 2r = {}",
                        i + 1,
                        j.render(),
                        imp.t.render(),
                        i + 2,
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

/// `app:KKT`, as printed: "the KKT conditions apply and yield the existence
/// of multipliers λ_i(t) ≥ 0 such that x(t) − (x⁰ + t u⁰) + N Σ λ_i(t)(e_i −
/// e_{i+1}) = 0 … This provides directly the multipliers … introduced in the
/// main text" — checked with the `λ` of `eq:dyn-micro`.
pub fn kkt_printed<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "app:KKT";
    for t in &case.times {
        let s = state(case, t, ID)?;
        let y = free_flight(case.data(), t);
        let (mu, _) = kkt_multipliers(&y, &s.positions);
        if mu != s.multipliers {
            return Err(Violation::new(
                ID,
                format!(
                    "t = {}: the stationarity condition needs multipliers {} but eq:dyn-micro's λ(t) = {}",
                    t.render(),
                    render_vec(&mu),
                    render_vec(&s.multipliers)
                ),
            ));
        }
    }
    Ok(())
}

/// Corrected `app:KKT`: the KKT multipliers `μ(t)` of the position
/// projection satisfy stationarity, `μ ≥ 0`, `μ_N = 0`, complementarity, and
/// `μ(t) = ∫_0^t λ(s) ds`.
pub fn kkt_corrected<S: Scalar>(case: &Case<S>) -> R {
    const ID: &str = "app:KKT (corrected)";
    let two_r = case.data().two_r();
    for t in &case.times {
        let s = state(case, t, ID)?;
        let y = free_flight(case.data(), t);
        let (mu, mu_n) = kkt_multipliers(&y, &s.positions);
        let integral = lambda_integral(&case.traj, t);
        if mu != integral || !mu_n.is_zero() {
            return Err(Violation::new(
                ID,
                format!(
                    "t = {}: μ = {} (μ_N = {}) but ∫λ = {}",
                    t.render(),
                    render_vec(&mu),
                    mu_n.render(),
                    render_vec(&integral)
                ),
            ));
        }
        for (i, m) in mu.iter().enumerate() {
            let slack = s.positions[i + 1].clone() - &s.positions[i] - &two_r;
            if *m < S::zero() || (!m.is_zero() && !slack.is_zero()) {
                return Err(Violation::new(
                    ID,
                    format!(
                        "t = {}: μ_{} = {}, slack {}",
                        t.render(),
                        i + 1,
                        m.render(),
                        slack.render()
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// `prop:proj-micro#uniqueness-identity`: for two solutions with the same
/// `u⁰`, "(N²/2) d/dt ‖x¹ − x²‖² = −⟨ξ¹ − ξ², x¹ − x²⟩". The second solution
/// starts from `x⁰ + (0, r, 2r, …)` (still in `K`); derivatives are right
/// derivatives at the probe times.
pub fn uniqueness_identity_printed<S: Scalar>(case: &Case<S>) -> R {
    uniqueness(case, "prop:proj-micro#uniqueness-identity", false)
}

/// Corrected: `(N/2) d/dt ‖x¹ − x²‖² = −⟨ξ¹ − ξ², x¹ − x²⟩ ≤ 0`
/// (monotonicity of `∂I_K`).
pub fn uniqueness_identity_corrected<S: Scalar>(case: &Case<S>) -> R {
    uniqueness(
        case,
        "prop:proj-micro#uniqueness-identity (corrected)",
        true,
    )
}

fn uniqueness<S: Scalar>(case: &Case<S>, id: &'static str, corrected: bool) -> R {
    let data = case.data();
    let r = data.radius().clone();
    let mut off = S::zero();
    let x2: Vec<S> = data
        .positions()
        .iter()
        .map(|x| {
            let v = x.clone() + &off;
            off = off.clone() + &r;
            v
        })
        .collect();
    let other = InitialData::new(r, x2, data.velocities().to_vec())
        .map_err(|e| Violation::new(id, format!("second datum: {e}")))?;
    let n = S::from_usize(case.n());
    for t in &case.times {
        let s1 = state(case, t, id)?;
        let s2 = state_at(&other, t).map_err(|e| Violation::new(id, e.to_string()))?;
        let d = sub(&s1.positions, &s2.positions);
        let dd = sub(&s1.velocities, &s2.velocities);
        // ξ^a = u⁰ − u^a, so −⟨ξ¹ − ξ², d⟩ = ⟨u¹ − u², d⟩.
        let rhs = dot(&dd, &d);
        // d/dt ‖d‖² = (2/N)⟨d', d⟩.
        let deriv = S::from_i64(2) / &n * &rhs;
        let factor = if corrected { n.clone() } else { n.clone() * &n };
        let lhs = factor / S::from_i64(2) * &deriv;
        if lhs != rhs || (corrected && rhs > S::zero()) {
            return Err(Violation::new(
                id,
                format!(
                    "t = {}: {} d/dt‖x¹−x²‖² = {} but −⟨ξ¹−ξ², x¹−x²⟩ = {}",
                    t.render(),
                    if corrected { "(N/2)" } else { "(N²/2)" },
                    lhs.render(),
                    rhs.render()
                ),
            ));
        }
    }
    Ok(())
}

pub use crate::trajectory::probe_times;

/// Runs the core section-2 checkers (`prop:proj-micro`, `eq:dyn-micro`,
/// `prop:micro-pressure`) on one trajectory at the probe times (all of them,
/// or a spread of `limit` collision instants); returns the number of checks
/// made.
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
