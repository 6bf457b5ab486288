// The mesh stages' interface with legacy.wgsl's per-vertex light direction and half vector:
// for the legacy looks and the per-vertex mistakes alone, as llvmpipe sets up and
// interpolates every vertex output, read or not. Appended to the mesh pass at build time
// instead of mesh_varyings.wgsl (render::shaders::MESH_PER_VERTEX).

struct PerVertexOutput {
    @builtin(position) clip_position: vec4<f32>,
    @location(0) world_position: vec3<f32>,
    @location(1) world_normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    @location(3) world_tangent: vec4<f32>,
    @location(4) vertex_light: vec3<f32>,
    @location(5) vertex_half: vec3<f32>,
};

alias Varyings = PerVertexOutput;

// What a vertex stage writes: VertexOutput with the per-vertex vectors (legacy.wgsl's
// vertex_vectors).
fn vertex_varyings(out: VertexOutput) -> Varyings {
    let vectors = vertex_vectors(out.world_position, out.world_normal);
    return PerVertexOutput(out.clip_position, out.world_position, out.world_normal, out.uv, out.world_tangent, vectors[0], vectors[1]);
}

// What a fragment stage shades: VertexOutput, the interpolated per-vertex vectors kept for the
// mistakes' hooks and the legacy looks (mistakes.wgsl's per_vertex).
fn fragment_inputs(in: Varyings) -> VertexOutput {
    per_vertex = PerVertexVectors(in.vertex_light, in.vertex_half);
    return VertexOutput(in.clip_position, in.world_position, in.world_normal, in.uv, in.world_tangent);
}
