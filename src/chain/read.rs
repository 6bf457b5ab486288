//! The fragment stage's texture reads, after the parallax step: every texture the lighting
//! reads, at the UV the step leaves and with its footprint, and the vertex outputs the
//! lighting takes as they are ([`SurfaceSample`]). The sampling itself is the reader's
//! ([`Fragment::sample`]); which texture is read where, and the height rules (16 bits in R, G;
//! a depth map flipped), are the shader's, here.

use glam::{Mat3, Vec2, Vec3, Vec4};

use super::fragment::{Footprint, Fragment, Map, Varyings};
use super::legacy::EmbossSample;
use super::parallax::ConeTexel;
use crate::frame::{BumpKind, FrameParams, LightingSpace};
use crate::height::cone::decode_cone_ratio;
use crate::scene::Material;
use crate::shading::spaces::triangle_inverse_tbn;
use crate::shading::{NormalTexel, height_sample};

/// What the lighting reads at one surface point: the vertex outputs and the filtered texture
/// samples.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SurfaceSample {
    /// World-space position, metres.
    pub position: Vec3,
    /// The interpolated vertex normal taken by the normal matrix (not normalised).
    pub world_normal: Vec3,
    /// Whether the point is on a front face (else a back face of a double-sided material).
    pub front_facing: bool,
    /// The interpolated tangent taken by the model matrix, its `w` times `sign(det(model))`;
    /// `None` where the mesh is drawn without a tangent stream.
    pub world_tangent: Option<Vec4>,
    /// The normal matrix (inverse-transpose of the model matrix): object-space maps need it.
    pub normal_matrix: Mat3,
    /// The filtered base colour texture, linear; `None` without one (white).
    pub base_color: Option<Vec3>,
    /// The bump texture's reading, by the instance's [`BumpKind`]; `None` without a bump.
    pub bump: Option<BumpSample>,
    /// The filtered metallic-roughness texture (B metal, G rough); `None` without one.
    pub metallic_roughness: Option<Vec3>,
    /// The occlusion texture's red; `None` without one.
    pub occlusion: Option<f32>,
    /// The filtered gloss (specular) map; `None` without one.
    pub gloss: Option<Vec3>,
    /// The filtered emissive texture, linear; `None` without one.
    pub emissive: Option<Vec3>,
    /// The clear-coat textures at the layer's coordinates: strength (red), roughness
    /// (green), the normal map's RGB; `None` where the material has none.
    pub clearcoat: Option<f32>,
    pub clearcoat_roughness: Option<f32>,
    pub clearcoat_normal: Option<Vec3>,
    /// The per-vertex light direction and half vector ([`super::legacy::vertex_vectors`]),
    /// interpolated (perspective-correct) as the vertex stage passes them on.
    pub vertex_light: Vec3,
    pub vertex_half: Vec3,
    /// The height map's neighbours for the emboss look; `None` where no height map is bound
    /// (only normal-mapped surfaces with a height map, uploaded for parallax or emboss).
    pub emboss: Option<EmbossSample>,
    /// The triangle's inverse frame (world → tangent space) for tangent-space lighting
    /// ([`triangle_inverse_tbn`] from the quad derivatives of the position and the
    /// interpolated UV, as the tangent-space pipeline takes it); `None`: the inverse of the
    /// point's own T, B, N (lit in another space, or no derivatives).
    pub triangle_frame: Option<Mat3>,
    /// The detail normal map's filtered RGB at the UV times its tiling
    /// ([`super::detail::read`]); `None` where none is bound.
    pub detail: Option<Vec3>,
}

/// What the bump texture gives at a point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BumpSample {
    /// The normal map's filtered texel (and X-Ray's `bump#`), linear (tangent- or
    /// object-space maps).
    NormalMap(NormalTexel),
    /// Screen-space derivatives for Blinn's bump from the height map: of the position
    /// (metres per pixel, world space) and of the decoded height sample ([`height_sample`],
    /// full range per pixel, before the depth flip, range and strength).
    HeightSlopes { dp_dx: Vec3, dp_dy: Vec3, dh_dx: f32, dh_dy: f32 },
}

/// The material's height map at `uv` with `footprint` ([`Map::Height`]): 0..1, white = high,
/// a depth map flipped (`1 − sample`); 0 where none is bound.
pub fn relief_height(material: &Material, fragment: &impl Fragment, uv: Vec2, footprint: Footprint) -> f32 {
    let sample = fragment.sample(Map::Height, uv, footprint).map_or(0.0, |t| height_sample(t.truncate()));
    if material.height_map.as_ref().is_some_and(|h| h.depth) { 1.0 - sample } else { sample }
}

/// What relaxed cone stepping reads of the height texture at `uv`: level 0, filtered, the
/// height as [`relief_height`] decodes it and the cone ratio the prepare stage packed into
/// blue ([`decode_cone_ratio`]).
pub fn relief_cone(material: &Material, fragment: &impl Fragment, uv: Vec2) -> ConeTexel {
    let ratio = fragment.sample(Map::Height, uv, None).map_or(0.0, |t| decode_cone_ratio(t.z));
    ConeTexel { height: relief_height(material, fragment, uv, None), ratio }
}

/// Every texture the lighting of an instance bumped by `bump` reads at `uv` (the UV after
/// parallax) with `footprint` (its derivatives), and the vertex outputs `at`; `n` is the unit
/// geometric normal facing the viewer's side.
pub fn read(
    bump: BumpKind,
    material: &Material,
    fragment: &impl Fragment,
    at: &Varyings,
    (uv, footprint): (Vec2, Footprint),
    n: Vec3,
    frame: &FrameParams,
) -> SurfaceSample {
    let sample = |map| fragment.sample(map, uv, footprint);
    let rgb = |map| sample(map).map(Vec4::truncate);
    let bump = match bump {
        BumpKind::TangentSpace | BumpKind::ObjectSpace => sample(Map::Bump)
            .map(|rgba| BumpSample::NormalMap(NormalTexel { rgba, correction: rgb(Map::BumpCorrection) })),
        BumpKind::HeightInShader => fragment.size(Map::Bump).and_then(|_| {
            // Every pixel of the quad samples at its own UV with the quad's footprint.
            let height =
                |v: &Varyings| fragment.sample(Map::Bump, v.uv, footprint).map_or(0.0, |t| height_sample(t.truncate()));
            let (dx, dy) = fragment.derivatives(|v| v.position.extend(height(v)))?;
            Some(BumpSample::HeightSlopes { dp_dx: dx.truncate(), dp_dy: dy.truncate(), dh_dx: dx.w, dh_dy: dy.w })
        }),
        BumpKind::None => None,
    };
    // The clear coat's textures at the layer's coordinates; the footprint through the linear
    // part of its transform.
    let coat = |map| {
        let coat = material.clearcoat.as_ref()?;
        let linear =
            |d: Vec2| Vec2::new(coat.uv_transform[0].truncate().dot(d), coat.uv_transform[1].truncate().dot(d));
        let coat_footprint = footprint.map(|(dx, dy)| (linear(dx), linear(dy)));
        fragment.sample(map, coat.layer_uv(uv), coat_footprint).map(Vec4::truncate)
    };
    // The emboss look's height neighbours one texel apart at mip 0, where a height map is bound.
    let emboss = fragment.size(Map::Height).map(|size| {
        let texel = size.as_vec2().recip();
        let height = |offset: Vec2| relief_height(material, fragment, uv + offset, None);
        EmbossSample {
            left: height(Vec2::new(-texel.x, 0.0)),
            right: height(Vec2::new(texel.x, 0.0)),
            up: height(Vec2::new(0.0, -texel.y)),
            down: height(Vec2::new(0.0, texel.y)),
        }
    });
    let triangle_frame = (frame.shading.lighting_space == LightingSpace::Tangent)
        .then(|| fragment.derivatives(|v| v.position).zip(fragment.derivatives(|v| v.uv)))
        .flatten()
        .map(|((dp_dx, dp_dy), (duv_dx, duv_dy))| triangle_inverse_tbn(dp_dx, dp_dy, duv_dx, duv_dy, n));
    SurfaceSample {
        position: at.position,
        world_normal: at.world_normal,
        front_facing: fragment.front_facing(),
        world_tangent: at.world_tangent,
        normal_matrix: fragment.normal_matrix(),
        base_color: rgb(Map::BaseColor),
        bump,
        metallic_roughness: rgb(Map::MetallicRoughness),
        occlusion: rgb(Map::Occlusion).map(|t| t.x),
        gloss: rgb(Map::Gloss),
        emissive: rgb(Map::Emissive),
        clearcoat: coat(Map::Clearcoat).map(|t| t.x),
        clearcoat_roughness: coat(Map::ClearcoatRoughness).map(|t| t.y),
        clearcoat_normal: coat(Map::ClearcoatNormal),
        vertex_light: at.vertex_light,
        vertex_half: at.vertex_half,
        emboss,
        triangle_frame,
        detail: super::detail::read(material, fragment, uv, footprint),
    }
}
