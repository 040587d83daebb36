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

use std::cmp::Ordering;

use num_rational::BigRational;
use num_traits::Signed;

use super::surd::Surd;
use crate::error::Error;
use crate::quantile::{BlockVelocity, MacroDatum};
use crate::scalar::Scalar;

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

/// A candidate minimiser of `Φ_M(w) = F(w) − M w`.
#[derive(Debug, Clone)]
struct Feature {
    attach: Attach,
    /// `m(M) = c0 + c1 M + c2 M²` where the feature is active.
    poly: [Q; 3],
    /// Arcs: the slopes `[f(a⁺), f(b⁻)]` for which the minimiser is inside.
    range: Option<(Q, Q)>,
    /// Knot: its position; arc: `(f_c, f_s)` with `τ(M) = (M − f_c)/f_s`.
    knot: Option<Q>,
    arc: Option<(Q, Q)>,
}

impl Feature {
    fn valid_open(&self, lo: Option<&Q>, hi: Option<&Q>) -> bool {
        match (&self.range, lo, hi) {
            (None, _, _) => true,
            (Some((a, b)), Some(lo), Some(hi)) => a <= lo && hi <= b,
            _ => false,
        }
    }
    fn valid_at(&self, k: &Q) -> bool {
        match &self.range {
            None => true,
            Some((a, b)) => a <= k && k <= b,
        }
    }
    fn value(&self, k: &Q) -> Q {
        &self.poly[0] + &self.poly[1] * k + &self.poly[2] * k * k
    }
    fn slope(&self, k: &Q) -> Q {
        &self.poly[1] + q(2) * &self.poly[2] * k
    }
    fn position(&self, m: &Surd) -> Surd {
        match (&self.knot, &self.arc) {
            (Some(w), _) => Surd::from_rational(w.clone()),
            (None, Some((fc, fs))) => m.add_rational(&-fc.clone()).mul_rational(&fs.recip()),
            (None, None) => Surd::from_rational(Q::zero()),
        }
    }
}

/// A jump of the minimiser at level `level`: from `from` (position `left`)
/// to `to` (position `right`).
#[derive(Debug, Clone)]
struct Event {
    level: Surd,
    left: Surd,
    right: Surd,
    from: Attach,
    to: Attach,
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

    fn features(&self, t: &Q) -> Vec<Feature> {
        let two = q(2);
        let mut feats = Vec::with_capacity(2 * self.pieces.len() + 1);
        let mut big_f = Q::zero(); // F(a) at the current knot
        for (k, p) in self.pieces.iter().enumerate() {
            let (fc, fs) = self.f_coeffs(k, t);
            feats.push(Feature {
                attach: Attach::Knot(k),
                poly: [big_f.clone(), -p.a.clone(), Q::zero()],
                range: None,
                knot: Some(p.a.clone()),
                arc: None,
            });
            if fs.is_positive() {
                let c = &big_f - &fc * &p.a - &fs * &p.a * &p.a / &two;
                feats.push(Feature {
                    attach: Attach::Arc(k),
                    poly: [
                        &c - &fc * &fc / (&two * &fs),
                        &fc / &fs,
                        -(&two * &fs).recip(),
                    ],
                    range: Some((&fc + &fs * &p.a, &fc + &fs * &p.b)),
                    knot: None,
                    arc: Some((fc.clone(), fs.clone())),
                });
            }
            big_f = big_f + &fc * (&p.b - &p.a) + &fs * (&p.b * &p.b - &p.a * &p.a) / &two;
        }
        let last = self.pieces.last().map(|p| p.b.clone()).unwrap_or_else(q1);
        feats.push(Feature {
            attach: Attach::Knot(self.pieces.len()),
            poly: [big_f, -last.clone(), Q::zero()],
            range: None,
            knot: Some(last),
            arc: None,
        });
        feats
    }

    /// The feature active just left (`right = false`) or just right of `k`
    /// among `valid`: lexicographic minimum of `(m(k), ±m'(k), m''(k)/2)`.
    fn limit(feats: &[Feature], valid: &[usize], k: &Q, right: bool) -> Option<usize> {
        let key = |i: usize| {
            let f = &feats[i];
            let d = f.slope(k);
            (f.value(k), if right { d } else { -d }, f.poly[2].clone())
        };
        valid.iter().copied().min_by(|&a, &b| key(a).cmp(&key(b)))
    }

    /// The jump levels strictly inside the bracket `(lo, hi)`, between the
    /// feature `a` active at its left end and `b` active at its right end.
    fn between(
        feats: &[Feature],
        valid: &[usize],
        a: usize,
        b: usize,
        bracket: (Option<&Q>, Option<&Q>),
        events: &mut Vec<Event>,
    ) -> Result<(), Error> {
        let mut stack = vec![(a, b)];
        while let Some((a, b)) = stack.pop() {
            if a == b {
                continue;
            }
            if a > b {
                return Err(internal("active features out of order"));
            }
            let diff = [
                &feats[a].poly[0] - &feats[b].poly[0],
                &feats[a].poly[1] - &feats[b].poly[1],
                &feats[a].poly[2] - &feats[b].poly[2],
            ];
            let level = crossing(&diff)?;
            if let Some(lo) = bracket.0 {
                if level.cmp_rational(lo) != Ordering::Greater {
                    return Err(internal("crossing below its bracket"));
                }
            }
            if let Some(hi) = bracket.1 {
                if level.cmp_rational(hi) != Ordering::Less {
                    return Err(internal("crossing above its bracket"));
                }
            }
            let mut best: Option<(usize, Surd)> = None;
            for &c in valid.iter().filter(|&&c| a < c && c < b) {
                let d = [
                    &feats[c].poly[0] - &feats[a].poly[0],
                    &feats[c].poly[1] - &feats[a].poly[1],
                    &feats[c].poly[2] - &feats[a].poly[2],
                ];
                let v = level.eval_quadratic(&d);
                if v.signum() == Ordering::Less
                    && best
                        .as_ref()
                        .is_none_or(|(_, bv)| v.cmp_exact(bv) == Ordering::Less)
                {
                    best = Some((c, v));
                }
            }
            match best {
                Some((c, _)) => {
                    stack.push((c, b));
                    stack.push((a, c));
                }
                None => events.push(Event {
                    left: feats[a].position(&level),
                    right: feats[b].position(&level),
                    level,
                    from: feats[a].attach,
                    to: feats[b].attach,
                }),
            }
        }
        Ok(())
    }

    /// Every jump of the minimiser `τ(M)`, in increasing `M`.
    fn events(&self, t: &Q) -> Result<Vec<Event>, Error> {
        let feats = self.features(t);
        let mut ks: Vec<Q> = Vec::with_capacity(2 * self.pieces.len());
        for k in 0..self.pieces.len() {
            let (fc, fs) = self.f_coeffs(k, t);
            ks.push(&fc + &fs * &self.pieces[k].a);
            ks.push(&fc + &fs * &self.pieces[k].b);
        }
        ks.sort();
        ks.dedup();
        let last = feats.len() - 1;
        let mut events = Vec::new();
        let mut current = 0usize;
        let mut lo: Option<Q> = None;
        for j in 0..=ks.len() {
            let hi = ks.get(j);
            let valid: Vec<usize> = (0..feats.len())
                .filter(|&i| feats[i].valid_open(lo.as_ref(), hi))
                .collect();
            let target = match hi {
                Some(k) => Self::limit(&feats, &valid, k, false)
                    .ok_or_else(|| internal("no active feature"))?,
                None => last,
            };
            Self::between(
                &feats,
                &valid,
                current,
                target,
                (lo.as_ref(), hi),
                &mut events,
            )?;
            let Some(k) = hi else { break };
            // The minimisers at the knot value k itself.
            let at: Vec<usize> = (0..feats.len()).filter(|&i| feats[i].valid_at(k)).collect();
            let min = at
                .iter()
                .map(|&i| feats[i].value(k))
                .min()
                .ok_or_else(|| internal("no feature at a knot value"))?;
            let kk = Surd::from_rational(k.clone());
            let mut lo_pos: Option<(Q, Attach)> = None;
            let mut hi_pos: Option<(Q, Attach)> = None;
            for &i in at.iter().filter(|&&i| feats[i].value(k) == min) {
                let pos = feats[i]
                    .position(&kk)
                    .as_rational()
                    .cloned()
                    .ok_or_else(|| internal("irrational position at a knot value"))?;
                if lo_pos.as_ref().is_none_or(|(p, _)| pos < *p) {
                    lo_pos = Some((pos.clone(), feats[i].attach));
                }
                if hi_pos.as_ref().is_none_or(|(p, _)| pos > *p) {
                    hi_pos = Some((pos, feats[i].attach));
                }
            }
            if let (Some((l, fa)), Some((r, fb))) = (lo_pos, hi_pos) {
                if r > l {
                    events.push(Event {
                        level: kk,
                        left: Surd::from_rational(l),
                        right: Surd::from_rational(r),
                        from: fa,
                        to: fb,
                    });
                }
            }
            let next_hi = ks.get(j + 1);
            let valid_next: Vec<usize> = (0..feats.len())
                .filter(|&i| feats[i].valid_open(Some(k), next_hi))
                .collect();
            current = Self::limit(&feats, &valid_next, k, true)
                .ok_or_else(|| internal("no active feature"))?;
            lo = Some(k.clone());
        }
        Ok(events)
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

    /// The blocks overlapping `[l, r]`, with the overlap ends.
    fn overlaps(&self, l: &Surd, r: &Surd) -> Vec<(usize, Surd, Surd)> {
        let mut out = Vec::new();
        for (k, p) in self.pieces.iter().enumerate() {
            let lo = if l.cmp_rational(&p.a) == Ordering::Greater {
                l.clone()
            } else {
                Surd::from_rational(p.a.clone())
            };
            let hi = if r.cmp_rational(&p.b) == Ordering::Less {
                r.clone()
            } else {
                Surd::from_rational(p.b.clone())
            };
            if hi.cmp_exact(&lo) == Ordering::Greater {
                out.push((k, lo, hi));
            }
        }
        out
    }

    fn free_region(
        &self,
        l: &Surd,
        r: &Surd,
        t: &Q,
        segments: &mut Vec<Segment<Surd>>,
    ) -> Result<(), Error> {
        let s = |v: &Q| Surd::from_rational(v.clone());
        for (k, lo, hi) in self.overlaps(l, r) {
            let (_, fs) = self.f_coeffs(k, t);
            if !fs.is_positive() {
                return Err(internal("a non-increasing stretch was left free"));
            }
            let p = &self.pieces[k];
            segments.push(Segment {
                w0: lo,
                w1: hi,
                block: k,
                plateau: None,
                x: [s(&(&p.x0[0] + t * &p.u0[0])), s(&(&p.x0[1] + t * &p.u0[1]))],
                u: [s(&p.u0[0]), s(&p.u0[1])],
                lambda: [s(&Q::zero()), s(&Q::zero()), s(&Q::zero())],
            });
        }
        Ok(())
    }

    fn plateau_region(
        &self,
        ev: &Event,
        t: &Q,
        segments: &mut Vec<Segment<Surd>>,
        plateaus: &mut Vec<Plateau<Surd>>,
    ) -> Result<(), Error> {
        let mismatch = || internal("surd fields mismatch on a plateau");
        let parts = self.overlaps(&ev.left, &ev.right);
        let two = q(2);
        // ∫ U⁰ over the plateau.
        let mut integral = Surd::from_rational(Q::zero());
        for (k, lo, hi) in &parts {
            let p = &self.pieces[*k];
            let d1 = hi.checked_sub(lo).ok_or_else(mismatch)?;
            let d2 = hi.square().checked_sub(&lo.square()).ok_or_else(mismatch)?;
            let part = d1
                .mul_rational(&p.u0[0])
                .checked_add(&d2.mul_rational(&(&p.u0[1] / &two)))
                .ok_or_else(mismatch)?;
            integral = integral.checked_add(&part).ok_or_else(mismatch)?;
        }
        let length = ev.right.checked_sub(&ev.left).ok_or_else(mismatch)?;
        let mean = integral.checked_div(&length).ok_or_else(mismatch)?;
        let index = plateaus.len();
        let zero = Surd::from_rational(Q::zero());
        let one = Surd::from_rational(q(1));
        let mut acc = zero.clone(); // Λ at the left end of the current part
        for (k, lo, hi) in parts {
            let p = &self.pieces[k];
            let (u, lambda) = if t.is_zero() {
                (
                    [
                        Surd::from_rational(p.u0[0].clone()),
                        Surd::from_rational(p.u0[1].clone()),
                    ],
                    [zero.clone(), zero.clone(), zero.clone()],
                )
            } else {
                // Λ(w) = acc + (u0c − Ū)(w − lo) + u0s (w² − lo²)/2.
                let c1 = mean.neg().add_rational(&p.u0[0]);
                let c2 = Surd::from_rational(&p.u0[1] / &two);
                let c0 = acc
                    .checked_sub(&c1.checked_mul(&lo).ok_or_else(mismatch)?)
                    .and_then(|v| v.checked_sub(&c2.checked_mul(&lo.square())?))
                    .ok_or_else(mismatch)?;
                let at_hi = c0
                    .checked_add(&c1.checked_mul(&hi).ok_or_else(mismatch)?)
                    .and_then(|v| v.checked_add(&c2.checked_mul(&hi.square())?))
                    .ok_or_else(mismatch)?;
                acc = at_hi;
                ([mean.clone(), zero.clone()], [c0, c1, c2])
            };
            segments.push(Segment {
                w0: lo,
                w1: hi,
                block: k,
                plateau: Some(index),
                x: [ev.level.clone(), one.clone()],
                u,
                lambda,
            });
        }
        if !t.is_zero() && acc.signum() != Ordering::Equal {
            return Err(internal("Λ does not return to 0 at the end of a plateau"));
        }
        plateaus.push(Plateau {
            w0: ev.left.clone(),
            w1: ev.right.clone(),
            level: ev.level.clone(),
            velocity: mean,
            attach: (ev.from, ev.to),
        });
        Ok(())
    }
}

fn q1() -> Q {
    <Q as Scalar>::one()
}

/// The root of the increasing `c0 + c1 M + c2 M²` inside its bracket: the
/// one where the derivative `2c2 M + c1 = +√disc ≥ 0`.
fn crossing(c: &[Q; 3]) -> Result<Surd, Error> {
    if c[2].is_zero() {
        if c[1].is_zero() {
            return Err(internal("two features with parallel minimum values"));
        }
        return Ok(Surd::from_rational(-&c[0] / &c[1]));
    }
    let disc = &c[1] * &c[1] - q(4) * &c[2] * &c[0];
    let root = Surd::sqrt_of(&disc).ok_or_else(|| internal("negative discriminant"))?;
    let den = (q(2) * &c[2]).recip();
    Ok(root.add_rational(&-c[1].clone()).mul_rational(&den))
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
