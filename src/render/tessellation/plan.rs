//! Which base triangles the GPU tessellates this frame, and how finely: the CPU half of GPU
//! displacement. Per base edge, the number of segments is the fewest that cut its projection
//! on screen into pieces no longer than the target (in pixels), at most
//! [`MAX_GPU_EDGE_SEGMENTS`] (on a seam, the next power of two: its welded points are made
//! once, at the finest cut, [`crate::prepare::seams`]); a triangle is cut into `n²` on a
//! barycentric grid of `n`, the most its three edges ask, and a grid vertex on an edge cut
//! into fewer segments `e` is moved to the nearest of that edge's own `e + 1` points. Both triangles on an edge meet it in the
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
    /// `n`: the grid's segments per side.
    pub segments: u32,
    /// Segments of edge `k`, from corner `k` to corner `k + 1` (at most `n`; powers of two on
    /// seams).
    pub edge_segments: [u32; 3],
    pub first_vertex: u32,
    pub first_index: u32,
    /// Bit `k`: edge `k` runs against its canonical direction (from the larger end position
    /// to the smaller), in which both its triangles compute its points.
    pub reversed: u32,
    /// Per edge, its first welded point in the seam table ([`crate::prepare::seams`]), or
    /// [`NO_SEAM`].
    pub seams: [u32; 3],
    pub pad: u32,
}

/// [`Patch::seams`] of an edge that is no seam.
pub const NO_SEAM: u32 = u32::MAX;

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
    /// Per triangle, per edge: its first point in the seam table, if it is a seam.
    pub seams: &'a [[Option<u32>; 3]],
    /// The finest cut of a seam edge (a power of two): its welded points are made at it.
    pub seam_segments: u32,
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
/// unless `cull_back_faces` is off it is not far past the horizon at every corner.
///
/// Relief is carved inward, so near a silhouette the front's grooves uncover what lies just
/// past the horizon, whose brick sides face the eye although the base triangle does not. On a
/// surface curved with radius `r`, a point `φ` past the horizon lies `r (1 − cos φ)` behind
/// the horizon's tangent plane, so grooves `depth` deep uncover at most `φ ≈ √(2 depth / r)`;
/// a triangle is culled only where every corner is half as far again past that. The radius is
/// estimated from how much the triangle's normals turn along its longest edge.
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
    let longest = (0..3).map(|k| p[k].distance(p[(k + 1) % 3])).fold(0.0, f32::max);
    let model_normals = n.map(|q| q.normalize_or_zero());
    let turn = (0..3).map(|k| model_normals[k].angle_between(model_normals[(k + 1) % 3])).fold(0.0, f32::max);
    // d / r with r = longest / turn; a flat triangle (turn 0) uncovers nothing past its horizon.
    let depth_over_radius = if longest > 0.0 { depth_m.abs() * turn / longest } else { 0.0 };
    let past = (1.5 * (2.0 * depth_over_radius).sqrt()).min(1.0);
    let face = (world[1] - world[0]).cross(world[2] - world[0]).normalize_or_zero();
    let face = if transform.determinant() < 0.0 { -face } else { face };
    (0..3).any(|k| {
        let to_eye = (view.eye - world[k]).normalize_or_zero();
        face.dot(to_eye) >= -past || normals[k].dot(to_eye) >= -past
    })
}

/// Segments for an edge `pixels` long at a target of `target` pixels per segment; on a seam, a
/// power of two, at most `seam` (its finest cut).
fn segments_for(pixels: f32, target: f32, seam: Option<u32>) -> u32 {
    let wanted = pixels / target;
    // NaN and anything past the maximum ask for the most.
    let segments = if wanted.is_nan() || wanted >= MAX_GPU_EDGE_SEGMENTS as f32 {
        MAX_GPU_EDGE_SEGMENTS
    } else {
        wanted.ceil().max(1.0) as u32
    };
    match seam {
        Some(finest) => segments.next_power_of_two().min(finest),
        None => segments,
    }
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
        let mut seam = vec![false; lengths.len()];
        for (edges, seams) in m.edges.of_triangle.iter().zip(m.seams) {
            for k in 0..3 {
                seam[edges[k] as usize] |= seams[k].is_some();
            }
        }
        let segments: Vec<u32> =
            lengths.iter().zip(&seam).map(|(&l, &s)| segments_for(l, target, s.then_some(m.seam_segments))).collect();
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
                seams: m.seams[triangle].map(|s| s.unwrap_or(NO_SEAM)),
                pad: 0,
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

#[cfg(test)]
mod tests {
    use glam::Vec2;

    use super::*;
    use crate::scene::OrbitCamera;

    /// A `cells × cells` grid of quads, two triangles each, in the z = 0 plane facing +Z,
    /// `side` metres wide, centred on the origin.
    fn grid(cells: u32, side: f32) -> Mesh {
        let mut mesh = Mesh::empty("grid");
        for y in 0..=cells {
            for x in 0..=cells {
                let (u, v) = (x as f32 / cells as f32, y as f32 / cells as f32);
                mesh.positions.push(Vec3::new((u - 0.5) * side, (v - 0.5) * side, 0.0));
                mesh.normals.push(Vec3::Z);
                mesh.uvs.push(Vec2::new(u, 1.0 - v));
            }
        }
        let at = |x: u32, y: u32| y * (cells + 1) + x;
        for y in 0..cells {
            for x in 0..cells {
                mesh.indices.extend([
                    at(x, y),
                    at(x + 1, y),
                    at(x + 1, y + 1),
                    at(x, y),
                    at(x + 1, y + 1),
                    at(x, y + 1),
                ]);
            }
        }
        mesh
    }

    fn view_from(yaw_deg: f32, distance: f32) -> View {
        let camera = OrbitCamera {
            target: Vec3::ZERO,
            yaw: yaw_deg.to_radians(),
            pitch: 0.0,
            distance,
            fov_y: 50f32.to_radians(),
        };
        View { view_projection: camera.view_projection(16.0 / 9.0), eye: camera.eye(), size: [1280, 720] }
    }

    fn planned<'a>(mesh: &'a Mesh, edges: &'a MeshEdges, seams: &'a [[Option<u32>; 3]]) -> PlannedMesh<'a> {
        PlannedMesh {
            mesh,
            edges,
            transforms: vec![Mat4::IDENTITY],
            depth_m: 0.01,
            cull_back_faces: true,
            seams,
            seam_segments: MAX_GPU_EDGE_SEGMENTS,
        }
    }

    /// Each shared edge is one edge (a 4 × 4 grid has 40 sides and 16 diagonals), and a
    /// triangle's edges run against their canonical direction exactly where the shared edge's
    /// other triangle runs with it.
    #[test]
    fn shared_edges_are_one_edge_in_one_direction() {
        let mesh = grid(4, 1.0);
        let edges = MeshEdges::of(&mesh);
        assert_eq!(edges.ends.len(), 56);
        let mut seen: HashMap<u32, Vec<bool>> = HashMap::new();
        for (ids, reversed) in edges.of_triangle.iter().zip(&edges.reversed) {
            for (k, id) in ids.iter().enumerate() {
                seen.entry(*id).or_default().push(reversed & (1 << k) != 0);
            }
        }
        assert!(seen.values().filter(|s| s.len() == 2).all(|s| s[0] != s[1]));
    }

    /// Segments are at most the maximum; a patch's grid is its longest edge's;
    /// the ranges add up; nearer the camera, more segments.
    #[test]
    fn segments_follow_the_edges_on_screen() {
        let mesh = grid(4, 1.0);
        let (edges, seams) = (MeshEdges::of(&mesh), vec![[None; 3]; 32]);
        let far = plan(&[planned(&mesh, &edges, &seams)], &view_from(0.0, 3.0), 4.0, BUDGET);
        let near = plan(&[planned(&mesh, &edges, &seams)], &view_from(0.0, 1.5), 4.0, BUDGET);
        for p in &far.patches {
            assert!(p.edge_segments.iter().all(|s| (1..=MAX_GPU_EDGE_SEGMENTS).contains(s)));
            assert_eq!(p.segments, *p.edge_segments.iter().max().unwrap());
        }
        let triangles: u32 = far.patches.iter().map(|p| p.segments * p.segments).sum();
        assert_eq!((far.triangles, far.meshes[0].indices), (triangles, 3 * triangles));
        assert_eq!(far.pixels_per_edge, 4.0);
        assert!(near.triangles >= 3 * far.triangles, "{} against {}", near.triangles, far.triangles);
    }

    /// Past the budget the target edge grows by √2 until the plan fits, and says so.
    #[test]
    fn the_budget_lengthens_the_edges() {
        let mesh = grid(4, 1.0);
        let (edges, seams) = (MeshEdges::of(&mesh), vec![[None; 3]; 32]);
        let free = plan(&[planned(&mesh, &edges, &seams)], &view_from(0.0, 1.5), 1.0, BUDGET);
        let budget = (free.triangles / 5, free.vertices / 5);
        let tight = plan(&[planned(&mesh, &edges, &seams)], &view_from(0.0, 1.5), 1.0, budget);
        assert!(tight.triangles <= budget.0 && tight.vertices <= budget.1);
        assert!(tight.pixels_per_edge > 1.0, "{}", tight.pixels_per_edge);
        // One √2 step less would not have fitted.
        let finer = plan(&[planned(&mesh, &edges, &seams)], &view_from(0.0, 1.5), tight.pixels_per_edge / 1.5, BUDGET);
        assert!(finer.triangles > budget.0 || finer.vertices > budget.1);
        // A budget below the base mesh draws the base mesh.
        let base = plan(&[planned(&mesh, &edges, &seams)], &view_from(0.0, 1.5), 1.0, (1, 1));
        assert_eq!(base.triangles, 32);
    }

    /// Seen from behind, the single-sided grid is culled; double-sided it is not; a grid behind
    /// the camera is culled either way.
    #[test]
    fn culling_by_facing_and_frustum() {
        let mesh = grid(4, 1.0);
        let (edges, seams) = (MeshEdges::of(&mesh), vec![[None; 3]; 32]);
        let behind = view_from(180.0, 2.0);
        let single = plan(&[planned(&mesh, &edges, &seams)], &behind, 4.0, BUDGET);
        assert_eq!((single.culled, single.triangles), (32, 0));
        let double = PlannedMesh { cull_back_faces: false, ..planned(&mesh, &edges, &seams) };
        assert_eq!(plan(&[double], &behind, 4.0, BUDGET).culled, 0);
        let away =
            PlannedMesh { transforms: vec![Mat4::from_translation(Vec3::Z * 10.0)], ..planned(&mesh, &edges, &seams) };
        assert_eq!(plan(&[away], &view_from(0.0, 2.0), 4.0, BUDGET).culled, 32);
    }
}
