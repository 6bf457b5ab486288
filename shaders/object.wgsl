// The object uniform and the material's textures (group 1), bound by every pass that draws a
// mesh (render::bindings::MATERIAL; parallax.wgsl adds the height map at binding 12), and the
// bits of Object.flags. Prepended after frame.wgsl at build time (render::shaders).

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
    detail: vec4<f32>,          // the detail map's tiling and strength (HAS_DETAIL), unused, unused
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
@group(1) @binding(14) var detail_normal_texture: texture_2d<f32>; // linear: the detail normal map (HAS_DETAIL)

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
const HAS_DETAIL: u32 = 262144u;
const OCCLUSION_IN_METALLIC_ROUGHNESS: u32 = 524288u;
