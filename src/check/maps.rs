//! Every normal map a scene's materials use, in every slot glTF has (the base
//! `normalTexture` and `KHR_materials_clearcoat`'s `clearcoatNormalTexture`): what
//! [`check_normal_map`] finds, the layout the map is read with and why, and the warnings.

use std::fmt::Write;

use image::RgbaImage;

use super::green::GreenConvention;
use super::material_exponent;
use super::mip_shortening::{self, LevelShortening, first_over_sharp, mip_shortening};
use super::normal_map::{NormalMapFindings, check_normal_map, decoded_normals, layout_evidence};
use super::votes_picture::votes_picture;
use crate::names::Named;
use crate::scene::{Material, NormalLayout, NormalMap, Scene, stored_layout};
use crate::texture::compressed::{Stored, StoredChannels};

/// The slot of a material a normal map sits in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NormalSlot {
    /// `normalTexture` (OBJ `map_Bump`/`norm`): the base surface's normal.
    Base,
    /// `KHR_materials_clearcoat`'s `clearcoatNormalTexture`: the coat's own normal.
    ClearCoat,
}

impl NormalSlot {
    /// How the report names the slot: `normal map`, `clear-coat normal map`.
    pub fn label(self) -> &'static str {
        match self {
            NormalSlot::Base => "normal map",
            NormalSlot::ClearCoat => "clear-coat normal map",
        }
    }

    /// A short name for files: `normal`, `clearcoat`.
    pub fn file_name(self) -> &'static str {
        match self {
            NormalSlot::Base => "normal",
            NormalSlot::ClearCoat => "clearcoat",
        }
    }
}

/// One normal map as a material uses it.
#[derive(Debug, Clone, PartialEq)]
pub struct MapFindings {
    pub material: String,
    pub slot: NormalSlot,
    pub texture: String,
    /// Index of the texture in [`Scene::textures`].
    pub texture_index: usize,
    pub findings: NormalMapFindings,
    /// The channel layout the map is drawn with (the material's, as loaded), and why.
    pub layout: NormalLayout,
    pub layout_reason: String,
    /// What the texture file's format says about its channels (DDS, KTX2).
    pub stored: Option<Stored>,
    /// The material's Blinn-Phong exponent (metallic-roughness: Beckmann's `2/α² − 2`).
    pub shininess: f32,
    /// Per mip level, how short the averaged normals get ([`mip_shortening`]); empty unless
    /// the map is the base slot's, read as RGB.
    pub mips: Vec<LevelShortening>,
}

/// The normal maps of `material`, slot by slot.
fn normal_slots(material: &Material) -> impl Iterator<Item = (NormalSlot, &NormalMap)> {
    let base = material.normal_map.as_ref().map(|map| (NormalSlot::Base, map));
    let coat = material.clearcoat.as_ref().and_then(|c| c.normal_map.as_ref()).map(|map| (NormalSlot::ClearCoat, map));
    base.into_iter().chain(coat)
}

/// Checks every normal map in every slot of `scene`'s materials.
pub fn check_normal_maps(scene: &Scene) -> Vec<MapFindings> {
    let mut found = Vec::new();
    for material in &scene.materials {
        for (slot, map) in normal_slots(material) {
            let Some(texture) = scene.textures.get(map.texture) else { continue };
            let layout = map.convention.layout;
            let findings = check_normal_map(texture, layout);
            let evidence = layout_evidence(findings.suggested_layout);
            let layout_reason = match (layout, map.correction.and_then(|c| scene.textures.get(c))) {
                (NormalLayout::Xray, Some(correction)) => {
                    format!("X-Ray pair: {:?} with the correction {:?} beside it", texture.name, correction.name)
                }
                (NormalLayout::Xray, None) => format!("X-Ray bump {:?} without a bump# correction", texture.name),
                (layout, _) => {
                    let texels = match layout == findings.suggested_layout {
                        true => format!("as loaded, and {evidence}"),
                        false => format!("as loaded, although {evidence}"),
                    };
                    match map.stored.as_ref() {
                        Some(stored) if stored_layout(stored) == Some(layout) => stored.reason(),
                        Some(stored) if stored_layout(stored).is_none() => format!("{}; {texels}", stored.reason()),
                        _ => texels,
                    }
                }
            };
            let shininess = material_exponent(material);
            let mips = if layout == NormalLayout::Rgb && slot == NormalSlot::Base {
                mip_shortening(texture, shininess)
            } else {
                vec![]
            };
            found.push(MapFindings {
                material: material.name.clone(),
                slot,
                texture: texture.name.clone(),
                texture_index: map.texture,
                findings,
                layout,
                layout_reason,
                stored: map.stored.clone(),
                shininess,
                mips,
            });
        }
    }
    found
}

/// Warn about texels that decode more than 10% off unit length when more than this share of
/// a normal map's texels do.
pub const NON_UNIT_WARN_SHARE: f32 = 0.05;
/// Warn about texels with `z < 0` (pointing into the surface) from this share on: 0.01%, the
/// smallest share the report prints as non-zero.
pub const NEGATIVE_Z_WARN_SHARE: f32 = 1e-4;

impl MapFindings {
    /// `material "M", normal map "T"`.
    pub fn name(&self) -> String {
        format!("material {:?}, {} {:?}", self.material, self.slot.label(), self.texture)
    }

    /// The tiles' green votes as a picture over the map ([`votes_picture`]); `None` when
    /// the texture is not in `scene`.
    pub fn votes_picture(&self, scene: &Scene) -> Option<RgbaImage> {
        let texture = scene.textures.get(self.texture_index)?;
        let normals = decoded_normals(texture, self.findings.read_layout);
        Some(votes_picture(&normals, texture.width, texture.height, &self.findings.green))
    }

    /// The map's warnings, one line each.
    pub fn warnings(&self) -> Vec<String> {
        let (f, name) = (&self.findings, self.name());
        let mut warnings = Vec::new();
        if self.layout != f.suggested_layout && self.layout != NormalLayout::Xray {
            let (suggested, evidence) = (f.suggested_layout.name(), layout_evidence(f.suggested_layout));
            warnings.push(format!("{name}: {evidence}, which suggests --normal-layout {suggested}"));
        }
        if f.looks_object_space {
            warnings.push(format!(
                "{name}: its normals spread over the sphere rather than around +Z: an object-space map, \
                 drawn as tangent space (its green is not judged)"
            ));
        }
        if let Some((GreenConvention::DirectX, confidence)) = f.convention {
            warnings.push(format!("{name}: green looks DirectX (−Y), confidence {confidence:.2}"));
        }
        if let Some(stored) = self.stored.as_ref().filter(|s| s.channels == StoredChannels::ColourBlock) {
            warnings.push(format!(
                "{name}: stored as {} (three channels in a block format made for colour): z takes bits from x and y; \
                 BC5 or two-channel UASTC keep x and y only and rebuild z",
                stored.format
            ));
        }
        // The texel statistics read red, green, blue as x, y, z.
        if self.layout != NormalLayout::Rgb {
            return warnings;
        }
        if f.non_unit_share > NON_UNIT_WARN_SHARE {
            warnings.push(format!("{name}: {:.1}% of texels decode far from unit length", f.non_unit_share * 100.0));
        }
        if f.negative_z_share >= NEGATIVE_Z_WARN_SHARE && !f.looks_object_space {
            let share = f.negative_z_share * 100.0;
            warnings.push(format!("{name}: {share:.2}% of texels point into the surface (z < 0)"));
        }
        if f.looks_srgb {
            warnings.push(format!("{name}: looks sRGB-encoded (flat texels near 188 instead of 128)"));
        }
        if let Some(l) = first_over_sharp(&self.mips) {
            warnings.push(format!(
                "{name}: from mip level {} ({}×{}) its averaged normals are {:.3} long: a re-normalised chain \
                 draws the highlight with exponent {:.0} where the bumps it averages spread it to {:.1} \
                 (Toksvig, {:.2}×, below {}×); --mip-filter toksvig or vmf widens it",
                l.level,
                l.width,
                l.height,
                l.mean_length,
                self.shininess,
                l.exponent_ratio * self.shininess,
                l.exponent_ratio,
                mip_shortening::WARN_EXPONENT_RATIO
            ));
        }
        warnings
    }

    /// The map's lines of the report.
    pub fn write_text(&self, out: &mut String) {
        let f = &self.findings;
        let _ = writeln!(
            out,
            "  {}: {:.1}% non-unit, {:.2}% z < 0, {}, {}; green: {}",
            self.name(),
            f.non_unit_share * 100.0,
            f.negative_z_share * 100.0,
            if f.looks_srgb { "looks sRGB-encoded" } else { "linear" },
            if f.looks_object_space { "object space" } else { "tangent space" },
            f.green_text(),
        );
        let _ = writeln!(out, "    layout: {} ({})", self.layout.name(), self.layout_reason);
        if !self.mips.is_empty() {
            let lengths: Vec<String> = self.mips.iter().map(|l| format!("{:.3}", l.mean_length)).collect();
            let ratios: Vec<String> = self.mips.iter().map(|l| format!("{:.2}", l.exponent_ratio)).collect();
            let _ = writeln!(out, "    mips: mean |Na| per level {}", lengths.join(" "));
            let _ = writeln!(
                out,
                "    Toksvig exponent over the material's {:.0} per level (1: a re-normalised chain is right) {}",
                self.shininess,
                ratios.join(" ")
            );
        }
    }
}
