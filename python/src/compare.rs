//! `sticky.compare`: another solver's answer against the exact one — the
//! library's comparison ([`sticky::report::compare`], the one behind
//! `sticky compare`), every figure as an exact `Fraction` and a `float`.

use std::sync::Arc;

use num_rational::BigRational;
use pyo3::exceptions::PyAttributeError;
use pyo3::prelude::*;
use pyo3::types::{PyList, PyTuple};
use sticky::cluster::Cluster;
use sticky::reference::measure::{MaxError, PairValue};
use sticky::report::compare::decimal::{nearest_f64, Value};
use sticky::report::compare::{
    compare_solution_by, CompareFailure, CompareOptions, ContactTolerance, FrameReport, Report,
};
use sticky::report::solution::Frame;

use crate::convert::{self, Column};
use crate::errors;
use crate::interrupt;
use crate::report_lists::FrameLists;
use crate::scene::Scene;

/// The nearest double of `q` (None beyond the range of doubles).
fn float(q: &BigRational) -> Option<f64> {
    nearest_f64(Value::Rational(q))
}

/// The nearest double of `√q`.
fn root_float(q: &BigRational) -> Option<f64> {
    nearest_f64(Value::SquareRoot(q))
}

/// An optional column of numbers (exact, errors naming `name[i]`).
fn optional_column(
    obj: Option<&Bound<'_, PyAny>>,
    name: &str,
) -> PyResult<Option<Vec<BigRational>>> {
    obj.map(|o| convert::column(o, name).and_then(|c: Column| c.into_exact(name)))
        .transpose()
}

/// A solver's cluster: its first particle and its size.
#[derive(Debug, Clone, Copy)]
struct Given {
    first: usize,
    size: usize,
}

/// The solver's clusters: an iterable of `(first, size)` pairs of ints;
/// errors name `clusters[k]`.
fn given_clusters(obj: &Bound<'_, PyAny>) -> PyResult<Vec<Given>> {
    let py = obj.py();
    let wrong = |what: &str| {
        let message = format!("{what} must be a (first, size) pair of integers");
        errors::argument_type(py, what, message)
    };
    if obj.is_instance_of::<pyo3::types::PyString>() {
        return Err(wrong("clusters"));
    }
    let items = obj.try_iter().map_err(|_| wrong("clusters"))?;
    let mut out = Vec::new();
    for (k, item) in items.enumerate() {
        let what = convert::entry("clusters", k);
        let item = item?;
        let pair: Vec<Bound<'_, PyAny>> = match item.try_iter() {
            Ok(i) if !item.is_instance_of::<pyo3::types::PyString>() => {
                i.collect::<PyResult<_>>()?
            }
            _ => return Err(wrong(&what)),
        };
        let [first, size] = pair.as_slice() else {
            return Err(wrong(&what));
        };
        out.push(Given {
            first: convert::count(first, &what)?,
            size: convert::count(size, &what)?,
        });
    }
    Ok(out)
}

/// The solver's contacts from its clusters: `contacts[j]` for the pair
/// `(j, j + 1)` is whether both lie in one cluster.
fn contacts(py: Python<'_>, clusters: &[Given], n: usize) -> PyResult<Vec<bool>> {
    let mut joined = vec![false; n.saturating_sub(1)];
    let mut next = 0usize;
    for (k, &Given { first, size }) in clusters.iter().enumerate() {
        let end = first.checked_add(size).filter(|&e| e <= n);
        let Some(end) = end.filter(|_| first == next && size > 0) else {
            let what = convert::entry("clusters", k);
            let message = format!(
                "{what} = ({first}, {size}): clusters must be (first, size) pairs that tile 0 … {} left to right",
                n.saturating_sub(1)
            );
            return Err(errors::argument(py, &what, message));
        };
        joined[first..end - 1].fill(true);
        next = end;
    }
    if next != n {
        let message = format!(
            "clusters cover particles 0 … {} of {n}: they must tile them all",
            next as i64 - 1
        );
        return Err(errors::argument(py, "clusters", message));
    }
    Ok(joined)
}

/// compare(scene, t, positions, velocities=None, *, multipliers=None,
/// clusters=None, contact_tol=0, overlap_tol=0) -> CompareReport
///
/// Another solver's answer at time t against sticky's exact one, as
/// `sticky compare` measures it: position, velocity and multiplier errors
/// (max with its index, L²), overlaps with their depths, missed and
/// spurious contacts and clusters, λ sign and complementarity, Oleinik, and
/// the verdict ("exact", "rounding", "inexact" or "invalid"). Numbers are
/// read exactly (a float as its binary value). `clusters`: the solver's own
/// contact clusters as (first, size) pairs; without them a pair with gap
/// ≤ 2r + contact_tol counts as a contact. `overlap_tol`: the rounding
/// tolerance, relative to 2r. Indices from 0.
#[pyfunction]
#[pyo3(
    signature = (scene, t, positions, velocities=None, *, multipliers=None, clusters=None, contact_tol=None, overlap_tol=None),
    text_signature = "(scene, t, positions, velocities=None, *, multipliers=None, clusters=None, contact_tol=0, overlap_tol=0)"
)]
#[allow(clippy::too_many_arguments)]
pub fn compare(
    py: Python<'_>,
    scene: &Bound<'_, Scene>,
    t: &Bound<'_, PyAny>,
    positions: &Bound<'_, PyAny>,
    velocities: Option<&Bound<'_, PyAny>>,
    multipliers: Option<&Bound<'_, PyAny>>,
    clusters: Option<&Bound<'_, PyAny>>,
    contact_tol: Option<&Bound<'_, PyAny>>,
    overlap_tol: Option<&Bound<'_, PyAny>>,
) -> PyResult<CompareReport> {
    let clusters = clusters.map(given_clusters).transpose()?;
    let t = convert::exact(t, "t")?;
    let positions = convert::column(positions, "positions")?.into_exact("positions")?;
    let mut frame = Frame::new(t, positions);
    frame.velocities = optional_column(velocities, "velocities")?;
    frame.multipliers = optional_column(multipliers, "multipliers")?;
    let zero = || BigRational::new(0.into(), 1.into());
    let options = CompareOptions {
        contact_tol: ContactTolerance::Absolute(match contact_tol {
            Some(c) => convert::exact(c, "contact_tol")?,
            None => zero(),
        }),
        overlap_tol: match overlap_tol {
            Some(c) => convert::exact(c, "overlap_tol")?,
            None => zero(),
        },
    };
    let given = scene;
    let scene = given.get();
    let inner = Arc::clone(&scene.inner);
    let n = py.detach(|| inner.n()).map_err(errors::py_error)?;
    if let Some(c) = &clusters {
        frame.contacts = Some(contacts(py, c, n)?);
    }
    let frame = Arc::new(frame);
    let kept = Arc::clone(&frame);
    let report = interrupt::run_sized(py, n, move |stop| {
        compare_solution_by(
            inner.solver(),
            std::slice::from_ref(&*frame),
            &options,
            stop,
        )
    })?
    .map_err(|e| {
        let message = match e {
            CompareFailure::Frame { error, .. } => error.to_string(),
            other => other.to_string(),
        };
        errors::raise(py, "CompareError", message, vec![])
    })?;
    let report = Arc::new(report);
    let frames = (0..report.frames.len())
        .map(|index| {
            let report = Arc::clone(&report);
            Py::new(py, FrameFigures { report, index })
        })
        .collect::<PyResult<Vec<_>>>()?;
    Ok(CompareReport {
        report,
        frames,
        scene: given.clone().unbind(),
        frame: kept,
    })
}

/// The comparison of one time: every figure exact (`Fraction`) and as the
/// nearest double (`*_float`), indices from 0.
#[pyclass(module = "sticky", frozen, name = "CompareFrame")]
pub struct FrameFigures {
    /// The whole report (shared, not copied: a frame's lists are `O(N)`).
    report: Arc<Report>,
    /// Which of its frames.
    index: usize,
}

impl FrameFigures {
    /// The frame's figures.
    fn frame(&self) -> &FrameReport {
        &self.report.frames[self.index]
    }
}

/// A max error as Python sees it: `(value, value as float, index)`.
type MaxTuple<'py> = (Bound<'py, PyAny>, Option<f64>, usize);

/// An overlap as Python sees it: `(pair, depth, depth as float)`.
type OverlapTuple<'py> = (usize, Bound<'py, PyAny>, Option<f64>);

/// `(value, value as float, index)` of a max error.
fn max_error<'py>(py: Python<'py>, m: Option<&MaxError>) -> PyResult<Option<MaxTuple<'py>>> {
    m.map(|m| Ok((convert::fraction(py, &m.value)?, float(&m.value), m.index)))
        .transpose()
}

/// `[(pair, value)]` with exact values.
fn pairs<'py>(py: Python<'py>, v: &[PairValue]) -> PyResult<Vec<(usize, Bound<'py, PyAny>)>> {
    v.iter()
        .map(|p| Ok((p.pair, convert::fraction(py, &p.value)?)))
        .collect()
}

/// `[(first, size)]`.
fn cluster_pairs(v: &[Cluster]) -> Vec<(usize, usize)> {
    v.iter().map(|c| (c.first, c.size)).collect()
}

#[pymethods]
impl FrameFigures {
    /// The time, exact.
    #[getter]
    fn t<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        convert::fraction(py, &self.frame().comparison.t)
    }

    /// This time's verdict: "exact", "rounding", "inexact" or "invalid".
    #[getter]
    fn verdict(&self) -> &'static str {
        self.frame().verdict.name()
    }

    /// Whether every figure is 0 (the answer is the exact one).
    #[getter]
    fn exact(&self) -> bool {
        self.frame().comparison.is_exact()
    }

    /// max_i |x_i - exact x_i|, exact.
    #[getter]
    fn position_max<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        convert::fraction(py, &self.frame().comparison.position_max.value)
    }

    /// The nearest double of position_max.
    #[getter]
    fn position_max_float(&self) -> Option<f64> {
        float(&self.frame().comparison.position_max.value)
    }

    /// The first index reaching position_max.
    #[getter]
    fn position_max_index(&self) -> usize {
        self.frame().comparison.position_max.index
    }

    /// (1/N) Σ e_i², the square of the L² position error, exact.
    #[getter]
    fn position_l2_squared<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        convert::fraction(py, &self.frame().comparison.position_l2_squared)
    }

    /// The L² position error: the double nearest to the exact root.
    #[getter]
    fn position_l2_float(&self) -> Option<f64> {
        root_float(&self.frame().comparison.position_l2_squared)
    }

    /// (value, float, index) of the max velocity error; None without
    /// velocities.
    #[getter]
    fn velocity_max<'py>(&self, py: Python<'py>) -> PyResult<Option<MaxTuple<'py>>> {
        max_error(py, self.frame().comparison.velocity_max.as_ref())
    }

    /// The square of the L² velocity error, exact; None without velocities.
    #[getter]
    fn velocity_l2_squared<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyAny>>> {
        self.frame()
            .comparison
            .velocity_l2_squared
            .as_ref()
            .map(|q| convert::fraction(py, q))
            .transpose()
    }

    /// The L² velocity error, nearest double of the exact root.
    #[getter]
    fn velocity_l2_float(&self) -> Option<f64> {
        self.frame()
            .comparison
            .velocity_l2_squared
            .as_ref()
            .and_then(root_float)
    }

    /// (value, float, index) of the max multiplier error; None without
    /// multipliers.
    #[getter]
    fn multiplier_max<'py>(&self, py: Python<'py>) -> PyResult<Option<MaxTuple<'py>>> {
        max_error(py, self.frame().comparison.multiplier_max.as_ref())
    }

    /// Overlapping pairs (j, j+1): [(j, depth 2r - gap)], exact.
    #[getter]
    fn overlaps<'py>(&self, py: Python<'py>) -> PyResult<Vec<OverlapTuple<'py>>> {
        self.frame()
            .comparison
            .overlaps
            .iter()
            .map(|o| Ok((o.pair, convert::fraction(py, &o.depth)?, float(&o.depth))))
            .collect()
    }

    /// Pairs in contact in the exact answer, not in the solver's.
    #[getter]
    fn missed_contacts(&self) -> usize {
        self.frame().comparison.missed_contacts
    }

    /// Pairs in contact in the solver's answer, not in the exact one.
    #[getter]
    fn spurious_contacts(&self) -> usize {
        self.frame().comparison.spurious_contacts
    }

    /// Exact clusters (first, size) the solver does not have.
    #[getter]
    fn missed_clusters(&self) -> Vec<(usize, usize)> {
        cluster_pairs(&self.frame().comparison.missed_clusters)
    }

    /// The solver's clusters (first, size) the exact answer does not have.
    #[getter]
    fn spurious_clusters(&self) -> Vec<(usize, usize)> {
        cluster_pairs(&self.frame().comparison.spurious_clusters)
    }

    /// Pairs with λ < 0: [(pair, λ)], exact.
    #[getter]
    fn negative_multipliers<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<Vec<(usize, Bound<'py, PyAny>)>> {
        pairs(py, &self.frame().comparison.negative_multipliers)
    }

    /// Pairs with λ·(gap - 2r) ≠ 0: [(pair, product)], exact.
    #[getter]
    fn complementarity<'py>(&self, py: Python<'py>) -> PyResult<Vec<(usize, Bound<'py, PyAny>)>> {
        pairs(py, &self.frame().comparison.complementarity)
    }

    /// i for each pair (i-1, i) breaking the discrete Oleinik condition
    /// (prop:Oleinik); None when not checked.
    #[getter]
    fn oleinik(&self) -> Option<Vec<usize>> {
        self.frame().comparison.oleinik.clone()
    }

    fn __repr__(&self) -> String {
        let c = &self.frame().comparison;
        format!(
            "CompareFrame(t={}, verdict={:?}, position_max={} at {}, overlaps={}, missed_contacts={}, spurious_contacts={})",
            convert::shown(&c.t),
            self.frame().verdict.name(),
            convert::shown(&c.position_max.value),
            c.position_max.index,
            c.overlaps.len(),
            c.missed_contacts,
            c.spurious_contacts
        )
    }
}

/// What `sticky.compare` returns: the verdict, one `CompareFrame` per time
/// (`frames`; with one time its figures are also the report's own
/// attributes: `report.position_max`), `text()` (the report of `sticky
/// compare`), `to_dict()` (its JSON).
#[pyclass(module = "sticky", frozen)]
pub struct CompareReport {
    report: Arc<Report>,
    frames: Vec<Py<FrameFigures>>,
    /// The scene compared with, and the answer compared (for pickling).
    scene: Py<Scene>,
    frame: Arc<Frame>,
}

/// The clusters `(first, size)` of a contact set (`contacts[j]`: the pair
/// `(j, j + 1)` touches).
fn clusters_of(contacts: &[bool]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut first = 0;
    for (j, &touch) in contacts.iter().enumerate() {
        if !touch {
            out.push((first, j + 1 - first));
            first = j + 1;
        }
    }
    out.push((first, contacts.len() + 1 - first));
    out
}

#[pymethods]
impl CompareReport {
    /// The verdict: "exact", "rounding", "inexact" or "invalid" (the worst
    /// time's).
    #[getter]
    fn verdict(&self) -> &'static str {
        self.report.verdict.name()
    }

    /// One CompareFrame per time.
    #[getter]
    fn frames(&self, py: Python<'_>) -> Vec<Py<FrameFigures>> {
        self.frames.iter().map(|f| f.clone_ref(py)).collect()
    }

    /// The text report of `sticky compare`.
    fn text(&self) -> String {
        self.report.text()
    }

    /// The verdict line of the text report.
    fn summary(&self) -> String {
        self.report.summary()
    }

    /// The report as `sticky compare --json` prints it (every figure an
    /// exact string with its nearest double beside it).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        // The typed JSON off the interpreter's thread; its long lists built
        // as Python objects directly, the rest through its text.
        let report = Arc::clone(&self.report);
        let steps = report.frames.len().saturating_mul(report.n);
        let (text, lists) = interrupt::run_sized(py, steps, move |_| {
            let mut json = report.to_json_value();
            let lists: Vec<FrameLists> = json.times.iter_mut().map(FrameLists::take).collect();
            (sticky::json::to_string(&json), lists)
        })?;
        let d = py.import("json")?.call_method1("loads", (text,))?;
        let times = d.get_item("times")?;
        crate::bulk::collector_paused(py, || {
            for (k, lists) in lists.iter().enumerate() {
                lists.fill(&times.get_item(k)?)?;
            }
            Ok(())
        })?;
        Ok(d)
    }

    /// With one time, the figures of that time (`report.position_max`, …).
    fn __getattr__<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
        match self.frames.as_slice() {
            [only] => only.bind(py).getattr(name),
            _ => Err(PyAttributeError::new_err(format!(
                "CompareReport has no attribute {name:?} (with several times, read it from report.frames[k])"
            ))),
        }
    }

    fn __repr__(&self, py: Python<'_>) -> String {
        let frames: Vec<String> = self.frames.iter().map(|f| f.get().__repr__()).collect();
        let _ = py;
        format!(
            "CompareReport(verdict={:?}, frames=[{}])",
            self.report.verdict.name(),
            frames.join(", ")
        )
    }

    fn __str__(&self) -> String {
        self.report.text()
    }

    /// Pickling and deep copies: the comparison made again from the exact
    /// answer compared (`sticky._values.report_again`).
    fn __reduce__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)> {
        let f = &self.frame;
        let list = |v: &Option<Vec<BigRational>>| -> PyResult<Option<Bound<'py, PyList>>> {
            v.as_deref()
                .map(|v| crate::bulk::fractions(py, v))
                .transpose()
        };
        let contact_tol = match &self.report.options.contact_tol {
            ContactTolerance::Absolute(q) => q.clone(),
            _ => self.report.contact_tol.clone(),
        };
        let args = (
            self.scene.clone_ref(py),
            convert::fraction(py, &f.t)?,
            crate::bulk::fractions(py, &f.positions)?,
            list(&f.velocities)?,
            list(&f.multipliers)?,
            f.contacts.as_deref().map(clusters_of),
            convert::fraction(py, &contact_tol)?,
            convert::fraction(py, &self.report.options.overlap_tol)?,
        )
            .into_pyobject(py)?;
        let again = py.import("sticky._values")?.getattr("report_again")?;
        Ok((again, args))
    }
}
