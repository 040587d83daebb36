//! `sticky bench --history`: the full exact history from the scaled columns
//! (the `events_columns` row of [`super::run`]) against our f64 PAVA, and
//! nothing else, in pairs on one scene.
//!
//! The ratio of the `events_columns` row to the `f64` row is a ratio of two
//! medians of three repetitions, each on a fresh scene whose `BigRational`
//! generation takes most of the run (about four minutes at N = 10⁶ with
//! every row). On a shared machine the f64 pass alone moves by half again
//! from one minute to the next (13–20 ns per particle at N = 10⁶ on the
//! machine this was written on), and so does that ratio. Here the scene
//! is made once (untimed), and the two calls are timed back to back, the
//! order alternating from pair to pair, so that both see the same state of
//! the machine: the ratio of each pair, and their median, are the figures
//! to read. The scene and the two calls are exactly those of the full
//! bench (the first timed repetition's scene).

use num_rational::BigRational;

use super::{free_f64, measured, median, scaled_columns, scene};
use crate::fast::merge::history_words;
use crate::projection::isotonic;

/// One pair: both calls on the same scene, back to back.
#[derive(Debug, Clone, Copy)]
pub struct Pair {
    /// Our f64 PAVA, ns per particle.
    pub f64_ns: f64,
    /// The full exact history from the scaled columns, ns per particle.
    pub history_ns: f64,
}

impl Pair {
    /// The history's time over the f64 pass's.
    pub fn ratio(&self) -> f64 {
        self.history_ns / self.f64_ns
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
    /// The median of the pairs' ratios.
    pub fn median_ratio(&self) -> Option<f64> {
        median(self.pairs.iter().map(Pair::ratio).collect())
    }
}

/// Times `reps` pairs (after one untimed pair) on the bench's scene of `n`
/// particles at time `t` (the f64 pass's input; the history does not
/// depend on `t`); an error when the scene's scaled columns do not fit the
/// integer engine.
pub fn run(n: usize, reps: usize, t: &BigRational) -> Result<HistoryReport, String> {
    let n = n.max(2);
    let nf = n as f64;
    let data = scene(n, 1001);
    let y = free_f64(&data, t);
    let (x, u, dx, du) = scaled_columns(&data)
        .ok_or("the scene's scaled columns do not fit i64: nothing to measure")?;
    // Each call reads a copy of its input made just before it (untimed), as
    // in the full bench, where the input of each row has just been
    // computed. (The allocator keeps freed memory resident in this mode,
    // `Memory::Resident`: neither call faults in pages the other freed.)
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
    let mut pairs = Vec::with_capacity(reps);
    for k in 0..=reps {
        let (f64_ns, history_ns) = if k % 2 == 0 {
            let f = f64_pass();
            (f, history()?)
        } else {
            let h = history()?;
            (f64_pass(), h)
        };
        // Pair 0 warms the allocator and the caches up.
        if k > 0 {
            pairs.push(Pair { f64_ns, history_ns });
        }
    }
    Ok(HistoryReport { n, pairs })
}

/// One line per pair, then the median of the ratios and their range.
pub fn table(r: &HistoryReport) -> String {
    let mut out = format!(
        "N = {}: the full exact history (events_columns) against our f64 PAVA, pairs timed back to back\n  {:>4} {:>14} {:>14} {:>9}\n",
        r.n, "pair", "f64 ns/p", "history ns/p", "× f64"
    );
    for (k, p) in r.pairs.iter().enumerate() {
        out.push_str(&format!(
            "  {:>4} {:>14.1} {:>14.1} {:>9.2}\n",
            k + 1,
            p.f64_ns,
            p.history_ns,
            p.ratio()
        ));
    }
    let ratios = r.pairs.iter().map(Pair::ratio);
    let (lo, hi) = ratios.fold((f64::INFINITY, 0f64), |(a, b), v| (a.min(v), b.max(v)));
    if let Some(m) = r.median_ratio() {
        out.push_str(&format!(
            "  median ratio {m:.2} (range {lo:.2}–{hi:.2} over {} pairs)\n",
            r.pairs.len()
        ));
    }
    out
}

/// `{"n": …, "pairs": [{"f64": …, "history": …, "ratio": …}, …], "median_ratio": …}`.
pub fn json(r: &HistoryReport) -> String {
    let pairs: Vec<String> = r
        .pairs
        .iter()
        .map(|p| {
            format!(
                "{{\"f64\": {:.3}, \"history\": {:.3}, \"ratio\": {:.4}}}",
                p.f64_ns,
                p.history_ns,
                p.ratio()
            )
        })
        .collect();
    format!(
        "{{\"n\": {}, \"pairs\": [{}], \"median_ratio\": {}}}",
        r.n,
        pairs.join(", "),
        r.median_ratio()
            .map_or("null".into(), |m| format!("{m:.4}"))
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_bigint::BigInt;

    #[test]
    fn ratios_and_their_median() {
        let pair = |f64_ns, history_ns| Pair { f64_ns, history_ns };
        let r = HistoryReport {
            n: 10,
            pairs: vec![pair(2.0, 60.0), pair(4.0, 40.0), pair(1.0, 20.0)],
        };
        assert_eq!(r.pairs[0].ratio(), 30.0);
        assert_eq!(r.median_ratio(), Some(20.0));
        let text = table(&r);
        assert!(
            text.contains("median ratio 20.00 (range 10.00–30.00 over 3 pairs)"),
            "{text}"
        );
        assert!(json(&r).ends_with("\"median_ratio\": 20.0000}"));
    }

    #[test]
    fn pairs_measure_both_calls() {
        let t = BigRational::new(BigInt::from(1), BigInt::from(100));
        let r = run(3000, 3, &t).unwrap();
        assert_eq!((r.n, r.pairs.len()), (3000, 3));
        for p in &r.pairs {
            assert!(p.f64_ns > 0.0 && p.history_ns > 0.0, "{p:?}");
        }
        let m = r.median_ratio().unwrap();
        let mut ratios: Vec<f64> = r.pairs.iter().map(Pair::ratio).collect();
        ratios.sort_by(f64::total_cmp);
        assert_eq!(m, ratios[1]);
        let text = table(&r);
        assert_eq!(text.lines().count(), 2 + 3 + 1, "{text}");
        assert!(text.contains(&format!("median ratio {m:.2}")), "{text}");
        let v: serde_json::Value = serde_json::from_str(&json(&r)).expect("valid JSON");
        assert_eq!(v["pairs"].as_array().map(Vec::len), Some(3));
        assert_eq!(v["n"], 3000);
        assert!((v["median_ratio"].as_f64().unwrap() - m).abs() < 1e-3 * m);
    }
}
