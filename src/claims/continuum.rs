//! The limit system checked on the exact continuum solution
//! ([`crate::limit::continuum`]) of the macroscopic data of the scaling
//! claims ([`super::macro_data`]: the two shipped scenes and the random
//! data), at `t = T/4, T/2, 3T/4, T`, on the profiles that are rational
//! there (every comparison exact; an irrational profile is skipped and the
//! count says how many were checked).
//!
//! A rational profile is a list of segments `[w₀, w₁]` on which
//! `X = x₀ + x₁w`, `U = u₀ + u₁w`, `Λ = λ₀ + λ₁w + λ₂w²`; every check below
//! is on these polynomials (a quadratic is non-negative on an interval iff
//! it is at both ends and at its vertex when inside).

use num_rational::BigRational;

use super::macro_data::{cases, MacroCase};
use super::Violation;
use crate::limit::continuum::{Profile, Segment};
use crate::scalar::Scalar;

type Q = BigRational;
type R = Result<(), Violation>;

fn poly(c: &[Q], w: &Q) -> Q {
    c.iter().rev().fold(Q::zero(), |acc, x| acc * w + x)
}

/// `min_{w ∈ [w₀, w₁]} (c₀ + c₁w + c₂w²)`, exact.
fn min_quadratic(c: &[Q; 3], w0: &Q, w1: &Q) -> (Q, Q) {
    let mut best = (poly(c, w0), w0.clone());
    let end = (poly(c, w1), w1.clone());
    if end.0 < best.0 {
        best = end;
    }
    if c[2] > Q::zero() {
        let v = -c[1].clone() / (Q::from_i64(2) * &c[2]);
        if v > *w0 && v < *w1 {
            let val = poly(c, &v);
            if val < best.0 {
                best = (val, v);
            }
        }
    }
    best
}

fn each_profile(
    id: &'static str,
    mut f: impl FnMut(&MacroCase, &Q, &Profile<Q>) -> R,
) -> Result<usize, Violation> {
    let mut checked = 0;
    for c in cases(id)? {
        for (t, p) in &c.profiles {
            if let Some(p) = p {
                f(&c, t, p)?;
                checked += 1;
            }
        }
    }
    if checked == 0 {
        return Err(Violation::new(id, "vacuous: no rational continuum profile"));
    }
    Ok(checked)
}

fn seg_text(s: &Segment<Q>) -> String {
    format!("segment [{}, {}]", s.w0.render(), s.w1.render())
}

/// `eq:Lagr-1` on one profile: `∂_w X ≥ 1`, `Λ ≥ 0`, `(∂_w X − 1)Λ = 0`,
/// `Λ(t,0) = Λ(t,1) = 0`, and `∂_t X = U⁰ − ∂_w Λ` with `∂_t X = U` (the
/// profile's right derivative) and `U⁰` read from the datum (at the
/// segment's midpoint and ends, where both sides are affine).
pub fn lagr1_profile(name: &str, t: &Q, p: &Profile<Q>, u0: impl Fn(&Q) -> Q) -> R {
    const ID: &str = "eq:Lagr-1";
    let bad = |what: String| {
        Err(Violation::new(
            ID,
            format!("{name}, t = {}: {what}", t.render()),
        ))
    };
    for s in &p.segments {
        if s.x[1] < Q::one() {
            return bad(format!("{}: ∂_w X = {} < 1", seg_text(s), s.x[1].render()));
        }
        let (m, at) = min_quadratic(&s.lambda, &s.w0, &s.w1);
        if m < Q::zero() {
            return bad(format!(
                "{}: Λ(w = {}) = {} < 0",
                seg_text(s),
                at.render(),
                m.render()
            ));
        }
        if s.x[1] != Q::one() && s.lambda.iter().any(|c| !c.is_zero()) {
            return bad(format!(
                "{}: ∂_w X − 1 = {} but Λ = {} + {}w + {}w² is not 0",
                seg_text(s),
                (s.x[1].clone() - Q::one()).render(),
                s.lambda[0].render(),
                s.lambda[1].render(),
                s.lambda[2].render()
            ));
        }
        let h = s.w1.clone() - &s.w0;
        for w in [
            s.w0.clone() + h.clone() / Q::from_i64(4),
            s.w0.clone() + h.clone() / Q::from_i64(2),
            s.w1.clone() - h / Q::from_i64(4),
        ] {
            let lhs = poly(&s.u, &w);
            let rhs = u0(&w) - (s.lambda[1].clone() + Q::from_i64(2) * &s.lambda[2] * &w);
            if lhs != rhs {
                return bad(format!(
                    "{}: at w = {}, ∂_t X = U = {} but U⁰ − ∂_w Λ = {}",
                    seg_text(s),
                    w.render(),
                    lhs.render(),
                    rhs.render()
                ));
            }
        }
    }
    for (w, seg) in [
        (Q::zero(), p.segments.first()),
        (Q::one(), p.segments.last()),
    ] {
        if let Some(s) = seg {
            let v = poly(&s.lambda, &w);
            if !v.is_zero() {
                return bad(format!("Λ(t, {}) = {} ≠ 0", w.render(), v.render()));
            }
        }
    }
    Ok(())
}

/// `eq:Lagr-1` on every rational continuum profile.
pub fn lagr1() -> R {
    const ID: &str = "eq:Lagr-1";
    each_profile(ID, |c, t, p| {
        lagr1_profile(&c.name, t, p, |w| c.datum.u0(w))
    })
    .map(|_| ())
}

/// `Λ(t₁) − Λ(t₀) ≥ 0` on `[0, 1]` (the pressure `P = ∂_t Λ` is a
/// non-negative measure on `(t₀, t₁] × (0, 1)`), and the momentum equation
/// `∂_t U + ∂_w P = 0` integrated over `(t₀, t₁]`: `U(t₁) − U(t₀) =
/// −∂_w(Λ(t₁) − Λ(t₀))` on the common refinement of the two profiles.
pub fn pde_lagr2_pair(name: &str, a: &Profile<Q>, b: &Profile<Q>) -> R {
    const ID: &str = "eq:PDE-Lagr-2";
    let mut cuts: Vec<Q> = a
        .segments
        .iter()
        .chain(&b.segments)
        .flat_map(|s| [s.w0.clone(), s.w1.clone()])
        .collect();
    cuts.sort();
    cuts.dedup();
    let find = |p: &Profile<Q>, w: &Q| -> Option<Segment<Q>> {
        p.segments
            .iter()
            .find(|s| s.w0 <= *w && *w <= s.w1)
            .cloned()
    };
    for w in cuts.windows(2) {
        let mid = (w[0].clone() + &w[1]) / Q::from_i64(2);
        let (Some(sa), Some(sb)) = (find(a, &mid), find(b, &mid)) else {
            continue;
        };
        let d: [Q; 3] = std::array::from_fn(|k| sb.lambda[k].clone() - &sa.lambda[k]);
        let (m, at) = min_quadratic(&d, &w[0], &w[1]);
        if m < Q::zero() {
            return Err(Violation::new(
                ID,
                format!(
                    "{name}: Λ({}, w) − Λ({}, w) = {} < 0 at w = {}: P = ∂_t Λ is not ≥ 0",
                    b.t.render(),
                    a.t.render(),
                    m.render(),
                    at.render()
                ),
            ));
        }
        let du: [Q; 2] = std::array::from_fn(|k| sb.u[k].clone() - &sa.u[k]);
        if du[0] != -d[1].clone() || du[1] != -(Q::from_i64(2) * &d[2]) {
            return Err(Violation::new(
                ID,
                format!(
                    "{name}: on [{}, {}], U({}) − U({}) = {} + {}w but −∂_w(Λ({}) − Λ({})) = {} + {}w",
                    w[0].render(),
                    w[1].render(),
                    b.t.render(),
                    a.t.render(),
                    du[0].render(),
                    du[1].render(),
                    b.t.render(),
                    a.t.render(),
                    (-d[1].clone()).render(),
                    (-(Q::from_i64(2) * &d[2])).render()
                ),
            ));
        }
    }
    Ok(())
}

/// `eq:PDE-Lagr-2` between consecutive rational profiles of every datum.
pub fn pde_lagr2() -> R {
    const ID: &str = "eq:PDE-Lagr-2";
    let mut checked = 0;
    for c in cases(ID)? {
        for w in c.profiles.windows(2) {
            if let (Some(a), Some(b)) = (&w[0].1, &w[1].1) {
                pde_lagr2_pair(&c.name, a, b)?;
                checked += 1;
            }
        }
    }
    if checked == 0 {
        return Err(Violation::new(ID, "vacuous: no pair of rational profiles"));
    }
    Ok(())
}

/// `eq:Oleinik-Lagr` on one profile at `t > 0`: on every segment (the
/// absolutely continuous parts) `t ∂_w U < ∂_w X` strictly, and at every
/// segment boundary (the jump parts) `t [U] ≤ [X]`.
pub fn oleinik_profile(name: &str, t: &Q, p: &Profile<Q>) -> R {
    const ID: &str = "eq:Oleinik-Lagr";
    for s in &p.segments {
        if t.clone() * &s.u[1] >= s.x[1] {
            return Err(Violation::new(
                ID,
                format!(
                    "{name}, t = {}, {}: t ∂_w U = {} ≥ ∂_w X = {}",
                    t.render(),
                    seg_text(s),
                    (t.clone() * &s.u[1]).render(),
                    s.x[1].render()
                ),
            ));
        }
    }
    for w in p.segments.windows(2) {
        let at = &w[1].w0;
        let jx = poly(&w[1].x, at) - poly(&w[0].x, at);
        let ju = poly(&w[1].u, at) - poly(&w[0].u, at);
        if t.clone() * &ju > jx {
            return Err(Violation::new(
                ID,
                format!(
                    "{name}, t = {}, w = {}: t [U] = {} > [X] = {}",
                    t.render(),
                    at.render(),
                    (t.clone() * ju).render(),
                    jx.render()
                ),
            ));
        }
    }
    Ok(())
}

/// `eq:Oleinik-Lagr` on every rational continuum profile.
pub fn oleinik_lagr() -> R {
    each_profile("eq:Oleinik-Lagr", |c, t, p| oleinik_profile(&c.name, t, p)).map(|_| ())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(n: i64, d: i64) -> Q {
        Q::new(n.into(), d.into())
    }

    fn seg(w0: Q, w1: Q, x: [Q; 2], u: [Q; 2], lambda: [Q; 3]) -> Segment<Q> {
        Segment {
            w0,
            w1,
            block: 0,
            plateau: None,
            x,
            u,
            lambda,
        }
    }

    fn profile(t: Q, segments: Vec<Segment<Q>>) -> Profile<Q> {
        Profile {
            t,
            segments,
            plateaus: vec![],
        }
    }

    /// Two touching blocks meeting at speed ±1, stuck at t: one plateau
    /// with U = 0 and Λ = w(1 − w)/… built by hand.
    fn stuck(t: Q) -> Profile<Q> {
        // U⁰ = 1 on (0, 1/2), −1 on (1/2, 1); U = 0; Λ = ∫(U⁰ − U).
        profile(
            t,
            vec![
                seg(
                    q(0, 1),
                    q(1, 2),
                    [q(0, 1), q(1, 1)],
                    [q(0, 1), q(0, 1)],
                    [q(0, 1), q(1, 1), q(0, 1)],
                ),
                seg(
                    q(1, 2),
                    q(1, 1),
                    [q(0, 1), q(1, 1)],
                    [q(0, 1), q(0, 1)],
                    [q(1, 1), q(-1, 1), q(0, 1)],
                ),
            ],
        )
    }

    fn u0(w: &Q) -> Q {
        if *w <= q(1, 2) {
            q(1, 1)
        } else {
            q(-1, 1)
        }
    }

    #[test]
    fn the_hand_built_sticky_profile_passes() {
        assert!(lagr1_profile("stuck", &q(1, 1), &stuck(q(1, 1)), u0).is_ok());
        assert!(oleinik_profile("stuck", &q(1, 1), &stuck(q(1, 1))).is_ok());
        assert!(pde_lagr2_pair("stuck", &stuck(q(1, 2)), &stuck(q(1, 1))).is_ok());
    }

    #[test]
    fn a_negative_multiplier_is_caught() {
        let mut p = stuck(q(1, 1));
        p.segments[0].lambda = [q(0, 1), q(-1, 1), q(0, 1)];
        p.segments[0].u = [q(2, 1), q(0, 1)];
        assert!(lagr1_profile("neg", &q(1, 1), &p, u0).is_err());
    }

    #[test]
    fn a_multiplier_off_the_congested_set_is_caught() {
        let mut p = stuck(q(1, 1));
        p.segments[1].x = [q(-1, 2), q(2, 1)];
        assert!(lagr1_profile("off", &q(1, 1), &p, u0).is_err());
    }

    #[test]
    fn a_wrong_momentum_balance_is_caught() {
        let mut p = stuck(q(1, 1));
        p.segments[0].u = [q(1, 4), q(0, 1)];
        assert!(lagr1_profile("mom", &q(1, 1), &p, u0).is_err());
        assert!(pde_lagr2_pair("mom", &stuck(q(1, 2)), &p).is_err());
    }

    #[test]
    fn a_decreasing_multiplier_is_a_negative_pressure() {
        let mut later = stuck(q(1, 1));
        for s in &mut later.segments {
            for c in &mut s.lambda {
                *c = c.clone() / Q::from_i64(2);
            }
        }
        assert!(pde_lagr2_pair("dec", &stuck(q(1, 2)), &later).is_err());
    }

    #[test]
    fn an_oleinik_violation_is_caught() {
        let mut p = stuck(q(1, 1));
        p.segments[0].u = [q(0, 1), q(1, 1)];
        assert!(oleinik_profile("ole", &q(1, 1), &p).is_err());
        let mut j = stuck(q(1, 1));
        j.segments[1].u = [q(1, 1), q(0, 1)];
        assert!(oleinik_profile("jump", &q(1, 1), &j).is_err());
    }
}
