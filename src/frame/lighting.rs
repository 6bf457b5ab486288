//! In which space the lit views light a surface (world per pixel; tangent, as the ARB-era
//! shaders did; view, as the GLSL practicum does): the same formulas with the normal, light and
//! view vectors taken into world, tangent or view space first; and where a frame's light
//! markers are.

use super::{FrameParams, ShadingSettings};
use crate::scene::{LightKind, ShadingModel};

/// Where the lighting is computed. A pipeline variant of the lit views of tangent-space
/// normal-mapped surfaces (other surfaces have no tangent frame and light in world space).
/// Named `world`, `tangent`, `view`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, strum::IntoStaticStr, strum::VariantArray)]
#[strum(serialize_all = "kebab-case")]
pub enum LightingSpace {
    /// The map's normal through the per-pixel T, B, N into world space; light and view
    /// vectors per pixel in world space.
    #[default]
    World,
    /// As the ARB-era tangent-space shaders did: the light and view vectors taken into tangent
    /// space by the inverse of the triangle's T, B, N (from its positions and UVs, not
    /// orthogonalised; the identity where its UVs have no area) and normalised per pixel; the
    /// map's normal used as decoded.
    Tangent,
    /// As the GLSL practicum does: the map's normal through T, B, N, then with the light and
    /// view vectors rotated into view space by the camera's view matrix.
    View,
}

impl LightingSpace {
    /// The index the `LIGHTING_SPACE` pipeline constant takes.
    pub fn shader_index(self) -> u32 {
        self as u32
    }
}

/// How one surface is lit: the model its lights are shaded with and the space they are
/// computed in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SurfaceLighting {
    pub shading_model: ShadingModel,
    pub lighting_space: LightingSpace,
}

impl ShadingSettings {
    /// How a surface whose material shades with `material_model` is lit: with the frame's
    /// override of the model, else the material's; in the frame's lighting space when its
    /// normal comes from a tangent-space normal map through a tangent frame
    /// (`tangent_space_normal`) and the classic model lights it, else in world space (other
    /// surfaces have no tangent frame to light in). The chain and the draw planner both ask
    /// this, so the CPU twin and the pipeline chosen agree.
    pub fn surface_lighting(&self, material_model: ShadingModel, tangent_space_normal: bool) -> SurfaceLighting {
        let shading_model = self.shading_override.unwrap_or(material_model);
        let lighting_space = match (tangent_space_normal, shading_model) {
            (true, ShadingModel::BlinnPhong) => self.lighting_space,
            _ => LightingSpace::World,
        };
        SurfaceLighting { shading_model, lighting_space }
    }
}

impl FrameParams {
    /// Where light `index`'s marker is drawn and dragged: a point light's position; a
    /// directional light's half the camera distance from the camera target, towards the light.
    pub fn marker_position(&self, index: usize) -> glam::Vec3 {
        let light = &self.lights[index];
        match light.kind {
            LightKind::Point => light.position,
            LightKind::Directional => {
                let towards = crate::math::normalize_or(light.position, glam::Vec3::Y);
                self.camera.target + towards * (0.5 * self.camera.distance)
            }
        }
    }
}
