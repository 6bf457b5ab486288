//! Loading real files: every third-party model loads and renders, every picture decodes and
//! three texture sets are drawn on the built-in scene; the glTF normal-map conformance models
//! shade like their real-geometry twins; geometry without normals, mirrored or seen from
//! behind shows normals facing the camera.
//!
//! The files are the repository's fixtures (tests/fixtures/README.md); a missing one fails.

mod common;

use std::path::{Path, PathBuf};

use bumpview::frame::ViewMode;
use bumpview::load::{SceneFiles, load_scene, replace_textures};
use bumpview::render::capture::{render_float, render_image};
use bumpview::render::{Gpu, Renderer};
use bumpview::scene::Scene;
use bumpview::scene::builtin::teaching_scene;
use common::{asset, assets, bounding_sphere_distance, decode_debug, default_params};
use glam::Vec2;

fn load(base: &Path, relative: &str) -> Scene {
    load_scene(&asset(base, relative)).unwrap_or_else(|e| panic!("{e}"))
}

fn renderer() -> Renderer {
    let gpu = Gpu::headless().unwrap_or_else(|e| panic!("GPU tests need an adapter: {e}"));
    Renderer::from_gpu(&gpu)
}

/// Every file under `dir` whose extension (lower case) is one of `extensions`.
fn files_under(dir: &Path, extensions: &[&str]) -> Vec<PathBuf> {
    let mut found = vec![];
    for entry in std::fs::read_dir(dir).unwrap().map(Result::unwrap) {
        let path = entry.path();
        if path.is_dir() {
            found.extend(files_under(&path, extensions));
        } else if path.extension().is_some_and(|e| extensions.contains(&e.to_string_lossy().to_lowercase().as_str())) {
            found.push(path);
        }
    }
    found.sort();
    found
}

/// Models the README lists; each must be present (the walk below finds any others too).
const MODELS: [&str; 15] = [
    "gltf/NormalTangentTest/glTF/NormalTangentTest.gltf",
    "gltf/NormalTangentMirrorTest/glTF/NormalTangentMirrorTest.gltf",
    "gltf/TwoSidedPlane/glTF/TwoSidedPlane.gltf",
    "gltf/NegativeScaleTest/glTF/NegativeScaleTest.gltf",
    "gltf/TextureCoordinateTest/glTF/TextureCoordinateTest.gltf",
    "gltf/TextureTransformTest/glTF/TextureTransformTest.gltf",
    "gltf/MultiUVTest/glTF/MultiUVTest.gltf",
    "gltf/Box/glTF/Box.gltf",
    "gltf/BoxTextured/glTF-Binary/BoxTextured.glb",
    "gltf/OrientationTest/glTF/OrientationTest.gltf",
    "gltf/Box With Spaces/glTF/Box With Spaces.gltf",
    "gltf/WaterBottle/glTF/WaterBottle.gltf",
    "gltf/Suzanne/glTF/Suzanne.gltf",
    "obj/spot/spot_quadrangulated.obj",
    "obj/learn-wgpu-cube/cube.obj",
];

#[test]
fn every_model_and_texture_loads_and_renders_without_nan() {
    let base = assets();
    MODELS.iter().for_each(|m| _ = asset(&base, m));
    let mut renderer = renderer();
    let mut draw = |scene: &Scene, what: &str| {
        renderer.set_scene(scene, Default::default());
        for view in [ViewMode::Lit, ViewMode::ShadingNormal] {
            let mut params = default_params(scene);
            params.shading.view = view;
            let image = render_float(&mut renderer, [96, 72], &params).unwrap_or_else(|e| panic!("{what}: {e}"));
            assert!(image.pixels.iter().flatten().all(|c| c.is_finite()), "{what}: NaN or infinity in {view:?}");
        }
    };
    let models = files_under(&base, &["gltf", "glb", "obj"]);
    assert!(models.len() >= MODELS.len());
    for model in &models {
        let scene = load_scene(model).unwrap_or_else(|e| panic!("{e}"));
        draw(&scene, &model.display().to_string());
    }
    // Every picture in the folder decodes; each texture set is drawn on the built-in scene.
    for image in files_under(&base, &["png", "jpg", "jpeg", "tga", "bmp"]) {
        bumpview::load::image::load_texture(&image, bumpview::scene::TextureKind::Color)
            .unwrap_or_else(|e| panic!("{e}"));
    }
    let sets = [
        ("textures/ambientCG_Rock058/albedo.jpg", "textures/ambientCG_Rock058/normal.jpg", None),
        ("textures/bevy_parallax_cube/cube_color.png", "textures/bevy_parallax_cube/cube_normal.png", None),
        (
            "textures/ambientCG_Rock058/albedo.jpg",
            "textures/ambientCG_Rock058/normal.jpg",
            Some("textures/ambientCG_Rock058/displacement.jpg"),
        ),
    ];
    for (color, normal, height) in sets {
        let mut scene = teaching_scene();
        let slots = SceneFiles {
            mesh: None,
            color: Some(asset(&base, color)),
            normal: Some(asset(&base, normal)),
            height: height.map(|h| asset(&base, h)),
            gloss: Some(asset(&base, "textures/ambientCG_Rock058/roughness.jpg")),
            ..Default::default()
        };
        replace_textures(&mut scene, &slots).unwrap_or_else(|e| panic!("{e}"));
        draw(&scene, color);
    }
}

/// A square cell of the conformance models in a picture: its pixel bounds.
#[derive(Debug, Clone, Copy)]
struct Cell {
    min: [u32; 2],
    max: [u32; 2],
}

impl Cell {
    fn center(&self) -> Vec2 {
        glam::UVec2::new(self.min[0] + self.max[0], self.min[1] + self.max[1]).as_vec2() * 0.5
    }
    fn size(&self) -> Vec2 {
        glam::UVec2::new(self.max[0] - self.min[0], self.max[1] - self.min[1]).as_vec2()
    }
}

/// The connected regions (4-neighbours) of pixels that differ from the background colour
/// (pixel (0, 0)) by more than 8/255 in a channel: the model's cells and labels.
fn regions(image: &image::RgbaImage) -> Vec<Cell> {
    let (w, h) = image.dimensions();
    let background = *image.get_pixel(0, 0);
    let covered = |x: u32, y: u32| {
        let p = image.get_pixel(x, y);
        (0..3).any(|c| p[c].abs_diff(background[c]) > 8)
    };
    let mut seen = vec![false; (w * h) as usize];
    let mut cells = vec![];
    for start in 0..w * h {
        if seen[start as usize] || !covered(start % w, start / w) {
            continue;
        }
        let mut cell = Cell { min: [w, h], max: [0, 0] };
        let mut stack = vec![start];
        seen[start as usize] = true;
        while let Some(i) = stack.pop() {
            let (x, y) = (i % w, i / w);
            cell.min = [cell.min[0].min(x), cell.min[1].min(y)];
            cell.max = [cell.max[0].max(x), cell.max[1].max(y)];
            let neighbours = [(x.wrapping_sub(1), y), (x + 1, y), (x, y.wrapping_sub(1)), (x, y + 1)];
            for (nx, ny) in neighbours {
                if nx < w && ny < h && !seen[(ny * w + nx) as usize] && covered(nx, ny) {
                    seen[(ny * w + nx) as usize] = true;
                    stack.push(ny * w + nx);
                }
            }
        }
        cells.push(cell);
    }
    cells
}

/// The test cells of a conformance model in rows, left to right: regions that are square
/// (sides within 10 %) and as large as the largest (labels and the "Front" sign drop out).
fn cell_rows(image: &image::RgbaImage) -> Vec<Vec<Cell>> {
    let squares: Vec<Cell> =
        regions(image).into_iter().filter(|c| (c.size().x / c.size().y.max(1.0) - 1.0).abs() < 0.1).collect();
    let largest = squares.iter().map(|c| c.size().x).fold(0.0, f32::max);
    let mut cells: Vec<Cell> = squares.into_iter().filter(|c| c.size().x > 0.8 * largest).collect();
    cells.sort_by(|a, b| a.center().y.total_cmp(&b.center().y));
    let mut rows: Vec<Vec<Cell>> = vec![];
    for cell in cells {
        match rows.last_mut() {
            Some(row) if (row[0].center().y - cell.center().y).abs() < 0.5 * largest => row.push(cell),
            _ => rows.push(vec![cell]),
        }
    }
    rows.iter_mut().for_each(|row| row.sort_by(|a, b| a.center().x.total_cmp(&b.center().x)));
    rows
}

/// Samples per cell side for the comparison.
const GRID: u32 = 24;

/// The metric: in the Shading-normal view from the front, each row holds groups of
/// `group` cells, the first real geometry and the others normal-mapped copies. For each
/// normal-mapped cell, the mean angle (degrees) between the decoded shading normal at a
/// point and at the same relative point of the geometry cell, over a `GRID`² lattice in
/// the inner 80 % of the cells (away from the anti-aliased borders). Returns every cell's
/// mean angle. The picture is saved in the temporary folder for a look.
fn twin_angles(scene: &Scene, group: usize, name: &str) -> Vec<f32> {
    let mut renderer = renderer();
    renderer.set_scene(scene, Default::default());
    let mut params = default_params(scene);
    params.shading.view = ViewMode::ShadingNormal;
    // Straight from the front, as the models' reference screenshots, and as far as the model's
    // bounding sphere needs (farther than the default framing): perspective then distorts
    // the cells across the picture alike, so relative points of two cells meet.
    params.camera.pitch = 0.0;
    params.camera.distance = bounding_sphere_distance(scene, &params.camera);
    let image = render_image(&mut renderer, [768, 768], &params).unwrap();
    image.save(std::env::temp_dir().join(format!("bumpview-{name}.png"))).unwrap();
    let rows = cell_rows(&image);
    assert_eq!(rows.len(), 5, "{name}: five rows of cells");
    let mut angles = vec![];
    for row in &rows {
        assert_eq!(row.len() % group, 0, "{name}: a row of {} cells", row.len());
        for cells in row.chunks(group) {
            let (geometry, mapped) = (cells[0], &cells[1..]);
            for cell in mapped {
                let mut sum = 0.0;
                for j in 0..GRID {
                    for i in 0..GRID {
                        let f = (Vec2::new(i as f32, j as f32) + 0.5) / GRID as f32 * 0.8 + 0.1;
                        let at = |c: &Cell| {
                            let p = Vec2::new(c.min[0] as f32, c.min[1] as f32) + f * c.size();
                            decode_debug(image.get_pixel(p.x as u32, p.y as u32))
                        };
                        sum += at(&geometry).angle_between(at(cell)).to_degrees();
                    }
                }
                angles.push(sum / (GRID * GRID) as f32);
            }
        }
    }
    angles
}

/// Flips the green channel of every normal map: the classic DirectX/OpenGL mix-up.
fn flip_green(scene: &mut Scene) {
    let maps: Vec<usize> = scene.materials.iter().filter_map(|m| m.normal_map.as_ref().map(|n| n.texture)).collect();
    for texture in maps {
        std::sync::Arc::make_mut(&mut scene.textures[texture]).rgba.chunks_exact_mut(4).for_each(|t| t[1] = 255 - t[1]);
    }
}

/// Bound on each normal-mapped cell's mean angle to its geometry twin, degrees. Measured
/// (768² picture, lavapipe): mean 4.6° over NormalTangentTest's cells and 5.0° over
/// NormalTangentMirrorTest's, worst cell 6.9°. The error is not zero because the twins
/// differ in ways the check must tolerate: the map is an 8-bit bake sampled with bilinear
/// filtering and mips, the real bump is a faceted sphere with interpolated normals that
/// perspective shifts by its height, and at the bump's rim a one-pixel offset between the
/// two rasterisations costs tens of degrees. A flipped green channel mirrors every bump's
/// slope top to bottom: 27–28° per cell, so the bound sits between with room either side.
const TWIN_BOUND_DEG: f32 = 8.0;

#[test]
fn normal_mapped_cells_shade_like_their_geometry_twins() {
    let base = assets();
    let cases = [
        ("gltf/NormalTangentTest/glTF/NormalTangentTest.gltf", 2, "NormalTangentTest"),
        ("gltf/NormalTangentMirrorTest/glTF/NormalTangentMirrorTest.gltf", 4, "NormalTangentMirrorTest"),
    ];
    for (file, group, name) in cases {
        let mut scene = load(&base, file);
        let angles = twin_angles(&scene, group, name);
        let worst = angles.iter().copied().fold(0.0, f32::max);
        let mean = angles.iter().sum::<f32>() / angles.len() as f32;
        println!("{name}: {} mapped cells, mean angle {mean:.2}°, worst cell {worst:.2}°", angles.len());
        assert!(worst < TWIN_BOUND_DEG, "{name}: a normal-mapped cell is {worst:.2}° off its twin: {angles:?}");

        flip_green(&mut scene);
        let flipped = twin_angles(&scene, group, &format!("{name}-flipped-green"));
        let best = flipped.iter().copied().fold(f32::INFINITY, f32::min);
        let mean = flipped.iter().sum::<f32>() / flipped.len() as f32;
        println!("{name} with green flipped: mean angle {mean:.2}°, best cell {best:.2}°");
        assert!(best > TWIN_BOUND_DEG, "{name}: flipping green must fail the check in every cell: {flipped:?}");
    }
}

/// The fraction of covered pixels (away from edges) whose Normal-view normal faces the
/// camera (positive dot with the direction to the eye), and how many pixels were judged.
fn facing_fraction(scene: &Scene, camera: bumpview::scene::OrbitCamera, name: &str) -> (f32, usize) {
    let mut renderer = renderer();
    renderer.set_scene(scene, Default::default());
    let mut params = default_params(scene);
    params.camera = camera;
    params.shading.view = ViewMode::Normal;
    let size = [256, 256];
    let image = render_image(&mut renderer, size, &params).unwrap();
    image.save(std::env::temp_dir().join(format!("bumpview-{name}-normals.png"))).unwrap();
    let background = *image.get_pixel(0, 0);
    let covered = |x: u32, y: u32| (0..3).any(|c| image.get_pixel(x, y)[c].abs_diff(background[c]) > 8);
    let (mut facing, mut judged) = (0, 0);
    for y in 1..size[1] - 1 {
        for x in 1..size[0] - 1 {
            if !(0..9).all(|k| covered(x + k % 3 - 1, y + k / 3 - 1)) {
                continue;
            }
            let pixel = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
            let (_, dir) = camera.ray_through_pixel(pixel, Vec2::new(size[0] as f32, size[1] as f32));
            judged += 1;
            facing += (decode_debug(image.get_pixel(x, y)).dot(-dir) > 0.0) as usize;
        }
    }
    (facing as f32 / judged.max(1) as f32, judged)
}

#[test]
fn back_faces_mirrored_and_computed_normals_face_the_camera() {
    let base = assets();
    let cases = [
        ("gltf/TwoSidedPlane/glTF/TwoSidedPlane.gltf", std::f32::consts::PI, "TwoSidedPlane from behind"),
        ("gltf/NegativeScaleTest/glTF/NegativeScaleTest.gltf", 0.0, "NegativeScaleTest"),
        ("gltf/TextureTransformTest/glTF/TextureTransformTest.gltf", 0.0, "TextureTransformTest"),
        ("obj/spot/spot_quadrangulated.obj", 0.6, "spot (quads, no vn)"),
    ];
    for (file, yaw, name) in cases {
        let scene = load(&base, file);
        let camera = bumpview::scene::OrbitCamera { yaw, pitch: 0.2, ..scene.default_camera };
        let (fraction, judged) = facing_fraction(&scene, camera, &name.replace(' ', "_"));
        println!("{name}: {:.2} % of {judged} pixels face the camera", 100.0 * fraction);
        // Interpolated normals may lean away right at a silhouette; 1 % covers those pixels.
        assert!(judged > 1000 && fraction > 0.99, "{name}: {fraction} of {judged} pixels face the camera");
    }
    // The mirrored copies in NegativeScaleTest are mirror images of the originals.
    let scene = load(&base, "gltf/NegativeScaleTest/glTF/NegativeScaleTest.gltf");
    assert!(scene.instances.iter().any(|i| i.transform.determinant() < 0.0));
}

#[test]
fn obj_map_bump_holding_a_normal_map_fills_the_normal_map_slot() {
    let base = assets();
    let scene = load(&base, "obj/learn-wgpu-cube/cube.obj");
    let material = &scene.materials[scene.instances[0].material];
    assert!(material.normal_map.is_some() && material.height_map.is_none(), "{material:?}");
    assert!(material.base_color_texture.is_some());
}
