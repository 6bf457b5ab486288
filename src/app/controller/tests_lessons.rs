//! Lessons in the viewer: opening one shows its whole state and scene, Page Down / Page Up
//! step through the course within its ends, the state stays interactive, and presenting hides
//! the panel and fills the screen.

use bumpview::lessons::catalogue;
use bumpview::scene::teaching::TeachingScene;
use bumpview::state::Command;

use super::tests::{controller, settle};
use crate::app::action::Action;

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
