//! Normal-map mip filtering: every method draws plain shading at 1× (level 0), the
//! CPU twins equal the GPU at probe points at a distance, Toksvig's and vMF's variance
//! estimates against synthetic Gaussian slope fields of known variance.

mod common;

use bumpview::frame::SceneOptions;
use bumpview::names::Named;
use bumpview::render::capture::render_image;
use bumpview::scene::{ShadingModel, TextureImage, TextureKind};
use bumpview::shading::mip_filter::{toksvig_variance, vmf_variance};
use bumpview::texture::MipFilter;
use common::*;
use glam::Vec3;

const SIZE: [u32; 2] = [256, 256];

/// The materials' perceptual roughness under metallic-roughness: glossy enough for the
/// widening to show (the built-in materials' factor is 1, which nothing widens).
const ROUGHNESS: f32 = 0.3;

/// The built-in scene with every material's roughness [`ROUGHNESS`].
fn glossy_scene() -> bumpview::scene::Scene {
    let mut scene = scene();
    for material in &mut scene.materials {
        material.roughness = ROUGHNESS;
    }
    scene
}

/// The largest difference in 8-bit steps over the colour channels of two pictures.
fn max_steps(a: &image::RgbaImage, b: &image::RgbaImage) -> u8 {
    a.pixels().zip(b.pixels()).flat_map(|(p, q)| (0..3).map(move |c| p[c].abs_diff(q[c]))).max().unwrap_or(0)
}

/// At 0.3 m from the wall a pixel covers about 0.56 brick texels: the normal map is read at
/// level 0, where `|Na| = 1`, so Toksvig and vMF add nothing, base-only reads what the box
/// mips read and LEAN, magnified (`shading::mip_filter::lean_fade` is 0 below level 0), draws
/// the normal map's own texel with no variance (measured before that fade: 31 steps in
/// Blinn-Phong and 123 in metallic-roughness from the bilinear blend's covariance, 4 and 17
/// from the mean-slope normal alone). Each method's picture equals the re-normalised box mips' exactly (0 steps), in
/// Blinn-Phong and in metallic-roughness (every material's roughness [`ROUGHNESS`]); geometric
/// specular AA widens wherever the normal changes from pixel to pixel, at 1× too, so it is
/// measured, not held equal.
#[test]
fn every_method_but_geometric_aa_draws_plain_shading_at_one_to_one() {
    let scene = glossy_scene();
    let mut renderer = renderer_for(&scene);
    for model in [ShadingModel::BlinnPhong, ShadingModel::MetallicRoughness] {
        let mut params = close_wall_params(&scene, 0.3);
        params.shading.shading_override = Some(model);
        let plain = render_image(&mut renderer, SIZE, &params).unwrap();
        for &filter in MipFilter::all() {
            renderer.set_scene(&scene, SceneOptions { mip_filter: filter, ..Default::default() });
            let image = render_image(&mut renderer, SIZE, &params).unwrap();
            let steps = max_steps(&plain, &image);
            println!("{model:?}, {}: {steps} steps from the re-normalised box mips at 1×", filter.name());
            match filter {
                MipFilter::GeometricSpecularAa => assert!(steps > 0, "geometric AA widens at 1× too"),
                _ => assert_eq!(steps, 0, "{model:?}, {}", filter.name()),
            }
        }
        renderer.set_scene(&scene, SceneOptions::default());
    }
}

/// Farther away (3 m: a pixel covers about 5.6 texels, level ≈ 2.5) the CPU chain through the
/// probe equals the GPU for every method at a grid of probe points: lit within 3 steps of 8
/// bits (the tolerance of tests/probe.rs), shading normal within 2; and the widening methods
/// do change the picture there (LEAN at every point: its covariance is never exactly 0 there;
/// measured: lit within 0.82 steps in Blinn-Phong and 0.91 in metallic-roughness, normal 1.36,
/// the half floats rounded on the CPU as uploaded).
#[test]
fn the_cpu_twins_equal_the_gpu_at_probe_points_at_a_distance() {
    let scene = glossy_scene();
    for model in [ShadingModel::BlinnPhong, ShadingModel::MetallicRoughness] {
        let mut params = close_wall_params(&scene, 3.0);
        params.shading.shading_override = Some(model);
        for &filter in MipFilter::all() {
            let options = SceneOptions { mip_filter: filter, ..Default::default() };
            let readouts = gpu_against_probe(&scene, &options, &params, SIZE, 19, [3.0, 2.0]);
            let widened = readouts.iter().filter(|(_, r)| r.chain.mip.variance > 0.0).count();
            let lods: Vec<f32> = readouts.iter().filter_map(|(_, r)| r.chain.mip.lod).collect();
            let mean_lod = lods.iter().sum::<f32>() / lods.len().max(1) as f32;
            println!(
                "{model:?}, {}: {} points, {widened} widened, mean lod {mean_lod:.2}",
                filter.name(),
                readouts.len()
            );
            assert!(mean_lod > 1.5, "the wall is minified: lod {mean_lod}");
            assert!(readouts.iter().all(|(_, r)| r.chain.mip.filter == filter));
            if filter.widens() {
                assert!(widened * 2 > readouts.len(), "{}: {widened} of {}", filter.name(), readouts.len());
            } else {
                assert_eq!(widened, 0, "{}", filter.name());
            }
        }
    }
}

/// A deterministic standard normal sample stream (a 64-bit LCG through Box–Muller).
fn gaussians(seed: u64) -> impl Iterator<Item = f32> {
    let mut state = seed;
    let mut uniform = move || {
        state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        ((state >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    };
    std::iter::from_fn(move || {
        let (u, v) = (uniform(), uniform());
        Some(((-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()) as f32)
    })
}

/// A `side × side` RGB normal map whose slopes `∂h/∂x`, `∂h/∂y` are independent Gaussians of
/// standard deviation `sigma` (per axis): `n = normalize(−sx, −sy, 1)`, 8 bits per channel.
fn gaussian_slope_map(side: u32, sigma: f32, seed: u64) -> TextureImage {
    let mut g = gaussians(seed);
    let mut rgba = Vec::with_capacity((side * side * 4) as usize);
    for _ in 0..side * side {
        let (sx, sy) = (sigma * g.next().unwrap_or(0.0), sigma * g.next().unwrap_or(0.0));
        let n = Vec3::new(-sx, -sy, 1.0).normalize() * 0.5 + 0.5;
        rgba.extend(n.to_array().map(|c| (c * 255.0).round() as u8));
        rgba.push(255);
    }
    TextureImage::new("gaussian slopes", side, side, TextureKind::NormalMap, rgba)
}

/// Toksvig's `σ² = (1 − |Na|)/|Na|` estimates the per-axis slope variance of a Gaussian slope
/// field, `σ²_slope` (for small slopes `|Na| ≈ 1 − σ²_slope`), and vMF's `2/κ` the Beckmann
/// `α² = 2σ²_slope`: at the level whose texels cover 64 × 64 base texels (4096 slopes each),
/// averaged over its texels. Both run low as the slopes grow (`E[1/√(1 + s²)]` falls short of
/// `1 − σ²` by about `3σ⁴`): for σ = 0.05, 0.1, 0.2, 0.3 Toksvig within 2%, 4%, 8%, 15% and
/// vMF within 2%, 5%, 13%, 25% (measured: 0.1%, 1.8%, 6.6%, 13.2% and 0.3%, 3.2%, 11.4%,
/// 21.8% low, with these seeds). The 8-bit
/// alpha the mip chain uploads holds each texel's `|Na|` within half a step.
#[test]
fn toksvig_and_vmf_estimate_the_variance_of_gaussian_slope_fields() {
    let cases = [(0.05f32, 0.02, 0.02), (0.1, 0.04, 0.05), (0.2, 0.08, 0.13), (0.3, 0.15, 0.25)];
    for (i, (sigma, toksvig_tolerance, vmf_tolerance)) in cases.into_iter().enumerate() {
        let map = gaussian_slope_map(256, sigma, 7 + i as u64);
        let means = map.normal_means();
        let chain = map.mip_chain_filtered(MipFilter::Toksvig).unwrap();
        let level = 6;
        let (w, _, normals) = &means[level - 1]; // normal_means starts at level 1
        assert_eq!((*w, chain[level].width), (4, 4));
        let count = normals.len() as f32;
        let toksvig = normals.iter().map(|n| toksvig_variance(n.length())).sum::<f32>() / count;
        let vmf = normals.iter().map(|n| vmf_variance(n.length())).sum::<f32>() / count;
        let variance = sigma * sigma;
        let (toksvig_ratio, vmf_ratio) = (toksvig / variance, vmf / (2.0 * variance));
        println!("σ = {sigma}: Toksvig σ² / σ²_slope = {toksvig_ratio:.4}, vMF (2/κ) / (2σ²_slope) = {vmf_ratio:.4}");
        assert!((toksvig_ratio - 1.0).abs() < toksvig_tolerance, "σ = {sigma}: Toksvig {toksvig} vs {variance}");
        assert!((vmf_ratio - 1.0).abs() < vmf_tolerance, "σ = {sigma}: vMF {vmf} vs {}", 2.0 * variance);
        for (texel, n) in chain[level].rgba.chunks_exact(4).zip(normals) {
            assert!((texel[3] as f32 / 255.0 - n.length()).abs() <= 0.5 / 255.0 + 1e-6);
        }
    }
}

/// LEAN's covariance `M − B·Bᵀ` at every mip texel of a synthetic field (Gaussian slopes,
/// σ = 0.25, 64 × 64) equals the covariance of level 0's slopes over the block it covers,
/// computed directly in f64: the moments are linear, so box-averaged moments are the block's
/// moments. Equal to f32 rounding: within 1e-6 absolute (measured 3.3e-8; slopes of order
/// 0.25, variances 0.06).
#[test]
fn lean_covariance_equals_the_slope_covariance_of_the_base_level_at_every_mip() {
    use bumpview::texture::{decode_unit_normal, slopes};
    let map = gaussian_slope_map(64, 0.25, 3);
    let base: Vec<glam::DVec2> =
        map.rgba.chunks_exact(4).map(|t| slopes(decode_unit_normal([t[0], t[1], t[2]])).as_dvec2()).collect();
    let levels = map.lean_moments();
    assert_eq!(levels.len(), 7);
    let mut worst = 0.0f64;
    for (k, level) in levels.iter().enumerate() {
        let block = 1usize << k;
        for y in 0..level.height as usize {
            for x in 0..level.width as usize {
                let texels: Vec<glam::DVec2> =
                    (0..block * block).map(|i| base[(y * block + i / block) * 64 + x * block + i % block]).collect();
                let n = texels.len() as f64;
                let mean = texels.iter().copied().sum::<glam::DVec2>() / n;
                let d = |f: &dyn Fn(glam::DVec2) -> f64| texels.iter().map(|&b| f(b - mean)).sum::<f64>() / n;
                let direct = glam::DVec3::new(d(&|v| v.x * v.x), d(&|v| v.y * v.y), d(&|v| v.x * v.y));
                let lean = level.covariance(y * level.width as usize + x).as_dvec3();
                worst = worst.max((lean - direct).abs().max_element());
            }
        }
    }
    println!("LEAN covariance against the base level's: worst {worst:e}");
    assert!(worst < 1e-6, "{worst}");
}

/// No method but LEAN makes or uploads a texture of its own: the built-in scene uploads its
/// colour and normal maps (2 textures) under every method, each method's normal-map chain
/// replacing the box one (base-only: one level), and LEAN exactly one more, the moments of its
/// normal map. The methods that do not widen share the box pipelines; each
/// widening method builds its own lit variants (the two instance kinds: double-sided wall and
/// floor, single-sided torus), once.
#[test]
fn only_lean_uploads_a_texture_of_its_own_and_only_widening_builds_pipelines() {
    use bumpview::prepare::PreparedScene;
    let scene = scene();
    let params = default_params(&scene);
    let mut renderer = renderer_for(&scene);
    render_image(&mut renderer, [64, 48], &params).unwrap();
    let box_pipelines = renderer.counters().pipelines_built;
    for &filter in MipFilter::all() {
        let options = SceneOptions { mip_filter: filter, ..Default::default() };
        let mut fresh = renderer_for(&scene);
        fresh.set_scene(&scene, options.clone());
        render_image(&mut fresh, [64, 48], &params).unwrap();
        let counters = fresh.counters();
        // renderer_for uploads the default scene first: 2 textures, then 2 more with `options`,
        // and LEAN its texture of the moments of the one normal map.
        let own = if filter == MipFilter::Lean { 1 } else { 0 };
        assert_eq!(counters.textures_uploaded, 2 + 2 + own, "{}", filter.name());
        let expected = if filter.widens() { box_pipelines } else { 0 };
        renderer.set_scene(&scene, options.clone());
        let before = renderer.counters().pipelines_built;
        render_image(&mut renderer, [64, 48], &params).unwrap();
        assert_eq!(renderer.counters().pipelines_built - before, expected, "{}", filter.name());
        let prepared = PreparedScene::new(&scene, &options);
        let normal_map = scene.materials[0].normal_map.as_ref().map(|m| m.texture).unwrap_or(0);
        let levels = prepared.mip_chain(normal_map).unwrap().len();
        assert_eq!(levels == 1, filter == MipFilter::BaseOnly, "{}: {levels} levels", filter.name());
        // LEAN's texture: the full chain of its normal map, 8 bytes a texel (Rgba16Float).
        let lean = prepared.lean_texture(normal_map);
        assert_eq!(lean.is_some(), filter == MipFilter::Lean, "{}", filter.name());
        if let Some(lean) = lean {
            assert_eq!(lean.len(), levels);
            let bytes: u64 = lean.iter().map(|l| 8 * u64::from(l.width) * u64::from(l.height)).sum();
            let (w, h) = (lean[0].width, lean[0].height);
            println!("LEAN's texture of the {w}×{h} normal map: {} levels, {bytes} bytes", lean.len());
        }
        renderer.set_scene(&scene, SceneOptions::default());
    }
}

/// A material's own method wins over the scene's (the torus Toksvig, the rest vMF); a preset
/// keeps both and the split pair; the `mip-filter` split draws its two methods for every
/// material, over per-material choices.
#[test]
fn per_material_methods_win_and_presets_keep_them() {
    use bumpview::prepare::PreparedScene;
    use bumpview::scene::MaterialOverrides;
    use bumpview::state::preset::Preset;
    use bumpview::state::{Command, SplitDifference, ViewerState};
    let scene = scene();
    let torus = scene.instances.iter().find(|i| i.material != scene.instances[0].material).map(|i| i.material);
    let torus = torus.expect("two materials");
    let mut state = ViewerState::new(&scene);
    state.apply(Command::SetMipFilter(MipFilter::Vmf));
    let own = MaterialOverrides { mip_filter: Some(MipFilter::Toksvig), ..Default::default() };
    state.apply(Command::SetMaterialOverrides { material: Some(torus), overrides: own });
    state.apply(Command::SetSplitMipFilters([MipFilter::BaseOnly, MipFilter::GeometricSpecularAa]));
    let prepared = PreparedScene::new(&scene, &state.scene_options);
    for instance in &prepared.instances {
        let expected = if instance.material == torus { MipFilter::Toksvig } else { MipFilter::Vmf };
        assert_eq!(instance.mip_filter, expected, "material {}", instance.material);
    }
    let preset = Preset::from_toml(&Preset::from_state(&state, Default::default()).to_toml()).unwrap();
    assert_eq!(preset.to_state(&scene).unwrap(), state);
    state.apply(Command::SetSplit(true));
    state.apply(Command::SetSplitDifference(SplitDifference::MipFilter));
    let uploads = state.scene_uploads();
    let right = uploads.split_right.expect("a second upload");
    for (options, method) in [(&uploads.main, MipFilter::BaseOnly), (&right, MipFilter::GeometricSpecularAa)] {
        assert!(PreparedScene::new(&scene, options).instances.iter().all(|i| i.mip_filter == method));
    }
}
