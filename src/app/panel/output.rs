//! What leaves the viewer: screenshots and tile exports, presets, and the renderer's figures.

use bumpview::render::capture::MAX_SUPERSAMPLE;

use super::outcome;
use crate::app::action::Action;
use crate::app::controller::{Controller, PresetForm, ScreenshotForm};

/// The screenshot of the 3D view only (size, background, supersampling) and the tile export.
pub(super) fn screenshot(ui: &mut egui::Ui, form: &mut ScreenshotForm, actions: &mut Vec<Action>) {
    ui.horizontal(|ui| {
        ui.label("Size");
        ui.add(egui::TextEdit::singleline(&mut form.size_text).hint_text("view size").desired_width(110.0))
            .on_hover_text("WxH in pixels, e.g. 3840x2160, up to the adapter's limit; empty uses the view's size");
    });
    ui.checkbox(&mut form.transparent, "Transparent background")
        .on_hover_text("alpha 0 where there is no geometry; the PNG keeps alpha");
    ui.add(egui::Slider::new(&mut form.supersample, 1..=MAX_SUPERSAMPLE).text("supersampling ×"))
        .on_hover_text("render at k times the size and average k×k pixels in linear light");
    if ui.button("Save PNG (F12)").clicked() {
        actions.push(Action::Screenshot);
    }
    ui.add(
        egui::TextEdit::singleline(&mut form.tiles_text).hint_text("flat,bumped,tangent").desired_width(f32::INFINITY),
    )
    .on_hover_text(
        "tiles: rows separated by ';', tiles by ',', each NAME or NAME@STRENGTH; NAME is flat, bumped, \
         bump-only, colour-only or a view (tangent, shading-normal, handedness, ...); empty: flat,bumped,tangent",
    );
    ui.horizontal(|ui| {
        if ui.button("Export tiles").on_hover_text("the tiles above as one PNG, each of the size above").clicked() {
            actions.push(Action::ExportTiles);
        }
        ui.checkbox(&mut form.captions, "captions")
            .on_hover_text("a strip under each tile: view and mode, strength, normal-map convention, tangents");
    });
    outcome(ui, &form.message);
}

/// Save and load the whole state (files, camera, light, settings, screenshot options).
pub(super) fn preset(ui: &mut egui::Ui, form: &mut PresetForm, actions: &mut Vec<Action>) {
    ui.add(egui::TextEdit::singleline(&mut form.path_text).hint_text("file, e.g. slide.toml"))
        .on_hover_text("the preset file; bumpview render --preset FILE draws the same picture");
    let path = std::path::PathBuf::from(form.path_text.trim());
    let named = !form.path_text.trim().is_empty();
    ui.horizontal(|ui| {
        if ui.add_enabled(named, egui::Button::new("Save preset")).clicked() {
            actions.push(Action::SavePreset(path.clone()));
        }
        if ui.add_enabled(named, egui::Button::new("Load preset")).clicked() {
            actions.push(Action::LoadPreset(path));
        }
    });
    outcome(ui, &form.message);
}

/// The interactive-frames setting and what the last interactive frame cost.
pub(super) fn interactive(ui: &mut egui::Ui, controller: &Controller, actions: &mut Vec<Action>) {
    let mut on = controller.interactive_frames();
    let hint = "while you drag or the light orbits: 1 sample per pixel, and fewer pixels while a frame costs more \
                than twice the adapter's floor (at least 4 ms); one full-quality frame (4× MSAA) when input stops. \
                Screenshots and exports are always full quality.";
    if ui.checkbox(&mut on, "Interactive frames while dragging").on_hover_text(hint).changed() {
        actions.push(Action::SetInteractiveFrames(on));
    }
    if let (true, Some(frame), Some([width, _])) = (on, controller.last_interactive(), controller.view_size()) {
        let [w, h] = frame.size;
        ui.small(format!(
            "last: {w}x{h} ({:.0} % of the view's width), {:.1} ms, budget {:.1} ms",
            100.0 * w as f64 / width as f64,
            frame.frame_ms,
            frame.budget_ms
        ));
    }
}

/// The adapter, the view's size, the work done so far and what the last scene change cost.
pub(super) fn stats(ui: &mut egui::Ui, controller: &Controller) {
    let size = controller.view_size().map_or_else(|| "no view".to_owned(), |[w, h]| format!("{w}x{h}"));
    let renderer = controller.renderer();
    let counters = renderer.counters();
    ui.small(format!(
        "{} · view {size} · {} frames drawn · {} pipelines built",
        renderer.adapter_name(),
        counters.frames_drawn,
        counters.pipelines_built
    ));
    if let Some(job) = controller.last_job() {
        // Two short lines: a wider panel would narrow the 3D view.
        ui.small(format!(
            "last scene change: load {:.0} ms, prepare {:.0} ms, upload {:.0} ms,",
            job.load_ms, job.prepare_ms, job.upload_ms
        ));
        ui.small(format!("measure {:.0} ms (off the UI thread); install {:.1} ms", job.measure_ms, job.install_ms));
    }
}
