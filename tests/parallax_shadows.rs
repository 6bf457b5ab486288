//! The searches' soft self-shadows (chain::parallax::soft_shadow, shaders/parallax.wgsl's
//! parallax_soft_shadow) on the built-in brick wall (relief 1 cm deep) under a grazing light:
//! the probe's CPU twin against the rendered pixels, strength 0 as no shadows at all, and
//! shadows that only darken. Differences are 8-bit steps of the stored (sRGB) picture, on
//! lavapipe.

mod common;

use bumpview::frame::{FrameParams, Parallax, ParallaxSettings, SceneOptions};
use bumpview::probe::ProbeScene;
use bumpview::render::capture::render_image;
use common::*;
use glam::Vec3;

const SIZE: [u32; 2] = [256, 256];

/// The close wall from 60° off its normal, lit from far to its left, low over it.
fn grazing(technique: Parallax, shadow_strength: f32) -> FrameParams {
    let scene = scene();
    let mut params = close_wall_params(&scene, 0.4);
    params.camera.yaw = 60f32.to_radians();
    params.lights[0].position = params.camera.target + Vec3::new(-3.0, 0.4, 0.5);
    params.shading.parallax =
        ParallaxSettings { technique, layers_min: 16, layers_max: 16, steps: 5, shadow_strength, ..Default::default() };
    params
}

/// The probe dims the light as the shader does: at 529 points over the picture 90 % within
/// 3 steps, 99 % within 20 and all within 48 (measured: steep 1.4 / 9.5 / 40.8, occlusion
/// 1.2 / 5.4 / 35.6, relief 1.3 / 5.3 / 36.6; the search's hit moves by a fraction of a texel
/// with the GPU's 8-bit filtering weights, as in tests/parallax.rs, and a shadow's edge with
/// it), and about a tenth of the points lie in shadow (40-47 below half the light).
#[test]
fn the_probe_shadows_as_the_shader_does() {
    let scene = scene();
    let options = SceneOptions { parallax: true, ..Default::default() };
    let mut renderer = renderer_for(&scene);
    renderer.set_scene(&scene, options.clone());
    let probe = ProbeScene::new(&scene, &options);
    for technique in [Parallax::Steep, Parallax::Occlusion, Parallax::Relief] {
        let params = grazing(technique, 1.0);
        let image = render_image(&mut renderer, SIZE, &params).unwrap();
        let (mut diffs, mut shadowed) = (vec![], 0);
        for y in (3..SIZE[1]).step_by(11) {
            for x in (5..SIZE[0]).step_by(11) {
                let readout = probe.probe(&params, SIZE, [x, y]).expect("the wall fills the view");
                let march = readout.march.expect("the wall marches");
                assert!((0.0..=1.0).contains(&march.light_visibility[0]), "{march:?}");
                shadowed += usize::from(march.light_visibility[0] < 0.5);
                let cpu = readout.shown_bytes().unwrap();
                let gpu = image.get_pixel(x, y);
                diffs.push((0..3).map(|c| (gpu[c] as f32 - cpu[c]).abs()).fold(0.0, f32::max));
            }
        }
        diffs.sort_by(f32::total_cmp);
        let (p90, p99, max) = (percentile(&diffs, 0.9), percentile(&diffs, 0.99), diffs[diffs.len() - 1]);
        println!(
            "shadows {technique:?}: {shadowed} of {} points below half the light; 90% within {p90}, 99% within {p99}, max {max}",
            diffs.len()
        );
        assert!(shadowed > diffs.len() / 20, "{technique:?}: {shadowed} shadowed points");
        assert!(
            p90 <= 3.0 && p99 <= 20.0 && max <= 48.0,
            "{technique:?}: 90th percentile {p90}, 99th {p99}, max {max}"
        );
    }
}

/// Strength 0 draws exactly the picture without shadows; shadows only darken.
#[test]
fn zero_strength_is_no_shadow_and_shadows_only_darken() {
    let scene = scene();
    let mut renderer = renderer_for(&scene);
    renderer.set_scene(&scene, SceneOptions { parallax: true, ..Default::default() });
    let plain = render_image(&mut renderer, SIZE, &grazing(Parallax::Occlusion, 0.0)).unwrap();
    let mut params = grazing(Parallax::Occlusion, 0.0);
    params.shading.parallax.shadow_strength = -0.0;
    assert_eq!(plain, render_image(&mut renderer, SIZE, &params).unwrap());
    let shadowed = render_image(&mut renderer, SIZE, &grazing(Parallax::Occlusion, 2.0)).unwrap();
    let darker = plain.pixels().zip(shadowed.pixels()).filter(|(a, b)| (0..3).any(|c| b[c] + 2 < a[c])).count();
    let brighter = plain.pixels().zip(shadowed.pixels()).filter(|(a, b)| (0..3).any(|c| b[c] > a[c] + 1)).count();
    println!("strength 2: {darker} pixels darker, {brighter} brighter");
    assert!(darker > 1000 && brighter == 0, "{darker} darker, {brighter} brighter");
}
