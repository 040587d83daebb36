//! The continuum solution of the constrained system in Lagrangian
//! coordinates, exactly: `X(t) = P_K(X⁰ + tU⁰)` in `L²(0,1)` with
//! `K = {∂_w X ≥ 1}` (the macroscopic projection formula, `eq:Lagr-1` and
//! Appendix C.1: the first-order inclusion `∂_t X + ∂I_K(X) ∋ U⁰` has the
//! unique solution given by the projection, by the monotonicity argument of
//! `app:uniqueness`), `U(t) = P_{H_{X(t)}}(U⁰)` (`eq:velocity-projection`),
//! and the multiplier `Λ` with `∂_t X = U⁰ − ∂_w Λ`, `Λ(t,0) = Λ(t,1) = 0`
//! (`eq:Lagr-1`), whose time derivative is the pressure `P = ∂_t Λ`
//! (`prop:2ndorder-LagrPDE`).
//!
//! # The projection
//!
//! `K = w + C` with `C` the cone of non-decreasing functions, so
//! `X(t) = w + f*` where `f* = P_C f` is the `L²` isotonic regression of
//!
//! ```text
//! f(w) = X⁰(w) + t U⁰(w) − w,
//! ```
//!
//! the slope of the greatest convex minorant (GCM) of `F(w) = ∫_0^w f`.
//! For a `[macro]` datum `f` is piecewise affine in `w` (one piece per
//! block: `X⁰` has slope `1/ρ_b`, an affine velocity gives `U⁰` slope
//! `κ_b/ρ_b`), so `F` is piecewise quadratic.
//!
//! We compute the GCM by its Legendre dual: for a level `M`, let
//! `m(M) = min_{w∈[0,1]} (F(w) − M w)` and `τ(M)` its minimiser. `τ` is
//! non-decreasing, and `f*(w) = M` exactly on the intervals
//! `[τ(M⁻), τ(M⁺)]` where the minimiser jumps (the *plateaus*: pooled,
//! congested intervals `{∂_w X = 1}`); elsewhere `f* = f`. The candidate
//! minimisers are *features* of `F`: the knots `w = m_b` (where `m` is
//! linear in `M`) and the convex arcs (pieces with slope `s_b > 0`, where
//! `m(M) = F(a) − Ma − (M − f(a⁺))²/(2s_b)` for `M` between the arc's end
//! slopes). Between two consecutive *knot values* (the one-sided values of
//! `f` at the knots, all rational) every feature's `m` is a fixed polynomial
//! of degree ≤ 2; the active feature is found at the ends of each such
//! bracket, and the jump levels inside it are crossings `m_A(M) = m_B(M)` —
//! one quadratic equation with rational coefficients each — refined
//! recursively whenever a feature in between is strictly lower at the
//! crossing (it is then active in between, by monotonicity of `τ`).
//!
//! **Exactness.** Every plateau level `M` is rational (when the
//! discriminant is a rational square, always the case when `f` is piecewise
//! constant, i.e. density-1 blocks with constant velocities) or a quadratic
//! surd `a + b√d` ([`Surd`]); the plateau ends are affine in `M` with
//! rational coefficients, so each plateau lives in one field `Q(√d)` and
//! everything about it (ends, level, mean velocity, `Λ`) is exact. All
//! comparisons are exact. [`Profile::to_rational`] returns the profile over
//! `BigRational` when no surd appears; [`Profile::to_f64`] rounds each
//! number to the nearest double with a rigorous bound (see [`Surd`]).
//!
//! **Velocity.** On a plateau `U(t)` is the mean of `U⁰` over it
//! (`eq:velocity-projection`: `H_{X(t)}` holds the functions constant on each
//! connected component of `{∂_w X(t) = 1}`, and the orthogonal projection
//! onto it averages); elsewhere `U = U⁰`. For `t > 0` the plateaus at `t`
//! are those just after `t` (clusters never split), so `U(t)` is the right
//! derivative of `X`, as for the particles. At `t = 0` the profile reports
//! `U = U⁰` and `Λ = 0` (the right derivative; it equals `P_{H_{X⁰}}(U⁰)`
//! exactly when `hyp:u0` holds).
//!
//! **Multiplier.** `∂_w Λ = U⁰ − U(t)` with `Λ(t,0) = 0` gives `Λ = 0` off
//! the plateaus and `Λ(t,w) = ∫_{w₀}^{w} (U⁰ − Ū)` on a plateau `[w₀, w₁]`
//! with mean `Ū` (it returns to 0 at `w₁`: checked exactly).

mod gcm;
mod profile;
mod regions;

use std::cmp::Ordering;

use num_rational::BigRational;
use num_traits::Signed;

use super::surd::Surd;
use crate::error::Error;
use crate::quantile::{BlockVelocity, MacroDatum};
use crate::scalar::Scalar;

pub use profile::{Attach, Plateau, Profile, Segment};

type Q = BigRational;

fn q(n: i64) -> Q {
    BigRational::from_integer(n.into())
}

fn internal(what: &str) -> Error {
    Error::Unsupported {
        message: format!("internal error in the continuum solver (please report): {what}"),
    }
}

/// One block of the datum in mass coordinates: `w ∈ [a, b]`,
/// `X⁰(w) = x0[0] + x0[1]·w`, `U⁰(w) = u0[0] + u0[1]·w`.
#[derive(Debug, Clone, PartialEq)]
struct Piece {
    a: Q,
    b: Q,
    x0: [Q; 2],
    u0: [Q; 2],
}

/// `P((t₀, t₁] × (0, 1))`, see [`Continuum::pressure_mass`].
#[derive(Debug, Clone, PartialEq)]
pub struct PressureMass {
    /// The value (nearest double).
    pub value: f64,
    /// A bound on `|value − exact|`.
    pub bound: f64,
    /// The exact value, when rational.
    pub exact: Option<BigRational>,
}

/// `∫_{w0}^{w1} Λ` on one segment, exactly (one field per segment).
fn segment_lambda_integral(s: &Segment<Surd>) -> Option<Surd> {
    let (a, b) = (&s.w0, &s.w1);
    let d1 = b.checked_sub(a)?;
    let d2 = b.square().checked_sub(&a.square())?;
    let d3 = b
        .square()
        .checked_mul(b)?
        .checked_sub(&a.square().checked_mul(a)?)?;
    s.lambda[0]
        .checked_mul(&d1)?
        .checked_add(
            &s.lambda[1]
                .checked_mul(&d2)?
                .mul_rational(&BigRational::new(1.into(), 2.into())),
        )?
        .checked_add(
            &s.lambda[2]
                .checked_mul(&d3)?
                .mul_rational(&BigRational::new(1.into(), 3.into())),
        )
}

/// The exact continuum solution of a `[macro]` datum.
#[derive(Debug, Clone)]
pub struct Continuum {
    datum: MacroDatum,
    pieces: Vec<Piece>,
}

impl Continuum {
    /// Prepares the solution of `datum` (`X⁰`, `U⁰` as affine pieces in `w`).
    pub fn new(datum: &MacroDatum) -> Self {
        let breaks = datum.mass_breakpoints();
        let mut pieces = Vec::with_capacity(datum.blocks().len());
        for (k, block) in datum.blocks().iter().enumerate() {
            let (Some(a), Some(b)) = (breaks.get(k), breaks.get(k + 1)) else {
                break;
            };
            let inv = block.density.recip();
            // X⁰(w) = from + (w − a)/ρ.
            let x0 = [&block.from - a * &inv, inv.clone()];
            let u0 = match &block.velocity {
                BlockVelocity::Constant(c) => [c.clone(), Q::zero()],
                BlockVelocity::Affine(va, vb) => {
                    // U⁰(w) = va + κ (X⁰(w) − from), κ = (vb − va)/(to − from).
                    let kappa = (vb - va) / (&block.to - &block.from);
                    let slope = &kappa * &inv;
                    [va - &slope * a, slope]
                }
            };
            pieces.push(Piece {
                a: a.clone(),
                b: b.clone(),
                x0,
                u0,
            });
        }
        Continuum {
            datum: datum.clone(),
            pieces,
        }
    }

    /// The datum.
    pub fn datum(&self) -> &MacroDatum {
        &self.datum
    }

    /// `f(w) = X⁰ + tU⁰ − w` on block `k`: `(f_c, f_s)` with `f = f_c + f_s w`.
    fn f_coeffs(&self, k: usize, t: &Q) -> (Q, Q) {
        let p = &self.pieces[k];
        (&p.x0[0] + t * &p.u0[0], &p.x0[1] + t * &p.u0[1] - q(1))
    }

    /// The profile `X(t)`, `U(t)`, `Λ(t)` at a time `t ≥ 0`, exact (see the
    /// module documentation).
    pub fn profile(&self, t: &BigRational) -> Result<Profile<Surd>, Error> {
        if t.is_negative() {
            return Err(Error::NegativeTime { t: t.render() });
        }
        let events = self.events(t)?;
        let mut segments = Vec::new();
        let mut plateaus = Vec::new();
        let mut cursor = Surd::from_rational(Q::zero());
        for ev in events
            .iter()
            .filter(|e| e.right.cmp_exact(&e.left) == Ordering::Greater)
        {
            if ev.left.cmp_exact(&cursor) == Ordering::Less {
                return Err(internal("plateaus out of order"));
            }
            self.free_region(&cursor, &ev.left, t, &mut segments)?;
            self.plateau_region(ev, t, &mut segments, &mut plateaus)?;
            cursor = ev.right.clone();
        }
        self.free_region(&cursor, &Surd::from_rational(q(1)), t, &mut segments)?;
        Ok(Profile {
            t: t.clone(),
            segments,
            plateaus,
        })
    }

    /// The pressure measure of a time slab, `P((t₀, t₁] × (0, 1)) =
    /// ∫_0^1 Λ(t₁) − ∫_0^1 Λ(t₀)` (`P = ∂_t Λ`): exact when both profiles are
    /// rational, otherwise in `f64` with a rigorous bound (each plateau's
    /// integral is a surd, rounded as in [`Surd::to_f64_bounded`]).
    pub fn pressure_mass(&self, t0: &BigRational, t1: &BigRational) -> Result<PressureMass, Error> {
        let (a, b) = (self.profile(t0)?, self.profile(t1)?);
        if let (Some(ea), Some(eb)) = (a.to_rational(), b.to_rational()) {
            let exact = eb.lambda_integral() - ea.lambda_integral();
            return Ok(PressureMass {
                value: exact.to_f64_lossy(),
                bound: 0.0,
                exact: Some(exact),
            });
        }
        let mut value = 0.0;
        let mut bound = 0.0;
        for (p, sign) in [(&b, 1.0), (&a, -1.0)] {
            for s in &p.segments {
                let v =
                    segment_lambda_integral(s).ok_or_else(|| internal("surd fields mismatch"))?;
                let (f, e) = v.to_f64_bounded();
                value += sign * f;
                bound += e + f.abs() * f64::EPSILON;
            }
        }
        Ok(PressureMass {
            value,
            bound: bound * (1.0 + 1e-10) + 4.0 * f64::EPSILON * value.abs(),
            exact: None,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::quantile::Block;

    fn r(n: i64, d: i64) -> Q {
        BigRational::new(n.into(), d.into())
    }

    fn block(from: Q, to: Q, density: Q, v: BlockVelocity) -> Block {
        Block {
            from,
            to,
            density,
            velocity: v,
        }
    }

    #[test]
    fn riemann_compression_plateau() {
        let d = MacroDatum::new(vec![
            block(r(0, 1), r(1, 1), r(1, 2), BlockVelocity::Constant(r(1, 1))),
            block(r(1, 1), r(2, 1), r(1, 2), BlockVelocity::Constant(r(-1, 1))),
        ])
        .unwrap();
        let c = Continuum::new(&d);
        let p = c.profile(&r(1, 8)).unwrap().to_rational().unwrap();
        assert_eq!(p.plateaus.len(), 1);
        assert_eq!(p.plateaus[0].w0, r(3, 8));
        assert_eq!(p.plateaus[0].w1, r(5, 8));
        assert_eq!(p.plateaus[0].level, r(1, 2));
        assert_eq!(p.plateaus[0].velocity, r(0, 1));
        // Λ = t − |w − 1/2| on the plateau.
        assert_eq!(p.lambda_at(&r(1, 2)), Some(r(1, 8)));
        assert_eq!(p.lambda_at(&r(7, 16)), Some(r(1, 16)));
        assert_eq!(p.lambda_integral(), r(1, 64));
        // Free parts: X = 2w + t.
        assert_eq!(p.x_at(&r(1, 4)), Some(r(5, 8)));
        let late = c.profile(&r(3, 1)).unwrap().to_rational().unwrap();
        assert_eq!(late.plateaus.len(), 1);
        assert_eq!(late.plateaus[0].w0, r(0, 1));
        assert_eq!(late.plateaus[0].w1, r(1, 1));
        assert_eq!(late.lambda_integral(), r(1, 4));
        let pm = c.pressure_mass(&r(1, 8), &r(1, 4)).unwrap();
        assert_eq!(pm.exact, Some(r(1, 16) - r(1, 64)));
    }

    #[test]
    fn expansion_meets_congested_block_irrationally() {
        let d = MacroDatum::new(vec![
            block(
                r(0, 1),
                r(1, 1),
                r(1, 2),
                BlockVelocity::Affine(r(-1, 1), r(1, 1)),
            ),
            block(r(3, 2), r(2, 1), r(1, 1), BlockVelocity::Constant(r(-1, 2))),
        ])
        .unwrap();
        let c = Continuum::new(&d);
        // Before t = 1/3 the congested block is alone on its plateau.
        let p = c.profile(&r(1, 4)).unwrap();
        assert_eq!(p.plateaus.len(), 1);
        assert_eq!(p.plateaus[0].w0.as_rational(), Some(&r(1, 2)));
        // At t = 1 the pooled level solves d² + 5d − 5 = 0 (d = 3/2 − M).
        let p = c.profile(&r(1, 1)).unwrap();
        assert!(!p.is_rational());
        let m = &p.plateaus[0].level;
        let d_ = m.neg().add_rational(&r(3, 2));
        let eq = d_.eval_quadratic(&[r(-5, 1), r(5, 1), r(1, 1)]);
        assert_eq!(eq.signum(), Ordering::Equal, "{m}");
        let (pf, bound) = p.to_f64();
        assert!(bound < 1e-15);
        assert!(pf.lambda_integral() > 0.0);
        assert!(pf.max_density() <= 1.0);
        let pm = c.pressure_mass(&r(0, 1), &r(1, 1)).unwrap();
        assert!(pm.exact.is_none());
        assert!((pm.value - pf.lambda_integral()).abs() <= pm.bound + 1e-15);
        assert!(pm.bound < 1e-14);
    }
}
