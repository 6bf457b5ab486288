//! A frame's GPU time from timestamp queries: timestamps written into the command encoder
//! before and after the frame's passes, resolved and read back, times the queue's timestamp
//! period. Only where the device has `TIMESTAMP_QUERY` and `TIMESTAMP_QUERY_INSIDE_ENCODERS`
//! ([`crate::render::Gpu::headless`] asks for them when the adapter has them).

use std::num::NonZeroU32;

use crate::error::RenderError;
use crate::frame::{FrameParams, Msaa};
use crate::render::capture::IMAGE_FORMAT;
use crate::render::timing::target_texture;
use crate::render::{DrawOptions, RenderTarget, Renderer};

/// The features timestamp timing needs.
pub const FEATURES: wgpu::Features =
    wgpu::Features::TIMESTAMP_QUERY.union(wgpu::Features::TIMESTAMP_QUERY_INSIDE_ENCODERS);

/// The median GPU time in milliseconds of `frames` full-quality frames (4× MSAA where the
/// format allows) of `params` at `size`, after one untimed frame; `None` without the
/// features.
pub fn gpu_frame_ms(
    renderer: &mut Renderer,
    params: &FrameParams,
    size: [u32; 2],
    frames: NonZeroU32,
) -> Result<Option<f64>, RenderError> {
    let device = renderer.device().clone();
    if !device.features().contains(FEATURES) {
        return Ok(None);
    }
    renderer.check_target_size(size)?;
    let texture = target_texture(&device, size);
    let view = texture.create_view(&Default::default());
    let target = RenderTarget { view: &view, format: IMAGE_FORMAT, size };
    let options = DrawOptions { msaa: Msaa::X4, ..Default::default() };
    let queries = device.create_query_set(&wgpu::QuerySetDescriptor {
        label: Some("frame timestamps"),
        ty: wgpu::QueryType::Timestamp,
        count: 2,
    });
    let buffer = |usage| {
        device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("timestamps"),
            size: 16,
            usage,
            mapped_at_creation: false,
        })
    };
    let resolved = buffer(wgpu::BufferUsages::QUERY_RESOLVE | wgpu::BufferUsages::COPY_SRC);
    let readback = buffer(wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST);
    let period_ns = renderer.queue().get_timestamp_period() as f64;
    let mut times = vec![];
    for frame in 0..=frames.get() {
        let mut encoder = device.create_command_encoder(&Default::default());
        encoder.write_timestamp(&queries, 0);
        renderer.draw(&mut encoder, &target, params, None, options)?;
        encoder.write_timestamp(&queries, 1);
        encoder.resolve_query_set(&queries, 0..2, &resolved, 0);
        encoder.copy_buffer_to_buffer(&resolved, 0, &readback, 0, 16);
        renderer.queue().submit([encoder.finish()]);
        let slice = readback.slice(..);
        slice.map_async(wgpu::MapMode::Read, |_| {});
        device.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| RenderError::Wait(e.to_string()))?;
        let ticks: Vec<u64> = {
            let bytes = slice.get_mapped_range().map_err(|e| RenderError::Wait(e.to_string()))?;
            bytes.chunks_exact(8).map(|b| u64::from_le_bytes(b.try_into().expect("8 bytes"))).collect()
        };
        readback.unmap();
        if frame > 0 {
            times.push(ticks[1].saturating_sub(ticks[0]) as f64 * period_ns / 1e6);
        }
    }
    times.sort_by(f64::total_cmp);
    Ok(Some(times[times.len() / 2]))
}
