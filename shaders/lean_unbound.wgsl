// LEAN's read in the mesh modules without its texture (all but render::shaders::MESH_LEAN,
// whose lean.wgsl reads it): the normal map's texel as sampled.
fn lean_texel(sample: NormalSample, uv: vec2<f32>, strength: f32) -> NormalSample {
    return sample;
}
