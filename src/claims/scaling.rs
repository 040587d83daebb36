//! Bounds "with C independent of N" and limits "as N → ∞", checked across N
//! on macroscopic data, exactly: the two shipped symmetric scenes and
//! [`macro_data::RANDOM_DATA`] random `[macro]` data admissible under `hyp:u0`, each at
//! `N = 4, 8, …, N_max` ([`macro_data`]: the exact histories come from the
//! integer event merge, and every measured quantity is a `BigRational`).
//!
//! The verdict on one datum is exact too. Let `N_mid` be the geometric
//! middle of the range (the largest N with `N² ≤ N_min · N_max`) and
//! `M = max_{N ≤ N_mid} q(N)` (the early values, so that a quantity that
//! is still 0 at the smallest N — no collision yet — is not mistaken for a
//! growing one):
//!
//! * every quantity is a norm: a **negative** value is a violation (the
//!   verdicts below compare squares, which cannot see a sign);
//! * a bound claimed independent of N is reported as a **counterexample**
//!   when `q(N_max)² · N_mid ≥ M² · N_max` and `q(N_max) ≠ 0`, i.e. when it
//!   grows at least like `√N` over the second half of the range;
//! * a quantity claimed to tend to 0 **holds** when
//!   `q(N_max)² · N_max ≤ M² · N_mid` (it decays at least like `1/√N`).
//!
//! A claim also fails when none of its data is non-trivial (every value 0):
//! a check that cannot fail is not run. The fitted log-log slope is
//! reported as an `f64` for reading only.

use num_rational::BigRational;

use super::macro_data::{self, Row, Series};
use super::proved::{self, Proved, Tightness};
use super::Violation;
use crate::rate::log_log_slope;
use crate::scalar::Scalar;

type Q = BigRational;

/// How far to go in N.
#[derive(Debug, Clone, Copy)]
pub struct Budget {
    /// Largest N (a power of two ≥ 8).
    pub max_n: usize,
    /// A deliberate corruption of every measured [`Row`] before the verdict
    /// (`tests/claims_selfcheck.rs` shows with it that every scaling checker
    /// can fail); `None` in every real run.
    #[doc(hidden)]
    pub tamper: Option<RowTamper>,
}

impl Budget {
    /// The budget up to `max_n`, untampered.
    pub fn up_to(max_n: usize) -> Self {
        Budget {
            max_n,
            tamper: None,
        }
    }
}

/// A hand-written mutant of the measured table: changes one [`Row`] (a
/// factor `1/N` forgotten, a norm left out, a sign lost).
#[doc(hidden)]
pub type RowTamper = fn(&mut Row);

/// The measured table of [`macro_data::table`], with the budget's
/// [`RowTamper`] applied to every row when there is one.
fn table(budget: Budget, id: &'static str) -> Result<std::sync::Arc<Vec<Series>>, Violation> {
    let t = macro_data::table(budget.max_n, id)?;
    let Some(f) = budget.tamper else {
        return Ok(t);
    };
    let mut t = (*t).clone();
    for s in &mut t {
        for r in &mut s.rows {
            f(r);
        }
    }
    Ok(std::sync::Arc::new(t))
}

/// What a scaling check measured on one datum (or on the random data as a
/// whole).
#[derive(Debug, Clone)]
pub struct ScalingReport {
    /// The datum.
    pub scene: String,
    /// `(N, q(N))`, exact.
    pub values: Vec<(usize, BigRational)>,
    /// Least-squares slope of `log q` against `log N` (reading aid).
    pub slope: f64,
    /// The (datum, N) pairs measured.
    pub cases: usize,
    /// The largest ratio measured / constant proved in Coq
    /// ([`proved::PROVED`]), for a quantity with a proved constant.
    pub tightness: Option<Tightness>,
}

impl ScalingReport {
    /// One line: the first and last values and the slope.
    pub fn summary(&self) -> String {
        let vals: Vec<String> = match (self.values.first(), self.values.last()) {
            (Some((n0, q0)), Some((n1, q1))) if self.values.len() > 1 => {
                vec![
                    format!("N={n0}: {}", short(q0)),
                    format!("N={n1}: {}", short(q1)),
                ]
            }
            _ => self
                .values
                .iter()
                .map(|(n, q)| format!("N={n}: {}", short(q)))
                .collect(),
        };
        let proved = self
            .tightness
            .as_ref()
            .map(|t| format!(", {}", t.summary()))
            .unwrap_or_default();
        format!(
            "{}: {} (log-log slope {:.3}{proved})",
            self.scene,
            vals.join(" … "),
            self.slope
        )
    }
}

fn short(q: &BigRational) -> String {
    let s = q.render();
    if s.len() <= 24 {
        s
    } else {
        format!("≈{:.6e}", q.to_f64_lossy())
    }
}

/// A scaling checker: the measurements, or the violation.
pub type ScalingCheck = fn(Budget) -> Result<Vec<ScalingReport>, Violation>;

/// The N values of a budget: `4, 8, …, max_n`.
pub fn ns(budget: Budget) -> Vec<usize> {
    macro_data::ns(budget.max_n)
}

fn slope(values: &[(usize, BigRational)]) -> f64 {
    let pts: Vec<(f64, f64)> = values
        .iter()
        .filter(|(_, q)| q.to_f64_lossy() > 0.0)
        .map(|(n, q)| (*n as f64, q.to_f64_lossy()))
        .collect();
    log_log_slope(&pts)
}

/// What a claim says of its quantity.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verdict {
    /// Bounded independently of N.
    Bounded,
    /// Tends to 0 as N → ∞.
    ToZero,
}

fn values_text(values: &[(usize, Q)]) -> String {
    values
        .iter()
        .map(|(n, q)| format!("N={n}: {}", short(q)))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The exact verdict on one datum's values (see the module documentation).
pub fn judge(
    id: &'static str,
    scene: &str,
    values: &[(usize, Q)],
    verdict: Verdict,
) -> Result<(), Violation> {
    if let Some((n, q)) = values.iter().find(|(_, q)| *q < Q::zero()) {
        return Err(Violation::new(
            id,
            format!(
                "{scene}: N = {n}: the norm is negative ({}): {}",
                q.render(),
                values_text(values)
            ),
        ));
    }
    let (Some((n0, _)), Some((n1, q1))) = (values.first(), values.last()) else {
        return Ok(());
    };
    if n1 <= n0 {
        return Ok(());
    }
    let n_mid = values
        .iter()
        .map(|(n, _)| *n)
        .filter(|n| n * n <= n0 * n1)
        .max()
        .unwrap_or(*n0);
    let m = values
        .iter()
        .filter(|(n, _)| *n <= n_mid)
        .map(|(_, q)| q.clone())
        .fold(Q::zero(), |a, b| if b > a { b } else { a });
    let sq = |q: &Q, n: usize| q.clone() * q * Q::from_usize(n);
    let (fails, why) = match verdict {
        Verdict::Bounded => (
            !q1.is_zero() && sq(q1, n_mid) >= sq(&m, *n1),
            "grows at least like √N: not bounded independently of N",
        ),
        Verdict::ToZero => (sq(q1, *n1) > sq(&m, n_mid), "does not decay like 1/√N"),
    };
    if fails {
        return Err(Violation::new(
            id,
            format!(
                "{scene}: {} (log-log slope {:.3}) — {why}",
                values_text(values),
                slope(values)
            ),
        ));
    }
    Ok(())
}

/// Runs `pick` on every datum of the table at `N = 4 … max_n` and judges
/// each series; the reports are the shipped scenes' and one for the random
/// data (its steepest datum).
fn run(
    id: &'static str,
    budget: Budget,
    verdict: Verdict,
    pick: impl Fn(&Row) -> Option<Q>,
) -> Result<Vec<ScalingReport>, Violation> {
    let table = table(budget, id)?;
    judge_all(id, &table, verdict, pick)
}

/// Judges every series of a given table (the scaling checks run it on the
/// measured table; unit tests feed wrong tables).
pub fn judge_all(
    id: &'static str,
    table: &[Series],
    verdict: Verdict,
    pick: impl Fn(&Row) -> Option<Q>,
) -> Result<Vec<ScalingReport>, Violation> {
    let mut reports = Vec::new();
    let mut nontrivial = 0usize;
    let mut cases = 0usize;
    let mut random: Vec<ScalingReport> = Vec::new();
    for (k, s) in table.iter().enumerate() {
        let values: Vec<(usize, Q)> = s
            .rows
            .iter()
            .filter_map(|r| pick(r).map(|q| (r.n, q)))
            .collect();
        judge(id, &s.name, &values, verdict)?;
        let tightness = match proved::for_checker(id) {
            Some(
                p @ proved::Proved {
                    measure: Some(proved::Measure { of: measure, .. }),
                    ..
                },
            ) => proved::check(p, *measure, s)?,
            _ => None,
        };
        cases += values.len();
        if values.len() >= 2 && values.iter().any(|(_, q)| !q.is_zero()) {
            nontrivial += 1;
        }
        let scene = datum_label(k, s);
        let report = ScalingReport {
            tightness: tightness.map(|t| Tightness {
                scene: scene.clone(),
                ..t
            }),
            scene,
            slope: slope(&values),
            cases: values.len(),
            values,
        };
        if k < 2 {
            reports.push(report);
        } else {
            random.push(report);
        }
    }
    if nontrivial == 0 {
        return Err(Violation::new(
            id,
            format!(
                "vacuous: on all {} data the quantity is 0 (or unmeasured) at every N",
                table.len()
            ),
        ));
    }
    let measured = random.iter().filter(|r| r.cases > 0).count();
    // The random data's tightest ratio (whichever datum it is on).
    let tightest = random
        .iter()
        .filter_map(|r| r.tightness.clone())
        .max_by(|a, b| a.ratio().cmp(&b.ratio()));
    if let Some(steep) = random
        .into_iter()
        .filter(|r| r.values.iter().any(|(_, q)| !q.is_zero()))
        .max_by(|a, b| a.slope.total_cmp(&b.slope))
    {
        reports.push(ScalingReport {
            scene: format!("{measured} random data measured, steepest {}", steep.scene),
            tightness: tightest,
            ..steep
        });
    }
    if let Some(first) = reports.first_mut() {
        first.scene = format!(
            "{} data non-trivial of {}; {}",
            nontrivial,
            table.len(),
            first.scene
        );
    }
    if let Some(r) = reports.first_mut() {
        r.cases = cases;
    }
    for r in reports.iter_mut().skip(1) {
        r.cases = 0;
    }
    Ok(reports)
}

/// How the reports name the `k`-th datum of the table: the two shipped
/// scenes by name, the random data by number.
fn datum_label(k: usize, s: &Series) -> String {
    if k < 2 {
        s.name.clone()
    } else {
        format!("random #{}", k - 1)
    }
}

/// The tightness of a proved constant whose quantity no scaling checker
/// judges (a statement checked case by case): measured on the table at
/// `N = 4 … max_n`, the shipped scenes' and the random data's tightest, as
/// [`judge_all`] reports them; the first measurement above the constant
/// is the violation.
pub fn proved_tightness(p: &Proved, max_n: usize) -> Result<Vec<Tightness>, Violation> {
    let Some(proved::Measure { of: measure, .. }) = p.measure else {
        return Ok(Vec::new());
    };
    let table = table(Budget::up_to(max_n), p.claim)?;
    let mut out = Vec::new();
    let mut tightest: Option<Tightness> = None;
    for (k, s) in table.iter().enumerate() {
        let Some(t) = proved::check(p, measure, s)? else {
            continue;
        };
        let t = Tightness {
            scene: datum_label(k, s),
            ..t
        };
        if k < 2 {
            out.push(t);
        } else if tightest.as_ref().is_none_or(|b| t.ratio() > b.ratio()) {
            tightest = Some(t);
        }
    }
    out.extend(tightest);
    Ok(out)
}

/// `eq:sup-micro-u-L#N-lambda`: `sup_{t ≤ T} sup_i N|λ_i(t)| ≤ C'` with C'
/// independent of N.
pub fn n_lambda(budget: Budget) -> Result<Vec<ScalingReport>, Violation> {
    run("eq:sup-micro-u-L#N-lambda", budget, Verdict::Bounded, |r| {
        Some(r.lambda_sup.clone() * Q::from_usize(r.n))
    })
}

/// Corrected: `sup_{t ≤ T} sup_i |λ_i(t)| ≤ C'` (without the factor N).
pub fn lambda_sup(budget: Budget) -> Result<Vec<ScalingReport>, Violation> {
    run(
        "eq:sup-micro-u-L#N-lambda (corrected)",
        budget,
        Verdict::Bounded,
        |r| Some(r.lambda_sup.clone()),
    )
}

/// `prop:pressure-bound`: `‖P̃_N‖_{M(0,T; L¹(0,1))} ≤ C`: the total
/// variation `Σ_k (1/N) Σ_i |[λ_i]_{t_k}|` over collisions `t_k ≤ T`. Sign
/// aware: a negative jump (`P̃_N ≥ 0` fails) makes the signed mass differ
/// from the norm, and the checker reports it.
pub fn pressure_mass(budget: Budget) -> Result<Vec<ScalingReport>, Violation> {
    const ID: &str = "prop:pressure-bound";
    let table = table(budget, ID)?;
    pressure_on(&table)
}

/// [`pressure_mass`] on a given table.
pub fn pressure_on(table: &[Series]) -> Result<Vec<ScalingReport>, Violation> {
    const ID: &str = "prop:pressure-bound";
    for s in table {
        if let Some(r) = s.rows.iter().find(|r| r.pressure_signed != r.pressure_abs) {
            return Err(Violation::new(
                ID,
                format!(
                    "{}, N = {}: P̃_N is not a non-negative measure: Σ(1/N)[λ_i] = {} but Σ(1/N)|[λ_i]| = {}",
                    s.name,
                    r.n,
                    r.pressure_signed.render(),
                    r.pressure_abs.render()
                ),
            ));
        }
    }
    judge_all(ID, table, Verdict::Bounded, |r| {
        Some(r.pressure_abs.clone())
    })
}

/// `prop:L2-micro`: the seven norms of the statement, `sup_t` of the sum of
/// their squares `‖X_N‖² + ‖X̃_N‖² + ‖∂_t X_N‖² + ‖∂_t X̃_N‖² + ‖Λ_N‖² +
/// ‖Λ̃_N‖² + ‖∂_w Λ̃_N‖²` in `L²(0,1)` ([`Row::l2`]; bounded iff the sum of
/// the norms is, within a factor √7).
pub fn l2_bounds(budget: Budget) -> Result<Vec<ScalingReport>, Violation> {
    run("prop:L2-micro", budget, Verdict::Bounded, |r| {
        Some(r.l2.clone())
    })
}

/// `prop:2ndorder-LagrPDE#PN-minus-tPN`: `|⟨P_N − P̃_N, Ψ⟩| ≤ (C/N)
/// ‖∂_t Ψ‖_{L¹(0,T; L^∞(0,1))}`, for `Ψ = ψ(t)w`: `⟨P_N − P̃_N, Ψ⟩ =
/// −∫ψ'(t) ∫(Λ_N − Λ̃_N) w dw dt`, so `C ≥ N sup_t |∫(Λ_N − Λ̃_N) w dw|`
/// ([`Row::pn_gap`]) must stay bounded.
pub fn pn_minus_tpn(budget: Budget) -> Result<Vec<ScalingReport>, Violation> {
    run(
        "prop:2ndorder-LagrPDE#PN-minus-tPN",
        budget,
        Verdict::Bounded,
        |r| Some(r.pn_gap.clone()),
    )
}

/// `pwUN-L1`: `sup_{t ∈ [α, T]} ‖∂_w Ũ_N(t)‖_{L¹} ≤ C_α`, at `α = T/2`
/// (`= Σ|u_i − u_{i−1}|`, the total variation of `u`); only data on which
/// it is not 0 count as non-trivial.
pub fn tv_u(budget: Budget) -> Result<Vec<ScalingReport>, Violation> {
    run("pwUN-L1#independent-of-N", budget, Verdict::Bounded, |r| {
        Some(r.tv_late.clone())
    })
}

/// `eq:bound-UN-Linf`: `‖U_N‖_{L^∞} + ‖Ũ_N‖_{L^∞} ≤ C` (`= 2 sup_t max_i
/// |u_i(t)|`: `Ũ_N` interpolates the `u_i`, with `u_0 = u_1`).
pub fn bound_un_linf(budget: Budget) -> Result<Vec<ScalingReport>, Violation> {
    run("eq:bound-UN-Linf", budget, Verdict::Bounded, |r| {
        Some(r.u_sup.clone())
    })
}

/// `thm:main#discretisation` (i): `‖X⁰_N − X⁰‖²_{L²(0,1)} → 0` for the
/// quantile sample of [`crate::quantile::MacroDatum::quantiles`], against
/// `X⁰` as the continuum profile at `t = 0` (exact: affine pieces).
pub fn discretisation(budget: Budget) -> Result<Vec<ScalingReport>, Violation> {
    run("thm:main#discretisation", budget, Verdict::ToZero, |r| {
        r.disc_x.clone()
    })
}

/// `thm:main#discretisation-U`: `‖U⁰_N − U⁰‖²_{L²(0,1)} → 0` for the printed
/// quantile sample `u⁰_i = U⁰(i/N)`.
pub fn discretisation_u(budget: Budget) -> Result<Vec<ScalingReport>, Violation> {
    run("thm:main#discretisation-U", budget, Verdict::ToZero, |r| {
        r.disc_u.clone()
    })
}

/// `cond:Linfty`: `x⁰_N − x⁰_0 + sup_i |u⁰_i| ≤ C'_0` with `C'_0`
/// independent of N, for the quantile sample (the smallest such constant at
/// each N, with the artificial particle `x⁰_0 = x⁰_1 − 1/N − δ`, `δ = 1`).
pub fn cond_linfty(budget: Budget) -> Result<Vec<ScalingReport>, Violation> {
    cond_linfty_on(&table(budget, "cond:Linfty")?)
}

/// [`cond_linfty`] on a given table.
pub fn cond_linfty_on(table: &[Series]) -> Result<Vec<ScalingReport>, Violation> {
    judge_all("cond:Linfty", table, Verdict::Bounded, |r| {
        Some(r.c0_prime.clone())
    })
}

/// The proposition "Eulerian formulation", momentum equation, for the
/// particles: `max_φ |R_mom^N(φ)| → 0` (`O(1/N)` by the identity of
/// [`crate::limit::eulerian`]) over the test family of the datum, up to
/// `T`.
pub fn eulerian_momentum(budget: Budget) -> Result<Vec<ScalingReport>, Violation> {
    const ID: &str = "prop:eulerian-formulation#momentum";
    eulerian_momentum_on(&table(budget, ID)?)
}

/// [`eulerian_momentum`] on a given table.
pub fn eulerian_momentum_on(table: &[Series]) -> Result<Vec<ScalingReport>, Violation> {
    judge_all(
        "prop:eulerian-formulation#momentum",
        table,
        Verdict::ToZero,
        |r| Some(r.momentum.clone()),
    )
}

/// The mass equation of the proposition "Eulerian formulation" for the
/// interpolated density `ρ̃_N = X̃_N#L¹` transported by the paper's
/// velocity `U_N`: `max_φ |R_N(φ)| → 0` ([`Row::mass_interpolated`], see
/// [`crate::limit::eulerian::interpolated_mass_residuals`]), measured for
/// `N ≤` [`macro_data::MASS_INTERPOLATED_MAX_N`].
pub fn eulerian_mass_interpolated(budget: Budget) -> Result<Vec<ScalingReport>, Violation> {
    run(
        "prop:eulerian-formulation#mass-interpolated",
        budget,
        Verdict::ToZero,
        |r| r.mass_interpolated.clone(),
    )
}

/// `eq:Lagr-1#particle-multiplier`: the continuum `Λ` against the
/// particles' own multipliers, `max_t max_i |λ_i(t) − Λ(t, i/N)| → 0`
/// ([`Row::lambda_nodes`]), at the comparison times with a rational
/// profile.
pub fn lagr1_particle_multiplier(budget: Budget) -> Result<Vec<ScalingReport>, Violation> {
    run(
        "eq:Lagr-1#particle-multiplier",
        budget,
        Verdict::ToZero,
        |r| r.lambda_nodes.clone(),
    )
}

/// `prop:cvg1` as printed: `X̃_N → X` in `C([0,T] × [0,1])`, measured at
/// `t = 0` on the whole `[0, 1]`: `sup_{w ∈ [0,1]} |X̃_N(0,w) − X⁰(w)|`
/// (the artificial particle's cell `[0, 1/N]` included).
pub fn cvg1_uniform(budget: Budget) -> Result<Vec<ScalingReport>, Violation> {
    run("prop:cvg1", budget, Verdict::ToZero, |r| {
        Some(r.uniform_x0.clone())
    })
}

/// `prop:cvg1` corrected: `sup_t ‖X_N(t) − X(t)‖²_{L²} → 0` and the weak-*
/// test `max_φ |∫(Λ_N(t) − Λ(t))φ| → 0` (`φ ∈ {1, w}`), at `t = T/4, T/2,
/// 3T/4, T`, against the exact continuum solution (data whose profiles
/// are rational there).
pub fn cvg1_measured(budget: Budget) -> Result<Vec<ScalingReport>, Violation> {
    const ID: &str = "prop:cvg1 (corrected)";
    let mut x = run(ID, budget, Verdict::ToZero, |r| r.cvg_x.clone())?;
    let l = run(ID, budget, Verdict::ToZero, |r| r.cvg_lambda.clone())?;
    for r in &mut x {
        r.scene = format!("‖X_N − X‖²: {}", r.scene);
    }
    x.extend(l.into_iter().map(|mut r| {
        r.scene = format!("|⟨Λ_N − Λ, φ⟩|: {}", r.scene);
        r
    }));
    Ok(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(n: i64, d: i64) -> Q {
        Q::new(n.into(), d.into())
    }

    fn series(name: &str, values: &[(usize, Q)]) -> Vec<(usize, Q)> {
        let _ = name;
        values.to_vec()
    }

    #[test]
    fn a_growing_bound_is_caught() {
        let v = series("g", &[(4, q(1, 1)), (64, q(4, 1)), (1024, q(16, 1))]);
        assert!(judge("t", "g", &v, Verdict::Bounded).is_err());
        let flat = series("f", &[(4, q(1, 1)), (64, q(2, 1)), (1024, q(2, 1))]);
        assert!(judge("t", "f", &flat, Verdict::Bounded).is_ok());
    }

    #[test]
    fn a_non_decaying_limit_is_caught() {
        let v = series("c", &[(4, q(1, 2)), (64, q(1, 2)), (1024, q(1, 2))]);
        assert!(judge("t", "c", &v, Verdict::ToZero).is_err());
        let ok = series("d", &[(4, q(1, 1)), (64, q(1, 16)), (1024, q(1, 256))]);
        assert!(judge("t", "d", &ok, Verdict::ToZero).is_ok());
    }

    #[test]
    fn a_negative_norm_is_caught() {
        // Squares cannot see it: (−16)² grows exactly like 16².
        let v = series("n", &[(4, q(1, 1)), (64, q(-1, 1)), (1024, q(1, 1))]);
        assert!(judge("t", "n", &v, Verdict::Bounded).is_err());
    }

    fn row(n: usize, v: Q) -> Row {
        Row {
            n,
            lambda_sup: v.clone(),
            pressure_abs: v.clone(),
            pressure_signed: v.clone(),
            l2: v.clone(),
            tv_late: v.clone(),
            u_sup: v.clone(),
            disc_x: Some(v.clone()),
            disc_u: Some(v.clone()),
            uniform_x0: v.clone(),
            cvg_x: Some(v.clone()),
            cvg_lambda: Some(v.clone()),
            lambda_nodes: Some(v.clone()),
            pn_gap: v.clone(),
            c0_prime: v.clone(),
            momentum: v.clone(),
            mass_interpolated: Some(v.clone()),
            l2_xu: v.clone(),
            increment_sup: v.clone(),
            width_sup: v.clone(),
            data: super::super::proved::SceneData::of(
                std::slice::from_ref(&v),
                std::slice::from_ref(&v),
                &Q::one(),
            ),
        }
    }

    #[test]
    fn an_all_zero_table_is_vacuous() {
        let t = vec![Series {
            name: "zero".into(),
            rows: vec![row(4, Q::zero()), row(8, Q::zero())],
        }];
        assert!(judge_all("t", &t, Verdict::Bounded, |r| Some(r.tv_late.clone())).is_err());
    }

    /// The measured table at N = 4 … 64 with one column scaled by N (a
    /// plausible bug: a factor 1/N forgotten).
    fn scaled(f: fn(&mut Row, Q)) -> Vec<Series> {
        let mut t = (*macro_data::table(64, "test").unwrap()).clone();
        for s in &mut t {
            for r in &mut s.rows {
                let n = Q::from_usize(r.n);
                f(r, n);
            }
        }
        t
    }

    #[test]
    fn cond_linfty_rejects_an_unscaled_sample() {
        cond_linfty_on(&macro_data::table(64, "test").unwrap()).unwrap();
        // Positions sampled at i instead of i/N: the spread grows like N.
        let t = scaled(|r, n| r.c0_prime = r.c0_prime.clone() * n);
        assert!(cond_linfty_on(&t).is_err());
    }

    #[test]
    fn the_momentum_residual_must_decay() {
        eulerian_momentum_on(&macro_data::table(64, "test").unwrap()).unwrap();
        // The pressure atoms not divided by N: R_mom^N no longer → 0.
        let t = scaled(|r, n| r.momentum = r.momentum.clone() * n);
        assert!(eulerian_momentum_on(&t).is_err());
    }

    #[test]
    fn a_negative_pressure_jump_is_caught() {
        let mut r = row(8, q(1, 2));
        r.pressure_signed = q(1, 4);
        let t = vec![Series {
            name: "neg".into(),
            rows: vec![row(4, q(1, 2)), r],
        }];
        assert!(pressure_on(&t).is_err());
    }
}
