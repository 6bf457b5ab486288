//! Decoding image files with their size known first: the header is read, the caller admits its
//! size (each consumer has its own limits), and only then are pixels allocated, with the
//! decoder's own allocations capped by the caller (textures: [`MAX_DECODE_BYTES`]). A JPEG whose entropy-coded data
//! ends before its end-of-image marker is refused rather than decoded as a grey remainder.
//!
//! [`decode_image`] is the one entry point of the loader, the command line's texture flags,
//! dropped files and the bake: PNG, JPEG, TGA, BMP and WebP through `image`, DDS and KTX2
//! through [`super::compressed`].

use std::io::Cursor;

use image::{ColorType, DynamicImage, ImageDecoder, ImageFormat, ImageReader, Limits, RgbaImage};

use super::compressed::{Container, Stored, decode_container};

/// The formats `image` decodes in this build (its features in Cargo.toml).
pub const IMAGE_FORMATS: [ImageFormat; 5] =
    [ImageFormat::Png, ImageFormat::Jpeg, ImageFormat::Tga, ImageFormat::Bmp, ImageFormat::WebP];

/// The one line for bytes that are none of the formats read here.
pub const NOT_AN_IMAGE: &str = "not an image (expected PNG, JPEG, TGA, BMP, WebP, DDS or KTX2 data)";

/// The most bytes a texture's decoder may allocate for its pixels: 1 GiB, the image file cap
/// (`crate::read::FileKind::Image`). The bake admits its inputs by its own `--max-memory`.
pub const MAX_DECODE_BYTES: u64 = 1 << 30;

/// What an image file's header says, before any pixel is decoded.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Header {
    pub width: u32,
    pub height: u32,
    /// Bytes of the decoded pixels at the file's own depth and channels.
    pub decoded_bytes: u64,
    pub color: ColorType,
}

impl Header {
    /// Texels of the image.
    pub fn texels(&self) -> u64 {
        self.width as u64 * self.height as u64
    }
}

/// Decodes image file bytes of any format read here once `admit` accepts the header, with
/// what a DDS or KTX2 file's format says about its channels (`None` for other formats). The
/// format comes from the bytes' signature; only TGA, which has none, from `tga_by_name` (the
/// file is named `*.tga`). The error is one line.
pub fn decode_image(
    bytes: &[u8],
    tga_by_name: bool,
    max_bytes: u64,
    admit: impl FnOnce(&Header) -> Result<(), String>,
) -> Result<(DynamicImage, Option<Stored>), String> {
    if let Some(container) = Container::sniff(bytes) {
        let admit_rgba = |width: u32, height: u32| -> Result<(), String> {
            let decoded_bytes = (width as u64 * height as u64).saturating_mul(4);
            admit(&Header { width, height, decoded_bytes, color: ColorType::Rgba8 })?;
            if decoded_bytes > max_bytes {
                let mib = decoded_bytes.div_ceil(1 << 20);
                return Err(format!(
                    "{width}x{height} texels decode to {mib} MiB, over the {} MiB an image may take",
                    max_bytes >> 20
                ));
            }
            Ok(())
        };
        let decoded = decode_container(container, bytes, admit_rgba)?;
        let image = RgbaImage::from_raw(decoded.width, decoded.height, decoded.rgba).expect("width · height · 4 bytes");
        return Ok((DynamicImage::ImageRgba8(image), Some(decoded.stored)));
    }
    let format = image::guess_format(bytes).ok().or(tga_by_name.then_some(ImageFormat::Tga));
    let format = match format {
        Some(f) if IMAGE_FORMATS.contains(&f) => f,
        Some(f) => return Err(format!("{f:?} images are not supported (PNG, JPEG, TGA, BMP, WebP, DDS, KTX2)")),
        None => return Err(NOT_AN_IMAGE.to_owned()),
    };
    Ok((decode_admitted(bytes, format, max_bytes, admit)?, None))
}

/// Decodes `bytes` as `format` once `admit` accepts the header: `admit`'s message is returned
/// instead of decoding, and so is a header whose pixels take more than `max_bytes` or a
/// truncated JPEG. The error is one line.
pub fn decode_admitted(
    bytes: &[u8],
    format: ImageFormat,
    max_bytes: u64,
    admit: impl FnOnce(&Header) -> Result<(), String>,
) -> Result<DynamicImage, String> {
    let name = format!("{format:?}").to_uppercase();
    let unreadable = |e: image::ImageError| format!("not a readable {name} image: {e}");
    // Limits are set after the caller's check, so an oversized header gets the caller's message.
    let mut reader = ImageReader::with_format(Cursor::new(bytes), format);
    reader.no_limits();
    let mut decoder = reader.into_decoder().map_err(unreadable)?;
    let (width, height) = decoder.dimensions();
    let header = Header { width, height, decoded_bytes: decoder.total_bytes(), color: decoder.color_type() };
    admit(&header)?;
    if header.decoded_bytes > max_bytes {
        let mib = header.decoded_bytes.div_ceil(1 << 20);
        return Err(format!(
            "{width}x{height} texels decode to {mib} MiB, over the {} MiB an image may take",
            max_bytes >> 20
        ));
    }
    if format == ImageFormat::Jpeg && jpeg_is_truncated(bytes) {
        return Err("the JPEG data ends before its end-of-image marker (truncated)".to_owned());
    }
    let mut limits = Limits::no_limits();
    limits.max_image_width = Some(width);
    limits.max_image_height = Some(height);
    limits.max_alloc = Some(max_bytes);
    decoder.set_limits(limits).map_err(unreadable)?;
    DynamicImage::from_decoder(decoder).map_err(unreadable)
}

/// Whether a JPEG stream lacks the end-of-image marker (`FF D9`) after its last start-of-scan
/// (`FF DA`). Inside entropy-coded data an `FF` byte is always followed by `00` or a restart
/// marker, so the marker found there is the real one; a thumbnail in an `APP1` segment comes
/// before the main image's scans.
pub fn jpeg_is_truncated(bytes: &[u8]) -> bool {
    let last_scan = bytes.windows(2).rposition(|w| w == [0xFF, 0xDA]);
    match last_scan {
        Some(at) => !bytes[at..].windows(2).any(|w| w == [0xFF, 0xD9]),
        None => true,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_jpeg_cut_before_its_end_marker_is_truncated() {
        let mut encoded = Vec::new();
        let image = image::RgbImage::from_fn(16, 16, |x, y| image::Rgb([x as u8 * 16, y as u8 * 16, 128]));
        image.write_to(&mut Cursor::new(&mut encoded), ImageFormat::Jpeg).unwrap();
        assert!(!jpeg_is_truncated(&encoded));
        assert!(decode_admitted(&encoded, ImageFormat::Jpeg, MAX_DECODE_BYTES, |_| Ok(())).is_ok());
        let cut = &encoded[..encoded.len() - 40];
        assert!(jpeg_is_truncated(cut));
        let error = decode_admitted(cut, ImageFormat::Jpeg, MAX_DECODE_BYTES, |_| Ok(())).unwrap_err();
        assert!(error.contains("truncated"), "{error}");
        let refused = decode_admitted(&encoded, ImageFormat::Jpeg, MAX_DECODE_BYTES, |h| {
            Err(format!("{}x{}", h.width, h.height))
        });
        assert_eq!(refused.unwrap_err(), "16x16");
    }
}
