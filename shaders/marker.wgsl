// The light marker: a small unlit octahedron in the light's colour.
// Prepended at build time: frame.wgsl.

@group(1) @binding(0) var<uniform> marker_model: mat4x4<f32>;

@vertex
fn vs_marker(@location(0) position: vec3<f32>) -> @builtin(position) vec4<f32> {
    return frame.view_proj * marker_model * vec4<f32>(position, 1.0);
}

@fragment
fn fs_marker() -> @location(0) vec4<f32> {
    return vec4<f32>(min(frame.light_color.rgb, vec3<f32>(1.0)), 1.0);
}
