// The light markers: a small unlit octahedron per light that is on, in its colour, drawn as
// instance i of light i (render::scene_gpu::MarkerUniform).
// Prepended at build time: frame.wgsl.

struct Marker {
    centre: vec4<f32>, // world space, metres
    color: vec4<f32>,  // the light's colour, each channel at most 1
};

@group(1) @binding(0) var<uniform> markers: array<Marker, MAX_LIGHTS>;

struct MarkerOutput {
    @builtin(position) clip_position: vec4<f32>,
    @location(0) @interpolate(flat) light: u32,
};

@vertex
fn vs_marker(@location(0) position: vec3<f32>, @builtin(instance_index) light: u32) -> MarkerOutput {
    let world = markers[light].centre.xyz + position;
    return MarkerOutput(frame.view_proj * vec4<f32>(world, 1.0), light);
}

@fragment
fn fs_marker(in: MarkerOutput) -> @location(0) vec4<f32> {
    return vec4<f32>(markers[in.light].color.rgb, 1.0);
}
