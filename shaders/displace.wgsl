// GPU displacement (src/render/tessellation): writes the vertices and triangles of the
// patches the CPU planned (plan.rs) into the pool's vertex and index buffers, which the plain
// mesh pipeline then draws. The CPU twin of every vertex is displaced_vertex in
// src/prepare/displace.rs, formula for formula; keep the two in step.
//
// Each invocation makes one vertex (cs_vertices) or one triangle (cs_triangles) of one mesh's
// patches, found by a binary search over the patches' first vertex or index. Patch p's grid
// has n = segments cuts per side; vertex (i, j) sits at barycentric ((n − i − j)/n, i/n, j/n)
// and rows of n + 1 − i vertices follow each other. A vertex on edge k, cut into e ≤ n
// segments, moves to that edge's nearest of e + 1 points, computed from the edge's canonical
// end (plan.rs's `reversed`) so both of its triangles get bit-identical points.
//
// Prepended at build time (render::shaders::DISPLACE): frame.wgsl, object.wgsl and common.wgsl
// (height_sample, normalize_or); the bindings here are group 2's.

struct Patch {
    triangle: u32,
    segments: u32,
    edge_segments: array<u32, 3>,
    first_vertex: u32,
    first_index: u32,
    reversed: u32,
    // Per edge, its first point in seam_points, or NO_SEAM.
    seams: array<u32, 3>,
    pad: u32,
}

const NO_SEAM: u32 = 0xffffffffu;

// Per mesh: its patches, where its vertices and indices go, and its height map.
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
    // Invocations per row of workgroups (the dispatch may be two-dimensional).
    row: u32,
    // Points per seam edge less one: the finest cut of the seams (Seams::segments).
    seam_segments: u32,
}

// A base vertex: position and u, normal and v (model space), and its welded displaced
// position with w = 1 where copies of it meet (src/prepare/seams.rs), else zeros.
struct BaseVertex {
    position_u: vec4<f32>,
    normal_v: vec4<f32>,
    welded: vec4<f32>,
}

@group(2) @binding(0) var<uniform> params: Params;
@group(2) @binding(1) var<storage, read> base_vertices: array<BaseVertex>;
@group(2) @binding(2) var<storage, read> base_indices: array<u32>;
@group(2) @binding(3) var<storage, read> patches: array<Patch>;
@group(2) @binding(4) var<storage, read_write> out_positions: array<f32>;
@group(2) @binding(5) var<storage, read_write> out_normals: array<f32>;
@group(2) @binding(6) var<storage, read_write> out_uvs: array<f32>;
@group(2) @binding(7) var<storage, read_write> out_indices: array<u32>;
@group(2) @binding(8) var height_map: texture_2d<f32>;
@group(2) @binding(9) var<storage, read> seam_points: array<vec4<f32>>;

const WRAP_REPEAT: u32 = 0u;
const WRAP_CLAMP: u32 = 1u;

// ---- the height field, as src/scene/sample.rs reads level 0 ----

fn wrap_texel(i: i32, size: i32, wrap: u32) -> i32 {
    if wrap == WRAP_REPEAT {
        return ((i % size) + size) % size;
    }
    if wrap == WRAP_CLAMP {
        return clamp(i, 0, size - 1);
    }
    let m = ((i % (2 * size)) + 2 * size) % (2 * size);
    return select(2 * size - 1 - m, m, m < size);
}

fn texel(x: i32, y: i32, size: vec2<i32>) -> vec4<f32> {
    let at = vec2<i32>(wrap_texel(x, size.x, params.wrap_u), wrap_texel(y, size.y, params.wrap_v));
    return textureLoad(height_map, at, 0);
}

fn lerp4(a: vec4<f32>, b: vec4<f32>, t: f32) -> vec4<f32> {
    return a + (b - a) * t;
}

// The height (0..1, white = high) at uv: bilinear, as sample_bilinear.
fn height_at(uv: vec2<f32>) -> f32 {
    let size = vec2<i32>(textureDimensions(height_map, 0));
    let x = uv.x * f32(size.x) - 0.5;
    let y = uv.y * f32(size.y) - 0.5;
    let x0 = floor(x);
    let y0 = floor(y);
    let fx = x - x0;
    let fy = y - y0;
    let ix = i32(x0);
    let iy = i32(y0);
    let top = lerp4(texel(ix, iy, size), texel(ix + 1, iy, size), fx);
    let bottom = lerp4(texel(ix, iy + 1, size), texel(ix + 1, iy + 1, size), fx);
    let sample = height_sample(lerp4(top, bottom, fy));
    return select(sample, 1.0 - sample, params.depth_map != 0u);
}

// (∂h/∂u, ∂h/∂v) by central differences one texel apart.
fn height_gradient(uv: vec2<f32>) -> vec2<f32> {
    let size = vec2<f32>(textureDimensions(height_map, 0));
    let du = vec2<f32>(1.0 / size.x, 0.0);
    let dv = vec2<f32>(0.0, 1.0 / size.y);
    return vec2<f32>(
        (height_at(uv + du) - height_at(uv - du)) / (2.0 * du.x),
        (height_at(uv + dv) - height_at(uv - dv)) / (2.0 * dv.y),
    );
}

// ---- one vertex ----

struct Corners {
    p: array<vec3<f32>, 3>,
    n: array<vec3<f32>, 3>,
    uv: array<vec2<f32>, 3>,
    welded: array<vec4<f32>, 3>,
}

fn corners_of(piece: Patch) -> Corners {
    var c: Corners;
    for (var k = 0u; k < 3u; k++) {
        let v = base_vertices[base_indices[3u * piece.triangle + k]];
        c.p[k] = v.position_u.xyz;
        c.n[k] = v.normal_v.xyz;
        c.uv[k] = vec2<f32>(v.position_u.w, v.normal_v.w);
        c.welded[k] = v.welded;
    }
    return c;
}

// The undisplaced point: position, interpolated normal and UV; and, where it lies on a seam,
// its welded displaced position (w = 1; else w = 0).
struct Point {
    p: vec3<f32>,
    n: vec3<f32>,
    uv: vec2<f32>,
    welded: vec4<f32>,
}

fn corner_point(c: Corners, k: u32) -> Point {
    return Point(c.p[k], c.n[k], c.uv[k], c.welded[k]);
}

// Point m of the e + 1 on the edge from corner a to corner b, weighted in that order; on a
// seam its welded point, seam_points[seam + m · seam_segments / e] from the same end.
fn edge_point(c: Corners, a: u32, b: u32, m: u32, e: u32, seam: u32) -> Point {
    let wa = f32(e - m) / f32(e);
    let wb = f32(m) / f32(e);
    var welded = vec4<f32>(0.0);
    if seam != NO_SEAM {
        welded = seam_points[seam + m * (params.seam_segments / e)];
    }
    return Point(c.p[a] * wa + c.p[b] * wb, c.n[a] * wa + c.n[b] * wb, c.uv[a] * wa + c.uv[b] * wb, welded);
}

// Grid point k of n along edge `edge` (corner edge → edge + 1), moved to the nearest of the
// edge's own points, computed from its canonical end.
fn on_edge(c: Corners, piece: Patch, edge: u32, k: u32) -> Point {
    let n = piece.segments;
    let e = piece.edge_segments[edge];
    let m = (2u * k * e + n) / (2u * n);
    let start = edge;
    let end = (edge + 1u) % 3u;
    if m == 0u {
        return corner_point(c, start);
    }
    if m == e {
        return corner_point(c, end);
    }
    let seam = piece.seams[edge];
    if (piece.reversed & (1u << edge)) != 0u {
        return edge_point(c, end, start, e - m, e, seam);
    }
    return edge_point(c, start, end, m, e, seam);
}

// Grid vertex (i, j) of the patch, undisplaced.
fn grid_point(c: Corners, piece: Patch, i: u32, j: u32) -> Point {
    let n = piece.segments;
    if j == 0u {
        return on_edge(c, piece, 0u, i);
    }
    if i + j == n {
        return on_edge(c, piece, 1u, j);
    }
    if i == 0u {
        return on_edge(c, piece, 2u, n - j);
    }
    let w = vec3<f32>(f32(n - i - j), f32(i), f32(j)) / f32(n);
    return Point(
        c.p[0] * w.x + c.p[1] * w.y + c.p[2] * w.z,
        c.n[0] * w.x + c.n[1] * w.y + c.n[2] * w.z,
        c.uv[0] * w.x + c.uv[1] * w.y + c.uv[2] * w.z,
        vec4<f32>(0.0),
    );
}

// displaced_vertex: the point moved by (h − 1) · depth along its unit normal (or, on a seam, to
// its welded point), and the exact normal of this surface, as long as the interpolated one.
fn displaced(c: Corners, point: Point) -> Point {
    let face = cross(c.p[1] - c.p[0], c.p[2] - c.p[0]);
    let length = length(point.n);
    var unit = normalize_or(face, vec3<f32>(0.0, 0.0, 1.0));
    if length > 1e-12 {
        unit = point.n / length;
    }
    let depth = params.depth_m;
    if depth == 0.0 {
        return point;
    }
    let lift = (height_at(point.uv) - 1.0) * depth;
    let gradient = height_gradient(point.uv);
    var along: array<vec3<f32>, 2>;
    for (var k = 1u; k < 3u; k++) {
        let edge = c.p[k] - c.p[0];
        let tangent = edge - unit * dot(unit, edge);
        let d_normal = c.n[k] - c.n[0];
        let d_unit = (d_normal - unit * dot(unit, d_normal)) / max(length, 1e-12);
        along[k - 1u] = tangent + d_unit * lift + unit * (depth * dot(gradient, c.uv[k] - c.uv[0]));
    }
    let side = select(1.0, -1.0, dot(face, unit) < 0.0);
    let exact = normalize_or(cross(along[0], along[1]) * side, unit);
    var moved = point.p + unit * lift;
    if point.welded.w != 0.0 {
        moved = point.welded.xyz;
    }
    return Point(moved, exact * max(length, 1e-12), point.uv, point.welded);
}

// ---- finding an invocation's patch ----

fn invocation(id: vec3<u32>) -> u32 {
    return id.x + id.y * params.row;
}

// The last of the mesh's patches whose first vertex (or index, when `by_index`) is at most
// `at`.
fn patch_at(at: u32, by_index: bool) -> Patch {
    var low = params.first_patch;
    var high = params.first_patch + params.patch_count - 1u;
    while low < high {
        let middle = (low + high + 1u) / 2u;
        let first = select(patches[middle].first_vertex, patches[middle].first_index, by_index);
        if first <= at {
            low = middle;
        } else {
            high = middle - 1u;
        }
    }
    return patches[low];
}

// Vertex (i, j) of a grid of n: its index within the patch.
fn grid_index(n: u32, i: u32, j: u32) -> u32 {
    return i * (n + 1u) - i * (max(i, 1u) - 1u) / 2u + j;
}

@compute @workgroup_size(64)
fn cs_vertices(@builtin(global_invocation_id) id: vec3<u32>) {
    let g = invocation(id);
    if g >= params.vertex_count {
        return;
    }
    let at = params.first_vertex + g;
    let piece = patch_at(at, false);
    let n = piece.segments;
    let local = at - piece.first_vertex;
    // Row i starts at grid_index(n, i, 0); solve for i, then mend float rounding.
    let b = 2.0 * f32(n) + 3.0;
    var i = u32(max(floor((b - sqrt(max(b * b - 8.0 * f32(local), 0.0))) / 2.0), 0.0));
    i = min(i, n);
    while i > 0u && grid_index(n, i, 0u) > local {
        i -= 1u;
    }
    while i < n && grid_index(n, i + 1u, 0u) <= local {
        i += 1u;
    }
    let j = local - grid_index(n, i, 0u);
    let c = corners_of(piece);
    let v = displaced(c, grid_point(c, piece, i, j));
    out_positions[3u * at] = v.p.x;
    out_positions[3u * at + 1u] = v.p.y;
    out_positions[3u * at + 2u] = v.p.z;
    out_normals[3u * at] = v.n.x;
    out_normals[3u * at + 1u] = v.n.y;
    out_normals[3u * at + 2u] = v.n.z;
    out_uvs[2u * at] = v.uv.x;
    out_uvs[2u * at + 1u] = v.uv.y;
}

@compute @workgroup_size(64)
fn cs_triangles(@builtin(global_invocation_id) id: vec3<u32>) {
    let g = invocation(id);
    if g >= params.triangle_count {
        return;
    }
    let at = params.first_index + 3u * g;
    let piece = patch_at(at, true);
    let n = piece.segments;
    let local = (at - piece.first_index) / 3u;
    // Row i holds 2(n − i) − 1 triangles and starts at i(2n − i): solve for i, then mend.
    var i = u32(max(floor(f32(n) - sqrt(max(f32(n) * f32(n) - f32(local), 0.0))), 0.0));
    i = min(i, n - 1u);
    while i > 0u && i * (2u * n - i) > local {
        i -= 1u;
    }
    while i + 1u < n && (i + 1u) * (2u * n - i - 1u) <= local {
        i += 1u;
    }
    let k = local - i * (2u * n - i);
    let j = k / 2u;
    var corners = vec3<u32>(grid_index(n, i, j), grid_index(n, i + 1u, j), grid_index(n, i, j + 1u));
    if k % 2u == 1u {
        corners = vec3<u32>(grid_index(n, i + 1u, j), grid_index(n, i + 1u, j + 1u), grid_index(n, i, j + 1u));
    }
    out_indices[at] = piece.first_vertex + corners.x;
    out_indices[at + 1u] = piece.first_vertex + corners.y;
    out_indices[at + 2u] = piece.first_vertex + corners.z;
}
