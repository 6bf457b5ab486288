//! `bumpview bake --mips`: a normal map's mip chain as one PNG per level, each texel's
//! direction in RGB and, in alpha, what a mip-filter method derives from the length `|Na|`
//! of the mean of the level-0 unit normals it covers (a gloss factor, a roughness).
//!
//! The means are [`TextureImage::normal_means`]'s, the same 2×2 boxes as the renderer's
//! chains; the value in alpha is the caller's function of `|Na|` (the shading layer's
//! formulas, which this layer does not reach).

use std::path::{Path, PathBuf};

use glam::Vec3;

use super::BakeError;
use crate::atomic::write_atomically;
use crate::texture::TextureImage;

/// The levels of `map` (level 0 first, down to 1×1; only level 0 when `levels_past_0` is
/// false): RGB the re-normalised mean normal, alpha `round(255 · alpha(|Na|))` with `alpha`
/// clamped to 0..1.
pub fn mip_levels(map: &TextureImage, levels_past_0: bool, alpha: impl Fn(f32) -> f32) -> Vec<TextureImage> {
    let level = |width: u32, height: u32, normals: &mut dyn Iterator<Item = Vec3>| {
        let rgba = normals
            .flat_map(|mean| {
                let length = mean.length().min(1.0);
                let rgb = (mean.try_normalize().unwrap_or(Vec3::Z) * 0.5 + 0.5).to_array();
                let [r, g, b] = rgb.map(|c| (c * 255.0).round() as u8);
                [r, g, b, (alpha(length).clamp(0.0, 1.0) * 255.0).round() as u8]
            })
            .collect();
        TextureImage::new(map.name.clone(), width, height, map.kind, rgba)
    };
    let mut levels = vec![level(map.width, map.height, &mut map.base_normals())];
    if levels_past_0 {
        let below = map.normal_means().into_iter();
        levels.extend(below.map(|(width, height, normals)| level(width, height, &mut normals.into_iter())));
    }
    levels
}

/// The file of level `level` of `input` in `dir`: `<input stem>_mip<level>.png`.
pub fn level_path(dir: &Path, input: &Path, level: usize) -> PathBuf {
    let stem = input.file_stem().map_or("normal".into(), |s| s.to_string_lossy().into_owned());
    dir.join(format!("{stem}_mip{level}.png"))
}

/// Writes each of `levels` as an RGBA8 PNG at `paths` (atomically); returns what it wrote.
pub fn write_levels(levels: &[TextureImage], paths: &[PathBuf]) -> Result<(), BakeError> {
    for (level, path) in levels.iter().zip(paths) {
        let image = image::RgbaImage::from_raw(level.width, level.height, level.rgba.clone())
            .ok_or_else(|| BakeError::new(path, "a level's bytes do not fill its size"))?;
        write_atomically(path, |out| image.write_to(out, image::ImageFormat::Png).map_err(std::io::Error::other))
            .map_err(|e| BakeError::new(path, format!("cannot write: {e}")))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::TextureKind;

    /// Two texels tilted ±0.6 rad about y side by side, twice: level 1 is (0, 0, 1) with
    /// |Na| = cos 0.6 (to 8-bit steps) in alpha through the given function.
    #[test]
    fn levels_hold_the_mean_direction_and_the_function_of_its_length() {
        let tilt = |s: f32| {
            let n = Vec3::new(s * 0.6f32.sin(), 0.0, 0.6f32.cos()) * 0.5 + 0.5;
            let [r, g, b] = n.to_array().map(|c| (c * 255.0).round() as u8);
            [r, g, b, 255]
        };
        let rgba = [tilt(1.0), tilt(-1.0), tilt(-1.0), tilt(1.0)].concat();
        let map = TextureImage::new("n", 2, 2, TextureKind::NormalMap, rgba);
        let levels = mip_levels(&map, true, |length| length);
        assert_eq!(levels.len(), 2);
        assert_eq!(&levels[0].rgba[..3], &tilt(1.0)[..3]);
        assert_eq!(levels[0].rgba[3], 255);
        let t = levels[1].texel(0, 0);
        assert_eq!(&t[..3], &[128, 128, 255]);
        assert!((t[3] as f32 - 255.0 * 0.6f32.cos()).abs() <= 1.0, "{t:?}");
        assert_eq!(mip_levels(&map, false, |_| 2.0).iter().map(|l| l.rgba[3]).collect::<Vec<_>>(), [255]);
    }
}
