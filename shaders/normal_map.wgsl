// The normal map (and the clear coat's) read, decoded and taken to world space: the CPU twins
// are src/shading.rs (unpack_normal, decode_normal, tangent_space_normal) and chain::shade.
// Part of the mesh pass (render::shaders::MESH).

// shading::unpack_normal's RG and AG layouts: z rebuilt from x and y (0..1 each).
fn rebuilt_z(x01: f32, y01: f32) -> vec3<f32> {
    let xy = vec2<f32>(x01, y01) * 2.0 - 1.0;
    let xy2 = dot(xy, xy);
    let shrink = select(1.0, inverseSqrt(xy2), xy2 > 1.0);
    return vec3<f32>(xy * shrink, sqrt(max(1.0 - xy2, 0.0)));
}

// shading::unpack_normal: the signed vector the texel's channels hold by the layout bits;
// `correction` is X-Ray's bump# RGB (0.5 without one).
fn unpack_normal(texel: vec4<f32>, correction: vec3<f32>, flags: u32) -> vec3<f32> {
    if (flags & LAYOUT_RG) != 0u {
        return rebuilt_z(texel.r, texel.g);
    }
    if (flags & LAYOUT_AG) != 0u {
        return rebuilt_z(texel.a, texel.g);
    }
    if (flags & LAYOUT_XRAY) != 0u {
        return texel.abg + correction - 1.0; // x = A, y = B, z = G (X-Ray's Nu.wzy)
    }
    return texel.rgb * 2.0 - 1.0;
}

// shading::decode_normal
fn decode_normal(texel: vec4<f32>, correction: vec3<f32>, flags: u32) -> vec3<f32> {
    var v = unpack_normal(texel, correction, flags);
    if (flags & FLIP_GREEN) != 0u {
        v.y = -v.y;
    }
    return normalize_or(v, vec3<f32>(0.0, 0.0, 1.0));
}

// shading::packed_gloss: X-Ray's bump red squared scales k_s (set by the normal-mapped entry
// points before they shade; 1 elsewhere).
var<private> packed_gloss: f32 = 1.0;

// The normal map's texel at `uv` with X-Ray's bump# correction where the material has one.
struct NormalSample {
    texel: vec4<f32>,
    correction: vec3<f32>,
};

fn sample_normal_map(uv: vec2<f32>) -> NormalSample {
    var correction = vec3<f32>(0.5);
    if has(HAS_BUMP_CORRECTION) {
        correction = textureSample(bump_correction_texture, detail_sampler, uv).rgb;
    }
    let texel = textureSample(bump_texture, detail_sampler, uv);
    if (object.flags & LAYOUT_XRAY) != 0u {
        packed_gloss = texel.r * texel.r;
    }
    return NormalSample(texel, correction);
}

// shading::tangent_space_normal: the decoded texel after strength, z ≥ 0, in tangent space.
fn tangent_space_normal(texel: NormalSample, strength: f32, flags: u32) -> vec3<f32> {
    let decoded = decode_normal(texel.texel, texel.correction, flags);
    let scaled = vec3<f32>(decoded.xy * strength, max(decoded.z, 0.0));
    return normalize_or(scaled, vec3<f32>(0.0, 0.0, 1.0));
}

// shading::tangent_space_normal, then shading::tangent_to_world (through mistakes.wgsl's
// tangent_to_world, which holds the classic mistakes beside it); `n` is the base
// normal, `flags` carries the map's convention bits.
fn perturbed_normal(n: vec3<f32>, frame_tb: TangentFrame, texel: NormalSample, strength: f32, flags: u32) -> vec3<f32> {
    let nt = tangent_space_normal(texel, strength, flags);
    return tangent_to_world(frame_tb, n, nt);
}

// The clear coat's texture coordinates (Object.clearcoat_uv).
fn clearcoat_uv(uv: vec2<f32>) -> vec2<f32> {
    let p = vec3<f32>(uv, 1.0);
    return vec2<f32>(dot(object.clearcoat_uv[0].xyz, p), dot(object.clearcoat_uv[1].xyz, p));
}

// chain::shade's clear-coat normal: the coat's normal map through the frame (OpenGL
// convention, bump strength times its scale), else the geometric normal.
fn clearcoat_normal(in: VertexOutput, n: vec3<f32>, frame_tb: TangentFrame) -> vec3<f32> {
    if !has(HAS_CLEARCOAT_NORMAL) || frame.bump_enabled == 0u {
        return n;
    }
    let texel = textureSample(clearcoat_normal_texture, detail_sampler, clearcoat_uv(in.uv));
    let coat = NormalSample(vec4<f32>(texel.rgb, 1.0), vec3<f32>(0.5));
    return perturbed_normal(n, frame_tb, coat, frame.strength * object.clearcoat.z, 0u);
}
