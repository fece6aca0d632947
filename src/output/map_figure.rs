//! The idealisation map (`impact sweep --map`): a grid over two varied quantities, each cell coloured by the first
//! assumption of the instantaneous impact that fails there, in the order of severity
//! ([`crate::idealisation::SEVERITY`]) — a paler shade of its colour where none fails and it is the first marginal
//! one, pale green where all hold — with, for every assumption whose failing threshold crosses the grid, the line
//! where its ratio reaches it, and the line where a bouncing ball's contact lasts a tenth of its flight to the next
//! bounce under standard gravity (docs/idealisation.md#the-idealisation-map). A function of the sweep's table alone
//! ([`crate::sweep::map`] reads it).

use super::chart::{Axis, Chart, Colour, Layer, Mark, Stroke};
use std::collections::HashMap;

/// Canvas size, px: taller than the other figures, for the legend below the map.
const SIZE: (f64, f64) = (960.0, 760.0);

/// What a cell shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verdict {
    /// The first failing assumption, as an index into [`crate::idealisation::SEVERITY`].
    Fails(usize),
    /// None fails; the first marginal one.
    Marginal(usize),
    /// Every measured assumption holds.
    Holds,
    /// No verdict: the row is an error, or its verdicts were not measured.
    Unknown,
}

/// Where one assumption's ratio reaches a threshold: `levels[j][i]` is ln(|ratio| / threshold) at the cell (i, j)
/// (NaN where not measured), so the line is its zero.
#[derive(Debug, Clone, PartialEq)]
pub struct Boundary {
    /// Index into [`crate::idealisation::SEVERITY`].
    pub assumption: usize,
    /// The threshold is where the assumption starts to fail (`true`) or to be marginal.
    pub fails: bool,
    pub levels: Vec<Vec<f64>>,
}

/// What the map shows: a function of the sweep's table, nothing else.
#[derive(Debug, Clone, PartialEq)]
pub struct IdealisationMap {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub log_x: bool,
    pub log_y: bool,
    /// The cells' centres along each axis, increasing, in the units of the labels.
    pub xs: Vec<f64>,
    pub ys: Vec<f64>,
    /// `cells[j][i]`: the cell at (xs[i], ys[j]).
    pub cells: Vec<Vec<Verdict>>,
    pub boundaries: Vec<Boundary>,
    /// `flight[j][i]`: ln(ratio / 0.1) of the contact time to the flight between bounces, g t_c / (2 e v0), at the
    /// cell (i, j): +inf where e = 0 (no bounce: beyond the line), NaN where not measured; `None` when the CSV lacks
    /// its columns. Its zero is drawn as one more line (not a cell colour).
    pub flight: Option<Vec<Vec<f64>>>,
}

/// The flight line's name in the legend.
pub const FLIGHT_LABEL: &str = "contact > 1/10 of the flight between bounces (2 e v0 / g)";
/// The flight line: wide, solid and green (no assumption's colour), drawn under the assumptions' dashed lines (on the
/// map of an elastic ball it lies on gravity's, since J = 2 m v0 there: both stay visible).
const FLIGHT_STROKE: Stroke = Stroke { colour: Colour(44, 160, 44), width: 6.0, dash: None };

/// Each assumption's colour where it fails first, in [`crate::idealisation::SEVERITY`]'s order, and its name in the legend.
const ASSUMPTIONS: [(Colour, &str); 8] = [
    (Colour(148, 103, 189), "quasi-static (elastic waves)"),
    (Colour(140, 86, 75), "particles (contact size)"),
    (Colour(214, 39, 40), "instantaneous (travel in contact)"),
    (Colour(31, 119, 180), "isolated (gravity in contact)"),
    (Colour(255, 127, 14), "elastic (yield)"),
    (Colour(227, 119, 194), "constant e"),
    (Colour(188, 189, 34), "smooth (friction)"),
    (Colour(23, 190, 207), "central"),
];
const HOLDS: Colour = Colour(226, 242, 222);
const UNKNOWN: Colour = Colour(200, 200, 200);

/// `colour` mixed with white: `strength` of it (1: itself).
fn pale(colour: Colour, strength: f64) -> Colour {
    let mix = |c: u8| (f64::from(c) * strength + 255.0 * (1.0 - strength)).round() as u8;
    Colour(mix(colour.0), mix(colour.1), mix(colour.2))
}

/// `colour` darkened: `strength` of it (1: itself).
fn dark(colour: Colour, strength: f64) -> Colour {
    let mix = |c: u8| (f64::from(c) * strength).round() as u8;
    Colour(mix(colour.0), mix(colour.1), mix(colour.2))
}

/// The colour of a cell and its name in the legend, with its legend rank.
fn style(verdict: Verdict) -> (Colour, String, i32) {
    match verdict {
        Verdict::Fails(k) => (ASSUMPTIONS[k].0, format!("{} fails", ASSUMPTIONS[k].1), 2 * k as i32),
        Verdict::Marginal(k) => {
            (pale(ASSUMPTIONS[k].0, 0.35), format!("{} marginal", ASSUMPTIONS[k].1), 2 * k as i32 + 1)
        }
        Verdict::Holds => (HOLDS, "all hold".into(), 100),
        Verdict::Unknown => (UNKNOWN, "no verdict (see the status column)".into(), 101),
    }
}

/// A position on an axis: log10 of the value on a log axis (where cells and lines are interpolated), else itself.
fn to_axis(value: f64, log: bool) -> f64 {
    if log { value.log10() } else { value }
}

fn from_axis(value: f64, log: bool) -> f64 {
    if log { 10f64.powf(value) } else { value }
}

/// The edges of cells centred on `centres` (increasing): half-way between neighbours on the axis, the outer cells as
/// wide as their neighbours' halves (a single cell: a factor of 2 or ±5 % of its value either side).
fn edges(centres: &[f64], log: bool) -> Vec<f64> {
    let u: Vec<f64> = centres.iter().map(|&c| to_axis(c, log)).collect();
    let n = u.len();
    if n == 1 {
        let half = if log { 2f64.log10() } else { 0.05 * u[0].abs().max(1.0) };
        return vec![from_axis(u[0] - half, log), from_axis(u[0] + half, log)];
    }
    let mut edges = vec![from_axis(u[0] - (u[1] - u[0]) / 2.0, log)];
    edges.extend(u.windows(2).map(|w| from_axis((w[0] + w[1]) / 2.0, log)));
    edges.push(from_axis(u[n - 1] + (u[n - 1] - u[n - 2]) / 2.0, log));
    edges
}

/// The figure as an SVG document.
pub fn svg(map: &IdealisationMap) -> String {
    chart(map).svg()
}

/// The chart of the map.
pub fn chart(map: &IdealisationMap) -> Chart {
    let (x_edges, y_edges) = (edges(&map.xs, map.log_x), edges(&map.ys, map.log_y));
    let axis = |label: &str, edges: &[f64], log: bool| {
        let (low, high) = (edges[0], edges[edges.len() - 1]);
        if log { Axis::log(label, low, high).exact() } else { Axis::linear(label, low, high) }
    };
    let mut chart = Chart::new(
        map.title.as_str(),
        axis(&map.x_label, &x_edges, map.log_x),
        axis(&map.y_label, &y_edges, map.log_y),
    );
    (chart.width, chart.height) = SIZE;
    chart.legend_below = true;
    // The cells of each verdict, as rectangles (two opposite corners), in the order met.
    type Tile = [(f64, f64); 2];
    let mut groups: Vec<(Verdict, Vec<Tile>)> = Vec::new();
    for (j, row) in map.cells.iter().enumerate() {
        for (i, &verdict) in row.iter().enumerate() {
            let tile = [(x_edges[i], y_edges[j]), (x_edges[i + 1], y_edges[j + 1])];
            match groups.iter_mut().find(|(v, _)| *v == verdict) {
                Some((_, tiles)) => tiles.push(tile),
                None => groups.push((verdict, vec![tile])),
            }
        }
    }
    for (verdict, tiles) in groups {
        let (fill, label, rank) = style(verdict);
        chart.push(Layer::new("cells", Mark::Tiles { tiles, fill }).label(label).rank(rank));
    }
    if let Some(levels) = &map.flight {
        let lines = contour(&map.xs, &map.ys, levels, map.log_x, map.log_y);
        for (n, points) in lines.into_iter().enumerate() {
            let layer = Layer::new("flight", Mark::Line { points, stroke: FLIGHT_STROKE, marker: None });
            chart.push(if n == 0 { layer.label(FLIGHT_LABEL).rank(300) } else { layer });
        }
    }
    for boundary in &map.boundaries {
        let (colour, name) = ASSUMPTIONS[boundary.assumption];
        let stroke = if boundary.fails {
            Stroke::dashed(dark(colour, 0.6), 2.2, 9.0, 4.0)
        } else {
            Stroke::dashed(dark(colour, 0.7), 2.6, 3.0, 3.0)
        };
        let lines = contour(&map.xs, &map.ys, &boundary.levels, map.log_x, map.log_y);
        for (n, points) in lines.into_iter().enumerate() {
            let layer = Layer::new("boundary", Mark::Line { points, stroke, marker: None });
            let short = name.split(" (").next().unwrap_or(name);
            let label = format!("boundary: {short} {}", if boundary.fails { "fails" } else { "marginal" });
            chart.push(if n == 0 { layer.label(label).rank(200 + boundary.assumption as i32) } else { layer });
        }
    }
    chart
}

/// The zero line of `levels` over the grid of centres (`levels[j][i]` at (xs[i], ys[j])), by marching squares with
/// linear interpolation on the axes (log10 on a log axis, where the ratios' power laws are straight), as polylines
/// in data coordinates. Squares with a corner that is not a number are skipped.
pub fn contour(xs: &[f64], ys: &[f64], levels: &[Vec<f64>], log_x: bool, log_y: bool) -> Vec<Vec<(f64, f64)>> {
    // An edge of the grid: from centre (i, j) to (i + 1, j) (along x) or to (i, j + 1).
    type Edge = (usize, usize, bool);
    let level = |i: usize, j: usize| levels[j][i];
    let crossing = |(i, j, along_x): Edge| -> (f64, f64) {
        let (i2, j2) = if along_x { (i + 1, j) } else { (i, j + 1) };
        let (a, b) = (level(i, j), level(i2, j2));
        let t = a / (a - b);
        let (u0, v0) = (to_axis(xs[i], log_x), to_axis(ys[j], log_y));
        let (u1, v1) = (to_axis(xs[i2], log_x), to_axis(ys[j2], log_y));
        (from_axis(u0 + t * (u1 - u0), log_x), from_axis(v0 + t * (v1 - v0), log_y))
    };
    let mut segments: Vec<[Edge; 2]> = Vec::new();
    for j in 0..ys.len().saturating_sub(1) {
        for i in 0..xs.len().saturating_sub(1) {
            let corners = [level(i, j), level(i + 1, j), level(i + 1, j + 1), level(i, j + 1)];
            if corners.iter().any(|c| !c.is_finite()) {
                continue;
            }
            // The square's sides in turn, and whether the level changes sign along each.
            let sides: [Edge; 4] = [(i, j, true), (i + 1, j, false), (i, j + 1, true), (i, j, false)];
            let crossed: Vec<Edge> =
                (0..4).filter(|&k| (corners[k] >= 0.0) != (corners[(k + 1) % 4] >= 0.0)).map(|k| sides[k]).collect();
            match crossed.as_slice() {
                [a, b] => segments.push([*a, *b]),
                // A saddle: the centre's sign decides which corners the lines cut off.
                [a, b, c, d] => {
                    let centre = corners.iter().sum::<f64>() / 4.0;
                    if (centre >= 0.0) == (corners[0] >= 0.0) {
                        segments.push([*a, *b]);
                        segments.push([*c, *d]);
                    } else {
                        segments.push([*d, *a]);
                        segments.push([*b, *c]);
                    }
                }
                _ => {}
            }
        }
    }
    // Chain the segments through their shared edges into polylines.
    let mut at: HashMap<Edge, Vec<usize>> = HashMap::new();
    for (n, segment) in segments.iter().enumerate() {
        for edge in segment {
            at.entry(*edge).or_default().push(n);
        }
    }
    let mut used = vec![false; segments.len()];
    let mut lines = Vec::new();
    for start in 0..segments.len() {
        if used[start] {
            continue;
        }
        used[start] = true;
        let mut chain = std::collections::VecDeque::from(segments[start].to_vec());
        for forward in [true, false] {
            loop {
                let end = if forward { chain[chain.len() - 1] } else { chain[0] };
                let next = at[&end].iter().copied().find(|&n| !used[n]);
                let Some(n) = next else { break };
                used[n] = true;
                let other = if segments[n][0] == end { segments[n][1] } else { segments[n][0] };
                if forward {
                    chain.push_back(other);
                } else {
                    chain.push_front(other);
                }
            }
        }
        lines.push(chain.into_iter().map(crossing).collect());
    }
    lines
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::idealisation::SEVERITY;

    #[test]
    fn the_order_of_severity_has_a_colour_for_each() {
        assert_eq!(SEVERITY.len(), ASSUMPTIONS.len());
        for (key, (_, name)) in SEVERITY.iter().zip(ASSUMPTIONS) {
            assert!(name.starts_with(&key.replace('_', "-")[..5]), "{key}: {name}");
        }
    }

    #[test]
    fn cell_edges_lie_half_way_on_the_axis() {
        assert_eq!(edges(&[1.0, 2.0, 3.0], false), [0.5, 1.5, 2.5, 3.5]);
        let log = edges(&[1.0, 10.0, 100.0], true);
        for (got, want) in log.iter().zip([10f64.powf(-0.5), 10f64.powf(0.5), 10f64.powf(1.5), 10f64.powf(2.5)]) {
            assert!((got - want).abs() < 1e-12 * want, "{got} against {want}");
        }
    }

    #[test]
    fn a_straight_boundary_is_found_where_the_level_vanishes() {
        // level = x - 1.5 on a 4 x 3 grid: the zero is the line x = 1.5, one polyline over the three rows.
        let xs = [0.0, 1.0, 2.0, 3.0];
        let ys = [0.0, 1.0, 2.0];
        let levels: Vec<Vec<f64>> = ys.iter().map(|_| xs.iter().map(|x| x - 1.5).collect()).collect();
        let lines = contour(&xs, &ys, &levels, false, false);
        assert_eq!(lines.len(), 1, "{lines:?}");
        assert_eq!(lines[0].len(), 3);
        assert!(lines[0].iter().all(|&(x, _)| (x - 1.5).abs() < 1e-12), "{lines:?}");
    }
}
