//! The scene uploads a renderer holds: set (uploaded here) or installed (uploaded elsewhere,
//! [`super::Uploader`]), and what the viewer asks of them.

use std::sync::Arc;

use super::scene_gpu::GpuScene;
use super::{ReferenceFrames, Renderer, SceneUpload, Uploader};
use crate::frame::{SceneOptions, SceneUploads};
use crate::prepare::PreparedScene;
use crate::scene::Scene;

impl Renderer {
    /// Replaces the scene with `scene` prepared with `options` ([`PreparedScene::new`]) and
    /// uploads what it uses. A split scene ([`Self::set_split_scene`]) is kept: replace or
    /// drop it too when the scene changes.
    pub fn set_scene(&mut self, scene: &Scene, options: SceneOptions) {
        self.set_prepared(Arc::new(PreparedScene::new(scene, &options)));
    }

    /// Replaces the scene with one prepared already, uploading it now (on this thread; an
    /// [`Uploader`] uploads on another).
    pub fn set_prepared(&mut self, prepared: Arc<PreparedScene>) {
        let upload = self.uploader().upload(prepared, ReferenceFrames::OnFirstUse);
        let split = self.held(true);
        self.install(upload, split);
    }

    /// Gives the split view's right half its own upload of `scene` made with `options` (two
    /// tangent methods, two conventions, two bump sources), or with `None` drops it, so the
    /// right half is drawn from the main scene again. Its notices are added to the main ones.
    pub fn set_split_scene(&mut self, scene: &Scene, options: Option<SceneOptions>) {
        self.set_split_prepared(options.map(|options| Arc::new(PreparedScene::new(scene, &options))));
    }

    /// [`Self::set_split_scene`] with a scene prepared already, uploaded now.
    pub fn set_split_prepared(&mut self, prepared: Option<Arc<PreparedScene>>) {
        let split = prepared.map(|prepared| self.uploader().upload(prepared, ReferenceFrames::OnFirstUse));
        split.iter().for_each(|split| self.count_new(split));
        self.split_scene = split.map(|s| s.0);
    }

    /// Something to upload scenes with on any thread, for [`Self::install`].
    pub fn uploader(&self) -> Uploader {
        Uploader { device: self.device.clone(), queue: self.queue.clone(), layouts: self.pipelines.layouts.clone() }
    }

    /// Shows `main`, and `split` as the split view's right half (`None`: drawn from `main`):
    /// a swap, nothing is uploaded here. The work of an upload not held already is added to
    /// the counters, so an upload kept (or moved between the halves) counts once. Returns the
    /// uploads no longer held, for the caller to free where it likes (freeing a large one
    /// takes milliseconds).
    pub fn install(&mut self, main: SceneUpload, split: Option<SceneUpload>) -> Vec<SceneUpload> {
        std::iter::once(&main).chain(&split).for_each(|upload| self.count_new(upload));
        self.notices = main.0.notices.clone();
        let old_main = self.scene.replace(main.0);
        let old_split = std::mem::replace(&mut self.split_scene, split.map(|s| s.0));
        let held = |old: &Arc<GpuScene>| self.scene.iter().chain(&self.split_scene).any(|h| Arc::ptr_eq(h, old));
        old_main.into_iter().chain(old_split).filter(|old| !held(old)).map(SceneUpload).collect()
    }

    /// Adds `upload`'s work to the counters unless it is held already.
    fn count_new(&mut self, upload: &SceneUpload) {
        if !self.scene.iter().chain(&self.split_scene).any(|held| Arc::ptr_eq(held, &upload.0)) {
            self.counters += upload.0.work;
        }
    }

    /// The main upload (`split_half` false) or the split view's right half's own one (true;
    /// `None` when it is drawn from the main one), to install again or hand to a job.
    pub fn held(&self, split_half: bool) -> Option<SceneUpload> {
        let held = if split_half { &self.split_scene } else { &self.scene };
        held.clone().map(SceneUpload)
    }

    /// [`Self::set_scene`] and [`Self::set_split_scene`] for what a viewer state asks.
    pub fn set_scene_uploads(&mut self, scene: &Scene, uploads: &SceneUploads) {
        self.set_scene(scene, uploads.main.clone());
        self.set_split_scene(scene, uploads.split_right.clone());
    }

    /// The scene options of the uploads the renderer holds, as [`Self::set_scene_uploads`] takes
    /// them (`None` before the first scene), to compare with what a viewer state asks.
    pub fn uploads(&self) -> Option<SceneUploads> {
        let options = |scene: &Arc<GpuScene>| scene.prepared.options.clone();
        let main = options(self.scene.as_ref()?);
        Some(SceneUploads { main, split_right: self.split_scene.as_ref().map(options) })
    }

    /// The prepared scene the main picture (`split_half` false) or the split view's right
    /// half (true; the main one when the right half has no upload of its own) is drawn from:
    /// what the probe of that picture wraps.
    pub fn prepared(&self, split_half: bool) -> Option<&Arc<PreparedScene>> {
        let split = self.split_scene.as_ref().filter(|_| split_half);
        split.or(self.scene.as_ref()).map(|s| &s.prepared)
    }

    /// How the textures of the main scene (or the split view's right half, `split_half`) went
    /// to the GPU: a file's own blocks or RGBA8, and their bytes.
    pub fn texture_uploads(&self, split_half: bool) -> &[super::texture_cache::TextureUpload] {
        let split = self.split_scene.as_ref().filter(|_| split_half);
        split.or(self.scene.as_ref()).map_or(&[], |s| &s.uploads)
    }

    /// What GPU displacement drew in the last frame of the main scene (or the split view's
    /// right half, `split_half`): its stats, `None` where nothing is displaced on the GPU.
    pub fn gpu_displacement(&self, split_half: bool) -> Option<super::tessellation::GpuDisplacementStats> {
        let split = self.split_scene.as_ref().filter(|_| split_half);
        split.or(self.scene.as_ref())?.tessellation.as_ref()?.stats()
    }

    /// The prepared scene of the main picture (or the split view's right half) with its meshes
    /// as the last frame drew them: with GPU displacement, its displaced meshes read back.
    pub fn drawn_prepared(&self, split_half: bool) -> Option<Arc<PreparedScene>> {
        let split = self.split_scene.as_ref().filter(|_| split_half);
        let scene = split.or(self.scene.as_ref())?;
        Some(match &scene.tessellation {
            Some(tessellation) => tessellation.drawn_prepared(&self.device, &self.queue, &scene.prepared),
            None => Arc::clone(&scene.prepared),
        })
    }

    /// The meshes GPU displacement made in the last frame, read back (`(index in the prepared
    /// scene's meshes, mesh)`); empty where nothing is displaced on the GPU.
    pub fn gpu_displaced_meshes(&self, split_half: bool) -> Result<Vec<(usize, crate::scene::Mesh)>, String> {
        let split = self.split_scene.as_ref().filter(|_| split_half);
        let Some(tessellation) = split.or(self.scene.as_ref()).and_then(|s| s.tessellation.as_ref()) else {
            return Ok(vec![]);
        };
        tessellation.read_back(&self.device, &self.queue)
    }
}
