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
//! * [`bulk`] — many exact values at once: `Fraction` and string lists, dicts;
//! * [`errors`] — the library's errors as `sticky.errors` exceptions;
//! * [`interrupt`] — long work off the interpreter's thread (GIL, Ctrl-C).

mod bulk;
mod compare;
mod convert;
mod errors;
mod events;
mod interrupt;
mod isotonic;
mod macro_scene;
mod report_lists;
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
    let inner = std::sync::Arc::clone(&scene.inner);
    let n = py.detach(|| inner.n()).map_err(scene::py_error)?;
    let exported = interrupt::run_sized(py, n, move |stop| exported(&inner, stop))?;
    let e = exported.map_err(|e| errors::raise(py, "UnsupportedError", e, vec![]))?;
    Ok(bulk::export_dict(py, &e)?.into_any())
}

/// The export's object of `scene`: from its columns of doubles when it was
/// built from them ([`sticky::report::export::export_doubles`]), else from
/// the validated scene; the error's message otherwise.
fn exported(
    scene: &scene::Inner,
    stop: &dyn sticky::progress::Progress,
) -> Result<sticky::report::export::ExportJson, String> {
    use sticky::report::export::{export, export_doubles, ExportJson};
    if let Some((positions, velocities)) = scene.solver().doubles() {
        let radius = scene.radius().map_err(|e| e.to_string())?;
        let fast = export_doubles(&radius, positions, velocities, stop);
        if let Some(e) = fast.map_err(|e| e.to_string())? {
            return Ok(e);
        }
    }
    let file = scene.scene().map_err(|e| e.to_string())?;
    let e = export(file).map_err(|e| e.to_string())?;
    Ok(ExportJson::of(file, &e))
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
