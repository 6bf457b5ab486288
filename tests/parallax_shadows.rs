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

/// Median and 90th percentile of |GPU − probe| over the shadowed points alone, 8-bit steps
/// (measured: steep 0.43 / 0.62, occlusion 0.50 / 0.69, relief 0.50 / 0.74 at 40-47 points).
const SHADOWED_BOUNDS: [f32; 2] = [1.0, 2.0];

/// The same at strength 0, over the points strength 1 shadows (measured: median 0.54, 90th
/// percentile 1.13, at 47 points; a shadow there darkens them by tens of steps).
const ZERO_STRENGTH_BOUNDS: [f32; 2] = [1.0, 3.0];

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

/// Per point of an 11-pixel grid over the picture: |GPU − probe| (largest channel, 8-bit
/// steps) and the probe's light visibility (0 shadowed … 1 lit).
fn gpu_against_probe(technique: Parallax, shadow_strength: f32) -> Vec<(f32, f32)> {
    let scene = scene();
    let options = SceneOptions { parallax: true, ..Default::default() };
    let mut renderer = renderer_for(&scene);
    renderer.set_scene(&scene, options.clone());
    let probe = ProbeScene::new(&scene, &options);
    let params = grazing(technique, shadow_strength);
    let image = render_image(&mut renderer, SIZE, &params).unwrap();
    let mut points = vec![];
    for y in (3..SIZE[1]).step_by(11) {
        for x in (5..SIZE[0]).step_by(11) {
            let readout = probe.probe(&params, SIZE, [x, y]).expect("the wall fills the view");
            let march = readout.march.expect("the wall marches");
            assert!((0.0..=1.0).contains(&march.light_visibility[0]), "{march:?}");
            let cpu = readout.shown_bytes().unwrap();
            let gpu = image.get_pixel(x, y);
            points
                .push(((0..3).map(|c| (gpu[c] as f32 - cpu[c]).abs()).fold(0.0, f32::max), march.light_visibility[0]));
        }
    }
    points
}

/// Sorted differences of `points` whose visibility passes `keep`.
fn sorted_diffs(points: &[(f32, f32)], keep: impl Fn(f32) -> bool) -> Vec<f32> {
    let mut diffs: Vec<f32> = points.iter().filter(|p| keep(p.1)).map(|p| p.0).collect();
    diffs.sort_by(f32::total_cmp);
    diffs
}

/// The probe dims the light as the shader does: at 529 points over the picture 90 % within
/// 3 steps, 99 % within 20 and all within 48 (measured: steep 1.4 / 9.5 / 40.8, occlusion
/// 1.2 / 5.4 / 35.6, relief 1.3 / 5.3 / 36.6; the search's hit moves by a fraction of a texel
/// with the GPU's 8-bit filtering weights, as in tests/parallax.rs, and a shadow's edge with
/// it), and about a tenth of the points lie in shadow (40-47 below half the light). The
/// shadowed points are checked on their own too, since they are fewer than the tenth the
/// 90th percentile leaves out: SHADOWED_BOUNDS below.
#[test]
fn the_probe_shadows_as_the_shader_does() {
    for technique in [Parallax::Steep, Parallax::Occlusion, Parallax::Relief] {
        let points = gpu_against_probe(technique, 1.0);
        let diffs = sorted_diffs(&points, |_| true);
        let shadowed = sorted_diffs(&points, |v| v < 0.5);
        let (p90, p99, max) = (percentile(&diffs, 0.9), percentile(&diffs, 0.99), diffs[diffs.len() - 1]);
        let (s50, s90) = (percentile(&shadowed, 0.5), percentile(&shadowed, 0.9));
        println!(
            "shadows {technique:?}: {} of {} points below half the light (median {s50}, 90% within {s90}); \
             90% within {p90}, 99% within {p99}, max {max}",
            shadowed.len(),
            diffs.len()
        );
        assert!(shadowed.len() > diffs.len() / 20, "{technique:?}: {} shadowed points", shadowed.len());
        assert!(
            p90 <= 3.0 && p99 <= 20.0 && max <= 48.0,
            "{technique:?}: 90th percentile {p90}, 99th {p99}, max {max}"
        );
        assert!(
            s50 <= SHADOWED_BOUNDS[0] && s90 <= SHADOWED_BOUNDS[1],
            "{technique:?}: shadowed points: median {s50}, 90th percentile {s90}"
        );
    }
}

/// Strength 0 draws the picture without shadows, checked against the CPU chain (which skips
/// the shadow at strength 0) at the points strength 1 shadows: a shader that still shadowed
/// at 0 would be darker there by the shadow itself. Shadows only darken.
#[test]
fn zero_strength_is_no_shadow_and_shadows_only_darken() {
    let shadowed_at_one: Vec<bool> = gpu_against_probe(Parallax::Occlusion, 1.0).iter().map(|p| p.1 < 0.5).collect();
    let at_zero = gpu_against_probe(Parallax::Occlusion, 0.0);
    assert!(at_zero.iter().all(|p| p.1 == 1.0), "the CPU chain shadows at strength 0");
    let mut diffs: Vec<f32> = at_zero.iter().zip(&shadowed_at_one).filter(|(_, s)| **s).map(|(p, _)| p.0).collect();
    diffs.sort_by(f32::total_cmp);
    println!(
        "strength 0 at the {} points strength 1 shadows: GPU against CPU median {}, 90% within {}, max {}",
        diffs.len(),
        percentile(&diffs, 0.5),
        percentile(&diffs, 0.9),
        diffs[diffs.len() - 1]
    );
    assert!(diffs.len() > 20, "{} shadowed points", diffs.len());
    let (p50, p90) = (percentile(&diffs, 0.5), percentile(&diffs, 0.9));
    assert!(p50 <= ZERO_STRENGTH_BOUNDS[0] && p90 <= ZERO_STRENGTH_BOUNDS[1], "{diffs:?}");
    let scene = scene();
    let mut renderer = renderer_for(&scene);
    renderer.set_scene(&scene, SceneOptions { parallax: true, ..Default::default() });
    let plain = render_image(&mut renderer, SIZE, &grazing(Parallax::Occlusion, 0.0)).unwrap();
    let shadowed = render_image(&mut renderer, SIZE, &grazing(Parallax::Occlusion, 2.0)).unwrap();
    let darker = plain.pixels().zip(shadowed.pixels()).filter(|(a, b)| (0..3).any(|c| b[c] + 2 < a[c])).count();
    let brighter = plain.pixels().zip(shadowed.pixels()).filter(|(a, b)| (0..3).any(|c| b[c] > a[c] + 1)).count();
    println!("strength 2: {darker} pixels darker, {brighter} brighter");
    assert!(darker > 1000 && brighter == 0, "{darker} darker, {brighter} brighter");
}
