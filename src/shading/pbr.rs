//! glTF 2.0 metallic-roughness shading (the BRDF of the glTF spec, appendix B) with every
//! light and a procedural sky for image-based reflections; CPU twin of `shaders/pbr.wgsl`.
//!
//! Units: a light's radiance ([`super::lights::incident`]) is treated as the irradiance `E/π`
//! of a surface facing it, so a white Lambertian surface lit head-on shows it, as in the
//! Blinn-Phong model. The frame's ambient light is not used: the sky is the ambient light.
//! The sky is radiance (linear RGB) by direction, world space.

use std::f32::consts::PI;

use glam::{Vec2, Vec3};

use super::lights::incident;
use super::{LightingVectors, SELF_SHADOW_FADE};
use crate::math::{normalize_or, smoothstep};
use crate::scene::{Light, Lights};

/// The classic model's exponent whose highlight a metallic-roughness `roughness` has:
/// Beckmann's `2/α² − 2` with `α = roughness²` (Walter et al. 2007), roughness clamped to
/// 0..1 and `α` to at least 10⁻³ (an exponent of at most 2·10⁶ − 2). Callers clamp it to the
/// range they draw.
pub fn roughness_exponent(roughness: f32) -> f32 {
    let alpha = roughness.clamp(0.0, 1.0).powi(2).max(1e-3);
    2.0 / (alpha * alpha) - 2.0
}

/// Sky radiance straight up.
pub const SKY_ZENITH: Vec3 = Vec3::new(0.12, 0.22, 0.45);
/// Sky radiance just above the horizon.
pub const SKY_HORIZON: Vec3 = Vec3::new(0.55, 0.60, 0.65);
/// Ground radiance, every direction below the horizon (`y < 0`): the sharp horizon edge.
pub const GROUND: Vec3 = Vec3::new(0.06, 0.05, 0.04);
/// Cosine-weighted mean of the sky over the upper hemisphere: `E[sqrt(y)] = 0.8` for the
/// density `2y` of `y = cos θ`.
pub const SKY_MEAN: Vec3 = Vec3::new(
    SKY_HORIZON.x + 0.8 * (SKY_ZENITH.x - SKY_HORIZON.x),
    SKY_HORIZON.y + 0.8 * (SKY_ZENITH.y - SKY_HORIZON.y),
    SKY_HORIZON.z + 0.8 * (SKY_ZENITH.z - SKY_HORIZON.z),
);
/// Smallest perceptual roughness shaded (GGX is a delta at 0): `α ≥ 0.002`.
pub const MIN_ROUGHNESS: f32 = 0.045;

/// The sky in unit direction `dir` (world space): horizon → zenith by `sqrt(y)` above
/// `y = 0`, the constant ground below; discontinuous at the horizon.
pub fn sky(dir: Vec3) -> Vec3 {
    if dir.y >= 0.0 { SKY_HORIZON.lerp(SKY_ZENITH, dir.y.sqrt()) } else { GROUND }
}

/// Cosine-weighted mean radiance of the sky over the hemisphere around unit `n`: the part of
/// that hemisphere above the horizon has weight `(1 + n.y) / 2` (exact for a uniform sky;
/// the gradient is replaced by its mean [`SKY_MEAN`]). Lambertian irradiance over π.
pub fn sky_average(n: Vec3) -> Vec3 {
    GROUND.lerp(SKY_MEAN, 0.5 + 0.5 * n.y.clamp(-1.0, 1.0))
}

/// The blurred sky a rough surface reflects along `r`: `mix(sky(r), sky_average(r), roughness)`
/// — sharp for a mirror, the hemisphere mean for a fully rough surface (an approximation of
/// prefiltering the sky with the GGX lobe).
pub fn reflected_sky(r: Vec3, roughness: f32) -> Vec3 {
    sky(r).lerp(sky_average(r), roughness)
}

/// Karis's analytic fit of the split-sum environment BRDF ("Physically Based Shading on
/// Mobile", 2014): scale and bias of F0 for `n·v` and perceptual roughness.
pub fn environment_brdf(n_dot_v: f32, roughness: f32) -> Vec2 {
    let r = roughness * glam::Vec4::new(-1.0, -0.0275, -0.572, 0.022) + glam::Vec4::new(1.0, 0.0425, 1.04, -0.04);
    let a004 = (r.x * r.x).min((-9.28 * n_dot_v).exp2()) * r.x + r.y;
    Vec2::new(-1.04, 1.04) * a004 + Vec2::new(r.z, r.w)
}

/// GGX (Trowbridge-Reitz) normal distribution with `α = roughness²`.
pub fn ggx_distribution(n_dot_h: f32, alpha: f32) -> f32 {
    let a2 = alpha * alpha;
    let d = n_dot_h * n_dot_h * (a2 - 1.0) + 1.0;
    a2 / (PI * d * d)
}

/// Smith height-correlated visibility `V = G / (4 |n·l| |n·v|)` (glTF spec).
pub fn smith_visibility(n_dot_l: f32, n_dot_v: f32, alpha: f32) -> f32 {
    let a2 = alpha * alpha;
    let gv = n_dot_l * (n_dot_v * n_dot_v * (1.0 - a2) + a2).sqrt();
    let gl = n_dot_v * (n_dot_l * n_dot_l * (1.0 - a2) + a2).sqrt();
    let sum = gv + gl;
    if sum > 0.0 { 0.5 / sum } else { 0.0 }
}

/// Schlick's Fresnel.
pub fn fresnel_schlick(f0: Vec3, v_dot_h: f32) -> Vec3 {
    f0 + (Vec3::ONE - f0) * (1.0 - v_dot_h.clamp(0.0, 1.0)).powi(5)
}

/// What metallic-roughness shading needs at one surface point.
#[derive(Debug, Clone, Copy)]
pub struct PbrInputs {
    /// Linear base colour (texture × factor).
    pub base_color: Vec3,
    /// 0..1 (factor × texture blue).
    pub metallic: f32,
    /// Perceptual roughness 0..1 (factor × texture green), clamped to [`MIN_ROUGHNESS`].
    pub roughness: f32,
    /// Sky occlusion 0..1 (`1 + strength · (texture red − 1)`); 1 = none.
    pub occlusion: f32,
    /// Unit geometric normal (flipped on back faces of double-sided materials).
    pub geometric_normal: Vec3,
    /// Unit shading normal.
    pub shading_normal: Vec3,
    /// Point position, metres.
    pub position: Vec3,
    pub eye: Vec3,
    /// Every light (switched-off ones bring nothing); their ambient light is not used.
    pub lights: Lights,
    /// The world-space directions to each light and to the eye as the lighting sees them
    /// ([`super::world_vectors`], where the chain's per-vertex mistakes may replace the first
    /// light's); `None`: the true ones.
    pub seen: Option<LightingVectors>,
    /// The clear-coat layer over the base, if any.
    pub clearcoat: Option<ClearcoatInputs>,
}

/// A clear coat at one point (`KHR_materials_clearcoat`): a dielectric layer, F0 = 0.04.
#[derive(Debug, Clone, Copy)]
pub struct ClearcoatInputs {
    /// Layer strength 0..1 (factor × texture red).
    pub factor: f32,
    /// Perceptual roughness 0..1 (factor × texture green), clamped to [`MIN_ROUGHNESS`].
    pub roughness: f32,
    /// Unit normal of the layer (its own normal map, else the geometric normal).
    pub normal: Vec3,
}

/// Reflectance of the clear coat at normal incidence (index of refraction 1.5).
pub const CLEARCOAT_F0: f32 = 0.04;

/// Outgoing linear radiance: every light that is on through the glTF BRDF ([`pbr_light`]),
/// plus the sky: `occlusion · (c_diff · sky_average(n) + reflected_sky(r, roughness) · (F0 · A +
/// B))` with `(A, B)` from [`environment_brdf`]. A clear coat (`KHR_materials_clearcoat`)
/// adds its own highlights and sky reflection with its roughness and normal, F0 = 0.04, and
/// dims the base by `1 − factor · F(N_c·V)`.
pub fn metallic_roughness(p: &PbrInputs) -> Vec3 {
    let n = p.shading_normal;
    let v = normalize_or(p.eye - p.position, p.geometric_normal);
    let lit = p.lights.as_slice().iter().enumerate().filter(|(_, light)| light.enabled);
    let terms = lit.map(|(k, light)| {
        let (l, v) = match &p.seen {
            Some(seen) => (seen.lights[k], seen.views[k]),
            None => (incident(light, p.position, p.geometric_normal).direction, v),
        };
        pbr_light(p, light, l, v)
    });
    let (direct, coat_direct) = terms.fold((Vec3::ZERO, Vec3::ZERO), |(a, b), (c, d)| (a + c, b + d));
    let roughness = p.roughness.clamp(MIN_ROUGHNESS, 1.0);
    let metallic = p.metallic.clamp(0.0, 1.0);
    let c_diff = p.base_color.lerp(Vec3::ZERO, metallic);
    let f0 = Vec3::splat(0.04).lerp(p.base_color, metallic);
    let n_dot_v = n.dot(v).max(1e-4);
    let r = normalize_or(2.0 * n.dot(v) * n - v, n);
    let ab = environment_brdf(n_dot_v, roughness);
    let ambient = c_diff * sky_average(n) + reflected_sky(r, roughness) * (f0 * ab.x + ab.y);
    let occlusion = p.occlusion.clamp(0.0, 1.0);
    let base = direct + occlusion * ambient;
    let Some(coat) = p.clearcoat else { return base };
    // The layer as the Khronos sample viewer shades it: its own GGX highlights and sky
    // reflection, over the base dimmed by what the layer reflects towards the eye.
    let nc = coat.normal;
    let roughness = coat.roughness.clamp(MIN_ROUGHNESS, 1.0);
    let nc_dot_v = nc.dot(v).max(1e-4);
    let f0 = Vec3::splat(CLEARCOAT_F0);
    let rc = normalize_or(2.0 * nc.dot(v) * nc - v, nc);
    let ab = environment_brdf(nc_dot_v, roughness);
    let coat_sky = reflected_sky(rc, roughness) * (CLEARCOAT_F0 * ab.x + ab.y);
    let through = fresnel_schlick(f0, nc_dot_v);
    base * (Vec3::ONE - coat.factor * through) + coat.factor * (coat_direct + occlusion * coat_sky)
}

/// What one light adds through the glTF BRDF, `(base, clear coat)`:
/// `π · ((1 − F) · c_diff/π + F · D · V) · radiance · max(n·l, 0)` faded by the same
/// geometric self-shadow as Blinn-Phong, and the coat's `π · F_c · D_c · V_c · radiance ·
/// max(n_c·l, 0)` with the same fade (zero without a coat); `l` and `v` are the unit
/// directions to the light and to the eye the lighting sees ([`PbrInputs::seen`]).
pub fn pbr_light(p: &PbrInputs, light: &Light, l: Vec3, v: Vec3) -> (Vec3, Vec3) {
    let n_geo = p.geometric_normal;
    let n = p.shading_normal;
    let incident = incident(light, p.position, n_geo);
    let h = normalize_or(l + v, n_geo);
    let roughness = p.roughness.clamp(MIN_ROUGHNESS, 1.0);
    let alpha = roughness * roughness;
    let metallic = p.metallic.clamp(0.0, 1.0);
    let c_diff = p.base_color.lerp(Vec3::ZERO, metallic);
    let f0 = Vec3::splat(0.04).lerp(p.base_color, metallic);
    let n_dot_l = n.dot(l).max(0.0);
    let n_dot_v = n.dot(v).max(1e-4);
    let n_dot_h = n.dot(h).max(0.0);
    let fresnel = fresnel_schlick(f0, v.dot(h));
    let specular = fresnel * ggx_distribution(n_dot_h, alpha) * smith_visibility(n_dot_l, n_dot_v, alpha);
    let diffuse = (Vec3::ONE - fresnel) * c_diff / PI;
    let self_shadow = smoothstep(0.0, SELF_SHADOW_FADE, n_geo.dot(l));
    let direct = PI * (diffuse + specular) * incident.radiance * n_dot_l * self_shadow;
    let Some(coat) = p.clearcoat else { return (direct, Vec3::ZERO) };
    let nc = coat.normal;
    let roughness = coat.roughness.clamp(MIN_ROUGHNESS, 1.0);
    let alpha = roughness * roughness;
    let nc_dot_l = nc.dot(l).max(0.0);
    let nc_dot_v = nc.dot(v).max(1e-4);
    let highlight = fresnel_schlick(Vec3::splat(CLEARCOAT_F0), v.dot(h))
        * ggx_distribution(nc.dot(h).max(0.0), alpha)
        * smith_visibility(nc_dot_l, nc_dot_v, alpha);
    (direct, PI * highlight * incident.radiance * nc_dot_l * self_shadow)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn horizon_is_sharp_and_averages_are_between_ground_and_sky() {
        let above = sky(Vec3::new(1.0, 1e-4, 0.0).normalize());
        let below = sky(Vec3::new(1.0, -1e-4, 0.0).normalize());
        assert!((above - below).length() > 0.5);
        assert!((sky_average(Vec3::Y) - SKY_MEAN).length() < 1e-6);
        assert!((sky_average(-Vec3::Y) - GROUND).length() < 1e-6);
    }

    /// GGX integrates to one over the hemisphere when projected: ∫ D (n·h) dω = 1.
    #[test]
    fn ggx_is_normalised() {
        for alpha in [0.1f32, 0.5, 1.0] {
            let steps = 20000;
            let mut sum = 0.0;
            for i in 0..steps {
                let theta = (i as f32 + 0.5) / steps as f32 * PI / 2.0;
                let c = theta.cos();
                sum += ggx_distribution(c, alpha) * c * theta.sin() * 2.0 * PI * (PI / 2.0 / steps as f32);
            }
            assert!((sum - 1.0).abs() < 0.01, "{alpha}: {sum}");
        }
    }

    #[test]
    fn grazing_and_extreme_inputs_stay_finite() {
        let p = PbrInputs {
            base_color: Vec3::ONE,
            metallic: 1.0,
            roughness: 0.0,
            occlusion: 1.0,
            geometric_normal: Vec3::Y,
            shading_normal: Vec3::X,
            position: Vec3::ZERO,
            eye: Vec3::new(0.0, 1e-7, 1.0),
            lights: Lights::one(Light::point(Vec3::new(1.0, 1e-7, 0.0), Vec3::ONE), Vec3::ZERO),
            seen: None,
            clearcoat: Some(ClearcoatInputs { factor: 1.0, roughness: 0.0, normal: Vec3::Z }),
        };
        assert!(metallic_roughness(&p).is_finite());
        let eye_on_point = PbrInputs { eye: Vec3::ZERO, ..p };
        assert!(metallic_roughness(&eye_on_point).is_finite());
    }
}
