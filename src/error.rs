//! The crate's error type: everything a user can get wrong, each with a
//! message that names the field and, for constraint violations, the first
//! offending pair. Library code reports these; it never panics on user input.
//!
//! Particle and block indices in messages count from 0, like the field paths
//! (`particles.positions[2]`, `macro.blocks[1]`) and every program output
//! (issue 28: one index convention); the paper's `x_1 … x_N` is `positions[0]`
//! … `positions[N-1]`.

use std::fmt;

use crate::rational::NumberError;

/// An error in a scene, in initial data, or in a request.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum Error {
    /// The scene file could not be read.
    Io {
        /// What the operating system said.
        message: String,
    },
    /// The scene is not valid TOML.
    Toml {
        /// The TOML parser's message (with line and column).
        message: String,
    },
    /// A required field is absent.
    MissingField {
        /// Dotted path of the field, e.g. `particles.positions`.
        field: String,
    },
    /// A field the format does not know (likely a typo).
    UnknownField {
        /// Dotted path of the field.
        field: String,
    },
    /// A field has the wrong TOML type.
    WrongType {
        /// Dotted path of the field.
        field: String,
        /// What was expected there.
        expected: &'static str,
    },
    /// A TOML float where an exact number is required: it would be rounded.
    Float {
        /// Dotted path of the field.
        field: String,
        /// The float as TOML read it.
        value: String,
    },
    /// A string that is not an exact number.
    Number {
        /// Dotted path of the field.
        field: String,
        /// The offending text.
        text: String,
        /// Why it was refused.
        reason: NumberError,
    },
    /// A scene must have exactly one of `[particles]` and `[macro]`.
    SceneKind {
        /// What was found.
        message: String,
    },
    /// `positions` and `velocities` differ in length.
    LengthMismatch {
        /// Number of positions.
        positions: usize,
        /// Number of velocities.
        velocities: usize,
    },
    /// N = 0: a scene needs at least one particle.
    NoParticles,
    /// The radius must be positive.
    NonPositiveRadius {
        /// The radius given.
        radius: String,
    },
    /// Two consecutive particles overlap: `x_{i+1} - x_i < 2r` (`df:KN`).
    Overlap {
        /// Index of the left particle, from 0.
        i: usize,
        /// The gap `x_{i+1} - x_i`.
        gap: String,
        /// `2r`.
        two_r: String,
    },
    /// Two particles in contact approach each other: `u⁰` is outside the
    /// velocity cone `C_{x⁰}` (`def:velcone`).
    Approaching {
        /// Index of the left particle, from 0.
        i: usize,
        /// Velocity of the left particle.
        left: String,
        /// Velocity of the right particle.
        right: String,
    },
    /// A `[macro]` block has a density outside `(0, 1]`.
    Density {
        /// Index of the block in `macro.blocks`, from 0.
        block: usize,
        /// The density given.
        density: String,
    },
    /// The `[macro]` blocks do not carry total mass exactly 1 (`thm:main`).
    Mass {
        /// The total mass found.
        mass: String,
    },
    /// `[macro]` blocks that are empty, unsorted or overlapping, or a velocity
    /// not allowed on a block.
    Block {
        /// Index of the block in `macro.blocks`, from 0.
        block: usize,
        /// What is wrong with it.
        reason: String,
    },
    /// The column file a `[particles]` table names (`data = "…"`) cannot be
    /// read or holds a bad value (the message gives its line and column, or
    /// its byte offset).
    DataFile {
        /// The file name as the scene gives it.
        file: String,
        /// What is wrong, and where in the file.
        message: String,
    },
    /// A requested time is negative.
    NegativeTime {
        /// The time given.
        t: String,
    },
    /// A request the engine cannot serve (for example a scalar type that
    /// cannot hold the data).
    Unsupported {
        /// What was asked.
        message: String,
    },
    /// The exact answer would need more machine work than the cap (the
    /// environment variable `STICKY_MAX_WORK` raises it).
    WorkLimit {
        /// The estimated work, in word operations.
        work: u64,
        /// The cap, in word operations.
        cap: u64,
        /// The whole explanation (engine, N, denominators, how to go on).
        message: String,
    },
    /// The run would need more memory than its limit (the environment
    /// variable `STICKY_MAX_MEMORY`, in MiB, sets it; by default three
    /// quarters of the machine's memory).
    Memory {
        /// The projected peak, in bytes.
        need: u64,
        /// The limit, in bytes.
        limit: u64,
        /// The whole explanation (the projection, how to go on).
        message: String,
    },
    /// Long work stopped early because its watcher asked it to (Ctrl-C:
    /// [`crate::progress::Progress::cancelled`]); there is no answer.
    Interrupted {
        /// The work that was stopped (`the projection`, `the event merge`).
        during: &'static str,
    },
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Io { message } => write!(f, "cannot read the scene: {message}"),
            Error::Toml { message } => write!(f, "not valid TOML: {}", message.trim_end()),
            Error::MissingField { field } => write!(f, "missing field `{field}`"),
            Error::UnknownField { field } => write!(f, "unknown field `{field}`"),
            Error::WrongType { field, expected } => {
                write!(f, "field `{field}` must be {expected}")
            }
            Error::Float { field, value } => write!(
                f,
                "field `{field}` is the TOML float {value}, which would be rounded: write it as a quoted exact number, e.g. \"{value}\" or a fraction \"p/q\""
            ),
            Error::Number { field, text, reason } => {
                write!(f, "field `{field}`: {text:?} is refused: {reason}")
            }
            Error::SceneKind { message } => write!(f, "{message}"),
            Error::LengthMismatch {
                positions,
                velocities,
            } => write!(
                f,
                "length mismatch: {positions} positions but {velocities} velocities"
            ),
            Error::NoParticles => write!(f, "no particles: N must be at least 1"),
            Error::NonPositiveRadius { radius } => {
                write!(f, "radius must be positive, got {radius}")
            }
            Error::Overlap { i, gap, two_r } => write!(
                f,
                "positions[{i}] and positions[{}] overlap: gap {gap} < 2r = {two_r}",
                i + 1
            ),
            Error::Approaching { i, left, right } => write!(
                f,
                "particles {i} and {j} (indices from 0) are in contact and approach each other: velocities[{i}] = {left} > velocities[{j}] = {right} (u⁰ outside the velocity cone)",
                j = i + 1
            ),
            Error::Density { block, density } => write!(
                f,
                "macro.blocks[{block}]: density {density} is not in (0, 1]"
            ),
            Error::Mass { mass } => {
                write!(f, "macro blocks carry total mass {mass}, not 1")
            }
            Error::Block { block, reason } => write!(f, "macro.blocks[{block}]: {reason}"),
            Error::DataFile { file, message } => {
                write!(f, "particle data file {file}: {message}")
            }
            Error::NegativeTime { t } => write!(f, "time {t} is negative"),
            Error::Unsupported { message }
            | Error::WorkLimit { message, .. }
            | Error::Memory { message, .. } => {
                write!(f, "{message}")
            }
            Error::Interrupted { during } => write!(f, "interrupted during {during}"),
        }
    }
}

impl std::error::Error for Error {}
