//! The scenes: the speed-vs-accuracy suite (random scenes and shipped
//! scenes, [`crate::scene::SHIPPED`]) and the stability scenes built to
//! break the methods, each exact and rounded to `f64`.

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::Zero;

use crate::generate::{initial_data, Limits, SplitMix64};
use crate::initial::{unshift, InitialData};
use crate::reference::{round_to_f64, velocity_scale};
use crate::scalar::Scalar;
use crate::scene;

use super::jobs::{STABILITY_STEP_CAP, STEP_CAP};
use super::{AtlasError, Size};

/// One scene at one time, exact and rounded.
pub(super) struct Case {
    pub(super) name: String,
    pub(super) description: String,
    pub(super) exact: InitialData<BigRational>,
    pub(super) data: InitialData<f64>,
    pub(super) t: f64,
    pub(super) tq: BigRational,
    pub(super) n: usize,
    pub(super) two_r: f64,
    pub(super) v: f64,
    /// `Δt` of the time-steppers in the stability section.
    pub(super) step: f64,
    /// Sweep cap of the one-time iterative projection in the stability
    /// section.
    pub(super) cap: usize,
    /// Sweep cap of the time-steppers' inner solves in the stability
    /// section.
    pub(super) step_cap: usize,
}

impl Case {
    fn new(
        name: &str,
        description: &str,
        exact: InitialData<BigRational>,
        t: f64,
    ) -> Result<Case, AtlasError> {
        let scene_err = |message: String| AtlasError::Scene {
            scene: name.to_string(),
            message,
        };
        let data = round_to_f64(&exact).map_err(|e| scene_err(e.to_string()))?;
        let tq = t
            .to_big_rational()
            .ok_or_else(|| scene_err(format!("time {t} is not finite")))?;
        let v = velocity_scale(&data);
        Ok(Case {
            name: name.to_string(),
            description: description.to_string(),
            n: data.n(),
            two_r: data.two_r(),
            v,
            step: t / 1024.0,
            cap: 100_000,
            step_cap: STEP_CAP,
            exact,
            data,
            t,
            tq,
        })
    }
}

use crate::rational::ratio as q;

pub(super) fn data_err(name: &str) -> impl Fn(crate::Error) -> AtlasError + '_ {
    move |e| AtlasError::Scene {
        scene: name.to_string(),
        message: e.to_string(),
    }
}

/// Random scene of `N` particles (fixed seed per `N`).
fn random_case(n: usize, t: f64) -> Result<Case, AtlasError> {
    let mut rng = SplitMix64::new(0x5EED_0000 + n as u64);
    let bytes = rng.bytes(32 * n + 64);
    let limits = Limits {
        max_n: n,
        ..Limits::default()
    };
    let exact = initial_data(&bytes, limits);
    Case::new(
        &format!("random-{n}"),
        "generate::initial_data (groups of clusters, chains meeting at one instant)",
        exact,
        t,
    )
}

/// A shipped scene, at its `t_end`.
fn shipped_case(name: &str) -> Result<Case, AtlasError> {
    let text = scene::shipped(name).ok_or_else(|| AtlasError::Scene {
        scene: name.to_string(),
        message: "not a shipped scene".to_string(),
    })?;
    let s = scene::parse(text).map_err(data_err(name))?;
    let t = s
        .t_end
        .as_ref()
        .map(Scalar::to_f64_lossy)
        .ok_or_else(|| AtlasError::Scene {
            scene: name.to_string(),
            message: "no t_end".to_string(),
        })?;
    let description = s.description.clone().unwrap_or_default();
    Case::new(name, &description, s.data, t)
}

/// The shipped scenes of the suite ([`scene::SHIPPED`]), by name.
const SHIPPED_SCENES: [&str; 3] = [
    "appendix-c-two-blocks",
    "three-cluster-simultaneous",
    "riemann-compression",
];

/// The speed-vs-accuracy suite.
pub(super) fn suite(size: Size) -> Result<Vec<Case>, AtlasError> {
    let sizes: &[usize] = if size == Size::Quick {
        &[10, 100, 1000]
    } else {
        &[10, 100, 1000, 10_000, 100_000]
    };
    let mut out = Vec::new();
    for &n in sizes {
        out.push(random_case(n, 1025.0 / 1024.0)?);
    }
    for name in SHIPPED_SCENES {
        out.push(shipped_case(name)?);
    }
    Ok(out)
}

/// Pairs colliding at `1 + (j − m/2)·2⁻⁶⁰`: collision times closer than the
/// resolution of `f64` near `t = 1` (`2⁻⁵²`), measured at `t = 1`.
fn near_simultaneous() -> Result<Case, AtlasError> {
    let name = "near-simultaneous";
    let m: i64 = 64;
    let two_r = q(1, 2);
    let tiny = BigRational::new(BigInt::from(1), BigInt::from(1) << 60usize);
    let mut x = Vec::new();
    let mut u = Vec::new();
    for j in 0..m {
        let tau = q(1, 1) + &(tiny.clone() * q(j - m / 2, 1));
        let left = q(10 * j, 1);
        let right = left.clone() + &two_r + &(q(2, 1) * &tau);
        x.extend([left, right]);
        u.extend([q(1, 1), q(-1, 1)]);
    }
    let exact = InitialData::new(q(1, 4), x, u).map_err(data_err(name))?;
    Case::new(
        name,
        "64 pairs closing at speed 2, pair j colliding at t = 1 + (j − 32)·2^-60 (closer than one ulp of t = 1); measured at t = 1, when exactly 33 pairs have collided",
        exact,
        1.0,
    )
}

/// Chains of 3 or 4 clusters meeting at one instant `T = 1` (velocities in
/// thirds and sevenths, 2r = 1/3: nothing is a dyadic rational), measured
/// at `t = T`.
fn multi_cluster_instant() -> Result<Case, AtlasError> {
    let name = "multi-cluster-instant";
    let chains: i64 = 100;
    let two_r = q(1, 3);
    let mut shifted = Vec::new();
    let mut u = Vec::new();
    for j in 0..chains {
        let k = 3 + (j % 2);
        let w = q(1, 3) + &q(j % 7, 7);
        let meet = q(100 * j, 1);
        for c in 0..k {
            let v = w.clone() * q(k - 1 - 2 * c, 1);
            let size = 1 + ((j + c) % 3);
            let p = meet.clone() - &v; // T = 1
            for _ in 0..size {
                shifted.push(p.clone());
                u.push(v.clone());
            }
        }
    }
    let x = unshift(&shifted, &two_r);
    let exact = InitialData::new(q(1, 6), x, u).map_err(data_err(name))?;
    Case::new(
        name,
        "100 chains of 3 or 4 clusters (sizes 1–3) meeting at the single instant t = 1 (velocities multiples of 1/3 + k/7, 2r = 1/3); measured at t = 1",
        exact,
        1.0,
    )
}

/// A Riemann compression at coordinates `10⁹ + 2(i − 1)/N` with `2r = 1/N`
/// (excess gaps `1/N`), measured at `t = 1/4`.
fn offset_1e9(n: usize) -> Result<Case, AtlasError> {
    let name = "offset-1e9";
    let nn = n as i64;
    let base = q(1_000_000_000, 1);
    let x: Vec<BigRational> = (0..nn).map(|i| base.clone() + &q(2 * i, nn)).collect();
    let u: Vec<BigRational> = (0..nn)
        .map(|i| if i < nn / 2 { q(1, 1) } else { q(-1, 1) })
        .collect();
    let exact = InitialData::new(q(1, 2 * nn), x, u).map_err(data_err(name))?;
    Case::new(
        name,
        &format!("N = {n}, x_i = 1e9 + 2(i−1)/N, 2r = 1/N (gaps 1/N beyond contact), velocities +1 then −1 (a compression); measured at t = 1/4"),
        exact,
        0.25,
    )
}

/// `N` particles with `2r = 1/N`, excess gaps `k·10⁻⁶·2r` (`k = 1 … 9`)
/// and velocities in `[−1, 1]`, measured at `t = 2⁻²⁰` (about one
/// diameter of travel).
fn tiny_gaps(n: usize) -> Result<Case, AtlasError> {
    let name = if n >= 1_000_000 {
        "tiny-gaps-1e6".to_string()
    } else {
        format!("tiny-gaps-{n}")
    };
    let nn = n as i64;
    let mut rng = SplitMix64::new(0x7172_0000 + n as u64);
    let mut shifted = Vec::with_capacity(n);
    let mut u = Vec::with_capacity(n);
    let mut acc = <BigRational as Zero>::zero();
    for i in 0..n {
        if i > 0 {
            let k = 1 + (rng.next_u64() % 9) as i64;
            acc += q(k, nn * 1_000_000);
        }
        shifted.push(acc.clone());
        let v = (rng.next_u64() % 2001) as i64 - 1000;
        u.push(q(v, 1000));
    }
    let two_r = q(1, nn);
    let x = unshift(&shifted, &two_r);
    let exact = InitialData::new(q(1, 2 * nn), x, u).map_err(data_err(&name))?;
    Case::new(
        &name,
        &format!("N = {n}, 2r = 1/N, gaps k·1e-6·2r beyond contact (k = 1…9), velocities k/1000 in [−1, 1]; measured at t = 2^-20 (about one diameter of travel)"),
        exact,
        1.0 / 1_048_576.0,
    )
}

/// A random scene of 20 particles measured at `t = 10⁶`.
fn long_horizon(size: Size) -> Result<Case, AtlasError> {
    let mut rng = SplitMix64::new(0x10C6);
    let bytes = rng.bytes(1000);
    let exact = initial_data(
        &bytes,
        Limits {
            max_n: 20,
            ..Limits::default()
        },
    );
    let mut case = Case::new(
        "long-horizon",
        "a random scene of 20 particles (generate::initial_data) measured at t = 1e6",
        exact,
        1e6,
    )?;
    case.step = size.pick(4.0, 0.25);
    Ok(case)
}

/// `N = 1000` particles at unit spacing (2r = 1/2) with velocities
/// `±10^e`, `e ∈ {−6, …, 6}`: twelve orders of magnitude, measured at `t = 1`.
fn velocity_decades() -> Result<Case, AtlasError> {
    let name = "velocities-12-decades";
    let mut rng = SplitMix64::new(0x1E12);
    let n = 1000;
    let mut x = Vec::with_capacity(n);
    let mut u = Vec::with_capacity(n);
    for i in 0..n {
        x.push(q(i as i64, 1));
        let e = (rng.next_u64() % 13) as i32 - 6;
        let sign = if rng.next_u64() % 2 == 0 { 1 } else { -1 };
        let mag = if e >= 0 {
            q(sign * 10i64.pow(e as u32), 1)
        } else {
            q(sign, 10i64.pow((-e) as u32))
        };
        u.push(mag);
    }
    let exact = InitialData::new(q(1, 4), x, u).map_err(data_err(name))?;
    Case::new(
        name,
        "N = 1000 at unit spacing, 2r = 1/2, velocities ±10^e with e uniform in −6…6 (twelve orders of magnitude); measured at t = 1",
        exact,
        1.0,
    )
}

/// The stability scenes.
pub(super) fn stability_suite(size: Size) -> Result<Vec<Case>, AtlasError> {
    let mut out = vec![
        near_simultaneous()?,
        multi_cluster_instant()?,
        offset_1e9(size.pick(1000, 10_000))?,
        tiny_gaps(size.pick(10_000, 1_000_000))?,
        long_horizon(size)?,
        velocity_decades()?,
    ];
    // Time-steppers: a power of two of steps, at most `max_steps` and about
    // `steps_budget` particle-steps (at least 4 steps); inner sweep caps of
    // about `sweeps_budget / N` (between 100 and STABILITY_STEP_CAP).
    let (max_steps, steps_budget, sweeps_budget, budget) = if size == Size::Quick {
        (256usize, 256_000usize, 2_500_000usize, 200_000_000usize)
    } else {
        (1024, 4_000_000, 100_000_000, 2_000_000_000)
    };
    for case in &mut out {
        if case.name != "long-horizon" {
            let mut steps = 4usize;
            while steps * 2 <= max_steps && steps * 2 * case.n <= steps_budget {
                steps *= 2;
            }
            case.step = case.t / steps as f64;
        }
        case.step_cap = (sweeps_budget / case.n.max(1)).clamp(100, STABILITY_STEP_CAP);
        // A work budget of pair updates for the one-time iterative
        // projection (full sweeps over N − 1 pairs).
        case.cap = (budget / case.n.max(1)).clamp(1000, 1_000_000);
    }
    Ok(out)
}
