//! Figures of one impact, each drawn once as SVG (see [`super::chart`]) and rasterised from that same SVG into an
//! anti-aliased PNG (see [`super::render`]): force against time with the phases shaded, the force–penetration
//! loop with its area (the energy dissipated) filled, and the normal velocities of both bodies with V0 and the
//! instantaneous before/after values as reference lines. Bodies are called by their names in the report.
//!
//! A frictional contact (the report's oblique section with a friction coefficient above zero) adds a second panel
//! to the force–time figure, on the same time axis: the tangential force against the initial slip, between the
//! dashed Coulomb limits ±μF, with the stretches below the limit (the tangential spring holding) shaded.

use super::chart::{self, Axis, Chart, Colour, Layer, Mark, Marker, Shape, Stack, Stroke, fixed, prefix, si};
use super::render;
use crate::files::write_atomically;
use crate::history::{History, Phase};
use crate::report::Report;
use anyhow::Context;
use nalgebra::Vector3;
use std::path::{Path, PathBuf};

/// The figures one impact gives, by file stem.
pub const FIGURES: [&str; 3] = ["force_time", "force_penetration", "velocities"];

const COMPRESSION: Colour = chart::PALETTE[0];
const RESTITUTION: Colour = chart::PALETTE[3];
/// The shade of the stretches below the Coulomb limit and the tangential force's colour.
const BELOW_LIMIT: Colour = chart::PALETTE[2];
const TANGENTIAL: Colour = chart::PALETTE[4];
/// Heights of the force–time figure's two panels (normal force over tangential force) of a frictional contact, px.
const NORMAL_PANEL: f64 = 470.0;
const TANGENTIAL_PANEL: f64 = 450.0;
/// The two bodies' colours in the velocity figure.
const BODIES: [Colour; 2] = [chart::PALETTE[0], chart::PALETTE[1]];
/// The fill of the dissipated-energy loop.
const LOOP: Colour = chart::PALETTE[4];
/// Stroke width of a measured curve, px.
const CURVE: f64 = 2.2;

/// A figure's title: the scene's (or sweep's) title, then what the figure shows (if anything). Every figure's title
/// is made here.
pub fn caption(title: &str, what: &str) -> String {
    // A title is the user's string, whatever its length: cut, so that the figure renders at once.
    let title = crate::text::cut(title, crate::text::TITLE_CHARS);
    if what.is_empty() { title } else { format!("{title} — {what}") }
}

/// Writes the three figures as SVG and PNG into `folder` (created if missing); returns the files written. Every
/// figure is rendered before any file is written, so a failure to draw writes nothing.
pub fn write_all(report: &Report, history: &History, folder: &Path) -> anyhow::Result<Vec<PathBuf>> {
    let mut files: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    for name in FIGURES {
        let svg = svg(name, report, history);
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

/// The SVG document of the figure `name` (one of [`FIGURES`]; anything else gives the velocity figure).
pub fn svg(name: &str, report: &Report, history: &History) -> String {
    match name {
        "force_time" => match friction(report) {
            Some(mu) => forces(report, history, mu).svg(),
            None => force_time(report, history).svg(),
        },
        "force_penetration" => force_penetration(report, history).svg(),
        _ => velocities(report, history).svg(),
    }
}

/// The friction coefficient of a frictional contact: the report has an oblique section that is not smooth.
fn friction(report: &Report) -> Option<f64> {
    report.oblique.as_ref().filter(|o| o.regime != "smooth" && o.friction > 0.0).map(|o| o.friction)
}

/// The force–time figure of a frictional contact: the normal force over the tangential force, one time axis.
fn forces(report: &Report, history: &History, mu: f64) -> Stack {
    let mut normal = force_time(report, history);
    normal.title = caption(&report.title, "contact forces");
    // Two forces now: name this one.
    normal.y.label = normal.y.label.replace("contact force", "normal force");
    for layer in normal.layers.iter_mut().filter(|layer| layer.class == "curve") {
        layer.label = Some("normal force F(t)".into());
    }
    normal.height = NORMAL_PANEL;
    normal.x_labels = false;
    let mut tangential = tangential_force(report, history, mu);
    tangential.height = TANGENTIAL_PANEL;
    Stack::new(vec![normal, tangential])
}

/// Seconds since first contact of the last sample (0 without samples).
fn contact_span(report: &Report, history: &History) -> f64 {
    history.samples.last().map_or(0.0, |s| s.time - report.contact.start_time).max(0.0)
}

/// Decimals that give event times three significant digits on an axis reaching `x_max` (in its own unit).
fn time_decimals(x_max: f64) -> usize {
    if x_max > 0.0 { (2.0 - x_max.log10().floor()).clamp(0.0, 6.0) as usize } else { 1 }
}

/// The force axis: lowest and highest force (N) with the compressive peak, its SI scale, and the range drawn in
/// scaled units (0 at the bottom unless the force turns tensile).
fn force_axis(report: &Report, history: &History) -> ((f64, &'static str), (f64, f64)) {
    let low = history.samples.iter().map(|s| s.force).fold(0.0, f64::min);
    let high = history.samples.iter().map(|s| s.force).fold(report.contact.max_force, f64::max);
    let (factor, unit) = prefix(high.max(-low));
    let pad = 0.06 * (high - low) / factor;
    let bottom = if low < 0.0 { low / factor - pad } else { 0.0 };
    ((factor, unit), (bottom, high / factor + pad))
}

/// A thin line at zero force when the force turns tensile.
fn zero_line(chart: &mut Chart) {
    if chart.y.low < 0.0 {
        chart.push(Layer::new("zero", Mark::HLine { y: 0.0, stroke: Stroke::solid(Colour::GREY, 0.8) }));
    }
}

fn force_time(report: &Report, history: &History) -> Chart {
    let c = &report.contact;
    let start = c.start_time;
    let (tf, tp) = prefix(contact_span(report, history));
    let ((ff, fp), (y0, y1)) = force_axis(report, history);
    let x_max = contact_span(report, history) / tf;
    let mut chart = Chart::new(
        caption(&report.title, "contact force"),
        Axis::linear(format!("time since first contact t ({tp}s)"), 0.0, x_max),
        Axis::linear(format!("contact force F ({fp}N)"), y0, y1),
    );
    let t0 = (c.max_compression_time - start) / tf;
    // The phases shaded and named in place, at the foot of each band (where the pulse is low).
    for (from, to, colour, name) in [(0.0, t0, COMPRESSION, "compression"), (t0, x_max, RESTITUTION, "restitution")] {
        chart.push(Layer::new("phase", Mark::Span { from, to, fill: colour, opacity: 0.1 }));
        let text = name.to_string();
        let note = Mark::Note { at: ((from + to) / 2.0, y0), offset: (0.0, -10.0), text, anchor: "middle", colour };
        chart.push(Layer::new("phase-name", note));
    }
    zero_line(&mut chart);
    let dashed = Stroke::dashed(Colour::BLACK, 1.2, 6.0, 4.0);
    chart.push(
        Layer::new("reference", Mark::VLine { x: t0, stroke: dashed })
            .label(format!("maximum compression (d′ = 0), t = {} {tp}s", fixed(t0, time_decimals(x_max))))
            .rank(1),
    );
    let force = history.samples.iter().map(|s| ((s.time - start) / tf, s.force / ff)).collect();
    let curve = Mark::Line { points: force, stroke: Stroke::solid(Colour::BLACK, CURVE), marker: None };
    chart.push(Layer::new("curve", curve).label("contact force F(t)").rank(0));
    let peak = ((c.max_force_time - start) / tf, c.max_force / ff);
    let marker = Marker::new(Shape::Circle, 5.0, RESTITUTION);
    chart.push(
        Layer::new("peak", Mark::Points { points: vec![peak], marker })
            .label(format!(
                "peak force {} at t = {} {tp}s",
                si(c.max_force, "N", 4),
                fixed(peak.0, time_decimals(x_max))
            ))
            .rank(2),
    );
    chart
}

/// The direction the tangential force is measured against: the slip of body 1's contact point relative to body 2's
/// at first contact, or (without one) the largest tangential force's.
fn slip_direction(history: &History) -> Vector3<f64> {
    let first = history.samples.first().map_or_else(Vector3::zeros, |s| s.slip);
    if first.norm() > 0.0 {
        return first.normalize();
    }
    let largest = history
        .samples
        .iter()
        .map(|s| s.tangential_force)
        .fold(Vector3::zeros(), |a: Vector3<f64>, f| if f.norm() > a.norm() { f } else { a });
    if largest.norm() > 0.0 { -largest.normalize() } else { Vector3::zeros() }
}

/// The stretches of the history below the Coulomb limit (the spring's sticking mode) as (from, to) in seconds since first contact: runs of samples that do not
/// slide, each reaching halfway to its neighbours (the samples do not locate the switches more finely).
fn below_limit_stretches(report: &Report, history: &History) -> Vec<(f64, f64)> {
    let start = report.contact.start_time;
    let samples = &history.samples;
    let time = |i: usize| samples[i].time - start;
    let mut stretches: Vec<(f64, f64)> = Vec::new();
    let mut i = 0;
    while i < samples.len() {
        if samples[i].sliding {
            i += 1;
            continue;
        }
        let first = i;
        while i < samples.len() && !samples[i].sliding {
            i += 1;
        }
        let from = if first == 0 { time(0) } else { (time(first - 1) + time(first)) / 2.0 };
        let to = if i == samples.len() { time(i - 1) } else { (time(i - 1) + time(i)) / 2.0 };
        stretches.push((from, to));
    }
    stretches
}

/// The tangential force on body 1 against its initial slip, −F_t·ŝ₀ (positive while friction opposes that slip),
/// between the Coulomb limits ±μF (dashed), with the stretches below the limit shaded and maximum compression marked.
fn tangential_force(report: &Report, history: &History, mu: f64) -> Chart {
    let c = &report.contact;
    let start = c.start_time;
    let direction = slip_direction(history);
    let span = contact_span(report, history);
    let (tf, tp) = prefix(span);
    let x_max = span / tf;
    let time = |t: f64| (t - start) / tf;
    let against: Vec<(f64, f64)> =
        history.samples.iter().map(|s| (time(s.time), -s.tangential_force.dot(&direction))).collect();
    let limit: Vec<(f64, f64)> = history.samples.iter().map(|s| (time(s.time), mu * s.force.max(0.0))).collect();
    let high = against.iter().chain(&limit).map(|p| p.1).fold(mu * c.max_force, f64::max);
    let low = against.iter().map(|p| p.1).fold(0.0, f64::min);
    // The lower limit −μF only where the force reverses noticeably.
    let reverses = low < -0.02 * high;
    let low = if reverses { low.min(-high) } else { low };
    let (ff, fp) = prefix(high.max(-low));
    let pad = 0.06 * (high - low) / ff;
    let bottom = if low < 0.0 { low / ff - pad } else { 0.0 };
    let mut chart = Chart::new(
        "",
        Axis::linear(format!("time since first contact t ({tp}s)"), 0.0, x_max),
        Axis::linear(format!("tangential force ({fp}N)"), bottom, high / ff + pad),
    );
    let oblique = report.oblique.as_ref();
    let below = oblique.and_then(|o| o.below_friction_limit_duration).unwrap_or(0.0);
    for (i, (from, to)) in below_limit_stretches(report, history).into_iter().enumerate() {
        let layer = Layer::new("below", Mark::Span { from: from / tf, to: to / tf, fill: BELOW_LIMIT, opacity: 0.15 });
        chart.push(if i == 0 {
            layer.label(format!("below the Coulomb limit (shaded): {} in all", si(below, "s", 3))).rank(3)
        } else {
            layer
        });
    }
    zero_line(&mut chart);
    let t0 = time(c.max_compression_time);
    let dashed = Stroke::dashed(Colour::BLACK, 1.2, 6.0, 4.0);
    chart.push(Layer::new("reference", Mark::VLine { x: t0, stroke: dashed }));
    // Where the contact points stop slipping (the regime turns to sticking), if they do during the contact.
    if let Some(rest) = oblique.and_then(|o| o.slip_rest_time).filter(|&rest| rest > 0.0) {
        let dotted = Stroke::dashed(TANGENTIAL, 1.6, 2.0, 3.0);
        let label = format!("the contact points' slip comes to rest, t = {}", si(rest, "s", 3));
        chart.push(Layer::new("rest", Mark::VLine { x: rest / tf, stroke: dotted }).label(label).rank(2));
    }
    let scaled = |points: &[(f64, f64)], sign: f64| points.iter().map(|&(t, f)| (t, sign * f / ff)).collect();
    let name = report.bodies[0].name.as_str();
    let work = oblique.and_then(|o| o.friction_work).map(|w| format!(", friction work {}", si(w, "J", 3)));
    let curve = Mark::Line { points: scaled(&against, 1.0), stroke: Stroke::solid(TANGENTIAL, CURVE), marker: None };
    chart.push(
        Layer::new("curve", curve)
            .label(format!("tangential force on {name} against its initial slip{}", work.unwrap_or_default()))
            .rank(0),
    );
    // Over the curve, so that the sliding stretches, where the force lies on the limit, show both.
    let coulomb = Stroke::dashed(Colour::BLACK, 1.3, 7.0, 4.0);
    let upper = Mark::Line { points: scaled(&limit, 1.0), stroke: coulomb, marker: None };
    let text = if reverses { "Coulomb limits ±μF" } else { "Coulomb limit μF" };
    chart.push(Layer::new("coulomb", upper).label(format!("{text}, μ = {mu}")).rank(1));
    if reverses {
        let lower = Mark::Line { points: scaled(&limit, -1.0), stroke: coulomb, marker: None };
        chart.push(Layer::new("coulomb", lower));
    }
    chart
}

/// What the shaded loop's area is, in words, with its value from the report; `None` when there is nothing to
/// shade (no dissipation, or the bodies never parted).
fn loop_label(report: &Report) -> Option<String> {
    if !report.contact.separated {
        return None;
    }
    let e = &report.energy;
    if report.law.separation == "penetration" {
        // A closed loop in d: the elastic force's work cancels, the area is the damping force's work.
        let work = e.dissipated?;
        (work > 1e-9 * e.kinetic_before).then(|| format!("loop area = energy dissipated = {}", si(work, "J", 4)))
    } else {
        // Separation at zero force leaves the loop open at d > 0: closed along F = 0, the area is the work of the
        // force over the contact, the kinetic energy lost (dissipated plus the elastic energy left behind).
        let lost = e.kinetic_before - e.kinetic_after?;
        (lost > 1e-9 * e.kinetic_before).then(|| format!("shaded area = kinetic energy lost = {}", si(lost, "J", 4)))
    }
}

fn force_penetration(report: &Report, history: &History) -> Chart {
    let c = &report.contact;
    let d_max = history.samples.iter().map(|s| s.penetration).fold(c.max_penetration, f64::max);
    let (df, dp) = prefix(d_max);
    let ((ff, fp), (y0, y1)) = force_axis(report, history);
    let mut chart = Chart::new(
        caption(&report.title, "force against penetration"),
        Axis::linear(format!("penetration d ({dp}m)"), 0.0, d_max / df * 1.04),
        Axis::linear(format!("contact force F ({fp}N)"), y0, y1),
    );
    let point = |s: &crate::history::Sample| (s.penetration / df, s.force / ff);
    if let Some(label) = loop_label(report) {
        // Closed along F = 0 back to d = 0 and up the force axis: neither leg adds to the integral of F dd, so the
        // area is the work of the force over the contact.
        let mut outline: Vec<(f64, f64)> = history.samples.iter().map(point).collect();
        if let Some(&(d_end, _)) = outline.last() {
            outline.extend([(d_end, 0.0), (0.0, 0.0)]);
        }
        let area = Mark::Area { points: outline, fill: LOOP, opacity: 0.2 };
        chart.push(Layer::new("loop-fill", area).label(label).rank(2));
    }
    zero_line(&mut chart);
    for (phase, colour, rank) in [(Phase::Compression, COMPRESSION, 0), (Phase::Restitution, RESTITUTION, 1)] {
        let mut line: Vec<(f64, f64)> = history.samples.iter().filter(|s| s.phase == phase).map(point).collect();
        if phase == Phase::Restitution {
            // Join the loop at maximum compression.
            if let Some(last) = history.samples.iter().rfind(|s| s.phase == Phase::Compression) {
                line.insert(0, point(last));
            }
        }
        // Unloading dashed over loading, so that both show where they coincide (an elastic contact).
        let stroke = match phase {
            Phase::Compression => Stroke::solid(colour, CURVE),
            Phase::Restitution => Stroke::dashed(colour, CURVE, 8.0, 4.0),
        };
        let curve = Mark::Line { points: line, stroke, marker: None };
        chart.push(Layer::new("curve", curve).label(phase.name()).rank(rank));
    }
    chart
}

fn velocities(report: &Report, history: &History) -> Chart {
    let c = &report.contact;
    let n = history.normal;
    let start = c.start_time;
    let normal = |v: &[f64; 3]| v[0] * n.x + v[1] * n.y + v[2] * n.z;
    let names = [report.bodies[0].name.as_str(), report.bodies[1].name.as_str()];
    let before = [normal(&report.bodies[0].velocity_before), normal(&report.bodies[1].velocity_before)];
    let after = report.instantaneous.as_ref().map(|i| (i.restitution, [0, 1].map(|b| normal(&i.velocity_after[b]))));

    let mut values: Vec<f64> =
        history.samples.iter().flat_map(|s| [s.velocities[0].dot(&n), s.velocities[1].dot(&n)]).collect();
    values.extend(before);
    values.push(c.common_normal_velocity);
    values.extend(after.iter().flat_map(|a| a.1));
    let (low, high) = values.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)));
    let (low, high) = if low.is_finite() { (low, high) } else { (0.0, 0.0) };
    let (vf, vp) = prefix(low.abs().max(high.abs()));
    let pad = 0.05 * (high - low) / vf;
    // Every speed in the legend with the same decimals: four significant digits of the largest.
    let largest = low.abs().max(high.abs()) / vf;
    let decimals = (3 - largest.log10().floor().max(0.0) as usize).min(3);
    let speed = |v: f64| format!("{} {vp}m/s", fixed(v / vf, decimals));

    let (tf, tp) = prefix(contact_span(report, history));
    let x_max = contact_span(report, history) / tf;
    let mut chart = Chart::new(
        caption(&report.title, "normal velocities"),
        Axis::linear(format!("time since first contact t ({tp}s)"), 0.0, x_max),
        Axis::linear(format!("normal velocity v·n ({vp}m/s)"), low / vf - pad, high / vf + pad),
    );
    for body in 0..2 {
        let points = history.samples.iter().map(|s| ((s.time - start) / tf, s.velocities[body].dot(&n) / vf)).collect();
        let curve = Mark::Line { points, stroke: Stroke::solid(BODIES[body], CURVE), marker: None };
        chart.push(Layer::new("curve", curve).label(names[body]).rank(4 * body as i32));
    }
    // Reference lines over the curves, thin, so that they stay visible where a curve meets them: dotted before,
    // dashed after, V0 dashed black.
    for body in 0..2 {
        let stroke = Stroke::dashed(BODIES[body], 1.3, 1.5, 3.0);
        chart.push(
            Layer::new("reference", Mark::HLine { y: before[body] / vf, stroke })
                .label(format!("{} before: {}", names[body], speed(before[body])))
                .rank(4 * body as i32 + 1),
        );
    }
    if let Some((e, values)) = after {
        for body in 0..2 {
            let stroke = Stroke::dashed(BODIES[body], 1.3, 7.0, 4.0);
            chart.push(
                Layer::new("reference", Mark::HLine { y: values[body] / vf, stroke })
                    .label(format!(
                        "{} after, instantaneous (e = {}): {}",
                        names[body],
                        fixed(e, 3),
                        speed(values[body])
                    ))
                    .rank(4 * body as i32 + 2),
            );
        }
    }
    let v0 = c.common_normal_velocity / vf;
    chart.push(
        Layer::new("reference", Mark::HLine { y: v0, stroke: Stroke::dashed(Colour::BLACK, 1.2, 7.0, 4.0) })
            .label(format!("common normal velocity V0 = {}", speed(c.common_normal_velocity)))
            .rank(3),
    );
    let t0 = (c.max_compression_time - start) / tf;
    let marker = Marker::new(Shape::Circle, 4.5, Colour::BLACK);
    chart.push(
        Layer::new("event", Mark::Points { points: vec![(t0, v0)], marker })
            .label(format!("maximum compression, t = {} {tp}s", fixed(t0, time_decimals(x_max))))
            .rank(7),
    );
    chart
}
