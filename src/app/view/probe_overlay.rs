//! The probe over the 3D view: a marker at the pinned point and, beside it, a small window with
//! the readout of the shading chain there and a button that clears the probe.

use bumpview::scene::OrbitCamera;

use crate::app::action::Action;
use crate::app::probe::Probe;

/// Points between the marker's centre and the readout window, across and down: more than the
/// marker's reach (its ticks end 14 points out), so the window never covers the marker, even
/// when the view is too narrow for it beside the marker and it is pushed back over the point.
const WINDOW_OFFSET: f32 = 18.0;

/// Draws the marker and the readout window for `probe` over the view at `rect` (`size` pixels)
/// seen by `camera`; returns the window's action (Clear).
pub(super) fn show(
    ui: &egui::Ui,
    probe: &Probe,
    rect: egui::Rect,
    size: [u32; 2],
    camera: &OrbitCamera,
) -> Option<Action> {
    let report = probe.report()?;
    let pixel = probe.shown_at(camera, size)?;
    let point = rect.min + egui::vec2(pixel.x, pixel.y) * (rect.width() / size[0] as f32);
    paint_marker(ui.painter(), point);
    // The window opens on the side where it fits beside the marker (its size from the last
    // frame), else towards the larger free side, so it never covers the point it describes.
    let id = egui::Id::unique("probe readout");
    let width = ui.ctx().memory(|m| m.area_rect(id)).map_or(0.0, |r| r.width());
    let fits_right = point.x + WINDOW_OFFSET + width <= rect.max.x;
    let fits_left = point.x - WINDOW_OFFSET - width >= rect.min.x;
    let right = if fits_right != fits_left { fits_right } else { point.x < rect.center().x };
    let below = point.y < rect.center().y;
    let pivot = match (right, below) {
        (true, true) => egui::Align2::LEFT_TOP,
        (true, false) => egui::Align2::LEFT_BOTTOM,
        (false, true) => egui::Align2::RIGHT_TOP,
        (false, false) => egui::Align2::RIGHT_BOTTOM,
    };
    let offset = egui::vec2(
        if right { WINDOW_OFFSET } else { -WINDOW_OFFSET },
        if below { WINDOW_OFFSET } else { -WINDOW_OFFSET },
    );
    let mut action = None;
    egui::Area::new(id).order(egui::Order::Foreground).fixed_pos(point + offset).pivot(pivot).constrain_to(rect).show(
        ui.ctx(),
        |ui| {
            egui::Frame::popup(ui.style()).show(ui, |ui| {
                ui.horizontal(|ui| {
                    ui.strong(format!("Probe at pixel ({}, {})", report.pixel[0], report.pixel[1]));
                    if ui.small_button("Clear").on_hover_text("remove the probe (P + click pins another)").clicked() {
                        action = Some(Action::ClearProbe);
                    }
                });
                if let Some(half) = &report.half {
                    ui.small(format!("split half {half}"));
                }
                match &report.text {
                    Ok(text) => ui.label(egui::RichText::new(text).monospace().size(11.0)),
                    Err(why) => ui.weak(*why),
                };
            });
        },
    );
    action
}

/// A ring with four ticks, yellow on black so it shows on any picture.
fn paint_marker(painter: &egui::Painter, centre: egui::Pos2) {
    for (width, colour) in [(3.0, egui::Color32::BLACK), (1.5, egui::Color32::from_rgb(255, 220, 0))] {
        let stroke = egui::Stroke::new(width, colour);
        painter.circle_stroke(centre, 6.0, stroke);
        for d in [egui::vec2(1.0, 0.0), egui::vec2(0.0, 1.0)] {
            painter.line_segment([centre + d * 9.0, centre + d * 14.0], stroke);
            painter.line_segment([centre - d * 9.0, centre - d * 14.0], stroke);
        }
    }
}
