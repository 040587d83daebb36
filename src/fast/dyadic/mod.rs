//! The lean path for doubles (issue 27): columns of `f64` straight to the
//! integer PAVA and back to the nearest doubles, with no `BigRational` and
//! no big integer per value.
//!
//! Every double is a dyadic rational `m 2^e`. [`Dyadic::from_doubles`]
//! decomposes each one with integer operations and scales each column to
//! its smallest exponent: with `2r = a / (b_o 2^{b_s})` (`b_o` odd) and
//! `ex` the smallest exponent among the positions and `2^{-b_s}`,
//!
//! `x̃⁰_i = x⁰_i − 2r i = X̃_i 2^{ex} / b_o` (`df:translat-x`),
//! `u⁰_i = U_i 2^{eu}`,
//!
//! with `X̃_i`, `U_i` in `i128`, and checks `df:KN` (`X̃_{i+1} ≥ X̃_i`) and
//! `def:velcone` (`U_{i+1} ≥ U_i` across a contact) on them. At a time
//! `t = p / (q_o 2^{q_s})`, with `ey = min(ex, eu − q_s)`,
//!
//! `Y_i = A X̃_i + B U_i`, `A = q_o 2^{ex − ey}`, `B = b_o p 2^{eu − q_s − ey}`,
//! `ỹ_i = x̃⁰_i + t u⁰_i = Y_i / M`, `M = b_o q_o 2^{−ey}`,
//!
//! and the kernel's PAVA ([`crate::fast::kernel`], `prop:proj-micro`) runs on
//! the `i128` pairs `(Y_i, U_i)` under the kernel's width bound
//! (`b_Y + b_K ≤ 127`). A block of `k` entries with sums `S = ΣY`,
//! `S_U = ΣU` gives, for each of its particles `i`,
//!
//! * `x_i = S/(kM) + 2r i = (S + k C i) 2^{ey} / (k b_o q_o)`, `C = A R`,
//!   `R = 2r b_o 2^{−ex}` (an integer);
//! * `u_i = S_U 2^{eu} / k` (`eq:proj-u-micro`);
//! * `λ_m = (k Σ_{j ≤ m} U_j − m S_U) 2^{eu} / (k N)` for the `m`-th pair of
//!   the block (`eq:dyn-micro`, [`crate::contact::cluster_multiplier_numerators`]).
//!
//! Each is an `i128` numerator over a 64-bit denominator times a power of
//! two, rounded once to the nearest double by [`round::nearest`] (one
//! integer division, none when the denominator is a power of two; the
//! multipliers by [`quotient::nearest`], no division per pair) or
//! reduced to lowest terms on demand ([`DyadicBlocks::exact_state`]).
//!
//! **Same results.** Everything answers `None` the moment the data leave
//! this range (a non-finite value, a radius or time whose factors do not fit
//! 64 bits, a scaled value beyond `i128`, invalid data, the width bound not
//! proved): the caller then takes another path, which gives the same answer
//! or the error of record. The tests compare the exact states with the
//! generic projection and the doubles with the exact values' nearest
//! doubles, bit for bit.

mod halves;
pub mod isotonic;
mod pava;
pub mod quotient;
pub mod round;
mod wide;

use std::sync::Arc;

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Signed, ToPrimitive, Zero};

use crate::cluster::Cluster;
use crate::fast::kernel::{size_bits, word_clusters, Run, Width};
use crate::fast::stream::Nearest;
use crate::fast::wide::I256;
use crate::state::State;
use pava::Sum;
use quotient::Denominator;
use round::{Divisor, Split};
use wide::{Factor, Wide};

/// Bits of `|v|` (0 for 0).
fn bits(v: u128) -> u64 {
    u64::from(128 - v.leading_zeros())
}

/// `v 2^s` when it fits `i128` (exactly), `None` otherwise.
fn shl_exact(v: i128, s: u64) -> Option<i128> {
    if v == 0 {
        return Some(0);
    }
    if s >= 127 || bits(v.unsigned_abs()) + s > 126 {
        return None;
    }
    Some(v << s)
}

/// A finite double as `(m, e)` with value `m 2^e`, `m` odd (or `0`);
/// `None` for a NaN or an infinity.
fn decompose(d: f64) -> Option<(i64, i64)> {
    let b = d.to_bits();
    let field = ((b >> 52) & 0x7ff) as i64;
    let frac = (b & ((1u64 << 52) - 1)) as i64;
    let (m, e) = match field {
        0x7ff => return None,
        0 => (frac, -1074),
        _ => (frac | (1 << 52), field - 1075),
    };
    if m == 0 {
        return Some((0, 0));
    }
    let tz = i64::from(m.trailing_zeros());
    let m = m >> tz;
    Some((if d < 0.0 { -m } else { m }, e + tz))
}

/// A non-negative rational as `(a, o, s)` with value `a / (o 2^s)`: `a`
/// odd (or `0`), `o` odd, both on 64 bits, `s` of either sign (the powers
/// of two of the numerator and the denominator together); `None` when it
/// is negative or a term does not fit.
fn split_odd(q: &BigRational) -> Option<(u64, u64, i64)> {
    if q.is_negative() {
        return None;
    }
    if q.is_zero() {
        return Some((0, 1, 0));
    }
    let za = q.numer().trailing_zeros()?;
    let a = (q.numer() >> za).to_u64()?;
    let zd = q.denom().trailing_zeros()?;
    let o = (q.denom() >> zd).to_u64()?;
    Some((a, o, i64::try_from(zd).ok()? - i64::try_from(za).ok()?))
}

/// Bits of `|v|` up to which the columns are stored as `i64`: `|v| < 2^63`.
const NARROW_BITS: u64 = 63;

/// The scaled columns `X̃_i`, `U_i` (shared with the [`DyadicBlocks`] of
/// every time): on `i64` when every value fits, which halves the memory the
/// PAVA reads (grid data), on `i128` otherwise. The PAVA's `Y_i`, sums and
/// blocks are `i128` either way, under the same width bound.
#[derive(Debug, Clone)]
enum Columns {
    /// Every `|X̃_i|`, `|U_i|` has at most [`NARROW_BITS`] bits.
    Narrow { x: Arc<Vec<i64>>, u: Arc<Vec<i64>> },
    /// Some value has more.
    Wide {
        x: Arc<Vec<i128>>,
        u: Arc<Vec<i128>>,
    },
}

impl Columns {
    /// The columns, narrow when `x_bits` and `u_bits` (the bits of the
    /// largest `|X̃_i|` and `|U_i|`) are at most [`NARROW_BITS`].
    fn new(x: Vec<i128>, u: Vec<i128>, x_bits: u64, u_bits: u64) -> Columns {
        if x_bits <= NARROW_BITS && u_bits <= NARROW_BITS {
            // Exact: |v| < 2^63 fits i64.
            let narrow = |v: Vec<i128>| -> Arc<Vec<i64>> {
                Arc::new(
                    v.into_iter()
                        .map(|w| {
                            debug_assert!(i64::try_from(w).is_ok());
                            w as i64
                        })
                        .collect(),
                )
            };
            Columns::Narrow {
                x: narrow(x),
                u: narrow(u),
            }
        } else {
            // The vectors themselves, not a copy.
            Columns::Wide {
                x: Arc::new(x),
                u: Arc::new(u),
            }
        }
    }

    /// N.
    fn len(&self) -> usize {
        match self {
            Columns::Narrow { x, .. } => x.len(),
            Columns::Wide { x, .. } => x.len(),
        }
    }

    /// `U_i` (`None` past the end).
    fn u(&self, i: usize) -> Option<i128> {
        match self {
            Columns::Narrow { u, .. } => u.get(i).map(|&v| i128::from(v)),
            Columns::Wide { u, .. } => u.get(i).copied(),
        }
    }
}

/// A scene of doubles on integer columns over dyadic scales (module
/// documentation): `x̃⁰_i = X̃_i 2^{ex} / b_o`, `u⁰_i = U_i 2^{eu}`.
#[derive(Debug, Clone)]
pub struct Dyadic {
    radius: BigRational,
    /// `X̃_i` and `U_i`.
    columns: Columns,
    ex: i64,
    eu: i64,
    b_odd: u64,
    /// `R = 2r b_o 2^{−ex}`, the integer `2r` at the positions' scale.
    two_r: i128,
    x_bits: u64,
    u_bits: u64,
}

impl Dyadic {
    /// The scene of radius `radius` (`None`: `1/(2N)`) with positions `xs`
    /// and velocities `us`, each double taken as the exact binary rational
    /// it is. `None` when a value is not finite, the radius's terms do not
    /// fit 64 bits, a scaled value does not fit `i128`, or the data are not
    /// valid (`df:KN`, `def:velcone`): the general path
    /// ([`crate::InitialData::new`]) then answers or names the error.
    pub fn from_doubles(radius: Option<BigRational>, xs: &[f64], us: &[f64]) -> Option<Dyadic> {
        let n = xs.len();
        if n == 0 || us.len() != n {
            return None;
        }
        let radius = radius.unwrap_or_else(|| BigRational::new(1.into(), BigInt::from(2 * n)));
        if !radius.is_positive() {
            return None;
        }
        let (a, b_odd, b_s) = split_odd(&(&radius + &radius))?;
        if a == 0 {
            return None;
        }
        // Two passes over the doubles and none over intermediate vectors:
        // the least exponents first, then each scaled value straight into
        // its column, checked and measured on the way.
        let least = |v: &[f64]| -> Option<Option<i64>> {
            let mut least: Option<i64> = None;
            for &d in v {
                let (m, e) = decompose(d)?;
                if m != 0 {
                    least = Some(least.map_or(e, |l| l.min(e)));
                }
            }
            Some(least)
        };
        let ex = least(xs)?.map_or(-b_s, |e| e.min(-b_s));
        let eu = least(us)?.unwrap_or(0);
        // R = a 2^{−b_s − ex}, X̃_i = b_o m_i 2^{e_i − ex} − R i.
        let two_r = shl_exact(i128::from(a), u64::try_from(-b_s - ex).ok()?)?;
        let b = i128::from(b_odd);
        let mut x = Vec::with_capacity(n);
        let mut u = Vec::with_capacity(n);
        let (mut x_or, mut u_or) = (0u128, 0u128);
        // `R i`, `None` once it leaves `i128` (an error only if used).
        let mut step = Some(0i128);
        for (&dx, &du) in xs.iter().zip(us) {
            let (m, e) = decompose(dx)?;
            let scaled = shl_exact(i128::from(m) * b, (e - ex) as u64)?;
            let xi = scaled.checked_sub(step?)?;
            let (m, e) = decompose(du)?;
            let ui = shl_exact(i128::from(m), (e - eu) as u64)?;
            // `df:KN` and `def:velcone` on the scaled data, the checks of
            // `InitialData::new` (the general path names the first failure).
            if let (Some(&xp), Some(&up)) = (x.last(), u.last()) {
                if xi < xp || (xi == xp && ui < up) {
                    return None;
                }
            }
            // The bits of the largest `|v|` are those of the `or` of all.
            x_or |= xi.unsigned_abs();
            u_or |= ui.unsigned_abs();
            x.push(xi);
            u.push(ui);
            step = step.and_then(|s| s.checked_add(two_r));
        }
        let (x_bits, u_bits) = (bits(x_or), bits(u_or));
        Some(Dyadic {
            radius,
            x_bits,
            u_bits,
            columns: Columns::new(x, u, x_bits, u_bits),
            ex,
            eu,
            b_odd,
            two_r,
        })
    }

    /// N.
    pub fn n(&self) -> usize {
        self.columns.len()
    }

    /// Whether the columns are stored as `i64` ([`Columns`]).
    #[cfg(test)]
    fn is_narrow(&self) -> bool {
        matches!(self.columns, Columns::Narrow { .. })
    }

    /// The same scene on `i128` columns (tests compare the two widths).
    #[cfg(test)]
    fn widened(&self) -> Dyadic {
        let widen =
            |v: &[i64]| -> Arc<Vec<i128>> { Arc::new(v.iter().map(|&w| i128::from(w)).collect()) };
        let columns = match &self.columns {
            Columns::Narrow { x, u } => Columns::Wide {
                x: widen(x),
                u: widen(u),
            },
            wide => wide.clone(),
        };
        Dyadic {
            columns,
            ..self.clone()
        }
    }

    /// The radius r.
    pub fn radius(&self) -> &BigRational {
        &self.radius
    }

    /// The exact PAVA blocks at `t ≥ 0` on `i128` sums; `None` when `t < 0`,
    /// its terms do not fit 64 bits, or the kernel's `i128` bound does not
    /// hold at `t` (the caller then takes another path).
    pub fn blocks_at(&self, t: &BigRational) -> Option<DyadicBlocks> {
        self.blocks_with(t, halves::PARALLEL_MIN)
    }

    /// [`Self::blocks_at`], on two threads from `parallel_min` entries on
    /// (the PAVA now, the outputs later).
    fn blocks_with(&self, t: &BigRational, parallel_min: usize) -> Option<DyadicBlocks> {
        let (p, q_odd, q_s) = split_odd(t)?;
        let ey = self.ex.min(self.eu - q_s);
        // A = q_o 2^{ex − ey}, B = b_o p 2^{eu − q_s − ey}.
        let fa = Factor {
            odd: u128::from(q_odd),
            shift: u64::try_from(self.ex - ey).ok()?,
        };
        let fb = Factor {
            odd: u128::from(self.b_odd) * u128::from(p),
            shift: u64::try_from(self.eu - q_s - ey).ok()?,
        };
        // The kernel's bound (`crate::fast::kernel`): |Y_i| < 2^b_Y, every
        // block sum and cross product below 2^(b_Y + b_K) ≤ 2^127, the same
        // for the U sums; beyond it, the same on 256 bits (`wide`).
        let b_k = size_bits(self.n());
        let b_y = (fa.bits() + self.x_bits).max(fb.bits() + self.u_bits) + 1;
        let narrow = if b_y + b_k > 127 || self.u_bits + b_k > 127 {
            None
        } else {
            self.narrow_sums(&fa, &fb, b_y + b_k, parallel_min)
        };
        let sums = match narrow {
            Some(s) => s,
            None => BlockSums::Wide(match &self.columns {
                Columns::Narrow { x, u } => self.wide_sums(x, u, &fa, &fb, parallel_min)?,
                Columns::Wide { x, u } => self.wide_sums(x, u, &fa, &fb, parallel_min)?,
            }),
        };
        Some(DyadicBlocks {
            d: self.clone(),
            parallel_min,
            sums,
            t: t.clone(),
            ey,
            q_odd,
        })
    }

    /// The PAVA on `i128` sums (or `i64` ones, under the bound on 63 bits),
    /// `sum_bits = b_Y + b_K ≤ 127`; `None` when `C` leaves `i128`.
    fn narrow_sums(
        &self,
        fa: &Factor,
        fb: &Factor,
        sum_bits: u64,
        parallel_min: usize,
    ) -> Option<BlockSums> {
        // Both factors are below 2^{b_Y − 1} ≤ 2^126.
        let a = shl_exact(i128::try_from(fa.odd).ok()?, fa.shift)?;
        let b = shl_exact(i128::try_from(fb.odd).ok()?, fb.shift)?;
        let c = a.checked_mul(self.two_r)?;
        // The same bound on 63 bits: the PAVA on `i64` sums (`A`, `B`
        // then fit `i64` too, each term of `Y_i` being below `2^{b_Y − 1}`).
        let b_k = size_bits(self.n());
        let narrow_sums = sum_bits <= NARROW_BITS && self.u_bits + b_k <= NARROW_BITS;
        let ab64 = i64::try_from(a).ok().zip(i64::try_from(b).ok());
        let runs = match (&self.columns, ab64) {
            (Columns::Narrow { x, u }, Some((a, b))) if narrow_sums => {
                pava_ab(x, u, a, b, parallel_min)
            }
            (Columns::Narrow { x, u }, _) => pava_ab(x, u, a, b, parallel_min),
            (Columns::Wide { x, u }, _) => pava_ab(x, u, a, b, parallel_min),
        };
        Some(BlockSums::Narrow { runs, c })
    }

    /// The PAVA on 256-bit sums ([`wide`]).
    fn wide_sums<T: Copy + Into<I256> + Into<i128> + Sync>(
        &self,
        x: &[T],
        u: &[T],
        fa: &Factor,
        fb: &Factor,
        parallel_min: usize,
    ) -> Option<Wide> {
        let widths = (self.x_bits, self.u_bits);
        Wide::new(x, u, fa, fb, self.two_r, widths, parallel_min)
    }
}

/// The PAVA on `(Y_i, U_i)`, `Y_i = A X̃_i + B U_i`, on either width of
/// columns ([`Columns`]) and of sums ([`Sum`]: `W` must hold the sums and
/// their products by block sizes, and `A`, `B`).
fn pava_ab<T: Copy + Into<W> + Sync, W: Sum + Into<i128> + Send + Sync>(
    xs: &[T],
    us: &[T],
    a: W,
    b: W,
    parallel_min: usize,
) -> Vec<Run<i128>> {
    let b_wide: i128 = b.into();
    if a == W::size(1) && b_wide > 0 && b_wide.count_ones() == 1 {
        // The common case (2r and t dyadic, the positions' scale the
        // finer): `Y_i = X̃_i + U_i 2^j`, a shift for a product.
        let j = b_wide.trailing_zeros();
        halves::pava(xs, us, parallel_min, |x, u| {
            x.into().plus(u.into().shifted(j))
        })
    } else {
        halves::pava(xs, us, parallel_min, |x, u| {
            a.times(x.into()).plus(b.times(u.into()))
        })
    }
}

/// The PAVA blocks of a [`Dyadic`] scene at one time, and the state they
/// give (each output computed when asked for: the blocks hold everything
/// it needs, the scene's columns shared).
#[derive(Debug, Clone)]
pub struct DyadicBlocks {
    d: Dyadic,
    /// Outputs are filled by two threads from this many particles on.
    parallel_min: usize,
    sums: BlockSums,
    t: BigRational,
    ey: i64,
    q_odd: u64,
}

/// The PAVA's blocks on the words the bound allowed, with
/// `C = A R`: `x_i = (S + k C i) 2^{ey} / (k b_o q_o)`.
#[derive(Debug, Clone, PartialEq)]
enum BlockSums {
    /// `i128` sums (`b_Y + b_K ≤ 127`).
    Narrow { runs: Vec<Run<i128>>, c: i128 },
    /// 256-bit `ΣY` ([`wide`]: `b_Y + b_K ≤ 254`), `ΣU` on `i128`.
    Wide(Wide),
}

/// A block's `ΣY` as a big integer (for the exact state).
trait SumY: Copy + Sync {
    fn big(self) -> BigInt;
}

impl SumY for i128 {
    fn big(self) -> BigInt {
        BigInt::from(self)
    }
}

impl SumY for I256 {
    fn big(self) -> BigInt {
        self.to_bigint()
    }
}

/// The multipliers of one block of `k = us.len() ≥ 2` entries with
/// `S_U = su`, into `out` (its first `k − 1` pairs): the `m`-th is
/// `(k Σ_{j ≤ m} U_j − m S_U) 2^{eu} / (k N)` (`eq:dyn-micro`), `den = k N`.
/// The numerator moves by `k U_m − S_U` from one pair to the next. With
/// `|U_j| < 2^{u_bits}` every numerator and every partial sum is below
/// `2 k² 2^{u_bits}`: the caller checks `2 bits(k) + u_bits + 1 ≤ 127`, and
/// the wrapping arithmetic is then exact.
fn block_multipliers<T: Copy + Into<i128>>(
    us: &[T],
    su: i128,
    den: &Denominator,
    eu: i64,
    out: &mut [f64],
) {
    let k = us.len() as i128;
    let mut num = 0i128;
    for (&u, l) in us.iter().zip(out.iter_mut()) {
        num = num.wrapping_add(k.wrapping_mul(u.into())).wrapping_sub(su);
        // `λ ≥ 0` (eq:dyn-micro, the Coq development's `multiplier_nonneg`).
        debug_assert!(num >= 0);
        *l = quotient::nearest(num, den, eu);
    }
}

/// [`block_multipliers`] with checked arithmetic, for a block beyond its
/// bound: `None` when a numerator leaves `i128`.
fn block_multipliers_checked<T: Copy + Into<i128>>(
    us: &[T],
    su: i128,
    den: &Denominator,
    eu: i64,
    out: &mut [f64],
) -> Option<()> {
    let k = i128::try_from(us.len()).ok()?;
    let mut num = 0i128;
    for (&u, l) in us.iter().zip(out.iter_mut()) {
        num = num.checked_add(k.checked_mul(u.into())?)?.checked_sub(su)?;
        *l = quotient::nearest(num, den, eu);
    }
    Some(())
}

/// The velocities of the particles of `runs` into `out`:
/// `u_i = S_U 2^{eu} / k` (`eq:proj-u-micro`), one value per block.
fn fill_velocities<W>(runs: &[Run<W, i128>], eu: i64, out: &mut [f64]) -> Option<()> {
    let mut o = 0usize;
    for r in runs {
        let u = round::nearest(r.su, r.k, eu);
        let k = r.k as usize;
        out.get_mut(o..o + k)?.fill(u);
        o += k;
    }
    Some(())
}

/// `num 2^exp / den` in lowest terms.
fn exact(num: BigInt, den: BigInt, exp: i64) -> BigRational {
    let shift = exp.unsigned_abs() as usize;
    if exp >= 0 {
        crate::gcd::ratio(num << shift, den)
    } else {
        crate::gcd::ratio(num, den << shift)
    }
}

impl DyadicBlocks {
    /// The time.
    pub fn t(&self) -> &BigRational {
        &self.t
    }

    /// N.
    pub fn n(&self) -> usize {
        self.d.n()
    }

    /// The state rounded to the nearest doubles (ties to even), each value
    /// rounded once from its exact value; `None` when an intermediate does
    /// not fit `i128` or a denominator 64 bits (then round
    /// [`Self::exact_state`]).
    pub fn nearest(&self) -> Option<Nearest> {
        Some(Nearest {
            positions: self.positions()?,
            velocities: self.velocities()?,
            multipliers: self.multipliers()?,
        })
    }

    /// `x(t)` rounded to the nearest doubles ([`Self::nearest`]'s).
    pub fn positions(&self) -> Option<Vec<f64>> {
        let den_y = self.d.b_odd.checked_mul(self.q_odd)?;
        let (n, pm, ey) = (self.n(), self.parallel_min, self.ey);
        match &self.sums {
            BlockSums::Narrow { runs, c } => {
                halves::fill_by_halves(runs, n, n, pm, |runs, first, out| {
                    self.fill_positions(runs, first, *c, den_y, out)
                })
                .or_else(|| {
                    // `S + k C i` beyond 127 bits (the PAVA's sums fit, the
                    // positions' numerators need not): the same blocks on
                    // 256-bit numerators.
                    let w = wide::Wide::widen(runs, *c);
                    halves::fill_by_halves(&w.runs, n, n, pm, |runs, first, out| {
                        wide::fill_positions(runs, first, w.c, den_y, ey, out)
                    })
                })
            }
            BlockSums::Wide(w) => halves::fill_by_halves(&w.runs, n, n, pm, |runs, first, out| {
                wide::fill_positions(runs, first, w.c, den_y, ey, out)
            }),
        }
    }

    /// `u(t)` rounded to the nearest doubles ([`Self::nearest`]'s).
    pub fn velocities(&self) -> Option<Vec<f64>> {
        let n = self.n();
        let eu = self.d.eu;
        let pm = self.parallel_min;
        match &self.sums {
            BlockSums::Narrow { runs, .. } => {
                halves::fill_by_halves(runs, n, n, pm, |r, _, out| fill_velocities(r, eu, out))
            }
            BlockSums::Wide(w) => {
                halves::fill_by_halves(&w.runs, n, n, pm, |r, _, out| fill_velocities(r, eu, out))
            }
        }
    }

    /// `λ(t)` rounded to the nearest doubles ([`Self::nearest`]'s).
    pub fn multipliers(&self) -> Option<Vec<f64>> {
        let n = self.n();
        let big_n = u64::try_from(n).ok()?;
        let (len, pm) = (n.saturating_sub(1), self.parallel_min);
        match &self.sums {
            BlockSums::Narrow { runs, .. } => {
                halves::fill_by_halves(runs, n, len, pm, |runs, first, out| {
                    self.fill_multipliers(runs, first, big_n, out)
                })
            }
            BlockSums::Wide(w) => {
                halves::fill_by_halves(&w.runs, n, len, pm, |runs, first, out| {
                    self.fill_multipliers(runs, first, big_n, out)
                })
            }
        }
    }

    /// The positions of the particles of `runs` (the first one is particle
    /// `first`) into `out`.
    fn fill_positions(
        &self,
        runs: &[Run<i128>],
        first: usize,
        c: i128,
        den_y: u64,
        out: &mut [f64],
    ) -> Option<()> {
        let ey = self.ey;
        let mut first = first;
        let mut o = 0usize;
        for r in runs {
            let k = r.k;
            let ki = i128::from(k);
            let block = out.get_mut(o..o + k as usize)?;
            // x_i = (S + k C i) 2^{ey} / (k b_o q_o), i = first, first + 1, …
            let den = k.checked_mul(den_y)?;
            let step = ki.checked_mul(c)?;
            let first_i = i128::try_from(first).ok()?;
            let num_at = |m: u64| r.sy.checked_add(step.checked_mul(first_i + i128::from(m))?);
            if den_y == 1 {
                // x_i 2^{−ey} = ⌊S/k⌋ + C i + (S mod k)/k: one division per
                // block, none per particle (`round::nearest_plus`).
                // Runs of values in one binade at once
                // (`round::nearest_plus_run`), the others one by one.
                let split = Split::new(r.sy, k);
                let mut w = split.floor.checked_add(c.checked_mul(first_i)?)?;
                let mut m = 0usize;
                while m < block.len() {
                    let mut done = round::nearest_plus_run(w, c, &split, ey, &mut block[m..]);
                    if done == 0 {
                        block[m] = match round::nearest_plus(w, &split, ey) {
                            Some(x) => x,
                            None => round::nearest(num_at(m as u64)?, den, ey),
                        };
                        done = 1;
                    }
                    m += done;
                    if m < block.len() {
                        let moved = c.checked_mul(i128::try_from(done).ok()?)?;
                        w = w.checked_add(moved)?;
                    }
                }
            } else {
                let den = Divisor::new(den);
                for (m, x) in (0..k).zip(block.iter_mut()) {
                    *x = round::nearest_by(num_at(m)?, &den, ey);
                }
            }
            first += k as usize;
            o += k as usize;
        }
        Some(())
    }

    /// The multipliers of the pairs from `first` on, block by block over
    /// `runs`, into `out` (the last pair of a block, a gap, is `0`).
    fn fill_multipliers<W>(
        &self,
        runs: &[Run<W, i128>],
        first: usize,
        big_n: u64,
        out: &mut [f64],
    ) -> Option<()> {
        let (n, eu) = (self.n(), self.d.eu);
        let mut first = first;
        let mut o = 0usize;
        for r in runs {
            let k = r.k;
            // λ of the m-th pair of the block: (k Σ_{j ≤ m} U_j − m S_U) 2^{eu} / (k N),
            // no integer division per pair (`quotient::nearest`); the last
            // pair of a block (m = k, a gap) is exactly 0.
            if k > 1 {
                let den = Denominator::new(k.checked_mul(big_n)?);
                let block = out.get_mut(o..o + k as usize - 1)?;
                let range = first..first + k as usize;
                let within = 2 * bits(u128::from(k)) + self.d.u_bits < 127;
                match (&self.d.columns, within) {
                    (Columns::Narrow { u, .. }, true) => {
                        block_multipliers(u.get(range)?, r.su, &den, eu, block)
                    }
                    (Columns::Wide { u, .. }, true) => {
                        block_multipliers(u.get(range)?, r.su, &den, eu, block)
                    }
                    (Columns::Narrow { u, .. }, false) => {
                        block_multipliers_checked(u.get(range)?, r.su, &den, eu, block)?
                    }
                    (Columns::Wide { u, .. }, false) => {
                        block_multipliers_checked(u.get(range)?, r.su, &den, eu, block)?
                    }
                }
            }
            first += k as usize;
            o += k as usize - 1;
            if first < n {
                *out.get_mut(o)? = 0.0;
                o += 1;
            }
        }
        Some(())
    }

    /// The exact state (`prop:proj-micro`): every value in lowest terms,
    /// from the same block sums.
    pub fn exact_state(&self) -> State<BigRational> {
        match &self.sums {
            BlockSums::Narrow { runs, c } => self.exact_state_of(runs, BigInt::from(*c)),
            BlockSums::Wide(w) => self.exact_state_of(&w.runs, w.c.to_bigint()),
        }
    }

    /// [`Self::exact_state`] from the blocks `runs` and `C`.
    fn exact_state_of<W: SumY>(&self, runs: &[Run<W, i128>], c: BigInt) -> State<BigRational> {
        let n = self.n();
        let (ey, eu) = (self.ey, self.d.eu);
        let den_y = BigInt::from(self.d.b_odd) * BigInt::from(self.q_odd);
        let mut positions = Vec::with_capacity(n);
        let mut velocities = Vec::with_capacity(n);
        let mut multipliers = Vec::with_capacity(n.saturating_sub(1));
        let mut first = 0usize;
        for r in runs {
            let k = r.k;
            let kb = BigInt::from(k);
            let den = &kb * &den_y;
            for m in 0..k as usize {
                let num = r.sy.big() + &kb * &c * BigInt::from(first + m);
                positions.push(exact(num, den.clone(), ey));
            }
            let u = exact(BigInt::from(r.su), kb.clone(), eu);
            velocities.extend(std::iter::repeat_n(u, k as usize));
            let mut prefix = BigInt::zero();
            for m in 1..=k {
                let i = first + m as usize - 1;
                if i + 1 >= n {
                    break;
                }
                prefix += BigInt::from(self.d.columns.u(i).unwrap_or(0));
                let num = &kb * &prefix - BigInt::from(m) * BigInt::from(r.su);
                multipliers.push(exact(num, &kb * BigInt::from(n), eu));
            }
            first += k as usize;
        }
        // `λ ≥ 0` (eq:dyn-micro, the Coq development's `multiplier_nonneg`).
        debug_assert!(multipliers.iter().all(|l: &BigRational| !l.is_negative()));
        State {
            t: self.t.clone(),
            positions,
            velocities,
            multipliers,
            clusters: self.clusters(),
        }
    }

    /// The contact clusters of `x(t)` (`df:Omega-micro`): runs of blocks
    /// with equal `x̃` (cross-multiplied sums, exact by the kernel's bound).
    pub fn clusters(&self) -> Vec<Cluster> {
        match &self.sums {
            BlockSums::Narrow { runs, .. } => word_clusters(runs),
            BlockSums::Wide(w) => word_clusters(&w.runs),
        }
    }

    /// The words the PAVA ran on: [`Width::I128`] (or narrower), or
    /// [`Width::I256`] beyond the `i128` bound.
    pub fn width(&self) -> Width {
        match &self.sums {
            BlockSums::Narrow { .. } => Width::I128,
            BlockSums::Wide(_) => Width::I256,
        }
    }
}

#[cfg(test)]
mod tests;
