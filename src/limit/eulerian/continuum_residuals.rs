//! The continuum side of the weak form: `R_mass`, `R_mom` of the exact
//! profile, by Gauss–Legendre in `w` (exact) and composite Gauss–Legendre in
//! `t` on panels cut where the plateau structure changes.

use num_bigint::BigInt;
use num_rational::BigRational;

use super::TestFunction;
use crate::error::Error;
use crate::limit::continuum::{Continuum, Profile};
use crate::scalar::Scalar;

/// Gauss–Legendre nodes and weights on `[−1, 1]`.
const GL5: [(f64, f64); 5] = [
    (0.0, 0.568_888_888_888_888_9),
    (-0.538_469_310_105_683_1, 0.478_628_670_499_366_47),
    (0.538_469_310_105_683_1, 0.478_628_670_499_366_47),
    (-0.906_179_845_938_664, 0.236_926_885_056_189_08),
    (0.906_179_845_938_664, 0.236_926_885_056_189_08),
];
const GL4: [(f64, f64); 4] = [
    (-0.339_981_043_584_856_26, 0.652_145_154_862_546_1),
    (0.339_981_043_584_856_26, 0.652_145_154_862_546_1),
    (-0.861_136_311_594_052_6, 0.347_854_845_137_453_85),
    (0.861_136_311_594_052_6, 0.347_854_845_137_453_85),
];

/// The continuum residuals of one test function at one time:
/// `(mass integrand, momentum integrand)` (the `w`-integrals, exact up to
/// rounding: 4 Gauss nodes per segment).
fn continuum_integrands(p: &Profile<f64>, f: &TestFunction<f64>, t: f64) -> (f64, f64) {
    let b = f.time_bump(&t);
    let db = f.time_bump_dt(&t);
    let (mut j1, mut j2, mut i1, mut i2, mut i3, mut i4) = (0.0, 0.0, 0.0, 0.0, 0.0, 0.0);
    for s in &p.segments {
        let half = (s.w1 - s.w0) / 2.0;
        let mid = (s.w1 + s.w0) / 2.0;
        for (node, weight) in GL4 {
            let w = mid + half * node;
            let wt = weight * half;
            let x = s.x[0] + s.x[1] * w;
            let u = s.u[0] + s.u[1] * w;
            let l = s.lambda[0] + s.lambda[1] * w + s.lambda[2] * w * w;
            let (q0, q1, q2) = (f.space(&x, 0), f.space(&x, 1), f.space(&x, 2));
            j1 += wt * q0;
            j2 += wt * q1 * u;
            i1 += wt * q0 * u;
            i2 += wt * q1 * u * u;
            i3 += wt * l * q1;
            i4 += wt * l * u * q2;
        }
    }
    (db * j1 + b * j2, db * i1 + b * i2 - db * i3 - b * i4)
}

/// A quadrature result with its error estimate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Quadrature {
    /// The computed value.
    pub value: f64,
    /// The error estimate (panel doubling plus the skipped bisection
    /// intervals).
    pub error: f64,
}

fn rational(t: f64) -> Result<BigRational, Error> {
    BigRational::from_float(t).ok_or_else(|| Error::Unsupported {
        message: format!("time {t} is not finite"),
    })
}

/// Integrates the continuum residuals of `tests` over their windows with
/// `panels` panels (see the module documentation); test functions with the
/// same window share the quadrature nodes (one exact profile per node).
/// Returns, per test function, `(mass residual, momentum residual)`.
pub fn continuum_residuals(
    continuum: &Continuum,
    tests: &[TestFunction<BigRational>],
    panels: usize,
) -> Result<Vec<(Quadrature, Quadrature)>, Error> {
    let mut out = vec![
        (
            Quadrature {
                value: 0.0,
                error: 0.0
            },
            Quadrature {
                value: 0.0,
                error: 0.0
            }
        );
        tests.len()
    ];
    let mut done = vec![false; tests.len()];
    for k in 0..tests.len() {
        if done[k] {
            continue;
        }
        let group: Vec<usize> = (k..tests.len())
            .filter(|&j| tests[j].t0 == tests[k].t0 && tests[j].t1 == tests[k].t1)
            .collect();
        let fs: Vec<TestFunction<f64>> = group
            .iter()
            .map(|&j| {
                tests[j].convert::<f64>().ok_or_else(|| Error::Unsupported {
                    message: "test function does not fit f64".to_string(),
                })
            })
            .collect::<Result<_, _>>()?;
        let (t0, t1) = (&tests[k].t0, &tests[k].t1);
        let coarse = integrate_window(continuum, t0, t1, &fs, panels)?;
        let fine = integrate_window(continuum, t0, t1, &fs, 2 * panels)?;
        for (g, &j) in group.iter().enumerate() {
            let (c, f) = (coarse.0[g], fine.0[g]);
            out[j] = (
                Quadrature {
                    value: f.0,
                    error: (f.0 - c.0).abs() + fine.1,
                },
                Quadrature {
                    value: f.1,
                    error: (f.1 - c.1).abs() + fine.1,
                },
            );
            done[j] = true;
        }
    }
    Ok(out)
}

/// Per test function `(mass, momentum)` on the window `[t0, t1]`, and the
/// bound for the skipped bisection intervals.
#[allow(clippy::type_complexity)]
fn integrate_window(
    continuum: &Continuum,
    t0: &BigRational,
    t1: &BigRational,
    fs: &[TestFunction<f64>],
    panels: usize,
) -> Result<(Vec<(f64, f64)>, f64), Error> {
    let width = t1 - t0;
    let tol = &width / BigRational::from_integer(BigInt::from(1u64 << 40));
    let sig = |t: &BigRational| continuum.profile(t).map(|p| p.signature());
    let mut pieces: Vec<(BigRational, BigRational)> = Vec::new();
    let mut skipped = BigRational::from_integer(0.into());
    let panels = panels.max(1);
    let mut sig_a = sig(t0)?;
    for k in 0..panels {
        let a = t0 + &width * BigRational::new(BigInt::from(k), BigInt::from(panels));
        let b = t0 + &width * BigRational::new(BigInt::from(k + 1), BigInt::from(panels));
        let mut start = a.clone();
        let sig_b = sig(&b)?;
        let mut s0 = sig_a;
        let mut guard = 0;
        // Cut the panel where the plateau structure changes (up to 8 times).
        while s0 != sig_b && guard < 8 {
            guard += 1;
            let (mut lo, mut hi) = (start.clone(), b.clone());
            while &hi - &lo > tol {
                let mid = (&lo + &hi) / BigRational::from_integer(2.into());
                if sig(&mid)? == s0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            pieces.push((start.clone(), lo.clone()));
            skipped += &hi - &lo;
            start = hi;
            s0 = sig(&start)?;
        }
        pieces.push((start, b));
        sig_a = sig_b;
    }
    let mut sums = vec![(0.0, 0.0); fs.len()];
    let mut sup = 0.0f64;
    for (a, b) in pieces {
        let (af, bf) = (a.to_f64_lossy(), b.to_f64_lossy());
        let half = (bf - af) / 2.0;
        let mid = (bf + af) / 2.0;
        if half <= 0.0 {
            continue;
        }
        for (node, weight) in GL5 {
            let t = mid + half * node;
            let (p, _) = continuum.profile(&rational(t)?)?.to_f64();
            for (f, acc) in fs.iter().zip(sums.iter_mut()) {
                let (m1, m2) = continuum_integrands(&p, f, t);
                sup = sup.max(m1.abs()).max(m2.abs());
                acc.0 += weight * half * m1;
                acc.1 += weight * half * m2;
            }
        }
    }
    Ok((sums, 2.0 * sup * skipped.to_f64_lossy()))
}
