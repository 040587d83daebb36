//! `sticky.Scene.from_macro`: a `[macro]` scene from Python values, built
//! by the library's [`sticky::scene::macro_data`] (the checks and limits of
//! a TOML `[macro]` table) with the numbers read as `Scene` reads them
//! ([`convert::exact`]).

use std::sync::Arc;

use num_rational::BigRational;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};
use sticky::quantile::{Block, BlockVelocity};
use sticky::scene::Scene as SceneFile;

use crate::convert;
use crate::errors::{self, py_error};
use crate::scene::{Inner, Scene};

/// The keys of a block given as a dict, in the order of a tuple.
const KEYS: [&str; 4] = ["from", "to", "density", "velocity"];

/// The items of a sequence that is not a string, or None.
fn items<'py>(obj: &Bound<'py, PyAny>) -> Option<Vec<Bound<'py, PyAny>>> {
    if obj.is_instance_of::<PyString>() {
        return None;
    }
    obj.try_iter().ok()?.collect::<PyResult<_>>().ok()
}

/// One block: a `(from, to, density, velocity)` sequence or a dict with
/// those keys; the velocity a number or a pair `(a, b)`. Errors name
/// `blocks[k]`.
fn block(obj: &Bound<'_, PyAny>, what: &str) -> PyResult<Block> {
    let py = obj.py();
    let shape = || {
        let message = format!(
            "{what}: a (from, to, density, velocity) tuple or a dict with those keys is needed"
        );
        errors::argument(py, what, message)
    };
    let values: Vec<Bound<'_, PyAny>> = if let Ok(d) = obj.cast::<PyDict>() {
        let mut unknown = Vec::new();
        for key in d.keys() {
            let known = key
                .extract::<String>()
                .is_ok_and(|k| KEYS.contains(&k.as_str()));
            if !known {
                unknown.push(key.repr()?.to_string());
            }
        }
        if !unknown.is_empty() {
            let message = format!("{what}: unknown keys [{}]", unknown.join(", "));
            return Err(errors::argument(py, what, message));
        }
        KEYS.iter()
            .map(|k| {
                d.get_item(k)?
                    .ok_or_else(|| errors::argument(py, what, format!("{what}: missing key {k:?}")))
            })
            .collect::<PyResult<_>>()?
    } else {
        items(obj).ok_or_else(shape)?
    };
    let [from, to, density, velocity] = values.as_slice() else {
        return Err(shape());
    };
    let field = |key: &str| format!("{what}.{key}");
    let number = |v: &Bound<'_, PyAny>, key: &str| convert::exact(v, &field(key));
    let velocity = match items(velocity) {
        Some(pair) => match pair.as_slice() {
            [a, b] => BlockVelocity::Affine(
                convert::exact(a, &format!("{what}.velocity[0]"))?,
                convert::exact(b, &format!("{what}.velocity[1]"))?,
            ),
            _ => {
                let what = field("velocity");
                let message = format!("{what}: a number or a pair (a, b) is needed");
                return Err(errors::argument(py, &what, message));
            }
        },
        None => BlockVelocity::Constant(number(velocity, "velocity")?),
    };
    Ok(Block {
        from: number(from, "from")?,
        to: number(to, "to")?,
        density: number(density, "density")?,
        velocity,
    })
}

/// Scene.from_macro(particles, blocks, *, name=None, t_end=None) -> Scene
///
/// A [macro] scene (docs/guide/scenes.md): a piecewise constant density
/// rho0 of blocks, sampled with N = `particles` at the quantiles (x0_i =
/// X0(i/N), u0_i = U0(i/N), 2r = 1/N: the paper's thm:main). `blocks`
/// lists, left to right, (from, to, density, velocity) tuples or dicts with
/// those keys; the block is [from, to), density in (0, 1], the masses add
/// up to exactly 1; velocity is a number, or a pair (a, b) for u0 affine
/// from a at `from` to b at `to` (only where density < 1). Numbers are
/// read as Scene reads them (ints, Fractions, floats as their exact binary
/// value, exact strings; bools refused). The checks and messages of the
/// [macro] section of a TOML file (sticky.MacroError and its kin).
#[pyfunction]
#[pyo3(signature = (particles, blocks, *, name=None, t_end=None))]
pub fn from_macro(
    py: Python<'_>,
    particles: &Bound<'_, PyAny>,
    blocks: &Bound<'_, PyAny>,
    name: Option<String>,
    t_end: Option<&Bound<'_, PyAny>>,
) -> PyResult<Scene> {
    let n = convert::count(particles, "particles")?;
    let list = items(blocks).ok_or_else(|| {
        let message = "blocks: a sequence of blocks (from, to, density, velocity) is needed";
        errors::argument_type(py, "blocks", message.to_string())
    })?;
    let blocks = list
        .iter()
        .enumerate()
        .map(|(k, b)| block(b, &convert::entry("blocks", k)))
        .collect::<PyResult<Vec<_>>>()?;
    let t_end: Option<BigRational> = t_end.map(|t| convert::exact(t, "t_end")).transpose()?;
    if let Some(t) = &t_end {
        if t < &BigRational::from_integer(0.into()) {
            let message = format!("t_end = {} is negative", convert::shown(t));
            return Err(errors::argument(py, "t_end", message));
        }
    }
    let (kind, data) = py
        .detach(|| sticky::scene::macro_data(blocks, n))
        .map_err(py_error)?;
    let file = SceneFile {
        name,
        description: None,
        t_end,
        kind,
        data,
    };
    Ok(Scene {
        inner: Arc::new(py.detach(|| Inner::from_scene(file))),
    })
}
