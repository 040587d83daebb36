//! The cost model of the [`Solver`](crate::solver::Solver): what the choice
//! of an engine rests on (`N`, the size of the common denominators the
//! integer engines scale to, `df:translat-x`, and of the largest single
//! value), and the line `--explain` prints.

use num_rational::BigRational;

use crate::fast::engine::ExactEngine;
use crate::initial::InitialData;

/// Beyond this many bits the running lcm of [`Cost::of`] stops: the common
/// denominator is then known to be at least this large (2^16 bits, 1,024
/// words: past it the common-denominator engines are out of the question).
pub const LCM_BITS_LIMIT: u64 = 1 << 16;

/// The size of a common denominator: exact, or a lower bound when the
/// running lcm stopped at [`LCM_BITS_LIMIT`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Bits {
    /// The common denominator has exactly this many bits.
    Exact(u64),
    /// The common denominator has at least this many bits.
    AtLeast(u64),
}

impl Bits {
    /// The bits known (exact, or the lower bound).
    pub fn bits(self) -> u64 {
        match self {
            Bits::Exact(b) | Bits::AtLeast(b) => b,
        }
    }
}

impl std::fmt::Display for Bits {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Bits::Exact(b) => write!(f, "{b} bits"),
            Bits::AtLeast(b) => write!(f, "more than {b} bits"),
        }
    }
}

/// What the choice of an engine rests on: `N`, the size of the common
/// denominators the integer engines scale to (`df:translat-x`), of the
/// largest single denominator and numerator, and the estimated word
/// operations of each kind of engine.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Cost {
    /// The number of particles.
    pub n: usize,
    /// The common denominator of the translated positions or of the
    /// velocities (the larger), radius included.
    pub common_denominator: Bits,
    /// Bits of the largest single denominator of the data.
    pub largest_denominator_bits: u64,
    /// Bits of the largest numerator of the data.
    pub largest_numerator_bits: u64,
    /// Word operations of the common-denominator engines (kernel, adaptive,
    /// merge): `N · w²`, `w` the words of a scaled value (common
    /// denominator plus numerator), each answer reduced by a gcd on them.
    pub common: u64,
    /// Word operations of the generic engines on local denominators:
    /// `N · w²` on the largest single value, times [`GENERIC_OVERHEAD`].
    pub local: u64,
}

/// The generic `BigRational` engines reduce after every operation: a
/// handful of gcds per particle where the integer kernels run one. Measured
/// on the hostile scene at `t = 100` (0.9 s generic, 3.5 s kernel with
/// 450-word common denominators) and on word-sized data (the kernel tens of
/// times faster), 32 puts the switch between the two.
pub const GENERIC_OVERHEAD: u64 = 32;

/// Past this many words of a scaled value the common-denominator engines
/// leave their fixed widths (`i128`, 256 bits) for `BigInt`.
const FIXED_WIDTH_WORDS: u64 = 4;

impl Cost {
    /// The cost model of `data`: a running lcm of the denominators (with a
    /// remainder by each small denominator, [`crate::gcd`]), stopped once
    /// past [`LCM_BITS_LIMIT`].
    pub fn of(data: &InitialData<BigRational>) -> Cost {
        let radius = data.radius().denom().magnitude();
        let running = |values: &[BigRational]| -> Bits {
            let denoms = values.iter().map(|q| q.denom().magnitude());
            match crate::gcd::running_lcm(radius, denoms, LCM_BITS_LIMIT) {
                crate::gcd::RunningLcm::Exact(lcm) => Bits::Exact(lcm.bits()),
                crate::gcd::RunningLcm::Past(bits) => Bits::AtLeast(bits),
            }
        };
        let x = running(data.positions());
        let u = running(data.velocities());
        let largest_denominator_bits = largest_denominator_bits(data);
        // Stopped early, the lcm is at least the bits reached and at least
        // every single denominator.
        let common_denominator = match (x, u) {
            (Bits::AtLeast(b), _) | (_, Bits::AtLeast(b)) => {
                Bits::AtLeast(b.max(largest_denominator_bits))
            }
            (Bits::Exact(a), Bits::Exact(b)) => Bits::Exact(a.max(b)),
        };
        let largest_numerator_bits = std::iter::once(data.radius())
            .chain(data.positions())
            .chain(data.velocities())
            .map(|q| q.numer().bits())
            .max()
            .unwrap_or(0);
        let n = data.n() as u64;
        let square = |bits: u64| {
            let w = bits.div_ceil(64).max(1);
            n.saturating_mul(w.saturating_mul(w))
        };
        Cost {
            n: data.n(),
            common_denominator,
            largest_denominator_bits,
            largest_numerator_bits,
            common: square(common_denominator.bits() + largest_numerator_bits),
            local: square(largest_denominator_bits + largest_numerator_bits)
                .saturating_mul(GENERIC_OVERHEAD),
        }
    }

    /// Whether the common-denominator engines are the cheaper: their values
    /// fit fixed widths, or their estimate is below the generic one.
    pub fn common_is_cheaper(&self) -> bool {
        (self.common_denominator.bits() + self.largest_numerator_bits).div_ceil(64)
            <= FIXED_WIDTH_WORDS
            || self.common <= self.local
    }

    /// One line for `--explain`: the engine chosen, `N`, the common
    /// denominator and each candidate's estimate.
    pub fn explain(&self, chosen: &dyn ExactEngine) -> String {
        format!(
            "engine: {} (N = {}, common denominator {}, largest single denominator {} bits, largest numerator {} bits; estimated word operations: common-denominator integer engines ~{:.2e}, generic BigRational on local denominators ~{:.2e})",
            chosen.name(),
            self.n,
            self.common_denominator,
            self.largest_denominator_bits,
            self.largest_numerator_bits,
            self.common as f64,
            self.local as f64,
        )
    }
}

/// The bits of the largest denominator of the data (radius, positions,
/// velocities).
pub(crate) fn largest_denominator_bits(data: &InitialData<BigRational>) -> u64 {
    std::iter::once(data.radius())
        .chain(data.positions())
        .chain(data.velocities())
        .map(|q| q.denom().bits())
        .max()
        .unwrap_or(0)
}
