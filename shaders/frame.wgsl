// Frame-wide uniforms shared by every pass (group 0). Rust side: FrameUniform in
// src/render/uniforms.rs. Prepended to each shader at build time.

struct Frame {
    view_proj: mat4x4<f32>,
    camera_pos: vec4<f32>,
    light_pos: vec4<f32>,
    light_color: vec4<f32>,   // linear RGB
    ambient: vec4<f32>,       // linear RGB
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
    parallax_shadow_strength: f32, // ParallaxSettings::shadow_strength (0: no self-shadows)
};

@group(0) @binding(0) var<uniform> frame: Frame;

