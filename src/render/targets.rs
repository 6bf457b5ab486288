//! A frame's attachments: multisampled colour (resolved into the target) and depth, kept per
//! sample count so frames that switch between 1 and 4 samples (interactive and full quality)
//! keep both, and the render pass that clears and draws into them.

use super::Background;
use super::pipelines::DEPTH_FORMAT;

/// Multisampled colour and depth attachments for one target size, format and sample count.
pub struct FrameTargets {
    size: [u32; 2],
    format: wgpu::TextureFormat,
    samples: u32,
    /// `None` at 1 sample: the frame is drawn into the target itself.
    msaa_color: Option<wgpu::TextureView>,
    depth: wgpu::TextureView,
}

/// The attachments of the last frame drawn with each sample count.
#[derive(Default)]
pub struct Attachments {
    targets: Vec<FrameTargets>,
}

impl Attachments {
    /// Makes the attachments for `samples` at `size` (pixels) and `format`, unless the last
    /// frame with that sample count had them.
    pub fn ensure(&mut self, device: &wgpu::Device, size: [u32; 2], format: wgpu::TextureFormat, samples: u32) {
        let current = self.targets.iter().find(|t| t.samples == samples);
        if current.is_some_and(|t| t.size == size && t.format == format) {
            return;
        }
        self.targets.retain(|t| t.samples != samples);
        let texture = |label: &str, format| {
            device
                .create_texture(&wgpu::TextureDescriptor {
                    label: Some(label),
                    size: wgpu::Extent3d { width: size[0], height: size[1], depth_or_array_layers: 1 },
                    mip_level_count: 1,
                    sample_count: samples,
                    dimension: wgpu::TextureDimension::D2,
                    format,
                    usage: wgpu::TextureUsages::RENDER_ATTACHMENT,
                    view_formats: &[],
                })
                .create_view(&Default::default())
        };
        let msaa_color = (samples > 1).then(|| texture("msaa colour", format));
        let depth = texture("depth", DEPTH_FORMAT);
        self.targets.push(FrameTargets { size, format, samples, msaa_color, depth });
    }

    /// The attachments for `samples`, made by [`Self::ensure`].
    pub fn get(&self, samples: u32) -> &FrameTargets {
        self.targets.iter().find(|t| t.samples == samples).expect("made by Attachments::ensure")
    }
}

/// Begins the one render pass of a frame (or of the floor): `targets`' multisampled colour
/// resolved into `view` (or `view` itself at 1 sample) and their depth, both cleared.
pub fn begin_scene_pass<'e>(
    encoder: &'e mut wgpu::CommandEncoder,
    targets: &FrameTargets,
    view: &wgpu::TextureView,
    background: Background,
) -> wgpu::RenderPass<'e> {
    let (view, resolve_target) = match &targets.msaa_color {
        Some(msaa) => (msaa, Some(view)),
        None => (view, None),
    };
    encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
        label: Some("scene"),
        color_attachments: &[Some(wgpu::RenderPassColorAttachment {
            view,
            depth_slice: None,
            resolve_target,
            ops: wgpu::Operations { load: wgpu::LoadOp::Clear(background.clear_color()), store: wgpu::StoreOp::Store },
        })],
        depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
            view: &targets.depth,
            depth_ops: Some(wgpu::Operations { load: wgpu::LoadOp::Clear(1.0), store: wgpu::StoreOp::Discard }),
            stencil_ops: None,
        }),
        timestamp_writes: None,
        occlusion_query_set: None,
        multiview_mask: None,
    })
}
