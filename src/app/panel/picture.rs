//! The lit picture's modes and the overlays; the camera's gestures and the probe.

use bumpview::frame::ShadingMode;
use bumpview::render::glyphs::MAX_GLYPHS_PER_MESH;
use bumpview::state::{Command, ViewerState};

use crate::app::action::Action;

/// The classic demo modes (keys 1/2/3), the wireframe overlay (W) and the T/B/N glyphs (G).
pub(super) fn show(ui: &mut egui::Ui, state: &ViewerState, actions: &mut Vec<Action>) {
    let mut mode = state.shading.mode;
    ui.horizontal_wrapped(|ui| {
        for (choice, label, hint) in [
            (ShadingMode::BumpTimesColour, "bump × colour (1)", "lighting with the bumped normal times the colour"),
            (ShadingMode::BumpOnly, "bump only (2)", "lighting with a white albedo: the relief alone"),
            (ShadingMode::ColourOnly, "colour only (3)", "the colour texture as stored: no bump, no lighting"),
        ] {
            ui.radio_value(&mut mode, choice, label).on_hover_text(hint);
        }
    });
    if mode != state.shading.mode {
        actions.push(Command::SetShadingMode(mode).into());
    }
    let mut wireframe = state.shading.wireframe;
    let checkbox = ui.checkbox(&mut wireframe, "Wireframe overlay (W)").on_hover_text(
        "triangle edges drawn again as lines; needs line polygon mode on the GPU, else the Check section says so",
    );
    if checkbox.changed() {
        actions.push(Command::SetWireframe(wireframe).into());
    }
    let mut glyphs = state.shading.tbn_glyphs;
    let checkbox = ui.checkbox(&mut glyphs, "T/B/N glyphs (G)").on_hover_text(format!(
        "short lines at vertices: tangent red, bitangent green, normal blue (the frames the shading uses); \
         meshes with tangent frames only, at most {MAX_GLYPHS_PER_MESH} glyphs per mesh, spread evenly"
    ));
    if checkbox.changed() {
        actions.push(Command::SetGlyphs(glyphs).into());
    }
}

/// The camera's gestures, its reset, and how to probe a pixel.
pub(super) fn camera(ui: &mut egui::Ui, actions: &mut Vec<Action>) {
    ui.weak("Left-drag orbits, wheel zooms, Shift- or middle-drag pans");
    if ui.button("Reset camera (R)").clicked() {
        actions.push(Command::ResetCamera.into());
    }
    ui.weak("P + click on the view pins a probe: the whole shading chain at that point, in a window beside it");
}
