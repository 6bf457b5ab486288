//! Viewer state and the commands that change it. The UI (keys, panels, mouse) only produces
//! [`Command`]s; [`ViewerState::apply`] is the one place they take effect, so the window, the
//! `render` command and the tests all describe a picture the same way: a [`FrameParams`].

use glam::{Vec2, Vec3};

use crate::height::Kernel;
use crate::render::{BumpSource, FrameParams, SceneOptions, SplitFrame};
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
    /// The split view on or off (key S).
    SetSplit(bool),
    ToggleSplit,
    /// What the split view's halves differ in.
    SetSplitDifference(SplitDifference),
    /// The divider's position, a fraction of the view's width (clamped to 0..1).
    SetSplitDivider(f32),
    /// The two views of [`SplitDifference::View`], left and right.
    SetSplitViews([ViewMode; 2]),
    /// The two strengths of [`SplitDifference::Strength`] (within [`STRENGTH_RANGE`]).
    SetSplitStrengths([f32; 2]),
    /// The two modes of [`SplitDifference::Mode`].
    SetSplitModes([ShadingMode; 2]),
}

/// What the split view's two halves differ in: only uniforms, so both halves share one scene
/// upload. (Two tangent methods or two normal-map conventions need different GPU data and are
/// not offered.)
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum SplitDifference {
    /// Bump off │ bump on.
    #[default]
    Bump,
    /// Two views, e.g. Lit │ Shading normal.
    View,
    /// Two bump strengths.
    Strength,
    /// Two lit-picture modes (bump × colour, bump only, colour only).
    Mode,
}

impl SplitDifference {
    pub const ALL: [SplitDifference; 4] =
        [SplitDifference::Bump, SplitDifference::View, SplitDifference::Strength, SplitDifference::Mode];

    /// Name as used on the command line and in presets.
    pub fn name(self) -> &'static str {
        match self {
            SplitDifference::Bump => "bump",
            SplitDifference::View => "view",
            SplitDifference::Strength => "strength",
            SplitDifference::Mode => "mode",
        }
    }

    pub fn from_name(name: &str) -> Option<SplitDifference> {
        SplitDifference::ALL.into_iter().find(|d| d.name() == name)
    }
}

/// The split view's settings: the two halves are the current shading with one thing changed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SplitView {
    pub enabled: bool,
    pub difference: SplitDifference,
    /// The divider, a fraction of the width.
    pub divider: f32,
    pub views: [ViewMode; 2],
    pub strengths: [f32; 2],
    pub modes: [ShadingMode; 2],
}

impl Default for SplitView {
    fn default() -> Self {
        SplitView {
            enabled: false,
            difference: SplitDifference::Bump,
            divider: 0.5,
            views: [ViewMode::Lit, ViewMode::ShadingNormal],
            strengths: [1.0, 3.0],
            modes: [ShadingMode::ColourOnly, ShadingMode::BumpTimesColour],
        }
    }
}

impl SplitView {
    /// The left and right shading: `current` with the chosen difference applied.
    pub fn shading(&self, current: &ShadingSettings) -> [ShadingSettings; 2] {
        let side = |i: usize| {
            let mut s = *current;
            match self.difference {
                SplitDifference::Bump => s.bump_enabled = i == 1,
                SplitDifference::View => s.view = self.views[i],
                SplitDifference::Strength => s.strength = self.strengths[i],
                SplitDifference::Mode => s.mode = self.modes[i],
            }
            s
        };
        [side(0), side(1)]
    }

    /// The on-screen labels of the left and right halves.
    pub fn labels(&self) -> [String; 2] {
        std::array::from_fn(|i| match self.difference {
            SplitDifference::Bump => ["bump off", "bump on"][i].to_owned(),
            SplitDifference::View => view_label(self.views[i]).to_owned(),
            SplitDifference::Strength => format!("strength {:.2}", self.strengths[i]),
            SplitDifference::Mode => mode_label(self.modes[i]).to_owned(),
        })
    }
}

/// A view's name for people (labels and captions).
pub fn view_label(view: ViewMode) -> &'static str {
    match view {
        ViewMode::Lit => "Lit",
        ViewMode::Tangent => "Tangent",
        ViewMode::Bitangent => "Bitangent",
        ViewMode::Normal => "Normal",
        ViewMode::ShadingNormal => "Shading normal",
        ViewMode::Difference => "Difference",
        ViewMode::UvCheck => "UV check",
        ViewMode::Handedness => "Handedness",
        ViewMode::OverTilt => "Over-tilt",
    }
}

/// A lit-picture mode's name for people (labels and captions).
pub fn mode_label(mode: ShadingMode) -> &'static str {
    match mode {
        ShadingMode::BumpTimesColour => "bump × colour",
        ShadingMode::BumpOnly => "bump only",
        ShadingMode::ColourOnly => "colour only",
    }
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
    /// The split view (two settings side by side).
    pub split: SplitView,
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
            split: SplitView::default(),
        }
    }

    /// The split view's two pictures, when it is on.
    pub fn split_frame(&self) -> Option<SplitFrame> {
        self.split.enabled.then(|| {
            let [left, right] = self.split.shading(&self.shading);
            SplitFrame { left, right, divider: self.split.divider }
        })
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
            Command::SetSplit(on) => self.split.enabled = on,
            Command::ToggleSplit => self.split.enabled = !self.split.enabled,
            Command::SetSplitDifference(difference) => self.split.difference = difference,
            Command::SetSplitDivider(x) if x.is_finite() => self.split.divider = x.clamp(0.0, 1.0),
            Command::SetSplitDivider(_) => {}
            Command::SetSplitViews(views) => self.split.views = views,
            Command::SetSplitStrengths(strengths) if strengths.iter().all(|s| s.is_finite()) => {
                self.split.strengths = strengths.map(|s| s.clamp(*STRENGTH_RANGE.start(), *STRENGTH_RANGE.end()))
            }
            Command::SetSplitStrengths(_) => {}
            Command::SetSplitModes(modes) => self.split.modes = modes,
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
