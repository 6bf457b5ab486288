//! The keys a slide carries over its pictures for the views that draw a quantity as a colour:
//! the Difference view's colour scale and the Over-tilt view's key, as exported pictures carry
//! them ([`annotate::legend`]), and for the views that draw a unit world-space vector `v` as the
//! colour `0.5·v + 0.5` (tangent, bitangent, normal, shading and clear-coat normal) the colour
//! of each axis. Each key is drawn once, at the top right of the last side that shows its view.

use image::RgbaImage;
use strum::VariantArray;

use super::{Lesson, Side};
use crate::frame::ViewMode;
use crate::render::annotate;
use crate::render::text::{self, text_width};

/// The direction views' axes and the colours `0.5·v + 0.5` gives them (sRGB, as stored).
pub const AXES: [(&str, [u8; 3]); 3] = [("+X", [255, 128, 128]), ("+Y", [128, 255, 128]), ("+Z", [128, 128, 255])];
/// The direction key's first line.
pub const DIRECTION_TITLE: &str = "colour = 0.5·v + 0.5";
/// The keys' backing: black at this opacity (as the exported pictures' labels).
const BACKING_ALPHA: f32 = 170.0 / 255.0;

/// The view `side` is drawn in: its half's view in a split of views, else the preset's.
pub fn side_view(side: &Side) -> ViewMode {
    let split = &side.preset.split;
    let name = match side.half {
        Some(half) if split.difference == "view" => &split.views[half],
        _ => &side.preset.shading.view,
    };
    ViewMode::VARIANTS.iter().copied().find(|v| <&str>::from(*v) == name.as_str()).unwrap_or_default()
}

/// Whether `view` draws a unit vector as the colour `0.5·v + 0.5`.
pub fn is_direction_view(view: ViewMode) -> bool {
    matches!(
        view,
        ViewMode::Tangent
            | ViewMode::Bitangent
            | ViewMode::Normal
            | ViewMode::ShadingNormal
            | ViewMode::ClearcoatNormal
    )
}

/// Draws the keys of `lesson`'s views over `slide`, where each side shows in `areas`
/// (`[x, y, width, height]`, one per side); text `px` high.
pub fn draw(slide: &mut RgbaImage, lesson: &Lesson, areas: &[[u32; 4]], px: f32) {
    let views: Vec<ViewMode> = lesson.sides.iter().map(side_view).collect();
    let last = |wanted: &dyn Fn(ViewMode) -> bool| views.iter().rposition(|&v| wanted(v));
    for view in [ViewMode::Difference, ViewMode::OverTilt] {
        if let Some(i) = last(&|v| v == view) {
            let [x, y, w, h] = areas[i];
            let range = lesson.sides[i].preset.shading.difference_range_deg;
            annotate::legend(slide, view, range, [x, y, x + w, y + h], true);
        }
    }
    if let Some(i) = last(&is_direction_view) {
        direction_key(slide, areas[i], px);
    }
}

/// The direction views' key at the top right of `area`: [`DIRECTION_TITLE`] over a swatch and
/// name per axis, on a dark backing; nothing where the area is too narrow for it.
fn direction_key(slide: &mut RgbaImage, [x, y, w, _]: [u32; 4], px: f32) {
    let (pad, swatch, space) = (px * 0.4, px * 0.9, px * 0.7);
    let row: f32 = AXES.iter().map(|(name, _)| swatch + pad + text_width(name, px) + space).sum::<f32>() - space;
    let box_w = row.max(text_width(DIRECTION_TITLE, px)) + 2.0 * pad;
    if box_w + 2.0 * pad > w as f32 {
        return;
    }
    let (x0, y0) = ((x + w) as f32 - pad - box_w, y as f32 + pad);
    let box_h = px * 2.6 + 2.0 * pad;
    text::fill(slide, [x0, y0, x0 + box_w, y0 + box_h].map(|v| v.round() as i64), [0, 0, 0], BACKING_ALPHA);
    let clip = [x0 as u32, (x0 + box_w) as u32];
    text::draw(slide, DIRECTION_TITLE, clip, x0 + pad, y0 + pad + px * 0.95, px, [255, 255, 255]);
    let row_top = y0 + pad + px * 1.45;
    let mut at = x0 + pad;
    for (name, color) in AXES {
        text::fill(slide, [at, row_top, at + swatch, row_top + swatch].map(|v| v.round() as i64), color, 1.0);
        at += swatch + pad;
        text::draw(slide, name, clip, at, row_top + px * 0.85, px, [255, 255, 255]);
        at += text_width(name, px) + space;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lessons::catalogue;

    #[test]
    fn each_colour_view_lesson_carries_its_key() {
        let lessons = catalogue().unwrap();
        let views = |name: &str| {
            let lesson = lessons.iter().find(|l| l.name == name).unwrap();
            lesson.sides.iter().map(side_view).collect::<Vec<_>>()
        };
        assert!(views("tangent-methods").contains(&ViewMode::Difference));
        assert!(views("frame-views").into_iter().all(is_direction_view));
        assert!(views("kernels").into_iter().all(is_direction_view));
        let lesson = lessons.iter().find(|l| l.name == "frame-views").unwrap();
        let mut slide = RgbaImage::from_pixel(400, 200, image::Rgba([90, 90, 90, 255]));
        let areas = vec![[0, 0, 200, 112], [200, 0, 200, 112], [0, 100, 200, 100], [200, 100, 200, 100]];
        draw(&mut slide, lesson, &areas, 12.0);
        for (_, color) in AXES {
            let found = slide.pixels().any(|p| p.0[..3] == color);
            assert!(found, "the swatch {color:?} on the last tile");
        }
        assert!((0..200).all(|x| slide.get_pixel(x, 150).0 == [90, 90, 90, 255]), "only the last tile keyed");
    }
}
