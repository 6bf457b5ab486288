//! The parallax family: technique, depth, the search's layers and relief's steps (uniforms);
//! displacement, its ground truth: the tessellation level and what it costs.

use bumpview::frame::{
    MAX_DISPLACEMENT_LEVEL, MAX_PARALLAX_LAYERS, MAX_PARALLAX_SHADOW_STRENGTH, MAX_PARALLAX_STEPS, Parallax,
};
use bumpview::names::Named;
use bumpview::prepare::displace::DisplacementStats;
use bumpview::state::{Command, ViewerState};

use crate::app::action::Action;

/// The technique selector, the depth (the material's or metres) and, for the searches, the
/// layers and steps.
pub(super) fn show(ui: &mut egui::Ui, state: &ViewerState, actions: &mut Vec<Action>) {
    let settings = state.shading.parallax;
    let mut technique = settings.technique;
    egui::ComboBox::from_label("technique").selected_text(technique.name()).show_ui(ui, |ui| {
        for &choice in Parallax::all() {
            ui.selectable_value(&mut technique, choice, choice.name());
        }
    });
    if technique != settings.technique {
        actions.push(Command::SetParallax(technique).into());
    }
    ui.weak("normal-mapped surfaces with a height map; UVs shift along the view ray before the maps are read");
    let mut own_depth = settings.depth_m.is_none();
    if ui.checkbox(&mut own_depth, "depth: the material's height range").changed() {
        actions.push(Command::SetParallaxDepth(if own_depth { None } else { Some(0.01) }).into());
    }
    if let Some(mut depth) = settings.depth_m {
        let slider = egui::Slider::new(&mut depth, 0.0..=0.1).text("depth").suffix(" m").max_decimals(4);
        if ui.add(slider).on_hover_text("0 is plain normal mapping").changed() {
            actions.push(Command::SetParallaxDepth(Some(depth)).into());
        }
    }
    if technique.marches() {
        let (mut min, mut max) = (settings.layers_min, settings.layers_max);
        let layers = 1..=MAX_PARALLAX_LAYERS;
        let hint = "layers of the linear search: min face-on, max at grazing views";
        let changed =
            ui.add(egui::Slider::new(&mut min, layers.clone()).logarithmic(true).text("min layers")).changed()
                | ui.add(egui::Slider::new(&mut max, layers).logarithmic(true).text("max layers"))
                    .on_hover_text(hint)
                    .changed();
        if changed {
            actions.push(Command::SetParallaxLayers([min, max]).into());
        }
    }
    if technique.marches() {
        let mut on = settings.shadows_on();
        if ui
            .checkbox(&mut on, "self-shadows")
            .on_hover_text("Tatarchuk's soft shadows: a ray from the hit towards the light")
            .changed()
        {
            actions.push(Command::SetParallaxShadows(if on { 1.0 } else { 0.0 }).into());
        }
        if on {
            let mut strength = settings.shadow_strength;
            let slider = egui::Slider::new(&mut strength, 0.0..=MAX_PARALLAX_SHADOW_STRENGTH).text("shadow strength");
            if ui.add(slider).changed() {
                actions.push(Command::SetParallaxShadows(strength).into());
            }
        }
    }
    if technique.refines() {
        let mut steps = settings.steps;
        if ui.add(egui::Slider::new(&mut steps, 0..=MAX_PARALLAX_STEPS).text("binary steps")).changed() {
            actions.push(Command::SetParallaxSteps(steps).into());
        }
    }
}

/// Displacement's level (0 off) and, per drawn scene (the split view's right half may have its
/// own), the displaced meshes' vertices, triangles and memory; the level drawn and why, in the
/// warning colour, when it is below the slider's.
pub(super) fn displacement(
    ui: &mut egui::Ui,
    state: &ViewerState,
    displaced: [Option<DisplacementStats>; 2],
    actions: &mut Vec<Action>,
) {
    let mut level = state.scene_options.displacement.level;
    let slider = egui::Slider::new(&mut level, 0..=MAX_DISPLACEMENT_LEVEL).text("displacement level");
    let hint = "the ground truth: height-mapped meshes tessellated (4^level triangles each) and moved along \
                their normals by the depth above; 0 is off";
    if ui.add(slider).on_hover_text(hint).changed() {
        actions.push(Command::SetDisplacement(level).into());
    }
    // A level lowered past the triangle budget is said here, under the slider that asked for it.
    for (stats, half) in displaced.iter().zip(["", "split right: "]) {
        match stats {
            Some(stats) if stats.asked > stats.level => {
                ui.colored_label(ui.visuals().warn_fg_color, format!("{half}{}", stats.asked_and_drawn()));
            }
            Some(stats) => {
                ui.weak(format!("{half}{}", stats.summary()));
            }
            None => {}
        }
    }
}
