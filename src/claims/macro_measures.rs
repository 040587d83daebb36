//! The exact measures of [`super::macro_data`]'s rows: closed-form sums
//! over the particles (pressure jumps, `Λ_N` moments, `L²` distances to a
//! rational profile, the seven norms of `prop:L2-micro`), each computed
//! without rounding.

use num_rational::BigRational;
use num_traits::{Signed, ToPrimitive};

use crate::limit::continuum::{Profile, Segment};
use crate::quantile::MacroDatum;
use crate::scalar::Scalar;
use crate::trajectory::Trajectory;

type Q = BigRational;

pub(super) fn abs(x: Q) -> Q {
    if x < Q::zero() {
        -x
    } else {
        x
    }
}

pub(super) fn max(a: Q, b: Q) -> Q {
    if b > a {
        b
    } else {
        a
    }
}

/// `Σ_{k=1}^{s} |a + k d|` and `Σ_{k=1}^{s} (a + k d)`, exact.
pub(super) fn progression_sums(a: &Q, d: &Q, s: usize) -> (Q, Q) {
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
pub(super) fn pressure(traj: &Trajectory<Q>, t_end: &Q) -> (Q, Q) {
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
pub(super) fn lambda_moment(p: &Profile<Q>, k: i32) -> Q {
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
pub(super) fn lambda_n_moment(lambda: &[Q], k: i32) -> Q {
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
pub(super) fn uniform_x0(d: &MacroDatum, x: &[Q]) -> Q {
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
pub(super) fn lambda_node_gap(l: &[Q], p: &Profile<Q>) -> Q {
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
pub(super) fn lambda_gap_moment(l: &[Q]) -> Q {
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
pub(super) fn affine_sq(a: &Q, b: &Q) -> Q {
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
pub(super) fn seven_norms(x: &[Q], u: &[Q], l: &[Q]) -> Q {
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
pub(super) struct Sum(std::collections::HashMap<num_bigint::BigInt, num_bigint::BigInt>);

impl Sum {
    pub(super) fn add(&mut self, x: Q) {
        let (n, d) = x.into_raw();
        *self.0.entry(d).or_default() += n;
    }
    /// Adds `x²` (reduced as `x` is: no gcd needed).
    pub(super) fn add_square(&mut self, x: &Q) {
        *self.0.entry(x.denom() * x.denom()).or_default() += x.numer() * x.numer();
    }
    pub(super) fn total(self) -> Q {
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
pub(super) fn l2_sq(v: &[Q], p: &Profile<Q>, coef: fn(&Segment<Q>) -> &[Q; 2]) -> Q {
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

#[cfg(test)]
mod tests {
    use super::*;

    fn q(n: i64, d: i64) -> Q {
        Q::new(n.into(), d.into())
    }

    /// `∫(Λ_N − Λ̃_N) w dw` by hand: N = 2, λ = (1, 0): cell 1 (d = 1) gives
    /// 1·(0 + 1/24), cell 2 (d = −1) gives −1·(1/8 + 1/24): total −1/8.
    #[test]
    fn lambda_gap_moment_by_hand() {
        assert_eq!(lambda_gap_moment(&[q(1, 1), q(0, 1)]), q(-1, 8));
        assert_eq!(lambda_gap_moment(&[q(0, 1), q(0, 1)]), q(0, 1));
    }

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

    /// The seven norms on one particle by hand: x_1 = 0, u_1 = 1, λ_1 = 0,
    /// so x_0 = −2 (δ = 1, 1/N = 1), u_0 = 1, λ_0 = 0: constant parts
    /// 0 + 1 + 0, affine parts (4 + 0 + 0)/3 + (1 + 1 + 1)/3 + 0, slope 0.
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
}
