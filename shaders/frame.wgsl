// Frame-wide uniforms shared by every pass (group 0). Rust side: FrameUniform in
// src/render/uniforms.rs. Prepended to each shader at build time.

// One light that is on (LightUniform).
struct Light {
    position: vec4<f32>,      // xyz: point position (w = 1) or direction towards the light (w = 0)
    radiance: vec4<f32>,      // rgb: colour × intensity, linear
    attenuation: vec4<f32>,   // c, l, q of 1 / (c + l·d + q·d²)
};

const MAX_LIGHTS: u32 = 8u; // scene::MAX_LIGHTS

struct Frame {
    view_proj: mat4x4<f32>,
    camera_pos: vec4<f32>,
    lights: array<Light, MAX_LIGHTS>, // the lights that are on; the first light_count used
    ambient: vec4<f32>,       // linear RGB, colour × strength
    strength: f32,            // bump strength s, glTF normalTexture.scale semantics
    bump_enabled: u32,
    self_shadow_fade: f32,    // SELF_SHADOW_FADE
    difference_range_deg: f32, // the Difference view's colour scale runs 0..this, degrees
    shading_mode: u32,        // ShadingMode::shader_index(): bump × colour, bump only, colour only
    over_tilt_cos: f32,       // shading::over_tilt_cos(): the Over-tilt view marks N·N_geo below this
    parallax_layers_min: u32, // ParallaxSettings::layers_min, layers_max
    parallax_layers_max: u32,
    parallax_steps: u32,      // relief's binary-search steps
    parallax_depth_m: f32,    // the relief's depth, metres; negative: each material's height range
    light_count: u32,
    specular_mode: u32,       // SpecularMode::shader_index(): Blinn, Phong, off
    shininess: f32,           // for every material; negative: each material's own
    view_rotation: mat3x3<f32>, // world → view space (OrbitCamera::view_rotation)
};

@group(0) @binding(0) var<uniform> frame: Frame;

