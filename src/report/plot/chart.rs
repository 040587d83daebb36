//! Line and scatter charts: x/y axes (linear or log), series with markers
//! and dashes, many-line groups, and a legend beside or inside the plot.

use std::fmt;

use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::font::FAMILY;
use super::grid::text_width;
use super::{Axis, Chart, Dash, LegendPosition, Marker, Rgb, Scale, BLACK_RGB};

fn keep(v: f64, scale: Scale) -> bool {
    v.is_finite() && (scale == Scale::Linear || v > 0.0)
}

/// The range shown on one axis: the given one, or the data's with a margin.
fn fit(axis: &Axis, values: impl Iterator<Item = f64>) -> (f64, f64) {
    if let Some((lo, hi)) = axis.range {
        if keep(lo, axis.scale) && keep(hi, axis.scale) && lo < hi {
            return (lo, hi);
        }
    }
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.filter(|&v| keep(v, axis.scale)) {
        lo = lo.min(v);
        hi = hi.max(v);
    }
    match axis.scale {
        Scale::Log => {
            if !(lo.is_finite() && hi.is_finite()) {
                return (1.0, 10.0);
            }
            // A margin of 5% of the decades spanned (at least 0.1 decade),
            // so that points on the extremes stay off the frame.
            let (a, b) = (lo.log10(), hi.log10());
            let pad = ((b - a) * 0.05).max(0.1);
            (10f64.powf(a - pad), 10f64.powf(b + pad))
        }
        Scale::Linear => {
            if !(lo.is_finite() && hi.is_finite()) {
                return (0.0, 1.0);
            }
            if hi <= lo {
                let pad = if lo == 0.0 { 1.0 } else { lo.abs() * 0.1 };
                return (lo - pad, hi + pad);
            }
            let pad = (hi - lo) * 0.05;
            (lo - pad, hi + pad)
        }
    }
}

/// Tick labels: `1e-3` style on log axes, short decimals on linear ones.
pub(super) fn tick(v: f64, scale: Scale) -> String {
    match scale {
        Scale::Log => {
            let e = v.log10();
            if (e - e.round()).abs() < 1e-9 {
                format!("1e{}", e.round() as i64)
            } else {
                format!("{v:.0e}")
            }
        }
        Scale::Linear => {
            if v == 0.0 {
                "0".to_string()
            } else if v.abs() >= 1e5 || v.abs() < 1e-3 {
                format!("{v:.2e}")
            } else {
                let s = format!("{v:.4}");
                let s = s.trim_end_matches('0').trim_end_matches('.');
                s.to_string()
            }
        }
    }
}

pub(super) fn chart_on<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    chart: &Chart,
) -> Result<(), String> {
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let xs = chart
        .series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.0))
        .chain(
            chart
                .polylines
                .iter()
                .flat_map(|g| g.lines.iter().flat_map(|l| l.1.iter().map(|p| p.0))),
        );
    let ys = chart
        .series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.1))
        .chain(
            chart
                .polylines
                .iter()
                .flat_map(|g| g.lines.iter().flat_map(|l| l.1.iter().map(|p| p.1))),
        );
    let (x0, x1) = fit(&chart.x, xs);
    let (y0, y1) = fit(&chart.y, ys);
    let area = root
        .titled(&chart.title, (FAMILY, 20))
        .map_err(|e| e.to_string())?;
    let entries = legend_entries(chart);
    let inside = match chart.legend {
        LegendPosition::Right => None,
        LegendPosition::UpperLeft => Some(SeriesLabelPosition::UpperLeft),
        LegendPosition::UpperRight => Some(SeriesLabelPosition::UpperRight),
        LegendPosition::LowerLeft => Some(SeriesLabelPosition::LowerLeft),
        LegendPosition::LowerRight => Some(SeriesLabelPosition::LowerRight),
    };
    let plot = if inside.is_none() && !entries.is_empty() {
        let (w, _) = area.dim_in_pixel();
        let font = TextStyle::from((FAMILY, 14).into_font());
        let side_w = entries
            .iter()
            .map(|e| {
                area.estimate_text_size(&e.label, &font)
                    .map_or_else(|_| text_width(&e.label, 14), |(w, _)| w)
            })
            .max()
            .unwrap_or(0)
            + 56;
        let side_w = side_w.min(w / 2);
        let (plot, side) = area.split_horizontally(w.saturating_sub(side_w));
        side_legend(&side, &entries)?;
        plot
    } else {
        area
    };
    let root = &plot;
    match (chart.x.scale, chart.y.scale) {
        (Scale::Linear, Scale::Linear) => plot_in(root, chart, inside, x0..x1, y0..y1),
        (Scale::Linear, Scale::Log) => plot_in(root, chart, inside, x0..x1, (y0..y1).log_scale()),
        (Scale::Log, Scale::Linear) => plot_in(root, chart, inside, (x0..x1).log_scale(), y0..y1),
        (Scale::Log, Scale::Log) => plot_in(
            root,
            chart,
            inside,
            (x0..x1).log_scale(),
            (y0..y1).log_scale(),
        ),
    }
}

/// One legend entry drawn beside the plot.
struct Entry {
    label: String,
    color: Rgb,
    line: bool,
    dash: Dash,
    marker: Option<Marker>,
    size: u32,
    width: u32,
}

/// The pieces of a legend's line sample from `x` to `x + len` at height `y`
/// (pixels): one piece when solid, several when dashed or dotted.
fn sample_line(x: i32, y: i32, len: i32, dash: Dash) -> Vec<Vec<(i32, i32)>> {
    let Some((on, off)) = dash_pattern(dash) else {
        return vec![vec![(x, y), (x + len, y)]];
    };
    let (on, off) = (on as i32, off as i32);
    let mut out = Vec::new();
    let mut a = x;
    while a < x + len {
        out.push(vec![(a, y), ((a + on).min(x + len), y)]);
        a += on + off;
    }
    out
}

/// The on/off lengths (pixels) of a dashed line.
fn dash_pattern(dash: Dash) -> Option<(u32, u32)> {
    match dash {
        Dash::Solid => None,
        Dash::Dashed => Some((7, 4)),
        Dash::Dotted => Some((2, 3)),
    }
}

fn legend_entries(chart: &Chart) -> Vec<Entry> {
    let mut out = Vec::new();
    for g in &chart.polylines {
        if let Some(label) = &g.label {
            out.push(Entry {
                label: label.clone(),
                color: g.lines.first().map_or(BLACK_RGB, |l| l.0),
                line: true,
                dash: Dash::Solid,
                marker: None,
                size: 0,
                width: g.width.max(2),
            });
        }
    }
    for s in &chart.series {
        if let Some(label) = &s.label {
            out.push(Entry {
                label: label.clone(),
                color: s.color,
                line: s.line,
                dash: s.dash,
                marker: s.marker,
                size: s.marker_size,
                width: s.width.max(2),
            });
        }
    }
    out
}

fn side_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    entries: &[Entry],
) -> Result<(), String> {
    let err = |e: &dyn fmt::Display| e.to_string();
    let style = TextStyle::from((FAMILY, 14).into_font())
        .color(&BLACK)
        .pos(Pos::new(HPos::Left, VPos::Center));
    for (i, e) in entries.iter().enumerate() {
        let y = 40 + 24 * i as i32;
        let x = 8;
        let color = e.color.color();
        if e.line {
            for piece in sample_line(x, y, 24, e.dash) {
                area.draw(&PathElement::new(piece, color.stroke_width(e.width)))
                    .map_err(|e| err(&e))?;
            }
        }
        if let Some(m) = e.marker {
            let (fill, outline) = shape(m, e.size);
            area.draw(
                &(EmptyElement::at((x + 12, y))
                    + Polygon::new(fill, color.filled())
                    + PathElement::new(outline, color.stroke_width(e.width))),
            )
            .map_err(|e| err(&e))?;
        }
        area.draw(&Text::new(e.label.clone(), (x + 34, y), style.clone()))
            .map_err(|e| err(&e))?;
    }
    Ok(())
}

/// A marker as pixel offsets from its centre: a filled polygon (empty for
/// outline-only markers) and an outline path (empty for filled ones).
#[allow(clippy::type_complexity)]
fn shape(m: Marker, size: u32) -> (Vec<(i32, i32)>, Vec<(i32, i32)>) {
    let d = size.max(1) as i32;
    let disc = |r: f64| -> Vec<(i32, i32)> {
        (0..=16)
            .map(|k| {
                let a = f64::from(k) * std::f64::consts::PI / 8.0;
                ((r * a.cos()).round() as i32, (r * a.sin()).round() as i32)
            })
            .collect()
    };
    match m {
        Marker::Circle => (disc(f64::from(d)), Vec::new()),
        Marker::Ring => (Vec::new(), disc(f64::from(d))),
        Marker::Square => (vec![(-d, -d), (d, -d), (d, d), (-d, d)], Vec::new()),
        Marker::Triangle => {
            let e = d + 1;
            (vec![(0, -e), (e, e * 3 / 4), (-e, e * 3 / 4)], Vec::new())
        }
        Marker::Cross => (Vec::new(), vec![(-d, -d), (d, d), (0, 0), (d, -d), (-d, d)]),
        Marker::Diamond => {
            let e = d + 1;
            (vec![(0, -e), (e, 0), (0, e), (-e, 0)], Vec::new())
        }
    }
}

fn plot_in<DB, X, Y>(
    root: &DrawingArea<DB, Shift>,
    chart: &Chart,
    inside: Option<SeriesLabelPosition>,
    x: X,
    y: Y,
) -> Result<(), String>
where
    DB: DrawingBackend,
    X: AsRangedCoord<Value = f64>,
    Y: AsRangedCoord<Value = f64>,
    X::CoordDescType: ValueFormatter<f64>,
    Y::CoordDescType: ValueFormatter<f64>,
{
    let err = |e: &dyn fmt::Display| e.to_string();
    let mut ctx = ChartBuilder::on(root)
        .margin(16)
        .x_label_area_size(48)
        .y_label_area_size(76)
        .build_cartesian_2d(x, y)
        .map_err(|e| err(&e))?;
    let (xs, ys) = (chart.x.scale, chart.y.scale);
    let fx = move |v: &f64| tick(*v, xs);
    let fy = move |v: &f64| tick(*v, ys);
    ctx.configure_mesh()
        .x_desc(chart.x.label.as_str())
        .y_desc(chart.y.label.as_str())
        .x_label_formatter(&fx)
        .y_label_formatter(&fy)
        .label_style((FAMILY, 14))
        .axis_desc_style((FAMILY, 16))
        .light_line_style(RGBColor(235, 235, 235))
        .bold_line_style(RGBColor(205, 205, 205))
        .draw()
        .map_err(|e| err(&e))?;
    let mut labelled = false;
    for group in &chart.polylines {
        let lines: Vec<PathElement<(f64, f64)>> = group
            .lines
            .iter()
            .map(|(c, pts)| {
                let pts: Vec<(f64, f64)> = pts
                    .iter()
                    .copied()
                    .filter(|p| keep(p.0, xs) && keep(p.1, ys))
                    .collect();
                PathElement::new(pts, c.color().stroke_width(group.width))
            })
            .collect();
        let anno = ctx.draw_series(lines).map_err(|e| err(&e))?;
        if let Some(label) = &group.label {
            let color = group.lines.first().map_or(BLACK, |l| l.0.color());
            let w = group.width.max(2);
            anno.label(label.as_str()).legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(w))
            });
            labelled = true;
        }
    }
    for s in &chart.series {
        let pts: Vec<(f64, f64)> = s
            .points
            .iter()
            .copied()
            .filter(|p| keep(p.0, xs) && keep(p.1, ys))
            .collect();
        let color = s.color.color();
        let stroke = color.stroke_width(s.width);
        let (on, off) = dash_pattern(s.dash).unwrap_or((1 << 20, 1));
        if s.line {
            ctx.draw_series(std::iter::once(DashedPathElement::new(
                pts.clone(),
                on,
                off,
                stroke,
            )))
            .map_err(|e| err(&e))?;
        }
        let (fill, outline) = s
            .marker
            .map_or((Vec::new(), Vec::new()), |m| shape(m, s.marker_size));
        let anno = if s.marker.is_some() {
            ctx.draw_series(pts.iter().map(|&p| {
                EmptyElement::at(p)
                    + Polygon::new(fill.clone(), color.filled())
                    + PathElement::new(outline.clone(), stroke)
            }))
            .map_err(|e| err(&e))?
        } else {
            // An empty series: it carries the legend entry of the line.
            ctx.draw_series(std::iter::empty::<EmptyElement<(f64, f64), DB>>())
                .map_err(|e| err(&e))?
        };
        if let Some(label) = &s.label {
            let (line, w) = (s.line, s.width.max(2));
            anno.label(label.as_str()).legend(move |(x, y)| {
                let glyph_line = if line {
                    vec![(-10, 0), (10, 0)]
                } else {
                    Vec::new()
                };
                EmptyElement::at((x + 10, y))
                    + DashedPathElement::new(glyph_line, on, off, color.stroke_width(w))
                    + Polygon::new(fill.clone(), color.filled())
                    + PathElement::new(outline.clone(), color.stroke_width(w))
            });
            labelled = true;
        }
    }
    if let (true, Some(pos)) = (labelled, inside) {
        ctx.configure_series_labels()
            .position(pos)
            .label_font((FAMILY, 14))
            .background_style(WHITE.mix(0.85))
            .border_style(RGBColor(120, 120, 120))
            .draw()
            .map_err(|e| err(&e))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ticks() {
        assert_eq!(tick(1e-3, Scale::Log), "1e-3");
        assert_eq!(tick(1.0, Scale::Log), "1e0");
        assert_eq!(tick(0.25, Scale::Linear), "0.25");
        assert_eq!(tick(0.0, Scale::Linear), "0");
    }

    #[test]
    fn fit_ranges() {
        let (lo, hi) = fit(&Axis::log("x"), [3e-5, 2e2].into_iter());
        assert!(lo < 3e-5 && lo > 1e-5 && hi > 2e2 && hi < 1e3, "{lo} {hi}");
        assert_eq!(fit(&Axis::log("x"), [0.0, -1.0].into_iter()), (1.0, 10.0));
        let (lo, hi) = fit(&Axis::linear("x"), [1.0, 1.0].into_iter());
        assert!(lo < 1.0 && hi > 1.0);
    }

    #[test]
    fn dashed_legend_samples_stay_in_their_box() {
        assert_eq!(
            sample_line(0, 5, 24, Dash::Solid),
            vec![vec![(0, 5), (24, 5)]]
        );
        for dash in [Dash::Dashed, Dash::Dotted] {
            let pieces = sample_line(0, 5, 24, dash);
            assert!(pieces.len() > 1, "{dash:?}");
            assert!(pieces
                .iter()
                .flatten()
                .all(|&(x, y)| (0..=24).contains(&x) && y == 5));
        }
    }
}
