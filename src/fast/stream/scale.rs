//! The scaling of [`crate::fast::scaling`] (`df:translat-x`: `x̃⁰_i = X_i / D_x`,
//! `u⁰_i = U_i / D_u`) on values that arrive one at a time, kept straight
//! as `i64`: the column file is read twice (the denominators, then the
//! values), and nothing wider than the final column is ever held. Each
//! pass may take the file in stretches on several threads: the lcms of the
//! stretches merge ([`Lcm::merge`]), and the scaled stretches join in
//! order ([`Joined`]) under the gcd of their `g`s.
//!
//! The least common denominator of the translated positions is `D / g`,
//! with `D` the lcm of the denominators and `g` the gcd of `D` and every
//! `X'_i = x⁰_i D − i (2r) D`; `g` is known only at the end. Each `X'_i` is
//! stored divided by the `g` of the moment, which only shrinks (at most
//! 128 times: each change at least halves it): a value stored under `g_k`
//! is multiplied by `g_k / g` at the end. `|X'_i / g_k| ≤ |X'_i / g|`, so a
//! column whose final values fit `i64` never overflows on the way, and one
//! whose values do not is refused (the general path then reads the file).

use crate::fast::int::{gcd, MulSmall};
use crate::fast::scaling::{div_rem, divided_range, Denominators, Divisibility, ExactDiv, Range};

/// The common denominator of one column and the step of its translation,
/// known after the first pass: what every [`ColumnScaler`] of the second
/// pass starts from.
#[derive(Clone)]
pub(crate) struct ColumnScale {
    den: Denominators,
    /// `2r D` per particle (positions), 0 (velocities).
    step: i128,
}

/// One stretch of a column being scaled (the second pass): its values
/// arriving in order from its first row on.
pub(crate) struct ColumnScaler {
    den: Denominators,
    step: i128,
    offset: i128,
    g: u128,
    test: Divisibility,
    div: ExactDiv,
    range: Range,
    values: Vec<i64>,
    /// `(first index, g)` of each stretch of values stored under one `g`.
    stretches: Vec<(usize, u128)>,
}

/// The stretches of one column put back in order ([`Joined::take`]), to be
/// brought under the column's final `g` ([`Joined::finish`]).
pub(crate) struct Joined {
    lcm: u128,
    g: u128,
    range: Range,
    values: Vec<i64>,
    stretches: Vec<(usize, u128)>,
}

/// A scaled column: `values[i] / den`, and the range of the values.
pub(crate) struct ScaledColumn {
    pub(crate) values: Vec<i64>,
    pub(crate) den: u128,
    pub(crate) range: Range,
}

/// The denominators of one column (the first pass).
pub(crate) struct Lcm(Denominators);

impl Lcm {
    /// No denominator yet (the lcm is 1).
    pub(crate) fn new() -> Lcm {
        Lcm(Denominators::new())
    }

    /// Takes `d > 0` in; `None` when the lcm overflows 128 bits.
    #[inline]
    pub(crate) fn add(&mut self, d: u64) -> Option<()> {
        self.0.add(u128::from(d))
    }

    /// Takes in the denominators `other` took (the lcm of both); `None`
    /// when it overflows 128 bits. The lcm of a set does not depend on the
    /// order its members came in, nor on how they were grouped.
    pub(crate) fn merge(&mut self, other: &Lcm) -> Option<()> {
        self.0.add(other.0.lcm)
    }

    /// The column's scale for the second pass; `two_r`, the pair `(p, d)`
    /// of `2r`, for the positions (its denominator taken into the lcm),
    /// `None` for the velocities.
    pub(crate) fn scale(mut self, two_r: Option<(i128, u128)>) -> Option<ColumnScale> {
        if let Some((_, rd)) = two_r {
            self.0.add(rd)?;
        }
        let mut den = self.0;
        den.finish();
        let step = match two_r {
            Some((rn, rd)) => rn.checked_mul(i128::try_from(den.factor(rd)).ok()?)?,
            None => 0,
        };
        Some(ColumnScale { den, step })
    }

    /// The scaler of a whole column read in one stretch, for `capacity`
    /// values ([`Lcm::scale`], then [`ColumnScale::part`] from row 0).
    #[cfg(test)]
    pub(crate) fn scaler(
        self,
        two_r: Option<(i128, u128)>,
        capacity: usize,
    ) -> Option<ColumnScaler> {
        self.scale(two_r)?.part(0, capacity)
    }
}

impl ColumnScale {
    /// The scaler of the stretch of the column that starts at row `first`,
    /// for `capacity` values; `None` when `first · 2r D` overflows.
    pub(crate) fn part(&self, first: usize, capacity: usize) -> Option<ColumnScaler> {
        let g = self.den.lcm;
        Some(ColumnScaler {
            den: self.den.clone(),
            step: self.step,
            offset: self.step.checked_mul(i128::try_from(first).ok()?)?,
            g,
            test: Divisibility::new(g),
            div: ExactDiv::new(g),
            range: Range::EMPTY,
            values: Vec::with_capacity(capacity),
            stretches: vec![(0, g)],
        })
    }

    /// An empty column of `capacity` values, its stretches to come in
    /// order.
    pub(crate) fn joined(&self, capacity: usize) -> Joined {
        Joined {
            lcm: self.den.lcm,
            g: self.den.lcm,
            range: Range::EMPTY,
            values: Vec::with_capacity(capacity),
            stretches: Vec::new(),
        }
    }
}

impl ColumnScaler {
    /// Takes the next value `p / d` (a denominator the first pass saw);
    /// `None` on overflow.
    #[inline]
    pub(crate) fn push(&mut self, p: i64, d: u64) -> Option<()> {
        let f = i128::try_from(self.den.factor(u128::from(d))).ok()?;
        let v = i128::from(p).mul_small(f)?.checked_sub(self.offset)?;
        self.offset = self.offset.checked_add(self.step)?;
        if self.g != 1 && !self.test.divides(v.unsigned_abs()) {
            self.g = gcd(self.g, div_rem(v.unsigned_abs(), self.g).1);
            self.test = Divisibility::new(self.g);
            self.div = ExactDiv::new(self.g);
            self.stretches.push((self.values.len(), self.g));
        }
        self.range.take(v);
        self.values.push(i64::try_from(self.div.apply(v)).ok()?);
        Some(())
    }

    /// The column over its least common denominator, when it was read in
    /// one stretch; `None` when a value does not fit `i64`.
    #[cfg(test)]
    pub(crate) fn finish(self) -> Option<ScaledColumn> {
        let mut whole = Joined {
            lcm: self.den.lcm,
            g: self.den.lcm,
            range: Range::EMPTY,
            values: Vec::new(),
            stretches: Vec::new(),
        };
        whole.take(self);
        whole.finish()
    }
}

impl Joined {
    /// Appends the next stretch of the column (the one that starts where
    /// the values so far end).
    pub(crate) fn take(&mut self, part: ColumnScaler) {
        debug_assert_eq!(part.den.lcm, self.lcm);
        let at = self.values.len();
        // g only shrinks: the column's g divides every stretch's.
        self.g = gcd(self.g, part.g);
        if part.range.lo <= part.range.hi {
            self.range.take(part.range.lo);
            self.range.take(part.range.hi);
        }
        self.stretches
            .extend(part.stretches.iter().map(|&(i, g)| (at + i, g)));
        self.values.extend_from_slice(&part.values);
    }

    /// The column over its least common denominator; `None` when a value
    /// does not fit `i64`.
    pub(crate) fn finish(mut self) -> Option<ScaledColumn> {
        let g = self.g;
        let range = divided_range(self.range, g);
        i64::try_from(range.lo).ok()?;
        i64::try_from(range.hi).ok()?;
        let ends = self.stretches.iter().skip(1).map(|s| s.0);
        let ends: Vec<usize> = ends.chain([self.values.len()]).collect();
        for (&(start, g_k), end) in self.stretches.iter().zip(ends) {
            // g divides g_k: each value is multiplied by g_k / g.
            let m = i64::try_from(g_k / g).ok()?;
            debug_assert_eq!(g_k % g, 0);
            if m != 1 {
                for v in &mut self.values[start..end] {
                    *v = v.checked_mul(m)?;
                }
            }
        }
        Some(ScaledColumn {
            values: self.values,
            den: self.lcm / g,
            range,
        })
    }
}
