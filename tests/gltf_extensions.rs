//! glTF extensions real models use: Draco-compressed and quantized meshes, against the same
//! geometry stored plainly (the shared sample models, and a mesh quantized here); and the
//! framing of every loaded model.

mod common;

use std::path::{Path, PathBuf};

use bumpview::load::load_scene;
use bumpview::scene::Scene;
use common::{asset, assets};
use glam::{Mat4, Vec2, Vec3, Vec4};

/// Every drawn triangle's corners in world space, each triangle's corners rotated to start at
/// its smallest, sorted: equal for equal geometry whatever the vertex order.
fn world_triangles(scene: &Scene) -> Vec<[[i64; 3]; 3]> {
    let key = |p: Vec3| (p * 1e3).round().to_array().map(|c| c as i64);
    let mut triangles: Vec<[[i64; 3]; 3]> = scene
        .instances
        .iter()
        .flat_map(|instance| {
            let mesh = &scene.meshes[instance.mesh];
            mesh.indices.chunks_exact(3).map(move |t| {
                let mut corners =
                    [0, 1, 2].map(|k| key(instance.transform.transform_point3(mesh.positions[t[k] as usize])));
                let first = (0..3).min_by_key(|&k| corners[k]).unwrap();
                corners.rotate_left(first);
                corners
            })
        })
        .collect();
    triangles.sort();
    triangles
}

/// Draco's box decodes to the same 12 triangles as the plain Box sample (to a millimetre: the
/// stream quantizes positions), with unit normals.
#[test]
fn the_draco_box_is_the_plain_box() {
    let base = assets();
    let draco = load_scene(&asset(&base, "gltf/Box-Draco/Box.gltf")).unwrap_or_else(|e| panic!("{e}"));
    let plain = load_scene(&asset(&base, "gltf/Box/glTF/Box.gltf")).unwrap();
    assert_eq!(world_triangles(&draco).len(), 12);
    assert_eq!(world_triangles(&draco), world_triangles(&plain));
    let normals = &draco.meshes[0].normals;
    assert!(normals.iter().all(|n| (n.length() - 1.0).abs() < 1e-3), "{normals:?}");
}

/// The quantized morph cube (positions as unsigned shorts scaled by the node, normals as
/// normalised bytes) opens as a cube: 2 cm on a side after its node transforms, unit normals
/// each along a face axis, within the bytes' 1/127 steps.
#[test]
fn the_quantized_cube_reads_as_floats() {
    let base = assets();
    let path = asset(&base, "gltf/AnimatedMorphCube/glTF-Quantized/AnimatedMorphCube.gltf");
    let scene = load_scene(&path).unwrap_or_else(|e| panic!("{e}"));
    let (lo, hi) = bumpview::load::bounds(&scene).unwrap();
    let size = hi - lo;
    assert!((size - Vec3::splat(2.0)).abs().max_element() < 0.02, "{size}");
    for n in &scene.meshes[0].normals {
        assert!((n.length() - 1.0).abs() < 1e-6, "normalised after reading: {n}");
        assert!(n.abs().max_element() > 1.0 - 2.0 / 127.0, "along an axis: {n}");
    }
}

/// A triangle written here with every attribute quantized (positions as signed shorts scaled
/// by the node, normals and tangents as normalised bytes, UVs as normalised unsigned shorts)
/// loads as the float triangle it was made from, within each type's step.
#[test]
fn a_mesh_quantized_here_reads_back_within_one_step() {
    let positions = [Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.5)];
    let normal = Vec3::new(0.0, -0.4472136, 0.8944272);
    let tangent = Vec4::new(1.0, 0.0, 0.0, -1.0);
    let uvs = [Vec2::new(0.0, 1.0), Vec2::new(1.0, 1.0), Vec2::new(0.25, 0.0)];
    let scale = 1.0 / 32767.0;
    let mut bin = vec![];
    for p in positions {
        // VEC3 of shorts, padded to 8 bytes (glTF aligns vertex elements to 4 bytes).
        for c in p.to_array() {
            bin.extend(((c / scale).round() as i16).to_le_bytes());
        }
        bin.extend([0, 0]);
    }
    let byte = |c: f32| ((c * 127.0).round() as i8) as u8;
    for _ in 0..3 {
        bin.extend(normal.to_array().map(byte));
        bin.push(0);
    }
    for _ in 0..3 {
        bin.extend(tangent.to_array().map(byte));
    }
    for uv in uvs {
        for c in uv.to_array() {
            bin.extend(((c * 65535.0).round() as u16).to_le_bytes());
        }
    }
    let json = format!(
        r#"{{"asset": {{"version": "2.0"}}, "extensionsUsed": ["KHR_mesh_quantization"],
        "extensionsRequired": ["KHR_mesh_quantization"],
        "buffers": [{{"uri": "tri.bin", "byteLength": {}}}],
        "bufferViews": [
            {{"buffer": 0, "byteOffset": 0, "byteLength": 24, "byteStride": 8}},
            {{"buffer": 0, "byteOffset": 24, "byteLength": 12, "byteStride": 4}},
            {{"buffer": 0, "byteOffset": 36, "byteLength": 12, "byteStride": 4}},
            {{"buffer": 0, "byteOffset": 48, "byteLength": 12, "byteStride": 4}}],
        "accessors": [
            {{"bufferView": 0, "componentType": 5122, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [32767, 32767, 16384]}},
            {{"bufferView": 1, "componentType": 5120, "normalized": true, "count": 3, "type": "VEC3"}},
            {{"bufferView": 2, "componentType": 5120, "normalized": true, "count": 3, "type": "VEC4"}},
            {{"bufferView": 3, "componentType": 5123, "normalized": true, "count": 3, "type": "VEC2"}}],
        "meshes": [{{"primitives": [{{"attributes": {{"POSITION": 0, "NORMAL": 1, "TANGENT": 2, "TEXCOORD_0": 3}}}}]}}],
        "nodes": [{{"mesh": 0, "scale": [{scale:e}, {scale:e}, {scale:e}]}}], "scenes": [{{"nodes": [0]}}], "scene": 0}}"#,
        bin.len()
    );
    let dir = std::env::temp_dir().join(format!("bumpview-quantized-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("tri.bin"), &bin).unwrap();
    std::fs::write(dir.join("tri.gltf"), json).unwrap();
    let scene = load_scene(&dir.join("tri.gltf")).unwrap_or_else(|e| panic!("{e}"));
    std::fs::remove_dir_all(&dir).unwrap();
    let (mesh, transform) = (&scene.meshes[0], scene.instances[0].transform);
    assert_eq!(transform, Mat4::from_scale(Vec3::splat(scale)));
    for (read, made) in mesh.positions.iter().zip(positions) {
        assert!((transform.transform_point3(*read) - made).abs().max_element() <= 0.5 * scale, "{read} vs {made}");
    }
    // One step of a normalised byte is 1/127; the loader re-normalises normals.
    assert!(mesh.normals.iter().all(|n| (*n - normal).length() < 1.0 / 127.0), "{:?}", mesh.normals);
    let tangents = mesh.tangents.as_ref().unwrap();
    assert!(tangents.iter().all(|t| (*t - tangent).length() < 1.0 / 127.0), "{tangents:?}");
    for (read, made) in mesh.uvs.iter().zip(uvs) {
        assert!((*read - made).abs().max_element() <= 0.5 / 65535.0, "{read} vs {made}");
    }
}

/// Share of the view's height and width (at `aspect`) the scene's vertices span from its
/// default camera.
fn fill(scene: &Scene, aspect: f32) -> (f32, f32) {
    let view_projection = scene.default_camera.view_projection(aspect);
    let (mut lo, mut hi) = (Vec2::INFINITY, Vec2::NEG_INFINITY);
    for instance in &scene.instances {
        for p in &scene.meshes[instance.mesh].positions {
            let clip = view_projection * instance.transform.transform_point3(*p).extend(1.0);
            let ndc = clip.truncate().truncate() / clip.w;
            (lo, hi) = (lo.min(ndc), hi.max(ndc));
        }
    }
    let span = (hi - lo) * 0.5;
    (span.y, span.x)
}

/// Every model, whatever its units and node transforms, fills about two thirds of the view's
/// height (the vertex farthest from the centre sits at 2/3 of the half-height; the other side
/// may fall short when the model is not symmetric in the view), unless its width limits it
/// (then it spans most of the width); under a node that scales it 100× and moves it, the same.
#[test]
fn a_loaded_model_fills_two_thirds_of_the_views_height() {
    let base = assets();
    let mut models = vec![];
    for folder in [base.join("gltf"), base.join("obj")] {
        collect_models(&folder, &mut models);
    }
    assert!(models.len() >= 15, "{models:?}");
    let aspect = 1280.0 / 800.0;
    for model in models {
        let mut scene = load_scene(&model).unwrap_or_else(|e| panic!("{e}"));
        let (height, width) = fill(&scene, aspect);
        println!("{}: height {height:.3}, width {width:.3}", model.display());
        let width_limited = width * aspect > 0.85;
        assert!((0.5..=0.67).contains(&height) || width_limited, "{}: height {height}", model.display());
        assert!(height <= 0.67 && width <= 1.0, "{}: height {height}, width {width}", model.display());
        let moved = Mat4::from_translation(Vec3::new(300.0, -20.0, 5.0)) * Mat4::from_scale(Vec3::splat(100.0));
        scene.instances.iter_mut().for_each(|i| i.transform = moved * i.transform);
        bumpview::load::frame_scene(&mut scene);
        let (scaled_height, _) = fill(&scene, aspect);
        assert!((scaled_height - height).abs() < 1e-3, "{}: {height} vs {scaled_height} scaled", model.display());
    }
}

fn collect_models(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap().map(Result::unwrap) {
        let path = entry.path();
        if path.is_dir() {
            collect_models(&path, out);
        } else if path.extension().is_some_and(|e| ["gltf", "glb", "obj"].contains(&&*e.to_string_lossy())) {
            out.push(path);
        }
    }
}

/// A clear-coat material written here: its factors, its three textures (one missing: its slot
/// stays empty with a warning), and its own `KHR_texture_transform` taken relative to the one
/// the mesh's coordinates carry (the normal map's), so the layer reads its texture where the
/// file says.
#[test]
fn a_clear_coat_written_here_loads_with_its_textures_and_transform() {
    let dir = std::env::temp_dir().join(format!("bumpview-clearcoat-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    image::RgbaImage::from_pixel(4, 4, image::Rgba([128, 128, 255, 255])).save(dir.join("n.png")).unwrap();
    image::RgbaImage::from_pixel(4, 4, image::Rgba([200, 60, 0, 255])).save(dir.join("cc.png")).unwrap();
    let values: [f32; 15] = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 1.0, 0.0, 0.0];
    std::fs::write(dir.join("tri.bin"), values.iter().flat_map(|v| v.to_le_bytes()).collect::<Vec<u8>>()).unwrap();
    let json = r#"{"asset": {"version": "2.0"}, "extensionsUsed": ["KHR_materials_clearcoat", "KHR_texture_transform"],
        "images": [{"uri": "n.png"}, {"uri": "cc.png"}, {"uri": "gone.png"}],
        "textures": [{"source": 0}, {"source": 1}, {"source": 2}],
        "materials": [{"normalTexture": {"index": 0, "extensions": {"KHR_texture_transform": {"offset": [0.5, 0], "scale": [2, 2]}}},
            "extensions": {"KHR_materials_clearcoat": {"clearcoatFactor": 0.8, "clearcoatRoughnessFactor": 0.25,
                "clearcoatTexture": {"index": 1, "extensions": {"KHR_texture_transform": {"offset": [0.1, 0.2], "rotation": 0.5, "scale": [4, 3]}}},
                "clearcoatRoughnessTexture": {"index": 2},
                "clearcoatNormalTexture": {"index": 0, "scale": 0.5}}}}],
        "buffers": [{"uri": "tri.bin", "byteLength": 60}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 36}, {"buffer": 0, "byteOffset": 36, "byteLength": 24}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3", "min": [0, 0, 0], "max": [1, 1, 0]},
            {"bufferView": 1, "componentType": 5126, "count": 3, "type": "VEC2"}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 1}, "material": 0}]}],
        "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0}"#;
    std::fs::write(dir.join("cc.gltf"), json).unwrap();
    let scene = load_scene(&dir.join("cc.gltf")).unwrap_or_else(|e| panic!("{e}"));
    std::fs::remove_dir_all(&dir).unwrap();
    let coat = scene.materials[0].clearcoat.as_ref().expect("a clear coat");
    assert_eq!((coat.factor, coat.roughness), (0.8, 0.25));
    assert!(coat.texture.is_some() && coat.normal_map.as_ref().is_some_and(|m| m.scale == 0.5));
    assert_eq!(coat.roughness_texture, None, "gone.png is missing");
    assert!(scene.warnings.iter().any(|w| w.to_string().contains("gone.png")), "{:?}", scene.warnings);
    // The file's coordinates r: the mesh holds the normal map's s = 2r + (0.5, 0); the coat
    // texture reads t = offset + R(rotation) · (scale ∘ r).
    let (sin, cos) = 0.5f32.sin_cos();
    for r in [Vec2::ZERO, Vec2::new(1.0, 0.0), Vec2::new(0.3, 0.7)] {
        let stream = 2.0 * r + Vec2::new(0.5, 0.0);
        let scaled = r * Vec2::new(4.0, 3.0);
        let expected =
            Vec2::new(0.1, 0.2) + Vec2::new(cos * scaled.x + sin * scaled.y, -sin * scaled.x + cos * scaled.y);
        let got = coat.layer_uv(stream);
        assert!((got - expected).abs().max_element() < 1e-5, "{r}: {got} vs {expected}");
    }
    // The mesh drawn with this coat has the layer's normal map, so it gets a tangent stream.
    let prepared = bumpview::prepare::PreparedScene::new(&scene, &Default::default());
    assert!(prepared.instances[0].textures.clearcoat_normal.is_some() && prepared.meshes[0].frames.is_some());
}
