//! Stiff and extreme shading cases on the software adapter: transforms that stretch or
//! mirror, a camera inside a mesh, grazing light. Each renders to a float target too and
//! asserts that no pixel is NaN or infinity.

mod common;

use bumpview::frame::FrameParams;
use bumpview::frame::ViewMode;
use bumpview::names::Named;
use bumpview::render::Renderer;
use bumpview::render::capture::{render_float, render_image};
use bumpview::report::surfaces::uv_sphere;
use bumpview::scene::builtin::{WALL_Z, teaching_scene};
use bumpview::scene::{Instance, OrbitCamera, Scene};
use common::*;
use glam::{Mat4, Vec2, Vec3};

/// A scene holding one UV sphere placed by `transform`, with the bricks' colour and no bump.
fn sphere_scene(transform: Mat4) -> Scene {
    let mut scene = teaching_scene();
    let material = bumpview::scene::Material { normal_map: None, double_sided: false, ..scene.materials[1].clone() };
    scene.meshes = vec![uv_sphere(96, 48).mesh];
    scene.materials = vec![material];
    scene.instances = vec![Instance { mesh: 0, material: 0, transform }];
    scene
}

fn assert_finite(renderer: &mut Renderer, params: &FrameParams, case: &str) {
    for &view in ViewMode::all() {
        let mut params = *params;
        params.shading.view = view;
        let image = render_float(renderer, [96, 72], &params).unwrap();
        let bad = image.pixels.iter().filter(|p| p.iter().any(|c| !c.is_finite())).count();
        assert_eq!(bad, 0, "{case}, {view:?}: {bad} non-finite pixels");
    }
}

/// An ellipsoid made by scaling a unit sphere by (a, b, c): its exact normal at a surface
/// point p is `normalize(p.x/a², p.y/b², p.z/c²)`, i.e. the sphere normal n mapped to
/// `normalize(n.x/a, n.y/b, n.z/c)` — what the inverse-transpose gives. The Normal view
/// matches it to within the mesh's faceting (96×48) and 8-bit colour: mean < 0.5°, max < 2°
/// (measured on lavapipe: mean 0.18°, max 0.53°).
/// `mirror` negates a: the determinant turns negative, normals must still point outwards.
fn check_ellipsoid(mirror: bool) {
    let (a, b, c) = (1.6f32, 0.7, 1.1);
    let scale = Vec3::new(if mirror { -a } else { a }, b, c);
    let scene = sphere_scene(Mat4::from_scale(scale));
    let mut renderer = renderer_for(&scene);
    let mut params = default_params(&scene);
    params.camera = OrbitCamera { target: Vec3::ZERO, yaw: 0.6, pitch: 0.35, distance: 5.0, ..params.camera };
    params.shading.view = ViewMode::Normal;
    let size = [200, 150];
    let image = render_image(&mut renderer, size, &params).unwrap();
    let mut angles = vec![];
    for y in (0..size[1]).step_by(2) {
        for x in (0..size[0]).step_by(2) {
            let (origin, dir) = params.camera.ray_through_pixel(
                Vec2::new(x as f32 + 0.5, y as f32 + 0.5),
                Vec2::new(size[0] as f32, size[1] as f32),
            );
            // Ray against x²/a² + y²/b² + z²/c² = 1, in the unit sphere's space.
            let inv = Vec3::new(1.0 / a, 1.0 / b, 1.0 / c);
            let (o, d) = (origin * inv, dir * inv);
            let (qa, qb, qc) = (d.dot(d), 2.0 * o.dot(d), o.dot(o) - 1.0);
            let disc = qb * qb - 4.0 * qa * qc;
            if disc <= 0.0 {
                continue;
            }
            let t = (-qb - disc.sqrt()) / (2.0 * qa);
            let p = origin + dir * t;
            let exact = Vec3::new(p.x / (a * a), p.y / (b * b), p.z / (c * c)).normalize();
            // Skip the silhouette, where the pixel mixes surfaces.
            if exact.dot(-dir) < 0.2 {
                continue;
            }
            angles.push(decode_debug(image.get_pixel(x, y)).angle_between(exact).to_degrees());
        }
    }
    let mean = angles.iter().sum::<f32>() / angles.len() as f32;
    let max = angles.iter().copied().fold(0.0, f32::max);
    println!("ellipsoid (mirror {mirror}): {} pixels, mean {mean:.2}°, max {max:.2}°", angles.len());
    assert!(angles.len() > 500, "the ellipsoid fills part of the view");
    assert!(mean < 0.5 && max < 2.0, "mean {mean}°, max {max}°");
    assert_finite(&mut renderer, &params, "ellipsoid");
}

#[test]
fn non_uniform_scale_gives_exact_ellipsoid_normals() {
    check_ellipsoid(false);
}

#[test]
fn negative_determinant_keeps_normals_outward() {
    check_ellipsoid(true);
}

/// The camera inside the torus tube and inside the sphere: only back faces or nothing in
/// view; the picture is finite and the renderer does not fail.
#[test]
fn camera_inside_a_mesh_stays_finite() {
    let scene = scene();
    let mut renderer = renderer_for(&scene);
    let mut params = default_params(&scene);
    let tube_centre =
        bumpview::scene::builtin::TORUS_CENTER + Vec3::new(bumpview::scene::builtin::TORUS_MAJOR_RADIUS, 0.0, 0.0);
    params.camera = OrbitCamera { target: tube_centre, distance: 0.05, ..params.camera };
    assert_finite(&mut renderer, &params, "inside the torus");
    let sphere = sphere_scene(Mat4::IDENTITY);
    let mut renderer = renderer_for(&sphere);
    params.camera = OrbitCamera { target: Vec3::ZERO, distance: 0.1, ..params.camera };
    assert_finite(&mut renderer, &params, "inside the sphere");
}

/// Grazing light on the wall: just below the wall's plane the wall gets ambient only, even
/// where the bumped normal leans towards the light; just above it the self-shadow fade
/// lets in only a little light; both pictures are finite.
#[test]
fn grazing_light_is_faded_and_never_lights_from_below() {
    let scene = scene();
    let mut renderer = renderer_for(&scene);
    let mut params = close_wall_params(&scene, 0.3);
    params.shading.strength = 4.0; // steep bevels lean far towards a grazing light
    let mut dark = params;
    dark.lights[0].color = Vec3::ZERO;
    let ambient = render_image(&mut renderer, [96, 96], &dark).unwrap();
    let brightness = |p: &FrameParams, renderer: &mut Renderer| {
        let image = render_image(renderer, [96, 96], p).unwrap();
        image
            .pixels()
            .zip(ambient.pixels())
            .map(|(a, b)| (0..3).map(|c| a[c].abs_diff(b[c]) as u32).sum::<u32>())
            .sum::<u32>()
    };
    let mut below = params;
    below.lights[0].position = Vec3::new(3.0, 1.5, WALL_Z - 1e-3);
    assert_eq!(brightness(&below, &mut renderer), 0, "light below the surface adds nothing");
    assert_finite(&mut renderer, &below, "grazing from below");
    let mut above = params;
    above.lights[0].position = Vec3::new(3.0, 1.5, WALL_Z + 0.05);
    let mut frontal = params;
    frontal.lights[0].position = Vec3::new(0.0, 1.5, WALL_Z + 0.5);
    let (grazing, full) = (brightness(&above, &mut renderer), brightness(&frontal, &mut renderer));
    println!("light added: grazing {grazing}, frontal {full}");
    assert!(grazing > 0 && grazing * 4 < full, "grazing {grazing} vs frontal {full}");
    assert_finite(&mut renderer, &above, "grazing from above");
}

/// The UV check view marks what `bumpview check` counts: a square whose right half has
/// mirrored u shows blue there and grey on the left; a square whose UVs have no area is red.
#[test]
fn uv_check_view_marks_mirrored_and_degenerate_triangles() {
    use bumpview::report::stiff::{grid, mirrored_halves};
    let mut scene = teaching_scene();
    let material = bumpview::scene::Material { normal_map: None, ..scene.materials[0].clone() };
    let mut degenerate = grid(2, |_| Vec2::splat(0.5));
    degenerate.positions.iter_mut().for_each(|p| p.y -= 1.2);
    scene.meshes = vec![mirrored_halves(), degenerate];
    scene.materials = vec![material];
    scene.instances = vec![
        Instance { mesh: 0, material: 0, transform: Mat4::IDENTITY },
        Instance { mesh: 1, material: 0, transform: Mat4::IDENTITY },
    ];
    let mut renderer = renderer_for(&scene);
    let mut params = default_params(&scene);
    params.camera =
        OrbitCamera { target: Vec3::new(0.5, -0.1, 0.0), yaw: 0.0, pitch: 0.0, distance: 4.0, ..params.camera };
    params.shading.view = ViewMode::UvCheck;
    let size = [200, 200];
    let image = render_image(&mut renderer, size, &params).unwrap();
    let pixel_at = |p: Vec3| {
        let clip = params.camera.view_projection(1.0).project_point3(p);
        let (x, y) = (((clip.x + 1.0) * 0.5 * size[0] as f32) as u32, ((1.0 - clip.y) * 0.5 * size[1] as f32) as u32);
        *image.get_pixel(x, y)
    };
    let (left, right, red) =
        (pixel_at(Vec3::new(0.2, 0.5, 0.0)), pixel_at(Vec3::new(0.8, 0.5, 0.0)), pixel_at(Vec3::new(0.5, -0.7, 0.0)));
    assert!(left[0].abs_diff(left[2]) < 10 && left[0] > 60, "left half grey: {left:?}");
    assert!(right[2] as i32 > right[0] as i32 + 60, "right half blue: {right:?}");
    assert!(red[0] as i32 > red[2] as i32 + 60, "degenerate square red: {red:?}");
    assert_finite(&mut renderer, &params, "uv check");
}

/// Every stiff tangent case (report::stiff::cases) drawn normal-mapped with every generated
/// tangent method: the float target holds no NaN or infinity in the lit and frame views. The
/// case with NaN and infinity in its vertices is repaired on upload, with a notice.
#[test]
fn every_stiff_tangent_case_renders_finite_with_every_method() {
    use bumpview::frame::SceneOptions;
    use bumpview::report::stiff::cases;
    use bumpview::tangent::TangentMethod;
    for case in cases() {
        let mut scene = teaching_scene();
        scene.meshes = vec![case.mesh];
        scene.instances = vec![Instance { mesh: 0, material: 0, transform: Mat4::IDENTITY }];
        let mut params = default_params(&scene);
        params.camera =
            OrbitCamera { target: Vec3::new(0.5, 0.5, 0.0), yaw: 0.2, pitch: 0.1, distance: 3.0, ..params.camera };
        let gpu = bumpview::render::Gpu::headless().unwrap();
        let mut renderer = Renderer::from_gpu(&gpu);
        for method in TangentMethod::all().iter().copied().filter(|m| m.is_generated()) {
            renderer.set_scene(&scene, SceneOptions { tangent_method: Some(method), ..Default::default() });
            if case.name.starts_with("NaN") {
                assert!(
                    renderer.notices().iter().any(|n| n.contains("NaN or infinite data")),
                    "{:?}",
                    renderer.notices()
                );
            }
            for view in [ViewMode::Lit, ViewMode::Tangent, ViewMode::ShadingNormal] {
                let mut params = params;
                params.shading.view = view;
                let image = render_float(&mut renderer, [64, 48], &params).unwrap();
                let bad = image.pixels.iter().filter(|p| p.iter().any(|c| !c.is_finite())).count();
                assert_eq!(bad, 0, "{}, {method:?}, {view:?}: {bad} non-finite pixels", case.name);
            }
        }
    }
}
