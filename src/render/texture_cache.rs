//! A scene's textures and samplers on the GPU, each made once, on first use: textures with
//! their mip chains (LEAN's texture of a normal map, a white stand-in), samplers by wrap mode.

use std::borrow::Cow;

use super::gpu_errors::caught;
use crate::counters::WorkCounters;
use crate::prepare::PreparedScene;
use crate::scene::{SamplerWrap, TextureImage, TextureKind, Wrap};

/// Uploads textures on first use, each once.
pub(super) struct TextureCache<'a> {
    pub device: &'a wgpu::Device,
    queue: &'a wgpu::Queue,
    views: Vec<Option<wgpu::TextureView>>,
    /// LEAN's textures, by the normal map's index, uploaded on first use.
    lean: Vec<Option<wgpu::TextureView>>,
    white: Option<wgpu::TextureView>,
    /// What could not be uploaded as given (textures larger than the adapter allows).
    pub notices: Vec<String>,
}

/// One mip level to upload: its size in texels and its bytes, row by row.
type Level<'a> = ([u32; 2], &'a [u8]);

impl<'a> TextureCache<'a> {
    /// A cache for a scene of `count` textures, uploading with `device` and `queue`.
    pub fn new(device: &'a wgpu::Device, queue: &'a wgpu::Queue, count: usize) -> TextureCache<'a> {
        TextureCache { device, queue, views: vec![None; count], lean: vec![None; count], white: None, notices: vec![] }
    }

    /// Uploads `image` with its mip chain. A texture larger than the adapter allows starts at
    /// the first mip level that fits (a notice says so) instead of failing.
    fn upload(
        &mut self,
        image: &TextureImage,
        mips: &[TextureImage],
        counters: &mut WorkCounters,
    ) -> wgpu::TextureView {
        let format = match image.kind {
            TextureKind::Color => wgpu::TextureFormat::Rgba8UnormSrgb,
            TextureKind::NormalMap | TextureKind::Height | TextureKind::Data => wgpu::TextureFormat::Rgba8Unorm,
        };
        let limit = self.device.limits().max_texture_dimension_2d;
        let fits = mips.iter().position(|m| m.width <= limit && m.height <= limit).unwrap_or(mips.len() - 1);
        if fits > 0 {
            let (w, h) = (mips[fits].width, mips[fits].height);
            self.notices.push(format!(
                "texture {:?} is {}x{}, more than the adapter's {limit} per side: downscaled to {w}x{h}",
                image.name, image.width, image.height
            ));
        }
        let levels: Vec<Level> = mips[fits..].iter().map(|m| ([m.width, m.height], m.rgba.as_slice())).collect();
        let texture = self.create(&image.name, format, 4, &levels).unwrap_or_else(|problem| {
            self.notices.push(format!(
                "texture {:?} ({}x{}) could not be uploaded ({problem}): drawn without it",
                image.name, image.width, image.height
            ));
            let neutral = TextureImage::neutral(&image.name, image.kind);
            self.create(&image.name, format, 4, &[([1, 1], &neutral.rgba)]).expect("a 1x1 texture fits any device")
        });
        counters.textures_uploaded += 1;
        texture.create_view(&Default::default())
    }

    /// A sampled 2D texture of `format` (`texel_bytes` a texel) holding `levels`, level 0
    /// first; the device's out-of-memory or validation error, on one line, instead of the
    /// uncaptured-error panic (caught by error scopes around the creation and the writes).
    fn create(
        &self,
        label: &str,
        format: wgpu::TextureFormat,
        texel_bytes: u32,
        levels: &[Level],
    ) -> Result<wgpu::Texture, String> {
        caught(self.device, || self.create_unscoped(label, format, texel_bytes, levels))
    }

    /// [`Self::create`] without the error scopes.
    fn create_unscoped(
        &self,
        label: &str,
        format: wgpu::TextureFormat,
        texel_bytes: u32,
        levels: &[Level],
    ) -> wgpu::Texture {
        let size = |[width, height]: [u32; 2]| wgpu::Extent3d { width, height, depth_or_array_layers: 1 };
        let texture = self.device.create_texture(&wgpu::TextureDescriptor {
            label: Some(label),
            size: size(levels[0].0),
            mip_level_count: levels.len() as u32,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        });
        for (level, &(extent, bytes)) in levels.iter().enumerate() {
            self.queue.write_texture(
                wgpu::TexelCopyTextureInfo {
                    texture: &texture,
                    mip_level: level as u32,
                    origin: wgpu::Origin3d::ZERO,
                    aspect: wgpu::TextureAspect::All,
                },
                bytes,
                wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(texel_bytes * extent[0]),
                    rows_per_image: Some(extent[1]),
                },
                size(extent),
            );
        }
        texture
    }

    pub fn get(&mut self, prepared: &PreparedScene, index: usize, counters: &mut WorkCounters) -> wgpu::TextureView {
        if self.views[index].is_none() {
            let image = &prepared.scene.textures[index];
            let chain = prepared.mip_chain(index).unwrap_or_else(|notice| {
                self.notices.push(notice);
                Cow::Owned(prepared.neutral_chain(index))
            });
            self.views[index] = Some(self.upload(image, &chain, counters));
        }
        self.views[index].clone().expect("uploaded above")
    }

    /// LEAN's texture of normal map `index` ([`PreparedScene::lean_texture`]: `Rgba16Float`,
    /// 8 bytes a texel, with the full mip chain; from the first level that fits the adapter,
    /// as [`Self::upload`] does); `None` where no instance draws it with LEAN.
    pub fn lean(
        &mut self,
        prepared: &PreparedScene,
        index: usize,
        counters: &mut WorkCounters,
    ) -> Option<wgpu::TextureView> {
        if self.lean[index].is_none() {
            let levels = prepared.lean_texture(index)?;
            let limit = self.device.limits().max_texture_dimension_2d;
            let fits = levels.iter().position(|m| m.width <= limit && m.height <= limit).unwrap_or(levels.len() - 1);
            let levels: Vec<Level> = levels[fits..].iter().map(|m| ([m.width, m.height], m.bytes())).collect();
            let label = format!("LEAN moments of {}", prepared.scene.textures[index].name);
            let format = wgpu::TextureFormat::Rgba16Float;
            let texture = self.create(&label, format, 8, &levels).unwrap_or_else(|problem| {
                self.notices.push(format!("{label} could not be uploaded ({problem}): drawn without them"));
                self.create(&label, format, 8, &[([1, 1], &[0; 8])]).expect("a 1x1 texture fits any device")
            });
            counters.textures_uploaded += 1;
            self.lean[index] = Some(texture.create_view(&Default::default()));
        }
        self.lean[index].clone()
    }

    /// A 1×1 white colour texture for materials without a base colour texture.
    pub fn white(&mut self, counters: &mut WorkCounters) -> wgpu::TextureView {
        if self.white.is_none() {
            let image = TextureImage::neutral("white", TextureKind::Color);
            self.white = Some(self.upload(&image, std::slice::from_ref(&image), counters));
        }
        self.white.clone().expect("uploaded above")
    }
}

/// Samplers by wrap mode, made on first use (linear filtering, trilinear mips).
#[derive(Default)]
pub(super) struct SamplerCache {
    made: Vec<(SamplerWrap, wgpu::Sampler)>,
}

impl SamplerCache {
    pub fn get(&mut self, device: &wgpu::Device, wrap: SamplerWrap) -> wgpu::Sampler {
        if let Some((_, sampler)) = self.made.iter().find(|(w, _)| *w == wrap) {
            return sampler.clone();
        }
        let mode = |w| match w {
            Wrap::Repeat => wgpu::AddressMode::Repeat,
            Wrap::ClampToEdge => wgpu::AddressMode::ClampToEdge,
            Wrap::MirroredRepeat => wgpu::AddressMode::MirrorRepeat,
        };
        let sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("material"),
            address_mode_u: mode(wrap.u),
            address_mode_v: mode(wrap.v),
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            mipmap_filter: wgpu::MipmapFilterMode::Linear,
            ..Default::default()
        });
        self.made.push((wrap, sampler.clone()));
        sampler
    }
}
