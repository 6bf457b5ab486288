//! What moves the camera and the lights: orbiting, zooming and panning the camera, dragging
//! the selected light, and the lights' orbit animation.

use super::{Command, LIGHT_ORBIT_SPEED, ViewerState};
use crate::math::normalize_or;
use crate::scene::LightKind;

impl ViewerState {
    /// Applies `command` if it moves the camera or a light; whether it did.
    pub(super) fn apply_motion(&mut self, command: Command) -> bool {
        match command {
            Command::SetLightPosition(p) if p.is_finite() => {
                let selected = self.selected_light();
                self.lights[selected].position = p
            }
            Command::SetLightPosition(_) => {}
            Command::DragLight { pixels, viewport_height } => {
                let selected = self.selected_light();
                let marker = self.frame_params().marker_position(selected);
                let depth = (marker - self.camera.eye()).length();
                let (right, up) = self.camera.right_up();
                let scale = self.camera.metres_per_pixel(depth, viewport_height);
                let moved = marker + (pixels.x * right - pixels.y * up) * scale;
                let light = &mut self.lights[selected];
                light.position = match light.kind {
                    LightKind::Point => moved,
                    LightKind::Directional => normalize_or(moved - self.camera.target, light.position),
                };
            }
            Command::SetLightOrbit(on) => self.light_orbit = on,
            Command::ToggleLightOrbit => self.light_orbit = !self.light_orbit,
            Command::OrbitCamera { d_yaw, d_pitch } => self.camera.orbit(d_yaw, d_pitch),
            Command::Zoom(factor) => self.camera.zoom(factor),
            Command::PanCamera { pixels, viewport_height } => self.camera.pan(pixels, viewport_height),
            Command::ResetCamera => self.camera = self.default_camera,
            Command::PointCamera { yaw, pitch, distance } => self.camera.point(yaw, pitch, distance),
            Command::Tick(seconds) if self.light_orbit && seconds.is_finite() => {
                // Turn every light about the vertical axis through the camera target.
                let rotation = glam::Quat::from_rotation_y(LIGHT_ORBIT_SPEED * seconds);
                let target = self.camera.target;
                for light in self.lights.as_mut_slice() {
                    light.position = match light.kind {
                        LightKind::Point => target + rotation * (light.position - target),
                        LightKind::Directional => rotation * light.position,
                    };
                }
            }
            Command::Tick(_) => {}
            _ => return false,
        }
        true
    }
}
