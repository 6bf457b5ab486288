//! The wireframe overlay: every instance's triangle edges over the surfaces, where the device
//! can draw lines (`wgpu::Features::POLYGON_MODE_LINE`); else a notice says why it is missing.

use super::{FramePipelines, InstanceDraw};
use crate::frame::ShadingSettings;
use crate::render::pipelines::Pass;
use crate::render::scene_gpu::GpuScene;

/// The notice shown while the wireframe overlay is on but the device cannot draw lines.
pub const WIREFRAME_UNSUPPORTED: &str =
    "wireframe overlay (W) needs wgpu::Features::POLYGON_MODE_LINE, which this device does not have";

/// Every instance of `scene` when `shading` asks for the wireframe and `line_mode` (the device
/// draws lines), else none. Each binds its variant's group-1 layout.
pub fn plan(scene: &GpuScene, shading: &ShadingSettings, line_mode: bool) -> Vec<InstanceDraw> {
    let wanted = shading.wireframe && line_mode;
    let instances = scene.instances.iter().enumerate().filter(|_| wanted);
    instances.map(|(index, i)| InstanceDraw { instance: index, pass: Pass::Wireframe { variant: i.variant } }).collect()
}

/// Draws each planned instance's triangles as lines, from its positions alone.
pub fn record(pass: &mut wgpu::RenderPass, pipelines: &FramePipelines, scene: &GpuScene, draws: &[InstanceDraw]) {
    for draw in draws {
        let instance = &scene.instances[draw.instance];
        let Some(streams) = scene.drawn_streams(instance.mesh) else { continue };
        pass.set_pipeline(pipelines.get(draw.pass));
        pass.set_bind_group(1, &instance.bind_group, &[]);
        pass.set_vertex_buffer(0, streams.positions.slice(..));
        pass.set_index_buffer(streams.indices.slice(..), wgpu::IndexFormat::Uint32);
        pass.draw_indexed(streams.range, 0, 0..1);
    }
}

/// Adds [`WIREFRAME_UNSUPPORTED`] to `notices` while the wireframe is `wanted` without
/// `line_mode`, and removes it otherwise.
pub fn update_notice(notices: &mut Vec<String>, wanted: bool, line_mode: bool) {
    let shown = notices.iter().position(|n| n == WIREFRAME_UNSUPPORTED);
    match (wanted && !line_mode, shown) {
        (true, None) => notices.push(WIREFRAME_UNSUPPORTED.to_owned()),
        (false, Some(index)) => {
            notices.remove(index);
        }
        _ => {}
    }
}
