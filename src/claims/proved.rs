//! The section-3 constants proved in Coq for every N
//! (`proofs/coq/theories/S3*.v`), as exact functions of one sampled datum,
//! and the comparison of the ledger's measurements with them (by the
//! scaling checkers, and by `with_proved` for a statement checked case
//! by case).
//!
//! Each [`Proved`] row names a claim (printed or corrected statement), the
//! Coq theorem, the quantity it bounds, and the constant in words and as a
//! function of the datum's [`SceneData`]. A row with a [`Proved::measure`]
//! is checked by the scaling checker its [`Measure::checker`]: every measured
//! value (each datum, each N) above the constant is a violation of the
//! proof by the code, and the report records the tightness
//! `max measured / constant`. Everything is exact (`BigRational`).

use num_bigint::BigInt;
use num_rational::BigRational;
use num_traits::Signed;

use super::coq::Statement;
use super::domain::Domain;
use super::ledger::{timeless, Budget, Outcome, Status};
use super::macro_data::{Row, Series};
use super::Kind;
use super::Violation;
use crate::scalar::Scalar;

type Q = BigRational;

/// The data of one sampled datum at one N that the proved constants read.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneData {
    /// `M = max_i |u⁰_i|`.
    pub m: Q,
    /// `S = x⁰_N − x⁰_0`, with the artificial particle
    /// `x⁰_0 = x⁰_1 − 1/N − δ`, `δ = 1` (`df:x0`).
    pub s: Q,
    /// The horizon `T` of the check.
    pub t: Q,
    /// `‖x⁰‖² = (1/N) Σ_i (x⁰_i)²`.
    pub x0_sq: Q,
    /// `‖u⁰‖² = (1/N) Σ_i (u⁰_i)²`.
    pub u0_sq: Q,
}

impl SceneData {
    /// The data of positions `x⁰_1 … x⁰_N` and velocities `u⁰`, horizon `t`.
    pub fn of(x0: &[Q], u0: &[Q], t: &Q) -> Self {
        debug_assert!(
            !x0.is_empty() && x0.len() == u0.len(),
            "one x⁰, u⁰ per particle"
        );
        let nn = Q::from_usize(x0.len());
        let sq = |v: &[Q]| v.iter().fold(Q::zero(), |a, b| a + b.clone() * b) / &nn;
        SceneData {
            m: u0.iter().map(|v| v.abs()).fold(Q::zero(), Q::max),
            s: x0[x0.len() - 1].clone() - &x0[0] + nn.recip() + Q::one(),
            t: t.clone(),
            x0_sq: sq(x0),
            u0_sq: sq(u0),
        }
    }
}

/// One proved constant.
#[derive(Debug, Clone, Copy)]
pub struct Proved {
    /// The ledger claim id.
    pub claim: &'static str,
    /// Which of its statements the theorem proves.
    pub statement: Statement,
    /// The Coq theorem (`Module.name` in `proofs/coq/theories/`).
    pub theorem: &'static str,
    /// The quantity bounded, as the ledger measures it.
    pub quantity: &'static str,
    /// The constant, in words.
    pub constant: &'static str,
    /// The constant on one datum.
    pub value: fn(&SceneData) -> Q,
    /// The measurement compared with the constant (`None`: no measured
    /// quantity of the ledger is this one).
    pub measure: Option<Measure>,
}

/// A measurement of a proved quantity on the scaling table
/// ([`super::macro_data::table`]).
#[derive(Debug, Clone, Copy)]
pub struct Measure {
    /// Who compares it: the id a scaling checker reports under, or the
    /// claim's own id for a statement checked case by case (the ledger
    /// then measures it on the scaling table once the cases hold).
    pub checker: &'static str,
    /// The measured quantity of a [`Row`].
    pub of: fn(&Row) -> Q,
}

fn two_m(d: &SceneData) -> Q {
    d.m.clone() * Q::from_i64(2)
}

fn bv(d: &SceneData) -> Q {
    d.s.clone() + d.t.clone() * &d.m * Q::from_i64(2)
}

/// `C_α = 2(1 + 2T)C'_0/α + 2M` of `S3BVU.pwUN_L1` at the ledger's
/// `α = T/2`: `4(1 + 2T)(S + M)/T + 2M`.
fn c_alpha(d: &SceneData) -> Q {
    debug_assert!(d.t.is_positive(), "pwUN-L1 needs 0 < α = T/2");
    let c0 = d.s.clone() + &d.m;
    let one_2t = Q::one() + d.t.clone() * Q::from_i64(2);
    one_2t * c0 * Q::from_i64(4) / &d.t + two_m(d)
}

/// Every proved constant, in the ledger's order.
pub const PROVED: [Proved; 10] = [
    Proved {
        claim: "eq:sup-micro-u-L#velocity-and-increments",
        statement: Statement::Printed,
        theorem: "S3Linf.multiplier_increment_bound",
        quantity: "sup_t max_i |N(λ_i(t) − λ_{i−1}(t))|",
        constant: "2M, M = max_i |u⁰_i|",
        value: two_m,
        measure: Some(Measure {
            checker: "eq:sup-micro-u-L#velocity-and-increments",
            of: |r| r.increment_sup.clone(),
        }),
    },
    Proved {
        claim: "eq:sup-micro-u-L#N-lambda",
        statement: Statement::Corrected,
        theorem: "S3Linf.multiplier_sup_bound",
        quantity: "sup_{t ≤ T} max_i |λ_i(t)|",
        constant: "2M, M = max_i |u⁰_i|",
        value: two_m,
        measure: Some(Measure {
            checker: "eq:sup-micro-u-L#N-lambda (corrected)",
            of: |r| r.lambda_sup.clone(),
        }),
    },
    Proved {
        claim: "eq:diffLambda_N",
        statement: Statement::Corrected,
        theorem: "S3Linf.diffLambda_N",
        quantity: "N · sup_{t,w} |Λ̃_N − Λ_N|",
        constant: "2M, M = max_i |u⁰_i|",
        value: two_m,
        measure: Some(Measure {
            checker: "eq:diffLambda_N",
            of: |r| r.increment_sup.clone(),
        }),
    },
    Proved {
        claim: "eq:BV_XN",
        statement: Statement::Printed,
        theorem: "S3Positions.BV_XN",
        quantity: "sup_{t ≤ T} (x_N(t) − x_0(t)) = ∫|∂_w X̃_N|",
        constant: "S + 2TM, S = x⁰_N − x⁰_0 (x⁰_0 = x⁰_1 − 1/N − δ, δ = 1), M = max_i |u⁰_i|",
        value: bv,
        measure: Some(Measure {
            checker: "eq:BV_XN",
            of: |r| r.width_sup.clone(),
        }),
    },
    Proved {
        claim: "prop:cvg1#XN-L1",
        statement: Statement::Printed,
        theorem: "S3Positions.XN_L1",
        quantity: "N · sup_{t ≤ T} ‖X̃_N − X_N‖_{L¹}",
        constant: "(S + 2TM)/2, S = x⁰_N − x⁰_0 (x⁰_0 = x⁰_1 − 1/N − δ, δ = 1), M = max_i |u⁰_i|",
        value: |d| bv(d) / Q::from_i64(2),
        measure: Some(Measure {
            checker: "prop:cvg1#XN-L1",
            of: |r| r.width_sup.clone() / Q::from_i64(2),
        }),
    },
    Proved {
        claim: "prop:pressure-bound",
        statement: Statement::Printed,
        theorem: "S3Pressure.pressure_bound",
        quantity: "Σ_{t_k ≤ T} (1/N) Σ_i [λ_i]_{t_k} (φ = 1)",
        constant: "2M, M = max_i |u⁰_i|",
        value: two_m,
        measure: Some(Measure {
            checker: "prop:pressure-bound",
            of: |r| r.pressure_abs.clone(),
        }),
    },
    Proved {
        claim: "prop:L2-micro",
        statement: Statement::Printed,
        theorem: "S3L2.L2_micro_XN_UN",
        quantity: "sup_{t ≤ T} (‖X_N(t)‖² + ‖∂_t X_N(t)‖²) in L²(0,1) (two of the seven norms)",
        constant: "(3 + 2T²)·C₀², C₀² = max(‖x⁰‖², ‖u⁰‖²) (the theorem's 2(1 + T²)C₀² + C₀²)",
        value: |d| {
            let c = d.x0_sq.clone().max(d.u0_sq.clone());
            (Q::from_i64(3) + d.t.clone() * &d.t * Q::from_i64(2)) * c
        },
        measure: Some(Measure {
            checker: "prop:L2-micro",
            of: |r| r.l2_xu.clone(),
        }),
    },
    Proved {
        claim: "prop:2ndorder-LagrPDE#PN-minus-tPN",
        statement: Statement::Printed,
        theorem: "S3Linf.diffLambda_N",
        quantity: "N · sup_t |∫_0^1 (Λ_N − Λ̃_N) w dw|",
        constant: "M = max_i |u⁰_i| (diffLambda_N's N·|Λ̃_N − Λ_N| ≤ 2M, times ∫_0^1 w dw = 1/2)",
        value: |d| d.m.clone(),
        measure: Some(Measure {
            checker: "prop:2ndorder-LagrPDE#PN-minus-tPN",
            of: |r| r.pn_gap.clone(),
        }),
    },
    Proved {
        claim: "eq:bound-UN-Linf",
        statement: Statement::Printed,
        theorem: "S3Linf.bound_UN_tUN_Linf",
        quantity: "‖U_N‖_∞ + ‖Ũ_N‖_∞ = 2 sup_t max_i |u_i(t)|",
        constant: "2M, M = max_i |u⁰_i|",
        value: two_m,
        measure: Some(Measure {
            checker: "eq:bound-UN-Linf",
            of: |r| r.u_sup.clone(),
        }),
    },
    Proved {
        claim: "pwUN-L1#independent-of-N",
        statement: Statement::Printed,
        theorem: "S3BVU.pwUN_L1",
        quantity: "sup_{t ∈ [α, T]} ‖∂_w Ũ_N(t)‖_{L¹} = Σ_i |u_i − u_{i−1}| at α = T/2",
        constant: "C_α = 2(1 + 2T)C'_0/α + 2M at α = T/2, C'_0 = S + M (cond:Linfty's smallest), S = x⁰_N − x⁰_0 (x⁰_0 = x⁰_1 − 1/N − δ, δ = 1), M = max_i |u⁰_i|",
        value: c_alpha,
        measure: Some(Measure {
            checker: "pwUN-L1#independent-of-N",
            of: |r| r.tv_late.clone(),
        }),
    },
];

/// The proved constant of one statement of a claim.
pub fn proved(claim: &str, statement: Statement) -> Option<&'static Proved> {
    PROVED
        .iter()
        .find(|p| p.claim == claim && p.statement == statement)
}

/// The proved constant a scaling checker compares with (by the id it
/// reports under).
pub fn for_checker(id: &str) -> Option<&'static Proved> {
    PROVED
        .iter()
        .find(|p| p.measure.is_some_and(|m| m.checker == id))
}

/// The largest ratio measured / constant on one datum.
#[derive(Debug, Clone, PartialEq)]
pub struct Tightness {
    /// The datum.
    pub scene: String,
    /// The N where the ratio is largest.
    pub n: usize,
    /// The measured value there.
    pub measured: Q,
    /// The proved constant there.
    pub constant: Q,
}

impl Tightness {
    /// `measured / constant` (0 when the constant is 0, which forces the
    /// measured value to be 0).
    pub fn ratio(&self) -> Q {
        if self.constant.is_zero() {
            Q::zero()
        } else {
            self.measured.clone() / &self.constant
        }
    }

    /// One line for the ledger note.
    pub fn summary(&self) -> String {
        format!(
            "max/proved constant = {} ≈ {} (N = {}: {} ≤ {})",
            self.ratio().render(),
            decimal(&self.ratio()),
            self.n,
            self.measured.render(),
            self.constant.render()
        )
    }
}

/// The note of a statement checked case by case whose quantity was
/// measured against its proved constant: one [`Tightness::summary`] per
/// datum.
pub fn note(tightness: &[Tightness]) -> Option<String> {
    if tightness.is_empty() {
        return None;
    }
    let each: Vec<String> = tightness
        .iter()
        .map(|t| format!("{}: {}", t.scene, t.summary()))
        .collect();
    Some(format!(
        "on the scaling data, against the constant proved in Coq: {}",
        each.join("; ")
    ))
}

/// A statement checked case by case that holds, and whose quantity has a
/// constant proved in Coq with a measurement (`claims::proved`): the
/// measurement on the scaling table (`budget.scaling_max_n`) is compared
/// with the constant; the outcome gains the tightness, or becomes the
/// counterexample of a measurement above the constant (the code against
/// the proof). Every other outcome is returned as it is.
pub(crate) fn with_proved(
    kind: &Kind<BigRational>,
    domain: &Domain,
    id: &str,
    statement: Statement,
    outcome: Outcome,
    budget: Budget,
) -> Outcome {
    let (Kind::Case(_), Status::Holds, Some(p)) = (kind, &outcome.status, proved(id, statement))
    else {
        return outcome;
    };
    match super::scaling::proved_tightness(p, budget.scaling_max_n) {
        Ok(tightness) => Outcome {
            note: outcome.note.or_else(|| note(&tightness)),
            tightness,
            ..outcome
        },
        Err(v) => Outcome {
            status: Status::Counterexample,
            cases: outcome.cases,
            witness_data: Some(timeless(&v, domain)),
            witness: Some(v.witness),
            tightness: Vec::new(),
            note: None,
        },
    }
}

/// `q ≥ 0` truncated to four decimals (integer arithmetic only).
pub fn decimal(q: &Q) -> String {
    let scaled = (q.clone() * Q::from_i64(10_000)).floor().to_integer();
    let (int, frac) = (
        &scaled / BigInt::from(10_000),
        &scaled % BigInt::from(10_000),
    );
    format!("{int}.{frac:0>4}")
}

/// Compares `measure` with the constant `p` on every row of one datum:
/// the violation names the first row above it; else the tightness.
pub fn check(
    p: &Proved,
    measure: fn(&Row) -> Q,
    series: &Series,
) -> Result<Option<Tightness>, Violation> {
    let mut best: Option<Tightness> = None;
    for r in &series.rows {
        let c = (p.value)(&r.data);
        let v = measure(r);
        if v > c {
            return Err(Violation::new(
                p.claim,
                format!(
                    "{}, N = {}: the measured {} = {} exceeds the constant proved in Coq ({}: {} = {})",
                    series.name,
                    r.n,
                    p.quantity,
                    v.render(),
                    p.theorem,
                    p.constant,
                    c.render()
                ),
            ));
        }
        let t = Tightness {
            scene: series.name.clone(),
            n: r.n,
            measured: v,
            constant: c,
        };
        if best.as_ref().is_none_or(|b| t.ratio() > b.ratio()) {
            best = Some(t);
        }
    }
    Ok(best)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(n: i64, d: i64) -> Q {
        Q::new(n.into(), d.into())
    }

    #[test]
    fn scene_data_by_hand() {
        let d = SceneData::of(&[q(0, 1), q(1, 2)], &[q(1, 1), q(-3, 1)], &q(2, 1));
        assert_eq!(d.m, q(3, 1));
        // x⁰_0 = 0 − 1/2 − 1: S = 1/2 + 3/2.
        assert_eq!(d.s, q(2, 1));
        assert_eq!(d.x0_sq, q(1, 8));
        assert_eq!(d.u0_sq, q(5, 1));
        assert_eq!((PROVED[3].value)(&d), q(14, 1));
        assert_eq!(decimal(&q(1, 8)), "0.1250");
        assert_eq!(decimal(&q(7, 3)), "2.3333");
    }

    #[test]
    fn every_row_names_a_claim_and_a_coq_theorem() {
        let claims = crate::claims::registry::<Q>();
        for p in PROVED {
            let c = claims.iter().find(|c| c.id == p.claim);
            let c = c.unwrap_or_else(|| panic!("{} is not a claim", p.claim));
            assert_eq!(p.statement == Statement::Corrected, c.correction.is_some());
            let (module, name) = p.theorem.split_once('.').unwrap();
            let path = format!(
                "{}/proofs/coq/theories/{module}.v",
                env!("CARGO_MANIFEST_DIR")
            );
            let text = std::fs::read_to_string(&path).unwrap();
            assert!(text.contains(&format!("Theorem {name} ")), "{}", p.theorem);
        }
    }

    /// On the measured table (N = 4 … 64) every measured constant holds,
    /// and the same measurement scaled past the constant fails: each
    /// comparison can fail, whatever the tightness.
    #[test]
    fn each_comparison_holds_and_can_fail() {
        let table = crate::claims::macro_data::table(64, "test").unwrap();
        for p in PROVED {
            let Some(Measure { of: measure, .. }) = p.measure else {
                continue;
            };
            let mut worst = Q::zero();
            for s in table.iter() {
                if let Some(t) = check(&p, measure, s).unwrap() {
                    worst = worst.max(t.ratio());
                }
            }
            assert!(worst > Q::zero(), "{}: never measured above 0", p.claim);
            // A mutant multiplying every measurement past the tightest one.
            let k = (worst.recip() * Q::from_i64(2)).ceil();
            let scaled: Vec<Series> = table
                .iter()
                .map(|s| Series {
                    name: s.name.clone(),
                    rows: s
                        .rows
                        .iter()
                        .map(|r| {
                            let mut r = r.clone();
                            r.data.m = r.data.m.clone() / &k;
                            r.data.s = r.data.s.clone() / &k;
                            r.data.x0_sq = r.data.x0_sq.clone() / &k;
                            r.data.u0_sq = r.data.u0_sq.clone() / &k;
                            r
                        })
                        .collect(),
                })
                .collect();
            assert!(
                scaled.iter().any(|s| check(&p, measure, s).is_err()),
                "{}",
                p.claim
            );
        }
    }

    /// A statement checked case by case carries its tightness too: once
    /// its cases hold, the ledger measures its quantity on the scaling
    /// table (the shipped scenes and the tightest random datum).
    #[test]
    fn case_checked_constants_report_their_tightness() {
        use crate::claims::ledger::{run_claim, Budget, Status};
        let budget = Budget {
            cases: 2,
            max_n: 4,
            scaling_max_n: 16,
            seed: 1,
        };
        let claims = crate::claims::registry::<Q>();
        let mut checked = 0;
        for p in PROVED {
            let claim = claims.iter().find(|c| c.id == p.claim).unwrap();
            let kind = claim.checker(p.statement).unwrap();
            if p.measure.is_none() || !matches!(kind, crate::claims::Kind::Case(_)) {
                continue;
            }
            checked += 1;
            let entry = run_claim(claim, budget);
            let outcome = match p.statement {
                Statement::Printed => &entry.outcome,
                Statement::Corrected => &entry.correction.as_ref().unwrap().1,
            };
            assert!(
                matches!(outcome.status, Status::Holds | Status::Identity(_)),
                "{}: {:?} {:?}",
                p.claim,
                outcome.status,
                outcome.witness
            );
            assert!(outcome.tightness.len() >= 3, "{}", p.claim);
            assert!(
                outcome.tightness.iter().all(|t| t.ratio() <= Q::one())
                    && outcome.tightness.iter().any(|t| t.ratio().is_positive()),
                "{}",
                p.claim
            );
        }
        assert_eq!(checked, 4);
    }

    /// The ledger's scaling checker of `eq:bound-UN-Linf` with every
    /// measured `‖U_N‖_∞ + ‖Ũ_N‖_∞` doubled (the budget's tamper hook):
    /// still bounded in N, but above the proved `2M`, so it fails.
    #[test]
    fn a_doubled_velocity_bound_fails_against_the_constant() {
        let budget = |tamper| crate::claims::scaling::Budget { max_n: 64, tamper };
        crate::claims::scaling::bound_un_linf(budget(None)).unwrap();
        let doubled: crate::claims::scaling::RowTamper =
            |r| r.u_sup = r.u_sup.clone() * Q::from_i64(2);
        let err = crate::claims::scaling::bound_un_linf(budget(Some(doubled))).unwrap_err();
        assert!(
            err.witness.contains("exceeds the constant proved in Coq"),
            "{err}"
        );
    }
}
