//! Presets: the whole viewer state (files, camera, lights, shading, scene options, kernel) and
//! the capture settings as a small TOML file, for `bumpview render --preset` and the viewer.
//!
//! Enums are stored by the names the command line uses (`view = "shading-normal"`), angles in
//! degrees. Reading is strict about what is there and lenient about what is not:
//!
//! - an **unknown** key or section, a value of the wrong type or an unknown name is an error
//!   naming the key (and, for parse errors, the line);
//! - a **missing** key takes its default: the scene's own camera, light and ambient light, the viewer's
//!   start settings ([`crate::frame::ShadingSettings::default`],
//!   [`crate::frame::SceneOptions::default`], the default
//!   kernel), no files (the built-in scene), and a capture at the caller's size;
//! - `allow_outside_files = true` in `[files]` lets the mesh read files outside its folder, as
//!   `--allow-outside-files` does ([`SceneFiles::allow_outside_files`]); it is written only
//!   when set.
//!
//! Numbers survive a round trip exactly: `f32` values are written as the shortest decimal that
//! reads back to the same bits, and angles go through `f64` degrees, so a saved state renders
//! the same pixels again.

use std::path::Path;

use glam::Vec3;
use serde::{Deserialize, Serialize};

use crate::frame::ShadingSettings;
use crate::height::Kernel;
use crate::load::SceneFiles;
use crate::names::{Named, parse_or_auto};
use crate::scene::{Light, Scene};
use crate::state::ViewerState;

mod checked;
mod sections;
mod split_section;

pub use sections::*;
pub use split_section::SplitPreset;

/// The preset format this code writes and reads.
pub const FORMAT_VERSION: u32 = 1;

pub use crate::error::{PresetError, PresetSceneError};

/// The whole preset file.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Preset {
    /// [`FORMAT_VERSION`]; missing means the current one.
    pub version: Option<u32>,
    /// Relative paths are relative to the preset file's folder.
    pub files: SceneFiles,
    pub camera: CameraPreset,
    pub light: LightPreset,
    /// Every light, in order; missing: the scene's default light alone.
    pub lights: Vec<LightEntryPreset>,
    pub ambient: AmbientPreset,
    pub shading: ShadingPreset,
    pub scene: ScenePreset,
    pub capture: CapturePreset,
    pub split: SplitPreset,
}

/// A lesson file seen as a preset: its `[preset]` tables (no key of a preset is called
/// `preset`, so a file with that table is a lesson's). Its other keys are not read here.
#[derive(Deserialize)]
struct LessonPresetPart {
    preset: Preset,
}

impl Preset {
    /// The preset of `state` showing `files`; no capture settings.
    pub fn from_state(state: &ViewerState, files: SceneFiles) -> Preset {
        let camera = state.camera;
        Preset {
            version: Some(FORMAT_VERSION),
            files,
            camera: CameraPreset {
                target: Some(camera.target.to_array()),
                yaw_deg: Some(degrees(camera.yaw)),
                pitch_deg: Some(degrees(camera.pitch)),
                distance: Some(camera.distance),
                fov_y_deg: Some(degrees(camera.fov_y)),
            },
            light: LightPreset {
                position: None,
                color: None,
                orbit: state.light_orbit,
                marker: state.shading.show_light_marker,
            },
            lights: state.lights.as_slice().iter().map(LightEntryPreset::from).collect(),
            ambient: AmbientPreset {
                color: Some(state.lights.ambient_color.to_array()),
                strength: state.lights.ambient_strength,
            },
            shading: ShadingPreset::from(&state.shading),
            scene: ScenePreset::new(&state.scene_options, state.kernel),
            capture: CapturePreset::default(),
            split: SplitPreset::from(&state.split),
        }
    }

    /// The viewer state on `scene` (which gives the defaults of camera and light).
    pub fn to_state(&self, scene: &Scene) -> Result<ViewerState, PresetError> {
        let settings = self.settings()?;
        let mut state = ViewerState::new(scene);
        let c = &self.camera;
        let radians = |deg: Option<f64>, default: f32| deg.map_or(default, |d| d.to_radians() as f32);
        state.camera.target = c.target.map_or(state.camera.target, Vec3::from_array);
        state.camera.yaw = radians(c.yaw_deg, state.camera.yaw);
        state.camera.pitch = radians(c.pitch_deg, state.camera.pitch);
        state.camera.distance = c.distance.unwrap_or(state.camera.distance);
        state.camera.fov_y = radians(c.fov_y_deg, state.camera.fov_y);
        let default_position = state.lights[0].position;
        let lights: Vec<Light> =
            self.lights.iter().enumerate().map(|(i, l)| l.to_light(i, default_position)).collect::<Result<_, _>>()?;
        if !lights.is_empty() {
            state.lights = state.lights.with_lights(&lights).map_err(|e| PresetError(format!("lights: {e}")))?;
        }
        state.lights[0].position = self.light.position.map_or(state.lights[0].position, Vec3::from_array);
        state.lights[0].color = self.light.color.map_or(state.lights[0].color, Vec3::from_array);
        state.lights.ambient_color = self.ambient.color.map_or(state.lights.ambient_color, Vec3::from_array);
        state.lights.ambient_strength = settings.ambient_strength;
        state.shading = settings.shading;
        state.light_orbit = settings.light_orbit;
        state.scene_options = settings.scene_options;
        state.kernel = settings.kernel;
        state.split = settings.split;
        Ok(state)
    }

    /// The brick-map kernel the scene is made with.
    pub fn kernel(&self) -> Result<Kernel, PresetError> {
        named("scene.kernel", &self.scene.kernel)
    }

    /// Loads the preset's files ([`SceneFiles::build`]; the built-in scene made with the
    /// preset's kernel when there is no mesh).
    pub fn build_scene(&self) -> Result<Scene, PresetSceneError> {
        Ok(self.files.build(self.kernel()?)?)
    }

    /// The shading a picture of this preset is drawn with, checked, without a scene: the whole
    /// picture's (`half` `None`, as with the split view off) or a split half's.
    pub fn shading_of(&self, half: Option<usize>) -> Result<ShadingSettings, PresetError> {
        let settings = self.settings()?;
        Ok(match half {
            None => settings.shading,
            Some(i) => settings.split.shading(&settings.shading)[i.min(1)],
        })
    }

    /// The preset as TOML, with a comment line on top.
    pub fn to_toml(&self) -> String {
        let body = toml::to_string(self).expect("a preset is always representable in TOML");
        format!("# bumpview preset (bumpview render --preset FILE)\n{body}")
    }

    /// Parses and checks a preset (every name and range; see the module doc for missing keys).
    /// A lesson file (`crate::lessons`: its preset under a `[preset]` table, beside its title,
    /// caption, claim and comparison) reads as the preset it holds; the lesson's own keys are
    /// left to the lessons module to check. Errors name the key and, for what TOML rejects, the
    /// line of `text`.
    pub fn from_toml(text: &str) -> Result<Preset, PresetError> {
        let error = |e: toml::de::Error| PresetError(one_line(&e.to_string()));
        let table: toml::Table = toml::from_str(text).map_err(error)?;
        let preset = if table.get("preset").is_some_and(toml::Value::is_table) {
            toml::from_str::<LessonPresetPart>(text).map_err(error)?.preset
        } else {
            toml::from_str::<Preset>(text).map_err(error)?
        };
        preset.settings()?;
        Ok(preset)
    }

    /// Reads a preset file; relative file paths in it become relative to its folder.
    pub fn load(path: &Path) -> Result<Preset, PresetError> {
        let in_file = |message: String| PresetError(format!("{}: {message}", path.display()));
        let bytes = crate::read::read_file(path, crate::read::FileKind::Preset).map_err(|e| in_file(e.to_string()))?;
        let text = String::from_utf8(bytes).map_err(|_| in_file("not UTF-8 text".into()))?;
        let mut preset = Preset::from_toml(&text).map_err(|e| in_file(e.0))?;
        let folder = path.parent().unwrap_or(Path::new(""));
        preset.files = preset.files.resolved(folder);
        Ok(preset)
    }

    /// Writes the preset atomically ([`crate::atomic::write_atomically`]), its files relative
    /// to its folder or absolute ([`SceneFiles::relative_to`]), so it loads from any working
    /// directory.
    pub fn save(&self, path: &Path) -> Result<(), PresetError> {
        let files = self.files.relative_to(path.parent().unwrap_or(Path::new("")));
        let stored = Preset { files, ..self.clone() };
        crate::atomic::write_bytes_atomically(path, stored.to_toml().as_bytes())
            .map_err(|e| PresetError(format!("could not write {}: {e}", path.display())))
    }
}

/// The names of a left and a right value.
fn names<T: Named>(pair: [T; 2]) -> [String; 2] {
    pair.map(|value| value.name().to_owned())
}

/// The value named `text` ([`Named`]), else an error for `key` listing the names.
fn named<T: Named>(key: &str, text: &str) -> Result<T, PresetError> {
    T::parse_name(text).map_err(|e| bad(key, text, &format!("one of {}", e.expected.join(", "))))
}

/// `auto` (`None`) or the value named `text`, else an error for `key` listing the names.
fn named_or_auto<T: Named>(key: &str, text: &str) -> Result<Option<T>, PresetError> {
    parse_or_auto(text).map_err(|e| bad(key, text, &format!("one of {}", e.expected.join(", "))))
}

/// [`named`] for a left and a right value.
fn named_pair<T: Named>(key: &str, pair: &[String; 2]) -> Result<[T; 2], PresetError> {
    Ok([named(key, &pair[0])?, named(key, &pair[1])?])
}

/// A GPU displacement's pixels per edge, checked: `None` stays `None`.
fn gpu_pixels(key: &str, pixels: Option<f32>) -> Result<Option<f32>, PresetError> {
    let range = crate::frame::GPU_PIXELS_PER_EDGE;
    match pixels {
        Some(p) if !range.contains(&p) => {
            Err(bad(key, &p.to_string(), &format!("pixels per edge, {} to {}", range.start(), range.end())))
        }
        pixels => Ok(pixels),
    }
}

/// "`key` = "value": expected …".
fn bad(key: &str, value: &str, expected: &str) -> PresetError {
    PresetError(format!("{key} = {value:?}: expected {expected}"))
}

/// toml's multi-line message (location, source line, caret, reason) as "location: reason".
pub fn one_line(message: &str) -> String {
    let quoted_source =
        |line: &str| line.starts_with('|') || line.split_once(" |").is_some_and(|(n, _)| n.parse::<u32>().is_ok());
    let lines: Vec<&str> = message.lines().map(str::trim).filter(|l| !l.is_empty() && !quoted_source(l)).collect();
    lines.join(": ")
}

/// Degrees of an angle of `radians`: the shortest decimal that converts back to exactly the
/// same `f32` radians (`20` rather than `19.99999941818584` where that is exact).
fn degrees(radians: f32) -> f64 {
    let exact = f64::from(radians).to_degrees();
    let short = f64::from(radians.to_degrees());
    if short.to_radians() as f32 == radians { short } else { exact }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frame::LightingSpace;
    use crate::frame::{BumpSource, ShadingMode, ViewMode};
    use crate::frame::{LegacyLook, LegacySettings, Mistake};
    use crate::height::Border;
    use crate::scene::builtin::teaching_scene;
    use crate::scene::{GreenAxis, MaterialOverrides, NormalLayout, ShadingModel, SpecularMode};
    use crate::state::{Command, LightCommand};
    use crate::tangent::TangentMethod;

    #[test]
    fn a_changed_state_round_trips_exactly() {
        let scene = teaching_scene();
        let mut state = ViewerState::new(&scene);
        state.apply(Command::OrbitCamera { d_yaw: 0.3712, d_pitch: -0.1234 });
        state.apply(Command::Zoom(1.137));
        state.apply(Command::SetLightPosition(Vec3::new(-1.1, 2.3, 0.7)));
        state.apply(Command::SetStrength(2.37));
        state.apply(Command::SetView(ViewMode::ShadingNormal));
        state.apply(Command::SetLightMarker(false));
        state.apply(Command::SetTangentMethod(Some(TangentMethod::PerFace)));
        state.apply(Command::SetKernel(Kernel::Sobel5));
        let overrides = MaterialOverrides {
            green: Some(GreenAxis::DirectX),
            height_range_m: Some(0.0123),
            layout: Some(NormalLayout::Ag),
            ..Default::default()
        };
        state.apply(Command::SetMaterialOverrides { material: None, overrides });
        let own =
            MaterialOverrides { border: Some(Border::Clamp), layout: Some(NormalLayout::Xray), ..Default::default() };
        state.apply(Command::SetMaterialOverrides { material: Some(1), overrides: own });
        state.apply(Command::SetShadingOverride(Some(ShadingModel::MetallicRoughness)));
        state.apply(Command::SetShadingMode(ShadingMode::BumpOnly));
        state.apply(Command::ToggleWireframe);
        state.apply(Command::ToggleGlyphs);
        state.apply(Command::SetSplit(true));
        state.apply(Command::SetSplitDifference(crate::state::SplitDifference::Strength));
        state.apply(Command::SetSplitDivider(0.3137));
        state.apply(Command::SetSplitStrengths([0.37, 2.91]));
        state.apply(Command::SetSplitViews([ViewMode::Tangent, ViewMode::Handedness]));
        state.apply(Command::SetSplitModes([ShadingMode::BumpOnly, ShadingMode::ColourOnly]));
        state.apply(Command::SetSplitTangentMethods([TangentMethod::Analytic, TangentMethod::PerFace]));
        state.apply(Command::SetSplitConventions([GreenAxis::DirectX, GreenAxis::OpenGl]));
        state.apply(Command::SetSplitBumpSources([BumpSource::HeightInShader, BumpSource::NormalMap]));
        state.apply(Command::SetSplitMistakes([Mistake::GreenFlipped, Mistake::LightPerVertex]));
        state.apply(Command::SetMistake(Mistake::SrgbNormalMap));
        state.apply(Command::SetLegacy(LegacySettings { look: LegacyLook::Dot3, cube_map_size: Some(16) }));
        let mut sun = crate::scene::Light::directional(Vec3::new(0.3, 1.7, -0.2), Vec3::new(1.0, 0.9, 0.71));
        sun.intensity = 1.37;
        let mut lamp = crate::scene::Light::point(Vec3::new(0.1, 0.2, 0.3), Vec3::new(0.2, 0.3, 1.0));
        lamp.attenuation = crate::scene::Attenuation { constant: 0.5, linear: 0.25, quadratic: 0.125 };
        lamp.enabled = false;
        for (index, light) in [(1, sun), (2, lamp)] {
            state.apply(Command::Lighting(LightCommand::Set { index, light }));
        }
        state.apply(Command::Lighting(LightCommand::SetAmbient { color: Vec3::new(0.1, 0.2, 0.3), strength: 0.77 }));
        state.apply(Command::Lighting(LightCommand::SetSpecular(SpecularMode::Phong)));
        state.apply(Command::Lighting(LightCommand::SetShininess(Some(71.5))));
        state.apply(Command::Lighting(LightCommand::SetLightingSpace(LightingSpace::Tangent)));
        let files = SceneFiles { height: Some("/x/h.png".into()), ..Default::default() };
        let text = Preset::from_state(&state, files.clone()).to_toml();
        let back = Preset::from_toml(&text).unwrap();
        assert_eq!(back.files, files);
        assert_eq!(back.to_state(&scene).unwrap(), state, "{text}");
        assert_eq!(back.to_state(&scene).unwrap().lights.len(), 3);
    }

    /// Presets written before several lights (one `[light]` position and colour) still load,
    /// into the first light; bad light entries are errors naming them.
    #[test]
    fn old_single_light_presets_load_and_bad_lights_are_named() {
        let scene = teaching_scene();
        let old = "[light]\nposition = [1.0, 2.0, 3.0]\ncolor = [0.5, 0.25, 1.0]\nmarker = false\n";
        let state = Preset::from_toml(old).unwrap().to_state(&scene).unwrap();
        assert_eq!(state.lights.len(), 1);
        assert_eq!(state.lights[0].position, Vec3::new(1.0, 2.0, 3.0));
        assert_eq!(state.lights[0].color, Vec3::new(0.5, 0.25, 1.0));
        assert!(!state.shading.show_light_marker);
        let bad = "[[lights]]\nkind = \"spot\"\n";
        assert!(Preset::from_toml(bad).unwrap_err().0.starts_with("lights[0].kind"));
        let bad = "[[lights]]\n[[lights]]\nattenuation = [0.0, 0.0, 0.0]\n";
        assert!(Preset::from_toml(bad).unwrap_err().0.starts_with("lights[1].attenuation"));
        let nine = "[[lights]]\n".repeat(9);
        assert!(Preset::from_toml(&nine).unwrap_err().0.starts_with("lights"));
        assert!(Preset::from_toml("[shading]\nshininess = 0.5\n").is_err());
        assert!(Preset::from_toml("[ambient]\nstrength = -1.0\n").is_err());
    }

    /// Older presets' `two_channel = true` reads as the RG layout; a bad layout names its key.
    #[test]
    fn two_channel_reads_as_the_rg_layout() {
        let scene = teaching_scene();
        let state = Preset::from_toml("[scene.materials]\ntwo_channel = true\n").unwrap().to_state(&scene).unwrap();
        assert_eq!(state.scene_options.materials.layout, Some(NormalLayout::Rg));
        let bad = Preset::from_toml("[scene.materials]\nnormal_layout = \"bc7\"\n").and_then(|p| p.to_state(&scene));
        assert!(bad.unwrap_err().to_string().contains("scene.materials.normal_layout"));
    }

    #[test]
    fn missing_keys_take_defaults_and_unknown_ones_are_errors() {
        let scene = teaching_scene();
        let empty = Preset::from_toml("").unwrap();
        assert_eq!(empty.to_state(&scene).unwrap(), ViewerState::new(&scene));
        let partial = Preset::from_toml("[shading]\nstrength = 2.5\n[camera]\ndistance = 3.0\n").unwrap();
        let state = partial.to_state(&scene).unwrap();
        assert_eq!((state.shading.strength, state.camera.distance), (2.5, 3.0));
        assert_eq!(state.camera.yaw, scene.default_camera.yaw);
        let unknown = Preset::from_toml("[shading]\nstrenght = 2.5\n").unwrap_err().0;
        assert!(unknown.contains("strenght") && unknown.contains("line 2"), "{unknown}");
        let name = Preset::from_toml("[shading]\nview = \"shiny\"\n").unwrap_err().0;
        assert!(name.starts_with("shading.view = \"shiny\": expected one of lit,"), "{name}");
        let kind = Preset::from_toml("[light]\norbit = 1\n").unwrap_err().0;
        assert!(kind.contains("orbit") || kind.contains("line 2"), "{kind}");
        assert!(Preset::from_toml("[capture]\nsupersample = 5\n").is_err());
        assert!(Preset::from_toml("version = 2\n").unwrap_err().0.starts_with("version"));
    }

    #[test]
    fn a_lesson_file_reads_as_its_preset() {
        let lesson = "title = \"t\"\ncaption = \"c\"\nclaim = \"{changed}\"\n\
                      [preset.shading]\nstrength = 2.5\n[[tiles]]\nlabel = \"a\"\n";
        assert_eq!(Preset::from_toml(lesson).unwrap().shading.strength, 2.5);
        let typo = "title = \"t\"\n\n[preset.shading]\nstrenght = 2.5\n";
        let message = Preset::from_toml(typo).unwrap_err().0;
        assert!(message.contains("line 4") && message.contains("strenght"), "{message}");
    }
}
