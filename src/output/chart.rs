//! A small chart model written as SVG with fractional coordinates: a title, two axes (linear or logarithmic),
//! layers of marks drawn in order (lines, markers, filled areas, shaded spans, reference lines) and a legend whose
//! symbols are drawn with the very style of the marks they name. The PNG of a figure is this SVG rasterised by
//! [`super::render`], so both always agree.
//!
//! Why not plotters: its backends take whole-pixel coordinates, draw dashed lines as separate segments (so a legend
//! cannot show the same dash pattern), and its bitmap backend does not anti-alias lines. Everything here is in
//! pixels of a [`WIDTH`] × [`HEIGHT`] canvas; data coordinates are whatever the axes hold (already scaled to the
//! units their labels name).

use super::render::{FONT_FAMILY, escape, text_width};
use std::fmt::Write;

/// Canvas width, px (one SVG unit is one PNG pixel).
pub const WIDTH: f64 = 960.0;
/// Canvas height, px.
pub const HEIGHT: f64 = 640.0;

/// Font sizes, px.
const TITLE_SIZE: f64 = 20.0;
const LABEL_SIZE: f64 = 17.0;
const HEADING_SIZE: f64 = 16.0;
const TICK_SIZE: f64 = 15.0;
const LEGEND_SIZE: f64 = 14.5;
const NOTE_SIZE: f64 = 14.5;
/// Outer padding of the canvas, px.
const PAD: f64 = 14.0;
/// Major and minor tick lengths, px (ticks point outwards).
const TICK_LENGTH: f64 = 5.0;
const MINOR_TICK_LENGTH: f64 = 3.0;
/// Least distance between major ticks on a linear x and y axis, px.
const X_SPACING: f64 = 80.0;
const Y_SPACING: f64 = 60.0;
/// Gap between a tick and its label, px.
const TICK_GAP: f64 = 4.0;
/// Ascent of DejaVu Sans (0.928 em) and the shift that centres digits on a line (half the cap height, 0.36 em).
const ASCENT: f64 = 0.93;
const MIDLINE: f64 = 0.36;
/// Superscripts (log-axis exponents): size and rise as fractions of the base size.
const SUPER_SIZE: f64 = 0.72;
const SUPER_RISE: f64 = 0.45;
/// Legend layout, px: the symbol's length, the gap to the text, a row's height, the box's inner padding, the gap
/// between the plot's frame and a legend inside it.
const SYMBOL: f64 = 36.0;
const SYMBOL_GAP: f64 = 8.0;
const ROW: f64 = LEGEND_SIZE * 1.55;
const LEGEND_PAD: f64 = 8.0;
const LEGEND_INSET: f64 = 10.0;
const COLUMN_GAP: f64 = 24.0;
/// Text and axes colour; grid colour.
const INK: &str = "#000000";
const GRID: &str = "#e3e3e3";

/// An opaque sRGB colour.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Colour(pub u8, pub u8, pub u8);

impl Colour {
    pub const BLACK: Colour = Colour(0, 0, 0);
    pub const WHITE: Colour = Colour(255, 255, 255);
    pub const GREY: Colour = Colour(110, 110, 110);

    /// `#rrggbb`.
    pub fn hex(self) -> String {
        format!("#{:02x}{:02x}{:02x}", self.0, self.1, self.2)
    }
}

/// Line colours in curve order (the tab10 palette, distinguishable in colour-vision deficiencies' common forms).
pub const PALETTE: [Colour; 10] = [
    Colour(31, 119, 180),
    Colour(255, 127, 14),
    Colour(44, 160, 44),
    Colour(214, 39, 40),
    Colour(148, 103, 189),
    Colour(140, 86, 75),
    Colour(227, 119, 194),
    Colour(127, 127, 127),
    Colour(188, 189, 34),
    Colour(23, 190, 207),
];

/// How a line is stroked: colour, width (px) and an optional dash pattern (dash, gap in px).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stroke {
    pub colour: Colour,
    pub width: f64,
    pub dash: Option<(f64, f64)>,
}

impl Stroke {
    pub fn solid(colour: Colour, width: f64) -> Stroke {
        Stroke { colour, width, dash: None }
    }

    pub fn dashed(colour: Colour, width: f64, dash: f64, gap: f64) -> Stroke {
        Stroke { colour, width, dash: Some((dash, gap)) }
    }

    /// The SVG presentation attributes of this stroke.
    fn attributes(&self) -> String {
        let mut text = format!("stroke=\"{}\" stroke-width=\"{}\"", self.colour.hex(), number(self.width));
        match self.dash {
            Some((dash, gap)) => {
                let _ = write!(text, " stroke-dasharray=\"{} {}\" stroke-linecap=\"butt\"", number(dash), number(gap));
            }
            None => text.push_str(" stroke-linecap=\"round\""),
        }
        text.push_str(" stroke-linejoin=\"round\"");
        text
    }
}

/// A marker's shape.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Shape {
    Circle,
    Square,
    Diamond,
    TriangleUp,
    TriangleDown,
}

/// Marker shapes in curve order (so curves stay distinct in grey-scale print).
pub const SHAPES: [Shape; 5] = [Shape::Circle, Shape::Square, Shape::TriangleUp, Shape::Diamond, Shape::TriangleDown];

/// A point marker: shape, radius (px), fill, and a thin edge that keeps overlapping markers apart.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Marker {
    pub shape: Shape,
    pub radius: f64,
    pub fill: Colour,
    pub edge: Colour,
}

impl Marker {
    pub fn new(shape: Shape, radius: f64, fill: Colour) -> Marker {
        Marker { shape, radius, fill, edge: Colour::WHITE }
    }

    /// This marker centred at (x, y) px.
    fn svg(&self, x: f64, y: f64) -> String {
        let paint = format!("fill=\"{}\" stroke=\"{}\" stroke-width=\"0.8\"", self.fill.hex(), self.edge.hex());
        let r = self.radius;
        let polygon = |corners: &[(f64, f64)]| {
            let points: Vec<String> =
                corners.iter().map(|(dx, dy)| format!("{},{}", number(x + dx * r), number(y + dy * r))).collect();
            format!("<polygon points=\"{}\" {paint}/>", points.join(" "))
        };
        match self.shape {
            Shape::Circle => format!("<circle cx=\"{}\" cy=\"{}\" r=\"{}\" {paint}/>", number(x), number(y), number(r)),
            // Equal areas: the square's half side is 0.886 r, the diamond's half diagonal 1.25 r.
            Shape::Square => polygon(&[(-0.886, -0.886), (0.886, -0.886), (0.886, 0.886), (-0.886, 0.886)]),
            Shape::Diamond => polygon(&[(0.0, -1.25), (1.25, 0.0), (0.0, 1.25), (-1.25, 0.0)]),
            Shape::TriangleUp => polygon(&[(0.0, -1.35), (1.17, 0.67), (-1.17, 0.67)]),
            Shape::TriangleDown => polygon(&[(0.0, 1.35), (1.17, -0.67), (-1.17, -0.67)]),
        }
    }
}

/// What a layer draws, in data coordinates.
#[derive(Debug, Clone, PartialEq)]
pub enum Mark {
    /// A polyline, optionally with a marker at every point.
    Line { points: Vec<(f64, f64)>, stroke: Stroke, marker: Option<Marker> },
    /// Markers alone.
    Points { points: Vec<(f64, f64)>, marker: Marker },
    /// A closed polygon, filled with `fill` at `opacity` (0 to 1), no outline.
    Area { points: Vec<(f64, f64)>, fill: Colour, opacity: f64 },
    /// Rectangles, each given by two opposite corners, filled with `fill` without anti-aliasing (neighbours meet
    /// without a seam), no outline: the cells of a map.
    Tiles { tiles: Vec<[(f64, f64); 2]>, fill: Colour },
    /// A band over the plot's whole height between two x values.
    Span { from: f64, to: f64, fill: Colour, opacity: f64 },
    /// A horizontal reference line across the plot at y.
    HLine { y: f64, stroke: Stroke },
    /// A vertical reference line over the plot's height at x.
    VLine { x: f64, stroke: Stroke },
    /// A text in the plot at a data point `at`, moved by `offset` px (x right, y down), anchored `start`, `middle`
    /// or `end`; never in the legend.
    Note { at: (f64, f64), offset: (f64, f64), text: String, anchor: &'static str, colour: Colour },
}

/// One layer of the chart: a mark, the SVG class it is written with (for readers and tests), and an optional
/// legend entry. Legend entries come in order of `rank` (then of the layers), whatever the drawing order.
#[derive(Debug, Clone, PartialEq)]
pub struct Layer {
    pub mark: Mark,
    pub class: &'static str,
    pub label: Option<String>,
    pub rank: i32,
}

impl Layer {
    pub fn new(class: &'static str, mark: Mark) -> Layer {
        Layer { mark, class, label: None, rank: 0 }
    }

    /// Names this layer in the legend.
    pub fn label(mut self, text: impl Into<String>) -> Layer {
        self.label = Some(text.into());
        self
    }

    /// Its place in the legend (lower first).
    pub fn rank(mut self, rank: i32) -> Layer {
        self.rank = rank;
        self
    }
}

/// An axis: its label (with units), its data range, linear or logarithmic (a log axis is widened to whole decades,
/// every one of them labelled 10^k, unless it is [`Axis::exact`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    pub label: String,
    pub low: f64,
    pub high: f64,
    pub log: bool,
    /// A log axis spans exactly [low, high] (a map's cells fill the plot), not whole decades.
    pub exact: bool,
}

impl Axis {
    pub fn linear(label: impl Into<String>, low: f64, high: f64) -> Axis {
        Axis { label: label.into(), low, high, log: false, exact: false }
    }

    pub fn log(label: impl Into<String>, low: f64, high: f64) -> Axis {
        Axis { label: label.into(), low, high, log: true, exact: false }
    }

    /// This axis spanning exactly its range.
    pub fn exact(self) -> Axis {
        Axis { exact: true, ..self }
    }

    /// The range drawn: finite and non-empty; whole decades on a log axis.
    fn span(&self) -> (f64, f64) {
        if self.log {
            let (low, high) = if self.low > 0.0 && self.high >= self.low && self.high.is_finite() {
                (self.low, self.high)
            } else {
                (0.1, 1.0)
            };
            if self.exact && high > low {
                return (low, high);
            }
            let first = (low.log10() + 1e-9).floor();
            let last = (high.log10() - 1e-9).ceil().max(first + 1.0);
            (10f64.powf(first), 10f64.powf(last))
        } else if !(self.low.is_finite() && self.high.is_finite()) {
            (0.0, 1.0)
        } else if self.high > self.low {
            (self.low, self.high)
        } else {
            let half = self.low.abs().max(1.0) * 0.05;
            (self.low - half, self.high + half)
        }
    }

    /// Where `value` falls, from 0 (low end) to 1 (high end).
    fn fraction(&self, value: f64) -> f64 {
        let (low, high) = self.span();
        if self.log {
            (value.max(f64::MIN_POSITIVE).log10() - low.log10()) / (high.log10() - low.log10())
        } else {
            (value - low) / (high - low)
        }
    }

    /// The ticks for an axis `length` px long, major ticks at least `spacing` px apart on a linear axis.
    fn ticks(&self, length: f64, spacing: f64) -> Ticks {
        let (low, high) = self.span();
        if self.log { log_ticks(low, high) } else { linear_ticks(low, high, (length / spacing).clamp(2.0, 12.0)) }
    }
}

/// A tick label: a plain number, or a power of ten written 10 with a superscript.
#[derive(Debug, Clone, PartialEq)]
enum Label {
    Plain(String),
    Power(i32),
}

impl Label {
    fn width(&self, size: f64) -> f64 {
        match self {
            Label::Plain(text) => text_width(text, size, false),
            Label::Power(k) => text_width("10", size, false) + text_width(&signed(*k), SUPER_SIZE * size, false),
        }
    }

    /// A `<text>` element with this label, its baseline at (x, y), anchored `start`, `middle` or `end`.
    fn svg(&self, class: &str, x: f64, y: f64, anchor: &str) -> String {
        let open = format!(
            "<text class=\"{class}\" x=\"{}\" y=\"{}\" font-size=\"{TICK_SIZE}\" text-anchor=\"{anchor}\" fill=\"{INK}\">",
            number(x),
            number(y)
        );
        match self {
            Label::Plain(text) => format!("{open}{}</text>", escape(text)),
            Label::Power(k) => format!(
                "{open}10<tspan dy=\"{}\" font-size=\"{}\">{}</tspan></text>",
                number(-SUPER_RISE * TICK_SIZE),
                number(SUPER_SIZE * TICK_SIZE),
                signed(*k)
            ),
        }
    }
}

/// An axis's ticks: labelled major ticks, unlabelled minor ones.
#[derive(Debug, Clone, PartialEq)]
struct Ticks {
    major: Vec<(f64, Label)>,
    minor: Vec<f64>,
}

/// An integer with a typographic minus sign.
fn signed(k: i32) -> String {
    if k < 0 { format!("\u{2212}{}", -i64::from(k)) } else { k.to_string() }
}

/// `value` with `decimals` decimals, a typographic minus sign, and no minus sign on a value that rounds to zero.
pub fn fixed(value: f64, decimals: usize) -> String {
    let text = format!("{value:.decimals$}");
    match text.strip_prefix('-') {
        Some(rest) if rest.chars().all(|c| c == '0' || c == '.') => rest.to_string(),
        Some(rest) => format!("\u{2212}{rest}"),
        None => text,
    }
}

/// `value` in `unit` with an SI prefix and `digits` significant digits, e.g. `172.8 mJ`.
pub fn si(value: f64, unit: &str, digits: usize) -> String {
    if value == 0.0 || !value.is_finite() {
        return format!("{} {unit}", fixed(value, 0));
    }
    let (factor, prefix) = prefix(value.abs());
    let scaled = value / factor;
    let magnitude = scaled.abs().log10().floor().max(0.0) as usize;
    format!("{} {prefix}{unit}", fixed(scaled, digits.saturating_sub(magnitude + 1)))
}

/// A scale for values up to `max` in magnitude: a factor and its SI prefix, so that `max / factor` reads between 1
/// and 1000 (nano to giga).
pub fn prefix(max: f64) -> (f64, &'static str) {
    let steps = [(1e-9, "n"), (1e-6, "µ"), (1e-3, "m"), (1.0, ""), (1e3, "k"), (1e6, "M"), (1e9, "G")];
    // A hair below each step, so that 999.9999999 µ still reads as µ and 1e-3 (rounding to 1e-3) reads as m.
    let magnitude = max.abs() * (1.0 + 1e-12);
    steps.iter().rev().find(|(factor, _)| magnitude >= *factor).map_or((1e-9, "n"), |&(f, p)| (f, p))
}

/// Linear ticks over [low, high]: the finest step of 1, 2, 2.5 or 5 times a power of ten that makes at most
/// `most` intervals, every label with the same number of decimals (the step's).
fn linear_ticks(low: f64, high: f64, most: f64) -> Ticks {
    let raw = (high - low) / most;
    let power = 10f64.powf(raw.log10().floor());
    let step = [1.0, 2.0, 2.5, 5.0, 10.0].map(|m| m * power).into_iter().find(|s| *s >= raw * (1.0 - 1e-9));
    let step = step.unwrap_or(10.0 * power);
    let decimals = (0..=15)
        .find(|&d| {
            let scaled = step * 10f64.powi(d);
            (scaled - scaled.round()).abs() < 1e-6 * scaled.max(1.0)
        })
        .unwrap_or(15) as usize;
    let first = (low / step - 1e-9).ceil();
    let last = (high / step + 1e-9).floor();
    let count = (last - first + 1.0).clamp(0.0, 200.0) as usize;
    let major = (0..count)
        .map(|i| {
            let value = (first + i as f64) * step;
            let value = if value.abs() < 1e-9 * step { 0.0 } else { value };
            (value, Label::Plain(fixed(value, decimals)))
        })
        .collect();
    Ticks { major, minor: Vec::new() }
}

/// Decade ticks over [low, high] (whole decades), each labelled 10^k (every second one past 12 decades), with
/// minor ticks at 2..9 times each decade.
/// (An exact axis's ends need not be decades: the decades and minor ticks inside it.)
fn log_ticks(low: f64, high: f64) -> Ticks {
    let first = (low.log10() - 1e-9).ceil() as i32;
    let last = (high.log10() + 1e-9).floor() as i32;
    let every = if last - first > 12 { 2 } else { 1 };
    let major = (first..=last).filter(|k| (k - first) % every == 0).map(|k| (10f64.powi(k), Label::Power(k))).collect();
    let inside = |v: &f64| *v >= low * (1.0 - 1e-9) && *v <= high * (1.0 + 1e-9);
    let minor =
        (first - 1..=last).flat_map(|k| (2..=9).map(move |m| f64::from(m) * 10f64.powi(k))).filter(inside).collect();
    Ticks { major, minor }
}

/// The pixel centre nearest to `position`, px: a 1-px line there covers one pixel column (or row) exactly, so the
/// frame, ticks and grid are crisp. Data keep their fractional positions.
fn crisp(position: f64) -> f64 {
    (position - 0.5).round() + 0.5
}

/// A number for an SVG attribute: at most two decimals, trailing zeros dropped.
pub fn number(value: f64) -> String {
    let text = format!("{value:.2}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    if text == "-0" { "0".into() } else { text.to_string() }
}

/// The plot area in canvas pixels.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Frame {
    left: f64,
    top: f64,
    right: f64,
    bottom: f64,
}

impl Frame {
    fn width(&self) -> f64 {
        self.right - self.left
    }

    fn height(&self) -> f64 {
        self.bottom - self.top
    }
}

/// A legend entry: the layer it names and its text's width.
struct Entry<'a> {
    layer: &'a Layer,
    text: &'a str,
    width: f64,
}

/// Where the legend goes: a box inside the plot at a top-left corner (px), or rows below the x axis's label.
enum Placement {
    Inside(f64, f64),
    Below { widths: Vec<f64>, rows: usize, left: f64, top: f64 },
}

/// A chart: a title, two axes, layers drawn in order, on a canvas of `width` × `height` px ([`WIDTH`] × [`HEIGHT`]
/// unless it is a panel of a [`Stack`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Chart {
    pub title: String,
    pub x: Axis,
    pub y: Axis,
    pub layers: Vec<Layer>,
    /// Canvas size, px.
    pub width: f64,
    pub height: f64,
    /// Whether the x axis's tick labels and label are written (a panel above another one with the same x axis
    /// leaves them to the panel below; its ticks stay).
    pub x_labels: bool,
    /// The least left edge of the plot area, px: stacked panels share the widest one's, so that their frames align.
    pub min_left: f64,
    /// Write the legend below the plot even when it would fit inside.
    pub legend_below: bool,
    /// A panel's heading, e.g. "(a) rebound spin": left-aligned over the plot area, under the title (if any).
    pub heading: String,
}

impl Chart {
    pub fn new(title: impl Into<String>, x: Axis, y: Axis) -> Chart {
        Chart {
            title: title.into(),
            x,
            y,
            layers: Vec::new(),
            width: WIDTH,
            height: HEIGHT,
            x_labels: true,
            min_left: 0.0,
            legend_below: false,
            heading: String::new(),
        }
    }

    pub fn push(&mut self, layer: Layer) {
        self.layers.push(layer);
    }

    /// The title's font size: the standard one, smaller if the title would not fit the canvas.
    fn title_size(&self) -> f64 {
        let width = text_width(&self.title, TITLE_SIZE, false);
        let room = self.width - 2.0 * PAD;
        if width > room { TITLE_SIZE * room / width } else { TITLE_SIZE }
    }

    /// The plot area, leaving `below` px under the x axis's label for a legend.
    fn frame(&self, below: f64) -> Frame {
        let top = if self.title.is_empty() { PAD + 8.0 } else { PAD + 1.2 * TITLE_SIZE + 14.0 };
        let top = if self.heading.is_empty() { top } else { top + HEADING_SIZE * 1.2 + 2.0 };
        let bottom = if self.x_labels {
            let superscript = if self.x.log { SUPER_RISE * TICK_SIZE } else { 0.0 };
            let x_ticks_height = TICK_LENGTH + TICK_GAP + superscript + 1.2 * TICK_SIZE;
            self.height - PAD - below - 1.2 * LABEL_SIZE - 6.0 - x_ticks_height
        } else {
            self.height - PAD - below - TICK_LENGTH
        };
        let y_ticks = self.y.ticks(bottom - top, Y_SPACING);
        let widest = y_ticks.major.iter().map(|(_, label)| label.width(TICK_SIZE)).fold(0.0, f64::max);
        let left = (PAD + 1.2 * LABEL_SIZE + 10.0 + widest + TICK_GAP + TICK_LENGTH).max(self.min_left);
        // Room on the right for half of a label that sits at the right end of the x axis.
        let mut right = self.width - PAD - 10.0;
        for (value, label) in self.x.ticks(right - left, X_SPACING).major {
            let x = left + self.x.fraction(value) * (right - left);
            let overhang = x + label.width(TICK_SIZE) / 2.0 - (self.width - PAD);
            if overhang > 0.0 {
                right -= overhang;
            }
        }
        Frame { left: crisp(left), top: crisp(top), right: crisp(right), bottom: crisp(bottom) }
    }

    /// Canvas position of a data point.
    fn pixel(&self, frame: &Frame, (x, y): (f64, f64)) -> (f64, f64) {
        (frame.left + self.x.fraction(x) * frame.width(), frame.bottom - self.y.fraction(y) * frame.height())
    }

    fn entries(&self) -> Vec<Entry<'_>> {
        let mut entries: Vec<Entry> = self
            .layers
            .iter()
            .filter(|layer| !matches!(layer.mark, Mark::Note { .. }))
            .filter_map(|layer| {
                layer.label.as_deref().map(|text| Entry { layer, text, width: text_width(text, LEGEND_SIZE, false) })
            })
            .collect();
        entries.sort_by_key(|entry| entry.layer.rank);
        entries
    }

    /// Canvas points that a legend inside the plot must not cover: the lines, markers and reference lines, sampled
    /// every 2 px (areas and spans are background).
    fn obstacles(&self, frame: &Frame) -> Vec<(f64, f64)> {
        let mut points = Vec::new();
        let mut trace = |path: &[(f64, f64)]| {
            for pair in path.windows(2) {
                let ((x0, y0), (x1, y1)) = (pair[0], pair[1]);
                let steps = ((x1 - x0).hypot(y1 - y0) / 2.0).ceil().clamp(1.0, 10_000.0) as usize;
                for i in 0..=steps {
                    let t = i as f64 / steps as f64;
                    points.push((x0 + t * (x1 - x0), y0 + t * (y1 - y0)));
                }
            }
            if path.len() == 1 {
                points.push(path[0]);
            }
        };
        for layer in &self.layers {
            match &layer.mark {
                Mark::Line { points: data, .. } | Mark::Points { points: data, .. } => {
                    let path: Vec<(f64, f64)> = data.iter().map(|&p| self.pixel(frame, p)).collect();
                    if matches!(layer.mark, Mark::Points { .. }) {
                        path.iter().for_each(|&p| trace(&[p]));
                    } else {
                        trace(&path);
                    }
                }
                Mark::HLine { y, .. } => {
                    let y = self.pixel(frame, (self.x.span().0, *y)).1;
                    trace(&[(frame.left, y), (frame.right, y)]);
                }
                Mark::VLine { x, .. } => {
                    let x = self.pixel(frame, (*x, self.y.span().0)).0;
                    trace(&[(x, frame.top), (x, frame.bottom)]);
                }
                Mark::Note { at, offset, text, anchor, .. } => {
                    let (x, y) = self.pixel(frame, *at);
                    let (x, y) = (x + offset.0, y + offset.1);
                    let width = text_width(text, NOTE_SIZE, false);
                    let left = match *anchor {
                        "middle" => x - width / 2.0,
                        "end" => x - width,
                        _ => x,
                    };
                    let (top, bottom) = (y - ASCENT * NOTE_SIZE, y + (1.2 - ASCENT) * NOTE_SIZE);
                    trace(&[(left, top), (left + width, top), (left + width, bottom), (left, bottom), (left, top)]);
                }
                Mark::Area { .. } | Mark::Span { .. } | Mark::Tiles { .. } => {}
            }
        }
        points.retain(|&(x, y)| x >= frame.left && x <= frame.right && y >= frame.top && y <= frame.bottom);
        points
    }

    /// The legend box's size, px, for entries in one column.
    fn box_size(entries: &[Entry]) -> (f64, f64) {
        let widest = entries.iter().map(|e| e.width).fold(0.0, f64::max);
        (2.0 * LEGEND_PAD + SYMBOL + SYMBOL_GAP + widest, 2.0 * LEGEND_PAD + entries.len() as f64 * ROW)
    }

    /// The first free spot inside the plot (corners first, then edge middles) for the legend box, if any.
    fn inside(&self, frame: &Frame, entries: &[Entry]) -> Option<(f64, f64)> {
        let (width, height) = Self::box_size(entries);
        if width > frame.width() - 2.0 * LEGEND_INSET || height > frame.height() - 2.0 * LEGEND_INSET {
            return None;
        }
        let (west, east) = (frame.left + LEGEND_INSET, frame.right - LEGEND_INSET - width);
        let (north, south) = (frame.top + LEGEND_INSET, frame.bottom - LEGEND_INSET - height);
        let (centre, middle) = ((frame.left + frame.right - width) / 2.0, (frame.top + frame.bottom - height) / 2.0);
        let candidates = [
            (east, north),
            (west, north),
            (east, south),
            (west, south),
            (centre, north),
            (centre, south),
            (east, middle),
            (west, middle),
        ];
        let obstacles = self.obstacles(frame);
        let margin = 5.0;
        candidates.into_iter().find(|&(x, y)| {
            !obstacles.iter().any(|&(px, py)| {
                px >= x - margin && px <= x + width + margin && py >= y - margin && py <= y + height + margin
            })
        })
    }

    /// The legend in columns below the x axis's label, filled column by column: each column's width (px), and
    /// the number of rows. As many columns as fit the canvas's width.
    fn below(&self, entries: &[Entry]) -> (Vec<f64>, usize) {
        let room = self.width - 2.0 * PAD;
        for columns in (1..=entries.len()).rev() {
            let rows = entries.len().div_ceil(columns);
            let widths: Vec<f64> = entries
                .chunks(rows)
                .map(|column| SYMBOL + SYMBOL_GAP + column.iter().map(|e| e.width).fold(0.0, f64::max))
                .collect();
            let total = widths.iter().sum::<f64>() + (widths.len() - 1) as f64 * COLUMN_GAP;
            if total <= room || columns == 1 {
                return (widths, rows);
            }
        }
        (Vec::new(), 0)
    }

    /// The chart as a standalone SVG document.
    pub fn svg(&self) -> String {
        let (frame, content) = self.content("plot-area");
        let mut svg = svg_document(self.width, self.height, 64 * 1024);
        svg.push_str(&clip_path("plot-area", &frame));
        svg.push_str(&content);
        svg.push_str("</svg>\n");
        svg
    }

    /// The plot area and everything drawn on the canvas but its background: the title, grid, layers (clipped by
    /// the clip path `clip`, which the caller defines over the plot area), axes and legend.
    fn content(&self, clip: &str) -> (Frame, String) {
        let entries = self.entries();
        let mut frame = self.frame(0.0);
        let inside = if self.legend_below { None } else { self.inside(&frame, &entries) };
        let placement = if entries.is_empty() {
            None
        } else if let Some((x, y)) = inside {
            Some(Placement::Inside(x, y))
        } else {
            let (widths, rows) = self.below(&entries);
            let height = rows as f64 * ROW + 6.0;
            frame = self.frame(height);
            let total = widths.iter().sum::<f64>() + (widths.len().max(1) - 1) as f64 * COLUMN_GAP;
            // Centred under the plot, inside the canvas.
            let left = ((frame.left + frame.right - total) / 2.0).min(self.width - PAD - total).max(PAD);
            Some(Placement::Below { widths, rows, left, top: self.height - PAD - height + 6.0 })
        };

        let mut svg = String::with_capacity(64 * 1024);
        if !self.title.is_empty() {
            let size = self.title_size();
            let _ = writeln!(
                svg,
                "<text class=\"title\" x=\"{}\" y=\"{}\" font-size=\"{}\" text-anchor=\"middle\" fill=\"{INK}\">{}</text>",
                number(self.width / 2.0),
                number(PAD + ASCENT * size),
                number(size),
                escape(&self.title)
            );
        }
        if !self.heading.is_empty() {
            let _ = writeln!(
                svg,
                "<text class=\"heading\" x=\"{}\" y=\"{}\" font-size=\"{HEADING_SIZE}\" fill=\"{INK}\">{}</text>",
                number(frame.left),
                number(frame.top - 8.0),
                escape(&self.heading)
            );
        }
        let x_ticks = self.x.ticks(frame.width(), X_SPACING);
        let y_ticks = self.y.ticks(frame.height(), Y_SPACING);
        self.grid(&mut svg, &frame, &x_ticks, &y_ticks);
        self.data(&mut svg, &frame, clip);
        self.axes(&mut svg, &frame, &x_ticks, &y_ticks);
        match placement {
            Some(Placement::Inside(x, y)) => legend_box(&mut svg, &entries, x, y),
            Some(Placement::Below { widths, rows, left, top }) => {
                legend_columns(&mut svg, &entries, &widths, rows, left, top)
            }
            None => {}
        }
        (frame, svg)
    }

    /// Light grid lines at the major ticks, under the data.
    fn grid(&self, svg: &mut String, frame: &Frame, x_ticks: &Ticks, y_ticks: &Ticks) {
        svg.push_str("<g class=\"grid\" fill=\"none\" stroke=\"");
        svg.push_str(GRID);
        svg.push_str("\" stroke-width=\"1\">\n");
        for (value, _) in &x_ticks.major {
            let x = crisp(frame.left + self.x.fraction(*value) * frame.width());
            let _ = writeln!(
                svg,
                "<line x1=\"{x}\" y1=\"{}\" x2=\"{x}\" y2=\"{}\"/>",
                number(frame.top),
                number(frame.bottom),
                x = number(x)
            );
        }
        for (value, _) in &y_ticks.major {
            let y = crisp(frame.bottom - self.y.fraction(*value) * frame.height());
            let _ = writeln!(
                svg,
                "<line x1=\"{}\" y1=\"{y}\" x2=\"{}\" y2=\"{y}\"/>",
                number(frame.left),
                number(frame.right),
                y = number(y)
            );
        }
        svg.push_str("</g>\n");
    }

    /// The layers, clipped to the plot area (markers unclipped, but only those inside it).
    fn data(&self, svg: &mut String, frame: &Frame, clip: &str) {
        let inside = |&(x, y): &(f64, f64)| {
            x >= frame.left - 0.5 && x <= frame.right + 0.5 && y >= frame.top - 0.5 && y <= frame.bottom + 0.5
        };
        let polyline = |points: &[(f64, f64)]| -> String {
            points
                .iter()
                .map(|&p| self.pixel(frame, p))
                .map(|(x, y)| format!("{},{}", number(x), number(y)))
                .collect::<Vec<_>>()
                .join(" ")
        };
        for layer in &self.layers {
            let class = layer.class;
            let mut markers: Vec<(Marker, Vec<(f64, f64)>)> = Vec::new();
            let _ = write!(svg, "<g class=\"{class}\">");
            let clip = format!("clip-path=\"url(#{clip})\"");
            match &layer.mark {
                Mark::Line { points, stroke, marker } => {
                    let _ = write!(
                        svg,
                        "<polyline {clip} points=\"{}\" fill=\"none\" {}/>",
                        polyline(points),
                        stroke.attributes()
                    );
                    if let Some(marker) = marker {
                        markers.push((*marker, points.clone()));
                    }
                }
                Mark::Points { points, marker } => markers.push((*marker, points.clone())),
                Mark::Area { points, fill, opacity } => {
                    let _ = write!(
                        svg,
                        "<polygon {clip} points=\"{}\" fill=\"{}\" fill-opacity=\"{}\" stroke=\"none\"/>",
                        polyline(points),
                        fill.hex(),
                        number(*opacity)
                    );
                }
                Mark::Tiles { tiles, fill } => {
                    let mut path = String::with_capacity(48 * tiles.len());
                    for [a, b] in tiles {
                        let ((x0, y0), (x1, y1)) = (self.pixel(frame, *a), self.pixel(frame, *b));
                        let _ = write!(
                            path,
                            "M{} {}H{}V{}H{}Z",
                            number(x0),
                            number(y0),
                            number(x1),
                            number(y1),
                            number(x0)
                        );
                    }
                    let _ = write!(
                        svg,
                        "<path {clip} d=\"{path}\" fill=\"{}\" stroke=\"none\" shape-rendering=\"crispEdges\"/>",
                        fill.hex()
                    );
                }
                Mark::Span { from, to, fill, opacity } => {
                    let a = self.pixel(frame, (*from, 0.0)).0.clamp(frame.left, frame.right);
                    let b = self.pixel(frame, (*to, 0.0)).0.clamp(frame.left, frame.right);
                    let _ = write!(
                        svg,
                        "<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"{}\" fill-opacity=\"{}\" \
                         shape-rendering=\"crispEdges\"/>",
                        number(a.min(b)),
                        number(frame.top),
                        number((b - a).abs()),
                        number(frame.height()),
                        fill.hex(),
                        number(*opacity)
                    );
                }
                Mark::HLine { y, stroke } => {
                    let y = self.pixel(frame, (self.x.span().0, *y)).1;
                    if y >= frame.top - 0.5 && y <= frame.bottom + 0.5 {
                        let _ = write!(
                            svg,
                            "<line x1=\"{}\" y1=\"{y}\" x2=\"{}\" y2=\"{y}\" {}/>",
                            number(frame.left),
                            number(frame.right),
                            stroke.attributes(),
                            y = number(y)
                        );
                    }
                }
                Mark::VLine { x, stroke } => {
                    let x = self.pixel(frame, (*x, self.y.span().0)).0;
                    if x >= frame.left - 0.5 && x <= frame.right + 0.5 {
                        let _ = write!(
                            svg,
                            "<line x1=\"{x}\" y1=\"{}\" x2=\"{x}\" y2=\"{}\" {}/>",
                            number(frame.top),
                            number(frame.bottom),
                            stroke.attributes(),
                            x = number(x)
                        );
                    }
                }
                Mark::Note { at, offset, text, anchor, colour } => {
                    let (x, y) = self.pixel(frame, *at);
                    let _ = write!(
                        svg,
                        "<text x=\"{}\" y=\"{}\" font-size=\"{NOTE_SIZE}\" text-anchor=\"{anchor}\" fill=\"{}\">{}</text>",
                        number(x + offset.0),
                        number(y + offset.1),
                        colour.hex(),
                        escape(text)
                    );
                }
            }
            for (marker, points) in markers {
                for p in points.iter().map(|&p| self.pixel(frame, p)).filter(inside) {
                    svg.push_str(&marker.svg(p.0, p.1));
                }
            }
            svg.push_str("</g>\n");
        }
    }

    /// The frame, the ticks and their labels, the axis labels.
    fn axes(&self, svg: &mut String, frame: &Frame, x_ticks: &Ticks, y_ticks: &Ticks) {
        let _ = writeln!(
            svg,
            "<rect class=\"frame\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"none\" stroke=\"{INK}\" \
             stroke-width=\"1\"/>",
            number(frame.left),
            number(frame.top),
            number(frame.width()),
            number(frame.height())
        );
        let mut marks = String::new();
        let mut labels = String::new();
        let superscript = if self.x.log { SUPER_RISE * TICK_SIZE } else { 0.0 };
        let x_baseline = frame.bottom + TICK_LENGTH + TICK_GAP + superscript + ASCENT * TICK_SIZE;
        for (value, label) in &x_ticks.major {
            let x = crisp(frame.left + self.x.fraction(*value) * frame.width());
            tick(&mut marks, x, frame.bottom, x, frame.bottom + TICK_LENGTH);
            if self.x_labels {
                labels.push_str(&label.svg("tick-x", x, x_baseline, "middle"));
                labels.push('\n');
            }
        }
        for value in &x_ticks.minor {
            let x = crisp(frame.left + self.x.fraction(*value) * frame.width());
            tick(&mut marks, x, frame.bottom, x, frame.bottom + MINOR_TICK_LENGTH);
        }
        let y_anchor = frame.left - TICK_LENGTH - TICK_GAP;
        for (value, label) in &y_ticks.major {
            let y = crisp(frame.bottom - self.y.fraction(*value) * frame.height());
            tick(&mut marks, frame.left - TICK_LENGTH, y, frame.left, y);
            labels.push_str(&label.svg("tick-y", y_anchor, y + MIDLINE * TICK_SIZE, "end"));
            labels.push('\n');
        }
        for value in &y_ticks.minor {
            let y = crisp(frame.bottom - self.y.fraction(*value) * frame.height());
            tick(&mut marks, frame.left - MINOR_TICK_LENGTH, y, frame.left, y);
        }
        let _ = writeln!(svg, "<g class=\"ticks\" stroke=\"{INK}\" stroke-width=\"1\">{marks}</g>");
        svg.push_str(&labels);
        let x_label_baseline = x_baseline + (1.0 - ASCENT) * TICK_SIZE + 6.0 + ASCENT * LABEL_SIZE;
        if self.x_labels {
            let _ = writeln!(
                svg,
                "<text class=\"axis-label x\" x=\"{}\" y=\"{}\" font-size=\"{LABEL_SIZE}\" text-anchor=\"middle\" \
                 fill=\"{INK}\">{}</text>",
                number((frame.left + frame.right) / 2.0),
                number(x_label_baseline),
                escape(&self.x.label)
            );
        }
        let (x, y) = (PAD + ASCENT * LABEL_SIZE, (frame.top + frame.bottom) / 2.0);
        let _ = writeln!(
            svg,
            "<text class=\"axis-label y\" x=\"{x}\" y=\"{y}\" transform=\"rotate(-90 {x} {y})\" \
             font-size=\"{LABEL_SIZE}\" text-anchor=\"middle\" fill=\"{INK}\">{}</text>",
            escape(&self.y.label),
            x = number(x),
            y = number(y)
        );
    }
}

/// The opening of a standalone SVG document of `width` by `height` pixels on a white background (the caller adds
/// the content and `</svg>`), in a string of `capacity` bytes.
fn svg_document(width: f64, height: f64, capacity: usize) -> String {
    let mut svg = String::with_capacity(capacity);
    let _ = write!(
        svg,
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{w}\" height=\"{h}\" viewBox=\"0 0 {w} {h}\" \
         font-family=\"{FONT_FAMILY}, sans-serif\">\n<rect class=\"background\" width=\"{w}\" height=\"{h}\" \
         fill=\"#ffffff\"/>\n",
        w = number(width),
        h = number(height),
    );
    svg
}

/// The definition of a clip path `id` over the plot area `frame`.
fn clip_path(id: &str, frame: &Frame) -> String {
    format!(
        "<defs><clipPath id=\"{id}\"><rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"/></clipPath></defs>\n",
        number(frame.left),
        number(frame.top),
        number(frame.width()),
        number(frame.height())
    )
}

/// Charts stacked top to bottom on one canvas as wide as the widest: panels that share their x axis (a panel
/// above another usually hides its x labels, see [`Chart::x_labels`]) or simply belong together. The plot areas'
/// left edges are aligned. The first panel's title is the figure's.
#[derive(Debug, Clone, PartialEq)]
pub struct Stack {
    pub panels: Vec<Chart>,
}

impl Stack {
    pub fn new(panels: Vec<Chart>) -> Stack {
        Stack { panels }
    }

    /// The canvas size, px.
    pub fn size(&self) -> (f64, f64) {
        let width = self.panels.iter().map(|p| p.width).fold(0.0, f64::max);
        (width, self.panels.iter().map(|p| p.height).sum())
    }

    /// The panels as they are drawn: their left edges aligned on the widest.
    fn aligned(&self) -> Vec<Chart> {
        let left = self.panels.iter().map(|p| p.frame(0.0).left).fold(0.0, f64::max);
        self.panels.iter().map(|p| Chart { min_left: p.min_left.max(left), ..p.clone() }).collect()
    }

    /// The stack as a standalone SVG document; each panel is a group `<g class="panel">` moved into place, its
    /// data clipped by its own clip path.
    pub fn svg(&self) -> String {
        let (width, height) = self.size();
        let mut svg = svg_document(width, height, 128 * 1024);
        let mut top = 0.0;
        for (i, panel) in self.aligned().iter().enumerate() {
            let id = format!("plot-area-{}", i + 1);
            let (frame, content) = panel.content(&id);
            let _ = writeln!(svg, "<g class=\"panel\" transform=\"translate(0 {})\">", number(top));
            svg.push_str(&clip_path(&id, &frame));
            svg.push_str(&content);
            svg.push_str("</g>\n");
            top += panel.height;
        }
        svg.push_str("</svg>\n");
        svg
    }
}

fn tick(svg: &mut String, x1: f64, y1: f64, x2: f64, y2: f64) {
    let _ =
        write!(svg, "<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\"/>", number(x1), number(y1), number(x2), number(y2));
}

/// One legend entry, its symbol starting at x and centred on the row's middle line y.
fn entry(svg: &mut String, entry: &Entry, x: f64, y: f64) {
    svg.push_str("<g class=\"legend-entry\">");
    let line = |stroke: &Stroke| {
        format!(
            "<line class=\"legend-symbol\" x1=\"{}\" y1=\"{y}\" x2=\"{}\" y2=\"{y}\" {}/>",
            number(x + 2.0),
            number(x + SYMBOL - 2.0),
            stroke.attributes(),
            y = number(y)
        )
    };
    match &entry.layer.mark {
        Mark::Line { stroke, marker, .. } => {
            svg.push_str(&line(stroke));
            if let Some(marker) = marker {
                svg.push_str(&marker.svg(x + SYMBOL / 2.0, y));
            }
        }
        Mark::HLine { stroke, .. } | Mark::VLine { stroke, .. } => svg.push_str(&line(stroke)),
        Mark::Points { marker, .. } => svg.push_str(&marker.svg(x + SYMBOL / 2.0, y)),
        Mark::Note { .. } => {}
        Mark::Tiles { fill, .. } => {
            let _ = write!(
                svg,
                "<rect class=\"legend-symbol\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"{}\" stroke=\"#808080\" \
                 stroke-width=\"0.6\"/>",
                number(x + 2.0),
                number(y - 0.45 * LEGEND_SIZE),
                number(SYMBOL - 4.0),
                number(0.9 * LEGEND_SIZE),
                fill.hex()
            );
        }
        Mark::Area { fill, opacity, .. } | Mark::Span { fill, opacity, .. } => {
            let _ = write!(
                svg,
                "<rect class=\"legend-symbol\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"{}\" fill-opacity=\"{}\"/>",
                number(x + 2.0),
                number(y - 0.45 * LEGEND_SIZE),
                number(SYMBOL - 4.0),
                number(0.9 * LEGEND_SIZE),
                fill.hex(),
                number(*opacity)
            );
        }
    }
    let _ = writeln!(
        svg,
        "<text x=\"{}\" y=\"{}\" font-size=\"{LEGEND_SIZE}\" fill=\"{INK}\">{}</text></g>",
        number(x + SYMBOL + SYMBOL_GAP),
        number(y + MIDLINE * LEGEND_SIZE),
        escape(entry.text)
    );
}

/// The legend as a box at (x, y), one entry a row.
fn legend_box(svg: &mut String, entries: &[Entry], x: f64, y: f64) {
    let (width, height) = Chart::box_size(entries);
    let (x, y, width, height) = (crisp(x), crisp(y), width.round(), height.round());
    let _ = writeln!(
        svg,
        "<g class=\"legend\"><rect class=\"legend-box\" x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\" fill=\"#ffffff\" \
         fill-opacity=\"0.9\" stroke=\"#b0b0b0\" stroke-width=\"1\"/>",
        number(x),
        number(y),
        number(width),
        number(height)
    );
    for (i, e) in entries.iter().enumerate() {
        entry(svg, e, x + LEGEND_PAD, y + LEGEND_PAD + (i as f64 + 0.5) * ROW);
    }
    svg.push_str("</g>\n");
}

/// The legend in columns of `rows` entries (widths in px), the first row's top at `top`.
fn legend_columns(svg: &mut String, entries: &[Entry], widths: &[f64], rows: usize, left: f64, top: f64) {
    svg.push_str("<g class=\"legend\">\n");
    let mut x = left;
    for (column, width) in entries.chunks(rows.max(1)).zip(widths) {
        for (row, e) in column.iter().enumerate() {
            entry(svg, e, x, top + (row as f64 + 0.5) * ROW);
        }
        x += width + COLUMN_GAP;
    }
    svg.push_str("</g>\n");
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_ticks_share_their_decimals() {
        let ticks = linear_ticks(0.0, 1.0, 4.0);
        let labels: Vec<_> = ticks.major.iter().map(|(_, l)| l.clone()).collect();
        let texts: Vec<String> = labels
            .iter()
            .map(|l| match l {
                Label::Plain(t) => t.clone(),
                Label::Power(_) => String::new(),
            })
            .collect();
        assert_eq!(texts, ["0.00", "0.25", "0.50", "0.75", "1.00"]);
        let ticks = linear_ticks(-1.1, 1.1, 5.0);
        assert!(ticks.major.iter().any(|(v, l)| *v == 0.0 && *l == Label::Plain("0.0".into())));
        assert!(ticks.major.iter().any(|(_, l)| *l == Label::Plain("\u{2212}1.0".into())));
    }

    #[test]
    fn log_axes_label_every_decade() {
        let axis = Axis::log("x", 0.013, 87.0);
        assert_eq!(axis.span(), (0.01, 100.0));
        let ticks = axis.ticks(800.0, X_SPACING);
        let powers: Vec<_> = ticks.major.iter().map(|(_, l)| l.clone()).collect();
        assert_eq!(powers, [-2, -1, 0, 1, 2].map(Label::Power));
        assert_eq!(ticks.minor.len(), 32);
    }

    #[test]
    fn numbers_read_well() {
        assert_eq!(number(12.0), "12");
        assert_eq!(number(12.345), "12.35");
        assert_eq!(number(-0.001), "0");
        assert_eq!(fixed(-0.0001, 3), "0.000");
        assert_eq!(fixed(-0.8, 3), "\u{2212}0.800");
        assert_eq!(si(0.17281, "J", 4), "172.8 mJ");
        assert_eq!(si(2.5e-5, "s", 3), "25.0 µs");
        assert_eq!(prefix(54e-6), (1e-6, "µ"));
    }
}
