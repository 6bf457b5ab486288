//! The chain's normal-map mip filtering step ([`crate::shading::mip_filter`], the twin of
//! `shaders/mip_filter.wgsl`): what the instance's method adds to `α²` at the point and the
//! exponent and roughness it widens, with the level of detail the normal map is read at.

use glam::{Vec3, Vec4};

use super::fragment::{Footprint, Fragment, Map};
use crate::shading::NormalTexel;
use crate::shading::mip_filter::{
    alpha_variance, lean_fade, lean_normal, lean_variance, widened_roughness, widened_shininess,
};
use crate::texture::MipFilter;

/// What the mip filtering step takes besides the texel: the method, the screen-space
/// derivatives of the shading normal (geometric specular AA only; `None` otherwise or without
/// a quad), the normal map's level of detail and, for LEAN, its moments filtered at the point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MipInputs {
    pub filter: MipFilter,
    pub normal_derivatives: Option<(Vec3, Vec3)>,
    pub lod: Option<f32>,
    /// LEAN's texture `(Bx, By, Bx², By²)` read where the normal map is
    /// ([`Fragment::lean_moments`]); `None` for the other methods.
    pub moments: Option<Vec4>,
}

impl MipInputs {
    /// No filtering (the plain chain: the neighbours geometric specular AA differentiates).
    pub const NONE: MipInputs =
        MipInputs { filter: MipFilter::RenormalizedBox, normal_derivatives: None, lod: None, moments: None };
}

/// The mip filtering step's values at one point (the probe's readout).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MipValues {
    /// The instance's method.
    pub filter: MipFilter,
    /// The level of detail the normal map's footprint asks for (`log2` of its longer side in
    /// level-0 texels; below 0 magnified, read at level 0); `None` without a normal map or a
    /// footprint.
    pub lod: Option<f32>,
    /// `|Na|`, the filtered texel's alpha for the methods that keep it ([`MipFilter::keeps_length`]),
    /// else 1.
    pub length: f32,
    /// What the method adds to `α²` ([`alpha_variance`]; LEAN: `strength² ×`
    /// [`lean_fade`]`(lod) ×` [`lean_variance`] of its moments); 0 without widening.
    pub variance: f32,
    /// The classic exponent after widening and the factor on `k_s` that keeps the lobe's
    /// energy ([`widened_shininess`]).
    pub shininess: f32,
    pub energy: f32,
    /// The perceptual roughness after widening ([`widened_roughness`]) where the point is
    /// lit by metallic-roughness; `None` under the classic model.
    pub roughness: Option<f32>,
}

impl MipValues {
    /// The values at a point read with `texel` (`None`: no normal map), the bump `strength`,
    /// the bump on or off, the unwidened `shininess` and, under metallic-roughness, the
    /// unwidened perceptual `roughness`.
    pub fn new(
        inputs: MipInputs,
        texel: Option<NormalTexel>,
        (strength, bump_on): (f32, bool),
        shininess: f32,
        roughness: Option<f32>,
    ) -> Self {
        let filter = inputs.filter;
        let length = texel.filter(|_| filter.keeps_length()).map_or(1.0, |t| t.rgba.w);
        let variance = match inputs.moments.filter(|_| filter == MipFilter::Lean && bump_on && texel.is_some()) {
            Some(moments) => strength * strength * lean_fade(inputs.lod.unwrap_or(0.0)) * lean_variance(moments),
            None => alpha_variance(filter, length, strength, bump_on, inputs.normal_derivatives),
        };
        let (shininess, energy) = widened_shininess(filter, shininess, variance);
        let roughness = roughness.map(|r| widened_roughness(r, variance));
        MipValues { filter, lod: inputs.lod, length, variance, shininess, energy, roughness }
    }
}

/// The normal map's texel as LEAN reads it: its RGB faded by [`lean_fade`] at the point's
/// level of detail to the mean-slope normal of the moments ([`lean_normal`], encoded `n·½ + ½`
/// as the map stores normals) — the map's own texel under magnification, the mean slope's
/// from level 1 on — so that the convention, the bump strength and the rest of the normal-map
/// path apply to it as to any texel (the twin of lean.wgsl's `lean_texel`); unchanged without
/// moments.
pub fn lean_texel(texel: NormalTexel, inputs: &MipInputs) -> NormalTexel {
    match inputs.moments.filter(|_| inputs.filter == MipFilter::Lean) {
        Some(moments) => {
            let fade = lean_fade(inputs.lod.unwrap_or(0.0));
            let rgb = texel.rgba.truncate().lerp(lean_normal(moments) * 0.5 + 0.5, fade);
            NormalTexel { rgba: rgb.extend(texel.rgba.w), ..texel }
        }
        None => texel,
    }
}

/// The normal map's level of detail at `footprint`, as the sampler takes it: `log2` of the
/// longer of the footprint's derivatives in level-0 texels.
pub fn normal_map_lod(fragment: &impl Fragment, footprint: Footprint) -> Option<f32> {
    let size = fragment.size(Map::Bump)?.as_vec2();
    let (dx, dy) = footprint?;
    Some((dx * size).length().max((dy * size).length()).log2()).filter(|lod| lod.is_finite())
}
