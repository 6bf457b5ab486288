//! `bake --cone-map`: a height map's relaxed cone map ([`crate::height::cone`]) written as the
//! 8-bit grey PNG the viewer packs into the height texture's blue channel:
//! `⌊255 · √(ratio / MAX_CONE_RATIO)⌋`, white = the widest cone.

use std::path::Path;

use super::BakeError;
use crate::atomic::write_atomically;
use crate::height::HeightField;
use crate::height::cone::{decode_cone_ratio, encode_cone_ratio, relaxed_cone_ratios};

/// What a baked cone map holds: its narrowest and mean stored ratio (UV units per unit of
/// depth fraction) and the seconds its build took.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConeMapStats {
    pub narrowest: f32,
    pub mean: f32,
    pub build_s: f64,
}

/// Builds `field`'s relaxed cone map and writes it to `path` (grey, 8 bits), atomically.
pub fn write_cone_map(path: &Path, field: &HeightField) -> Result<ConeMapStats, BakeError> {
    let started = std::time::Instant::now();
    let stored: Vec<u8> = relaxed_cone_ratios(field).into_iter().map(encode_cone_ratio).collect();
    let build_s = started.elapsed().as_secs_f64();
    let ratios = stored.iter().map(|&b| decode_cone_ratio(f32::from(b) / 255.0));
    let narrowest = ratios.clone().fold(f32::INFINITY, f32::min);
    let mean = ratios.sum::<f32>() / stored.len().max(1) as f32;
    let image = image::GrayImage::from_raw(field.width, field.height, stored)
        .ok_or_else(|| BakeError::new(path, "the cone map does not fill the image"))?;
    write_atomically(path, |out| image.write_to(out, image::ImageFormat::Png).map_err(std::io::Error::other))
        .map_err(|e| BakeError::new(path, format!("cannot write: {e}")))?;
    Ok(ConeMapStats { narrowest, mean, build_s })
}
