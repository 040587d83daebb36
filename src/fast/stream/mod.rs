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

use std::io::{self, Write};
use std::path::Path;

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Signed, ToPrimitive, Zero};

use crate::cluster::Cluster;
use crate::columns::{f64_small, Small};
use crate::error::Error;
use crate::fast::int::gcd;
use crate::fast::kernel::{i128_clusters, pava_words, size_bits, Run};
use crate::fast::scaling::{scale_pairs, small_word, Range};
use crate::scene::{column_scene, inline_scene, ColumnScene, MAX_NUMBER_BITS, MAX_SCENE_BYTES};

mod csv;
mod digits;
pub mod memory;
mod read;
mod scale;

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

/// One exact value, in lowest terms: on words, or a `BigRational` when its
/// reduction did not fit them.
#[derive(Debug, Clone, PartialEq)]
pub enum Exact {
    /// `num / den`, `den > 0`, in lowest terms.
    Small(i128, i128),
    /// Any rational.
    Big(BigRational),
}

impl Exact {
    /// `num / den` (`den > 0`) in lowest terms.
    pub(crate) fn ratio(num: i128, den: i128) -> Exact {
        let (a, b) = (num.unsigned_abs(), den.unsigned_abs());
        let g = gcd(a, b);
        if g <= 1 {
            return if num == 0 {
                Exact::Small(0, 1)
            } else {
                Exact::Small(num, den)
            };
        }
        // The divisions on 64-bit words when both terms fit them (most
        // values): the same quotients.
        if let (Ok(a), Ok(b), Ok(g)) = (u64::try_from(a), u64::try_from(b), u64::try_from(g)) {
            let (p, q) = (i128::from(a / g), i128::from(b / g));
            return Exact::Small(if num < 0 { -p } else { p }, if den < 0 { -q } else { q });
        }
        let g = g as i128;
        Exact::Small(num / g, den / g)
    }
    /// `num / den` on `BigInt`.
    fn big(num: BigInt, den: BigInt) -> Exact {
        Exact::Big(BigRational::new(num, den))
    }
    /// Writes the value as the contract does: `p/q`, or `p` when `q = 1`
    /// ([`crate::rational::render_exact`]).
    pub fn write<W: Write + ?Sized>(&self, out: &mut W) -> io::Result<()> {
        write!(out, "{self}")
    }
}

impl std::fmt::Display for Exact {
    /// `p/q`, or `p` when `q = 1`, as [`Exact::write`].
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Exact::Small(n, 1) => write!(f, "{n}"),
            Exact::Small(n, d) => write!(f, "{n}/{d}"),
            Exact::Big(q) => f.write_str(&crate::rational::render_exact(q)),
        }
    }
}

impl Exact {
    /// The nearest double (ties to even; `±∞` beyond the range): one
    /// correctly rounded division when both terms are exact doubles,
    /// `BigRational`'s conversion otherwise.
    pub fn to_f64_lossy(&self) -> f64 {
        const EXACT: i128 = 1 << 53;
        match self {
            Exact::Small(n, d) if n.abs() <= EXACT && *d <= EXACT => *n as f64 / *d as f64,
            _ => {
                let (n, d) = self.numer_denom();
                crate::scalar::Scalar::to_f64_lossy(&BigRational::new(n, d))
            }
        }
    }
    fn numer_denom(&self) -> (BigInt, BigInt) {
        match self {
            Exact::Small(n, d) => (BigInt::from(*n), BigInt::from(*d)),
            Exact::Big(q) => (q.numer().clone(), q.denom().clone()),
        }
    }
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
        let (a, b) = (i128::from(a), i128::from(b));
        let (xs, us) = (&self.x, &self.u);
        // |a|, |X_i|, |b|, |U_i| < 2^63 and the sums below 2^(b_Y + b_K)
        // (the kernel's proof): the wrapping operations are exact.
        let runs = pava_words(self.n(), |i| {
            let (x, u) = (i128::from(xs[i]), i128::from(us[i]));
            (a.wrapping_mul(x).wrapping_add(b.wrapping_mul(u)), u)
        });
        Some(LeanBlocks {
            d: self,
            runs,
            t: t.clone(),
            dy: (i128::from(q).checked_mul(self.dx)).and_then(|v| v.checked_mul(self.du)),
        })
    }
}

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
        return Some(sign * (a as f64 / b as f64));
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
    Some(sign * (m as f64) * scale)
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

/// A stretch of whole blocks of a [`LeanBlocks`] ([`LeanBlocks::pieces`]):
/// its values can be computed apart from the others' and put back in order.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Piece {
    /// The index of its first particle.
    first: usize,
    /// Its blocks, as indices into the blocks of the time.
    runs: std::ops::Range<usize>,
}

/// The PAVA blocks of a [`Lean`] scene at one time, and the state they give,
/// value by value.
#[derive(Debug)]
pub struct LeanBlocks<'a> {
    d: &'a Lean,
    runs: Vec<Run<i128>>,
    t: BigRational,
    dy: Option<i128>,
}

impl LeanBlocks<'_> {
    /// The time.
    pub fn t(&self) -> &BigRational {
        &self.t
    }

    /// N.
    pub fn n(&self) -> usize {
        self.d.n()
    }

    /// `s / (k d)` in lowest terms, for a block sum `s` over `k` entries and
    /// a denominator `d` (on words when `k d` fits).
    fn mean(&self, s: i128, k: u64, d: Option<i128>, d_big: impl Fn() -> BigInt) -> Exact {
        match d.and_then(|d| d.checked_mul(i128::from(k))) {
            Some(den) => Exact::ratio(s, den),
            None => Exact::big(BigInt::from(s), d_big() * BigInt::from(k)),
        }
    }

    fn mean_y(&self, r: &Run<i128>) -> Exact {
        let (q, dx, du) = (self.t.denom(), self.d.dx, self.d.du);
        self.mean(r.sy, r.k, self.dy, || {
            q * BigInt::from(dx) * BigInt::from(du)
        })
    }

    fn mean_u(&self, r: &Run<i128>) -> Exact {
        let du = self.d.du;
        self.mean(r.su, r.k, Some(du), || BigInt::from(du))
    }

    /// Calls `f` on every position `x_i(t)` in order: the block's `x̃` plus
    /// `2r·i`, one fraction in lowest terms.
    pub fn positions(&self, f: impl FnMut(&Exact) -> io::Result<()>) -> io::Result<()> {
        self.positions_from(&self.runs, 0, f)
    }

    /// The blocks cut, at block ends, into pieces of at least `particles`
    /// particles each (the last one may hold fewer), in order: together
    /// they hold every block once.
    pub fn pieces(&self, particles: usize) -> Vec<Piece> {
        let mut pieces = Vec::new();
        let (mut first, mut start, mut size) = (0usize, 0usize, 0usize);
        for (j, r) in self.runs.iter().enumerate() {
            size += r.k as usize;
            if size >= particles.max(1) {
                pieces.push(Piece {
                    first,
                    runs: start..j + 1,
                });
                first += size;
                (start, size) = (j + 1, 0);
            }
        }
        if start < self.runs.len() {
            pieces.push(Piece {
                first,
                runs: start..self.runs.len(),
            });
        }
        debug_assert_eq!(
            pieces.iter().map(|p| p.runs.len()).sum::<usize>(),
            self.runs.len()
        );
        pieces
    }

    /// [`Self::positions`] of the particles of `piece` only.
    pub fn positions_of(
        &self,
        piece: &Piece,
        f: impl FnMut(&Exact) -> io::Result<()>,
    ) -> io::Result<()> {
        self.positions_from(&self.runs[piece.runs.clone()], piece.first, f)
    }

    /// [`Self::velocities`] of the particles of `piece` only.
    pub fn velocities_of(
        &self,
        piece: &Piece,
        f: impl FnMut(&Exact) -> io::Result<()>,
    ) -> io::Result<()> {
        self.velocities_from(&self.runs[piece.runs.clone()], f)
    }

    /// [`Self::multipliers`] of the pairs `(i, i + 1)` whose left particle
    /// `i` is in `piece` (none for the last particle).
    pub fn multipliers_of(
        &self,
        piece: &Piece,
        f: impl FnMut(&Exact) -> io::Result<()>,
    ) -> io::Result<()> {
        self.multipliers_from(&self.runs[piece.runs.clone()], piece.first, self.n(), f)
    }

    fn positions_from(
        &self,
        runs: &[Run<i128>],
        mut i: usize,
        mut f: impl FnMut(&Exact) -> io::Result<()>,
    ) -> io::Result<()> {
        let (rn, rd) = self.d.two_r;
        for r in runs {
            let y = self.mean_y(r);
            for _ in 0..r.k {
                let small = match &y {
                    Exact::Small(yn, yd) => (|| {
                        let num = yn.checked_mul(rd)?.checked_add(
                            rn.checked_mul(*yd)?.checked_mul(i128::try_from(i).ok()?)?,
                        )?;
                        Some(Exact::ratio(num, yd.checked_mul(rd)?))
                    })(),
                    Exact::Big(_) => None,
                };
                let v = small.unwrap_or_else(|| {
                    let (yn, yd) = y.numer_denom();
                    let (rn, rd) = (BigInt::from(rn), BigInt::from(rd));
                    Exact::big(&yn * &rd + rn * &yd * BigInt::from(i), yd * rd)
                });
                f(&v)?;
                i += 1;
            }
        }
        Ok(())
    }

    /// Calls `f` on every velocity `u_i(t)` in order (the right derivative,
    /// `eq:proj-u-micro`): one value per block, given `k` times.
    pub fn velocities(&self, f: impl FnMut(&Exact) -> io::Result<()>) -> io::Result<()> {
        self.velocities_from(&self.runs, f)
    }

    fn velocities_from(
        &self,
        runs: &[Run<i128>],
        mut f: impl FnMut(&Exact) -> io::Result<()>,
    ) -> io::Result<()> {
        for r in runs {
            let v = self.mean_u(r);
            for _ in 0..r.k {
                f(&v)?;
            }
        }
        Ok(())
    }

    /// Calls `f` on every multiplier `λ_1 … λ_{N−1}` of `eq:dyn-micro` in
    /// order: on a block of `k` particles with `S = ΣU`, the `m`-th is
    /// `(k Σ_{j ≤ m} U_j − m S) / (k D_u N)`
    /// ([`crate::contact::cluster_multiplier_numerators`]).
    pub fn multipliers(&self, f: impl FnMut(&Exact) -> io::Result<()>) -> io::Result<()> {
        self.multipliers_from(&self.runs, 0, self.n(), f)
    }

    fn multipliers_from(
        &self,
        runs: &[Run<i128>],
        mut first: usize,
        n: usize,
        mut f: impl FnMut(&Exact) -> io::Result<()>,
    ) -> io::Result<()> {
        let big_n = i128::try_from(n).unwrap_or(i128::MAX);
        for r in runs {
            let k = i128::from(r.k);
            let den = k.checked_mul(self.d.du).and_then(|v| v.checked_mul(big_n));
            let mut prefix = 0i128;
            for m in 1..=r.k as usize {
                let i = first + m - 1;
                if i + 1 >= n {
                    break;
                }
                // |prefix| ≤ k 2^u_bits < 2^127 (the kernel's bound).
                prefix = prefix.wrapping_add(i128::from(self.d.u[i]));
                let num = k
                    .checked_mul(prefix)
                    .and_then(|a| a.checked_sub(i128::try_from(m).ok()?.checked_mul(r.su)?));
                let v = match (num, den) {
                    (Some(0), _) => Exact::Small(0, 1),
                    (Some(num), Some(den)) => Exact::ratio(num, den),
                    _ => {
                        let num = BigInt::from(k) * BigInt::from(prefix)
                            - BigInt::from(m) * BigInt::from(r.su);
                        if num.is_zero() {
                            Exact::Small(0, 1)
                        } else {
                            Exact::big(
                                num,
                                BigInt::from(k) * BigInt::from(self.d.du) * BigInt::from(n),
                            )
                        }
                    }
                };
                f(&v)?;
            }
            first += r.k as usize;
        }
        Ok(())
    }

    /// Calls `f(i, x_i, u_i, λ_{i+1})` on every particle in order (0-based
    /// `i`; `λ` of the pair `(i, i+1)`, `None` for the last particle): the
    /// values of [`Self::positions`], [`Self::velocities`] and
    /// [`Self::multipliers`], row by row.
    pub fn rows(
        &self,
        mut f: impl FnMut(usize, &Exact, &Exact, Option<&Exact>) -> io::Result<()>,
    ) -> io::Result<()> {
        // The three visitors in step, one block at a time.
        let n = self.n();
        let mut i = 0usize;
        for r in &self.runs {
            let one = LeanBlocks {
                d: self.d,
                runs: vec![r.clone()],
                t: self.t.clone(),
                dy: self.dy,
            };
            let (mut xs, mut us, mut ls) = (Vec::new(), Vec::new(), Vec::new());
            let k = r.k as usize;
            one.positions_from(&one.runs, i, |v| {
                xs.push(v.clone());
                Ok(())
            })?;
            one.velocities(|v| {
                us.push(v.clone());
                Ok(())
            })?;
            one.multipliers_from(&one.runs, i, n, |v| {
                ls.push(v.clone());
                Ok(())
            })?;
            for m in 0..k {
                f(i + m, &xs[m], &us[m], ls.get(m))?;
            }
            i += k;
        }
        Ok(())
    }

    /// The state rounded to the nearest doubles (ties to even), each value
    /// rounded once from its exact value: the same doubles as
    /// [`Exact::to_f64_lossy`] of [`Self::positions`], [`Self::velocities`]
    /// and [`Self::multipliers`], without their reductions to lowest terms
    /// ([`nearest_ratio`] on the unreduced fractions; the reduced path when
    /// one of them does not fit words).
    pub fn nearest(&self) -> Nearest {
        self.nearest_words().unwrap_or_else(|| Nearest {
            positions: self.rounded(|f| self.positions(f)),
            velocities: self.rounded(|f| self.velocities(f)),
            multipliers: self.rounded(|f| self.multipliers(f)),
        })
    }

    /// The values a visitor gives, each rounded to the nearest double.
    fn rounded(&self, visit: impl FnOnce(&mut Visitor<'_>) -> io::Result<()>) -> Vec<f64> {
        let mut v = Vec::with_capacity(self.n());
        // The visitors fail only when their callback does; this one never does.
        let _ = visit(&mut |e| {
            v.push(e.to_f64_lossy());
            Ok(())
        });
        v
    }

    fn nearest_words(&self) -> Option<Nearest> {
        let n = self.n();
        let (rn, rd) = self.d.two_r;
        let big_n = i128::try_from(n).ok()?;
        let mut out = Nearest {
            positions: Vec::with_capacity(n),
            velocities: Vec::with_capacity(n),
            multipliers: Vec::with_capacity(n.saturating_sub(1)),
        };
        let mut first = 0usize;
        for r in &self.runs {
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
        Some(out)
    }

    /// The contact clusters of `x(t)` (`df:Omega-micro`): runs of blocks
    /// with equal `x̃` (cross-multiplied sums, exact by the kernel's bound).
    pub fn clusters(&self) -> Vec<Cluster> {
        i128_clusters(&self.runs)
    }
}

#[cfg(test)]
mod tests;
