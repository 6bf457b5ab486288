//! KTX2 files from Binomial's Basis Universal encoder (native builds only): UASTC 4×4 blocks,
//! Zstandard-supercompressed, and ETC1S with BasisLZ (the `.basis` file's codebooks and Huffman
//! tables become the supercompression global data). The encoder writes a `.basis` file; its
//! parts are read back by the `.basis` layout (header fields at fixed offsets, 23-byte slice
//! descriptors: data offset at 13, size at 17).

use basis_universal::{BasisTextureFormat, Compressor, CompressorParams};

/// Basis Universal's `.basis` file of `rgba` in `format` (linear, one level), UASTC after
/// rate-distortion optimisation at quality scalar `rdo` where given.
fn basis_file(
    rgba: &[u8],
    width: u32,
    height: u32,
    format: BasisTextureFormat,
    rdo: Option<f32>,
) -> Result<Vec<u8>, String> {
    let mut params = CompressorParams::new();
    params.set_rdo_uastc(rdo);
    params.set_basis_format(format);
    params.set_uastc_quality_level(basis_universal::UASTC_QUALITY_DEFAULT);
    params.set_etc1s_quality_level(basis_universal::ETC1S_QUALITY_DEFAULT);
    params.set_generate_mipmaps(false);
    params.set_color_space(basis_universal::ColorSpace::Linear);
    params.source_image_mut(0).init(rgba, width, height, 4);
    let mut compressor = Compressor::new(1);
    // SAFETY: `params` outlives `compressor.process()` (the crate's documented contract).
    let processed = unsafe { compressor.init(&params) && compressor.process().is_ok() };
    if !processed {
        return Err("the Basis Universal encoder failed".to_owned());
    }
    Ok(compressor.basis_file().to_vec())
}

/// A little-endian unsigned field of `bytes` bytes at `at` in `file`.
fn field(file: &[u8], at: usize, bytes: usize) -> Result<usize, String> {
    let raw = file.get(at..at + bytes).ok_or("the .basis file is truncated")?;
    Ok(raw.iter().rev().fold(0, |value, &b| value << 8 | b as usize))
}

/// The bytes `[offset, offset + size)` of `file`.
fn part(file: &[u8], offset: usize, size: usize) -> Result<&[u8], String> {
    file.get(offset..offset + size).ok_or_else(|| "a .basis part lies outside the file".to_owned())
}

/// The data of the `.basis` file's first slice.
fn first_slice(file: &[u8]) -> Result<&[u8], String> {
    let slice = field(file, 65, 4)?;
    part(file, field(file, slice + 13, 4)?, field(file, slice + 17, 4)?)
}

/// A KTX2 file of UASTC blocks of `rgba` (rate-distortion optimised at quality scalar `rdo`
/// where given), Zstandard-supercompressed.
pub fn uastc(rgba: &[u8], width: u32, height: u32, rdo: Option<f32>) -> Result<Vec<u8>, String> {
    uastc_levels(&[(rgba, width, height)], rdo)
}

/// [`uastc`] of a mip chain: `levels` are `(rgba, width, height)`, level 0 first, each encoded
/// on its own.
pub fn uastc_levels(levels: &[(&[u8], u32, u32)], rdo: Option<f32>) -> Result<Vec<u8>, String> {
    let mut packed = Vec::with_capacity(levels.len());
    for &(rgba, width, height) in levels {
        let file = basis_file(rgba, width, height, BasisTextureFormat::UASTC4x4, rdo)?;
        let blocks = first_slice(&file)?;
        let expected = width.div_ceil(4) as usize * height.div_ceil(4) as usize * 16;
        if blocks.len() != expected {
            return Err(format!("the .basis slice holds {} bytes, {expected} expected", blocks.len()));
        }
        packed.push((
            ruzstd::encoding::compress_to_vec(blocks, ruzstd::encoding::CompressionLevel::Fastest),
            blocks.len(),
        ));
    }
    // UASTC, 16 bytes a block, one RGBA sample of 128 bits.
    let dfd = Dfd { model: 166, block_bytes: 16, samples: &[(3, 0, 127)] };
    let (width, height) = (levels[0].1, levels[0].2);
    Ok(ktx2_file(width, height, 2, &dfd, &[], &packed))
}

/// A KTX2 file of ETC1S `rgba` (RGB) with BasisLZ: the global data is the 20-byte header
/// (endpoint and selector counts, the byte lengths of endpoints, selectors, tables and
/// extended data), one 20-byte image descriptor (flags, RGB slice offset and length, alpha
/// slice offset and length) and the codebooks and tables; the level is the RGB slice.
pub fn etc1s(rgba: &[u8], width: u32, height: u32) -> Result<Vec<u8>, String> {
    let rgb: Vec<u8> = rgba.chunks_exact(4).flat_map(|t| [t[0], t[1], t[2], 255]).collect();
    let file = basis_file(&rgb, width, height, BasisTextureFormat::ETC1S, None)?;
    let endpoints = part(&file, field(&file, 41, 4)?, field(&file, 45, 3)?)?;
    let selectors = part(&file, field(&file, 50, 4)?, field(&file, 54, 3)?)?;
    let tables = part(&file, field(&file, 57, 4)?, field(&file, 61, 4)?)?;
    let slice = first_slice(&file)?;
    let mut global = Vec::new();
    global.extend((field(&file, 39, 2)? as u16).to_le_bytes());
    global.extend((field(&file, 48, 2)? as u16).to_le_bytes());
    for length in [endpoints.len(), selectors.len(), tables.len(), 0] {
        global.extend((length as u32).to_le_bytes());
    }
    for word in [0, 0, slice.len() as u32, 0, 0] {
        global.extend(word.to_le_bytes());
    }
    global.extend(endpoints.iter().chain(selectors).chain(tables));
    // ETC1S, no fixed block bytes, one sample: channel RGB (0), 64 bits.
    let dfd = Dfd { model: 163, block_bytes: 0, samples: &[(0, 0, 63)] };
    Ok(ktx2_file(width, height, 1, &dfd, &global, &[(slice.to_vec(), 0)]))
}

/// A basic data format descriptor: colour model, bytes a 4×4 block (plane 0) and its samples
/// (channel id, bit offset, bit length − 1).
struct Dfd<'a> {
    model: u8,
    block_bytes: u8,
    samples: &'a [(u8, u16, u8)],
}

/// A KTX2 file of `levels` (level 0 first; each as stored and its bytes once unpacked, 0 for
/// BasisLZ), `scheme` its supercompression (1 BasisLZ, 2 Zstandard), `global` the
/// supercompression global data, BT.709 primaries, linear, straight alpha. The levels' data
/// lie smallest first, as the KTX2 specification orders them, each at a multiple of 8.
fn ktx2_file(width: u32, height: u32, scheme: u32, dfd: &Dfd, global: &[u8], levels: &[(Vec<u8>, usize)]) -> Vec<u8> {
    let dfd_length = 4 + 24 + 16 * dfd.samples.len() as u32;
    let dfd_offset = 80 + 24 * levels.len() as u32;
    let global_offset = dfd_offset + dfd_length;
    let mut level_offsets = vec![0; levels.len()];
    let mut end = (global_offset as usize + global.len()).next_multiple_of(8);
    for (index, (data, _)) in levels.iter().enumerate().rev() {
        level_offsets[index] = end;
        end = (end + data.len()).next_multiple_of(8);
    }
    let mut out = vec![0xAB, b'K', b'T', b'X', b' ', b'2', b'0', 0xBB, b'\r', b'\n', 0x1A, b'\n'];
    // vkFormat (undefined), typeSize, width, height, depth, layers, faces, levels, scheme;
    // DFD offset and length, key/value data offset and length.
    let count = levels.len() as u32;
    for word in [0, 1, width, height, 0, 0, 1, count, scheme, dfd_offset, dfd_length, 0, 0] {
        out.extend(word.to_le_bytes());
    }
    let global_at = if global.is_empty() { 0 } else { global_offset as u64 };
    for word in [global_at, global.len() as u64] {
        out.extend(word.to_le_bytes());
    }
    for ((data, raw), &offset) in levels.iter().zip(&level_offsets) {
        for word in [offset, data.len(), *raw] {
            out.extend((word as u64).to_le_bytes());
        }
    }
    out.extend(dfd_length.to_le_bytes());
    out.extend(0u32.to_le_bytes()); // vendor 0 (Khronos), descriptor type 0 (basic)
    out.extend(2u16.to_le_bytes()); // version
    out.extend((dfd_length as u16 - 4).to_le_bytes()); // block size
    out.extend([dfd.model, 1, 1, 0]);
    out.extend([3, 3, 0, 0]); // 4x4 texel blocks (dimension − 1)
    out.extend([dfd.block_bytes, 0, 0, 0, 0, 0, 0, 0]);
    for &(channel, offset, length) in dfd.samples {
        out.extend(offset.to_le_bytes());
        out.extend([length, channel]);
        out.extend([0u8; 4]); // sample position
        out.extend(0u32.to_le_bytes());
        out.extend(u32::MAX.to_le_bytes());
    }
    out.extend(global);
    for (index, (data, _)) in levels.iter().enumerate().rev() {
        out.resize(level_offsets[index], 0);
        out.extend(data);
    }
    out
}
