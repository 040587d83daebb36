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

use crate::cluster::{runs, Cluster};
use crate::columns::{read_csv_small, read_npy_small, Small};
use crate::fast::int::gcd;
use crate::fast::kernel::{pava_words, size_bits, Run};
use crate::fast::scaling::scale_pairs;
use crate::scene::{column_scene, inline_scene, MAX_NUMBER_BITS, MAX_SCENE_BYTES};

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
        let g = gcd(num.unsigned_abs(), den.unsigned_abs());
        if g <= 1 {
            return if num == 0 {
                Exact::Small(0, 1)
            } else {
                Exact::Small(num, den)
            };
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
        match self {
            Exact::Small(n, 1) => write!(out, "{n}"),
            Exact::Small(n, d) => write!(out, "{n}/{d}"),
            Exact::Big(q) => write!(out, "{}", crate::rational::render_exact(q)),
        }
    }
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
    /// general path then reads it).
    pub fn load(path: &Path) -> Option<Lean> {
        let meta = std::fs::metadata(path).ok()?;
        if !meta.is_file() || meta.len() > MAX_SCENE_BYTES {
            return None;
        }
        let text = std::fs::read(path).ok()?;
        if let Some(s) = inline_scene(&text) {
            drop(text);
            return Lean::new(s.radius, s.charged_bits, s.positions, s.velocities);
        }
        drop(text);
        let scene = column_scene(path)?;
        let (xs, us) = {
            let bytes = std::fs::read(&scene.data).ok()?;
            match scene.data.extension().and_then(|e| e.to_str()) {
                Some("csv") => read_csv_small(&bytes)?,
                Some("npy") => read_npy_small(&bytes)?,
                _ => return None,
            }
        };
        Lean::new(scene.radius, scene.charged_bits, xs, us)
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
        let radius = radius.unwrap_or_else(|| BigRational::new(1.into(), BigInt::from(2 * n)));
        if !radius.is_positive() {
            return None;
        }
        let two_r = &radius + &radius;
        let two_r = (two_r.numer().to_i128()?, two_r.denom().to_i128()?);
        let s = scale_pairs((two_r.0, u128::try_from(two_r.1).ok()?), &xs, &us)?;
        drop((xs, us));
        // `df:KN` and `def:velcone` on the scaled data, the checks of
        // `InitialData::new` (the general path names the first failure).
        for i in 1..n {
            if s.x[i] < s.x[i - 1] || (s.x[i] == s.x[i - 1] && s.u[i] < s.u[i - 1]) {
                return None;
            }
        }
        let narrow = |v: &[i128]| v.iter().map(|&a| i64::try_from(a).ok()).collect();
        let (x, u): (Option<Vec<i64>>, Option<Vec<i64>>) = (narrow(&s.x), narrow(&s.u));
        let max_bits = |v: &[i64]| {
            v.iter()
                .map(|a| bits_u(u128::from(a.unsigned_abs())))
                .max()
                .unwrap_or(0)
        };
        let (x, u) = (x?, u?);
        Some(Lean {
            radius,
            two_r,
            x_bits: max_bits(&x),
            u_bits: max_bits(&u),
            x,
            u,
            dx: s.dx.to_i128()?,
            du: s.du.to_i128()?,
        })
    }

    /// N.
    pub fn n(&self) -> usize {
        self.x.len()
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
        self.positions_from(0, f)
    }

    fn positions_from(
        &self,
        mut i: usize,
        mut f: impl FnMut(&Exact) -> io::Result<()>,
    ) -> io::Result<()> {
        let (rn, rd) = self.d.two_r;
        for r in &self.runs {
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
    pub fn velocities(&self, mut f: impl FnMut(&Exact) -> io::Result<()>) -> io::Result<()> {
        for r in &self.runs {
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
        self.multipliers_from(0, self.n(), f)
    }

    fn multipliers_from(
        &self,
        mut first: usize,
        n: usize,
        mut f: impl FnMut(&Exact) -> io::Result<()>,
    ) -> io::Result<()> {
        let big_n = i128::try_from(n).unwrap_or(i128::MAX);
        for r in &self.runs {
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
            one.positions_from(i, |v| {
                xs.push(v.clone());
                Ok(())
            })?;
            one.velocities(|v| {
                us.push(v.clone());
                Ok(())
            })?;
            one.multipliers_from(i, n, |v| {
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

    /// The contact clusters of `x(t)` (`df:Omega-micro`): runs of blocks
    /// with equal `x̃` (cross-multiplied sums, exact by the kernel's bound).
    pub fn clusters(&self) -> Vec<Cluster> {
        let blocks = runs(self.runs.len(), |j| {
            let (a, b) = (&self.runs[j], &self.runs[j + 1]);
            a.sy.wrapping_mul(i128::from(b.k)) == b.sy.wrapping_mul(i128::from(a.k))
        });
        let mut first = 0usize;
        blocks
            .into_iter()
            .map(|c| {
                let size: u64 = self.runs[c.first..c.first + c.size]
                    .iter()
                    .map(|r| r.k)
                    .sum();
                let start = first;
                first += size as usize;
                Cluster {
                    first: start,
                    size: size as usize,
                }
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fast::kernel::{state_at, IntegerData};
    use crate::generate::{initial_data, Limits, SplitMix64};
    use crate::initial::InitialData;
    use crate::rational::ratio as q;
    use crate::trajectory::{probe_times, Trajectory};

    /// A visitor of values, as `LeanBlocks` calls it.
    type Sink<'a> = dyn FnMut(&Exact) -> io::Result<()> + 'a;

    /// The value of `v`, checked to be in lowest terms with `den > 0`.
    fn value(v: &Exact) -> BigRational {
        if let Exact::Small(n, d) = *v {
            assert!(
                d > 0 && gcd(n.unsigned_abs(), d.unsigned_abs()) == 1,
                "{v:?}"
            );
        }
        let (n, d) = v.numer_denom();
        BigRational::new(n, d)
    }

    /// `data` as word pairs, the radius given (`None`: the paper's `1/(2N)`).
    fn lean(data: &InitialData<BigRational>, radius: bool) -> Option<Lean> {
        let pair = |q: &BigRational| Some((q.numer().to_i64()?, q.denom().to_u64()?));
        let col = |v: &[BigRational]| v.iter().map(pair).collect::<Option<Vec<_>>>();
        let r = radius.then(|| data.radius().clone());
        Lean::new(r, 0, col(data.positions())?, col(data.velocities())?)
    }

    /// The streaming path's state — positions, velocities, multipliers,
    /// clusters, row by row as well — is the kernel's at every probe time
    /// (collision instants and between), each value in lowest terms, and
    /// its event history is the generic event merge's.
    #[test]
    fn lean_state_and_history_are_the_kernels() {
        let mut rng = SplitMix64::new(31);
        for k in 0..120 {
            let data = initial_data(
                &rng.bytes(200),
                Limits {
                    max_n: 1 + k % 25,
                    max_den: 1 + (k % 6) as u32,
                    max_speed: 1 + (k % 7) as u32,
                },
            );
            let n = data.n();
            let l = lean(&data, true).expect("small data on words");
            assert_eq!((l.n(), l.radius()), (n, data.radius()));
            let d = IntegerData::new(&data);
            let history = Trajectory::new(data.clone());
            for t in probe_times(&history, Some(6)) {
                let want = state_at(&d, &t).unwrap();
                let b = l.blocks_at(&t).expect("within the i128 bound");
                assert_eq!((b.t(), b.n()), (&t, n));
                let collect = |visit: &dyn Fn(&mut Sink)| {
                    let mut v = Vec::new();
                    visit(&mut |e| {
                        v.push(value(e));
                        Ok(())
                    });
                    v
                };
                let xs = collect(&|f| b.positions(f).unwrap());
                let us = collect(&|f| b.velocities(f).unwrap());
                let ls = collect(&|f| b.multipliers(f).unwrap());
                assert_eq!(xs, want.positions, "scene {k}, t = {t}");
                assert_eq!(us, want.velocities, "scene {k}, t = {t}");
                assert_eq!(ls, want.multipliers, "scene {k}, t = {t}");
                assert_eq!(b.clusters(), want.clusters, "scene {k}, t = {t}");
                let mut rows = 0;
                b.rows(|i, x, u, lambda| {
                    assert_eq!(i, rows);
                    assert_eq!((value(x), value(u)), (xs[i].clone(), us[i].clone()));
                    assert_eq!(lambda.map(value), ls.get(i).cloned());
                    rows += 1;
                    Ok(())
                })
                .unwrap();
                assert_eq!(rows, n);
            }
            let events = lean_events(&l);
            let want: Vec<_> = history
                .impulses()
                .iter()
                .map(|i| {
                    let parts = i.parts.iter().map(|c| c.size as u32).collect();
                    (i.t.clone(), i.cluster.first, i.cluster.size, parts)
                })
                .collect();
            assert_eq!(events, want, "scene {k}");
        }
    }

    /// Without a radius the scene takes the paper's `r = 1/(2N)`; data that
    /// `InitialData::new` refuses (overlap, crossing velocities at a
    /// contact), columns of different lengths, no particles, a negative time
    /// and values beyond the number budget are declined (`None`).
    #[test]
    fn lean_declines_what_the_general_path_refuses() {
        let xs = vec![(0, 1), (1, 2), (3, 1)];
        let us = vec![(1, 1), (-1, 3), (0, 1)];
        let l = Lean::new(None, 0, xs.clone(), us.clone()).unwrap();
        assert_eq!(l.radius(), &q(1, 6));
        let general = InitialData::with_paper_radius(
            vec![q(0, 1), q(1, 2), q(3, 1)],
            vec![q(1, 1), q(-1, 3), q(0, 1)],
        )
        .unwrap();
        let t = q(1, 5);
        let b = l.blocks_at(&t).unwrap();
        let mut got = Vec::new();
        b.positions(|v| {
            got.push(value(v));
            Ok(())
        })
        .unwrap();
        assert_eq!(
            got,
            state_at(&IntegerData::new(&general), &t).unwrap().positions
        );
        assert!(l.blocks_at(&q(-1, 5)).is_none());
        // r = 1/4: 0 and 1/3 overlap.
        assert!(Lean::new(Some(q(1, 4)), 0, xs.clone(), us.clone()).is_none());
        // A contact (0, 1/2 at r = 1/4) with crossing velocities.
        assert!(Lean::new(Some(q(1, 4)), 0, vec![(0, 1), (1, 2)], vec![(1, 1), (0, 1)]).is_none());
        assert!(Lean::new(Some(q(1, 4)), 0, vec![(0, 1), (1, 2)], vec![(0, 1), (1, 1)]).is_some());
        assert!(Lean::new(Some(q(1, 4)), 0, vec![(0, 1), (1, 2)], vec![(0, 1), (0, 1)]).is_some());
        assert!(Lean::new(None, 0, xs.clone(), us[..2].to_vec()).is_none());
        assert!(Lean::new(None, 0, Vec::new(), Vec::new()).is_none());
        assert!(Lean::new(Some(q(0, 1)), 0, xs.clone(), us.clone()).is_none());
        // The number budget: charged bits push the total over it.
        assert!(Lean::new(None, MAX_NUMBER_BITS - 10, xs.clone(), us.clone()).is_none());
        // The six numbers cost their bits (numerators 0, 1, 2, 1, 1, 0;
        // denominators 1, 2, 1, 1, 2, 1) and 64 each: 5 + 8 + 384.
        let cost = 397;
        assert!(Lean::new(None, MAX_NUMBER_BITS - cost, xs.clone(), us.clone()).is_some());
        assert!(Lean::new(None, MAX_NUMBER_BITS - cost + 1, xs, us).is_none());
    }

    /// `Exact`: lowest terms, the contract's rendering (`p/q`, `p` when
    /// `q = 1`) and the nearest double.
    #[test]
    fn exact_values_render_and_round() {
        assert_eq!(Exact::ratio(0, 7), Exact::Small(0, 1));
        assert_eq!(Exact::ratio(6, 4), Exact::Small(3, 2));
        assert_eq!(Exact::ratio(-6, 3), Exact::Small(-2, 1));
        assert_eq!(Exact::ratio(5, 3), Exact::Small(5, 3));
        let text = |v: &Exact| {
            let mut out = Vec::new();
            v.write(&mut out).unwrap();
            String::from_utf8(out).unwrap()
        };
        assert_eq!(text(&Exact::ratio(-6, 4)), "-3/2");
        assert_eq!(text(&Exact::ratio(8, 4)), "2");
        let big = BigRational::new(BigInt::from(1) << 130, BigInt::from(3));
        assert_eq!(text(&Exact::Big(big.clone())), big.to_string());
        assert_eq!(Exact::ratio(1, 3).to_f64_lossy(), 1.0 / 3.0);
        assert_eq!(Exact::ratio(-7, 2).to_f64_lossy(), -3.5);
        // Beyond 2^53 the division of doubles would round twice.
        let (n, d) = ((1i128 << 60) + 1, 3i128);
        let want = crate::scalar::Scalar::to_f64_lossy(&q(n as i64, d as i64));
        assert_eq!(Exact::Small(n, d).to_f64_lossy(), want);
        assert_eq!(Exact::Small(1 << 53, 1).to_f64_lossy(), 2f64.powi(53));
        // A numerator beyond 2^53 whose rounding before the division moves
        // the quotient to another double: 579832826712306748/510 =
        // 1136927111200601.466…, whose nearest double is …601.5; rounding
        // the numerator first gives …601.25.
        let (n, d) = (579_832_826_712_306_748i128, 510i128);
        assert_eq!(Exact::Small(n, d).to_f64_lossy(), 1_136_927_111_200_601.5);
        // The same with the denominator beyond 2^53.
        let (n, d) = (41_260_899_282i128, 996_700_932_334_889_006i128);
        let want = crate::scalar::Scalar::to_f64_lossy(&BigRational::new(n.into(), d.into()));
        assert_ne!(want, n as f64 / d as f64);
        assert_eq!(Exact::Small(n, d).to_f64_lossy(), want);
        assert_eq!(Exact::Big(big.clone()).to_f64_lossy(), 2f64.powi(130) / 3.0);
    }

    /// `Lean::load` reads a `[particles]` scene whose columns are in a CSV
    /// or an NPY file into the same scaled columns as the values given
    /// directly; a directory, a missing file and a scene that is not a
    /// column scene are declined.
    #[test]
    fn load_reads_csv_and_npy_scenes() {
        let dir = std::env::temp_dir().join(format!("sticky-lean-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let scene = |name: &str, data: &str| {
            let path = dir.join(format!("{name}.toml"));
            let text = format!("[particles]\nradius = \"1/8\"\ndata = \"{data}\"\n");
            std::fs::write(&path, text).unwrap();
            path
        };
        std::fs::write(
            dir.join("a.csv"),
            format!("{}\n0,1\n1/2,-1/4\n3,0\n", crate::columns::CSV_HEADER),
        )
        .unwrap();
        let rows = [(0.0, 1.0), (0.5, -0.25), (3.0, 0.0)];
        std::fs::write(dir.join("a.npy"), crate::columns::write_npy(&rows)).unwrap();
        let want = Lean::new(
            Some(q(1, 8)),
            0,
            vec![(0, 1), (1, 2), (3, 1)],
            vec![(1, 1), (-1, 4), (0, 1)],
        )
        .unwrap();
        for data in ["a.csv", "a.npy"] {
            let l = Lean::load(&scene(&data.replace('.', "-"), data))
                .unwrap_or_else(|| panic!("{data}"));
            assert_eq!(
                (&l.x, &l.u, l.dx, l.du, &l.radius, l.two_r),
                (&want.x, &want.u, want.dx, want.du, &want.radius, want.two_r),
                "{data}"
            );
        }
        assert!(Lean::load(&dir).is_none());
        assert!(Lean::load(&dir.join("missing.toml")).is_none());
        std::fs::write(dir.join("a.txt"), "0,1\n").unwrap();
        assert!(Lean::load(&scene("txt", "a.txt")).is_none());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// The event history of `l` (time, first, size, part sizes).
    fn lean_events(l: &Lean) -> Vec<(BigRational, usize, usize, Vec<u32>)> {
        let mut events = Vec::new();
        l.history()
            .expect("within the merge's bound")
            .for_each_event(|t, first, size, parts| {
                events.push((value(t), first, size, parts.to_vec()));
                Ok(())
            })
            .unwrap();
        events
    }

    /// The same, from the generic event merge on `data`.
    fn generic_events(
        data: InitialData<BigRational>,
    ) -> Vec<(BigRational, usize, usize, Vec<u32>)> {
        Trajectory::new(data)
            .impulses()
            .iter()
            .map(|i| {
                let parts = i.parts.iter().map(|c| c.size as u32).collect();
                (i.t.clone(), i.cluster.first, i.cluster.size, parts)
            })
            .collect()
    }

    /// Word columns near the top of `i64`: cluster sums beyond `i64` (the
    /// merge must take `i128` sums when `N·max|X| ≥ 2^63`, the boundary
    /// included) and event times whose `gap·D_u` leaves `i128` (reduced on
    /// `BigInt`): the history is still the generic one.
    #[test]
    fn large_word_histories_are_the_generic() {
        let big = |v: i128| BigRational::from_integer(BigInt::from(v));
        // N·M = 2 · 2^62 = 2^63: two particles in contact, one cluster.
        let xs = vec![(1i64 << 62, 1u64), ((1 << 62) + 1, 1)];
        let l = Lean::new(Some(q(1, 2)), 0, xs, vec![(0, 1), (0, 1)]).unwrap();
        assert!(lean_events(&l).is_empty());
        assert_eq!(l.x, [1 << 62, 1 << 62]);
        // Eight particles 2^58 apart, at 1/3 past the integers (D_x = 3),
        // velocities (100 s₁ + 10 s₂ + s₃)/2^62 (D_u = 2^62; s₁, s₂, s₃ = ±1
        // alternating by particle, by pair, by half): pairs meet, then pairs
        // of pairs, then the halves, whose `gap = k_L k_R (X̄_R − X̄_L) =
        // 16 · 3 · 2^60` gives `gap·D_u > 2^127`.
        // And N·M > 2^63: sums in `i128`.
        let n = 8;
        let positions: Vec<_> = (0..n).map(|i| big(i * (1 << 58)) + q(1, 3)).collect();
        let sign = |b: bool| if b { 1 } else { -1 };
        let velocities: Vec<_> = (0..n)
            .map(|i| {
                let v = 100 * sign(i % 2 == 0) + 10 * sign(i / 2 % 2 == 0) + sign(i < 4);
                BigRational::new(BigInt::from(v), BigInt::from(1u64 << 62))
            })
            .collect();
        let data = InitialData::new(q(1, 2), positions, velocities).unwrap();
        let l = lean(&data, true).unwrap();
        assert_eq!((l.dx, l.du), (3, 1 << 62));
        let m =
            l.x.iter()
                .chain(&l.u)
                .map(|v| v.unsigned_abs())
                .max()
                .unwrap();
        assert!(u128::from(m) * n as u128 > 1 << 63);
        let events = lean_events(&l);
        assert_eq!(events.len(), 7, "{events:?}");
        assert_eq!(events[6].1..events[6].2, 0..8);
        assert_eq!(events, generic_events(data));
    }

    /// `blocks_at` answers exactly where the kernel's `i128` bound
    /// `b_Y + b_K < 128` holds (`b_Y = max(bits a + bits max|X|,
    /// bits b + bits max|U|) + 1`), and then with the kernel's state.
    #[test]
    fn blocks_at_answers_within_the_i128_bound() {
        let big = |v: i128| BigRational::from_integer(BigInt::from(v));
        // X = (0, 2^61 − 1, 2^62 − 2): 62 bits; U = (1, 0, −1); b_K = 2.
        let data = InitialData::new(
            q(1, 2),
            vec![big(0), big(1 << 61), big(1 << 62)],
            vec![q(1, 1), q(0, 1), q(-1, 1)],
        )
        .unwrap();
        let l = lean(&data, true).unwrap();
        let d = IntegerData::new(&data);
        let at = |e: u32| BigRational::new(BigInt::from(1), BigInt::from(1i128 << e));
        // t = 1/2^61: a = 2^61, b_Y = 62 + 62 + 1 = 125, 125 + 2 < 128.
        let b = l.blocks_at(&at(61)).expect("within the bound");
        let mut xs = Vec::new();
        b.positions(|v| {
            xs.push(value(v));
            Ok(())
        })
        .unwrap();
        assert_eq!(xs, state_at(&d, &at(61)).unwrap().positions);
        // t = 1/2^62: a = 2^62 (63 bits), 126 + 2 = 128: declined.
        assert!(l.blocks_at(&at(62)).is_none());
    }

    /// Denominators whose product leaves `i128` while every scaled value
    /// fits `i64` (`D_x = p₁ p₂ ≈ 2^100`, `D_u = 2^30`, so `D_y = q D_x D_u`
    /// is beyond `i128`): the block means and positions are reduced on
    /// `BigInt`, and are still the kernel's.
    #[test]
    fn lean_values_beyond_i128_denominators() {
        let (p1, p2) = (1_125_899_906_842_597i64, 1_125_899_906_842_589i64);
        // 2r = 1/3; x̃ = (0, 1/p₁, 1/p₂, 1/p₂): particles 2 and 3 in contact
        // with one velocity (one block of two at t = 0).
        let xs = vec![
            (0, 1),
            (p1 + 3, 3 * p1 as u64),
            (2 * p2 + 3, 3 * p2 as u64),
            (p2 + 1, p2 as u64),
        ];
        let us = vec![(3, 1 << 30), (-5, 1 << 30), (-1, 1 << 30), (-1, 1 << 30)];
        let l = Lean::new(Some(q(1, 6)), 0, xs.clone(), us.clone()).unwrap();
        assert!(l.dx > 1 << 99);
        assert!(l.blocks_at(&q(1, 3)).is_none());
        let rat = |&(p, d): &(i64, u64)| BigRational::new(p.into(), d.into());
        let data = InitialData::new(
            q(1, 6),
            xs.iter().map(rat).collect(),
            us.iter().map(rat).collect(),
        )
        .unwrap();
        let d = IntegerData::new(&data);
        // `b = p D_x` must fit a word: t = 0 (then `D_y = D_x D_u`).
        let t = q(0, 1);
        let want = state_at(&d, &t).unwrap();
        let b = l.blocks_at(&t).expect("within the i128 bound");
        let mut rows = 0;
        b.rows(|i, x, u, lambda| {
            assert_eq!(value(x), want.positions[i], "t = {t}, i = {i}");
            assert_eq!(value(u), want.velocities[i], "t = {t}, i = {i}");
            assert_eq!(lambda.map(value), want.multipliers.get(i).cloned());
            rows += 1;
            Ok(())
        })
        .unwrap();
        assert_eq!(rows, 4);
        assert_eq!(b.clusters(), want.clusters);
        assert_eq!(b.runs.iter().map(|r| r.k).collect::<Vec<_>>(), [1, 1, 2]);
    }
}
