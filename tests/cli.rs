//! The `bumpview render` command as a user runs it: a PNG on success, one line and a
//! non-zero status on any failure.

use std::process::Command;

use bumpview::render::export::caption_strip_height;
use image::GenericImageView;

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
    let cases: [(&[&str], i32); 22] = [
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
        (&["render", "--out", "x.png", "--split", "compression", "--split-sides", "dds-bc1,dds-bc5"], 2),
        (&["render", "--out", "x.png", "--split", "compression", "--split-sides", "uncompressed,bc6h"], 2),
        (&["render", "--out", "x.png", "--grid", "flat,shiny"], 2),
        (&["render", "--out", "x.png", "--grid", "flat;bumped,tangent"], 2),
        (&["render", "--out", "x.png", "--row", "--grid"], 2),
        (&["render", "--out", "x.png", "--light", "1,2,3:1,1,1:-1"], 2),
        (&["render", "--out", "x.png", "--attenuation", "0,0,0"], 2),
        (&["render", "--out", "x.png", "--shininess", "0.5"], 2),
        (&["render", "--out", "x.png", "--specular", "shiny"], 2),
        (&["render", "--out", "x.png", "--directional-light", "0,0,0"], 2),
        (
            &[
                "render", "--out", "x.png", "--light", "0,1,0", "--light", "0,1,0", "--light", "0,1,0", "--light",
                "0,1,0", "--light", "0,1,0", "--light", "0,1,0", "--light", "0,1,0", "--light", "0,1,0", "--light",
                "0,1,0",
            ],
            2,
        ),
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

/// A bad command line's message is whole: what is wrong and what is allowed (the missing
/// flag, the flag it conflicts with, the possible values), on one `bumpview:` line and the
/// lines clap adds under it, exit status 2.
#[test]
fn command_line_errors_name_the_problem_and_what_is_allowed() {
    let cases: [(&[&str], &[&str]); 8] = [
        (&["render"], &["required", "--out"]),
        (&["render", "--out", "x.png", "--captions"], &["required", "--row", "--grid"]),
        (&["render", "--out", "x.png", "--split-sides", "1,2"], &["required", "--split"]),
        (&["render", "--out", "x.png", "--cube-map-size", "16"], &["required", "--legacy"]),
        (&["--capture-window", "x.png"], &["required", "--exit-after"]),
        (&["render", "--frames", "5", "--row"], &["cannot be used with", "--row"]),
        (&["render", "--out", "x.png", "--legacy", "dot3", "--cube-map-size", "12"], &["'12'", "8, 16, 32, 64"]),
        (&["render", "--out", "x.png", "--view", "sideways"], &["'sideways'", "lit", "shading-normal"]),
    ];
    for (args, expected) in cases {
        let output = bumpview(args);
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(2), "{args:?}: {stderr}");
        assert_eq!(stderr_lines(&output).len(), 1, "{args:?}: {stderr}");
        for text in expected {
            assert!(stderr.contains(text), "{args:?}: {text:?} missing from {stderr}");
        }
    }
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

/// `render`'s picture flags are the viewer's commands, so an out-of-range value is clamped as
/// the panel clamps it (README, *Headless pictures*): strength 10 draws strength 4's picture and
/// is saved as 4, a pitch of 100° is 89° and a distance of 10⁶ m is 500 m; a divider outside
/// the view is still a bad value (exit 2).
#[test]
fn out_of_range_values_are_clamped_as_in_the_viewer() {
    use bumpview::scene::builtin::teaching_scene;
    use bumpview::state::{Command as ViewerCommand, ViewerState};

    let dir = std::env::temp_dir().join(format!("bumpview-cli-clamp-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = |name: &str| dir.join(name).to_str().unwrap().to_owned();
    let render = |png: &str, extra: &[&str]| {
        let (out, saved) = (path(png), path(&format!("{png}.toml")));
        let mut args = vec!["render", "--out", &out, "--size", "96x64", "--save-preset", &saved];
        args.extend(extra);
        let output = bumpview(&args);
        assert!(output.status.success(), "{args:?}: {}", String::from_utf8_lossy(&output.stderr));
        (image::open(&out).unwrap().to_rgba8(), std::fs::read_to_string(&saved).unwrap())
    };
    let mut viewer = ViewerState::new(&teaching_scene());
    viewer.apply(ViewerCommand::SetStrength(10.0));
    let clamped = viewer.shading.strength;
    assert_eq!(clamped, 4.0);

    let (too_strong, saved) = render("strong.png", &["--strength", "10"]);
    let (strongest, _) = render("strongest.png", &["--strength", &clamped.to_string()]);
    assert!(saved.contains(&format!("strength = {clamped:?}")), "{saved}");
    assert_eq!(too_strong, strongest, "strength 10 draws the clamped strength's picture");

    let (_, saved) = render("far.png", &["--camera", "30,100,1000000"]);
    assert!(saved.contains("pitch_deg = 89.0") && saved.contains("distance = 500.0"), "{saved}");

    let output = bumpview(&["render", "--out", &path("x.png"), "--split", "bump", "--split-at", "-0.5"]);
    assert_eq!(output.status.code(), Some(2));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `--help` lists every name an enum flag takes, from the enum itself.
#[test]
fn help_lists_every_view_and_method() {
    use bumpview::frame::ViewMode;
    use bumpview::names::Named;
    use bumpview::tangent::TangentMethod;

    let output = bumpview(&["render", "--help"]);
    assert!(output.status.success());
    let help = String::from_utf8_lossy(&output.stdout);
    for name in ViewMode::names().into_iter().chain(TangentMethod::names()) {
        assert!(help.contains(name), "render --help does not name {name}:\n{help}");
    }
    let viewer_help = String::from_utf8_lossy(&bumpview(&["--help"]).stdout).into_owned();
    assert!(!viewer_help.contains("not yet shaded"), "{viewer_help}");
}

/// `render --frames N` prints one line on stdout, `frame <ms> ms, floor <ms> ms, ratio <r>`
/// (medians, two decimals; the ratio of the unrounded medians), for full-quality frames and
/// with `--interactive` for the viewer's interactive ones. No timing is asserted: only the
/// line's form and that its numbers agree.
#[test]
fn frames_prints_frame_floor_and_ratio() {
    for extra in [&[][..], &["--interactive"], &["--split", "bump", "--view", "normal"]] {
        let mut args = vec!["render", "--frames", "3", "--size", "64x48"];
        args.extend(extra);
        let output = bumpview(&args);
        assert!(output.status.success(), "{args:?}: {}", String::from_utf8_lossy(&output.stderr));
        let stdout = String::from_utf8(output.stdout).unwrap();
        let lines: Vec<&str> = stdout.lines().collect();
        assert_eq!(lines.len(), 1, "{stdout:?}");
        let number = |text: &str| {
            let (whole, decimals) = text.split_once('.').unwrap_or_else(|| panic!("{text:?} in {stdout:?}"));
            assert!(whole.chars().all(|c| c.is_ascii_digit()) && !whole.is_empty(), "{stdout:?}");
            assert!(decimals.len() == 2 && decimals.chars().all(|c| c.is_ascii_digit()), "{stdout:?}");
            text.parse::<f64>().unwrap()
        };
        let rest = lines[0].strip_prefix("frame ").unwrap_or_else(|| panic!("{stdout:?}"));
        let (frame, rest) = rest.split_once(" ms, floor ").unwrap_or_else(|| panic!("{stdout:?}"));
        let (floor, ratio) = rest.split_once(" ms, ratio ").unwrap_or_else(|| panic!("{stdout:?}"));
        let (frame, floor, ratio) = (number(frame), number(floor), number(ratio));
        assert!(floor > 0.0 && frame > 0.0, "{stdout:?}");
        // Each printed median is rounded to 0.005 ms, the ratio to 0.005.
        let slack = 0.005 + 0.005 * (1.0 + ratio) / floor;
        assert!((ratio - frame / floor).abs() <= slack, "{stdout:?}");
    }
}

/// `--frames` draws instead of writing: with `--out`, 0 frames, or `--interactive` without it
/// is a bad flag (exit 2, one line).
#[test]
fn frames_flag_errors() {
    let cases: [&[&str]; 4] = [
        &["render", "--frames", "0"],
        &["render", "--frames", "3", "--out", "x.png"],
        &["render", "--interactive", "--out", "x.png"],
        &["render", "--frames", "3", "--row"],
    ];
    for args in cases {
        let output = bumpview(args);
        assert_eq!(output.status.code(), Some(2), "{args:?}: {}", String::from_utf8_lossy(&output.stderr));
        assert_eq!(stderr_lines(&output).len(), 1, "{args:?}: {:?}", String::from_utf8_lossy(&output.stderr));
    }
}

/// The caption strip `--parallax steep --parallax-layers 16 --grid bumped --captions` should
/// draw under its 96 × 64 tile: the library's caption of that tile (checked to name the
/// technique and its layers, the view, the strength, the convention and the tangents), drawn
/// as `render_grid` draws captions.
fn steep_caption_strip() -> image::RgbaImage {
    use bumpview::frame::{Parallax, SceneUploads};
    use bumpview::render::capture::CaptureOptions;
    use bumpview::render::export::{TileGrid, caption, render_grid, wrap_caption};
    use bumpview::state::{Command as ViewerCommand, ViewerState};

    let scene = bumpview::scene::builtin::teaching_scene();
    let mut state = ViewerState::new(&scene);
    state.apply(ViewerCommand::SetParallax(Parallax::Steep));
    state.apply(ViewerCommand::SetParallaxLayers([16, 16]));
    let grid = TileGrid::parse("bumped", &state.shading).unwrap();
    let gpu = bumpview::render::Gpu::headless().unwrap();
    let mut renderer = bumpview::render::Renderer::from_gpu(&gpu);
    let uploads = SceneUploads { main: state.scene_options_drawing(&grid.tiles), split_right: None };
    renderer.set_scene_uploads(&scene, &uploads);
    let lines = caption(&renderer, &scene, &state.scene_options, &grid.tiles[0]);
    let expected = [
        "Lit: bump × colour".to_owned(),
        "bump on, strength 1.00".to_owned(),
        "normal map: OpenGL (+Y)".to_owned(),
        "tangents: auto: meshopt".to_owned(),
        "parallax: steep, 16 layers".to_owned(),
    ];
    assert_eq!(lines, expected);
    let wrapped = wrap_caption(&lines, 96).len();
    assert!(wrapped > 5, "the lines wrap to the 96-pixel tile: {wrapped}");
    let picture =
        render_grid(&mut renderer, &CaptureOptions::plain([96, 64]), &state.frame_params(), &grid, Some(&[lines]))
            .unwrap();
    assert_eq!(picture.height(), 64 + caption_strip_height(96, wrapped), "a strip of the wrapped lines");
    picture.view(0, 64, 96, picture.height() - 64).to_image()
}

/// The parallax flags reach the picture and the saved preset; depth 0 is the plain picture;
/// layers outside 1–256, steps over 16 and a negative depth are bad values (exit 2); tile
/// captions name the technique and its layers; `--split parallax` takes two techniques.
#[test]
fn parallax_flags_draw_save_and_caption_the_technique() {
    let dir = std::env::temp_dir().join(format!("bumpview-cli-parallax-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = |name: &str| dir.join(name).to_str().unwrap().to_owned();
    let render = |png: &str, extra: &[&str]| {
        let out = path(png);
        let mut args = vec!["render", "--out", &out, "--size", "96x64", "--camera", "60,0,0.5"];
        args.extend(extra);
        let output = bumpview(&args);
        assert!(output.status.success(), "{args:?}: {}", String::from_utf8_lossy(&output.stderr));
        image::open(&out).unwrap().to_rgba8()
    };
    let saved = path("relief.toml");
    let plain = render("plain.png", &[]);
    let relief = render(
        "relief.png",
        &["--parallax", "relief", "--parallax-layers", "4,64", "--parallax-steps", "3", "--save-preset", &saved],
    );
    assert_ne!(plain, relief, "the relief shows at 60°");
    let preset = std::fs::read_to_string(&saved).unwrap();
    for line in ["parallax = \"relief\"", "parallax_layers = [4, 64]", "parallax_steps = 3"] {
        assert!(preset.contains(line), "{line} in {preset}");
    }
    let flat = render("flat.png", &["--parallax", "occlusion", "--parallax-depth", "0"]);
    assert_eq!(plain, flat, "depth 0 is plain normal mapping");
    render("split.png", &["--split", "parallax", "--split-sides", "offset,relief"]);
    let grid =
        render("grid.png", &["--parallax", "steep", "--parallax-layers", "16", "--grid", "bumped", "--captions"]);
    assert_eq!(steep_caption_strip(), grid.view(0, 64, 96, grid.height() - 64).to_image(), "the steep tile's caption");

    for bad in [&["--parallax-layers", "0,8"][..], &["--parallax-layers", "8,300"], &["--parallax-steps", "17"]] {
        let output = bumpview(&[&["render", "--out", &path("bad.png")][..], bad].concat());
        assert_eq!(output.status.code(), Some(2), "{bad:?}");
    }
    let output = bumpview(&["render", "--out", &path("bad.png"), "--parallax-depth=-0.01"]);
    assert_eq!(output.status.code(), Some(2));
    assert_eq!(stderr_lines(&output).len(), 1);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// What the renderer could not do as asked is said on stderr, one line each: a mesh without
/// texture coordinates drawn without the normal map given for it.
#[test]
fn render_says_what_it_drew_otherwise_than_asked() {
    let dir = std::env::temp_dir().join(format!("bumpview-cli-notices-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("flat.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//1\n").unwrap();
    image::RgbaImage::from_pixel(4, 4, image::Rgba([128, 128, 255, 255])).save(dir.join("n.png")).unwrap();
    let (obj, normal, out) = (dir.join("flat.obj"), dir.join("n.png"), dir.join("out.png"));
    let output = bumpview(&[
        "render",
        obj.to_str().unwrap(),
        "--normal",
        normal.to_str().unwrap(),
        "--size",
        "64x48",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    let lines = stderr_lines(&output);
    let notices: Vec<&String> = lines.iter().filter(|l| l.starts_with("bumpview: notice: ")).collect();
    assert_eq!(notices.len(), 1, "{lines:?}");
    assert!(notices[0].contains("has no texture coordinates: drawn without its bump map"), "{lines:?}");
    std::fs::remove_dir_all(&dir).unwrap();
}
