//! One background job per scene change: load the files when they changed, prepare the scene
//! for the options it will be drawn with (tangent frames and drawn geometry,
//! [`PreparedScene::new`]; the textures' mip chains, [`PreparedScene::precompute_mip_chains`])
//! and upload it to the GPU ([`Uploader`]), and measure it for the panel ([`SceneFacts`]), then
//! hand the UI one [`SceneReady`]. The UI thread only installs what arrives (a swap,
//! [`bumpview::render::Renderer::install`]); the window keeps drawing the previous scene
//! meanwhile.
//!
//! A newer job supersedes an older one: the older stops before its next stage, and a result
//! it delivered anyway is dropped by [`SceneJobs::accept`], so no stale scene installs over a
//! newer one. Files being loaded are shared ([`Load`]): an option change during a load asks
//! for the same files, which are read once.

use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, OnceLock, mpsc};

use web_time::Instant;

use bumpview::frame::SceneUploads;
use bumpview::height::Kernel;
use bumpview::load::{LoadError, SceneFiles};
use bumpview::prepare::PreparedScene;
use bumpview::render::{ReferenceFrames, SceneUpload, Uploader};
use bumpview::scene::Scene;

use super::facts::SceneFacts;
use crate::app::files::{Job, Purpose};

/// Makes a scene from its files and the built-in scene's kernel: [`SceneFiles::build`], or a
/// fake in tests.
pub type BuildFn = Arc<dyn Fn(&SceneFiles, Kernel) -> Result<Scene, LoadError> + Send + Sync>;

/// Files to load, shared by every job that needs them: the first to get there reads them,
/// the others wait for that and take its scene.
#[derive(Debug)]
pub struct Load {
    pub job: Job,
    scene: OnceLock<Result<Arc<Scene>, String>>,
}

impl Load {
    pub fn new(job: Job) -> Arc<Load> {
        Arc::new(Load { job, scene: OnceLock::new() })
    }

    /// The scene, loaded with `build` unless another job did; the error is the loader's
    /// one-line message (a loader panic becomes one too, so no spinner turns forever).
    fn scene(&self, build: &BuildFn) -> Result<Arc<Scene>, String> {
        let load = || {
            let built =
                std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| build(&self.job.files, self.job.kernel)));
            match built {
                Ok(result) => result.map(Arc::new).map_err(|e| e.to_string()),
                Err(panic) => Err(format!("{}: the loader failed (a bug): {}", self.job.label, panic_message(&*panic))),
            }
        };
        self.scene.get_or_init(load).clone()
    }
}

/// What a job makes its scene from.
#[derive(Debug, Clone)]
pub enum Source {
    /// Files to load: opened, reloaded, a preset's, the built-in scene with another kernel.
    Load(Arc<Load>),
    /// The scene shown now, prepared for other options (or for the first time: the scene
    /// given on the command line). `held` are its uploads drawn now, reused for the options
    /// they were prepared with; `facts` its facts, reused where still true.
    Shown { scene: Arc<Scene>, held: Vec<SceneUpload>, facts: Option<Arc<SceneFacts>> },
}

impl Source {
    /// Why the scene is made: a load's purpose, else the scene stays ([`Purpose::Reload`]).
    pub fn purpose(&self) -> Purpose {
        match self {
            Source::Load(load) => load.job.purpose,
            Source::Shown { .. } => Purpose::Reload,
        }
    }
}

/// How long a job's stages took on its worker, and the install on the UI thread, milliseconds.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct JobTimes {
    /// Reading the files (0 when the shown scene was prepared again or another job read them).
    pub load_ms: f64,
    /// Tangent frames, drawn geometry and mip chains of both uploads.
    pub prepare_ms: f64,
    /// Uploading both to the GPU (0 when the uploads drawn were reused).
    pub upload_ms: f64,
    /// The tangent method's timing and errors, `check`.
    pub measure_ms: f64,
    /// Installing the result, on the UI thread (set there).
    pub install_ms: f64,
}

/// A scene made ready by a job, to install.
#[derive(Debug, Clone, PartialEq)]
pub struct Ready {
    pub scene: Arc<Scene>,
    /// The options `main` and `split` were prepared with.
    pub uploads: SceneUploads,
    pub main: SceneUpload,
    pub split: Option<SceneUpload>,
    pub facts: Arc<SceneFacts>,
    pub times: JobTimes,
}

/// The one result a job hands the UI ([`super::Controller::poll_background`] installs it).
#[derive(Debug, Clone, PartialEq)]
pub struct SceneReady {
    /// Which job this is; only the latest's result is installed.
    generation: u64,
    /// The files loaded, when the job loaded any (for the recent list and the status).
    pub load: Option<Job>,
    /// The scene, or why the files did not load (or the job failed).
    pub outcome: Result<Ready, String>,
}

/// The job in flight, as far as the UI is concerned (the latest started).
struct Busy {
    label: String,
    source: Source,
    uploads: SceneUploads,
    /// Whether new uploads are made with the Difference view's reference frames.
    reference: ReferenceFrames,
    /// What the worker is doing now.
    stage: Arc<Mutex<&'static str>>,
    started: Instant,
}

/// Runs scene jobs on worker threads, the latest only.
pub struct SceneJobs {
    build: BuildFn,
    uploader: Uploader,
    sender: mpsc::Sender<SceneReady>,
    receiver: mpsc::Receiver<SceneReady>,
    /// Number of the latest job started; workers read it to stop when superseded.
    latest: Arc<AtomicU64>,
    busy: Option<Busy>,
}

impl SceneJobs {
    /// Jobs that load files with `build` and upload with `uploader`.
    pub fn new(build: BuildFn, uploader: Uploader) -> SceneJobs {
        let (sender, receiver) = mpsc::channel();
        SceneJobs { build, uploader, sender, receiver, latest: Arc::new(AtomicU64::new(0)), busy: None }
    }

    /// Starts a job making `source` ready for `uploads` on a new thread, superseding the one in
    /// flight; its new uploads are made with the reference frames when `reference` says so.
    /// `wake` is called from it when its action is sent. The error says why no thread could be
    /// started (the scene shown stays).
    pub fn start(
        &mut self,
        source: Source,
        uploads: SceneUploads,
        reference: ReferenceFrames,
        label: String,
        wake: impl Fn() + Send + 'static,
    ) -> Result<(), String> {
        let generation = self.latest.fetch_add(1, Ordering::SeqCst) + 1;
        let stage = Arc::new(Mutex::new("waiting"));
        let worker = Worker {
            generation,
            latest: Arc::clone(&self.latest),
            stage: Arc::clone(&stage),
            build: Arc::clone(&self.build),
            uploader: self.uploader.clone(),
            reference,
        };
        let (job_source, job_uploads, sender) = (source.clone(), uploads.clone(), self.sender.clone());
        let run = move || {
            if let Some(ready) = worker.run(job_source, job_uploads) {
                // The receiver is gone only when the viewer closed.
                let _ = sender.send(ready);
                wake();
            }
        };
        let spawned = spawn(run);
        self.busy = spawned.is_ok().then(|| Busy { label, source, uploads, reference, stage, started: Instant::now() });
        spawned
    }

    /// What the panel shows while a job runs: the scene's name, the stage and the seconds so
    /// far.
    pub fn busy(&self) -> Option<String> {
        self.busy.as_ref().map(|busy| {
            let stage = *busy.stage.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
            format!("{}: {stage} ({:.1} s)", busy.label, busy.started.elapsed().as_secs_f64())
        })
    }

    /// The source, options and reference frames of the job in flight.
    pub fn in_flight(&self) -> Option<(&Source, &SceneUploads, ReferenceFrames)> {
        self.busy.as_ref().map(|busy| (&busy.source, &busy.uploads, busy.reference))
    }

    /// The results jobs have sent since the last call.
    pub fn poll(&self) -> Vec<SceneReady> {
        self.receiver.try_iter().collect()
    }

    /// Waits up to `timeout` for the next result a job sends.
    #[cfg(test)]
    pub fn wait(&self, timeout: std::time::Duration) -> Option<SceneReady> {
        self.receiver.recv_timeout(timeout).ok()
    }

    /// `Ok(ready)` if it is the latest job's (which then is no longer in flight); `Err(ready)`
    /// for a superseded job's, which must not be installed (only freed).
    pub fn accept(&mut self, ready: SceneReady) -> Result<SceneReady, SceneReady> {
        if ready.generation != self.latest.load(Ordering::SeqCst) {
            return Err(ready);
        }
        self.busy = None;
        Ok(ready)
    }
}

/// A job's side on its thread.
struct Worker {
    generation: u64,
    latest: Arc<AtomicU64>,
    stage: Arc<Mutex<&'static str>>,
    build: BuildFn,
    uploader: Uploader,
    reference: ReferenceFrames,
}

impl Worker {
    /// Every stage in turn, each named in `stage` as it starts; `None` once superseded. A
    /// panic becomes the outcome's message.
    fn run(&self, source: Source, uploads: SceneUploads) -> Option<SceneReady> {
        let load = match &source {
            Source::Load(load) => Some(load.job.clone()),
            Source::Shown { .. } => None,
        };
        let label = load.as_ref().map_or("the scene", |job| job.label.as_str()).to_owned();
        let made = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| self.make(source, uploads)));
        let outcome = match made {
            Ok(outcome) => outcome?,
            Err(panic) => Err(format!("{label}: preparing failed (a bug): {}", panic_message(&*panic))),
        };
        Some(SceneReady { generation: self.generation, load, outcome })
    }

    fn make(&self, source: Source, uploads: SceneUploads) -> Option<Result<Ready, String>> {
        let mut times = JobTimes::default();
        let (scene, held, facts) = match source {
            Source::Load(load) => {
                self.set("loading the files");
                let started = Instant::now();
                let scene = match load.scene(&self.build) {
                    Ok(scene) => scene,
                    Err(message) => return Some(Err(message)),
                };
                times.load_ms = milliseconds(started);
                (scene, Vec::new(), None)
            }
            Source::Shown { scene, held, facts } => (scene, held, facts),
        };
        let mut made = |options| self.uploaded(&scene, &held, options, &mut times);
        let main = made(&uploads.main)?;
        let split = match &uploads.split_right {
            Some(options) => Some(made(options)?),
            None => None,
        };
        self.current()?;
        self.set("measuring the tangent method, checking");
        let started = Instant::now();
        let facts = Arc::new(SceneFacts::renewed(facts.as_deref(), &scene, uploads.main.tangent_method));
        times.measure_ms = milliseconds(started);
        self.current()?;
        Some(Ok(Ready { scene, uploads, main, split, facts, times }))
    }

    /// `scene` prepared with `options` and uploaded, or the one of `held` made with them;
    /// the stages' times are added to `times`. `None` once superseded.
    fn uploaded(
        &self,
        scene: &Scene,
        held: &[SceneUpload],
        options: &bumpview::frame::SceneOptions,
        times: &mut JobTimes,
    ) -> Option<SceneUpload> {
        if let Some(held) = held.iter().find(|u| u.prepared().options == *options) {
            return Some(held.clone());
        }
        self.current()?;
        self.set("tangent frames and geometry");
        let started = Instant::now();
        let mut prepared = PreparedScene::new(scene, options);
        self.current()?;
        self.set("mip chains");
        prepared.precompute_mip_chains();
        times.prepare_ms += milliseconds(started);
        self.current()?;
        self.set("uploading to the GPU");
        let started = Instant::now();
        let upload = self.uploader.upload(Arc::new(prepared), self.reference);
        times.upload_ms += milliseconds(started);
        Some(upload)
    }

    /// `Some` while this is the latest job.
    fn current(&self) -> Option<()> {
        (self.latest.load(Ordering::SeqCst) == self.generation).then_some(())
    }

    fn set(&self, stage: &'static str) {
        *self.stage.lock().unwrap_or_else(|poisoned| poisoned.into_inner()) = stage;
    }
}

/// Runs a job on a thread of its own; the error says why none could be started.
#[cfg(not(target_arch = "wasm32"))]
fn spawn(run: impl FnOnce() + Send + 'static) -> Result<(), String> {
    let spawned = std::thread::Builder::new().name("bumpview-scene".into()).spawn(run);
    spawned.map(drop).map_err(|e| format!("could not start a thread to make the scene ready: {e}"))
}

/// The web build has one thread: the job runs as a task of the page's event loop, after the
/// frame that started it (the page shows the spinner first, then is busy for the job's length).
#[cfg(target_arch = "wasm32")]
fn spawn(run: impl FnOnce() + 'static) -> Result<(), String> {
    wasm_bindgen_futures::spawn_local(async move { run() });
    Ok(())
}

/// Milliseconds since `started`.
fn milliseconds(started: Instant) -> f64 {
    started.elapsed().as_secs_f64() * 1e3
}

/// The text of a panic's payload (a `&str` or `String`, as `panic!` makes).
fn panic_message(payload: &(dyn std::any::Any + Send)) -> &str {
    payload.downcast_ref::<&str>().copied().or(payload.downcast_ref::<String>().map(String::as_str)).unwrap_or("panic")
}
