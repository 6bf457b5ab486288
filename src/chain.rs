//! The one CPU shading chain: the twin of the fragment stage of `shaders/mesh.wgsl` (with
//! `parallax.wgsl`, `mistakes.wgsl`, `legacy.wgsl`, `lights.wgsl`, `pbr.wgsl`), step by step,
//! returning every intermediate value. [`shade`] takes what the fragment shader gets — the
//! interpolated vertex outputs and a texture sampler with quad derivatives, a [`Fragment`] —
//! and runs the same formulas ([`crate::shading`]) in the same order: the parallax march and
//! the UV it shifts ([`parallax`]), the texture reads there, the geometric normal, the tangent
//! frame, the bump by the instance's [`BumpKind`] (the classic [`mistakes`] beside the right
//! path), every light dimmed by the relief's soft shadow and lit in the frame's
//! [`ShadingMode`] with the material's (or the overriding) shading model (or a [`legacy`]
//! look), and the colour the frame's [`ViewMode`] stores. The pixel probe, the report and the
//! CPU reference tests call it; none of them holds a shading step of its own.
//!
//! Spaces and units follow the crate conventions: positions in metres, world space; vectors
//! unit length, world space unless named tangent space; colours linear RGB 0..1 unless named
//! stored (what the target holds: sRGB-encoded for the lit picture, `0.5·v + 0.5` for
//! vector views).

pub mod detail;
pub mod fragment;
pub mod legacy;
mod lit;
mod mip;
pub mod mistakes;
pub mod parallax;
mod read;
mod relief;

pub use detail::DetailValues;
pub use fragment::{Footprint, Fragment, Map, Varyings};
pub use mip::{MipInputs, MipValues};
pub use relief::MarchValues;

use glam::Vec3;

use crate::frame::{BumpKind, FrameParams, LightingSpace};
use crate::math::normalize_or;
use crate::scene::{MAX_LIGHTS, Material, ShadingModel};
use crate::shading::NormalTexel;
use crate::texture::MipFilter;

/// Every value along the chain at one point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ChainValues {
    /// The parallax step ([`MarchValues`]); `None`: parallax off, depth 0, no height map bound,
    /// or no quad derivatives. The textures are read at its shifted UV.
    pub march: Option<MarchValues>,
    /// The normal map's filtered texel as read (RGBA 0..1 linear, with X-Ray's `bump#`),
    /// before any mistake; `None` without a normal map.
    pub texel: Option<NormalTexel>,
    /// The decoded normal-map vector ([`decode_normal`]): tangent space, or model space for an
    /// object-space map. `None` without a normal map.
    pub decoded: Option<Vec3>,
    /// The effective strength: the frame's strength times the material's `normalTexture.scale`
    /// (the height bump uses the frame's strength alone).
    pub strength: f32,
    /// Tangent-space normal after strength, `normalize(x·s, y·s, max(z, 0))` (tangent-space
    /// maps only).
    pub after_strength: Option<Vec3>,
    /// The detail step ([`DetailValues`]: base, detail and blended tangent-space normals);
    /// `None` without a detail map. Its blended normal is what goes to world space.
    pub detail: Option<DetailValues>,
    /// World-space tangent after Gram-Schmidt against `normal`, bitangent `w · cross(N, T)`,
    /// handedness `w = ±1`; `None` without a tangent stream.
    pub tangent: Option<Vec3>,
    pub bitangent: Option<Vec3>,
    pub w: Option<f32>,
    /// The geometric normal, facing the viewer's side on a double-sided back face.
    pub normal: Vec3,
    /// The normal used for lighting.
    pub shading_normal: Vec3,
    /// The clear-coat layer's normal (its normal map through T, B, N; else `normal`).
    pub clearcoat_normal: Vec3,
    /// Unit direction from the point to the eye.
    pub view_dir: Vec3,
    /// The per-vertex light direction as interpolated (the surface sample's `vertex_light`), and
    /// the light vector DOT3 lit with: that one, or it through the normalization cube map;
    /// `None` outside DOT3.
    pub vertex_light: Vec3,
    pub dot3_light: Option<Vec3>,
    /// Each of the frame's lights at the point, in the frame's order; `None` for a light
    /// that is off and past the last light. Under the per-vertex mistakes the first light
    /// that is on has the direction and half vector the mistake sees
    /// ([`mistakes::seen_light_direction`], [`mistakes::seen_view_direction`]).
    pub lights: [Option<LightTerms>; MAX_LIGHTS],
    /// Linear albedo: base colour texture times the factor.
    pub albedo: Vec3,
    /// The model the point is lit with (the frame's override, else the material's).
    pub shading_model: ShadingModel,
    /// The space the point is lit in: the frame's for the classic model on tangent-space
    /// normal-mapped surfaces with a tangent frame, else world space.
    pub lighting_space: LightingSpace,
    /// The normal map's mip filtering at the point ([`MipValues`]): the method, the level of
    /// detail, `|Na|`, and the exponent or roughness it widens to.
    pub mip: MipValues,
    /// The lit colour in the frame's shading mode, linear RGB.
    pub color_linear: Vec3,
    /// What the frame's view stores, 0..1; `None` for the Difference and UV check views,
    /// which need screen-space data of a whole triangle.
    pub shown: Option<Vec3>,
}

/// One light at one point of the chain.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LightTerms {
    /// Unit direction from the point to the light, and its half vector with the view direction.
    pub direction: Vec3,
    pub half: Vec3,
    /// `N·L`, `N·H` and `R·V` (`R = 2(N·L)N − L`) with the shading normal, signed (the
    /// shading uses `max(·, 0)`).
    pub n_dot_l: f32,
    pub n_dot_h: f32,
    pub r_dot_v: f32,
    /// The geometric self-shadow fade `smoothstep(0, SELF_SHADOW_FADE, N_geo·L)`, 0..1.
    pub self_shadow: f32,
    /// The distance attenuation (1 for a directional light) and the radiance arriving,
    /// `color · intensity · attenuation`, linear RGB.
    pub attenuation: f32,
    pub radiance: Vec3,
}

/// The fragment stage at `fragment` on an instance bumped by `bump`, drawn with `material`
/// under `frame` (whose lights carry the ambient light), in the shader's order: the parallax
/// step (the UV and footprint the textures are read with), the texture reads, the frame, the
/// bump, every light dimmed by the relief's soft shadow, and the colour the view stores.
pub fn shade(bump: BumpKind, material: &Material, fragment: &impl Fragment, frame: &FrameParams) -> ChainValues {
    let at = fragment.varyings();
    let facing = if fragment.front_facing() { 1.0 } else { -1.0 };
    let step = relief::step(material, fragment, &at, facing, frame);
    let n = normalize_or(at.world_normal, Vec3::Z) * facing;
    let surface = read::read(bump, material, fragment, &at, (step.uv, step.footprint), n, frame);
    let (dimmed, visibility) = relief::shadowed(material, fragment, &step, at.position, frame);
    let filter = fragment.mip_filter();
    // Geometric specular AA differentiates the shading normal over the quad: each pixel's own
    // chain up to its normal (its own UV, without the parallax shift).
    let normal_derivatives = (filter == MipFilter::GeometricSpecularAa)
        .then(|| {
            fragment.derivatives(|v| {
                let n = normalize_or(v.world_normal, Vec3::Z) * facing;
                let surface = read::read(bump, material, fragment, v, (v.uv, step.footprint), n, frame);
                lit::lit(bump, material, &surface, frame, MipInputs::NONE).shading_normal
            })
        })
        .flatten();
    let lod = mip::normal_map_lod(fragment, step.footprint).filter(|_| surface.bump.is_some());
    let moments = (filter == MipFilter::Lean).then(|| fragment.lean_moments(step.uv, step.footprint)).flatten();
    let inputs = MipInputs { filter, normal_derivatives, lod, moments };
    let values = lit::lit(bump, material, &surface, &dimmed, inputs);
    ChainValues { march: relief::values(material, fragment, &step, visibility, &values), ..values }
}
