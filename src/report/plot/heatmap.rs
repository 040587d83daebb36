//! Heat maps: a value on an x/y grid of cells, each cell filled with the
//! colour of its value on a continuous, perceptually uniform scale
//! ([`viridis`]), with a labelled colour bar beside the plot.
//!
//! Two maps meant to be compared side by side (the particle and continuum
//! densities of one scene) are given the same [`ColourScale`]: one colour,
//! one value, in both pictures.

use std::fmt;

use plotters::coord::Shift;
use plotters::prelude::*;

use super::chart::tick;
use super::font::FAMILY;
use super::{Axis, Rgb, Scale};

/// Eleven evenly spaced samples of matplotlib's *viridis* colour map
/// (s = 0, 0.1, …, 1): dark blue to yellow, lightness increasing steadily,
/// readable by colour-blind readers and in grey-scale print.
const VIRIDIS: [Rgb; 11] = [
    Rgb(0x44, 0x01, 0x54),
    Rgb(0x48, 0x25, 0x76),
    Rgb(0x41, 0x44, 0x87),
    Rgb(0x35, 0x60, 0x8d),
    Rgb(0x2a, 0x78, 0x8e),
    Rgb(0x21, 0x91, 0x8c),
    Rgb(0x22, 0xa8, 0x84),
    Rgb(0x43, 0xbf, 0x71),
    Rgb(0x7a, 0xd1, 0x51),
    Rgb(0xbd, 0xdf, 0x26),
    Rgb(0xfd, 0xe7, 0x25),
];

/// The viridis colour at `s ∈ [0, 1]` (clamped; a non-finite `s` gives the
/// low end), interpolated linearly between the table's samples.
pub fn viridis(s: f64) -> Rgb {
    let s = if s.is_finite() {
        s.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let pos = s * (VIRIDIS.len() - 1) as f64;
    let k = (pos.floor() as usize).min(VIRIDIS.len() - 2);
    let u = pos - k as f64;
    let (a, b) = (VIRIDIS[k], VIRIDIS[k + 1]);
    let mix = |p: u8, q: u8| (f64::from(p) + (f64::from(q) - f64::from(p)) * u).round() as u8;
    Rgb(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// A continuous colour scale: values from `lo` to `hi` mapped on
/// [`viridis`], named by `label` on the colour bar.
#[derive(Debug, Clone, PartialEq)]
pub struct ColourScale {
    /// What the colour shows (quantity and unit), written along the bar.
    pub label: String,
    /// The value drawn in the darkest colour (smaller values too).
    pub lo: f64,
    /// The value drawn in the lightest colour (larger values too).
    pub hi: f64,
}

impl ColourScale {
    /// The scale `[lo, hi]` named `label`.
    pub fn new(label: impl Into<String>, lo: f64, hi: f64) -> Self {
        ColourScale {
            label: label.into(),
            lo,
            hi,
        }
    }

    /// The colour of `v` (`None` when `v` is not finite: the cell is left
    /// blank rather than drawn in a colour that means a value).
    pub fn colour(&self, v: f64) -> Option<Rgb> {
        if !v.is_finite() {
            return None;
        }
        let span = self.hi - self.lo;
        let s = if span > 0.0 && span.is_finite() {
            (v - self.lo) / span
        } else {
            0.5
        };
        Some(viridis(s))
    }

    /// The range shown on the bar (a degenerate or non-finite range is
    /// widened so that the bar can still be drawn).
    fn range(&self) -> (f64, f64) {
        let (lo, hi) = (self.lo, self.hi);
        if lo.is_finite() && hi.is_finite() && lo < hi {
            (lo, hi)
        } else if lo.is_finite() {
            (lo - 0.5, lo + 0.5)
        } else {
            (0.0, 1.0)
        }
    }
}

/// A heat map: cell `(j, k)` covers `[x_edges[k], x_edges[k+1]] ×
/// [y_edges[j], y_edges[j+1]]` and is coloured by `values[j][k]`.
#[derive(Debug, Clone, PartialEq)]
pub struct Heatmap {
    /// The title, above the plot.
    pub title: String,
    /// The horizontal axis (its label; drawn linear, over the edges' range).
    pub x: Axis,
    /// The vertical axis (its label; drawn linear, over the edges' range).
    pub y: Axis,
    /// Column boundaries, increasing (one more than the columns).
    pub x_edges: Vec<f64>,
    /// Row boundaries, increasing (one more than the rows).
    pub y_edges: Vec<f64>,
    /// `values[row][column]`; a non-finite value leaves its cell blank.
    pub values: Vec<Vec<f64>>,
    /// The colour scale (and the colour bar's label).
    pub scale: ColourScale,
    /// Image size in pixels.
    pub size: (u32, u32),
}

/// Width of the colour bar's area (bar, ticks and label), pixels.
const BAR_AREA: u32 = 130;

pub(super) fn heatmap_size(map: &Heatmap) -> (u32, u32) {
    map.size
}

/// The range covered by increasing `edges` (a unit range when there are
/// none).
fn span(edges: &[f64]) -> (f64, f64) {
    match (edges.first(), edges.last()) {
        (Some(&a), Some(&b)) if a.is_finite() && b.is_finite() && a < b => (a, b),
        (Some(&a), _) if a.is_finite() => (a - 0.5, a + 0.5),
        _ => (0.0, 1.0),
    }
}

/// The cells of one row merged into runs of one colour:
/// `(x from, x to, colour)`.
fn runs(edges: &[f64], row: &[f64], scale: &ColourScale) -> Vec<(f64, f64, Rgb)> {
    let mut out: Vec<(f64, f64, Rgb)> = Vec::new();
    for (k, v) in row.iter().enumerate() {
        let (Some(&a), Some(&b)) = (edges.get(k), edges.get(k + 1)) else {
            break;
        };
        let Some(c) = scale.colour(*v) else {
            continue;
        };
        match out.last_mut() {
            Some(last) if last.2 == c && last.1 == a => last.1 = b,
            _ => out.push((a, b, c)),
        }
    }
    out
}

pub(super) fn heatmap_on<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    map: &Heatmap,
) -> Result<(), String> {
    let err = |e: &dyn fmt::Display| e.to_string();
    root.fill(&WHITE).map_err(|e| err(&e))?;
    let area = root.titled(&map.title, (FAMILY, 20)).map_err(|e| err(&e))?;
    let (w, _) = area.dim_in_pixel();
    let (plot, bar) = area.split_horizontally(w.saturating_sub(BAR_AREA));
    let (x0, x1) = span(&map.x_edges);
    let (y0, y1) = span(&map.y_edges);
    let mut ctx = ChartBuilder::on(&plot)
        .margin(16)
        .x_label_area_size(48)
        .y_label_area_size(76)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(|e| err(&e))?;
    let fx = |v: &f64| tick(*v, Scale::Linear);
    ctx.configure_mesh()
        .disable_mesh()
        .x_desc(map.x.label.as_str())
        .y_desc(map.y.label.as_str())
        .x_label_formatter(&fx)
        .y_label_formatter(&fx)
        .label_style((FAMILY, 14))
        .axis_desc_style((FAMILY, 16))
        .draw()
        .map_err(|e| err(&e))?;
    let mut cells = Vec::new();
    for (j, row) in map.values.iter().enumerate() {
        let (Some(&a), Some(&b)) = (map.y_edges.get(j), map.y_edges.get(j + 1)) else {
            break;
        };
        for (l, r, c) in runs(&map.x_edges, row, &map.scale) {
            cells.push(Rectangle::new([(l, a), (r, b)], c.color().filled()));
        }
    }
    ctx.draw_series(cells).map_err(|e| err(&e))?;
    colour_bar(&bar, &map.scale)
}

/// The colour bar: the scale's colours from `lo` (bottom) to `hi` (top),
/// ticks and the scale's label on the right.
fn colour_bar<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    scale: &ColourScale,
) -> Result<(), String> {
    let err = |e: &dyn fmt::Display| e.to_string();
    let (lo, hi) = scale.range();
    let mut ctx = ChartBuilder::on(area)
        .margin_top(16)
        .margin_bottom(16)
        .margin_left(8)
        .margin_right(4)
        .x_label_area_size(48)
        .right_y_label_area_size(72)
        .build_cartesian_2d(0.0..1.0, lo..hi)
        .map_err(|e| err(&e))?;
    let fy = |v: &f64| tick(*v, Scale::Linear);
    ctx.configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .y_desc(scale.label.as_str())
        .y_label_formatter(&fy)
        .y_labels(6)
        .label_style((FAMILY, 14))
        .axis_desc_style((FAMILY, 16))
        .draw()
        .map_err(|e| err(&e))?;
    const STEPS: usize = 128;
    let step = (hi - lo) / STEPS as f64;
    ctx.draw_series((0..STEPS).map(|i| {
        let a = lo + step * i as f64;
        let c = scale.colour(a + step / 2.0).unwrap_or(Rgb(255, 255, 255));
        Rectangle::new([(0.0, a), (1.0, a + step)], c.color().filled())
    }))
    .map_err(|e| err(&e))?;
    ctx.draw_series(std::iter::once(Rectangle::new(
        [(0.0, lo), (1.0, hi)],
        BLACK.stroke_width(1),
    )))
    .map_err(|e| err(&e))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Relative luminance (sRGB, linearised), 0 = black, 1 = white.
    fn luminance(c: Rgb) -> f64 {
        let lin = |v: u8| {
            let v = f64::from(v) / 255.0;
            if v <= 0.04045 {
                v / 12.92
            } else {
                ((v + 0.055) / 1.055).powf(2.4)
            }
        };
        0.2126 * lin(c.0) + 0.7152 * lin(c.1) + 0.0722 * lin(c.2)
    }

    #[test]
    fn viridis_ends_and_lightness_increase() {
        assert_eq!(viridis(0.0), Rgb(0x44, 0x01, 0x54));
        assert_eq!(viridis(1.0), Rgb(0xfd, 0xe7, 0x25));
        assert_eq!(viridis(f64::NAN), viridis(0.0));
        assert_eq!(viridis(2.0), viridis(1.0));
        // A perceptually ordered scale: lightness grows with the value.
        let mut last = -1.0;
        for i in 0..=100 {
            let l = luminance(viridis(f64::from(i) / 100.0));
            assert!(l > last, "luminance falls at {i}");
            last = l;
        }
    }

    #[test]
    fn scale_maps_range_and_leaves_non_finite_blank() {
        let s = ColourScale::new("ρ", 0.0, 2.0);
        assert_eq!(s.colour(0.0), Some(viridis(0.0)));
        assert_eq!(s.colour(1.0), Some(viridis(0.5)));
        assert_eq!(s.colour(5.0), Some(viridis(1.0)));
        assert_eq!(s.colour(f64::NAN), None);
        assert_eq!(ColourScale::new("x", 1.0, 1.0).range(), (0.5, 1.5));
    }

    #[test]
    fn runs_merge_equal_neighbours() {
        let s = ColourScale::new("ρ", 0.0, 1.0);
        let r = runs(&[0.0, 1.0, 2.0, 3.0, 4.0], &[1.0, 1.0, f64::NAN, 0.0], &s);
        assert_eq!(r, vec![(0.0, 2.0, viridis(1.0)), (3.0, 4.0, viridis(0.0))]);
    }
}
