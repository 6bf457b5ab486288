//! Viewer state and the commands that change it. The UI (keys, panels, mouse) only produces
//! [`Command`]s; [`ViewerState::apply`] is the one place they take effect, so the window, the
//! `render` command and the tests all describe a picture the same way: a [`FrameParams`].

use glam::{Vec2, Vec3};

use crate::height::Kernel;
use crate::render::{BumpSource, FrameParams, SceneOptions};
use crate::scene::{Light, MaterialOverrides, OrbitCamera, Scene, ShadingModel};
use crate::shading::{ShadingMode, ShadingSettings, ViewMode};
use crate::tangent::TangentMethod;

/// The strength slider's range; typed values outside it are clamped.
pub const STRENGTH_RANGE: std::ops::RangeInclusive<f32> = -2.0..=4.0;
/// Allowed colour-scale spans of the Difference view, degrees.
pub const DIFFERENCE_RANGE: std::ops::Range<f32> = 0.01..180.0;
/// Orbit animation speed of the light, radians per second about the scene's vertical axis.
pub const LIGHT_ORBIT_SPEED: f32 = 0.8;

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Command {
    SetBump(bool),
    ToggleBump,
    SetStrength(f32),
    /// Adds to the strength (the `[` / `]` keys), within [`STRENGTH_RANGE`].
    StepStrength(f32),
    SetView(ViewMode),
    CycleView,
    SetLightPosition(Vec3),
    /// Moves the light parallel to the screen by a drag of `pixels` in a viewport
    /// `viewport_height` pixels tall, keeping its depth from the eye.
    DragLight {
        pixels: Vec2,
        viewport_height: f32,
    },
    SetLightOrbit(bool),
    ToggleLightOrbit,
    SetLightMarker(bool),
    /// Yaw and pitch increments, radians.
    OrbitCamera {
        d_yaw: f32,
        d_pitch: f32,
    },
    /// Multiplies the camera distance.
    Zoom(f32),
    PanCamera {
        pixels: Vec2,
        viewport_height: f32,
    },
    ResetCamera,
    /// Advances animations by `seconds`.
    Tick(f32),
    /// Tangent frames by this method (`None`: the mesh's own, else MikkTSpace).
    SetTangentMethod(Option<TangentMethod>),
    SetBumpSource(BumpSource),
    /// Height→normal kernel of the built-in brick normal map.
    SetKernel(Kernel),
    /// The Difference view's colour scale spans 0 to this many degrees.
    SetDifferenceRange(f32),
    /// Normal- and height-map conventions for one material (index into the scene's
    /// materials; they win over the viewer-wide ones field by field) or, with `material`
    /// `None`, for every material (re-makes GPU data).
    SetMaterialOverrides {
        material: Option<usize>,
        overrides: MaterialOverrides,
    },
    /// Shade every material with this model (`None`: each material's own); a uniform.
    SetShadingOverride(Option<ShadingModel>),
    /// Bump × colour, bump only or colour only (keys 1/2/3); a uniform.
    SetShadingMode(ShadingMode),
    /// The wireframe overlay (a second pass).
    SetWireframe(bool),
    ToggleWireframe,
}

/// Everything the user can change about the picture.
#[derive(Debug, Clone, PartialEq)]
pub struct ViewerState {
    pub camera: OrbitCamera,
    pub default_camera: OrbitCamera,
    pub light: Light,
    pub shading: ShadingSettings,
    pub light_orbit: bool,
    /// Tangent method, bump source and material overrides; a change means re-making the
    /// scene's GPU data.
    pub scene_options: SceneOptions,
    /// Kernel of the built-in normal map; a change means re-making the normal map.
    pub kernel: Kernel,
}

impl ViewerState {
    pub fn new(scene: &Scene) -> Self {
        ViewerState {
            camera: scene.default_camera,
            default_camera: scene.default_camera,
            light: scene.default_light,
            shading: ShadingSettings::default(),
            light_orbit: false,
            scene_options: SceneOptions::default(),
            kernel: Kernel::default(),
        }
    }

    /// What the renderer needs to draw the current picture.
    pub fn frame_params(&self) -> FrameParams {
        FrameParams { camera: self.camera, light: self.light, shading: self.shading }
    }

    /// Whether frames must keep coming without input.
    pub fn is_animating(&self) -> bool {
        self.light_orbit
    }

    pub fn apply(&mut self, command: Command) {
        match command {
            Command::SetBump(on) => self.shading.bump_enabled = on,
            Command::ToggleBump => self.shading.bump_enabled = !self.shading.bump_enabled,
            Command::SetStrength(s) if s.is_finite() => {
                self.shading.strength = s.clamp(*STRENGTH_RANGE.start(), *STRENGTH_RANGE.end())
            }
            Command::SetStrength(_) => {}
            Command::StepStrength(delta) => self.apply(Command::SetStrength(self.shading.strength + delta)),
            Command::SetView(view) => self.shading.view = view,
            Command::CycleView => self.shading.view = self.shading.view.next(),
            Command::SetLightPosition(p) if p.is_finite() => self.light.position = p,
            Command::SetLightPosition(_) => {}
            Command::DragLight { pixels, viewport_height } => {
                let depth = (self.light.position - self.camera.eye()).length();
                let (right, up) = self.camera.right_up();
                let scale = self.camera.metres_per_pixel(depth, viewport_height);
                self.light.position += (pixels.x * right - pixels.y * up) * scale;
            }
            Command::SetLightOrbit(on) => self.light_orbit = on,
            Command::ToggleLightOrbit => self.light_orbit = !self.light_orbit,
            Command::SetLightMarker(on) => self.shading.show_light_marker = on,
            Command::OrbitCamera { d_yaw, d_pitch } => self.camera.orbit(d_yaw, d_pitch),
            Command::Zoom(factor) => self.camera.zoom(factor),
            Command::PanCamera { pixels, viewport_height } => self.camera.pan(pixels, viewport_height),
            Command::ResetCamera => self.camera = self.default_camera,
            Command::Tick(seconds) if self.light_orbit && seconds.is_finite() => {
                // Rotate the light about the vertical axis through the camera target.
                let rotation = glam::Quat::from_rotation_y(LIGHT_ORBIT_SPEED * seconds);
                let target = self.camera.target;
                let offset = self.light.position - target;
                self.light.position = target + rotation * offset;
            }
            Command::Tick(_) => {}
            Command::SetTangentMethod(method) => self.scene_options.tangent_method = method,
            Command::SetBumpSource(source) => self.scene_options.bump_source = source,
            Command::SetKernel(kernel) => self.kernel = kernel,
            Command::SetDifferenceRange(degrees) if degrees.is_finite() => {
                self.shading.difference_range_deg = degrees.clamp(DIFFERENCE_RANGE.start, DIFFERENCE_RANGE.end)
            }
            Command::SetDifferenceRange(_) => {}
            Command::SetMaterialOverrides { material, overrides } => {
                self.scene_options.set_overrides(material, overrides)
            }
            Command::SetShadingOverride(model) => self.shading.shading_override = model,
            Command::SetShadingMode(mode) => self.shading.mode = mode,
            Command::SetWireframe(on) => self.shading.wireframe = on,
            Command::ToggleWireframe => self.shading.wireframe = !self.shading.wireframe,
        }
    }
}

/// Decides whether a frame must be drawn: only when what it would show has changed.
#[derive(Debug, Default)]
pub struct RedrawTracker {
    last: Option<(FrameParams, [u32; 2])>,
}

impl RedrawTracker {
    /// True (and remembers the frame) when `params` at `size` differs from the last frame drawn.
    pub fn needs_redraw(&mut self, params: &FrameParams, size: [u32; 2]) -> bool {
        let frame = (*params, size);
        if self.last.as_ref() == Some(&frame) {
            false
        } else {
            self.last = Some(frame);
            true
        }
    }

    /// Forces the next frame to be drawn (e.g. after the scene changed).
    pub fn invalidate(&mut self) {
        self.last = None;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::builtin::teaching_scene;

    #[test]
    fn unchanged_state_needs_no_redraw() {
        let scene = teaching_scene();
        let mut state = ViewerState::new(&scene);
        let mut tracker = RedrawTracker::default();
        assert!(tracker.needs_redraw(&state.frame_params(), [64, 64]));
        assert!(!tracker.needs_redraw(&state.frame_params(), [64, 64]));
        state.apply(Command::Tick(0.5)); // no animation running: nothing changes
        assert!(!tracker.needs_redraw(&state.frame_params(), [64, 64]));
        state.apply(Command::ToggleBump);
        assert!(tracker.needs_redraw(&state.frame_params(), [64, 64]));
        assert!(tracker.needs_redraw(&state.frame_params(), [65, 64]));
    }

    #[test]
    fn orbiting_light_keeps_its_distance_from_the_axis() {
        let scene = teaching_scene();
        let mut state = ViewerState::new(&scene);
        state.apply(Command::SetLightOrbit(true));
        let before = state.light.position;
        state.apply(Command::Tick(1.0));
        let after = state.light.position;
        assert_ne!(before, after);
        let radius = |p: Vec3| {
            let d = p - state.camera.target;
            Vec2::new(d.x, d.z).length()
        };
        assert!((radius(before) - radius(after)).abs() < 1e-5);
        assert!((before.y - after.y).abs() < 1e-6);
    }

    #[test]
    fn modes_and_wireframe_are_uniform_changes_the_tracker_sees() {
        let scene = teaching_scene();
        let mut state = ViewerState::new(&scene);
        let mut tracker = RedrawTracker::default();
        assert!(tracker.needs_redraw(&state.frame_params(), [64, 64]));
        state.apply(Command::SetShadingMode(ShadingMode::BumpOnly));
        assert!(tracker.needs_redraw(&state.frame_params(), [64, 64]));
        state.apply(Command::SetShadingMode(ShadingMode::BumpOnly));
        assert!(!tracker.needs_redraw(&state.frame_params(), [64, 64]));
        state.apply(Command::ToggleWireframe);
        assert!(state.shading.wireframe);
        assert!(tracker.needs_redraw(&state.frame_params(), [64, 64]));
        state.apply(Command::SetWireframe(false));
        assert!(!state.shading.wireframe);
        assert_eq!(state.scene_options, SceneOptions::default(), "no GPU data to re-make");
    }

    #[test]
    fn strength_is_clamped_and_nan_ignored() {
        let scene = teaching_scene();
        let mut state = ViewerState::new(&scene);
        state.apply(Command::SetStrength(10.0));
        assert_eq!(state.shading.strength, 4.0);
        state.apply(Command::SetStrength(f32::NAN));
        assert_eq!(state.shading.strength, 4.0);
        state.apply(Command::StepStrength(-0.5));
        state.apply(Command::StepStrength(-0.5));
        assert_eq!(state.shading.strength, 3.0);
    }
}
