// The lights (src/shading/lights.rs) and the classic model with its lighting spaces
// (src/shading.rs blinn_phong, src/shading/spaces.rs). Part of the mesh pass; uses
// common.wgsl's helpers (normalize_or) and object.wgsl's Object uniform.

// ---- lights (src/shading/lights.rs) ----

const MIN_ATTENUATION_DENOMINATOR: f32 = 1e-6; // lights::MIN_ATTENUATION_DENOMINATOR
const MAX_LIGHT_DISTANCE_M: f32 = 1e15;         // lights::MAX_LIGHT_DISTANCE_M
const SPECULAR_PHONG: u32 = 1u;                // SpecularMode::Phong
const SPECULAR_OFF: u32 = 2u;                  // SpecularMode::Off

// lights::attenuation: OpenGL's 1 / (c + l·d + q·d²).
fn attenuation(coefficients: vec3<f32>, distance_m: f32) -> f32 {
    let d = min(distance_m, MAX_LIGHT_DISTANCE_M);
    let c = coefficients;
    return 1.0 / max(c.x + c.y * d + c.z * d * d, MIN_ATTENUATION_DENOMINATOR);
}

// lights::Incident
struct Incident {
    direction: vec3<f32>,
    radiance: vec3<f32>,
};

// lights::incident: a point light (w = 1) attenuated by distance, a directional one (w = 0) not.
fn incident_light(light: Light, position: vec3<f32>, fallback: vec3<f32>) -> Incident {
    if light.position.w == 0.0 {
        return Incident(normalize_or(light.position.xyz, fallback), light.radiance.rgb);
    }
    let to_light = light.position.xyz - position;
    let factor = attenuation(light.attenuation.xyz, length(to_light));
    return Incident(normalize_or(to_light, fallback), light.radiance.rgb * factor);
}

// lights::specular_power: Blinn max(N·H, 0)^s, Phong max(R·V, 0)^s, or 0.
fn specular_power(n: vec3<f32>, n_geo: vec3<f32>, l: vec3<f32>, v: vec3<f32>, shininess: f32) -> f32 {
    var cosine = max(dot(n, normalize_or(l + v, n_geo)), 0.0);
    if frame.specular_mode == SPECULAR_PHONG {
        cosine = max(dot(2.0 * dot(n, l) * n - l, v), 0.0);
    } else if frame.specular_mode == SPECULAR_OFF {
        cosine = 0.0;
    }
    if dot(n, l) > 0.0 && cosine > 0.0 {
        return pow(cosine, shininess);
    }
    return 0.0;
}

// The material's shininess, or the frame's for every material, widened by the normal map's
// mip filter (mip_filter.wgsl; unchanged without one).
fn shininess() -> f32 {
    return mip_widened_shininess(select(object.specular.a, frame.shininess, frame.shininess >= 0.0)).x;
}

// The mip filter's energy factor on k_s for the widened exponent (1 without widening).
fn shininess_energy() -> f32 {
    return mip_widened_shininess(select(object.specular.a, frame.shininess, frame.shininess >= 0.0)).y;
}

// shading::light_term: one light's diffuse and specular with the self-shadow fade, from unit
// vectors of one lighting space.
fn light_term(albedo: vec3<f32>, k_s: vec3<f32>, n_geo: vec3<f32>, n: vec3<f32>, l: vec3<f32>, v: vec3<f32>, radiance: vec3<f32>) -> vec3<f32> {
    let self_shadow = smoothstep(0.0, frame.self_shadow_fade, dot(n_geo, l));
    let n_dot_l = max(dot(n, l), 0.0);
    let specular = specular_power(n, n_geo, l, v, shininess());
    return self_shadow * radiance * (albedo * n_dot_l + k_s * specular);
}

// ---- lighting spaces (src/shading/spaces.rs); LightingSpace::shader_index() ----

const LIGHTING_TANGENT: u32 = 1u;
const LIGHTING_VIEW: u32 = 2u;
// The space the classic model lights in: set for tangent-space normal-mapped surfaces in the
// lit views, else world space (0).
override LIGHTING_SPACE: u32 = 0u;

// Tangent-space lighting's inputs at this fragment (normal_mapped_surface sets them when LIGHTING_SPACE is tangent):
// the map's normal after strength, and the triangle's inverse frame (world → tangent space).
struct TangentSpaceInputs {
    normal: vec3<f32>,
    to_tangent: mat3x3<f32>,
};
var<private> tangent_space: TangentSpaceInputs;

// shading::blinn_phong with the vectors of the pipeline's lighting space
// (shading::world_vectors with the per-vertex mistakes' hooks of mistakes.wgsl, which act in
// world space, then spaces::tangent_lighting_vectors or spaces::view_lighting_vectors):
// the ambient light plus every light that is on, its radiance attenuated in world space.
// k_s: the material's specular colour, times its gloss map where it has one.
fn blinn_phong(albedo: vec3<f32>, k_s: vec3<f32>, n_geo: vec3<f32>, n_shading: vec3<f32>, position: vec3<f32>) -> vec3<f32> {
    var sum = albedo * frame.ambient.rgb;
    var g = n_geo;
    var n = n_shading;
    if LIGHTING_SPACE == LIGHTING_TANGENT {
        g = vec3<f32>(0.0, 0.0, 1.0);
        n = tangent_space.normal;
    } else if LIGHTING_SPACE == LIGHTING_VIEW {
        g = frame.view_rotation * n_geo;
        n = frame.view_rotation * n_shading;
    }
    let to_eye = normalize_or(frame.camera_pos.xyz - position, n_geo);
    for (var i = 0u; i < min(frame.light_count, MAX_LIGHTS); i++) {
        let arriving = incident_light(frame.lights[i], position, n_geo);
        var l = seen_light_direction(i, arriving.direction, n_geo);
        var v = seen_view_direction(i, l, to_eye, n_geo);
        if LIGHTING_SPACE == LIGHTING_TANGENT {
            l = normalize_or(tangent_space.to_tangent * l, g);
            v = normalize_or(tangent_space.to_tangent * v, g);
        } else if LIGHTING_SPACE == LIGHTING_VIEW {
            l = frame.view_rotation * l;
            v = frame.view_rotation * v;
        }
        // The parallax searches' soft self-shadow of this light (1 without one).
        let visibility = parallax_light_visibility(arriving.direction);
        sum += light_term(albedo, k_s, g, n, l, v, arriving.radiance * visibility);
    }
    return sum;
}

// ---- tangent-space lighting (as the ARB-era shaders light; src/shading/spaces.rs) ----

const MIN_TBN_DETERMINANT: f32 = 1e-6; // spaces::MIN_TBN_DETERMINANT
const MIN_UV_AREA_PER_M2: f32 = 1e-6;  // spaces::MIN_UV_AREA_PER_M2

fn identity3() -> mat3x3<f32> {
    return mat3x3<f32>(vec3<f32>(1.0, 0.0, 0.0), vec3<f32>(0.0, 1.0, 0.0), vec3<f32>(0.0, 0.0, 1.0));
}

// spaces::inverse_tbn: the inverse of (T | B | N), the identity where it is degenerate.
fn inverse_tbn(t: vec3<f32>, b: vec3<f32>, n: vec3<f32>) -> mat3x3<f32> {
    let det = dot(t, cross(b, n));
    if !(abs(det) >= MIN_TBN_DETERMINANT) || abs(det) > 1e30 {
        return identity3();
    }
    // Rows of the inverse: the cross products of the columns over the determinant.
    return transpose(mat3x3<f32>(cross(b, n), cross(n, t), cross(t, b))) * (1.0 / det);
}

// spaces::triangle_inverse_tbn: the ARB-era shaders' per-triangle frame from two differences across the
// triangle (here the pixel's screen-space derivatives of position and UV): T = ∂P/∂u,
// B = −∂P/∂v, N the face normal on `normal`'s side, normalised, not orthogonalised, inverted.
fn triangle_inverse_tbn(dp_a: vec3<f32>, dp_b: vec3<f32>, duv_a: vec2<f32>, duv_b: vec2<f32>, normal: vec3<f32>) -> mat3x3<f32> {
    let det = duv_a.x * duv_b.y - duv_a.y * duv_b.x;
    let face = cross(dp_a, dp_b);
    if !(abs(det) > MIN_UV_AREA_PER_M2 * length(face)) || abs(det) > 1e30 {
        return identity3();
    }
    let dp_du = (dp_a * duv_b.y - dp_b * duv_a.y) / det;
    let dp_dv = (dp_b * duv_a.x - dp_a * duv_b.x) / det;
    var n = normalize_or(face, normal);
    if dot(n, normal) < 0.0 {
        n = -n;
    }
    return inverse_tbn(normalize_or(dp_du, vec3<f32>(1.0, 0.0, 0.0)), normalize_or(-dp_dv, vec3<f32>(0.0, 1.0, 0.0)), n);
}
