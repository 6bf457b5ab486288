//! Image files → [`TextureImage`]: PNG, JPEG, TGA, BMP and WebP (8 or 16 bits per channel;
//! grey, grey + alpha, RGB or RGBA), and DDS and KTX2 decoded to RGBA8
//! ([`crate::texture::compressed`], with what their format says about the channels). Colour
//! and normal maps become RGBA8 (grey replicated to RGB, 16 bits rounded to 8); height maps
//! keep 16 bits through [`encode_height`].
//!
//! Sizes are checked from the header before any pixel is decoded: a side of at most
//! [`MAX_SIDE`], at most [`MAX_TEXELS`] texels per texture, and, for the textures of one
//! scene ([`load_scene_texture`]), at most [`MAX_SCENE_TEXELS`] in all and [`MAX_TEXTURES`]
//! textures. A height map counts twice (its normal map is made beside it).

use std::path::Path;

use image::{DynamicImage, ImageFormat};

use crate::error::LoadError;
use crate::scene::{Scene, TextureImage, TextureKind, encode_height};
use crate::texture::compressed::{GpuTexels, Stored};
use crate::texture::decode::{MAX_DECODE_BYTES, decode_image};

/// The largest side of a texture, texels: the largest 2D texture most GPUs take (wgpu's
/// `max_texture_dimension_2d` on desktop Vulkan) and the bake's largest input.
pub const MAX_SIDE: u32 = 16384;

/// The most texels one texture may have: 2²⁶ (8192², 256 MiB as RGBA8), so that drawing or
/// checking it stays within the memory stated in docs/inputs.md.
pub const MAX_TEXELS: u64 = 1 << 26;

/// The most texels the textures of one scene may have together: 2²⁷ (two 8192² maps).
pub const MAX_SCENE_TEXELS: u64 = 1 << 27;

/// The most textures one scene may have.
pub const MAX_TEXTURES: usize = 4096;

/// Reads and decodes the image file at `path` as a texture of `kind`, within [`MAX_TEXELS`].
pub fn load_texture(path: &Path, kind: TextureKind) -> Result<TextureImage, LoadError> {
    let bytes = super::read_file(path, crate::read::FileKind::Image, "image")?;
    decode_texture_within(&bytes, path, kind, MAX_TEXELS)
}

/// [`load_texture`] for a texture that joins `scene`: within what the scene's textures leave
/// of [`MAX_SCENE_TEXELS`] and [`MAX_TEXTURES`].
pub fn load_scene_texture(scene: &Scene, path: &Path, kind: TextureKind) -> Result<TextureImage, LoadError> {
    load_scene_texture_stored(scene, path, kind).map(|(texture, _)| texture)
}

/// [`load_scene_texture`] with what a DDS or KTX2 file's format says about its channels.
pub fn load_scene_texture_stored(
    scene: &Scene,
    path: &Path,
    kind: TextureKind,
) -> Result<(TextureImage, Option<Stored>), LoadError> {
    let room = texel_room(scene).map_err(|problem| LoadError::new(path, problem))?;
    let bytes = super::read_file(path, crate::read::FileKind::Image, "image")?;
    decode_texture_stored(&bytes, path, kind, room)
}

/// The texels a further texture of `scene` may have (at most [`MAX_TEXELS`]), or why there is
/// no room for one.
pub fn texel_room(scene: &Scene) -> Result<u64, String> {
    if scene.textures.len() >= MAX_TEXTURES {
        return Err(format!("the scene has {MAX_TEXTURES} textures already, the most it may have"));
    }
    let used: u64 = scene.textures.iter().map(|t| t.width as u64 * t.height as u64).sum();
    Ok(MAX_SCENE_TEXELS.saturating_sub(used).min(MAX_TEXELS))
}

/// Decodes image file bytes within [`MAX_TEXELS`]; `path` names the image in errors and
/// becomes the texture name. The format comes from the bytes' signature; only TGA, which has
/// none, is taken from the file extension.
pub fn decode_texture(bytes: &[u8], path: &Path, kind: TextureKind) -> Result<TextureImage, LoadError> {
    decode_texture_within(bytes, path, kind, MAX_TEXELS)
}

/// [`decode_texture`] refusing, from the header, more than `room` texels (twice for a height
/// map, whose normal map is made beside it) or a side over [`MAX_SIDE`].
pub fn decode_texture_within(
    bytes: &[u8],
    path: &Path,
    kind: TextureKind,
    room: u64,
) -> Result<TextureImage, LoadError> {
    decode_texture_stored(bytes, path, kind, room).map(|(texture, _)| texture)
}

/// [`decode_texture_within`] with what a DDS or KTX2 file's format says about its channels.
pub fn decode_texture_stored(
    bytes: &[u8],
    path: &Path,
    kind: TextureKind,
    room: u64,
) -> Result<(TextureImage, Option<Stored>), LoadError> {
    let tga_by_name = ImageFormat::from_path(path).ok() == Some(ImageFormat::Tga);
    let admit = |header: &crate::texture::decode::Header| {
        let (width, height) = (header.width, header.height);
        if width == 0 || height == 0 {
            return Err("the image is empty (0 pixels)".to_owned());
        }
        if width > MAX_SIDE || height > MAX_SIDE {
            return Err(format!("{width}x{height} texels is over the limit of {MAX_SIDE} per side"));
        }
        let texels = header.texels() * if kind == TextureKind::Height { 2 } else { 1 };
        if texels > room {
            let counted = if kind == TextureKind::Height {
                format!("{} Mi counted, as a height map counts twice for its normal map; ", texels >> 20)
            } else {
                String::new()
            };
            return Err(format!(
                "{width}x{height} texels is over the {} Mi texels a texture may have here ({counted}at most {} Mi per texture, {} Mi per scene)",
                room >> 20,
                MAX_TEXELS >> 20,
                MAX_SCENE_TEXELS >> 20
            ));
        }
        Ok(())
    };
    let (image, stored) =
        decode_image(bytes, tga_by_name, MAX_DECODE_BYTES, admit).map_err(|problem| LoadError::new(path, problem))?;
    let mut texture = to_texture(image, path.to_string_lossy().into_owned(), kind)
        .ok_or_else(|| LoadError::new(path, "no memory for the decoded texture"))?;
    // A height map's texels are re-encoded (16 bits in red and green): its blocks no longer apply.
    if let Some(GpuTexels::Blocks(chain)) = stored.as_ref().map(|s| &s.gpu).filter(|_| kind != TextureKind::Height) {
        texture.file_blocks = Some(chain.clone());
    }
    Ok((texture, stored))
}

/// Converts a decoded image to the texture layout of `kind` (`None`: the system refused the
/// memory for a height map's texels). An RGBA8 image is taken as it is, without a copy.
pub fn to_texture(image: DynamicImage, name: String, kind: TextureKind) -> Option<TextureImage> {
    let (width, height) = (image.width(), image.height());
    let rgba = match kind {
        TextureKind::Color | TextureKind::NormalMap | TextureKind::Data => image.into_rgba8().into_raw(),
        // Height = luminance at 16 bits (white = high).
        TextureKind::Height => {
            let grey = image.into_luma16();
            let mut rgba = super::budget::try_vec(width as usize * height as usize * 4)?;
            rgba.extend(grey.pixels().flat_map(|p| {
                let [high, low] = encode_height(p.0[0] as f32 / 65535.0);
                [high, low, 0, 255]
            }));
            rgba
        }
    };
    Some(TextureImage::new(name, width, height, kind, rgba))
}
