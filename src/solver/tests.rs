//! The Solver's choices: per cost, forced by name, its fast paths, and its
//! fallback when the work check refuses the cost model's engine (these
//! tests assume `$STICKY_MAX_WORK` unset: the default caps).

use num_bigint::BigInt;

use super::*;
use crate::fast::engine::ENGINES;
use crate::progress::Silent;
use crate::rational::ratio as q;
use crate::solver::cost::Cost;

/// Two collisions at different instants, a cluster that stays apart, a
/// contact at t = 0 that separates: every value on words.
fn small() -> InitialData<BigRational> {
    InitialData::new(
        q(1, 4),
        vec![q(0, 1), q(1, 1), q(3, 1), q(9, 2), q(6, 1), q(13, 2)],
        vec![q(2, 1), q(0, 1), q(-1, 1), q(0, 1), q(1, 1), q(3, 1)],
    )
    .unwrap()
}

/// The hostile shape of issue 29: velocities `(-1)^i/(i+1)`, small
/// denominators one by one, `lcm(1, …, N)` together.
fn hostile(n: i64) -> InitialData<BigRational> {
    InitialData::new(
        q(1, 2),
        (0..n).map(|i| q(3 * i, 1)).collect(),
        (0..n)
            .map(|i| q(if i % 2 == 0 { 1 } else { -1 }, i + 1))
            .collect(),
    )
    .unwrap()
}

fn forced(name: &str) -> Options {
    Options {
        engine: name.parse().unwrap(),
        ..Options::default()
    }
}

fn times() -> Vec<BigRational> {
    [
        q(0, 1),
        q(1, 3),
        q(1, 2),
        q(1, 1),
        q(7, 4),
        q(3, 1),
        q(100, 1),
    ]
    .to_vec()
}

#[test]
fn engines_are_named_and_auto_is_the_default() {
    assert_eq!(Options::default().engine, Engine::Auto);
    assert_eq!("auto".parse::<Engine>().unwrap(), Engine::Auto);
    for e in ENGINES {
        assert_ne!(e.name(), Engine::Auto.name());
        assert_eq!(e.name().parse::<Engine>().unwrap().name(), e.name());
    }
    assert_eq!("projection".parse::<Engine>().unwrap().name(), "kernel");
    assert_eq!("events".parse::<Engine>().unwrap().name(), "merge");
    let e = "nope".parse::<Engine>().unwrap_err().to_string();
    assert!(e.contains("unknown engine \"nope\""), "{e}");
    let names: Vec<&str> = Engine::choices().map(|c| c.name).collect();
    assert_eq!(names[0], "auto");
    assert_eq!(names.len(), ENGINES.len() + 1);
}

/// The cost model's choice: the integer kernel on small common
/// denominators, the blockwise projection past them (`lcm(1..400)`: 574
/// bits), each explained.
#[test]
fn the_cost_model_chooses_per_cost() {
    let s = Solver::from_data(hostile(8));
    assert_eq!(s.engine().unwrap().name(), "kernel");
    assert_eq!(s.choice().unwrap().reason, Reason::CostModel);
    let s = Solver::from_data(hostile(400));
    let c = s.choice().unwrap();
    assert_eq!(
        (c.engine.name(), &c.reason),
        ("blockwise", &Reason::CostModel)
    );
    let line = s.explain().unwrap();
    assert!(
        line.starts_with("engine: blockwise (N = 400, common denominator 574 bits")
            && line.ends_with(" (chosen by the cost model)"),
        "{line}"
    );
    assert!(s
        .explain_events()
        .unwrap()
        .starts_with("engine: merge (N = 400,"));
}

/// `Auto` answers on the fast paths where the data allow (words, dyadic
/// doubles), a forced engine on itself alone; every answer is the oracle's.
#[test]
fn fast_paths_for_auto_and_the_named_engine_alone() {
    let data = small();
    let auto = Solver::from_data(data.clone());
    for t in times() {
        let oracle = crate::projection::state_at(&data, &t).unwrap();
        let a = auto.state(&t).unwrap();
        assert!(matches!(a, Answer::Words(_)), "t = {t}");
        assert_eq!(a.into_state(), oracle);
        for e in ENGINES {
            let s = Solver::from_data(data.clone()).with_options(forced(e.name()));
            let a = s.state(&t).unwrap();
            assert!(matches!(a, Answer::Exact(_)), "{}", e.name());
            assert_eq!(a.into_state(), oracle, "{} at {t}", e.name());
            assert!(s.explain().unwrap().ends_with(" (named by --engine)"));
        }
    }
    // Columns of doubles: the filter or the dyadic path, the same states.
    let xs = [0.0, 1.0, 3.0, 4.5, 6.0, 6.5];
    let us = [2.0, 0.0, -1.0, 0.0, 1.0, 3.0];
    let s = Solver::from_doubles(Some(q(1, 4)), xs.to_vec(), us.to_vec()).unwrap();
    assert_eq!(s.doubles().map(|(x, _)| x.len()), Some(6));
    let mut seen = Vec::new();
    s.states(&times(), &Silent, |a| -> Result<(), Error> {
        assert!(matches!(a, Answer::Dyadic(_) | Answer::Filtered(_)));
        seen.push(a.into_state());
        Ok(())
    })
    .unwrap();
    let oracle: Vec<_> = times()
        .iter()
        .map(|t| crate::projection::state_at(&data, t).unwrap())
        .collect();
    assert_eq!(seen, oracle);
}

/// The history: the word merge where the data allow, the trajectory
/// otherwise (a forced engine), the same collisions; the projection.
#[test]
fn events_and_projection() {
    let data = small();
    let oracle = crate::trajectory::Trajectory::new(data.clone());
    let words = Solver::from_data(data.clone()).events(&Silent).unwrap();
    assert!(matches!(words, History::Words(_)));
    let exact = Solver::from_data(data.clone())
        .with_options(forced("generic-projection"))
        .events(&Silent)
        .unwrap();
    assert!(matches!(exact, History::Exact(_)));
    assert_eq!(words.collisions(), exact.collisions());
    assert_eq!(words.collisions().len(), oracle.impulses().len());
    assert!(!words.collisions().is_empty());
    let z = vec![q(3, 1), q(0, 1), q(1, 2)];
    let s = Solver::from_data(data);
    assert_eq!(
        s.project(&z).unwrap(),
        crate::projection::project_k(&z, &q(1, 2))
    );
}

/// A caller that asks to stop between two times gets
/// [`Error::Interrupted`].
#[test]
fn states_stop_when_asked() {
    struct Stop;
    impl Progress for Stop {
        fn cancelled(&self) -> bool {
            true
        }
    }
    let s = Solver::from_data(small());
    let r = s.states(&times(), &Stop, |_| -> Result<(), Error> {
        panic!("no state once stopped")
    });
    assert!(matches!(r, Err(Error::Interrupted { .. })));
}

/// 1024 particles whose velocities have four coprime denominators of
/// ~12,800 bits (powers of 3, 5, 7, 11): the common denominator has
/// ~51,200 bits (800 words), so the cost model prefers the kernel
/// (`800² ≤ 32 · 200²`) but its work check refuses it
/// (`1024 · 800² > 2^29`); the blockwise projection on local denominators
/// passes (`1024 · 201² < 2^29`) and answers. Forced, the kernel is
/// refused with the message of record.
#[test]
fn the_work_check_refusal_falls_back_to_blockwise() {
    let big = |p: u32, e: u32| BigInt::from(p).pow(e);
    let dens = [big(3, 8076), big(5, 5513), big(7, 4560), big(11, 3700)];
    let n = 1024usize;
    let data = InitialData::new(
        q(1, 2),
        (0..n).map(|i| q(3 * i as i64, 1)).collect(),
        (0..n)
            .map(|i| BigRational::new(1.into(), dens[i % 4].clone()))
            .collect(),
    )
    .unwrap();
    let s = Solver::from_data(data.clone());
    let c = s.choice().unwrap();
    assert_eq!(c.engine.name(), "blockwise");
    assert_eq!(c.reason, Reason::Fallback("kernel"));
    assert!(c.work.is_ok());
    assert!(s.explain().unwrap().ends_with(
        "(the cost model chose kernel, which the work check refuses: this one passes it)"
    ));
    let t = q(1, 1);
    let state = s.state(&t).unwrap().into_state();
    assert_eq!(state.positions[1], q(3, 1) + &data.velocities()[1]);
    let kernel = Solver::from_data(data).with_options(forced("kernel"));
    let e = kernel.state(&t).err().unwrap().to_string();
    assert!(
        e.starts_with("the exact answer by the engine kernel needs at least")
            && e.contains("N = 1024"),
        "{e}"
    );
    assert!(kernel.check_work().is_err());
}

/// A double `t` with a full mantissa (a Python float such as `0.01`) and a
/// double radius on a Solver built from doubles, with positions spread
/// over many binades: the dyadic path on its 256-bit sums answers, not the general engine, and its state is the
/// oracle's (the projection on the exact data).
#[test]
fn a_full_mantissa_double_time_stays_on_the_dyadic_path() {
    let exact = |v: f64| crate::columns::f64_exact(v).unwrap();
    // Positions from 10⁻³ to 10⁶ (82 bits of scale) times a 53-bit `t`:
    // the sums leave `i128`.
    let xs = [0.0, 0.001, 0.0021, 0.0035, 1e6];
    let us = [1.0, -1.0, 0.3, -0.7, 0.1];
    let r = exact(4e-7);
    let s = Solver::from_doubles(Some(r.clone()), xs.to_vec(), us.to_vec()).unwrap();
    let data = InitialData::new(
        r,
        xs.iter().map(|&x| exact(x)).collect(),
        us.iter().map(|&u| exact(u)).collect(),
    )
    .unwrap();
    let t = exact(0.01);
    // The filter answers first, with the same state.
    let filtered = s.state(&t).unwrap();
    assert!(matches!(filtered, Answer::Filtered(_)));
    let a = s.state_by_exact_paths(&t, &Silent).unwrap();
    match &a {
        Answer::Dyadic(b) => assert_eq!(b.width(), crate::fast::kernel::Width::I256),
        _ => panic!("a double t left the dyadic path"),
    }
    let oracle = crate::projection::state_at(&data, &t).unwrap();
    // Particles 0 and 1 have met (the answer is not free flight).
    let gap = &oracle.positions[1] - &oracle.positions[0];
    assert_eq!(gap, q(2, 1) * data.radius());
    assert_eq!(filtered.into_state(), oracle);
    assert_eq!(a.into_state(), oracle);
}

/// The hostile scene of issue 38 at N = 400: positions `i·10^4000`
/// (13,288-bit numerators), velocities `(−1)^i·i/(i+1)` (`lcm(1, …, 400)`
/// together). With a cap of one operation less than the work estimate of
/// the event merge, passed through the API, `events` is refused by the
/// work check before the merge begins (no progress stage), with the
/// estimate, the cap and what to do in the error; at the estimate, it
/// answers.
#[test]
fn a_hostile_history_past_the_callers_cap_is_refused_up_front() {
    #[derive(Default)]
    struct Stages(std::sync::atomic::AtomicUsize);
    impl Progress for Stages {
        fn stage(&self, _: &str, _: Option<u64>) {
            self.0.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        }
    }
    let n = 400i64;
    let big = BigInt::from(10).pow(4000);
    let data = InitialData::new(
        q(1, 2),
        (0..n)
            .map(|i| BigRational::from_integer(&big * i))
            .collect(),
        (0..n)
            .map(|i| q(if i % 2 == 0 { i } else { -i }, i + 1))
            .collect(),
    )
    .unwrap();
    let words = Cost::of(&data).common_denominator.bits().div_ceil(64);
    assert!(words > 1, "{words}");
    let estimate = n as u64 * words * words;
    let capped = |cap: u64| {
        Solver::from_data(data.clone()).with_options(Options {
            work: WorkCap::Operations(cap),
            ..Options::default()
        })
    };
    let stages = Stages::default();
    match capped(estimate - 1).events(&stages) {
        Err(Error::WorkLimit { work, cap, message }) => {
            assert_eq!((work, cap), (estimate, estimate - 1));
            assert!(
                message.contains("engine merge")
                    && message.contains("N = 400")
                    && message.contains(work::WORK_VAR),
                "{message}"
            );
        }
        other => panic!("not refused: {:?}", other.map(|h| h.collisions().len())),
    }
    assert_eq!(stages.0.load(std::sync::atomic::Ordering::Relaxed), 0);
    let answered = capped(estimate).events(&stages).unwrap().collisions();
    let plain = Solver::from_data(data)
        .events(&Silent)
        .unwrap()
        .collisions();
    assert!(!answered.is_empty());
    assert_eq!(answered, plain);
    assert!(stages.0.load(std::sync::atomic::Ordering::Relaxed) > 0);
}

/// Isotonic regression of doubles: the machine-integer path where it
/// applies, the rational one where it does not (an exponent range no word
/// holds), both the nearest doubles of the exact regression; a NaN is
/// refused.
#[test]
fn isotonic_doubles_on_both_paths() {
    let exact = |z: &[f64]| -> Vec<f64> {
        let q: Vec<BigRational> = z
            .iter()
            .map(|&d| BigRational::from_float(d).unwrap())
            .collect();
        crate::projection::isotonic(&q)
            .iter()
            .map(crate::Scalar::to_f64_lossy)
            .collect()
    };
    let easy = [3.0, 1.0, 2.0, 0.5, 4.0];
    assert!(crate::fast::dyadic::isotonic::isotonic_doubles(&easy).is_some());
    assert_eq!(isotonic_doubles(&easy).unwrap(), exact(&easy));
    let wide = [1e300, 1e-300, 0.1, -1e300, 3.0];
    assert!(crate::fast::dyadic::isotonic::isotonic_doubles(&wide).is_none());
    assert_eq!(isotonic_doubles(&wide).unwrap(), exact(&wide));
    assert!(matches!(
        isotonic_doubles(&[1.0, f64::NAN]),
        Err(Error::Unsupported { .. })
    ));
}

/// States the filter refuses (a block past its size, a value past its
/// exponent range, an exact tie) are answered by the exact paths, the
/// same states as the generic projection; one it proves comes from it.
#[test]
fn the_filter_refuses_and_the_exact_paths_answer() {
    let exact = |v: f64| crate::columns::f64_exact(v).unwrap();
    let big = 2f64.powi(350);
    let many: Vec<f64> = (0..200).map(f64::from).collect();
    let slow: Vec<f64> = (0..200).map(|i| -f64::from(i) / 64.0).collect();
    /// Who answers a case.
    #[derive(Debug, Clone, Copy, PartialEq, Eq)]
    enum By {
        Filter,
        ExactPaths,
    }
    /// A scene of doubles (radius, positions, velocities) at time `t`.
    struct FilterCase {
        r: f64,
        xs: Vec<f64>,
        us: Vec<f64>,
        t: f64,
        by: By,
    }
    let case = |r, xs, us, t, by| FilterCase { r, xs, us, t, by };
    let cases = [
        case(0.125, many, slow, 1000.0, By::ExactPaths),
        case(0.25, vec![0.0, big], vec![1.0, 0.0], 1.0, By::ExactPaths),
        case(
            0.25,
            vec![0.0, 1.5, 10.0],
            vec![1.0, 0.0, 0.0],
            1.0,
            By::ExactPaths,
        ),
        case(
            0.25,
            vec![0.0, 1.5, 10.0],
            vec![1.0, 0.0, 0.0],
            1.25,
            By::Filter,
        ),
    ];
    for FilterCase { r, xs, us, t, by } in cases {
        let s = Solver::from_doubles(Some(exact(r)), xs.clone(), us.clone()).unwrap();
        let data = InitialData::new(
            exact(r),
            xs.iter().map(|&x| exact(x)).collect(),
            us.iter().map(|&u| exact(u)).collect(),
        )
        .unwrap();
        let a = s.state(&exact(t)).unwrap();
        let answered = if matches!(a, Answer::Filtered(_)) {
            By::Filter
        } else {
            By::ExactPaths
        };
        assert_eq!(answered, by, "{xs:?} at {t}");
        let oracle = crate::projection::state_at(&data, &exact(t)).unwrap();
        assert_eq!(a.into_state(), oracle);
    }
}
