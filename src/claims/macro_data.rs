//! The macroscopic data the scaling claims ([`super::scaling`]) run on, and
//! what is measured on each of them at each N, once.
//!
//! The data are the two shipped symmetric scenes (`appendix-c-two-blocks`,
//! `riemann-compression`) and [`RANDOM_DATA`] random `[macro]` data
//! admissible under `hyp:u0` ([`crate::generate::macro_datum`], fixed seed,
//! horizon `T = 1`): blocks of density exactly 1 next to dilute ones,
//! vacuum gaps, velocity jumps at block boundaries, affine velocities. Each
//! is sampled at `N = 4, 8, …, N_max` and its exact sticky history computed
//! by the integer event merge ([`crate::fast::merge::trajectory`], equal to
//! the generic `BigRational` one: the oracle battery checks it); every
//! quantity of a [`Row`] is then exact.
//!
//! The sampling is the paper's `x⁰_i = X⁰(i/N)`, `u⁰_i = U⁰(i/N)`; where
//! it puts two touching particles on a collision course (the corrected
//! `thm:main#sampling-contacts`), both take the congested side's value of
//! `U⁰` ([`admissible_sample`]).

use std::sync::{Arc, Mutex};

use num_rational::BigRational;

use super::macro_measures::{
    abs, l2_sq, lambda_gap_moment, lambda_moment, lambda_n_moment, lambda_node_gap, max, pressure,
    seven_norms, uniform_x0, Sum,
};
use super::proved::SceneData;
use super::Violation;
use crate::generate::{macro_datum, SplitMix64};
use crate::initial::InitialData;
use crate::limit::continuum::{Continuum, Profile};
use crate::limit::eulerian::{
    interpolated_mass_residuals, particle_momentum_residuals, support_window, test_family,
    TestFunction,
};
use crate::quantile::MacroDatum;
use crate::scalar::Scalar;
use crate::scene::{self, SceneKind};
use crate::trajectory::Trajectory;

type Q = BigRational;

/// The largest N at which [`Row::mass_interpolated`] is measured (its
/// cost is `O(N)` exact polynomial integrals per test function, on
/// collision times whose denominators grow with N; timings in
/// `docs/journal.md`).
pub const MASS_INTERPOLATED_MAX_N: usize = 512;

/// Random macroscopic data the scaling claims run on (besides the two
/// shipped scenes).
pub const RANDOM_DATA: usize = 16;

/// The shipped scenes, by name.
const SCENES: [&str; 2] = ["appendix-c-two-blocks", "riemann-compression"];

/// One macroscopic datum with its horizon and its exact continuum profiles
/// at the comparison times `T/4, T/2, 3T/4, T` (`None` where the profile is
/// irrational).
#[derive(Debug, Clone)]
pub struct MacroCase {
    /// The scene name, or the datum as the `blocks` of a `[macro]` scene.
    pub name: String,
    /// The datum.
    pub datum: MacroDatum,
    /// The horizon `T`.
    pub t_end: Q,
    /// `(t, X(t), Λ(t))` of the continuum solution at the comparison times.
    pub profiles: Vec<(Q, Option<Profile<Q>>)>,
    /// `X⁰`, `U⁰` as the continuum profile at `t = 0`.
    pub initial: Option<Profile<Q>>,
    /// The test functions `φ = B(t)Q(x)` of the weak residuals
    /// ([`test_family`] on the datum's [`support_window`]).
    pub tests: Vec<TestFunction<Q>>,
}

/// What is measured on one datum at one N (every value exact).
#[derive(Debug, Clone)]
pub struct Row {
    /// N.
    pub n: usize,
    /// `sup_{t ≤ T} sup_i |λ_i(t)|` over the probe times.
    pub lambda_sup: Q,
    /// `Σ_{t_k ≤ T} (1/N) Σ_i |[λ_i]_{t_k}|`: the total variation of the
    /// pressure measure, `‖P̃_N‖_{M(0,T; L¹)}`.
    pub pressure_abs: Q,
    /// The same sum without absolute values.
    pub pressure_signed: Q,
    /// `sup_t` of the sum of the squared `L²(0,1)` norms of the seven
    /// functions of `prop:L2-micro`: `X_N, X̃_N, ∂_t X_N, ∂_t X̃_N, Λ_N, Λ̃_N,
    /// ∂_w Λ̃_N` (`seven_norms`).
    pub l2: Q,
    /// `sup_{t ∈ [T/2, T]} Σ_i |u_i − u_{i−1}|`.
    pub tv_late: Q,
    /// `sup_t (‖U_N‖_∞ + ‖Ũ_N‖_∞) = 2 sup_t max_i |u_i(t)|`.
    pub u_sup: Q,
    /// `‖X⁰_N − X⁰‖²_{L²}` of the printed quantile sample.
    pub disc_x: Option<Q>,
    /// `‖U⁰_N − U⁰‖²_{L²}` of the printed quantile sample.
    pub disc_u: Option<Q>,
    /// `sup_w |X̃_N(0, w) − X⁰(w)|` over `w ∈ [0, 1]` (the artificial
    /// particle's cell included).
    pub uniform_x0: Q,
    /// `max ‖X_N(t) − X(t)‖²_{L²}` over the comparison times with a
    /// rational profile.
    pub cvg_x: Option<Q>,
    /// `max |∫_0^1 (Λ_N(t) − Λ(t)) φ|` over the comparison times with a
    /// rational profile and `φ ∈ {1, w}`.
    pub cvg_lambda: Option<Q>,
    /// `max_i |λ_i(t) − Λ(t, i/N)|`, the particles' multipliers against the
    /// continuum `Λ` at the nodes `w = i/N` (`λ_N = (1/N)Σ(u⁰_j − u_j)`),
    /// maximised over the comparison times with a rational profile
    /// (`lambda_node_gap`).
    pub lambda_nodes: Option<Q>,
    /// `N · sup_t |∫_0^1 (Λ_N − Λ̃_N)(t,w) w dw|` over the probe times: the
    /// factor of `‖∂_t Ψ‖` in `|⟨P_N − P̃_N, Ψ⟩| ≤ (C/N)‖∂_t Ψ‖` for
    /// `Ψ = ψ(t)w` (`lambda_gap_moment`).
    pub pn_gap: Q,
    /// `C'_0 = (x⁰_N − x⁰_0) + sup_i |u⁰_i|`, the smallest constant of
    /// `cond:Linfty` for the sample (artificial particle `x⁰_0 = x⁰_1 − 1/N − δ`,
    /// `δ = 1`, as in `prop:Linf-micro`).
    pub c0_prime: Q,
    /// `max_φ |R_mom^N(φ)|` over [`MacroCase::tests`] (the particles' weak
    /// momentum residual, [`particle_momentum_residuals`]), plus the bound on
    /// its dyadic accumulation error: an upper bound of the exact value.
    pub momentum: Q,
    /// `max_φ |R_N(φ)|` over [`MacroCase::tests`], `R_N(φ) = ∫∫ ρ̃_N ∂_t φ +
    /// m̃_N ∂_x φ` with `ρ̃_N = X̃_N#L¹`, `m̃_N = X̃_N#(U_N L¹)`
    /// ([`interpolated_mass_residuals`]), plus the bound on its dyadic
    /// accumulation error; `None` above [`MASS_INTERPOLATED_MAX_N`].
    pub mass_interpolated: Option<Q>,
    /// `sup_t (‖X_N(t)‖² + ‖∂_t X_N(t)‖²)` in `L²(0,1)`: `(1/N) Σ_i (x_i² +
    /// u_i²)`, the two norms of `prop:L2-micro` with a constant proved in Coq.
    pub l2_xu: Q,
    /// `sup_t max_{i=1…N} N|λ_i(t) − λ_{i−1}(t)|` over the probe times
    /// (`λ_0 = 0`): the increments of `eq:sup-micro-u-L`, and `N · sup_w
    /// |Λ̃_N − Λ_N|` of `eq:diffLambda_N` (on cell `i` the affine `Λ̃_N`
    /// runs from `λ_{i−1}` to `λ_i` and `Λ_N` is one of them).
    pub increment_sup: Q,
    /// `sup_t (x_N(t) − x_0(t))` over the probe times, the artificial
    /// particle `x_0 = x_1 − 1/N − δ`, `δ = 1` (`df:x0`): `∫_0^1 |∂_w X̃_N|`
    /// of `eq:BV_XN`, and twice `N ‖X̃_N − X_N‖_{L¹}` of `prop:cvg1#XN-L1`.
    pub width_sup: Q,
    /// The datum's data at this N, for the proved constants.
    pub data: SceneData,
}

/// One datum measured across N.
#[derive(Debug, Clone)]
pub struct Series {
    /// The datum's name.
    pub name: String,
    /// One row per N, increasing.
    pub rows: Vec<Row>,
}

fn q(n: i64, d: i64) -> Q {
    Q::new(n.into(), d.into())
}

/// The data: the shipped scenes, then the random ones (fewest blocks
/// first).
pub fn cases(id: &'static str) -> Result<Vec<MacroCase>, Violation> {
    let mut out = Vec::new();
    for name in SCENES {
        let text = scene::shipped(name)
            .ok_or_else(|| Violation::new(id, format!("{name} is not a shipped scene")))?;
        let s = scene::parse(text).map_err(|e| Violation::new(id, format!("{name}: {e}")))?;
        let t_end = s.t_end.clone().unwrap_or_else(Q::one);
        let SceneKind::Macro { datum, .. } = s.kind else {
            return Err(Violation::new(id, format!("{name} is not a macro scene")));
        };
        out.push(case(name.to_string(), datum, t_end));
    }
    let mut rng = SplitMix64::new(0x005C_A1E5);
    let mut random: Vec<MacroDatum> = (0..RANDOM_DATA)
        .map(|_| macro_datum(&rng.bytes(40)))
        .collect();
    random.sort_by_key(|d| d.blocks().len());
    for datum in random {
        out.push(case(
            super::sampling::render_blocks(&datum),
            datum,
            Q::one(),
        ));
    }
    Ok(out)
}

fn case(name: String, datum: MacroDatum, t_end: Q) -> MacroCase {
    let c = Continuum::new(&datum);
    let profiles = (1..=4)
        .map(|k| {
            let t = t_end.clone() * q(k, 4);
            let p = c.profile(&t).ok().and_then(|p| p.to_rational());
            (t, p)
        })
        .collect();
    let initial = c.profile(&Q::zero()).ok().and_then(|p| p.to_rational());
    let (center, scale) = support_window(&c, &t_end);
    let tests = test_family(&t_end, &center, &scale);
    MacroCase {
        name,
        datum,
        t_end,
        profiles,
        initial,
        tests,
    }
}

/// The quantile sample `x⁰_i = X⁰(i/N)`, `u⁰_i = U⁰(i/N)`, radius
/// `1/(2N)`, except that two touching particles (`x⁰_{i+1} − x⁰_i = 1/N`)
/// both take `U⁰` at the middle of the congested interval between them,
/// the congested side's value (corrected `thm:main#sampling-contacts`).
pub fn admissible_sample(d: &MacroDatum, n: usize) -> Result<InitialData<Q>, String> {
    let (x, mut u) = d.quantiles(n).map_err(|e| e.to_string())?;
    let nn = Q::from_usize(n);
    let inv = nn.recip();
    for i in 0..n.saturating_sub(1) {
        if x[i + 1].clone() - &x[i] == inv {
            // Particles i+1, i+2 (1-based) at w = (i+1)/N, (i+2)/N.
            let mid = d.u0(&(Q::from_usize(2 * i + 3) / (Q::from_i64(2) * &nn)));
            u[i] = mid.clone();
            u[i + 1] = mid;
        }
    }
    InitialData::new(inv / Q::from_i64(2), x, u).map_err(|e| e.to_string())
}

/// The N values `4, 8, …, max_n` (at least `4, 8`).
pub fn ns(max_n: usize) -> Vec<usize> {
    let mut v = Vec::new();
    let mut n = 4;
    while n <= max_n.max(8) {
        v.push(n);
        n *= 2;
    }
    v
}

fn row(c: &MacroCase, n: usize, id: &'static str) -> Result<Row, Violation> {
    let data = admissible_sample(&c.datum, n)
        .map_err(|e| Violation::new(id, format!("{}, N = {n}: {e}", c.name)))?;
    row_of(c, &crate::fast::merge::trajectory(&data), id)
}

/// The [`Row`] of one datum at one N from its computed history `traj`
/// (unit tests pass a corrupted history here, to show the scaling
/// checkers reject it).
fn row_of(c: &MacroCase, traj: &Trajectory<Q>, id: &'static str) -> Result<Row, Violation> {
    let data = traj.data();
    let n = data.n();
    let fail = |e: String| Violation::new(id, format!("{}, N = {n}: {e}", c.name));
    let u0 = data.velocities().to_vec();
    let nn = Q::from_usize(n);
    let alpha = c.t_end.clone() / Q::from_i64(2);
    let (mut lambda_sup, mut l2, mut tv_late, mut u_sup) =
        (Q::zero(), Q::zero(), Q::zero(), Q::zero());
    let mut cvg_x: Option<Q> = None;
    let mut cvg_lambda: Option<Q> = None;
    let mut lambda_nodes: Option<Q> = None;
    let mut pn_gap = Q::zero();
    let mut l2_xu = Q::zero();
    let (mut increment_sup, mut width_sup) = (Q::zero(), Q::zero());
    // x_N − x_0 = x_N − x_1 + 1/N + δ, δ = 1 (df:x0).
    let artificial = nn.recip() + Q::one();
    // t = kT/4, k = 0 … 4: the comparison times and 0.
    let probes = std::iter::once((Q::zero(), None))
        .chain(c.profiles.iter().map(|(t, p)| (t.clone(), p.as_ref())));
    for (t, profile) in probes {
        let s = traj.at(&t).map_err(|e| fail(e.to_string()))?;
        // λ_1 … λ_{N−1} as the state has them; λ_N = (1/N) Σ (u⁰_j − u_j).
        let mut l = s.multipliers.clone();
        let mut ln = Sum::default();
        for (a, b) in u0.iter().zip(&s.velocities) {
            ln.add(a.clone() - b);
        }
        l.push(ln.total() / &nn);
        for v in &l {
            lambda_sup = max(lambda_sup, abs(v.clone()));
        }
        for v in &s.velocities {
            u_sup = max(u_sup, abs(v.clone()) * Q::from_i64(2));
        }
        let mut previous = Q::zero();
        for v in &l {
            increment_sup = max(increment_sup, abs(v.clone() - &previous) * &nn);
            previous = v.clone();
        }
        if let (Some(first), Some(last)) = (s.positions.first(), s.positions.last()) {
            width_sup = max(width_sup, last.clone() - first + &artificial);
        }
        l2 = max(l2, seven_norms(&s.positions, &s.velocities, &l));
        let mut xu = Sum::default();
        for v in s.positions.iter().chain(&s.velocities) {
            xu.add_square(v);
        }
        l2_xu = max(l2_xu, xu.total() / &nn);
        pn_gap = max(pn_gap, abs(lambda_gap_moment(&l)) * &nn);
        if t >= alpha {
            let mut tv = Sum::default();
            for w in s.velocities.windows(2) {
                tv.add(abs(w[1].clone() - &w[0]));
            }
            tv_late = max(tv_late, tv.total());
        }
        if let Some(p) = profile {
            let dx = l2_sq(&s.positions, p, |s| &s.x);
            cvg_x = Some(max(cvg_x.unwrap_or_else(Q::zero), dx));
            let gap = lambda_node_gap(&l, p);
            lambda_nodes = Some(max(lambda_nodes.unwrap_or_else(Q::zero), gap));
            for k in 0..2 {
                let d = abs(lambda_n_moment(&l, k) - lambda_moment(p, k));
                cvg_lambda = Some(max(cvg_lambda.unwrap_or_else(Q::zero), d));
            }
        }
    }
    let (pressure_abs, pressure_signed) = pressure(traj, &c.t_end);
    // cond:Linfty: C'_0 = S + M, S = x⁰_N − x⁰_0 = x⁰_N − x⁰_1 + 1/N + δ (δ = 1).
    let scene_data = SceneData::of(data.positions(), &u0, &c.t_end);
    let c0_prime = scene_data.s.clone() + &scene_data.m;
    let residuals =
        particle_momentum_residuals(traj, &c.tests, &c.t_end).map_err(|e| fail(e.to_string()))?;
    let rounding = Q::from_float(residuals.rounding_bound)
        .ok_or_else(|| fail("rounding bound not finite".into()))?;
    let momentum = residuals
        .values
        .into_iter()
        .fold(Q::zero(), |m, v| max(m, abs(v)))
        + rounding;
    let mass_interpolated = if n <= MASS_INTERPOLATED_MAX_N {
        let r = interpolated_mass_residuals(traj, &c.tests, &c.t_end)
            .map_err(|e| fail(e.to_string()))?;
        let rounding = Q::from_float(r.rounding_bound)
            .ok_or_else(|| fail("rounding bound not finite".into()))?;
        Some(r.values.into_iter().fold(Q::zero(), |m, v| max(m, abs(v))) + rounding)
    } else {
        None
    };
    let (qx, qu) = c.datum.quantiles(n).map_err(|e| fail(e.to_string()))?;
    let (disc_x, disc_u) = match &c.initial {
        Some(p) => (Some(l2_sq(&qx, p, |s| &s.x)), Some(l2_sq(&qu, p, |s| &s.u))),
        None => (None, None),
    };
    Ok(Row {
        n,
        lambda_sup,
        pressure_abs,
        pressure_signed,
        l2,
        tv_late,
        u_sup,
        disc_x,
        disc_u,
        uniform_x0: uniform_x0(&c.datum, &qx),
        cvg_x,
        cvg_lambda,
        lambda_nodes,
        pn_gap,
        c0_prime,
        momentum,
        mass_interpolated,
        l2_xu,
        increment_sup,
        width_sup,
        data: scene_data,
    })
}

type Cache = Mutex<Vec<(usize, Arc<Vec<Series>>)>>;
static TABLE: Cache = Mutex::new(Vec::new());

/// Every datum measured at `N = 4 … max_n` (computed once per `max_n` and
/// kept: every scaling claim reads the same table).
pub fn table(max_n: usize, id: &'static str) -> Result<Arc<Vec<Series>>, Violation> {
    if let Ok(cache) = TABLE.lock() {
        if let Some((_, t)) = cache.iter().find(|(m, _)| *m == max_n) {
            return Ok(t.clone());
        }
    }
    let mut out = Vec::new();
    for c in cases(id)? {
        let rows = ns(max_n)
            .into_iter()
            .map(|n| row(&c, n, id))
            .collect::<Result<Vec<_>, _>>()?;
        out.push(Series { name: c.name, rows });
    }
    let t = Arc::new(out);
    if let Ok(mut cache) = TABLE.lock() {
        cache.push((max_n, t.clone()));
    }
    Ok(t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pressure_matches_the_materialised_jumps() {
        let c = &cases("test").unwrap()[3];
        let data = admissible_sample(&c.datum, 32).unwrap();
        let traj = crate::fast::merge::trajectory(&data);
        let (ab, si) = pressure(&traj, &c.t_end);
        let nn = Q::from_usize(32);
        let jumps: Vec<Q> = traj
            .impulses()
            .iter()
            .filter(|i| i.t <= c.t_end)
            .flat_map(|i| i.jumps())
            .collect();
        assert_eq!(si, jumps.iter().fold(Q::zero(), |x, y| x + y) / &nn);
        assert_eq!(
            ab,
            jumps.iter().fold(Q::zero(), |x, y| x + abs(y.clone())) / nn
        );
    }

    /// `prop:pressure-bound` (sign-aware): a history whose collisions list
    /// their parts' velocities right to left (a plausible bug of the event
    /// merge) has negative pressure jumps; measured through the same
    /// [`row_of`] as the true history, the scaling checker rejects it
    /// (a check of `Σ|[λ_i]|` alone, or of its square, would not).
    #[test]
    fn a_history_with_negative_pressure_jumps_is_rejected() {
        use crate::contact::Impulse;
        const ID: &str = "prop:pressure-bound";
        let c = &cases("test").unwrap()[0];
        let mut good = Vec::new();
        let mut bad = Vec::new();
        for n in [4usize, 8, 16] {
            let data = admissible_sample(&c.datum, n).unwrap();
            let traj = crate::fast::merge::trajectory(&data);
            let imps: Vec<Impulse<Q>> = traj
                .impulses()
                .iter()
                .map(|imp| {
                    let mut pv = imp.part_velocities.clone();
                    pv.reverse();
                    Impulse {
                        part_velocities: pv,
                        ..imp.clone()
                    }
                })
                .collect();
            let reversed = Trajectory::from_parts(data.clone(), traj.join_times().to_vec(), imps);
            good.push(row_of(c, &traj, ID).unwrap());
            bad.push(row_of(c, &reversed, ID).unwrap());
        }
        let table = |rows: Vec<Row>| {
            vec![Series {
                name: c.name.clone(),
                rows,
            }]
        };
        super::super::scaling::pressure_on(&table(good)).unwrap();
        let err = super::super::scaling::pressure_on(&table(bad)).unwrap_err();
        assert!(err.witness.contains("not a non-negative measure"), "{err}");
    }

    #[test]
    fn the_statements_say_what_is_run() {
        let claims = crate::claims::registry::<BigRational>();
        let c = claims.iter().find(|c| c.id == "prop:L2-micro").unwrap();
        assert!(c.statement.contains(&format!("{RANDOM_DATA} random")));
        assert!(c.statement.contains(&format!(
            "{}",
            crate::claims::ledger::Budget::default().scaling_max_n
        )));
    }
}
