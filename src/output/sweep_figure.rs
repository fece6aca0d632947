//! The figure of a sweep, PNG or SVG by the file's extension (the PNG rasterised from the SVG, see
//! [`super::chart`]): effective e against the first varied quantity, one line per law (and per value of the other
//! varied keys), with the ideal diagonal e_eff = e_nominal when the x axis is the nominal e — the comparison figure
//! of the contact-mechanics literature. The diagonal is drawn over the curves, so that it stays visible where a map
//! is exact.

use super::chart::{self, Axis, Chart, Colour, Layer, Mark, Marker, Stroke};
use super::figures::caption;
use super::incidence_figure::{self, IncidenceFigure};
use super::map_figure::{self, IdealisationMap};
use super::render;
use anyhow::{Context, anyhow};
use std::path::{Path, PathBuf};

/// Figure size in pixels.
pub const SIZE: (u32, u32) = (chart::WIDTH as u32, chart::HEIGHT as u32);

/// Curves with at most this many points show a marker at every point (more would hide the lines).
const MARKED: usize = 25;

/// The figure a sweep draws: effective e ([`SweepFigure`]), or the oblique-impact panels of a sweep over the angle
/// of incidence ([`IncidenceFigure`]), or the idealisation map of a sweep over two keys (`--map`,
/// [`IdealisationMap`]).
#[derive(Debug, Clone, PartialEq)]
pub enum SweepPlot {
    Restitution(SweepFigure),
    Incidence(IncidenceFigure),
    Map(IdealisationMap),
}

impl SweepPlot {
    /// The figure as an SVG document.
    pub fn svg(&self) -> String {
        match self {
            SweepPlot::Restitution(figure) => svg(figure),
            SweepPlot::Incidence(figure) => incidence_figure::svg(figure),
            SweepPlot::Map(map) => map_figure::svg(map),
        }
    }
}

/// What a sweep figure shows: a function of the sweep's table, nothing else.
#[derive(Debug, Clone, PartialEq)]
pub struct SweepFigure {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    /// Draw the ideal line y = x.
    pub diagonal: bool,
    /// Logarithmic x axis.
    pub log_x: bool,
    pub curves: Vec<Curve>,
}

/// One line of the figure; `None` points are gaps (rows without a value).
#[derive(Debug, Clone, PartialEq)]
pub struct Curve {
    pub label: String,
    pub points: Vec<Option<(f64, f64)>>,
}

impl SweepFigure {
    fn known(&self) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.curves.iter().flat_map(|c| c.points.iter().flatten().copied())
    }

    /// The x range (positive for a log axis), padded when it is a single value; the whole of [0, 1] against the
    /// nominal e.
    fn x_range(&self) -> (f64, f64) {
        let (low, high) = self.data_x_range();
        if self.diagonal && !self.log_x { (low.min(0.0), high.max(1.0)) } else { (low, high) }
    }

    fn data_x_range(&self) -> (f64, f64) {
        let xs = self.known().map(|p| p.0).filter(|x| !self.log_x || *x > 0.0);
        let (low, high) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| (a.min(x), b.max(x)));
        match (low.is_finite(), self.log_x) {
            (false, true) => (0.1, 1.0),
            (false, false) => (0.0, 1.0),
            (true, true) if low == high => (low / 2.0, high * 2.0),
            (true, false) if low == high => (low - low.abs().max(1.0) * 0.05, high + low.abs().max(1.0) * 0.05),
            (true, _) => (low, high),
        }
    }

    /// The y range: at least [0, 1] (e lives there), wider if a value falls outside.
    fn y_range(&self) -> (f64, f64) {
        let (low, high) = self.known().fold((0.0f64, 1.0f64), |(a, b), p| (a.min(p.1), b.max(p.1)));
        let pad = 0.04 * (high - low);
        (low - if low < 0.0 { pad } else { 0.0 }, high + pad)
    }
}

/// A figure rendered to a temporary file beside its target; [`Staged::commit`] renames it into place, dropping it
/// uncommitted removes it. So a sweep can render its figure, write its CSV, and only then show both.
#[derive(Debug)]
pub struct Staged {
    temporary: PathBuf,
    target: PathBuf,
    committed: bool,
}

impl Staged {
    /// Moves the figure into place; returns its path.
    pub fn commit(mut self) -> anyhow::Result<PathBuf> {
        std::fs::rename(&self.temporary, &self.target)
            .with_context(|| format!("cannot write {}", self.target.display()))?;
        self.committed = true;
        Ok(self.target.clone())
    }
}

impl Drop for Staged {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_file(&self.temporary);
        }
    }
}

/// Whether `path` names a figure format this module writes (`.png` or `.svg`, any case).
pub fn format_of(path: &Path) -> Option<&'static str> {
    match path.extension()?.to_str()?.to_ascii_lowercase().as_str() {
        "png" => Some("png"),
        "svg" => Some("svg"),
        _ => None,
    }
}

/// Renders `figure` to a temporary file in `target`'s folder (created if missing), PNG or SVG by `target`'s
/// extension.
pub fn stage(figure: &SweepPlot, target: &Path) -> anyhow::Result<Staged> {
    let format = format_of(target).ok_or_else(|| anyhow!("{}: a figure must end in .png or .svg", target.display()))?;
    let svg = figure.svg();
    let bytes = if format == "png" {
        render::png(&svg).with_context(|| format!("cannot render {}", target.display()))?
    } else {
        svg.into_bytes()
    };
    let folder = target.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    std::fs::create_dir_all(folder).with_context(|| format!("cannot create the folder {}", folder.display()))?;
    let name = target.file_name().with_context(|| format!("{} is not a file path", target.display()))?;
    let temporary = folder.join(format!(".{}.partial-{}.{format}", name.to_string_lossy(), std::process::id()));
    let staged = Staged { temporary: temporary.clone(), target: target.to_path_buf(), committed: false };
    std::fs::write(&temporary, bytes).with_context(|| format!("cannot write {}", target.display()))?;
    Ok(staged)
}

/// Renders `figure` into an RGB pixel buffer of [`SIZE`] (row-major, 3 bytes a pixel): for checks of the image.
pub fn render_rgb(figure: &SweepFigure) -> anyhow::Result<Vec<u8>> {
    render::rgb(&svg(figure))
}

/// The figure as an SVG document.
pub fn svg(figure: &SweepFigure) -> String {
    chart(figure).svg()
}

/// The chart of the figure.
pub fn chart(figure: &SweepFigure) -> Chart {
    let (x0, x1) = figure.x_range();
    let (y0, y1) = figure.y_range();
    let x = if figure.log_x {
        Axis::log(figure.x_label.as_str(), x0, x1)
    } else {
        Axis::linear(figure.x_label.as_str(), x0, x1)
    };
    let mut chart = Chart::new(caption(&figure.title, ""), x, Axis::linear(figure.y_label.as_str(), y0, y1));
    for (i, curve) in figure.curves.iter().enumerate() {
        let colour = chart::PALETTE[i % chart::PALETTE.len()];
        let shape = chart::SHAPES[i % chart::SHAPES.len()];
        let rank = i as i32;
        if curve.points.iter().all(Option::is_none) {
            // Still in the legend, so that a law whose every row failed is not silently missing.
            let empty = Mark::Line { points: Vec::new(), stroke: Stroke::solid(colour, 1.0), marker: None };
            let label = format!("{} (no value: see the status column)", curve.label);
            chart.push(Layer::new("curve", empty).label(label).rank(rank));
            continue;
        }
        let marked = curve.points.iter().flatten().count() <= MARKED;
        // A gap (a row without a value) breaks the line; a lone point keeps a marker so that it shows.
        let runs = curve.points.split(Option::is_none).filter(|run| !run.is_empty());
        for (j, run) in runs.enumerate() {
            let points: Vec<(f64, f64)> = run.iter().flatten().copied().collect();
            let marker = (marked || points.len() == 1).then(|| Marker::new(shape, 3.5, colour));
            let line = Mark::Line { points, stroke: Stroke::solid(colour, 2.0), marker };
            let layer = Layer::new("curve", line);
            chart.push(if j == 0 { layer.label(curve.label.as_str()).rank(rank) } else { layer });
        }
    }
    if figure.diagonal {
        // Over the curves, so that it stays visible where a map is exact. Sampled, so that it stays the line y = x
        // on a log axis too.
        let line: Vec<(f64, f64)> = (0..=200)
            .map(|i| {
                let t = f64::from(i) / 200.0;
                let x = if figure.log_x { x0 * (x1 / x0).powf(t) } else { x0 + (x1 - x0) * t };
                (x, x)
            })
            .collect();
        let diagonal = Mark::Line { points: line, stroke: Stroke::dashed(Colour::BLACK, 1.3, 6.0, 5.0), marker: None };
        chart.push(Layer::new("diagonal", diagonal).label("ideal: effective e = nominal e").rank(-1));
    }
    chart
}
