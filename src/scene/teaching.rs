//! Built-in scenes made for one lesson's point ([`TeachingScene`]): the teaching scene of
//! [`super::builtin`] with its wall replaced by a panel that shows a mistake the plain wall
//! hides, a coarse sphere, or the bricks with a gloss map or packed as X-Ray's bump pair.
//! A preset selects one by name (`[files] builtin = "mirrored-wall"`).

use std::f32::consts::{PI, TAU};

use glam::{Mat4, Vec2, Vec3, Vec4};
use serde::{Deserialize, Serialize};

use super::bricks::brick_height_field;
use super::builtin::{
    BRICK_TILE_M, WALL_X, WALL_Y, WALL_Z, floor_mesh, teaching_scene_with_kernel, wall_mesh, wall_uv,
};
use super::material::Clearcoat;
use super::{Instance, Mesh, NormalMap, Scene, TextureImage, TextureKind};
use crate::height::Kernel;

/// Radius of [`TeachingScene::CoarseSphere`]'s sphere, metres, and its centre.
pub const SPHERE_RADIUS: f32 = 0.8;
pub const SPHERE_CENTER: Vec3 = Vec3::new(0.0, 1.0, 0.0);
/// Its segments around the axis and rings pole to pole: 30° per edge.
pub const SPHERE_SEGMENTS: u32 = 12;
pub const SPHERE_RINGS: u32 = 6;
/// How far [`TeachingScene::BentWall`]'s normals lean at the wall's edges (the normal at a
/// point is `normalize(Z + BEND · offset)`, the offset from the centre in half-widths).
pub const BEND: f32 = 0.9;

/// A built-in scene; [`TeachingScene::Bricks`] is the teaching scene itself.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize, strum::IntoStaticStr, strum::VariantArray,
)]
#[serde(rename_all = "kebab-case")]
#[strum(serialize_all = "kebab-case")]
pub enum TeachingScene {
    /// Wall, floor and torus ([`super::builtin::teaching_scene`]).
    #[default]
    Bricks,
    /// The wall's right half carries the texture mirrored (u runs −X), as a symmetric
    /// model's second half does: its tangents have `w = −1`.
    MirroredWall,
    /// The wall with bent vertex normals (a cushion: they lean out by up to [`BEND`] towards
    /// the edges) and supplied tangents along the flat wall, as averaged from its faces: the
    /// tangents are not orthogonal to the normals.
    BentWall,
    /// A UV sphere of [`SPHERE_SEGMENTS`] × [`SPHERE_RINGS`] quads on the floor, no wall, no
    /// torus: large triangles, between whose vertices per-vertex lighting shows.
    CoarseSphere,
    /// The bricks with a gloss map: the brick faces shiny, the mortar dull (gloss follows height).
    GlossyBricks,
    /// The bricks' normal map packed as X-Ray's bump texture: the normal in A, B, G and the
    /// gloss's square root in R.
    XrayBricks,
    /// The bricks under a smooth clear coat (`KHR_materials_clearcoat`, no coat normal map):
    /// the base bumped, the coat's normal the surface's.
    ClearcoatBricks,
    /// Every material's normal map large waves (a sine pair tilting up to 59°), a fine ripple
    /// detail map tiled four times over it ([`super::DetailMap`]): where the detail blends differ.
    DetailWaves,
}

impl TeachingScene {
    /// The scene, its brick normal map made by `kernel`.
    pub fn build(self, kernel: Kernel) -> Scene {
        let mut scene = teaching_scene_with_kernel(kernel);
        match self {
            TeachingScene::Bricks => {}
            TeachingScene::MirroredWall => scene.meshes[0] = mirrored_wall_mesh(),
            TeachingScene::BentWall => scene.meshes[0] = bent_wall_mesh(),
            TeachingScene::CoarseSphere => {
                scene.meshes = vec![floor_mesh(), sphere_mesh()];
                scene.instances = vec![
                    Instance { mesh: 0, material: 0, transform: Mat4::IDENTITY },
                    Instance { mesh: 1, material: 1, transform: Mat4::from_translation(SPHERE_CENTER) },
                ];
            }
            TeachingScene::GlossyBricks => {
                scene.textures.push(gloss_texture().into());
                let gloss = scene.textures.len() - 1;
                scene.materials.iter_mut().for_each(|m| m.gloss_texture = Some(gloss));
            }
            TeachingScene::XrayBricks => {
                let packed = xray_texture(&scene.textures[1]);
                scene.textures.push(packed.into());
                let bump = scene.textures.len() - 1;
                scene.materials.iter_mut().for_each(|m| m.normal_map = Some(NormalMap::xray(bump, None)));
            }
            TeachingScene::ClearcoatBricks => {
                for material in &mut scene.materials {
                    material.roughness = 0.6;
                    material.clearcoat = Some(Clearcoat {
                        factor: 1.0,
                        texture: None,
                        roughness: 0.1,
                        roughness_texture: None,
                        normal_map: None,
                        uv_transform: Clearcoat::SAME_UV,
                    });
                }
            }
            TeachingScene::DetailWaves => {
                scene.textures.push(super::sine_pair_normal_map(256, 1, 1.2).into());
                scene.textures.push(super::sine_pair_normal_map(64, 2, 0.8).into());
                let (base, detail) = (scene.textures.len() - 2, scene.textures.len() - 1);
                for material in &mut scene.materials {
                    material.normal_map = Some(NormalMap::new(base, 1.0));
                    material.height_map = None;
                    let map = super::DetailMap::new(detail, super::DetailBlend::default());
                    material.detail_map = Some(super::DetailMap { tiling: 4.0, ..map });
                }
            }
        }
        scene
    }
}

/// The wall's texture coordinates mirrored about x = 0 (right half: u runs −X).
fn mirrored_uv(p: Vec3) -> Vec2 {
    wall_uv(Vec3::new(-p.x.abs(), p.y, p.z))
}

/// The wall of two halves, each its own vertices (the seam is split, as exporters split it):
/// the left half as [`wall_mesh`], the right half with [`mirrored_uv`].
fn mirrored_wall_mesh() -> Mesh {
    let mut mesh = wall_mesh();
    mesh.name = "mirrored wall".into();
    mesh.indices.clear();
    mesh.positions.clear();
    mesh.normals.clear();
    mesh.uvs.clear();
    let mut analytic = vec![];
    const CELLS: u32 = 8;
    for (x0, tangent) in [(WALL_X[0], Vec4::new(1.0, 0.0, 0.0, 1.0)), (0.0, Vec4::new(-1.0, 0.0, 0.0, -1.0))] {
        let base = mesh.positions.len() as u32;
        for j in 0..=CELLS {
            for i in 0..=CELLS {
                let x = x0 + (WALL_X[1] - WALL_X[0]) * 0.5 * i as f32 / CELLS as f32;
                let y = WALL_Y[0] + (WALL_Y[1] - WALL_Y[0]) * j as f32 / CELLS as f32;
                let p = Vec3::new(x, y, WALL_Z);
                mesh.positions.push(p);
                mesh.normals.push(Vec3::Z);
                mesh.uvs.push(mirrored_uv(p));
                analytic.push(tangent);
            }
        }
        quads(&mut mesh.indices, base, CELLS, CELLS);
    }
    mesh.analytic_tangents = Some(analytic);
    mesh
}

/// Counter-clockwise (seen from +Z, +Y up) triangles of a `columns × rows` grid of vertices
/// from `base`, row after row.
fn quads(indices: &mut Vec<u32>, base: u32, columns: u32, rows: u32) {
    let stride = columns + 1;
    for j in 0..rows {
        for i in 0..columns {
            let a = base + j * stride + i;
            indices.extend([a, a + 1, a + stride + 1, a, a + stride + 1, a + stride]);
        }
    }
}

/// [`TeachingScene::BentWall`]'s wall: normals bent, tangents `(1, 0, 0, 1)` supplied.
fn bent_wall_mesh() -> Mesh {
    let mut mesh = wall_mesh();
    mesh.name = "bent wall".into();
    let centre = Vec2::new((WALL_X[0] + WALL_X[1]) * 0.5, (WALL_Y[0] + WALL_Y[1]) * 0.5);
    let half = Vec2::new(WALL_X[1] - WALL_X[0], WALL_Y[1] - WALL_Y[0]) * 0.5;
    mesh.normals = mesh
        .positions
        .iter()
        .map(|p| {
            let offset = (Vec2::new(p.x, p.y) - centre) / half;
            (Vec3::Z + BEND * offset.extend(0.0)).normalize()
        })
        .collect();
    mesh.tangents = Some(vec![Vec4::new(1.0, 0.0, 0.0, 1.0); mesh.positions.len()]);
    mesh
}

/// A UV sphere about the origin: u once around (+X towards −Z), v pole to pole, the
/// texture repeating so a brick is about as large as on the wall; its analytic frame
/// (`T` along the parallel, `w = +1`).
fn sphere_mesh() -> Mesh {
    let mut mesh = Mesh::empty("coarse sphere");
    let mut analytic = vec![];
    let u_repeats = (TAU * SPHERE_RADIUS / BRICK_TILE_M).round().max(1.0);
    let v_repeats = (PI * SPHERE_RADIUS / BRICK_TILE_M).round().max(1.0);
    for j in 0..=SPHERE_RINGS {
        // theta from the south pole (−Y) up to the north pole (+Y).
        let theta = PI * j as f32 / SPHERE_RINGS as f32;
        for i in 0..=SPHERE_SEGMENTS {
            let phi = TAU * i as f32 / SPHERE_SEGMENTS as f32;
            let (sin_t, cos_t) = theta.sin_cos();
            let (sin_p, cos_p) = phi.sin_cos();
            let n = Vec3::new(sin_t * cos_p, -cos_t, -sin_t * sin_p);
            mesh.positions.push(n * SPHERE_RADIUS);
            mesh.normals.push(n);
            let u = u_repeats * i as f32 / SPHERE_SEGMENTS as f32;
            mesh.uvs.push(Vec2::new(u, v_repeats * (1.0 - j as f32 / SPHERE_RINGS as f32)));
            analytic.push(Vec4::new(-sin_p, 0.0, -cos_p, 1.0));
        }
    }
    mesh.analytic_tangents = Some(analytic);
    // Along +i the point moves along T, along +j up (B): (T, B, N) right-handed, so this
    // order is counter-clockwise from outside.
    quads(&mut mesh.indices, 0, SPHERE_SEGMENTS, SPHERE_RINGS);
    mesh
}

/// The bricks' gloss map (linear grey): `0.1 + 0.9 · height`, so the raised faces are shiny
/// and the recessed mortar dull.
fn gloss_texture() -> TextureImage {
    let field = brick_height_field(BRICK_TILE_M);
    let rgba = field
        .samples
        .iter()
        .flat_map(|h| {
            let g = ((0.1 + 0.9 * h.clamp(0.0, 1.0)) * 255.0).round() as u8;
            [g, g, g, 255]
        })
        .collect();
    TextureImage::new("bricks (gloss)", field.width, field.height, TextureKind::Data, rgba)
}

/// `normal_map` (RGB, OpenGL) packed as X-Ray's bump texture: A, B, G = R, G, B of the map, R
/// = √gloss with the gloss of [`gloss_texture`].
fn xray_texture(normal_map: &TextureImage) -> TextureImage {
    let gloss = gloss_texture();
    let rgba = normal_map
        .rgba
        .chunks_exact(4)
        .zip(gloss.rgba.chunks_exact(4))
        .flat_map(|(n, g)| {
            let root = ((g[0] as f32 / 255.0).sqrt() * 255.0).round() as u8;
            [root, n[2], n[1], n[0]]
        })
        .collect();
    TextureImage::new("bricks (X-Ray bump)", normal_map.width, normal_map.height, TextureKind::NormalMap, rgba)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::names::Named;
    use crate::tangent::bitangent;

    #[test]
    fn every_scene_builds_with_faces_along_their_normals() {
        for &teaching in TeachingScene::all() {
            let scene = teaching.build(Kernel::default());
            for mesh in &scene.meshes {
                for tri in mesh.indices.chunks_exact(3) {
                    let [a, b, c] = [0, 1, 2].map(|k| mesh.positions[tri[k] as usize]);
                    let face = (b - a).cross(c - a);
                    // The sphere's pole triangles have (nearly) no area: no facing to check.
                    if face.length() > 1e-6 {
                        let n = mesh.normals[tri[0] as usize];
                        assert!(face.dot(n) > 0.0, "{} {}", teaching.name(), mesh.name);
                    }
                }
            }
        }
    }

    #[test]
    fn the_mirrored_half_has_w_minus_one_and_the_image_up_still_up() {
        let mesh = mirrored_wall_mesh();
        let tangents = mesh.analytic_tangents.as_ref().unwrap();
        for (i, p) in mesh.positions.iter().enumerate() {
            let t = tangents[i];
            // u grows along T: mirrored, it grows towards −X on the right half.
            assert_eq!(t.w, if i >= mesh.positions.len() / 2 { -1.0 } else { 1.0 }, "{p}");
            assert_eq!(bitangent(Vec3::Z, t), Vec3::Y);
        }
        assert_eq!(mirrored_uv(Vec3::new(1.5, 1.0, WALL_Z)), mirrored_uv(Vec3::new(-1.5, 1.0, WALL_Z)));
    }

    #[test]
    fn the_bent_walls_tangents_lean_on_its_normals() {
        let mesh = bent_wall_mesh();
        let tangents = mesh.tangents.as_ref().unwrap();
        let worst = mesh.normals.iter().zip(tangents).map(|(n, t)| n.dot(t.truncate()).abs()).fold(0.0, f32::max);
        assert!(worst > 0.5, "{worst}");
    }
}
