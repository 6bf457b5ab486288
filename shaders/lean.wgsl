// LEAN mapping (Olano & Baker, I3D 2010) in the mesh pass: LEAN's texture of the normal map's
// slope moments (Bx, By, Bx², By²) in half floats (texture::LeanTexels), group 2, bound only in
// LEAN's pipelines (render::shaders::MESH_LEAN; the other mesh modules take lean_unbound.wgsl).
// CPU twins: shading::mip_filter::{lean_normal, lean_variance} and chain::mip::lean_texel.

@group(2) @binding(0) var lean_moments: texture_2d<f32>;

const LEAN_HALF_FLOOR: f32 = 0.001953125; // mip_filter::LEAN_HALF_FLOOR, 2⁻⁹

// mip_filter::lean_variance: the trace of Σ = M − B·Bᵀ, each term less the half floats'
// rounding and at least 0.
fn lean_variance(moments: vec4<f32>) -> f32 {
    let sxx = max(moments.z - moments.x * moments.x - LEAN_HALF_FLOOR * moments.z, 0.0);
    let syy = max(moments.w - moments.y * moments.y - LEAN_HALF_FLOOR * moments.w, 0.0);
    return sxx + syy;
}

// mip_filter::lean_fade: clamp(lod, 0, 1), lod from the fine derivatives of `uv` in level-0
// texels as chain::mip::normal_map_lod takes it (none under magnification).
fn lean_fade(uv: vec2<f32>) -> f32 {
    let size = vec2<f32>(textureDimensions(lean_moments));
    let longer = max(length(dpdxFine(uv) * size), length(dpdyFine(uv) * size));
    return clamp(log2(longer), 0.0, 1.0);
}

// mip_filter::lean_normal: the mean slope's normal, normalize(Bx, By, 1), tangent space.
fn lean_normal(moments: vec4<f32>) -> vec3<f32> {
    return normalize_or(vec3<f32>(moments.xy, 1.0), vec3<f32>(0.0, 0.0, 1.0));
}

// chain::mip::lean_texel: the normal map's texel with its RGB faded (lean_fade) to the
// mean-slope normal's (n·½ + ½, so the convention and the strength apply as to any texel), and
// LEAN's variance times strength² and the fade added to α² (mip_variance) with the bump on.
fn lean_texel(sample: NormalSample, uv: vec2<f32>, strength: f32) -> NormalSample {
    let moments = textureSample(lean_moments, detail_sampler, uv);
    let fade = lean_fade(uv);
    if frame.bump_enabled != 0u {
        mip_variance = strength * strength * fade * lean_variance(moments);
    }
    var texel = sample;
    texel.texel = vec4<f32>(mix(sample.texel.rgb, lean_normal(moments) * 0.5 + 0.5, fade), sample.texel.a);
    return texel;
}
