//! The classic-mistake selector (a pipeline variant), each mistake with its one-line explanation.

use bumpview::frame::Mistake;
use bumpview::names::Named;
use bumpview::state::{Command, ViewerState};

use crate::app::action::Action;

/// The selector and what the chosen mistake breaks; the split view's "mistake" difference puts
/// it beside the correct picture.
pub(super) fn show(ui: &mut egui::Ui, state: &ViewerState, actions: &mut Vec<Action>) {
    let current = state.shading.mistake;
    let mut mistake = current;
    egui::ComboBox::from_label("draw with").selected_text(mistake.label()).show_ui(ui, |ui| {
        for &choice in Mistake::all() {
            ui.selectable_value(&mut mistake, choice, choice.label()).on_hover_text(choice.explanation());
        }
    });
    if mistake != current {
        actions.push(Command::SetMistake(mistake).into());
    }
    ui.weak(mistake.explanation());
    ui.weak("split view → differs: mistake puts two side by side");
}
