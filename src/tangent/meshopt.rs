//! MikkTSpace-compatible tangent frames by meshoptimizer (`meshopt_generateTangents` with
//! `meshopt_TangentCompatible`, meshoptimizer 1.3 through the `meshopt` crate): the same
//! weighting and fallbacks as Mikkelsen's MikkTSpace (Mikkelsen 2008, "Simulation of wrinkled
//! surfaces revisited", whose reference implementation bevy_mikktspace ports). Measured by the
//! report on the 1M-triangle torus: 124 ms (8.0 M triangles/s) against bevy_mikktspace's
//! 1.50 s (0.67 M triangles/s); frames within 4.8e-4° of bevy_mikktspace's on the report's
//! spheres and tori and within 0.0124° on the shared models (`tests/tangent_methods.rs`). That
//! is why it makes the missing tangents ("auto").
//!
//! Like [`super::generate_mikktspace`] it is fed `(u, 1 − v)` (crate conventions: `v` runs
//! down the image), and a vertex takes the frame of the last corner that uses it.

use std::borrow::Cow;

use glam::{Vec2, Vec3, Vec4};
use meshopt::TangentOptions;

use crate::math::{any_perpendicular, handedness, orthonormalize_tangent};
use crate::scene::Mesh;

/// meshoptimizer's MikkTSpace-compatible tangents, one per vertex. Vertices it leaves without
/// a frame (only degenerate triangles around them), vertices no triangle uses and non-finite
/// results get a valid orthonormal fallback with `w = +1`, as in [`super::generate_mikktspace`].
pub fn generate_meshopt(mesh: &Mesh) -> Vec<Vec4> {
    let count = mesh.positions.len();
    let mut frames = vec![Vec4::ZERO; count];
    // meshoptimizer reads every index it is given: triangles naming a missing vertex are left out.
    let in_range = |t: &[u32]| t.iter().all(|&i| (i as usize) < count);
    let indices: Cow<[u32]> = if mesh.indices.len().is_multiple_of(3) && mesh.indices.chunks_exact(3).all(in_range) {
        Cow::Borrowed(&mesh.indices)
    } else {
        Cow::Owned(mesh.indices.chunks_exact(3).filter(|t| in_range(t)).flatten().copied().collect())
    };
    let normals: Cow<[Vec3]> = if mesh.normals.len() == count {
        Cow::Borrowed(&mesh.normals)
    } else {
        Cow::Owned((0..count).map(|i| mesh.normals.get(i).copied().unwrap_or(Vec3::Z)).collect())
    };
    if !indices.is_empty() {
        let uvs: Vec<[f32; 2]> =
            (0..count).map(|i| mesh.uvs.get(i).copied().unwrap_or(Vec2::ZERO)).map(|uv| [uv.x, 1.0 - uv.y]).collect();
        let corners = meshopt::generate_tangents(
            Some(&indices),
            bytemuck::cast_slice(&mesh.positions),
            bytemuck::cast_slice(normals.as_ref()),
            &uvs,
            TangentOptions::Compatible | TangentOptions::ZeroFallback,
        );
        for (&vertex, corner) in indices.iter().zip(corners) {
            frames[vertex as usize] = Vec4::from_array(corner);
        }
    }
    frames
        .iter()
        .zip(normals.iter())
        .map(|(&t, &n)| {
            let direction = t.truncate();
            if direction != Vec3::ZERO && direction.is_finite() {
                orthonormalize_tangent(direction, n).extend(handedness(t))
            } else {
                any_perpendicular(n).extend(1.0)
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tangent::generate_mikktspace;

    use crate::tangent::test_quad as quad;

    #[test]
    fn equals_mikktspace_on_a_quad_and_its_mirror_image() {
        for flip in [false, true] {
            let mesh = quad(flip);
            let (a, b) = (generate_meshopt(&mesh), generate_mikktspace(&mesh));
            for (a, b) in a.iter().zip(&b) {
                assert!((*a - *b).length() < 1e-6, "{a} {b}");
            }
        }
    }

    #[test]
    fn unused_vertices_missing_uvs_and_bad_indices_get_fallback_frames() {
        let mut mesh = quad(false);
        mesh.positions.push(Vec3::X);
        mesh.normals.push(Vec3::Y);
        mesh.indices.extend([0, 1, 9]);
        let frames = generate_meshopt(&mesh);
        assert_eq!(frames.len(), 5);
        assert!((frames[0].truncate() - Vec3::X).length() < 1e-6);
        assert_eq!(frames[4], any_perpendicular(Vec3::Y).extend(1.0));
        mesh.uvs.clear();
        let frames = generate_meshopt(&mesh);
        assert!(frames.iter().zip(&mesh.normals).all(|(t, n)| t.is_finite() && t.truncate().dot(*n).abs() < 1e-6));
    }
}
