//! One N of the study: the particle side (the trajectory of the quantile
//! sampling, its interpolations at the sample times, the uniform bounds of
//! §3.2–3.3 and the weak residuals) compared with the continuum profile at
//! each sample time ([`Sample`], with the rounding bounds of its `f64` form).

use std::time::Instant;

use num_rational::BigRational;

use super::distance::{lambda_l2_squared, u_l1, x_l2_squared};
use super::{Engine, Measure, Quantity, Row};
use crate::error::Error;
use crate::limit::continuum::Profile;
use crate::limit::eulerian::{particle_complementarity, particle_momentum_residuals, TestFunction};
use crate::limit::interpolation::{abs, max_of, PressureMeasure, Snapshot};
use crate::limit::surd::Surd;
use crate::quantile::MacroDatum;
use crate::scalar::Scalar;
use crate::trajectory::Trajectory;

/// A profile at one sample time, in every form the comparisons need.
pub(super) struct Sample {
    pub(super) exact: Option<Profile<BigRational>>,
    pub(super) float: Profile<f64>,
    /// Rounding bounds of the f64 profile for `X` (L²), `U` (L¹), `Λ` (L²).
    pub(super) bound_x: f64,
    pub(super) bound_u: f64,
    pub(super) bound_l: f64,
    pub(super) range: f64,
    pub(super) spread: f64,
    pub(super) spread_q: Option<BigRational>,
    pub(super) tv: f64,
    pub(super) tv_q: Option<BigRational>,
}

impl Sample {
    /// The rounding bounds: every coefficient of the f64 profile is within
    /// `β` of the exact one (`|w| ≤ 1`, so a segment's values are within
    /// `3β`); a breakpoint rounded by `e` moves the values on a set of
    /// measure `e`, by at most the jump there plus `2·slope·e`, which costs
    /// `√e·(jump + 2·slope·e)` in `L²` and `e·(jump + 2·slope·e)` in `L¹`.
    pub(super) fn new(p: &Profile<Surd>) -> Self {
        let exact = p.to_rational();
        let (float, _) = p.to_f64();
        let mut beta = 0.0f64;
        let mut slope = 0.0f64;
        let mut range = 0.0f64;
        for (s, f) in p.segments.iter().zip(&float.segments) {
            for c in s.x.iter().chain(&s.u).chain(&s.lambda) {
                beta = beta.max(c.to_f64_bounded().1);
            }
            slope = slope
                .max(f.x[1].abs())
                .max(f.u[1].abs())
                .max(f.lambda[1].abs() + 2.0 * f.lambda[2].abs());
            for w in [f.w0, f.w1] {
                let x = f.x[0] + f.x[1] * w;
                range = range.max(x.abs());
            }
        }
        let (mut bound_x, mut bound_u, mut bound_l) = (3.0 * beta, 3.0 * beta, 3.0 * beta);
        for k in 1..float.segments.len() {
            let e = p.segments[k].w0.to_f64_bounded().1;
            if e == 0.0 {
                continue;
            }
            let (a, b) = (&float.segments[k - 1], &float.segments[k]);
            let w = b.w0;
            let jx = (b.x[0] + b.x[1] * w - a.x[0] - a.x[1] * w).abs();
            let ju = (b.u[0] + b.u[1] * w - a.u[0] - a.u[1] * w).abs();
            let lam = |s: &crate::limit::continuum::Segment<f64>| {
                s.lambda[0] + s.lambda[1] * w + s.lambda[2] * w * w
            };
            let jl = (lam(b) - lam(a)).abs();
            // The exact jump is within 6β of the rounded one.
            let extra = 6.0 * beta + 2.0 * slope * e;
            bound_x += e.sqrt() * (jx + extra);
            bound_u += e * (ju + extra);
            bound_l += e.sqrt() * (jl + extra);
        }
        Sample {
            spread: float.spread(),
            tv: float.u_total_variation(),
            spread_q: exact.as_ref().map(|e| e.spread()),
            tv_q: exact.as_ref().map(|e| e.u_total_variation()),
            exact,
            float,
            bound_x,
            bound_u,
            bound_l,
            range,
        }
    }
    pub(super) fn conversion_bound(&self) -> f64 {
        self.bound_x.max(self.bound_u).max(self.bound_l)
    }
}

pub(super) fn short(q: &BigRational) -> Option<String> {
    let s = q.render();
    (s.len() <= 60).then_some(s)
}

/// A rational measure.
pub(super) fn exact_measure<S: Scalar>(v: &S) -> Measure {
    let q = if S::EXACT { v.to_big_rational() } else { None };
    Measure {
        value: v.to_f64_lossy(),
        bound: 0.0,
        exact: q.as_ref().and_then(short),
    }
}

/// A norm from its square.
pub(super) fn norm_measure<S: Scalar>(sq: &S, bound: f64) -> Measure {
    let q = if S::EXACT { sq.to_big_rational() } else { None };
    Measure {
        value: sq.to_f64_lossy().max(0.0).sqrt(),
        bound,
        exact: q.as_ref().and_then(short).map(|s| format!("sqrt({s})")),
    }
}

/// The study's context: datum, continuum samples, test functions.
pub(super) struct Context {
    pub(super) datum: MacroDatum,
    pub(super) times: Vec<BigRational>,
    pub(super) samples: Vec<Sample>,
    pub(super) t_end: BigRational,
    pub(super) delta: BigRational,
    pub(super) tests: Vec<TestFunction<BigRational>>,
    pub(super) lambda_end: BigRational,
    pub(super) lambda_end_f: (f64, f64),
}

/// The particle-side numbers of one row, in the engine's scalar.
pub(super) struct ParticleSide<S> {
    pub(super) snaps: Vec<Snapshot<S>>,
    pub(super) pressure_mass: S,
    pub(super) residuals: Vec<S>,
    pub(super) complementarity: Vec<S>,
    pub(super) rounding: f64,
    pub(super) collisions: usize,
}

pub(super) fn particle_side<S: Scalar>(
    traj: &Trajectory<S>,
    ctx: &Context,
) -> Result<ParticleSide<S>, Error> {
    let conv = |q: &BigRational| {
        S::from_big_rational(q).ok_or_else(|| Error::Unsupported {
            message: format!("{} does not fit the engine's scalar", q.render()),
        })
    };
    let delta = conv(&ctx.delta)?;
    let t_end = conv(&ctx.t_end)?;
    let mut snaps = Vec::with_capacity(ctx.times.len());
    for t in &ctx.times {
        let s = traj.at(&conv(t)?)?;
        snaps.push(Snapshot::new(&s, traj.data().velocities(), delta.clone())?);
    }
    let tests: Vec<TestFunction<S>> = ctx
        .tests
        .iter()
        .map(|f| {
            f.convert::<S>().ok_or_else(|| Error::Unsupported {
                message: "test function does not fit the engine's scalar".to_string(),
            })
        })
        .collect::<Result<_, _>>()?;
    let pressure_mass = PressureMeasure::new(traj).mass_until(&t_end);
    let residuals = particle_momentum_residuals(traj, &tests, &t_end)?;
    let complementarity = particle_complementarity(traj, &tests, &t_end, &delta);
    let rounding = residuals.rounding_bound.max(complementarity.rounding_bound);
    let (residuals, complementarity) = (residuals.values, complementarity.values);
    let collisions = traj
        .impulses()
        .iter()
        .filter(|i| i.t.total_cmp(&t_end).is_le())
        .count();
    Ok(ParticleSide {
        snaps,
        pressure_mass,
        residuals,
        complementarity,
        rounding,
        collisions,
    })
}

pub(super) fn snap_f64<S: Scalar>(s: &Snapshot<S>) -> Snapshot<f64> {
    let f = |v: &[S]| v.iter().map(|x| x.to_f64_lossy()).collect::<Vec<f64>>();
    Snapshot {
        t: s.t.to_f64_lossy(),
        n: s.n,
        delta: s.delta.to_f64_lossy(),
        x: f(&s.x),
        u: f(&s.u),
        u0: f(&s.u0),
        lambda: f(&s.lambda),
    }
}

/// The comparisons `(x_l2², u_l1, λ_l2²)` at one sample, exact when
/// possible.
pub(super) fn compare<S: Scalar>(
    snap: &Snapshot<S>,
    sample: &Sample,
) -> (Measure, Measure, Measure) {
    let n = snap.n;
    if S::EXACT {
        if let Some(p) = &sample.exact {
            let q = |v: &[S]| -> Option<Vec<BigRational>> {
                v.iter().map(|x| x.to_big_rational()).collect()
            };
            if let (Some(x), Some(u), Some(l)) =
                (q(&snap.x[1..]), q(&snap.u[1..]), q(&snap.lambda[1..]))
            {
                return (
                    norm_measure(&x_l2_squared(&x, p), 0.0),
                    exact_measure(&u_l1(&u, p)),
                    norm_measure(&lambda_l2_squared(&l, p), 0.0),
                );
            }
        }
    }
    let f = snap_f64(snap);
    let p = &sample.float;
    // Summation of n terms, and the rounding of the particle values (an
    // absolute ε·|x| on each) when they come from the exact engine.
    let round = (n as f64 + 20.0) * f64::EPSILON;
    let input = 2.0 * f64::EPSILON * sample.range.max(1.0);
    let x2 = x_l2_squared(&f.x[1..], p);
    let u1 = u_l1(&f.u[1..], p);
    let l2 = lambda_l2_squared(&f.lambda[1..], p);
    (
        Measure::float(
            x2.max(0.0).sqrt(),
            sample.bound_x + input + round * x2.max(0.0).sqrt(),
        ),
        Measure::float(u1, sample.bound_u + input + round * u1),
        Measure::float(
            l2.max(0.0).sqrt(),
            sample.bound_l + input + round * l2.max(0.0).sqrt(),
        ),
    )
}

pub(super) fn max_measure(a: Measure, b: Measure) -> Measure {
    if b.value > a.value {
        Measure {
            bound: a.bound.max(b.bound),
            ..b
        }
    } else {
        Measure {
            bound: a.bound.max(b.bound),
            ..a
        }
    }
}

pub(super) fn row_from<S: Scalar>(
    ps: &ParticleSide<S>,
    ctx: &Context,
    n: usize,
    engine: Engine,
    seconds: f64,
) -> Row {
    let zero = || Measure {
        value: 0.0,
        bound: 0.0,
        exact: Some("0".to_string()),
    };
    let (mut xl2, mut ul1, mut ll2) = (zero(), zero(), zero());
    let mut xl2_end = zero();
    let mut bv = S::zero();
    let (mut bv_err, mut tv_err) = (zero(), zero());
    let mut tv = S::zero();
    let mut ole = S::zero();
    let mut dens = S::zero();
    let mut nlambda = S::zero();
    let mut exact_cmp = S::EXACT;
    let delta_f = ctx.delta.to_f64_lossy();
    for (j, (snap, sample)) in ps.snaps.iter().zip(&ctx.samples).enumerate() {
        exact_cmp &= sample.exact.is_some();
        let (x, u, l) = compare(snap, sample);
        if j + 1 == ps.snaps.len() {
            xl2_end = x.clone();
        }
        xl2 = max_measure(xl2, x);
        bv = max_of(bv, snap.bv_x());
        dens = max_of(dens, snap.max_density());
        nlambda = snap.lambda.iter().fold(nlambda, |m, l| {
            max_of(m, abs(l.clone()) * &S::from_usize(n))
        });
        // eq:BV_XN against its limit X(t,1) − X(t,0⁺) + δ.
        let bv_e = match (&sample.spread_q, S::EXACT, snap.bv_x().to_big_rational()) {
            (Some(sq), true, Some(b)) => exact_measure(&abs(b - sq - &ctx.delta)),
            _ => Measure::float(
                (snap.bv_x().to_f64_lossy() - sample.spread - delta_f).abs(),
                sample.conversion_bound() + 4.0 * f64::EPSILON,
            ),
        };
        bv_err = max_measure(bv_err, bv_e);
        if j == 0 {
            continue;
        }
        ul1 = max_measure(ul1, u);
        ll2 = max_measure(ll2, l);
        tv = max_of(tv, snap.tv_u());
        ole = max_of(ole, snap.oleinik_margin());
        let tv_e = match (&sample.tv_q, S::EXACT, snap.tv_u().to_big_rational()) {
            (Some(tq), true, Some(b)) => exact_measure(&abs(b - tq)),
            _ => Measure::float(
                (snap.tv_u().to_f64_lossy() - sample.tv).abs(),
                sample.conversion_bound() + (n as f64 + 20.0) * f64::EPSILON * sample.tv,
            ),
        };
        tv_err = max_measure(tv_err, tv_e);
    }
    let pm = exact_measure(&ps.pressure_mass);
    let pm_err = if S::EXACT {
        match ps.pressure_mass.to_big_rational() {
            Some(p) if ctx.samples.last().is_some_and(|s| s.exact.is_some()) => {
                exact_measure(&abs(p - &ctx.lambda_end))
            }
            _ => Measure::float(
                (ps.pressure_mass.to_f64_lossy() - ctx.lambda_end_f.0).abs(),
                ctx.lambda_end_f.1,
            ),
        }
    } else {
        Measure::float(
            (ps.pressure_mass.to_f64_lossy() - ctx.lambda_end_f.0).abs(),
            ctx.lambda_end_f.1 + (ps.collisions as f64 + 20.0) * f64::EPSILON * pm.value,
        )
    };
    let resid = ps
        .residuals
        .iter()
        .fold(S::zero(), |m, r| max_of(m, abs(r.clone())));
    let compl = ps
        .complementarity
        .iter()
        .fold(S::zero(), |m, r| max_of(m, abs(r.clone())));
    let float_bound = |v: &S| {
        if S::EXACT {
            ps.rounding
        } else {
            (ps.collisions as f64 + 20.0) * 16.0 * f64::EPSILON * v.to_f64_lossy().abs()
        }
    };
    let values = vec![
        (Quantity::XL2, xl2),
        (Quantity::XL2End, xl2_end),
        (Quantity::UL1, ul1),
        (Quantity::LambdaL2, ll2),
        (Quantity::PressureMass, pm),
        (Quantity::PressureMassError, pm_err),
        (Quantity::BvX, exact_measure(&bv)),
        (Quantity::BvXError, bv_err),
        (Quantity::TvU, exact_measure(&tv)),
        (Quantity::TvUError, tv_err),
        (Quantity::ResidualMass, zero()),
        (
            Quantity::ResidualMomentum,
            Measure {
                bound: float_bound(&resid),
                ..exact_measure(&resid)
            },
        ),
        (
            Quantity::Complementarity,
            Measure {
                bound: float_bound(&compl),
                ..exact_measure(&compl)
            },
        ),
        (Quantity::Oleinik, exact_measure(&ole)),
        (
            Quantity::MaxDensity,
            Measure {
                // f64: a contact gap 1/N between positions of size ≲ bv_x
                // is computed with an error ≤ 2ε·bv_x, i.e. a relative
                // error ≤ 2ε·N·bv_x on the density.
                bound: if S::EXACT {
                    0.0
                } else {
                    4.0 * f64::EPSILON * n as f64 * bv.to_f64_lossy().abs().max(1.0)
                },
                ..exact_measure(&dens)
            },
        ),
        (Quantity::NLambda, exact_measure(&nlambda)),
    ];
    Row {
        n,
        engine,
        exact_comparisons: exact_cmp,
        seconds,
        collisions: ps.collisions,
        values,
    }
}

pub(super) fn run_n(ctx: &Context, n: usize, engine: Engine) -> Result<(Row, Vec<f64>), Error> {
    let start = Instant::now();
    let data = ctx.datum.sample(n)?;
    match engine {
        Engine::Exact => {
            let traj = Trajectory::new(data);
            let ps = particle_side(&traj, ctx)?;
            let res = ps.residuals.iter().map(|r| r.to_f64_lossy()).collect();
            Ok((
                row_from(&ps, ctx, n, engine, start.elapsed().as_secs_f64()),
                res,
            ))
        }
        Engine::Float => {
            let data = data.convert::<f64>().ok_or_else(|| Error::Unsupported {
                message: format!("the sample with N = {n} does not fit f64"),
            })??;
            let traj = Trajectory::new(data);
            let ps = particle_side(&traj, ctx)?;
            let res = ps.residuals.clone();
            Ok((
                row_from(&ps, ctx, n, engine, start.elapsed().as_secs_f64()),
                res,
            ))
        }
    }
}
