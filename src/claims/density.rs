//! `lem:density` (= `lem:density-app`, "Regularity of the Eulerian
//! density"): for `X` non-decreasing with `∂_w X ≥ 1`, the push-forward
//! `ρ(t) = X(t)#L¹_(0,1)` is (i) absolutely continuous in time with values
//! in `P_2(R)` and (ii) has a density `0 ≤ ρ ≤ 1`.
//!
//! * **Particles** ([`density`], per case, `2r = 1/N`): the hypothesis is
//!   met by `X̃_N` (`∂_w X̃_N = N(x_i − x_{i−1}) ≥ 1` on every cell,
//!   artificial particle included); (ii) `ρ̃_N = 1/(N(x_i − x_{i−1}))` on
//!   `(x_{i−1}, x_i)` (read by [`crate::limit::eulerian::particle_density`])
//!   lies in `[0, 1]`, gives each cell the mass `1/N` of its `w`-interval
//!   (so it is the density of `X̃_N#L¹`) and vanishes off `[x_0, x_N]`;
//!   (i) the proof's coupling bound between consecutive probe times `s < t`,
//!   `W_2(ρ̃_N(s), ρ̃_N(t))² ≤ ∫_0^1 |X̃_N(t,w) − X̃_N(s,w)|² dw ≤
//!   (t − s)² ‖∂_t X̃_N‖²_{L^∞((s,t)×(0,1))}`, exactly. In one dimension the
//!   monotone coupling is optimal: `W_2²` is the `L²` distance of the
//!   quantile functions, and the quantile function of `ρ̃_N(t)` is
//!   `X̃_N(t, ·)` itself (non-decreasing, and pushing `L¹` to `ρ̃_N` — the two
//!   facts checked), so the first inequality is the equality
//!   `W_2² = ∫|X̃_N(t) − X̃_N(s)|²` (piecewise affine in `w` on the grid
//!   `i/N`: `(1/N) Σ_i (g_{i−1}² + g_{i−1}g_i + g_i²)/3`, `g_i = x_i(t) − x_i(s)`).
//!   The bound is checked in the proof's steps (`coupling_steps`): each
//!   node's displacement, then each cell's share, then their mean.
//!   `‖∂_t X̃_N‖_∞` on `(s, t)` is `max_i |u_i(τ)|` over `τ = s` and the
//!   collision instants in `(s, t)` (the velocities are constant between
//!   collisions; `∂_t X̃_N` interpolates `u_0 = u_1, u_1, …, u_N`).
//! * **Continuum** ([`density_continuum`]): on the rational profiles of the
//!   18 macroscopic data, `∂_w X ≥ 1` on every segment, and
//!   `ρ = 1/∂_w X ∈ [0, 1]` ([`crate::limit::eulerian::continuum_density`]) on
//!   the image of each segment, 0 in the vacuum between images.

use super::discrete::{abs, delta};
use super::{Case, FromPaper, Violation};
use crate::limit::eulerian::{continuum_density, particle_density};
use crate::limit::interpolation::Snapshot;
use crate::scalar::Scalar;

type R = Result<(), Violation>;

const ID: &str = "lem:density";

fn snapshot<S: Scalar>(case: &Case<S>, t: &S) -> Result<Snapshot<S>, Violation> {
    let s = case
        .state(t)
        .map_err(|e| Violation::new(ID, e.to_string()))?;
    Snapshot::new(&s, case.data().velocities(), delta::<S>())
        .map_err(|e| Violation::new(ID, e.to_string()))
}

/// The hypothesis and item (ii) at one snapshot.
fn density_at<S: Scalar>(snap: &Snapshot<S>) -> Result<(), String> {
    let n = snap.n;
    let inv_n = S::one() / &S::from_usize(n);
    let two = S::from_i64(2);
    for i in 1..=n {
        let slope = snap.dw_x_tilde(i);
        if slope < S::one() {
            return Err(format!(
                "hypothesis: ∂_w X̃_N = N(x[{}] − x[{}]) = {} < 1",
                FromPaper(i),
                FromPaper(i - 1),
                slope.render()
            ));
        }
        let (a, b) = (&snap.x[i - 1], &snap.x[i]);
        let mid = (a.clone() + b) / &two;
        let rho = particle_density(snap, &mid);
        if rho < S::zero() || rho > S::one() {
            return Err(format!(
                "ρ̃_N = {} ∉ [0, 1] on (x[{}], x[{}])",
                rho.render(),
                FromPaper(i - 1),
                FromPaper(i)
            ));
        }
        let mass = rho.clone() * &(b.clone() - a);
        if mass != inv_n {
            return Err(format!(
                "ρ̃_N = {} on (x[{}], x[{}]) gives the cell mass {} ≠ 1/N: not the density of X̃_N#L¹",
                rho.render(),
                FromPaper(i - 1),
                FromPaper(i),
                mass.render()
            ));
        }
    }
    for x in [snap.x[0].clone() - &S::one(), snap.x[n].clone() + &S::one()] {
        let rho = particle_density(snap, &x);
        if !rho.is_zero() {
            return Err(format!(
                "ρ̃_N({}) = {} ≠ 0 off the support [x[−1], x[N−1]]",
                x.render(),
                rho.render()
            ));
        }
    }
    Ok(())
}

/// The displacements `g_i = X̃_N(t, i/N) − X̃_N(s, i/N) = x_i(t) − x_i(s)`
/// of the nodes `i = 0 … N` (the artificial particle first).
fn displacements<S: Scalar>(a: &Snapshot<S>, b: &Snapshot<S>) -> Vec<S> {
    a.x.iter().zip(&b.x).map(|(p, q)| q.clone() - p).collect()
}

/// `N ∫_{cell} |X̃_N(t,w) − X̃_N(s,w)|² dw = (g² + gh + h²)/3` on the cell
/// between nodes with displacements `g`, `h` (the interpolant is affine).
fn cell_cost<S: Scalar>(g: &S, h: &S) -> S {
    (g.clone() * g + &(g.clone() * h) + &(h.clone() * h)) / &S::from_i64(3)
}

/// `∫_0^1 |X̃_N(t,w) − X̃_N(s,w)|² dw` (both affine on each cell).
fn coupling_cost<S: Scalar>(a: &Snapshot<S>, b: &Snapshot<S>) -> S {
    let g = displacements(a, b);
    let sum = g
        .windows(2)
        .fold(S::zero(), |acc, w| acc + &cell_cost(&w[0], &w[1]));
    sum / &S::from_usize(a.n)
}

/// The proof of `lem:density` (i) between `s` and `t`, step by step, with
/// `bound = (t − s)² ‖∂_t X̃_N‖²_∞`: (1) every node moves by at most
/// `(t − s)‖∂_t X̃_N‖_∞` (the Lipschitz step; squares compared); (2) every
/// cell's share `(g² + gh + h²)/3 ≤ bound` (the exact integral of the
/// square of an affine interpolant, times `N`); (3) their mean, the
/// coupling cost, `≤ bound`.
fn coupling_steps<S: Scalar>(a: &Snapshot<S>, b: &Snapshot<S>, bound: &S) -> Result<(), String> {
    let g = displacements(a, b);
    for (i, gi) in g.iter().enumerate() {
        let sq = gi.clone() * gi;
        if sq > *bound {
            return Err(format!(
                "Lipschitz step: |x[{i}](t) − x[{i}](s)|² = {} > (t − s)² ‖∂_t X̃_N‖²_∞ = {}",
                sq.render(),
                bound.render(),
                i = FromPaper(i)
            ));
        }
    }
    for (i, w) in g.windows(2).enumerate() {
        let cell = cell_cost(&w[0], &w[1]);
        if cell > *bound {
            return Err(format!(
                "cell step: on the cell (x[{}], x[{}]), N ∫|X̃_N(t) − X̃_N(s)|² = {} > (t − s)² ‖∂_t X̃_N‖²_∞ = {}",
                FromPaper(i),
                FromPaper(i + 1),
                cell.render(),
                bound.render()
            ));
        }
    }
    let cost = coupling_cost(a, b);
    if cost > *bound {
        return Err(format!(
            "W_2(ρ̃_N(s), ρ̃_N(t))² = ∫|X̃_N(t) − X̃_N(s)|² = {} > (t − s)² ‖∂_t X̃_N‖²_∞ = {}",
            cost.render(),
            bound.render()
        ));
    }
    Ok(())
}

fn sup_speed<S: Scalar>(snap: &Snapshot<S>) -> S {
    snap.u.iter().fold(S::zero(), |m, v| {
        let a = abs(v.clone());
        if a > m {
            a
        } else {
            m
        }
    })
}

/// `lem:density` for the particle interpolation `X̃_N`, at every probe time
/// and between consecutive probe times (see the module documentation).
pub fn density<S: Scalar>(case: &Case<S>) -> R {
    let snaps: Vec<Snapshot<S>> = case
        .times
        .iter()
        .map(|t| snapshot(case, t))
        .collect::<Result<_, _>>()?;
    for snap in &snaps {
        density_at(snap).map_err(|e| {
            Violation::new(ID, format!("t = {}, N = {}: {e}", snap.t.render(), snap.n))
        })?;
    }
    for w in snaps.windows(2) {
        let (a, b) = (&w[0], &w[1]);
        if b.t <= a.t {
            continue;
        }
        // ‖∂_t X̃_N‖_∞ on (s, t): the velocities at s and after every
        // collision instant in (s, t).
        let mut sup = sup_speed(a);
        for imp in case.traj.impulses() {
            if imp.t > a.t && imp.t < b.t {
                let m = sup_speed(&snapshot(case, &imp.t)?);
                if m > sup {
                    sup = m;
                }
            }
        }
        let dt = b.t.clone() - &a.t;
        let bound = dt.clone() * &dt * &sup * &sup;
        coupling_steps(a, b, &bound).map_err(|e| {
            Violation::new(
                ID,
                format!("s = {}, t = {}: {e}", a.t.render(), b.t.render()),
            )
        })?;
    }
    Ok(())
}

/// `lem:density` (ii) for the exact continuum solution: on every rational
/// profile of the macroscopic data, `∂_w X ≥ 1` and `ρ = 1/∂_w X ∈ [0, 1]`
/// on each segment's image, `ρ = 0` in the vacuum between images.
pub fn density_continuum() -> R {
    const CID: &str = "lem:density#continuum";
    let mut checked = 0usize;
    for c in super::macro_data::cases(CID)? {
        for (t, p) in &c.profiles {
            let Some(p) = p else { continue };
            checked += 1;
            density_continuum_profile(&c.name, t, p)?;
        }
    }
    if checked == 0 {
        return Err(Violation::new(
            CID,
            "vacuous: no rational continuum profile",
        ));
    }
    Ok(())
}

/// [`density_continuum`] on one profile at `t` (`tests/claims_selfcheck.rs`
/// runs it on a corrupted profile).
pub fn density_continuum_profile(
    name: &str,
    t: &num_rational::BigRational,
    p: &crate::limit::continuum::Profile<num_rational::BigRational>,
) -> R {
    use num_rational::BigRational as Q;
    const CID: &str = "lem:density#continuum";
    let bad = |what: String| {
        Err(Violation::new(
            CID,
            format!("{name}, t = {}: {what}", t.render()),
        ))
    };
    let ends = |s: &crate::limit::continuum::Segment<Q>| {
        (
            s.x[0].clone() + s.x[1].clone() * &s.w0,
            s.x[0].clone() + s.x[1].clone() * &s.w1,
        )
    };
    for s in &p.segments {
        if s.x[1] < Q::one() {
            return bad(format!(
                "hypothesis: ∂_w X = {} < 1 on [{}, {}]",
                s.x[1].render(),
                s.w0.render(),
                s.w1.render()
            ));
        }
        let (a, b) = ends(s);
        let rho = continuum_density(p, &((a.clone() + &b) / Q::from_i64(2)));
        if rho < Q::zero() || rho > Q::one() {
            return bad(format!(
                "ρ = {} ∉ [0, 1] on ({}, {})",
                rho.render(),
                a.render(),
                b.render()
            ));
        }
        // The image has the mass of its w-interval.
        if rho.clone() * (b.clone() - &a) != s.w1.clone() - &s.w0 {
            return bad(format!(
                "ρ = {} on ({}, {}) is not the density of X(t)#L¹ there",
                rho.render(),
                a.render(),
                b.render()
            ));
        }
    }
    for w in p.segments.windows(2) {
        let (_, b) = ends(&w[0]);
        let (a, _) = ends(&w[1]);
        if a > b {
            let rho = continuum_density(p, &((a.clone() + &b) / Q::from_i64(2)));
            if !rho.is_zero() {
                return bad(format!(
                    "ρ = {} ≠ 0 in the vacuum ({}, {})",
                    rho.render(),
                    b.render(),
                    a.render()
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

    /// N = 2, 2r = 1/2: a head-on collision at t = 1/4.
    fn head_on() -> Case<num_rational::BigRational> {
        let data = InitialData::with_paper_radius(vec![q(0, 1), q(1, 1)], vec![q(1, 1), q(-1, 1)])
            .unwrap();
        Case::new(data, None)
    }

    #[test]
    fn the_particles_pass_and_a_compressed_cell_fails() {
        let case = head_on();
        density(&case).unwrap();
        let mut snap = snapshot(&case, &q(1, 2)).unwrap();
        density_at(&snap).unwrap();
        // Particles closer than 2r = 1/N: ρ̃_N = 2 > 1 (and ∂_w X̃_N < 1).
        snap.x[2] = snap.x[1].clone() + q(1, 4);
        assert!(density_at(&snap).unwrap_err().contains("hypothesis"));
    }

    #[test]
    fn a_displacement_faster_than_the_velocities_fails() {
        let case = head_on();
        let a = snapshot(&case, &q(0, 1)).unwrap();
        let mut b = snapshot(&case, &q(1, 8)).unwrap();
        assert!(coupling_cost(&a, &b) <= q(1, 64) * sup_speed(&a) * sup_speed(&a));
        for x in &mut b.x {
            *x = x.clone() + q(1, 1);
        }
        assert!(coupling_cost(&a, &b) > q(1, 64) * sup_speed(&a) * sup_speed(&a));
    }

    /// The proof's first step fails on a node moved faster than the
    /// velocities allow, with the node's index from 0 (`x[−1]` the
    /// artificial particle).
    #[test]
    fn the_lipschitz_step_names_the_node() {
        let case = head_on();
        let a = snapshot(&case, &q(0, 1)).unwrap();
        let b = snapshot(&case, &q(1, 8)).unwrap();
        let bound = q(1, 64) * sup_speed(&a) * sup_speed(&a);
        coupling_steps(&a, &b, &bound).unwrap();
        let mut c = b.clone();
        c.x[0] = c.x[0].clone() + q(1, 1);
        let e = coupling_steps(&a, &c, &bound).unwrap_err();
        assert!(e.starts_with("Lipschitz step: |x[−1](t)"), "{e}");
        // A bound below a node's true displacement (1/8 at speed 1).
        let e = coupling_steps(&a, &b, &q(1, 65)).unwrap_err();
        assert!(e.starts_with("Lipschitz step"), "{e}");
    }

    /// The cell term is the exact integral: Simpson's rule, exact on the
    /// quadratic `(g + (h − g)θ)²`, gives `(g² + 4m² + h²)/6`, `m` the mean.
    #[test]
    fn the_cell_term_is_the_integral_of_the_square() {
        for (g, h) in [(q(1, 1), q(1, 1)), (q(-2, 3), q(5, 7)), (q(0, 1), q(3, 1))] {
            let m = (g.clone() + &h) / q(2, 1);
            let simpson = (g.clone() * &g + q(4, 1) * &m * &m + h.clone() * &h) / q(6, 1);
            assert_eq!(cell_cost(&g, &h), simpson);
        }
    }

    #[test]
    fn the_continuum_densities_are_at_most_one() {
        density_continuum().unwrap();
    }
}
