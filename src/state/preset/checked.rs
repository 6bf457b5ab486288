//! A preset's sections checked and typed: each value against its range or its names, the
//! error naming the key that is wrong.

use std::collections::BTreeMap;

use glam::Vec3;

use super::{FORMAT_VERSION, LightPreset, Preset, ScenePreset, ShadingPreset, bad, named, named_or_auto};
use crate::error::PresetError;
use crate::frame::{
    CUBE_MAP_SIZES, Displacement, LegacySettings, MAX_DISPLACEMENT_LEVEL, MAX_PARALLAX_LAYERS,
    MAX_PARALLAX_SHADOW_STRENGTH, MAX_PARALLAX_STEPS, ParallaxSettings, SceneOptions, ShadingSettings,
};
use crate::height::Kernel;
use crate::render::capture::MAX_SUPERSAMPLE;
use crate::scene::MAX_LIGHTS;
use crate::state::{DIFFERENCE_RANGE, SplitView};

/// What a preset sets besides files, camera and light, checked and typed.
pub(super) struct Settings {
    pub shading: ShadingSettings,
    pub ambient_strength: f32,
    pub light_orbit: bool,
    pub scene_options: SceneOptions,
    pub kernel: Kernel,
    pub split: SplitView,
}

impl Preset {
    /// Checks and types everything but files, camera and light.
    pub(super) fn settings(&self) -> Result<Settings, PresetError> {
        if let Some(version) = self.version.filter(|&v| v != FORMAT_VERSION) {
            return Err(bad("version", &version.to_string(), &format!("{FORMAT_VERSION} (this bumpview's format)")));
        }
        self.check_camera_and_lights()?;
        self.check_capture()?;
        Ok(Settings {
            // Every field: a new setting must get a place in the preset format too.
            shading: self.shading.to_settings(&self.light)?,
            ambient_strength: self.ambient.strength,
            light_orbit: self.light.orbit,
            scene_options: self.scene.to_options()?,
            kernel: self.kernel()?,
            split: self.split.to_split()?,
        })
    }

    /// Checks the camera, the lights and the ambient light.
    fn check_camera_and_lights(&self) -> Result<(), PresetError> {
        let c = &self.camera;
        if let Some(d) = c.distance.filter(|d| !(d.is_finite() && *d > 0.0)) {
            return Err(bad("camera.distance", &d.to_string(), "a positive number of metres"));
        }
        if let Some(f) = c.fov_y_deg.filter(|f| !(f.is_finite() && *f > 0.0 && *f < 180.0)) {
            return Err(bad("camera.fov_y_deg", &f.to_string(), "degrees between 0 and 180"));
        }
        for (key, angle) in [("camera.yaw_deg", c.yaw_deg), ("camera.pitch_deg", c.pitch_deg)] {
            if let Some(angle) = angle.filter(|a| !a.is_finite()) {
                return Err(bad(key, &angle.to_string(), "a finite number of degrees"));
            }
        }
        let triples =
            [("camera.target", c.target), ("light.position", self.light.position), ("light.color", self.light.color)];
        for (key, triple) in triples {
            if let Some(triple) = triple.filter(|t| !t.iter().all(|v| v.is_finite())) {
                return Err(bad(key, &format!("{triple:?}"), "three finite numbers"));
            }
        }
        if self.lights.len() > MAX_LIGHTS {
            return Err(bad("lights", &format!("{} entries", self.lights.len()), &format!("at most {MAX_LIGHTS}")));
        }
        for (i, light) in self.lights.iter().enumerate() {
            light.to_light(i, Vec3::ZERO)?;
        }
        let a = &self.ambient;
        if let Some(color) = a.color.filter(|c| !c.iter().all(|v| v.is_finite() && *v >= 0.0)) {
            return Err(bad("ambient.color", &format!("{color:?}"), "linear RGB, each finite and at least 0"));
        }
        if !(a.strength.is_finite() && a.strength >= 0.0) {
            return Err(bad("ambient.strength", &a.strength.to_string(), "a finite number, at least 0"));
        }
        Ok(())
    }

    /// Checks the capture settings.
    fn check_capture(&self) -> Result<(), PresetError> {
        let capture = &self.capture;
        if !(1..=MAX_SUPERSAMPLE).contains(&capture.supersample) {
            let range = format!("1 to {MAX_SUPERSAMPLE}");
            return Err(bad("capture.supersample", &capture.supersample.to_string(), &range));
        }
        if let Some([w, h]) = capture.size.filter(|[w, h]| *w == 0 || *h == 0) {
            return Err(bad("capture.size", &format!("[{w}, {h}]"), "[width, height], each at least 1"));
        }
        Ok(())
    }
}

impl ShadingPreset {
    /// The shading settings this section (with `light`'s marker) sets, checked.
    fn to_settings(&self, light: &LightPreset) -> Result<ShadingSettings, PresetError> {
        let s = self;
        if let Some(shininess) = s.shininess.filter(|s| !(s.is_finite() && *s >= 1.0)) {
            return Err(bad("shading.shininess", &shininess.to_string(), "a finite number, at least 1"));
        }
        if !s.strength.is_finite() {
            return Err(bad("shading.strength", &s.strength.to_string(), "a finite number"));
        }
        if !(DIFFERENCE_RANGE.start..=DIFFERENCE_RANGE.end).contains(&s.difference_range_deg) {
            let range = format!("degrees, {} to {}", DIFFERENCE_RANGE.start, DIFFERENCE_RANGE.end);
            return Err(bad("shading.difference_range_deg", &s.difference_range_deg.to_string(), &range));
        }
        let view = named("shading.view", &s.view)?;
        let model = named_or_auto("shading.model", &s.model)?;
        let mode = named("shading.mode", &s.mode)?;
        let layers = format!("[min, max], each 1 to {MAX_PARALLAX_LAYERS}");
        if let Some([a, b]) =
            Some(s.parallax_layers).filter(|l| l.iter().any(|n| !(1..=MAX_PARALLAX_LAYERS).contains(n)))
        {
            return Err(bad("shading.parallax_layers", &format!("[{a}, {b}]"), &layers));
        }
        if s.parallax_steps > MAX_PARALLAX_STEPS {
            let steps = format!("0 to {MAX_PARALLAX_STEPS}");
            return Err(bad("shading.parallax_steps", &s.parallax_steps.to_string(), &steps));
        }
        if !(0.0..=MAX_PARALLAX_SHADOW_STRENGTH).contains(&s.parallax_shadows) {
            let strengths = format!("0 (off) to {MAX_PARALLAX_SHADOW_STRENGTH}");
            return Err(bad("shading.parallax_shadows", &s.parallax_shadows.to_string(), &strengths));
        }
        let cube_map_size = match s.cube_map_size {
            0 => None,
            size if CUBE_MAP_SIZES.contains(&size) => Some(size),
            size => return Err(bad("shading.cube_map_size", &size.to_string(), "0 (none), 8, 16, 32 or 64")),
        };
        if let Some(d) = s.parallax_depth_m.filter(|d| !(d.is_finite() && *d >= 0.0)) {
            return Err(bad("shading.parallax_depth_m", &d.to_string(), "metres, 0 or more"));
        }
        Ok(ShadingSettings {
            bump_enabled: s.bump,
            strength: s.strength,
            view,
            show_light_marker: light.marker,
            difference_range_deg: s.difference_range_deg,
            shading_override: model,
            mode,
            wireframe: s.wireframe,
            tbn_glyphs: s.tbn_glyphs,
            parallax: ParallaxSettings {
                technique: named("shading.parallax", &s.parallax)?,
                layers_min: s.parallax_layers[0],
                layers_max: s.parallax_layers[1],
                steps: s.parallax_steps,
                depth_m: s.parallax_depth_m,
                shadow_strength: s.parallax_shadows,
            },
            mistake: named("shading.mistake", &s.mistake)?,
            legacy: LegacySettings { look: named("shading.legacy", &s.legacy)?, cube_map_size },
            specular: named("shading.specular", &s.specular)?,
            shininess: s.shininess,
            lighting_space: named("shading.lighting_space", &s.lighting_space)?,
            detail_blend: named_or_auto("shading.detail_blend", &s.detail_blend)?,
        })
    }
}

impl ScenePreset {
    /// The scene options this section sets, checked.
    fn to_options(&self) -> Result<SceneOptions, PresetError> {
        let scene = self;
        let tangent_method = named_or_auto("scene.tangents", &scene.tangents)?;
        let bump_source = named("scene.bump_source", &scene.bump_source)?;
        let mut per_material = BTreeMap::new();
        for (index, overrides) in &scene.per_material {
            let section = format!("scene.per_material.{index}");
            let i = index.parse::<usize>().map_err(|_| bad(&section, index, "a material index (0, 1, …)"))?;
            per_material.insert(i, overrides.to_overrides(&section)?);
        }
        if scene.displacement > MAX_DISPLACEMENT_LEVEL {
            let levels = format!("0 (off) to {MAX_DISPLACEMENT_LEVEL}");
            return Err(bad("scene.displacement", &scene.displacement.to_string(), &levels));
        }
        Ok(SceneOptions {
            tangent_method,
            bump_source,
            materials: scene.materials.to_overrides("scene.materials")?,
            per_material,
            // Set by `ViewerState::scene_uploads` from the shading.
            parallax: false,
            cone_maps: false,
            displacement: Displacement {
                level: scene.displacement,
                gpu: super::gpu_pixels("scene.gpu_displacement", scene.gpu_displacement)?,
                ..Default::default()
            },
            tangents_without_gram_schmidt: false,
            mip_filter: named("scene.mip_filter", &scene.mip_filter)?,
            // Set by `ViewerState::scene_uploads` for the compression split's right half.
            normal_maps_through: None,
        })
    }
}
