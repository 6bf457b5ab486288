//! Comparison exports: a row of tiles, each the same camera and light under other shading
//! settings, with an optional caption strip under each tile stating view, mode, strength,
//! normal-map convention and tangent source. The captions are drawn on the CPU with the Hack
//! font that `epaint_default_fonts` bundles, rasterised by `ab_glyph`.

use ab_glyph::{Font, FontRef, PxScale, ScaleFont, point};

use super::capture::{CaptureOptions, render_capture};
use super::{BumpSource, FrameParams, Renderer, SceneOptions};
use crate::error::RenderError;
use crate::scene::Scene;
use crate::shading::{ShadingSettings, ViewMode};
use crate::viewer::{mode_label, view_label};

/// The caption strip's background and text colours (sRGB).
pub const CAPTION_BACKGROUND: [u8; 3] = [24, 26, 30];
const CAPTION_TEXT: [u8; 3] = [235, 235, 235];

/// The default row: flat │ bumped │ Tangent view, from `current` (lit pictures in its mode,
/// at its strength).
pub fn default_row(current: &ShadingSettings) -> Vec<ShadingSettings> {
    let lit = ShadingSettings { view: ViewMode::Lit, ..*current };
    vec![
        ShadingSettings { bump_enabled: false, ..lit },
        ShadingSettings { bump_enabled: true, ..lit },
        ShadingSettings { view: ViewMode::Tangent, bump_enabled: true, ..lit },
    ]
}

/// The caption of a tile: view (and mode), bump and strength, the normal-map convention of the
/// scene's materials (after `options`' overrides) and the tangent frames the renderer drew
/// with (its current scene, made with `options`).
pub fn caption(renderer: &Renderer, scene: &Scene, options: &SceneOptions, shading: &ShadingSettings) -> Vec<String> {
    let view = match shading.view {
        ViewMode::Lit | ViewMode::OverTilt => format!("{}: {}", view_label(shading.view), mode_label(shading.mode)),
        other => format!("{} view", view_label(other)),
    };
    let bump = if shading.bump_enabled {
        format!("bump on, strength {:.2}", shading.strength)
    } else {
        format!("bump off (strength {:.2})", shading.strength)
    };
    let mut greens: Vec<&str> = Vec::new();
    for (index, material) in scene.materials.iter().enumerate() {
        let Some(map) = &material.normal_map else { continue };
        let green = options.overrides_in_use(index).green.unwrap_or(map.convention.green);
        let name = green.label();
        if !greens.contains(&name) {
            greens.push(name);
        }
    }
    let convention = if greens.is_empty() { "none".to_owned() } else { greens.join(", ") };
    let tangents = if options.bump_source == BumpSource::HeightInShader {
        "none (height in shader)".to_owned()
    } else {
        let mut names: Vec<&str> = Vec::new();
        for method in renderer.tangent_methods().into_iter().flatten() {
            if !names.contains(&method.name()) {
                names.push(method.name());
            }
        }
        let used = if names.is_empty() { "none".to_owned() } else { names.join(", ") };
        match options.tangent_method {
            None => format!("auto: {used}"),
            Some(_) => used,
        }
    };
    vec![view, bump, format!("normal map: {convention}"), format!("tangents: {tangents}")]
}

/// Text size of captions under tiles `tile_width` pixels wide, pixels.
fn caption_px(tile_width: u32) -> f32 {
    (tile_width as f32 / 30.0).clamp(11.0, 32.0)
}

/// Height of a caption strip of `lines` lines under tiles `tile_width` pixels wide.
pub fn caption_strip_height(tile_width: u32, lines: usize) -> u32 {
    let px = caption_px(tile_width);
    (lines as f32 * px * 1.25 + px).ceil() as u32
}

/// Renders one tile per entry of `tiles` (each a capture as `options` say, with `params`'
/// camera and light) side by side, left to right, with no gap: tile `i` is the pixels
/// `[i·w, (i+1)·w) × [0, h)`. With `captions` (one list of lines per tile), a strip of
/// [`caption_strip_height`] under each tile holds its lines.
pub fn render_row(
    renderer: &mut Renderer,
    options: &CaptureOptions,
    params: &FrameParams,
    tiles: &[ShadingSettings],
    captions: Option<&[Vec<String>]>,
) -> Result<image::RgbaImage, RenderError> {
    let [width, height] = options.size;
    let lines = captions.map_or(0, |c| c.iter().map(Vec::len).max().unwrap_or(0));
    let strip = if captions.is_some() { caption_strip_height(width, lines) } else { 0 };
    let count = tiles.len() as u32;
    let mut row = image::RgbaImage::new(width.saturating_mul(count), height + strip);
    for (i, shading) in tiles.iter().enumerate() {
        let tile = render_capture(renderer, options, &FrameParams { shading: *shading, ..*params })?;
        let x0 = i as u32 * width;
        image::imageops::replace(&mut row, &tile, x0 as i64, 0);
        if let Some(text) = captions.and_then(|c| c.get(i)) {
            let [r, g, b] = CAPTION_BACKGROUND;
            for y in height..height + strip {
                for x in x0..x0 + width {
                    row.put_pixel(x, y, image::Rgba([r, g, b, 255]));
                }
            }
            let px = caption_px(width);
            for (line, words) in text.iter().enumerate() {
                let baseline = height as f32 + px * 0.5 + px * (1.25 * line as f32 + 1.0);
                draw_text(&mut row, words, [x0, x0 + width], x0 as f32 + px * 0.5, baseline, px);
            }
        }
    }
    Ok(row)
}

/// Draws `text` in Hack at `px` pixels, left end of the baseline at `(x, baseline)`, clipped to
/// the columns `columns[0]..columns[1]`, blending [`CAPTION_TEXT`] by glyph coverage.
fn draw_text(image: &mut image::RgbaImage, text: &str, columns: [u32; 2], x: f32, baseline: f32, px: f32) {
    let font = FontRef::try_from_slice(epaint_default_fonts::HACK_REGULAR).expect("the bundled Hack font parses");
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
            let inside = x >= columns[0] as i64 && x < columns[1] as i64 && y >= 0 && y < image.height() as i64;
            if inside {
                let pixel = image.get_pixel_mut(x as u32, y as u32);
                let a = coverage.clamp(0.0, 1.0);
                for (channel, text) in pixel.0.iter_mut().zip(CAPTION_TEXT) {
                    *channel = (*channel as f32 * (1.0 - a) + text as f32 * a).round() as u8;
                }
            }
        });
    }
}
