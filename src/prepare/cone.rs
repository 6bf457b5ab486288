//! The prepare stage's branch for relaxed cone stepping ([`crate::frame::Parallax::RelaxedCone`]):
//! while a picture draws relaxed cones (`SceneOptions::cone_maps`), a height texture the parallax
//! family marches gets its relaxed cone map ([`crate::height::cone`]) in blue at level 0, where
//! the march reads it with the height in one sample; the other techniques never read blue.

use crate::height::cone::{encode_cone_ratio, relaxed_cone_ratios};
use crate::scene::{HeightMap, TextureImage};

/// `texture` (the height map of `slot`) with each texel's relaxed cone ratio in blue, over
/// the heights as the march reads them (a depth map flipped).
pub fn with_cone_map(texture: &TextureImage, slot: &HeightMap) -> TextureImage {
    let field = slot.height_field(texture, 1.0);
    let mut packed = texture.clone();
    for (texel, &ratio) in packed.rgba.chunks_exact_mut(4).zip(&relaxed_cone_ratios(&field)) {
        texel[2] = encode_cone_ratio(ratio);
    }
    packed
}
