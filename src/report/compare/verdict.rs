//! The verdict of a comparison: one word on a ladder from best to worst.
//!
//! | verdict    | meaning |
//! |------------|---------|
//! | `exact`    | every figure is `0`: the answer is sticky's, and breaks no constraint |
//! | `rounding` | exact up to the rounding tolerance: every error and every constraint break within its [`Tolerances`] bound, the contact clusters right, no `prop:Oleinik` violation |
//! | `inexact`  | no constraint broken beyond its bound, but some error beyond it |
//! | `invalid`  | a constraint of the model broken beyond its bound: an overlap (`df:KN`), `λ < 0` or complementarity (`eq:dyn-micro`), `prop:Oleinik` |
//!
//! With a rounding tolerance of `0` (the default) every bound is `0`, and
//! the ladder is `exact` / `inexact` / `invalid` — but for one answer: a
//! correctly rounded one ([`Representation::NearestDoubles`]: every value
//! given is the nearest double of the exact one, the contact clusters, when
//! given, the exact ones) is `rounding` whatever the tolerances, since its
//! overlaps, negative `λ` or missed contacts are the rounding's alone.

use std::fmt;
use std::str::FromStr;

use num_rational::BigRational;
use num_traits::Signed;

use crate::columns::f64_exact;
use crate::reference::measure::Comparison;
use crate::scalar::Scalar;

/// The verdict, ordered from best to worst (`Exact < Rounding < Inexact <
/// Invalid`): a report's verdict is its worst time's.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Verdict {
    /// Every figure is `0`.
    Exact,
    /// Every figure within its rounding bound ([`Tolerances`]), not all `0`.
    Rounding,
    /// No constraint broken beyond its bound; some error beyond it.
    Inexact,
    /// A constraint of the model broken beyond its bound.
    Invalid,
}

impl Verdict {
    /// Every verdict, best first.
    pub const ALL: [Verdict; 4] = [
        Verdict::Exact,
        Verdict::Rounding,
        Verdict::Inexact,
        Verdict::Invalid,
    ];

    /// The word: `exact`, `rounding`, `inexact` or `invalid`.
    pub fn name(self) -> &'static str {
        match self {
            Verdict::Exact => "exact",
            Verdict::Rounding => "rounding",
            Verdict::Inexact => "inexact",
            Verdict::Invalid => "invalid",
        }
    }

    /// What the word means, in a few words.
    pub fn meaning(self) -> &'static str {
        match self {
            Verdict::Exact => "equal to sticky's answer, breaks no constraint",
            Verdict::Rounding => "equal to sticky's answer up to the rounding tolerance",
            Verdict::Inexact => "admissible up to the tolerance, not equal to sticky's answer",
            Verdict::Invalid => "breaks a constraint of the model",
        }
    }
}

impl fmt::Display for Verdict {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A word that is not a verdict.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct UnknownVerdict(pub String);

impl fmt::Display for UnknownVerdict {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{:?} is not a verdict (expected exact, rounding, inexact or invalid)",
            self.0
        )
    }
}

impl std::error::Error for UnknownVerdict {}

impl FromStr for Verdict {
    type Err = UnknownVerdict;
    fn from_str(s: &str) -> Result<Verdict, UnknownVerdict> {
        Verdict::ALL
            .into_iter()
            .find(|v| v.name() == s)
            .ok_or_else(|| UnknownVerdict(s.to_string()))
    }
}

/// The absolute bounds of the `rounding` verdict at one time, from the
/// rounding tolerance `TOL ≥ 0` (relative): lengths (position errors,
/// overlap depths, the gap of a pair where `λ ≠ 0`) within `TOL · 2r`,
/// velocity errors within `TOL · max_i |u⁰_i|` (every exact velocity is a
/// cluster's mean of initial velocities, so that is their scale), multiplier
/// errors and negative `λ` within `TOL · max_j λ_j(t)` (the exact
/// multipliers at that time).
#[derive(Debug, Clone, PartialEq)]
pub struct Tolerances {
    /// `TOL · 2r`.
    pub length: BigRational,
    /// `TOL · max_i |u⁰_i|`.
    pub velocity: BigRational,
    /// `TOL · max_j λ_j(t)`.
    pub multiplier: BigRational,
}

/// What the candidate's values are, against the exact ones.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Representation {
    /// Every value given is the nearest double (ties to even) of the exact
    /// value, and the contact clusters, when given, are the exact ones.
    NearestDoubles,
    /// Anything else.
    Other,
}

impl Representation {
    /// `NearestDoubles` when every candidate column of `columns` (pairs
    /// `(given, exact)`, of equal lengths) holds the nearest doubles of its
    /// exact column and `contacts_right`; `Other` otherwise.
    pub fn of(columns: &[(&[BigRational], &[BigRational])], contacts_right: bool) -> Self {
        let nearest = |(given, exact): &(&[BigRational], &[BigRational])| {
            debug_assert_eq!(given.len(), exact.len());
            given
                .iter()
                .zip(exact.iter())
                .all(|(g, e)| f64_exact(e.to_f64_lossy()).is_some_and(|d| &d == g))
        };
        if contacts_right && columns.iter().all(nearest) {
            Representation::NearestDoubles
        } else {
            Representation::Other
        }
    }
}

/// One time's verdict. `gaps[j] = x_{j+1} − x_j − 2r` of the candidate and
/// `multipliers` its `λ` (if given), for the complementarity bound: a pair
/// with `λ_j (x_{j+1} − x_j − 2r) ≠ 0` is within it when its gap is within
/// `tol.length` of contact or its `λ_j` within `tol.multiplier` of `0`.
/// A correctly rounded answer (`representation`) is `rounding` at worst.
pub fn judge(
    c: &Comparison,
    gaps: &[BigRational],
    multipliers: Option<&[BigRational]>,
    tol: &Tolerances,
    representation: Representation,
) -> Verdict {
    if c.is_exact() {
        return Verdict::Exact;
    }
    if representation == Representation::NearestDoubles {
        return Verdict::Rounding;
    }
    let deep_overlap = c.overlaps.iter().any(|o| o.depth > tol.length);
    let negative = c
        .negative_multipliers
        .iter()
        .any(|p| -&p.value > tol.multiplier);
    let complementarity = c.complementarity.iter().any(|p| {
        let gap_far = gaps.get(p.pair).is_none_or(|g| g.abs() > tol.length);
        let lambda_far = multipliers
            .and_then(|l| l.get(p.pair))
            .is_none_or(|l| l.abs() > tol.multiplier);
        gap_far && lambda_far
    });
    let oleinik = c.oleinik.as_ref().is_some_and(|o| !o.is_empty());
    if deep_overlap || negative || complementarity || oleinik {
        return Verdict::Invalid;
    }
    let within = c.position_max.value <= tol.length
        && c.velocity_max
            .as_ref()
            .is_none_or(|m| m.value <= tol.velocity)
        && c.multiplier_max
            .as_ref()
            .is_none_or(|m| m.value <= tol.multiplier)
        && c.missed_contacts == 0
        && c.spurious_contacts == 0;
    if within {
        Verdict::Rounding
    } else {
        Verdict::Inexact
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rational::ratio as q;
    use crate::reference::measure::{MaxError, Overlap};

    fn clean() -> Comparison {
        Comparison {
            t: q(1, 1),
            position_max: MaxError {
                value: q(0, 1),
                index: 0,
            },
            position_l2_squared: q(0, 1),
            velocity_max: None,
            velocity_l2_squared: None,
            multiplier_max: None,
            overlaps: vec![],
            missed_clusters: vec![],
            spurious_clusters: vec![],
            missed_contacts: 0,
            spurious_contacts: 0,
            negative_multipliers: vec![],
            complementarity: vec![],
            oleinik: None,
        }
    }

    fn tol(length: BigRational) -> Tolerances {
        Tolerances {
            length,
            velocity: q(0, 1),
            multiplier: q(0, 1),
        }
    }

    /// A position 1/1000 off that overlaps its neighbour by `depth`.
    fn overlapping(depth: BigRational) -> Comparison {
        let mut c = clean();
        c.position_max.value = depth.clone();
        c.overlaps.push(Overlap { pair: 0, depth });
        c
    }

    #[test]
    fn the_ladder() {
        let none = tol(q(0, 1));
        let some = tol(q(1, 100));
        assert_eq!(
            judge(&clean(), &[], None, &none, Representation::Other),
            Verdict::Exact
        );
        // Within the bound: rounding; beyond it: invalid; no bound: invalid.
        assert_eq!(
            judge(
                &overlapping(q(1, 1000)),
                &[],
                None,
                &some,
                Representation::Other
            ),
            Verdict::Rounding
        );
        assert_eq!(
            judge(
                &overlapping(q(1, 10)),
                &[],
                None,
                &some,
                Representation::Other
            ),
            Verdict::Invalid
        );
        assert_eq!(
            judge(
                &overlapping(q(1, 1000)),
                &[],
                None,
                &none,
                Representation::Other
            ),
            Verdict::Invalid
        );
        // A small overlap with a large error elsewhere: inexact.
        let mut c = overlapping(q(1, 1000));
        c.position_max.value = q(1, 2);
        assert_eq!(
            judge(&c, &[], None, &some, Representation::Other),
            Verdict::Inexact
        );
        // A wrong contact cluster is never rounding.
        let mut c = clean();
        c.missed_contacts = 1;
        assert_eq!(
            judge(&c, &[], None, &some, Representation::Other),
            Verdict::Inexact
        );
        assert!(Verdict::Exact < Verdict::Rounding);
        assert!(Verdict::Rounding < Verdict::Inexact);
        assert!(Verdict::Inexact < Verdict::Invalid);
        assert_eq!("rounding".parse::<Verdict>(), Ok(Verdict::Rounding));
        assert!("round".parse::<Verdict>().is_err());
    }
}
