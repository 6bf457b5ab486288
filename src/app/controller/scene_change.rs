//! Scene changes in the controller: every change that needs the scene made again — files
//! opened or reloaded, a kernel change, and any option the GPU data depends on (tangent method,
//! bump source, conventions, the split view's halves), and the scene given at start — becomes
//! one scene job ([`super::scene_job`]); the job's one action installs its result: the UI
//! thread only swaps in the uploads the job made.

use std::sync::Arc;
use web_time::Instant;

use bumpview::frame::SceneUploads;
use bumpview::frame::ViewMode;
use bumpview::height::Kernel;
use bumpview::names::Named;
use bumpview::render::ReferenceFrames;

use super::scene_job::{Ready, SceneReady, Source};
use super::{Controller, watched_files};
use crate::app::files::{self, Job, Purpose, Status};

impl Controller {
    /// Starts loading `job`'s files (nothing when there is no job: the plan failed and the
    /// status says why).
    pub(super) fn load(&mut self, job: Option<Job>) {
        if let Some(job) = job {
            self.request(Source::Load(super::scene_job::Load::new(job)));
        }
    }

    /// Re-makes the built-in scene with a new brick-map kernel (in the background, keeping
    /// the view and any textures in its slots); loaded meshes do not use the kernel.
    pub(super) fn rebuild_builtin(&mut self, kernel: Kernel) {
        if self.files.scene_files.mesh.is_none() && self.files.kernel != kernel {
            let done = format!("brick normal map made with {}", kernel.name());
            self.load(Some(Job::reload(self.files.scene_files.clone(), kernel, done)));
        }
    }

    /// The uploads a scene made for `purpose` is to have: what the state asks, without the
    /// per-material overrides for a new mesh (they name the old mesh's materials).
    fn planned_uploads(&self, purpose: Purpose) -> SceneUploads {
        if purpose != Purpose::Open || self.state.scene_options.per_material.is_empty() {
            return self.state.scene_uploads();
        }
        let mut planned = self.state.clone();
        planned.scene_options.per_material.clear();
        planned.scene_uploads()
    }

    /// Starts a scene job when the GPU data the state asks for is neither drawn nor on its way:
    /// the tangent method, bump source or conventions changed, or the split view's halves. A
    /// load in flight is asked for again with the new options (its files are read once).
    pub(super) fn sync_uploads(&mut self) {
        let (source, aimed) = match self.jobs.in_flight() {
            Some((source, uploads, _)) => (source.clone(), Some(uploads.clone())),
            None => (self.shown(), self.renderer.uploads()),
        };
        let wanted = self.planned_uploads(source.purpose());
        if aimed.as_ref() != Some(&wanted) && self.failed.as_ref() != Some(&wanted) {
            self.request(source);
        }
    }

    /// The scene shown, with its uploads and facts for the job to reuse.
    fn shown(&self) -> Source {
        let held = self.renderer.held(false).into_iter().chain(self.renderer.held(true)).collect();
        Source::Shown { scene: Arc::clone(&self.scene), held, facts: self.facts.clone() }
    }

    /// Whether a half of the view shows the Difference view now, so new uploads had better
    /// bring its reference frames (else the first frame drawn from them makes them).
    fn reference_frames(&self) -> ReferenceFrames {
        let shown = self.state.split_frame().map_or(vec![self.state.shading], |s| vec![s.left, s.right]);
        if shown.iter().any(|shading| shading.view == ViewMode::Difference) {
            ReferenceFrames::WithUpload
        } else {
            ReferenceFrames::OnFirstUse
        }
    }

    /// Starts the job making `source` ready for the options the state asks, superseding the
    /// one in flight; a thread that cannot be started becomes the status.
    fn request(&mut self, source: Source) {
        let uploads = self.planned_uploads(source.purpose());
        let label = match &source {
            Source::Load(load) => load.job.label.clone(),
            Source::Shown { .. } => {
                self.files.scene_files.paths().first().map_or_else(|| "built-in scene".into(), |p| files::file_name(p))
            }
        };
        let wake = self.waker();
        let reference = self.reference_frames();
        if let Err(message) = self.jobs.start(source, uploads, reference, label, wake) {
            self.files.status = Some(Status::Failed(message));
        }
    }

    /// Takes in a scene job's action: a superseded job's is freed (off the UI thread); the
    /// latest's outcome goes to the files (recent list, status) when it loaded any, and its
    /// scene is installed.
    pub(super) fn scene_ready(&mut self, ready: SceneReady) {
        let aimed = self.jobs.in_flight().map(|(_, uploads, _)| uploads.clone());
        let SceneReady { load, outcome, .. } = match self.jobs.accept(ready) {
            Ok(ready) => ready,
            Err(superseded) => return free_elsewhere(superseded),
        };
        self.failed = None;
        let purpose = load.as_ref().map_or(Purpose::Reload, |job| job.purpose);
        match (load, outcome) {
            (Some(job), outcome) => {
                let loaded = outcome.as_ref().map(drop).map_err(Clone::clone);
                self.files.finish(job, loaded);
                if let Ok(ready) = outcome {
                    self.install(ready, purpose);
                    self.watch_error = self.watcher.watch(&watched_files(&self.files.scene_files, &self.scene)).err();
                }
            }
            (None, Ok(ready)) => self.install(ready, purpose),
            (None, Err(message)) => {
                self.files.status = Some(Status::Failed(message));
                self.failed = aimed;
            }
        }
    }

    /// Shows a scene a job made ready: swaps in its uploads (made on the worker), timed. A new
    /// mesh is framed by its default camera and light; otherwise camera, light and settings
    /// stay.
    fn install(&mut self, ready: Ready, purpose: Purpose) {
        let Ready { scene, uploads: _, main, split, facts, mut times } = ready;
        if purpose == Purpose::Open {
            // Per-material overrides name materials by index: they belong to the old mesh.
            self.state.scene_options.per_material.clear();
            self.state.camera = scene.default_camera;
            self.state.lights = scene.default_lights();
        }
        self.state.default_camera = scene.default_camera;
        let started = Instant::now();
        let replaced = self.renderer.install(main, split);
        times.install_ms = started.elapsed().as_secs_f64() * 1e3;
        self.last_job = Some(times);
        let mut replaced_scene = None;
        if !Arc::ptr_eq(&self.scene, &scene) {
            replaced_scene = Some(std::mem::replace(&mut self.scene, scene));
            self.probe.scene_changed();
        }
        free_elsewhere((replaced, replaced_scene));
        self.facts = Some(facts);
        self.revision += 1;
    }
}

/// Frees what a scene change replaced (uploads, the scene) on a thread of its own: freeing a
/// 1M-triangle upload (its buffers, textures and prepared scene) took up to 40 ms on the UI
/// thread. When no thread can be started it is freed here.
fn free_elsewhere(replaced: impl Send + 'static) {
    // On failure the closure, and so `replaced`, is dropped here.
    let _ = std::thread::Builder::new().name("bumpview-free".into()).spawn(move || drop(replaced));
}
