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
    view_mode: u32,           // ViewMode::shader_index()
    self_shadow_fade: f32,    // SELF_SHADOW_FADE
    difference_range_deg: f32, // the Difference view's colour scale runs 0..this, degrees
    shading_override: u32,    // 0: each material's own model, else 1 + ShadingModel::shader_index()
    _pad1: f32,
    _pad2: f32,
};

@group(0) @binding(0) var<uniform> frame: Frame;

