//! `atlas.csv` and `stability.csv`: one row per (scene, method, parameter),
//! columns [`super::CSV_COLUMNS`].

use std::path::Path;

use crate::report::io::csv_field;
use crate::report::plot::write_whole;

use super::failure::Failure;
use super::solve::{Row, Status};
use super::{AtlasError, CSV_COLUMNS};

/// A time or step for text: plain decimals in `[10⁻³, 10⁷)`, else
/// scientific.
pub(super) fn short(v: f64) -> String {
    if v == 0.0 || (1e-3..1e7).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

fn num(v: f64) -> String {
    if v == 0.0 {
        "0".to_string()
    } else {
        format!("{v:e}")
    }
}

fn opt<T>(v: Option<T>, f: impl Fn(T) -> String) -> String {
    v.map(f).unwrap_or_default()
}

fn csv_row(row: &Row) -> Vec<String> {
    let e = row.errors;
    let int = |k: usize| k.to_string();
    vec![
        row.scene.clone(),
        row.n.to_string(),
        num(row.t),
        row.setting.method.to_string(),
        row.setting.parameter.clone(),
        row.setting.sweep.as_str().to_string(),
        opt(row.setting.dt, num),
        opt(row.setting.tol, num),
        opt(row.setting.cap, int),
        row.status.to_string(),
        num(row.wall),
        row.repeats.to_string(),
        opt(e.map(|e| e.position), num),
        opt(e.and_then(|e| e.velocity), num),
        opt(e.and_then(|e| e.lambda), num),
        opt(e.and_then(|e| e.kkt), num),
        opt(e.map(|e| e.missed_contacts), int),
        opt(e.map(|e| e.spurious_contacts), int),
        opt(e.map(|e| e.cluster_mismatch()), int),
        opt(e.and_then(|e| e.min_gap), num),
        opt(e.and_then(|e| e.min_gap).map(|g| g / row.two_r), num),
        opt(e.and_then(|e| e.min_lambda), num),
        opt(e.and_then(|e| e.min_pressure_jump), num),
        opt(e.and_then(|e| e.oleinik_violations), int),
        opt(row.work.map(|w| w.steps), int),
        opt(row.work.map(|w| w.iterations), int),
        opt(row.work.map(|w| w.unconverged), int),
        opt(row.converged, |c| c.to_string()),
        opt(row.residual, num),
        opt(row.process_seconds, num),
        opt(row.setup_seconds, num),
    ]
}

pub(super) fn write_csv(
    path: &Path,
    rows: &[Row],
    failures: Option<&[Vec<Failure>]>,
) -> Result<(), AtlasError> {
    let mut text = CSV_COLUMNS.join(",");
    if failures.is_some() {
        text.push_str(",failures");
    }
    text.push('\n');
    for (i, row) in rows.iter().enumerate() {
        let mut fields = csv_row(row);
        if let Some(f) = failures {
            // A skipped row has no failures and is not OK: empty.
            let skipped = matches!(row.status, Status::Skipped(_));
            let cell = f.get(i).filter(|_| !skipped).map_or(String::new(), |fs| {
                if fs.is_empty() {
                    "OK".to_string()
                } else {
                    fs.iter()
                        .map(ToString::to_string)
                        .collect::<Vec<_>>()
                        .join("; ")
                }
            });
            fields.push(cell);
        }
        let line: Vec<String> = fields.iter().map(|s| csv_field(s)).collect();
        text.push_str(&line.join(","));
        text.push('\n');
    }
    write_whole(path, text.as_bytes()).map_err(AtlasError::from)
}
