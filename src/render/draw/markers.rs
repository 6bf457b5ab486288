//! The light markers: a small unlit octahedron at each light that is on, in its colour, when
//! the half's shading shows them, sized from the scene's bounds ([`crate::render::marker_gpu::marker_radius`]). Light i
//! is instance i of the marker mesh, its centre and colour element i of the markers' uniform
//! ([`uniforms`]).

use bytemuck::Zeroable;
use glam::Vec3;

use super::FramePipelines;
use crate::frame::{FrameParams, ShadingSettings};
use crate::render::marker_gpu::{GpuMarker, MarkerUniform};
use crate::render::pipelines::Pass;
use crate::scene::MAX_LIGHTS;

/// The markers' pass.
pub const PASS: Pass = Pass::LightMarker;

/// The lights whose markers are drawn, by index.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct MarkerDraw {
    lights: Vec<u32>,
}

/// The lights that are on, when `shading` shows the markers.
pub fn plan(shading: &ShadingSettings, params: &FrameParams) -> Option<MarkerDraw> {
    let lights = params.lights.as_slice().iter().enumerate().filter(|(_, light)| light.enabled);
    shading.show_light_marker.then(|| MarkerDraw { lights: lights.map(|(i, _)| i as u32).collect() })
}

/// The markers' uniform of `params`: each light's marker centre (world space, metres) and its
/// colour clamped to 0..1; zero past the last light.
pub fn uniforms(params: &FrameParams) -> [MarkerUniform; MAX_LIGHTS] {
    let mut markers = [MarkerUniform::zeroed(); MAX_LIGHTS];
    for (i, (marker, light)) in markers.iter_mut().zip(params.lights.as_slice()).enumerate() {
        let centre = params.marker_position(i);
        *marker = MarkerUniform {
            centre: centre.extend(1.0).to_array(),
            color: light.color.clamp(Vec3::ZERO, Vec3::ONE).extend(1.0).to_array(),
        };
    }
    markers
}

/// Draws the planned lights' markers.
pub fn record(pass: &mut wgpu::RenderPass, pipelines: &FramePipelines, marker: &GpuMarker, draw: &MarkerDraw) {
    pass.set_pipeline(pipelines.get(PASS));
    pass.set_bind_group(1, &marker.bind_group, &[]);
    pass.set_vertex_buffer(0, marker.positions.slice(..));
    pass.set_index_buffer(marker.indices.slice(..), wgpu::IndexFormat::Uint32);
    for &i in &draw.lights {
        pass.draw_indexed(0..marker.index_count, 0, i..i + 1);
    }
}
