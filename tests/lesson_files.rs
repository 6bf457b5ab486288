//! Lessons a lecturer writes: a lesson file beside its own model, drawn by
//! `bumpview slides --lesson FILE` and `--lessons-dir DIR` from any working directory, loaded
//! as a preset by `bumpview render --preset FILE`, and its mistakes reported on one line with
//! the file, the line and the key.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn bumpview(args: &[&str]) -> Output {
    // From the file system's root, so that nothing resolves against the repository.
    Command::new(env!("CARGO_BIN_EXE_bumpview")).current_dir("/").args(args).output().expect("run bumpview")
}

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).lines().filter(|l| l.starts_with("bumpview:")).collect()
}

/// A fresh folder with a lecture in it: `model/` holds a copy of the NormalTangentTest glTF
/// (from outside the repository's assets, as a lecturer's own model is), `my-lesson.toml`
/// names it relative to itself.
fn lecture(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("bumpview-lesson-files-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let model = dir.join("lecture/model");
    std::fs::create_dir_all(&model).unwrap();
    let source = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/gltf/NormalTangentTest/glTF");
    for entry in std::fs::read_dir(source).unwrap() {
        let entry = entry.unwrap();
        std::fs::copy(entry.path(), model.join(entry.file_name())).unwrap();
    }
    let lesson = r#"
title = "My model: bump off | on"
caption = "The normal map of my own model, off and on."
claim = "The normal map changes {changed} of the picture."
labels = ["bump off", "bump on"]

[preset.files]
mesh = "model/NormalTangentTest.gltf"

[preset.split]
enabled = true
difference = "bump"
"#;
    std::fs::write(dir.join("lecture/my-lesson.toml"), lesson).unwrap();
    dir
}

#[test]
fn a_lesson_file_draws_its_own_model_from_anywhere() {
    let dir = lecture("own-model");
    let lesson = dir.join("lecture/my-lesson.toml");
    let deck = dir.join("deck");
    let args = ["slides", "--lesson", lesson.to_str().unwrap(), "--out", deck.to_str().unwrap(), "--size", "480x270"];
    let output = bumpview(&args);
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(String::from_utf8_lossy(&output.stdout).contains("The normal map changes"));
    let slide = image::open(deck.join("01-my-lesson.png")).unwrap().to_rgba8();
    assert_eq!(slide.dimensions(), (480, 270));

    // The same file is a preset: `render` draws its state.
    let picture = dir.join("picture.png");
    let output = bumpview(&["render", "--preset", lesson.to_str().unwrap(), "--out", picture.to_str().unwrap()]);
    assert!(output.status.success(), "{}", stderr(&output));

    // The slide came from the lesson's own model: without it, the deck names the missing file.
    std::fs::remove_file(dir.join("lecture/model/NormalTangentTest.gltf")).unwrap();
    let output = bumpview(&[&args[..3], &["--out", dir.join("deck2").to_str().unwrap()]].concat());
    assert_eq!(output.status.code(), Some(1));
    assert!(stderr(&output).contains("NormalTangentTest.gltf"), "{}", stderr(&output));
}

#[test]
fn a_folder_of_lessons_is_drawn_in_name_order() {
    let dir = lecture("folder");
    let folder = dir.join("lecture");
    std::fs::copy(folder.join("my-lesson.toml"), folder.join("another.toml")).unwrap();
    let deck = dir.join("deck");
    let output = bumpview(&[
        "slides",
        "--lessons-dir",
        folder.to_str().unwrap(),
        "--out",
        deck.to_str().unwrap(),
        "--size",
        "480x270",
    ]);
    assert!(output.status.success(), "{}", stderr(&output));
    assert!(deck.join("01-another.png").is_file() && deck.join("02-my-lesson.png").is_file());
}

#[test]
fn a_mistake_is_one_line_naming_the_file_the_line_and_the_key() {
    let dir = lecture("mistake");
    let lesson = dir.join("lecture/my-lesson.toml");
    let text = std::fs::read_to_string(&lesson).unwrap().replace("difference = \"bump\"", "diference = \"bump\"");
    std::fs::write(&lesson, text).unwrap();
    let output =
        bumpview(&["slides", "--lesson", lesson.to_str().unwrap(), "--out", dir.join("deck").to_str().unwrap()]);
    assert_eq!(output.status.code(), Some(1));
    let message = stderr(&output);
    assert_eq!(message.lines().count(), 1, "{message}");
    assert!(
        message.contains("my-lesson.toml") && message.contains("line 12") && message.contains("diference"),
        "{message}"
    );
}
