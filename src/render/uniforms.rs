//! Uniform blocks, laid out exactly as the WGSL structs in `shaders/frame.wgsl` and `shaders/object.wgsl`.

use bytemuck::{Pod, Zeroable};

use crate::frame::FrameParams;
use crate::math::normal_matrix;
use crate::prepare::PreparedInstance;
use crate::scene::{Clearcoat, Light, LightKind, MAX_LIGHTS, Material, Wrap};
use crate::shading::SELF_SHADOW_FADE;

/// WGSL `Light`: one light that is on.
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
pub struct LightUniform {
    /// xyz: a point light's position (w = 1) or a directional light's direction towards the
    /// light (w = 0), world space.
    position: [f32; 4],
    /// rgb: colour × intensity, linear.
    radiance: [f32; 4],
    /// The attenuation coefficients c, l, q; unused.
    attenuation: [f32; 4],
}

impl LightUniform {
    fn new(light: &Light) -> Self {
        let w = match light.kind {
            LightKind::Point => 1.0,
            LightKind::Directional => 0.0,
        };
        let [c, l, q] = light.attenuation.to_array();
        LightUniform {
            position: light.position.extend(w).to_array(),
            radiance: (light.color * light.intensity).extend(1.0).to_array(),
            attenuation: [c, l, q, 0.0],
        }
    }
}

/// WGSL `Frame`.
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
pub struct FrameUniform {
    view_proj: [[f32; 4]; 4],
    camera_pos: [f32; 4],
    /// The lights that are on, in order, the first `light_count` used.
    lights: [LightUniform; MAX_LIGHTS],
    /// Colour × strength, linear.
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
    light_count: u32,
    specular_mode: u32,
    /// The shininess for every material; negative: each material's own.
    shininess: f32,
    parallax_shadow_strength: f32,
    /// WGSL aligns `view_rotation` (a mat3x3, columns of vec4) to 16 bytes.
    _padding: [f32; 2],
    /// World → view space rotation (columns; w unused), for view-space lighting.
    view_rotation: [[f32; 4]; 3],
}

impl FrameUniform {
    /// The frame of `params` seen through `view_projection` (world → clip space).
    pub fn new(params: &FrameParams, view_projection: glam::Mat4) -> Self {
        let parallax = params.shading.parallax;
        let mut lights = [LightUniform::zeroed(); MAX_LIGHTS];
        let on = params.lights.as_slice().iter().filter(|light| light.enabled);
        let mut light_count = 0;
        for (slot, light) in lights.iter_mut().zip(on) {
            *slot = LightUniform::new(light);
            light_count += 1;
        }
        FrameUniform {
            view_proj: view_projection.to_cols_array_2d(),
            camera_pos: params.camera.eye().extend(1.0).to_array(),
            lights,
            ambient: params.lights.ambient().extend(1.0).to_array(),
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
            light_count,
            specular_mode: params.shading.specular.shader_index(),
            shininess: params.shading.shininess.map_or(-1.0, |s| s.max(1.0)),
            parallax_shadow_strength: if parallax.shadows_on() { parallax.shadow_strength } else { 0.0 },
            _padding: [0.0; 2],
            view_rotation: params.camera.view_rotation().to_cols_array_2d().map(|c| [c[0], c[1], c[2], 0.0]),
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
    /// The detail normal map's tiling and strength, unused, unused.
    detail: [f32; 4],
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
/// Bit of `flags`: binding 6 holds the material's occlusion texture.
pub(crate) const HAS_OCCLUSION_TEXTURE: u32 = 16384;
/// Bit of `flags`: binding 13 holds X-Ray's `bump#` correction texture (bits 15 and 16 are
/// [`crate::scene::NormalConvention`]'s layouts).
pub(crate) const HAS_BUMP_CORRECTION: u32 = 1 << 17;
/// Bit of `flags`: binding 14 holds the material's detail normal map (shaders/detail.wgsl).
pub(crate) const HAS_DETAIL: u32 = 1 << 18;
/// Bit of `flags`: the occlusion texture is the metallic-roughness texture (glTF's packed
/// occlusion-roughness-metallic maps), so its red comes from the metallic-roughness sample.
pub(crate) const OCCLUSION_IN_METALLIC_ROUGHNESS: u32 = 1 << 19;

/// The bits of `flags` that say which optional textures and lobes a material has: the mesh
/// pipelines are specialised to them ([`super::pipelines::Pass::Mesh`]'s `features`, the
/// `MATERIAL_FEATURES` constant), so a pipeline compiles no code for what its material lacks.
/// The other bits (conventions, parallax clamps) stay uniforms.
pub(crate) const MATERIAL_FEATURES: u32 = HAS_METALLIC_ROUGHNESS
    | HAS_OCCLUSION_TEXTURE
    | HAS_GLOSS
    | HAS_EMISSIVE_TEXTURE
    | HAS_CLEARCOAT
    | HAS_CLEARCOAT_TEXTURE
    | HAS_CLEARCOAT_ROUGHNESS_TEXTURE
    | HAS_CLEARCOAT_NORMAL
    | HAS_BUMP_CORRECTION
    | HAS_DETAIL
    | OCCLUSION_IN_METALLIC_ROUGHNESS;

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
                | bit(slots.occlusion.is_some(), HAS_OCCLUSION_TEXTURE)
                | bit(
                    slots.occlusion.is_some() && slots.occlusion == slots.metallic_roughness,
                    OCCLUSION_IN_METALLIC_ROUGHNESS,
                )
                | if material.gloss_texture.is_some() { HAS_GLOSS } else { 0 }
                | bit(slots.emissive.is_some(), HAS_EMISSIVE_TEXTURE)
                | bit(coat.is_some(), HAS_CLEARCOAT)
                | bit(slots.clearcoat.is_some(), HAS_CLEARCOAT_TEXTURE)
                | bit(slots.clearcoat_roughness.is_some(), HAS_CLEARCOAT_ROUGHNESS_TEXTURE)
                | bit(slots.clearcoat_normal.is_some(), HAS_CLEARCOAT_NORMAL)
                | bit(slots.height.is_some(), HAS_PARALLAX_HEIGHT)
                | bit(slots.bump_correction.is_some(), HAS_BUMP_CORRECTION)
                | bit(slots.detail.is_some(), HAS_DETAIL)
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
            detail: material.detail_map.map_or([0.0; 4], |d| [d.tiling, d.strength, 0.0, 0.0]),
        }
    }

    /// The [`MATERIAL_FEATURES`] bits of `flags`: what the instance's pipeline is specialised to.
    pub fn features(&self) -> u32 {
        self.flags & MATERIAL_FEATURES
    }
}

/// The detail blend an instance with material features `features` is drawn with: the frame's
/// override, else its material's `own`, where it has a detail map; else the default (no
/// detail code is compiled, so the pipelines are shared).
pub(crate) fn detail_blend_drawn(
    features: u32,
    own: crate::frame::DetailBlend,
    shading: &crate::frame::ShadingSettings,
) -> crate::frame::DetailBlend {
    if features & HAS_DETAIL == 0 { Default::default() } else { shading.detail_blend.unwrap_or(own) }
}
