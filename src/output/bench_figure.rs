//! The work–precision figure of `impact bench`: the largest relative error over the reference impacts against the
//! time per impact, both on logarithmic axes, one line per method through its settings — the way the
//! ODE-benchmarking literature draws them (lower left is better).

use super::chart::{self, Axis, Chart, Layer, Mark, Marker, Stroke};

/// Errors below this are drawn at it (an exact zero has no place on a log axis).
pub const ERROR_FLOOR: f64 = 1e-17;

/// One method's line: its settings' (seconds per impact, largest error), in the order of the settings.
#[derive(Debug, Clone, PartialEq)]
pub struct Curve {
    pub label: String,
    pub points: Vec<(f64, f64)>,
}

/// The figure's data.
#[derive(Debug, Clone, PartialEq)]
pub struct BenchFigure {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub curves: Vec<Curve>,
}

/// Room kept between the outermost points and the axes' ends, as a factor (0.03 decade, about a marker's radius).
const MARKER_ROOM: f64 = 1.072;

impl BenchFigure {
    /// The points that can be drawn (finite, positive time; the error floored at [`ERROR_FLOOR`]).
    fn drawn(points: &[(f64, f64)]) -> Vec<(f64, f64)> {
        points
            .iter()
            .filter(|(t, e)| t.is_finite() && *t > 0.0 && e.is_finite())
            .map(|&(t, e)| (t, e.max(ERROR_FLOOR)))
            .collect()
    }

    fn range(&self, pick: impl Fn(&(f64, f64)) -> f64, fallback: (f64, f64)) -> (f64, f64) {
        let values = self.curves.iter().flat_map(|c| Self::drawn(&c.points)).map(|p| pick(&p));
        let (low, high) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)));
        // A point within a marker's width of a decade moves the axis to the next decade, so no marker is cut.
        if low.is_finite() { (low / MARKER_ROOM, high * MARKER_ROOM) } else { fallback }
    }
}

/// The chart of the figure.
pub fn chart(figure: &BenchFigure) -> Chart {
    let (x0, x1) = figure.range(|p| p.0, (1e-7, 1e-3));
    let (y0, y1) = figure.range(|p| p.1, (1e-16, 1.0));
    let mut chart = Chart::new(
        figure.title.as_str(),
        Axis::log(figure.x_label.as_str(), x0, x1),
        Axis::log(figure.y_label.as_str(), y0, y1),
    );
    chart.legend_below = true;
    for (i, curve) in figure.curves.iter().enumerate() {
        let colour = chart::PALETTE[i % chart::PALETTE.len()];
        let marker = Marker::new(chart::SHAPES[i % chart::SHAPES.len()], 4.0, colour);
        let line = Mark::Line {
            points: BenchFigure::drawn(&curve.points),
            stroke: Stroke::solid(colour, 2.0),
            marker: Some(marker),
        };
        chart.push(Layer::new("curve", line).label(curve.label.as_str()).rank(i as i32));
    }
    chart
}

/// The figure as an SVG document.
pub fn svg(figure: &BenchFigure) -> String {
    chart(figure).svg()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_method_is_a_line_on_log_axes_and_zero_errors_sit_on_the_floor() {
        let figure = BenchFigure {
            title: "t".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            curves: vec![
                Curve { label: "a".into(), points: vec![(1e-6, 1e-3), (2e-6, 1e-10), (3e-6, 0.0)] },
                Curve { label: "b".into(), points: vec![(1e-4, 1e-2), (f64::NAN, f64::INFINITY)] },
            ],
        };
        let chart = chart(&figure);
        assert!(chart.x.log && chart.y.log);
        assert_eq!(chart.layers.len(), 2);
        let Mark::Line { points, .. } = &chart.layers[0].mark else { panic!("a line") };
        assert_eq!(points, &[(1e-6, 1e-3), (2e-6, 1e-10), (3e-6, ERROR_FLOOR)]);
        let Mark::Line { points, .. } = &chart.layers[1].mark else { panic!("a line") };
        assert_eq!(points.len(), 1, "a failed run is left out");
        let svg = svg(&figure);
        assert_eq!(svg.matches("class=\"legend-entry\"").count(), 2);
    }
}
