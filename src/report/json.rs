//! The machine-readable output of docs/guide/json.md — the interop contract —
//! as serde types, printed by [`crate::json`] in the contract's spelling:
//!
//! ```json
//! {"n": 4, "radius": "1/8", "t": "3/2", "positions": ["-1/4", "0", "1/4", "1/2"], "velocities": ["0", "0", "0", "0"], "multipliers": ["1/4", "1/2", "1/4"], "clusters": [[0, 4]]}
//! ```
//!
//! * every rational is a string in lowest terms, `"p/q"` or `"p"`;
//! * `velocities` are right derivatives (post-collision);
//! * `multipliers` are `λ_1 … λ_{N−1}` of `eq:dyn-micro`;
//! * `clusters` lists the contact clusters of `x(t)` as
//!   `[first index (0-based), size]`, left to right.
//!
//! `sticky events --json` prints [`EventsJson`]:
//! `{"events": [{"t": "...", "first": i, "size": k, "parts": [a, b, ...]}, ...]}`,
//! one entry per cluster formed by a collision, sorted by time then `first`.
//!
//! The streaming path ([`crate::fast::stream`]) fills the same types with
//! columns that are computed while they are written ([`write_lean_state`],
//! [`write_word_events`]): one set of keys, the same bytes.

use std::io;

use serde::ser::{Error as _, SerializeSeq};
use serde::{Serialize, Serializer};

use crate::cluster::Cluster;
use crate::contact::Impulse;
use crate::fast::merge::WordHistory;
use crate::fast::stream::{Exact, LeanBlocks, Piece};
use crate::json::{Displayed, Elements, Rational};
use crate::limit::continuum::Profile;
use crate::limit::surd::Surd;
use crate::scalar::Scalar;
use crate::state::State;

pub use crate::text::string;

/// `sticky run --json`: the state at one time (one line per time).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(test, derive(schemars::JsonSchema))]
#[cfg_attr(test, schemars(rename = "State"))]
pub struct StateJson<C = Vec<Rational>> {
    /// The number of particles N.
    pub n: usize,
    /// The radius `r`.
    pub radius: Rational,
    /// The time `t`.
    pub t: Rational,
    /// `x(t)`, N values.
    pub positions: C,
    /// `u(t)`, the right derivative (after a collision at `t`), N values.
    pub velocities: C,
    /// `λ(t)` of `eq:dyn-micro`, N − 1 values: entry `i` is the force
    /// between particles `i` and `i + 1` (the paper's `λ_{i+1}`).
    pub multipliers: C,
    /// The contact clusters of `x(t)`, left to right, as `[first, size]`
    /// (indices from 0).
    pub clusters: Vec<[usize; 2]>,
}

/// `sticky events --json`: every cluster formed by a collision.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(test, derive(schemars::JsonSchema))]
#[cfg_attr(test, schemars(rename = "Events"))]
pub struct EventsJson<E = Vec<EventJson>> {
    /// Sorted by `t`, then `first`.
    pub events: E,
}

/// One cluster formed at a collision.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(test, derive(schemars::JsonSchema))]
#[cfg_attr(test, schemars(rename = "Event"))]
pub struct EventJson<T = Rational, P = Vec<usize>> {
    /// The collision time.
    pub t: T,
    /// The cluster's first particle (from 0).
    pub first: usize,
    /// Its number of particles: `first … first + size − 1`.
    pub size: usize,
    /// The sizes of the clusters that met there, left to right (two or
    /// more).
    pub parts: P,
}

/// The `[first, size]` pairs of the contract.
pub fn cluster_pairs(clusters: &[Cluster]) -> Vec<[usize; 2]> {
    clusters.iter().map(|c| [c.first, c.size]).collect()
}

impl StateJson {
    /// The contract object of `s` (radius `radius`).
    pub fn of<S: Scalar>(s: &State<S>, radius: &S) -> StateJson {
        let column = |v: &[S]| v.iter().map(Rational::of).collect();
        StateJson {
            n: s.positions.len(),
            radius: Rational::of(radius),
            t: Rational::of(&s.t),
            positions: column(&s.positions),
            velocities: column(&s.velocities),
            multipliers: column(&s.multipliers),
            clusters: cluster_pairs(&s.clusters),
        }
    }
}

impl EventsJson {
    /// The contract object of a collision history.
    pub fn of<S: Scalar>(impulses: &[Impulse<S>]) -> EventsJson {
        let events = impulses
            .iter()
            .map(|i| EventJson {
                t: Rational::of(&i.t),
                first: i.cluster.first,
                size: i.cluster.size,
                parts: i.parts.iter().map(|p| p.size).collect(),
            })
            .collect();
        EventsJson { events }
    }
}

/// One state as the contract's JSON object (one line).
pub fn state<S: Scalar>(s: &State<S>, radius: &S) -> String {
    crate::json::to_string(&StateJson::of(s, radius))
}

/// The collision history as `{"events": [...]}` (one line).
pub fn events<S: Scalar>(impulses: &[Impulse<S>]) -> String {
    crate::json::to_string(&EventsJson::of(impulses))
}

/// Which value of a [`LeanBlocks`] a [`LeanColumn`] walks.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Column {
    Positions,
    Velocities,
    Multipliers,
}

/// The particles of a piece of the blocks whose values are formatted
/// together on one thread ([`write_lean_state`]).
pub const PIECE_PARTICLES: usize = 1 << 14;

/// One column of the streaming path's state, serialised value by value as
/// the blocks give it: the blocks cut into pieces of `piece` particles,
/// each piece's values reduced and formatted on a worker thread
/// ([`crate::parallel::in_order`]), then written in order.
#[derive(Debug, Clone, Copy)]
pub struct LeanColumn<'a> {
    blocks: &'a LeanBlocks<'a>,
    column: Column,
    piece: usize,
}

/// The values of one piece of a column, formatted as the contract writes
/// array elements: `"v_1", "v_2", …` ([`Elements`]; empty for no value).
struct Formatted {
    text: String,
}

impl LeanColumn<'_> {
    /// The values of `piece` in this column, each formatted as `Exact`'s
    /// `Display` writes it ([`Exact::push_text`]: digits straight into one
    /// buffer per piece) between quotes, `", "` between two.
    fn format(&self, piece: &Piece) -> io::Result<Formatted> {
        // Room for the usual values (no growth copies): 16 bytes each.
        let mut text = Vec::with_capacity(16 * self.piece.min(PIECE_PARTICLES));
        let each = |v: &Exact| {
            if !text.is_empty() {
                text.extend_from_slice(b", ");
            }
            text.push(b'"');
            v.push_text(&mut text);
            text.push(b'"');
            Ok(())
        };
        match self.column {
            Column::Positions => self.blocks.positions_of(piece, each),
            Column::Velocities => self.blocks.velocities_of(piece, each),
            Column::Multipliers => self.blocks.multipliers_of(piece, each),
        }?;
        Ok(Formatted {
            text: String::from_utf8(text).map_err(io::Error::other)?,
        })
    }
}

impl Serialize for LeanColumn<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut seq = s.serialize_seq(None)?;
        let pieces = self.blocks.pieces(self.piece);
        let workers = crate::parallel::workers();
        crate::parallel::in_order(
            &pieces,
            workers,
            |piece| self.format(piece),
            |formatted| {
                let f = formatted.map_err(S::Error::custom)?;
                // A piece may hold no value (the last particle's multiplier).
                if f.text.is_empty() {
                    return Ok(());
                }
                seq.serialize_element(&Elements::new(&f.text))
            },
        )?;
        seq.end()
    }
}

/// [`state`] written straight from the streaming path's blocks
/// ([`crate::fast::stream`]), value by value, formatted on every core in
/// pieces of [`PIECE_PARTICLES`]: the same bytes (the tests compare them),
/// and a final newline.
pub fn write_lean_state(
    out: &mut impl io::Write,
    b: &LeanBlocks<'_>,
    radius: &num_rational::BigRational,
) -> io::Result<()> {
    write_lean_state_in_pieces(out, b, radius, PIECE_PARTICLES)
}

/// [`write_lean_state`] with pieces of at least `piece` particles (the
/// bytes do not depend on it; the tests take small pieces).
pub fn write_lean_state_in_pieces(
    out: &mut impl io::Write,
    b: &LeanBlocks<'_>,
    radius: &num_rational::BigRational,
    piece: usize,
) -> io::Result<()> {
    let column = |column| LeanColumn {
        blocks: b,
        column,
        piece,
    };
    let state = StateJson {
        n: b.n(),
        radius: Rational::of(radius),
        t: Rational::of(b.t()),
        positions: column(Column::Positions),
        velocities: column(Column::Velocities),
        multipliers: column(Column::Multipliers),
        clusters: cluster_pairs(&b.clusters()),
    };
    crate::json::to_writer(&mut *out, &state)?;
    out.write_all(b"\n")
}

/// The events of a [`WordHistory`], serialised one by one as it gives them.
#[derive(Debug, Clone, Copy)]
pub struct WordEvents<'a>(pub &'a WordHistory);

impl Serialize for WordEvents<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut seq = s.serialize_seq(None)?;
        let mut failure = None;
        let walked = self.0.for_each_event(|t, first, size, parts| {
            let event = EventJson {
                t: Displayed(t),
                first,
                size,
                parts,
            };
            seq.serialize_element(&event).map_err(|e| {
                failure = Some(e);
                io::Error::other("stopped by the serializer")
            })
        });
        if let Some(e) = failure {
            return Err(e);
        }
        walked.map_err(S::Error::custom)?;
        seq.end()
    }
}

/// [`events`] written straight from the streaming path's history
/// ([`crate::fast::merge::WordHistory`]), event by event: the same bytes,
/// and a final newline.
pub fn write_word_events(out: &mut impl io::Write, h: &WordHistory) -> io::Result<()> {
    crate::json::to_writer(
        &mut *out,
        &EventsJson {
            events: WordEvents(h),
        },
    )?;
    out.write_all(b"\n")
}

/// `sticky run --model continuum --json`: the continuum solution of a
/// `[macro]` scene at one time (an extension of the contract, marked by
/// its `"model"` key). Every number is a string: a rational in lowest
/// terms, or a quadratic surd `"a + b·√d"` where the plateau ends are
/// irrational (see `limit::surd`).
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(test, derive(schemars::JsonSchema))]
#[cfg_attr(test, schemars(rename = "Continuum"))]
pub struct ContinuumJson {
    /// Always `"continuum"`: tells this object from a particle state.
    pub model: ModelTag,
    /// The time.
    pub t: Rational,
    /// The pieces of the solution in the mass variable `w`, left to right.
    pub segments: Vec<SegmentJson>,
    /// The congested zones (plateaus of the density).
    pub plateaus: Vec<PlateauJson>,
}

/// The `"model"` key of [`ContinuumJson`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[cfg_attr(test, derive(schemars::JsonSchema))]
pub enum ModelTag {
    /// The continuum model.
    #[serde(rename = "continuum")]
    Continuum,
}

/// On `[w0, w1]`: `X(t, w) = x[0] + x[1]·w`, `U` likewise, `Λ` a quadratic.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(test, derive(schemars::JsonSchema))]
#[cfg_attr(test, schemars(rename = "Segment"))]
pub struct SegmentJson {
    /// Left end in `w` (a rational or a quadratic surd).
    pub w0: String,
    /// Right end in `w`.
    pub w1: String,
    /// The block of the initial data it comes from (from 0).
    pub block: usize,
    /// The plateau it lies in (from 0), `null` outside the congested zones.
    pub plateau: Option<usize>,
    /// `X`'s coefficients `[c0, c1]`.
    pub x: [String; 2],
    /// `U`'s coefficients `[c0, c1]`.
    pub u: [String; 2],
    /// `Λ`'s coefficients `[c0, c1, c2]`.
    pub lambda: [String; 3],
}

/// A congested zone.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[cfg_attr(test, derive(schemars::JsonSchema))]
#[cfg_attr(test, schemars(rename = "Plateau"))]
pub struct PlateauJson {
    /// Left end in `w`.
    pub w0: String,
    /// Right end in `w`.
    pub w1: String,
    /// The density level.
    pub level: String,
    /// The common velocity.
    pub velocity: String,
}

impl ContinuumJson {
    /// The contract object of a continuum profile.
    pub fn of(p: &Profile<Surd>) -> ContinuumJson {
        let s = |v: &Surd| v.to_string();
        ContinuumJson {
            model: ModelTag::Continuum,
            t: Rational(crate::rational::render_exact(&p.t)),
            segments: p
                .segments
                .iter()
                .map(|g| SegmentJson {
                    w0: s(&g.w0),
                    w1: s(&g.w1),
                    block: g.block,
                    plateau: g.plateau,
                    x: g.x.each_ref().map(s),
                    u: g.u.each_ref().map(s),
                    lambda: g.lambda.each_ref().map(s),
                })
                .collect(),
            plateaus: p
                .plateaus
                .iter()
                .map(|q| PlateauJson {
                    w0: s(&q.w0),
                    w1: s(&q.w1),
                    level: s(&q.level),
                    velocity: s(&q.velocity),
                })
                .collect(),
        }
    }
}

/// [`ContinuumJson`] as one line.
pub fn continuum_profile(p: &Profile<Surd>) -> String {
    crate::json::to_string(&ContinuumJson::of(p))
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_rational::BigRational;

    #[test]
    fn design_example_verbatim() {
        let q = |n: i64, d: i64| BigRational::from_i64(n) / BigRational::from_i64(d);
        let s = State {
            t: q(3, 2),
            positions: vec![q(-1, 4), q(0, 1), q(1, 4), q(1, 2)],
            velocities: vec![q(0, 1); 4],
            multipliers: vec![q(1, 4), q(1, 2), q(1, 4)],
            clusters: vec![Cluster { first: 0, size: 4 }],
        };
        assert_eq!(
            state(&s, &q(1, 8)),
            r#"{"n": 4, "radius": "1/8", "t": "3/2", "positions": ["-1/4", "0", "1/4", "1/2"], "velocities": ["0", "0", "0", "0"], "multipliers": ["1/4", "1/2", "1/4"], "clusters": [[0, 4]]}"#
        );
        assert_eq!(events::<BigRational>(&[]), r#"{"events": []}"#);
    }

    #[test]
    fn strings_are_escaped() {
        assert_eq!(string("a\"b\\c\n\u{1}"), r#""a\"b\\c\n\u0001""#);
    }
}
