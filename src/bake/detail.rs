//! `bake --detail`: the blended normals of a base and a detail normal map
//! (`crate::shading::detail_blend::blend_maps`) written as a 16-bit normal map PNG.

use std::path::Path;

use glam::Vec3;

use super::BakeError;
use crate::atomic::write_atomically;

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
