//! `millpath render --png`: the SVG top view rasterised (resvg), for READMEs and CI artefacts
//! without a browser.

/// Width of the picture's longer side in pixels.
const SIDE: f32 = 1200.0;

/// The PNG bytes of an SVG drawing on a white background, its longer side [`SIDE`] pixels.
pub fn svg_to_png(svg: &str) -> Result<Vec<u8>, String> {
    use resvg::{tiny_skia, usvg};
    let tree = usvg::Tree::from_str(svg, &usvg::Options::default()).map_err(|e| e.to_string())?;
    let size = tree.size();
    let scale = SIDE / size.width().max(size.height()).max(1e-3);
    let (w, h) = (
        (size.width() * scale).ceil().clamp(1.0, 8192.0) as u32,
        (size.height() * scale).ceil().clamp(1.0, 8192.0) as u32,
    );
    let mut pixmap = tiny_skia::Pixmap::new(w, h).ok_or("picture too large")?;
    pixmap.fill(tiny_skia::Color::WHITE);
    resvg::render(
        &tree,
        tiny_skia::Transform::from_scale(scale, scale),
        &mut pixmap.as_mut(),
    );
    pixmap.encode_png().map_err(|e| e.to_string())
}
