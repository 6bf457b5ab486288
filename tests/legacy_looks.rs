//! The legacy looks (`--legacy`): DOT3 with the light vector normalised per vertex or through
//! a normalization cube map, and the emboss look's 2D light map. Each draws on the GPU as the
//! CPU chain does (the probe), and each changes the picture the documented way.

mod common;

use bumpview::frame::{CUBE_MAP_SIZES, FrameParams, LegacyLook, LegacySettings, SceneOptions, ShadingMode};
use bumpview::scene::builtin::WALL_Z;
use common::*;
use glam::Vec3;

const SIZE: [u32; 2] = [128, 128];
/// The close wall's tolerances of tests/probe.rs: 3 steps lit, 2 shading normal.
const WALL: [f32; 2] = [3.0, 2.0];
/// Emboss reads its light map at the nearest texel: the GPU's filtering rounding in the
/// height samples can move the lookup by one texel, 1/128 of the brightness, up to 5 steps of
/// the sRGB picture at its dark end; 6 steps lit.
const EMBOSS: [f32; 2] = [6.0, 2.0];

/// The close wall in the bump-only picture (white albedo) with `legacy`, the light 0.35 m in
/// front of it: each of the wall's triangles (0.5 × 0.375 m) spans about a light distance.
fn wall(legacy: LegacySettings) -> (bumpview::scene::Scene, FrameParams) {
    let scene = scene();
    let mut params = close_wall_params(&scene, 0.3);
    params.shading.mode = ShadingMode::BumpOnly;
    params.shading.legacy = legacy;
    (scene, params)
}

/// With L normalised per vertex and interpolated, DOT3 lights with a vector shorter than 1
/// between the vertices (and turned from the true direction): unit next to the vertices,
/// shortest mid-triangle, and the picture darker than with that vector re-normalised.
#[test]
fn dot3_with_l_per_vertex_is_shorter_between_vertices() {
    let (scene, params) = wall(LegacySettings { look: LegacyLook::Dot3, cube_map_size: None });
    // Every 6 pixels from (4, 4): (64, 64), next to the wall's vertex at (0, 1.5), is sampled.
    let readouts = gpu_against_probe(&scene, &SceneOptions::default(), &params, SIZE, 6, WALL);
    let (mut shortest, mut near_vertex, mut turned, mut near) = (1.0f32, 0.0f32, 0.0f32, 0);
    for (_, r) in &readouts {
        let l = r.chain.dot3_light.unwrap();
        // L per vertex, from the light's position to each corner of the hit triangle, mixed
        // with the hit's weights (the wall's point light; its instance is not moved).
        let instance = &scene.instances[r.point.instance];
        let mesh = &scene.meshes[instance.mesh];
        let corners = &mesh.indices[3 * r.point.triangle..3 * r.point.triangle + 3];
        let expected: glam::Vec3 = (0..3)
            .map(|i| {
                let corner = instance.transform.transform_point3(mesh.positions[corners[i] as usize]);
                (params.lights[0].position - corner).normalize() * r.point.barycentric[i]
            })
            .sum();
        assert!((l - expected).length() < 1e-4, "L {l} against {expected} mixed from the corners");
        let expected = params.lights[0].color * params.lights[0].intensity * r.chain.shading_normal.dot(l).max(0.0);
        assert!((r.chain.color_linear - expected).abs().max_element() < 1e-5);
        shortest = shortest.min(l.length());
        turned = turned.max(l.angle_between(r.chain.lights[0].unwrap().direction).to_degrees());
        if r.point.barycentric.max_element() > 0.99 {
            near_vertex = near_vertex.max(1.0 - l.length());
            near += 1;
        }
    }
    println!(
        "DOT3, L per vertex: shortest |L| {shortest:.4}, {near_vertex:.5} short at {near} pixels next to vertices, turned up to {turned:.1}°"
    );
    assert!(shortest < 0.95 && near_vertex < 0.005 && near > 0, "{shortest} {near_vertex} {near}");
}

/// Through a normalization cube map the interpolated L is re-normalised up to the map's
/// resolution: the largest difference to the exactly re-normalised vector shrinks with the
/// face size until the texels' 8 bits dominate (here from 16² on: 2 steps of 1/255 at most).
/// The per-vertex direction error stays: the cube map cannot see it.
#[test]
fn dot3_through_the_cube_map_approaches_exact_normalisation() {
    let mut errors = vec![];
    for size in CUBE_MAP_SIZES {
        let (scene, params) = wall(LegacySettings { look: LegacyLook::Dot3, cube_map_size: Some(size) });
        let readouts = gpu_against_probe(&scene, &SceneOptions::default(), &params, SIZE, 7, WALL);
        let worst = readouts
            .iter()
            .map(|(_, r)| (r.chain.dot3_light.unwrap() - r.chain.vertex_light.normalize()).length())
            .fold(0.0f32, f32::max);
        println!(
            "DOT3, cube map {size}²: worst |L_cube − normalize(L)| {worst:.4} ({:.1} steps of 1/255)",
            worst * 255.0
        );
        errors.push(worst);
    }
    assert!(errors[1..].iter().all(|&e| e < 2.0 / 255.0 && e < errors[0] / 2.0), "{errors:?}");
}

/// Emboss with bump off (no slope) is the light map alone: the spot `1 − r / 128` with `r`
/// the distance in centimetres from the light's foot on the wall (to the light map's texel);
/// with bump on, only sloped pixels change.
#[test]
fn emboss_is_the_light_map_spot_moved_by_the_slopes() {
    let (scene, mut params) = wall(LegacySettings { look: LegacyLook::Emboss, cube_map_size: None });
    // The height map is bound for emboss (ViewerState::scene_uploads sets this).
    let options = SceneOptions { parallax: true, ..Default::default() };
    params.shading.bump_enabled = false;
    let flat = gpu_against_probe(&scene, &options, &params, SIZE, 7, WALL);
    let foot = Vec3::new(params.lights[0].position.x, params.lights[0].position.y, WALL_Z);
    let worst = flat
        .iter()
        .map(|(_, r)| {
            let spot = (1.0 - (r.position - foot).length() * 100.0 / 128.0).max(0.0);
            (r.chain.color_linear.x - spot).abs()
        })
        .fold(0.0f32, f32::max);
    println!("emboss, bump off: worst {worst:.4} off the spot 1 − r/128");
    assert!(worst < 0.02, "{worst}");
    params.shading.bump_enabled = true;
    let bumped = gpu_against_probe(&scene, &options, &params, SIZE, 7, EMBOSS);
    let (mut moved, mut still) = (0, 0);
    for ((_, f), (_, b)) in flat.iter().zip(&bumped) {
        if (f.chain.color_linear - b.chain.color_linear).abs().max_element() > 1e-6 {
            moved += 1;
        } else {
            still += 1;
        }
    }
    println!("emboss, bump on: {moved} pixels changed, {still} unchanged");
    assert!(moved > 10 && still > 10, "{moved} {still}");
}

/// The cube map and the light map are uploaded when a picture first needs them, once while
/// it does, and again only after a picture without them dropped them; pictures without a
/// legacy look upload neither.
#[test]
fn legacy_textures_are_uploaded_only_while_used() {
    let (scene, mut params) = wall(LegacySettings::default());
    let mut renderer = renderer_for(&scene);
    let uploads = |renderer: &bumpview::render::Renderer| renderer.counters().textures_uploaded;
    let mut draw = |renderer: &mut bumpview::render::Renderer, legacy| {
        params.shading.legacy = legacy;
        bumpview::render::capture::render_image(renderer, [32, 32], &params).unwrap();
    };
    draw(&mut renderer, LegacySettings::default());
    let scene_textures = uploads(&renderer);
    let cube = LegacySettings { look: LegacyLook::Dot3, cube_map_size: Some(32) };
    draw(&mut renderer, cube);
    draw(&mut renderer, cube);
    assert_eq!(uploads(&renderer), scene_textures + 1, "the cube map, once");
    draw(&mut renderer, LegacySettings { look: LegacyLook::Emboss, cube_map_size: None });
    assert_eq!(uploads(&renderer), scene_textures + 2, "the light map; the cube map dropped");
    draw(&mut renderer, LegacySettings::default());
    draw(&mut renderer, cube);
    assert_eq!(uploads(&renderer), scene_textures + 3, "the cube map again, after it was dropped");
}

/// The legacy looks light with the first light that is on, whatever its kind: DOT3 under a
/// directional light is `radiance · max(N·L, 0)` with L its direction (the same at every
/// vertex, so interpolation leaves it unit); with every light off, DOT3 and emboss show the
/// ambient light alone. The GPU draws each as the probe.
#[test]
fn legacy_looks_use_the_first_light_and_the_ambient_light_without_one() {
    let (scene, mut params) = wall(LegacySettings { look: LegacyLook::Dot3, cube_map_size: None });
    let mut sun = bumpview::scene::Light::directional(Vec3::new(0.3, 0.4, 1.0), Vec3::new(1.0, 0.8, 0.6));
    sun.intensity = 0.9;
    params.lights[0].enabled = false;
    params.lights.push(sun).unwrap();
    let readouts = gpu_against_probe(&scene, &SceneOptions::default(), &params, SIZE, 7, WALL);
    let l = sun.position.normalize();
    let worst = readouts
        .iter()
        .map(|(_, r)| {
            let expected = sun.color * sun.intensity * r.chain.shading_normal.dot(l).max(0.0);
            (r.chain.color_linear - expected).abs().max_element()
        })
        .fold(0.0f32, f32::max);
    println!("DOT3 under a directional light: worst {worst:.2e} off radiance · max(N·L, 0)");
    assert!(worst < 1e-5 && !readouts.is_empty(), "{worst}");
    params.lights[1].enabled = false;
    let options = SceneOptions { parallax: true, ..Default::default() };
    for look in [LegacyLook::Dot3, LegacyLook::Emboss] {
        params.shading.legacy = LegacySettings { look, cube_map_size: None };
        let readouts = gpu_against_probe(&scene, &options, &params, SIZE, 7, WALL);
        let ambient = params.lights.ambient();
        let exact = readouts.iter().all(|(_, r)| r.chain.color_linear == ambient);
        println!("{look:?} with every light off: {} pixels, each the ambient light: {exact}", readouts.len());
        assert!(exact && !readouts.is_empty());
    }
}
