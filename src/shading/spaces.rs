//! The lighting spaces of the classic model (seeds 000 and 003): the vectors
//! [`super::blinn_phong`] lights with, taken into tangent space the way seed 003's vertex
//! shader does, or into view space as seed 000 does. World space is [`super::world_vectors`].
//! Twins of `inverse_tbn`, `vs_tangent_space` and the lighting-space branches of
//! `blinn_phong` in `shaders/mesh.wgsl`.

use glam::{Mat3, Vec3};

use super::LightingVectors;
use crate::math::normalize_or;
use crate::scene::{Light, MAX_LIGHTS};

/// `|det(T, B, N)|` below this counts as degenerate (UVs without area): the inverse is then
/// the identity, as in seed 003.
pub const MIN_TBN_DETERMINANT: f32 = 1e-6;

/// The inverse of the matrix whose columns are `t`, `b`, `n` (world → tangent space; not
/// the transpose, so a frame that is not orthogonal is inverted exactly), or the identity
/// where its determinant is below [`MIN_TBN_DETERMINANT`] or not finite.
pub fn inverse_tbn(t: Vec3, b: Vec3, n: Vec3) -> Mat3 {
    let tbn = Mat3::from_cols(t, b, n);
    let det = tbn.determinant();
    if det.is_finite() && det.abs() >= MIN_TBN_DETERMINANT { tbn.inverse() } else { Mat3::IDENTITY }
}

/// What the tangent-space vertex stage outputs for one vertex: the vectors to the eye and to
/// each light (by the frame's light index) through the inverse of the vertex's frame,
/// unnormalised, so that interpolating them is exact where the frame is constant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TangentSpaceVectors {
    pub view: Vec3,
    pub lights: [Vec3; MAX_LIGHTS],
}

impl TangentSpaceVectors {
    /// The vectors of a triangle's three corners interpolated with barycentric `weights`, as
    /// the rasteriser interpolates vertex outputs (perspective-correct: weights in world space).
    pub fn weighted(corners: [&TangentSpaceVectors; 3], weights: Vec3) -> TangentSpaceVectors {
        let w = weights.to_array();
        let mix =
            |f: &dyn Fn(&TangentSpaceVectors) -> Vec3| (0..3).fold(Vec3::ZERO, |sum, i| sum + f(corners[i]) * w[i]);
        TangentSpaceVectors { view: mix(&|c| c.view), lights: std::array::from_fn(|l| mix(&|c| c.lights[l])) }
    }
}

/// The vertex stage of tangent-space lighting at a vertex at `position` (world space) with
/// world normal `normal` and world tangent `tangent` (xyz, handedness `w`): the frame
/// `T = normalize(tangent)`, `B = w · cross(N, T)`, `N = normalize(normal)` is inverted
/// ([`inverse_tbn`]) and takes `eye − position`, `light − position` for point lights and the
/// direction towards each directional light.
pub fn tangent_space_vectors(
    position: Vec3,
    normal: Vec3,
    tangent: glam::Vec4,
    lights: &[Light],
    eye: Vec3,
) -> TangentSpaceVectors {
    let n = normalize_or(normal, Vec3::Z);
    let t = normalize_or(tangent.truncate(), crate::math::any_perpendicular(n));
    let b = crate::math::handedness(tangent) * n.cross(t);
    let to_tangent = inverse_tbn(t, b, n);
    let mut out = TangentSpaceVectors { view: to_tangent * (eye - position), lights: [Vec3::ZERO; MAX_LIGHTS] };
    for (l, light) in out.lights.iter_mut().zip(lights) {
        *l = to_tangent
            * match light.kind {
                crate::scene::LightKind::Point => light.position - position,
                crate::scene::LightKind::Directional => light.position,
            };
    }
    out
}

/// The fragment stage of tangent-space lighting: the interpolated vectors normalised, the
/// geometric normal `+Z` (the frame's own N), the shading normal the map's tangent-space
/// normal after strength as it is (no frame applied). Degenerate vectors fall back to `+Z`.
pub fn tangent_lighting_vectors(interpolated: &TangentSpaceVectors, shading_normal: Vec3) -> LightingVectors {
    LightingVectors {
        geometric_normal: Vec3::Z,
        shading_normal,
        view: normalize_or(interpolated.view, Vec3::Z),
        lights: interpolated.lights.map(|l| normalize_or(l, Vec3::Z)),
    }
}

/// View-space lighting (seed 000): the world-space vectors (the normal already through
/// T, B, N) rotated by the camera's `view_rotation` (world → view).
pub fn view_lighting_vectors(world: &LightingVectors, view_rotation: Mat3) -> LightingVectors {
    LightingVectors {
        geometric_normal: view_rotation * world.geometric_normal,
        shading_normal: view_rotation * world.shading_normal,
        view: view_rotation * world.view,
        lights: world.lights.map(|l| view_rotation * l),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn degenerate_frames_invert_to_the_identity_and_skewed_ones_exactly() {
        assert_eq!(inverse_tbn(Vec3::X, Vec3::X, Vec3::Z), Mat3::IDENTITY);
        assert_eq!(inverse_tbn(Vec3::NAN, Vec3::Y, Vec3::Z), Mat3::IDENTITY);
        let (t, b, n) = (Vec3::new(1.0, 0.3, 0.0), Vec3::new(0.2, 1.0, 0.1), Vec3::Z);
        let m = inverse_tbn(t, b, n);
        assert!((m * t - Vec3::X).length() < 1e-6 && (m * b - Vec3::Y).length() < 1e-6);
    }
}
