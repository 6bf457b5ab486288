//! A grid lesson shown live: every tile drawn as `bumpview slides` draws it
//! ([`draw_sides_live`]), with the viewer's camera and lights laid over it, on a worker
//! thread with an adapter of its own (as the card's number is measured), at the size the view
//! gives each tile. Only the newest request is drawn; a drag that outpaces the worker skips
//! the views in between, and nothing is drawn while nothing changes.

use std::sync::mpsc;

use bumpview::lessons::Lesson;
use bumpview::lessons::measure::{LiveLook, SceneCache, draw_sides_live};
use bumpview::render::{Gpu, Renderer};
use image::RgbaImage;

/// What the tiles are drawn of: the lesson (by its index in the catalogue), the look laid over
/// it and each tile's size in pixels.
#[derive(Debug, Clone, PartialEq)]
pub struct TilesKey {
    pub lesson: usize,
    pub look: LiveLook,
    pub size: [u32; 2],
}

/// A grid lesson's tiles, drawn.
pub struct Tiles {
    pub key: TilesKey,
    /// One picture per side, in the lesson's order; or why they could not be drawn.
    pub pictures: Result<Vec<RgbaImage>, String>,
    /// Counts the tiles that arrived, so the view knows when to take in new pictures.
    pub serial: u64,
}

/// The worker and what it last drew.
#[derive(Default)]
pub struct LessonGrid {
    worker: Option<Worker>,
    /// The key of the newest request sent.
    asked: Option<TilesKey>,
    shown: Option<Tiles>,
    arrived: u64,
}

struct Worker {
    /// `None` only while dropped.
    requests: Option<mpsc::Sender<(Lesson, TilesKey)>>,
    results: mpsc::Receiver<(TilesKey, Result<Vec<RgbaImage>, String>)>,
    thread: Option<std::thread::JoinHandle<()>>,
}

impl Drop for Worker {
    /// Ends the thread (after the tiles it is drawing) and waits for it, so that its adapter
    /// is gone before the process exits (a Vulkan driver torn down under a running thread
    /// may crash).
    fn drop(&mut self) {
        self.requests = None;
        if let Some(thread) = self.thread.take() {
            let _ = thread.join();
        }
    }
}

impl LessonGrid {
    /// The tiles drawn last (of the lesson and look asked last, or of an earlier one while the
    /// newest is on its way).
    pub fn shown(&self) -> Option<&Tiles> {
        self.shown.as_ref()
    }

    /// Whether tiles are asked for and not yet here.
    pub fn pending(&self) -> bool {
        self.asked.as_ref().is_some_and(|asked| self.shown.as_ref().is_none_or(|t| t.key != *asked))
    }

    /// Asks for `lesson`'s tiles of `key` unless they were the last asked; the worker starts on
    /// first use and calls `wake` when tiles arrive.
    pub fn ask(&mut self, lesson: &Lesson, key: TilesKey, wake: impl Fn() + Send + 'static) {
        if self.asked.as_ref() == Some(&key) {
            return;
        }
        let worker = self.worker.get_or_insert_with(|| Worker::start(wake));
        if worker.requests.as_ref().is_some_and(|r| r.send((lesson.clone(), key.clone())).is_ok()) {
            self.asked = Some(key);
        }
    }

    /// Takes in tiles that arrived; whether any did.
    pub fn poll(&mut self) -> bool {
        let Some(worker) = &self.worker else { return false };
        let Some((key, pictures)) = worker.results.try_iter().last() else { return false };
        self.arrived += 1;
        self.shown = Some(Tiles { key, pictures, serial: self.arrived });
        true
    }
}

impl Worker {
    fn start(wake: impl Fn() + Send + 'static) -> Worker {
        let (requests, inbox) = mpsc::channel::<(Lesson, TilesKey)>();
        let (outbox, results) = mpsc::channel();
        let thread = std::thread::spawn(move || {
            let mut drawer = Gpu::headless().map(|gpu| (Renderer::from_gpu(&gpu), SceneCache::default(), None));
            // Blocks for a request, then skips to the newest one queued behind it.
            while let Ok(first) = inbox.recv() {
                let (lesson, key) = inbox.try_iter().last().unwrap_or(first);
                let pictures = match &mut drawer {
                    Ok((renderer, scenes, lesson_of_scenes)) => {
                        // The scenes of one lesson are kept while it shows, not every lesson's.
                        if *lesson_of_scenes != Some(key.lesson) {
                            *scenes = SceneCache::default();
                            *lesson_of_scenes = Some(key.lesson);
                        }
                        draw_sides_live(renderer, scenes, &lesson, key.size, &key.look).map_err(|e| e.to_string())
                    }
                    Err(e) => Err(format!("no adapter to draw the tiles on: {e}")),
                };
                if outbox.send((key, pictures)).is_err() {
                    return;
                }
                wake();
            }
        });
        Worker { requests: Some(requests), results, thread: Some(thread) }
    }
}
