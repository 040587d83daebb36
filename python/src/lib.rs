//! The native part of the `sticky` Python package (`sticky._sticky`):
//! bindings of the library's public API — no engine or metric code of its
//! own (docs/guide/architecture.md).
//!
//! * [`scene`] — `Scene`: input, validation, the state at t, events, P_K;
//! * [`state`] — `State`: nearest doubles at once, exact values on demand;
//! * [`states`] — `States`: the states at several times, each computed on first read;
//! * [`events`] — `Event`;
//! * [`isotonic`] — exact isotonic regression;
//! * [`macro_scene`] — `Scene.from_macro`, through the library's `[macro]` checks;
//! * [`compare`] — another solver's answer against the exact one;
//! * [`convert`] — Python numbers to exact rationals and back;
//! * [`errors`] — the library's errors as `sticky.errors` exceptions;
//! * [`interrupt`] — long work off the interpreter's thread (GIL, Ctrl-C).

mod compare;
mod convert;
mod errors;
mod events;
mod interrupt;
mod isotonic;
mod macro_scene;
mod scene;
mod state;
mod states;

use pyo3::prelude::*;
use sticky::claims::ledger::{self, Budget};

/// Text as Python's `json.loads` reads it.
fn json_loads<'py>(py: Python<'py>, text: &str) -> PyResult<Bound<'py, PyAny>> {
    py.import("json")?.call_method1("loads", (text,))
}

/// claims(cases=200, max_n=24, scaling_max_n=4096, seed=0x5EED) ->
/// list[dict]: the ledger of the paper's claims, each checked now as
/// `sticky claims --json` checks it (id, section, statement, status,
/// cases, engines, witness, correction). The default budget takes about a
/// minute; the GIL is released, Ctrl-C returns at once.
#[pyfunction]
#[pyo3(signature = (cases=None, max_n=None, scaling_max_n=None, seed=None))]
fn claims<'py>(
    py: Python<'py>,
    cases: Option<&Bound<'py, PyAny>>,
    max_n: Option<&Bound<'py, PyAny>>,
    scaling_max_n: Option<&Bound<'py, PyAny>>,
    seed: Option<&Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    let count =
        |v: Option<&Bound<'py, PyAny>>, name: &str| v.map(|v| convert::count(v, name)).transpose();
    let (cases, max_n) = (count(cases, "cases")?, count(max_n, "max_n")?);
    let scaling_max_n = count(scaling_max_n, "scaling_max_n")?;
    let seed = count(seed, "seed")?.map(|s| s as u64);
    let budget = Budget::asked(cases, max_n, scaling_max_n, seed);
    // The ledger stops between claims once Ctrl-C is pressed (its partial
    // answer is dropped: the caller already has KeyboardInterrupt).
    let text = interrupt::run(py, move |stop| ledger::json(&ledger::run(budget, stop)))?;
    json_loads(py, &text)
}

/// export(scene) -> dict: the scene's data rounded to doubles, as `sticky
/// export --format json` writes them (each value's exact string, its double
/// and the rounding error). ValueError when a value is beyond the range of
/// a double.
#[pyfunction]
fn export<'py>(py: Python<'py>, scene: &scene::Scene) -> PyResult<Bound<'py, PyAny>> {
    let file = scene.file(py)?;
    let text = py
        .detach(|| {
            sticky::report::export::export(file).map(|e| sticky::report::export::json(file, &e))
        })
        .map_err(|e| errors::raise(py, "UnsupportedError", e.to_string(), vec![]))?;
    json_loads(py, &text)
}

/// The module `sticky._sticky`.
#[pymodule]
fn _sticky(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_class::<scene::Scene>()?;
    m.add_class::<state::State>()?;
    m.add_class::<states::States>()?;
    m.add_class::<events::Event>()?;
    m.add_class::<compare::CompareReport>()?;
    m.add_class::<compare::FrameFigures>()?;
    m.add_function(wrap_pyfunction!(compare::compare, m)?)?;
    m.add_function(wrap_pyfunction!(isotonic::isotonic, m)?)?;
    m.add_function(wrap_pyfunction!(macro_scene::from_macro, m)?)?;
    m.add_function(wrap_pyfunction!(claims, m)?)?;
    m.add_function(wrap_pyfunction!(export, m)?)?;
    Ok(())
}
