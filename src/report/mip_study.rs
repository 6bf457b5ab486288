//! Normal maps at a distance: every mip filter's picture against a supersampled reference, on
//! the GPU ([`super::mip_specimen`] for the specimens).
//!
//! - **Reference**: [`MipFilter::BaseOnly`] (a normal map of one level, so the sampler reads
//!   level 0 bilinearly), drawn at `g` times the picture's size and box-filtered `g × g` in linear
//!   radiance (float target): `g × g` samples of the base level per pixel, `g` =
//!   [`MipPlan::supersample`] (16). Its convergence is measured at frame 0 against `g = 24`
//!   ([`Convergence`]).
//! - **Static error**: RMSE over the linear RGB channels of frame 0 against the reference's.
//! - **Specular energy ratio**: the mean of (picture − the same picture with the highlight
//!   off) over the reference's, at frame 0.
//! - **Shimmer**: the camera and light pan `1/8` pixel per frame along +x for
//!   [`MipPlan::frames`] frames; per pixel and channel, the standard deviation over time of
//!   (frame − reference frame), averaged.
//! - **Cost**: median GPU frame time ([`gpu_frame_ms`], 4× MSAA) at [`MipPlan::timing_size`],
//!   and the bytes of every texture level uploaded.
//!
//! Only pixels the surface covers fully in every reference frame count (no silhouette). Frames
//! are drawn with one sample per pixel, as the interactive viewer draws them.

use std::num::NonZeroU32;
use std::sync::Arc;

use strum::VariantArray;

use super::gpu_time::gpu_frame_ms;
use super::mip_specimen::{MipSpecimen, Shape};
use crate::error::RenderError;
use crate::frame::{FrameParams, Msaa, SceneOptions, ShadingSettings};
use crate::names::Named;
use crate::prepare::PreparedScene;
use crate::render::capture::{FLOAT_FORMAT, draw_offscreen};
use crate::render::{Background, DrawOptions, Renderer};
use crate::scene::SpecularMode;
use crate::texture::MipFilter;

/// Pan per frame, pixels.
pub const PAN_PX_PER_FRAME: f32 = 1.0 / 8.0;
/// A sample counts as covered at this alpha or above.
const COVERED_ALPHA: f32 = 0.999;

/// What the study measures.
#[derive(Debug, Clone, PartialEq)]
pub struct MipPlan {
    pub shapes: Vec<Shape>,
    /// Texels of level 0 per pixel along each side.
    pub minifications: Vec<u32>,
    /// Picture side, pixels.
    pub size: u32,
    /// Frames of the pan.
    pub frames: u32,
    /// Reference samples per pixel along each side.
    pub supersample: u32,
    /// Sample grids of the convergence check, compared with the largest.
    pub convergence: Vec<u32>,
    /// Picture side of the timed frames, pixels.
    pub timing_size: u32,
    pub timed_frames: NonZeroU32,
}

impl MipPlan {
    /// Plane and torus at 1×, 4×, 16× and 64×, 64-pixel pictures, 64 frames.
    pub fn full() -> MipPlan {
        MipPlan {
            shapes: vec![Shape::Plane, Shape::Torus],
            minifications: vec![1, 4, 16, 64],
            size: 64,
            frames: 64,
            supersample: 16,
            convergence: vec![8, 16, 24],
            timing_size: 512,
            timed_frames: NonZeroU32::new(5).expect("5"),
        }
    }

    /// 16× only, 32-pixel pictures, 16 frames.
    pub fn quick() -> MipPlan {
        MipPlan {
            minifications: vec![16],
            size: 32,
            frames: 16,
            timing_size: 128,
            timed_frames: NonZeroU32::new(1).expect("1"),
            ..MipPlan::full()
        }
    }
}

/// Linear RGB of a picture and which pixels the surface covers fully.
#[derive(Debug, Clone, PartialEq)]
pub struct Radiance {
    pub size: u32,
    pub rgb: Vec<[f32; 3]>,
    pub covered: Vec<bool>,
}

/// Draws `params` at `size × size` pixels into a float target (one sample, transparent
/// background: alpha is coverage) and box-filters `grid × grid` blocks.
pub fn radiance(renderer: &mut Renderer, size: u32, grid: u32, params: &FrameParams) -> Result<Radiance, RenderError> {
    let big = size * grid;
    let options = DrawOptions { background: Background::Transparent, msaa: Msaa::Off };
    let bytes = draw_offscreen(renderer, [big, big], FLOAT_FORMAT, |renderer, encoder, target| {
        renderer.draw(encoder, target, params, None, options)
    })?;
    let sample = |x: u32, y: u32| -> [f32; 4] {
        let at = ((y * big + x) * 16) as usize;
        std::array::from_fn(|c| f32::from_le_bytes(bytes[at + 4 * c..at + 4 * c + 4].try_into().expect("4 bytes")))
    };
    let count = (grid * grid) as f32;
    let mut rgb = Vec::with_capacity((size * size) as usize);
    let mut covered = Vec::with_capacity(rgb.capacity());
    for y in 0..size {
        for x in 0..size {
            let (mut sum, mut full) = ([0.0f32; 3], true);
            for dy in 0..grid {
                for dx in 0..grid {
                    let s = sample(x * grid + dx, y * grid + dy);
                    (0..3).for_each(|c| sum[c] += s[c]);
                    full &= s[3] >= COVERED_ALPHA;
                }
            }
            rgb.push(sum.map(|v| v / count));
            covered.push(full);
        }
    }
    Ok(Radiance { size, rgb, covered })
}

/// RMSE over the linear RGB channels of the pixels `mask` holds.
pub fn rmse(a: &Radiance, b: &Radiance, mask: &[bool]) -> f64 {
    let (mut squares, mut pixels) = (0.0f64, 0usize);
    for ((p, q), &m) in a.rgb.iter().zip(&b.rgb).zip(mask) {
        if m {
            squares += (0..3).map(|c| f64::from(p[c] - q[c]).powi(2)).sum::<f64>();
            pixels += 1;
        }
    }
    (squares / (3 * pixels.max(1)) as f64).sqrt()
}

/// Mean over the masked pixels of the RGB sum of `lit − unlit` (the highlight's radiance).
pub fn specular_energy(lit: &Radiance, unlit: &Radiance, mask: &[bool]) -> f64 {
    let (mut sum, mut pixels) = (0.0f64, 0usize);
    for ((p, q), &m) in lit.rgb.iter().zip(&unlit.rgb).zip(mask) {
        if m {
            sum += (0..3).map(|c| f64::from(p[c] - q[c])).sum::<f64>();
            pixels += 1;
        }
    }
    sum / pixels.max(1) as f64
}

/// Per pixel and channel, the standard deviation over the frames of (frame − reference);
/// the mean over the masked pixels' channels.
pub fn shimmer(frames: &[Radiance], references: &[Radiance], mask: &[bool]) -> f64 {
    let n = frames.len().min(references.len()).max(1) as f64;
    let (mut total, mut pixels) = (0.0f64, 0usize);
    for (index, _) in mask.iter().enumerate().filter(|(_, m)| **m) {
        for c in 0..3 {
            let (mut sum, mut squares) = (0.0f64, 0.0f64);
            for (frame, reference) in frames.iter().zip(references) {
                let d = f64::from(frame.rgb[index][c] - reference.rgb[index][c]);
                sum += d;
                squares += d * d;
            }
            let mean = sum / n;
            total += (squares / n - mean * mean).max(0.0).sqrt();
        }
        pixels += 1;
    }
    total / (3 * pixels.max(1)) as f64
}

/// How a method is drawn: the scene as prepared for it and its shading settings.
pub struct MethodSetup {
    pub name: &'static str,
    pub prepared: Arc<PreparedScene>,
    pub shading: ShadingSettings,
}

/// The scene prepared with `filter` for every material.
fn prepared(specimen: &MipSpecimen, filter: MipFilter) -> PreparedScene {
    PreparedScene::new(&specimen.scene, &SceneOptions { mip_filter: filter, ..Default::default() })
}

/// Bytes of every texture level `prepared` uploads (RGBA8 chains, and LEAN's half-float moments).
pub fn texture_bytes(prepared: &PreparedScene) -> u64 {
    (0..prepared.scene.textures.len())
        .filter(|&i| prepared.uses_texture(i))
        .map(|i| {
            let chain: u64 =
                prepared.mip_chain(i).iter().flat_map(|chain| chain.iter()).map(|level| level.rgba.len() as u64).sum();
            // LEAN's moments: `Rgba16Float`, 8 bytes a texel, made only where LEAN draws.
            let moments: u64 =
                prepared.lean_texture(i).unwrap_or_default().iter().map(|l| l.bytes().len() as u64).sum();
            chain + moments
        })
        .sum()
}

/// Every [`MipFilter`] the renderer draws as chosen on `specimen` (one that falls back to
/// another, [`crate::prepare::mip_filter_of`], is left out), in declaration order.
pub fn methods(specimen: &MipSpecimen) -> Vec<MethodSetup> {
    MipFilter::VARIANTS
        .iter()
        .map(|&filter| (filter, prepared(specimen, filter)))
        .filter(|(filter, prepared)| prepared.instances.iter().all(|i| i.mip_filter == *filter))
        .map(|(filter, prepared)| MethodSetup {
            name: filter.name(),
            prepared: Arc::new(prepared),
            shading: ShadingSettings::default(),
        })
        .collect()
}

/// One method at one specimen and minification.
#[derive(Debug, Clone, PartialEq)]
pub struct MipRow {
    pub shape: Shape,
    pub minification: u32,
    pub method: &'static str,
    /// RMSE of linear RGB against the reference at frame 0.
    pub rmse: f64,
    /// Mean specular radiance over the reference's.
    pub energy_ratio: f64,
    /// Mean per-pixel standard deviation over the pan of (frame − reference frame).
    pub shimmer: f64,
    /// Median GPU frame time, ms (`None`: no timestamp queries).
    pub frame_ms: Option<f64>,
    /// Bytes of the textures uploaded.
    pub texture_bytes: u64,
}

/// How far the reference is from converged, at frame 0: RMSE of each grid against the largest.
#[derive(Debug, Clone, PartialEq)]
pub struct Convergence {
    pub shape: Shape,
    pub minification: u32,
    /// `(grid, RMSE against the largest grid)`, the largest last with 0.
    pub rmse_by_grid: Vec<(u32, f64)>,
    /// Mean linear radiance of the reference (a scale for the RMSEs).
    pub mean_radiance: f64,
}

/// What the study measured.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct MipStudy {
    pub rows: Vec<MipRow>,
    pub convergence: Vec<Convergence>,
}

/// The shading of a method with the highlight off.
fn unlit(shading: ShadingSettings) -> ShadingSettings {
    ShadingSettings { specular: SpecularMode::Off, ..shading }
}

/// Measures `shape` at `minification`: the reference frames, its convergence, then each
/// method.
pub fn measure(
    renderer: &mut Renderer,
    plan: &MipPlan,
    shape: Shape,
    minification: u32,
) -> Result<(Vec<MipRow>, Convergence), RenderError> {
    let specimen = MipSpecimen::new(shape, minification, plan.size);
    let pan = |t: u32| t as f32 * PAN_PX_PER_FRAME;
    let shading = ShadingSettings::default();
    renderer.set_prepared(Arc::new(prepared(&specimen, MipFilter::BaseOnly)));
    let mut references = vec![];
    for t in 0..plan.frames {
        references.push(radiance(renderer, plan.size, plan.supersample, &specimen.params(pan(t), shading))?);
    }
    let mask: Vec<bool> = (0..references[0].covered.len()).map(|i| references.iter().all(|r| r.covered[i])).collect();
    let reference_unlit = radiance(renderer, plan.size, plan.supersample, &specimen.params(0.0, unlit(shading)))?;
    let reference_energy = specular_energy(&references[0], &reference_unlit, &mask);
    let largest = plan.convergence.iter().copied().max().unwrap_or(plan.supersample);
    let mut grids = vec![];
    for &grid in &plan.convergence {
        let picture = if grid == plan.supersample {
            references[0].clone()
        } else {
            radiance(renderer, plan.size, grid, &specimen.params(0.0, shading))?
        };
        grids.push((grid, picture));
    }
    let finest = grids.iter().find(|(g, _)| *g == largest).map(|(_, p)| p.clone()).unwrap_or(references[0].clone());
    let rmse_by_grid = grids.iter().map(|(g, p)| (*g, rmse(p, &finest, &mask))).collect();
    let covered = mask.iter().filter(|m| **m).count().max(1) as f64;
    let mean_radiance = references[0]
        .rgb
        .iter()
        .zip(&mask)
        .filter(|(_, m)| **m)
        .map(|(p, _)| p.iter().map(|&v| f64::from(v)).sum::<f64>() / 3.0)
        .sum::<f64>()
        / covered;
    let convergence = Convergence { shape, minification, rmse_by_grid, mean_radiance };
    let timed = MipSpecimen::new(shape, minification, plan.timing_size);
    let mut rows = vec![];
    for (method, timed_method) in methods(&specimen).into_iter().zip(methods(&timed)) {
        renderer.set_prepared(method.prepared.clone());
        let mut frames = vec![];
        for t in 0..plan.frames {
            frames.push(radiance(renderer, plan.size, 1, &specimen.params(pan(t), method.shading))?);
        }
        let frame_unlit = radiance(renderer, plan.size, 1, &specimen.params(0.0, unlit(method.shading)))?;
        renderer.set_prepared(timed_method.prepared.clone());
        let size = [plan.timing_size; 2];
        let frame_ms = gpu_frame_ms(renderer, &timed.params(0.0, method.shading), size, plan.timed_frames)?;
        rows.push(MipRow {
            shape,
            minification,
            method: method.name,
            rmse: rmse(&frames[0], &references[0], &mask),
            energy_ratio: specular_energy(&frames[0], &frame_unlit, &mask) / reference_energy.max(1e-12),
            shimmer: shimmer(&frames, &references, &mask),
            frame_ms,
            texture_bytes: texture_bytes(&method.prepared),
        });
    }
    Ok((rows, convergence))
}

/// Cases (specimens × minifications) [`study`] measures.
pub fn case_count(plan: &MipPlan) -> usize {
    plan.shapes.len() * plan.minifications.len()
}

/// Every specimen of `plan` at every minification on `renderer`; `step()` after each.
pub fn study(renderer: &mut Renderer, plan: &MipPlan, step: &mut dyn FnMut()) -> Result<MipStudy, RenderError> {
    let mut out = MipStudy::default();
    for &shape in &plan.shapes {
        for &minification in &plan.minifications {
            let (rows, convergence) = measure(renderer, plan, shape, minification)?;
            out.rows.extend(rows);
            out.convergence.push(convergence);
            step();
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn picture(values: &[f32]) -> Radiance {
        Radiance { size: 1, rgb: values.iter().map(|&v| [v; 3]).collect(), covered: vec![true; values.len()] }
    }

    /// A constant offset from the reference is static error, not shimmer; a frame-to-frame
    /// flicker of ±d is shimmer d.
    #[test]
    fn shimmer_is_the_spread_over_time_of_the_difference() {
        let references = vec![picture(&[0.5, 0.2]); 4];
        let offset: Vec<Radiance> = (0..4).map(|_| picture(&[0.6, 0.3])).collect();
        assert!(shimmer(&offset, &references, &[true, true]) < 1e-7);
        assert!((rmse(&offset[0], &references[0], &[true, true]) - 0.1).abs() < 1e-6);
        let flicker: Vec<Radiance> =
            (0..4).map(|t| picture(&[0.5 + if t % 2 == 0 { 0.05 } else { -0.05 }, 0.2])).collect();
        // Pixel 0 has spread 0.05, pixel 1 none; the second pixel is masked out.
        assert!((shimmer(&flicker, &references, &[true, false]) - 0.05).abs() < 1e-6);
        assert!((shimmer(&flicker, &references, &[true, true]) - 0.025).abs() < 1e-6);
    }

    #[test]
    fn specular_energy_is_the_mean_highlight() {
        let (lit, unlit) = (picture(&[0.5, 0.3]), picture(&[0.2, 0.2]));
        assert!((specular_energy(&lit, &unlit, &[true, true]) - 3.0 * 0.2).abs() < 1e-6);
    }
}
