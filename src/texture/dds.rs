//! DDS files (DirectDraw Surface): the container parsed by `ddsfile`, the top level of the
//! first layer (or cube face) decoded to RGBA8: BC1–BC5 and BC7 blocks ([`super::blocks`]),
//! and uncompressed layouts of 8 to 32 bits a texel read through their channel masks
//! (legacy headers) or their DXGI format (`DX10` headers). A file of blocks with its whole mip
//! chain keeps it ([`FileBlocks`]).
//!
//! A BC3 file is DXT5nm (x in alpha, y in green) when its pixel format carries the
//! `DDPF_NORMAL` flag (`0x80000000`, written by NVIDIA's tools) or the `RXGB` code.

use super::blocks::{Block, Texels};
use super::stored::{Decoded, FileBlocks, GpuTexels, Stored, StoredChannels, mip_size, no_memory};
use ddsfile::DxgiFormat;

/// Bytes before the texels: the magic and the 124-byte header (a `DX10` header adds 20).
const HEADER_BYTES: usize = 128;

/// The pixel format flag NVIDIA's tools set on a normal map (DXT5nm when the code is DXT5).
const DDPF_NORMAL: u32 = 0x8000_0000;

/// Decodes a DDS file's top level once `admit(width, height)` accepts its size.
pub fn decode(bytes: &[u8], admit: impl FnOnce(u32, u32) -> Result<(), String>) -> Result<Decoded, String> {
    if bytes.len() < HEADER_BYTES {
        return Err(format!("the DDS header needs {HEADER_BYTES} bytes but the file has {} (truncated)", bytes.len()));
    }
    let dds = ddsfile::Dds::read(bytes).map_err(|e| format!("not a readable DDS file: {e}"))?;
    let (width, height) = (dds.header.width, dds.header.height);
    if dds.header.depth.is_some_and(|d| d > 1) {
        return Err("3D (volume) DDS textures are not supported".to_owned());
    }
    let flags = u32::from_le_bytes(bytes[80..84].try_into().expect("4 bytes"));
    let (layout, format, channels) = layout(&dds, flags)?;
    admit(width, height)?;
    let data = dds.data.as_slice();
    let needed = layout.level_bytes(width, height);
    if (data.len() as u64) < needed {
        return Err(format!(
            "the DDS texels end after {} of the {needed} bytes its {width}x{height} top level needs (truncated)",
            data.len()
        ));
    }
    let rgba = layout.decode(data, width, height).ok_or_else(|| no_memory(width, height))?;
    let gpu = match layout {
        Texels::Blocks(block) => {
            // The first layer's levels come first, each right after the one above it.
            let mut at = 0usize;
            let levels = dds.get_num_mipmap_levels() as usize;
            FileBlocks::gather((block, None), width, height, levels, |level| {
                let [w, h] = mip_size(width, height, level);
                let bytes = block.level_bytes(w, h) as usize;
                let slice = data.get(at..at.checked_add(bytes)?)?;
                at += bytes;
                Some(slice.into())
            })
        }
        Texels::Masks { .. } => GpuTexels::Decoded("uncompressed"),
    };
    Ok(Decoded { width, height, rgba, stored: Stored { format: format!("{format} DDS"), channels, gpu } })
}

/// The texel layout of `dds`, its format's name and what it says about the channels; `flags`
/// are the pixel format's raw flags.
fn layout(dds: &ddsfile::Dds, flags: u32) -> Result<(Texels, String, StoredChannels), String> {
    let block = |b: Block, channels| Ok((Texels::Blocks(b), b.name().to_owned(), channels));
    let spf = &dds.header.spf;
    let fourcc = spf.fourcc.as_ref().map(|f| f.0.to_le_bytes());
    match (&dds.header10, fourcc.as_ref()) {
        (Some(h10), _) => dxgi_layout(h10.dxgi_format),
        (None, Some(b"DXT1")) => block(Block::Bc1, StoredChannels::ColourBlock),
        (None, Some(b"DXT2" | b"DXT3")) => block(Block::Bc2, StoredChannels::ColourBlock),
        (None, Some(b"RXGB")) => block(Block::Bc3, StoredChannels::Ag),
        (None, Some(b"DXT4" | b"DXT5")) if flags & DDPF_NORMAL != 0 => block(Block::Bc3, StoredChannels::Ag),
        (None, Some(b"DXT4" | b"DXT5")) => block(Block::Bc3, StoredChannels::ColourBlock),
        (None, Some(b"ATI1" | b"BC4U")) => block(Block::Bc4, StoredChannels::Plain),
        (None, Some(b"ATI2" | b"BC5U")) => block(Block::Bc5, StoredChannels::Rg),
        (None, Some(code)) => Err(format!("DDS code {:?} is not supported", String::from_utf8_lossy(code))),
        (None, None) => {
            let bits = spf.rgb_bit_count.unwrap_or(0);
            let masks = [spf.r_bit_mask, spf.g_bit_mask, spf.b_bit_mask, spf.a_bit_mask].map(|m| m.unwrap_or(0));
            if ![8, 16, 24, 32].contains(&bits) || masks.iter().all(|&m| m == 0) {
                return Err(format!("the DDS pixel format ({bits} bits, masks {masks:08x?}) is not supported"));
            }
            let two = masks[0] != 0 && masks[1] != 0 && masks[2] == 0 && masks[3] == 0;
            let channels = if two { StoredChannels::Rg } else { StoredChannels::Plain };
            Ok((Texels::Masks { bits, masks }, format!("uncompressed {bits}-bit"), channels))
        }
    }
}

/// The layout of a `DX10` header's DXGI format, its name and what it says about the channels.
fn dxgi_layout(format: DxgiFormat) -> Result<(Texels, String, StoredChannels), String> {
    use DxgiFormat as F;
    let masked = |bits, masks, name: &str, channels| Ok((Texels::Masks { bits, masks }, name.to_owned(), channels));
    let block = |b: Block, channels| Ok((Texels::Blocks(b), b.name().to_owned(), channels));
    match format {
        F::BC1_Typeless | F::BC1_UNorm | F::BC1_UNorm_sRGB => block(Block::Bc1, StoredChannels::ColourBlock),
        F::BC2_Typeless | F::BC2_UNorm | F::BC2_UNorm_sRGB => block(Block::Bc2, StoredChannels::ColourBlock),
        F::BC3_Typeless | F::BC3_UNorm | F::BC3_UNorm_sRGB => block(Block::Bc3, StoredChannels::ColourBlock),
        F::BC4_Typeless | F::BC4_UNorm => block(Block::Bc4, StoredChannels::Plain),
        F::BC5_Typeless | F::BC5_UNorm => block(Block::Bc5, StoredChannels::Rg),
        F::BC7_Typeless | F::BC7_UNorm | F::BC7_UNorm_sRGB => block(Block::Bc7, StoredChannels::Rgba),
        F::R8G8B8A8_Typeless | F::R8G8B8A8_UNorm | F::R8G8B8A8_UNorm_sRGB => {
            masked(32, [0xff, 0xff00, 0xff_0000, 0xff00_0000], "R8G8B8A8", StoredChannels::Plain)
        }
        F::B8G8R8A8_Typeless | F::B8G8R8A8_UNorm | F::B8G8R8A8_UNorm_sRGB => {
            masked(32, [0xff_0000, 0xff00, 0xff, 0xff00_0000], "B8G8R8A8", StoredChannels::Plain)
        }
        F::B8G8R8X8_Typeless | F::B8G8R8X8_UNorm | F::B8G8R8X8_UNorm_sRGB => {
            masked(32, [0xff_0000, 0xff00, 0xff, 0], "B8G8R8X8", StoredChannels::Plain)
        }
        F::R8G8_Typeless | F::R8G8_UNorm => masked(16, [0xff, 0xff00, 0, 0], "R8G8", StoredChannels::Rg),
        F::R8_Typeless | F::R8_UNorm => masked(8, [0xff, 0, 0, 0], "R8", StoredChannels::Plain),
        other => Err(format!("DXGI format {other:?} is not supported (BC1-BC5, BC7, 8-bit RGBA, RG, R)")),
    }
}

/// A DDS file (with a `DX10` header) holding `levels` mip levels of a `width`×`height` texture
/// in `format`, `texels` level 0 first: what `bake --format dds-…` writes.
pub fn dxgi_file(texels: Vec<u8>, width: u32, height: u32, format: DxgiFormat, levels: u32) -> Result<Vec<u8>, String> {
    let params = ddsfile::NewDxgiParams {
        height,
        width,
        depth: None,
        format,
        mipmap_levels: Some(levels),
        array_layers: None,
        caps2: None,
        is_cubemap: false,
        resource_dimension: ddsfile::D3D10ResourceDimension::Texture2D,
        alpha_mode: ddsfile::AlphaMode::Unknown,
    };
    let mut dds = ddsfile::Dds::new_dxgi(params).map_err(|e| format!("cannot make the DDS header: {e}"))?;
    dds.data = texels;
    let mut bytes = Vec::new();
    dds.write(&mut bytes).map_err(|e| format!("cannot write the DDS file: {e}"))?;
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;
    use ddsfile::{D3DFormat, NewD3dParams};

    fn written(mut dds: ddsfile::Dds, texels: &[u8]) -> Vec<u8> {
        dds.data = texels.to_vec();
        let mut bytes = Vec::new();
        dds.write(&mut bytes).unwrap();
        bytes
    }

    #[test]
    fn uncompressed_layouts_decode_through_their_masks_and_r8g8_is_two_channels() {
        let rg = dxgi_file(vec![10, 20, 30, 40], 2, 1, DxgiFormat::R8G8_UNorm, 1).unwrap();
        let decoded = decode(&rg, |_, _| Ok(())).unwrap();
        assert_eq!(decoded.rgba, [10, 20, 0, 255, 30, 40, 0, 255]);
        assert_eq!((decoded.stored.format.as_str(), decoded.stored.channels), ("R8G8 DDS", StoredChannels::Rg));
        // Legacy A8R8G8B8: bytes B, G, R, A in memory.
        let params = NewD3dParams {
            height: 1,
            width: 1,
            depth: None,
            format: D3DFormat::A8R8G8B8,
            mipmap_levels: None,
            caps2: None,
        };
        let bgra = written(ddsfile::Dds::new_d3d(params).unwrap(), &[1, 2, 3, 4]);
        let decoded = decode(&bgra, |_, _| Ok(())).unwrap();
        assert_eq!(decoded.rgba, [3, 2, 1, 4]);
        // Cut short: one line that says so.
        let error = decode(&rg[..rg.len() - 1], |_, _| Ok(())).unwrap_err();
        assert!(error.contains("truncated"), "{error}");
    }
}
