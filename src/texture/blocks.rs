//! Texel layouts → RGBA8: BCn (S3TC / RGTC / BPTC) 4×4 blocks, and uncompressed texels read
//! through channel masks ([`decode_masked`]). Blocks are decoded on the CPU by `bcdec_rs` (a pure-Rust
//! port of bcdec; it builds for the browser too). DDS and KTX2 files hand their top level here.
//!
//! Channels of the decoded texels: BC1/BC2/BC3/BC7 as stored; BC4 grey (its one channel in red,
//! green and blue, alpha 255); BC5 red and green as stored, blue 0 and alpha 255 (a
//! two-channel normal map: x in red, y in green, z rebuilt when drawn).

/// A block-compressed format.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Block {
    /// DXT1: RGB with 1-bit alpha, 8 bytes a block.
    Bc1,
    /// DXT3: RGB with explicit 4-bit alpha.
    Bc2,
    /// DXT5: RGB with interpolated alpha (DXT5nm stores x in alpha, y in green).
    Bc3,
    /// One channel (RGTC1), 8 bytes a block.
    Bc4,
    /// Two channels (RGTC2): a normal map's x and y.
    Bc5,
    /// BPTC: RGBA of high quality.
    Bc7,
}

impl Block {
    /// Bytes of one 4×4 block.
    pub fn block_bytes(self) -> u64 {
        match self {
            Block::Bc1 | Block::Bc4 => 8,
            _ => 16,
        }
    }

    /// Its name, e.g. `BC5`.
    pub fn name(self) -> &'static str {
        match self {
            Block::Bc1 => "BC1",
            Block::Bc2 => "BC2",
            Block::Bc3 => "BC3",
            Block::Bc4 => "BC4",
            Block::Bc5 => "BC5",
            Block::Bc7 => "BC7",
        }
    }

    /// Bytes of a `width`×`height` level: whole blocks, rows of blocks top to bottom.
    pub fn level_bytes(self, width: u32, height: u32) -> u64 {
        width.div_ceil(4) as u64 * height.div_ceil(4) as u64 * self.block_bytes()
    }
}

/// How a level's texels are stored when no transcoder is needed: BCn blocks, or uncompressed
/// texels of 8 to 32 bits read through their red, green, blue and alpha masks (0: absent).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Texels {
    Blocks(Block),
    Masks { bits: u32, masks: [u32; 4] },
}

impl Texels {
    /// Bytes of a `width`×`height` level.
    pub fn level_bytes(self, width: u32, height: u32) -> u64 {
        match self {
            Texels::Blocks(block) => block.level_bytes(width, height),
            Texels::Masks { bits, .. } => (width as u64 * bits as u64).div_ceil(8) * height as u64,
        }
    }

    /// The `width`×`height` level in `data` as RGBA8 ([`decode_level`], [`decode_masked`]).
    pub fn decode(self, data: &[u8], width: u32, height: u32) -> Option<Vec<u8>> {
        match self {
            Texels::Blocks(block) => decode_level(block, data, width, height),
            Texels::Masks { bits, masks } => decode_masked(data, width, height, bits, masks),
        }
    }
}

/// Decodes the `width`×`height` level in `data` (at least [`Block::level_bytes`] bytes, else
/// `None`) into `rgba` (cleared; `width · height · 4` bytes reserved fallibly, `None` when the
/// system refuses them).
pub fn decode_level(block: Block, data: &[u8], width: u32, height: u32) -> Option<Vec<u8>> {
    let needed = usize::try_from(block.level_bytes(width, height)).ok()?;
    let data = data.get(..needed)?;
    let (w, h) = (width as usize, height as usize);
    let mut rgba = Vec::new();
    rgba.try_reserve_exact(w.checked_mul(h)?.checked_mul(4)?).ok()?;
    rgba.resize(w * h * 4, 0);
    let blocks_x = w.div_ceil(4);
    let size = block.block_bytes() as usize;
    let mut texels = [0u8; 64];
    for (index, bytes) in data.chunks_exact(size).enumerate() {
        let (bx, by) = (index % blocks_x * 4, index / blocks_x * 4);
        decode_block(block, bytes, &mut texels);
        for row in 0..4.min(h - by) {
            let columns = 4.min(w - bx);
            let at = ((by + row) * w + bx) * 4;
            rgba[at..at + columns * 4].copy_from_slice(&texels[row * 16..row * 16 + columns * 4]);
        }
    }
    Some(rgba)
}

/// One block's 16 texels as RGBA8, rows of 4.
fn decode_block(block: Block, bytes: &[u8], texels: &mut [u8; 64]) {
    match block {
        Block::Bc1 => bcdec_rs::bc1(bytes, texels, 16),
        Block::Bc2 => bcdec_rs::bc2(bytes, texels, 16),
        Block::Bc3 => bcdec_rs::bc3(bytes, texels, 16),
        Block::Bc7 => bcdec_rs::bc7(bytes, texels, 16),
        Block::Bc4 => {
            let mut grey = [0u8; 16];
            bcdec_rs::bc4(bytes, &mut grey, 4, false);
            for (texel, &v) in texels.chunks_exact_mut(4).zip(&grey) {
                texel.copy_from_slice(&[v, v, v, 255]);
            }
        }
        Block::Bc5 => {
            let mut rg = [0u8; 32];
            bcdec_rs::bc5(bytes, &mut rg, 8, false);
            for (texel, pair) in texels.chunks_exact_mut(4).zip(rg.chunks_exact(2)) {
                texel.copy_from_slice(&[pair[0], pair[1], 0, 255]);
            }
        }
    }
}

/// Texels of `bits` bits (little-endian) read through `masks` (red, green, blue, alpha), each
/// channel scaled to 0..255: a red-only layout is grey (red in red, green and blue), an absent
/// colour channel 0 and an absent alpha 255. `None`: too little data or no memory.
fn decode_masked(data: &[u8], width: u32, height: u32, bits: u32, masks: [u32; 4]) -> Option<Vec<u8>> {
    let texel_bytes = bits as usize / 8;
    let pitch = width as usize * texel_bytes;
    let data = data.get(..pitch.checked_mul(height as usize)?)?;
    let mut rgba = Vec::new();
    rgba.try_reserve_exact((width as usize).checked_mul(height as usize)?.checked_mul(4)?).ok()?;
    let grey = masks[1] == 0 && masks[2] == 0;
    for texel in data.chunks_exact(texel_bytes) {
        let mut word = [0u8; 4];
        word[..texel_bytes].copy_from_slice(texel);
        let value = u32::from_le_bytes(word);
        let [r, g, b, a] = masks.map(|mask| channel(value, mask));
        let r = r.unwrap_or(0);
        match grey {
            true => rgba.extend([r, r, r, a.unwrap_or(255)]),
            false => rgba.extend([r, g.unwrap_or(0), b.unwrap_or(0), a.unwrap_or(255)]),
        }
    }
    Some(rgba)
}

/// The bits of `value` under `mask` scaled to 0..255 (rounded); `None` for an empty mask.
fn channel(value: u32, mask: u32) -> Option<u8> {
    if mask == 0 {
        return None;
    }
    let shift = mask.trailing_zeros();
    let top = (mask >> shift) as u64;
    let bits = ((value & mask) >> shift) as u64;
    Some(((bits * 255 + top / 2) / top) as u8)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_bc5_block_of_two_constant_channels_decodes_to_them_and_short_data_is_refused() {
        // BC4 halves with endpoints (200, 200) and (60, 60): every texel takes endpoint 0.
        let block = [200, 200, 0, 0, 0, 0, 0, 0, 60, 60, 0, 0, 0, 0, 0, 0];
        let rgba = decode_level(Block::Bc5, &block, 3, 2).unwrap();
        assert_eq!(rgba.len(), 3 * 2 * 4);
        assert!(rgba.chunks_exact(4).all(|t| t == [200, 60, 0, 255]));
        assert!(decode_level(Block::Bc5, &block[..15], 3, 2).is_none());
        assert_eq!(Block::Bc1.level_bytes(5, 5), 4 * 8);
    }
}
