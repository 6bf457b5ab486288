//! Decoding image files with their size known first: the header is read, the caller admits its
//! size (each consumer has its own limits), and only then are pixels allocated, with the
//! decoder's own allocations capped by the caller (textures: [`MAX_DECODE_BYTES`]). A JPEG whose entropy-coded data
//! ends before its end-of-image marker is refused rather than decoded as a grey remainder.

use std::io::Cursor;

use image::{ColorType, DynamicImage, ImageDecoder, ImageFormat, ImageReader, Limits};

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
