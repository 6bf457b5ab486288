// Detail normal blending: the base and the detail tangent-space normals (each after its
// strength) made into one, by the DETAIL_BLEND pipeline constant. The CPU twins are
// src/shading/detail_blend.rs, run by chain::shade (src/chain/detail.rs). Part of the mesh
// pass (render::shaders::MESH); the detail map is sampled only where MATERIAL_FEATURES has
// HAS_DETAIL.

// The method: DetailBlend::shader_index() (src/scene/detail.rs).
override DETAIL_BLEND: u32 = 4u;
const DETAIL_LINEAR: u32 = 0u;
const DETAIL_PARTIAL_DERIVATIVE: u32 = 1u;
const DETAIL_WHITEOUT: u32 = 2u;
const DETAIL_UDN: u32 = 3u;
const DETAIL_RNM: u32 = 4u;
const DETAIL_SURFACE_GRADIENT: u32 = 5u;

const MIN_GRADIENT_Z: f32 = 1e-3; // detail_blend::MIN_GRADIENT_Z

// detail_blend::linear
fn detail_linear(b: vec3<f32>, d: vec3<f32>) -> vec3<f32> {
    return normalize_or(b + d, b);
}

// detail_blend::partial_derivative
fn detail_partial_derivative(b: vec3<f32>, d: vec3<f32>) -> vec3<f32> {
    return normalize_or(vec3<f32>(b.xy * d.z + d.xy * b.z, b.z * d.z), b);
}

// detail_blend::whiteout
fn detail_whiteout(b: vec3<f32>, d: vec3<f32>) -> vec3<f32> {
    return normalize_or(vec3<f32>(b.xy + d.xy, b.z * d.z), b);
}

// detail_blend::udn
fn detail_udn(b: vec3<f32>, d: vec3<f32>) -> vec3<f32> {
    return normalize_or(vec3<f32>(b.xy + d.xy, b.z), b);
}

// detail_blend::rnm
fn detail_rnm(b: vec3<f32>, d: vec3<f32>) -> vec3<f32> {
    let t = b + vec3<f32>(0.0, 0.0, 1.0);
    let u = vec3<f32>(-d.xy, d.z);
    return normalize_or(t * (dot(t, u) / t.z) - u, b);
}

// detail_blend::gradient_of_normal
fn gradient_of_normal(n: vec3<f32>, v: vec3<f32>) -> vec3<f32> {
    let k = max(dot(n, v), MIN_GRADIENT_Z);
    return (k * n - v) / k;
}

// detail_blend::surface_gradient (with resolve_gradient)
fn detail_surface_gradient(b: vec3<f32>, d: vec3<f32>) -> vec3<f32> {
    let n = vec3<f32>(0.0, 0.0, 1.0);
    let gradient = gradient_of_normal(n, b) + gradient_of_normal(n, d);
    return normalize_or(n - gradient, n);
}

// detail_blend::blend
fn blend_detail(b: vec3<f32>, d: vec3<f32>) -> vec3<f32> {
    switch DETAIL_BLEND {
        case DETAIL_LINEAR: { return detail_linear(b, d); }
        case DETAIL_PARTIAL_DERIVATIVE: { return detail_partial_derivative(b, d); }
        case DETAIL_WHITEOUT: { return detail_whiteout(b, d); }
        case DETAIL_UDN: { return detail_udn(b, d); }
        case DETAIL_SURFACE_GRADIENT: { return detail_surface_gradient(b, d); }
        default: { return detail_rnm(b, d); }
    }
}

// chain::detail::values: the base tangent-space normal `nt` (after its strength) with the
// detail map blended in where the material has one, read at `uv` times its tiling, decoded
// (OpenGL convention, RGB) and scaled by its strength as shading::tangent_space_normal does.
fn detailed_normal(nt: vec3<f32>, uv: vec2<f32>) -> vec3<f32> {
    if !has(HAS_DETAIL) {
        return nt;
    }
    let texel = textureSample(detail_normal_texture, detail_sampler, uv * object.detail.x);
    let up = vec3<f32>(0.0, 0.0, 1.0);
    let decoded = normalize_or(texel.rgb * 2.0 - 1.0, up);
    let d = normalize_or(vec3<f32>(decoded.xy * object.detail.y, max(decoded.z, 0.0)), up);
    return blend_detail(nt, d);
}
