//! The lights: which one is selected (the position sliders at the top and Ctrl-drag move it),
//! adding and removing lights, each light's kind, colour, intensity, on/off and attenuation,
//! the ambient light, the specular mode and shininess, and the lighting space.

use bumpview::frame::LightingSpace;
use bumpview::names::Named;
use bumpview::scene::{Attenuation, Light, LightKind, MAX_LIGHTS, SpecularMode};
use bumpview::state::{Command, LightCommand, ViewerState};
use glam::Vec3;

use crate::app::action::Action;

fn push(actions: &mut Vec<Action>, command: LightCommand) {
    actions.push(Command::Lighting(command).into());
}

/// The light list, the selected light's settings, the ambient light and the lighting model.
pub(super) fn show(ui: &mut egui::Ui, state: &ViewerState, actions: &mut Vec<Action>) {
    let selected = state.selected_light();
    ui.horizontal_wrapped(|ui| {
        for (i, light) in state.lights.as_slice().iter().enumerate() {
            let [r, g, b] = light.color.clamp(Vec3::ZERO, Vec3::ONE).to_array().map(|c| (c * 255.0) as u8);
            let text = egui::RichText::new(format!("L{}", i + 1)).color(egui::Color32::from_rgb(r, g, b));
            let text = if light.enabled { text } else { text.strikethrough() };
            if ui.selectable_label(i == selected, text).clicked() {
                push(actions, LightCommand::Select(i));
            }
        }
        if state.lights.len() < MAX_LIGHTS && ui.button("+").on_hover_text("add a point light").clicked() {
            let light = Light { enabled: true, ..state.lights[selected] };
            push(actions, LightCommand::Set { index: state.lights.len(), light });
            push(actions, LightCommand::Select(state.lights.len()));
        }
        if state.lights.len() > 1 && ui.button("−").on_hover_text("remove the selected light").clicked() {
            push(actions, LightCommand::Remove(selected));
        }
    });
    light(ui, selected, state.lights[selected], actions);
    ui.separator();
    ambient(ui, state, actions);
    model(ui, state, actions);
}

/// The selected light's settings.
fn light(ui: &mut egui::Ui, index: usize, light: Light, actions: &mut Vec<Action>) {
    let mut edited = light;
    ui.horizontal(|ui| {
        ui.checkbox(&mut edited.enabled, "on");
        egui::ComboBox::from_id_salt("light kind").selected_text(edited.kind.name()).show_ui(ui, |ui| {
            for &kind in LightKind::all() {
                ui.selectable_value(&mut edited.kind, kind, kind.name());
            }
        });
        let mut color = edited.color.to_array();
        ui.color_edit_button_rgb(&mut color);
        edited.color = Vec3::from_array(color);
    });
    if edited.kind != light.kind {
        // A point light becomes a light from where it was (seen from the origin), and back.
        edited.position = light.position;
    }
    ui.add(egui::Slider::new(&mut edited.intensity, 0.0..=4.0).text("intensity"));
    if edited.kind == LightKind::Point {
        let [mut c, mut l, mut q] = edited.attenuation.to_array();
        ui.horizontal(|ui| {
            ui.label("attenuation 1/(c + l·d + q·d²)");
            ui.add(egui::DragValue::new(&mut c).speed(0.01).range(0.0..=10.0).prefix("c "));
            ui.add(egui::DragValue::new(&mut l).speed(0.01).range(0.0..=10.0).prefix("l "));
            ui.add(egui::DragValue::new(&mut q).speed(0.01).range(0.0..=10.0).prefix("q "));
        });
        edited.attenuation = Attenuation::from_array([c, l, q]).unwrap_or(light.attenuation);
    } else {
        ui.weak("directional: the position sliders give the direction towards the light");
    }
    if edited != light {
        push(actions, LightCommand::Set { index, light: edited });
    }
}

fn ambient(ui: &mut egui::Ui, state: &ViewerState, actions: &mut Vec<Action>) {
    let (mut color, mut strength) = (state.lights.ambient_color.to_array(), state.lights.ambient_strength);
    let changed = ui
        .horizontal(|ui| {
            ui.label("ambient");
            ui.color_edit_button_rgb(&mut color).changed()
                | ui.add(egui::Slider::new(&mut strength, 0.0..=4.0).text("strength")).changed()
        })
        .inner;
    if changed {
        push(actions, LightCommand::SetAmbient { color: Vec3::from_array(color), strength });
    }
}

/// Specular mode, shininess and lighting space.
fn model(ui: &mut egui::Ui, state: &ViewerState, actions: &mut Vec<Action>) {
    let shading = &state.shading;
    let mut specular = shading.specular;
    egui::ComboBox::from_label("specular").selected_text(specular.label()).show_ui(ui, |ui| {
        for &mode in SpecularMode::all() {
            ui.selectable_value(&mut specular, mode, mode.label());
        }
    });
    if specular != shading.specular {
        push(actions, LightCommand::SetSpecular(specular));
    }
    let mut own = shading.shininess.is_none();
    if ui.checkbox(&mut own, "shininess: each material's own").changed() {
        push(actions, LightCommand::SetShininess(if own { None } else { Some(32.0) }));
    }
    if let Some(mut shininess) = shading.shininess {
        let slider = egui::Slider::new(&mut shininess, 1.0..=256.0).logarithmic(true).text("shininess");
        if ui.add(slider).changed() {
            push(actions, LightCommand::SetShininess(Some(shininess)));
        }
    }
    let mut space = shading.lighting_space;
    egui::ComboBox::from_label("lighting space").selected_text(space.name()).show_ui(ui, |ui| {
        for &choice in LightingSpace::all() {
            ui.selectable_value(&mut space, choice, choice.name());
        }
    });
    if space != shading.lighting_space {
        push(actions, LightCommand::SetLightingSpace(space));
    }
}
