//! Tangent frames by several methods, so they can be compared against exact answers.
//!
//! Every method returns one MikkTSpace-style `vec4` per vertex: `xyz` unit and orthogonal to
//! the vertex normal, `w = ±1`, bitangent `B = w · cross(N, T)` pointing up the image (crate
//! conventions). None returns NaN: degenerate input falls back to a valid orthonormal frame.

mod compare;
#[cfg(not(target_arch = "wasm32"))]
mod meshopt;
mod mikktspace;
mod uv_delta;

use glam::{Vec3, Vec4};

use crate::math::orthonormalize_tangent;
use crate::scene::Mesh;
pub use compare::{AngleStats, FrameAngles, MethodMeasurement, angle_degrees, frame_angles, measure};
#[cfg(not(target_arch = "wasm32"))]
pub use meshopt::generate_meshopt;
pub use mikktspace::generate_mikktspace;
pub use uv_delta::{
    Weighting, averaged_face_frames, averaged_face_frames_without_gram_schmidt, face_frame, per_face_frames,
};

/// How tangent frames are made. Named `mikktspace`, `meshopt`, `per-face`, `averaged-uniform`,
/// `averaged-area`, `averaged-angle`, `supplied`, `analytic`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, strum::IntoStaticStr, strum::VariantArray)]
#[strum(serialize_all = "kebab-case")]
pub enum TangentMethod {
    /// MikkTSpace (bevy_mikktspace): the standard bakers use.
    #[default]
    #[strum(serialize = "mikktspace")]
    MikkTSpace,
    /// meshoptimizer's MikkTSpace-compatible generator: the same frames (within 0.05° on the
    /// test models) about ten times faster; what "auto" generates ([`resolve`]).
    Meshopt,
    /// Each triangle's own frame from its edge and UV deltas; a vertex takes the frame of
    /// the last triangle that uses it, so this is exact only on an unwelded mesh
    /// ([`Mesh::unwelded`]), which is how the renderer draws it.
    PerFace,
    /// Face frames averaged at each vertex with equal weights ([`Weighting::Uniform`]), then
    /// Gram-Schmidt against the normal and `w = sign(dot(cross(N, T), B))`.
    AveragedUniform,
    /// As [`TangentMethod::AveragedUniform`], each face weighted by its area ([`Weighting::Area`]).
    AveragedArea,
    /// As [`TangentMethod::AveragedUniform`], each face weighted by its corner angle at the
    /// vertex ([`Weighting::Angle`]).
    AveragedAngle,
    /// The tangents the mesh file supplies, re-orthogonalised against the normal, `w` kept.
    Supplied,
    /// The exact frame of a built-in parametric surface.
    Analytic,
}

impl TangentMethod {
    /// The face weighting of an averaging method.
    pub fn weighting(self) -> Option<Weighting> {
        match self {
            TangentMethod::AveragedUniform => Some(Weighting::Uniform),
            TangentMethod::AveragedArea => Some(Weighting::Area),
            TangentMethod::AveragedAngle => Some(Weighting::Angle),
            _ => None,
        }
    }

    /// Whether the method computes frames (rather than taking them from the mesh).
    pub fn is_generated(self) -> bool {
        !matches!(self, TangentMethod::Supplied | TangentMethod::Analytic)
    }
}

/// The frames to draw `mesh` with. `choice = None` is the default rule ("auto"): the mesh's
/// supplied tangents if it has them, else MikkTSpace frames made by meshoptimizer
/// ([`TangentMethod::Meshopt`]; by bevy_mikktspace in the web build, [`MESHOPT_BUILT`]). A chosen method with nothing to offer for this mesh (no
/// supplied or analytic frames) falls back the same way. Returns the frames and the method
/// actually used.
pub fn resolve(mesh: &Mesh, choice: Option<TangentMethod>) -> (Vec<Vec4>, TangentMethod) {
    let wanted = choice.unwrap_or(TangentMethod::Supplied);
    match tangents(mesh, wanted) {
        Some(frames) => (frames, wanted),
        None => generated(mesh),
    }
}

/// Whether this build has meshoptimizer (C++): not the web build (wasm32), where "auto" makes
/// missing tangents with MikkTSpace (bevy_mikktspace) and [`TangentMethod::Meshopt`] gives none.
pub const MESHOPT_BUILT: bool = cfg!(not(target_arch = "wasm32"));

/// The frames "auto" makes for a mesh without usable ones, and by which method.
#[cfg(not(target_arch = "wasm32"))]
fn generated(mesh: &Mesh) -> (Vec<Vec4>, TangentMethod) {
    (generate_meshopt(mesh), TangentMethod::Meshopt)
}

/// The frames "auto" makes for a mesh without usable ones, and by which method: MikkTSpace,
/// as the web build has no meshoptimizer.
#[cfg(target_arch = "wasm32")]
fn generated(mesh: &Mesh) -> (Vec<Vec4>, TangentMethod) {
    (generate_mikktspace(mesh), TangentMethod::MikkTSpace)
}

/// meshoptimizer's frames ([`MESHOPT_BUILT`]).
#[cfg(not(target_arch = "wasm32"))]
fn meshopt_frames(mesh: &Mesh) -> Option<Vec<Vec4>> {
    Some(generate_meshopt(mesh))
}

/// None: the web build has no meshoptimizer ([`MESHOPT_BUILT`]).
#[cfg(target_arch = "wasm32")]
fn meshopt_frames(_mesh: &Mesh) -> Option<Vec<Vec4>> {
    None
}

/// The frames of `method` without their Gram-Schmidt against the vertex normal, where it has
/// one to skip: averaged face frames only normalised, supplied and analytic frames as given
/// (normalised); `None` for the others (MikkTSpace, meshopt and per-face frames are drawn
/// as [`tangents`] makes them).
pub fn without_gram_schmidt(mesh: &Mesh, method: TangentMethod) -> Option<Vec<Vec4>> {
    let given = |frames: &Vec<Vec4>| {
        let normalised = frames.iter().zip(&mesh.normals).map(|(t, &n)| {
            crate::math::normalize_or(t.truncate(), crate::math::any_perpendicular(n)).extend(t.w.signum())
        });
        normalised.collect()
    };
    match method {
        TangentMethod::AveragedUniform | TangentMethod::AveragedArea | TangentMethod::AveragedAngle => {
            method.weighting().map(|weighting| averaged_face_frames_without_gram_schmidt(mesh, weighting))
        }
        TangentMethod::Supplied => mesh.tangents.as_ref().filter(|t| t.len() == mesh.positions.len()).map(given),
        TangentMethod::Analytic => {
            mesh.analytic_tangents.as_ref().filter(|t| t.len() == mesh.positions.len()).map(given)
        }
        TangentMethod::MikkTSpace | TangentMethod::Meshopt | TangentMethod::PerFace => None,
    }
}

/// The reference frames a method is compared with: the analytic frame where the mesh has
/// one (built-in surfaces), else MikkTSpace (bevy_mikktspace, the reference implementation).
/// Returns the frames and which reference it is.
pub fn reference(mesh: &Mesh) -> (Vec<Vec4>, TangentMethod) {
    match tangents(mesh, TangentMethod::Analytic) {
        Some(frames) => (frames, TangentMethod::Analytic),
        None => (generate_mikktspace(mesh), TangentMethod::MikkTSpace),
    }
}

/// Per-vertex frames of `mesh` by `method`; `None` when the mesh has no supplied or
/// analytic frames for those methods (the caller decides the fallback).
pub fn tangents(mesh: &Mesh, method: TangentMethod) -> Option<Vec<Vec4>> {
    let reorthogonalised = |frames: &Vec<Vec4>| {
        frames
            .iter()
            .zip(&mesh.normals)
            .map(|(t, &n)| orthonormalize_tangent(t.truncate(), n).extend(t.w.signum()))
            .collect()
    };
    match method {
        TangentMethod::MikkTSpace => Some(generate_mikktspace(mesh)),
        TangentMethod::Meshopt => meshopt_frames(mesh),
        TangentMethod::PerFace => {
            let mut frames = vec![Vec4::ZERO; mesh.positions.len()];
            for (triangle, frame) in mesh.indices.chunks_exact(3).zip(per_face_frames(mesh)) {
                for &v in triangle {
                    let n = mesh.normals[v as usize];
                    frames[v as usize] = orthonormalize_tangent(frame.truncate(), n).extend(frame.w);
                }
            }
            Some(frames)
        }
        TangentMethod::AveragedUniform | TangentMethod::AveragedArea | TangentMethod::AveragedAngle => {
            method.weighting().map(|weighting| averaged_face_frames(mesh, weighting))
        }
        TangentMethod::Supplied => {
            mesh.tangents.as_ref().filter(|t| t.len() == mesh.positions.len()).map(reorthogonalised)
        }
        TangentMethod::Analytic => {
            mesh.analytic_tangents.as_ref().filter(|t| t.len() == mesh.positions.len()).map(reorthogonalised)
        }
    }
}

/// The bitangent `w · cross(N, T)` of a MikkTSpace tangent (crate conventions).
pub fn bitangent(normal: Vec3, tangent: Vec4) -> Vec3 {
    crate::math::handedness(tangent) * normal.cross(tangent.truncate())
}
/// Test fixture: a unit quad in the XY plane facing +Z, u along +X (mirrored when `flip_u`)
/// and v (glTF, down the image) along −Y.
#[cfg(test)]
pub(crate) fn test_quad(flip_u: bool) -> Mesh {
    use glam::{Vec2, Vec3};
    let u = |x: f32| if flip_u { 1.0 - x } else { x };
    Mesh {
        positions: vec![Vec3::new(0., 0., 0.), Vec3::new(1., 0., 0.), Vec3::new(1., 1., 0.), Vec3::new(0., 1., 0.)],
        normals: vec![Vec3::Z; 4],
        uvs: vec![Vec2::new(u(0.), 1.), Vec2::new(u(1.), 1.), Vec2::new(u(1.), 0.), Vec2::new(u(0.), 0.)],
        indices: vec![0, 1, 2, 0, 2, 3],
        ..Mesh::empty("quad")
    }
}
