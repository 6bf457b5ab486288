//! Lessons in the viewer: opening one shows its whole state and scene, Page Down / Page Up
//! step through the course within its ends, the state stays interactive, and presenting hides
//! the panel and fills the screen, a grid lesson shows as its grid, and the split view saves as a
//! lesson.

use std::time::Duration;

use bumpview::lessons::files::LessonWords;
use bumpview::lessons::measure::{SceneCache, measure};
use bumpview::lessons::{Lesson, catalogue};
use bumpview::render::{Gpu, Renderer};
use bumpview::scene::teaching::TeachingScene;
use bumpview::state::{Command, SplitDifference};
use web_time::Instant;

use super::tests::{controller, settle};
use crate::app::action::Action;
use crate::app::controller::{Controller, Measurement};

#[test]
fn a_lesson_shows_its_whole_state_and_scene_and_stays_interactive() {
    let mut controller = controller();
    controller.lessons.second_adapter = false;
    let all = catalogue().unwrap();
    let index = all.iter().position(|l| l.name == "mistake-handedness").unwrap();
    controller.apply([Action::OpenLesson(index)]);
    settle(&mut controller);
    assert_eq!(controller.files.scene_files.builtin, Some(TeachingScene::MirroredWall));
    assert_eq!(controller.scene().meshes[0].name, "mirrored wall");
    let expected = all[index].apply(controller.scene()).unwrap();
    assert_eq!(controller.state.frame_params(), expected.frame_params());
    assert_eq!((&controller.state.split, &controller.state.scene_options), (&expected.split, &expected.scene_options));
    assert!(controller.lessons.card && controller.lessons.lesson() == Some(&all[index]));
    // Every lesson stays interactive: the state takes commands as before.
    controller.apply([Action::Viewer(Command::SetSplitDivider(0.25)), Action::Viewer(Command::ToggleBump)]);
    assert_eq!(controller.state.split.divider, 0.25);
    assert_ne!(controller.state.shading.bump_enabled, expected.shading.bump_enabled);
    controller.apply([Action::ShowLessonCard(false)]);
    assert!(!controller.lessons.card);
}

#[test]
fn page_down_and_up_step_through_the_course_within_its_ends() {
    let mut controller = controller();
    controller.lessons.second_adapter = false;
    let count = controller.lessons.catalogue.len();
    controller.apply([Action::StepLesson(1)]);
    assert_eq!(controller.lessons.current, Some(0), "the first lesson when none is shown");
    controller.apply([Action::StepLesson(1), Action::StepLesson(1), Action::StepLesson(-1)]);
    assert_eq!(controller.lessons.current, Some(1));
    controller.apply([Action::StepLesson(-1), Action::StepLesson(-1)]);
    assert_eq!(controller.lessons.current, Some(0), "stays at the first");
    controller.apply([Action::OpenLesson(count - 1), Action::StepLesson(1)]);
    assert_eq!(controller.lessons.current, Some(count - 1), "stays at the last");
    settle(&mut controller);
    let last = &controller.lessons.catalogue[count - 1];
    assert_eq!(controller.state.frame_params(), last.apply(controller.scene()).unwrap().frame_params());
}

#[test]
fn presenting_hides_the_panel_and_fills_the_screen_and_the_same_keys_undo_it() {
    let mut controller = controller();
    assert!(!controller.lessons.panel_hidden && !controller.lessons.fullscreen);
    controller.apply([Action::TogglePanel, Action::ToggleFullscreen]);
    assert!(controller.lessons.panel_hidden && controller.lessons.fullscreen);
    controller.apply([Action::TogglePanel, Action::ToggleFullscreen]);
    assert!(!controller.lessons.panel_hidden && !controller.lessons.fullscreen);
}

/// In a bump-split lesson B changes neither half: the viewer says why instead of doing
/// nothing visibly; with the split off, B toggles bump as ever and says nothing.
#[test]
fn a_key_the_split_overrides_says_why() {
    let mut controller = controller();
    controller.lessons.second_adapter = false;
    let index = controller.lessons.catalogue.iter().position(|l| l.name == "bump-off-on").unwrap();
    controller.apply([Action::OpenLesson(index)]);
    settle(&mut controller);
    controller.apply([Action::Viewer(Command::ToggleBump)]);
    let status = format!("{:?}", controller.files.status);
    assert!(status.contains("sets this per half (bump off │ bump on)"), "{status}");
    controller.apply([Action::Viewer(Command::SetSplit(false))]);
    controller.files.status = None;
    let bump = controller.state.shading.bump_enabled;
    controller.apply([Action::Viewer(Command::ToggleBump)]);
    assert!(controller.files.status.is_none() && controller.state.shading.bump_enabled != bump);
}

/// Waits (120 s at most) for the grid's worker to deliver tiles after `serial`.
fn tiles_after(controller: &mut Controller, serial: u64) -> Vec<image::RgbaImage> {
    let started = Instant::now();
    loop {
        controller.poll_background(Instant::now());
        if let Some(tiles) = controller.lessons.grid.shown().filter(|t| t.serial > serial) {
            return tiles.pictures.clone().unwrap_or_else(|e| panic!("{e}"));
        }
        assert!(started.elapsed() < Duration::from_secs(120), "no tiles arrived");
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// A grid lesson shows as its grid: each tile the picture the slide draws (two tangent
/// methods: two scenes), turning with the view's camera; B leaves the grid for the last tile and
/// says so.
#[test]
fn a_grid_lesson_shows_the_slides_tiles_follows_the_camera_and_b_leaves_it() {
    let mut controller = controller();
    let index = controller.lessons.catalogue.iter().position(|l| l.name == "tangent-methods").unwrap();
    controller.apply([Action::OpenLesson(index)]);
    settle(&mut controller);
    assert!(controller.lessons.grid_lesson().is_some(), "a grid lesson opens as its grid");
    let size = [160, 90];
    controller.ask_grid_tiles(size);
    let tiles = tiles_after(&mut controller, 0);
    let lesson = controller.lessons.catalogue[index].clone();
    let gpu = Gpu::headless().unwrap();
    let slide = measure(&mut Renderer::from_gpu(&gpu), &mut SceneCache::default(), &lesson, size, false).unwrap();
    assert_eq!(tiles.len(), 2);
    assert!(tiles == slide.sides, "the tiles are the slide's pictures at the lesson's own view");

    controller.apply([Action::Viewer(Command::OrbitCamera { d_yaw: 0.4, d_pitch: 0.1 })]);
    assert!(controller.lessons.grid_lesson().is_some(), "the camera keeps the grid");
    controller.ask_grid_tiles(size);
    let turned = tiles_after(&mut controller, 1);
    assert!(turned.iter().zip(&tiles).all(|(a, b)| a != b), "every tile turns with the camera");

    controller.apply([Action::Viewer(Command::ToggleBump)]);
    assert!(controller.lessons.grid_lesson().is_none(), "B leaves the grid for the live view");
    let status = format!("{:?}", controller.files.status);
    assert!(status.contains("left the lesson's grid for its last tile (MikkTSpace)"), "{status}");
    // The card's measurement runs on an adapter of its own: let it end before the process does.
    let started = Instant::now();
    while controller.lessons.measurement == Some(Measurement::Running) {
        assert!(started.elapsed() < Duration::from_secs(120), "the measurement did not end");
        controller.poll_background(Instant::now());
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// "Save as lesson" writes the split view as a lesson file that reads back as the same
/// comparison and opens it as a lesson; without a split view it says why and writes nothing.
#[test]
fn save_as_lesson_writes_the_split_view_and_opens_it() {
    let mut controller = controller();
    controller.lessons.second_adapter = false;
    let dir = std::env::temp_dir().join(format!("bumpview-save-lesson-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("my-strengths.toml");
    let words = LessonWords { title: "Strength".into(), caption: "Half and double.".into(), claim: "{changed}".into() };
    controller.apply([Action::Viewer(Command::SetSplit(false))]);
    controller.apply([Action::SaveLesson { path: path.clone(), words: words.clone() }]);
    let message = format!("{:?}", controller.lessons.draft_message);
    assert!(message.contains("turn the split view on") && !path.exists(), "{message}");

    let count = controller.lessons.catalogue.len();
    controller.apply([
        Action::Viewer(Command::SetSplitDifference(SplitDifference::Strength)),
        Action::Viewer(Command::SetSplitStrengths([0.5, 2.0])),
        Action::Viewer(Command::SetSplit(true)),
        Action::SaveLesson { path: path.clone(), words },
    ]);
    assert!(matches!(controller.lessons.draft_message, Some(Ok(_))), "{:?}", controller.lessons.draft_message);
    let saved = Lesson::load(&path).unwrap();
    assert_eq!(controller.lessons.catalogue.len(), count + 1);
    assert_eq!(controller.lessons.lesson(), Some(&saved), "shown as the current lesson");
    assert_eq!(saved.title, "Strength");
    assert_eq!(saved.apply(controller.scene()).unwrap().frame_params(), controller.state.frame_params());
    std::fs::remove_dir_all(&dir).unwrap();
}
