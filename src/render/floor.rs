//! The adapter's floor: a clear and one full-screen triangle of one colour (shaders/floor.wgsl),
//! drawn with a frame's attachments ([`super::Renderer::draw_floor`]). Its pipelines are
//! built on first use per format and sample count, and counted with the scene's.

use std::collections::HashMap;

use super::pipelines::DEPTH_FORMAT;
use super::shaders;
use crate::counters::WorkCounters;

/// The floor's shader and its pipelines by target format and sample count.
pub struct FloorPipelines {
    module: wgpu::ShaderModule,
    cache: HashMap<(wgpu::TextureFormat, u32), wgpu::RenderPipeline>,
}

impl FloorPipelines {
    pub fn new(device: &wgpu::Device) -> Self {
        let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
            label: Some(shaders::FLOOR.label),
            source: wgpu::ShaderSource::Wgsl(shaders::FLOOR.source().into()),
        });
        FloorPipelines { module, cache: HashMap::new() }
    }

    /// Builds the pipeline for `format` and `samples` unless it is cached.
    pub fn ensure(
        &mut self,
        device: &wgpu::Device,
        format: wgpu::TextureFormat,
        samples: u32,
        counters: &mut WorkCounters,
    ) {
        if self.cache.contains_key(&(format, samples)) {
            return;
        }
        // Depth test and writes as the meshes' pipelines have them (super::pipelines).
        let pipeline = device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
            label: Some("floor"),
            layout: None,
            vertex: wgpu::VertexState {
                module: &self.module,
                entry_point: Some("vs_floor"),
                buffers: &[],
                compilation_options: Default::default(),
            },
            primitive: wgpu::PrimitiveState::default(),
            depth_stencil: Some(wgpu::DepthStencilState {
                format: DEPTH_FORMAT,
                depth_write_enabled: Some(true),
                depth_compare: Some(wgpu::CompareFunction::Less),
                stencil: Default::default(),
                bias: Default::default(),
            }),
            multisample: wgpu::MultisampleState { count: samples, ..Default::default() },
            fragment: Some(wgpu::FragmentState {
                module: &self.module,
                entry_point: Some("fs_floor"),
                targets: &[Some(wgpu::ColorTargetState { format, blend: None, write_mask: wgpu::ColorWrites::ALL })],
                compilation_options: Default::default(),
            }),
            multiview_mask: None,
            cache: None,
        });
        counters.pipelines_built += 1;
        self.cache.insert((format, samples), pipeline);
    }

    /// A pipeline previously made by [`Self::ensure`].
    pub fn get(&self, format: wgpu::TextureFormat, samples: u32) -> &wgpu::RenderPipeline {
        &self.cache[&(format, samples)]
    }
}
