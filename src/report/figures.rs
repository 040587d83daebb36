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

use crate::cluster::Cluster;
use crate::error::Error;
use crate::limit::converge::ConvergenceReport;
use crate::limit::eulerian::DensityGrid;
use crate::report::plot::{
    palette, series_style, write_chart, write_heatmap, Axis, Chart, ColourScale, Heatmap, Marker,
    PlotError, Polylines, Series, BLACK_RGB,
};
use crate::scalar::Scalar;
use crate::trajectory::Trajectory;

fn plot_err(e: PlotError) -> Error {
    Error::Unsupported {
        message: format!("cannot write a figure: {e}"),
    }
}

/// At most this many collision markers are drawn (evenly chosen beyond
/// that, and the legend says so).
const MAX_MARKERS: usize = 4000;

/// The contact points of the collisions up to `t_end`: for every impulse,
/// one `(t, x)` per pair of consecutive parts, `x` the point where the last
/// particle of the left part touches the first of the right one
/// (`x_last + r`) at the collision time `t`. A merge of `k` parts has
/// `k − 1` contact points. Computed from the impulses' own data in O(1)
/// each ([`Trajectory::position_in`]), exactly.
pub fn contact_points(
    traj: &Trajectory<BigRational>,
    t_end: &BigRational,
) -> Vec<(BigRational, BigRational)> {
    contacts_every(traj, t_end, 1)
}

/// The number of contact points up to `t_end` (see [`contact_points`]).
fn contact_count(traj: &Trajectory<BigRational>, t_end: &BigRational) -> usize {
    traj.impulses()
        .iter()
        .take_while(|i| i.t <= *t_end)
        .map(|i| i.parts.len().saturating_sub(1))
        .sum()
}

/// Every `every`-th contact point up to `t_end` (the first, the
/// `every + 1`-th, …).
fn contacts_every(
    traj: &Trajectory<BigRational>,
    t_end: &BigRational,
    every: usize,
) -> Vec<(BigRational, BigRational)> {
    let r = traj.data().radius().clone();
    let mut out = Vec::new();
    let mut k = 0usize;
    for imp in traj.impulses().iter().take_while(|i| i.t <= *t_end) {
        for left in imp.parts.iter().take(imp.parts.len().saturating_sub(1)) {
            if k % every.max(1) == 0 {
                let last = left.end() - 1;
                let x = traj.position_in(&imp.cluster, last, &imp.t) + &r;
                out.push((imp.t.clone(), x));
            }
            k += 1;
        }
    }
    out
}

/// The worldlines `t ↦ x_i(t)` on `[0, t_end]` (x horizontal, t upward),
/// coloured by the cluster each particle belongs to at `t_end`, with a
/// marker at every contact point of every collision ([`contact_points`]:
/// where two parts meet, at the instant they meet). At most 400 worldlines
/// are drawn (every k-th particle beyond that) and at most 4000 markers
/// (every k-th contact beyond that); the title and legend say so.
///
/// Cost: one pass over the impulses, O(1) per drawn point; no state of all
/// N particles is built, so 10⁵ particles draw in well under a second.
pub fn spacetime(
    traj: &Trajectory<BigRational>,
    t_end: &BigRational,
    dir: &Path,
    stem: &str,
) -> Result<Vec<PathBuf>, Error> {
    let n = traj.data().n();
    let impulses = traj.impulses();
    let upto = impulses.partition_point(|i| i.t <= *t_end);
    // Positions are affine between collisions: the nodes are 0, the
    // collision times up to t_end (at most 600, evenly spread) and t_end.
    let mut nodes: Vec<BigRational> = vec![BigRational::zero()];
    let step = upto.div_ceil(600).max(1);
    for imp in impulses[..upto].iter().step_by(step) {
        if nodes.last() != Some(&imp.t) && imp.t > BigRational::zero() {
            nodes.push(imp.t.clone());
        }
    }
    if nodes.last() != Some(t_end) && *t_end > BigRational::zero() {
        nodes.push(t_end.clone());
    }
    // The drawn particles and the cluster each belongs to, swept forward in
    // time through the impulses (clusters only grow: an impulse's cluster
    // replaces the one of every drawn particle inside it).
    let every = n.div_ceil(400).max(1);
    let drawn: Vec<usize> = (0..n).step_by(every).collect();
    let mut owner: Vec<Cluster> = vec![Cluster { first: 0, size: 1 }; drawn.len()];
    // Positions of the drawn points in f64 (the clusters are the exact ones).
    let lossy = traj.to_f64_lossy();
    {
        let initial = lossy.clusters_after(&0.0);
        let mut c = initial.iter().peekable();
        for (k, &i) in drawn.iter().enumerate() {
            while c.peek().is_some_and(|c| c.end() <= i) {
                c.next();
            }
            owner[k] = c.peek().map_or(Cluster { first: i, size: 1 }, |c| **c);
        }
    }
    let mut lines: Vec<Vec<(f64, f64)>> = vec![Vec::with_capacity(nodes.len()); drawn.len()];
    let mut next = 0;
    for t in &nodes {
        while next < upto && impulses[next].t <= *t {
            let c = impulses[next].cluster;
            let from = c.first.div_ceil(every);
            let to = (c.end() - 1) / every;
            for o in owner.iter_mut().take(to + 1).skip(from) {
                *o = c;
            }
            next += 1;
        }
        let tf = t.to_f64_lossy();
        for (k, &i) in drawn.iter().enumerate() {
            lines[k].push((lossy.position_in(&owner[k], i, &tf), tf));
        }
    }
    // Colour: one palette colour per cluster at t_end, alternating along
    // the line.
    let mut colours = Vec::with_capacity(drawn.len());
    let mut k = 0usize;
    for (j, o) in owner.iter().enumerate() {
        if j > 0 && owner[j - 1] != *o {
            k += 1;
        }
        colours.push(palette(k));
    }
    let total = contact_count(traj, t_end);
    let thin = total.div_ceil(MAX_MARKERS).max(1);
    let events: Vec<(f64, f64)> = contacts_every(traj, t_end, thin)
        .into_iter()
        .map(|(t, x)| (x.to_f64_lossy(), t.to_f64_lossy()))
        .collect();
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
        label: Some(format!(
            "worldline, colour = contact cluster at t = {}",
            t_end.render()
        )),
        lines: colours.into_iter().zip(lines).collect(),
        width: 1,
    });
    let label = match (total, thin) {
        (0, _) => "no collision before t_end".to_string(),
        (_, 1) => format!("collision: contact point where two parts meet ({total})"),
        _ => format!("collision contact points (every {thin}th of {total})"),
    };
    let mut markers = Series::scatter(label, BLACK_RGB, Marker::Circle, events);
    markers.marker_size = if total > 500 { 2 } else { 4 };
    chart.series.push(markers);
    Ok(write_chart(&chart, dir, stem).map_err(plot_err)?.paths())
}

/// The colour scale of every density map: `ρ` from 0 (vacuum) to 1
/// (congested, the constraint `ρ ≤ 1`). The particle and the continuum maps
/// of a scene share it, so that one colour is one density in both.
pub fn density_scale() -> ColourScale {
    ColourScale::new("density ρ", 0.0, 1.0)
}

/// The density `ρ(t, x)` as a heat map (one row per time of the grid, one
/// cell per position), coloured on `scale` (viridis) with a colour bar.
pub fn density(
    grid: &DensityGrid,
    title: &str,
    scale: &ColourScale,
    dir: &Path,
    stem: &str,
) -> Result<Vec<PathBuf>, Error> {
    let (x_edges, y_edges) = (centred_edges(&grid.xs), centred_edges(&grid.times));
    // Time rows sit at t_0 = 0 … t_end: clip their cells to [0, t_end].
    let y_edges = match (grid.times.first(), grid.times.last()) {
        (Some(&a), Some(&b)) if y_edges.len() > 2 => {
            let mut e = y_edges;
            let last = e.len() - 1;
            e[0] = a;
            e[last] = b;
            e
        }
        _ => y_edges,
    };
    let map = Heatmap {
        title: title.to_string(),
        x: Axis::linear("position x"),
        y: Axis::linear("time t"),
        x_edges,
        y_edges,
        values: grid.values.clone(),
        scale: scale.clone(),
        size: (1100, 640),
    };
    Ok(write_heatmap(&map, dir, stem).map_err(plot_err)?.paths())
}

/// Cell boundaries around increasing centres: midpoints between neighbours,
/// and half a step beyond the ends (a unit cell around a single centre).
fn centred_edges(c: &[f64]) -> Vec<f64> {
    match c {
        [] => Vec::new(),
        [x] => vec![x - 0.5, x + 0.5],
        _ => {
            let mut e = Vec::with_capacity(c.len() + 1);
            e.push(c[0] - (c[1] - c[0]) / 2.0);
            e.extend(c.windows(2).map(|w| (w[0] + w[1]) / 2.0));
            let k = c.len() - 1;
            e.push(c[k] + (c[k] - c[k - 1]) / 2.0);
            e
        }
    }
}

/// The pressure impulses: one marker per non-zero jump of `λ_i`, at the
/// contact point and collision time, in five classes of weight (the weight
/// of an impulse is the jump of `λ_i` there, `prop:micro-pressure`), one
/// palette colour each.
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
        "pressure impulses p = dλ/dt (prop:micro-pressure): weight = jump of λ_i at a collision",
        Axis::linear("position x of the contact"),
        Axis::linear("time t"),
    );
    for (k, pts) in classes.into_iter().enumerate() {
        let mut series = Series::scatter(
            format!(
                "jump of λ_i in ({:.2e}, {:.2e}]",
                max * k as f64 / 5.0,
                max * (k + 1) as f64 / 5.0
            ),
            // Five distinct colours (the ramp's middle classes were two
            // nearly identical greens), the marker growing with the weight.
            palette(k),
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
            let values: Vec<(usize, f64)> = report
                .rows
                .iter()
                .filter_map(|r| r.get(rate.quantity).map(|m| (r.n, m.value)))
                .collect();
            let pts: Vec<(f64, f64)> = values
                .iter()
                .filter(|(_, v)| *v > 0.0 && v.is_finite())
                .map(|&(n, v)| (n as f64, v))
                .collect();
            let label = series_label(rate.quantity.label(), rate.slope_all, &values);
            if pts.is_empty() {
                // Nothing a log axis can show: the legend says why, in words,
                // with no line or marker sample.
                let mut note = Series::line(label, BLACK_RGB, Vec::new());
                note.line = false;
                chart.series.push(note);
                continue;
            }
            chart
                .series
                .push(Series::line(label, BLACK_RGB, pts).with_style(series_style(k)));
            k += 1;
        }
        if k > 0 {
            // (Charts whose every series is a note are not written.)
            out.extend(write_chart(&chart, dir, stem).map_err(plot_err)?.paths());
        }
    }
    Ok(out)
}

/// The legend text of one convergence series: the quantity and its fitted
/// log-log slope, or, when there is none, why — never a bare `NaN`.
/// `values` are `(N, value)` for every N measured.
fn series_label(quantity: &str, slope: f64, values: &[(usize, f64)]) -> String {
    let positive: Vec<usize> = values
        .iter()
        .filter(|(_, v)| *v > 0.0 && v.is_finite())
        .map(|(n, _)| *n)
        .collect();
    let zeros = values.iter().filter(|(_, v)| *v == 0.0).count();
    if positive.is_empty() {
        return if zeros == values.len() {
            format!("{quantity}: 0 at every N (not drawn)")
        } else {
            format!("{quantity}: no positive value (not drawn)")
        };
    }
    if slope.is_finite() {
        return format!("{quantity} (slope {slope:.2})");
    }
    let why = match (positive.as_slice(), zeros) {
        ([n], 0) => format!("one value, N = {n}"),
        ([n], _) => format!("0 except at N = {n}"),
        (_, 0) => "rounding-level values".to_string(),
        (_, z) => format!("rounding level, 0 at {z} N"),
    };
    format!("{quantity} (no slope: {why})")
}
