//! The commands the UI produces (keys, panels, mouse); [`super::ViewerState::apply`] is where
//! they take effect.

use glam::{Vec2, Vec3};

use super::{LightCommand, SplitDifference};
use crate::frame::{BumpSource, LegacySettings, Mistake, Parallax, ShadingMode, ViewMode};
use crate::height::Kernel;
use crate::scene::{GreenAxis, MaterialOverrides, ShadingModel};
use crate::tangent::TangentMethod;
use crate::texture::MipFilter;

#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Command {
    SetBump(bool),
    ToggleBump,
    SetStrength(f32),
    /// Adds to the strength (the `[` / `]` keys), within [`STRENGTH_RANGE`](crate::frame::STRENGTH_RANGE).
    StepStrength(f32),
    SetView(ViewMode),
    CycleView,
    /// Moves the selected light (a directional light: the direction towards it).
    SetLightPosition(Vec3),
    /// Moves the selected light's marker ([`FrameParams::marker_position`]) parallel to the
    /// screen by a drag of `pixels` in a viewport `viewport_height` pixels tall, keeping its
    /// depth from the eye; a directional light then points from the target to the marker.
    DragLight {
        pixels: Vec2,
        viewport_height: f32,
    },
    SetLightOrbit(bool),
    ToggleLightOrbit,
    SetLightMarker(bool),
    /// Yaw and pitch increments, radians.
    OrbitCamera {
        d_yaw: f32,
        d_pitch: f32,
    },
    /// Multiplies the camera distance.
    Zoom(f32),
    PanCamera {
        pixels: Vec2,
        viewport_height: f32,
    },
    ResetCamera,
    /// Points the camera ([`OrbitCamera::point`](crate::scene::OrbitCamera::point)): yaw and pitch in radians (pitch clamped
    /// to ±89°), distance in metres (clamped to the zoom range), about the same target.
    PointCamera {
        yaw: f32,
        pitch: f32,
        distance: f32,
    },
    /// Advances animations by `seconds`.
    Tick(f32),
    /// Tangent frames by this method (`None`: the mesh's own, else MikkTSpace by meshoptimizer).
    SetTangentMethod(Option<TangentMethod>),
    SetBumpSource(BumpSource),
    /// How every material's normal map is mip-filtered (re-makes GPU data).
    SetMipFilter(MipFilter),
    /// The two methods of [`SplitDifference::MipFilter`].
    SetSplitMipFilters([MipFilter; 2]),
    /// The right half's format of [`SplitDifference::Compression`].
    SetSplitCompression(crate::bake::compressed_format::CompressedFormat),
    /// Height→normal kernel of the built-in brick normal map.
    SetKernel(Kernel),
    /// The Difference view's colour scale spans 0 to this many degrees.
    SetDifferenceRange(f32),
    /// Normal- and height-map conventions for one material (index into the scene's
    /// materials; they win over the viewer-wide ones field by field) or, with `material`
    /// `None`, for every material (re-makes GPU data).
    SetMaterialOverrides {
        material: Option<usize>,
        overrides: MaterialOverrides,
    },
    /// Shade every material with this model (`None`: each material's own); a uniform.
    SetShadingOverride(Option<ShadingModel>),
    /// Blend every detail normal map with this method (`None`: each material's own); a
    /// pipeline variant.
    SetDetailBlend(Option<crate::frame::DetailBlend>),
    /// The two methods of [`SplitDifference::DetailBlend`].
    SetSplitDetailBlends([crate::frame::DetailBlend; 2]),
    /// Bump × colour, bump only or colour only (keys 1/2/3); a uniform.
    SetShadingMode(ShadingMode),
    /// The wireframe overlay (a second pass).
    SetWireframe(bool),
    ToggleWireframe,
    /// T/B/N glyphs at vertices (key G; a line pass).
    SetGlyphs(bool),
    ToggleGlyphs,
    /// The split view on or off (key S).
    SetSplit(bool),
    ToggleSplit,
    /// What the split view's halves differ in.
    SetSplitDifference(SplitDifference),
    /// The divider's position, a fraction of the view's width (clamped to 0..1).
    SetSplitDivider(f32),
    /// The two views of [`SplitDifference::View`], left and right.
    SetSplitViews([ViewMode; 2]),
    /// The two strengths of [`SplitDifference::Strength`] (within [`STRENGTH_RANGE`](crate::frame::STRENGTH_RANGE)).
    SetSplitStrengths([f32; 2]),
    /// The two modes of [`SplitDifference::Mode`].
    SetSplitModes([ShadingMode; 2]),
    /// The two tangent methods of [`SplitDifference::Tangents`].
    SetSplitTangentMethods([TangentMethod; 2]),
    /// The two green conventions of [`SplitDifference::Convention`].
    SetSplitConventions([GreenAxis; 2]),
    /// The two bump sources of [`SplitDifference::BumpSource`].
    SetSplitBumpSources([BumpSource; 2]),
    /// The two techniques of [`SplitDifference::Parallax`].
    SetSplitParallax([Parallax; 2]),
    /// The two mistakes of [`SplitDifference::Mistake`].
    SetSplitMistakes([Mistake; 2]),
    /// Draw with a classic mistake (a pipeline variant).
    SetMistake(Mistake),
    /// A legacy look and DOT3's cube map face size (one of [`crate::frame::CUBE_MAP_SIZES`],
    /// else none).
    SetLegacy(LegacySettings),
    /// The two spaces of [`SplitDifference::LightingSpace`].
    SetSplitLightingSpaces([crate::frame::LightingSpace; 2]),
    /// The parallax technique (a uniform).
    SetParallax(Parallax),
    /// The search's layers `[min, max]`, each clamped to 1..=[`MAX_PARALLAX_LAYERS`].
    SetParallaxLayers([u32; 2]),
    /// Relief mapping's binary-search steps, clamped to 0..=[`MAX_PARALLAX_STEPS`].
    SetParallaxSteps(u32),
    /// The relief's depth in metres (`None`: each material's height range); a negative or
    /// non-finite depth is ignored.
    SetParallaxDepth(Option<f32>),
    /// The lights, the ambient light, the specular mode and shininess, the lighting space.
    Lighting(LightCommand),
    /// The searches' soft self-shadow strength (0 off), clamped to
    /// 0..=[`MAX_PARALLAX_SHADOW_STRENGTH`]; a non-finite value is ignored.
    SetParallaxShadows(f32),
    /// Displacement's CPU tessellation level (0 off), clamped to 0..=[`MAX_DISPLACEMENT_LEVEL`](crate::frame::MAX_DISPLACEMENT_LEVEL),
    /// GPU displacement off; it makes geometry, so it is a scene option.
    SetDisplacement(u32),
    /// Displacement on the GPU at this many pixels per edge (clamped to
    /// [`GPU_PIXELS_PER_EDGE`](crate::frame::GPU_PIXELS_PER_EDGE); a non-finite value is
    /// ignored), or `None`: back to the CPU level.
    SetGpuDisplacement(Option<f32>),
    /// The split view's [`SplitDifference::Displacement`]: the left half's parallax technique,
    /// the right half's displacement level (clamped to 1..=[`MAX_DISPLACEMENT_LEVEL`](crate::frame::MAX_DISPLACEMENT_LEVEL))
    /// or, when given, GPU displacement at this many pixels per edge instead.
    SetSplitDisplacement(Parallax, u32, Option<f32>),
}

impl Command {
    /// Whether the command moves only the camera or changes only the lights (what a lesson's
    /// grid shown live follows, [`crate::lessons::measure::LiveLook`]).
    pub fn moves_camera_or_lights(&self) -> bool {
        use Command::*;
        match self {
            OrbitCamera { .. } | Zoom(_) | PanCamera { .. } | ResetCamera | PointCamera { .. } => true,
            SetLightPosition(_) | DragLight { .. } | SetLightOrbit(_) | ToggleLightOrbit | Tick(_) => true,
            Lighting(light) => !matches!(
                light,
                LightCommand::SetSpecular(_) | LightCommand::SetShininess(_) | LightCommand::SetLightingSpace(_)
            ),
            _ => false,
        }
    }
}
