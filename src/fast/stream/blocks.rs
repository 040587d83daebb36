//! The PAVA blocks of a [`Lean`] scene at one time and the state they
//! give, value by value in lowest terms (`eq:proj-u-micro`,
//! `eq:dyn-micro`), whole or in [`Piece`]s that can be computed apart.

use std::io;

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::Zero;

use crate::cluster::Cluster;
use crate::fast::kernel::{i128_clusters, Run};

use super::reduce::{Reducer, ScenePrimes};
use super::{Exact, Lean};

/// A stretch of whole blocks of a [`LeanBlocks`] ([`LeanBlocks::pieces`]):
/// its values can be computed apart from the others' and put back in order.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Piece {
    /// The index of its first particle.
    pub(super) first: usize,
    /// Its blocks, as indices into the blocks of the time.
    pub(super) runs: std::ops::Range<usize>,
}

/// The PAVA blocks of a [`Lean`] scene at one time, and the state they give,
/// value by value.
#[derive(Debug)]
pub struct LeanBlocks<'a> {
    pub(super) d: &'a Lean,
    pub(super) runs: Vec<Run<i128>>,
    pub(super) t: BigRational,
    pub(super) dy: Option<i128>,
    /// The odd primes of the denominators of the state ([`super::reduce`]).
    pub(super) primes: ScenePrimes,
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
    fn mean(red: &Reducer, s: i128, k: u64, d: Option<i128>, d_big: impl Fn() -> BigInt) -> Exact {
        match d.and_then(|d| d.checked_mul(i128::from(k))) {
            Some(den) => red.ratio(s, den),
            None => Exact::big(BigInt::from(s), d_big() * BigInt::from(k)),
        }
    }

    fn mean_y(&self, r: &Run<i128>, red: &Reducer) -> Exact {
        let (q, dx, du) = (self.t.denom(), self.d.dx, self.d.du);
        Self::mean(red, r.sy, r.k, self.dy, || {
            q * BigInt::from(dx) * BigInt::from(du)
        })
    }

    fn mean_u(&self, r: &Run<i128>, red: &Reducer) -> Exact {
        let du = self.d.du;
        Self::mean(red, r.su, r.k, Some(du), || BigInt::from(du))
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

    pub(super) fn positions_from(
        &self,
        runs: &[Run<i128>],
        mut i: usize,
        mut f: impl FnMut(&Exact) -> io::Result<()>,
    ) -> io::Result<()> {
        let (rn, rd) = self.d.two_r;
        for r in runs {
            let red = self.primes.block(r.k);
            let y = self.mean_y(r, &red);
            // x_i = (y_n r_d + r_n y_d i) / (y_d r_d): the numerator steps by
            // `r_n y_d` from one particle to the next (one addition, no
            // product per value); the `BigInt` form when it leaves `i128`.
            let (mut num, step, den) = match &y {
                Exact::Small(yn, yd) => {
                    let step = rn.checked_mul(*yd);
                    let num = (|| {
                        yn.checked_mul(rd)?
                            .checked_add(step?.checked_mul(i128::try_from(i).ok()?)?)
                    })();
                    (num, step, yd.checked_mul(rd))
                }
                Exact::Big(_) => (None, None, None),
            };
            for _ in 0..r.k {
                let v = match (num, den) {
                    (Some(num), Some(den)) => red.ratio(num, den),
                    _ => {
                        let (yn, yd) = y.numer_denom();
                        let (rn, rd) = (BigInt::from(rn), BigInt::from(rd));
                        Exact::big(&yn * &rd + rn * &yd * BigInt::from(i), yd * rd)
                    }
                };
                f(&v)?;
                num = num.zip(step).and_then(|(num, step)| num.checked_add(step));
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

    pub(super) fn velocities_from(
        &self,
        runs: &[Run<i128>],
        mut f: impl FnMut(&Exact) -> io::Result<()>,
    ) -> io::Result<()> {
        for r in runs {
            let v = self.mean_u(r, &self.primes.block(r.k));
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

    pub(super) fn multipliers_from(
        &self,
        runs: &[Run<i128>],
        mut first: usize,
        n: usize,
        mut f: impl FnMut(&Exact) -> io::Result<()>,
    ) -> io::Result<()> {
        let big_n = i128::try_from(n).unwrap_or(i128::MAX);
        for r in runs {
            let k = i128::from(r.k);
            let red = self.primes.block(r.k);
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
                    (Some(num), Some(den)) => red.ratio(num, den),
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
                primes: self.primes.clone(),
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

    /// The contact clusters of `x(t)` (`df:Omega-micro`): runs of blocks
    /// with equal `x̃` (cross-multiplied sums, exact by the kernel's bound).
    pub fn clusters(&self) -> Vec<Cluster> {
        i128_clusters(&self.runs)
    }
}
