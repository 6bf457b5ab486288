//! The flags for the numerical methods and texture conventions behind a picture, shared by the
//! viewer and `render`, and the viewer [`Command`]s they stand for.

use bumpview::frame::{BumpSource, DetailBlend};
use bumpview::height::{Border, Kernel};
use bumpview::scene::{GreenAxis, MaterialOverrides, NormalLayout, ShadingModel};
use bumpview::state::{Command, ViewerState};
use bumpview::tangent::TangentMethod;
use bumpview::texture::MipFilter;

use super::args::{self, AutoOr};

/// The numerical methods behind the picture (shared by the viewer and `render`).
#[derive(clap::Args, Clone, Copy)]
pub struct MethodArgs {
    /// Tangent frames: auto (the mesh's own, else MikkTSpace by meshoptimizer) or a method [default: auto].
    #[arg(long, value_parser = args::named_or_auto::<TangentMethod>())]
    pub tangents: Option<AutoOr<TangentMethod>>,
    /// Height→normal kernel for the built-in brick normal map [default: central].
    #[arg(long, value_parser = args::named::<Kernel>())]
    pub kernel: Option<Kernel>,
    /// Where the bump comes from: the normal map, or the height map in the shader (Blinn's
    /// bump by screen-space derivatives, no tangents) [default: normal-map].
    #[arg(long, value_parser = args::named::<BumpSource>())]
    pub bump_source: Option<BumpSource>,
    /// How normal maps are mip-filtered at a distance: base-only (no mips), renormalized-box
    /// (2×2 box, re-normalised), toksvig (Toksvig 2004), lean (Olano & Baker 2010), vmf
    /// (roughness from a von Mises–Fisher fit, Karis 2018) or geometric-specular-aa
    /// (Tokuyoshi & Kaplanyan 2019) [default: renormalized-box].
    #[arg(long, value_name = "NAME", value_parser = args::named::<MipFilter>())]
    pub mip_filter: Option<MipFilter>,
    #[command(flatten)]
    pub materials: MaterialArgs,
}

/// Texture conventions for every material and the shading model (viewer and `render`).
#[derive(clap::Args, Clone, Copy)]
pub struct MaterialArgs {
    /// Normal maps' green channel: opengl (+Y up the image) or directx (−Y); default: as loaded.
    #[arg(long, value_parser = args::named::<GreenAxis>())]
    pub normal_convention: Option<GreenAxis>,
    /// Normal maps' channel layout: rgb; rg (BC5: x, y in red, green, z rebuilt); ag (DXT5nm:
    /// x in alpha, y in green, z rebuilt); xray (X-Ray's bump pair: x, y, z in alpha, blue,
    /// green, gloss = red², plus bump#'s correction); default: as loaded.
    #[arg(long, value_parser = args::named::<NormalLayout>())]
    pub normal_layout: Option<NormalLayout>,
    /// Short for `--normal-layout rg`: normal maps store only red and green.
    #[arg(long, conflicts_with = "normal_layout")]
    pub two_channel: bool,
    /// Normal maps hold object-space (model-space) normals; no tangents are used.
    #[arg(long)]
    pub object_space: bool,
    /// Height maps store depth (white = deep).
    #[arg(long)]
    pub depth_map: bool,
    /// Metres spanned by a height map's full range (world units).
    #[arg(long, value_name = "METRES", value_parser = args::parse_positive)]
    pub height_range: Option<f32>,
    /// Height→normal kernel for every height map (re-makes its normal map). `--kernel` only
    /// makes the built-in brick map.
    #[arg(long, value_parser = args::named::<Kernel>())]
    pub height_kernel: Option<Kernel>,
    /// Height maps' border when differentiating: wrap (tiling) or clamp (re-makes the normal map).
    #[arg(long, value_parser = args::named::<Border>())]
    pub height_border: Option<Border>,
    /// Shading model: auto (each material's own: pbr for glTF, blinn-phong for OBJ and the
    /// built-in scene), blinn-phong, or pbr (glTF metallic-roughness) [default: auto].
    #[arg(long, value_parser = args::named_or_auto::<ShadingModel>())]
    pub shading: Option<AutoOr<ShadingModel>>,
    /// Detail normal maps' repeats per base UV unit [default: 8].
    #[arg(long, value_name = "TIMES", value_parser = args::parse_positive)]
    pub detail_tiling: Option<f32>,
    /// Detail normal maps' strength, as a normal map's scale (0 flat) [default: 1].
    #[arg(long, value_name = "S")]
    pub detail_strength: Option<f32>,
    /// How detail normal maps blend with the base normal map: auto (each material's own, rnm),
    /// linear, partial-derivative (slopes add), whiteout, udn, rnm (reoriented, Barré-Brisebois
    /// & Hill 2012) or surface-gradient (Mikkelsen 2020) [default: auto].
    #[arg(long, value_name = "NAME", value_parser = args::named_or_auto::<DetailBlend>())]
    pub detail_blend: Option<AutoOr<DetailBlend>>,
}

impl MaterialArgs {
    /// The conventions given, for every material.
    fn overrides(&self) -> MaterialOverrides {
        MaterialOverrides {
            green: self.normal_convention,
            layout: if self.two_channel { Some(NormalLayout::Rg) } else { self.normal_layout },
            object_space: self.object_space.then_some(true),
            depth_map: self.depth_map.then_some(true),
            height_range_m: self.height_range,
            kernel: self.height_kernel,
            border: self.height_border,
            // --mip-filter sets the scene option (SceneOptions::mip_filter) instead.
            mip_filter: None,
            detail_tiling: self.detail_tiling,
            detail_strength: self.detail_strength,
        }
    }
}

impl MethodArgs {
    /// Whether no method or convention flag was given (the viewer then restores its last state).
    #[cfg(feature = "ui")]
    pub fn is_empty(&self) -> bool {
        let m = &self.materials;
        self.tangents.is_none()
            && self.kernel.is_none()
            && self.bump_source.is_none()
            && self.mip_filter.is_none()
            && m.overrides().is_empty()
            && m.shading.is_none()
            && m.detail_blend.is_none()
    }

    /// The flags as commands on `state` (a preset's, say): only what was given changes, and
    /// conventions go over the state's all-materials ones field by field.
    pub fn commands(&self, state: &ViewerState) -> Vec<Command> {
        let mut commands = Vec::new();
        if let Some(AutoOr(method)) = self.tangents {
            commands.push(Command::SetTangentMethod(method));
        }
        if let Some(source) = self.bump_source {
            commands.push(Command::SetBumpSource(source));
        }
        if let Some(filter) = self.mip_filter {
            commands.push(Command::SetMipFilter(filter));
        }
        let overrides = self.materials.overrides();
        if !overrides.is_empty() {
            let overrides = overrides.over(state.scene_options.materials);
            commands.push(Command::SetMaterialOverrides { material: None, overrides });
        }
        if let Some(kernel) = self.kernel {
            commands.push(Command::SetKernel(kernel));
        }
        if let Some(AutoOr(model)) = self.materials.shading {
            commands.push(Command::SetShadingOverride(model));
        }
        if let Some(AutoOr(method)) = self.materials.detail_blend {
            commands.push(Command::SetDetailBlend(method));
        }
        commands
    }
}
