//! The report for scripts (feature `json`): one JSON object, every figure
//! both as an exact string (`"position_max": {"value": "1/1000", …}`) and,
//! beside it, the nearest double as a JSON number (`"value_f64": 0.001`),
//! correctly rounded from the exact value by [`decimal`](super::decimal).
//! A double that would be infinite is `null`, and a line of `notes` says
//! which. Indices are from 0 (`"index_base": 0`).
//!
//! The shape is typed here (serde), so the keys cannot drift between the
//! command line and the Python package, which both print this.

use num_rational::BigRational;
use serde::Serialize;

use super::decimal::{nearest_f64, Value};
use super::text::exact_root;
use super::{FrameReport, Report};
use crate::cluster::Cluster;
use crate::reference::measure::MaxError;
use crate::scalar::Scalar;

/// The JSON object of a [`Report`].
#[derive(Debug, Clone, Serialize)]
#[cfg_attr(test, derive(schemars::JsonSchema))]
#[cfg_attr(test, schemars(rename = "Compare"))]
pub struct ReportJson {
    /// The scene's file, if named.
    pub scene: Option<String>,
    /// The solution's file, if named.
    pub solution: Option<String>,
    /// `N`.
    pub n: usize,
    /// Indices of particles and pairs start here: always `0`.
    pub index_base: usize,
    /// `r`, exact.
    pub radius: String,
    /// `r`, nearest double.
    pub radius_f64: Option<f64>,
    /// The contact tolerance as a length, exact.
    pub contact_tol: String,
    /// The rounding tolerance `TOL` (relative), exact.
    pub overlap_tol: String,
    /// One object per time.
    pub times: Vec<FrameJson>,
    /// `exact`, `rounding`, `inexact` or `invalid`.
    pub verdict: &'static str,
    /// The verdict line of the text report.
    pub summary: String,
    /// Doubles that are `null` and why (empty when none).
    pub notes: Vec<String>,
}

/// An exact `max_i |a_i − b_i|` and where.
#[derive(Debug, Clone, Serialize)]
#[cfg_attr(test, derive(schemars::JsonSchema))]
#[cfg_attr(test, schemars(rename = "Max"))]
pub struct MaxJson {
    /// Exact.
    pub value: String,
    /// Nearest double.
    pub value_f64: Option<f64>,
    /// The first index reaching it (from 0).
    pub index: usize,
}

/// An overlapping pair.
#[derive(Debug, Clone, Serialize)]
#[cfg_attr(test, derive(schemars::JsonSchema))]
#[cfg_attr(test, schemars(rename = "Overlap"))]
pub struct OverlapJson {
    /// The pair `(pair, pair + 1)`, from 0.
    pub pair: usize,
    /// `2r − (x_{pair+1} − x_pair)`, exact.
    pub depth: String,
    /// Nearest double.
    pub depth_f64: Option<f64>,
    /// `depth / 2r`, exact.
    pub depth_relative: String,
    /// Nearest double.
    pub depth_relative_f64: Option<f64>,
    /// `depth ≤ TOL · 2r`.
    pub within_tolerance: bool,
}

/// A value attached to a pair.
#[derive(Debug, Clone, Serialize)]
#[cfg_attr(test, derive(schemars::JsonSchema))]
#[cfg_attr(test, schemars(rename = "PairValue"))]
pub struct PairJson {
    /// The pair `(pair, pair + 1)`, from 0.
    pub pair: usize,
    /// Exact.
    pub value: String,
    /// Nearest double.
    pub value_f64: Option<f64>,
}

/// One time.
#[derive(Debug, Clone, Serialize)]
#[cfg_attr(test, derive(schemars::JsonSchema))]
#[cfg_attr(test, schemars(rename = "Frame"))]
pub struct FrameJson {
    /// The time, exact.
    pub t: String,
    /// Nearest double.
    pub t_f64: Option<f64>,
    /// Its line in the solution file (0: not from a file).
    pub line: usize,
    /// Max position error.
    pub position_max: MaxJson,
    /// `(1/N) Σ e_i²`, exact.
    pub position_l2_squared: String,
    /// Nearest double.
    pub position_l2_squared_f64: Option<f64>,
    /// The `L²` error exact when it is rational, else `null`.
    pub position_l2: Option<String>,
    /// The `L²` error, the double nearest to the exact root.
    pub position_l2_f64: Option<f64>,
    /// Max velocity error (`null`: no velocities given).
    pub velocity_max: Option<MaxJson>,
    /// As for positions.
    pub velocity_l2_squared: Option<String>,
    /// Nearest double.
    pub velocity_l2_squared_f64: Option<f64>,
    /// As for positions.
    pub velocity_l2: Option<String>,
    /// Nearest double of the exact root.
    pub velocity_l2_f64: Option<f64>,
    /// Max `λ` error (`null`: no multipliers given).
    pub multiplier_max: Option<MaxJson>,
    /// Every overlapping pair.
    pub overlaps: Vec<OverlapJson>,
    /// Pairs in contact in the exact answer, not in the solver's.
    pub missed_contacts: usize,
    /// Pairs in contact in the solver's answer, not in the exact one.
    pub spurious_contacts: usize,
    /// Exact clusters `[first, size]` the solver does not have.
    pub missed_clusters: Vec<[usize; 2]>,
    /// The solver's clusters the exact answer does not have.
    pub spurious_clusters: Vec<[usize; 2]>,
    /// Pairs with `λ < 0`.
    pub negative_multipliers: Vec<PairJson>,
    /// Pairs with `λ·(gap − 2r) ≠ 0`, the product.
    pub complementarity: Vec<PairJson>,
    /// `i` for each pair `(i − 1, i)` breaking `prop:Oleinik` (`null`: not
    /// checked).
    pub oleinik: Option<Vec<usize>>,
    /// Every figure `0`.
    pub exact: bool,
    /// This time's verdict.
    pub verdict: &'static str,
}

/// Collects the `notes` while the doubles are made.
struct Doubles {
    notes: Vec<String>,
}

impl Doubles {
    fn of(&mut self, v: Value<'_>, what: impl FnOnce() -> String) -> Option<f64> {
        let d = nearest_f64(v);
        if d.is_none() {
            self.notes.push(format!(
                "{} is beyond the range of a double: its _f64 is null",
                what()
            ));
        }
        d
    }

    fn q(&mut self, q: &BigRational, what: impl FnOnce() -> String) -> Option<f64> {
        self.of(Value::Rational(q), what)
    }

    fn max(&mut self, m: &MaxError, what: impl FnOnce() -> String) -> MaxJson {
        MaxJson {
            value: m.value.render(),
            value_f64: self.q(&m.value, what),
            index: m.index,
        }
    }

    fn pairs(
        &mut self,
        items: &[crate::reference::measure::PairValue],
        what: impl Fn(usize) -> String,
    ) -> Vec<PairJson> {
        items
            .iter()
            .map(|p| PairJson {
                pair: p.pair,
                value: p.value.render(),
                value_f64: self.q(&p.value, || what(p.pair)),
            })
            .collect()
    }
}

fn clusters(items: &[Cluster]) -> Vec<[usize; 2]> {
    items.iter().map(|k| [k.first, k.size]).collect()
}

fn frame(d: &mut Doubles, f: &FrameReport, two_r: &BigRational) -> FrameJson {
    let c = &f.comparison;
    let at = c.t.render();
    let name = |k: &str| format!("t = {at}: {k}");
    FrameJson {
        t: c.t.render(),
        t_f64: d.q(&c.t, || name("t")),
        line: f.line,
        position_max: d.max(&c.position_max, || name("position_max")),
        position_l2_squared: c.position_l2_squared.render(),
        position_l2_squared_f64: d.q(&c.position_l2_squared, || name("position_l2_squared")),
        position_l2: exact_root(&c.position_l2_squared).map(|r| r.render()),
        position_l2_f64: d.of(Value::SquareRoot(&c.position_l2_squared), || {
            name("position_l2")
        }),
        velocity_max: c
            .velocity_max
            .as_ref()
            .map(|m| d.max(m, || name("velocity_max"))),
        velocity_l2_squared: c.velocity_l2_squared.as_ref().map(Scalar::render),
        velocity_l2_squared_f64: c
            .velocity_l2_squared
            .as_ref()
            .and_then(|s| d.q(s, || name("velocity_l2_squared"))),
        velocity_l2: c
            .velocity_l2_squared
            .as_ref()
            .and_then(exact_root)
            .map(|r| r.render()),
        velocity_l2_f64: c
            .velocity_l2_squared
            .as_ref()
            .and_then(|s| d.of(Value::SquareRoot(s), || name("velocity_l2"))),
        multiplier_max: c
            .multiplier_max
            .as_ref()
            .map(|m| d.max(m, || name("multiplier_max"))),
        overlaps: c
            .overlaps
            .iter()
            .map(|o| {
                let rel = crate::reduced::quotient(&o.depth, two_r);
                OverlapJson {
                    pair: o.pair,
                    depth: o.depth.render(),
                    depth_f64: d.q(&o.depth, || name(&format!("overlaps pair {}", o.pair))),
                    depth_relative: rel.render(),
                    depth_relative_f64: d
                        .q(&rel, || name(&format!("overlaps pair {} relative", o.pair))),
                    within_tolerance: o.depth <= f.tolerances.length,
                }
            })
            .collect(),
        missed_contacts: c.missed_contacts,
        spurious_contacts: c.spurious_contacts,
        missed_clusters: clusters(&c.missed_clusters),
        spurious_clusters: clusters(&c.spurious_clusters),
        negative_multipliers: d.pairs(&c.negative_multipliers, |p| {
            name(&format!("negative_multipliers pair {p}"))
        }),
        complementarity: d.pairs(&c.complementarity, |p| {
            name(&format!("complementarity pair {p}"))
        }),
        oleinik: c.oleinik.clone(),
        exact: c.is_exact(),
        verdict: f.verdict.name(),
    }
}

impl Report {
    /// The typed JSON object of this report.
    pub fn to_json_value(&self) -> ReportJson {
        let two_r = self.two_r();
        let mut d = Doubles { notes: Vec::new() };
        let times = self
            .frames
            .iter()
            .map(|f| frame(&mut d, f, &two_r))
            .collect();
        let radius_f64 = d.q(&self.radius, || "radius".into());
        ReportJson {
            scene: self.scene.clone(),
            solution: self.solution.clone(),
            n: self.n,
            index_base: 0,
            radius: self.radius.render(),
            radius_f64,
            contact_tol: self.contact_tol.render(),
            overlap_tol: self.options.overlap_tol.render(),
            times,
            verdict: self.verdict.name(),
            summary: self.summary(),
            notes: d.notes,
        }
    }

    /// The report as one line of JSON.
    pub fn json(&self) -> String {
        // Serializing plain strings, numbers and options cannot fail.
        serde_json::to_string(&self.to_json_value()).unwrap_or_default()
    }
}
