//! Many exact values handed to Python at once: lists of
//! `fractions.Fraction` and of exact strings `"p/q"`, built straight from
//! the library's values (no JSON text on the way), with Ctrl-C honoured
//! between chunks ([`CHUNK`]): these loops hold the GIL, so they ask Python
//! for signals themselves.

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::ToPrimitive;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyString, PyTuple, PyType};
use pyo3::{intern, IntoPyObjectExt};
use sticky::json::Rational;
use sticky::rational::render_exact;
use sticky::report::export::{ColumnJson, ExportJson, RoundedJson};

use crate::convert;

/// Values built between two checks for Ctrl-C ([`Python::check_signals`]).
pub const CHUNK: usize = 1 << 15;

/// `v` as a Python `int`: from a machine word when it fits one (`i64`,
/// then `i128`: a few C calls), else from its bytes.
fn int<'py>(py: Python<'py>, v: &BigInt) -> PyResult<Bound<'py, PyAny>> {
    if let Some(w) = v.to_i64() {
        return w.into_bound_py_any(py);
    }
    if let Some(w) = v.to_i128() {
        return w.into_bound_py_any(py);
    }
    v.into_bound_py_any(py)
}

/// How `fractions.Fraction` values are made.
enum Maker<'py> {
    /// `object.__new__(Fraction)` with its two slots `_numerator` and
    /// `_denominator` set: what `Fraction(p, q)` stores once it has reduced
    /// `p/q`, without its Python-level checks and gcd (a `BigRational` is
    /// already in lowest terms with a positive denominator). Taken only when
    /// the class is the standard library's slotted one and a probe made so
    /// equals the constructor's (see [`Maker::new`]).
    Slots {
        class: Bound<'py, PyType>,
        new: Bound<'py, PyAny>,
    },
    /// `Fraction(p, q)`.
    Constructor(Bound<'py, PyType>),
}

impl<'py> Maker<'py> {
    /// The fastest maker this Python's `fractions` module allows.
    fn new(py: Python<'py>) -> PyResult<Maker<'py>> {
        let class = convert::fraction_class(py)?.clone();
        let slots = Maker::Slots {
            class: class.clone(),
            new: py.get_type::<pyo3::types::PyAny>().getattr("__new__")?,
        };
        let trusted = || -> PyResult<bool> {
            let names = class.getattr("__slots__")?;
            let expected = PyTuple::new(py, ["_numerator", "_denominator"])?;
            if !names.eq(expected)? {
                return Ok(false);
            }
            let q = BigRational::new((-3).into(), 4.into());
            let (probe, made) = (slots.make(&q)?, class.call1((-3, 4))?);
            Ok(probe.eq(&made)?
                && probe.hash()? == made.hash()?
                && probe.str()?.to_cow()? == made.str()?.to_cow()?)
        };
        // Any surprise (another `fractions`, other slots) means the
        // constructor.
        if trusted().unwrap_or(false) {
            Ok(slots)
        } else {
            Ok(Maker::Constructor(class))
        }
    }

    /// `q` as a `Fraction`.
    fn make(&self, q: &BigRational) -> PyResult<Bound<'py, PyAny>> {
        debug_assert!(
            q.denom() > &BigInt::from(0),
            "a BigRational's denominator is positive"
        );
        match self {
            Maker::Slots { class, new } => {
                let py = class.py();
                let f = new.call1((class,))?;
                f.setattr(intern!(py, "_numerator"), int(py, q.numer())?)?;
                f.setattr(intern!(py, "_denominator"), int(py, q.denom())?)?;
                Ok(f)
            }
            Maker::Constructor(class) => {
                let py = class.py();
                class.call1((int(py, q.numer())?, int(py, q.denom())?))
            }
        }
    }
}

/// `v` as a list of `fractions.Fraction` (Ctrl-C: `KeyboardInterrupt`).
/// Python's cyclic garbage collector is paused while they are made (and
/// restored as it was): each new `Fraction` is an object it tracks, and a
/// collection every few hundred of them walks the young ones again and
/// again; two ints per `Fraction` make no cycle.
pub fn fractions<'py>(py: Python<'py>, v: &[BigRational]) -> PyResult<Bound<'py, PyList>> {
    let maker = Maker::new(py)?;
    collector_paused(py, || list(py, v, |_, q| maker.make(q)))
}

/// The items of `v` made by `make`, as a list (Ctrl-C: `KeyboardInterrupt`,
/// between chunks of [`CHUNK`]).
pub fn list<'py, T>(
    py: Python<'py>,
    v: &[T],
    make: impl Fn(Python<'py>, &T) -> PyResult<Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyList>> {
    let mut items = Vec::with_capacity(v.len());
    for chunk in v.chunks(CHUNK) {
        py.check_signals()?;
        for item in chunk {
            items.push(make(py, item)?);
        }
    }
    PyList::new(py, items)
}

/// `make()` with Python's cyclic garbage collector paused, and restored as
/// it was (see [`fractions`]: many new tracked objects without cycles).
pub fn collector_paused<'py, R>(
    py: Python<'py>,
    make: impl FnOnce() -> PyResult<R>,
) -> PyResult<R> {
    let gc = py.import(intern!(py, "gc"))?;
    let enabled = gc.call_method0(intern!(py, "isenabled"))?.is_truthy()?;
    if enabled {
        gc.call_method0(intern!(py, "disable"))?;
    }
    let made = make();
    if enabled {
        gc.call_method0(intern!(py, "enable"))?;
    }
    made
}

/// `v` as a list of exact strings ([`render_exact`];
/// Ctrl-C: `KeyboardInterrupt`).
pub fn texts<'py>(py: Python<'py>, v: &[BigRational]) -> PyResult<Bound<'py, PyList>> {
    list(py, v, |py, q| {
        Ok(PyString::new(py, &render_exact(q)).into_any())
    })
}

/// Strings already written (the export's), as a list; equal strings in a
/// row share one Python `str` (the export's errors are mostly `"0"`).
fn written<'py>(py: Python<'py>, v: &[Rational]) -> PyResult<Bound<'py, PyList>> {
    let mut items: Vec<Bound<'py, PyString>> = Vec::with_capacity(v.len());
    let mut previous: Option<(&str, Bound<'py, PyString>)> = None;
    for chunk in v.chunks(CHUNK) {
        py.check_signals()?;
        for r in chunk {
            let item = match &previous {
                Some((text, item)) if *text == r.0 => item.clone(),
                _ => PyString::new(py, &r.0),
            };
            previous = Some((&r.0, item.clone()));
            items.push(item);
        }
    }
    PyList::new(py, items)
}

/// The dict `json.loads` makes of [`ExportJson`]'s text, built directly:
/// the same keys in the same order, exact values as strings, doubles as
/// `float`.
pub fn export_dict<'py>(py: Python<'py>, e: &ExportJson) -> PyResult<Bound<'py, PyDict>> {
    let rounded = |r: &RoundedJson| -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        d.set_item("exact", &r.exact.0)?;
        d.set_item("f64", r.f64)?;
        d.set_item("error", &r.error.0)?;
        Ok(d)
    };
    let column = |c: &ColumnJson| -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        d.set_item("exact", written(py, &c.exact)?)?;
        d.set_item("f64", PyList::new(py, &c.f64)?)?;
        d.set_item("error", written(py, &c.error)?)?;
        Ok(d)
    };
    let d = PyDict::new(py);
    d.set_item("name", &e.name)?;
    d.set_item("n", e.n)?;
    d.set_item("t_end", e.t_end.as_ref().map(|t| &t.0))?;
    d.set_item("radius", rounded(&e.radius)?)?;
    d.set_item("positions", column(&e.positions)?)?;
    d.set_item("velocities", column(&e.velocities)?)?;
    d.set_item("f64_admissible", e.f64_admissible)?;
    d.set_item(
        "f64_min_gap_minus_2r",
        e.f64_min_gap_minus_2r.as_ref().map(|g| &g.0),
    )?;
    Ok(d)
}
