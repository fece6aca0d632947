//! Figures of one impact (plotters, PNG and SVG, with an embedded font so no system fonts are needed):
//! force against time with the phases shaded, the force–penetration hysteresis loop, and the normal velocities
//! of both bodies with V0 and the instantaneous before/after values as reference lines.

use crate::history::{History, Phase};
use crate::report::Report;
use anyhow::{Context, anyhow};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::{Path, PathBuf};
use std::sync::Once;

/// Figure size in pixels.
const SIZE: (u32, u32) = (960, 640);
const COMPRESSION: RGBColor = RGBColor(31, 119, 180);
const RESTITUTION: RGBColor = RGBColor(214, 39, 40);
const BODY_2: RGBColor = RGBColor(44, 160, 44);
pub const FONT: &str = "sans-serif";

/// The figures one impact gives, by file stem.
pub const FIGURES: [&str; 3] = ["force_time", "force_penetration", "velocities"];

pub fn register_font() {
    static REGISTER: Once = Once::new();
    REGISTER.call_once(|| {
        // The embedded DejaVu Sans is a valid font, so registration cannot fail.
        let _ = plotters::style::register_font(FONT, FontStyle::Normal, dejavu::sans::regular());
        let _ = plotters::style::register_font(FONT, FontStyle::Bold, dejavu::sans::bold());
    });
}

/// A scale for an axis: a factor and its SI prefix, chosen so that `max` reads between 1 and 1000.
fn prefix(max: f64) -> (f64, &'static str) {
    let steps = [(1e-9, "n"), (1e-6, "µ"), (1e-3, "m"), (1.0, ""), (1e3, "k"), (1e6, "M"), (1e9, "G")];
    let magnitude = max.abs();
    steps.iter().rev().find(|(factor, _)| magnitude >= *factor).map_or((1e-9, "n"), |&(f, p)| (f, p))
}

/// Writes the three figures as PNG and SVG into `folder`: all of them, or (on error) none new.
pub fn write_all(report: &Report, history: &History, folder: &Path) -> anyhow::Result<Vec<PathBuf>> {
    register_font();
    std::fs::create_dir_all(folder).with_context(|| format!("cannot create the folder {}", folder.display()))?;
    let mut staged: Vec<(PathBuf, PathBuf)> = Vec::new();
    let result = (|| -> anyhow::Result<()> {
        for name in FIGURES {
            for extension in ["png", "svg"] {
                let target = folder.join(format!("{name}.{extension}"));
                let temporary = folder.join(format!(".{name}.partial-{}.{extension}", std::process::id()));
                staged.push((temporary.clone(), target));
                if extension == "png" {
                    let root = BitMapBackend::new(&temporary, SIZE).into_drawing_area();
                    draw(name, report, history, &root)?;
                    root.present().map_err(|e| anyhow!("cannot render {name}.png: {e}"))?;
                } else {
                    let root = SVGBackend::new(&temporary, SIZE).into_drawing_area();
                    draw(name, report, history, &root)?;
                    root.present().map_err(|e| anyhow!("cannot render {name}.svg: {e}"))?;
                }
            }
        }
        Ok(())
    })();
    if let Err(error) = result {
        for (temporary, _) in &staged {
            let _ = std::fs::remove_file(temporary);
        }
        return Err(error);
    }
    for (temporary, target) in &staged {
        std::fs::rename(temporary, target).with_context(|| format!("cannot write {}", target.display()))?;
    }
    Ok(staged.into_iter().map(|(_, target)| target).collect())
}

fn draw<DB: DrawingBackend<ErrorType: 'static>>(
    name: &str,
    report: &Report,
    history: &History,
    root: &DrawingArea<DB, Shift>,
) -> anyhow::Result<()> {
    root.fill(&WHITE).map_err(|e| anyhow!("{e:?}"))?;
    let drawn = match name {
        "force_time" => force_time(report, history, root),
        "force_penetration" => force_penetration(report, history, root),
        _ => velocities(report, history, root),
    };
    drawn.map_err(|e| anyhow!("cannot draw {name}: {e}"))
}

/// What drawing a figure gives: nothing, or plotters' error.
pub type Drawn = Result<(), Box<dyn std::error::Error>>;

/// A chart builder with the project's title, margins and axis areas; the caller picks the axes.
pub fn frame<'a, 'b, DB: DrawingBackend>(
    root: &'a DrawingArea<DB, Shift>,
    title: &str,
    title_size: u32,
) -> ChartBuilder<'a, 'b, DB> {
    let mut builder = ChartBuilder::on(root);
    builder.caption(title, (FONT, title_size)).margin(20).x_label_area_size(55).y_label_area_size(80);
    builder
}

/// Four decimals, without a minus sign on a value that rounds to zero.
fn fixed(value: f64) -> String {
    let text = format!("{value:.4}");
    if text == "-0.0000" { "0.0000".into() } else { text }
}

fn caption(report: &Report, what: &str) -> String {
    format!("{} — {what}", super::text::cut(&report.title, super::text::TITLE_CHARS))
}

fn force_time<DB: DrawingBackend<ErrorType: 'static>>(
    report: &Report,
    history: &History,
    root: &DrawingArea<DB, Shift>,
) -> Drawn {
    let c = &report.contact;
    let start = c.start_time;
    let end = history.samples.last().map_or(start, |s| s.time);
    let (tf, tp) = prefix(end - start);
    let (ff, fp) = prefix(c.max_force);
    let low = history.samples.iter().map(|s| s.force).fold(0.0, f64::min);
    let (x_max, y_max, y_min) = ((end - start) / tf, c.max_force / ff * 1.08, (low / ff * 1.08).min(0.0));
    let mut chart = frame(root, &caption(report, "contact force"), 22).build_cartesian_2d(0.0..x_max, y_min..y_max)?;
    chart
        .configure_mesh()
        .x_desc(format!("time since first contact ({tp}s)"))
        .y_desc(format!("contact force ({fp}N)"))
        .light_line_style(BLACK.mix(0.04))
        .axis_desc_style((FONT, 20))
        .label_style((FONT, 16))
        .draw()?;
    let t0 = (c.max_compression_time - start) / tf;
    for (from, to, color, label) in [(0.0, t0, COMPRESSION, "compression"), (t0, x_max, RESTITUTION, "restitution")] {
        chart
            .draw_series(std::iter::once(Rectangle::new([(from, y_min), (to, y_max)], color.mix(0.12).filled())))?
            .label(label)
            .legend(move |(x, y)| Rectangle::new([(x, y - 6), (x + 18, y + 6)], color.mix(0.3).filled()));
    }
    chart
        .draw_series(LineSeries::new(
            history.samples.iter().map(|s| ((s.time - start) / tf, s.force / ff)),
            BLACK.stroke_width(3),
        ))?
        .label("F(t)")
        .legend(|(x, y)| PathElement::new([(x, y), (x + 18, y)], BLACK.stroke_width(3)));
    chart
        .draw_series(DashedLineSeries::new([(t0, y_min), (t0, y_max)], 8, 5, BLACK.stroke_width(1)))?
        .label("maximum compression (d' = 0, V0)")
        .legend(|(x, y)| PathElement::new([(x, y), (x + 18, y)], BLACK.stroke_width(1)));
    let peak = ((c.max_force_time - start) / tf, c.max_force / ff);
    chart
        .draw_series(std::iter::once(Circle::new(peak, 6, RESTITUTION.filled())))?
        .label("peak force")
        .legend(|(x, y)| Circle::new((x + 9, y), 5, RESTITUTION.filled()));
    legend(&mut chart, SeriesLabelPosition::UpperRight)
}

fn force_penetration<DB: DrawingBackend<ErrorType: 'static>>(
    report: &Report,
    history: &History,
    root: &DrawingArea<DB, Shift>,
) -> Drawn {
    let c = &report.contact;
    let (df, dp) = prefix(c.max_penetration);
    let (ff, fp) = prefix(c.max_force);
    let low = history.samples.iter().map(|s| s.force).fold(0.0, f64::min);
    let mut chart = frame(root, &caption(report, "force against penetration"), 22)
        .build_cartesian_2d(0.0..c.max_penetration / df * 1.05, (low / ff * 1.08).min(0.0)..c.max_force / ff * 1.08)?;
    chart
        .configure_mesh()
        .x_desc(format!("penetration ({dp}m)"))
        .y_desc(format!("contact force ({fp}N)"))
        .light_line_style(BLACK.mix(0.04))
        .axis_desc_style((FONT, 20))
        .label_style((FONT, 16))
        .draw()?;
    for (phase, color) in [(Phase::Compression, COMPRESSION), (Phase::Restitution, RESTITUTION)] {
        let points = history.samples.iter().filter(|s| s.phase == phase);
        let mut line: Vec<(f64, f64)> = points.map(|s| (s.penetration / df, s.force / ff)).collect();
        if phase == Phase::Restitution {
            // Join the loop at maximum compression.
            if let Some(last) = history.samples.iter().rfind(|s| s.phase == Phase::Compression) {
                line.insert(0, (last.penetration / df, last.force / ff));
            }
        }
        chart
            .draw_series(LineSeries::new(line, color.stroke_width(3)))?
            .label(phase.name())
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 18, y)], color.stroke_width(3)));
    }
    if let Some(work) = report.energy.dissipated {
        // An empty series only to put the loop's meaning in the legend.
        chart
            .draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())?
            .label(format!("loop area = energy dissipated = {work:.4e} J"))
            .legend(|(x, y)| Rectangle::new([(x, y - 6), (x + 18, y + 6)], RESTITUTION.mix(0.15).filled()));
    }
    legend(&mut chart, SeriesLabelPosition::UpperLeft)
}

fn velocities<DB: DrawingBackend<ErrorType: 'static>>(
    report: &Report,
    history: &History,
    root: &DrawingArea<DB, Shift>,
) -> Drawn {
    let c = &report.contact;
    let n = history.normal;
    let start = c.start_time;
    let end = history.samples.last().map_or(start, |s| s.time);
    let (tf, tp) = prefix(end - start);
    let normal = |v: &[f64; 3]| v[0] * n.x + v[1] * n.y + v[2] * n.z;
    // (label, value, colour, dash length): long dashes for V0 and the instantaneous values after, short for before.
    let mut references: Vec<(String, f64, RGBColor, u32)> =
        vec![(format!("V0 = {} m/s", fixed(c.common_normal_velocity)), c.common_normal_velocity, BLACK, 8)];
    for (i, color) in [(0, COMPRESSION), (1, BODY_2)] {
        let value = normal(&report.bodies[i].velocity_before);
        references.push((format!("body {} before: {} m/s", i + 1, fixed(value)), value, color, 2));
    }
    if let Some(ideal) = &report.instantaneous {
        for (i, color) in [(0, COMPRESSION), (1, BODY_2)] {
            let value = normal(&ideal.velocity_after[i]);
            let label =
                format!("body {} after, instantaneous (e = {:.4}): {} m/s", i + 1, ideal.restitution, fixed(value));
            references.push((label, value, color, 8));
        }
    }
    let mut values: Vec<f64> =
        history.samples.iter().flat_map(|s| [s.velocities[0].dot(&n), s.velocities[1].dot(&n)]).collect();
    values.extend(references.iter().map(|r| r.1));
    let (low, high) = values.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| (a.min(v), b.max(v)));
    let pad = 0.08 * (high - low).max(1e-12);
    // Headroom above the curves for the legend, so it never hides the crossing at V0.
    let headroom = 0.6 * (high - low).max(1e-12);
    let mut chart = frame(root, &caption(report, "normal velocities"), 22)
        .build_cartesian_2d(0.0..(end - start) / tf, (low - pad)..(high + headroom))?;
    chart
        .configure_mesh()
        .x_desc(format!("time since first contact ({tp}s)"))
        .y_desc("normal velocity (m/s)")
        .y_label_formatter(&|v| {
            let text = format!("{v:.2}");
            if text.trim_start_matches('-').chars().all(|c| c == '0' || c == '.') { "0".into() } else { text }
        })
        .light_line_style(BLACK.mix(0.04))
        .axis_desc_style((FONT, 20))
        .label_style((FONT, 16))
        .draw()?;
    let x_max = (end - start) / tf;
    for (label, value, color, dash) in references {
        chart
            .draw_series(DashedLineSeries::new([(0.0, value), (x_max, value)], dash, 5, color.stroke_width(1)))?
            .label(label)
            .legend(move |(x, y)| {
                // Three dashes of the line's own length (capped to fit the 18-pixel key).
                let length = dash.min(5) as i32;
                EmptyElement::at((x, y))
                    + PathElement::new([(0, 0), (length, 0)], color.stroke_width(1))
                    + PathElement::new([(7, 0), (7 + length, 0)], color.stroke_width(1))
                    + PathElement::new([(14, 0), (14 + length, 0)], color.stroke_width(1))
            });
    }
    for (i, color) in [(0usize, COMPRESSION), (1, BODY_2)] {
        let name = report.bodies[i].name.clone();
        chart
            .draw_series(LineSeries::new(
                history.samples.iter().map(|s| ((s.time - start) / tf, s.velocities[i].dot(&n))),
                color.stroke_width(3),
            ))?
            .label(name)
            .legend(move |(x, y)| PathElement::new([(x, y), (x + 18, y)], color.stroke_width(3)));
    }
    legend(&mut chart, SeriesLabelPosition::UpperRight)
}

/// The legend box every figure of the project uses, at `position`.
pub fn legend<'a, DB: DrawingBackend<ErrorType: 'static> + 'a, X: Ranged, Y: Ranged>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<X, Y>>,
    position: SeriesLabelPosition,
) -> Drawn {
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font((FONT, 16))
        .position(position)
        .draw()?;
    Ok(())
}
