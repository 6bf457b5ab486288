//! Loading scenes on worker threads, so the window keeps drawing while files are read.

use std::sync::{Arc, mpsc};

use bumpview::height::Kernel;
use bumpview::load::{LoadError, SceneFiles};
use bumpview::scene::Scene;

use super::Job;

/// Makes a scene from its files and the built-in scene's kernel: [`SceneFiles::build`], or a
/// fake in tests.
pub type BuildFn = Arc<dyn Fn(&SceneFiles, Kernel) -> Result<Scene, LoadError> + Send + Sync>;

/// A job's outcome from the worker: the scene or the loader's one-line message.
#[derive(Debug, Clone, PartialEq)]
pub struct Finished {
    pub job: Job,
    pub result: Result<Scene, String>,
}

/// Loads scenes on worker threads, one job at a time as far as the UI is concerned: a new job
/// supersedes the one in flight, whose result is then dropped when it arrives.
pub struct Loader {
    build: BuildFn,
    sender: mpsc::Sender<(u64, Finished)>,
    receiver: mpsc::Receiver<(u64, Finished)>,
    /// Number of the latest job started.
    generation: u64,
    /// The latest job's label while it runs.
    busy: Option<String>,
}

impl Loader {
    /// A loader that makes scenes with `build`.
    pub fn new(build: BuildFn) -> Loader {
        let (sender, receiver) = mpsc::channel();
        Loader { build, sender, receiver, generation: 0, busy: None }
    }

    /// Starts `job` on a new thread; `wake` is called from that thread when it is done (the
    /// viewer asks for a repaint, so the result is picked up at once). The error says why no
    /// thread could be started.
    pub fn start(&mut self, job: Job, wake: impl Fn() + Send + 'static) -> Result<(), String> {
        self.generation += 1;
        let label = job.label.clone();
        let (generation, build, sender) = (self.generation, Arc::clone(&self.build), self.sender.clone());
        let spawned = std::thread::Builder::new().name("bumpview-load".into()).spawn(move || {
            // A loader bug must not leave the spinner turning forever: a panic becomes a message.
            let built = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| build(&job.files, job.kernel)));
            let result = match built {
                Ok(result) => result.map_err(|e| e.to_string()),
                Err(panic) => Err(format!("{}: the loader failed (a bug): {}", job.label, panic_message(&*panic))),
            };
            // The receiver is gone only when the viewer closed.
            let _ = sender.send((generation, Finished { job, result }));
            wake();
        });
        self.busy = spawned.is_ok().then_some(label);
        spawned.map(drop).map_err(|e| format!("could not start a loading thread: {e}"))
    }

    /// The label of the job in flight, if any.
    pub fn busy(&self) -> Option<&str> {
        self.busy.as_deref()
    }

    /// The latest job's outcome once it has arrived; older jobs' outcomes are dropped.
    pub fn poll(&mut self) -> Option<Finished> {
        while let Ok((generation, finished)) = self.receiver.try_recv() {
            if generation == self.generation {
                self.busy = None;
                return Some(finished);
            }
        }
        None
    }
}

/// The text of a panic's payload (a `&str` or `String`, as `panic!` makes).
fn panic_message(payload: &(dyn std::any::Any + Send)) -> &str {
    payload.downcast_ref::<&str>().copied().or(payload.downcast_ref::<String>().map(String::as_str)).unwrap_or("panic")
}
