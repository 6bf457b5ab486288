//! The GPU texture file formats the bake writes ([`CompressedFormat`]): named on every target
//! (the viewer's state and presets name them), written and read back on native builds only
//! ([`super::compressed_out`], [`super::round_trip`]).

/// A GPU texture file format the bake writes; named `dds-bc1`, `dds-dxt5nm`, `dds-bc5`,
/// `dds-bc7`, `dds-rg8`, `ktx2-uastc`, `ktx2-uastc-rdo`, `ktx2-etc1s` (`bake --format`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, strum::IntoStaticStr, strum::VariantArray)]
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
    /// DDS, uncompressed R8G8: x and y as they are, 16 bits a texel (z rebuilt when read).
    DdsRg8,
    /// KTX2, UASTC 4×4 (RGBA), Zstandard supercompression.
    Ktx2Uastc,
    /// KTX2, UASTC 4×4 after the encoder's rate-distortion optimisation (quality scalar
    /// [`UASTC_RDO_QUALITY`]), which trades error for blocks Zstandard packs smaller.
    Ktx2UastcRdo,
    /// KTX2, ETC1S (RGB) with BasisLZ supercompression.
    Ktx2Etc1s,
}

/// The UASTC rate-distortion quality scalar of [`CompressedFormat::Ktx2UastcRdo`] (Binomial's
/// default: lower keeps more quality, higher packs smaller).
pub const UASTC_RDO_QUALITY: f32 = 1.0;

impl CompressedFormat {
    /// The file extension of the format's files.
    pub fn extension(self) -> &'static str {
        match self {
            CompressedFormat::Ktx2Uastc | CompressedFormat::Ktx2UastcRdo | CompressedFormat::Ktx2Etc1s => "ktx2",
            _ => "dds",
        }
    }

    /// Bits a texel takes on the GPU once decoded from the file's supercompression: 4 for BC1
    /// and ETC1S, 8 for BC3, BC5, BC7 and UASTC, 16 for R8G8.
    pub fn gpu_bits_per_texel(self) -> u32 {
        match self {
            CompressedFormat::DdsBc1 | CompressedFormat::Ktx2Etc1s => 4,
            CompressedFormat::DdsRg8 => 16,
            _ => 8,
        }
    }
}
