//! CPU images with their colour space, and their mip chains (a normal map's by its
//! [`MipFilter`]).

mod basis;
mod blocks;
pub mod compressed;
mod dds;
pub mod decode;
mod ktx2;
mod lean;
mod mip_filter;
mod normal_mips;
mod stored;

pub use dds::dxgi_file;
pub use lean::{LeanLevel, LeanTexels, MIN_LEAN_NZ, half_bits, half_value, round_to_half, slopes};
pub use mip_filter::MipFilter;
pub use normal_mips::decode_unit_normal;

use std::collections::TryReserveError;

use glam::Vec3;

use crate::math::{linear_to_srgb, normalize_or, srgb_to_linear};

/// How a texture's values are to be read; decides its GPU format and how mips average.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum TextureKind {
    /// sRGB-encoded colour (base colour).
    Color,
    /// Tangent-space normal map, linear, `n = 2·rgb − 1`.
    NormalMap,
    /// Height in 0..1 with 16 bits: red holds the high byte, green the low byte, so
    /// `h = (256·255·r + 255·g) / 65535` for r, g in 0..1 — linear in r and g, so texture
    /// filtering of the two channels filters the height. See [`encode_height`].
    Height,
    /// Linear data, each channel on its own (metallic-roughness, occlusion, gloss).
    Data,
}

/// The red and green bytes of a height in 0..1 ([`TextureKind::Height`]).
pub fn encode_height(h: f32) -> [u8; 2] {
    let level = (h.clamp(0.0, 1.0) * 65535.0).round() as u16;
    level.to_be_bytes()
}

/// The height in 0..1 of red and green bytes ([`TextureKind::Height`]).
pub fn decode_height(high: u8, low: u8) -> f32 {
    u16::from_be_bytes([high, low]) as f32 / 65535.0
}

/// An RGBA8 image, rows top to bottom.
#[derive(Debug, Clone, PartialEq)]
pub struct TextureImage {
    pub name: String,
    pub width: u32,
    pub height: u32,
    pub kind: TextureKind,
    /// `width · height · 4` bytes.
    pub rgba: Vec<u8>,
    /// The file's own block levels (a DDS or KTX2 file's whole chain), whose level 0 decodes to
    /// `rgba`: drawn as they are where the adapter samples them and no mip filter makes levels
    /// of its own (`PreparedScene::file_blocks` decides). Whatever changes `rgba` sets it to
    /// `None`.
    pub file_blocks: Option<std::sync::Arc<compressed::FileBlocks>>,
}

impl TextureImage {
    /// A `width`×`height` image of `kind` holding `rgba` (`width · height · 4` bytes), not
    /// read from a file of blocks.
    pub fn new(name: impl Into<String>, width: u32, height: u32, kind: TextureKind, rgba: Vec<u8>) -> TextureImage {
        TextureImage { name: name.into(), width, height, kind, rgba, file_blocks: None }
    }

    /// RGBA bytes of texel `(x, y)`, coordinates wrapped into the image.
    pub fn texel(&self, x: i64, y: i64) -> [u8; 4] {
        let x = x.rem_euclid(self.width as i64) as usize;
        let y = y.rem_euclid(self.height as i64) as usize;
        let i = (y * self.width as usize + x) * 4;
        self.rgba[i..i + 4].try_into().expect("4 bytes")
    }

    /// The next mip level (half size, at least 1×1), by a 2×2 box filter: colour averaged
    /// in linear light, normals decoded, averaged and re-normalised, heights averaged.
    pub fn downsampled(&self) -> TextureImage {
        let (w, h) = ((self.width / 2).max(1), (self.height / 2).max(1));
        let mut rgba = Vec::with_capacity((w * h * 4) as usize);
        for y in 0..h as i64 {
            for x in 0..w as i64 {
                let texels = [(0, 0), (1, 0), (0, 1), (1, 1)].map(|(dx, dy)| {
                    let sx = (2 * x + dx).min(self.width as i64 - 1);
                    let sy = (2 * y + dy).min(self.height as i64 - 1);
                    self.texel(sx, sy)
                });
                let alpha = texels.iter().map(|t| t[3] as f32).sum::<f32>() / 4.0;
                let rgb = match self.kind {
                    TextureKind::Height => None,
                    TextureKind::Color => Some({
                        let mean = texels.iter().fold(Vec3::ZERO, |acc, t| {
                            acc + Vec3::new(t[0] as f32, t[1] as f32, t[2] as f32).map(|c| srgb_to_linear(c / 255.0))
                        }) / 4.0;
                        mean.map(linear_to_srgb)
                    }),
                    TextureKind::Data => Some(
                        texels.iter().fold(Vec3::ZERO, |acc, t| acc + Vec3::new(t[0] as f32, t[1] as f32, t[2] as f32))
                            / (4.0 * 255.0),
                    ),
                    TextureKind::NormalMap => Some({
                        let sum = texels.iter().fold(Vec3::ZERO, |acc, t| {
                            acc + Vec3::new(t[0] as f32, t[1] as f32, t[2] as f32) / 127.5 - 1.0
                        });
                        normalize_or(sum, Vec3::Z) * 0.5 + 0.5
                    }),
                };
                let rgb = match rgb {
                    Some(rgb) => rgb.to_array().map(|c| (c * 255.0).round() as u8),
                    None => {
                        let mean = texels.iter().map(|t| decode_height(t[0], t[1])).sum::<f32>() / 4.0;
                        let [high, low] = encode_height(mean);
                        [high, low, 0]
                    }
                };
                rgba.extend(rgb);
                rgba.push(alpha.round() as u8);
            }
        }
        TextureImage::new(self.name.clone(), w, h, self.kind, rgba)
    }

    /// This image followed by its mip levels down to 1×1; the system refusing the memory for
    /// level 0's copy (the texture's size, which comes from the input) is an error, not an
    /// abort.
    pub fn mip_chain(&self) -> Result<Vec<TextureImage>, TryReserveError> {
        let mut chain = vec![self.try_copy(|t| t)?];
        while let Some(last) = chain.last().filter(|t| t.width > 1 || t.height > 1) {
            chain.push(last.downsampled());
        }
        Ok(chain)
    }

    /// A copy of this image with each texel mapped by `texel`, its bytes reserved fallibly.
    pub fn try_copy(&self, texel: impl Fn([u8; 4]) -> [u8; 4]) -> Result<TextureImage, TryReserveError> {
        let mut rgba = Vec::new();
        rgba.try_reserve_exact(self.rgba.len())?;
        rgba.extend(self.rgba.chunks_exact(4).flat_map(|t| texel(t.try_into().expect("4 bytes"))));
        Ok(TextureImage::new(self.name.clone(), self.width, self.height, self.kind, rgba))
    }

    /// A 1×1 stand-in named `name` that draws as if the texture were absent: a flat normal, a
    /// height of 0, white colour and data.
    pub fn neutral(name: &str, kind: TextureKind) -> TextureImage {
        let texel = match kind {
            TextureKind::NormalMap => [128, 128, 255, 255],
            TextureKind::Height => [0, 0, 0, 255],
            TextureKind::Color | TextureKind::Data => [255; 4],
        };
        TextureImage::new(name.to_owned(), 1, 1, kind, texel.to_vec())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn heights_round_trip_sixteen_bits_and_average_in_mips() {
        for h in [0.0, 0.123_456, 0.5, 1.0] {
            let [high, low] = encode_height(h);
            assert!((decode_height(high, low) - h).abs() <= 0.5 / 65535.0);
        }
        let rgba = [0.2f32, 0.4, 0.6, 0.8]
            .iter()
            .flat_map(|&h| {
                let [a, b] = encode_height(h);
                [a, b, 0, 255]
            })
            .collect();
        let image = TextureImage::new("h", 2, 2, TextureKind::Height, rgba);
        let t = image.downsampled().texel(0, 0);
        assert!((decode_height(t[0], t[1]) - 0.5).abs() < 1e-4);
    }

    #[test]
    fn mip_chain_ends_at_one_texel_and_keeps_normals_unit() {
        let rgba = [[255, 128, 128, 255], [0, 128, 128, 255], [128, 255, 128, 255], [128, 128, 255, 255]].concat();
        let image = TextureImage::new("n", 2, 2, TextureKind::NormalMap, rgba);
        let chain = image.mip_chain().unwrap();
        assert_eq!(chain.len(), 2);
        let t = chain[1].texel(0, 0);
        let n = Vec3::new(t[0] as f32, t[1] as f32, t[2] as f32) / 127.5 - 1.0;
        assert!((n.length() - 1.0).abs() < 0.02, "{n}");
    }
}
