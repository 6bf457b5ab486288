// The adapter's floor (src/render/floor.rs): one triangle covering the whole target, of one
// colour, depth-tested and written like the scene's meshes. The least any frame costs.

@vertex
fn vs_floor(@builtin(vertex_index) index: u32) -> @builtin(position) vec4<f32> {
    // (-1, -1), (3, -1), (-1, 3): the clip square lies inside.
    let corner = vec2<f32>(f32((index << 1u) & 2u), f32(index & 2u));
    return vec4<f32>(corner * 2.0 - 1.0, 0.5, 1.0);
}

@fragment
fn fs_floor() -> @location(0) vec4<f32> {
    return vec4<f32>(0.5, 0.5, 0.5, 1.0);
}
