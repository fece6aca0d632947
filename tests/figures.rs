//! The figures as a reviewer would look at them: anti-aliased PNGs with rendered text, SVGs with fractional
//! coordinates, the dissipated-energy loop filled, legend symbols in the style of their lines, ticks of one
//! precision per axis, labelled log decades, units on the axes, no empty band kept for the legend, bodies called by
//! their names, reference lines over what they are compared with, and a gallery that reports only what it wrote.

mod common;

use common::binary::{Scratch, impact};
use resvg::tiny_skia::Pixmap;
use std::collections::BTreeSet;

/// Two named steel balls closing at 2 m/s, Hunt–Crossley with e = 0.7 (separation at zero penetration).
const SCENE: &str = "title = \"figure test\"\n\
    [[bodies]]\nname = \"striker\"\nradius = 0.01\ndensity = 7850\nvelocity = [1.5, 0, 0]\nyoung = 2.1e11\npoisson = 0.3\n\
    [[bodies]]\nname = \"anvil\"\nradius = 0.02\ndensity = 7850\nvelocity = [-0.5, 0, 0]\nyoung = 2.1e11\npoisson = 0.3\n\
    [contact]\nlaw = \"hunt-crossley\"\nrestitution = 0.7\n";

/// The three figures of [`SCENE`]: (name, SVG text, PNG pixels).
struct Figures {
    _scratch: Scratch,
    figures: Vec<(&'static str, String, Pixmap)>,
}

impl Figures {
    fn render(test: &str) -> Figures {
        let scratch = Scratch::new(test);
        std::fs::write(scratch.path().join("s.toml"), SCENE).expect("write the scene");
        let out = impact(scratch.path(), &["run", "s.toml", "--plot", "figs"]);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
        let figures = ["force_time", "force_penetration", "velocities"]
            .into_iter()
            .map(|name| {
                let folder = scratch.path().join("figs");
                let svg = std::fs::read_to_string(folder.join(format!("{name}.svg"))).expect("the SVG");
                let png = std::fs::read(folder.join(format!("{name}.png"))).expect("the PNG");
                (name, svg, Pixmap::decode_png(&png).expect("a PNG"))
            })
            .collect();
        Figures { _scratch: scratch, figures }
    }

    fn get(&self, name: &str) -> (&str, &Pixmap) {
        let (_, svg, png) = self.figures.iter().find(|f| f.0 == name).expect("a figure of that name");
        (svg, png)
    }
}

/// The opening tags `<TAG ...>` in `svg`.
fn tags<'a>(svg: &'a str, tag: &str) -> Vec<&'a str> {
    let open = format!("<{tag} ");
    svg.match_indices(&open).map(|(i, _)| &svg[i..i + svg[i..].find('>').expect("a closed tag") + 1]).collect()
}

/// The value of attribute `name` in an opening tag.
fn attribute<'a>(tag: &'a str, name: &str) -> Option<&'a str> {
    let key = format!(" {name}=\"");
    let start = tag.find(&key)? + key.len();
    Some(&tag[start..start + tag[start..].find('"')?])
}

fn number(tag: &str, name: &str) -> f64 {
    attribute(tag, name).and_then(|v| v.parse().ok()).unwrap_or_else(|| panic!("no number {name} in {tag}"))
}

/// The contents of the groups `<g class="CLASS">...</g>` (not nested), in document order.
fn groups<'a>(svg: &'a str, class: &str) -> Vec<&'a str> {
    let open = format!("<g class=\"{class}\">");
    svg.match_indices(&open)
        .map(|(i, _)| {
            let body = &svg[i + open.len()..];
            &body[..body.find("</g>").expect("a closed group")]
        })
        .collect()
}

/// The texts of the `<text class="CLASS"` elements, tags (superscripts) stripped.
fn texts(svg: &str, class: &str) -> Vec<String> {
    let open = format!("<text class=\"{class}\"");
    svg.match_indices(&open)
        .map(|(i, _)| {
            let body = &svg[i..];
            let inner = &body[body.find('>').expect("a tag") + 1..body.find("</text>").expect("a closed text")];
            let mut plain = String::new();
            let mut in_tag = false;
            for c in inner.chars() {
                match c {
                    '<' => in_tag = true,
                    '>' => in_tag = false,
                    _ if !in_tag => plain.push(c),
                    _ => {}
                }
            }
            plain
        })
        .collect()
}

/// The points of a polyline.
fn points(polyline: &str) -> Vec<(f64, f64)> {
    attribute(polyline, "points")
        .expect("points")
        .split_whitespace()
        .map(|pair| {
            let (x, y) = pair.split_once(',').expect("x,y");
            (x.parse().expect("x"), y.parse().expect("y"))
        })
        .collect()
}

fn pixel(png: &Pixmap, x: i64, y: i64) -> [u8; 3] {
    let p = png.pixel(x as u32, y as u32).expect("inside the image");
    [p.red(), p.green(), p.blue()]
}

#[test]
fn png_lines_are_anti_aliased() {
    let figures = Figures::render("png_lines_are_anti_aliased");
    let (svg, png) = figures.get("force_time");
    let curve = groups(svg, "curve");
    let line = points(tags(curve.first().expect("the force curve"), "polyline")[0]);
    // Around 20 points along the pulse, away from the peak marker and the line of maximum compression: a line
    // without anti-aliasing shows its colour, the two phases' shadings and the grid lines; smooth edges blend the
    // line into the background in many shades.
    let mut colours: BTreeSet<[u8; 3]> = BTreeSet::new();
    for i in 0..20 {
        let fraction = if i < 10 { 0.02 + 0.03 * f64::from(i) } else { 0.55 + 0.04 * f64::from(i - 10) };
        let (x, y) = line[(fraction * (line.len() - 1) as f64) as usize];
        let (x, y) = (x.round() as i64, y.round() as i64);
        colours.extend((-3..=3).flat_map(|dx| (-3..=3).map(move |dy| pixel(png, x + dx, y + dy))));
    }
    assert!(colours.len() >= 20, "only {} colours around the line: not anti-aliased", colours.len());
}

#[test]
fn text_is_rendered_with_the_embedded_font() {
    let figures = Figures::render("text_is_rendered_with_the_embedded_font");
    for (name, svg, png) in &figures.figures {
        for class in ["axis-label x", "title"] {
            let tag = tags(svg, "text").into_iter().find(|t| attribute(t, "class") == Some(class)).expect("a label");
            let (x, y) = (number(tag, "x") as i64, number(tag, "y") as i64);
            let dark = (x - 80..x + 80)
                .flat_map(|px| (y - 14..y + 4).map(move |py| (px, py)))
                .filter(|&(px, py)| pixel(png, px, py).iter().all(|&c| c < 110))
                .count();
            assert!(dark > 80, "{name}: only {dark} dark pixels where the {class} is written");
        }
    }
}

#[test]
fn svg_data_have_fractional_coordinates() {
    let figures = Figures::render("svg_data_have_fractional_coordinates");
    for (name, svg, _) in &figures.figures {
        let coordinates: Vec<f64> =
            tags(svg, "polyline").iter().flat_map(|p| points(p)).flat_map(|(x, y)| [x, y]).collect();
        let fractional = coordinates.iter().filter(|c| c.fract() != 0.0).count();
        assert!(
            fractional * 2 > coordinates.len(),
            "{name}: {fractional} of {} coordinates are fractional",
            coordinates.len()
        );
    }
}

#[test]
fn the_dissipated_energy_loop_is_filled_and_its_legend_swatch_matches() {
    let figures = Figures::render("the_dissipated_energy_loop_is_filled_and_its_legend_swatch_matches");
    let (svg, _) = figures.get("force_penetration");
    let fill = groups(svg, "loop-fill");
    let polygon = tags(fill.first().expect("a loop-fill layer"), "polygon")[0];
    let opacity = number(polygon, "fill-opacity");
    assert!(opacity > 0.0 && opacity < 0.5, "a light translucent fill, not {opacity}");
    assert!(points(polygon).len() > 100, "the loop's outline");
    let legend = groups(svg, "legend-entry");
    let swatch = legend
        .iter()
        .find(|entry| entry.contains("energy dissipated"))
        .and_then(|entry| tags(entry, "rect").into_iter().next())
        .expect("a legend entry with a swatch for the loop");
    assert_eq!(attribute(swatch, "fill"), attribute(polygon, "fill"));
    assert_eq!(attribute(swatch, "fill-opacity"), attribute(polygon, "fill-opacity"));
}

/// The dash patterns of a figure: (in the legend, in the plot).
fn dash_patterns(svg: &str) -> (BTreeSet<String>, BTreeSet<String>) {
    let legend_start = svg.find("<g class=\"legend\">").unwrap_or(svg.len());
    let pattern = |tag: &&str| attribute(tag, "stroke-dasharray").map(String::from);
    let (plot, legend) = svg.split_at(legend_start);
    let collect = |part: &str| -> BTreeSet<String> {
        ["line", "polyline"].iter().flat_map(|t| tags(part, t)).filter_map(|t| pattern(&t)).collect()
    };
    (collect(legend), collect(plot))
}

#[test]
fn legend_symbols_are_dashed_like_their_lines() {
    let figures = Figures::render("legend_symbols_are_dashed_like_their_lines");
    for name in ["force_time", "velocities"] {
        let (svg, _) = figures.get(name);
        let (legend, plot) = dash_patterns(svg);
        assert!(!plot.is_empty(), "{name} has dashed reference lines");
        assert_eq!(legend, plot, "{name}: the legend's dash patterns are the lines'");
    }
}

/// Decimals of a tick label (digits after the point).
fn decimals(label: &str) -> usize {
    label.split_once('.').map_or(0, |(_, fraction)| fraction.len())
}

#[test]
fn tick_labels_of_an_axis_share_their_precision() {
    let figures = Figures::render("tick_labels_of_an_axis_share_their_precision");
    for (name, svg, _) in &figures.figures {
        for class in ["tick-x", "tick-y"] {
            let labels = texts(svg, class);
            assert!(labels.len() >= 3, "{name}: {class} has {labels:?}");
            let precision: BTreeSet<usize> = labels.iter().map(|l| decimals(l)).collect();
            assert_eq!(precision.len(), 1, "{name}: {class} labels {labels:?} mix precisions");
        }
    }
}

#[test]
fn axes_are_labelled_with_scaled_units() {
    let figures = Figures::render("axes_are_labelled_with_scaled_units");
    let (force_time, _) = figures.get("force_time");
    assert!(texts(force_time, "axis-label x")[0].contains("(µs)"), "{:?}", texts(force_time, "axis-label x"));
    assert!(texts(force_time, "axis-label y")[0].contains("(kN)"), "{:?}", texts(force_time, "axis-label y"));
    let (loop_figure, _) = figures.get("force_penetration");
    assert!(texts(loop_figure, "axis-label x")[0].contains("(µm)"), "{:?}", texts(loop_figure, "axis-label x"));
}

#[test]
fn the_velocity_figure_names_the_bodies_and_keeps_no_empty_band() {
    let figures = Figures::render("the_velocity_figure_names_the_bodies_and_keeps_no_empty_band");
    let (svg, _) = figures.get("velocities");
    assert!(svg.contains("striker") && svg.contains("anvil"), "the bodies' names");
    assert!(!svg.contains("body 1") && !svg.contains("body 2"), "no second naming of the bodies");
    // The highest curve or reference line reaches the top of the plot, give or take the margin.
    let frame = tags(svg, "rect").into_iter().find(|t| attribute(t, "class") == Some("frame")).expect("the frame");
    let (top, height) = (number(frame, "y"), number(frame, "height"));
    let highest = groups(svg, "curve")
        .iter()
        .flat_map(|g| tags(g, "polyline"))
        .flat_map(points)
        .map(|p| p.1)
        .fold(f64::INFINITY, f64::min);
    assert!(highest - top < 0.1 * height, "the data start {} px below the plot's top", highest - top);
}

#[test]
fn reference_lines_stay_visible_over_the_curves() {
    let figures = Figures::render("reference_lines_stay_visible_over_the_curves");
    let (svg, _) = figures.get("velocities");
    let last_curve = svg.rfind("<g class=\"curve\">").expect("curves");
    let first_reference = svg.find("<g class=\"reference\">").expect("reference lines");
    assert!(first_reference > last_curve, "the reference lines are drawn over the curves");
}

// ---------------------------------------------------------------------------------------------------------------
// Sweep figures and the gallery

const SWEEP_SCENE: &str = "[[bodies]]\nradius = 0.01\ndensity = 7850\nvelocity = [1.0, 0, 0]\nyoung = 2.1e11\n\
    poisson = 0.3\n[[bodies]]\nradius = 0.01\ndensity = 7850\nvelocity = [-1.0, 0, 0]\nyoung = 2.1e11\npoisson = 0.3\n\
    [contact]\nlaw = \"hunt-crossley\"\nrestitution = 0.5\n";

#[test]
fn a_log_damping_axis_labels_every_decade_in_the_laws_units() {
    let scratch = Scratch::new("log-axis");
    std::fs::write(scratch.path().join("s.toml"), SWEEP_SCENE).expect("write the scene");
    let args = ["sweep", "s.toml", "--vary", "contact.damping=0.01:100:9:log", "--out", "d.csv", "--plot", "d.svg"];
    let out = impact(scratch.path(), &args);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let svg = scratch.read("d.svg");
    assert_eq!(texts(&svg, "tick-x"), ["10\u{2212}2", "10\u{2212}1", "100", "101", "102"], "10^k at every decade");
    let label = &texts(&svg, "axis-label x")[0];
    assert!(label.contains("(s/m)") && !label.contains("law units"), "{label}");
}

#[test]
fn the_ideal_diagonal_is_drawn_over_the_curves_and_dashed_in_the_legend() {
    let scratch = Scratch::new("diagonal");
    std::fs::write(scratch.path().join("s.toml"), SWEEP_SCENE).expect("write the scene");
    let args = [
        "sweep",
        "s.toml",
        "--vary",
        "contact.restitution=0.1:0.9:5",
        "--law",
        "carvalho-martins,hunt-crossley",
        "--out",
        "e.csv",
        "--plot",
        "e.svg",
    ];
    let out = impact(scratch.path(), &args);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let svg = scratch.read("e.svg");
    let diagonal = svg.find("<g class=\"diagonal\">").expect("the diagonal");
    assert!(diagonal > svg.rfind("<g class=\"curve\">").expect("curves"), "the diagonal is drawn last");
    let (legend, plot) = dash_patterns(&svg);
    assert!(!plot.is_empty() && legend == plot, "legend {legend:?}, plot {plot:?}");
    for class in ["tick-x", "tick-y"] {
        let precision: BTreeSet<usize> = texts(&svg, class).iter().map(|l| decimals(l)).collect();
        assert_eq!(precision.len(), 1, "{class}: {:?}", texts(&svg, class));
    }
}

#[test]
fn the_gallery_reports_only_the_figures_it_leaves() {
    let scratch = Scratch::new("gallery");
    let out = impact(scratch.path(), &["gallery", "--out", "g"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let said = format!("{}{}", String::from_utf8_lossy(&out.stdout), String::from_utf8_lossy(&out.stderr));
    let paths: Vec<&str> = said.lines().filter_map(|line| line.strip_prefix("wrote ")).collect();
    let mut expected = [
        "demo_force_time.png",
        "demo_velocities.png",
        "effective_restitution.png",
        "restitution_speed.png",
        "kelvin_voigt_force_penetration.png",
        "chung_ooi_20deg_force_time.png",
        "chung_ooi_test4.png",
        "bouncing_ball_heights.png",
        "newtons_cradle_3_velocities.png",
        "rod_angle_sweep.png",
    ]
    .map(|name| format!("g/{name}"));
    let mut reported: Vec<String> = paths.iter().map(|p| p.to_string()).collect();
    reported.sort();
    expected.sort();
    assert_eq!(reported, expected, "it said:\n{said}");
    for path in &reported {
        assert!(scratch.path().join(path).is_file(), "{path} was reported but is not there");
    }
    let mut left: Vec<String> = std::fs::read_dir(scratch.path().join("g"))
        .expect("the gallery folder")
        .map(|e| e.expect("an entry").file_name().to_string_lossy().into_owned())
        .collect();
    left.sort();
    assert_eq!(left.len(), expected.len(), "only the figures: {left:?}");
}

// ---------------------------------------------------------------------------------------------------------------
// Oblique impacts with friction

/// Chung & Ooi's test 4 (docs/oblique.md#chung-and-ooi-test-4): an alumina sphere (r = 2.5 mm) on a rigid wall at
/// 3.9 m/s, mu = 0.092, e = 0.98 from Tsuji's exact map; at `degrees` from the normal, with friction `mu`.
fn alumina_on_wall(degrees: f64, mu: f64) -> String {
    let (s, c) = degrees.to_radians().sin_cos();
    format!(
        "title = \"alumina\"\n[[bodies]]\nname = \"sphere\"\nradius = 0.0025\ndensity = 4000\n\
         velocity = [{}, 0.0, {}]\nyoung = 3.8e11\npoisson = 0.23\n\
         [[bodies]]\nname = \"wall\"\nradius = inf\nmass = inf\nvelocity = [0.0, 0.0, 0.0]\nyoung = inf\n\
         [contact]\nlaw = \"tsuji\"\nrestitution = 0.98\nfriction = {mu}\nnormal = [0.0, 0.0, -1.0]\n",
        3.9 * s,
        -3.9 * c
    )
}

/// The force–time SVG of `scene`.
fn force_time_of(scratch: &Scratch, scene: &str, folder: &str) -> String {
    std::fs::write(scratch.path().join(format!("{folder}.toml")), scene).expect("write the scene");
    let out = impact(scratch.path(), &["run", &format!("{folder}.toml"), "--plot", folder]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    scratch.read(&format!("{folder}/force_time.svg"))
}

/// The panels `<g class="panel" ...>...` of a stacked figure, in order (each up to the next panel or the end).
fn panels(svg: &str) -> Vec<&str> {
    let starts: Vec<usize> = svg.match_indices("<g class=\"panel\"").map(|(i, _)| i).collect();
    starts.iter().enumerate().map(|(k, &i)| &svg[i..starts.get(k + 1).copied().unwrap_or(svg.len())]).collect()
}

/// The y of a horizontal line (the first `<line` in the group of class `class`).
fn line_y(svg: &str, class: &str) -> f64 {
    let group = groups(svg, class);
    number(tags(group.first().unwrap_or_else(|| panic!("a {class} line")), "line")[0], "y1")
}

#[test]
fn the_tangential_force_panel_belongs_to_frictional_contacts_only() {
    let scratch = Scratch::new("tangential_force_panel");
    // Central and frictionless, oblique and smooth: one panel, no tangential force, as before.
    let central = Figures::render("tangential_force_panel_central");
    let smooth = force_time_of(&scratch, &alumina_on_wall(20.0, 0.0), "smooth");
    for svg in [central.get("force_time").0, smooth.as_str()] {
        assert!(panels(svg).is_empty(), "a single chart");
        assert!(!svg.contains("class=\"coulomb\"") && !svg.contains("tangential"), "no tangential force");
    }

    // At 20 degrees the sphere slides, holds below the Coulomb limit (the force turns round) and slides back; its
    // contact points' slip comes to rest on the way.
    let svg = force_time_of(&scratch, &alumina_on_wall(20.0, 0.092), "friction");
    let [normal, tangential] = panels(&svg)[..] else { panic!("two panels: normal and tangential force") };
    assert!(texts(normal, "axis-label y")[0].starts_with("normal force"), "{:?}", texts(normal, "axis-label y"));
    assert!(texts(normal, "tick-x").is_empty() && texts(normal, "axis-label x").is_empty(), "one time axis, below");
    assert!(texts(tangential, "axis-label x")[0].contains("(µs)"));
    assert!(texts(tangential, "axis-label y")[0].contains("tangential force (N)"));
    assert!(tangential.contains("μ = 0.092"), "the friction coefficient in the legend");
    assert!(!groups(tangential, "below").is_empty(), "the stretches below the Coulomb limit shaded");
    assert!(!groups(tangential, "rest").is_empty(), "the slip's rest marked");
    let frames: Vec<f64> = [normal, tangential]
        .iter()
        .map(|p| number(tags(p, "rect").into_iter().find(|t| attribute(t, "class") == Some("frame")).unwrap(), "x"))
        .collect();
    assert_eq!(frames[0], frames[1], "the panels' plot areas are aligned");

    // The Coulomb limits, dashed like their legend symbol, above and below (the force reverses).
    let coulomb: Vec<Vec<(f64, f64)>> =
        groups(tangential, "coulomb").iter().map(|g| points(tags(g, "polyline")[0])).collect();
    assert_eq!(coulomb.len(), 2, "+μF and −μF");
    let (legend, plot) = dash_patterns(tangential);
    assert!(!plot.is_empty() && legend.is_subset(&plot), "legend {legend:?}, plot {plot:?}");
    let dashed = attribute(tags(groups(tangential, "coulomb")[0], "polyline")[0], "stroke-dasharray");
    assert!(dashed.is_some(), "the Coulomb limit is dashed");

    // Measured from the zero lines: the limit is mu F, so it follows the normal force at one ratio, and the tangential
    // force never leaves it (Coulomb's law), reaching it where the contact slides.
    let normal_force = points(tags(groups(normal, "curve")[0], "polyline")[0]);
    let tangential_force = points(tags(groups(tangential, "curve")[0], "polyline")[0]);
    let (zero_n, zero_t) = (line_y(normal, "zero"), line_y(tangential, "zero"));
    assert_eq!(normal_force.len(), coulomb[0].len());
    let peak = normal_force.iter().map(|p| zero_n - p.1).fold(0.0, f64::max);
    let ratios: Vec<f64> = normal_force
        .iter()
        .zip(&coulomb[0])
        .filter(|(n, _)| zero_n - n.1 > 0.2 * peak)
        .map(|(n, c)| (zero_t - c.1) / (zero_n - n.1))
        .collect();
    let (low, high) = ratios.iter().fold((f64::INFINITY, 0.0f64), |(a, b), &r| (a.min(r), b.max(r)));
    assert!(high / low < 1.01, "limit / normal force from {low} to {high}");
    let mut on_limit = 0;
    for ((t, upper), lower) in tangential_force.iter().zip(&coulomb[0]).zip(&coulomb[1]) {
        assert!(t.1 >= upper.1 - 0.6 && t.1 <= lower.1 + 0.6, "the tangential force beyond μF at x = {}", t.0);
        on_limit += usize::from((t.1 - upper.1).abs() < 0.6 || (t.1 - lower.1).abs() < 0.6);
    }
    assert!(on_limit > tangential_force.len() / 3, "sliding on the limit at {on_limit} samples");
    assert!(tangential_force.iter().any(|t| t.1 > zero_t + 5.0), "the force turns round");
}

/// A chart's axis as (value, pixel) pairs of its major ticks: the grid lines (vertical for x, horizontal for y) with
/// the tick labels, in the same order.
fn axis(svg: &str, x: bool) -> Vec<(f64, f64)> {
    let start = svg.find("<g class=\"grid\"").expect("a grid");
    let grid = &svg[start..start + svg[start..].find("</g>").expect("closed")];
    let lines: Vec<f64> = tags(grid, "line")
        .into_iter()
        .filter(|l| (number(l, "x1") == number(l, "x2")) == x)
        .map(|l| number(l, if x { "x1" } else { "y1" }))
        .collect();
    let labels = texts(svg, if x { "tick-x" } else { "tick-y" });
    let values = labels.iter().map(|l| l.replace('\u{2212}', "-").parse::<f64>().expect("a number"));
    values.zip(lines).collect()
}

/// The pixel of `value` on an axis (linear between its outer ticks).
fn to_pixel(axis: &[(f64, f64)], value: f64) -> f64 {
    let ((v0, p0), (v1, p1)) = (axis[0], axis[axis.len() - 1]);
    p0 + (value - v0) * (p1 - p0) / (v1 - v0)
}

#[test]
fn the_incidence_sweep_figure_has_three_panels_of_simulation_and_rigid_theory() {
    let scratch = Scratch::new("incidence_figure");
    let model = concat!(env!("CARGO_MANIFEST_DIR"), "/models/chung-ooi-test4.toml");
    std::fs::copy(model, scratch.path().join("t4.toml")).expect("the model");
    let args = ["sweep", "t4.toml", "--vary", "bodies.0.incidence_deg=5:85:9", "--out", "t4.csv", "--plot", "t4.svg"];
    let out = impact(scratch.path(), &args);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let svg = scratch.read("t4.svg");
    let [a, b, c] = panels(&svg)[..] else { panic!("three panels") };
    let headings: Vec<String> = [a, b, c].iter().map(|p| texts(p, "heading")[0].clone()).collect();
    for (heading, start) in headings.iter().zip(["(a) tangential restitution", "(b) rebound spin", "(c) rebound angle"])
    {
        assert!(heading.starts_with(start), "{heading}");
    }
    assert!(texts(b, "axis-label y")[0].ends_with("(rad/s)") && texts(c, "axis-label y")[0].ends_with("(°)"));
    assert!(texts(a, "tick-x").is_empty() && texts(b, "tick-x").is_empty(), "one x axis, at the bottom");
    let x_label = &texts(c, "axis-label x")[0];
    assert!(x_label.contains("incidence") && x_label.ends_with("(°)"), "{x_label}");

    // Rigid-body theory of a sphere (I = 2/5 m r²) on a wall, e = 0.98, mu = 0.092: it sticks (rolls) below
    // tan(theta*) = (7/2) mu (1 + e), where the centre keeps 5/7 of its tangential velocity and spins at
    // omega = 5 v sin(theta) / (7 r); sliding, the tangential velocity loses mu (1 + e) v cos(theta) and
    // omega = 5 mu (1 + e) v cos(theta) / (2 r).
    let (mu, e, v, r) = (0.092f64, 0.98, 3.9, 0.0025);
    let threshold = (3.5 * mu * (1.0 + e)).atan();
    let sticks = |theta: f64| theta.tan() <= 3.5 * mu * (1.0 + e);
    let restitution = |t: f64| if sticks(t) { 5.0 / 7.0 } else { 1.0 - mu * (1.0 + e) / t.tan() };
    let spin =
        |t: f64| if sticks(t) { 5.0 * v * t.sin() / (7.0 * r) } else { 5.0 * mu * (1.0 + e) * v * t.cos() / (2.0 * r) };
    let x_axis = axis(c, true);
    for (panel, exact) in [(a, &restitution as &dyn Fn(f64) -> f64), (b, &spin)] {
        let y_axis = axis(panel, false);
        let rigid = points(tags(groups(panel, "rigid")[0], "polyline")[0]);
        assert_eq!(rigid.len(), 9);
        for (i, point) in rigid.iter().enumerate() {
            let degrees = 5.0 + 10.0 * i as f64;
            assert!((point.0 - to_pixel(&x_axis, degrees)).abs() < 0.6, "x of {degrees} degrees");
            let expected = to_pixel(&y_axis, exact(degrees.to_radians()));
            assert!(
                (point.1 - expected).abs() < 1.0,
                "rigid theory at {degrees} degrees: {} px off",
                point.1 - expected
            );
        }
    }
    for panel in [a, b, c] {
        let rigid = tags(groups(panel, "rigid")[0], "polyline")[0];
        assert!(attribute(rigid, "stroke-dasharray").is_some(), "rigid-body theory dashed");
        let simulated = groups(panel, "simulated")[0];
        assert_eq!(points(tags(simulated, "polyline")[0]).len(), 9);
        assert_eq!(tags(simulated, "circle").len(), 9, "a marker at every simulated point");
        // The rigid sliding threshold in every panel, at theta*.
        let line = tags(groups(panel, "threshold")[0], "line")[0];
        let expected = to_pixel(&x_axis, threshold.to_degrees());
        assert!((number(line, "x1") - expected).abs() < 0.6, "threshold at {} px, not {expected}", number(line, "x1"));
    }
    assert!(c.contains(&format!("θ* = {:.1}°", threshold.to_degrees())), "the threshold named in the legend");
    let (legend, plot) = dash_patterns(c);
    assert!(!legend.is_empty() && legend.is_subset(&plot), "legend {legend:?}, plot {plot:?}");

    // Mindlin's tangential compliance below the threshold: the centre keeps 0.89 of its tangential velocity at 5
    // degrees and 0.63 at 25 (Maw, Barber & Fawcett; Chung & Ooi), against rigid theory's 5/7.
    let (y_axis, simulated) = (axis(a, false), points(tags(groups(a, "simulated")[0], "polyline")[0]));
    for (i, physics) in [(0, 0.89), (2, 0.63)] {
        let expected = to_pixel(&y_axis, physics);
        let tolerance = (to_pixel(&y_axis, physics - 0.015) - expected).abs();
        assert!((simulated[i].1 - expected).abs() < tolerance, "tangential restitution at {} degrees", 5 + 10 * i);
    }
}

#[test]
fn merge_draws_the_incidence_figure_of_its_shards() {
    let scratch = Scratch::new("incidence_merge");
    let model = concat!(env!("CARGO_MANIFEST_DIR"), "/models/chung-ooi-test4.toml");
    std::fs::copy(model, scratch.path().join("t4.toml")).expect("the model");
    for shard in ["1/2", "2/2"] {
        let name = format!("s{}.csv", &shard[..1]);
        let args = ["sweep", "t4.toml", "--vary", "bodies.0.incidence_deg=10:70:4", "--shard", shard, "--out", &name];
        let out = impact(scratch.path(), &args);
        assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    }
    let out = impact(scratch.path(), &["merge", "all.csv", "s1.csv", "s2.csv", "--plot", "all.svg"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let svg = scratch.read("all.svg");
    assert_eq!(panels(&svg).len(), 3, "the incidence figure, not effective e");
    assert!(!svg.contains("effective e"));
}
