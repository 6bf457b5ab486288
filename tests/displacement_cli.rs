//! Displacement, self-shadows and parallax tiles on the command line: the flags reach the
//! picture, stderr and the saved preset, which draws the same picture again; bad values are
//! errors naming the flag or key.

use std::process::Command;

fn bumpview(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_bumpview")).args(args).output().unwrap()
}

#[test]
fn displacement_and_shadows_draw_report_and_round_trip_through_a_preset() {
    let dir = std::env::temp_dir().join(format!("bumpview-displacement-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = |name: &str| dir.join(name).to_str().unwrap().to_owned();
    let run = |extra: &[&str]| {
        let mut args = vec!["render", "--size", "96x64", "--camera", "60,0,0.5"];
        args.extend(extra);
        let output = bumpview(&args);
        assert!(output.status.success(), "{args:?}: {}", String::from_utf8_lossy(&output.stderr));
        output
    };
    let (flags, preset, again) = (path("flags.png"), path("saved.toml"), path("again.png"));
    let output = run(&[
        "--out",
        &flags,
        "--displacement",
        "2",
        "--parallax",
        "occlusion",
        "--parallax-shadows",
        "--split",
        "displacement",
        "--split-sides",
        "relief,3",
        "--save-preset",
        &preset,
    ]);
    // The split's left half draws the parallax technique undisplaced, its right half level 3.
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains("bumpview: displacement (split right): level 3:"), "{stderr}");
    assert!(!stderr.contains("bumpview: displacement: level"), "{stderr}");
    let alone = run(&["--out", &path("alone.png"), "--displacement", "2"]);
    let stderr = String::from_utf8_lossy(&alone.stderr);
    assert!(stderr.contains("bumpview: displacement: level 2:") && stderr.contains("vertices"), "{stderr}");
    let text = std::fs::read_to_string(&preset).unwrap();
    for line in
        ["displacement = 2", "parallax_shadows = 1.0", "difference = \"displacement\"", "displacement_level = 3"]
    {
        assert!(text.contains(line), "{line} in {text}");
    }
    run(&["--preset", &preset, "--out", &again]);
    assert_eq!(std::fs::read(&flags).unwrap(), std::fs::read(&again).unwrap(), "identical PNG bytes");

    let grid = path("grid.png");
    run(&["--out", &grid, "--grid", "off,steep:8,occlusion:32", "--captions"]);
    assert!(image::open(&grid).unwrap().height() > 64, "a caption strip");

    for bad in [
        &["--displacement", "11"][..],
        &["--parallax-shadows", "5"],
        &["--parallax-shadows", "-1"],
        &["--split", "displacement", "--split-sides", "occlusion,0"],
        &["--grid", "occlusion:0"],
        &["--grid", "bumped:8"],
    ] {
        let output = bumpview(&[&["render", "--out", &path("bad.png")][..], bad].concat());
        assert!(!output.status.success(), "{bad:?}");
        let stderr = String::from_utf8_lossy(&output.stderr);
        // One message: its first line starts `bumpview:`, clap's may go on under it.
        assert_eq!(stderr.lines().filter(|l| l.starts_with("bumpview:")).count(), 1, "{bad:?}: {stderr}");
    }
    for (bad, key) in [
        ("[scene]\ndisplacement = 11\n", "scene.displacement"),
        ("[shading]\nparallax_shadows = 9.0\n", "shading.parallax_shadows"),
        ("[split]\ndisplacement_level = 0\n", "split.displacement_level"),
    ] {
        let broken = path("broken.toml");
        std::fs::write(&broken, bad).unwrap();
        let output = bumpview(&["render", "--preset", &broken]);
        assert_eq!(output.status.code(), Some(1), "{bad}");
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(stderr.contains(key), "{bad}: {stderr}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A level past the triangle budget is drawn lower, and render's stderr line names the level
/// asked, the level drawn and why (the built-in scene's 6400 base triangles at level 6 would be
/// 26 214 400); with no split view on, nothing is said (or built) for a right half.
#[test]
fn a_capped_level_is_named_with_the_level_asked_and_no_split_copy_is_reported() {
    let out = std::env::temp_dir().join(format!("bumpview-displacement-cap-{}.png", std::process::id()));
    let output = bumpview(&["render", "--size", "96x64", "--out", out.to_str().unwrap(), "--displacement", "6"]);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let stderr = String::from_utf8_lossy(&output.stderr);
    let budget = bumpview::frame::MAX_DISPLACED_TRIANGLES;
    let line = format!(
        "bumpview: displacement: level 5 drawn, 6 asked (26214400 triangles would pass the budget of {budget}): 3590400 vertices, 6553600 triangles,"
    );
    assert!(stderr.contains(&line), "{line}\nin\n{stderr}");
    assert!(!stderr.contains("split right"), "{stderr}");
    std::fs::remove_file(&out).unwrap();
}
