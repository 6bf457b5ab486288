//! The current lesson's caption card over the 3D view: its title, caption and claim with the
//! number measured for it, and a button that hides the card; while the lesson's scene is
//! prepared, a veil over the previous picture instead.

use crate::app::action::Action;
use crate::app::controller::{LessonsForm, Measurement};

/// The card's width, points (narrower on a narrow view).
const CARD_WIDTH: f32 = 420.0;

/// While the current lesson's scene is prepared (`busy` names the stage), the picture in
/// `view` is still the previous one's: it is veiled and the lesson's title and the stage shown
/// instead of the card, so no card stands over another lesson's picture.
pub(super) fn show_preparing(painter: &egui::Painter, lessons: &LessonsForm, view: egui::Rect, busy: &str) {
    let Some(lesson) = lessons.lesson() else { return };
    painter.rect_filled(view, 0.0, egui::Color32::from_black_alpha(200));
    let text = format!("{}\n\npreparing: {busy}", lesson.title);
    let colour = painter.ctx().global_style().visuals.strong_text_color();
    painter.text(view.center(), egui::Align2::CENTER_CENTER, text, egui::FontId::proportional(22.0), colour);
}

/// Draws the card in the bottom-left corner of `view` while it is on; the hide button's
/// action and the height in points the card takes from the bottom of `view` (0 without one).
pub(super) fn show(ui: &mut egui::Ui, lessons: &LessonsForm, view: egui::Rect) -> (Option<Action>, f32) {
    let Some(lesson) = lessons.lesson().filter(|_| lessons.card) else { return (None, 0.0) };
    let number = match &lessons.measurement {
        Some(Measurement::Done(percent)) => lesson.claim_with(*percent),
        Some(Measurement::Running) => "measuring…".to_owned(),
        Some(Measurement::Failed(why)) => format!("not measured: {why}"),
        None => String::new(),
    };
    let width = CARD_WIDTH.min(view.width() - 24.0).max(120.0);
    let mut hide = false;
    let card = egui::Area::new(egui::Id::unique("lesson card"))
        .fixed_pos(view.left_bottom() + egui::vec2(12.0, -12.0))
        .pivot(egui::Align2::LEFT_BOTTOM)
        .show(ui.ctx(), |ui| {
            egui::Frame::popup(ui.style()).show(ui, |ui| {
                ui.set_max_width(width);
                ui.horizontal(|ui| {
                    ui.strong(&lesson.title);
                    hide = ui.small_button("×").on_hover_text("Hide the caption card").clicked();
                });
                ui.label(&lesson.caption);
                if !number.is_empty() {
                    ui.colored_label(ui.visuals().warn_fg_color, number);
                }
                let position = lessons.current.map_or(0, |i| i + 1);
                let panel = if lessons.panel_hidden { "H shows the panel" } else { "H hides the panel" };
                ui.weak(format!("lesson {position} of {} · Page Down / Page Up · {panel}", lessons.catalogue.len()));
            });
        });
    (hide.then_some(Action::ShowLessonCard(false)), view.bottom() - card.response.rect.top())
}
