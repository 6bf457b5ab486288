//! Basis Universal textures (`KHR_texture_basisu`) → RGBA8 through Binomial's transcoder (the
//! `basis-universal` crate, C++ built by `cc`): UASTC blocks, and ETC1S (BasisLZ) levels, whose
//! codebooks, tables and slices are put into the `.basis` file the crate's transcoder reads. It
//! does not build for the browser: there the file is refused in one line that says so.
//!
//! The transcoder writes BC7 blocks (UASTC's designed near-lossless target), which
//! [`super::blocks`] decodes: the crate's wrapper sizes an RGBA32 output as if it were blocks
//! (a quarter of the row), so asking it for RGBA32 directly writes past its buffer.

#[cfg(not(target_arch = "wasm32"))]
use super::blocks::{Block, decode_level};

/// Transcodes `width`×`height` texels of UASTC blocks (16 bytes each, rows of blocks) to RGBA8
/// (`Ok(None)`: no memory for the texels).
#[cfg(not(target_arch = "wasm32"))]
pub fn transcode_uastc(blocks: &[u8], width: u32, height: u32) -> Result<Option<Vec<u8>>, String> {
    let bc7 = transcode_uastc_blocks(blocks, width, height)?;
    Ok(decode_level(Block::Bc7, &bc7, width, height))
}

/// Transcodes `width`×`height` texels of UASTC blocks to BC7 blocks (16 bytes each).
#[cfg(not(target_arch = "wasm32"))]
pub fn transcode_uastc_blocks(blocks: &[u8], width: u32, height: u32) -> Result<Vec<u8>, String> {
    use basis_universal::{DecodeFlags, LowLevelUastcTranscoder, SliceParametersUastc, TranscoderBlockFormat};
    let parameters = SliceParametersUastc {
        num_blocks_x: width.div_ceil(4),
        num_blocks_y: height.div_ceil(4),
        has_alpha: true,
        original_width: width,
        original_height: height,
    };
    LowLevelUastcTranscoder::new()
        .transcode_slice(blocks, parameters, DecodeFlags::empty(), TranscoderBlockFormat::BC7)
        .map_err(|e| format!("the UASTC blocks do not transcode: {e:?}"))
}

/// The browser build has no Basis transcoder.
#[cfg(target_arch = "wasm32")]
pub fn transcode_uastc(_blocks: &[u8], _width: u32, _height: u32) -> Result<Option<Vec<u8>>, String> {
    Err("UASTC (Basis Universal) textures cannot be transcoded in the browser build".to_owned())
}

/// The browser build has no Basis transcoder.
#[cfg(target_arch = "wasm32")]
pub fn transcode_uastc_blocks(_blocks: &[u8], _width: u32, _height: u32) -> Result<Vec<u8>, String> {
    Err("UASTC (Basis Universal) textures cannot be transcoded in the browser build".to_owned())
}

/// The parts of a KTX2 BasisLZ (ETC1S) level: codebooks and tables from the supercompression
/// global data, the first image's RGB and alpha slices from the level.
#[cfg(not(target_arch = "wasm32"))]
struct Etc1sParts<'a> {
    endpoint_count: u16,
    selector_count: u16,
    endpoints: &'a [u8],
    selectors: &'a [u8],
    tables: &'a [u8],
    rgb: &'a [u8],
    alpha: &'a [u8],
}

/// Reads the global data: a 20-byte header (endpoint and selector counts; byte lengths of
/// endpoints, selectors, tables and extended data), `images` 20-byte image descriptors (flags;
/// RGB slice offset and length; alpha slice offset and length, relative to the level), then
/// the endpoints, selectors and tables. Every range is checked against its bytes.
#[cfg(not(target_arch = "wasm32"))]
fn etc1s_parts<'a>(global: &'a [u8], level: &'a [u8], images: usize) -> Result<Etc1sParts<'a>, String> {
    let bad = || "the KTX2 BasisLZ global data is truncated or inconsistent".to_owned();
    let word = |at: usize| global.get(at..at + 4).map(|b| u32::from_le_bytes(b.try_into().expect("4")) as usize);
    let half = |at: usize| global.get(at..at + 2).map(|b| u16::from_le_bytes([b[0], b[1]]));
    let range = |bytes: &'a [u8], at: usize, len: usize| bytes.get(at..at.checked_add(len)?);
    let (endpoint_count, selector_count) = (half(0).ok_or_else(bad)?, half(2).ok_or_else(bad)?);
    let [Some(endpoints_len), Some(selectors_len), Some(tables_len)] = [word(4), word(8), word(12)] else {
        return Err(bad());
    };
    let start = images.checked_mul(20).and_then(|d| d.checked_add(20)).ok_or_else(bad)?;
    let endpoints = range(global, start, endpoints_len).ok_or_else(bad)?;
    let selectors = range(global, start + endpoints_len, selectors_len).ok_or_else(bad)?;
    let tables = range(global, start + endpoints_len + selectors_len, tables_len).ok_or_else(bad)?;
    let [rgb_at, rgb_len, alpha_at, alpha_len] = [word(24), word(28), word(32), word(36)].map(|w| w.unwrap_or(0));
    let missing = || "the KTX2 BasisLZ slice lies outside its level".to_owned();
    let rgb = range(level, rgb_at, rgb_len).filter(|s| !s.is_empty()).ok_or_else(missing)?;
    let alpha = range(level, alpha_at, alpha_len).ok_or_else(missing)?;
    Ok(Etc1sParts { endpoint_count, selector_count, endpoints, selectors, tables, rgb, alpha })
}

/// Basis Universal's CRC-16 (its `basisu::crc16`), over `bytes`.
#[cfg(not(target_arch = "wasm32"))]
fn crc16(bytes: &[u8]) -> u16 {
    let mut crc = !0u16;
    for &b in bytes {
        let q = b as u16 ^ (crc >> 8);
        let k = (q >> 4) ^ q;
        crc = (crc << 8) ^ k ^ (k << 5) ^ (k << 12);
    }
    !crc
}

/// The `.basis` file (format version 0x13) that holds `parts` as one ETC1S image of
/// `width`×`height`: the 77-byte header, one slice descriptor (23 bytes) per slice, the
/// codebooks, tables and slices. The transcoder reads `.basis` files, not KTX2.
#[cfg(not(target_arch = "wasm32"))]
fn basis_file(parts: &Etc1sParts, width: u32, height: u32) -> Vec<u8> {
    let slices: Vec<&[u8]> = [parts.rgb, parts.alpha].into_iter().filter(|s| !s.is_empty()).collect();
    let put = |out: &mut Vec<u8>, value: usize, bytes: usize| out.extend(&(value as u64).to_le_bytes()[..bytes]);
    let header_end = 77 + 23 * slices.len();
    let endpoints_at = header_end;
    let selectors_at = endpoints_at + parts.endpoints.len();
    let tables_at = selectors_at + parts.selectors.len();
    let mut slice_at = tables_at + parts.tables.len();
    let mut out = Vec::new();
    for (index, slice) in slices.iter().enumerate() {
        put(&mut out, 0, 4); // image 0, level 0
        put(&mut out, if index == 1 { 1 } else { 0 }, 1); // an alpha slice's flag
        for value in [width as usize, height as usize, width.div_ceil(4) as usize, height.div_ceil(4) as usize] {
            put(&mut out, value, 2);
        }
        put(&mut out, slice_at, 4);
        put(&mut out, slice.len(), 4);
        put(&mut out, crc16(slice) as usize, 2);
        slice_at += slice.len();
    }
    out.extend(parts.endpoints.iter().chain(parts.selectors).chain(parts.tables));
    slices.iter().for_each(|s| out.extend(*s));
    let mut header = Vec::with_capacity(77);
    put(&mut header, (b'B' as usize) << 8 | b's' as usize, 2);
    put(&mut header, 0x13, 2);
    put(&mut header, 77, 2);
    put(&mut header, 0, 2); // header CRC, set below
    put(&mut header, out.len(), 4);
    put(&mut header, crc16(&out) as usize, 2);
    put(&mut header, slices.len(), 3);
    put(&mut header, 1, 3); // images
    put(&mut header, 0, 1); // ETC1S
    put(&mut header, if slices.len() == 2 { 1 | 4 } else { 1 }, 2); // ETC1S, has alpha slices
    header.extend([0u8; 1 + 3 + 4 + 4 + 4]); // 2D; frame time, reserved, user data
    put(&mut header, parts.endpoint_count as usize, 2);
    put(&mut header, endpoints_at, 4);
    put(&mut header, parts.endpoints.len(), 3);
    put(&mut header, parts.selector_count as usize, 2);
    put(&mut header, selectors_at, 4);
    put(&mut header, parts.selectors.len(), 3);
    put(&mut header, tables_at, 4);
    put(&mut header, parts.tables.len(), 4);
    put(&mut header, 77, 4); // slice descriptors
    put(&mut header, 0, 8); // no extended data
    let crc = crc16(&header[8..]);
    header[6..8].copy_from_slice(&crc.to_le_bytes());
    header.extend(out);
    header
}

/// Transcodes the first image of a KTX2 ETC1S (BasisLZ) level to RGBA8 through the `.basis`
/// file of the same data ([`basis_file`]); `images` is the number of image descriptors in
/// `global` (levels × layers × faces).
#[cfg(not(target_arch = "wasm32"))]
pub fn transcode_etc1s(global: &[u8], level: &[u8], width: u32, height: u32, images: usize) -> Result<Vec<u8>, String> {
    use basis_universal::{TranscodeParameters, Transcoder, TranscoderTextureFormat};
    let file = basis_file(&etc1s_parts(global, level, images)?, width, height);
    let mut transcoder = Transcoder::new();
    transcoder.prepare_transcoding(&file).map_err(|()| "the ETC1S codebooks do not decode".to_owned())?;
    let rgba = transcoder
        .transcode_image_level(&file, TranscoderTextureFormat::RGBA32, TranscodeParameters::default())
        .map_err(|e| format!("the ETC1S slices do not transcode: {e:?}"))?;
    transcoder.end_transcoding();
    match rgba.len() as u64 == width as u64 * height as u64 * 4 {
        true => Ok(rgba),
        false => Err("the ETC1S transcoder returned a level of another size".to_owned()),
    }
}

/// The browser build has no Basis transcoder.
#[cfg(target_arch = "wasm32")]
pub fn transcode_etc1s(_: &[u8], _: &[u8], _: u32, _: u32, _: usize) -> Result<Vec<u8>, String> {
    Err("ETC1S (Basis Universal) textures cannot be transcoded in the browser build".to_owned())
}
