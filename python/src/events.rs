//! `sticky.Event`: one cluster formed by a collision (`sticky events`).

use num_rational::BigRational;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use sticky::solver::Collision;
use sticky::Scalar;

use crate::convert;

/// A cluster formed by a collision at time t: its first particle (indexed
/// from 0), its size, and the sizes of the clusters that merged into it at
/// that instant, left to right (two or more).
#[pyclass(module = "sticky", frozen)]
pub struct Event {
    t: BigRational,
    first: usize,
    size: usize,
    parts: Vec<usize>,
}

impl Event {
    /// The event of a collision of the library's history.
    pub fn from_collision(c: Collision) -> Event {
        Event {
            t: c.t,
            first: c.first,
            size: c.size,
            parts: c.parts,
        }
    }
}

#[pymethods]
impl Event {
    /// The collision time, exact (fractions.Fraction).
    #[getter]
    fn t<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        convert::fraction(py, &self.t)
    }

    /// The collision time as the nearest double.
    #[getter]
    fn t_float(&self) -> f64 {
        self.t.to_f64_lossy()
    }

    /// The first particle of the cluster formed (indexed from 0).
    #[getter]
    fn first(&self) -> usize {
        self.first
    }

    /// The number of particles of the cluster formed.
    #[getter]
    fn size(&self) -> usize {
        self.size
    }

    /// The sizes of the clusters that merged, left to right.
    #[getter]
    fn parts(&self) -> Vec<usize> {
        self.parts.clone()
    }

    /// The event as `sticky events --json` prints it: {"t": "p/q", "first",
    /// "size", "parts"}.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let event = sticky::report::json::EventJson {
            t: sticky::json::Rational::of(&self.t),
            first: self.first,
            size: self.size,
            parts: self.parts.clone(),
        };
        py.import("json")?
            .call_method1("loads", (sticky::json::to_string(&event),))?
            .cast_into::<PyDict>()
            .map_err(Into::into)
    }

    fn __repr__(&self) -> String {
        format!(
            "Event(t={}, first={}, size={}, parts={:?})",
            convert::shown(&self.t),
            self.first,
            self.size,
            self.parts
        )
    }
}
