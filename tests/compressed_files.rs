//! GPU texture files opened as normal maps: DDS (BC5, BC7), KTX2 (UASTC, Zstandard) and WebP
//! fixtures of the brick normal map (tests/fixtures/compressed, made by `make_fixtures`) draw
//! the built-in scene within a measured distance of the same map as PNG, and `check` reads
//! each with the layout its format states.

mod common;

use std::path::{Path, PathBuf};

use bumpview::check::check_normal_maps;
use bumpview::load::{SceneFiles, load_scene, replace_textures, texture_scene};
use bumpview::names::Named;
use bumpview::render::capture::render_image;
use bumpview::scene::{NormalLayout, Scene};
use common::*;

fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/compressed")
}

/// The side of the fixtures, texels.
const SIDE: u32 = 256;

/// Writes the fixtures: the built-in brick normal map resized to [`SIDE`]² (triangle filter)
/// as PNG (the reference), lossless WebP, DDS BC5 and BC7 and KTX2 UASTC. Run with
/// `cargo test --test compressed_files -- --ignored make_fixtures`.
#[test]
#[ignore]
fn make_fixtures() {
    use bumpview::bake::compressed_out::{CompressedFormat, encode};
    let scene = scene();
    let normal = &scene.textures[scene.materials[0].normal_map.as_ref().unwrap().texture];
    let full = image::RgbaImage::from_raw(normal.width, normal.height, normal.rgba.clone()).unwrap();
    let small = image::imageops::resize(&full, SIDE, SIDE, image::imageops::FilterType::Triangle);
    let folder = fixtures();
    std::fs::create_dir_all(&folder).unwrap();
    image::DynamicImage::ImageRgba8(small.clone()).into_rgb8().save(folder.join("brick_normal.png")).unwrap();
    let mut webp = Vec::new();
    let rgb = image::DynamicImage::ImageRgba8(small.clone()).into_rgb8();
    image::codecs::webp::WebPEncoder::new_lossless(&mut webp)
        .encode(rgb.as_raw(), SIDE, SIDE, image::ExtendedColorType::Rgb8)
        .unwrap();
    std::fs::write(folder.join("brick_normal.webp"), webp).unwrap();
    write_quads(&folder);
    for (name, format) in [
        ("brick_normal_bc5.dds", CompressedFormat::DdsBc5),
        ("brick_normal_bc7.dds", CompressedFormat::DdsBc7),
        ("brick_normal_uastc.ktx2", CompressedFormat::Ktx2Uastc),
    ] {
        std::fs::write(folder.join(name), encode(small.as_raw(), SIDE, SIDE, format).unwrap()).unwrap();
    }
}

/// A 2 m square facing +Z (positions, normals, UVs, two triangles) in `quad.bin`, and three
/// glTF files drawing it with the brick normal map: as PNG, as KTX2 through
/// `KHR_texture_basisu` (required, no fallback) and as WebP through `EXT_texture_webp` (used,
/// with the PNG as fallback `source`).
fn write_quads(folder: &Path) {
    let mut bin = Vec::new();
    let floats: [f32; 32] = [
        -1., -1., 0., 1., -1., 0., 1., 1., 0., -1., 1., 0., // positions
        0., 0., 1., 0., 0., 1., 0., 0., 1., 0., 0., 1., // normals
        0., 1., 1., 1., 1., 0., 0., 0., // UVs
    ];
    floats.iter().for_each(|f| bin.extend(f.to_le_bytes()));
    [0u16, 1, 2, 0, 2, 3].iter().for_each(|i| bin.extend(i.to_le_bytes()));
    std::fs::write(folder.join("quad.bin"), &bin).unwrap();
    let gltf = |texture: &str, images: &str, required: &str, used: &str| {
        format!(
            r#"{{"asset":{{"version":"2.0"}},{required}"extensionsUsed":[{used}],
"buffers":[{{"uri":"quad.bin","byteLength":140}}],
"bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":128}},{{"buffer":0,"byteOffset":128,"byteLength":12}}],
"accessors":[
 {{"bufferView":0,"byteOffset":0,"componentType":5126,"count":4,"type":"VEC3","min":[-1,-1,0],"max":[1,1,0]}},
 {{"bufferView":0,"byteOffset":48,"componentType":5126,"count":4,"type":"VEC3"}},
 {{"bufferView":0,"byteOffset":96,"componentType":5126,"count":4,"type":"VEC2"}},
 {{"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0,"NORMAL":1,"TEXCOORD_0":2}},"indices":3,"material":0}}]}}],
"materials":[{{"pbrMetallicRoughness":{{"metallicFactor":0,"roughnessFactor":0.4}},"normalTexture":{{"index":0}}}}],
"textures":[{texture}],
"images":[{images}],
"nodes":[{{"mesh":0}}],"scenes":[{{"nodes":[0]}}],"scene":0}}
"#
        )
    };
    let png = r#"{"uri":"brick_normal.png"}"#;
    std::fs::write(folder.join("quad_png.gltf"), gltf(r#"{"source":0}"#, png, "", "")).unwrap();
    let basisu = gltf(
        r#"{"extensions":{"KHR_texture_basisu":{"source":0}}}"#,
        r#"{"uri":"brick_normal_uastc.ktx2","mimeType":"image/ktx2"}"#,
        r#""extensionsRequired":["KHR_texture_basisu"],"#,
        r#""KHR_texture_basisu""#,
    );
    std::fs::write(folder.join("quad_basisu.gltf"), basisu).unwrap();
    let webp = gltf(
        r#"{"source":1,"extensions":{"EXT_texture_webp":{"source":0}}}"#,
        &format!(r#"{{"uri":"brick_normal.webp","mimeType":"image/webp"}},{png}"#),
        "",
        r#""EXT_texture_webp""#,
    );
    std::fs::write(folder.join("quad_webp.gltf"), webp).unwrap();
}

/// The built-in scene with `normal` as every material's normal map.
fn with_normal_map(normal: &Path) -> Scene {
    let mut scene = scene();
    let files = SceneFiles { normal: Some(normal.to_owned()), ..Default::default() };
    replace_textures(&mut scene, &files).unwrap_or_else(|e| panic!("{e}"));
    scene
}

/// Root mean square difference of two pictures' RGB, 0..255.
fn rmse(a: &image::RgbaImage, b: &image::RgbaImage) -> f64 {
    let sum: f64 =
        a.pixels().zip(b.pixels()).flat_map(|(p, q)| (0..3).map(move |c| (p[c] as f64 - q[c] as f64).powi(2))).sum();
    (sum / (a.width() * a.height() * 3) as f64).sqrt()
}

/// Each fixture, the layout `check` must read it with, the start of its reason, and the RMSE
/// bound of its picture against the PNG's (0..255; docs/compressed.md has the measurements).
const CASES: [(&str, NormalLayout, &str, f64); 4] = [
    ("brick_normal.webp", NormalLayout::Rgb, "as loaded", 0.0),
    ("brick_normal_bc5.dds", NormalLayout::Rg, "BC5 DDS: two channels", 1.0),
    ("brick_normal_bc7.dds", NormalLayout::Rgb, "BC7 DDS: three or four channels", 0.5),
    ("brick_normal_uastc.ktx2", NormalLayout::Rgb, "UASTC KTX2 (Zstandard): three or four", 0.5),
];

#[test]
fn compressed_normal_maps_draw_like_the_png_and_check_reads_their_layout() {
    let size = [640, 360];
    let reference_scene = with_normal_map(&fixtures().join("brick_normal.png"));
    let mut renderer = renderer_for(&reference_scene);
    let params = default_params(&reference_scene);
    let reference = render_image(&mut renderer, size, &params).unwrap();
    // The scale of the bounds: the same picture without a normal map.
    let mut flat_scene = reference_scene.clone();
    flat_scene.materials.iter_mut().for_each(|m| (m.normal_map, m.height_map) = (None, None));
    renderer.set_scene(&flat_scene, Default::default());
    let flat = rmse(&reference, &render_image(&mut renderer, size, &default_params(&flat_scene)).unwrap());
    println!("without a normal map: RMSE {flat:.3} against the PNG");
    assert!(flat > 4.0, "the normal map changes the picture by RMSE {flat:.3} only");
    for (name, layout, reason, bound) in CASES {
        let path = fixtures().join(name);
        let scene = with_normal_map(&path);
        renderer.set_scene(&scene, Default::default());
        let picture = render_image(&mut renderer, size, &default_params(&scene)).unwrap();
        let distance = rmse(&reference, &picture);
        println!("{name}: RMSE {distance:.3} against the PNG");
        assert!(distance <= bound, "{name}: RMSE {distance:.3} over {bound}");
        let checked = check_normal_maps(&texture_scene(&path).unwrap());
        let found = &checked[0];
        println!("{name}: layout {} ({})", found.layout.name(), found.layout_reason);
        assert_eq!(found.layout, layout, "{name}");
        assert!(found.layout_reason.starts_with(reason), "{name}: {}", found.layout_reason);
    }
}

/// A glTF model drawn at its opening view, without load warnings.
fn drawn_model(renderer: &mut bumpview::render::Renderer, path: &Path, size: [u32; 2]) -> image::RgbaImage {
    let scene = load_scene(path).unwrap_or_else(|e| panic!("{e}"));
    assert!(scene.warnings.is_empty(), "{}: {:?}", path.display(), scene.warnings);
    renderer.set_scene(&scene, Default::default());
    render_image(renderer, size, &default_params(&scene)).unwrap()
}

/// KTX2 through `KHR_texture_basisu` (required) and WebP through `EXT_texture_webp` draw the
/// quad as its PNG-textured twin does (measured: RMSE 0.635 for UASTC, seen closer than on
/// the built-in scene; 0 for lossless WebP), and `check` names the KTX2 format.
#[test]
fn gltf_textures_by_basisu_and_webp_draw_like_png() {
    let size = [480, 480];
    let folder = fixtures();
    let mut renderer = renderer_for(&scene());
    let reference = drawn_model(&mut renderer, &folder.join("quad_png.gltf"), size);
    for (name, bound) in [("quad_basisu.gltf", 1.0), ("quad_webp.gltf", 0.0)] {
        let picture = drawn_model(&mut renderer, &folder.join(name), size);
        let distance = rmse(&reference, &picture);
        println!("{name}: RMSE {distance:.3} against quad_png.gltf");
        assert!(distance <= bound, "{name}: RMSE {distance:.3} over {bound}");
    }
    let checked = check_normal_maps(&load_scene(&folder.join("quad_basisu.gltf")).unwrap());
    assert!(checked[0].layout_reason.starts_with("UASTC KTX2 (Zstandard)"), "{}", checked[0].layout_reason);
}
