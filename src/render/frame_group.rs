//! Group 0 of each half of a frame: its `Frame` uniform and the legacy looks' textures
//! ([`super::legacy`]). The split view's right half has its own uniform, as both halves are
//! written before the encoder is submitted.

use super::legacy::{LegacyNeeds, LegacyTextures};
use super::uniforms::FrameUniform;
use crate::counters::WorkCounters;
use crate::frame::ShadingSettings;

/// One half's frame uniform and the bind group that holds it with the legacy textures.
struct HalfGroup {
    uniform: wgpu::Buffer,
    bind_group: wgpu::BindGroup,
    /// The legacy textures `bind_group` holds.
    bound: LegacyNeeds,
}

/// The frame bind groups of the (at most two) halves, and the legacy textures they bind.
pub struct FrameGroups {
    halves: [HalfGroup; 2],
    legacy: LegacyTextures,
}

impl FrameGroups {
    /// Both halves' uniforms, bound with the legacy placeholders, for the frame `layout`.
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue, layout: &wgpu::BindGroupLayout) -> Self {
        let legacy = LegacyTextures::new(device, queue);
        let half = |label| {
            let uniform = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: std::mem::size_of::<FrameUniform>() as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            let bound = LegacyNeeds::default();
            let bind_group = legacy.bind_group(device, layout, &uniform, bound);
            HalfGroup { uniform, bind_group, bound }
        };
        FrameGroups { halves: [half("frame"), half("frame (split, right half)")], legacy }
    }

    /// Writes half `index`'s (0 left or whole, 1 right) frame uniform.
    pub fn write(&self, queue: &wgpu::Queue, index: usize, uniform: &FrameUniform) {
        queue.write_buffer(&self.halves[index].uniform, 0, bytemuck::bytes_of(uniform));
    }

    /// Half `index`'s bind group.
    pub fn bind_group(&self, index: usize) -> &wgpu::BindGroup {
        &self.halves[index].bind_group
    }

    /// Makes the legacy looks' textures the halves' `shadings` use (dropping the others) and
    /// rebinds a half whose textures change.
    pub fn bind_legacy_textures(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        layout: &wgpu::BindGroupLayout,
        shadings: &[ShadingSettings],
        counters: &mut WorkCounters,
    ) {
        let needs: Vec<_> = shadings.iter().map(LegacyNeeds::of).collect();
        if needs.iter().zip(&self.halves).all(|(wanted, half)| *wanted == half.bound) {
            return;
        }
        self.legacy.retain(device, queue, &needs, counters);
        for (half, wanted) in self.halves.iter_mut().zip(needs) {
            if half.bound != wanted {
                half.bind_group = self.legacy.bind_group(device, layout, &half.uniform, wanted);
                half.bound = wanted;
            }
        }
    }
}
