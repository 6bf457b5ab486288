//! LEAN mapping's moments of a normal map (Olano & Baker, "LEAN mapping", I3D 2010): per texel
//! the slopes `B = (nx/nz, ny/nz)` and their second moments `M = (Bx², By², Bx·By)`, box-filtered
//! down the mip chain. Both are linear in the texels, so a mip texel's moments are exactly the
//! means over the base texels it covers and `M − B·Bᵀ` is their covariance. Made in floats and
//! uploaded as `Rgba16Float` ([`LeanTexels`]: `(Bx, By, Bx², By²)`, 11 significant bits): in
//! 8 bits the cancellation in `M − B·Bᵀ` loses the variance (Olano & Baker scale `B` by a
//! per-map factor for that); in half floats a single slope's `Bx² − (Bx)²` is rounding noise
//! of a few `2⁻¹¹·Bx²`, which `shading::mip_filter::LEAN_HALF_FLOOR` takes off.

use glam::{Vec2, Vec3, Vec4};

use super::{TextureImage, decode_unit_normal};

/// The smallest `nz` a slope is taken at: steeper normals are read as 20:1 slopes (a normal
/// map's z is positive; at the horizon the slope is infinite).
pub const MIN_LEAN_NZ: f32 = 0.05;

/// One level of LEAN's moments, row by row.
#[derive(Debug, Clone, PartialEq)]
pub struct LeanLevel {
    pub width: u32,
    pub height: u32,
    /// Mean slopes `B = (nx/nz, ny/nz)` (tangent space, per unit of the surface).
    pub first: Vec<Vec2>,
    /// Mean second moments `(Bx², By², Bx·By)`.
    pub second: Vec<Vec3>,
}

impl LeanLevel {
    /// The slope covariance `M − B·Bᵀ` at texel `index`: `(σxx, σyy, σxy)`.
    pub fn covariance(&self, index: usize) -> Vec3 {
        let (b, m) = (self.first[index], self.second[index]);
        Vec3::new(m.x - b.x * b.x, m.y - b.y * b.y, m.z - b.x * b.y)
    }
}

/// The slopes of a unit tangent-space normal, `(nx/nz, ny/nz)` with `nz ≥` [`MIN_LEAN_NZ`].
pub fn slopes(n: Vec3) -> Vec2 {
    Vec2::new(n.x, n.y) / n.z.max(MIN_LEAN_NZ)
}

/// A base texel's moments: its slopes `B` and `(Bx², By², Bx·By)`.
fn texel_moments(t: &[u8]) -> (Vec2, Vec3) {
    let b = slopes(decode_unit_normal([t[0], t[1], t[2]]));
    (b, Vec3::new(b.x * b.x, b.y * b.y, b.x * b.y))
}

impl LeanLevel {
    /// The next level (half size, at least 1×1): each texel the mean of the 2×2 box it covers
    /// in a `width × height` level whose texel `i` has the moments `at(i)` (edge texels repeated
    /// on odd sizes, as [`TextureImage::downsampled`]).
    fn boxed(width: u32, height: u32, at: impl Fn(usize) -> (Vec2, Vec3)) -> LeanLevel {
        let (w, h) = (width as usize, height as usize);
        let (nw, nh) = ((w / 2).max(1), (h / 2).max(1));
        let (mut first, mut second) = (Vec::with_capacity(nw * nh), Vec::with_capacity(nw * nh));
        for y in 0..nh {
            for x in 0..nw {
                let corners = [(0, 0), (1, 0), (0, 1), (1, 1)]
                    .map(|(dx, dy)| at((2 * y + dy).min(h - 1) * w + (2 * x + dx).min(w - 1)));
                first.push(corners.iter().map(|c| c.0).sum::<Vec2>() / 4.0);
                second.push(corners.iter().map(|c| c.1).sum::<Vec3>() / 4.0);
            }
        }
        LeanLevel { width: nw as u32, height: nh as u32, first, second }
    }

    /// This level as uploaded: `(Bx, By, Bx², By²)` in half floats.
    pub fn texels(&self) -> LeanTexels {
        let bits = self.first.iter().zip(&self.second).map(|(b, m)| [b.x, b.y, m.x, m.y].map(half_bits));
        LeanTexels { width: self.width, height: self.height, bits: bits.collect() }
    }
}

impl TextureImage {
    /// LEAN's moments of this RGB normal map, level 0 first down to 1×1, by the same 2×2 boxes
    /// as [`TextureImage::downsampled`]: level 0 from the texels ([`texel_moments`]), each
    /// further level the box means of the one before, in f32.
    pub fn lean_moments(&self) -> Vec<LeanLevel> {
        let (first, second) = self.rgba.chunks_exact(4).map(texel_moments).unzip();
        let base = LeanLevel { width: self.width, height: self.height, first, second };
        std::iter::once(base).chain(self.lean_moments_below()).collect()
    }

    /// [`Self::lean_moments`] below level 0, made one level at a time: level 1 from the
    /// texels' bytes, so level 0's moments (20 bytes a texel) are never held.
    fn lean_moments_below(&self) -> impl Iterator<Item = LeanLevel> + '_ {
        let level_1 = (self.width > 1 || self.height > 1)
            .then(|| LeanLevel::boxed(self.width, self.height, |i| texel_moments(&self.rgba[4 * i..4 * i + 4])));
        std::iter::successors(level_1, |last| {
            (last.width > 1 || last.height > 1)
                .then(|| LeanLevel::boxed(last.width, last.height, |i| (last.first[i], last.second[i])))
        })
    }

    /// LEAN's texture of this RGB normal map as uploaded ([`LeanTexels`]), level 0 first down
    /// to 1×1: the moments of [`TextureImage::lean_moments`] in half floats, 8 bytes a texel,
    /// made with one level of f32 moments at a time.
    pub fn lean_texture(&self) -> Vec<LeanTexels> {
        let base = self.rgba.chunks_exact(4).map(|t| {
            let (b, m) = texel_moments(t);
            [b.x, b.y, m.x, m.y].map(half_bits)
        });
        let base = LeanTexels { width: self.width, height: self.height, bits: base.collect() };
        std::iter::once(base).chain(self.lean_moments_below().map(|level| level.texels())).collect()
    }
}

/// One level of LEAN's texture as the GPU gets it (`Rgba16Float`, 8 bytes a texel): per texel
/// `(Bx, By, Bx², By²)` as half floats ([`half_bits`]), row by row. `Bx·By` is left out: the
/// shader widens the highlight by the covariance's trace alone.
#[derive(Debug, Clone, PartialEq)]
pub struct LeanTexels {
    pub width: u32,
    pub height: u32,
    /// The half floats' bit patterns, RGBA (`Rgba16Float`'s texels).
    pub bits: Vec<[u16; 4]>,
}

impl LeanTexels {
    /// Texel `index`'s `(Bx, By, Bx², By²)` (the half floats' values).
    pub fn texel(&self, index: usize) -> Vec4 {
        Vec4::from_array(self.bits[index].map(half_value))
    }

    /// The texels as the texture's bytes (native endian).
    pub fn bytes(&self) -> &[u8] {
        bytemuck::cast_slice(&self.bits)
    }
}

/// The IEEE 754 half float nearest `x` (ties to even; beyond ±65504 infinite), bit for bit.
pub fn half_bits(x: f32) -> u16 {
    let bits = x.to_bits();
    let sign = ((bits >> 16) & 0x8000) as u16;
    let magnitude = bits & 0x7fff_ffff;
    if magnitude >= 0x7f80_0000 {
        return sign | if magnitude > 0x7f80_0000 { 0x7e00 } else { 0x7c00 };
    }
    let exponent = (magnitude >> 23) as i32 - 127;
    if exponent > 15 {
        return sign | 0x7c00;
    }
    if exponent >= -14 {
        let mantissa = magnitude & 0x7f_ffff;
        let truncated = (((exponent + 15) as u32) << 10) | (mantissa >> 13);
        let rest = mantissa & 0x1fff;
        let up = rest > 0x1000 || (rest == 0x1000 && truncated & 1 == 1);
        // A carry out of the mantissa steps the exponent (or reaches infinity), as it should.
        return sign | (truncated + u32::from(up)) as u16;
    }
    // Subnormal: a multiple of 2⁻²⁴ (1024 of them is the smallest normal, 0x0400).
    let multiples = (f64::from(f32::from_bits(magnitude)) * 16_777_216.0).round_ties_even() as u16;
    sign | multiples
}

/// The value of the half float with bits `bits`.
pub fn half_value(bits: u16) -> f32 {
    let sign = if bits & 0x8000 != 0 { -1.0 } else { 1.0 };
    let (exponent, mantissa) = (i32::from((bits >> 10) & 0x1f), f32::from(bits & 0x3ff));
    sign * match exponent {
        0 => mantissa * 2f32.powi(-24),
        31 if mantissa == 0.0 => f32::INFINITY,
        31 => f32::NAN,
        e => (1.0 + mantissa / 1024.0) * 2f32.powi(e - 15),
    }
}

/// `x` rounded to the nearest half float, as a `Rgba16Float` texture stores it.
pub fn round_to_half(x: f32) -> f32 {
    half_value(half_bits(x))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The uploaded texture, made one level at a time, is the full moments' chain in half
    /// floats bit for bit, on odd and one-texel-wide sizes too.
    #[test]
    fn the_texture_is_the_moments_in_half_floats() {
        for (width, height) in [(1, 1), (7, 5), (1, 6), (16, 16)] {
            let rgba = (0..width * height * 4).map(|i| (i * 37 % 251) as u8).collect();
            let kind = crate::texture::TextureKind::NormalMap;
            let image = TextureImage::new("n", width, height, kind, rgba);
            let from_moments: Vec<LeanTexels> = image.lean_moments().iter().map(LeanLevel::texels).collect();
            assert_eq!(image.lean_texture(), from_moments, "{width}×{height}");
        }
    }

    /// Known half floats, ties to even, the subnormals and the overflow.
    #[test]
    fn half_floats_round_to_nearest_even() {
        for (x, bits) in [(1.0f32, 0x3c00u16), (-2.0, 0xc000), (65504.0, 0x7bff), (0.1, 0x2e66), (1.0 / 3.0, 0x3555)] {
            assert_eq!(half_bits(x), bits, "{x}");
        }
        assert_eq!(half_bits(2f32.powi(-24)), 1);
        assert_eq!(half_bits(2f32.powi(-25)), 0, "a tie rounds to the even 0");
        assert_eq!(half_bits(1.0 + 2f32.powi(-11)), 0x3c00, "a tie rounds to the even mantissa");
        assert_eq!(half_bits(65520.0), 0x7c00);
        assert_eq!(half_bits(0.0), 0);
        for bits in [0x0001u16, 0x03ff, 0x0400, 0x3555, 0x7bff, 0xbc01] {
            assert_eq!(half_bits(half_value(bits)), bits);
        }
        assert_eq!(round_to_half(0.1), 0.099975586);
    }
}
