// The colour of a mesh pixel in the pipeline's view (VIEW) and, in the lit views, shading
// model (SHADING_MODEL): chain::shade's last step, the lit colour, and the debug views' colours.
// Part of the mesh pass (render::shaders::MESH).

// The view the pipeline draws: ViewMode::shader_index(), one of the VIEW_ constants below
// (0 is Lit).
override VIEW: u32 = 0u;
// The shading model of the lit views (Lit, Over-tilt): ShadingModel::shader_index(), the
// frame's override or else the material's own.
override SHADING_MODEL: u32 = 0u;
const SHADING_METALLIC_ROUGHNESS: u32 = 1u;

// The optional textures and lobes the pipeline's material has: the HAS_ bits of
// MaterialFeatures (src/render/uniforms.rs). Flag tests of these bits go through has(), so a
// pipeline compiles no code for a feature its material lacks: lavapipe runs both sides of a
// branch on a uniform, texture samples included.
override MATERIAL_FEATURES: u32 = 0xffffffffu;

// Whether the material has `feature` (a HAS_ bit of MATERIAL_FEATURES).
fn has(feature: u32) -> bool {
    return (object.flags & (MATERIAL_FEATURES & feature)) != 0u;
}

const VIEW_TANGENT: u32 = 1u;
const VIEW_BITANGENT: u32 = 2u;
const VIEW_NORMAL: u32 = 3u;
const VIEW_SHADING_NORMAL: u32 = 4u;
const VIEW_DIFFERENCE: u32 = 5u;
const VIEW_UV_CHECK: u32 = 6u;
const VIEW_HANDEDNESS: u32 = 7u;
const VIEW_OVER_TILT: u32 = 8u;
const VIEW_CLEARCOAT_NORMAL: u32 = 9u;

const MODE_BUMP_ONLY: u32 = 1u;
const MODE_COLOUR_ONLY: u32 = 2u;

// The lit colour (chain::shade) in the pipeline's shading model, plus emitted light in the
// bump × colour picture.
fn lit_color(in: VertexOutput, n_geo: vec3<f32>, n_shading: vec3<f32>, n_coat: vec3<f32>) -> vec3<f32> {
    var albedo = textureSample(base_color_texture, base_color_sampler, in.uv).rgb * object.base_color.rgb;
    var emission = object.emissive.rgb;
    if has(HAS_EMISSIVE_TEXTURE) {
        emission *= textureSample(emissive_texture, base_color_sampler, in.uv).rgb;
    }
    if frame.shading_mode == MODE_COLOUR_ONLY {
        return albedo;
    }
    if frame.shading_mode == MODE_BUMP_ONLY {
        albedo = vec3<f32>(1.0);
        emission = vec3<f32>(0.0);
    }
    if SHADING_MODEL != SHADING_METALLIC_ROUGHNESS {
        var k_s = object.specular.rgb;
        if has(HAS_GLOSS) {
            k_s *= textureSample(gloss_texture, detail_sampler, in.uv).rgb;
        }
        k_s *= packed_gloss * shininess_energy();
        return blinn_phong(albedo, k_s, n_geo, n_shading, in.world_position) + emission;
    }
    // Each texture is sampled only where the material has it (has(): the pipeline leaves the
    // others out): without one its binding holds a placeholder and the factors stand alone.
    var metal_rough = vec4<f32>(1.0);
    if has(HAS_METALLIC_ROUGHNESS) {
        metal_rough = textureSample(metallic_roughness_texture, detail_sampler, in.uv);
    }
    // Without an occlusion texture the factor is exactly 1.
    var occlusion = 1.0;
    if has(HAS_OCCLUSION_TEXTURE) {
        // A packed occlusion-roughness-metallic map is read once: the same texture, sampler and
        // UV give the same red. Tested on the constant alone (the pipeline's features are the
        // material's), so the pipeline compiles only one of the two reads.
        var occluded = metal_rough.r;
        if (MATERIAL_FEATURES & OCCLUSION_IN_METALLIC_ROUGHNESS) == 0u {
            occluded = textureSample(occlusion_texture, detail_sampler, in.uv).r;
        }
        occlusion += object.occlusion_strength * (occluded - 1.0);
    }
    var coat = vec2<f32>(0.0); // factor, roughness; 0: no coat
    if has(HAS_CLEARCOAT) {
        coat = object.clearcoat.xy;
    }
    if has(HAS_CLEARCOAT_TEXTURE) {
        coat.x *= textureSample(clearcoat_texture, detail_sampler, clearcoat_uv(in.uv)).r;
    }
    if has(HAS_CLEARCOAT_ROUGHNESS_TEXTURE) {
        coat.y *= textureSample(clearcoat_roughness_texture, detail_sampler, clearcoat_uv(in.uv)).g;
    }
    let inputs = PbrInputs(
        albedo,
        object.metallic * metal_rough.b,
        mip_widened_roughness(object.roughness * metal_rough.g),
        occlusion,
        n_geo,
        n_shading,
        in.world_position,
        has(HAS_CLEARCOAT),
        coat.x,
        coat.y,
        n_coat,
    );
    return metallic_roughness(inputs) + emission;
}

// The UV check view, from screen-space derivatives of the UVs and the position: red where the
// UV triangle has (relatively) no area, blue where its UV winding is mirrored against the
// geometric normal (w = −1 there), grey elsewhere. The CPU twin is check::check_mesh.
fn uv_check_color(in: VertexOutput, n_geo: vec3<f32>) -> vec3<f32> {
    let du = vec2<f32>(dpdx(in.uv.x), dpdy(in.uv.x));
    let dv = vec2<f32>(dpdx(in.uv.y), dpdy(in.uv.y));
    let dp_dx = dpdx(in.world_position);
    let dp_dy = dpdy(in.world_position);
    let det = du.x * dv.y - du.y * dv.x;
    let shade = 0.35 + 0.5 * abs(dot(n_geo, normalize_or(frame.camera_pos.xyz - in.world_position, n_geo)));
    if abs(det) <= 1e-3 * length(du) * length(dv) || length(du) * length(dv) == 0.0 {
        return vec3<f32>(0.9, 0.1, 0.1) * shade;
    }
    // ∂P/∂u and ∂P/∂v (v down the image), each times det; mirrored when (∂P/∂u, ∂P/∂v_up)
    // winds against the vertex normal.
    let dp_du = dp_dx * dv.y - dp_dy * dv.x;
    let dp_dv = dp_dy * du.x - dp_dx * du.y;
    if dot(cross(dp_du, dp_dv), in.world_normal) > 0.0 {
        return vec3<f32>(0.15, 0.35, 1.0) * shade;
    }
    return vec3<f32>(0.75) * shade;
}

// shading::handedness_color: green for w = +1, magenta for w = −1, grey without tangents.
fn handedness_color(in: VertexOutput, n_geo: vec3<f32>, w: f32) -> vec3<f32> {
    var base = vec3<f32>(0.5);
    if w < 0.0 {
        base = vec3<f32>(0.9, 0.2, 0.8);
    } else if w > 0.0 {
        base = vec3<f32>(0.25, 0.85, 0.3);
    }
    let to_eye = normalize_or(frame.camera_pos.xyz - in.world_position, n_geo);
    return base * (0.35 + 0.65 * abs(dot(n_geo, to_eye)));
}

fn surface_color(
    in: VertexOutput,
    n_geo: vec3<f32>,
    frame_tb: TangentFrame,
    n_shading: vec3<f32>,
    n_coat: vec3<f32>,
) -> vec4<f32> {
    switch VIEW {
        case VIEW_TANGENT: { return stored(0.5 * frame_tb.t + 0.5); }
        case VIEW_BITANGENT: { return stored(0.5 * frame_tb.b + 0.5); }
        case VIEW_NORMAL: { return stored(0.5 * n_geo + 0.5); }
        case VIEW_SHADING_NORMAL: { return stored(0.5 * n_shading + 0.5); }
        // Drawn with fs_difference when the mesh has frames; without them, neutral grey.
        case VIEW_DIFFERENCE: { return stored(vec3<f32>(0.5)); }
        case VIEW_UV_CHECK: { return stored(uv_check_color(in, n_geo)); }
        case VIEW_HANDEDNESS: { return stored(handedness_color(in, n_geo, frame_tb.w)); }
        case VIEW_CLEARCOAT_NORMAL: { return stored(0.5 * n_coat + 0.5); }
        // shading::over_tilted: saturated red where N·N_geo < cos(OVER_TILT_LIMIT_DEG), over
        // the lit picture in grey (shading::over_tilt_grey: its linear luminance).
        case VIEW_OVER_TILT: {
            if dot(n_shading, n_geo) < frame.over_tilt_cos {
                return stored(vec3<f32>(1.0, 0.0, 0.0));
            }
            let lit = lit_or_legacy(in, n_geo, frame_tb, n_shading, n_coat);
            return vec4<f32>(vec3<f32>(dot(lit, vec3<f32>(0.2126, 0.7152, 0.0722))), 1.0);
        }
        default: { return vec4<f32>(lit_or_legacy(in, n_geo, frame_tb, n_shading, n_coat), 1.0); }
    }
}
