//! `sticky.Scene`: initial data `(x⁰, u⁰, r)`, validated as the command
//! line validates them (`df:KN`, `def:velcone`), and the exact answers for
//! them: the state at any time (`prop:proj-micro`), the collision events,
//! the projection onto `K` (`df:KN`).
//!
//! Three paths, one answer. Columns of doubles (numpy arrays, lists of
//! `float`) go the library's dyadic path ([`sticky::fast::dyadic`]: `i128`
//! columns over dyadic scales, the kernel's PAVA, one rounding per value
//! with no big number); other data on machine words (small fractions) go
//! the library's streaming path ([`sticky::fast::stream`]:
//! `i64` columns, the integer kernel's PAVA, values in lowest terms on
//! words); anything else — and the streaming path's refusals (a value off
//! words, a time beyond its bound, invalid data, whose error of record the
//! general path names) — goes the general path ([`sticky::fast::engine`]'s
//! cheapest exact engine on the validated `BigRational` data).

use std::path::PathBuf;
use std::sync::{Arc, OnceLock};

use num_rational::BigRational;
use numpy::PyArray1;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyList;
use sticky::fast::dyadic::Dyadic;
use sticky::fast::engine;
use sticky::fast::kernel::{self, IntegerData};
use sticky::fast::stream::Lean;
use sticky::progress::Progress;
use sticky::scene::{Scene as SceneFile, SceneKind};
use sticky::{Error, InitialData};

use crate::convert::{self, Column};
use crate::events::Event;
use crate::interrupt;
use crate::state::{Answer, State};

pub use crate::errors::py_error;

/// Where the general path's data come from when they are built lazily.
enum Source {
    /// Already built (`Inner::general` is set).
    Built,
    /// Doubles of a numpy array, kept until the general path needs them.
    Doubles {
        radius: Option<BigRational>,
        positions: Vec<f64>,
        velocities: Vec<f64>,
    },
    /// A scene file the streaming path read.
    File(PathBuf),
}

/// Everything a scene holds, shared with the worker threads.
pub struct Inner {
    dyadic: Option<Dyadic>,
    lean: Option<Lean>,
    source: Source,
    general: OnceLock<SceneFile>,
    scaled: OnceLock<IntegerData>,
}

impl Inner {
    /// A scene from validated data (the general path), and the streaming
    /// path when its values are on words.
    pub(crate) fn from_scene(scene: SceneFile) -> Inner {
        let lean = Lean::from_data(&scene.data);
        let general = OnceLock::new();
        let _ = general.set(scene);
        Inner {
            dyadic: None,
            lean,
            source: Source::Built,
            general,
            scaled: OnceLock::new(),
        }
    }

    /// The validated scene of the general path, built on first use.
    pub fn scene(&self) -> Result<&SceneFile, Error> {
        if let Some(s) = self.general.get() {
            return Ok(s);
        }
        let built = match &self.source {
            // `Inner::from_scene` sets `general` with `Source::Built`.
            Source::Built => {
                return Err(Error::Unsupported {
                    message: "a built scene without its data (a bug in sticky: please report it)"
                        .into(),
                })
            }
            Source::Doubles {
                radius,
                positions,
                velocities,
            } => {
                let exact = |v: &[f64]| -> Result<Vec<BigRational>, Error> {
                    v.iter()
                        .map(|&d| {
                            sticky::columns::f64_exact(d).ok_or_else(|| Error::Unsupported {
                                message: format!("{d} is not a finite number"),
                            })
                        })
                        .collect()
                };
                let (x, u) = (exact(positions)?, exact(velocities)?);
                let data = match radius {
                    Some(r) => InitialData::new(r.clone(), x, u)?,
                    None => InitialData::with_paper_radius(x, u)?,
                };
                particles(data)
            }
            Source::File(path) => sticky::scene::load(path)?,
        };
        Ok(self.general.get_or_init(|| built))
    }

    /// The data scaled to integers once, for the integer kernel.
    fn scaled(&self) -> Result<&IntegerData, Error> {
        if let Some(s) = self.scaled.get() {
            return Ok(s);
        }
        let data = &self.scene()?.data;
        engine::check_work(data)?;
        Ok(self.scaled.get_or_init(|| IntegerData::new(data)))
    }

    /// The radius r.
    pub fn radius(&self) -> Result<BigRational, Error> {
        if let Some(d) = &self.dyadic {
            return Ok(d.radius().clone());
        }
        match &self.lean {
            Some(l) => Ok(l.radius().clone()),
            None => Ok(self.scene()?.data.radius().clone()),
        }
    }

    /// N.
    pub fn n(&self) -> Result<usize, Error> {
        if let Some(d) = &self.dyadic {
            return Ok(d.n());
        }
        match &self.lean {
            Some(l) => Ok(l.n()),
            None => Ok(self.scene()?.n()),
        }
    }

    /// The exact state at `t`: the dyadic path's or the streaming path's
    /// blocks when they answer, the blockwise projection otherwise (the same
    /// state: the library's tests compare them), which polls `stop` and
    /// ends with [`Error::Interrupted`] on Ctrl-C.
    pub fn answer(&self, t: &BigRational, stop: &dyn Progress) -> Result<Answer, Error> {
        if let Some(blocks) = self.dyadic.as_ref().and_then(|d| d.blocks_at(t)) {
            return Answer::from_dyadic(blocks, stop);
        }
        if let Some(blocks) = self.lean.as_ref().and_then(|l| l.blocks_at(t)) {
            return Ok(Answer::from_blocks(&blocks));
        }
        let data = &self.scene()?.data;
        engine::check_work_watched(data, &engine::Blockwise)?;
        let state = sticky::blockwise::state_at(data, t, stop)?;
        Answer::from_state(state, stop)
    }

    /// The exact state at `t`, every value a `BigRational` (for the exact
    /// lists a `State` gives on demand).
    pub fn exact(&self, t: &BigRational) -> Result<sticky::State<BigRational>, Error> {
        if let Some(blocks) = self.dyadic.as_ref().and_then(|d| d.blocks_at(t)) {
            return Ok(blocks.exact_state());
        }
        if let Some(blocks) = self.lean.as_ref().and_then(|l| l.blocks_at(t)) {
            return Ok(crate::state::exact_state(&blocks));
        }
        kernel::state_at(self.scaled()?, t)
    }
}

/// A `[particles]` scene with no name around `data`.
fn particles(data: InitialData<BigRational>) -> SceneFile {
    SceneFile {
        name: None,
        description: None,
        t_end: None,
        kind: SceneKind::Particles,
        data,
    }
}

/// N particles on a line, of radius r, with their initial positions and
/// velocities: validated on construction, exact answers on demand.
#[pyclass(module = "sticky", frozen)]
pub struct Scene {
    pub(crate) inner: Arc<Inner>,
}

impl Scene {
    fn wrap(inner: Inner) -> Scene {
        Scene {
            inner: Arc::new(inner),
        }
    }

    /// The validated scene of the general path (built now if needed).
    pub fn file(&self, py: Python<'_>) -> PyResult<&SceneFile> {
        let inner = &self.inner;
        py.detach(|| inner.scene()).map_err(py_error)
    }
}

#[pymethods]
impl Scene {
    /// Scene(positions, velocities, radius=None)
    ///
    /// positions, velocities: numpy arrays or sequences of numbers, each
    /// read exactly (a float as the binary value of the double, an int, a
    /// fractions.Fraction, or an exact string such as "1/3"). radius: the
    /// same kinds; None means the paper's 2r = 1/N. Raises ValueError with
    /// the command line's message on a length mismatch, an overlap
    /// (x[i+1] - x[i] < 2r), a velocity outside the cone (particles in
    /// contact that approach), a NaN or an infinity.
    #[new]
    #[pyo3(signature = (positions, velocities, radius=None))]
    fn new(
        py: Python<'_>,
        positions: &Bound<'_, PyAny>,
        velocities: &Bound<'_, PyAny>,
        radius: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Scene> {
        let radius = radius.map(|r| convert::exact(r, "radius")).transpose()?;
        let x = convert::column(positions, "positions")?;
        let u = convert::column(velocities, "velocities")?;
        if x.len() != u.len() {
            return Err(py_error(Error::LengthMismatch {
                positions: x.len(),
                velocities: u.len(),
            }));
        }
        if let (Column::Doubles(xs), Column::Doubles(us)) = (&x, &u) {
            let paths = py.detach(|| match Dyadic::from_doubles(radius.clone(), xs, us) {
                Some(d) => Some((Some(d), None)),
                None => Lean::from_doubles(radius.clone(), xs, us).map(|l| (None, Some(l))),
            });
            if let Some((dyadic, lean)) = paths {
                let (Column::Doubles(positions), Column::Doubles(velocities)) = (x, u) else {
                    return Err(PyValueError::new_err("unreachable: columns of doubles"));
                };
                return Ok(Scene::wrap(Inner {
                    dyadic,
                    lean,
                    source: Source::Doubles {
                        radius,
                        positions,
                        velocities,
                    },
                    general: OnceLock::new(),
                    scaled: OnceLock::new(),
                }));
            }
        }
        let (x, u) = (x.into_exact("positions")?, u.into_exact("velocities")?);
        let data = py
            .detach(|| match radius {
                Some(r) => InitialData::new(r, x, u),
                None => InitialData::with_paper_radius(x, u),
            })
            .map_err(py_error)?;
        Ok(Scene::wrap(
            py.detach(|| Inner::from_scene(particles(data))),
        ))
    }

    /// Scene.load(path): a scene file, as `sticky run` reads it — TOML with
    /// [particles] (inline, or `data = "x.csv"` / `"x.npy"` beside it) or
    /// [macro] (the quantile sampling of a macroscopic datum). OSError when
    /// the file cannot be read, ValueError with the command line's message
    /// when it is not a valid scene.
    #[staticmethod]
    fn load(py: Python<'_>, path: PathBuf) -> PyResult<Scene> {
        let inner = py.detach(|| -> Result<Inner, Error> {
            if let Some(lean) = Lean::load(&path) {
                return Ok(Inner {
                    dyadic: None,
                    lean: Some(lean),
                    source: Source::File(path),
                    general: OnceLock::new(),
                    scaled: OnceLock::new(),
                });
            }
            Ok(Inner::from_scene(sticky::scene::load(&path)?))
        });
        Ok(Scene::wrap(inner.map_err(py_error)?))
    }

    /// Scene.from_toml(text): a scene from the text of a TOML scene file
    /// ([particles] with inline values, or [macro]); ValueError with the
    /// command line's message when it is not valid.
    #[staticmethod]
    fn from_toml(py: Python<'_>, text: &str) -> PyResult<Scene> {
        let scene = py.detach(|| sticky::scene::parse(text)).map_err(py_error)?;
        Ok(Scene::wrap(py.detach(|| Inner::from_scene(scene))))
    }

    /// The number of particles N.
    #[getter]
    fn n(&self, py: Python<'_>) -> PyResult<usize> {
        let inner = &self.inner;
        py.detach(|| inner.n()).map_err(py_error)
    }

    fn __len__(&self, py: Python<'_>) -> PyResult<usize> {
        self.n(py)
    }

    /// The radius r, exact (fractions.Fraction).
    #[getter]
    fn radius<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let inner = &self.inner;
        let r = py.detach(|| inner.radius()).map_err(py_error)?;
        convert::fraction(py, &r)
    }

    /// The scene's `name` field (None when it has none).
    #[getter]
    fn name(&self, py: Python<'_>) -> PyResult<Option<String>> {
        Ok(self.file(py)?.name.clone())
    }

    /// "particles" or "macro": where the initial data came from.
    #[getter]
    fn kind(&self, py: Python<'_>) -> PyResult<&'static str> {
        Ok(match self.file(py)?.kind {
            SceneKind::Macro { .. } => "macro",
            _ => "particles",
        })
    }

    /// The initial positions x⁰ as a numpy float64 array (nearest doubles).
    #[getter]
    fn positions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        if let Source::Doubles { positions, .. } = &self.inner.source {
            return Ok(PyArray1::from_slice(py, positions));
        }
        let v = convert::nearest(self.file(py)?.data.positions());
        Ok(PyArray1::from_vec(py, v))
    }

    /// The initial velocities u⁰ as a numpy float64 array (nearest doubles).
    #[getter]
    fn velocities<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        if let Source::Doubles { velocities, .. } = &self.inner.source {
            return Ok(PyArray1::from_slice(py, velocities));
        }
        let v = convert::nearest(self.file(py)?.data.velocities());
        Ok(PyArray1::from_vec(py, v))
    }

    /// The initial positions x⁰, exact: a list of fractions.Fraction.
    fn exact_positions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        convert::fractions(py, self.file(py)?.data.positions())
    }

    /// The initial velocities u⁰, exact: a list of fractions.Fraction.
    fn exact_velocities<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        convert::fractions(py, self.file(py)?.data.velocities())
    }

    /// state(t) -> State: the exact state at time t ≥ 0 (a float read as
    /// its exact binary value, an int, a Fraction or an exact string):
    /// x(t) = P_K(x⁰ + t u⁰), u(t) = P_{H_x(t)}(u⁰), the multipliers λ and
    /// the contact clusters (`prop:proj-micro`). ValueError for t < 0.
    /// The GIL is released while it runs; Ctrl-C interrupts it.
    fn state(&self, py: Python<'_>, t: &Bound<'_, PyAny>) -> PyResult<State> {
        let t = convert::exact(t, "t")?;
        let mut states = self.answers(py, vec![t])?;
        states
            .pop()
            .ok_or_else(|| PyValueError::new_err("no state"))
    }

    /// states(ts) -> list[State]: state(t) for every t of ts.
    fn states(&self, py: Python<'_>, ts: &Bound<'_, PyAny>) -> PyResult<Vec<State>> {
        let times = convert::column(ts, "ts")?.into_exact("ts")?;
        self.answers(py, times)
    }

    /// events() -> list[Event]: every cluster formed by a collision, sorted
    /// by time then by its first particle (indices from 0), with the sizes
    /// of the clusters that merged into it (the data of `sticky events`).
    fn events(&self, py: Python<'_>) -> PyResult<Vec<Event>> {
        let inner = Arc::clone(&self.inner);
        let impulses = interrupt::run(py, move |stop| -> Result<_, Error> {
            let data = &inner.scene()?.data;
            engine::check_work_watched(data, &engine::Merge)?;
            Ok(sticky::fast::merge::trajectory_with_progress(data, stop)?
                .impulses()
                .to_vec())
        })?
        .map_err(py_error)?;
        Ok(impulses.iter().map(Event::from_impulse).collect())
    }

    /// project(z, exact=False): the exact projection P_K(z) of an arbitrary
    /// array z onto K = {x : x[i+1] - x[i] ≥ 2r} (`df:KN`), with this
    /// scene's radius: a numpy float64 array of the nearest doubles, or a
    /// list of fractions.Fraction when exact=True.
    #[pyo3(signature = (z, exact=false))]
    fn project<'py>(
        &self,
        py: Python<'py>,
        z: &Bound<'py, PyAny>,
        exact: bool,
    ) -> PyResult<Bound<'py, PyAny>> {
        let z = convert::column(z, "z")?.into_exact("z")?;
        let n = self.n(py)?;
        if z.len() != n {
            let message = format!(
                "z has {} values but the scene has N = {n} particles",
                z.len()
            );
            return Err(crate::errors::argument(py, "z", message));
        }
        let inner = &self.inner;
        let r = py.detach(|| inner.radius()).map_err(py_error)?;
        let two_r = &r + &r;
        let x = interrupt::run_sized(py, n, move |_| sticky::projection::project_k(&z, &two_r))?;
        crate::isotonic::output(py, &x, exact)
    }

    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        let n = self.n(py)?;
        let inner = &self.inner;
        let r = py.detach(|| inner.radius()).map_err(py_error)?;
        Ok(format!("Scene(n={n}, radius={})", convert::shown(&r)))
    }
}

impl Scene {
    /// The states at `times`, on a worker thread (GIL released, Ctrl-C).
    fn answers(&self, py: Python<'_>, times: Vec<BigRational>) -> PyResult<Vec<State>> {
        let steps = self.n(py)?.saturating_mul(times.len());
        let inner = Arc::clone(&self.inner);
        let answers = interrupt::run_sized(py, steps, move |stop| -> Result<Vec<Answer>, Error> {
            let mut out = Vec::with_capacity(times.len());
            for t in &times {
                if stop.cancelled() {
                    break;
                }
                out.push(inner.answer(t, stop)?);
            }
            Ok(out)
        })?
        .map_err(py_error)?;
        answers
            .into_iter()
            .map(|a| State::new(py, Arc::clone(&self.inner), a))
            .collect()
    }
}
