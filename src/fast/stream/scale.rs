//! The scaling of [`crate::fast::scaling`] (`df:translat-x`: `x̃⁰_i = X_i / D_x`,
//! `u⁰_i = U_i / D_u`) on values that arrive one at a time, kept straight
//! as `i64`: the column file is read twice (the denominators, then the
//! values), and nothing wider than the final column is ever held.
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

/// One column being scaled: its common denominator known (first pass), its
/// values arriving in order (second pass).
pub(crate) struct ColumnScaler {
    den: Denominators,
    /// `2r D` per particle (positions), 0 (velocities).
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

    /// The scaler of the second pass, for `capacity` values; `two_r`, the
    /// pair `(p, d)` of `2r`, for the positions (its denominator taken into
    /// the lcm), `None` for the velocities.
    pub(crate) fn scaler(
        mut self,
        two_r: Option<(i128, u128)>,
        capacity: usize,
    ) -> Option<ColumnScaler> {
        if let Some((_, rd)) = two_r {
            self.0.add(rd)?;
        }
        let mut den = self.0;
        den.finish();
        let step = match two_r {
            Some((rn, rd)) => rn.checked_mul(i128::try_from(den.factor(rd)).ok()?)?,
            None => 0,
        };
        let g = den.lcm;
        Some(ColumnScaler {
            den,
            step,
            offset: 0,
            g,
            test: Divisibility::new(g),
            div: ExactDiv::new(g),
            range: Range::EMPTY,
            values: Vec::with_capacity(capacity),
            stretches: vec![(0, g)],
        })
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
            den: self.den.lcm / g,
            range,
        })
    }
}
