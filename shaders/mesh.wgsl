// The mesh pass: Blinn-Phong or metallic-roughness (pbr.wgsl) with tangent- or object-space
// normal mapping, the parallax family and the debug views. The CPU twin of the fragment stage
// is chain::shade (src/chain.rs), step for step; keep the two in step.
//
// Entry points form the pipeline variants (src/render/pipelines.rs), each specialised by
// pipeline constants (VIEW, SHADING_MODEL, MATERIAL_FEATURES, PARALLAX, MISTAKE, LEGACY,
// LIGHTING_SPACE, MIP_FILTER) so it compiles only what it draws:
//   vs_plain  + fs_plain          mesh without tangents, material without normal map
//   vs_tangent + fs_tangent       mesh with tangents, material without normal map
//   vs_tangent + fs_normal_mapped mesh with tangents and a tangent-space normal map, read at
//                                 the UV the parallax family shifts (parallax.wgsl), lit in
//                                 any space (LIGHTING_SPACE)
//   vs_plain  + fs_object_space   object-space normal map, no tangents
//   vs_plain  + fs_height_bump    bump from the height map in screen space, no tangents
//
// Each entry point is written once, over `Varyings`: the stages' interface comes from one of
// two fragments appended at build time (render::shaders), mesh_varyings.wgsl (VertexOutput
// itself) or mesh_varyings_per_vertex.wgsl (VertexOutput plus the per-vertex light direction
// and half vector, for the legacy looks and the per-vertex mistakes alone).
//
// Prepended at build time: frame.wgsl (the Frame uniform, group 0), object.wgsl (group 1),
// common.wgsl, normal_map.wgsl, mip_filter.wgsl (the MIP_FILTER constant), lean.wgsl (LEAN's
// texture, group 2, in render::shaders::MESH_LEAN) or lean_unbound.wgsl, surface_color.wgsl,
// pbr.wgsl, parallax.wgsl, mistakes.wgsl (the MISTAKE constant), legacy.wgsl (the LEGACY constant) and lights.wgsl (the lights and
// the classic model's lighting spaces).

// ---- vertex stages ----

@vertex
fn vs_plain(@location(0) position: vec3<f32>, @location(1) normal: vec3<f32>, @location(2) uv: vec2<f32>) -> Varyings {
    return vertex_varyings(to_world(position, normal, uv, vec4<f32>(0.0)));
}

@vertex
fn vs_tangent(
    @location(0) position: vec3<f32>,
    @location(1) normal: vec3<f32>,
    @location(2) uv: vec2<f32>,
    @location(3) tangent: vec4<f32>,
) -> Varyings {
    return vertex_varyings(to_world(position, normal, uv, tangent));
}

// ---- surfaces: each variant's shading normal and frame, then the view's colour ----

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

// A tangent-space normal map read at the UV the parallax family shifts. Lit in tangent space
// (LIGHTING_SPACE, blinn_phong's LIGHTING_TANGENT branch): the same normal, frame and views,
// with the light and view vectors taken by the triangle's inverse frame from screen-space
// derivatives (the ARB-era tangent-space shaders take light − P per vertex and interpolate;
// with one frame per triangle that is the frame times light − P at the pixel, exactly).
fn normal_mapped_surface(vertex: VertexOutput, front_facing: bool) -> vec4<f32> {
    let n = geometric_normal(vertex.world_normal, front_facing);
    if LIGHTING_SPACE == LIGHTING_TANGENT {
        tangent_space.to_tangent = triangle_inverse_tbn(
            dpdx(vertex.world_position),
            dpdy(vertex.world_position),
            dpdx(vertex.uv),
            dpdy(vertex.uv),
            n,
        );
        tangent_space.normal = vec3<f32>(0.0, 0.0, 1.0);
    }
    var in = vertex;
    in.uv = parallax_uv(vertex.uv, n, vertex.world_position);
    let frame_tb = mistaken_frame(in.world_tangent, n);
    let texel = mistaken_texel(lean_texel(sample_normal_map(in.uv), in.uv, frame.strength * object.normal_scale));
    set_mip_variance_from_texel(texel.texel, frame.strength * object.normal_scale);
    var n_shading = base_normal(vertex.world_normal, front_facing, n);
    if frame.bump_enabled != 0u {
        let strength = frame.strength * object.normal_scale;
        let nt = detailed_normal(tangent_space_normal(texel, strength, mistaken_flags(object.flags)), in.uv);
        n_shading = tangent_to_world(frame_tb, n_shading, nt);
        if LIGHTING_SPACE == LIGHTING_TANGENT {
            tangent_space.normal = nt;
        }
    }
    set_mip_variance_from_normal(n_shading);
    return surface_color(in, n, frame_tb, n_shading, clearcoat_normal(in, n, frame_tb));
}

// shading::object_space_normal: the map holds model-space normals; no tangents.
fn object_space_surface(in: VertexOutput, front_facing: bool) -> vec4<f32> {
    let n = geometric_normal(in.world_normal, front_facing);
    let texel = mistaken_texel(sample_normal_map(in.uv));
    set_mip_variance_from_texel(texel.texel, frame.strength * object.normal_scale);
    var n_shading = base_normal(in.world_normal, front_facing, n);
    if frame.bump_enabled != 0u {
        let facing = select(-1.0, 1.0, front_facing);
        let model_normal = decode_normal(texel.texel, texel.correction, mistaken_flags(object.flags));
        let n_map = facing * normalize_or((object.normal_matrix * vec4<f32>(model_normal, 0.0)).xyz, n);
        n_shading = normalize_or(n + frame.strength * object.normal_scale * (n_map - n), n);
    }
    set_mip_variance_from_normal(n_shading);
    // No tangents: the T and B views show the zero vector (mid grey), and no coat normal map.
    return surface_color(in, n, TangentFrame(vec3<f32>(0.0), vec3<f32>(0.0), 0.0), n_shading, n);
}

// Blinn's bump from a height field without tangents: Mikkelsen's surface gradient from
// screen-space derivatives of the position and of the height (metres, height_sample).
fn height_bump_surface(in: VertexOutput, front_facing: bool) -> vec4<f32> {
    let n = geometric_normal(in.world_normal, front_facing);
    let texel = textureSample(bump_texture, detail_sampler, in.uv);
    var sample = height_sample(texel);
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

// ---- fragment entry points ----

@fragment
fn fs_plain(in: Varyings, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    return plain_surface(fragment_inputs(in), front_facing);
}

@fragment
fn fs_tangent(in: Varyings, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    return tangent_surface(fragment_inputs(in), front_facing);
}

@fragment
fn fs_normal_mapped(in: Varyings, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    return normal_mapped_surface(fragment_inputs(in), front_facing);
}

@fragment
fn fs_object_space(in: Varyings, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    return object_space_surface(fragment_inputs(in), front_facing);
}

@fragment
fn fs_height_bump(in: Varyings, @builtin(front_facing) front_facing: bool) -> @location(0) vec4<f32> {
    return height_bump_surface(fragment_inputs(in), front_facing);
}
