//! `sticky compare` on a Solver built from doubles (the Python package's
//! path: the dyadic answers, the figures without a gcd per value) gives the
//! report of the general path on the same data read exactly, and every
//! figure equals the one of the plain `BigRational` formulas (the
//! definitions of `reference::measure::compare`), on small random scenes of
//! doubles with their own nearest answers, perturbed answers and exact ones.

use num_rational::BigRational;
use num_traits::{Signed, Zero};
use sticky::cluster::Cluster;
use sticky::columns::f64_exact;
use sticky::generate::SplitMix64;
use sticky::progress::Silent;
use sticky::report::compare::{
    compare_solution_by, compare_solution_with, CompareOptions, Report, Verdict,
};
use sticky::report::solution::Frame;
use sticky::solver::Solver;
use sticky::{InitialData, Scalar};

/// A deterministic stream of doubles in `[0, 1)`, from the crate's own
/// generator.
struct Stream(SplitMix64);

impl Stream {
    fn next(&mut self) -> f64 {
        self.0.unit()
    }
}

fn exact(v: &[f64]) -> Vec<BigRational> {
    v.iter().map(|&d| f64_exact(d).expect("finite")).collect()
}

fn nearest(v: &[BigRational]) -> Vec<f64> {
    v.iter().map(Scalar::to_f64_lossy).collect()
}

/// A random scene of doubles: exponential-like gaps above contact, some
/// pairs at contact exactly, velocities in `[−1, 1]`, and a time.
fn scene(s: &mut Stream) -> (f64, Vec<f64>, Vec<f64>, f64) {
    let n = 2 + (s.next() * 40.0) as usize;
    let radius = [4e-7, 0.125, 1.0 / 3.0][(s.next() * 3.0) as usize];
    let (mut x, mut u) = (vec![0.0f64], vec![s.next() * 2.0 - 1.0]);
    for _ in 1..n {
        let gap = if s.next() < 0.2 {
            0.0
        } else {
            s.next() * 4.0 * radius
        };
        let last = *x.last().unwrap_or(&0.0);
        // The sum rounded up so that the gap stays at least 2r.
        let mut next = last + 2.0 * radius + gap;
        while next - last < 2.0 * radius {
            next = f64::from_bits(next.to_bits() + 1);
        }
        x.push(next);
        u.push(s.next() * 2.0 - 1.0);
    }
    let t = [0.01, 0.5, s.next(), 0.0][(s.next() * 4.0) as usize];
    (radius, x, u, t)
}

/// The plain definitions, on `BigRational`'s own operators.
fn plain_max(a: &[BigRational], b: &[BigRational]) -> (BigRational, usize) {
    let mut best = (<BigRational as Zero>::zero(), 0);
    for (i, (p, q)) in a.iter().zip(b).enumerate() {
        let d = (p - q).abs();
        if d > best.0 {
            best = (d, i);
        }
    }
    best
}

fn plain_l2(a: &[BigRational], b: &[BigRational]) -> BigRational {
    let s = a
        .iter()
        .zip(b)
        .fold(<BigRational as Zero>::zero(), |s, (p, q)| {
            s + (p - q) * (p - q)
        });
    s / BigRational::from_integer(a.len().into())
}

/// Every figure of `report` against the plain definitions.
fn check_figures(
    report: &Report,
    frame: &Frame,
    state: &sticky::State<BigRational>,
    two_r: &BigRational,
) {
    let c = &report.frames[0].comparison;
    let x = &frame.positions;
    let (value, index) = plain_max(x, &state.positions);
    assert_eq!(
        (&c.position_max.value, c.position_max.index),
        (&value, index)
    );
    assert_eq!(c.position_l2_squared, plain_l2(x, &state.positions));
    if let Some(u) = &frame.velocities {
        let (value, index) = plain_max(u, &state.velocities);
        let m = c.velocity_max.as_ref().expect("velocities given");
        assert_eq!((&m.value, m.index), (&value, index));
        assert_eq!(c.velocity_l2_squared, Some(plain_l2(u, &state.velocities)));
        let t = &state.t;
        let oleinik: Vec<usize> = (1..x.len())
            .filter(|&i| {
                let dx = &x[i] - &x[i - 1];
                !dx.is_positive() || t * (&u[i] - &u[i - 1]) >= dx
            })
            .collect();
        if t.is_positive() {
            assert_eq!(c.oleinik.as_deref(), Some(oleinik.as_slice()));
        }
    }
    let gaps: Vec<BigRational> = x.windows(2).map(|w| &w[1] - &w[0] - two_r).collect();
    let overlaps: Vec<(usize, BigRational)> = gaps
        .iter()
        .enumerate()
        .filter(|(_, g)| g.is_negative())
        .map(|(j, g)| (j, -g.clone()))
        .collect();
    let found: Vec<(usize, BigRational)> = c
        .overlaps
        .iter()
        .map(|o| (o.pair, o.depth.clone()))
        .collect();
    assert_eq!(found, overlaps);
    if let Some(l) = &frame.multipliers {
        let (value, index) = plain_max(l, &state.multipliers);
        let m = c.multiplier_max.as_ref().expect("multipliers given");
        assert_eq!((&m.value, m.index), (&value, index));
        let products: Vec<(usize, BigRational)> = l
            .iter()
            .zip(&gaps)
            .enumerate()
            .map(|(j, (v, g))| (j, v * g))
            .filter(|(_, p)| !Zero::is_zero(p))
            .collect();
        let found: Vec<(usize, BigRational)> = c
            .complementarity
            .iter()
            .map(|p| (p.pair, p.value.clone()))
            .collect();
        assert_eq!(found, products);
    }
    // Contacts: gap ≤ 0 (the default tolerance), clusters by `contains`.
    let contact: Vec<bool> = gaps.iter().map(|g| !g.is_positive()).collect();
    let cand = sticky::cluster::runs(x.len(), |j| contact[j]);
    let missed: Vec<Cluster> = state
        .clusters
        .iter()
        .filter(|c| c.size >= 2 && !cand.contains(c))
        .copied()
        .collect();
    assert_eq!(c.missed_clusters, missed);
}

#[test]
fn the_doubles_path_gives_the_general_report_and_the_plain_figures() {
    let mut s = Stream(SplitMix64::new(0x5eed_0038));
    let mut checked = 0;
    let mut verdicts = std::collections::BTreeSet::new();
    for _ in 0..200 {
        let (radius, x, u, t) = scene(&mut s);
        let r = f64_exact(radius).expect("finite");
        let Ok(data) = InitialData::new(r.clone(), exact(&x), exact(&u)) else {
            continue;
        };
        let solver = Solver::from_doubles(Some(r), x.clone(), u.clone())
            .expect("valid doubles take a fast path");
        let t = f64_exact(t).expect("finite");
        let state = solver.state(&t).expect("a state").into_state();
        let own = |v: &[BigRational]| exact(&nearest(v));
        // The own answer, one with a few ulps moved and a λ negated, and
        // the exact answer.
        let mut moved = nearest(&state.positions);
        let k = (s.next() * moved.len() as f64) as usize;
        moved[k] = f64::from_bits(moved[k].to_bits() + 3);
        let mut lambda = own(&state.multipliers);
        if let Some(l) = lambda.first_mut() {
            *l = -l.clone() - BigRational::from_float(1e-3).expect("finite");
        }
        let frames = [
            (
                own(&state.positions),
                own(&state.velocities),
                own(&state.multipliers),
            ),
            (exact(&moved), own(&state.velocities), lambda),
            (
                state.positions.clone(),
                state.velocities.clone(),
                state.multipliers.clone(),
            ),
        ];
        for (positions, velocities, multipliers) in frames {
            let mut frame = Frame::new(t.clone(), positions);
            frame.velocities = Some(velocities);
            frame.multipliers = Some(multipliers);
            let options = CompareOptions::default();
            let by = compare_solution_by(&solver, std::slice::from_ref(&frame), &options, &Silent)
                .expect("compares");
            let with =
                compare_solution_with(&data, std::slice::from_ref(&frame), &options, &Silent)
                    .expect("compares");
            assert_eq!(by, with);
            check_figures(&by, &frame, &state, &data.two_r());
            verdicts.insert(by.verdict);
            checked += 1;
        }
    }
    assert!(
        checked >= 200,
        "{checked} comparisons: the scenes are mostly valid"
    );
    // The own answer is `rounding` (or `exact`), the exact one `exact`, a
    // moved one worse: every rung reached.
    for v in [Verdict::Exact, Verdict::Rounding, Verdict::Invalid] {
        assert!(verdicts.contains(&v), "{v} never reached: {verdicts:?}");
    }
}
