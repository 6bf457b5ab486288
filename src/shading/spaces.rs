//! The lighting spaces of the classic model: the vectors [`super::blinn_phong`] lights with,
//! taken into tangent space by each triangle's inverse frame as the ARB-era shaders do, or into
//! view space as the GLSL practicum does. World space is [`super::world_vectors`].
//! Twins of `inverse_tbn`, `triangle_inverse_tbn` and the lighting-space branches of
//! `blinn_phong` in `shaders/lights.wgsl`.

use glam::{Mat3, Vec2, Vec3};

use super::LightingVectors;
use crate::math::normalize_or;

/// `|det(T, B, N)|` below this counts as degenerate (UVs without area): the inverse is then
/// the identity, as in the ARB-era shaders.
pub const MIN_TBN_DETERMINANT: f32 = 1e-6;

/// The inverse of the matrix whose columns are `t`, `b`, `n` (world → tangent space; not
/// the transpose, so a frame that is not orthogonal is inverted exactly), or the identity
/// where its determinant is below [`MIN_TBN_DETERMINANT`] or not finite.
pub fn inverse_tbn(t: Vec3, b: Vec3, n: Vec3) -> Mat3 {
    let tbn = Mat3::from_cols(t, b, n);
    let det = tbn.determinant();
    if det.is_finite() && det.abs() >= MIN_TBN_DETERMINANT { tbn.inverse() } else { Mat3::IDENTITY }
}

/// Triangles whose UV area per world area is below this many UV² per m² count as degenerate
/// (UVs without area): their inverse frame is the identity, as in the ARB-era shaders. The ratio is the
/// same from the triangle's edges and from a pixel's screen-space derivatives.
pub const MIN_UV_AREA_PER_M2: f32 = 1e-6;

/// The ARB-era shaders' per-triangle inverse frame (world → tangent space) from two
/// differences across the triangle — its edges, or a pixel's screen-space derivatives — of the
/// world position (`dp_a`, `dp_b`, metres) and of the texture coordinates (`duv_a`, `duv_b`, v down the
/// image): `T = ∂P/∂u`, `B = −∂P/∂v` (v up, the map's green), `N` the face normal on the side
/// of `normal`, each normalised but not orthogonalised, then [`inverse_tbn`]. The identity where
/// the UVs have no area ([`MIN_UV_AREA_PER_M2`]).
pub fn triangle_inverse_tbn(dp_a: Vec3, dp_b: Vec3, duv_a: Vec2, duv_b: Vec2, normal: Vec3) -> Mat3 {
    let det = duv_a.x * duv_b.y - duv_a.y * duv_b.x;
    let face = dp_a.cross(dp_b);
    if !(det.is_finite() && det.abs() > MIN_UV_AREA_PER_M2 * face.length()) {
        return Mat3::IDENTITY;
    }
    let dp_du = (dp_a * duv_b.y - dp_b * duv_a.y) / det;
    let dp_dv = (dp_b * duv_a.x - dp_a * duv_b.x) / det;
    let n = normalize_or(face, normal);
    let n = if n.dot(normal) < 0.0 { -n } else { n };
    inverse_tbn(normalize_or(dp_du, Vec3::X), normalize_or(-dp_dv, Vec3::Y), n)
}

/// Tangent-space lighting (the ARB-era shaders): the world-space vectors taken by the triangle's inverse
/// frame `to_tangent` and normalised (those shaders take `light − P` per vertex and interpolates;
/// with one frame per triangle that is `to_tangent · (light − P)` at the pixel exactly), the
/// geometric normal `+Z`, the shading normal the map's tangent-space normal after strength as
/// it is (no frame applied). Degenerate vectors fall back to `+Z`.
pub fn tangent_lighting_vectors(world: &LightingVectors, to_tangent: Mat3, shading_normal: Vec3) -> LightingVectors {
    LightingVectors {
        geometric_normal: Vec3::Z,
        shading_normal,
        lights: world.lights.map(|l| normalize_or(to_tangent * l, Vec3::Z)),
        views: world.views.map(|v| normalize_or(to_tangent * v, Vec3::Z)),
    }
}

/// View-space lighting (the GLSL practicum): the world-space vectors (the normal already through
/// T, B, N) rotated by the camera's `view_rotation` (world → view).
pub fn view_lighting_vectors(world: &LightingVectors, view_rotation: Mat3) -> LightingVectors {
    LightingVectors {
        geometric_normal: view_rotation * world.geometric_normal,
        shading_normal: view_rotation * world.shading_normal,
        lights: world.lights.map(|l| view_rotation * l),
        views: world.views.map(|v| view_rotation * v),
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

    /// The wall's mapping (u along +X, v down −Y) gives the identity frame from its edges or
    /// any other pair of differences; a triangle with collinear UVs gives the identity too; a
    /// skewed mapping keeps its skew.
    #[test]
    fn triangle_frames_follow_the_uv_mapping() {
        let uv_of = |p: Vec3| Vec2::new(p.x / 0.5, -p.y / 0.25);
        let (p0, p1, p2) = (Vec3::ZERO, Vec3::new(0.3, 0.1, 0.0), Vec3::new(-0.1, 0.4, 0.0));
        let m = triangle_inverse_tbn(p1 - p0, p2 - p0, uv_of(p1) - uv_of(p0), uv_of(p2) - uv_of(p0), Vec3::Z);
        assert!((m - Mat3::IDENTITY).abs_diff_eq(Mat3::ZERO, 1e-6), "{m}");
        let collinear = triangle_inverse_tbn(p1 - p0, p2 - p0, Vec2::new(1.0, 1.0), Vec2::new(2.0, 2.0), Vec3::Z);
        assert_eq!(collinear, Mat3::IDENTITY);
        let skew = |p: Vec3| Vec2::new(p.x + p.y, -p.y);
        let m = triangle_inverse_tbn(p1 - p0, p2 - p0, skew(p1) - skew(p0), skew(p2) - skew(p0), Vec3::Z);
        let b = Vec3::new(-1.0, 1.0, 0.0).normalize();
        assert!((m * b - Vec3::Y).length() < 1e-5, "{}", m * b);
    }
}
