//! The parallax family: technique, depth, the search's layers and relief's steps (uniforms);
//! displacement, its ground truth: on the CPU at a level or on the GPU at an edge length, and
//! what it costs.

use bumpview::frame::{
    DEFAULT_PIXELS_PER_EDGE, GPU_PIXELS_PER_EDGE, MAX_DISPLACEMENT_LEVEL, MAX_PARALLAX_LAYERS,
    MAX_PARALLAX_SHADOW_STRENGTH, MAX_PARALLAX_STEPS, Parallax,
};
use bumpview::names::Named;
use bumpview::prepare::displace::DisplacementStats;
use bumpview::render::tessellation::GpuDisplacementStats;
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

/// What displacement drew in one drawn scene: the CPU's mesh or the GPU's last tessellation.
pub(super) enum Displaced {
    Cpu(DisplacementStats),
    Gpu(GpuDisplacementStats),
}

/// Displacement: on the CPU at a level (0 off) or on the GPU at a target edge, and, per drawn
/// scene (the split view's right half may have its own), the displaced geometry's vertices,
/// triangles and memory; in the warning colour when a budget made it coarser than asked.
pub(super) fn displacement(
    ui: &mut egui::Ui,
    state: &ViewerState,
    displaced: [Option<Displaced>; 2],
    actions: &mut Vec<Action>,
) {
    let displacement = state.scene_options.displacement;
    let mut on_gpu = displacement.gpu.is_some();
    let hint = "tessellate on the GPU for each view, edges cut to a length on screen, instead of once on the CPU";
    if ui.checkbox(&mut on_gpu, "on the GPU").on_hover_text(hint).changed() {
        let command = if on_gpu {
            Command::SetGpuDisplacement(Some(DEFAULT_PIXELS_PER_EDGE))
        } else {
            Command::SetGpuDisplacement(None)
        };
        actions.push(command.into());
    }
    if let Some(mut pixels) = displacement.gpu {
        let slider = egui::Slider::new(&mut pixels, GPU_PIXELS_PER_EDGE).logarithmic(true).text("pixels per edge");
        let hint = "the target edge length on screen: shorter is closer to the true surface and costs more";
        if ui.add(slider).on_hover_text(hint).changed() {
            actions.push(Command::SetGpuDisplacement(Some(pixels)).into());
        }
    } else {
        let mut level = displacement.level;
        let slider = egui::Slider::new(&mut level, 0..=MAX_DISPLACEMENT_LEVEL).text("displacement level");
        let hint = "the ground truth: height-mapped meshes tessellated (4^level triangles each) and moved along \
                    their normals by the depth above; 0 is off";
        if ui.add(slider).on_hover_text(hint).changed() {
            actions.push(Command::SetDisplacement(level).into());
        }
    }
    // A level or edge made coarser by a budget is said here, under the control that asked for it.
    for (drawn, half) in displaced.iter().zip(["", "split right: "]) {
        let (text, coarser) = match drawn {
            Some(Displaced::Cpu(stats)) => (stats.asked_and_drawn(), stats.asked > stats.level),
            Some(Displaced::Gpu(stats)) => (stats.summary(), stats.budget_notice().is_some()),
            None => continue,
        };
        if coarser {
            ui.colored_label(ui.visuals().warn_fg_color, format!("{half}{text}"));
        } else {
            ui.weak(format!("{half}{text}"));
        }
    }
}
