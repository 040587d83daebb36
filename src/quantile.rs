//! Macroscopic initial data `(ρ⁰, u⁰)` and their quantile sampling into N
//! particles (paper §2.1 "Discretisation of the macroscopic initial datum",
//! `thm:main` (i)).
//!
//! A [`MacroDatum`] is a piecewise constant density made of [`Block`]s:
//! block `b` carries the constant density `ρ_b ∈ (0, 1]` on `[from_b, to_b)`
//! and a velocity that is constant, or affine from `a` at `from_b` to `b` at
//! `to_b` when `ρ_b < 1`. `thm:main` asks for
//!
//! > `ρ⁰ ∈ P₂(ℝ)`, `ρ⁰ ≪ L¹`, `ρ⁰ ≤ 1`, `supp ρ⁰ ⋐ ℝ`,
//! > `u⁰ ∈ L²(ℝ, ρ⁰) ∩ L^∞(ℝ, ρ⁰)`, `∂ₓu⁰ = 0` in `{ρ⁰ = 1}` (`hyp:u0`),
//!
//! so the blocks must carry total mass exactly 1 and a congested block
//! (`ρ_b = 1`) must have a constant velocity.
//!
//! With the masses `m_0 = 0 < m_1 < … < m_B = 1` accumulated block by block,
//! the monotone transport map `X⁰` with `ρ⁰ = X⁰_# L¹_(0,1)` is
//!
//! ```text
//! X⁰(w) = inf{ x : F(x) ≥ w } = from_b + (w − m_{b−1}) / ρ_b   for m_{b−1} < w ≤ m_b,
//! ```
//!
//! `F` the cumulative distribution function of `ρ⁰`, and the Lagrangian
//! velocity is `U⁰ = u⁰ ∘ X⁰`. The paper samples both at the quantiles:
//! `x⁰_i = X⁰(i/N)`, `u⁰_i = U⁰(i/N)`, `i = 1, …, N`, with `2r = 1/N`.
//! Since `ρ⁰ ≤ 1`, `x⁰_{i+1} − x⁰_i ≥ 1/N`, and by `hyp:u0` two particles in
//! contact have equal velocities: the sample is admissible initial data.
//!
//! Everything here is exact ([`BigRational`]); nothing is rounded.
//!
//! Conventions: blocks are indexed from 0 in error messages
//! ([`Error::Block`], [`Error::Density`]), as `macro.blocks[k]`; at a
//! mass breakpoint `w = m_b`, [`MacroDatum::x0`] and [`MacroDatum::u0`] use
//! the block on the left (`X⁰` is left-continuous, being a generalised
//! inverse of a CDF).

use num_bigint::BigInt;
use num_integer::Integer;
use num_rational::BigRational;
use num_traits::{One, Signed, ToPrimitive, Zero};

use crate::error::Error;
use crate::initial::InitialData;
use crate::rational::render_exact;

/// Longest exact rendering [`render_short`] prints in full.
const MAX_RENDERED_CHARS: usize = 80;

/// `q` for an error message: exact (`"p/q"`) when short, otherwise a
/// decimal approximation with six decimals and the length of the exact form,
/// so that a message stays one readable line. Used for values from user
/// data, which may have thousands of digits.
pub(crate) fn render_short(q: &BigRational) -> String {
    let exact = render_exact(q);
    if exact.chars().count() <= MAX_RENDERED_CHARS {
        return exact;
    }
    let scale = BigInt::from(1_000_000u32);
    // floor(|q|·10⁶), computed exactly over the integers.
    let scaled = (q.numer().abs() * &scale) / q.denom();
    let (int_part, frac_part) = scaled.div_rem(&scale);
    let sign = if q.is_negative() { "-" } else { "" };
    format!(
        "≈ {sign}{int_part}.{frac_part:0>6} (exact value of {} characters)",
        exact.len()
    )
}

/// The initial velocity `u⁰` on one block.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum BlockVelocity {
    /// `u⁰ = c` on the whole block.
    Constant(BigRational),
    /// `u⁰` affine in `x`: `a` at the block's `from`, `b` at its `to`.
    /// Allowed only on blocks of density below 1 (`hyp:u0`), unless `a = b`.
    Affine(BigRational, BigRational),
}

impl BlockVelocity {
    /// `true` when the velocity does not vary over the block (a constant, or
    /// an affine velocity with equal end values).
    pub fn is_constant(&self) -> bool {
        match self {
            BlockVelocity::Constant(_) => true,
            BlockVelocity::Affine(a, b) => a == b,
        }
    }
}

/// One block of a macroscopic datum: density `density` on `[from, to)` and
/// velocity `velocity`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Block {
    /// Left end of the block.
    pub from: BigRational,
    /// Right end of the block (`from < to`).
    pub to: BigRational,
    /// The constant density `ρ⁰` on the block, in `(0, 1]`.
    pub density: BigRational,
    /// The velocity `u⁰` on the block.
    pub velocity: BlockVelocity,
}

impl Block {
    /// The mass `density · (to − from)` the block carries.
    pub fn mass(&self) -> BigRational {
        &self.density * (&self.to - &self.from)
    }

    /// `u⁰(x)` on this block: the constant, or the affine interpolation
    /// `a + (b − a)(x − from)/(to − from)` (exact; `x` is not clamped). On
    /// an empty block (`from = to`, refused by [`MacroDatum::new`]) an
    /// affine velocity gives `a`.
    pub fn velocity_at(&self, x: &BigRational) -> BigRational {
        match &self.velocity {
            BlockVelocity::Constant(c) => c.clone(),
            BlockVelocity::Affine(a, b) => {
                let length = &self.to - &self.from;
                if a == b || length.is_zero() {
                    return a.clone();
                }
                a + (b - a) * (x - &self.from) / length
            }
        }
    }
}

/// A validated macroscopic initial datum `(ρ⁰, u⁰)` satisfying the hypotheses
/// of `thm:main` (see the module documentation).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct MacroDatum {
    blocks: Vec<Block>,
    /// `m_0 = 0, m_1, …, m_B = 1`.
    breakpoints: Vec<BigRational>,
}

impl MacroDatum {
    /// Checks and wraps the blocks, in this order, block by block:
    ///
    /// * `from < to` (else [`Error::Block`], "empty");
    /// * `0 < density ≤ 1` (else [`Error::Density`]);
    /// * an affine velocity only where `density < 1` (or with equal end
    ///   values, which is a constant): `hyp:u0` requires `∂ₓu⁰ = 0` on the
    ///   congested set `{ρ⁰ = 1}` (else [`Error::Block`]);
    /// * block `k + 1` starts at or after the end of block `k` — touching is
    ///   allowed (else [`Error::Block`], "unsorted" when it starts before
    ///   block `k` starts, "overlaps block k" otherwise);
    ///
    /// and finally that the total mass `Σ density·(to − from)` is exactly 1
    /// (`thm:main`: `ρ⁰` is a probability measure; else [`Error::Mass`]). An
    /// empty list of blocks has mass 0 and is refused with [`Error::Mass`].
    /// Block indices in errors count from 0 (`macro.blocks[k]`).
    pub fn new(blocks: Vec<Block>) -> Result<Self, Error> {
        let one = BigRational::one();
        let mut breakpoints = Vec::with_capacity(blocks.len() + 1);
        let mut mass = BigRational::zero();
        breakpoints.push(mass.clone());
        let mut previous: Option<&Block> = None;
        for (k, block) in blocks.iter().enumerate() {
            let number = k;
            if block.from >= block.to {
                return Err(Error::Block {
                    block: number,
                    reason: format!(
                        "empty: from = {} is not below to = {}",
                        render_short(&block.from),
                        render_short(&block.to)
                    ),
                });
            }
            if !block.density.is_positive() || block.density > one {
                return Err(Error::Density {
                    block: number,
                    density: render_short(&block.density),
                });
            }
            if block.density == one && !block.velocity.is_constant() {
                return Err(Error::Block {
                    block: number,
                    reason: "an affine velocity is not allowed on a congested block (density 1): hyp:u0 requires the velocity to be constant where the density is 1".to_string(),
                });
            }
            if let Some(prev) = previous {
                if block.from < prev.to {
                    let reason = if block.from < prev.from {
                        format!(
                            "unsorted: it starts at {}, before macro.blocks[{}] (which starts at {}); list blocks from left to right",
                            render_short(&block.from),
                            k - 1,
                            render_short(&prev.from)
                        )
                    } else {
                        format!(
                            "overlaps macro.blocks[{}]: it starts at {}, before that block ends at {}",
                            k - 1,
                            render_short(&block.from),
                            render_short(&prev.to)
                        )
                    };
                    return Err(Error::Block {
                        block: number,
                        reason,
                    });
                }
            }
            mass += block.mass();
            breakpoints.push(mass.clone());
            previous = Some(block);
        }
        if mass != one {
            return Err(Error::Mass {
                mass: render_short(&mass),
            });
        }
        Ok(MacroDatum {
            blocks,
            breakpoints,
        })
    }

    /// The blocks, left to right.
    pub fn blocks(&self) -> &[Block] {
        &self.blocks
    }

    /// The cumulative masses `m_0 = 0 < m_1 < … < m_B = 1`: `m_b` is the
    /// mass of blocks `1 … b`.
    pub fn mass_breakpoints(&self) -> Vec<BigRational> {
        self.breakpoints.clone()
    }

    /// `ρ⁰(x)`: the density of the block with `from ≤ x < to`, 0 outside
    /// every block.
    pub fn density_at(&self, x: &BigRational) -> BigRational {
        self.block_at(x)
            .map(|b| b.density.clone())
            .unwrap_or_else(BigRational::zero)
    }

    /// `u⁰(x)` on the block with `from ≤ x < to`; `None` outside the support
    /// (where `u⁰` is not defined: `u⁰ ∈ L²(ℝ, ρ⁰)`).
    pub fn velocity_at(&self, x: &BigRational) -> Option<BigRational> {
        self.block_at(x).map(|b| b.velocity_at(x))
    }

    /// The cumulative distribution function `F(x) = ρ⁰((−∞, x])`, exact.
    pub fn cdf(&self, x: &BigRational) -> BigRational {
        let mut total = BigRational::zero();
        for block in &self.blocks {
            if *x <= block.from {
                break;
            }
            if *x >= block.to {
                total += block.mass();
            } else {
                total += &block.density * (x - &block.from);
                break;
            }
        }
        total
    }

    /// The block with `from ≤ x < to`, if any.
    fn block_at(&self, x: &BigRational) -> Option<&Block> {
        let k = self.blocks.partition_point(|b| b.to <= *x);
        self.blocks.get(k).filter(|b| b.from <= *x)
    }

    /// The 0-based index `b` of the block with `m_b < w ≤ m_{b+1}` (blocks
    /// numbered from 0 here), with `w` clamped into `[0, 1]`; `w ≤ 0` gives
    /// the first block, `w > 1` the last.
    fn block_of_mass(&self, w: &BigRational) -> usize {
        // breakpoints[1..] = m_1 … m_B; the first b with w ≤ m_{b+1}.
        let ends = self.breakpoints.get(1..).unwrap_or(&[]);
        let k = ends.partition_point(|m| m < w);
        k.min(self.blocks.len().saturating_sub(1))
    }

    /// `X⁰(w)` on block `b` (0-based), `w` clamped to the block's mass range.
    fn x0_in(&self, b: usize, w: &BigRational) -> BigRational {
        match (
            self.blocks.get(b),
            self.breakpoints.get(b),
            self.breakpoints.get(b + 1),
        ) {
            (Some(block), Some(lo), Some(hi)) => {
                let w = if w < lo {
                    lo
                } else if w > hi {
                    hi
                } else {
                    w
                };
                &block.from + (w - lo) / &block.density
            }
            // Unreachable for a validated datum (at least one block).
            _ => BigRational::zero(),
        }
    }

    /// The monotone transport map `X⁰(w) = inf{ x : F(x) ≥ w }` with
    /// `ρ⁰ = X⁰_# L¹_(0,1)` (paper §2.1, `thm:main`), exact: on block `b`,
    /// `m_{b−1} < w ≤ m_b`, it is `from_b + (w − m_{b−1})/ρ_b`.
    ///
    /// It is left-continuous: at a mass breakpoint `w = m_b` it is the `to`
    /// of block `b` (the block on the left), and `X⁰(1)` is the `to` of the
    /// last block. Outside `(0, 1]`, `w` is clamped: `X⁰(w) = from_1` for
    /// `w ≤ 0` (the right limit at 0) and `X⁰(w) = X⁰(1)` for `w > 1`.
    pub fn x0(&self, w: &BigRational) -> BigRational {
        self.x0_in(self.block_of_mass(w), w)
    }

    /// The Lagrangian velocity `U⁰(w) = u⁰(X⁰(w))` (`thm:main`), exact, with
    /// the same block choice as [`MacroDatum::x0`] (left-continuous at the
    /// mass breakpoints; clamped outside `(0, 1]`). An affine velocity is
    /// evaluated at `X⁰(w)`.
    pub fn u0(&self, w: &BigRational) -> BigRational {
        let b = self.block_of_mass(w);
        let x = self.x0_in(b, w);
        self.blocks
            .get(b)
            .map(|block| block.velocity_at(&x))
            .unwrap_or_else(BigRational::zero)
    }

    /// The quantile sampling of paper §2.1 / `thm:main` (i):
    /// `x⁰_i = X⁰(i/N)`, `u⁰_i = U⁰(i/N)` for `i = 1, …, N`, radius
    /// `r = 1/(2N)` (`2r = 1/N`), validated by [`InitialData::new`].
    ///
    /// Since `ρ⁰ ≤ 1` the positions never overlap (`x⁰_{i+1} − x⁰_i ≥ 1/N`,
    /// with equality only when `ρ⁰ = 1` on `(x⁰_i, x⁰_{i+1})`). Two sampled
    /// particles in contact therefore straddle a congested stretch, and
    /// `hyp:u0` gives them equal velocities — except across the left end of
    /// a congested block touched by the block before it, where `u⁰` may
    /// jump: when that jump is downwards (the left block is faster) and the
    /// contact is sampled (always, if both blocks are congested; when
    /// `m_b·N` is an integer otherwise), the particles approach each other
    /// and [`InitialData::new`] reports [`Error::Approaching`].
    /// `n = 0` gives [`Error::NoParticles`].
    ///
    /// Cost: `O(N + B)` exact operations; memory: N positions and N
    /// velocities (an allocation failure is reported as
    /// [`Error::Unsupported`], not a panic).
    pub fn sample(&self, n: usize) -> Result<InitialData<BigRational>, Error> {
        let (positions, velocities) = self.quantiles(n)?;
        let big_n = BigRational::from_integer(n.into());
        let radius = (big_n * BigRational::from_integer(2.into())).recip();
        InitialData::new(radius, positions, velocities)
    }

    /// `U⁰(w+)`, the right limit of the Lagrangian velocity at the mass
    /// coordinate `w` (at a mass breakpoint `m_b`, the value of the block
    /// on the right; [`MacroDatum::u0`] is the left-continuous one). For
    /// `w` at or beyond 1, the last block's value at its right end.
    pub fn u0_right(&self, w: &BigRational) -> BigRational {
        let ends = self.breakpoints.get(1..).unwrap_or(&[]);
        let b = ends
            .partition_point(|m| m <= w)
            .min(self.blocks.len().saturating_sub(1));
        let x = self.x0_in(b, w);
        self.blocks
            .get(b)
            .map(|block| block.velocity_at(&x))
            .unwrap_or_else(BigRational::zero)
    }

    /// The quantile sample itself, `(x⁰_i, u⁰_i) = (X⁰(i/N), U⁰(i/N))` for
    /// `i = 1 … N`, without the admissibility check of [`MacroDatum::sample`]
    /// (the claims of §2.1 are about exactly these numbers, admissible or
    /// not). Errors as [`MacroDatum::sample`] for `n = 0` and allocation.
    pub fn quantiles(&self, n: usize) -> Result<(Vec<BigRational>, Vec<BigRational>), Error> {
        if n == 0 {
            return Err(Error::NoParticles);
        }
        let big_n = BigRational::from_integer(n.into());
        // On block b (0-based), X⁰(i/N) = from_b + (i/N − m_b)/ρ_b and U⁰(i/N)
        // are affine in i: evaluate them as (p + i·r)/d with one reduction
        // per value, rather than a chain of rational operations.
        let mut positions = Vec::new();
        let mut velocities = Vec::new();
        if positions.try_reserve_exact(n).is_err() || velocities.try_reserve_exact(n).is_err() {
            return Err(Error::Unsupported {
                message: format!("cannot allocate the sample of {n} particles"),
            });
        }
        let mut i = 1usize;
        for (b, block) in self.blocks.iter().enumerate() {
            let (Some(lo), Some(hi)) = (self.breakpoints.get(b), self.breakpoints.get(b + 1))
            else {
                break;
            };
            // The particles of this block: i/N ≤ m_{b+1}, i.e. i ≤ ⌊N·m_{b+1}⌋
            // (everything left for the last block, m_B = 1).
            let end = if b + 1 == self.blocks.len() {
                n
            } else {
                (&big_n * hi)
                    .floor()
                    .to_integer()
                    .to_usize()
                    .unwrap_or(n)
                    .min(n)
            };
            if i > end {
                continue;
            }
            // x_i = c + i·s with s = 1/(N ρ_b), c = from_b − m_b/ρ_b.
            let s = (&big_n * &block.density).recip();
            let c = &block.from - lo / &block.density;
            let x = Affine::new(&c, &s);
            let u = match &block.velocity {
                BlockVelocity::Affine(a, v) if a != v => {
                    // u = a + k (x − from_b), k = (v − a)/(to_b − from_b).
                    let k = (v - a) / (&block.to - &block.from);
                    Some(Affine::new(&(a + &k * (&c - &block.from)), &(&k * &s)))
                }
                _ => None,
            };
            let constant = block.velocity_at(&block.from);
            while i <= end {
                let k = BigInt::from(i);
                positions.push(x.at(&k));
                velocities.push(match &u {
                    Some(u) => u.at(&k),
                    None => constant.clone(),
                });
                i += 1;
            }
        }
        Ok((positions, velocities))
    }
}

/// `i ↦ c + i·s` over a common denominator: `(p + i·r)/d`.
struct Affine {
    p: BigInt,
    r: BigInt,
    d: BigInt,
}

impl Affine {
    fn new(c: &BigRational, s: &BigRational) -> Self {
        let d = c.denom().lcm(s.denom());
        let p = c.numer() * (&d / c.denom());
        let r = s.numer() * (&d / s.denom());
        Affine { p, r, d }
    }

    fn at(&self, i: &BigInt) -> BigRational {
        BigRational::new(&self.p + &self.r * i, self.d.clone())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::rational::ratio as q;

    fn block(from: BigRational, to: BigRational, density: BigRational, u: BigRational) -> Block {
        Block {
            from,
            to,
            density,
            velocity: BlockVelocity::Constant(u),
        }
    }

    #[test]
    fn appendix_c_sampling() {
        let d = MacroDatum::new(vec![
            block(q(0, 1), q(1, 2), q(1, 1), q(1, 1)),
            block(q(3, 4), q(5, 4), q(1, 1), q(-1, 1)),
        ])
        .unwrap();
        assert_eq!(d.mass_breakpoints(), vec![q(0, 1), q(1, 2), q(1, 1)]);
        assert_eq!(d.x0(&q(1, 2)), q(1, 2));
        assert_eq!(d.u0(&q(1, 2)), q(1, 1));
        assert_eq!(d.x0(&q(9, 16)), q(13, 16));
        assert_eq!(d.u0(&q(9, 16)), q(-1, 1));
        let data = d.sample(16).unwrap();
        assert_eq!(data.n(), 16);
        assert_eq!(*data.radius(), q(1, 32));
        for (k, x) in data.positions().iter().enumerate() {
            let i = k as i64 + 1;
            let expected = if i <= 8 { q(i, 16) } else { q(i, 16) + q(1, 4) };
            assert_eq!(*x, expected, "x_{i}");
        }
    }

    #[test]
    fn long_values_are_shortened_in_messages() {
        assert_eq!(render_short(&q(-7, 4)), "-7/4");
        let third = BigRational::new(BigInt::from(1), BigInt::from(3).pow(200u32));
        let big = BigRational::from_integer(BigInt::from(2)) - third;
        let shown = render_short(&big);
        assert!(shown.starts_with("≈ 1.999999 (exact value of "), "{shown}");
        assert!(render_short(&-big).starts_with("≈ -1.999999"));
        let e = MacroDatum::new(vec![block(
            q(0, 1),
            q(1, 1),
            q(1, 1) - BigRational::new(BigInt::from(1), BigInt::from(10).pow(100u32)),
            q(0, 1),
        )])
        .unwrap_err();
        assert!(e.to_string().contains("total mass ≈ 0.999999"), "{e}");
    }

    #[test]
    fn clamps_outside_unit_interval() {
        let d = MacroDatum::new(vec![block(q(2, 1), q(3, 1), q(1, 1), q(5, 1))]).unwrap();
        assert_eq!(d.x0(&q(0, 1)), q(2, 1));
        assert_eq!(d.x0(&q(-7, 1)), q(2, 1));
        assert_eq!(d.x0(&q(9, 1)), q(3, 1));
        assert_eq!(d.u0(&q(9, 1)), q(5, 1));
    }
}
