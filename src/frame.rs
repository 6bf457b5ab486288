//! What a frame shows, as plain types: the frame parameters (camera, light, the cheap shading
//! toggles), the scene options that decide GPU data (tangent method, bump source, material
//! overrides), the views and lit modes with their labels, and the one function that decides
//! how an instance is bumped ([`bump_kind`]). Everything above this layer — the prepare
//! stage, the GPU renderer, the CPU probe, the viewer state — describes a picture with these.

mod lighting;
mod looks;
mod parallax;

pub use crate::scene::DetailBlend;
pub use lighting::{LightingSpace, SurfaceLighting};
pub use looks::{CUBE_MAP_SIZES, LegacyLook, LegacySettings, Mistake};
pub use parallax::{
    DEFAULT_PIXELS_PER_EDGE, Displacement, GPU_PIXELS_PER_EDGE, MAX_DISPLACED_TRIANGLES, MAX_DISPLACEMENT_LEVEL,
    MAX_GPU_DISPLACED_TRIANGLES, MAX_GPU_DISPLACED_VERTICES, MAX_GPU_EDGE_SEGMENTS, MAX_PARALLAX_LAYERS,
    MAX_PARALLAX_SHADOW_STRENGTH, MAX_PARALLAX_STEPS, Parallax, ParallaxSettings,
};

use crate::names::Named;
use crate::scene::{
    Lights, MaterialOverrides, NormalSpace, OrbitCamera, PerMaterialOverrides, Scene, ShadingModel, SpecularMode,
};
use crate::tangent::TangentMethod;
use crate::texture::MipFilter;

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
    /// The lit picture in grey ([`crate::shading::over_tilt_grey`]) with pixels in
    /// [`OVER_TILT_COLOR`] where the shading normal tilts past [`OVER_TILT_LIMIT_DEG`] from
    /// the geometric normal ([`over_tilted`]).
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
    /// Blend every material's detail normal map with this method (`None`: each material's
    /// own); a pipeline variant of materials with a detail map.
    pub detail_blend: Option<DetailBlend>,
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
            detail_blend: None,
        }
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
    /// Pack each marched height map's relaxed cone map ([`Parallax::reads_cones`]) into its
    /// blue channel: on while a picture draws relaxed cone stepping (`ViewerState::scene_uploads`
    /// sets it), so no other technique pays for building one.
    pub cone_maps: bool,
    /// Displaced geometry instead of the normal map where a material has a height map.
    pub displacement: Displacement,
    /// Draw averaged and supplied tangent frames without Gram-Schmidt against the vertex
    /// normal ([`crate::tangent::without_gram_schmidt`]): on while a picture shows
    /// [`Mistake::NoGramSchmidt`] (`ViewerState::scene_uploads` sets it).
    pub tangents_without_gram_schmidt: bool,
    /// How every material's normal map is mip-filtered ([`MipFilter`]): it decides the mip
    /// chain baked and uploaded, and the pipeline variant (`MIP_FILTER`).
    pub mip_filter: MipFilter,
    /// Every RGB normal map drawn after a round trip through this GPU texture format (encoded
    /// and decoded on the CPU, [`crate::bake::round_trip::normal_maps_through`]): the
    /// `compression` split's right half. `None`: as loaded.
    pub normal_maps_through: Option<crate::bake::compressed_format::CompressedFormat>,
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
    /// captions name the technique by its one name, its layers and a changed depth.
    #[test]
    fn parallax_layers_follow_the_view_angle_and_captions_name_them() {
        let settings =
            ParallaxSettings { technique: Parallax::Occlusion, layers_min: 8, layers_max: 32, ..Default::default() };
        assert_eq!([1.0, 0.5, 0.0, f32::NAN].map(|c| settings.layers(c)), [8, 20, 32, 32]);
        let swapped = ParallaxSettings { layers_min: 999, layers_max: 0, ..settings };
        assert_eq!(swapped.layer_range(), (1, 256));
        assert_eq!(settings.caption(), "parallax: occlusion, 8–32 layers");
        let relief = ParallaxSettings { technique: Parallax::Relief, layers_min: 16, layers_max: 16, ..settings };
        assert_eq!(relief.caption(), "parallax: relief, 16 layers + 5 steps");
        let deep = ParallaxSettings { technique: Parallax::OffsetLimited, depth_m: Some(0.03), ..settings };
        assert_eq!(deep.caption(), "parallax: offset-limited, depth 3.00 cm");
        for &technique in Parallax::all() {
            let caption = ParallaxSettings { technique, ..settings }.caption();
            assert!(
                caption.starts_with(&format!("parallax: {},", technique.name())) || caption.ends_with(technique.name())
            );
        }
    }
}
