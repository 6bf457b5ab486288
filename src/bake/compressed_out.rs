//! Writing RGBA8 images as GPU texture files (native builds only): DDS with BC1, BC3 (DXT5nm),
//! BC5 or BC7 blocks from Intel's ISPC texture compressor (`intel_tex_2`), and KTX2 with UASTC blocks from
//! Binomial's Basis Universal encoder (`basis-universal`), Zstandard-supercompressed
//! (`ruzstd`). One level each (viewers make the mips). Sides must be multiples of 4.

use ddsfile::{AlphaMode, D3D10ResourceDimension, Dds, DxgiFormat, NewDxgiParams};

/// A GPU texture file format the bake writes; named `dds-bc1`, `dds-dxt5nm`, `dds-bc5`,
/// `dds-bc7`, `ktx2-uastc` (`bake --format`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, strum::IntoStaticStr, strum::VariantArray)]
#[strum(serialize_all = "kebab-case")]
pub enum CompressedFormat {
    /// DDS, BC1 (DXT1): RGB in 4 bits a texel, the block format made for colour.
    DdsBc1,
    /// DDS, BC3 as DXT5nm: x in alpha, y in green (red 255, blue 0), flagged `DDPF_NORMAL`.
    DdsDxt5nm,
    /// DDS, BC5: red and green only (a two-channel normal map: x, y).
    DdsBc5,
    /// DDS, BC7 (RGBA).
    DdsBc7,
    /// KTX2, UASTC 4×4 (RGBA), Zstandard supercompression.
    Ktx2Uastc,
}

impl CompressedFormat {
    /// The file extension of the format's files.
    pub fn extension(self) -> &'static str {
        match self {
            CompressedFormat::Ktx2Uastc => "ktx2",
            _ => "dds",
        }
    }
}

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
            dds(intel_tex_2::bc1::compress_blocks(&surface), width, height, DxgiFormat::BC1_UNorm)
        }
        CompressedFormat::DdsDxt5nm => {
            let swizzled: Vec<u8> = rgba.chunks_exact(4).flat_map(|t| [255, t[1], 0, t[0]]).collect();
            let surface = intel_tex_2::RgbaSurface { data: &swizzled, width, height, stride: width * 4 };
            dxt5nm(intel_tex_2::bc3::compress_blocks(&surface), width, height)
        }
        CompressedFormat::DdsBc5 => {
            let rg: Vec<u8> = rgba.chunks_exact(4).flat_map(|t| [t[0], t[1]]).collect();
            let surface = intel_tex_2::RgSurface { data: &rg, width, height, stride: width * 2 };
            dds(intel_tex_2::bc5::compress_blocks(&surface), width, height, DxgiFormat::BC5_UNorm)
        }
        CompressedFormat::DdsBc7 => {
            let surface = intel_tex_2::RgbaSurface { data: rgba, width, height, stride: width * 4 };
            let settings = intel_tex_2::bc7::alpha_basic_settings();
            dds(intel_tex_2::bc7::compress_blocks(&settings, &surface), width, height, DxgiFormat::BC7_UNorm)
        }
        CompressedFormat::Ktx2Uastc => Ok(ktx2_uastc(&uastc_blocks(rgba, width, height)?, width, height)),
    }
}

/// A DDS file (with a `DX10` header) of one level of `blocks`.
fn dds(blocks: Vec<u8>, width: u32, height: u32, format: DxgiFormat) -> Result<Vec<u8>, String> {
    let params = NewDxgiParams {
        height,
        width,
        depth: None,
        format,
        mipmap_levels: Some(1),
        array_layers: None,
        caps2: None,
        is_cubemap: false,
        resource_dimension: D3D10ResourceDimension::Texture2D,
        alpha_mode: AlphaMode::Unknown,
    };
    let mut dds = Dds::new_dxgi(params).map_err(|e| format!("cannot make the DDS header: {e}"))?;
    dds.data = blocks;
    let mut bytes = Vec::new();
    dds.write(&mut bytes).map_err(|e| format!("cannot write the DDS file: {e}"))?;
    Ok(bytes)
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
    let mut dds = Dds::new_d3d(params).map_err(|e| format!("cannot make the DDS header: {e}"))?;
    dds.data = blocks;
    let mut bytes = Vec::new();
    dds.write(&mut bytes).map_err(|e| format!("cannot write the DDS file: {e}"))?;
    bytes[83] |= 0x80;
    Ok(bytes)
}

/// The UASTC blocks of `rgba`: Basis Universal's encoder writes a `.basis` file, whose one
/// slice is read back from its slice descriptor (offsets from the `.basis` format: the header's
/// slice descriptor offset at byte 65; a descriptor's data offset at 13 and size at 17).
fn uastc_blocks(rgba: &[u8], width: u32, height: u32) -> Result<Vec<u8>, String> {
    use basis_universal::{BasisTextureFormat, Compressor, CompressorParams, UASTC_QUALITY_DEFAULT};
    let mut params = CompressorParams::new();
    params.set_basis_format(BasisTextureFormat::UASTC4x4);
    params.set_uastc_quality_level(UASTC_QUALITY_DEFAULT);
    params.set_generate_mipmaps(false);
    params.set_color_space(basis_universal::ColorSpace::Linear);
    params.source_image_mut(0).init(rgba, width, height, 4);
    let mut compressor = Compressor::new(1);
    // SAFETY: `params` outlives `compressor.process()` (the crate's documented contract).
    let processed = unsafe { compressor.init(&params) && compressor.process().is_ok() };
    if !processed {
        return Err("the Basis Universal encoder failed".to_owned());
    }
    let file = compressor.basis_file();
    let word = |at: usize| file.get(at..at + 4).map(|b| u32::from_le_bytes(b.try_into().expect("4 bytes")) as usize);
    let slice = word(65).ok_or("the .basis file is truncated")?;
    let (offset, size) = (word(slice + 13), word(slice + 17));
    let blocks = offset.zip(size).and_then(|(o, s)| file.get(o..o + s)).ok_or("the .basis slice is out of range")?;
    let expected = width.div_ceil(4) as usize * height.div_ceil(4) as usize * 16;
    if blocks.len() != expected {
        return Err(format!("the .basis slice holds {} bytes, {expected} expected", blocks.len()));
    }
    Ok(blocks.to_vec())
}

/// A KTX2 file of one level of UASTC `blocks`, Zstandard-supercompressed, with a basic data
/// format descriptor (colour model UASTC, one RGBA sample, linear).
fn ktx2_uastc(blocks: &[u8], width: u32, height: u32) -> Vec<u8> {
    let packed = ruzstd::encoding::compress_to_vec(blocks, ruzstd::encoding::CompressionLevel::Fastest);
    const HEADER: u32 = 80;
    const LEVEL_INDEX: u32 = 24;
    const DFD: u32 = 4 + 24 + 16;
    let dfd_offset = HEADER + LEVEL_INDEX;
    let data_offset = dfd_offset + DFD;
    let mut out = Vec::new();
    out.extend([0xAB, b'K', b'T', b'X', b' ', b'2', b'0', 0xBB, b'\r', b'\n', 0x1A, b'\n']);
    // vkFormat (undefined), typeSize, width, height, depth, layers, faces, levels, Zstandard.
    for word in [0, 1, width, height, 0, 0, 1, 1, 2] {
        out.extend(word.to_le_bytes());
    }
    // DFD offset and length, key/value data offset and length; then supercompression global
    // data offset and length (none: 64-bit zeros).
    for word in [dfd_offset, DFD, 0, 0] {
        out.extend(word.to_le_bytes());
    }
    out.extend([0u8; 16]);
    for word in [data_offset as u64, packed.len() as u64, blocks.len() as u64] {
        out.extend(word.to_le_bytes());
    }
    out.extend(DFD.to_le_bytes());
    out.extend(0u32.to_le_bytes()); // vendor 0 (Khronos), descriptor type 0 (basic)
    out.extend(2u16.to_le_bytes()); // version
    out.extend((24u16 + 16).to_le_bytes()); // block size
    out.extend([166, 1, 1, 0]); // UASTC, BT.709 primaries, linear, straight alpha
    out.extend([3, 3, 0, 0]); // 4x4 texel blocks (dimension − 1)
    out.extend([16, 0, 0, 0, 0, 0, 0, 0]); // bytes per block
    out.extend(0u16.to_le_bytes()); // bit offset
    out.extend([127, 3]); // 128 bits, channel RGBA
    out.extend([0u8; 4]); // sample position
    out.extend(0u32.to_le_bytes());
    out.extend(u32::MAX.to_le_bytes());
    out.extend(packed);
    out
}
