//! How a loaded scene opens: light markers sized from the scene, small on the built-in scene
//! and on a 0.26 m model; a glTF model seen from its front, +Z.

mod common;

use bumpview::frame::FrameParams;
use bumpview::load::load_scene;
use bumpview::render::Renderer;
use bumpview::render::capture::render_image;
use bumpview::scene::Scene;
use bumpview::state::ViewerState;
use common::*;

/// The pixels where `a` and `b` differ.
fn differing(a: &image::RgbaImage, b: &image::RgbaImage) -> usize {
    a.enumerate_pixels().filter(|(x, y, p)| *p != b.get_pixel(*x, *y)).count()
}

/// The share of the picture's pixels the light markers change, drawn with `params`.
fn marker_share(renderer: &mut Renderer, params: &FrameParams, size: [u32; 2]) -> f64 {
    let with = render_image(renderer, size, &FrameParams { shading: params.shading, ..*params }).unwrap();
    let mut hidden = *params;
    hidden.shading.show_light_marker = false;
    let without = render_image(renderer, size, &hidden).unwrap();
    differing(&with, &without) as f64 / (size[0] * size[1]) as f64
}

fn opened(scene: &Scene) -> FrameParams {
    ViewerState::new(scene).frame_params()
}

/// The marker is a share of the scene's size: on the built-in scene (5.8 m across) as it
/// opens, and on WaterBottle (0.26 m high) seen from 3× its opening distance (which puts its
/// default light in the picture), it covers well under 0.1 % of the picture and is drawn.
/// (A 6 cm marker covered 0.38 % of that WaterBottle picture, and on opening cut a wedge
/// into the picture's corner.)
#[test]
fn light_markers_stay_small_on_large_and_small_scenes() {
    let size = [1280, 720];
    let builtin = scene();
    let bottle = load_scene(&asset(&assets(), "gltf/WaterBottle/glTF/WaterBottle.gltf")).unwrap();
    for (name, scene, pull_back) in [("built-in", builtin, 1.0), ("WaterBottle", bottle, 3.0)] {
        let mut renderer = renderer_for(&scene);
        let mut params = opened(&scene);
        params.camera.distance *= pull_back;
        assert!(params.shading.show_light_marker);
        let share = marker_share(&mut renderer, &params, size);
        println!("{name}: the marker covers {:.4} % of {}x{}", 100.0 * share, size[0], size[1]);
        assert!(share > 0.0 && share < 0.001, "{name}: marker share {share}");
    }
}

/// A glTF model opens seen from its front, +Z (glTF 2.0: "the front of a glTF asset faces
/// +Z"), a little above: OrientationTest's camera sits on the +Z side of its target.
#[test]
fn a_model_opens_from_its_front() {
    let scene = load_scene(&asset(&assets(), "gltf/OrientationTest/glTF/OrientationTest.gltf")).unwrap();
    let camera = opened(&scene).camera;
    let seen_from = (camera.eye() - camera.target).normalize();
    assert!(seen_from.z > 0.95 && seen_from.x.abs() < 1e-5 && seen_from.y > 0.0, "seen from {seen_from}");
}
