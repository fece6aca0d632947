//! Figures of a world run, each drawn once as SVG and rasterised into an anti-aliased PNG: every contact's force on
//! one time axis, every movable body's velocity, and — under gravity — every movable body's height with its apexes
//! marked beside the apexes of the textbook's sequential model. They are drawn from the report and the run's trace
//! (a [`WorldTrace`], which keeps the instants of the series, thinned to a bounded number).

use super::chart::{self, Axis, Chart, Colour, Layer, Mark, Marker, Shape, Stroke, prefix};
use super::figures::caption;
use super::render;
use crate::files::write_atomically;
use crate::report::world::WorldReport;
use crate::world::flight::Kinematic;
use crate::world::record::{ContactSample, Observer};
use anyhow::Context;
use nalgebra::Vector3;
use std::path::{Path, PathBuf};

/// The figures of a world run, by file stem (`heights` only under gravity).
pub const FIGURES: [&str; 3] = ["contact_forces", "velocities", "heights"];

/// Most instants a trace keeps: beyond, it keeps every other one (and from then on every second, fourth, ...).
const KEPT: usize = 40_000;

/// Stroke width of a measured curve, px.
const CURVE: f64 = 1.8;

/// Most curves named one by one in a legend.
const NAMED: usize = 8;

/// One kept instant: every body's state, the active contacts.
#[derive(Debug, Clone)]
struct Instant {
    time: f64,
    bodies: Vec<Kinematic>,
    contacts: Vec<ContactSample>,
}

/// The instants of a run for its figures, thinned evenly to at most [`KEPT`].
#[derive(Debug, Default)]
pub struct WorldTrace {
    instants: Vec<Instant>,
    /// Keep one instant in `stride`.
    stride: usize,
    seen: usize,
}

impl WorldTrace {
    pub fn new() -> WorldTrace {
        WorldTrace { instants: Vec::new(), stride: 1, seen: 0 }
    }
}

impl Observer for WorldTrace {
    fn instant(&mut self, time: f64, bodies: &[Kinematic], contacts: &[ContactSample]) {
        self.seen += 1;
        // Every instant of a contact's start or end is kept (a pulse is never lost to the thinning).
        if !(self.seen - 1).is_multiple_of(self.stride)
            && contacts.is_empty() == self.instants.last().is_none_or(|i| i.contacts.is_empty())
        {
            return;
        }
        self.instants.push(Instant { time, bodies: bodies.to_vec(), contacts: contacts.to_vec() });
        if self.instants.len() > KEPT {
            let kept: Vec<Instant> =
                self.instants.drain(..).enumerate().filter(|(k, _)| k % 2 == 0).map(|(_, i)| i).collect();
            self.instants = kept;
            self.stride *= 2;
        }
    }
}

/// The figures this run draws: the heights only under gravity.
pub fn names(report: &WorldReport) -> Vec<&'static str> {
    let gravity = report.world.gravity.iter().any(|g| *g != 0.0);
    FIGURES.iter().copied().filter(|name| *name != "heights" || gravity).collect()
}

/// Writes the run's figures as SVG and PNG into `folder` (created if missing); returns the files written. Every
/// figure is rendered before any file is written.
pub fn write_all(report: &WorldReport, trace: &WorldTrace, folder: &Path) -> anyhow::Result<Vec<PathBuf>> {
    let mut files: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    for name in names(report) {
        let svg = svg(name, report, trace);
        let png = render::png(&svg).with_context(|| format!("cannot render {name}.png"))?;
        files.push((folder.join(format!("{name}.png")), png));
        files.push((folder.join(format!("{name}.svg")), svg.into_bytes()));
    }
    std::fs::create_dir_all(folder).with_context(|| format!("cannot create the folder {}", folder.display()))?;
    for (path, bytes) in &files {
        write_atomically(path, bytes)?;
    }
    Ok(files.into_iter().map(|(path, _)| path).collect())
}

/// The SVG document of the figure `name` (one of [`FIGURES`]).
pub fn svg(name: &str, report: &WorldReport, trace: &WorldTrace) -> String {
    match name {
        "contact_forces" => contact_forces(report, trace).svg(),
        "heights" => heights(report, trace).svg(),
        _ => velocities(report, trace).svg(),
    }
}

/// The time axis of the run: (factor, prefix, end in that unit).
fn time_axis(report: &WorldReport, trace: &WorldTrace) -> (f64, &'static str, f64) {
    let end = trace.instants.last().map_or(report.world.end_time, |i| i.time).max(report.world.end_time);
    let (tf, tp) = prefix(end);
    (tf, tp, end / tf)
}

/// The range of `values` with a margin, and the unit's (factor, prefix).
fn range(values: impl Iterator<Item = f64>) -> (f64, f64, f64, &'static str) {
    let (low, high) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)));
    let (low, high) = if low.is_finite() { (low.min(0.0), high.max(0.0)) } else { (0.0, 1.0) };
    let (factor, unit) = prefix(low.abs().max(high.abs()));
    let pad = 0.05 * (high - low).max(f64::MIN_POSITIVE) / factor;
    (low / factor - pad, high / factor + pad, factor, unit)
}

/// A legend entry for curve `k` of `count`: named while there are few, the rest gathered in one entry.
fn legend(layer: Layer, k: usize, count: usize, name: String, rest: &str) -> Layer {
    if k < NAMED {
        layer.label(name).rank(k as i32)
    } else if k == NAMED {
        layer.label(format!("{} more {rest}", count - NAMED)).rank(k as i32)
    } else {
        layer
    }
}

/// Every contact's normal force against the run's time, one colour each.
fn contact_forces(report: &WorldReport, trace: &WorldTrace) -> Chart {
    let (tf, tp, end) = time_axis(report, trace);
    let forces = trace.instants.iter().flat_map(|i| i.contacts.iter().map(|c| c.force));
    let (low, high, ff, fp) = range(forces);
    let mut chart = Chart::new(
        caption(&report.title, "contact forces"),
        Axis::linear(format!("time t ({tp}s)"), 0.0, end),
        Axis::linear(format!("normal force ({fp}N)"), low, high),
    );
    let count = report.contacts.len();
    for (k, contact) in report.contacts.iter().enumerate() {
        // The contact's curve: zero just before it begins and after it ends, its samples in between.
        let mut points = vec![(contact.start_time / tf, 0.0)];
        points.extend(
            trace
                .instants
                .iter()
                .filter_map(|i| i.contacts.iter().find(|c| c.index == k).map(|c| (i.time / tf, c.force / ff))),
        );
        if let Some(end) = contact.end_time {
            points.push((end / tf, 0.0));
        }
        let colour = chart::PALETTE[k % chart::PALETTE.len()];
        let curve = Mark::Line { points, stroke: Stroke::solid(colour, CURVE), marker: None };
        let [i, j] = contact.bodies;
        let name = format!(
            "contact {k}: {} – {}, peak {}",
            report.bodies[i].name,
            report.bodies[j].name,
            chart::si(contact.max_force, "N", 3)
        );
        chart.push(legend(Layer::new("curve", curve), k, count, name, "contacts"));
    }
    chart
}

/// The axis of motion: the direction along which the bodies' velocities vary most (gravity's, under gravity).
fn motion_axis(report: &WorldReport, trace: &WorldTrace) -> (Vector3<f64>, &'static str) {
    let g = Vector3::from(report.world.gravity);
    if g.norm() > 0.0 {
        return (-g / g.norm(), "up");
    }
    let names = ["x", "y", "z"];
    let spread = |axis: usize| {
        let values = trace.instants.iter().flat_map(|i| i.bodies.iter().map(move |b| b.velocity[axis]));
        let (low, high) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)));
        high - low
    };
    let axis = (0..3).max_by(|a, b| spread(*a).total_cmp(&spread(*b))).unwrap_or(0);
    (Vector3::ith(axis, 1.0), names[axis])
}

/// The movable bodies (index, name).
fn movable(report: &WorldReport) -> Vec<(usize, &str)> {
    report.bodies.iter().enumerate().filter(|(_, b)| b.mass.is_finite()).map(|(k, b)| (k, b.name.as_str())).collect()
}

/// Every movable body's velocity along the axis of motion against time.
fn velocities(report: &WorldReport, trace: &WorldTrace) -> Chart {
    let (tf, tp, end) = time_axis(report, trace);
    let (axis, axis_name) = motion_axis(report, trace);
    let bodies = movable(report);
    let values = trace.instants.iter().flat_map(|i| bodies.iter().map(|&(k, _)| i.bodies[k].velocity.dot(&axis)));
    let (low, high, vf, vp) = range(values);
    let mut chart = Chart::new(
        caption(&report.title, "velocities"),
        Axis::linear(format!("time t ({tp}s)"), 0.0, end),
        Axis::linear(format!("velocity, {axis_name} ({vp}m/s)"), low, high),
    );
    if low < 0.0 {
        chart.push(Layer::new("zero", Mark::HLine { y: 0.0, stroke: Stroke::solid(Colour::GREY, 0.8) }));
    }
    for (n, &(k, name)) in bodies.iter().enumerate() {
        let points = trace.instants.iter().map(|i| (i.time / tf, i.bodies[k].velocity.dot(&axis) / vf)).collect();
        let colour = chart::PALETTE[n % chart::PALETTE.len()];
        let curve = Mark::Line { points, stroke: Stroke::solid(colour, CURVE), marker: None };
        chart.push(legend(Layer::new("curve", curve), n, bodies.len(), name.to_string(), "bodies"));
    }
    // Without gravity the velocities end constant: the textbook's sequential model beside them, dashed.
    let gravity = report.world.gravity.iter().any(|g| *g != 0.0);
    if let (false, Some(model), true) = (gravity, report.sequential.nominal.as_ref(), bodies.len() <= NAMED) {
        for (n, &(k, _)) in bodies.iter().enumerate() {
            let colour = chart::PALETTE[n % chart::PALETTE.len()];
            let value = Vector3::from(model.velocity_after[k]).dot(&axis) / vf;
            let line = Layer::new("model", Mark::HLine { y: value, stroke: Stroke::dashed(colour, 1.2, 6.0, 4.0) });
            chart.push(if n == 0 {
                line.label("the sequential model's velocities after (dashed)").rank(NAMED as i32 + 1)
            } else {
                line
            });
        }
    }
    chart
}

/// Every movable body's height against gravity, its apexes marked (where its velocity along gravity turns in
/// flight) and, for its contacts with immovable bodies, the apex the sequential model's rebound would reach from the
/// same point.
fn heights(report: &WorldReport, trace: &WorldTrace) -> Chart {
    let (tf, tp, end) = time_axis(report, trace);
    let g = Vector3::from(report.world.gravity);
    let down = g.norm();
    let up = -g / down;
    let bodies = movable(report);
    let values = trace.instants.iter().flat_map(|i| bodies.iter().map(|&(k, _)| i.bodies[k].position.dot(&up)));
    let (low, high) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| (a.min(v), b.max(v)));
    let (low, high) = if low.is_finite() { (low, high) } else { (0.0, 1.0) };
    let model = report.sequential.nominal.as_ref();
    // The model's apexes: after contact k of a body with an immovable one, from the body's height when it ended.
    let mut model_apexes: Vec<(usize, f64, f64)> = Vec::new();
    if let Some(model) = model {
        for (k, contact) in report.contacts.iter().enumerate() {
            let [i, j] = contact.bodies;
            let (Some(end_time), Some(after)) = (contact.end_time, model.contact_velocities_after.get(k)) else {
                continue;
            };
            let (body, velocity) = match (report.bodies[i].mass.is_finite(), report.bodies[j].mass.is_finite()) {
                (true, false) => (i, after[0]),
                (false, true) => (j, after[1]),
                _ => continue,
            };
            let rising = Vector3::from(velocity).dot(&up);
            let at =
                trace.instants.iter().min_by(|a, b| (a.time - end_time).abs().total_cmp(&(b.time - end_time).abs()));
            let (Some(at), true) = (at, rising > 0.0) else { continue };
            let height = at.bodies[body].position.dot(&up) + rising * rising / (2.0 * down);
            model_apexes.push((body, end_time + rising / down, height));
        }
    }
    let top = model_apexes.iter().map(|a| a.2).fold(high, f64::max);
    let (hf, hp) = prefix(low.abs().max(top.abs()));
    let pad = 0.05 * (top - low).max(f64::MIN_POSITIVE) / hf;
    let mut chart = Chart::new(
        caption(&report.title, "heights"),
        Axis::linear(format!("time t ({tp}s)"), 0.0, end),
        Axis::linear(format!("height of the centre ({hp}m)"), low / hf - pad, top / hf + pad),
    );
    for (n, &(k, name)) in bodies.iter().enumerate() {
        let colour = chart::PALETTE[n % chart::PALETTE.len()];
        let points: Vec<(f64, f64)> =
            trace.instants.iter().map(|i| (i.time / tf, i.bodies[k].position.dot(&up) / hf)).collect();
        chart.push(legend(
            Layer::new("curve", Mark::Line { points, stroke: Stroke::solid(colour, CURVE), marker: None }),
            2 * n,
            2 * bodies.len(),
            name.to_string(),
            "curves",
        ));
        // Apexes: where the velocity along gravity turns from rising to falling between two kept instants (the
        // flights' apexes are instants of the trace), the higher of the two.
        let rising = |i: &Instant| i.bodies[k].velocity.dot(&up);
        let height = |i: &Instant| i.bodies[k].position.dot(&up);
        let free = |i: &Instant| i.contacts.iter().all(|c| !report.contacts[c.index].bodies.contains(&k));
        let apexes: Vec<(f64, f64)> = trace
            .instants
            .windows(2)
            .filter(|w| rising(&w[0]) > 0.0 && rising(&w[1]) <= 0.0 && free(&w[0]) && free(&w[1]))
            .map(|w| if height(&w[0]) > height(&w[1]) { &w[0] } else { &w[1] })
            .map(|i| (i.time / tf, height(i) / hf))
            .collect();
        // The model's markers first, larger and hollow, so that the simulation's apexes stay visible over them.
        let model: Vec<(f64, f64)> = model_apexes.iter().filter(|a| a.0 == k).map(|a| (a.1 / tf, a.2 / hf)).collect();
        if !model.is_empty() {
            let marker = Marker { edge: colour, ..Marker::new(Shape::TriangleDown, 5.5, Colour::WHITE) };
            let what = "the instantaneous model's apexes (each contact alone, nominal e)";
            chart.push(
                Layer::new("model", Mark::Points { points: model, marker }).label(format!("{name}: {what}")).rank(101),
            );
        }
        if !apexes.is_empty() {
            let marker = Marker::new(Shape::Circle, 2.6, colour);
            chart.push(
                Layer::new("apex", Mark::Points { points: apexes, marker }).label(format!("{name}: apexes")).rank(100),
            );
        }
    }
    chart
}
