//! The convergence study `N → ∞` (`thm:main` (iii), §3): for quantile
//! samplings of one `[macro]` datum with `N = n_min, 2 n_min, …, n_max`,
//! the distances between the particle interpolations and the exact
//! continuum solution ([`super::continuum`]), the uniform bounds of §3.2–3.3
//! and the weak residuals of `eq:macro-euler` ([`super::eulerian`]), with
//! least-squares log-log rates.
//!
//! **Engines.** `N ≤ exact_max` runs the exact engine
//! (`Trajectory<BigRational>`); larger `N` run the same generic code on
//! `f64` (`Trajectory::<f64>` on `data.convert::<f64>()`). Each row says
//! which. Comparisons with the continuum are exact (`BigRational`) when the
//! engine is exact and the continuum profile is rational at every sample
//! time; otherwise they are computed in `f64` from the exactly computed
//! profile rounded with a rigorous bound (see [`Measure::bound`]). The `f64`
//! engine has no rigorous bound: it is validated by running both engines at
//! `N = exact_max` ([`EngineCheck`]).
//!
//! **Sample times.** `0`, `t_j = T(3j − 1)/(3K)` for `j = 1 … K`
//! (`K = time_samples`), and `T`. The off-grid times keep the plateau ends
//! of the (dyadic) shipped scenes off the particle grid `i/N`, where some
//! errors vanish by accident. Sups over `[0, T]` (or `[α, T]`, `α = t_1`)
//! are maxima over these times, except the pressure mass, which is exact
//! over `[0, T]`.
//!
//! **Files.** This one: the options, the report and the driver
//! ([`converge`]); `quantity.rs`: what is measured ([`Measure`],
//! [`Quantity`], [`Row`]) and the fitted [`rates`]; `distance.rs`: the
//! `L²`/`L¹` distances of `thm:main` (iii); `particles.rs`: one N, the
//! particle side against the continuum samples; `summary.rs`: the text
//! table; `campaign.rs`: the study as a campaign of units (`--shard`). The
//! CSV files are written by `report::converge`.

use num_bigint::BigInt;
use num_rational::BigRational;

use super::continuum::{Continuum, Profile};
use super::eulerian::{
    complementarity_defect, continuum_residuals, oleinik_margin, support_window, test_family,
    Quadrature,
};
use super::surd::Surd;
use crate::error::Error;
use crate::progress::{Progress, Silent};
use crate::scalar::Scalar;
use crate::scene::{Scene, SceneKind};

#[cfg(feature = "json")]
pub mod campaign;
mod distance;
mod particles;
mod quantity;
mod summary;

pub use distance::{lambda_l2_squared, u_l1, u_l2_squared, x_l2_squared};
use particles::{exact_measure, max_measure, run_n, Context, Sample};

pub use quantity::{rates, Measure, Quantity, Rate, Row};

/// Options of [`converge`].
#[derive(Debug, Clone, PartialEq)]
pub struct ConvergeOptions {
    /// Smallest N (rounded up to a power of two, at least 2).
    pub n_min: usize,
    /// Largest N.
    pub n_max: usize,
    /// Largest N run by the exact engine.
    pub exact_max: usize,
    /// The horizon `T` (default: the scene's `t_end`, else 1).
    pub t_end: Option<BigRational>,
    /// `K`: the sample times are `0`, `T(3j − 1)/(3K)` (`j = 1 … K`), `T`.
    pub time_samples: usize,
    /// `δ` of the artificial particle (`df:x0`).
    pub delta: BigRational,
    /// Panels of the time quadrature of the continuum residuals (0: skip
    /// the continuum residuals).
    pub panels: usize,
}

impl Default for ConvergeOptions {
    fn default() -> Self {
        ConvergeOptions {
            n_min: 8,
            n_max: 1 << 16,
            exact_max: 1 << 12,
            t_end: None,
            time_samples: 8,
            delta: BigRational::from_integer(1.into()),
            panels: 16,
        }
    }
}

/// Which engine computed a row.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "json", derive(serde::Serialize, serde::Deserialize))]
pub enum Engine {
    /// `BigRational`, exact.
    Exact,
    /// `f64`.
    Float,
}

impl Engine {
    /// `"exact"` or `"f64"`.
    pub fn name(self) -> &'static str {
        match self {
            Engine::Exact => "exact",
            Engine::Float => "f64",
        }
    }
}

/// The continuum side of the study.
#[derive(Debug, Clone, PartialEq)]
pub struct ContinuumSummary {
    /// `true` when the profile was rational at every sample time.
    pub rational: bool,
    /// Number of plateaus at each sample time.
    pub plateaus: Vec<usize>,
    /// `∫_0^1 Λ(T, w) dw`, the pressure mass on `[0, T]`.
    pub pressure_mass: Measure,
    /// `X(t_j,1) − X(t_j,0⁺)` at each sample time.
    pub spread: Vec<f64>,
    /// `TV(U(t_j))` at each sample time.
    pub tv_u: Vec<f64>,
    /// `∫_0^1 Λ(t_j)`: the pressure mass on `[0, t_j]`, at each sample time.
    pub lambda_integral: Vec<f64>,
    /// `max ρ` over the sample times (≤ 1, `lem:density`).
    pub max_density: Measure,
    /// `max_j t_j sup ∂_x u` (`< 1`; `None` if `u` jumps up without a gap).
    pub oleinik: Option<f64>,
    /// `max |Λ|` outside the plateaus (0: `(∂_w X − 1)Λ = 0`, so
    /// `(1 − ρ)p = 0`).
    pub complementarity_defect: Measure,
    /// Per test function: `(mass residual, momentum residual)`, by
    /// quadrature (exact value 0).
    pub residuals: Vec<(Quadrature, Quadrature)>,
}

/// Both engines at one N: the difference of each quantity.
#[derive(Debug, Clone, PartialEq)]
pub struct EngineCheck {
    /// The N.
    pub n: usize,
    /// `|exact − f64| / max(|exact|, 10⁻³⁰⁰)` per quantity.
    pub differences: Vec<(Quantity, f64)>,
}

/// Everything [`converge`] measured.
#[derive(Debug, Clone, PartialEq)]
pub struct ConvergenceReport {
    /// The scene's name.
    pub scene: String,
    /// `T`.
    pub t_end: BigRational,
    /// The sample times.
    pub times: Vec<BigRational>,
    /// `δ`.
    pub delta: BigRational,
    /// The test functions, by name.
    pub test_functions: Vec<String>,
    /// One row per N.
    pub rows: Vec<Row>,
    /// Per test function and row: `R_mom^N(φ)`.
    pub particle_residuals: Vec<Vec<f64>>,
    /// Fitted rates.
    pub rates: Vec<Rate>,
    /// The continuum.
    pub continuum: ContinuumSummary,
    /// Exact vs f64 engine at `exact_max`, when both ran.
    pub engine_check: Option<EngineCheck>,
}

/// The powers of two from `n_min` to `n_max`.
pub fn n_values(opts: &ConvergeOptions) -> Vec<usize> {
    let mut n = opts.n_min.max(2).next_power_of_two();
    let mut out = Vec::new();
    while n <= opts.n_max {
        out.push(n);
        n *= 2;
    }
    out
}

/// Runs the study on a `[macro]` scene (see the module documentation).
pub fn converge(scene: &Scene, opts: &ConvergeOptions) -> Result<ConvergenceReport, Error> {
    converge_with_progress(scene, opts, &Silent)
}

/// [`converge`], telling `progress` which N is being computed (one step per
/// N, and one for the engine check) and asking it between two N whether to
/// stop: when [`Progress::cancelled`] says so, the study ends early and the
/// report holds the rows computed so far (the caller, which asked for the
/// stop, says so).
pub fn converge_with_progress(
    scene: &Scene,
    opts: &ConvergeOptions,
    progress: &dyn Progress,
) -> Result<ConvergenceReport, Error> {
    let study = Study::new(scene, opts)?;
    let units = study.units();
    progress.stage(
        &format!(
            "{}: N = {} … {}",
            study.scene,
            study.ns[0],
            study.ns[study.ns.len() - 1]
        ),
        Some(units.len() as u64),
    );
    let mut results = Vec::with_capacity(units.len());
    for unit in units {
        if progress.cancelled() {
            break;
        }
        progress.note(&match unit {
            Unit::Particles { n } => {
                format!("{}: N = {n} ({})", study.scene, study.engine(n).name())
            }
            Unit::EngineCheck { n } => format!("engine check: N = {n} on f64"),
        });
        results.push(study.run_unit(unit)?);
        progress.advance(1);
    }
    study.report(&results)
}

/// One independent piece of a study (a campaign's unit, issue 38 item 3).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Unit {
    /// The particles at this N against the continuum.
    Particles {
        /// N.
        n: usize,
    },
    /// The `f64` engine at this N (the largest exactly computed one), to
    /// compare with the exact row ([`EngineCheck`]).
    EngineCheck {
        /// N.
        n: usize,
    },
}

/// What a [`Unit`] computed.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "json", derive(serde::Serialize, serde::Deserialize))]
pub enum UnitResult {
    /// The row of one N and its momentum residual per test function.
    Particles {
        /// The row.
        row: Row,
        /// `R_mom^N(φ)` per test function.
        #[cfg_attr(feature = "json", serde(with = "crate::campaign::bits::many"))]
        residuals: Vec<f64>,
    },
    /// The `f64` engine's row at the N of the engine check.
    EngineCheck {
        /// The row.
        row: Row,
    },
}

/// A study set up: the continuum at the sample times and the test
/// functions, which every unit compares with, and the N to run.
pub struct Study {
    scene: String,
    opts: ConvergeOptions,
    continuum: Continuum,
    profiles: Vec<Profile<Surd>>,
    lambda_end: Option<BigRational>,
    ctx: Context,
    ns: Vec<usize>,
}

impl Study {
    /// Sets up the study of a `[macro]` scene (the continuum side is cheap
    /// beside the particles: every shard and the merge set it up).
    pub fn new(scene: &Scene, opts: &ConvergeOptions) -> Result<Study, Error> {
        let SceneKind::Macro { datum, .. } = &scene.kind else {
            return Err(Error::Unsupported {
                message:
                    "the convergence study needs a [macro] scene (a macroscopic datum to sample)"
                        .to_string(),
            });
        };
        if opts.n_max > crate::scene::MAX_MACRO_PARTICLES {
            return Err(Error::Unsupported {
                message: format!(
                    "N = {} exceeds the limit of {} particles",
                    opts.n_max,
                    crate::scene::MAX_MACRO_PARTICLES
                ),
            });
        }
        let t_end = opts
            .t_end
            .clone()
            .or_else(|| scene.t_end.clone())
            .unwrap_or_else(|| BigRational::from_integer(1.into()));
        if t_end <= BigRational::from_integer(0.into()) {
            return Err(Error::Unsupported {
                message: format!("the horizon T must be positive, got {}", t_end.render()),
            });
        }
        if opts.delta <= BigRational::from_integer(0.into()) {
            return Err(Error::Unsupported {
                message: format!("δ must be positive, got {}", opts.delta.render()),
            });
        }
        let k = opts.time_samples.max(1);
        let mut times = vec![BigRational::from_integer(0.into())];
        times.extend(
            (1..=k)
                .map(|j| &t_end * BigRational::new(BigInt::from(3 * j - 1), BigInt::from(3 * k))),
        );
        times.push(t_end.clone());
        let continuum = Continuum::new(datum);
        let profiles: Vec<Profile<Surd>> = times
            .iter()
            .map(|t| continuum.profile(t))
            .collect::<Result<_, _>>()?;
        let samples: Vec<Sample> = profiles.iter().map(Sample::new).collect();
        let (center, scale) = support_window(&continuum, &t_end);
        let tests = test_family(&t_end, &center, &scale);
        let last = samples.last().ok_or_else(|| Error::Unsupported {
            message: "no sample time".to_string(),
        })?;
        let lambda_end = last.exact.as_ref().map(|p| p.lambda_integral());
        let lambda_end_f = {
            let v = last.float.lambda_integral();
            (
                v,
                last.conversion_bound() * 2.0 + 64.0 * f64::EPSILON * v.abs(),
            )
        };
        let ctx = Context {
            datum: datum.clone(),
            times: times.clone(),
            samples,
            t_end: t_end.clone(),
            delta: opts.delta.clone(),
            tests,
            lambda_end: lambda_end
                .clone()
                .unwrap_or_else(|| BigRational::from_integer(0.into())),
            lambda_end_f,
        };
        let ns = n_values(opts);
        if ns.is_empty() {
            return Err(Error::Unsupported {
                message: format!("no power of two N with {} ≤ N ≤ {}", opts.n_min, opts.n_max),
            });
        }
        Ok(Study {
            scene: scene.name.clone().unwrap_or_else(|| "scene".to_string()),
            opts: opts.clone(),
            continuum,
            profiles,
            lambda_end,
            ctx,
            ns,
        })
    }

    fn engine(&self, n: usize) -> Engine {
        if n <= self.opts.exact_max {
            Engine::Exact
        } else {
            Engine::Float
        }
    }

    /// The units, in the order of a single run: every N, then the engine
    /// check (both engines at the largest exact N) when N goes past
    /// `exact_max`.
    pub fn units(&self) -> Vec<Unit> {
        let mut units: Vec<Unit> = self.ns.iter().map(|&n| Unit::Particles { n }).collect();
        let largest_exact = self.ns.iter().rev().find(|&&n| n <= self.opts.exact_max);
        if let (Some(&n), true) = (largest_exact, self.opts.n_max > self.opts.exact_max) {
            units.push(Unit::EngineCheck { n });
        }
        units
    }

    /// Runs one unit.
    pub fn run_unit(&self, unit: Unit) -> Result<UnitResult, Error> {
        Ok(match unit {
            Unit::Particles { n } => {
                let (row, residuals) = run_n(&self.ctx, n, self.engine(n))?;
                UnitResult::Particles { row, residuals }
            }
            Unit::EngineCheck { n } => UnitResult::EngineCheck {
                row: run_n(&self.ctx, n, Engine::Float)?.0,
            },
        })
    }

    /// The report from the results of the units (of [`Study::units`], in
    /// order; a prefix when the study was stopped early).
    pub fn report(&self, results: &[UnitResult]) -> Result<ConvergenceReport, Error> {
        let ctx = &self.ctx;
        let profiles = &self.profiles;
        let opts = &self.opts;
        let mut rows: Vec<Row> = Vec::new();
        let mut residual_columns: Vec<&[f64]> = Vec::new();
        let mut engine_check = None;
        for result in results {
            match result {
                UnitResult::Particles { row, residuals } => {
                    rows.push(row.clone());
                    residual_columns.push(residuals);
                }
                UnitResult::EngineCheck { row: f } => {
                    let Some(r) = rows
                        .iter()
                        .find(|r| r.n == f.n && r.engine == Engine::Exact)
                    else {
                        continue;
                    };
                    let differences = Quantity::ALL
                        .iter()
                        .filter_map(|&q| {
                            let (a, b) = (r.get(q)?.value, f.get(q)?.value);
                            Some((q, (a - b).abs() / a.abs().max(1e-300)))
                        })
                        .collect();
                    engine_check = Some(EngineCheck {
                        n: r.n,
                        differences,
                    });
                }
            }
        }
        let particle_residuals = (0..ctx.tests.len())
            .map(|k| {
                residual_columns
                    .iter()
                    .map(|c| c.get(k).copied().unwrap_or(f64::NAN))
                    .collect()
            })
            .collect();
        // The continuum side.
        let rational = ctx.samples.iter().all(|s| s.exact.is_some());
        let mut max_density = Measure::float(0.0, 0.0);
        let mut oleinik = Some(0.0f64);
        let mut defect = Measure::float(0.0, 0.0);
        for (s, p) in ctx.samples.iter().zip(profiles) {
            let m = match &s.exact {
                Some(e) => exact_measure(&e.max_density()),
                None => Measure::float(s.float.max_density(), s.conversion_bound()),
            };
            max_density = max_measure(max_density, m);
            let d = match &s.exact {
                Some(e) => exact_measure(&complementarity_defect(e)),
                None => Measure::float(complementarity_defect(&s.float), s.conversion_bound()),
            };
            defect = max_measure(defect, d);
            let t = p.t.to_f64_lossy();
            let tol = 4.0 * s.conversion_bound() + 16.0 * f64::EPSILON * s.range;
            oleinik = match (oleinik, oleinik_margin(&s.float, &t, &tol)) {
                (Some(a), Some(b)) => Some(a.max(b)),
                _ => None,
            };
        }
        let residuals = if opts.panels > 0 {
            continuum_residuals(&self.continuum, &ctx.tests, opts.panels)?
        } else {
            Vec::new()
        };
        let pressure_mass = match &self.lambda_end {
            Some(q) => exact_measure(q),
            None => Measure::float(ctx.lambda_end_f.0, ctx.lambda_end_f.1),
        };
        let summary = ContinuumSummary {
            rational,
            plateaus: profiles.iter().map(|p| p.plateaus.len()).collect(),
            pressure_mass,
            spread: ctx.samples.iter().map(|s| s.spread).collect(),
            tv_u: ctx.samples.iter().map(|s| s.tv).collect(),
            lambda_integral: ctx
                .samples
                .iter()
                .map(|s| s.float.lambda_integral())
                .collect(),
            max_density,
            oleinik,
            complementarity_defect: defect,
            residuals,
        };
        Ok(ConvergenceReport {
            scene: self.scene.clone(),
            t_end: ctx.t_end.clone(),
            times: ctx.times.clone(),
            delta: opts.delta.clone(),
            test_functions: ctx.tests.iter().map(|f| f.name()).collect(),
            rates: rates(&rows),
            rows,
            particle_residuals,
            continuum: summary,
            engine_check,
        })
    }
}
