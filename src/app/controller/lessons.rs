//! Lessons in the viewer: the catalogue, the lesson shown and its caption card. Opening a
//! lesson shows its whole state as loading a preset does ([`Controller::show_preset`]); the
//! number on the card is measured off the UI thread, on a headless adapter of its own, as
//! `bumpview slides` measures it, at the default slide's picture size: the card and the slide
//! show one number.

use std::sync::mpsc;

use bumpview::lessons::measure::{SceneCache, measure};
use bumpview::lessons::slide::{DEFAULT_SLIDE_SIZE, SlideLayout};
use bumpview::lessons::{self, Lesson};
use bumpview::render::{Gpu, Renderer};

use super::Controller;

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
    /// Whether opening a lesson measures its number (off in tests: no second adapter).
    pub(super) measure_numbers: bool,
    results: Option<mpsc::Receiver<(usize, Measurement)>>,
}

impl LessonsForm {
    /// The catalogue read; numbers measured when `measure_numbers`.
    pub(super) fn new(measure_numbers: bool) -> LessonsForm {
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
            measure_numbers,
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

    /// Takes in a finished measurement of the current lesson; whether one arrived.
    pub fn poll(&mut self) -> bool {
        let Some(arrived) = self.results.as_ref().and_then(|r| r.try_recv().ok()) else { return false };
        if Some(arrived.0) == self.current {
            self.measurement = Some(arrived.1);
            self.results = None;
        }
        true
    }

    /// Starts measuring lesson `index` on a worker thread; `wake` is called when it is done.
    fn start_measuring(&mut self, index: usize, wake: impl Fn() + Send + 'static) {
        if !self.measure_numbers {
            self.measurement = None;
            return;
        }
        let lesson = self.catalogue[index].clone();
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
    /// Adds a lesson file's lesson to the course and shows its card and number; the viewer
    /// already shows its state (it started from [`Lesson::viewer_preset`]).
    pub(super) fn show_lesson_file(&mut self, lesson: Lesson) {
        self.lessons.catalogue.push(lesson);
        let index = self.lessons.catalogue.len() - 1;
        self.lessons.current = Some(index);
        self.lessons.card = true;
        let wake = self.waker();
        self.lessons.start_measuring(index, wake);
    }

    /// Shows lesson `index`: its whole state (and its scene, loaded in the background when it
    /// differs), its caption card, and its number measured.
    pub(super) fn open_lesson(&mut self, index: usize) {
        let Some(lesson) = self.lessons.catalogue.get(index) else { return };
        let preset = lesson.viewer_preset().clone();
        let name = lesson.name.clone();
        match self.show_preset(&preset, format!("opened the scene of lesson {name}")) {
            Ok(()) => {
                self.lessons.current = Some(index);
                self.lessons.card = true;
                self.preset.message = Some(Ok(format!("lesson {name}")));
                let wake = self.waker();
                self.lessons.start_measuring(index, wake);
            }
            Err(e) => self.preset.message = Some(Err(format!("lesson {name}: {e}"))),
        }
    }
}
