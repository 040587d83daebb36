//! The hypotheses of `thm:main` on a macroscopic datum, and those of part
//! (i) on its quantile sampling, each checked separately so that a report
//! says *which* hypothesis fails.
//!
//! `thm:main` asks of `(ρ⁰, u⁰)`:
//!
//! > `ρ⁰ ∈ P₂(ℝ)`, `ρ⁰ ≪ L¹`, `ρ⁰ ≤ 1`, `supp ρ⁰ ⋐ ℝ`,
//! > `u⁰ ∈ L²(ℝ,ρ⁰) ∩ L^∞(ℝ,ρ⁰)`, `∂ₓu⁰ = 0` in `{ρ⁰ = 1}` (`hyp:u0`),
//!
//! and part (i) says the sampling `x⁰_i = X⁰(i/N)`, `u⁰_i = U⁰(i/N)`
//! (paper §2.1) satisfies
//!
//! > `x⁰_{i+1} − x⁰_i ≥ 2r = 1/N`, `u⁰_{i+1} = u⁰_i` whenever
//! > `x⁰_{i+1} − x⁰_i = 2r`, and `X⁰_N → X⁰`, `U⁰_N → U⁰` in `L²(0,1)`.
//!
//! For blocks of constant density, `hyp:u0` fails exactly when a congested
//! block carries a non-constant velocity, or when two congested blocks
//! touch with different velocities (then `{ρ⁰ = 1}` contains the contact
//! point in its interior and `∂ₓu⁰` has a Dirac mass there). The second
//! case passes [`MacroDatum::new`] when the right block is faster; its
//! sampling is then in the velocity cone `def:velcone` but violates the
//! equality that part (i) asserts.

use num_rational::BigRational;
use num_traits::Signed;

use super::continuum::Continuum;
use super::converge::{u_l2_squared, x_l2_squared};
use crate::error::Error;
use crate::quantile::{Block, MacroDatum};
use crate::scalar::Scalar;

/// One hypothesis of `thm:main`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Hypothesis {
    /// Blocks are non-empty intervals, sorted and pairwise disjoint (so
    /// that the density is the given piecewise constant function).
    WellFormed,
    /// `ρ⁰ ≪ L¹` and `0 < ρ⁰ ≤ 1` on every block.
    DensityAtMostOne,
    /// `ρ⁰` is a probability measure: total mass exactly 1.
    Probability,
    /// `supp ρ⁰ ⋐ ℝ` and `ρ⁰ ∈ P₂(ℝ)` (finitely many bounded blocks).
    CompactSupport,
    /// `u⁰ ∈ L²(ℝ,ρ⁰) ∩ L^∞(ℝ,ρ⁰)` (finite constant or affine velocities).
    BoundedVelocity,
    /// `hyp:u0`: `∂ₓu⁰ = 0` in `{ρ⁰ = 1}`.
    HypU0,
    /// (i): `x⁰_{i+1} − x⁰_i ≥ 2r = 1/N`.
    NonOverlapping,
    /// (i): `u⁰_{i+1} = u⁰_i` whenever `x⁰_{i+1} − x⁰_i = 2r`.
    ContactVelocities,
}

impl Hypothesis {
    /// The statement, with the paper's label.
    pub fn statement(self) -> &'static str {
        match self {
            Hypothesis::WellFormed => "blocks are non-empty, sorted and disjoint",
            Hypothesis::DensityAtMostOne => "thm:main: ρ⁰ ≪ L¹, ρ⁰ ≤ 1",
            Hypothesis::Probability => "thm:main: ρ⁰ is a probability measure (mass 1)",
            Hypothesis::CompactSupport => "thm:main: supp ρ⁰ ⋐ ℝ, ρ⁰ ∈ P₂(ℝ)",
            Hypothesis::BoundedVelocity => "thm:main: u⁰ ∈ L²(ℝ,ρ⁰) ∩ L^∞(ℝ,ρ⁰)",
            Hypothesis::HypU0 => "hyp:u0: ∂ₓu⁰ = 0 in {ρ⁰ = 1}",
            Hypothesis::NonOverlapping => "thm:main (i): x⁰_{i+1} − x⁰_i ≥ 2r = 1/N",
            Hypothesis::ContactVelocities => {
                "thm:main (i): u⁰_{i+1} = u⁰_i whenever x⁰_{i+1} − x⁰_i = 2r"
            }
        }
    }
}

/// The verdict on one hypothesis.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Check {
    /// The hypothesis.
    pub hypothesis: Hypothesis,
    /// Whether it holds.
    pub holds: bool,
    /// Why (the first offending block or pair when it fails).
    pub detail: String,
}

/// The verdicts on a list of hypotheses.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct HypothesisReport {
    /// One check per hypothesis.
    pub checks: Vec<Check>,
}

impl HypothesisReport {
    /// `true` when every hypothesis holds.
    pub fn holds(&self) -> bool {
        self.checks.iter().all(|c| c.holds)
    }
    /// The hypotheses that fail.
    pub fn failures(&self) -> Vec<&Check> {
        self.checks.iter().filter(|c| !c.holds).collect()
    }
}

fn check(hypothesis: Hypothesis, failure: Option<String>) -> Check {
    Check {
        hypothesis,
        holds: failure.is_none(),
        detail: failure.unwrap_or_else(|| "holds".to_string()),
    }
}

/// Checks every hypothesis of `thm:main` on raw blocks (which need not
/// pass [`MacroDatum::new`]); blocks are named `blocks[k]`, indexed from 0.
pub fn check_blocks(blocks: &[Block]) -> HypothesisReport {
    let one = BigRational::from_integer(1.into());
    let mut well = None;
    for (k, b) in blocks.iter().enumerate() {
        if b.from >= b.to {
            well = Some(format!(
                "blocks[{}] is empty: from = {} ≥ to = {}",
                k,
                b.from.render(),
                b.to.render()
            ));
            break;
        }
        if k > 0 && b.from < blocks[k - 1].to {
            well = Some(format!(
                "blocks[{}] starts at {} before blocks[{}] ends at {} (the density would add up on the overlap)",
                k,
                b.from.render(),
                k - 1,
                blocks[k - 1].to.render()
            ));
            break;
        }
    }
    if blocks.is_empty() {
        well = Some("no blocks".to_string());
    }
    let density = blocks
        .iter()
        .enumerate()
        .find(|(_, b)| !b.density.is_positive() || b.density > one)
        .map(|(k, b)| format!("blocks[{}] has density {} ∉ (0, 1]", k, b.density.render()));
    let mass = blocks
        .iter()
        .filter(|b| b.from < b.to)
        .fold(BigRational::zero(), |m, b| m + b.mass());
    let probability = (mass != one).then(|| format!("total mass {} ≠ 1", mass.render()));
    // Finitely many blocks with rational ends: always compact, always P₂,
    // always bounded velocities.
    let mut hyp = None;
    for (k, b) in blocks.iter().enumerate() {
        if b.density == one && !b.velocity.is_constant() {
            hyp = Some(format!(
                "blocks[{}] is congested (density 1) with a non-constant velocity",
                k
            ));
            break;
        }
        if k > 0 {
            let a = &blocks[k - 1];
            if a.density == one && b.density == one && a.to == b.from {
                let (va, vb) = (a.velocity_at(&a.to), b.velocity_at(&b.from));
                if va != vb {
                    hyp = Some(format!(
                        "congested blocks[{}] and blocks[{}] touch at x = {} with velocities {} and {}: ∂ₓu⁰ has a Dirac mass inside {{ρ⁰ = 1}}",
                        k - 1,
                        k,
                        b.from.render(),
                        va.render(),
                        vb.render()
                    ));
                    break;
                }
            }
        }
    }
    HypothesisReport {
        checks: vec![
            check(Hypothesis::WellFormed, well),
            check(Hypothesis::DensityAtMostOne, density),
            check(Hypothesis::Probability, probability),
            check(Hypothesis::CompactSupport, None),
            check(Hypothesis::BoundedVelocity, None),
            check(Hypothesis::HypU0, hyp),
        ],
    }
}

/// [`check_blocks`] on a validated datum (only `hyp:u0` can fail).
pub fn check_datum(datum: &MacroDatum) -> HypothesisReport {
    check_blocks(datum.blocks())
}

/// What part (i) of `thm:main` says of one sampling.
#[derive(Debug, Clone, PartialEq)]
pub struct SamplingReport {
    /// N.
    pub n: usize,
    /// [`Hypothesis::NonOverlapping`] and [`Hypothesis::ContactVelocities`].
    pub checks: HypothesisReport,
    /// `‖X⁰_N − X⁰‖²_{L²(0,1)}`, exact.
    pub x0_l2_squared: BigRational,
    /// `‖U⁰_N − U⁰‖²_{L²(0,1)}`, exact.
    pub u0_l2_squared: BigRational,
}

/// Samples `x⁰_i = X⁰(i/N)`, `u⁰_i = U⁰(i/N)` exactly (without the
/// validation of [`MacroDatum::sample`], so that a failing hypothesis is
/// reported rather than refused) and checks part (i) of `thm:main`.
pub fn check_sampling(datum: &MacroDatum, n: usize) -> Result<SamplingReport, Error> {
    if n == 0 {
        return Err(Error::NoParticles);
    }
    if n > crate::scene::MAX_MACRO_PARTICLES {
        return Err(Error::Unsupported {
            message: format!(
                "N = {n} exceeds the limit of {} particles",
                crate::scene::MAX_MACRO_PARTICLES
            ),
        });
    }
    let nn = BigRational::from_integer(n.into());
    let two_r = nn.recip();
    let ws: Vec<BigRational> = (1..=n)
        .map(|i| BigRational::from_integer(i.into()) / &nn)
        .collect();
    let x: Vec<BigRational> = ws.iter().map(|w| datum.x0(w)).collect();
    let u: Vec<BigRational> = ws.iter().map(|w| datum.u0(w)).collect();
    let mut overlap = None;
    let mut contact = None;
    for i in 0..n.saturating_sub(1) {
        let gap = &x[i + 1] - &x[i];
        if gap < two_r && overlap.is_none() {
            overlap = Some(format!(
                "particles {} and {} (indices from 0): gap {} < 2r = {}",
                i,
                i + 1,
                gap.render(),
                two_r.render()
            ));
        }
        if gap == two_r && u[i] != u[i + 1] && contact.is_none() {
            contact = Some(format!(
                "particles {} and {} (indices from 0) touch with velocities {} and {}",
                i,
                i + 1,
                u[i].render(),
                u[i + 1].render()
            ));
        }
    }
    let profile = Continuum::new(datum)
        .profile(&BigRational::zero())?
        .to_rational()
        .ok_or_else(|| Error::Unsupported {
            message: "the initial profile is not rational (it always is: please report)"
                .to_string(),
        })?;
    Ok(SamplingReport {
        n,
        checks: HypothesisReport {
            checks: vec![
                check(Hypothesis::NonOverlapping, overlap),
                check(Hypothesis::ContactVelocities, contact),
            ],
        },
        x0_l2_squared: x_l2_squared(&x, &profile),
        u0_l2_squared: u_l2_squared(&u, &profile),
    })
}
