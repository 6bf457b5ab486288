//! Extreme inputs: no NaN or infinity reaches a pixel, and bad requests are clear errors.

mod common;

use bumpview::RenderError;
use bumpview::frame::FrameParams;
use bumpview::frame::{ShadingMode, ViewMode};
use bumpview::names::Named;
use bumpview::render::capture::{render_float, render_image};
use bumpview::scene::builtin::WALL_Z;
use common::*;
use glam::Vec3;

/// Renders every view of `params` to a float target and asserts all pixels are finite; the
/// Lit and Over-tilt views in every shading mode, the last view with the wireframe overlay.
fn assert_finite_in_every_view(renderer: &mut bumpview::render::Renderer, params: FrameParams, case: &str) {
    for &view in ViewMode::all() {
        let modes: &[ShadingMode] = if matches!(view, ViewMode::Lit | ViewMode::OverTilt) {
            ShadingMode::all()
        } else {
            &[ShadingMode::BumpTimesColour]
        };
        for &mode in modes {
            let mut params = params;
            params.shading.view = view;
            params.shading.mode = mode;
            params.shading.show_light_marker = true;
            params.shading.wireframe = view == ViewMode::OverTilt;
            let image = render_float(renderer, [160, 120], &params).unwrap();
            let bad = image.pixels.iter().filter(|p| p.iter().any(|c| !c.is_finite())).count();
            assert_eq!(bad, 0, "{case}, {view:?}, {mode:?}: {bad} non-finite pixels");
        }
    }
}

#[test]
fn extreme_strengths_stay_finite() {
    let scene = scene();
    let mut renderer = renderer_for(&scene);
    for strength in [-1000.0, 1000.0] {
        for params in [default_params(&scene), close_wall_params(&scene, 0.3)] {
            let mut params = params;
            params.shading.strength = strength;
            assert_finite_in_every_view(&mut renderer, params, &format!("strength {strength}"));
        }
    }
}

/// The light exactly on the wall (a visible surface point) and exactly on the floor.
#[test]
fn light_on_the_surface_stays_finite() {
    let scene = scene();
    let mut renderer = renderer_for(&scene);
    for light in [Vec3::new(0.0, 1.5, WALL_Z), Vec3::new(0.5, 0.0, 0.5)] {
        for params in [default_params(&scene), close_wall_params(&scene, 0.3)] {
            let mut params = params;
            params.lights[0].position = light;
            assert_finite_in_every_view(&mut renderer, params, &format!("light at {light}"));
        }
    }
}

#[test]
fn empty_and_oversized_viewports_are_clear_errors() {
    let scene = scene();
    let mut renderer = renderer_for(&scene);
    let params = default_params(&scene);
    for size in [[0, 0], [0, 100], [100, 0]] {
        let error = render_image(&mut renderer, size, &params).unwrap_err();
        assert!(matches!(error, RenderError::EmptyViewport { .. }), "{error}");
        assert!(error.to_string().contains("empty"), "{error}");
    }
    let limit = renderer.max_target_size();
    let error = render_image(&mut renderer, [limit + 1, 16], &params).unwrap_err();
    assert!(matches!(error, RenderError::ViewportTooLarge { .. }), "{error}");
    // The renderer still works afterwards.
    render_image(&mut renderer, [32, 32], &params).unwrap();
}

/// Light behind the wall: the wall's pixels get ambient only. A render with the light switched
/// off (colour zero) is ambient only by construction; the two must be the same picture.
#[test]
fn light_behind_the_wall_leaves_ambient_only() {
    let scene = scene();
    let mut renderer = renderer_for(&scene);
    let mut behind = close_wall_params(&scene, 0.3);
    behind.lights[0].position = Vec3::new(0.1, 1.6, WALL_Z - 0.5);
    let mut dark = behind;
    dark.lights[0].color = Vec3::ZERO;
    let mut front = behind;
    front.lights[0].position.z = WALL_Z + 0.5;
    let [behind, dark, front] = [behind, dark, front].map(|p| render_image(&mut renderer, [128, 128], &p).unwrap());
    let max_difference = |a: &image::RgbaImage, b: &image::RgbaImage| {
        a.pixels().zip(b.pixels()).map(|(p, q)| (0..3).map(|c| p[c].abs_diff(q[c])).max().unwrap()).max().unwrap()
    };
    assert_eq!(max_difference(&behind, &dark), 0, "light behind the wall must add nothing");
    assert!(max_difference(&front, &dark) > 50, "the same light in front must light the wall");
}

/// The scan can fail: a NaN light colour (which the viewer never produces) reaches the
/// float target as NaN, so a shader that made NaN would be seen.
#[test]
fn float_target_shows_nan_when_the_shader_makes_it() {
    let scene = scene();
    let mut renderer = renderer_for(&scene);
    let mut params = default_params(&scene);
    params.lights[0].color = Vec3::NAN;
    let image = render_float(&mut renderer, [64, 48], &params).unwrap();
    assert!(image.pixels.iter().any(|p| p.iter().any(|c| c.is_nan())));
}
