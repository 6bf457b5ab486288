//! The meshes' surfaces: each instance drawn with the mesh pass specialised to what it has and
//! to the half's view, or with the Difference pass.

use super::{FramePipelines, InstanceDraw};
use crate::frame::{LegacySettings, LightingSpace, Parallax, ShadingSettings, ViewMode};
use crate::prepare::Variant;
use crate::render::pipelines::Pass;
use crate::render::scene_gpu::{GpuInstance, GpuScene};
use crate::texture::MipFilter;

/// Every instance of `scene` with the pass it is drawn with in `shading`.
pub fn plan(scene: &GpuScene, shading: &ShadingSettings) -> Vec<InstanceDraw> {
    let instances = scene.instances.iter().enumerate();
    instances
        .map(|(index, instance)| InstanceDraw { instance: index, pass: drawn_pass(instance, scene, shading) })
        .collect()
}

/// Draws each planned instance: its vertex streams (the reference tangents only in the
/// Difference pass) and its triangles.
pub fn record(pass: &mut wgpu::RenderPass, pipelines: &FramePipelines, scene: &GpuScene, draws: &[InstanceDraw]) {
    for draw in draws {
        let instance = &scene.instances[draw.instance];
        let mesh = &scene.meshes[instance.mesh];
        let Some(streams) = scene.drawn_streams(instance.mesh) else { continue };
        pass.set_pipeline(pipelines.get(draw.pass));
        pass.set_bind_group(1, &instance.bind_group, &[]);
        if let (Pass::Mesh { mip_filter: MipFilter::Lean, .. }, Some(lean)) = (draw.pass, &instance.lean_bind_group) {
            pass.set_bind_group(2, lean, &[]);
        }
        pass.set_vertex_buffer(0, streams.positions.slice(..));
        pass.set_vertex_buffer(1, streams.normals.slice(..));
        pass.set_vertex_buffer(2, streams.uvs.slice(..));
        if let Some(tangents) = &mesh.tangents {
            pass.set_vertex_buffer(3, tangents.slice(..));
        }
        if let (Pass::Difference { .. }, Some(reference)) = (draw.pass, mesh.reference_tangents.get()) {
            pass.set_vertex_buffer(4, reference.slice(..));
        }
        pass.set_index_buffer(streams.indices.slice(..), wgpu::IndexFormat::Uint32);
        pass.draw_indexed(streams.range, 0, 0..1);
    }
}

/// The pass an instance is drawn with in `shading`'s view: the Difference view has its own
/// pass for meshes that have tangent frames; else the mesh pass specialised to the view, in a
/// lit view to the shading model (the frame's override, else the material's), where a
/// height map is bound for it, to the parallax technique, and to the material's features.
fn drawn_pass(instance: &GpuInstance, scene: &GpuScene, shading: &ShadingSettings) -> Pass {
    let GpuInstance { variant, cull_back_faces, mirrored, features, mip_filter, .. } = *instance;
    if shading.view == ViewMode::Difference && scene.prepared.meshes[instance.mesh].frames.is_some() {
        return Pass::Difference { variant, cull_back_faces, mirrored };
    }
    let surface = shading.surface_lighting(instance.shading_model, variant == Variant::NormalMapped);
    let lighting = shading.view.is_lit().then_some(surface.shading_model);
    let parallax = if instance.parallax_height { shading.parallax.technique } else { Parallax::default() };
    let parallax_shadows = parallax.shifts() && shading.parallax.shadows_on();
    let legacy = if shading.view.is_lit() { shading.legacy } else { LegacySettings::default() };
    let (view, mistake) = (shading.view, shading.mistake);
    let lighting_space = if lighting.is_some() { surface.lighting_space } else { LightingSpace::World };
    // The highlight widening is the lit views' (the debug views show the normal as drawn);
    // the methods that do not widen share the plain pipelines. LEAN draws its own normal, the
    // mean slope's, in every view, where its texture is bound.
    let kept = match mip_filter {
        MipFilter::Lean => instance.lean_bind_group.is_some(),
        _ => lighting.is_some() && mip_filter.widens(),
    };
    let mip_filter = if kept { mip_filter } else { MipFilter::RenormalizedBox };
    let detail_blend = crate::render::uniforms::detail_blend_drawn(features, instance.detail_blend, shading);
    Pass::Mesh {
        variant,
        cull_back_faces,
        mirrored,
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
    }
}
