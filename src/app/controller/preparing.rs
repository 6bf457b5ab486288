//! A loaded scene made ready off the UI thread: its tangent frames and drawn geometry
//! ([`PreparedScene::new`], for the options the state will draw it with), its textures' mip
//! chains ([`PreparedScene::precompute_mip_chains`]) and the panel's facts (the tangent
//! method's timing and errors, `check`'s findings). The window keeps drawing the previous
//! scene meanwhile; the panel says which stage runs and for how long.

use std::sync::{Arc, Mutex, mpsc};
use std::time::Instant;

use bumpview::frame::SceneUploads;
use bumpview::prepare::PreparedScene;
use bumpview::scene::Scene;

use super::SceneFacts;
use crate::app::files::Purpose;

/// A scene ready to install: what the worker made, for `uploads`.
pub struct Prepared {
    pub scene: Scene,
    pub purpose: Purpose,
    /// The options `main` and `split` were prepared with.
    pub uploads: SceneUploads,
    pub main: Arc<PreparedScene>,
    pub split: Option<Arc<PreparedScene>>,
    pub facts: SceneFacts,
}

/// The job in flight.
struct Busy {
    label: String,
    /// What the worker is doing now.
    stage: Arc<Mutex<&'static str>>,
    started: Instant,
}

/// Prepares loaded scenes on worker threads, the latest only: a new job supersedes the one in
/// flight, whose result is dropped when it arrives.
pub struct Preparer {
    sender: mpsc::Sender<(u64, Prepared)>,
    receiver: mpsc::Receiver<(u64, Prepared)>,
    generation: u64,
    busy: Option<Busy>,
}

impl Default for Preparer {
    fn default() -> Preparer {
        let (sender, receiver) = mpsc::channel();
        Preparer { sender, receiver, generation: 0, busy: None }
    }
}

impl Preparer {
    /// Prepares `scene` for `uploads` on a new thread (its tangent method's facts for
    /// `uploads.main`); `wake` is called from it when done. The error says why no thread could
    /// be started (the scene is then dropped: the previous one stays).
    pub fn start(
        &mut self,
        scene: Scene,
        purpose: Purpose,
        uploads: SceneUploads,
        label: String,
        wake: impl Fn() + Send + 'static,
    ) -> Result<(), String> {
        self.generation += 1;
        let stage = Arc::new(Mutex::new("tangent frames and geometry"));
        let (generation, sender, worker_stage) = (self.generation, self.sender.clone(), Arc::clone(&stage));
        let job = move || {
            let prepared = prepare(scene, purpose, uploads, &worker_stage);
            // The receiver is gone only when the viewer closed.
            let _ = sender.send((generation, prepared));
            wake();
        };
        let spawned = std::thread::Builder::new().name("bumpview-prepare".into()).spawn(job);
        self.busy = spawned.is_ok().then(|| Busy { label, stage, started: Instant::now() });
        spawned.map(drop).map_err(|e| format!("could not start a thread to prepare the scene: {e}"))
    }

    /// What the panel shows while a scene is being prepared: its name, the stage and the
    /// seconds so far.
    pub fn busy(&self) -> Option<String> {
        self.busy.as_ref().map(|busy| {
            let stage = *busy.stage.lock().unwrap_or_else(|poisoned| poisoned.into_inner());
            format!("preparing {}: {stage} ({:.1} s)", busy.label, busy.started.elapsed().as_secs_f64())
        })
    }

    /// The latest job's scene once it is ready; older jobs' are dropped.
    pub fn poll(&mut self) -> Option<Prepared> {
        while let Ok((generation, prepared)) = self.receiver.try_recv() {
            if generation == self.generation {
                self.busy = None;
                return Some(prepared);
            }
        }
        None
    }
}

/// The worker's part: every stage in turn, each named in `stage` as it starts.
fn prepare(scene: Scene, purpose: Purpose, uploads: SceneUploads, stage: &Mutex<&'static str>) -> Prepared {
    let set = |name| *stage.lock().unwrap_or_else(|poisoned| poisoned.into_inner()) = name;
    let made = |options| {
        set("tangent frames and geometry");
        let mut prepared = PreparedScene::new(&scene, options);
        set("mip chains");
        prepared.precompute_mip_chains();
        Arc::new(prepared)
    };
    let main = made(&uploads.main);
    let split = uploads.split_right.as_ref().map(made);
    set("tangent method measurements and checks");
    let facts = SceneFacts::new(&scene, uploads.main.tangent_method);
    Prepared { scene, purpose, uploads, main, split, facts }
}

#[cfg(test)]
mod tests {
    use std::time::Duration;

    use bumpview::scene::builtin::teaching_scene;
    use bumpview::state::ViewerState;

    use super::*;

    /// The worker prepares the scene for the options asked, mip chains included, says what it
    /// is doing meanwhile, and delivers only the latest job.
    #[test]
    fn prepares_the_latest_scene_on_a_worker_with_its_mip_chains() {
        let scene = teaching_scene();
        let uploads = ViewerState::new(&scene).scene_uploads();
        let mut preparer = Preparer::default();
        preparer.start(scene.clone(), Purpose::Reload, uploads.clone(), "old".into(), || ()).unwrap();
        preparer.start(scene, Purpose::Open, uploads.clone(), "bricks".into(), || ()).unwrap();
        assert!(preparer.busy().unwrap().starts_with("preparing bricks: "));
        let deadline = Instant::now() + Duration::from_secs(60);
        let prepared = loop {
            if let Some(prepared) = preparer.poll() {
                break prepared;
            }
            assert!(Instant::now() < deadline, "the worker never finished");
            std::thread::sleep(Duration::from_millis(5));
        };
        assert_eq!((prepared.purpose, prepared.uploads.clone()), (Purpose::Open, uploads));
        assert!(preparer.busy().is_none());
        let main = &prepared.main;
        for index in 0..main.scene.textures.len() {
            assert_eq!(main.mip_chains[index].is_some(), main.uses_texture(index), "texture {index}");
        }
        assert!(main.meshes.iter().any(|m| m.frames.is_some()), "tangent frames made on the worker");
    }
}
