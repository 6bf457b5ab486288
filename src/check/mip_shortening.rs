//! How much a normal map's averaged normals shorten down its mip chain, and what that does to
//! the highlight a re-normalised chain draws.
//!
//! Level `k` of a box-filtered chain averages `2ᵏ × 2ᵏ` unit normals of level 0; the mean's
//! length `|Na|` falls below 1 where they disagree
//! ([`crate::texture::TextureImage::normal_means`]). A re-normalised chain throws `|Na|` away
//! and draws the level's highlight with the material's exponent `s`, as sharp as at level 0;
//! the lobe of the normals it stands for is wider, Toksvig's `s′ = |Na|·s / (|Na| + s·(1 − |Na|))`
//! ([`crate::shading::mip_filter::widened_shininess`]). The ratio `s′/s` says how much too
//! sharp (and, unnormalised, too bright for its size) the plain chain's highlight is there.

use crate::shading::mip_filter::{toksvig_variance, widened_shininess};
use crate::texture::{MipFilter, TextureImage};

/// The exponent the ratio is stated for when a material has none of its own to give: the
/// built-in materials' 32.
pub const REFERENCE_SHININESS: f32 = 32.0;
/// Warn where the Toksvig-equivalent exponent falls below this share of the material's: the
/// lobe's angular width goes as `1/√s`, so a re-normalised chain's highlight is then less than
/// half as wide as the bumps it averages make it (a factor of 2 in width, 4 in exponent).
pub const WARN_EXPONENT_RATIO: f32 = 0.25;
/// Levels smaller than this many texels a side are not warned about: the whole map seen in a
/// few pixels, where any method's highlight is a guess.
pub const WARN_MIN_SIDE: u32 = 8;

/// One mip level.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LevelShortening {
    pub level: u32,
    pub width: u32,
    pub height: u32,
    /// The mean over the level's texels of `|Na|`, the length of the mean of the unit
    /// normals of level 0 each one covers.
    pub mean_length: f32,
    /// Toksvig's `s′/s` at the mean length for the exponent asked for.
    pub exponent_ratio: f32,
}

/// Every level of `map`'s chain (level 0 first, down to 1×1) for exponent `shininess` (0 or
/// less: no highlight to sharpen, every ratio 1).
pub fn mip_shortening(map: &TextureImage, shininess: f32) -> Vec<LevelShortening> {
    // Level 0 from its bytes, one normal at a time; the means below from the chain.
    let base_length = map.base_normals().map(|n| n.length().min(1.0) as f64).sum::<f64>();
    let base = (map.width, map.height, base_length / (map.rgba.len() / 4).max(1) as f64);
    let below = map.normal_means().into_iter().map(|(width, height, means)| {
        let count = means.len().max(1) as f64;
        (width, height, means.iter().map(|m| m.length().min(1.0) as f64).sum::<f64>() / count)
    });
    std::iter::once(base)
        .chain(below)
        .enumerate()
        .map(|(level, (width, height, mean_length))| {
            let mean_length = mean_length as f32;
            let (widened, _) = widened_shininess(MipFilter::Toksvig, shininess, 2.0 * toksvig_variance(mean_length));
            // An exponent of 0 (a lobe as wide as it gets) cannot be widened: ratio 1.
            let exponent_ratio = if shininess > 0.0 { widened / shininess } else { 1.0 };
            LevelShortening { level: level as u32, width, height, mean_length, exponent_ratio }
        })
        .collect()
}

/// The first level of at least [`WARN_MIN_SIDE`] texels a side whose exponent ratio is below
/// [`WARN_EXPONENT_RATIO`].
pub fn first_over_sharp(levels: &[LevelShortening]) -> Option<LevelShortening> {
    levels.iter().find(|l| l.width.min(l.height) >= WARN_MIN_SIDE && l.exponent_ratio < WARN_EXPONENT_RATIO).copied()
}

#[cfg(test)]
mod tests {
    use glam::Vec3;

    use super::*;
    use crate::scene::TextureKind;

    /// A 64×64 map whose texels alternate, checkerwise, between two normals tilted ±θ about
    /// y: level 0 has |Na| = 1, every further level exactly cos θ (each 2×2 block holds two of
    /// each). Slope variance tan²θ along x, so Toksvig's σ² = (1 − cos θ)/cos θ.
    fn checker(theta: f32) -> TextureImage {
        let rgba = (0..64u32 * 64)
            .flat_map(|i| {
                let sign = if (i % 64 + i / 64) % 2 == 0 { 1.0 } else { -1.0 };
                let n = Vec3::new(sign * theta.sin(), 0.0, theta.cos());
                let [r, g, b] = (n * 0.5 + 0.5).to_array().map(|c| (c * 255.0).round() as u8);
                [r, g, b, 255]
            })
            .collect();
        TextureImage::new("checker", 64, 64, TextureKind::NormalMap, rgba)
    }

    #[test]
    fn averaged_normals_shorten_to_the_cosine_of_the_tilt() {
        let theta = 0.3f32;
        let levels = mip_shortening(&checker(theta), 32.0);
        assert_eq!(levels.len(), 7);
        assert!((levels[0].mean_length - 1.0).abs() < 1e-3 && (levels[0].exponent_ratio - 1.0).abs() < 0.05);
        // 8-bit texels: the decoded tilt is within half a step of θ.
        let cos = theta.cos();
        for l in &levels[1..] {
            assert!((l.mean_length - cos).abs() < 2e-3, "{l:?}");
            let s = 32.0 * cos / (cos + 32.0 * (1.0 - cos));
            assert!((l.exponent_ratio - s / 32.0).abs() < 0.01, "{l:?}");
        }
        // cos 0.3 = 0.955: s′ = 12.2 of 32 (0.38×), under the warning's 4×.
        assert_eq!(first_over_sharp(&levels), None);
        // cos 0.5 = 0.878: s′ = 5.9 of 32 (0.18×), warned from level 1 (32×32) on.
        let steep = mip_shortening(&checker(0.5), 32.0);
        assert!((steep[1].exponent_ratio - 0.183).abs() < 0.01, "{:?}", steep[1]);
        assert_eq!(first_over_sharp(&steep).map(|l| (l.level, l.width)), Some((1, 32)));
    }
}
