//! The classic tangent frame of a triangle from its edges and UV deltas (Lengyel), and
//! per-vertex averages of it.
//!
//! For a triangle with edges `e1 = p1 − p0`, `e2 = p2 − p0` and UV deltas `(Δu, Δv)` (with v
//! measured *up* the image, crate conventions), the 2×2 system `e = Δu·T + Δv·B` gives
//! `T = (e1·Δv2 − e2·Δv1) / det` and `B = (e2·Δu1 − e1·Δu2) / det`, `det = Δu1·Δv2 − Δu2·Δv1`.

use glam::{Vec3, Vec4};

use crate::math::{any_perpendicular, normalize_or, orthonormalize_tangent};
use crate::scene::Mesh;

/// A UV triangle counts as degenerate when `|det|` is below this fraction of the product of
/// its UV extents: a relative test, so scaling the UVs (or the mesh) changes nothing.
const RELATIVE_UV_EPSILON: f32 = 1e-6;

/// How face frames are weighted when averaged at a vertex.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Weighting {
    /// Every face counts the same.
    Uniform,
    /// Faces count by their area.
    Area,
    /// Faces count by the corner angle at the vertex.
    Angle,
}

/// The frame of one triangle as `(T, B)`, both unit; `None` when its UVs (relatively) or its
/// positions are degenerate.
pub fn face_frame(p: [Vec3; 3], uv: [glam::Vec2; 3]) -> Option<(Vec3, Vec3)> {
    let (e1, e2) = (p[1] - p[0], p[2] - p[0]);
    // v up the image: flip the stored v (which runs down).
    let (du1, dv1) = (uv[1].x - uv[0].x, uv[0].y - uv[1].y);
    let (du2, dv2) = (uv[2].x - uv[0].x, uv[0].y - uv[2].y);
    let det = du1 * dv2 - du2 * dv1;
    let scale = (du1.abs() + du2.abs()) * (dv1.abs() + dv2.abs());
    if !det.is_finite() || det.abs() <= RELATIVE_UV_EPSILON * scale {
        return None;
    }
    let t = normalize_or((e1 * dv2 - e2 * dv1) / det, Vec3::ZERO);
    let b = normalize_or((e2 * du1 - e1 * du2) / det, Vec3::ZERO);
    (t != Vec3::ZERO && b != Vec3::ZERO).then_some((t, b))
}

fn corners(mesh: &Mesh, triangle: &[u32]) -> ([Vec3; 3], [glam::Vec2; 3]) {
    let p = [0, 1, 2].map(|k| mesh.positions[triangle[k] as usize]);
    let uv = [0, 1, 2].map(|k| mesh.uvs.get(triangle[k] as usize).copied().unwrap_or_default());
    (p, uv)
}

/// One frame per triangle, as `(T, w)` with `T` unit and orthogonal to the face normal and
/// `w = sign(dot(cross(N_face, T), B))`. Degenerate triangles get a valid fallback frame
/// perpendicular to their normal with `w = +1`.
pub fn per_face_frames(mesh: &Mesh) -> Vec<Vec4> {
    mesh.indices
        .chunks_exact(3)
        .map(|triangle| {
            let (p, uv) = corners(mesh, triangle);
            let face_normal = normalize_or((p[1] - p[0]).cross(p[2] - p[0]), mesh.normals[triangle[0] as usize]);
            match face_frame(p, uv) {
                Some((t, b)) => {
                    let t = orthonormalize_tangent(t, face_normal);
                    let w = if face_normal.cross(t).dot(b) < 0.0 { -1.0 } else { 1.0 };
                    t.extend(w)
                }
                None => any_perpendicular(face_normal).extend(1.0),
            }
        })
        .collect()
}

/// Corner angle at `p[k]`, radians.
fn corner_angle(p: [Vec3; 3], k: usize) -> f32 {
    let (a, b) = (p[(k + 1) % 3] - p[k], p[(k + 2) % 3] - p[k]);
    a.angle_between(b)
}

/// Face frames summed at each vertex with `weighting`, then Gram-Schmidt against the vertex
/// normal and `w = sign(dot(cross(N, T), ΣB))`. Vertices with no usable face get a valid
/// fallback frame with `w = +1`.
pub fn averaged_face_frames(mesh: &Mesh, weighting: Weighting) -> Vec<Vec4> {
    frames_from_sums(mesh, weighting, orthonormalize_tangent)
}

/// As [`averaged_face_frames`] without Gram-Schmidt: each vertex's averaged `T` only
/// normalised (not made orthogonal to its normal), `w` as there. The classic mistake
/// [`crate::frame::Mistake::NoGramSchmidt`] draws these.
pub fn averaged_face_frames_without_gram_schmidt(mesh: &Mesh, weighting: Weighting) -> Vec<Vec4> {
    frames_from_sums(mesh, weighting, |t, n| crate::math::normalize_or(t, crate::math::any_perpendicular(n)))
}

/// The averaged frames: `T = tangent(ΣT, N)` at each vertex and `w = sign(dot(cross(N, T), ΣB))`.
fn frames_from_sums(mesh: &Mesh, weighting: Weighting, tangent: impl Fn(Vec3, Vec3) -> Vec3) -> Vec<Vec4> {
    let (sum_t, sum_b) = averaged_sums(mesh, weighting);
    sum_t
        .iter()
        .zip(&sum_b)
        .zip(&mesh.normals)
        .map(|((&t, &b), &n)| {
            let t = tangent(t, n);
            let w = if n.cross(t).dot(b) < 0.0 { -1.0 } else { 1.0 };
            t.extend(w)
        })
        .collect()
}

/// Per vertex, the weighted sums of the face frames' `T` and `B`.
fn averaged_sums(mesh: &Mesh, weighting: Weighting) -> (Vec<Vec3>, Vec<Vec3>) {
    let mut sum_t = vec![Vec3::ZERO; mesh.positions.len()];
    let mut sum_b = vec![Vec3::ZERO; mesh.positions.len()];
    for triangle in mesh.indices.chunks_exact(3) {
        let (p, uv) = corners(mesh, triangle);
        let Some((t, b)) = face_frame(p, uv) else { continue };
        let area = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).length();
        for (k, &v) in triangle.iter().enumerate() {
            let weight = match weighting {
                Weighting::Uniform => 1.0,
                Weighting::Area => area,
                Weighting::Angle => corner_angle(p, k),
            };
            if weight.is_finite() {
                sum_t[v as usize] += t * weight;
                sum_b[v as usize] += b * weight;
            }
        }
    }
    (sum_t, sum_b)
}

#[cfg(test)]
mod tests {
    use super::*;
    use glam::Vec2;

    #[test]
    fn right_triangle_in_the_plane_gives_x_and_y() {
        // v stored down the image: the point at +Y has the smaller v.
        let p = [Vec3::ZERO, Vec3::X, Vec3::Y];
        let uv = [Vec2::new(0.0, 1.0), Vec2::new(1.0, 1.0), Vec2::new(0.0, 0.0)];
        let (t, b) = face_frame(p, uv).unwrap();
        assert!((t - Vec3::X).length() < 1e-6 && (b - Vec3::Y).length() < 1e-6);
    }

    #[test]
    fn degeneracy_is_judged_relative_to_the_uv_extent() {
        let p = [Vec3::ZERO, Vec3::X, Vec3::Y];
        let tiny = [Vec2::new(0.0, 1e-6), Vec2::new(1e-6, 1e-6), Vec2::new(0.0, 0.0)];
        assert!(face_frame(p, tiny).is_some(), "small but well-shaped UVs are fine");
        let collinear = [Vec2::new(0.0, 0.0), Vec2::new(1.0, 1.0), Vec2::new(2.0, 2.0)];
        assert!(face_frame(p, collinear).is_none());
        assert!(face_frame(p, [Vec2::ZERO; 3]).is_none());
    }
}
