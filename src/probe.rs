//! The pixel probe: the whole shading chain at one pixel of the 3D view, on the CPU.
//!
//! [`ProbeScene::pick`] casts the ray through a pixel's centre ([`OrbitCamera::ray_through_pixel`])
//! against every drawn triangle in world space (brute force, nearest hit; back faces of
//! single-sided materials are culled as on the GPU) and pins the surface point as a triangle
//! and its barycentric coordinates ([`ProbePoint`]). [`ProbeScene::readout`] then interpolates
//! what the vertex shader passes on (position, normal, UV, tangent frame — the frames the
//! renderer draws with: the same [`tangent::resolve`] on the same, possibly unwelded, mesh
//! with the same scene options and material overrides), samples the textures as the GPU's
//! trilinear sampler does (level of detail from the UV footprint of the pixel's 2×2 quad,
//! [`sample_bilinear`] on the mip levels around it) and runs the CPU twin of `shaders/mesh.wgsl`
//! ([`crate::shading`]). The pinned point stays where it is when the camera or light moves;
//! only the readout is recomputed.
//!
//! Spaces and units follow the crate conventions: positions in metres, world space; vectors
//! unit length, world space unless named tangent space; colours linear RGB 0..1 unless named
//! sRGB. The barycentric coordinates of a ray-triangle hit are the perspective-correct ones
//! the rasteriser interpolates with, so the interpolated values equal the GPU's up to float
//! rounding. Screen-space derivatives (texture footprints, the height bump in the shader) come
//! from the values at the four pixel centres of the 2×2 quad holding the point's pixel, found
//! on the triangle's plane as the rasteriser does for the quad. Where the GPU
//! downscaled a texture larger than the adapter allows, the probe differs from the picture.

use glam::{Mat4, Vec2, Vec3, Vec4};

use crate::math::{handedness, linear_to_srgb, normalize_or, orthonormalize_tangent, smoothstep, srgb_to_linear};
use crate::render::{BumpKind, BumpSource, FrameParams, SceneOptions, bump_kind};
use crate::scene::{Mesh, OrbitCamera, SamplerWrap, Scene, ShadingModel, TextureImage, TextureKind, Wrap};
use crate::shading::pbr::{PbrInputs, metallic_roughness};
use crate::shading::{
    LightingInputs, SELF_SHADOW_FADE, ShadingMode, ViewMode, blinn_phong, debug_color, decode_normal, handedness_color,
    object_space_normal, over_tilted,
};
use crate::tangent::{self, TangentMethod};

/// A pinned surface point: a triangle of one instance and barycentric coordinates on it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProbePoint {
    /// Index into [`Scene::instances`].
    pub instance: usize,
    /// Triangle index into the drawn mesh's indices (`3 · triangle ..`); the drawn mesh is the
    /// unwelded one for per-face frames, with the same triangle order.
    pub triangle: usize,
    /// Weights of the triangle's three corners (sum 1).
    pub barycentric: Vec3,
    /// Whether the hit face is a front face (else a back face of a double-sided material).
    pub front_facing: bool,
}

/// Everything along the chain at a probed point. Tangent-space quantities are `None` where the
/// mesh is drawn without tangents; normal-map quantities are `None` without a normal map.
#[derive(Debug, Clone, PartialEq)]
pub struct ProbeReadout {
    pub point: ProbePoint,
    /// Index into [`Scene::meshes`] and [`Scene::materials`].
    pub mesh: usize,
    pub material: usize,
    /// World-space position, metres.
    pub position: Vec3,
    /// Distance from the eye, metres.
    pub distance: f32,
    /// Texture coordinates (crate conventions: origin top-left, v down).
    pub uv: Vec2,
    pub bump: BumpKind,
    /// Whether bump mapping is on (the `B` toggle); off, the shading normal is `normal`.
    pub bump_enabled: bool,
    /// The normal map's texel containing `uv` at mip 0: its integer coordinates and raw bytes
    /// (RGBA, 0–255, before filtering).
    pub texel_xy: Option<[u32; 2]>,
    pub texel_raw: Option<[u8; 4]>,
    /// The normal map's filtered sample at `uv` (RGB, 0..1, linear; at the mip levels the GPU
    /// reads): what the shader decodes.
    pub texel: Option<Vec3>,
    /// The decoded unit vector ([`decode_normal`]): tangent space, or model space for an
    /// object-space map.
    pub decoded: Option<Vec3>,
    /// Effective strength: the viewer's strength times the material's `normalTexture.scale`.
    pub strength: f32,
    /// Tangent-space normal after strength: `normalize(x·s, y·s, max(z, 0))` (tangent-space
    /// maps only).
    pub after_strength: Option<Vec3>,
    /// World-space tangent after Gram-Schmidt against `normal`, bitangent `w · cross(N, T)`,
    /// handedness `w = ±1` (the instance's mirroring included).
    pub tangent: Option<Vec3>,
    pub bitangent: Option<Vec3>,
    pub w: Option<f32>,
    /// The tangent method the frames come from.
    pub tangent_method: Option<TangentMethod>,
    /// Geometric (interpolated vertex) normal, world space, facing the viewer's side on a
    /// double-sided back face.
    pub normal: Vec3,
    /// The normal used for lighting, world space.
    pub shading_normal: Vec3,
    /// Unit directions from the point to the light and the eye, and their half vector.
    pub light_dir: Vec3,
    pub view_dir: Vec3,
    pub half: Vec3,
    /// `N·L` and `N·H` with the shading normal, signed (the shader uses `max(·, 0)`).
    pub n_dot_l: f32,
    pub n_dot_h: f32,
    /// The geometric self-shadow fade `smoothstep(0, SELF_SHADOW_FADE, N_geo·L)`, 0..1.
    pub self_shadow: f32,
    /// Linear albedo: base colour texture (filtered as the GPU does) times the factor.
    pub albedo: Vec3,
    pub shading_model: ShadingModel,
    /// The lit colour in the viewer's shading mode, linear RGB.
    pub color_linear: Vec3,
    /// What the current view stores at this pixel, 0..1 as in the PNG (sRGB-encoded for the
    /// lit picture, `0.5·v + 0.5` for vector views); `None` for the Difference and UV check
    /// views, which the probe does not reproduce.
    pub shown: Option<Vec3>,
}

impl ProbeReadout {
    /// `shown` as 8-bit values (unrounded), as they compare with a rendered PNG.
    pub fn shown_bytes(&self) -> Option<Vec3> {
        self.shown.map(|c| c * 255.0)
    }
}

/// The scene as the renderer draws it, prepared for probing: material overrides applied and
/// the tangent frames made once (re-make it when the scene or the scene options change).
#[derive(Debug, Clone)]
pub struct ProbeScene {
    scene: Scene,
    bump_source: BumpSource,
    /// Per mesh: the geometry drawn (unwelded for per-face frames when drawn with tangents).
    drawn: Vec<Mesh>,
    /// Per mesh: its frames and their method, when drawn with tangents.
    frames: Vec<Option<(Vec<Vec4>, TangentMethod)>>,
    /// Per texture: its mip chain as uploaded ([`TextureImage::mip_chain`]), level 0 first.
    mips: Vec<Vec<TextureImage>>,
}

impl ProbeScene {
    /// Prepares `scene` as [`crate::render::Renderer::set_scene`] with `options` draws it.
    pub fn new(scene: &Scene, options: &SceneOptions) -> ProbeScene {
        let scene = options.materials.applied_with(&options.per_material, scene);
        let bump_source = options.bump_source;
        let mut drawn = vec![];
        let mut frames = vec![];
        for (index, mesh) in scene.meshes.iter().enumerate() {
            let with_tangents = scene.instances.iter().any(|i| {
                i.mesh == index && {
                    let bump = bump_kind(&scene, i.mesh, i.material, bump_source);
                    bump == BumpKind::TangentSpace
                        || (bump == BumpKind::None
                            && mesh.tangents.as_ref().is_some_and(|t| t.len() == mesh.positions.len()))
                }
            });
            if !with_tangents {
                drawn.push(mesh.clone());
                frames.push(None);
                continue;
            }
            let mesh =
                if options.tangent_method == Some(TangentMethod::PerFace) { mesh.unwelded() } else { mesh.clone() };
            frames.push(Some(tangent::resolve(&mesh, options.tangent_method)));
            drawn.push(mesh);
        }
        let mips = scene.textures.iter().map(TextureImage::mip_chain).collect();
        ProbeScene { scene, bump_source, drawn, frames, mips }
    }

    /// The scene with the material overrides applied.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// Number of triangles a pick tests.
    pub fn triangle_count(&self) -> usize {
        self.scene.instances.iter().map(|i| self.drawn[i.mesh].indices.len() / 3).sum()
    }

    /// The nearest drawn surface under the centre of pixel `pixel` (from the top-left) of a
    /// `size` view, or `None` where the ray meets nothing.
    pub fn pick(&self, camera: &OrbitCamera, size: [u32; 2], pixel: [u32; 2]) -> Option<ProbePoint> {
        let centre = Vec2::new(pixel[0] as f32 + 0.5, pixel[1] as f32 + 0.5);
        let (origin, dir) = camera.ray_through_pixel(centre, Vec2::new(size[0] as f32, size[1] as f32));
        let mut best: Option<(f32, ProbePoint)> = None;
        for (instance_index, instance) in self.scene.instances.iter().enumerate() {
            let mesh = &self.drawn[instance.mesh];
            let double_sided = self.scene.materials[instance.material].double_sided;
            let mirror = if instance.transform.determinant() < 0.0 { -1.0 } else { 1.0 };
            for (triangle, corners) in mesh.indices.chunks_exact(3).enumerate() {
                let Some(p) = corner_positions(mesh, corners, &instance.transform) else { continue };
                let Some((t, barycentric)) = intersect(origin, dir, p) else { continue };
                let face = (p[1] - p[0]).cross(p[2] - p[0]) * mirror;
                let front_facing = face.dot(dir) < 0.0;
                if (!front_facing && !double_sided) || best.is_some_and(|(d, _)| d <= t) {
                    continue;
                }
                best = Some((t, ProbePoint { instance: instance_index, triangle, barycentric, front_facing }));
            }
        }
        best.map(|(_, point)| point)
    }

    /// The chain at a pinned point under `params` (camera, light, strength, toggles) in a view
    /// `size` pixels large (the height bump in the shader depends on the pixel grid).
    pub fn readout(&self, point: &ProbePoint, params: &FrameParams, size: [u32; 2]) -> ProbeReadout {
        let instance = &self.scene.instances[point.instance];
        let material = &self.scene.materials[instance.material];
        let mesh = &self.drawn[instance.mesh];
        let corners = &mesh.indices[3 * point.triangle..3 * point.triangle + 3];
        let b = point.barycentric;
        let lerp3 = |values: &[Vec3]| {
            corners.iter().zip(b.to_array()).fold(Vec3::ZERO, |acc, (&i, w)| {
                acc + values.get(i as usize).copied().filter(|v| v.is_finite()).unwrap_or(Vec3::Z) * w
            })
        };
        let model = instance.transform;
        let det = model.determinant();
        let normal_matrix = if det.is_finite() && det != 0.0 { model.inverse().transpose() } else { Mat4::IDENTITY };
        let model_position =
            corners.iter().zip(b.to_array()).fold(Vec3::ZERO, |acc, (&i, w)| acc + mesh.positions[i as usize] * w);
        let position = model.transform_point3(model_position);
        let has_uvs = mesh.uvs.len() == mesh.positions.len();
        let uv = if has_uvs {
            corners.iter().zip(b.to_array()).fold(Vec2::ZERO, |acc, (&i, w)| {
                acc + Some(mesh.uvs[i as usize]).filter(|v| v.is_finite()).unwrap_or(Vec2::ZERO) * w
            })
        } else {
            Vec2::ZERO
        };
        // The pixel's 2×2 quad: texture footprints (mip levels) and the height bump need it.
        let quad = corner_positions(mesh, corners, &model).map(|triangle| Quad {
            camera: &params.camera,
            size,
            triangle,
            position,
        });
        let uv_at = |barycentric: Vec3| {
            corners.iter().zip(barycentric.to_array()).fold(Vec2::ZERO, |acc, (&i, w)| {
                acc + mesh.uvs.get(i as usize).copied().filter(|v| v.is_finite()).unwrap_or(Vec2::ZERO) * w
            })
        };
        let footprint = quad.as_ref().filter(|_| has_uvs).and_then(|q| q.derivatives(|b, _| uv_at(b)));
        let sample = |texture: usize, wrap: SamplerWrap| self.sample(texture, uv, wrap, footprint);
        let normals = if mesh.normals.len() == mesh.positions.len() { &mesh.normals[..] } else { &[] };
        let world_normal = normal_matrix.transform_vector3(lerp3(normals));
        let n = normalize_or(world_normal, Vec3::Z) * if point.front_facing { 1.0 } else { -1.0 };

        let frames = self.frames[instance.mesh].as_ref();
        let frame = frames.map(|(tangents, method)| {
            let t = corners.iter().zip(b.to_array()).fold(Vec4::ZERO, |acc, (&i, w)| acc + tangents[i as usize] * w);
            let world = model.transform_vector3(t.truncate()).extend(t.w * if det < 0.0 { -1.0 } else { 1.0 });
            let tangent = orthonormalize_tangent(world.truncate(), n);
            let w = handedness(world);
            (tangent, w * n.cross(tangent), w, *method)
        });

        let bump = bump_kind(&self.scene, instance.mesh, instance.material, self.bump_source);
        let shading = &params.shading;
        let map =
            material.normal_map.as_ref().filter(|_| matches!(bump, BumpKind::TangentSpace | BumpKind::ObjectSpace));
        let strength = shading.strength * map.map_or(1.0, |m| m.scale);
        let sampled = map.map(|m| {
            let texture = &self.scene.textures[m.texture];
            let texel = sample(m.texture, material.detail_wrap);
            let xy = nearest_texel(texture, uv, material.detail_wrap);
            (xy, texture.texel(xy[0] as i64, xy[1] as i64), texel, decode_normal(texel, m.convention))
        });
        let after_strength = sampled
            .filter(|_| bump == BumpKind::TangentSpace)
            .map(|(_, _, _, d)| normalize_or(Vec3::new(d.x * strength, d.y * strength, d.z.max(0.0)), Vec3::Z));
        let shading_normal = match (shading.bump_enabled, bump, frame, after_strength, sampled, map) {
            (true, BumpKind::TangentSpace, Some((t, bt, _, _)), Some(nt), _, _) => {
                normalize_or(t * nt.x + bt * nt.y + n * nt.z, n)
            }
            (true, BumpKind::ObjectSpace, _, _, Some((_, _, texel, _)), Some(m)) => {
                let matrix = glam::Mat3::from_mat4(normal_matrix);
                object_space_normal(n, matrix, point.front_facing, texel, strength, m.convention)
            }
            (true, BumpKind::HeightInShader, ..) => {
                let (Some(map), Some(quad)) = (material.height_map.as_ref(), quad.as_ref()) else {
                    unreachable!("a height-in-shader bump has a height map; the pick hit finite corners")
                };
                // Every pixel of the quad samples at the quad's footprint, as the GPU does.
                let height_at = |barycentric: Vec3| {
                    let texel = self.sample(map.texture, uv_at(barycentric), material.detail_wrap, footprint);
                    let sample = (texel.x * 65280.0 + texel.y * 255.0) / 65535.0;
                    let sample = if map.depth { 1.0 - sample } else { sample };
                    sample * map.range_m * shading.strength
                };
                height_bump_normal(quad, n, height_at)
            }
            _ => n,
        };

        let eye = params.camera.eye();
        let light_dir = normalize_or(params.light.position - position, n);
        let view_dir = normalize_or(eye - position, n);
        let half = normalize_or(light_dir + view_dir, n);
        let base = material.base_color_texture.map_or(Vec3::ONE, |t| sample(t, material.base_color_wrap));
        let albedo = base * material.base_color_factor.truncate();
        let shading_model = shading.shading_override.unwrap_or(material.shading_model);
        let lit_albedo = if shading.mode == ShadingMode::BumpOnly { Vec3::ONE } else { albedo };
        let color_linear = match (shading.mode, shading_model) {
            (ShadingMode::ColourOnly, _) => albedo,
            (_, ShadingModel::BlinnPhong) => blinn_phong(&LightingInputs {
                albedo: lit_albedo,
                geometric_normal: n,
                shading_normal,
                position,
                eye,
                light: params.light,
                ambient: self.scene.ambient,
                specular: material.specular
                    * material.gloss_texture.map_or(Vec3::ONE, |t| sample(t, material.detail_wrap)),
                shininess: material.shininess.max(1.0),
            }),
            (_, ShadingModel::MetallicRoughness) => {
                let detail = |t: usize| sample(t, material.detail_wrap);
                let metal_rough = material.metallic_roughness_texture.map_or(Vec3::ONE, detail);
                let occlusion =
                    material.occlusion.as_ref().map_or(1.0, |o| 1.0 + o.strength * (detail(o.texture).x - 1.0));
                metallic_roughness(&PbrInputs {
                    base_color: lit_albedo,
                    metallic: material.metallic * metal_rough.z,
                    roughness: material.roughness * metal_rough.y,
                    occlusion,
                    geometric_normal: n,
                    shading_normal,
                    position,
                    eye,
                    light: params.light,
                })
            }
        };
        let lit = color_linear.map(linear_to_srgb);
        let zero = Vec3::ZERO;
        let shown = match shading.view {
            ViewMode::Lit => Some(lit),
            ViewMode::OverTilt if over_tilted(n, shading_normal) => Some(crate::shading::OVER_TILT_COLOR),
            ViewMode::OverTilt => Some(lit),
            ViewMode::Tangent => Some(debug_color(frame.map_or(zero, |f| f.0))),
            ViewMode::Bitangent => Some(debug_color(frame.map_or(zero, |f| f.1))),
            ViewMode::Normal => Some(debug_color(n)),
            ViewMode::ShadingNormal => Some(debug_color(shading_normal)),
            ViewMode::Handedness => Some(handedness_color(frame.map(|f| f.2), n, eye - position)),
            ViewMode::Difference | ViewMode::UvCheck => None,
        };
        ProbeReadout {
            point: *point,
            mesh: instance.mesh,
            material: instance.material,
            position,
            distance: (eye - position).length(),
            uv,
            bump,
            bump_enabled: shading.bump_enabled,
            texel_xy: sampled.map(|s| s.0),
            texel_raw: sampled.map(|s| s.1),
            texel: sampled.map(|s| s.2),
            decoded: sampled.map(|s| s.3),
            strength,
            after_strength,
            tangent: frame.map(|f| f.0),
            bitangent: frame.map(|f| f.1),
            w: frame.map(|f| f.2),
            tangent_method: frame.map(|f| f.3),
            normal: n,
            shading_normal,
            light_dir,
            view_dir,
            half,
            n_dot_l: shading_normal.dot(light_dir),
            n_dot_h: shading_normal.dot(half),
            self_shadow: smoothstep(0.0, SELF_SHADOW_FADE, n.dot(light_dir)),
            albedo,
            shading_model,
            color_linear,
            shown,
        }
    }

    /// Texture `index` at `uv` as the GPU's sampler reads it (linear filtering, linear between
    /// mip levels, no anisotropy): level of detail `log2` of the longer of the footprint's
    /// derivatives in texels (`footprint`: d(uv)/dx and d(uv)/dy per pixel; `None`: level 0),
    /// bilinear at level 0 when magnified, else between the two levels around it.
    fn sample(&self, index: usize, uv: Vec2, wrap: SamplerWrap, footprint: Option<(Vec2, Vec2)>) -> Vec3 {
        let chain = &self.mips[index];
        let texels = Vec2::new(chain[0].width as f32, chain[0].height as f32);
        let lod = footprint.map_or(0.0, |(dx, dy)| (dx * texels).length().max((dy * texels).length()).log2());
        let lod = if lod.is_finite() { lod.clamp(0.0, (chain.len() - 1) as f32) } else { 0.0 };
        let level = lod.floor() as usize;
        let fine = sample_bilinear(&chain[level], uv, wrap);
        match chain.get(level + 1) {
            Some(coarse) if lod > level as f32 => fine.lerp(sample_bilinear(coarse, uv, wrap), lod - level as f32),
            _ => fine,
        }
    }

    /// [`Self::pick`] then [`Self::readout`] with `params`' camera.
    pub fn probe(&self, params: &FrameParams, size: [u32; 2], pixel: [u32; 2]) -> Option<ProbeReadout> {
        self.pick(&params.camera, size, pixel).map(|point| self.readout(&point, params, size))
    }
}

/// A surface point's triangle seen in a view: what the rasteriser's 2×2 pixel quad around it
/// interpolates over.
struct Quad<'a> {
    camera: &'a OrbitCamera,
    size: [u32; 2],
    /// The triangle's corners, world space.
    triangle: [Vec3; 3],
    /// The point, world space.
    position: Vec3,
}

impl Quad<'_> {
    /// Barycentric coordinates (unbounded: helper pixels lie off the triangle) and position
    /// where the ray through the centre of pixel `(x, y)` meets the triangle's plane.
    fn on_plane(&self, x: i64, y: i64) -> Option<(Vec3, Vec3)> {
        let centre = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
        let (origin, dir) = self.camera.ray_through_pixel(centre, Vec2::new(self.size[0] as f32, self.size[1] as f32));
        meet_plane(origin, dir, self.triangle).map(|(t, barycentric)| (barycentric, origin + dir * t))
    }

    /// Fine screen-space derivatives of `value(barycentric, position)` at the point's pixel, as
    /// lavapipe takes them: differences across its 2×2 quad along the pixel's own row
    /// (`d/dx`) and column (`d/dy`). `None` where the view sees the plane edge-on.
    fn derivatives<T: std::ops::Sub<Output = T> + Copy>(&self, value: impl Fn(Vec3, Vec3) -> T) -> Option<(T, T)> {
        let pixel = project_to_pixel(self.camera, self.size, self.position)?;
        let (x, y) = (pixel.x.floor() as i64, pixel.y.floor() as i64);
        let (x0, y0) = (x & !1, y & !1);
        let at = |x, y| self.on_plane(x, y).map(|(b, p)| value(b, p));
        Some((at(x0 + 1, y)? - at(x0, y)?, at(x, y0 + 1)? - at(x, y0)?))
    }
}

/// The shading normal `fs_height_bump` makes from the height map: Mikkelsen's surface gradient
/// from screen-space derivatives of the position and of `height_at(barycentric)` (metres).
/// Falls back on `n` where the view sees the plane edge-on.
fn height_bump_normal(quad: &Quad, n: Vec3, height_at: impl Fn(Vec3) -> f32) -> Vec3 {
    let Some((dx, dy)) = quad.derivatives(|b, p| p.extend(height_at(b))) else { return n };
    let (dp_dx, dh_dx, dp_dy, dh_dy) = (dx.truncate(), dx.w, dy.truncate(), dy.w);
    let r1 = dp_dy.cross(n);
    let r2 = n.cross(dp_dx);
    let det = dp_dx.dot(r1);
    let sign = if det > 0.0 {
        1.0
    } else if det < 0.0 {
        -1.0
    } else {
        0.0
    };
    let surface_gradient = sign * (dh_dx * r1 + dh_dy * r2);
    normalize_or(det.abs() * n - surface_gradient, n)
}

/// Where a world-space point appears in a `size` view: pixels from the top-left (`None` behind
/// the eye).
pub fn project_to_pixel(camera: &OrbitCamera, size: [u32; 2], world: Vec3) -> Option<Vec2> {
    let clip = camera.view_projection(size[0] as f32 / size[1] as f32) * world.extend(1.0);
    (clip.w > 0.0).then(|| {
        let ndc = clip.truncate() / clip.w;
        Vec2::new((ndc.x + 1.0) * 0.5 * size[0] as f32, (1.0 - ndc.y) * 0.5 * size[1] as f32)
    })
}

/// A triangle's corners in world space, or `None` when an index is out of range or a position
/// is not finite (the renderer drops such triangles).
fn corner_positions(mesh: &Mesh, corners: &[u32], model: &Mat4) -> Option<[Vec3; 3]> {
    let mut p = [Vec3::ZERO; 3];
    for (out, &i) in p.iter_mut().zip(corners) {
        let position = mesh.positions.get(i as usize).filter(|p| p.is_finite())?;
        *out = model.transform_point3(*position);
    }
    Some(p)
}

/// Möller–Trumbore, both faces: the distance along `dir` (unit) and the barycentric weights
/// of the hit inside the triangle, in front of `origin`.
fn intersect(origin: Vec3, dir: Vec3, p: [Vec3; 3]) -> Option<(f32, Vec3)> {
    let (t, barycentric) = meet_plane(origin, dir, p)?;
    let [_, u, v] = barycentric.to_array();
    let inside = (0.0..=1.0).contains(&u) && v >= 0.0 && u + v <= 1.0;
    (inside && t > 0.0).then_some((t, barycentric))
}

/// Where the ray meets the plane of triangle `p` (either side, behind `origin` too): the
/// signed distance along `dir` and the barycentric weights, unbounded off the triangle.
/// `None` for a ray parallel to the plane.
fn meet_plane(origin: Vec3, dir: Vec3, p: [Vec3; 3]) -> Option<(f32, Vec3)> {
    let (e1, e2) = (p[1] - p[0], p[2] - p[0]);
    let h = dir.cross(e2);
    let a = e1.dot(h);
    if a.is_nan() || a.abs() < 1e-12 {
        return None;
    }
    let f = 1.0 / a;
    let s = origin - p[0];
    let q = s.cross(e1);
    let (u, v, t) = (f * s.dot(h), f * dir.dot(q), f * e2.dot(q));
    let barycentric = Vec3::new(1.0 - u - v, u, v);
    (t.is_finite() && barycentric.is_finite()).then_some((t, barycentric))
}

/// Integer texel coordinate `i` of a `size`-texel axis under a wrap mode.
fn wrap_texel(i: i64, size: u32, wrap: Wrap) -> i64 {
    let n = size.max(1) as i64;
    match wrap {
        Wrap::Repeat => i.rem_euclid(n),
        Wrap::ClampToEdge => i.clamp(0, n - 1),
        Wrap::MirroredRepeat => {
            let m = i.rem_euclid(2 * n);
            if m < n { m } else { 2 * n - 1 - m }
        }
    }
}

/// The texel of mip level 0 that contains `uv` (nearest filtering), after wrapping.
pub fn nearest_texel(texture: &TextureImage, uv: Vec2, wrap: SamplerWrap) -> [u32; 2] {
    let x = (uv.x * texture.width as f32).floor() as i64;
    let y = (uv.y * texture.height as f32).floor() as i64;
    [wrap_texel(x, texture.width, wrap.u) as u32, wrap_texel(y, texture.height, wrap.v) as u32]
}

/// Bilinear sample of mip level 0 (RGB, 0..1), as the GPU's linear magnification filter reads
/// it with the given wrap modes; sRGB colour texels are decoded to linear before filtering, as
/// through an sRGB texture view.
pub fn sample_bilinear(texture: &TextureImage, uv: Vec2, wrap: SamplerWrap) -> Vec3 {
    let x = uv.x * texture.width as f32 - 0.5;
    let y = uv.y * texture.height as f32 - 0.5;
    let (x0, y0) = (x.floor(), y.floor());
    let (fx, fy) = (x - x0, y - y0);
    let texel = |dx: i64, dy: i64| {
        let tx = wrap_texel(x0 as i64 + dx, texture.width, wrap.u);
        let ty = wrap_texel(y0 as i64 + dy, texture.height, wrap.v);
        let t = texture.texel(tx, ty);
        let rgb = Vec3::new(t[0] as f32, t[1] as f32, t[2] as f32) / 255.0;
        match texture.kind {
            TextureKind::Color => rgb.map(srgb_to_linear),
            TextureKind::NormalMap | TextureKind::Height | TextureKind::Data => rgb,
        }
    };
    let top = texel(0, 0).lerp(texel(1, 0), fx);
    let bottom = texel(0, 1).lerp(texel(1, 1), fx);
    top.lerp(bottom, fy)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ray_hits_a_triangle_with_its_barycentrics_and_misses_beside_it() {
        let p = [Vec3::ZERO, Vec3::X, Vec3::Y];
        let (t, b) = intersect(Vec3::new(0.25, 0.25, 2.0), -Vec3::Z, p).unwrap();
        assert!((t - 2.0).abs() < 1e-6 && (b - Vec3::new(0.5, 0.25, 0.25)).length() < 1e-6, "{t} {b}");
        assert!(intersect(Vec3::new(0.75, 0.75, 2.0), -Vec3::Z, p).is_none());
        assert!(intersect(Vec3::new(0.25, 0.25, 2.0), Vec3::Z, p).is_none(), "behind the origin");
    }

    #[test]
    fn wrap_modes_fold_texel_indices() {
        assert_eq!([-1, 0, 4, 5].map(|i| wrap_texel(i, 4, Wrap::Repeat)), [3, 0, 0, 1]);
        assert_eq!([-1, 0, 4, 5].map(|i| wrap_texel(i, 4, Wrap::ClampToEdge)), [0, 0, 3, 3]);
        assert_eq!([-1, 0, 4, 5, 8].map(|i| wrap_texel(i, 4, Wrap::MirroredRepeat)), [0, 0, 3, 2, 0]);
    }
}
