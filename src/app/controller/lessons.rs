//! Lessons in the viewer: the catalogue, the lesson shown and its caption card. Opening a
//! lesson shows its whole state as loading a preset does ([`Controller::show_preset`]); the
//! number on the card is measured off the UI thread, on a headless adapter of its own, as
//! `bumpview slides` measures it, at the default slide's picture size: the card and the slide
//! show one number. A grid lesson shows as its grid, every tile drawn live
//! ([`super::lesson_grid`]), until a change other than the camera's or the lights' leaves the
//! view to its last tile.

use std::sync::mpsc;

use bumpview::lessons::files::{LessonWords, lesson_file_text};
use bumpview::lessons::measure::{LiveLook, SceneCache, measure};
use bumpview::lessons::slide::{DEFAULT_SLIDE_SIZE, SlideLayout};
use bumpview::lessons::{self, Lesson};
use bumpview::render::{Gpu, Renderer};
use bumpview::state::Command;

use super::Controller;
use super::lesson_grid::{LessonGrid, TilesKey};
use crate::app::files::Status;

/// What the lesson's number is on the card.
#[derive(Debug, Clone, PartialEq)]
pub enum Measurement {
    /// Being measured.
    Running,
    /// The share of changed pixels, percent.
    Done(f32),
    Failed(String),
}

/// The course, the lesson shown and whether its card shows.
pub struct LessonsForm {
    /// Every lesson, in order (empty, with [`Self::error`], if the catalogue did not read).
    pub catalogue: Vec<Lesson>,
    pub error: Option<String>,
    /// Index into the catalogue of the lesson opened last.
    pub current: Option<usize>,
    /// Whether the caption card shows over the view.
    pub card: bool,
    /// Presenting: the control panel hidden (H), so the view and the card fill the window.
    pub panel_hidden: bool,
    /// Presenting: the window full-screen (F11).
    pub fullscreen: bool,
    /// The current lesson's number.
    pub measurement: Option<Measurement>,
    /// Whether a worker with an adapter of its own measures a lesson's number and draws a
    /// grid lesson's tiles (not in a browser: no threads there; off in tests).
    pub(super) second_adapter: bool,
    /// Whether the view shows the current grid lesson's tiles rather than its last tile.
    pub grid_shown: bool,
    /// The current grid lesson's tiles.
    pub grid: LessonGrid,
    /// The "Save as lesson" form: its words, its file, and what the last save did.
    pub draft: LessonWords,
    pub draft_path: String,
    pub draft_message: Option<Result<String, String>>,
    results: Option<mpsc::Receiver<(usize, Measurement)>>,
}

impl LessonsForm {
    /// The catalogue read; numbers measured when `second_adapter`.
    pub(super) fn new(second_adapter: bool) -> LessonsForm {
        let (catalogue, error) = match lessons::catalogue() {
            Ok(all) => (all, None),
            Err(e) => (vec![], Some(e.to_string())),
        };
        LessonsForm {
            catalogue,
            error,
            current: None,
            card: false,
            panel_hidden: false,
            fullscreen: false,
            measurement: None,
            second_adapter,
            grid_shown: false,
            grid: LessonGrid::default(),
            draft: LessonWords {
                claim: "The change shows on {changed} of the picture.".into(),
                ..LessonWords::default()
            },
            draft_path: String::new(),
            draft_message: None,
            results: None,
        }
    }

    /// The lesson shown, if any.
    pub fn lesson(&self) -> Option<&Lesson> {
        self.catalogue.get(self.current?)
    }

    /// The lesson `step` places after the current one (before it for a negative step), staying
    /// within the course; the first one when none is shown.
    pub fn stepped(&self, step: i32) -> Option<usize> {
        let last = self.catalogue.len().checked_sub(1)?;
        Some(match self.current {
            None => 0,
            Some(i) => (i as i64 + i64::from(step)).clamp(0, last as i64) as usize,
        })
    }

    /// Whether the current lesson's number or grid tiles are still on their way.
    pub fn pending(&self) -> bool {
        self.measurement == Some(Measurement::Running) || (self.grid_lesson().is_some() && self.grid.pending())
    }

    /// The lesson whose tiles the view shows as a grid, if any.
    pub fn grid_lesson(&self) -> Option<&Lesson> {
        self.lesson().filter(|lesson| self.grid_shown && !lesson.split)
    }

    /// Takes in a finished measurement of the current lesson and tiles drawn; whether either arrived.
    pub fn poll(&mut self) -> bool {
        let tiles = self.grid.poll();
        let Some(arrived) = self.results.as_ref().and_then(|r| r.try_recv().ok()) else { return tiles };
        if Some(arrived.0) == self.current {
            // The card's claim, also on stderr for a presenter's terminal and for scripts.
            if let (Measurement::Done(percent), Some(lesson)) = (&arrived.1, self.lesson()) {
                eprintln!("bumpview: lesson {}: {}", lesson.name, lesson.claim_with(*percent));
            }
            self.measurement = Some(arrived.1);
            self.results = None;
        }
        true
    }

    /// Starts measuring lesson `index` on a worker thread; `wake` is called when it is done.
    fn start_measuring(&mut self, index: usize, wake: impl Fn() + Send + 'static) {
        if !self.second_adapter {
            self.measurement = None;
            return;
        }
        // The card's number is the whole pictures' share: the magnified inset is left undrawn.
        let lesson = Lesson { inset: None, ..self.catalogue[index].clone() };
        let (sender, receiver) = mpsc::channel();
        self.results = Some(receiver);
        self.measurement = Some(Measurement::Running);
        std::thread::spawn(move || {
            let measured = Gpu::headless().map_err(|e| e.to_string()).and_then(|gpu| {
                let mut renderer = Renderer::from_gpu(&gpu);
                let mut scenes = SceneCache::default();
                let size = SlideLayout::new(DEFAULT_SLIDE_SIZE).picture_size(&lesson);
                measure(&mut renderer, &mut scenes, &lesson, size, false).map_err(|e| e.to_string())
            });
            let result = measured.map_or_else(Measurement::Failed, |m| Measurement::Done(m.changed_percent));
            // The viewer may have closed or moved on: nothing to tell then.
            if sender.send((index, result)).is_ok() {
                wake();
            }
        });
    }
}

impl Controller {
    /// Asks for the current grid lesson's tiles at `size` pixels each, with the camera and
    /// lights of the view now (nothing when they are drawn or on their way already).
    pub fn ask_grid_tiles(&mut self, size: [u32; 2]) {
        let wake = self.waker();
        let lessons = &mut self.lessons;
        let Some(lesson) = lessons.current.filter(|_| lessons.grid_lesson().is_some()) else { return };
        let look = LiveLook { camera: self.state.camera, lights: self.state.lights };
        lessons.grid.ask(&lessons.catalogue[lesson], TilesKey { lesson, look, size }, wake);
    }

    /// Leaves a grid lesson's tiles for the live view of its last tile when `command` changes
    /// more than the camera and the lights (which the tiles follow), saying so.
    pub(super) fn leave_grid_for(&mut self, command: Command) {
        if command.moves_camera_or_lights() {
            return;
        }
        let Some(lesson) = self.lessons.grid_lesson() else { return };
        let last = lesson.sides.last().map_or("", |side| side.label.as_str());
        let why = format!(
            "the view left the lesson's grid for its last tile ({last}), live; the lesson list shows the grid again"
        );
        self.files.status = Some(Status::Done(why));
        self.lessons.grid_shown = false;
    }

    /// Writes the current state's split view as a lesson file at `path` with `words` (its
    /// files relative to the lesson's folder) and shows it as a lesson, its number measured;
    /// says where, or why not (one line).
    #[cfg(not(target_arch = "wasm32"))]
    pub(super) fn save_lesson(&mut self, path: &std::path::Path, words: &LessonWords) -> Result<String, String> {
        let folder = path.parent().unwrap_or(std::path::Path::new(""));
        let labels = self.state.split.labels();
        let text = lesson_file_text(words, &self.current_preset(), &labels, folder).map_err(|e| e.message)?;
        bumpview::atomic::write_bytes_atomically(path, text.as_bytes())
            .map_err(|e| format!("could not write {}: {e}", path.display()))?;
        let lesson = Lesson::load(path).map_err(|e| e.to_string())?;
        self.show_lesson_file(lesson);
        Ok(format!("saved {} and opened it as a lesson", path.display()))
    }

    /// Offers the lesson file as a download named as `path`'s file; says which, or why not.
    #[cfg(target_arch = "wasm32")]
    pub(super) fn save_lesson(&mut self, path: &std::path::Path, words: &LessonWords) -> Result<String, String> {
        let name = path.file_name().map_or("lesson.toml".into(), |n| n.to_string_lossy().into_owned());
        let labels = self.state.split.labels();
        let text = lesson_file_text(words, &self.current_preset(), &labels, std::path::Path::new(""))
            .map_err(|e| e.message)?;
        crate::app::browser::download(&name, "application/toml", text.as_bytes())?;
        Ok(format!("downloaded {name}"))
    }

    /// Adds a lesson file's lesson to the course and shows its card and number; the viewer
    /// already shows its state (it started from [`Lesson::viewer_preset`]).
    pub(super) fn show_lesson_file(&mut self, lesson: Lesson) {
        self.lessons.catalogue.push(lesson);
        let index = self.lessons.catalogue.len() - 1;
        self.show_lesson_at(index);
    }

    /// Shows lesson `index`: its whole state (and its scene, loaded in the background when it
    /// differs), its caption card, and its number measured.
    pub(super) fn open_lesson(&mut self, index: usize) {
        let Some(lesson) = self.lessons.catalogue.get(index) else { return };
        let preset = lesson.viewer_preset().clone();
        let name = lesson.name.clone();
        match self.show_preset(&preset, format!("opened the scene of lesson {name}")) {
            Ok(()) => {
                self.show_lesson_at(index);
                self.preset.message = Some(Ok(format!("lesson {name}")));
            }
            Err(e) => self.preset.message = Some(Err(format!("lesson {name}: {e}"))),
        }
    }

    /// Makes lesson `index` the current one: its card, its grid and its number.
    fn show_lesson_at(&mut self, index: usize) {
        self.lessons.current = Some(index);
        self.lessons.card = true;
        self.lessons.grid_shown = self.lessons.second_adapter;
        let wake = self.waker();
        self.lessons.start_measuring(index, wake);
    }
}
