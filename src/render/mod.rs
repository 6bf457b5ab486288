//! The wgpu renderer. It draws into any texture view it is given, so the window, screenshots
//! and tests share one code path: [`Renderer::draw`]. Depth-tested, with 4× MSAA where the
//! adapter supports it for the target format ([`Msaa::X4`]) or 1 sample ([`Msaa::Off`], the
//! interactive frames). [`Renderer::draw_floor`] draws the adapter's floor, what any frame of
//! that size and MSAA costs at least; [`timing`] measures frames against it.
//!
//! The renderer keeps the long-lived resources (the pipeline pool, the frame uniforms, the
//! attachments, the scene uploads); each kind of thing drawn — meshes, wireframe, T/B/N glyphs,
//! light markers — has its own file under `render/draw/` that plans its passes from a frame's
//! per-draw values and records them. The WGSL is split by pass ([`shaders`]).
//!
//! A prepared scene can be uploaded without the renderer, on any thread ([`Uploader`], e.g. a
//! scene job's worker), and shown by [`Renderer::install`], a swap that uploads nothing.

pub mod annotate;
mod bindings;
pub mod capture;
mod draw;
pub mod export;
mod floor;
mod frame_group;
pub mod glyphs;
pub mod gpu;
mod gpu_errors;
mod held;
mod legacy;
mod marker_gpu;
pub mod pipelines;
mod scene_gpu;
pub mod shaders;
pub mod srgb_copy;
mod targets;
pub mod tessellation;
pub mod text;
mod texture_cache;
pub mod timing;
mod uniforms;
pub mod upload;
mod window;

use std::sync::Arc;

use crate::counters::WorkCounters;
use crate::error::RenderError;
use crate::frame::{FrameParams, Msaa, ShadingSettings, SplitFrame, ViewMode};
use crate::tangent::TangentMethod;
pub use draw::wireframe::WIREFRAME_UNSUPPORTED;
use draw::{FramePipelines, HalfPlan};
pub use gpu::Gpu;
use pipelines::{PipelineKey, Pipelines};
use scene_gpu::GpuScene;
use targets::{Attachments, begin_scene_pass};
use tessellation::pipelines::DisplacePipelines;
pub use texture_cache::TextureUpload;
use uniforms::FrameUniform;
pub use upload::{ReferenceFrames, SceneUpload, Uploader};
pub use window::PictureWindow;

/// Where to draw: a view of a 2D texture of `format`, `size` pixels.
pub struct RenderTarget<'a> {
    pub view: &'a wgpu::TextureView,
    pub format: wgpu::TextureFormat,
    pub size: [u32; 2],
}

/// Background colour (linear RGB): a dark blue-grey that neither debug colours nor lit
/// bricks are confused with.
const CLEAR_COLOR: wgpu::Color = wgpu::Color { r: 0.02, g: 0.025, b: 0.035, a: 1.0 };

/// What a frame is drawn over where there is no geometry.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Background {
    /// The opaque background colour.
    #[default]
    Opaque,
    /// Transparent black (alpha 0): the target then holds premultiplied colour, antialiased
    /// edges partly transparent.
    Transparent,
}

impl Background {
    fn clear_color(self) -> wgpu::Color {
        match self {
            Background::Opaque => CLEAR_COLOR,
            Background::Transparent => wgpu::Color::TRANSPARENT,
        }
    }
}

/// How a frame is drawn, besides what it shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct DrawOptions {
    pub background: Background,
    pub msaa: Msaa,
}

pub struct Renderer {
    device: wgpu::Device,
    queue: wgpu::Queue,
    adapter: wgpu::Adapter,
    pipelines: Pipelines,
    /// Each half's group 0: its frame uniform and the legacy looks' textures.
    frame_groups: frame_group::FrameGroups,
    /// The floor's pipelines ([`Self::draw_floor`]), by format and sample count.
    floor: floor::FloorPipelines,
    scene: Option<Arc<GpuScene>>,
    /// The split view's right half, when it differs from the left in GPU data
    /// ([`Self::set_split_scene`]); else the right half is drawn from `scene` too.
    split_scene: Option<Arc<GpuScene>>,
    /// The attachments of the last frame drawn with each sample count.
    targets: Attachments,
    counters: WorkCounters,
    /// The scene's notices, plus one while the wireframe is asked for but unsupported, and one
    /// while GPU displacement's budget lengthens its edges.
    notices: Vec<String>,
    /// GPU displacement's compute pipelines, made when a scene first asks for it.
    displace_pipelines: Option<DisplacePipelines>,
    /// The part of the picture frames show ([`Self::set_window`]); `None`: all of it.
    window: Option<PictureWindow>,
}

impl Renderer {
    pub fn new(device: wgpu::Device, queue: wgpu::Queue, adapter: wgpu::Adapter) -> Self {
        let pipelines = Pipelines::new(&device);
        Renderer {
            frame_groups: frame_group::FrameGroups::new(&device, &queue, &pipelines.layouts.frame),
            floor: floor::FloorPipelines::new(&device),
            device,
            queue,
            adapter,
            pipelines,
            scene: None,
            split_scene: None,
            targets: Attachments::default(),
            counters: WorkCounters::default(),
            notices: Vec::new(),
            displace_pipelines: None,
            window: None,
        }
    }

    pub fn from_gpu(gpu: &Gpu) -> Self {
        Renderer::new(gpu.device.clone(), gpu.queue.clone(), gpu.adapter.clone())
    }

    /// "name (backend)" of the adapter drawing the frames.
    pub fn adapter_name(&self) -> String {
        gpu::adapter_name(&self.adapter)
    }

    pub fn device(&self) -> &wgpu::Device {
        &self.device
    }

    pub fn queue(&self) -> &wgpu::Queue {
        &self.queue
    }

    /// Whether the device can draw the wireframe overlay (`POLYGON_MODE_LINE`).
    pub fn supports_wireframe(&self) -> bool {
        self.device.features().contains(wgpu::Features::POLYGON_MODE_LINE)
    }

    /// Per mesh of the current scene: the tangent method its frames come from, or `None`
    /// when it is drawn without tangents.
    pub fn tangent_methods(&self) -> Vec<Option<TangentMethod>> {
        let meshes = self.scene.iter().flat_map(|s| &s.prepared.meshes);
        meshes.map(|m| m.frames.as_ref().map(|f| f.method)).collect()
    }

    /// What the current scene asked for but could not get (a texture downscaled to fit the
    /// adapter, a bump map on a mesh without texture coordinates), one line each; the split
    /// view's right-half upload adds those the main one does not have.
    pub fn notices(&self) -> Vec<String> {
        let split = self.split_scene.iter().flat_map(|s| &s.notices).filter(|n| !self.notices.contains(n));
        self.notices.iter().chain(split).cloned().collect()
    }

    /// The work done so far.
    pub fn counters(&self) -> WorkCounters {
        self.counters
    }

    /// The pipeline variants built so far.
    pub fn built_pipelines(&self) -> Vec<PipelineKey> {
        self.pipelines.built().copied().collect()
    }

    /// The largest width or height a target may have.
    pub fn max_target_size(&self) -> u32 {
        self.device.limits().max_texture_dimension_2d
    }

    /// An error for an empty or oversized target.
    pub fn check_target_size(&self, size: [u32; 2]) -> Result<(), RenderError> {
        let [width, height] = size;
        let limit = self.max_target_size();
        if width == 0 || height == 0 {
            Err(RenderError::EmptyViewport { width, height })
        } else if width > limit || height > limit {
            Err(RenderError::ViewportTooLarge { width, height, limit })
        } else {
            Ok(())
        }
    }

    /// The samples per pixel a frame of `format` is drawn with: 1 for [`Msaa::Off`], else
    /// [`Self::sample_count`].
    pub fn samples(&self, format: wgpu::TextureFormat, msaa: Msaa) -> u32 {
        match msaa {
            Msaa::X4 => self.sample_count(format),
            Msaa::Off => 1,
        }
    }

    /// 4 when the device can render and resolve 4× MSAA in `format`, else 1. Adapter-specific
    /// format features count only when the device enabled them.
    pub fn sample_count(&self, format: wgpu::TextureFormat) -> u32 {
        let device_features = self.device.features();
        let features = if device_features.contains(wgpu::Features::TEXTURE_ADAPTER_SPECIFIC_FORMAT_FEATURES) {
            self.adapter.get_texture_format_features(format)
        } else {
            format.guaranteed_format_features(device_features)
        };
        let resolvable = features.flags.contains(wgpu::TextureFormatFeatureFlags::MULTISAMPLE_RESOLVE);
        if resolvable && features.flags.sample_count_supported(4) { 4 } else { 1 }
    }

    /// Records one frame of the current scene into `encoder`, drawing into `target`: the split
    /// view when `split` is given, else the whole picture. In the split view the columns left of
    /// the divider are drawn with `split.left` and the others with `split.right`, in one pass
    /// with a scissor rectangle per half, the right half from the split scene when one is set
    /// ([`Self::set_split_scene`]); each half holds exactly the pixels a whole picture with its
    /// settings (and scene upload) would. Uniforms are written to the queue now; the frame
    /// appears when `encoder` is submitted.
    pub fn draw(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        target: &RenderTarget,
        params: &FrameParams,
        split: Option<&SplitFrame>,
        options: DrawOptions,
    ) -> Result<(), RenderError> {
        match split {
            None => {
                let whole = Half { shading: params.shading, scissor: None, scene: SceneSlot::Main };
                self.record(encoder, target, params, &[whole], options)
            }
            Some(split) => {
                let [width, height] = target.size;
                let x = split.divider_pixels(width);
                let right_scene = if self.split_scene.is_some() { SceneSlot::Split } else { SceneSlot::Main };
                let halves = [
                    Half { shading: split.left, scissor: Some([0, 0, x, height]), scene: SceneSlot::Main },
                    Half { shading: split.right, scissor: Some([x, 0, width - x, height]), scene: right_scene },
                ];
                self.record(encoder, target, params, &halves, options)
            }
        }
    }

    /// One full-quality frame ([`Self::draw`] with default options).
    pub fn render(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        target: &RenderTarget,
        params: &FrameParams,
    ) -> Result<(), RenderError> {
        self.draw(encoder, target, params, None, DrawOptions::default())
    }

    /// Records the adapter's floor into `encoder`: the clear and one full-screen triangle of
    /// one colour, depth-tested and written, into `target` with the attachments, sample count
    /// and resolve a frame drawn with `msaa` has. No frame of that size can cost less.
    pub fn draw_floor(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        target: &RenderTarget,
        msaa: Msaa,
    ) -> Result<(), RenderError> {
        self.check_target_size(target.size)?;
        let samples = self.samples(target.format, msaa);
        self.floor.ensure(&self.device, target.format, samples, &mut self.counters);
        self.targets.ensure(&self.device, target.size, target.format, samples);
        let mut pass = begin_scene_pass(encoder, self.targets.get(samples), target.view, Background::Opaque);
        pass.set_pipeline(self.floor.get(target.format, samples));
        pass.draw(0..3, 0..1);
        Ok(())
    }

    /// The upload a half is drawn from.
    fn scene_in(&self, slot: SceneSlot) -> Option<&GpuScene> {
        match slot {
            SceneSlot::Main => self.scene.as_deref(),
            SceneSlot::Split => self.split_scene.as_deref(),
        }
    }

    /// Records one frame of at most two halves, each with its shading, scissor rectangle and
    /// scene upload: each drawable plans its passes once ([`HalfPlan`]), their pipelines are
    /// built, then the plans are recorded in one render pass. An empty rectangle draws nothing.
    fn record(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        target: &RenderTarget,
        params: &FrameParams,
        halves: &[Half],
        options: DrawOptions,
    ) -> Result<(), RenderError> {
        assert!(halves.len() <= 2, "one uniform buffer per half, two in all");
        self.check_target_size(target.size)?;
        let samples = self.samples(target.format, options.msaa);
        self.prepare_scenes(halves)?;
        self.write_uniforms(halves, params, target.size)?;
        let shadings: Vec<_> = halves.iter().map(|h| h.shading).collect();
        let layout = &self.pipelines.layouts.frame;
        self.frame_groups.bind_legacy_textures(&self.device, &self.queue, layout, &shadings, &mut self.counters);
        let line_mode = self.supports_wireframe();
        let wants_wireframe = halves.iter().any(|h| h.shading.wireframe);
        draw::wireframe::update_notice(&mut self.notices, wants_wireframe, line_mode);
        let plans = halves
            .iter()
            .map(|half| {
                let scene = self.scene_in(half.scene).ok_or(RenderError::NoScene)?;
                Ok(HalfPlan::new(scene, &half.shading, params, line_mode))
            })
            .collect::<Result<Vec<_>, RenderError>>()?;
        for pass in plans.iter().flat_map(HalfPlan::passes) {
            let key = FramePipelines::key(pass, target.format, samples);
            self.pipelines.ensure(&self.device, key, &mut self.counters);
        }
        self.targets.ensure(&self.device, target.size, target.format, samples);
        self.tessellate(encoder, halves, params, target.size);
        let pipelines = FramePipelines { pool: &self.pipelines, format: target.format, samples };
        let mut pass = begin_scene_pass(encoder, self.targets.get(samples), target.view, options.background);
        for (index, (half, plan)) in halves.iter().zip(&plans).enumerate() {
            if let Some([x, y, width, height]) = half.scissor {
                if width == 0 || height == 0 {
                    continue;
                }
                pass.set_scissor_rect(x, y, width, height);
            }
            let scene = self.scene_in(half.scene).expect("planned above");
            pass.set_bind_group(0, self.frame_groups.bind_group(index), &[]);
            plan.record(&mut pass, &pipelines, scene);
        }
        drop(pass);
        self.counters.frames_drawn += 1;
        Ok(())
    }

    /// Tessellates the GPU-displaced meshes of the halves' scene uploads for this frame's view
    /// into `encoder` (each upload once, and only when the view changed), and keeps the budget's
    /// notice while it lengthens the edges.
    fn tessellate(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        halves: &[Half],
        params: &FrameParams,
        size: [u32; 2],
    ) {
        let view = tessellation::plan::View {
            view_projection: self.view_projection(&params.camera, size),
            eye: params.camera.eye(),
            size,
        };
        let mut slots: Vec<SceneSlot> = halves.iter().map(|h| h.scene).collect();
        slots.dedup();
        let tessellated = |this: &Self, slot: SceneSlot| this.scene_in(slot).is_some_and(|s| s.tessellation.is_some());
        let wanted = slots.iter().any(|&slot| tessellated(self, slot));
        let compute = self.adapter.get_downlevel_capabilities().flags.contains(wgpu::DownlevelFlags::COMPUTE_SHADERS);
        self.notices.retain(|n| n != tessellation::NO_COMPUTE_NOTICE);
        if wanted && !compute {
            self.notices.push(tessellation::NO_COMPUTE_NOTICE.to_owned());
            return;
        }
        if wanted && self.displace_pipelines.is_none() {
            self.displace_pipelines = Some(DisplacePipelines::new(&self.device));
        }
        let mut notice = None;
        for slot in slots {
            let tessellation = self.scene_in(slot).and_then(|s| s.tessellation.as_ref());
            let (Some(tessellation), Some(pipelines)) = (tessellation, &self.displace_pipelines) else { continue };
            tessellation.run(&self.device, &self.queue, encoder, pipelines, view);
            notice = notice.or(tessellation.stats().and_then(|s| s.budget_notice()));
        }
        self.notices.retain(|n| !n.starts_with(tessellation::BUDGET_NOTICE_START));
        self.notices.extend(notice);
    }

    /// Makes what the halves' views need of their scene uploads and the uploads lack: the
    /// reference frames of the Difference view (unless made with the upload,
    /// [`ReferenceFrames::WithUpload`]).
    fn prepare_scenes(&mut self, halves: &[Half]) -> Result<(), RenderError> {
        for half in halves {
            let scene = match half.scene {
                SceneSlot::Main => self.scene.as_ref(),
                SceneSlot::Split => self.split_scene.as_ref(),
            }
            .ok_or(RenderError::NoScene)?;
            if half.shading.view == ViewMode::Difference {
                scene.ensure_reference_frames(&self.device, &mut self.counters);
            }
        }
        Ok(())
    }

    /// Writes each half's frame uniform (its shading over `params`, for a target of `size`
    /// pixels) and the light markers of its scene upload.
    fn write_uniforms(&self, halves: &[Half], params: &FrameParams, size: [u32; 2]) -> Result<(), RenderError> {
        let view_projection = self.view_projection(&params.camera, size);
        let markers = draw::markers::uniforms(params);
        for (index, half) in halves.iter().enumerate() {
            let scene = self.scene_in(half.scene).ok_or(RenderError::NoScene)?;
            let frame = FrameParams { shading: half.shading, ..*params };
            self.frame_groups.write(&self.queue, index, &FrameUniform::new(&frame, view_projection));
            if let Some(marker) = &scene.marker {
                self.queue.write_buffer(&marker.lights, 0, bytemuck::bytes_of(&markers));
            }
        }
        Ok(())
    }
}

/// Which scene upload a half of the frame is drawn from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum SceneSlot {
    Main,
    /// The split view's right-half upload.
    Split,
}

/// One half of a frame (or the whole of it).
struct Half {
    shading: ShadingSettings,
    /// `[x, y, width, height]` in pixels; `None`: the whole target.
    scissor: Option<[u32; 4]>,
    scene: SceneSlot,
}
