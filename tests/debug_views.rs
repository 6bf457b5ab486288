//! The TBN debug views: each shows a world-space unit vector v as the stored colour 0.5·v + 0.5.

mod common;

use bumpview::frame::ViewMode;
use bumpview::height::{Border, Kernel};
use bumpview::render::capture::render_image;
use bumpview::scene::bricks::brick_height_field;
use bumpview::scene::builtin::{
    BRICK_TILE_M, FLOOR_Z, TORUS_CENTER, TORUS_MAJOR_RADIUS, TORUS_MINOR_RADIUS, WALL_X, WALL_Y, WALL_Z, wall_uv,
};
use common::*;
use glam::{Vec2, Vec3};

#[derive(Debug, Clone, Copy, PartialEq)]
enum Surface {
    Wall,
    Floor,
    Other,
}

/// What the ray through a pixel centre hits first, judged analytically: wall, floor, or
/// something else (the torus's bounding sphere, the background).
fn surface_at(camera: &bumpview::scene::OrbitCamera, size: [u32; 2], x: i64, y: i64) -> Surface {
    if x < 0 || y < 0 || x >= size[0] as i64 || y >= size[1] as i64 {
        return Surface::Other;
    }
    let (x, y) = (x as u32, y as u32);
    let (origin, dir) =
        camera.ray_through_pixel(Vec2::new(x as f32 + 0.5, y as f32 + 0.5), Vec2::new(size[0] as f32, size[1] as f32));
    let to_centre = TORUS_CENTER - origin;
    let closest = to_centre - dir * to_centre.dot(dir);
    if closest.length() < TORUS_MAJOR_RADIUS + TORUS_MINOR_RADIUS + 0.05 {
        return Surface::Other;
    }
    let distance = |p: Option<Vec3>| p.map_or(f32::INFINITY, |p| (p - origin).length());
    let wall = hit_plane(camera, size, x, y, Vec3::Z, WALL_Z)
        .filter(|p| (WALL_X[0]..WALL_X[1]).contains(&p.x) && (WALL_Y[0]..WALL_Y[1]).contains(&p.y));
    let floor = hit_plane(camera, size, x, y, Vec3::Y, 0.0)
        .filter(|p| (WALL_X[0]..WALL_X[1]).contains(&p.x) && (FLOOR_Z[0]..FLOOR_Z[1]).contains(&p.z));
    match (distance(wall), distance(floor)) {
        (w, f) if w.is_finite() && w < f => Surface::Wall,
        (_, f) if f.is_finite() => Surface::Floor,
        _ => Surface::Other,
    }
}

/// Renders `view` from the default camera and checks every sampled pixel at least 3 pixels
/// inside the wall or floor against the expected colour, within 2/255 per channel.
fn check_view(view: ViewMode, expected_wall: Option<[f32; 3]>, expected_floor: Option<[f32; 3]>) {
    let scene = scene();
    let mut renderer = renderer_for(&scene);
    let size = [320, 240];
    let mut params = default_params(&scene);
    params.shading.view = view;
    let image = render_image(&mut renderer, size, &params).unwrap();
    let mut checked = [0, 0];
    for y in (0..size[1] as i64).step_by(4) {
        for x in (0..size[0] as i64).step_by(4) {
            let surface = surface_at(&params.camera, size, x, y);
            let interior = [(-3, 0), (3, 0), (0, -3), (0, 3)]
                .iter()
                .all(|(dx, dy)| surface_at(&params.camera, size, x + dx, y + dy) == surface);
            let expected = match surface {
                Surface::Wall if interior => expected_wall.map(|e| (e, 0)),
                Surface::Floor if interior => expected_floor.map(|e| (e, 1)),
                _ => None,
            };
            if let Some((expected, which)) = expected {
                let pixel = image.get_pixel(x as u32, y as u32);
                for c in 0..3 {
                    let stored = unit(pixel[c]);
                    assert!(
                        (stored - expected[c]).abs() <= 2.0 / 255.0,
                        "{view:?} {surface:?} at ({x}, {y}): {pixel:?} vs {expected:?}"
                    );
                }
                checked[which] += 1;
            }
        }
    }
    assert!(expected_wall.is_none() || checked[0] > 300, "too few wall pixels: {checked:?}");
    assert!(expected_floor.is_none() || checked[1] > 300, "too few floor pixels: {checked:?}");
}

#[test]
fn wall_tangent_is_plus_x() {
    check_view(ViewMode::Tangent, Some([1.0, 0.5, 0.5]), Some([1.0, 0.5, 0.5]));
}

/// The wall's bitangent points up (+Y); the floor's away from the default camera (−Z).
#[test]
fn bitangent_points_up_the_image() {
    check_view(ViewMode::Bitangent, Some([0.5, 1.0, 0.5]), Some([0.5, 0.5, 0.0]));
}

#[test]
fn geometric_normals_of_wall_and_floor() {
    check_view(ViewMode::Normal, Some([0.5, 0.5, 1.0]), Some([0.5, 1.0, 0.5]));
}

/// Renders the Normal and Shading-normal views of the close wall; returns per-pixel angles
/// (degrees) between them and the matching CPU slope angle of the height field.
fn normal_vs_shading_normal(bump: bool, strength: f32) -> Vec<(f32, f32)> {
    let scene = scene();
    let mut renderer = renderer_for(&scene);
    let size = [256, 256];
    let mut params = close_wall_params(&scene, 0.3);
    params.shading.bump_enabled = bump;
    params.shading.strength = strength;
    params.shading.view = ViewMode::Normal;
    let normal = render_image(&mut renderer, size, &params).unwrap();
    params.shading.view = ViewMode::ShadingNormal;
    let shading = render_image(&mut renderer, size, &params).unwrap();
    let field = brick_height_field(BRICK_TILE_M);
    let mut angles = vec![];
    for y in (0..size[1]).step_by(3) {
        for x in (0..size[0]).step_by(3) {
            let gpu =
                decode_debug(normal.get_pixel(x, y)).angle_between(decode_debug(shading.get_pixel(x, y))).to_degrees();
            let uv = wall_uv(hit_plane(&params.camera, size, x, y, Vec3::Z, WALL_Z).unwrap());
            let texel = (uv * field.width as f32).floor();
            let cpu = field
                .normal(Kernel::CentralDifference, Border::Wrap, texel.x as i64, texel.y as i64)
                .angle_between(Vec3::Z)
                .to_degrees();
            angles.push((gpu, cpu));
        }
    }
    angles
}

#[test]
fn without_bump_the_shading_normal_is_the_normal() {
    for (bump, strength) in [(false, 1.0), (true, 0.0)] {
        for (gpu, _) in normal_vs_shading_normal(bump, strength) {
            // 2/255 per channel of a unit vector is at most about 0.9°.
            assert!(gpu < 1.0, "bump {bump} strength {strength}: {gpu}°");
        }
    }
}

/// Along the mortar edges the shading normal turns by a clear angle; on flat brick faces it
/// stays near the geometric normal.
#[test]
fn with_bump_the_mortar_edges_tilt_the_normal() {
    let angles = normal_vs_shading_normal(true, 1.0);
    let edges: Vec<f32> = angles.iter().filter(|(_, cpu)| *cpu > 25.0).map(|(gpu, _)| *gpu).collect();
    let faces: Vec<f32> = angles.iter().filter(|(_, cpu)| *cpu < 2.0).map(|(gpu, _)| *gpu).collect();
    let mean = |v: &[f32]| v.iter().sum::<f32>() / v.len() as f32;
    println!(
        "edges: {} pixels, mean {:.1}°; faces: {} pixels, mean {:.2}°",
        edges.len(),
        mean(&edges),
        faces.len(),
        mean(&faces)
    );
    assert!(edges.len() > 100 && faces.len() > 100);
    assert!(mean(&edges) > 20.0, "mean tilt on mortar edges {}°", mean(&edges));
    assert!(mean(&faces) < 3.0, "mean tilt on brick faces {}°", mean(&faces));
}

/// The relief points the right way: on the top bevel of a brick the surface falls towards
/// +Y, so the world shading normal leans to +Y, and on the bottom bevel to −Y, as the height
/// field says; a flipped green channel or bitangent would lean every one the other way.
#[test]
fn bevels_lean_the_way_the_height_field_slopes() {
    let scene = scene();
    let mut renderer = renderer_for(&scene);
    let size = [256, 256];
    let mut params = close_wall_params(&scene, 0.3);
    params.shading.view = ViewMode::ShadingNormal;
    let image = render_image(&mut renderer, size, &params).unwrap();
    let field = brick_height_field(BRICK_TILE_M);
    let (mut up, mut down) = (0, 0);
    for y in 0..size[1] {
        for x in (0..size[0]).step_by(2) {
            let uv = wall_uv(hit_plane(&params.camera, size, x, y, Vec3::Z, WALL_Z).unwrap());
            let t = (uv * field.width as f32).floor();
            let cpu = field.normal(Kernel::CentralDifference, Border::Wrap, t.x as i64, t.y as i64);
            if cpu.y.abs() > 0.4 && cpu.x.abs() < 0.1 {
                let gpu = decode_debug(image.get_pixel(x, y));
                if gpu.y * cpu.y > 0.0 { up += 1 } else { down += 1 }
            }
        }
    }
    println!("bevel pixels leaning as the height field says: {up}, against it: {down}");
    assert!(up > 50 && down * 20 < up, "{up} agree, {down} disagree");
}

/// Blinn's bump computed in the shader from the height map (screen-space derivatives, no
/// tangents) agrees with the normal map made from the same heights: on the close wall where
/// the height field is smooth the two shading normals are within a few degrees on average.
/// Screen-space derivatives work per 2×2 pixel quad, so single pixels at mortar edges differ
/// more; the mean and the median are the fair measures.
#[test]
fn height_in_shader_matches_the_normal_map() {
    use bumpview::frame::{BumpSource, SceneOptions};
    let scene = scene();
    let size = [256, 256];
    let mut params = close_wall_params(&scene, 0.3);
    params.shading.view = ViewMode::ShadingNormal;
    let mut renderer = renderer_for(&scene);
    let from_map = render_image(&mut renderer, size, &params).unwrap();
    renderer.set_scene(&scene, SceneOptions { bump_source: BumpSource::HeightInShader, ..Default::default() });
    let from_height = render_image(&mut renderer, size, &params).unwrap();
    let mut angles: Vec<f32> = from_map
        .pixels()
        .zip(from_height.pixels())
        .map(|(a, b)| decode_debug(a).angle_between(decode_debug(b)).to_degrees())
        .collect();
    angles.sort_by(f32::total_cmp);
    let mean = angles.iter().sum::<f32>() / angles.len() as f32;
    let median = angles[angles.len() / 2];
    println!("height-in-shader vs normal map: mean {mean:.2}°, median {median:.2}°");
    assert!(mean < 3.0 && median < 1.5, "mean {mean}°, median {median}°");
    // And it is a bump at all: the shading normal differs from the geometric normal.
    params.shading.view = ViewMode::Normal;
    let geometric = render_image(&mut renderer, size, &params).unwrap();
    let tilted = from_height
        .pixels()
        .zip(geometric.pixels())
        .filter(|(a, b)| decode_debug(a).angle_between(decode_debug(b)) > 0.3)
        .count();
    assert!(tilted > 1000, "{tilted} tilted pixels");
}
