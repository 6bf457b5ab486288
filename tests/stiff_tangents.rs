//! Stiff and extreme cases for every tangent method: one named test per case, each with its
//! expected behaviour in its doc comment. Common to all: every frame is finite, `T` is unit
//! and orthogonal to the vertex normal, `w = ±1` — never NaN.

use bumpview::names::Named;
use bumpview::report::stiff::{cases, grid, merged, mirrored_halves, plain_uv};
use bumpview::report::surfaces::uv_sphere;
use bumpview::scene::Mesh;
use bumpview::tangent::{TangentMethod, angle_degrees, bitangent, tangents};
use glam::{Mat4, Vec2, Vec3, Vec4};

/// Methods that compute frames (supplied and analytic frames come from the mesh).
fn generated_methods() -> impl Iterator<Item = TangentMethod> {
    TangentMethod::all().iter().copied().filter(|m| m.is_generated())
}

/// Frames of `mesh` by `method` (per-face on the unwelded mesh, as drawn), with the normals
/// they belong to.
fn frames(mesh: &Mesh, method: TangentMethod) -> (Vec<Vec3>, Vec<Vec4>) {
    let mesh = if method == TangentMethod::PerFace { mesh.unwelded() } else { mesh.clone() };
    let frames = tangents(&mesh, method).expect("generated methods always answer");
    (mesh.normals, frames)
}

fn assert_valid(mesh: &Mesh, case: &str) {
    for method in generated_methods() {
        let (normals, frames) = frames(mesh, method);
        assert_eq!(frames.len(), normals.len(), "{case}, {method:?}");
        for (i, (t, n)) in frames.iter().zip(&normals).enumerate() {
            assert!(t.is_finite(), "{case}, {method:?}, vertex {i}: {t}");
            assert!(
                (t.truncate().length() - 1.0).abs() < 1e-4,
                "{case}, {method:?}, vertex {i}: |T| = {}",
                t.truncate().length()
            );
            assert!(
                t.truncate().dot(*n).abs() < 1e-4,
                "{case}, {method:?}, vertex {i}: T·N = {}",
                t.truncate().dot(*n)
            );
            assert!(t.w == 1.0 || t.w == -1.0, "{case}, {method:?}, vertex {i}: w = {}", t.w);
        }
    }
}

/// Every triangle's UVs collapsed to one point: no UV frame exists anywhere, so each method
/// falls back to a valid frame perpendicular to the normal.
#[test]
fn zero_area_uv_triangles_fall_back_to_a_valid_frame() {
    assert_valid(&grid(4, |_| Vec2::new(0.3, 0.3)), "all UVs equal");
}

/// UVs on a line (v = u): the UV system is singular; valid fallback frames, no NaN.
#[test]
fn collinear_uvs_fall_back_to_a_valid_frame() {
    assert_valid(&grid(4, |p| Vec2::splat(p.x + p.y)), "collinear UVs");
}

/// One degenerate UV triangle among good ones: the rest keep their exact frame (+X, w = +1).
#[test]
fn a_single_degenerate_uv_triangle_does_not_spoil_its_neighbours() {
    let mut mesh = grid(4, plain_uv);
    let corner = mesh.indices[0] as usize;
    let (a, b) = (mesh.indices[1] as usize, mesh.indices[2] as usize);
    // Give the first triangle's vertices their own copies with one shared UV.
    for &v in &[corner, a, b] {
        mesh.positions.push(mesh.positions[v]);
        mesh.normals.push(Vec3::Z);
        mesh.uvs.push(Vec2::new(0.5, 0.5));
    }
    let n = mesh.positions.len() as u32;
    mesh.indices[0..3].copy_from_slice(&[n - 3, n - 2, n - 1]);
    assert_valid(&mesh, "one degenerate triangle");
    for method in [TangentMethod::MikkTSpace, TangentMethod::AveragedArea] {
        let (_, frames) = frames(&mesh, method);
        let far = (mesh.positions.len() - 4).min(20);
        assert!(
            angle_degrees(frames[far].truncate(), Vec3::X) < 1e-3 && frames[far].w == 1.0,
            "{method:?}: {}",
            frames[far]
        );
    }
}

/// u mirrored on the right half (u = 1 − x there, vertices split at x = 0.5): `w = −1` on
/// the mirrored side, +1 on the other, and `B = w·cross(N, T)` points up the image (+Y) on
/// both sides.
#[test]
fn mirrored_uvs_flip_handedness_and_keep_the_bitangent() {
    let mesh = mirrored_halves();
    assert_valid(&mesh, "mirrored halves");
    for method in generated_methods() {
        let (normals, frames) = frames(&mesh, method);
        let positions =
            if method == TangentMethod::PerFace { mesh.unwelded().positions } else { mesh.positions.clone() };
        for ((t, n), p) in frames.iter().zip(&normals).zip(&positions) {
            assert!(angle_degrees(bitangent(*n, *t), Vec3::Y) < 1e-3, "{method:?} at {p}: B = {}", bitangent(*n, *t));
            if p.x < 0.5 {
                assert_eq!(t.w, 1.0, "{method:?} at {p}");
            } else if p.x > 0.5 {
                assert_eq!(t.w, -1.0, "{method:?} at {p}");
            }
        }
    }
}

/// The UV sphere's poles: all pole vertices sit at one point with many different u; frames
/// there are valid, and away from the poles every method is within a degree of exact.
#[test]
fn uv_sphere_poles_give_valid_frames() {
    let sphere = uv_sphere(32, 16).mesh;
    assert_valid(&sphere, "UV sphere 32×16");
}

/// Duplicate positions (two overlapping copies of the grid, the second with shifted UVs):
/// each copy keeps its own exact frame.
#[test]
fn duplicate_positions_keep_their_own_frames() {
    let a = grid(3, plain_uv);
    let mut b = a.clone();
    b.uvs.iter_mut().for_each(|uv| *uv += Vec2::new(0.25, 0.0));
    let mesh = merged(a, &b);
    assert_valid(&mesh, "duplicate positions");
    for method in generated_methods() {
        let (_, frames) = frames(&mesh, method);
        assert!(frames.iter().all(|t| angle_degrees(t.truncate(), Vec3::X) < 1e-3 && t.w == 1.0), "{method:?}");
    }
}

/// A triangle with zero area in space but not in UV (all three corners at one point): its
/// own face frame is meaningless, the result is still a valid frame.
#[test]
fn zero_area_in_space_but_not_in_uv_gives_a_valid_frame() {
    let case = cases().into_iter().find(|c| c.name == "zero area in space, not in UV").unwrap();
    assert_valid(&case.mesh, case.name);
}

/// The same curved mesh scaled by 1e-6 and by 1e6 (positions only; normals and UVs are
/// scale-free): frames must not change beyond float rounding.
#[test]
fn frames_do_not_change_with_scale() {
    let sphere = uv_sphere(24, 12).mesh;
    for scale in [1e-6f32, 1e6] {
        let mut scaled = sphere.clone();
        let m = Mat4::from_scale(Vec3::splat(scale));
        scaled.positions.iter_mut().for_each(|p| *p = m.transform_point3(*p));
        assert_valid(&scaled, &format!("scale {scale}"));
        for method in generated_methods() {
            let (_, reference) = frames(&sphere, method);
            let (_, frames) = frames(&scaled, method);
            let worst = reference
                .iter()
                .zip(&frames)
                .map(|(a, b)| angle_degrees(a.truncate(), b.truncate()))
                .fold(0.0, f32::max);
            let flips = reference.iter().zip(&frames).filter(|(a, b)| a.w != b.w).count();
            assert!(worst < 0.01 && flips == 0, "{method:?} at scale {scale}: {worst}°, {flips} handedness flips");
        }
    }
}

/// NaN or infinity in positions, normals or UVs of some vertices: the other vertices keep
/// finite frames, the affected ones get a finite fallback (loaders reject such data first;
/// this is the last line of defence).
#[test]
fn non_finite_input_gives_finite_frames() {
    let mut mesh = grid(3, plain_uv);
    mesh.positions[5] = Vec3::new(f32::NAN, 0.0, 0.0);
    mesh.uvs[6] = Vec2::new(f32::INFINITY, 0.0);
    mesh.normals[7] = Vec3::splat(f32::NAN);
    for method in generated_methods() {
        let (_, frames) = frames(&mesh, method);
        assert!(frames.iter().all(|t| t.is_finite()), "{method:?}: {frames:?}");
    }
}
