//! The built-in teaching scene: a brick wall in the XY plane facing +Z, a brick floor in the
//! XZ plane facing +Y, and a brick torus with its analytic tangent frame, all shaded with a
//! brick normal map made at start-up from a procedural height field.

use std::f32::consts::TAU;

use glam::{Mat4, Vec2, Vec3, Vec4};

use super::bricks::{brick_color_texture, brick_height_field};
use super::{HeightMap, Instance, Light, Material, Mesh, NormalMap, OrbitCamera, Scene};
use crate::height::{Border, Kernel};
use crate::names::Named;

/// Metres covered by one repeat of the brick texture on the wall and floor.
pub const BRICK_TILE_M: f32 = 1.0;
/// The wall: x in `WALL_X`, y in `WALL_Y`, at z = `WALL_Z`.
pub const WALL_X: [f32; 2] = [-2.0, 2.0];
pub const WALL_Y: [f32; 2] = [0.0, 3.0];
pub const WALL_Z: f32 = -1.0;
/// The floor: x in `WALL_X`, z in `FLOOR_Z`, at y = 0.
pub const FLOOR_Z: [f32; 2] = [WALL_Z, 2.0];
/// Torus radii (metres) and centre; its axis is +Z, so it faces the default camera.
pub const TORUS_MAJOR_RADIUS: f32 = 0.45;
pub const TORUS_MINOR_RADIUS: f32 = 0.18;
pub const TORUS_CENTER: Vec3 = Vec3::new(1.0, 0.65, 0.2);

/// The wall's texture coordinates at a point on it (tile repeats, v down the image):
/// u runs along +X and the image's up (−v) along +Y.
pub fn wall_uv(p: Vec3) -> Vec2 {
    Vec2::new((p.x - WALL_X[0]) / BRICK_TILE_M, (WALL_Y[1] - p.y) / BRICK_TILE_M)
}

/// The floor's texture coordinates: u along +X, the image's up along −Z (away from the default camera).
pub fn floor_uv(p: Vec3) -> Vec2 {
    Vec2::new((p.x - WALL_X[0]) / BRICK_TILE_M, (p.z - FLOOR_Z[0]) / BRICK_TILE_M)
}

/// A flat rectangle split into `cells × cells` quads with one normal and UVs from `uv_of`.
fn grid_plane(name: &str, corner: Vec3, edge_u: Vec3, edge_v: Vec3, normal: Vec3, uv_of: fn(Vec3) -> Vec2) -> Mesh {
    const CELLS: u32 = 8;
    let mut mesh = Mesh::empty(name);
    // u runs along edge_u; the image's up is cross(N, T), so w = +1 (see wall_uv, floor_uv).
    let analytic = edge_u.normalize().extend(1.0);
    for j in 0..=CELLS {
        for i in 0..=CELLS {
            let p = corner + edge_u * (i as f32 / CELLS as f32) + edge_v * (j as f32 / CELLS as f32);
            mesh.positions.push(p);
            mesh.normals.push(normal);
            mesh.uvs.push(uv_of(p));
        }
    }
    mesh.analytic_tangents = Some(vec![analytic; mesh.positions.len()]);
    let stride = CELLS + 1;
    for j in 0..CELLS {
        for i in 0..CELLS {
            let a = j * stride + i;
            let quad = [a, a + 1, a + stride + 1, a, a + stride + 1, a + stride];
            mesh.indices.extend(quad);
        }
    }
    // Make every triangle counter-clockwise as seen from the side the normal points to.
    let (p0, p1, p2) = (mesh.positions[0], mesh.positions[1], mesh.positions[stride as usize + 1]);
    if (p1 - p0).cross(p2 - p0).dot(normal) < 0.0 {
        mesh.indices.chunks_exact_mut(3).for_each(|tri| tri.swap(1, 2));
    }
    mesh
}

pub fn wall_mesh() -> Mesh {
    let corner = Vec3::new(WALL_X[0], WALL_Y[0], WALL_Z);
    let width = WALL_X[1] - WALL_X[0];
    let height = WALL_Y[1] - WALL_Y[0];
    grid_plane("wall", corner, Vec3::X * width, Vec3::Y * height, Vec3::Z, wall_uv)
}

pub fn floor_mesh() -> Mesh {
    let corner = Vec3::new(WALL_X[0], 0.0, FLOOR_Z[0]);
    let width = WALL_X[1] - WALL_X[0];
    let depth = FLOOR_Z[1] - FLOOR_Z[0];
    grid_plane("floor", corner, Vec3::X * width, Vec3::Z * depth, Vec3::Y, floor_uv)
}

/// The torus `P(s, t) = ((R + r cos t) cos s, (R + r cos t) sin s, r sin t)` about the
/// origin, axis +Z, with its analytic frame: `T = ∂P/∂s / |∂P/∂s|`, `N` outward,
/// `B = ∂P/∂t / |∂P/∂t| = cross(N, T)`, so `w = +1`. The texture repeats `u_repeats` times
/// around the ring and once around the tube; the image's up follows increasing `t`.
pub fn torus_mesh(segments: u32, sides: u32) -> Mesh {
    let (big_r, r) = (TORUS_MAJOR_RADIUS, TORUS_MINOR_RADIUS);
    let u_repeats = (TAU * big_r / BRICK_TILE_M).round().max(1.0);
    let v_repeats = 1.0;
    let mut mesh = Mesh::empty("torus");
    let mut analytic = vec![];
    for j in 0..=sides {
        let t = TAU * j as f32 / sides as f32;
        for i in 0..=segments {
            let s = TAU * i as f32 / segments as f32;
            let (sin_s, cos_s) = s.sin_cos();
            let (sin_t, cos_t) = t.sin_cos();
            let ring = big_r + r * cos_t;
            mesh.positions.push(Vec3::new(ring * cos_s, ring * sin_s, r * sin_t));
            mesh.normals.push(Vec3::new(cos_t * cos_s, cos_t * sin_s, sin_t));
            mesh.uvs
                .push(Vec2::new(u_repeats * i as f32 / segments as f32, v_repeats * (1.0 - j as f32 / sides as f32)));
            analytic.push(Vec4::new(-sin_s, cos_s, 0.0, 1.0));
        }
    }
    mesh.analytic_tangents = Some(analytic);
    let stride = segments + 1;
    for j in 0..sides {
        for i in 0..segments {
            let a = j * stride + i;
            // (s, t) increase along (T, B); with N = cross(T, B) outward this order is counter-clockwise.
            mesh.indices.extend([a, a + 1, a + stride + 1, a, a + stride + 1, a + stride]);
        }
    }
    mesh
}

/// The default view: wall, floor and torus together, from the front and a little above.
pub fn default_camera() -> OrbitCamera {
    OrbitCamera { target: Vec3::new(0.0, 1.0, 0.0), yaw: 0.35, pitch: 0.3, distance: 5.0, fov_y: 50f32.to_radians() }
}

pub fn default_light() -> Light {
    Light::point(Vec3::new(-0.8, 2.0, 1.2), Vec3::ONE)
}

/// Builds the whole scene with the brick normal map made by the central-difference kernel
/// and the brick height map (for bump mapping in the shader).
/// Every mesh carries its analytic frame; none supplies tangents, so MikkTSpace makes them.
pub fn teaching_scene() -> Scene {
    teaching_scene_with_kernel(Kernel::CentralDifference)
}

/// [`teaching_scene`] with the brick normal map made from the height field by `kernel`.
pub fn teaching_scene_with_kernel(kernel: Kernel) -> Scene {
    let height = brick_height_field(BRICK_TILE_M);
    let textures = vec![
        brick_color_texture(),
        height.to_normal_map(kernel, Border::Wrap, &format!("bricks (normal map, {} kernel)", kernel.name())),
        height.to_height_texture("bricks (height)"),
    ];
    let bricks = Material {
        name: "bricks".into(),
        base_color_factor: Vec4::ONE,
        base_color_texture: Some(0),
        normal_map: Some(NormalMap::new(1, 1.0)),
        height_map: Some(HeightMap { kernel, ..HeightMap::new(2, height.range_m) }),
        specular: Vec3::splat(0.25),
        shininess: 32.0,
        double_sided: true,
        ..Material::default()
    };
    let torus_material = Material { double_sided: false, ..bricks.clone() };
    Scene {
        meshes: vec![wall_mesh(), floor_mesh(), torus_mesh(96, 32)],
        materials: vec![bricks, torus_material],
        textures: textures.into_iter().map(Into::into).collect(),
        instances: vec![
            Instance { mesh: 0, material: 0, transform: Mat4::IDENTITY },
            Instance { mesh: 1, material: 0, transform: Mat4::IDENTITY },
            Instance { mesh: 2, material: 1, transform: Mat4::from_translation(TORUS_CENTER) },
        ],
        ambient: Vec3::splat(0.08),
        default_light: default_light(),
        default_camera: default_camera(),
        files: vec![],
        warnings: vec![],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::tangent::bitangent;

    #[test]
    fn torus_frame_is_right_handed_and_matches_its_parameter_directions() {
        let mesh = torus_mesh(24, 12);
        let tangents = mesh.analytic_tangents.as_ref().unwrap();
        let stride = 25;
        for j in 0..12 {
            for i in 0..24 {
                let a = j * stride + i;
                let n = mesh.normals[a];
                let t = tangents[a];
                let dp_ds = mesh.positions[a + 1] - mesh.positions[a];
                let dp_dt = mesh.positions[a + stride] - mesh.positions[a];
                assert!(t.truncate().dot(dp_ds.normalize()) > 0.99);
                assert!(bitangent(n, t).dot(dp_dt.normalize()) > 0.95);
                // Up the image (−v) is the +t direction.
                assert!(mesh.uvs[a + stride].y < mesh.uvs[a].y);
            }
        }
    }

    #[test]
    fn triangles_face_along_their_normals() {
        for mesh in [wall_mesh(), floor_mesh(), torus_mesh(24, 12)] {
            for tri in mesh.indices.chunks_exact(3) {
                let [a, b, c] = [0, 1, 2].map(|k| mesh.positions[tri[k] as usize]);
                let face = (b - a).cross(c - a);
                if face.length() > 1e-9 {
                    assert!(face.dot(mesh.normals[tri[0] as usize]) > 0.0, "{}", mesh.name);
                }
            }
        }
    }
}
