//! Eulerian fields and the weak form of the constrained Euler system
//! `eq:macro-euler`, for the particles and for the continuum.
//!
//! The Eulerian variables are push-forwards of the Lagrangian ones (§3.4,
//! `df:rho` and the proposition "Eulerian formulation"):
//! `ρ = X(t)#L¹_(0,1)`, `ρu = X(t)#(U L¹)`, `p = (Id, X)#P`.
//!
//! * **Density.** For the continuum `ρ(t, X(t,w)) = 1/∂_w X(t,w)` (the
//!   canonical representative of `lem:density`), 0 in vacuum; for the
//!   particles `ρ̃_N = X̃_N(t)#L¹`, equal to `1/(N(x_i − x_{i−1}))` on
//!   `(x_{i−1}, x_i)` (artificial particle included). Both are ≤ 1 because
//!   `∂_w X ≥ 1` and `∂_w X̃_N ≥ 1`.
//! * **Weak residuals.** Against `φ(t,x) = B(t)·Q(x)` with `B` a `C³`
//!   polynomial bump supported in a window `[t₀, t₁] ⊂ [0, T]`
//!   (`B = (4(t−t₀)(t₁−t)/(t₁−t₀)²)⁴`) and `Q(x) = ((x − c)/L)^m`,
//!   `m = 2, 3, 4` (the supports of `ρ`, `p` stay in a fixed bounded set, so
//!   a polynomial in `x` is a test function there; `m ≤ 1` gives exactly
//!   zero residuals: conservation of mass and momentum):
//!
//!   ```text
//!   R_mass(φ) = ∫∫ (∂_t φ + u ∂_x φ) ρ,
//!   R_mom(φ)  = ∫∫ (∂_t φ + u ∂_x φ) ρu + ⟨p, ∂_x φ⟩.
//!   ```
//!
//!   *Particles* (`X_N`, `U_N`, `P_N`, as in the paper): `x_i` is
//!   Lipschitz with derivative `u_i`, so `R_mass = (1/N) Σ_i ∫ d/dt φ(t,x_i) = 0`
//!   identically, and integrating by parts in time between collisions (with
//!   `u_i` jumping by `−N([λ_i] − [λ_{i−1}])`) gives the exact identity
//!
//!   ```text
//!   R_mom^N(φ) = Σ_k B(t_k) Σ_i [λ_i]_k ( Q'(x_i)/N − (Q(x_{i+1}) − Q(x_i)) )
//!   ```
//!
//!   (collisions `t_k`, pairs `i` of the merged cluster, all in contact:
//!   `x_{i+1} = x_i + 2r`). Inside a part of the merged cluster the jumps are
//!   affine in `i` and the positions equally spaced, so each part's sum is a
//!   combination of the power sums `Σ j^r` (integers, exact): O(parts) per
//!   collision, exact on `BigRational`. With `2r = 1/N` the bracket is
//!   `−(2r)² Q''/2 + O(N⁻³)`: the residual is `O(1/N)`.
//!
//!   *Continuum*: by the change of variables of the paper's proof and
//!   `P = ∂_t Λ` integrated by parts in time,
//!   `R_mom(φ) = ∫∫ [(∂_tφ + U∂_xφ)(t,X) U − Λ (∂_t∂_xφ + U ∂²_xφ)(t,X)] dw dt`.
//!   The `w`-integral is exact (Gauss–Legendre with 4 nodes per segment,
//!   exact for the degree ≤ 5 polynomials that appear, in `f64` from the
//!   rounded profile); the `t`-integral is composite 5-node Gauss–Legendre
//!   on panels cut at the instants where the plateau structure changes
//!   (located by bisection to `2⁻⁴⁰·T`), with an error estimate from panel
//!   doubling. The exact value is 0; the computed one measures the solver
//!   and the quadrature.
//! * **Complementarity** `(1 − ρ)p = 0`: for the particles with the paper's
//!   representative (`ρ(t, X_N(w)) = 1/∂_w X̃_N(w)` on the cell of `w`, and
//!   `P_N = p_i` on cell `i`, `p = (Id, X_N)#P_N`):
//!   `⟨(1 − ρ_N)p_N, φ⟩ = Σ_k Σ_i ([λ_i]_k/N)(1 − 1/(N(x_i − x_{i−1}))) φ(t_k, x_i)`,
//!   non-zero only at the left end of each merged cluster (the pairing of
//!   `λ_i`, which lives on the pair `(i, i+1)`, with the slope of the pair
//!   `(i−1, i)` — the off-by-one of `lem:discPDE2`); for the continuum `Λ`
//!   vanishes off the plateaus where `ρ = 1` (checked exactly by
//!   [`complementarity_defect`]).
//! * **Oleinik** `∂_x u < 1/t`: [`oleinik_margin`] returns `t · sup ∂_x u`,
//!   with `∂_x u = ∂_w U/∂_w X` on each segment and `[U]/[X]` across a
//!   vacuum gap (the linear interpolation of `u` through the gap); it must
//!   be `< 1`.

mod continuum_residuals;
mod fields;
mod grids;
mod mass_interpolated;
mod particles;

pub use continuum_residuals::{continuum_residuals, Quadrature};
pub use fields::{
    complementarity_defect, continuum_density, continuum_momentum, continuum_pressure_potential,
    continuum_velocity, oleinik_margin, particle_density, particle_pressure_atoms,
};
pub use grids::{continuum_density_grid, particle_density_grid, DensityGrid};
pub use mass_interpolated::interpolated_mass_residuals;
pub use particles::{
    cluster_containing, particle_complementarity, particle_momentum_residuals, ClusterPositions,
    Residuals, MAX_TEST_DEGREE, RESIDUAL_BITS,
};

use num_rational::BigRational;

use super::continuum::Continuum;
use super::interpolation::{abs, max_of};
use crate::scalar::Scalar;

/// `φ(t, x) = B(t) Q(x)`: a `C³` bump in time on `[t0, t1]` times
/// `Q(x) = ((x − center)/scale)^degree`.
#[derive(Debug, Clone, PartialEq)]
pub struct TestFunction<S> {
    /// Start of the time window.
    pub t0: S,
    /// End of the time window.
    pub t1: S,
    /// Centre of the space polynomial.
    pub center: S,
    /// Scale of the space polynomial.
    pub scale: S,
    /// Degree `m` of the space polynomial (2 to 4).
    pub degree: u32,
}

impl<S: Scalar> TestFunction<S> {
    /// `b = 4(t−t₀)(t₁−t)/(t₁−t₀)²` and `b'`, or `None` outside the window.
    fn b_parts(&self, t: &S) -> Option<(S, S)> {
        if t.total_cmp(&self.t0).is_le() || t.total_cmp(&self.t1).is_ge() {
            return None;
        }
        let width = self.t1.clone() - &self.t0;
        let w2 = width.clone() * &width;
        let four = S::from_i64(4);
        let b = four.clone() * &(t.clone() - &self.t0) * &(self.t1.clone() - t) / &w2;
        let db = four * &(self.t1.clone() + &self.t0 - &(S::from_i64(2) * t)) / &w2;
        Some((b, db))
    }
    /// `B(t)`.
    pub fn time_bump(&self, t: &S) -> S {
        match self.b_parts(t) {
            Some((b, _)) => {
                let b2 = b.clone() * &b;
                b2.clone() * &b2
            }
            None => S::zero(),
        }
    }
    /// `B'(t)`.
    pub fn time_bump_dt(&self, t: &S) -> S {
        match self.b_parts(t) {
            Some((b, db)) => S::from_i64(4) * &(b.clone() * &b * &b) * &db,
            None => S::zero(),
        }
    }
    /// `Q^{(k)}(x) = m!/(m−k)! (x − c)^{m−k} / L^m` (0 for `k > m`).
    pub fn space(&self, x: &S, k: u32) -> S {
        if k > self.degree {
            return S::zero();
        }
        let mut coeff = S::one();
        for j in 0..k {
            coeff = coeff * &S::from_i64(i64::from(self.degree - j));
        }
        let y = x.clone() - &self.center;
        let mut p = S::one();
        for _ in 0..(self.degree - k) {
            p = p * &y;
        }
        let mut l = S::one();
        for _ in 0..self.degree {
            l = l * &self.scale;
        }
        coeff * &p / &l
    }
    /// `φ(t, x)`.
    pub fn value(&self, t: &S, x: &S) -> S {
        self.time_bump(t) * &self.space(x, 0)
    }
    /// A short name: `B[t0,t1]·((x−c)/L)^m`.
    pub fn name(&self) -> String {
        format!(
            "B[{},{}]·((x−{})/{})^{}",
            self.t0.render(),
            self.t1.render(),
            self.center.render(),
            self.scale.render(),
            self.degree
        )
    }
    /// The same test function over another scalar.
    pub fn convert<T: Scalar>(&self) -> Option<TestFunction<T>> {
        let c = |v: &S| v.to_big_rational().and_then(|q| T::from_big_rational(&q));
        Some(TestFunction {
            t0: c(&self.t0)?,
            t1: c(&self.t1)?,
            center: c(&self.center)?,
            scale: c(&self.scale)?,
            degree: self.degree,
        })
    }
}

/// The family used by the convergence study: windows `[0,T]`, `[0,T/2]`,
/// `[T/4,3T/4]`, `[T/2,T]` times degrees 2, 3, 4, with `center` and
/// `scale` covering the support of the motion.
pub fn test_family(
    t_end: &BigRational,
    center: &BigRational,
    scale: &BigRational,
) -> Vec<TestFunction<BigRational>> {
    let f = |n: i64, d: i64| t_end * BigRational::new(n.into(), d.into());
    let windows = [
        (f(0, 1), f(1, 1)),
        (f(0, 1), f(1, 2)),
        (f(1, 4), f(3, 4)),
        (f(1, 2), f(1, 1)),
    ];
    let mut out = Vec::new();
    for (t0, t1) in windows {
        for degree in 2..=4 {
            out.push(TestFunction {
                t0: t0.clone(),
                t1: t1.clone(),
                center: center.clone(),
                scale: scale.clone(),
                degree,
            });
        }
    }
    out
}

/// The centre and half-width of an interval containing every position of
/// the continuum and of the particles on `[0, T]`: the datum's support
/// widened by `T·max|u⁰|` and the artificial particle's offset.
pub fn support_window(continuum: &Continuum, t_end: &BigRational) -> (BigRational, BigRational) {
    let blocks = continuum.datum().blocks();
    let zero = BigRational::from_integer(0.into());
    let (lo, hi) = match (blocks.first(), blocks.last()) {
        (Some(f), Some(l)) => (f.from.clone(), l.to.clone()),
        _ => (zero.clone(), BigRational::from_integer(1.into())),
    };
    let umax = blocks.iter().fold(zero.clone(), |m, b| {
        let (a, c) = match &b.velocity {
            crate::quantile::BlockVelocity::Constant(c) => (c.clone(), c.clone()),
            crate::quantile::BlockVelocity::Affine(a, c) => (a.clone(), c.clone()),
        };
        max_of(max_of(m, abs(a)), abs(c))
    });
    let two = BigRational::from_integer(2.into());
    let center = (&lo + &hi) / &two;
    let half = (&hi - &lo) / &two + t_end * umax + BigRational::from_integer(1.into());
    (center, half)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn test_function_derivatives() {
        let q = |n: i64, d: i64| BigRational::new(n.into(), d.into());
        let f = TestFunction {
            t0: q(0, 1),
            t1: q(1, 1),
            center: q(1, 2),
            scale: q(2, 1),
            degree: 3,
        };
        assert_eq!(f.time_bump(&q(1, 2)), q(1, 1));
        assert_eq!(f.time_bump(&q(0, 1)), q(0, 1));
        assert_eq!(f.time_bump_dt(&q(1, 2)), q(0, 1));
        // Q = ((x − 1/2)/2)³: Q'(x) = 3(x − 1/2)²/8.
        assert_eq!(f.space(&q(3, 2), 1), q(3, 8));
        assert_eq!(f.space(&q(3, 2), 3), q(6, 8));
        assert_eq!(f.space(&q(3, 2), 4), q(0, 1));
    }
}
