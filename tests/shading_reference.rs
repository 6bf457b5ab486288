//! Rendered pixels on the wall against the CPU reference of the same Blinn-Phong shading
//! (the CPU chain, src/chain.rs), texel for texel.

mod common;

use bumpview::math::linear_to_srgb;
use bumpview::render::capture::render_image;
use bumpview::scene::Scene;
use common::*;
use glam::Vec3;

/// The CPU picture of the wall (8-bit sRGB) at one pixel.
fn reference_pixel(scene: &Scene, params: &bumpview::frame::FrameParams, size: [u32; 2], x: u32, y: u32) -> Vec3 {
    wall_chain(scene, params, size, x, y).color_linear.map(|c| linear_to_srgb(c) * 255.0)
}

/// Per-channel differences |GPU − CPU| in 8-bit steps over a grid of pixels, sorted. The
/// CPU reference uses bump strength `cpu_strength_factor` times the GPU's.
fn differences(bump: bool, cpu_strength_factor: f32) -> Vec<f32> {
    let scene = scene();
    differences_of(&scene, &scene, bump, cpu_strength_factor)
}

/// [`differences`] of `scene` drawn on the GPU against `cpu_scene` shaded on the CPU.
fn differences_of(scene: &Scene, cpu_scene: &Scene, bump: bool, cpu_strength_factor: f32) -> Vec<f32> {
    let mut renderer = renderer_for(scene);
    let size = [256, 256];
    let mut params = close_wall_params(scene, 0.3);
    params.shading.bump_enabled = bump;
    let image = render_image(&mut renderer, size, &params).unwrap();
    let mut diffs = vec![];
    for y in (2..size[1]).step_by(5) {
        for x in (2..size[0]).step_by(5) {
            let gpu = image.get_pixel(x, y);
            let mut cpu_params = params;
            cpu_params.shading.strength *= cpu_strength_factor;
            let cpu = reference_pixel(cpu_scene, &cpu_params, size, x, y);
            let diff = (0..3).map(|c| (gpu[c] as f32 - cpu[c]).abs()).fold(0.0, f32::max);
            diffs.push(diff);
        }
    }
    diffs.sort_by(f32::total_cmp);
    diffs
}

/// Without bump the only inputs are interpolated positions and the colour texture:
/// tolerance 1 step = output rounding (0.5, the CPU value is not rounded) + filtering and
/// float differences (measured max 0.85 on lavapipe, rounding included).
#[test]
fn flat_wall_matches_cpu_blinn_phong() {
    let diffs = differences(false, 1.0);
    let max = diffs.last().copied().unwrap();
    println!(
        "flat: median {} p99 {} max {max} over {} pixels",
        percentile(&diffs, 0.5),
        percentile(&diffs, 0.99),
        diffs.len()
    );
    assert!(max <= 1.0, "max difference {max} steps");
}

/// With bump the normal map is filtered too. Where a texel step crosses a mortar edge the
/// normal turns by tens of degrees within one texel, and the specular lobe (shininess 32)
/// magnifies the rasteriser's filter-weight precision there (measured max 1.6 steps on
/// lavapipe); hence 1 step for 99% of pixels and 3 steps for the few edge pixels.
#[test]
fn bumped_wall_matches_cpu_blinn_phong() {
    let diffs = differences(true, 1.0);
    let (p99, max) = (percentile(&diffs, 0.99), *diffs.last().unwrap());
    println!("bumped: median {} p99 {p99} max {max} over {} pixels", percentile(&diffs, 0.5), diffs.len());
    assert!(p99 <= 1.5, "99th percentile {p99} steps");
    assert!(max <= 3.0, "max difference {max} steps");
}

/// The comparison can fail: a reference with the relief inverted is far off along the mortar.
#[test]
fn inverted_relief_is_detected() {
    let diffs = differences(true, -1.0);
    let p99 = percentile(&diffs, 0.99);
    println!("inverted reference: p99 {p99}");
    assert!(p99 > 10.0, "99th percentile {p99} steps");
}

/// The wall with a gloss (specular) map: vertical stripes of k_s × 1, × 0.25, × 0 and × 1,
/// 4 texels wide (linear 8-bit data) over the bricks' UVs.
fn glossy_wall() -> Scene {
    let mut scene = scene();
    let (width, height) = (64u32, 64u32);
    let levels = [255u8, 64, 0, 255];
    let rgba =
        (0..width * height).flat_map(|i| [levels[(i % width / 4 % 4) as usize]; 3].into_iter().chain([255])).collect();
    scene.textures.push(
        bumpview::scene::TextureImage::new("gloss stripes", width, height, bumpview::scene::TextureKind::Data, rgba)
            .into(),
    );
    scene.materials[0].gloss_texture = Some(scene.textures.len() - 1);
    scene
}

/// The gloss map scales k_s texel for texel as the CPU reference does (flat-wall tolerance),
/// and the comparison can fail: a reference that ignores the map is off in the highlight.
#[test]
fn gloss_map_scales_the_specular_term_as_the_cpu_reference_does() {
    let glossy = glossy_wall();
    let diffs = differences_of(&glossy, &glossy, false, 1.0);
    let max = diffs.last().copied().unwrap();
    println!("gloss: median {} p99 {} max {max}", percentile(&diffs, 0.5), percentile(&diffs, 0.99));
    assert!(max <= 1.0, "max difference {max} steps");
    let ignored = differences_of(&glossy, &scene(), false, 1.0);
    let worst = ignored.last().copied().unwrap();
    println!("gloss map ignored by the reference: max {worst} steps");
    assert!(worst > 10.0, "a reference without the gloss map is only {worst} steps off");
}
