//! What the viewer and `render` start from: a preset (or the defaults) with the command line's
//! files and method flags over it, its scene loaded and its state made.

use bumpview::error::PresetSceneError;
use bumpview::load::SceneFiles;
use bumpview::names::Named;
use bumpview::scene::Scene;
use bumpview::state::ViewerState;
use bumpview::state::preset::{CapturePreset, Preset};

use super::methods::MethodArgs;

/// A scene and the state to show it in, and where they came from.
pub struct Started {
    /// The files the scene was made from: the command line's over the preset's.
    pub files: SceneFiles,
    /// The preset's screenshot settings.
    pub capture: CapturePreset,
    pub scene: Scene,
    pub state: ViewerState,
}

/// `preset` with `files` over its files slot by slot and the method flags applied as the
/// viewer's commands (`--kernel` also makes the built-in scene). The error names the file or
/// key and the problem.
pub fn start(preset: Preset, files: SceneFiles, methods: &MethodArgs) -> Result<Started, PresetSceneError> {
    let mut preset = preset;
    preset.files = files.over(preset.files);
    if let Some(kernel) = methods.kernel {
        kernel.name().clone_into(&mut preset.scene.kernel);
    }
    let scene = preset.build_scene()?;
    let mut state = preset.to_state(&scene)?;
    for command in methods.commands(&state) {
        state.apply(command);
    }
    Ok(Started { files: preset.files, capture: preset.capture, scene, state })
}
