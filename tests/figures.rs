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
        "kelvin_voigt_force_penetration.png",
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
    assert_eq!(left.len(), 4, "only the figures: {left:?}");
}
