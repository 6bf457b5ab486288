// The legacy looks (frame::LegacyLook) as lit modes, each the twin of its step in
// src/chain/legacy.rs: DOT3 with the light vector normalised per vertex (optionally
// re-normalised through a normalization cube map) and the emboss look's 2D light map.
// LEGACY is LegacySettings::shader_index(), a pipeline constant: 0 lights as today.

override LEGACY: u32 = 0u;

const LEGACY_DOT3: u32 = 1u;
const LEGACY_DOT3_CUBE_MAP: u32 = 2u;
const LEGACY_EMBOSS: u32 = 3u;
const LIGHT_MAP_SIZE: f32 = 256.0;       // chain::legacy::LIGHT_MAP_SIZE
const EMBOSS_PIXELS_PER_M: f32 = 100.0;  // chain::legacy::EMBOSS_PIXELS_PER_M

// The normalization cube map, six faces as layers (chain::legacy::normalization_cube_map),
// and the emboss light map (chain::legacy::emboss_light_map); 1×1 placeholders while unused.
@group(0) @binding(1) var normalization_cube_map: texture_2d_array<f32>;
@group(0) @binding(2) var emboss_light_map: texture_2d<f32>;

// chain::legacy::vertex_vectors: the unit direction to the first light that is on (the normal
// without one) and the half vector at a vertex, for interpolation.
fn vertex_vectors(position: vec3<f32>, normal: vec3<f32>) -> array<vec3<f32>, 2> {
    let n = normalize_or(normal, vec3<f32>(0.0, 0.0, 1.0));
    var l = n;
    if frame.light_count > 0u {
        l = incident_light(frame.lights[0], position, n).direction;
    }
    let v = normalize_or(frame.camera_pos.xyz - position, n);
    return array<vec3<f32>, 2>(l, normalize_or(l + v, n));
}

// chain::legacy::cube_map_lookup: bilinear on the face `d` points at, clamped at its edges,
// each texel decoded 2·rgb − 1, not re-normalised.
fn cube_map_lookup(d: vec3<f32>) -> vec3<f32> {
    let size = i32(textureDimensions(normalization_cube_map).x);
    let a = abs(d);
    var axis = 2;
    if a.x >= a.y && a.x >= a.z {
        axis = 0;
    } else if a.y >= a.z {
        axis = 1;
    }
    var c = d;
    let major = c[axis];
    let face = 2 * axis + select(0, 1, major < 0.0);
    let scale = select(0.0, 1.0 / abs(major), major != 0.0);
    let uv = vec2<f32>(c[(axis + 1) % 3], c[(axis + 2) % 3]) * scale;
    let texel = clamp((uv + 1.0) * 0.5 * f32(size) - 0.5, vec2<f32>(0.0), vec2<f32>(f32(size - 1)));
    let i0 = vec2<i32>(floor(texel));
    let i1 = min(i0 + 1, vec2<i32>(size - 1));
    let f = texel - vec2<f32>(i0);
    let t00 = textureLoad(normalization_cube_map, vec2<i32>(i0.x, i0.y), face, 0).rgb * 2.0 - 1.0;
    let t10 = textureLoad(normalization_cube_map, vec2<i32>(i1.x, i0.y), face, 0).rgb * 2.0 - 1.0;
    let t01 = textureLoad(normalization_cube_map, vec2<i32>(i0.x, i1.y), face, 0).rgb * 2.0 - 1.0;
    let t11 = textureLoad(normalization_cube_map, vec2<i32>(i1.x, i1.y), face, 0).rgb * 2.0 - 1.0;
    return mix(mix(t00, t10, f.x), mix(t01, t11, f.x), f.y);
}

// chain::legacy::emboss_brightness: the light map's nearest texel, 0 off the map.
fn emboss_brightness(slope: vec2<f32>, light: vec2<f32>) -> f32 {
    let at = floor(slope - light + LIGHT_MAP_SIZE / 2.0);
    if any(at < vec2<f32>(0.0)) || any(at >= vec2<f32>(LIGHT_MAP_SIZE)) {
        return 0.0;
    }
    return textureLoad(emboss_light_map, vec2<i32>(at), 0).r;
}

// The height sample (0..1, after the depth flip) at mip 0, `offset` from `uv`.
fn emboss_height(uv: vec2<f32>, offset: vec2<f32>) -> f32 {
    let texel = textureSampleLevel(height_texture, detail_sampler, uv + offset, 0.0);
    let sample = height_sample(texel);
    return select(sample, 1.0 - sample, (object.flags & DEPTH_MAP) != 0u);
}

// chain::shade's legacy branch: DOT3's or emboss's colour lit by the first light that is on
// (the ambient light alone without one), else today's lighting (lit_color), whose light loop
// reads the per-vertex vectors through the mistakes' hooks (mistakes.wgsl).
fn lit_or_legacy(in: VertexOutput, n_geo: vec3<f32>, frame_tb: TangentFrame, n_shading: vec3<f32>, n_coat: vec3<f32>) -> vec3<f32> {
    if LEGACY == 0u || frame.shading_mode == MODE_COLOUR_ONLY {
        return lit_color(in, n_geo, n_shading, n_coat);
    }
    var albedo = vec3<f32>(1.0);
    if frame.shading_mode != MODE_BUMP_ONLY {
        albedo = textureSample(base_color_texture, base_color_sampler, in.uv).rgb * object.base_color.rgb;
    }
    if frame.light_count == 0u {
        return albedo * frame.ambient.rgb;
    }
    let first = frame.lights[0];
    let arriving = incident_light(first, in.world_position, n_geo);
    if LEGACY == LEGACY_DOT3 || LEGACY == LEGACY_DOT3_CUBE_MAP {
        var l = per_vertex.light;
        if LEGACY == LEGACY_DOT3_CUBE_MAP {
            l = cube_map_lookup(per_vertex.light);
        }
        return albedo * arriving.radiance * max(dot(n_shading, l), 0.0);
    }
    // Emboss, where a height map is bound and the surface has a tangent frame.
    if (object.flags & HAS_PARALLAX_HEIGHT) == 0u || frame_tb.w == 0.0 {
        return albedo * frame.ambient.rgb;
    }
    let size = vec2<f32>(textureDimensions(height_texture, 0));
    let step = 1.0 / size;
    let left = emboss_height(in.uv, vec2<f32>(-step.x, 0.0));
    let right = emboss_height(in.uv, vec2<f32>(step.x, 0.0));
    let up = emboss_height(in.uv, vec2<f32>(0.0, -step.y));
    let down = emboss_height(in.uv, vec2<f32>(0.0, step.y));
    let strength = select(0.0, frame.strength, frame.bump_enabled != 0u);
    let slope = vec2<f32>(right - left, down - up) * 255.0 * strength;
    // chain::legacy::emboss_to_light: to a point light (w = 1), a directional one's unit direction.
    var to_light = arriving.direction;
    if first.position.w != 0.0 {
        to_light = first.position.xyz - in.world_position;
    }
    let light = vec2<f32>(dot(frame_tb.t, to_light), -dot(frame_tb.b, to_light)) * EMBOSS_PIXELS_PER_M;
    return albedo * arriving.radiance * emboss_brightness(slope, light);
}
