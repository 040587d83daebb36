//! Another solver's answer against sticky's exact one: every figure, the
//! verdict, and the report for people ([`Report::text`]) and for scripts
//! (`Report::json`, feature `json`) — the one comparison behind `sticky
//! compare` and the Python package's `sticky.compare`.
//!
//! The exact answer at each time is the [`Solver`]'s
//! `x(t) = P_K(x⁰ + t u⁰)` (`prop:proj-micro`), `u(t)` and `λ(t)`
//! (`eq:dyn-micro`); the figures are
//! [`reference::measure::compare`](crate::reference::measure::compare)'s,
//! exact; the verdict is [`verdict`]'s ladder (`exact`, `rounding`,
//! `inexact`, `invalid`). Particles and pairs are indexed from 0 everywhere.
//!
//! ```
//! use num_rational::BigRational;
//! use sticky::report::compare::{compare_solution, CompareOptions, Verdict};
//! use sticky::report::solution::Frame;
//! use sticky::InitialData;
//!
//! let q = |n: i64, d: i64| BigRational::new(n.into(), d.into());
//! // Two particles of radius 1/4 meet at t = 3/4 and stick at 3/4, 5/4.
//! let data = InitialData::new(q(1, 4), vec![q(0, 1), q(2, 1)], vec![q(1, 1), q(-1, 1)])?;
//! // A solver's answer at t = 1, the right particle 1/1000 too far right.
//! let frame = Frame::new(q(1, 1), vec![q(3, 4), q(5, 4) + q(1, 1000)]);
//! let report = compare_solution(&data, &[frame], &CompareOptions::default())?;
//! let c = &report.frames[0].comparison;
//! assert_eq!((c.position_max.value.clone(), c.position_max.index), (q(1, 1000), 1));
//! assert_eq!(report.verdict, Verdict::Inexact); // the contact is missed
//! assert!(report.text().contains("1/1000 (1.000e-3)"));
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod decimal;
#[cfg(feature = "json")]
pub mod json;
pub mod text;
pub mod verdict;

use std::fmt;

use num_rational::BigRational;
use num_traits::{Signed, Zero};

use crate::initial::InitialData;
use crate::progress::{Progress, Silent};
use crate::reference::measure::{
    candidate_gaps, compare_with_gaps, largest, CompareError, Comparison,
};
use crate::report::solution::Frame;
use crate::scalar::Scalar;
use crate::solver::Solver;

pub use verdict::{Representation, Tolerances, Verdict};

/// When two neighbours of the solver's answer count as in contact, if the
/// answer gives no `clusters` of its own: gap `x_{j+1} − x_j ≤ 2r + tol`.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum ContactTolerance {
    /// `tol` itself (a length, `≥ 0`).
    Absolute(BigRational),
    /// `tol = k · 2r` for this `k ≥ 0` (the peers of `scripts/peers/` use
    /// `k = 10⁻⁶`).
    Relative(BigRational),
}

impl ContactTolerance {
    /// The tolerance as a length, for data of diameter `2r = two_r`.
    pub fn length(&self, two_r: &BigRational) -> BigRational {
        match self {
            ContactTolerance::Absolute(t) => t.clone(),
            ContactTolerance::Relative(k) => k * two_r,
        }
    }
}

/// How to compare.
#[derive(Debug, Clone, PartialEq)]
pub struct CompareOptions {
    /// The contact rule when the answer gives no `clusters` (default:
    /// absolute `0`, a contact is an exact touch or an overlap).
    pub contact_tol: ContactTolerance,
    /// The rounding tolerance `TOL ≥ 0`, relative: overlaps and position
    /// errors up to `TOL · 2r` (and the other bounds of [`Tolerances`]) make
    /// an answer `rounding` instead of `invalid` or `inexact` (default `0`:
    /// no answer is `rounding`).
    pub overlap_tol: BigRational,
}

impl Default for CompareOptions {
    fn default() -> CompareOptions {
        CompareOptions {
            contact_tol: ContactTolerance::Absolute(<BigRational as Zero>::zero()),
            overlap_tol: <BigRational as Zero>::zero(),
        }
    }
}

/// One time of the answer, measured.
#[derive(Debug, Clone, PartialEq)]
pub struct FrameReport {
    /// The line of the solution file where this time starts (1-based; `0`
    /// when the frame did not come from a file).
    pub line: usize,
    /// Every figure, exact.
    pub comparison: Comparison,
    /// The rounding bounds at this time.
    pub tolerances: Tolerances,
    /// This time's verdict.
    pub verdict: Verdict,
}

/// The whole comparison: every time, every figure, the verdict.
#[derive(Debug, Clone, PartialEq)]
pub struct Report {
    /// The scene's file, if any (shown in the report's header and JSON).
    pub scene: Option<String>,
    /// The solution's file, if any.
    pub solution: Option<String>,
    /// The number of particles `N`.
    pub n: usize,
    /// The radius `r`.
    pub radius: BigRational,
    /// The options used.
    pub options: CompareOptions,
    /// The contact tolerance as a length (`2r + this` is a contact).
    pub contact_tol: BigRational,
    /// One report per time, in the solution's order.
    pub frames: Vec<FrameReport>,
    /// The worst time's verdict.
    pub verdict: Verdict,
}

impl Report {
    /// Names the files compared (the report's header and JSON show them).
    pub fn with_files(mut self, scene: impl Into<String>, solution: impl Into<String>) -> Report {
        self.scene = Some(scene.into());
        self.solution = Some(solution.into());
        self
    }

    /// `2r`.
    pub fn two_r(&self) -> BigRational {
        &self.radius + &self.radius
    }

    /// The one-line verdict with the worst figures: `inexact (…): max
    /// position error 1/1000 (1.000e-3) (t = 1), …`.
    pub fn summary(&self) -> String {
        text::summary(self)
    }

    /// The report for people: per time, every figure exact with a decimal
    /// beside it, then the verdict line.
    pub fn text(&self) -> String {
        text::report(self)
    }
}

/// Why a solution cannot be compared.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum CompareFailure {
    /// One time of the solution cannot be compared (a wrong length, a
    /// negative time).
    Frame {
        /// Its line in the solution file (`0`: not from a file).
        line: usize,
        /// Its time.
        t: BigRational,
        /// What is wrong.
        error: CompareError,
    },
    /// A tolerance is negative.
    NegativeTolerance {
        /// `contact tolerance` or `overlap tolerance`.
        what: &'static str,
    },
    /// The scene's data cannot be read (a scene the general path refuses).
    Scene {
        /// The library's message.
        message: String,
    },
    /// The observer asked to stop.
    Interrupted,
}

impl fmt::Display for CompareFailure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CompareFailure::Frame { line, t, error } if *line > 0 => {
                write!(f, "{line}: {error}")?;
                let _ = t;
                Ok(())
            }
            CompareFailure::Frame { t, error, .. } => write!(f, "t = {}: {error}", t.render()),
            CompareFailure::NegativeTolerance { what } => write!(f, "the {what} is negative"),
            CompareFailure::Scene { message } => f.write_str(message),
            CompareFailure::Interrupted => f.write_str("interrupted"),
        }
    }
}

impl std::error::Error for CompareFailure {}

/// Compares every frame of a solution with the exact answer of `data` at its
/// time ([`compare_solution_with`] with no progress shown).
pub fn compare_solution(
    data: &InitialData<BigRational>,
    frames: &[Frame],
    options: &CompareOptions,
) -> Result<Report, CompareFailure> {
    compare_solution_with(data, frames, options, &Silent)
}

/// Compares every frame of a solution with the exact answer of `data` at its
/// time, telling `progress` of each frame (and stopping when it asks).
pub fn compare_solution_with(
    data: &InitialData<BigRational>,
    frames: &[Frame],
    options: &CompareOptions,
    progress: &dyn Progress,
) -> Result<Report, CompareFailure> {
    compare_solution_by(
        &crate::solver::Solver::from_data(data.clone()),
        frames,
        options,
        progress,
    )
}

/// `max_i |u⁰_i|` of the Solver's data: from its doubles when it was built
/// from them (`|·|` and `max` are exact on doubles), else from its
/// validated data.
fn largest_speed(solver: &Solver) -> Result<BigRational, crate::Error> {
    if let Some((_, u)) = solver.doubles() {
        let top = u.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        return crate::columns::f64_exact(top).ok_or_else(|| crate::Error::Unsupported {
            message: format!("{top} is not a finite number"),
        });
    }
    let speeds: Vec<BigRational> = solver
        .data()?
        .velocities()
        .iter()
        .map(|u| u.abs())
        .collect();
    Ok(largest(&speeds)
        .cloned()
        .unwrap_or_else(<BigRational as Zero>::zero))
}

/// [`compare_solution_with`] on the exact answers of `solver`, by the path
/// its data allow (a Solver built from doubles answers a double time on
/// the dyadic path, with no `BigRational` engine).
pub fn compare_solution_by(
    solver: &Solver,
    frames: &[Frame],
    options: &CompareOptions,
    progress: &dyn Progress,
) -> Result<Report, CompareFailure> {
    let scene = |e: crate::Error| CompareFailure::Scene {
        message: e.to_string(),
    };
    let radius = solver.radius().map_err(scene)?.clone();
    let n = solver.n().map_err(scene)?;
    let two_r = &radius + &radius;
    let contact_tol = options.contact_tol.length(&two_r);
    if contact_tol.is_negative() {
        return Err(CompareFailure::NegativeTolerance {
            what: "contact tolerance",
        });
    }
    if options.overlap_tol.is_negative() {
        return Err(CompareFailure::NegativeTolerance {
            what: "overlap tolerance",
        });
    }
    let tol = &options.overlap_tol;
    let speed = largest_speed(solver).map_err(scene)?;
    progress.stage("compare", Some(frames.len() as u64));
    let mut reports = Vec::with_capacity(frames.len());
    for f in frames {
        if progress.cancelled() {
            return Err(CompareFailure::Interrupted);
        }
        let fail = |error: CompareError| CompareFailure::Frame {
            line: f.line,
            t: f.t.clone(),
            error,
        };
        let state = solver
            .state_with_progress(&f.t, progress)
            .map_err(|e| {
                fail(CompareError::Exact {
                    message: e.to_string(),
                })
            })?
            .into_state();
        let x = &f.positions;
        let gaps = candidate_gaps(x, &two_r);
        let comparison =
            compare_with_gaps(&f.candidate(), &state, &gaps, &contact_tol).map_err(fail)?;
        // λ ≥ 0 (eq:dyn-micro): the largest is the largest |λ|.
        debug_assert!(state.multipliers.iter().all(|l| !l.is_negative()));
        let lambda_scale = largest(&state.multipliers)
            .cloned()
            .unwrap_or_else(<BigRational as Zero>::zero);
        let tolerances = Tolerances {
            length: tol * &two_r,
            velocity: tol * &speed,
            multiplier: tol * lambda_scale,
        };
        let mut columns = vec![(x.as_slice(), state.positions.as_slice())];
        if let Some(u) = &f.velocities {
            columns.push((u.as_slice(), state.velocities.as_slice()));
        }
        if let Some(l) = &f.multipliers {
            columns.push((l.as_slice(), state.multipliers.as_slice()));
        }
        let contacts_right = f.contacts.is_none()
            || (comparison.missed_contacts == 0 && comparison.spurious_contacts == 0);
        let representation = Representation::of(&columns, contacts_right);
        let verdict = verdict::judge(
            &comparison,
            &gaps,
            f.multipliers.as_deref(),
            &tolerances,
            representation,
        );
        debug_assert_eq!(verdict == Verdict::Exact, comparison.is_exact());
        reports.push(FrameReport {
            line: f.line,
            comparison,
            tolerances,
            verdict,
        });
        progress.advance(1);
    }
    progress.finish();
    let verdict = reports
        .iter()
        .map(|r| r.verdict)
        .max()
        .unwrap_or(Verdict::Exact);
    Ok(Report {
        scene: None,
        solution: None,
        n,
        radius,
        options: options.clone(),
        contact_tol,
        frames: reports,
        verdict,
    })
}
