//! Uploading a prepared scene without the renderer: an [`Uploader`] (the renderer's device,
//! queue and bind group layouts; `Send + Sync`, cheap to clone) uploads on any thread, e.g. a
//! scene job's worker, and the [`SceneUpload`] it returns is shown by
//! [`super::Renderer::install`], a swap that uploads nothing.

use std::sync::Arc;

use super::pipelines::Layouts;
use super::scene_gpu::{self, GpuScene};
use crate::prepare::PreparedScene;

/// Uploads prepared scenes for one renderer ([`super::Renderer::uploader`]).
#[derive(Clone)]
pub struct Uploader {
    pub(super) device: wgpu::Device,
    pub(super) queue: wgpu::Queue,
    pub(super) layouts: Layouts,
}

/// What the Difference view needs of an upload, made with it or not.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ReferenceFrames {
    /// Made by the renderer when the Difference view is first drawn from the upload.
    OnFirstUse,
    /// Made with the upload (the Difference view is shown already).
    WithUpload,
}

impl Uploader {
    /// Uploads what `prepared` holds ([`scene_gpu::upload`]: geometry, tangent streams, T/B/N
    /// glyph lines, textures with their mip chains) and, with [`ReferenceFrames::WithUpload`],
    /// the Difference view's reference frames. Textures are written through the queue: they
    /// reach the GPU with the next submission of any thread.
    pub fn upload(&self, prepared: Arc<PreparedScene>, reference: ReferenceFrames) -> SceneUpload {
        let mut gpu = scene_gpu::upload(&self.device, &self.queue, &self.layouts, prepared);
        if reference == ReferenceFrames::WithUpload {
            let mut work = gpu.work;
            gpu.ensure_reference_frames(&self.device, &mut work);
            gpu.work = work;
        }
        SceneUpload(Arc::new(gpu))
    }
}

/// A prepared scene on the GPU, to draw once installed ([`super::Renderer::install`]). Clones
/// share the upload; two are equal when they are the same upload.
#[derive(Clone)]
pub struct SceneUpload(pub(super) Arc<GpuScene>);

impl SceneUpload {
    /// The prepared scene uploaded.
    pub fn prepared(&self) -> &Arc<PreparedScene> {
        &self.0.prepared
    }
}

impl PartialEq for SceneUpload {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

impl std::fmt::Debug for SceneUpload {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SceneUpload").field("options", &self.0.prepared.options).finish_non_exhaustive()
    }
}
