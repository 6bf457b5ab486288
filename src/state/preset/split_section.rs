//! The preset's `[split]` section: the split view's settings by name, and the split view they
//! describe.

use serde::{Deserialize, Serialize};

use super::{PresetError, bad, named, named_pair, names};
use crate::frame::MAX_DISPLACEMENT_LEVEL;
use crate::names::Named;
use crate::state::{SplitDifference, SplitView};

/// The split view: on or off, what differs, the divider and the pairs of values.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SplitPreset {
    pub enabled: bool,
    /// A [`SplitDifference`] name: `bump`, `view`, `strength`, `mode`, `tangents`,
    /// `convention`, `bump-source`, `parallax`, `lighting-space`, `displacement`, `mip-filter`,
    /// `detail-blend` or `compression`.
    pub difference: String,
    /// The divider, a fraction of the width (0..1).
    pub divider: f32,
    /// [`ViewMode`](crate::frame::ViewMode) names, left and right.
    pub views: [String; 2],
    pub strengths: [f32; 2],
    /// [`ShadingMode`](crate::frame::ShadingMode) names, left and right.
    pub modes: [String; 2],
    /// [`TangentMethod`](crate::tangent::TangentMethod) names, left and right.
    pub tangents: [String; 2],
    /// Green conventions (`opengl`, `directx`), left and right.
    pub conventions: [String; 2],
    /// [`BumpSource`](crate::frame::BumpSource) names, left and right.
    pub bump_sources: [String; 2],
    /// [`Parallax`](crate::frame::Parallax) technique names, left and right.
    pub parallax: [String; 2],
    /// [`Mistake`](crate::frame::Mistake) names, left and right.
    pub mistakes: [String; 2],
    /// [`LightingSpace`](crate::frame::LightingSpace) names, left and right.
    pub lighting_spaces: [String; 2],
    /// The right half's displacement level in the `displacement` split (1 to 10).
    pub displacement_level: u32,
    /// The right half displaced on the GPU instead, at this many pixels per edge (0.5 to 64).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub gpu_displacement: Option<f32>,
    /// [`MipFilter`](crate::texture::MipFilter) names, left and right.
    pub mip_filters: [String; 2],
    /// [`DetailBlend`](crate::frame::DetailBlend) names, left and right.
    pub detail_blends: [String; 2],
    /// The right half's [`CompressedFormat`](crate::bake::compressed_format::CompressedFormat)
    /// name in the `compression` split, e.g. `dds-bc1`.
    pub compression: String,
}

impl Default for SplitPreset {
    fn default() -> Self {
        SplitPreset::from(&SplitView::default())
    }
}

impl From<&SplitView> for SplitPreset {
    fn from(s: &SplitView) -> Self {
        SplitPreset {
            enabled: s.enabled,
            difference: s.difference.name().to_owned(),
            divider: s.divider,
            views: names(s.views),
            strengths: s.strengths,
            modes: names(s.modes),
            tangents: names(s.tangent_methods),
            conventions: names(s.conventions),
            bump_sources: names(s.bump_sources),
            parallax: names(s.parallax),
            mistakes: names(s.mistakes),
            lighting_spaces: names(s.lighting_spaces),
            displacement_level: s.displacement_level,
            gpu_displacement: s.displacement_gpu,
            mip_filters: names(s.mip_filters),
            detail_blends: names(s.detail_blends),
            compression: s.compression.name().to_owned(),
        }
    }
}

impl SplitPreset {
    pub(super) fn to_split(&self) -> Result<SplitView, PresetError> {
        let difference: SplitDifference = named("split.difference", &self.difference)?;
        if !(self.divider.is_finite() && (0.0..=1.0).contains(&self.divider)) {
            return Err(bad("split.divider", &self.divider.to_string(), "a fraction of the width, 0 to 1"));
        }
        if let Some(s) = self.strengths.iter().find(|s| !s.is_finite()) {
            return Err(bad("split.strengths", &s.to_string(), "finite numbers"));
        }
        if !(1..=MAX_DISPLACEMENT_LEVEL).contains(&self.displacement_level) {
            let levels = format!("1 to {MAX_DISPLACEMENT_LEVEL}");
            return Err(bad("split.displacement_level", &self.displacement_level.to_string(), &levels));
        }
        Ok(SplitView {
            // Every field: a new split setting must get a place in the preset format too.
            enabled: self.enabled,
            difference,
            divider: self.divider,
            views: named_pair("split.views", &self.views)?,
            strengths: self.strengths,
            modes: named_pair("split.modes", &self.modes)?,
            tangent_methods: named_pair("split.tangents", &self.tangents)?,
            conventions: named_pair("split.conventions", &self.conventions)?,
            bump_sources: named_pair("split.bump_sources", &self.bump_sources)?,
            parallax: named_pair("split.parallax", &self.parallax)?,
            mistakes: named_pair("split.mistakes", &self.mistakes)?,
            lighting_spaces: named_pair("split.lighting_spaces", &self.lighting_spaces)?,
            displacement_level: self.displacement_level,
            displacement_gpu: super::gpu_pixels("split.gpu_displacement", self.gpu_displacement)?,
            mip_filters: named_pair("split.mip_filters", &self.mip_filters)?,
            detail_blends: named_pair("split.detail_blends", &self.detail_blends)?,
            compression: named("split.compression", &self.compression)?,
        })
    }
}
