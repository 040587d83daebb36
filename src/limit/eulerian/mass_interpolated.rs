//! The mass equation for the interpolated density `ρ̃_N = X̃_N(t)#L¹`
//! transported by the paper's velocity `U_N` (`df:UN`): the one pairing of
//! the two interpolations whose weak residual is not identically 0.
//!
//! For any map `Y(t, w)` Lipschitz in `t`, `∫φ(t, ·) d(Y(t)#L¹) =
//! ∫_0^1 φ(t, Y(t, w)) dw`, so the residual of `(Y#L¹, Y#(∂_t Y L¹))`
//! against `φ` with compact support in time is `∫_0^T d/dt ∫_0^1 φ(t, Y)
//! dw dt = 0`: for the particles (`Y = X_N`, `∂_t X_N = U_N`) and for the
//! interpolation (`Y = X̃_N`, `∂_t X̃_N = Ũ_N`) alike. With
//! `ρ̃_N = X̃_N#L¹` (the density of `lem:density`) and the momentum
//! `m̃_N = X̃_N#(U_N L¹)` (the velocity of `eq:PDE-Lagr-N`):
//!
//! ```text
//! R_N(φ) = ∫∫ ρ̃_N ∂_t φ + m̃_N ∂_x φ
//!        = ∫_0^T ∫_0^1 (U_N − Ũ_N)(t, w) ∂_x φ(t, X̃_N(t, w)) dw dt.
//! ```
//!
//! On the cell of the pair `(i−1, i)`, `w = (i−1)/N + s/N`, `U_N − Ũ_N =
//! (1 − s)(u_i − u_{i−1})` and `X̃_N = x_{i−1} + s g_i`, `g_i = x_i −
//! x_{i−1}`; for `φ = B(t) Q(x)`, `Q = ((x − c)/L)^m`,
//!
//! ```text
//! cell = (1/N)(u_i − u_{i−1}) B(t) ∫_0^1 (1 − s) Q'(x_{i−1} + s g_i) ds,
//! ∫_0^1 (1 − s)(A + sG)^{m−1} ds = Σ_j C(m−1, j) A^{m−1−j} G^j / ((j+1)(j+2)).
//! ```
//!
//! Only pairs apart carry a term (`u_i = u_{i−1}` inside a cluster, and the
//! artificial particle moves with particle 1), and a pair's term is a
//! polynomial in `t` until one of its two clusters takes part in a
//! collision: the sum is kept as one open *piece* per pair apart, closed
//! and reopened at the collisions of its neighbours (`O(N)` pieces in all,
//! each integrated exactly against the bump `B`).

use std::collections::BTreeMap;

use super::particles::{Accumulator, ClusterPositions};
use super::{Residuals, TestFunction};
use crate::error::Error;
use crate::limit::poly;
use crate::scalar::Scalar;
use crate::trajectory::Trajectory;

/// A pair apart `(i−1, i)` since `start`: its two particles' positions at
/// `start` and their (constant) velocities until the piece is closed.
#[derive(Debug, Clone)]
struct Piece<S> {
    start: S,
    left_x: S,
    left_u: S,
    right_x: S,
    right_u: S,
}

impl<S: Scalar> Piece<S> {
    /// The left particle's position at `t`.
    fn left_at(&self, t: &S) -> S {
        self.left_x.clone() + &((t.clone() - &self.start) * &self.left_u)
    }
    /// The right particle's position at `t`.
    fn right_at(&self, t: &S) -> S {
        self.right_x.clone() + &((t.clone() - &self.start) * &self.right_u)
    }
}

/// `(a + b τ)^k` for `k = 0 … top`, as polynomials in `τ`.
fn affine_powers<S: Scalar>(a: &S, b: &S, top: usize) -> Vec<Vec<S>> {
    let base = vec![a.clone(), b.clone()];
    let mut out = vec![vec![S::one()]];
    for k in 1..=top {
        let next = poly::mul(&out[k - 1], &base);
        out.push(next);
    }
    out
}

/// `C(n, k)` for the small `n` of the test degrees.
fn binomial(n: usize, k: usize) -> i64 {
    (0..k).fold(1i64, |acc, j| acc * (n - j) as i64 / (j as i64 + 1))
}

/// `∫_0^1 (1 − s) Q'(A(τ) + c + s G(τ)) ds` as a polynomial in `τ`, for
/// `Q = ((x − c)/L)^m`, `A(τ) = a0 + a1 τ` (the left particle minus `c`)
/// and `G(τ) = g0 + g1 τ` (the gap).
fn cell_kernel<S: Scalar>(f: &TestFunction<S>, a: [&S; 2], g: [&S; 2]) -> Vec<S> {
    let m = f.degree as usize;
    if m == 0 {
        return Vec::new();
    }
    let pa = affine_powers(a[0], a[1], m - 1);
    let pg = affine_powers(g[0], g[1], m - 1);
    let mut out: Vec<S> = Vec::new();
    for j in 0..m {
        let coeff = S::from_i64(binomial(m - 1, j)) / &S::from_usize((j + 1) * (j + 2));
        let term: Vec<S> = poly::mul(&pa[m - 1 - j], &pg[j])
            .into_iter()
            .map(|c| c * &coeff)
            .collect();
        poly::add_into(&mut out, &term);
    }
    let mut lm = S::one();
    for _ in 0..m {
        lm = lm * &f.scale;
    }
    let scale = S::from_usize(m) / &lm;
    out.into_iter().map(|c| c * &scale).collect()
}

/// `B(start + τ)` as a polynomial in `τ` (the bump of `f`, `b⁴` with
/// `b = 4(t − t₀)(t₁ − t)/(t₁ − t₀)²`), valid inside the window.
fn bump_in_tau<S: Scalar>(f: &TestFunction<S>, start: &S) -> Vec<S> {
    let width = f.t1.clone() - &f.t0;
    let k = S::from_i64(4) / &(width.clone() * &width);
    let alpha = start.clone() - &f.t0;
    let beta = f.t1.clone() - start;
    // b = k (α + τ)(β − τ) = k (αβ + (β − α)τ − τ²).
    let b = vec![
        k.clone() * &alpha * &beta,
        k.clone() * &(beta - &alpha),
        S::zero() - &k,
    ];
    let b2 = poly::mul(&b, &b);
    poly::mul(&b2, &b2)
}

/// The contribution of one closed piece on `[start, end]` to each test
/// function: `(1/N)(u_i − u_{i−1}) ∫ B(t) kernel(t) dt` over the part of
/// the piece inside the test's window.
fn close<S: Scalar>(
    piece: &Piece<S>,
    end: &S,
    tests: &[TestFunction<S>],
    n: &S,
    acc: &mut Accumulator<S>,
) {
    let du = piece.right_u.clone() - &piece.left_u;
    if du.is_zero() || end.total_cmp(&piece.start).is_le() {
        return;
    }
    let gap = piece.right_x.clone() - &piece.left_x;
    for (k, f) in tests.iter().enumerate() {
        let lo = if piece.start.total_cmp(&f.t0).is_ge() {
            piece.start.clone()
        } else {
            f.t0.clone()
        };
        let hi = if end.total_cmp(&f.t1).is_le() {
            end.clone()
        } else {
            f.t1.clone()
        };
        if hi.total_cmp(&lo).is_le() {
            continue;
        }
        let a0 = piece.left_x.clone() - &f.center;
        let kernel = cell_kernel(f, [&a0, &piece.left_u], [&gap, &du]);
        let integrand = poly::mul(&bump_in_tau(f, &piece.start), &kernel);
        let value = poly::integral(&integrand, &(hi - &piece.start))
            - &poly::integral(&integrand, &(lo - &piece.start));
        acc.add(k, value * &du / n);
    }
}

/// `R_N(φ) = ∫∫ ρ̃_N ∂_t φ + m̃_N ∂_x φ` (module documentation) for each test
/// function, over `[0, t_end]`, each piece's exact value accumulated on
/// the dyadic grid of [`super::RESIDUAL_BITS`] bits (the bound is in
/// [`Residuals::rounding_bound`]). Test functions of degree above
/// [`super::MAX_TEST_DEGREE`] are refused.
pub fn interpolated_mass_residuals<S: Scalar>(
    traj: &Trajectory<S>,
    tests: &[TestFunction<S>],
    t_end: &S,
) -> Result<Residuals<S>, Error> {
    if let Some(f) = tests.iter().find(|f| f.degree > super::MAX_TEST_DEGREE) {
        return Err(Error::Unsupported {
            message: format!(
                "test function of degree {} (at most {} is supported)",
                f.degree,
                super::MAX_TEST_DEGREE
            ),
        });
    }
    let data = traj.data();
    let n = S::from_usize(data.n());
    let (x0, u0) = (data.positions(), data.velocities());
    let pos = ClusterPositions::new(traj);
    let mut acc = Accumulator::new(tests.len());
    // Key i: the pair (i−1, i), 0-based particles.
    let mut open: BTreeMap<usize, Piece<S>> = (1..data.n())
        .map(|i| {
            let piece = Piece {
                start: S::zero(),
                left_x: x0[i - 1].clone(),
                left_u: u0[i - 1].clone(),
                right_x: x0[i].clone(),
                right_u: u0[i].clone(),
            };
            (i, piece)
        })
        .collect();
    for imp in traj.impulses() {
        if imp.t.total_cmp(t_end).is_gt() {
            break;
        }
        let (first, end) = (imp.cluster.first, imp.cluster.end());
        // The pairs inside the merged cluster are in contact from now on.
        let inside: Vec<usize> = open.range(first + 1..end).map(|(i, _)| *i).collect();
        for i in inside {
            if let Some(p) = open.remove(&i) {
                close(&p, &imp.t, tests, &n, &mut acc);
            }
        }
        // The pairs at its two ends: one side now moves with the cluster.
        if let Some(p) = open.get_mut(&first) {
            close(p, &imp.t, tests, &n, &mut acc);
            *p = Piece {
                left_x: p.left_at(&imp.t),
                left_u: p.left_u.clone(),
                right_x: pos.position(imp.cluster, first, &imp.t),
                right_u: imp.velocity.clone(),
                start: imp.t.clone(),
            };
        }
        if let Some(p) = open.get_mut(&end) {
            close(p, &imp.t, tests, &n, &mut acc);
            *p = Piece {
                left_x: pos.position(imp.cluster, end - 1, &imp.t),
                left_u: imp.velocity.clone(),
                right_x: p.right_at(&imp.t),
                right_u: p.right_u.clone(),
                start: imp.t.clone(),
            };
        }
    }
    for p in open.values() {
        close(p, t_end, tests, &n, &mut acc);
    }
    Ok(acc.finish())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::initial::InitialData;
    use crate::rational::ratio as q;
    use num_rational::BigRational as Q;

    /// `∫∫ ρ̃_N ∂_t φ + m̃_N ∂_x φ` computed the other way, in Eulerian
    /// variables: on `(x_{i−1}, x_i)`, `ρ̃_N = 1/(N g_i)` and `m̃_N =
    /// u_i/(N g_i)`, so the `x`-integral is `(B'(t)(P(x_i) − P(x_{i−1})) +
    /// B(t) u_i (Q(x_i) − Q(x_{i−1})))/(N g_i)` with `P' = Q` (artificial
    /// cell included); the `t`-integral by composite Gauss–Legendre (f64,
    /// a test only) on the intervals between collisions, where it is
    /// smooth.
    fn eulerian_f64(traj: &Trajectory<Q>, f: &TestFunction<Q>, t_end: &Q) -> f64 {
        let data = traj.data();
        let n = data.n();
        let c = f.center.to_f64_lossy();
        let l = f.scale.to_f64_lossy();
        let m = f.degree as i32;
        let qf = |x: f64| ((x - c) / l).powi(m);
        let pf = |x: f64| l * ((x - c) / l).powi(m + 1) / f64::from(m + 1);
        let mut cuts: Vec<Q> = vec![Q::zero()];
        cuts.extend(
            traj.impulses()
                .iter()
                .map(|i| i.t.clone())
                .filter(|t| t < t_end),
        );
        cuts.push(t_end.clone());
        let nodes = [
            (-0.906_179_845_938_664, 0.236_926_885_056_189_1),
            (-0.538_469_310_105_683, 0.478_628_670_499_366_5),
            (0.0, 0.568_888_888_888_888_9),
            (0.538_469_310_105_683, 0.478_628_670_499_366_5),
            (0.906_179_845_938_664, 0.236_926_885_056_189_1),
        ];
        let mut total = 0.0;
        for w in cuts.windows(2) {
            if w[1] <= w[0] {
                continue;
            }
            let s = traj.at(&w[0]).unwrap();
            let (t0, t1) = (w[0].to_f64_lossy(), w[1].to_f64_lossy());
            let panels = 200;
            for p in 0..panels {
                let a = t0 + (t1 - t0) * p as f64 / panels as f64;
                let b = t0 + (t1 - t0) * (p + 1) as f64 / panels as f64;
                for (z, wt) in nodes {
                    let t = 0.5 * (a + b) + 0.5 * (b - a) * z;
                    let tq = Q::from_float(t).unwrap();
                    let bt = f.time_bump(&tq).to_f64_lossy();
                    let dbt = f.time_bump_dt(&tq).to_f64_lossy();
                    let x: Vec<f64> = s
                        .positions
                        .iter()
                        .zip(&s.velocities)
                        .map(|(x, u)| x.to_f64_lossy() + (t - t0) * u.to_f64_lossy())
                        .collect();
                    let u: Vec<f64> = s.velocities.iter().map(|u| u.to_f64_lossy()).collect();
                    let nf = n as f64;
                    let mut v = 0.0;
                    for i in 0..n {
                        let left = if i == 0 {
                            x[0] - 1.0 / nf - 1.0
                        } else {
                            x[i - 1]
                        };
                        let g = x[i] - left;
                        v += (dbt * (pf(x[i]) - pf(left)) + bt * u[i] * (qf(x[i]) - qf(left)))
                            / (nf * g);
                    }
                    total += 0.5 * (b - a) * wt * v;
                }
            }
        }
        total
    }

    #[test]
    fn the_residual_matches_the_eulerian_integral() {
        // Four particles, two collisions at different times, a pair apart
        // until the end.
        let data = InitialData::new(
            q(1, 8),
            vec![q(0, 1), q(1, 2), q(3, 2), q(5, 2)],
            vec![q(2, 1), q(-1, 1), q(0, 1), q(3, 4)],
        )
        .unwrap();
        let traj = Trajectory::new(data);
        let t_end = q(2, 1);
        assert!(!traj.impulses().is_empty());
        let tests: Vec<TestFunction<Q>> = [(q(0, 1), q(2, 1)), (q(1, 4), q(3, 2))]
            .into_iter()
            .flat_map(|(t0, t1)| {
                (2..=4).map(move |degree| TestFunction {
                    t0: t0.clone(),
                    t1: t1.clone(),
                    center: q(1, 1),
                    scale: q(3, 1),
                    degree,
                })
            })
            .collect();
        let r = interpolated_mass_residuals(&traj, &tests, &t_end).unwrap();
        let mut nonzero = 0;
        for (f, v) in tests.iter().zip(&r.values) {
            let exact = v.to_f64_lossy();
            let other = eulerian_f64(&traj, f, &t_end);
            assert!(
                (exact - other).abs() <= 1e-9 * (1.0 + other.abs()),
                "{}: exact {exact} against the Eulerian quadrature {other}",
                f.name()
            );
            nonzero += usize::from(!v.is_zero());
        }
        assert!(nonzero > 0, "every residual is 0: nothing was compared");
    }
}
