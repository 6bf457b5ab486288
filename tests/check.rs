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
    let Some(base) = assets() else { return };
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
