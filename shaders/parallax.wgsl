// The parallax family (frame::Parallax): texture coordinates shifted along the view ray by
// the material's height map before the normal map and the colour are read. The CPU twin is
// src/chain/parallax.rs, formula for formula; its doc comment states the geometry (reference
// plane at the top of the relief, UV density from screen-space derivatives) and the bounds.
// Part of the mesh pass (render::shaders::MESH); normal_mapped_surface calls parallax_uv, the lighting
// multiplies each light by parallax_light_visibility (the searches' soft self-shadows).

@group(1) @binding(12) var height_texture: texture_2d<f32>; // linear: 16-bit height in R (high), G (low),
// and for relaxed cones the cone ratio in B at level 0 (height::cone::encode_cone_ratio)

// The technique the pipeline draws: Parallax::shader_index(), one of the PARALLAX_ constants
// below (0 is off). A pipeline constant, so a pipeline compiles only its own march.
override PARALLAX: u32 = 0u;
// Whether the searches cast soft self-shadows (ParallaxSettings::shadows_on): off, the pipeline
// compiles no shadow code (lavapipe would run it for every pixel, strength 0 or not).
override PARALLAX_SHADOWS: bool = true;

const PARALLAX_OFFSET: u32 = 1u;
const PARALLAX_OFFSET_LIMITED: u32 = 2u;
const PARALLAX_STEEP: u32 = 3u;
const PARALLAX_OCCLUSION: u32 = 4u;
const PARALLAX_RELIEF: u32 = 5u;
const PARALLAX_RELAXED_CONE: u32 = 6u;
const MAX_CONE_RATIO: f32 = 0.25; // height::cone::MAX_CONE_RATIO
const SMALLEST_NORMAL_F32: f32 = 1.17549435e-38; // f32::MIN_POSITIVE
const MAX_PARALLAX_LAYERS: u32 = 256u;
const MAX_PARALLAX_STEPS: u32 = 16u;
const GRAZING_N_DOT_V: f32 = 0.05;

// Bits of Object.flags (src/render/uniforms.rs).
const HAS_PARALLAX_HEIGHT: u32 = 2048u;
const PARALLAX_CLAMP_U: u32 = 4096u;
const PARALLAX_CLAMP_V: u32 = 8192u;

struct ParallaxRay {
    uv: vec2<f32>,
    per_depth: vec2<f32>, // UV shift at the full depth
    duv_dx: vec2<f32>,
    duv_dy: vec2<f32>,
};

// Where the search hit, kept for the self-shadows of the lighting (chain::parallax::soft_shadow).
struct ParallaxHit {
    ray: ParallaxRay,
    uv: vec2<f32>,   // the UV there
    grad_u: vec3<f32>,
    grad_v: vec3<f32>,
    n: vec3<f32>,
    depth_m: f32,
    marched: u32,    // 1 once a search has run at this pixel
};

var<private> parallax_hit: ParallaxHit;

const SHADOW_SHARPNESS: f32 = 8.0;

fn parallax_clamp(uv: vec2<f32>) -> vec2<f32> {
    var out = uv;
    if (object.flags & PARALLAX_CLAMP_U) != 0u {
        out.x = clamp(out.x, 0.0, 1.0);
    }
    if (object.flags & PARALLAX_CLAMP_V) != 0u {
        out.y = clamp(out.y, 0.0, 1.0);
    }
    return out;
}

fn parallax_uv_at(ray: ParallaxRay, t: f32) -> vec2<f32> {
    return parallax_clamp(ray.uv + ray.per_depth * t);
}

// 1 − height of a height-map texel (a depth map's sample as it is).
fn parallax_depth_of_texel(texel: vec4<f32>) -> f32 {
    let sample = height_sample(texel);
    if (object.flags & DEPTH_MAP) != 0u {
        return sample;
    }
    return 1.0 - sample;
}

// 1 − height at `uv`, sampled with the pixel's UV footprint `duv_dx`, `duv_dy`.
fn parallax_depth_of(uv: vec2<f32>, duv_dx: vec2<f32>, duv_dy: vec2<f32>) -> f32 {
    return parallax_depth_of_texel(textureSampleGrad(height_texture, detail_sampler, uv, duv_dx, duv_dy));
}

// 1 − height at depth fraction t along the ray.
fn parallax_depth_at(ray: ParallaxRay, t: f32) -> f32 {
    return parallax_depth_of(parallax_uv_at(ray, t), ray.duv_dx, ray.duv_dy);
}

// ParallaxSettings::layers: floor(max + (min − max)·cos + 0.5), both clamped to 1..=256.
fn parallax_layers(cos_angle: f32) -> u32 {
    let low = clamp(min(frame.parallax_layers_min, frame.parallax_layers_max), 1u, MAX_PARALLAX_LAYERS);
    let high = clamp(max(frame.parallax_layers_min, frame.parallax_layers_max), 1u, MAX_PARALLAX_LAYERS);
    return u32(floor(f32(high) + (f32(low) - f32(high)) * clamp(cos_angle, 0.0, 1.0) + 0.5));
}

// chain::parallax::march. Derivatives are taken before any branch (uniform control flow).
fn parallax_uv(uv: vec2<f32>, n: vec3<f32>, position: vec3<f32>) -> vec2<f32> {
    let dp_dx = dpdx(position);
    let dp_dy = dpdy(position);
    let duv_dx = dpdx(uv);
    let duv_dy = dpdy(uv);
    var depth_m = object.height_range_m;
    if frame.parallax_depth_m >= 0.0 {
        depth_m = frame.parallax_depth_m;
    }
    let r1 = cross(dp_dy, n);
    let r2 = cross(n, dp_dx);
    let det = dot(dp_dx, r1);
    if PARALLAX == 0u || (object.flags & HAS_PARALLAX_HEIGHT) == 0u || depth_m == 0.0 || abs(det) < 1e-20 {
        return uv;
    }
    let grad_u = (r1 * duv_dx.x + r2 * duv_dy.x) / det;
    let grad_v = (r1 * duv_dx.y + r2 * duv_dy.y) / det;
    let v = normalize_or(frame.camera_pos.xyz - position, n);
    let n_dot_v = dot(n, v);
    let along = vec2<f32>(-dot(grad_u, v), -dot(grad_v, v)) * depth_m;
    let ray = ParallaxRay(uv, along / max(n_dot_v, GRAZING_N_DOT_V), duv_dx, duv_dy);
    if PARALLAX == PARALLAX_OFFSET {
        return parallax_uv_at(ray, parallax_depth_at(ray, 0.0));
    }
    if PARALLAX == PARALLAX_OFFSET_LIMITED {
        return parallax_clamp(uv + along * parallax_depth_at(ray, 0.0));
    }
    let layers = parallax_layers(n_dot_v);
    if PARALLAX == PARALLAX_RELAXED_CONE {
        let cone_hit_uv = parallax_uv_at(ray, parallax_relaxed_cone(ray, layers));
        parallax_hit = ParallaxHit(ray, cone_hit_uv, grad_u, grad_v, n, depth_m, 1u);
        return cone_hit_uv;
    }
    var i = 0u;
    var t = 0.0;
    var d = parallax_depth_at(ray, 0.0);
    var t_prev = t;
    var d_prev = d;
    while i < layers && t < d {
        t_prev = t;
        d_prev = d;
        i += 1u;
        t = f32(i) / f32(layers);
        d = parallax_depth_at(ray, t);
    }
    var t_hit = t;
    if PARALLAX == PARALLAX_OCCLUSION && i > 0u {
        let after = d - t;
        let before = d_prev - t_prev;
        let w = after / (after - before);
        t_hit = t_prev * w + t * (1.0 - w);
    }
    if PARALLAX == PARALLAX_RELIEF && i > 0u {
        var low_t = t_prev;
        var high_t = t;
        for (var k = 0u; k < min(frame.parallax_steps, MAX_PARALLAX_STEPS); k += 1u) {
            let mid = 0.5 * (low_t + high_t);
            if mid >= parallax_depth_at(ray, mid) {
                high_t = mid;
            } else {
                low_t = mid;
            }
        }
        t_hit = high_t;
    }
    let hit_uv = parallax_uv_at(ray, t_hit);
    parallax_hit = ParallaxHit(ray, hit_uv, grad_u, grad_v, n, depth_m, 1u);
    return hit_uv;
}

// What relaxed cone stepping reads at depth fraction t along the ray (chain::read::relief_cone):
// level 0, filtered; x = 1 − height, y = the cone ratio (height::cone::decode_cone_ratio).
fn parallax_cone_at(ray: ParallaxRay, t: f32) -> vec2<f32> {
    let texel = textureSampleLevel(height_texture, detail_sampler, parallax_uv_at(ray, t), 0.0);
    return vec2<f32>(parallax_depth_of_texel(texel), MAX_CONE_RATIO * texel.b * texel.b);
}

// chain::parallax's relaxed cone steps then binary search: the depth fraction the ray stops at.
fn parallax_relaxed_cone(ray: ParallaxRay, layers: u32) -> f32 {
    let ray_ratio = length(ray.per_depth);
    var i = 0u;
    var t = 0.0;
    var t_prev = 0.0;
    var texel = parallax_cone_at(ray, 0.0);
    while i < layers && t < texel.x {
        let below = texel.x - t;
        t_prev = t;
        t += texel.y * below / max(ray_ratio + texel.y, SMALLEST_NORMAL_F32);
        i += 1u;
        texel = parallax_cone_at(ray, t);
    }
    if i == 0u {
        return t;
    }
    var low_t = t_prev;
    var high_t = t;
    for (var k = 0u; k < min(frame.parallax_steps, MAX_PARALLAX_STEPS); k += 1u) {
        let mid = 0.5 * (low_t + high_t);
        if mid >= parallax_cone_at(ray, mid).x {
            high_t = mid;
        } else {
            low_t = mid;
        }
    }
    return high_t;
}

// chain::parallax::light_in_tangent_space and soft_shadow: the light towards unit direction
// `l` arrives times this at the pixel (1 without a search, shadows off, or a light below).
fn parallax_light_visibility(l: vec3<f32>) -> f32 {
    if !PARALLAX_SHADOWS || PARALLAX < PARALLAX_STEEP || parallax_hit.marched == 0u {
        return 1.0;
    }
    let hit = parallax_hit;
    return parallax_soft_shadow(vec3<f32>(dot(hit.grad_u, l), dot(hit.grad_v, l), dot(hit.n, l)));
}

// The soft self-shadow towards one light in tangent space (∇u·l, ∇v·l, N·l).
fn parallax_soft_shadow(light_ts: vec3<f32>) -> f32 {
    let hit = parallax_hit;
    if frame.parallax_shadow_strength <= 0.0 || light_ts.z <= 0.0 {
        return 1.0;
    }
    let start = parallax_depth_of(hit.uv, hit.ray.duv_dx, hit.ray.duv_dy);
    if start <= 0.0 {
        return 1.0;
    }
    let per_depth = light_ts.xy * hit.depth_m / max(light_ts.z, GRAZING_N_DOT_V);
    let samples = parallax_layers(light_ts.z);
    var blocked = 0.0;
    for (var i = 1u; i <= samples; i += 1u) {
        let f = f32(i) / f32(samples);
        let ray_depth = start * (1.0 - f);
        let surface_depth = parallax_depth_of(parallax_clamp(hit.uv + per_depth * (start * f)), hit.ray.duv_dx, hit.ray.duv_dy);
        blocked = max(blocked, (ray_depth - surface_depth) * (1.0 - f));
    }
    return 1.0 - clamp(frame.parallax_shadow_strength * SHADOW_SHARPNESS * blocked, 0.0, 1.0);
}
