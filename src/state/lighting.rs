//! The lighting commands: which light is selected, adding, changing and removing lights, the
//! ambient light, the specular mode and shininess, and the lighting space.

use glam::Vec3;

use crate::frame::LightingSpace;
use crate::scene::{Light, MAX_LIGHTS, SpecularMode};

use super::ViewerState;

/// A change to the lights or to how they light ([`super::Command::Lighting`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LightCommand {
    /// Light `index` is the one the position sliders, `SetLightPosition` and Ctrl-drag move
    /// (clamped to the lights there are).
    Select(usize),
    /// Replaces light `index`, or appends it when `index` is the number of lights (ignored
    /// past that, when [`MAX_LIGHTS`] are there, or with a non-finite or negative value).
    Set {
        index: usize,
        light: Light,
    },
    /// Removes light `index`; the last light stays.
    Remove(usize),
    /// Keeps the first `count` lights (at least one).
    Truncate(usize),
    /// The ambient light: linear RGB colour and a strength multiplying it (each at least 0).
    SetAmbient {
        color: Vec3,
        strength: f32,
    },
    SetSpecular(SpecularMode),
    /// The shininess for every material (`None`: each material's own), at least 1.
    SetShininess(Option<f32>),
    SetLightingSpace(LightingSpace),
}

/// Whether the numbers of `light` are ones a light may have: finite, colour and intensity at
/// least 0, attenuation coefficients at least 0 and not all 0.
fn acceptable(light: &Light) -> bool {
    light.is_finite()
        && light.color.min_element() >= 0.0
        && light.intensity >= 0.0
        && crate::scene::Attenuation::from_array(light.attenuation.to_array()).is_ok()
}

impl ViewerState {
    /// The light the position sliders and Ctrl-drag move.
    pub fn selected_light(&self) -> usize {
        self.selected_light.min(self.lights.len() - 1)
    }

    pub(super) fn apply_lighting(&mut self, command: LightCommand) {
        match command {
            LightCommand::Select(index) => self.selected_light = index.min(self.lights.len() - 1),
            LightCommand::Set { index, light } if acceptable(&light) => {
                if index < self.lights.len() {
                    self.lights[index] = light;
                } else if index == self.lights.len() && index < MAX_LIGHTS {
                    let _ = self.lights.push(light);
                }
            }
            LightCommand::Set { .. } => {}
            LightCommand::Remove(index) => {
                let _ = self.lights.remove(index);
                self.selected_light = self.selected_light();
            }
            LightCommand::Truncate(count) => {
                while self.lights.len() > count.max(1) {
                    let _ = self.lights.remove(self.lights.len() - 1);
                }
                self.selected_light = self.selected_light();
            }
            LightCommand::SetAmbient { color, strength }
                if color.is_finite() && color.min_element() >= 0.0 && strength.is_finite() && strength >= 0.0 =>
            {
                self.lights.ambient_color = color;
                self.lights.ambient_strength = strength;
            }
            LightCommand::SetAmbient { .. } => {}
            LightCommand::SetSpecular(mode) => self.shading.specular = mode,
            LightCommand::SetShininess(Some(s)) if !s.is_finite() => {}
            LightCommand::SetShininess(shininess) => self.shading.shininess = shininess.map(|s| s.max(1.0)),
            LightCommand::SetLightingSpace(space) => self.shading.lighting_space = space,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::builtin::teaching_scene;
    use crate::state::Command;

    #[test]
    fn lights_are_added_selected_dragged_and_removed() {
        let scene = teaching_scene();
        let mut state = ViewerState::new(&scene);
        let red = Light::point(Vec3::new(1.0, 1.0, 1.0), Vec3::X);
        state.apply(Command::Lighting(LightCommand::Set { index: 1, light: red }));
        state.apply(Command::Lighting(LightCommand::Set { index: 5, light: red }));
        assert_eq!(state.lights.len(), 2, "only appended at the end");
        state.apply(Command::Lighting(LightCommand::Select(7)));
        assert_eq!(state.selected_light(), 1);
        state.apply(Command::SetLightPosition(Vec3::new(2.0, 3.0, 4.0)));
        assert_eq!(state.lights[1].position, Vec3::new(2.0, 3.0, 4.0));
        assert_eq!(state.lights[0], scene.default_light, "the other light stays");
        let before = state.lights[1].position;
        state.apply(Command::DragLight { pixels: glam::Vec2::new(10.0, 0.0), viewport_height: 100.0 });
        assert_ne!(state.lights[1].position, before);
        assert_eq!(state.lights[0], scene.default_light);
        state.apply(Command::Lighting(LightCommand::Remove(1)));
        assert_eq!((state.lights.len(), state.selected_light()), (1, 0));
        state.apply(Command::Lighting(LightCommand::Remove(0)));
        assert_eq!(state.lights.len(), 1, "the last light stays");
        let bad = Light { intensity: f32::NAN, ..red };
        state.apply(Command::Lighting(LightCommand::Set { index: 0, light: bad }));
        assert_eq!(state.lights[0], scene.default_light);
    }

    /// Dragging a directional light's marker turns its direction: the marker stays half the
    /// camera distance from the target.
    #[test]
    fn dragging_a_directional_light_turns_it() {
        let scene = teaching_scene();
        let mut state = ViewerState::new(&scene);
        let sun = Light::directional(Vec3::new(0.0, 1.0, 1.0), Vec3::ONE);
        state.apply(Command::Lighting(LightCommand::Set { index: 0, light: sun }));
        state.apply(Command::DragLight { pixels: glam::Vec2::new(40.0, 0.0), viewport_height: 200.0 });
        let towards = state.lights[0].position;
        assert!((towards.length() - 1.0).abs() < 1e-5 && towards.x > 0.1, "{towards}");
        let marker = state.frame_params().marker_position(0);
        let distance = (marker - state.camera.target).length();
        assert!((distance - 0.5 * state.camera.distance).abs() < 1e-4);
    }
}
