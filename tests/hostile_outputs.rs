//! Outputs and permissions: an existing `--out` that is not a regular file (a device such as
//! `/dev/null`, a FIFO, a directory, a link to one) is refused, `--force` or not; every output
//! a command writes is checked against its inputs and its other outputs before the first
//! write (`--out` and `--save-preset` naming one file, `bake --mips` levels named like an
//! input); the atomic writer's temporary is created exclusively, never through a planted
//! link; files outside a model's folder are read only when allowed; bidirectional controls in
//! names are printed escaped. Each hostile file is made here. Every run of the binary is
//! killed after [`PATIENCE`], so a hang fails instead of hanging.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use bumpview::load::{SceneFiles, load_model};

/// How long a refused run may take: the refusals read nothing, so this is generous.
const PATIENCE: Duration = Duration::from_secs(60);

/// Runs the binary with `args`, killing it after [`PATIENCE`].
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
    let dir = std::env::temp_dir().join(format!("bumpview-outputs-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn text(path: &Path) -> &str {
    path.to_str().unwrap()
}

/// The lines bumpview wrote on stderr.
fn ours(output: &Output) -> Vec<String> {
    String::from_utf8_lossy(&output.stderr).lines().filter(|l| l.starts_with("bumpview:")).map(str::to_owned).collect()
}

/// Asserts `output` is one line on stderr containing `wanted`, with exit status `code`.
fn refused(output: &Output, code: i32, wanted: &str) {
    let lines = ours(output);
    assert_eq!(output.status.code(), Some(code), "{lines:?}");
    assert_eq!(lines.len(), 1, "{lines:?}");
    assert!(lines[0].contains(wanted), "{lines:?} lacks {wanted:?}");
}

/// A 16×8 grey PNG.
fn grey_png(path: &Path) {
    image::GrayImage::from_fn(16, 8, |x, y| image::Luma([(x * 9 + y * 5) as u8])).save(path).unwrap();
}

/// An 8×8 flat normal map (RGB 128,128,255).
fn flat_normal_png(path: &Path) {
    image::RgbImage::from_pixel(8, 8, image::Rgb([128, 128, 255])).save(path).unwrap();
}

/// One triangle whose buffer is the file `uri` (36 bytes) and, with `image`, a material whose
/// base colour is the image file `image`.
fn triangle_gltf(uri: &str, image: Option<&str>) -> String {
    let (material, textures) = match image {
        Some(image) => (
            r#", "material": 0"#,
            format!(
                r#""materials": [{{"pbrMetallicRoughness": {{"baseColorTexture": {{"index": 0}}}}}}],
                "textures": [{{"source": 0}}], "images": [{{"uri": "{image}"}}],"#
            ),
        ),
        None => ("", String::new()),
    };
    format!(
        r#"{{"asset": {{"version": "2.0"}}, {textures}
        "buffers": [{{"uri": "{uri}", "byteLength": 36}}],
        "bufferViews": [{{"buffer": 0, "byteOffset": 0, "byteLength": 36}}],
        "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}}],
        "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}{material}}}]}}],
        "nodes": [{{"mesh": 0}}], "scenes": [{{"nodes": [0]}}], "scene": 0}}"#
    )
}

fn triangle_bin() -> Vec<u8> {
    [0f32, 0., 0., 1., 0., 0., 0., 1., 0.].iter().flat_map(|v| v.to_le_bytes()).collect()
}

/// `--out` naming `/dev/null`, a FIFO, a directory or a link to a FIFO is refused with one
/// line and exit 2 by render, bake, slides and report, with `--force` too; the FIFO is still
/// a FIFO and `/dev/null` still a device afterwards. (Before: `--force` renamed a PNG over
/// them.)
#[cfg(unix)]
#[test]
fn an_out_that_is_not_a_regular_file_is_refused_even_with_force() {
    use std::os::unix::fs::FileTypeExt;
    let dir = temp_dir("special");
    let fifo = dir.join("pipe.png");
    assert!(Command::new("mkfifo").arg(&fifo).status().unwrap().success());
    let link = dir.join("link.png");
    std::os::unix::fs::symlink(&fifo, &link).unwrap();
    let folder = dir.join("folder.png");
    std::fs::create_dir_all(&folder).unwrap();
    let height = dir.join("h.png");
    grey_png(&height);
    let targets = [("/dev/null", "is a device"), (text(&fifo), "is a FIFO"), (text(&link), "is a FIFO")];
    for (out, kind) in targets.into_iter().chain([(text(&folder), "is a directory")]) {
        let output = bumpview(&["render", "--out", out, "--force"]);
        refused(
            &output,
            2,
            &format!("{out}: {kind}, not a regular file: refusing to write over it, even with --force"),
        );
        let output = bumpview(&["render", "--out", text(&dir.join("fine.png")), "--save-preset", out, "--force"]);
        refused(&output, 2, kind);
    }
    for (out, kind) in targets {
        let output = bumpview(&["bake", text(&height), "--out", out, "--force"]);
        refused(&output, 2, kind);
    }
    let output = bumpview(&["report", "--quick", "--out", "/dev/null"]);
    refused(&output, 2, "/dev/null: is not a directory");
    let slides = dir.join("slides");
    std::fs::create_dir_all(&slides).unwrap();
    assert!(Command::new("mkfifo").arg(slides.join("index.md")).status().unwrap().success());
    let output = bumpview(&["slides", "--out", text(&slides), "--lessons", "bump-off-on", "--force"]);
    refused(&output, 2, "index.md: is a FIFO");
    assert!(std::fs::symlink_metadata(&fifo).unwrap().file_type().is_fifo());
    assert!(std::fs::metadata("/dev/null").unwrap().file_type().is_char_device());
    assert!(!dir.join("fine.png").exists(), "nothing was drawn");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `render --out x --save-preset x` is refused (exit 2; before: exit 0 and the preset lost
/// under the PNG), as is a directory bake whose two inputs share a name.
#[test]
fn two_outputs_naming_one_file_are_refused() {
    let dir = temp_dir("twice");
    let out = dir.join("x.png");
    let output = bumpview(&["render", "--out", text(&out), "--save-preset", text(&out)]);
    refused(&output, 2, "is written twice");
    let through_dots = dir.join("sub/../x.png");
    std::fs::create_dir_all(dir.join("sub")).unwrap();
    let output = bumpview(&["render", "--out", text(&out), "--save-preset", text(&through_dots)]);
    refused(&output, 2, "is written twice");
    assert!(!out.exists());
    for side in ["a", "b"] {
        std::fs::create_dir_all(dir.join(side)).unwrap();
        flat_normal_png(&dir.join(side).join("n.png"));
    }
    let (a, b) = (dir.join("a/n.png"), dir.join("b/n.png"));
    let output = bumpview(&["bake", "--mips", "toksvig", text(&a), text(&b), "--out", text(&dir.join("mips"))]);
    refused(&output, 2, "is written twice");
    assert!(!dir.join("mips/n_mip0.png").exists(), "nothing was written");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `bake --mips` with a second input named like the first one's level 0, `x_mip0.png`, in the
/// output directory is refused before any level is written, the input untouched (before: it
/// was overwritten); a level named like an input of a later file is caught as well.
#[test]
fn bake_mips_never_writes_over_an_input() {
    let dir = temp_dir("mips");
    let x = dir.join("x.png");
    let level = dir.join("x_mip0.png");
    flat_normal_png(&x);
    grey_png(&level);
    let before = std::fs::read(&level).unwrap();
    for order in [[&x, &level], [&level, &x]] {
        let output =
            bumpview(&["bake", "--mips", "toksvig", text(order[0]), text(order[1]), "--out", text(&dir), "--force"]);
        refused(&output, 2, &format!("{}: is also an input", level.display()));
        assert_eq!(std::fs::read(&level).unwrap(), before);
        assert!(!dir.join("x_mip1.png").exists() && !dir.join("x_mip0_mip0.png").exists(), "nothing was written");
    }
    // An 8×8 map has 4 levels, all written once nothing collides.
    std::fs::remove_file(&level).unwrap();
    let output = bumpview(&["bake", "--mips", "toksvig", text(&x), "--out", text(&dir.join("out"))]);
    assert_eq!(output.status.code(), Some(0), "{:?}", ours(&output));
    let written: Vec<bool> = (0..5).map(|k| dir.join(format!("out/x_mip{k}.png")).exists()).collect();
    assert_eq!(written, [true, true, true, true, false]);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A symbolic link planted at each temporary name the atomic writer may try (and at the
/// older `.NAME.PID.tmp`) pointing at an unrelated file: the write succeeds under another
/// name, the unrelated file is untouched, the links are left as they were, and no temporary
/// is left behind. With every name taken the write fails without following any of them.
#[cfg(unix)]
#[test]
fn the_atomic_writer_never_follows_a_planted_link() {
    let dir = temp_dir("planted");
    let victim = dir.join("victim.txt");
    std::fs::write(&victim, b"keep me").unwrap();
    let out = dir.join("out.png");
    let pid = std::process::id();
    let planted: Vec<PathBuf> = std::iter::once(dir.join(format!(".out.png.{pid}.tmp")))
        .chain((0..3).map(|n| dir.join(format!(".out.png.{pid}.{n}.tmp"))))
        .collect();
    for link in &planted {
        std::os::unix::fs::symlink(&victim, link).unwrap();
    }
    bumpview::atomic::write_bytes_atomically(&out, b"new picture").unwrap();
    assert_eq!(std::fs::read(&out).unwrap(), b"new picture");
    assert_eq!(std::fs::read(&victim).unwrap(), b"keep me");
    assert!(planted.iter().all(|l| std::fs::symlink_metadata(l).unwrap().file_type().is_symlink()));
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 2 + planted.len(), "no temporary left behind");
    // Every name taken: refused, nothing followed.
    let crowded = dir.join("crowded.png");
    for n in 0..64 {
        std::os::unix::fs::symlink(&victim, dir.join(format!(".crowded.png.{pid}.{n}.tmp"))).unwrap();
    }
    assert!(bumpview::atomic::write_bytes_atomically(&crowded, b"x").is_err());
    assert_eq!((std::fs::read(&victim).unwrap(), crowded.exists()), (b"keep me".to_vec(), false));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A model's folder `model/` beside a secret file `secret.bin` (and a secret image):
/// buffers, images, material libraries and MTL textures reached by `..`, an absolute path, a
/// `file:` URI or a symbolic link inside leading out are refused by [`load_model`] with one
/// line naming the file and how to allow it, and read once allowed; a file inside opens
/// either way.
#[test]
fn files_outside_the_models_folder_are_read_only_when_allowed() {
    let dir = temp_dir("outside");
    let model = dir.join("model");
    std::fs::create_dir_all(model.join("sub")).unwrap();
    std::fs::write(dir.join("secret.bin"), triangle_bin()).unwrap();
    std::fs::write(model.join("inside.bin"), triangle_bin()).unwrap();
    grey_png(&dir.join("secret.png"));
    grey_png(&model.join("inside.png"));
    let absolute = dir.join("secret.bin").display().to_string();
    let mut cases = vec![
        (triangle_gltf("../secret.bin", None), "../secret.bin".to_owned(), "buffer"),
        (triangle_gltf(&absolute, None), absolute.clone(), "buffer"),
        (triangle_gltf(&format!("file://{absolute}"), None), absolute.clone(), "buffer"),
        (triangle_gltf("inside.bin", Some("../secret.png")), "../secret.png".to_owned(), "image"),
        (triangle_gltf("sub/../../secret.bin", None), "sub/../../secret.bin".to_owned(), "buffer"),
    ];
    #[cfg(unix)]
    {
        std::os::unix::fs::symlink(dir.join("secret.bin"), model.join("link.bin")).unwrap();
        cases.push((triangle_gltf("link.bin", None), "link.bin".to_owned(), "buffer"));
    }
    let gltf = model.join("m.gltf");
    for (json, named, what) in &cases {
        std::fs::write(&gltf, json).unwrap();
        let error = load_model(&gltf, false).map(|_| ()).unwrap_err().to_string();
        let file = if Path::new(named).is_absolute() { PathBuf::from(named) } else { model.join(named) };
        let expected = format!(
            "{}: the {what} that m.gltf names lies outside the model's folder ({}) and was not read: pass --allow-outside-files (or set allow_outside_files = true in a preset's [files]) to allow it",
            file.display(),
            model.display()
        );
        assert_eq!(error, expected, "{named}");
        let scene = load_model(&gltf, true).unwrap_or_else(|e| panic!("{named}: {e}"));
        assert_eq!(scene.meshes[0].positions.len(), 3, "{named}");
    }
    std::fs::write(&gltf, triangle_gltf("inside.bin", Some("inside.png"))).unwrap();
    assert!(!load_model(&gltf, false).unwrap_or_else(|e| panic!("{e}")).textures.is_empty());
    // OBJ: a material library and a texture outside.
    let obj = model.join("m.obj");
    std::fs::write(&obj, "mtllib ../outside.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    std::fs::write(dir.join("outside.mtl"), "newmtl a\nKd 1 1 1\n").unwrap();
    let error = load_model(&obj, false).map(|_| ()).unwrap_err().to_string();
    assert!(
        error
            .starts_with(&format!("{}: the material library that m.obj names", model.join("../outside.mtl").display())),
        "{error}"
    );
    assert!(load_model(&obj, true).is_ok());
    std::fs::write(&obj, "mtllib m.mtl\nusemtl a\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").unwrap();
    std::fs::write(model.join("m.mtl"), format!("newmtl a\nmap_Kd {}\n", dir.join("secret.png").display())).unwrap();
    let error = load_model(&obj, false).map(|_| ()).unwrap_err().to_string();
    assert!(
        error.starts_with(&format!("{}: the texture that m.mtl names", dir.join("secret.png").display())),
        "{error}"
    );
    assert_eq!(load_model(&obj, true).unwrap_or_else(|e| panic!("{e}")).textures.len(), 1);
    std::fs::write(model.join("m.mtl"), "newmtl a\nmap_Kd inside.png\n").unwrap();
    assert_eq!(load_model(&obj, false).unwrap_or_else(|e| panic!("{e}")).textures.len(), 1);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The command line: `check` and `render` refuse the outside buffer with one line naming it
/// (check: exit 2; render: exit 1, no PNG); `--allow-outside-files` (check then warns that the
/// model is not portable) and a preset's `allow_outside_files = true` in `[files]` allow it.
#[test]
fn the_flag_and_the_preset_key_allow_outside_files() {
    let dir = temp_dir("allow");
    let model = dir.join("model");
    std::fs::create_dir_all(&model).unwrap();
    std::fs::write(dir.join("secret.bin"), triangle_bin()).unwrap();
    let gltf = model.join("m.gltf");
    std::fs::write(&gltf, triangle_gltf("../secret.bin", None)).unwrap();
    let output = bumpview(&["check", text(&gltf)]);
    assert_eq!(output.status.code(), Some(2));
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(stdout.contains("lies outside the model's folder") && stdout.contains("--allow-outside-files"), "{stdout}");
    let output = bumpview(&["check", text(&gltf), "--allow-outside-files"]);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(stdout.contains("the model is not portable") && !stdout.contains("--allow-outside-files"), "{stdout}");
    let png = dir.join("never.png");
    let output = bumpview(&["render", text(&gltf), "--out", text(&png), "--size", "8x8"]);
    refused(&output, 1, "secret.bin: the buffer that m.gltf names lies outside the model's folder");
    assert!(!png.exists());
    // The preset key parses, round-trips, and loads the model.
    let preset = bumpview::state::preset::Preset::from_toml(&format!(
        "[files]\nmesh = {:?}\nallow_outside_files = true\n",
        gltf.display().to_string()
    ))
    .unwrap_or_else(|e| panic!("{e}"));
    assert!(preset.files.allow_outside_files);
    assert!(preset.build_scene().is_ok());
    let files = SceneFiles { allow_outside_files: false, ..preset.files.clone() };
    assert!(bumpview::state::preset::Preset { files, ..preset.clone() }.build_scene().is_err());
    let reparsed = bumpview::state::preset::Preset::from_toml(&preset.to_toml()).unwrap_or_else(|e| panic!("{e}"));
    assert!(reparsed.files.allow_outside_files);
    assert!(!bumpview::state::preset::Preset::default().to_toml().contains("allow_outside_files"));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A buffer URI holding U+202E (right-to-left override) and an isolate is printed escaped in
/// `check`'s line, so the terminal does not reorder the name (before: printed raw).
#[test]
fn bidirectional_controls_in_names_are_printed_escaped() {
    let dir = temp_dir("bidi");
    let gltf = dir.join("m.gltf");
    std::fs::write(&gltf, triangle_gltf("a\u{202e}nib.exe\u{2066}.bin", None)).unwrap();
    let output = bumpview(&["check", text(&gltf)]);
    assert_eq!(output.status.code(), Some(2));
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(!stdout.contains('\u{202e}') && !stdout.contains('\u{2066}'), "{stdout}");
    assert!(stdout.contains("a\\u{202e}nib.exe\\u{2066}.bin"), "{stdout}");
    std::fs::remove_dir_all(&dir).unwrap();
}
