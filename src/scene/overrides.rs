//! Viewer-wide changes to every material's texture conventions (command line and panel),
//! applied to a copy of the loaded scene so that the file's own settings stay available.

use super::material::TEXTURE_SPAN_M;
use super::{GreenAxis, NormalMap, NormalSpace, Scene};

/// Settings that replace each material's own where set (`None`: the material's own).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MaterialOverrides {
    /// Normal-map green convention.
    pub green: Option<GreenAxis>,
    /// Two-channel normal maps (z reconstructed).
    pub two_channel: Option<bool>,
    /// Object-space (true) or tangent-space (false) normal maps.
    pub object_space: Option<bool>,
    /// Height maps are depth maps (white = deep).
    pub depth_map: Option<bool>,
    /// Metres per full range of every height map (world units).
    pub height_range_m: Option<f32>,
}

impl MaterialOverrides {
    pub fn is_empty(&self) -> bool {
        *self == MaterialOverrides::default()
    }

    /// `scene` with these settings on every material. A material whose height map settings
    /// change gets its normal map re-made from the height map with its kernel and border.
    pub fn applied_to(&self, scene: &Scene) -> Scene {
        let mut scene = scene.clone();
        for index in 0..scene.materials.len() {
            let material = &mut scene.materials[index];
            if let Some(normal) = &mut material.normal_map {
                let convention = &mut normal.convention;
                convention.green = self.green.unwrap_or(convention.green);
                convention.two_channel = self.two_channel.unwrap_or(convention.two_channel);
                if let Some(object) = self.object_space {
                    convention.space = if object { NormalSpace::Object } else { NormalSpace::Tangent };
                }
            }
            let Some(height) = &mut material.height_map else { continue };
            let before = height.clone();
            height.depth = self.depth_map.unwrap_or(height.depth);
            height.range_m = self.height_range_m.filter(|r| r.is_finite()).unwrap_or(height.range_m);
            if *height != before {
                let height = height.clone();
                let normals = height.to_normal_map(&scene.textures[height.texture], TEXTURE_SPAN_M);
                scene.textures.push(normals);
                let map = NormalMap::new(scene.textures.len() - 1, 1.0);
                scene.materials[index].normal_map = Some(map);
            }
        }
        scene
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::builtin::teaching_scene;

    #[test]
    fn depth_flag_inverts_the_made_normal_map_and_keeps_the_original() {
        let scene = teaching_scene();
        let overrides = MaterialOverrides { depth_map: Some(true), ..Default::default() };
        let changed = overrides.applied_to(&scene);
        assert_eq!(scene, teaching_scene());
        let original = &scene.textures[scene.materials[0].normal_map.as_ref().unwrap().texture];
        let inverted = &changed.textures[changed.materials[0].normal_map.as_ref().unwrap().texture];
        // Find a sloped texel: the depth map's normal leans the other way in x and y.
        let i = original.rgba.chunks_exact(4).position(|t| t[0].abs_diff(128) > 20).unwrap() * 4;
        assert_eq!(original.rgba[i] as i32 + inverted.rgba[i] as i32, 255, "{i}");
        assert!(changed.materials[0].height_map.as_ref().unwrap().depth);
    }
}
