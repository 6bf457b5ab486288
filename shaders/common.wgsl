// What every pass that draws a mesh shares (render::shaders): the vertex transform to world
// space, the guarded vector helpers (src/math.rs), the surface's tangent frame and debug
// colours stored as given. Conventions: see the crate docs (src/lib.rs).

// True when the target stores sRGB-encoded values (Rgba8UnormSrgb): debug colours are then
// decoded first so the stored bytes equal 0.5·v + 0.5.
override TARGET_ENCODES_SRGB: bool = true;

// What the vertex stages write and the fragment stages read (every shading function takes it).
struct VertexOutput {
    @builtin(position) clip_position: vec4<f32>,
    @location(0) world_position: vec3<f32>,
    @location(1) world_normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    @location(3) world_tangent: vec4<f32>,
};

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

// shading::height_sample: a height map's texel as a height sample, 0..1 of the full range: 16
// bits in red (high byte) and green (low byte), TextureKind::Height.
fn height_sample(texel: vec4<f32>) -> f32 {
    return (texel.r * 65280.0 + texel.g * 255.0) / 65535.0;
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
