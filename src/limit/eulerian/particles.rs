//! The particle side of the weak form: the exact momentum residuals
//! `R_mom^N(φ)` and the complementarity pairing `⟨(1 − ρ_N) p_N, φ⟩`, summed
//! over the collisions by power sums on a dyadic grid.

use num_bigint::BigInt;
use num_rational::BigRational;

use super::TestFunction;
use crate::cluster::Cluster;
use crate::error::Error;
use crate::scalar::Scalar;
use crate::trajectory::Trajectory;

/// `Σ_{j=0}^{s−1} j^r` for `r ≤ 5`, exact.
fn power_sum(s: usize, r: u32) -> BigInt {
    let n = BigInt::from(s);
    let one = BigInt::from(1);
    let m = &n - &one; // Σ_{j=0}^{m} j^r with m = s − 1
    match r {
        0 => n,
        1 => &m * &n / 2,
        2 => &m * &n * (BigInt::from(2) * &n - &one) / 6,
        3 => {
            let s1 = &m * &n / 2;
            &s1 * &s1
        }
        4 => {
            &m * &n
                * (BigInt::from(2) * &n - &one)
                * (BigInt::from(3) * &n * &n - BigInt::from(3) * &n - &one)
                / 30
        }
        _ => {
            // r = 5: n²(n−1)²(2n²−2n−1)/12 with n = s.
            &n * &n * &m * &m * (BigInt::from(2) * &n * &n - BigInt::from(2) * &n - &one) / 12
        }
    }
}

fn to_s<S: Scalar>(v: BigInt) -> S {
    S::from_big_rational(&BigRational::from_integer(v)).unwrap_or_else(S::zero)
}

/// Prefix sums of the translated initial positions and velocities, to
/// place any cluster at any time in O(1): a cluster `C` moves rigidly with
/// `x̃_C(t) = (Σ_C x̃⁰ + t Σ_C u⁰)/|C|` (`trajectory`'s module docs).
#[derive(Debug, Clone)]
pub struct ClusterPositions<S> {
    px: Vec<S>,
    pu: Vec<S>,
    two_r: S,
}

impl<S: Scalar> ClusterPositions<S> {
    /// The prefix sums of `traj`'s data.
    pub fn new(traj: &Trajectory<S>) -> Self {
        let data = traj.data();
        let mut px = vec![S::zero()];
        let mut pu = vec![S::zero()];
        for (x, u) in data.shifted_positions().iter().zip(data.velocities()) {
            let lx = px[px.len() - 1].clone() + x;
            let lu = pu[pu.len() - 1].clone() + u;
            px.push(lx);
            pu.push(lu);
        }
        ClusterPositions {
            px,
            pu,
            two_r: data.two_r(),
        }
    }
    /// The position of particle `j` (0-based) at `t` when it belongs to
    /// the rigid cluster `c` then.
    pub fn position(&self, c: Cluster, j: usize, t: &S) -> S {
        let k = S::from_usize(c.size);
        let sx = self.px[c.end()].clone() - &self.px[c.first];
        let su = self.pu[c.end()].clone() - &self.pu[c.first];
        (sx + &(t.clone() * &su)) / &k + &(self.two_r.clone() * &S::from_usize(j))
    }
}

/// The cluster containing particle `j` just after `t` (from the join
/// times; O(cluster size)).
pub fn cluster_containing<S: Scalar>(traj: &Trajectory<S>, j: usize, t: &S) -> Cluster {
    let joins = traj.join_times();
    let joined = |i: usize| {
        joins
            .get(i)
            .and_then(|jt| jt.as_ref())
            .is_some_and(|jt| jt.total_cmp(t).is_le())
    };
    let mut first = j;
    while first > 0 && joined(first - 1) {
        first -= 1;
    }
    let mut last = j;
    while joined(last) {
        last += 1;
    }
    Cluster {
        first,
        size: last + 1 - first,
    }
}

/// Bits of the dyadic grid on which the exact residual sums are
/// accumulated: every collision's contribution is computed exactly, then
/// rounded to the nearest multiple of `2^{−RESIDUAL_BITS}` before it is
/// added (otherwise the common denominator of hundreds of collision times
/// raised to the 8th power makes exact sums cost minutes).
pub const RESIDUAL_BITS: usize = 256;

/// Weak residuals of the particles, one per test function.
#[derive(Debug, Clone, PartialEq)]
pub struct Residuals<S> {
    /// One value per test function.
    pub values: Vec<S>,
    /// A bound on the accumulation error: `terms · 2^{−RESIDUAL_BITS−1}`
    /// on an exact scalar (0 for `f64`, whose own rounding is not bounded
    /// here).
    pub rounding_bound: f64,
}

/// Accumulates exact terms on the dyadic grid `2^{−RESIDUAL_BITS}` (exact
/// scalars) or plainly (`f64`).
pub(super) struct Accumulator<S> {
    values: Vec<S>,
    terms: usize,
    scale: BigRational,
}

impl<S: Scalar> Accumulator<S> {
    pub(super) fn new(k: usize) -> Self {
        Accumulator {
            values: vec![S::zero(); k],
            terms: 0,
            scale: BigRational::from_integer(BigInt::from(1) << RESIDUAL_BITS),
        }
    }
    pub(super) fn add(&mut self, k: usize, v: S) {
        let v = if S::EXACT {
            match v.to_big_rational() {
                Some(q) => {
                    let r = (q * &self.scale).round() / &self.scale;
                    S::from_big_rational(&r).unwrap_or(v)
                }
                None => v,
            }
        } else {
            v
        };
        self.values[k] = self.values[k].clone() + &v;
        self.terms += 1;
    }
    pub(super) fn finish(self) -> Residuals<S> {
        Residuals {
            rounding_bound: if S::EXACT {
                self.terms as f64 * 2f64.powi(-(RESIDUAL_BITS as i32) - 1)
            } else {
                0.0
            },
            values: self.values,
        }
    }
}

/// `Q^{(j)}(x)` for `j = 0 … degree` (powers of `x − c` computed once).
fn space_derivatives<S: Scalar>(f: &TestFunction<S>, x: &S) -> Vec<S> {
    let m = f.degree as usize;
    let y = x.clone() - &f.center;
    let mut pow = vec![S::one()];
    for j in 1..=m {
        let v = pow[j - 1].clone() * &y;
        pow.push(v);
    }
    let mut lm = S::one();
    for _ in 0..m {
        lm = lm * &f.scale;
    }
    (0..=m)
        .map(|j| {
            let mut coeff = S::one();
            for i in 0..j {
                coeff = coeff * &S::from_usize(m - i);
            }
            coeff * &pow[m - j] / &lm
        })
        .collect()
}

/// The largest degree of `Q` [`particle_momentum_residuals`] handles.
pub const MAX_TEST_DEGREE: u32 = 4;

/// The particle momentum residual `R_mom^N(φ)` of each test function (the
/// exact identity of the module documentation), over the collisions with
/// `t_k ≤ t_end`. The mass residual of the particles is identically 0.
/// Test functions of degree above [`MAX_TEST_DEGREE`] are refused.
pub fn particle_momentum_residuals<S: Scalar>(
    traj: &Trajectory<S>,
    tests: &[TestFunction<S>],
    t_end: &S,
) -> Result<Residuals<S>, Error> {
    if let Some(f) = tests.iter().find(|f| f.degree > MAX_TEST_DEGREE) {
        return Err(Error::Unsupported {
            message: format!(
                "test function of degree {} (at most {MAX_TEST_DEGREE} is supported)",
                f.degree
            ),
        });
    }
    let data = traj.data();
    let n = S::from_usize(data.n());
    let h = data.two_r();
    let pos = ClusterPositions::new(traj);
    let mut acc = Accumulator::new(tests.len());
    // h^k / k! and h^k.
    let mut hk_fact = vec![S::one()];
    let mut hpow = vec![S::one()];
    for k in 1..=6 {
        let v = hk_fact[k - 1].clone() * &h / &S::from_usize(k);
        hk_fact.push(v);
        let p = hpow[k - 1].clone() * &h;
        hpow.push(p);
    }
    let fact = [1i64, 1, 2, 6, 24, 120].map(S::from_i64);
    let gap = S::one() / &n - &h; // 1/N − 2r (0 with the paper's radius)
                                  // Test functions sharing their space part share its Taylor data.
    let mut space_of: Vec<usize> = Vec::with_capacity(tests.len());
    let mut spaces: Vec<&TestFunction<S>> = Vec::new();
    for f in tests {
        let k = spaces
            .iter()
            .position(|g| g.degree == f.degree && g.center == f.center && g.scale == f.scale);
        space_of.push(k.unwrap_or_else(|| {
            spaces.push(f);
            spaces.len() - 1
        }));
    }
    for imp in traj.impulses() {
        if imp.t.total_cmp(t_end).is_gt() {
            break;
        }
        let b: Vec<S> = tests.iter().map(|f| f.time_bump(&imp.t)).collect();
        if b.iter().all(|v| v.is_zero()) {
            continue;
        }
        let mut before = S::zero();
        let mut contrib = vec![S::zero(); spaces.len()];
        for (part, vp) in imp.parts.iter().zip(&imp.part_velocities) {
            let dv = vp.clone() - &imp.velocity;
            let xp = pos.position(imp.cluster, part.first, &imp.t);
            // Σ_j (C_p + (j+1) dv) j^r for r = 0 … 4.
            let sums: Vec<S> = (0..=4)
                .map(|r| {
                    let sr = to_s::<S>(power_sum(part.size, r));
                    let sr1 = to_s::<S>(power_sum(part.size, r + 1));
                    (before.clone() + &dv) * &sr + &(dv.clone() * &sr1)
                })
                .collect();
            for (k, f) in spaces.iter().enumerate() {
                let m = f.degree as usize;
                let q = space_derivatives(f, &xp);
                let mut total = S::zero();
                for r in 0..m {
                    // g_r = G^{(r)}(x_p)/r!, G = Q'(1/N − h) − Σ_{k≥2} h^k Q^{(k)}/k!.
                    let mut g = q[r + 1].clone() * &gap;
                    for kk in 2..=(m - r) {
                        g = g - &(hk_fact[kk].clone() * &q[kk + r]);
                    }
                    total = total + &(g / &fact[r] * &hpow[r] * &sums[r]);
                }
                contrib[k] = contrib[k].clone() + &total;
            }
            before = before + &(S::from_usize(part.size) * &dv);
        }
        for (k, bk) in b.into_iter().enumerate() {
            if !bk.is_zero() {
                acc.add(k, bk * &contrib[space_of[k]] / &n);
            }
        }
    }
    Ok(acc.finish())
}

/// `⟨(1 − ρ_N) p_N, φ⟩` for each test function, with the paper's
/// representative of `ρ_N` (see the module documentation), over the
/// collisions with `t_k ≤ t_end`; `delta` is the `δ` of `df:x0`.
pub fn particle_complementarity<S: Scalar>(
    traj: &Trajectory<S>,
    tests: &[TestFunction<S>],
    t_end: &S,
    delta: &S,
) -> Residuals<S> {
    let data = traj.data();
    let n = S::from_usize(data.n());
    let pos = ClusterPositions::new(traj);
    let mut acc = Accumulator::new(tests.len());
    for imp in traj.impulses() {
        if imp.t.total_cmp(t_end).is_gt() {
            break;
        }
        let first = imp.cluster.first;
        let Some(v0) = imp.part_velocities.first() else {
            continue;
        };
        // The jump of λ at the first pair of the merged cluster.
        let jump = (v0.clone() - &imp.velocity) / &n;
        if jump.is_zero() {
            continue;
        }
        let x_first = pos.position(imp.cluster, first, &imp.t);
        let gap = if first == 0 {
            S::one() / &n + delta
        } else {
            let c = cluster_containing(traj, first - 1, &imp.t);
            x_first.clone() - &pos.position(c, first - 1, &imp.t)
        };
        let factor = S::one() - &(S::one() / &(n.clone() * &gap));
        if factor.is_zero() {
            continue;
        }
        for (k, f) in tests.iter().enumerate() {
            let v = f.value(&imp.t, &x_first);
            if !v.is_zero() {
                acc.add(k, jump.clone() / &n * &factor * &v);
            }
        }
    }
    acc.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn power_sums_match_direct_sums() {
        for s in [1usize, 2, 3, 7, 100] {
            for r in 0..=5u32 {
                let direct: BigInt = (0..s).map(|j| BigInt::from(j).pow(r)).sum();
                assert_eq!(power_sum(s, r), direct, "s = {s}, r = {r}");
            }
        }
    }
}
