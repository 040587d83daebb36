//! A certified floating-point filter for the state of a scene of doubles at
//! a double time (issue 38): the PAVA of `prop:proj-micro` run in `f64`,
//! its partition **proved** optimal by the projection's index-form KKT
//! conditions (`\label{app:KKT}`, the Coq development's `Kkt.v`), and each
//! output rounded once to the nearest double of its exact value. Anything
//! the filter cannot prove makes it answer `None`; the caller then takes
//! the exact dyadic path ([`crate::fast::dyadic`]), which gives the same
//! doubles. The filter never answers differently from the exact engines:
//! the tests compare them bit for bit, adversarial near-ties included.
//!
//! **The problem.** With `z_i = x⁰_i + t u⁰_i − 2r i` (`df:translat-x`),
//! `x(t) = P_K(x⁰ + t u⁰)` is `x_i = m_B + 2r i` for the particle `i` of the
//! block `B` of the isotonic regression of `z`, `m_B` the mean of `z` over
//! `B`. A partition into blocks of consecutive indices gives the
//! regression (the projection onto the cone of non-decreasing vectors,
//! unique) exactly when (KKT, index form):
//!
//! 1. the block means are non-decreasing from one block to the next;
//! 2. inside each block `B = [a, b]`, every prefix sum
//!    `Σ_{a ≤ i ≤ j} (z_i − m_B) ≥ 0` (`j < b`): the multipliers are `≥ 0`.
//!
//! The filter proves both **strictly** (means strictly increasing, every
//! prefix sum `> 0`): then the partition is also the one of `z + ε u⁰` for
//! all small `ε > 0`, i.e. the exact path's lexicographic blocks, each
//! block is its own contact cluster (`df:Omega-micro`), and the velocities
//! (`eq:proj-u-micro`: block means of `u⁰`) and multipliers
//! (`eq:dyn-micro`) follow from the same partition. A tie (a prefix sum of
//! exactly 0, two touching clusters) is never proved: the exact path
//! answers it.
//!
//! **Error analysis** (standard model `|fl(a ∘ b) − a ∘ b| ≤ u |a ∘ b|`,
//! `u = 2⁻⁵³`, no underflow or overflow: every nonzero `|x⁰_i|`, `|u⁰_i|`,
//! `t`, `2r` lies in `[2⁻³⁰⁰, 2³⁰⁰]` ([`SAFE_EXP`]) and `N ≤ 2²⁶`, else the
//! filter refuses). The PAVA runs on `ẑ_i = fl(fl(x_i + fl(t u_i)) −
//! fl(2r i))`; four roundings give `|ẑ_i − z_i| ≤ u(|t u_i| + |w_i| + |s_i| +
//! |ẑ_i|) ≤ 3.01 u G ≤ 4 u G = E` with `G ≥ max|x⁰| + t max|u⁰| + 2r N`
//! (computed with `eft::up`). A mean of `m` consecutive `ẑ` by recursive
//! summation then one division is within `E + (m − 1) u G (1 + 2⁻⁴⁰) +
//! u G (1 + 2⁻⁴⁰) ≤ (4 + 2m) u G =: β(m)` of the exact mean of `z`
//! (`|ẑ_i| ≤ G(1 + 4u)`). So
//!
//! * condition 1 between blocks `A`, `B` is proved by
//!   `fl(μ̂_B − μ̂_A) > up(β(k_A) + β(k_B))` (monotone rounding: the float
//!   difference exceeding a double implies the exact one does);
//! * condition 2 at a split of `B` (`m` entries left, `k − m` right) is
//!   `mean(left) > mean(right)` (equivalent to the prefix sum being `> 0`),
//!   proved by `fl(μ̂_L − μ̂_R) > up(β(m) + β(k − m))` with the left mean from
//!   the prefix and the right one from the suffix, each a recursive sum.
//!
//! The outputs: a one-particle block's position is the nearest double of
//! `x⁰_i + t u⁰_i` (`eft::nearest_free_flight`); a larger block's
//! positions, velocity and multipliers are quotients `(Σ exact terms)/d`
//! rounded by `eft::Acc::nearest_quotient` (double-double with a bound,
//! Ziv's test), the rare undecided ones exactly.
//!
//! The decisions of the float PAVA itself need no proof: only the
//! certificate is trusted. A partition the floats got wrong fails it.

mod eft;
mod outputs;
mod pava;
mod project;
#[cfg(test)]
mod tests;

use std::sync::Arc;

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Signed, ToPrimitive};

pub use outputs::{Filtered, Partition};
pub use project::project_into;

/// Every nonzero magnitude the filter takes lies in `[2^−SAFE_EXP,
/// 2^SAFE_EXP]` (module documentation).
pub const SAFE_EXP: i32 = 300;

/// The largest `N` the filter takes: sums of indices and products of block
/// sizes (`k N`, `k i`) stay exact integers below `2⁵³`.
pub const MAX_N: usize = 1 << 26;

/// The double equal to `q`, if there is one (finite).
pub fn exact_double(q: &BigRational) -> Option<f64> {
    let d = q.to_f64()?;
    (d.is_finite() && BigRational::from_float(d).as_ref() == Some(q)).then_some(d)
}

/// Is `v` zero or of a magnitude in the filter's range, `[2^−SAFE_EXP,
/// 2^SAFE_EXP]`? (By its [`magnitude`] bits: a NaN's and an infinity's lie
/// above the range.)
#[inline]
fn in_range(v: f64) -> bool {
    const LOWEST: u64 = ((1023 - SAFE_EXP) as u64) << 52;
    const HIGHEST: u64 = ((1023 + SAFE_EXP) as u64) << 52;
    let m = magnitude(v);
    m == 0 || (LOWEST..=HIGHEST).contains(&m)
}

/// What the exact validation of columns of doubles ([`Checked::new`])
/// established, without the columns: the radius, `2r` (a double), `N`,
/// `max |u⁰_i|` and whether the filter's range holds. The filter runs on
/// the columns it was made from, wherever they live ([`Checked::at_into`]).
#[derive(Debug, Clone)]
pub struct Checked {
    radius: BigRational,
    two_r: f64,
    n: usize,
    /// `max |u⁰_i|`.
    u_max: f64,
    /// Every value in the filter's range and `N ≤ MAX_N`.
    in_range: bool,
}

/// Columns of doubles validated exactly (`df:KN`, `def:velcone`), with a
/// radius `r` such that `2r` is a double: the data of the filter, shared
/// with its answers.
#[derive(Debug, Clone)]
pub struct Doubles {
    checked: Checked,
    x: Arc<Vec<f64>>,
    u: Arc<Vec<f64>>,
}

/// Why [`Doubles::validate`] did not take the columns (they are handed
/// back).
#[derive(Debug)]
pub struct Refused {
    /// The positions given.
    pub positions: Vec<f64>,
    /// The velocities given.
    pub velocities: Vec<f64>,
    /// Invalid, or not decided in doubles.
    pub reason: Refusal,
}

/// The kind of a [`Refused`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Refusal {
    /// The data are not valid initial data (`df:KN`, `def:velcone`, a NaN
    /// or an infinity): the general path names the error.
    Invalid,
    /// `2r` is not a double, or there are no particles, or the lengths
    /// differ: the check was not made here.
    Undecided,
}

impl Doubles {
    /// The columns, validated with exact decisions in doubles: every value
    /// finite, and for each pair `x_{i+1} − x_i ≥ 2r`, with
    /// `u_{i+1} ≥ u_i` where the gap is exactly `2r` (`InitialData::new`'s
    /// checks). `radius` `None` is the paper's `1/(2N)`.
    ///
    /// **The gap test is exact.** With `d = fl(x_{i+1} − x_i)` and `2r` a
    /// double: if `d > 2r` then the exact gap `> 2r` (were it `≤ 2r`, its
    /// rounding would be `≤ fl(2r) = 2r`, rounding being monotone); if
    /// `d < 2r` the exact gap is `< 2r` likewise; if `d = 2r`, the exact gap
    /// is `d + e` with `e` the `eft::two_sum` error (`x_{i+1} − x_i = d + e`
    /// exactly), so it is `≥ 2r` iff `e ≥ 0` and equal to `2r` iff `e = 0`.
    /// (Sterbenz: when `x_i` and `x_{i+1}` are within a factor 2 the
    /// difference is exact and `e = 0`.) An infinite `d` (finite values
    /// overflowing) is a gap beyond every double, `> 2r`.
    pub fn validate(
        radius: Option<BigRational>,
        positions: Vec<f64>,
        velocities: Vec<f64>,
    ) -> Result<Doubles, Box<Refused>> {
        match Checked::new(radius, &positions, &velocities) {
            Ok(checked) => Ok(Doubles::from_checked(checked, positions, velocities)),
            Err(reason) => Err(Box::new(Refused {
                positions,
                velocities,
                reason,
            })),
        }
    }

    /// The columns `checked` was made from ([`Checked::new`]): nothing is
    /// checked again. Columns other than those (of another length) make
    /// every [`Doubles::at`] answer `None`.
    pub fn from_checked(checked: Checked, positions: Vec<f64>, velocities: Vec<f64>) -> Doubles {
        debug_assert!(positions.len() == checked.n && velocities.len() == checked.n);
        Doubles {
            checked,
            x: Arc::new(positions),
            u: Arc::new(velocities),
        }
    }

    /// What the validation established.
    pub fn checked(&self) -> &Checked {
        &self.checked
    }

    /// N.
    pub fn n(&self) -> usize {
        self.checked.n
    }

    /// The radius.
    pub fn radius(&self) -> &BigRational {
        &self.checked.radius
    }

    /// The positions and velocities.
    pub fn columns(&self) -> (&[f64], &[f64]) {
        (&self.x, &self.u)
    }

    /// The positions and velocities, shared.
    pub fn shared_columns(&self) -> (Arc<Vec<f64>>, Arc<Vec<f64>>) {
        (Arc::clone(&self.x), Arc::clone(&self.u))
    }

    /// The certified state at `t` ([`Filtered`]), or `None` when `t` is not
    /// a double `≥ 0` in range, a value is out of range, or a check of the
    /// certificate does not pass (module documentation).
    pub fn at(&self, t: &BigRational) -> Option<Filtered> {
        self.at_with(t, pava::PARALLEL_MIN)
    }

    /// [`Self::at`] with the positions' nearest doubles written into
    /// `positions` (`N` of them, e.g. a buffer of the caller's allocator):
    /// the answer's own [`Filtered::positions`] is then empty. On `None`
    /// `positions` holds anything.
    pub fn at_into(&self, t: &BigRational, positions: &mut [f64]) -> Option<Filtered> {
        self.at_into_with(t, positions, pava::PARALLEL_MIN)
    }

    /// [`Self::at`] on two threads from `parallel_min` particles on.
    fn at_with(&self, t: &BigRational, parallel_min: usize) -> Option<Filtered> {
        let mut positions = vec![0.0; self.n()];
        let mut f = self.at_into_with(t, &mut positions, parallel_min)?;
        f.set_positions(positions);
        Some(f)
    }

    /// [`Self::at_into`] on two threads from `parallel_min` particles on.
    fn at_into_with(
        &self,
        t: &BigRational,
        positions: &mut [f64],
        parallel_min: usize,
    ) -> Option<Filtered> {
        let partition = self
            .checked
            .at_into_with(&self.x, &self.u, t, positions, parallel_min)?;
        Some(Filtered::new(
            partition,
            Arc::clone(&self.x),
            Arc::clone(&self.u),
        ))
    }
}

impl Checked {
    /// Columns of doubles validated with exact decisions in doubles
    /// ([`Doubles::validate`], whose proof of the gap test this is), read
    /// where they lie; `radius` `None` is the paper's `1/(2N)`.
    pub fn new(
        radius: Option<BigRational>,
        positions: &[f64],
        velocities: &[f64],
    ) -> Result<Checked, Refusal> {
        let n = positions.len();
        if n == 0 || velocities.len() != n {
            return Err(Refusal::Undecided);
        }
        let (radius, two_r) = Checked::two_r(radius, n)?;
        let scan = check(positions, velocities, two_r);
        Checked::of_scan(radius, two_r, n, scan)
    }

    /// [`Checked::new`] on the copies it makes: `positions` and
    /// `velocities` are copied into `into_positions` and `into_velocities`
    /// (each `N` long), and every decision is made on the values written
    /// there, chunk by chunk while they are in cache. The answer is about
    /// the copies, whatever happens to the sources meanwhile: a caller
    /// that keeps the copies unchanged keeps what was checked.
    pub fn copied(
        radius: Option<BigRational>,
        positions: &[f64],
        velocities: &[f64],
        into_positions: &mut [f64],
        into_velocities: &mut [f64],
    ) -> Result<Checked, Refusal> {
        let n = positions.len();
        if n == 0
            || [
                velocities.len(),
                into_positions.len(),
                into_velocities.len(),
            ] != [n; 3]
        {
            return Err(Refusal::Undecided);
        }
        let (radius, two_r) = Checked::two_r(radius, n)?;
        let scan = copy_and_check(
            Pair::new(positions, velocities),
            Copies {
                x: into_positions,
                u: into_velocities,
            },
            two_r,
        );
        Checked::of_scan(radius, two_r, n, scan)
    }

    /// The radius (`None` is the paper's `1/(2N)`) and `2r` as a double,
    /// when it is one and `r > 0`.
    fn two_r(radius: Option<BigRational>, n: usize) -> Result<(BigRational, f64), Refusal> {
        let radius = radius.unwrap_or_else(|| BigRational::new(1.into(), BigInt::from(2 * n)));
        match exact_double(&(&radius + &radius)) {
            Some(d) if radius.is_positive() => Ok((radius, d)),
            _ => Err(Refusal::Undecided),
        }
    }

    /// What a validating scan of `n` particles found.
    fn of_scan(
        radius: BigRational,
        two_r: f64,
        n: usize,
        scan: Option<Scan>,
    ) -> Result<Checked, Refusal> {
        match scan {
            Some(Scan { u_max, in_range }) => Ok(Checked {
                radius,
                two_r,
                n,
                u_max,
                in_range: in_range && self::in_range(two_r) && n <= MAX_N,
            }),
            None => Err(Refusal::Invalid),
        }
    }

    /// N.
    pub fn n(&self) -> usize {
        self.n
    }

    /// The radius.
    pub fn radius(&self) -> &BigRational {
        &self.radius
    }

    /// [`Doubles::at_into`] on the columns `x`, `u` this was made from
    /// (borrowed, e.g. from arrays of the caller's allocator): the
    /// certified partition ([`Partition`]), the positions' nearest doubles
    /// in `positions`. `None` as [`Doubles::at`], or when a column or
    /// `positions` is not `N` long.
    pub fn at_into(
        &self,
        x: &[f64],
        u: &[f64],
        t: &BigRational,
        positions: &mut [f64],
    ) -> Option<Partition> {
        self.at_into_with(x, u, t, positions, pava::PARALLEL_MIN)
    }

    /// [`Self::at_into`] on two threads from `parallel_min` particles on.
    fn at_into_with(
        &self,
        x: &[f64],
        u: &[f64],
        t: &BigRational,
        positions: &mut [f64],
        parallel_min: usize,
    ) -> Option<Partition> {
        let n = self.n;
        if !self.in_range || t.is_negative() || [x.len(), u.len(), positions.len()] != [n; 3] {
            return None;
        }
        let tf = exact_double(t)?;
        if !in_range(tf) {
            return None;
        }
        let multi = pava::certified(self, x, u, tf, positions, parallel_min)?;
        Some(Partition::new(self.clone(), t.clone(), tf, multi))
    }
}

/// What the validating scan learnt besides validity.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Scan {
    u_max: f64,
    in_range: bool,
}

/// The exact validity checks of [`Doubles::validate`]; `None` when the
/// data are invalid. From [`PARALLEL_CHECK`] particles on, each half is
/// scanned by its own thread (the right half from the last particle of the
/// left one, so the pair across the junction is checked too).
fn check(x: &[f64], u: &[f64], two_r: f64) -> Option<Scan> {
    check_with(x, u, two_r, PARALLEL_CHECK)
}

/// [`check`] on two threads from `parallel_min` particles on (at least 2).
fn check_with(x: &[f64], u: &[f64], two_r: f64, parallel_min: usize) -> Option<Scan> {
    let n = x.len();
    if n >= parallel_min.max(2) {
        let h = n / 2;
        let (left, right) = crate::parallel::join(
            || scan(&x[..h], &u[..h], two_r),
            || scan(&x[h - 1..], &u[h - 1..], two_r),
        );
        return Some(left?.and(right?));
    }
    scan(x, u, two_r)
}

/// Two threads scan the columns from this many particles on.
const PARALLEL_CHECK: usize = 1 << 16;

impl Scan {
    /// What two scans of adjacent ranges found together.
    fn and(self, other: Scan) -> Scan {
        Scan {
            u_max: self.u_max.max(other.u_max),
            in_range: self.in_range && other.in_range,
        }
    }
}

/// The columns read by [`copy_and_check`].
#[derive(Clone, Copy)]
struct Pair<'a> {
    x: &'a [f64],
    u: &'a [f64],
}

impl<'a> Pair<'a> {
    fn new(x: &'a [f64], u: &'a [f64]) -> Pair<'a> {
        debug_assert_eq!(x.len(), u.len());
        Pair { x, u }
    }

    fn split_at(self, h: usize) -> (Pair<'a>, Pair<'a>) {
        let ((xl, xr), (ul, ur)) = (self.x.split_at(h), self.u.split_at(h));
        (Pair::new(xl, ul), Pair::new(xr, ur))
    }
}

/// Where [`copy_and_check`] writes, as long as its [`Pair`].
struct Copies<'a> {
    x: &'a mut [f64],
    u: &'a mut [f64],
}

impl Copies<'_> {
    fn split_at(&mut self, h: usize) -> (Copies<'_>, Copies<'_>) {
        let ((xl, xr), (ul, ur)) = (self.x.split_at_mut(h), self.u.split_at_mut(h));
        (Copies { x: xl, u: ul }, Copies { x: xr, u: ur })
    }
}

/// [`check`] of `from` made on its copy into `into`: each half on its own
/// thread from [`PARALLEL_CHECK`] particles on, then the pair across the
/// junction, read from the copies.
fn copy_and_check(from: Pair<'_>, into: Copies<'_>, two_r: f64) -> Option<Scan> {
    copy_and_check_with(from, into, two_r, PARALLEL_CHECK, COPY_CHUNK)
}

/// The particles copied, then scanned while in cache, at a time.
const COPY_CHUNK: usize = 1 << 10;

/// [`copy_and_check`] on two threads from `parallel_min` particles on (at
/// least 2), `chunk` particles at a time.
fn copy_and_check_with(
    from: Pair<'_>,
    mut into: Copies<'_>,
    two_r: f64,
    parallel_min: usize,
    chunk: usize,
) -> Option<Scan> {
    let n = from.x.len();
    debug_assert!(into.x.len() == n && into.u.len() == n && chunk > 0);
    if n >= parallel_min.max(2) {
        let h = n / 2;
        let (left_from, right_from) = from.split_at(h);
        let (left_into, right_into) = into.split_at(h);
        let (left, right) = crate::parallel::join(
            move || copy_and_scan(left_from, left_into, two_r, chunk),
            move || copy_and_scan(right_from, right_into, two_r, chunk),
        );
        let across = scan(&into.x[h - 1..=h], &into.u[h - 1..=h], two_r)?;
        return Some(left?.and(right?).and(across));
    }
    copy_and_scan(from, into, two_r, chunk)
}

/// The copy of `from` into `into` and [`scan`] of the copy, `chunk`
/// particles at a time, each chunk from the last particle of the one
/// before (so every pair is checked), while it is in cache.
fn copy_and_scan(from: Pair<'_>, into: Copies<'_>, two_r: f64, chunk: usize) -> Option<Scan> {
    let n = from.x.len();
    let mut found = Scan {
        u_max: 0.0,
        in_range: true,
    };
    for start in (0..n).step_by(chunk) {
        let end = (start + chunk).min(n);
        into.x[start..end].copy_from_slice(&from.x[start..end]);
        into.u[start..end].copy_from_slice(&from.u[start..end]);
        let back = start.saturating_sub(1);
        found = found.and(scan(&into.x[back..end], &into.u[back..end], two_r)?);
    }
    Some(found)
}

/// The magnitude bits of a double (its sign cleared): for two non-NaN
/// doubles `|a| ≤ |b|` iff `magnitude(a) ≤ magnitude(b)` as integers.
#[inline(always)]
fn magnitude(v: f64) -> u64 {
    v.to_bits() & !(1u64 << 63)
}

/// The checks of [`check`] on one range, in passes of operations on
/// doubles the compiler vectorizes:
///
/// * every gap: `fl(x_{i+1} − x_i) > 2r` proves the exact gap `> 2r`
///   ([`Doubles::validate`]); only when some float gap is not above `2r`
///   (or is a NaN) does the exact pair-by-pair decision run. Either way
///   the positions are then increasing (`2r > 0`), and finite when the
///   first and last are: an infinity or a NaN inside makes a gap on its
///   side `−∞` or a NaN, never above `2r`;
/// * the positions in the filter's range ([`in_range`]): being
///   increasing, the largest magnitude is at an end and the least nonzero
///   one next to the first position `≥ 0`;
/// * the velocities finite and in range, and `max |u⁰|`, by
///   [`Magnitudes`].
fn scan(x: &[f64], u: &[f64], two_r: f64) -> Option<Scan> {
    let n = x.len();
    debug_assert!(n > 0 && u.len() == n);
    let wide = x
        .iter()
        .zip(&x[1..])
        .fold(true, |all, (&a, &b)| all & (b - a > two_r));
    if !wide {
        exact_gaps(x, u, two_r)?;
    }
    let (first, last) = (x[0], x[n - 1]);
    if !(first.abs() <= f64::MAX && last.abs() <= f64::MAX) {
        return None;
    }
    let velocities = Magnitudes::of(u)?;
    // The positions next to the first one `≥ 0`.
    let k = x.partition_point(|&v| v < 0.0);
    let near_zero = &x[k.saturating_sub(1)..n.min(k + 2)];
    let in_range = velocities.in_range()
        && [first, last]
            .into_iter()
            .chain(near_zero.iter().copied())
            .all(self::in_range);
    Some(Scan {
        u_max: velocities.largest,
        in_range,
    })
}

/// The largest and the least nonzero magnitude of a column of finite
/// doubles, found in four lanes of running maxima and minima (the
/// compiler vectorizes them).
#[derive(Debug, Clone, Copy)]
struct Magnitudes {
    largest: f64,
    /// `+∞` when every value is zero.
    least_nonzero: f64,
}

impl Magnitudes {
    /// Those of `v`; `None` when a value is an infinity or a NaN (`0 v`
    /// is then a NaN, and a NaN in a lane's running sum stays).
    fn of(v: &[f64]) -> Option<Magnitudes> {
        const LANES: usize = 4;
        let mut not_finite = [0.0f64; LANES];
        let mut largest = [0.0f64; LANES];
        let mut least = [f64::INFINITY; LANES];
        // Compare-selects, one instruction each, not `f64::max` and
        // `f64::min`, which also look for NaNs: `not_finite` finds those.
        let mut lane = |l: usize, value: f64| {
            let a = value.abs();
            not_finite[l] += value * 0.0;
            largest[l] = if a > largest[l] { a } else { largest[l] };
            let nonzero = if a == 0.0 { f64::INFINITY } else { a };
            least[l] = if nonzero < least[l] {
                nonzero
            } else {
                least[l]
            };
        };
        let mut chunks = v.chunks_exact(LANES);
        for c in &mut chunks {
            for (l, &value) in c.iter().enumerate() {
                lane(l, value);
            }
        }
        for (l, &value) in chunks.remainder().iter().enumerate() {
            lane(l, value);
        }
        if not_finite.iter().any(|&s| s != 0.0) {
            return None;
        }
        let found = Magnitudes {
            largest: largest.into_iter().fold(0.0, f64::max),
            least_nonzero: least.into_iter().fold(f64::INFINITY, f64::min),
        };
        debug_assert_eq!(
            found.largest.to_bits(),
            v.iter().map(|d| magnitude(*d)).max().unwrap_or(0)
        );
        Some(found)
    }

    /// Those of two columns together.
    fn and(self, other: Magnitudes) -> Magnitudes {
        Magnitudes {
            largest: self.largest.max(other.largest),
            least_nonzero: self.least_nonzero.min(other.least_nonzero),
        }
    }

    /// Every value zero or in the filter's range ([`in_range`]).
    fn in_range(self) -> bool {
        in_range(self.largest)
            && (self.least_nonzero == f64::INFINITY || in_range(self.least_nonzero))
    }
}

/// The gap decisions of [`Doubles::validate`], pair by pair (finite
/// values): `None` at the first pair closer than `2r`, or at `2r` with
/// approaching velocities.
fn exact_gaps(x: &[f64], u: &[f64], two_r: f64) -> Option<()> {
    for (i, pair) in x.windows(2).enumerate() {
        let d = pair[1] - pair[0];
        if d > two_r {
            continue;
        }
        // `d < 2r`, or a NaN: invalid.
        if d != two_r {
            return None;
        }
        let (_, e) = eft::two_sum(pair[1], -pair[0]);
        if e < 0.0 || (e == 0.0 && u[i + 1] < u[i]) {
            return None;
        }
    }
    Some(())
}
