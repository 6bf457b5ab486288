//! The panel's files: the heading with Open…, the loading spinner and the last outcome (always
//! in sight), and a section with the texture slot buttons (click for a dialog, or drop a
//! texture on one), the recent files, and per material and mesh which maps and tangent frames
//! are in use. Everything it does is an [`Action`].

use bumpview::load::TextureSlot;
use bumpview::names::Named;
use bumpview::scene::Scene;
use bumpview::tangent::TangentMethod;

use crate::app::action::Action;
use crate::app::controller::Controller;
use crate::app::files::{Files, Status, file_name};

/// The panel's heading and Open…, the scene job in flight, the last load's outcome and why hot
/// reload does not work, if it does not.
pub(super) fn heading(ui: &mut egui::Ui, controller: &Controller, actions: &mut Vec<Action>) {
    let files = &controller.files;
    ui.horizontal(|ui| {
        ui.heading("bumpview");
        let open = ui.add_enabled(!controller.dialog_open(), egui::Button::new("Open…"));
        if open.on_hover_text("a glTF (.gltf, .glb) or OBJ mesh, or a texture; or drop files on the window").clicked() {
            actions.push(Action::ShowDialog(None));
        }
    });
    // On a row of its own that wraps: a long stage name must not widen the panel (and so
    // shrink the view) while a scene job runs.
    if let Some(busy) = controller.busy() {
        ui.horizontal_wrapped(|ui| {
            ui.add(egui::Spinner::new());
            ui.label(busy);
        });
    }
    match &files.status {
        Some(Status::Done(message)) => {
            ui.label(message);
        }
        Some(Status::Failed(message)) => {
            ui.colored_label(ui.visuals().error_fg_color, message);
        }
        None => {}
    }
    if let Some(error) = controller.watch_error() {
        ui.colored_label(ui.visuals().warn_fg_color, error);
    }
}

/// The slot buttons, the recent files and the scene's maps and frames; returns where each slot
/// button is, for files dropped on them.
pub(super) fn show(
    ui: &mut egui::Ui,
    controller: &Controller,
    actions: &mut Vec<Action>,
) -> Vec<(TextureSlot, egui::Rect)> {
    let targets = slot_buttons(ui, controller, actions);
    recent_files(ui, &controller.files, actions);
    scene_maps(ui, controller.scene(), &controller.renderer().tangent_methods());
    targets
}

/// One button per texture slot with the file in it: a click opens a dialog for the slot, a
/// texture dropped on it goes into it.
fn slot_buttons(
    ui: &mut egui::Ui,
    controller: &Controller,
    actions: &mut Vec<Action>,
) -> Vec<(TextureSlot, egui::Rect)> {
    ui.weak("Texture slots: click to choose, or drop a texture on one");
    let mut targets = Vec::new();
    egui::Grid::new("slots").num_columns(2).show(ui, |ui| {
        for &slot in TextureSlot::all() {
            ui.label(slot.label());
            let file = controller.files.scene_files.texture(slot);
            let text = file.map_or_else(|| "— choose…".to_owned(), file_name);
            let button = ui.add_enabled(!controller.dialog_open(), egui::Button::new(text).truncate());
            targets.push((slot, button.rect));
            let hover = file.map_or_else(|| "from the mesh's material".to_owned(), |f| f.display().to_string());
            if button.on_hover_text(hover).clicked() {
                actions.push(Action::ShowDialog(Some(slot)));
            }
            ui.end_row();
        }
    });
    targets
}

/// The recent files, newest first; a click opens one (a texture goes to its guessed slot).
fn recent_files(ui: &mut egui::Ui, files: &Files, actions: &mut Vec<Action>) {
    egui::CollapsingHeader::new(format!("Recent files ({})", files.recent.paths().len())).show(ui, |ui| {
        if files.recent.paths().is_empty() {
            ui.weak("none yet");
        }
        for path in files.recent.paths() {
            if ui.small_button(file_name(path)).on_hover_text(path.display().to_string()).clicked() {
                actions.push(Action::Open { paths: vec![path.clone()], slot: None });
            }
        }
    });
}

/// Per material the normal and height maps in use; per mesh where its tangent frames come
/// from ("file" when the file supplies them, else the method that generated them).
fn scene_maps(ui: &mut egui::Ui, scene: &Scene, tangents: &[Option<TangentMethod>]) {
    let texture = |index: Option<usize>| {
        // Texture names are the files they came from; the file name is enough here.
        let name = |t: &std::sync::Arc<bumpview::scene::TextureImage>| file_name(std::path::Path::new(&t.name));
        index.and_then(|i| scene.textures.get(i)).map_or_else(|| "none".to_owned(), name)
    };
    let heading = format!("Scene: {} materials, {} meshes", scene.materials.len(), scene.meshes.len());
    egui::CollapsingHeader::new(heading).default_open(true).show(ui, |ui| {
        egui::Grid::new("materials").striped(true).num_columns(2).show(ui, |ui| {
            for material in &scene.materials {
                ui.small(&material.name);
                ui.vertical(|ui| {
                    ui.small(format!("normal map: {}", texture(material.normal_map.as_ref().map(|n| n.texture))));
                    ui.small(format!("height map: {}", texture(material.height_map.as_ref().map(|h| h.texture))));
                });
                ui.end_row();
            }
            for (mesh, method) in scene.meshes.iter().zip(tangents) {
                let source = match method {
                    Some(TangentMethod::Supplied) => "tangents: file".to_owned(),
                    Some(method) => format!("tangents: generated: {}", method.name()),
                    None => "tangents: none (no normal map)".to_owned(),
                };
                ui.small(&mesh.name);
                ui.small(source);
                ui.end_row();
            }
        });
    });
}

/// While files are dragged over the window, says what dropping them does.
pub fn drop_hint(ctx: &egui::Context) {
    if ctx.input(|i| i.raw.hovered_files.is_empty()) {
        return;
    }
    let painter = ctx.layer_painter(egui::LayerId::new(egui::Order::Foreground, egui::Id::unique("drop hint")));
    let rect = ctx.content_rect();
    painter.rect_filled(rect, 0.0, egui::Color32::from_black_alpha(160));
    painter.text(
        rect.center(),
        egui::Align2::CENTER_CENTER,
        "Drop to open: a mesh replaces the scene; a texture fills the slot it is dropped on,\n\
         or the one its name suggests",
        egui::FontId::proportional(18.0),
        egui::Color32::WHITE,
    );
}
