//! World, tangent and view-space lighting compared per surface of the built-in scene (its
//! default camera and light, MikkTSpace frames, the brick normal map at strength 1), on the
//! CPU chain ([`crate::chain::shade`], held equal to the GPU by tests/lighting_spaces.rs).
//!
//! Three points per triangle, at barycentric weights (4, 1, 1)/6 and their rotations; each
//! triangle's inverse frame from its edges (the chain's derivatives are the differences along
//! two edges, [`TrianglePoint`]); the normal map read at the nearest texel of mip 0. The lit picture is compared in 8-bit sRGB
//! steps; the vectors by the angle between the light direction a space lights with and the
//! exact one, both in the pixel's own frame — for the diffuse term, the angle between the
//! shading normal of that space and the one of world space.

use glam::{Mat3, UVec2, Vec2, Vec3, Vec4};

use crate::chain::legacy::vertex_vectors;
use crate::chain::{Footprint, Fragment, Map, Varyings, shade};
use crate::frame::{BumpKind, FrameParams, LightingSpace, SceneOptions, ShadingSettings};
use crate::math::{linear_to_srgb, normal_matrix, normalize_or};
use crate::prepare::PreparedScene;
use crate::scene::{Scene, TextureImage};
use crate::shading::spaces::triangle_inverse_tbn;

/// One surface, one space against world space.
#[derive(Debug, Clone, PartialEq)]
pub struct SpaceRow {
    pub surface: String,
    pub space: LightingSpace,
    pub points: usize,
    /// Angle between the light direction lit with and the exact one, degrees.
    pub mean_angle_deg: f32,
    pub max_angle_deg: f32,
    /// Largest channel difference of the lit colour from world space's, 8-bit sRGB steps.
    pub mean_delta: f32,
    pub max_delta: f32,
}

/// Tangent and view space against world space on every tangent-space normal-mapped instance
/// of `scene` (one row per instance and space).
pub fn space_rows(scene: &Scene) -> Vec<SpaceRow> {
    let prepared = PreparedScene::new(scene, &SceneOptions::default());
    let params = FrameParams {
        camera: scene.default_camera,
        lights: scene.default_lights(),
        shading: ShadingSettings::default(),
    };
    let eye = params.camera.eye();
    let mut rows = vec![];
    for instance in prepared.instances.iter().filter(|i| i.bump == BumpKind::TangentSpace) {
        let prepared_mesh = &prepared.meshes[instance.mesh];
        let (mesh, Some(frames)) = (&prepared_mesh.mesh, prepared_mesh.frames.as_ref()) else { continue };
        let material = &scene.materials[instance.material];
        let Some(map) = material.normal_map.as_ref() else { continue };
        let texture = &scene.textures[map.texture];
        let (model, normals) = (instance.transform, normal_matrix(instance.transform));
        let mirror = if instance.mirrored() { -1.0 } else { 1.0 };
        let world_tangent =
            |i: usize| model.transform_vector3(frames.tangents[i].truncate()).extend(frames.tangents[i].w * mirror);
        let corner = |i: usize| {
            let position = model.transform_point3(mesh.positions[i]);
            let normal = normals.transform_vector3(mesh.normals[i]);
            (position, normal, world_tangent(i), mesh.uvs[i])
        };
        let mut measured = [(0.0f32, 0.0f32, 0.0f32, 0.0f32, 0usize); 2];
        for triangle in mesh.indices.chunks_exact(3) {
            let corners = [0, 1, 2].map(|k| corner(triangle[k] as usize));
            let [a, b, c] = corners;
            let face_normal = a.1 + b.1 + c.1;
            for rotation in 0..3 {
                let mut weights = [1.0 / 6.0; 3];
                weights[rotation] = 4.0 / 6.0;
                let w = Vec3::from_array(weights);
                let mix3 = |f: &dyn Fn(usize) -> Vec3| f(0) * w.x + f(1) * w.y + f(2) * w.z;
                let position = mix3(&|k| corners[k].0);
                let normal = mix3(&|k| corners[k].1);
                let tangent = corners.iter().zip(weights).fold(Vec4::ZERO, |sum, (c, w)| sum + c.2 * w);
                let uv = corners.iter().zip(weights).fold(Vec2::ZERO, |sum, (c, w)| sum + c.3 * w);
                let front_facing = normal.dot(eye - position) >= 0.0 || !material.double_sided;
                let facing = if front_facing { 1.0 } else { -1.0 };
                let to_tangent = triangle_inverse_tbn(b.0 - a.0, c.0 - a.0, b.3 - a.3, c.3 - a.3, face_normal * facing);
                let (vertex_light, vertex_half) = vertex_vectors(position, normal, params.lights.first_on(), eye);
                let at = Varyings {
                    position,
                    world_normal: normal,
                    uv,
                    world_tangent: Some(tangent),
                    // No mistake or legacy look is drawn here: the per-vertex vectors at the point.
                    vertex_light,
                    vertex_half,
                };
                let corner_at = |k: usize| Varyings { position: corners[k].0, uv: corners[k].3, ..at };
                let point = TrianglePoint {
                    at,
                    corners: [corner_at(0), corner_at(1), corner_at(2)],
                    front_facing,
                    normal_matrix: Mat3::from_mat4(normals),
                    normal_map: texture,
                };
                let shaded = |space: LightingSpace| {
                    let frame =
                        FrameParams { shading: ShadingSettings { lighting_space: space, ..params.shading }, ..params };
                    shade(instance.bump, material, &point, &frame)
                };
                let world = shaded(LightingSpace::World);
                let bytes = |c: Vec3| c.map(|v| linear_to_srgb(v) * 255.0);
                for (slot, space) in [LightingSpace::Tangent, LightingSpace::View].into_iter().enumerate() {
                    let other = shaded(space);
                    let delta = (bytes(other.color_linear) - bytes(world.color_linear)).abs().max_element();
                    let angle = match space {
                        LightingSpace::Tangent => tangent_angle_deg(&world, to_tangent),
                        _ => 0.0,
                    };
                    let m = &mut measured[slot];
                    *m = (m.0 + angle, m.1.max(angle), m.2 + delta, m.3.max(delta), m.4 + 1);
                }
            }
        }
        for (slot, space) in [LightingSpace::Tangent, LightingSpace::View].into_iter().enumerate() {
            let (angle_sum, angle_max, delta_sum, delta_max, points) = measured[slot];
            let n = points.max(1) as f32;
            rows.push(SpaceRow {
                surface: mesh.name.clone(),
                space,
                points,
                mean_angle_deg: angle_sum / n,
                max_angle_deg: angle_max,
                mean_delta: delta_sum / n,
                max_delta: delta_max,
            });
        }
    }
    rows
}

/// A point of a triangle as the report reads it: derivatives are the differences along the
/// triangle's edges from corner 0 (the quad's up to a 2×2 change of basis, which the triangle
/// frame does not see); only the normal map is bound, read at the nearest texel of mip 0
/// (RGB, alpha 1, whatever the footprint).
struct TrianglePoint<'a> {
    at: Varyings,
    corners: [Varyings; 3],
    front_facing: bool,
    normal_matrix: Mat3,
    normal_map: &'a TextureImage,
}

impl Fragment for TrianglePoint<'_> {
    fn varyings(&self) -> Varyings {
        self.at
    }

    fn front_facing(&self) -> bool {
        self.front_facing
    }

    fn normal_matrix(&self) -> Mat3 {
        self.normal_matrix
    }

    fn derivatives<T: std::ops::Sub<Output = T> + Copy>(&self, value: impl Fn(&Varyings) -> T) -> Option<(T, T)> {
        let [a, b, c] = self.corners.each_ref().map(value);
        Some((b - a, c - a))
    }

    fn sample(&self, map: Map, uv: Vec2, _: Footprint) -> Option<Vec4> {
        let t = self.normal_map;
        (map == Map::Bump).then(|| {
            let texel = t.texel((uv.x * t.width as f32).floor() as i64, (uv.y * t.height as f32).floor() as i64);
            Vec3::new(texel[0] as f32, texel[1] as f32, texel[2] as f32).extend(255.0) / 255.0
        })
    }

    fn size(&self, map: Map) -> Option<UVec2> {
        (map == Map::Bump).then(|| UVec2::new(self.normal_map.width, self.normal_map.height))
    }
}

/// The largest angle over the lights that are on between the light direction taken by the
/// triangle's inverse frame and the exact one (the world direction in the pixel's T, B, N),
/// degrees.
fn tangent_angle_deg(world: &crate::chain::ChainValues, to_tangent: glam::Mat3) -> f32 {
    let (Some(t), Some(b)) = (world.tangent, world.bitangent) else { return 0.0 };
    let n = world.normal;
    let mut worst = 0f32;
    for terms in world.lights.iter().flatten() {
        let l = terms.direction;
        let exact = Vec3::new(t.dot(l), b.dot(l), n.dot(l));
        let lit = normalize_or(to_tangent * l, Vec3::Z);
        // atan2 of sine and cosine: acos loses small angles to f32 rounding near 1.
        worst = worst.max(exact.cross(lit).length().atan2(exact.dot(lit)).to_degrees());
    }
    worst
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::builtin::teaching_scene;

    /// The flat wall's frame is constant: tangent space agrees with world space (within float
    /// rounding, under a tenth of an 8-bit step); the torus's frame turns, and they differ.
    #[test]
    fn the_wall_agrees_and_the_torus_differs() {
        let rows = space_rows(&teaching_scene());
        let row = |surface: &str, space| rows.iter().find(|r| r.surface == surface && r.space == space).unwrap();
        let wall = row("wall", LightingSpace::Tangent);
        assert!(wall.max_delta < 0.1 && wall.max_angle_deg < 0.01, "{wall:?}");
        let torus = row("torus", LightingSpace::Tangent);
        assert!(torus.max_angle_deg > 0.1 && torus.max_delta > 0.5, "{torus:?}");
        for r in rows.iter().filter(|r| r.space == LightingSpace::View) {
            assert!(r.max_delta < 0.1, "{r:?}");
        }
    }
}
