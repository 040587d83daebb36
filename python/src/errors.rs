//! The library's errors as the exceptions of `sticky.errors`
//! (`python/sticky/errors.py`): one class per kind of mistake, each a
//! `StickyError` and the built-in exception the same mistake raised before
//! (`ValueError`, `OSError`, `TypeError`), with the structured fields of
//! [`sticky::Error`] as attributes (indices from 0, exact values as
//! `fractions.Fraction`).

use pyo3::exceptions::PyKeyboardInterrupt;
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::PyModule;
use pyo3::IntoPyObjectExt;
use sticky::Error;

use crate::convert;

/// The module `sticky.errors`, imported once.
static MODULE: PyOnceLock<Py<PyModule>> = PyOnceLock::new();

/// An attribute of an exception: its name and its value.
pub struct Field<'py> {
    name: &'static str,
    value: PyResult<Bound<'py, PyAny>>,
}

impl<'py> Field<'py> {
    /// Any value Python can hold.
    pub fn new<T: IntoPyObject<'py>>(py: Python<'py>, name: &'static str, value: T) -> Self {
        Field {
            name,
            value: value.into_bound_py_any(py),
        }
    }

    /// An exact number written as the library writes it (`"p/q"`), as a
    /// `fractions.Fraction`.
    fn exact(py: Python<'py>, name: &'static str, text: &str) -> Self {
        Field {
            name,
            value: convert::fraction_class(py).and_then(|f| f.call1((text,))),
        }
    }
}

/// The exception `class` of `sticky.errors` with `message` and `fields`;
/// when that cannot be built, the reason why.
pub fn raise(py: Python<'_>, class: &str, message: String, fields: Vec<Field<'_>>) -> PyErr {
    let build = || -> PyResult<PyErr> {
        let module =
            MODULE.get_or_try_init(py, || Ok::<_, PyErr>(py.import("sticky.errors")?.unbind()))?;
        let exception = module.bind(py).getattr(class)?.call1((message,))?;
        for f in fields {
            exception.setattr(f.name, f.value?)?;
        }
        Ok(PyErr::from_value(exception))
    };
    build().unwrap_or_else(|e| e)
}

/// A number that is not a finite exact value, or a count out of range, at
/// `argument` (`positions[3]`): `sticky.ArgumentError`.
pub fn argument(py: Python<'_>, argument: &str, message: String) -> PyErr {
    let field = Field::new(py, "argument", argument);
    raise(py, "ArgumentError", message, vec![field])
}

/// An argument of the wrong kind at `argument`: `sticky.ArgumentTypeError`.
pub fn argument_type(py: Python<'_>, argument: &str, message: String) -> PyErr {
    let field = Field::new(py, "argument", argument);
    raise(py, "ArgumentTypeError", message, vec![field])
}

/// A library error as its exception (the GIL is taken if needed).
pub fn py_error(e: Error) -> PyErr {
    Python::attach(|py| error(py, e))
}

/// `text (≈ decimal)` for a long exact number written `"p/q"`.
fn shown(text: &str) -> String {
    convert::with_decimal(text)
}

/// A library error as its exception.
fn error(py: Python<'_>, e: Error) -> PyErr {
    let message = e.to_string();
    match e {
        Error::Io { .. } => raise(py, "SceneReadError", message, vec![]),
        Error::Toml { .. } | Error::SceneKind { .. } => {
            raise(py, "SceneFormatError", message, vec![])
        }
        Error::MissingField { field }
        | Error::UnknownField { field }
        | Error::WrongType { field, .. }
        | Error::Float { field, .. }
        | Error::Number { field, .. } => {
            let field = Field::new(py, "field", field);
            raise(py, "SceneFormatError", message, vec![field])
        }
        Error::DataFile { file, .. } => {
            let field = Field::new(py, "file", file);
            raise(py, "SceneFormatError", message, vec![field])
        }
        Error::LengthMismatch {
            positions,
            velocities,
        } => {
            let fields = vec![
                Field::new(py, "positions", positions),
                Field::new(py, "velocities", velocities),
            ];
            raise(py, "LengthMismatchError", message, fields)
        }
        Error::Overlap { i, gap, two_r } => {
            let (class, message) = if gap.starts_with('-') {
                (
                    "NotSortedError",
                    format!(
                        "positions[{j}] < positions[{i}]: the positions are not sorted (they must increase by at least 2r = {}; the gap is {})",
                        shown(&two_r),
                        shown(&gap),
                        j = i + 1
                    ),
                )
            } else {
                (
                    "OverlapError",
                    format!(
                        "positions[{i}] and positions[{j}] overlap: gap {} < 2r = {}",
                        shown(&gap),
                        shown(&two_r),
                        j = i + 1
                    ),
                )
            };
            let fields = vec![
                Field::new(py, "i", i),
                Field::exact(py, "gap", &gap),
                Field::exact(py, "two_r", &two_r),
            ];
            raise(py, class, message, fields)
        }
        Error::Approaching { i, left, right } => {
            let message = format!(
                "particles {i} and {j} (indices from 0) are in contact and approach each other: velocities[{i}] = {} > velocities[{j}] = {} (u⁰ outside the velocity cone)",
                shown(&left),
                shown(&right),
                j = i + 1
            );
            let fields = vec![
                Field::new(py, "i", i),
                Field::exact(py, "left", &left),
                Field::exact(py, "right", &right),
            ];
            raise(py, "VelocityConeError", message, fields)
        }
        Error::Density { block, .. } | Error::Block { block, .. } => {
            let field = Field::new(py, "block", block);
            raise(py, "MacroError", message, vec![field])
        }
        Error::Mass { .. } => raise(py, "MacroError", message, vec![]),
        Error::NegativeTime { t } => {
            let message = format!("time {} is negative", shown(&t));
            let field = Field::exact(py, "t", &t);
            raise(py, "NegativeTimeError", message, vec![field])
        }
        Error::WorkLimit { work, cap, .. } => {
            let fields = vec![Field::new(py, "work", work), Field::new(py, "cap", cap)];
            raise(py, "WorkLimitError", message, fields)
        }
        Error::Unsupported { .. } => raise(py, "UnsupportedError", message, vec![]),
        // The caller already has the KeyboardInterrupt of its Ctrl-C.
        Error::Interrupted { .. } => PyKeyboardInterrupt::new_err(message),
        // `NoParticles`, `NonPositiveRadius`, and what later versions add.
        _ => raise(py, "InvalidDataError", message, vec![]),
    }
}
