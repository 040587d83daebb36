//! `sticky.Scene`: initial data `(x⁰, u⁰, r)`, validated as the command
//! line validates them (`df:KN`, `def:velcone`), and the exact answers for
//! them: the state at any time (`prop:proj-micro`), the collision events,
//! the projection onto `K` (`df:KN`).
//!
//! Every answer is the library's [`Solver`]'s, which chooses the path as
//! it does for the command line: the dyadic path for columns of doubles,
//! the streaming path on machine words, else the cost model's exact engine
//! on the validated `BigRational` data (the same answer every way).

use std::path::PathBuf;
use std::sync::{Arc, OnceLock};

use num_rational::BigRational;
use numpy::{PyArray1, PyArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyList;
use sticky::fast::filter::{Checked, Doubles};
use sticky::progress::Progress;
use sticky::scene::{Scene as SceneFile, SceneKind};
use sticky::solver::{Answer as Solved, Engine, Options, Solver, WorkCap};
use sticky::{Error, InitialData};

use crate::convert::{self, Column};
use crate::events::Event;
use crate::interrupt;
use crate::isotonic::Filtered;
use crate::state::{Answer, State};
use crate::states::States;

pub use crate::errors::py_error;

/// Everything a scene holds, shared with the worker threads: the library's
/// [`Solver`], which chooses the engine of every answer — built on first
/// need when the scene keeps its doubles in numpy arrays ([`Private`]).
pub struct Inner {
    held: Held,
}

/// How a scene holds its data.
enum Held {
    /// A Solver, built with the scene.
    Solver(Solver),
    /// Columns of doubles validated in place, the Solver built from them
    /// on first need.
    Private {
        columns: Private,
        solver: OnceLock<Solver>,
    },
}

/// A scene's own copies of its columns of doubles, in read-only arrays of
/// numpy's allocator that nothing else holds (they never change), validated
/// exactly ([`Checked`]): the certified filter runs on slices borrowed from
/// them, and the library's `Vec` columns are made only when an exact path
/// needs them (at `N = 10⁶`, 16 MB of fresh pages saved on construction).
struct Private {
    radius: Option<BigRational>,
    checked: Checked,
    positions: Py<PyArray1<f64>>,
    velocities: Py<PyArray1<f64>>,
}

impl Private {
    /// The Solver of these columns (copied into the library's vectors,
    /// the GIL taken for the copy: callers reach here without it or on
    /// the thread that holds it).
    fn solver(&self) -> Solver {
        let (x, u) = Python::attach(|py| {
            let x = self.positions.bind(py).readonly();
            let u = self.velocities.bind(py).readonly();
            (x.as_array().to_vec(), u.as_array().to_vec())
        });
        let d = Doubles::from_checked(self.checked.clone(), x, u);
        watched(Solver::from_filter(self.radius.clone(), d))
    }
}

/// `solver` with work that can be interrupted: only the hopeless is
/// refused.
fn watched(solver: Solver) -> Solver {
    solver.with_options(Options {
        work: WorkCap::Watched,
        ..Options::default()
    })
}

/// A scene's private columns ([`Inner::private_columns`]).
pub struct PrivateView<'a, 'py> {
    /// What their validation established.
    pub checked: &'a Checked,
    /// The positions.
    pub positions: &'a Bound<'py, PyArray1<f64>>,
    /// The velocities.
    pub velocities: &'a Bound<'py, PyArray1<f64>>,
}

impl Inner {
    /// A scene from validated data.
    pub(crate) fn from_scene(scene: SceneFile) -> Inner {
        Inner::new(Solver::from_scene(scene))
    }

    /// A scene answered by `solver` (work that can be interrupted: only
    /// the hopeless is refused).
    fn new(solver: Solver) -> Inner {
        Inner {
            held: Held::Solver(watched(solver)),
        }
    }

    /// The library's Solver of this scene.
    pub fn solver(&self) -> &Solver {
        match &self.held {
            Held::Solver(s) => s,
            Held::Private { columns, solver } => {
                if let Some(s) = solver.get() {
                    return s;
                }
                // Built outside the cell: the build takes the GIL, so a
                // thread holding the GIL must never wait on the cell
                // while the thread initializing it waits for the GIL. Two
                // threads may both build; the first stored is kept.
                let built = columns.solver();
                solver.get_or_init(|| built)
            }
        }
    }

    /// The scene's private columns of doubles, if it keeps them.
    pub fn private_columns<'a, 'py>(&'a self, py: Python<'py>) -> Option<PrivateView<'a, 'py>> {
        match &self.held {
            Held::Private { columns, .. } => Some(PrivateView {
                checked: &columns.checked,
                positions: columns.positions.bind(py),
                velocities: columns.velocities.bind(py),
            }),
            Held::Solver(_) => None,
        }
    }

    /// The validated scene of the general path, built on first use.
    pub fn scene(&self) -> Result<&SceneFile, Error> {
        self.solver().scene()
    }

    /// The radius r.
    pub fn radius(&self) -> Result<BigRational, Error> {
        match &self.held {
            Held::Private { columns, .. } => Ok(columns.checked.radius().clone()),
            Held::Solver(s) => s.radius().cloned(),
        }
    }

    /// N.
    pub fn n(&self) -> Result<usize, Error> {
        match &self.held {
            Held::Private { columns, .. } => Ok(columns.checked.n()),
            Held::Solver(s) => s.n(),
        }
    }

    /// The exact state at `t`, as the Solver's path left it, polling
    /// `stop` (Ctrl-C ends it with [`Error::Interrupted`]).
    pub fn answer(&self, t: &BigRational, stop: &dyn Progress) -> Result<Answer, Error> {
        match self.solver().state_with_progress(t, stop)? {
            Solved::Filtered(f) => Ok(Answer::from_filtered(f)),
            Solved::Dyadic(blocks) => Answer::from_dyadic(blocks, stop),
            Solved::Words(blocks) => Ok(Answer::from_blocks(&blocks)),
            solved => Answer::from_state(solved.into_state(), stop),
        }
    }

    /// The exact state at `t` by the exact paths, every value a
    /// `BigRational` (for the exact lists a `State` gives on demand),
    /// polling `stop` (Ctrl-C ends it with [`Error::Interrupted`]).
    pub fn exact(
        &self,
        t: &BigRational,
        stop: &dyn Progress,
    ) -> Result<sticky::State<BigRational>, Error> {
        Ok(self.solver().state_by_exact_paths(t, stop)?.into_state())
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
        // Refused: read again below, where the paths that take such
        // columns, or the error of record, are found.
        if let Some(private) = convert::private_columns(py, positions, velocities, radius.clone())?
        {
            return Ok(Scene::wrap(Inner {
                held: Held::Private {
                    columns: Private {
                        radius,
                        checked: private.checked,
                        positions: private.positions.unbind(),
                        velocities: private.velocities.unbind(),
                    },
                    solver: OnceLock::new(),
                },
            }));
        }
        let (x, u) = match convert::double_columns(py, positions, velocities) {
            Some((x, u)) => (Column::Doubles(x), Column::Doubles(u)),
            None => (
                convert::column(positions, "positions")?,
                convert::column(velocities, "velocities")?,
            ),
        };
        if x.len() != u.len() {
            return Err(py_error(Error::LengthMismatch {
                positions: x.len(),
                velocities: u.len(),
            }));
        }
        let (x, u) = match (x, u) {
            (Column::Doubles(xs), Column::Doubles(us)) => {
                let r = radius.clone();
                match py.detach(|| Solver::from_double_columns(r, xs, us)) {
                    Ok(solver) => return Ok(Scene::wrap(Inner::new(solver))),
                    Err(refused) => {
                        let refused = *refused;
                        (
                            Column::Doubles(refused.positions),
                            Column::Doubles(refused.velocities),
                        )
                    }
                }
            }
            other => other,
        };
        let (x, u) = (x.into_exact("positions")?, u.into_exact("velocities")?);
        let data = py
            .detach(|| match radius {
                Some(r) => InitialData::new(r, x, u),
                None => InitialData::with_paper_radius(x, u),
            })
            .map_err(py_error)?;
        Ok(Scene::wrap(
            py.detach(|| Inner::from_scene(SceneFile::particles(data))),
        ))
    }

    /// Scene.load(path): a scene file, as `sticky run` reads it — TOML with
    /// [particles] (inline, or `data = "x.csv"` / `"x.npy"` beside it) or
    /// [macro] (the quantile sampling of a macroscopic datum). OSError when
    /// the file cannot be read, ValueError with the command line's message
    /// when it is not a valid scene.
    #[staticmethod]
    fn load(py: Python<'_>, path: PathBuf) -> PyResult<Scene> {
        let inner = py.detach(|| Solver::load(&path).map(Inner::new));
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
        if let Some(private) = self.inner.private_columns(py) {
            return copy(private.positions);
        }
        if let Some((positions, _)) = self.inner.solver().doubles() {
            return Ok(PyArray1::from_slice(py, positions));
        }
        let v = convert::nearest(self.file(py)?.data.positions());
        Ok(PyArray1::from_vec(py, v))
    }

    /// The initial velocities u⁰ as a numpy float64 array (nearest doubles).
    #[getter]
    fn velocities<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        if let Some(private) = self.inner.private_columns(py) {
            return copy(private.velocities);
        }
        if let Some((_, velocities)) = self.inner.solver().doubles() {
            return Ok(PyArray1::from_slice(py, velocities));
        }
        let v = convert::nearest(self.file(py)?.data.velocities());
        Ok(PyArray1::from_vec(py, v))
    }

    /// The initial positions x⁰, exact: a list of fractions.Fraction.
    fn exact_positions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        crate::bulk::fractions(py, self.file(py)?.data.positions())
    }

    /// The initial velocities u⁰, exact: a list of fractions.Fraction.
    fn exact_velocities<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        crate::bulk::fractions(py, self.file(py)?.data.velocities())
    }

    /// state(t) -> State: the exact state at time t ≥ 0 (a float read as
    /// its exact binary value, an int, a Fraction or an exact string):
    /// x(t) = P_K(x⁰ + t u⁰), u(t) = P_{H_x(t)}(u⁰), the multipliers λ and
    /// the contact clusters (`prop:proj-micro`). ValueError for t < 0.
    /// The GIL is released while it runs; Ctrl-C interrupts it.
    fn state(&self, py: Python<'_>, t: &Bound<'_, PyAny>) -> PyResult<State> {
        let t = convert::exact(t, "t")?;
        if let Some(state) = self.filtered(py, &t)? {
            return Ok(state);
        }
        let mut states = self.answers(py, vec![t])?;
        states
            .pop()
            .ok_or_else(|| PyValueError::new_err("no state"))
    }

    /// states(ts) -> States: state(t) for every t of ts, as a sequence
    /// computed lazily (each state on first read, then kept); the times
    /// are read and checked now.
    fn states(&self, ts: &Bound<'_, PyAny>) -> PyResult<States> {
        let times = convert::column(ts, "ts")?.into_exact("ts")?;
        States::new(Arc::clone(&self.inner), times)
    }

    /// events() -> list[Event]: every cluster formed by a collision, sorted
    /// by time then by its first particle (indices from 0), with the sizes
    /// of the clusters that merged into it (the data of `sticky events`).
    fn events(&self, py: Python<'_>) -> PyResult<Vec<Event>> {
        let inner = Arc::clone(&self.inner);
        let collisions = interrupt::run(py, move |stop| -> Result<_, Error> {
            Ok(inner.solver().events(stop)?.collisions())
        })?
        .map_err(py_error)?;
        Ok(collisions.into_iter().map(Event::from_collision).collect())
    }

    /// explain() -> str: which engine answers this scene's states and why
    /// (N, the common denominator, each candidate's estimated cost): the
    /// line `sticky run --explain` prints.
    fn explain(&self, py: Python<'_>) -> PyResult<String> {
        let inner = &self.inner;
        py.detach(|| inner.solver().explain()).map_err(py_error)
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
        let n = self.n(py)?;
        let inner = Arc::clone(&self.inner);
        let radius = || py.detach(|| inner.radius()).map_err(py_error);
        let mut refused = false;
        if !exact && z.len().ok() == Some(n) {
            match crate::isotonic::filtered(py, z, &radius()?)? {
                Filtered::Proved(x) => return Ok(x.into_any()),
                Filtered::Refused => refused = true,
                Filtered::NotTried => {}
            }
        }
        let z = convert::column(z, "z")?;
        if z.len() != n {
            let message = format!(
                "z has {} values but the scene has N = {n} particles",
                z.len()
            );
            return Err(crate::errors::argument(py, "z", message));
        }
        if let (false, convert::Column::Doubles(d)) = (exact, &z) {
            if d.iter().all(|v| v.is_finite()) {
                return crate::isotonic::nearest_of_doubles(py, d.clone(), radius()?, refused);
            }
        }
        let z = z.into_exact("z")?;
        let x =
            interrupt::run_sized(py, n, move |_| inner.solver().project(&z))?.map_err(py_error)?;
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
    /// The state at `t` when the certified filter proves it, its positions
    /// written straight into a numpy array (numpy's allocator, GIL
    /// released: a few milliseconds at `N = 10⁶`, no worker thread);
    /// `None` when the filter does not answer (the Solver's paths then do).
    fn filtered(&self, py: Python<'_>, t: &BigRational) -> PyResult<Option<State>> {
        if let Some(private) = self.inner.private_columns(py) {
            let checked = private.checked;
            let positions = convert::empty(py, checked.n())?;
            let answer = {
                let (x, u) = (private.positions.readonly(), private.velocities.readonly());
                let (x, u) = (x.as_slice()?, u.as_slice()?);
                let mut rw = positions.readwrite();
                let out = rw.as_slice_mut()?;
                py.detach(|| checked.at_into(x, u, t, out))
            };
            return match answer {
                Some(p) => State::partitioned(Arc::clone(&self.inner), positions, p).map(Some),
                None => Ok(None),
            };
        }
        let solver = self.inner.solver();
        let Some(d) = solver.filter() else {
            return Ok(None);
        };
        if solver.options().engine != Engine::Auto {
            return Ok(None);
        }
        let positions = convert::empty(py, d.n())?;
        let answer = {
            let mut rw = positions.readwrite();
            let out = rw.as_slice_mut()?;
            py.detach(|| d.at_into(t, out))
        };
        match answer {
            Some(f) => State::filtered(Arc::clone(&self.inner), positions, f).map(Some),
            None => Ok(None),
        }
    }

    /// The states at `times`, on a worker thread (GIL released, Ctrl-C).
    fn answers(&self, py: Python<'_>, times: Vec<BigRational>) -> PyResult<Vec<State>> {
        states_at(py, &self.inner, times)
    }
}

/// A writable copy of one of a scene's private arrays (numpy's own copy).
fn copy<'py>(array: &Bound<'py, PyArray1<f64>>) -> PyResult<Bound<'py, PyArray1<f64>>> {
    Ok(array.call_method0("copy")?.cast_into::<PyArray1<f64>>()?)
}

/// The states of `scene` at `times`, on a worker thread (GIL released,
/// Ctrl-C).
pub(crate) fn states_at(
    py: Python<'_>,
    scene: &Arc<Inner>,
    times: Vec<BigRational>,
) -> PyResult<Vec<State>> {
    let steps = py
        .detach(|| scene.n())
        .map_err(py_error)?
        .saturating_mul(times.len());
    let inner = Arc::clone(scene);
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
        .map(|a| State::new(py, Arc::clone(scene), a))
        .collect()
}
