//! Stiff and extreme cases for every tangent method: one named test per case, each with its
//! expected behaviour in its doc comment. Common to all: every frame is finite, `T` is unit
//! and orthogonal to the vertex normal (a non-finite or zero normal counts as +Z, as the
//! methods sanitise it), `w = ±1` — never NaN.

use bumpview::math::normalize_or;
use bumpview::names::Named;
use bumpview::report::stiff::{
    NON_FINITE_VERTICES, away_from, cases, duplicate_positions, grid, mirrored_halves, non_finite_grid, plain_uv,
};
use bumpview::report::surfaces::{Region, uv_sphere};
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

/// Per-face frames are made on the unwelded mesh, whose vertex k is `mesh.indices[k]`: `per_vertex`
/// of `mesh` as the frames of `method` are laid out.
fn as_drawn<T: Copy>(mesh: &Mesh, method: TangentMethod, per_vertex: &[T]) -> Vec<T> {
    if method == TangentMethod::PerFace {
        mesh.indices.iter().map(|&v| per_vertex[v as usize]).collect()
    } else {
        per_vertex.to_vec()
    }
}

/// The exact frame `T = ±X` with `w = ±1`, within 1e-3° (float rounding of unit vectors is
/// far below that).
fn is_exact(t: Vec4, exact: Vec4) -> bool {
    angle_degrees(t.truncate(), exact.truncate()) < 1e-3 && t.w == exact.w
}

fn assert_valid(mesh: &Mesh, case: &str) {
    for method in generated_methods() {
        let (normals, frames) = frames(mesh, method);
        assert_eq!(frames.len(), normals.len(), "{case}, {method:?}");
        for (i, (t, n)) in frames.iter().zip(&normals).enumerate() {
            let n = &normalize_or(*n, Vec3::Z);
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

/// One degenerate UV triangle among good ones: every other vertex keeps its exact frame
/// (+X, w = +1) with every generated method; the degenerate triangle's own corners get a
/// valid fallback.
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
    let degenerate: Vec<bool> = (0..n).map(|v| v + 3 >= n).collect();
    for method in generated_methods() {
        let (_, frames) = frames(&mesh, method);
        let degenerate = as_drawn(&mesh, method, &degenerate);
        let mut checked = 0;
        for (i, t) in frames.iter().enumerate().filter(|(i, _)| !degenerate[*i]) {
            assert!(is_exact(*t, Vec4::new(1.0, 0.0, 0.0, 1.0)), "{method:?}, vertex {i}: {t}");
            checked += 1;
        }
        assert!(checked >= frames.len() - 3, "{method:?}: {checked} of {} vertices", frames.len());
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
/// there are valid. Away from the poles (the sphere's own regions) every method is near the
/// exact frame: in the interior the smooth methods within 1° (area weighting is the loosest,
/// 0.82°: its north and south faces differ in area, so their tilts do not cancel; MikkTSpace,
/// uniform and angle weighting 1e-5°) and the flat per-face frames within half a cell (a face
/// frame is the direction of its chord, the exact tangent half a cell away: measured 5.2°,
/// bound 5.625°); on the seam columns, whose copies each see the faces on one side only,
/// every method within half a cell too.
#[test]
fn uv_sphere_poles_give_valid_frames_and_exact_ones_away_from_them() {
    let (segments, rings) = (32, 16);
    let sphere = uv_sphere(segments, rings);
    assert_valid(&sphere.mesh, "UV sphere 32×16");
    let half_cell = 180.0 / segments as f32;
    for method in generated_methods() {
        let (normals, frames) = frames(&sphere.mesh, method);
        let exact = as_drawn(&sphere.mesh, method, sphere.mesh.analytic_tangents.as_ref().unwrap());
        let regions = as_drawn(&sphere.mesh, method, &sphere.regions);
        let mut worst = [0.0f32; 2];
        for (((t, e), n), region) in frames.iter().zip(&exact).zip(&normals).zip(&regions) {
            let error =
                angle_degrees(t.truncate(), e.truncate()).max(angle_degrees(bitangent(*n, *t), bitangent(*n, *e)));
            match region {
                Region::Interior => worst[0] = worst[0].max(error),
                Region::Seam => worst[1] = worst[1].max(error),
                _ => {}
            }
        }
        println!("{method:?}: worst error interior {:.5}°, seams {:.3}°", worst[0], worst[1]);
        let interior_bound = if method == TangentMethod::PerFace { half_cell } else { 1.0 };
        assert!(worst[0] < interior_bound, "{method:?}: {}° in the interior", worst[0]);
        assert!(worst[1] < half_cell, "{method:?}: {}° on the seams", worst[1]);
    }
    let counted = |r| sphere.regions.iter().filter(|&&x| x == r).count();
    assert!(counted(Region::Interior) > 300 && counted(Region::Seam) > 20, "the regions hold vertices");
}

/// Duplicate positions: two overlapping copies of a grid, the second with u mirrored, so
/// its exact frame is T = −X, w = −1 against the first's +X, w = +1. Each copy keeps its own
/// exact frame; a method that merged coincident vertices would give both the same one.
#[test]
fn duplicate_positions_keep_their_own_frames() {
    let mesh = duplicate_positions();
    assert_valid(&mesh, "duplicate positions");
    let half = mesh.positions.len() / 2;
    assert_eq!(mesh.positions[..half], mesh.positions[half..], "the copies coincide");
    let exact = mesh.analytic_tangents.clone().unwrap();
    assert!(
        exact[..half].iter().all(|e| e.x == 1.0 && e.w == 1.0)
            && exact[half..].iter().all(|e| e.x == -1.0 && e.w == -1.0)
    );
    for method in generated_methods() {
        let (_, frames) = frames(&mesh, method);
        let exact = as_drawn(&mesh, method, &exact);
        let mirrored = frames.iter().zip(&exact).filter(|(_, e)| e.w < 0.0).count();
        assert_eq!(2 * mirrored, frames.len(), "{method:?}: half the frames belong to the mirrored copy");
        for (i, (t, e)) in frames.iter().zip(&exact).enumerate() {
            assert!(is_exact(*t, *e), "{method:?}, vertex {i}: {t}, exact {e}");
        }
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

/// NaN or infinity in positions, normals or UVs of some vertices: every frame is finite,
/// unit, orthogonal to the sanitised normal (a NaN normal counts as +Z) with w = ±1, and the
/// vertices away from the bad ones (in no triangle that uses one) keep their exact frame +X,
/// w = +1 (loaders reject such data first; this is the last line of defence).
#[test]
fn non_finite_input_gives_valid_frames_and_keeps_the_rest_exact() {
    let mesh = non_finite_grid();
    assert_valid(&mesh, "NaN / Inf");
    let away = away_from(&mesh, &NON_FINITE_VERTICES);
    let held = away.iter().filter(|&&a| a).count();
    // 49 vertices; each bad vertex and its six neighbours are left out, 21 at most.
    assert!(held >= 28, "{held} vertices away from the bad ones");
    for method in generated_methods() {
        let (_, frames) = frames(&mesh, method);
        let away = as_drawn(&mesh, method, &away);
        for (i, t) in frames.iter().enumerate().filter(|(i, _)| away[*i]) {
            assert!(is_exact(*t, Vec4::new(1.0, 0.0, 0.0, 1.0)), "{method:?}, vertex {i}: {t}");
        }
    }
}
