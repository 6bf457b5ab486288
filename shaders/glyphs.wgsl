// The T/B/N glyphs' pass (src/render/glyphs.rs makes the lines): a line list at chosen
// vertices, each line in its axis's colour. Prepended at build time: frame.wgsl, object.wgsl,
// common.wgsl (render::shaders::GLYPHS).

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
