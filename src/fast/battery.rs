//! The oracle battery: every exact engine of [`ENGINES`] against the
//! generic `BigRational` engines (memchr/regex style — one battery, every
//! implementation, the simplest one as the oracle).
//!
//! At each requested time, every engine's state must equal, field by field,
//! the generic projection's ([`crate::projection::state_at`]: positions,
//! right-derivative velocities, the multipliers `λ` of `eq:dyn-micro`,
//! contact clusters; `prop:proj-micro`). A history engine must moreover
//! rebuild the initial data exactly and record the same impulses (the Dirac
//! masses of `prop:micro-pressure`) and join times as the generic event
//! merge ([`Trajectory::new`]), impulse by impulse.
//!
//! Unit tests, the proptest suite (`tests/engines.rs`) and the fuzz target
//! `kernels` ([`crate::claims::fuzz::kernels`]) all call [`check`] or
//! [`check_probes`].

use std::cell::OnceCell;
use std::fmt;

use num_rational::BigRational;

use crate::error::Error;
use crate::fast::engine::{ExactEngine, GenericEvents, GenericProjection, Prepared, ENGINES};
use crate::initial::InitialData;
use crate::projection;
use crate::state::State;
use crate::trajectory::{probe_times, Trajectory};

/// The first difference the battery found between an engine and the oracle.
#[derive(Debug, Clone, PartialEq)]
pub struct Mismatch {
    /// The engine's name ([`ExactEngine::name`]).
    pub engine: &'static str,
    /// The time of a state that differs; `None` for a difference in the
    /// history (impulses, join times, rebuilt data).
    pub t: Option<BigRational>,
    /// What differs, with both values.
    pub what: String,
}

impl fmt::Display for Mismatch {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.t {
            Some(t) => write!(
                f,
                "engine {} ≠ the generic projection at t = {t}: {}",
                self.engine, self.what
            ),
            None => write!(
                f,
                "engine {} ≠ the generic event merge: {}",
                self.engine, self.what
            ),
        }
    }
}

impl std::error::Error for Mismatch {}

/// Every engine of [`ENGINES`] on `data` at each of `times`.
pub fn check(data: &InitialData<BigRational>, times: &[BigRational]) -> Result<(), Mismatch> {
    check_engines(ENGINES, data, times)
}

/// Every engine of [`ENGINES`] on `data` at the probe times of its history
/// ([`probe_times`]: 0, the collision instants — exact ties — and between
/// them; `limit` bounds the number of instants). Returns the generic
/// history (the oracle's) for the caller's further checks.
pub fn check_probes(
    data: &InitialData<BigRational>,
    limit: Option<usize>,
) -> Result<Trajectory<BigRational>, Mismatch> {
    let history = Trajectory::new(data.clone());
    let times = probe_times(&history, limit);
    battery(ENGINES, data, &times, Some(&history))?;
    Ok(history)
}

/// The given engines on `data` at each of `times` (a test may add an engine
/// of its own).
pub fn check_engines(
    engines: &[&dyn ExactEngine],
    data: &InitialData<BigRational>,
    times: &[BigRational],
) -> Result<(), Mismatch> {
    battery(engines, data, times, None)
}

/// The battery. The oracles are computed once: the states of
/// [`GenericProjection`] (which is then not compared with itself) and the
/// history of [`GenericEvents`] (`known`, or computed when first needed;
/// its states are compared like any other engine's).
fn battery(
    engines: &[&dyn ExactEngine],
    data: &InitialData<BigRational>,
    times: &[BigRational],
    known: Option<&Trajectory<BigRational>>,
) -> Result<(), Mismatch> {
    let lazy = OnceCell::new();
    let history = || known.unwrap_or_else(|| lazy.get_or_init(|| Trajectory::new(data.clone())));
    let oracle: Vec<Result<State<BigRational>, Error>> = times
        .iter()
        .map(|t| projection::state_at(data, t))
        .collect();
    for engine in engines {
        let fail = |t: Option<&BigRational>, what: String| Mismatch {
            engine: engine.name(),
            t: t.cloned(),
            what,
        };
        if engine.name() == GenericProjection.name() {
            continue;
        }
        let prepared = if engine.name() == GenericEvents.name() {
            Box::new(Recorded(history())) as Box<dyn Prepared + '_>
        } else {
            engine.prepare(data)
        };
        if let Some(got) = prepared.trajectory() {
            if let Some(what) = history_diff(history(), got) {
                return Err(fail(None, what));
            }
        }
        for (t, want) in times.iter().zip(&oracle) {
            let what = match (want, prepared.state_at(t)) {
                (Ok(want), Ok(got)) => state_diff(want, &got),
                (Err(_), Err(_)) => None,
                (Ok(_), Err(e)) => Some(format!("an error ({e}), the oracle answers")),
                (Err(e), Ok(_)) => Some(format!("an answer, the oracle fails ({e})")),
            };
            if let Some(what) = what {
                return Err(fail(Some(t), what));
            }
        }
    }
    Ok(())
}

/// The generic history already computed, answering as [`GenericEvents`].
struct Recorded<'a>(&'a Trajectory<BigRational>);

impl Prepared for Recorded<'_> {
    fn state_at(&self, t: &BigRational) -> Result<State<BigRational>, Error> {
        self.0.at(t)
    }
    fn trajectory(&self) -> Option<&Trajectory<BigRational>> {
        Some(self.0)
    }
}

/// The first index where two lists differ, described.
fn list_diff<T: PartialEq + fmt::Debug>(field: &str, want: &[T], got: &[T]) -> Option<String> {
    if let Some(i) = (0..want.len().min(got.len())).find(|&i| want[i] != got[i]) {
        return Some(format!(
            "{field}[{i}] = {:?}, expected {:?}",
            got[i], want[i]
        ));
    }
    (want.len() != got.len()).then(|| format!("{} {field}, expected {}", got.len(), want.len()))
}

/// The first field where two states differ.
fn state_diff(want: &State<BigRational>, got: &State<BigRational>) -> Option<String> {
    if want.t != got.t {
        return Some(format!("t = {}, expected {}", got.t, want.t));
    }
    let show = |v: &[BigRational]| v.iter().map(ToString::to_string).collect::<Vec<_>>();
    list_diff("positions", &show(&want.positions), &show(&got.positions))
        .or_else(|| {
            list_diff(
                "velocities",
                &show(&want.velocities),
                &show(&got.velocities),
            )
        })
        .or_else(|| {
            list_diff(
                "multipliers",
                &show(&want.multipliers),
                &show(&got.multipliers),
            )
        })
        .or_else(|| list_diff("clusters", &want.clusters, &got.clusters))
}

/// The first difference between two histories.
fn history_diff(want: &Trajectory<BigRational>, got: &Trajectory<BigRational>) -> Option<String> {
    if want.data() != got.data() {
        return Some("the rebuilt initial data differ".into());
    }
    list_diff("impulses", want.impulses(), got.impulses())
        .or_else(|| list_diff("join times", want.join_times(), got.join_times()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cluster::runs;
    use crate::contact::multipliers;
    use crate::generate::{initial_data, Limits, SplitMix64};
    use crate::initial::unshift;
    use crate::projection::{pava_blocks, project_at};

    use crate::rational::ratio as q;

    /// A wrong engine: PAVA on the positions alone, the velocity tie-break
    /// dropped (so the velocity is not the right derivative where two
    /// clusters touch and separate).
    struct NoTieBreak;

    impl ExactEngine for NoTieBreak {
        fn name(&self) -> &'static str {
            "no-tie-break"
        }
        fn summary(&self) -> &'static str {
            "deliberately wrong"
        }
        fn prepare(&self, data: &InitialData<BigRational>) -> Box<dyn Prepared> {
            Box::new(Wrong(data.clone()))
        }
    }

    struct Wrong(InitialData<BigRational>);

    impl Prepared for Wrong {
        fn state_at(&self, t: &BigRational) -> Result<State<BigRational>, Error> {
            let data = &self.0;
            let free = project_at(data, t).shifted_free;
            let (mut shifted, mut velocities) = (Vec::new(), Vec::new());
            for b in pava_blocks(&free, None) {
                let r = b.first..b.first + b.size;
                let mean_u = data.velocities()[r].iter().sum::<BigRational>() / q(b.size as i64, 1);
                shifted.extend(std::iter::repeat_n(b.mean_y(), b.size));
                velocities.extend(std::iter::repeat_n(mean_u, b.size));
            }
            let (multipliers, _) = multipliers(data.velocities(), &velocities);
            Ok(State {
                t: t.clone(),
                positions: unshift(&shifted, &data.two_r()),
                clusters: runs(data.n(), |j| shifted[j] == shifted[j + 1]),
                velocities,
                multipliers,
            })
        }
    }

    /// A wrong history engine: the generic merge with its last impulse lost.
    struct LostImpulse;

    impl ExactEngine for LostImpulse {
        fn name(&self) -> &'static str {
            "lost-impulse"
        }
        fn summary(&self) -> &'static str {
            "deliberately wrong"
        }
        fn prepare(&self, data: &InitialData<BigRational>) -> Box<dyn Prepared> {
            struct H(Trajectory<BigRational>);
            impl Prepared for H {
                fn state_at(&self, t: &BigRational) -> Result<State<BigRational>, Error> {
                    self.0.at(t)
                }
                fn trajectory(&self) -> Option<&Trajectory<BigRational>> {
                    Some(&self.0)
                }
            }
            let full = Trajectory::new(data.clone());
            let mut impulses = full.impulses().to_vec();
            impulses.pop();
            Box::new(H(Trajectory::from_parts(
                data.clone(),
                full.join_times().to_vec(),
                impulses,
            )))
        }
    }

    #[test]
    fn every_engine_passes_on_random_scenes() {
        let mut rng = SplitMix64::new(41);
        for k in 0..120 {
            let data = initial_data(
                &rng.bytes(300),
                Limits {
                    max_n: 1 + k % 30,
                    ..Limits::default()
                },
            );
            if let Err(m) = check_probes(&data, Some(6)).map(drop) {
                panic!("case {k}: {m}");
            }
        }
    }

    /// The battery can fail: a contact at `t = 0` that separates is two
    /// blocks for the right derivative, one block without the tie-break.
    #[test]
    fn a_wrong_engine_is_caught() {
        let data =
            InitialData::new(q(1, 2), vec![q(0, 1), q(1, 1)], vec![q(0, 1), q(1, 1)]).unwrap();
        let times = [q(0, 1), q(1, 1)];
        assert_eq!(check(&data, &times), Ok(()));
        let wrong: [&dyn ExactEngine; 2] = [&crate::fast::engine::Kernel, &NoTieBreak];
        let m = check_engines(&wrong, &data, &times).unwrap_err();
        assert_eq!(m.engine, "no-tie-break");
        assert_eq!(m.t, Some(q(0, 1)));
        assert!(m.what.starts_with("velocities[0]"), "{m}");
        // A history that lost an impulse.
        let data =
            InitialData::new(q(1, 2), vec![q(0, 1), q(2, 1)], vec![q(1, 1), q(0, 1)]).unwrap();
        let m = check_engines(&[&LostImpulse], &data, &times).unwrap_err();
        assert_eq!((m.engine, m.t.clone()), ("lost-impulse", None));
        assert!(m.what.contains("impulses"), "{m}");
    }
}
