//! The proposition "Eulerian formulation" (§3.4, unlabelled: ledger ids
//! `prop:eulerian-formulation#…`): `(ρ, ρu, p)` defined by push-forward is a
//! distributional solution of the constrained Euler system `eq:macro-euler`
//! with `∂_x u < 1/t`.
//!
//! * **Mass, particles** ([`mass`], per case): the weak residual
//!   `R_mass^N(φ) = ∫∫ (∂_t φ + u ∂_x φ) ρ = (1/N) Σ_i ∫_0^T (∂_t φ + u_i ∂_x φ)(t, x_i(t)) dt`
//!   is exactly 0 for the test functions `φ = B(t) Q(x)` of
//!   [`crate::limit::eulerian::TestFunction`] (`B` the `C³` bump of a
//!   window `[t₀, t₁]`, `Q = ((x − c)/L)^m`). Computed, not assumed: on each
//!   time piece between consecutive collision instants (cut at `t₀`, `t₁`)
//!   the state at the piece's left end gives `x_i(τ) = x_i(a) + (τ − a) u_i(a)`,
//!   the integrand is a polynomial in `τ` (degree ≤ 7 + m), integrated
//!   exactly. It vanishes only if the positions the engine reports at each
//!   instant are those reached by moving with the velocities it reports
//!   (`x_i` Lipschitz with derivative `u_i`), the proof's "differentiating
//!   under the integral sign".
//! * **Momentum, particles**: `O(1/N)`, a scaling claim
//!   ([`super::scaling::eulerian_momentum`], `limit::eulerian`'s exact
//!   residual).
//! * **Oleinik, continuum** ([`oleinik`]): `t ∂_x u < 1` on the support
//!   (`∂_x u = ∂_w U/∂_w X` on each segment) and `t ∂_x u ≤ 1` across the
//!   vacuum gaps (`u` interpolated linearly through the gap, `[U]/[X]`), by
//!   [`crate::limit::eulerian::oleinik_margin`], on the rational profiles of
//!   the 18 macroscopic data.

use num_rational::BigRational;

use super::{Case, Violation};
use crate::limit::eulerian::{oleinik_margin, TestFunction};
use crate::limit::poly::{add_into, integral, mul};
use crate::scalar::Scalar;
use crate::state::State;

type R = Result<(), Violation>;

const MASS: &str = "prop:eulerian-formulation#mass";

/// `C(m, k)`.
fn binomial<S: Scalar>(m: usize, k: usize) -> S {
    (0..k).fold(S::one(), |c, j| {
        c * &S::from_usize(m - j) / &S::from_usize(j + 1)
    })
}

/// The power sums `M[j][k] = Σ_i y_i^j u_i^k` (`j + k ≤ d`, `y_i = x_i − c`)
/// of a state: every `Σ_i ((y_i + τ u_i)/L)^m` is a combination of them
/// (binomial expansion), so one pass over the particles serves every test
/// function of the same centre.
pub(crate) fn power_sums<S: Scalar>(s: &State<S>, center: &S, d: usize) -> Vec<Vec<S>> {
    let n = s.positions.len();
    // yp[j][i] = y_i^j, up[k][i] = u_i^k (j, k ≥ 1; the 0th powers are 1).
    let y: Vec<S> = s.positions.iter().map(|x| x.clone() - center).collect();
    let powers = |v: &[S]| -> Vec<Vec<S>> {
        (0..=d as u32)
            .map(|j| match j {
                0 => vec![S::one(); n],
                1 => v.to_vec(),
                _ => v.iter().map(|a| a.powi(j)).collect(),
            })
            .collect()
    };
    let (yp, up) = (powers(&y), powers(&s.velocities));
    let mut m = vec![vec![S::zero(); d + 1]; d + 1];
    for j in 0..=d {
        for k in 0..=(d - j) {
            m[j][k] = S::sum_of_products(&yp[j], &up[k]);
        }
    }
    m
}

/// `Σ_i Q(x_i(τ))` and `Σ_i u_i Q'(x_i(τ))` as polynomials in `τ`
/// (`Q = ((x − c)/L)^m`, `x_i(τ) = x_i + τ u_i`) from the power sums:
/// `Σ_k C(m,k) M[m−k][k] τ^k / L^m` and `Σ_k m C(m−1,k) M[m−1−k][k+1] τ^k / L^m`.
pub(crate) fn moment_polys<S: Scalar>(sums: &[Vec<S>], scale: &S, m: u32) -> (Vec<S>, Vec<S>) {
    let m = m as usize;
    let lm = (0..m).fold(S::one(), |p, _| p * scale);
    let s0 = (0..=m)
        .map(|k| binomial::<S>(m, k) * &sums[m - k][k] / &lm)
        .collect();
    let s1 = (0..m)
        .map(|k| S::from_usize(m) * &binomial::<S>(m - 1, k) * &sums[m - 1 - k][k + 1] / &lm)
        .collect();
    (s0, s1)
}

/// `(B, B')` on `[a, b] ⊂ [t₀, t₁]` as polynomials in `τ = t − a`.
pub(crate) fn bump<S: Scalar>(f: &TestFunction<S>, a: &S) -> (Vec<S>, Vec<S>) {
    let w = f.t1.clone() - &f.t0;
    let k = S::from_i64(4) / &(w.clone() * &w);
    let (p, q) = (a.clone() - &f.t0, f.t1.clone() - a);
    // b = k (p + τ)(q − τ), b' = k (q − p − 2τ).
    let b = vec![
        k.clone() * &p * &q,
        k.clone() * &(q.clone() - &p),
        -k.clone(),
    ];
    let db = vec![k.clone() * &(q - &p), -(k * &S::from_i64(2))];
    let b2 = mul(&b, &b);
    let b3 = mul(&b2, &b);
    let big_b = mul(&b3, &b);
    let d_big_b: Vec<S> = mul(&b3, &db)
        .into_iter()
        .map(|c| c * &S::from_i64(4))
        .collect();
    (big_b, d_big_b)
}

/// The power sums ([`power_sums`]) of the state at each time asked for,
/// computed once and shared by the test functions.
struct Sums<'a, S> {
    case: &'a Case<S>,
    center: S,
    degree: usize,
    by_time: Vec<(S, Vec<Vec<S>>)>,
}

impl<S: Scalar> Sums<'_, S> {
    fn at(&mut self, t: &S) -> Result<&[Vec<S>], Violation> {
        let i = match self.by_time.binary_search_by(|(s, _)| s.total_cmp(t)) {
            Ok(i) => i,
            Err(i) => {
                let s = self
                    .case
                    .state(t)
                    .map_err(|e| Violation::new(MASS, e.to_string()))?;
                let sums = power_sums(&s, &self.center, self.degree);
                self.by_time.insert(i, (t.clone(), sums));
                i
            }
        };
        Ok(&self.by_time[i].1)
    }
}

/// The integrand of the piece starting at `a`, a polynomial in
/// `τ = t − a`: `B'(τ) Σ_i Q(x_i(τ)) + B(τ) Σ_i u_i Q'(x_i(τ))` from the
/// power sums of the state at `a`.
pub(crate) fn piece_integrand<S: Scalar>(
    f: &TestFunction<S>,
    sums: &[Vec<S>],
    a: &S,
    m: u32,
) -> Vec<S> {
    // Σ_i Q(x_i(τ)) and Σ_i u_i Q'(x_i(τ)), from the state at a.
    let (s0, s1) = moment_polys(sums, &f.scale, m);
    let (big_b, d_big_b) = bump(f, a);
    let mut integrand = mul(&d_big_b, &s0);
    add_into(&mut integrand, &mul(&big_b, &s1));
    integrand
}

/// The cuts of `[t₀, t₁]` into the pieces of [`mass_residual`]: `t₀`, the
/// collision instants strictly inside, `t₁` (also read by the prover's
/// identity argument, `prove::telescope`).
pub(crate) fn mass_cuts<S: Scalar>(case: &Case<S>, f: &TestFunction<S>) -> Vec<S> {
    let mut cuts = vec![f.t0.clone()];
    for imp in case.traj.impulses() {
        if imp.t > f.t0 && imp.t < f.t1 && cuts.last() != Some(&imp.t) {
            cuts.push(imp.t.clone());
        }
    }
    cuts.push(f.t1.clone());
    cuts
}

/// `R_mass^N(φ)` over `[t₀, t₁]`, piece by piece (see the module
/// documentation).
fn mass_residual<S: Scalar>(
    case: &Case<S>,
    f: &TestFunction<S>,
    sums: &mut Sums<'_, S>,
) -> Result<S, Violation> {
    let cuts = mass_cuts(case, f);
    let m = f.degree;
    let mut total = S::zero();
    for w in cuts.windows(2) {
        let (a, b) = (&w[0], &w[1]);
        let integrand = piece_integrand(f, sums.at(a)?, a, m);
        total = total + &integral(&integrand, &(b.clone() - a));
    }
    Ok(total / &S::from_usize(case.n()))
}

/// The test functions of the mass check: windows `[0, T]` and
/// `[T/4, 3T/4]` (`T` the last probe time), degrees 2 and 3, centred at
/// `x⁰_1`, scale 1.
pub(crate) fn mass_tests<S: Scalar>(case: &Case<S>) -> Vec<TestFunction<S>> {
    let Some(t_end) = case.times.last().filter(|t| **t > S::zero()) else {
        return Vec::new();
    };
    let q = |k: i64| t_end.clone() * &S::from_i64(k) / &S::from_i64(4);
    let mut out = Vec::new();
    for (t0, t1) in [(S::zero(), t_end.clone()), (q(1), q(3))] {
        for degree in [2, 3] {
            out.push(TestFunction {
                t0: t0.clone(),
                t1: t1.clone(),
                center: case.data().positions()[0].clone(),
                scale: S::one(),
                degree,
            });
        }
    }
    out
}

/// `prop:eulerian-formulation#mass` for the particles: `R_mass^N(φ) = 0`
/// exactly (see the module documentation).
pub fn mass<S: Scalar>(case: &Case<S>) -> R {
    let tests = mass_tests(case);
    let Some(first) = tests.first() else {
        return Ok(());
    };
    let mut sums = Sums {
        case,
        center: first.center.clone(),
        degree: tests.iter().map(|f| f.degree as usize).max().unwrap_or(0),
        by_time: Vec::new(),
    };
    for f in tests {
        debug_assert!(f.center == sums.center);
        let r = mass_residual(case, &f, &mut sums)?;
        if !r.is_zero() {
            return Err(Violation::new(
                MASS,
                format!(
                    "N = {}: R_mass^N(φ) = {} ≠ 0 for φ = {}",
                    case.n(),
                    r.render(),
                    f.name()
                ),
            ));
        }
    }
    Ok(())
}

/// `prop:eulerian-formulation#oleinik` on the continuum: on every rational
/// profile at `t > 0`, `t ∂_x u < 1` on each segment (the support) and the
/// margin over the vacuum gaps too, `t [U]/[X] ≤ 1`
/// ([`oleinik_margin`]); `u` jumping upwards with no gap fails.
pub fn oleinik() -> R {
    const ID: &str = "prop:eulerian-formulation#oleinik";
    let mut checked = 0usize;
    for c in super::macro_data::cases(ID)? {
        for (t, p) in &c.profiles {
            let Some(p) = p else { continue };
            checked += 1;
            oleinik_on_profile(&c.name, t, p)?;
        }
    }
    if checked == 0 {
        return Err(Violation::new(ID, "vacuous: no rational continuum profile"));
    }
    Ok(())
}

/// [`oleinik`] on one profile at `t > 0` (`tests/claims_selfcheck.rs` runs
/// it on a corrupted profile).
pub fn oleinik_on_profile(
    name: &str,
    t: &BigRational,
    p: &crate::limit::continuum::Profile<BigRational>,
) -> R {
    type Q = BigRational;
    const ID: &str = "prop:eulerian-formulation#oleinik";
    let Some(margin) = oleinik_margin(p, t, &Q::zero()) else {
        return Err(Violation::new(
            ID,
            format!(
                "{name}, t = {}: u jumps upwards with no vacuum gap (∂_x u = +∞)",
                t.render()
            ),
        ));
    };
    if margin > Q::one() {
        return Err(Violation::new(
            ID,
            format!(
                "{name}, t = {}: t sup ∂_x u = {} > 1",
                t.render(),
                margin.render()
            ),
        ));
    }
    for s in &p.segments {
        if t.clone() * &s.u[1] >= s.x[1] {
            return Err(Violation::new(
                ID,
                format!(
                    "{name}, t = {}: on the image of [{}, {}], t ∂_x u = t ∂_w U/∂_w X = {} ≥ 1",
                    t.render(),
                    s.w0.render(),
                    s.w1.render(),
                    (t.clone() * &s.u[1] / &s.x[1]).render()
                ),
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::initial::InitialData;
    use crate::rational::ratio as q;

    type Q = BigRational;

    #[test]
    fn polynomial_integral_is_exact() {
        // ∫_0^2 (1 + 3τ²) dτ = 2 + 8 = 10.
        assert_eq!(integral(&[q(1, 1), q(0, 1), q(3, 1)], &q(2, 1)), q(10, 1));
        let (b, db) = bump(
            &TestFunction {
                t0: q(0, 1),
                t1: q(1, 1),
                center: q(0, 1),
                scale: q(1, 1),
                degree: 2,
            },
            &q(0, 1),
        );
        // B(1/2) = 1, B'(1/2) = 0.
        let at = |p: &[Q], x: Q| p.iter().rev().fold(Q::zero(), |a, c| a * &x + c);
        assert_eq!(at(&b, q(1, 2)), q(1, 1));
        assert_eq!(at(&db, q(1, 2)), q(0, 1));
    }

    #[test]
    fn the_particles_conserve_mass_and_a_lagging_state_does_not() {
        let data = InitialData::with_paper_radius(
            vec![q(0, 1), q(1, 1), q(3, 1)],
            vec![q(1, 1), q(-1, 1), q(-2, 1)],
        )
        .unwrap();
        let case = Case::new(data, None);
        mass(&case).unwrap();
        // Positions of t/2 reported at t, with the velocities of t.
        fn lag(d: &InitialData<Q>, s: &mut crate::state::State<Q>) {
            let h = s.t.clone() / Q::from_i64(2);
            s.positions = crate::projection::state_at(d, &h).unwrap().positions;
        }
        assert!(mass(&case.clone().tampered(lag)).is_err());
    }

    #[test]
    fn the_continuum_satisfies_the_eulerian_oleinik_inequality() {
        oleinik().unwrap();
    }
}
