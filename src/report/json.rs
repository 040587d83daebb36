//! The machine-readable output of DESIGN.md §3 — the interop contract.
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
//! `sticky events --json` prints
//! `{"events": [{"t": "...", "first": i, "size": k, "parts": [a, b, ...]}, ...]}`,
//! one entry per cluster formed by a collision, sorted by time then `first`.
//!
//! The writer is hand-made and tiny: the values are numbers-as-strings and
//! integers, so no escaping beyond what [`string`] does is needed, and the
//! key order is the documented one.

use crate::cluster::Cluster;
use crate::contact::Impulse;
use crate::scalar::Scalar;
use crate::state::State;

pub use crate::text::string;

/// A JSON array of numbers-as-strings.
pub fn number_array<S: Scalar>(v: &[S]) -> String {
    let items: Vec<String> = v.iter().map(|x| string(&x.render())).collect();
    format!("[{}]", items.join(", "))
}

/// `[[first, size], …]`.
pub fn cluster_array(clusters: &[Cluster]) -> String {
    let items: Vec<String> = clusters
        .iter()
        .map(|c| format!("[{}, {}]", c.first, c.size))
        .collect();
    format!("[{}]", items.join(", "))
}

/// One state as the contract's JSON object (one line).
pub fn state<S: Scalar>(s: &State<S>, radius: &S) -> String {
    format!(
        "{{\"n\": {}, \"radius\": {}, \"t\": {}, \"positions\": {}, \"velocities\": {}, \"multipliers\": {}, \"clusters\": {}}}",
        s.positions.len(),
        string(&radius.render()),
        string(&s.t.render()),
        number_array(&s.positions),
        number_array(&s.velocities),
        number_array(&s.multipliers),
        cluster_array(&s.clusters),
    )
}

/// [`state`] written straight from the streaming path's blocks
/// ([`crate::fast::stream`]), value by value, with no string per value:
/// the same bytes (the tests compare them), and a final newline.
pub fn write_lean_state(
    out: &mut impl std::io::Write,
    b: &crate::fast::stream::LeanBlocks<'_>,
    radius: &num_rational::BigRational,
) -> std::io::Result<()> {
    write!(
        out,
        "{{\"n\": {}, \"radius\": {}, \"t\": {}, \"positions\": [",
        b.n(),
        string(&radius.render()),
        string(&b.t().render()),
    )?;
    fn item<W: std::io::Write>(
        out: &mut W,
        first: &mut bool,
        v: &crate::fast::stream::Exact,
    ) -> std::io::Result<()> {
        out.write_all(if *first { b"\"" } else { b", \"" })?;
        *first = false;
        v.write(out)?;
        out.write_all(b"\"")
    }
    let mut first = true;
    b.positions(|v| item(out, &mut first, v))?;
    out.write_all(b"], \"velocities\": [")?;
    first = true;
    b.velocities(|v| item(out, &mut first, v))?;
    out.write_all(b"], \"multipliers\": [")?;
    first = true;
    b.multipliers(|v| item(out, &mut first, v))?;
    writeln!(out, "], \"clusters\": {}}}", cluster_array(&b.clusters()))
}

/// [`events`] written straight from the streaming path's history
/// ([`crate::fast::merge::WordHistory`]), event by event: the same bytes,
/// and a final newline.
pub fn write_word_events(
    out: &mut impl std::io::Write,
    h: &crate::fast::merge::WordHistory,
) -> std::io::Result<()> {
    out.write_all(b"{\"events\": [")?;
    let mut first_event = true;
    h.for_each_event(|t, first, size, parts| {
        out.write_all(if first_event {
            b"{\"t\": \""
        } else {
            b", {\"t\": \""
        })?;
        first_event = false;
        t.write(out)?;
        write!(
            out,
            "\", \"first\": {first}, \"size\": {size}, \"parts\": ["
        )?;
        for (k, p) in parts.iter().enumerate() {
            if k > 0 {
                out.write_all(b", ")?;
            }
            write!(out, "{p}")?;
        }
        out.write_all(b"]}")
    })?;
    out.write_all(b"]}\n")
}

/// The collision history as `{"events": [...]}` (one line).
pub fn events<S: Scalar>(impulses: &[Impulse<S>]) -> String {
    let items: Vec<String> = impulses
        .iter()
        .map(|i| {
            let parts: Vec<String> = i.parts.iter().map(|p| p.size.to_string()).collect();
            format!(
                "{{\"t\": {}, \"first\": {}, \"size\": {}, \"parts\": [{}]}}",
                string(&i.t.render()),
                i.cluster.first,
                i.cluster.size,
                parts.join(", ")
            )
        })
        .collect();
    format!("{{\"events\": [{}]}}", items.join(", "))
}

/// `sticky run --model continuum --json`: the continuum solution of a
/// `[macro]` scene at one time (an extension of the contract, marked by its
/// `"model"` key):
/// `{"model": "continuum", "t": "...", "segments": [{"w0", "w1", "block",
/// "plateau", "x": [c0, c1], "u": [c0, c1], "lambda": [c0, c1, c2]}, ...],
/// "plateaus": [{"w0", "w1", "level", "velocity"}, ...]}` — `X(t, w) = c0 +
/// c1 w` on `[w0, w1]` in the mass variable `w`, and so on. Every number is
/// a string: a rational in lowest terms, or a quadratic surd `"a + b·√d"`
/// where the plateau ends are irrational (see `limit::surd`).
pub fn continuum_profile(p: &crate::limit::continuum::Profile<crate::limit::surd::Surd>) -> String {
    let s = |v: &crate::limit::surd::Surd| string(&v.to_string());
    let arr = |v: &[crate::limit::surd::Surd]| {
        format!("[{}]", v.iter().map(s).collect::<Vec<_>>().join(", "))
    };
    let segments: Vec<String> = p
        .segments
        .iter()
        .map(|g| {
            format!(
                "{{\"w0\": {}, \"w1\": {}, \"block\": {}, \"plateau\": {}, \"x\": {}, \"u\": {}, \"lambda\": {}}}",
                s(&g.w0),
                s(&g.w1),
                g.block,
                g.plateau.map_or("null".into(), |k| k.to_string()),
                arr(&g.x),
                arr(&g.u),
                arr(&g.lambda)
            )
        })
        .collect();
    let plateaus: Vec<String> = p
        .plateaus
        .iter()
        .map(|q| {
            format!(
                "{{\"w0\": {}, \"w1\": {}, \"level\": {}, \"velocity\": {}}}",
                s(&q.w0),
                s(&q.w1),
                s(&q.level),
                s(&q.velocity)
            )
        })
        .collect();
    format!(
        "{{\"model\": \"continuum\", \"t\": {}, \"segments\": [{}], \"plateaus\": [{}]}}",
        string(&crate::rational::render_exact(&p.t)),
        segments.join(", "),
        plateaus.join(", ")
    )
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
