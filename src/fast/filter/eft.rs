//! Error-free transformations of doubles and the one rounding test the
//! filter needs: the nearest double of `(Σ terms) / d`, decided in double-
//! double arithmetic when a rigorous error bound allows, computed exactly
//! (`BigRational`) otherwise.
//!
//! **Model.** Every operation on doubles used here is correctly rounded to
//! nearest: `fl(a ∘ b) = (a ∘ b)(1 + θ)`, `|θ| ≤ u = 2⁻⁵³`, as long as the
//! result is a normal double or zero; `fl` is monotone and `fl(c) = c` for a
//! double `c`. The filter's callers keep every magnitude inside
//! `[2⁻⁷⁰⁰, 2⁷⁰⁰]` (or zero) — the exponent range of [`super::SAFE_EXP`] —
//! so no result here underflows or overflows ([`up`] adds a floor for the
//! bounds themselves).
//!
//! * [`two_sum`] (Knuth): `s + e = a + b` exactly, `s = fl(a + b)`.
//! * [`two_prod`] (with a fused multiply-add): `p + e = a b` exactly,
//!   `p = fl(a b)`; exact when `e` is representable, which holds when the
//!   exponents of `a` and `b` add up to at least `−1022 + 106` (our range).
//! * [`Acc`], the `Sum2` of Ogita, Rump and Oishi: `s` the running
//!   [`two_sum`], `σ` the float sum of its errors `e_j`. Then
//!   `Σ terms = s + Σ e_j` exactly and `|Σ e_j − σ| ≤ γ_{n−1} Σ|e_j|`
//!   (recursive summation, `γ_m = m u / (1 − m u)`), bounded by
//!   `n u A (1 + 2⁻⁴⁰)` with `A` the float sum of the `|e_j|` (itself within
//!   `γ_{n−1}` of the exact sum) for `n < 2²⁰`.

use num_rational::BigRational;
use num_traits::{ToPrimitive, Zero};

/// The unit roundoff `u = 2⁻⁵³`.
pub(crate) const U: f64 = f64::EPSILON / 2.0;

/// A rigorous upper bound of a non-negative quantity computed in floats
/// from exact data by at most 2¹⁰ operations of the standard model: each
/// moved it by a factor within `(1 ± u)`, so the result times
/// `(1 + 2⁻⁴⁰)` (itself rounded: `(1 − u)(1 + 2⁻⁴⁰) > (1 + u)^{2¹⁰}`) is
/// above the exact value; the floor `2⁻⁹⁶⁰` covers any absolute error of a
/// result near the subnormal range.
#[inline]
pub(crate) fn up(v: f64) -> f64 {
    v * (1.0 + 1.0 / (1u64 << 40) as f64) + f64::from_bits(((1023 - 960) as u64) << 52)
}

/// `(s, e)` with `s = fl(a + b)` and `s + e = a + b` exactly (Knuth's
/// branch-free TwoSum; exact in binary floating point without overflow).
#[inline]
pub(crate) fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    let e = (a - (s - bb)) + (b - bb);
    (s, e)
}

/// `(p, e)` with `p = fl(a b)` and `p + e = a b` exactly (the residual by a
/// fused multiply-add, correctly rounded by IEEE 754; exact in the
/// filter's exponent range).
#[inline]
pub(crate) fn two_prod(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    (p, a.mul_add(b, -p))
}

/// A sum of doubles in double-double (`Sum2`, module documentation): the
/// exact sum lies within [`Acc::bound`] of `s + σ`.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Acc {
    /// The running `fl` sum of the terms.
    s: f64,
    /// The float sum of the [`two_sum`] errors.
    sigma: f64,
    /// The float sum of their magnitudes.
    abs: f64,
    /// Terms added.
    n: u32,
}

impl Acc {
    /// Adds the exact double `a`.
    #[inline]
    pub(crate) fn add(&mut self, a: f64) {
        let (s, e) = two_sum(self.s, a);
        self.s = s;
        self.sigma += e;
        self.abs += e.abs();
        self.n += 1;
    }

    /// Adds the exact product `a b` (two terms, [`two_prod`]).
    #[inline]
    pub(crate) fn add_product(&mut self, a: f64, b: f64) {
        let (p, e) = two_prod(a, b);
        self.add(p);
        self.add(e);
    }

    /// A bound of `|Σ terms − (s + σ)|`: `γ_{n−1} Σ|e_j| ≤ n u A (1 + 2⁻⁴⁰)`
    /// (`n < 2²⁰`, so `γ_{n−1} < n u (1 + 2⁻³³)` and `Σ|e_j| ≤ A (1 + 2⁻³³)`),
    /// made rigorous in floats by [`up`].
    fn bound(&self) -> f64 {
        debug_assert!(self.n < 1 << 20);
        up(f64::from(self.n) * U * up(self.abs))
    }

    /// The nearest double of `(Σ terms) / d` (ties to even) when the bound
    /// decides it, `None` otherwise (the caller then computes it exactly,
    /// [`exact_quotient`]). `d ≥ 1` is an integer below `2⁵³`.
    ///
    /// The candidate is `R = fl(q₁ + q₂)` with `q₁ = fl(s/d)`,
    /// `q₂ = fl((fl(s − q₁ d)' + σ)/d)`. With `g` the gap between `R` and
    /// its neighbours (the smaller one when `|R|` is a power of two), `R`
    /// is the nearest double of `X = T/d` (`T` the exact sum) when
    /// `|T − R d| < d g / 2`. `R d = p + e` exactly ([`two_prod`]),
    /// `T − R d = (s − p) + (σ − e) + (T − s − σ)` where `s − p = a + b`
    /// exactly ([`two_sum`]); `v = fl(fl(fl(a + b') … )` of the four small
    /// terms `a, b, σ, −e` has error `≤ γ₃ Σ|terms| ≤ 4u Σ|terms|`. So
    /// `|T − R d| ≤ |v| + 4u Σ|terms| + bound`, and the test
    /// `fl(|v| + up(…)) < d g / 2` (monotone rounding, `d g / 2` an exact
    /// double) proves `|T − R d| < d g / 2`: a value strictly inside the
    /// rounding interval of `R`, never on its midpoints.
    pub(crate) fn nearest_quotient(&self, d: f64) -> Option<f64> {
        debug_assert!(d >= 1.0 && d.fract() == 0.0 && d < (1u64 << 53) as f64);
        let q1 = self.s / d;
        let rem = (-q1).mul_add(d, self.s);
        let q2 = (rem + self.sigma) / d;
        let r = q1 + q2;
        if r == 0.0 || !r.is_finite() {
            return None;
        }
        let half_gap = half_gap(r)?;
        let (p, e) = two_prod(r, d);
        let (a, b) = two_sum(self.s, -p);
        let v = ((a + b) + self.sigma) - e;
        let spread = a.abs() + b.abs() + self.sigma.abs() + e.abs();
        let err = up(4.0 * U * spread) + self.bound();
        let limit = d * half_gap;
        // `limit` is exact: `d < 2⁵³` times a power of two.
        (v.abs() + up(err) < limit).then_some(r)
    }
}

/// Half the gap between the normal double `r ≠ 0` and its nearer
/// neighbour: `ulp(r)/2`, or `ulp(r)/4` when `|r|` is a power of two (the
/// gap below it is half the gap above). `None` near the subnormal range.
#[inline]
pub(crate) fn half_gap(r: f64) -> Option<f64> {
    let h = half_gap_or_zero(r);
    (h != 0.0).then_some(h)
}

/// [`half_gap`], `0` where it is `None`: branch-free, in operations on
/// doubles only, which the compiler vectorizes (it cannot vectorize the
/// 64-bit integer compares of the bits' fields on the baseline target).
///
/// `2^E` (`|r|` with its significand cleared) times `2⁻⁵³`, or `2⁻⁵⁴`
/// when `|r| = 2^E`: a power of two, exact when it is a normal double,
/// and `None` (`0`) when it is not.
#[inline(always)]
fn half_gap_or_zero(r: f64) -> f64 {
    const EXPONENT: u64 = 0x7ff << 52;
    let a = r.abs();
    let binade = f64::from_bits(a.to_bits() & EXPONENT);
    let h = binade * if a == binade { U / 2.0 } else { U };
    if h >= f64::MIN_POSITIVE {
        h
    } else {
        0.0
    }
}

/// The nearest double of `x + t u` (ties to even) for doubles in the
/// filter's range: `w = fl(x + fl(t u))` when the test below proves it,
/// else the fused multiply-add (correctly rounded, a library call on
/// machines without the instruction).
///
/// With `p = fl(t u)`, `x + p = w + e` exactly ([`two_sum`]) and
/// `|t u − p| ≤ u |t u| < 2u |p| = |p| 2⁻⁵²` (`|t u| ≤ |p|/(1 − u)`), so
/// `|x + t u − w| < |e| + |p| 2⁻⁵²`; when `fl(|e| + |p| 2⁻⁵²)` is below
/// [`half_gap`]`(w)` (monotone rounding: then the exact sum is too) the
/// value is strictly inside `w`'s rounding interval.
#[cfg(test)]
pub(crate) fn nearest_free_flight(x: f64, t: f64, u: f64) -> f64 {
    let p = t * u;
    let (w, e) = two_sum(x, p);
    nearest_free_flight_of(x, t, u, p, w, e)
}

/// [`nearest_free_flight`] from the `p = fl(t u)` and `(w, e) =`
/// [`two_sum`]`(x, p)` the caller has already computed.
#[inline(always)]
pub(crate) fn nearest_free_flight_of(x: f64, t: f64, u: f64, p: f64, w: f64, e: f64) -> f64 {
    debug_assert!(p.to_bits() == (t * u).to_bits() && (w, e) == two_sum(x, p));
    if is_nearest_free_flight(p, w, e) {
        w
    } else {
        u.mul_add(t, x)
    }
}

/// Does [`nearest_free_flight_of`] prove `w` the nearest double (the test
/// above, branch-free: a zero [`half_gap`] proves nothing)?
#[inline(always)]
pub(crate) fn is_nearest_free_flight(p: f64, w: f64, e: f64) -> bool {
    e.abs() + p.abs() * f64::EPSILON < half_gap_or_zero(w)
}

/// The nearest double of `(Σ terms) / d` computed exactly (the rare values
/// the bound of [`Acc::nearest_quotient`] does not decide).
pub(crate) fn exact_quotient(terms: &[f64], d: u64) -> f64 {
    if let Some(q) = word_quotient(terms, d) {
        debug_assert_eq!(q.to_bits(), rational_quotient(terms, d).to_bits());
        return q;
    }
    rational_quotient(terms, d)
}

/// [`exact_quotient`] in one machine word: the terms' sum as an `i128`
/// multiple of the least term's unit in the last place, then the integer
/// quotient by `d` with at least 74 bits and a sticky remainder, rounded
/// once to 53 bits (ties to even). `None` when the terms span too many
/// binades for the word (more than 64 between their units), there are 256
/// or more, `d` is 0 or the result leaves the normal range (the rational
/// quotient then answers). A zero sum is `+0`.
fn word_quotient(terms: &[f64], d: u64) -> Option<f64> {
    if d == 0 || terms.len() >= 256 {
        return None;
    }
    // Each nonzero finite term is `m 2^e` with `|m| < 2⁵³`.
    let parts = terms.iter().filter(|t| **t != 0.0).map(|&t| {
        let bits = t.to_bits();
        let field = ((bits >> 52) & 0x7ff) as i32;
        let fraction = (bits & ((1u64 << 52) - 1)) as i128;
        let (m, e) = if field == 0 {
            (fraction, -1074)
        } else {
            (fraction | (1 << 52), field - 1075)
        };
        (if t < 0.0 { -m } else { m }, e, field == 0x7ff)
    });
    let mut least = i32::MAX;
    let mut greatest = i32::MIN;
    for (_, e, special) in parts.clone() {
        if special {
            return None;
        }
        least = least.min(e);
        greatest = greatest.max(e);
    }
    if least == i32::MAX {
        return Some(0.0);
    }
    // `|m| 2^(e − least) < 2^(53 + 64)`, fewer than 2⁸ of them: `|sum| < 2¹²⁵`.
    if greatest - least > 64 {
        return None;
    }
    let sum: i128 = parts.map(|(m, e, _)| m << (e - least)).sum();
    if sum == 0 {
        return Some(0.0);
    }
    let magnitude = sum.unsigned_abs();
    let shift = magnitude.leading_zeros() - 1;
    let wide = magnitude << shift;
    // `wide ≥ 2¹²⁶`, `d < 2⁶⁴`: at least 63 bits of quotient, plus a sticky
    // bit for what the remainder leaves.
    let (q, sticky) = (wide / u128::from(d), wide % u128::from(d) != 0);
    let drop = 128 - q.leading_zeros() - 53;
    let mut mantissa = q >> drop;
    let rest = q & ((1u128 << drop) - 1);
    let half = 1u128 << (drop - 1);
    if rest > half || (rest == half && (sticky || mantissa & 1 == 1)) {
        mantissa += 1;
    }
    // The value is `mantissa 2^exponent`, `mantissa ≤ 2⁵³`.
    let exponent = least - shift as i32 + drop as i32;
    if !(-1022..=1023 - 53).contains(&exponent) {
        return None;
    }
    let scale = f64::from_bits(((exponent + 1023) as u64) << 52);
    let value = mantissa as f64 * scale;
    Some(if sum < 0 { -value } else { value })
}

/// [`exact_quotient`] on rationals.
fn rational_quotient(terms: &[f64], d: u64) -> f64 {
    let mut sum = BigRational::zero();
    for &t in terms {
        // Finite by the filter's range.
        if let Some(q) = BigRational::from_float(t) {
            sum += q;
        }
    }
    let q = sum / BigRational::from_integer(d.into());
    q.to_f64().unwrap_or(f64::NAN)
}

/// The nearest double of `(Σ terms) / d`: [`Acc::nearest_quotient`] when it
/// decides, else [`exact_quotient`].
pub(crate) fn quotient(terms: &[f64], d: u64) -> f64 {
    let mut acc = Acc::default();
    for &t in terms {
        acc.add(t);
    }
    match acc.nearest_quotient(d as f64) {
        Some(r) => {
            debug_assert_eq!(r.to_bits(), exact_quotient(terms, d).to_bits());
            r
        }
        None => exact_quotient(terms, d),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::SplitMix64;

    /// A double with a random mantissa and an exponent in `[lo, hi)`.
    fn random(rng: &mut SplitMix64, lo: i32, hi: i32) -> f64 {
        let m = rng.unit() + 0.5;
        let e = lo + (rng.next_u64() % (hi - lo) as u64) as i32;
        let v = m * 2f64.powi(e);
        if rng.next_u64() % 2 == 0 {
            v
        } else {
            -v
        }
    }

    #[test]
    fn two_sum_and_two_prod_are_exact() {
        let mut rng = SplitMix64::new(0xe7f);
        for _ in 0..10_000 {
            let (a, b) = (random(&mut rng, -60, 60), random(&mut rng, -60, 60));
            let q = |v: f64| BigRational::from_float(v).unwrap();
            let (s, e) = two_sum(a, b);
            assert_eq!(q(s) + q(e), q(a) + q(b));
            let (p, e) = two_prod(a, b);
            assert_eq!(q(p) + q(e), q(a) * q(b));
        }
    }

    /// The decided quotients against the exact ones on random term lists,
    /// near-midpoint ones included (a term far below the others).
    #[test]
    fn decided_quotients_are_the_exact_nearest() {
        let mut rng = SplitMix64::new(0x9a7);
        let (mut decided, mut undecided) = (0, 0);
        for case in 0..20_000 {
            let n = 1 + (rng.next_u64() % 12) as usize;
            let mut terms: Vec<f64> = (0..n).map(|_| random(&mut rng, -10, 10)).collect();
            if case % 3 == 0 {
                terms.push(random(&mut rng, -200, -100));
            }
            let d = 1 + rng.next_u64() % if case % 2 == 0 { 7 } else { 1 << 40 };
            let mut acc = Acc::default();
            terms.iter().for_each(|&t| acc.add(t));
            let exact = exact_quotient(&terms, d);
            match acc.nearest_quotient(d as f64) {
                Some(r) => {
                    decided += 1;
                    assert_eq!(r.to_bits(), exact.to_bits(), "{terms:?} / {d}");
                }
                None => undecided += 1,
            }
            assert_eq!(quotient(&terms, d).to_bits(), exact.to_bits());
        }
        assert!(decided > 15_000, "{decided} decided");
        let _ = undecided;
    }

    /// `(2 + 3·2⁻⁵² − 2⁻²⁰⁰)/2`: just below the midpoint `1 + 3·2⁻⁵³`
    /// whose tie goes up. `s` rounds `2 + 3·2⁻⁵²` to even, `σ` holds the
    /// `−2⁻⁵²` and loses the `−2⁻²⁰⁰` added to it, so the double-double
    /// value is the midpoint itself and its candidate the tie's double:
    /// only the bound keeps the test from answering it. The exact nearest
    /// is the lower neighbour.
    #[test]
    fn a_value_below_a_midpoint_beyond_double_double_is_not_decided() {
        let terms = [
            2.0,
            3.0 * 2f64.powi(-52),
            -(2f64.powi(-200)),
            2f64.powi(-60),
            -(2f64.powi(-60)),
        ];
        let mut acc = Acc::default();
        terms.iter().for_each(|&t| acc.add(t));
        let lower = 1.0 + 2f64.powi(-52);
        assert_eq!(exact_quotient(&terms, 2), lower);
        assert_eq!(acc.nearest_quotient(2.0), None);
        assert_eq!(quotient(&terms, 2), lower);
    }

    #[test]
    fn free_flights_are_the_nearest_doubles() {
        let mut rng = SplitMix64::new(0xf1e);
        for case in 0..20_000 {
            let x = random(&mut rng, -5, 30);
            let t = random(&mut rng, -12, 2).abs();
            let u = if case % 4 == 0 {
                // `t u` cancelling most of `x`.
                -x / t * (1.0 + random(&mut rng, -40, -20))
            } else {
                random(&mut rng, -3, 3)
            };
            let q = |v: f64| BigRational::from_float(v).unwrap();
            let exact = (q(x) + q(t) * q(u)).to_f64().unwrap();
            assert_eq!(nearest_free_flight(x, t, u).to_bits(), exact.to_bits());
        }
    }

    #[test]
    fn half_gaps_are_half_the_nearer_gap() {
        for r in [1.0, 1.5, 3.0e-7, -2.0, -7.25e10, f64::MAX] {
            let h = half_gap(r).unwrap();
            let a = r.abs();
            let gap =
                (a - f64::from_bits(a.to_bits() - 1)).min(f64::from_bits(a.to_bits() + 1) - a);
            assert_eq!(h, gap / 2.0, "{r}");
        }
        assert_eq!(half_gap(0.0), None);
        assert_eq!(half_gap(f64::MIN_POSITIVE), None);
    }

    /// The branch-free half gap on doubles of every binade (random
    /// significands, and the powers of two and their neighbours): half the
    /// nearer gap when that is a normal double, else `0`.
    #[test]
    fn branch_free_half_gaps_in_every_binade() {
        let mut rng = SplitMix64::new(0x4a1f);
        for field in 0..2047u64 {
            let significands = [0, 1, (1 << 52) - 1, rng.next_u64() >> 12];
            for (m, sign) in significands
                .into_iter()
                .zip([0, 1u64 << 63].into_iter().cycle())
            {
                let r = f64::from_bits(sign | field << 52 | m);
                let a = r.abs();
                let below = a - f64::from_bits(a.to_bits().saturating_sub(1));
                let above = f64::from_bits(a.to_bits() + 1) - a;
                let half = below.min(above) / 2.0;
                let want = if a != 0.0 && half >= f64::MIN_POSITIVE {
                    half
                } else {
                    0.0
                };
                assert_eq!(half_gap_or_zero(r).to_bits(), want.to_bits(), "{r:e}");
            }
        }
    }

    /// The word quotient is the rational one, bit for bit, or declines:
    /// sums of 1 to 200 terms over up to 63 binades, halves of sums of
    /// two doubles (a tie every other time), cancellations to zero,
    /// divisors from 1 to 2⁵³; and it declines what spans more binades.
    #[test]
    fn word_quotients_are_the_rational_ones() {
        let mut rng = SplitMix64::new(0x9e7);
        let mut decided = 0;
        for case in 0..20_000 {
            let k = 1 + (rng.next_u64() % 200) as usize;
            let lo = -40 - (rng.next_u64() % 4) as i32;
            let mut terms: Vec<f64> = (0..k).map(|_| random(&mut rng, lo, 20)).collect();
            let d = match case % 4 {
                0 => 2,
                1 => 1 + rng.next_u64() % 64,
                2 => 1 + rng.next_u64() % (1u64 << 53),
                _ => 3,
            };
            match case % 5 {
                0 => terms.truncate(2),
                1 => {
                    let t = terms[0];
                    terms.push(-t);
                    terms.swap(0, k);
                }
                2 => terms.iter_mut().for_each(|t| *t = t.round()),
                _ => {}
            }
            if case % 50 == 0 {
                terms = vec![1.5, -1.5];
            }
            let want = rational_quotient(&terms, d);
            if let Some(got) = word_quotient(&terms, d) {
                assert_eq!(got.to_bits(), want.to_bits(), "{terms:?} / {d}");
                decided += 1;
            }
        }
        assert_eq!(decided, 20_000);
        assert_eq!(word_quotient(&[1.0, 2f64.powi(-70)], 3), None);
        assert_eq!(word_quotient(&[1.0, f64::NAN], 3), None);
    }
}
