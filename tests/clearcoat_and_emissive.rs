//! Clear coats (`KHR_materials_clearcoat`, on the Khronos ClearCoatTest model) and emitted
//! light, on the software adapter: the GPU against the CPU chain at probed pixels, the layer
//! against its definition, and nothing drawn or uploaded for a coat or an emission that is not
//! there.

mod common;

use bumpview::frame::{FrameParams, SceneOptions, ShadingMode, ViewMode};
use bumpview::load::load_scene;
use bumpview::names::Named;
use bumpview::probe::ProbeScene;
use bumpview::render::Background;
use bumpview::render::capture::{CaptureOptions, render_capture, render_image};
use bumpview::scene::{Instance, Light, Lights, Scene};
use bumpview::shading::pbr::{ClearcoatInputs, PbrInputs, metallic_roughness};
use common::*;
use glam::Vec3;

fn clearcoat_test() -> Scene {
    let path = asset(&assets(), "gltf/ClearCoatTest/glTF/ClearCoatTest.gltf");
    load_scene(&path).unwrap_or_else(|e| panic!("{e}"))
}

/// Per-channel |GPU − probe| in 8-bit steps at every third pixel of a 256² view of `params`' picture whose
/// point and four neighbours lie on materials chosen by `keep` (fully covered, smooth: creases
/// and silhouettes, which MSAA blends and the probe does not, are left out); sorted.
fn gpu_against_probe(scene: &Scene, params: &FrameParams, keep: impl Fn(&str) -> bool) -> Vec<f32> {
    let size = [256, 256];
    let probe = ProbeScene::new(scene, &SceneOptions::default());
    let mut renderer = renderer_for(scene);
    let options = CaptureOptions { background: Background::Transparent, ..CaptureOptions::plain(size) };
    let image = render_capture(&mut renderer, &options, params).unwrap();
    let mut cache = std::collections::HashMap::new();
    let mut shown = |x: u32, y: u32| {
        *cache.entry((x, y)).or_insert_with(|| {
            let readout = probe.probe(params, size, [x, y])?;
            keep(&scene.materials[readout.material].name).then_some(readout.shown_bytes()?)
        })
    };
    let mut diffs = vec![];
    for y in (1..size[1] - 1).step_by(3) {
        for x in (1..size[0] - 1).step_by(3) {
            let gpu = image.get_pixel(x, y);
            let Some(cpu) = shown(x, y).filter(|_| gpu[3] == 255) else { continue };
            let neighbours = [(x - 1, y), (x + 1, y), (x, y - 1), (x, y + 1)];
            if neighbours
                .into_iter()
                .all(|(nx, ny)| shown(nx, ny).is_some_and(|c| (c - cpu).abs().max_element() <= 6.0))
            {
                diffs.push((0..3).map(|c| (gpu[c] as f32 - cpu[c]).abs()).fold(0.0, f32::max));
            }
        }
    }
    diffs.sort_by(f32::total_cmp);
    diffs
}

/// The coated column (strength, roughness and normal textures): the
/// GPU's lit pixels equal the CPU chain's within 1.5 steps at 95% and 4 at all (texture
/// filtering of the coat's normal map and the sharp coat highlight bound it; the plain
/// wall's bound is 3), and the Clear-coat normal view within 2 steps at 95%.
#[test]
fn the_coated_column_matches_the_cpu_chain() {
    let scene = clearcoat_test();
    let coated = |name: &str| name.ends_with("_Coated");
    // The camera on the coated column, which then fills most of the view.
    let column: Vec<&Instance> = scene.instances.iter().filter(|i| coated(&scene.materials[i.material].name)).collect();
    let points =
        || column.iter().flat_map(|i| scene.meshes[i.mesh].positions.iter().map(|p| i.transform.transform_point3(*p)));
    let (lo, hi) = points().fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), p| (lo.min(p), hi.max(p)));
    for view in [ViewMode::Lit, ViewMode::ClearcoatNormal] {
        let mut params = default_params(&scene);
        params.camera.target = (lo + hi) * 0.5;
        params.camera.distance = 0.55 * (hi - lo).y / (params.camera.fov_y * 0.5).tan();
        params.shading.view = view;
        let diffs = gpu_against_probe(&scene, &params, coated);
        let (p95, max) = (percentile(&diffs, 0.95), *diffs.last().unwrap());
        println!("{view:?}: {} pixels, median {} p95 {p95} max {max} steps", diffs.len(), percentile(&diffs, 0.5));
        assert!(diffs.len() > 200, "{view:?}: {} pixels", diffs.len());
        let p95_bound = if view == ViewMode::Lit { 1.5 } else { 2.0 };
        assert!(p95 <= p95_bound && max <= 4.0, "{view:?}: p95 {p95} max {max} steps");
    }
}

/// The coat layer is its definition: a coated material shades as its base dimmed by
/// `1 − factor · F(N_c·V)` plus `factor` times a black dielectric of the coat's roughness and
/// normal (the "coating only" column of ClearCoatTest), for many points, lights and factors.
#[test]
fn a_coat_is_the_dimmed_base_plus_a_black_dielectric() {
    // N_c·V kept above 1e-4, as the BRDF keeps N·V (grazing and back-facing views).
    let schlick = |cos: f32| 0.04 + 0.96 * (1.0 - cos.clamp(1e-4, 1.0)).powi(5);
    for i in 0..200 {
        let t = i as f32 * 0.37;
        let n = Vec3::new(t.sin() * 0.3, 1.0, t.cos() * 0.2).normalize();
        let coat_normal = Vec3::new((t * 1.7).cos() * 0.4, 1.0, (t * 0.3).sin() * 0.4).normalize();
        let base = PbrInputs {
            base_color: Vec3::new(0.6, 0.3, 0.1),
            metallic: (t * 0.11).fract(),
            roughness: 0.2 + 0.7 * (t * 0.07).fract(),
            occlusion: 0.8,
            geometric_normal: Vec3::Y,
            shading_normal: n,
            position: Vec3::ZERO,
            eye: Vec3::new(t.cos() * 2.0, 1.0 + (t * 0.5).sin(), t.sin() * 2.0),
            lights: Lights::one(
                Light::point(Vec3::new(-1.0, 2.0, (t * 0.9).cos()), Vec3::new(1.0, 0.9, 0.8)),
                Vec3::ZERO,
            ),
            seen: None,
            clearcoat: None,
        };
        let factor = (t * 0.13).fract();
        let roughness = 0.05 + 0.5 * (t * 0.19).fract();
        let coated = PbrInputs { clearcoat: Some(ClearcoatInputs { factor, roughness, normal: coat_normal }), ..base };
        let black = PbrInputs { base_color: Vec3::ZERO, metallic: 0.0, roughness, shading_normal: coat_normal, ..base };
        let v = (base.eye - base.position).normalize();
        let expected = metallic_roughness(&base) * (1.0 - factor * schlick(coat_normal.dot(v)))
            + factor * metallic_roughness(&black);
        let got = metallic_roughness(&coated);
        assert!((got - expected).abs().max_element() < 1e-5, "{i}: {got} vs {expected}");
        let none =
            PbrInputs { clearcoat: Some(ClearcoatInputs { factor: 0.0, roughness, normal: coat_normal }), ..base };
        assert_eq!(metallic_roughness(&none), metallic_roughness(&base), "{i}: a coat of factor 0 is no coat");
    }
}

/// A coat of factor 0 draws exactly the picture without the extension, and uploads none of the
/// coat's textures; a material that emits nothing uploads no emissive texture.
#[test]
fn an_invisible_coat_or_emission_costs_nothing() {
    let scene = clearcoat_test();
    let mut without = scene.clone();
    without.materials.iter_mut().for_each(|m| m.clearcoat = None);
    let mut zero = scene.clone();
    zero.materials.iter_mut().filter_map(|m| m.clearcoat.as_mut()).for_each(|c| c.factor = 0.0);
    let params = default_params(&scene);
    let draw = |scene: &Scene| {
        let mut renderer = renderer_for(scene);
        let image = render_image(&mut renderer, [160, 120], &params).unwrap();
        (image, renderer.counters().textures_uploaded)
    };
    let (coated, coated_uploads) = draw(&scene);
    let (plain, plain_uploads) = draw(&without);
    let (zeroed, zeroed_uploads) = draw(&zero);
    assert_eq!(zeroed, plain, "factor 0 draws the uncoated picture exactly");
    assert_eq!(zeroed_uploads, plain_uploads);
    assert!(coated != plain && coated_uploads > plain_uploads, "{coated_uploads} vs {plain_uploads}");
    let mut dark = scene.clone();
    dark.materials.iter_mut().for_each(|m| m.emissive_factor = Vec3::ZERO);
    let (_, dark_uploads) = draw(&dark);
    assert_eq!(dark_uploads + 1, coated_uploads, "the labels' emissive texture only");
}

/// Emitted light adds to the lit picture (bump × colour only): on the built-in wall with an
/// emissive texture (the bricks' colour) and factor, the GPU matches the CPU chain at probed
/// pixels within the plain wall's 3 steps, and the emission raises the pixels it should.
#[test]
fn emission_adds_to_the_lit_picture() {
    let mut scene = scene();
    scene.materials[0].emissive_factor = Vec3::new(0.3, 0.1, 0.0);
    scene.materials[0].emissive_texture = scene.materials[0].base_color_texture;
    let mut params = close_wall_params(&scene, 0.3);
    let size = [128, 128];
    let probe = ProbeScene::new(&scene, &SceneOptions::default());
    let mut renderer = renderer_for(&scene);
    let mut dark = scene.clone();
    dark.materials[0].emissive_factor = Vec3::ZERO;
    let mut dark_renderer = renderer_for(&dark);
    for &mode in ShadingMode::all() {
        params.shading.mode = mode;
        let lit = render_image(&mut renderer, size, &params).unwrap();
        let unlit = render_image(&mut dark_renderer, size, &params).unwrap();
        let mut brighter = 0;
        for y in (2..size[1]).step_by(9) {
            for x in (2..size[0]).step_by(9) {
                let readout = probe.probe(&params, size, [x, y]).unwrap();
                let (gpu, cpu) = (lit.get_pixel(x, y), readout.shown_bytes().unwrap());
                let diff = (0..3).map(|c| (gpu[c] as f32 - cpu[c]).abs()).fold(0.0, f32::max);
                assert!(diff <= 3.0, "{mode:?} ({x},{y}): GPU {gpu:?} vs chain {cpu}");
                brighter += (lit.get_pixel(x, y)[0] > unlit.get_pixel(x, y)[0]) as u32;
                assert_eq!(lit.get_pixel(x, y)[2], unlit.get_pixel(x, y)[2], "no blue in the emission");
            }
        }
        let expected = if mode == ShadingMode::BumpTimesColour { 190 } else { 0 };
        assert!(
            if expected > 0 { brighter >= expected } else { brighter == 0 },
            "{mode:?}: {brighter} of 196 pixels brighter"
        );
    }
}

/// An OBJ material's `Ke` is its emitted light and `map_Ke` its emissive texture (which shows as
/// is where `Ke` is missing or black).
#[test]
fn obj_materials_read_ke_and_map_ke() {
    let dir = std::env::temp_dir().join(format!("bumpview-obj-emissive-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    image::RgbaImage::from_pixel(2, 2, image::Rgba([255, 128, 0, 255])).save(dir.join("glow.png")).unwrap();
    let mtl = "newmtl lamp\nKe 0.5 0.25 0\nnewmtl sign\nmap_Ke glow.png\n";
    std::fs::write(dir.join("m.mtl"), mtl).unwrap();
    let obj = "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl lamp\nf 1/1 2/2 3/3\nusemtl sign\nf 1/1 3/3 2/2\n";
    std::fs::write(dir.join("m.obj"), obj).unwrap();
    let scene = load_scene(&dir.join("m.obj")).unwrap_or_else(|e| panic!("{e}"));
    std::fs::remove_dir_all(&dir).unwrap();
    let by_name = |name: &str| scene.materials.iter().find(|m| m.name == name).unwrap();
    assert_eq!(by_name("lamp").emissive_factor, Vec3::new(0.5, 0.25, 0.0));
    assert_eq!(by_name("lamp").emissive_texture, None);
    let sign = by_name("sign");
    assert_eq!(sign.emissive_factor, Vec3::ONE);
    assert!(sign.emissive_texture.is_some_and(|t| scene.textures[t].rgba[..4] == [255, 128, 0, 255]));
}
