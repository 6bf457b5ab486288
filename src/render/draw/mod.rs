//! A frame's drawing, by drawable, in the manner of rerun's re_renderer: each kind of thing
//! drawn has its own file — [`mesh`] (the surfaces), [`wireframe`], [`glyphs`] (T/B/N) and
//! [`markers`] (the lights) — with a `plan` that chooses its passes once from what changes per
//! draw (a scene upload and a half's shading) and a `record` that draws that plan with the
//! pipelines of the long-lived pool ([`Pipelines`]). [`HalfPlan`] is one half's plans: the
//! renderer builds their pipelines before the render pass and records them inside it.

pub mod glyphs;
pub mod markers;
pub mod mesh;
pub mod wireframe;

use super::pipelines::{Pass, PipelineKey, Pipelines};
use super::scene_gpu::GpuScene;
use crate::frame::{FrameParams, ShadingSettings};

/// One instance of a scene upload drawn with the pipeline of `pass`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct InstanceDraw {
    /// The index into [`GpuScene::instances`].
    pub instance: usize,
    pub pass: Pass,
}

/// The pool's pipelines for one target: its format and sample count complete their keys.
pub struct FramePipelines<'a> {
    pub pool: &'a Pipelines,
    pub format: wgpu::TextureFormat,
    pub samples: u32,
}

impl FramePipelines<'_> {
    /// The key of `pass` on this target.
    pub fn key(pass: Pass, format: wgpu::TextureFormat, samples: u32) -> PipelineKey {
        PipelineKey { pass, format, samples }
    }

    /// The pipeline of `pass`, built already ([`Pipelines::ensure`] with [`HalfPlan::passes`]).
    pub fn get(&self, pass: Pass) -> &wgpu::RenderPipeline {
        self.pool.get(&Self::key(pass, self.format, self.samples))
    }
}

/// What one half of a frame (or the whole of it) draws, in order: the meshes, then the
/// overlays over them (wireframe, glyphs), then the light markers.
pub struct HalfPlan {
    meshes: Vec<InstanceDraw>,
    wireframe: Vec<InstanceDraw>,
    glyphs: Vec<InstanceDraw>,
    markers: Option<markers::MarkerDraw>,
}

impl HalfPlan {
    /// Each drawable's plan for `scene` drawn with `shading`; `line_mode`: whether the device
    /// can draw lines (the wireframe needs it).
    pub fn new(scene: &GpuScene, shading: &ShadingSettings, params: &FrameParams, line_mode: bool) -> Self {
        HalfPlan {
            meshes: mesh::plan(scene, shading),
            wireframe: wireframe::plan(scene, shading, line_mode),
            glyphs: glyphs::plan(scene, shading),
            markers: markers::plan(shading, params),
        }
    }

    /// Every pass the plan draws with (some more than once).
    pub fn passes(&self) -> impl Iterator<Item = Pass> + '_ {
        let instances = self.meshes.iter().chain(&self.wireframe).chain(&self.glyphs);
        instances.map(|draw| draw.pass).chain(self.markers.as_ref().map(|_| markers::PASS))
    }

    /// Records the plan into `pass`, whose group 0 (the half's frame) is bound already.
    pub fn record(&self, pass: &mut wgpu::RenderPass, pipelines: &FramePipelines, scene: &GpuScene) {
        mesh::record(pass, pipelines, scene, &self.meshes);
        wireframe::record(pass, pipelines, scene, &self.wireframe);
        glyphs::record(pass, pipelines, scene, &self.glyphs);
        if let (Some(draw), Some(marker)) = (&self.markers, &scene.marker) {
            markers::record(pass, pipelines, marker, draw);
        }
    }
}
