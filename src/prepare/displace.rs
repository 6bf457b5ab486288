//! Displacement mapping on the CPU ([`Displacement`]), the ground truth the parallax family is
//! measured against. wgpu has no tessellation stage; of its two stand-ins — tessellating on
//! the CPU, or drawing a dense grid displaced in a vertex shader — this is the first: it needs
//! no new pipeline, shader or vertex layout (the displaced mesh is an ordinary mesh drawn by
//! the plain variant), it works on any mesh (a grid in the vertex shader would need the base
//! surface's parameterisation), and the CPU probe picks and shades the very triangles the GPU
//! draws.
//!
//! Each triangle is cut into `n² = 4^level` triangles on a barycentric grid (vertices shared
//! within a triangle; on a shared edge both triangles compute bit-identical positions, so the
//! surface has no cracks; where two surfaces or two normals meet at an edge, [`weld`](super::weld)
//! joins them). A vertex at barycentric `(b₁, b₂)` of the base triangle lies at
//! `P' = P + N̂ · (h − 1) · depth`, with `P`, the normal `N` and the UV interpolated linearly,
//! `N̂ = N / |N|` and `h` the height map's bilinear sample (0..1, white = high, a depth map
//! flipped) at the UV — the parallax convention: the mesh surface is the top of the relief.
//! Its normal is the exact normal of that surface, `∂P'/∂b₁ × ∂P'/∂b₂`, with
//! `∂P'/∂bₖ = Tₖ + ∂N̂/∂bₖ · (h − 1) · depth + N̂ · depth · ∇h·∂uv/∂bₖ`, where `Tₖ` is the
//! triangle's edge projected onto the plane normal to `N̂` (the base is the smooth surface the
//! interpolated normals describe, so depth 0 shades exactly as the undisplaced mesh) and `∇h`
//! is the height's UV gradient by central differences one texel apart.

use glam::{Vec2, Vec3};
use rayon::prelude::*;

use super::weld::{EdgeVertex, weld};
use crate::frame::{Displacement, MAX_DISPLACED_TRIANGLES, MAX_DISPLACEMENT_LEVEL};
use crate::scene::sample::sample_bilinear;
use crate::scene::{Material, Mesh, SamplerWrap, Scene, TextureImage};
use crate::shading::height_sample;

/// Bytes a displaced vertex takes on the GPU: position and normal (3 × f32 each) and UV
/// (2 × f32). Indices take 4 bytes each.
pub const VERTEX_BYTES: usize = 32;

/// What displacement made: the level drawn (lowered from the one asked for when the scene
/// would exceed [`MAX_DISPLACED_TRIANGLES`]), and the displaced meshes' size.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct DisplacementStats {
    /// The level drawn.
    pub level: u32,
    /// The level asked for; above `level` when the scene would have passed the budget.
    pub asked: u32,
    /// Triangles of the base meshes displaced (each cut into `4^level`).
    pub base_triangles: usize,
    pub vertices: usize,
    pub triangles: usize,
    /// Vertex and index buffers, bytes.
    pub bytes: usize,
}

impl DisplacementStats {
    /// `level L: V vertices, T triangles, M MiB`.
    pub fn summary(&self) -> String {
        let mib = self.bytes as f64 / (1024.0 * 1024.0);
        format!("level {}: {} vertices, {} triangles, {mib:.1} MiB", self.level, self.vertices, self.triangles)
    }

    /// [`Self::summary`], naming the level asked for and why it was not drawn when the level
    /// was lowered: `level 5 drawn, 6 asked (26214400 triangles would pass the budget of
    /// 8388608): …`.
    pub fn asked_and_drawn(&self) -> String {
        if self.asked == self.level {
            return self.summary();
        }
        let would = self.base_triangles.saturating_mul(1 << (2 * self.asked));
        let summary = self.summary();
        let drawn = summary.split_once(": ").map_or(summary.as_str(), |(_, rest)| rest);
        format!(
            "level {} drawn, {} asked ({would} triangles would pass the budget of {MAX_DISPLACED_TRIANGLES}): {drawn}",
            self.level, self.asked
        )
    }
}

/// The height field a material's height map describes, as the GPU's sampler reads level 0.
pub(super) struct HeightLookup<'a> {
    pub texture: &'a TextureImage,
    pub wrap: SamplerWrap,
    pub depth: bool,
}

impl HeightLookup<'_> {
    /// The height (0..1, white = high) at `uv`.
    pub fn at(&self, uv: Vec2) -> f32 {
        let sample = height_sample(sample_bilinear(self.texture, uv, self.wrap).truncate());
        if self.depth { 1.0 - sample } else { sample }
    }

    /// `(∂h/∂u, ∂h/∂v)` by central differences one texel apart.
    fn gradient(&self, uv: Vec2) -> Vec2 {
        let du = Vec2::new(1.0 / self.texture.width as f32, 0.0);
        let dv = Vec2::new(0.0, 1.0 / self.texture.height as f32);
        Vec2::new(
            (self.at(uv + du) - self.at(uv - du)) / (2.0 * du.x),
            (self.at(uv + dv) - self.at(uv - dv)) / (2.0 * dv.y),
        )
    }
}

/// `scene` with every instance whose material has a height map (and whose mesh has texture
/// coordinates and normals per vertex, indices in range; non-finite data is left to the
/// prepare stage's repair, which drops such triangles) drawing a displaced copy of its mesh with a copy of its material without
/// normal and height maps; the stats when anything was displaced on the CPU. Notices say when
/// the level was lowered. With [`Displacement::gpu`] the copies are of the base mesh, and what
/// the GPU displaces them with is returned instead ([`GpuDisplacedMesh`]).
pub fn displaced(
    mut scene: Scene,
    displacement: &Displacement,
    notices: &mut Vec<String>,
) -> (Scene, Option<DisplacementStats>, Vec<GpuDisplacedMesh>) {
    if !displacement.is_on() {
        return (scene, None, vec![]);
    }
    let displaceable = |mesh: usize, material: usize| {
        let mesh = &scene.meshes[mesh];
        let map = scene.materials[material].height_map.as_ref();
        map.is_some_and(|m| scene.textures.get(m.texture).is_some_and(|t| t.width > 0 && t.height > 0))
            && mesh.uvs.len() == mesh.positions.len()
            && mesh.normals.len() == mesh.positions.len()
            && !mesh.indices.is_empty()
            && mesh.indices.iter().all(|&i| (i as usize) < mesh.positions.len())
    };
    let mut pairs: Vec<(usize, usize)> =
        scene.instances.iter().map(|i| (i.mesh, i.material)).filter(|&(m, mat)| displaceable(m, mat)).collect();
    pairs.sort_unstable();
    pairs.dedup();
    if pairs.is_empty() {
        return (scene, None, vec![]);
    }
    if displacement.gpu.is_some() {
        let on_gpu = pairs.iter().map(|&pair| displaced_on_gpu(&mut scene, pair, displacement)).collect();
        return (scene, None, on_gpu);
    }
    let base_triangles: usize = pairs.iter().map(|&(mesh, _)| scene.meshes[mesh].indices.len() / 3).sum();
    let asked = displacement.level.min(MAX_DISPLACEMENT_LEVEL);
    let mut level = asked;
    while level > 1 && base_triangles << (2 * level) > MAX_DISPLACED_TRIANGLES {
        level -= 1;
    }
    if level < asked {
        notices.push(format!(
            "displacement level {asked} would draw {} triangles: drawn at level {level} (at most {MAX_DISPLACED_TRIANGLES})",
            base_triangles << (2 * asked)
        ));
    }
    let mut stats = DisplacementStats { level, asked, base_triangles, vertices: 0, triangles: 0, bytes: 0 };
    let mut made = vec![];
    for &(mesh_index, material_index) in &pairs {
        let material = &scene.materials[material_index];
        let map = material.height_map.as_ref().expect("displaceable");
        let depth_m = displacement.depth_m.unwrap_or(map.range_m);
        let depth_m = if depth_m.is_finite() { depth_m } else { 0.0 };
        let heights =
            HeightLookup { texture: &scene.textures[map.texture], wrap: material.detail_wrap, depth: map.depth };
        let (mesh, edges) = displace_mesh(&scene.meshes[mesh_index], level, depth_m, &heights);
        stats.vertices += mesh.positions.len();
        stats.triangles += mesh.indices.len() / 3;
        stats.bytes += mesh.positions.len() * VERTEX_BYTES + mesh.indices.len() * 4;
        made.push(((mesh_index, material_index), mesh, flat_copy(material), edges));
    }
    weld_where_drawn_alike(&scene, &mut made);
    for (pair, mesh, material, _) in made {
        draw_instead(&mut scene, pair, mesh, material);
    }
    (scene, Some(stats), vec![])
}

/// `material` without normal and height maps: the displaced surface's own normals shade it.
fn flat_copy(material: &Material) -> Material {
    Material { name: format!("{} (displaced)", material.name), normal_map: None, height_map: None, ..material.clone() }
}

/// Appends `mesh` and `material` to `scene`, and makes the instances that drew the pair
/// `(mesh, material)` draw them instead; the new mesh's index.
fn draw_instead(
    scene: &mut Scene,
    (mesh_index, material_index): (usize, usize),
    mesh: Mesh,
    material: Material,
) -> usize {
    scene.meshes.push(mesh);
    scene.materials.push(material);
    let (new_mesh, new_material) = (scene.meshes.len() - 1, scene.materials.len() - 1);
    for instance in &mut scene.instances {
        if (instance.mesh, instance.material) == (mesh_index, material_index) {
            (instance.mesh, instance.material) = (new_mesh, new_material);
        }
    }
    new_mesh
}

/// A mesh the GPU tessellates and displaces every time the view changes
/// ([`crate::render`]'s tessellation): a copy of a base mesh drawn with a flat material, and
/// the height map it is displaced by.
#[derive(Debug, Clone, PartialEq)]
pub struct GpuDisplacedMesh {
    /// The base mesh's copy in the prepared scene, which its instances draw.
    pub mesh: usize,
    /// The height map, a texture of the prepared scene (level 0 read, bilinear, as
    /// [`HeightLookup`] reads it).
    pub height_texture: usize,
    /// Metres the full height range spans.
    pub depth_m: f32,
    /// The map holds depth (`1 − sample` is the height).
    pub depth_map: bool,
    /// How the height map wraps (the material's detail wrap, as on the CPU).
    pub wrap: crate::scene::SamplerWrap,
}

impl GpuDisplacedMesh {
    /// The CPU twin of the GPU's displaced vertex (shaders/displace.wgsl): position and normal
    /// (as long as the interpolated one) at barycentric weights `w` of triangle `triangle` of
    /// `mesh`, displaced by this mesh's height map in `scene`.
    pub fn displaced_point(&self, scene: &Scene, mesh: &Mesh, triangle: usize, w: [f32; 3]) -> (Vec3, Vec3) {
        let corners = [0, 1, 2].map(|k| mesh.indices[3 * triangle + k] as usize);
        let (p, nrm, uv) =
            (corners.map(|i| mesh.positions[i]), corners.map(|i| mesh.normals[i]), corners.map(|i| mesh.uvs[i]));
        let heights =
            HeightLookup { texture: &scene.textures[self.height_texture], wrap: self.wrap, depth: self.depth_map };
        let (position, normal, _) = displaced_vertex(&p, &nrm, &uv, w, self.depth_m, &heights);
        (position, normal)
    }
}

/// Makes the instances drawing `pair` draw a copy of its mesh with a flat material, and says
/// what the GPU displaces that copy with.
fn displaced_on_gpu(scene: &mut Scene, pair: (usize, usize), displacement: &Displacement) -> GpuDisplacedMesh {
    let material = &scene.materials[pair.1];
    let map = material.height_map.as_ref().expect("displaceable");
    let depth_m = displacement.depth_m.unwrap_or(map.range_m);
    let (height_texture, depth_map, wrap) = (map.texture, map.depth, material.detail_wrap);
    let mut mesh = scene.meshes[pair.0].clone();
    mesh.name = format!("{} (displaced on the GPU)", mesh.name);
    mesh.tangents = None;
    mesh.analytic_tangents = None;
    let flat = flat_copy(material);
    let mesh = draw_instead(scene, pair, mesh, flat);
    GpuDisplacedMesh { mesh, height_texture, depth_m: if depth_m.is_finite() { depth_m } else { 0.0 }, depth_map, wrap }
}

/// Welds (see [`weld`](super::weld)) the displaced meshes drawn with one and the same
/// transform (the built-in wall and floor: the identity), whose shared edges then meet in the
/// world too; a mesh drawn with several transforms is welded only with itself.
fn weld_where_drawn_alike(scene: &Scene, made: &mut [((usize, usize), Mesh, Material, Vec<EdgeVertex>)]) {
    let transform_of = |pair: (usize, usize)| {
        let mut transforms = scene.instances.iter().filter(|i| (i.mesh, i.material) == pair).map(|i| i.transform);
        let first = transforms.next()?;
        transforms.all(|t| t == first).then_some(first.to_cols_array().map(f32::to_bits))
    };
    let mut groups: Vec<(Option<[u32; 16]>, Vec<usize>)> = vec![];
    for (k, entry) in made.iter().enumerate() {
        let key = transform_of(entry.0);
        match groups.iter_mut().find(|(g, _)| key.is_some() && *g == key) {
            Some((_, members)) => members.push(k),
            None => groups.push((key, vec![k])),
        }
    }
    for (_, members) in groups {
        let mut meshes: Vec<(&mut Vec<Vec3>, Vec<EdgeVertex>)> = made
            .iter_mut()
            .enumerate()
            .filter(|(k, _)| members.contains(k))
            .map(|(_, entry)| (&mut entry.1.positions, std::mem::take(&mut entry.3)))
            .collect();
        weld(&mut meshes);
    }
}

/// `mesh` tessellated at `level` and displaced by `depth_m` metres of `heights`, with the
/// vertices on its base triangles' edges (for [`weld`](super::weld)).
fn displace_mesh(mesh: &Mesh, level: u32, depth_m: f32, heights: &HeightLookup) -> (Mesh, Vec<EdgeVertex>) {
    let n = 1u32 << level;
    let per_triangle = ((n + 1) * (n + 2) / 2) as usize;
    type Patch = (Vec<Vec3>, Vec<Vec3>, Vec<Vec2>, Vec<EdgeVertex>);
    let patches: Vec<Patch> = mesh
        .indices
        .par_chunks_exact(3)
        .map(|corners| {
            let corners = [corners[0], corners[1], corners[2]].map(|i| i as usize);
            let (p, nrm, uv) =
                (corners.map(|i| mesh.positions[i]), corners.map(|i| mesh.normals[i]), corners.map(|i| mesh.uvs[i]));
            let mut out = (Vec::with_capacity(per_triangle), Vec::with_capacity(per_triangle), vec![], vec![]);
            for i in 0..=n {
                for j in 0..=n - i {
                    let w = [(n - i - j) as f32 / n as f32, i as f32 / n as f32, j as f32 / n as f32];
                    let (position, normal, edge) = displaced_vertex(&p, &nrm, &uv, w, depth_m, heights);
                    if i == 0 || j == 0 || i + j == n {
                        out.3.push(EdgeVertex { index: out.0.len() as u32, ..edge });
                    }
                    out.0.push(position);
                    out.1.push(normal);
                    out.2.push(uv[0] * w[0] + uv[1] * w[1] + uv[2] * w[2]);
                }
            }
            out
        })
        .collect();
    let mut out = Mesh {
        name: format!("{} (displaced, level {level})", mesh.name),
        positions: Vec::with_capacity(patches.len() * per_triangle),
        normals: Vec::with_capacity(patches.len() * per_triangle),
        uvs: Vec::with_capacity(patches.len() * per_triangle),
        tangents: None,
        analytic_tangents: None,
        indices: Vec::with_capacity(patches.len() * (n * n) as usize * 3),
    };
    // Vertex (i, j) of a patch: rows of n + 1 − i vertices.
    let index = |i: u32, j: u32| i * (n + 1) - i * (i.saturating_sub(1)) / 2 + j;
    let mut edges = vec![];
    for (positions, normals, uvs, patch_edges) in patches {
        let base = out.positions.len() as u32;
        edges.extend(patch_edges.into_iter().map(|e| EdgeVertex { index: base + e.index, ..e }));
        for i in 0..n {
            for j in 0..n - i {
                out.indices.extend([index(i, j), index(i + 1, j), index(i, j + 1)].map(|v| base + v));
                if i + j + 1 < n {
                    out.indices.extend([index(i + 1, j), index(i + 1, j + 1), index(i, j + 1)].map(|v| base + v));
                }
            }
        }
        out.positions.extend(positions);
        out.normals.extend(normals);
        out.uvs.extend(uvs);
    }
    (out, edges)
}

/// The displaced position and normal at barycentric weights `w` of the triangle with corners
/// `p`, normals `nrm` and UVs `uv` (the module's formulas). The normal has the length of the
/// interpolated one, so at depth 0 it is exactly the undisplaced mesh's. Also the vertex's
/// base position, unit normal and lift (its index left 0).
fn displaced_vertex(
    p: &[Vec3; 3],
    nrm: &[Vec3; 3],
    uv: &[Vec2; 3],
    w: [f32; 3],
    depth_m: f32,
    heights: &HeightLookup,
) -> (Vec3, Vec3, EdgeVertex) {
    let position = p[0] * w[0] + p[1] * w[1] + p[2] * w[2];
    let normal = nrm[0] * w[0] + nrm[1] * w[1] + nrm[2] * w[2];
    let at = uv[0] * w[0] + uv[1] * w[1] + uv[2] * w[2];
    let face = (p[1] - p[0]).cross(p[2] - p[0]);
    let (unit, length) = unit_normal(normal, face);
    if depth_m == 0.0 {
        return (position, normal, EdgeVertex { index: 0, base: position, unit, lift: 0.0 });
    }
    let lift = (heights.at(at) - 1.0) * depth_m;
    let gradient = heights.gradient(at);
    let along = |k: usize| {
        let edge = p[k] - p[0];
        let tangent = edge - unit * unit.dot(edge);
        let d_normal = nrm[k] - nrm[0];
        let d_unit = (d_normal - unit * unit.dot(d_normal)) / length.max(1e-12);
        tangent + d_unit * lift + unit * (depth_m * gradient.dot(uv[k] - uv[0]))
    };
    let cross = along(1).cross(along(2));
    // Oriented like the interpolated normal (the base triangle may wind against it).
    let side = if face.dot(unit) < 0.0 { -1.0 } else { 1.0 };
    let exact = (cross * side).normalize_or(unit);
    (position + unit * lift, exact * length.max(1e-12), EdgeVertex { index: 0, base: position, unit, lift })
}

/// The direction a vertex with interpolated normal `normal` moves in: the unit normal (and the
/// normal's length), or the triangle's `face` normal where the normal is zero or not finite.
pub(super) fn unit_normal(normal: Vec3, face: Vec3) -> (Vec3, f32) {
    let length = normal.length();
    let unit = if length > 1e-12 && normal.is_finite() { normal / length } else { face.normalize_or(Vec3::Z) };
    (unit, length)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::builtin::teaching_scene;

    #[test]
    fn a_level_cuts_each_triangle_into_four_to_the_level_and_shares_no_index_across_patches() {
        let scene = teaching_scene();
        let wall = &scene.meshes[0];
        let heights = HeightLookup { texture: &scene.textures[2], wrap: scene.materials[0].detail_wrap, depth: false };
        let (mesh, _) = displace_mesh(wall, 3, 0.0, &heights);
        let base = wall.indices.len() / 3;
        assert_eq!(mesh.indices.len() / 3, base * 64);
        assert_eq!(mesh.positions.len(), base * 45);
        assert!(mesh.indices.iter().all(|&i| (i as usize) < mesh.positions.len()));
        // Every sub-triangle winds like its base triangle.
        let face = (wall.positions[wall.indices[1] as usize] - wall.positions[wall.indices[0] as usize])
            .cross(wall.positions[wall.indices[2] as usize] - wall.positions[wall.indices[0] as usize]);
        let first = &mesh.indices[..3];
        let [a, b, c] = [0, 1, 2].map(|k| mesh.positions[first[k] as usize]);
        assert!((b - a).cross(c - a).dot(face) > 0.0);
    }

    /// The built-in wall and floor, displaced 4 cm at level 2, share every vertex of their
    /// seam bit for bit: each of the wall's vertices at v = 3 (8 cells × (5 along the bottom
    /// edge of one triangle + the corner of the other)) is also a vertex of the floor.
    #[test]
    fn the_wall_and_floor_share_their_displaced_seam() {
        let mut notices = vec![];
        let (scene, _, _) =
            displaced(teaching_scene(), &Displacement { level: 2, depth_m: Some(0.04), gpu: None }, &mut notices);
        let [wall, floor] = [0, 1].map(|i| &scene.meshes[scene.instances[i].mesh]);
        let key = |p: &Vec3| p.to_array().map(f32::to_bits);
        let floor_points: std::collections::HashSet<_> = floor.positions.iter().map(key).collect();
        let seam: Vec<&Vec3> =
            wall.positions.iter().zip(&wall.uvs).filter(|(_, uv)| (uv.y - 3.0).abs() < 1e-5).map(|(p, _)| p).collect();
        assert_eq!(seam.len(), 48);
        assert!(seam.iter().all(|p| floor_points.contains(&key(p))), "{seam:?}");
        assert!(seam.iter().any(|p| p.y < -0.01), "the seam moved down with the floor");
    }

    /// A square with a height ramp `h = u` (16-bit texels at their centres, so bilinear
    /// filtering is exact inside) displaced 0.1 m: positions at `z = (u − 1) · 0.1` and the
    /// normal `(−0.1, 0, 1)` normalised (u runs along +x at one unit per metre).
    #[test]
    fn a_ramp_is_displaced_to_its_exact_surface_and_normal() {
        let width = 64u32;
        let mut rgba = vec![];
        for _ in 0..4 {
            for i in 0..width {
                let [hi, lo] = crate::scene::encode_height((i as f32 + 0.5) / width as f32);
                rgba.extend([hi, lo, 0, 255]);
            }
        }
        let texture = TextureImage::new("ramp", width, 4, crate::scene::TextureKind::Height, rgba);
        let heights = HeightLookup { texture: &texture, wrap: SamplerWrap::default(), depth: false };
        let mut square = Mesh::empty("square");
        for (x, y) in [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)] {
            square.positions.push(Vec3::new(x, y, 0.0));
            square.normals.push(Vec3::Z);
            square.uvs.push(Vec2::new(x, 1.0 - y));
        }
        square.indices = vec![0, 1, 2, 0, 2, 3];
        let (mesh, _) = displace_mesh(&square, 5, 0.1, &heights);
        let expected_normal = Vec3::new(-0.1, 0.0, 1.0).normalize();
        let mut checked = 0;
        for ((p, n), uv) in mesh.positions.iter().zip(&mesh.normals).zip(&mesh.uvs) {
            if uv.x < 2.0 / width as f32 || uv.x > 1.0 - 2.0 / width as f32 {
                continue; // the border texels clamp or wrap
            }
            assert!((p.z - (uv.x - 1.0) * 0.1).abs() < 1e-4, "{p} at {uv}");
            assert!(n.normalize().angle_between(expected_normal) < 1e-3, "{n} at {uv}");
            checked += 1;
        }
        assert!(checked > 900, "{checked}");
    }
}
