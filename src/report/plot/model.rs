//! The chart model: colours, axes, markers, line styles, series, charts
//! and grids — plain data that the drawing modules turn into pictures.

use plotters::style::RGBColor;

/// An RGB colour.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Rgb(pub u8, pub u8, pub u8);

impl Rgb {
    pub(super) fn color(self) -> RGBColor {
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
    /// Filled diamond.
    Diamond,
}

/// How a line is stroked.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dash {
    /// A continuous line.
    Solid,
    /// Long dashes.
    Dashed,
    /// Short dots.
    Dotted,
}

/// The look of one series among many: colour, marker and dash together.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SeriesStyle {
    /// Colour of the line and markers.
    pub color: Rgb,
    /// The marker.
    pub marker: Marker,
    /// The line's dash.
    pub dash: Dash,
}

/// The markers [`series_style`] cycles through.
const MARKERS: [Marker; 6] = [
    Marker::Circle,
    Marker::Square,
    Marker::Triangle,
    Marker::Cross,
    Marker::Ring,
    Marker::Diamond,
];

/// The style of the `i`-th of many series: the colour cycles through the ten
/// of [`PALETTE`], and each further round of ten changes the dash (solid,
/// dashed, dotted) and shifts the marker, so that no two of the first 30
/// series share colour, marker and dash, and series `i` and `i + 10` never
/// share both colour and marker.
pub fn series_style(i: usize) -> SeriesStyle {
    let round = i / PALETTE.len();
    SeriesStyle {
        color: palette(i),
        marker: MARKERS[(i + round) % MARKERS.len()],
        dash: [Dash::Solid, Dash::Dashed, Dash::Dotted][round % 3],
    }
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
    /// How the line is stroked.
    pub dash: Dash,
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
            dash: Dash::Solid,
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
            dash: Dash::Solid,
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

    /// The same series drawn in `style` (colour, dash, and a marker at each
    /// point).
    pub fn with_style(mut self, style: SeriesStyle) -> Self {
        self.color = style.color;
        self.dash = style.dash;
        self.marker = Some(style.marker);
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thirty_series_styles_are_distinct() {
        let styles: Vec<SeriesStyle> = (0..30).map(series_style).collect();
        for (i, a) in styles.iter().enumerate() {
            for (j, b) in styles.iter().enumerate().skip(i + 1) {
                assert_ne!(a, b, "series {i} and {j} look alike");
                if j == i + 10 {
                    assert!(a.marker != b.marker && a.dash != b.dash, "{i} and {j}");
                }
            }
        }
    }
}
