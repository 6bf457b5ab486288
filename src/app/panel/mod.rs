//! The control panel, laid out for a lecture: the toggles used every minute — bump on/off,
//! strength, view, split view, light — stay at the top without scrolling ([`quick`]); the rest
//! sits below in collapsible sections whose open/closed state egui keeps for the session
//! (each header has a fixed id). Widgets edit copies of the state and report changes as
//! [`Action`]s; only the forms' text fields are edited in place.

mod detail;
mod files;
mod lessons;
mod lights;
mod methods;
mod mistakes;
mod output;
mod parallax;
mod picture;
mod quick;

use bumpview::load::TextureSlot;
pub use files::drop_hint;

use super::action::Action;
use super::controller::Controller;

/// Shows the whole panel; returns what the user changed and where the texture slot buttons
/// were drawn (for files dropped on them; none while their section is closed).
pub fn show(
    ui: &mut egui::Ui,
    controller: &mut Controller,
    render_error: Option<&str>,
) -> (Vec<Action>, Vec<(TextureSlot, egui::Rect)>) {
    let mut actions = Vec::new();
    files::heading(ui, controller, &mut actions);
    #[cfg(target_arch = "wasm32")]
    crate::app::browser::panel_note(ui, &controller.renderer().adapter_name());
    if let Some(error) = render_error {
        ui.colored_label(ui.visuals().error_fg_color, error);
    }
    quick::show(ui, &controller.state, &mut actions);
    ui.separator();
    let mut slot_targets = Vec::new();
    egui::ScrollArea::vertical().show(ui, |ui| {
        section(ui, "Lessons", false, |ui| lessons::show(ui, &mut controller.lessons, &mut actions));
        section(ui, "Files and texture slots", false, |ui| {
            slot_targets = files::show(ui, controller, &mut actions);
        });
        section(ui, "Lit picture and overlays", true, |ui| picture::show(ui, &controller.state, &mut actions));
        section(ui, "Lights and specular", false, |ui| lights::show(ui, &controller.state, &mut actions));
        section(ui, "Parallax and displacement", false, |ui| {
            // A right half without an upload of its own is drawn from the main one: not listed.
            let renderer = controller.renderer();
            let split_upload = renderer.uploads().is_some_and(|u| u.split_right.is_some());
            let displaced = [false, true].map(|half| {
                let cpu = || renderer.prepared(half).and_then(|p| p.displacement).map(parallax::Displaced::Cpu);
                let gpu = || renderer.gpu_displacement(half).map(parallax::Displaced::Gpu);
                (!half || split_upload).then(|| cpu().or_else(gpu)).flatten()
            });
            parallax::show(ui, &controller.state, &mut actions);
            parallax::displacement(ui, &controller.state, displaced, &mut actions);
        });
        section(ui, "Classic mistakes", false, |ui| mistakes::show(ui, &controller.state, &mut actions));
        section(ui, "Legacy looks", false, |ui| mistakes::legacy(ui, &controller.state, &mut actions));
        section(ui, "Tangent frames and kernels", false, |ui| {
            let measurements = controller.facts().map_or(&[][..], |facts| &facts.measurements[..]);
            methods::methods(ui, &controller.state, measurements, &mut actions);
        });
        section(ui, "Texture conventions and shading", false, |ui| {
            methods::conventions(ui, &controller.state, &controller.scene().materials, &mut actions);
        });
        section(ui, "Check", false, |ui| methods::check(ui, controller, &mut actions));
        section(ui, "Camera and probe", false, |ui| picture::camera(ui, &mut actions));
        section(ui, "Screenshot and tiles", false, |ui| {
            output::screenshot(ui, &mut controller.screenshot, &mut actions)
        });
        section(ui, "Preset", false, |ui| output::preset(ui, &mut controller.preset, &mut actions));
        ui.separator();
        output::interactive(ui, controller, &mut actions);
        output::stats(ui, controller);
    });
    (actions, slot_targets)
}

/// A collapsible section titled `title`, open at first if `open`; its id is the title, so egui
/// remembers whether it is open.
fn section(ui: &mut egui::Ui, title: &str, open: bool, body: impl FnOnce(&mut egui::Ui)) {
    egui::CollapsingHeader::new(egui::RichText::new(title).strong()).id_salt(title).default_open(open).show(ui, body);
}

/// A form's last outcome: plain on success, in the error colour on failure.
fn outcome(ui: &mut egui::Ui, message: &Option<Result<String, String>>) {
    match message {
        Some(Ok(message)) => {
            ui.label(message);
        }
        Some(Err(message)) => {
            ui.colored_label(ui.visuals().error_fg_color, message);
        }
        None => {}
    }
}
