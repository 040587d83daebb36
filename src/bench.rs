//! `sticky bench`: PAVA at one time `t` on random scenes, every method timed
//! in the same run on fresh inputs (a new scene for each repetition, so that
//! the branch predictor cannot learn one input), in ns per particle, with
//! the ratio to our own f64 PAVA; the peers (scipy, scikit-learn) through
//! `scripts/peers.py` on identical data.
//!
//! Methods:
//! * `f64` — [`crate::projection::isotonic`] on `f64` (the generic code);
//! * `exact_int` — [`crate::kernel::blocks_at`] on data that fit `i128`
//!   (exact block means in lowest terms);
//! * `exact_bigint` — the same kernel on data with 30-digit decimals, which
//!   forces the `BigInt` loop;
//! * `bigrational_naive` — the generic PAVA on `BigRational` (measured on
//!   N/10 particles and reported per particle, saying so);
//! * `events` — the full exact event-driven trajectory
//!   ([`crate::trajectory::Trajectory::new`]).
//!
//! Timings are whole calls measured with `std::time::Instant` (median of the
//! repetitions); they are reports, never test assertions.

use std::path::Path;
use std::process::Command;
use std::time::Instant;

use num_bigint::BigInt;
use num_rational::BigRational;

use crate::generate::{initial_data, Limits, SplitMix64};
use crate::initial::InitialData;
use crate::kernel::{blocks_at, IntegerData, Width};
use crate::projection::{isotonic, pava_blocks};
use crate::scalar::Scalar;
use crate::trajectory::Trajectory;

/// What to measure.
#[derive(Debug, Clone)]
pub struct BenchOptions {
    /// Number of particles.
    pub n: usize,
    /// Repetitions (each on a fresh scene).
    pub reps: usize,
    /// Run the Python peers (skipped with a message when Python is absent).
    pub peers: bool,
    /// Time the full event-driven trajectory too.
    pub events: bool,
}

/// One measured method.
#[derive(Debug, Clone)]
pub struct Measure {
    /// Method name.
    pub method: &'static str,
    /// Median ns per particle (`None` when not measured).
    pub ns_per_particle: Option<f64>,
    /// A remark (e.g. measured on a smaller N, or why skipped).
    pub note: String,
}

/// The benchmark result.
#[derive(Debug, Clone)]
pub struct BenchReport {
    /// N.
    pub n: usize,
    /// Our methods.
    pub ours: Vec<Measure>,
    /// The peers.
    pub peers: Vec<Measure>,
}

fn median(mut v: Vec<f64>) -> Option<f64> {
    if v.is_empty() {
        return None;
    }
    v.sort_by(f64::total_cmp);
    Some(v[v.len() / 2])
}

/// A random admissible scene of exactly `n` particles with dyadic data
/// (gaps in `{0, …, 1023}/1024` beyond `2r = 1/N`, one in eight a contact;
/// velocities in `{−512, …, 512}/256`, raised on contacts to stay in the
/// velocity cone), so that `f64` holds the initial data exactly and the
/// peers see the same numbers.
pub fn scene(n: usize, seed: u64) -> InitialData<BigRational> {
    let mut rng = SplitMix64::new(seed);
    let q = |a: i64, b: i64| BigRational::new(BigInt::from(a), BigInt::from(b));
    let mut shifted = Vec::with_capacity(n);
    let mut velocities: Vec<BigRational> = Vec::with_capacity(n);
    let mut pos = 0i64;
    for i in 0..n {
        let r = rng.next_u64();
        let contact = i > 0 && r % 8 == 0;
        if i > 0 && !contact {
            pos += 1 + ((r >> 3) % 1023) as i64;
        }
        let mut v = ((r >> 16) % 1025) as i64 - 512;
        if contact {
            if let Some(prev) = velocities.last() {
                let prev = (prev * BigRational::from_integer(BigInt::from(256)))
                    .to_integer()
                    .to_string()
                    .parse::<i64>()
                    .unwrap_or(v);
                v = v.max(prev);
            }
        }
        shifted.push(q(pos, 1024));
        velocities.push(q(v, 256));
    }
    let two_r = q(1, n.max(1) as i64);
    let positions = crate::initial::unshift(&shifted, &two_r);
    InitialData::new(
        two_r / BigRational::from_integer(BigInt::from(2)),
        positions,
        velocities,
    )
    .unwrap_or_else(|_| initial_data(&[], Limits::default()))
}

/// The same scene with every position shifted by a 30-digit decimal, so
/// that the common denominators no longer fit `i128`.
fn big_scene(d: &InitialData<BigRational>) -> InitialData<BigRational> {
    let offset = BigRational::new(
        BigInt::parse_bytes(b"123456789012345678901234567891", 10).unwrap_or_default(),
        BigInt::from(10u32).pow(29),
    );
    let positions = d.positions().iter().map(|x| x + &offset).collect();
    InitialData::new(d.radius().clone(), positions, d.velocities().to_vec())
        .unwrap_or_else(|_| d.clone())
}

/// `ỹ = x̃⁰ + t u⁰` in f64 (the peers' input).
fn free_f64(d: &InitialData<BigRational>, t: &BigRational) -> Vec<f64> {
    d.shifted_positions()
        .iter()
        .zip(d.velocities())
        .map(|(x, u)| (x + t * u).to_f64_lossy())
        .collect()
}

fn time<R>(f: impl FnOnce() -> R) -> (f64, R) {
    let t0 = Instant::now();
    let r = f();
    (t0.elapsed().as_secs_f64() * 1e9, r)
}

/// Runs the benchmark at time `t` (`t` small: few clusters; `t` large: few
/// large clusters).
pub fn run(opts: &BenchOptions, t: &BigRational, scripts: &Path) -> BenchReport {
    let n = opts.n.max(1);
    let nf = n as f64;
    let (mut f64s, mut ints, mut bigs, mut naive, mut events) =
        (vec![], vec![], vec![], vec![], vec![]);
    let naive_n = (n / 10).max(1);
    let mut peer_inputs: Vec<Vec<f64>> = Vec::new();
    let mut widths = Vec::new();
    for rep in 0..opts.reps.max(1) {
        let data = scene(n, 1000 + rep as u64);
        let y = free_f64(&data, t);
        let (ns, out) = time(|| isotonic::<f64>(&y));
        std::hint::black_box(out);
        f64s.push(ns / nf);
        let ints_data = IntegerData::new(&data);
        let (ns, b) = time(|| blocks_at(&ints_data, t));
        widths.push(b.width());
        ints.push(ns / nf);
        let big = IntegerData::new(&big_scene(&data));
        let (ns, b) = time(|| blocks_at(&big, t));
        if b.width() != Width::I128 {
            bigs.push(ns / nf);
        }
        let small = scene(naive_n, 5000 + rep as u64);
        let ys: Vec<BigRational> = small
            .shifted_positions()
            .iter()
            .zip(small.velocities())
            .map(|(x, u)| x + t * u)
            .collect();
        let (ns, out) = time(|| pava_blocks(&ys, Some(small.velocities())));
        std::hint::black_box(out);
        naive.push(ns / naive_n as f64);
        if opts.events {
            let (ns, traj) = time(|| Trajectory::new(data.clone()));
            std::hint::black_box(traj.impulses().len());
            events.push(ns / nf);
        }
        peer_inputs.push(y);
    }
    let m = |method, v: Vec<f64>, note: String| Measure {
        method,
        ns_per_particle: median(v),
        note,
    };
    let ours = vec![
        m("f64", f64s, "generic PAVA on f64".into()),
        m(
            "exact_int",
            ints,
            format!(
                "integer kernel, width {:?}",
                widths.first().copied().unwrap_or(Width::I128)
            ),
        ),
        m(
            "exact_bigint",
            bigs,
            "integer kernel on 30-digit decimals (BigInt loop)".into(),
        ),
        m(
            "bigrational_naive",
            naive,
            format!(
                "generic PAVA on BigRational, measured on N = {naive_n} and reported per particle"
            ),
        ),
        m("adaptive", vec![], "not implemented yet".into()),
        m(
            "events",
            events,
            if opts.events {
                "full exact event-driven trajectory".into()
            } else {
                "skipped".into()
            },
        ),
    ];
    let peers = if opts.peers {
        run_peers(&peer_inputs, scripts)
    } else {
        vec![]
    };
    BenchReport { n, ours, peers }
}

/// Writes the inputs as raw little-endian f64 and runs `scripts/peers.py`,
/// which prints `name ns_per_particle` lines.
fn run_peers(inputs: &[Vec<f64>], scripts: &Path) -> Vec<Measure> {
    let skipped = |why: String| {
        vec![
            Measure {
                method: "scipy",
                ns_per_particle: None,
                note: why.clone(),
            },
            Measure {
                method: "sklearn",
                ns_per_particle: None,
                note: why,
            },
        ]
    };
    let dir = std::env::temp_dir().join(format!("sticky-bench-{}", std::process::id()));
    if let Err(e) = std::fs::create_dir_all(&dir) {
        return skipped(format!("cannot create {}: {e}", dir.display()));
    }
    let mut files = Vec::new();
    for (k, y) in inputs.iter().enumerate() {
        let path = dir.join(format!("y{k}.f64"));
        let bytes: Vec<u8> = y.iter().flat_map(|v| v.to_le_bytes()).collect();
        if let Err(e) = std::fs::write(&path, bytes) {
            return skipped(format!("cannot write {}: {e}", path.display()));
        }
        files.push(path);
    }
    let out = Command::new("python3")
        .arg(scripts.join("peers.py"))
        .args(&files)
        .output();
    let _ = std::fs::remove_dir_all(&dir);
    let out = match out {
        Ok(o) if o.status.success() => o,
        Ok(o) => {
            return skipped(format!(
                "peers.py failed: {}",
                String::from_utf8_lossy(&o.stderr)
                    .lines()
                    .last()
                    .unwrap_or("")
            ))
        }
        Err(e) => return skipped(format!("python3 not available: {e}")),
    };
    let text = String::from_utf8_lossy(&out.stdout);
    ["scipy", "sklearn"]
        .iter()
        .map(|name| {
            let v = text
                .lines()
                .find_map(|l| l.strip_prefix(&format!("{name} ")))
                .map(str::trim);
            let parsed = v.and_then(|s| s.parse::<f64>().ok());
            Measure {
                method: name,
                ns_per_particle: parsed,
                note: match (parsed, v) {
                    (Some(_), _) => "same data, same run".into(),
                    (None, Some(s)) => s.to_string(),
                    (None, None) => "no result".into(),
                },
            }
        })
        .collect()
}

fn num(v: Option<f64>) -> String {
    v.map_or("null".into(), |x| format!("{x:.2}"))
}

/// `{"n": …, "ns_per_particle": {…}, "peers": {…}}`.
pub fn json(r: &BenchReport) -> String {
    let items = |ms: &[Measure]| {
        ms.iter()
            .map(|m| format!("\"{}\": {}", m.method, num(m.ns_per_particle)))
            .collect::<Vec<_>>()
            .join(", ")
    };
    format!(
        "{{\"n\": {}, \"ns_per_particle\": {{{}}}, \"peers\": {{{}}}}}",
        r.n,
        items(&r.ours),
        items(&r.peers)
    )
}

/// A table with the ratio to our f64 PAVA.
pub fn table(r: &BenchReport) -> String {
    let base = r
        .ours
        .iter()
        .find(|m| m.method == "f64")
        .and_then(|m| m.ns_per_particle);
    let mut out = format!(
        "N = {}\n  {:<18} {:>12} {:>10}  note\n",
        r.n, "method", "ns/particle", "× f64"
    );
    for m in r.ours.iter().chain(&r.peers) {
        let ratio = match (m.ns_per_particle, base) {
            (Some(v), Some(b)) if b > 0.0 => format!("{:.2}", v / b),
            _ => "—".into(),
        };
        out.push_str(&format!(
            "  {:<18} {:>12} {:>10}  {}\n",
            m.method,
            m.ns_per_particle.map_or("—".into(), |v| format!("{v:.1}")),
            ratio,
            m.note
        ));
    }
    out
}
