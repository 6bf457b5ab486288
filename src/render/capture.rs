//! Offscreen frames read back to the CPU, and PNG files written atomically.

use std::path::Path;

use super::{FrameParams, RenderTarget, Renderer};
use crate::error::RenderError;

/// Format of pictures: 8-bit RGBA holding sRGB-encoded values.
pub const IMAGE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;
/// Format for scans of raw shader output: 32-bit float RGBA keeps NaN and infinity.
pub const FLOAT_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba32Float;

/// A frame of [`FLOAT_FORMAT`] pixels, rows top to bottom.
pub struct FloatImage {
    pub width: u32,
    pub height: u32,
    pub pixels: Vec<[f32; 4]>,
}

/// Renders one frame at `size` into a fresh texture of `format` and returns its bytes,
/// tightly packed, rows top to bottom.
fn render_offscreen(
    renderer: &mut Renderer,
    size: [u32; 2],
    format: wgpu::TextureFormat,
    params: &FrameParams,
) -> Result<Vec<u8>, RenderError> {
    renderer.check_target_size(size)?;
    let [width, height] = size;
    let extent = wgpu::Extent3d { width, height, depth_or_array_layers: 1 };
    let device = renderer.device().clone();
    let texture = device.create_texture(&wgpu::TextureDescriptor {
        label: Some("offscreen"),
        size: extent,
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC,
        view_formats: &[],
    });
    let view = texture.create_view(&Default::default());
    let mut encoder = device.create_command_encoder(&Default::default());
    renderer.render(&mut encoder, &RenderTarget { view: &view, format, size }, params)?;

    let bytes_per_pixel = format.block_copy_size(None).expect("colour format");
    let row_bytes = width * bytes_per_pixel;
    let padded_row_bytes = row_bytes.div_ceil(wgpu::COPY_BYTES_PER_ROW_ALIGNMENT) * wgpu::COPY_BYTES_PER_ROW_ALIGNMENT;
    let buffer = device.create_buffer(&wgpu::BufferDescriptor {
        label: Some("readback"),
        size: padded_row_bytes as u64 * height as u64,
        usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
        mapped_at_creation: false,
    });
    encoder.copy_texture_to_buffer(
        texture.as_image_copy(),
        wgpu::TexelCopyBufferInfo {
            buffer: &buffer,
            layout: wgpu::TexelCopyBufferLayout {
                offset: 0,
                bytes_per_row: Some(padded_row_bytes),
                rows_per_image: None,
            },
        },
        extent,
    );
    renderer.queue().submit([encoder.finish()]);

    let slice = buffer.slice(..);
    let (sender, receiver) = std::sync::mpsc::channel();
    slice.map_async(wgpu::MapMode::Read, move |result| {
        let _ = sender.send(result);
    });
    device.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| RenderError::Readback(e.to_string()))?;
    receiver
        .recv()
        .map_err(|e| RenderError::Readback(e.to_string()))?
        .map_err(|e| RenderError::Readback(e.to_string()))?;
    let mapped = slice.get_mapped_range().map_err(|e| RenderError::Readback(e.to_string()))?;
    let mut bytes = Vec::with_capacity((row_bytes * height) as usize);
    for row in mapped.chunks_exact(padded_row_bytes as usize) {
        bytes.extend_from_slice(&row[..row_bytes as usize]);
    }
    Ok(bytes)
}

/// Renders one frame offscreen as an sRGB RGBA8 image: the pixels a screenshot holds.
pub fn render_image(
    renderer: &mut Renderer,
    size: [u32; 2],
    params: &FrameParams,
) -> Result<image::RgbaImage, RenderError> {
    let bytes = render_offscreen(renderer, size, IMAGE_FORMAT, params)?;
    Ok(image::RgbaImage::from_raw(size[0], size[1], bytes).expect("4 bytes per pixel"))
}

/// Renders one frame offscreen to a float target: raw shader output, NaN and infinity kept.
pub fn render_float(renderer: &mut Renderer, size: [u32; 2], params: &FrameParams) -> Result<FloatImage, RenderError> {
    let bytes = render_offscreen(renderer, size, FLOAT_FORMAT, params)?;
    let pixels = bytes
        .chunks_exact(16)
        .map(|p| std::array::from_fn(|i| f32::from_le_bytes(p[i * 4..i * 4 + 4].try_into().expect("4 bytes"))))
        .collect();
    Ok(FloatImage { width: size[0], height: size[1], pixels })
}

/// Writes `image` as a PNG at `path` through a temporary file in the same folder and a
/// rename, so an interrupted write never leaves a broken file at `path`.
pub fn write_png_atomically(image: &image::RgbaImage, path: &Path) -> Result<(), RenderError> {
    let failed = |reason: String| RenderError::Write { path: path.to_owned(), reason };
    let file_name = path.file_name().ok_or_else(|| failed("not a file path".into()))?;
    let temporary = path.with_file_name(format!(".{}.{}.tmp", file_name.to_string_lossy(), std::process::id()));
    let result = image
        .save_with_format(&temporary, image::ImageFormat::Png)
        .map_err(|e| failed(e.to_string()))
        .and_then(|()| std::fs::rename(&temporary, path).map_err(|e| failed(e.to_string())));
    if result.is_err() {
        let _ = std::fs::remove_file(&temporary);
    }
    result
}
