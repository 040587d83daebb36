//! Where methods fail: the failure kinds of the stability section, their
//! thresholds, and the classification of one measured row.

use std::fmt;

use crate::report::plot::Rgb;

use super::solve::{Row, Status};

/// An overlap deeper than this fraction of the contact length `2r` counts
/// as [`Failure::Overlap`] (a millionth of a diameter; shallower ones are
/// mostly the rounding of touching particles, `ε·X` with `X` the size of
/// the coordinates; the CSV has every depth).
pub const OVERLAP_TOLERANCE: f64 = 1e-6;

/// `λ` or a pressure jump below `−SIGN_TOLERANCE · V` (`V = max |u⁰|`)
/// counts as negative.
pub const SIGN_TOLERANCE: f64 = 1e-12;

/// A position error above this fraction of `2r` counts as
/// [`Failure::LargeError`].
pub const LARGE_ERROR: f64 = 0.1;

/// A velocity error above this fraction of `V` counts as
/// [`Failure::WrongVelocities`].
pub const VELOCITY_TOLERANCE: f64 = 1e-6;

/// What went wrong for one (scene, method) of the stability section.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub enum Failure {
    /// The solver refused or failed (too many steps, NaN, …): its message.
    Refused(String),
    /// An inner iterative solve stopped at its iteration cap.
    NoConvergence {
        /// How many inner solves did not converge.
        unconverged: usize,
    },
    /// Particles overlap (`df:KN` violated) by more than
    /// [`OVERLAP_TOLERANCE`]`·2r`.
    Overlap {
        /// The deepest overlap, in units of `2r`.
        depth: f64,
    },
    /// The contact set at `t` differs from the exact `Ω_{x(t)}`
    /// (`df:Omega-micro`): collisions missed (exact contacts not reported)
    /// or spurious (reported contacts that do not exist).
    WrongClusters {
        /// Exact contacts the method misses.
        missed: usize,
        /// Contacts the method reports that are not exact contacts.
        spurious: usize,
    },
    /// Velocities off by more than [`VELOCITY_TOLERANCE`]`·V`: a collision
    /// missed, spurious or not yet resolved changes the post-collision
    /// velocity (`eq:proj-u-micro`).
    WrongVelocities {
        /// The velocity error, in units of `V`.
        error: f64,
    },
    /// A multiplier `λ_i < 0` (`eq:dyn-micro`).
    NegativeLambda {
        /// The smallest `λ`.
        min: f64,
    },
    /// A pressure jump `< 0` (`prop:micro-pressure`).
    NegativePressure {
        /// The smallest jump.
        min: f64,
    },
    /// Pairs violating `prop:Oleinik`.
    Oleinik {
        /// How many pairs.
        pairs: usize,
    },
    /// Position error above [`LARGE_ERROR`]`·2r`.
    LargeError {
        /// The position error, in units of `2r`.
        error: f64,
    },
}

impl Failure {
    /// The kind's short name (the legend of the stability chart).
    pub fn kind(&self) -> &'static str {
        match self {
            Failure::Refused(_) => "refused",
            Failure::NoConvergence { .. } => "no convergence",
            Failure::Overlap { .. } => "overlap",
            Failure::WrongClusters { .. } => "wrong clusters",
            Failure::WrongVelocities { .. } => "wrong velocities",
            Failure::NegativeLambda { .. } => "negative λ",
            Failure::NegativePressure { .. } => "negative p",
            Failure::Oleinik { .. } => "Oleinik violated",
            Failure::LargeError { .. } => "position error > 2r/10",
        }
    }

    pub(super) fn index(&self) -> usize {
        match self {
            Failure::Refused(_) => 0,
            Failure::NoConvergence { .. } => 1,
            Failure::Overlap { .. } => 2,
            Failure::WrongClusters { .. } => 3,
            Failure::WrongVelocities { .. } => 4,
            Failure::NegativeLambda { .. } => 5,
            Failure::NegativePressure { .. } => 6,
            Failure::Oleinik { .. } => 7,
            Failure::LargeError { .. } => 8,
        }
    }
}

impl fmt::Display for Failure {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Failure::Refused(m) => write!(f, "refused ({m})"),
            Failure::NoConvergence { unconverged } => {
                write!(f, "no convergence ({unconverged} solves at the cap)")
            }
            Failure::Overlap { depth } => write!(f, "overlap ({depth:.1e}·2r)"),
            Failure::WrongClusters { missed, spurious } => {
                write!(f, "wrong clusters ({missed} missed, {spurious} spurious)")
            }
            Failure::WrongVelocities { error } => write!(f, "wrong velocities ({error:.1e}·V)"),
            Failure::NegativeLambda { min } => write!(f, "negative λ ({min:.1e})"),
            Failure::NegativePressure { min } => write!(f, "negative p ({min:.1e})"),
            Failure::Oleinik { pairs } => write!(f, "Oleinik violated ({pairs} pairs)"),
            Failure::LargeError { error } => write!(f, "position error {error:.1e}·2r"),
        }
    }
}

/// Colours of the failure kinds (by [`Failure`] order) and of "OK".
pub(super) const FAILURE_COLORS: [Rgb; 9] = [
    Rgb(0, 0, 0),
    Rgb(148, 103, 189),
    Rgb(214, 39, 40),
    Rgb(255, 127, 14),
    Rgb(227, 119, 194),
    Rgb(140, 86, 75),
    Rgb(188, 189, 34),
    Rgb(23, 190, 207),
    Rgb(127, 127, 127),
];
pub(super) const FAILURE_NAMES: [&str; 9] = [
    "refused",
    "no convergence",
    "overlap",
    "wrong clusters",
    "wrong velocities",
    "negative λ",
    "negative p",
    "Oleinik violated",
    "position error > 2r/10",
];
pub(super) const OK_COLOR: Rgb = Rgb(44, 160, 44);

/// The failures of one stability row.
pub(super) fn classify(row: &Row) -> Vec<Failure> {
    let mut out = Vec::new();
    if let Status::Refused(m) = &row.status {
        out.push(Failure::Refused(m.clone()));
        return out;
    }
    if row.converged == Some(false) {
        out.push(Failure::NoConvergence {
            unconverged: row.work.map_or(0, |w| w.unconverged),
        });
    }
    let Some(e) = row.errors else {
        return out;
    };
    let v = row.v.max(f64::MIN_POSITIVE);
    if let Some(g) = e.min_gap {
        if g < -OVERLAP_TOLERANCE * row.two_r {
            out.push(Failure::Overlap {
                depth: -g / row.two_r,
            });
        }
    }
    if e.cluster_mismatch() > 0 {
        out.push(Failure::WrongClusters {
            missed: e.missed_contacts,
            spurious: e.spurious_contacts,
        });
    }
    if let Some(ve) = e.velocity {
        if ve > VELOCITY_TOLERANCE * v {
            out.push(Failure::WrongVelocities { error: ve / v });
        }
    }
    if let Some(m) = e.min_lambda {
        if m < -SIGN_TOLERANCE * v {
            out.push(Failure::NegativeLambda { min: m });
        }
    }
    if let Some(m) = e.min_pressure_jump {
        if m < -SIGN_TOLERANCE * v {
            out.push(Failure::NegativePressure { min: m });
        }
    }
    if let Some(k) = e.oleinik_violations {
        if k > 0 {
            out.push(Failure::Oleinik { pairs: k });
        }
    }
    if e.position > LARGE_ERROR * row.two_r {
        out.push(Failure::LargeError {
            error: e.position / row.two_r,
        });
    }
    out
}
