//! The controller on a headless GPU, without a window: actions in, state, uploads and files out.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::{Duration, Instant};

use bumpview::frame::ViewMode;
use bumpview::load::SceneFiles;
use bumpview::render::{Gpu, Renderer};
use bumpview::scene::Scene;
use bumpview::scene::builtin::teaching_scene;
use bumpview::state::preset::CapturePreset;
use bumpview::state::{Command, SplitDifference, ViewerState};
use bumpview::tangent::TangentMethod;

use super::{Controller, Start};
use crate::app::action::Action;

/// What a controller on `scene` with a headless renderer, no recent list and no last state
/// starts with.
pub(super) fn start(scene: Scene) -> (Start, Renderer) {
    let gpu = Gpu::headless().expect("a GPU adapter (WGPU_BACKEND=vulkan with lavapipe)");
    let start = Start {
        state: ViewerState::new(&scene),
        scene,
        files: SceneFiles::default(),
        capture: CapturePreset::default(),
        last_state: None,
        recent_file: None,
        notice: None,
        lesson: None,
    };
    (start, Renderer::from_gpu(&gpu))
}

/// A controller on the built-in scene once its first scene job is installed.
pub(super) fn controller() -> Controller {
    let (start, renderer) = start(teaching_scene());
    let mut controller = Controller::new(start, renderer, Arc::new(|| {}));
    settle(&mut controller);
    controller
}

/// Runs the UI's background step until no scene job is in flight (60 s at most).
pub(super) fn settle(controller: &mut Controller) {
    let started = Instant::now();
    while controller.busy().is_some() {
        assert!(started.elapsed() < Duration::from_secs(60), "the scene job did not finish");
        std::thread::sleep(Duration::from_millis(5));
        controller.poll_background(Instant::now());
    }
}

/// A fresh folder for one test's files.
fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("bumpview-controller-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn file_names(dir: &Path) -> Vec<String> {
    let mut names: Vec<_> =
        std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
    names.sort();
    names
}

#[test]
fn a_tangent_method_change_re_uploads_once_and_uniforms_never() {
    let mut controller = controller();
    let uploads = || controller.renderer().counters().scenes_uploaded;
    assert_eq!(uploads(), 1, "the start's upload");
    controller.apply([Command::SetTangentMethod(Some(TangentMethod::PerFace)).into()]);
    settle(&mut controller);
    assert_eq!(controller.renderer().counters().scenes_uploaded, 2);
    let held = controller.renderer().prepared(false).unwrap();
    assert_eq!(held.options.tangent_method, Some(TangentMethod::PerFace));
    assert_eq!(controller.facts().unwrap().measurements[0].1.method, TangentMethod::PerFace, "measured again");

    // The same method again, uniforms and a uniform split: nothing to upload.
    let uniforms = [
        Command::SetTangentMethod(Some(TangentMethod::PerFace)),
        Command::SetStrength(2.5),
        Command::SetView(ViewMode::Tangent),
        Command::SetSplit(true),
    ];
    controller.apply(uniforms.map(Action::from));
    assert!(controller.busy().is_none(), "no scene job");
    assert_eq!(controller.renderer().counters().scenes_uploaded, 2);

    // A split in tangent methods needs a second upload, once; turning it off drops it.
    controller.apply([Command::SetSplitDifference(SplitDifference::Tangents).into()]);
    settle(&mut controller);
    controller.apply([Command::SetStrength(1.0).into()]);
    assert_eq!(controller.renderer().counters().scenes_uploaded, 3, "the right half's upload (left is per-face)");
    assert!(controller.renderer().uploads().unwrap().split_right.is_some());
    controller.apply([Command::SetSplit(false).into()]);
    settle(&mut controller);
    assert_eq!(controller.renderer().uploads().unwrap().split_right, None);
    assert_eq!(controller.renderer().counters().scenes_uploaded, 3, "the left half's upload stays");
}

#[test]
fn the_probe_reads_the_scene_the_renderer_draws() {
    let mut controller = controller();
    controller.set_view_size(Some([320, 180]));
    controller.apply([Action::PinProbe { pixel: [160, 50], size: [320, 180] }]);
    controller.refresh_probe();
    let drawn = controller.renderer().prepared(false).unwrap();
    assert!(Arc::ptr_eq(controller.probe().prepared().unwrap(), drawn), "the renderer's prepared scene itself");
    assert!(controller.probe().report().unwrap().text.is_ok(), "the wall is at that pixel");

    controller.apply([Command::SetTangentMethod(Some(TangentMethod::PerFace)).into()]);
    settle(&mut controller);
    controller.refresh_probe();
    let drawn = controller.renderer().prepared(false).unwrap();
    assert!(Arc::ptr_eq(controller.probe().prepared().unwrap(), drawn), "follows the new upload");
}

#[test]
fn a_preset_load_applies_its_state_and_a_bad_one_keeps_the_state() {
    let dir = temp_dir("preset");
    let mut controller = controller();
    let good = dir.join("slide.toml");
    let text = "[shading]\nview = \"shading-normal\"\nstrength = 2.5\n[capture]\nsize = [640, 360]\n";
    std::fs::write(&good, text).unwrap();
    controller.apply([Action::LoadPreset(good.clone())]);
    assert_eq!(controller.preset.message, Some(Ok(format!("loaded {}", good.display()))));
    assert_eq!((controller.state.shading.view, controller.state.shading.strength), (ViewMode::ShadingNormal, 2.5));
    assert_eq!(controller.screenshot.size_text, "640x360");
    assert!(controller.busy().is_none(), "same files and scene options: no scene job");

    let before = controller.state.clone();
    let bad = dir.join("bad.toml");
    std::fs::write(&bad, "[shading]\nstrenght = 2\n").unwrap();
    controller.apply([Action::LoadPreset(bad)]);
    let message = controller.preset.message.clone().unwrap().unwrap_err();
    assert!(message.contains("bad.toml") && message.contains("strenght"), "{message}");
    assert_eq!(controller.state, before, "a bad preset changes nothing");

    // Saving writes the state that loading reads back.
    let saved = dir.join("saved.toml");
    controller.apply([Action::SavePreset(saved.clone())]);
    assert!(controller.preset.message.clone().unwrap().is_ok());
    controller.apply([Command::SetStrength(0.5).into(), Action::LoadPreset(saved)]);
    assert_eq!(controller.state, before);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_screenshot_and_a_tile_export_write_pngs_atomically() {
    let dir = temp_dir("screenshot");
    let mut controller = controller();
    controller.set_screenshot_dir(dir.clone());
    controller.apply([Action::Screenshot]);
    assert_eq!(controller.screenshot.message, Some(Err("the view has no size yet".into())));
    assert!(file_names(&dir).is_empty());

    controller.set_view_size(Some([96, 64]));
    controller.apply([Action::Screenshot]);
    let message = controller.screenshot.message.clone().unwrap().unwrap();
    assert!(message.ends_with("(96x64)"), "{message}");
    // Only the PNG is left: the temporary file was renamed over it.
    let names = file_names(&dir);
    assert!(names.len() == 1 && names[0].starts_with("bumpview-") && names[0].ends_with(".png"), "{names:?}");
    let image = image::open(dir.join(&names[0])).unwrap();
    assert_eq!((image.width(), image.height()), (96, 64));

    // Tiles of the form's size while a split's left half has its own upload, which stays.
    controller.screenshot.size_text = "40x30".into();
    controller.screenshot.tiles_text = "flat,bumped".into();
    controller.apply([Command::SetSplit(true).into(), Command::SetSplitDifference(SplitDifference::Tangents).into()]);
    settle(&mut controller);
    let held = controller.renderer().uploads();
    controller.apply([Action::ExportTiles]);
    let message = controller.screenshot.message.clone().unwrap().unwrap();
    assert!(message.ends_with("(80x30, 2 tiles)"), "{message}");
    assert_eq!(controller.renderer().uploads(), held, "the split's uploads come back");
    assert_eq!(file_names(&dir).len(), 2);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_texture_opened_into_a_slot_reloads_the_scene_in_the_background() {
    let dir = temp_dir("open");
    let texture = dir.join("paint.png");
    image::RgbaImage::from_pixel(4, 4, image::Rgba([200, 40, 40, 255])).save(&texture).unwrap();
    let mut controller = controller();
    let camera = controller.state.camera;
    controller.apply([Command::OrbitCamera { d_yaw: 0.3, d_pitch: 0.0 }.into()]);
    let moved = controller.state.camera;
    assert_ne!(moved, camera);
    let revision = controller.revision();
    controller.apply([Action::Open { paths: vec![texture.clone()], slot: Some(bumpview::load::TextureSlot::Color) }]);
    let started = Instant::now();
    while controller.busy().is_some() || controller.revision() == revision {
        assert!(started.elapsed() < Duration::from_secs(60), "the load did not finish");
        std::thread::sleep(Duration::from_millis(20));
        controller.poll_background(Instant::now());
    }
    assert_eq!(controller.files.scene_files.color.as_deref(), Some(texture.as_path()));
    assert_eq!(controller.state.camera, moved, "a texture keeps the view");
    assert_eq!(controller.renderer().counters().scenes_uploaded, 2, "the reloaded scene, once");
    let painted = controller.scene().textures.iter().any(|t| t.name.contains("paint.png"));
    assert!(painted, "the texture is in the scene");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// While something is dragged or the light orbits, frames are interactive: one sample per
/// pixel at the learnt render scale, each timed against the floor at the view's size; when
/// input stops the next frame is full quality; with the panel setting off every frame is.
#[test]
fn interactive_frames_only_while_active_and_enabled() {
    use bumpview::frame::{FrameQuality, Msaa};
    use bumpview::render::RenderTarget;
    use bumpview::render::capture::IMAGE_FORMAT;
    use bumpview::render::timing::target_texture;
    use bumpview::state::interactive::MIN_BUDGET_MS;

    let mut controller = controller();
    let view_size = [160, 100];
    controller.set_view_size(Some(view_size));
    let quality = controller.frame_quality(true);
    assert_eq!(quality, FrameQuality { msaa: Msaa::Off, render_scale: 1.0 }, "every pixel until a frame is timed");
    let size = quality.render_size(view_size);
    let texture = target_texture(controller.renderer().device(), size);
    let view = texture.create_view(&Default::default());
    let built = controller.renderer().counters().pipelines_built;
    controller.draw(&RenderTarget { view: &view, format: IMAGE_FORMAT, size }, Msaa::Off).unwrap();
    let last = controller.last_interactive().expect("timed");
    assert_eq!(last.size, size);
    assert!(last.frame_ms > 0.0 && last.budget_ms >= MIN_BUDGET_MS, "{last:?}");
    assert!(controller.renderer().counters().pipelines_built > built, "one-sample pipelines and the floor's");
    let scale = controller.frame_quality(true).render_scale;
    assert!((0.25..=1.0).contains(&scale), "{scale}");

    assert_eq!(controller.frame_quality(false), FrameQuality::FULL, "input stopped");
    controller.apply([Action::SetInteractiveFrames(false)]);
    assert!(!controller.interactive_frames());
    assert_eq!(controller.frame_quality(true), FrameQuality::FULL, "the setting off");
}
