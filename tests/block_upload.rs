//! A DDS or KTX2 file's own BC blocks on the GPU (docs/compressed.md): a normal map with its
//! whole mip chain goes up as the file's blocks where the adapter samples BC (lavapipe does),
//! and draws what a device without BC draws from the same levels decoded on the CPU; the probe
//! reads those decoded levels. A file of one level is decoded and its mips made here; `check`
//! and the uploads say which.

mod common;

use std::path::{Path, PathBuf};

use bumpview::check::check_normal_maps;
use bumpview::load::{SceneFiles, replace_textures, texture_scene};
use bumpview::render::Renderer;
use bumpview::render::capture::render_image;
use bumpview::render::gpu::Gpu;
use bumpview::scene::Scene;
use common::*;

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/compressed").join(name)
}

/// The built-in scene with `normal` as every material's normal map, and that map's index.
fn with_normal_map(normal: &Path) -> (Scene, usize) {
    let mut scene = scene();
    let files = SceneFiles { normal: Some(normal.to_owned()), ..Default::default() };
    replace_textures(&mut scene, &files).unwrap_or_else(|e| panic!("{e}"));
    let index = scene.materials[0].normal_map.as_ref().unwrap().texture;
    (scene, index)
}

/// A renderer on a device that was not given BC sampling: the decoded levels go up as RGBA8.
fn renderer_without_bc(scene: &Scene) -> Renderer {
    let gpu =
        Gpu::headless().unwrap_or_else(|e| panic!("GPU tests need an adapter (install mesa-vulkan-drivers): {e}"));
    let descriptor = wgpu::DeviceDescriptor { required_limits: gpu.adapter.limits(), ..Default::default() };
    let (device, queue) = pollster::block_on(gpu.adapter.request_device(&descriptor)).unwrap();
    let mut renderer = Renderer::new(device, queue, gpu.adapter);
    renderer.set_scene(scene, Default::default());
    renderer
}

/// The largest difference of two pictures' channels (0..255), how many pixels differ, and the
/// root mean square difference of their RGB.
fn difference(a: &image::RgbaImage, b: &image::RgbaImage) -> (u8, usize, f64) {
    let channels = || a.pixels().zip(b.pixels()).map(|(p, q)| [0, 1, 2].map(|c| p[c].abs_diff(q[c])));
    let worst = channels().flatten().max().unwrap_or(0);
    let differing = channels().filter(|d| d.iter().any(|&d| d > 0)).count();
    let squares: f64 = channels().flatten().map(|d| f64::from(d).powi(2)).sum();
    (worst, differing, (squares / (a.width() * a.height() * 3) as f64).sqrt())
}

/// The fixture `name` (256², 9 levels) is drawn from its blocks (`form` on the GPU), the
/// probe reads its levels decoded, and a device without BC draws the same levels decoded
/// within `worst` steps and RMSE `bound`.
fn drawn_from_its_own_blocks(name: &str, form: &str, worst_bound: u8, rmse_bound: f64) {
    let (scene, index) = with_normal_map(&fixture(name));
    let chain = scene.textures[index].file_blocks.clone().expect("a complete chain of blocks");
    assert_eq!(chain.levels.len(), 9);
    let mut renderer = renderer_for(&scene);
    assert!(renderer.device().features().contains(wgpu::Features::TEXTURE_COMPRESSION_BC), "lavapipe samples BC");
    // Small, so the wall's far half samples levels 2-4, not only the top.
    let size = [320, 180];
    let params = default_params(&scene);
    let blocks = render_image(&mut renderer, size, &params).unwrap();
    let is_map = |u: &&bumpview::render::TextureUpload| u.name == scene.textures[index].name;
    let upload = renderer.texture_uploads(false).iter().find(is_map).unwrap().clone();
    assert_eq!((upload.form.as_str(), upload.bytes), (form, chain.bytes()));
    // The probe's chain is the file's levels decoded.
    let prepared = renderer.prepared(false).unwrap();
    let levels = prepared.mip_chain(index).unwrap();
    assert_eq!(levels.len(), chain.levels.len());
    for (level, image) in levels.iter().enumerate() {
        assert_eq!(image.rgba, chain.decoded_level(level).unwrap(), "level {level}");
    }

    let mut decoding = renderer_without_bc(&scene);
    let decoded = render_image(&mut decoding, size, &params).unwrap();
    let upload = decoding.texture_uploads(false).iter().find(is_map).unwrap().clone();
    let texels: u64 = levels.iter().map(|l| u64::from(l.width * l.height)).sum();
    assert_eq!((upload.form.as_str(), upload.bytes), ("RGBA8", 4 * texels));
    let (worst, differing, rmse) = difference(&blocks, &decoded);
    println!("{name}: against its levels decoded, {differing} pixels differ, by at most {worst}, RMSE {rmse:.3}");
    assert!(worst <= worst_bound && rmse <= rmse_bound, "{worst} steps, RMSE {rmse:.3} ({differing} pixels)");
}

/// BC5: the GPU interpolates the endpoints at more than 8 bits (as Direct3D specifies), the
/// CPU's decoder rounds each texel to 8 bits: half a step in x or y, a few in the lit picture.
#[test]
fn a_bc5_file_with_its_mip_chain_is_drawn_from_its_own_blocks() {
    drawn_from_its_own_blocks("brick_normal_bc5_mips.dds", "BC5 blocks as stored", 4, 0.3);
}

/// UASTC, transcoded level by level to BC7 blocks, which the GPU and `bcdec_rs` decode alike,
/// bit for bit.
#[test]
fn a_uastc_file_with_its_mip_chain_is_drawn_from_its_transcoded_blocks() {
    drawn_from_its_own_blocks("brick_normal_uastc_mips.ktx2", "BC7 blocks transcoded from UASTC", 0, 0.0);
}

#[test]
fn a_file_of_one_level_is_decoded_and_check_says_so() {
    let path = fixture("brick_normal_bc5.dds");
    let (scene, index) = with_normal_map(&path);
    assert!(scene.textures[index].file_blocks.is_none());
    let mut renderer = renderer_for(&scene);
    render_image(&mut renderer, [64, 36], &default_params(&scene)).unwrap();
    let name = &scene.textures[index].name;
    let upload = renderer.texture_uploads(false).iter().find(|u| &u.name == name).unwrap().clone();
    assert_eq!((upload.form.as_str(), upload.bytes), ("RGBA8", 4 * (256 * 256 * 4 - 1) / 3));
    let reason = |path: &Path| check_normal_maps(&texture_scene(path).unwrap())[0].layout_reason.clone();
    let one_level = reason(&path);
    assert!(one_level.ends_with("; decoded to RGBA8: one level, the mips are made here"), "{one_level}");
    let whole_chain = reason(&fixture("brick_normal_bc5_mips.dds"));
    let expected = "; 9 levels of BC5 blocks, uploaded as they are where the adapter samples BC";
    assert!(whole_chain.ends_with(expected), "{whole_chain}");
}
