//! The light markers: a small unlit octahedron at each light that is on, in its colour, when
//! the half's shading shows them, sized from the scene's bounds ([`marker_radius`]). Light i
//! is instance i of the marker mesh, its centre and colour element i of the markers' uniform
//! ([`uniforms`]).

use bytemuck::Zeroable;
use glam::Vec3;

use super::FramePipelines;
use crate::frame::{FrameParams, ShadingSettings};
use crate::render::pipelines::Pass;
use crate::render::scene_gpu::{GpuMarker, MarkerUniform};
use crate::scene::{MAX_LIGHTS, Scene};

/// A marker's radius (centre to tip) as a share of the scene's bounding-box diagonal: 0.058 m
/// on the built-in scene (5.83 m), 3.0 mm on WaterBottle (0.30 m).
pub const MARKER_SHARE_OF_SCENE: f32 = 0.01;

/// The light markers' radius for `scene`, metres: [`MARKER_SHARE_OF_SCENE`] of the diagonal
/// of its drawn bounds ([`crate::load::bounds`]); 0.06 m for a scene without finite vertices.
pub fn marker_radius(scene: &Scene) -> f32 {
    let diagonal = crate::load::bounds(scene).map(|(low, high)| (high - low).length());
    match diagonal {
        Some(d) if d.is_finite() && d > 0.0 => MARKER_SHARE_OF_SCENE * d,
        _ => 0.06,
    }
}

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
