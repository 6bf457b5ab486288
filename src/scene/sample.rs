//! Textures read as the GPU's sampler reads them: wrap modes, bilinear filtering, and the
//! level of detail from a pixel's UV footprint between mip levels.

use glam::{Vec2, Vec3, Vec4};

use super::{SamplerWrap, TextureImage, TextureKind, Wrap};
use crate::math::srgb_to_linear;

/// Texture `chain` (mip levels, level 0 first) at `uv` as the GPU's sampler reads it (linear
/// filtering, linear between mip levels, no anisotropy): level of detail `log2` of the longer
/// of the footprint's derivatives in texels (`footprint`: d(uv)/dx and d(uv)/dy per pixel;
/// `None`: level 0), bilinear at level 0 when magnified, else between the two levels around it.
pub fn sample_trilinear(chain: &[TextureImage], uv: Vec2, wrap: SamplerWrap, footprint: Option<(Vec2, Vec2)>) -> Vec4 {
    let texels = Vec2::new(chain[0].width as f32, chain[0].height as f32);
    let lod = footprint.map_or(0.0, |(dx, dy)| (dx * texels).length().max((dy * texels).length()).log2());
    let lod = if lod.is_finite() { lod.clamp(0.0, (chain.len() - 1) as f32) } else { 0.0 };
    let level = lod.floor() as usize;
    let fine = sample_bilinear(&chain[level], uv, wrap);
    match chain.get(level + 1) {
        Some(coarse) if lod > level as f32 => fine.lerp(sample_bilinear(coarse, uv, wrap), lod - level as f32),
        _ => fine,
    }
}

/// Integer texel coordinate `i` of a `size`-texel axis under a wrap mode.
fn wrap_texel(i: i64, size: u32, wrap: Wrap) -> i64 {
    let n = size.max(1) as i64;
    match wrap {
        Wrap::Repeat => i.rem_euclid(n),
        Wrap::ClampToEdge => i.clamp(0, n - 1),
        Wrap::MirroredRepeat => {
            let m = i.rem_euclid(2 * n);
            if m < n { m } else { 2 * n - 1 - m }
        }
    }
}

/// The texel of mip level 0 that contains `uv` (nearest filtering), after wrapping.
pub fn nearest_texel(texture: &TextureImage, uv: Vec2, wrap: SamplerWrap) -> [u32; 2] {
    let x = (uv.x * texture.width as f32).floor() as i64;
    let y = (uv.y * texture.height as f32).floor() as i64;
    [wrap_texel(x, texture.width, wrap.u) as u32, wrap_texel(y, texture.height, wrap.v) as u32]
}

/// Bilinear sample of mip level 0 (RGBA, 0..1), as the GPU's linear magnification filter reads
/// it with the given wrap modes; sRGB colour texels are decoded to linear before filtering, as
/// through an sRGB texture view (alpha is linear).
pub fn sample_bilinear(texture: &TextureImage, uv: Vec2, wrap: SamplerWrap) -> Vec4 {
    let x = uv.x * texture.width as f32 - 0.5;
    let y = uv.y * texture.height as f32 - 0.5;
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let texel = |dx: i64, dy: i64| {
        let tx = wrap_texel(x0 as i64 + dx, texture.width, wrap.u);
        let ty = wrap_texel(y0 as i64 + dy, texture.height, wrap.v);
        let t = texture.texel(tx, ty);
        let rgb = Vec3::new(t[0] as f32, t[1] as f32, t[2] as f32) / 255.0;
        let rgb = match texture.kind {
            TextureKind::Color => rgb.map(srgb_to_linear),
            TextureKind::NormalMap | TextureKind::Height | TextureKind::Data => rgb,
        };
        rgb.extend(t[3] as f32 / 255.0)
    };
    let top = texel(0, 0).lerp(texel(1, 0), fx);
    let bottom = texel(0, 1).lerp(texel(1, 1), fx);
    top.lerp(bottom, fy)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrap_modes_fold_texel_indices() {
        assert_eq!([-1, 0, 4, 5].map(|i| wrap_texel(i, 4, Wrap::Repeat)), [3, 0, 0, 1]);
        assert_eq!([-1, 0, 4, 5].map(|i| wrap_texel(i, 4, Wrap::ClampToEdge)), [0, 0, 3, 3]);
        assert_eq!([-1, 0, 4, 5, 8].map(|i| wrap_texel(i, 4, Wrap::MirroredRepeat)), [0, 0, 3, 2, 0]);
    }
}
