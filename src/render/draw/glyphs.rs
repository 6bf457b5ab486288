//! The T/B/N glyphs: the line lists [`crate::render::glyphs`] makes for meshes with tangent
//! frames, over the surfaces, when the half's shading asks for them.

use super::{FramePipelines, InstanceDraw};
use crate::frame::ShadingSettings;
use crate::render::pipelines::Pass;
use crate::render::scene_gpu::{GpuInstance, GpuScene};

/// The instances of `scene` whose meshes have glyph lines, when `shading` asks for glyphs
/// (their lines are made with the upload, [`crate::render::scene_gpu::upload`]). Each binds
/// its variant's group-1 layout.
pub fn plan(scene: &GpuScene, shading: &ShadingSettings) -> Vec<InstanceDraw> {
    let instances = scene.instances.iter().enumerate().filter(|(_, i)| shading.tbn_glyphs && has_glyphs(i, scene));
    instances.map(|(index, i)| InstanceDraw { instance: index, pass: Pass::Glyphs { variant: i.variant } }).collect()
}

/// Draws each planned instance's glyph lines.
pub fn record(pass: &mut wgpu::RenderPass, pipelines: &FramePipelines, scene: &GpuScene, draws: &[InstanceDraw]) {
    for draw in draws {
        let instance = &scene.instances[draw.instance];
        let Some((lines, count)) = &scene.meshes[instance.mesh].glyphs else { continue };
        pass.set_pipeline(pipelines.get(draw.pass));
        pass.set_bind_group(1, &instance.bind_group, &[]);
        pass.set_vertex_buffer(0, lines.slice(..));
        pass.draw(0..*count, 0..1);
    }
}

/// Whether an instance's mesh has glyph lines to draw (made for meshes with tangent frames).
fn has_glyphs(instance: &GpuInstance, scene: &GpuScene) -> bool {
    scene.meshes[instance.mesh].glyphs.as_ref().is_some_and(|(_, count)| *count > 0)
}
