//! What an exported picture carries over the 3D image, drawn on the CPU as the viewer draws
//! it over the view: the split view's divider and the labels of its halves, the Difference
//! view's colour scale with its numbers, and the Over-tilt view's key. Sizes follow the
//! picture's height so a 720-pixel-high export matches the viewer's 15-point labels.

use super::text;
use crate::frame::ViewMode;
use crate::shading::{OVER_TILT_COLOR, OVER_TILT_LIMIT_DEG, difference_color};

/// Colour of the divider and the label text (sRGB).
const WHITE: [u8; 3] = [255, 255, 255];
/// The labels' and legends' background: black at this opacity (the viewer's 170/255).
const BACKING_ALPHA: f32 = 170.0 / 255.0;

/// Pixels per viewer point for a picture `height` pixels high: 1 at 720, at least 0.75.
fn scale(height: u32) -> f32 {
    (height as f32 / 720.0).max(0.75)
}

/// The divider's columns in a picture `height` pixels high with the right half starting at
/// column `divider`: `divider − w/2 .. divider + w/2`, `w` 2 pixels at 720 high (the viewer's
/// 2-point line), at least 2.
pub fn divider_columns(divider: u32, height: u32) -> [u32; 2] {
    let w = ((2.0 * scale(height)).round() as u32).max(2);
    [divider.saturating_sub(w / 2), divider + w - w / 2]
}

/// Draws the split view's divider at column `divider` (the first of the right half) and
/// `labels` (left, right) on dark boxes at the top beside it, each wrapped to its half.
pub fn split(image: &mut image::RgbaImage, divider: u32, labels: [&str; 2]) {
    let (width, height) = image.dimensions();
    let s = scale(height);
    let [d0, d1] = divider_columns(divider, height);
    text::fill(image, [d0 as i64, 0, d1.min(width) as i64, height as i64], WHITE, 1.0);
    let (px, gap, pad) = (15.0 * s, 10.0 * s, 4.0 * s);
    let top = 8.0 * s;
    let room = [divider as f32 - gap - 2.0 * pad, width as f32 - divider as f32 - gap - 2.0 * pad];
    for (side, label) in labels.into_iter().enumerate() {
        if label.is_empty() || room[side] < px {
            continue;
        }
        let lines = text::wrap(label, px, room[side]);
        let box_width = lines.iter().map(|l| text::text_width(l, px)).fold(0.0, f32::max);
        let left = if side == 0 { divider as f32 - gap - box_width } else { divider as f32 + gap };
        draw_box(image, &lines, px, [left, top], box_width, pad);
    }
}

/// Draws `lines` at `px` on a dark box, the first line's top-left at `at`, `width` the widest
/// line, `pad` pixels of box around them.
fn draw_box(image: &mut image::RgbaImage, lines: &[String], px: f32, at: [f32; 2], width: f32, pad: f32) {
    let height = px * 1.25 * lines.len() as f32;
    let [x, y] = at;
    let rect = [x - pad, y - pad, x + width + pad, y + height + pad].map(|v| v.round() as i64);
    text::fill(image, rect, [0, 0, 0], BACKING_ALPHA);
    draw_lines(image, lines, px, at, [rect[0].max(0) as u32, rect[2].max(0) as u32]);
}

/// Draws `lines` at `px` in white, the first line's top-left at `at`, clipped to `columns`.
fn draw_lines(image: &mut image::RgbaImage, lines: &[String], px: f32, [x, y]: [f32; 2], columns: [u32; 2]) {
    for (i, line) in lines.iter().enumerate() {
        text::draw(image, line, columns, x, y + px * 0.95 + px * 1.25 * i as f32, px, WHITE);
    }
}

/// Draws the key of `view` over the pixels `area` = `[x0, y0, x1, y1)` (a whole picture, a
/// split half or a tile) at its top corner on the side `right`: the Difference view's colour
/// scale, bottom 0° to top `range_deg` and over, with the three numbers; the Over-tilt view's
/// swatch and limit. Other views have none, nor an area too narrow to hold the key.
pub fn legend(image: &mut image::RgbaImage, view: ViewMode, range_deg: f32, area: [u32; 4], right: bool) {
    let [c0, y0, c1, y1] = area.map(|c| c as f32);
    let s = scale(area[3].saturating_sub(area[1]));
    let px = 12.0 * s;
    let pad = 6.0 * s;
    let top = y0 + 12.0 * s;
    match view {
        ViewMode::Difference => {
            let (bar_w, bar_h) = (16.0 * s, (160.0 * s).min((y1 - y0) * 0.6));
            let numbers = [format!("≥{range_deg:.3}°"), format!("{:.3}°", range_deg / 2.0), "0°".to_owned()];
            let title = "angle to reference";
            let text_w = numbers.iter().map(|n| text::text_width(n, px)).fold(0.0, f32::max);
            let box_w = (text_w + pad + bar_w).max(text::text_width(title, px));
            if box_w + 2.0 * pad + 12.0 * s > c1 - c0 {
                return;
            }
            let x = if right { c1 - pad - box_w - 6.0 * s } else { c0 + pad + 6.0 * s };
            let rect = [x - pad, top - pad, x + box_w + pad, top + px * 1.9 + bar_h + px * 0.5 + pad];
            text::fill(image, rect.map(|v| v.round() as i64), [0, 0, 0], BACKING_ALPHA);
            let clip = [rect[0].max(0.0) as u32, rect[2].max(0.0) as u32];
            text::draw(image, title, clip, x, top + px * 0.95, px, WHITE);
            let bar_top = top + px * 1.9;
            let bar_x = x + box_w - bar_w;
            const STEPS: u32 = 64;
            for i in 0..STEPS {
                let t = (i as f32 + 0.5) / STEPS as f32;
                let color = difference_color(t).map(|c| (c * 255.0).round() as u8);
                let low = bar_top + bar_h * (1.0 - i as f32 / STEPS as f32);
                let high = bar_top + bar_h * (1.0 - (i + 1) as f32 / STEPS as f32);
                text::fill(image, [bar_x, high, bar_x + bar_w, low].map(|v| v.round() as i64), color, 1.0);
            }
            for (k, number) in numbers.iter().enumerate() {
                let y = bar_top + bar_h * k as f32 / 2.0 + px * 0.35;
                let w = text::text_width(number, px);
                text::draw(image, number, clip, bar_x - pad - w, y, px, WHITE);
            }
        }
        ViewMode::OverTilt => {
            let label = format!("tilted over {OVER_TILT_LIMIT_DEG:.0}° from the surface normal");
            let swatch = px;
            let room = (c1 - c0) - 4.0 * pad - swatch - 12.0 * s;
            if room < px {
                return;
            }
            let lines = text::wrap(&label, px, room);
            let text_w = lines.iter().map(|l| text::text_width(l, px)).fold(0.0, f32::max);
            let box_w = swatch + pad + text_w;
            let x = if right { c1 - pad - box_w - 6.0 * s } else { c0 + pad + 6.0 * s };
            let rect = [x - pad, top - pad, x + box_w + pad, top + px * 1.25 * lines.len() as f32 + pad];
            text::fill(image, rect.map(|v| v.round() as i64), [0, 0, 0], BACKING_ALPHA);
            let color = OVER_TILT_COLOR.to_array().map(|c| (c * 255.0).round() as u8);
            text::fill(image, [x, top + px * 0.1, x + swatch, top + px * 1.1].map(|v| v.round() as i64), color, 1.0);
            let clip = [rect[0].max(0.0) as u32, rect[2].max(0.0) as u32];
            draw_lines(image, &lines, px, [x + swatch + pad, top], clip);
        }
        _ => {}
    }
}
