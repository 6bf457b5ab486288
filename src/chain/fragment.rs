//! What the fragment stage reads besides the frame's uniforms: the vertex stage's outputs
//! interpolated at the point ([`Varyings`], the WGSL `VertexOutput` / `PerVertexOutput`), and
//! what the GPU gives a fragment ([`Fragment`]): the textures bound to the instance, filtered
//! by their samplers, and screen-space derivatives over the fragment's 2×2 pixel quad.
//!
//! The pixel probe implements [`Fragment`] with the GPU's trilinear filtering and the quad the
//! rasteriser shades; the report and the tests implement it with their own simpler readings.
//! [`crate::chain::shade`] decides what is read where, as the shader does.

use std::ops::Sub;

use glam::{Mat3, UVec2, Vec2, Vec3, Vec4};

use crate::texture::MipFilter;

/// The vertex stage's outputs at one point, interpolated perspective-correct.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Varyings {
    /// World-space position, metres.
    pub position: Vec3,
    /// The vertex normal taken by the normal matrix (not normalised).
    pub world_normal: Vec3,
    /// Texture coordinates (crate conventions: origin top-left, v down).
    pub uv: Vec2,
    /// The tangent taken by the model matrix, its `w` times `sign(det(model))`; `None` where
    /// the mesh is drawn without a tangent stream.
    pub world_tangent: Option<Vec4>,
    /// The per-vertex light direction and half vector ([`crate::chain::legacy::vertex_vectors`]).
    pub vertex_light: Vec3,
    pub vertex_half: Vec3,
}

/// A texture slot of the instance, as the shader binds it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Map {
    /// Base colour (sRGB, read linear; the base-colour sampler).
    BaseColor,
    /// The bump slot: the normal map (tangent- or object-space), or the height map of the
    /// height bump in the shader (16 bits in R, G).
    Bump,
    /// X-Ray's `bump#` beside the normal map.
    BumpCorrection,
    MetallicRoughness,
    Occlusion,
    Gloss,
    /// Emitted colour (sRGB, read linear; the base-colour sampler).
    Emissive,
    Clearcoat,
    ClearcoatRoughness,
    ClearcoatNormal,
    /// The height map the parallax family marches and the emboss look reads (16 bits in R, G).
    Height,
    /// The material's detail normal map (linear RGB, the detail sampler), read at the UV times
    /// its tiling ([`crate::scene::DetailMap::uv`]).
    Detail,
}

/// A texture read's footprint: the derivatives of its UV per pixel along x and y (the level
/// of detail comes from them); `None`: mip level 0.
pub type Footprint = Option<(Vec2, Vec2)>;

/// What the GPU gives one fragment: its interpolated inputs, its facing, the instance's normal
/// matrix, quad derivatives and filtered texture reads.
pub trait Fragment {
    /// The vertex stage's outputs at the fragment.
    fn varyings(&self) -> Varyings;
    /// Whether the fragment is on a front face (else a back face of a double-sided material).
    fn front_facing(&self) -> bool;
    /// The instance's normal matrix (inverse-transpose of the model matrix).
    fn normal_matrix(&self) -> Mat3;
    /// Fine screen-space derivatives of `value` of the varyings at the fragment: the difference
    /// across the quad along the fragment's row (`d/dx`) and column (`d/dy`), every pixel of
    /// the quad running `value` on its own varyings (as `dpdx`, `dpdy` and the implicit
    /// derivatives of `textureSample`). `None` where they are not known (a plane seen edge-on,
    /// or a reader without a pixel grid).
    fn derivatives<T: Sub<Output = T> + Copy>(&self, value: impl Fn(&Varyings) -> T) -> Option<(T, T)>;
    /// `map` filtered at `uv` with `footprint`, RGBA 0..1 linear (colour maps decoded from
    /// sRGB); `None` where the instance binds no texture there.
    fn sample(&self, map: Map, uv: Vec2, footprint: Footprint) -> Option<Vec4>;
    /// Level 0's size in texels of `map`; `None` where the instance binds no texture there.
    fn size(&self, map: Map) -> Option<UVec2>;
    /// How the instance's normal map is mip-filtered as drawn (its `MIP_FILTER` pipeline
    /// constant and mip chain, [`crate::prepare::PreparedInstance::mip_filter`]); readers
    /// without one draw today's re-normalised box mips.
    fn mip_filter(&self) -> MipFilter {
        MipFilter::RenormalizedBox
    }
    /// LEAN's texture (`(Bx, By, Bx², By²)`, [`crate::texture::LeanTexels`]) filtered at `uv`
    /// with `footprint` through the normal map's sampler, where the instance draws LEAN;
    /// `None` elsewhere (readers without it draw the other methods).
    fn lean_moments(&self, _uv: Vec2, _footprint: Footprint) -> Option<Vec4> {
        None
    }
}
