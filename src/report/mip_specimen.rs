//! The mip-filter study's specimens ([`super::mip_study`]): a synthetic normal map of fine
//! bumps with a known slope variance, on a plane and on the built-in torus, each with its UVs
//! tiled so that a texel of level 0 spans `1/k` of a pixel's width: **k× minification**, mip
//! level `log2 k`. The camera and the point light move together (a pan), so on the plane —
//! parallel to the image plane — a pan is an exact translation of the picture.

use std::f32::consts::TAU;

use glam::{Mat4, Vec2, Vec3, Vec4};

use crate::frame::{FrameParams, ShadingSettings};
use crate::scene::builtin::{TORUS_MAJOR_RADIUS, TORUS_MINOR_RADIUS, default_camera, default_light, torus_mesh};
use crate::scene::{Instance, Light, Lights, Material, Mesh, NormalMap, OrbitCamera, Scene, TextureKind};
use crate::texture::TextureImage;

/// Texels along each side of the synthetic normal map.
pub const MAP_SIDE: u32 = 128;
/// Vertical field of view of every specimen's camera, degrees.
const FOV_Y_DEG: f32 = 50.0;
/// The Blinn-Phong exponent of the specimens' material.
pub const SHININESS: f32 = 64.0;

/// The waves of the height field, `(p, q, phase)`: `h = Σ a sin(2π(p·x + q·y)/side + phase)`
/// with integer `p, q` (so the map tiles), wavelengths of 10 to 26 texels: smooth between
/// texels (bilinear reads follow them), many to a pixel at 16× and 64×.
const WAVES: [(f32, f32, f32); 6] =
    [(11.0, 3.0, 0.3), (-4.0, 10.0, 1.7), (7.0, -8.0, 2.9), (2.0, 13.0, 4.1), (-12.0, -5.0, 5.3), (3.0, 4.0, 0.9)];

/// Standard deviation of each slope component (∂h/∂x, ∂h/∂y) over the map: every wave has
/// the same slope amplitude, scaled so that `(σx² + σy²)/2` is this squared.
pub const SLOPE_SIGMA: f32 = 0.35;

/// The synthetic tangent-space normal map (OpenGL convention): `n = normalize(−∂h/∂x,
/// −∂h/∂y, 1)` of [`WAVES`] sampled at texel centres, `x` right and `y` up the image.
pub fn normal_map() -> TextureImage {
    let side = MAP_SIDE as f32;
    // Each wave's slope amplitude c: Σ c²/2 over the two components is 2σ².
    let c = (4.0 * SLOPE_SIGMA * SLOPE_SIGMA / WAVES.len() as f32).sqrt();
    let mut rgba = Vec::with_capacity((MAP_SIDE * MAP_SIDE * 4) as usize);
    for row in 0..MAP_SIDE {
        for column in 0..MAP_SIDE {
            let (x, y) = (column as f32 + 0.5, -(row as f32 + 0.5));
            let mut slope = Vec2::ZERO;
            for (p, q, phase) in WAVES {
                let direction = Vec2::new(p, q);
                let cos = (TAU * direction.dot(Vec2::new(x, y)) / side + phase).cos();
                slope += c * cos * direction / direction.length();
            }
            let n = Vec3::new(-slope.x, -slope.y, 1.0).normalize();
            rgba.extend((n * 0.5 + 0.5).to_array().map(|v| (v * 255.0).round() as u8));
            rgba.push(255);
        }
    }
    TextureImage::new("fine bumps (normal map)", MAP_SIDE, MAP_SIDE, TextureKind::NormalMap, rgba)
}

/// Which surface.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Shape {
    /// A 1.2 m square facing the camera, filling the picture.
    Plane,
    /// The built-in torus (96 × 32 quads), its axis towards the camera.
    Torus,
}

impl Shape {
    pub fn name(self) -> &'static str {
        match self {
            Shape::Plane => "plane",
            Shape::Torus => "torus",
        }
    }

    /// Camera distance from the target, metres.
    fn distance(self) -> f32 {
        match self {
            Shape::Plane => 0.9,
            Shape::Torus => 1.6,
        }
    }

    /// The light's offset from the camera's target, metres.
    fn light_offset(self) -> Vec3 {
        match self {
            Shape::Plane => Vec3::new(-0.25, 0.2, 0.8),
            Shape::Torus => Vec3::new(-0.5, 0.6, 1.4),
        }
    }

    /// Depth from the eye where texel size is set to `1/k` pixel: the plane, or the front of
    /// the torus's tube.
    fn measured_depth(self) -> f32 {
        match self {
            Shape::Plane => self.distance(),
            Shape::Torus => self.distance() - TORUS_MINOR_RADIUS,
        }
    }
}

/// A specimen at one minification.
#[derive(Debug, Clone)]
pub struct MipSpecimen {
    pub shape: Shape,
    /// Texels of level 0 per pixel along each side (at [`Shape::measured_depth`]).
    pub minification: u32,
    /// Picture size, pixels (square).
    pub size: u32,
    pub scene: Scene,
}

impl MipSpecimen {
    /// `shape` at `minification` for `size × size` pictures.
    pub fn new(shape: Shape, minification: u32, size: u32) -> MipSpecimen {
        let pixel_m = 2.0 * shape.measured_depth() * (FOV_Y_DEG.to_radians() / 2.0).tan() / size as f32;
        let texels_per_m = minification as f32 / pixel_m;
        let mesh = match shape {
            Shape::Plane => plane(1.2, texels_per_m / MAP_SIDE as f32),
            Shape::Torus => {
                let mut mesh = torus_mesh(96, 32);
                // The built-in UVs span [0, u_repeats] × [0, 1]: rescale both to whole repeats
                // at the asked texel density.
                let u_max = mesh.uvs.iter().map(|uv| uv.x).fold(1.0f32, f32::max);
                let repeats = |length_m: f32| (length_m * texels_per_m / MAP_SIDE as f32).round().max(1.0);
                let scale = Vec2::new(repeats(TAU * TORUS_MAJOR_RADIUS) / u_max, repeats(TAU * TORUS_MINOR_RADIUS));
                mesh.uvs.iter_mut().for_each(|uv| *uv *= scale);
                mesh
            }
        };
        let material = Material {
            name: "fine bumps".into(),
            base_color_factor: Vec4::new(0.3, 0.3, 0.3, 1.0),
            normal_map: Some(NormalMap::new(0, 1.0)),
            specular: Vec3::splat(0.6),
            shininess: SHININESS,
            ..Material::default()
        };
        let scene = Scene {
            meshes: vec![mesh],
            materials: vec![material],
            textures: vec![normal_map().into()],
            instances: vec![Instance { mesh: 0, material: 0, transform: Mat4::IDENTITY }],
            ambient: Vec3::splat(0.03),
            default_light: default_light(),
            default_camera: default_camera(),
            files: vec![],
            warnings: vec![],
        };
        MipSpecimen { shape, minification, size, scene }
    }

    /// The width of a pixel at the target's depth, metres.
    pub fn pixel_m(&self) -> f32 {
        2.0 * self.shape.distance() * (FOV_Y_DEG.to_radians() / 2.0).tan() / self.size as f32
    }

    /// The frame panned `pan_px` pixels (at the target's depth) to the right: the camera's
    /// target and the light move together along +x.
    pub fn params(&self, pan_px: f32, shading: ShadingSettings) -> FrameParams {
        let target = Vec3::X * pan_px * self.pixel_m();
        let camera = OrbitCamera {
            target,
            yaw: 0.0,
            pitch: 0.0,
            distance: self.shape.distance(),
            fov_y: FOV_Y_DEG.to_radians(),
        };
        let light = Light::point(target + self.shape.light_offset(), Vec3::ONE);
        let shading = ShadingSettings { show_light_marker: false, ..shading };
        FrameParams { camera, lights: Lights::one(light, self.scene.ambient), shading }
    }
}

/// A square of side `side_m` in the z = 0 plane facing +Z, centred on the origin, its UVs
/// `uv_per_m` per metre (u along +x, v down).
fn plane(side_m: f32, uv_per_m: f32) -> Mesh {
    let mut mesh = Mesh::empty("plane");
    let h = side_m / 2.0;
    for (x, y) in [(-h, -h), (h, -h), (h, h), (-h, h)] {
        mesh.positions.push(Vec3::new(x, y, 0.0));
        mesh.normals.push(Vec3::Z);
        mesh.uvs.push(Vec2::new(x, -y) * uv_per_m);
    }
    mesh.indices = vec![0, 1, 2, 0, 2, 3];
    mesh
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The decoded map's slope components have the stated spread (8-bit steps and the finite
    /// sum of waves: within 3 %), and no mean tilt.
    #[test]
    fn the_map_has_its_stated_slope_spread() {
        let map = normal_map();
        let slopes: Vec<Vec2> = map
            .rgba
            .chunks_exact(4)
            .map(|t| {
                let n = Vec3::new(t[0] as f32, t[1] as f32, t[2] as f32) / 127.5 - 1.0;
                Vec2::new(-n.x / n.z, -n.y / n.z)
            })
            .collect();
        let count = slopes.len() as f32;
        let mean = slopes.iter().copied().sum::<Vec2>() / count;
        let variance = slopes.iter().map(|s| (*s - mean).length_squared()).sum::<f32>() / count / 2.0;
        assert!(mean.length() < 0.01, "{mean}");
        assert!((variance.sqrt() / SLOPE_SIGMA - 1.0).abs() < 0.03, "{}", variance.sqrt());
    }

    /// A texel spans 1/k of a pixel on the plane: the UVs cross k · side / MAP_SIDE repeats
    /// over `side` pixels.
    #[test]
    fn the_plane_is_tiled_to_its_minification() {
        let specimen = MipSpecimen::new(Shape::Plane, 16, 64);
        let mesh = &specimen.scene.meshes[0];
        let uv_per_m = (mesh.uvs[1].x - mesh.uvs[0].x) / (mesh.positions[1].x - mesh.positions[0].x);
        let texels_per_pixel = uv_per_m * MAP_SIDE as f32 * specimen.pixel_m();
        assert!((texels_per_pixel - 16.0).abs() < 1e-3, "{texels_per_pixel}");
    }
}
