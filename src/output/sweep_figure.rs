//! The figure of a sweep (plotters, PNG or SVG by the file's extension, with the embedded font of
//! [`super::figures`]): effective e against the first varied quantity, one line per law (and per value of the
//! other varied keys), with the ideal diagonal e_eff = e_nominal when the x axis is the nominal e — the comparison
//! figure of the contact-mechanics literature.

use super::figures::{FONT, register_font};
use anyhow::{Context, anyhow};
use plotters::coord::Shift;
use plotters::coord::ranged1d::{AsRangedCoord, ValueFormatter};
use plotters::prelude::*;
use std::path::{Path, PathBuf};

/// Figure size in pixels.
pub const SIZE: (u32, u32) = (960, 640);

/// Line colours, in curve order (the tab10 palette).
const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

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

    /// The x range (positive for a log axis), padded when it is a single value.
    fn x_range(&self) -> (f64, f64) {
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
pub fn stage(figure: &SweepFigure, target: &Path) -> anyhow::Result<Staged> {
    register_font();
    let format = format_of(target).ok_or_else(|| anyhow!("{}: a figure must end in .png or .svg", target.display()))?;
    let folder = target.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    std::fs::create_dir_all(folder).with_context(|| format!("cannot create the folder {}", folder.display()))?;
    let name = target.file_name().with_context(|| format!("{} is not a file path", target.display()))?;
    // The extension stays last: the PNG encoder picks the format from it.
    let temporary = folder.join(format!(".{}.partial-{}.{format}", name.to_string_lossy(), std::process::id()));
    let staged = Staged { temporary: temporary.clone(), target: target.to_path_buf(), committed: false };
    let rendered = if format == "png" {
        let root = BitMapBackend::new(&temporary, SIZE).into_drawing_area();
        draw(figure, &root).and_then(|()| root.present().map_err(|e| anyhow!("{e}")))
    } else {
        let root = SVGBackend::new(&temporary, SIZE).into_drawing_area();
        draw(figure, &root).and_then(|()| root.present().map_err(|e| anyhow!("{e}")))
    };
    rendered.with_context(|| format!("cannot render {}", target.display()))?;
    Ok(staged)
}

/// Renders `figure` into an RGB pixel buffer of [`SIZE`] (row-major, 3 bytes a pixel): for checks of the image.
pub fn render_rgb(figure: &SweepFigure) -> anyhow::Result<Vec<u8>> {
    register_font();
    let mut pixels = vec![0u8; (SIZE.0 * SIZE.1 * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut pixels, SIZE).into_drawing_area();
        draw(figure, &root)?;
        root.present().map_err(|e| anyhow!("{e}"))?;
    }
    Ok(pixels)
}

/// Draws the whole figure on `root`.
pub fn draw<DB: DrawingBackend<ErrorType: 'static>>(
    figure: &SweepFigure,
    root: &DrawingArea<DB, Shift>,
) -> anyhow::Result<()> {
    root.fill(&WHITE).map_err(|e| anyhow!("{e:?}"))?;
    let (x0, x1) = figure.x_range();
    let drawn = if figure.log_x { chart(figure, root, (x0..x1).log_scale()) } else { chart(figure, root, x0..x1) };
    drawn.map_err(|e| anyhow!("cannot draw the sweep figure: {e}"))
}

type Drawn = Result<(), Box<dyn std::error::Error>>;

fn chart<DB, X>(figure: &SweepFigure, root: &DrawingArea<DB, Shift>, x_axis: X) -> Drawn
where
    DB: DrawingBackend<ErrorType: 'static>,
    X: AsRangedCoord<Value = f64>,
    X::CoordDescType: Ranged<ValueType = f64> + ValueFormatter<f64>,
{
    let (x0, x1) = figure.x_range();
    let (y0, y1) = figure.y_range();
    let mut chart = super::figures::frame(root, &figure.title, 26).build_cartesian_2d(x_axis, y0..y1)?;
    chart
        .configure_mesh()
        .x_desc(figure.x_label.as_str())
        .y_desc(figure.y_label.as_str())
        .axis_desc_style((FONT, 20))
        .label_style((FONT, 16))
        .draw()?;
    if figure.diagonal {
        // Sampled, so that it stays the line y = x on a log axis too.
        let line = (0..=200).map(|i| {
            let t = f64::from(i) / 200.0;
            let x = if figure.log_x { x0 * (x1 / x0).powf(t) } else { x0 + (x1 - x0) * t };
            (x, x)
        });
        chart
            .draw_series(DashedLineSeries::new(line.filter(|p| p.1 >= y0 && p.1 <= y1), 10, 6, BLACK.stroke_width(2)))?
            .label("ideal: effective e = nominal e")
            .legend(|(x, y)| PathElement::new([(x, y), (x + 18, y)], BLACK.stroke_width(2)));
    }
    for (i, curve) in figure.curves.iter().enumerate() {
        let color = PALETTE[i % PALETTE.len()];
        let style = color.stroke_width(3);
        if curve.points.iter().all(Option::is_none) {
            // Still in the legend, so that a law whose every row failed is not silently missing.
            chart
                .draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())?
                .label(format!("{} (no value: see the status column)", curve.label))
                .legend(move |(x, y)| PathElement::new([(x, y), (x + 18, y)], color.stroke_width(1)));
            continue;
        }
        // A gap (a row without a value) breaks the line.
        for (j, run) in curve.points.split(Option::is_none).filter(|run| !run.is_empty()).enumerate() {
            let run: Vec<(f64, f64)> = run.iter().flatten().copied().collect();
            let marks = chart.draw_series(run.iter().map(|&p| Circle::new(p, 3, color.filled())))?;
            if j == 0 {
                marks
                    .label(curve.label.as_str())
                    .legend(move |(x, y)| PathElement::new([(x, y), (x + 18, y)], color.stroke_width(3)));
            }
            chart.draw_series(LineSeries::new(run, style))?;
        }
    }
    let position = if figure.diagonal { SeriesLabelPosition::LowerRight } else { SeriesLabelPosition::UpperRight };
    super::figures::legend(&mut chart, position)
}
