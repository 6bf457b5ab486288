//! Image files → [`TextureImage`]: PNG, JPEG, TGA and BMP; 8 or 16 bits per channel; grey,
//! grey + alpha, RGB or RGBA. Colour and normal maps become RGBA8 (grey replicated to RGB,
//! 16 bits rounded to 8); height maps keep 16 bits through [`encode_height`].

use std::path::Path;

use image::{DynamicImage, ImageFormat};

use crate::error::LoadError;
use crate::scene::{TextureImage, TextureKind, encode_height};

/// The formats this build decodes (the `image` crate features in Cargo.toml).
const FORMATS: [ImageFormat; 4] = [ImageFormat::Png, ImageFormat::Jpeg, ImageFormat::Tga, ImageFormat::Bmp];

/// Reads and decodes the image file at `path` as a texture of `kind`.
pub fn load_texture(path: &Path, kind: TextureKind) -> Result<TextureImage, LoadError> {
    let bytes = super::read_file(path, crate::read::FileKind::Image, "image")?;
    decode_texture(&bytes, path, kind)
}

/// Decodes image file bytes; `path` names the image in errors and becomes the texture name.
/// The format comes from the bytes' signature; only TGA, which has none, is taken from the
/// file extension.
pub fn decode_texture(bytes: &[u8], path: &Path, kind: TextureKind) -> Result<TextureImage, LoadError> {
    let by_extension = ImageFormat::from_path(path).ok().filter(|&f| f == ImageFormat::Tga);
    let format = image::guess_format(bytes).ok().or(by_extension);
    let format = match format {
        Some(f) if FORMATS.contains(&f) => f,
        Some(f) => return Err(LoadError::new(path, format!("{f:?} images are not supported (PNG, JPEG, TGA, BMP)"))),
        None => return Err(LoadError::new(path, "not an image (expected PNG, JPEG, TGA or BMP data)")),
    };
    let image = image::load_from_memory_with_format(bytes, format)
        .map_err(|e| LoadError::new(path, format!("not a readable {format:?} image: {e}")))?;
    if image.width() == 0 || image.height() == 0 {
        return Err(LoadError::new(path, "the image is empty (0 pixels)"));
    }
    Ok(to_texture(&image, path.to_string_lossy().into_owned(), kind))
}

/// Converts a decoded image to the texture layout of `kind`.
pub fn to_texture(image: &DynamicImage, name: String, kind: TextureKind) -> TextureImage {
    let rgba = match kind {
        TextureKind::Color | TextureKind::NormalMap | TextureKind::Data => image.to_rgba8().into_raw(),
        // Height = luminance at 16 bits (white = high).
        TextureKind::Height => image
            .to_luma16()
            .pixels()
            .flat_map(|p| {
                let [high, low] = encode_height(p.0[0] as f32 / 65535.0);
                [high, low, 0, 255]
            })
            .collect(),
    };
    TextureImage { name, width: image.width(), height: image.height(), kind, rgba }
}
