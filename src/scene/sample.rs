//! Textures read as the GPU's sampler reads them: wrap modes, bilinear filtering, and the
//! level of detail from a pixel's UV footprint between mip levels.

use glam::{Vec2, Vec3, Vec4};

use super::{SamplerWrap, TextureImage, TextureKind, Wrap};
use crate::math::srgb_to_linear;
use crate::texture::LeanTexels;

/// Texture `chain` (mip levels, level 0 first) at `uv` as the GPU's sampler reads it (linear
/// filtering, linear between mip levels, no anisotropy): level of detail `log2` of the longer
/// of the footprint's derivatives in texels (`footprint`: d(uv)/dx and d(uv)/dy per pixel;
/// `None`: level 0), bilinear at level 0 when magnified, else between the two levels around it.
pub fn sample_trilinear(chain: &[TextureImage], uv: Vec2, wrap: SamplerWrap, footprint: Option<(Vec2, Vec2)>) -> Vec4 {
    let size = Vec2::new(chain[0].width as f32, chain[0].height as f32);
    trilinear(size, chain.len(), footprint, |level| sample_bilinear(&chain[level], uv, wrap))
}

/// LEAN's texture (float levels, level 0 first) at `uv` as the GPU's sampler reads it: as
/// [`sample_trilinear`], with no decoding.
pub fn sample_trilinear_texels(
    chain: &[LeanTexels],
    uv: Vec2,
    wrap: SamplerWrap,
    footprint: Option<(Vec2, Vec2)>,
) -> Vec4 {
    let size = Vec2::new(chain[0].width as f32, chain[0].height as f32);
    trilinear(size, chain.len(), footprint, |level| {
        let texels = &chain[level];
        let width = texels.width;
        bilinear([width, texels.height], uv, wrap, |x, y| texels.texel((y * width + x) as usize))
    })
}

/// The trilinear blend of `levels` mip levels read by `sample` (a level's bilinear read), at
/// the level of detail of `footprint` on a level 0 of `size` texels.
fn trilinear(size: Vec2, levels: usize, footprint: Option<(Vec2, Vec2)>, sample: impl Fn(usize) -> Vec4) -> Vec4 {
    let lod = footprint.map_or(0.0, |(dx, dy)| (dx * size).length().max((dy * size).length()).log2());
    let lod = if lod.is_finite() { lod.clamp(0.0, (levels - 1) as f32) } else { 0.0 };
    let level = lod.floor() as usize;
    let fine = sample(level);
    if level + 1 < levels && lod > level as f32 { fine.lerp(sample(level + 1), lod - level as f32) } else { fine }
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
    bilinear([texture.width, texture.height], uv, wrap, |x, y| {
        let t = texture.texel(i64::from(x), i64::from(y));
        let rgb = Vec3::new(t[0] as f32, t[1] as f32, t[2] as f32) / 255.0;
        let rgb = match texture.kind {
            TextureKind::Color => rgb.map(srgb_to_linear),
            TextureKind::NormalMap | TextureKind::Height | TextureKind::Data => rgb,
        };
        rgb.extend(t[3] as f32 / 255.0)
    })
}

/// The bilinear blend at `uv` of the four texels `texel` gives (wrapped texel coordinates) on
/// a `width × height` level.
fn bilinear([width, height]: [u32; 2], uv: Vec2, wrap: SamplerWrap, texel: impl Fn(u32, u32) -> Vec4) -> Vec4 {
    let x = uv.x * width as f32 - 0.5;
    let y = uv.y * height as f32 - 0.5;
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let at = |dx: i64, dy: i64| {
        let tx = wrap_texel(x0 as i64 + dx, width, wrap.u);
        let ty = wrap_texel(y0 as i64 + dy, height, wrap.v);
        texel(tx as u32, ty as u32)
    };
    let top = at(0, 0).lerp(at(1, 0), fx);
    let bottom = at(0, 1).lerp(at(1, 1), fx);
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
