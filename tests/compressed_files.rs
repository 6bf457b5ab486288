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
/// as PNG (the reference), lossless WebP, DDS BC1, DXT5nm, BC5 and BC7 and KTX2 UASTC and
/// ETC1S; BC5 and UASTC also with their mip chains; the
/// quads and grids of [`write_quads`] and [`write_grids`]. Run with
/// `cargo test --test compressed_files -- --ignored make_fixtures`.
#[test]
#[ignore]
fn make_fixtures() {
    use bumpview::bake::compressed_out::{CompressedFormat, encode, encode_with_mips};
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
    write_grids(&folder);
    for (name, format) in [
        ("brick_normal_bc1.dds", CompressedFormat::DdsBc1),
        ("brick_normal_dxt5nm.dds", CompressedFormat::DdsDxt5nm),
        ("brick_normal_bc5.dds", CompressedFormat::DdsBc5),
        ("brick_normal_bc7.dds", CompressedFormat::DdsBc7),
        ("brick_normal_uastc.ktx2", CompressedFormat::Ktx2Uastc),
        ("brick_normal_etc1s.ktx2", CompressedFormat::Ktx2Etc1s),
    ] {
        std::fs::write(folder.join(name), encode(small.as_raw(), SIDE, SIDE, format).unwrap()).unwrap();
    }
    for (name, format) in [
        ("brick_normal_bc5_mips.dds", CompressedFormat::DdsBc5),
        ("brick_normal_uastc_mips.ktx2", CompressedFormat::Ktx2Uastc),
    ] {
        std::fs::write(folder.join(name), encode_with_mips(small.as_raw(), SIDE, SIDE, format).unwrap()).unwrap();
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

/// Cells per side of the waved grid of [`write_grids`].
const CELLS: usize = 24;

/// Positions, normals, UVs and triangle corners of a mesh.
type Streams = (Vec<[f32; 3]>, Vec<[f32; 3]>, Vec<[f32; 2]>, Vec<u32>);

/// The grid: 2 m square, z = 0.05·sin(πx)·sin(πy) m, its analytic unit normals, UVs (v down)
/// and two triangles a cell.
fn grid() -> Streams {
    use std::f32::consts::PI;
    let (mut positions, mut normals, mut uvs, mut indices) = (vec![], vec![], vec![], vec![]);
    for j in 0..=CELLS {
        for i in 0..=CELLS {
            let (x, y) = (i as f32 / CELLS as f32 * 2.0 - 1.0, j as f32 / CELLS as f32 * 2.0 - 1.0);
            positions.push([x, y, 0.05 * (PI * x).sin() * (PI * y).sin()]);
            let (dx, dy) = (0.05 * PI * (PI * x).cos() * (PI * y).sin(), 0.05 * PI * (PI * x).sin() * (PI * y).cos());
            let n = glam::Vec3::new(-dx, -dy, 1.0).normalize();
            normals.push(n.to_array());
            uvs.push([(x + 1.0) / 2.0, (1.0 - y) / 2.0]);
        }
    }
    let at = |i: usize, j: usize| (j * (CELLS + 1) + i) as u32;
    for j in 0..CELLS {
        for i in 0..CELLS {
            indices.extend([at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    (positions, normals, uvs, indices)
}

/// The glTF of the grid: `buffers`, `views` (JSON arrays' contents), four accessors over views
/// 0–3 (position, normal as `normal` accessor fields, UV, 16-bit indices) and the brick normal
/// map.
fn grid_gltf(extensions: &str, buffers: &str, views: &str, normal: &str) -> String {
    let (v, i) = ((CELLS + 1) * (CELLS + 1), CELLS * CELLS * 6);
    format!(
        r#"{{"asset":{{"version":"2.0"}},{extensions}
"buffers":[{buffers}],"bufferViews":[{views}],
"accessors":[
 {{"bufferView":0,"componentType":5126,"count":{v},"type":"VEC3","min":[-1,-1,-0.05],"max":[1,1,0.05]}},
 {{"bufferView":1,"count":{v},"type":"VEC3",{normal}}},
 {{"bufferView":2,"componentType":5126,"count":{v},"type":"VEC2"}},
 {{"bufferView":3,"componentType":5123,"count":{i},"type":"SCALAR"}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0,"NORMAL":1,"TEXCOORD_0":2}},"indices":3,"material":0}}]}}],
"materials":[{{"pbrMetallicRoughness":{{"metallicFactor":0,"roughnessFactor":0.4}},"normalTexture":{{"index":0}}}}],
"textures":[{{"source":0}}],"images":[{{"uri":"brick_normal.png"}}],
"nodes":[{{"mesh":0}}],"scenes":[{{"nodes":[0]}}],"scene":0}}
"#
    )
}

/// The waved grid twice: `grid_plain.gltf` (float normals, plain buffer) and
/// `grid_meshopt.gltf` (`EXT_meshopt_compression` required: meshoptimizer's vertex codec for
/// positions and UVs, its octahedral filter on 12-bit normals in 16-bit slots, its index codec
/// for the triangles; the fallback buffer holds no data).
fn write_grids(folder: &Path) {
    let (positions, normals, uvs, indices) = grid();
    let bytes = |floats: &[f32]| floats.iter().flat_map(|f| f.to_le_bytes()).collect::<Vec<u8>>();
    let short: Vec<u8> = indices.iter().flat_map(|&i| (i as u16).to_le_bytes()).collect();
    let streams = [bytes(positions.as_flattened()), bytes(normals.as_flattened()), bytes(uvs.as_flattened()), short];
    let mut plain = Vec::new();
    let mut views = vec![];
    for (n, stream) in streams.iter().enumerate() {
        let stride = [r#","byteStride":12"#, r#","byteStride":12"#, r#","byteStride":8"#, ""][n];
        views.push(format!(r#"{{"buffer":0,"byteOffset":{},"byteLength":{}{stride}}}"#, plain.len(), stream.len()));
        plain.extend(stream);
    }
    std::fs::write(folder.join("grid_plain.bin"), &plain).unwrap();
    let plain_json = grid_gltf(
        "",
        &format!(r#"{{"uri":"grid_plain.bin","byteLength":{}}}"#, plain.len()),
        &views.join(","),
        r#""componentType":5126"#,
    );
    std::fs::write(folder.join("grid_plain.gltf"), plain_json).unwrap();

    let with_w: Vec<[f32; 4]> = normals.iter().map(|n| [n[0], n[1], n[2], 0.0]).collect();
    let octahedral: Vec<[i16; 4]> = meshopt::encode_filter_oct(&with_w, 12);
    let packed = [
        (meshopt::encode_vertex_buffer(&positions).unwrap(), 12, positions.len(), "ATTRIBUTES", "NONE"),
        (meshopt::encode_vertex_buffer(&octahedral).unwrap(), 8, normals.len(), "ATTRIBUTES", "OCTAHEDRAL"),
        (meshopt::encode_vertex_buffer(&uvs).unwrap(), 8, uvs.len(), "ATTRIBUTES", "NONE"),
        (meshopt::encode_index_buffer(&indices, positions.len()).unwrap(), 2, indices.len(), "TRIANGLES", "NONE"),
    ];
    let (mut compressed, mut decoded_at, mut views) = (Vec::new(), 0, vec![]);
    for (n, (stream, stride, count, mode, filter)) in packed.iter().enumerate() {
        let view_stride = if n == 3 { String::new() } else { format!(r#","byteStride":{stride}"#) };
        views.push(format!(
            r#"{{"buffer":1,"byteOffset":{decoded_at},"byteLength":{}{view_stride},"extensions":{{"EXT_meshopt_compression":{{"buffer":0,"byteOffset":{},"byteLength":{},"byteStride":{stride},"count":{count},"mode":"{mode}","filter":"{filter}"}}}}}}"#,
            stride * count,
            compressed.len(),
            stream.len()
        ));
        compressed.extend(stream);
        compressed.resize(compressed.len().next_multiple_of(4), 0);
        decoded_at += (stride * count).next_multiple_of(4);
    }
    std::fs::write(folder.join("grid_meshopt.bin"), &compressed).unwrap();
    let meshopt_json = grid_gltf(
        r#""extensionsUsed":["EXT_meshopt_compression","KHR_mesh_quantization"],"extensionsRequired":["EXT_meshopt_compression","KHR_mesh_quantization"],"#,
        &format!(
            r#"{{"uri":"grid_meshopt.bin","byteLength":{}}},{{"byteLength":{decoded_at},"extensions":{{"EXT_meshopt_compression":{{"fallback":true}}}}}}"#,
            compressed.len()
        ),
        &views.join(","),
        r#""componentType":5122,"normalized":true"#,
    );
    std::fs::write(folder.join("grid_meshopt.gltf"), meshopt_json).unwrap();
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
const CASES: [(&str, NormalLayout, &str, f64); 6] = [
    ("brick_normal.webp", NormalLayout::Rgb, "as loaded", 0.0),
    ("brick_normal_bc5.dds", NormalLayout::Rg, "BC5 DDS: two channels", 1.0),
    ("brick_normal_dxt5nm.dds", NormalLayout::Ag, "BC3 DDS: DXT5nm", 1.0),
    ("brick_normal_bc1.dds", NormalLayout::Rgb, "BC1 DDS: three channels in a block format made for colour", 1.5),
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
        // A two-channel map's statistics read x and y, its z rebuilt: none below the surface.
        if layout != NormalLayout::Rgb {
            let f = &found.findings;
            assert!(f.negative_z_share == 0.0 && f.non_unit_share < 0.01, "{name}: {f:?}");
        }
        let warned = found.warnings().iter().any(|w| w.contains("block format made for colour"));
        assert_eq!(warned, name.contains("bc1"), "{name}: {:?}", found.warnings());
    }
}

/// ETC1S (BasisLZ) KTX2: drawn within RMSE 2.0 of the PNG (measured 1.563).
#[test]
fn etc1s_normal_maps_draw_near_the_png() {
    let path = fixtures().join("brick_normal_etc1s.ktx2");
    let size = [640, 360];
    let reference_scene = with_normal_map(&fixtures().join("brick_normal.png"));
    let mut renderer = renderer_for(&reference_scene);
    let reference = render_image(&mut renderer, size, &default_params(&reference_scene)).unwrap();
    let scene = with_normal_map(&path);
    renderer.set_scene(&scene, Default::default());
    let distance = rmse(&reference, &render_image(&mut renderer, size, &default_params(&scene)).unwrap());
    println!("brick_normal_etc1s.ktx2: RMSE {distance:.3} against the PNG");
    assert!(distance <= 2.0, "RMSE {distance:.3}");
    let found = &check_normal_maps(&texture_scene(&path).unwrap())[0];
    assert!(found.layout_reason.starts_with("ETC1S KTX2 (BasisLZ): three channels"), "{}", found.layout_reason);
    assert!(found.warnings().iter().any(|w| w.contains("block format made for colour")));
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

/// The meshopt-compressed grid draws as its plain twin: positions, UVs and triangles decode
/// exactly; the normals carry 12-bit octahedral quantisation (measured: within 0.020° of the
/// plain normals, picture RMSE 0.060).
#[test]
fn a_meshopt_compressed_model_draws_like_its_plain_twin() {
    let size = [480, 480];
    let folder = fixtures();
    let plain = load_scene(&folder.join("grid_plain.gltf")).unwrap();
    let packed = load_scene(&folder.join("grid_meshopt.gltf")).unwrap_or_else(|e| panic!("{e}"));
    assert!(plain.meshes[0].positions == packed.meshes[0].positions, "positions differ");
    assert!(plain.meshes[0].uvs == packed.meshes[0].uvs, "UVs differ");
    // The index codec may rotate a triangle's corners (winding kept).
    let rotated = |t: &[u32]| (0..3).map(|r| [t[r], t[(r + 1) % 3], t[(r + 2) % 3]]).min().unwrap();
    let triangles = |m: &bumpview::scene::Mesh| m.indices.chunks_exact(3).map(rotated).collect::<Vec<_>>();
    assert!(triangles(&plain.meshes[0]) == triangles(&packed.meshes[0]), "triangles differ");
    let worst = plain.meshes[0].normals.iter().zip(&packed.meshes[0].normals).map(|(a, b)| a.angle_between(*b));
    let worst = worst.fold(0.0f32, f32::max).to_degrees();
    println!("grid_meshopt.gltf: normals within {worst:.3}° of the plain ones");
    assert!(worst < 0.1, "{worst}°");
    let mut renderer = renderer_for(&scene());
    let reference = drawn_model(&mut renderer, &folder.join("grid_plain.gltf"), size);
    let picture = drawn_model(&mut renderer, &folder.join("grid_meshopt.gltf"), size);
    let distance = rmse(&reference, &picture);
    println!("grid_meshopt.gltf: RMSE {distance:.3} against grid_plain.gltf");
    assert!(distance <= 0.25, "RMSE {distance:.3}");
}

/// `bake --format` writes the committed fixtures again, byte for byte, from the PNG.
#[test]
fn bake_format_writes_the_fixtures_again() {
    let dir = std::env::temp_dir().join(format!("bumpview-bake-format-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (format, fixture) in [
        ("dds-bc5", "brick_normal_bc5.dds"),
        ("dds-bc5 --with-mips", "brick_normal_bc5_mips.dds"),
        ("ktx2-uastc --with-mips", "brick_normal_uastc_mips.ktx2"),
        ("ktx2-uastc", "brick_normal_uastc.ktx2"),
    ] {
        let out = dir.join(fixture);
        let status = std::process::Command::new(env!("CARGO_BIN_EXE_bumpview"))
            .arg("bake")
            .arg("--format")
            .args(format.split(' '))
            .args(["--force", "--out"])
            .arg(&out)
            .arg(fixtures().join("brick_normal.png"))
            .status()
            .unwrap();
        assert!(status.success(), "{format}");
        assert!(std::fs::read(&out).unwrap() == std::fs::read(fixtures().join(fixture)).unwrap(), "{format}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The `compression` split draws its right half with the normal map the loader reads from the
/// bake's file: with the brick PNG loaded, the BC5 split's right half equals, pixel for pixel,
/// the scene opened with the committed BC5 fixture (the same encoder's output, byte for byte),
/// and its left half the PNG's picture. 2× supersampled, so every 2×2 block lies in one half.
#[test]
fn the_compression_splits_right_half_is_the_map_read_from_its_file() {
    use bumpview::bake::compressed_format::CompressedFormat;
    use bumpview::frame::FrameParams;
    use bumpview::render::capture::{CaptureOptions, render_capture, render_capture_split};
    use bumpview::state::{Command, SplitDifference, ViewerState};
    let size = [160, 96];
    let scene = with_normal_map(&fixtures().join("brick_normal.png"));
    let mut renderer = renderer_for(&scene);
    let mut state = ViewerState::new(&scene);
    state.shading.show_light_marker = false;
    state.apply(Command::SetSplit(true));
    state.apply(Command::SetSplitDifference(SplitDifference::Compression));
    state.apply(Command::SetSplitCompression(CompressedFormat::DdsBc5));
    let preset = bumpview::state::preset::Preset::from_state(&state, Default::default());
    let kept = bumpview::state::preset::Preset::from_toml(&preset.to_toml()).unwrap().to_state(&scene).unwrap();
    assert_eq!(kept.split, state.split, "a preset keeps the split's format");
    let uploads = state.scene_uploads();
    assert_eq!(uploads.split_right.as_ref().unwrap().normal_maps_through, Some(CompressedFormat::DdsBc5));
    renderer.set_scene_uploads(&scene, &uploads);
    let (params, split) = (state.frame_params(), state.split_frame().unwrap());
    let options = CaptureOptions { supersample: 2, ..CaptureOptions::plain(size) };
    let image = render_capture_split(&mut renderer, &options, &params, &split).unwrap();
    let divider = split.divider_pixels(size[0]);
    let mut full = |scene: &Scene, shading| {
        renderer.set_scene(scene, uploads.main.clone());
        render_capture(&mut renderer, &options, &FrameParams { shading, ..params }).unwrap()
    };
    let left = full(&scene, split.left);
    let right = full(&with_normal_map(&fixtures().join("brick_normal_bc5.dds")), split.right);
    assert_ne!(left, right, "BC5 must change the picture for the test to mean anything");
    for y in 0..size[1] {
        for x in 0..size[0] {
            let expected = if x < divider { &left } else { &right };
            assert_eq!(image.get_pixel(x, y), expected.get_pixel(x, y), "pixel ({x}, {y})");
        }
    }
}
