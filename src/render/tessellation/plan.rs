//! Which base triangles the GPU tessellates this frame, and how finely: the CPU half of GPU
//! displacement. Per base edge, the number of segments is the smallest power of two that
//! cuts its projection on screen into pieces no longer than the target (in pixels), at most
//! [`MAX_GPU_EDGE_SEGMENTS`]; a triangle is cut into `n²` on a barycentric grid of `n`, the
//! most its three edges ask, and a grid vertex on an edge cut into fewer segments `e` is moved
//! to the nearest of that edge's own `e + 1` points. Both triangles on an edge meet it in the
//! same points, so no crack opens (the edge's segments are computed once per edge, keyed by
//! its end positions). Triangles outside the frustum, or facing away where the material is
//! single-sided, are not tessellated at all. When the frame would pass the budget
//! ([`MAX_GPU_DISPLACED_TRIANGLES`], [`MAX_GPU_DISPLACED_VERTICES`]) the target edge grows by
//! `√2` until it fits, and the plan says so.
//!
//! This half is a few flops per base edge (thousands of edges, microseconds) and knows the
//! counts exactly, so the GPU half needs no read-back, prefix sum or indirect draw: it writes
//! every vertex and triangle of the plan into ranges given here.

use std::collections::HashMap;

use glam::{Mat4, Vec3, Vec4};

use crate::frame::{MAX_GPU_DISPLACED_TRIANGLES, MAX_GPU_DISPLACED_VERTICES, MAX_GPU_EDGE_SEGMENTS};
use crate::scene::Mesh;

/// A base triangle as the compute pass reads it: which, into how many segments per side, and
/// where its vertices and indices go. 32 bytes, the WGSL `Patch`.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, bytemuck::Pod, bytemuck::Zeroable)]
pub struct Patch {
    /// Its first index's position in the pool's base index buffer, divided by 3.
    pub triangle: u32,
    /// `n`: the grid's segments per side (a power of two).
    pub segments: u32,
    /// Segments of edge `k`, from corner `k` to corner `k + 1` (powers of two, at most `n`).
    pub edge_segments: [u32; 3],
    pub first_vertex: u32,
    pub first_index: u32,
    /// Bit `k`: edge `k` runs against its canonical direction (from the larger end position
    /// to the smaller), in which both its triangles compute its points.
    pub reversed: u32,
}

impl Patch {
    /// Vertices of its grid: `(n + 1)(n + 2) / 2`.
    pub fn vertex_count(segments: u32) -> u32 {
        (segments + 1) * (segments + 2) / 2
    }
}

/// A base mesh's edges, each shared edge once, keyed by its end positions (so triangles that
/// meet along a UV seam, whose vertices are copies, still share the edge).
#[derive(Debug, Clone, PartialEq)]
pub struct MeshEdges {
    /// Per triangle, the edge from corner `k` to corner `k + 1`.
    pub of_triangle: Vec<[u32; 3]>,
    /// Per triangle, [`Patch::reversed`].
    pub reversed: Vec<u32>,
    /// Per edge, its end positions (model space) in canonical order.
    pub ends: Vec<[Vec3; 2]>,
}

/// A position's key: its bits, with −0 as +0.
fn position_key(p: Vec3) -> [u32; 3] {
    p.to_array().map(|c| (c + 0.0).to_bits())
}

impl MeshEdges {
    pub fn of(mesh: &Mesh) -> MeshEdges {
        let mut ids: HashMap<([u32; 3], [u32; 3]), u32> = HashMap::new();
        let mut edges = MeshEdges { of_triangle: vec![], reversed: vec![], ends: vec![] };
        for corners in mesh.indices.chunks_exact(3) {
            let p = [0, 1, 2].map(|k| mesh.positions[corners[k] as usize]);
            let mut reversed = 0;
            let ids = [0, 1, 2].map(|k| {
                let (a, b) = (p[k], p[(k + 1) % 3]);
                let (key_a, key_b) = (position_key(a), position_key(b));
                let (key, ends) = if key_a <= key_b {
                    ((key_a, key_b), [a, b])
                } else {
                    reversed |= 1 << k;
                    ((key_b, key_a), [b, a])
                };
                *ids.entry(key).or_insert_with(|| {
                    edges.ends.push(ends);
                    edges.ends.len() as u32 - 1
                })
            });
            edges.of_triangle.push(ids);
            edges.reversed.push(reversed);
        }
        edges
    }
}

/// What a frame is drawn into: the camera and the picture's size.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct View {
    pub view_projection: Mat4,
    pub eye: Vec3,
    /// Pixels, width and height.
    pub size: [u32; 2],
}

/// One GPU-displaced mesh of a scene as the plan needs it.
pub struct PlannedMesh<'a> {
    pub mesh: &'a Mesh,
    pub edges: &'a MeshEdges,
    /// The model matrices of the instances that draw it.
    pub transforms: Vec<Mat4>,
    /// The relief's depth, metres: how far below the base triangle the surface may lie.
    pub depth_m: f32,
    /// Back faces are culled (a single-sided material).
    pub cull_back_faces: bool,
}

/// This frame's tessellation of every GPU-displaced mesh, ready to upload.
#[derive(Debug, Clone, PartialEq)]
pub struct Plan {
    pub patches: Vec<Patch>,
    /// Per mesh: its patches' range in [`Self::patches`], and its vertices' and indices'
    /// ranges in the pool.
    pub meshes: Vec<MeshRanges>,
    pub vertices: u32,
    pub triangles: u32,
    /// The target edge drawn (pixels): the one asked for, or larger where the budget said so.
    pub pixels_per_edge: f32,
    /// Base triangles left out (outside the frustum, or facing away).
    pub culled: u32,
}

/// Where one mesh's part of the plan lies.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct MeshRanges {
    pub patches: std::ops::Range<u32>,
    pub first_vertex: u32,
    pub vertices: u32,
    pub first_index: u32,
    pub indices: u32,
}

/// How many pixels long edge `[a, b]` (model space, drawn with `transform`) is on screen: its
/// part in front of the camera (`w` above a tenth of a millimetre).
fn edge_pixels(view: &View, transform: Mat4, [a, b]: [Vec3; 2]) -> f32 {
    const NEAR_W: f32 = 1e-4;
    let clip = |p: Vec3| view.view_projection * (transform * p.extend(1.0));
    let (mut ca, mut cb) = (clip(a), clip(b));
    if ca.w < NEAR_W && cb.w < NEAR_W {
        return 0.0;
    }
    if ca.w < NEAR_W || cb.w < NEAR_W {
        let t = (NEAR_W - ca.w) / (cb.w - ca.w);
        let cut = ca + (cb - ca) * t;
        if ca.w < NEAR_W { ca = cut } else { cb = cut }
    }
    let half = glam::Vec2::new(view.size[0] as f32, view.size[1] as f32) * 0.5;
    let screen = |c: Vec4| glam::Vec2::new(c.x, c.y) / c.w * half;
    let pixels = (screen(ca) - screen(cb)).length();
    if pixels.is_finite() { pixels } else { f32::MAX }
}

/// Whether base triangle `p` (model space, drawn with `transform`) may show: some of it, or
/// of its relief down to `depth_m` below it along the normals `n`, is inside the frustum, and
/// unless `cull_back_faces` is off it does not face away at all three corners (by both its own
/// normal and each corner's).
fn may_show(view: &View, transform: Mat4, p: [Vec3; 3], n: [Vec3; 3], depth_m: f32, cull_back_faces: bool) -> bool {
    let world = p.map(|q| transform.transform_point3(q));
    let normals = n.map(|q| transform.transform_vector3(q).normalize_or_zero());
    let lowest = [0, 1, 2].map(|k| world[k] - normals[k] * depth_m.abs());
    let clips: Vec<Vec4> = world.iter().chain(&lowest).map(|q| view.view_projection * q.extend(1.0)).collect();
    let outside = |test: fn(Vec4) -> bool| clips.iter().all(|&c| test(c));
    let culled_by_frustum = outside(|c| c.x > c.w)
        || outside(|c| c.x < -c.w)
        || outside(|c| c.y > c.w)
        || outside(|c| c.y < -c.w)
        || outside(|c| c.z > c.w)
        || outside(|c| c.w <= 0.0);
    if culled_by_frustum {
        return false;
    }
    if !cull_back_faces {
        return true;
    }
    let face = (world[1] - world[0]).cross(world[2] - world[0]);
    let mirrored = transform.determinant() < 0.0;
    let face = if mirrored { -face } else { face };
    (0..3).any(|k| {
        let to_eye = view.eye - world[k];
        face.dot(to_eye) >= 0.0 || normals[k].dot(to_eye) >= 0.0
    })
}

/// Segments for an edge `pixels` long at a target of `target` pixels per segment.
fn segments_for(pixels: f32, target: f32) -> u32 {
    let wanted = pixels / target;
    if !(wanted < MAX_GPU_EDGE_SEGMENTS as f32) {
        return MAX_GPU_EDGE_SEGMENTS;
    }
    (wanted.ceil().max(1.0) as u32).next_power_of_two()
}

/// Plans this frame's tessellation of `meshes` seen in `view` at `pixels_per_edge` (above 0),
/// within `budget` (triangles, vertices; the constants unless a test asks for less).
pub fn plan(meshes: &[PlannedMesh], view: &View, pixels_per_edge: f32, budget: (u32, u32)) -> Plan {
    let lengths: Vec<Vec<f32>> = meshes
        .iter()
        .map(|m| {
            let longest =
                |ends: &[Vec3; 2]| m.transforms.iter().map(|&t| edge_pixels(view, t, *ends)).fold(0.0, f32::max);
            m.edges.ends.iter().map(longest).collect()
        })
        .collect();
    let shown: Vec<Vec<bool>> = meshes
        .iter()
        .map(|m| {
            let mesh = m.mesh;
            let shows = |corners: &[u32]| {
                let p = [0, 1, 2].map(|k| mesh.positions[corners[k] as usize]);
                let n = [0, 1, 2].map(|k| mesh.normals[corners[k] as usize]);
                m.transforms.iter().any(|&t| may_show(view, t, p, n, m.depth_m, m.cull_back_faces))
            };
            mesh.indices.chunks_exact(3).map(shows).collect()
        })
        .collect();
    let mut target = if pixels_per_edge > 0.0 && pixels_per_edge.is_finite() { pixels_per_edge } else { 1.0 };
    // √2⁶⁴ = 2³²: by then every edge is one segment, and the base mesh is all there is to draw.
    for _ in 0..64 {
        if let Some(plan) = plan_at(meshes, &lengths, &shown, target, Some(budget)) {
            return plan;
        }
        target *= std::f32::consts::SQRT_2;
    }
    plan_at(meshes, &lengths, &shown, f32::MAX, None).expect("no budget")
}

/// [`plan`] at one target edge; `None` when it would pass `budget`.
fn plan_at(
    meshes: &[PlannedMesh],
    lengths: &[Vec<f32>],
    shown: &[Vec<bool>],
    target: f32,
    budget: Option<(u32, u32)>,
) -> Option<Plan> {
    let (max_triangles, max_vertices) = budget.map_or((u64::MAX, u64::MAX), |(t, v)| (u64::from(t), u64::from(v)));
    let mut plan =
        Plan { patches: vec![], meshes: vec![], vertices: 0, triangles: 0, pixels_per_edge: target, culled: 0 };
    let (mut vertices, mut triangles) = (0u64, 0u64);
    let mut first_triangle = 0u32;
    for ((m, lengths), shown) in meshes.iter().zip(lengths).zip(shown) {
        let segments: Vec<u32> = lengths.iter().map(|&l| segments_for(l, target)).collect();
        let start = (plan.patches.len() as u32, vertices as u32, triangles as u32 * 3);
        for (triangle, (edges, &visible)) in m.edges.of_triangle.iter().zip(shown).enumerate() {
            if !visible {
                plan.culled += 1;
                continue;
            }
            let edge_segments = edges.map(|e| segments[e as usize]);
            let n = edge_segments.into_iter().max().unwrap_or(1);
            plan.patches.push(Patch {
                triangle: first_triangle + triangle as u32,
                segments: n,
                edge_segments,
                first_vertex: vertices as u32,
                first_index: triangles as u32 * 3,
                reversed: m.edges.reversed[triangle],
            });
            vertices += u64::from(Patch::vertex_count(n));
            triangles += u64::from(n * n);
            if triangles > max_triangles || vertices > max_vertices || triangles * 3 > u64::from(u32::MAX) {
                return None;
            }
        }
        plan.meshes.push(MeshRanges {
            patches: start.0..plan.patches.len() as u32,
            first_vertex: start.1,
            vertices: vertices as u32 - start.1,
            first_index: start.2,
            indices: triangles as u32 * 3 - start.2,
        });
        first_triangle += m.edges.of_triangle.len() as u32;
    }
    (plan.vertices, plan.triangles) = (vertices as u32, triangles as u32);
    Some(plan)
}

/// The budget GPU displacement is drawn within: (triangles, vertices).
pub const BUDGET: (u32, u32) = (MAX_GPU_DISPLACED_TRIANGLES, MAX_GPU_DISPLACED_VERTICES);
