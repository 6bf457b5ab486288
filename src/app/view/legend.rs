//! The Difference view's colour legend, drawn over the 3D view.

use bumpview::shading::difference_color;

/// Number of flat steps the gradient bar is drawn with.
const STEPS: usize = 32;

/// Draws a vertical bar of the Difference colour scale in the top-right corner of `view`,
/// labelled 0 … `range_deg` degrees (values above the range show the top colour).
pub(super) fn difference(painter: &egui::Painter, view: egui::Rect, range_deg: f32) {
    let bar = egui::Rect::from_min_size(view.right_top() + egui::vec2(-46.0, 12.0), egui::vec2(16.0, 160.0));
    painter.rect_filled(
        bar.expand2(egui::vec2(40.0, 14.0)).translate(egui::vec2(-18.0, 0.0)),
        4.0,
        egui::Color32::from_black_alpha(150),
    );
    for i in 0..STEPS {
        let t = (i as f32 + 0.5) / STEPS as f32;
        let [r, g, b] = difference_color(t).map(|c| (c * 255.0).round() as u8);
        let top = bar.bottom() - bar.height() * (i + 1) as f32 / STEPS as f32;
        let step = egui::Rect::from_min_max(
            egui::pos2(bar.left(), top),
            egui::pos2(bar.right(), top + bar.height() / STEPS as f32 + 0.5),
        );
        painter.rect_filled(step, 0.0, egui::Color32::from_rgb(r, g, b));
    }
    for (fraction, text) in
        [(0.0, "0°".to_owned()), (0.5, format!("{:.3}°", range_deg / 2.0)), (1.0, format!("≥{range_deg:.3}°"))]
    {
        let y = bar.bottom() - bar.height() * fraction;
        painter.text(
            egui::pos2(bar.left() - 4.0, y),
            egui::Align2::RIGHT_CENTER,
            text,
            egui::FontId::monospace(11.0),
            egui::Color32::WHITE,
        );
    }
}
