//! `bake --detail`: a base and a detail normal map (tangent space, OpenGL convention, RGB)
//! blended into one 16-bit normal map by a [`DetailBlend`] method — what artists bake
//! offline — with the formulas the shader runs ([`crate::shading::detail_blend`]).

use std::path::Path;

use glam::{Vec2, Vec3};

use super::BakeError;
use crate::atomic::write_atomically;
use crate::scene::sample::sample_bilinear;
use crate::scene::{DetailBlend, NormalConvention, SamplerWrap, TextureImage};
use crate::shading::detail_blend::blend;
use crate::shading::{NormalTexel, decode_normal, tangent_space_normal};

/// The blended normal at every texel of `base`: the detail map read bilinearly (wrapping) at
/// the texel centre's UV times `tiling`, scaled by `strength`, blended by `method`; unit
/// tangent-space vectors, row by row from the top.
pub fn blended_normals(
    base: &TextureImage,
    detail: &TextureImage,
    tiling: f32,
    strength: f32,
    method: DetailBlend,
) -> Vec<Vec3> {
    let convention = NormalConvention::default();
    let size = Vec2::new(base.width as f32, base.height as f32);
    let mut out = Vec::with_capacity((base.width * base.height) as usize);
    for y in 0..base.height {
        for x in 0..base.width {
            let texel = base.texel(i64::from(x), i64::from(y)).map(|c| f32::from(c) / 255.0);
            let b = decode_normal(NormalTexel::rgb(Vec3::new(texel[0], texel[1], texel[2])), convention);
            let uv = (Vec2::new(x as f32, y as f32) + 0.5) / size * tiling;
            let d_texel = sample_bilinear(detail, uv, SamplerWrap::default()).truncate();
            let d = tangent_space_normal(decode_normal(NormalTexel::rgb(d_texel), convention), strength);
            out.push(blend(method, tangent_space_normal(b, 1.0), d));
        }
    }
    out
}

/// Writes `normals` (`width` per row) as a 16-bit RGB PNG at `path`, `0.5·n + 0.5`, atomically.
pub fn write_normals_16(path: &Path, width: u32, normals: &[Vec3]) -> Result<(), BakeError> {
    let height = (normals.len() / width.max(1) as usize) as u32;
    let samples: Vec<u16> = normals
        .iter()
        .flat_map(|n| (*n * 0.5 + 0.5).to_array().map(|c| (c.clamp(0.0, 1.0) * 65535.0).round() as u16))
        .collect();
    let image = image::ImageBuffer::<image::Rgb<u16>, _>::from_raw(width, height, samples)
        .ok_or_else(|| BakeError::new(path, "the normals do not fill the image"))?;
    write_atomically(path, |out| image.write_to(out, image::ImageFormat::Png).map_err(std::io::Error::other))
        .map_err(|e| BakeError::new(path, format!("cannot write: {e}")))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::names::Named;

    /// A flat detail map leaves the base's normals as they are (every method but the linear
    /// mix, which halves the tilt), to the 8-bit base's decoding.
    #[test]
    fn a_flat_detail_map_gives_the_base_back() {
        let base = crate::scene::sine_pair_normal_map(16, 1, 0.8);
        let flat = TextureImage { rgba: [128, 128, 255, 255].repeat(4), width: 2, height: 2, ..base.clone() };
        for &method in DetailBlend::all().iter().filter(|&&m| m != DetailBlend::Linear) {
            let normals = blended_normals(&base, &flat, 3.0, 1.0, method);
            for (i, n) in normals.iter().enumerate() {
                let t = base.texel((i % 16) as i64, (i / 16) as i64).map(|c| f32::from(c) / 255.0);
                let b = Vec3::new(t[0], t[1], t[2]) * 2.0 - 1.0;
                assert!(n.angle_between(b.normalize()) < 0.01, "{}: texel {i}", method.name());
            }
        }
    }
}
