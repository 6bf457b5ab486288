//! GPU texture containers (DDS, KTX2) decoded to RGBA8 on the CPU, and what their format says
//! about the channels ([`Stored`]): a BC5 or RG8 file holds two channels, a DXT5nm file x in
//! alpha and y in green. Only the top level is decoded (mips are made from it as for any
//! image); sizes from the header are admitted by the caller and checked against the file's
//! length before a texel is allocated.

use super::decode::Header;

/// What a texture file's own format says about how it stores channels.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Stored {
    /// The format and its container, e.g. `BC5 DDS`, `UASTC KTX2 (Zstandard)`.
    pub format: String,
    pub channels: StoredChannels,
}

/// The channels a format keeps, as far as a normal map is concerned.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StoredChannels {
    /// Two channels: x in red, y in green (BC5, R8G8, a two-channel Basis file).
    Rg,
    /// DXT5nm: x in alpha, y in green (a BC3 file flagged as a normal map).
    Ag,
    /// Three channels in a block format made for colour (BC1, BC2, BC3): a normal map there
    /// keeps z and loses precision in x and y.
    ColourBlock,
    /// Three or four channels in a block format of high quality (BC7, UASTC).
    Rgba,
    /// Uncompressed channels: what the texels hold.
    Plain,
}

impl Stored {
    /// Why a normal map in this format is read as it is, e.g. `BC5 DDS: two channels`.
    pub fn reason(&self) -> String {
        let what = match self.channels {
            StoredChannels::Rg => "two channels, x in red and y in green",
            StoredChannels::Ag => "DXT5nm, x in alpha and y in green",
            StoredChannels::ColourBlock => "three channels in a block format made for colour",
            StoredChannels::Rgba => "three or four channels in a high-quality block format",
            StoredChannels::Plain => "uncompressed channels",
        };
        format!("{}: {what}, decoded to RGBA8", self.format)
    }
}

/// A container's top level as RGBA8, rows top to bottom.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Decoded {
    pub width: u32,
    pub height: u32,
    /// `width · height · 4` bytes.
    pub rgba: Vec<u8>,
    pub stored: Stored,
}

/// The containers recognised by their first bytes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Container {
    Dds,
    Ktx2,
}

impl Container {
    /// The container `bytes` start with, if any.
    pub fn sniff(bytes: &[u8]) -> Option<Container> {
        if bytes.starts_with(b"DDS ") {
            Some(Container::Dds)
        } else if bytes.starts_with(&[0xAB, b'K', b'T', b'X', b' ', b'2', b'0', 0xBB]) {
            Some(Container::Ktx2)
        } else {
            None
        }
    }
}

/// Decodes a DDS or KTX2 file's top level once `admit` accepts its size (and its RGBA8 takes
/// at most `max_bytes`); the error is one line.
pub fn decode_container(
    container: Container,
    bytes: &[u8],
    max_bytes: u64,
    admit: impl FnOnce(&Header) -> Result<(), String>,
) -> Result<Decoded, String> {
    let admit_rgba = |width: u32, height: u32| -> Result<(), String> {
        let decoded_bytes = (width as u64 * height as u64).saturating_mul(4);
        admit(&Header { width, height, decoded_bytes, color: image::ColorType::Rgba8 })?;
        if decoded_bytes > max_bytes {
            let mib = decoded_bytes.div_ceil(1 << 20);
            return Err(format!(
                "{width}x{height} texels decode to {mib} MiB, over the {} MiB an image may take",
                max_bytes >> 20
            ));
        }
        Ok(())
    };
    match container {
        Container::Dds => super::dds::decode(bytes, admit_rgba),
        Container::Ktx2 => super::ktx2::decode(bytes, admit_rgba),
    }
}

/// `None` when the system refuses `width · height · 4` bytes, as one line.
pub(super) fn no_memory(width: u32, height: u32) -> String {
    format!("no memory for the {width}x{height} decoded texels")
}
