//! What a frame shows, as plain types: the frame parameters (camera, light, the cheap shading
//! toggles), the scene options that decide GPU data (tangent method, bump source, material
//! overrides), the views and lit modes with their labels, and the one function that decides
//! how an instance is bumped ([`bump_kind`]). Everything above this layer — the prepare
//! stage, the GPU renderer, the CPU probe, the viewer state — describes a picture with these.

mod lighting;
mod looks;

pub use crate::texture::MipFilter;
pub use lighting::LightingSpace;
pub use looks::{CUBE_MAP_SIZES, LegacyLook, LegacySettings, Mistake};

use crate::names::Named;
use crate::scene::{
    Lights, MaterialOverrides, NormalSpace, OrbitCamera, PerMaterialOverrides, Scene, ShadingModel, SpecularMode,
};
use crate::tangent::TangentMethod;

/// The bump strength's range (the slider's; typed values outside it are clamped).
pub const STRENGTH_RANGE: std::ops::RangeInclusive<f32> = -2.0..=4.0;

/// What the view shows. Debug views show a world-space unit vector `v` as `0.5·v + 0.5`.
/// Named ([`crate::names::Named`]) as on the command line and in presets: `lit`,
/// `shading-normal`, `uv-check`, ….
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, strum::IntoStaticStr, strum::VariantArray)]
#[strum(serialize_all = "kebab-case")]
pub enum ViewMode {
    /// Blinn-Phong shading.
    #[default]
    Lit,
    /// The tangent `T` after Gram-Schmidt against the geometric normal.
    Tangent,
    /// The bitangent `B = w · cross(N, T)`.
    Bitangent,
    /// The geometric (interpolated vertex) normal.
    Normal,
    /// The normal after the normal map and bump strength.
    ShadingNormal,
    /// Angle between the mesh's tangent frame and the reference frame (analytic where the
    /// mesh has one, else MikkTSpace), on the [`difference_color`] scale.
    Difference,
    /// Triangles whose UVs have no area (red) or are mirrored (blue), as `bumpview check`
    /// counts them, from screen-space derivatives.
    UvCheck,
    /// Tangent handedness `w`: green where +1, magenta where −1 (mirrored UV islands), grey
    /// where the mesh is drawn without tangents ([`handedness_color`]).
    Handedness,
    /// The lit picture with pixels in [`OVER_TILT_COLOR`] where the shading normal tilts
    /// past [`OVER_TILT_LIMIT_DEG`] from the geometric normal ([`over_tilted`]).
    OverTilt,
    /// The clear-coat layer's normal (`KHR_materials_clearcoat`, after its normal map) where
    /// a material has a clear coat, else the geometric normal.
    ClearcoatNormal,
}

impl ViewMode {
    /// A view's name for people (labels and captions).
    pub fn label(self) -> &'static str {
        match self {
            ViewMode::Lit => "Lit",
            ViewMode::Tangent => "Tangent",
            ViewMode::Bitangent => "Bitangent",
            ViewMode::Normal => "Normal",
            ViewMode::ShadingNormal => "Shading normal",
            ViewMode::Difference => "Difference",
            ViewMode::UvCheck => "UV check",
            ViewMode::Handedness => "Handedness",
            ViewMode::OverTilt => "Over-tilt",
            ViewMode::ClearcoatNormal => "Clear-coat normal",
        }
    }

    /// The next mode in declaration order ([`Named::all`]), wrapping around.
    pub fn next(self) -> ViewMode {
        let all = ViewMode::all();
        let i = all.iter().position(|&m| m == self).unwrap_or(0);
        all[(i + 1) % all.len()]
    }

    /// The index the mesh shader's `VIEW` pipeline constant takes.
    pub fn shader_index(self) -> u32 {
        self as u32
    }

    /// Whether the view shows the lit picture (Lit, Over-tilt), so its pipeline depends on
    /// the shading model.
    pub fn is_lit(self) -> bool {
        matches!(self, ViewMode::Lit | ViewMode::OverTilt)
    }
}

/// What the lit picture is made of, as in the classic demos (keys 1/2/3). A uniform. Named
/// `bump-colour`, `bump-only`, `colour-only`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, strum::IntoStaticStr, strum::VariantArray)]
#[strum(serialize_all = "kebab-case")]
pub enum ShadingMode {
    /// Lighting with the (bumped) shading normal times the colour texture.
    #[default]
    #[strum(serialize = "bump-colour")]
    BumpTimesColour,
    /// Lighting with the shading normal and a white albedo: the relief alone.
    BumpOnly,
    /// The albedo as stored (colour texture × factor): no bump, no lighting.
    ColourOnly,
}

impl ShadingMode {
    /// A lit-picture mode's name for people (labels and captions).
    pub fn label(self) -> &'static str {
        match self {
            ShadingMode::BumpTimesColour => "bump × colour",
            ShadingMode::BumpOnly => "bump only",
            ShadingMode::ColourOnly => "colour only",
        }
    }

    /// The index the shader switches on (`frame.shading_mode`).
    pub fn shader_index(self) -> u32 {
        self as u32
    }
}

/// The toggles that keep the scene's GPU data: uniforms, except the view, the shading model,
/// the parallax technique, the mistake and the legacy look, which pick pipeline variants (each
/// built on first use, then cached). Two of them bring GPU data of their own: emboss binds the
/// height maps ([`SceneOptions::parallax`]) and no Gram-Schmidt uploads other frames
/// ([`SceneOptions::tangents_without_gram_schmidt`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShadingSettings {
    pub bump_enabled: bool,
    /// Bump strength `s`, glTF `normalTexture.scale` semantics, multiplied with the
    /// material's own scale. 0 is flat, negative inverts.
    pub strength: f32,
    /// A pipeline variant: each pipeline draws one view.
    pub view: ViewMode,
    pub show_light_marker: bool,
    /// The Difference view's colour scale spans 0 to this many degrees.
    pub difference_range_deg: f32,
    /// Shade every material with this model (`None`: each material's own). A pipeline
    /// variant in the lit views.
    pub shading_override: Option<ShadingModel>,
    /// Bump × colour, bump only or colour only (a uniform).
    pub mode: ShadingMode,
    /// Draw the triangle edges over the picture (a second pass; needs
    /// `wgpu::Features::POLYGON_MODE_LINE`, else it is skipped with a notice).
    pub wireframe: bool,
    /// Draw T/B/N glyphs (red, green, blue lines) at vertices of meshes with tangent frames,
    /// thinned on dense meshes (a line pass).
    pub tbn_glyphs: bool,
    /// Parallax mapping of normal-mapped surfaces with a height map: the technique picks a
    /// pipeline variant, layers, steps and depth are uniforms.
    pub parallax: ParallaxSettings,
    /// Draw with one classic mistake (a pipeline variant).
    pub mistake: Mistake,
    /// A legacy look instead of today's lighting in the lit views (a pipeline variant).
    pub legacy: LegacySettings,
    /// The classic model's highlight: Blinn, Phong or none (a uniform).
    pub specular: SpecularMode,
    /// The classic model's shininess exponent for every material (`None`: each material's
    /// own); at least 1 (a uniform).
    pub shininess: Option<f32>,
    /// Where the lit views light tangent-space normal-mapped surfaces (a pipeline variant).
    pub lighting_space: LightingSpace,
}

impl Default for ShadingSettings {
    fn default() -> Self {
        ShadingSettings {
            bump_enabled: true,
            strength: 1.0,
            view: ViewMode::Lit,
            show_light_marker: true,
            difference_range_deg: 5.0,
            shading_override: None,
            mode: ShadingMode::BumpTimesColour,
            wireframe: false,
            tbn_glyphs: false,
            parallax: ParallaxSettings::default(),
            mistake: Mistake::None,
            legacy: LegacySettings::default(),
            specular: SpecularMode::Blinn,
            shininess: None,
            lighting_space: LightingSpace::World,
        }
    }
}

/// How texture coordinates are shifted by the material's height map before the normal map and
/// the colour are read (the parallax family). The reference plane is the mesh surface, the
/// top of the relief: a texel of height `h` (0..1, white = high; `1 − sample` for a depth map)
/// lies `(1 − h) · depth` metres below it. A uniform. Named `off`, `offset`, `offset-limited`,
/// `steep`, `occlusion`, `relief`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, strum::IntoStaticStr, strum::VariantArray)]
#[strum(serialize_all = "kebab-case")]
pub enum Parallax {
    /// No shift: plain normal mapping.
    #[default]
    Off,
    /// Kaneko et al. 2001, "Detailed shape representation with parallax mapping": one height
    /// sample at the pixel's UV, shifted along the view ray to that depth (`÷ N·V`).
    Offset,
    /// Welsh 2004, "Parallax mapping with offset limiting": as [`Parallax::Offset`] without
    /// the `÷ N·V`, so the shift never exceeds the depth at grazing views.
    OffsetLimited,
    /// McGuire & McGuire 2005, "Steep parallax mapping": a linear search along the view ray
    /// through equally spaced depth layers; the first layer below the relief.
    Steep,
    /// Tatarchuk 2006, "Dynamic parallax occlusion mapping with approximate soft shadows": the
    /// linear search, then the ray's intersection with the straight line between the heights
    /// of the last two layers.
    Occlusion,
    /// Policarpo, Oliveira & Comba 2005, "Real-time relief mapping on arbitrary polygonal
    /// surfaces": the linear search, then binary-search steps between the last two layers.
    Relief,
}

impl Parallax {
    /// A technique's name for people (labels and captions).
    pub fn label(self) -> &'static str {
        match self {
            Parallax::Off => "no parallax",
            Parallax::Offset => "parallax offset",
            Parallax::OffsetLimited => "offset limiting",
            Parallax::Steep => "steep parallax",
            Parallax::Occlusion => "parallax occlusion",
            Parallax::Relief => "relief mapping",
        }
    }

    /// The index the `PARALLAX` pipeline constant takes (shaders/parallax.wgsl).
    pub fn shader_index(self) -> u32 {
        self as u32
    }

    /// Whether the technique searches through layers (steep, occlusion, relief).
    pub fn marches(self) -> bool {
        matches!(self, Parallax::Steep | Parallax::Occlusion | Parallax::Relief)
    }
}

/// The most layers a search takes, and the most binary-search steps of relief mapping: the
/// bounds of the shader's loops.
pub const MAX_PARALLAX_LAYERS: u32 = 256;
pub const MAX_PARALLAX_STEPS: u32 = 16;

/// The parallax technique and its settings (uniforms).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParallaxSettings {
    pub technique: Parallax,
    /// Layers of the linear search: `max` seen face-on, `min` at grazing views, linear in
    /// `N·V` between (Tatarchuk 2006); each clamped to 1..=[`MAX_PARALLAX_LAYERS`]. Equal
    /// values give a fixed count.
    pub layers_min: u32,
    pub layers_max: u32,
    /// Binary-search steps of relief mapping, 0..=[`MAX_PARALLAX_STEPS`].
    pub steps: u32,
    /// The relief's depth, metres: `None` takes each material's height range
    /// ([`crate::scene::HeightMap::range_m`]). 0 is plain normal mapping.
    pub depth_m: Option<f32>,
    /// Soft self-shadowing of the searches (Tatarchuk 2006): how dark the relief's own
    /// shadows are, 0 (off) to [`MAX_PARALLAX_SHADOW_STRENGTH`]; a uniform.
    pub shadow_strength: f32,
}

/// The strongest parallax self-shadowing (4 darkens fully where a blocker rises a 32nd of the
/// depth above the light ray next to the point).
pub const MAX_PARALLAX_SHADOW_STRENGTH: f32 = 4.0;

impl Default for ParallaxSettings {
    fn default() -> Self {
        ParallaxSettings {
            technique: Parallax::Off,
            layers_min: 8,
            layers_max: 32,
            steps: 5,
            depth_m: None,
            shadow_strength: 0.0,
        }
    }
}

impl ParallaxSettings {
    /// The layer count at `n_dot_v` (`N·V`, 0 grazing .. 1 face-on): Tatarchuk's
    /// `⌊max + (min − max) · N·V + ½⌋`, within [`Self::layer_range`].
    pub fn layers(&self, n_dot_v: f32) -> u32 {
        let (low, high) = self.layer_range();
        let t = if n_dot_v.is_finite() { n_dot_v.clamp(0.0, 1.0) } else { 0.0 };
        (high as f32 + (low as f32 - high as f32) * t + 0.5).floor() as u32
    }

    /// `(min, max)` clamped to 1..=[`MAX_PARALLAX_LAYERS`], `min ≤ max`.
    pub fn layer_range(&self) -> (u32, u32) {
        let clamp = |n: u32| n.clamp(1, MAX_PARALLAX_LAYERS);
        let (a, b) = (clamp(self.layers_min), clamp(self.layers_max));
        (a.min(b), a.max(b))
    }

    /// A caption: the technique and, for searches, its layers (and relief's steps, and the
    /// shadows when on).
    pub fn caption(&self) -> String {
        let (low, high) = self.layer_range();
        let layers = if low == high { format!("{high} layers") } else { format!("{low}–{high} layers") };
        let shadows = if self.shadows_on() { ", shadows" } else { "" };
        match self.technique {
            Parallax::Off | Parallax::Offset | Parallax::OffsetLimited => self.technique.label().to_owned(),
            Parallax::Steep | Parallax::Occlusion => format!("{}, {layers}{shadows}", self.technique.label()),
            Parallax::Relief => format!("{}, {layers} + {} steps{shadows}", self.technique.label(), self.steps),
        }
    }

    /// Whether the searches cast soft self-shadows (a strength above 0).
    pub fn shadows_on(&self) -> bool {
        self.shadow_strength > 0.0 && self.shadow_strength.is_finite()
    }
}

/// The most tessellation levels of [`Displacement`]: each triangle becomes at most
/// `4^MAX_DISPLACEMENT_LEVEL` triangles (the prepare stage lowers the level further when a
/// scene would exceed [`MAX_DISPLACED_TRIANGLES`]).
pub const MAX_DISPLACEMENT_LEVEL: u32 = 10;
/// The most triangles a displaced scene draws (about 48 bytes per vertex, 12 per triangle).
pub const MAX_DISPLACED_TRIANGLES: usize = 8 << 20;

/// Displacement mapping, the parallax family's ground truth: every instance whose material
/// has a height map (and whose mesh has texture coordinates) is tessellated on the CPU, each
/// triangle's edges cut into `2^level` segments, and each vertex moved along its normal by
/// `(h − 1) · depth` — the same convention as [`Parallax`]: the mesh surface is the top of the
/// relief, a texel of height `h` lies `(1 − h) · depth` metres below it. It is shaded with the
/// displaced surface's normals instead of the normal map. A scene option: it makes geometry.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Displacement {
    /// Tessellation level, 0 (off) to [`MAX_DISPLACEMENT_LEVEL`]: `4^level` triangles per
    /// triangle.
    pub level: u32,
    /// The relief's depth, metres: `None` takes each material's height range. The viewer
    /// sets it from [`ParallaxSettings::depth_m`] so both mean the same relief.
    pub depth_m: Option<f32>,
}

impl Displacement {
    /// Whether meshes are displaced.
    pub fn is_on(&self) -> bool {
        self.level > 0
    }

    /// A caption: `displacement, level L` or `no displacement`.
    pub fn caption(&self) -> String {
        if self.is_on() { format!("displacement, level {}", self.level) } else { "no displacement".to_owned() }
    }
}

/// Everything that decides one picture, besides the scene and the target size.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameParams {
    pub camera: OrbitCamera,
    /// The lights and the ambient light.
    pub lights: Lights,
    pub shading: ShadingSettings,
}

/// The split view's two pictures: the same camera and lights, `left` shading left of the
/// divider and `right` shading right of it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SplitFrame {
    pub left: ShadingSettings,
    pub right: ShadingSettings,
    /// Where the divider is, as a fraction of the width (0 left edge, 1 right edge).
    pub divider: f32,
}

impl SplitFrame {
    /// The divider's column in a target `width` pixels wide: the first column of the right half.
    pub fn divider_pixels(&self, width: u32) -> u32 {
        let fraction = if self.divider.is_finite() { self.divider.clamp(0.0, 1.0) } else { 0.5 };
        ((fraction * width as f32).round() as u32).min(width)
    }
}

/// Multisampling of a frame: full quality or the cheaper interactive frames.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub enum Msaa {
    /// 4 samples per pixel where the adapter can render and resolve them in the target's
    /// format, else 1: screenshots, exports and the frame shown once input stops.
    #[default]
    X4,
    /// 1 sample per pixel: frames drawn while the user drags or a light orbits.
    Off,
}

/// How much a frame may cost: its multisampling and the share of the view's pixels drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FrameQuality {
    pub msaa: Msaa,
    /// Pixels drawn per view pixel along each side, in (0, 1]: 0.5 draws a quarter of the
    /// pixels, shown enlarged. 1 draws every pixel.
    pub render_scale: f32,
}

impl FrameQuality {
    /// Every pixel with 4× MSAA: what screenshots and exports are drawn with.
    pub const FULL: FrameQuality = FrameQuality { msaa: Msaa::X4, render_scale: 1.0 };

    /// The size in pixels to draw a view of `view_size` pixels at: each side times
    /// [`Self::render_scale`], rounded, at least 1 and at most the side (a non-finite or
    /// non-positive scale draws every pixel).
    pub fn render_size(&self, view_size: [u32; 2]) -> [u32; 2] {
        let scale =
            if self.render_scale.is_finite() && self.render_scale > 0.0 { self.render_scale.min(1.0) } else { 1.0 };
        view_size.map(|side| ((side as f32 * scale).round() as u32).max(1).min(side))
    }
}

impl Default for FrameQuality {
    fn default() -> Self {
        FrameQuality::FULL
    }
}

/// Where the bump comes from. It decides pipelines and uploads, so it is a scene option, not
/// a uniform. Named `normal-map`, `height-in-shader`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, strum::IntoStaticStr, strum::VariantArray)]
#[strum(serialize_all = "kebab-case")]
pub enum BumpSource {
    /// The material's normal map (the built-in one is made from its height field by a kernel).
    #[default]
    NormalMap,
    /// Blinn's bump from the material's height map, differentiated in screen space in the
    /// shader (Mikkelsen's surface gradient): no tangents needed.
    HeightInShader,
}

impl BumpSource {
    /// A bump source's name for people (labels and captions).
    pub fn label(self) -> &'static str {
        match self {
            BumpSource::NormalMap => "normal map",
            BumpSource::HeightInShader => "height in shader",
        }
    }
}

/// How an instance's surface is bumped: decided by its material, whether its mesh has texture
/// coordinates, and the bump source. The renderer picks its pipeline variant by it and the
/// probe reproduces the same chain.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BumpKind {
    /// No bump map (or no texture coordinates): the geometric normal shades.
    None,
    /// Tangent-space normal map through T, B, N.
    TangentSpace,
    /// Object-space normal map through the normal matrix (no tangents).
    ObjectSpace,
    /// Blinn's bump from the height map by screen-space derivatives (no tangents).
    HeightInShader,
}

/// The [`BumpKind`] of an instance drawing `scene.meshes[mesh]` with `scene.materials[material]`.
pub fn bump_kind(scene: &Scene, mesh: usize, material: usize, bump_source: BumpSource) -> BumpKind {
    let mesh = &scene.meshes[mesh];
    let material = &scene.materials[material];
    let has_uvs = mesh.uvs.len() == mesh.positions.len();
    if bump_source == BumpSource::HeightInShader && material.height_map.is_some() && has_uvs {
        BumpKind::HeightInShader
    } else if let Some(map) = material.normal_map.as_ref().filter(|_| has_uvs) {
        match map.convention.space {
            NormalSpace::Tangent => BumpKind::TangentSpace,
            NormalSpace::Object => BumpKind::ObjectSpace,
        }
    } else {
        BumpKind::None
    }
}

/// How a scene is prepared for drawing: changing these re-makes GPU data.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SceneOptions {
    /// Tangent frames by this method; `None`: the mesh's own, else MikkTSpace (by meshoptimizer).
    pub tangent_method: Option<TangentMethod>,
    pub bump_source: BumpSource,
    /// Normal- and height-map conventions that replace every material's own.
    pub materials: MaterialOverrides,
    /// Per material (index into the scene's materials): conventions that win over
    /// `materials` field by field.
    pub per_material: PerMaterialOverrides,
    /// Bind each normal-mapped material's height map for the parallax family and the emboss
    /// look: on while a technique or emboss is chosen (`ViewerState::scene_uploads` sets it),
    /// so the height maps are uploaded only then.
    pub parallax: bool,
    /// Displaced geometry instead of the normal map where a material has a height map.
    pub displacement: Displacement,
    /// Draw averaged and supplied tangent frames without Gram-Schmidt against the vertex
    /// normal ([`crate::tangent::without_gram_schmidt`]): on while a picture shows
    /// [`Mistake::NoGramSchmidt`] (`ViewerState::scene_uploads` sets it).
    pub tangents_without_gram_schmidt: bool,
    /// How every material's normal map is mip-filtered ([`MipFilter`]): it decides the mip
    /// chain baked and uploaded, and the pipeline variant (`MIP_FILTER`).
    pub mip_filter: MipFilter,
}

impl SceneOptions {
    /// The overrides edited for `material` (`None`: the viewer-wide ones), not merged.
    pub fn overrides(&self, material: Option<usize>) -> MaterialOverrides {
        match material {
            None => self.materials,
            Some(index) => self.per_material.get(&index).copied().unwrap_or_default(),
        }
    }

    /// Replaces the overrides of `material` (`None`: the viewer-wide ones); an empty
    /// per-material record is dropped.
    pub fn set_overrides(&mut self, material: Option<usize>, overrides: MaterialOverrides) {
        match material {
            None => self.materials = overrides,
            Some(index) if overrides.is_empty() => {
                self.per_material.remove(&index);
            }
            Some(index) => {
                self.per_material.insert(index, overrides);
            }
        }
    }

    /// What material `index` is drawn with: its own overrides over the viewer-wide ones.
    pub fn overrides_in_use(&self, index: usize) -> MaterialOverrides {
        self.materials.for_material(&self.per_material, index)
    }

    /// The mip filter material `index`'s normal map is made and drawn with: its overrides'
    /// ([`MaterialOverrides::mip_filter`]) where set, else [`Self::mip_filter`].
    pub fn mip_filter_of(&self, index: usize) -> MipFilter {
        self.overrides_in_use(index).mip_filter.unwrap_or(self.mip_filter)
    }
}

/// The scene options the GPU data must be made with: `main` for the picture (and the split
/// view's left half), `split_right` for the split view's right half when it needs its own upload.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SceneUploads {
    pub main: SceneOptions,
    pub split_right: Option<SceneOptions>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn render_size_scales_each_side_and_keeps_at_least_a_pixel() {
        let half = FrameQuality { msaa: Msaa::Off, render_scale: 0.5 };
        assert_eq!(half.render_size([1280, 720]), [640, 360]);
        assert_eq!(half.render_size([3, 1]), [2, 1]);
        assert_eq!(FrameQuality::FULL.render_size([1280, 720]), [1280, 720]);
        for scale in [0.0, -1.0, f32::NAN, 7.0] {
            assert_eq!(FrameQuality { render_scale: scale, ..half }.render_size([1280, 720]), [1280, 720]);
        }
    }

    /// Tatarchuk's count: `max` face-on, `min` grazing, clamped to 1..=256 in either order;
    /// captions name the technique and its layers.
    #[test]
    fn parallax_layers_follow_the_view_angle_and_captions_name_them() {
        let settings =
            ParallaxSettings { technique: Parallax::Occlusion, layers_min: 8, layers_max: 32, ..Default::default() };
        assert_eq!([1.0, 0.5, 0.0, f32::NAN].map(|c| settings.layers(c)), [8, 20, 32, 32]);
        let swapped = ParallaxSettings { layers_min: 999, layers_max: 0, ..settings };
        assert_eq!(swapped.layer_range(), (1, 256));
        assert_eq!(settings.caption(), "parallax occlusion, 8–32 layers");
        let relief = ParallaxSettings { technique: Parallax::Relief, layers_min: 16, layers_max: 16, ..settings };
        assert_eq!(relief.caption(), "relief mapping, 16 layers + 5 steps");
        assert_eq!(ParallaxSettings { technique: Parallax::Offset, ..settings }.caption(), "parallax offset");
    }
}
