//! A machine-word rational with checked arithmetic: the cheap exact
//! oracle of the `kernels` fuzz target (`claims::fuzz::kernels`).
//!
//! [`CheckedRatio`] is `Ratio<i64>` whose every operation is checked: an
//! overflow, or a division by zero, never wraps and never panics — it
//! answers `0` and marks the computation as overflowed in a per-thread
//! flag. [`exactly`] runs a computation with the flag cleared and keeps its
//! answer only when the flag stayed clear: then every operation was the
//! exact rational operation, so the answer is the one the same generic code
//! gives over `BigRational`. Otherwise the caller computes again over
//! `BigRational`. The answer of an overflowed run is never used, so the
//! `0`s it computed with only have to keep the generic code from panicking
//! (no division by zero ever reaches `Ratio`).

use std::cell::Cell;
use std::cmp::Ordering;
use std::fmt;
use std::ops::{Add, Div, Mul, Neg, Sub};

use num_bigint::BigInt;
use num_rational::{BigRational, Ratio};
use num_traits::{CheckedAdd, CheckedDiv, CheckedMul, CheckedSub, ToPrimitive, Zero};

use crate::scalar::Scalar;

thread_local! {
    /// Set by the first checked operation of [`CheckedRatio`] that would
    /// overflow (or divide by zero) since [`exactly`] cleared it.
    static OVERFLOWED: Cell<bool> = const { Cell::new(false) };
}

/// The largest magnitude of a numerator or denominator taken in by
/// [`Scalar::from_big_rational`]: below `i64::MAX`, so that no value ever
/// holds `i64::MIN`, whose negation overflows.
const WORD_BOUND: i64 = i64::MAX >> 1;

/// An exact rational on machine words with checked operations (see the
/// module's documentation): exact inside [`exactly`], or flagged.
#[derive(Clone, PartialEq, Eq, PartialOrd, Ord)]
pub struct CheckedRatio(Ratio<i64>);

impl CheckedRatio {
    /// The same value as a `BigRational`. A `Ratio` is kept in lowest terms
    /// with a positive denominator, as a `BigRational` is: no gcd needed.
    pub fn to_big(&self) -> BigRational {
        BigRational::new_raw(BigInt::from(*self.0.numer()), BigInt::from(*self.0.denom()))
    }
}

impl fmt::Debug for CheckedRatio {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.0)
    }
}

/// Runs `compute` on [`CheckedRatio`]s: `Some` of its answer when none of
/// its operations overflowed (the answer is then exact), `None` otherwise.
pub fn exactly<R>(compute: impl FnOnce() -> R) -> Option<R> {
    let outer = OVERFLOWED.with(|f| f.replace(false));
    let answer = compute();
    let overflowed = OVERFLOWED.with(|f| f.replace(outer));
    (!overflowed).then_some(answer)
}

/// Marks the running computation as overflowed; `0` stands for the value.
fn overflow() -> CheckedRatio {
    OVERFLOWED.with(|f| f.set(true));
    CheckedRatio(Ratio::from_integer(0))
}

/// The checked result, or [`overflow`].
fn checked(r: Option<Ratio<i64>>) -> CheckedRatio {
    match r {
        // Keep every word below the bound: a later negation or widening
        // cannot reach i64::MIN.
        Some(r) if r.numer().unsigned_abs() <= WORD_BOUND as u64 && *r.denom() <= WORD_BOUND => {
            CheckedRatio(r)
        }
        _ => overflow(),
    }
}

macro_rules! checked_op {
    ($trait:ident, $method:ident, $checked:ident) => {
        impl $trait for CheckedRatio {
            type Output = CheckedRatio;
            fn $method(self, rhs: CheckedRatio) -> CheckedRatio {
                checked(self.0.$checked(&rhs.0))
            }
        }
        impl<'a> $trait<&'a CheckedRatio> for CheckedRatio {
            type Output = CheckedRatio;
            fn $method(self, rhs: &'a CheckedRatio) -> CheckedRatio {
                checked(self.0.$checked(&rhs.0))
            }
        }
    };
}

checked_op!(Add, add, checked_add);
checked_op!(Sub, sub, checked_sub);
checked_op!(Mul, mul, checked_mul);
checked_op!(Div, div, checked_div);

impl Neg for CheckedRatio {
    type Output = CheckedRatio;
    fn neg(self) -> CheckedRatio {
        // No word is i64::MIN (`checked`), so the negation is exact.
        CheckedRatio(-self.0)
    }
}

impl Scalar for CheckedRatio {
    const EXACT: bool = true;
    fn zero() -> Self {
        CheckedRatio(Ratio::from_integer(0))
    }
    fn one() -> Self {
        CheckedRatio(Ratio::from_integer(1))
    }
    fn from_i64(n: i64) -> Self {
        checked(Some(Ratio::from_integer(n)))
    }
    fn is_zero(&self) -> bool {
        Zero::is_zero(&self.0)
    }
    fn total_cmp(&self, other: &Self) -> Ordering {
        // num-rational's order does not overflow (it compares by integer
        // division and remainders).
        self.0.cmp(&other.0)
    }
    fn to_f64_lossy(&self) -> f64 {
        self.0.to_f64().unwrap_or(f64::NAN)
    }
    fn from_big_rational(q: &BigRational) -> Option<Self> {
        let n = q.numer().to_i64()?;
        let d = q.denom().to_i64()?;
        (n.unsigned_abs() <= WORD_BOUND as u64 && d <= WORD_BOUND)
            .then(|| CheckedRatio(Ratio::new_raw(n, d)))
    }
    fn to_big_rational(&self) -> Option<BigRational> {
        Some(self.to_big())
    }
    fn render(&self) -> String {
        self.0.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rational::ratio as q;

    fn c(n: i64, d: i64) -> CheckedRatio {
        CheckedRatio(Ratio::new(n, d))
    }

    #[test]
    fn exact_operations_stay_exact() {
        let got = exactly(|| (c(1, 3) + c(1, 6)) * c(4, 1) / c(-2, 1) - c(1, 2));
        assert_eq!(got, Some(c(-3, 2)));
        assert_eq!(c(-3, 2).to_big_rational(), Some(q(-3, 2)));
    }

    #[test]
    fn overflow_and_division_by_zero_are_flagged_not_wrapped() {
        let big = c(WORD_BOUND, 1);
        assert_eq!(exactly(|| big.clone() * c(2, 1)), None);
        assert_eq!(exactly(|| big.clone() + big.clone()), None);
        assert_eq!(exactly(|| c(1, WORD_BOUND) * c(1, 3)), None);
        assert_eq!(exactly(|| c(1, 2) / CheckedRatio::zero()), None);
        // The flag is cleared by the next run.
        assert_eq!(
            exactly(|| big.clone() - c(1, 1)),
            Some(c(WORD_BOUND - 1, 1))
        );
    }

    #[test]
    fn from_big_rational_refuses_wide_words() {
        let wide = BigRational::from_integer(BigInt::from(i64::MAX));
        assert_eq!(CheckedRatio::from_big_rational(&wide), None);
        let back = CheckedRatio::from_big_rational(&q(-7, 4));
        assert_eq!(back, Some(c(-7, 4)));
    }
}
