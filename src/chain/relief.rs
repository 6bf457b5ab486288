//! The parallax step of [`super::shade`] at one fragment, as `shaders/parallax.wgsl` runs it
//! around the formulas of [`super::parallax`]: the march at the interpolated UV (the height
//! map read with that UV's footprint), the UV and footprint the other textures are read with
//! (the shifted UV's derivatives: every pixel of the quad marches with the fragment's own
//! position and UV derivatives), and each light dimmed by the relief's soft self-shadow
//! (`parallax_light_visibility`).

use glam::{Vec2, Vec3};

use super::ChainValues;
use super::fragment::{Footprint, Fragment, Map, Varyings};
use super::parallax::{March, MarchInputs, light_in_tangent_space, march, soft_shadow};
use super::read::{relief_cone, relief_height};
use crate::frame::FrameParams;
use crate::math::normalize_or;
use crate::scene::{MAX_LIGHTS, Material, Wrap};
use crate::shading::lights::incident;

/// The parallax step at a fragment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Step {
    /// The march and its inputs; `None`: parallax off, depth 0, no height map bound, or no
    /// quad derivatives.
    pub marched: Option<(March, MarchInputs)>,
    /// The UV the other textures are read at and its footprint.
    pub uv: Vec2,
    pub footprint: Footprint,
    /// The height map's footprint (the interpolated UV's derivatives).
    pub height_footprint: Footprint,
}

/// The parallax march at a probed or referenced point, as the chain shows it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MarchValues {
    /// The unit direction to the eye in tangent space `(V·T, V·B, V·N)`; `None` without a
    /// tangent frame.
    pub view_tangent: Option<Vec3>,
    /// Layers of the linear search (0 for the offset techniques) and the first layer at or
    /// below the relief.
    pub layers: u32,
    pub layer_hit: u32,
    /// The UV the textures are read at, and its shift from the interpolated UV.
    pub uv: Vec2,
    pub shift: Vec2,
    /// The depth reached along the ray, 0..1 of the relief's depth.
    pub depth: f32,
    /// The height map at the shifted UV, 0..1 (white = high, a depth map flipped).
    pub height: f32,
    /// The share of each of the frame's lights (by index) reaching the point past the
    /// relief's own shadow ([`soft_shadow`]; 1 without shadows or light).
    pub light_visibility: [f32; MAX_LIGHTS],
}

/// The parallax step of `frame` on `material` at the fragment (`at` its varyings, `facing`
/// ±1 for a front or back face).
pub fn step(material: &Material, fragment: &impl Fragment, at: &Varyings, facing: f32, frame: &FrameParams) -> Step {
    let parallax = &frame.shading.parallax;
    let depth_m = parallax.depth_m.map_or(material.height_map.as_ref().map_or(0.0, |h| h.range_m), |d| d.max(0.0));
    let interpolated = fragment.derivatives(|v| v.uv);
    let unshifted = Step { marched: None, uv: at.uv, footprint: interpolated, height_footprint: interpolated };
    let on = parallax.technique.shifts() && depth_m != 0.0 && fragment.size(Map::Height).is_some();
    let Some(((dp_dx, dp_dy), (duv_dx, duv_dy))) =
        on.then(|| fragment.derivatives(|v| v.position)).flatten().zip(interpolated)
    else {
        return unshifted;
    };
    let detail = material.detail_wrap;
    let clamp = [detail.u == Wrap::ClampToEdge, detail.v == Wrap::ClampToEdge];
    let height = |uv| relief_height(material, fragment, uv, interpolated);
    let cone = |uv| relief_cone(material, fragment, uv);
    let eye = frame.camera.eye();
    let march_at = |v: &Varyings| {
        let normal = normalize_or(v.world_normal, Vec3::Z) * facing;
        let view_dir = normalize_or(eye - v.position, normal);
        let inputs = MarchInputs { uv: v.uv, normal, view_dir, dp_dx, dp_dy, duv_dx, duv_dy, depth_m, clamp };
        (march(parallax, &inputs, height, cone), inputs)
    };
    let marched = march_at(at);
    let footprint = fragment.derivatives(|v| march_at(v).0.uv);
    Step { marched: Some(marched), uv: marched.0.uv, footprint, height_footprint: interpolated }
}

/// `frame` with each light's intensity times its share past the relief's soft shadow at the
/// march's hit (from the point at `position`), and the shares; `frame` unchanged and all 1
/// without a march.
pub fn shadowed(
    material: &Material,
    fragment: &impl Fragment,
    step: &Step,
    position: Vec3,
    frame: &FrameParams,
) -> (FrameParams, [f32; MAX_LIGHTS]) {
    let mut dimmed = *frame;
    let mut visibility = [1.0; MAX_LIGHTS];
    if let Some((hit, inputs)) = &step.marched {
        let height = |uv| relief_height(material, fragment, uv, step.height_footprint);
        for (light, share) in dimmed.lights.as_mut_slice().iter_mut().zip(&mut visibility) {
            let l = incident(light, position, inputs.normal).direction;
            *share = soft_shadow(&frame.shading.parallax, inputs, hit, light_in_tangent_space(inputs, l), height);
            light.intensity *= *share;
        }
    }
    (dimmed, visibility)
}

/// What the chain shows of the march: the view direction in the chain's frame (`values`), the
/// height at the hit read again.
pub fn values(
    material: &Material,
    fragment: &impl Fragment,
    step: &Step,
    light_visibility: [f32; MAX_LIGHTS],
    values: &ChainValues,
) -> Option<MarchValues> {
    let (m, _) = step.marched?;
    let v = values.view_dir;
    Some(MarchValues {
        view_tangent: values
            .tangent
            .zip(values.bitangent)
            .map(|(t, b)| Vec3::new(v.dot(t), v.dot(b), v.dot(values.normal))),
        layers: m.layers,
        layer_hit: m.layer_hit,
        uv: m.uv,
        shift: m.shift,
        depth: m.depth,
        height: relief_height(material, fragment, m.uv, step.height_footprint),
        light_visibility,
    })
}
