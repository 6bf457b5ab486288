//! Every binding of the shaders, written once: the bind group layouts and the bind groups are
//! built from these slots, and a test holds the WGSL's `@group`/`@binding` declarations (and
//! its view, mode and flag constants) to the Rust side.
//!
//! Group 0 is the frame ([`FRAME`]); group 1 is the drawn object and its material
//! ([`MATERIAL`]), or the light markers' centres and colours ([`MARKERS`]); group 2, in LEAN's
//! mesh pipelines alone, is LEAN's texture ([`LEAN_GROUP`]).

/// What a slot holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Resource {
    /// A uniform buffer, read by the vertex and fragment stages.
    Uniform,
    /// A filterable 2D float texture, read by the fragment stage.
    Texture,
    /// A filterable 2D array float texture, read by the fragment stage.
    TextureArray,
    /// A filtering sampler, used by the fragment stage.
    Sampler,
    /// A uniform buffer, read by the compute stage.
    ComputeUniform,
    /// A storage buffer the compute stage reads.
    StorageRead,
    /// A storage buffer the compute stage writes.
    StorageWrite,
    /// A 2D float texture the compute stage loads texels of.
    ComputeTexture,
}

/// One binding: its number, the WGSL global it declares, and what it holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Slot {
    pub binding: u32,
    pub wgsl_name: &'static str,
    pub resource: Resource,
}

const fn slot(binding: u32, wgsl_name: &'static str, resource: Resource) -> Slot {
    Slot { binding, wgsl_name, resource }
}

/// Group 0: the `Frame` uniform (shaders/frame.wgsl).
pub const FRAME: Slot = slot(0, "frame", Resource::Uniform);
/// Group 0: DOT3's normalization cube map, its six faces as layers (shaders/legacy.wgsl,
/// `chain::legacy::normalization_cube_map`), linear; a 1×1 placeholder while unused.
pub const NORMALIZATION_CUBE_MAP: Slot = slot(1, "normalization_cube_map", Resource::TextureArray);
/// Group 0: the emboss look's light map (`chain::legacy::emboss_light_map`), linear; a 1×1
/// placeholder while unused.
pub const EMBOSS_LIGHT_MAP: Slot = slot(2, "emboss_light_map", Resource::Texture);
/// Group 0, in binding order.
pub const FRAME_GROUP: [Slot; 3] = [FRAME, NORMALIZATION_CUBE_MAP, EMBOSS_LIGHT_MAP];

/// Group 1 of the mesh shader: the `Object` uniform.
pub const OBJECT: Slot = slot(0, "object", Resource::Uniform);
/// The base colour texture, through an sRGB view (samples are linear).
pub const BASE_COLOR_TEXTURE: Slot = slot(1, "base_color_texture", Resource::Texture);
/// The base colour texture's sampler (the material's base colour wrap modes).
pub const BASE_COLOR_SAMPLER: Slot = slot(2, "base_color_sampler", Resource::Sampler);
/// The normal map or the height map, linear; only in layouts of variants with a bump texture.
pub const BUMP_TEXTURE: Slot = slot(3, "bump_texture", Resource::Texture);
/// The sampler of the bump, metallic-roughness, occlusion and gloss textures.
pub const DETAIL_SAMPLER: Slot = slot(4, "detail_sampler", Resource::Sampler);
/// Metallic-roughness, linear: B metal, G rough.
pub const METALLIC_ROUGHNESS_TEXTURE: Slot = slot(5, "metallic_roughness_texture", Resource::Texture);
/// Occlusion, linear: R.
pub const OCCLUSION_TEXTURE: Slot = slot(6, "occlusion_texture", Resource::Texture);
/// Gloss (specular) map, linear: RGB scales k_s.
pub const GLOSS_TEXTURE: Slot = slot(7, "gloss_texture", Resource::Texture);

/// Emissive, sRGB (samples are linear), through the base colour sampler.
pub const EMISSIVE_TEXTURE: Slot = slot(8, "emissive_texture", Resource::Texture);
/// The clear coat's strength (R), roughness (G) and normal map, linear, at the coat's coordinates.
pub const CLEARCOAT_TEXTURE: Slot = slot(9, "clearcoat_texture", Resource::Texture);
pub const CLEARCOAT_ROUGHNESS_TEXTURE: Slot = slot(10, "clearcoat_roughness_texture", Resource::Texture);
pub const CLEARCOAT_NORMAL_TEXTURE: Slot = slot(11, "clearcoat_normal_texture", Resource::Texture);
/// The height map the parallax family marches (shaders/parallax.wgsl), linear, through the
/// detail sampler; a placeholder where the instance has none.
pub const HEIGHT_TEXTURE: Slot = slot(12, "height_texture", Resource::Texture);
/// X-Ray's `bump#` texture (RGB: the normal's compression-error correction), linear, through
/// the detail sampler; only in layouts of variants with a bump texture, a placeholder where
/// the instance has none.
pub const BUMP_CORRECTION_TEXTURE: Slot = slot(13, "bump_correction_texture", Resource::Texture);

/// The detail normal map (shaders/detail.wgsl), linear, through the detail sampler at the UV
/// times its tiling; a placeholder where the instance has none.
pub const DETAIL_NORMAL_TEXTURE: Slot = slot(14, "detail_normal_texture", Resource::Texture);

/// Group 1 of the mesh shader, in binding order.
pub const MATERIAL: [Slot; 15] = [
    OBJECT,
    BASE_COLOR_TEXTURE,
    BASE_COLOR_SAMPLER,
    BUMP_TEXTURE,
    DETAIL_SAMPLER,
    METALLIC_ROUGHNESS_TEXTURE,
    OCCLUSION_TEXTURE,
    GLOSS_TEXTURE,
    EMISSIVE_TEXTURE,
    CLEARCOAT_TEXTURE,
    CLEARCOAT_ROUGHNESS_TEXTURE,
    CLEARCOAT_NORMAL_TEXTURE,
    HEIGHT_TEXTURE,
    BUMP_CORRECTION_TEXTURE,
    DETAIL_NORMAL_TEXTURE,
];

/// Group 2 of LEAN's mesh pipelines (shaders/lean.wgsl): LEAN's texture of the normal map's
/// slope moments `(Bx, By, Bx², By²)`, `Rgba16Float` with the full mip chain, through the detail
/// sampler ([`crate::texture::LeanTexels`]).
pub const LEAN_MOMENTS: Slot = slot(0, "lean_moments", Resource::Texture);
/// Group 2, in binding order.
pub const LEAN_GROUP: [Slot; 1] = [LEAN_MOMENTS];

/// Group 2 of GPU displacement's compute pass (shaders/displace.wgsl): one mesh's parameters.
pub const DISPLACE_PARAMS: Slot = slot(0, "params", Resource::ComputeUniform);
/// The pool's base vertices (`position, u` and `normal, v`, model space).
pub const DISPLACE_BASE_VERTICES: Slot = slot(1, "base_vertices", Resource::StorageRead);
pub const DISPLACE_BASE_INDICES: Slot = slot(2, "base_indices", Resource::StorageRead);
/// The frame's patches ([`super::tessellation::plan::Patch`]).
pub const DISPLACE_PATCHES: Slot = slot(3, "patches", Resource::StorageRead);
/// The displaced vertices' streams and the triangles, which the mesh pipeline draws.
pub const DISPLACE_POSITIONS: Slot = slot(4, "out_positions", Resource::StorageWrite);
pub const DISPLACE_NORMALS: Slot = slot(5, "out_normals", Resource::StorageWrite);
pub const DISPLACE_UVS: Slot = slot(6, "out_uvs", Resource::StorageWrite);
pub const DISPLACE_INDICES: Slot = slot(7, "out_indices", Resource::StorageWrite);
/// The mesh's height map, level 0 read texel by texel.
pub const DISPLACE_HEIGHT_MAP: Slot = slot(8, "height_map", Resource::ComputeTexture);
/// The welded points of the seams where displaced surfaces meet ([`crate::prepare::seams`]).
pub const DISPLACE_SEAM_POINTS: Slot = slot(9, "seam_points", Resource::StorageRead);
/// Group 2 of GPU displacement, in binding order.
pub const DISPLACE_GROUP: [Slot; 10] = [
    DISPLACE_PARAMS,
    DISPLACE_BASE_VERTICES,
    DISPLACE_BASE_INDICES,
    DISPLACE_PATCHES,
    DISPLACE_POSITIONS,
    DISPLACE_NORMALS,
    DISPLACE_UVS,
    DISPLACE_INDICES,
    DISPLACE_HEIGHT_MAP,
    DISPLACE_SEAM_POINTS,
];

/// Group 1 of the marker shader: each light's marker centre and colour.
pub const MARKERS: Slot = slot(0, "markers", Resource::Uniform);

impl Slot {
    /// The layout entry of this slot.
    pub fn layout_entry(&self) -> wgpu::BindGroupLayoutEntry {
        let (visibility, ty) = match self.resource {
            Resource::Uniform => (
                wgpu::ShaderStages::VERTEX | wgpu::ShaderStages::FRAGMENT,
                wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
            ),
            Resource::Texture | Resource::TextureArray => (
                wgpu::ShaderStages::FRAGMENT,
                wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Float { filterable: true },
                    view_dimension: if self.resource == Resource::Texture {
                        wgpu::TextureViewDimension::D2
                    } else {
                        wgpu::TextureViewDimension::D2Array
                    },
                    multisampled: false,
                },
            ),
            Resource::Sampler => {
                (wgpu::ShaderStages::FRAGMENT, wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering))
            }
            Resource::ComputeUniform | Resource::StorageRead | Resource::StorageWrite => {
                let ty = match self.resource {
                    Resource::ComputeUniform => wgpu::BufferBindingType::Uniform,
                    read => wgpu::BufferBindingType::Storage { read_only: read == Resource::StorageRead },
                };
                (
                    wgpu::ShaderStages::COMPUTE,
                    wgpu::BindingType::Buffer { ty, has_dynamic_offset: false, min_binding_size: None },
                )
            }
            Resource::ComputeTexture => (
                wgpu::ShaderStages::COMPUTE,
                wgpu::BindingType::Texture {
                    sample_type: wgpu::TextureSampleType::Float { filterable: true },
                    view_dimension: wgpu::TextureViewDimension::D2,
                    multisampled: false,
                },
            ),
        };
        wgpu::BindGroupLayoutEntry { binding: self.binding, visibility, ty, count: None }
    }

    /// The bind group entry putting `resource` in this slot.
    pub fn entry<'a>(&self, resource: wgpu::BindingResource<'a>) -> wgpu::BindGroupEntry<'a> {
        wgpu::BindGroupEntry { binding: self.binding, resource }
    }
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeMap;

    use wgpu::naga;

    use super::*;
    use crate::frame::{LegacyLook, LegacySettings, MAX_PARALLAX_LAYERS, MAX_PARALLAX_STEPS, Mistake, Parallax};
    use crate::frame::{LightingSpace, ShadingMode, ViewMode};
    use crate::names::Named;
    use crate::render::shaders::{DISPLACE, MARKER, MESH, MESH_LEAN, MESH_LEAN_PER_VERTEX};
    use crate::render::uniforms::{
        DEPTH_MAP, HAS_BUMP_CORRECTION, HAS_CLEARCOAT, HAS_CLEARCOAT_NORMAL, HAS_CLEARCOAT_ROUGHNESS_TEXTURE,
        HAS_CLEARCOAT_TEXTURE, HAS_DETAIL, HAS_EMISSIVE_TEXTURE, HAS_GLOSS, HAS_METALLIC_ROUGHNESS,
        HAS_OCCLUSION_TEXTURE, HAS_PARALLAX_HEIGHT, OCCLUSION_IN_METALLIC_ROUGHNESS, PARALLAX_CLAMP_U,
        PARALLAX_CLAMP_V,
    };
    use crate::scene::{NormalConvention, ShadingModel, SpecularMode};
    use crate::texture::MipFilter;

    fn module(wgsl: &crate::render::shaders::Wgsl) -> naga::Module {
        let source = wgsl.source();
        naga::front::wgsl::parse_str(&source).unwrap_or_else(|e| panic!("{}", e.emit_to_string(&source)))
    }

    /// `(group, binding)` of every resource global, by name.
    fn wgsl_bindings(module: &naga::Module) -> BTreeMap<String, (u32, u32)> {
        let globals = module.global_variables.iter().map(|(_, g)| g);
        globals.filter_map(|g| Some((g.name.clone()?, g.binding.as_ref().map(|b| (b.group, b.binding))?))).collect()
    }

    /// Every `u32` constant with its value, by name.
    fn wgsl_u32_constants(module: &naga::Module) -> BTreeMap<String, u32> {
        let constants = module.constants.iter().map(|(_, c)| c);
        constants
            .filter_map(|c| match module.global_expressions[c.init] {
                naga::Expression::Literal(naga::Literal::U32(value)) => Some((c.name.clone()?, value)),
                _ => None,
            })
            .collect()
    }

    /// `prefix` and a kebab-case name as a WGSL constant name: `VIEW_` + `shading-normal`
    /// gives `VIEW_SHADING_NORMAL`.
    fn constant_name(prefix: &str, name: &str) -> String {
        format!("{prefix}{}", name.replace('-', "_").to_uppercase())
    }

    #[test]
    fn the_wgsl_bindings_are_the_tables() {
        let mesh = wgsl_bindings(&module(&MESH));
        let mut expected: BTreeMap<String, (u32, u32)> =
            MATERIAL.iter().map(|s| (s.wgsl_name.to_owned(), (1, s.binding))).collect();
        expected.extend(FRAME_GROUP.iter().map(|s| (s.wgsl_name.to_owned(), (0, s.binding))));
        assert_eq!(mesh, expected, "the mesh pass against render::bindings");
        expected.extend(LEAN_GROUP.iter().map(|s| (s.wgsl_name.to_owned(), (2, s.binding))));
        assert_eq!(wgsl_bindings(&module(&MESH_LEAN)), expected, "LEAN's mesh pass against render::bindings");
        assert_eq!(wgsl_bindings(&module(&MESH_LEAN_PER_VERTEX)), expected, "LEAN's per-vertex mesh pass");
        let marker = wgsl_bindings(&module(&MARKER));
        let expected = BTreeMap::from([
            (FRAME.wgsl_name.to_owned(), (0, FRAME.binding)),
            (MARKERS.wgsl_name.to_owned(), (1, MARKERS.binding)),
        ]);
        assert_eq!(marker, expected, "shaders/marker.wgsl against render::bindings");
        let expected: BTreeMap<String, (u32, u32)> =
            DISPLACE_GROUP.iter().map(|s| (s.wgsl_name.to_owned(), (2, s.binding))).collect();
        // Its own file's bindings: those of the module less those of the files before it.
        let before = crate::render::shaders::Wgsl { label: "before displace", files: &DISPLACE.files[..3] };
        let mut displace = wgsl_bindings(&module(&DISPLACE));
        displace.retain(|name, _| !wgsl_bindings(&module(&before)).contains_key(name));
        assert_eq!(displace, expected, "shaders/displace.wgsl against render::bindings");
        let numbers: Vec<u32> = MATERIAL.iter().map(|s| s.binding).collect();
        assert_eq!(numbers, (0..MATERIAL.len() as u32).collect::<Vec<_>>(), "one slot per number, in order");
    }

    /// The shader switches on the enums' indices through named constants: each must equal the
    /// Rust value. The first view and mode are the shader's `default` branches.
    #[test]
    fn the_wgsl_constants_are_the_rust_values() {
        let constants = wgsl_u32_constants(&module(&MESH));
        let mut expected = BTreeMap::new();
        for view in ViewMode::all().iter().copied().filter(|&v| v != ViewMode::default()) {
            expected.insert(constant_name("VIEW_", view.name()), view.shader_index());
        }
        for mode in ShadingMode::all().iter().copied().filter(|&m| m != ShadingMode::default()) {
            expected.insert(constant_name("MODE_", mode.name()), mode.shader_index());
        }
        expected.insert("FLIP_GREEN".into(), NormalConvention::FLIP_GREEN);
        expected.insert("LAYOUT_RG".into(), NormalConvention::LAYOUT_RG);
        expected.insert("LAYOUT_AG".into(), NormalConvention::LAYOUT_AG);
        expected.insert("LAYOUT_XRAY".into(), NormalConvention::LAYOUT_XRAY);
        expected.insert("HAS_BUMP_CORRECTION".into(), HAS_BUMP_CORRECTION);
        expected.insert("DEPTH_MAP".into(), DEPTH_MAP);
        expected.insert("HAS_METALLIC_ROUGHNESS".into(), HAS_METALLIC_ROUGHNESS);
        expected.insert("HAS_OCCLUSION_TEXTURE".into(), HAS_OCCLUSION_TEXTURE);
        expected.insert("HAS_GLOSS".into(), HAS_GLOSS);
        expected.insert("HAS_EMISSIVE_TEXTURE".into(), HAS_EMISSIVE_TEXTURE);
        expected.insert("HAS_CLEARCOAT".into(), HAS_CLEARCOAT);
        expected.insert("HAS_CLEARCOAT_TEXTURE".into(), HAS_CLEARCOAT_TEXTURE);
        expected.insert("HAS_CLEARCOAT_ROUGHNESS_TEXTURE".into(), HAS_CLEARCOAT_ROUGHNESS_TEXTURE);
        expected.insert("HAS_CLEARCOAT_NORMAL".into(), HAS_CLEARCOAT_NORMAL);
        expected.insert("SHADING_METALLIC_ROUGHNESS".into(), ShadingModel::MetallicRoughness.shader_index());
        for (name, legacy) in [
            ("LEGACY_DOT3", LegacySettings { look: LegacyLook::Dot3, cube_map_size: None }),
            ("LEGACY_DOT3_CUBE_MAP", LegacySettings { look: LegacyLook::Dot3, cube_map_size: Some(32) }),
            ("LEGACY_EMBOSS", LegacySettings { look: LegacyLook::Emboss, cube_map_size: None }),
        ] {
            expected.insert(name.into(), legacy.shader_index());
        }
        for mistake in Mistake::all().iter().copied().filter(|&m| m != Mistake::None) {
            expected.insert(constant_name("MISTAKE_", mistake.name()), mistake.shader_index());
        }
        for technique in Parallax::shifting() {
            expected.insert(constant_name("PARALLAX_", technique.name()), technique.shader_index());
        }
        expected.insert("MAX_PARALLAX_LAYERS".into(), MAX_PARALLAX_LAYERS);
        expected.insert("MAX_PARALLAX_STEPS".into(), MAX_PARALLAX_STEPS);
        expected.insert("HAS_PARALLAX_HEIGHT".into(), HAS_PARALLAX_HEIGHT);
        expected.insert("PARALLAX_CLAMP_U".into(), PARALLAX_CLAMP_U);
        expected.insert("PARALLAX_CLAMP_V".into(), PARALLAX_CLAMP_V);
        expected.insert("MAX_LIGHTS".into(), crate::scene::MAX_LIGHTS as u32);
        for space in LightingSpace::all().iter().copied().filter(|&s| s != LightingSpace::default()) {
            expected.insert(constant_name("LIGHTING_", space.name()), space.shader_index());
        }
        for mode in SpecularMode::all().iter().copied().filter(|&m| m != SpecularMode::default()) {
            expected.insert(constant_name("SPECULAR_", mode.name()), mode.shader_index());
        }
        // The mip filters the shader switches on (LEAN has its own modules, MESH_LEAN and MESH_LEAN_PER_VERTEX).
        for filter in [MipFilter::Toksvig, MipFilter::Vmf, MipFilter::GeometricSpecularAa] {
            expected.insert(constant_name("MIP_", filter.name()), filter.shader_index());
        }
        expected.insert("HAS_DETAIL".into(), HAS_DETAIL);
        expected.insert("OCCLUSION_IN_METALLIC_ROUGHNESS".into(), OCCLUSION_IN_METALLIC_ROUGHNESS);
        for method in crate::frame::DetailBlend::all() {
            expected.insert(constant_name("DETAIL_", method.name()), method.shader_index());
        }
        assert_eq!(constants, expected, "u32 constants of the mesh pass against the Rust side");
    }

    /// The Rust uniform structs are as large as the WGSL ones they fill: a field added on one
    /// side only, or padding that misplaces `view_rotation`, fails here instead of drawing wrong.
    #[test]
    fn the_uniform_structs_have_the_wgsl_sizes() {
        use crate::render::uniforms::{FrameUniform, LightUniform, ObjectUniform};
        let module = module(&MESH);
        let mut layouter = naga::proc::Layouter::default();
        layouter.update(module.to_ctx()).expect("the mesh shader's types have a layout");
        for (name, rust_size) in [
            ("Frame", std::mem::size_of::<FrameUniform>()),
            ("Object", std::mem::size_of::<ObjectUniform>()),
            ("Light", std::mem::size_of::<LightUniform>()),
        ] {
            let (handle, _) = module.types.iter().find(|(_, t)| t.name.as_deref() == Some(name)).expect(name);
            assert_eq!(layouter[handle].size as usize, rust_size, "WGSL {name} against its Rust uniform");
        }
    }

    /// The parallax march's grazing floor (shaders/parallax.wgsl, chain::parallax) and the
    /// attenuation's bounds (shading::lights) are one number on both sides.
    #[test]
    fn the_wgsl_float_constants_are_the_rust_ones() {
        let module = module(&MESH);
        for (name, expected) in [
            ("GRAZING_N_DOT_V", crate::chain::parallax::GRAZING_N_DOT_V),
            ("MIN_ATTENUATION_DENOMINATOR", crate::shading::lights::MIN_ATTENUATION_DENOMINATOR),
            ("MAX_LIGHT_DISTANCE_M", crate::shading::lights::MAX_LIGHT_DISTANCE_M),
            ("MIN_TBN_DETERMINANT", crate::shading::spaces::MIN_TBN_DETERMINANT),
            ("MIN_UV_AREA_PER_M2", crate::shading::spaces::MIN_UV_AREA_PER_M2),
            ("MIN_GRADIENT_Z", crate::shading::detail_blend::MIN_GRADIENT_Z),
        ] {
            let constant = module.constants.iter().map(|(_, c)| c).find(|c| c.name.as_deref() == Some(name));
            let value = constant.map(|c| &module.global_expressions[c.init]);
            let literal = matches!(value, Some(naga::Expression::Literal(naga::Literal::F32(v))) if *v == expected);
            assert!(literal, "{name}: {value:?}");
        }
    }
}
