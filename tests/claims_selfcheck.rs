//! The ledger's self-check (issue 29, item 8): every claim of the ledger
//! has a checker that can fail, shown on a deliberately broken input, or is
//! listed here with the reason it has none — and that list is asserted, so
//! a new checker that cannot fail breaks CI rather than waiting for an
//! audit.
//!
//! * **case claims** (and case corrections): `tests/claims_mutants.rs`
//!   requires each to reject a hand-written mutant of the engines' output on
//!   a case whose true output it accepts; here we only check that they are
//!   all of that kind.
//! * **scaling claims** (and scaling corrections): run on the measured table
//!   at N = 4 … 64 with every row corrupted by a [`RowTamper`] — every value
//!   replaced by N (a quantity that grows), or by 0 (nothing measured) — and
//!   required to fail under each; a checker that ignores its
//!   table, or whose verdict cannot see growth, is caught.
//! * **exact-formula claims**: those that read the continuum solution are
//!   run on a corrupted profile ([`formula_mutant`]); a formula claim whose
//!   printed form is false has failed already (its correction is then the
//!   one to show); the others are in [`NO_MUTANT`], with the reason.
//! * **identities** (`Claim::identity`): a checker that passes for any
//!   consistent path; listed in [`IDENTITIES`].

use num_rational::BigRational;
use sticky::claims::macro_data::cases;
use sticky::claims::scaling::{Budget, RowTamper};
use sticky::claims::{continuum, density, eulerian, registry, Kind};
use sticky::limit::appendix_c::{self, TwoBlocks};
use sticky::limit::continuum::Continuum;
use sticky::trajectory::Trajectory;
use sticky::Scalar;

type Q = BigRational;

/// Formula claims with no broken-input check here, and why.
const NO_MUTANT: &[(&str, &str)] = &[
    ("thm:main#sampling-mass", "reads no engine output: a property of the quantile sampling of fixed data (x⁰_{i+1} − x⁰_i ≥ 1/N from ρ⁰ ≤ 1); a broken sampling is caught by the exact quantiles written in src/quantile.rs's tests (x0(9/16) = 13/16, …)"),
    ("thm:main#sampling-contacts (corrected)", "reads no engine output: the printed form fails (counterexample) and the corrected one reads the same fixed samples with the one-sided limits of U⁰; a broken U⁰ is caught by the exact values in src/quantile.rs's tests (u0(9/16) = −1, …)"),
    ("app:uniqueness#free-collision", "reads no engine output: a closed formula of Appendix C (t* = η/2) on the exact two-block data; a broken formula is caught by the exact X^f = w + η/2 it is compared with, and by tests/limit/appendix_c.rs::appendix_c_as_printed"),
    ("app:uniqueness#sticky-pressure (corrected)", "reads no engine output: the printed P¹ fails (counterexample); the corrected weight is compared with the continuum Λ's jump by app:uniqueness#sticky-pressure-is-continuum, whose mutant is above, and with every eq:PDE-Lagr-2 finding in tests/limit/appendix_c.rs::appendix_c_as_printed"),
    ("app:uniqueness#rebound-pressure", "reads no engine output: a closed formula of Appendix C (no engine computes the rebound); tests/limit/appendix_c.rs::appendix_c_as_printed asserts each of its eq:PDE-Lagr-2 findings for five η"),
    ("app:uniqueness#projection-selects-sticky", "reads no engine output: two closed-form continuations of Appendix C against the projection principle; tests/limit/appendix_c.rs::appendix_c_as_printed asserts the rebound fails eq:velocity-projection and eq:Lagr-1 for five η"),
    ("app:uniqueness#rebound-oleinik", "reads no engine output: a closed formula of Appendix C; tests/limit/appendix_c.rs::appendix_c_as_printed asserts eq:Oleinik-Lagr holds for the rebound exactly when η < 1 (five η)"),
];

/// Claims reported as identities (their checker passes for any consistent
/// path, whatever the dynamics).
const IDENTITIES: &[&str] = &["prop:eulerian-formulation#mass"];

/// Every measured value of a row set to `value` (the list of a row's
/// measured fields, written once for every tamper below).
fn set_every_value(r: &mut sticky::claims::macro_data::Row, value: &Q) {
    for v in [
        &mut r.lambda_sup,
        &mut r.pressure_abs,
        &mut r.pressure_signed,
        &mut r.l2,
        &mut r.tv_late,
        &mut r.u_sup,
        &mut r.uniform_x0,
        &mut r.pn_gap,
        &mut r.c0_prime,
        &mut r.momentum,
    ] {
        *v = value.clone();
    }
    for v in [
        &mut r.disc_x,
        &mut r.disc_u,
        &mut r.cvg_x,
        &mut r.cvg_lambda,
        &mut r.lambda_nodes,
        &mut r.mass_interpolated,
    ]
    .into_iter()
    .flatten()
    {
        *v = value.clone();
    }
}

/// Every measured value replaced by N: a quantity that grows (as when a
/// factor 1/N is forgotten), whatever the claim's verdict expects.
fn grows(r: &mut sticky::claims::macro_data::Row) {
    let n = Q::from_usize(r.n);
    set_every_value(r, &n);
}

/// Every measured value set to 0.
fn zeroed(r: &mut sticky::claims::macro_data::Row) {
    set_every_value(r, &Q::zero());
}

const ROW_TAMPERS: &[(&str, RowTamper)] = &[
    ("every value replaced by N", grows),
    ("every value 0", zeroed),
];

/// A formula claim run on a corrupted datum: `Some(result)` for the claims
/// that read the continuum solution (the result must be an error).
fn formula_mutant(id: &str) -> Option<Result<(), String>> {
    if let Some(r) = appendix_c_mutant(id) {
        return Some(r);
    }
    let id: &'static str = [
        "eq:Lagr-1",
        "eq:PDE-Lagr-2",
        "eq:Oleinik-Lagr",
        "lem:density#continuum",
        "prop:eulerian-formulation#oleinik",
    ]
    .into_iter()
    .find(|k| *k == id)?;
    let cs = cases(id).ok()?;
    let profiles = || {
        cs.iter().flat_map(|c| {
            c.profiles
                .iter()
                .filter_map(move |(t, p)| p.as_ref().map(|p| (c, t.clone(), p.clone())))
        })
    };
    let err = |r: Result<(), sticky::claims::Violation>| r.map_err(|v| v.witness);
    match id {
        // Λ with its sign flipped (a quadratic Λ ≥ 0 somewhere positive).
        "eq:Lagr-1" => Some(
            profiles()
                .filter(|(_, _, p)| {
                    p.segments
                        .iter()
                        .any(|s| s.lambda.iter().any(|c| !c.is_zero()))
                })
                .map(|(c, t, mut p)| {
                    for s in &mut p.segments {
                        for l in &mut s.lambda {
                            *l = -l.clone();
                        }
                    }
                    err(continuum::lagr1_profile(&c.name, &t, &p, |w| c.datum.u0(w)))
                })
                .find(|r| r.is_err())
                .unwrap_or(Ok(())),
        ),
        // Two times read in the wrong order: Λ decreasing, P < 0.
        "eq:PDE-Lagr-2" => Some(
            cs.iter()
                .flat_map(|c| {
                    c.profiles
                        .windows(2)
                        .filter_map(move |w| match (&w[0].1, &w[1].1) {
                            (Some(a), Some(b)) => {
                                Some(err(continuum::pde_lagr2_pair(&c.name, b, a)))
                            }
                            _ => None,
                        })
                })
                .find(|r| r.is_err())
                .unwrap_or(Ok(())),
        ),
        // The velocity's slope raised above ∂_w X / t on every segment.
        "eq:Oleinik-Lagr" => Some(
            profiles()
                .map(|(c, t, mut p)| {
                    for s in &mut p.segments {
                        s.u[1] = s.x[1].clone() / &t + Q::one();
                    }
                    err(continuum::oleinik_profile(&c.name, &t, &p))
                })
                .find(|r| r.is_err())
                .unwrap_or(Ok(())),
        ),
        // X's slope below 1 on every segment (ρ = 1/∂_w X > 1: the
        // hypothesis ∂_w X ≥ 1 fails, and ρ ≤ 1 with it).
        "lem:density#continuum" => Some(
            profiles()
                .map(|(c, t, mut p)| {
                    for s in &mut p.segments {
                        s.x[1] = s.x[1].clone() / Q::from_i64(2);
                    }
                    err(density::density_continuum_profile(&c.name, &t, &p))
                })
                .find(|r| r.is_err())
                .unwrap_or(Ok(())),
        ),
        // The velocity's slope raised above ∂_w X / t on every segment, as
        // for eq:Oleinik-Lagr, read through the Eulerian u = U(t, W(t, x)).
        "prop:eulerian-formulation#oleinik" => Some(
            profiles()
                .map(|(c, t, mut p)| {
                    for s in &mut p.segments {
                        s.u[1] = s.x[1].clone() / &t + Q::one();
                    }
                    err(eulerian::oleinik_on_profile(&c.name, &t, &p))
                })
                .find(|r| r.is_err())
                .unwrap_or(Ok(())),
        ),
        _ => None,
    }
}

/// The Appendix C claims that read the engines' histories or the continuum
/// solver, run on corrupted ones.
fn appendix_c_mutant(id: &str) -> Option<Result<(), String>> {
    let err = |r: Result<(), sticky::claims::Violation>| r.map_err(|v| v.witness);
    let tb = TwoBlocks::new(Q::new(1.into(), 4.into())).ok()?;
    match id {
        // The engine's positions at t = 1 with the last particle moved by
        // 1/N (true positions are accepted: checked first).
        "app:uniqueness#particle-limit" => {
            let t = Q::one();
            let datum = tb.datum().ok()?;
            let mut good = Vec::new();
            let mut bad = Vec::new();
            for n in [8usize, 16, 32] {
                let s = Trajectory::new(datum.sample(n).ok()?).at(&t).ok()?;
                let (d1, d2) = tb.distances_of(&s.positions, &t);
                good.push((n, d1, d2));
                let mut x = s.positions.clone();
                let last = x.len() - 1;
                x[last] = x[last].clone() + Q::from_usize(n).recip();
                let (d1, d2) = tb.distances_of(&x, &t);
                bad.push((n, d1, d2));
            }
            if appendix_c::particle_limit_on(&tb, &t, &good).is_err() {
                // The true positions must pass for the mutant to mean anything.
                return Some(Ok(()));
            }
            Some(err(appendix_c::particle_limit_on(&tb, &t, &bad)))
        }
        // The continuum profile at t* replaced by the one at t*/2: no jump
        // of Λ, while P¹ is not 0 inside (0, 1).
        "app:uniqueness#sticky-pressure-is-continuum" => {
            let c = Continuum::new(&tb.datum().ok()?);
            let before = c.profile(&(tb.t_star() / Q::from_i64(2))).ok()?;
            let at = c.profile(&tb.t_star()).ok()?;
            if appendix_c::pressure_is_continuum_on(&tb, &before, &at).is_err() {
                // The true profiles must pass for the mutant to mean anything.
                return Some(Ok(()));
            }
            Some(err(appendix_c::pressure_is_continuum_on(
                &tb, &before, &before,
            )))
        }
        _ => None,
    }
}

#[test]
fn every_claim_can_fail_or_says_why_not() {
    let mut unexplained = Vec::new();
    let mut listed_formulas = Vec::new();
    let mut identities = Vec::new();
    let mut scaling = 0usize;
    for claim in registry::<Q>() {
        if claim.identity.is_some() {
            identities.push(claim.id);
        }
        let mut checks: Vec<(String, &Kind<Q>)> = vec![(claim.id.to_string(), &claim.kind)];
        if let Some(c) = &claim.correction {
            checks.push((format!("{} (corrected)", claim.id), &c.check));
        }
        for (id, kind) in checks {
            match kind {
                // tests/claims_mutants.rs: each must reject a mutant.
                Kind::Case(_) => {}
                Kind::Scaling(check) => {
                    scaling += 1;
                    for (name, t) in ROW_TAMPERS {
                        let b = Budget {
                            max_n: 64,
                            tamper: Some(*t),
                        };
                        if check(b).is_ok() {
                            unexplained.push(format!(
                                "{id}: the scaling checker accepts a table with {name}"
                            ));
                        }
                    }
                }
                Kind::Formula(check) => {
                    let printed_fails = !id.ends_with("(corrected)") && check().is_err();
                    if printed_fails {
                        continue;
                    }
                    match formula_mutant(&id) {
                        Some(Err(_)) => {}
                        Some(Ok(())) => unexplained
                            .push(format!("{id}: the formula checker accepts its mutant")),
                        None => {
                            if NO_MUTANT.iter().any(|(n, _)| *n == id) {
                                listed_formulas.push(id);
                            } else {
                                unexplained.push(format!(
                                    "{id}: exact-formula claim with no mutant and no reason in NO_MUTANT"
                                ));
                            }
                        }
                    }
                }
                Kind::NotCheckable(_) => unexplained.push(format!("{id}: not checkable")),
            }
        }
    }
    assert!(scaling >= 10, "the registry lost its scaling claims");
    assert!(
        unexplained.is_empty(),
        "{} checker(s) that no broken input fails:\n{}",
        unexplained.len(),
        unexplained.join("\n")
    );
    // The lists are exact: no stale entry.
    let mut expected: Vec<&str> = NO_MUTANT.iter().map(|(n, _)| *n).collect();
    expected.sort_unstable();
    listed_formulas.sort();
    assert_eq!(
        listed_formulas, expected,
        "NO_MUTANT is not the list of formula claims without a mutant"
    );
    assert_eq!(identities, IDENTITIES, "the identities changed");
}
