// Blinn-Phong or metallic-roughness (pbr.wgsl) with tangent- or object-space normal mapping,
// and the TBN debug views.
// Conventions: see the crate docs (src/lib.rs). The CPU reference of every function here is
// src/shading.rs; keep the two in step.
//
// Entry points form the pipeline variants (src/render/pipelines.rs), and each mesh variant is
// specialised by two pipeline constants, VIEW and SHADING_MODEL, so it compiles only the view
// and the shading model it draws:
//   vs_plain  + fs_plain          mesh without tangents, material without normal map
//   vs_tangent + fs_tangent       mesh with tangents, material without normal map
//   vs_tangent + fs_normal_mapped mesh with tangents and a tangent-space normal map, read at
//                                 the UV the parallax family shifts (parallax.wgsl)
//   vs_tangent + fs_normal_mapped_tangent_space  the same, lit in tangent space (seed 003)
//   vs_plain  + fs_object_space   object-space normal map, no tangents
//   vs_plain  + fs_height_bump    bump from the height map in screen space, no tangents
//   vs_difference + fs_difference the Difference view: a mesh's frames against reference frames
//   vs_wireframe + fs_wireframe   the wireframe overlay (a second pass, PolygonMode::Line)
//   vs_glyph + fs_glyph           T/B/N glyphs at vertices (a line list, src/render/glyphs.rs)
//
// Prepended at build time: frame.wgsl (the Frame uniform, group 0), pbr.wgsl, parallax.wgsl,
// mistakes.wgsl (the classic mistakes, the MISTAKE constant), legacy.wgsl (the legacy looks,
// the LEGACY constant) and lights.wgsl (the lights and the classic model's lighting spaces).

struct Object {
    model: mat4x4<f32>,
    normal_matrix: mat4x4<f32>, // inverse-transpose of model (upper 3x3 used)
    base_color: vec4<f32>,      // linear factor
    specular: vec4<f32>,        // rgb = k_s, a = shininess
    handedness: f32,            // sign(det(model)), multiplies tangent w
    normal_scale: f32,          // the material's normalTexture.scale
    height_range_m: f32,        // metres spanned by the height map's full range
    flags: u32,                 // NormalConvention::flags | DEPTH_MAP | HAS_METALLIC_ROUGHNESS | HAS_GLOSS
    metallic: f32,              // metallic-roughness factors
    roughness: f32,
    occlusion_strength: f32,
    emissive: vec4<f32>,        // rgb: linear emitted light (times the texture at 8 if HAS_EMISSIVE_TEXTURE)
    clearcoat: vec4<f32>,       // factor, perceptual roughness, normal-map scale (HAS_CLEARCOAT)
    clearcoat_uv: array<vec4<f32>, 2>, // rows of the 2x3 affine: mesh UV -> the coat's textures
};

@group(1) @binding(0) var<uniform> object: Object;
@group(1) @binding(1) var base_color_texture: texture_2d<f32>; // sRGB view: samples are linear
@group(1) @binding(2) var base_color_sampler: sampler;
@group(1) @binding(3) var bump_texture: texture_2d<f32>;       // normal map or height map, linear
@group(1) @binding(4) var detail_sampler: sampler;             // bump, metallic-roughness, occlusion
@group(1) @binding(5) var metallic_roughness_texture: texture_2d<f32>; // linear: B metal, G rough
@group(1) @binding(6) var occlusion_texture: texture_2d<f32>;  // linear: R occlusion
@group(1) @binding(7) var gloss_texture: texture_2d<f32>;      // linear: RGB scales k_s
@group(1) @binding(8) var emissive_texture: texture_2d<f32>;   // sRGB view; base colour sampler
@group(1) @binding(9) var clearcoat_texture: texture_2d<f32>;  // linear: R coat strength
@group(1) @binding(10) var clearcoat_roughness_texture: texture_2d<f32>; // linear: G coat roughness
@group(1) @binding(11) var clearcoat_normal_texture: texture_2d<f32>;    // linear: the coat's normal map
@group(1) @binding(13) var bump_correction_texture: texture_2d<f32>; // linear: X-Ray's bump# (RGB correction)

const FLIP_GREEN: u32 = 1u;
const LAYOUT_RG: u32 = 2u;
const DEPTH_MAP: u32 = 8u;
const HAS_METALLIC_ROUGHNESS: u32 = 16u;
const HAS_GLOSS: u32 = 32u;
const HAS_OCCLUSION_TEXTURE: u32 = 16384u;
const HAS_EMISSIVE_TEXTURE: u32 = 64u;
const HAS_CLEARCOAT: u32 = 128u;
const HAS_CLEARCOAT_TEXTURE: u32 = 256u;
const HAS_CLEARCOAT_ROUGHNESS_TEXTURE: u32 = 512u;
const HAS_CLEARCOAT_NORMAL: u32 = 1024u;
const LAYOUT_AG: u32 = 32768u;
const LAYOUT_XRAY: u32 = 65536u;
const HAS_BUMP_CORRECTION: u32 = 131072u;
const SHADING_METALLIC_ROUGHNESS: u32 = 1u;

// True when the target stores sRGB-encoded values (Rgba8UnormSrgb): debug colours are then
// decoded first so the stored bytes equal 0.5·v + 0.5.
override TARGET_ENCODES_SRGB: bool = true;
// The view the pipeline draws: ViewMode::shader_index(), one of the VIEW_ constants below
// (0 is Lit).
override VIEW: u32 = 0u;
// The shading model of the lit views (Lit, Over-tilt): ShadingModel::shader_index(), the
// frame's override or else the material's own.
override SHADING_MODEL: u32 = 0u;

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

// What the vertex stages write and the fragment stages read (every shading function takes it).
struct VertexOutput {
    @builtin(position) clip_position: vec4<f32>,
    @location(0) world_position: vec3<f32>,
    @location(1) world_normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    @location(3) world_tangent: vec4<f32>,
};

// VertexOutput with legacy.wgsl's per-vertex light direction and half vector: what the
// `_per_vertex` stages pass on, for the legacy looks and the per-vertex mistakes alone
// (render::pipelines::per_vertex_entry): llvmpipe sets up every vertex output, read or not.
struct PerVertexOutput {
    @builtin(position) clip_position: vec4<f32>,
    @location(0) world_position: vec3<f32>,
    @location(1) world_normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    @location(3) world_tangent: vec4<f32>,
    @location(4) vertex_light: vec3<f32>,
    @location(5) vertex_half: vec3<f32>,
};

// The fragment inputs of a `_per_vertex` entry point, its per-vertex vectors kept for the
// mistakes' hooks and the legacy looks (mistakes.wgsl's per_vertex).
fn with_per_vertex(v: PerVertexOutput) -> VertexOutput {
    per_vertex = PerVertexVectors(v.vertex_light, v.vertex_half);
    return VertexOutput(v.clip_position, v.world_position, v.world_normal, v.uv, v.world_tangent);
}

fn to_world(position: vec3<f32>, normal: vec3<f32>, uv: vec2<f32>, tangent: vec4<f32>) -> VertexOutput {
    var out: VertexOutput;
    let world = object.model * vec4<f32>(position, 1.0);
    out.clip_position = frame.view_proj * world;
    out.world_position = world.xyz;
    out.world_normal = (object.normal_matrix * vec4<f32>(normal, 0.0)).xyz;
    out.uv = uv;
    out.world_tangent = vec4<f32>((object.model * vec4<f32>(tangent.xyz, 0.0)).xyz, tangent.w * object.handedness);
    return out;
}

// VertexOutput with legacy.wgsl's per-vertex light direction and half vector.
fn with_vertex_vectors(out: VertexOutput) -> PerVertexOutput {
    let vectors = vertex_vectors(out.world_position, out.world_normal);
    return PerVertexOutput(out.clip_position, out.world_position, out.world_normal, out.uv, out.world_tangent, vectors[0], vectors[1]);
}

@vertex
fn vs_plain(@location(0) position: vec3<f32>, @location(1) normal: vec3<f32>, @location(2) uv: vec2<f32>) -> VertexOutput {
    return to_world(position, normal, uv, vec4<f32>(0.0));
}

@vertex
fn vs_tangent(
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    @location(3) tangent: vec4<f32>,
) -> VertexOutput {
    return to_world(position, normal, uv, tangent);
}

@vertex
fn vs_plain_per_vertex(@location(0) position: vec3<f32>, @location(1) normal: vec3<f32>, @location(2) uv: vec2<f32>) -> PerVertexOutput {
    return with_vertex_vectors(to_world(position, normal, uv, vec4<f32>(0.0)));
}

@vertex
fn vs_tangent_per_vertex(
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    @location(3) tangent: vec4<f32>,
) -> PerVertexOutput {
    return with_vertex_vectors(to_world(position, normal, uv, tangent));
}

// ---- guarded vector helpers (src/math.rs) ----

fn normalize_or(v: vec3<f32>, fallback: vec3<f32>) -> vec3<f32> {
    let length_squared = dot(v, v);
    if length_squared >= 1e-30 && length_squared < 1e30 {
        return v * inverseSqrt(length_squared);
    }
    return fallback;
}

// glam's Vec3::any_orthonormal_vector.
fn any_perpendicular(n: vec3<f32>) -> vec3<f32> {
    let s = select(-1.0, 1.0, n.z >= 0.0);
    let a = -1.0 / (s + n.z);
    let b = n.x * n.y * a;
    return vec3<f32>(b, s + n.y * n.y * a, -n.y);
}

fn orthonormalize_tangent(t: vec3<f32>, n: vec3<f32>) -> vec3<f32> {
    return normalize_or(t - n * dot(n, t), any_perpendicular(n));
}

// ---- surface frame ----

fn geometric_normal(world_normal: vec3<f32>, front_facing: bool) -> vec3<f32> {
    let n = normalize_or(world_normal, vec3<f32>(0.0, 0.0, 1.0));
    // Only double-sided materials draw back faces; there N flips, and with it B.
    return select(-n, n, front_facing);
}

struct TangentFrame {
    t: vec3<f32>,
    b: vec3<f32>,
    w: f32, // handedness ±1; 0 where the mesh is drawn without tangents
};

fn tangent_frame(world_tangent: vec4<f32>, n: vec3<f32>) -> TangentFrame {
    let t = orthonormalize_tangent(world_tangent.xyz, n);
    let w = select(1.0, -1.0, world_tangent.w < 0.0);
    return TangentFrame(t, w * cross(n, t), w);
}

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

// shading::perturbed_normal (through mistakes.wgsl's tangent_to_world); `n` is the base
// normal, `flags` carries the map's convention bits.
fn perturbed_normal(n: vec3<f32>, frame_tb: TangentFrame, texel: NormalSample, strength: f32, flags: u32) -> vec3<f32> {
    let nt = tangent_space_normal(texel, strength, flags);
    return tangent_to_world(frame_tb, n, nt);
}

fn srgb_to_linear(c: vec3<f32>) -> vec3<f32> {
    return select(pow((c + 0.055) / 1.055, vec3<f32>(2.4)), c / 12.92, c <= vec3<f32>(0.04045));
}

// A debug colour that must be *stored* as given.
fn stored(c: vec3<f32>) -> vec4<f32> {
    if TARGET_ENCODES_SRGB {
        return vec4<f32>(srgb_to_linear(c), 1.0);
    }
    return vec4<f32>(c, 1.0);
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
        k_s *= packed_gloss;
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
        occlusion += object.occlusion_strength * (textureSample(occlusion_texture, detail_sampler, in.uv).r - 1.0);
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
        object.roughness * metal_rough.g,
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
        // shading::over_tilted: saturated red where N·N_geo < cos(OVER_TILT_LIMIT_DEG).
        case VIEW_OVER_TILT: {
            if dot(n_shading, n_geo) < frame.over_tilt_cos {
                return stored(vec3<f32>(1.0, 0.0, 0.0));
            }
            return vec4<f32>(lit_or_legacy(in, n_geo, frame_tb, n_shading, n_coat), 1.0);
        }
        default: { return vec4<f32>(lit_or_legacy(in, n_geo, frame_tb, n_shading, n_coat), 1.0); }
    }
}

fn plain_surface(in: VertexOutput, front_facing: bool) -> vec4<f32> {
    let n = geometric_normal(in.world_normal, front_facing);
    // No tangents: the T and B views show the zero vector (mid grey).
    let base = base_normal(in.world_normal, front_facing, n);
    return surface_color(in, n, TangentFrame(vec3<f32>(0.0), vec3<f32>(0.0), 0.0), base, n);
}

fn tangent_surface(in: VertexOutput, front_facing: bool) -> vec4<f32> {
    let n = geometric_normal(in.world_normal, front_facing);
    let frame_tb = mistaken_frame(in.world_tangent, n);
    let base = base_normal(in.world_normal, front_facing, n);
    return surface_color(in, n, frame_tb, base, clearcoat_normal(in, n, frame_tb));
}

fn normal_mapped_surface(vertex: VertexOutput, front_facing: bool) -> vec4<f32> {
    let n = geometric_normal(vertex.world_normal, front_facing);
    var in = vertex;
    in.uv = parallax_uv(vertex.uv, n, vertex.world_position);
    let frame_tb = mistaken_frame(in.world_tangent, n);
    let texel = mistaken_texel(sample_normal_map(in.uv));
    var n_shading = base_normal(vertex.world_normal, front_facing, n);
    if frame.bump_enabled != 0u {
        let strength = frame.strength * object.normal_scale;
        n_shading = perturbed_normal(n_shading, frame_tb, texel, strength, mistaken_flags(object.flags));
    }
    return surface_color(in, n, frame_tb, n_shading, clearcoat_normal(in, n, frame_tb));
}

// fs_normal_mapped lit in tangent space (blinn_phong's LIGHTING_TANGENT branch): the same
// normal, frame and views, with the light and view vectors taken by the triangle's inverse
// frame from screen-space derivatives (seed 003 takes light − P per vertex and interpolates;
// with one frame per triangle that is the frame times light − P at the pixel, exactly).
fn normal_mapped_tangent_space_surface(vertex: VertexOutput, front_facing: bool) -> vec4<f32> {
    let n = geometric_normal(vertex.world_normal, front_facing);
    tangent_space.to_tangent = triangle_inverse_tbn(
        dpdx(vertex.world_position),
        dpdy(vertex.world_position),
        dpdx(vertex.uv),
        dpdy(vertex.uv),
        n,
    );
    var in = vertex;
    in.uv = parallax_uv(vertex.uv, n, vertex.world_position);
    let frame_tb = mistaken_frame(in.world_tangent, n);
    let texel = mistaken_texel(sample_normal_map(in.uv));
    var n_shading = base_normal(vertex.world_normal, front_facing, n);
    tangent_space.normal = vec3<f32>(0.0, 0.0, 1.0);
    if frame.bump_enabled != 0u {
        let strength = frame.strength * object.normal_scale;
        let flags = mistaken_flags(object.flags);
        n_shading = perturbed_normal(n_shading, frame_tb, texel, strength, flags);
        tangent_space.normal = tangent_space_normal(texel, strength, flags);
    }
    return surface_color(in, n, frame_tb, n_shading, clearcoat_normal(in, n, frame_tb));
}

// shading::object_space_normal: the map holds model-space normals; no tangents.
fn object_space_surface(in: VertexOutput, front_facing: bool) -> vec4<f32> {
    let n = geometric_normal(in.world_normal, front_facing);
    let texel = mistaken_texel(sample_normal_map(in.uv));
    var n_shading = base_normal(in.world_normal, front_facing, n);
    if frame.bump_enabled != 0u {
        let facing = select(-1.0, 1.0, front_facing);
        let model_normal = decode_normal(texel.texel, texel.correction, mistaken_flags(object.flags));
        let n_map = facing * normalize_or((object.normal_matrix * vec4<f32>(model_normal, 0.0)).xyz, n);
        n_shading = normalize_or(n + frame.strength * object.normal_scale * (n_map - n), n);
    }
    // No tangents: the T and B views show the zero vector (mid grey), and no coat normal map.
    return surface_color(in, n, TangentFrame(vec3<f32>(0.0), vec3<f32>(0.0), 0.0), n_shading, n);
}

// Blinn's bump from a height field without tangents: Mikkelsen's surface gradient from
// screen-space derivatives of the position and of the height (metres). Heights are 16 bits in
// red (high byte) and green (low byte), TextureKind::Height.
fn height_bump_surface(in: VertexOutput, front_facing: bool) -> vec4<f32> {
    let n = geometric_normal(in.world_normal, front_facing);
    let texel = textureSample(bump_texture, detail_sampler, in.uv);
    var sample = (texel.r * 65280.0 + texel.g * 255.0) / 65535.0;
    if (object.flags & DEPTH_MAP) != 0u {
        sample = 1.0 - sample;
    }
    let height = sample * object.height_range_m * frame.strength;
    let dp_dx = dpdx(in.world_position);
    let dp_dy = dpdy(in.world_position);
    let dh_dx = dpdx(height);
    let dh_dy = dpdy(height);
    var n_shading = base_normal(in.world_normal, front_facing, n);
    if frame.bump_enabled != 0u {
        let r1 = cross(dp_dy, n);
        let r2 = cross(n, dp_dx);
        let det = dot(dp_dx, r1);
        let surface_gradient = sign(det) * (dh_dx * r1 + dh_dy * r2);
        n_shading = normalize_or(abs(det) * n - surface_gradient, n);
    }
    // No tangents: the T and B views show the zero vector (mid grey), and no coat normal map.
    return surface_color(in, n, TangentFrame(vec3<f32>(0.0), vec3<f32>(0.0), 0.0), n_shading, n);
}

// ---- fragment entry points: each surface without and with the per-vertex vectors ----

@fragment
fn fs_plain(in: VertexOutput, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    return plain_surface(in, front_facing);
}

@fragment
fn fs_plain_per_vertex(in: PerVertexOutput, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    return plain_surface(with_per_vertex(in), front_facing);
}

@fragment
fn fs_tangent(in: VertexOutput, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    return tangent_surface(in, front_facing);
}

@fragment
fn fs_tangent_per_vertex(in: PerVertexOutput, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    return tangent_surface(with_per_vertex(in), front_facing);
}

@fragment
fn fs_normal_mapped(in: VertexOutput, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    return normal_mapped_surface(in, front_facing);
}

@fragment
fn fs_normal_mapped_per_vertex(in: PerVertexOutput, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    return normal_mapped_surface(with_per_vertex(in), front_facing);
}

@fragment
fn fs_normal_mapped_tangent_space(in: VertexOutput, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    return normal_mapped_tangent_space_surface(in, front_facing);
}

@fragment
fn fs_normal_mapped_tangent_space_per_vertex(in: PerVertexOutput, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    return normal_mapped_tangent_space_surface(with_per_vertex(in), front_facing);
}

@fragment
fn fs_object_space(in: VertexOutput, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    return object_space_surface(in, front_facing);
}

@fragment
fn fs_object_space_per_vertex(in: PerVertexOutput, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    return object_space_surface(with_per_vertex(in), front_facing);
}

@fragment
fn fs_height_bump(in: VertexOutput, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    return height_bump_surface(in, front_facing);
}

@fragment
fn fs_height_bump_per_vertex(in: PerVertexOutput, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    return height_bump_surface(with_per_vertex(in), front_facing);
}

// ---- Difference view (shading::difference_color is the CPU twin of the colour scale) ----

struct DifferenceOutput {
    @builtin(position) clip_position: vec4<f32>,
    @location(1) world_normal: vec3<f32>,
    @location(3) world_tangent: vec4<f32>,
    @location(4) world_reference: vec4<f32>,
};

@vertex
fn vs_difference(
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    @location(3) tangent: vec4<f32>,
    @location(4) reference: vec4<f32>,
) -> DifferenceOutput {
    let frame_out = to_world(position, normal, uv, tangent);
    let reference_out = to_world(position, normal, uv, reference);
    return DifferenceOutput(frame_out.clip_position, frame_out.world_normal, frame_out.world_tangent, reference_out.world_tangent);
}

fn angle_deg(a: vec3<f32>, b: vec3<f32>) -> f32 {
    return degrees(acos(clamp(dot(a, b), -1.0, 1.0)));
}

// Viridis-like ramp through five stops, t in 0..1 (display values).
fn difference_color(t: f32) -> vec3<f32> {
    let stops = array<vec3<f32>, 5>(
        vec3<f32>(0.267, 0.005, 0.329),
        vec3<f32>(0.229, 0.322, 0.546),
        vec3<f32>(0.128, 0.567, 0.551),
        vec3<f32>(0.369, 0.789, 0.383),
        vec3<f32>(0.993, 0.906, 0.144),
    );
    let x = clamp(t, 0.0, 1.0) * 4.0;
    let i = min(u32(floor(x)), 3u);
    return mix(stops[i], stops[i + 1u], x - f32(i));
}

// The larger of the angles between the two frames' T and B, on a 0..difference_range scale.
@fragment
fn fs_difference(in: DifferenceOutput, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    let n = geometric_normal(in.world_normal, front_facing);
    let frame_tb = tangent_frame(in.world_tangent, n);
    let reference_tb = tangent_frame(in.world_reference, n);
    let angle = max(angle_deg(frame_tb.t, reference_tb.t), angle_deg(frame_tb.b, reference_tb.b));
    return stored(difference_color(angle / max(frame.difference_range_deg, 1e-6)));
}

// ---- Wireframe overlay: the triangle edges in a dim colour, drawn after the meshes ----

@vertex
fn vs_wireframe(@location(0) position: vec3<f32>) -> @builtin(position) vec4<f32> {
    return frame.view_proj * (object.model * vec4<f32>(position, 1.0));
}

@fragment
fn fs_wireframe() -> @location(0) vec4<f32> {
    return stored(vec3<f32>(0.08, 0.08, 0.1));
}

// ---- T/B/N glyphs (src/render/glyphs.rs) ----

// Glyph bases sit this fraction of the glyph length above the surface, along N, so the T and
// B lines, which lie in the tangent plane, win the depth test against their own surface.
const GLYPH_LIFT: f32 = 0.04;

struct GlyphOutput {
    @builtin(position) clip_position: vec4<f32>,
    @location(0) color: vec3<f32>,
};

// glyph = [axis (0 T, 1 B, 2 N), end (0 surface, 1 tip), length (model-space metres)]. The
// frame is the shading's: T orthonormalised against N, B = w·(N × T), in world space.
@vertex
fn vs_glyph(
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(3) tangent: vec4<f32>,
    @location(5) glyph: vec3<f32>,
) -> GlyphOutput {
    let v = to_world(position, normal, vec2<f32>(0.0), tangent);
    let n = normalize_or(v.world_normal, vec3<f32>(0.0, 0.0, 1.0));
    let tb = tangent_frame(v.world_tangent, n);
    let model = mat3x3<f32>(object.model[0].xyz, object.model[1].xyz, object.model[2].xyz);
    let length = glyph.z * pow(abs(determinant(model)), 1.0 / 3.0);
    var direction = n;
    var color = vec3<f32>(0.2, 0.4, 1.0);
    if glyph.x < 0.5 {
        direction = tb.t;
        color = vec3<f32>(1.0, 0.15, 0.1);
    } else if glyph.x < 1.5 {
        direction = tb.b;
        color = vec3<f32>(0.1, 1.0, 0.15);
    }
    let world = v.world_position + n * (GLYPH_LIFT * length) + direction * (glyph.y * length);
    var out: GlyphOutput;
    out.clip_position = frame.view_proj * vec4<f32>(world, 1.0);
    out.color = color;
    return out;
}

@fragment
fn fs_glyph(in: GlyphOutput) -> @location(0) vec4<f32> {
    return stored(in.color);
}
