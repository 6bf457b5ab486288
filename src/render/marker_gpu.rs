//! The light markers' GPU data: an octahedron sized from the scene ([`marker_radius`]), drawn
//! once per light that is on, and the uniform that places and colours each
//! ([`MarkerUniform`]). Uploaded with the scene ([`super::scene_gpu`]), drawn by
//! `render::draw::markers`.

use glam::Vec3;

use super::bindings;
use super::gpu_errors::buffer_with;
use super::pipelines::Layouts;
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

/// The light markers: an octahedron drawn once per light that is on, at its centre in its
/// colour ([`MarkerUniform`]).
pub struct GpuMarker {
    pub positions: wgpu::Buffer,
    pub indices: wgpu::Buffer,
    pub index_count: u32,
    /// `[MarkerUniform; MAX_LIGHTS]`, by the frame's light index.
    pub lights: wgpu::Buffer,
    pub bind_group: wgpu::BindGroup,
}

/// WGSL `Marker` (shaders/marker.wgsl): one light's marker.
#[repr(C)]
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
pub struct MarkerUniform {
    /// World space, metres ([`crate::frame::FrameParams::marker_position`]); w unused.
    pub centre: [f32; 4],
    /// The light's colour with each channel at most 1; a unused.
    pub color: [f32; 4],
}

impl GpuMarker {
    /// The markers of `scene`: the octahedron and the uniform buffer (filled per frame).
    pub fn upload(device: &wgpu::Device, layouts: &Layouts, scene: &Scene) -> GpuMarker {
        let (positions, indices) = octahedron(marker_radius(scene));
        let lights = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("light markers"),
            size: std::mem::size_of::<[MarkerUniform; MAX_LIGHTS]>() as u64,
            usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let bind_group = device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("light marker"),
            layout: &layouts.marker,
            entries: &[bindings::MARKERS.entry(lights.as_entire_binding())],
        });
        GpuMarker {
            positions: buffer_with(
                device,
                "marker positions",
                bytemuck::cast_slice(&positions),
                wgpu::BufferUsages::VERTEX,
            ),
            indices: buffer_with(device, "marker indices", bytemuck::cast_slice(&indices), wgpu::BufferUsages::INDEX),
            index_count: indices.len() as u32,
            lights,
            bind_group,
        }
    }
}

/// The light marker's geometry: an octahedron of `radius` metres around the origin.
fn octahedron(radius: f32) -> (Vec<Vec3>, Vec<u32>) {
    let positions = [Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z].map(|v| v * radius).to_vec();
    let mut indices = vec![];
    for (a, b) in [(0u32, 4u32), (4, 1), (1, 5), (5, 0)] {
        indices.extend([b, a, 2, a, b, 3]);
    }
    (positions, indices)
}
