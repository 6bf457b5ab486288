//! The compression study: what each GPU texture format the bake writes
//! ([`CompressedFormat`]) does to a normal map. Each map makes the trip the `compression`
//! split draws ([`crate::bake::round_trip::round_trip`]: the bake's encoder, the loader's
//! decoder); the decoded texels are read as the renderer reads them
//! ([`crate::shading::decode_normal`]: z rebuilt for two-channel layouts) and compared with the
//! source texels read as RGB: the angle between the two normals, in degrees. The lit picture
//! (the built-in scene with the map as every material's normal map, its opening view) is
//! compared with the picture of the source map: RMSE of the 8-bit sRGB RGB values, 0–255.

use std::path::Path;

use glam::{DVec3, Vec4};

use crate::bake::compressed_format::CompressedFormat;
use crate::bake::round_trip::{round_trip, use_round_trip};
use crate::error::RenderError;
use crate::frame::{FrameParams, ShadingSettings};
use crate::render::Renderer;
use crate::scene::{NormalConvention, NormalLayout, NormalMap, Scene, TextureImage, TextureKind, stored_layout};
use crate::shading::{NormalTexel, decode_normal};

/// What the study measures.
#[derive(Debug, Clone, PartialEq)]
pub struct CompressionPlan {
    /// The side of the seeded noise map, texels.
    pub noise_side: u32,
    /// The brick map resized to this side (`None`: as the built-in scene makes it).
    pub brick_side: Option<u32>,
    /// The shared assets folder holding `textures/ambientCG_Rock058/normal.jpg` (`None`: the
    /// rock is left out).
    pub assets: Option<std::path::PathBuf>,
    /// The lit pictures' size, pixels.
    pub picture: [u32; 2],
}

impl CompressionPlan {
    /// The brick map as built, Rock058, a 512² noise map; 640×360 pictures.
    pub fn full(assets: Option<std::path::PathBuf>) -> CompressionPlan {
        CompressionPlan { noise_side: 512, brick_side: None, assets, picture: [640, 360] }
    }

    /// 64² brick and noise maps, no rock, 160×90 pictures (tests, CI).
    pub fn quick() -> CompressionPlan {
        CompressionPlan { noise_side: 64, brick_side: Some(64), assets: None, picture: [160, 90] }
    }
}

/// The seed of the noise map.
pub const NOISE_SEED: u64 = 0x6e6f_6973_655f_6d61;

/// The next of a SplitMix64 sequence, as a number in [−1, 1).
fn splitmix(state: &mut u64) -> f64 {
    *state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    (z ^ (z >> 31)) as f64 / 2f64.powi(63) - 1.0
}

/// A `side`² RGB normal map of independent texels: slopes `(gx, gy)` uniform in [−1, 1)²
/// (SplitMix64 from `seed`), normal `normalize(−gx, −gy, 1)`, each component stored as
/// `round((c + 1)/2 · 255)`. No texel tilts more than `atan(√2)` ≈ 54.74° (z ≥ 1/√3).
pub fn noise_normal_map(side: u32, seed: u64) -> TextureImage {
    let mut state = seed;
    let unorm = |c: f64| ((c + 1.0) * 0.5 * 255.0).round() as u8;
    let mut rgba = Vec::with_capacity(side as usize * side as usize * 4);
    for _ in 0..side as usize * side as usize {
        let (gx, gy) = (splitmix(&mut state), splitmix(&mut state));
        let n = DVec3::new(-gx, -gy, 1.0).normalize();
        rgba.extend([unorm(n.x), unorm(n.y), unorm(n.z), 255]);
    }
    TextureImage::new(format!("noise ({side}², seeded)"), side, side, TextureKind::NormalMap, rgba)
}

/// The unit normal texel `i` of `rgba` holds, read in `layout` (OpenGL green).
fn normal_at(rgba: &[u8], i: usize, layout: NormalLayout) -> DVec3 {
    let t = &rgba[i * 4..i * 4 + 4];
    let texel = NormalTexel {
        rgba: Vec4::from_array([t[0], t[1], t[2], t[3]].map(|c| f32::from(c) / 255.0)),
        correction: None,
    };
    decode_normal(texel, NormalConvention { layout, ..Default::default() }).as_dvec3()
}

/// Mean, 99th percentile and largest angle (degrees) between `source`'s normals (RGB) and
/// `decoded`'s read in `layout`.
pub fn angle_errors(source: &TextureImage, decoded: &[u8], layout: NormalLayout) -> [f64; 3] {
    let mut angles: Vec<f64> = (0..source.rgba.len() / 4)
        .map(|i| {
            super::detail_study::angle_deg(normal_at(&source.rgba, i, NormalLayout::Rgb), normal_at(decoded, i, layout))
        })
        .collect();
    angles.sort_by(f64::total_cmp);
    let n = angles.len().max(1);
    let p99 = angles.get(((n - 1) as f64 * 0.99).round() as usize).copied().unwrap_or(0.0);
    [angles.iter().sum::<f64>() / n as f64, p99, angles.last().copied().unwrap_or(0.0)]
}

/// The shortest and longest vector `2·rgb/255 − 1` of `map`'s texels and the mean of
/// `|1 − length|`: two-channel layouts take x and y as they are and rebuild z for length 1, so
/// a map whose vectors are not unit (a JPEG's) reads differently there even uncompressed.
pub fn stored_lengths(map: &TextureImage) -> [f64; 3] {
    let lengths = map
        .rgba
        .chunks_exact(4)
        .map(|t| DVec3::new(t[0].into(), t[1].into(), t[2].into()).map(|c: f64| c / 255.0 * 2.0 - 1.0).length());
    let (mut low, mut high, mut off, mut n) = (f64::MAX, 0.0f64, 0.0, 0.0);
    for length in lengths {
        (low, high, off, n) = (low.min(length), high.max(length), off + (1.0 - length).abs(), n + 1.0);
    }
    [low, high, off / f64::max(n, 1.0)]
}

/// What one format did to one map.
#[derive(Debug, Clone, PartialEq)]
pub struct Measured {
    /// Mean, p99 and largest angle to the source normal, degrees.
    pub angle_deg: [f64; 3],
    /// RMSE of the lit picture against the source map's (8-bit sRGB, 0–255); `None` without a GPU.
    pub lit_rmse: Option<f64>,
    /// Bits a texel takes on the GPU ([`CompressedFormat::gpu_bits_per_texel`]).
    pub gpu_bits: u32,
    /// Bits a texel takes in the file (header and supercompression included).
    pub file_bits: f64,
    /// Wall-clock milliseconds of one encode.
    pub encode_ms: f64,
}

/// One map through one format: measured, or why not.
#[derive(Debug, Clone, PartialEq)]
pub struct CompressionRow {
    pub map: String,
    pub format: CompressedFormat,
    pub outcome: Result<Measured, String>,
}

/// The study's maps: the built-in scene's brick map, Rock058's normal map (with the assets),
/// the noise map; and what was left out.
pub fn maps(plan: &CompressionPlan) -> (Vec<(String, TextureImage)>, Vec<String>) {
    let scene = crate::scene::builtin::teaching_scene();
    let index = scene.materials.iter().find_map(|m| m.normal_map.as_ref()).map(|m| m.texture);
    let mut brick = scene.textures[index.expect("the built-in scene has a normal map")].as_ref().clone();
    if let Some(side) = plan.brick_side {
        let full = image::RgbaImage::from_raw(brick.width, brick.height, brick.rgba).expect("w·h·4 bytes");
        brick.rgba = image::imageops::resize(&full, side, side, image::imageops::FilterType::Triangle).into_raw();
        (brick.width, brick.height) = (side, side);
    }
    let mut maps = vec![("bricks".to_owned(), brick)];
    let mut notes = vec![];
    match &plan.assets {
        Some(assets) => match rock(assets) {
            Ok(rock) => maps.push(("Rock058".to_owned(), rock)),
            Err(e) => notes.push(format!("Rock058 left out: {e}")),
        },
        None => notes.push("Rock058 left out: no shared assets given (--assets or BUMPVIEW_TEST_ASSETS)".to_owned()),
    }
    maps.push(("noise".to_owned(), noise_normal_map(plan.noise_side, NOISE_SEED)));
    (maps, notes)
}

fn rock(assets: &Path) -> Result<TextureImage, crate::error::LoadError> {
    let path = assets.join("textures/ambientCG_Rock058/normal.jpg");
    crate::load::image::load_texture(&path, TextureKind::NormalMap)
}

/// The built-in scene with `map` as every material's normal map, and the map's index.
pub fn scene_with(map: &TextureImage) -> (Scene, usize) {
    let mut scene = crate::scene::builtin::teaching_scene();
    scene.textures.push(std::sync::Arc::new(map.clone()));
    let texture = scene.textures.len() - 1;
    scene.materials.iter_mut().for_each(|m| m.normal_map = Some(NormalMap::new(texture, 1.0)));
    (scene, texture)
}

/// `scene` at its opening view (no light marker), `size` pixels.
pub fn picture(renderer: &mut Renderer, scene: &Scene, size: [u32; 2]) -> Result<image::RgbaImage, RenderError> {
    renderer.set_scene(scene, Default::default());
    let shading = ShadingSettings { show_light_marker: false, ..Default::default() };
    let params = FrameParams { camera: scene.default_camera, lights: scene.default_lights(), shading };
    crate::render::capture::render_image(renderer, size, &params)
}

/// Root mean square difference of two pictures' RGB bytes, 0–255.
pub fn rmse_255(a: &image::RgbaImage, b: &image::RgbaImage) -> f64 {
    let sum: f64 = a
        .pixels()
        .zip(b.pixels())
        .flat_map(|(p, q)| (0..3).map(move |c| (f64::from(p[c]) - f64::from(q[c])).powi(2)))
        .sum();
    (sum / (a.width() as f64 * a.height() as f64 * 3.0)).sqrt()
}

/// Every format on `map`; lit pictures with `renderer` (`None`: no GPU, no RMSE).
pub fn measure_map(
    name: &str,
    map: &TextureImage,
    mut renderer: Option<&mut Renderer>,
    size: [u32; 2],
) -> Result<Vec<CompressionRow>, RenderError> {
    let (scene, texture) = scene_with(map);
    let reference = match renderer.as_deref_mut() {
        Some(r) => Some(picture(r, &scene, size)?),
        None => None,
    };
    let texels = f64::from(map.width) * f64::from(map.height);
    let mut rows = vec![];
    for &format in <CompressedFormat as strum::VariantArray>::VARIANTS {
        let outcome = round_trip(&map.rgba, map.width, map.height, format);
        let outcome = match outcome {
            Err(e) => Err(e),
            Ok(done) => {
                let layout = done.stored.as_ref().and_then(stored_layout).unwrap_or(NormalLayout::Rgb);
                let angle_deg = angle_errors(map, &done.rgba, layout);
                let lit_rmse = match (renderer.as_deref_mut(), &reference) {
                    (Some(r), Some(reference)) => {
                        let mut through = scene.clone();
                        let made = TextureImage { rgba: done.rgba, file_blocks: None, ..map.clone() };
                        use_round_trip(&mut through, texture, made.into(), done.stored.as_ref());
                        Some(rmse_255(&picture(r, &through, size)?, reference))
                    }
                    _ => None,
                };
                let file_bits = done.file_bytes as f64 * 8.0 / texels;
                let gpu_bits = format.gpu_bits_per_texel();
                Ok(Measured { angle_deg, lit_rmse, gpu_bits, file_bits, encode_ms: done.encode_seconds * 1e3 })
            }
        };
        rows.push(CompressionRow { map: name.to_owned(), format, outcome });
    }
    Ok(rows)
}
