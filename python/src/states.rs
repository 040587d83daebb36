//! `sticky.States`: the states of a scene at several times, as a lazy
//! sequence. `Scene.states(ts)` reads and checks every time at once (a bad
//! or negative time raises there), and each state is computed when it is
//! first read (`states[k]`, iteration, `list(states)`), then kept: reading
//! one state of twenty costs one state, not twenty.

use std::sync::{Arc, OnceLock};

use num_rational::BigRational;
use num_traits::Signed;
use pyo3::exceptions::{PyIndexError, PyTypeError};
use pyo3::prelude::*;
use pyo3::types::{PyList, PySlice, PyTuple};
use sticky::Error;

use crate::scene::{py_error, Inner, Scene};
use crate::state::State;

/// The states of a scene at the times `ts` of `Scene.states(ts)`, in the
/// order given: a sequence (`len`, indexing from the end, slices,
/// iteration) whose states are computed on first read and kept.
#[pyclass(module = "sticky", frozen, sequence)]
pub struct States {
    scene: Arc<Inner>,
    times: Vec<BigRational>,
    /// One cell per time: the state once read.
    states: Vec<OnceLock<Py<State>>>,
}

impl States {
    /// The states of `scene` at `times`, none computed yet; `NegativeTimeError`
    /// for a time below 0 (raised now, as an eager call would).
    pub fn new(scene: Arc<Inner>, times: Vec<BigRational>) -> PyResult<States> {
        if let Some(t) = times.iter().find(|t| t.is_negative()) {
            return Err(py_error(Error::NegativeTime {
                t: sticky::rational::render_exact(t),
            }));
        }
        let states = times.iter().map(|_| OnceLock::new()).collect();
        Ok(States {
            scene,
            times,
            states,
        })
    }

    /// The state at `times[k]` (`k` in range), computed now if it was not.
    fn get(&self, py: Python<'_>, k: usize) -> PyResult<Py<State>> {
        debug_assert!(k < self.times.len());
        if let Some(s) = self.states[k].get() {
            return Ok(s.clone_ref(py));
        }
        let computed = crate::scene::states_at(py, &self.scene, vec![self.times[k].clone()])?
            .pop()
            .ok_or_else(|| pyo3::exceptions::PyValueError::new_err("no state"))?;
        let computed = Py::new(py, computed)?;
        // Another thread may have read it meanwhile: keep the first.
        Ok(self.states[k].get_or_init(|| computed).clone_ref(py))
    }

    /// `index` as a position in `0 … len - 1` (negative from the end).
    fn position(&self, index: isize) -> PyResult<usize> {
        let len = self.times.len() as isize;
        let k = if index < 0 { index + len } else { index };
        if (0..len).contains(&k) {
            Ok(k as usize)
        } else {
            Err(PyIndexError::new_err(format!(
                "index {index} is out of range for {len} states"
            )))
        }
    }
}

#[pymethods]
impl States {
    fn __len__(&self) -> usize {
        self.times.len()
    }

    /// `states[k]`: the state at the k-th time (negative k from the end);
    /// `states[a:b:c]`: a list of those states.
    fn __getitem__<'py>(
        &self,
        py: Python<'py>,
        index: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyAny>> {
        if let Ok(slice) = index.cast::<PySlice>() {
            let range = slice.indices(self.times.len() as isize)?;
            let mut out = Vec::with_capacity(range.slicelength);
            let mut k = range.start;
            for _ in 0..range.slicelength {
                out.push(self.get(py, k as usize)?);
                k += range.step;
            }
            return Ok(PyList::new(py, out)?.into_any());
        }
        if index.is_instance_of::<pyo3::types::PyBool>() {
            return Err(PyTypeError::new_err(
                "States indices are integers or slices, not bool",
            ));
        }
        let Ok(index) = index.extract::<isize>() else {
            if index.is_instance_of::<pyo3::types::PyInt>() {
                return Err(PyIndexError::new_err(format!(
                    "index {index} is out of range for {} states",
                    self.times.len()
                )));
            }
            return Err(PyTypeError::new_err(format!(
                "States indices are integers or slices, not {}",
                index.get_type().name()?
            )));
        };
        let k = self.position(index)?;
        Ok(self.get(py, k)?.into_bound(py).into_any())
    }

    /// Iteration computes each state as it is reached.
    fn __iter__(slf: Bound<'_, Self>) -> StatesIter {
        StatesIter {
            states: slf.unbind(),
            next: std::sync::atomic::AtomicUsize::new(0),
        }
    }

    /// The times, exact (fractions.Fraction), in order.
    #[getter]
    fn times<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        crate::bulk::fractions(py, &self.times)
    }

    /// The scene these are states of.
    #[getter]
    fn scene(&self) -> Scene {
        Scene {
            inner: Arc::clone(&self.scene),
        }
    }

    fn __repr__(&self) -> String {
        let computed = self.states.iter().filter(|s| s.get().is_some()).count();
        format!(
            "States({} times, {computed} computed so far)",
            self.times.len()
        )
    }

    /// Pickling and deep copies: `scene.states(times)` again, no state
    /// computed (`sticky._values.states_again`).
    fn __reduce__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)> {
        let args = (Bound::new(py, self.scene())?, self.times(py)?).into_pyobject(py)?;
        let again = py.import("sticky._values")?.getattr("states_again")?;
        Ok((again, args))
    }
}

/// An iterator over [`States`], computing each state as it is reached.
#[pyclass(module = "sticky", frozen)]
pub struct StatesIter {
    states: Py<States>,
    next: std::sync::atomic::AtomicUsize,
}

#[pymethods]
impl StatesIter {
    fn __iter__(slf: Bound<'_, Self>) -> Bound<'_, Self> {
        slf
    }

    fn __next__(&self, py: Python<'_>) -> PyResult<Option<Py<State>>> {
        use std::sync::atomic::Ordering;
        let states = self.states.get();
        let k = self.next.fetch_add(1, Ordering::Relaxed);
        if k >= states.times.len() {
            // Stay exhausted.
            self.next.store(states.times.len(), Ordering::Relaxed);
            return Ok(None);
        }
        states.get(py, k).map(Some)
    }
}
