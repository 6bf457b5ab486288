//! The chain's detail step: the material's detail normal map read at the UV times its tiling,
//! decoded and scaled by its strength, and blended with the base normal map's tangent-space
//! normal by the method in use ([`crate::shading::detail_blend`]) — the twin of
//! `detailed_normal` in `shaders/detail.wgsl`.

use glam::{Vec2, Vec3};

use super::fragment::{Footprint, Fragment, Map};
use crate::frame::{DetailBlend, ShadingSettings};
use crate::scene::{Material, NormalConvention};
use crate::shading::detail_blend::blend;
use crate::shading::{NormalTexel, decode_normal, tangent_space_normal};

/// The detail step at one point, tangent space.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DetailValues {
    /// The method in use: the frame's override, else the material's.
    pub method: DetailBlend,
    /// The base normal map's normal after its strength.
    pub base: Vec3,
    /// The detail map's normal after its strength.
    pub detail: Vec3,
    /// The two blended: what goes to world space.
    pub blended: Vec3,
}

/// The material's detail map's filtered RGB at `uv` (the base UV after parallax) with
/// `footprint`, read at the UV times its tiling; `None` without a detail map bound.
pub fn read(material: &Material, fragment: &impl Fragment, uv: Vec2, footprint: Footprint) -> Option<Vec3> {
    let detail = material.detail_map?;
    let tiled = footprint.map(|(dx, dy)| (dx * detail.tiling, dy * detail.tiling));
    fragment.sample(Map::Detail, detail.uv(uv), tiled).map(|t| t.truncate())
}

/// The detail step for the base tangent-space normal `base` and the detail map's filtered RGB
/// `texel`; `None` without either (then the base normal is drawn as it is).
pub fn values(
    material: &Material,
    texel: Option<Vec3>,
    base: Option<Vec3>,
    shading: &ShadingSettings,
) -> Option<DetailValues> {
    let map = material.detail_map?;
    let (texel, base) = (texel?, base?);
    let decoded = decode_normal(NormalTexel::rgb(texel), NormalConvention::default());
    let detail = tangent_space_normal(decoded, map.strength);
    let method = shading.detail_blend.unwrap_or(map.blend);
    Some(DetailValues { method, base, detail, blended: blend(method, base, detail) })
}
