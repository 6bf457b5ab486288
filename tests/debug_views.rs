//! The TBN debug views: each shows a world-space unit vector v as the stored colour 0.5·v + 0.5.

mod common;

use bumpview::frame::ViewMode;
use bumpview::height::{Border, Kernel};
use bumpview::render::capture::{render_float, render_image};
use bumpview::scene::bricks::{BEVEL_WIDTH, BRICKS_PER_ROW, MORTAR_HALF_WIDTH, ROWS, TILE_TEXELS, brick_height_field};
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

/// One sampled pixel of the close wall: the angle (degrees) between the rendered Normal and
/// Shading-normal views, the tilt of the height field's own central-difference normal at the
/// pixel's texel, and the tilt of the CPU chain's shading normal there ([`wall_lighting_inputs`]:
/// the normal map sampled bilinearly, perturbed with the strength, as src/shading.rs does).
struct Tilt {
    gpu: f32,
    field: f32,
    cpu: f32,
}

/// Renders the Normal and Shading-normal views of the close wall; returns [`Tilt`]s on a grid.
fn normal_vs_shading_normal(bump: bool, strength: f32) -> Vec<Tilt> {
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
    let mut tilts = vec![];
    for y in (0..size[1]).step_by(3) {
        for x in (0..size[0]).step_by(3) {
            let gpu =
                decode_debug(normal.get_pixel(x, y)).angle_between(decode_debug(shading.get_pixel(x, y))).to_degrees();
            let uv = wall_uv(hit_plane(&params.camera, size, x, y, Vec3::Z, WALL_Z).unwrap());
            let texel = (uv * field.width as f32).floor();
            let field = field
                .normal(Kernel::CentralDifference, Border::Wrap, texel.x as i64, texel.y as i64)
                .angle_between(Vec3::Z)
                .to_degrees();
            let cpu = wall_chain(&scene, &params, size, x, y).shading_normal.angle_between(Vec3::Z).to_degrees();
            tilts.push(Tilt { gpu, field, cpu });
        }
    }
    tilts
}

#[test]
fn without_bump_the_shading_normal_is_the_normal() {
    for (bump, strength) in [(false, 1.0), (true, 0.0)] {
        for Tilt { gpu, .. } in normal_vs_shading_normal(bump, strength) {
            // 2/255 per channel of a unit vector is at most about 0.9°.
            assert!(gpu < 1.0, "bump {bump} strength {strength}: {gpu}°");
        }
    }
}

/// Along the mortar edges (pixels whose texel's height-field normal tilts by over 25°) the
/// shading normal tilts as much as the CPU chain says at those same pixels: the GPU's mean
/// within 1° of the CPU's. Why 1°: both read the same 8-bit normal map bilinearly; the GPU
/// stores the result in 8 bits (up to about 0.9° per pixel, half that on average) and filters
/// with 8-bit weights; a mean over hundreds of pixels averages the rounding. Measured: 40.42° both, over 1210
/// pixels (with the shader's strength halved the GPU gives 23.3°).
/// Half the bump strength tilts the edges about half as much and is far outside. On flat brick
/// faces the shading normal stays near the geometric normal.
#[test]
fn with_bump_the_mortar_edges_tilt_the_normal() {
    let tilts = normal_vs_shading_normal(true, 1.0);
    let edges: Vec<&Tilt> = tilts.iter().filter(|t| t.field > 25.0).collect();
    let faces: Vec<&Tilt> = tilts.iter().filter(|t| t.field < 2.0).collect();
    let mean = |v: &[&Tilt], f: fn(&Tilt) -> f32| v.iter().map(|t| f(t)).sum::<f32>() / v.len() as f32;
    let (gpu, cpu) = (mean(&edges, |t| t.gpu), mean(&edges, |t| t.cpu));
    println!(
        "edges: {} pixels, mean tilt GPU {gpu:.3}°, CPU {cpu:.3}°; faces: {} pixels, mean GPU {:.2}°, CPU {:.2}°",
        edges.len(),
        faces.len(),
        mean(&faces, |t| t.gpu),
        mean(&faces, |t| t.cpu),
    );
    assert!(edges.len() > 100 && faces.len() > 100);
    assert!(cpu > 30.0, "the CPU chain's mean tilt on mortar edges is {cpu}°");
    assert!((gpu - cpu).abs() < 1.0, "mean tilt on mortar edges: GPU {gpu}°, CPU {cpu}°");
    assert!(mean(&faces, |t| t.gpu) < 3.0, "mean tilt on brick faces {}°", mean(&faces, |t| t.gpu));
}

/// Where a point of the brick tile lies (continuous texel coordinates, y down the image), from
/// the layout the tile is made with (src/scene/bricks.rs): the distance to the nearest joint
/// centre line beside it (left or right) and the unit direction towards it in tangent space
/// (x right, y up the image), then the same for the nearest joint above or below it.
fn joints(tx: f32, ty: f32) -> [(f32, Vec2); 2] {
    let tile = TILE_TEXELS as f32;
    let (brick_w, brick_h) = (tile / BRICKS_PER_ROW as f32, tile / ROWS as f32);
    let (tx, ty) = (tx.rem_euclid(tile), ty.rem_euclid(tile));
    let row = (ty / brick_h).floor();
    let shifted = (tx + if row as u32 % 2 == 1 { brick_w * 0.5 } else { 0.0 }).rem_euclid(tile);
    let lx = shifted - (shifted / brick_w).floor() * brick_w;
    let ly = ty - row * brick_h;
    // Towards the left joint is −x; towards the joint above (smaller rows) is +y.
    let beside = if lx < brick_w - lx { (lx, -Vec2::X) } else { (brick_w - lx, Vec2::X) };
    let above_below = if ly < brick_h - ly { (ly, Vec2::Y) } else { (brick_h - ly, -Vec2::Y) };
    [beside, above_below]
}

/// The relief points the right way and as steeply as the height field's analytic profile:
/// the tile's height is `mortar + (face − mortar)·smoothstep(M, M + W, d)` with `d` the
/// distance to the nearest joint, `M` the mortar half width and `W` the bevel width, so on a
/// bevel the surface falls towards the joint and the shading normal leans towards it, in x
/// on the bevels beside vertical joints and in y beside horizontal ones. Checked on every
/// pixel of the close wall (float target, Shading-normal view) on a bevel more than a texel in
/// from either end of it (there the analytic slope is at least 20% of its peak; at the ends
/// it falls to nothing and bilinear filtering blends in the flat mortar or face), and not
/// within 2 texels of a corner's ridge, where the two bevels meet and the kernel's and the
/// filter's texels straddle both:
///
/// - no such pixel leans the wrong way;
/// - away from corners (the other joint beyond the bevel), the shading normal's tangent-space
///   x and y against the analytic normal `normalize(−s·∂h/∂x, −s·∂h/∂y_up, 1)`, with `face`
///   and `mortar` read from the height field a texel past each end of the bevel: within 0.1 at
///   every pixel (measured: median 0.027, 95th percentile 0.046, max 0.062). What separates
///   them: central differences of a smoothstep 6 texels wide are off by up to 4% of its peak
///   slope, bilinear filtering between texel centres by about 2%, the face's noise and tilt
///   (left out of the profile) by 1–2%, the 8-bit encoding of the map by 0.004.
///
/// A flipped green channel or bitangent leans every horizontal bevel the wrong way, a
/// flipped tangent every vertical one.
#[test]
fn bevels_lean_the_way_the_height_field_slopes() {
    let scene = scene();
    let mut renderer = renderer_for(&scene);
    let size = [256, 256];
    let mut params = close_wall_params(&scene, 0.3);
    params.shading.view = ViewMode::ShadingNormal;
    let image = render_float(&mut renderer, size, &params).unwrap();
    let field = brick_height_field(BRICK_TILE_M);
    // Metres of height per unit sample over metres per texel: the slope of one sample per texel.
    let s = field.range_m / field.texel_size_m;
    let level = |tx: f32, ty: f32| field.at(tx.floor() as i64, ty.floor() as i64);
    let (start, end) = (MORTAR_HALF_WIDTH, MORTAR_HALF_WIDTH + BEVEL_WIDTH);
    let (mut checked, mut wrong, mut errors) = ([0usize; 2], vec![], [vec![], vec![]]);
    for y in 0..size[1] {
        for x in 0..size[0] {
            let uv = wall_uv(hit_plane(&params.camera, size, x, y, Vec3::Z, WALL_Z).unwrap());
            let (tx, ty) = (uv.x * TILE_TEXELS as f32, uv.y * TILE_TEXELS as f32);
            let [beside, above_below] = joints(tx, ty);
            let axis = (above_below.0 < beside.0) as usize; // 0: a vertical joint (lean in x), 1: horizontal (in y)
            let ((d, towards), other) = if axis == 0 { (beside, above_below.0) } else { (above_below, beside.0) };
            if !(start + 1.0..=end - 1.0).contains(&d) || other - d < 2.0 {
                continue;
            }
            let p = image.pixels[(y * size[0] + x) as usize];
            let gpu = (Vec3::new(p[0], p[1], p[2]) * 2.0 - 1.0).normalize();
            checked[axis] += 1;
            let along = if axis == 0 { gpu.x * towards.x } else { gpu.y * towards.y };
            if along <= 0.0 {
                wrong.push((x, y, d, gpu));
            }
            if other <= end + 1.0 {
                continue; // a corner: the face sample below would lie on the other bevel
            }
            // Texel steps (y down) towards the joint and away from it.
            let step = Vec2::new(towards.x, -towards.y);
            let mortar = level(tx + step.x * (d - start + 1.0), ty + step.y * (d - start + 1.0));
            let face = level(tx - step.x * (end + 1.0 - d), ty - step.y * (end + 1.0 - d));
            let t = (d - start) / BEVEL_WIDTH;
            // dh/dd in samples per texel: the derivative of smoothstep. The height rises away
            // from the joint, so the normal leans towards it.
            let lean = towards * (face - mortar) * 6.0 * t * (1.0 - t) / BEVEL_WIDTH * s;
            let analytic = Vec3::new(lean.x, lean.y, 1.0).normalize();
            errors[axis].push((gpu.x - analytic.x).abs().max((gpu.y - analytic.y).abs()));
        }
    }
    for e in &mut errors {
        e.sort_by(f32::total_cmp);
    }
    let stats = |e: &[f32]| (percentile(e, 0.5), percentile(e, 0.95), e[e.len() - 1]);
    let (x_bevels, y_bevels) = (stats(&errors[0]), stats(&errors[1]));
    println!(
        "bevel pixels: {} beside vertical joints, {} beside horizontal ones; {} lean the wrong way; \
         max(|Δx|, |Δy|) against the analytic normal (p50, p95, max) on {} and {} of them: {x_bevels:?}, {y_bevels:?}",
        checked[0],
        checked[1],
        wrong.len(),
        errors[0].len(),
        errors[1].len()
    );
    assert!(checked.iter().all(|&n| n > 300), "{checked:?} bevel pixels");
    assert!(wrong.is_empty(), "{} pixels lean the wrong way, e.g. {:?}", wrong.len(), &wrong[..wrong.len().min(5)]);
    assert!(
        errors.iter().all(|e| e.len() > 300),
        "{} and {} pixels away from corners",
        errors[0].len(),
        errors[1].len()
    );
    for (what, (_, _, max)) in [("vertical", x_bevels), ("horizontal", y_bevels)] {
        assert!(max < 0.1, "bevels beside {what} joints: the shading normal is up to {max} off the analytic one");
    }
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
