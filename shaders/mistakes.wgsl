// The classic mistakes (frame::Mistake), each the twin of its step in src/chain/mistakes.rs.
// MISTAKE is Mistake::shader_index(), a pipeline constant: 0 (none) compiles every step to
// the correct one of the mesh shader.

override MISTAKE: u32 = 0u;

const MISTAKE_TBN_TYPO: u32 = 1u;
const MISTAKE_HANDEDNESS_IGNORED: u32 = 2u;
const MISTAKE_SRGB_NORMAL_MAP: u32 = 3u;
const MISTAKE_NO_RENORMALIZATION: u32 = 4u;
const MISTAKE_NO_GRAM_SCHMIDT: u32 = 5u;
const MISTAKE_GREEN_FLIPPED: u32 = 6u;
const MISTAKE_HALF_VECTOR_PER_VERTEX: u32 = 7u;
const MISTAKE_LIGHT_PER_VERTEX: u32 = 8u;

// mistakes::texel_read: through an sRGB view the colour channels arrive sRGB-decoded.
fn mistaken_texel(texel: NormalSample) -> NormalSample {
    if MISTAKE == MISTAKE_SRGB_NORMAL_MAP {
        return NormalSample(vec4<f32>(srgb_to_linear(texel.texel.rgb), texel.texel.a), texel.correction);
    }
    return texel;
}

// mistakes::convention_read: the other green convention.
fn mistaken_flags(flags: u32) -> u32 {
    if MISTAKE == MISTAKE_GREEN_FLIPPED {
        return flags ^ FLIP_GREEN;
    }
    return flags;
}

// mistakes::tangent_frame
fn mistaken_frame(world_tangent: vec4<f32>, n: vec3<f32>) -> TangentFrame {
    if MISTAKE == MISTAKE_HANDEDNESS_IGNORED {
        let t = orthonormalize_tangent(world_tangent.xyz, n);
        return TangentFrame(t, cross(n, t), 1.0);
    }
    if MISTAKE == MISTAKE_NO_GRAM_SCHMIDT {
        let t = normalize_or(world_tangent.xyz, any_perpendicular(n));
        let w = select(1.0, -1.0, world_tangent.w < 0.0);
        return TangentFrame(t, w * cross(n, t), w);
    }
    return tangent_frame(world_tangent, n);
}

// mistakes::base_normal: the interpolated normal as it comes, else the unit one.
fn base_normal(world_normal: vec3<f32>, front_facing: bool, n: vec3<f32>) -> vec3<f32> {
    if MISTAKE == MISTAKE_NO_RENORMALIZATION {
        return select(-world_normal, world_normal, front_facing);
    }
    return n;
}

// mistakes::to_world: the tangent-space normal through T, B and the base normal.
fn tangent_to_world(frame_tb: TangentFrame, base: vec3<f32>, nt: vec3<f32>) -> vec3<f32> {
    let sum = frame_tb.t * nt.x + frame_tb.b * nt.y + base * nt.z;
    if MISTAKE == MISTAKE_TBN_TYPO {
        let y = frame_tb.t.y * nt.x + frame_tb.b.y * nt.y + base.z * nt.z;
        return normalize_or(vec3<f32>(sum.x, y, sum.z), base);
    }
    if MISTAKE == MISTAKE_NO_RENORMALIZATION {
        return sum;
    }
    return normalize_or(sum, base);
}

// The vertex stage's per-vertex light direction and half vector as interpolated, set by the
// per-vertex interface's fragment_inputs (mesh_varyings_per_vertex.wgsl) before anything is lit;
// the hooks below and the legacy looks read them.
struct PerVertexVectors {
    light: vec3<f32>,
    half: vec3<f32>,
};
var<private> per_vertex: PerVertexVectors;

// mistakes::seen_light_direction: the direction towards light `i` (of the lights that are on)
// the lighting uses; the first light's is the interpolated per-vertex one, re-normalised,
// under light-per-vertex.
fn seen_light_direction(i: u32, l: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    if MISTAKE == MISTAKE_LIGHT_PER_VERTEX && i == 0u {
        return normalize_or(per_vertex.light, n);
    }
    return l;
}

// mistakes::seen_view_direction: the direction towards the eye light `i`'s highlight uses;
// the first light's is l mirrored about the interpolated per-vertex half vector under
// half-vector-per-vertex, so that normalize(l + v) is that half vector.
fn seen_view_direction(i: u32, l: vec3<f32>, v: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    if MISTAKE == MISTAKE_HALF_VECTOR_PER_VERTEX && i == 0u {
        let h = normalize_or(per_vertex.half, n);
        return h * (2.0 * dot(h, l)) - l;
    }
    return v;
}
