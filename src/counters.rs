//! Counts of the work the core does, so tests can prove that a scene gets only what it needs.

/// Monotonic counters owned by a [`crate::render::Renderer`].
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
pub struct WorkCounters {
    /// Vertex tangent frames generated with MikkTSpace (frames supplied by a mesh are not counted).
    pub tangent_frames_generated: u64,
    /// Prepared scenes uploaded to the GPU (a main scene or a split view's right half).
    pub scenes_uploaded: u64,
    /// Textures uploaded to the GPU (each mip chain counts once).
    pub textures_uploaded: u64,
    /// Render pipelines compiled (each variant once; later uses hit the cache).
    pub pipelines_built: u64,
    /// Frames drawn by [`crate::render::Renderer::render`].
    pub frames_drawn: u64,
}

impl std::ops::AddAssign for WorkCounters {
    fn add_assign(&mut self, other: WorkCounters) {
        self.tangent_frames_generated += other.tangent_frames_generated;
        self.scenes_uploaded += other.scenes_uploaded;
        self.textures_uploaded += other.textures_uploaded;
        self.pipelines_built += other.pipelines_built;
        self.frames_drawn += other.frames_drawn;
    }
}
