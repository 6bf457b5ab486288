// Normal-map mip filtering: how much the filtered normal map widens the highlight,
// as a variance added to α², and the classic exponent and the perceptual roughness widened by
// it. The CPU twins are src/shading/mip_filter.rs, run by chain::shade. Part of the mesh pass
// (render::shaders::MESH); uses frame.wgsl's Frame uniform.

// The method: MipFilter::shader_index() (src/texture/mip_filter.rs). The default, 1, is the
// re-normalised box mips (no widening); base-only shares it (its normal map has no mips).
override MIP_FILTER: u32 = 1u;
const MIP_TOKSVIG: u32 = 2u;
const MIP_VMF: u32 = 4u;
const MIP_GEOMETRIC_SPECULAR_AA: u32 = 5u;

const GSAA_VARIANCE: f32 = 0.15;     // mip_filter::GSAA_VARIANCE
const GSAA_THRESHOLD: f32 = 0.2;     // mip_filter::GSAA_THRESHOLD
const MIN_NORMAL_LENGTH: f32 = 1e-3; // mip_filter::MIN_NORMAL_LENGTH

// What the normal map adds to α² at this fragment (mip_filter::alpha_variance): set by the
// normal-mapped entry points before they shade, 0 elsewhere.
var<private> mip_variance: f32 = 0.0;

// mip_filter::clamped_length
fn clamped_length(length: f32) -> f32 {
    return clamp(length, MIN_NORMAL_LENGTH, 1.0);
}

// mip_filter::toksvig_variance: σ² = (1 − |Na|) / |Na|.
fn toksvig_variance(length: f32) -> f32 {
    let r = clamped_length(length);
    return (1.0 - r) / r;
}

// mip_filter::vmf_variance: 2/κ = 2(1 − r²) / (3r − r³).
fn vmf_variance(length: f32) -> f32 {
    let r = clamped_length(length);
    return 2.0 * (1.0 - r * r) / (3.0 * r - r * r * r);
}

// mip_filter::gsaa_variance: min(2·σ²·(|∂n/∂x|² + |∂n/∂y|²), κ).
fn gsaa_variance(dn_dx: vec3<f32>, dn_dy: vec3<f32>) -> f32 {
    let variance = GSAA_VARIANCE * (dot(dn_dx, dn_dx) + dot(dn_dy, dn_dy));
    return min(2.0 * variance, GSAA_THRESHOLD);
}

// mip_filter::alpha_variance for the methods that read the map: |Na| is the texel's alpha
// (the mip chain stores it), times strength².
fn set_mip_variance_from_texel(texel: vec4<f32>, strength: f32) {
    if frame.bump_enabled == 0u {
        return;
    }
    let s2 = strength * strength;
    if MIP_FILTER == MIP_TOKSVIG {
        mip_variance = s2 * 2.0 * toksvig_variance(texel.a);
    } else if MIP_FILTER == MIP_VMF {
        mip_variance = s2 * vmf_variance(texel.a);
    }
}

// mip_filter::alpha_variance for geometric specular AA: from the fine screen-space
// derivatives of the unit shading normal (world space).
fn set_mip_variance_from_normal(n: vec3<f32>) {
    if MIP_FILTER == MIP_GEOMETRIC_SPECULAR_AA {
        let dn_dx = dpdxFine(n);
        let dn_dy = dpdyFine(n);
        if frame.bump_enabled != 0u {
            mip_variance = gsaa_variance(dn_dx, dn_dy);
        }
    }
}

// mip_filter::widened_shininess: (s′, the energy factor (1 + s′)/(1 + s) on k_s).
fn mip_widened_shininess(shininess: f32) -> vec2<f32> {
    if !(mip_variance > 0.0) {
        return vec2<f32>(shininess, 1.0);
    }
    let s = max(shininess, 0.0);
    var widened = 2.0 / min(2.0 / (s + 2.0) + mip_variance, 1.0) - 2.0;
    if MIP_FILTER == MIP_TOKSVIG {
        widened = s / (1.0 + s * 0.5 * mip_variance);
    }
    widened = max(widened, 0.0);
    return vec2<f32>(widened, (1.0 + widened) / (1.0 + s));
}

// mip_filter::widened_roughness: r′ = (min(r⁴ + variance, 1))^¼.
fn mip_widened_roughness(roughness: f32) -> f32 {
    if !(mip_variance > 0.0) {
        return roughness;
    }
    let alpha = roughness * roughness;
    return sqrt(sqrt(min(alpha * alpha + mip_variance, 1.0)));
}
