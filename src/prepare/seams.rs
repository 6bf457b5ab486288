//! Where GPU-displaced surfaces meet ([`super::displace::GpuDisplacedMesh`]): the welded points
//! of the edges and corners they share, made once per upload on the CPU by the CPU weld's own
//! rule ([`weld::common_offset`](super::weld::common_offset)). The compute pass reads these
//! points instead of displacing them itself, so the GPU's surfaces meet where the CPU's do.
//!
//! A seam is a base edge (keyed by its end positions) whose triangles displace it differently:
//! two surfaces along a crease (the built-in wall and floor), or one surface split along a UV
//! seam (the torus, whose copies sample the height map at u = 0 and u = 1). Each seam edge
//! gets a point per segment end at the finest cut ([`Seams::segments`]), so every power-of-two
//! cut reads its points from it; each vertex whose position has copies that move differently
//! gets its welded position. Meshes are welded together where their instances draw them with
//! one and the same transform, as on the CPU.

use std::collections::HashMap;

use glam::Vec3;

use super::PreparedScene;
use super::displace::{GpuDisplacedMesh, HeightLookup, unit_normal};
use super::weld::common_offset;
use crate::frame::MAX_GPU_EDGE_SEGMENTS;
use crate::scene::Mesh;

/// The welded points of the GPU-displaced meshes of a prepared scene, per mesh in the order of
/// [`PreparedScene::gpu_displaced`].
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Seams {
    /// Per mesh, per vertex: its welded, displaced position where copies of its position move
    /// differently (model space).
    pub corners: Vec<Vec<Option<Vec3>>>,
    /// Per mesh, per triangle, per edge (corner `k` to `k + 1`): the index in `points` of its
    /// first point, the rest following from its canonical end (the smaller end position).
    pub edges: Vec<Vec<[Option<u32>; 3]>>,
    /// Welded, displaced positions along the seam edges (model space): `segments + 1` per edge.
    pub points: Vec<Vec3>,
    /// The finest cut of a seam edge: [`MAX_GPU_EDGE_SEGMENTS`], or a smaller power of two
    /// where many seams would pass [`MAX_SEAM_POINTS`]; the plan cuts seams no finer.
    pub segments: u32,
}

/// The most welded points the seams hold (16 bytes each on the GPU: 4 MiB).
pub const MAX_SEAM_POINTS: usize = 1 << 18;

/// The finest cut `edges` seam edges can have within [`MAX_SEAM_POINTS`]: a power of two, at
/// most [`MAX_GPU_EDGE_SEGMENTS`], at least 1.
fn seam_segments(edges: usize) -> u32 {
    let mut segments = MAX_GPU_EDGE_SEGMENTS;
    while segments > 1 && edges * (segments as usize + 1) > MAX_SEAM_POINTS {
        segments /= 2;
    }
    segments
}

/// Where `side` moves point `m` of `segments` along its edge from corner `e` (counted from the
/// edge's canonical end), and the undisplaced point.
fn along((side, reversed): &(Side, bool), e: usize, m: u32, segments: u32) -> ((Vec3, f32), Vec3) {
    let mut w = [0.0; 3];
    let (start, end) = if *reversed { ((e + 1) % 3, e) } else { (e, (e + 1) % 3) };
    w[start] = (segments - m) as f32 / segments as f32;
    w[end] = m as f32 / segments as f32;
    let base = side.mesh.positions[side.corners[start]] * w[start] + side.mesh.positions[side.corners[end]] * w[end];
    (side.moves(w), base)
}

/// How one side of a seam moves a point: its mesh's heights and the corners' data.
struct Side<'a> {
    heights: HeightLookup<'a>,
    depth_m: f32,
    mesh: &'a Mesh,
    corners: [usize; 3],
}

impl Side<'_> {
    /// `(unit normal, lift)` at barycentric weights `w`.
    fn moves(&self, w: [f32; 3]) -> (Vec3, f32) {
        let at = |k: usize| self.corners[k];
        let m = self.mesh;
        let normal: Vec3 = (0..3).map(|k| m.normals[at(k)] * w[k]).sum();
        let uv: glam::Vec2 = (0..3).map(|k| m.uvs[at(k)] * w[k]).sum();
        let face = (m.positions[at(1)] - m.positions[at(0)]).cross(m.positions[at(2)] - m.positions[at(0)]);
        let lift = if self.depth_m == 0.0 { 0.0 } else { (self.heights.at(uv) - 1.0) * self.depth_m };
        (unit_normal(normal, face).0, lift)
    }
}

/// Corner `k` (and the edge from it to corner `k + 1`) of triangle `t` of mesh `m`: `(m, t, k)`.
type Corner = (usize, usize, usize);

/// A seam edge: its copies (one per triangle on it), and each copy's side with whether it
/// runs against the edge's canonical direction.
type SeamEdge<'a> = (Vec<Corner>, Vec<(Side<'a>, bool)>);

/// A position's key: its bits, with −0 as +0.
fn key(p: Vec3) -> [u32; 3] {
    p.to_array().map(|c| (c + 0.0).to_bits())
}

/// The seams of `prepared`'s GPU-displaced meshes.
pub fn seams(prepared: &PreparedScene) -> Seams {
    let displaced = &prepared.gpu_displaced;
    let mesh_of = |g: &GpuDisplacedMesh| &prepared.meshes[g.mesh].mesh;
    let mut seams = Seams {
        corners: displaced.iter().map(|g| vec![None; mesh_of(g).positions.len()]).collect(),
        edges: displaced.iter().map(|g| vec![[None; 3]; mesh_of(g).indices.len() / 3]).collect(),
        points: vec![],
        segments: MAX_GPU_EDGE_SEGMENTS,
    };
    let mut pending: Vec<SeamEdge> = vec![];
    for group in weld_groups(prepared) {
        // Every corner of every triangle of the group, by position and by edge.
        let mut by_position: HashMap<[u32; 3], Vec<Corner>> = HashMap::new();
        let mut by_edge: HashMap<([u32; 3], [u32; 3]), Vec<Corner>> = HashMap::new();
        for &k in &group {
            let mesh = mesh_of(&displaced[k]);
            for (t, corners) in mesh.indices.chunks_exact(3).enumerate() {
                for e in 0..3 {
                    let (a, b) = (mesh.positions[corners[e] as usize], mesh.positions[corners[(e + 1) % 3] as usize]);
                    by_position.entry(key(a)).or_default().push((k, t, e));
                    let ends = if key(a) <= key(b) { (key(a), key(b)) } else { (key(b), key(a)) };
                    by_edge.entry(ends).or_default().push((k, t, e));
                }
            }
        }
        let side = |(k, t, _): (usize, usize, usize)| {
            let g = &displaced[k];
            let mesh = mesh_of(g);
            let texture = &prepared.scene.textures[g.height_texture];
            Side {
                heights: HeightLookup { texture, wrap: g.wrap, depth: g.depth_map },
                depth_m: g.depth_m,
                mesh,
                corners: [0, 1, 2].map(|c| mesh.indices[3 * t + c] as usize),
            }
        };
        for copies in by_position.values() {
            let moves: Vec<(Vec3, f32)> =
                copies.iter().map(|&(k, t, e)| side((k, t, e)).moves(corner_weights(e))).collect();
            if moves.iter().all(|m| *m == moves[0]) {
                continue;
            }
            let (k, t, e) = copies[0];
            let side0 = side((k, t, e));
            let welded = side0.mesh.positions[side0.corners[e]] + common_offset(moves.into_iter());
            for &(k, t, e) in copies {
                let vertex = mesh_of(&displaced[k]).indices[3 * t + e] as usize;
                seams.corners[k][vertex] = Some(welded);
            }
        }
        // Seam edges first: how many decides how finely their points are made.
        let seam_edges: Vec<SeamEdge> = by_edge
            .values()
            .filter_map(|copies| {
                let sides: Vec<(Side, bool)> = copies
                    .iter()
                    .map(|&(k, t, e)| {
                        let side = side((k, t, e));
                        let ends = (side.corners[e], side.corners[(e + 1) % 3]);
                        let reversed = key(side.mesh.positions[ends.0]) > key(side.mesh.positions[ends.1]);
                        (side, reversed)
                    })
                    .collect();
                let moves = |i: usize, m: u32| along(&sides[i], copies[i].2, m, 16).0;
                let differ = (0..=16).any(|m| (1..sides.len()).any(|i| moves(i, m) != moves(0, m)));
                differ.then(|| (copies.clone(), sides))
            })
            .collect();
        pending.extend(seam_edges);
    }
    seams.segments = seam_segments(pending.len());
    for (copies, sides) in pending {
        let start = seams.points.len() as u32;
        for m in 0..=seams.segments {
            let moves: Vec<((Vec3, f32), Vec3)> =
                sides.iter().zip(&copies).map(|(side, &(_, _, e))| along(side, e, m, seams.segments)).collect();
            seams.points.push(moves[0].1 + common_offset(moves.iter().map(|(mv, _)| *mv)));
        }
        for (k, t, e) in copies {
            seams.edges[k][t][e] = Some(start);
        }
    }
    seams
}

/// The weights of corner `k`.
fn corner_weights(k: usize) -> [f32; 3] {
    let mut w = [0.0; 3];
    w[k] = 1.0;
    w
}

/// The GPU-displaced meshes (indices into [`PreparedScene::gpu_displaced`]) welded together:
/// those whose instances all draw them with one and the same transform share a group; a mesh
/// drawn with several transforms is welded only with itself.
fn weld_groups(prepared: &PreparedScene) -> Vec<Vec<usize>> {
    let transform_of = |mesh: usize| {
        let mut transforms = prepared.instances.iter().filter(|i| i.mesh == mesh).map(|i| i.transform);
        let first = transforms.next()?;
        transforms.all(|t| t == first).then_some(first.to_cols_array().map(f32::to_bits))
    };
    let mut groups: Vec<(Option<[u32; 16]>, Vec<usize>)> = vec![];
    for (k, g) in prepared.gpu_displaced.iter().enumerate() {
        let transform = transform_of(g.mesh);
        match groups.iter_mut().find(|(t, _)| transform.is_some() && *t == transform) {
            Some((_, members)) => members.push(k),
            None => groups.push((transform, vec![k])),
        }
    }
    groups.into_iter().map(|(_, members)| members).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Few seams take the finest cut; many take the finest power of two within the points'
    /// budget, down to one segment.
    #[test]
    fn many_seams_are_cut_more_coarsely() {
        assert_eq!(seam_segments(0), MAX_GPU_EDGE_SEGMENTS);
        assert_eq!(seam_segments(500), MAX_GPU_EDGE_SEGMENTS);
        assert_eq!(seam_segments(1000), 256);
        assert_eq!(seam_segments(10_000_000), 1);
    }

    /// The built-in scene on the GPU: the wall and floor meet along seams, and so do the
    /// torus's copies along its UV seams; every seam holds a point per segment end.
    #[test]
    fn the_built_in_scene_has_its_seams() {
        let options =
            crate::frame::SceneOptions { displacement: crate::frame::Displacement::on_gpu(3.0), ..Default::default() };
        let prepared = PreparedScene::new(&crate::scene::builtin::teaching_scene(), &options);
        let seams = seams(&prepared);
        let seam_edges: usize = seams.edges.iter().flatten().flatten().flatten().count();
        assert!(seam_edges > 0 && seams.corners.iter().flatten().any(Option::is_some));
        assert_eq!(seams.segments, MAX_GPU_EDGE_SEGMENTS);
        assert_eq!(seams.points.len() % (MAX_GPU_EDGE_SEGMENTS as usize + 1), 0);
    }
}
