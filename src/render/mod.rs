//! The wgpu renderer. It draws into any texture view it is given, so the window, screenshots
//! and tests share one code path: [`Renderer::draw`]. Depth-tested, with 4× MSAA where the
//! adapter supports it for the target format ([`Msaa::X4`]) or 1 sample ([`Msaa::Off`], the
//! interactive frames). [`Renderer::draw_floor`] draws the adapter's floor, what any frame of
//! that size and MSAA costs at least; [`timing`] measures frames against it.

mod bindings;
pub mod capture;
pub mod export;
mod floor;
pub mod glyphs;
pub mod gpu;
mod legacy;
pub mod pipelines;
mod scene_gpu;
pub mod timing;
mod uniforms;

use std::sync::Arc;

use bytemuck::Zeroable;
use glam::Vec3;

use crate::counters::WorkCounters;
use crate::error::RenderError;
use crate::frame::{
    FrameParams, LegacySettings, LightingSpace, Msaa, Parallax, SceneOptions, SceneUploads, ShadingSettings,
    SplitFrame, ViewMode,
};
use crate::prepare::{PreparedScene, Variant};
use crate::scene::{MAX_LIGHTS, Scene, ShadingModel};
use crate::tangent::TangentMethod;
pub use gpu::Gpu;
use pipelines::{DEPTH_FORMAT, Pass, PipelineKey, Pipelines};
use scene_gpu::{GpuScene, MarkerUniform};
use uniforms::FrameUniform;

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

/// Multisampled colour and depth attachments for one target size, format and sample count.
struct FrameTargets {
    size: [u32; 2],
    format: wgpu::TextureFormat,
    samples: u32,
    msaa_color: Option<wgpu::TextureView>,
    depth: wgpu::TextureView,
}

pub struct Renderer {
    device: wgpu::Device,
    queue: wgpu::Queue,
    adapter: wgpu::Adapter,
    pipelines: Pipelines,
    frame_uniform: wgpu::Buffer,
    frame_bind_group: wgpu::BindGroup,
    /// The right half's frame uniform in split view (the left half uses `frame_uniform`):
    /// both are written before the encoder is submitted, so each half needs its own.
    split_uniform: wgpu::Buffer,
    split_bind_group: wgpu::BindGroup,
    /// The legacy looks' textures, and what the two frame bind groups hold of them.
    legacy: legacy::LegacyTextures,
    bound: [legacy::LegacyNeeds; 2],
    /// The floor's pipelines ([`Self::draw_floor`]), by format and sample count.
    floor: floor::FloorPipelines,
    scene: Option<GpuScene>,
    /// The split view's right half, when it differs from the left in GPU data
    /// ([`Self::set_split_scene`]); else the right half is drawn from `scene` too.
    split_scene: Option<GpuScene>,
    /// The attachments of the last frame drawn with each sample count, so frames that switch
    /// between 1 and 4 samples (interactive and full quality) keep both.
    targets: Vec<FrameTargets>,
    counters: WorkCounters,
    /// The scene's notices, plus one while the wireframe is asked for but unsupported.
    notices: Vec<String>,
}

/// The notice shown while the wireframe overlay is on but the device cannot draw lines.
pub const WIREFRAME_UNSUPPORTED: &str =
    "wireframe overlay (W) needs wgpu::Features::POLYGON_MODE_LINE, which this device does not have";

impl Renderer {
    pub fn new(device: wgpu::Device, queue: wgpu::Queue, adapter: wgpu::Adapter) -> Self {
        let pipelines = Pipelines::new(&device);
        let legacy = legacy::LegacyTextures::new(&device, &queue);
        let uniform = |label| {
            let buffer = device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: std::mem::size_of::<FrameUniform>() as u64,
                usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                mapped_at_creation: false,
            });
            let bind_group = legacy.bind_group(&device, &pipelines.layouts.frame, &buffer, Default::default());
            (buffer, bind_group)
        };
        let (frame_uniform, frame_bind_group) = uniform("frame");
        let (split_uniform, split_bind_group) = uniform("frame (split, right half)");
        Renderer {
            floor: floor::FloorPipelines::new(&device),
            device,
            queue,
            adapter,
            pipelines,
            frame_uniform,
            frame_bind_group,
            split_uniform,
            split_bind_group,
            legacy,
            bound: Default::default(),
            scene: None,
            split_scene: None,
            targets: Vec::new(),
            counters: WorkCounters::default(),
            notices: Vec::new(),
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

    /// Replaces the scene with `scene` prepared with `options` ([`PreparedScene::new`]) and
    /// uploads what it uses. A split scene ([`Self::set_split_scene`]) is kept: replace or
    /// drop it too when the scene changes.
    pub fn set_scene(&mut self, scene: &Scene, options: SceneOptions) {
        self.set_prepared(Arc::new(PreparedScene::new(scene, &options)));
    }

    /// Replaces the scene with one prepared already (e.g. off the UI thread).
    pub fn set_prepared(&mut self, prepared: Arc<PreparedScene>) {
        let gpu = self.upload(prepared);
        self.notices = gpu.notices.clone();
        self.scene = Some(gpu);
    }

    /// Gives the split view's right half its own upload of `scene` made with `options` (two
    /// tangent methods, two conventions, two bump sources), or with `None` drops it, so the
    /// right half is drawn from the main scene again. Its notices are added to the main ones.
    pub fn set_split_scene(&mut self, scene: &Scene, options: Option<SceneOptions>) {
        self.set_split_prepared(options.map(|options| Arc::new(PreparedScene::new(scene, &options))));
    }

    /// [`Self::set_split_scene`] with a scene prepared already.
    pub fn set_split_prepared(&mut self, prepared: Option<Arc<PreparedScene>>) {
        self.split_scene = prepared.map(|prepared| self.upload(prepared));
    }

    /// [`Self::set_scene`] and [`Self::set_split_scene`] for what a viewer state asks.
    pub fn set_scene_uploads(&mut self, scene: &Scene, uploads: &SceneUploads) {
        self.set_scene(scene, uploads.main.clone());
        self.set_split_scene(scene, uploads.split_right.clone());
    }

    /// The scene options of the uploads the renderer holds, as [`Self::set_scene_uploads`] takes
    /// them (`None` before the first scene), to compare with what a viewer state asks.
    pub fn uploads(&self) -> Option<SceneUploads> {
        let options = |scene: &GpuScene| scene.prepared.options.clone();
        let main = options(self.scene.as_ref()?);
        Some(SceneUploads { main, split_right: self.split_scene.as_ref().map(options) })
    }

    /// The prepared scene the main picture (`split_half` false) or the split view's right
    /// half (true; the main one when the right half has no upload of its own) is drawn from:
    /// what the probe of that picture wraps.
    pub fn prepared(&self, split_half: bool) -> Option<&Arc<PreparedScene>> {
        let split = self.split_scene.as_ref().filter(|_| split_half);
        split.or(self.scene.as_ref()).map(|s| &s.prepared)
    }

    fn upload(&mut self, prepared: Arc<PreparedScene>) -> GpuScene {
        let layouts = &self.pipelines.layouts;
        scene_gpu::upload(&self.device, &self.queue, layouts, prepared, &mut self.counters)
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

    /// The attachments for `samples` at `size` and `format`, made unless the last frame with
    /// that sample count had them.
    fn ensure_targets(&mut self, size: [u32; 2], format: wgpu::TextureFormat, samples: u32) -> &FrameTargets {
        let index = self.targets.iter().position(|t| t.samples == samples);
        if let Some(i) = index.filter(|&i| self.targets[i].size == size && self.targets[i].format == format) {
            return &self.targets[i];
        }
        self.targets.retain(|t| t.samples != samples);
        let texture = |label: &str, format| {
            self.device
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
        self.targets.last().expect("pushed above")
    }

    /// Records one frame of the current scene into `encoder`, drawing into `target`: the split
    /// view when `split` is given ([`Self::render_split`]), else the whole picture. Uniforms
    /// are written to the queue now; the frame appears when `encoder` is submitted.
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

    /// [`Self::render`] over the given background.
    pub fn render_with_background(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        target: &RenderTarget,
        params: &FrameParams,
        background: Background,
    ) -> Result<(), RenderError> {
        self.draw(encoder, target, params, None, DrawOptions { background, ..Default::default() })
    }

    /// The split view: one frame of the same camera and light whose columns left of the
    /// divider are drawn with `split.left` and the others with `split.right`, in one pass with
    /// a scissor rectangle per half. The right half is drawn from the split scene when one is
    /// set ([`Self::set_split_scene`]). Each half holds exactly the pixels a full
    /// [`Self::render`] with its settings (and scene upload) would. Full quality.
    pub fn render_split(
        &mut self,
        encoder: &mut wgpu::CommandEncoder,
        target: &RenderTarget,
        params: &FrameParams,
        split: &SplitFrame,
        background: Background,
    ) -> Result<(), RenderError> {
        self.draw(encoder, target, params, Some(split), DrawOptions { background, ..Default::default() })
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
        let targets = self.ensure_targets(target.size, target.format, samples);
        let mut pass = begin_scene_pass(encoder, targets, target.view, Background::Opaque);
        pass.set_pipeline(self.floor.get(target.format, samples));
        pass.draw(0..3, 0..1);
        Ok(())
    }

    /// The upload a half is drawn from.
    fn scene_in(&self, slot: SceneSlot) -> Option<&GpuScene> {
        match slot {
            SceneSlot::Main => self.scene.as_ref(),
            SceneSlot::Split => self.split_scene.as_ref(),
        }
    }

    /// Records one frame of at most two halves, each with its shading, scissor rectangle and
    /// scene upload. An empty rectangle draws nothing.
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
        // Here and for the pipelines below the scene is borrowed field by field ([`Self::scene_in`]
        // would borrow all of `self`), as the counters and the pipeline cache change meanwhile.
        for half in halves {
            let scene = match half.scene {
                SceneSlot::Main => self.scene.as_mut(),
                SceneSlot::Split => self.split_scene.as_mut(),
            }
            .ok_or(RenderError::NoScene)?;
            if half.shading.view == ViewMode::Difference {
                scene.ensure_reference_frames(&self.device, &mut self.counters);
            }
            if half.shading.tbn_glyphs {
                scene.ensure_glyphs(&self.device);
            }
        }
        let aspect = target.size[0] as f32 / target.size[1] as f32;
        let mut markers = [MarkerUniform::zeroed(); MAX_LIGHTS];
        for (i, (marker, light)) in markers.iter_mut().zip(params.lights.as_slice()).enumerate() {
            let centre = params.marker_position(i);
            *marker = MarkerUniform {
                centre: centre.extend(1.0).to_array(),
                color: light.color.clamp(Vec3::ZERO, Vec3::ONE).extend(1.0).to_array(),
            };
        }
        for (half, buffer) in halves.iter().zip([&self.frame_uniform, &self.split_uniform]) {
            let scene = self.scene_in(half.scene).ok_or(RenderError::NoScene)?;
            let frame = FrameParams { shading: half.shading, ..*params };
            self.queue.write_buffer(buffer, 0, bytemuck::bytes_of(&FrameUniform::new(&frame, aspect)));
            self.queue.write_buffer(&scene.marker.lights, 0, bytemuck::bytes_of(&markers));
        }

        self.bind_legacy_textures(halves);

        let key = |pass| PipelineKey { pass, format: target.format, samples };
        let line_mode = self.device.features().contains(wgpu::Features::POLYGON_MODE_LINE);
        let wants_wireframe = halves.iter().any(|h| h.shading.wireframe);
        let unsupported_notice = self.notices.iter().position(|n| n == WIREFRAME_UNSUPPORTED);
        match (wants_wireframe && !line_mode, unsupported_notice) {
            (true, None) => self.notices.push(WIREFRAME_UNSUPPORTED.to_owned()),
            (false, Some(index)) => {
                self.notices.remove(index);
            }
            _ => {}
        }
        for half in halves {
            let scene = match half.scene {
                SceneSlot::Main => self.scene.as_ref(),
                SceneSlot::Split => self.split_scene.as_ref(),
            }
            .ok_or(RenderError::NoScene)?;
            let shading = &half.shading;
            let marker = shading.show_light_marker.then_some(Pass::LightMarker);
            let wireframe = shading.wireframe && line_mode;
            let wireframe_passes = scene.instances.iter().filter(|_| wireframe).map(wireframe_pass);
            let glyph_passes =
                scene.instances.iter().filter(|i| shading.tbn_glyphs && has_glyphs(i, scene)).map(glyph_pass);
            let drawn = scene.instances.iter().map(|i| drawn_pass(i, scene, shading));
            for pass in drawn.chain(marker).chain(wireframe_passes).chain(glyph_passes) {
                self.pipelines.ensure(&self.device, key(pass), &mut self.counters);
            }
        }
        self.ensure_targets(target.size, target.format, samples);
        let targets = self.targets.iter().find(|t| t.samples == samples).expect("made above");
        let mut pass = begin_scene_pass(encoder, targets, target.view, options.background);
        for (half, bind_group) in halves.iter().zip([&self.frame_bind_group, &self.split_bind_group]) {
            if let Some([x, y, width, height]) = half.scissor {
                if width == 0 || height == 0 {
                    continue;
                }
                pass.set_scissor_rect(x, y, width, height);
            }
            let scene = self.scene_in(half.scene).expect("checked above");
            let shading = &half.shading;
            pass.set_bind_group(0, bind_group, &[]);
            for instance in &scene.instances {
                let instance_pass = drawn_pass(instance, scene, shading);
                let mesh = &scene.meshes[instance.mesh];
                pass.set_pipeline(self.pipelines.get(&key(instance_pass)));
                pass.set_bind_group(1, &instance.bind_group, &[]);
                pass.set_vertex_buffer(0, mesh.positions.slice(..));
                pass.set_vertex_buffer(1, mesh.normals.slice(..));
                pass.set_vertex_buffer(2, mesh.uvs.slice(..));
                if let Some(tangents) = &mesh.tangents {
                    pass.set_vertex_buffer(3, tangents.slice(..));
                }
                if let (Pass::Difference { .. }, Some(reference)) = (instance_pass, &mesh.reference_tangents) {
                    pass.set_vertex_buffer(4, reference.slice(..));
                }
                pass.set_index_buffer(mesh.indices.slice(..), wgpu::IndexFormat::Uint32);
                pass.draw_indexed(0..mesh.index_count, 0, 0..1);
            }
            if shading.wireframe && line_mode {
                for instance in &scene.instances {
                    let mesh = &scene.meshes[instance.mesh];
                    pass.set_pipeline(self.pipelines.get(&key(wireframe_pass(instance))));
                    pass.set_bind_group(1, &instance.bind_group, &[]);
                    pass.set_vertex_buffer(0, mesh.positions.slice(..));
                    pass.set_index_buffer(mesh.indices.slice(..), wgpu::IndexFormat::Uint32);
                    pass.draw_indexed(0..mesh.index_count, 0, 0..1);
                }
            }
            if shading.tbn_glyphs {
                for instance in scene.instances.iter().filter(|i| has_glyphs(i, scene)) {
                    let Some((lines, count)) = &scene.meshes[instance.mesh].glyphs else { continue };
                    pass.set_pipeline(self.pipelines.get(&key(glyph_pass(instance))));
                    pass.set_bind_group(1, &instance.bind_group, &[]);
                    pass.set_vertex_buffer(0, lines.slice(..));
                    pass.draw(0..*count, 0..1);
                }
            }
            if shading.show_light_marker {
                let marker = &scene.marker;
                pass.set_pipeline(self.pipelines.get(&key(Pass::LightMarker)));
                pass.set_bind_group(1, &marker.bind_group, &[]);
                pass.set_vertex_buffer(0, marker.positions.slice(..));
                pass.set_index_buffer(marker.indices.slice(..), wgpu::IndexFormat::Uint32);
                for (i, _) in params.lights.as_slice().iter().enumerate().filter(|(_, light)| light.enabled) {
                    pass.draw_indexed(0..marker.index_count, 0, i as u32..i as u32 + 1);
                }
            }
        }
        drop(pass);
        self.counters.frames_drawn += 1;
        Ok(())
    }
}

impl Renderer {
    /// Makes the legacy looks' textures the halves use (dropping the others) and rebinds a
    /// frame bind group whose textures change.
    fn bind_legacy_textures(&mut self, halves: &[Half]) {
        let needs: Vec<_> = halves.iter().map(|h| legacy::LegacyNeeds::of(&h.shading)).collect();
        if needs.iter().zip(&self.bound).all(|(a, b)| a == b) {
            return;
        }
        self.legacy.retain(&self.device, &self.queue, &needs, &mut self.counters);
        let layout = &self.pipelines.layouts.frame;
        for (index, wanted) in needs.into_iter().enumerate() {
            let (uniform, bind_group) = match index {
                0 => (&self.frame_uniform, &mut self.frame_bind_group),
                _ => (&self.split_uniform, &mut self.split_bind_group),
            };
            if self.bound[index] != wanted {
                *bind_group = self.legacy.bind_group(&self.device, layout, uniform, wanted);
                self.bound[index] = wanted;
            }
        }
    }
}

/// Begins the one render pass of a frame (or of the floor): `targets`' multisampled colour
/// resolved into `view` (or `view` itself at 1 sample) and their depth, both cleared.
fn begin_scene_pass<'e>(
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

/// The wireframe of an instance binds its variant's group-1 layout.
fn wireframe_pass(instance: &scene_gpu::GpuInstance) -> Pass {
    Pass::Wireframe { variant: instance.variant }
}

/// The glyphs of an instance bind its variant's group-1 layout.
fn glyph_pass(instance: &scene_gpu::GpuInstance) -> Pass {
    Pass::Glyphs { variant: instance.variant }
}

/// Whether an instance's mesh has glyph lines to draw (made for meshes with tangent frames).
fn has_glyphs(instance: &scene_gpu::GpuInstance, scene: &GpuScene) -> bool {
    scene.meshes[instance.mesh].glyphs.as_ref().is_some_and(|(_, count)| *count > 0)
}

/// The pass an instance is drawn with in `shading`'s view: the Difference view has its own
/// pass for meshes that have tangent frames; else the mesh pass specialised to the view, in a
/// lit view to the shading model (the frame's override, else the material's), where a
/// height map is bound for it, to the parallax technique, and to the material's features.
fn drawn_pass(instance: &scene_gpu::GpuInstance, scene: &GpuScene, shading: &ShadingSettings) -> Pass {
    let scene_gpu::GpuInstance { variant, cull_back_faces, mirrored, features, .. } = *instance;
    if shading.view == ViewMode::Difference && scene.prepared.meshes[instance.mesh].frames.is_some() {
        return Pass::Difference { variant, cull_back_faces, mirrored };
    }
    let lighting = shading.view.is_lit().then(|| shading.shading_override.unwrap_or(instance.shading_model));
    let parallax = if instance.parallax_height { shading.parallax.technique } else { Parallax::Off };
    let legacy = if shading.view.is_lit() { shading.legacy } else { LegacySettings::default() };
    let (view, mistake) = (shading.view, shading.mistake);
    // As chain::shade decides: the classic model on tangent-space normal-mapped surfaces.
    let lighting_space = match (variant, lighting) {
        (Variant::NormalMapped, Some(ShadingModel::BlinnPhong)) => shading.lighting_space,
        _ => LightingSpace::World,
    };
    Pass::Mesh {
        variant,
        cull_back_faces,
        mirrored,
        view,
        lighting,
        parallax,
        mistake,
        legacy,
        lighting_space,
        features,
    }
}
