//! The long lists of a comparison's JSON (`CompareReport.to_dict()`): one
//! entry per overlapping pair, per pair breaking `λ ≥ 0` or
//! complementarity, per wrong cluster, per Oleinik violation — `O(N)` on a
//! floating-point answer. They are taken out of the library's typed JSON
//! ([`FrameJson`]) before the rest is written as text, and built here as
//! Python lists of dicts straight from the typed values (the keys of the
//! typed fields, in their order), with the collector paused and Ctrl-C
//! honoured between chunks.

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use pyo3::{intern, IntoPyObjectExt};
use sticky::report::compare::json::{FrameJson, OverlapJson, PairJson};

use crate::bulk::list;

/// One time's long lists, taken out of its [`FrameJson`].
pub struct FrameLists {
    overlaps: Vec<OverlapJson>,
    negative_multipliers: Vec<PairJson>,
    complementarity: Vec<PairJson>,
    missed_clusters: Vec<[usize; 2]>,
    spurious_clusters: Vec<[usize; 2]>,
    /// `None`: not checked (the key stays `null`).
    oleinik: Option<Vec<usize>>,
}

impl FrameLists {
    /// Takes the lists out of `f`, leaving them empty (`oleinik` as it was
    /// when `None`).
    pub fn take(f: &mut FrameJson) -> FrameLists {
        FrameLists {
            overlaps: std::mem::take(&mut f.overlaps),
            negative_multipliers: std::mem::take(&mut f.negative_multipliers),
            complementarity: std::mem::take(&mut f.complementarity),
            missed_clusters: std::mem::take(&mut f.missed_clusters),
            spurious_clusters: std::mem::take(&mut f.spurious_clusters),
            oleinik: f.oleinik.as_mut().map(std::mem::take),
        }
    }

    /// Puts the lists into `time`, the dict `json.loads` made of the rest of
    /// this time's object (same keys, values as `json.loads` gives them).
    pub fn fill(&self, time: &Bound<'_, PyAny>) -> PyResult<()> {
        let py = time.py();
        time.set_item(intern!(py, "overlaps"), list(py, &self.overlaps, overlap)?)?;
        time.set_item(
            intern!(py, "negative_multipliers"),
            list(py, &self.negative_multipliers, pair)?,
        )?;
        time.set_item(
            intern!(py, "complementarity"),
            list(py, &self.complementarity, pair)?,
        )?;
        time.set_item(
            intern!(py, "missed_clusters"),
            list(py, &self.missed_clusters, cluster)?,
        )?;
        time.set_item(
            intern!(py, "spurious_clusters"),
            list(py, &self.spurious_clusters, cluster)?,
        )?;
        if let Some(o) = &self.oleinik {
            time.set_item(
                intern!(py, "oleinik"),
                list(py, o, |py, i| i.into_bound_py_any(py))?,
            )?;
        }
        Ok(())
    }
}

/// An [`OverlapJson`] as its dict.
fn overlap<'py>(py: Python<'py>, o: &OverlapJson) -> PyResult<Bound<'py, PyAny>> {
    let d = PyDict::new(py);
    d.set_item(intern!(py, "pair"), o.pair)?;
    d.set_item(intern!(py, "depth"), &o.depth)?;
    d.set_item(intern!(py, "depth_f64"), o.depth_f64)?;
    d.set_item(intern!(py, "depth_relative"), &o.depth_relative)?;
    d.set_item(intern!(py, "depth_relative_f64"), o.depth_relative_f64)?;
    d.set_item(intern!(py, "within_tolerance"), o.within_tolerance)?;
    Ok(d.into_any())
}

/// A [`PairJson`] as its dict.
fn pair<'py>(py: Python<'py>, p: &PairJson) -> PyResult<Bound<'py, PyAny>> {
    let d = PyDict::new(py);
    d.set_item(intern!(py, "pair"), p.pair)?;
    d.set_item(intern!(py, "value"), &p.value)?;
    d.set_item(intern!(py, "value_f64"), p.value_f64)?;
    Ok(d.into_any())
}

/// A cluster `[first, size]` as its list.
fn cluster<'py>(py: Python<'py>, c: &[usize; 2]) -> PyResult<Bound<'py, PyAny>> {
    Ok(PyList::new(py, c)?.into_any())
}
