//! The scaling study (`sticky bench --scaling`): [`run`] for every N in
//! both regimes, the CSV, the log-log charts and the fitted slopes.

use std::path::Path;

use num_bigint::BigInt;
use num_rational::BigRational;

use super::{run, BenchOptions, Metric};

/// The two regimes of the scaling study: the bench scene at a small time
/// (almost every particle its own block) and at a large one (few large
/// clusters).
pub const REGIMES: [(&str, i64, i64); 2] = [("few-clusters", 1, 100), ("large-clusters", 20, 1)];

/// What `sticky bench --scaling` measures.
#[derive(Debug, Clone)]
pub struct ScalingOptions {
    /// The particle numbers (each a full [`run`]).
    pub ns: Vec<usize>,
    /// Repetitions per N (fresh scenes).
    pub reps: usize,
    /// Run the Python peers or not.
    pub peers: super::Peers,
    /// Warm timings or peak memory ([`super::Memory::Cold`]).
    pub metric: Metric,
    /// Output folder.
    pub out: std::path::PathBuf,
}

/// One row of the scaling study.
#[derive(Debug, Clone)]
pub struct ScalingRow {
    /// The regime ([`REGIMES`]).
    pub regime: &'static str,
    /// N.
    pub n: usize,
    /// Method name.
    pub method: &'static str,
    /// Median ns per particle.
    pub ns_per_particle: Option<f64>,
    /// Median peak memory, MiB (memory mode only).
    pub peak_mib: Option<f64>,
}

/// Runs [`run`] for every N and regime, writes `scaling.csv` (or
/// `scaling-memory.csv`), one chart per regime (ns per particle against N,
/// log-log, every method and peer; or MiB against N) and returns the rows
/// with the paths written.
pub fn scaling(
    opts: &ScalingOptions,
    scripts: &Path,
    mut progress: impl FnMut(&str),
) -> Result<(Vec<ScalingRow>, Vec<std::path::PathBuf>), crate::report::plot::PlotError> {
    let mut rows = Vec::new();
    for &(regime, p, q) in &REGIMES {
        let t = BigRational::new(BigInt::from(p), BigInt::from(q));
        for &n in &opts.ns {
            progress(&format!("{regime}: N = {n}"));
            // Small N: more repetitions (fresh scenes), up to 30.
            let reps = opts.reps.max((1_000_000 / n.max(1)).min(30));
            let r = run(
                &BenchOptions {
                    n,
                    reps,
                    peers: opts.peers,
                    events: super::Events::Time,
                    metric: opts.metric,
                },
                &t,
                scripts,
            );
            for m in r.ours.iter().chain(&r.peers) {
                rows.push(ScalingRow {
                    regime,
                    n,
                    method: m.method,
                    ns_per_particle: m.ns_per_particle,
                    peak_mib: m.peak_mib,
                });
            }
        }
    }
    let stem = stem(opts.metric);
    let mut csv = String::from("regime,n,method,ns_per_particle,peak_mib\n");
    let cell = |v: Option<f64>| v.map_or(String::new(), |x| format!("{x:.4}"));
    for r in &rows {
        csv.push_str(&format!(
            "{},{},{},{},{}\n",
            r.regime,
            r.n,
            r.method,
            cell(r.ns_per_particle),
            cell(r.peak_mib)
        ));
    }
    std::fs::create_dir_all(&opts.out).map_err(|e| crate::report::plot::PlotError::Io {
        path: opts.out.clone(),
        message: e.to_string(),
    })?;
    let csv_path = opts.out.join(format!("{stem}.csv"));
    crate::report::plot::write_whole(&csv_path, csv.as_bytes())?;
    let mut written = vec![csv_path];
    written.extend(scaling_charts(&rows, &opts.out, opts.metric)?);
    Ok((rows, written))
}

/// Reads the rows of a `scaling.csv` (or `scaling-memory.csv`) that
/// [`scaling`] wrote; a line that is not a row (bad field count, unknown
/// regime, bad number) is an error naming its line.
pub fn read_scaling_csv(text: &str) -> Result<Vec<ScalingRow>, String> {
    let mut rows = Vec::new();
    let mut names: Vec<&'static str> = Vec::new();
    for (k, line) in text.lines().enumerate().skip(1) {
        if line.trim().is_empty() {
            continue;
        }
        let bad = |what: &str| format!("line {}: {what}: {line:?}", k + 1);
        let f: Vec<&str> = line.split(',').collect();
        let [regime, n, method, ns, mib] = f[..] else {
            return Err(bad("expected 5 fields"));
        };
        let regime = REGIMES
            .iter()
            .map(|r| r.0)
            .find(|r| *r == regime)
            .ok_or_else(|| bad("unknown regime"))?;
        let n = n.parse().map_err(|_| bad("bad N"))?;
        let num = |v: &str| -> Result<Option<f64>, String> {
            if v.is_empty() {
                Ok(None)
            } else {
                v.parse().map(Some).map_err(|_| bad("bad number"))
            }
        };
        // Method names are few: each distinct one is kept once for the
        // process (rows hold `&'static str`, as when measured).
        let method = match names.iter().find(|m| **m == method) {
            Some(m) => *m,
            None => {
                let m: &'static str = Box::leak(method.to_string().into_boxed_str());
                names.push(m);
                m
            }
        };
        rows.push(ScalingRow {
            regime,
            n,
            method,
            ns_per_particle: num(ns)?,
            peak_mib: num(mib)?,
        });
    }
    Ok(rows)
}

/// The file stem of the study's CSV and charts.
fn stem(metric: Metric) -> &'static str {
    match metric {
        Metric::Time => "scaling",
        Metric::PeakMemory => "scaling-memory",
    }
}

/// The charts of [`scaling`] redrawn from its rows (for example read back
/// from a CSV with [`read_scaling_csv`]), one per regime, into `out` as
/// `scaling-REGIME` (or `scaling-memory-REGIME`); returns the paths written.
pub fn scaling_charts(
    rows: &[ScalingRow],
    out: &Path,
    metric: Metric,
) -> Result<Vec<std::path::PathBuf>, crate::report::plot::PlotError> {
    let stem = stem(metric);
    let mut written = Vec::new();
    for &(regime, p, q) in &REGIMES {
        let chart = scaling_chart(rows, regime, &format!("{p}/{q}"), metric);
        written.extend(
            crate::report::plot::write_chart(&chart, out, &format!("{stem}-{regime}"))?.paths(),
        );
    }
    Ok(written)
}

/// Per method: the least-squares slope of the total time (or memory)
/// against N on log-log axes (1 = linear).
pub fn slopes(rows: &[ScalingRow], regime: &str, metric: Metric) -> Vec<(&'static str, f64)> {
    let mut methods: Vec<&'static str> = Vec::new();
    for r in rows.iter().filter(|r| r.regime == regime) {
        if !methods.contains(&r.method) {
            methods.push(r.method);
        }
    }
    methods
        .into_iter()
        .filter_map(|m| {
            let pts: Vec<(f64, f64)> = rows
                .iter()
                .filter(|r| r.regime == regime && r.method == m)
                .filter_map(|r| {
                    let v = match metric {
                        Metric::PeakMemory => r.peak_mib,
                        Metric::Time => r.ns_per_particle.map(|v| v * r.n as f64),
                    };
                    v.filter(|v| *v > 0.0).map(|v| (r.n as f64, v))
                })
                .collect();
            (pts.len() >= 2).then(|| (m, crate::rate::log_log_slope(&pts)))
        })
        .collect()
}

fn scaling_chart(
    rows: &[ScalingRow],
    regime: &str,
    t: &str,
    metric: Metric,
) -> crate::report::plot::Chart {
    use crate::report::plot::{palette, series_style, Axis, Chart, Series};
    let slopes = slopes(rows, regime, metric);
    let title = if metric == Metric::PeakMemory {
        format!("Peak memory against N — {regime} (t = {t})")
    } else {
        format!("Cost per particle against N — {regime} (t = {t}), warm, median of the repetitions")
    };
    let y = if metric == Metric::PeakMemory {
        "peak resident-set growth (MiB)"
    } else {
        "ns per particle"
    };
    let mut chart = Chart::new(title, Axis::log("N (particles)"), Axis::log(y));
    for (k, (method, slope)) in slopes.iter().enumerate() {
        let pts: Vec<(f64, f64)> = rows
            .iter()
            .filter(|r| r.regime == regime && r.method == *method)
            .filter_map(|r| {
                let v = if metric == Metric::PeakMemory {
                    r.peak_mib
                } else {
                    r.ns_per_particle
                };
                v.filter(|v| *v > 0.0).map(|v| (r.n as f64, v))
            })
            .collect();
        let label = format!("{method} (slope {slope:.2})");
        // More than ten series: colour, marker and dash vary together.
        chart
            .series
            .push(Series::line(label, palette(k), pts).with_style(series_style(k)));
    }
    chart
}
