//! Writing RGBA8 images as GPU texture files (native builds only): DDS with BC1, BC3 (DXT5nm),
//! BC5 or BC7 blocks from Intel's ISPC texture compressor (`intel_tex_2`), and KTX2 with UASTC blocks from
//! Binomial's Basis Universal encoder (`basis-universal`), Zstandard-supercompressed
//! (`ruzstd`), or ETC1S with BasisLZ ([`super::ktx2_out`]). One level, or (DDS, UASTC) the
//! whole mip chain ([`encode_with_mips`]). Sides must be multiples of 4.

use ddsfile::DxgiFormat;

pub use super::compressed_format::CompressedFormat;
use crate::names::Named;
use crate::scene::{TextureImage, TextureKind};
use crate::texture::dxgi_file;

/// Encodes a `width`×`height` RGBA8 image (rows top to bottom) as `format`'s file bytes,
/// one level.
pub fn encode(rgba: &[u8], width: u32, height: u32, format: CompressedFormat) -> Result<Vec<u8>, String> {
    check_size(rgba, width, height)?;
    match format {
        CompressedFormat::Ktx2Uastc => super::ktx2_out::uastc(rgba, width, height, None),
        CompressedFormat::Ktx2UastcRdo => {
            super::ktx2_out::uastc(rgba, width, height, Some(super::compressed_format::UASTC_RDO_QUALITY))
        }
        CompressedFormat::Ktx2Etc1s => super::ktx2_out::etc1s(rgba, width, height),
        dds => dds_file(dds, dds_level(dds, rgba, width, height), width, height, 1),
    }
}

/// [`encode`] for a normal map with its complete mip chain in the file (DDS formats and UASTC;
/// an ETC1S file keeps one level): each level the re-normalised 2×2 box mean of the one above,
/// as the viewer makes a normal map's chain ([`TextureImage::mip_chain`]); in a DDS file of
/// blocks a level whose sides are not multiples of 4 is encoded with its last row and column
/// repeated to fill whole blocks.
pub fn encode_with_mips(rgba: &[u8], width: u32, height: u32, format: CompressedFormat) -> Result<Vec<u8>, String> {
    check_size(rgba, width, height)?;
    let kind = TextureKind::NormalMap;
    let map = TextureImage::new(String::new(), width, height, kind, rgba.to_vec());
    let chain = map.mip_chain().map_err(|e| format!("no memory for the mip chain: {e}"))?;
    let levels = || chain.iter().map(|l| (l.rgba.as_slice(), l.width, l.height)).collect::<Vec<_>>();
    match format {
        CompressedFormat::Ktx2Uastc => return super::ktx2_out::uastc_levels(&levels(), None),
        CompressedFormat::Ktx2UastcRdo => {
            return super::ktx2_out::uastc_levels(&levels(), Some(super::compressed_format::UASTC_RDO_QUALITY));
        }
        CompressedFormat::Ktx2Etc1s => return Err(format!("{} files are written with one level", format.name())),
        _ => {}
    }
    let mut texels = Vec::new();
    for level in &chain {
        // Block formats cover whole blocks: a level's last texels repeated to fill them.
        let side = |s: u32| if format == CompressedFormat::DdsRg8 { s } else { s.next_multiple_of(4) };
        let [w, h] = [side(level.width), side(level.height)];
        let last = |s: u32| i64::from(s) - 1;
        let filled: Vec<u8> = (0..i64::from(h))
            .flat_map(|y| {
                (0..i64::from(w)).flat_map(move |x| level.texel(x.min(last(level.width)), y.min(last(level.height))))
            })
            .collect();
        texels.extend(dds_level(format, &filled, w, h));
    }
    dds_file(format, texels, width, height, chain.len() as u32)
}

/// Sides that are multiples of 4 and as many bytes as texels.
fn check_size(rgba: &[u8], width: u32, height: u32) -> Result<(), String> {
    if !width.is_multiple_of(4) || !height.is_multiple_of(4) || width == 0 || height == 0 {
        return Err(format!("{width}x{height}: block-compressed files need sides that are multiples of 4"));
    }
    if rgba.len() as u64 != width as u64 * height as u64 * 4 {
        return Err("the image holds fewer texels than its size".to_owned());
    }
    Ok(())
}

/// One level's texels in a DDS `format`: blocks (sides multiples of 4) or RG8 texels.
fn dds_level(format: CompressedFormat, rgba: &[u8], width: u32, height: u32) -> Vec<u8> {
    let rgba_surface = |data| intel_tex_2::RgbaSurface { data, width, height, stride: width * 4 };
    let rg = || rgba.chunks_exact(4).flat_map(|t| [t[0], t[1]]).collect::<Vec<u8>>();
    match format {
        CompressedFormat::DdsBc1 => intel_tex_2::bc1::compress_blocks(&rgba_surface(rgba)),
        CompressedFormat::DdsDxt5nm => {
            let swizzled: Vec<u8> = rgba.chunks_exact(4).flat_map(|t| [255, t[1], 0, t[0]]).collect();
            intel_tex_2::bc3::compress_blocks(&rgba_surface(&swizzled))
        }
        CompressedFormat::DdsBc5 => {
            intel_tex_2::bc5::compress_blocks(&intel_tex_2::RgSurface { data: &rg(), width, height, stride: width * 2 })
        }
        CompressedFormat::DdsBc7 => {
            intel_tex_2::bc7::compress_blocks(&intel_tex_2::bc7::alpha_basic_settings(), &rgba_surface(rgba))
        }
        _ => rg(),
    }
}

/// The DDS file of `levels` levels of `texels` in `format` (a `DX10` header; DXT5nm a legacy
/// one).
fn dds_file(
    format: CompressedFormat,
    texels: Vec<u8>,
    width: u32,
    height: u32,
    levels: u32,
) -> Result<Vec<u8>, String> {
    let dxgi = match format {
        CompressedFormat::DdsDxt5nm => return dxt5nm(texels, width, height, levels),
        CompressedFormat::DdsBc1 => DxgiFormat::BC1_UNorm,
        CompressedFormat::DdsBc5 => DxgiFormat::BC5_UNorm,
        CompressedFormat::DdsBc7 => DxgiFormat::BC7_UNorm,
        _ => DxgiFormat::R8G8_UNorm,
    };
    dxgi_file(texels, width, height, dxgi, levels)
}

/// A legacy-header DDS file of BC3 `blocks` with the `DXT5` code and the pixel format flag
/// `DDPF_NORMAL` (`0x80000000`, byte 80 on) that marks DXT5nm.
fn dxt5nm(blocks: Vec<u8>, width: u32, height: u32, levels: u32) -> Result<Vec<u8>, String> {
    let params = ddsfile::NewD3dParams {
        height,
        width,
        depth: None,
        format: ddsfile::D3DFormat::DXT5,
        mipmap_levels: Some(levels),
        caps2: None,
    };
    let mut dds = ddsfile::Dds::new_d3d(params).map_err(|e| format!("cannot make the DDS header: {e}"))?;
    dds.data = blocks;
    let mut bytes = Vec::new();
    dds.write(&mut bytes).map_err(|e| format!("cannot write the DDS file: {e}"))?;
    bytes[83] |= 0x80;
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::texture::compressed::GpuTexels;
    use crate::texture::decode::{MAX_DECODE_BYTES, decode_image};

    /// A 12×20 map's chain (6×10, 3×5, 1×2, 1×1 below it) is written as whole blocks, so the
    /// reader finds every level complete; RG8 levels keep their own sizes.
    #[test]
    fn levels_whose_sides_are_not_multiples_of_4_are_written_as_whole_blocks() {
        let rgba: Vec<u8> = (0..12 * 20).flat_map(|i| [(i * 5 % 256) as u8, (i * 11 % 256) as u8, 200, 255]).collect();
        for format in
            [CompressedFormat::DdsBc5, CompressedFormat::DdsBc1, CompressedFormat::DdsDxt5nm, CompressedFormat::DdsBc7]
        {
            let file = encode_with_mips(&rgba, 12, 20, format).unwrap();
            let (_, stored) = decode_image(&file, false, MAX_DECODE_BYTES, |_| Ok(())).unwrap();
            let Some(GpuTexels::Blocks(chain)) = stored.map(|s| s.gpu) else { panic!("{format:?}: not a whole chain") };
            assert_eq!(chain.levels.len(), 5, "{format:?}");
        }
        let file = encode_with_mips(&rgba, 12, 20, CompressedFormat::DdsRg8).unwrap();
        let texels: usize = [(12, 20), (6, 10), (3, 5), (1, 2), (1, 1)].iter().map(|(w, h)| w * h).sum();
        assert!(file.len() >= 2 * texels && file.len() < 2 * texels + 200, "{} bytes", file.len());
    }
}
