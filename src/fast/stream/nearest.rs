//! The streaming path's state rounded to the nearest doubles: each value
//! rounded once from its unreduced fraction on 128-bit words
//! ([`nearest_ratio`]), the same doubles as the reduced values'
//! [`Exact::to_f64_lossy`].

use std::io;

use crate::fast::kernel::Run;

use super::{Exact, LeanBlocks, Piece};

/// The nearest double of `num / den` (`den > 0`; round to nearest, ties to
/// even), on 128-bit words with no reduction to lowest terms: one correctly
/// rounded division when both terms are exact doubles, else the quotient
/// scaled to 55 or 56 bits by one integer division, rounded with the
/// remainder as sticky bit. `None` when the scaling does not fit 128 bits or
/// the result would not be a normal double (the caller then reduces and
/// rounds through [`Exact::to_f64_lossy`]).
pub fn nearest_ratio(num: i128, den: i128) -> Option<f64> {
    const EXACT: u128 = 1 << 53;
    if den <= 0 {
        return None;
    }
    if num == 0 {
        return Some(0.0);
    }
    let (a, b) = (num.unsigned_abs(), den.unsigned_abs());
    let sign = if num < 0 { -1.0 } else { 1.0 };
    if a <= EXACT && b <= EXACT {
        // Through `u64` (exact: both ≤ 2^53): one machine conversion each,
        // not the 128-bit one.
        return Some(sign * (a as u64 as f64 / b as u64 as f64));
    }
    let la = 128 - i64::from(a.leading_zeros());
    let lb = 128 - i64::from(b.leading_zeros());
    // a/b lies in (2^(la-lb-1), 2^(la-lb+1)): q = ⌊a 2^s / b⌋ with
    // s = 55 - (la - lb) lies in [2^54, 2^56).
    let s = 55 - (la - lb);
    let (q, inexact) = if s >= 0 {
        if la + s > 127 {
            return None;
        }
        let a2 = a << s;
        (a2 / b, a2 % b != 0)
    } else {
        if lb - s > 127 {
            return None;
        }
        let b2 = b << (-s);
        (a / b2, a % b2 != 0)
    };
    debug_assert!((1u128 << 54..1u128 << 56).contains(&q));
    let drop = 128 - i64::from(q.leading_zeros()) - 53;
    let mut m = q >> drop;
    let rest = q & ((1u128 << drop) - 1);
    let half = 1u128 << (drop - 1);
    if rest > half || (rest == half && (inexact || m & 1 == 1)) {
        m += 1;
    }
    // The value is m · 2^e, m ≤ 2^53 exact in a double.
    let e = drop - s;
    if !(-1022..=1023 - 54).contains(&e) {
        return None;
    }
    let scale = f64::from_bits(u64::try_from(e + 1023).ok()? << 52);
    Some(sign * (m as u64 as f64) * scale)
}

/// A callback of the value visitors of [`LeanBlocks`].
type Visitor<'a> = dyn FnMut(&Exact) -> io::Result<()> + 'a;

/// The state of a [`LeanBlocks`] rounded to the nearest doubles
/// ([`LeanBlocks::nearest`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Nearest {
    /// `x(t)`.
    pub positions: Vec<f64>,
    /// `u(t)`.
    pub velocities: Vec<f64>,
    /// `λ_1 … λ_{N−1}`.
    pub multipliers: Vec<f64>,
}

impl LeanBlocks<'_> {
    /// The state rounded to the nearest doubles (ties to even), each value
    /// rounded once from its exact value: the same doubles as
    /// [`Exact::to_f64_lossy`] of [`Self::positions`], [`Self::velocities`]
    /// and [`Self::multipliers`], without their reductions to lowest terms
    /// ([`nearest_ratio`] on the unreduced fractions; the reduced path when
    /// one of them does not fit words).
    pub fn nearest(&self) -> Nearest {
        let mut out = Nearest::with_capacity(self.n());
        if self.nearest_words(&self.runs, 0, &mut out).is_some() {
            return out;
        }
        Nearest {
            positions: rounded(|f| self.positions(f)),
            velocities: rounded(|f| self.velocities(f)),
            multipliers: rounded(|f| self.multipliers(f)),
        }
    }

    /// Appends to `out` the rows of the particles of `piece`, in order,
    /// each `x_i, u_i, λ_{i+1}` (0 for the last particle) as little-endian
    /// doubles: the `(N, 3)` rows `run --format npy` writes. Each double is
    /// that of [`Self::nearest`] (the reduced path for a piece whose
    /// unreduced fractions do not all fit words), so pieces formatted
    /// apart and put back in order give the bytes of the whole.
    pub fn push_nearest_rows(&self, piece: &Piece, out: &mut Vec<u8>) {
        let runs = &self.runs[piece.runs.clone()];
        let k: usize = runs.iter().map(|r| r.k as usize).sum();
        let mut near = Nearest::with_capacity(k);
        if self.nearest_words(runs, piece.first, &mut near).is_none() {
            let n = self.n();
            near = Nearest {
                positions: rounded(|f| self.positions_from(runs, piece.first, f)),
                velocities: rounded(|f| self.velocities_from(runs, f)),
                multipliers: rounded(|f| self.multipliers_from(runs, piece.first, n, f)),
            };
        }
        debug_assert_eq!((near.positions.len(), near.velocities.len()), (k, k));
        out.reserve(24 * k);
        for (m, (x, u)) in near.positions.iter().zip(&near.velocities).enumerate() {
            let l = near.multipliers.get(m).copied().unwrap_or(0.0);
            for v in [*x, *u, l] {
                out.extend_from_slice(&v.to_le_bytes());
            }
        }
    }

    /// The nearest doubles of the values of the blocks `runs`, whose first
    /// particle is `first`, appended to `out`; `None` (and `out` left in
    /// any state) when an unreduced fraction does not fit words.
    fn nearest_words(&self, runs: &[Run<i128>], mut first: usize, out: &mut Nearest) -> Option<()> {
        let n = self.n();
        let (rn, rd) = self.d.two_r;
        let big_n = i128::try_from(n).ok()?;
        for r in runs {
            let k = i128::from(r.k);
            // x_i = S_Y / (k D_Y) + (r_n / r_d) i = (S_Y r_d + r_n k D_Y i) / (k D_Y r_d).
            let ky = self.dy?.checked_mul(k)?;
            let den = ky.checked_mul(rd)?;
            let step = ky.checked_mul(rn)?;
            let base = r.sy.checked_mul(rd)?;
            let first_i = i128::try_from(first).ok()?;
            for m in 0..k {
                let num = base.checked_add(step.checked_mul(first_i + m)?)?;
                out.positions.push(nearest_ratio(num, den)?);
            }
            let u = nearest_ratio(r.su, k.checked_mul(self.d.du)?)?;
            out.velocities.extend(std::iter::repeat_n(u, r.k as usize));
            // λ of the m-th pair of the block: (k Σ_{j ≤ m} U_j − m S) / (k D_u N).
            let den = k.checked_mul(self.d.du)?.checked_mul(big_n)?;
            let mut prefix = 0i128;
            for m in 1..=r.k as usize {
                let i = first + m - 1;
                if i + 1 >= n {
                    break;
                }
                prefix = prefix.checked_add(i128::from(self.d.u[i]))?;
                let num = k
                    .checked_mul(prefix)?
                    .checked_sub(i128::try_from(m).ok()?.checked_mul(r.su)?)?;
                out.multipliers.push(nearest_ratio(num, den)?);
            }
            first += r.k as usize;
        }
        Some(())
    }
}

impl Nearest {
    fn with_capacity(n: usize) -> Nearest {
        Nearest {
            positions: Vec::with_capacity(n),
            velocities: Vec::with_capacity(n),
            multipliers: Vec::with_capacity(n),
        }
    }
}

/// The values a visitor gives, each rounded to the nearest double.
fn rounded(visit: impl FnOnce(&mut Visitor<'_>) -> io::Result<()>) -> Vec<f64> {
    let mut v = Vec::new();
    // The visitors fail only when their callback does; this one never does.
    let _ = visit(&mut |e| {
        v.push(e.to_f64_lossy());
        Ok(())
    });
    v
}
