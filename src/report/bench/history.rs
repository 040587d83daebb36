//! `sticky bench --history`: the full exact history against our f64 PAVA,
//! and nothing else, timed back to back on one scene.
//!
//! The ratio of the `events_columns` row of [`super::run`] to its `f64` row
//! is a ratio of two medians of three repetitions, each on a fresh scene
//! whose `BigRational` generation takes most of the run (about four minutes
//! at N = 10⁶ with every row). On a shared machine the f64 pass alone moves
//! by half again from one minute to the next (13–20 ns per particle at
//! N = 10⁶ on the machine this was written on), and so does that ratio.
//! Here the scene is made once (untimed), and the calls are timed back to
//! back, the order reversed from one round to the next, so that they see
//! the same state of the machine: the ratios of each round, and their
//! medians, are the figures to read. The scene and the calls are exactly
//! those of the full bench (the first timed repetition's scene):
//!
//! * our f64 PAVA on `x̃⁰ + t u⁰` (the `f64` row);
//! * the history from the scaled `i64` columns, the path `sticky events`
//!   takes on a file (the `events_columns` row);
//! * the history from the `BigRational` data, the scaling to common
//!   denominators included ([`IntegerTrajectory::new`], the `events` row).

use crate::json::Fixed;
use num_rational::BigRational;

use super::{free_f64, measured, median, scaled_columns, scene};
use crate::fast::merge::{history_words, Engine, IntegerTrajectory};
use crate::projection::isotonic;

/// One round: the three calls on the same scene, back to back.
#[derive(Debug, Clone, Copy)]
pub struct Pair {
    /// Our f64 PAVA, ns per particle.
    pub f64_ns: f64,
    /// The full exact history from the scaled columns, ns per particle.
    pub history_ns: f64,
    /// The same history from the `BigRational` data, scaling included, ns
    /// per particle.
    pub from_data_ns: f64,
}

impl Pair {
    /// The history's time (from the columns) over the f64 pass's.
    pub fn ratio(&self) -> f64 {
        self.history_ns / self.f64_ns
    }
    /// The history's time from the `BigRational` data over the f64 pass's.
    pub fn ratio_from_data(&self) -> f64 {
        self.from_data_ns / self.f64_ns
    }
}

/// What `sticky bench --history` measured.
#[derive(Debug, Clone)]
pub struct HistoryReport {
    /// Number of particles.
    pub n: usize,
    /// The timed pairs, in order (one untimed pair ran first).
    pub pairs: Vec<Pair>,
}

impl HistoryReport {
    /// The median of the rounds' ratios (history from the columns).
    pub fn median_ratio(&self) -> Option<f64> {
        median(self.pairs.iter().map(Pair::ratio).collect())
    }
    /// The median of the rounds' ratios (history from the `BigRational`
    /// data).
    pub fn median_ratio_from_data(&self) -> Option<f64> {
        median(self.pairs.iter().map(Pair::ratio_from_data).collect())
    }
}

/// Times `reps` rounds (after one untimed round) on the bench's scene of `n`
/// particles at time `t` (the f64 pass's input; the history does not
/// depend on `t`); an error when the scene's scaled columns do not fit the
/// integer engine (from the columns or from the data).
pub fn run(n: usize, reps: usize, t: &BigRational) -> Result<HistoryReport, String> {
    let n = n.max(2);
    let nf = n as f64;
    let data = scene(n, 1001);
    let y = free_f64(&data, t);
    let (x, u, dx, du) = scaled_columns(&data)
        .ok_or("the scene's scaled columns do not fit i64: nothing to measure")?;
    // The f64 pass and the history from the columns each read a copy of
    // their input made just before them (untimed), as in the full bench,
    // where the input of those rows has just been computed; the history
    // from the data reads the scene itself, as the `events` row does. (The
    // allocator keeps freed memory resident in this mode,
    // `Memory::Resident`: no call faults in pages another one freed.)
    let f64_pass = || {
        let y = y.clone();
        let (ns, _, out) = measured(|| isotonic::<f64>(&y));
        std::hint::black_box(out);
        ns / nf
    };
    let history = || {
        let (x, u) = (x.clone(), u.clone());
        let (ns, _, h) = measured(|| history_words(&x, &u, dx, du));
        h.map(|_| ns / nf)
            .ok_or("the integer engine's bound fails on this scene")
    };
    let from_data = || {
        let (ns, _, h) = measured(|| IntegerTrajectory::new(&data));
        (h.engine() != Engine::BigRational)
            .then_some(ns / nf)
            .ok_or("the integer engine's bound fails on this scene")
    };
    let mut pairs = Vec::with_capacity(reps);
    for k in 0..=reps {
        let (f64_ns, history_ns, from_data_ns) = if k % 2 == 0 {
            let f = f64_pass();
            let h = history()?;
            (f, h, from_data()?)
        } else {
            let d = from_data()?;
            let h = history()?;
            (f64_pass(), h, d)
        };
        // Round 0 warms the allocator and the caches up.
        if k > 0 {
            pairs.push(Pair {
                f64_ns,
                history_ns,
                from_data_ns,
            });
        }
    }
    Ok(HistoryReport { n, pairs })
}

/// One line per round, then the medians of the ratios and their ranges.
pub fn table(r: &HistoryReport) -> String {
    let mut out = format!(
        "N = {}: the full exact history against our f64 PAVA, timed back to back\n  \
         (columns: from the scaled i64 columns, the events_columns row; data: from the BigRational data, scaling included, the events row)\n  \
         {:>5} {:>10} {:>12} {:>8} {:>12} {:>8}\n",
        r.n, "round", "f64 ns/p", "columns ns/p", "× f64", "data ns/p", "× f64"
    );
    for (k, p) in r.pairs.iter().enumerate() {
        out.push_str(&format!(
            "  {:>5} {:>10.1} {:>12.1} {:>8.2} {:>12.1} {:>8.2}\n",
            k + 1,
            p.f64_ns,
            p.history_ns,
            p.ratio(),
            p.from_data_ns,
            p.ratio_from_data()
        ));
    }
    for (what, ratio, m) in [
        ("columns", Pair::ratio as fn(&Pair) -> f64, r.median_ratio()),
        ("data", Pair::ratio_from_data, r.median_ratio_from_data()),
    ] {
        let ratios = r.pairs.iter().map(ratio);
        let (lo, hi) = ratios.fold((f64::INFINITY, 0f64), |(a, b), v| (a.min(v), b.max(v)));
        if let Some(m) = m {
            out.push_str(&format!(
                "  median ratio, {what}: {m:.2} (range {lo:.2}–{hi:.2} over {} rounds)\n",
                r.pairs.len()
            ));
        }
    }
    out
}

/// `sticky bench --history --json`: one object.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct HistoryJson {
    /// N.
    pub n: usize,
    /// One entry per measured pair of runs.
    pub pairs: Vec<PairJson>,
    /// The median of `ratio` (`null`: no pair).
    pub median_ratio: Option<Fixed<4>>,
    /// The median of `ratio_from_data`.
    pub median_ratio_from_data: Option<Fixed<4>>,
}

/// One measured pair: ns per particle of each pipeline and their ratios.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct PairJson {
    /// The `f64` PAVA.
    pub f64: Fixed<3>,
    /// The exact history.
    pub history: Fixed<3>,
    /// `history / f64`.
    pub ratio: Fixed<4>,
    /// The exact history from the data file.
    pub from_data: Fixed<3>,
    /// `from_data / f64`.
    pub ratio_from_data: Fixed<4>,
}

/// [`HistoryJson`] as one line.
pub fn json(r: &HistoryReport) -> String {
    let pairs = r
        .pairs
        .iter()
        .map(|p| PairJson {
            f64: Fixed(p.f64_ns),
            history: Fixed(p.history_ns),
            ratio: Fixed(p.ratio()),
            from_data: Fixed(p.from_data_ns),
            ratio_from_data: Fixed(p.ratio_from_data()),
        })
        .collect();
    crate::json::to_string(&HistoryJson {
        n: r.n,
        pairs,
        median_ratio: r.median_ratio().map(Fixed),
        median_ratio_from_data: r.median_ratio_from_data().map(Fixed),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_bigint::BigInt;

    #[test]
    fn ratios_and_their_median() {
        let pair = |f64_ns, history_ns, from_data_ns| Pair {
            f64_ns,
            history_ns,
            from_data_ns,
        };
        let r = HistoryReport {
            n: 10,
            pairs: vec![
                pair(2.0, 60.0, 70.0),
                pair(4.0, 40.0, 48.0),
                pair(1.0, 20.0, 30.0),
            ],
        };
        assert_eq!(r.pairs[0].ratio(), 30.0);
        assert_eq!(r.pairs[0].ratio_from_data(), 35.0);
        assert_eq!(r.median_ratio(), Some(20.0));
        assert_eq!(r.median_ratio_from_data(), Some(30.0));
        let text = table(&r);
        assert!(
            text.contains("median ratio, columns: 20.00 (range 10.00–30.00 over 3 rounds)"),
            "{text}"
        );
        assert!(
            text.contains("median ratio, data: 30.00 (range 12.00–35.00 over 3 rounds)"),
            "{text}"
        );
        assert!(
            json(&r).ends_with("\"median_ratio\": 20.0000, \"median_ratio_from_data\": 30.0000}")
        );
    }

    #[test]
    fn rounds_measure_the_three_calls() {
        let t = BigRational::new(BigInt::from(1), BigInt::from(100));
        let r = run(3000, 3, &t).unwrap();
        assert_eq!((r.n, r.pairs.len()), (3000, 3));
        for p in &r.pairs {
            assert!(
                p.f64_ns > 0.0 && p.history_ns > 0.0 && p.from_data_ns > 0.0,
                "{p:?}"
            );
        }
        let m = r.median_ratio().unwrap();
        let mut ratios: Vec<f64> = r.pairs.iter().map(Pair::ratio).collect();
        ratios.sort_by(f64::total_cmp);
        assert_eq!(m, ratios[1]);
        let text = table(&r);
        assert_eq!(text.lines().count(), 3 + 3 + 2, "{text}");
        assert!(
            text.contains(&format!("median ratio, columns: {m:.2}")),
            "{text}"
        );
        let d = r.median_ratio_from_data().unwrap();
        let mut ratios: Vec<f64> = r.pairs.iter().map(Pair::ratio_from_data).collect();
        ratios.sort_by(f64::total_cmp);
        assert_eq!(d, ratios[1]);
        assert!(
            text.contains(&format!("median ratio, data: {d:.2}")),
            "{text}"
        );
        let v: serde_json::Value = serde_json::from_str(&json(&r)).expect("valid JSON");
        assert_eq!(v["pairs"].as_array().map(Vec::len), Some(3));
        assert_eq!(v["n"], 3000);
        assert!((v["median_ratio"].as_f64().unwrap() - m).abs() < 1e-3 * m);
        assert!((v["median_ratio_from_data"].as_f64().unwrap() - d).abs() < 1e-3 * d);
    }
}
