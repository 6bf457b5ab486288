//! The `bumpview render` command as a user runs it: a PNG on success, one line and a
//! non-zero status on any failure.

use std::process::Command;

fn bumpview(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_bumpview")).args(args).output().expect("run bumpview")
}

fn stderr_lines(output: &std::process::Output) -> Vec<String> {
    // Drivers may log their own lines (e.g. about XDG_RUNTIME_DIR); ours start with "bumpview:".
    String::from_utf8_lossy(&output.stderr).lines().filter(|l| l.starts_with("bumpview:")).map(str::to_owned).collect()
}

#[test]
fn render_writes_a_png_of_the_requested_size() {
    let dir = std::env::temp_dir().join(format!("bumpview-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("wall.png");
    let output = bumpview(&[
        "render",
        "--out",
        out.to_str().unwrap(),
        "--size",
        "200x120",
        "--view",
        "shading-normal",
        "--bump",
        "on",
        "--strength",
        "-1.5",
        "--light",
        "-1,2,1.5",
        "--camera",
        "10,15,4",
    ]);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let image = image::open(&out).unwrap();
    assert_eq!((image.width(), image.height()), (200, 120));
    // Not blank: the picture has more than one colour.
    let rgb = image.to_rgb8();
    let first = rgb.get_pixel(0, 0);
    assert!(rgb.pixels().any(|p| p != first));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Bad flags and values exit 2, failures of the work itself 1; either prints one line.
#[test]
fn failures_exit_non_zero_with_one_line() {
    let cases: [(&[&str], i32); 14] = [
        (&["render", "--out", "x.png", "--frobnicate"], 2),
        (&["render", "--out", "x.png", "--view", "sideways"], 2),
        (&["render", "--out", "x.png", "--size", "0x10"], 2),
        (&["render", "--out", "x.png", "--light", "1,2"], 2),
        (&["render", "--out", "x.png", "--bump", "maybe"], 2),
        (&["render", "--out", "x.png", "--height-kernel", "median"], 2),
        (&["render", "--out", "x.png", "--height-border", "mirror"], 2),
        (&["render", "--out", "x.png", "--camera=0,0,-1"], 2),
        (&["render", "--out", "x.png", "--split", "view", "--split-at", "1.5"], 2),
        (&["render", "--out", "x.png", "--split", "tangents", "--split-sides", "mikktspace,bogus"], 2),
        (&["render", "--out", "x.png", "--grid", "flat,shiny"], 2),
        (&["render", "--out", "x.png", "--grid", "flat;bumped,tangent"], 2),
        (&["render", "--out", "x.png", "--row", "--grid"], 2),
        (&["render", "--out", "/nonexistent-dir/x.png", "--size", "16x16"], 1),
    ];
    for (args, code) in cases {
        let output = bumpview(args);
        assert_eq!(output.status.code(), Some(code), "{args:?}: {}", String::from_utf8_lossy(&output.stderr));
        let lines = stderr_lines(&output);
        assert_eq!(lines.len(), 1, "{args:?}: {:?}", String::from_utf8_lossy(&output.stderr));
    }
    let unwritable = bumpview(&["render", "--out", "/nonexistent-dir/x.png", "--size", "16x16"]);
    assert!(stderr_lines(&unwritable)[0].contains("/nonexistent-dir/x.png"));
    let grid = bumpview(&["render", "--out", "x.png", "--grid", "flat,shiny"]);
    assert!(stderr_lines(&grid)[0].contains("shading-normal"), "{:?}", stderr_lines(&grid));
}

/// `--height-kernel` re-makes loaded height maps' normal maps: on the built-in scene it gives
/// the picture `--kernel` (which makes the brick map from the exact height field) gives, up
/// to the 16-bit height texture, and not the default central-difference one (measured close
/// to the wall: max 2 and 11 steps).
#[test]
fn height_kernel_remakes_the_normal_map_from_the_height_map() {
    let dir = std::env::temp_dir().join(format!("bumpview-cli-kernel-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let render = |name: &str, extra: &[&str]| {
        let out = dir.join(name);
        let out = out.to_str().unwrap();
        let mut args =
            vec!["render", "--out", out, "--size", "640x480", "--view", "shading-normal", "--camera", "0,0,0.1"];
        args.extend(extra);
        let output = bumpview(&args);
        assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
        image::open(out).unwrap().to_rgb8()
    };
    let max_diff = |a: &image::RgbImage, b: &image::RgbImage| {
        a.as_raw().iter().zip(b.as_raw()).map(|(p, q)| p.abs_diff(*q)).max().unwrap()
    };
    let central = render("central.png", &[]);
    let built_in_sobel = render("kernel.png", &["--kernel", "sobel3"]);
    let remade_sobel = render("height-kernel.png", &["--height-kernel", "sobel3", "--height-border", "wrap"]);
    let (same, other) = (max_diff(&built_in_sobel, &remade_sobel), max_diff(&central, &remade_sobel));
    println!("--height-kernel sobel3: max {same} steps from --kernel sobel3, {other} from central");
    assert!(same <= 3 && other >= 8, "{same} {other}");
    std::fs::remove_dir_all(&dir).ok();
}
