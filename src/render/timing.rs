//! What a frame costs on this adapter: frames and the adapter's floor
//! ([`Renderer::draw_floor`]) drawn alternately in one run, each waited for, as medians and
//! their ratio. `bumpview render --frames N` prints it; the frame benchmark uses it.

use std::fmt;
use std::num::NonZeroU32;

use web_time::Instant;

use super::capture::IMAGE_FORMAT;
use super::{DrawOptions, RenderTarget, Renderer};
use crate::error::RenderError;
use crate::frame::{FrameParams, FrameQuality, Msaa, SplitFrame};

/// Median wall times of a frame and of the floor, milliseconds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameTiming {
    /// One frame: recording, submission and the adapter's work until it is done, at the
    /// quality's render size and MSAA.
    pub frame_ms: f64,
    /// The floor at the view's full size with the same MSAA: the least a frame shown in that
    /// view costs.
    pub floor_ms: f64,
}

impl FrameTiming {
    /// The frame's median time over the floor's.
    pub fn ratio(&self) -> f64 {
        self.frame_ms / self.floor_ms
    }
}

impl fmt::Display for FrameTiming {
    /// `frame <ms> ms, floor <ms> ms, ratio <r>`: the `--frames` line.
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        write!(f, "frame {:.2} ms, floor {:.2} ms, ratio {:.2}", self.frame_ms, self.floor_ms, self.ratio())
    }
}

/// What to time: a picture (the split view when `split` is given) shown in a view of
/// `view_size` pixels, drawn with `quality`.
#[derive(Debug, Clone, Copy)]
pub struct TimedPicture<'a> {
    pub params: &'a FrameParams,
    pub split: Option<&'a SplitFrame>,
    pub view_size: [u32; 2],
    pub quality: FrameQuality,
}

/// Draws `frames` frames of `picture` and as many floors, alternately (so both see the same
/// load on a shared machine), each submitted alone and waited for, after one untimed frame
/// and floor that build pipelines and attachments. Targets are [`IMAGE_FORMAT`], like
/// screenshots and the window's view.
pub fn time_frames(
    renderer: &mut Renderer,
    picture: &TimedPicture,
    frames: NonZeroU32,
) -> Result<FrameTiming, RenderError> {
    time_turning_frames(renderer, picture, frames, 0.0)
}

/// [`time_frames`] with the camera turned by `degrees_per_frame` about its target before each
/// frame (yaw), as while the view is dragged: work done once per view (GPU displacement's
/// tessellation) is then done every frame.
pub fn time_turning_frames(
    renderer: &mut Renderer,
    picture: &TimedPicture,
    frames: NonZeroU32,
    degrees_per_frame: f32,
) -> Result<FrameTiming, RenderError> {
    let render_size = picture.quality.render_size(picture.view_size);
    renderer.check_target_size(picture.view_size)?;
    let frame_texture = target_texture(renderer.device(), render_size);
    let floor_texture = target_texture(renderer.device(), picture.view_size);
    let frame_view = frame_texture.create_view(&Default::default());
    let floor_view = floor_texture.create_view(&Default::default());
    let frame_target = RenderTarget { view: &frame_view, format: IMAGE_FORMAT, size: render_size };
    let floor_target = RenderTarget { view: &floor_view, format: IMAGE_FORMAT, size: picture.view_size };
    let options = DrawOptions { msaa: picture.quality.msaa, ..Default::default() };
    let mut params = *picture.params;
    let mut frame = |renderer: &mut Renderer| {
        if degrees_per_frame != 0.0 {
            params.camera.orbit(degrees_per_frame.to_radians(), 0.0);
        }
        timed(renderer, |renderer, encoder| renderer.draw(encoder, &frame_target, &params, picture.split, options))
    };
    let floor = |renderer: &mut Renderer| {
        timed(renderer, |renderer, encoder| renderer.draw_floor(encoder, &floor_target, options.msaa))
    };
    frame(renderer)?;
    floor(renderer)?;
    let mut frame_times = Vec::new();
    let mut floor_times = Vec::new();
    for _ in 0..frames.get() {
        frame_times.push(frame(renderer)?);
        floor_times.push(floor(renderer)?);
    }
    Ok(FrameTiming { frame_ms: median(frame_times), floor_ms: median(floor_times) })
}

/// The median time of `frames` floors at `size` with `msaa` in [`IMAGE_FORMAT`], each waited
/// for, after one untimed floor, in milliseconds: the budget of the viewer's interactive
/// frames is a multiple of it.
pub fn time_floor(renderer: &mut Renderer, size: [u32; 2], msaa: Msaa, frames: NonZeroU32) -> Result<f64, RenderError> {
    renderer.check_target_size(size)?;
    let texture = target_texture(renderer.device(), size);
    let view = texture.create_view(&Default::default());
    let target = RenderTarget { view: &view, format: IMAGE_FORMAT, size };
    timed(renderer, |renderer, encoder| renderer.draw_floor(encoder, &target, msaa))?;
    let times = (0..frames.get())
        .map(|_| timed(renderer, |renderer, encoder| renderer.draw_floor(encoder, &target, msaa)))
        .collect::<Result<Vec<_>, _>>()?;
    Ok(median(times))
}

/// A render target of `size` in [`IMAGE_FORMAT`] (render attachment only).
pub fn target_texture(device: &wgpu::Device, size: [u32; 2]) -> wgpu::Texture {
    device.create_texture(&wgpu::TextureDescriptor {
        label: Some("timed target"),
        size: wgpu::Extent3d { width: size[0], height: size[1], depth_or_array_layers: 1 },
        mip_level_count: 1,
        sample_count: 1,
        dimension: wgpu::TextureDimension::D2,
        format: IMAGE_FORMAT,
        usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
        view_formats: &[],
    })
}

/// Milliseconds from recording `record` to the adapter finishing it: records into a fresh
/// encoder, submits and waits.
pub fn timed(
    renderer: &mut Renderer,
    record: impl FnOnce(&mut Renderer, &mut wgpu::CommandEncoder) -> Result<(), RenderError>,
) -> Result<f64, RenderError> {
    let start = Instant::now();
    let mut encoder = renderer.device().create_command_encoder(&Default::default());
    record(renderer, &mut encoder)?;
    renderer.queue().submit([encoder.finish()]);
    renderer.device().poll(wgpu::PollType::wait_indefinitely()).map_err(|e| RenderError::Wait(e.to_string()))?;
    Ok(start.elapsed().as_secs_f64() * 1e3)
}

/// The median of `values` (the mean of the middle two for an even count); `values` not empty.
fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    let middle = values.len() / 2;
    if values.len() % 2 == 1 { values[middle] } else { 0.5 * (values[middle - 1] + values[middle]) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn median_of_odd_and_even_counts() {
        assert_eq!(median(vec![3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(vec![4.0, 1.0, 3.0, 2.0]), 2.5);
    }

    #[test]
    fn the_line_has_the_documented_format() {
        let timing = FrameTiming { frame_ms: 12.345, floor_ms: 4.0 };
        assert_eq!(timing.to_string(), "frame 12.35 ms, floor 4.00 ms, ratio 3.09");
    }
}
