//! The figure of the rod dropped at an angle (`plots/rod_angle_sweep.png`, [`crate::rod_sweep`]): two panels on one
//! axis of the rod's angle to the floor, (a) the apparent e of its impact sequence — the mass centre's rebound speed
//! when the sequence is over, over its fall speed — and (b) the number of contacts in the sequence; each simulated
//! (solid, markers), by the sequential instantaneous model over the simulated contacts (dashed), and by the rigid rod
//! with its own order of end impacts (dotted), with the contacts' e and the one strike without gravity of rigid-body theory for scale.

use super::chart::{Axis, Chart, Colour, Layer, Mark, Marker, PALETTE, Shape, Stack, Stroke};
use super::figures::caption;
use crate::rod_sweep::SweepPoint;

/// A panel: its heading, its y label, and its three series (simulated, sequential, rigid; `None`: no value).
type Panel = (&'static str, &'static str, [Vec<Option<(f64, f64)>>; 3]);

/// Canvas heights of the two panels, px: the first carries the title, the last the x axis's labels and the legend.
const HEIGHTS: [f64; 2] = [520.0, 500.0];

/// The figure as an SVG document.
pub fn svg(title: &str, points: &[SweepPoint]) -> String {
    stack(title, points).svg()
}

/// The figure's two panels.
pub fn stack(title: &str, points: &[SweepPoint]) -> Stack {
    let degrees: Vec<f64> = points.iter().map(|p| p.degrees).collect();
    // The contacts' e: the simulated first contact's, the same to 1e-3 at every angle.
    let e = points.iter().map(|p| p.e).sum::<f64>() / points.len().max(1) as f64;
    let series = |value: &dyn Fn(&SweepPoint) -> Option<f64>| -> Vec<Option<(f64, f64)>> {
        points.iter().map(|p| value(p).map(|y| (p.degrees, y))).collect()
    };
    let panels: [Panel; 2] = [
        (
            "(a) apparent e: the mass centre's rebound speed when the sequence is over / its fall speed",
            "apparent e",
            [
                series(&|p| Some(p.simulated.apparent_e)),
                series(&|p| Some(p.sequential.apparent_e)),
                series(&|p| p.rigid.as_ref().map(|r| r.apparent_e)),
            ],
        ),
        (
            "(b) contacts in the sequence (up to the rebound's apex)",
            "contacts",
            [
                series(&|p| Some(p.simulated.contacts() as f64)),
                series(&|p| Some(p.sequential.contacts() as f64)),
                series(&|p| p.rigid.as_ref().map(|r| r.contacts() as f64)),
            ],
        ),
    ];
    let x0 = degrees.iter().copied().fold(f64::INFINITY, f64::min).min(0.0);
    let x1 = degrees.iter().copied().fold(f64::NEG_INFINITY, f64::max).max(90.0);
    let names = [
        "simulation (compliant Hunt–Crossley ends)",
        "sequential model over the simulated contacts, each contact's simulated e",
        "rigid rod, its own order of end impacts, constant e",
    ];
    let mut charts = Vec::new();
    for (panel, (heading, y_label, data)) in panels.into_iter().enumerate() {
        let known = data.iter().flatten().flatten().map(|p| p.1);
        let (low, high) = known.fold((0.0f64, 1.0f64), |(a, b), y| (a.min(y), b.max(y)));
        let high = if panel == 1 { high.ceil() + 0.5 } else { high + 0.05 * (high - low) };
        let text = if panel == 0 { caption(title, "") } else { String::new() };
        let mut chart = Chart::new(text, Axis::linear("rod's angle to the floor when dropped θ (°)", x0, x1), {
            Axis::linear(y_label, low, high)
        });
        chart.heading = heading.into();
        chart.height = HEIGHTS[panel];
        let last = panel == 1;
        chart.x_labels = last;
        chart.legend_below = last;
        let label = |layer: Layer, text: String, rank: i32| if last { layer.label(text).rank(rank) } else { layer };
        if panel == 0 {
            let line = Mark::HLine { y: e, stroke: Stroke::dashed(Colour::GREY, 1.2, 2.0, 3.0) };
            chart.push(Layer::new("material", line));
            let note = Mark::Note {
                at: (x0, e),
                offset: (8.0, -6.0),
                text: format!("each contact's e = {e:.3}"),
                anchor: "start",
                colour: Colour::GREY,
            };
            chart.push(Layer::new("material-note", note));
            // Rigid-body theory (docs/references.md): one strike of the lower end, no gravity: (1 + e)/(1 + 3 cos²θ) - 1, dashed grey, over 0–90°.
            let closed: Vec<(f64, f64)> = (0..=180)
                .map(|i| {
                    let t = f64::from(i) / 2.0;
                    let c2 = t.to_radians().cos().powi(2);
                    (t, (1.0 + e) / (1.0 + 3.0 * c2) - 1.0)
                })
                .filter(|p| p.1 >= low)
                .collect();
            let mark = Mark::Line { points: closed, stroke: Stroke::dashed(Colour::GREY, 1.0, 6.0, 4.0), marker: None };
            chart.push(Layer::new("one-strike", mark));
        } else {
            // Its legend entry, under the last panel with the others (the line itself is in panel (a)).
            let entry =
                Mark::Line { points: Vec::new(), stroke: Stroke::dashed(Colour::GREY, 1.0, 6.0, 4.0), marker: None };
            let text = "(a) one strike without gravity, rigid-body theory: (1 + e)/(1 + 3 cos²θ) − 1, under the points beyond 59°";
            chart.push(Layer::new("one-strike", entry).label(text).rank(3));
        }
        let styles = [
            (PALETTE[0], Stroke::solid(PALETTE[0], 2.2), Some(Marker::new(Shape::Circle, 3.2, PALETTE[0]))),
            (PALETTE[1], Stroke::dashed(PALETTE[1], 2.0, 7.0, 4.0), None),
            (Colour::BLACK, Stroke::dashed(Colour::BLACK, 1.6, 2.0, 3.0), None),
        ];
        for (i, points) in data.iter().enumerate() {
            let (_, stroke, marker) = styles[i];
            for (j, run) in points.split(Option::is_none).filter(|run| !run.is_empty()).enumerate() {
                let run: Vec<(f64, f64)> = run.iter().flatten().copied().collect();
                let line = Mark::Line { points: run, stroke, marker };
                let layer = Layer::new("series", line);
                chart.push(if j == 0 { label(layer, names[i].to_string(), i as i32) } else { layer });
            }
        }
        charts.push(chart);
    }
    Stack::new(charts)
}
