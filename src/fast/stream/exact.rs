//! One exact value of the streaming path's state, in lowest terms: on
//! machine words, or a `BigRational` when its reduction does not fit them.

use std::io::{self, Write};

use num_bigint::BigInt;
use num_rational::BigRational;

use crate::fast::int::gcd;

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
        // A power-of-two denominator (every dyadic scene's): the gcd is the
        // common power of two.
        let g = if b.is_power_of_two() && a != 0 {
            1 << a.trailing_zeros().min(b.trailing_zeros())
        } else {
            gcd(a, b)
        };
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
    pub(super) fn big(num: BigInt, den: BigInt) -> Exact {
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
        const EXACT: u128 = 1 << 53;
        match self {
            // `unsigned_abs`: `i128::MIN` has no `abs`.
            Exact::Small(n, d) if n.unsigned_abs() <= EXACT && d.unsigned_abs() <= EXACT => {
                *n as i64 as f64 / *d as i64 as f64
            }
            _ => {
                let (n, d) = self.numer_denom();
                crate::scalar::Scalar::to_f64_lossy(&BigRational::new(n, d))
            }
        }
    }
    pub(super) fn numer_denom(&self) -> (BigInt, BigInt) {
        match self {
            Exact::Small(n, d) => (BigInt::from(*n), BigInt::from(*d)),
            Exact::Big(q) => (q.numer().clone(), q.denom().clone()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Exact;

    /// Small values of either size convert to their nearest doubles; the
    /// least `i128` (no `abs`) goes the rational way, without a panic.
    #[test]
    fn nearest_doubles_of_small_values() {
        assert_eq!(Exact::Small(-3, 4).to_f64_lossy(), -0.75);
        assert_eq!(Exact::Small(1, 3).to_f64_lossy(), 1.0 / 3.0);
        assert_eq!(Exact::Small(i128::MIN, 1).to_f64_lossy(), -(2f64.powi(127)));
        let big = (1i128 << 60) + 1;
        assert_eq!(Exact::Small(big, 1).to_f64_lossy(), 2f64.powi(60));
    }
}
