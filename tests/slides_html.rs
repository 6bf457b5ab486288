//! `bumpview slides --html`: a page of the slides whose built-in lessons open live in the web
//! build copied beside it, and a clear refusal when there is no web build to copy.

use std::path::PathBuf;
use std::process::Command;

/// A fresh folder for one test.
fn folder(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("bumpview-slides-html-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A stand-in for what scripts/build-web.sh makes: the page, its script and its wasm.
fn web_build(dir: &std::path::Path) -> PathBuf {
    let build = dir.join("dist");
    std::fs::create_dir_all(&build).unwrap();
    for (name, text) in [
        ("index.html", "<!DOCTYPE html><title>bumpview</title>"),
        ("bumpview.js", "// js"),
        ("bumpview_bg.wasm", "\0asm"),
    ] {
        std::fs::write(build.join(name), text).unwrap();
    }
    build
}

#[test]
fn the_html_deck_links_each_slide_to_its_lesson_live_in_the_web_build_beside_it() {
    let dir = folder("deck");
    let build = web_build(&dir);
    let out = dir.join("deck");
    let run = Command::new(env!("CARGO_BIN_EXE_bumpview"))
        .args(["slides", "--size", "480x270", "--lessons", "cg-wall,strength", "--html", "--web-build"])
        .arg(&build)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    assert!(run.status.success(), "{}", String::from_utf8_lossy(&run.stderr));
    let page = std::fs::read_to_string(out.join("index.html")).unwrap();
    for (number, name) in [(1, "cg-wall"), (2, "strength")] {
        assert!(
            page.contains(&format!("<a href=\"web/index.html#lesson={name}\"><img src=\"{number:02}-{name}.png\"")),
            "{page}"
        );
        assert!(out.join(format!("{number:02}-{name}.png")).is_file());
    }
    for name in ["index.html", "bumpview.js", "bumpview_bg.wasm"] {
        assert_eq!(
            std::fs::read(out.join("web").join(name)).unwrap(),
            std::fs::read(build.join(name)).unwrap(),
            "{name}"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn without_a_web_build_html_is_refused_before_anything_is_drawn() {
    let dir = folder("refused");
    let out = dir.join("deck");
    let run = Command::new(env!("CARGO_BIN_EXE_bumpview"))
        .args(["slides", "--lessons", "cg-wall", "--html", "--web-build"])
        .arg(dir.join("no-such-build"))
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains("make it with scripts/build-web.sh"), "{stderr}");
    assert!(!out.exists(), "nothing is written");
    std::fs::remove_dir_all(&dir).unwrap();
}
