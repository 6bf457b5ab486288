//! Stiff and extreme normal and height maps: texels pointing into the surface, 1×1 textures,
//! a cliff in 8- and 16-bit heights, and a normal-mapped material on a mesh without UVs. Each
//! renders to a float target on the software adapter and must have no NaN or infinity.

mod common;

use bumpview::frame::{BumpSource, FrameParams, SceneOptions, ViewMode};
use bumpview::height::{Border, HeightField, Kernel};
use bumpview::names::Named;
use bumpview::render::capture::{FloatImage, render_float, render_image};
use bumpview::scene::{Scene, TextureImage};
use common::*;
use glam::Vec3;

fn assert_finite_everywhere(scene: &Scene, params: &FrameParams, case: &str) {
    assert_finite_everywhere_with(scene, SceneOptions::default(), params, case);
}

fn assert_finite_everywhere_with(scene: &Scene, options: SceneOptions, params: &FrameParams, case: &str) {
    let mut renderer = renderer_for(scene);
    renderer.set_scene(scene, options);
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
    scene.textures[texture] = TextureImage { width, height, rgba, ..(*scene.textures[texture]).clone() }.into();
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
        TextureImage { width: 1, height: 1, rgba: vec![180, 90, 60, 255], ..(*scene.textures[colour]).clone() }.into();
    let params = default_params(&scene);
    assert_finite_everywhere(&scene, &params, "1×1 textures");
}

/// A cliff: heights 0.25 left of the middle and 0.75 right of it (32 × 8 texels, 1 mm texels,
/// 1 cm range). Neither height is a level of 8 bits, and rounding moves them towards each
/// other (63.75 → 64, 191.25 → 191), so the 8-bit step is 127/255 = 0.498 against the 16-bit
/// 0.49999. (0.3 → 0.7 would not do: both round up by half a level and the step stays 0.4.)
fn cliff() -> HeightField {
    let (width, height) = (32u32, 8u32);
    let samples = (0..height).flat_map(|_| (0..width).map(move |x| if x < width / 2 { 0.25 } else { 0.75 })).collect();
    HeightField { width, height, samples, range_m: 0.01, texel_size_m: 0.001 }
}

/// The largest angle 8-bit heights can turn a normal at the cliff against 16-bit ones, degrees:
/// the step's 1/255 of the range, 0.8 % of the step, turns a slope s by at most
/// 0.008·s/(1 + s²) rad, largest at s = 1: 0.004 rad = 0.229°.
const RAW_BOUND_DEG: f32 = 0.23;

/// The angle between two vectors in degrees, from atan2 (acos loses small angles in f32).
fn degrees_between(a: Vec3, b: Vec3) -> f32 {
    a.cross(b).length().atan2(a.dot(b)).to_degrees()
}

/// The angle (degrees) between two debug colours of a float target.
fn debug_angle(a: &[f32; 4], b: &[f32; 4]) -> f32 {
    let decode = |p: &[f32; 4]| Vec3::new(p[0], p[1], p[2]) * 2.0 - 1.0;
    degrees_between(decode(a), decode(b))
}

/// A cliff is the stiff case for finite differences: every kernel gives finite unit normals,
/// steep at the cliff; away from it (where every tap reads one height) 8- and 16-bit heights
/// give the same flat normal, and at the cliff they differ, by more than 0.01° and under
/// [`RAW_BOUND_DEG`] = 0.23°.
/// Why: 8-bit rounding moves each sample by at most 0.5/255, the step of 0.5 by at most 1/255
/// (0.8%), so a slope s changes by 0.8% and its angle by at most 0.008·s/(1 + s²) rad, 0.23°
/// at s = 1; 16 bits move it 256 times less. Measured: 0.043° to 0.101°, depending on the kernel.
///
/// Rendered with the height map in the shader (8- and 16-bit heights uploaded, Blinn's bump
/// from screen-space derivatives) to a float target: no NaN or infinity in any view, the cliff
/// tilts the shading normal (576 pixels by over 2°), and the two depths' pictures differ, by
/// under the same 0.23° (measured at most 0.035°: the shader's bilinear filter spreads the
/// step over a texel, which lowers the slope).
#[test]
fn a_cliff_in_8_and_16_bit_heights_stays_finite_and_bounded() {
    let field = cliff();
    let (width, height) = (field.width as i64, field.height as i64);
    let (eight, sixteen) = (field.quantized(8), field.quantized(16));
    let mut cliff_differences = vec![];
    for &kernel in Kernel::all() {
        for border in [Border::Wrap, Border::Clamp] {
            let mut at_cliff = 0.0f32;
            for y in 0..height {
                for x in 0..width {
                    let (a, b) = (eight.normal(kernel, border, x, y), sixteen.normal(kernel, border, x, y));
                    for n in [a, b] {
                        assert!(n.is_finite() && (n.length() - 1.0).abs() < 1e-5, "{kernel:?} {border:?} at {x}: {n}");
                    }
                    let difference = degrees_between(a, b);
                    // Taps reach at most 2 texels; the wrap puts a second cliff at the field's edge.
                    let near_cliff =
                        (x - width / 2).abs() <= 2 || (border == Border::Wrap && (x <= 1 || x >= width - 3));
                    if near_cliff {
                        at_cliff = at_cliff.max(difference);
                    } else {
                        // Flat: the taps cancel up to float rounding of the non-dyadic 8-bit levels.
                        for n in [a, b] {
                            assert!((n - Vec3::Z).length() < 1e-6, "{kernel:?} {border:?} at {x}: {n}, flat");
                        }
                    }
                }
            }
            assert!(
                at_cliff > 0.01 && at_cliff < RAW_BOUND_DEG,
                "{kernel:?} {border:?}: 8 vs 16 bits differ by {at_cliff}° at the cliff"
            );
            cliff_differences.push(at_cliff);
            let steepest = (width / 2 - 2..width / 2 + 2)
                .map(|x| sixteen.normal(kernel, border, x, 4).z)
                .fold(f32::INFINITY, f32::min);
            assert!(steepest < 0.6, "{kernel:?}: the cliff must be steep, z = {steepest}");
        }
    }
    let (low, high) = cliff_differences.iter().fold((f32::INFINITY, 0.0f32), |(l, h), &d| (l.min(d), h.max(d)));
    println!("8 vs 16 bits at the cliff: {low:.3}° to {high:.3}° over kernels and borders");

    // On the GPU: the close wall, whose centre (x = 0, u = 2) is the tile's wrap, a cliff.
    let options = SceneOptions { bump_source: BumpSource::HeightInShader, ..Default::default() };
    let scene_with = |field: &HeightField| {
        let mut scene = scene();
        let texture = scene.materials[0].height_map.as_ref().expect("the bricks have a height map").texture;
        scene.textures[texture] = field.to_height_texture("cliff").into();
        scene
    };
    let mut params = close_wall_params(&scene(), 0.3);
    let mut shading_normals: Vec<FloatImage> = vec![];
    for (bits, field) in [(8, &eight), (16, &sixteen)] {
        let scene = scene_with(field);
        assert_finite_everywhere_with(&scene, options.clone(), &params, &format!("{bits}-bit cliff"));
        let mut renderer = renderer_for(&scene);
        renderer.set_scene(&scene, options.clone());
        params.shading.view = ViewMode::Normal;
        let geometric = render_float(&mut renderer, [96, 72], &params).unwrap();
        params.shading.view = ViewMode::ShadingNormal;
        let shading = render_float(&mut renderer, [96, 72], &params).unwrap();
        let tilted = geometric.pixels.iter().zip(&shading.pixels).filter(|(g, s)| debug_angle(g, s) > 2.0).count();
        println!("{bits}-bit cliff: {tilted} pixels tilted by over 2°");
        assert!(tilted > 50, "{bits}-bit: the cliff must tilt the shading normal ({tilted} pixels)");
        shading_normals.push(shading);
    }
    let rendered = shading_normals[0]
        .pixels
        .iter()
        .zip(&shading_normals[1].pixels)
        .map(|(a, b)| debug_angle(a, b))
        .fold(0.0f32, f32::max);
    println!("rendered 8 vs 16 bits: max {rendered:.3}°");
    assert!(rendered > 0.0 && rendered < RAW_BOUND_DEG, "rendered 8- and 16-bit cliffs differ by {rendered}°");
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
