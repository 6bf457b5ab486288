//! The pixel probe (src/probe/) against the ray-plane reference of the wall and against
//! rendered pixels: the probe's numbers are the CPU twin of what the GPU draws there.

mod common;

use bumpview::frame::{SceneOptions, ViewMode};
use bumpview::load::load_scene;
use bumpview::probe::ProbeScene;
use bumpview::render::Background;
use bumpview::render::capture::{CaptureOptions, render_capture, render_image};
use bumpview::scene::builtin::{WALL_Z, wall_uv};
use bumpview::scene::{GreenAxis, MaterialOverrides, OrbitCamera};
use common::*;
use glam::Vec3;

const SIZE: [u32; 2] = [256, 256];
/// A grid of pixels over the close wall view (12 × 12, every 23 pixels; some on mortar edges).
fn pixels() -> impl Iterator<Item = [u32; 2]> {
    (3..SIZE[1]).step_by(23).flat_map(|y| (5..SIZE[0]).step_by(23).map(move |x| [x, y]))
}

fn close(a: Vec3, b: Vec3, tolerance: f32) -> bool {
    (a - b).abs().max_element() <= tolerance
}

/// UV and frame equal the wall's; the colour equals the rendered lit pixel within the bumped
/// tolerance of tests/shading_reference.rs (3 steps of 8 bits per channel: the maximum over the
/// wall, reached only next to mortar edges; 1.5 steps for 99% of pixels).
#[test]
fn probe_on_the_close_wall_matches_the_wall_and_the_rendered_pixels() {
    let scene = scene();
    let params = close_wall_params(&scene, 0.3);
    let probe_scene = ProbeScene::new(&scene, &SceneOptions::default());
    let mut renderer = renderer_for(&scene);
    let lit = render_image(&mut renderer, SIZE, &params).unwrap();
    let mut normal_params = params;
    normal_params.shading.view = ViewMode::ShadingNormal;
    let normals = render_image(&mut renderer, SIZE, &normal_params).unwrap();
    let mut worst = (0.0f32, 0.0f32);
    for [x, y] in pixels() {
        let readout = probe_scene.probe(&params, SIZE, [x, y]).expect("the wall fills the view");
        let hit = hit_plane(&params.camera, SIZE, x, y, Vec3::Z, WALL_Z).unwrap();
        assert_eq!(readout.mesh, 0, "the wall");
        assert!(close(readout.position, hit, 1e-5), "{x},{y}: {} vs {hit}", readout.position);
        let uv = wall_uv(hit);
        assert!((readout.uv - uv).abs().max_element() < 1e-5, "{x},{y}: uv {} vs {uv}", readout.uv);
        assert!(close(readout.chain.tangent.unwrap(), Vec3::X, 1e-5), "T {:?}", readout.chain.tangent);
        assert!(close(readout.chain.bitangent.unwrap(), Vec3::Y, 1e-5), "B {:?}", readout.chain.bitangent);
        assert!(close(readout.chain.normal, Vec3::Z, 1e-5), "N {}", readout.chain.normal);
        assert_eq!(readout.chain.w, Some(1.0));
        assert!(readout.texel_raw.is_some() && readout.chain.decoded.is_some());
        // The same chain as the wall reference of tests/common.
        let reference = wall_chain(&scene, &params, SIZE, x, y);
        let n_diff = (readout.chain.shading_normal - reference.shading_normal).abs().max_element();
        assert!(
            n_diff < 1e-3,
            "({x},{y}): shading normal {} vs reference {}",
            readout.chain.shading_normal,
            reference.shading_normal
        );
        assert!(close(readout.chain.albedo, reference.albedo, 1e-5));

        let gpu = lit.get_pixel(x, y);
        let cpu = readout.shown_bytes().unwrap();
        let diff = (0..3).map(|c| (gpu[c] as f32 - cpu[c]).abs()).fold(0.0, f32::max);
        let stored = normals.get_pixel(x, y);
        let expected = (readout.chain.shading_normal * 0.5 + 0.5) * 255.0;
        let normal_diff = (0..3).map(|c| (stored[c] as f32 - expected[c]).abs()).fold(0.0, f32::max);
        worst = (worst.0.max(diff), worst.1.max(normal_diff));
        assert!(diff <= 3.0, "({x},{y}): GPU {gpu:?} vs probe {cpu}");
        assert!(normal_diff <= 2.0, "({x},{y}): shading normal view {stored:?} vs probe {expected}");
        // The decoded pixel of the Shading-normal view within 2/255 per stored channel.
        assert!(close(decode_debug(stored), readout.chain.shading_normal, 4.0 / 255.0 + 1e-3));
    }
    println!("worst: lit {} steps, shading normal {} steps", worst.0, worst.1);
}

#[test]
fn a_ray_that_meets_nothing_gives_none() {
    let scene = scene();
    let mut params = close_wall_params(&scene, 0.3);
    // Level with the horizon, far above the wall and the torus.
    params.camera =
        OrbitCamera { target: Vec3::new(0.0, 40.0, 0.0), yaw: 0.0, pitch: 0.0, distance: 5.0, ..params.camera };
    let probe_scene = ProbeScene::new(&scene, &SceneOptions::default());
    assert!(probe_scene.probe(&params, SIZE, [128, 128]).is_none());
    assert!(probe_scene.probe(&params, SIZE, [0, 0]).is_none());
}

/// The pinned point stays; N·L follows the light as `N · normalize(light − P)` says.
#[test]
fn moving_the_light_changes_n_dot_l_at_the_pinned_point() {
    let scene = scene();
    let mut params = close_wall_params(&scene, 0.3);
    let probe_scene = ProbeScene::new(&scene, &SceneOptions::default());
    let point = probe_scene.pick(&params.camera, SIZE, [90, 140]).unwrap();
    let before = probe_scene.readout(&point, &params, SIZE);
    params.lights[0].position = Vec3::new(-0.4, 1.2, WALL_Z + 0.2);
    params.camera.yaw = 0.3; // the camera may move too: the point stays pinned
    let after = probe_scene.readout(&point, &params, SIZE);
    assert_eq!(before.position, after.position);
    assert_eq!(before.chain.shading_normal, after.chain.shading_normal);
    let expected = after.chain.shading_normal.dot((params.lights[0].position - after.position).normalize());
    assert!(
        (after.chain.lights[0].unwrap().n_dot_l - expected).abs() < 1e-6,
        "{} vs {expected}",
        after.chain.lights[0].unwrap().n_dot_l
    );
    assert!(
        (after.chain.lights[0].unwrap().n_dot_l - before.chain.lights[0].unwrap().n_dot_l).abs() > 0.05,
        "{} vs {}",
        after.chain.lights[0].unwrap().n_dot_l,
        before.chain.lights[0].unwrap().n_dot_l
    );
    assert_ne!(before.chain.color_linear, after.chain.color_linear);
}

/// The probe uses the material overrides the renderer draws with: DirectX green flips the
/// decoded y of the same texel.
#[test]
fn material_overrides_reach_the_probe() {
    let scene = scene();
    let params = close_wall_params(&scene, 0.3);
    let plain = ProbeScene::new(&scene, &SceneOptions::default()).probe(&params, SIZE, [40, 50]).unwrap();
    let options = SceneOptions {
        materials: MaterialOverrides { green: Some(GreenAxis::DirectX), ..Default::default() },
        ..Default::default()
    };
    let flipped = ProbeScene::new(&scene, &options).probe(&params, SIZE, [40, 50]).unwrap();
    assert_eq!(plain.texel_raw, flipped.texel_raw);
    let (a, b) = (plain.chain.decoded.unwrap(), flipped.chain.decoded.unwrap());
    assert!((a.x - b.x).abs() < 1e-6 && (a.y + b.y).abs() < 1e-6, "{a} {b}");
}

/// The third-party meshes the pick bench times (benches/probe_pick.rs), each through the
/// asset helper (set, a missing file fails): from the default camera a row of picks across
/// the middle of the view hits the mesh, and every hit lies on its pixel's ray (it projects
/// back to the pixel centre within 0.01 px: f32 rounding of a point a few metres away) with
/// barycentric coordinates inside its triangle (within 1e-5 of rounding).
#[test]
fn picks_on_the_asset_meshes_hit_on_the_ray() {
    let base = assets();
    for relative in [
        "obj/spot/spot_triangulated.obj",
        "gltf/NormalTangentMirrorTest/glTF/NormalTangentMirrorTest.gltf",
        "gltf/WaterBottle/glTF/WaterBottle.gltf",
        "gltf/Suzanne/glTF/Suzanne.gltf",
    ] {
        let scene = load_scene(&asset(&base, relative)).unwrap_or_else(|e| panic!("{e}"));
        let probe_scene = ProbeScene::new(&scene, &SceneOptions::default());
        let params = bumpview::state::ViewerState::new(&scene).frame_params();
        let mut hits = 0;
        for x in (98..158).step_by(3) {
            let Some(point) = probe_scene.pick(&params.camera, SIZE, [x, 128]) else { continue };
            hits += 1;
            let b = point.barycentric;
            assert!(b.min_element() > -1e-5 && (b.element_sum() - 1.0).abs() < 1e-5, "{relative} at {x}: {b}");
            let position = probe_scene.readout(&point, &params, SIZE).position;
            let shown = bumpview::probe::project_to_pixel(&params.camera, SIZE, position).expect("in front");
            let centre = glam::Vec2::new(x as f32 + 0.5, 128.5);
            assert!(shown.distance(centre) < 0.01, "{relative} at {x}: the hit {position} shows at {shown}");
        }
        println!("{relative}: {} triangles, {hits} of 20 picks hit", probe_scene.triangle_count());
        assert!(hits >= 10, "{relative}: the default camera frames the mesh, yet {hits} of 20 picks hit");
    }
}

/// Frames as drawn on third-party meshes: supplied tangents with mirrored islands (w = −1) and
/// double-sided materials seen from both sides (back faces flip N and B). The probe's Normal,
/// Tangent and Bitangent views equal the rendered ones within 1 step at 95% of the probed
/// pixels and 3 steps at all (measured 0.55 and 2.5 on lavapipe). Partly covered (antialiased) pixels, alpha < 255 over a transparent background, are
/// left out, and so are pixels whose neighbours differ (creases, which MSAA blends and the probe
/// does not).
#[test]
fn probe_frames_match_the_rendered_debug_views_on_assets() {
    let base = assets();
    let size = [128, 128];
    for relative in
        ["gltf/NormalTangentMirrorTest/glTF/NormalTangentMirrorTest.gltf", "gltf/TwoSidedPlane/glTF/TwoSidedPlane.gltf"]
    {
        let scene = load_scene(&asset(&base, relative)).unwrap();
        let probe_scene = ProbeScene::new(&scene, &SceneOptions::default());
        let mut renderer = renderer_for(&scene);
        let mut diffs = vec![];
        let mut back_faces = 0;
        for (turn, tilt) in [(0.0, 1.0), (std::f32::consts::PI, 1.0), (0.0, -1.0)] {
            for view in [ViewMode::Normal, ViewMode::Bitangent, ViewMode::Tangent] {
                let mut params = default_params(&scene);
                params.camera.yaw += turn;
                params.camera.pitch *= tilt;
                params.camera.distance = bounding_sphere_distance(&scene, &params.camera);
                params.shading.view = view;
                let options = CaptureOptions { background: Background::Transparent, ..CaptureOptions::plain(size) };
                let image = render_capture(&mut renderer, &options, &params).unwrap();
                let shown = |x, y| probe_scene.probe(&params, size, [x, y]).and_then(|r| r.shown_bytes());
                for y in (1..size[1] - 1).step_by(3) {
                    for x in (1..size[0] - 1).step_by(3) {
                        let gpu = image.get_pixel(x, y);
                        let Some(readout) = probe_scene.probe(&params, size, [x, y]).filter(|_| gpu[3] == 255) else {
                            continue;
                        };
                        let cpu = readout.shown_bytes().unwrap();
                        let smooth = [(x - 1, y), (x + 1, y), (x, y - 1), (x, y + 1)]
                            .into_iter()
                            .all(|(nx, ny)| shown(nx, ny).is_some_and(|c| (c - cpu).abs().max_element() <= 6.0));
                        if !smooth {
                            continue;
                        }
                        back_faces += !readout.point.front_facing as u32;
                        diffs.push((0..3).map(|c| (gpu[c] as f32 - cpu[c]).abs()).fold(0.0, f32::max));
                    }
                }
            }
        }
        diffs.sort_by(f32::total_cmp);
        let (p95, max) = (percentile(&diffs, 0.95), *diffs.last().unwrap());
        println!("{relative}: {} pixels ({back_faces} on back faces), p95 {p95} max {max} steps", diffs.len());
        assert!(diffs.len() > 300 && back_faces > 50, "{relative}: {} pixels", diffs.len());
        assert!(p95 <= 1.0 && max <= 3.0, "{relative}: p95 {p95} max {max} steps");
    }
}

/// Blinn's bump from the height map in the shader: the probe's screen-space differences over
/// the pixel's 2×2 quad give the shading normal and colour the GPU stores there, face-on and
/// from an angle. The probe computes in exact arithmetic; lavapipe filters the 16-bit height's
/// two 8-bit channels with 8-bit results, which a difference of neighbouring samples magnifies
/// (measured: median ≈ 1 step, 95th percentile 2.8 / 5.0, max 3.9 / 6.3 steps face-on / at
/// yaw 0.5). The bounds sit above that; a probe without the bump is far further off.
#[test]
fn probe_reproduces_the_height_bump_in_the_shader() {
    let scene = scene();
    let options = SceneOptions { bump_source: bumpview::frame::BumpSource::HeightInShader, ..Default::default() };
    let probe_scene = ProbeScene::new(&scene, &options);
    let mut renderer = renderer_for(&scene);
    renderer.set_scene(&scene, options);
    let max_diff = |stored: &image::Rgba<u8>, expected: Vec3| {
        (0..3).map(|c| (stored[c] as f32 - expected[c]).abs()).fold(0.0, f32::max)
    };
    for (yaw, pitch) in [(0.0f32, 0.0f32), (0.5, 0.3)] {
        let mut params = close_wall_params(&scene, 0.3);
        params.camera.yaw = yaw;
        params.camera.pitch = pitch;
        let lit = render_image(&mut renderer, SIZE, &params).unwrap();
        let mut normal_params = params;
        normal_params.shading.view = ViewMode::ShadingNormal;
        let normals = render_image(&mut renderer, SIZE, &normal_params).unwrap();
        let (mut colour, mut normal, mut unbumped) = (vec![], vec![], vec![]);
        for [x, y] in pixels() {
            let Some(readout) = probe_scene.probe(&params, SIZE, [x, y]) else { continue };
            let stored = normals.get_pixel(x, y);
            normal.push(max_diff(stored, (readout.chain.shading_normal * 0.5 + 0.5) * 255.0));
            unbumped.push(max_diff(stored, (readout.chain.normal * 0.5 + 0.5) * 255.0));
            colour.push(max_diff(lit.get_pixel(x, y), readout.shown_bytes().unwrap()));
        }
        for diffs in [&mut colour, &mut normal, &mut unbumped] {
            diffs.sort_by(f32::total_cmp);
        }
        let stats = |d: &[f32]| (percentile(d, 0.5), percentile(d, 0.95), d[d.len() - 1]);
        let (c, n, u) = (stats(&colour), stats(&normal), stats(&unbumped));
        println!("yaw {yaw}: {} pixels; (p50, p95, max) colour {c:?} normal {n:?} without bump {u:?}", normal.len());
        assert!(normal.len() > 100);
        for (what, (p50, p95, max)) in [("colour", c), ("shading normal", n)] {
            assert!(p50 <= 1.5 && p95 <= 6.0 && max <= 10.0, "{what}: p50 {p50} p95 {p95} max {max} steps");
        }
        assert!(u.1 > 3.0 * n.1, "without the bump: p95 {} steps, probe {}", u.1, n.1);
    }
}

/// From the default camera the bricks are minified: the GPU reads smaller mip levels, and so
/// does the probe (level of detail from the pixel quad's UV footprint, linear between levels).
/// Pixels next to another instance or the background are left out (4× MSAA blends them).
/// Measured: colour median 0.7, 95th percentile 2.0 steps (a probe reading only mip level 0:
/// median 16, 95th percentile 53 steps).
#[test]
fn probe_reads_the_mip_levels_the_gpu_reads_when_textures_are_minified() {
    let scene = scene();
    let probe_scene = ProbeScene::new(&scene, &SceneOptions::default());
    let mut renderer = renderer_for(&scene);
    let params = default_params(&scene);
    let lit = render_image(&mut renderer, SIZE, &params).unwrap();
    let mut normal_params = params;
    normal_params.shading.view = ViewMode::ShadingNormal;
    let normals = render_image(&mut renderer, SIZE, &normal_params).unwrap();
    let instance_at = |x: i64, y: i64| {
        let pixel = [x.clamp(0, SIZE[0] as i64 - 1) as u32, y.clamp(0, SIZE[1] as i64 - 1) as u32];
        probe_scene.pick(&params.camera, SIZE, pixel).map(|p| p.instance)
    };
    let (mut colour, mut normal) = (vec![], vec![]);
    for [x, y] in pixels() {
        let Some(readout) = probe_scene.probe(&params, SIZE, [x, y]) else { continue };
        let (x, y) = (x as i64, y as i64);
        let inside = (-1..=1).all(|dy| (-1..=1).all(|dx| instance_at(x + dx, y + dy) == Some(readout.point.instance)));
        if !inside {
            continue;
        }
        let (x, y) = (x as u32, y as u32);
        let stored = normals.get_pixel(x, y);
        let expected = (readout.chain.shading_normal * 0.5 + 0.5) * 255.0;
        normal.push((0..3).map(|c| (stored[c] as f32 - expected[c]).abs()).fold(0.0, f32::max));
        let (gpu, cpu) = (lit.get_pixel(x, y), readout.shown_bytes().unwrap());
        colour.push((0..3).map(|c| (gpu[c] as f32 - cpu[c]).abs()).fold(0.0, f32::max));
    }
    colour.sort_by(f32::total_cmp);
    normal.sort_by(f32::total_cmp);
    let stats = |d: &[f32]| (percentile(d, 0.5), percentile(d, 0.95), d[d.len() - 1]);
    let (c, n) = (stats(&colour), stats(&normal));
    println!("{} pixels; (p50, p95, max) colour {c:?} shading normal {n:?}", colour.len());
    assert!(colour.len() > 50, "{} pixels", colour.len());
    for (what, (p50, p95, max)) in [("colour", c), ("shading normal", n)] {
        assert!(p50 <= 1.5 && p95 <= 3.0 && max <= 6.0, "{what}: p50 {p50} p95 {p95} max {max} steps");
    }
}
