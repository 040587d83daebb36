//! The interpolations of the particle variables on the mass interval
//! `(0, 1)`, exactly as defined in §3.1 (`ssec:interpol1`):
//!
//! * piecewise constant on `((i−1)/N, i/N]`: `X_N = x_i` (`df:XN`),
//!   `U_N = u_i` (`df:UN`), `Λ_N = λ_i` (`df:LN`), and `P_N = ∂_t Λ_N`
//!   (`df:PN`), a measure in time: Dirac masses at the collision times with
//!   weights the jumps of `λ_i` (`prop:micro-pressure`);
//! * continuous piecewise affine on `[(i−1)/N, i/N]`:
//!   `X̃_N = N(x_i − x_{i−1})(w − (i−1)/N) + x_{i−1}` and likewise `Ũ_N`,
//!   `Λ̃_N`, `P̃_N`, with the artificial particle
//!   `x_0 = x_1 − 1/N − δ` (`df:x0`, `δ > 0` independent of N).
//!
//! The artificial particle moves with particle 1 (`x_0(t)` is defined from
//! `x_1(t)` at every time), so `u_0 = u_1` and `u⁰_0 = u⁰_1`; `λ_0 = 0` and
//! `p_0 = 0` (the boundary condition `λ_0 = 0` the paper says the device
//! preserves); `λ_N = 0`, `p_N = 0` (`eq:dyn-micro`).
//!
//! Everything is generic over [`Scalar`]: exact on `BigRational`, rounded on
//! `f64`. A [`Snapshot`] holds the augmented arrays at one time and
//! evaluates the interpolations as functions of `w`; [`Interpolations`]
//! evaluates them as functions of `(t, w)`; [`PressureMeasure`] is `P_N` /
//! `P̃_N` as a measure in time.

use num_rational::BigRational;
use num_traits::ToPrimitive;

use crate::contact::multipliers;
use crate::error::Error;
use crate::scalar::Scalar;
use crate::state::State;
use crate::trajectory::Trajectory;

pub(crate) fn abs<S: Scalar>(x: S) -> S {
    if x.total_cmp(&S::zero()).is_lt() {
        -x
    } else {
        x
    }
}

pub(crate) fn max_of<S: Scalar>(a: S, b: S) -> S {
    if b.total_cmp(&a).is_gt() {
        b
    } else {
        a
    }
}

/// The cell `i ∈ 1..=N` with `w ∈ ((i−1)/N, i/N]` (`w ≤ 1/N` gives 1,
/// `w > 1` gives N); `None` for NaN or an infinite `w`.
pub fn cell<S: Scalar>(w: &S, n: usize) -> Option<usize> {
    let q = w.to_big_rational()? * BigRational::from_integer(n.into());
    let i = q.ceil().to_integer().to_i64()?;
    Some(i.clamp(1, n.max(1) as i64) as usize)
}

/// The augmented particle arrays at one time `t`, index 0 being the
/// artificial particle of `df:x0`, and the interpolations of §3.1 as
/// functions of `w`.
#[derive(Debug, Clone, PartialEq)]
pub struct Snapshot<S> {
    /// The time.
    pub t: S,
    /// N.
    pub n: usize,
    /// `δ` of `df:x0`.
    pub delta: S,
    /// `x_0 … x_N`, `x_0 = x_1 − 1/N − δ`.
    pub x: Vec<S>,
    /// `u_0 … u_N` (right derivatives), `u_0 = u_1`.
    pub u: Vec<S>,
    /// `u⁰_0 … u⁰_N`, `u⁰_0 = u⁰_1`.
    pub u0: Vec<S>,
    /// `λ_0 … λ_N` (`eq:dyn-micro`), `λ_0 = 0`; `λ_N` as computed (it is 0).
    pub lambda: Vec<S>,
}

impl<S: Scalar> Snapshot<S> {
    /// The snapshot of `state` (for initial velocities `u0`) with the
    /// artificial particle at distance `1/N + δ` to the left of particle 1.
    pub fn new(state: &State<S>, u0: &[S], delta: S) -> Result<Self, Error> {
        let n = state.positions.len();
        if n == 0 {
            return Err(Error::NoParticles);
        }
        if delta.total_cmp(&S::zero()).is_le() {
            return Err(Error::Unsupported {
                message: format!("δ of df:x0 must be positive, got {}", delta.render()),
            });
        }
        if u0.len() != n || state.velocities.len() != n {
            return Err(Error::LengthMismatch {
                positions: n,
                velocities: u0.len(),
            });
        }
        let nn = S::from_usize(n);
        let mut x = Vec::with_capacity(n + 1);
        x.push(state.positions[0].clone() - &(S::one() / &nn) - &delta);
        x.extend(state.positions.iter().cloned());
        let mut u = Vec::with_capacity(n + 1);
        u.push(state.velocities[0].clone());
        u.extend(state.velocities.iter().cloned());
        let mut u0a = Vec::with_capacity(n + 1);
        u0a.push(u0[0].clone());
        u0a.extend(u0.iter().cloned());
        let (l, ln) = multipliers(u0, &state.velocities);
        let mut lambda = Vec::with_capacity(n + 1);
        lambda.push(S::zero());
        lambda.extend(l);
        lambda.push(ln);
        Ok(Snapshot {
            t: state.t.clone(),
            n,
            delta,
            x,
            u,
            u0: u0a,
            lambda,
        })
    }

    fn nn(&self) -> S {
        S::from_usize(self.n)
    }

    fn cell_of(&self, w: &S) -> Result<usize, Error> {
        if w.total_cmp(&S::zero()).is_lt() || w.total_cmp(&S::one()).is_gt() {
            return Err(Error::Unsupported {
                message: format!("w = {} is outside [0, 1]", w.render()),
            });
        }
        cell(w, self.n).ok_or_else(|| Error::Unsupported {
            message: format!("w = {} is not a number", w.render()),
        })
    }

    /// `(w − (i−1)/N)·N ∈ [0, 1]` on cell `i`.
    fn frac(&self, w: &S, i: usize) -> S {
        w.clone() * &self.nn() - &S::from_usize(i - 1)
    }

    fn affine(&self, v: &[S], w: &S) -> Result<S, Error> {
        let i = self.cell_of(w)?;
        Ok((v[i].clone() - &v[i - 1]) * &self.frac(w, i) + &v[i - 1])
    }

    /// `X_N(t, w) = x_i` on `((i−1)/N, i/N]` (`df:XN`).
    pub fn x_n(&self, w: &S) -> Result<S, Error> {
        Ok(self.x[self.cell_of(w)?].clone())
    }
    /// `U_N(t, w) = u_i` (`df:UN`).
    pub fn u_n(&self, w: &S) -> Result<S, Error> {
        Ok(self.u[self.cell_of(w)?].clone())
    }
    /// `U⁰_N(w) = u⁰_i`.
    pub fn u0_n(&self, w: &S) -> Result<S, Error> {
        Ok(self.u0[self.cell_of(w)?].clone())
    }
    /// `Λ_N(t, w) = λ_i` (`df:LN`).
    pub fn lambda_n(&self, w: &S) -> Result<S, Error> {
        Ok(self.lambda[self.cell_of(w)?].clone())
    }
    /// `X̃_N(t, w) = N(x_i − x_{i−1})(w − (i−1)/N) + x_{i−1}`.
    pub fn x_tilde(&self, w: &S) -> Result<S, Error> {
        self.affine(&self.x, w)
    }
    /// `Ũ_N(t, w)`, the same interpolation of the velocities.
    pub fn u_tilde(&self, w: &S) -> Result<S, Error> {
        self.affine(&self.u, w)
    }
    /// `Λ̃_N(t, w)`, the same interpolation of the multipliers.
    pub fn lambda_tilde(&self, w: &S) -> Result<S, Error> {
        self.affine(&self.lambda, w)
    }
    /// `∂_w X̃_N = N(x_i − x_{i−1})` on cell `i ∈ 1..=N` (`≥ 2rN = 1`; an
    /// index outside `1..=N` is a programming error and panics).
    pub fn dw_x_tilde(&self, i: usize) -> S {
        (self.x[i].clone() - &self.x[i - 1]) * &self.nn()
    }
    /// `∂_w Ũ_N = N(u_i − u_{i−1})` on cell `i ∈ 1..=N` (an index outside
    /// that range is a programming error and panics).
    pub fn dw_u_tilde(&self, i: usize) -> S {
        (self.u[i].clone() - &self.u[i - 1]) * &self.nn()
    }
    /// `∂_w Λ̃_N = N(λ_i − λ_{i−1})` on cell `i ∈ 1..=N` (as above).
    pub fn dw_lambda_tilde(&self, i: usize) -> S {
        (self.lambda[i].clone() - &self.lambda[i - 1]) * &self.nn()
    }
    /// `∫_0^1 |X̃_N − X_N| dw`, summed cell by cell (each cell contributes
    /// a triangle of base `1/N` and height `x_i − x_{i−1}`).
    pub fn l1_x_tilde_minus_x_n(&self) -> S {
        let two_n = self.nn() * &S::from_i64(2);
        (1..=self.n).fold(S::zero(), |acc, i| {
            acc + &(abs(self.x[i].clone() - &self.x[i - 1]) / &two_n)
        })
    }
    /// `∫_0^1 |Ũ_N − U_N| dw = (1/2N) Σ |u_i − u_{i−1}|`.
    pub fn l1_u_tilde_minus_u_n(&self) -> S {
        self.tv_u() / &(self.nn() * &S::from_i64(2))
    }
    /// `∫_0^1 |∂_w X̃_N| dw = x_N − x_0` (`eq:BV_XN`).
    pub fn bv_x(&self) -> S {
        self.x[self.n].clone() - &self.x[0]
    }
    /// `‖∂_w Ũ_N(t)‖_{L¹} = Σ_{i=1}^N |u_i − u_{i−1}|` (`pwUN-L1`).
    pub fn tv_u(&self) -> S {
        (1..=self.n).fold(S::zero(), |acc, i| {
            acc + &abs(self.u[i].clone() - &self.u[i - 1])
        })
    }
    /// `max_i t (u_i − u_{i−1})/(x_i − x_{i−1})` over `i = 1 … N`: the
    /// discrete Oleinik inequality `eq:Oleinik-tUN` (`prop:Oleinik`) says it
    /// is `< 1` for `t > 0`.
    pub fn oleinik_margin(&self) -> S {
        (1..=self.n).fold(S::zero(), |m, i| {
            let gap = self.x[i].clone() - &self.x[i - 1];
            if gap.is_zero() {
                return m;
            }
            max_of(
                m,
                self.t.clone() * &(self.u[i].clone() - &self.u[i - 1]) / &gap,
            )
        })
    }
    /// `max ρ̃_N = max_i 1/(N(x_i − x_{i−1}))`, the largest density of
    /// `X̃_N # L¹` (at most 1 since `∂_w X̃_N ≥ 1`).
    pub fn max_density(&self) -> S {
        (1..=self.n).fold(S::zero(), |m, i| {
            let slope = self.dw_x_tilde(i);
            if slope.is_zero() {
                return m;
            }
            max_of(m, S::one() / &slope)
        })
    }
    /// `(1/N) Σ_{i=1}^{N} λ_i = ∫_0^1 Λ_N(t, w) dw`.
    pub fn lambda_integral(&self) -> S {
        let sum = (1..=self.n).fold(S::zero(), |acc, i| acc + &self.lambda[i]);
        sum / &self.nn()
    }
}

/// The interpolations of §3.1 as functions of `(t, w)` for one trajectory
/// (each evaluation builds the [`Snapshot`] at `t`, O(N)).
#[derive(Debug, Clone, Copy)]
pub struct Interpolations<'a, S> {
    traj: &'a Trajectory<S>,
    delta: &'a S,
}

impl<'a, S: Scalar> Interpolations<'a, S> {
    /// The interpolations of `traj` with the artificial particle at
    /// distance `1/N + δ`.
    pub fn new(traj: &'a Trajectory<S>, delta: &'a S) -> Self {
        Interpolations { traj, delta }
    }
    /// The snapshot at `t ≥ 0`.
    pub fn at(&self, t: &S) -> Result<Snapshot<S>, Error> {
        let s = self.traj.at(t)?;
        Snapshot::new(&s, self.traj.data().velocities(), self.delta.clone())
    }
    /// `X_N(t, w)`.
    pub fn x_n(&self, t: &S, w: &S) -> Result<S, Error> {
        self.at(t)?.x_n(w)
    }
    /// `U_N(t, w)`.
    pub fn u_n(&self, t: &S, w: &S) -> Result<S, Error> {
        self.at(t)?.u_n(w)
    }
    /// `Λ_N(t, w)`.
    pub fn lambda_n(&self, t: &S, w: &S) -> Result<S, Error> {
        self.at(t)?.lambda_n(w)
    }
    /// `X̃_N(t, w)`.
    pub fn x_tilde(&self, t: &S, w: &S) -> Result<S, Error> {
        self.at(t)?.x_tilde(w)
    }
    /// `Ũ_N(t, w)`.
    pub fn u_tilde(&self, t: &S, w: &S) -> Result<S, Error> {
        self.at(t)?.u_tilde(w)
    }
    /// `Λ̃_N(t, w)`.
    pub fn lambda_tilde(&self, t: &S, w: &S) -> Result<S, Error> {
        self.at(t)?.lambda_tilde(w)
    }
    /// `P_N = ∂_t Λ_N` and `P̃_N` as measures in time.
    pub fn pressure(&self) -> PressureMeasure<'a, S> {
        PressureMeasure { traj: self.traj }
    }
}

/// `P_N = ∂_t Λ_N` (`df:PN`) and `P̃_N`: Dirac masses in time at the
/// collision times `t_k`, with weights `p_i^k = λ_i(t_k) − λ_i(t_k⁻)` (the
/// jumps of the multipliers; every other `λ_j` is continuous at `t_k`).
#[derive(Debug, Clone, Copy)]
pub struct PressureMeasure<'a, S> {
    traj: &'a Trajectory<S>,
}

impl<'a, S: Scalar> PressureMeasure<'a, S> {
    /// The measure of `traj`.
    pub fn new(traj: &'a Trajectory<S>) -> Self {
        PressureMeasure { traj }
    }
    /// The number of atoms (collisions).
    pub fn atoms(&self) -> usize {
        self.traj.impulses().len()
    }
    /// The time of atom `k`.
    pub fn time(&self, k: usize) -> Option<&S> {
        self.traj.impulses().get(k).map(|i| &i.t)
    }
    /// The weights `p_0 … p_N` of atom `k` (`p_0 = p_N = 0`; `p_i` is the
    /// jump of `λ_i`, the force between particles `i` and `i + 1`).
    pub fn weights(&self, k: usize) -> Option<Vec<S>> {
        let imp = self.traj.impulses().get(k)?;
        let n = self.traj.data().n();
        let mut p = vec![S::zero(); n + 1];
        for (j, v) in imp.jumps().into_iter().enumerate() {
            p[imp.cluster.first + j + 1] = v;
        }
        Some(p)
    }
    /// `P_N(t_k, w) = p_i` on `((i−1)/N, i/N]`: the weight of the Dirac
    /// mass at `t_k` as a function of `w`.
    pub fn p_n(&self, k: usize, w: &S) -> Result<S, Error> {
        let p = self.weights(k).ok_or_else(|| no_atom(k))?;
        let i = cell(w, p.len() - 1).ok_or_else(|| no_atom(k))?;
        Ok(p[i].clone())
    }
    /// `P̃_N(t_k, w) = N(p_i − p_{i−1})(w − (i−1)/N) + p_{i−1}`.
    pub fn p_tilde(&self, k: usize, w: &S) -> Result<S, Error> {
        let p = self.weights(k).ok_or_else(|| no_atom(k))?;
        let n = p.len() - 1;
        let i = cell(w, n).ok_or_else(|| no_atom(k))?;
        let frac = w.clone() * &S::from_usize(n) - &S::from_usize(i - 1);
        Ok((p[i].clone() - &p[i - 1]) * &frac + &p[i - 1])
    }
    /// `∫_0^1 P̃_N(t_k, w) dw = (1/N) Σ_{i=1}^{N−1} p_i` (trapezoids with
    /// `p_0 = p_N = 0`; also `= ∫_0^1 P_N(t_k, w) dw`), in O(parts): on a
    /// part of size `s` and pre-collision velocity `v_p` the jumps grow by
    /// `(v_p − v)/N` per particle.
    pub fn mass(&self, k: usize) -> Option<S> {
        let imp = self.traj.impulses().get(k)?;
        let n = S::from_usize(imp.n);
        let mut before = S::zero(); // Σ_{q<p} s_q (v_q − v)
        let mut total = S::zero();
        for (part, vp) in imp.parts.iter().zip(&imp.part_velocities) {
            let s = S::from_usize(part.size);
            let dv = vp.clone() - &imp.velocity;
            let tri = S::from_usize(part.size) * &S::from_usize(part.size + 1) / &S::from_i64(2);
            total = total + &(s.clone() * &before) + &(dv.clone() * &tri);
            before = before + &(s * &dv);
        }
        Some(total / &n / &n)
    }
    /// `‖P̃_N‖_{M(0,T; L¹(0,1))}`: the total mass of the atoms with
    /// `t_k ≤ T` (`prop:pressure-bound`).
    pub fn mass_until(&self, t_end: &S) -> S {
        (0..self.atoms())
            .filter(|&k| self.time(k).is_some_and(|t| t.total_cmp(t_end).is_le()))
            .filter_map(|k| self.mass(k))
            .fold(S::zero(), |a, b| a + &b)
    }
}

fn no_atom(k: usize) -> Error {
    Error::Unsupported {
        message: format!("no pressure atom number {k}"),
    }
}
