//! The macroscopic data the scaling claims ([`super::scaling`]) run on, and
//! what is measured on each of them at each N, once.
//!
//! The data are the two shipped symmetric scenes (`appendix-c-two-blocks`,
//! `riemann-compression`) and [`RANDOM_DATA`] random `[macro]` data
//! admissible under `hyp:u0` ([`crate::generate::macro_datum`], fixed seed,
//! horizon `T = 1`): blocks of density exactly 1 next to dilute ones,
//! vacuum gaps, velocity jumps at block boundaries, affine velocities. Each
//! is sampled at `N = 4, 8, …, N_max` and its exact sticky history computed
//! by the integer event merge ([`crate::fast::merge::trajectory`], equal to
//! the generic `BigRational` one: the oracle battery checks it); every
//! quantity of a [`Row`] is then exact.
//!
//! The sampling is the paper's `x⁰_i = X⁰(i/N)`, `u⁰_i = U⁰(i/N)`; where
//! it puts two touching particles on a collision course (the corrected
//! `thm:main#sampling-contacts`), both take the congested side's value of
//! `U⁰` ([`admissible_sample`]).

use std::sync::{Arc, Mutex};

use num_rational::BigRational;
use num_traits::{Signed, ToPrimitive};

use super::Violation;
use crate::generate::{macro_datum, SplitMix64};
use crate::initial::InitialData;
use crate::limit::continuum::{Continuum, Profile, Segment};
use crate::limit::eulerian::{
    interpolated_mass_residuals, particle_momentum_residuals, support_window, test_family,
    TestFunction,
};
use crate::quantile::MacroDatum;
use crate::scalar::Scalar;
use crate::scene::{self, SceneKind};
use crate::trajectory::Trajectory;

type Q = BigRational;

/// The largest N at which [`Row::mass_interpolated`] is measured (its
/// cost is `O(N)` exact polynomial integrals per test function, on
/// collision times whose denominators grow with N: up to 27 s for one
/// datum at N = 4096, 3 s at N = 512).
pub const MASS_INTERPOLATED_MAX_N: usize = 512;

/// Random macroscopic data the scaling claims run on (besides the two
/// shipped scenes).
pub const RANDOM_DATA: usize = 16;

/// The shipped scenes, by name.
const SCENES: [&str; 2] = ["appendix-c-two-blocks", "riemann-compression"];

/// One macroscopic datum with its horizon and its exact continuum profiles
/// at the comparison times `T/4, T/2, 3T/4, T` (`None` where the profile is
/// irrational).
#[derive(Debug, Clone)]
pub struct MacroCase {
    /// The scene name, or the datum as the `blocks` of a `[macro]` scene.
    pub name: String,
    /// The datum.
    pub datum: MacroDatum,
    /// The horizon `T`.
    pub t_end: Q,
    /// `(t, X(t), Λ(t))` of the continuum solution at the comparison times.
    pub profiles: Vec<(Q, Option<Profile<Q>>)>,
    /// `X⁰`, `U⁰` as the continuum profile at `t = 0`.
    pub initial: Option<Profile<Q>>,
    /// The test functions `φ = B(t)Q(x)` of the weak residuals
    /// ([`test_family`] on the datum's [`support_window`]).
    pub tests: Vec<TestFunction<Q>>,
}

/// What is measured on one datum at one N (every value exact).
#[derive(Debug, Clone)]
pub struct Row {
    /// N.
    pub n: usize,
    /// `sup_{t ≤ T} sup_i |λ_i(t)|` over the probe times.
    pub lambda_sup: Q,
    /// `Σ_{t_k ≤ T} (1/N) Σ_i |[λ_i]_{t_k}|`: the total variation of the
    /// pressure measure, `‖P̃_N‖_{M(0,T; L¹)}`.
    pub pressure_abs: Q,
    /// The same sum without absolute values.
    pub pressure_signed: Q,
    /// `sup_t` of the sum of the squared `L²(0,1)` norms of the seven
    /// functions of `prop:L2-micro`: `X_N, X̃_N, ∂_t X_N, ∂_t X̃_N, Λ_N, Λ̃_N,
    /// ∂_w Λ̃_N` (`seven_norms`).
    pub l2: Q,
    /// `sup_{t ∈ [T/2, T]} Σ_i |u_i − u_{i−1}|`.
    pub tv_late: Q,
    /// `sup_t (‖U_N‖_∞ + ‖Ũ_N‖_∞) = 2 sup_t max_i |u_i(t)|`.
    pub u_sup: Q,
    /// `‖X⁰_N − X⁰‖²_{L²}` of the printed quantile sample.
    pub disc_x: Option<Q>,
    /// `‖U⁰_N − U⁰‖²_{L²}` of the printed quantile sample.
    pub disc_u: Option<Q>,
    /// `sup_w |X̃_N(0, w) − X⁰(w)|` over `w ∈ [0, 1]` (the artificial
    /// particle's cell included).
    pub uniform_x0: Q,
    /// `max ‖X_N(t) − X(t)‖²_{L²}` over the comparison times with a
    /// rational profile.
    pub cvg_x: Option<Q>,
    /// `max |∫_0^1 (Λ_N(t) − Λ(t)) φ|` over the comparison times with a
    /// rational profile and `φ ∈ {1, w}`.
    pub cvg_lambda: Option<Q>,
    /// `max_i |λ_i(t) − Λ(t, i/N)|`, the particles' multipliers against the
    /// continuum `Λ` at the nodes `w = i/N` (`λ_N = (1/N)Σ(u⁰_j − u_j)`),
    /// maximised over the comparison times with a rational profile
    /// (`lambda_node_gap`).
    pub lambda_nodes: Option<Q>,
    /// `N · sup_t |∫_0^1 (Λ_N − Λ̃_N)(t,w) w dw|` over the probe times: the
    /// factor of `‖∂_t Ψ‖` in `|⟨P_N − P̃_N, Ψ⟩| ≤ (C/N)‖∂_t Ψ‖` for
    /// `Ψ = ψ(t)w` (`lambda_gap_moment`).
    pub pn_gap: Q,
    /// `C'_0 = (x⁰_N − x⁰_0) + sup_i |u⁰_i|`, the smallest constant of
    /// `cond:Linfty` for the sample (artificial particle `x⁰_0 = x⁰_1 − 1/N − δ`,
    /// `δ = 1`, as in `prop:Linf-micro`).
    pub c0_prime: Q,
    /// `max_φ |R_mom^N(φ)|` over [`MacroCase::tests`] (the particles' weak
    /// momentum residual, [`particle_momentum_residuals`]), plus the bound on
    /// its dyadic accumulation error: an upper bound of the exact value.
    pub momentum: Q,
    /// `max_φ |R_N(φ)|` over [`MacroCase::tests`], `R_N(φ) = ∫∫ ρ̃_N ∂_t φ +
    /// m̃_N ∂_x φ` with `ρ̃_N = X̃_N#L¹`, `m̃_N = X̃_N#(U_N L¹)`
    /// ([`interpolated_mass_residuals`]), plus the bound on its dyadic
    /// accumulation error; `None` above [`MASS_INTERPOLATED_MAX_N`].
    pub mass_interpolated: Option<Q>,
}

/// One datum measured across N.
#[derive(Debug, Clone)]
pub struct Series {
    /// The datum's name.
    pub name: String,
    /// One row per N, increasing.
    pub rows: Vec<Row>,
}

fn q(n: i64, d: i64) -> Q {
    Q::new(n.into(), d.into())
}

fn abs(x: Q) -> Q {
    if x < Q::zero() {
        -x
    } else {
        x
    }
}

fn max(a: Q, b: Q) -> Q {
    if b > a {
        b
    } else {
        a
    }
}

/// The data: the shipped scenes, then the random ones (fewest blocks
/// first).
pub fn cases(id: &'static str) -> Result<Vec<MacroCase>, Violation> {
    let mut out = Vec::new();
    for name in SCENES {
        let text = scene::shipped(name)
            .ok_or_else(|| Violation::new(id, format!("{name} is not a shipped scene")))?;
        let s = scene::parse(text).map_err(|e| Violation::new(id, format!("{name}: {e}")))?;
        let t_end = s.t_end.clone().unwrap_or_else(Q::one);
        let SceneKind::Macro { datum, .. } = s.kind else {
            return Err(Violation::new(id, format!("{name} is not a macro scene")));
        };
        out.push(case(name.to_string(), datum, t_end));
    }
    let mut rng = SplitMix64::new(0x005C_A1E5);
    let mut random: Vec<MacroDatum> = (0..RANDOM_DATA)
        .map(|_| macro_datum(&rng.bytes(40)))
        .collect();
    random.sort_by_key(|d| d.blocks().len());
    for datum in random {
        out.push(case(
            super::sampling::render_blocks(&datum),
            datum,
            Q::one(),
        ));
    }
    Ok(out)
}

fn case(name: String, datum: MacroDatum, t_end: Q) -> MacroCase {
    let c = Continuum::new(&datum);
    let profiles = (1..=4)
        .map(|k| {
            let t = t_end.clone() * q(k, 4);
            let p = c.profile(&t).ok().and_then(|p| p.to_rational());
            (t, p)
        })
        .collect();
    let initial = c.profile(&Q::zero()).ok().and_then(|p| p.to_rational());
    let (center, scale) = support_window(&c, &t_end);
    let tests = test_family(&t_end, &center, &scale);
    MacroCase {
        name,
        datum,
        t_end,
        profiles,
        initial,
        tests,
    }
}

/// The quantile sample `x⁰_i = X⁰(i/N)`, `u⁰_i = U⁰(i/N)`, radius
/// `1/(2N)`, except that two touching particles (`x⁰_{i+1} − x⁰_i = 1/N`)
/// both take `U⁰` at the middle of the congested interval between them,
/// the congested side's value (corrected `thm:main#sampling-contacts`).
pub fn admissible_sample(d: &MacroDatum, n: usize) -> Result<InitialData<Q>, String> {
    let (x, mut u) = d.quantiles(n).map_err(|e| e.to_string())?;
    let nn = Q::from_usize(n);
    let inv = nn.recip();
    for i in 0..n.saturating_sub(1) {
        if x[i + 1].clone() - &x[i] == inv {
            // Particles i+1, i+2 (1-based) at w = (i+1)/N, (i+2)/N.
            let mid = d.u0(&(Q::from_usize(2 * i + 3) / (Q::from_i64(2) * &nn)));
            u[i] = mid.clone();
            u[i + 1] = mid;
        }
    }
    InitialData::new(inv / Q::from_i64(2), x, u).map_err(|e| e.to_string())
}

/// The N values `4, 8, …, max_n` (at least `4, 8`).
pub fn ns(max_n: usize) -> Vec<usize> {
    let mut v = Vec::new();
    let mut n = 4;
    while n <= max_n.max(8) {
        v.push(n);
        n *= 2;
    }
    v
}

/// `Σ_{k=1}^{s} |a + k d|` and `Σ_{k=1}^{s} (a + k d)`, exact.
fn progression_sums(a: &Q, d: &Q, s: usize) -> (Q, Q) {
    // Σ_{k=p}^{r} (a + k d).
    let sum = |a: &Q, d: &Q, p: usize, r: usize| -> Q {
        if r < p {
            return Q::zero();
        }
        let cnt = Q::from_usize(r - p + 1);
        cnt.clone() * a + d.clone() * Q::from_usize(p + r) * cnt / Q::from_i64(2)
    };
    let signed = sum(a, d, 1, s);
    if d.is_zero() {
        return (abs(a.clone()) * Q::from_usize(s), signed);
    }
    // |a + k d| = |a2 + k d2| with d2 > 0: the terms increase, and the
    // first j of them (k < −a2/d2) are negative.
    let (a2, d2) = if *d < Q::zero() {
        (-a.clone(), -d.clone())
    } else {
        (a.clone(), d.clone())
    };
    let bound = (-a2.clone() / &d2).ceil().to_integer() - num_bigint::BigInt::from(1);
    let j = if bound.is_negative() {
        0
    } else {
        bound.to_usize().unwrap_or(s).min(s)
    };
    let absolute = sum(&a2, &d2, j + 1, s) - sum(&a2, &d2, 1, j);
    (absolute, signed)
}

/// `(Σ|jumps|, Σ jumps)` of the pressure over the collisions `t ≤ T`,
/// divided by N: jumps are affine in the index on each merging part
/// ([`crate::contact::Impulse::jumps`]), summed in closed form.
fn pressure(traj: &Trajectory<Q>, t_end: &Q) -> (Q, Q) {
    let mut total_abs = Q::zero();
    let mut total = Q::zero();
    for imp in traj.impulses().iter().filter(|i| i.t <= *t_end) {
        let nn = Q::from_usize(imp.n);
        let mut acc = Q::zero();
        for (part, v) in imp.parts.iter().zip(&imp.part_velocities) {
            let step = (v.clone() - &imp.velocity) / &nn;
            let (a, s) = progression_sums(&acc, &step, part.size);
            total_abs += a;
            total += s;
            acc += step * Q::from_usize(part.size);
        }
    }
    let nn = Q::from_usize(traj.data().n());
    (total_abs / &nn, total / nn)
}

/// `∫_0^1 Λ(w) w^k dw` (`k = 0, 1`) of a rational profile.
fn lambda_moment(p: &Profile<Q>, k: i32) -> Q {
    let mut total = Q::zero();
    for s in &p.segments {
        for (j, c) in s.lambda.iter().enumerate() {
            let e = j as i32 + k + 1;
            let pw = |w: &Q| -> Q { (0..e).fold(Q::one(), |acc, _| acc * w) };
            total += c.clone() * (pw(&s.w1) - pw(&s.w0)) / Q::from_i64(i64::from(e));
        }
    }
    total
}

/// `∫_0^1 Λ_N w^k dw` (`k = 0, 1`) with `Λ_N = λ_i` on `((i−1)/N, i/N]`
/// (`λ_N` last): `(1/N) Σ λ_i` and `Σ λ_i (2i − 1)/(2N²)`.
fn lambda_n_moment(lambda: &[Q], k: i32) -> Q {
    let n = lambda.len();
    let mut s = Sum::default();
    for (i, l) in lambda.iter().enumerate() {
        if k == 0 {
            s.add(l.clone());
        } else {
            s.add(l.clone() * Q::from_usize(2 * i + 1));
        }
    }
    let nn = Q::from_usize(n);
    if k == 0 {
        s.total() / nn
    } else {
        s.total() / (Q::from_i64(2) * &nn * nn)
    }
}

/// `sup_{w ∈ [0, 1]} |X̃_N(0, w) − X⁰(w)|`, the artificial particle's cell
/// `[0, 1/N]` included (`df:x0`: `x_0 = x_1 − 1/N − δ`, `δ = 1`, so that
/// `X̃_N(0, 0) = x_0`): both are affine between consecutive points of
/// `{i/N} ∪ {mass breakpoints}`, so the sup is over their one-sided values
/// there.
fn uniform_x0(d: &MacroDatum, x: &[Q]) -> Q {
    let n = x.len();
    let nn = Q::from_usize(n);
    // x_0, x_1, …, x_N: the artificial particle first.
    let mut full = Vec::with_capacity(n + 1);
    full.push(x[0].clone() - nn.recip() - Q::one());
    full.extend_from_slice(x);
    let breaks = d.mass_breakpoints();
    let mut sup = Q::zero();
    for i in 1..=n {
        let (a, b) = (Q::from_usize(i - 1) / &nn, Q::from_usize(i) / &nn);
        // Without a mass breakpoint in [a, b], X⁰ is affine on the cell and
        // X̃_N(0) interpolates it at both ends (x_i = X⁰(i/N)): equal —
        // except on the first cell, whose left end is the artificial x_0.
        if i > 1 && !breaks.iter().any(|m| *m >= a && *m <= b) {
            continue;
        }
        let mut cuts = vec![a.clone()];
        cuts.extend(breaks.iter().filter(|m| **m > a && **m < b).cloned());
        cuts.push(b);
        // X̃_N on [a, b]: x_{i−1} + N (w − a)(x_i − x_{i−1}).
        let tilde =
            |w: &Q| full[i - 1].clone() + (w.clone() - &a) * &nn * (full[i].clone() - &full[i - 1]);
        for w in cuts.windows(2) {
            let h = w[1].clone() - &w[0];
            let eps = h.clone() / Q::from_i64(4);
            let f1 = d.x0(&(w[0].clone() + &eps));
            let f2 = d.x0(&(w[1].clone() - &eps));
            let slope = (f2 - &f1) / (h / Q::from_i64(2));
            let left = f1 - slope.clone() * &eps;
            let right = left.clone() + slope * (w[1].clone() - &w[0]);
            sup = max(sup, abs(tilde(&w[0]) - left));
            sup = max(sup, abs(tilde(&w[1]) - right));
        }
    }
    sup
}

/// `max_i |λ_i − Λ(i/N)|` for the multipliers `λ_1 … λ_N` of one state and
/// the continuum profile at the same time: `Λ` is quadratic on each
/// segment, evaluated at the nodes `i/N` in increasing order (one pass
/// over the segments; `Λ` is continuous, so a node on a segment end may be
/// read from either side).
fn lambda_node_gap(l: &[Q], p: &Profile<Q>) -> Q {
    let nn = Q::from_usize(l.len());
    let mut k = 0usize;
    let mut sup = Q::zero();
    for (i, li) in l.iter().enumerate() {
        let w = Q::from_usize(i + 1) / &nn;
        while k + 1 < p.segments.len() && p.segments[k].w1 < w {
            k += 1;
        }
        let Some(s) = p.segments.get(k) else {
            return sup;
        };
        let lam = s.lambda[0].clone() + (s.lambda[1].clone() + s.lambda[2].clone() * &w) * &w;
        sup = max(sup, abs(li.clone() - lam));
    }
    sup
}

/// `∫_0^1 (Λ_N − Λ̃_N)(t,w) w dw` from `λ_1 … λ_N` (`λ_0 = 0`): on cell `i`,
/// `w = (i−1)/N + s/N`, `Λ_N − Λ̃_N = d_i (1 − s)` with `d_i = λ_i − λ_{i−1}`,
/// so the cell gives `d_i ((i−1)/(2N²) + 1/(6N²))`. (Against `Ψ = ψ(t)`
/// alone the integral is `(λ_N − λ_0)/(2N) = 0`: `w` is the first test
/// that sees the difference.)
fn lambda_gap_moment(l: &[Q]) -> Q {
    let n = l.len();
    let nn = Q::from_usize(n);
    let mut sum = Sum::default();
    for i in 0..n {
        let prev = if i == 0 { Q::zero() } else { l[i - 1].clone() };
        let d = l[i].clone() - prev;
        sum.add(d * (Q::from_usize(3 * i + 1)));
    }
    sum.total() / (Q::from_i64(6) * &nn * &nn)
}

/// `∫_{(i−1)/N}^{i/N} f²` for `f` affine from `a` to `b`: `(a² + ab + b²)/(3N)`
/// (without the factor `1/N`, applied once by the caller).
fn affine_sq(a: &Q, b: &Q) -> Q {
    (a.clone() * a + a.clone() * b + b.clone() * b) / Q::from_i64(3)
}

/// The sum of the squared `L²(0,1)` norms of the seven functions of
/// `prop:L2-micro` at one instant, from the positions `x_1 … x_N`, the
/// velocities `u_1 … u_N` and the multipliers `λ_1 … λ_N`: the constant
/// interpolations `X_N, ∂_t X_N = U_N, Λ_N` (value `x_i, u_i, λ_i` on
/// `((i−1)/N, i/N]`), the affine ones `X̃_N, ∂_t X̃_N = Ũ_N, Λ̃_N` (from
/// `x_0 = x_1 − 1/N − δ` with `δ = 1`, `u_0 = u_1` — the artificial particle
/// moves with particle 1 — and `λ_0 = 0`, `df:x0`), and `∂_w Λ̃_N = N(λ_i −
/// λ_{i−1})` on each cell.
fn seven_norms(x: &[Q], u: &[Q], l: &[Q]) -> Q {
    let n = x.len();
    debug_assert!(u.len() == n && l.len() == n, "one x, u and λ per particle");
    let nn = Q::from_usize(n);
    let x0 = x[0].clone() - nn.recip() - Q::one();
    let (mut constant, mut affine, mut slope) = (Sum::default(), Sum::default(), Sum::default());
    for i in 0..n {
        let (xp, up, lp) = if i == 0 {
            (&x0, &u[0], &Q::zero())
        } else {
            (&x[i - 1], &u[i - 1], &l[i - 1])
        };
        constant.add(x[i].clone() * &x[i] + u[i].clone() * &u[i] + l[i].clone() * &l[i]);
        affine.add(affine_sq(xp, &x[i]) + affine_sq(up, &u[i]) + affine_sq(lp, &l[i]));
        let d = l[i].clone() - lp;
        slope.add(d.clone() * d);
    }
    // (1/N) Σ per cell, and ‖∂_w Λ̃_N‖² = (1/N) Σ N²(λ_i − λ_{i−1})².
    (constant.total() + affine.total()) / &nn + slope.total() * nn
}

/// An exact sum that adds numerators over equal denominators first (the
/// values of one cluster share theirs), so that the running sum does not
/// carry the lcm of every denominator through N reductions.
#[derive(Default)]
struct Sum(std::collections::HashMap<num_bigint::BigInt, num_bigint::BigInt>);

impl Sum {
    fn add(&mut self, x: Q) {
        let (n, d) = x.into_raw();
        *self.0.entry(d).or_default() += n;
    }
    /// Adds `x²` (reduced as `x` is: no gcd needed).
    fn add_square(&mut self, x: &Q) {
        *self.0.entry(x.denom() * x.denom()).or_default() += x.numer() * x.numer();
    }
    fn total(self) -> Q {
        self.0
            .into_iter()
            .fold(Q::zero(), |a, (d, n)| a + Q::new(n, d))
    }
}

/// `∫_0^1 (V_N − V)²` for `V_N = v_i` on `(i/N, (i+1)/N)` (0-based) and `V`
/// affine on each segment of a rational profile (`coef` picks `X` or `U`).
/// A cell cut by a segment end is integrated directly (`∫ g² = h(g₀² + g₀g₁
/// + g₁²)/3` for the affine `g`); the cells `i₀ ≤ i < i₁` inside a segment
/// `V = A + Bw` in closed form, `(1/N)Σ(v_i − A − Bm_i)² + (i₁ − i₀)B²/(12N³)`
/// (`m_i = (2i+1)/(2N)`), expanded into sums of `v_i²`, `v_i`, `(2i+1)v_i`.
fn l2_sq(v: &[Q], p: &Profile<Q>, coef: fn(&Segment<Q>) -> &[Q; 2]) -> Q {
    let n = v.len();
    let nn = Q::from_usize(n);
    let h = nn.recip();
    let three = Q::from_i64(3);
    let mut tot = Sum::default();
    let mut squares = Sum::default();
    let partial = |tot: &mut Sum, i: usize, lo: &Q, hi: &Q, c: &[Q; 2]| {
        if i < n && hi > lo {
            let g0 = v[i].clone() - &c[0] - c[1].clone() * lo;
            let g1 = v[i].clone() - &c[0] - c[1].clone() * hi;
            tot.add((hi.clone() - lo) * (g0.clone() * &g0 + g0 * &g1 + g1.clone() * &g1) / &three);
        }
    };
    // Σ_{i < k} (2i + 1)² = k(2k − 1)(2k + 1)/3.
    let odd_sq = |k: usize| {
        Q::from_usize(k) * Q::from_usize(2 * k + 1) * Q::from_i64(2 * k as i64 - 1) / &three
    };
    for seg in &p.segments {
        let c = coef(seg);
        let (f0, f1) = (seg.w0.clone() * &nn, seg.w1.clone() * &nn);
        let to_usize = |x: Q| x.to_integer().to_usize().unwrap_or(n).min(n);
        let (i_lo, i_hi) = (to_usize(f0.ceil()), to_usize(f1.floor()));
        let edge = Q::from_usize(i_lo) * &h;
        if !f0.is_integer() {
            let hi = if seg.w1 < edge { seg.w1.clone() } else { edge };
            partial(&mut tot, to_usize(f0.floor()), &seg.w0, &hi, c);
        }
        if i_lo < i_hi {
            let (a, b) = (&c[0], &c[1]);
            let (mut s1, mut s2) = (Sum::default(), Sum::default());
            for i in i_lo..i_hi {
                squares.add_square(&v[i]);
                s1.add(v[i].clone());
                s2.add(v[i].clone() * Q::from_usize(2 * i + 1));
            }
            let cnt = Q::from_usize(i_hi - i_lo);
            let (i0, i1) = (Q::from_usize(i_lo), Q::from_usize(i_hi));
            tot.add(-Q::from_i64(2) * &h * a * s1.total());
            tot.add(-h.clone() * &h * b * s2.total());
            tot.add(
                h.clone()
                    * (cnt.clone() * a * a
                        + a.clone() * b * (i1.clone() * &i1 - i0.clone() * &i0) / &nn
                        + b.clone() * b * (odd_sq(i_hi) - odd_sq(i_lo))
                            / (Q::from_i64(4) * &nn * &nn)),
            );
            tot.add(cnt * b * b * &h * &h * &h / Q::from_i64(12));
        }
        if i_lo <= i_hi && !f1.is_integer() {
            partial(&mut tot, i_hi, &(Q::from_usize(i_hi) * &h), &seg.w1, c);
        }
    }
    tot.add(squares.total() * h);
    tot.total()
}

fn row(c: &MacroCase, n: usize, id: &'static str) -> Result<Row, Violation> {
    let data = admissible_sample(&c.datum, n)
        .map_err(|e| Violation::new(id, format!("{}, N = {n}: {e}", c.name)))?;
    row_of(c, &crate::fast::merge::trajectory(&data), id)
}

/// The [`Row`] of one datum at one N from its computed history `traj`
/// (unit tests pass a corrupted history here, to show the scaling
/// checkers reject it).
fn row_of(c: &MacroCase, traj: &Trajectory<Q>, id: &'static str) -> Result<Row, Violation> {
    let data = traj.data();
    let n = data.n();
    let fail = |e: String| Violation::new(id, format!("{}, N = {n}: {e}", c.name));
    let u0 = data.velocities().to_vec();
    let nn = Q::from_usize(n);
    let alpha = c.t_end.clone() / Q::from_i64(2);
    let (mut lambda_sup, mut l2, mut tv_late, mut u_sup) =
        (Q::zero(), Q::zero(), Q::zero(), Q::zero());
    let mut cvg_x: Option<Q> = None;
    let mut cvg_lambda: Option<Q> = None;
    let mut lambda_nodes: Option<Q> = None;
    let mut pn_gap = Q::zero();
    // t = kT/4, k = 0 … 4: the comparison times and 0.
    let probes = std::iter::once((Q::zero(), None))
        .chain(c.profiles.iter().map(|(t, p)| (t.clone(), p.as_ref())));
    for (t, profile) in probes {
        let s = traj.at(&t).map_err(|e| fail(e.to_string()))?;
        // λ_1 … λ_{N−1} as the state has them; λ_N = (1/N) Σ (u⁰_j − u_j).
        let mut l = s.multipliers.clone();
        let mut ln = Sum::default();
        for (a, b) in u0.iter().zip(&s.velocities) {
            ln.add(a.clone() - b);
        }
        l.push(ln.total() / &nn);
        for v in &l {
            lambda_sup = max(lambda_sup, abs(v.clone()));
        }
        for v in &s.velocities {
            u_sup = max(u_sup, abs(v.clone()) * Q::from_i64(2));
        }
        l2 = max(l2, seven_norms(&s.positions, &s.velocities, &l));
        pn_gap = max(pn_gap, abs(lambda_gap_moment(&l)) * &nn);
        if t >= alpha {
            let mut tv = Sum::default();
            for w in s.velocities.windows(2) {
                tv.add(abs(w[1].clone() - &w[0]));
            }
            tv_late = max(tv_late, tv.total());
        }
        if let Some(p) = profile {
            let dx = l2_sq(&s.positions, p, |s| &s.x);
            cvg_x = Some(max(cvg_x.unwrap_or_else(Q::zero), dx));
            let gap = lambda_node_gap(&l, p);
            lambda_nodes = Some(max(lambda_nodes.unwrap_or_else(Q::zero), gap));
            for k in 0..2 {
                let d = abs(lambda_n_moment(&l, k) - lambda_moment(p, k));
                cvg_lambda = Some(max(cvg_lambda.unwrap_or_else(Q::zero), d));
            }
        }
    }
    let (pressure_abs, pressure_signed) = pressure(traj, &c.t_end);
    // cond:Linfty: x⁰_N − x⁰_0 = x⁰_N − x⁰_1 + 1/N + δ (δ = 1).
    let x0 = data.positions();
    let spread0 = x0[n - 1].clone() - &x0[0] + nn.recip() + Q::one();
    let c0_prime = spread0 + u0.iter().fold(Q::zero(), |m, v| max(m, abs(v.clone())));
    let residuals =
        particle_momentum_residuals(traj, &c.tests, &c.t_end).map_err(|e| fail(e.to_string()))?;
    let rounding = Q::from_float(residuals.rounding_bound)
        .ok_or_else(|| fail("rounding bound not finite".into()))?;
    let momentum = residuals
        .values
        .into_iter()
        .fold(Q::zero(), |m, v| max(m, abs(v)))
        + rounding;
    let mass_interpolated = if n <= MASS_INTERPOLATED_MAX_N {
        let r = interpolated_mass_residuals(traj, &c.tests, &c.t_end)
            .map_err(|e| fail(e.to_string()))?;
        let rounding = Q::from_float(r.rounding_bound)
            .ok_or_else(|| fail("rounding bound not finite".into()))?;
        Some(r.values.into_iter().fold(Q::zero(), |m, v| max(m, abs(v))) + rounding)
    } else {
        None
    };
    let (qx, qu) = c.datum.quantiles(n).map_err(|e| fail(e.to_string()))?;
    let (disc_x, disc_u) = match &c.initial {
        Some(p) => (Some(l2_sq(&qx, p, |s| &s.x)), Some(l2_sq(&qu, p, |s| &s.u))),
        None => (None, None),
    };
    Ok(Row {
        n,
        lambda_sup,
        pressure_abs,
        pressure_signed,
        l2,
        tv_late,
        u_sup,
        disc_x,
        disc_u,
        uniform_x0: uniform_x0(&c.datum, &qx),
        cvg_x,
        cvg_lambda,
        lambda_nodes,
        pn_gap,
        c0_prime,
        momentum,
        mass_interpolated,
    })
}

type Cache = Mutex<Vec<(usize, Arc<Vec<Series>>)>>;
static TABLE: Cache = Mutex::new(Vec::new());

/// Every datum measured at `N = 4 … max_n` (computed once per `max_n` and
/// kept: every scaling claim reads the same table).
pub fn table(max_n: usize, id: &'static str) -> Result<Arc<Vec<Series>>, Violation> {
    if let Ok(cache) = TABLE.lock() {
        if let Some((_, t)) = cache.iter().find(|(m, _)| *m == max_n) {
            return Ok(t.clone());
        }
    }
    let mut out = Vec::new();
    for c in cases(id)? {
        let rows = ns(max_n)
            .into_iter()
            .map(|n| row(&c, n, id))
            .collect::<Result<Vec<_>, _>>()?;
        out.push(Series { name: c.name, rows });
    }
    let t = Arc::new(out);
    if let Ok(mut cache) = TABLE.lock() {
        cache.push((max_n, t.clone()));
    }
    Ok(t)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `∫(Λ_N − Λ̃_N) w dw` by hand: N = 2, λ = (1, 0): cell 1 (d = 1) gives
    /// 1·(0 + 1/24), cell 2 (d = −1) gives −1·(1/8 + 1/24): total −1/8.
    #[test]
    fn lambda_gap_moment_by_hand() {
        assert_eq!(lambda_gap_moment(&[q(1, 1), q(0, 1)]), q(-1, 8));
        assert_eq!(lambda_gap_moment(&[q(0, 1), q(0, 1)]), q(0, 1));
    }

    /// The seven norms on one particle by hand: x_1 = 0, u_1 = 1, λ_1 = 0,
    /// so x_0 = −2 (δ = 1, 1/N = 1), u_0 = 1, λ_0 = 0: constant parts
    /// 0 + 1 + 0, affine parts (4 + 0 + 0)/3 + (1 + 1 + 1)/3 + 0, slope 0.
    /// One segment, Λ(w) = w(1 − w): at N = 2 the nodes are 1/2 (Λ = 1/4)
    /// and 1 (Λ = 0); λ = (1/4, 1/8) misses the second by 1/8.
    #[test]
    fn lambda_node_gap_by_hand() {
        use crate::limit::continuum::Segment;
        let seg = Segment {
            w0: q(0, 1),
            w1: q(1, 1),
            block: 0,
            x: [q(0, 1), q(1, 1)],
            u: [q(0, 1), q(0, 1)],
            lambda: [q(0, 1), q(1, 1), q(-1, 1)],
            plateau: None,
        };
        let p = Profile {
            t: q(1, 1),
            segments: vec![seg],
            plateaus: vec![],
        };
        assert_eq!(lambda_node_gap(&[q(1, 4), q(1, 8)], &p), q(1, 8));
        assert_eq!(lambda_node_gap(&[q(1, 4), q(0, 1)], &p), q(0, 1));
    }

    #[test]
    fn seven_norms_by_hand() {
        let z = Q::zero();
        let one = Q::one();
        assert_eq!(
            seven_norms(&[Q::zero()], &[one], &[z]),
            q(10, 3),
            "‖X_N‖² + ‖X̃_N‖² + ‖U_N‖² + ‖Ũ_N‖² + ‖Λ_N‖² + ‖Λ̃_N‖² + ‖∂_wΛ̃_N‖²"
        );
        // Two particles, λ = (1, 0): ‖∂_w Λ̃_N‖² = (1/2)·4·(1 + 1) = 4 of it.
        let x = [q(0, 1), q(1, 2)];
        let u = [q(0, 1), q(0, 1)];
        let with = seven_norms(&x, &u, &[q(1, 1), q(0, 1)]);
        let without = seven_norms(&x, &u, &[q(0, 1), q(0, 1)]);
        // Λ_N: (1/2)(1); Λ̃_N: (1/2)(1/3 + 1/3); ∂_w Λ̃_N: 2(1 + 1).
        assert_eq!(with - without, q(1, 2) + q(1, 3) + q(4, 1));
    }

    #[test]
    fn progression_sums_match_the_terms() {
        for (a, d, s) in [
            (q(-3, 2), q(1, 1), 5),
            (q(2, 1), q(-1, 3), 9),
            (q(0, 1), q(0, 1), 3),
        ] {
            let terms: Vec<Q> = (1..=s)
                .map(|k| a.clone() + d.clone() * Q::from_usize(k))
                .collect();
            let (ab, si) = progression_sums(&a, &d, s);
            assert_eq!(si, terms.iter().fold(Q::zero(), |x, y| x + y));
            assert_eq!(ab, terms.iter().fold(Q::zero(), |x, y| x + abs(y.clone())));
        }
    }

    #[test]
    fn pressure_matches_the_materialised_jumps() {
        let c = &cases("test").unwrap()[3];
        let data = admissible_sample(&c.datum, 32).unwrap();
        let traj = crate::fast::merge::trajectory(&data);
        let (ab, si) = pressure(&traj, &c.t_end);
        let nn = Q::from_usize(32);
        let jumps: Vec<Q> = traj
            .impulses()
            .iter()
            .filter(|i| i.t <= c.t_end)
            .flat_map(|i| i.jumps())
            .collect();
        assert_eq!(si, jumps.iter().fold(Q::zero(), |x, y| x + y) / &nn);
        assert_eq!(
            ab,
            jumps.iter().fold(Q::zero(), |x, y| x + abs(y.clone())) / nn
        );
    }

    /// `prop:pressure-bound` (sign-aware): a history whose collisions list
    /// their parts' velocities right to left (a plausible bug of the event
    /// merge) has negative pressure jumps; measured through the same
    /// [`row_of`] as the true history, the scaling checker rejects it
    /// (a check of `Σ|[λ_i]|` alone, or of its square, would not).
    #[test]
    fn a_history_with_negative_pressure_jumps_is_rejected() {
        use crate::contact::Impulse;
        const ID: &str = "prop:pressure-bound";
        let c = &cases("test").unwrap()[0];
        let mut good = Vec::new();
        let mut bad = Vec::new();
        for n in [4usize, 8, 16] {
            let data = admissible_sample(&c.datum, n).unwrap();
            let traj = crate::fast::merge::trajectory(&data);
            let imps: Vec<Impulse<Q>> = traj
                .impulses()
                .iter()
                .map(|imp| {
                    let mut pv = imp.part_velocities.clone();
                    pv.reverse();
                    Impulse {
                        part_velocities: pv,
                        ..imp.clone()
                    }
                })
                .collect();
            let reversed = Trajectory::from_parts(data.clone(), traj.join_times().to_vec(), imps);
            good.push(row_of(c, &traj, ID).unwrap());
            bad.push(row_of(c, &reversed, ID).unwrap());
        }
        let table = |rows: Vec<Row>| {
            vec![Series {
                name: c.name.clone(),
                rows,
            }]
        };
        super::super::scaling::pressure_on(&table(good)).unwrap();
        let err = super::super::scaling::pressure_on(&table(bad)).unwrap_err();
        assert!(err.witness.contains("not a non-negative measure"), "{err}");
    }

    #[test]
    fn the_statements_say_what_is_run() {
        let claims = crate::claims::registry::<BigRational>();
        let c = claims.iter().find(|c| c.id == "prop:L2-micro").unwrap();
        assert!(c.statement.contains(&format!("{RANDOM_DATA} random")));
        assert!(c.statement.contains(&format!(
            "{}",
            crate::claims::ledger::Budget::default().scaling_max_n
        )));
    }
}
