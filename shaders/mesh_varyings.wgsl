// The mesh stages' interface of most pipelines: VertexOutput itself. Appended to the mesh
// pass at build time instead of mesh_varyings_per_vertex.wgsl (render::shaders::MESH).

alias Varyings = VertexOutput;

// What a vertex stage writes.
fn vertex_varyings(out: VertexOutput) -> Varyings {
    return out;
}

// What a fragment stage shades.
fn fragment_inputs(in: Varyings) -> VertexOutput {
    return in;
}
