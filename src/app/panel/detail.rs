//! The detail normal map's controls: the blend method for every material (`auto`: each
//! material's own), and the tiling and strength of every material's detail map.

use bumpview::frame::DetailBlend;
use bumpview::names::{Named, name_or_auto};
use bumpview::scene::DEFAULT_DETAIL_TILING;
use bumpview::state::{Command, ViewerState};

use crate::app::action::Action;

/// The method, tiling and strength; shown only where a material has a detail map.
pub(super) fn detail(ui: &mut egui::Ui, state: &ViewerState, has_detail: bool, actions: &mut Vec<Action>) {
    if !has_detail {
        ui.weak("detail normal map: none (Files: detail normal map)");
        return;
    }
    let mut method = state.shading.detail_blend;
    egui::ComboBox::from_label("detail blend").selected_text(name_or_auto(method)).show_ui(ui, |ui| {
        for choice in std::iter::once(None).chain(DetailBlend::all().iter().copied().map(Some)) {
            ui.selectable_value(&mut method, choice, name_or_auto(choice));
        }
    });
    if method != state.shading.detail_blend {
        actions.push(Command::SetDetailBlend(method).into());
    }
    let current = state.scene_options.materials;
    let mut new = current;
    let mut tiling = current.detail_tiling.unwrap_or(DEFAULT_DETAIL_TILING);
    let mut strength = current.detail_strength.unwrap_or(1.0);
    ui.horizontal(|ui| {
        if ui.add(egui::DragValue::new(&mut tiling).range(0.25..=64.0).speed(0.1)).changed() {
            new.detail_tiling = Some(tiling);
        }
        ui.label("detail tiling (repeats per UV unit)");
    });
    ui.horizontal(|ui| {
        if ui.add(egui::DragValue::new(&mut strength).range(-4.0..=4.0).speed(0.01)).changed() {
            new.detail_strength = Some(strength);
        }
        ui.label("detail strength");
    });
    if new != current {
        actions.push(Command::SetMaterialOverrides { material: None, overrides: new }.into());
    }
}
