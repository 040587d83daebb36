//! The streaming path from a column file to the answer: bytes to the
//! integer kernel's representation to output, with no `BigRational` per
//! value where the data allow (issue 13, part 2).
//!
//! For a `[particles]` scene whose columns live in a CSV or NPY file
//! ([`crate::columns`]) or inline in the TOML ([`crate::scene::inline_scene`]),
//! [`Lean::load`] reads every value straight into a pair of machine words
//! ([`crate::columns::parse_small`], [`crate::columns::f64_small`]), scales the columns to common
//! denominators on words (`df:translat-x`, the same scaling as the kernel,
//! `fast::scaling`), validates them on the scaled integers
//! (`df:KN`: `X̃_{i+1} ≥ X̃_i`; `def:velcone`: `U_{i+1} ≥ U_i` across a
//! contact) and keeps them as `i64` columns: 16 bytes per particle.
//! [`Lean::blocks_at`] runs the kernel's PAVA on `i128` sums
//! ([`crate::fast::kernel`], `prop:proj-micro`), and [`LeanBlocks`] gives
//! each value of the state in lowest terms straight from the block sums:
//! one reduction per block for the block means (`eq:proj-u-micro`), one
//! machine-word gcd per particle for a position (`x_i = x̃ + 2r·i`) and a
//! multiplier (`eq:dyn-micro`).
//!
//! **Same results.** Everything here answers `None` the moment the data
//! leave its range (a value not on words, an overflow, an invalid scene, a
//! width the `i128` bound does not prove): the caller then takes the general
//! path ([`crate::scene::load`], [`crate::fast::kernel::state_at`]), which
//! gives the same answer or the error of record. A single value whose
//! reduction overflows words is reduced on `BigInt` ([`Exact::Big`]). The
//! tests compare both paths byte for byte.

use std::path::Path;

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Signed, ToPrimitive};

use crate::columns::{f64_small, Small};
use crate::error::Error;
use crate::fast::kernel::{size_bits, word_runs};
use crate::fast::scaling::{scale_pairs, small_word, Range};
use crate::scene::{column_scene, inline_scene, ColumnScene, MAX_NUMBER_BITS, MAX_SCENE_BYTES};

mod blocks;
mod csv;
mod digits;
mod exact;
pub mod memory;
mod nearest;
mod read;
mod reduce;
mod scale;

pub use blocks::{LeanBlocks, Piece};
pub use exact::Exact;
pub use nearest::{nearest_ratio, Nearest};

use memory::Footprint;
use read::{ColumnFile, Segment};

/// A segment of a column file and the rows it holds, from its first one
/// (known after the first pass).
struct SegmentAt {
    segment: Segment,
    first: usize,
    rows: usize,
}
use scale::ScaledColumn;

/// Bits of `|v|` (0 for 0).
fn bits_u(v: u128) -> u64 {
    u64::from(128 - v.leading_zeros())
}

/// A `[particles]` scene with a column file, on `i64` columns over common
/// denominators: `x̃⁰_i = x[i] / dx`, `u⁰_i = u[i] / du` (`df:translat-x`).
#[derive(Debug, Clone)]
pub struct Lean {
    radius: BigRational,
    two_r: (i128, i128),
    x: Vec<i64>,
    u: Vec<i64>,
    x_bits: u64,
    u_bits: u64,
    dx: i128,
    du: i128,
}

impl Lean {
    /// Reads the scene at `path` on the streaming path; `None` when it is
    /// not a `[particles]` scene with its columns inline
    /// ([`crate::scene::inline_scene`]) or in a column file, whose values fit
    /// words and whose data are valid (the module documentation: the
    /// general path then reads it), or when [`Lean::open`] refuses it.
    pub fn load(path: &Path) -> Option<Lean> {
        Lean::open(path).ok().flatten()
    }

    /// [`Lean::load`], with the refusal of a column file whose projected
    /// memory ([`Lean::footprint`]) exceeds the limit ([`memory::limit`])
    /// as [`Error::Memory`], before anything is read. A column file is
    /// read in segments on every core, twice (the denominators, then the
    /// values): the peak is the `i64` columns and the segments in memory
    /// (4 MiB together), and the general path's
    /// budget on the size of the numbers ([`MAX_NUMBER_BITS`], meant for
    /// `BigRational` data) does not apply to it.
    pub fn open(path: &Path) -> Result<Option<Lean>, Error> {
        let Ok(meta) = std::fs::metadata(path) else {
            return Ok(None);
        };
        if !meta.is_file() || meta.len() > MAX_SCENE_BYTES {
            return Ok(None);
        }
        let Ok(text) = std::fs::read(path) else {
            return Ok(None);
        };
        if let Some(s) = inline_scene(&text) {
            drop(text);
            return Ok(Lean::new(
                s.radius,
                s.charged_bits,
                s.positions,
                s.velocities,
            ));
        }
        drop(text);
        let Some((scene, file)) = Lean::column_file(path) else {
            return Ok(None);
        };
        let need = Lean::footprint_of(&file);
        let limit = memory::limit();
        if need.peak() > limit {
            return Err(Error::Memory {
                need: need.peak(),
                limit,
                message: format!(
                    "the streaming path would need {need}, over the memory limit of {} \
                     (set {}, in MiB, to change it)",
                    memory::mib(limit),
                    memory::LIMIT_VAR
                ),
            });
        }
        Ok(Lean::from_file(scene.radius, &file))
    }

    /// The column scene at `path` and its column file, when it is one.
    fn column_file(path: &Path) -> Option<(ColumnScene, ColumnFile)> {
        let scene = column_scene(path)?;
        let file = ColumnFile::open(&scene.data)?;
        Some((scene, file))
    }

    fn footprint_of(file: &ColumnFile) -> Footprint {
        Footprint::new(file.rows_at_most(), file.exact_count(), file.len())
    }

    /// The projected peak memory of the streaming path on the scene at
    /// `path`, from its column file's size and NPY header alone; `None`
    /// when it is not a column scene.
    pub fn footprint(path: &Path) -> Option<Footprint> {
        Lean::column_file(path).map(|(_, file)| Lean::footprint_of(&file))
    }

    /// The radius (`None`: `1/(2N)`) and `2r` as an `i128` fraction; `None`
    /// for a radius that is not positive or whose `2r` is not on words.
    fn radius_of(radius: Option<BigRational>, n: usize) -> Option<(BigRational, (i128, i128))> {
        let radius = radius.unwrap_or_else(|| BigRational::new(1.into(), BigInt::from(2 * n)));
        if !radius.is_positive() {
            return None;
        }
        let two_r = &radius + &radius;
        let two_r = (two_r.numer().to_i128()?, two_r.denom().to_i128()?);
        Some((radius, two_r))
    }

    /// The scene of radius `radius` (`None`: `1/(2N)`) whose columns are in
    /// `file`, read in two passes ([`scale`]), each on every core: the
    /// file's segments read on worker threads ([`crate::parallel::in_order`])
    /// and their results taken back in order.
    fn from_file(radius: Option<BigRational>, file: &ColumnFile) -> Option<Lean> {
        let segments = file.segments()?;
        let workers = crate::parallel::workers();
        // The first pass: each segment's rows and denominators.
        let (mut lx, mut lu) = (scale::Lcm::new(), scale::Lcm::new());
        let mut counts = Vec::with_capacity(segments.len());
        let denominators = |s: &Segment| {
            let (mut lx, mut lu) = (scale::Lcm::new(), scale::Lcm::new());
            let rows = file.rows_of(s, |(_, dx), (_, du)| {
                lx.add(dx)?;
                lu.add(du)
            })?;
            Some((rows, lx, lu))
        };
        crate::parallel::in_order(&segments, workers, denominators, |part| {
            let (rows, x, u) = part.ok_or(())?;
            lx.merge(&x).ok_or(())?;
            lu.merge(&u).ok_or(())?;
            counts.push(rows);
            Ok::<(), ()>(())
        })
        .ok()?;
        let n: usize = counts.iter().sum();
        if n == 0 {
            return None;
        }
        let (radius, two_r) = Lean::radius_of(radius, n)?;
        let sx = lx.scale(Some((two_r.0, u128::try_from(two_r.1).ok()?)))?;
        let su = lu.scale(None)?;
        // The second pass: each segment scaled from its first row on.
        let mut first = 0usize;
        let starts: Vec<SegmentAt> = segments
            .iter()
            .zip(&counts)
            .map(|(&segment, &rows)| {
                let at = SegmentAt {
                    segment,
                    first,
                    rows,
                };
                first += rows;
                at
            })
            .collect();
        let (mut jx, mut ju) = (sx.joined(n), su.joined(n));
        let values = |s: &SegmentAt| {
            let mut px = sx.part(s.first, s.rows)?;
            let mut pu = su.part(s.first, s.rows)?;
            let rows = file.rows_of(&s.segment, |(p, d), (q, e)| {
                px.push(p, d)?;
                pu.push(q, e)
            })?;
            (rows == s.rows).then_some((px, pu))
        };
        crate::parallel::in_order(&starts, workers, values, |part| {
            let (x, u) = part.ok_or(())?;
            jx.take(x);
            ju.take(u);
            Ok::<(), ()>(())
        })
        .ok()?;
        let (x, u) = (jx.finish()?, ju.finish()?);
        debug_assert_eq!((x.values.len(), u.values.len()), (n, n));
        Lean::valid(radius, two_r, x, u)
    }

    /// The streaming path for columns of doubles, each taken as the exact
    /// binary rational it is ([`crate::columns::f64_small`]), with radius
    /// `radius` (`None`: `1/(2N)`): what the Python package hands over from
    /// numpy arrays. `None` when a value is not finite or not on words, or
    /// the data are not valid (the general path, [`crate::InitialData::new`]
    /// on [`crate::columns::f64_exact`] values, then answers or names the
    /// error).
    pub fn from_doubles(radius: Option<BigRational>, xs: &[f64], us: &[f64]) -> Option<Lean> {
        let col = |v: &[f64]| v.iter().map(|&d| f64_small(d)).collect::<Option<Vec<_>>>();
        Lean::new(radius, 0, col(xs)?, col(us)?)
    }

    /// The streaming path for validated initial data whose every value has
    /// a numerator and a denominator on 64-bit words; `None` otherwise (the
    /// general path, [`crate::fast::kernel`], then answers).
    pub fn from_data(data: &crate::InitialData<BigRational>) -> Option<Lean> {
        let col = |v: &[BigRational]| v.iter().map(small_word).collect::<Option<Vec<_>>>();
        Lean::new(
            Some(data.radius().clone()),
            0,
            col(data.positions())?,
            col(data.velocities())?,
        )
    }

    /// The scene of radius `radius` (`None`: `1/(2N)`) with columns `xs`,
    /// `us`, `charged_bits` already charged against the number budget.
    pub(crate) fn new(
        radius: Option<BigRational>,
        charged_bits: u64,
        xs: Vec<Small>,
        us: Vec<Small>,
    ) -> Option<Lean> {
        let n = xs.len();
        if n == 0 || us.len() != n {
            return None;
        }
        // The general path's budget on the size of the numbers
        // (`scene::MAX_NUMBER_BITS`, 64 bits of header per number).
        let cost = |&(p, d): &Small| bits_u(u128::from(p.unsigned_abs())) + bits_u(d.into()) + 64;
        let total: u64 = xs.iter().chain(&us).map(cost).sum::<u64>() + charged_bits;
        if total > MAX_NUMBER_BITS {
            return None;
        }
        let (radius, two_r) = Lean::radius_of(radius, n)?;
        let s = scale_pairs((two_r.0, u128::try_from(two_r.1).ok()?), &xs, &us)?;
        drop((xs, us));
        let column = |values: &[i128], den: BigInt, range: Range| {
            Some(ScaledColumn {
                values: range.narrow(values)?,
                den: den.to_u128()?,
                range,
            })
        };
        let x = column(&s.x, s.dx, s.x_range)?;
        let u = column(&s.u, s.du, s.u_range)?;
        Lean::valid(radius, two_r, x, u)
    }

    /// The scene on its scaled columns, when the data are valid: `df:KN`
    /// and `def:velcone` on the scaled data, the checks of
    /// `InitialData::new` (the general path names the first failure).
    fn valid(
        radius: BigRational,
        two_r: (i128, i128),
        x: ScaledColumn,
        u: ScaledColumn,
    ) -> Option<Lean> {
        let (xs, us) = (&x.values, &u.values);
        for i in 1..xs.len() {
            if xs[i] < xs[i - 1] || (xs[i] == xs[i - 1] && us[i] < us[i - 1]) {
                return None;
            }
        }
        Some(Lean {
            radius,
            two_r,
            x_bits: bits_u(x.range.max_abs()),
            u_bits: bits_u(u.range.max_abs()),
            dx: i128::try_from(x.den).ok()?,
            du: i128::try_from(u.den).ok()?,
            x: x.values,
            u: u.values,
        })
    }

    /// N.
    pub fn n(&self) -> usize {
        self.x.len()
    }

    /// What `--explain` says of this path: `N`, the widths of the scaled
    /// columns and of their common denominators.
    pub fn explain(&self) -> String {
        format!(
            "engine: streaming (N = {}, positions of {} bits over a denominator of {} bits, \
             velocities of {} bits over one of {} bits): i64 columns and the i128 PAVA; \
             a time beyond its bound goes to the general path",
            self.n(),
            self.x_bits,
            bits_u(self.dx.unsigned_abs()),
            self.u_bits,
            bits_u(self.du.unsigned_abs()),
        )
    }

    /// The whole collision history on the integer event merge
    /// ([`crate::fast::merge`]); `None` when its bound does not hold.
    pub fn history(&self) -> Option<crate::fast::merge::WordHistory> {
        crate::fast::merge::history_words(&self.x, &self.u, self.dx, self.du)
    }

    /// The radius r.
    pub fn radius(&self) -> &BigRational {
        &self.radius
    }

    /// The exact PAVA blocks at `t ≥ 0` on `i128` sums ([`crate::fast::kernel`]),
    /// `None` when `t < 0` or the `i128` bound of the kernel does not hold at
    /// `t` (then the general path answers).
    pub fn blocks_at(&self, t: &BigRational) -> Option<LeanBlocks<'_>> {
        if t.is_negative() {
            return None;
        }
        let (p, q) = (t.numer().to_i64()?, t.denom().to_i64()?);
        // Y_i = a X_i + b U_i, a = q D_u, b = p D_x, over D_y = q D_x D_u.
        let a = i64::try_from(i128::from(q).checked_mul(self.du)?).ok()?;
        let b = i64::try_from(i128::from(p).checked_mul(self.dx)?).ok()?;
        let b_k = size_bits(self.n());
        let b_y = (bits_u(u128::from(a.unsigned_abs())) + self.x_bits)
            .max(bits_u(u128::from(b.unsigned_abs())) + self.u_bits)
            + 1;
        if b_y + b_k >= 128 || self.u_bits + b_k >= 128 {
            return None;
        }
        // |a|, |X_i|, |b|, |U_i| < 2^63 and the sums below 2^(b_Y + b_K):
        // the kernel's `i128` bound, under which its loop is exact.
        let runs = word_runs(&self.x, &self.u, a, b, self.u_bits);
        // Every denominator of the state divides k q D_x D_u r_d N
        // (positions, velocities, multipliers: `LeanBlocks`).
        let fixed = [
            u128::from(q.unsigned_abs()),
            self.dx.unsigned_abs(),
            self.du.unsigned_abs(),
            self.two_r.1.unsigned_abs(),
            self.n() as u128,
        ];
        Some(LeanBlocks {
            d: self,
            runs,
            t: t.clone(),
            dy: (i128::from(q).checked_mul(self.dx)).and_then(|v| v.checked_mul(self.du)),
            primes: reduce::ScenePrimes::of(&fixed),
        })
    }
}

#[cfg(test)]
mod tests;
