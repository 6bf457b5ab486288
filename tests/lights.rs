//! Several lights, attenuation and the specular modes on the software adapter: the GPU
//! against the CPU chain (src/chain.rs) and against the formulas themselves.

mod common;

use bumpview::frame::FrameParams;
use bumpview::math::linear_to_srgb;
use bumpview::render::capture::{FloatImage, render_float, render_image};
use bumpview::scene::builtin::WALL_Z;
use bumpview::scene::{Attenuation, Light, Scene, SpecularMode};
use bumpview::shading::lights::attenuation;
use common::*;
use glam::Vec3;

/// At 0.3 m from the wall a pixel of 256 covers about 0.56 brick texels: textures magnify and
/// read mip 0, as the CPU chain does (tests/common's `close_wall_params`).
const SIZE: [u32; 2] = [256, 256];

/// The flat wall seen from 0.3 m (no bump: the inputs are interpolated positions and the
/// colour texture only) lit by `lights`.
fn wall(scene: &Scene, lights: &[Light]) -> FrameParams {
    let mut params = close_wall_params(scene, 0.3);
    params.shading.bump_enabled = false;
    params.lights = params.lights.with_lights(lights).unwrap();
    params
}

/// A warm point light in front of the wall and a cool directional light from the upper left,
/// dim enough that no channel of the wall passes 1.
fn two_lights() -> [Light; 2] {
    let lamp = Light { intensity: 0.4, ..Light::point(Vec3::new(0.1, 1.6, WALL_Z + 0.3), Vec3::new(1.0, 0.8, 0.6)) };
    let sun = Light { intensity: 0.3, ..Light::directional(Vec3::new(-1.0, 1.0, 2.0), Vec3::new(0.6, 0.8, 1.0)) };
    [lamp, sun]
}

fn rgb(image: &FloatImage, x: u32, y: u32) -> Vec3 {
    let [r, g, b, _] = image.pixels[(y * image.width + x) as usize];
    Vec3::new(r, g, b)
}

/// Largest |a − b| over the channels of every pixel, linear.
fn max_difference(a: &FloatImage, b: &FloatImage, c: &FloatImage, off: &FloatImage) -> f32 {
    let mut worst = 0f32;
    for y in 0..SIZE[1] {
        for x in 0..SIZE[0] {
            let sum = rgb(b, x, y) + rgb(c, x, y) - rgb(off, x, y);
            worst = worst.max((rgb(a, x, y) - sum).abs().max_element());
        }
    }
    worst
}

/// Two lights equal the sum of each alone, less the ambient light counted twice, in linear
/// light (a float target: nothing clamps): on the GPU within float rounding, and in the CPU
/// chain. The check can fail: a shader that drew only the first light would miss the second
/// light's whole contribution.
#[test]
fn two_lights_equal_the_sum_of_each_alone() {
    let scene = scene();
    let mut renderer = renderer_for(&scene);
    let [lamp, sun] = two_lights();
    let dark = Light { enabled: false, ..lamp };
    let mut draw = |lights: &[Light]| render_float(&mut renderer, SIZE, &wall(&scene, lights)).unwrap();
    let (both, lamp_alone, sun_alone, ambient) = (draw(&[lamp, sun]), draw(&[lamp]), draw(&[sun]), draw(&[dark]));
    let gpu = max_difference(&both, &lamp_alone, &sun_alone, &ambient);
    let brightest = both.pixels.iter().map(|p| p[0].max(p[1]).max(p[2])).fold(0.0, f32::max);
    let sun_share = max_difference(&sun_alone, &ambient, &ambient, &ambient);
    println!("GPU: |both − (lamp + sun − ambient)| ≤ {gpu}; brightest {brightest}; the sun adds up to {sun_share}");
    assert!(brightest < 1.0, "a channel passes 1 ({brightest}): pick dimmer lights");
    assert!(gpu < 1e-5, "GPU sum off by {gpu}");
    assert!(sun_share > 0.05, "the second light adds only {sun_share}");

    let mut cpu = 0f32;
    for (x, y) in [(10, 10), (128, 128), (210, 80), (60, 230)] {
        let shade = |lights: &[Light]| wall_chain(&scene, &wall(&scene, lights), SIZE, x, y).color_linear;
        let sum = shade(&[lamp]) + shade(&[sun]) - shade(&[dark]);
        cpu = cpu.max((shade(&[lamp, sun]) - sum).abs().max_element());
        let gpu_pixel = rgb(&both, x, y);
        assert!((gpu_pixel - shade(&[lamp, sun])).abs().max_element() < 2e-3, "GPU {gpu_pixel} at {x},{y}");
    }
    println!("CPU: |both − (lamp + sun − ambient)| ≤ {cpu}");
    assert!(cpu < 1e-6, "CPU sum off by {cpu}");
}

/// Attenuation `1 / (c + l·d + q·d²)` at the distance of each pixel's wall point from the
/// light: the light's share of the pixel (its colour less the ambient-only colour) with
/// attenuation, over the share without, equals the formula at distances 0.20 to 0.31 m.
/// Measured max relative error 4.0e-6 on lavapipe; bound 1e-4 (4× MSAA averages four sample
/// positions per pixel, where the factor is not linear). The check can fail: the formula
/// with l and q swapped is 0.42 off.
#[test]
fn attenuation_matches_the_formula_at_measured_distances() {
    let scene = scene();
    let mut renderer = renderer_for(&scene);
    let coefficients = Attenuation { constant: 0.5, linear: 1.5, quadratic: 4.0 };
    let lamp = Light::point(Vec3::new(0.05, 1.52, WALL_Z + 0.2), Vec3::splat(0.4));
    let faded = Light { attenuation: coefficients, ..lamp };
    let dark = Light { enabled: false, ..lamp };
    let mut draw = |light: Light| render_float(&mut renderer, SIZE, &wall(&scene, &[light])).unwrap();
    let (full, attenuated, ambient) = (draw(lamp), draw(faded), draw(dark));
    let camera = wall(&scene, &[lamp]).camera;
    let swapped = Attenuation { linear: coefficients.quadratic, quadratic: coefficients.linear, ..coefficients };
    let (mut worst, mut worst_swapped, mut distances) = (0f32, 0f32, vec![]);
    for y in (4..SIZE[1]).step_by(16) {
        for x in (4..SIZE[0]).step_by(16) {
            let p = hit_plane(&camera, SIZE, x, y, Vec3::Z, WALL_Z).unwrap();
            let d = (lamp.position - p).length();
            let share = |image: &FloatImage| rgb(image, x, y).x - rgb(&ambient, x, y).x;
            let measured = share(&attenuated) / share(&full);
            worst = worst.max((measured / attenuation(coefficients, d) - 1.0).abs());
            worst_swapped = worst_swapped.max((measured / attenuation(swapped, d) - 1.0).abs());
            distances.push(d);
        }
    }
    distances.sort_by(f32::total_cmp);
    println!(
        "distances {:.3}..{:.3} m: relative error max {worst:.2e}; against the swapped formula {worst_swapped:.2e}",
        distances[0],
        distances[distances.len() - 1]
    );
    assert!(worst < 1e-4, "relative error {worst}");
    assert!(worst_swapped > 1e-2, "the swapped formula is only {worst_swapped} off");
}

/// Per-channel |GPU − CPU| in 8-bit steps over a grid of the flat wall under `params`, sorted.
fn steps_against_cpu(scene: &Scene, params: &FrameParams, cpu_params: &FrameParams) -> Vec<f32> {
    let mut renderer = renderer_for(scene);
    let image = render_image(&mut renderer, SIZE, params).unwrap();
    let mut diffs = vec![];
    for y in (2..SIZE[1]).step_by(5) {
        for x in (2..SIZE[0]).step_by(5) {
            let cpu = wall_chain(scene, cpu_params, SIZE, x, y).color_linear.map(|c| linear_to_srgb(c) * 255.0);
            let gpu = image.get_pixel(x, y);
            diffs.push((0..3).map(|c| (gpu[c] as f32 - cpu[c]).abs()).fold(0.0, f32::max));
        }
    }
    diffs.sort_by(f32::total_cmp);
    diffs
}

/// Blinn, Phong and no highlight, with a point and a directional light and a shininess of
/// 48 for every material: the GPU matches the CPU chain within the flat wall's tolerance of
/// tests/shading_reference.rs (1 step: output rounding plus float differences). The
/// comparison can fail: Phong's picture against Blinn's reference is far off in the highlight.
#[test]
fn phong_and_blinn_highlights_match_the_cpu_reference() {
    let scene = scene();
    let [lamp, sun] = two_lights();
    let lamp = Light { intensity: 1.0, ..lamp };
    let mut params = wall(&scene, &[lamp, sun]);
    params.shading.shininess = Some(48.0);
    for &mode in [SpecularMode::Blinn, SpecularMode::Phong, SpecularMode::Off].iter() {
        params.shading.specular = mode;
        let diffs = steps_against_cpu(&scene, &params, &params);
        let max = *diffs.last().unwrap();
        println!("{mode:?}: median {} p99 {} max {max} steps", percentile(&diffs, 0.5), percentile(&diffs, 0.99));
        assert!(max <= 1.0, "{mode:?}: max {max} steps");
    }
    let mut blinn_reference = params;
    blinn_reference.shading.specular = SpecularMode::Blinn;
    params.shading.specular = SpecularMode::Phong;
    let diffs = steps_against_cpu(&scene, &params, &blinn_reference);
    let max = *diffs.last().unwrap();
    println!("Phong picture against the Blinn reference: max {max} steps");
    assert!(max > 10.0, "Phong and Blinn differ by only {max} steps");
}

/// Each light that is on gets a marker in its colour where it is (a directional light's half
/// the camera distance from the target, towards it); a light that is off gets none.
#[test]
fn markers_take_their_lights_colours() {
    let scene = scene();
    let mut renderer = renderer_for(&scene);
    let red = Light::point(Vec3::new(-0.9, 1.4, 1.0), Vec3::new(1.0, 0.0, 0.0));
    let green = Light::directional(Vec3::new(0.6, 0.5, 1.0), Vec3::new(0.0, 1.0, 0.0));
    let off = Light { enabled: false, ..Light::point(Vec3::new(0.8, 1.6, 1.0), Vec3::new(0.0, 0.0, 1.0)) };
    let mut params = default_params(&scene);
    params.shading.show_light_marker = true;
    params.lights = params.lights.with_lights(&[red, green, off]).unwrap();
    let size = [160, 120];
    let image = render_image(&mut renderer, size, &params).unwrap();
    let view_projection = params.camera.view_projection(size[0] as f32 / size[1] as f32);
    for (index, expected) in [(0, [255, 0, 0]), (1, [0, 255, 0])] {
        let clip = view_projection * params.marker_position(index).extend(1.0);
        let ndc = clip.truncate() / clip.w;
        let x = ((ndc.x * 0.5 + 0.5) * size[0] as f32) as u32;
        let y = ((0.5 - ndc.y * 0.5) * size[1] as f32) as u32;
        let pixel = image.get_pixel(x, y);
        assert_eq!([pixel[0], pixel[1], pixel[2]], expected, "marker of light {index} at {x},{y}");
    }
    let clip = view_projection * off.position.extend(1.0);
    let ndc = clip.truncate() / clip.w;
    let (x, y) = (((ndc.x * 0.5 + 0.5) * size[0] as f32) as u32, ((0.5 - ndc.y * 0.5) * size[1] as f32) as u32);
    let pixel = image.get_pixel(x, y);
    assert_ne!([pixel[0], pixel[1], pixel[2]], [0, 0, 255], "a light that is off has no marker");
}

/// Extreme lights stay finite in every lighting space: a point light exactly on the wall with
/// pure quadratic attenuation (the denominator floored), a directional light with a tiny
/// direction, a huge intensity far away, and eight lights at once.
#[test]
fn extreme_lights_stay_finite() {
    let scene = scene();
    let mut renderer = renderer_for(&scene);
    let on_wall = Light {
        attenuation: Attenuation { constant: 0.0, linear: 0.0, quadratic: 1.0 },
        ..Light::point(Vec3::new(0.0, 1.5, WALL_Z), Vec3::ONE)
    };
    let tiny = Light::directional(Vec3::new(0.0, 1e-20, 1e-20), Vec3::ONE);
    let far = Light { intensity: 1e30, ..Light::point(Vec3::splat(1e20), Vec3::ONE) };
    let lights = [on_wall, tiny, far, on_wall, tiny, far, on_wall, tiny];
    for space in [bumpview::frame::LightingSpace::World, bumpview::frame::LightingSpace::Tangent] {
        let mut params = close_wall_params(&scene, 0.3);
        params.lights = params.lights.with_lights(&lights).unwrap();
        params.shading.lighting_space = space;
        params.shading.specular = SpecularMode::Phong;
        let image = render_float(&mut renderer, [64, 64], &params).unwrap();
        let bad = image.pixels.iter().filter(|p| p.iter().any(|c| !c.is_finite())).count();
        assert_eq!(bad, 0, "{space:?}: {bad} non-finite pixels");
        let cpu = wall_chain(&scene, &params, [64, 64], 32, 32);
        assert!(cpu.color_linear.is_finite(), "{space:?}: CPU {}", cpu.color_linear);
    }
}
