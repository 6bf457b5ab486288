//! Uniform blocks, laid out exactly as the WGSL structs in `shaders/frame.wgsl` and `shaders/mesh.wgsl`.

use bytemuck::{Pod, Zeroable};
use glam::Vec3;

use crate::frame::FrameParams;
use crate::math::normal_matrix;
use crate::prepare::PreparedInstance;
use crate::scene::{Clearcoat, Material, Wrap};
use crate::shading::SELF_SHADOW_FADE;

/// WGSL `Frame`.
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
pub struct FrameUniform {
    view_proj: [[f32; 4]; 4],
    camera_pos: [f32; 4],
    light_pos: [f32; 4],
    light_color: [f32; 4],
    ambient: [f32; 4],
    strength: f32,
    bump_enabled: u32,
    self_shadow_fade: f32,
    difference_range_deg: f32,
    shading_mode: u32,
    over_tilt_cos: f32,
    parallax_layers_min: u32,
    parallax_layers_max: u32,
    parallax_steps: u32,
    parallax_depth_m: f32,
    /// The WGSL struct's size is a multiple of 16 bytes.
    _padding: [f32; 2],
}

impl FrameUniform {
    pub fn new(params: &FrameParams, ambient: Vec3, aspect: f32) -> Self {
        let parallax = params.shading.parallax;
        FrameUniform {
            view_proj: params.camera.view_projection(aspect).to_cols_array_2d(),
            camera_pos: params.camera.eye().extend(1.0).to_array(),
            light_pos: params.light.position.extend(1.0).to_array(),
            light_color: params.light.color.extend(1.0).to_array(),
            ambient: ambient.extend(1.0).to_array(),
            strength: params.shading.strength,
            bump_enabled: params.shading.bump_enabled as u32,
            self_shadow_fade: SELF_SHADOW_FADE,
            difference_range_deg: params.shading.difference_range_deg,
            shading_mode: params.shading.mode.shader_index(),
            over_tilt_cos: crate::shading::over_tilt_cos(),
            parallax_layers_min: parallax.layers_min,
            parallax_layers_max: parallax.layers_max,
            parallax_steps: parallax.steps,
            parallax_depth_m: parallax.depth_m.map_or(-1.0, |d| d.max(0.0)),
            _padding: [0.0; 2],
        }
    }
}

/// WGSL `Object`: one per drawn instance.
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
pub struct ObjectUniform {
    model: [[f32; 4]; 4],
    normal_matrix: [[f32; 4]; 4],
    base_color: [f32; 4],
    specular: [f32; 4],
    handedness: f32,
    normal_scale: f32,
    height_range_m: f32,
    flags: u32,
    metallic: f32,
    roughness: f32,
    occlusion_strength: f32,
    /// WGSL aligns `emissive` (a vec4) to 16 bytes.
    _padding: u32,
    /// Linear emitted light (rgb); a texture at binding 8 multiplies it where flagged.
    emissive: [f32; 4],
    /// The clear coat: factor, perceptual roughness, its normal map's scale, unused.
    clearcoat: [f32; 4],
    /// Rows of the 2×3 affine from the mesh's texture coordinates to the coat's (xyz each).
    clearcoat_uv: [[f32; 4]; 2],
}

/// Bit of `flags` beside [`crate::scene::NormalConvention::flags`]: the height map stores
/// depth (white = deep).
pub(crate) const DEPTH_MAP: u32 = 8;
/// Bit of `flags`: binding 5 holds the material's metallic-roughness texture (else a
/// placeholder the shader ignores).
pub(crate) const HAS_METALLIC_ROUGHNESS: u32 = 16;
/// Bit of `flags`: binding 7 holds the material's gloss (specular) map, which scales k_s.
pub(crate) const HAS_GLOSS: u32 = 32;
/// Bit of `flags`: binding 8 holds the emissive texture, which multiplies `emissive`.
pub(crate) const HAS_EMISSIVE_TEXTURE: u32 = 64;
/// Bit of `flags`: a clear coat lies over the metallic-roughness base.
pub(crate) const HAS_CLEARCOAT: u32 = 128;
/// Bits of `flags`: bindings 9, 10, 11 hold the coat's strength, roughness and normal textures.
pub(crate) const HAS_CLEARCOAT_TEXTURE: u32 = 256;
pub(crate) const HAS_CLEARCOAT_ROUGHNESS_TEXTURE: u32 = 512;
pub(crate) const HAS_CLEARCOAT_NORMAL: u32 = 1024;
/// Bit of `flags`: binding 12 holds the material's height map, which the parallax family marches.
pub(crate) const HAS_PARALLAX_HEIGHT: u32 = 2048;
/// Bits of `flags`: the height map's sampler clamps u, v; marched coordinates stay in 0..1.
pub(crate) const PARALLAX_CLAMP_U: u32 = 4096;
pub(crate) const PARALLAX_CLAMP_V: u32 = 8192;
/// Bit of `flags`: binding 13 holds X-Ray's `bump#` correction texture (bits 14 and 15 are
/// [`crate::scene::NormalConvention`]'s layouts).
pub(crate) const HAS_BUMP_CORRECTION: u32 = 1 << 16;

impl ObjectUniform {
    /// Normals go through the inverse-transpose of the model matrix; tangent `w` is
    /// multiplied by `sign(det(model))` (crate conventions).
    pub fn new(instance: &PreparedInstance, material: &Material) -> Self {
        let model = instance.transform;
        let determinant = model.determinant();
        let slots = &instance.textures;
        let bit = |on: bool, flag: u32| if on { flag } else { 0 };
        let coat = material.visible_clearcoat();
        let coat_uv = coat.map_or(Clearcoat::SAME_UV, |c| c.uv_transform).map(|row| row.extend(0.0).to_array());
        ObjectUniform {
            model: model.to_cols_array_2d(),
            normal_matrix: normal_matrix(model).to_cols_array_2d(),
            base_color: material.base_color_factor.to_array(),
            specular: material.specular.extend(material.shininess.max(1.0)).to_array(),
            handedness: if determinant < 0.0 { -1.0 } else { 1.0 },
            normal_scale: material.normal_map.as_ref().map_or(1.0, |n| n.scale),
            height_range_m: material.height_map.as_ref().map_or(0.0, |h| h.range_m),
            flags: material.normal_map.as_ref().map_or(0, |n| n.convention.flags())
                | if material.height_map.as_ref().is_some_and(|h| h.depth) { DEPTH_MAP } else { 0 }
                | if material.metallic_roughness_texture.is_some() { HAS_METALLIC_ROUGHNESS } else { 0 }
                | if material.gloss_texture.is_some() { HAS_GLOSS } else { 0 }
                | bit(slots.emissive.is_some(), HAS_EMISSIVE_TEXTURE)
                | bit(coat.is_some(), HAS_CLEARCOAT)
                | bit(slots.clearcoat.is_some(), HAS_CLEARCOAT_TEXTURE)
                | bit(slots.clearcoat_roughness.is_some(), HAS_CLEARCOAT_ROUGHNESS_TEXTURE)
                | bit(slots.clearcoat_normal.is_some(), HAS_CLEARCOAT_NORMAL)
                | bit(slots.height.is_some(), HAS_PARALLAX_HEIGHT)
                | bit(slots.bump_correction.is_some(), HAS_BUMP_CORRECTION)
                | bit(material.detail_wrap.u == Wrap::ClampToEdge, PARALLAX_CLAMP_U)
                | bit(material.detail_wrap.v == Wrap::ClampToEdge, PARALLAX_CLAMP_V),
            metallic: material.metallic,
            roughness: material.roughness,
            occlusion_strength: material.occlusion.as_ref().map_or(0.0, |o| o.strength),
            _padding: 0,
            emissive: material.emissive_factor.extend(0.0).to_array(),
            clearcoat: coat
                .map_or([0.0; 4], |c| [c.factor, c.roughness, c.normal_map.as_ref().map_or(1.0, |m| m.scale), 0.0]),
            clearcoat_uv: coat_uv,
        }
    }
}
