//! The distances of `thm:main` (iii) between the particle interpolations
//! and the continuum profile, cell by cell against the profile's pieces:
//! exact on exact inputs.

use crate::limit::continuum::Profile;
use crate::limit::interpolation::{abs, max_of};
use crate::scalar::Scalar;

/// `∫_0^1 (X_N − X)²`, exact on exact inputs: cells `((i−1)/N, i/N]`
/// against the profile's affine pieces (`∫ g² = h(g₀² + g₀g₁ + g₁²)/3`).
pub fn x_l2_squared<V: Scalar>(x: &[V], profile: &Profile<V>) -> V {
    let three = V::from_i64(3);
    overlap_sum(x.len(), profile, |i, lo, hi, s| {
        let g0 = x[i - 1].clone() - &(s.x[0].clone() + &(s.x[1].clone() * lo));
        let g1 = x[i - 1].clone() - &(s.x[0].clone() + &(s.x[1].clone() * hi));
        (hi.clone() - lo) * &(g0.clone() * &g0 + &(g0 * &g1) + &(g1.clone() * &g1)) / &three
    })
}

/// `∫_0^1 (U_N − U)²`, exact on exact inputs (as [`x_l2_squared`]).
pub fn u_l2_squared<V: Scalar>(u: &[V], profile: &Profile<V>) -> V {
    let three = V::from_i64(3);
    overlap_sum(u.len(), profile, |i, lo, hi, s| {
        let g0 = u[i - 1].clone() - &(s.u[0].clone() + &(s.u[1].clone() * lo));
        let g1 = u[i - 1].clone() - &(s.u[0].clone() + &(s.u[1].clone() * hi));
        (hi.clone() - lo) * &(g0.clone() * &g0 + &(g0 * &g1) + &(g1.clone() * &g1)) / &three
    })
}

/// `∫_0^1 |U_N − U|`, exact on exact inputs (an affine `g` on `[lo, hi]`:
/// `h|g₀ + g₁|/2` without a sign change, `h(g₀² + g₁²)/(2|g₀ − g₁|)` with one).
pub fn u_l1<V: Scalar>(u: &[V], profile: &Profile<V>) -> V {
    let two = V::from_i64(2);
    overlap_sum(u.len(), profile, |i, lo, hi, s| {
        let g0 = u[i - 1].clone() - &(s.u[0].clone() + &(s.u[1].clone() * lo));
        let g1 = u[i - 1].clone() - &(s.u[0].clone() + &(s.u[1].clone() * hi));
        let h = hi.clone() - lo;
        let s0 = g0.total_cmp(&V::zero());
        let s1 = g1.total_cmp(&V::zero());
        if s0.is_ge() == s1.is_ge() || s0.is_eq() || s1.is_eq() {
            h * &abs(g0 + &g1) / &two
        } else {
            h * &(g0.clone() * &g0 + &(g1.clone() * &g1)) / &(two.clone() * &abs(g0 - &g1))
        }
    })
}

/// `∫_0^1 (Λ_N − Λ)²` with `Λ_N = λ_i` on cell `i` (`λ_N = 0`), exact on
/// exact inputs (`h(g₀² + g₀g₁ + g₁²)/3` where `Λ` is affine, Boole's rule —
/// exact for the degree-4 integrand — where it is quadratic).
pub fn lambda_l2_squared<V: Scalar>(lambda: &[V], profile: &Profile<V>) -> V {
    let c = [7, 32, 12, 32, 7].map(V::from_i64);
    let ninety = V::from_i64(90);
    let four = V::from_i64(4);
    let three = V::from_i64(3);
    overlap_sum(lambda.len(), profile, |i, lo, hi, s| {
        let h = hi.clone() - lo;
        let at = |w: &V| {
            lambda[i - 1].clone()
                - &(s.lambda[0].clone()
                    + &(s.lambda[1].clone() * w)
                    + &(s.lambda[2].clone() * w * w))
        };
        if s.lambda[2].is_zero() {
            let (g0, g1) = (at(lo), at(hi));
            return h * &(g0.clone() * &g0 + &(g0 * &g1) + &(g1.clone() * &g1)) / &three;
        }
        let mut acc = V::zero();
        for (k, ck) in c.iter().enumerate() {
            let g = at(&(lo.clone() + &(h.clone() * &V::from_usize(k) / &four)));
            acc = acc + &(ck.clone() * &g * &g);
        }
        h * &acc / &ninety
    })
}

/// `Σ_i Σ_segments f(i, lo, hi, segment)` over the overlaps of the cells
/// `((i−1)/N, i/N]` with the segments (two pointers, O(N + segments)).
pub(super) fn overlap_sum<V: Scalar>(
    n: usize,
    profile: &Profile<V>,
    mut f: impl FnMut(usize, &V, &V, &crate::limit::continuum::Segment<V>) -> V,
) -> V {
    let nn = V::from_usize(n);
    let segs = &profile.segments;
    let mut total = V::zero();
    let mut k = 0usize;
    for i in 1..=n {
        let lo_c = V::from_usize(i - 1) / &nn;
        let hi_c = V::from_usize(i) / &nn;
        while k < segs.len() && segs[k].w1.total_cmp(&lo_c).is_le() {
            k += 1;
        }
        let mut kk = k;
        while kk < segs.len() && segs[kk].w0.total_cmp(&hi_c).is_lt() {
            let s = &segs[kk];
            let lo = max_of(lo_c.clone(), s.w0.clone());
            let hi = if s.w1.total_cmp(&hi_c).is_lt() {
                s.w1.clone()
            } else {
                hi_c.clone()
            };
            if hi.total_cmp(&lo).is_gt() {
                total = total + &f(i, &lo, &hi, s);
            }
            kk += 1;
        }
    }
    total
}
