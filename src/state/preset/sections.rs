//! The sections of a preset file, one struct each, and their conversions from and to the
//! viewer state's values.

use crate::frame::{SceneOptions, ShadingSettings};
use crate::height::Kernel;
use crate::names::{Named, name_or_auto};
use crate::render::Background;
use crate::render::capture::CaptureOptions;
use crate::scene::{Attenuation, Light, MaterialOverrides, NormalLayout};
use glam::Vec3;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

use super::*;

/// The orbit camera; each missing value is the scene's default camera's.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct CameraPreset {
    /// The point looked at, metres.
    pub target: Option<[f32; 3]>,
    /// Degrees about +Y (0 looks along −Z).
    pub yaw_deg: Option<f64>,
    /// Degrees above the target.
    pub pitch_deg: Option<f64>,
    /// Metres from the target.
    pub distance: Option<f32>,
    /// Vertical field of view, degrees.
    pub fov_y_deg: Option<f64>,
}

/// The `[light]` table: orbit and markers, and (older presets) the one light's position and
/// colour, which set the first light; missing ones are the scene's default light's.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct LightPreset {
    /// Metres, world space (older presets; `[[lights]]` holds every light).
    pub position: Option<[f32; 3]>,
    /// Linear RGB (older presets).
    pub color: Option<[f32; 3]>,
    /// The lights orbit the target.
    pub orbit: bool,
    /// The light markers are drawn.
    pub marker: bool,
}

impl Default for LightPreset {
    fn default() -> Self {
        let shading = ShadingSettings::default();
        LightPreset { position: None, color: None, orbit: false, marker: shading.show_light_marker }
    }
}

/// One `[[lights]]` entry; missing keys are those of a white point light of intensity 1,
/// on, without attenuation, at the scene's default light's position.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct LightEntryPreset {
    /// `point` or `directional`.
    pub kind: String,
    /// A point light's position (metres, world space) or a directional light's direction
    /// towards the light.
    pub position: Option<[f32; 3]>,
    /// Linear RGB, each at least 0.
    pub color: [f32; 3],
    /// At least 0.
    pub intensity: f32,
    pub enabled: bool,
    /// `[c, l, q]` of `1 / (c + l·d + q·d²)`, each at least 0, not all 0.
    pub attenuation: [f32; 3],
}

impl Default for LightEntryPreset {
    fn default() -> Self {
        LightEntryPreset::from(&Light::point(Vec3::ZERO, Vec3::ONE))
    }
}

impl From<&Light> for LightEntryPreset {
    fn from(light: &Light) -> Self {
        LightEntryPreset {
            kind: light.kind.name().to_owned(),
            position: Some(light.position.to_array()),
            color: light.color.to_array(),
            intensity: light.intensity,
            enabled: light.enabled,
            attenuation: light.attenuation.to_array(),
        }
    }
}

impl LightEntryPreset {
    /// The light; `index` names the entry in errors, `default_position` stands in for a
    /// missing position.
    pub(super) fn to_light(&self, index: usize, default_position: Vec3) -> Result<Light, PresetError> {
        let key = |k: &str| format!("lights[{index}].{k}");
        let kind = named(&key("kind"), &self.kind)?;
        let position = self.position.map_or(default_position, Vec3::from_array);
        if !position.is_finite() {
            return Err(bad(&key("position"), &format!("{position}"), "finite numbers"));
        }
        let color = Vec3::from_array(self.color);
        if !(color.is_finite() && color.min_element() >= 0.0) {
            return Err(bad(&key("color"), &format!("{:?}", self.color), "linear RGB, each finite and at least 0"));
        }
        if !(self.intensity.is_finite() && self.intensity >= 0.0) {
            return Err(bad(&key("intensity"), &self.intensity.to_string(), "a finite number, at least 0"));
        }
        let attenuation = Attenuation::from_array(self.attenuation)
            .map_err(|e| bad(&key("attenuation"), &format!("{:?}", self.attenuation), &e))?;
        Ok(Light { kind, position, color, intensity: self.intensity, enabled: self.enabled, attenuation })
    }
}

/// The ambient light; a missing colour is the scene's.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct AmbientPreset {
    /// Linear RGB, each at least 0.
    pub color: Option<[f32; 3]>,
    /// Multiplies the colour, at least 0.
    pub strength: f32,
}

impl Default for AmbientPreset {
    fn default() -> Self {
        AmbientPreset { color: None, strength: 1.0 }
    }
}

/// The shader uniforms: bump, strength, view and shading model.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ShadingPreset {
    pub bump: bool,
    pub strength: f32,
    /// A [`ViewMode`](crate::frame::ViewMode) name.
    pub view: String,
    pub difference_range_deg: f32,
    /// `auto`, `blinn-phong` or `pbr`.
    pub model: String,
    /// A [`ShadingMode`](crate::frame::ShadingMode) name: `bump-colour`, `bump-only` or `colour-only`.
    pub mode: String,
    /// The wireframe overlay.
    pub wireframe: bool,
    /// T/B/N glyphs at vertices.
    pub tbn_glyphs: bool,
    /// A [`Parallax`](crate::frame::Parallax) technique name: `off`, `offset`, `steep`, ….
    pub parallax: String,
    /// The search's layers `[min, max]` (each 1 to 256).
    pub parallax_layers: [u32; 2],
    /// Relief mapping's binary-search steps (0 to 16).
    pub parallax_steps: u32,
    /// The relief's depth, metres; missing: each material's height range.
    pub parallax_depth_m: Option<f32>,
    /// A [`Mistake`](crate::frame::Mistake) name: `none`, `tbn-typo`, `green-flipped`, ….
    pub mistake: String,
    /// A [`LegacyLook`](crate::frame::LegacyLook) name: `off`, `dot3`, `emboss`.
    pub legacy: String,
    /// DOT3's normalization cube map face size: 8, 16, 32 or 64; 0: none (L per vertex).
    pub cube_map_size: u32,
    /// A [`SpecularMode`](crate::scene::SpecularMode) name: `blinn`, `phong` or `off`.
    pub specular: String,
    /// The shininess for every material (at least 1); missing: each material's own.
    pub shininess: Option<f32>,
    /// A [`LightingSpace`](crate::frame::LightingSpace) name: `world`, `tangent` or `view`.
    pub lighting_space: String,
    /// `auto` (each material's own) or a [`DetailBlend`](crate::frame::DetailBlend) name for
    /// every detail normal map: `linear`, `partial-derivative`, `whiteout`, `udn`, `rnm`,
    /// `surface-gradient`.
    pub detail_blend: String,
    /// The searches' soft self-shadows: their strength, 0 (off) to 4.
    pub parallax_shadows: f32,
}

/// How the scene is prepared: tangents, bump source, kernel and material conventions.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ScenePreset {
    /// `auto` or a [`TangentMethod`](crate::tangent::TangentMethod) name.
    pub tangents: String,
    /// A [`BumpSource`](crate::frame::BumpSource) name.
    pub bump_source: String,
    /// The built-in brick map's [`Kernel`] name.
    pub kernel: String,
    /// Conventions for every material.
    pub materials: OverridesPreset,
    /// Conventions per material, by index into the scene's materials (`"0"`, `"1"`…).
    pub per_material: BTreeMap<String, OverridesPreset>,
    /// Displacement's tessellation level, 0 (off) to 10: materials with a height map drawn
    /// as displaced geometry, the depth the parallax depth.
    pub displacement: u32,
    /// Displacement on the GPU instead, at this many pixels per edge (0.5 to 64).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gpu_displacement: Option<f32>,
    /// A [`MipFilter`](crate::texture::MipFilter) name: how every normal map is mip-filtered.
    pub mip_filter: String,
}

/// [`MaterialOverrides`] by name; a missing key keeps the material's own setting.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct OverridesPreset {
    /// `opengl` or `directx`.
    pub normal_convention: Option<String>,
    /// A [`NormalLayout`](crate::scene::NormalLayout) name: `rgb`, `rg`, `ag`, `xray`.
    pub normal_layout: Option<String>,
    /// Older presets' spelling of `normal_layout = "rg"` (true) or `"rgb"` (false); read, never
    /// written.
    pub two_channel: Option<bool>,
    pub object_space: Option<bool>,
    pub depth_map: Option<bool>,
    pub height_range_m: Option<f32>,
    /// A [`Kernel`] name.
    pub height_kernel: Option<String>,
    /// `wrap` or `clamp`.
    pub height_border: Option<String>,
    /// A [`MipFilter`](crate::texture::MipFilter) name for the normal map (over `[scene]
    /// mip_filter`).
    pub mip_filter: Option<String>,
    /// The detail normal map's repeats per base UV unit (above 0).
    pub detail_tiling: Option<f32>,
    /// The detail normal map's strength (0 flat).
    pub detail_strength: Option<f32>,
}

/// Screenshot settings: size, transparent background, supersampling.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct CapturePreset {
    /// `[width, height]` in pixels; `None`: the caller's size (the view's, or `render`'s default).
    pub size: Option<[u32; 2]>,
    /// Clear to alpha 0 where there is no geometry.
    pub transparent: bool,
    /// Render at this many times the size and box-filter down, 1..=[`MAX_SUPERSAMPLE`].
    pub supersample: u32,
    /// Row exports get a caption strip under each tile.
    pub captions: bool,
}

impl Default for ShadingPreset {
    fn default() -> Self {
        ShadingPreset::from(&ShadingSettings::default())
    }
}

impl From<&ShadingSettings> for ShadingPreset {
    fn from(s: &ShadingSettings) -> Self {
        ShadingPreset {
            bump: s.bump_enabled,
            strength: s.strength,
            view: s.view.name().to_owned(),
            difference_range_deg: s.difference_range_deg,
            model: name_or_auto(s.shading_override).to_owned(),
            mode: s.mode.name().to_owned(),
            wireframe: s.wireframe,
            tbn_glyphs: s.tbn_glyphs,
            parallax: s.parallax.technique.name().to_owned(),
            parallax_layers: [s.parallax.layers_min, s.parallax.layers_max],
            parallax_steps: s.parallax.steps,
            parallax_depth_m: s.parallax.depth_m,
            mistake: s.mistake.name().to_owned(),
            legacy: s.legacy.look.name().to_owned(),
            cube_map_size: s.legacy.cube_map_size.unwrap_or(0),
            specular: s.specular.name().to_owned(),
            shininess: s.shininess,
            lighting_space: s.lighting_space.name().to_owned(),
            detail_blend: name_or_auto(s.detail_blend).to_owned(),
            parallax_shadows: s.parallax.shadow_strength,
        }
    }
}

impl Default for ScenePreset {
    fn default() -> Self {
        ScenePreset::new(&SceneOptions::default(), Kernel::default())
    }
}

impl ScenePreset {
    pub(super) fn new(options: &SceneOptions, kernel: Kernel) -> ScenePreset {
        ScenePreset {
            tangents: name_or_auto(options.tangent_method).to_owned(),
            bump_source: options.bump_source.name().to_owned(),
            kernel: kernel.name().to_owned(),
            materials: OverridesPreset::from(&options.materials),
            per_material: options.per_material.iter().map(|(i, o)| (i.to_string(), o.into())).collect(),
            displacement: options.displacement.level,
            gpu_displacement: options.displacement.gpu,
            mip_filter: options.mip_filter.name().to_owned(),
        }
    }
}

impl Default for CapturePreset {
    fn default() -> Self {
        CapturePreset { size: None, transparent: false, supersample: 1, captions: false }
    }
}

impl CapturePreset {
    /// The capture these settings describe, `size` pixels when they give none.
    pub fn options(&self, size: [u32; 2]) -> CaptureOptions {
        let background = if self.transparent { Background::Transparent } else { Background::Opaque };
        CaptureOptions { size: self.size.unwrap_or(size), background, supersample: self.supersample }
    }
}

impl From<&MaterialOverrides> for OverridesPreset {
    fn from(o: &MaterialOverrides) -> Self {
        OverridesPreset {
            normal_convention: o.green.map(|g| g.name().to_owned()),
            normal_layout: o.layout.map(|l| l.name().to_owned()),
            two_channel: None,
            object_space: o.object_space,
            depth_map: o.depth_map,
            height_range_m: o.height_range_m,
            height_kernel: o.kernel.map(|k| k.name().to_owned()),
            height_border: o.border.map(|b| b.name().to_owned()),
            mip_filter: o.mip_filter.map(|m| m.name().to_owned()),
            detail_tiling: o.detail_tiling,
            detail_strength: o.detail_strength,
        }
    }
}

impl OverridesPreset {
    /// The overrides; `section` names the table in errors.
    pub(super) fn to_overrides(&self, section: &str) -> Result<MaterialOverrides, PresetError> {
        let key = |k: &str| format!("{section}.{k}");
        let height_range_m = match self.height_range_m {
            Some(r) if !(r.is_finite() && r >= 0.0) => {
                return Err(bad(&key("height_range_m"), &r.to_string(), "a finite number of metres, at least 0"));
            }
            r => r,
        };
        Ok(MaterialOverrides {
            green: self.normal_convention.as_deref().map(|n| named(&key("normal_convention"), n)).transpose()?,
            layout: match (&self.normal_layout, self.two_channel) {
                (Some(name), _) => Some(named(&key("normal_layout"), name)?),
                (None, Some(two)) => Some(if two { NormalLayout::Rg } else { NormalLayout::Rgb }),
                (None, None) => None,
            },
            object_space: self.object_space,
            depth_map: self.depth_map,
            height_range_m,
            kernel: self.height_kernel.as_deref().map(|n| named(&key("height_kernel"), n)).transpose()?,
            border: self.height_border.as_deref().map(|n| named(&key("height_border"), n)).transpose()?,
            mip_filter: self.mip_filter.as_deref().map(|n| named(&key("mip_filter"), n)).transpose()?,
            detail_tiling: match self.detail_tiling {
                Some(t) if !(t.is_finite() && t > 0.0) => {
                    return Err(bad(&key("detail_tiling"), &t.to_string(), "a finite number above 0"));
                }
                t => t,
            },
            detail_strength: match self.detail_strength {
                Some(s) if !s.is_finite() => {
                    return Err(bad(&key("detail_strength"), &s.to_string(), "a finite number"));
                }
                s => s,
            },
        })
    }
}
