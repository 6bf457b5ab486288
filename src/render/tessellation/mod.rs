//! Displacement on the GPU, every time the view changes: the CPU plans which base triangles
//! are cut how finely for this view ([`plan`]), and a compute pass (shaders/displace.wgsl)
//! writes the displaced vertices and triangles into one pool of vertex and index buffers,
//! which the plain mesh pipeline draws as it draws the CPU's displaced meshes. wgpu has no
//! tessellation stage; compute work and an ordinary draw also run in WebGPU. The pool is
//! sized to the frame's need (grown by doubling, within [`plan::BUDGET`]: at most 16 MiB),
//! where the CPU's level 5 of the built-in scene holds 185 MiB.
//!
//! References: Khoury, Dupuy & Riccio 2018, "Adaptive GPU tessellation with compute shaders"
//! (per-frame subdivision from projected edge lengths in compute) and the DirectX 11 hull
//! stage's integer edge factors, of which the per-edge segments here, with the inner grid's
//! edge vertices snapped to them, are the simplest crack-free form. The result is measured against the CPU tessellation (tests/gpu_displacement.rs).

pub mod pipelines;
pub mod plan;
mod read_back;

use std::sync::Mutex;

use glam::Mat4;

use self::pipelines::DisplacePipelines;
use self::plan::{MeshEdges, Plan, PlannedMesh, View};
use super::bindings;
use super::gpu_errors::buffer_with;
use crate::prepare::{PreparedScene, seams};
use crate::scene::Mesh;

/// The vertex streams and the index range a mesh is drawn with this frame.
pub struct DrawnStreams {
    pub positions: wgpu::Buffer,
    pub normals: wgpu::Buffer,
    pub uvs: wgpu::Buffer,
    pub indices: wgpu::Buffer,
    pub range: std::ops::Range<u32>,
}

/// One mesh the GPU displaces.
struct TessellatedMesh {
    /// Its index in the prepared scene's meshes.
    mesh: usize,
    /// The base mesh as prepared (model space).
    base: Mesh,
    /// Per triangle, per edge: its first point in the seam table, if it is a seam.
    seams: Vec<[Option<u32>; 3]>,
    edges: MeshEdges,
    /// The model matrices of the instances that draw it.
    transforms: Vec<Mat4>,
    depth_m: f32,
    cull_back_faces: bool,
    /// Its [`Params`] uniform.
    params: wgpu::Buffer,
    height_map: wgpu::TextureView,
    depth_map: bool,
    wrap: [u32; 2],
}

/// One mesh's uniform of the compute pass: the WGSL `Params`.
#[repr(C)]
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct Params {
    first_patch: u32,
    patch_count: u32,
    first_vertex: u32,
    vertex_count: u32,
    first_index: u32,
    triangle_count: u32,
    depth_map: u32,
    wrap_u: u32,
    wrap_v: u32,
    depth_m: f32,
    row: u32,
    seam_segments: u32,
}

/// The buffers a frame's tessellation is written into, and the bind groups over them.
struct Pool {
    positions: wgpu::Buffer,
    normals: wgpu::Buffer,
    uvs: wgpu::Buffer,
    indices: wgpu::Buffer,
    /// (vertices, triangles) they hold.
    capacity: (u32, u32),
    /// Per mesh.
    bind_groups: Vec<wgpu::BindGroup>,
}

/// What the last tessellation drew.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GpuDisplacementStats {
    pub vertices: u32,
    pub triangles: u32,
    /// The pool's buffers (bytes): vertices, indices, patches and the base mesh.
    pub bytes: u64,
    /// The target edge asked for and the one drawn (pixels); larger where the budget said so.
    pub pixels_asked: f32,
    pub pixels_drawn: f32,
    /// Base triangles left out (outside the view, or facing away).
    pub culled: u32,
}

impl GpuDisplacementStats {
    /// `GPU: T triangles, V vertices, M MiB`, and why the edges are longer than asked.
    pub fn summary(&self) -> String {
        let mib = self.bytes as f64 / (1024.0 * 1024.0);
        let mut text = format!("GPU: {} triangles, {} vertices, {mib:.1} MiB", self.triangles, self.vertices);
        if let Some(notice) = self.budget_notice() {
            text = format!("{text} ({notice})");
        }
        text
    }

    /// Said while the budget made the edges longer than asked.
    pub fn budget_notice(&self) -> Option<String> {
        (self.pixels_drawn > self.pixels_asked).then(|| {
            let (triangles, vertices) = plan::BUDGET;
            format!(
                "{BUDGET_NOTICE_START} {:.1} px edges, not {}: finer would pass the budget of {triangles} triangles and {vertices} vertices",
                self.pixels_drawn, self.pixels_asked
            )
        })
    }
}

/// Said where the device has no compute shaders (WebGL2): the meshes are drawn undisplaced.
pub const NO_COMPUTE_NOTICE: &str =
    "GPU displacement needs compute shaders, which this device does not have: drawn undisplaced";

/// How [`GpuDisplacementStats::budget_notice`] begins.
pub const BUDGET_NOTICE_START: &str = "GPU displacement drawn with";

/// What the view was when the pool was last written.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Key {
    view: View,
    pixels_per_edge: f32,
}

#[derive(Default)]
struct State {
    key: Option<Key>,
    pool: Option<Pool>,
    plan: Option<Plan>,
    stats: Option<GpuDisplacementStats>,
    /// The prepared scene with the meshes of this tessellation, once read back.
    drawn: Option<std::sync::Arc<PreparedScene>>,
}

/// A scene's GPU displacement: its base meshes on the GPU, and the pool of the last frame.
pub struct Tessellation {
    meshes: Vec<TessellatedMesh>,
    base_vertices: wgpu::Buffer,
    base_indices: wgpu::Buffer,
    patches: wgpu::Buffer,
    /// The welded points of the seams ([`seams::Seams::points`], `xyz` and 1).
    seam_points: wgpu::Buffer,
    /// The seams' finest cut ([`seams::Seams::segments`]).
    seam_segments: u32,
    base_bytes: u64,
    pixels_per_edge: f32,
    state: Mutex<State>,
}

/// A base vertex as the compute pass reads it: `position, u`, `normal, v`, and its welded
/// displaced position with `w` 1 where it is welded ([`Seams::corners`]), else zeros.
#[repr(C)]
#[derive(Debug, Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct BaseVertex {
    position_u: [f32; 4],
    normal_v: [f32; 4],
    welded: [f32; 4],
}

impl Tessellation {
    /// The GPU displacement of `prepared`'s [`PreparedScene::gpu_displaced`] meshes, each height
    /// map a view given by `height_map`; `None` when it has none.
    pub fn new(
        device: &wgpu::Device,
        prepared: &PreparedScene,
        mut height_map: impl FnMut(usize) -> wgpu::TextureView,
    ) -> Option<Tessellation> {
        let pixels_per_edge = prepared.options.displacement.gpu?;
        if prepared.gpu_displaced.is_empty() {
            return None;
        }
        let mut seams = seams::seams(prepared);
        let (mut vertices, mut indices, mut meshes) = (vec![], vec![], vec![]);
        for (k, displaced) in prepared.gpu_displaced.iter().enumerate() {
            let mesh = &prepared.meshes[displaced.mesh].mesh;
            let first_vertex = vertices.len() as u32;
            let streams = mesh.positions.iter().zip(&mesh.normals).zip(&mesh.uvs).zip(&seams.corners[k]);
            vertices.extend(streams.map(|(((p, n), uv), welded)| BaseVertex {
                position_u: [p.x, p.y, p.z, uv.x],
                normal_v: [n.x, n.y, n.z, uv.y],
                welded: welded.map_or([0.0; 4], |w| [w.x, w.y, w.z, 1.0]),
            }));
            indices.extend(mesh.indices.iter().map(|i| first_vertex + i));
            let drawing = prepared.instances.iter().filter(|i| i.mesh == displaced.mesh);
            let material =
                &prepared.scene.materials[prepared.instances.iter().find(|i| i.mesh == displaced.mesh)?.material];
            meshes.push(TessellatedMesh {
                mesh: displaced.mesh,
                base: mesh.clone(),
                seams: std::mem::take(&mut seams.edges[k]),
                edges: MeshEdges::of(mesh),
                transforms: drawing.map(|i| i.transform).collect(),
                depth_m: displaced.depth_m,
                cull_back_faces: !material.double_sided,
                params: device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("GPU displacement parameters"),
                    size: std::mem::size_of::<Params>() as u64,
                    usage: wgpu::BufferUsages::UNIFORM | wgpu::BufferUsages::COPY_DST,
                    mapped_at_creation: false,
                }),
                height_map: height_map(displaced.height_texture),
                depth_map: displaced.depth_map,
                wrap: [displaced.wrap.u, displaced.wrap.v].map(wrap_index),
            });
        }
        let storage = wgpu::BufferUsages::STORAGE;
        let base_triangles = (indices.len() / 3).max(1) as u64;
        let patches = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("GPU displacement patches"),
            size: base_triangles * std::mem::size_of::<plan::Patch>() as u64,
            usage: storage | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let base_bytes = (vertices.len() * std::mem::size_of::<BaseVertex>() + indices.len() * 4) as u64
            + base_triangles * std::mem::size_of::<plan::Patch>() as u64;
        // At least one point: a binding holds one element or more.
        let mut points: Vec<[f32; 4]> = seams.points.iter().map(|p| [p.x, p.y, p.z, 1.0]).collect();
        points.resize(points.len().max(1), [0.0; 4]);
        let seam_points = buffer_with(device, "GPU displacement seam points", bytemuck::cast_slice(&points), storage);
        let base_bytes = base_bytes + seam_points.size();
        Some(Tessellation {
            seam_points,
            seam_segments: seams.segments,
            base_vertices: buffer_with(
                device,
                "GPU displacement base vertices",
                bytemuck::cast_slice(&vertices),
                storage,
            ),
            base_indices: buffer_with(device, "GPU displacement base indices", bytemuck::cast_slice(&indices), storage),
            patches,
            base_bytes,
            meshes,
            pixels_per_edge,
            state: Mutex::new(State::default()),
        })
    }

    /// Whether mesh `mesh` of the prepared scene is displaced here.
    pub fn displaces(&self, mesh: usize) -> bool {
        self.meshes.iter().any(|m| m.mesh == mesh)
    }

    /// What the last tessellation drew.
    pub fn stats(&self) -> Option<GpuDisplacementStats> {
        self.state.lock().expect("tessellation state").stats
    }

    /// The vertex streams and the index range mesh `mesh` is drawn with this frame; `None`
    /// before the first tessellation.
    pub fn drawn(&self, mesh: usize) -> Option<DrawnStreams> {
        let state = self.state.lock().expect("tessellation state");
        let (pool, plan) = (state.pool.as_ref()?, state.plan.as_ref()?);
        let k = self.meshes.iter().position(|m| m.mesh == mesh)?;
        let ranges = &plan.meshes[k];
        let range = ranges.first_index..ranges.first_index + ranges.indices;
        Some(DrawnStreams {
            positions: pool.positions.clone(),
            normals: pool.normals.clone(),
            uvs: pool.uvs.clone(),
            indices: pool.indices.clone(),
            range,
        })
    }

    /// Tessellates for `view` into `encoder` unless the pool already holds this view's.
    pub fn run(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        encoder: &mut wgpu::CommandEncoder,
        pipelines: &DisplacePipelines,
        view: View,
    ) {
        let mut state = self.state.lock().expect("tessellation state");
        let key = Key { view, pixels_per_edge: self.pixels_per_edge };
        if state.key == Some(key) && state.pool.is_some() {
            return;
        }
        let planned: Vec<PlannedMesh> = self
            .meshes
            .iter()
            .map(|m| PlannedMesh {
                mesh: &m.base,
                edges: &m.edges,
                transforms: m.transforms.clone(),
                depth_m: m.depth_m,
                cull_back_faces: m.cull_back_faces,
                seams: &m.seams,
                seam_segments: self.seam_segments,
            })
            .collect();
        let plan = plan::plan(&planned, &view, self.pixels_per_edge, plan::BUDGET);
        let capacity = state.pool.as_ref().map_or((0, 0), |p| p.capacity);
        if plan.vertices > capacity.0 || plan.triangles > capacity.1 {
            let (max_triangles, max_vertices) = plan::BUDGET;
            let grown =
                (grow(capacity.0, plan.vertices, max_vertices), grow(capacity.1, plan.triangles, max_triangles));
            state.pool = Some(self.pool(device, pipelines, grown));
        }
        let pool = state.pool.as_ref().expect("made above");
        if !plan.patches.is_empty() {
            queue.write_buffer(&self.patches, 0, bytemuck::cast_slice(&plan.patches));
        }
        let mut pass = encoder.begin_compute_pass(&wgpu::ComputePassDescriptor {
            label: Some("GPU displacement"),
            timestamp_writes: None,
        });
        for ((mesh, ranges), bind_group) in self.meshes.iter().zip(&plan.meshes).zip(&pool.bind_groups) {
            if ranges.patches.is_empty() {
                continue;
            }
            let (vertex_groups, triangle_groups) = (ranges.vertices.div_ceil(64), (ranges.indices / 3).div_ceil(64));
            let row = pipelines::ROW_GROUPS;
            let params = Params {
                first_patch: ranges.patches.start,
                patch_count: ranges.patches.len() as u32,
                first_vertex: ranges.first_vertex,
                vertex_count: ranges.vertices,
                first_index: ranges.first_index,
                triangle_count: ranges.indices / 3,
                depth_map: u32::from(mesh.depth_map),
                wrap_u: mesh.wrap[0],
                wrap_v: mesh.wrap[1],
                depth_m: mesh.depth_m,
                row: row * 64,
                seam_segments: self.seam_segments,
            };
            queue.write_buffer(&mesh.params, 0, bytemuck::bytes_of(&params));
            pass.set_bind_group(2, bind_group, &[]);
            for (pipeline, groups) in [(&pipelines.vertices, vertex_groups), (&pipelines.triangles, triangle_groups)] {
                pass.set_pipeline(pipeline);
                pass.dispatch_workgroups(groups.min(row), groups.div_ceil(row), 1);
            }
        }
        drop(pass);
        let bytes = pool_bytes(pool.capacity) + self.base_bytes;
        state.stats = Some(GpuDisplacementStats {
            vertices: plan.vertices,
            triangles: plan.triangles,
            bytes,
            pixels_asked: self.pixels_per_edge,
            pixels_drawn: plan.pixels_per_edge,
            culled: plan.culled,
        });
        state.plan = Some(plan);
        state.key = Some(key);
        state.drawn = None;
    }

    /// A pool holding `(vertices, triangles)`, with each mesh's bind group over it.
    fn pool(&self, device: &wgpu::Device, pipelines: &DisplacePipelines, capacity: (u32, u32)) -> Pool {
        let usage = wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::VERTEX | wgpu::BufferUsages::COPY_SRC;
        let make = |label: &str, bytes: u64, usage: wgpu::BufferUsages| {
            device.create_buffer(&wgpu::BufferDescriptor {
                label: Some(label),
                size: bytes.max(4),
                usage,
                mapped_at_creation: false,
            })
        };
        let (vertices, triangles) = (u64::from(capacity.0), u64::from(capacity.1));
        let positions = make("GPU displacement positions", vertices * 12, usage);
        let normals = make("GPU displacement normals", vertices * 12, usage);
        let uvs = make("GPU displacement uvs", vertices * 8, usage);
        let indices = make(
            "GPU displacement indices",
            triangles * 12,
            wgpu::BufferUsages::STORAGE | wgpu::BufferUsages::INDEX | wgpu::BufferUsages::COPY_SRC,
        );
        let bind_groups = self
            .meshes
            .iter()
            .map(|mesh| {
                device.create_bind_group(&wgpu::BindGroupDescriptor {
                    label: Some("GPU displacement"),
                    layout: &pipelines.layout,
                    entries: &[
                        bindings::DISPLACE_PARAMS.entry(wgpu::Buffer::as_entire_binding(&mesh.params)),
                        bindings::DISPLACE_BASE_VERTICES.entry(wgpu::Buffer::as_entire_binding(&self.base_vertices)),
                        bindings::DISPLACE_BASE_INDICES.entry(wgpu::Buffer::as_entire_binding(&self.base_indices)),
                        bindings::DISPLACE_PATCHES.entry(wgpu::Buffer::as_entire_binding(&self.patches)),
                        bindings::DISPLACE_SEAM_POINTS.entry(wgpu::Buffer::as_entire_binding(&self.seam_points)),
                        bindings::DISPLACE_POSITIONS.entry(wgpu::Buffer::as_entire_binding(&positions)),
                        bindings::DISPLACE_NORMALS.entry(wgpu::Buffer::as_entire_binding(&normals)),
                        bindings::DISPLACE_UVS.entry(wgpu::Buffer::as_entire_binding(&uvs)),
                        bindings::DISPLACE_INDICES.entry(wgpu::Buffer::as_entire_binding(&indices)),
                        bindings::DISPLACE_HEIGHT_MAP.entry(wgpu::BindingResource::TextureView(&mesh.height_map)),
                    ],
                })
            })
            .collect();
        Pool { positions, normals, uvs, indices, capacity, bind_groups }
    }
}

/// Bytes of a pool holding `(vertices, triangles)`: 32 per vertex, 12 per triangle.
fn pool_bytes((vertices, triangles): (u32, u32)) -> u64 {
    u64::from(vertices) * 32 + u64::from(triangles) * 12
}

/// A capacity that holds `needed`: doubled from `current` (at least 4096), at most `budget`
/// unless the need itself is larger (a base mesh past it).
fn grow(current: u32, needed: u32, budget: u32) -> u32 {
    let mut capacity = current.max(4096);
    while capacity < needed {
        capacity = capacity.saturating_mul(2);
    }
    capacity.min(budget).max(needed)
}

/// The shader's wrap mode numbers (`WRAP_REPEAT`, `WRAP_CLAMP`, else mirrored).
fn wrap_index(wrap: crate::scene::Wrap) -> u32 {
    match wrap {
        crate::scene::Wrap::Repeat => 0,
        crate::scene::Wrap::ClampToEdge => 1,
        crate::scene::Wrap::MirroredRepeat => 2,
    }
}

#[cfg(test)]
mod tests {
    use wgpu::naga;

    use super::*;

    /// The compute pass's buffers hold what shaders/displace.wgsl reads: each Rust struct has
    /// its WGSL twin's size.
    #[test]
    fn the_structs_have_the_wgsl_sizes() {
        let source = crate::render::shaders::DISPLACE.source();
        let module = naga::front::wgsl::parse_str(&source).expect("displace.wgsl parses");
        let mut layouter = naga::proc::Layouter::default();
        layouter.update(module.to_ctx()).expect("its types have a layout");
        for (name, rust_size) in [
            ("Params", std::mem::size_of::<Params>()),
            ("Patch", std::mem::size_of::<plan::Patch>()),
            ("BaseVertex", std::mem::size_of::<BaseVertex>()),
        ] {
            let (handle, _) = module.types.iter().find(|(_, t)| t.name.as_deref() == Some(name)).expect(name);
            assert_eq!(layouter[handle].size as usize, rust_size, "WGSL {name} against its Rust struct");
        }
    }
}
