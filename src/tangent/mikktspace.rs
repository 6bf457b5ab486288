//! MikkTSpace tangent frames (bevy_mikktspace), the default method.
//!
//! MikkTSpace assumes `v` runs *up* the image, while this crate stores glTF-style UVs with
//! `v` running down; it is therefore fed `(u, 1 − v)`, which makes the bitangent `B = w · cross(N, T)` point up the image — the
//! direction a tangent-space normal map's green channel (+Y) means.

use bevy_mikktspace::{Geometry, TangentSpace, generate_tangents};
use glam::Vec4;

use crate::math::{any_perpendicular, orthonormalize_tangent};
use crate::scene::Mesh;

struct MikkInput<'a> {
    mesh: &'a Mesh,
    tangents: Vec<Option<Vec4>>,
}

impl MikkInput<'_> {
    fn vertex(&self, face: usize, vert: usize) -> usize {
        self.mesh.indices[face * 3 + vert] as usize
    }
}

impl Geometry for MikkInput<'_> {
    fn num_faces(&self) -> usize {
        self.mesh.indices.len() / 3
    }

    fn num_vertices_of_face(&self, _face: usize) -> usize {
        3
    }

    fn position(&self, face: usize, vert: usize) -> [f32; 3] {
        self.mesh.positions[self.vertex(face, vert)].to_array()
    }

    fn normal(&self, face: usize, vert: usize) -> [f32; 3] {
        self.mesh.normals[self.vertex(face, vert)].to_array()
    }

    fn tex_coord(&self, face: usize, vert: usize) -> [f32; 2] {
        let uv = self.mesh.uvs[self.vertex(face, vert)];
        [uv.x, 1.0 - uv.y]
    }

    fn set_tangent(&mut self, tangent_space: Option<TangentSpace>, face: usize, vert: usize) {
        let vertex = self.vertex(face, vert);
        self.tangents[vertex] = tangent_space.map(|t| Vec4::from_array(t.tangent_encoded()));
    }
}

/// MikkTSpace tangents, one per vertex. Indexed vertices that MikkTSpace would split get the
/// last frame written (meshes are expected to be split at UV seams already, as glTF
/// requires). Vertices MikkTSpace leaves without a frame (isolated degenerate triangles) get
/// a valid orthonormal fallback with `w = +1`.
pub fn generate_mikktspace(mesh: &Mesh) -> Vec<Vec4> {
    let mut input = MikkInput { mesh, tangents: vec![None; mesh.positions.len()] };
    // The error type of bevy_mikktspace has no variants: generation cannot fail.
    let _ = generate_tangents(&mut input);
    input
        .tangents
        .iter()
        .zip(&mesh.normals)
        .map(|(tangent, &normal)| match tangent {
            Some(t) => orthonormalize_tangent(t.truncate(), normal).extend(t.w.signum()),
            None => any_perpendicular(normal).extend(1.0),
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tangent::bitangent;
    use glam::{Vec2, Vec3};

    use crate::tangent::test_quad as quad;

    #[test]
    fn bitangent_points_up_the_image() {
        for t in generate_mikktspace(&quad(false)) {
            assert!((t.truncate() - Vec3::X).length() < 1e-5 && t.w == 1.0, "{t}");
            assert!((bitangent(Vec3::Z, t) - Vec3::Y).length() < 1e-5);
        }
    }

    #[test]
    fn mirrored_u_flips_handedness_not_the_bitangent() {
        for t in generate_mikktspace(&quad(true)) {
            assert!((t.truncate() + Vec3::X).length() < 1e-5 && t.w == -1.0, "{t}");
            assert!((bitangent(Vec3::Z, t) - Vec3::Y).length() < 1e-5);
        }
    }

    #[test]
    fn degenerate_uvs_still_give_unit_orthogonal_frames() {
        let mut mesh = quad(false);
        mesh.uvs = vec![Vec2::ZERO; 4];
        for t in generate_mikktspace(&mesh) {
            assert!(
                t.is_finite() && (t.truncate().length() - 1.0).abs() < 1e-5 && t.truncate().dot(Vec3::Z).abs() < 1e-5
            );
        }
    }
}
