//! The classic demo modes (bump × colour, bump only, colour only), the Handedness and
//! Over-tilt views and the wireframe overlay, on the software adapter, against the CPU twin
//! in src/chain.rs.

mod common;

use bumpview::frame::FrameParams;
use bumpview::frame::{ShadingMode, ViewMode};
use bumpview::math::{linear_to_srgb, srgb_to_linear};
use bumpview::names::Named;
use bumpview::render::capture::{render_float, render_image};
use bumpview::report::stiff::mirrored_halves;
use bumpview::scene::{Instance, OrbitCamera, Scene};
use bumpview::shading::{HANDEDNESS_NEGATIVE, HANDEDNESS_POSITIVE, handedness_color, over_tilt_grey, over_tilted};
use common::*;
use glam::{Mat4, Vec3};

/// Per-channel differences |GPU − CPU| in 8-bit steps on a grid of wall pixels, sorted: the
/// GPU drawing `gpu_mode` against the CPU twin shading `cpu_mode`.
fn mode_differences_against(gpu_mode: ShadingMode, cpu_mode: ShadingMode) -> Vec<f32> {
    let scene = scene();
    let mut renderer = renderer_for(&scene);
    let size = [256, 256];
    let mut params = close_wall_params(&scene, 0.3);
    params.shading.mode = gpu_mode;
    let image = render_image(&mut renderer, size, &params).unwrap();
    let mut diffs = vec![];
    for y in (2..size[1]).step_by(5) {
        for x in (2..size[0]).step_by(5) {
            let gpu = image.get_pixel(x, y);
            let cpu_params = FrameParams {
                shading: bumpview::frame::ShadingSettings { mode: cpu_mode, ..params.shading },
                ..params
            };
            let cpu = wall_chain(&scene, &cpu_params, size, x, y).color_linear.map(|c| linear_to_srgb(c) * 255.0);
            diffs.push((0..3).map(|c| (gpu[c] as f32 - cpu[c]).abs()).fold(0.0, f32::max));
        }
    }
    diffs.sort_by(f32::total_cmp);
    diffs
}

/// [`mode_differences_against`] the CPU twin of the same mode.
fn mode_differences(mode: ShadingMode) -> Vec<f32> {
    mode_differences_against(mode, mode)
}

/// Each mode matches its CPU twin with the tolerances of tests/shading_reference.rs: colour
/// only has no normal map in it (1 step: rounding and filtering); the lit modes read the
/// normal map (99% within 1.5 steps, the few mortar-edge pixels within 3).
#[test]
fn each_mode_matches_the_cpu_reference() {
    for &mode in ShadingMode::all() {
        let diffs = mode_differences(mode);
        let (p99, max) = (percentile(&diffs, 0.99), *diffs.last().unwrap());
        println!("{mode:?}: median {} p99 {p99} max {max} over {} pixels", percentile(&diffs, 0.5), diffs.len());
        if mode == ShadingMode::ColourOnly {
            assert!(max <= 1.0, "{mode:?}: max difference {max} steps");
        } else {
            assert!(p99 <= 1.5 && max <= 3.0, "{mode:?}: p99 {p99}, max {max} steps");
        }
    }
}

/// The comparison can fail: each mode's GPU picture against the CPU twin of each other mode
/// is far off (median over 10 steps, where its own twin is within 1.5 at the 99th percentile).
/// And the modes are different pictures on the GPU too.
#[test]
fn modes_differ_from_each_other() {
    for &gpu_mode in ShadingMode::all() {
        for cpu_mode in ShadingMode::all().iter().copied().filter(|&m| m != gpu_mode) {
            let median = percentile(&mode_differences_against(gpu_mode, cpu_mode), 0.5);
            println!("GPU {gpu_mode:?} against CPU {cpu_mode:?}: median {median} steps");
            assert!(median > 10.0, "GPU {gpu_mode:?} passes for the CPU's {cpu_mode:?}: median {median} steps");
        }
    }
    let scene = scene();
    let mut renderer = renderer_for(&scene);
    let size = [128, 128];
    let images = ShadingMode::all()
        .iter()
        .map(|&mode| {
            let mut params = close_wall_params(&scene, 0.3);
            params.shading.mode = mode;
            render_image(&mut renderer, size, &params).unwrap()
        })
        .collect::<Vec<_>>();
    let mean_difference = |a: &image::RgbaImage, b: &image::RgbaImage| {
        let total: u64 =
            a.pixels().zip(b.pixels()).map(|(p, q)| (0..3).map(|c| p[c].abs_diff(q[c]) as u64).sum::<u64>()).sum();
        total as f64 / (size[0] * size[1] * 3) as f64
    };
    for i in 0..3 {
        for j in i + 1..3 {
            let d = mean_difference(&images[i], &images[j]);
            println!("{:?} vs {:?}: mean {d:.1} steps", ShadingMode::all()[i], ShadingMode::all()[j]);
            assert!(d > 10.0, "{:?} and {:?} look alike ({d})", ShadingMode::all()[i], ShadingMode::all()[j]);
        }
    }
    // Bump only is grey: the white albedo under a white light.
    let grey = images[1].pixels().filter(|p| p[0].abs_diff(p[1]) <= 2 && p[1].abs_diff(p[2]) <= 2).count();
    assert!(grey as f64 > 0.95 * (size[0] * size[1]) as f64, "bump only: {grey} grey pixels");
}

fn is_over_tilt_red(p: &image::Rgba<u8>) -> bool {
    p[0] >= 250 && p[1] <= 5 && p[2] <= 5
}

/// Over-tilt pixels on the close wall: the GPU's red pixels on a grid against the CPU's
/// `over_tilted` on the same texels. Returns (GPU count, CPU count, disagreements away from
/// the threshold).
fn over_tilt_counts(strength: f32) -> (usize, usize, usize) {
    let scene = scene();
    let mut renderer = renderer_for(&scene);
    let size = [256, 256];
    let mut params = close_wall_params(&scene, 0.3);
    params.shading.view = ViewMode::OverTilt;
    params.shading.strength = strength;
    let image = render_image(&mut renderer, size, &params).unwrap();
    let (mut gpu_count, mut cpu_count, mut wrong) = (0, 0, 0);
    let limit = bumpview::shading::over_tilt_cos();
    for y in (1..size[1]).step_by(2) {
        for x in (1..size[0]).step_by(2) {
            let chain = wall_chain(&scene, &params, size, x, y);
            let cpu = over_tilted(chain.normal, chain.shading_normal);
            let gpu = is_over_tilt_red(image.get_pixel(x, y));
            gpu_count += gpu as usize;
            cpu_count += cpu as usize;
            // Filtering differences move the boundary by a fraction of a texel: count only
            // the pixels whose cosine is clearly on one side.
            let margin = (chain.normal.dot(chain.shading_normal) - limit).abs();
            if gpu != cpu && margin > 0.02 {
                wrong += 1;
            }
        }
    }
    (gpu_count, cpu_count, wrong)
}

/// At strength 1 the bricks tilt at most 50°: nothing is marked. At ±4 the bevels tilt up
/// to 78°: the GPU marks the pixels the CPU twin marks.
#[test]
fn over_tilt_marks_steep_bevels_only_at_high_strength() {
    let (gpu, cpu, wrong) = over_tilt_counts(1.0);
    assert_eq!((gpu, cpu, wrong), (0, 0, 0), "strength 1 must mark nothing");
    for strength in [4.0, -4.0] {
        let (gpu, cpu, wrong) = over_tilt_counts(strength);
        println!("strength {strength}: GPU {gpu}, CPU {cpu} marked of 16384, {wrong} clear disagreements");
        assert!(cpu > 50, "strength {strength}: the CPU twin marks only {cpu}");
        assert!((gpu as f32 - cpu as f32).abs() <= 0.1 * cpu as f32, "strength {strength}: GPU {gpu}, CPU {cpu}");
        assert_eq!(wrong, 0, "strength {strength}");
    }
}

/// Outside the marked pixels the Over-tilt view is the lit picture in grey: its linear
/// luminance, so the red marks cannot be taken for red bricks.
#[test]
fn over_tilt_is_the_lit_picture_in_grey_elsewhere() {
    let scene = scene();
    let mut renderer = renderer_for(&scene);
    let mut params = close_wall_params(&scene, 0.3);
    params.shading.strength = 4.0;
    let lit = render_image(&mut renderer, [128, 128], &params).unwrap();
    params.shading.view = ViewMode::OverTilt;
    let marked = render_image(&mut renderer, [128, 128], &params).unwrap();
    let mut red = 0;
    for (p, q) in lit.pixels().zip(marked.pixels()) {
        if is_over_tilt_red(q) {
            red += 1;
        } else {
            // The grey of the lit pixel; 2 steps for the resolve and the 8-bit round trip.
            let linear = Vec3::from_array([0, 1, 2].map(|c| srgb_to_linear(p[c] as f32 / 255.0)));
            let grey = (linear_to_srgb(over_tilt_grey(linear).x) * 255.0).round() as u8;
            assert!((0..3).all(|c| q[c].abs_diff(grey) <= 2), "{p:?} gives grey {grey}, drawn {q:?}");
        }
    }
    assert!(red > 0);
}

/// A scene of `stiff::mirrored_halves` (the right half's UVs mirrored) with the bricks.
fn mirrored_scene() -> Scene {
    let mut scene = scene();
    scene.meshes = vec![mirrored_halves()];
    scene.instances = vec![Instance { mesh: 0, material: 0, transform: Mat4::IDENTITY }];
    scene
}

fn facing_params(scene: &Scene, target: Vec3, distance: f32) -> FrameParams {
    let mut params = default_params(scene);
    params.camera = OrbitCamera { target, yaw: 0.0, pitch: 0.0, distance, ..params.camera };
    params.shading.view = ViewMode::Handedness;
    params
}

fn stored_byte(c: f32) -> f32 {
    c * 255.0
}

/// On the mirrored halves the left half is w = +1 (green) and the right half w = −1
/// (magenta), each equal to `handedness_color` seen head-on, within 1 step.
#[test]
fn handedness_view_shows_the_mirrored_half() {
    let scene = mirrored_scene();
    let mut renderer = renderer_for(&scene);
    let params = facing_params(&scene, Vec3::new(0.5, 0.5, 0.0), 1.2);
    let size = [128, 128];
    let image = render_image(&mut renderer, size, &params).unwrap();
    let eye = params.camera.eye();
    for (x, expected_w) in [(40, 1.0), (88, -1.0)] {
        let y = 64;
        let p = hit_plane(&params.camera, size, x, y, Vec3::Z, 0.0).unwrap();
        let expected = handedness_color(Some(expected_w), Vec3::Z, eye - p).map(stored_byte);
        let pixel = image.get_pixel(x, y);
        let diff = (0..3).map(|c| (pixel[c] as f32 - expected[c]).abs()).fold(0.0, f32::max);
        assert!(diff <= 1.0, "pixel ({x}, {y}) {pixel:?}, expected {expected} (w = {expected_w})");
    }
    // The colours are the documented ones: green for +1, magenta for −1.
    const { assert!(HANDEDNESS_POSITIVE.y > HANDEDNESS_POSITIVE.x && HANDEDNESS_NEGATIVE.x > HANDEDNESS_NEGATIVE.y) };
}

fn is_magenta(p: &image::Rgba<u8>) -> bool {
    p[0] as i32 > p[1] as i32 + 60 && p[2] as i32 > p[1] as i32 + 60
}

fn is_green(p: &image::Rgba<u8>) -> bool {
    p[1] as i32 > p[0] as i32 + 60 && p[1] as i32 > p[2] as i32 + 60
}

/// NormalTangentMirrorTest: `bumpview check` counts mirrored triangles; the Handedness view
/// shows both colours, and the pixels the UV check view paints blue (mirrored UVs) are
/// magenta here.
#[test]
fn handedness_view_agrees_with_the_uv_check_on_the_mirror_test_asset() {
    let base = assets();
    let path = asset(&base, "gltf/NormalTangentMirrorTest/glTF/NormalTangentMirrorTest.gltf");
    let scene = bumpview::load::load_scene(&path).unwrap();
    let mirrored: usize = bumpview::check::check_scene(&scene).meshes.iter().map(|m| m.mirrored).sum();
    assert!(mirrored > 0);
    let mut renderer = renderer_for(&scene);
    let mut params = default_params(&scene);
    let size = [320, 180];
    params.shading.view = ViewMode::Handedness;
    let handedness = render_image(&mut renderer, size, &params).unwrap();
    params.shading.view = ViewMode::UvCheck;
    let uv_check = render_image(&mut renderer, size, &params).unwrap();
    let is_blue = |p: &image::Rgba<u8>| p[2] as i32 > p[0] as i32 + 60 && p[2] as i32 > p[1] as i32 + 30;
    let (mut blue, mut blue_and_magenta, mut green) = (0, 0, 0);
    for (h, u) in handedness.pixels().zip(uv_check.pixels()) {
        green += is_green(h) as usize;
        if is_blue(u) {
            blue += 1;
            blue_and_magenta += is_magenta(h) as usize;
        }
    }
    let magenta = handedness.pixels().filter(|p| is_magenta(p)).count();
    println!("{mirrored} mirrored triangles; {green} green, {magenta} magenta, {blue} UV-check blue");
    assert!(green > 100 && magenta > 100);
    // Edges between cells are antialiased differently in the two views: 95% agreement.
    assert!(blue > 100 && blue_and_magenta as f64 >= 0.95 * blue as f64, "{blue_and_magenta} of {blue}");
    assert!((magenta as f64 - blue as f64).abs() <= 0.1 * blue as f64, "magenta {magenta}, blue {blue}");
}

/// The wireframe overlay: with POLYGON_MODE_LINE (lavapipe has it) it darkens pixels along
/// the projected triangle edges of the wall and nowhere far from them.
#[test]
fn wireframe_overlay_draws_along_triangle_edges() {
    let mut scene = scene();
    // The wall alone, so every edge in view is one of its edges.
    scene.instances.retain(|i| scene.meshes[i.mesh].name == "wall");
    let wall = scene.instances[0].mesh;
    let mut renderer = renderer_for(&scene);
    assert!(renderer.supports_wireframe(), "lavapipe supports POLYGON_MODE_LINE");
    let mut params = facing_params(&scene, Vec3::new(0.0, 1.5, bumpview::scene::builtin::WALL_Z), 3.5);
    params.shading.view = ViewMode::Lit;
    let size = [200, 150];
    let plain = render_image(&mut renderer, size, &params).unwrap();
    params.shading.wireframe = true;
    let wired = render_image(&mut renderer, size, &params).unwrap();
    assert!(renderer.notices().is_empty(), "{:?}", renderer.notices());

    // Projected edges of the wall's triangles.
    let view_proj = params.camera.view_projection(size[0] as f32 / size[1] as f32);
    let mesh = &scene.meshes[wall];
    let to_screen = |p: Vec3| {
        let c = view_proj.project_point3(p);
        glam::Vec2::new((c.x * 0.5 + 0.5) * size[0] as f32, (0.5 - c.y * 0.5) * size[1] as f32)
    };
    let edges: Vec<_> = mesh
        .indices
        .chunks_exact(3)
        .flat_map(|t| [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])])
        .map(|(a, b)| (to_screen(mesh.positions[a as usize]), to_screen(mesh.positions[b as usize])))
        .collect();
    let distance_to_edges = |q: glam::Vec2| {
        edges
            .iter()
            .map(|&(a, b)| {
                let ab = b - a;
                let t = ((q - a).dot(ab) / ab.length_squared().max(1e-12)).clamp(0.0, 1.0);
                (a + ab * t).distance(q)
            })
            .fold(f32::INFINITY, f32::min)
    };
    let luma = |p: &image::Rgba<u8>| p[0] as u32 + p[1] as u32 + p[2] as u32;
    let (mut darker_near, mut changed_far) = (0, 0);
    let mut dark = [0, 0];
    for y in 0..size[1] {
        for x in 0..size[0] {
            let (p, q) = (plain.get_pixel(x, y), wired.get_pixel(x, y));
            let centre = glam::Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
            let near = distance_to_edges(centre) <= 1.5;
            dark[0] += (luma(p) < 150) as usize;
            dark[1] += (luma(q) < 150) as usize;
            if p != q {
                if near {
                    darker_near += (luma(q) < luma(p)) as usize;
                } else {
                    changed_far += 1;
                }
            }
        }
    }
    println!(
        "{} triangles: {darker_near} pixels darkened near edges, {changed_far} changed far; dark {dark:?}",
        edges.len() / 3
    );
    assert!(darker_near > 200, "{darker_near} pixels darkened along the edges");
    assert_eq!(changed_far, 0, "pixels changed away from every edge");
    assert!(dark[1] > dark[0]);

    // Finite on a float target, in every view.
    for &view in ViewMode::all() {
        params.shading.view = view;
        let image = render_float(&mut renderer, [96, 72], &params).unwrap();
        assert!(image.pixels.iter().all(|p| p.iter().all(|c| c.is_finite())), "{view:?}");
    }
}

/// Without line polygon mode the overlay is skipped and a notice says why; switching it off
/// removes the notice. (Checked on a device made without the feature.)
#[test]
fn wireframe_without_line_mode_is_a_notice() {
    let gpu = bumpview::render::Gpu::headless().unwrap();
    let descriptor = wgpu::DeviceDescriptor { label: Some("no lines"), ..Default::default() };
    let (device, queue) = pollster::block_on(gpu.adapter.request_device(&descriptor)).unwrap();
    let mut renderer = bumpview::render::Renderer::new(device, queue, gpu.adapter.clone());
    let scene = scene();
    renderer.set_scene(&scene, Default::default());
    assert!(!renderer.supports_wireframe());
    let mut params = default_params(&scene);
    let plain = render_image(&mut renderer, [64, 48], &params).unwrap();
    params.shading.wireframe = true;
    let wired = render_image(&mut renderer, [64, 48], &params).unwrap();
    assert_eq!(plain, wired, "no overlay without the feature");
    assert!(renderer.notices().iter().any(|n| n == bumpview::render::WIREFRAME_UNSUPPORTED));
    params.shading.wireframe = false;
    render_image(&mut renderer, [64, 48], &params).unwrap();
    assert!(renderer.notices().is_empty(), "{:?}", renderer.notices());
}
