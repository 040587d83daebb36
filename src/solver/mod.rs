//! The one front door: a [`Solver`] is built from initial data (or a scene
//! file, or columns of doubles) and answers every question about them —
//! the state at a time ([`Solver::state`], `prop:proj-micro`), at many
//! times streamed to a sink ([`Solver::states`]), the collision history
//! ([`Solver::events`]), the projection onto `K` ([`Solver::project`],
//! `df:KN`) — choosing the engine itself. Callers never pick one: the
//! command line (`sticky run/events/check/compare`) and the Python package
//! ask the Solver and nothing else.
//!
//! The choice, in order, for [`Engine::Auto`] (the default):
//!
//! 0. the certified `f64` filter ([`crate::fast::filter`]) when the Solver
//!    was built from doubles with `2r` a double and `t` is a double: the
//!    PAVA in floating point with its partition proved optimal, or, when a
//!    check does not pass, nothing (the next path answers);
//! 1. the dyadic path ([`crate::fast::dyadic`]) when the Solver was built
//!    from doubles and the time is one it covers (every double `t` with a
//!    64-bit odd part);
//! 2. the streaming path on machine words ([`crate::fast::stream`]) when
//!    every value fits words and the time is within its bound;
//! 3. the cheapest exact engine of [`ENGINES`](crate::fast::engine::ENGINES)
//!    by the cost model ([`cost::Cost`]), after the work check
//!    ([`work`]); when the check refuses it, the blockwise projection on
//!    local denominators if its own check passes ([`choice::Choice`]).
//!
//! [`Engine::Forced`] skips 1 and 2 and runs the named engine alone.
//! [`Solver::explain`] says which engine the cost model chose and why (what
//! `sticky run --explain` prints). Every path gives the same exact answer:
//! the oracle battery ([`crate::fast::battery`]) runs every engine against
//! the generic projection, and the streaming tests compare the paths byte
//! for byte.
//!
//! ```
//! use num_rational::BigRational;
//! use sticky::solver::Solver;
//! use sticky::InitialData;
//!
//! let q = |n: i64, d: i64| BigRational::new(n.into(), d.into());
//! // Two particles of radius 1/4 meet at t = 3/4 and stick at 3/4, 5/4.
//! let data = InitialData::new(q(1, 4), vec![q(0, 1), q(2, 1)], vec![q(1, 1), q(-1, 1)])?;
//! let solver = Solver::from_data(data);
//! let state = solver.state(&q(1, 1))?.into_state();
//! assert_eq!(state.positions, vec![q(3, 4), q(5, 4)]);
//! assert_eq!(solver.events(&sticky::progress::Silent)?.collisions()[0].t, q(3, 4));
//! // Data on machine words: the streaming path answers first.
//! assert!(solver.explain()?.starts_with("engine: streaming (N = 2,"));
//! # Ok::<(), sticky::Error>(())
//! ```

pub mod answer;
pub mod choice;
pub mod cost;
mod source;
pub mod work;

#[cfg(test)]
mod tests;

use std::path::Path;
use std::sync::{Arc, OnceLock};

use num_rational::BigRational;

use crate::error::Error;
use crate::fast::dyadic::Dyadic;
use crate::fast::engine::{ExactEngine, Merge, Prepared};
use crate::fast::filter::{Doubles, Refusal, Refused};
use crate::fast::stream::Lean;
use crate::initial::InitialData;
use crate::progress::{Progress, Silent};
use crate::scene::Scene;
use crate::trajectory::Trajectory;

pub use answer::{Answer, Collision, History};
pub use choice::{Choice, Engine, EngineChoice, Reason};
pub use work::WorkCap;

use source::Source;

/// How a [`Solver`] answers: which engine, and how much work it accepts.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Options {
    /// The engine of the one-shot states ([`Engine::Auto`] by default).
    pub engine: Engine,
    /// The cap of the work check ([`WorkCap::Plain`] by default).
    pub work: WorkCap,
}

/// Initial data and every exact answer about them, each by the path the
/// data allow (the module documentation).
pub struct Solver {
    options: Options,
    /// Columns of doubles validated exactly, for the filter (and the
    /// dyadic and streaming paths, built from them on first use).
    filter: Option<Doubles>,
    dyadic: OnceLock<Option<Dyadic>>,
    words: OnceLock<Option<Lean>>,
    source: Source,
    general: OnceLock<Scene>,
    choice: OnceLock<Choice>,
    prepared: OnceLock<Box<dyn Prepared>>,
}

impl Solver {
    /// A Solver with the given fast paths, its general data from `source`.
    fn with_paths(dyadic: Option<Dyadic>, words: Option<Lean>, source: Source) -> Solver {
        Solver {
            options: Options::default(),
            filter: None,
            dyadic: OnceLock::from(dyadic),
            words: OnceLock::from(words),
            source,
            general: OnceLock::new(),
            choice: OnceLock::new(),
            prepared: OnceLock::new(),
        }
    }

    /// A Solver for a validated scene (the streaming path too when every
    /// value fits words).
    pub fn from_scene(scene: Scene) -> Solver {
        let words = Lean::from_data(&scene.data);
        let solver = Solver::with_paths(None, words, Source::Built);
        let _ = solver.general.set(scene);
        solver
    }

    /// A Solver for validated initial data.
    pub fn from_data(data: InitialData<BigRational>) -> Solver {
        Solver::from_scene(Scene::particles(data))
    }

    /// The scene file at `path`: read on the streaming path when it is a
    /// `[particles]` scene on machine words (the general data then read
    /// only if a question needs them), else read and validated now (the
    /// error of record when it is not a valid scene). A column scene whose
    /// projected memory on the streaming path exceeds its limit is refused
    /// before anything is read ([`Error::Memory`], [`Lean::open`]).
    pub fn load(path: &Path) -> Result<Solver, Error> {
        match Lean::open(path)? {
            Some(words) => Ok(Solver::with_paths(
                None,
                Some(words),
                Source::File(path.to_path_buf()),
            )),
            None => Ok(Solver::from_scene(crate::scene::load(path)?)),
        }
    }

    /// Columns of doubles, each the exact binary rational it is, with
    /// radius `radius` (`None`: `1/(2N)`): [`Self::from_double_columns`],
    /// `None` when it refuses them.
    pub fn from_doubles(
        radius: Option<BigRational>,
        positions: Vec<f64>,
        velocities: Vec<f64>,
    ) -> Option<Solver> {
        Solver::from_double_columns(radius, positions, velocities).ok()
    }

    /// Columns of doubles, each the exact binary rational it is, with
    /// radius `radius` (`None`: `1/(2N)`). When `2r` is a double the data
    /// are validated in doubles with exact decisions
    /// ([`Doubles::validate`]) and nothing else is built: the filter
    /// answers the states, the dyadic and streaming paths are built on
    /// first need. Otherwise the dyadic path or else the streaming path
    /// reads them now. The columns are handed back ([`Refused`]) when the
    /// data are invalid or no path takes them (the caller then validates
    /// them and calls [`Solver::from_data`], which names the error of
    /// record).
    pub fn from_double_columns(
        radius: Option<BigRational>,
        positions: Vec<f64>,
        velocities: Vec<f64>,
    ) -> Result<Solver, Box<Refused>> {
        let refused = match Doubles::validate(radius.clone(), positions, velocities) {
            Ok(d) => return Ok(Solver::from_filter(radius, d)),
            Err(r) if r.reason == Refusal::Invalid => return Err(r),
            Err(r) => r,
        };
        let Refused {
            positions,
            velocities,
            ..
        } = *refused;
        let dyadic = Dyadic::from_doubles(radius.clone(), &positions, &velocities);
        let words = match dyadic {
            Some(_) => None,
            None => Lean::from_doubles(radius.clone(), &positions, &velocities),
        };
        if dyadic.is_none() && words.is_none() {
            return Err(Box::new(Refused {
                positions,
                velocities,
                reason: Refusal::Undecided,
            }));
        }
        Ok(Solver::with_paths(
            dyadic,
            words,
            Source::Doubles {
                radius,
                positions: Arc::new(positions),
                velocities: Arc::new(velocities),
            },
        ))
    }

    /// Columns of doubles already validated ([`Doubles`]), given with
    /// radius `radius` (`None`: `1/(2N)`): the filter answers the states,
    /// the dyadic and streaming paths are built on first need.
    pub fn from_filter(radius: Option<BigRational>, d: Doubles) -> Solver {
        let (positions, velocities) = d.shared_columns();
        let mut solver = Solver::with_paths(
            None,
            None,
            Source::Doubles {
                radius,
                positions,
                velocities,
            },
        );
        solver.dyadic = OnceLock::new();
        solver.words = OnceLock::new();
        solver.filter = Some(d);
        solver
    }

    /// The dyadic path's columns ([`crate::fast::dyadic`]), built from the
    /// doubles on first use.
    fn dyadic(&self) -> Option<&Dyadic> {
        self.dyadic
            .get_or_init(|| {
                let f = self.filter.as_ref()?;
                let (x, u) = f.columns();
                Dyadic::from_doubles(Some(f.radius().clone()), x, u)
            })
            .as_ref()
    }

    /// The streaming path's words ([`crate::fast::stream`]), built from the
    /// doubles on first use when the dyadic path does not take them.
    fn words(&self) -> Option<&Lean> {
        self.words
            .get_or_init(|| {
                let f = self.filter.as_ref()?;
                if self.dyadic().is_some() {
                    return None;
                }
                let (x, u) = f.columns();
                Lean::from_doubles(Some(f.radius().clone()), x, u)
            })
            .as_ref()
    }

    /// The same Solver answering with `options`.
    pub fn with_options(mut self, options: Options) -> Solver {
        self.options = options;
        self.choice = OnceLock::new();
        self.prepared = OnceLock::new();
        self
    }

    /// The options it answers with.
    pub fn options(&self) -> Options {
        self.options
    }

    /// The validated scene (built now from the source if needed).
    pub fn scene(&self) -> Result<&Scene, Error> {
        if let Some(s) = self.general.get() {
            return Ok(s);
        }
        let built = self.source.scene()?;
        Ok(self.general.get_or_init(|| built))
    }

    /// The validated initial data.
    pub fn data(&self) -> Result<&InitialData<BigRational>, Error> {
        Ok(&self.scene()?.data)
    }

    /// The certified filter's columns ([`Doubles`]), when it was built from
    /// doubles with `2r` a double: for a caller that wants the filter's
    /// answer in its own buffers ([`Doubles::at_into`]).
    pub fn filter(&self) -> Option<&Doubles> {
        self.filter.as_ref()
    }

    /// The columns of doubles it was built from, if it was
    /// ([`Solver::from_doubles`]): positions, velocities.
    pub fn doubles(&self) -> Option<(&[f64], &[f64])> {
        self.source.doubles()
    }

    /// N.
    pub fn n(&self) -> Result<usize, Error> {
        if let Some(f) = &self.filter {
            return Ok(f.n());
        }
        if let Some(d) = self.dyadic() {
            return Ok(d.n());
        }
        match self.words() {
            Some(w) => Ok(w.n()),
            None => Ok(self.data()?.n()),
        }
    }

    /// The radius r.
    pub fn radius(&self) -> Result<&BigRational, Error> {
        if let Some(f) = &self.filter {
            return Ok(f.radius());
        }
        if let Some(d) = self.dyadic() {
            return Ok(d.radius());
        }
        match self.words() {
            Some(w) => Ok(w.radius()),
            None => Ok(self.data()?.radius()),
        }
    }

    /// The engine of the one-shot states, its cost and why
    /// ([`Choice::resolve`]), decided once.
    pub fn choice(&self) -> Result<&Choice, Error> {
        if let Some(c) = self.choice.get() {
            return Ok(c);
        }
        let c = Choice::resolve(self.data()?, self.options.engine, self.options.work);
        Ok(self.choice.get_or_init(|| c))
    }

    /// What `sticky run --explain` prints (and Python's `Scene.explain()`):
    /// the engine of the one-shot states, `N`, the common denominator, each
    /// candidate's estimated cost, and why. A scene file the streaming path
    /// read ([`Engine::Auto`]) is explained without reading its general
    /// data: the streaming path's widths ([`Lean::explain`]) and, for a
    /// column file, the projected peak memory ([`Lean::footprint`]).
    pub fn explain(&self) -> Result<String, Error> {
        if self.options.engine == Engine::Auto {
            if let Some(words) = self.words() {
                // The streaming path answers first (`state_with_progress`);
                // a column file adds its projected memory.
                let mut text = words.explain();
                if let Some(f) = self.source.path().and_then(Lean::footprint) {
                    text.push_str(&format!("\nmemory: {f}"));
                }
                return Ok(text);
            }
        }
        Ok(self.choice()?.explain())
    }

    /// What `sticky events --explain` prints: the cost model, for the
    /// integer event merge that gives the history.
    pub fn explain_events(&self) -> Result<String, Error> {
        Ok(self.choice()?.cost.explain(&Merge))
    }

    /// The chosen engine prepared for the data, after its work check.
    fn prepared(&self) -> Result<&dyn Prepared, Error> {
        if let Some(p) = self.prepared.get() {
            return Ok(p.as_ref());
        }
        let choice = self.choice()?;
        choice.work.clone()?;
        let p = choice.engine.prepare(self.data()?);
        Ok(self.prepared.get_or_init(|| p).as_ref())
    }

    /// Runs the work check of the general path now (a no-op once it
    /// passed): for callers that want its refusal before any output.
    pub fn check_work(&self) -> Result<(), Error> {
        self.prepared().map(|_| ())
    }

    /// The exact state at `t ≥ 0` ([`Solver::state_with_progress`], silent).
    pub fn state(&self, t: &BigRational) -> Result<Answer<'_>, Error> {
        self.state_with_progress(t, &Silent)
    }

    /// The exact state at `t ≥ 0`: the first path of the module
    /// documentation that answers. `progress` hears of long work and stops
    /// it ([`Error::Interrupted`]).
    pub fn state_with_progress(
        &self,
        t: &BigRational,
        progress: &dyn Progress,
    ) -> Result<Answer<'_>, Error> {
        if self.options.engine == Engine::Auto {
            // The filter first: a proved partition in floating point.
            if let Some(f) = self.filter.as_ref().and_then(|d| d.at(t)) {
                return Ok(Answer::Filtered(f));
            }
            return self.state_by_exact_paths(t, progress);
        }
        let state = self.prepared()?.state_at_with_progress(t, progress)?;
        Ok(Answer::Exact(state))
    }

    /// [`Self::state_with_progress`] on the exact paths alone (no filter).
    pub fn state_by_exact_paths(
        &self,
        t: &BigRational,
        progress: &dyn Progress,
    ) -> Result<Answer<'_>, Error> {
        if self.options.engine == Engine::Auto {
            // A double `t` on a Solver built from doubles goes the dyadic
            // path whatever its mantissa (its wider words included).
            if let Some(b) = self.dyadic().and_then(|d| d.blocks_at(t)) {
                return Ok(Answer::Dyadic(b));
            }
            if let Some(b) = self.words().and_then(|w| w.blocks_at(t)) {
                return Ok(Answer::Words(b));
            }
        }
        let state = self.prepared()?.state_at_with_progress(t, progress)?;
        Ok(Answer::Exact(state))
    }

    /// The exact state at every time of `times`, in order, each handed to
    /// `sink` as soon as it is computed (nothing is kept: big N at many
    /// times streams). Stops at the first error, the Solver's or the
    /// sink's, and with [`Error::Interrupted`] between two times once
    /// `progress` asks.
    pub fn states<E: From<Error>>(
        &self,
        times: &[BigRational],
        progress: &dyn Progress,
        mut sink: impl FnMut(Answer<'_>) -> Result<(), E>,
    ) -> Result<(), E> {
        for t in times {
            if progress.cancelled() {
                return Err(Error::Interrupted {
                    during: "the states",
                }
                .into());
            }
            sink(self.state_with_progress(t, progress)?)?;
        }
        Ok(())
    }

    /// The whole collision history: the integer event merge on the
    /// streaming path's words when the data allow ([`History::Words`]),
    /// else the event merge on the validated data after its work check
    /// ([`Solver::trajectory`]).
    pub fn events(&self, progress: &dyn Progress) -> Result<History, Error> {
        if self.options.engine == Engine::Auto {
            if let Some(h) = self.words().and_then(|w| w.history()) {
                return Ok(History::Words(h));
            }
        }
        self.trajectory(progress).map(History::Exact)
    }

    /// The whole trajectory (impulses, join times) by the integer event
    /// merge ([`crate::fast::merge`], which falls back to the generic merge
    /// when its widths do not suffice), after its work check; `progress`
    /// counts the merges and stops them.
    pub fn trajectory(&self, progress: &dyn Progress) -> Result<Trajectory<BigRational>, Error> {
        let data = self.data()?;
        work::check_work_for(
            data,
            &Merge,
            self.options.work,
            self.choice.get().map(|c| &c.cost),
        )?;
        crate::fast::merge::trajectory_with_progress(data, progress)
    }

    /// The exact projection `P_K(z)` onto `K = {x : x_{i+1} − x_i ≥ 2r}`
    /// (`df:KN`) with this Solver's radius; `z` has any length.
    pub fn project(&self, z: &[BigRational]) -> Result<Vec<BigRational>, Error> {
        let r = self.radius()?;
        let two_r = r + r;
        Ok(crate::projection::project_k(z, &two_r))
    }

    /// [`Self::project`] of doubles (each read exactly), rounded to the
    /// nearest doubles: [`project_doubles_certified`] when it proves the
    /// answer, else [`project_doubles_exactly`]. A NaN or an infinity is
    /// [`Error::Unsupported`].
    pub fn project_doubles(&self, z: &[f64]) -> Result<Vec<f64>, Error> {
        project_doubles(z, self.radius()?)
    }

    /// The engine that answers the one-shot states when no fast path does.
    pub fn engine(&self) -> Result<&'static dyn ExactEngine, Error> {
        Ok(self.choice()?.engine)
    }
}

/// The isotonic regression (non-decreasing, equal weights) of doubles, each
/// read exactly, rounded to the nearest doubles: [`project_doubles`] with
/// `r = 0`. A NaN or an infinity is [`Error::Unsupported`].
pub fn isotonic_doubles(z: &[f64]) -> Result<Vec<f64>, Error> {
    project_doubles(z, &BigRational::from_integer(0.into()))
}

/// `P_K(z)` for `K = {x : x_{i+1} − x_i ≥ 2r}` (`df:KN`; `r = 0`: the
/// isotonic regression) of doubles, each read exactly, rounded to the
/// nearest doubles: [`project_doubles_certified`] when it proves the
/// answer, else [`project_doubles_exactly`]. A NaN or an infinity is
/// [`Error::Unsupported`].
pub fn project_doubles(z: &[f64], radius: &BigRational) -> Result<Vec<f64>, Error> {
    let mut x = vec![0.0; z.len()];
    if project_doubles_certified(z, radius, &mut x) {
        return Ok(x);
    }
    project_doubles_exactly(z, radius)
}

/// The first path of [`Solver::project_doubles`] and [`isotonic_doubles`]
/// (`radius` `0`): the certified filter
/// ([`crate::fast::filter::project_into`]), on the caller's buffers, `out`
/// as long as `z` — milliseconds at `N = 10⁶`. `false` when it does not
/// prove the answer (`out` then holds anything): [`project_doubles_exactly`]
/// answers.
pub fn project_doubles_certified(z: &[f64], radius: &BigRational, out: &mut [f64]) -> bool {
    crate::fast::filter::project_into(z, radius, out).is_some()
}

/// The other paths of [`Solver::project_doubles`] and [`isotonic_doubles`]
/// (`radius` `0`): on machine integers ([`crate::fast::dyadic::isotonic`])
/// when the values and the radius allow, else by the general projection on
/// the exact values. A NaN or an infinity is [`Error::Unsupported`].
pub fn project_doubles_exactly(z: &[f64], radius: &BigRational) -> Result<Vec<f64>, Error> {
    if let Some(x) = crate::fast::dyadic::isotonic::project_doubles(z, radius) {
        return Ok(x);
    }
    let x = crate::projection::project_k(&exact_doubles(z)?, &(radius + radius));
    Ok(x.iter().map(crate::Scalar::to_f64_lossy).collect())
}

/// The exact values of finite doubles; a NaN or an infinity is
/// [`Error::Unsupported`].
fn exact_doubles(z: &[f64]) -> Result<Vec<BigRational>, Error> {
    z.iter()
        .map(|&d| {
            BigRational::from_float(d).ok_or_else(|| Error::Unsupported {
                message: format!("z contains {d}: every value must be finite"),
            })
        })
        .collect()
}
