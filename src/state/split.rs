//! The split view: two pictures side by side that differ in one thing, in uniforms (one scene
//! upload) or in GPU data (a second upload for the right half).

use super::Command;
use crate::bake::compressed_format::CompressedFormat;
use crate::frame::{
    BumpSource, DetailBlend, LightingSpace, MAX_DISPLACEMENT_LEVEL, Mistake, Parallax, STRENGTH_RANGE, SceneOptions,
    ShadingMode, ShadingSettings, ViewMode,
};
use crate::names::Named;
use crate::scene::GreenAxis;
use crate::tangent::TangentMethod;
use crate::texture::MipFilter;

/// What the split view's two halves differ in. Bump, view, strength, mode, parallax and
/// lighting space are uniforms or pipeline variants, so both halves share one scene upload; the others change GPU data
/// ([`SplitDifference::changes_gpu_data`]), so the right half is drawn from a second upload of
/// the scene. Named `bump`, `view`, `strength`, `mode`, `tangents`, `convention`,
/// `bump-source`, `parallax`, `mistake`, `lighting-space`, `displacement`, `mip-filter`,
/// `detail-blend`, `compression`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, strum::IntoStaticStr, strum::VariantArray)]
#[strum(serialize_all = "kebab-case")]
pub enum SplitDifference {
    /// Bump off │ bump on.
    #[default]
    Bump,
    /// Two views, e.g. Lit │ Shading normal.
    View,
    /// Two bump strengths.
    Strength,
    /// Two lit-picture modes (bump × colour, bump only, colour only).
    Mode,
    /// Two tangent-frame methods.
    Tangents,
    /// Two normal-map green conventions (OpenGL │ DirectX) for every material.
    Convention,
    /// Two bump sources (normal map │ height in shader).
    BumpSource,
    /// Two parallax techniques (same layers, steps and depth).
    Parallax,
    /// Two classic mistakes, e.g. none │ TBN typo (pipeline variants, one upload).
    Mistake,
    /// Two lighting spaces (world │ tangent by default).
    LightingSpace,
    /// The left parallax technique (`parallax[0]`) │ displacement at `displacement_level`, the
    /// ground truth (same depth).
    Displacement,
    /// Two normal-map mip filters ([`MipFilter`]; re-normalised box │ Toksvig by default) for
    /// every material, over per-material choices: different mip chains, so a second upload.
    MipFilter,
    /// Two detail-blend methods ([`DetailBlend`]; UDN │ RNM by default) for every material's
    /// detail normal map: pipeline variants, one upload.
    DetailBlend,
    /// Every RGB normal map as loaded │ after a round trip through a GPU texture format
    /// ([`CompressedFormat`], BC1 by default; encoded and decoded on the CPU): a second upload.
    Compression,
}

impl SplitDifference {
    /// Whether the halves need different GPU data (tangent streams, material flags, pipeline
    /// variants), not only different uniforms.
    pub fn changes_gpu_data(self) -> bool {
        matches!(
            self,
            SplitDifference::Tangents
                | SplitDifference::Convention
                | SplitDifference::BumpSource
                | SplitDifference::Displacement
                | SplitDifference::MipFilter
                | SplitDifference::Compression
        )
    }
}

/// The split view's settings: the two halves are the current settings with one thing changed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SplitView {
    pub enabled: bool,
    pub difference: SplitDifference,
    /// The divider, a fraction of the width.
    pub divider: f32,
    pub views: [ViewMode; 2],
    pub strengths: [f32; 2],
    pub modes: [ShadingMode; 2],
    pub tangent_methods: [TangentMethod; 2],
    pub conventions: [GreenAxis; 2],
    pub bump_sources: [BumpSource; 2],
    pub parallax: [Parallax; 2],
    pub mistakes: [Mistake; 2],
    pub lighting_spaces: [LightingSpace; 2],
    /// The right half's displacement level in [`SplitDifference::Displacement`].
    pub displacement_level: u32,
    /// The right half displaced on the GPU at this many pixels per edge instead.
    pub displacement_gpu: Option<f32>,
    /// The two methods of [`SplitDifference::MipFilter`].
    pub mip_filters: [MipFilter; 2],
    /// The two methods of [`SplitDifference::DetailBlend`].
    pub detail_blends: [DetailBlend; 2],
    /// The right half's format in [`SplitDifference::Compression`].
    pub compression: CompressedFormat,
}

impl Default for SplitView {
    fn default() -> Self {
        SplitView {
            enabled: false,
            difference: SplitDifference::Bump,
            divider: 0.5,
            views: [ViewMode::Lit, ViewMode::ShadingNormal],
            strengths: [1.0, 3.0],
            modes: [ShadingMode::ColourOnly, ShadingMode::BumpTimesColour],
            tangent_methods: [TangentMethod::PerFace, TangentMethod::MikkTSpace],
            conventions: [GreenAxis::OpenGl, GreenAxis::DirectX],
            bump_sources: [BumpSource::NormalMap, BumpSource::HeightInShader],
            parallax: [Parallax::plainest_search(), Parallax::headline()],
            mistakes: [Mistake::None, Mistake::TbnTypo],
            lighting_spaces: [LightingSpace::World, LightingSpace::Tangent],
            displacement_level: 6,
            displacement_gpu: None,
            mip_filters: [MipFilter::RenormalizedBox, MipFilter::Toksvig],
            detail_blends: [DetailBlend::Udn, DetailBlend::Rnm],
            compression: CompressedFormat::DdsBc1,
        }
    }
}

impl SplitView {
    /// Applies `command` if it is one of the split view's; whether it was.
    pub(super) fn apply(&mut self, command: Command) -> bool {
        match command {
            Command::SetSplitMipFilters(filters) => self.mip_filters = filters,
            Command::SetSplitDetailBlends(methods) => self.detail_blends = methods,
            Command::SetSplitCompression(format) => self.compression = format,
            Command::SetSplitDisplacement(technique, level, gpu) => {
                self.parallax[0] = technique;
                self.displacement_level = level.clamp(1, MAX_DISPLACEMENT_LEVEL);
                let range = crate::frame::GPU_PIXELS_PER_EDGE;
                self.displacement_gpu = gpu.filter(|p| p.is_finite()).map(|p| p.clamp(*range.start(), *range.end()));
            }
            Command::SetSplit(on) => self.enabled = on,
            Command::ToggleSplit => self.enabled = !self.enabled,
            Command::SetSplitDifference(difference) => self.difference = difference,
            Command::SetSplitDivider(x) if x.is_finite() => self.divider = x.clamp(0.0, 1.0),
            Command::SetSplitDivider(_) => {}
            Command::SetSplitViews(views) => self.views = views,
            Command::SetSplitStrengths(strengths) if strengths.iter().all(|s| s.is_finite()) => {
                self.strengths = strengths.map(|s| s.clamp(*STRENGTH_RANGE.start(), *STRENGTH_RANGE.end()))
            }
            Command::SetSplitStrengths(_) => {}
            Command::SetSplitModes(modes) => self.modes = modes,
            Command::SetSplitTangentMethods(methods) => self.tangent_methods = methods,
            Command::SetSplitConventions(conventions) => self.conventions = conventions,
            Command::SetSplitBumpSources(sources) => self.bump_sources = sources,
            Command::SetSplitParallax(techniques) => self.parallax = techniques,
            Command::SetSplitMistakes(mistakes) => self.mistakes = mistakes,
            Command::SetSplitLightingSpaces(spaces) => self.lighting_spaces = spaces,
            _ => return false,
        }
        true
    }

    /// The left and right shading: `current` with the chosen difference applied.
    pub fn shading(&self, current: &ShadingSettings) -> [ShadingSettings; 2] {
        let side = |i: usize| {
            let mut s = *current;
            match self.difference {
                SplitDifference::Bump => s.bump_enabled = i == 1,
                SplitDifference::View => s.view = self.views[i],
                SplitDifference::Strength => s.strength = self.strengths[i],
                SplitDifference::Mode => s.mode = self.modes[i],
                SplitDifference::Parallax => s.parallax.technique = self.parallax[i],
                SplitDifference::Mistake => s.mistake = self.mistakes[i],
                SplitDifference::LightingSpace => s.lighting_space = self.lighting_spaces[i],
                SplitDifference::DetailBlend => s.detail_blend = Some(self.detail_blends[i]),
                SplitDifference::Displacement if i == 0 => s.parallax.technique = self.parallax[0],
                SplitDifference::Displacement => {}
                SplitDifference::Tangents
                | SplitDifference::Convention
                | SplitDifference::BumpSource
                | SplitDifference::MipFilter
                | SplitDifference::Compression => {}
            }
            s
        };
        [side(0), side(1)]
    }

    /// The left and right scene options: `current` with the chosen difference applied (both
    /// equal to `current` for differences that are only uniforms). A convention applies to
    /// every material, over per-material choices.
    pub fn scene_options(&self, current: &SceneOptions) -> [SceneOptions; 2] {
        std::array::from_fn(|i| {
            let mut options = current.clone();
            match self.difference {
                SplitDifference::Tangents => options.tangent_method = Some(self.tangent_methods[i]),
                SplitDifference::Convention => {
                    options.materials.green = Some(self.conventions[i]);
                    for overrides in options.per_material.values_mut() {
                        overrides.green = None;
                    }
                    options.per_material.retain(|_, o| !o.is_empty());
                }
                SplitDifference::BumpSource => options.bump_source = self.bump_sources[i],
                SplitDifference::Displacement => {
                    options.displacement.level = [0, self.displacement_level][i];
                    options.displacement.gpu = [None, self.displacement_gpu][i];
                }
                SplitDifference::MipFilter => {
                    options.mip_filter = self.mip_filters[i];
                    options.materials.mip_filter = None;
                    for overrides in options.per_material.values_mut() {
                        overrides.mip_filter = None;
                    }
                    options.per_material.retain(|_, o| !o.is_empty());
                }
                SplitDifference::Compression => options.normal_maps_through = [None, Some(self.compression)][i],
                SplitDifference::Bump
                | SplitDifference::View
                | SplitDifference::Strength
                | SplitDifference::Mode
                | SplitDifference::Parallax
                | SplitDifference::Mistake
                | SplitDifference::LightingSpace
                | SplitDifference::DetailBlend => {}
            }
            options
        })
    }

    /// Whether `command` changes only what this split view sets per half (bump with a bump
    /// split, the view with a view split, the strength, the shading mode): the halves then draw
    /// as before, so the viewer says why instead.
    pub fn overrides(&self, command: Command) -> bool {
        self.enabled
            && matches!(
                (self.difference, command),
                (SplitDifference::Bump, Command::ToggleBump | Command::SetBump(_))
                    | (SplitDifference::View, Command::CycleView | Command::SetView(_))
                    | (SplitDifference::Strength, Command::StepStrength(_) | Command::SetStrength(_))
                    | (SplitDifference::Mode, Command::SetShadingMode(_))
            )
    }

    /// The on-screen labels of the left and right halves.
    pub fn labels(&self) -> [String; 2] {
        std::array::from_fn(|i| match self.difference {
            SplitDifference::Bump => ["bump off", "bump on"][i].to_owned(),
            SplitDifference::View => self.views[i].label().to_owned(),
            SplitDifference::Strength => format!("strength {:.2}", self.strengths[i]),
            SplitDifference::Mode => self.modes[i].label().to_owned(),
            SplitDifference::Tangents => format!("tangents: {}", self.tangent_methods[i].name()),
            SplitDifference::Convention => format!("normal map: {}", self.conventions[i].label()),
            SplitDifference::BumpSource => self.bump_sources[i].label().to_owned(),
            SplitDifference::Parallax => format!("parallax: {}", self.parallax[i].name()),
            SplitDifference::Mistake => match self.mistakes[i] {
                Mistake::None => "correct".to_owned(),
                mistake => format!("{}: {}", mistake.name(), mistake.explanation()),
            },
            SplitDifference::LightingSpace => format!("lighting space: {}", self.lighting_spaces[i].name()),
            SplitDifference::Displacement if i == 0 => format!("parallax: {}", self.parallax[0].name()),
            SplitDifference::Displacement => format!("displacement, level {}", self.displacement_level),
            SplitDifference::MipFilter => format!("mips: {}", self.mip_filters[i].name()),
            SplitDifference::DetailBlend => format!("detail blend: {}", self.detail_blends[i].name()),
            SplitDifference::Compression if i == 0 => "normal map: uncompressed".to_owned(),
            SplitDifference::Compression => format!("normal map through {}", self.compression.name()),
        })
    }
}
