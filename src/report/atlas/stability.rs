//! The stability section's table (`stability.md`) and grid of markers.

use crate::report::plot::{Cell, Grid};

use super::charts::methods_with_peers;
use super::csv::short;
use super::failure::{
    Failure, FAILURE_COLORS, FAILURE_NAMES, OK_COLOR, OVERLAP_TOLERANCE, SIGN_TOLERANCE,
    VELOCITY_TOLERANCE,
};
use super::solve::{Row, Status};
use super::suite::Case;
use super::{EXACT_METHODS, METHODS};

/// The columns of the table and grid: our methods, then the peers that
/// have a row.
fn columns(rows: &[Row]) -> Vec<String> {
    let refs: Vec<&Row> = rows.iter().collect();
    methods_with_peers(&refs)
        .into_iter()
        .filter(|m| !EXACT_METHODS.contains(&m.as_str()))
        .filter(|m| METHODS.contains(&m.as_str()) || m.starts_with("peer:"))
        .collect()
}

pub(super) fn stability_grid(cases: &[Case], rows: &[Row], failures: &[Vec<Failure>]) -> Grid {
    let mut cells = Vec::new();
    let methods = columns(rows);
    for (i, case) in cases.iter().enumerate() {
        for (j, method) in methods.iter().enumerate() {
            let found = rows
                .iter()
                .zip(failures)
                .find(|(r, _)| r.scene == case.name && r.setting.method == *method);
            let Some((r, fs)) = found else {
                continue;
            };
            if matches!(r.status, Status::Skipped(_)) {
                continue;
            }
            let colors = if fs.is_empty() {
                vec![OK_COLOR]
            } else {
                fs.iter().map(|f| FAILURE_COLORS[f.index()]).collect()
            };
            cells.push(Cell {
                row: i,
                column: j,
                colors,
                text: None,
            });
        }
    }
    let mut legend = vec![("OK".to_string(), OK_COLOR)];
    legend.extend(
        FAILURE_NAMES
            .iter()
            .zip(FAILURE_COLORS)
            .map(|(n, c)| (n.to_string(), c)),
    );
    Grid {
        title: "Where methods fail: one square per failure kind (stability scenes)".to_string(),
        rows: cases.iter().map(|c| c.name.clone()).collect(),
        columns: methods,
        cells,
        legend,
    }
}

pub(super) fn stability_markdown(
    cases: &[Case],
    rows: &[Row],
    failures: &[Vec<Failure>],
) -> String {
    let mut md = String::new();
    md.push_str("# Where methods fail\n\n");
    md.push_str(
        "Each floating-point method once per scene, with its default tolerances; the \
         time-steppers with the step Δt and every iterative solve with the sweep cap given \
         below. Errors are measured exactly against the exact solution of the rational scene \
         (`reference::measure`); `stability.csv` has every number.\n\n",
    );
    let methods = columns(rows);
    md.push_str("| scene |");
    for m in &methods {
        md.push_str(&format!(" {m} |"));
    }
    md.push_str("\n|---|");
    for _ in &methods {
        md.push_str("---|");
    }
    md.push('\n');
    for case in cases {
        md.push_str(&format!("| {} |", case.name));
        for m in &methods {
            let found = rows
                .iter()
                .zip(failures)
                .find(|(r, _)| r.scene == case.name && &r.setting.method == m);
            let cell = match found {
                None => "—".to_string(),
                Some((r, fs)) => match &r.status {
                    Status::Skipped(why) => format!("— ({})", why.replace('|', "\\|")),
                    _ if fs.is_empty() => "OK".to_string(),
                    _ => fs
                        .iter()
                        .map(|f| f.to_string().replace('|', "\\|"))
                        .collect::<Vec<_>>()
                        .join("; "),
                },
            };
            md.push_str(&format!(" {cell} |"));
        }
        md.push('\n');
    }
    md.push_str("\n## Scenes\n\n");
    for case in cases {
        md.push_str(&format!(
            "- **{}** (N = {}, t = {}): {}. Time-steppers: Δt = {} ({} steps), at most {} sweeps per inner solve; iterative projection: at most {} sweeps.\n",
            case.name,
            case.n,
            short(case.t),
            case.description,
            short(case.step),
            (case.t / case.step).ceil(),
            case.step_cap,
            case.cap
        ));
    }
    md.push_str(&format!(
        "\n## Failure kinds\n\n\
         - **refused**: the solver returned an error (too many steps, NaN, …).\n\
         - **no convergence**: an inner iterative solve stopped at its sweep cap (the result is still measured).\n\
         - **overlap**: `min x_{{i+1}} − x_i − 2r < −{OVERLAP_TOLERANCE:e}·2r` (`df:KN`); the depth is given in units of 2r.\n\
         - **wrong clusters**: the method's contact set at t differs from the exact Ω(x(t)) (`df:Omega-micro`): collisions missed or spurious.\n\
         - **wrong velocities**: max |u − u(t)| > {VELOCITY_TOLERANCE:e}·V (V = max |u⁰|): a collision missed, spurious or not resolved in time changes the post-collision velocity.\n\
         - **negative λ / negative p**: a multiplier or a pressure jump below −{SIGN_TOLERANCE:e}·V (`eq:dyn-micro`, `prop:micro-pressure`).\n\
         - **Oleinik violated**: pairs with t(u_i − u_{{i−1}}) ≥ x_i − x_{{i−1}} (`prop:Oleinik`), counted exactly.\n\
         - **position error > 2r/10**: max |x − x(t)| above a tenth of a particle diameter.\n"
    ));
    md
}
