//! Helpers shared by the GPU integration tests. They run on whatever adapter wgpu finds —
//! on CI Mesa's lavapipe, pinned by WGPU_BACKEND in .ci/run. A missing adapter fails the
//! test; it never skips.
#![allow(dead_code)] // each test binary uses a different subset

use std::path::{Path, PathBuf};

use bumpview::chain::legacy::vertex_vectors;
use bumpview::chain::{ChainValues, Footprint, Fragment, Map, Varyings, shade};
use bumpview::frame::BumpKind;
use bumpview::frame::{FrameParams, SceneOptions, ViewMode};
use bumpview::probe::{ProbeReadout, ProbeScene};
use bumpview::render::capture::render_image;
use bumpview::render::{Gpu, Renderer};
use bumpview::scene::builtin::{WALL_Z, teaching_scene, wall_uv};
use bumpview::scene::{Material, OrbitCamera, Scene, TextureImage};
use bumpview::state::ViewerState;
use glam::{Mat3, UVec2, Vec2, Vec3, Vec4};

pub fn renderer_for(scene: &Scene) -> Renderer {
    let gpu =
        Gpu::headless().unwrap_or_else(|e| panic!("GPU tests need an adapter (install mesa-vulkan-drivers): {e}"));
    let mut renderer = Renderer::from_gpu(&gpu);
    renderer.set_scene(scene, Default::default());
    renderer
}

/// The built-in scene's default picture without the light marker.
pub fn default_params(scene: &Scene) -> FrameParams {
    let mut state = ViewerState::new(scene);
    state.shading.show_light_marker = false;
    state.frame_params()
}

/// The camera distance at which `scene`'s bounding sphere fits the vertical field of view with
/// a tenth to spare: farther than a loaded scene's default framing (two thirds of the view's
/// height), for tests whose numbers were measured at that distance.
pub fn bounding_sphere_distance(scene: &Scene, camera: &OrbitCamera) -> f32 {
    let (lo, hi) = bumpview::load::bounds(scene).expect("the scene has finite vertices");
    1.1 * (hi - lo).length() * 0.5 / (camera.fov_y * 0.5).sin()
}

/// Looking straight at the wall from `distance` metres, centred on (0, 1.5): at 256 pixels
/// and 0.3 m one pixel covers about 0.56 brick texels, so sampling magnifies and reads mip 0.
pub fn close_wall_params(scene: &Scene, distance: f32) -> FrameParams {
    let mut params = default_params(scene);
    params.camera =
        OrbitCamera { target: Vec3::new(0.0, 1.5, WALL_Z), yaw: 0.0, pitch: 0.0, distance, ..params.camera };
    params.lights[0].position = Vec3::new(0.12, 1.62, WALL_Z + 0.35);
    params
}

pub fn scene() -> Scene {
    teaching_scene()
}

/// Where the ray through pixel `(x, y)`'s centre meets the plane `dot(n, p) = d`, if in front.
pub fn hit_plane(camera: &OrbitCamera, size: [u32; 2], x: u32, y: u32, n: Vec3, d: f32) -> Option<Vec3> {
    let (origin, dir) =
        camera.ray_through_pixel(Vec2::new(x as f32 + 0.5, y as f32 + 0.5), Vec2::new(size[0] as f32, size[1] as f32));
    let denom = n.dot(dir);
    if denom.abs() < 1e-6 {
        return None;
    }
    let t = (d - n.dot(origin)) / denom;
    (t > 0.0).then(|| origin + dir * t)
}

/// An 8-bit stored value as 0..1.
pub fn unit(byte: u8) -> f32 {
    byte as f32 / 255.0
}

/// A stored debug colour decoded back to the unit vector it shows.
pub fn decode_debug(pixel: &image::Rgba<u8>) -> Vec3 {
    (Vec3::new(unit(pixel[0]), unit(pixel[1]), unit(pixel[2])) * 2.0 - 1.0).normalize_or_zero()
}

/// The third-party models, textures and height maps the tests read: tests/fixtures in the
/// repository (its README names each file's source and licence). Never missing on a clone.
pub fn assets() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures")
}

/// A file under [`assets`]; a missing one fails the test, naming it.
pub fn asset(base: &Path, relative: &str) -> PathBuf {
    let path = base.join(relative);
    assert!(path.is_file(), "test fixture {} is missing (tests/fixtures/README.md lists them)", path.display());
    path
}

/// Bilinear sample of mip level 0 with repeat addressing, as the GPU's linear magnification
/// filter does; sRGB texels are decoded before filtering, as for an sRGB texture view
/// ([`bumpview::probe::sample_bilinear`]).
pub fn sample_bilinear(texture: &TextureImage, uv: Vec2) -> Vec3 {
    bumpview::probe::sample_bilinear(texture, uv, Default::default()).truncate()
}

/// The value at fraction `p` (0..1) of sorted values.
pub fn percentile(sorted: &[f32], p: f32) -> f32 {
    sorted[((sorted.len() - 1) as f32 * p).round() as usize]
}

/// The CPU shading chain ([`bumpview::chain::shade`]) on the wall at pixel `(x, y)` of a
/// `size` picture under `params`: the bricks' bilinear colour, gloss and normal-map texels,
/// the wall's frame T = +X, w = +1 (its MikkTSpace frame, tests/debug_views.rs).
pub fn wall_chain(scene: &Scene, params: &FrameParams, size: [u32; 2], x: u32, y: u32) -> ChainValues {
    let p = hit_plane(&params.camera, size, x, y, Vec3::Z, WALL_Z).expect("the wall fills the view");
    // The wall is flat and the light and eye vectors are only read by the legacy looks and
    // the per-vertex mistakes: the values at the point itself.
    let (vertex_light, vertex_half) = vertex_vectors(p, Vec3::Z, params.lights.first_on(), params.camera.eye());
    let at = Varyings {
        position: p,
        world_normal: Vec3::Z,
        uv: wall_uv(p),
        world_tangent: Some(Vec4::new(1.0, 0.0, 0.0, 1.0)),
        vertex_light,
        vertex_half,
    };
    let material = &scene.materials[0];
    shade(BumpKind::TangentSpace, material, &WallPoint { at, scene, material }, params)
}

/// A point of the wall as [`wall_chain`] reads it: a front face, no pixel grid (no
/// derivatives: no parallax, the point's own frame for tangent-space lighting), the base
/// colour, normal map (RGB, alpha 1) and gloss bilinear at mip 0 with repeat addressing.
struct WallPoint<'a> {
    at: Varyings,
    scene: &'a Scene,
    material: &'a Material,
}

impl Fragment for WallPoint<'_> {
    fn varyings(&self) -> Varyings {
        self.at
    }

    fn front_facing(&self) -> bool {
        true
    }

    fn normal_matrix(&self) -> Mat3 {
        Mat3::IDENTITY
    }

    fn derivatives<T: std::ops::Sub<Output = T> + Copy>(&self, _: impl Fn(&Varyings) -> T) -> Option<(T, T)> {
        None
    }

    fn sample(&self, map: Map, uv: Vec2, _: Footprint) -> Option<Vec4> {
        let texture = match map {
            Map::BaseColor => self.material.base_color_texture,
            Map::Bump => self.material.normal_map.as_ref().map(|m| m.texture),
            Map::Gloss => self.material.gloss_texture,
            _ => None,
        };
        texture.map(|t| sample_bilinear(&self.scene.textures[t], uv).extend(1.0))
    }

    fn size(&self, _: Map) -> Option<UVec2> {
        None
    }
}

/// A loaded scene is sane: per mesh, every position, normal, UV and supplied tangent finite,
/// one normal per position, UVs and tangents absent or one per position (tangents are used as
/// given, so their `w` is only read for its sign), whole triangles with indices in range; instances name meshes and materials that exist,
/// materials name textures that exist, and each texture holds its `width · height` texels.
pub fn assert_sane(scene: &Scene, what: &str) {
    for mesh in &scene.meshes {
        let name = format!("{what}: mesh {:?}", mesh.name);
        let n = mesh.positions.len();
        assert!(
            mesh.positions.iter().chain(&mesh.normals).all(|v| v.is_finite()),
            "{name}: non-finite position or normal"
        );
        assert!(mesh.uvs.iter().all(|v| v.is_finite()), "{name}: non-finite UV");
        assert_eq!(mesh.normals.len(), n, "{name}: one normal per position");
        assert!(mesh.uvs.is_empty() || mesh.uvs.len() == n, "{name}: {} UVs for {n} positions", mesh.uvs.len());
        if let Some(tangents) = &mesh.tangents {
            assert_eq!(tangents.len(), n, "{name}: one tangent per position");
            assert!(tangents.iter().all(|t| t.is_finite()), "{name}: a non-finite tangent");
        }
        assert!(mesh.indices.len() % 3 == 0, "{name}: {} indices", mesh.indices.len());
        assert!(mesh.indices.iter().all(|&i| (i as usize) < n), "{name}: index out of range");
    }
    for instance in &scene.instances {
        assert!(
            instance.mesh < scene.meshes.len() && instance.material < scene.materials.len(),
            "{what}: {instance:?}"
        );
        assert!(instance.transform.is_finite(), "{what}: non-finite transform");
    }
    for material in &scene.materials {
        let slots = [material.base_color_texture, material.gloss_texture, material.metallic_roughness_texture]
            .into_iter()
            .chain([material.normal_map.as_ref().map(|m| m.texture), material.height_map.as_ref().map(|m| m.texture)])
            .chain([material.occlusion.as_ref().map(|o| o.texture)]);
        for texture in slots.flatten() {
            assert!(texture < scene.textures.len(), "{what}: material {:?} names texture {texture}", material.name);
        }
    }
    for texture in &scene.textures {
        assert_eq!(
            texture.rgba.len(),
            (texture.width * texture.height * 4) as usize,
            "{what}: texture {:?}",
            texture.name
        );
    }
}

/// The probe's readouts (with their pixels) on a grid of pixels (every `step`, from (4, 4)) of
/// a `size` picture of `scene` prepared with `options`, after checking that the GPU's lit and shading-normal
/// pictures equal them within `tolerance` steps of 8 bits (lit, shading normal). Pixels whose
/// neighbours see another instance or nothing are left out (silhouettes blend two surfaces).
pub fn gpu_against_probe(
    scene: &Scene,
    options: &SceneOptions,
    params: &FrameParams,
    size: [u32; 2],
    step: usize,
    tolerance: [f32; 2],
) -> Vec<([u32; 2], ProbeReadout)> {
    gpu_against_probe_of(scene, options, params, size, step, tolerance, |_| ProbeScene::new(scene, options))
}

/// [`gpu_against_probe`] with the probe `probe_of` makes from the renderer once it has drawn
/// the pictures (the scene it drew, for geometry made while drawing).
pub fn gpu_against_probe_of(
    scene: &Scene,
    options: &SceneOptions,
    params: &FrameParams,
    size: [u32; 2],
    step: usize,
    tolerance: [f32; 2],
    probe_of: impl FnOnce(&bumpview::render::Renderer) -> ProbeScene,
) -> Vec<([u32; 2], ProbeReadout)> {
    let mut renderer = renderer_for(scene);
    renderer.set_scene(scene, options.clone());
    let mut normal_params = *params;
    normal_params.shading.view = ViewMode::ShadingNormal;
    let normals = render_image(&mut renderer, size, &normal_params).unwrap();
    let lit = render_image(&mut renderer, size, params).unwrap();
    let probe = probe_of(&renderer);
    let mut worst = [0.0f32; 2];
    let mut readouts = vec![];
    for y in (4..size[1] - 1).step_by(step) {
        for x in (4..size[0] - 1).step_by(step) {
            let Some(readout) = probe.probe(params, size, [x, y]) else { continue };
            let instance = |dx: i32, dy: i32| {
                let pixel = [(x as i32 + dx) as u32, (y as i32 + dy) as u32];
                probe.pick(&params.camera, size, pixel).map(|p| p.instance)
            };
            let neighbours = [(-1, -1), (0, -1), (1, -1), (-1, 0), (1, 0), (-1, 1), (0, 1), (1, 1)];
            if neighbours.iter().any(|&(dx, dy)| instance(dx, dy) != Some(readout.point.instance)) {
                continue;
            }
            let cpu = readout.shown_bytes().unwrap();
            let gpu = lit.get_pixel(x, y);
            let lit_diff = (0..3).map(|c| (gpu[c] as f32 - cpu[c]).abs()).fold(0.0, f32::max);
            let expected = (readout.chain.shading_normal * 0.5 + 0.5) * 255.0;
            let stored = normals.get_pixel(x, y);
            let normal_diff = (0..3).map(|c| (stored[c] as f32 - expected[c]).abs()).fold(0.0, f32::max);
            worst = [worst[0].max(lit_diff), worst[1].max(normal_diff)];
            assert!(lit_diff <= tolerance[0], "({x},{y}): GPU {gpu:?} vs CPU {cpu}");
            assert!(normal_diff <= tolerance[1], "({x},{y}): GPU {stored:?} vs CPU {expected}");
            readouts.push(([x, y], readout));
        }
    }
    println!(
        "GPU against CPU at {} pixels: worst lit {} steps, shading normal {} steps",
        readouts.len(),
        worst[0],
        worst[1]
    );
    assert!(!readouts.is_empty(), "no pixel compared: nothing of the scene fills a pixel's neighbourhood");
    readouts
}

/// A PNG whose header declares `side²` texels of `color` and whose pixel data is ten zero bytes:
/// decoding it fails, so an error about memory came from the header alone.
pub fn header_only_png(path: &Path, side: u32, color: png::ColorType, depth: png::BitDepth) {
    let mut encoder = png::Encoder::new(std::fs::File::create(path).unwrap(), side, side);
    encoder.set_color(color);
    encoder.set_depth(depth);
    let mut writer = encoder.write_header().unwrap();
    let mut zlib = vec![0x78, 0x01, 0x01, 10, 0, !10, 0xff];
    zlib.extend([0; 10]);
    zlib.extend([0, 10, 0, 1]);
    writer.write_chunk(png::chunk::IDAT, &zlib).unwrap();
}

/// The proptest settings of the fuzz targets: 256 cases (`BUMPVIEW_FUZZ_CASES` sets more),
/// failing inputs kept beside the test file and replayed first.
pub fn fuzz_config() -> proptest::test_runner::Config {
    use proptest::test_runner::{Config, FileFailurePersistence};
    let cases = std::env::var("BUMPVIEW_FUZZ_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(256);
    Config {
        cases,
        failure_persistence: Some(Box::new(FileFailurePersistence::WithSource("proptest-regressions"))),
        ..Config::default()
    }
}
