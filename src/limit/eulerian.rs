//! Eulerian fields and the weak form of the constrained Euler system
//! `eq:macro-euler`, for the particles and for the continuum.
//!
//! The Eulerian variables are push-forwards of the Lagrangian ones (§3.4,
//! `df:rho` and the proposition "Eulerian formulation"):
//! `ρ = X(t)#L¹_(0,1)`, `ρu = X(t)#(U L¹)`, `p = (Id, X)#P`.
//!
//! * **Density.** For the continuum `ρ(t, X(t,w)) = 1/∂_w X(t,w)` (the
//!   canonical representative of `lem:density`), 0 in vacuum; for the
//!   particles `ρ̃_N = X̃_N(t)#L¹`, equal to `1/(N(x_i − x_{i−1}))` on
//!   `(x_{i−1}, x_i)` (artificial particle included). Both are ≤ 1 because
//!   `∂_w X ≥ 1` and `∂_w X̃_N ≥ 1`.
//! * **Weak residuals.** Against `φ(t,x) = B(t)·Q(x)` with `B` a `C³`
//!   polynomial bump supported in a window `[t₀, t₁] ⊂ [0, T]`
//!   (`B = (4(t−t₀)(t₁−t)/(t₁−t₀)²)⁴`) and `Q(x) = ((x − c)/L)^m`,
//!   `m = 2, 3, 4` (the supports of `ρ`, `p` stay in a fixed bounded set, so
//!   a polynomial in `x` is a test function there; `m ≤ 1` gives exactly
//!   zero residuals: conservation of mass and momentum):
//!
//!   ```text
//!   R_mass(φ) = ∫∫ (∂_t φ + u ∂_x φ) ρ,
//!   R_mom(φ)  = ∫∫ (∂_t φ + u ∂_x φ) ρu + ⟨p, ∂_x φ⟩.
//!   ```
//!
//!   *Particles* (`X_N`, `U_N`, `P_N`, as in the paper): `x_i` is
//!   Lipschitz with derivative `u_i`, so `R_mass = (1/N) Σ_i ∫ d/dt φ(t,x_i) = 0`
//!   identically, and integrating by parts in time between collisions (with
//!   `u_i` jumping by `−N([λ_i] − [λ_{i−1}])`) gives the exact identity
//!
//!   ```text
//!   R_mom^N(φ) = Σ_k B(t_k) Σ_i [λ_i]_k ( Q'(x_i)/N − (Q(x_{i+1}) − Q(x_i)) )
//!   ```
//!
//!   (collisions `t_k`, pairs `i` of the merged cluster, all in contact:
//!   `x_{i+1} = x_i + 2r`). Inside a part of the merged cluster the jumps are
//!   affine in `i` and the positions equally spaced, so each part's sum is a
//!   combination of the power sums `Σ j^r` (integers, exact): O(parts) per
//!   collision, exact on `BigRational`. With `2r = 1/N` the bracket is
//!   `−(2r)² Q''/2 + O(N⁻³)`: the residual is `O(1/N)`.
//!
//!   *Continuum*: by the change of variables of the paper's proof and
//!   `P = ∂_t Λ` integrated by parts in time,
//!   `R_mom(φ) = ∫∫ [(∂_tφ + U∂_xφ)(t,X) U − Λ (∂_t∂_xφ + U ∂²_xφ)(t,X)] dw dt`.
//!   The `w`-integral is exact (Gauss–Legendre with 4 nodes per segment,
//!   exact for the degree ≤ 5 polynomials that appear, in `f64` from the
//!   rounded profile); the `t`-integral is composite 5-node Gauss–Legendre
//!   on panels cut at the instants where the plateau structure changes
//!   (located by bisection to `2⁻⁴⁰·T`), with an error estimate from panel
//!   doubling. The exact value is 0; the computed one measures the solver
//!   and the quadrature.
//! * **Complementarity** `(1 − ρ)p = 0`: for the particles with the paper's
//!   representative (`ρ(t, X_N(w)) = 1/∂_w X̃_N(w)` on the cell of `w`, and
//!   `P_N = p_i` on cell `i`, `p = (Id, X_N)#P_N`):
//!   `⟨(1 − ρ_N)p_N, φ⟩ = Σ_k Σ_i ([λ_i]_k/N)(1 − 1/(N(x_i − x_{i−1}))) φ(t_k, x_i)`,
//!   non-zero only at the left end of each merged cluster (the pairing of
//!   `λ_i`, which lives on the pair `(i, i+1)`, with the slope of the pair
//!   `(i−1, i)` — the off-by-one of `lem:discPDE2`); for the continuum `Λ`
//!   vanishes off the plateaus where `ρ = 1` (checked exactly by
//!   [`complementarity_defect`]).
//! * **Oleinik** `∂_x u < 1/t`: [`oleinik_margin`] returns `t · sup ∂_x u`,
//!   with `∂_x u = ∂_w U/∂_w X` on each segment and `[U]/[X]` across a
//!   vacuum gap (the linear interpolation of `u` through the gap); it must
//!   be `< 1`.

use num_bigint::BigInt;
use num_rational::BigRational;

use super::continuum::{Continuum, Profile};
use super::interpolation::{abs, max_of, Snapshot};
use crate::cluster::Cluster;
use crate::error::Error;
use crate::scalar::Scalar;
use crate::trajectory::Trajectory;

/// `φ(t, x) = B(t) Q(x)`: a `C³` bump in time on `[t0, t1]` times
/// `Q(x) = ((x − center)/scale)^degree`.
#[derive(Debug, Clone, PartialEq)]
pub struct TestFunction<S> {
    /// Start of the time window.
    pub t0: S,
    /// End of the time window.
    pub t1: S,
    /// Centre of the space polynomial.
    pub center: S,
    /// Scale of the space polynomial.
    pub scale: S,
    /// Degree `m` of the space polynomial (2 to 4).
    pub degree: u32,
}

impl<S: Scalar> TestFunction<S> {
    /// `b = 4(t−t₀)(t₁−t)/(t₁−t₀)²` and `b'`, or `None` outside the window.
    fn b_parts(&self, t: &S) -> Option<(S, S)> {
        if t.total_cmp(&self.t0).is_le() || t.total_cmp(&self.t1).is_ge() {
            return None;
        }
        let width = self.t1.clone() - &self.t0;
        let w2 = width.clone() * &width;
        let four = S::from_i64(4);
        let b = four.clone() * &(t.clone() - &self.t0) * &(self.t1.clone() - t) / &w2;
        let db = four * &(self.t1.clone() + &self.t0 - &(S::from_i64(2) * t)) / &w2;
        Some((b, db))
    }
    /// `B(t)`.
    pub fn time_bump(&self, t: &S) -> S {
        match self.b_parts(t) {
            Some((b, _)) => {
                let b2 = b.clone() * &b;
                b2.clone() * &b2
            }
            None => S::zero(),
        }
    }
    /// `B'(t)`.
    pub fn time_bump_dt(&self, t: &S) -> S {
        match self.b_parts(t) {
            Some((b, db)) => S::from_i64(4) * &(b.clone() * &b * &b) * &db,
            None => S::zero(),
        }
    }
    /// `Q^{(k)}(x) = m!/(m−k)! (x − c)^{m−k} / L^m` (0 for `k > m`).
    pub fn space(&self, x: &S, k: u32) -> S {
        if k > self.degree {
            return S::zero();
        }
        let mut coeff = S::one();
        for j in 0..k {
            coeff = coeff * &S::from_i64(i64::from(self.degree - j));
        }
        let y = x.clone() - &self.center;
        let mut p = S::one();
        for _ in 0..(self.degree - k) {
            p = p * &y;
        }
        let mut l = S::one();
        for _ in 0..self.degree {
            l = l * &self.scale;
        }
        coeff * &p / &l
    }
    /// `φ(t, x)`.
    pub fn value(&self, t: &S, x: &S) -> S {
        self.time_bump(t) * &self.space(x, 0)
    }
    /// A short name: `B[t0,t1]·((x−c)/L)^m`.
    pub fn name(&self) -> String {
        format!(
            "B[{},{}]·((x−{})/{})^{}",
            self.t0.render(),
            self.t1.render(),
            self.center.render(),
            self.scale.render(),
            self.degree
        )
    }
    /// The same test function over another scalar.
    pub fn convert<T: Scalar>(&self) -> Option<TestFunction<T>> {
        let c = |v: &S| v.to_big_rational().and_then(|q| T::from_big_rational(&q));
        Some(TestFunction {
            t0: c(&self.t0)?,
            t1: c(&self.t1)?,
            center: c(&self.center)?,
            scale: c(&self.scale)?,
            degree: self.degree,
        })
    }
}

/// The family used by the convergence study: windows `[0,T]`, `[0,T/2]`,
/// `[T/4,3T/4]`, `[T/2,T]` times degrees 2, 3, 4, with `center` and
/// `scale` covering the support of the motion.
pub fn test_family(
    t_end: &BigRational,
    center: &BigRational,
    scale: &BigRational,
) -> Vec<TestFunction<BigRational>> {
    let f = |n: i64, d: i64| t_end * BigRational::new(n.into(), d.into());
    let windows = [
        (f(0, 1), f(1, 1)),
        (f(0, 1), f(1, 2)),
        (f(1, 4), f(3, 4)),
        (f(1, 2), f(1, 1)),
    ];
    let mut out = Vec::new();
    for (t0, t1) in windows {
        for degree in 2..=4 {
            out.push(TestFunction {
                t0: t0.clone(),
                t1: t1.clone(),
                center: center.clone(),
                scale: scale.clone(),
                degree,
            });
        }
    }
    out
}

/// The centre and half-width of an interval containing every position of
/// the continuum and of the particles on `[0, T]`: the datum's support
/// widened by `T·max|u⁰|` and the artificial particle's offset.
pub fn support_window(continuum: &Continuum, t_end: &BigRational) -> (BigRational, BigRational) {
    let blocks = continuum.datum().blocks();
    let zero = BigRational::from_integer(0.into());
    let (lo, hi) = match (blocks.first(), blocks.last()) {
        (Some(f), Some(l)) => (f.from.clone(), l.to.clone()),
        _ => (zero.clone(), BigRational::from_integer(1.into())),
    };
    let umax = blocks.iter().fold(zero.clone(), |m, b| {
        let (a, c) = match &b.velocity {
            crate::quantile::BlockVelocity::Constant(c) => (c.clone(), c.clone()),
            crate::quantile::BlockVelocity::Affine(a, c) => (a.clone(), c.clone()),
        };
        max_of(max_of(m, abs(a)), abs(c))
    });
    let two = BigRational::from_integer(2.into());
    let center = (&lo + &hi) / &two;
    let half = (&hi - &lo) / &two + t_end * umax + BigRational::from_integer(1.into());
    (center, half)
}

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
struct Accumulator<S> {
    values: Vec<S>,
    terms: usize,
    scale: BigRational,
}

impl<S: Scalar> Accumulator<S> {
    fn new(k: usize) -> Self {
        Accumulator {
            values: vec![S::zero(); k],
            terms: 0,
            scale: BigRational::from_integer(BigInt::from(1) << RESIDUAL_BITS),
        }
    }
    fn add(&mut self, k: usize, v: S) {
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
    fn finish(self) -> Residuals<S> {
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

/// The largest `|Λ(t, w)|` over the segments outside the plateaus, where
/// `∂_w X > 1` (it must be 0: `(∂_w X − 1) Λ = 0` of `eq:Lagr-1`, whence
/// `(1 − ρ)p = 0`), evaluated at both ends of each segment.
pub fn complementarity_defect<V: Scalar>(profile: &Profile<V>) -> V {
    profile
        .segments
        .iter()
        .filter(|s| s.plateau.is_none())
        .flat_map(|s| {
            [s.w0.clone(), s.w1.clone()]
                .into_iter()
                .map(move |w| (s, w))
        })
        .map(|(s, w)| {
            abs(s.lambda[0].clone()
                + &(s.lambda[1].clone() * &w)
                + &(s.lambda[2].clone() * &w * &w))
        })
        .fold(V::zero(), max_of)
}

/// `t · sup ∂_x u` for the continuum profile (see the module
/// documentation); `None` when `u` jumps up with no gap in `X` (an
/// infinite `∂_x u`, violating `eq:Oleinik-Lagr`). A gap `|[X]| ≤ tol` is
/// treated as no gap: pass 0 for an exact profile, the rounding bound of
/// the profile for a rounded one (where `X`, continuous at a plateau end,
/// may come out with a gap of `±1e-16`).
pub fn oleinik_margin<V: Scalar>(profile: &Profile<V>, t: &V, tol: &V) -> Option<V> {
    let mut m = V::zero();
    let mut prev: Option<(V, V)> = None; // (X, U) at the previous right end
    for s in &profile.segments {
        if !s.x[1].is_zero() {
            m = max_of(m, t.clone() * &s.u[1] / &s.x[1]);
        }
        let xl = s.x[0].clone() + &(s.x[1].clone() * &s.w0);
        let ul = s.u[0].clone() + &(s.u[1].clone() * &s.w0);
        if let Some((xp, up)) = prev {
            let dx = xl.clone() - &xp;
            let du = ul.clone() - &up;
            if abs(dx.clone()).total_cmp(tol).is_le() {
                if du.total_cmp(tol).is_gt() {
                    return None;
                }
            } else {
                m = max_of(m, t.clone() * &du / &dx);
            }
        }
        prev = Some((
            s.x[0].clone() + &(s.x[1].clone() * &s.w1),
            s.u[0].clone() + &(s.u[1].clone() * &s.w1),
        ));
    }
    Some(m)
}

/// The continuum density `ρ(t, x)` (0 in vacuum, `1/∂_w X` on the image of
/// a segment; on a plateau, 1).
pub fn continuum_density<V: Scalar>(profile: &Profile<V>, x: &V) -> V {
    for s in &profile.segments {
        let a = s.x[0].clone() + &(s.x[1].clone() * &s.w0);
        let b = s.x[0].clone() + &(s.x[1].clone() * &s.w1);
        if a.total_cmp(x).is_le() && x.total_cmp(&b).is_lt() && !s.x[1].is_zero() {
            return V::one() / &s.x[1];
        }
    }
    V::zero()
}

/// The continuum velocity `u(t, x) = U(t, W(t, x))` on the support
/// (`None` in vacuum).
pub fn continuum_velocity<V: Scalar>(profile: &Profile<V>, x: &V) -> Option<V> {
    for s in &profile.segments {
        let a = s.x[0].clone() + &(s.x[1].clone() * &s.w0);
        let b = s.x[0].clone() + &(s.x[1].clone() * &s.w1);
        if a.total_cmp(x).is_le() && x.total_cmp(&b).is_lt() && !s.x[1].is_zero() {
            let w = (x.clone() - &s.x[0]) / &s.x[1];
            return Some(s.u[0].clone() + &(s.u[1].clone() * &w));
        }
    }
    None
}

/// The continuum momentum density `ρu(t, x)` (0 in vacuum), the density of
/// `X(t)#(U L¹)`.
pub fn continuum_momentum<V: Scalar>(profile: &Profile<V>, x: &V) -> V {
    match continuum_velocity(profile, x) {
        Some(u) => continuum_density(profile, x) * &u,
        None => V::zero(),
    }
}

/// `Λ(t, W(t, x))`, `W` the generalised inverse of `X(t)` (0 in vacuum and
/// outside the support): the Eulerian pressure potential, whose time
/// derivative is `p = ∂_t Λ(t, W(t, x))` (the remark after the proposition
/// "Eulerian formulation").
pub fn continuum_pressure_potential<V: Scalar>(profile: &Profile<V>, x: &V) -> V {
    for s in &profile.segments {
        let a = s.x[0].clone() + &(s.x[1].clone() * &s.w0);
        let b = s.x[0].clone() + &(s.x[1].clone() * &s.w1);
        if a.total_cmp(x).is_le() && x.total_cmp(&b).is_lt() && !s.x[1].is_zero() {
            let w = (x.clone() - &s.x[0]) / &s.x[1];
            return s.lambda[0].clone()
                + &(s.lambda[1].clone() * &w)
                + &(s.lambda[2].clone() * &w * &w);
        }
    }
    V::zero()
}

/// The particle pressure `p_N = (Id, X_N)#P_N` as its atoms
/// `(t_k, x_i(t_k), [λ_i]_k / N)` (mass of the pair `(i, i+1)` placed at
/// `x_i`, as `X_N = x_i` on the cell of `P_N = p_i`), for the collisions
/// with `t_k ≤ t_end` and non-zero jumps. Cost: the total size of the
/// merged clusters (up to `O(N²)`), so meant for pictures at moderate N.
pub fn particle_pressure_atoms<S: Scalar>(traj: &Trajectory<S>, t_end: &S) -> Vec<(S, S, S)> {
    let n = S::from_usize(traj.data().n());
    let pos = ClusterPositions::new(traj);
    let mut out = Vec::new();
    for imp in traj.impulses() {
        if imp.t.total_cmp(t_end).is_gt() {
            break;
        }
        for (k, jump) in imp.jumps().into_iter().enumerate() {
            if !jump.is_zero() {
                let i = imp.cluster.first + k;
                out.push((
                    imp.t.clone(),
                    pos.position(imp.cluster, i, &imp.t),
                    jump / &n,
                ));
            }
        }
    }
    out
}

/// The particle density `ρ̃_N(t, x) = 1/(N(x_i − x_{i−1}))` on
/// `[x_{i−1}, x_i)` (`X̃_N # L¹`), 0 elsewhere.
pub fn particle_density<S: Scalar>(snap: &Snapshot<S>, x: &S) -> S {
    let k = snap.x.partition_point(|xi| xi.total_cmp(x).is_le());
    if k == 0 || k > snap.n {
        return S::zero();
    }
    let slope = snap.dw_x_tilde(k);
    if slope.is_zero() {
        S::zero()
    } else {
        S::one() / &slope
    }
}

/// A density map `ρ(t_j, x_k)` on a grid, for heat maps.
#[derive(Debug, Clone, PartialEq)]
pub struct DensityGrid {
    /// The times (rows).
    pub times: Vec<f64>,
    /// The positions (columns).
    pub xs: Vec<f64>,
    /// `values[j][k] = ρ(times[j], xs[k])`, in `[0, 1]`.
    pub values: Vec<Vec<f64>>,
}

/// `x_k = x_min + (k + 1/2)(x_max − x_min)/nx` and
/// `t_j = j T/(nt − 1)`, rational.
fn grids(
    t_end: &BigRational,
    nt: usize,
    x_range: (&BigRational, &BigRational),
    nx: usize,
) -> (Vec<BigRational>, Vec<BigRational>) {
    let times = (0..nt)
        .map(|j| t_end * BigRational::new(BigInt::from(j), BigInt::from(nt.max(2) - 1)))
        .collect();
    let width = x_range.1 - x_range.0;
    let xs = (0..nx)
        .map(|k| {
            x_range.0
                + &width * BigRational::new(BigInt::from(2 * k + 1), BigInt::from(2 * nx.max(1)))
        })
        .collect();
    (times, xs)
}

/// The continuum density on an `nt × nx` grid over `[0, T] × [x_min, x_max]`
/// (the profile at each time is exact, then rounded).
pub fn continuum_density_grid(
    continuum: &Continuum,
    t_end: &BigRational,
    nt: usize,
    x_range: (&BigRational, &BigRational),
    nx: usize,
) -> Result<DensityGrid, Error> {
    let (times, xs) = grids(t_end, nt, x_range, nx);
    let xf: Vec<f64> = xs.iter().map(|x| x.to_f64_lossy()).collect();
    let mut values = Vec::with_capacity(times.len());
    for t in &times {
        let (p, _) = continuum.profile(t)?.to_f64();
        values.push(xf.iter().map(|x| continuum_density(&p, x)).collect());
    }
    Ok(DensityGrid {
        times: times.iter().map(|t| t.to_f64_lossy()).collect(),
        xs: xf,
        values,
    })
}

/// The particle density `ρ̃_N` on the same kind of grid.
pub fn particle_density_grid<S: Scalar>(
    traj: &Trajectory<S>,
    delta: &S,
    t_end: &BigRational,
    nt: usize,
    x_range: (&BigRational, &BigRational),
    nx: usize,
) -> Result<DensityGrid, Error> {
    let (times, xs) = grids(t_end, nt, x_range, nx);
    let conv = |q: &BigRational| {
        S::from_big_rational(q).ok_or_else(|| Error::Unsupported {
            message: format!("{} does not fit the scalar type", q.to_f64_lossy()),
        })
    };
    let xs_s: Vec<S> = xs.iter().map(conv).collect::<Result<_, _>>()?;
    let mut values = Vec::with_capacity(times.len());
    for t in &times {
        let s = traj.at(&conv(t)?)?;
        let snap = Snapshot::new(&s, traj.data().velocities(), delta.clone())?;
        values.push(
            xs_s.iter()
                .map(|x| particle_density(&snap, x).to_f64_lossy())
                .collect(),
        );
    }
    Ok(DensityGrid {
        times: times.iter().map(|t| t.to_f64_lossy()).collect(),
        xs: xs.iter().map(|x| x.to_f64_lossy()).collect(),
        values,
    })
}

/// Gauss–Legendre nodes and weights on `[−1, 1]`.
const GL5: [(f64, f64); 5] = [
    (0.0, 0.568_888_888_888_888_9),
    (-0.538_469_310_105_683_1, 0.478_628_670_499_366_47),
    (0.538_469_310_105_683_1, 0.478_628_670_499_366_47),
    (-0.906_179_845_938_664, 0.236_926_885_056_189_08),
    (0.906_179_845_938_664, 0.236_926_885_056_189_08),
];
const GL4: [(f64, f64); 4] = [
    (-0.339_981_043_584_856_26, 0.652_145_154_862_546_1),
    (0.339_981_043_584_856_26, 0.652_145_154_862_546_1),
    (-0.861_136_311_594_052_6, 0.347_854_845_137_453_85),
    (0.861_136_311_594_052_6, 0.347_854_845_137_453_85),
];

/// The continuum residuals of one test function at one time:
/// `(mass integrand, momentum integrand)` (the `w`-integrals, exact up to
/// rounding: 4 Gauss nodes per segment).
fn continuum_integrands(p: &Profile<f64>, f: &TestFunction<f64>, t: f64) -> (f64, f64) {
    let b = f.time_bump(&t);
    let db = f.time_bump_dt(&t);
    let (mut j1, mut j2, mut i1, mut i2, mut i3, mut i4) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    for s in &p.segments {
        let half = (s.w1 - s.w0) / 2.0;
        let mid = (s.w1 + s.w0) / 2.0;
        for (node, weight) in GL4 {
            let w = mid + half * node;
            let wt = weight * half;
            let x = s.x[0] + s.x[1] * w;
            let u = s.u[0] + s.u[1] * w;
            let l = s.lambda[0] + s.lambda[1] * w + s.lambda[2] * w * w;
            let (q0, q1, q2) = (f.space(&x, 0), f.space(&x, 1), f.space(&x, 2));
            j1 += wt * q0;
            j2 += wt * q1 * u;
            i1 += wt * q0 * u;
            i2 += wt * q1 * u * u;
            i3 += wt * l * q1;
            i4 += wt * l * u * q2;
        }
    }
    (db * j1 + b * j2, db * i1 + b * i2 - db * i3 - b * i4)
}

/// A quadrature result with its error estimate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Quadrature {
    /// The computed value.
    pub value: f64,
    /// The error estimate (panel doubling plus the skipped bisection
    /// intervals).
    pub error: f64,
}

fn rational(t: f64) -> Result<BigRational, Error> {
    BigRational::from_float(t).ok_or_else(|| Error::Unsupported {
        message: format!("time {t} is not finite"),
    })
}

/// Integrates the continuum residuals of `tests` over their windows with
/// `panels` panels (see the module documentation); test functions with the
/// same window share the quadrature nodes (one exact profile per node).
/// Returns, per test function, `(mass residual, momentum residual)`.
pub fn continuum_residuals(
    continuum: &Continuum,
    tests: &[TestFunction<BigRational>],
    panels: usize,
) -> Result<Vec<(Quadrature, Quadrature)>, Error> {
    let mut out = vec![
        (
            Quadrature {
                value: 0.0,
                error: 0.0
            },
            Quadrature {
                value: 0.0,
                error: 0.0
            }
        );
        tests.len()
    ];
    let mut done = vec![false; tests.len()];
    for k in 0..tests.len() {
        if done[k] {
            continue;
        }
        let group: Vec<usize> = (k..tests.len())
            .filter(|&j| tests[j].t0 == tests[k].t0 && tests[j].t1 == tests[k].t1)
            .collect();
        let fs: Vec<TestFunction<f64>> = group
            .iter()
            .map(|&j| {
                tests[j].convert::<f64>().ok_or_else(|| Error::Unsupported {
                    message: "test function does not fit f64".to_string(),
                })
            })
            .collect::<Result<_, _>>()?;
        let (t0, t1) = (&tests[k].t0, &tests[k].t1);
        let coarse = integrate_window(continuum, t0, t1, &fs, panels)?;
        let fine = integrate_window(continuum, t0, t1, &fs, 2 * panels)?;
        for (g, &j) in group.iter().enumerate() {
            let (c, f) = (coarse.0[g], fine.0[g]);
            out[j] = (
                Quadrature {
                    value: f.0,
                    error: (f.0 - c.0).abs() + fine.1,
                },
                Quadrature {
                    value: f.1,
                    error: (f.1 - c.1).abs() + fine.1,
                },
            );
            done[j] = true;
        }
    }
    Ok(out)
}

/// Per test function `(mass, momentum)` on the window `[t0, t1]`, and the
/// bound for the skipped bisection intervals.
#[allow(clippy::type_complexity)]
fn integrate_window(
    continuum: &Continuum,
    t0: &BigRational,
    t1: &BigRational,
    fs: &[TestFunction<f64>],
    panels: usize,
) -> Result<(Vec<(f64, f64)>, f64), Error> {
    let width = t1 - t0;
    let tol = &width / BigRational::from_integer(BigInt::from(1u64 << 40));
    let sig = |t: &BigRational| continuum.profile(t).map(|p| p.signature());
    let mut pieces: Vec<(BigRational, BigRational)> = Vec::new();
    let mut skipped = BigRational::from_integer(0.into());
    let panels = panels.max(1);
    let mut sig_a = sig(t0)?;
    for k in 0..panels {
        let a = t0 + &width * BigRational::new(BigInt::from(k), BigInt::from(panels));
        let b = t0 + &width * BigRational::new(BigInt::from(k + 1), BigInt::from(panels));
        let mut start = a.clone();
        let sig_b = sig(&b)?;
        let mut s0 = sig_a;
        let mut guard = 0;
        // Cut the panel where the plateau structure changes (up to 8 times).
        while s0 != sig_b && guard < 8 {
            guard += 1;
            let (mut lo, mut hi) = (start.clone(), b.clone());
            while &hi - &lo > tol {
                let mid = (&lo + &hi) / BigRational::from_integer(2.into());
                if sig(&mid)? == s0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            pieces.push((start.clone(), lo.clone()));
            skipped += &hi - &lo;
            start = hi;
            s0 = sig(&start)?;
        }
        pieces.push((start, b));
        sig_a = sig_b;
    }
    let mut sums = vec![(0.0, 0.0); fs.len()];
    let mut sup = 0.0f64;
    for (a, b) in pieces {
        let (af, bf) = (a.to_f64_lossy(), b.to_f64_lossy());
        let half = (bf - af) / 2.0;
        let mid = (bf + af) / 2.0;
        if half <= 0.0 {
            continue;
        }
        for (node, weight) in GL5 {
            let t = mid + half * node;
            let (p, _) = continuum.profile(&rational(t)?)?.to_f64();
            for (f, acc) in fs.iter().zip(sums.iter_mut()) {
                let (m1, m2) = continuum_integrands(&p, f, t);
                sup = sup.max(m1.abs()).max(m2.abs());
                acc.0 += weight * half * m1;
                acc.1 += weight * half * m2;
            }
        }
    }
    Ok((sums, 2.0 * sup * skipped.to_f64_lossy()))
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

    #[test]
    fn test_function_derivatives() {
        let q = |n: i64, d: i64| BigRational::new(n.into(), d.into());
        let f = TestFunction {
            t0: q(0, 1),
            t1: q(1, 1),
            center: q(1, 2),
            scale: q(2, 1),
            degree: 3,
        };
        assert_eq!(f.time_bump(&q(1, 2)), q(1, 1));
        assert_eq!(f.time_bump(&q(0, 1)), q(0, 1));
        assert_eq!(f.time_bump_dt(&q(1, 2)), q(0, 1));
        // Q = ((x − 1/2)/2)³: Q'(x) = 3(x − 1/2)²/8.
        assert_eq!(f.space(&q(3, 2), 1), q(3, 8));
        assert_eq!(f.space(&q(3, 2), 3), q(6, 8));
        assert_eq!(f.space(&q(3, 2), 4), q(0, 1));
    }
}
