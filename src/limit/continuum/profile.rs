//! The exact profile `X(t)`, `U(t)`, `Λ(t)` at one time: its segments,
//! plateaus, and the quantities read off it.

use std::cmp::Ordering;

use num_rational::BigRational;

use crate::limit::surd::Surd;
use crate::scalar::Scalar;

/// The feature of `F = ∫f` a plateau end touches.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Attach {
    /// The knot `w = m_j` (the mass breakpoint `j`, `m_0 = 0`, `m_B = 1`).
    Knot(usize),
    /// A point inside block `k` (0-based), where `f = M`.
    Arc(usize),
}

/// One piece of the profile on `[w0, w1]` (a block, or the part of a block
/// inside or outside a plateau), with its polynomials in the absolute mass
/// variable `w` (coefficients of `1, w, w²`).
#[derive(Debug, Clone, PartialEq)]
pub struct Segment<V> {
    /// Left end.
    pub w0: V,
    /// Right end (`> w0`).
    pub w1: V,
    /// The block (0-based) the segment lies in.
    pub block: usize,
    /// The plateau (index into [`Profile::plateaus`]) containing it, if any.
    pub plateau: Option<usize>,
    /// `X(t, w) = x[0] + x[1] w`.
    pub x: [V; 2],
    /// `U(t, w) = u[0] + u[1] w`.
    pub u: [V; 2],
    /// `Λ(t, w) = lambda[0] + lambda[1] w + lambda[2] w²`.
    pub lambda: [V; 3],
}

/// A congested interval `[w0, w1]` of `{∂_w X = 1}` (a pooled block of the
/// isotonic regression): `X = w + level` and `U = velocity` on it.
#[derive(Debug, Clone, PartialEq)]
pub struct Plateau<V> {
    /// Left end.
    pub w0: V,
    /// Right end.
    pub w1: V,
    /// `M = X(t,w) − w` on the plateau.
    pub level: V,
    /// The mean of `U⁰` over the plateau (`eq:velocity-projection`).
    pub velocity: V,
    /// The features of `F` its ends touch (left, right).
    pub attach: (Attach, Attach),
}

/// `X(t)`, `U(t)`, `Λ(t)` on `[0, 1]` at one time, as exact pieces.
#[derive(Debug, Clone, PartialEq)]
pub struct Profile<V> {
    /// The time.
    pub t: BigRational,
    /// The pieces, left to right, covering `[0, 1]`.
    pub segments: Vec<Segment<V>>,
    /// The congested intervals, left to right.
    pub plateaus: Vec<Plateau<V>>,
}

impl<V> Profile<V> {
    /// The same profile with every number mapped by `f` (`None` when one
    /// number is refused).
    pub fn try_map<W>(&self, mut f: impl FnMut(&V) -> Option<W>) -> Option<Profile<W>> {
        let mut segments = Vec::with_capacity(self.segments.len());
        for s in &self.segments {
            segments.push(Segment {
                w0: f(&s.w0)?,
                w1: f(&s.w1)?,
                block: s.block,
                plateau: s.plateau,
                x: [f(&s.x[0])?, f(&s.x[1])?],
                u: [f(&s.u[0])?, f(&s.u[1])?],
                lambda: [f(&s.lambda[0])?, f(&s.lambda[1])?, f(&s.lambda[2])?],
            });
        }
        let mut plateaus = Vec::with_capacity(self.plateaus.len());
        for p in &self.plateaus {
            plateaus.push(Plateau {
                w0: f(&p.w0)?,
                w1: f(&p.w1)?,
                level: f(&p.level)?,
                velocity: f(&p.velocity)?,
                attach: p.attach,
            });
        }
        Some(Profile {
            t: self.t.clone(),
            segments,
            plateaus,
        })
    }

    /// The plateau structure: the features each plateau end touches. It
    /// changes only at the instants where plateaus form, merge or reach a
    /// new block boundary.
    pub fn signature(&self) -> Vec<(Attach, Attach)> {
        self.plateaus.iter().map(|p| p.attach).collect()
    }
}

impl Profile<Surd> {
    /// `true` when every number of the profile is rational.
    pub fn is_rational(&self) -> bool {
        self.try_map(|s| s.as_rational().cloned()).is_some()
    }
    /// The profile over `BigRational`, when every number is rational.
    pub fn to_rational(&self) -> Option<Profile<BigRational>> {
        self.try_map(|s| s.as_rational().cloned())
    }
    /// The profile rounded to doubles, and the largest rounding bound of
    /// its numbers (each double is within that distance of the exact surd;
    /// see [`Surd::to_f64_bounded`]).
    pub fn to_f64(&self) -> (Profile<f64>, f64) {
        let mut worst = 0.0f64;
        let p = self
            .try_map(|s| {
                let (v, b) = s.to_f64_bounded();
                worst = worst.max(b);
                Some(v)
            })
            .unwrap_or_else(|| Profile {
                t: self.t.clone(),
                segments: vec![],
                plateaus: vec![],
            });
        (p, worst)
    }
    /// `X(t, w)` exactly, at a rational `w ∈ [0, 1]` (left-continuous: the
    /// segment with `w0 < w ≤ w1`; `w = 0` uses the first one).
    pub fn x_exact(&self, w: &BigRational) -> Option<Surd> {
        let s = self.segment_exact(w)?;
        s.x[1].mul_rational(w).checked_add(&s.x[0])
    }
    /// `U(t, w)` exactly (same convention as [`Profile::x_exact`]).
    pub fn u_exact(&self, w: &BigRational) -> Option<Surd> {
        let s = self.segment_exact(w)?;
        s.u[1].mul_rational(w).checked_add(&s.u[0])
    }
    /// `Λ(t, w)` exactly (same convention as [`Profile::x_exact`]).
    pub fn lambda_exact(&self, w: &BigRational) -> Option<Surd> {
        let s = self.segment_exact(w)?;
        s.lambda[2]
            .mul_rational(&(w * w))
            .checked_add(&s.lambda[1].mul_rational(w))?
            .checked_add(&s.lambda[0])
    }
    fn segment_exact(&self, w: &BigRational) -> Option<&Segment<Surd>> {
        self.segments
            .iter()
            .find(|s| s.w1.cmp_rational(w) != Ordering::Less)
            .or(self.segments.last())
    }
}

fn abs<V: Scalar>(x: V) -> V {
    if x.total_cmp(&V::zero()).is_lt() {
        -x
    } else {
        x
    }
}

impl<V: Scalar> Profile<V> {
    /// The segment with `w0 < w ≤ w1` (the first one for `w ≤ 0`, the last
    /// for `w > 1`).
    pub fn segment_at(&self, w: &V) -> Option<&Segment<V>> {
        let k = self.segments.partition_point(|s| s.w1.total_cmp(w).is_lt());
        self.segments.get(k).or(self.segments.last())
    }
    /// `X(t, w)`.
    pub fn x_at(&self, w: &V) -> Option<V> {
        self.segment_at(w)
            .map(|s| s.x[0].clone() + &(s.x[1].clone() * w))
    }
    /// `U(t, w)`.
    pub fn u_at(&self, w: &V) -> Option<V> {
        self.segment_at(w)
            .map(|s| s.u[0].clone() + &(s.u[1].clone() * w))
    }
    /// `Λ(t, w)`.
    pub fn lambda_at(&self, w: &V) -> Option<V> {
        self.segment_at(w).map(|s| {
            s.lambda[0].clone() + &(s.lambda[1].clone() * w) + &(s.lambda[2].clone() * w * w)
        })
    }
    /// `∫_0^1 Λ(t, w) dw`: the total pressure mass on `[0, t]`,
    /// `∫_0^t ∫_0^1 P = ∫_0^1 Λ(t) − ∫_0^1 Λ(0)` with `Λ(0) = 0`
    /// (`prop:pressure-bound`'s quantity in the limit), exact.
    pub fn lambda_integral(&self) -> V {
        let two = V::from_i64(2);
        let three = V::from_i64(3);
        let mut total = V::zero();
        for s in &self.segments {
            let (a, b) = (&s.w0, &s.w1);
            let d1 = b.clone() - a;
            let d2 = b.clone() * b - &(a.clone() * a);
            let d3 = b.clone() * b * b - &(a.clone() * a * a);
            total = total
                + &(s.lambda[0].clone() * &d1)
                + &(s.lambda[1].clone() * &d2 / &two)
                + &(s.lambda[2].clone() * &d3 / &three);
        }
        total
    }
    /// The total variation of `w ↦ U(t, w)` on `(0, 1)`, jumps included:
    /// the limit of `‖∂_w Ũ_N(t)‖_{L¹}` (`pwUN-L1`).
    pub fn u_total_variation(&self) -> V {
        let mut total = V::zero();
        let mut prev: Option<V> = None;
        for s in &self.segments {
            let left = s.u[0].clone() + &(s.u[1].clone() * &s.w0);
            let right = s.u[0].clone() + &(s.u[1].clone() * &s.w1);
            if let Some(p) = prev {
                total = total + &abs(left.clone() - &p);
            }
            total = total + &abs(right.clone() - &left);
            prev = Some(right);
        }
        total
    }
    /// `X(t, 1) − X(t, 0⁺)`: the spread of the support, whose discrete
    /// counterpart `x_N − x_1` enters `eq:BV_XN`.
    pub fn spread(&self) -> V {
        match (self.segments.first(), self.segments.last()) {
            (Some(f), Some(l)) => {
                let x1 = l.x[0].clone() + &(l.x[1].clone() * &l.w1);
                let x0 = f.x[0].clone() + &(f.x[1].clone() * &f.w0);
                x1 - &x0
            }
            _ => V::zero(),
        }
    }
    /// The largest density `max ρ = max 1/∂_w X` over the segments
    /// (`lem:density`: it must be ≤ 1).
    pub fn max_density(&self) -> V {
        self.segments
            .iter()
            .filter(|s| !s.x[1].is_zero())
            .map(|s| V::one() / &s.x[1])
            .fold(
                V::zero(),
                |m, d| if d.total_cmp(&m).is_gt() { d } else { m },
            )
    }
}
