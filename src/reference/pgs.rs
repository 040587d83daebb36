//! Projected Gauss–Seidel (PGS) on the chain complementarity problem shared
//! by the iterative reference solvers.
//!
//! Unknowns `z ∈ R^N` (positions or velocities) and one impulse `ν_i ≥ 0` per
//! pair `(i, i+1)` (0-based):
//!
//! ```text
//! z = z_free − Σ_i ν_i (e_i − e_{i+1}),
//! g_i(z) = z_{i+1} − z_i − c ≥ 0,   ν_i ≥ 0,   ν_i · g_i(z) = 0.
//! ```
//!
//! * With `z` the positions, `z_free = y = x⁰ + t u⁰` and `c = 2r` this is
//!   Appendix A's KKT system of `min ½‖x − y‖²` over `K^N` (`app:KKT`), with
//!   `ν = N μ` (`x − y + N Σ μ_i (e_i − e_{i+1}) = 0`).
//! * With `z` the velocities and `c = 0` it is Moreau's velocity-level impact
//!   law with restitution 0 on unit masses (`0 ≤ u_{i+1} − u_i ⊥ P_i ≥ 0`).
//!
//! The Delassus matrix of the chain is `W = tridiag(−1, 2, −1)`. One PGS
//! update of pair `i` minimises the dual exactly in `ν_i`:
//! `ν_i ← max(0, ν_i − g_i/2)`, moving `z_i` and `z_{i+1}` by the change.
//! A *sweep* updates the pairs of a run left to right. The stopping test is
//! the natural residual `r_i = |min(ν_i, g_i)|` (zero exactly at a solution:
//! `g_i ≥ 0`, `ν_i ≥ 0` and one of them zero), `max_i r_i ≤ threshold`.
//!
//! Pairs that share no particle do not interact (`W` is block diagonal on
//! runs of consecutive pairs), so the solvers work run by run: [`solve_run`]
//! on a given run, [`solve_grown`] on runs grown from the violated pairs, and
//! [`solve_full`] sweeping every pair as a generic QP code would. For a run
//! of `m` coupled pairs the Gauss–Seidel contraction factor is about
//! `1 − π²/m²`, so reaching a residual `δ` costs about
//! `(m/π)² ln(1/δ)` sweeps: large congested clusters are where PGS is slow.

/// Stopping rule of one PGS solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stop {
    /// Absolute threshold on the natural residual `max_i |min(ν_i, g_i)|`.
    pub threshold: f64,
    /// Largest number of sweeps of one run.
    pub max_sweeps: usize,
}

/// What one PGS solve did.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Report {
    /// Sweeps performed (summed over runs).
    pub sweeps: usize,
    /// Largest final natural residual over the runs solved.
    pub residual: f64,
    /// Runs stopped by the sweep cap before meeting the threshold.
    pub unconverged: usize,
}

impl Report {
    fn absorb(&mut self, other: Report) {
        self.sweeps += other.sweeps;
        self.residual = self.residual.max(other.residual);
        self.unconverged += other.unconverged;
    }
}

/// `g_i(z) = (z_{i+1} − z_i) − c`.
#[inline]
pub fn gap(z: &[f64], i: usize, c: f64) -> f64 {
    (z[i + 1] - z[i]) - c
}

/// One PGS update of pair `i`.
#[inline]
fn update(z: &mut [f64], nu: &mut [f64], i: usize, c: f64) {
    let g = gap(z, i, c);
    let new = (nu[i] - 0.5 * g).max(0.0);
    let d = new - nu[i];
    if d != 0.0 {
        nu[i] = new;
        z[i] -= d;
        z[i + 1] += d;
    }
}

/// The natural residual `max_{lo ≤ i ≤ hi} |min(ν_i, g_i)|`.
pub fn residual(z: &[f64], nu: &[f64], lo: usize, hi: usize, c: f64) -> f64 {
    (lo..=hi).fold(0.0, |m, i| m.max(nu[i].min(gap(z, i, c)).abs()))
}

/// PGS on the pairs `lo..=hi` until the residual is at most
/// `stop.threshold` or `stop.max_sweeps` sweeps were made. `ν` is used as
/// the starting point (warm start) and updated in place, as is `z`.
pub fn solve_run(
    z: &mut [f64],
    nu: &mut [f64],
    lo: usize,
    hi: usize,
    c: f64,
    stop: Stop,
) -> Report {
    let mut sweeps = 0;
    loop {
        let r = residual(z, nu, lo, hi, c);
        // A NaN residual also stops: the caller's finiteness check reports
        // it.
        if r.partial_cmp(&stop.threshold) != Some(std::cmp::Ordering::Greater) {
            return Report {
                sweeps,
                residual: r,
                unconverged: 0,
            };
        }
        if sweeps >= stop.max_sweeps {
            return Report {
                sweeps,
                residual: r,
                unconverged: 1,
            };
        }
        for i in lo..=hi {
            update(z, nu, i, c);
        }
        sweeps += 1;
    }
}

/// PGS on every pair at once, `sweeps` counting full sweeps over all
/// `N − 1` pairs: the generic method, blind to the chain structure.
pub fn solve_full(z: &mut [f64], nu: &mut [f64], c: f64, stop: Stop) -> Report {
    if z.len() < 2 {
        return Report::default();
    }
    solve_run(z, nu, 0, z.len() - 2, c, stop)
}

/// Maximal runs of consecutive indices in a sorted list.
pub fn runs_of(sorted: &[usize]) -> Vec<(usize, usize)> {
    let mut out: Vec<(usize, usize)> = Vec::new();
    for &i in sorted {
        match out.last_mut() {
            Some((_, hi)) if *hi + 1 == i => *hi = i,
            _ => out.push((i, i)),
        }
    }
    out
}

/// PGS on the runs of the given sorted pair list, each run solved
/// separately (they share no particle). Pairs not listed keep `ν = 0` and
/// are not enforced (Moreau–Jean's index set).
pub fn solve_listed(z: &mut [f64], nu: &mut [f64], pairs: &[usize], c: f64, stop: Stop) -> Report {
    let mut report = Report::default();
    for (lo, hi) in runs_of(pairs) {
        report.absorb(solve_run(z, nu, lo, hi, c, stop));
    }
    report
}

/// PGS on runs grown from the violated pairs: starts from the pairs with
/// `g_i < −threshold` (with `ν = 0` these are exactly the pairs whose natural
/// residual is too large), solves each run, then adds a neighbouring pair
/// whenever the solve made it violated, merging runs that come to share a
/// particle, until no pair outside the runs is violated. Pairs that never
/// join a run keep `ν_i = 0` and both their particles unmoved. The fixed
/// point is the same as [`solve_full`]'s; the cost follows the runs that
/// actually carry impulses instead of `N` per sweep.
///
/// `ν` must be zero on entry (cold start).
pub fn solve_grown(z: &mut [f64], nu: &mut [f64], c: f64, stop: Stop) -> Report {
    let mut report = Report::default();
    let pairs = z.len().saturating_sub(1);
    let violated = |z: &[f64], i: usize| gap(z, i, c) < -stop.threshold;
    let seeds: Vec<usize> = (0..pairs).filter(|&i| violated(z, i)).collect();
    let seeds = runs_of(&seeds);
    // Final runs, left to right, each solved (as far as the cap allows) with
    // its residual.
    let mut done: Vec<(usize, usize, Report)> = Vec::new();
    let mut k = 0;
    while k < seeds.len() {
        let (mut lo, mut hi) = seeds[k];
        k += 1;
        loop {
            // A finished run sharing a particle with this one joins it.
            if let Some(&(plo, phi, _)) = done.last() {
                if phi + 1 >= lo {
                    lo = lo.min(plo);
                    hi = hi.max(phi);
                    done.pop();
                    continue;
                }
            }
            // So do the seed runs it reaches.
            while k < seeds.len() && seeds[k].0 <= hi + 1 {
                hi = hi.max(seeds[k].1);
                k += 1;
            }
            let r = solve_run(z, nu, lo, hi, c, stop);
            report.sweeps += r.sweeps;
            let mut grew = false;
            if lo > 0 && violated(z, lo - 1) {
                lo -= 1;
                grew = true;
            }
            if hi + 1 < pairs && violated(z, hi + 1) {
                hi += 1;
                grew = true;
            }
            if !grew {
                done.push((lo, hi, r));
                break;
            }
        }
    }
    for (_, _, r) in done {
        report.residual = report.residual.max(r.residual);
        report.unconverged += r.unconverged;
    }
    report
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_particles_meet_in_the_middle() {
        // y = (1, 0), c = 0: projection (1/2, 1/2), ν = 1/2.
        let mut z = vec![1.0, 0.0];
        let mut nu = vec![0.0];
        let stop = Stop {
            threshold: 0.0,
            max_sweeps: 10,
        };
        let r = solve_full(&mut z, &mut nu, 0.0, stop);
        assert_eq!(z, vec![0.5, 0.5]);
        assert_eq!(nu, vec![0.5]);
        assert_eq!(r.unconverged, 0);
        assert_eq!(r.sweeps, 1);
    }

    #[test]
    fn grown_equals_full() {
        let y = vec![0.0, 3.0, 2.0, 1.0, 5.0, 9.0, 6.0, 6.5, 20.0];
        let stop = Stop {
            threshold: 1e-13,
            max_sweeps: 100_000,
        };
        let (mut a, mut na) = (y.clone(), vec![0.0; y.len() - 1]);
        let (mut b, mut nb) = (y.clone(), vec![0.0; y.len() - 1]);
        let ra = solve_full(&mut a, &mut na, 1.0, stop);
        let rb = solve_grown(&mut b, &mut nb, 1.0, stop);
        assert_eq!(ra.unconverged + rb.unconverged, 0);
        for (p, q) in a.iter().zip(&b) {
            assert!((p - q).abs() < 1e-11, "{a:?} vs {b:?}");
        }
        assert_eq!(runs_of(&[1, 2, 3, 6, 8, 9]), vec![(1, 3), (6, 6), (8, 9)]);
    }

    #[test]
    fn cap_is_reported() {
        let mut z = vec![3.0, 2.0, 1.0, 0.0];
        let mut nu = vec![0.0; 3];
        let r = solve_full(
            &mut z,
            &mut nu,
            0.0,
            Stop {
                threshold: 1e-15,
                max_sweeps: 2,
            },
        );
        assert_eq!(r.sweeps, 2);
        assert_eq!(r.unconverged, 1);
        assert!(r.residual > 1e-15);
    }
}
