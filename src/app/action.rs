//! What the user asked for or what arrived from another thread: a viewer [`Command`] or an
//! action only the app knows. The panel, the keys, the mouse, dropped files, the file dialog
//! and hot reload all produce these (a finished scene job is the controller's own); the controller
//! ([`super::controller::Controller::apply`]) is the one place they take effect.

use std::path::PathBuf;

use bumpview::lessons::files::LessonWords;
use bumpview::load::TextureSlot;
use bumpview::state::Command;

#[derive(Debug, Clone, PartialEq)]
pub enum Action {
    /// A change to the viewer state.
    Viewer(Command),
    /// Save a PNG of the 3D view (F12 or the panel button).
    Screenshot,
    /// Save a PNG of the tile export (the form's spec, else flat │ bumped │ Tangent view),
    /// captions as the form says.
    ExportTiles,
    /// Write the whole state as a preset file.
    SavePreset(PathBuf),
    /// Read a preset file and show its files and state.
    LoadPreset(PathBuf),
    /// Open files (dropped, chosen in the dialog or the recent list): a mesh replaces the
    /// scene; images go into `slot` (dropped on it or chosen for it) or the one their name
    /// suggests.
    Open { paths: Vec<PathBuf>, slot: Option<TextureSlot> },
    /// Show the file dialog for a mesh or texture (`None`) or for one slot's texture.
    ShowDialog(Option<TextureSlot>),
    /// The file dialog closed with a file, or without one (`None`).
    DialogClosed { slot: Option<TextureSlot>, path: Option<PathBuf> },
    /// Files of the scene changed on disk and have settled: re-make it, keeping the view.
    Reload,
    /// Pin the pixel probe at `pixel` of a view `size` pixels (P + click, `--probe`).
    PinProbe { pixel: [u32; 2], size: [u32; 2] },
    /// Remove the pixel probe.
    ClearProbe,
    /// Draw cheaper frames while the user drags or the light orbits (one sample per pixel,
    /// fewer pixels when still slow), or always full quality.
    SetInteractiveFrames(bool),
    /// Show lesson `index` of the catalogue: its whole state and its caption card.
    OpenLesson(usize),
    /// Show the lesson this many after the current one (before it when negative; Page Down
    /// and Page Up, what presenter remotes send), the first when none is shown.
    StepLesson(i32),
    /// Show or hide the current lesson's caption card.
    ShowLessonCard(bool),
    /// Write the current state's split view as a lesson file at `path` with these words, and
    /// show it as a lesson.
    SaveLesson { path: PathBuf, words: LessonWords },
    /// Hide or show the control panel (H), so the 3D view and the card fill the window.
    TogglePanel,
    /// Make the window full-screen or windowed again (F11).
    ToggleFullscreen,
}

impl From<Command> for Action {
    fn from(command: Command) -> Self {
        Action::Viewer(command)
    }
}
