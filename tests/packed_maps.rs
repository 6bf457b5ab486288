//! Packed normal maps: the RG (BC5), AG (DXT5nm) and X-Ray pair layouts decode to the
//! normals they were made from within 8-bit error, the GPU draws them as the CPU chain does,
//! and a colour texture with `NAME_bump.*` and `NAME_bump#.*` beside it loads (and checks) as
//! X-Ray's pair.

mod common;

use bumpview::check::check_scene;
use bumpview::frame::SceneOptions;
use bumpview::load::SceneFiles;
use bumpview::render::capture::render_image;
use bumpview::scene::{NormalLayout, NormalMap, Scene, TextureImage, TextureKind};
use bumpview::shading::{NormalTexel, decode_normal};
use common::*;
use glam::{Vec3, Vec4};

/// The source normals: the built-in brick map's texels decoded as unit vectors (floats).
fn source_normals(scene: &Scene) -> (TextureImage, Vec<Vec3>) {
    let map = (*scene.textures[scene.materials[0].normal_map.as_ref().unwrap().texture]).clone();
    let normals = map
        .rgba
        .chunks_exact(4)
        .map(|t| (Vec3::new(unit(t[0]), unit(t[1]), unit(t[2])) * 2.0 - 1.0).normalize())
        .collect();
    (map, normals)
}

fn byte(v: f32) -> u8 {
    (v.clamp(0.0, 1.0) * 255.0).round() as u8
}

/// X-Ray's gloss byte for texel `i` (gloss = red², so this covers 0.06..1).
fn gloss_byte(i: usize) -> u8 {
    64 + (i % 192) as u8
}

/// `n` packed in `layout`: the texture's RGBA bytes and, for X-Ray, the `bump#` bytes. X-Ray's
/// `bump` stores `h = n/2 + 1/2` with 6 bits per channel (a stand-in for DXT's compression
/// error) and `bump#` the rest, `h − bump + 1/2`, in 8 bits, so `bump + bump# − 1 = n/2`.
fn pack(n: Vec3, layout: NormalLayout, i: usize) -> ([u8; 4], [u8; 4]) {
    let h = n * 0.5 + 0.5;
    match layout {
        NormalLayout::Rgb => ([byte(h.x), byte(h.y), byte(h.z), 255], [128; 4]),
        NormalLayout::Rg => ([byte(h.x), byte(h.y), 0, 255], [128; 4]),
        NormalLayout::Ag => ([255, byte(h.y), 0, byte(h.x)], [128; 4]),
        NormalLayout::Xray => {
            let coarse = h.to_array().map(|c| byte((c * 63.0).round() / 63.0));
            let stored = Vec3::from_array(coarse.map(unit));
            let [ex, ey, ez] = (h - stored + 0.5).to_array().map(byte);
            let [cx, cy, cz] = coarse;
            ([gloss_byte(i), cz, cy, cx], [ex, ey, ez, 128])
        }
    }
}

fn texel_of(bytes: [u8; 4], correction: Option<[u8; 4]>) -> NormalTexel {
    let v = |b: [u8; 4]| Vec4::from_array(b.map(unit));
    NormalTexel { rgba: v(bytes), correction: correction.map(|c| v(c).truncate()) }
}

/// The largest angle (degrees) between the source normals and their decoded packing.
fn worst_angle(normals: &[Vec3], layout: NormalLayout, with_correction: bool) -> f32 {
    let convention = bumpview::scene::NormalConvention { layout, ..Default::default() };
    normals
        .iter()
        .enumerate()
        .map(|(i, &n)| {
            let (bytes, correction) = pack(n, layout, i);
            let decoded = decode_normal(texel_of(bytes, with_correction.then_some(correction)), convention);
            decoded.angle_between(n).to_degrees()
        })
        .fold(0.0, f32::max)
}

/// Every packing decodes to its source normals within the error of 8-bit RGB on the same
/// normals (plus 10%: RG and AG rebuild z from x and y, whose rounding z then inherits);
/// X-Ray's 6-bit `bump` alone is several times worse, and its `bump#` brings it back.
#[test]
fn packed_layouts_round_trip_within_8_bit_error() {
    let (_, normals) = source_normals(&scene());
    let rgb = worst_angle(&normals, NormalLayout::Rgb, false);
    let [rg, ag, xray] =
        [NormalLayout::Rg, NormalLayout::Ag, NormalLayout::Xray].map(|l| worst_angle(&normals, l, true));
    let bump_alone = worst_angle(&normals, NormalLayout::Xray, false);
    println!(
        "worst angle: rgb {rgb:.3}°, rg {rg:.3}°, ag {ag:.3}°, x-ray pair {xray:.3}°, bump alone {bump_alone:.3}°"
    );
    assert!(rgb < 0.5, "{rgb}");
    for (name, angle) in [("rg", rg), ("ag", ag), ("x-ray pair", xray)] {
        assert!(angle <= rgb * 1.1, "{name}: {angle}° against 8-bit RGB's {rgb}°");
    }
    assert!(bump_alone > 3.0 * rgb, "{bump_alone}");
}

/// The built-in scene with material 0's normal map re-packed in `layout` (X-Ray with its
/// `bump#`).
fn packed_scene(layout: NormalLayout) -> Scene {
    let mut scene = scene();
    let (map, normals) = source_normals(&scene);
    let packed: Vec<_> = normals.iter().enumerate().map(|(i, &n)| pack(n, layout, i)).collect();
    let image =
        |name: &str, kind, bytes: Vec<[u8; 4]>| TextureImage::new(name, map.width, map.height, kind, bytes.concat());
    scene.textures.push(image("packed", TextureKind::NormalMap, packed.iter().map(|p| p.0).collect()).into());
    let bump = scene.textures.len() - 1;
    let mut normal_map = NormalMap::new(bump, 1.0);
    normal_map.convention.layout = layout;
    if layout == NormalLayout::Xray {
        scene.textures.push(image("packed#", TextureKind::Data, packed.iter().map(|p| p.1).collect()).into());
        normal_map = NormalMap::xray(bump, Some(scene.textures.len() - 1));
    }
    scene.materials[0].normal_map = Some(normal_map);
    scene
}

/// On the close wall, each layout's lit and shading-normal pictures equal the CPU chain (the
/// probe, which samples RGBA and `bump#` as the GPU does) within the probe test's tolerances
/// (3 and 2 steps of 8 bits, tests/probe.rs); X-Ray's gloss (red²) darkens the highlight where
/// red is low, so the lit X-Ray picture differs from the RG one by more than that.
#[test]
fn the_gpu_draws_packed_layouts_as_the_cpu_chain() {
    const SIZE: [u32; 2] = [128, 128];
    let mut lit_pictures = vec![];
    for layout in [NormalLayout::Rg, NormalLayout::Ag, NormalLayout::Xray] {
        let scene = packed_scene(layout);
        let mut params = close_wall_params(&scene, 0.3);
        params.lights[0].position = glam::Vec3::new(0.02, 1.52, -0.7);
        // X-Ray sums two filtered textures before normalising, so the GPU's filter rounding
        // enters twice: 3 steps for its normals (measured 2.4 at most), against 2 for one.
        let normal_tolerance = if layout == NormalLayout::Xray { 3.0 } else { 2.0 };
        println!("{layout:?}:");
        let compared = gpu_against_probe(&scene, &SceneOptions::default(), &params, SIZE, 11, [3.0, normal_tolerance]);
        // The wall fills the view: most of the 11 × 11 grid is compared.
        assert!(compared.len() > 80, "{layout:?}: only {} pixels compared", compared.len());
        lit_pictures.push(render_image(&mut renderer_for(&scene), SIZE, &params).unwrap());
    }
    let max_diff = lit_pictures[0].pixels().zip(lit_pictures[2].pixels()).map(|(a, b)| a[1].abs_diff(b[1])).max();
    println!("RG against X-Ray lit: max {max_diff:?} steps in green");
    assert!(max_diff.unwrap() > 6, "the X-Ray gloss must show");
}

/// A folder of `NAME.png`, `NAME_bump.png`, `NAME_bump#.png` loads as X-Ray's pair on every
/// material, and `check` says so and why.
#[test]
fn a_colour_texture_with_bump_files_beside_it_loads_as_the_x_ray_pair() {
    let folder = std::env::temp_dir().join(format!("bumpview-xray-{}", std::process::id()));
    std::fs::create_dir_all(&folder).unwrap();
    let scene = packed_scene(NormalLayout::Xray);
    let map = scene.materials[0].normal_map.as_ref().unwrap();
    let save = |texture: usize, name: &str| {
        let t = &scene.textures[texture];
        image::RgbaImage::from_raw(t.width, t.height, t.rgba.clone()).unwrap().save(folder.join(name)).unwrap();
    };
    save(map.texture, "wall_bump.png");
    save(map.correction.unwrap(), "wall_bump#.png");
    save(scene.materials[0].base_color_texture.unwrap(), "wall.png");
    let files = SceneFiles { color: Some(folder.join("wall.png")), ..Default::default() };
    let loaded = files.build(Default::default()).unwrap();
    for material in &loaded.materials {
        let normal_map = material.normal_map.as_ref().unwrap();
        assert_eq!(normal_map.convention.layout, NormalLayout::Xray);
        assert_eq!(loaded.textures[normal_map.texture].rgba, scene.textures[map.texture].rgba);
        assert_eq!(loaded.textures[normal_map.correction.unwrap()].rgba, scene.textures[map.correction.unwrap()].rgba);
    }
    let report = check_scene(&loaded).to_text();
    println!("{report}");
    assert!(
        report.contains("layout: xray (X-Ray pair: ") && report.contains("wall_bump#.png\" beside it)"),
        "{report}"
    );
    // Without bump#, the pair is the bump alone.
    std::fs::remove_file(folder.join("wall_bump#.png")).unwrap();
    let loaded = files.build(Default::default()).unwrap();
    assert_eq!(loaded.materials[0].normal_map.as_ref().unwrap().correction, None);
    std::fs::remove_dir_all(&folder).unwrap();
}
