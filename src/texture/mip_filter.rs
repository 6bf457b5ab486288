//! How a normal map is filtered at a distance: what its mip chain holds and how the
//! highlight is widened from it. A scene option (`crate::frame::SceneOptions::mip_filter`; the
//! enum is imported from `crate::texture` only) — it decides what is baked and uploaded — and a
//! pipeline variant (the `MIP_FILTER` constant, shaders/mip_filter.wgsl). Here, in the data
//! layer, because the mip chains ([`super::TextureImage::mip_chain_filtered`]) depend on it;
//! the formulas are `crate::shading::mip_filter`'s; docs/mip-filtering.md lists them with
//! their sources.

/// The mip-filtering method of normal maps. Named (as on the command line and in presets)
/// `base-only`, `renormalized-box`, `toksvig`, `lean`, `vmf`, `geometric-specular-aa`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, strum::IntoStaticStr, strum::VariantArray)]
#[strum(serialize_all = "kebab-case")]
pub enum MipFilter {
    /// No mips on the normal map (one level, so the sampler reads level 0 at every distance):
    /// the aliasing itself.
    BaseOnly,
    /// 2×2 box-filtered mips, each averaged normal re-normalised: what most viewers do, and
    /// the default.
    #[default]
    RenormalizedBox,
    /// Toksvig (NVIDIA technical brief 2004; JGT 2005): the averaged normal's length `|Na|`
    /// is kept per mip and widens the lobe, `s′ = |Na|·s / (|Na| + s·(1 − |Na|))`.
    Toksvig,
    /// LEAN mapping (Olano & Baker, I3D 2010): first and second slope moments in a linearly
    /// filterable half-float texture; the normal from the mean slope, the lobe widened by the
    /// filtered covariance's trace.
    Lean,
    /// Roughness from normal variance by a von Mises–Fisher fit (Neubelt & Pettineo 2013 as
    /// corrected by Karis 2018): `κ = (3|Na| − |Na|³) / (1 − |Na|²)`, `α′ = √(α² + 2/κ)`.
    Vmf,
    /// Geometric specular antialiasing (Kaplanyan et al. HPG 2016; Tokuyoshi & Kaplanyan
    /// 2019 as Filament adopted it): plain mips, the roughness widened from the screen-space
    /// derivatives of the shading normal.
    GeometricSpecularAa,
}

impl MipFilter {
    /// The index the `MIP_FILTER` pipeline constant takes (shaders/mip_filter.wgsl).
    pub fn shader_index(self) -> u32 {
        self as u32
    }

    /// Whether the normal map keeps mip levels past level 0 ([`MipFilter::BaseOnly`] does not).
    pub fn has_mips(self) -> bool {
        self != MipFilter::BaseOnly
    }

    /// Whether each mip stores the averaged normal's length `|Na|` (in the normal map's alpha)
    /// for the shader to widen the lobe with (Toksvig, vMF).
    pub fn keeps_length(self) -> bool {
        matches!(self, MipFilter::Toksvig | MipFilter::Vmf)
    }

    /// Whether the method widens the highlight in the shader (Toksvig, LEAN, vMF, geometric
    /// specular AA): only these get a `MIP_FILTER` pipeline variant of their own.
    pub fn widens(self) -> bool {
        !matches!(self, MipFilter::BaseOnly | MipFilter::RenormalizedBox)
    }

    /// Whether the method reads LEAN's texture of slope moments (made and uploaded only then,
    /// `PreparedScene::lean_texture`).
    pub fn reads_moments(self) -> bool {
        self == MipFilter::Lean
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::names::Named;

    /// The shader's `MIP_` constants are these indices (names: tests/names.rs).
    #[test]
    fn shader_indices_follow_the_declaration_order() {
        let indices: Vec<u32> = MipFilter::all().iter().map(|m| m.shader_index()).collect();
        assert_eq!(indices, [0, 1, 2, 3, 4, 5]);
        assert_eq!(MipFilter::default(), MipFilter::RenormalizedBox);
    }
}
