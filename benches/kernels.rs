//! `cargo bench`: micro-benchmarks of the exact kernels' building blocks, on
//! fresh inputs for every sample (a new scene per sample, so the branch
//! predictor cannot learn one input). No benchmark framework: each line is
//! the median of the samples, in ns per particle (or per operation), with
//! the ratio to f64 PAVA measured in the same run. Reports, never
//! assertions; `sticky bench` is the whole-call comparison with the peers.
//! `sticky bench` runs under `MALLOC_MMAP_MAX_=0` (see `sticky::report::bench::Memory`);
//! `MALLOC_MMAP_MAX_=0 cargo bench` gives the same allocator setting here.

use std::hint::black_box;
use std::time::Instant;

use num_bigint::BigInt;
use num_rational::BigRational;

use sticky::fast::adaptive::adaptive_blocks_at;
use sticky::fast::kernel::{blocks_at, IntegerData};
use sticky::fast::merge::IntegerTrajectory;
use sticky::fast::wide::Int;
use sticky::projection::isotonic;
use sticky::report::bench::{decimal_scene, scene};
use sticky::scalar::Scalar;

const SAMPLES: usize = 9;

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Median over fresh inputs of `f(input)`, in ns per unit.
fn sample<I, R>(units: usize, mut make: impl FnMut(u64) -> I, mut f: impl FnMut(&I) -> R) -> f64 {
    // One warm-up sample on its own input.
    black_box(f(&make(999)));
    let v = (0..SAMPLES as u64)
        .map(|s| {
            let input = make(s);
            let t0 = Instant::now();
            black_box(f(&input));
            t0.elapsed().as_secs_f64() * 1e9 / units as f64
        })
        .collect();
    median(v)
}

fn main() {
    // `cargo bench -- <filter>` passes extra arguments; `--bench` is cargo's.
    // `n=<N>` chooses the sizes (10^4 and 10^5 by default).
    let (sizes, filter): (Vec<String>, Vec<String>) = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with("--"))
        .partition(|a| a.starts_with("n="));
    let sizes: Vec<usize> = sizes.iter().filter_map(|a| a[2..].parse().ok()).collect();
    let sizes = if sizes.is_empty() {
        vec![10_000, 100_000]
    } else {
        sizes
    };
    let wanted = |name: &str| filter.is_empty() || filter.iter().any(|f| name.contains(f.as_str()));
    let t = BigRational::new(BigInt::from(1), BigInt::from(100));
    for n in sizes {
        let free = |s: u64| -> Vec<f64> {
            let d = scene(n, s);
            d.shifted_positions()
                .iter()
                .zip(d.velocities())
                .map(|(x, u)| (x + &t * u).to_f64_lossy())
                .collect()
        };
        let base = sample(n, free, |y| isotonic::<f64>(y));
        println!("pava/f64/{n:<8} {base:>10.2} ns/particle   1.00× f64");
        let line = |name: &str, v: &dyn Fn() -> f64| {
            if wanted(name) {
                let v = v();
                println!("{name:<22} {v:>10.2} ns/particle {:>6.2}× f64", v / base);
            }
        };
        let ints = |s: u64| IntegerData::new(&scene(n, s));
        line(&format!("pava/i128/{n}"), &|| {
            sample(n, ints, |d| blocks_at(d, &t))
        });
        let wide = |s: u64| IntegerData::new(&decimal_scene(&scene(n, s), 30));
        line(&format!("pava/i256/{n}"), &|| {
            sample(n, wide, |d| blocks_at(d, &t))
        });
        let wider = |s: u64| IntegerData::new(&decimal_scene(&scene(n, s), 100));
        line(&format!("pava/i512/{n}"), &|| {
            sample(n, wider, |d| blocks_at(d, &t))
        });
        let big = |s: u64| IntegerData::new(&decimal_scene(&scene(n, s), 200));
        line(&format!("pava/bigint/{n}"), &|| {
            sample(n, big, |d| blocks_at(d, &t))
        });
        line(&format!("pava/adaptive-big/{n}"), &|| {
            sample(n, big, |d| adaptive_blocks_at(d, &t))
        });
        line(&format!("history/i64/{n}"), &|| {
            sample(n, |s| scene(n, s), IntegerTrajectory::new)
        });
        line(&format!("means/lowest-terms/{n}"), &|| {
            sample(
                n,
                |s| blocks_at(&IntegerData::new(&scene(n, s)), &t),
                |b| (0..b.len()).map(|j| b.mean_y(j)).collect::<Vec<_>>(),
            )
        });
    }
    // 256- and 512-bit arithmetic, per operation.
    if wanted("i256") {
        wide_ops::<4>("i256");
    }
    if wanted("i512") {
        wide_ops::<8>("i512");
    }
}

/// `Int<L>` addition, multiplication and comparison, per operation.
fn wide_ops<const L: usize>(name: &str) {
    {
        let ops = 1_000_000;
        let vals = |s: u64| -> Vec<Int<L>> {
            let mut x = s.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
            (0..ops)
                .map(|_| {
                    x ^= x << 13;
                    x ^= x >> 7;
                    x ^= x << 17;
                    Int::<L>::from_i128((i128::from(x as i64) << 40) ^ i128::from(x))
                })
                .collect()
        };
        let add = sample(ops, vals, |v| {
            v.iter().fold(Int::<L>::ZERO, |a, b| a.wrapping_add(*b))
        });
        let mul = sample(ops, vals, |v| {
            v.windows(2).map(|w| w[0].wrapping_mul(w[1])).max()
        });
        let cmp = sample(ops, vals, |v| v.windows(2).filter(|w| w[0] < w[1]).count());
        println!("{name}/add               {add:>10.2} ns/op");
        println!("{name}/mul               {mul:>10.2} ns/op");
        println!("{name}/cmp               {cmp:>10.2} ns/op");
    }
}
