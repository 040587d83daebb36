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

use crate::checked::{exactly, CheckedRatio};
use crate::contact::Impulse;
use crate::error::Error;
use crate::fast::engine::{ExactEngine, GenericEvents, GenericProjection, Prepared, ENGINES};
use crate::initial::InitialData;
use crate::projection;
use crate::state::State;
use crate::trajectory::{probe_times, Trajectory};

mod diff;
mod similarity;

use diff::history_diff;
pub use similarity::Similarity;

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

/// The battery through a similarity: the oracles (the generic projection
/// and the generic event merge, checked against each other) run on the
/// small `data` at its probe times ([`probe_times`], `limit` instants);
/// every other engine of [`ENGINES`] runs on `similarity`'s image of the
/// data and must answer the image of the oracles' states and history
/// ([`Similarity`], compared by cross-multiplication, no gcd). Wide
/// integers reach the fast engines' wide widths while the `BigRational`
/// oracle computes on small numbers. A history engine whose history is the
/// image of the oracle's is not asked for states: they are
/// [`Trajectory::at`] of the same parts, and the oracle's own states were
/// compared with the projection's. Returns the oracle's history on `data`.
pub fn check_similar(
    data: &InitialData<BigRational>,
    similarity: &Similarity,
    limit: Option<usize>,
) -> Result<Trajectory<BigRational>, Mismatch> {
    check_similar_asking(data, similarity, limit, &|_, _| true)
}

/// Which engines a caller of [`check_similar_asking`] asks, given the
/// image data they would run on.
pub type Asked<'a> = &'a dyn Fn(&dyn ExactEngine, &InitialData<BigRational>) -> bool;

/// [`check_similar`] asking only the engines for which `asked` holds on
/// the image data (the `kernels` fuzz target keeps the merge's generic
/// `BigRational` fallback, slow on wide data, to small N).
pub fn check_similar_asking(
    data: &InitialData<BigRational>,
    similarity: &Similarity,
    limit: Option<usize>,
    asked: Asked<'_>,
) -> Result<Trajectory<BigRational>, Mismatch> {
    let Oracles {
        history,
        times,
        states: oracle,
    } = match word_oracles(data, limit) {
        Some(oracles) => oracles?,
        None => big_oracles(data, limit)?,
    };
    let fast = |image: &InitialData<BigRational>| -> Vec<&dyn ExactEngine> {
        ENGINES
            .iter()
            .copied()
            .filter(|e| e.name() != GenericProjection.name() && e.name() != GenericEvents.name())
            .filter(|e| asked(*e, image))
            .collect()
    };
    if similarity.is_identity() {
        compare(
            &fast(data),
            data,
            &times,
            &oracle,
            &|| &history,
            HistoryStates::Checked,
            similarity,
        )?;
    } else {
        let image_history = similarity.trajectory(&history);
        compare(
            &fast(image_history.data()),
            image_history.data(),
            &times,
            &oracle,
            &|| &image_history,
            HistoryStates::Checked,
            similarity,
        )?;
    }
    Ok(history)
}

/// The oracles of [`check_similar`] on the small data: the generic event
/// merge's history, the probe times, and the generic projection's states
/// there (already compared with the history's states).
struct Oracles {
    history: Trajectory<BigRational>,
    times: Vec<BigRational>,
    states: Vec<Result<State<BigRational>, Error>>,
}

/// The oracles over `BigRational`: the generic event merge checked against
/// the generic projection at the probe times.
fn big_oracles(data: &InitialData<BigRational>, limit: Option<usize>) -> Result<Oracles, Mismatch> {
    let history = Trajectory::new(data.clone());
    let times = probe_times(&history, limit);
    let states = oracle_states(data, &times);
    let generic: [&dyn ExactEngine; 1] = [&GenericEvents];
    compare(
        &generic,
        data,
        &times,
        &states,
        &|| &history,
        HistoryStates::Unchecked,
        &Similarity::identity(),
    )?;
    Ok(Oracles {
        history,
        times,
        states,
    })
}

/// [`big_oracles`] computed by the same generic code on machine words
/// ([`CheckedRatio`]: every operation checked), then widened: `None` when
/// a value does not fit or an operation overflows — then the caller
/// computes over `BigRational`. The small decoded data of the `kernels`
/// fuzz target always fit; `BigRational`'s gcds under the fuzzer's
/// comparison tracing were most of an input's time.
fn word_oracles(
    data: &InitialData<BigRational>,
    limit: Option<usize>,
) -> Option<Result<Oracles, Mismatch>> {
    let (history, times, states, events) = exactly(|| {
        let words = data.convert::<CheckedRatio>()?.ok()?;
        let history = Trajectory::new(words.clone());
        let times = probe_times(&history, limit);
        let states: Vec<_> = times
            .iter()
            .map(|t| projection::state_at(&words, t))
            .collect();
        let events: Vec<_> = times.iter().map(|t| history.at(t)).collect();
        Some((history, times, states, events))
    })??;
    let big = |v: &CheckedRatio| v.to_big();
    let state = |s: Result<State<CheckedRatio>, Error>| {
        s.map(|s| State {
            t: big(&s.t),
            positions: s.positions.iter().map(big).collect(),
            velocities: s.velocities.iter().map(big).collect(),
            multipliers: s.multipliers.iter().map(big).collect(),
            clusters: s.clusters,
        })
    };
    let times: Vec<BigRational> = times.iter().map(big).collect();
    let states: Vec<_> = states.into_iter().map(state).collect();
    for ((t, want), got) in times.iter().zip(&states).zip(events.into_iter().map(state)) {
        if let Some(what) = state_check(want, got, &Similarity::identity()) {
            return Some(Err(Mismatch {
                engine: GenericEvents.name(),
                t: Some(t.clone()),
                what,
            }));
        }
    }
    let impulses = history
        .impulses()
        .iter()
        .map(|i| Impulse {
            t: big(&i.t),
            cluster: i.cluster,
            parts: i.parts.clone(),
            part_velocities: i.part_velocities.iter().map(big).collect(),
            velocity: big(&i.velocity),
            n: i.n,
        })
        .collect();
    let join_times = history
        .join_times()
        .iter()
        .map(|j| j.as_ref().map(big))
        .collect();
    Some(Ok(Oracles {
        history: Trajectory::from_parts(data.clone(), join_times, impulses),
        times,
        states,
    }))
}

/// The generic projection's states of `data` at `times`: the oracle.
fn oracle_states(
    data: &InitialData<BigRational>,
    times: &[BigRational],
) -> Vec<Result<State<BigRational>, Error>> {
    times
        .iter()
        .map(|t| projection::state_at(data, t))
        .collect()
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
    let oracle = oracle_states(data, times);
    compare(
        engines,
        data,
        times,
        &oracle,
        &history,
        HistoryStates::Unchecked,
        &Similarity::identity(),
    )
}

/// Whether the states of the oracle's history, at the battery's times, are
/// known to equal the generic projection's. A state of a history is a
/// function of its data, join times and impulses ([`Trajectory::at`]), so
/// once they are, a history engine whose history equals the oracle's
/// (compared first, exactly) has those states too: they are not evaluated
/// again.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum HistoryStates {
    /// Compared ([`GenericEvents`] passed on these times).
    Checked,
    /// Not compared yet.
    Unchecked,
}

/// Each engine (but the generic projection, the oracle itself) on `data`
/// against the `oracle`'s states at `times` and, for a history engine,
/// against the oracle's `history`; [`GenericEvents`] answers from that
/// history instead of computing it again.
fn compare<'h>(
    engines: &[&dyn ExactEngine],
    data: &InitialData<BigRational>,
    times: &[BigRational],
    oracle: &[Result<State<BigRational>, Error>],
    history: &dyn Fn() -> &'h Trajectory<BigRational>,
    mut history_states: HistoryStates,
    similarity: &Similarity,
) -> Result<(), Mismatch> {
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
        let recorded = engine.name() == GenericEvents.name();
        if let Some(got) = prepared.trajectory() {
            if let Some(what) = history_diff(history(), got) {
                return Err(fail(None, what));
            }
            if !recorded && history_states == HistoryStates::Checked {
                continue;
            }
        }
        for (t, want) in times.iter().zip(oracle) {
            if let Some(what) = state_check(want, prepared.state_at(t), similarity) {
                return Err(fail(Some(t), what));
            }
        }
        if recorded {
            history_states = HistoryStates::Checked;
        }
    }
    Ok(())
}

/// How an engine's answer `got` differs from the image of the oracle's
/// answer `want` (`None`: it does not).
fn state_check(
    want: &Result<State<BigRational>, Error>,
    got: Result<State<BigRational>, Error>,
    similarity: &Similarity,
) -> Option<String> {
    match (want, got) {
        (Ok(want), Ok(got)) => similarity.state_diff(want, &got),
        (Err(_), Err(_)) => None,
        (Ok(_), Err(e)) => Some(format!("an error ({e}), the oracle answers")),
        (Err(e), Ok(_)) => Some(format!("an answer, the oracle fails ({e})")),
    }
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

    /// The similarities of the `kernels` fuzz target's kinds: wide
    /// numerators, wide denominators, a negative shift.
    fn similarities() -> Vec<Similarity> {
        let three = |k: u32| BigRational::from_integer(num_bigint::BigInt::from(3).pow(k));
        vec![
            Similarity::new(three(90), q(1, 3)).unwrap(),
            Similarity::new(three(40).recip(), -three(70) + q(1, 3)).unwrap(),
            Similarity::new(q(1 << 40, 1), three(200)).unwrap(),
        ]
    }

    /// The theorem [`check_similar`] rests on, on the generic engines: the
    /// projection and the event merge of the image data are the images of
    /// those of the data (the comparison by cross-multiplication included).
    #[test]
    fn generic_engines_commute_with_similarities() {
        let mut rng = SplitMix64::new(7);
        for k in 0..30 {
            let data = initial_data(
                &rng.bytes(60),
                Limits {
                    max_n: 1 + k % 12,
                    ..Limits::default()
                },
            );
            let history = Trajectory::new(data.clone());
            for sim in similarities() {
                let image = sim.data(&data);
                let image_history = Trajectory::new(image.clone());
                assert_eq!(
                    history_diff(&sim.trajectory(&history), &image_history),
                    None
                );
                for t in probe_times(&history, None) {
                    let want = projection::state_at(&data, &t).unwrap();
                    let got = projection::state_at(&image, &t).unwrap();
                    assert_eq!(sim.state_diff(&want, &got), None, "case {k}, {sim}");
                }
            }
        }
    }

    /// [`Similarity::position`] and [`Similarity::velocity`] are the
    /// `BigRational` operators' `ratio·x + shift` and `ratio·u`, in the
    /// same lowest terms (numerator and denominator equal, not only the
    /// values).
    #[test]
    fn images_are_the_rational_operators() {
        let mut rng = SplitMix64::new(11);
        for k in 0..20 {
            let data = initial_data(&rng.bytes(60), Limits::default());
            for sim in similarities().into_iter().chain([Similarity::identity()]) {
                for v in data.positions().iter().chain(data.velocities()) {
                    let (x, u) = (sim.position(v), sim.velocity(v));
                    let (want_x, want_u) = (v * &sim.ratio + &sim.shift, v * &sim.ratio);
                    assert_eq!(
                        (x.numer(), x.denom()),
                        (want_x.numer(), want_x.denom()),
                        "case {k}"
                    );
                    assert_eq!(
                        (u.numer(), u.denom()),
                        (want_u.numer(), want_u.denom()),
                        "case {k}"
                    );
                }
            }
        }
    }

    /// The comparison through a similarity can fail: one position, one
    /// velocity or one multiplier off in the image is reported.
    #[test]
    fn a_wrong_image_is_caught() {
        let data = InitialData::new(
            q(1, 4),
            vec![q(0, 1), q(1, 1), q(3, 1)],
            vec![q(2, 1), q(0, 1), q(-1, 1)],
        )
        .unwrap();
        let t = q(1, 1);
        let want = projection::state_at(&data, &t).unwrap();
        for sim in similarities() {
            let image = projection::state_at(&sim.data(&data), &t).unwrap();
            assert_eq!(sim.state_diff(&want, &image), None);
            let mut bad = image.clone();
            bad.positions[2] += q(1, 1);
            let what = sim.state_diff(&want, &bad).unwrap();
            assert!(what.starts_with("positions[2]"), "{what}");
            let mut bad = image.clone();
            bad.velocities[0] = -bad.velocities[0].clone();
            assert!(sim
                .state_diff(&want, &bad)
                .unwrap()
                .starts_with("velocities[0]"));
            let mut bad = image.clone();
            bad.multipliers[0] += q(1, 7);
            assert!(sim
                .state_diff(&want, &bad)
                .unwrap()
                .starts_with("multipliers[0]"));
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

    /// The machine-word oracles answer on the `kernels` target's small
    /// data, exactly what the `BigRational` oracles answer.
    #[test]
    fn word_oracles_equal_big_oracles_on_small_data() {
        let mut rng = SplitMix64::new(43);
        for k in 0..80 {
            let data = initial_data(
                &rng.bytes(80),
                Limits {
                    max_n: 1 + k % 12,
                    max_den: 8,
                    max_speed: 16,
                },
            );
            let words = word_oracles(&data, Some(3))
                .expect("small data fit machine words")
                .unwrap();
            let big = big_oracles(&data, Some(3)).unwrap();
            assert_eq!(history_diff(&big.history, &words.history), None, "case {k}");
            assert_eq!(big.times, words.times, "case {k}");
            assert_eq!(big.states, words.states, "case {k}");
        }
    }

    /// Data whose words overflow (denominators near 2^62, whose sums do
    /// not fit) get no machine-word answer; the battery then computes over
    /// `BigRational` and still passes.
    #[test]
    fn words_that_overflow_fall_back_to_big_rationals() {
        let d = (1_i64 << 61) + 1;
        let wide = |n: i64| BigRational::new(n.into(), d.into());
        let data = InitialData::new(
            q(1, 1024),
            vec![q(0, 1), q(1, 1) + wide(1), q(3, 1)],
            vec![q(1, 1), wide(3), q(-1, 3)],
        )
        .unwrap();
        assert!(word_oracles(&data, Some(3)).is_none());
        let history = check_similar(&data, &Similarity::identity(), Some(3)).unwrap();
        assert!(!history.impulses().is_empty());
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
