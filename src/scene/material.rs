//! Materials and their texture slots, with the conventions a slot's texture follows
//! (normal-map convention, height-map settings, sampler wrap modes) and the shading model.

use glam::{Vec3, Vec4};

use super::{TextureImage, decode_height};
use crate::height::{Border, HeightField, Kernel};
use crate::texture::compressed::{Stored, StoredChannels};

/// Metres one UV unit spans for a texture from a file (files carry no unit; the built-in
/// bricks use the same, [`super::builtin::BRICK_TILE_M`]).
pub const TEXTURE_SPAN_M: f32 = 1.0;

/// Which way a tangent-space normal map's green channel points. Named `opengl`, `directx`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, strum::IntoStaticStr, strum::VariantArray)]
#[strum(serialize_all = "lowercase")]
pub enum GreenAxis {
    /// +Y = green = up the image (OpenGL, Blender, glTF): the crate convention.
    #[default]
    OpenGl,
    /// +Y = green = down the image (DirectX, Unreal, 3ds Max): green is flipped on decode.
    DirectX,
}

impl GreenAxis {
    /// Name for people (panel, labels, captions).
    pub fn label(self) -> &'static str {
        match self {
            GreenAxis::OpenGl => "OpenGL (+Y)",
            GreenAxis::DirectX => "DirectX (−Y)",
        }
    }
}

/// The space a normal map's vectors are in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum NormalSpace {
    /// Tangent space: `x` along T, `y` along B, `z` along the geometric normal.
    #[default]
    Tangent,
    /// Object (model) space: the decoded vector is a model-space normal, taken to world space
    /// by the normal matrix (inverse-transpose of the model matrix). No tangents are needed.
    Object,
}

/// Which channels of a normal map hold the vector ([`crate::shading::unpack_normal`]). Named
/// `rgb`, `rg`, `ag`, `xray` (command line `--normal-layout`, presets `normal_layout`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, strum::IntoStaticStr, strum::VariantArray)]
#[strum(serialize_all = "lowercase")]
pub enum NormalLayout {
    /// x, y, z in red, green, blue: `2·rgb − 1`.
    #[default]
    Rgb,
    /// Two-channel (BC5): x in red, y in green, `z = sqrt(max(0, 1 − x² − y²))` with `(x, y)`
    /// scaled back onto the unit circle where `x² + y² > 1`. What `bake --two-channel` writes.
    Rg,
    /// DXT5nm: x in alpha, y in green, z rebuilt as for [`NormalLayout::Rg`].
    Ag,
    /// X-Ray's (S.T.A.L.K.E.R.) pair: the `bump` texture holds x in alpha, y in blue, z in
    /// green and the gloss in red (gloss = red², scaling k_s); the optional `bump#` texture
    /// ([`NormalMap::correction`]) holds a compression-error correction in RGB (and the height
    /// in alpha, unused here). The vector is `bump.agb + bump#.rgb − 1`, each part a signed
    /// half range, so the sum lies in [−1, 1]; without `bump#` the correction is 0.5 (none).
    Xray,
}

impl NormalLayout {
    /// Name for people (panel, labels, captions).
    pub fn label(self) -> &'static str {
        match self {
            NormalLayout::Rgb => "RGB",
            NormalLayout::Rg => "RG (two-channel, BC5)",
            NormalLayout::Ag => "AG (DXT5nm)",
            NormalLayout::Xray => "X-Ray pair (bump + bump#)",
        }
    }
}

/// How a normal map's texels decode to a unit vector (crate conventions: linear, by the
/// channel layout). The shader receives it as [`NormalConvention::flags`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct NormalConvention {
    pub green: GreenAxis,
    pub layout: NormalLayout,
    pub space: NormalSpace,
}

impl NormalConvention {
    /// Bit of [`NormalConvention::flags`]: green is flipped (DirectX).
    pub const FLIP_GREEN: u32 = 1;
    /// Bit of [`NormalConvention::flags`]: the RG layout (z is reconstructed from x and y).
    pub const LAYOUT_RG: u32 = 2;
    /// Bit of [`NormalConvention::flags`]: object-space map.
    pub const OBJECT_SPACE: u32 = 4;
    /// Bit of [`NormalConvention::flags`]: the AG (DXT5nm) layout.
    pub const LAYOUT_AG: u32 = 1 << 15;
    /// Bit of [`NormalConvention::flags`]: the X-Ray pair layout.
    pub const LAYOUT_XRAY: u32 = 1 << 16;

    /// The convention bits of the shader's `object.flags`.
    pub fn flags(self) -> u32 {
        let mut flags = 0;
        if self.green == GreenAxis::DirectX {
            flags |= Self::FLIP_GREEN;
        }
        flags |= match self.layout {
            NormalLayout::Rgb => 0,
            NormalLayout::Rg => Self::LAYOUT_RG,
            NormalLayout::Ag => Self::LAYOUT_AG,
            NormalLayout::Xray => Self::LAYOUT_XRAY,
        };
        if self.space == NormalSpace::Object {
            flags |= Self::OBJECT_SPACE;
        }
        flags
    }

    /// A short description for the panel, e.g. "OpenGL (+Y), tangent space".
    pub fn describe(self) -> String {
        let green = self.green.label();
        let space = match self.space {
            NormalSpace::Tangent => "tangent space",
            NormalSpace::Object => "object space",
        };
        let channels = match self.layout {
            NormalLayout::Rgb => String::new(),
            layout => format!(", {}", layout.label()),
        };
        format!("{green}{channels}, {space}")
    }
}

/// A normal map slot with its glTF `scale` (bump strength multiplier) and its convention.
#[derive(Debug, Clone, PartialEq)]
pub struct NormalMap {
    pub texture: usize,
    pub scale: f32,
    pub convention: NormalConvention,
    /// X-Ray's `bump#` texture (linear: RGB the compression-error correction, A the height),
    /// read only in the [`NormalLayout::Xray`] layout.
    pub correction: Option<usize>,
    /// What the texture file's format says about its channels (DDS, KTX2); `None` for other
    /// images. [`NormalMap::with_stored`] takes the layout from it.
    pub stored: Option<Stored>,
}

impl NormalMap {
    /// A tangent-space OpenGL-convention RGB normal map with `scale`.
    pub fn new(texture: usize, scale: f32) -> NormalMap {
        NormalMap { texture, scale, convention: NormalConvention::default(), correction: None, stored: None }
    }

    /// The map read in the layout its file's format states: RG for two channels (BC5, R8G8,
    /// two-channel UASTC), AG for DXT5nm; other formats keep the layout as it is.
    pub fn with_stored(mut self, stored: Option<&Stored>) -> NormalMap {
        if let Some(stored) = stored {
            if let Some(layout) = stored_layout(stored) {
                self.convention.layout = layout;
            }
            self.stored = Some(stored.clone());
        }
        self
    }

    /// An X-Ray pair: `bump` (normal in A, B, G; gloss in R) and the optional `bump#`.
    pub fn xray(bump: usize, correction: Option<usize>) -> NormalMap {
        let convention = NormalConvention { layout: NormalLayout::Xray, ..Default::default() };
        NormalMap { texture: bump, scale: 1.0, convention, correction, stored: None }
    }

    /// The `bump#` texture where the layout reads it.
    pub fn correction_in_use(&self) -> Option<usize> {
        self.correction.filter(|_| self.convention.layout == NormalLayout::Xray)
    }
}

/// The layout a file's format states for a normal map: RG for two channels, AG for DXT5nm,
/// `None` for formats that keep three or four channels.
pub fn stored_layout(stored: &Stored) -> Option<NormalLayout> {
    match stored.channels {
        StoredChannels::Rg => Some(NormalLayout::Rg),
        StoredChannels::Ag => Some(NormalLayout::Ag),
        StoredChannels::ColourBlock | StoredChannels::Rgba | StoredChannels::Plain => None,
    }
}

/// A height map slot: a [`super::TextureKind::Height`] texture and how it becomes normals.
#[derive(Debug, Clone, PartialEq)]
pub struct HeightMap {
    pub texture: usize,
    /// Metres the full sample range (0 → 1) spans, world units.
    pub range_m: f32,
    /// Finite-difference kernel used when the height map is turned into a normal map.
    pub kernel: Kernel,
    /// Wrap (tiling) or clamp at the image border when differentiating.
    pub border: Border,
    /// The map stores depth (white = deep): height `h = 1 − sample`.
    pub depth: bool,
}

impl HeightMap {
    /// A wrapping height map (white = high) spanning `range_m` metres, central differences.
    pub fn new(texture: usize, range_m: f32) -> HeightMap {
        HeightMap { texture, range_m, kernel: Kernel::CentralDifference, border: Border::Wrap, depth: false }
    }

    /// The height field of `heights` (this slot's texture) as these settings read it: heights
    /// 0 → 1 (depth maps inverted) over `range_m`; one UV unit spans `uv_span_m` metres.
    pub fn height_field(&self, heights: &TextureImage, uv_span_m: f32) -> HeightField {
        let samples = heights.rgba.chunks_exact(4).map(|t| decode_height(t[0], t[1]));
        HeightField {
            width: heights.width,
            height: heights.height,
            samples: samples.map(|h| if self.depth { 1.0 - h } else { h }).collect(),
            range_m: self.range_m,
            texel_size_m: uv_span_m / heights.width.max(1) as f32,
        }
    }

    /// The tangent-space normal map (OpenGL convention) of `heights` (this slot's texture)
    /// with these settings; one UV unit spans `uv_span_m` metres on the surface.
    pub fn to_normal_map(&self, heights: &TextureImage, uv_span_m: f32) -> TextureImage {
        self.height_field(heights, uv_span_m).to_normal_map(
            self.kernel,
            self.border,
            &format!("{} (normals)", heights.name),
        )
    }
}

/// How a material is lit. Named `blinn-phong`, `pbr`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, strum::IntoStaticStr, strum::VariantArray)]
#[strum(serialize_all = "kebab-case")]
pub enum ShadingModel {
    /// The lecture model: ambient + Lambert + Blinn-Phong specular ([`crate::shading::blinn_phong`]).
    #[default]
    BlinnPhong,
    /// glTF 2.0 metallic-roughness: GGX, Smith height-correlated visibility, Schlick Fresnel,
    /// with the point light and the procedural sky ([`crate::shading::pbr::metallic_roughness`]).
    #[strum(serialize = "pbr")]
    MetallicRoughness,
}

impl ShadingModel {
    /// The index the mesh shader's `SHADING_MODEL` pipeline constant takes.
    pub fn shader_index(self) -> u32 {
        self as u32
    }
}

/// How a texture coordinate outside 0..1 is read (glTF sampler `wrapS` / `wrapT`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Wrap {
    #[default]
    Repeat,
    ClampToEdge,
    MirroredRepeat,
}

/// Wrap modes along `u` and `v`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct SamplerWrap {
    pub u: Wrap,
    pub v: Wrap,
}

/// An occlusion texture slot (red channel, linear) and its glTF `strength`.
#[derive(Debug, Clone, PartialEq)]
pub struct Occlusion {
    pub texture: usize,
    pub strength: f32,
}

/// A material. Texture fields index [`super::Scene::textures`].
#[derive(Debug, Clone, PartialEq)]
pub struct Material {
    pub name: String,
    /// Linear RGBA multiplier of the base colour texture.
    pub base_color_factor: Vec4,
    /// sRGB colour texture.
    pub base_color_texture: Option<usize>,
    pub normal_map: Option<NormalMap>,
    /// A second, tiled tangent-space normal map blended over the normal map
    /// ([`super::DetailMap`]); drawn only where the material has a normal map.
    pub detail_map: Option<super::DetailMap>,
    /// Heights for bump mapping in the shader and for making the normal map.
    pub height_map: Option<HeightMap>,
    /// Linear gloss (specular) map (OBJ `map_Ks`/`map_Ns`, `--gloss`): Blinn-Phong's k_s is
    /// multiplied by its RGB (sampled with the detail sampler); metallic-roughness shading
    /// does not read it.
    pub gloss_texture: Option<usize>,
    /// Blinn-Phong: linear specular colour k_s.
    pub specular: Vec3,
    /// Blinn-Phong exponent (≥ 1).
    pub shininess: f32,
    /// Draw back faces too, with the frame flipped.
    pub double_sided: bool,
    pub shading_model: ShadingModel,
    /// Metallic-roughness: metalness factor in 0..1 (times the texture's blue).
    pub metallic: f32,
    /// Metallic-roughness: perceptual roughness factor in 0..1 (times the texture's green);
    /// GGX `α = roughness²`.
    pub roughness: f32,
    /// Linear texture: blue = metalness, green = roughness (glTF).
    pub metallic_roughness_texture: Option<usize>,
    /// Ambient (sky) occlusion; metallic-roughness only.
    pub occlusion: Option<Occlusion>,
    /// Sampler of the base colour texture.
    pub base_color_wrap: SamplerWrap,
    /// Sampler of the normal or height map, the metallic-roughness and occlusion textures.
    pub detail_wrap: SamplerWrap,
    /// Light the surface emits, linear RGB (glTF `emissiveFactor`, times
    /// `KHR_materials_emissive_strength`); zero: none.
    pub emissive_factor: Vec3,
    /// sRGB emissive texture, multiplied by the factor (base colour sampler).
    pub emissive_texture: Option<usize>,
    /// `KHR_materials_clearcoat`: a clear layer over the metallic-roughness base.
    pub clearcoat: Option<Clearcoat>,
}

/// A clear coat (`KHR_materials_clearcoat`): a dielectric layer (F0 = 0.04) with its own
/// roughness and normal over the base. Its textures are linear and sampled with the detail
/// sampler at the layer's texture coordinates ([`Clearcoat::uv_transform`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Clearcoat {
    /// Layer strength 0..1, times the texture's red.
    pub factor: f32,
    pub texture: Option<usize>,
    /// Perceptual roughness 0..1, times the texture's green; GGX `α = roughness²`.
    pub roughness: f32,
    pub roughness_texture: Option<usize>,
    /// The layer's own tangent-space normal map (OpenGL convention, its `scale`).
    pub normal_map: Option<NormalMap>,
    /// From the mesh's texture coordinates to the layer's (its `KHR_texture_transform`
    /// relative to the one the mesh's coordinates carry): `uv' = (row0 · (u, v, 1), row1 · (u, v, 1))`.
    pub uv_transform: [Vec3; 2],
}

impl Clearcoat {
    /// The identity of [`Clearcoat::uv_transform`].
    pub const SAME_UV: [Vec3; 2] = [Vec3::X, Vec3::Y];

    /// `uv` on the layer's textures.
    pub fn layer_uv(&self, uv: glam::Vec2) -> glam::Vec2 {
        let p = uv.extend(1.0);
        glam::Vec2::new(self.uv_transform[0].dot(p), self.uv_transform[1].dot(p))
    }
}

impl Default for Material {
    /// White, untextured, Blinn-Phong with a weak specular; dielectric, fully rough for
    /// metallic-roughness; repeat samplers.
    fn default() -> Self {
        Material {
            name: "material".into(),
            base_color_factor: Vec4::ONE,
            base_color_texture: None,
            normal_map: None,
            detail_map: None,
            height_map: None,
            gloss_texture: None,
            specular: Vec3::splat(0.04),
            shininess: 32.0,
            double_sided: false,
            shading_model: ShadingModel::BlinnPhong,
            metallic: 0.0,
            roughness: 1.0,
            metallic_roughness_texture: None,
            occlusion: None,
            base_color_wrap: SamplerWrap::default(),
            detail_wrap: SamplerWrap::default(),
            emissive_factor: Vec3::ZERO,
            emissive_texture: None,
            clearcoat: None,
        }
    }
}

impl Material {
    /// The clear coat when it shows (a layer with a factor above 0).
    pub fn visible_clearcoat(&self) -> Option<&Clearcoat> {
        self.clearcoat.as_ref().filter(|c| c.factor > 0.0)
    }

    /// Whether the material emits light.
    pub fn emits(&self) -> bool {
        self.emissive_factor != Vec3::ZERO
    }
}
