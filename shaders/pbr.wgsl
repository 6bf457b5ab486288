// glTF 2.0 metallic-roughness (spec appendix B) with every light and a procedural sky.
// CPU twin: src/shading/pbr.rs (constants and functions line for line; keep them in step).
// Part of the mesh pass (render::shaders::MESH).

const PI: f32 = 3.14159265;
const SKY_ZENITH: vec3<f32> = vec3<f32>(0.12, 0.22, 0.45);
const SKY_HORIZON: vec3<f32> = vec3<f32>(0.55, 0.60, 0.65);
const GROUND: vec3<f32> = vec3<f32>(0.06, 0.05, 0.04);
const SKY_MEAN: vec3<f32> = SKY_HORIZON + 0.8 * (SKY_ZENITH - SKY_HORIZON);
const MIN_ROUGHNESS: f32 = 0.045;

// pbr::sky: sharp edge at the horizon y = 0.
fn sky(dir: vec3<f32>) -> vec3<f32> {
    if dir.y >= 0.0 {
        return mix(SKY_HORIZON, SKY_ZENITH, sqrt(dir.y));
    }
    return GROUND;
}

// pbr::sky_average
fn sky_average(n: vec3<f32>) -> vec3<f32> {
    return mix(GROUND, SKY_MEAN, 0.5 + 0.5 * clamp(n.y, -1.0, 1.0));
}

// pbr::reflected_sky
fn reflected_sky(r: vec3<f32>, roughness: f32) -> vec3<f32> {
    return mix(sky(r), sky_average(r), roughness);
}

// pbr::environment_brdf (Karis 2014)
fn environment_brdf(n_dot_v: f32, roughness: f32) -> vec2<f32> {
    let r = roughness * vec4<f32>(-1.0, -0.0275, -0.572, 0.022) + vec4<f32>(1.0, 0.0425, 1.04, -0.04);
    let a004 = min(r.x * r.x, exp2(-9.28 * n_dot_v)) * r.x + r.y;
    return vec2<f32>(-1.04, 1.04) * a004 + r.zw;
}

fn ggx_distribution(n_dot_h: f32, alpha: f32) -> f32 {
    let a2 = alpha * alpha;
    let d = n_dot_h * n_dot_h * (a2 - 1.0) + 1.0;
    return a2 / (PI * d * d);
}

fn smith_visibility(n_dot_l: f32, n_dot_v: f32, alpha: f32) -> f32 {
    let a2 = alpha * alpha;
    let gv = n_dot_l * sqrt(n_dot_v * n_dot_v * (1.0 - a2) + a2);
    let gl = n_dot_v * sqrt(n_dot_l * n_dot_l * (1.0 - a2) + a2);
    let sum = gv + gl;
    return select(0.0, 0.5 / sum, sum > 0.0);
}

fn fresnel_schlick(f0: vec3<f32>, v_dot_h: f32) -> vec3<f32> {
    return f0 + (vec3<f32>(1.0) - f0) * pow(1.0 - clamp(v_dot_h, 0.0, 1.0), 5.0);
}

struct PbrInputs {
    base_color: vec3<f32>,
    metallic: f32,
    roughness: f32,
    occlusion: f32,
    n_geo: vec3<f32>,
    n: vec3<f32>,
    position: vec3<f32>,
    has_clearcoat: bool,
    clearcoat: f32,           // factor × texture red
    clearcoat_roughness: f32, // factor × texture green
    n_coat: vec3<f32>,
};

const CLEARCOAT_F0: f32 = 0.04;

// pbr::pbr_light: one light's base and clear-coat highlights; `i` counts the lights that are
// on, for the per-vertex mistakes' hooks (mistakes.wgsl).
struct PbrLight {
    base: vec3<f32>,
    coat: vec3<f32>,
};

fn pbr_light(p: PbrInputs, i: u32, light: Light) -> PbrLight {
    let arriving = incident_light(light, p.position, p.n_geo);
    let l = seen_light_direction(i, arriving.direction, p.n_geo);
    let v = seen_view_direction(i, l, normalize_or(frame.camera_pos.xyz - p.position, p.n_geo), p.n_geo);
    let h = normalize_or(l + v, p.n_geo);
    let roughness = clamp(p.roughness, MIN_ROUGHNESS, 1.0);
    let alpha = roughness * roughness;
    let metallic = clamp(p.metallic, 0.0, 1.0);
    let c_diff = mix(p.base_color, vec3<f32>(0.0), metallic);
    let f0 = mix(vec3<f32>(0.04), p.base_color, metallic);
    let n_dot_l = max(dot(p.n, l), 0.0);
    let n_dot_v = max(dot(p.n, v), 1e-4);
    let n_dot_h = max(dot(p.n, h), 0.0);
    let fresnel = fresnel_schlick(f0, dot(v, h));
    let specular = fresnel * ggx_distribution(n_dot_h, alpha) * smith_visibility(n_dot_l, n_dot_v, alpha);
    let diffuse = (vec3<f32>(1.0) - fresnel) * c_diff / PI;
    let self_shadow = smoothstep(0.0, frame.self_shadow_fade, dot(p.n_geo, l)) * parallax_light_visibility(arriving.direction);
    let direct = PI * (diffuse + specular) * arriving.radiance * n_dot_l * self_shadow;
    if !p.has_clearcoat {
        return PbrLight(direct, vec3<f32>(0.0));
    }
    let nc = p.n_coat;
    let coat_roughness = clamp(p.clearcoat_roughness, MIN_ROUGHNESS, 1.0);
    let coat_alpha = coat_roughness * coat_roughness;
    let nc_dot_l = max(dot(nc, l), 0.0);
    let nc_dot_v = max(dot(nc, v), 1e-4);
    let highlight = fresnel_schlick(vec3<f32>(CLEARCOAT_F0), dot(v, h))
        * ggx_distribution(max(dot(nc, h), 0.0), coat_alpha)
        * smith_visibility(nc_dot_l, nc_dot_v, coat_alpha);
    return PbrLight(direct, PI * highlight * arriving.radiance * nc_dot_l * self_shadow);
}

// pbr::metallic_roughness; normalize_or comes from common.wgsl, incident_light from
// lights.wgsl.
fn metallic_roughness(p: PbrInputs) -> vec3<f32> {
    var direct = vec3<f32>(0.0);
    var coat_direct = vec3<f32>(0.0);
    for (var i = 0u; i < min(frame.light_count, MAX_LIGHTS); i++) {
        let terms = pbr_light(p, i, frame.lights[i]);
        direct += terms.base;
        coat_direct += terms.coat;
    }
    let v = normalize_or(frame.camera_pos.xyz - p.position, p.n_geo);
    let roughness = clamp(p.roughness, MIN_ROUGHNESS, 1.0);
    let metallic = clamp(p.metallic, 0.0, 1.0);
    let c_diff = mix(p.base_color, vec3<f32>(0.0), metallic);
    let f0 = mix(vec3<f32>(0.04), p.base_color, metallic);
    let n_dot_v = max(dot(p.n, v), 1e-4);
    let r = normalize_or(2.0 * dot(p.n, v) * p.n - v, p.n);
    let ab = environment_brdf(n_dot_v, roughness);
    let ambient = c_diff * sky_average(p.n) + reflected_sky(r, roughness) * (f0 * ab.x + ab.y);
    let occlusion = clamp(p.occlusion, 0.0, 1.0);
    let base = direct + occlusion * ambient;
    if !p.has_clearcoat {
        return base;
    }
    // pbr::metallic_roughness's clear coat: its own highlights and sky reflection, over the
    // base dimmed by what the layer reflects towards the eye.
    let nc = p.n_coat;
    let coat_roughness = clamp(p.clearcoat_roughness, MIN_ROUGHNESS, 1.0);
    let nc_dot_v = max(dot(nc, v), 1e-4);
    let f0_coat = vec3<f32>(CLEARCOAT_F0);
    let rc = normalize_or(2.0 * dot(nc, v) * nc - v, nc);
    let coat_ab = environment_brdf(nc_dot_v, coat_roughness);
    let coat_sky = reflected_sky(rc, coat_roughness) * (CLEARCOAT_F0 * coat_ab.x + coat_ab.y);
    let through = fresnel_schlick(f0_coat, nc_dot_v);
    return base * (vec3<f32>(1.0) - p.clearcoat * through) + p.clearcoat * (coat_direct + occlusion * coat_sky);
}
