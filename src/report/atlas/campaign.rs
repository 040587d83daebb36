//! The atlas as a campaign (issue 38, item 3): its units are the jobs of
//! every scene — scene × method × parameter, the suite's scenes then the
//! stability section's, each in the order of [`super::run`] — each solved,
//! timed and measured alone ([`Campaign::run_unit`]). A shard of
//! `sticky atlas --shard I/N` runs the units `u ≡ I (mod N)`, and
//! [`Campaign::publish`] writes from every unit's row the files a single
//! run writes.
//!
//! The rows are the single run's but for what is measured on the clock:
//! `wall_seconds` and `repeats` (a fast solve is repeated until 2 ms, or
//! 20 ms, have passed), and through them the charts that draw the wall time
//! (`pareto-*`, `cost-vs-n`). Every other column of `atlas.csv` and
//! `stability.csv`, `stability.md`, the `error-vs-dt-*` and `stability`
//! charts are equal byte for byte. The peers (`--peers`) are not units.

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use serde::{Deserialize, Serialize};

use super::jobs::{jobs, stability_jobs};
use super::solve::{exact_states, solve_unit, ExactStates, Row};
use super::suite::{stability_suite, suite, Case};
use super::{min_time, write_files, AtlasError, Size};

/// What a shard's file records of the run: what every shard and the merge
/// build the same scenes and jobs from.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct AtlasSetup {
    /// How much of the atlas ([`super::AtlasOptions::size`]).
    pub size: Size,
    /// Only these scenes; empty: every scene
    /// ([`super::AtlasOptions::scenes`]).
    pub scenes: Vec<String>,
}

/// Which part of the atlas a scene belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Section {
    /// The suite: the exact engines and every method over its sweeps.
    Suite,
    /// The stability section: each floating-point method once.
    Stability,
}

/// One unit: a job of a scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Unit {
    section: Section,
    case: usize,
    job: usize,
}

/// One unit's result: its row of `atlas.csv` or `stability.csv` (each
/// double as its bit pattern in JSON, [`crate::campaign::bits`]).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct UnitRow(Row);

/// The scenes of a setup, their jobs as units, and the exact states of the
/// suite's scenes, each computed once when a unit first needs it.
pub struct Campaign {
    setup: AtlasSetup,
    suite: Vec<Case>,
    stability: Vec<Case>,
    exact: Vec<OnceLock<Result<ExactStates, AtlasError>>>,
}

impl Campaign {
    /// The scenes of `setup` (as [`super::run`] builds them).
    pub fn new(setup: &AtlasSetup) -> Result<Campaign, AtlasError> {
        let keep = |c: &Case| setup.scenes.is_empty() || setup.scenes.contains(&c.name);
        let mut main = suite(setup.size)?;
        main.retain(keep);
        let mut stability = stability_suite(setup.size)?;
        stability.retain(keep);
        Ok(Campaign {
            setup: setup.clone(),
            exact: main.iter().map(|_| OnceLock::new()).collect(),
            suite: main,
            stability,
        })
    }

    /// Every unit, in the order of the single run's rows.
    pub fn units(&self) -> Vec<Unit> {
        let of = |section: Section, cases: &[Case]| -> Vec<Unit> {
            cases
                .iter()
                .enumerate()
                .flat_map(|(case, c)| {
                    let count = match section {
                        Section::Suite => jobs(c, self.setup.size).len(),
                        Section::Stability => stability_jobs(c).len(),
                    };
                    (0..count).map(move |job| Unit { section, case, job })
                })
                .collect()
        };
        let mut units = of(Section::Suite, &self.suite);
        units.extend(of(Section::Stability, &self.stability));
        units
    }

    /// Solves (timed) and measures one unit. The jobs are built again for
    /// the unit (cheap: solver settings), so units run on any thread.
    pub fn run_unit(&self, unit: Unit) -> Result<UnitRow, String> {
        let min = min_time(self.setup.size);
        let row = match unit.section {
            Section::Suite => {
                let case = &self.suite[unit.case];
                let exact = self.exact[unit.case]
                    .get_or_init(|| exact_states(case))
                    .as_ref()
                    .map_err(|e| e.to_string())?;
                let job = &jobs(case, self.setup.size)[unit.job];
                solve_unit(case, Some(exact), job, min)
            }
            Section::Stability => {
                let case = &self.stability[unit.case];
                solve_unit(case, None, &stability_jobs(case)[unit.job], min)
            }
        };
        Ok(UnitRow(row))
    }

    /// Writes the atlas's files under `out_dir` from every unit's row, in
    /// unit order (what [`crate::campaign::file::merge`] hands back): the
    /// files of a single run without `--peers`.
    pub fn publish(&self, out_dir: &Path, rows: Vec<UnitRow>) -> Result<Vec<PathBuf>, AtlasError> {
        std::fs::create_dir_all(out_dir).map_err(|e| AtlasError::Io {
            path: out_dir.to_path_buf(),
            message: e.to_string(),
        })?;
        let units = self.units();
        debug_assert_eq!(units.len(), rows.len());
        let (main, stab): (Vec<_>, Vec<_>) = units
            .iter()
            .zip(rows)
            .partition(|(u, _)| u.section == Section::Suite);
        let rows: Vec<Row> = main.into_iter().map(|(_, r)| r.0).collect();
        let stab_rows: Vec<Row> = stab.into_iter().map(|(_, r)| r.0).collect();
        write_files(
            out_dir,
            &self.suite,
            &self.stability,
            &rows,
            &stab_rows,
            None,
        )
    }
}
