//! Presets in the viewer: the whole state, the scene's files and the screenshot settings saved
//! as TOML, loaded back (state at once, files in the background), and kept between runs as
//! `last.toml`.

use std::path::Path;

use bumpview::state::preset::Preset;

use super::{Controller, ScreenshotForm};
use crate::app::files::Job;

/// The preset path field and the outcome of the last save or load.
#[derive(Default)]
pub struct PresetForm {
    /// The file "Save preset" and "Load preset" use.
    pub path_text: String,
    /// What the last save or load did, or why it failed.
    pub message: Option<Result<String, String>>,
}

/// Where the viewer keeps its state between runs: `last.toml`, a preset, next to the recent
/// list ([`crate::app::files::recent_file`]).
#[cfg(not(target_arch = "wasm32"))]
pub fn last_state_file() -> Option<std::path::PathBuf> {
    crate::app::files::recent_file().map(|recent| recent.with_file_name("last.toml"))
}

impl Controller {
    /// The whole state, the scene's files and the screenshot settings as a preset.
    pub fn current_preset(&self) -> Preset {
        let files = self.files.scene_files.clone();
        Preset { capture: self.screenshot.capture(), ..Preset::from_state(&self.state, files) }
    }

    /// Writes [`Self::current_preset`] to `path` atomically; says where, or why not.
    #[cfg(not(target_arch = "wasm32"))]
    pub(super) fn save_preset(&self, path: &Path) -> Result<String, String> {
        self.current_preset().save(path).map_err(|e| e.to_string())?;
        Ok(format!("saved {}", path.display()))
    }

    /// Offers [`Self::current_preset`] as a download named as `path`'s file; says which, or why
    /// not. (It can be loaded again by dropping it on the page.)
    #[cfg(target_arch = "wasm32")]
    pub(super) fn save_preset(&self, path: &Path) -> Result<String, String> {
        let name = path.file_name().map_or("bumpview.toml".into(), |n| n.to_string_lossy().into_owned());
        crate::app::browser::download(&name, "application/toml", self.current_preset().to_toml().as_bytes())?;
        Ok(format!("downloaded {name}"))
    }

    /// Loads a preset file and shows it ([`Self::show_preset`]). A preset that does not load
    /// leaves the state as it was.
    pub(super) fn load_preset(&mut self, path: &Path) -> Result<String, String> {
        let preset = Preset::load(path).map_err(|e| e.to_string())?;
        self.show_preset(&preset, format!("opened the files of {}", path.display()))?;
        Ok(format!("loaded {}", path.display()))
    }

    /// Shows a preset's state at once and loads its files in the background when they differ
    /// from the scene's (a reload: the preset's camera and light stay; `done` is the files'
    /// status then). A preset whose state does not fit the scene leaves the state as it was.
    pub(super) fn show_preset(&mut self, preset: &Preset, done: String) -> Result<(), String> {
        let mut state = preset.to_state(&self.scene).map_err(|e| e.to_string())?;
        state.default_camera = self.state.default_camera;
        let wanted = preset.files.absolute();
        let kernel = state.kernel;
        self.state = state;
        self.screenshot = ScreenshotForm::new(&preset.capture);
        self.revision += 1;
        if (&wanted, kernel) != (&self.files.scene_files, self.files.kernel) {
            self.load(Some(Job::reload(wanted, kernel, done)));
        }
        Ok(())
    }

    /// Saves the state for the next start ([`last_state_file`]), if it is kept; a failure is
    /// reported on stderr (the window is closing).
    pub fn save_last_state(&self) {
        let Some(path) = &self.last_state else { return };
        let folder = path.parent().map_or(Ok(()), std::fs::create_dir_all).map_err(|e| e.to_string());
        if let Err(e) = folder.and_then(|()| self.current_preset().save(path).map_err(|e| e.to_string())) {
            eprintln!("bumpview: last state not saved: {e}");
        }
    }
}
