//! Guarded vector helpers: nothing here returns NaN or infinity for finite or non-finite input.

use glam::{Mat4, Vec3, Vec4};

/// Squared lengths outside this range are treated as degenerate by [`normalize_or`].
const MIN_LENGTH_SQUARED: f32 = 1e-30;
const MAX_LENGTH_SQUARED: f32 = 1e30;

/// `v / |v|`, or `fallback` when `v` is zero, tiny, huge or not finite.
pub fn normalize_or(v: Vec3, fallback: Vec3) -> Vec3 {
    let length_squared = v.length_squared();
    if (MIN_LENGTH_SQUARED..MAX_LENGTH_SQUARED).contains(&length_squared) {
        v / length_squared.sqrt()
    } else {
        fallback
    }
}

/// A unit vector perpendicular to `n` (a stable choice); `n` degenerate or not finite counts
/// as +Z.
pub fn any_perpendicular(n: Vec3) -> Vec3 {
    normalize_or(n, Vec3::Z).any_orthonormal_vector()
}

/// Gram-Schmidt: the part of `t` perpendicular to the normal `n`, normalised. Falls back to
/// [`any_perpendicular`] when `t` is parallel to `n` or degenerate; `n` degenerate or not
/// finite counts as +Z.
pub fn orthonormalize_tangent(t: Vec3, n: Vec3) -> Vec3 {
    let n = normalize_or(n, Vec3::Z);
    normalize_or(t - n * n.dot(t), any_perpendicular(n))
}

/// The handedness sign of a MikkTSpace tangent's `w`: `-1.0` when `w < 0`, else `1.0`.
pub fn handedness(tangent: Vec4) -> f32 {
    if tangent.w < 0.0 { -1.0 } else { 1.0 }
}

/// Hermite smoothstep, as WGSL's `smoothstep(edge0, edge1, x)`.
pub fn smoothstep(edge0: f32, edge1: f32, x: f32) -> f32 {
    let t = ((x - edge0) / (edge1 - edge0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// sRGB transfer function: encoded value in 0..1 → linear value in 0..1.
pub fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 { c / 12.92 } else { ((c + 0.055) / 1.055).powf(2.4) }
}

/// Inverse of [`srgb_to_linear`].
pub fn linear_to_srgb(c: f32) -> f32 {
    let c = c.clamp(0.0, 1.0);
    if c <= 0.003_130_8 { c * 12.92 } else { 1.055 * c.powf(1.0 / 2.4) - 0.055 }
}

/// The matrix that takes model-space normals to world space: the inverse-transpose of `model`,
/// or the identity where `model` is singular or not finite.
pub fn normal_matrix(model: Mat4) -> Mat4 {
    let determinant = model.determinant();
    if determinant.is_finite() && determinant != 0.0 { model.inverse().transpose() } else { Mat4::IDENTITY }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normalize_or_falls_back_on_degenerate_input() {
        let up = Vec3::Y;
        assert_eq!(normalize_or(Vec3::ZERO, up), up);
        assert_eq!(normalize_or(Vec3::splat(f32::NAN), up), up);
        assert_eq!(normalize_or(Vec3::new(f32::INFINITY, 0.0, 0.0), up), up);
        assert!((normalize_or(Vec3::new(3.0, 4.0, 0.0), up) - Vec3::new(0.6, 0.8, 0.0)).length() < 1e-6);
    }

    #[test]
    fn gram_schmidt_gives_a_unit_perpendicular_even_for_parallel_input() {
        let n = Vec3::Z;
        let t = orthonormalize_tangent(Vec3::new(1.0, 0.0, 0.5), n);
        assert!((t - Vec3::X).length() < 1e-6);
        let t = orthonormalize_tangent(Vec3::Z * 2.0, n);
        assert!((t.length() - 1.0).abs() < 1e-6 && t.dot(n).abs() < 1e-6);
        assert!(orthonormalize_tangent(Vec3::X, Vec3::NAN).is_finite());
        assert!(orthonormalize_tangent(Vec3::NAN, Vec3::ZERO).is_finite());
    }

    #[test]
    fn srgb_round_trips() {
        for i in 0..=255 {
            let c = i as f32 / 255.0;
            assert!((linear_to_srgb(srgb_to_linear(c)) - c).abs() < 1e-5);
        }
    }
}
