// The Difference view's pass: a mesh's tangent frames against reference frames (a second
// tangent stream at location 4), coloured by the larger of the angles between their T and B.
// shading::difference_color is the CPU twin of the colour scale. Prepended at build time:
// frame.wgsl, object.wgsl, common.wgsl (render::shaders::DIFFERENCE).

struct DifferenceOutput {
    @builtin(position) clip_position: vec4<f32>,
    @location(1) world_normal: vec3<f32>,
    @location(3) world_tangent: vec4<f32>,
    @location(4) world_reference: vec4<f32>,
};

@vertex
fn vs_difference(
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    @location(3) tangent: vec4<f32>,
    @location(4) reference: vec4<f32>,
) -> DifferenceOutput {
    let frame_out = to_world(position, normal, uv, tangent);
    let reference_out = to_world(position, normal, uv, reference);
    return DifferenceOutput(frame_out.clip_position, frame_out.world_normal, frame_out.world_tangent, reference_out.world_tangent);
}

fn angle_deg(a: vec3<f32>, b: vec3<f32>) -> f32 {
    return degrees(acos(clamp(dot(a, b), -1.0, 1.0)));
}

// Viridis-like ramp through five stops, t in 0..1 (display values).
fn difference_color(t: f32) -> vec3<f32> {
    let stops = array<vec3<f32>, 5>(
        vec3<f32>(0.267, 0.005, 0.329),
        vec3<f32>(0.229, 0.322, 0.546),
        vec3<f32>(0.128, 0.567, 0.551),
        vec3<f32>(0.369, 0.789, 0.383),
        vec3<f32>(0.993, 0.906, 0.144),
    );
    let x = clamp(t, 0.0, 1.0) * 4.0;
    let i = min(u32(floor(x)), 3u);
    return mix(stops[i], stops[i + 1u], x - f32(i));
}

// The larger of the angles between the two frames' T and B, on a 0..difference_range scale.
@fragment
fn fs_difference(in: DifferenceOutput, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    let n = geometric_normal(in.world_normal, front_facing);
    let frame_tb = tangent_frame(in.world_tangent, n);
    let reference_tb = tangent_frame(in.world_reference, n);
    let angle = max(angle_deg(frame_tb.t, reference_tb.t), angle_deg(frame_tb.b, reference_tb.b));
    return stored(difference_color(angle / max(frame.difference_range_deg, 1e-6)));
}
