//! A small chart writer on [plotters]: every figure is written as SVG and
//! PNG side by side, each file whole (a temporary name in the target folder,
//! then a rename), as DESIGN.md §3 asks of every command that writes files.
//!
//! Two kinds of figure:
//!
//! * [`Chart`] — x/y axes, each linear or logarithmic, with labels and a
//!   title; [`Series`] of points drawn as a line, as markers, or both (one
//!   legend entry per labelled series); and [`Polylines`], many lines with
//!   one colour each under a single legend entry (worldlines of a
//!   space-time diagram, a family of convergence curves). Markers at points
//!   (collision events, measured values) are a [`Series`] with a
//!   [`Marker`] and no line.
//! * [`Grid`] — a table of coloured markers: rows × columns of cells, each
//!   holding one coloured square per outcome it shows, with a colour
//!   legend (a heatmap of categories, e.g. method × scene outcomes).
//!
//! **Fonts.** Text in a bitmap is drawn by plotters' `ab_glyph` backend,
//! which has no font of its own and cannot lay out any text without one
//! (in SVG as well: label sizes are measured before they are written). The
//! first figure looks for a TrueType font on the machine: the file named by
//! the environment variable `STICKY_FONT`, then a list of common locations
//! ([`FONT_PATHS`]); `STICKY_FONT=none` skips the search. If none is found, a *metrics-only* font (every glyph
//! empty, 0.6 em wide) is built in memory and registered instead: SVG text is
//! drawn by the viewer's own fonts, so SVG files come out complete, but a PNG
//! would have no visible text, so PNGs are skipped ([`Written::png`] is
//! `None` and [`png_support`] says why). Nothing here panics for want of a
//! font.
//!
//! **Log axes** cannot show `0` or negative values: such points are left out
//! of a log axis (callers that want to show an error of exactly 0 place it at
//! a floor value and say so in the legend). Non-finite points are always
//! left out.

use std::fmt;
use std::fs;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// An RGB colour.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Rgb(pub u8, pub u8, pub u8);

impl Rgb {
    fn color(self) -> RGBColor {
        RGBColor(self.0, self.1, self.2)
    }
}

/// Black.
pub const BLACK_RGB: Rgb = Rgb(0, 0, 0);

/// Ten colours that stay distinct on screen and in print (Tableau 10).
pub const PALETTE: [Rgb; 10] = [
    Rgb(31, 119, 180),
    Rgb(255, 127, 14),
    Rgb(44, 160, 44),
    Rgb(214, 39, 40),
    Rgb(148, 103, 189),
    Rgb(140, 86, 75),
    Rgb(227, 119, 194),
    Rgb(127, 127, 127),
    Rgb(188, 189, 34),
    Rgb(23, 190, 207),
];

/// The `i`-th colour of [`PALETTE`], cycling.
pub fn palette(i: usize) -> Rgb {
    PALETTE[i % PALETTE.len()]
}

/// A colour between blue (`s = 0`) and red (`s = 1`) through green, for
/// colouring a family of lines by a parameter (`s` is clamped to `[0, 1]`).
pub fn ramp(s: f64) -> Rgb {
    let s = if s.is_finite() {
        s.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let (a, b, u) = if s < 0.5 {
        (Rgb(49, 54, 149), Rgb(26, 152, 80), s * 2.0)
    } else {
        (Rgb(26, 152, 80), Rgb(215, 48, 39), s * 2.0 - 1.0)
    };
    let mix = |p: u8, q: u8| (f64::from(p) + (f64::from(q) - f64::from(p)) * u).round() as u8;
    Rgb(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// Linear or logarithmic axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scale {
    /// Linear.
    Linear,
    /// Base-10 logarithmic (values `≤ 0` are not shown).
    Log,
}

/// One axis of a [`Chart`].
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    /// The axis label (quantity and unit).
    pub label: String,
    /// Linear or logarithmic.
    pub scale: Scale,
    /// The range shown; `None` fits the data (with a margin).
    pub range: Option<(f64, f64)>,
}

impl Axis {
    /// A linear axis fitted to the data.
    pub fn linear(label: impl Into<String>) -> Self {
        Axis {
            label: label.into(),
            scale: Scale::Linear,
            range: None,
        }
    }

    /// A logarithmic axis fitted to the data.
    pub fn log(label: impl Into<String>) -> Self {
        Axis {
            label: label.into(),
            scale: Scale::Log,
            range: None,
        }
    }

    /// The same axis showing `[lo, hi]`.
    pub fn with_range(mut self, lo: f64, hi: f64) -> Self {
        self.range = Some((lo, hi));
        self
    }
}

/// The shape of a point marker.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Marker {
    /// Filled disc.
    Circle,
    /// Hollow circle.
    Ring,
    /// Filled square.
    Square,
    /// Filled triangle.
    Triangle,
    /// Diagonal cross.
    Cross,
}

/// A series of points: a line through them, a marker at each, or both.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// The legend entry (`None`: no entry).
    pub label: Option<String>,
    /// Colour of the line and markers.
    pub color: Rgb,
    /// The points, in drawing order.
    pub points: Vec<(f64, f64)>,
    /// Join consecutive points by a line.
    pub line: bool,
    /// A marker at each point.
    pub marker: Option<Marker>,
    /// Line width in pixels (also the stroke of hollow markers).
    pub width: u32,
    /// Marker size (radius) in pixels.
    pub marker_size: u32,
}

impl Series {
    /// A line through `points`.
    pub fn line(label: impl Into<String>, color: Rgb, points: Vec<(f64, f64)>) -> Self {
        Series {
            label: Some(label.into()),
            color,
            points,
            line: true,
            marker: None,
            width: 2,
            marker_size: 4,
        }
    }

    /// A marker at each of `points`, no line.
    pub fn scatter(
        label: impl Into<String>,
        color: Rgb,
        marker: Marker,
        points: Vec<(f64, f64)>,
    ) -> Self {
        Series {
            label: Some(label.into()),
            color,
            points,
            line: false,
            marker: Some(marker),
            width: 2,
            marker_size: 4,
        }
    }

    /// The same series with a marker at each point as well.
    pub fn with_marker(mut self, marker: Marker) -> Self {
        self.marker = Some(marker);
        self
    }

    /// The same series without a legend entry.
    pub fn unlabelled(mut self) -> Self {
        self.label = None;
        self
    }
}

/// Many lines, each with its own colour, under one legend entry: the
/// worldlines of a space-time diagram, for example.
#[derive(Debug, Clone, PartialEq)]
pub struct Polylines {
    /// The legend entry (`None`: no entry); it shows the first line's colour.
    pub label: Option<String>,
    /// The lines: colour and points.
    pub lines: Vec<(Rgb, Vec<(f64, f64)>)>,
    /// Line width in pixels.
    pub width: u32,
}

/// Where the legend goes: beside the plot (never over the data) or in a
/// corner of the plotting area.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LegendPosition {
    /// To the right of the plotting area, outside it (the default).
    Right,
    /// Top left corner.
    UpperLeft,
    /// Top right corner.
    UpperRight,
    /// Bottom left corner.
    LowerLeft,
    /// Bottom right corner.
    LowerRight,
}

/// An x/y chart.
#[derive(Debug, Clone, PartialEq)]
pub struct Chart {
    /// The title, above the plot.
    pub title: String,
    /// The horizontal axis.
    pub x: Axis,
    /// The vertical axis.
    pub y: Axis,
    /// Many-line groups, drawn first (below the series).
    pub polylines: Vec<Polylines>,
    /// Series, drawn in order.
    pub series: Vec<Series>,
    /// Image size in pixels.
    pub size: (u32, u32),
    /// Legend position.
    pub legend: LegendPosition,
}

impl Chart {
    /// An empty 1100 × 640 chart, legend on the right.
    pub fn new(title: impl Into<String>, x: Axis, y: Axis) -> Self {
        Chart {
            title: title.into(),
            x,
            y,
            polylines: Vec::new(),
            series: Vec::new(),
            size: (1100, 640),
            legend: LegendPosition::Right,
        }
    }
}

/// One cell of a [`Grid`].
#[derive(Debug, Clone, PartialEq)]
pub struct Cell {
    /// Row index (0 = top).
    pub row: usize,
    /// Column index (0 = left).
    pub column: usize,
    /// One square per colour, side by side.
    pub colors: Vec<Rgb>,
    /// A short text under the squares (`None`: none).
    pub text: Option<String>,
}

/// A table of coloured markers with row and column labels and a colour
/// legend.
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    /// The title.
    pub title: String,
    /// Row labels, top to bottom.
    pub rows: Vec<String>,
    /// Column labels, left to right.
    pub columns: Vec<String>,
    /// The cells (any subset of rows × columns).
    pub cells: Vec<Cell>,
    /// The legend: what each colour means.
    pub legend: Vec<(String, Rgb)>,
}

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

// ---------------------------------------------------------------------------
// Fonts.

/// Where a TrueType font is looked for, after `$STICKY_FONT`.
pub const FONT_PATHS: [&str; 12] = [
    "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/TTF/DejaVuSans.ttf",
    "/usr/share/fonts/dejavu/DejaVuSans.ttf",
    "/usr/share/fonts/dejavu-sans-fonts/DejaVuSans.ttf",
    "/usr/share/fonts/truetype/liberation/LiberationSans-Regular.ttf",
    "/usr/share/fonts/liberation-sans/LiberationSans-Regular.ttf",
    "/usr/share/fonts/truetype/noto/NotoSans-Regular.ttf",
    "/usr/share/fonts/noto/NotoSans-Regular.ttf",
    "/usr/share/fonts/truetype/freefont/FreeSans.ttf",
    "/System/Library/Fonts/Supplemental/Arial.ttf",
    "/Library/Fonts/Arial.ttf",
    "C:\\Windows\\Fonts\\arial.ttf",
];

/// The font family name registered with plotters.
const FAMILY: &str = "sans-serif";

/// Whether PNG files can be written.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum PngSupport {
    /// A TrueType font was found and registered: PNGs are written.
    Font(PathBuf),
    /// No usable font: only SVGs are written; the reason.
    Skipped(String),
}

static FONT: OnceLock<PngSupport> = OnceLock::new();

/// Finds and registers a font, once per process; says whether PNGs can be
/// written.
pub fn png_support() -> &'static PngSupport {
    FONT.get_or_init(register_font)
}

fn register_font() -> PngSupport {
    let mut candidates: Vec<PathBuf> = Vec::new();
    let chosen = std::env::var_os("STICKY_FONT");
    let disabled = chosen.as_ref().is_some_and(|p| p == "none");
    if let Some(p) = chosen.filter(|_| !disabled) {
        candidates.push(PathBuf::from(p));
    }
    if !disabled {
        candidates.extend(FONT_PATHS.iter().map(PathBuf::from));
    }
    for path in candidates {
        let Ok(bytes) = fs::read(&path) else {
            continue;
        };
        // plotters keeps `&'static` font data: one font per process is
        // leaked on purpose (the registration happens once).
        let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
        if plotters::style::register_font(FAMILY, FontStyle::Normal, bytes).is_ok() {
            return PngSupport::Font(path);
        }
    }
    let metrics: &'static [u8] = Box::leak(metrics_only_font().into_boxed_slice());
    let why = if plotters::style::register_font(FAMILY, FontStyle::Normal, metrics).is_ok() {
        "no TrueType font found (set STICKY_FONT to a .ttf file); PNG skipped, SVG written"
    } else {
        "no TrueType font found and the built-in metrics font was refused; PNG skipped"
    };
    PngSupport::Skipped(why.to_string())
}

/// A minimal TrueType font with one empty glyph 0.6 em wide (tables `head`,
/// `hhea`, `hmtx`, `maxp`): enough for plotters to measure text, so that SVG
/// files can be laid out without a real font. Every character maps to the
/// empty glyph.
fn metrics_only_font() -> Vec<u8> {
    fn be16(v: &mut Vec<u8>, x: u16) {
        v.extend_from_slice(&x.to_be_bytes());
    }
    fn be32(v: &mut Vec<u8>, x: u32) {
        v.extend_from_slice(&x.to_be_bytes());
    }
    const UNITS: u16 = 1000;
    let mut head = Vec::with_capacity(54);
    be32(&mut head, 0x0001_0000); // version
    be32(&mut head, 0x0001_0000); // fontRevision
    be32(&mut head, 0); // checkSumAdjustment
    be32(&mut head, 0x5F0F_3CF5); // magicNumber
    be16(&mut head, 0); // flags
    be16(&mut head, UNITS); // unitsPerEm
    head.extend_from_slice(&[0; 16]); // created, modified
    for v in [0u16, (-236i16) as u16, 600, 928] {
        be16(&mut head, v); // xMin, yMin, xMax, yMax
    }
    be16(&mut head, 0); // macStyle
    be16(&mut head, 8); // lowestRecPPEM
    be16(&mut head, 2); // fontDirectionHint
    be16(&mut head, 0); // indexToLocFormat
    be16(&mut head, 0); // glyphDataFormat
    let mut hhea = Vec::with_capacity(36);
    be32(&mut hhea, 0x0001_0000);
    be16(&mut hhea, 928); // ascender
    be16(&mut hhea, (-236i16) as u16); // descender
    be16(&mut hhea, 0); // lineGap
    be16(&mut hhea, 600); // advanceWidthMax
    hhea.extend_from_slice(&[0; 22]); // minLSB … metricDataFormat
    be16(&mut hhea, 1); // numberOfHMetrics
    let mut hmtx = Vec::new();
    be16(&mut hmtx, 600); // advanceWidth
    be16(&mut hmtx, 0); // lsb
    let mut maxp = Vec::new();
    be32(&mut maxp, 0x0000_5000);
    be16(&mut maxp, 1); // numGlyphs
    let tables: [(&[u8; 4], Vec<u8>); 4] = [
        (b"head", head),
        (b"hhea", hhea),
        (b"hmtx", hmtx),
        (b"maxp", maxp),
    ];
    let mut out = Vec::new();
    be32(&mut out, 0x0001_0000);
    be16(&mut out, tables.len() as u16);
    be16(&mut out, 64); // searchRange
    be16(&mut out, 2); // entrySelector
    be16(&mut out, 0); // rangeShift
    let mut offset = 12 + 16 * tables.len();
    let mut body = Vec::new();
    for (tag, data) in &tables {
        let checksum = data
            .chunks(4)
            .map(|c| {
                let mut w = [0u8; 4];
                w[..c.len()].copy_from_slice(c);
                u32::from_be_bytes(w)
            })
            .fold(0u32, u32::wrapping_add);
        out.extend_from_slice(&tag[..]);
        be32(&mut out, checksum);
        be32(&mut out, offset as u32);
        be32(&mut out, data.len() as u32);
        body.extend_from_slice(data);
        while body.len() % 4 != 0 {
            body.push(0);
        }
        offset = 12 + 16 * tables.len() + body.len();
    }
    out.extend_from_slice(&body);
    out
}

// ---------------------------------------------------------------------------
// Writing files.

/// Writes `chart` as `dir/stem.svg` and `dir/stem.png` (PNG only when a font
/// was found); `dir` is created if needed.
pub fn write_chart(chart: &Chart, dir: &Path, stem: &str) -> Result<Written, PlotError> {
    write_figure(dir, stem, chart.size, |area| draw_chart(area, chart))
}

/// Writes `grid` as `dir/stem.svg` and `dir/stem.png` (PNG only when a font
/// was found); `dir` is created if needed.
pub fn write_grid(grid: &Grid, dir: &Path, stem: &str) -> Result<Written, PlotError> {
    let size = grid_size(grid);
    write_figure(dir, stem, size, |area| draw_grid(area, grid))
}

/// Writes `contents` to `path` whole: a temporary file in the same folder,
/// then a rename.
/// ([`crate::report::io::write_whole`], its one definition).
pub fn write_whole(path: &Path, contents: &[u8]) -> Result<(), PlotError> {
    crate::report::io::write_whole(path, contents).map_err(|e| PlotError::Io {
        path: path.to_path_buf(),
        message: e.to_string(),
    })
}

/// `dir/.name.partial-PID.ext`: a hidden sibling of `path` ending in `ext`
/// (the PNG encoder picks its format from the extension).
fn temporary(path: &Path, ext: &str) -> PathBuf {
    let name = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    path.with_file_name(format!(".{name}.partial-{}.{ext}", std::process::id()))
}

fn write_figure<F>(dir: &Path, stem: &str, size: (u32, u32), draw: F) -> Result<Written, PlotError>
where
    F: Fn(&mut dyn FigureArea) -> Result<(), String>,
{
    if stem.is_empty() || stem.contains(['/', '\\']) || stem.starts_with('.') {
        return Err(PlotError::BadName {
            stem: stem.to_string(),
        });
    }
    fs::create_dir_all(dir).map_err(|e| PlotError::Io {
        path: dir.to_path_buf(),
        message: e.to_string(),
    })?;
    let support = png_support();
    let svg = dir.join(format!("{stem}.svg"));
    let mut text = String::new();
    {
        let root = SVGBackend::with_string(&mut text, size).into_drawing_area();
        let mut area = Area(root);
        draw(&mut area).map_err(|message| PlotError::Draw {
            path: svg.clone(),
            message,
        })?;
        area.0.present().map_err(|e| PlotError::Draw {
            path: svg.clone(),
            message: e.to_string(),
        })?;
    }
    write_whole(&svg, text.as_bytes())?;
    let png = match support {
        PngSupport::Skipped(_) => None,
        PngSupport::Font(_) => {
            let path = dir.join(format!("{stem}.png"));
            let tmp = temporary(&path, "png");
            let drawn = {
                let root = BitMapBackend::new(&tmp, size).into_drawing_area();
                let mut area = Area(root);
                draw(&mut area).and_then(|()| area.0.present().map_err(|e| e.to_string()))
            };
            if let Err(message) = drawn {
                let _ = fs::remove_file(&tmp);
                return Err(PlotError::Draw { path, message });
            }
            fs::rename(&tmp, &path).map_err(|e| {
                let _ = fs::remove_file(&tmp);
                PlotError::Io {
                    path: path.clone(),
                    message: e.to_string(),
                }
            })?;
            Some(path)
        }
    };
    Ok(Written { svg, png })
}

/// The drawing area of one backend, behind a trait object so that one
/// drawing routine serves SVG and PNG.
trait FigureArea {
    fn chart(&mut self, chart: &Chart) -> Result<(), String>;
    fn grid(&mut self, grid: &Grid) -> Result<(), String>;
}

struct Area<DB: DrawingBackend>(DrawingArea<DB, Shift>);

impl<DB: DrawingBackend> FigureArea for Area<DB> {
    fn chart(&mut self, chart: &Chart) -> Result<(), String> {
        chart_on(&self.0, chart)
    }
    fn grid(&mut self, grid: &Grid) -> Result<(), String> {
        grid_on(&self.0, grid)
    }
}

fn draw_chart(area: &mut dyn FigureArea, chart: &Chart) -> Result<(), String> {
    area.chart(chart)
}

fn draw_grid(area: &mut dyn FigureArea, grid: &Grid) -> Result<(), String> {
    area.grid(grid)
}

// ---------------------------------------------------------------------------
// Charts.

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
fn tick(v: f64, scale: Scale) -> String {
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

fn chart_on<DB: DrawingBackend>(
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
    marker: Option<Marker>,
    size: u32,
    width: u32,
}

fn legend_entries(chart: &Chart) -> Vec<Entry> {
    let mut out = Vec::new();
    for g in &chart.polylines {
        if let Some(label) = &g.label {
            out.push(Entry {
                label: label.clone(),
                color: g.lines.first().map_or(BLACK_RGB, |l| l.0),
                line: true,
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
            area.draw(&PathElement::new(
                vec![(x, y), (x + 24, y)],
                color.stroke_width(e.width),
            ))
            .map_err(|e| err(&e))?;
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
        let size = s.marker_size;
        if let Some(m) = s.marker {
            if s.line {
                ctx.draw_series(std::iter::once(PathElement::new(pts.clone(), stroke)))
                    .map_err(|e| err(&e))?;
            }
            let (fill, outline) = shape(m, size);
            let anno = ctx
                .draw_series(pts.iter().map(|&p| {
                    EmptyElement::at(p)
                        + Polygon::new(fill.clone(), color.filled())
                        + PathElement::new(outline.clone(), stroke)
                }))
                .map_err(|e| err(&e))?;
            if let Some(label) = &s.label {
                let (line, w) = (s.line, s.width.max(2));
                anno.label(label.as_str()).legend(move |(x, y)| {
                    let glyph_line = if line {
                        vec![(x, y), (x + 20, y)]
                    } else {
                        Vec::new()
                    };
                    EmptyElement::at((x + 10, y))
                        + PathElement::new(
                            glyph_line
                                .iter()
                                .map(|&(a, b)| (a - x - 10, b - y))
                                .collect::<Vec<_>>(),
                            color.stroke_width(w),
                        )
                        + Polygon::new(fill.clone(), color.filled())
                        + PathElement::new(outline.clone(), color.stroke_width(w))
                });
                labelled = true;
            }
        } else {
            let anno = ctx
                .draw_series(std::iter::once(PathElement::new(pts, stroke)))
                .map_err(|e| err(&e))?;
            if let Some(label) = &s.label {
                let w = s.width.max(2);
                anno.label(label.as_str()).legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(w))
                });
                labelled = true;
            }
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

// ---------------------------------------------------------------------------
// Grids.

const CELL_W: u32 = 150;
const CELL_H: u32 = 46;
const TITLE_H: u32 = 44;
const HEADER_H: u32 = 36;
const LEGEND_LINE: u32 = 26;
const MARGIN: u32 = 16;

/// Approximate text width in pixels (0.6 em per character).
fn text_width(s: &str, size: u32) -> u32 {
    (s.chars().count() as u32 * size * 6).div_ceil(10)
}

fn label_width(grid: &Grid) -> u32 {
    grid.rows
        .iter()
        .map(|r| text_width(r, 14))
        .max()
        .unwrap_or(0)
        + 2 * MARGIN
}

fn legend_lines(grid: &Grid, width: u32) -> Vec<Vec<usize>> {
    let mut lines: Vec<Vec<usize>> = Vec::new();
    let mut used = width; // forces a first line
    for (i, (name, _)) in grid.legend.iter().enumerate() {
        let w = 24 + text_width(name, 14) + 24;
        if used + w > width.saturating_sub(2 * MARGIN) || lines.is_empty() {
            lines.push(Vec::new());
            used = 0;
        }
        used += w;
        if let Some(last) = lines.last_mut() {
            last.push(i);
        }
    }
    lines
}

fn grid_size(grid: &Grid) -> (u32, u32) {
    let cols = grid.columns.len().max(1) as u32;
    let rows = grid.rows.len().max(1) as u32;
    let width =
        (label_width(grid) + cols * CELL_W + MARGIN).max(text_width(&grid.title, 20) + 2 * MARGIN);
    let legend = legend_lines(grid, width).len() as u32;
    let height = TITLE_H + HEADER_H + rows * CELL_H + MARGIN + legend * LEGEND_LINE + MARGIN;
    (width, height)
}

fn grid_on<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, grid: &Grid) -> Result<(), String> {
    let err = |e: &dyn fmt::Display| e.to_string();
    root.fill(&WHITE).map_err(|e| err(&e))?;
    let (width, _) = grid_size(grid);
    let left = label_width(grid) as i32;
    let font = |size: u32, h: HPos, v: VPos| {
        TextStyle::from((FAMILY, size).into_font())
            .color(&BLACK)
            .pos(Pos::new(h, v))
    };
    root.draw(&Text::new(
        grid.title.clone(),
        (width as i32 / 2, (TITLE_H / 2) as i32),
        font(20, HPos::Center, VPos::Center),
    ))
    .map_err(|e| err(&e))?;
    let top = (TITLE_H + HEADER_H) as i32;
    let (cw, ch) = (CELL_W as i32, CELL_H as i32);
    for (j, name) in grid.columns.iter().enumerate() {
        let x = left + cw * j as i32 + cw / 2;
        root.draw(&Text::new(
            name.clone(),
            (x, (TITLE_H + HEADER_H / 2) as i32),
            font(14, HPos::Center, VPos::Center),
        ))
        .map_err(|e| err(&e))?;
    }
    let line = RGBColor(200, 200, 200);
    for (i, name) in grid.rows.iter().enumerate() {
        let y = top + ch * i as i32;
        root.draw(&Text::new(
            name.clone(),
            (left - MARGIN as i32 / 2, y + ch / 2),
            font(14, HPos::Right, VPos::Center),
        ))
        .map_err(|e| err(&e))?;
    }
    let (rows, cols) = (grid.rows.len() as i32, grid.columns.len() as i32);
    for i in 0..=rows {
        let y = top + ch * i;
        root.draw(&PathElement::new(
            vec![(left, y), (left + cw * cols, y)],
            line,
        ))
        .map_err(|e| err(&e))?;
    }
    for j in 0..=cols {
        let x = left + cw * j;
        root.draw(&PathElement::new(
            vec![(x, top), (x, top + ch * rows)],
            line,
        ))
        .map_err(|e| err(&e))?;
    }
    for cell in &grid.cells {
        if cell.row >= grid.rows.len() || cell.column >= grid.columns.len() {
            continue;
        }
        let x0 = left + cw * cell.column as i32;
        let y0 = top + ch * cell.row as i32;
        let k = cell.colors.len().max(1) as i32;
        let side = ((cw - 16) / k)
            .min(if cell.text.is_some() { 18 } else { 24 })
            .max(4);
        let total = side * k + 2 * (k - 1);
        let sy = if cell.text.is_some() {
            y0 + 5
        } else {
            y0 + (ch - side) / 2
        };
        for (m, c) in cell.colors.iter().enumerate() {
            let sx = x0 + (cw - total) / 2 + m as i32 * (side + 2);
            root.draw(&Rectangle::new(
                [(sx, sy), (sx + side, sy + side)],
                c.color().filled(),
            ))
            .map_err(|e| err(&e))?;
        }
        if let Some(t) = &cell.text {
            root.draw(&Text::new(
                t.clone(),
                (x0 + cw / 2, y0 + ch - 4),
                font(11, HPos::Center, VPos::Bottom),
            ))
            .map_err(|e| err(&e))?;
        }
    }
    let mut y = top + ch * rows + MARGIN as i32 + LEGEND_LINE as i32 / 2;
    for entries in legend_lines(grid, width) {
        let mut x = MARGIN as i32;
        for i in entries {
            let (name, c) = &grid.legend[i];
            root.draw(&Rectangle::new(
                [(x, y - 8), (x + 16, y + 8)],
                c.color().filled(),
            ))
            .map_err(|e| err(&e))?;
            root.draw(&Text::new(
                name.clone(),
                (x + 22, y),
                font(14, HPos::Left, VPos::Center),
            ))
            .map_err(|e| err(&e))?;
            x += 24 + text_width(name, 14) as i32 + 24;
        }
        y += LEGEND_LINE as i32;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn metrics_font_parses() {
        let bytes: &'static [u8] = Box::leak(metrics_only_font().into_boxed_slice());
        assert!(
            plotters::style::register_font("sticky-test-metrics", FontStyle::Normal, bytes).is_ok()
        );
    }

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
}
