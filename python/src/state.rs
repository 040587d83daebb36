//! `sticky.State`: the state at one time, as numpy arrays of the nearest
//! doubles and as exact `fractions.Fraction` lists on demand.
//!
//! On the dyadic path only the positions are rounded when the state is
//! made (they are what a projection gives); the velocities and the
//! multipliers are rounded from the kept blocks on first access, then
//! cached.

use std::sync::{Arc, OnceLock};

use num_rational::BigRational;
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use sticky::cluster::Cluster;
use sticky::fast::dyadic::DyadicBlocks;
use sticky::fast::filter::{Filtered, Partition};
use sticky::fast::stream::LeanBlocks;
use sticky::progress::Progress;
use sticky::Error;

use crate::scene::{py_error, Inner};
use crate::{bulk, convert, interrupt};

/// What an engine answered at one time: the nearest doubles of the
/// positions (and of the rest when they came with them), the clusters (or
/// the dyadic path's blocks to find them later), the dyadic path's blocks to
/// round the rest from later, and the exact state when the engine gave it
/// whole.
pub struct Answer {
    t: BigRational,
    positions: Vec<f64>,
    velocities: Option<Vec<f64>>,
    multipliers: Option<Vec<f64>>,
    /// `None`: found from `blocks` (or the exact state) on first use.
    clusters: Option<Vec<Cluster>>,
    blocks: Option<Kept>,
    exact: Option<sticky::State<BigRational>>,
}

/// What a fast path left to compute the velocities, multipliers and
/// clusters from on first use.
pub enum Kept {
    /// The dyadic path's blocks.
    Dyadic(DyadicBlocks),
    /// The filter's certified partition.
    Filtered(Filtered),
    /// The filter's certified partition of a scene's private columns
    /// (read from the scene when needed).
    Partition(Partition),
}

impl Kept {
    /// The nearest doubles of `which` (`None`: beyond machine words, the
    /// exact state answers).
    fn rounded(&self, which: Later) -> Option<Vec<f64>> {
        match (self, which) {
            (Kept::Dyadic(b), Later::Velocities) => b.velocities(),
            (Kept::Dyadic(b), Later::Multipliers) => b.multipliers(),
            (Kept::Filtered(f), Later::Velocities) => Some(f.velocities()),
            (Kept::Filtered(f), Later::Multipliers) => Some(f.multipliers()),
            // Written from the scene's columns ([`State::partition_array`]).
            (Kept::Partition(_), _) => None,
        }
    }

    /// The contact clusters.
    fn clusters(&self) -> Vec<Cluster> {
        match self {
            Kept::Dyadic(b) => b.clusters(),
            Kept::Filtered(f) => f.clusters(),
            Kept::Partition(p) => p.clusters(),
        }
    }
}

impl Answer {
    /// The nearest doubles from the streaming path's blocks (the exact
    /// values are computed again when asked for).
    pub fn from_blocks(b: &LeanBlocks<'_>) -> Answer {
        let nearest = b.nearest();
        Answer {
            t: b.t().clone(),
            positions: nearest.positions,
            velocities: Some(nearest.velocities),
            multipliers: Some(nearest.multipliers),
            clusters: Some(b.clusters()),
            blocks: None,
            exact: None,
        }
    }

    /// The filter's nearest doubles of the positions; its partition is kept
    /// for the rest.
    pub fn from_filtered(mut f: Filtered) -> Answer {
        Answer {
            t: f.t().clone(),
            positions: f.take_positions(),
            velocities: None,
            multipliers: None,
            clusters: None,
            blocks: Some(Kept::Filtered(f)),
            exact: None,
        }
    }

    /// The nearest doubles of the positions from the dyadic path's blocks,
    /// which are kept for the velocities and multipliers (the exact values
    /// are computed again when asked for); when an intermediate leaves
    /// `i128`, the exact state rounded (and kept).
    pub fn from_dyadic(b: DyadicBlocks, stop: &dyn Progress) -> Result<Answer, Error> {
        match b.positions() {
            Some(positions) => Ok(Answer {
                t: b.t().clone(),
                positions,
                velocities: None,
                multipliers: None,
                // A pass over the blocks a caller of `positions` need not
                // pay for: found on first use.
                clusters: None,
                blocks: Some(Kept::Dyadic(b)),
                exact: None,
            }),
            None => Answer::from_state(b.exact_state(), stop),
        }
    }

    /// The nearest doubles of an exact state, which is kept.
    pub fn from_state(s: sticky::State<BigRational>, stop: &dyn Progress) -> Result<Answer, Error> {
        // Rounding big fractions is long work of its own: it polls `stop`
        // every `ROUNDING_CHUNK` values.
        let round = |v: &[BigRational]| -> Result<Vec<f64>, Error> {
            let mut out = Vec::with_capacity(v.len());
            for chunk in v.chunks(ROUNDING_CHUNK) {
                if stop.cancelled() {
                    return Err(Error::Interrupted {
                        during: "the rounding to doubles",
                    });
                }
                out.extend(convert::nearest(chunk));
            }
            Ok(out)
        };
        Ok(Answer {
            t: s.t.clone(),
            positions: round(&s.positions)?,
            velocities: Some(round(&s.velocities)?),
            multipliers: Some(round(&s.multipliers)?),
            clusters: Some(s.clusters.clone()),
            blocks: None,
            exact: Some(s),
        })
    }
}

/// Values rounded between two polls of [`Progress::cancelled`] on the
/// general path.
const ROUNDING_CHUNK: usize = 4096;

/// The state of the particles at one time t: positions x(t), velocities
/// u(t) (right derivatives: after the collisions at t), multipliers λ(t)
/// (λ_1 … λ_{N-1} of the paper's eq:dyn-micro; entry i belongs to the pair
/// (i, i+1), indices from 0) and contact clusters. `positions`,
/// `velocities`, `multipliers` are numpy float64 arrays of the nearest
/// doubles (the velocities and multipliers computed on first access);
/// `exact_positions()` and its siblings give the exact values. The arrays
/// are read-only (`writeable=False`): no call changes a state.
#[pyclass(module = "sticky", frozen)]
pub struct State {
    scene: Arc<Inner>,
    t: BigRational,
    positions: Py<PyArray1<f64>>,
    velocities: OnceLock<Py<PyArray1<f64>>>,
    multipliers: OnceLock<Py<PyArray1<f64>>>,
    /// Found on first use when the engine did not give them.
    clusters: OnceLock<Vec<Cluster>>,
    /// A fast path's blocks, for the arrays not yet computed.
    blocks: Option<Arc<Kept>>,
    exact: OnceLock<sticky::State<BigRational>>,
}

/// Which of the arrays rounded on first access.
#[derive(Debug, Clone, Copy)]
enum Later {
    /// u(t).
    Velocities,
    /// λ(t).
    Multipliers,
}

impl State {
    /// Wraps an engine's answer.
    pub fn new(py: Python<'_>, scene: Arc<Inner>, a: Answer) -> PyResult<State> {
        let exact = OnceLock::new();
        if let Some(s) = a.exact {
            let _ = exact.set(s);
        }
        let array = |v: Option<Vec<f64>>| -> PyResult<_> {
            let cell = OnceLock::new();
            if let Some(v) = v {
                let _ = cell.set(convert::read_only(py, v)?.unbind());
            }
            Ok(cell)
        };
        let clusters = OnceLock::new();
        if let Some(c) = a.clusters {
            let _ = clusters.set(c);
        }
        Ok(State {
            scene,
            t: a.t,
            positions: convert::read_only(py, a.positions)?.unbind(),
            velocities: array(a.velocities)?,
            multipliers: array(a.multipliers)?,
            clusters,
            blocks: a.blocks.map(Arc::new),
            exact,
        })
    }

    /// The state the filter proved, its positions already in `positions`
    /// (a numpy array of numpy's allocator, [`sticky::fast::filter::Doubles::at_into`]).
    pub fn filtered(
        scene: Arc<Inner>,
        positions: Bound<'_, PyArray1<f64>>,
        f: Filtered,
    ) -> PyResult<State> {
        let t = f.t().clone();
        State::proved(scene, positions, t, Kept::Filtered(f))
    }

    /// The state the filter proved on the private columns of `scene`, its
    /// positions already in `positions` (a numpy array of numpy's
    /// allocator, [`sticky::fast::filter::Checked::at_into`]).
    pub fn partitioned(
        scene: Arc<Inner>,
        positions: Bound<'_, PyArray1<f64>>,
        p: Partition,
    ) -> PyResult<State> {
        let t = p.t().clone();
        State::proved(scene, positions, t, Kept::Partition(p))
    }

    /// A state at `t` whose positions the filter wrote into `positions`
    /// (made read-only here), the other arrays found from `kept` on need.
    fn proved(
        scene: Arc<Inner>,
        positions: Bound<'_, PyArray1<f64>>,
        t: BigRational,
        kept: Kept,
    ) -> PyResult<State> {
        positions.getattr("flags")?.setattr("writeable", false)?;
        Ok(State {
            scene,
            t,
            positions: positions.unbind(),
            velocities: OnceLock::new(),
            multipliers: OnceLock::new(),
            clusters: OnceLock::new(),
            blocks: Some(Arc::new(kept)),
            exact: OnceLock::new(),
        })
    }

    /// The array `which` of a state the filter proved on the scene's
    /// private columns, written into an array of numpy's allocator from the
    /// scene's velocities (GIL released while it is filled); `None` when
    /// the scene keeps no such columns.
    fn partition_array<'py>(
        py: Python<'py>,
        scene: &Inner,
        p: &Partition,
        which: Later,
    ) -> PyResult<Option<Bound<'py, PyArray1<f64>>>> {
        let Some(private) = scene.private_columns(py) else {
            return Ok(None);
        };
        let u = private.velocities;
        let len = match which {
            Later::Velocities => p.n(),
            Later::Multipliers => p.n().saturating_sub(1),
        };
        let array = convert::empty(py, len)?;
        {
            let u = u.readonly();
            let u = u.as_slice()?;
            let mut rw = array.readwrite();
            let out = rw.as_slice_mut()?;
            py.detach(|| match which {
                Later::Velocities => p.write_velocities(u, out),
                Later::Multipliers => p.write_multipliers(u, out),
            });
        }
        array.getattr("flags")?.setattr("writeable", false)?;
        Ok(Some(array))
    }

    /// The array `which` of a filtered state, written into an array of
    /// numpy's allocator (GIL released while it is filled).
    fn filtered_array<'py>(
        py: Python<'py>,
        f: &Filtered,
        which: Later,
    ) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let len = match which {
            Later::Velocities => f.n(),
            Later::Multipliers => f.n().saturating_sub(1),
        };
        let array = convert::empty(py, len)?;
        {
            let mut rw = array.readwrite();
            let out = rw.as_slice_mut()?;
            py.detach(|| match which {
                Later::Velocities => f.write_velocities(out),
                Later::Multipliers => f.write_multipliers(out),
            });
        }
        array.getattr("flags")?.setattr("writeable", false)?;
        Ok(array)
    }

    /// The array `which`, rounded on first access (GIL released) from the
    /// kept blocks, or from the exact state when the blocks leave machine
    /// words; cached.
    fn later<'py>(&self, py: Python<'py>, which: Later) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let cell = match which {
            Later::Velocities => &self.velocities,
            Later::Multipliers => &self.multipliers,
        };
        if let Some(a) = cell.get() {
            return Ok(a.bind(py).clone());
        }
        if let Some(Kept::Filtered(f)) = self.blocks.as_deref() {
            let array = State::filtered_array(py, f, which)?.unbind();
            return Ok(cell.get_or_init(|| array).bind(py).clone());
        }
        if let Some(Kept::Partition(p)) = self.blocks.as_deref() {
            if let Some(array) = State::partition_array(py, &self.scene, p, which)? {
                let array = array.unbind();
                return Ok(cell.get_or_init(|| array).bind(py).clone());
            }
        }
        let blocks = &self.blocks;
        let rounded = py.detach(|| blocks.as_ref().and_then(|b| b.rounded(which)));
        let values = match rounded {
            Some(v) => v,
            None => {
                let s = self.exact(py)?;
                let v = match which {
                    Later::Velocities => &s.velocities,
                    Later::Multipliers => &s.multipliers,
                };
                py.detach(|| convert::nearest(v))
            }
        };
        let array = convert::read_only(py, values)?.unbind();
        Ok(cell.get_or_init(|| array).bind(py).clone())
    }

    /// The contact clusters: given by the engine, or found on first use
    /// (GIL released) from the kept blocks, else from the exact state.
    fn contact_clusters(&self, py: Python<'_>) -> PyResult<&[Cluster]> {
        if let Some(c) = self.clusters.get() {
            return Ok(c);
        }
        let blocks = &self.blocks;
        let found = match py.detach(|| blocks.as_deref().map(Kept::clusters)) {
            Some(c) => c,
            None => self.exact(py)?.clusters.clone(),
        };
        Ok(self.clusters.get_or_init(|| found))
    }

    /// The exact state, on first use: from the dyadic path's kept blocks
    /// (the same block sums, [`DyadicBlocks::exact_state`]), else computed
    /// again by the exact paths; on a worker thread (GIL released, Ctrl-C).
    pub fn exact(&self, py: Python<'_>) -> PyResult<&sticky::State<BigRational>> {
        if let Some(s) = self.exact.get() {
            return Ok(s);
        }
        let (scene, t) = (Arc::clone(&self.scene), self.t.clone());
        let blocks = self.blocks.clone();
        let n = self.n(py);
        let s = interrupt::run_sized(py, n, move |stop| match blocks.as_deref() {
            Some(Kept::Dyadic(b)) => Ok(b.exact_state()),
            _ => scene.exact(&t, stop),
        })?
        .map_err(py_error)?;
        Ok(self.exact.get_or_init(|| s))
    }
}

#[pymethods]
impl State {
    /// The time t, exact (fractions.Fraction).
    #[getter]
    fn t<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        convert::fraction(py, &self.t)
    }

    /// The scene this is a state of.
    #[getter]
    fn scene(&self) -> crate::scene::Scene {
        crate::scene::Scene {
            inner: Arc::clone(&self.scene),
        }
    }

    /// The number of particles N.
    #[getter]
    fn n(&self, py: Python<'_>) -> usize {
        self.positions.bind(py).len().unwrap_or(0)
    }

    /// x(t): numpy float64 array, the nearest double of each exact value.
    #[getter]
    fn positions<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.positions.bind(py).clone()
    }

    /// u(t) (right derivative): numpy float64 array of nearest doubles
    /// (computed on first access, then cached).
    #[getter]
    fn velocities<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        self.later(py, Later::Velocities)
    }

    /// λ(t), N - 1 values (entry i: the pair (i, i+1)): numpy float64
    /// array of nearest doubles (computed on first access, then cached).
    #[getter]
    fn multipliers<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        self.later(py, Later::Multipliers)
    }

    /// The contact clusters of x(t), left to right, as (first, size) pairs
    /// (first indexed from 0), as `run --json` gives them.
    #[getter]
    fn clusters(&self, py: Python<'_>) -> PyResult<Vec<(usize, usize)>> {
        let clusters = self.contact_clusters(py)?;
        Ok(clusters.iter().map(|c| (c.first, c.size)).collect())
    }

    /// x(t) exact: a list of fractions.Fraction.
    fn exact_positions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        bulk::fractions(py, &self.exact(py)?.positions)
    }

    /// u(t) exact: a list of fractions.Fraction.
    fn exact_velocities<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        bulk::fractions(py, &self.exact(py)?.velocities)
    }

    /// λ(t) exact: a list of N - 1 fractions.Fraction.
    fn exact_multipliers<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyList>> {
        bulk::fractions(py, &self.exact(py)?.multipliers)
    }

    /// The state as `sticky run --json` prints it: a dict with "n",
    /// "radius", "t", "positions", "velocities", "multipliers" (exact
    /// strings "p/q" in lowest terms) and "clusters" ([first, size],
    /// indices from 0).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let s = self.exact(py)?;
        let radius = self.scene.radius().map_err(py_error)?;
        state_dict(py, s, &radius)
    }

    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        let clusters = self.contact_clusters(py)?;
        let shown: Vec<String> = clusters
            .iter()
            .take(8)
            .map(|c| format!("({}, {})", c.first, c.size))
            .collect();
        let more = if clusters.len() > 8 { ", ..." } else { "" };
        Ok(format!(
            "State(t={}, n={}, clusters=[{}{more}])",
            convert::shown(&self.t),
            self.n(py),
            shown.join(", ")
        ))
    }
}

/// The dict `json.loads` makes of `sticky run --json`'s object
/// ([`sticky::report::json::StateJson`]: the same keys in the same order),
/// built directly: exact values as strings `"p/q"`, clusters as
/// `[first, size]` lists (Ctrl-C: `KeyboardInterrupt`).
fn state_dict<'py>(
    py: Python<'py>,
    s: &sticky::State<BigRational>,
    radius: &BigRational,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("n", s.positions.len())?;
    d.set_item("radius", sticky::rational::render_exact(radius))?;
    d.set_item("t", sticky::rational::render_exact(&s.t))?;
    d.set_item("positions", bulk::texts(py, &s.positions)?)?;
    d.set_item("velocities", bulk::texts(py, &s.velocities)?)?;
    d.set_item("multipliers", bulk::texts(py, &s.multipliers)?)?;
    let clusters: Vec<[usize; 2]> = s.clusters.iter().map(|c| [c.first, c.size]).collect();
    d.set_item("clusters", clusters)?;
    Ok(d)
}
