//! Changes to materials' texture conventions (command line and panel): viewer-wide ones for
//! every material and per-material ones that win over them field by field, applied to a copy
//! of the loaded scene so that the file's own settings stay available.

use std::collections::BTreeMap;

use super::material::TEXTURE_SPAN_M;
use super::{GreenAxis, Material, NormalLayout, NormalMap, NormalSpace, Scene, TextureKind};
use crate::height::{Border, Kernel};
use crate::texture::MipFilter;

/// Settings that replace a material's own where set (`None`: the material's own, or for a
/// per-material record the viewer-wide setting).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MaterialOverrides {
    /// Normal-map green convention.
    pub green: Option<GreenAxis>,
    /// Normal maps' channel layout (RGB, RG, AG, X-Ray).
    pub layout: Option<NormalLayout>,
    /// Object-space (true) or tangent-space (false) normal maps.
    pub object_space: Option<bool>,
    /// Height maps are depth maps (white = deep).
    pub depth_map: Option<bool>,
    /// Metres per full range of every height map (world units).
    pub height_range_m: Option<f32>,
    /// Finite-difference kernel that turns height maps into normal maps.
    pub kernel: Option<Kernel>,
    /// Wrap or clamp at the height map's border when differentiating.
    pub border: Option<Border>,
    /// How the normal map is mip-filtered (`None`: [`crate::frame::SceneOptions::mip_filter`]);
    /// it changes the mip chain and the pipeline, not the material.
    pub mip_filter: Option<MipFilter>,
    /// The detail normal map's repeats per base UV unit ([`super::DetailMap::tiling`]).
    pub detail_tiling: Option<f32>,
    /// The detail normal map's strength ([`super::DetailMap::strength`]).
    pub detail_strength: Option<f32>,
}

/// Per-material overrides by index into [`Scene::materials`]; indices the scene does not
/// have are ignored.
pub type PerMaterialOverrides = BTreeMap<usize, MaterialOverrides>;

impl MaterialOverrides {
    pub fn is_empty(&self) -> bool {
        *self == MaterialOverrides::default()
    }

    /// These settings where set, else `base`'s: a per-material record over the viewer-wide one.
    pub fn over(self, base: MaterialOverrides) -> MaterialOverrides {
        MaterialOverrides {
            green: self.green.or(base.green),
            layout: self.layout.or(base.layout),
            object_space: self.object_space.or(base.object_space),
            depth_map: self.depth_map.or(base.depth_map),
            height_range_m: self.height_range_m.or(base.height_range_m),
            kernel: self.kernel.or(base.kernel),
            border: self.border.or(base.border),
            mip_filter: self.mip_filter.or(base.mip_filter),
            detail_tiling: self.detail_tiling.or(base.detail_tiling),
            detail_strength: self.detail_strength.or(base.detail_strength),
        }
    }

    /// What material `index` gets: its own record from `per_material` over these settings.
    pub fn for_material(self, per_material: &PerMaterialOverrides, index: usize) -> MaterialOverrides {
        per_material.get(&index).map_or(self, |own| own.over(self))
    }

    /// `material` as drawn with these settings, and whether its height map settings changed.
    /// Then its normal map must be re-made from the height map: this returns it in the crate
    /// convention (OpenGL, tangent space, scale 1) but still naming the old texture.
    pub fn in_use(&self, material: &Material) -> (Material, bool) {
        let mut material = material.clone();
        if let Some(normal) = &mut material.normal_map {
            let convention = &mut normal.convention;
            convention.green = self.green.unwrap_or(convention.green);
            convention.layout = self.layout.unwrap_or(convention.layout);
            if let Some(object) = self.object_space {
                convention.space = if object { NormalSpace::Object } else { NormalSpace::Tangent };
            }
        }
        if let Some(detail) = &mut material.detail_map {
            detail.tiling = self.detail_tiling.filter(|t| t.is_finite() && *t > 0.0).unwrap_or(detail.tiling);
            detail.strength = self.detail_strength.filter(|s| s.is_finite()).unwrap_or(detail.strength);
        }
        let Some(height) = &mut material.height_map else { return (material, false) };
        let before = height.clone();
        height.depth = self.depth_map.unwrap_or(height.depth);
        height.range_m = self.height_range_m.filter(|r| r.is_finite()).unwrap_or(height.range_m);
        height.kernel = self.kernel.unwrap_or(height.kernel);
        height.border = self.border.unwrap_or(height.border);
        let remade = *height != before;
        if remade {
            let texture = material.normal_map.as_ref().map_or(height.texture, |n| n.texture);
            material.normal_map = Some(NormalMap::new(texture, 1.0));
        }
        (material, remade)
    }

    /// `scene` with these settings on every material.
    pub fn applied_to(&self, scene: &Scene) -> Scene {
        self.applied_with(&PerMaterialOverrides::new(), scene)
    }

    /// `scene` with these settings on every material, and over them each material's own
    /// record from `per_material`. A material whose height map settings change gets its
    /// normal map re-made from the height map with its (possibly overridden) kernel and border.
    pub fn applied_with(&self, per_material: &PerMaterialOverrides, scene: &Scene) -> Scene {
        let mut scene = scene.clone();
        for index in 0..scene.materials.len() {
            let overrides = self.for_material(per_material, index);
            let (material, remade) = overrides.in_use(&scene.materials[index]);
            // A packed map's channels are not a vector's x, y, z: its mips average them one
            // by one (as data) instead of renormalising RGB.
            if let Some(map) = material.normal_map.as_ref().filter(|m| m.convention.layout != NormalLayout::Rgb)
                && let Some(texture) = scene.textures.get_mut(map.texture)
                && texture.kind == TextureKind::NormalMap
            {
                std::sync::Arc::make_mut(texture).kind = TextureKind::Data;
            }
            scene.materials[index] = material;
            let Some(height) = scene.materials[index].height_map.clone().filter(|_| remade) else { continue };
            let normals = height.to_normal_map(&scene.textures[height.texture], TEXTURE_SPAN_M);
            scene.textures.push(normals.into());
            scene.materials[index].normal_map = Some(NormalMap::new(scene.textures.len() - 1, 1.0));
        }
        scene
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::NormalConvention;
    use crate::scene::builtin::{teaching_scene, teaching_scene_with_kernel};

    #[test]
    fn the_overridden_scene_shares_the_images_it_does_not_change() {
        let scene = teaching_scene();
        let same = MaterialOverrides::default().applied_to(&scene);
        assert!(scene.textures.iter().zip(&same.textures).all(|(a, b)| std::sync::Arc::ptr_eq(a, b)));
        let remade = MaterialOverrides { depth_map: Some(true), ..Default::default() }.applied_to(&scene);
        let color = scene.materials[0].base_color_texture.unwrap();
        assert!(std::sync::Arc::ptr_eq(&scene.textures[color], &remade.textures[color]));
    }

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

    #[test]
    fn a_per_material_override_changes_only_its_material_and_wins() {
        let scene = teaching_scene();
        let all = MaterialOverrides { green: Some(GreenAxis::DirectX), depth_map: Some(false), ..Default::default() };
        let torus = MaterialOverrides {
            green: Some(GreenAxis::OpenGl),
            layout: Some(NormalLayout::Rg),
            kernel: Some(Kernel::Sobel3),
            border: Some(Border::Clamp),
            ..Default::default()
        };
        let per_material = PerMaterialOverrides::from([(1, torus)]);
        let changed = all.applied_with(&per_material, &scene);
        assert_eq!(scene, teaching_scene());
        // Material 0: only the viewer-wide settings (its height settings did not change).
        let bricks = &changed.materials[0];
        let normal = bricks.normal_map.as_ref().unwrap();
        assert_eq!(normal.convention.green, GreenAxis::DirectX);
        assert_eq!(normal.convention.layout, NormalLayout::Rgb);
        assert_eq!(normal.texture, scene.materials[0].normal_map.as_ref().unwrap().texture);
        assert_eq!(bricks.height_map, scene.materials[0].height_map);
        // Material 1: its own settings win; the new kernel and border re-make its normal map
        // in the crate convention (its green and layout apply to the file's map only).
        let (drawn, remade) = torus.over(all).in_use(&scene.materials[1]);
        assert!(remade);
        assert_eq!(drawn.height_map.as_ref().unwrap().kernel, Kernel::Sobel3);
        assert_eq!(changed.materials[1], Material { normal_map: changed.materials[1].normal_map.clone(), ..drawn });
        let height = changed.materials[1].height_map.as_ref().unwrap();
        assert_eq!((height.kernel, height.border, height.depth), (Kernel::Sobel3, Border::Clamp, false));
        let made = changed.materials[1].normal_map.as_ref().unwrap();
        assert_eq!(made.texture, scene.textures.len());
        assert_eq!(made.convention, NormalConvention::default());
        assert_eq!(changed.textures.len(), scene.textures.len() + 1);
        // The re-made map is the brick field's Sobel map (up to the 16-bit height texture and
        // the border), not the central-difference one it replaces.
        let max_diff = |a: &[u8], b: &[u8]| a.iter().zip(b).map(|(a, b)| a.abs_diff(*b)).max().unwrap();
        let sobel = teaching_scene_with_kernel(Kernel::Sobel3);
        let ours = &changed.textures[made.texture].rgba;
        let (to_sobel, to_central) = (max_diff(ours, &sobel.textures[1].rgba), max_diff(ours, &scene.textures[1].rgba));
        println!("re-made Sobel map: max {to_sobel} steps from the built-in Sobel map, {to_central} from central");
        assert!(to_sobel <= 2 && to_central > 10, "{to_sobel} {to_central}");
        // Without the green override, the torus inherits DirectX when its height is untouched.
        let green_only = MaterialOverrides { layout: Some(NormalLayout::Rg), ..Default::default() };
        let changed = all.applied_with(&PerMaterialOverrides::from([(1, green_only)]), &scene);
        let torus = changed.materials[1].normal_map.as_ref().unwrap().convention;
        assert_eq!((torus.green, torus.layout), (GreenAxis::DirectX, NormalLayout::Rg));
    }
}
