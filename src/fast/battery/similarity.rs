//! The similarities of the line under which the battery compares engines
//! on wide data with the oracle on small data (`df:KN`, `eq:dyn-micro`).

use std::fmt;

use num_rational::BigRational;
use num_traits::{One, Signed, Zero};

use super::diff::{list_diff, list_diff_debug};
use crate::contact::Impulse;
use crate::initial::InitialData;
use crate::state::State;
use crate::trajectory::Trajectory;

/// A similarity of the line, `x ↦ ratio·x + shift` with `ratio > 0`. The
/// sticky dynamics commute with it: the data `(ratio·r, ratio·x⁰ + shift,
/// ratio·u⁰)` move as `x(t) ↦ ratio·x(t) + shift`, `u(t) ↦ ratio·u(t)`,
/// `λ(t) ↦ ratio·λ(t)` (`λ` is linear in `u⁰ − u(t)`, `eq:dyn-micro`), with
/// the same contact clusters and collision times — `K_N` (`df:KN`) is
/// mapped onto itself for the scaled radius and the Euclidean projection
/// commutes with similarities. [`check_similar`](super::check_similar) runs the engines on the
/// image of small data and compares them with the image of the oracle's
/// answer on the small data: wide integers, the oracle on small ones.
#[derive(Debug, Clone, PartialEq)]
pub struct Similarity {
    pub(super) ratio: BigRational,
    pub(super) shift: BigRational,
}

impl Similarity {
    /// `x ↦ ratio·x + shift`; `None` unless `ratio > 0`.
    pub fn new(ratio: BigRational, shift: BigRational) -> Option<Similarity> {
        ratio.is_positive().then_some(Similarity { ratio, shift })
    }
    /// The identity.
    pub fn identity() -> Similarity {
        Similarity {
            ratio: BigRational::one(),
            shift: BigRational::zero(),
        }
    }
    pub(super) fn is_identity(&self) -> bool {
        self.ratio.is_one() && self.shift.is_zero()
    }
    fn scaled(&self, v: &[BigRational]) -> Vec<BigRational> {
        v.iter().map(|a| self.velocity(a)).collect()
    }
    /// The image of initial data (admissible again: gaps and the radius are
    /// scaled by the same positive ratio, the velocity cone is a cone).
    pub fn data(&self, d: &InitialData<BigRational>) -> InitialData<BigRational> {
        let x = d.positions().iter().map(|a| self.position(a)).collect();
        let image = InitialData::new(self.velocity(d.radius()), x, self.scaled(d.velocities()));
        debug_assert!(image.is_ok(), "a similarity keeps data admissible");
        image.unwrap_or_else(|_| d.clone())
    }
    /// The image `ratio·x + shift` of a position: with `ratio = p/q`,
    /// `shift = b/c`, `x = n/d`, `(p·n·c + b·q·d)/(q·d·c)` reduced once by
    /// [`crate::gcd::ratio`] (`BigRational`'s operators reduce twice, by
    /// `num-bigint`'s binary gcd, slow on a wide and a small operand).
    pub fn position(&self, x: &BigRational) -> BigRational {
        let (p, q) = (self.ratio.numer(), self.ratio.denom());
        let (b, c) = (self.shift.numer(), self.shift.denom());
        let (n, d) = (x.numer(), x.denom());
        crate::gcd::ratio(p * n * c + b * q * d, q * d * c)
    }
    /// The image `ratio·u` of a velocity (or of a multiplier `λ`):
    /// `(p·n)/(q·d)`, reduced once by [`crate::gcd::ratio`].
    pub fn velocity(&self, u: &BigRational) -> BigRational {
        let (p, q) = (self.ratio.numer(), self.ratio.denom());
        crate::gcd::ratio(p * u.numer(), q * u.denom())
    }
    /// Whether `image` is [`Similarity::position`]`(x)`, decided by
    /// cross-multiplication (no gcd): with `ratio = p/q`, `shift = b/c`,
    /// `x = n/d`, `image = m/e`: `m·q·d·c = (p·n·c + b·q·d)·e`.
    fn maps_position(&self, x: &BigRational, image: &BigRational) -> bool {
        let (p, q) = (self.ratio.numer(), self.ratio.denom());
        let (b, c) = (self.shift.numer(), self.shift.denom());
        let (n, d) = (x.numer(), x.denom());
        let (m, e) = (image.numer(), image.denom());
        m * q * d * c == (p * n * c + b * q * d) * e
    }
    /// Whether `image` is [`Similarity::velocity`]`(u)`: `m·q·d = p·n·e`.
    fn maps_velocity(&self, u: &BigRational, image: &BigRational) -> bool {
        let (p, q) = (self.ratio.numer(), self.ratio.denom());
        image.numer() * q * u.denom() == p * u.numer() * image.denom()
    }
    /// The first field where `got` differs from the image of `want` (the
    /// same time and clusters, positions mapped by the similarity,
    /// velocities and multipliers scaled); compared by cross-multiplication,
    /// formatted only at the difference.
    pub(super) fn state_diff(
        &self,
        want: &State<BigRational>,
        got: &State<BigRational>,
    ) -> Option<String> {
        if want.t != got.t {
            return Some(format!("t = {}, expected {}", got.t, want.t));
        }
        if self.is_identity() {
            return list_diff("positions", &want.positions, &got.positions, |w| w.clone())
                .or_else(|| {
                    list_diff("velocities", &want.velocities, &got.velocities, |w| {
                        w.clone()
                    })
                })
                .or_else(|| {
                    list_diff("multipliers", &want.multipliers, &got.multipliers, |w| {
                        w.clone()
                    })
                })
                .or_else(|| list_diff_debug("clusters", &want.clusters, &got.clusters));
        }
        let position = Image {
            same: &|w, g| self.maps_position(w, g),
            show: &|w| self.position(w),
        };
        let velocity = Image {
            same: &|w, g| self.maps_velocity(w, g),
            show: &|w| self.velocity(w),
        };
        list_diff_debug("clusters", &want.clusters, &got.clusters)
            .or_else(|| position.diff("positions", &want.positions, &got.positions))
            .or_else(|| velocity.diff("velocities", &want.velocities, &got.velocities))
            .or_else(|| velocity.diff("multipliers", &want.multipliers, &got.multipliers))
    }
    /// The image of a history: the image data, the same join times, each
    /// impulse's velocities scaled.
    pub fn trajectory(&self, h: &Trajectory<BigRational>) -> Trajectory<BigRational> {
        let impulses = h
            .impulses()
            .iter()
            .map(|i| Impulse {
                part_velocities: self.scaled(&i.part_velocities),
                velocity: self.velocity(&i.velocity),
                ..i.clone()
            })
            .collect();
        Trajectory::from_parts(self.data(h.data()), h.join_times().to_vec(), impulses)
    }
}

impl fmt::Display for Similarity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "x ↦ ({})·x + ({})", self.ratio, self.shift)
    }
}

/// How an expected value maps to the frame of the answer compared with it.
struct Image<'a> {
    /// Whether the answer `got` is the image of the expected `want`.
    same: &'a dyn Fn(&BigRational, &BigRational) -> bool,
    /// The image of `want`, for the message.
    show: &'a dyn Fn(&BigRational) -> BigRational,
}

impl Image<'_> {
    /// The first index where `got` is not the image of `want`, described.
    fn diff(&self, field: &str, want: &[BigRational], got: &[BigRational]) -> Option<String> {
        if let Some(i) = (0..want.len().min(got.len())).find(|&i| !(self.same)(&want[i], &got[i])) {
            return Some(format!(
                "{field}[{i}] = {}, expected {}",
                got[i],
                (self.show)(&want[i])
            ));
        }
        (want.len() != got.len()).then(|| format!("{} {field}, expected {}", got.len(), want.len()))
    }
}
