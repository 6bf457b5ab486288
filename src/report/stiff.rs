//! Stiff and extreme cases for tangent frames, each a small mesh with the exact frame where
//! one exists: the stability table of the report, and the meshes tests/stiff_tangents.rs uses.

use glam::{Mat4, Vec2, Vec3, Vec4};

use super::surfaces::uv_sphere;
use crate::names::Named;
use crate::scene::Mesh;
use crate::tangent::{TangentMethod, angle_degrees, tangents};

/// A `cells × cells` grid on the unit square in the XY plane facing +Z; `uv` maps a position
/// to its texture coordinates (v down the image).
pub fn grid(cells: u32, uv: impl Fn(Vec3) -> Vec2) -> Mesh {
    let mut mesh = Mesh::empty("grid");
    for j in 0..=cells {
        for i in 0..=cells {
            let p = Vec3::new(i as f32 / cells as f32, j as f32 / cells as f32, 0.0);
            mesh.positions.push(p);
            mesh.normals.push(Vec3::Z);
            mesh.uvs.push(uv(p));
        }
    }
    let stride = cells + 1;
    for j in 0..cells {
        for i in 0..cells {
            let a = j * stride + i;
            mesh.indices.extend([a, a + 1, a + stride + 1, a, a + stride + 1, a + stride]);
        }
    }
    mesh.analytic_tangents = Some(vec![Vec4::new(1.0, 0.0, 0.0, 1.0); mesh.positions.len()]);
    mesh
}

/// UVs with u along +X and the image's up along +Y.
pub fn plain_uv(p: Vec3) -> Vec2 {
    Vec2::new(p.x, 1.0 - p.y)
}

/// `b` appended to `a` (indices shifted).
pub fn merged(mut a: Mesh, b: &Mesh) -> Mesh {
    let offset = a.positions.len() as u32;
    a.positions.extend(&b.positions);
    a.normals.extend(&b.normals);
    a.uvs.extend(&b.uvs);
    a.indices.extend(b.indices.iter().map(|i| i + offset));
    if let (Some(frames), Some(more)) = (a.analytic_tangents.as_mut(), b.analytic_tangents.as_ref()) {
        frames.extend(more);
    }
    a
}

/// A 1×1 square whose right half has u mirrored (vertices split at x = 0.5): the exact frame
/// is T = +X, w = +1 on the left and T = −X, w = −1 on the right; B is +Y on both.
pub fn mirrored_halves() -> Mesh {
    let mut left = grid(2, |p| Vec2::new(p.x * 0.5, 1.0 - p.y));
    left.positions.iter_mut().for_each(|p| p.x *= 0.5);
    let mut right = grid(2, |p| Vec2::new(0.5 - p.x * 0.5, 1.0 - p.y));
    right.positions.iter_mut().for_each(|p| p.x = 0.5 + p.x * 0.5);
    right.analytic_tangents = Some(vec![Vec4::new(-1.0, 0.0, 0.0, -1.0); right.positions.len()]);
    merged(left, &right)
}

/// One stiff case: a mesh, and whether its `analytic_tangents` are the exact answer.
pub struct StiffCase {
    pub name: &'static str,
    pub mesh: Mesh,
    /// The analytic frames are exact; otherwise no frame exists and only validity counts.
    pub has_reference: bool,
}

/// The cases of the stability table.
pub fn cases() -> Vec<StiffCase> {
    let case = |name, mesh, has_reference| StiffCase { name, mesh, has_reference };
    let scaled = |scale: f32| {
        let mut sphere = uv_sphere(24, 12).mesh;
        let m = Mat4::from_scale(Vec3::splat(scale));
        sphere.positions.iter_mut().for_each(|p| *p = m.transform_point3(*p));
        sphere
    };
    let duplicate = {
        let a = grid(3, plain_uv);
        let mut b = a.clone();
        b.uvs.iter_mut().for_each(|uv| *uv += Vec2::new(0.25, 0.0));
        merged(a, &b)
    };
    let zero_area = {
        let mut mesh = grid(2, plain_uv);
        let n = mesh.positions.len() as u32;
        for uv in [Vec2::new(0.0, 0.0), Vec2::new(1.0, 0.0), Vec2::new(0.0, 1.0)] {
            mesh.positions.push(Vec3::new(0.5, 0.5, 0.0));
            mesh.normals.push(Vec3::Z);
            mesh.uvs.push(uv);
            mesh.analytic_tangents.as_mut().expect("grid has frames").push(Vec4::new(1.0, 0.0, 0.0, 1.0));
        }
        mesh.indices.extend([n, n + 1, n + 2]);
        mesh
    };
    let non_finite = {
        let mut mesh = grid(3, plain_uv);
        mesh.positions[5] = Vec3::new(f32::NAN, 0.0, 0.0);
        mesh.uvs[6] = Vec2::new(f32::INFINITY, 0.0);
        mesh.normals[7] = Vec3::NAN;
        mesh
    };
    vec![
        case("zero-area UV triangles", grid(4, |_| Vec2::splat(0.3)), false),
        case("collinear UVs", grid(4, |p| Vec2::splat(p.x + p.y)), false),
        case("mirrored UVs", mirrored_halves(), true),
        case("UV sphere poles (32×16)", uv_sphere(32, 16).mesh, true),
        case("duplicate positions", duplicate, true),
        case("zero area in space, not in UV", zero_area, true),
        case("scaled by 1e-6", scaled(1e-6), true),
        case("scaled by 1e6", scaled(1e6), true),
        case("NaN / Inf in position, UV, normal", non_finite, true),
    ]
}

/// One row of the stability table.
#[derive(Debug, Clone, PartialEq)]
pub struct StabilityRow {
    pub case: &'static str,
    pub method: &'static str,
    /// Frames with a NaN or infinite component.
    pub non_finite: usize,
    /// Frames that are not unit or not orthogonal to their normal (beyond 1e-4).
    pub invalid: usize,
    /// Largest angle between T (and B) and the exact frame, degrees; `None` where no exact
    /// frame exists.
    pub max_error_deg: Option<f32>,
}

/// Every generated method on every case.
pub fn stability_rows() -> Vec<StabilityRow> {
    let mut rows = vec![];
    for case in cases() {
        for &method in TangentMethod::all().iter().filter(|m| m.is_generated()) {
            let mesh = if method == TangentMethod::PerFace { case.mesh.unwelded() } else { case.mesh.clone() };
            let frames = tangents(&mesh, method).expect("generated methods always answer");
            let non_finite = frames.iter().filter(|t| !t.is_finite()).count();
            let invalid = frames
                .iter()
                .zip(&mesh.normals)
                .filter(|(t, n)| {
                    let n = n.normalize_or(Vec3::Z);
                    (t.truncate().length() - 1.0).abs() > 1e-4 || t.truncate().dot(n).abs() > 1e-4
                })
                .count();
            let max_error_deg = case.has_reference.then(|| {
                let exact = mesh.analytic_tangents.as_ref().expect("reference cases carry frames");
                frames
                    .iter()
                    .zip(exact)
                    .zip(&mesh.normals)
                    .map(|((t, e), n)| {
                        let b = |f: &Vec4| f.w.signum() * n.cross(f.truncate());
                        angle_degrees(t.truncate(), e.truncate()).max(angle_degrees(b(t), b(e)))
                    })
                    .fold(0.0f32, |worst, a| if a.is_nan() { f32::INFINITY } else { worst.max(a) })
            });
            rows.push(StabilityRow { case: case.name, method: method.name(), non_finite, invalid, max_error_deg });
        }
    }
    rows
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_case_gives_finite_frames_with_every_method() {
        let rows = stability_rows();
        assert!(rows.iter().all(|r| r.non_finite == 0), "{rows:#?}");
        // Where an exact frame exists and the input is sane, the methods find it.
        for r in rows.iter().filter(|r| r.case == "mirrored UVs" || r.case == "duplicate positions") {
            assert!(r.max_error_deg.unwrap() < 1e-3, "{r:?}");
        }
    }
}
