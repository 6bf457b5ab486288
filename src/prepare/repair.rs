//! Drawn geometry that cannot put NaN on screen. Loaders reject non-finite data; a scene
//! built in code may still hold it.

use glam::{Vec2, Vec3};

use crate::scene::Mesh;

/// `values` when it has `count` entries, else `count` defaults (a missing stream).
pub fn full_stream<T: Copy + Default>(values: &[T], count: usize) -> Vec<T> {
    if values.len() == count { values.to_vec() } else { vec![T::default(); count] }
}

/// `mesh` with triangles touching a non-finite or out-of-range position dropped, normals and
/// UVs one per vertex (missing streams zero), non-finite normals +Z and non-finite UVs 0.
/// A notice names the mesh and counts what was repaired.
pub fn repaired(mesh: &Mesh, notices: &mut Vec<String>) -> Mesh {
    let count = mesh.positions.len();
    let usable = |i: &u32| mesh.positions.get(*i as usize).is_some_and(|p| p.is_finite());
    let indices: Vec<u32> = mesh.indices.chunks_exact(3).filter(|t| t.iter().all(usable)).flatten().copied().collect();
    let normals = full_stream(&mesh.normals, count).into_iter().map(|n| if n.is_finite() { n } else { Vec3::Z });
    let uvs = full_stream(&mesh.uvs, count).into_iter().map(|uv| if uv.is_finite() { uv } else { Vec2::ZERO });
    let dropped = (mesh.indices.len() - indices.len()) / 3;
    let replaced =
        mesh.normals.iter().filter(|n| !n.is_finite()).count() + mesh.uvs.iter().filter(|uv| !uv.is_finite()).count();
    if dropped + replaced > 0 {
        notices.push(format!(
            "mesh {:?}: NaN or infinite data: {dropped} triangles dropped, {replaced} normals or UVs replaced",
            mesh.name
        ));
    }
    Mesh { normals: normals.collect(), uvs: uvs.collect(), indices, ..mesh.clone() }
}
