//! Text on slides: the Hack font that `epaint_default_fonts` bundles, measured and rasterised
//! by `ab_glyph`, wrapped at word boundaries to a width measured with the font.

use ab_glyph::{Font, FontRef, PxScale, ScaleFont, point};

fn font() -> FontRef<'static> {
    FontRef::try_from_slice(epaint_default_fonts::HACK_REGULAR).expect("the bundled Hack font parses")
}

/// The advance width of `text` at `px` pixels (the caret's travel, kerning-free as Hack is
/// monospaced), pixels.
pub fn text_width(text: &str, px: f32) -> f32 {
    let font = font();
    let scaled = font.as_scaled(PxScale::from(px));
    text.chars().map(|c| scaled.h_advance(font.glyph_id(c))).sum()
}

/// `text` broken into lines no wider than `width` pixels at `px`: at spaces, and inside a word
/// only when the word alone is wider than a line.
pub fn wrap(text: &str, px: f32, width: f32) -> Vec<String> {
    let mut lines = vec![];
    let mut line = String::new();
    for word in text.split_whitespace() {
        let candidate = if line.is_empty() { word.to_owned() } else { format!("{line} {word}") };
        if text_width(&candidate, px) <= width {
            line = candidate;
            continue;
        }
        if !line.is_empty() {
            lines.push(std::mem::take(&mut line));
        }
        // A word wider than the line is cut between characters.
        for c in word.chars() {
            let longer = format!("{line}{c}");
            if text_width(&longer, px) > width && !line.is_empty() {
                lines.push(std::mem::take(&mut line));
                line.push(c);
            } else {
                line = longer;
            }
        }
    }
    if !line.is_empty() {
        lines.push(line);
    }
    lines
}

/// Draws `text` at `px` pixels in `color`, the left end of its baseline at `(x, baseline)`,
/// blending by glyph coverage; what falls outside the image is left out.
pub fn draw_text(image: &mut image::RgbaImage, text: &str, x: f32, baseline: f32, px: f32, color: [u8; 3]) {
    let font = font();
    let scale = PxScale::from(px);
    let scaled = font.as_scaled(scale);
    let mut caret = x;
    for c in text.chars() {
        let id = font.glyph_id(c);
        let glyph = id.with_scale_and_position(scale, point(caret, baseline));
        caret += scaled.h_advance(id);
        let Some(outlined) = font.outline_glyph(glyph) else { continue };
        let bounds = outlined.px_bounds();
        outlined.draw(|gx, gy, coverage| {
            let (x, y) = (bounds.min.x as i64 + gx as i64, bounds.min.y as i64 + gy as i64);
            if x >= 0 && y >= 0 && x < image.width() as i64 && y < image.height() as i64 {
                let pixel = image.get_pixel_mut(x as u32, y as u32);
                let a = coverage.clamp(0.0, 1.0);
                for (channel, text) in pixel.0.iter_mut().zip(color) {
                    *channel = (*channel as f32 * (1.0 - a) + text as f32 * a).round() as u8;
                }
            }
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrapped_lines_fit_and_keep_every_word() {
        let text = "Blinn (1978) perturbs the normal before lighting and leaves the geometry alone.";
        for width in [120.0, 300.0, 2000.0] {
            let lines = wrap(text, 20.0, width);
            assert!(lines.iter().all(|l| text_width(l, 20.0) <= width), "{width}: {lines:?}");
            assert_eq!(lines.join(" "), text);
        }
        let cut = wrap("Supercalifragilistic", 20.0, 60.0);
        assert!(cut.len() > 1 && cut.iter().all(|l| text_width(l, 20.0) <= 60.0), "{cut:?}");
        assert_eq!(cut.concat(), "Supercalifragilistic");
    }
}
