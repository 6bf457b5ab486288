//! Render pipelines, one variant per combination of what a mesh and material actually have
//! and of the view and shading model drawn (WGSL pipeline constants, so a pipeline compiles
//! only the code it runs), built on first use and cached. Bump, strength and the lit mode are
//! uniforms instead.

use std::collections::HashMap;

use super::bindings;
use super::shaders::{self, Wgsl};
use crate::counters::WorkCounters;
use crate::frame::{DetailBlend, LegacyLook, LegacySettings, LightingSpace, Mistake, Parallax, ViewMode};
use crate::prepare::Variant;
use crate::scene::ShadingModel;
use crate::texture::MipFilter;

pub const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;

/// Pulls the wireframe's edges towards the eye so they win the depth test against the faces
/// they border (negative: nearer), by a constant and by the faces' depth slope.
const WIREFRAME_DEPTH_BIAS: wgpu::DepthBiasState = wgpu::DepthBiasState { constant: -8, slope_scale: -1.0, clamp: 0.0 };

/// A pipeline in the cache.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Pass {
    Mesh {
        variant: Variant,
        cull_back_faces: bool,
        /// The model matrix mirrors (negative determinant): front faces, counter-clockwise
        /// in model space, are clockwise on screen.
        mirrored: bool,
        /// The view drawn (the `VIEW` constant).
        view: ViewMode,
        /// The shading model of a lit view (the `SHADING_MODEL` constant); `None` for views
        /// that do not light.
        lighting: Option<ShadingModel>,
        /// The parallax technique (the `PARALLAX` constant); [`Parallax::Off`] for instances
        /// without a height map bound for it.
        parallax: Parallax,
        /// Whether the searches' soft self-shadows are on (the `PARALLAX_SHADOWS` constant);
        /// off, their code is left out, which saves a height sample and a loop per light on
        /// lavapipe, where a branch on the strength uniform would run for every pixel.
        parallax_shadows: bool,
        /// The classic mistake drawn (the `MISTAKE` constant).
        mistake: Mistake,
        /// The legacy look of a lit view (the `LEGACY` constant); off in the other views.
        legacy: LegacySettings,
        /// The classic model's lighting space (the `LIGHTING_SPACE` constant; tangent space
        /// has its own fragment stage); [`LightingSpace::World`] except for normal-mapped
        /// variants in lit views with the classic model.
        lighting_space: LightingSpace,
        /// The optional textures and lobes the material has (the `MATERIAL_FEATURES` constant,
        /// [`super::uniforms::MATERIAL_FEATURES`] bits): the code of the others is left out.
        /// On lavapipe that is what saves their cost, as it runs both sides of a branch on a
        /// uniform, texture samples included.
        features: u32,
        /// How the normal map's highlight is widened (the `MIP_FILTER` constant,
        /// shaders/mip_filter.wgsl); [`MipFilter::RenormalizedBox`] (no widening) outside the
        /// lit views and for the methods that do not widen ([`MipFilter::widens`]). LEAN, in
        /// every view (its normal is the mean slope's), has its own module
        /// ([`shaders::MESH_LEAN`], [`shaders::MESH_LEAN_PER_VERTEX`]) and its texture in
        /// group 2 ([`Layouts::lean`]).
        mip_filter: MipFilter,
        /// How the detail normal map is blended (the `DETAIL_BLEND` constant,
        /// shaders/detail.wgsl); the default where the material has no detail map.
        detail_blend: DetailBlend,
    },
    /// The Difference view of a mesh with a tangent stream: it adds the reference stream
    /// and binds the same group-1 layout as `variant`.
    Difference {
        variant: Variant,
        cull_back_faces: bool,
        mirrored: bool,
    },
    LightMarker,
    /// The wireframe overlay of a mesh drawn with `variant` (whose group-1 layout it binds):
    /// positions only, `PolygonMode::Line`, depth-tested with a bias towards the eye, no depth
    /// writes. Needs `wgpu::Features::POLYGON_MODE_LINE`.
    Wireframe {
        variant: Variant,
    },
    /// The T/B/N glyphs of a mesh drawn with `variant` (whose group-1 layout it binds): a line
    /// list ([`super::glyphs`]), depth-tested, no depth writes.
    Glyphs {
        variant: Variant,
    },
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct PipelineKey {
    pub pass: Pass,
    pub format: wgpu::TextureFormat,
    pub samples: u32,
}

/// Bind group layouts ([`super::bindings`]): group 0 is the frame; group 1 the object and
/// its material, with the bump texture only for variants that have one, or the light marker.
#[derive(Clone)]
pub struct Layouts {
    pub frame: wgpu::BindGroupLayout,
    pub plain_material: wgpu::BindGroupLayout,
    pub normal_mapped_material: wgpu::BindGroupLayout,
    pub marker: wgpu::BindGroupLayout,
    /// Group 2 of LEAN's mesh pipelines: LEAN's texture ([`bindings::LEAN_GROUP`]).
    pub lean: wgpu::BindGroupLayout,
}

impl Layouts {
    fn new(device: &wgpu::Device) -> Self {
        let layout = |label: &str, slots: &[bindings::Slot]| {
            let entries: Vec<_> = slots.iter().map(bindings::Slot::layout_entry).collect();
            device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor { label: Some(label), entries: &entries })
        };
        let bump_only = [bindings::BUMP_TEXTURE, bindings::BUMP_CORRECTION_TEXTURE];
        let plain: Vec<_> = bindings::MATERIAL.into_iter().filter(|s| !bump_only.contains(s)).collect();
        Layouts {
            frame: layout("frame", &bindings::FRAME_GROUP),
            plain_material: layout("plain material", &plain),
            normal_mapped_material: layout("normal-mapped material", &bindings::MATERIAL),
            marker: layout("light marker", &[bindings::MARKERS]),
            lean: layout("LEAN moments", &bindings::LEAN_GROUP),
        }
    }

    /// The group-1 layout a mesh variant binds.
    pub fn material(&self, variant: Variant) -> &wgpu::BindGroupLayout {
        if variant.has_bump_texture() { &self.normal_mapped_material } else { &self.plain_material }
    }
}

/// Layouts, shader modules and the cache of built pipelines: the long-lived resources every
/// drawable's pipelines come from, keyed by what they are ([`PipelineKey`]).
pub struct Pipelines {
    pub layouts: Layouts,
    /// The shader modules made so far (each on the first pipeline that needs it), by label.
    modules: HashMap<&'static str, wgpu::ShaderModule>,
    cache: HashMap<PipelineKey, wgpu::RenderPipeline>,
}

const POSITION: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: 12,
    step_mode: wgpu::VertexStepMode::Vertex,
    attributes: &wgpu::vertex_attr_array![0 => Float32x3],
};
const NORMAL: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: 12,
    step_mode: wgpu::VertexStepMode::Vertex,
    attributes: &wgpu::vertex_attr_array![1 => Float32x3],
};
const UV: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: 8,
    step_mode: wgpu::VertexStepMode::Vertex,
    attributes: &wgpu::vertex_attr_array![2 => Float32x2],
};
const TANGENT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: 16,
    step_mode: wgpu::VertexStepMode::Vertex,
    attributes: &wgpu::vertex_attr_array![3 => Float32x4],
};
const REFERENCE_TANGENT: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: 16,
    step_mode: wgpu::VertexStepMode::Vertex,
    attributes: &wgpu::vertex_attr_array![4 => Float32x4],
};

/// [`super::glyphs::GlyphVertex`]: position, normal, tangent, `[axis, end, length]`.
const GLYPH: wgpu::VertexBufferLayout<'static> = wgpu::VertexBufferLayout {
    array_stride: std::mem::size_of::<super::glyphs::GlyphVertex>() as u64,
    step_mode: wgpu::VertexStepMode::Vertex,
    attributes: &wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 3 => Float32x4, 5 => Float32x3],
};

/// The mesh pass's module for a pipeline: LEAN's (its texture bound) for LEAN, and the one
/// with the per-vertex light direction and half vector between its stages
/// ([`shaders::MESH_PER_VERTEX`], [`shaders::MESH_LEAN_PER_VERTEX`]) only where the legacy looks
/// or the per-vertex mistakes read them. llvmpipe sets up and interpolates every vertex output,
/// read or not; with the two in every pipeline a 4× MSAA frame of the built-in scene cost
/// 1.86–2.04× the floor, without them 1.73–1.80× (`render --frames 30`, same machine and load),
/// and LEAN's 2.25–2.37× with them, 2.14–2.27× without.
fn mesh_module(legacy: LegacySettings, mistake: Mistake, mip_filter: MipFilter) -> Wgsl {
    let per_vertex = legacy.look != LegacyLook::Off || mistake.reads_per_vertex_vectors();
    match (mip_filter == MipFilter::Lean, per_vertex) {
        (true, true) => shaders::MESH_LEAN_PER_VERTEX,
        (true, false) => shaders::MESH_LEAN,
        (false, true) => shaders::MESH_PER_VERTEX,
        (false, false) => shaders::MESH,
    }
}

/// The module a pass's pipelines are made from.
fn module_of(pass: Pass) -> Wgsl {
    match pass {
        Pass::Mesh { legacy, mistake, mip_filter, .. } => mesh_module(legacy, mistake, mip_filter),
        Pass::Difference { .. } => shaders::DIFFERENCE,
        Pass::Wireframe { .. } => shaders::WIREFRAME,
        Pass::Glyphs { .. } => shaders::GLYPHS,
        Pass::LightMarker => shaders::MARKER,
    }
}

impl Pipelines {
    pub fn new(device: &wgpu::Device) -> Self {
        Pipelines { layouts: Layouts::new(device), modules: HashMap::new(), cache: HashMap::new() }
    }

    /// Builds the pipeline for `key` unless it is cached (and its shader module unless made).
    pub fn ensure(&mut self, device: &wgpu::Device, key: PipelineKey, counters: &mut WorkCounters) {
        if !self.cache.contains_key(&key) {
            let wgsl = module_of(key.pass);
            let module = self.modules.entry(wgsl.label).or_insert_with(|| {
                device.create_shader_module(wgpu::ShaderModuleDescriptor {
                    label: Some(wgsl.label),
                    source: wgpu::ShaderSource::Wgsl(wgsl.source().into()),
                })
            });
            let pipeline = build(device, &self.layouts, module, key);
            counters.pipelines_built += 1;
            self.cache.insert(key, pipeline);
        }
    }

    /// A pipeline previously made by [`Pipelines::ensure`].
    pub fn get(&self, key: &PipelineKey) -> &wgpu::RenderPipeline {
        &self.cache[key]
    }

    /// The keys built so far.
    pub fn built(&self) -> impl Iterator<Item = &PipelineKey> {
        self.cache.keys()
    }
}

/// The pipeline for `key`, its stages from `module` ([`module_of`]).
fn build(
    device: &wgpu::Device,
    layouts: &Layouts,
    module: &wgpu::ShaderModule,
    key: PipelineKey,
) -> wgpu::RenderPipeline {
    let encodes_srgb = ("TARGET_ENCODES_SRGB", if key.format.is_srgb() { 1.0 } else { 0.0 });
    let front_face = match key.pass {
        Pass::Mesh { mirrored: true, .. } | Pass::Difference { mirrored: true, .. } => wgpu::FrontFace::Cw,
        _ => wgpu::FrontFace::Ccw,
    };
    let (group1, vs, fs, buffers, cull_mode, constants): (_, _, _, &[_], _, Vec<(&str, f64)>) = match key.pass {
        Pass::Mesh { variant, cull_back_faces, .. } => {
            let (vs, fs, buffers) = mesh_entry_points(variant);
            let cull = cull_back_faces.then_some(wgpu::Face::Back);
            let constants = mesh_constants(key.pass, encodes_srgb);
            (layouts.material(variant), vs, fs, buffers, cull, constants)
        }
        Pass::Difference { variant, cull_back_faces, .. } => {
            let buffers: &[_] = &[POSITION, NORMAL, UV, TANGENT, REFERENCE_TANGENT];
            let cull = cull_back_faces.then_some(wgpu::Face::Back);
            let layout = layouts.material(variant);
            (layout, "vs_difference", "fs_difference", buffers, cull, vec![encodes_srgb])
        }
        Pass::Wireframe { variant } => {
            (layouts.material(variant), "vs_wireframe", "fs_wireframe", &[POSITION], None, vec![encodes_srgb])
        }
        Pass::Glyphs { variant } => {
            (layouts.material(variant), "vs_glyph", "fs_glyph", &[GLYPH], None, vec![encodes_srgb])
        }
        Pass::LightMarker => (&layouts.marker, "vs_marker", "fs_marker", &[POSITION], Some(wgpu::Face::Back), vec![]),
    };
    let wireframe = matches!(key.pass, Pass::Wireframe { .. });
    let lean = matches!(key.pass, Pass::Mesh { mip_filter: MipFilter::Lean, .. });
    let overlay = wireframe || matches!(key.pass, Pass::Glyphs { .. });
    let polygon_mode = if wireframe { wgpu::PolygonMode::Line } else { wgpu::PolygonMode::Fill };
    let topology = match key.pass {
        Pass::Glyphs { .. } => wgpu::PrimitiveTopology::LineList,
        _ => wgpu::PrimitiveTopology::TriangleList,
    };
    let buffers: Vec<_> = buffers.iter().cloned().map(Some).collect();
    let layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
        label: Some("bumpview"),
        bind_group_layouts: &[Some(&layouts.frame), Some(group1), Some(&layouts.lean)][..if lean { 3 } else { 2 }],
        immediate_size: 0,
    });
    let options = wgpu::PipelineCompilationOptions { constants: &constants, ..Default::default() };
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(&format!("{key:?}")),
        layout: Some(&layout),
        vertex: wgpu::VertexState {
            module,
            entry_point: Some(vs),
            buffers: &buffers,
            compilation_options: options.clone(),
        },
        primitive: wgpu::PrimitiveState { topology, cull_mode, front_face, polygon_mode, ..Default::default() },
        depth_stencil: Some(wgpu::DepthStencilState {
            format: DEPTH_FORMAT,
            depth_write_enabled: Some(!overlay),
            depth_compare: Some(if overlay { wgpu::CompareFunction::LessEqual } else { wgpu::CompareFunction::Less }),
            stencil: Default::default(),
            bias: if wireframe { WIREFRAME_DEPTH_BIAS } else { Default::default() },
        }),
        multisample: wgpu::MultisampleState { count: key.samples, ..Default::default() },
        fragment: Some(wgpu::FragmentState {
            module,
            entry_point: Some(fs),
            targets: &[Some(wgpu::ColorTargetState {
                format: key.format,
                blend: None,
                write_mask: wgpu::ColorWrites::ALL,
            })],
            compilation_options: options,
        }),
        multiview_mask: None,
        cache: None,
    })
}

/// The vertex and fragment entry points and the vertex streams of a mesh pass of `variant`
/// (the lighting space is a pipeline constant, `LIGHTING_SPACE`).
fn mesh_entry_points(variant: Variant) -> (&'static str, &'static str, &'static [wgpu::VertexBufferLayout<'static>]) {
    match variant {
        Variant::Plain => ("vs_plain", "fs_plain", &[POSITION, NORMAL, UV]),
        Variant::Tangent => ("vs_tangent", "fs_tangent", &[POSITION, NORMAL, UV, TANGENT]),
        Variant::NormalMapped => ("vs_tangent", "fs_normal_mapped", &[POSITION, NORMAL, UV, TANGENT]),
        Variant::ObjectSpace => ("vs_plain", "fs_object_space", &[POSITION, NORMAL, UV]),
        Variant::HeightBump => ("vs_plain", "fs_height_bump", &[POSITION, NORMAL, UV]),
    }
}

/// The pipeline constants of a mesh pass (`pass` is a [`Pass::Mesh`]): the view, the
/// material's features and each variant choice that is not its default.
fn mesh_constants(pass: Pass, encodes_srgb: (&'static str, f64)) -> Vec<(&'static str, f64)> {
    let Pass::Mesh {
        view,
        lighting,
        parallax,
        parallax_shadows,
        mistake,
        legacy,
        lighting_space,
        features,
        mip_filter,
        detail_blend,
        ..
    } = pass
    else {
        return vec![encodes_srgb];
    };
    let mut constants =
        vec![encodes_srgb, ("VIEW", f64::from(view.shader_index())), ("MATERIAL_FEATURES", f64::from(features))];
    constants.extend(lighting.map(|model| ("SHADING_MODEL", f64::from(model.shader_index()))));
    if parallax.shifts() {
        constants.push(("PARALLAX", f64::from(parallax.shader_index())));
        if !parallax_shadows {
            constants.push(("PARALLAX_SHADOWS", 0.0));
        }
    }
    if mistake != Mistake::None {
        constants.push(("MISTAKE", f64::from(mistake.shader_index())));
    }
    if legacy.look != LegacyLook::Off {
        constants.push(("LEGACY", f64::from(legacy.shader_index())));
    }
    if lighting_space != LightingSpace::World {
        constants.push(("LIGHTING_SPACE", f64::from(lighting_space.shader_index())));
    }
    if mip_filter.widens() {
        constants.push(("MIP_FILTER", f64::from(mip_filter.shader_index())));
    }
    if detail_blend != DetailBlend::default() {
        constants.push(("DETAIL_BLEND", f64::from(detail_blend.shader_index())));
    }
    constants
}
