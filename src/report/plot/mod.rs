//! A small chart writer on [plotters]: every figure is written as SVG and
//! PNG side by side, each file whole (a temporary name in the target folder,
//! then a rename), as every command that writes files does (docs/guide/commands.md).
//!
//! Three kinds of figure:
//!
//! * [`Chart`] — x/y axes, each linear or logarithmic, with labels and a
//!   title; [`Series`] of points drawn as a line, as markers, or both (one
//!   legend entry per labelled series); and [`Polylines`], many lines with
//!   one colour each under a single legend entry (worldlines of a
//!   space-time diagram, a family of convergence curves). Markers at points
//!   (collision events, measured values) are a [`Series`] with a
//!   [`Marker`] and no line.
//! * [`Heatmap`] — a value on an x/y grid of cells drawn with a continuous,
//!   perceptually uniform colour scale ([`ColourScale`], viridis-like) and
//!   a labelled colour bar.
//! * [`Grid`] — a table of coloured markers: rows × columns of cells, each
//!   holding one coloured square per outcome it shows, with a colour
//!   legend (a heatmap of categories, e.g. method × scene outcomes).
//!
//! **Fonts.** Text in a bitmap is drawn by plotters' `ab_glyph` backend,
//! which has no font of its own and cannot lay out any text without one
//! (in SVG as well: label sizes are measured before they are written). The
//! first figure looks for a TrueType font on the machine: the file named by
//! the environment variable `STICKY_FONT`, then a list of common locations
//! ([`FONT_PATHS`]); `STICKY_FONT=none` skips the search. If none is found,
//! a *metrics-only* font (every glyph empty, 0.6 em wide) is built in memory and registered instead: SVG text is
//! drawn by the viewer's own fonts, so SVG files come out complete, but a PNG
//! would have no visible text, so PNGs are skipped ([`Written::png`] is
//! `None` and [`png_support`] says why) and standard error says so once per
//! process, with how to get them (install a font such as Debian's
//! `fonts-dejavu-core`, or set `STICKY_FONT`). Nothing here panics for want
//! of a font.
//!
//! **Log axes** cannot show `0` or negative values: such points are left out
//! of a log axis (callers that want to show an error of exactly 0 place it at
//! a floor value and say so in the legend). Non-finite points are always
//! left out.
//!
//! The module is split by idea: the data types (`model.rs`),
//! line/scatter drawing (`chart.rs`), heat maps and the colour scale
//! (`heatmap.rs`), category grids (`grid.rs`), fonts and PNG support
//! (`font.rs`), and writing files (`write.rs`).

use std::fmt;
use std::path::PathBuf;

mod chart;
mod font;
mod grid;
mod heatmap;
mod model;
mod write;

pub use font::{png_support, PngSupport, FONT_PATHS};
pub use heatmap::{viridis, ColourScale, Heatmap};
pub use model::{
    palette, ramp, series_style, Axis, Cell, Chart, Dash, Grid, LegendPosition, Marker, Polylines,
    Rgb, Scale, Series, SeriesStyle, BLACK_RGB, PALETTE,
};
pub use write::{write_chart, write_grid, write_heatmap, write_whole};

/// The files one figure was written to.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Written {
    /// The SVG file.
    pub svg: PathBuf,
    /// The PNG file (`None` when no font was found: see [`png_support`]).
    pub png: Option<PathBuf>,
}

impl Written {
    /// The paths written, SVG first.
    pub fn paths(&self) -> Vec<PathBuf> {
        let mut v = vec![self.svg.clone()];
        v.extend(self.png.clone());
        v
    }
}

/// Why a figure could not be written.
#[derive(Debug, Clone, PartialEq, Eq)]
#[non_exhaustive]
pub enum PlotError {
    /// Creating, writing or renaming a file failed.
    Io {
        /// The file.
        path: PathBuf,
        /// What the operating system said.
        message: String,
    },
    /// plotters could not draw the figure.
    Draw {
        /// The file being drawn.
        path: PathBuf,
        /// plotters' message.
        message: String,
    },
    /// A stem that is not a plain file name (empty, or with a path
    /// separator).
    BadName {
        /// The stem given.
        stem: String,
    },
}

impl fmt::Display for PlotError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PlotError::Io { path, message } => write!(f, "{}: {message}", path.display()),
            PlotError::Draw { path, message } => {
                write!(f, "{}: drawing failed: {message}", path.display())
            }
            PlotError::BadName { stem } => {
                write!(f, "figure name {stem:?} is not a plain file name")
            }
        }
    }
}

impl std::error::Error for PlotError {}
