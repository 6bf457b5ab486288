//! The viewer without a window: the state, the scene, the renderer (eframe's device in the
//! window, a headless one in tests) and the scene's files. [`Controller::apply`] is the one
//! place [`Action`]s take effect: commands on the state, files opened and reloaded, scenes
//! changed ([`scene_change`]: one background job per change, [`scene_job`]), exports
//! ([`exports`]) and presets ([`presets`]). The UI thread only uploads what a job made ready.

mod exports;
mod facts;
mod follow_frame;
mod lesson_grid;
mod lessons;
mod presets;
mod scene_change;
mod scene_job;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod tests_jobs;
#[cfg(test)]
mod tests_lessons;
#[cfg(test)]
mod ui_frames;

use std::num::NonZeroU32;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Duration;

use web_time::Instant;

use bumpview::error::RenderError;
use bumpview::frame::{FrameQuality, Msaa, SceneUploads};
use bumpview::lessons::Lesson;
use bumpview::load::SceneFiles;
use bumpview::render::timing::{time_floor, timed};
use bumpview::render::{DrawOptions, RenderTarget, Renderer};
use bumpview::scene::Scene;
use bumpview::state::interactive::InteractiveQuality;
use bumpview::state::preset::CapturePreset;
use bumpview::state::{Command, ViewerState};
pub use exports::ScreenshotForm;
pub use facts::SceneFacts;
pub use lesson_grid::Tiles;
pub use lessons::{LessonsForm, Measurement};
pub use presets::PresetForm;
#[cfg(not(target_arch = "wasm32"))]
pub use presets::last_state_file;
pub use scene_job::JobTimes;
use scene_job::SceneJobs;

use super::action::Action;
use super::dialog::Dialog;
use super::files::{self, Files, Job, Status};
use super::probe::Probe;
use super::watch::Watcher;

/// Called from worker threads (scene jobs, dialog, file watcher) to make the UI run a frame
/// and pick up what they delivered; a no-op without a window.
pub type Waker = Arc<dyn Fn() + Send + Sync>;

/// What the controller starts with.
pub struct Start {
    pub scene: Scene,
    pub state: ViewerState,
    /// The files `scene` was made from (made absolute here), watched for changes.
    pub files: SceneFiles,
    /// Screenshot size, background and supersampling.
    pub capture: CapturePreset,
    /// Where the state is saved on exit ([`last_state_file`]); `None`: not saved.
    pub last_state: Option<PathBuf>,
    /// Where the recent-files list is kept ([`files::recent_file`]); `None`: not kept.
    pub recent_file: Option<PathBuf>,
    /// Shown as the files' status at start (e.g. why the last state was not restored).
    pub notice: Option<String>,
    /// A lesson file opened from the command line: added to the course and shown with its
    /// card (`state` is already its state).
    pub lesson: Option<Lesson>,
}

/// What the last interactive frame cost, for the panel.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InteractiveFrame {
    /// Width and height drawn, pixels.
    pub size: [u32; 2],
    /// Drawing it until the adapter finished, milliseconds.
    pub frame_ms: f64,
    /// Its budget ([`InteractiveQuality::budget_ms`]), milliseconds.
    pub budget_ms: f64,
}

/// Floors timed for an interactive frame's budget: the median of this many.
const FLOOR_FRAMES: u32 = 5;

pub struct Controller {
    pub state: ViewerState,
    /// The scene the state is for; its GPU data may still be on its way ([`Self::busy`]).
    scene: Arc<Scene>,
    renderer: Renderer,
    /// The scene's files, the recent list and the last outcome.
    pub files: Files,
    dialog: Dialog,
    watcher: Watcher,
    /// Why hot reload does not work, when it does not.
    watch_error: Option<String>,
    wake: Waker,
    /// The facts of the scene drawn (`None` until its first job is done).
    facts: Option<Arc<SceneFacts>>,
    /// The screenshot and tile-export fields the panel edits, and their last outcome.
    pub screenshot: ScreenshotForm,
    /// The preset path field the panel edits, and the last save's or load's outcome.
    pub preset: PresetForm,
    /// The lessons, the one shown and its caption card.
    pub lessons: LessonsForm,
    probe: Probe,
    /// Makes scenes ready off the UI thread, one job per scene change.
    jobs: SceneJobs,
    /// What the last installed job cost.
    last_job: Option<JobTimes>,
    /// The uploads a job failed to make for the scene shown (a bug, shown in the status): not
    /// asked for again until the state asks for others.
    failed: Option<SceneUploads>,
    /// The 3D view's size in pixels, as last laid out (`None` before the first frame).
    view_size: Option<[u32; 2]>,
    /// Counts changes of the scene or its GPU data: a drawn picture older than this is stale.
    revision: u64,
    /// Where the state is saved on exit; `None`: not saved.
    last_state: Option<PathBuf>,
    /// The folder screenshots and tile exports go to; empty: the current directory.
    #[cfg(not(target_arch = "wasm32"))]
    screenshot_dir: PathBuf,
    /// Frames while the user drags or the light orbits: the panel setting and the render
    /// scale learnt from their times.
    interactive: InteractiveQuality,
    /// The adapter's floor at the view's size with one sample (pixels, milliseconds), timed
    /// at the first interactive frame at that size.
    floor: Option<([u32; 2], f64)>,
    /// What the last interactive frame cost.
    last_interactive: Option<InteractiveFrame>,
    /// GPU displacement's budget notice last told on stderr.
    said_budget: Option<String>,
}

impl Controller {
    /// A controller showing `start`'s scene with `renderer`, which gets the scene's uploads
    /// when the first scene job has made them ready; `wake` is called from worker threads when
    /// they deliver something.
    pub fn new(start: Start, renderer: Renderer, wake: Waker) -> Controller {
        let lesson = start.lesson.clone();
        let mut controller = Self::with_build(start, renderer, wake, Arc::new(SceneFiles::build));
        // A lesson's number is measured on a worker thread with its own adapter; a page has
        // neither threads nor a blocking read-back, so the web build's card shows the claim alone.
        controller.lessons.second_adapter = cfg!(not(target_arch = "wasm32"));
        if let Some(lesson) = lesson {
            controller.show_lesson_file(lesson);
        }
        controller
    }

    /// [`Self::new`] with files loaded by `build` (a fake in tests).
    fn with_build(start: Start, renderer: Renderer, wake: Waker, build: scene_job::BuildFn) -> Controller {
        let Start { scene, state, files: scene_files, capture, last_state, recent_file, notice, lesson: _ } = start;
        let mut files = Files::new(scene_files.absolute(), state.kernel, recent_file);
        files.remember_scene_files();
        if let Some(notice) = notice {
            files.status = Some(Status::Failed(notice));
        }
        let watch_wake = Arc::clone(&wake);
        let (mut watcher, watching) = Watcher::new(move || watch_wake());
        let watch_error = watching.and_then(|()| watcher.watch(&watched_files(&files.scene_files, &scene))).err();
        let uploader = renderer.uploader();
        let mut controller = Controller {
            facts: None,
            state,
            scene: Arc::new(scene),
            renderer,
            files,
            dialog: Dialog::default(),
            watcher,
            watch_error,
            wake,
            screenshot: ScreenshotForm::new(&capture),
            preset: PresetForm::default(),
            lessons: LessonsForm::new(false),
            probe: Probe::default(),
            said_budget: None,
            jobs: SceneJobs::new(build, uploader),
            last_job: None,
            failed: None,
            view_size: None,
            revision: 0,
            last_state,
            #[cfg(not(target_arch = "wasm32"))]
            screenshot_dir: PathBuf::new(),
            interactive: InteractiveQuality::default(),
            floor: None,
            last_interactive: None,
        };
        controller.sync_uploads();
        controller
    }

    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    pub fn renderer(&self) -> &Renderer {
        &self.renderer
    }

    /// The facts of the scene drawn (`None` until its first job is done).
    pub fn facts(&self) -> Option<&SceneFacts> {
        self.facts.as_deref()
    }

    /// What the panel shows while a scene job runs: the scene, the stage and the seconds so
    /// far; `None` when the scene drawn is the one the state asks for.
    pub fn busy(&self) -> Option<String> {
        self.jobs.busy()
    }

    /// What the last scene change cost, on its worker and in the upload.
    pub fn last_job(&self) -> Option<JobTimes> {
        self.last_job
    }

    pub fn probe(&self) -> &Probe {
        &self.probe
    }

    /// Why hot reload does not work, when it does not.
    pub fn watch_error(&self) -> Option<&str> {
        self.watch_error.as_deref()
    }

    /// Whether a file dialog is showing.
    pub fn dialog_open(&self) -> bool {
        self.dialog.is_open()
    }

    /// Counts changes of the scene or its GPU data (not of the frame parameters).
    pub fn revision(&self) -> u64 {
        self.revision
    }

    pub fn view_size(&self) -> Option<[u32; 2]> {
        self.view_size
    }

    /// Whether frames are drawn cheaper while the user drags or the light orbits.
    pub fn interactive_frames(&self) -> bool {
        self.interactive.enabled
    }

    /// What the last interactive frame cost (`None` before one was drawn).
    pub fn last_interactive(&self) -> Option<InteractiveFrame> {
        self.last_interactive
    }

    /// The quality of the next frame: interactive while `active` (something is being dragged,
    /// the view zoomed or the light orbits) and the setting is on, else full.
    pub fn frame_quality(&self, active: bool) -> FrameQuality {
        self.interactive.quality(active)
    }

    /// The 3D view was laid out `size` pixels large (screenshots default to it, the probe
    /// reads the picture at that size).
    pub fn set_view_size(&mut self, size: Option<[u32; 2]>) {
        self.view_size = size;
    }

    /// A function for worker threads that wakes the UI.
    fn waker(&self) -> impl Fn() + Send + 'static {
        let wake = Arc::clone(&self.wake);
        move || wake()
    }

    /// The one place actions take effect; then the renderer's uploads follow the state.
    pub fn apply(&mut self, actions: impl IntoIterator<Item = Action>) {
        for action in actions {
            self.apply_one(action);
        }
        self.sync_uploads();
    }

    fn apply_one(&mut self, action: Action) {
        match &action {
            Action::Viewer(command) => self.leave_grid_for(*command),
            // Other files: the lesson's tiles would no longer be what the view is about.
            Action::Open { .. } | Action::LoadPreset(_) | Action::DialogClosed { path: Some(_), .. } => {
                self.lessons.grid_shown = false;
            }
            _ => {}
        }
        match action {
            Action::Viewer(command) => {
                if self.state.split.overrides(command) {
                    let [left, right] = self.state.split.labels();
                    let why = format!("the split view sets this per half ({left} │ {right}): S turns the split off");
                    self.files.status = Some(Status::Done(why));
                }
                self.state.apply(command);
                if let Command::SetKernel(kernel) = command {
                    self.rebuild_builtin(kernel);
                }
            }
            #[cfg(not(target_arch = "wasm32"))]
            Action::Screenshot => self.screenshot.message = Some(self.save_screenshot()),
            #[cfg(not(target_arch = "wasm32"))]
            Action::ExportTiles => self.screenshot.message = Some(self.export_tiles()),
            #[cfg(target_arch = "wasm32")]
            Action::Screenshot | Action::ExportTiles => {
                self.screenshot.message = Some(Err(crate::app::browser::NO_CAPTURE.into()));
            }
            Action::SavePreset(path) => self.preset.message = Some(self.save_preset(&path)),
            Action::LoadPreset(path) => self.preset.message = Some(self.load_preset(&path)),
            Action::Open { paths, slot } => {
                let job = self.files.plan(&paths, slot);
                self.load(job);
            }
            Action::ShowDialog(slot) => {
                let folder = self.files.scene_files.paths().first().and_then(|f| f.parent()).map(Path::to_owned);
                if let Err(message) = self.dialog.show(slot, folder, self.waker()) {
                    self.files.status = Some(Status::Failed(message));
                }
            }
            Action::DialogClosed { slot, path: Some(path) } => {
                let job = self.files.plan(&[path], slot);
                self.load(job);
            }
            Action::DialogClosed { path: None, .. } => {
                self.files.status = Some(Status::Done(
                    "no file chosen (if no dialog appeared: this desktop has no file-chooser portal or zenity)".into(),
                ));
            }
            Action::Reload => {
                let scene_files = self.files.scene_files.clone();
                let name = scene_files.paths().first().map_or_else(|| "built-in scene".into(), |p| files::file_name(p));
                self.load(Some(Job::reload(scene_files, self.files.kernel, format!("reloaded {name}"))));
            }
            Action::PinProbe { pixel, size } => {
                self.probe.pin(pixel, size);
                (self.wake)();
            }
            Action::ClearProbe => self.probe.clear(),
            Action::SetInteractiveFrames(on) => self.interactive.enabled = on,
            Action::OpenLesson(index) => self.open_lesson(index),
            Action::StepLesson(step) => {
                if let Some(index) = self.lessons.stepped(step) {
                    self.open_lesson(index);
                }
            }
            Action::ShowLessonCard(on) => self.lessons.card = on && self.lessons.current.is_some(),
            Action::SaveLesson { path, words } => {
                self.lessons.draft_message = Some(self.save_lesson(&path, &words));
            }
            Action::TogglePanel => self.lessons.panel_hidden = !self.lessons.panel_hidden,
            Action::ToggleFullscreen => self.lessons.fullscreen = !self.lessons.fullscreen,
        }
    }

    /// Takes in what arrived from other threads: the dialog's answer, settled file changes and
    /// finished scene jobs. Returns how soon to look again while file changes are settling.
    pub fn poll_background(&mut self, now: Instant) -> Option<Duration> {
        let closed = self.dialog.poll().map(|(slot, path)| Action::DialogClosed { slot, path });
        // Scene files are relative where the mesh path was (a command-line argument); the
        // watcher reports absolute paths.
        let referred =
            |path: &PathBuf| self.scene.files.iter().any(|f| std::path::absolute(f).is_ok_and(|f| f == *path));
        if self.watcher.changes().iter().any(|path| files::affects(&self.files.scene_files, path) || referred(path)) {
            self.files.debouncer.changed(now);
        }
        let finished = self.jobs.poll();
        self.lessons.poll();
        // A reload waits for a scene job in flight (which wakes the UI when done), so that it
        // does not replace a mesh the user is opening.
        let (mut wait, mut reload) = (None, None);
        if self.jobs.busy().is_none() {
            if self.files.debouncer.fire(now) {
                reload = Some(Action::Reload);
            } else {
                wait = self.files.debouncer.remaining(now);
            }
        }
        // In the order they arrived: the dialog's answer, the finished jobs, then the reload.
        closed.into_iter().for_each(|action| self.apply_one(action));
        finished.into_iter().for_each(|ready| self.scene_ready(ready));
        self.apply(reload);
        wait
    }

    /// Advances the light orbit by `seconds`; whether it runs (frames must keep coming).
    pub fn animate(&mut self, seconds: f32) -> bool {
        if self.state.is_animating() {
            self.state.apply(Command::Tick(seconds));
        }
        self.state.is_animating()
    }

    /// Draws the current picture (the split view when it is on) into `target` with `msaa`
    /// and submits it. An interactive frame (one sample) is waited for and timed, and its
    /// time against the floor at the view's size sets the next one's render scale. Not in the
    /// web build: a page cannot wait for the GPU, so its interactive frames keep their scale.
    pub fn draw(&mut self, target: &RenderTarget, msaa: Msaa) -> Result<(), RenderError> {
        let params = self.state.frame_params();
        let split = self.state.split_frame();
        let options = DrawOptions { msaa, ..Default::default() };
        if msaa == Msaa::X4 || cfg!(target_arch = "wasm32") {
            let mut encoder = self.renderer.device().create_command_encoder(&Default::default());
            self.renderer.draw(&mut encoder, target, &params, split.as_ref(), options)?;
            self.renderer.queue().submit([encoder.finish()]);
            return Ok(());
        }
        let frame_ms =
            timed(&mut self.renderer, |r, encoder| r.draw(encoder, target, &params, split.as_ref(), options))?;
        let floor_ms = self.floor_ms(self.view_size.unwrap_or(target.size))?;
        self.interactive.record(frame_ms, floor_ms);
        let budget_ms = InteractiveQuality::budget_ms(floor_ms);
        self.last_interactive = Some(InteractiveFrame { size: target.size, frame_ms, budget_ms });
        Ok(())
    }

    /// The floor at `size` with one sample, milliseconds: timed once per size.
    fn floor_ms(&mut self, size: [u32; 2]) -> Result<f64, RenderError> {
        if let Some((_, ms)) = self.floor.filter(|(at, _)| *at == size) {
            return Ok(ms);
        }
        let frames = NonZeroU32::new(FLOOR_FRAMES).expect("not zero");
        let ms = time_floor(&mut self.renderer, size, Msaa::Off, frames)?;
        self.floor = Some((size, ms));
        Ok(ms)
    }
}

/// The files hot reload watches: the scene's (mesh, slot textures) and those the mesh file
/// referred to (buffers, material libraries, textures, also in other folders).
fn watched_files<'a>(scene_files: &'a SceneFiles, scene: &'a Scene) -> Vec<&'a Path> {
    let mut files = scene_files.paths();
    files.extend(scene.files.iter().map(PathBuf::as_path));
    files
}
