//! The parallax family's image error against frame time: every technique and layer count
//! drawn on the GPU and compared, pixel by pixel, with displacement (the ground truth,
//! [`crate::frame::Displacement`]) at a tessellation where its picture has stopped changing
//! (tested on the page: [`super::convergence::reference_step`]).
//!
//! A specimen is a surface, its material and where to look from: `angle` degrees from the
//! surface normal (about +Y, the camera on the +Z side at 0°). Error is the RMSE of the
//! linear RGB channels (sRGB pixels decoded) and the share of pixels whose largest channel
//! differs by more than 5/255; time is the median wall time of a full-quality frame at the
//! picture's size, submitted alone and waited for ([`time_frames`]).

use std::num::NonZeroU32;
use std::path::Path;

use glam::{Mat4, Vec2, Vec3};

use crate::error::{LoadError, RenderError};
use crate::frame::{
    Displacement, FrameParams, FrameQuality, Parallax, ParallaxSettings, SceneOptions, ShadingSettings,
};
use crate::load::add_height_map;
use crate::load::image::load_texture;
use crate::render::capture::{CaptureOptions, render_capture};
use crate::render::timing::{TimedPicture, time_frames};
use crate::render::{Background, Renderer};
use crate::report::gpu_time::gpu_frame_ms;
pub use crate::report::image_error::{ImageError, OFF_BY, image_error};
use crate::scene::builtin::{BRICK_TILE_M, teaching_scene, torus_mesh};
use crate::scene::{Instance, Light, Lights, Mesh, OrbitCamera, Scene, TextureKind};

/// The squares are measured within 0.4 m of their centre: 10 cm inside the border, more
/// than a 2 cm relief moves it at 80° (2 cm · tan 80° = 11 cm... seen along x, the border
/// rows and columns of texels).
pub const MEASURED_HALF_SIZE: f32 = 0.4;
/// The frame's vertical field of view, degrees.
const FOV_Y_DEG: f32 = 50.0;

/// A surface to look at: its scene, the point looked at and from how far, and the
/// displacement level its reference is drawn at.
#[derive(Debug, Clone)]
pub struct Specimen {
    pub name: String,
    pub scene: Scene,
    pub target: Vec3,
    pub distance: f32,
    /// The level where its picture has stopped changing (the page's convergence test,
    /// [`super::convergence::reference_step`], says whether it has).
    pub reference_level: u32,
    /// For a square in the z = 0 plane: errors count only pixels whose view ray meets the
    /// plane within this many metres of the centre along x and y (inside the border, where
    /// displacement lowers the square's edge — a silhouette no parallax technique draws —
    /// and the border would otherwise outweigh the relief). `None`: every pixel.
    pub measured_half_size: Option<f32>,
}

impl Specimen {
    /// The camera `angle_deg` from the normal (+Z at the target), turned about +Y.
    pub fn camera(&self, angle_deg: f32) -> OrbitCamera {
        OrbitCamera {
            target: self.target,
            yaw: angle_deg.to_radians(),
            pitch: 0.0,
            distance: self.distance,
            fov_y: FOV_Y_DEG.to_radians(),
        }
    }

    /// Which pixels of a `size` picture at `angle_deg` count ([`Self::measured_half_size`]).
    pub fn mask(&self, angle_deg: f32, size: [u32; 2]) -> Option<Vec<bool>> {
        let half = self.measured_half_size?;
        let camera = self.camera(angle_deg);
        let dims = Vec2::new(size[0] as f32, size[1] as f32);
        let inside = |x: u32, y: u32| {
            let (origin, dir) = camera.ray_through_pixel(Vec2::new(x as f32 + 0.5, y as f32 + 0.5), dims);
            let t = -origin.z / dir.z;
            let hit = origin + dir * t;
            dir.z.abs() > 1e-6 && t > 0.0 && hit.x.abs() <= half && hit.y.abs() <= half
        };
        Some((0..size[1]).flat_map(|y| (0..size[0]).map(move |x| (x, y))).map(|(x, y)| inside(x, y)).collect())
    }

    /// The frame at `angle_deg` with `parallax`, lit from the upper left in front.
    pub fn params(&self, angle_deg: f32, parallax: ParallaxSettings) -> FrameParams {
        let light = Light::point(self.target + Vec3::new(-0.6, 0.8, 1.0), Vec3::ONE);
        let shading = ShadingSettings { parallax, show_light_marker: false, ..Default::default() };
        FrameParams { camera: self.camera(angle_deg), lights: Lights::one(light, self.scene.ambient), shading }
    }
}

/// A 1 m square in the z = 0 plane facing +Z, two triangles, texture coordinates as on the
/// built-in wall (u along +x, v down, one repeat per [`BRICK_TILE_M`]).
pub fn square_mesh(name: &str) -> Mesh {
    square_mesh_of(name, 1.0)
}

/// [`square_mesh`] `side_m` metres wide, the texture at the same scale (a part of the tile).
pub fn square_mesh_of(name: &str, side_m: f32) -> Mesh {
    let mut mesh = Mesh::empty(name);
    let h = 0.5 * side_m;
    for (x, y) in [(-h, -h), (h, -h), (h, h), (-h, h)] {
        mesh.positions.push(Vec3::new(x, y, 0.0));
        mesh.normals.push(Vec3::Z);
        mesh.uvs.push(Vec2::new((x + 0.5) / BRICK_TILE_M, (0.5 - y) / BRICK_TILE_M));
    }
    mesh.indices = vec![0, 1, 2, 0, 2, 3];
    mesh
}

/// The built-in scene's brick material on `mesh`, alone.
fn bricks_on(mesh: Mesh, material: usize) -> Scene {
    let scene = teaching_scene();
    Scene { meshes: vec![mesh], instances: vec![Instance { mesh: 0, material, transform: Mat4::IDENTITY }], ..scene }
}

/// One square metre of the built-in wall: its bricks (normal map, and the height map
/// spanning 1 cm), seen from 1.3 m.
pub fn wall() -> Specimen {
    wall_of(1.0)
}

/// A square `side_m` metres wide (at most 1) of the built-in wall, seen from 1.3 · `side_m`
/// (the same picture at a larger scale), measured within 0.4 · `side_m` of the centre. Its
/// reference level keeps level 10's triangles per brick on the square metre: one level fewer
/// per halving of the side (each level halves the triangles' edges).
pub fn wall_of(side_m: f32) -> Specimen {
    let scene = bricks_on(square_mesh_of(&format!("wall ({side_m} m square)"), side_m), 0);
    let halvings = (1.0 / side_m).log2().round().max(0.0) as u32;
    Specimen {
        name: "wall".into(),
        scene,
        target: Vec3::ZERO,
        distance: 1.3 * side_m,
        reference_level: 10u32.saturating_sub(halvings),
        measured_half_size: Some(MEASURED_HALF_SIZE * side_m),
    }
}

/// The built-in torus (96 × 32 quads, bricks, 1 cm relief) alone, seen from 1.6 m.
pub fn torus() -> Specimen {
    let scene = bricks_on(torus_mesh(96, 32), 1);
    Specimen {
        name: "torus".into(),
        scene,
        target: Vec3::ZERO,
        distance: 1.6,
        reference_level: 5,
        measured_half_size: None,
    }
}

/// ambientCG's Rock058 (colour and displacement, white = high; the normal map made from the
/// displacement) on a square metre, its relief spanning 2 cm, seen from 1.3 m.
pub fn rock(assets: &Path) -> Result<Specimen, LoadError> {
    let folder = assets.join("textures/ambientCG_Rock058");
    let mut scene = bricks_on(square_mesh("rock (1 m²)"), 0);
    scene.materials.truncate(1);
    scene.textures = vec![load_texture(&folder.join("albedo.jpg"), TextureKind::Color)?.into()];
    scene.materials[0].base_color_texture = Some(0);
    scene.materials[0].name = "Rock058".into();
    add_height_map(&mut scene, &[0], load_texture(&folder.join("displacement.jpg"), TextureKind::Height)?, 2.0);
    Ok(Specimen {
        name: "Rock058".into(),
        scene,
        target: Vec3::ZERO,
        distance: 1.3,
        reference_level: 10,
        measured_half_size: Some(MEASURED_HALF_SIZE),
    })
}

/// Draws pictures of one specimen: one renderer, the scene uploaded per displacement level.
pub struct Bench<'a> {
    pub renderer: &'a mut Renderer,
    pub specimen: &'a Specimen,
    pub size: [u32; 2],
    /// The displacement level the scene is uploaded with now (0: none).
    uploaded: Option<u32>,
}

impl<'a> Bench<'a> {
    pub fn new(renderer: &'a mut Renderer, specimen: &'a Specimen, size: [u32; 2]) -> Self {
        Bench { renderer, specimen, size, uploaded: None }
    }

    /// Uploads the specimen displaced at `level` (0: not), unless it is already.
    fn upload(&mut self, level: u32) {
        if self.uploaded != Some(level) {
            let options = SceneOptions {
                parallax: level == 0,
                cone_maps: level == 0,
                displacement: Displacement { level, ..Default::default() },
                ..Default::default()
            };
            self.renderer.set_scene(&self.specimen.scene, options);
            self.uploaded = Some(level);
        }
    }

    /// The picture at `angle_deg` with `parallax` (displacement level 0) or displaced at
    /// `level` (parallax off).
    pub fn picture(
        &mut self,
        angle_deg: f32,
        parallax: ParallaxSettings,
        level: u32,
    ) -> Result<image::RgbaImage, RenderError> {
        self.upload(level);
        let options = CaptureOptions { size: self.size, background: Background::Opaque, supersample: 1 };
        render_capture(self.renderer, &options, &self.specimen.params(angle_deg, parallax))
    }

    /// The median frame time (ms) of [`Self::picture`]'s frame over `frames` frames: GPU time
    /// between timestamps where the device has them ([`gpu_frame_ms`]), else wall time with a
    /// wait ([`time_frames`]).
    pub fn frame_ms(
        &mut self,
        angle_deg: f32,
        parallax: ParallaxSettings,
        level: u32,
        frames: NonZeroU32,
    ) -> Result<f64, RenderError> {
        self.upload(level);
        let params = self.specimen.params(angle_deg, parallax);
        if let Some(ms) = gpu_frame_ms(self.renderer, &params, self.size, frames)? {
            return Ok(ms);
        }
        let picture = TimedPicture { params: &params, split: None, view_size: self.size, quality: FrameQuality::FULL };
        Ok(time_frames(self.renderer, &picture, frames)?.frame_ms)
    }
}

/// A technique at a layer count (`layers` for the searches; `None` otherwise).
pub fn settings(technique: Parallax, layers: Option<u32>) -> ParallaxSettings {
    let n = layers.unwrap_or(1);
    ParallaxSettings { technique, layers_min: n, layers_max: n, ..Default::default() }
}

/// What the study draws.
#[derive(Debug, Clone, PartialEq)]
pub struct ParallaxPlan {
    /// Camera angles from the normal, degrees.
    pub angles_deg: Vec<f32>,
    /// Layer counts of the searches (steep, occlusion, relief; min = max).
    pub layers: Vec<u32>,
    /// Picture size, pixels.
    pub size: [u32; 2],
    /// Frames timed per case.
    pub frames: NonZeroU32,
    /// The built-in torus besides the wall.
    pub torus: bool,
    /// Where the shared assets are (Rock058); `None`: the rock is left out.
    pub assets: Option<std::path::PathBuf>,
    /// Reference levels lowered by this many (a quicker, coarser reference).
    pub coarser_by: u32,
    /// The side of the wall's square, metres (1; the quick run's is smaller, so the same
    /// triangles per brick take fewer triangles: [`wall_of`]).
    pub wall_side_m: f32,
    /// Displacement levels below the reference drawn for its convergence (at [`Self::convergence_angle_deg`]).
    pub convergence_levels: u32,
    pub convergence_angle_deg: f32,
}

impl ParallaxPlan {
    /// Wall, torus and Rock058 at 0°, 45°, 70° and 80°, 4 to 64 layers, 1280 × 720.
    pub fn full(assets: Option<std::path::PathBuf>) -> ParallaxPlan {
        ParallaxPlan {
            angles_deg: vec![0.0, 45.0, 70.0, 80.0],
            layers: vec![4, 8, 16, 32, 64],
            size: [1280, 720],
            frames: NonZeroU32::new(3).expect("3"),
            torus: true,
            assets,
            coarser_by: 0,
            wall_side_m: 1.0,
            convergence_levels: 4,
            convergence_angle_deg: 70.0,
        }
    }

    /// The wall alone at 0° and 70°, 8 and 32 layers, 320 × 180, a coarser reference.
    pub fn quick() -> ParallaxPlan {
        ParallaxPlan {
            angles_deg: vec![0.0, 70.0],
            layers: vec![8, 32],
            size: [320, 180],
            frames: NonZeroU32::new(1).expect("1"),
            torus: false,
            assets: None,
            coarser_by: 1,
            wall_side_m: 0.5,
            convergence_levels: 1,
            convergence_angle_deg: 70.0,
        }
    }
}

/// One picture measured: a technique (a [`Parallax`] name, or `displacement`) at a layer
/// count or displacement level, against the specimen's reference at one angle.
#[derive(Debug, Clone, PartialEq)]
pub struct ParallaxRow {
    pub specimen: String,
    pub angle_deg: f32,
    pub technique: &'static str,
    pub layers: Option<u32>,
    pub level: Option<u32>,
    pub error: ImageError,
    /// Median frame time, ms.
    pub frame_ms: f64,
}

/// The name of displacement's rows.
pub const DISPLACEMENT: &str = "displacement";

/// Every technique the study draws with its layer counts: the ones without a search once.
pub fn cases(layers: &[u32]) -> Vec<(Parallax, Option<u32>)> {
    let mut cases = vec![(Parallax::default(), None)];
    for technique in Parallax::shifting() {
        match technique.marches() {
            true => cases.extend(layers.iter().map(|&n| (technique, Some(n)))),
            false => cases.push((technique, None)),
        }
    }
    cases
}

/// The specimens of `plan`; a failure to read the rock is returned as a line for the page.
pub fn specimens(plan: &ParallaxPlan) -> (Vec<Specimen>, Option<String>) {
    let mut list = vec![wall_of(plan.wall_side_m)];
    if plan.torus {
        list.push(torus());
    }
    let mut skipped = None;
    match &plan.assets {
        Some(assets) => match rock(assets) {
            Ok(rock) => list.push(rock),
            Err(e) => skipped = Some(format!("Rock058 left out: {e}")),
        },
        None => skipped = Some("Rock058 left out: no shared assets given (--assets or BUMPVIEW_TEST_ASSETS)".into()),
    }
    for specimen in &mut list {
        specimen.reference_level = specimen.reference_level.saturating_sub(plan.coarser_by).max(1);
    }
    (list, skipped)
}

/// Measures every case of `plan` on `specimen`: the references at every angle, displacement
/// at the levels below its reference (at the convergence angle), then every technique.
/// `step()` is called after each case.
pub fn measure_specimen(
    renderer: &mut Renderer,
    specimen: &Specimen,
    plan: &ParallaxPlan,
    step: &mut dyn FnMut(),
) -> Result<Vec<ParallaxRow>, RenderError> {
    let mut bench = Bench::new(renderer, specimen, plan.size);
    let off = settings(Parallax::default(), None);
    let reference_level = specimen.reference_level;
    let mut rows = vec![];
    let mut references = vec![];
    let masks: Vec<Option<Vec<bool>>> = plan.angles_deg.iter().map(|&a| specimen.mask(a, plan.size)).collect();
    for (&angle, mask) in plan.angles_deg.iter().zip(&masks) {
        let reference = bench.picture(angle, off, reference_level)?;
        let frame_ms = bench.frame_ms(angle, off, reference_level, plan.frames)?;
        let error = image_error(&reference, &reference, mask.as_deref());
        let row = ParallaxRow {
            specimen: specimen.name.clone(),
            angle_deg: angle,
            technique: DISPLACEMENT,
            layers: None,
            level: Some(reference_level),
            error,
            frame_ms,
        };
        rows.push(row);
        references.push(reference);
        step();
    }
    let at = plan.angles_deg.iter().position(|&a| a == plan.convergence_angle_deg);
    if let Some(at) = at {
        let angle = plan.angles_deg[at];
        for level in (1..reference_level).rev().take(plan.convergence_levels as usize) {
            let image = bench.picture(angle, off, level)?;
            let frame_ms = bench.frame_ms(angle, off, level, plan.frames)?;
            let row = ParallaxRow {
                specimen: specimen.name.clone(),
                angle_deg: angle,
                technique: DISPLACEMENT,
                layers: None,
                level: Some(level),
                error: image_error(&image, &references[at], masks[at].as_deref()),
                frame_ms,
            };
            rows.push(row);
            step();
        }
    }
    for ((&angle, reference), mask) in plan.angles_deg.iter().zip(&references).zip(&masks) {
        for (technique, layers) in cases(&plan.layers) {
            let parallax = settings(technique, layers);
            let image = bench.picture(angle, parallax, 0)?;
            let frame_ms = bench.frame_ms(angle, parallax, 0, plan.frames)?;
            let row = ParallaxRow {
                specimen: specimen.name.clone(),
                angle_deg: angle,
                technique: technique.into(),
                layers,
                level: None,
                error: image_error(&image, reference, mask.as_deref()),
                frame_ms,
            };
            rows.push(row);
            step();
        }
    }
    Ok(rows)
}

/// Cases [`measure_specimen`] measures per specimen.
pub fn case_count(plan: &ParallaxPlan, reference_level: u32) -> usize {
    let convergence = (reference_level.saturating_sub(1) as usize).min(plan.convergence_levels as usize);
    let convergence = if plan.angles_deg.contains(&plan.convergence_angle_deg) { convergence } else { 0 };
    plan.angles_deg.len() * (1 + cases(&plan.layers).len()) + convergence
}
