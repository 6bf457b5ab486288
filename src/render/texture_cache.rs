//! A scene's textures and samplers on the GPU, each made once, on first use: textures with
//! their mip chains (a file's own BC blocks where the adapter samples them, else RGBA8;
//! LEAN's texture of a normal map, a white stand-in), samplers by wrap mode.

use std::borrow::Cow;

use super::gpu_errors::caught;
use crate::counters::WorkCounters;
use crate::prepare::PreparedScene;
use crate::scene::{SamplerWrap, TextureImage, TextureKind, Wrap};
use crate::texture::compressed::{Block, FileBlocks};

/// How one texture of a scene went to the GPU: what the panel's facts say of it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TextureUpload {
    pub name: String,
    /// Its GPU format as a reader would say it, e.g. `BC5 blocks as stored` or `RGBA8 (sRGB)`.
    pub form: String,
    /// Bytes of every level on the GPU.
    pub bytes: u64,
}

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
    /// The scene's textures as uploaded, in upload order.
    pub uploads: Vec<TextureUpload>,
}

/// One mip level to upload: its size in texels and its bytes, row by row.
type Level<'a> = ([u32; 2], &'a [u8]);

impl<'a> TextureCache<'a> {
    /// A cache for a scene of `count` textures, uploading with `device` and `queue`.
    pub fn new(device: &'a wgpu::Device, queue: &'a wgpu::Queue, count: usize) -> TextureCache<'a> {
        let (views, lean) = (vec![None; count], vec![None; count]);
        TextureCache { device, queue, views, lean, white: None, notices: vec![], uploads: vec![] }
    }

    /// Uploads `image` with its mip chain as RGBA8, with what was uploaded. A texture larger
    /// than the adapter allows starts at the first mip level that fits (a notice says so)
    /// instead of failing.
    fn upload(
        &mut self,
        image: &TextureImage,
        mips: &[TextureImage],
        counters: &mut WorkCounters,
    ) -> (wgpu::TextureView, TextureUpload) {
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
        let texture = self.create(&image.name, format, &levels).unwrap_or_else(|problem| {
            self.notices.push(format!(
                "texture {:?} ({}x{}) could not be uploaded ({problem}): drawn without it",
                image.name, image.width, image.height
            ));
            let neutral = TextureImage::neutral(&image.name, image.kind);
            self.create(&image.name, format, &[([1, 1], &neutral.rgba)]).expect("a 1x1 texture fits any device")
        });
        let form = if format.is_srgb() { "RGBA8 (sRGB)" } else { "RGBA8" };
        let bytes = levels.iter().map(|(_, b)| b.len() as u64).sum();
        counters.textures_uploaded += 1;
        (
            texture.create_view(&Default::default()),
            TextureUpload { name: image.name.clone(), form: form.to_owned(), bytes },
        )
    }

    /// Uploads the first `levels` of a file's own blocks as they are, where the device samples
    /// BC formats and level 0 fits it, with what was uploaded; `None` (draw the decoded chain)
    /// elsewhere, or where the device refused the texture.
    fn upload_blocks(
        &mut self,
        image: &TextureImage,
        chain: &FileBlocks,
        levels: usize,
        counters: &mut WorkCounters,
    ) -> Option<(wgpu::TextureView, TextureUpload)> {
        let limit = self.device.limits().max_texture_dimension_2d;
        let samples = self.device.features().contains(wgpu::Features::TEXTURE_COMPRESSION_BC);
        if !samples || chain.width > limit || chain.height > limit {
            return None;
        }
        let srgb = image.kind == TextureKind::Color;
        let format = match chain.block {
            Block::Bc1 if srgb => wgpu::TextureFormat::Bc1RgbaUnormSrgb,
            Block::Bc1 => wgpu::TextureFormat::Bc1RgbaUnorm,
            Block::Bc2 if srgb => wgpu::TextureFormat::Bc2RgbaUnormSrgb,
            Block::Bc2 => wgpu::TextureFormat::Bc2RgbaUnorm,
            Block::Bc3 if srgb => wgpu::TextureFormat::Bc3RgbaUnormSrgb,
            Block::Bc3 => wgpu::TextureFormat::Bc3RgbaUnorm,
            Block::Bc5 => wgpu::TextureFormat::Bc5RgUnorm,
            Block::Bc7 if srgb => wgpu::TextureFormat::Bc7RgbaUnormSrgb,
            Block::Bc7 => wgpu::TextureFormat::Bc7RgbaUnorm,
            Block::Bc4 => return None,
        };
        let level_list: Vec<Level> = chain.levels[..levels]
            .iter()
            .enumerate()
            .map(|(i, bytes)| (chain.level_size(i), bytes.as_slice()))
            .collect();
        let texture = self.create(&image.name, format, &level_list).ok()?;
        let bytes = level_list.iter().map(|(_, b)| b.len() as u64).sum();
        let form = match chain.transcoded_from {
            Some(_) => chain.blocks_name(),
            None => format!("{} as stored", chain.blocks_name()),
        };
        counters.textures_uploaded += 1;
        Some((texture.create_view(&Default::default()), TextureUpload { name: image.name.clone(), form, bytes }))
    }

    /// A sampled 2D texture of `format` holding `levels` (rows of texels, or of 4×4 blocks for
    /// a block format), level 0 first; the device's out-of-memory or validation error, on one
    /// line, instead of the uncaptured-error panic (caught by error scopes around the creation
    /// and the writes).
    fn create(&self, label: &str, format: wgpu::TextureFormat, levels: &[Level]) -> Result<wgpu::Texture, String> {
        caught(self.device, || self.create_unscoped(label, format, levels))
    }

    /// [`Self::create`] without the error scopes.
    fn create_unscoped(&self, label: &str, format: wgpu::TextureFormat, levels: &[Level]) -> wgpu::Texture {
        let size = |[width, height]: [u32; 2]| wgpu::Extent3d { width, height, depth_or_array_layers: 1 };
        let (block_width, block_height) = format.block_dimensions();
        let block_bytes = format.block_copy_size(None).expect("a colour format");
        // A level's copy covers whole blocks: a 2×2 level of a BC texture is one 4×4 block.
        let blocks = |[width, height]: [u32; 2]| [width.div_ceil(block_width), height.div_ceil(block_height)];
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
            let [columns, rows] = blocks(extent);
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
                    bytes_per_row: Some(block_bytes * columns),
                    rows_per_image: Some(rows),
                },
                size([columns * block_width, rows * block_height]),
            );
        }
        texture
    }

    pub fn get(&mut self, prepared: &PreparedScene, index: usize, counters: &mut WorkCounters) -> wgpu::TextureView {
        if self.views[index].is_none() {
            let image = &prepared.scene.textures[index];
            let blocks = prepared.file_blocks(index);
            let view = blocks.and_then(|(chain, levels)| self.upload_blocks(image, chain, levels, counters));
            let (view, upload) = view.unwrap_or_else(|| {
                let chain = prepared.mip_chain(index).unwrap_or_else(|notice| {
                    self.notices.push(notice);
                    Cow::Owned(prepared.neutral_chain(index))
                });
                self.upload(image, &chain, counters)
            });
            self.uploads.push(upload);
            self.views[index] = Some(view);
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
            let texture = self.create(&label, format, &levels).unwrap_or_else(|problem| {
                self.notices.push(format!("{label} could not be uploaded ({problem}): drawn without them"));
                self.create(&label, format, &[([1, 1], &[0; 8])]).expect("a 1x1 texture fits any device")
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
            self.white = Some(self.upload(&image, std::slice::from_ref(&image), counters).0);
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
