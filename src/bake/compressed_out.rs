//! Writing RGBA8 images as GPU texture files (native builds only): DDS with BC1, BC3 (DXT5nm),
//! BC5 or BC7 blocks from Intel's ISPC texture compressor (`intel_tex_2`), and KTX2 with UASTC blocks from
//! Binomial's Basis Universal encoder (`basis-universal`), Zstandard-supercompressed
//! (`ruzstd`), or ETC1S with BasisLZ ([`super::ktx2_out`]). One level each (viewers make the
//! mips). Sides must be multiples of 4.

use ddsfile::DxgiFormat;

pub use super::compressed_format::CompressedFormat;
use crate::texture::dxgi_file;

/// Encodes a `width`×`height` RGBA8 image (rows top to bottom) as `format`'s file bytes.
pub fn encode(rgba: &[u8], width: u32, height: u32, format: CompressedFormat) -> Result<Vec<u8>, String> {
    if !width.is_multiple_of(4) || !height.is_multiple_of(4) || width == 0 || height == 0 {
        return Err(format!("{width}x{height}: block-compressed files need sides that are multiples of 4"));
    }
    if rgba.len() as u64 != width as u64 * height as u64 * 4 {
        return Err("the image holds fewer texels than its size".to_owned());
    }
    match format {
        CompressedFormat::DdsBc1 => {
            let surface = intel_tex_2::RgbaSurface { data: rgba, width, height, stride: width * 4 };
            dxgi_file(intel_tex_2::bc1::compress_blocks(&surface), width, height, DxgiFormat::BC1_UNorm)
        }
        CompressedFormat::DdsDxt5nm => {
            let swizzled: Vec<u8> = rgba.chunks_exact(4).flat_map(|t| [255, t[1], 0, t[0]]).collect();
            let surface = intel_tex_2::RgbaSurface { data: &swizzled, width, height, stride: width * 4 };
            dxt5nm(intel_tex_2::bc3::compress_blocks(&surface), width, height)
        }
        CompressedFormat::DdsBc5 => {
            let rg: Vec<u8> = rgba.chunks_exact(4).flat_map(|t| [t[0], t[1]]).collect();
            let surface = intel_tex_2::RgSurface { data: &rg, width, height, stride: width * 2 };
            dxgi_file(intel_tex_2::bc5::compress_blocks(&surface), width, height, DxgiFormat::BC5_UNorm)
        }
        CompressedFormat::DdsBc7 => {
            let surface = intel_tex_2::RgbaSurface { data: rgba, width, height, stride: width * 4 };
            let settings = intel_tex_2::bc7::alpha_basic_settings();
            dxgi_file(intel_tex_2::bc7::compress_blocks(&settings, &surface), width, height, DxgiFormat::BC7_UNorm)
        }
        CompressedFormat::DdsRg8 => {
            let rg: Vec<u8> = rgba.chunks_exact(4).flat_map(|t| [t[0], t[1]]).collect();
            dxgi_file(rg, width, height, DxgiFormat::R8G8_UNorm)
        }
        CompressedFormat::Ktx2Uastc => super::ktx2_out::uastc(rgba, width, height, None),
        CompressedFormat::Ktx2UastcRdo => {
            super::ktx2_out::uastc(rgba, width, height, Some(super::compressed_format::UASTC_RDO_QUALITY))
        }
        CompressedFormat::Ktx2Etc1s => super::ktx2_out::etc1s(rgba, width, height),
    }
}

/// A legacy-header DDS file of BC3 `blocks` with the `DXT5` code and the pixel format flag
/// `DDPF_NORMAL` (`0x80000000`, byte 80 on) that marks DXT5nm.
fn dxt5nm(blocks: Vec<u8>, width: u32, height: u32) -> Result<Vec<u8>, String> {
    let params = ddsfile::NewD3dParams {
        height,
        width,
        depth: None,
        format: ddsfile::D3DFormat::DXT5,
        mipmap_levels: Some(1),
        caps2: None,
    };
    let mut dds = ddsfile::Dds::new_d3d(params).map_err(|e| format!("cannot make the DDS header: {e}"))?;
    dds.data = blocks;
    let mut bytes = Vec::new();
    dds.write(&mut bytes).map_err(|e| format!("cannot write the DDS file: {e}"))?;
    bytes[83] |= 0x80;
    Ok(bytes)
}
