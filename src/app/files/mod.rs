//! Opening files in the viewer, as a state machine without a window: what a set of dropped or
//! chosen files means ([`plan_open`]: a mesh replaces the scene, an image fills a material
//! slot, chosen or guessed from its name by [`guess_slot`]), the [`Job`] that loads them (in
//! the controller's scene job), the recent-files list ([`RecentFiles`]) and the outcome of a
//! load ([`Files::finish`]).
//!
//! A scene is always re-made from its [`SceneFiles`] — the mesh file (or the built-in scene)
//! plus the texture files in its slots — and the built-in scene's kernel, so a texture drop and
//! a hot reload take the same path as opening a mesh, and a failure leaves the previous scene
//! and files untouched.

mod recent;

use std::path::{Path, PathBuf};

use bumpview::height::Kernel;
use bumpview::load::{SceneFiles, TextureSlot};
pub use recent::{RecentFiles, recent_file};

use super::watch::Debouncer;

/// Extensions of mesh files the loaders read (lower case).
const MESH_EXTENSIONS: [&str; 3] = ["gltf", "glb", "obj"];
/// Extensions of texture files the loaders read (lower case).
const IMAGE_EXTENSIONS: [&str; 8] = ["png", "jpg", "jpeg", "tga", "bmp", "webp", "dds", "ktx2"];
/// Files next to a mesh that it may read (buffers, materials, textures): a change to one of
/// them reloads the mesh.
const MESH_COMPANION_EXTENSIONS: [&str; 13] =
    ["gltf", "glb", "obj", "bin", "mtl", "png", "jpg", "jpeg", "tga", "bmp", "webp", "dds", "ktx2"];
/// The slot a texture file probably belongs in, from its name (case-insensitive):
/// `*normal*`, `*nrm*` or a `_n`/`-n` suffix → normal map; `*height*`, `*disp*`, `*bump*`,
/// `*depth*` → height map; `*rough*`, `*gloss*`, `*spec*` → gloss; anything else → colour.
pub fn guess_slot(path: &Path) -> TextureSlot {
    let stem = path.file_stem().map(|s| s.to_string_lossy().to_lowercase()).unwrap_or_default();
    let has = |words: &[&str]| words.iter().any(|w| stem.contains(w));
    if has(&["normal", "nrm"]) || stem.ends_with("_n") || stem.ends_with("-n") {
        TextureSlot::Normal
    } else if has(&["height", "disp", "bump", "depth"]) {
        TextureSlot::Height
    } else if has(&["rough", "gloss", "spec"]) {
        TextureSlot::Gloss
    } else {
        TextureSlot::Color
    }
}

/// What a file is to the viewer, by its extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FileKind {
    /// A glTF or OBJ mesh: replaces the scene.
    Mesh,
    /// An image: goes into a material slot.
    Image,
}

/// The kind of `path` by its extension (any case); `None` for anything else.
pub fn file_kind(path: &Path) -> Option<FileKind> {
    let extension = path.extension()?.to_string_lossy().to_ascii_lowercase();
    if MESH_EXTENSIONS.contains(&extension.as_str()) {
        Some(FileKind::Mesh)
    } else if IMAGE_EXTENSIONS.contains(&extension.as_str()) {
        Some(FileKind::Image)
    } else {
        None
    }
}

/// The file name of `path` for messages (the whole path when it has none).
pub fn file_name(path: &Path) -> String {
    path.file_name().unwrap_or(path.as_os_str()).to_string_lossy().into_owned()
}

/// Whether a change to `changed` on disk changes the scene made from `files` (absolute
/// paths): it is one of the files, or a buffer, material or texture file in the mesh's folder
/// (which the mesh may read).
pub fn affects(files: &SceneFiles, changed: &Path) -> bool {
    if files.paths().contains(&changed) {
        return true;
    }
    let companion = changed
        .extension()
        .is_some_and(|e| MESH_COMPANION_EXTENSIONS.contains(&e.to_string_lossy().to_ascii_lowercase().as_str()));
    companion && files.mesh.as_deref().and_then(Path::parent).is_some_and(|dir| changed.parent() == Some(dir))
}

/// Why a scene is loaded, which decides what happens to the view when it arrives.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Purpose {
    /// A new mesh: frame it with its default camera and light.
    Open,
    /// Same mesh, changed textures, files or kernel: camera, light and settings stay.
    Reload,
}

/// Files to load in a scene job and what to do with the scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Job {
    /// The files to load (absolute paths).
    pub files: SceneFiles,
    /// The built-in scene's brick-map kernel.
    pub kernel: Kernel,
    pub purpose: Purpose,
    /// What the spinner says is loading ("NAME").
    pub label: String,
    /// Files the user just opened, for the recent list once the load succeeded.
    pub opened: Vec<PathBuf>,
    /// What the panel says on success.
    pub done: String,
}

/// The job for files dropped on the window, chosen in a dialog or in the recent list. At most
/// one mesh: it replaces the scene (with empty slots). Images fill `slot` (the first image; a
/// drop on a slot button or that slot's dialog) or the slot [`guess_slot`] picks, on the mesh
/// or on the current scene's `current` files (built-in scene made with `kernel`). The error
/// names what cannot be opened.
pub fn plan_open(
    current: &SceneFiles,
    kernel: Kernel,
    paths: &[PathBuf],
    slot: Option<TextureSlot>,
) -> Result<Job, String> {
    let mut meshes = Vec::new();
    let mut images = Vec::new();
    for path in paths {
        match file_kind(path) {
            Some(FileKind::Mesh) => meshes.push(path),
            Some(FileKind::Image) => images.push(path),
            None => {
                return Err(format!(
                    "{}: not a mesh (.{}) or an image (.{})",
                    path.display(),
                    MESH_EXTENSIONS.join(", ."),
                    IMAGE_EXTENSIONS.join(", .")
                ));
            }
        }
    }
    let (mut files, purpose, mut notes) = match meshes.as_slice() {
        [] if images.is_empty() => return Err("no file to open".into()),
        [] => (current.clone(), Purpose::Reload, Vec::new()),
        [mesh] => {
            let files = SceneFiles { mesh: Some(absolute(mesh)), ..SceneFiles::default() };
            (files, Purpose::Open, vec![format!("opened {}", file_name(mesh))])
        }
        _ => {
            let names: Vec<_> = meshes.iter().map(|m| file_name(m)).collect();
            return Err(format!("{} meshes at once ({}): open one at a time", names.len(), names.join(", ")));
        }
    };
    for (i, image) in images.iter().enumerate() {
        let (target, how) = match slot.filter(|_| i == 0) {
            Some(chosen) => (chosen, "slot"),
            None => (guess_slot(image), "slot (guessed from the name)"),
        };
        files.set_texture(target, absolute(image));
        notes.push(format!("{} in the {} {how}", file_name(image), target.label()));
    }
    let opened: Vec<PathBuf> = meshes.iter().chain(&images).map(|p| absolute(p)).collect();
    let label = opened.iter().map(|p| file_name(p)).collect::<Vec<_>>().join(", ");
    Ok(Job { files, kernel, purpose, label, opened, done: notes.join("; ") })
}

/// `path` made absolute against the current directory (unchanged when that fails).
fn absolute(path: &Path) -> PathBuf {
    std::path::absolute(path).unwrap_or_else(|_| path.to_owned())
}

/// The last outcome the panel shows.
#[derive(Debug, Clone, PartialEq)]
pub enum Status {
    /// What was opened or reloaded.
    Done(String),
    /// Why a file could not be opened (the loader's message names the file); shown in the
    /// error colour.
    Failed(String),
}

impl Job {
    /// The job re-making the scene from `files` and `kernel` (hot reload, a kernel change, a
    /// preset's files); `done` is what the panel says on success.
    pub fn reload(files: SceneFiles, kernel: Kernel, done: String) -> Job {
        let label = files.paths().first().map_or_else(|| "built-in scene".to_owned(), |p| file_name(p));
        Job { files, kernel, purpose: Purpose::Reload, label, opened: vec![], done }
    }
}

/// The viewer's files: the current scene's files and kernel, the recent list, the status and
/// the hot-reload debouncer.
pub struct Files {
    /// What the current scene was made from (absolute paths).
    pub scene_files: SceneFiles,
    /// The built-in scene's brick-map kernel the current scene was made with.
    pub kernel: Kernel,
    pub recent: RecentFiles,
    pub status: Option<Status>,
    pub debouncer: Debouncer,
    /// Where the recent list is saved; `None`: not saved.
    recent_file: Option<PathBuf>,
}

impl Files {
    /// Files for a viewer showing the scene made from `scene_files` (absolute paths) and
    /// `kernel`, with the recent list read from `recent_file`.
    pub fn new(scene_files: SceneFiles, kernel: Kernel, recent_file: Option<PathBuf>) -> Files {
        let recent = recent_file.as_deref().map(RecentFiles::load).unwrap_or_default();
        Files { scene_files, kernel, recent, status: None, debouncer: Debouncer::default(), recent_file }
    }

    /// Puts the current scene's files (given on the command line) into the recent list and
    /// saves it; a failed save becomes the status.
    pub fn remember_scene_files(&mut self) {
        let files: Vec<PathBuf> = self.scene_files.paths().iter().map(|p| p.to_path_buf()).collect();
        if let Err(message) = self.remember(&files) {
            self.status = Some(Status::Failed(message));
        }
    }

    /// Puts `opened` into the recent list, first file first, and saves it. The error says
    /// why it could not be saved.
    fn remember(&mut self, opened: &[PathBuf]) -> Result<(), String> {
        for path in opened.iter().rev() {
            self.recent.push(path);
        }
        match &self.recent_file {
            Some(file) if !opened.is_empty() => {
                self.recent.save(file).map_err(|e| format!("recent list not saved: {}: {e}", file.display()))
            }
            _ => Ok(()),
        }
    }

    /// The job for what `paths` ask ([`plan_open`]); a plan error becomes the status.
    pub fn plan(&mut self, paths: &[PathBuf], slot: Option<TextureSlot>) -> Option<Job> {
        plan_open(&self.scene_files, self.kernel, paths, slot).map_err(|m| self.status = Some(Status::Failed(m))).ok()
    }

    /// Takes in a finished load: on success the files and kernel become the job's, the opened
    /// files go into the recent list (saved) and the status says what was done; on failure the
    /// status says why and nothing else changes.
    pub fn finish(&mut self, job: Job, outcome: Result<(), String>) {
        match outcome {
            Ok(()) => {
                let done = match self.remember(&job.opened) {
                    Ok(()) => job.done,
                    Err(message) => format!("{} ({message})", job.done),
                };
                self.scene_files = job.files;
                self.kernel = job.kernel;
                self.status = Some(Status::Done(done));
            }
            Err(message) => self.status = Some(Status::Failed(message)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn paths(names: &[&str]) -> Vec<PathBuf> {
        names.iter().map(PathBuf::from).collect()
    }

    #[test]
    fn slots_are_guessed_from_names() {
        let guess = |name: &str| guess_slot(Path::new(name));
        assert_eq!(guess("textures/Brick_Normal.png"), TextureSlot::Normal);
        assert_eq!(guess("wall_n.png"), TextureSlot::Normal);
        assert_eq!(guess("wall-N.TGA"), TextureSlot::Normal);
        assert_eq!(guess("rock_nrm.jpg"), TextureSlot::Normal);
        assert_eq!(guess("heightmap.png"), TextureSlot::Height);
        assert_eq!(guess("stone_DISP.png"), TextureSlot::Height);
        assert_eq!(guess("bump.bmp"), TextureSlot::Height);
        assert_eq!(guess("cube_depth.png"), TextureSlot::Height);
        assert_eq!(guess("metal_roughness.png"), TextureSlot::Gloss);
        assert_eq!(guess("gloss.png"), TextureSlot::Gloss);
        assert_eq!(guess("wall_spec.jpg"), TextureSlot::Gloss);
        assert_eq!(guess("albedo.png"), TextureSlot::Color);
        // "_n" only as a suffix: "brick_new" is not a normal map.
        assert_eq!(guess("brick_new.png"), TextureSlot::Color);
        assert_eq!(guess("noext"), TextureSlot::Color);
    }

    #[test]
    fn file_kinds_by_extension() {
        assert_eq!(file_kind(Path::new("a/Box.GLB")), Some(FileKind::Mesh));
        assert_eq!(file_kind(Path::new("spot.obj")), Some(FileKind::Mesh));
        assert_eq!(file_kind(Path::new("x.JPEG")), Some(FileKind::Image));
        assert_eq!(file_kind(Path::new("x.txt")), None);
        assert_eq!(file_kind(Path::new("gltf")), None);
    }

    #[test]
    fn a_mesh_opens_a_new_scene_and_images_fill_slots() {
        let current = SceneFiles { mesh: Some("/old.obj".into()), ..SceneFiles::default() };
        let job =
            plan_open(&current, Kernel::default(), &paths(&["/m/box.gltf", "/m/box_normal.png", "/m/paint.png"]), None)
                .unwrap();
        assert_eq!(job.purpose, Purpose::Open);
        assert_eq!(job.files.mesh.as_deref(), Some(Path::new("/m/box.gltf")));
        assert_eq!(job.files.normal.as_deref(), Some(Path::new("/m/box_normal.png")));
        assert_eq!(job.files.color.as_deref(), Some(Path::new("/m/paint.png")));
        assert_eq!(job.opened.len(), 3);
        assert!(job.done.contains("box_normal.png in the normal map slot (guessed"), "{}", job.done);

        // An image alone keeps the mesh and the other slots; a chosen slot wins over the name.
        let job =
            plan_open(&job.files, Kernel::default(), &paths(&["/t/wall_n.png"]), Some(TextureSlot::Height)).unwrap();
        assert_eq!(job.purpose, Purpose::Reload);
        assert_eq!(job.files.mesh.as_deref(), Some(Path::new("/m/box.gltf")));
        assert_eq!(job.files.height.as_deref(), Some(Path::new("/t/wall_n.png")));
        assert_eq!(job.files.normal.as_deref(), Some(Path::new("/m/box_normal.png")));
        assert_eq!(job.done, "wall_n.png in the height map slot");
    }

    #[test]
    fn unopenable_drops_are_errors_naming_the_file() {
        let current = SceneFiles::default();
        let plan = |names: &[&str]| plan_open(&current, Kernel::default(), &paths(names), None);
        let error = plan(&["/a/notes.txt"]).unwrap_err();
        assert!(error.starts_with("/a/notes.txt: not a mesh"), "{error}");
        let error = plan(&["/a.glb", "/b.obj"]).unwrap_err();
        assert!(error.contains("a.glb, b.obj"), "{error}");
        assert!(plan(&[]).is_err());
    }

    #[test]
    fn changes_to_the_mesh_its_folder_and_slot_files_count() {
        let files = SceneFiles {
            mesh: Some("/m/box.gltf".into()),
            color: Some("/t/paint.png".into()),
            ..SceneFiles::default()
        };
        let affected = |path: &str| affects(&files, Path::new(path));
        assert!(affected("/m/box.gltf"));
        assert!(affected("/m/box.bin"));
        assert!(affected("/m/box_normal.PNG"));
        assert!(affected("/t/paint.png"));
        assert!(!affected("/t/other.png"));
        assert!(!affected("/m/.box.gltf.swp"));
        assert!(!affected("/m/sub/box.bin"));
        assert!(!affects(&SceneFiles::default(), Path::new("/m/box.bin")));
    }

    #[test]
    fn a_finished_load_updates_files_recent_list_and_status() {
        let dir = std::env::temp_dir().join(format!("bumpview-files-{}", std::process::id()));
        let recent_file = dir.join("recent.txt");
        let mut files = Files::new(SceneFiles::default(), Kernel::default(), Some(recent_file.clone()));

        // Success: the files, recent list (saved) and status change.
        let job = files.plan(&paths(&["/m/good.obj"]), None).unwrap();
        files.finish(job, Ok(()));
        assert_eq!(files.scene_files.mesh.as_deref(), Some(Path::new("/m/good.obj")));
        assert_eq!(files.status, Some(Status::Done("opened good.obj".into())));
        assert_eq!(RecentFiles::load(&recent_file).paths(), [PathBuf::from("/m/good.obj")]);

        // Failure: the message is the status; files and recent list stay.
        let job = files.plan(&paths(&["/m/broken.obj"]), None).unwrap();
        files.finish(job, Err("/m/broken.obj: the file holds no triangles to draw".into()));
        assert_eq!(files.status, Some(Status::Failed("/m/broken.obj: the file holds no triangles to draw".into())));
        assert_eq!(files.scene_files.mesh.as_deref(), Some(Path::new("/m/good.obj")));
        assert_eq!(files.recent.paths().len(), 1);

        // A plan error is the status at once.
        assert!(files.plan(&paths(&["/m/readme.md"]), None).is_none());
        assert!(matches!(&files.status, Some(Status::Failed(m)) if m.contains("readme.md")));

        // A reload keeps the view and names the mesh.
        let job = Job::reload(files.scene_files.clone(), files.kernel, "reloaded".into());
        assert_eq!((job.purpose, job.label.as_str()), (Purpose::Reload, "good.obj"));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
