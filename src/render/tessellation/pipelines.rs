//! The compute pipelines of GPU displacement, made once per renderer.

use crate::render::bindings;
use crate::render::shaders;

/// Workgroups per row of a dispatch: a dispatch of more is two-dimensional (WebGPU allows
/// 65535 workgroups along each dimension).
pub const ROW_GROUPS: u32 = 32768;

/// `cs_vertices` and `cs_triangles` of shaders/displace.wgsl, over [`bindings::DISPLACE_GROUP`]
/// in group 2.
pub struct DisplacePipelines {
    pub layout: wgpu::BindGroupLayout,
    pub vertices: wgpu::ComputePipeline,
    pub triangles: wgpu::ComputePipeline,
}

impl DisplacePipelines {
    pub fn new(device: &wgpu::Device) -> DisplacePipelines {
        let entries: Vec<_> = bindings::DISPLACE_GROUP.iter().map(bindings::Slot::layout_entry).collect();
        let layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("GPU displacement"),
            entries: &entries,
        });
        let pipeline_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("GPU displacement"),
            bind_group_layouts: &[None, None, Some(&layout)],
            immediate_size: 0,
        });
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(shaders::DISPLACE.label),
            source: wgpu::ShaderSource::Wgsl(shaders::DISPLACE.source().into()),
        });
        let pipeline = |entry_point: &str| {
            device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some(entry_point),
                layout: Some(&pipeline_layout),
                module: &module,
                entry_point: Some(entry_point),
                compilation_options: Default::default(),
                cache: None,
            })
        };
        DisplacePipelines { vertices: pipeline("cs_vertices"), triangles: pipeline("cs_triangles"), layout }
    }
}
