//! GPU texture containers (DDS, KTX2) decoded to RGBA8 on the CPU, and what their format says
//! about the channels ([`Stored`]): a BC5 or RG8 file holds two channels, a DXT5nm file x in
//! alpha and y in green. The top level is decoded; a whole chain of BC levels is kept as the
//! file's blocks ([`GpuTexels::Blocks`]) for the GPU to sample as they are, else the mips are
//! made from the top level as for any image. Sizes from the header are admitted by the caller
//! and checked against the file's length before a texel is allocated.

pub use super::stored::{Block, Decoded, FileBlocks, GpuTexels, Stored, StoredChannels};

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

/// Decodes a DDS or KTX2 file's top level once `admit(width, height)` accepts its size; the
/// error is one line.
pub fn decode_container(
    container: Container,
    bytes: &[u8],
    admit: impl FnOnce(u32, u32) -> Result<(), String>,
) -> Result<Decoded, String> {
    match container {
        Container::Dds => super::dds::decode(bytes, admit),
        Container::Ktx2 => super::ktx2::decode(bytes, admit),
    }
}
