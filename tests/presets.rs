//! Presets reproduce pictures exactly (`bumpview render --preset`), and captures go beyond
//! the window: large sizes up to the adapter's limit, transparent backgrounds, supersampling.

use std::path::{Path, PathBuf};
use std::process::Command;

use bumpview::frame::SceneOptions;
use bumpview::frame::ViewMode;
use bumpview::load::SceneFiles;
use bumpview::render::capture::{CaptureOptions, render_capture};
use bumpview::render::{Background, Gpu, Renderer};
use bumpview::scene::builtin::teaching_scene;
use bumpview::state::preset::Preset;
use bumpview::state::{Command as ViewerCommand, ViewerState};
use bumpview::tangent::TangentMethod;
use glam::Vec3;

fn bumpview(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_bumpview")).args(args).output().expect("run bumpview")
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("bumpview-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn render_ok(args: &[&str]) {
    let output = bumpview(args);
    assert!(output.status.success(), "{args:?}: {}", String::from_utf8_lossy(&output.stderr));
}

fn pixels(path: &Path) -> image::RgbaImage {
    image::open(path).unwrap().to_rgba8()
}

#[test]
fn a_saved_state_renders_the_same_pixels_as_the_flags_and_again() {
    let dir = temp_dir("preset-cli");
    let s = |p: &Path| p.to_str().unwrap().to_owned();
    // The state the flags below describe, made in the library and saved as a preset.
    let scene = teaching_scene();
    let mut state = ViewerState::new(&scene);
    state.camera.yaw = 25f32.to_radians();
    state.camera.pitch = 0.0;
    state.camera.orbit(0.0, 12f32.to_radians());
    state.camera.distance = 4.5;
    state.apply(ViewerCommand::SetLightPosition(Vec3::new(-1.0, 2.0, 1.5)));
    state.apply(ViewerCommand::SetView(ViewMode::ShadingNormal));
    state.apply(ViewerCommand::SetStrength(2.5));
    state.apply(ViewerCommand::SetLightMarker(false));
    state.scene_options = SceneOptions { tangent_method: Some(TangentMethod::PerFace), ..Default::default() };
    let preset = dir.join("slide.toml");
    Preset::from_state(&state, SceneFiles::default()).save(&preset).unwrap();

    let flags = dir.join("flags.png");
    render_ok(&[
        "render",
        "--out",
        &s(&flags),
        "--size",
        "240x135",
        "--camera",
        "25,12,4.5",
        "--light=-1,2,1.5",
        "--view",
        "shading-normal",
        "--strength",
        "2.5",
        "--no-light-marker",
        "--tangents",
        "per-face",
    ]);
    let first = dir.join("first.png");
    let second = dir.join("second.png");
    for out in [&first, &second] {
        render_ok(&["render", "--preset", &s(&preset), "--out", &s(out), "--size", "240x135"]);
    }
    assert_eq!(pixels(&first), pixels(&second), "the same preset twice");
    assert_eq!(pixels(&first), pixels(&flags), "the preset and the equivalent flags");

    // A flag given with the preset wins; --save-preset writes what was drawn.
    let normal = dir.join("normal.png");
    let saved = dir.join("saved.toml");
    render_ok(&["render", "--preset", &s(&preset), "--out", &s(&normal), "--size", "240x135", "--view", "normal"]);
    assert_ne!(pixels(&normal), pixels(&first));
    render_ok(&[
        "render",
        "--preset",
        &s(&preset),
        "--view",
        "normal",
        "--save-preset",
        &s(&saved),
        "--out",
        &s(&normal),
        "--force",
    ]);
    let text = std::fs::read_to_string(&saved).unwrap();
    assert!(text.contains("view = \"normal\"") && text.contains("tangents = \"per-face\""), "{text}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A split view that needs a second upload, with glyphs: the preset `--save-preset` wrote
/// renders the picture of the flags, byte for byte, and keeps the chosen sides.
#[test]
fn a_gpu_data_split_with_glyphs_round_trips_through_a_preset() {
    let dir = temp_dir("preset-split");
    let s = |p: &Path| p.to_str().unwrap().to_owned();
    let (flags, preset, again) = (dir.join("flags.png"), dir.join("split.toml"), dir.join("again.png"));
    render_ok(&[
        "render",
        "--out",
        &s(&flags),
        "--size",
        "200x120",
        "--glyphs",
        "--view",
        "tangent",
        "--split",
        "tangents",
        "--split-sides",
        "averaged-uniform,analytic",
        "--split-at",
        "0.4",
        "--save-preset",
        &s(&preset),
    ]);
    let text = std::fs::read_to_string(&preset).unwrap();
    assert!(text.contains("tangents = [\"averaged-uniform\", \"analytic\"]"), "{text}");
    assert!(text.contains("tbn_glyphs = true") && text.contains("difference = \"tangents\""), "{text}");
    render_ok(&["render", "--preset", &s(&preset), "--out", &s(&again)]);
    assert_eq!(std::fs::read(&flags).unwrap(), std::fs::read(&again).unwrap(), "identical PNG bytes");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The parallax settings and a parallax split round-trip through a preset: the preset
/// `--save-preset` wrote renders the flags' picture byte for byte; out-of-range layers, steps
/// or depth in a preset are one line naming the key.
#[test]
fn parallax_settings_round_trip_through_a_preset() {
    let dir = temp_dir("preset-parallax");
    let s = |p: &Path| p.to_str().unwrap().to_owned();
    let (flags, preset, again) = (dir.join("flags.png"), dir.join("parallax.toml"), dir.join("again.png"));
    render_ok(&[
        "render",
        "--out",
        &s(&flags),
        "--size",
        "160x96",
        "--camera",
        "60,5,0.6",
        "--parallax",
        "relief",
        "--parallax-layers",
        "6,48",
        "--parallax-steps",
        "4",
        "--parallax-depth",
        "0.015",
        "--split",
        "parallax",
        "--split-sides",
        "offset-limited,relief",
        "--save-preset",
        &s(&preset),
    ]);
    let text = std::fs::read_to_string(&preset).unwrap();
    for line in ["parallax_layers = [6, 48]", "parallax_depth_m = 0.015", "parallax = [\"offset-limited\", \"relief\"]"]
    {
        assert!(text.contains(line), "{line} in {text}");
    }
    render_ok(&["render", "--preset", &s(&preset), "--out", &s(&again)]);
    assert_eq!(std::fs::read(&flags).unwrap(), std::fs::read(&again).unwrap(), "identical PNG bytes");
    for (bad, key) in [
        ("parallax_layers = [0, 8]", "parallax_layers"),
        ("parallax_steps = 17", "parallax_steps"),
        ("parallax_depth_m = -1.0", "parallax_depth_m"),
        ("parallax = \"bumpy\"", "shading.parallax"),
    ] {
        let broken = dir.join("broken.toml");
        std::fs::write(&broken, format!("[shading]\n{bad}\n")).unwrap();
        let output = bumpview(&["render", "--preset", &s(&broken)]);
        assert_eq!(output.status.code(), Some(1), "{bad}");
        let stderr = String::from_utf8_lossy(&output.stderr);
        let ours: Vec<_> = stderr.lines().filter(|l| l.starts_with("bumpview:")).collect();
        assert!(ours.len() == 1 && ours[0].contains(key), "{bad}: {stderr}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_broken_preset_is_one_line_naming_the_key() {
    let dir = temp_dir("preset-bad");
    let preset = dir.join("bad.toml");
    std::fs::write(&preset, "[shading]\nstrenght = 2\n").unwrap();
    let output = bumpview(&["render", "--preset", preset.to_str().unwrap()]);
    assert_eq!(output.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&output.stderr);
    let ours: Vec<_> = stderr.lines().filter(|l| l.starts_with("bumpview:")).collect();
    assert_eq!(ours.len(), 1, "{stderr}");
    assert!(ours[0].contains("bad.toml") && ours[0].contains("line 2") && ours[0].contains("strenght"), "{stderr}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The renderer on the software adapter with the built-in scene, and its default picture.
fn setup() -> (Renderer, bumpview::frame::FrameParams) {
    let gpu = Gpu::headless().expect("a GPU adapter (WGPU_BACKEND=vulkan with lavapipe)");
    let mut renderer = Renderer::from_gpu(&gpu);
    let scene = teaching_scene();
    renderer.set_scene(&scene, SceneOptions::default());
    (renderer, ViewerState::new(&scene).frame_params())
}

#[test]
fn a_4096_square_export_works_and_above_the_limit_is_a_clear_error() {
    let (mut renderer, params) = setup();
    let started = std::time::Instant::now();
    let image = render_capture(&mut renderer, &CaptureOptions::plain([4096, 4096]), &params).unwrap();
    eprintln!("4096x4096 in {:.1} s", started.elapsed().as_secs_f64());
    assert_eq!(image.dimensions(), (4096, 4096));
    let bricks = image.pixels().filter(|p| p[0] as i32 > p[1] as i32 + 30 && p[0] > 80).count();
    assert!(bricks > 4096 * 4096 / 10, "only {bricks} brick-coloured pixels");

    let limit = renderer.max_target_size();
    let error = render_capture(&mut renderer, &CaptureOptions::plain([limit + 1, 16]), &params).unwrap_err();
    assert!(error.to_string().contains(&format!("limit of {limit} pixels")), "{error}");
    let supersampled = CaptureOptions { supersample: 4, ..CaptureOptions::plain([limit / 2, 16]) };
    let error = render_capture(&mut renderer, &supersampled, &params).unwrap_err();
    assert!(error.to_string().contains(&format!("limit of {limit} pixels")), "{error}");
}

#[test]
fn a_transparent_export_is_clear_around_the_scene_and_opaque_on_the_wall() {
    let (mut renderer, params) = setup();
    let options = CaptureOptions { background: Background::Transparent, ..CaptureOptions::plain([320, 180]) };
    let image = render_capture(&mut renderer, &options, &params).unwrap();
    assert_eq!(image.get_pixel(1, 1)[3], 0, "background corner");
    let wall = image.get_pixel(160, 50);
    assert_eq!(wall[3], 255, "wall {wall:?}");
    // The opaque picture agrees with the transparent one wherever that is opaque.
    let opaque = render_capture(&mut renderer, &CaptureOptions::plain([320, 180]), &params).unwrap();
    assert_eq!(opaque.get_pixel(1, 1)[3], 255);
    let same = image.pixels().zip(opaque.pixels()).filter(|(t, _)| t[3] == 255).all(|(t, o)| t == o);
    assert!(same, "opaque pixels differ between the transparent and the plain export");
}

#[test]
fn supersampling_changes_only_edges() {
    let (mut renderer, params) = setup();
    let size = [320, 180];
    let plain = render_capture(&mut renderer, &CaptureOptions::plain(size), &params).unwrap();
    let options = CaptureOptions { supersample: 2, ..CaptureOptions::plain(size) };
    let fine = render_capture(&mut renderer, &options, &params).unwrap();
    assert_eq!(fine.dimensions(), plain.dimensions());
    let luma = |p: &image::Rgba<u8>| (p[0] as f32 + p[1] as f32 + p[2] as f32) / 3.0;
    let diff: Vec<f32> = plain.pixels().zip(fine.pixels()).map(|(a, b)| (luma(a) - luma(b)).abs()).collect();
    let mean = diff.iter().sum::<f32>() / diff.len() as f32;
    // An edge: the plain picture's 3×3 neighbourhood spans a large range of brightness
    // (silhouettes, the wall-floor fold, mortar lines).
    let (w, h) = (size[0] as i64, size[1] as i64);
    let edge = |x: i64, y: i64| {
        let around = (-1..=1).flat_map(|dy| (-1..=1).map(move |dx| (dx, dy))).map(|(dx, dy)| {
            let (nx, ny) = ((x + dx).clamp(0, w - 1), (y + dy).clamp(0, h - 1));
            luma(plain.get_pixel(nx as u32, ny as u32))
        });
        let (low, high) = around.fold((f32::MAX, f32::MIN), |(l, h), v| (l.min(v), h.max(v)));
        high - low > 16.0
    };
    let big: Vec<(i64, i64)> =
        (0..h).flat_map(|y| (0..w).map(move |x| (x, y))).filter(|&(x, y)| diff[(y * w + x) as usize] > 24.0).collect();
    let at_edges = big.iter().filter(|&&(x, y)| edge(x, y)).count();
    eprintln!("mean |Δ| {mean:.2}, {} pixels over 24 of which {at_edges} at edges", big.len());
    assert!(mean > 0.0 && mean < 4.0, "mean difference {mean}");
    assert!(at_edges * 5 >= big.len() * 4, "{at_edges} of {} large differences at edges", big.len());
    let max = diff.iter().enumerate().max_by(|a, b| a.1.total_cmp(b.1)).map(|(i, _)| i as i64).unwrap();
    assert!(edge(max % w, max / w), "the largest difference is not at an edge");
}

/// `--save-preset` writes a preset that loads from any working directory: a model given
/// relative to the working directory, outside the preset's folder, is stored absolute; one
/// inside it is stored relative to it, so the folder can move with its files. Either renders
/// the same pixels from another directory.
#[test]
fn a_preset_saved_from_one_folder_loads_from_any_other() {
    let dir = temp_dir("preset-paths");
    let fixture = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/obj/learn-wgpu-cube");
    let copy = dir.join("project/cubecopy");
    std::fs::create_dir_all(&copy).unwrap();
    for file in ["cube.obj", "cube.mtl", "cube-diffuse.jpg", "cube-normal.png"] {
        std::fs::copy(fixture.join(file), copy.join(file)).unwrap();
    }
    std::fs::create_dir_all(dir.join("project/presets")).unwrap();
    let run = |cwd: &Path, args: &[&str]| {
        let output = Command::new(env!("CARGO_BIN_EXE_bumpview")).current_dir(cwd).args(args).output().unwrap();
        assert!(output.status.success(), "{args:?} in {}: {}", cwd.display(), String::from_utf8_lossy(&output.stderr));
    };
    let project = dir.join("project");
    let small = ["--size", "48x32", "--camera", "30,20,4"];
    // Outside the preset's folder: stored absolute.
    let first = [["render", "cubecopy/cube.obj", "--color", "cubecopy/cube-diffuse.jpg"].as_slice(), &small].concat();
    run(&project, &[first.as_slice(), &["--out", "a.png", "--save-preset", "presets/cube.toml"]].concat());
    let text = std::fs::read_to_string(project.join("presets/cube.toml")).unwrap();
    let absolute = std::path::absolute(project.join("cubecopy/cube.obj")).unwrap();
    assert!(text.contains(&format!("mesh = {:?}", absolute.to_str().unwrap())), "{text}");
    let preset = project.join("presets/cube.toml");
    run(&dir, &["render", "--preset", preset.to_str().unwrap(), "--out", "b.png"]);
    assert_eq!(pixels(&project.join("a.png")), pixels(&dir.join("b.png")));
    // Inside it: stored relative, and the moved folder still loads.
    run(&project, &[first.as_slice(), &["--out", "c.png", "--save-preset", "here.toml"]].concat());
    let text = std::fs::read_to_string(project.join("here.toml")).unwrap();
    assert!(
        text.contains("mesh = \"cubecopy/cube.obj\"") && text.contains("color = \"cubecopy/cube-diffuse.jpg\""),
        "{text}"
    );
    std::fs::rename(&project, dir.join("moved")).unwrap();
    run(
        Path::new("/"),
        &[
            "render",
            "--preset",
            dir.join("moved/here.toml").to_str().unwrap(),
            "--out",
            dir.join("d.png").to_str().unwrap(),
        ],
    );
    assert_eq!(pixels(&dir.join("moved/c.png")), pixels(&dir.join("d.png")));
    std::fs::remove_dir_all(&dir).unwrap();
}
