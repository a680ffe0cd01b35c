//! PNG through a pure-Rust rasteriser (resvg/tiny-skia) rendering our own SVG.

use std::sync::OnceLock;

use crate::error::{IoError, IoResult};

/// Fonts of the system, loaded once (text in figures renders only if some font is found;
/// the geometry renders regardless).
fn fontdb() -> std::sync::Arc<resvg::usvg::fontdb::Database> {
    static DB: OnceLock<std::sync::Arc<resvg::usvg::fontdb::Database>> = OnceLock::new();
    DB.get_or_init(|| {
        let mut db = resvg::usvg::fontdb::Database::new();
        db.load_system_fonts();
        std::sync::Arc::new(db)
    })
    .clone()
}

/// Renders an SVG document to PNG bytes at `scale` (1 = the SVG's pixel size).
///
/// # Errors
/// [`IoError::Render`] if the SVG cannot be parsed or the image cannot be allocated or encoded
/// (an internal failure: our writers produce valid SVG).
pub fn svg_to_png(svg: &str, scale: f32) -> IoResult<Vec<u8>> {
    let (pixmap, _) = render_pixmap(svg, scale)?;
    pixmap
        .encode_png()
        .map_err(|e| IoError::Render(e.to_string()))
}

/// Renders an SVG document at `scale`; also returns the boxes `x, y, width, height` (in the
/// SVG's pixels) of its texts as laid out with the system's fonts (none without fonts).
pub(crate) fn render_pixmap(
    svg: &str,
    scale: f32,
) -> IoResult<(resvg::tiny_skia::Pixmap, Vec<[f64; 4]>)> {
    let mut opt = resvg::usvg::Options {
        fontdb: fontdb(),
        ..resvg::usvg::Options::default()
    };
    opt.font_family = "DejaVu Sans".into();
    let tree =
        resvg::usvg::Tree::from_str(svg, &opt).map_err(|e| IoError::Render(e.to_string()))?;
    let size = tree
        .size()
        .to_int_size()
        .scale_by(scale)
        .ok_or_else(|| IoError::Render(format!("cannot scale the image by {scale}")))?;
    let mut pixmap = resvg::tiny_skia::Pixmap::new(size.width(), size.height())
        .ok_or_else(|| IoError::Render("cannot allocate the image".into()))?;
    resvg::render(
        &tree,
        resvg::tiny_skia::Transform::from_scale(scale, scale),
        &mut pixmap.as_mut(),
    );
    let mut boxes = Vec::new();
    text_boxes(tree.root(), &mut boxes);
    Ok((pixmap, boxes))
}

fn text_boxes(g: &resvg::usvg::Group, out: &mut Vec<[f64; 4]>) {
    for node in g.children() {
        match node {
            resvg::usvg::Node::Group(g) => text_boxes(g, out),
            resvg::usvg::Node::Text(t) => {
                let b = t.abs_bounding_box();
                out.push([
                    f64::from(b.x()),
                    f64::from(b.y()),
                    f64::from(b.width()),
                    f64::from(b.height()),
                ]);
            }
            _ => {}
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn renders_a_line() {
        let svg = r#"<svg xmlns="http://www.w3.org/2000/svg" width="20" height="10"><rect width="20" height="10" fill="white"/><line x1="0" y1="5" x2="20" y2="5" stroke="black" stroke-width="2"/></svg>"#;
        let png = svg_to_png(svg, 2.0).unwrap();
        assert_eq!(&png[1..4], b"PNG");
        // IHDR: width 40, height 20 at scale 2
        assert_eq!(u32::from_be_bytes([png[16], png[17], png[18], png[19]]), 40);
        assert_eq!(u32::from_be_bytes([png[20], png[21], png[22], png[23]]), 20);
        assert!(matches!(svg_to_png("<svg", 1.0), Err(IoError::Render(_))));
    }
}
