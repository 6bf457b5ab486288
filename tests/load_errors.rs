//! Broken files: each returns an error whose one-line message names the file and the
//! problem, and nothing panics; good ones list the files they refer to. The files are made
//! here, in a temporary folder.

mod common;

use std::path::{Path, PathBuf};

use bumpview::load::load_scene;

/// A fresh temporary folder for one test.
fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("bumpview-load-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// One triangle: three positions (36 bytes) and the UVs (0, 1), (1, 1), (0, 0) (24 bytes).
fn triangle_bin() -> Vec<u8> {
    let values: [f32; 15] = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 1.0, 0.0, 0.0];
    values.iter().flat_map(|v| v.to_le_bytes()).collect()
}

/// A glTF document drawing [`triangle_bin`] from `buffer_uri` (`None`: the GLB chunk), with
/// a base colour texture from `image_uri` when given, and extra top-level JSON members.
fn triangle_gltf(buffer_uri: Option<&str>, image_uri: Option<&str>, extra: &str) -> String {
    let uri = buffer_uri.map_or(String::new(), |u| format!(r#""uri": "{u}", "#));
    let (material, textures) = match image_uri {
        Some(image) => (
            r#", "material": 0"#.to_owned(),
            format!(
                r#""materials": [{{"pbrMetallicRoughness": {{"baseColorTexture": {{"index": 0}}}}}}],
                "textures": [{{"source": 0}}], "images": [{{"uri": "{image}"}}],"#
            ),
        ),
        None => (String::new(), String::new()),
    };
    format!(
        r#"{{"asset": {{"version": "2.0"}}, {extra} {textures}
        "buffers": [{{{uri}"byteLength": 60}}],
        "bufferViews": [{{"buffer": 0, "byteOffset": 0, "byteLength": 36}}, {{"buffer": 0, "byteOffset": 36, "byteLength": 24}}],
        "accessors": [
            {{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}},
            {{"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"}}],
        "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0, "TEXCOORD_0": 1}}{material}}}]}}],
        "nodes": [{{"mesh": 0}}], "scenes": [{{"nodes": [0]}}], "scene": 0}}"#
    )
}

/// A GLB container of `json` and `bin`.
fn glb(json: &str, bin: &[u8]) -> Vec<u8> {
    let pad = |mut bytes: Vec<u8>, with: u8| {
        bytes.resize(bytes.len().div_ceil(4) * 4, with);
        bytes
    };
    let (json, bin) = (pad(json.as_bytes().to_vec(), b' '), pad(bin.to_vec(), 0));
    let total = 12 + 8 + json.len() + 8 + bin.len();
    let mut out = b"glTF".to_vec();
    out.extend(2u32.to_le_bytes());
    out.extend((total as u32).to_le_bytes());
    out.extend((json.len() as u32).to_le_bytes());
    out.extend(b"JSON");
    out.extend(json);
    out.extend((bin.len() as u32).to_le_bytes());
    out.extend(b"BIN\0");
    out.extend(bin);
    out
}

/// Loads `path`, expecting an error whose message names `file` and contains `problem`.
fn expect_error(path: &Path, file: &str, problem: &str) {
    let message = match load_scene(path) {
        Ok(_) => panic!("{} loaded, expected an error about {problem:?}", path.display()),
        Err(e) => e.to_string(),
    };
    println!("{message}");
    assert!(!message.contains('\n'), "one line: {message}");
    assert!(message.contains(file), "the message names {file}: {message}");
    assert!(message.to_lowercase().contains(problem), "the message says {problem:?}: {message}");
}

#[test]
fn good_gltf_glb_and_base64_buffers_load() {
    let dir = temp_dir("good");
    std::fs::write(dir.join("tri.bin"), triangle_bin()).unwrap();
    std::fs::write(dir.join("tri.gltf"), triangle_gltf(Some("tri.bin"), None, "")).unwrap();
    std::fs::write(dir.join("tri.glb"), glb(&triangle_gltf(None, None, ""), &triangle_bin())).unwrap();
    use base64::Engine;
    let data =
        format!("data:application/octet-stream;base64,{}", base64::prelude::BASE64_STANDARD.encode(triangle_bin()));
    std::fs::write(dir.join("embedded.gltf"), triangle_gltf(Some(&data), None, "")).unwrap();
    for name in ["tri.gltf", "tri.glb", "embedded.gltf"] {
        let scene = load_scene(&dir.join(name)).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(scene.instances.len(), 1);
        let mesh = &scene.meshes[0];
        // No normals in the file: flat ones, facing the counter-clockwise side (+Z).
        assert!(mesh.normals.iter().all(|n| (*n - glam::Vec3::Z).length() < 1e-6), "{name}");
        assert_eq!(mesh.uvs, [glam::Vec2::Y, glam::Vec2::ONE, glam::Vec2::ZERO], "{name}: UVs as stored (v down)");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn broken_files_give_one_line_naming_the_file_and_the_problem() {
    let dir = temp_dir("broken");
    let write = |name: &str, bytes: &[u8]| {
        std::fs::write(dir.join(name), bytes).unwrap();
        dir.join(name)
    };
    let good_glb = glb(&triangle_gltf(None, None, ""), &triangle_bin());
    expect_error(&write("truncated.glb", &good_glb[..good_glb.len() - 20]), "truncated.glb", "glb");
    // The header's length field disagrees with the file: shorter, and under the header's own 12 bytes.
    for (name, stated) in [("long.glb", good_glb.len() as u32 - 4), ("tiny-length.glb", 4)] {
        let mut bytes = good_glb.clone();
        bytes[8..12].copy_from_slice(&stated.to_le_bytes());
        expect_error(&write(name, &bytes), name, "length");
    }
    expect_error(&write("bad.gltf", b"{ \"asset\": { \"version\": \"2.0\" }, oops"), "bad.gltf", "json");
    expect_error(
        &write("no-bin.gltf", triangle_gltf(Some("gone.bin"), None, "").as_bytes()),
        "gone.bin",
        "could not read",
    );
    write("tri.bin", &triangle_bin());
    write("short.bin", &triangle_bin()[..30]);
    expect_error(&write("short.gltf", triangle_gltf(Some("short.bin"), None, "").as_bytes()), "short.bin", "truncated");
    // An extension the loader does not know, required (EXT_meshopt_compression, refused here
    // once, is read now: tests/compressed_files.rs).
    let unknown = triangle_gltf(Some("tri.bin"), None, r#""extensionsRequired": ["EXT_not_a_real_extension"],"#);
    expect_error(&write("unknown.gltf", unknown.as_bytes()), "unknown.gltf", "ext_not_a_real_extension");
    let remote = triangle_gltf(Some("https://example.com/tri.bin"), None, "");
    expect_error(&write("remote.gltf", remote.as_bytes()), "remote.gltf", "remote files are not fetched");
    expect_error(&write("empty.obj", b"# nothing here\n"), "empty.obj", "no faces");
    expect_error(&write("nan.obj", b"v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n"), "nan.obj", "nan");
    expect_error(&write("range.obj", b"v 0 0 0\nf 1 2 3\n"), "range.obj", "line 2");
    expect_error(&write("model.fbx", b"Kaydara"), "model.fbx", "unsupported");
    expect_error(&dir.join("absent.gltf"), "absent.gltf", "could not read");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Every prefix of a GLB errors. Every single-byte corruption, each byte XOR 0xA5 and each
/// byte set to 0xFF, errors without panicking or loads a sane scene ([`common::assert_sane`]):
/// in the 12-byte header, the two 8-byte chunk headers and the JSON chunk it must error (an
/// ASCII byte XOR 0xA5, and 0xFF, have the high bit set: never valid UTF-8 among ASCII); in
/// the vertex data it may load (XOR 0xA5 keeps these floats finite), or must error where
/// 0xFF makes a float's exponent all ones (infinity or NaN).
#[test]
fn every_prefix_and_byte_corruption_of_a_glb_errors_without_panicking() {
    let json = triangle_gltf(None, None, "");
    let good = glb(&json, &triangle_bin());
    let json_end = 20 + json.len().div_ceil(4) * 4;
    let bin_start = json_end + 8;
    assert_eq!(good.len(), bin_start + triangle_bin().len());
    let dir = temp_dir("fuzz");
    let path = dir.join("fuzz.glb");
    for length in 0..good.len() {
        std::fs::write(&path, &good[..length]).unwrap();
        assert!(load_scene(&path).is_err(), "a {length}-byte prefix loaded");
    }
    let (mut loaded, mut rejected_data) = (0, 0);
    for position in 0..good.len() {
        for corrupt in [|b: u8| b ^ 0xA5, |_| 0xFF] {
            let mut bytes = good.clone();
            bytes[position] = corrupt(bytes[position]);
            std::fs::write(&path, &bytes).unwrap();
            let what = format!("byte {position} {:#04x} → {:#04x}", good[position], bytes[position]);
            match load_scene(&path) {
                Ok(scene) if position < bin_start => {
                    panic!("{what}, in the header or JSON, loaded: {:?}", scene.meshes)
                }
                Ok(scene) => {
                    common::assert_sane(&scene, &what);
                    loaded += 1;
                }
                Err(_) if position >= bin_start => rejected_data += 1,
                Err(_) => {}
            }
        }
    }
    println!("vertex data corruptions: {loaded} loaded (sane), {rejected_data} rejected");
    // Both ways happen, so both the sanity checks and the loader's rejection are exercised.
    assert!(loaded > 50 && rejected_data > 0, "{loaded} loaded, {rejected_data} rejected");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn render_draws_a_mesh_file_or_fails_with_the_loaders_one_line() {
    let dir = temp_dir("cli");
    std::fs::write(dir.join("tri.bin"), triangle_bin()).unwrap();
    std::fs::write(dir.join("tri.gltf"), triangle_gltf(Some("tri.bin"), None, "")).unwrap();
    image::RgbaImage::from_pixel(4, 4, image::Rgba([200, 40, 40, 255])).save(dir.join("red.png")).unwrap();
    let run = |args: &[&str]| {
        std::process::Command::new(env!("CARGO_BIN_EXE_bumpview")).args(args).output().expect("run bumpview")
    };
    let out = dir.join("tri.png");
    let (out_arg, model, color) = (out.to_str().unwrap(), dir.join("tri.gltf"), dir.join("red.png"));
    let output = run(&[
        "render",
        "--out",
        out_arg,
        "--size",
        "64x48",
        model.to_str().unwrap(),
        "--color",
        color.to_str().unwrap(),
    ]);
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    assert_eq!(image::open(&out).unwrap().width(), 64);

    std::fs::write(dir.join("broken.gltf"), "{").unwrap();
    let output = run(&["render", "--force", "--out", out_arg, dir.join("broken.gltf").to_str().unwrap()]);
    assert!(!output.status.success());
    let stderr = String::from_utf8_lossy(&output.stderr);
    let lines: Vec<&str> = stderr.lines().filter(|l| l.starts_with("bumpview:")).collect();
    assert_eq!(lines.len(), 1, "{stderr}");
    assert!(lines[0].contains("broken.gltf") && lines[0].contains("JSON"), "{stderr}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The files a mesh refers to, wherever they are, are listed for hot reload: a glTF's buffer
/// and its image in a sub-folder, an OBJ's material library and the texture it names; the
/// mesh file itself, embedded data and a GLB's own chunk are not.
#[test]
fn the_files_a_mesh_refers_to_are_listed_for_hot_reload() {
    let dir = temp_dir("referred");
    std::fs::create_dir_all(dir.join("textures")).unwrap();
    image::RgbaImage::from_pixel(2, 2, image::Rgba([200, 100, 50, 255])).save(dir.join("textures/c.png")).unwrap();
    std::fs::write(dir.join("tri.bin"), triangle_bin()).unwrap();
    std::fs::write(dir.join("tri.gltf"), triangle_gltf(Some("tri.bin"), Some("textures/c.png"), "")).unwrap();
    let scene = load_scene(&dir.join("tri.gltf")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.files, [dir.join("tri.bin"), dir.join("textures/c.png")]);
    std::fs::write(dir.join("tri.glb"), glb(&triangle_gltf(None, None, ""), &triangle_bin())).unwrap();
    assert!(load_scene(&dir.join("tri.glb")).unwrap().files.is_empty());

    std::fs::write(dir.join("quad.mtl"), "newmtl paint\nmap_Kd textures/c.png\n").unwrap();
    std::fs::write(
        dir.join("quad.obj"),
        "mtllib quad.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nusemtl paint\nf 1/1 2/2 3/3\n",
    )
    .unwrap();
    let scene = load_scene(&dir.join("quad.obj")).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(scene.files, [dir.join("textures/c.png"), dir.join("quad.mtl")]);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A texture that cannot be read — missing, not an image, remote, of an unknown URI scheme —
/// does not fail the model: it opens with that slot empty and a warning naming the file and
/// the reason, which `check` counts as an error.
#[test]
fn an_unreadable_texture_leaves_its_slot_empty_with_a_warning() {
    let dir = temp_dir("unreadable-texture");
    std::fs::write(dir.join("tri.bin"), triangle_bin()).unwrap();
    std::fs::write(dir.join("fake.png"), b"this is text, not a picture").unwrap();
    for (image, file, reason) in [
        ("missing%20image.png", "missing image.png", "could not read"),
        ("fake.png", "fake.png", "not an image"),
        ("http://example.com/c.png", "c.gltf", "remote files are not fetched"),
        ("ftp://example.com/c.png", "c.gltf", "uri scheme"),
    ] {
        std::fs::write(dir.join("c.gltf"), triangle_gltf(Some("tri.bin"), Some(image), "")).unwrap();
        let scene = load_scene(&dir.join("c.gltf")).unwrap_or_else(|e| panic!("{image}: {e}"));
        assert_eq!(scene.materials[0].base_color_texture, None, "{image}: the slot stays empty");
        assert!(scene.textures.is_empty(), "{image}");
        let [warning] = &scene.warnings[..] else { panic!("{image}: one warning, got {:?}", scene.warnings) };
        let text = warning.to_string();
        assert!(text.contains(file) && text.to_lowercase().contains(reason), "{image}: {text}");
        let report = bumpview::check::check_scene(&scene);
        assert_eq!(report.severity(), bumpview::check::Severity::Error, "{}", report.to_text());
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// One missing and one corrupt texture in the same model: both slots stay empty, two
/// warnings, and the rest of the material (its factors) is kept.
#[test]
fn a_model_with_a_missing_and_a_corrupt_texture_opens_without_both() {
    let dir = temp_dir("two-unreadable");
    std::fs::write(dir.join("tri.bin"), triangle_bin()).unwrap();
    std::fs::write(dir.join("corrupt.png"), b"\x89PNG\r\n\x1a\n but then nothing a decoder wants").unwrap();
    let json = triangle_gltf(Some("tri.bin"), Some("missing.png"), "").replace(
        r#""materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}]"#,
        r#""materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "baseColorFactor": [0.5, 0.25, 1, 1]},
            "normalTexture": {"index": 1}}]"#,
    );
    let json = json.replace(
        r#""textures": [{"source": 0}], "images": [{"uri": "missing.png"}]"#,
        r#""textures": [{"source": 0}, {"source": 1}], "images": [{"uri": "missing.png"}, {"uri": "corrupt.png"}]"#,
    );
    std::fs::write(dir.join("two.gltf"), json).unwrap();
    let scene = load_scene(&dir.join("two.gltf")).unwrap_or_else(|e| panic!("{e}"));
    let material = &scene.materials[0];
    assert_eq!((material.base_color_texture.is_none(), material.normal_map.is_none()), (true, true));
    assert_eq!(material.base_color_factor, glam::Vec4::new(0.5, 0.25, 1.0, 1.0));
    let warnings: Vec<String> = scene.warnings.iter().map(ToString::to_string).collect();
    assert_eq!(warnings.len(), 2, "{warnings:?}");
    assert!(warnings[0].contains("missing.png") && warnings[1].contains("corrupt.png"), "{warnings:?}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `render` draws a model with an unreadable texture (exit 0, the warning on stderr naming
/// the file), and with `--strict` refuses it (exit 1, no PNG).
#[test]
fn render_warns_about_an_unreadable_texture_and_strict_refuses_it() {
    let dir = temp_dir("strict");
    std::fs::write(dir.join("tri.bin"), triangle_bin()).unwrap();
    std::fs::write(dir.join("m.gltf"), triangle_gltf(Some("tri.bin"), Some("gone.png"), "")).unwrap();
    let render = |strict: bool, out: &str| {
        let mut command = std::process::Command::new(env!("CARGO_BIN_EXE_bumpview"));
        command.args(["render", "--size", "32x24", "--out"]).arg(dir.join(out)).arg(dir.join("m.gltf"));
        if strict {
            command.arg("--strict");
        }
        command.output().unwrap()
    };
    let lenient = render(false, "lenient.png");
    let stderr = String::from_utf8_lossy(&lenient.stderr);
    assert_eq!(lenient.status.code(), Some(0), "{stderr}");
    assert!(stderr.contains("warning") && stderr.contains("gone.png"), "{stderr}");
    assert!(dir.join("lenient.png").is_file());
    let strict = render(true, "strict.png");
    let stderr = String::from_utf8_lossy(&strict.stderr);
    assert_eq!(strict.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("--strict") && !dir.join("strict.png").exists(), "{stderr}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Files outside the model's folder — an absolute path, a `file:` URI, a path through `..` —
/// still open, and `check` warns that the model is not portable; a file next to it does not.
#[test]
fn files_outside_the_models_folder_open_and_are_not_portable() {
    let dir = temp_dir("portable");
    let model = dir.join("model");
    std::fs::create_dir_all(&model).unwrap();
    std::fs::write(dir.join("outside.bin"), triangle_bin()).unwrap();
    std::fs::write(model.join("inside.bin"), triangle_bin()).unwrap();
    let absolute = dir.join("outside.bin").display().to_string();
    for (uri, portable) in [
        ("inside.bin".to_owned(), true),
        ("../outside.bin".to_owned(), false),
        (absolute.clone(), false),
        (format!("file://{absolute}"), false),
    ] {
        std::fs::write(model.join("m.gltf"), triangle_gltf(Some(&uri), None, "")).unwrap();
        let scene = load_scene(&model.join("m.gltf")).unwrap_or_else(|e| panic!("{uri}: {e}"));
        assert_eq!(scene.meshes[0].positions.len(), 3, "{uri}");
        let report = bumpview::check::check_scene(&scene);
        let warned = report.warnings().iter().any(|w| w.contains("not portable"));
        assert_eq!(warned, !portable, "{uri}: {:?}", report.warnings());
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
