//! What a GPU texture file's format says about its channels, and its decoded top level: the
//! types [`super::compressed`] hands out and its readers ([`super::dds`], [`super::ktx2`]) make.

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

/// `None` when the system refuses `width · height · 4` bytes, as one line.
pub(super) fn no_memory(width: u32, height: u32) -> String {
    format!("no memory for the {width}x{height} decoded texels")
}
