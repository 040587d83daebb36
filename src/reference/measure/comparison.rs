//! Another solver's answer at one time against the exact state
//! (`sticky compare`): max and `L²` errors, overlaps, wrong contacts and
//! clusters, the sign and complementarity of its `λ` (`eq:dyn-micro`), and
//! `prop:Oleinik` — every figure exact.

use std::collections::HashMap;
use std::fmt;

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{Signed, Zero};

use super::{exceeds, oleinik_violations};
use crate::reduced::{difference, product, quotient};

/// Another solver's answer at one time, already read exactly (see
/// `report::solution` for the file formats): the input of [`compare`].
#[derive(Debug, Clone, Copy)]
pub struct Candidate<'a> {
    /// Positions `x_1 … x_N`.
    pub positions: &'a [BigRational],
    /// Velocities `u_1 … u_N` (compared with the right derivative), if given.
    pub velocities: Option<&'a [BigRational]>,
    /// `λ_1 … λ_{N−1}` of `eq:dyn-micro`, if given.
    pub multipliers: Option<&'a [BigRational]>,
    /// The solver's own contact set (`contacts[j]` for the pair `(j, j+1)`,
    /// `N − 1` entries), if it reports one; otherwise [`compare`] takes the
    /// pairs with `x_{j+1} − x_j ≤ 2r + tol`.
    pub contacts: Option<&'a [bool]>,
}

/// The largest `|a_i − b_i|` and the first index where it is reached.
#[derive(Debug, Clone, PartialEq)]
pub struct MaxError {
    /// `max_i |a_i − b_i|` (exact).
    pub value: BigRational,
    /// The first index (0-based) reaching it.
    pub index: usize,
}

/// One overlapping pair: `x_{j+1} − x_j < 2r` (`df:KN` violated).
#[derive(Debug, Clone, PartialEq)]
pub struct Overlap {
    /// The pair `(pair, pair + 1)`, 0-based.
    pub pair: usize,
    /// `2r − (x_{j+1} − x_j) > 0`.
    pub depth: BigRational,
}

/// A value attached to one pair `(pair, pair + 1)` (0-based).
#[derive(Debug, Clone, PartialEq)]
pub struct PairValue {
    /// The pair, 0-based.
    pub pair: usize,
    /// The value.
    pub value: BigRational,
}

/// Everything [`compare`] finds, exact. `L²` errors are the discrete
/// `L²(0,1)` norm of the piecewise-constant interpolation (section 3):
/// `‖e‖² = (1/N) Σ_i e_i²`, kept squared so that it stays rational (a
/// constant error `δ` on every particle has `‖e‖ = δ`).
#[derive(Debug, Clone, PartialEq)]
pub struct Comparison {
    /// The time.
    pub t: BigRational,
    /// `max_i |x_i − x_i(t)|`.
    pub position_max: MaxError,
    /// `(1/N) Σ_i (x_i − x_i(t))²`.
    pub position_l2_squared: BigRational,
    /// `max_i |u_i − u_i(t)|` (right derivative), when velocities are given.
    pub velocity_max: Option<MaxError>,
    /// `(1/N) Σ_i (u_i − u_i(t))²`, when velocities are given.
    pub velocity_l2_squared: Option<BigRational>,
    /// `max_i |λ_i − λ_i(t)|`, when multipliers are given and `N ≥ 2`.
    pub multiplier_max: Option<MaxError>,
    /// Every overlapping pair of the candidate's positions, left to right.
    pub overlaps: Vec<Overlap>,
    /// Exact contact clusters of size ≥ 2 that the candidate does not have.
    pub missed_clusters: Vec<crate::cluster::Cluster>,
    /// Candidate contact clusters of size ≥ 2 that the exact solution does
    /// not have.
    pub spurious_clusters: Vec<crate::cluster::Cluster>,
    /// Pairs in contact in the exact solution, not in the candidate.
    pub missed_contacts: usize,
    /// Pairs in contact in the candidate, not in the exact solution.
    pub spurious_contacts: usize,
    /// Pairs with `λ_j < 0` (`eq:dyn-micro` wants `λ ≥ 0`), with `λ_j`.
    pub negative_multipliers: Vec<PairValue>,
    /// Pairs with `λ_j (x_{j+1} − x_j − 2r) ≠ 0` (complementarity of
    /// `eq:dyn-micro`), with that product.
    pub complementarity: Vec<PairValue>,
    /// `prop:Oleinik` violations of the candidate ([`oleinik_violations`]);
    /// `None` without velocities or at `t = 0`.
    pub oleinik: Option<Vec<usize>>,
}

impl Comparison {
    /// `true` when the candidate is the exact solution in every field it gave
    /// and breaks no constraint.
    pub fn is_exact(&self) -> bool {
        Zero::is_zero(&self.position_max.value)
            && self
                .velocity_max
                .as_ref()
                .is_none_or(|m| Zero::is_zero(&m.value))
            && self
                .multiplier_max
                .as_ref()
                .is_none_or(|m| Zero::is_zero(&m.value))
            && self.missed_contacts == 0
            && self.spurious_contacts == 0
            && !self.violates_model()
    }

    /// `true` when the candidate breaks a constraint of the model whatever
    /// the exact solution: an overlap (`df:KN`), `λ < 0` or complementarity
    /// (`eq:dyn-micro`), or `prop:Oleinik`.
    pub fn violates_model(&self) -> bool {
        !self.overlaps.is_empty()
            || !self.negative_multipliers.is_empty()
            || !self.complementarity.is_empty()
            || self.oleinik.as_ref().is_some_and(|o| !o.is_empty())
    }
}

/// Why [`compare`] cannot compare.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum CompareError {
    /// A field has the wrong length.
    Length {
        /// `positions`, `velocities`, `multipliers` or `contacts`.
        what: &'static str,
        /// The length wanted.
        expected: usize,
        /// The length given.
        found: usize,
    },
    /// The exact solution is not defined at that time (negative `t`).
    Exact {
        /// The exact engine's message.
        message: String,
    },
}

impl fmt::Display for CompareError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CompareError::Length {
                what,
                expected,
                found,
            } => write!(f, "{what}: {found} values, the scene needs {expected}"),
            CompareError::Exact { message } => f.write_str(message),
        }
    }
}

impl std::error::Error for CompareError {}

fn max_error(a: &[BigRational], b: &[BigRational]) -> MaxError {
    let mut best = Largest::default();
    for (i, (p, q)) in a.iter().zip(b).enumerate() {
        best.offer(i, difference(p, q));
    }
    best.into_max()
}

/// The running `max_i |d_i|` and its first index.
#[derive(Debug, Default)]
struct Largest {
    /// `d_index` itself (either sign): `|·|` is taken once, at the end.
    value: BigRational,
    index: usize,
}

impl Largest {
    /// Offers `d_i`: kept when `|d_i|` exceeds the largest so far.
    fn offer(&mut self, i: usize, d: BigRational) {
        // |d| > |v| ⟺ |n_d| m_v > |n_v| m_d (denominators positive).
        let (n, m) = (d.numer().magnitude(), d.denom().magnitude());
        let (nv, mv) = (
            self.value.numer().magnitude(),
            self.value.denom().magnitude(),
        );
        if n * mv > nv * m {
            *self = Largest { value: d, index: i };
        }
    }

    fn into_max(self) -> MaxError {
        MaxError {
            value: self.value.abs(),
            index: self.index,
        }
    }
}

/// [`max_error`] and `(1/N) Σ_i (a_i − b_i)²` ([`Squares`]) of the same
/// columns, each difference taken once.
fn max_and_mean_square(a: &[BigRational], b: &[BigRational]) -> (MaxError, BigRational) {
    let mut best = Largest::default();
    let mut squares = Squares::default();
    for (i, (p, q)) in a.iter().zip(b).enumerate() {
        let d = difference(p, q);
        squares.add(&d);
        best.offer(i, d);
    }
    (best.into_max(), squares.mean(a.len()))
}

/// A sum of squares `Σ n_i² / (o² 2^{2 z_i})` over one odd part `o` of the
/// denominators: the integer `Σ n_i² 2^{shift − 2 z_i}` over `2^shift`.
#[derive(Debug, Default)]
struct DyadicSum {
    numerator: BigInt,
    shift: u64,
}

impl DyadicSum {
    /// Adds `square / 2^shift`.
    fn add(&mut self, square: BigInt, shift: u64) {
        if shift > self.shift {
            self.numerator <<= shift - self.shift;
            self.shift = shift;
            self.numerator += square;
        } else {
            self.numerator += square << (self.shift - shift);
        }
    }
}

/// A running `Σ d_i²`. The squares are summed by the odd part of their
/// denominators, each group as one integer over a power of two (no gcd
/// per value: the denominators of doubles and of dyadic answers share a
/// few odd parts), and the groups added once at the end.
#[derive(Debug, Default)]
struct Squares {
    groups: HashMap<BigInt, DyadicSum>,
}

impl Squares {
    fn add(&mut self, d: &BigRational) {
        if Zero::is_zero(d) {
            return;
        }
        // A denominator is positive: it has a number of trailing zeros.
        let z = d.denom().trailing_zeros().unwrap_or(0);
        self.groups
            .entry(d.denom() >> z)
            .or_default()
            .add(d.numer() * d.numer(), 2 * z);
    }

    /// `(1/n) Σ d_i²` (`0` for `n = 0`).
    fn mean(self, n: usize) -> BigRational {
        if n == 0 {
            return <BigRational as Zero>::zero();
        }
        let mut s = <BigRational as Zero>::zero();
        for (odd, group) in self.groups {
            let den = (&odd * &odd) << group.shift;
            s = crate::reduced::sum(&s, &crate::gcd::ratio(group.numerator, den));
        }
        quotient(&s, &BigRational::from_integer(n.into()))
    }
}

fn check_len(what: &'static str, v: &[impl Sized], expected: usize) -> Result<(), CompareError> {
    if v.len() == expected {
        Ok(())
    } else {
        Err(CompareError::Length {
            what,
            expected,
            found: v.len(),
        })
    }
}

/// `x_{j+1} − x_j − 2r` for every pair of `x`, exact.
pub fn candidate_gaps(x: &[BigRational], two_r: &BigRational) -> Vec<BigRational> {
    x.windows(2)
        .map(|w| difference(&difference(&w[1], &w[0]), two_r))
        .collect()
}

/// Whether the clusters `clusters` (left to right, as a state's) hold `c`.
fn holds(clusters: &[crate::cluster::Cluster], c: &crate::cluster::Cluster) -> bool {
    clusters
        .binary_search_by_key(&c.first, |d| d.first)
        .is_ok_and(|k| clusters[k] == *c)
}

/// Compares a candidate exactly with the exact state `exact` of the data
/// whose `2r` is `two_r`. `tol ≥ 0` is the contact tolerance used when the
/// candidate gives no contact set of its own (`0`: a contact is an exact
/// `x_{j+1} − x_j ≤ 2r`).
///
/// **Contacts.** The exact contact set is exact: the pairs with gap `0` in
/// `x(t)` (`df:Omega-micro`), whatever the force (a resting contact has
/// `λ = μ = 0` and is a contact). A floating-point answer cannot hold a
/// gap of exactly `0` unless the coordinates are dyadic, so its contact set
/// is its own report when it gives one (`contacts`: our `f64` methods each
/// document their rule, [`crate::reference::Output::contacts`]; every peer
/// driver of `scripts/peers/` reports the pairs with gap `≤ 10⁻⁶·2r`), and
/// otherwise the pairs with gap `≤ tol` (the atlas passes `10⁻⁶·2r`, its
/// overlap threshold; `sticky compare` `--contact-tol`, default `0`). An
/// answer `10⁻¹³` from touching is thus in contact for the atlas and for
/// every peer; with `tol = 0` only if it touches or overlaps.
pub fn compare(
    cand: &Candidate<'_>,
    exact: &crate::state::State<BigRational>,
    two_r: &BigRational,
    tol: &BigRational,
) -> Result<Comparison, CompareError> {
    let gaps = candidate_gaps(cand.positions, two_r);
    compare_with_gaps(cand, exact, &gaps, tol)
}

/// [`compare`] given the candidate's gaps `gaps[j] = x_{j+1} − x_j − 2r`
/// ([`candidate_gaps`], of any length: the positions' length is checked
/// first), for a caller that needs them too (the verdict).
pub fn compare_with_gaps(
    cand: &Candidate<'_>,
    exact: &crate::state::State<BigRational>,
    gaps: &[BigRational],
    tol: &BigRational,
) -> Result<Comparison, CompareError> {
    let n = exact.positions.len();
    let pairs = n.saturating_sub(1);
    check_len("positions", cand.positions, n)?;
    if let Some(u) = cand.velocities {
        check_len("velocities", u, n)?;
    }
    if let Some(l) = cand.multipliers {
        check_len("multipliers", l, pairs)?;
    }
    if let Some(c) = cand.contacts {
        check_len("contacts", c, pairs)?;
    }
    let x = cand.positions;
    debug_assert_eq!(gaps.len(), pairs, "one gap per pair of the candidate");
    let overlaps = gaps
        .iter()
        .enumerate()
        .filter(|(_, g)| g.is_negative())
        .map(|(pair, g)| Overlap {
            pair,
            depth: -g.clone(),
        })
        .collect();
    let mut exact_contact = vec![false; pairs];
    for c in &exact.clusters {
        for flag in &mut exact_contact[c.first..c.end() - 1] {
            *flag = true;
        }
    }
    let cand_contact: Vec<bool> = match cand.contacts {
        Some(c) => c.to_vec(),
        None => gaps.iter().map(|g| !exceeds(g, tol)).collect(),
    };
    let missed_contacts = (0..pairs)
        .filter(|&j| exact_contact[j] && !cand_contact[j])
        .count();
    let spurious_contacts = (0..pairs)
        .filter(|&j| !exact_contact[j] && cand_contact[j])
        .count();
    let cand_clusters = crate::cluster::runs(n, |j| cand_contact[j]);
    let big = |c: &&crate::cluster::Cluster| c.size >= 2;
    let missed_clusters = exact
        .clusters
        .iter()
        .filter(big)
        .filter(|c| !holds(&cand_clusters, c))
        .copied()
        .collect();
    let spurious_clusters = cand_clusters
        .iter()
        .filter(big)
        .filter(|c| !holds(&exact.clusters, c))
        .copied()
        .collect();
    let (negative_multipliers, complementarity) = match cand.multipliers {
        Some(l) => (
            l.iter()
                .enumerate()
                .filter(|(_, v)| v.is_negative())
                .map(|(pair, v)| PairValue {
                    pair,
                    value: v.clone(),
                })
                .collect(),
            l.iter()
                .zip(gaps)
                .enumerate()
                .filter(|(_, (v, g))| !Zero::is_zero(*v) && !Zero::is_zero(*g))
                .map(|(pair, (v, g))| PairValue {
                    pair,
                    value: product(v, g),
                })
                .collect(),
        ),
        None => (Vec::new(), Vec::new()),
    };
    let (position_max, position_l2_squared) = max_and_mean_square(x, &exact.positions);
    let (velocity_max, velocity_l2_squared) = cand
        .velocities
        .map(|u| max_and_mean_square(u, &exact.velocities))
        .unzip();
    Ok(Comparison {
        t: exact.t.clone(),
        position_max,
        position_l2_squared,
        velocity_max,
        velocity_l2_squared,
        multiplier_max: cand
            .multipliers
            .filter(|_| pairs > 0)
            .map(|l| max_error(l, &exact.multipliers)),
        overlaps,
        missed_clusters,
        spurious_clusters,
        missed_contacts,
        spurious_contacts,
        negative_multipliers,
        complementarity,
        oleinik: cand
            .velocities
            .filter(|_| exact.t.is_positive())
            .map(|u| oleinik_violations(x, u, &exact.t)),
    })
}

#[cfg(test)]
mod compare_tests {
    use super::*;
    use crate::cluster::Cluster;
    use crate::state::State;

    use crate::rational::ratio as q;

    /// Three particles, 2r = 1/2, the first two in contact.
    fn exact() -> State<BigRational> {
        State {
            t: q(1, 1),
            positions: vec![q(0, 1), q(1, 2), q(2, 1)],
            velocities: vec![q(1, 1), q(1, 1), q(0, 1)],
            multipliers: vec![q(1, 3), q(0, 1)],
            clusters: vec![Cluster { first: 0, size: 2 }, Cluster { first: 2, size: 1 }],
        }
    }

    /// [`compare`] of a candidate without contacts against [`exact`]
    /// (`2r = 1/2`, no tolerance).
    fn against_exact(
        positions: &[BigRational],
        velocities: Option<&[BigRational]>,
        multipliers: Option<&[BigRational]>,
    ) -> Result<Comparison, CompareError> {
        let candidate = Candidate {
            positions,
            velocities,
            multipliers,
            contacts: None,
        };
        compare(&candidate, &exact(), &q(1, 2), &q(0, 1))
    }

    #[test]
    fn known_perturbations_exactly() {
        let x = vec![q(0, 1), q(1, 2), q(2, 1) + q(3, 100)];
        let u = vec![q(1, 1) - q(1, 7), q(1, 1), q(0, 1)];
        let l = vec![q(1, 3), q(-1, 5)];
        let c = against_exact(&x, Some(&u), Some(&l)).unwrap();
        assert_eq!(
            c.position_max,
            MaxError {
                value: q(3, 100),
                index: 2
            }
        );
        assert_eq!(c.position_l2_squared, q(9, 30000));
        assert_eq!(c.velocity_max.as_ref().unwrap().value, q(1, 7));
        assert_eq!(c.velocity_l2_squared, Some(q(1, 147)));
        assert_eq!(c.multiplier_max.as_ref().unwrap().value, q(1, 5));
        assert_eq!(
            c.negative_multipliers,
            vec![PairValue {
                pair: 1,
                value: q(-1, 5)
            }]
        );
        // Pair 1: gap 2 + 3/100 − 1/2 − 1/2 = 103/100, λ = −1/5.
        assert_eq!(
            c.complementarity,
            vec![PairValue {
                pair: 1,
                value: q(-103, 500)
            }]
        );
        assert!(c.overlaps.is_empty());
        // u_1 − u_0 = 1/7 over a gap 1/2 at t = 1: 1/7 < 1/2, fine.
        assert_eq!(c.oleinik, Some(vec![]));
        assert!(c.violates_model() && !c.is_exact());
    }

    /// The max error of either sign, reached twice: the first index, the
    /// value positive; the mean square over every particle.
    #[test]
    fn the_first_index_of_the_max_and_the_mean_square() {
        let x = vec![q(0, 1), q(1, 2) - q(1, 8), q(2, 1) + q(1, 8)];
        let u = vec![q(1, 1), q(1, 1) + q(1, 16), q(0, 1) - q(1, 4)];
        let c = against_exact(&x, Some(&u), None).unwrap();
        assert_eq!(
            c.position_max,
            MaxError {
                value: q(1, 8),
                index: 1
            }
        );
        assert_eq!(c.position_l2_squared, q(2, 3 * 64));
        assert_eq!(
            c.velocity_max,
            Some(MaxError {
                value: q(1, 4),
                index: 2
            })
        );
        assert_eq!(c.velocity_l2_squared, Some(q(1 + 16, 3 * 256)));
    }

    #[test]
    fn lengths_are_checked() {
        let r = against_exact(&[q(0, 1)], None, None);
        assert!(matches!(
            r,
            Err(CompareError::Length {
                expected: 3,
                found: 1,
                ..
            })
        ));
    }
}
