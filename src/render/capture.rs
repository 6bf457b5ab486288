//! Offscreen frames read back to the CPU, and PNG files written atomically.

use std::path::Path;

use super::gpu_errors::caught;
use super::{Background, DrawOptions, RenderTarget, Renderer};
use crate::error::RenderError;
use crate::frame::{FrameParams, SplitFrame};
use crate::math::{linear_to_srgb, srgb_to_linear};

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

/// Renders one full-quality frame at `size` into a fresh texture of `format` and returns its
/// bytes, tightly packed, rows top to bottom. With `split`, the split view with its divider at
/// the given column.
fn render_offscreen(
    renderer: &mut Renderer,
    size: [u32; 2],
    format: wgpu::TextureFormat,
    params: &FrameParams,
    background: Background,
    split: Option<(&SplitFrame, u32)>,
) -> Result<Vec<u8>, RenderError> {
    let split = split.map(|(split, divider_x)| SplitFrame { divider: divider_x as f32 / size[0] as f32, ..*split });
    let options = DrawOptions { background, ..Default::default() };
    draw_offscreen(renderer, size, format, |renderer, encoder, target| {
        renderer.draw(encoder, target, params, split.as_ref(), options)
    })
}

/// Runs `record` on a fresh texture of `size` and `format` (e.g. [`Renderer::draw`] with any
/// options, or [`Renderer::draw_floor`]) and returns the texture's bytes, tightly packed, rows
/// top to bottom.
pub fn draw_offscreen(
    renderer: &mut Renderer,
    size: [u32; 2],
    format: wgpu::TextureFormat,
    record: impl FnOnce(&mut Renderer, &mut wgpu::CommandEncoder, &RenderTarget) -> Result<(), RenderError>,
) -> Result<Vec<u8>, RenderError> {
    renderer.check_target_size(size)?;
    let [width, height] = size;
    let extent = wgpu::Extent3d { width, height, depth_or_array_layers: 1 };
    let device = renderer.device().clone();
    // A large picture may not fit in GPU memory: catch that (and what follows from it) as an
    // error instead of wgpu's default handler, which panics. Scopes pop in reverse order.
    let validation = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let out_of_memory = device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
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
    let target = RenderTarget { view: &view, format, size };
    record(renderer, &mut encoder, &target)?;

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
    let commands = encoder.finish();
    let memory_error = pollster::block_on(out_of_memory.pop());
    if let Some(error) = memory_error.or(pollster::block_on(validation.pop())) {
        return Err(RenderError::Gpu { width, height, reason: error.to_string() });
    }
    let slice = buffer.slice(..);
    let (sender, receiver) = std::sync::mpsc::channel();
    // The submission and the mapping may meet the device's limits too (memory it cannot map).
    caught(&device, || {
        renderer.queue().submit([commands]);
        slice.map_async(wgpu::MapMode::Read, move |result| {
            let _ = sender.send(result);
        });
    })
    .map_err(|reason| RenderError::Gpu { width, height, reason })?;
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
    let bytes = render_offscreen(renderer, size, IMAGE_FORMAT, params, Background::Opaque, None)?;
    Ok(image::RgbaImage::from_raw(size[0], size[1], bytes).expect("4 bytes per pixel"))
}

/// Renders one frame offscreen to a float target: raw shader output, NaN and infinity kept.
pub fn render_float(renderer: &mut Renderer, size: [u32; 2], params: &FrameParams) -> Result<FloatImage, RenderError> {
    render_float_with(renderer, size, params, None)
}

/// [`render_float`] of the split view.
pub fn render_float_split(
    renderer: &mut Renderer,
    size: [u32; 2],
    params: &FrameParams,
    split: &SplitFrame,
) -> Result<FloatImage, RenderError> {
    render_float_with(renderer, size, params, Some(split))
}

fn render_float_with(
    renderer: &mut Renderer,
    size: [u32; 2],
    params: &FrameParams,
    split: Option<&SplitFrame>,
) -> Result<FloatImage, RenderError> {
    let split = split.map(|s| (s, s.divider_pixels(size[0])));
    let bytes = render_offscreen(renderer, size, FLOAT_FORMAT, params, Background::Opaque, split)?;
    let pixels = bytes
        .chunks_exact(16)
        .map(|p| std::array::from_fn(|i| f32::from_le_bytes(p[i * 4..i * 4 + 4].try_into().expect("4 bytes"))))
        .collect();
    Ok(FloatImage { width: size[0], height: size[1], pixels })
}

/// Largest supersampling factor of a capture.
pub const MAX_SUPERSAMPLE: u32 = 4;

/// How a screenshot is made: the 3D view only, at any size the adapter allows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CaptureOptions {
    /// Width and height of the PNG, pixels.
    pub size: [u32; 2],
    /// With [`Background::Transparent`] the PNG has alpha 0 where there is no geometry.
    pub background: Background,
    /// Render at this many times `size` (1..=[`MAX_SUPERSAMPLE`]) and box-filter down in
    /// linear light.
    pub supersample: u32,
}

impl CaptureOptions {
    /// A plain capture: opaque background, no supersampling.
    pub fn plain(size: [u32; 2]) -> CaptureOptions {
        CaptureOptions { size, background: Background::Opaque, supersample: 1 }
    }
}

/// Renders a screenshot as `options` say: an sRGB RGBA8 image of `options.size`. A
/// transparent background gives straight (not premultiplied) alpha, as PNG expects.
pub fn render_capture(
    renderer: &mut Renderer,
    options: &CaptureOptions,
    params: &FrameParams,
) -> Result<image::RgbaImage, RenderError> {
    capture_with(renderer, options, params, None)
}

/// [`render_capture`] of the split view: one image, the divider on the column
/// [`SplitFrame::divider_pixels`] gives at `options.size` (supersampled blocks never straddle it).
pub fn render_capture_split(
    renderer: &mut Renderer,
    options: &CaptureOptions,
    params: &FrameParams,
    split: &SplitFrame,
) -> Result<image::RgbaImage, RenderError> {
    capture_with(renderer, options, params, Some(split))
}

fn capture_with(
    renderer: &mut Renderer,
    options: &CaptureOptions,
    params: &FrameParams,
    split: Option<&SplitFrame>,
) -> Result<image::RgbaImage, RenderError> {
    let factor = options.supersample;
    if !(1..=MAX_SUPERSAMPLE).contains(&factor) {
        return Err(RenderError::SupersampleFactor { factor, max: MAX_SUPERSAMPLE });
    }
    renderer.check_target_size(options.size)?;
    let [width, height] = options.size;
    let limit = renderer.max_target_size();
    let rendered = [width.saturating_mul(factor), height.saturating_mul(factor)];
    if rendered.iter().any(|&side| side > limit) {
        return Err(RenderError::SupersampleTooLarge { width, height, factor, limit });
    }
    let split = split.map(|s| (s, s.divider_pixels(width) * factor));
    let bytes = render_offscreen(renderer, rendered, IMAGE_FORMAT, params, options.background, split)?;
    let image = image::RgbaImage::from_raw(rendered[0], rendered[1], bytes).expect("4 bytes per pixel");
    let transparent = options.background == Background::Transparent;
    Ok(if factor == 1 && !transparent { image } else { downsample(&image, factor, transparent) })
}

/// Averages `factor`×`factor` blocks of `image` (sRGB colour, linear alpha) in linear light;
/// with `unpremultiply`, divides colour by alpha (the target held premultiplied colour over
/// transparent black).
fn downsample(image: &image::RgbaImage, factor: u32, unpremultiply: bool) -> image::RgbaImage {
    let to_linear: [f32; 256] = std::array::from_fn(|i| srgb_to_linear(i as f32 / 255.0));
    let count = (factor * factor) as f32;
    image::RgbaImage::from_fn(image.width() / factor, image.height() / factor, |x, y| {
        let mut sum = [0.0f32; 4];
        for dy in 0..factor {
            for dx in 0..factor {
                let p = image.get_pixel(x * factor + dx, y * factor + dy).0;
                for c in 0..3 {
                    sum[c] += to_linear[p[c] as usize];
                }
                sum[3] += p[3] as f32 / 255.0;
            }
        }
        let alpha = sum[3] / count;
        let scale = if unpremultiply && alpha > 0.0 { 1.0 / (alpha * count) } else { 1.0 / count };
        let channel = |c: usize| (linear_to_srgb(sum[c] * scale) * 255.0).round() as u8;
        image::Rgba([channel(0), channel(1), channel(2), (alpha * 255.0).round() as u8])
    })
}

/// Writes `image` as a PNG at `path` atomically ([`crate::atomic::write_atomically`]), so an
/// interrupted write never leaves a broken file at `path`.
pub fn write_png_atomically(image: &image::RgbaImage, path: &Path) -> Result<(), RenderError> {
    crate::atomic::write_atomically(path, |writer| {
        image.write_to(writer, image::ImageFormat::Png).map_err(std::io::Error::other)
    })
    .map_err(|e| RenderError::Write { path: path.to_owned(), reason: e.to_string() })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn downsampling_averages_in_linear_light_and_unpremultiplies() {
        // Black and white average to linear 0.5 (sRGB 188), not to 128.
        let image =
            image::RgbaImage::from_fn(2, 2, |x, _| if x == 0 { image::Rgba([0; 4]) } else { image::Rgba([255; 4]) });
        assert_eq!(downsample(&image, 2, false).get_pixel(0, 0).0, [188, 188, 188, 128]);
        // Half-covered white over transparent black is white at half alpha.
        assert_eq!(downsample(&image, 2, true).get_pixel(0, 0).0, [255, 255, 255, 128]);
        // Every 8-bit value survives the linear round trip.
        let ramp = image::RgbaImage::from_fn(256, 1, |x, _| image::Rgba([x as u8, x as u8, x as u8, 255]));
        assert_eq!(downsample(&ramp, 1, true), ramp);
    }
}
