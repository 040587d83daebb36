//! Python numbers to exact rationals and back.
//!
//! Every input number is read exactly: a `float` (numpy's `float64`
//! included) as the binary rational the double is
//! ([`sticky::columns::f64_exact`]), an `int` or a `fractions.Fraction` as
//! itself, a string by the scene files' reader
//! ([`sticky::rational::parse_exact`]: `"1/3"`, `"0.125"`, `"1e-3"`). Every
//! output rational is a `fractions.Fraction`, every `float` output the
//! nearest double of the exact value. A `bool` is refused everywhere (a
//! Python `bool` and numpy's `bool_` alike): `True` is not the number 1
//! here. Every error names its argument (`positions[3]`, `clusters[1]`).

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::{ToPrimitive, Zero};
use numpy::{PyArray1, PyArrayMethods, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyBool, PyFloat, PyInt, PySlice, PyString, PyType};
use sticky::columns::f64_exact;
use sticky::fast::filter::Checked;
use sticky::rational::parse_exact;
use sticky::Scalar;

use crate::errors;

/// A column of input numbers: all doubles (the fast path reads them on
/// machine words), or exact rationals of any kind.
pub enum Column {
    /// Every value a double (a `float64` array or a sequence of `float`).
    Doubles(Vec<f64>),
    /// Any exact values.
    Exact(Vec<BigRational>),
}

impl Column {
    /// Number of values.
    pub fn len(&self) -> usize {
        match self {
            Column::Doubles(v) => v.len(),
            Column::Exact(v) => v.len(),
        }
    }

    /// The exact values; a NaN or an infinity is a `ValueError` naming its
    /// entry (`name[i]`, 0-based).
    pub fn into_exact(self, name: &str) -> PyResult<Vec<BigRational>> {
        match self {
            Column::Exact(v) => Ok(v),
            Column::Doubles(v) => v
                .iter()
                .enumerate()
                .map(|(i, &d)| double(d, &entry(name, i)))
                .collect(),
        }
    }
}

/// `name[i]`, the bracket form of an entry (indices from 0).
pub fn entry(name: &str, i: usize) -> String {
    format!("{name}[{i}]")
}

/// The exact value of the double `d`, or the `ValueError` that names `what`.
pub fn double(d: f64, what: &str) -> PyResult<BigRational> {
    f64_exact(d).ok_or_else(|| {
        Python::attach(|py| {
            let message = format!("{what} is {d}: every value must be a finite number");
            errors::argument(py, what, message)
        })
    })
}

/// Whether `obj` is a Python `bool` or a numpy `bool_`.
fn is_bool(obj: &Bound<'_, PyAny>) -> bool {
    obj.is_instance_of::<PyBool>()
        || obj
            .get_type()
            .name()
            .is_ok_and(|n| n.to_cow().is_ok_and(|n| n == "bool" || n == "bool_"))
}

/// The `TypeError` (a `sticky.ArgumentTypeError`) for a bool at `what`.
fn no_bool(py: Python<'_>, what: &str) -> PyErr {
    errors::argument_type(
        py,
        what,
        format!("{what} is a bool: a number is needed (write 0 or 1)"),
    )
}

/// One Python number as an exact rational; errors name `what`.
pub fn exact(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<BigRational> {
    let py = obj.py();
    if is_bool(obj) {
        return Err(no_bool(py, what));
    }
    if let Ok(s) = obj.cast::<PyString>() {
        let text = s.to_cow()?;
        return parse_exact(&text)
            .map_err(|e| errors::argument(py, what, format!("{what}: {text:?} is refused: {e}")));
    }
    if let Ok(f) = obj.cast::<PyFloat>() {
        return double(f.value(), what);
    }
    let ratio = |num: Bound<'_, PyAny>, den: Bound<'_, PyAny>| -> PyResult<BigRational> {
        let int = |v: Bound<'_, PyAny>| -> PyResult<BigInt> {
            v.extract().map_err(|_| {
                errors::argument_type(
                    py,
                    what,
                    format!("{what}: its numerator and denominator must be integers"),
                )
            })
        };
        let (num, den) = (int(num)?, int(den)?);
        if den.is_zero() {
            return Err(errors::argument(
                py,
                what,
                format!("{what}: zero denominator"),
            ));
        }
        Ok(BigRational::new(num, den))
    };
    if obj.hasattr("numerator")? && obj.hasattr("denominator")? {
        return ratio(obj.getattr("numerator")?, obj.getattr("denominator")?);
    }
    if obj.hasattr("as_integer_ratio")? {
        // numpy's float32/float16, decimal.Decimal: their own exact ratio.
        let not_finite = || {
            let shown = obj.repr().map(|r| r.to_string()).unwrap_or_default();
            let message =
                format!("{what} is {shown} (not finite): every value must be a finite number");
            errors::argument(py, what, message)
        };
        let pair = obj
            .call_method0("as_integer_ratio")
            .map_err(|_| not_finite())?;
        let (num, den) = (
            pair.get_item(0).map_err(|_| not_finite())?,
            pair.get_item(1).map_err(|_| not_finite())?,
        );
        return ratio(num, den);
    }
    Err(errors::argument_type(
        py,
        what,
        format!(
            "{what}: expected a float, an int, a fractions.Fraction or an exact string such as \"1/3\", got {}",
            obj.get_type().name()?
        ),
    ))
}

/// A count or an index (an `int` in `0 … 2^64 - 1`, not a bool) at `what`.
pub fn count(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<usize> {
    let py = obj.py();
    if is_bool(obj) {
        return Err(no_bool(py, what));
    }
    if !obj.is_instance_of::<PyInt>() && !obj.hasattr("__index__")? {
        let kind = obj.get_type().name()?;
        let message = format!("{what}: an integer is needed, got {kind}");
        return Err(errors::argument_type(py, what, message));
    }
    let value: BigInt = obj
        .call_method0("__index__")
        .and_then(|i| i.extract())
        .map_err(|_| errors::argument_type(py, what, format!("{what}: an integer is needed")))?;
    value.to_usize().ok_or_else(|| {
        let message = format!("{what} = {value} is out of range: a count is in 0 … 2^64 - 1");
        errors::argument(py, what, message)
    })
}

/// Two columns of doubles, copied on two threads with the GIL released,
/// when both are contiguous one-dimensional `float64` numpy arrays (the
/// notebook's case); `None` otherwise (the caller reads them by [`column`]).
pub fn double_columns(
    py: Python<'_>,
    a: &Bound<'_, PyAny>,
    b: &Bound<'_, PyAny>,
) -> Option<(Vec<f64>, Vec<f64>)> {
    let a = a.extract::<PyReadonlyArray1<'_, f64>>().ok()?;
    let b = b.extract::<PyReadonlyArray1<'_, f64>>().ok()?;
    let (a, b) = (a.as_slice().ok()?, b.as_slice().ok()?);
    Some(py.detach(|| copy_pair(a, b)))
}

/// Private copies of two columns of doubles, validated exactly on the
/// copies ([`Checked::copied`], two threads, the GIL released) and made
/// read-only, when both are contiguous one-dimensional `float64` numpy
/// arrays of one length that the certified filter accepts; `None`
/// otherwise. Nothing else holds the copies: the caller's arrays may
/// change after, the copies do not.
///
/// Both copies are halves of one array from `numpy.empty`, every value
/// written before it is read: the allocator hands back the pages of a
/// scene freed before (zeroed arrays would take fresh pages from the
/// kernel, a page fault every 4 KiB).
pub fn private_columns<'py>(
    py: Python<'py>,
    a: &Bound<'py, PyAny>,
    b: &Bound<'py, PyAny>,
    radius: Option<BigRational>,
) -> PyResult<Option<PrivateColumns<'py>>> {
    let (Ok(a), Ok(b)) = (
        a.extract::<PyReadonlyArray1<'_, f64>>(),
        b.extract::<PyReadonlyArray1<'_, f64>>(),
    ) else {
        return Ok(None);
    };
    let (Ok(a), Ok(b)) = (a.as_slice(), b.as_slice()) else {
        return Ok(None);
    };
    let n = a.len();
    if b.len() != n || n == 0 {
        return Ok(None);
    }
    let both = empty(py, 2 * n)?;
    let checked = {
        let mut written = both.readwrite();
        let (x, u) = written.as_slice_mut()?.split_at_mut(n);
        py.detach(|| Checked::copied(radius, a, b, x, u))
    };
    let Ok(checked) = checked else {
        return Ok(None);
    };
    let half = |from: usize| -> PyResult<Bound<'py, PyArray1<f64>>> {
        let range = PySlice::new(py, from as isize, (from + n) as isize, 1);
        Ok(both.get_item(range)?.cast_into::<PyArray1<f64>>()?)
    };
    let (positions, velocities) = (half(0)?, half(n)?);
    for array in [&positions, &velocities] {
        array.getattr("flags")?.setattr("writeable", false)?;
    }
    Ok(Some(PrivateColumns {
        checked,
        positions,
        velocities,
    }))
}

/// A new array of `len` doubles from `numpy.empty`, for a caller that
/// writes every value before anything reads it: the allocator hands back
/// pages already in use (`PyArray1::zeros` would take fresh, zeroed pages
/// from the kernel at every call, a page fault every 4 KiB).
pub fn empty(py: Python<'_>, len: usize) -> PyResult<Bound<'_, PyArray1<f64>>> {
    static EMPTY: PyOnceLock<Py<PyAny>> = PyOnceLock::new();
    let empty = EMPTY.get_or_try_init(py, || -> PyResult<_> {
        Ok(py.import("numpy")?.getattr("empty")?.unbind())
    })?;
    Ok(empty.bind(py).call1((len,))?.cast_into::<PyArray1<f64>>()?)
}

/// The arrays of [`private_columns`].
pub struct PrivateColumns<'py> {
    /// What the validation of the copies established.
    pub checked: Checked,
    /// The positions' copy.
    pub positions: Bound<'py, PyArray1<f64>>,
    /// The velocities' copy.
    pub velocities: Bound<'py, PyArray1<f64>>,
}

/// Copies of `a` and `b`, the second on a thread of its own when it is
/// long enough to pay for one.
fn copy_pair(a: &[f64], b: &[f64]) -> (Vec<f64>, Vec<f64>) {
    const PARALLEL_MIN: usize = 1 << 16;
    if b.len() < PARALLEL_MIN {
        return (a.to_vec(), b.to_vec());
    }
    sticky::parallel::join(|| a.to_vec(), || b.to_vec())
}

/// A column of numbers: a one-dimensional `float64` numpy array, or any
/// iterable of numbers. Errors name `name[i]`.
pub fn column(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<Column> {
    if let Ok(array) = obj.extract::<PyReadonlyArray1<'_, f64>>() {
        let values = match array.as_slice() {
            Ok(s) => s.to_vec(),
            Err(_) => array.as_array().iter().copied().collect(),
        };
        return Ok(Column::Doubles(values));
    }
    let py = obj.py();
    if obj.is_instance_of::<PyString>() {
        let message = format!("{name} must be a sequence of numbers, not a string");
        return Err(errors::argument_type(py, name, message));
    }
    let items: Vec<Bound<'_, PyAny>> = obj
        .try_iter()
        .map_err(|_| {
            let message = format!(
                "{name} must be a sequence of numbers (a list or a one-dimensional numpy array)"
            );
            errors::argument_type(py, name, message)
        })?
        .collect::<PyResult<_>>()?;
    if items.iter().all(|x| x.is_instance_of::<PyFloat>()) {
        let values = items
            .iter()
            .map(|x| x.extract::<f64>())
            .collect::<PyResult<_>>()?;
        return Ok(Column::Doubles(values));
    }
    let values = items
        .iter()
        .enumerate()
        .map(|(i, x)| exact(x, &entry(name, i)))
        .collect::<PyResult<_>>()?;
    Ok(Column::Exact(values))
}

/// The class `fractions.Fraction`, imported once.
pub fn fraction_class(py: Python<'_>) -> PyResult<&Bound<'_, PyType>> {
    static FRACTION: PyOnceLock<Py<PyType>> = PyOnceLock::new();
    FRACTION.import(py, "fractions", "Fraction")
}

/// `text`, an exact number as the library writes it (`"p/q"`), with the
/// nearest double beside it when it is longer than a few digits:
/// `5404319552844595/18014398509481984 (≈ 0.3)`.
pub fn with_decimal(text: &str) -> String {
    const SHORT: usize = 8;
    if text.len() <= SHORT || !text.contains('/') {
        return text.to_string();
    }
    match parse_exact(text) {
        Ok(q) => format!("{text} (≈ {:?})", q.to_f64_lossy()),
        Err(_) => text.to_string(),
    }
}

/// `q` written exactly, with its decimal when it is long ([`with_decimal`]).
pub fn shown(q: &BigRational) -> String {
    with_decimal(&q.render())
}

/// `q` as a `fractions.Fraction`.
pub fn fraction<'py>(py: Python<'py>, q: &BigRational) -> PyResult<Bound<'py, PyAny>> {
    fraction_class(py)?.call1((q.numer().clone(), q.denom().clone()))
}

/// A numpy array of `v` that cannot be written to (`writeable=False`): the
/// arrays a `State` keeps and hands out again.
pub fn read_only(py: Python<'_>, v: Vec<f64>) -> PyResult<Bound<'_, PyArray1<f64>>> {
    let array = PyArray1::from_vec(py, v);
    array.getattr("flags")?.setattr("writeable", false)?;
    Ok(array)
}

/// The nearest doubles of `v` (ties to even).
pub fn nearest(v: &[BigRational]) -> Vec<f64> {
    v.iter().map(Scalar::to_f64_lossy).collect()
}
