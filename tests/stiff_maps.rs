//! Stiff and extreme normal and height maps: texels pointing into the surface, 1×1 textures,
//! a cliff in 8- and 16-bit heights, and a normal-mapped material on a mesh without UVs. Each
//! renders to a float target on the software adapter and must have no NaN or infinity.

mod common;

use bumpview::frame::FrameParams;
use bumpview::frame::ViewMode;
use bumpview::height::{Border, HeightField, Kernel};
use bumpview::names::Named;
use bumpview::render::capture::{render_float, render_image};
use bumpview::scene::{Scene, TextureImage};
use common::*;

fn assert_finite_everywhere(scene: &Scene, params: &FrameParams, case: &str) {
    let mut renderer = renderer_for(scene);
    for &view in ViewMode::all() {
        let mut params = *params;
        params.shading.view = view;
        let image = render_float(&mut renderer, [96, 72], &params).unwrap();
        let bad = image.pixels.iter().filter(|p| p.iter().any(|c| !c.is_finite())).count();
        assert_eq!(bad, 0, "{case}, {view:?}: {bad} non-finite pixels");
    }
}

/// The built-in scene with its normal map replaced by `width × height` texels of `rgb`.
fn with_normal_map(width: u32, height: u32, rgb: [u8; 3]) -> Scene {
    let mut scene = scene();
    let texture = scene.materials[0].normal_map.as_ref().unwrap().texture;
    let rgba = [rgb[0], rgb[1], rgb[2], 255].repeat((width * height) as usize);
    scene.textures[texture] = TextureImage { width, height, rgba, ..scene.textures[texture].clone() };
    scene
}

/// Texels with z < 0 (blue below 128) point into the surface. The decoder clamps z to 0
/// (the tangent-space normal never points into the surface), so the shading normal may lie in
/// the surface but never below it, and everything stays finite.
#[test]
fn texels_pointing_into_the_surface_never_bend_the_normal_below_it() {
    let scene = with_normal_map(8, 8, [200, 90, 20]);
    let mut params = close_wall_params(&scene, 0.3);
    assert_finite_everywhere(&scene, &params, "z < 0 texels");
    params.shading.view = ViewMode::ShadingNormal;
    let mut renderer = renderer_for(&scene);
    let image = render_image(&mut renderer, [64, 64], &params).unwrap();
    // The wall's normal is +Z; 2/255 of colour rounding allows a z of about −0.01.
    let lowest = image.pixels().map(|p| decode_debug(p).z).fold(f32::INFINITY, f32::min);
    assert!(lowest > -0.02, "a shading normal points below the wall: z = {lowest}");
}

/// 1×1 colour and normal textures: one mip level, drawn, finite in every view.
#[test]
fn one_texel_textures_work() {
    let mut scene = with_normal_map(1, 1, [128, 128, 255]);
    let colour = scene.materials[0].base_color_texture.unwrap();
    scene.textures[colour] =
        TextureImage { width: 1, height: 1, rgba: vec![180, 90, 60, 255], ..scene.textures[colour].clone() };
    let params = default_params(&scene);
    assert_finite_everywhere(&scene, &params, "1×1 textures");
}

/// A cliff (a step from 0 to 1 across one texel) is the stiff case for finite differences:
/// every kernel gives finite unit normals, steep at the cliff; away from it 8-bit and 16-bit
/// heights give the same normals (flat there), and at the cliff they differ by under 1°.
#[test]
fn a_cliff_in_8_and_16_bit_heights_stays_finite_and_bounded() {
    let (width, height) = (32u32, 8u32);
    let samples = (0..height).flat_map(|_| (0..width).map(|x| if x < width / 2 { 0.0 } else { 1.0 })).collect();
    let field = HeightField { width, height, samples, range_m: 0.01, texel_size_m: 0.001 };
    let (eight, sixteen) = (field.quantized(8), field.quantized(16));
    for &kernel in Kernel::all() {
        for border in [Border::Wrap, Border::Clamp] {
            for y in 0..height as i64 {
                for x in 0..width as i64 {
                    let (a, b) = (eight.normal(kernel, border, x, y), sixteen.normal(kernel, border, x, y));
                    assert!(a.is_finite() && (a.length() - 1.0).abs() < 1e-5, "{kernel:?} {border:?} at {x}: {a}");
                    assert!(a.angle_between(b).to_degrees() < 1.0, "{kernel:?} {border:?} at {x}: {a} vs {b}");
                }
            }
            let steepest = (width as i64 / 2 - 2..width as i64 / 2 + 2)
                .map(|x| sixteen.normal(kernel, border, x, 4).z)
                .fold(f32::INFINITY, f32::min);
            let far = sixteen.normal(kernel, border, width as i64 / 4, 4);
            assert!(steepest < 0.5, "{kernel:?}: the cliff must be steep, z = {steepest}");
            assert!((far - glam::Vec3::Z).length() < 1e-6, "{kernel:?}: flat away from the cliff, {far}");
        }
    }
}

/// A mesh without UVs whose material has a normal map is drawn without bump (no tangents are
/// generated for it) and stays finite.
#[test]
fn normal_mapped_material_on_a_mesh_without_uvs_draws_without_bump() {
    let mut scene = scene();
    scene.meshes.iter_mut().for_each(|m| m.uvs.clear());
    let params = default_params(&scene);
    assert_finite_everywhere(&scene, &params, "no UVs");
    let renderer = renderer_for(&scene);
    assert_eq!(renderer.counters().tangent_frames_generated, 0);
    assert!(renderer.notices().iter().any(|n| n.contains("no texture coordinates")), "{:?}", renderer.notices());
}

/// A texture wider than the adapter allows is downscaled to fit, with a notice, instead of
/// failing the upload; the scene renders and stays finite.
#[test]
fn a_texture_larger_than_the_adapter_allows_is_downscaled() {
    let probe = renderer_for(&scene());
    let limit = probe.max_target_size();
    let scene = with_normal_map(limit + 1, 2, [128, 128, 255]);
    let renderer = renderer_for(&scene);
    let notice = renderer.notices().iter().find(|n| n.contains("downscaled")).cloned();
    assert!(notice.as_ref().is_some_and(|n| n.contains(&format!("{}x2", limit + 1))), "{:?}", renderer.notices());
    assert_finite_everywhere(&scene, &default_params(&scene), "oversized texture");
}
