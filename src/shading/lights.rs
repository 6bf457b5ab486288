//! What one light brings to a surface point, one formula per function: OpenGL's distance
//! attenuation ([`attenuation`]), the direction and radiance arriving from a point or
//! directional light ([`incident`]) and the highlight of the classic model by specular mode
//! ([`specular_power`]). Twins of `attenuation`, `incident_light` and `specular_power` in
//! `shaders/lights.wgsl`. World space, metres, linear RGB.

use glam::Vec3;

use crate::math::normalize_or;
use crate::scene::{Attenuation, Light, LightKind, SpecularMode};

/// The denominator of [`attenuation`] never falls below this, so a light on the surface with
/// `c = 0` brings a large but finite amount.
pub const MIN_ATTENUATION_DENOMINATOR: f32 = 1e-6;
/// Distances are clamped to this many metres before squaring, so `q·d²` stays finite.
pub const MAX_LIGHT_DISTANCE_M: f32 = 1e15;

/// OpenGL's attenuation `1 / (c + l·d + q·d²)` at `distance_m` metres (the GLScene shader's
/// light-attenuation option), the denominator at least [`MIN_ATTENUATION_DENOMINATOR`].
pub fn attenuation(a: Attenuation, distance_m: f32) -> f32 {
    let d = distance_m.min(MAX_LIGHT_DISTANCE_M);
    1.0 / (a.constant + a.linear * d + a.quadratic * d * d).max(MIN_ATTENUATION_DENOMINATOR)
}

/// The light arriving at a point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Incident {
    /// Unit direction from the point towards the light.
    pub direction: Vec3,
    /// The attenuation factor (1 for a directional light).
    pub attenuation: f32,
    /// `color · intensity · attenuation`, linear RGB.
    pub radiance: Vec3,
}

/// What `light` brings to `position`: a point light from its position, attenuated by the
/// distance; a directional light from its direction, unattenuated. A degenerate direction (the
/// point on the light, a zero direction) falls back to `fallback`.
pub fn incident(light: &Light, position: Vec3, fallback: Vec3) -> Incident {
    let (direction, attenuation) = match light.kind {
        LightKind::Point => {
            let to_light = light.position - position;
            (normalize_or(to_light, fallback), attenuation(light.attenuation, to_light.length()))
        }
        LightKind::Directional => (normalize_or(light.position, fallback), 1.0),
    };
    Incident { direction, attenuation, radiance: light.color * light.intensity * attenuation }
}

/// The classic model's highlight for unit shading normal `n`, unit directions to the light
/// `l` and to the eye `v`: Blinn `max(N·H, 0)^shininess` with `H = normalize(L + V)` (falling
/// back to `n_geo`), Phong `max(R·V, 0)^shininess` with `R = 2(N·L)N − L`, or 0; zero where
/// `N·L ≤ 0` or the cosine is 0.
pub fn specular_power(mode: SpecularMode, n: Vec3, n_geo: Vec3, l: Vec3, v: Vec3, shininess: f32) -> f32 {
    let cosine = match mode {
        SpecularMode::Blinn => n.dot(normalize_or(l + v, n_geo)).max(0.0),
        SpecularMode::Phong => (2.0 * n.dot(l) * n - l).dot(v).max(0.0),
        SpecularMode::Off => 0.0,
    };
    if n.dot(l) > 0.0 && cosine > 0.0 { cosine.powf(shininess) } else { 0.0 }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn attenuation_is_the_opengl_formula_and_stays_finite() {
        let a = Attenuation { constant: 1.0, linear: 0.5, quadratic: 0.25 };
        assert_eq!(attenuation(a, 2.0), 1.0 / 3.0);
        assert_eq!(attenuation(Attenuation::NONE, 1e30), 1.0);
        let on_light = attenuation(Attenuation { constant: 0.0, linear: 0.0, quadratic: 1.0 }, 0.0);
        assert!(on_light.is_finite() && on_light > 0.0);
        for d in [f32::INFINITY, f32::NAN, f32::MAX] {
            assert!(attenuation(a, d).is_finite(), "{d}");
        }
    }

    #[test]
    fn directional_light_is_parallel_and_unattenuated() {
        let mut light = Light::directional(Vec3::new(0.0, 2.0, 0.0), Vec3::ONE);
        light.attenuation = Attenuation { constant: 0.0, linear: 0.0, quadratic: 9.0 };
        for p in [Vec3::ZERO, Vec3::new(5.0, -3.0, 2.0)] {
            assert_eq!(
                incident(&light, p, Vec3::Z),
                Incident { direction: Vec3::Y, attenuation: 1.0, radiance: Vec3::ONE }
            );
        }
    }

    /// Phong's R·V equals Blinn's N·H where the eye sits on the mirror direction (both 1);
    /// off the mirror direction Phong's cosine falls about twice as fast in angle.
    #[test]
    fn phong_and_blinn_agree_on_the_mirror_direction_only() {
        let n = Vec3::Z;
        let l = Vec3::new(0.6, 0.0, 0.8);
        let mirror = Vec3::new(-0.6, 0.0, 0.8);
        for mode in [SpecularMode::Blinn, SpecularMode::Phong] {
            assert!((specular_power(mode, n, n, l, mirror, 20.0) - 1.0).abs() < 1e-5, "{mode:?}");
        }
        let v = Vec3::new(-0.5, 0.0, 0.866_025_4);
        let blinn = specular_power(SpecularMode::Blinn, n, n, l, v, 1.0);
        let phong = specular_power(SpecularMode::Phong, n, n, l, v, 1.0);
        let deviation = (-0.6f32).atan2(0.8) - (-0.5f32).atan2(0.866_025_4);
        assert!((phong - deviation.cos()).abs() < 1e-5 && (blinn - (deviation / 2.0).cos()).abs() < 1e-5);
        assert_eq!(specular_power(SpecularMode::Off, n, n, l, mirror, 20.0), 0.0);
        assert_eq!(specular_power(SpecularMode::Phong, n, n, -l, mirror, 20.0), 0.0, "light below the surface");
    }
}
