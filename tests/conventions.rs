//! Normal-map conventions and samplers on the GPU: DirectX against OpenGL, two-channel and
//! object-space maps, clamped and mirrored wrap modes, glTF samplers, and a NaN scan of every
//! shader path they add.

mod common;

use bumpview::frame::ViewMode;
use bumpview::frame::{BumpSource, FrameParams, SceneOptions};
use bumpview::names::Named;
use bumpview::render::capture::{render_float, render_image};
use bumpview::scene::builtin::{WALL_Z, wall_uv};
use bumpview::scene::{
    GreenAxis, Instance, MaterialOverrides, NormalLayout, NormalSpace, SamplerWrap, Scene, ShadingModel, TextureImage,
    TextureKind, Wrap,
};
use bumpview::shading::{NormalTexel, decode_normal, object_space_normal};
use common::*;
use glam::{Mat3, Mat4, Vec3};

/// The built-in scene with only the wall (instance 0) and `transform` on it.
fn wall_only(transform: Mat4) -> Scene {
    let mut scene = scene();
    scene.instances = vec![Instance { mesh: 0, material: 0, transform }];
    scene
}

fn texture(name: &str, kind: TextureKind, width: u32, texels: &[[u8; 4]]) -> TextureImage {
    TextureImage::new(name, width, texels.len() as u32 / width, kind, texels.concat())
}

fn render_with(scene: &Scene, options: SceneOptions, params: &FrameParams, size: [u32; 2]) -> image::RgbaImage {
    let mut renderer = renderer_for(scene);
    renderer.set_scene(scene, options);
    render_image(&mut renderer, size, params).unwrap()
}

/// A DirectX map (green flipped) read with the DirectX flag shows the same shading normals
/// as the original read as OpenGL. Tolerance 2 steps on at most 0.5% of pixels, else 1: the
/// mip levels are re-encoded from the flipped map, and where an averaged green lands on a
/// rounding tie the two maps' mip texels differ by one step, which the display rounding can
/// turn into two (measured: max 2, on a handful of floor pixels far away). The same flipped
/// map read as OpenGL must be far off (the test can fail).
#[test]
fn directx_flag_undoes_a_flipped_green_channel() {
    let original = scene();
    let mut flipped = original.clone();
    let map = flipped.materials[0].normal_map.as_ref().unwrap().texture;
    std::sync::Arc::make_mut(&mut flipped.textures[map]).rgba.chunks_exact_mut(4).for_each(|t| t[1] = 255 - t[1]);
    let mut params = default_params(&original);
    params.shading.view = ViewMode::ShadingNormal;
    let size = [160, 120];
    let reference = render_with(&original, SceneOptions::default(), &params, size);
    let directx = MaterialOverrides { green: Some(GreenAxis::DirectX), ..Default::default() };
    let decoded = render_with(&flipped, SceneOptions { materials: directx, ..Default::default() }, &params, size);
    let misread = render_with(&flipped, SceneOptions::default(), &params, size);
    let max_diff = |a: &image::RgbaImage, b: &image::RgbaImage| {
        a.pixels().zip(b.pixels()).map(|(p, q)| (0..3).map(|c| p[c].abs_diff(q[c])).max().unwrap()).max().unwrap()
    };
    let (good, bad) = (max_diff(&reference, &decoded), max_diff(&reference, &misread));
    let over_one =
        reference.pixels().zip(decoded.pixels()).filter(|(p, q)| (0..3).any(|c| p[c].abs_diff(q[c]) > 1)).count();
    println!("DirectX flag: max {good} steps, {over_one} pixels over 1; read as OpenGL: max {bad} steps");
    assert!(good <= 2, "{good}");
    assert!(over_one * 200 <= (size[0] * size[1]) as usize, "{over_one}");
    assert!(bad > 40, "{bad}");
}

/// Two-channel texels outside the unit disc (x² + y² up to 2) and the zero texel decode to
/// finite unit normals on the GPU: the shading-normal view decodes to unit vectors and the
/// float target holds no NaN.
#[test]
fn two_channel_texels_outside_the_disc_give_finite_unit_normals() {
    let mut scene = wall_only(Mat4::IDENTITY);
    let texels = [[255, 255, 0, 255], [0, 255, 0, 255], [0, 0, 0, 255], [128, 128, 0, 255]];
    scene.textures.push(texture("two-channel", TextureKind::NormalMap, 2, &texels).into());
    scene.materials[0].normal_map.as_mut().unwrap().texture = scene.textures.len() - 1;
    scene.materials[0].normal_map.as_mut().unwrap().convention.layout = NormalLayout::Rg;
    let mut params = close_wall_params(&scene, 0.5);
    params.shading.view = ViewMode::ShadingNormal;
    let mut renderer = renderer_for(&scene);
    let float = render_float(&mut renderer, [64, 64], &params).unwrap();
    assert!(float.pixels.iter().flatten().all(|c| c.is_finite()));
    let image = render_image(&mut renderer, [64, 64], &params).unwrap();
    for pixel in image.pixels() {
        let v = Vec3::new(unit(pixel[0]), unit(pixel[1]), unit(pixel[2])) * 2.0 - 1.0;
        assert!((v.length() - 1.0).abs() < 0.02, "{v}");
    }
}

/// An object-space map on a rotated and non-uniformly scaled wall: every pixel's shading
/// normal is the normal matrix times the decoded model-space vector. Tolerance 1°: the
/// debug colour is stored in 8 bits (≤ 0.5 step = 0.002 per component, about 0.2°), plus
/// filtering of a constant texture (exact).
#[test]
fn object_space_map_follows_the_normal_matrix() {
    let centre = Vec3::new(0.0, 1.5, WALL_Z);
    let model = Mat4::from_translation(centre)
        * Mat4::from_rotation_y(25f32.to_radians())
        * Mat4::from_scale(Vec3::new(2.0, 1.0, 1.0))
        * Mat4::from_translation(-centre);
    let mut scene = wall_only(model);
    let texel = [200u8, 150, 210, 255];
    scene.textures.push(texture("object space", TextureKind::NormalMap, 1, &[texel]).into());
    let normal_map = scene.materials[0].normal_map.as_mut().unwrap();
    normal_map.texture = scene.textures.len() - 1;
    normal_map.convention.space = NormalSpace::Object;
    let convention = normal_map.convention;
    let rgb = NormalTexel::rgb(Vec3::new(unit(texel[0]), unit(texel[1]), unit(texel[2])));
    let normal_matrix = Mat3::from_mat4(model).inverse().transpose();
    let expected = (normal_matrix * decode_normal(rgb, convention)).normalize();
    let n_geo = (normal_matrix * Vec3::Z).normalize();
    let cpu = object_space_normal(n_geo, normal_matrix, true, rgb, 1.0, convention);
    assert!(cpu.angle_between(expected) < 1e-4);
    let mut params = close_wall_params(&scene, 1.0);
    params.shading.view = ViewMode::ShadingNormal;
    let mut renderer = renderer_for(&scene);
    let image = render_image(&mut renderer, [64, 64], &params).unwrap();
    let worst = image.pixels().map(|p| decode_debug(p).angle_between(expected).to_degrees()).fold(0.0, f32::max);
    println!("object space: worst {worst}° from {expected}");
    assert!(worst < 1.0, "{worst}°");
    // No tangents are made for it: the tangent view is the mid-grey of the zero vector.
    params.shading.view = ViewMode::Tangent;
    let tangent_view = render_image(&mut renderer, [16, 16], &params).unwrap();
    assert!(tangent_view.pixels().all(|p| (0..3).all(|c| p[c].abs_diff(128) <= 1)));
    assert_eq!(renderer.tangent_methods(), vec![None, None, None]);
}

/// Wrap modes: an 8×1 texture, left half red and right half blue, on the wall (u = x + 2).
/// In the second tile, u ∈ (1.1, 1.4) reads red when repeating but blue when clamped or
/// mirrored; u ∈ (1.6, 1.9) reads blue repeating or clamped but red mirrored.
#[test]
fn samplers_repeat_clamp_and_mirror() {
    let (red, blue) = ([255, 0, 0, 255], [0, 0, 255, 255]);
    for (wrap, expect_first, expect_second) in
        [(Wrap::Repeat, 'r', 'b'), (Wrap::ClampToEdge, 'b', 'b'), (Wrap::MirroredRepeat, 'b', 'r')]
    {
        let mut scene = wall_only(Mat4::IDENTITY);
        scene
            .textures
            .push(texture("halves", TextureKind::Color, 8, &[red, red, red, red, blue, blue, blue, blue]).into());
        scene.materials[0].base_color_texture = Some(scene.textures.len() - 1);
        scene.materials[0].normal_map = None;
        scene.materials[0].base_color_wrap = SamplerWrap { u: wrap, v: Wrap::Repeat };
        let mut params = close_wall_params(&scene, 2.0);
        params.camera.target.x = -0.5;
        let size = [128, 96];
        let image = render_with(&scene, SceneOptions::default(), &params, size);
        let mut checked = 0;
        for y in (0..size[1]).step_by(3) {
            for x in (0..size[0]).step_by(3) {
                let Some(p) = hit_plane(&params.camera, size, x, y, Vec3::Z, WALL_Z) else { continue };
                let u = wall_uv(p).x;
                let expected = match u {
                    u if u > 1.1 && u < 1.4 => expect_first,
                    u if u > 1.6 && u < 1.9 => expect_second,
                    _ => continue,
                };
                let pixel = image.get_pixel(x, y);
                let seen = if pixel[0] > pixel[2] { 'r' } else { 'b' };
                assert_eq!(seen, expected, "{wrap:?} at u = {u}: {pixel:?}");
                checked += 1;
            }
        }
        assert!(checked > 100, "{checked}");
    }
}

/// glTF samplers reach the materials: TextureTransformTest clamps its arrow texture; glTF
/// materials default to metallic-roughness with their factors and texture slots.
#[test]
fn gltf_samplers_and_metallic_roughness_are_loaded() {
    let base = assets();
    let path = asset(&base, "gltf/TextureTransformTest/glTF/TextureTransformTest.gltf");
    let scene = bumpview::load::load_scene(&path).unwrap();
    let clamp = SamplerWrap { u: Wrap::ClampToEdge, v: Wrap::ClampToEdge };
    let arrows = scene.materials.iter().filter(|m| m.base_color_wrap == clamp).count();
    assert_eq!(arrows, 6, "the six transformed materials use the clamping sampler");
    assert!(scene.materials.iter().all(|m| m.shading_model == ShadingModel::MetallicRoughness && m.metallic == 0.0));
    let path = asset(&base, "gltf/NormalTangentTest/glTF/NormalTangentTest.gltf");
    let scene = bumpview::load::load_scene(&path).unwrap();
    let material = &scene.materials[0];
    assert!(material.metallic_roughness_texture.is_some() && material.occlusion.is_some());
    assert_eq!(material.metallic_roughness_texture, material.occlusion.as_ref().map(|o| o.texture));
    assert_eq!(scene.textures[material.metallic_roughness_texture.unwrap()].kind, TextureKind::Data);
}

/// No NaN or infinity anywhere on a float target, for every path this adds: DirectX,
/// RG, AG and X-Ray layouts and object-space maps (on the curved torus too, with extreme texels), both
/// shading models, and a depth map bumped in the shader; lit and shading-normal views.
#[test]
fn new_variants_never_produce_nan() {
    let mut wild = scene();
    let texels = [[255, 255, 0, 255], [0, 0, 0, 255], [255, 0, 255, 255], [0, 255, 128, 255]];
    wild.textures.push(texture("wild", TextureKind::NormalMap, 2, &texels).into());
    let wild_map = wild.textures.len() - 1;
    wild.materials.iter_mut().for_each(|m| m.normal_map.as_mut().unwrap().texture = wild_map);
    let on = Some(true);
    let [rg, ag, xray] = [NormalLayout::Rg, NormalLayout::Ag, NormalLayout::Xray].map(Some);
    let cases = [
        (scene(), MaterialOverrides { green: Some(GreenAxis::DirectX), layout: rg, ..Default::default() }),
        (wild.clone(), MaterialOverrides { layout: rg, ..Default::default() }),
        (wild.clone(), MaterialOverrides { layout: ag, ..Default::default() }),
        (wild.clone(), MaterialOverrides { layout: xray, ..Default::default() }),
        (wild.clone(), MaterialOverrides { object_space: on, ..Default::default() }),
        (
            wild,
            MaterialOverrides { object_space: on, layout: rg, green: Some(GreenAxis::DirectX), ..Default::default() },
        ),
        (scene(), MaterialOverrides { depth_map: on, height_range_m: Some(0.05), ..Default::default() }),
    ];
    for (scene, materials) in cases {
        for &bump_source in BumpSource::all() {
            let options = SceneOptions { materials, bump_source, ..Default::default() };
            let mut renderer = renderer_for(&scene);
            renderer.set_scene(&scene, options);
            for shading in [None, Some(ShadingModel::BlinnPhong), Some(ShadingModel::MetallicRoughness)] {
                for view in [ViewMode::Lit, ViewMode::ShadingNormal] {
                    let mut params = default_params(&scene);
                    params.shading.view = view;
                    params.shading.shading_override = shading;
                    params.shading.strength = 4.0;
                    let image = render_float(&mut renderer, [96, 72], &params).unwrap();
                    let bad = image.pixels.iter().flatten().filter(|c| !c.is_finite()).count();
                    assert_eq!(bad, 0, "{materials:?} {bump_source:?} {shading:?} {view:?}");
                }
            }
        }
    }
}

/// Per-material overrides: in the built-in scene wall and floor use material 0 and the torus
/// material 1. Flipping green on material 1 only changes the torus's pixels in the
/// shading-normal view (exactly: the wall and floor draw with the same data), and changes
/// most of them; a per-material OpenGL setting wins over a viewer-wide DirectX one, so the
/// torus's inside (its pixels whose 3×3 neighbourhood is all torus, free of edge pixels that
/// blend in the wall) stays exactly as it was.
#[test]
fn per_material_green_flip_changes_only_that_material() {
    let full = scene();
    let mut without_torus = full.clone();
    without_torus.instances.retain(|i| i.material == 0);
    let mut params = default_params(&full);
    params.shading.view = ViewMode::ShadingNormal;
    let size = [240, 180];
    let reference = render_with(&full, SceneOptions::default(), &params, size);
    // The torus's pixels: where the picture changes when it is taken away.
    let torus = render_with(&without_torus, SceneOptions::default(), &params, size);
    let is_torus = |x: i64, y: i64| {
        let (x, y) = (x.clamp(0, size[0] as i64 - 1) as u32, y.clamp(0, size[1] as i64 - 1) as u32);
        let (p, q) = (reference.get_pixel(x, y), torus.get_pixel(x, y));
        (0..3).any(|c| p[c] != q[c])
    };
    // Per pixel: 0 off the torus, 1 on its edge, 2 inside.
    let region: Vec<usize> = (0..size[1] as i64)
        .flat_map(|y| (0..size[0] as i64).map(move |x| (x, y)))
        .map(|(x, y)| match is_torus(x, y) {
            false => 0,
            true if (-1..=1).all(|dy| (-1..=1).all(|dx| is_torus(x + dx, y + dy))) => 2,
            true => 1,
        })
        .collect();
    let count = |r: usize| region.iter().filter(|&&p| p == r).count();
    let (edge_pixels, inside_pixels) = (count(1), count(2));
    let directx = MaterialOverrides { green: Some(GreenAxis::DirectX), ..Default::default() };
    let opengl = MaterialOverrides { green: Some(GreenAxis::OpenGl), ..Default::default() };
    // Pixels changed by more than 2 steps against the reference: [off the torus, edge, inside].
    let changes = |options: SceneOptions| {
        let image = render_with(&full, options, &params, size);
        let mut changed = [0; 3];
        for ((p, q), &r) in reference.pixels().zip(image.pixels()).zip(&region) {
            if (0..3).any(|c| p[c].abs_diff(q[c]) > 2) {
                changed[r] += 1;
            }
        }
        changed
    };
    let torus_only = changes(SceneOptions { per_material: [(1, directx)].into(), ..Default::default() });
    let everywhere = changes(SceneOptions { materials: directx, ..Default::default() });
    let torus_kept =
        changes(SceneOptions { materials: directx, per_material: [(1, opengl)].into(), ..Default::default() });
    println!(
        "torus: {inside_pixels} inside, {edge_pixels} edge pixels; changed [off, edge, inside]: material 1 flipped \
         {torus_only:?}, all flipped {everywhere:?}, all flipped but material 1 {torus_kept:?}"
    );
    assert!(inside_pixels > 1000, "{inside_pixels}");
    assert_eq!(torus_only[0], 0, "pixels off the torus changed");
    assert!(torus_only[2] * 2 > inside_pixels, "{torus_only:?}");
    assert!(everywhere[0] > 4 * inside_pixels, "{everywhere:?}");
    assert_eq!(torus_kept[2], 0, "the torus's own OpenGL setting lost");
    assert_eq!(torus_kept[0], everywhere[0]);
}
