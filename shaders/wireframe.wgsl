// The wireframe overlay's pass: the triangle edges in a dim colour, drawn after the meshes with
// PolygonMode::Line (src/render/wireframe.rs). Prepended at build time: frame.wgsl, object.wgsl,
// common.wgsl (render::shaders::WIREFRAME).

@vertex
fn vs_wireframe(@location(0) position: vec3<f32>) -> @builtin(position) vec4<f32> {
    return frame.view_proj * (object.model * vec4<f32>(position, 1.0));
}

@fragment
fn fs_wireframe() -> @location(0) vec4<f32> {
    return stored(vec3<f32>(0.08, 0.08, 0.1));
}
