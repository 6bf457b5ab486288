//! Viewer state and the commands that change it. The UI (keys, panels, mouse) only produces
//! [`Command`]s; [`ViewerState::apply`] is the one place they take effect, so the window, the
//! `render` command and the tests all describe a picture the same way: a [`FrameParams`].

mod command;
pub mod interactive;
mod lighting;
mod motion;
pub mod preset;
mod split;

pub use command::Command;
pub use lighting::LightCommand;

pub use split::{SplitDifference, SplitView};

use crate::frame::{
    FrameParams, GPU_PIXELS_PER_EDGE, LegacyLook, LegacySettings, MAX_DISPLACEMENT_LEVEL, MAX_PARALLAX_LAYERS,
    MAX_PARALLAX_SHADOW_STRENGTH, MAX_PARALLAX_STEPS, Mistake, Msaa, Parallax, STRENGTH_RANGE, SceneOptions,
    SceneUploads, ShadingSettings, SplitFrame,
};
use crate::height::Kernel;
use crate::scene::{Lights, OrbitCamera, Scene};

/// Allowed colour-scale spans of the Difference view, degrees.
pub const DIFFERENCE_RANGE: std::ops::Range<f32> = 0.01..180.0;
/// Orbit animation speed of the lights, radians per second about the scene's vertical axis.
pub const LIGHT_ORBIT_SPEED: f32 = 0.8;

/// Everything the user can change about the picture.
#[derive(Debug, Clone, PartialEq)]
pub struct ViewerState {
    pub camera: OrbitCamera,
    pub default_camera: OrbitCamera,
    /// The lights and the ambient light.
    pub lights: Lights,
    /// Index into `lights` of the light that sliders and Ctrl-drag move
    /// ([`Self::selected_light`] keeps it in range).
    selected_light: usize,
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
            lights: scene.default_lights(),
            selected_light: 0,
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

    /// The GPU data the current picture needs: with the split view on and its halves differing
    /// in GPU data, the left half's options for the main upload and the right half's for a
    /// second one; else the current options alone.
    pub fn scene_uploads(&self) -> SceneUploads {
        let shown = self.split_frame().map_or(vec![self.shading], |s| vec![s.left, s.right]);
        let options = self.scene_options_drawing(&shown);
        // Frames without Gram-Schmidt for the pictures that show that mistake; the split
        // view's halves then differ in GPU data when only one shows it.
        let raw = |s: &ShadingSettings| s.mistake == Mistake::NoGramSchmidt;
        let with_frames = |options: SceneOptions, s: &ShadingSettings| SceneOptions {
            tangents_without_gram_schmidt: raw(s),
            ..options
        };
        let first = shown[0];
        let last = *shown.last().expect("one or two pictures");
        if self.split.enabled && self.split.difference.changes_gpu_data() {
            let [left, right] = self.split.scene_options(&options);
            SceneUploads { main: with_frames(left, &first), split_right: Some(with_frames(right, &last)) }
        } else if raw(&first) != raw(&last) {
            SceneUploads { main: with_frames(options.clone(), &first), split_right: Some(with_frames(options, &last)) }
        } else {
            SceneUploads { main: with_frames(options, &first), split_right: None }
        }
    }

    /// The scene options pictures with `shown` settings are drawn with: the height maps bound
    /// while any of them marches or embosses (with cone maps while one reads them), displacement at the parallax depth (so both
    /// draw the same relief); the split view aside.
    pub fn scene_options_drawing(&self, shown: &[ShadingSettings]) -> SceneOptions {
        let parallax =
            shown.iter().any(|s| s.parallax.technique != Parallax::Off || s.legacy.look == LegacyLook::Emboss);
        let cone_maps = shown.iter().any(|s| s.parallax.technique.reads_cones());
        let mut displacement = self.scene_options.displacement;
        displacement.depth_m = self.shading.parallax.depth_m;
        SceneOptions { parallax, cone_maps, displacement, ..self.scene_options.clone() }
    }

    /// The picture at pixel column `column` of a view `width` pixels wide: its parameters, the
    /// scene options it is drawn with and, in the split view, its half (0 left, 1 right; the
    /// renderer's divider column [`SplitFrame::divider_pixels`] is the right half's first).
    pub fn picture_at(&self, column: u32, width: u32) -> (FrameParams, SceneOptions, Option<usize>) {
        let params = self.frame_params();
        let uploads = self.scene_uploads();
        let Some(split) = self.split_frame() else { return (params, uploads.main, None) };
        if column < split.divider_pixels(width) {
            (FrameParams { shading: split.left, ..params }, uploads.main, Some(0))
        } else {
            let options = uploads.split_right.unwrap_or(uploads.main);
            (FrameParams { shading: split.right, ..params }, options, Some(1))
        }
    }

    /// What the renderer needs to draw the current picture.
    pub fn frame_params(&self) -> FrameParams {
        FrameParams { camera: self.camera, lights: self.lights, shading: self.shading }
    }

    /// Whether frames must keep coming without input.
    pub fn is_animating(&self) -> bool {
        self.light_orbit
    }

    /// The one place a command takes effect.
    pub fn apply(&mut self, command: Command) {
        if let Command::Lighting(command) = command {
            self.apply_lighting(command);
        } else if !self.split.apply(command) && !self.apply_motion(command) {
            self.apply_picture(command);
        }
    }

    /// The commands that change the picture itself (bump, views, methods, their settings).
    fn apply_picture(&mut self, command: Command) {
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
            Command::SetLightMarker(on) => self.shading.show_light_marker = on,
            Command::SetTangentMethod(method) => self.scene_options.tangent_method = method,
            Command::SetBumpSource(source) => self.scene_options.bump_source = source,
            Command::SetMipFilter(filter) => self.scene_options.mip_filter = filter,
            Command::SetKernel(kernel) => self.kernel = kernel,
            Command::SetDifferenceRange(degrees) if degrees.is_finite() => {
                self.shading.difference_range_deg = degrees.clamp(DIFFERENCE_RANGE.start, DIFFERENCE_RANGE.end)
            }
            Command::SetDifferenceRange(_) => {}
            Command::SetMaterialOverrides { material, overrides } => {
                self.scene_options.set_overrides(material, overrides)
            }
            Command::SetShadingOverride(model) => self.shading.shading_override = model,
            Command::SetDetailBlend(method) => self.shading.detail_blend = method,
            Command::SetShadingMode(mode) => self.shading.mode = mode,
            Command::SetWireframe(on) => self.shading.wireframe = on,
            Command::SetParallax(technique) => self.shading.parallax.technique = technique,
            Command::SetParallaxLayers([min, max]) => {
                let parallax = &mut self.shading.parallax;
                parallax.layers_min = min.clamp(1, MAX_PARALLAX_LAYERS);
                parallax.layers_max = max.clamp(1, MAX_PARALLAX_LAYERS);
            }
            Command::SetParallaxSteps(steps) => self.shading.parallax.steps = steps.min(MAX_PARALLAX_STEPS),
            Command::SetParallaxDepth(Some(d)) if !(d.is_finite() && d >= 0.0) => {}
            Command::SetParallaxDepth(depth) => self.shading.parallax.depth_m = depth,
            Command::SetParallaxShadows(s) if s.is_finite() => {
                self.shading.parallax.shadow_strength = s.clamp(0.0, MAX_PARALLAX_SHADOW_STRENGTH)
            }
            Command::SetParallaxShadows(_) => {}
            Command::SetDisplacement(level) => {
                self.scene_options.displacement.level = level.min(MAX_DISPLACEMENT_LEVEL);
                self.scene_options.displacement.gpu = None;
            }
            Command::SetGpuDisplacement(Some(pixels)) if !pixels.is_finite() => {}
            Command::SetGpuDisplacement(pixels) => {
                self.scene_options.displacement.gpu =
                    pixels.map(|p| p.clamp(*GPU_PIXELS_PER_EDGE.start(), *GPU_PIXELS_PER_EDGE.end()))
            }
            Command::ToggleWireframe => self.shading.wireframe = !self.shading.wireframe,
            Command::SetGlyphs(on) => self.shading.tbn_glyphs = on,
            Command::ToggleGlyphs => self.shading.tbn_glyphs = !self.shading.tbn_glyphs,
            Command::SetMistake(mistake) => self.shading.mistake = mistake,
            Command::SetLegacy(legacy) => {
                let size = legacy.cube_map_size.filter(|s| crate::frame::CUBE_MAP_SIZES.contains(s));
                self.shading.legacy = LegacySettings { cube_map_size: size, ..legacy };
            }
            // The lights, their motion and the camera's, and the split view: applied before.
            _ => {}
        }
    }
}

/// Decides whether a frame must be drawn: only when what it would show has changed — its
/// parameters, its size in pixels or its multisampling, so the full-quality frame after
/// interactive ones ([`interactive`]) is drawn once even though nothing else changed.
#[derive(Debug, Default)]
pub struct RedrawTracker {
    last: Option<(FrameParams, [u32; 2], Msaa)>,
}

impl RedrawTracker {
    /// True (and remembers the frame) when `params` drawn at `size` pixels with `msaa`
    /// differs from the last frame drawn.
    pub fn needs_redraw(&mut self, params: &FrameParams, size: [u32; 2], msaa: Msaa) -> bool {
        let frame = (*params, size, msaa);
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
    use crate::frame::{BumpSource, ShadingMode};
    use crate::names::Named;
    use crate::scene::builtin::teaching_scene;
    use crate::scene::{GreenAxis, MaterialOverrides, NormalLayout};
    use crate::tangent::TangentMethod;
    use glam::{Vec2, Vec3};

    #[test]
    fn unchanged_state_needs_no_redraw() {
        let scene = teaching_scene();
        let mut state = ViewerState::new(&scene);
        let mut tracker = RedrawTracker::default();
        assert!(tracker.needs_redraw(&state.frame_params(), [64, 64], Msaa::X4));
        assert!(!tracker.needs_redraw(&state.frame_params(), [64, 64], Msaa::X4));
        state.apply(Command::Tick(0.5)); // no animation running: nothing changes
        assert!(!tracker.needs_redraw(&state.frame_params(), [64, 64], Msaa::X4));
        state.apply(Command::ToggleBump);
        assert!(tracker.needs_redraw(&state.frame_params(), [64, 64], Msaa::X4));
        assert!(tracker.needs_redraw(&state.frame_params(), [65, 64], Msaa::X4));
    }

    /// Interactive frames at one sample and a smaller size, then the same picture at full
    /// quality once input stops: drawn once, then nothing until something changes.
    #[test]
    fn the_full_quality_frame_after_interactive_ones_is_drawn_once() {
        let scene = teaching_scene();
        let mut state = ViewerState::new(&scene);
        let mut tracker = RedrawTracker::default();
        state.apply(Command::OrbitCamera { d_yaw: 0.1, d_pitch: 0.0 });
        assert!(tracker.needs_redraw(&state.frame_params(), [32, 32], Msaa::Off));
        assert!(!tracker.needs_redraw(&state.frame_params(), [32, 32], Msaa::Off), "held still while dragging");
        assert!(tracker.needs_redraw(&state.frame_params(), [64, 64], Msaa::X4), "input stopped");
        assert!(!tracker.needs_redraw(&state.frame_params(), [64, 64], Msaa::X4));
    }

    #[test]
    fn orbiting_light_keeps_its_distance_from_the_axis() {
        let scene = teaching_scene();
        let mut state = ViewerState::new(&scene);
        state.apply(Command::SetLightOrbit(true));
        let before = state.lights[0].position;
        state.apply(Command::Tick(1.0));
        let after = state.lights[0].position;
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
        assert!(tracker.needs_redraw(&state.frame_params(), [64, 64], Msaa::X4));
        state.apply(Command::SetShadingMode(ShadingMode::BumpOnly));
        assert!(tracker.needs_redraw(&state.frame_params(), [64, 64], Msaa::X4));
        state.apply(Command::SetShadingMode(ShadingMode::BumpOnly));
        assert!(!tracker.needs_redraw(&state.frame_params(), [64, 64], Msaa::X4));
        state.apply(Command::ToggleWireframe);
        assert!(state.shading.wireframe);
        assert!(tracker.needs_redraw(&state.frame_params(), [64, 64], Msaa::X4));
        state.apply(Command::SetWireframe(false));
        assert!(!state.shading.wireframe);
        state.apply(Command::SetParallax(Parallax::Relief));
        assert!(tracker.needs_redraw(&state.frame_params(), [64, 64], Msaa::X4));
        state.apply(Command::SetParallaxLayers([0, 1000]));
        state.apply(Command::SetParallaxSteps(99));
        state.apply(Command::SetParallaxDepth(Some(-1.0)));
        let parallax = state.shading.parallax;
        assert_eq!((parallax.layers_min, parallax.layers_max, parallax.steps, parallax.depth_m), (1, 256, 16, None));
        assert_eq!(state.scene_options, SceneOptions::default(), "no GPU data to re-make");
    }

    #[test]
    fn only_gpu_data_differences_ask_for_a_second_upload_and_only_while_split_is_on() {
        let scene = teaching_scene();
        let mut state = ViewerState::new(&scene);
        let single = SceneUploads { main: SceneOptions::default(), split_right: None };
        state.apply(Command::SetSplitDifference(SplitDifference::Tangents));
        assert_eq!(state.scene_uploads(), single, "split off");
        state.apply(Command::SetSplit(true));
        for &difference in SplitDifference::all() {
            state.apply(Command::SetSplitDifference(difference));
            let uploads = state.scene_uploads();
            assert_eq!(uploads.split_right.is_some(), difference.changes_gpu_data(), "{difference:?}");
            if !difference.changes_gpu_data() {
                // A parallax split marches in both halves: one upload, with the height maps.
                let parallax = difference == SplitDifference::Parallax;
                let expected =
                    SceneUploads { main: SceneOptions { parallax, ..Default::default() }, split_right: None };
                assert_eq!(uploads, expected, "{difference:?}");
            }
        }
        state.apply(Command::SetSplitDifference(SplitDifference::Tangents));
        let uploads = state.scene_uploads();
        assert_eq!(uploads.main.tangent_method, Some(TangentMethod::PerFace));
        assert_eq!(uploads.split_right.unwrap().tangent_method, Some(TangentMethod::MikkTSpace));
    }

    #[test]
    fn a_split_convention_wins_over_per_material_green_and_keeps_other_overrides() {
        let scene = teaching_scene();
        let mut state = ViewerState::new(&scene);
        let own =
            MaterialOverrides { green: Some(GreenAxis::OpenGl), layout: Some(NormalLayout::Rg), ..Default::default() };
        state.apply(Command::SetMaterialOverrides { material: Some(0), overrides: own });
        state.apply(Command::SetMaterialOverrides {
            material: Some(1),
            overrides: MaterialOverrides { green: Some(GreenAxis::OpenGl), ..Default::default() },
        });
        state.apply(Command::SetSplit(true));
        state.apply(Command::SetSplitDifference(SplitDifference::Convention));
        let [left, right] = state.split.scene_options(&state.scene_options);
        for (options, green) in [(left, GreenAxis::OpenGl), (right, GreenAxis::DirectX)] {
            assert_eq!(options.overrides_in_use(0).green, Some(green));
            assert_eq!(options.overrides_in_use(0).layout, Some(NormalLayout::Rg));
            assert_eq!(options.overrides_in_use(1).green, Some(green));
            assert!(!options.per_material.contains_key(&1), "an emptied record is dropped");
        }
    }

    #[test]
    fn the_picture_at_a_column_is_that_of_its_split_half() {
        let scene = teaching_scene();
        let mut state = ViewerState::new(&scene);
        assert_eq!(state.picture_at(90, 100), (state.frame_params(), SceneOptions::default(), None));
        state.apply(Command::SetSplit(true));
        state.apply(Command::SetSplitDivider(0.255));
        // The renderer's divider column: round(0.255 · 100) = 26 is the right half's first.
        let (left, _, half) = state.picture_at(25, 100);
        assert_eq!((left.shading.bump_enabled, half), (false, Some(0)));
        let (right, _, half) = state.picture_at(26, 100);
        assert_eq!((right.shading.bump_enabled, half), (true, Some(1)));
        state.apply(Command::SetSplitDifference(SplitDifference::BumpSource));
        assert_eq!(state.picture_at(25, 100).1.bump_source, BumpSource::NormalMap);
        assert_eq!(state.picture_at(26, 100).1.bump_source, BumpSource::HeightInShader);
    }

    /// A mistake is a pipeline variant (one upload), except no Gram-Schmidt, whose frames are
    /// GPU data: a split against it uploads the right half's frames without Gram-Schmidt.
    #[test]
    fn split_mistakes_share_an_upload_unless_frames_differ() {
        let scene = teaching_scene();
        let mut state = ViewerState::new(&scene);
        state.apply(Command::SetSplit(true));
        state.apply(Command::SetSplitDifference(SplitDifference::Mistake));
        let [left, right] = state.split_frame().map(|s| [s.left.mistake, s.right.mistake]).unwrap();
        assert_eq!([left, right], [Mistake::None, Mistake::TbnTypo]);
        assert_eq!(state.scene_uploads().split_right, None);
        state.apply(Command::SetSplitMistakes([Mistake::None, Mistake::NoGramSchmidt]));
        let uploads = state.scene_uploads();
        assert!(!uploads.main.tangents_without_gram_schmidt);
        assert!(uploads.split_right.is_some_and(|o| o.tangents_without_gram_schmidt));
        state.apply(Command::SetSplit(false));
        state.apply(Command::SetMistake(Mistake::NoGramSchmidt));
        let uploads = state.scene_uploads();
        assert!(uploads.main.tangents_without_gram_schmidt && uploads.split_right.is_none());
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
