//! GPU texture files opened as normal maps: DDS (BC5, BC7), KTX2 (UASTC, Zstandard) and WebP
//! fixtures of the brick normal map (tests/fixtures/compressed, made by `make_fixtures`) draw
//! the built-in scene within a measured distance of the same map as PNG, and `check` reads
//! each with the layout its format states.

mod common;

use std::path::{Path, PathBuf};

use bumpview::check::check_normal_maps;
use bumpview::load::{SceneFiles, replace_textures, texture_scene};
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
    for (name, format) in [
        ("brick_normal_bc5.dds", CompressedFormat::DdsBc5),
        ("brick_normal_bc7.dds", CompressedFormat::DdsBc7),
        ("brick_normal_uastc.ktx2", CompressedFormat::Ktx2Uastc),
    ] {
        std::fs::write(folder.join(name), encode(small.as_raw(), SIDE, SIDE, format).unwrap()).unwrap();
    }
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
