//! The classic mistakes ([`Mistake`]) as steps of the CPU chain, each the twin of its branch
//! in `shaders/mistakes.wgsl`: the normal map's texel and convention as read, the tangent
//! frame as built, the normal before tangent space, and the way back to world space. With
//! [`Mistake::None`] every step is the correct one of [`crate::chain::shade`].
//!
//! Vectors are world space unless named tangent space; `n` is the unit geometric normal
//! (facing the viewer's side), `raw_normal` the interpolated one before normalisation.

use glam::{Vec3, Vec4};

use crate::frame::Mistake;
use crate::math::{any_perpendicular, handedness, normalize_or, orthonormalize_tangent, srgb_to_linear};
use crate::scene::{GreenAxis, Lights, NormalConvention};
use crate::shading::{self, LightingVectors, NormalTexel};

/// The texel as the shader reads it: through an sRGB view ([`Mistake::SrgbNormalMap`]) its
/// colour channels are decoded from sRGB (alpha and `bump#` stay linear); else as filtered.
pub fn texel_read(mistake: Mistake, texel: NormalTexel) -> NormalTexel {
    match mistake {
        Mistake::SrgbNormalMap => {
            NormalTexel { rgba: texel.rgba.truncate().map(srgb_to_linear).extend(texel.rgba.w), ..texel }
        }
        _ => texel,
    }
}

/// The convention the map is decoded with: the other green axis for [`Mistake::GreenFlipped`].
pub fn convention_read(mistake: Mistake, convention: NormalConvention) -> NormalConvention {
    match (mistake, convention.green) {
        (Mistake::GreenFlipped, GreenAxis::OpenGl) => NormalConvention { green: GreenAxis::DirectX, ..convention },
        (Mistake::GreenFlipped, GreenAxis::DirectX) => NormalConvention { green: GreenAxis::OpenGl, ..convention },
        _ => convention,
    }
}

/// The tangent frame `(T, B, w)` built from the interpolated tangent: the right one
/// ([`shading::tangent_frame`]), or the mistake's ([`frame_without_handedness`],
/// [`frame_without_gram_schmidt`]).
pub fn tangent_frame(mistake: Mistake, world_tangent: Vec4, n: Vec3) -> (Vec3, Vec3, f32) {
    match mistake {
        Mistake::HandednessIgnored => frame_without_handedness(world_tangent, n),
        Mistake::NoGramSchmidt => frame_without_gram_schmidt(world_tangent, n),
        _ => shading::tangent_frame(world_tangent, n),
    }
}

/// [`Mistake::HandednessIgnored`]: `T` by Gram-Schmidt, `B = N × T` with `w` dropped
/// (reported +1).
pub fn frame_without_handedness(world_tangent: Vec4, n: Vec3) -> (Vec3, Vec3, f32) {
    let t = orthonormalize_tangent(world_tangent.truncate(), n);
    (t, n.cross(t), 1.0)
}

/// [`Mistake::NoGramSchmidt`]: `T` only normalised, `B = w · (N × T)` (shorter than 1 where
/// `T` leans on `N`).
pub fn frame_without_gram_schmidt(world_tangent: Vec4, n: Vec3) -> (Vec3, Vec3, f32) {
    let w = handedness(world_tangent);
    let t = normalize_or(world_tangent.truncate(), any_perpendicular(n));
    (t, w * n.cross(t), w)
}

/// The normal lighting starts from: the interpolated normal as it comes (times `facing`) for
/// [`Mistake::NoRenormalization`], else the unit `n`.
pub fn base_normal(mistake: Mistake, raw_normal: Vec3, facing: f32, n: Vec3) -> Vec3 {
    match mistake {
        Mistake::NoRenormalization => raw_normal * facing,
        _ => n,
    }
}

/// The tangent-space normal `nt` in world space through `T`, `B` and `base` (the
/// [`base_normal`]): the right path ([`shading::tangent_to_world`]), or the mistake's
/// ([`world_with_tbn_typo`], [`world_without_renormalization`]).
pub fn to_world(mistake: Mistake, t: Vec3, b: Vec3, base: Vec3, nt: Vec3) -> Vec3 {
    match mistake {
        Mistake::TbnTypo => world_with_tbn_typo(t, b, base, nt),
        Mistake::NoRenormalization => world_without_renormalization(t, b, base, nt),
        _ => shading::tangent_to_world(t, b, base, nt),
    }
}

/// [`Mistake::TbnTypo`] (`TBN[1].z = N.z` instead of `N.y`): the world y takes `N.z` where
/// `N.y` belongs, then normalised.
pub fn world_with_tbn_typo(t: Vec3, b: Vec3, base: Vec3, nt: Vec3) -> Vec3 {
    let sum = t * nt.x + b * nt.y + base * nt.z;
    let typo = Vec3::new(sum.x, t.y * nt.x + b.y * nt.y + base.z * nt.z, sum.z);
    normalize_or(typo, base)
}

/// [`Mistake::NoRenormalization`]: `T·nt.x + B·nt.y + base·nt.z`, not normalised.
pub fn world_without_renormalization(t: Vec3, b: Vec3, base: Vec3, nt: Vec3) -> Vec3 {
    t * nt.x + b * nt.y + base * nt.z
}

/// The direction towards light `i` (counted among the lights that are on, so 0 is the
/// shader's `frame.lights[0]`) the lighting uses, given the true unit direction `l`: for
/// [`Mistake::LightPerVertex`] the first light's is the interpolated per-vertex light
/// direction `vertex_light` re-normalised (`n` the fallback); else `l`.
pub fn seen_light_direction(mistake: Mistake, i: usize, l: Vec3, vertex_light: Vec3, n: Vec3) -> Vec3 {
    match (mistake, i) {
        (Mistake::LightPerVertex, 0) => normalize_or(vertex_light, n),
        _ => l,
    }
}

/// The direction towards the eye light `i`'s highlight uses (`i` as in
/// [`seen_light_direction`]), given the unit direction to the light `l` and the true one to
/// the eye `v`: for [`Mistake::HalfVectorPerVertex`] the first light's is `l` mirrored about
/// the interpolated per-vertex half vector `h` re-normalised, `h·2(h·l) − l`, so that
/// `normalize(l + v)` is that half vector (`n` the fallback); else `v`.
pub fn seen_view_direction(mistake: Mistake, i: usize, l: Vec3, v: Vec3, vertex_half: Vec3, n: Vec3) -> Vec3 {
    match (mistake, i) {
        (Mistake::HalfVectorPerVertex, 0) => {
            let h = normalize_or(vertex_half, n);
            h * (2.0 * h.dot(l)) - l
        }
        _ => v,
    }
}

/// The world-space vectors ([`crate::shading::world_vectors`]) with the direction to each
/// light that is on and to the eye as the lighting sees them ([`seen_light_direction`],
/// [`seen_view_direction`]), light `k` of `lights` counted among those that are on. Applied
/// before any lighting space takes the vectors (the mistakes are defined in world space).
pub fn seen_vectors(
    mistake: Mistake,
    world: LightingVectors,
    lights: &Lights,
    vertex_light: Vec3,
    vertex_half: Vec3,
) -> LightingVectors {
    let n = world.geometric_normal;
    let mut seen = world;
    let on = lights.as_slice().iter().enumerate().filter(|(_, light)| light.enabled).map(|(k, _)| k);
    for (i, k) in on.enumerate() {
        let l = seen_light_direction(mistake, i, world.lights[k], vertex_light, n);
        seen.lights[k] = l;
        seen.views[k] = seen_view_direction(mistake, i, l, world.views[k], vertex_half, n);
    }
    seen
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The flat texel (128, 128, 255) read through an sRGB view decodes 38.8° off +Z, towards
    /// −x and −y equally: 128/255 is 0.2158 once decoded, so x = y = 2·0.2158 − 1.
    #[test]
    fn an_srgb_view_tilts_the_flat_texel_towards_minus_t_minus_b() {
        let flat = NormalTexel::rgb(Vec3::new(128.0, 128.0, 255.0) / 255.0);
        let read = crate::shading::decode_normal(texel_read(Mistake::SrgbNormalMap, flat), Default::default());
        let angle = read.angle_between(Vec3::Z).to_degrees();
        assert!((angle - 38.8).abs() < 0.1 && read.x < 0.0 && (read.x - read.y).abs() < 1e-6, "{angle} {read}");
    }

    /// The typo on a wall facing +Z puts `nt.z` into y: the flat normal leans 45° up; on a
    /// floor facing +Y (N.z = 0) it loses its normal part and lies in the floor.
    #[test]
    fn the_tbn_typo_leans_walls_up_and_flattens_floors() {
        let wall = to_world(Mistake::TbnTypo, Vec3::X, Vec3::Y, Vec3::Z, Vec3::Z);
        assert!((wall - Vec3::new(0.0, 1.0, 1.0).normalize()).length() < 1e-6, "{wall}");
        let nt = Vec3::new(0.2, 0.1, 0.97).normalize();
        let floor = to_world(Mistake::TbnTypo, Vec3::X, -Vec3::Z, Vec3::Y, nt);
        assert!(floor.y.abs() < 1e-6, "{floor}");
    }
}
