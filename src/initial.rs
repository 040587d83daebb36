//! Validated initial data `(x⁰, u⁰, r)`: `x⁰ ∈ K^N` (`df:KN`) and
//! `u⁰ ∈ C_{x⁰}` (`def:velcone`).

use crate::error::Error;
use crate::scalar::Scalar;

/// Initial positions and velocities of N particles of radius `r`, checked to
/// be admissible: `x⁰_{i+1} − x⁰_i ≥ 2r` and `u⁰_{i+1} ≥ u⁰_i` wherever
/// `x⁰_{i+1} − x⁰_i = 2r`.
#[derive(Debug, Clone, PartialEq)]
pub struct InitialData<S> {
    radius: S,
    positions: Vec<S>,
    velocities: Vec<S>,
}

impl<S: Scalar> InitialData<S> {
    /// Checks and wraps initial data. Errors name the first offending pair
    /// (indexed from 0: `positions[i]` is the paper's `x_{i+1}`).
    pub fn new(radius: S, positions: Vec<S>, velocities: Vec<S>) -> Result<Self, Error> {
        if positions.len() != velocities.len() {
            return Err(Error::LengthMismatch {
                positions: positions.len(),
                velocities: velocities.len(),
            });
        }
        if positions.is_empty() {
            return Err(Error::NoParticles);
        }
        if radius.total_cmp(&S::zero()).is_le() {
            return Err(Error::NonPositiveRadius {
                radius: radius.render(),
            });
        }
        let two_r = radius.plus(&radius);
        for i in 0..positions.len() - 1 {
            let gap = positions[i + 1].minus(&positions[i]);
            match gap.total_cmp(&two_r) {
                std::cmp::Ordering::Less => {
                    return Err(Error::Overlap {
                        i,
                        gap: gap.render(),
                        two_r: two_r.render(),
                    })
                }
                std::cmp::Ordering::Equal => {
                    if velocities[i].total_cmp(&velocities[i + 1]).is_gt() {
                        return Err(Error::Approaching {
                            i,
                            left: velocities[i].render(),
                            right: velocities[i + 1].render(),
                        });
                    }
                }
                std::cmp::Ordering::Greater => {}
            }
        }
        Ok(InitialData {
            radius,
            positions,
            velocities,
        })
    }

    /// Initial data with the paper's radius `2r = 1/N`.
    pub fn with_paper_radius(positions: Vec<S>, velocities: Vec<S>) -> Result<Self, Error> {
        let n = positions.len().max(1);
        let radius = S::one() / S::from_usize(2 * n);
        Self::new(radius, positions, velocities)
    }

    /// Number of particles N.
    pub fn n(&self) -> usize {
        self.positions.len()
    }
    /// The radius r.
    pub fn radius(&self) -> &S {
        &self.radius
    }
    /// `2r`.
    pub fn two_r(&self) -> S {
        self.radius.clone() + &self.radius
    }
    /// `x⁰`.
    pub fn positions(&self) -> &[S] {
        &self.positions
    }
    /// `u⁰`.
    pub fn velocities(&self) -> &[S] {
        &self.velocities
    }
    /// The translated configuration `x̃⁰_i = x⁰_i − 2r(i−1)` (`df:translat-x`),
    /// in which `K^N` becomes the cone of non-decreasing vectors (`df:tKN`).
    pub fn shifted_positions(&self) -> Vec<S> {
        shift(&self.positions, &self.two_r())
    }
    /// The same data rounded to `f64`, **not** re-validated: for pictures
    /// of a history computed exactly ([`crate::trajectory::Trajectory::to_f64_lossy`]),
    /// never as the input of a computation.
    pub(crate) fn to_f64_lossy(&self) -> InitialData<f64> {
        InitialData {
            radius: self.radius.to_f64_lossy(),
            positions: self.positions.iter().map(S::to_f64_lossy).collect(),
            velocities: self.velocities.iter().map(S::to_f64_lossy).collect(),
        }
    }

    /// Converts every number to another scalar type (`None` when one does not
    /// fit). The result is re-validated, so a rounding f64 conversion that
    /// creates an overlap is reported, not hidden.
    pub fn convert<T: Scalar>(&self) -> Option<Result<InitialData<T>, Error>> {
        let conv = |v: &S| v.to_big_rational().and_then(|q| T::from_big_rational(&q));
        let radius = conv(&self.radius)?;
        let positions = self
            .positions
            .iter()
            .map(conv)
            .collect::<Option<Vec<_>>>()?;
        let velocities = self
            .velocities
            .iter()
            .map(conv)
            .collect::<Option<Vec<_>>>()?;
        Some(InitialData::new(radius, positions, velocities))
    }
}

/// `x̃_i = x_i − 2r(i−1)` (`df:translat-x`; 0-based here: `x_i − 2r·i`).
pub fn shift<S: Scalar>(x: &[S], two_r: &S) -> Vec<S> {
    let mut offset = S::zero();
    x.iter()
        .map(|xi| {
            let v = xi.minus(&offset);
            offset = offset.plus(two_r);
            v
        })
        .collect()
}

/// Inverse of [`shift`]: `x_i = x̃_i + 2r(i−1)`.
pub fn unshift<S: Scalar>(xt: &[S], two_r: &S) -> Vec<S> {
    let mut offset = S::zero();
    xt.iter()
        .map(|xi| {
            let v = xi.clone() + &offset;
            offset = offset.clone() + two_r;
            v
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_rational::{BigRational, Rational64};

    fn checks<S: Scalar>() {
        let q = |n: i64, d: i64| S::from_i64(n) / S::from_i64(d);
        let r = q(1, 16);
        let ok = InitialData::new(
            r.clone(),
            vec![q(0, 1), q(1, 8), q(1, 4), q(3, 8)],
            vec![q(1, 1), q(1, 1), q(-1, 1), q(-1, 1)],
        );
        assert!(ok.is_err(), "particles 1 and 2 (from 0) touch and approach");
        let err = ok.unwrap_err();
        assert!(matches!(err, Error::Approaching { i: 1, .. }), "{err}");
        let overlap = InitialData::new(
            r.clone(),
            vec![q(0, 1), q(1, 8), q(1, 5), q(1, 2)],
            vec![q(0, 1); 4],
        )
        .unwrap_err();
        assert_eq!(
            overlap.to_string(),
            "positions[1] and positions[2] overlap: gap 3/40 < 2r = 1/8"
        );
        let fine = InitialData::new(
            r.clone(),
            vec![q(0, 1), q(1, 8), q(1, 2)],
            vec![q(-1, 1), q(2, 1), q(0, 1)],
        )
        .unwrap();
        assert_eq!(fine.shifted_positions(), vec![q(0, 1), q(0, 1), q(1, 4)]);
        assert_eq!(
            unshift(&fine.shifted_positions(), &fine.two_r()),
            fine.positions()
        );
        assert_eq!(
            InitialData::<S>::new(r.clone(), vec![], vec![]).unwrap_err(),
            Error::NoParticles
        );
        assert!(matches!(
            InitialData::new(q(0, 1), vec![q(0, 1)], vec![q(0, 1)]).unwrap_err(),
            Error::NonPositiveRadius { .. }
        ));
        assert!(matches!(
            InitialData::new(r, vec![q(0, 1)], vec![]).unwrap_err(),
            Error::LengthMismatch {
                positions: 1,
                velocities: 0
            }
        ));
    }

    #[test]
    fn validation_rational64() {
        checks::<Rational64>();
    }
    #[test]
    fn validation_bigrational() {
        checks::<BigRational>();
    }
}
