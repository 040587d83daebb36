//! The charts: Pareto fronts (error against solve time), errors against
//! `Δt`, and cost against `N`.

use crate::reference::ErrorsF64;
use crate::report::plot::{palette, series_style, Axis, Chart, Marker, Rgb, Series, BLACK_RGB};

use super::csv::short;
use super::jobs::{Sweep, EVENTS_TOL, ITERATIVE_TOL, SWEEP_DT};
use super::peers::peer_methods;
use super::solve::{Row, Status};
use super::{EXACT_METHODS, METHODS};

pub(super) fn style(method: &str) -> (Rgb, Marker) {
    match method {
        "exact-pava" => (BLACK_RGB, Marker::Square),
        "exact-events" => (Rgb(90, 90, 90), Marker::Ring),
        "pava-f64" => (palette(0), Marker::Circle),
        "events-f64" => (palette(1), Marker::Triangle),
        "moreau-jean" => (palette(2), Marker::Circle),
        "catching-up" => (palette(3), Marker::Square),
        "iterative-projection" => (palette(4), Marker::Cross),
        peer => match peer_methods().iter().position(|m| m == peer) {
            // The peers: a colour and marker each, after our five.
            Some(i) => {
                let s = series_style(i + 5);
                (s.color, s.marker)
            }
            None => (palette(7), Marker::Ring),
        },
    }
}

/// The floor at which errors of exactly 0 are drawn on a log axis: the
/// power of ten a decade below the smallest positive value (`1e-20` when
/// there is none).
fn floor_for(values: impl Iterator<Item = f64>) -> f64 {
    let min = values
        .filter(|v| v.is_finite() && *v > 0.0)
        .fold(f64::INFINITY, f64::min);
    if min.is_finite() {
        10f64.powf(min.log10().floor() - 1.0)
    } else {
        1e-20
    }
}

fn all_methods() -> impl Iterator<Item = &'static str> {
    EXACT_METHODS.iter().chain(METHODS.iter()).copied()
}

/// Our methods, then the peers that have a row in `rows`.
pub(super) fn methods_with_peers(rows: &[&Row]) -> Vec<String> {
    let mut out: Vec<String> = all_methods().map(str::to_string).collect();
    out.extend(
        peer_methods()
            .into_iter()
            .filter(|m| rows.iter().any(|r| &r.setting.method == m)),
    );
    out
}

/// Which unknown a chart draws the error of.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Unknown {
    /// The positions x(t).
    Position,
    /// The velocities u(t).
    Velocity,
}

impl Unknown {
    /// Both, in the order the charts are written.
    pub(super) const BOTH: [Unknown; 2] = [Unknown::Position, Unknown::Velocity];

    /// `"position"` or `"velocity"` (file names and labels).
    pub(super) fn name(self) -> &'static str {
        match self {
            Unknown::Position => "position",
            Unknown::Velocity => "velocity",
        }
    }

    /// The row's error on this unknown (`None`: not measured).
    fn error(self, e: &ErrorsF64) -> Option<f64> {
        match self {
            Unknown::Position => Some(e.position),
            Unknown::Velocity => e.velocity,
        }
    }
}

pub(super) fn pareto_chart(case: &str, rows: &[&Row], of: Unknown) -> Option<Chart> {
    let err = |r: &Row| -> Option<f64> { of.error(&r.errors?) };
    let usable: Vec<&Row> = rows
        .iter()
        .copied()
        .filter(|r| err(r).is_some() && r.wall > 0.0)
        .collect();
    if usable.is_empty() {
        return None;
    }
    let floor = floor_for(usable.iter().filter_map(|r| err(r)));
    let first = usable[0];
    let what = match of {
        Unknown::Position => "max position error |x − x(t)|",
        Unknown::Velocity => "max velocity error |u − u(t)|",
    };
    let mut chart = Chart::new(
        format!(
            "{case}, N = {}, t = {}: {} error vs solve time (error 0 drawn at {floor:.0e})",
            first.n,
            short(first.t),
            of.name()
        ),
        Axis::log("solve time [s] (peers: the solver call alone, median)"),
        Axis::log(what),
    );
    let mut points_all = Vec::new();
    for method in methods_with_peers(&usable) {
        let method = method.as_str();
        let pts: Vec<(f64, f64)> = usable
            .iter()
            .filter(|r| r.setting.method == method)
            .filter_map(|r| err(r).map(|e| (r.wall, if e > 0.0 { e } else { floor })))
            .collect();
        if pts.is_empty() {
            continue;
        }
        points_all.extend(pts.iter().copied());
        let (color, marker) = style(method);
        let label = if EXACT_METHODS.contains(&method) {
            format!("{method} (error 0, drawn at {floor:.0e})")
        } else {
            method.to_string()
        };
        let mut s = Series::scatter(label, color, marker, pts);
        s.marker_size = 5;
        chart.series.push(s);
    }
    points_all.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    // The smallest error reachable within a given time: a staircase
    // through the non-dominated points.
    let mut front: Vec<(f64, f64)> = Vec::new();
    let mut best = f64::INFINITY;
    for p in points_all {
        if p.1 < best {
            if best.is_finite() {
                front.push((p.0, best));
            }
            best = p.1;
            front.push(p);
        }
    }
    let mut s = Series::line("Pareto front", Rgb(60, 60, 60), front);
    s.width = 1;
    chart.series.insert(0, s);
    Some(chart)
}

pub(super) fn dt_chart(case: &str, rows: &[&Row]) -> Option<Chart> {
    let steppers = ["moreau-jean", "catching-up"];
    let sel: Vec<&Row> = rows
        .iter()
        .copied()
        .filter(|r| {
            steppers.contains(&r.setting.method.as_str())
                && r.setting.sweep == Sweep::Dt
                && r.errors.is_some()
        })
        .collect();
    if sel.is_empty() {
        return None;
    }
    let floor = floor_for(sel.iter().flat_map(|r| {
        let e = r.errors.unwrap_or_else(zero_errors);
        [e.position, e.velocity.unwrap_or(0.0)]
    }));
    let first = sel[0];
    let mut chart = Chart::new(
        format!(
            "{case}, N = {}, t = {}: time-steppers' error vs Δt (error 0 drawn at {floor:.0e})",
            first.n,
            short(first.t)
        ),
        Axis::log("time step Δt"),
        Axis::log("max error"),
    );
    for (i, m) in steppers.iter().enumerate() {
        for of in Unknown::BOTH {
            let mut pts: Vec<(f64, f64)> = sel
                .iter()
                .filter(|r| r.setting.method == *m)
                .filter_map(|r| {
                    let e = r.errors?;
                    let v = of.error(&e)?;
                    Some((r.setting.dt?, if v > 0.0 { v } else { floor }))
                })
                .collect();
            if pts.is_empty() {
                continue;
            }
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            let color = palette(2 + i);
            let label = format!("{m}: {}", of.name());
            let marker = match of {
                Unknown::Position => Marker::Circle,
                Unknown::Velocity => Marker::Ring,
            };
            chart
                .series
                .push(Series::line(label, color, pts).with_marker(marker));
        }
    }
    Some(chart)
}

fn zero_errors() -> ErrorsF64 {
    ErrorsF64 {
        position: 0.0,
        velocity: None,
        lambda: None,
        kkt: None,
        missed_contacts: 0,
        spurious_contacts: 0,
        min_gap: None,
        min_lambda: None,
        min_pressure_jump: None,
        oleinik_violations: None,
    }
}

/// The representative row of each method in `cost-vs-n`, and its legend.
pub(super) fn representative(r: &Row) -> Option<String> {
    match r.setting.method.as_str() {
        "exact-pava" | "exact-events" | "pava-f64" => Some(r.setting.method.clone()),
        "events-f64" if r.setting.tol == Some(EVENTS_TOL) => {
            Some(format!("events-f64 (tol {EVENTS_TOL:e})"))
        }
        "moreau-jean" | "catching-up"
            if r.setting.sweep == Sweep::Dt && r.setting.dt == Some(SWEEP_DT) =>
        {
            Some(format!("{} (Δt = 2^-8)", r.setting.method))
        }
        "iterative-projection"
            if r.setting.sweep == Sweep::Tol && r.setting.tol == Some(ITERATIVE_TOL) =>
        {
            Some(format!("iterative-projection (tol {ITERATIVE_TOL:e})"))
        }
        _ => None,
    }
}

pub(super) fn cost_chart(rows: &[Row]) -> Chart {
    let mut chart = Chart::new(
        "cost vs N on the random scenes (t = 1025/1024): solve time",
        Axis::log("number of particles N"),
        Axis::log("solve time [s] (peers: the solver call alone, median)"),
    );
    for method in all_methods() {
        let mut label = None;
        let mut pts = Vec::new();
        for r in rows
            .iter()
            .filter(|r| r.scene.starts_with("random-") && r.setting.method == method)
        {
            if let Some(l) = representative(r) {
                if !matches!(r.status, Status::Refused(_)) {
                    label = Some(l);
                    pts.push((r.n as f64, r.wall));
                }
            }
        }
        if let Some(label) = label {
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            let (color, marker) = style(method);
            chart
                .series
                .push(Series::line(label, color, pts).with_marker(marker));
        }
    }
    chart
}
