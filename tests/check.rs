//! `bumpview check` as a user runs it: a report per file, exit 0 when clean, 1 with warnings
//! only, 2 with errors.

mod common;

use std::path::Path;
use std::process::Command;

use common::{asset, assets};

fn check(files: &[&Path]) -> (i32, String) {
    let output = Command::new(env!("CARGO_BIN_EXE_bumpview")).arg("check").args(files).output().expect("run bumpview");
    (output.status.code().expect("exit code"), String::from_utf8_lossy(&output.stdout).into_owned())
}

/// A file that does not load is an error: exit 2, and the report names the file.
#[test]
fn a_broken_file_is_an_error() {
    let dir = std::env::temp_dir().join(format!("bumpview-check-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let broken = dir.join("broken.gltf");
    std::fs::write(&broken, "{ not json").unwrap();
    let (code, text) = check(&[&broken]);
    assert_eq!(code, 2, "{text}");
    assert!(text.contains("broken.gltf") && text.contains("error"), "{text}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// NormalTangentTest is clean and its map reads as OpenGL (glTF's convention); the same model
/// with the normal map's green channel flipped gets a DirectX warning (exit 1); Suzanne's
/// supplied tangents are not orthogonal to its normals (a warning).
#[test]
fn conventions_and_tangents_of_real_files() {
    let base = assets();
    let model = asset(&base, "gltf/NormalTangentTest/glTF/NormalTangentTest.gltf");
    let (code, text) = check(&[&model]);
    assert_eq!(code, 0, "{text}");
    assert!(text.contains("green: OpenGL"), "{text}");

    let dir = std::env::temp_dir().join(format!("bumpview-check-flip-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for entry in std::fs::read_dir(model.parent().unwrap()).unwrap().map(Result::unwrap) {
        std::fs::copy(entry.path(), dir.join(entry.file_name())).unwrap();
    }
    let normal_png = dir.join("NormalTangentTest_Normal.png");
    let mut image = image::open(&normal_png).unwrap().to_rgba8();
    image.pixels_mut().for_each(|p| p[1] = 255 - p[1]);
    image.save(&normal_png).unwrap();
    let (code, text) = check(&[&dir.join("NormalTangentTest.gltf")]);
    assert_eq!(code, 1, "{text}");
    assert!(text.contains("green looks DirectX"), "{text}");
    std::fs::remove_dir_all(&dir).unwrap();

    let suzanne = asset(&base, "gltf/Suzanne/glTF/Suzanne.gltf");
    let (code, text) = check(&[&suzanne]);
    assert_eq!(code, 1, "{text}");
    assert!(text.contains("not orthogonal to the normal"), "{text}");
}

/// An image is checked as a normal map and says which layout it is read with and why; the
/// brick map with blue made constant reads as RGB but suggests `rg` (a warning, exit 1);
/// `--normal-layout rg` reads it so, and says it was given.
#[test]
fn an_image_reports_its_layout_and_why() {
    let dir = std::env::temp_dir().join(format!("bumpview-check-layout-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let scene = common::scene();
    let map = &scene.textures[scene.materials[0].normal_map.as_ref().unwrap().texture];
    let save = |name: &str, rgba: Vec<u8>| {
        let path = dir.join(name);
        image::RgbaImage::from_raw(map.width, map.height, rgba).unwrap().save(&path).unwrap();
        path
    };
    let rgb = save("bricks.png", map.rgba.clone());
    let (code, text) = check(&[&rgb]);
    assert_eq!(code, 0, "{text}");
    assert!(text.contains("layout: rgb (as loaded, and red, green and blue vary)"), "{text}");
    let mut two = map.rgba.clone();
    two.chunks_exact_mut(4).for_each(|t| t[2] = 0);
    let rg = save("bricks-rg.png", two);
    let (code, text) = check(&[&rg]);
    assert_eq!(code, 1, "{text}");
    assert!(text.contains("layout: rgb (as loaded, although blue is constant)"), "{text}");
    assert!(text.contains("blue is constant, which suggests --normal-layout rg"), "{text}");
    let output = Command::new(env!("CARGO_BIN_EXE_bumpview"))
        .args(["check", "--normal-layout", "rg"])
        .arg(&rg)
        .output()
        .expect("run bumpview");
    let text = String::from_utf8_lossy(&output.stdout);
    assert_eq!(output.status.code(), Some(0), "{text}");
    assert!(text.contains("layout: rg (given by --normal-layout)"), "{text}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// ClearCoatTest's coat normal maps are checked in their own slot: its ribs bend along one
/// axis only, so their green is undetermined, and the report says why.
#[test]
fn clear_coat_normal_maps_are_checked() {
    let model = asset(&assets(), "gltf/ClearCoatTest/glTF/ClearCoatTest.gltf");
    let (code, text) = check(&[&model]);
    assert!(code <= 1, "{text}");
    let coat: Vec<&str> = text.lines().filter(|l| l.contains("clear-coat normal map")).collect();
    assert!(coat.len() >= 2, "{text}");
    assert!(coat.iter().any(|l| l.contains("green: undetermined (one-directional relief)")), "{text}");
}

/// `--explain DIR` writes each map's votes as a PNG named after the file, the map's number
/// and slot; a second run keeps them (exit 2) unless `--force`.
#[test]
fn explain_writes_the_votes_and_keeps_what_exists() {
    let dir = std::env::temp_dir().join(format!("bumpview-check-explain-{}", std::process::id()));
    let model = asset(&assets(), "gltf/NormalTangentTest/glTF/NormalTangentTest.gltf");
    let explain = |extra: &[&str]| {
        let output = Command::new(env!("CARGO_BIN_EXE_bumpview"))
            .args(["check", "--explain"])
            .arg(&dir)
            .args(extra)
            .arg(&model)
            .output()
            .expect("run bumpview");
        (output.status.code(), String::from_utf8_lossy(&output.stdout).into_owned())
    };
    let (code, text) = explain(&[]);
    assert_eq!(code, Some(0), "{text}");
    let picture = dir.join("NormalTangentTest.1.normal.votes.png");
    let (width, height) = image::image_dimensions(&picture).unwrap();
    assert_eq!((width, height), (2048, 2048));
    assert!(text.contains("votes of material"), "{text}");
    let (code, text) = explain(&[]);
    assert_eq!(code, Some(2), "{text}");
    assert!(text.contains("exists and was kept"), "{text}");
    let (code, text) = explain(&["--force"]);
    assert_eq!(code, Some(0), "{text}");
    std::fs::remove_dir_all(&dir).unwrap();
}
