//! The classic-mistake selector and the legacy looks (pipeline variants), each mistake with
//! its one-line explanation.

use bumpview::frame::{CUBE_MAP_SIZES, LegacyLook, Mistake};
use bumpview::names::Named;
use bumpview::state::{Command, ViewerState};

use crate::app::action::Action;

/// The selector and what the chosen mistake breaks; the split view's "mistake" difference puts
/// it beside the correct picture.
pub(super) fn show(ui: &mut egui::Ui, state: &ViewerState, actions: &mut Vec<Action>) {
    let current = state.shading.mistake;
    let mut mistake = current;
    egui::ComboBox::from_label("draw with").selected_text(mistake.name()).show_ui(ui, |ui| {
        for &choice in Mistake::all() {
            ui.selectable_value(&mut mistake, choice, choice.name()).on_hover_text(choice.explanation());
        }
    });
    if mistake != current {
        actions.push(Command::SetMistake(mistake).into());
    }
    ui.weak(mistake.explanation());
    ui.weak("split view → differs: mistake puts two side by side");
}

/// The legacy look and DOT3's normalization cube map size.
pub(super) fn legacy(ui: &mut egui::Ui, state: &ViewerState, actions: &mut Vec<Action>) {
    let current = state.shading.legacy;
    let mut legacy = current;
    egui::ComboBox::from_label("look").selected_text(legacy.look.name()).show_ui(ui, |ui| {
        for &choice in LegacyLook::all() {
            ui.selectable_value(&mut legacy.look, choice, choice.name());
        }
    });
    if legacy.look == LegacyLook::Dot3 {
        let size_name = |s: Option<u32>| s.map_or_else(|| "none: L per vertex".to_owned(), |s| format!("{s}×{s}"));
        egui::ComboBox::from_label("normalization cube map").selected_text(size_name(legacy.cube_map_size)).show_ui(
            ui,
            |ui| {
                for choice in std::iter::once(None).chain(CUBE_MAP_SIZES.map(Some)) {
                    ui.selectable_value(&mut legacy.cube_map_size, choice, size_name(choice));
                }
            },
        );
    }
    if legacy != current {
        actions.push(Command::SetLegacy(legacy).into());
    }
    ui.weak(match legacy.look {
        LegacyLook::Off => "today's lighting",
        LegacyLook::Dot3 => "diffuse N·L alone; L normalised per vertex and interpolated, or through the cube map",
        LegacyLook::Emboss => {
            "the 2D light-map bump: the light map read at (slope − light offset), in height-map texels"
        }
    });
}
