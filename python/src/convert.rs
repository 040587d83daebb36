//! Python numbers to exact rationals and back.
//!
//! Every input number is read exactly: a `float` (numpy's `float64`
//! included) as the binary rational the double is
//! ([`sticky::columns::f64_exact`]), an `int` or a `fractions.Fraction` as
//! itself, a string by the scene files' reader
//! ([`sticky::rational::parse_exact`]: `"1/3"`, `"0.125"`, `"1e-3"`). Every
//! output rational is a `fractions.Fraction`, every `float` output the
//! nearest double of the exact value.

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::Zero;
use numpy::PyReadonlyArray1;
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyFloat, PyList, PyString};
use sticky::columns::f64_exact;
use sticky::rational::parse_exact;
use sticky::Scalar;

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
        PyValueError::new_err(format!(
            "{what} is {d}: every value must be a finite number"
        ))
    })
}

/// One Python number as an exact rational; errors name `what`.
pub fn exact(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<BigRational> {
    if let Ok(s) = obj.cast::<PyString>() {
        let text = s.to_cow()?;
        return parse_exact(&text)
            .map_err(|e| PyValueError::new_err(format!("{what}: {text:?} is refused: {e}")));
    }
    if let Ok(f) = obj.cast::<PyFloat>() {
        return double(f.value(), what);
    }
    let ratio = |num: Bound<'_, PyAny>, den: Bound<'_, PyAny>| -> PyResult<BigRational> {
        let (num, den): (BigInt, BigInt) = (num.extract()?, den.extract()?);
        if den.is_zero() {
            return Err(PyValueError::new_err(format!("{what}: zero denominator")));
        }
        Ok(BigRational::new(num, den))
    };
    if obj.hasattr("numerator")? && obj.hasattr("denominator")? {
        return ratio(obj.getattr("numerator")?, obj.getattr("denominator")?);
    }
    if obj.hasattr("as_integer_ratio")? {
        // numpy's float32/float16, decimal.Decimal: their own exact ratio.
        let pair = obj.call_method0("as_integer_ratio").map_err(|_| {
            PyValueError::new_err(format!(
                "{what} is {} (not finite): every value must be a finite number",
                obj.repr().map(|r| r.to_string()).unwrap_or_default()
            ))
        })?;
        return ratio(pair.get_item(0)?, pair.get_item(1)?);
    }
    Err(PyTypeError::new_err(format!(
        "{what}: expected a float, an int, a fractions.Fraction or an exact string such as \"1/3\", got {}",
        obj.get_type().name()?
    )))
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
    if obj.is_instance_of::<PyString>() {
        return Err(PyTypeError::new_err(format!(
            "{name} must be a sequence of numbers, not a string"
        )));
    }
    let items: Vec<Bound<'_, PyAny>> = obj
        .try_iter()
        .map_err(|_| {
            PyTypeError::new_err(format!(
                "{name} must be a sequence of numbers (a list or a numpy array)"
            ))
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

/// The class `fractions.Fraction`.
pub fn fraction_class(py: Python<'_>) -> PyResult<Bound<'_, PyAny>> {
    py.import("fractions")?.getattr("Fraction")
}

/// `q` as a `fractions.Fraction`.
pub fn fraction<'py>(py: Python<'py>, q: &BigRational) -> PyResult<Bound<'py, PyAny>> {
    fraction_class(py)?.call1((q.numer().clone(), q.denom().clone()))
}

/// `v` as a list of `fractions.Fraction`.
pub fn fractions<'py>(py: Python<'py>, v: &[BigRational]) -> PyResult<Bound<'py, PyList>> {
    let class = fraction_class(py)?;
    let items = v
        .iter()
        .map(|q| class.call1((q.numer().clone(), q.denom().clone())))
        .collect::<PyResult<Vec<_>>>()?;
    PyList::new(py, items)
}

/// The nearest doubles of `v` (ties to even).
pub fn nearest(v: &[BigRational]) -> Vec<f64> {
    v.iter().map(Scalar::to_f64_lossy).collect()
}
