//! A texture's own block levels (a DDS or KTX2 file's, [`FileBlocks`]) as the chain it is
//! drawn with: where no mip filter makes levels of its own, the file's levels are the chain,
//! uploaded as blocks where the adapter samples them and decoded to RGBA8 for the CPU's twin
//! (the probe) and for adapters that cannot.

use super::PreparedScene;
use crate::scene::TextureImage;
use crate::texture::compressed::FileBlocks;

impl PreparedScene {
    /// Texture `index`'s file blocks and how many of their levels it is drawn with (1 for
    /// [`crate::texture::MipFilter::BaseOnly`], else all); `None` where it has none or a
    /// normal map's mip filter keeps `|Na|` in its levels' alpha (Toksvig, vMF).
    pub fn file_blocks(&self, index: usize) -> Option<(&FileBlocks, usize)> {
        let chain = self.scene.textures[index].file_blocks.as_deref()?;
        match self.normal_map_filter(index) {
            Some(filter) if filter.keeps_length() => None,
            Some(filter) if !filter.has_mips() => Some((chain, 1)),
            _ => Some((chain, chain.levels.len())),
        }
    }

    /// The levels of [`Self::file_blocks`] decoded to RGBA8 (`None`: the system refused the
    /// memory): level 0 is the texture's own texels.
    pub(super) fn file_mip_chain(&self, index: usize) -> Option<Option<Vec<TextureImage>>> {
        let (chain, levels) = self.file_blocks(index)?;
        let texture = &self.scene.textures[index];
        let level = |level: usize| {
            let [width, height] = chain.level_size(level);
            let rgba = chain.decoded_level(level)?;
            Some(TextureImage::new(texture.name.clone(), width, height, texture.kind, rgba))
        };
        Some((0..levels).map(level).collect())
    }
}
