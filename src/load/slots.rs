//! Texture files put into material slots: the command line's `--color`, `--normal`,
//! `--height` and `--gloss`, and MTL height maps.

use std::path::PathBuf;

use super::image::load_texture;
use crate::error::LoadError;
use crate::scene::material::TEXTURE_SPAN_M;
use crate::scene::{HeightMap, NormalMap, Scene, TextureImage, TextureKind};

/// Metres the full range of a height map from a file spans (times an MTL `-bm`).
pub const HEIGHT_RANGE_M: f32 = 0.01;

/// Texture files that replace a slot of every material in a scene.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TextureSlots {
    /// sRGB base colour.
    pub color: Option<PathBuf>,
    /// Tangent-space normal map, OpenGL convention (+Y up the image).
    pub normal: Option<PathBuf>,
    /// Height map (white = high); also becomes the normal map unless `normal` is given.
    pub height: Option<PathBuf>,
    /// Gloss/specular map (kept with the material; not yet shaded).
    pub gloss: Option<PathBuf>,
}

impl TextureSlots {
    pub fn is_empty(&self) -> bool {
        self == &TextureSlots::default()
    }
}

/// Loads each given file and puts it into its slot on every material of `scene`.
pub fn replace_textures(scene: &mut Scene, slots: &TextureSlots) -> Result<(), LoadError> {
    if let Some(path) = &slots.height {
        let every: Vec<usize> = (0..scene.materials.len()).collect();
        add_height_map(scene, &every, load_texture(path, TextureKind::Height)?, 1.0);
    }
    let mut each = |path: &Option<PathBuf>, kind, set: fn(&mut crate::scene::Material, usize)| {
        if let Some(path) = path {
            scene.textures.push(load_texture(path, kind)?);
            let texture = scene.textures.len() - 1;
            scene.materials.iter_mut().for_each(|m| set(m, texture));
        }
        Ok::<(), LoadError>(())
    };
    each(&slots.color, TextureKind::Color, |m, t| m.base_color_texture = Some(t))?;
    each(&slots.normal, TextureKind::NormalMap, |m, t| m.normal_map = Some(NormalMap::new(t, 1.0)))?;
    each(&slots.gloss, TextureKind::Data, |m, t| m.gloss_texture = Some(t))?;
    Ok(())
}

/// Puts a [`TextureKind::Height`] texture into the height map slot of `materials`, spanning
/// `multiplier ·` [`HEIGHT_RANGE_M`] metres, and the normal map made from it with the slot's
/// settings ([`HeightMap::new`]: central differences, wrapping) into its normal map slot.
pub fn add_height_map(scene: &mut Scene, materials: &[usize], heights: TextureImage, multiplier: f32) {
    let range_m = HEIGHT_RANGE_M * if multiplier.is_finite() { multiplier } else { 1.0 };
    let slot = HeightMap::new(scene.textures.len() + 1, range_m);
    let normal_map = slot.to_normal_map(&heights, TEXTURE_SPAN_M);
    scene.textures.extend([normal_map, heights]);
    for &m in materials {
        scene.materials[m].normal_map = Some(NormalMap::new(slot.texture - 1, 1.0));
        scene.materials[m].height_map = Some(slot.clone());
    }
}
