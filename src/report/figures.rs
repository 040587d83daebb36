//! The hydrodynamic-limit figures (`sticky plot`, `sticky converge`), drawn
//! with [`crate::report::plot`]: a space-time diagram of the particle worldlines
//! coloured by cluster with the collisions marked, the density `ρ(t, x)` as
//! a heat map, the pressure impulses, and the convergence charts (log-log,
//! one series per quantity).
//!
//! Figures are pictures: values are converted to `f64` here and only here,
//! after the exact computation.

use std::path::{Path, PathBuf};

use num_rational::BigRational;

use crate::error::Error;
use crate::limit::converge::ConvergenceReport;
use crate::limit::eulerian::DensityGrid;
use crate::report::plot::{
    palette, ramp, write_chart, Axis, Chart, Marker, PlotError, Polylines, Series,
};
use crate::scalar::Scalar;
use crate::trajectory::Trajectory;

fn plot_err(e: PlotError) -> Error {
    Error::Unsupported {
        message: format!("cannot write a figure: {e}"),
    }
}

/// The worldlines `t ↦ x_i(t)` on `[0, t_end]` (x horizontal, t upward),
/// coloured by the cluster each particle belongs to at `t_end`, with a
/// marker at every collision (at the contact point of the cluster formed).
/// At most 400 worldlines are drawn (every k-th particle beyond that).
pub fn spacetime(
    traj: &Trajectory<BigRational>,
    t_end: &BigRational,
    dir: &Path,
    stem: &str,
) -> Result<Vec<PathBuf>, Error> {
    let n = traj.data().n();
    // Positions are affine between collisions: the nodes are 0, the
    // collision times up to t_end (at most 600, evenly spread) and t_end.
    let mut nodes: Vec<BigRational> = vec![BigRational::zero()];
    let times: Vec<&BigRational> = traj
        .impulses()
        .iter()
        .map(|i| &i.t)
        .filter(|t| *t <= t_end)
        .collect();
    let step = times.len().div_ceil(600).max(1);
    for t in times.iter().step_by(step) {
        if nodes.last() != Some(*t) {
            nodes.push((*t).clone());
        }
    }
    if nodes.last() != Some(t_end) {
        nodes.push(t_end.clone());
    }
    let states: Vec<_> = nodes.iter().map(|t| traj.at(t)).collect::<Result<_, _>>()?;
    let last = states.last().ok_or_else(|| Error::Unsupported {
        message: "no state to draw".into(),
    })?;
    let mut colour = vec![palette(0); n];
    for (k, c) in last.clusters.iter().enumerate() {
        for i in c.range() {
            colour[i] = palette(k);
        }
    }
    let every = n.div_ceil(400).max(1);
    let lines: Vec<_> = (0..n)
        .step_by(every)
        .map(|i| {
            let pts = nodes
                .iter()
                .zip(&states)
                .map(|(t, s)| (s.positions[i].to_f64_lossy(), t.to_f64_lossy()))
                .collect();
            (colour[i], pts)
        })
        .collect();
    let mut events = Vec::new();
    for imp in traj.impulses().iter().filter(|i| i.t <= *t_end) {
        if let Ok(s) = traj.at(&imp.t) {
            let mid = imp.cluster.first + imp.cluster.size / 2;
            events.push((s.positions[mid].to_f64_lossy(), imp.t.to_f64_lossy()));
        }
    }
    let mut chart = Chart::new(
        format!(
            "worldlines of {n} sticky particles{}, coloured by cluster at t = {}",
            if every > 1 {
                format!(" (every {every}th)")
            } else {
                String::new()
            },
            t_end.render()
        ),
        Axis::linear("position x"),
        Axis::linear("time t"),
    );
    chart.polylines.push(Polylines {
        label: Some("particle worldlines".into()),
        lines,
        width: 1,
    });
    chart.series.push(Series::scatter(
        "collision (cluster formed)",
        crate::report::plot::BLACK_RGB,
        Marker::Circle,
        events,
    ));
    Ok(write_chart(&chart, dir, stem).map_err(plot_err)?.paths())
}

/// The density `ρ(t, x)` as a heat map: one horizontal band per time row,
/// one coloured segment per cell (colour ramp from 0 to 1).
pub fn density(
    grid: &DensityGrid,
    title: &str,
    dir: &Path,
    stem: &str,
) -> Result<Vec<PathBuf>, Error> {
    let dx = if grid.xs.len() > 1 {
        (grid.xs[grid.xs.len() - 1] - grid.xs[0]) / (grid.xs.len() - 1) as f64
    } else {
        1.0
    };
    let mut lines = Vec::new();
    for (t, row) in grid.times.iter().zip(&grid.values) {
        for (x, rho) in grid.xs.iter().zip(row) {
            lines.push((
                ramp(rho.clamp(0.0, 1.0)),
                vec![(x - dx / 2.0, *t), (x + dx / 2.0, *t)],
            ));
        }
    }
    let band = (560 / grid.times.len().max(1)).clamp(2, 40) as u32;
    let mut chart = Chart::new(
        format!("{title} (colour: 0 → 1)"),
        Axis::linear("position x"),
        Axis::linear("time t"),
    );
    chart.polylines.push(Polylines {
        label: Some("density ρ(t, x)".into()),
        lines,
        width: band,
    });
    for level in [0.0, 0.25, 0.5, 0.75, 1.0] {
        chart.series.push(Series::scatter(
            format!("ρ = {level}"),
            ramp(level),
            Marker::Square,
            vec![],
        ));
    }
    Ok(write_chart(&chart, dir, stem).map_err(plot_err)?.paths())
}

/// The pressure impulses: one marker per non-zero jump of `λ_i`, at the
/// contact point and collision time, in five classes of weight.
pub fn pressure(
    atoms: &[(BigRational, BigRational, BigRational)],
    dir: &Path,
    stem: &str,
) -> Result<Vec<PathBuf>, Error> {
    let max = atoms
        .iter()
        .map(|a| a.2.to_f64_lossy())
        .fold(0.0f64, f64::max)
        .max(f64::MIN_POSITIVE);
    let mut classes: Vec<Vec<(f64, f64)>> = vec![Vec::new(); 5];
    for (t, x, w) in atoms {
        let k = ((w.to_f64_lossy() / max) * 5.0).ceil().clamp(1.0, 5.0) as usize - 1;
        classes[k].push((x.to_f64_lossy(), t.to_f64_lossy()));
    }
    let mut chart = Chart::new(
        "pressure impulses p = dλ/dt (prop:micro-pressure): jumps of λ_i at collisions",
        Axis::linear("position x of the contact"),
        Axis::linear("time t"),
    );
    for (k, pts) in classes.into_iter().enumerate() {
        let mut series = Series::scatter(
            format!(
                "weight in ({:.2e}, {:.2e}]",
                max * k as f64 / 5.0,
                max * (k + 1) as f64 / 5.0
            ),
            ramp((k as f64 + 1.0) / 5.0),
            Marker::Circle,
            pts,
        );
        series.marker_size = 2 + k as u32;
        chart.series.push(series);
    }
    Ok(write_chart(&chart, dir, stem).map_err(plot_err)?.paths())
}

/// The convergence charts: every quantity against N on log-log axes (one
/// series each; quantities that vanish exactly are left out, as a log axis
/// cannot show 0), split into the distances that should tend to 0 and the
/// quantities that should stay bounded.
pub fn convergence(report: &ConvergenceReport, dir: &Path) -> Result<Vec<PathBuf>, Error> {
    let mut out = Vec::new();
    for (zero, stem, title) in [
        (
            true,
            "convergence-errors",
            "distances to the continuum limit vs N",
        ),
        (
            false,
            "convergence-bounded",
            "quantities bounded independently of N?",
        ),
    ] {
        let mut chart = Chart::new(
            format!("{}: {title}", report.scene),
            Axis::log("N (particles)"),
            Axis::log("value"),
        );
        let mut k = 0;
        for rate in &report.rates {
            if rate.quantity.tends_to_zero() != zero {
                continue;
            }
            let pts: Vec<(f64, f64)> = report
                .rows
                .iter()
                .filter_map(|r| r.get(rate.quantity).map(|m| (r.n as f64, m.value)))
                .filter(|(_, v)| *v > 0.0 && v.is_finite())
                .collect();
            if pts.is_empty() {
                continue;
            }
            chart.series.push(
                Series::line(
                    format!("{} (slope {:.2})", rate.quantity.label(), rate.slope_all),
                    palette(k),
                    pts,
                )
                .with_marker(Marker::Circle),
            );
            k += 1;
        }
        if k > 0 {
            out.extend(write_chart(&chart, dir, stem).map_err(plot_err)?.paths());
        }
    }
    Ok(out)
}
