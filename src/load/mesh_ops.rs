//! Geometry steps the loaders share: checks, triangulation and normals for files without them.

use std::path::Path;

use glam::{Vec2, Vec3};

use crate::error::LoadError;
use crate::math::normalize_or;
use crate::scene::Mesh;

/// Fails when an index points past the vertices or an attribute holds NaN or infinity.
pub fn check(mesh: &Mesh, path: &Path) -> Result<(), LoadError> {
    let count = mesh.positions.len();
    if let Some(&bad) = mesh.indices.iter().find(|&&i| i as usize >= count) {
        return Err(LoadError::new(path, format!("mesh {:?}: index {bad} but only {count} vertices", mesh.name)));
    }
    let found = [
        ("position", mesh.positions.iter().position(|p| !p.is_finite())),
        ("normal", mesh.normals.iter().position(|n| !n.is_finite())),
        ("texture coordinate", mesh.uvs.iter().position(|uv| !uv.is_finite())),
        ("tangent", mesh.tangents.as_ref().and_then(|t| t.iter().position(|t| !t.is_finite()))),
    ];
    if let Some((name, Some(vertex))) = found.into_iter().find(|(_, v)| v.is_some()) {
        let problem = format!("mesh {:?}: vertex {vertex} has a NaN or infinite {name}", mesh.name);
        return Err(LoadError::new(path, problem));
    }
    Ok(())
}

/// The triangles of a convex polygon given by its corner positions, as corner indices with
/// the polygon's winding: a quad is split along its shorter diagonal (the flatter and
/// better-shaped pair for a bent quad), larger polygons as a fan from the first corner.
pub fn triangulate(corners: &[Vec3]) -> Vec<[usize; 3]> {
    match corners.len() {
        0..=2 => vec![],
        4 if corners[0].distance_squared(corners[2]) > corners[1].distance_squared(corners[3]) => {
            vec![[0, 1, 3], [1, 2, 3]]
        }
        n => (1..n - 1).map(|i| [0, i, i + 1]).collect(),
    }
}

/// The unnormalised face normal (twice the area, along the CCW normal) of a triangle.
fn face_normal(mesh: &Mesh, triangle: &[u32]) -> Vec3 {
    let [a, b, c] = [0, 1, 2].map(|k| mesh.positions[triangle[k] as usize]);
    (b - a).cross(c - a)
}

/// The same triangles with a vertex per corner and each triangle's face normal: for files
/// without normals (glTF's rule: flat shading). Supplied tangents are dropped with them.
pub fn with_flat_normals(mesh: &Mesh) -> Mesh {
    let placeholder = Mesh { normals: vec![Vec3::Z; mesh.positions.len()], tangents: None, ..mesh.clone() };
    let mut flat = placeholder.unwelded();
    flat.normals =
        flat.indices.chunks_exact(3).flat_map(|t| [normalize_or(face_normal(&flat, t), Vec3::Z); 3]).collect();
    flat
}

/// Applies a glTF `KHR_texture_transform` (offset, rotation in radians, scale) to UVs in
/// glTF's space (v down): `uv' = T · R · S · uv` with `R = [[cos, sin], [−sin, cos]]`.
pub fn transform_uvs(uvs: &mut [Vec2], offset: Vec2, rotation: f32, scale: Vec2) {
    let (sin, cos) = rotation.sin_cos();
    for uv in uvs {
        let s = *uv * scale;
        *uv = offset + Vec2::new(cos * s.x + sin * s.y, -sin * s.x + cos * s.y);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quads_split_along_the_shorter_diagonal_and_keep_their_winding() {
        // A kite: corners 1 and 3 are closer than 0 and 2.
        let quad = [Vec3::new(-2.0, 0.0, 0.0), Vec3::new(0.0, -1.0, 0.0), Vec3::new(2.0, 0.0, 0.0), Vec3::Y];
        let triangles = triangulate(&quad);
        assert_eq!(triangles, vec![[0, 1, 3], [1, 2, 3]]);
        for [a, b, c] in triangles {
            assert!((quad[b] - quad[a]).cross(quad[c] - quad[a]).z > 0.0);
        }
        assert_eq!(triangulate(&[Vec3::ZERO; 5]).len(), 3);
    }

    #[test]
    fn flat_normals_face_along_ccw_winding() {
        let mut mesh = Mesh::empty("t");
        mesh.positions = vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::new(1.0, 1.0, 1.0)];
        mesh.indices = vec![0, 1, 2, 1, 3, 2];
        let flat = with_flat_normals(&mesh);
        assert_eq!(flat.positions.len(), 6);
        assert_eq!(flat.normals[0], Vec3::Z);
        assert!(flat.normals[3].z > 0.0);
    }

    #[test]
    fn texture_transform_rotates_a_quarter_turn() {
        let mut uvs = [Vec2::new(1.0, 0.0)];
        transform_uvs(&mut uvs, Vec2::new(0.5, 0.0), std::f32::consts::FRAC_PI_2, Vec2::splat(2.0));
        assert!((uvs[0] - Vec2::new(0.5, -2.0)).length() < 1e-6, "{}", uvs[0]);
    }
}
