//! From SVG text to pixels with `resvg` (anti-aliased), and text measurement with the same font and shaper, so
//! that a figure's layout, its SVG and its PNG agree. The font is the embedded DejaVu Sans: no system font is
//! looked up, so a machine without fonts renders the same image.

use anyhow::{Context, anyhow};
use resvg::tiny_skia::{Pixmap, Transform};
use resvg::usvg::{self, fontdb};
use std::sync::{Arc, OnceLock};

/// The font family every figure names (embedded; generic `sans-serif` resolves to it as well).
pub const FONT_FAMILY: &str = "DejaVu Sans";

/// The font database: DejaVu Sans regular, bold and oblique from memory, nothing from the system.
fn fonts() -> Arc<fontdb::Database> {
    static FONTS: OnceLock<Arc<fontdb::Database>> = OnceLock::new();
    FONTS
        .get_or_init(|| {
            let mut database = fontdb::Database::new();
            for face in [dejavu::sans::regular(), dejavu::sans::bold(), dejavu::sans::oblique()] {
                database.load_font_source(fontdb::Source::Binary(Arc::new(face)));
            }
            database.set_sans_serif_family(FONT_FAMILY);
            Arc::new(database)
        })
        .clone()
}

/// Parsing options with the embedded fonts.
fn options() -> usvg::Options<'static> {
    usvg::Options { font_family: FONT_FAMILY.into(), fontdb: fonts(), ..usvg::Options::default() }
}

/// Escapes text for an SVG text node or attribute.
pub fn escape(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            _ => out.push(c),
        }
    }
    out
}

/// The advance width of `text` set in DejaVu Sans at `size` pixels (`bold` or regular), in pixels. Falls back to
/// an estimate (0.6 em a character) should the layout fail.
pub fn text_width(text: &str, size: f64, bold: bool) -> f64 {
    if text.is_empty() {
        return 0.0;
    }
    let weight = if bold { "bold" } else { "normal" };
    let svg = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"10\" height=\"10\"><text x=\"0\" y=\"50\" \
         font-family=\"{FONT_FAMILY}\" font-size=\"{size}\" font-weight=\"{weight}\">{}</text></svg>",
        escape(text)
    );
    let measured = usvg::Tree::from_str(&svg, &options()).ok().and_then(|tree| {
        tree.root().children().iter().find_map(|node| match node {
            usvg::Node::Text(text) => Some(f64::from(text.bounding_box().width())),
            _ => None,
        })
    });
    measured.unwrap_or(0.6 * size * text.chars().count() as f64)
}

/// Rasterises an SVG document at its own size (one pixel per SVG unit), anti-aliased, on its own background.
pub fn rasterise(svg: &str) -> anyhow::Result<Pixmap> {
    let tree = usvg::Tree::from_str(svg, &options()).context("cannot read the figure's SVG")?;
    let size = tree.size().to_int_size();
    let mut pixmap = Pixmap::new(size.width(), size.height()).ok_or_else(|| anyhow!("the figure has an empty size"))?;
    resvg::render(&tree, Transform::identity(), &mut pixmap.as_mut());
    Ok(pixmap)
}

/// The SVG document rendered as a PNG file's bytes.
pub fn png(svg: &str) -> anyhow::Result<Vec<u8>> {
    rasterise(svg)?.encode_png().map_err(|e| anyhow!("cannot encode the PNG: {e}"))
}

/// The SVG document rendered as RGB pixels (row-major, 3 bytes a pixel; the figures are opaque).
pub fn rgb(svg: &str) -> anyhow::Result<Vec<u8>> {
    let pixmap = rasterise(svg)?;
    Ok(pixmap.pixels().iter().flat_map(|p| [p.red(), p.green(), p.blue()]).collect())
}
