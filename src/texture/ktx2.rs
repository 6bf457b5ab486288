//! KTX2 files: the container parsed by the `ktx2` crate, the top level of the first layer (or
//! cube face) decoded to RGBA8. Read directly: BC1–BC5 and BC7 ([`super::blocks`]), R8G8B8A8,
//! R8G8 and R8. Supercompression: Zstandard (`ruzstd`, pure Rust) and zlib (`flate2`).
//! UASTC and ETC1S with BasisLZ (`KHR_texture_basisu`) are transcoded by Binomial's transcoder
//! ([`super::basis`]), which is native only: the browser build names the file and says it
//! cannot. A Basis file that keeps x in red, green and blue and y in alpha (ETC1S channels
//! RRR and GGG, UASTC RRRG: how Basis stores normal maps) is handed on as x in red, y in green.
//! A whole mip chain of BC blocks, or of UASTC ones (transcoded level by level to BC7), is kept
//! for the GPU ([`FileBlocks`]).

use std::io::Read;

use ktx2::{ColorModel, Format, SupercompressionScheme};

use super::blocks::{Block, Texels};
use super::stored::{Decoded, FileBlocks, GpuTexels, Stored, StoredChannels, mip_size, no_memory};

/// DFD channel ids of two-channel Basis files: UASTC RRRG and RG, ETC1S RRR and GGG.
const UASTC_RRRG: u8 = 5;
const UASTC_RG: u8 = 6;
const ETC1S_RRR: u8 = 3;
const ETC1S_GGG: u8 = 4;

/// How the texels of a KTX2 file are stored.
enum Layout {
    /// BCn blocks, or texels read through the masks of a little-endian word.
    Plain(Texels),
    /// UASTC blocks; `true`: x in red, green and blue, y in alpha.
    Uastc(bool),
    /// ETC1S with BasisLZ; `true`: x in the RGB slice, y in the alpha slice.
    Etc1s(bool),
}

/// Decodes a KTX2 file's top level once `admit(width, height)` accepts its size.
pub fn decode(bytes: &[u8], admit: impl FnOnce(u32, u32) -> Result<(), String>) -> Result<Decoded, String> {
    if has_overflowing_block_dimension(bytes) {
        return Err("not a readable KTX2 file: a data format descriptor gives a texel block side of 256".to_owned());
    }
    let reader = ktx2::Reader::new(bytes).map_err(|e| format!("not a readable KTX2 file: {e}"))?;
    let header = reader.header();
    let (width, height) = (header.pixel_width, header.pixel_height.max(1));
    if header.pixel_depth > 1 {
        return Err("3D KTX2 textures are not supported".to_owned());
    }
    let scheme = header.supercompression_scheme;
    let (layout, name, channels) = layout(&reader, header.format, scheme)?;
    let packed = match scheme {
        None => String::new(),
        Some(SupercompressionScheme::Zstandard) => " (Zstandard)".to_owned(),
        Some(SupercompressionScheme::ZLIB) => " (zlib)".to_owned(),
        Some(SupercompressionScheme::BasisLZ) => " (BasisLZ)".to_owned(),
        Some(other) => return Err(format!("KTX2 supercompression {other:?} is not supported")),
    };
    admit(width, height)?;
    let level = reader.levels().next().ok_or("the KTX2 file has no mip level")?;
    // Level 0 is decoded from the blocks the GPU would take, so a UASTC level is transcoded once.
    let gpu = gpu_texels(&reader, &layout, scheme, width, height);
    let rgba = match (&gpu, &layout) {
        (GpuTexels::Blocks(chain), _) => chain.decoded_level(0),
        (_, &Layout::Etc1s(swizzle)) => {
            let images = header.level_count.max(1) as usize * header.layer_count.max(1) as usize;
            let images = images * header.face_count.max(1) as usize;
            let global = reader.supercompression_global_data();
            let rgba = super::basis::transcode_etc1s(global, level.data, width, height, images)?;
            Some(if swizzle { alpha_to_green(rgba) } else { rgba })
        }
        _ => decode_level_data(&layout, level.data, scheme, width, height)?,
    };
    let rgba = rgba.ok_or_else(|| no_memory(width, height))?;
    Ok(Decoded { width, height, rgba, stored: Stored { format: format!("{name} KTX2{packed}"), channels, gpu } })
}

/// The file's levels as BC blocks where its layout keeps them: BCn as stored, UASTC
/// transcoded level by level to BC7 (the transcoder's near-lossless target).
fn gpu_texels(
    reader: &ktx2::Reader<&[u8]>,
    layout: &Layout,
    scheme: Option<SupercompressionScheme>,
    width: u32,
    height: u32,
) -> GpuTexels {
    let levels = reader.header().level_count.max(1) as usize;
    let unpacked_level = |level: usize, needed: u64| {
        let data = reader.levels().nth(level)?.data;
        unpacked(data, scheme, needed).ok()
    };
    match *layout {
        Layout::Plain(Texels::Blocks(block)) => FileBlocks::gather((block, None), width, height, levels, |level| {
            let [w, h] = mip_size(width, height, level);
            unpacked_level(level, block.level_bytes(w, h)).map(Into::into)
        }),
        Layout::Uastc(false) => FileBlocks::gather((Block::Bc7, Some("UASTC")), width, height, levels, |level| {
            let [w, h] = mip_size(width, height, level);
            let uastc = unpacked_level(level, Block::Bc7.level_bytes(w, h))?;
            super::basis::transcode_uastc_blocks(&uastc, w, h).ok().map(Into::into)
        }),
        Layout::Uastc(true) | Layout::Etc1s(true) => GpuTexels::Decoded("x and y moved to red and green"),
        Layout::Etc1s(false) => GpuTexels::Decoded("ETC1S"),
        Layout::Plain(Texels::Masks { .. }) => GpuTexels::Decoded("uncompressed"),
    }
}

/// The texels of a level that is not BasisLZ: unpacked by `scheme`, checked against the bytes
/// `width`×`height` texels need, decoded (`Ok(None)`: no memory).
fn decode_level_data(
    layout: &Layout,
    data: &[u8],
    scheme: Option<SupercompressionScheme>,
    width: u32,
    height: u32,
) -> Result<Option<Vec<u8>>, String> {
    let needed = match *layout {
        Layout::Plain(texels) => texels.level_bytes(width, height),
        Layout::Uastc(_) => width.div_ceil(4) as u64 * height.div_ceil(4) as u64 * 16,
        Layout::Etc1s(_) => return Err("an ETC1S level is BasisLZ-supercompressed".to_owned()),
    };
    let data = unpacked(data, scheme, needed)?;
    if (data.len() as u64) < needed {
        return Err(format!(
            "the KTX2 top level holds {} of the {needed} bytes its {width}x{height} texels need (truncated)",
            data.len()
        ));
    }
    Ok(match *layout {
        Layout::Plain(texels) => texels.decode(&data, width, height),
        Layout::Uastc(swizzle) => {
            let rgba = super::basis::transcode_uastc(&data, width, height)?;
            rgba.map(|rgba| if swizzle { alpha_to_green(rgba) } else { rgba })
        }
        Layout::Etc1s(_) => None,
    })
}

/// A two-channel Basis layout (x in red, green and blue, y in alpha) as x in red, y in green,
/// blue 0, alpha 255.
fn alpha_to_green(mut rgba: Vec<u8>) -> Vec<u8> {
    for texel in rgba.chunks_exact_mut(4) {
        texel.copy_from_slice(&[texel[0], texel[3], 0, 255]);
    }
    rgba
}

/// The layout of a KTX2 file, its format's name and what it says about the channels.
fn layout(
    reader: &ktx2::Reader<&[u8]>,
    format: Option<Format>,
    scheme: Option<SupercompressionScheme>,
) -> Result<(Layout, String, StoredChannels), String> {
    let block = |b: Block, channels| Ok((Layout::Plain(Texels::Blocks(b)), b.name().to_owned(), channels));
    let masked = |bits, masks, name: &str, channels| {
        Ok((Layout::Plain(Texels::Masks { bits, masks }), name.to_owned(), channels))
    };
    let colour = StoredChannels::ColourBlock;
    match format {
        Some(Format::BC1_RGB_UNORM_BLOCK | Format::BC1_RGB_SRGB_BLOCK) => block(Block::Bc1, colour),
        Some(Format::BC1_RGBA_UNORM_BLOCK | Format::BC1_RGBA_SRGB_BLOCK) => block(Block::Bc1, colour),
        Some(Format::BC2_UNORM_BLOCK | Format::BC2_SRGB_BLOCK) => block(Block::Bc2, colour),
        Some(Format::BC3_UNORM_BLOCK | Format::BC3_SRGB_BLOCK) => block(Block::Bc3, colour),
        Some(Format::BC4_UNORM_BLOCK) => block(Block::Bc4, StoredChannels::Plain),
        Some(Format::BC5_UNORM_BLOCK) => block(Block::Bc5, StoredChannels::Rg),
        Some(Format::BC7_UNORM_BLOCK | Format::BC7_SRGB_BLOCK) => block(Block::Bc7, StoredChannels::Rgba),
        Some(Format::R8G8B8A8_UNORM | Format::R8G8B8A8_SRGB) => {
            masked(32, [0xff, 0xff00, 0xff_0000, 0xff00_0000], "R8G8B8A8", StoredChannels::Plain)
        }
        Some(Format::R8G8_UNORM) => masked(16, [0xff, 0xff00, 0, 0], "R8G8", StoredChannels::Rg),
        Some(Format::R8_UNORM) => masked(8, [0xff, 0, 0, 0], "R8", StoredChannels::Plain),
        Some(other) => Err(format!("KTX2 format {other:?} is not supported (BCn, R8G8B8A8, R8G8, R8, UASTC)")),
        None => {
            let dfd = reader.basic_dfd().ok_or("the KTX2 file has no basic data format descriptor")?;
            match dfd.color_model {
                Some(ColorModel::UASTC) => {
                    let channel = dfd.sample_information.first().map(|s| s.channel_type);
                    let rrrg = channel == Some(UASTC_RRRG);
                    let two = rrrg || channel == Some(UASTC_RG);
                    let channels = if two { StoredChannels::Rg } else { StoredChannels::Rgba };
                    Ok((Layout::Uastc(rrrg), "UASTC".to_owned(), channels))
                }
                Some(ColorModel::ETC1S) if scheme == Some(SupercompressionScheme::BasisLZ) => {
                    let ids: Vec<u8> = dfd.sample_information.iter().map(|s| s.channel_type).collect();
                    let two = ids == [ETC1S_RRR, ETC1S_GGG];
                    let channels = if two { StoredChannels::Rg } else { StoredChannels::ColourBlock };
                    Ok((Layout::Etc1s(two), "ETC1S".to_owned(), channels))
                }
                model => Err(format!("KTX2 colour model {model:?} without a format is not supported")),
            }
        }
    }
}

/// The top level's bytes, unpacked by `scheme`: at most `needed` bytes are inflated, so a
/// stream that claims more stops there, and the output grows with what the stream really
/// holds (nothing is reserved from a size the file states).
fn unpacked(data: &[u8], scheme: Option<SupercompressionScheme>, needed: u64) -> Result<Vec<u8>, String> {
    let mut out = Vec::new();
    let read = match scheme {
        None => return Ok(data.to_vec()),
        Some(SupercompressionScheme::Zstandard) => {
            let mut source = data;
            let decoder = ruzstd::decoding::StreamingDecoder::new(&mut source)
                .map_err(|e| format!("the KTX2 level's Zstandard stream does not decode: {e}"))?;
            decoder.take(needed).read_to_end(&mut out)
        }
        Some(_) => flate2::read::ZlibDecoder::new(data).take(needed).read_to_end(&mut out),
    };
    read.map_err(|e| format!("the KTX2 level's supercompressed data does not decode: {e}"))?;
    Ok(out)
}

/// Whether a basic block of the data format descriptor gives a texel block dimension byte of
/// 255 (a side of 256): `ktx2` 0.5 adds 1 to it as a `u8` and panics, so such a file is refused
/// before it is parsed. Walks the blocks as `ktx2` does (header word, version, size).
fn has_overflowing_block_dimension(bytes: &[u8]) -> bool {
    let word = |at: usize| bytes.get(at..at + 4).map(|b| u32::from_le_bytes(b.try_into().expect("4 bytes")));
    let (Some(offset), Some(length)) = (word(48), word(52)) else { return false };
    let end = (offset as usize).saturating_add(length as usize).min(bytes.len());
    let mut at = offset as usize + 4;
    while at.saturating_add(8) <= end {
        let basic = word(at) == Some(0);
        if basic && bytes.get(at + 12..at + 16).is_some_and(|d| d.contains(&255)) {
            return true;
        }
        let size = bytes.get(at + 6..at + 8).map_or(0, |b| u16::from_le_bytes([b[0], b[1]]) as usize);
        if size == 0 {
            break;
        }
        at += size;
    }
    false
}
