//! Appendix C (`app:uniqueness`, "Non-uniqueness of the second-order
//! dynamics"), exactly as printed and parametrised by `η > 0`:
//!
//! > `X⁰(w) = w 1_{[0,1/2)} + (w + η) 1_{[1/2,1]}`,
//! > `U⁰ = 1_{[0,1/2)} − 1_{[1/2,1]}`, collision at `t* = η/2` where
//! > `X^f(t*, w) = w + η/2`.
//! >
//! > Sticky: `X¹ = w + η/2`, `U¹ = 0`,
//! > `P¹ = [w 1_{[0,1/2)} − (1 − w) 1_{[1/2,1]}] δ_{t=t*}`.
//! >
//! > Rebound: `U² = 2w − 1`, `X² = w + η/2 + (t − t*) U²`,
//! > `P² = [(2w − w²) 1_{[0,1/2)} − (w² − 1) 1_{[1/2,1]}] δ_{t=t*}`.
//!
//! Every function here is a polynomial on `[0, 1/2)` and one on `[1/2, 1]`
//! ([`Piecewise`]); the positions after `t*` are `X = A(w) + (t − t*) B(w)`.
//! The checks are exact polynomial identities and sign conditions, valid
//! for **all** `t > t*` at once:
//!
//! * `eq:PDE-Lagr-2`: `∂_t X = U` (`B = U`, and `A = X^f(t*)`),
//!   `∂_t U + ∂_w P = 0` in `D'` with `P = W(w) δ_{t*}` (`W' = U⁰ − U(t*⁺)`
//!   on each piece, `W` continuous at `1/2` — a jump would put a Dirac mass
//!   in `∂_w P` — and `W(0) = W(1) = 0`, the boundary condition the appendix
//!   imposes), `∂_w X ≥ 1` and `X` non-decreasing;
//! * the sign and complementarity conditions `P ≥ 0`,
//!   `(∂_w X − 1) P = 0` (`∂_w X(t*) = 1` wherever `W ≠ 0`);
//! * `eq:Oleinik-Lagr`: `∂_w U < ∂_w X / t` for every `t > 0`: after `t*`
//!   it reads `A' − t* B' > 0` on each piece (and the same for the jumps at
//!   `1/2`); before `t*` only the jump of `U⁰` at `1/2` matters;
//! * the first-order system `eq:Lagr-1` with `Λ = ∫_0^t P = W` for `t > t*`:
//!   `∂_t X = U⁰ − ∂_w Λ` and `(∂_w X − 1) Λ = 0` for all `t > t*`;
//! * the projection principle `eq:velocity-projection`:
//!   `U(t) = P_{H_{X(t)}}(U⁰)` for `t > t*` (and before);
//! * the projection formula `X(t) = P_K(X⁰ + tU⁰)`, against the exact
//!   continuum solver;
//! * the particle limit: `‖X_N(t) − X^c(t)‖_{L²}` for the quantile
//!   samplings.
//!
//! The claims ledger's checks of Appendix C (each a `Result<(), Violation>`
//! on these formulas, called by the claims registry) are in
//! `checks` and re-exported here: this module is their one owner.

use num_rational::BigRational;
use num_traits::Signed;

use super::continuum::{Continuum, Profile, Segment};
use super::converge::x_l2_squared;
use super::poly;
use crate::error::Error;
use crate::quantile::{Block, BlockVelocity, MacroDatum};
use crate::scalar::Scalar;
use crate::trajectory::Trajectory;

mod checks;

pub use checks::{
    free_collision, particle_limit_on, pressure_is_continuum_on, projection_selects_sticky,
    rebound_oleinik, rebound_pressure, sticky_is_particle_limit, sticky_pressure_corrected,
    sticky_pressure_is_continuum, sticky_pressure_printed,
};

type Q = BigRational;

fn q(n: i64, d: i64) -> Q {
    BigRational::new(n.into(), d.into())
}

/// A function on `[0, 1]`: the polynomial `left` (coefficients of `1, w,
/// w², …`) on `[0, 1/2)` and `right` on `[1/2, 1]`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Piecewise {
    /// On `[0, 1/2)`.
    pub left: Vec<Q>,
    /// On `[1/2, 1]`.
    pub right: Vec<Q>,
}

/// The minimum of a polynomial of degree ≤ 2 on `[a, b]` (exact).
fn poly_min(p: &[Q], a: &Q, b: &Q) -> Q {
    let mut m = poly::eval(p, a).min(poly::eval(p, b));
    if p.len() >= 3 && !p[2].is_zero() {
        let v = -&p[1] / (q(2, 1) * &p[2]);
        if &v > a && &v < b {
            m = m.min(poly::eval(p, &v));
        }
    }
    m
}

impl Piecewise {
    fn new(left: Vec<Q>, right: Vec<Q>) -> Self {
        Piecewise { left, right }
    }
    fn constant(l: Q, r: Q) -> Self {
        Piecewise::new(vec![l], vec![r])
    }
    /// The value at `w` (left piece for `w < 1/2`).
    pub fn eval(&self, w: &Q) -> Q {
        if *w < q(1, 2) {
            poly::eval(&self.left, w)
        } else {
            poly::eval(&self.right, w)
        }
    }
    /// The left limit at `1/2` and the value there: the jump is their
    /// difference.
    pub fn jump_at_half(&self) -> Q {
        poly::eval(&self.right, &q(1, 2)) - poly::eval(&self.left, &q(1, 2))
    }
    /// The derivative on each piece.
    pub fn deriv(&self) -> Piecewise {
        Piecewise::new(poly::deriv(&self.left), poly::deriv(&self.right))
    }
    fn zip(&self, o: &Piecewise, f: impl Fn(&Q, &Q) -> Q + Copy) -> Piecewise {
        Piecewise::new(
            poly::combine(&self.left, &o.left, f),
            poly::combine(&self.right, &o.right, f),
        )
    }
    fn sub(&self, o: &Piecewise) -> Piecewise {
        self.zip(o, |a, b| a - b)
    }
    fn add(&self, o: &Piecewise) -> Piecewise {
        self.zip(o, |a, b| a + b)
    }
    fn scale(&self, c: &Q) -> Piecewise {
        Piecewise::new(
            self.left.iter().map(|x| x * c).collect(),
            self.right.iter().map(|x| x * c).collect(),
        )
    }
    fn mul(&self, o: &Piecewise) -> Piecewise {
        Piecewise::new(
            poly::mul(&self.left, &o.left),
            poly::mul(&self.right, &o.right),
        )
    }
    fn is_zero(&self) -> bool {
        poly::is_zero(&self.left) && poly::is_zero(&self.right)
    }
    /// The minimum over `[0, 1]` (pieces of degree ≤ 2).
    fn min(&self) -> Q {
        poly_min(&self.left, &q(0, 1), &q(1, 2)).min(poly_min(&self.right, &q(1, 2), &q(1, 1)))
    }
    /// The integral over `[0, 1]`.
    fn integral(&self) -> Q {
        let int = |p: &[Q], a: &Q, b: &Q| {
            p.iter().enumerate().fold(Q::zero(), |acc, (k, c)| {
                let e = (k + 1) as i32;
                acc + c * (pow(b, e) - pow(a, e)) / Q::from_integer((k + 1).into())
            })
        };
        int(&self.left, &q(0, 1), &q(1, 2)) + int(&self.right, &q(1, 2), &q(1, 1))
    }
}

fn show_poly(p: &[Q]) -> String {
    let terms: Vec<String> = p
        .iter()
        .enumerate()
        .filter(|(_, c)| !c.is_zero())
        .map(|(k, c)| match k {
            0 => c.render(),
            1 => format!("{}·w", c.render()),
            _ => format!("{}·w^{k}", c.render()),
        })
        .collect();
    if terms.is_empty() {
        "0".to_string()
    } else {
        terms.join(" + ")
    }
}

impl std::fmt::Display for Piecewise {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} on [0,1/2), {} on [1/2,1]",
            show_poly(&self.left),
            show_poly(&self.right)
        )
    }
}

fn pow(x: &Q, e: i32) -> Q {
    (0..e).fold(q(1, 1), |acc, _| acc * x)
}

/// The two continuations of Appendix C.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Continuation {
    /// `X¹`, `U¹`, `P¹`: the blocks stick.
    Sticky,
    /// `X²`, `U²`, `P²`: a rebound.
    Rebound,
}

impl Continuation {
    /// `"sticky"` or `"rebound"`.
    pub fn name(self) -> &'static str {
        match self {
            Continuation::Sticky => "sticky (X¹, U¹, P¹)",
            Continuation::Rebound => "rebound (X², U², P²)",
        }
    }
}

/// Which pressure formula: the printed one, or the corrected sticky one.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Printing {
    /// Exactly as printed.
    AsPrinted,
    /// `P¹ = [w 1_{[0,1/2)} + (1 − w) 1_{[1/2,1]}] δ_{t*}` (the sign of the
    /// second term fixed; `P²` is unchanged).
    Corrected,
}

/// The two-block datum of Appendix C with gap `η`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TwoBlocks {
    eta: Q,
}

/// One check of one continuation.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Finding {
    /// The paper's label of what is checked.
    pub claim: &'static str,
    /// The continuation.
    pub continuation: Continuation,
    /// The pressure formula used.
    pub printing: Printing,
    /// Whether it holds (for every `t > 0`).
    pub holds: bool,
    /// The exact witness, or what was verified.
    pub detail: String,
}

impl TwoBlocks {
    /// The example with gap `η > 0`.
    pub fn new(eta: Q) -> Result<Self, Error> {
        if !eta.is_positive() {
            return Err(Error::Unsupported {
                message: format!("Appendix C needs η > 0, got {}", eta.render()),
            });
        }
        Ok(TwoBlocks { eta })
    }
    /// `η`.
    pub fn eta(&self) -> &Q {
        &self.eta
    }
    /// `t* = η/2`.
    pub fn t_star(&self) -> Q {
        &self.eta / q(2, 1)
    }
    /// The datum: density 1 on `[0, 1/2]` (velocity 1) and on
    /// `[1/2 + η, 1 + η]` (velocity −1).
    pub fn datum(&self) -> Result<MacroDatum, Error> {
        let c = |v: i64| BlockVelocity::Constant(q(v, 1));
        MacroDatum::new(vec![
            Block {
                from: q(0, 1),
                to: q(1, 2),
                density: q(1, 1),
                velocity: c(1),
            },
            Block {
                from: q(1, 2) + &self.eta,
                to: q(1, 1) + &self.eta,
                density: q(1, 1),
                velocity: c(-1),
            },
        ])
    }
    /// `X⁰`.
    pub fn x0(&self) -> Piecewise {
        Piecewise::new(vec![q(0, 1), q(1, 1)], vec![self.eta.clone(), q(1, 1)])
    }
    /// `U⁰`.
    pub fn u0(&self) -> Piecewise {
        Piecewise::constant(q(1, 1), q(-1, 1))
    }
    /// `X^f(t) = X⁰ + t U⁰`.
    pub fn x_free(&self, t: &Q) -> Piecewise {
        self.x0().add(&self.u0().scale(t))
    }
    /// `A` and `B` with `X(t) = A + (t − t*) B` for `t ≥ t*`, as printed.
    pub fn after(&self, c: Continuation) -> (Piecewise, Piecewise) {
        let a = Piecewise::new(vec![self.t_star(), q(1, 1)], vec![self.t_star(), q(1, 1)]);
        let b = match c {
            Continuation::Sticky => Piecewise::constant(q(0, 1), q(0, 1)),
            Continuation::Rebound => {
                Piecewise::new(vec![q(-1, 1), q(2, 1)], vec![q(-1, 1), q(2, 1)])
            }
        };
        (a, b)
    }
    /// `X(t)` of a continuation (the free flow before `t*`).
    pub fn x(&self, c: Continuation, t: &Q) -> Piecewise {
        let ts = self.t_star();
        if *t < ts {
            return self.x_free(t);
        }
        let (a, b) = self.after(c);
        a.add(&b.scale(&(t - ts)))
    }
    /// `U(t)` (right derivative) of a continuation, as printed.
    pub fn u(&self, c: Continuation, t: &Q) -> Piecewise {
        if *t < self.t_star() {
            return self.u0();
        }
        match c {
            Continuation::Sticky => Piecewise::constant(q(0, 1), q(0, 1)),
            Continuation::Rebound => {
                Piecewise::new(vec![q(-1, 1), q(2, 1)], vec![q(-1, 1), q(2, 1)])
            }
        }
    }
    /// The weight `W` of `P = W(w) δ_{t = t*}`.
    pub fn pressure_weight(&self, c: Continuation, p: Printing) -> Piecewise {
        match (c, p) {
            // w 1_{[0,1/2)} − (1 − w) 1_{[1/2,1]}
            (Continuation::Sticky, Printing::AsPrinted) => {
                Piecewise::new(vec![q(0, 1), q(1, 1)], vec![q(-1, 1), q(1, 1)])
            }
            // w 1_{[0,1/2)} + (1 − w) 1_{[1/2,1]}
            (Continuation::Sticky, Printing::Corrected) => {
                Piecewise::new(vec![q(0, 1), q(1, 1)], vec![q(1, 1), q(-1, 1)])
            }
            // (2w − w²) 1_{[0,1/2)} − (w² − 1) 1_{[1/2,1]}
            (Continuation::Rebound, _) => Piecewise::new(
                vec![q(0, 1), q(2, 1), q(-1, 1)],
                vec![q(1, 1), q(0, 1), q(-1, 1)],
            ),
        }
    }

    /// Every check of the module documentation for one continuation.
    pub fn findings(&self, c: Continuation, p: Printing) -> Result<Vec<Finding>, Error> {
        let ts = self.t_star();
        let (a, b) = self.after(c);
        let u_after = self.u(c, &ts);
        let w = self.pressure_weight(c, p);
        let mut out = Vec::new();
        let mut push = |claim: &'static str, failure: Option<String>, ok: String| {
            out.push(Finding {
                claim,
                continuation: c,
                printing: p,
                holds: failure.is_none(),
                detail: failure.unwrap_or(ok),
            });
        };
        // ∂_t X = U.
        let xf = self.x_free(&ts);
        let fail = if a != xf {
            Some(format!("X(t*) = {a} ≠ X^f(t*) = {xf}"))
        } else if b != u_after {
            Some(format!("∂_t X = {b} ≠ U = {u_after} after t*"))
        } else {
            None
        };
        push(
            "eq:PDE-Lagr-2 (∂_t X = U)",
            fail,
            "X(t*) = X^f(t*) = w + η/2 and ∂_t X = U for t > t*".to_string(),
        );
        // ∂_t U + ∂_w P = 0.
        let target = self.u0().sub(&u_after);
        let dw = w.deriv();
        let fail = if dw.sub(&target).is_zero() {
            let jump = w.jump_at_half();
            if !jump.is_zero() {
                Some(format!(
                    "W jumps by {} at w = 1/2: ∂_w P has the Dirac mass {}·δ_{{w=1/2}}δ_{{t=t*}} that ∂_t U does not have",
                    jump.render(),
                    jump.render()
                ))
            } else {
                let (w0, w1) = (w.eval(&q(0, 1)), w.eval(&q(1, 1)));
                (!w0.is_zero() || !w1.is_zero()).then(|| {
                    format!(
                        "boundary values P(t*,0) = {}, P(t*,1) = {} (must be 0)",
                        w0.render(),
                        w1.render()
                    )
                })
            }
        } else {
            Some(format!("∂_w W = {dw} but U⁰ − U(t*⁺) = {target}"))
        };
        push(
            "eq:PDE-Lagr-2 (∂_t U + ∂_w P = 0)",
            fail,
            "∂_w W = U⁰ − U(t*⁺) on each piece, W continuous at 1/2, W(0) = W(1) = 0".to_string(),
        );
        // ∂_w X ≥ 1 (for all t ≥ t*), X non-decreasing.
        let (da, db) = (a.deriv(), b.deriv());
        let fail = if da.min() < q(1, 1) || db.min() < q(0, 1) {
            Some(format!(
                "∂_w X = A' + (t − t*)B' with min A' = {}, min B' = {}",
                da.min().render(),
                db.min().render()
            ))
        } else if a.jump_at_half() < q(0, 1) || b.jump_at_half() < q(0, 1) {
            Some("X decreases across w = 1/2".to_string())
        } else {
            None
        };
        push(
            "eq:PDE-Lagr-2 (∂_w X ≥ 1)",
            fail,
            "∂_w X ≥ 1 and X non-decreasing for all t ≥ t*".to_string(),
        );
        // P ≥ 0.
        let m = w.min();
        push(
            "eq:PDE-Lagr-2 (P ≥ 0)",
            (m < q(0, 1)).then(|| {
                format!(
                    "min_w W = {} < 0 (e.g. W(3/4) = {})",
                    m.render(),
                    w.eval(&q(3, 4)).render()
                )
            }),
            format!("min_w W = {} ≥ 0", m.render()),
        );
        // (∂_w X − 1) P = 0 at t*.
        let excess = da.sub(&Piecewise::constant(q(1, 1), q(1, 1)));
        push(
            "eq:PDE-Lagr-2 ((∂_w X − 1) P = 0)",
            (!excess.mul(&w).is_zero()).then(|| "∂_w X(t*) ≠ 1 where W ≠ 0".to_string()),
            "∂_w X(t*) = 1 on [0, 1]".to_string(),
        );
        // Oleinik, for all t > 0.
        let ole_after = da.sub(&db.scale(&ts));
        let jump_ok = {
            // t [B] < [A] + (t − t*)[B]  ⟺  [A] − t*[B] > 0, unless both jumps vanish.
            let (ja, jb) = (a.jump_at_half(), b.jump_at_half());
            (ja.is_zero() && jb.is_zero()) || (&ja - &ts * &jb).is_positive()
        };
        let fail = if ole_after.min() <= q(0, 1) {
            Some(format!(
                "after t*: ∂_w X − t ∂_w U = A' − t* B' has minimum {} ≤ 0 (the inequality needs η < {} here)",
                ole_after.min().render(),
                match c {
                    Continuation::Sticky => "∞".to_string(),
                    Continuation::Rebound => "1".to_string(),
                }
            ))
        } else if !jump_ok {
            Some("after t*: the jumps at w = 1/2 violate t[U] < [X]".to_string())
        } else {
            // Before t*: [U⁰] = −2 < [X⁰ + tU⁰]/t = (η − 2t)/t, since η > 0;
            // on each block ∂_w U⁰ = 0 < 1/t.
            None
        };
        push(
            "eq:Oleinik-Lagr",
            fail,
            format!(
                "∂_w U < ∂_w X/t for every t > 0 (after t*: A' − t*B' ≥ {} > 0)",
                ole_after.min().render()
            ),
        );
        // First-order system eq:Lagr-1 with Λ = W after t*.
        let u0_minus = self.u0().sub(&dw);
        let fail = if u0_minus != b {
            Some(format!("U⁰ − ∂_w Λ = {u0_minus} ≠ ∂_t X = {b}"))
        } else if !excess.mul(&w).is_zero() || !db.mul(&w).is_zero() {
            Some(format!(
                "(∂_w X − 1) Λ = (A' − 1 + (t − t*) B') W ≠ 0 for t > t* (e.g. at w = 1/4: ∂_w X − 1 = {}·(t − t*), Λ = {})",
                db.eval(&q(1, 4)).render(),
                w.eval(&q(1, 4)).render()
            ))
        } else {
            None
        };
        push(
            "eq:Lagr-1",
            fail,
            "∂_t X = U⁰ − ∂_w Λ, (∂_w X − 1)Λ = 0, Λ = W ≥ 0 for all t > t*".to_string(),
        );
        // Projection principle eq:velocity-projection after t*.
        let congested = |pc: &[Q], pb: &[Q]| {
            // ∂_w X ≡ 1 for every t > t* on the piece.
            poly::combine(pc, &[q(1, 1)], |x, y| x - y)
                .iter()
                .all(|v| v.is_zero())
                && poly::is_zero(pb)
        };
        let (cl, cr) = (
            congested(&da.left, &db.left),
            congested(&da.right, &db.right),
        );
        let joined = a.jump_at_half().is_zero() && b.jump_at_half().is_zero();
        let u0 = self.u0();
        // U⁰ is constant on each block: averaging over one congested block
        // leaves it unchanged, averaging over (0,1) gives its mean.
        let projected = if cl && cr && joined {
            let mean = u0.integral();
            Piecewise::constant(mean.clone(), mean)
        } else {
            u0.clone()
        };
        let diff = projected.sub(&u_after);
        // Before t*: X^f jumps by η − 2t > 0 at 1/2, two components, P_H(U⁰) = U⁰ = U.
        let separate_before = self.x_free(&(&ts / q(2, 1))).jump_at_half().is_positive();
        let fail = if !separate_before {
            Some("before t*, the blocks are not separated".to_string())
        } else {
            None
        };
        let fail = fail.or_else(|| (!diff.is_zero()).then(|| {
            let sq = diff.mul(&diff).integral();
            format!(
                "for t > t*, {{∂_w X = 1}} is {}, so P_H(U⁰) = {projected} but U = {u_after}: ‖U − P_H(U⁰)‖²_L² = {}",
                if cl && cr && joined { "(0,1)" } else if cl || cr { "one piece" } else { "empty" },
                sq.render()
            )
        }));
        push(
            "eq:velocity-projection",
            fail,
            "for t > t*, {∂_w X = 1} = (0,1) and U = mean of U⁰ = P_H(U⁰); before t*, the two blocks are separate components and U = U⁰".to_string(),
        );
        // The projection formula X(t) = P_K(X⁰ + tU⁰), against the solver.
        let continuum = Continuum::new(&self.datum()?);
        let mut fail = None;
        for t in [
            ts.clone() / q(2, 1),
            ts.clone(),
            ts.clone() * q(2, 1),
            &ts + q(1, 1),
        ] {
            let prof = continuum.profile(&t)?;
            let xc = self.x(c, &t);
            // Interior points only: the printed X⁰ is right-continuous at
            // 1/2 (1_{[1/2,1]}), the generalised inverse of the CDF is
            // left-continuous; they agree a.e. Both are affine on each
            // block, so agreement at these points is equality a.e.
            for k in 0..64 {
                let wq = q(2 * k + 1, 128);
                let solver = prof.x_exact(&wq).and_then(|s| s.as_rational().cloned());
                if solver.as_ref() != Some(&xc.eval(&wq)) {
                    fail = Some(format!(
                        "at t = {}, w = {}: X = {} but P_K(X⁰ + tU⁰) = {}",
                        t.render(),
                        wq.render(),
                        xc.eval(&wq).render(),
                        solver.map_or("?".to_string(), |s| s.render())
                    ));
                    break;
                }
            }
            if fail.is_some() {
                break;
            }
        }
        push(
            "eq:Lagr-1 (X(t) = P_K(X⁰ + tU⁰))",
            fail,
            "X(t) = P_K(X⁰ + tU⁰) a.e. at t = t*/2, t*, 2t*, t* + 1 (exact continuum solver)"
                .to_string(),
        );
        Ok(out)
    }

    /// `X^c(t)` as a profile (for the `L²` distances).
    fn profile_of(&self, c: Continuation, t: &Q) -> Profile<Q> {
        let x = self.x(c, t);
        let seg = |w0: Q, w1: Q, p: &[Q]| Segment {
            w0,
            w1,
            block: 0,
            plateau: None,
            x: [
                p.first().cloned().unwrap_or_else(Q::zero),
                p.get(1).cloned().unwrap_or_else(Q::zero),
            ],
            u: [Q::zero(), Q::zero()],
            lambda: [Q::zero(), Q::zero(), Q::zero()],
        };
        Profile {
            t: t.clone(),
            segments: vec![
                seg(q(0, 1), q(1, 2), &x.left),
                seg(q(1, 2), q(1, 1), &x.right),
            ],
            plateaus: vec![],
        }
    }

    /// `(N, ‖X_N(t) − X¹(t)‖², ‖X_N(t) − X²(t)‖²)` for the quantile
    /// samplings with the given N (exact).
    pub fn particle_distances(&self, ns: &[usize], t: &Q) -> Result<Vec<(usize, Q, Q)>, Error> {
        let datum = self.datum()?;
        let mut out = Vec::new();
        for &n in ns {
            let traj = Trajectory::new(datum.sample(n)?);
            let s = traj.at(t)?;
            let (d1, d2) = self.distances_of(&s.positions, t);
            out.push((n, d1, d2));
        }
        Ok(out)
    }

    /// `(‖X_N(t) − X¹(t)‖², ‖X_N(t) − X²(t)‖²)` for given particle positions
    /// at `t` (`X_N = x_i` on `((i−1)/N, i/N]`), exact.
    pub fn distances_of(&self, positions: &[Q], t: &Q) -> (Q, Q) {
        let p1 = self.profile_of(Continuation::Sticky, t);
        let p2 = self.profile_of(Continuation::Rebound, t);
        (x_l2_squared(positions, &p1), x_l2_squared(positions, &p2))
    }
}

/// The findings for `η`, both continuations, the printed formulas and the
/// corrected `P¹`.
pub fn all_findings(eta: &Q) -> Result<Vec<Finding>, Error> {
    let tb = TwoBlocks::new(eta.clone())?;
    let mut out = tb.findings(Continuation::Sticky, Printing::AsPrinted)?;
    out.extend(tb.findings(Continuation::Sticky, Printing::Corrected)?);
    out.extend(tb.findings(Continuation::Rebound, Printing::AsPrinted)?);
    Ok(out)
}
