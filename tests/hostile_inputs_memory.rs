//! Small hostile files that would cost gigabytes or minutes: each is made here and must end in
//! one line naming the file (or load as it should), within the budgets docs/inputs.md states.
//! A declared count no bytes back, an image whose header claims more texels than a texture
//! may have, one image or library named thousands of times, walks that were quadratic, a
//! triangle primitive without a whole triangle, and the smaller cases (a truncated JPEG,
//! `bake --mips` past the size limit, `extras` of any JSON type, primitives sharing one
//! accessor). Runs are killed after [`PATIENCE`], so a quadratic walk fails instead of hanging.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use base64::Engine;
use bumpview::error::LoadWarning;
use bumpview::load::image::{MAX_SIDE, MAX_TEXELS, decode_texture};
use bumpview::load::load_scene;
use bumpview::scene::{Scene, TextureKind};

/// How long one case may take: the linear walks and refusals take well under a second; the
/// quadratic ones took minutes.
const PATIENCE: Duration = Duration::from_secs(60);

fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("bumpview-memory-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

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

/// [`load_scene`] on another thread, failing the test past [`PATIENCE`].
fn load_patiently(path: &Path) -> Result<Scene, String> {
    let (send, receive) = mpsc::channel();
    let path = path.to_owned();
    std::thread::spawn(move || send.send(load_scene(&path).map_err(|e| e.to_string())));
    receive.recv_timeout(PATIENCE).unwrap_or_else(|_| panic!("loading took more than {PATIENCE:?}"))
}

fn data_uri(bytes: &[u8]) -> String {
    format!("data:application/octet-stream;base64,{}", base64::engine::general_purpose::STANDARD.encode(bytes))
}

/// One triangle's three float positions.
fn triangle_bytes() -> Vec<u8> {
    [0.0f32, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0].iter().flat_map(|f| f.to_le_bytes()).collect()
}

/// A PNG header of `width × height` grey texels with an empty pixel stream (a zlib stream
/// of nothing): enough for every size check, which reads only the header.
fn png_header_only(path: &Path, width: u32, height: u32) {
    let mut bytes = Vec::new();
    let mut encoder = png::Encoder::new(&mut bytes, width, height);
    encoder.set_color(png::ColorType::Grayscale);
    let mut writer = encoder.write_header().unwrap();
    writer.write_chunk(png::chunk::IDAT, &[0x78, 0x9c, 0x03, 0x00, 0x00, 0x00, 0x00, 0x01]).unwrap();
    drop(writer);
    std::fs::write(path, bytes).unwrap();
}

fn small_png(path: &Path, width: u32, height: u32) {
    image::GrayImage::from_pixel(width, height, image::Luma([128])).save(path).unwrap();
}

/// An index accessor without a bufferView whose sparse part (one index, one value) declares
/// 2²⁸ − 1 elements: 1 GiB of indices from a file under 1 KiB.
#[test]
fn a_declared_count_no_bytes_back_is_refused_by_the_budget() {
    let dir = temp_dir("sparse");
    let mut buffer = triangle_bytes();
    buffer.extend([0, 0, 0, 0, 0, 0, 0, 0]);
    let gltf = format!(
        r#"{{"asset": {{"version": "2.0"}},
        "buffers": [{{"uri": "{}", "byteLength": 44}}],
        "bufferViews": [{{"buffer": 0, "byteLength": 36}}, {{"buffer": 0, "byteOffset": 36, "byteLength": 1}},
                        {{"buffer": 0, "byteOffset": 40, "byteLength": 4}}],
        "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}},
                      {{"componentType": 5125, "count": 268435455, "type": "SCALAR",
                        "sparse": {{"count": 1, "indices": {{"bufferView": 1, "componentType": 5121}}, "values": {{"bufferView": 2}}}}}}],
        "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}, "indices": 1}}]}}],
        "nodes": [{{"mesh": 0}}], "scenes": [{{"nodes": [0]}}], "scene": 0}}"#,
        data_uri(&buffer)
    );
    let path = dir.join("sparse.gltf");
    std::fs::write(&path, gltf).unwrap();
    let error = load_patiently(&path).unwrap_err();
    assert!(error.contains("sparse.gltf") && error.contains("budget"), "{error}");
    let output = bumpview(&["check", path.to_str().unwrap()]);
    assert_eq!(output.status.code(), Some(2));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A 16384² header (a 261 KB grey PNG in the wild) is refused before a pixel is decoded, as
/// is a side past the GPU's limit; `check`, `render --normal`, `render --height` and
/// `bake --mips` all say so in one line.
#[test]
fn an_image_claiming_more_texels_than_a_texture_may_have_is_refused_from_its_header() {
    let dir = temp_dir("huge");
    let huge = dir.join("grey.png");
    png_header_only(&huge, 16384, 16384);
    let error = decode_texture(&std::fs::read(&huge).unwrap(), &huge, TextureKind::NormalMap).unwrap_err();
    let expected = format!("16384x16384 texels is over the {} Mi texels", MAX_TEXELS >> 20);
    assert!(error.to_string().contains(&expected), "{error}");
    let wide = dir.join("wide.png");
    png_header_only(&wide, 200_000, 1);
    let error = decode_texture(&std::fs::read(&wide).unwrap(), &wide, TextureKind::NormalMap).unwrap_err();
    assert!(error.to_string().contains(&format!("over the limit of {MAX_SIDE} per side")), "{error}");
    let out = dir.join("out.png");
    let (huge_arg, out_arg) = (huge.to_str().unwrap(), out.to_str().unwrap());
    for args in [
        vec!["check", huge_arg],
        vec!["render", "--normal", huge_arg, "--out", out_arg],
        vec!["render", "--height", huge_arg, "--out", out_arg],
        vec!["bake", "--mips", "toksvig", wide.to_str().unwrap(), "--out", dir.join("mips").to_str().unwrap()],
    ] {
        let output = bumpview(&args);
        let all = format!("{}{}", String::from_utf8_lossy(&output.stdout), String::from_utf8_lossy(&output.stderr));
        assert!(matches!(output.status.code(), Some(1 | 2)), "{args:?}: {all}");
        assert!(all.contains("texels is over"), "{args:?}: {all}");
        assert!(!all.contains("panicked"), "{args:?}: {all}");
    }
    assert!(!out.exists() && !dir.join("mips").join("wide_mip0.png").exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// An MTL naming one image 2,000 times, and an OBJ naming one MTL 2,000 times: one read,
/// one texture.
#[test]
fn an_image_or_library_named_again_is_read_once() {
    let dir = temp_dir("amplify");
    small_png(&dir.join("t.png"), 4, 4);
    let face = "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl m\nf 1/1 2/2 3/3\n";
    std::fs::write(dir.join("a.mtl"), format!("newmtl m\n{}", "map_Kd t.png\nbump t.png\n".repeat(2000))).unwrap();
    std::fs::write(dir.join("a.obj"), format!("mtllib a.mtl\n{face}")).unwrap();
    let scene = load_patiently(&dir.join("a.obj")).unwrap();
    // The colour texture, and the grey bump's height map and the normal map made from it.
    assert_eq!(scene.textures.len(), 3);
    std::fs::write(dir.join("b.mtl"), "newmtl m\nmap_Kd t.png\n").unwrap();
    std::fs::write(dir.join("b.obj"), format!("{}{face}", "mtllib b.mtl\n".repeat(2000))).unwrap();
    let scene = load_patiently(&dir.join("b.obj")).unwrap();
    assert_eq!((scene.textures.len(), scene.materials.len()), (1, 1));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A glTF without `scenes` whose nodes form one chain of 300,000 (root finding was a scan of
/// every child list per node), and an OBJ with 200,000 distinct `usemtl` names (a scan of the
/// groups per name).
#[test]
fn long_node_chains_and_many_material_names_load_in_linear_time() {
    let dir = temp_dir("walks");
    let count = 300_000;
    let nodes: Vec<String> = (0..count)
        .map(|i| if i + 1 < count { format!(r#"{{"children":[{}]}}"#, i + 1) } else { r#"{"mesh":0}"#.into() })
        .collect();
    let gltf = format!(
        r#"{{"asset":{{"version":"2.0"}},"buffers":[{{"uri":"{}","byteLength":36}}],"bufferViews":[{{"buffer":0,"byteLength":36}}],
        "accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}}],
        "meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}}}}]}}],"nodes":[{}]}}"#,
        data_uri(&triangle_bytes()),
        nodes.join(",")
    );
    std::fs::write(dir.join("chain.gltf"), gltf).unwrap();
    let scene = load_patiently(&dir.join("chain.gltf")).unwrap();
    assert_eq!(scene.instances.len(), 1);
    let names = 200_000;
    let mut obj = String::from("v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    (0..names).for_each(|i| obj.push_str(&format!("usemtl m{i}\nf 1 2 3\n")));
    std::fs::write(dir.join("names.obj"), obj).unwrap();
    let scene = load_patiently(&dir.join("names.obj")).unwrap();
    // Every name unknown (no library): one shared default material.
    assert_eq!((scene.meshes.len(), scene.materials.len()), (names, 1));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A triangle-list primitive of 2 indices is left out with a notice; the file's whole
/// triangle is drawn.
#[test]
fn a_primitive_without_a_whole_triangle_is_left_out_with_a_notice() {
    let dir = temp_dir("empty");
    let mut buffer = triangle_bytes();
    buffer.extend([0, 0, 1, 0]);
    let gltf = format!(
        r#"{{"asset": {{"version": "2.0"}}, "buffers": [{{"uri": "{}", "byteLength": 40}}],
        "bufferViews": [{{"buffer": 0, "byteLength": 36}}, {{"buffer": 0, "byteOffset": 36, "byteLength": 4}}],
        "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}},
                      {{"bufferView": 1, "componentType": 5123, "count": 2, "type": "SCALAR"}}],
        "meshes": [{{"name": "m", "primitives": [{{"attributes": {{"POSITION": 0}}, "indices": 1}}, {{"attributes": {{"POSITION": 0}}}}]}}],
        "nodes": [{{"mesh": 0}}], "scenes": [{{"nodes": [0]}}], "scene": 0}}"#,
        data_uri(&buffer)
    );
    std::fs::write(dir.join("two.gltf"), gltf).unwrap();
    let scene = load_patiently(&dir.join("two.gltf")).unwrap();
    assert_eq!((scene.meshes.len(), scene.instances.len()), (1, 1));
    assert!(scene.meshes.iter().all(|m| m.indices.len() == 3));
    assert_eq!(scene.warnings, [LoadWarning::EmptyPrimitive { mesh: "m #0".into() }]);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// 20,000 primitives reading one accessor make one mesh drawn 20,000 times, not 20,000 copies.
#[test]
fn primitives_reading_the_same_accessors_share_one_mesh() {
    let dir = temp_dir("shared");
    let primitives = vec![r#"{"attributes": {"POSITION": 0}}"#; 20_000].join(",");
    let gltf = format!(
        r#"{{"asset": {{"version": "2.0"}}, "buffers": [{{"uri": "{}", "byteLength": 36}}],
        "bufferViews": [{{"buffer": 0, "byteLength": 36}}],
        "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]}}],
        "meshes": [{{"primitives": [{primitives}]}}], "nodes": [{{"mesh": 0}}], "scenes": [{{"nodes": [0]}}], "scene": 0}}"#,
        data_uri(&triangle_bytes())
    );
    std::fs::write(dir.join("shared.gltf"), gltf).unwrap();
    let scene = load_patiently(&dir.join("shared.gltf")).unwrap();
    assert_eq!((scene.meshes.len(), scene.instances.len()), (1, 20_000));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `extras` is "application-specific data" of any JSON type (glTF 2.0 §5.1): an array, a
/// number or a string loads like an object.
#[test]
fn extras_of_any_json_type_are_accepted() {
    let dir = temp_dir("extras");
    for (name, extras) in [("array", "[1, 2]"), ("number", "3"), ("string", "\"x\"")] {
        let gltf = format!(
            r#"{{"asset": {{"version": "2.0"}}, "extras": {extras}, "buffers": [{{"uri": "{}", "byteLength": 36}}],
            "bufferViews": [{{"buffer": 0, "byteLength": 36}}],
            "accessors": [{{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0], "extras": {extras}}}],
            "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0}}, "extras": {extras}}}], "extras": {extras}}}],
            "nodes": [{{"mesh": 0, "extras": {extras}}}], "scenes": [{{"nodes": [0], "extras": {extras}}}], "scene": 0}}"#,
            data_uri(&triangle_bytes())
        );
        let path = dir.join(format!("{name}.gltf"));
        std::fs::write(&path, gltf).unwrap();
        let scene = load_patiently(&path).unwrap_or_else(|e| panic!("extras {name}: {e}"));
        assert_eq!(scene.instances.len(), 1);
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A JPEG cut before its end marker, its header patched to claim 16384²: `bake` refuses it
/// (exit 1, a failed input) instead of baking a grey remainder with exit 0.
#[test]
fn a_truncated_jpeg_does_not_bake() {
    let dir = temp_dir("jpeg");
    let mut encoded = Vec::new();
    let picture = image::RgbImage::from_fn(64, 64, |x, y| image::Rgb([(x * 4) as u8, (y * 4) as u8, 200]));
    picture.write_to(&mut std::io::Cursor::new(&mut encoded), image::ImageFormat::Jpeg).unwrap();
    let frame = encoded.windows(2).position(|w| w == [0xFF, 0xC0]).expect("a baseline frame header");
    encoded[frame + 5..frame + 9].copy_from_slice(&[0x40, 0x00, 0x40, 0x00]);
    encoded.truncate(encoded.len() * 2 / 3);
    let input = dir.join("cut.jpg");
    std::fs::write(&input, &encoded).unwrap();
    let out = dir.join("n.png");
    let output = bumpview(&["bake", input.to_str().unwrap(), "--out", out.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(matches!(output.status.code(), Some(1 | 2)), "{stderr}");
    assert!(stderr.contains("cut.jpg") && stderr.contains("truncated"), "{stderr}");
    assert!(!out.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}
