//! What a GPU texture file's format says about its channels, and its decoded top level: the
//! types [`super::compressed`] hands out and its readers ([`super::dds`], [`super::ktx2`]) make.

use std::sync::Arc;

pub use super::blocks::Block;

/// What a texture file's own format says about how it stores channels.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Stored {
    /// The format and its container, e.g. `BC5 DDS`, `UASTC KTX2 (Zstandard)`.
    pub format: String,
    pub channels: StoredChannels,
    /// How its texels can reach the GPU.
    pub gpu: GpuTexels,
}

/// How a file's texels can reach the GPU.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum GpuTexels {
    /// The file's own blocks, every level: uploaded as they are where the adapter samples the
    /// format (`wgpu::Features::TEXTURE_COMPRESSION_BC`).
    Blocks(Arc<FileBlocks>),
    /// Decoded to RGBA8, for the reason given (e.g. `one level, the mips are made here`).
    Decoded(&'static str),
}

/// The size of mip level `level` of a `width`×`height` texture, texels (at least 1×1).
pub fn mip_size(width: u32, height: u32, level: usize) -> [u32; 2] {
    [(width >> level).max(1), (height >> level).max(1)]
}

/// A file's BC blocks for its whole mip chain, level 0 (`width`×`height`, both multiples of 4)
/// down to 1×1; each level whole blocks, rows of blocks top to bottom.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FileBlocks {
    pub block: Block,
    /// The file's own format where its blocks were transcoded to `block` (UASTC → BC7).
    pub transcoded_from: Option<&'static str>,
    pub width: u32,
    pub height: u32,
    /// One entry per level, exactly [`Block::level_bytes`] of that level's size.
    pub levels: Vec<Vec<u8>>,
}

impl FileBlocks {
    /// Levels a complete chain of a `width`×`height` texture has: `floor(log2(max side)) + 1`.
    pub fn chain_length(width: u32, height: u32) -> usize {
        (32 - width.max(height).max(1).leading_zeros()) as usize
    }

    /// The size of level `level`, texels.
    pub fn level_size(&self, level: usize) -> [u32; 2] {
        mip_size(self.width, self.height, level)
    }

    /// What the blocks are, e.g. `BC5 blocks`, `BC7 blocks transcoded from UASTC`.
    pub fn blocks_name(&self) -> String {
        match self.transcoded_from {
            Some(source) => format!("{} blocks transcoded from {source}", self.block.name()),
            None => format!("{} blocks", self.block.name()),
        }
    }

    /// Bytes of every level.
    pub fn bytes(&self) -> u64 {
        self.levels.iter().map(|l| l.len() as u64).sum()
    }

    /// Level `level` decoded to RGBA8 (`None`: no memory), as the GPU samples it.
    pub fn decoded_level(&self, level: usize) -> Option<Vec<u8>> {
        let [width, height] = self.level_size(level);
        super::blocks::decode_level(self.block, &self.levels[level], width, height)
    }

    /// The chain of `block` levels (transcoded from a format, where named) that `level_data(i)`
    /// gives for a `width`×`height` texture whose file holds `levels` levels; or why they are
    /// decoded instead: sides not multiples of 4, levels missing or short, BC4 (one channel,
    /// which the GPU samples as red alone and the loader reads as grey).
    pub fn gather<'a>(
        (block, transcoded_from): (Block, Option<&'static str>),
        width: u32,
        height: u32,
        levels: usize,
        mut level_data: impl FnMut(usize) -> Option<std::borrow::Cow<'a, [u8]>>,
    ) -> GpuTexels {
        if block == Block::Bc4 {
            return GpuTexels::Decoded("one channel, read as grey");
        }
        if !width.is_multiple_of(4) || !height.is_multiple_of(4) {
            return GpuTexels::Decoded("sides not multiples of 4");
        }
        let length = FileBlocks::chain_length(width, height);
        if levels < length {
            return GpuTexels::Decoded(if levels <= 1 {
                "one level, the mips are made here"
            } else {
                "an incomplete mip chain, the mips are made here"
            });
        }
        let mut chain = FileBlocks { block, transcoded_from, width, height, levels: Vec::with_capacity(length) };
        for level in 0..length {
            let [w, h] = chain.level_size(level);
            let needed = block.level_bytes(w, h) as usize;
            match level_data(level).filter(|data| data.len() >= needed) {
                Some(data) => chain.levels.push(data[..needed].to_vec()),
                None => return GpuTexels::Decoded("a mip level shorter than its size needs"),
            }
        }
        GpuTexels::Blocks(Arc::new(chain))
    }
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
        match &self.gpu {
            GpuTexels::Blocks(chain) => format!(
                "{}: {what}; {} levels of {}, uploaded as they are where the adapter samples BC",
                self.format,
                chain.levels.len(),
                chain.blocks_name()
            ),
            GpuTexels::Decoded(why) => format!("{}: {what}; decoded to RGBA8: {why}", self.format),
        }
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
