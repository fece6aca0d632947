//! The figure of a sweep over the angle of incidence (an oblique impact with friction): three panels on one x axis,
//! (a) the tangential restitution of the centre, (b) the rebound spin, (c) the rebound angle of the contact points,
//! each simulated (solid lines with markers) beside rigid-body theory with the same e (dashed), and the angle where
//! rigid-body theory changes from sticking to sliding marked in every panel.

use super::chart::{self, Axis, Chart, Colour, Layer, Mark, Marker, Stack, Stroke, fixed};
use super::figures::caption;

/// Canvas heights of the three panels, px: the first carries the title, the last the x axis's labels and the legend.
const HEIGHTS: [f64; 3] = [370.0, 330.0, 440.0];
/// Series with at most this many points show a marker at every point.
const MARKED: usize = 40;

/// What the incidence figure shows: a function of the sweep's table, nothing else.
#[derive(Debug, Clone, PartialEq)]
pub struct IncidenceFigure {
    pub title: String,
    /// The varied angle, with its unit.
    pub x_label: String,
    /// The body whose spin panel (b) shows: 1 or 2 (the CSV's `spin_after_1` or `spin_after_2`).
    pub spin_body: usize,
    pub series: Vec<IncidenceSeries>,
}

/// One law (and combination of the other varied keys): for each panel, the simulated and the rigid-body points
/// (x in degrees; `None` is a gap: a row without that value).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct IncidenceSeries {
    pub label: String,
    /// Panels (a), (b), (c): tangential restitution of the centre (after / before), rebound spin (rad/s, the
    /// magnitude), rebound angle of the contact points from the normal (degrees; negative: the slip reversed).
    pub simulated: [Vec<Option<(f64, f64)>>; 3],
    pub rigid: [Vec<Option<(f64, f64)>>; 3],
    /// Where rigid-body theory changes from sticking to sliding within the sweep, if it does.
    pub threshold: Option<Threshold>,
}

/// The rigid-body sliding threshold.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Threshold {
    /// At `x` on the figure's axis; `degrees` is the contact points' angle of incidence there.
    At { x: f64, degrees: f64 },
    /// Somewhere between two swept angles (the table does not locate it more closely).
    Between(f64, f64),
}

/// The three panels' headings and y axis labels.
fn panels(spin_body: usize) -> [(String, String); 3] {
    [
        (
            "(a) tangential restitution of the centre: tangential velocity after / before".into(),
            "tangential restitution".into(),
        ),
        (format!("(b) rebound spin of body {spin_body}"), "spin |ω| (rad/s)".into()),
        (
            "(c) rebound angle of the contact points from the normal (negative: the slip reversed)".into(),
            "rebound angle (°)".into(),
        ),
    ]
}

impl IncidenceFigure {
    /// Every known point of the figure's panel `panel`.
    fn known(&self, panel: usize) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.series.iter().flat_map(move |s| s.simulated[panel].iter().chain(&s.rigid[panel]).flatten().copied())
    }

    /// The x range of every panel: the whole quadrant, 0 to 90 degrees, when the swept angles cover half of it or
    /// more; else the swept angles, padded so that the end markers stand clear of the frame.
    fn x_range(&self) -> (f64, f64) {
        let (low, high) = (0..3)
            .flat_map(|panel| self.known(panel))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| (a.min(p.0), b.max(p.0)));
        if !low.is_finite() {
            (0.0, 90.0)
        } else if low == high {
            (low - 1.0, high + 1.0)
        } else if low >= 0.0 && high <= 90.0 && high - low >= 45.0 {
            (0.0, 90.0)
        } else {
            let pad = 0.02 * (high - low);
            (low - pad, high + pad)
        }
    }

    /// Panel `panel`'s y range: its values, padded; from zero for the spin (a magnitude), with zero for the rebound
    /// angle (its sign matters).
    fn y_range(&self, panel: usize) -> (f64, f64) {
        let start = if panel == 0 { (f64::INFINITY, f64::NEG_INFINITY) } else { (0.0, 0.0) };
        let (low, high) = self.known(panel).fold(start, |(a, b), p| (a.min(p.1), b.max(p.1)));
        if !low.is_finite() {
            return (0.0, 1.0);
        }
        let pad = 0.06 * (high - low);
        let low = if panel == 1 && low >= 0.0 { 0.0 } else { low - pad };
        (low, high + pad)
    }

    /// The distinct thresholds (to 0.05 degrees), each with the series it belongs to: `None` when it is every
    /// series' threshold.
    fn thresholds(&self) -> Vec<(Option<usize>, Threshold)> {
        let same = |a: &Threshold, b: &Threshold| match (a, b) {
            (Threshold::At { x: a, .. }, Threshold::At { x: b, .. }) => (a - b).abs() < 0.05,
            (Threshold::Between(a, b), Threshold::Between(c, d)) => a == c && b == d,
            _ => false,
        };
        let mut found: Vec<(Option<usize>, Threshold)> = Vec::new();
        for (i, series) in self.series.iter().enumerate() {
            let Some(threshold) = series.threshold else { continue };
            if !found.iter().any(|(_, t)| same(t, &threshold)) {
                found.push((Some(i), threshold));
            }
        }
        let shared = self.series.iter().all(|s| s.threshold.is_some_and(|t| same(&t, &found[0].1)));
        if found.len() == 1 && shared {
            found[0].0 = None;
        }
        found
    }
}

/// The colours of series `i` of `count`: simulated and rigid. One series: blue against black; several: each its
/// palette colour, the rigid line dashed in the same colour.
fn colours(i: usize, count: usize) -> (Colour, Colour) {
    let colour = chart::PALETTE[i % chart::PALETTE.len()];
    if count == 1 { (colour, Colour::BLACK) } else { (colour, colour) }
}

/// The figure as an SVG document.
pub fn svg(figure: &IncidenceFigure) -> String {
    stack(figure).svg()
}

/// The figure's three panels.
pub fn stack(figure: &IncidenceFigure) -> Stack {
    let (x0, x1) = figure.x_range();
    let count = figure.series.len();
    let thresholds = figure.thresholds();
    let mut charts = Vec::new();
    for (panel, (heading, y_label)) in panels(figure.spin_body).into_iter().enumerate() {
        let (y0, y1) = figure.y_range(panel);
        let title = if panel == 0 { caption(&figure.title, "") } else { String::new() };
        let mut chart = Chart::new(title, Axis::linear(figure.x_label.as_str(), x0, x1), Axis::linear(y_label, y0, y1));
        chart.heading = heading;
        chart.height = HEIGHTS[panel];
        let last = panel == 2;
        chart.x_labels = last;
        chart.legend_below = last;
        // The legend once, under the last panel: the styles are the same in every panel.
        let label = |layer: Layer, text: String, rank: i32| if last { layer.label(text).rank(rank) } else { layer };
        if y0 < 0.0 {
            chart.push(Layer::new("zero", Mark::HLine { y: 0.0, stroke: Stroke::solid(Colour::GREY, 0.8) }));
        }
        for (i, (start, end)) in thresholds.iter().filter_map(|(i, t)| match t {
            Threshold::Between(a, b) => Some((i, (*a, *b))),
            Threshold::At { .. } => None,
        }) {
            let span = Mark::Span { from: start, to: end, fill: Colour::GREY, opacity: 0.15 };
            let owner = i.map(|i| format!(" ({})", figure.series[i].label)).unwrap_or_default();
            let text = format!("rigid-body theory turns from sticking to sliding in this interval{owner}");
            chart.push(label(Layer::new("threshold", span), text, 2 * count as i32 + 1));
        }
        // All simulations, then all rigid-body lines over them (so that theory shows where the two agree); with
        // several series, each a little narrower than the one before, so that coinciding lines and markers still
        // show every colour.
        let narrowing = |i: usize| if count > 1 { 1.0 - 0.45 * i as f64 / (count - 1) as f64 } else { 1.0 };
        for (i, series) in figure.series.iter().enumerate() {
            let colour = colours(i, count).0;
            let shape = chart::SHAPES[i % chart::SHAPES.len()];
            let marked = series.simulated[panel].iter().flatten().count() <= MARKED;
            let (width, radius) = if count > 1 { (3.2 * narrowing(i), 5.5 * narrowing(i)) } else { (2.0, 4.0) };
            let text = if count > 1 {
                format!("simulation, {}", series.label)
            } else {
                format!("simulation ({})", series.label)
            };
            for (j, points) in runs(&series.simulated[panel]).into_iter().enumerate() {
                let marker = (marked || points.len() == 1).then(|| Marker::new(shape, radius, colour));
                let line = Mark::Line { points, stroke: Stroke::solid(colour, width), marker };
                let layer = Layer::new("simulated", line);
                chart.push(if j == 0 { label(layer, text.clone(), 2 * i as i32) } else { layer });
            }
        }
        for (i, series) in figure.series.iter().enumerate() {
            let colour = colours(i, count).1;
            let width = if count > 1 { 2.6 * narrowing(i) } else { 1.8 };
            let theory = if count > 1 {
                format!("rigid-body theory with the simulated e, {}", series.label)
            } else {
                "rigid-body theory with the simulated e".to_string()
            };
            for (j, points) in runs(&series.rigid[panel]).into_iter().enumerate() {
                let line = Mark::Line { points, stroke: Stroke::dashed(colour, width, 7.0, 4.0), marker: None };
                let layer = Layer::new("rigid", line);
                chart.push(if j == 0 { label(layer, theory.clone(), 2 * i as i32 + 1) } else { layer });
            }
        }
        for (i, threshold) in &thresholds {
            let Threshold::At { x, degrees } = *threshold else { continue };
            let colour = i.map_or(Colour::GREY, |i| colours(i, count).0);
            let line = Mark::VLine { x, stroke: Stroke::dashed(colour, 1.5, 2.0, 3.0) };
            let owner = i.map(|i| format!(" ({})", figure.series[i].label)).unwrap_or_default();
            let text = format!("rigid-body theory sticks below θ* = {}°, slides above{owner}", fixed(degrees, 1));
            chart.push(label(Layer::new("threshold", line), text, 2 * count as i32 + 2));
            if panel == 0 && thresholds.len() == 1 {
                // Which side is which, at the top of the first panel.
                for (text, anchor, shift) in [("rigid: sticks", "end", -6.0), ("rigid: slides", "start", 6.0)] {
                    let note = Mark::Note { at: (x, y1), offset: (shift, 22.0), text: text.into(), anchor, colour };
                    chart.push(Layer::new("threshold-note", note));
                }
            }
        }
        charts.push(chart);
    }
    Stack::new(charts)
}

/// The runs of known points between gaps.
fn runs(points: &[Option<(f64, f64)>]) -> Vec<Vec<(f64, f64)>> {
    points
        .split(Option::is_none)
        .filter(|run| !run.is_empty())
        .map(|run| run.iter().flatten().copied().collect())
        .collect()
}
