//! Scene jobs through the controller, without a window: the scene given at start, option
//! changes and loads are made ready off the UI thread, one result each, and only the latest
//! job's result is installed.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, mpsc};
use std::time::Duration;

use bumpview::height::Kernel;
use bumpview::load::{LoadError, SceneFiles};
use bumpview::scene::builtin::{teaching_scene, teaching_scene_with_kernel};
use bumpview::state::Command;
use bumpview::tangent::TangentMethod;

use super::Controller;
use super::scene_job::{BuildFn, SceneReady};
use super::tests::{controller, settle, start};
use crate::app::action::Action;
use crate::app::files::Status;

/// Long enough for any job on the built-in scene under a loaded machine.
const JOB_TIMEOUT: Duration = Duration::from_secs(60);

/// Installs a job's `ready` as [`Controller::poll_background`] does when it arrives.
fn install(controller: &mut Controller, ready: SceneReady) {
    controller.scene_ready(ready);
    controller.sync_uploads();
}

/// The tangent method the renderer's main upload was prepared with.
fn drawn_method(controller: &Controller) -> Option<TangentMethod> {
    controller.renderer().prepared(false).unwrap().options.tangent_method
}

#[test]
fn the_scene_given_at_start_is_prepared_by_a_job() {
    let (start, renderer) = start(teaching_scene());
    let mut controller = Controller::new(start, renderer, Arc::new(|| {}));
    assert!(controller.renderer().prepared(false).is_none(), "nothing prepared on the UI thread");
    assert!(controller.facts().is_none(), "nor measured");
    assert!(controller.busy().is_some());
    settle(&mut controller);
    assert_eq!(controller.renderer().counters().scenes_uploaded, 1);
    assert!(controller.facts().is_some());
    let times = controller.last_job().unwrap();
    assert!(times.load_ms == 0.0 && times.prepare_ms > 0.0 && times.upload_ms > 0.0, "{times:?}");
}

/// An option change only starts a job: when `apply` returns, the renderer still holds the old
/// upload and the state the new option; the job's one result brings the new upload, made on
/// its worker, and installing it draws that upload.
#[test]
fn an_option_change_is_prepared_off_the_ui_thread() {
    let mut controller = controller();
    let held = Arc::clone(controller.renderer().prepared(false).unwrap());
    controller.apply([Command::SetTangentMethod(Some(TangentMethod::PerFace)).into()]);
    assert_eq!(controller.state.scene_options.tangent_method, Some(TangentMethod::PerFace));
    assert!(Arc::ptr_eq(controller.renderer().prepared(false).unwrap(), &held), "the old scene is drawn");
    assert_eq!(controller.renderer().counters().scenes_uploaded, 1);
    assert!(controller.busy().is_some());

    let ready = controller.jobs.wait(JOB_TIMEOUT).expect("the job's result");
    assert!(ready.load.is_none(), "a re-prepare loads nothing");
    let uploaded = ready.outcome.as_ref().expect("the scene").main.clone();
    install(&mut controller, ready);
    assert_eq!(drawn_method(&controller), Some(TangentMethod::PerFace));
    assert_eq!(
        controller.renderer().held(false),
        Some(uploaded),
        "the job's upload is drawn, none made on the UI thread"
    );
    assert_eq!(controller.renderer().counters().scenes_uploaded, 2);
    assert!(controller.busy().is_none());
}

/// A job's result that arrives after a newer job started is dropped: the old scene stays
/// drawn until the newer one's result installs.
#[test]
fn a_superseded_jobs_result_is_dropped() {
    let mut controller = controller();
    let before = drawn_method(&controller);
    controller.apply([Command::SetTangentMethod(Some(TangentMethod::PerFace)).into()]);
    let stale = controller.jobs.wait(JOB_TIMEOUT).expect("the first job's result");
    controller.apply([Command::SetTangentMethod(Some(TangentMethod::AveragedAngle)).into()]);
    install(&mut controller, stale);
    assert_eq!(drawn_method(&controller), before, "the superseded result is not installed");
    assert_eq!(controller.renderer().counters().scenes_uploaded, 1);
    assert!(controller.busy().is_some(), "the newer job is still awaited");
    settle(&mut controller);
    assert_eq!(drawn_method(&controller), Some(TangentMethod::AveragedAngle));
    assert_eq!(controller.facts().unwrap().measurements[0].1.method, TangentMethod::AveragedAngle);
    assert_eq!(controller.renderer().counters().scenes_uploaded, 2);
}

/// A job that fails (a bug in preparing) leaves the scene and says why, and its options are
/// not asked for again frame after frame; other options are.
#[test]
fn a_failed_job_is_not_started_again_for_the_same_options() {
    let mut controller = controller();
    let before = drawn_method(&controller);
    controller.apply([Command::SetTangentMethod(Some(TangentMethod::PerFace)).into()]);
    let mut failed = controller.jobs.wait(JOB_TIMEOUT).expect("the job's result");
    failed.outcome = Err("the scene: preparing failed (a bug): planted".into());
    install(&mut controller, failed);
    assert_eq!(controller.files.status, Some(Status::Failed("the scene: preparing failed (a bug): planted".into())));
    assert_eq!(drawn_method(&controller), before);
    controller.poll_background(std::time::Instant::now());
    assert!(controller.busy().is_none(), "not started again");
    controller.apply([Command::SetTangentMethod(Some(TangentMethod::AveragedArea)).into()]);
    settle(&mut controller);
    assert_eq!(drawn_method(&controller), Some(TangentMethod::AveragedArea));
}

/// A fake loader counting its calls: the built-in scene with the mesh's file name as its first
/// mesh's name, an error for `broken.obj`, a panic for `panic.obj`, and for `slow.obj` it
/// waits for a go from the test.
fn fake_build(slow: mpsc::Receiver<()>, calls: Arc<AtomicUsize>) -> BuildFn {
    let slow = Mutex::new(slow);
    Arc::new(move |files: &SceneFiles, kernel: Kernel| {
        calls.fetch_add(1, Ordering::SeqCst);
        let name = files.mesh.as_deref().map(crate::app::files::file_name).unwrap_or_default();
        if name == "slow.obj" {
            slow.lock().unwrap().recv().unwrap();
        }
        assert_ne!(name, "panic.obj", "a loader bug");
        if name == "broken.obj" {
            return Err(LoadError::new(Path::new("/m/broken.obj"), "the file holds no triangles to draw"));
        }
        let mut scene = teaching_scene_with_kernel(kernel);
        scene.meshes[0].name = name;
        Ok(scene)
    })
}

fn open(path: &str) -> Action {
    Action::Open { paths: vec![PathBuf::from(path)], slot: None }
}

/// The name of the drawn scene's first mesh (the fake loader's file name).
fn drawn_mesh(controller: &Controller) -> String {
    controller.renderer().prepared(false).unwrap().scene.meshes[0].name.clone()
}

#[test]
fn loads_succeed_fail_share_their_files_and_supersede() {
    let (go, slow) = mpsc::channel();
    let calls = Arc::new(AtomicUsize::new(0));
    let (start, renderer) = start(teaching_scene());
    let build = fake_build(slow, Arc::clone(&calls));
    let mut controller = Controller::with_build(start, renderer, Arc::new(|| {}), build);
    settle(&mut controller);

    controller.apply([open("/m/good.obj")]);
    settle(&mut controller);
    assert_eq!(drawn_mesh(&controller), "good.obj");
    assert_eq!(controller.files.status, Some(Status::Done("opened good.obj".into())));

    // A failed load leaves the scene; a loader panic is a message too.
    controller.apply([open("/m/broken.obj")]);
    settle(&mut controller);
    assert_eq!(
        controller.files.status,
        Some(Status::Failed("/m/broken.obj: the file holds no triangles to draw".into()))
    );
    controller.apply([open("/m/panic.obj")]);
    settle(&mut controller);
    assert!(matches!(&controller.files.status, Some(Status::Failed(m)) if m.contains("the loader failed (a bug)")));
    assert_eq!(drawn_mesh(&controller), "good.obj");

    // An option change while files load asks for the same files: they are read once, and the
    // scene arrives prepared with the new option.
    calls.store(0, Ordering::SeqCst);
    controller.apply([open("/m/slow.obj")]);
    controller.apply([Command::SetTangentMethod(Some(TangentMethod::PerFace)).into()]);
    assert!(controller.busy().unwrap().starts_with("slow.obj: "), "{:?}", controller.busy());
    go.send(()).unwrap();
    settle(&mut controller);
    assert_eq!((drawn_mesh(&controller), drawn_method(&controller)), ("slow.obj".into(), Some(TangentMethod::PerFace)));
    assert_eq!(calls.load(Ordering::SeqCst), 1, "read once");

    // A load superseded by another never installs, even when it finishes last.
    controller.apply([open("/m/slow.obj")]);
    controller.apply([open("/m/good.obj")]);
    settle(&mut controller);
    assert_eq!(drawn_mesh(&controller), "good.obj");
    let uploads = controller.renderer().counters().scenes_uploaded;
    go.send(()).unwrap();
    assert!(controller.jobs.wait(Duration::from_millis(500)).is_none(), "the superseded job stops");
    controller.poll_background(std::time::Instant::now());
    assert_eq!(
        (drawn_mesh(&controller), controller.renderer().counters().scenes_uploaded),
        ("good.obj".into(), uploads)
    );
    assert_eq!(controller.files.scene_files.mesh.as_deref(), Some(Path::new("/m/good.obj")));
}
