//! Lowest terms without a gcd per value: every denominator the state of a
//! [`super::LeanBlocks`] reduces is a product of the block size `k` and of
//! the scene's fixed numbers (`q`, `D_x`, `D_u`, the denominator of `2r`,
//! `N`), so its prime factors are known once those are factored. A value is
//! then put in lowest terms by removing the common powers of those primes:
//! a shift for 2, and for an odd prime `p` a divisibility test and an exact
//! division by one multiplication each (by `p`'s inverse modulo `2^64`),
//! where a binary gcd takes tens of steps.
//!
//! The primes are found by trial division, once per scene and once per
//! block of more than one particle; when a number has a prime factor the
//! trial division does not reach (or too many of them), or a value does not
//! fit 64-bit words, [`Exact::ratio`] (a gcd) reduces it instead: the same
//! lowest terms.

use super::Exact;

/// Trial divisors of the scene's fixed numbers stop below this bound: a
/// cofactor left over with no divisor below it is prime when it is below the
/// bound's square, unknown otherwise.
const TRIAL_BOUND: u64 = 1 << 16;

/// At most this many distinct odd primes (a 64-bit block size has at most
/// 15; the scene's numbers at most this many together).
const MAX_PRIMES: usize = 16;

/// An odd prime `p` with its inverse modulo `2^64`: `n` is a multiple of `p`
/// if and only if `n · inv mod 2^64 ≤ ⌊(2^64 − 1)/p⌋`, and then `n / p` is
/// that product (multiplication by `inv` is a bijection of the words that
/// maps the multiples of `p`, `p·m`, onto `m ≤ ⌊(2^64 − 1)/p⌋`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct OddPrime {
    p: u64,
    inv: u64,
    max: u64,
}

impl OddPrime {
    /// `p` odd, `p ≥ 3`.
    fn new(p: u64) -> OddPrime {
        debug_assert!(p % 2 == 1 && p >= 3);
        // Newton's iteration doubles the correct low bits: p·p ≡ 1 mod 8
        // (3 bits), then 6, 12, 24, 48, 96.
        let mut inv = p;
        for _ in 0..5 {
            inv = inv.wrapping_mul(2u64.wrapping_sub(p.wrapping_mul(inv)));
        }
        debug_assert_eq!(p.wrapping_mul(inv), 1);
        OddPrime {
            p,
            inv,
            max: u64::MAX / p,
        }
    }

    /// `n / p` when `p` divides `n`.
    #[inline]
    fn quotient(self, n: u64) -> Option<u64> {
        let q = n.wrapping_mul(self.inv);
        (q <= self.max).then_some(q)
    }
}

/// A set of distinct odd primes, at most [`MAX_PRIMES`].
#[derive(Debug, Clone, Copy)]
struct PrimeSet {
    primes: [OddPrime; MAX_PRIMES],
    len: usize,
}

impl PrimeSet {
    const EMPTY: PrimeSet = PrimeSet {
        primes: [OddPrime {
            p: 3,
            inv: 0,
            max: 0,
        }; MAX_PRIMES],
        len: 0,
    };

    fn as_slice(&self) -> &[OddPrime] {
        &self.primes[..self.len]
    }

    /// Adds `p` (odd, prime) unless it is already there; `None` when the set
    /// is full.
    fn add(&mut self, p: u64) -> Option<()> {
        if self.as_slice().iter().any(|q| q.p == p) {
            return Some(());
        }
        *self.primes.get_mut(self.len)? = OddPrime::new(p);
        self.len += 1;
        Some(())
    }

    /// Adds the odd prime factors of `m` found by trial division by the odd
    /// numbers `d` with `d² ≤ m` and `d < bound`; `None` when a cofactor
    /// with no such divisor is not proved prime (`≥ bound²`) or does not fit
    /// a word, or the set is full.
    fn add_factors(&mut self, m: u128, bound: u64) -> Option<()> {
        let mut m = m >> m.trailing_zeros().min(127);
        let mut d = 3u64;
        while m > 1 && u128::from(d) * u128::from(d) <= m {
            if d >= bound {
                return None;
            }
            if m % u128::from(d) == 0 {
                self.add(d)?;
                while m % u128::from(d) == 0 {
                    m /= u128::from(d);
                }
            }
            d += 2;
        }
        if m > 1 {
            // No divisor up to √m: m is prime.
            self.add(u64::try_from(m).ok()?)?;
        }
        Some(())
    }
}

/// The odd primes of the scene's fixed numbers (`None`: not all known),
/// boxed: the blocks of a time carry them, and are moved around whole.
#[derive(Debug, Clone)]
pub(crate) struct ScenePrimes(Option<Box<PrimeSet>>);

impl ScenePrimes {
    /// The odd prime factors of every number of `numbers` (each nonzero).
    pub(crate) fn of(numbers: &[u128]) -> ScenePrimes {
        let mut set = PrimeSet::EMPTY;
        let known = numbers
            .iter()
            .try_for_each(|&m| set.add_factors(m, TRIAL_BOUND));
        ScenePrimes(known.map(|()| Box::new(set)))
    }

    /// The reducer of a block of `k` particles: every denominator whose
    /// prime factors are those of `k` and of the scene's numbers.
    pub(crate) fn block(&self, k: u64) -> Reducer {
        let set = self.0.as_deref().copied().and_then(|mut set| {
            if k > 1 {
                // k < 2^64: a cofactor with no divisor below 2^32 is prime.
                set.add_factors(u128::from(k), 1 << 32)?;
            }
            Some(set)
        });
        Reducer(set)
    }
}

/// Puts the values of one block in lowest terms ([`ScenePrimes::block`]).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Reducer(Option<PrimeSet>);

impl Reducer {
    /// `num / den` (`den > 0`) in lowest terms, for a denominator whose odd
    /// prime factors are all in the set: the common powers of 2 and of each
    /// of them removed. [`Exact::ratio`] when the set is not known or the
    /// terms do not fit 64-bit words.
    #[inline]
    pub(crate) fn ratio(&self, num: i128, den: i128) -> Exact {
        let (Some(set), Ok(a), Ok(b)) = (
            &self.0,
            u64::try_from(num.unsigned_abs()),
            u64::try_from(den),
        ) else {
            return Exact::ratio(num, den);
        };
        if a == 0 {
            return Exact::Small(0, 1);
        }
        let z = a.trailing_zeros().min(b.trailing_zeros());
        let (mut a, mut b) = (a >> z, b >> z);
        for &p in set.as_slice() {
            while let Some(qb) = p.quotient(b) {
                let Some(qa) = p.quotient(a) else { break };
                (a, b) = (qa, qb);
            }
        }
        debug_assert_eq!(
            crate::fast::int::gcd(a.into(), b.into()),
            1,
            "a prime of {den} missing from the set"
        );
        let a = i128::from(a);
        Exact::Small(if num < 0 { -a } else { a }, i128::from(b))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::SplitMix64;

    /// The inverse test and quotient agree with `%` and `/` on every odd
    /// `p` below 200 and random words.
    #[test]
    fn divisibility_by_the_inverse() {
        let mut rng = SplitMix64::new(11);
        for p in (3..200u64).step_by(2) {
            let o = OddPrime::new(p);
            for _ in 0..200 {
                let r = rng.next_u64();
                for n in [r, r - r % p, p, 0, u64::MAX - u64::MAX % p] {
                    let want = (n % p == 0).then_some(n / p);
                    assert_eq!(o.quotient(n), want, "{n} / {p}");
                }
            }
        }
    }

    /// On denominators built from the scene's numbers and `k`, the reduced
    /// value is the gcd's, numerators of every sign and size.
    #[test]
    fn same_lowest_terms_as_the_gcd() {
        let mut rng = SplitMix64::new(5);
        let scenes: [&[u128]; 4] = [
            &[1, 1000, 1000, 500, 1_000_000],
            &[3, 15_000, 3000, 1500, 999_999],
            &[1, 1 << 10, 1 << 10, 512, 1 << 20],
            &[7, 65_521 * 13, 9, 49, 1],
        ];
        for numbers in scenes {
            let primes = ScenePrimes::of(numbers);
            assert!(primes.0.is_some(), "{numbers:?}");
            for k in [1u64, 2, 3, 9, 12, 97, 360, 65_521, 1 << 20, 999_983] {
                let red = primes.block(k);
                let mut den = u128::from(k);
                for &m in numbers {
                    let next = den * m;
                    if next >= 1 << 62 {
                        break;
                    }
                    den = next;
                }
                for _ in 0..300 {
                    let r = rng.next_u64();
                    // Numerators sharing some of den's factors.
                    let num = i128::from(r >> (r % 64)) * (den as i128 / (1 + (r % 7) as i128))
                        % (1 << 63);
                    let num = if r & 1 == 1 { -num } else { num };
                    let den = den as i128;
                    assert_eq!(red.ratio(num, den), Exact::ratio(num, den), "{num}/{den}");
                }
            }
        }
    }

    /// A number with a prime factor beyond the trial bound leaves the set
    /// unknown (the gcd then reduces), and a large prime within it is found.
    #[test]
    fn unknown_factors_fall_back() {
        let big_prime = (1u128 << 61) - 1;
        assert!(ScenePrimes::of(&[10, big_prime * big_prime]).0.is_none());
        let p = 65_537u128 * 65_539; // both prime, beyond the bound
        assert!(ScenePrimes::of(&[p]).0.is_none());
        let set = ScenePrimes::of(&[3 * 65_537]).0.map(|s| s.len);
        assert_eq!(set, Some(2));
        let red = ScenePrimes::of(&[big_prime * big_prime]).block(3);
        assert_eq!(red.ratio(6, 9), Exact::Small(2, 3));
    }
}
