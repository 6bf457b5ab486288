//! Image files in and out of the bake: decoding with size limits checked before any pixel is
//! allocated, and PNG encoding tuned for speed.
//!
//! PNG settings: filter *Up* (each row minus the row above: normal and height maps are smooth,
//! so rows differ little) and DEFLATE level 1 (flate2). Measured on the 4096² RGB normal map of
//! `scripts/compare-nvcompress.sh` (Rock058 tiled): 0.18 s and 8.3 MB, against 1.25 s and
//! 7.4 MB for the `png` crate's default (level 6, adaptive filters: 12% smaller, 7× slower) and
//! 0.18–0.22 s but 31 MB for fdeflate's `Compression::Fast` (no match finding, 3.7× larger).
//! Compression runs on its own thread while the next band of rows is computed.

use std::io::Write;
use std::path::Path;
use std::sync::mpsc;

use image::{DynamicImage, ImageFormat};

use super::BakeError;
use crate::texture::decode::decode_image;

/// The largest side, in texels, the bake reads: a 16384² 16-bit height map is 512 MiB and its
/// normal map 1.5 GiB. Larger headers are refused before their pixels are allocated.
pub const MAX_SIDE: u32 = 16384;

/// The smallest side: a kernel needs neighbours to take a difference.
pub const MIN_SIDE: u32 = 2;

/// Decodes the image file `path` (PNG, JPEG, TGA, BMP, WebP, DDS or KTX2; TGA by extension), refusing sizes
/// outside [`MIN_SIDE`]..=[`MAX_SIDE`] from the header.
pub fn read_image(path: &Path) -> Result<DynamicImage, BakeError> {
    read_image_admitted(path, |_| Ok(()))
}

/// What an image file's header says, before any pixel is decoded.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Header {
    pub width: u32,
    pub height: u32,
    /// Bytes of the file (held while decoding).
    pub file_bytes: u64,
    /// Bytes of the decoded pixels.
    pub decoded_bytes: u64,
    pub color: image::ColorType,
}

/// [`read_image`], with `admit` asked from the header before the pixels are allocated: its
/// error is returned instead of decoding.
pub fn read_image_admitted(
    path: &Path,
    admit: impl FnOnce(&Header) -> Result<(), BakeError>,
) -> Result<DynamicImage, BakeError> {
    let bytes = crate::read::read_file(path, crate::read::FileKind::Image)
        .map_err(|e| BakeError::new(path, format!("cannot read: {e}")))?;
    let tga_by_name = ImageFormat::from_path(path).ok() == Some(ImageFormat::Tga);
    let mut refused = None;
    let admit_header = |h: &crate::texture::decode::Header| {
        let stated = Header {
            width: h.width,
            height: h.height,
            file_bytes: bytes.len() as u64,
            decoded_bytes: h.decoded_bytes,
            color: h.color,
        };
        let admitted = check_size(path, h.width, h.height).and_then(|()| admit(&stated));
        admitted.map_err(|e| {
            let line = e.to_string();
            refused = Some(e);
            line
        })
    };
    // No cap of the decoder's own: the sides and `admit` (the bake's --max-memory) bound it.
    let decoded = decode_image(&bytes, tga_by_name, u64::MAX, admit_header);
    match (decoded, refused) {
        (Ok((image, _)), _) => Ok(image),
        // The caller's own error, as it made it.
        (Err(_), Some(refused)) => Err(refused),
        (Err(problem), None) => Err(BakeError::new(path, problem)),
    }
}

fn check_size(path: &Path, width: u32, height: u32) -> Result<(), BakeError> {
    if width > MAX_SIDE || height > MAX_SIDE {
        return Err(BakeError::new(
            path,
            format!("{width}x{height} texels is over the bake's limit of {MAX_SIDE} per side"),
        ));
    }
    if width < MIN_SIDE || height < MIN_SIDE {
        return Err(BakeError::new(
            path,
            format!("{width}x{height} texels is too small: a bake needs at least {MIN_SIDE}x{MIN_SIDE}"),
        ));
    }
    Ok(())
}

/// A PNG's pixel layout.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PngLayout {
    pub width: u32,
    pub height: u32,
    pub color: png::ColorType,
    pub sixteen_bit: bool,
}

impl PngLayout {
    fn row_bytes(&self) -> usize {
        self.width as usize * self.color.samples() * if self.sixteen_bit { 2 } else { 1 }
    }
}

/// Bytes of compressed data per PNG `IDAT` chunk.
const IDAT_BYTES: usize = 1 << 18;

/// Rows per band handed from the computing thread to the compressing one.
const BAND_ROWS: usize = 128;

/// Writes a PNG of `layout` to `out`: `fill(rows, bytes)` computes image rows `rows` into
/// `bytes` (big-endian for 16 bits) on the calling thread while the previous band is
/// compressed on another.
pub fn write_png(
    out: &mut (impl Write + Send),
    layout: PngLayout,
    mut fill: impl FnMut(std::ops::Range<usize>, &mut [u8]),
) -> std::io::Result<()> {
    let row_bytes = layout.row_bytes();
    let height = layout.height as usize;
    let (full, filled) = mpsc::sync_channel::<Vec<u8>>(1);
    let (empty, recycled) = mpsc::channel::<Vec<u8>>();
    std::thread::scope(|scope| {
        let compressor = scope.spawn(move || -> std::io::Result<()> {
            let mut encoder = png::Encoder::new(out, layout.width, layout.height);
            encoder.set_color(layout.color);
            encoder.set_depth(if layout.sixteen_bit { png::BitDepth::Sixteen } else { png::BitDepth::Eight });
            encoder.set_deflate_compression(png::DeflateCompression::Level(1));
            encoder.set_filter(png::Filter::Up);
            let mut writer = encoder.write_header().map_err(std::io::Error::other)?;
            let mut stream = writer.stream_writer_with_size(IDAT_BYTES)?;
            for band in filled {
                stream.write_all(&band)?;
                // The computing thread may have stopped (it stops when this one fails).
                let _ = empty.send(band);
            }
            stream.finish().map_err(std::io::Error::other)?;
            writer.finish().map_err(std::io::Error::other)
        });
        for start in (0..height).step_by(BAND_ROWS) {
            let rows = start..(start + BAND_ROWS).min(height);
            let mut band = recycled.try_recv().unwrap_or_default();
            band.resize(rows.len() * row_bytes, 0);
            fill(rows, &mut band);
            if full.send(band).is_err() {
                break;
            }
        }
        drop(full);
        compressor.join().unwrap_or_else(|panic| std::panic::resume_unwind(panic))
    })
}
