//! The machine-readable witness of a counterexample (`witness_data` of
//! `sticky claims --json`): the scene, the time(s) where the statement
//! fails, the open interval between collisions that holds them (for an
//! a.e.-in-`t` statement), and per time the indices, the test function and
//! the two sides' exact values. Every number is an exact string (`"p/q"`).
//! [`WitnessData::replay`] rebuilds the datum from these strings alone, so a
//! test can re-check every witness with the generic `BigRational` engine.

use num_rational::BigRational;

use super::domain::{Domain, OpenInterval, Refusal};
use super::{Case, CaseCheck};
use crate::initial::InitialData;
use crate::rational::{parse_exact, render_exact};
use crate::trajectory::Trajectory;
use crate::violation::{Detail, Violation};

/// The scene a witness lives on.
#[derive(Debug, Clone, PartialEq, Eq)]
#[cfg_attr(feature = "json", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(all(test, feature = "json"), derive(schemars::JsonSchema))]
#[cfg_attr(feature = "json", serde(tag = "kind", rename_all = "snake_case"))]
pub enum WitnessScene {
    /// A particle datum, every number an exact string.
    Particles {
        /// N.
        n: usize,
        /// The radius r.
        radius: String,
        /// x⁰.
        positions: Vec<String>,
        /// u⁰.
        velocities: Vec<String>,
    },
    /// A shipped scene (`scenes/<name>.toml`).
    Shipped {
        /// Its name.
        name: String,
    },
    /// A `[macro]` datum: its `blocks` array as in a scene file (the
    /// failing N is in the failure's text).
    Macro {
        /// `[{ from, to, density, velocity }, …]`, exact strings.
        blocks: String,
    },
    /// A fixed formula of the paper (no scene: the formula is the witness).
    Formula,
}

/// The open interval `(lo, hi)` between consecutive collision instants
/// (`hi = None` after the last) holding the witness times.
#[derive(Debug, Clone, PartialEq, Eq)]
#[cfg_attr(feature = "json", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(all(test, feature = "json"), derive(schemars::JsonSchema))]
pub struct Interval {
    /// The left end: 0 or a collision instant.
    pub lo: String,
    /// The right end, `None` after the last collision.
    pub hi: Option<String>,
}

/// The failure at one time (or the only failure of a timeless claim).
#[derive(Debug, Clone, PartialEq, Eq)]
#[cfg_attr(feature = "json", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(all(test, feature = "json"), derive(schemars::JsonSchema))]
pub struct Failure {
    /// The time, when there is one.
    pub t: Option<String>,
    /// The indices involved (from 0).
    pub indices: Vec<usize>,
    /// The Lagrangian points `w`, when pointwise in `w`.
    pub w: Vec<String>,
    /// The test function, when there is one.
    pub test_function: Option<String>,
    /// What the left side is.
    pub lhs_is: Option<String>,
    /// Its exact value.
    pub lhs: Option<String>,
    /// What the right side is.
    pub rhs_is: Option<String>,
    /// Its exact value.
    pub rhs: Option<String>,
    /// The checker's text.
    pub text: String,
}

impl Failure {
    /// The failure a violation describes.
    pub fn of(v: &Violation) -> Self {
        let Detail {
            t,
            indices,
            w,
            test_function,
            sides,
        } = (*v.detail).clone();
        let (lhs_is, lhs, rhs_is, rhs) = match sides {
            Some(s) => (Some(s.lhs_is), Some(s.lhs), Some(s.rhs_is), Some(s.rhs)),
            None => (None, None, None, None),
        };
        Failure {
            t,
            indices,
            w,
            test_function,
            lhs_is,
            lhs,
            rhs_is,
            rhs,
            text: v.witness.clone(),
        }
    }
}

/// The domain a witness was accepted in, in words.
#[derive(Debug, Clone, PartialEq, Eq)]
#[cfg_attr(feature = "json", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(all(test, feature = "json"), derive(schemars::JsonSchema))]
pub struct DomainData {
    /// The `\label` that states it.
    pub label: String,
    /// The paper's words.
    pub text: String,
    /// `every t`, `t > 0`, `a.e. t`, `measure in t`, `none`.
    pub time: String,
    /// The least N.
    pub min_n: usize,
    /// `none`, `C1_c((0,T)x(0,1))`, `C1_c((0,T))`.
    pub test_functions: String,
    /// `none`, `a.e. w`.
    pub w: String,
    /// `u0 in C_x0` or `u0 in H_x0`.
    pub datum: String,
}

impl DomainData {
    /// The words of `d`.
    pub fn of(d: &Domain) -> Self {
        use super::domain::{Datum, InTime, InW, TestFunctions};
        DomainData {
            label: d.label.to_string(),
            text: d.text.to_string(),
            time: match d.time {
                InTime::Every => "every t",
                InTime::Positive => "t > 0",
                InTime::AlmostEvery => "a.e. t",
                InTime::Measure => "measure in t",
                InTime::None => "none",
            }
            .to_string(),
            min_n: d.min_n,
            test_functions: match d.test_functions {
                TestFunctions::None => "none",
                TestFunctions::SmoothCompact => "C1_c((0,T)x(0,1))",
                TestFunctions::SmoothInTime => "C1_c((0,T))",
            }
            .to_string(),
            w: match d.w {
                InW::None => "none",
                InW::AlmostEvery => "a.e. w",
            }
            .to_string(),
            datum: match d.datum {
                Datum::InC => "u0 in C_x0",
                Datum::InH => "u0 in H_x0",
            }
            .to_string(),
        }
    }
}

/// A counterexample in machine-readable form.
#[derive(Debug, Clone, PartialEq, Eq)]
#[cfg_attr(feature = "json", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(all(test, feature = "json"), derive(schemars::JsonSchema))]
pub struct WitnessData {
    /// The scene.
    pub scene: WitnessScene,
    /// The domain the witness lies in.
    pub domain: DomainData,
    /// The times where the failure is shown (two for an a.e.-in-`t`
    /// statement, increasing).
    pub times: Vec<String>,
    /// The open interval between collisions holding `times` (a.e. in `t`).
    pub interval: Option<Interval>,
    /// One failure per time (or one for a timeless claim).
    pub failures: Vec<Failure>,
}

/// The scene of a particle datum.
pub fn particles(data: &InitialData<BigRational>) -> WitnessScene {
    let list = |v: &[BigRational]| v.iter().map(render_exact).collect();
    WitnessScene::Particles {
        n: data.n(),
        radius: render_exact(data.radius()),
        positions: list(data.positions()),
        velocities: list(data.velocities()),
    }
}

/// The interval of an [`OpenInterval`].
pub fn interval(iv: &OpenInterval<BigRational>) -> Interval {
    Interval {
        lo: render_exact(&iv.lo),
        hi: iv.hi.as_ref().map(render_exact),
    }
}

/// Why a witness does not replay.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum ReplayError {
    /// The witness has no particle scene (a formula or a shipped scene).
    NoParticles,
    /// A number or the datum does not parse.
    Unreadable(String),
    /// The witness lies outside its statement's domain.
    Outside(Refusal),
    /// The checker passes at a witness time.
    Holds(String),
    /// The checker fails, but with other values than recorded.
    OtherValues(String),
}

impl WitnessData {
    /// N of a particle witness (0 otherwise).
    pub fn scene_n(&self) -> usize {
        match &self.scene {
            WitnessScene::Particles { n, .. } => *n,
            _ => 0,
        }
    }
    /// Re-checks a particle witness from its strings alone: rebuilds the
    /// datum, computes its history with the generic engine, asks
    /// [`Domain::admits`] of the times and runs `check` at each time alone;
    /// every run must fail with the recorded two sides.
    pub fn replay(
        &self,
        domain: &Domain,
        check: CaseCheck<BigRational>,
    ) -> Result<(), ReplayError> {
        let WitnessScene::Particles {
            radius,
            positions,
            velocities,
            ..
        } = &self.scene
        else {
            return Err(ReplayError::NoParticles);
        };
        let num = |s: &String| parse_exact(s).map_err(|e| ReplayError::Unreadable(e.to_string()));
        let nums = |v: &[String]| v.iter().map(num).collect::<Result<Vec<_>, _>>();
        let data = InitialData::new(num(radius)?, nums(positions)?, nums(velocities)?)
            .map_err(|e| ReplayError::Unreadable(e.to_string()))?;
        let traj = Trajectory::new(data);
        let times = nums(&self.times)?;
        domain.admits(&traj, &times).map_err(ReplayError::Outside)?;
        let runs: Vec<Vec<BigRational>> = if times.is_empty() {
            vec![super::micro::probe_times(&traj, None)]
        } else {
            times.iter().map(|t| vec![t.clone()]).collect()
        };
        for (probe, recorded) in runs.into_iter().zip(&self.failures) {
            let case = Case::with_times(traj.clone(), probe);
            let v = match check(&case) {
                Ok(()) => return Err(ReplayError::Holds(recorded.text.clone())),
                Err(v) => v,
            };
            if Failure::of(&v) != *recorded {
                return Err(ReplayError::OtherValues(v.witness));
            }
        }
        Ok(())
    }
}
