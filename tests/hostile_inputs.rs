//! Hostile and careless inputs: devices, FIFOs and links to them are refused by
//! type before they are opened; no command writes over its inputs, and an existing output is
//! kept without `--force`; work asked by flags is refused up front past its budget; text from
//! files is printed escaped; and the smaller items (NaN preset values, `--height-range 0`,
//! `file://localhost/`, an outside buffer of the wrong size, supported required extensions).
//! Every run of the binary is killed after [`PATIENCE`], so a hang fails instead of hanging.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use bumpview::load::load_scene;
use bumpview::state::preset::Preset;

/// How long a refused run may take: the refusals read nothing, so this is generous.
const PATIENCE: Duration = Duration::from_secs(30);

/// Runs the binary with `args`, killing it after [`PATIENCE`] (a panic names the run).
fn bumpview(args: &[&str]) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_bumpview"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run bumpview");
    let started = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if started.elapsed() > PATIENCE {
            child.kill().unwrap();
            panic!("bumpview {args:?} still ran after {PATIENCE:?}");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().unwrap()
}

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("bumpview-hostile-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn text(path: &Path) -> &str {
    path.to_str().unwrap()
}

/// The lines bumpview wrote on stderr (a progress bar or warnings of libraries left out).
fn ours(output: &Output) -> Vec<String> {
    String::from_utf8_lossy(&output.stderr).lines().filter(|l| l.starts_with("bumpview:")).map(str::to_owned).collect()
}

/// One triangle (three float positions) whose buffer is the file `uri`, `length` bytes long.
fn triangle_gltf(uri: &str, length: usize, extra: &str) -> String {
    format!(
        r#"{{"asset": {{"version": "2.0"}}, {extra}
        "buffers": [{{"uri": "{uri}", "byteLength": {length}}}],
        "bufferViews": [{{"buffer": 0, "byteOffset": 0, "byteLength": 36}}],
        "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}}],
        "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}}}]}}],
        "nodes": [{{"mesh": 0}}], "scenes": [{{"nodes": [0]}}], "scene": 0}}"#
    )
}

fn triangle_bin() -> Vec<u8> {
    [0f32, 0., 0., 1., 0., 0., 0., 1., 0.].iter().flat_map(|v| v.to_le_bytes()).collect()
}

/// A 16×8 grey PNG.
fn grey_png(path: &Path) {
    image::GrayImage::from_fn(16, 8, |x, y| image::Luma([(x * 9 + y * 5) as u8])).save(path).unwrap();
}

/// `/dev/zero`, a FIFO and a link to `/dev/zero` as a model's buffer, a model, a preset and a
/// bake input: each refused by type at once (before: an 8.4 GB read and out of memory, or a
/// read of the FIFO that never returns).
#[cfg(unix)]
#[test]
fn devices_fifos_and_links_to_them_are_refused_by_type() {
    let dir = temp_dir("special");
    let fifo = dir.join("pipe.png");
    assert!(Command::new("mkfifo").arg(&fifo).status().unwrap().success());
    let link = dir.join("zero.gltf");
    std::os::unix::fs::symlink("/dev/zero", &link).unwrap();
    for (buffer, what) in [("/dev/zero", "character device"), (text(&fifo), "FIFO")] {
        let model = dir.join("model.gltf");
        std::fs::write(&model, triangle_gltf(buffer, 36, "")).unwrap();
        // `/dev/zero` lies outside the model's folder: allowed, to reach the check by type.
        let output = bumpview(&["check", text(&model), "--allow-outside-files"]);
        assert_eq!(output.status.code(), Some(2));
        let stdout = String::from_utf8_lossy(&output.stdout);
        assert!(stdout.contains(&format!("is a {what}")) && stdout.contains("not a regular file"), "{stdout}");
    }
    let output = bumpview(&["check", text(&link)]);
    assert!(String::from_utf8_lossy(&output.stdout).contains("is a character device, not a regular file"));
    let output = bumpview(&["render", "--preset", "/dev/zero", "--out", text(&dir.join("x.png"))]);
    assert_eq!((output.status.code(), ours(&output).len()), (Some(1), 1), "{:?}", ours(&output));
    assert!(ours(&output)[0].contains("character device"), "{:?}", ours(&output));
    for input in [text(&fifo), "/dev/zero"] {
        let output = bumpview(&["bake", input, "--out", text(&dir.join("n.png"))]);
        assert_eq!(output.status.code(), Some(1));
        assert!(ours(&output)[0].contains("not a regular file"), "{:?}", ours(&output));
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `bake a.png --out a.png`, a directory bake whose output is another input, and
/// `render --normal n.png --out n.png` are refused before any work (exit 2), the inputs
/// untouched; an existing output is kept without `--force` and replaced with it. (Before:
/// all of them overwrote, exit 0.)
#[test]
fn no_command_writes_over_its_inputs_and_outputs_need_force() {
    let dir = temp_dir("outputs");
    let a = dir.join("a.png");
    grey_png(&a);
    let original = std::fs::read(&a).unwrap();
    for to_height in [false, true] {
        let mut args = vec!["bake", text(&a), "--out", text(&a), "--force"];
        args.extend(to_height.then_some("--to-height"));
        let output = bumpview(&args);
        assert_eq!(output.status.code(), Some(2), "{args:?}");
        assert_eq!(
            ours(&output),
            [format!(
                "bumpview: {}: is also an input ({}): refusing to write over it, nothing was written",
                a.display(),
                a.display()
            )]
        );
    }
    let second = dir.join("a_normal.png");
    grey_png(&second);
    let second_bytes = std::fs::read(&second).unwrap();
    let output = bumpview(&["bake", text(&a), text(&second), "--out", text(&dir)]);
    assert_eq!(output.status.code(), Some(2));
    assert!(ours(&output)[0].contains("is also an input"), "{:?}", ours(&output));
    assert!(!dir.join("a_normal_normal.png").exists(), "nothing is baked");
    let output = bumpview(&["render", "--normal", text(&second), "--out", text(&second)]);
    assert_eq!(output.status.code(), Some(2));
    assert!(ours(&output)[0].contains("is also an input"), "{:?}", ours(&output));
    assert_eq!((std::fs::read(&a).unwrap(), std::fs::read(&second).unwrap()), (original, second_bytes.clone()));

    let out = dir.join("out.png");
    std::fs::write(&out, b"kept").unwrap();
    let output = bumpview(&["bake", text(&a), "--out", text(&out)]);
    assert_eq!(output.status.code(), Some(2));
    assert_eq!(
        ours(&output),
        [format!("bumpview: {}: exists and was kept: pass --force to replace it", out.display())]
    );
    assert_eq!(std::fs::read(&out).unwrap(), b"kept");
    let output = bumpview(&["render", "--out", text(&out), "--size", "8x8"]);
    assert_eq!(output.status.code(), Some(2));
    assert_eq!(std::fs::read(&out).unwrap(), b"kept");
    let output = bumpview(&["bake", text(&a), "--out", text(&out), "--force"]);
    assert!(output.status.success(), "{:?}", ours(&output));
    assert_eq!(image::open(&out).unwrap().width(), 16);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `--frames`, the tiles of `--grid` and the pixels of an export past their budgets are
/// refused at once naming the limit (before: a million frames ran on past a minute, 100×100
/// tiles took 828 MB); `--no-budget` lifts the first two.
#[test]
fn work_past_the_budgets_is_refused_up_front() {
    let output = bumpview(&["render", "--frames", "1000000"]);
    assert_eq!(output.status.code(), Some(2));
    let expected = "bumpview: --frames 1000000: at most 1000 frames are timed (--no-budget lifts this)";
    assert_eq!(ours(&output), [expected]);
    let row = vec!["flat"; 100].join(",");
    let grid = vec![row.as_str(); 100].join(";");
    let output = bumpview(&["render", "--out", "never.png", "--size", "8x8", "--grid", &grid]);
    assert_eq!(output.status.code(), Some(2));
    assert_eq!(ours(&output), ["bumpview: --grid of 10000 tiles: at most 64 are drawn (--no-budget lifts this)"]);
    let output = bumpview(&["render", "--out", "never.png", "--size", "16384x16384", "--supersample", "2"]);
    assert_eq!(output.status.code(), Some(2));
    let expected = "16384x16384, 1 tile(s), supersampled 2x is 1073741824 pixels to draw, over the limit of 268435456";
    assert_eq!(ours(&output), [format!("bumpview: {expected}")]);
    assert!(!Path::new("never.png").exists());
}

/// A buffer URI holding an escape sequence is printed as `\u{1b}` in `check`'s error line
/// (before: the raw ESC reached the terminal).
#[test]
fn text_from_files_is_printed_escaped() {
    let dir = temp_dir("escapes");
    let model = dir.join("model.gltf");
    std::fs::write(&model, triangle_gltf("\\u001b[31mred\\u0007.bin", 36, "")).unwrap();
    let output = bumpview(&["check", text(&model)]);
    assert_eq!(output.status.code(), Some(2));
    assert!(!output.stdout.iter().any(|&b| b == 0x1b || b == 0x07), "raw control bytes reached stdout");
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(stdout.contains("\\u{1b}[31mred\\u{7}.bin"), "{stdout}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `--height-range 0` and `-1` are refused by `render` as by `bake` (exit 2).
#[test]
fn render_refuses_a_height_range_that_is_not_positive() {
    for range in ["0", "-1"] {
        let output = bumpview(&["render", "--out", "never.png", &format!("--height-range={range}")]);
        assert_eq!(output.status.code(), Some(2), "{range}");
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(stderr.contains("expected a number above 0"), "{stderr}");
    }
}

/// NaN in a preset is refused naming its key: `difference_range_deg` (before: accepted) and
/// a camera value (before: "camera and light values must be finite numbers").
#[test]
fn nan_preset_values_are_refused_naming_the_key() {
    let error = Preset::from_toml("[shading]\ndifference_range_deg = nan\n").unwrap_err();
    assert_eq!(error.to_string(), r#"shading.difference_range_deg = "NaN": expected degrees, 0.01 to 180"#);
    let error = Preset::from_toml("[camera]\nyaw_deg = nan\n").unwrap_err();
    assert_eq!(error.to_string(), r#"camera.yaw_deg = "NaN": expected a finite number of degrees"#);
    let error = Preset::from_toml("[camera]\ntarget = [0, inf, 0]\n").unwrap_err();
    assert_eq!(error.to_string(), r#"camera.target = "[0.0, inf, 0.0]": expected three finite numbers"#);
    assert!(Preset::from_toml("[shading]\ndifference_range_deg = 180.0\n").is_ok());
}

/// `file://localhost/ABSOLUTE` is the absolute path (before: read as the relative
/// `localhost/ABSOLUTE`); another host is refused; an outside buffer of the wrong size fails
/// with the not-portable note (before: without it).
#[test]
fn file_uris_with_localhost_and_outside_buffers_of_the_wrong_size() {
    let dir = temp_dir("uris");
    let bin = dir.join("outside.bin");
    std::fs::write(&bin, triangle_bin()).unwrap();
    let model_dir = dir.join("model");
    std::fs::create_dir_all(&model_dir).unwrap();
    let model = model_dir.join("m.gltf");
    std::fs::write(&model, triangle_gltf(&format!("file://localhost{}", bin.display()), 36, "")).unwrap();
    let scene = load_scene(&model).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.files, std::slice::from_ref(&bin));
    std::fs::write(&model, triangle_gltf(&format!("file://elsewhere{}", bin.display()), 36, "")).unwrap();
    let error = load_scene(&model).map(|_| ()).unwrap_err().to_string();
    assert!(error.contains("names a file on another host"), "{error}");
    std::fs::write(&model, triangle_gltf("../outside.bin", 72, "")).unwrap();
    let error = load_scene(&model).map(|_| ()).unwrap_err().to_string();
    let expected = "buffer 0 should hold 72 bytes but has 36 (truncated?); it lies outside the model's folder: the model is not portable";
    assert_eq!(error, format!("{}: {expected}", model_dir.join("../outside.bin").display()));
    std::fs::write(&model, triangle_gltf("../missing.bin", 36, "")).unwrap();
    let error = load_scene(&model).map(|_| ()).unwrap_err().to_string();
    assert!(error.ends_with("the model is not portable"), "{error}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A glTF that requires KHR_materials_clearcoat or KHR_materials_emissive_strength (both
/// read) opens (before: refused as unsupported); an unknown required extension is refused.
#[test]
fn required_extensions_this_loader_reads_are_accepted() {
    let dir = temp_dir("required");
    std::fs::write(dir.join("t.bin"), triangle_bin()).unwrap();
    let model = dir.join("m.gltf");
    for extension in ["KHR_materials_clearcoat", "KHR_materials_emissive_strength"] {
        let extra = format!(r#""extensionsUsed": ["{extension}"], "extensionsRequired": ["{extension}"],"#);
        std::fs::write(&model, triangle_gltf("t.bin", 36, &extra)).unwrap();
        load_scene(&model).unwrap_or_else(|e| panic!("{extension}: {e}"));
    }
    let extra = r#""extensionsUsed": ["EXT_unknown"], "extensionsRequired": ["EXT_unknown"],"#;
    std::fs::write(&model, triangle_gltf("t.bin", 36, extra)).unwrap();
    let error = load_scene(&model).map(|_| ()).unwrap_err().to_string();
    assert!(error.contains("requires the glTF extension EXT_unknown"), "{error}");
    std::fs::remove_dir_all(&dir).unwrap();
}
