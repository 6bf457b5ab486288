//! Text drawn into exported pictures on the CPU (captions, split labels, legends): the Hack
//! font that `epaint_default_fonts` bundles, rasterised by `ab_glyph`. Widths are measured
//! with the same font and layout that draw the text, so a line [`wrap`] fits is drawn within
//! that width.

use ab_glyph::{Font, FontRef, PxScale, ScaleFont, point};

/// The bundled Hack regular face.
fn font() -> FontRef<'static> {
    FontRef::try_from_slice(epaint_default_fonts::HACK_REGULAR).expect("the bundled Hack font parses")
}

/// Each glyph of `text` at `px` pixels placed from a caret at `(x, baseline)`, and the caret
/// after the last glyph.
fn layout(font: &FontRef<'static>, text: &str, px: f32, x: f32, baseline: f32) -> (Vec<ab_glyph::Glyph>, f32) {
    let scale = PxScale::from(px);
    let scaled = font.as_scaled(scale);
    let mut caret = x;
    let mut glyphs = Vec::with_capacity(text.len());
    for c in text.chars() {
        let id = font.glyph_id(c);
        glyphs.push(id.with_scale_and_position(scale, point(caret, baseline)));
        caret += scaled.h_advance(id);
    }
    (glyphs, caret)
}

/// The width `text` covers drawn at `px` pixels, pixels: from the caret's start to the
/// farther of the last advance and the right edge of any glyph's ink.
pub fn text_width(text: &str, px: f32) -> f32 {
    let font = font();
    let (glyphs, caret) = layout(&font, text, px, 0.0, 0.0);
    let ink = glyphs.into_iter().filter_map(|g| font.outline_glyph(g)).map(|o| o.px_bounds().max.x);
    ink.fold(caret, f32::max)
}

/// `text` broken into lines no wider than `width` pixels at `px` ([`text_width`]): at spaces
/// where it can, inside a word only where the word alone is wider; continuation lines are
/// indented by two spaces (a caption's lines; [`wrap_paragraph`] for prose). A line keeps at
/// least one character, so a width below one character's is the only case a line exceeds it.
pub fn wrap(text: &str, px: f32, width: f32) -> Vec<String> {
    wrap_indented(text, px, width, "  ")
}

/// [`wrap`] without the indent: a paragraph's lines all start at the left edge.
pub fn wrap_paragraph(text: &str, px: f32, width: f32) -> Vec<String> {
    wrap_indented(text, px, width, "")
}

/// [`wrap`] with `indent` before every line but the first.
fn wrap_indented(text: &str, px: f32, width: f32, indent: &str) -> Vec<String> {
    let fits = |line: &str| text_width(line, px) <= width;
    let mut lines: Vec<String> = Vec::new();
    let mut line = String::new();
    for word in text.split(' ') {
        let lead = if lines.is_empty() { "" } else { indent };
        let candidate = match line.is_empty() {
            true => format!("{lead}{word}"),
            false => format!("{line} {word}"),
        };
        if fits(&candidate) {
            line = candidate;
            continue;
        }
        if !line.is_empty() {
            lines.push(std::mem::take(&mut line));
        }
        // The word starts a line; a word wider than a line is cut into pieces that fit.
        let mut piece = if lines.is_empty() { String::new() } else { indent.to_owned() };
        let mut start = piece.len();
        for c in word.chars() {
            piece.push(c);
            if !fits(&piece) && piece.len() - start > c.len_utf8() {
                piece.pop();
                lines.push(std::mem::replace(&mut piece, format!("{indent}{c}")));
                start = indent.len();
            }
        }
        line = piece;
    }
    if !line.trim().is_empty() || lines.is_empty() {
        lines.push(line);
    }
    lines
}

/// Draws `text` at `px` pixels, left end of the baseline at `(x, baseline)`, clipped to the
/// columns `columns[0]..columns[1]`, blending `color` (sRGB) by glyph coverage.
pub fn draw(
    image: &mut image::RgbaImage,
    text: &str,
    columns: [u32; 2],
    x: f32,
    baseline: f32,
    px: f32,
    color: [u8; 3],
) {
    let font = font();
    let (glyphs, _) = layout(&font, text, px, x, baseline);
    for glyph in glyphs {
        let Some(outlined) = font.outline_glyph(glyph) else { continue };
        let bounds = outlined.px_bounds();
        outlined.draw(|gx, gy, coverage| {
            let (x, y) = (bounds.min.x as i64 + gx as i64, bounds.min.y as i64 + gy as i64);
            let inside = x >= columns[0] as i64 && x < columns[1] as i64 && y >= 0 && y < image.height() as i64;
            if inside && x < image.width() as i64 {
                blend(image.get_pixel_mut(x as u32, y as u32), color, coverage);
            }
        });
    }
}

/// Blends the pixels `x0..x1 × y0..y1` (clipped to the image) towards `color` by `alpha`.
pub fn fill(image: &mut image::RgbaImage, [x0, y0, x1, y1]: [i64; 4], color: [u8; 3], alpha: f32) {
    let (w, h) = (image.width() as i64, image.height() as i64);
    for y in y0.clamp(0, h)..y1.clamp(0, h) {
        for x in x0.clamp(0, w)..x1.clamp(0, w) {
            blend(image.get_pixel_mut(x as u32, y as u32), color, alpha);
        }
    }
}

/// `pixel` moved towards `color` by `alpha` (0..1), made opaque where it is covered.
fn blend(pixel: &mut image::Rgba<u8>, color: [u8; 3], alpha: f32) {
    let a = alpha.clamp(0.0, 1.0);
    for (channel, c) in pixel.0.iter_mut().zip(color) {
        *channel = (*channel as f32 * (1.0 - a) + c as f32 * a).round() as u8;
    }
    if a > 0.0 {
        pixel.0[3] = pixel.0[3].max((a * 255.0).round() as u8);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrapped_lines_fit_their_width_and_keep_every_word() {
        let text = "mistake: no-gram-schmidt: T not orthogonal to N: the bump leaks into the normal's own direction";
        for (px, width) in [(11.0, 85.0), (21.3, 620.0), (15.0, 200.0), (11.0, 30.0)] {
            let lines = wrap(text, px, width);
            assert!(lines.len() > 1, "{px} px in {width}: {lines:?}");
            for line in &lines {
                assert!(text_width(line, px) <= width, "{line:?} at {px} px: {} > {width}", text_width(line, px));
            }
            let joined: String = lines.concat().split_whitespace().collect();
            assert_eq!(joined, text.split_whitespace().collect::<String>(), "no character lost");
        }
        assert_eq!(wrap("short", 11.0, 500.0), ["short"]);
        assert_eq!(wrap("", 11.0, 500.0), [""]);
    }

    #[test]
    fn widths_grow_with_the_text_and_its_size() {
        let (one, two) = (text_width("abc", 20.0), text_width("abcabc", 20.0));
        assert!(one > 20.0 && (two - 2.0 * one).abs() < 1.0, "{one} {two}");
        assert!((text_width("abc", 40.0) - 2.0 * one).abs() < 1.0);
    }
}
