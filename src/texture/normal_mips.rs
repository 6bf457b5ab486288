//! A normal map's mip chain by [`MipFilter`]: no mips, re-normalised box mips, or box mips that
//! keep the averaged normal's length `|Na|` in alpha (Toksvig, vMF). The means are taken in
//! floating point from level 0's unit normals, so level `k`'s `|Na|` is that of the whole
//! `2ᵏ × 2ᵏ` block (exactly, for power-of-two sizes), not of re-quantised levels.

use std::collections::TryReserveError;

use glam::Vec3;

use super::{MipFilter, TextureImage, TextureKind};
use crate::math::normalize_or;

/// Level 0's texel bytes `[r, g, b]` as the unit vector the shader decodes (`2·rgb − 1`,
/// normalised; +Z where it is degenerate).
pub fn decode_unit_normal(rgb: [u8; 3]) -> Vec3 {
    normalize_or(Vec3::from_array(rgb.map(|c| c as f32 / 255.0)) * 2.0 - 1.0, Vec3::Z)
}

impl TextureImage {
    /// The mip chain a normal map is uploaded with under `filter`: level 0 alone for
    /// [`MipFilter::BaseOnly`]; for [`MipFilter::keeps_length`] methods on an RGB normal map
    /// ([`TextureKind::NormalMap`]) level 0 with alpha 255 (`|Na| = 1`) and each further level
    /// the block's mean unit normal, its direction in RGB (re-normalised) and its length `|Na|`
    /// in alpha (`round(255·|Na|)`); else [`TextureImage::mip_chain`] (re-normalised box mips;
    /// packed layouts average channel by channel). LEAN's moments are textures of their own.
    pub fn mip_chain_filtered(&self, filter: MipFilter) -> Result<Vec<TextureImage>, TryReserveError> {
        if !filter.has_mips() {
            return Ok(vec![self.try_copy(|t| t)?]);
        }
        if !(filter.keeps_length() && self.kind == TextureKind::NormalMap) {
            return self.mip_chain();
        }
        let base = self.try_copy(|[r, g, b, _]| [r, g, b, 255])?;
        let below = self.normal_means().into_iter().map(|(width, height, normals)| {
            let rgba = normals
                .iter()
                .flat_map(|&mean| {
                    let rgb = normalize_or(mean, Vec3::Z) * 0.5 + 0.5;
                    let [r, g, b] = rgb.to_array().map(|c| (c * 255.0).round() as u8);
                    [r, g, b, (mean.length().min(1.0) * 255.0).round() as u8]
                })
                .collect();
            TextureImage::new(self.name.clone(), width, height, self.kind, rgba)
        });
        Ok(std::iter::once(base).chain(below).collect())
    }

    /// Level 0's unit normals ([`decode_unit_normal`]), row by row, read from the bytes as
    /// they are needed (12 bytes a texel would be three times the texture).
    pub fn base_normals(&self) -> impl Iterator<Item = Vec3> + '_ {
        self.rgba.chunks_exact(4).map(|t| decode_unit_normal([t[0], t[1], t[2]]))
    }

    /// Per mip level below level 0 (level 1 first, down to 1×1; none for a 1×1 image): its
    /// width, height and, row by row, the mean of level 0's unit normals
    /// ([`Self::base_normals`]) each texel covers, by the same 2×2 boxes (edge texels repeated
    /// on odd sizes) as [`TextureImage::downsampled`]. Its length is `|Na|`. Level 1 is made
    /// from level 0's bytes, so the chain takes 12 bytes per texel of level 1 and below (a
    /// third of level 0's texel count at most, 4 bytes per level-0 texel).
    pub fn normal_means(&self) -> Vec<(u32, u32, Vec<Vec3>)> {
        let (w, h) = (self.width as usize, self.height as usize);
        if w <= 1 && h <= 1 {
            return vec![];
        }
        let base = |x: usize, y: usize| {
            let i = (y.min(h - 1) * w + x.min(w - 1)) * 4;
            decode_unit_normal([self.rgba[i], self.rgba[i + 1], self.rgba[i + 2]])
        };
        let mut levels = vec![box_level(w, h, base)];
        while let Some((w, h, last)) = levels.last().filter(|(w, h, _)| *w > 1 || *h > 1) {
            let (w, h) = (*w as usize, *h as usize);
            let next = box_level(w, h, |x, y| last[y.min(h - 1) * w + x.min(w - 1)]);
            levels.push(next);
        }
        levels
    }
}

/// The level below a `w × h` level whose texel `(x, y)` (clamped by the caller) is `at(x, y)`:
/// each texel the mean of a 2×2 box.
fn box_level(w: usize, h: usize, at: impl Fn(usize, usize) -> Vec3) -> (u32, u32, Vec<Vec3>) {
    let (nw, nh) = ((w / 2).max(1), (h / 2).max(1));
    let next = (0..nh)
        .flat_map(|y| (0..nw).map(move |x| (x, y)))
        .map(|(x, y)| (at(2 * x, 2 * y) + at(2 * x + 1, 2 * y) + at(2 * x, 2 * y + 1) + at(2 * x + 1, 2 * y + 1)) / 4.0)
        .collect();
    (nw as u32, nh as u32, next)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two texels leaning ±45° about Y and two flat ones: level 1's mean is +Z with
    /// `|Na| = (2 + 2·cos 45°)/4`, stored in alpha; level 0 keeps its bytes with alpha 255.
    #[test]
    fn toksvig_mips_keep_the_mean_length_in_alpha() {
        let lean = |x: f32| {
            let v = Vec3::new(x, 0.0, 1.0).normalize() * 0.5 + 0.5;
            let [r, g, b] = v.to_array().map(|c| (c * 255.0).round() as u8);
            [r, g, b, 7]
        };
        let rgba = [lean(1.0), lean(-1.0), lean(0.0), lean(0.0)].concat();
        let image = TextureImage::new("n", 2, 2, TextureKind::NormalMap, rgba);
        let chain = image.mip_chain_filtered(MipFilter::Toksvig).unwrap();
        assert_eq!(chain.len(), 2);
        assert_eq!(chain[0].texel(0, 0), {
            let mut t = image.texel(0, 0);
            t[3] = 255;
            t
        });
        let means = image.normal_means();
        let expected = (2.0 + 2.0 * std::f32::consts::FRAC_1_SQRT_2) / 4.0;
        assert!((means[0].2[0].length() - expected).abs() < 4e-3, "{}", means[0].2[0]);
        assert_eq!(chain[1].texel(0, 0)[3], (means[0].2[0].length() * 255.0).round() as u8);
        assert_eq!(&chain[1].texel(0, 0)[..3], &[128, 128, 255]);
        assert_eq!(image.mip_chain_filtered(MipFilter::BaseOnly), Ok(vec![image.clone()]));
        assert_eq!(image.mip_chain_filtered(MipFilter::RenormalizedBox), image.mip_chain());
        let data = TextureImage { kind: TextureKind::Data, ..image.clone() };
        assert_eq!(data.mip_chain_filtered(MipFilter::Vmf), data.mip_chain());
    }
}
