//! Opening files in the viewer, as a state machine without a window: what a set of dropped or
//! chosen files means ([`plan_open`]: a mesh replaces the scene, an image fills a material
//! slot, chosen or guessed from its name by [`guess_slot`]), loading on a worker thread
//! ([`Loader`]), the recent-files list ([`RecentFiles`]), hot-reload debouncing
//! ([`Debouncer`]) and the outcome of a load ([`Files::finish`]).
//!
//! A scene is always re-made from its [`Source`] — the mesh file (or the built-in scene) plus
//! the texture files in its slots — so a texture drop and a hot reload take the same path as
//! opening a mesh, and a failure leaves the previous scene and source untouched.

use std::path::{Path, PathBuf};
use std::sync::{Arc, mpsc};
use std::time::{Duration, Instant};

use bumpview::height::Kernel;
use bumpview::load::{LoadError, TextureSlots, load_scene, replace_textures};
use bumpview::scene::Scene;
use bumpview::scene::builtin::teaching_scene_with_kernel;

/// Extensions of mesh files the loaders read (lower case).
const MESH_EXTENSIONS: [&str; 3] = ["gltf", "glb", "obj"];
/// Extensions of texture files the loaders read (lower case).
const IMAGE_EXTENSIONS: [&str; 5] = ["png", "jpg", "jpeg", "tga", "bmp"];
/// Files next to a mesh that it may read (buffers, materials, textures): a change to one of
/// them reloads the mesh.
const MESH_COMPANION_EXTENSIONS: [&str; 9] = ["gltf", "glb", "obj", "bin", "mtl", "png", "jpg", "jpeg", "tga"];
/// How many files the recent list keeps.
pub const RECENT_MAX: usize = 8;
/// Quiet time after the last change on disk before a hot reload: editors and exporters write
/// a file in several steps (truncate, write, rename), which must not each cause a load.
pub const RELOAD_DEBOUNCE: Duration = Duration::from_millis(200);

/// A material texture slot.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Slot {
    /// sRGB base colour.
    Color,
    /// Tangent-space normal map.
    Normal,
    /// Height map (white = high); also becomes the normal map unless one is given.
    Height,
    /// Gloss/specular map.
    Gloss,
}

impl Slot {
    /// Every slot, in the panel's order.
    pub const ALL: [Slot; 4] = [Slot::Color, Slot::Normal, Slot::Height, Slot::Gloss];

    /// The slot's name in the panel and in messages.
    pub fn label(self) -> &'static str {
        match self {
            Slot::Color => "colour",
            Slot::Normal => "normal map",
            Slot::Height => "height map",
            Slot::Gloss => "gloss",
        }
    }

    /// The file in this slot of `slots`.
    pub fn get(self, slots: &TextureSlots) -> Option<&Path> {
        match self {
            Slot::Color => slots.color.as_deref(),
            Slot::Normal => slots.normal.as_deref(),
            Slot::Height => slots.height.as_deref(),
            Slot::Gloss => slots.gloss.as_deref(),
        }
    }

    /// Puts `path` into this slot of `slots`.
    fn set(self, slots: &mut TextureSlots, path: PathBuf) {
        let field = match self {
            Slot::Color => &mut slots.color,
            Slot::Normal => &mut slots.normal,
            Slot::Height => &mut slots.height,
            Slot::Gloss => &mut slots.gloss,
        };
        *field = Some(path);
    }
}

/// The slot a texture file probably belongs in, from its name (case-insensitive):
/// `*normal*`, `*nrm*` or a `_n`/`-n` suffix → normal map; `*height*`, `*disp*`, `*bump*`,
/// `*depth*` → height map; `*rough*`, `*gloss*`, `*spec*` → gloss; anything else → colour.
pub fn guess_slot(path: &Path) -> Slot {
    let stem = path.file_stem().map(|s| s.to_string_lossy().to_lowercase()).unwrap_or_default();
    let has = |words: &[&str]| words.iter().any(|w| stem.contains(w));
    if has(&["normal", "nrm"]) || stem.ends_with("_n") || stem.ends_with("-n") {
        Slot::Normal
    } else if has(&["height", "disp", "bump", "depth"]) {
        Slot::Height
    } else if has(&["rough", "gloss", "spec"]) {
        Slot::Gloss
    } else {
        Slot::Color
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

/// What a scene is made from: a mesh file (or the built-in scene) and the texture files in
/// its slots. Paths are absolute, so that file-change events match them.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Source {
    /// The mesh file; `None`: the built-in teaching scene.
    pub mesh: Option<PathBuf>,
    /// Texture files put into every material's slots.
    pub slots: TextureSlots,
    /// Height→normal kernel of the built-in scene's brick normal map.
    pub kernel: Kernel,
}

impl Source {
    /// Loads the scene (on a worker thread; this reads files and may take a while).
    pub fn build(&self) -> Result<Scene, LoadError> {
        let mut scene = match &self.mesh {
            Some(path) => load_scene(path)?,
            None => teaching_scene_with_kernel(self.kernel),
        };
        replace_textures(&mut scene, &self.slots)?;
        Ok(scene)
    }

    /// Every file the source names: the mesh and the slot textures.
    pub fn files(&self) -> Vec<&Path> {
        self.mesh.iter().map(PathBuf::as_path).chain(Slot::ALL.iter().filter_map(|s| s.get(&self.slots))).collect()
    }

    /// Whether a change to `changed` on disk changes the scene: it is one of [`Self::files`], or
    /// a buffer, material or texture file in the mesh's folder (which the mesh may read).
    pub fn is_affected_by(&self, changed: &Path) -> bool {
        if self.files().contains(&changed) {
            return true;
        }
        let companion = changed
            .extension()
            .is_some_and(|e| MESH_COMPANION_EXTENSIONS.contains(&e.to_string_lossy().to_ascii_lowercase().as_str()));
        companion && self.mesh.as_deref().and_then(Path::parent).is_some_and(|dir| changed.parent() == Some(dir))
    }
}

/// Why a scene is loaded, which decides what happens to the view when it arrives.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Purpose {
    /// A new mesh: frame it with its default camera and light.
    Open,
    /// Same mesh, changed textures, files or kernel: camera, light and settings stay.
    Reload,
}

/// A scene to load on the worker thread and what to do with it.
#[derive(Debug, Clone, PartialEq)]
pub struct Job {
    pub source: Source,
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
/// or on the current scene. The error names what cannot be opened.
pub fn plan_open(current: &Source, paths: &[PathBuf], slot: Option<Slot>) -> Result<Job, String> {
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
    let (mut source, purpose, mut notes) = match meshes.as_slice() {
        [] if images.is_empty() => return Err("no file to open".into()),
        [] => (current.clone(), Purpose::Reload, Vec::new()),
        [mesh] => {
            let source = Source { mesh: Some(absolute(mesh)), slots: TextureSlots::default(), kernel: current.kernel };
            (source, Purpose::Open, vec![format!("opened {}", file_name(mesh))])
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
        target.set(&mut source.slots, absolute(image));
        notes.push(format!("{} in the {} {how}", file_name(image), target.label()));
    }
    let opened: Vec<PathBuf> = meshes.iter().chain(&images).map(|p| absolute(p)).collect();
    let label = opened.iter().map(|p| file_name(p)).collect::<Vec<_>>().join(", ");
    Ok(Job { source, purpose, label, opened, done: notes.join("; ") })
}

/// `path` made absolute against the current directory (unchanged when that fails).
fn absolute(path: &Path) -> PathBuf {
    std::path::absolute(path).unwrap_or_else(|_| path.to_owned())
}

/// Makes a scene from a source: [`Source::build`], or a fake in tests.
pub type BuildFn = Arc<dyn Fn(&Source) -> Result<Scene, LoadError> + Send + Sync>;

/// A job's outcome from the worker: the scene or the loader's one-line message.
#[derive(Debug, Clone, PartialEq)]
pub struct Finished {
    pub job: Job,
    pub result: Result<Scene, String>,
}

/// Loads scenes on worker threads, one job at a time as far as the UI is concerned: a new job
/// supersedes the one in flight, whose result is then dropped when it arrives.
pub struct Loader {
    build: BuildFn,
    sender: mpsc::Sender<(u64, Finished)>,
    receiver: mpsc::Receiver<(u64, Finished)>,
    /// Number of the latest job started.
    generation: u64,
    /// The latest job's label while it runs.
    busy: Option<String>,
}

impl Loader {
    /// A loader that makes scenes with `build`.
    pub fn new(build: BuildFn) -> Loader {
        let (sender, receiver) = mpsc::channel();
        Loader { build, sender, receiver, generation: 0, busy: None }
    }

    /// Starts `job` on a new thread; `wake` is called from that thread when it is done (the
    /// viewer asks for a repaint, so the result is picked up at once). The error says why no
    /// thread could be started.
    pub fn start(&mut self, job: Job, wake: impl Fn() + Send + 'static) -> Result<(), String> {
        self.generation += 1;
        let label = job.label.clone();
        let (generation, build, sender) = (self.generation, Arc::clone(&self.build), self.sender.clone());
        let spawned = std::thread::Builder::new().name("bumpview-load".into()).spawn(move || {
            // A loader bug must not leave the spinner turning forever: a panic becomes a message.
            let built = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| build(&job.source)));
            let result = match built {
                Ok(result) => result.map_err(|e| e.to_string()),
                Err(panic) => Err(format!("{}: the loader failed (a bug): {}", job.label, panic_message(&*panic))),
            };
            // The receiver is gone only when the viewer closed.
            let _ = sender.send((generation, Finished { job, result }));
            wake();
        });
        self.busy = spawned.is_ok().then_some(label);
        spawned.map(drop).map_err(|e| format!("could not start a loading thread: {e}"))
    }

    /// The label of the job in flight, if any.
    pub fn busy(&self) -> Option<&str> {
        self.busy.as_deref()
    }

    /// The latest job's outcome once it has arrived; older jobs' outcomes are dropped.
    pub fn poll(&mut self) -> Option<Finished> {
        while let Ok((generation, finished)) = self.receiver.try_recv() {
            if generation == self.generation {
                self.busy = None;
                return Some(finished);
            }
        }
        None
    }
}

/// The text of a panic's payload (a `&str` or `String`, as `panic!` makes).
fn panic_message(payload: &(dyn std::any::Any + Send)) -> &str {
    payload.downcast_ref::<&str>().copied().or(payload.downcast_ref::<String>().map(String::as_str)).unwrap_or("panic")
}

/// The most recently opened files, newest first, at most [`RECENT_MAX`].
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RecentFiles {
    paths: Vec<PathBuf>,
}

impl RecentFiles {
    /// The files, newest first.
    pub fn paths(&self) -> &[PathBuf] {
        &self.paths
    }

    /// Puts `path` first (moving it if it is there already) and drops the oldest beyond
    /// [`RECENT_MAX`]. Paths that cannot be written as one line of UTF-8 are not kept.
    pub fn push(&mut self, path: &Path) {
        if path.to_str().is_none_or(|s| s.is_empty() || s.contains(['\n', '\r'])) {
            return;
        }
        self.paths.retain(|p| p != path);
        self.paths.insert(0, path.to_owned());
        self.paths.truncate(RECENT_MAX);
    }

    /// Parses the file format: one path per line, newest first; blank lines are skipped.
    pub fn parse(text: &str) -> RecentFiles {
        let mut recent = RecentFiles::default();
        for line in text.lines().rev().map(str::trim_end).filter(|l| !l.is_empty()) {
            recent.push(Path::new(line));
        }
        recent
    }

    /// The file format of [`Self::parse`].
    pub fn to_text(&self) -> String {
        self.paths.iter().filter_map(|p| p.to_str()).map(|p| format!("{p}\n")).collect()
    }

    /// Reads the list from `file`; a missing or unreadable file (or one that is not UTF-8) is an
    /// empty list.
    pub fn load(file: &Path) -> RecentFiles {
        std::fs::read_to_string(file).map(|t| RecentFiles::parse(&t)).unwrap_or_default()
    }

    /// Writes the list to `file` atomically ([`bumpview::atomic::write_atomically`]; the folder
    /// is created if missing), so a crash leaves the old list or the new.
    pub fn save(&self, file: &Path) -> std::io::Result<()> {
        if let Some(dir) = file.parent().filter(|d| !d.as_os_str().is_empty()) {
            std::fs::create_dir_all(dir)?;
        }
        bumpview::atomic::write_bytes_atomically(file, self.to_text().as_bytes())
    }
}

/// Where the recent list lives: `$XDG_CONFIG_HOME/bumpview/recent.txt`, else
/// `$HOME/.config/bumpview/recent.txt` (`%APPDATA%` on Windows); `None` without either.
pub fn recent_file() -> Option<PathBuf> {
    let absolute_var = |name| std::env::var_os(name).map(PathBuf::from).filter(|p| p.is_absolute());
    let config = absolute_var("XDG_CONFIG_HOME")
        .or_else(|| absolute_var("HOME").map(|home| home.join(".config")))
        .or_else(|| absolute_var("APPDATA"))?;
    Some(config.join("bumpview").join("recent.txt"))
}

/// Waits for file changes to settle: each change pushes the deadline [`RELOAD_DEBOUNCE`] on.
#[derive(Debug, Default)]
pub struct Debouncer {
    due: Option<Instant>,
}

impl Debouncer {
    /// A change happened at `now`.
    pub fn changed(&mut self, now: Instant) {
        self.due = Some(now + RELOAD_DEBOUNCE);
    }

    /// True once, when the changes have settled by `now`.
    pub fn fire(&mut self, now: Instant) -> bool {
        let settled = self.due.is_some_and(|due| now >= due);
        if settled {
            self.due = None;
        }
        settled
    }

    /// Time left until the changes settle, while waiting.
    pub fn remaining(&self, now: Instant) -> Option<Duration> {
        self.due.map(|due| due.saturating_duration_since(now))
    }
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

/// The viewer's files: the current scene's source, the loader, the recent list and the status.
pub struct Files {
    pub source: Source,
    pub recent: RecentFiles,
    pub status: Option<Status>,
    pub loader: Loader,
    pub debouncer: Debouncer,
    /// Where the recent list is saved; `None`: not saved.
    recent_file: Option<PathBuf>,
}

impl Files {
    /// Files for a viewer showing `source`, with the recent list read from `recent_file`.
    pub fn new(source: Source, build: BuildFn, recent_file: Option<PathBuf>) -> Files {
        let recent = recent_file.as_deref().map(RecentFiles::load).unwrap_or_default();
        Files { source, recent, status: None, loader: Loader::new(build), debouncer: Debouncer::default(), recent_file }
    }

    /// Puts the files of the current source (given on the command line) into the recent
    /// list and saves it; a failed save becomes the status.
    pub fn remember_source(&mut self) {
        let files: Vec<PathBuf> = self.source.files().iter().map(|p| p.to_path_buf()).collect();
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

    /// Starts loading what `paths` ask for ([`plan_open`]); a plan error becomes the status.
    pub fn open(&mut self, paths: &[PathBuf], slot: Option<Slot>, wake: impl Fn() + Send + 'static) {
        match plan_open(&self.source, paths, slot) {
            Ok(job) => self.start(job, wake),
            Err(message) => self.status = Some(Status::Failed(message)),
        }
    }

    /// Starts re-making the current scene from `source` (hot reload, a kernel change).
    pub fn reload(&mut self, source: Source, done: String, wake: impl Fn() + Send + 'static) {
        let label = source.files().first().map_or_else(|| "built-in scene".to_owned(), |p| file_name(p));
        self.start(Job { source, purpose: Purpose::Reload, label, opened: vec![], done }, wake);
    }

    /// Starts `job`; a thread that cannot be started becomes the status.
    fn start(&mut self, job: Job, wake: impl Fn() + Send + 'static) {
        if let Err(message) = self.loader.start(job, wake) {
            self.status = Some(Status::Failed(message));
        }
    }

    /// Takes in a finished load: on success the source becomes the job's, the opened files
    /// go into the recent list (saved) and the new scene is returned with its purpose; on
    /// failure the status says why and nothing else changes.
    pub fn finish(&mut self, finished: Finished) -> Option<(Scene, Purpose)> {
        let Finished { job, result } = finished;
        match result {
            Ok(scene) => {
                let done = match self.remember(&job.opened) {
                    Ok(()) => job.done,
                    Err(message) => format!("{} ({message})", job.done),
                };
                self.source = job.source;
                self.status = Some(Status::Done(done));
                Some((scene, job.purpose))
            }
            Err(message) => {
                self.status = Some(Status::Failed(message));
                None
            }
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
        assert_eq!(guess("textures/Brick_Normal.png"), Slot::Normal);
        assert_eq!(guess("wall_n.png"), Slot::Normal);
        assert_eq!(guess("wall-N.TGA"), Slot::Normal);
        assert_eq!(guess("rock_nrm.jpg"), Slot::Normal);
        assert_eq!(guess("heightmap.png"), Slot::Height);
        assert_eq!(guess("stone_DISP.png"), Slot::Height);
        assert_eq!(guess("bump.bmp"), Slot::Height);
        assert_eq!(guess("cube_depth.png"), Slot::Height);
        assert_eq!(guess("metal_roughness.png"), Slot::Gloss);
        assert_eq!(guess("gloss.png"), Slot::Gloss);
        assert_eq!(guess("wall_spec.jpg"), Slot::Gloss);
        assert_eq!(guess("albedo.png"), Slot::Color);
        // "_n" only as a suffix: "brick_new" is not a normal map.
        assert_eq!(guess("brick_new.png"), Slot::Color);
        assert_eq!(guess("noext"), Slot::Color);
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
        let current = Source { mesh: Some("/old.obj".into()), ..Source::default() };
        let job = plan_open(&current, &paths(&["/m/box.gltf", "/m/box_normal.png", "/m/paint.png"]), None).unwrap();
        assert_eq!(job.purpose, Purpose::Open);
        assert_eq!(job.source.mesh.as_deref(), Some(Path::new("/m/box.gltf")));
        assert_eq!(job.source.slots.normal.as_deref(), Some(Path::new("/m/box_normal.png")));
        assert_eq!(job.source.slots.color.as_deref(), Some(Path::new("/m/paint.png")));
        assert_eq!(job.opened.len(), 3);
        assert!(job.done.contains("box_normal.png in the normal map slot (guessed"), "{}", job.done);

        // An image alone keeps the mesh and the other slots; a chosen slot wins over the name.
        let job = plan_open(&job.source, &paths(&["/t/wall_n.png"]), Some(Slot::Height)).unwrap();
        assert_eq!(job.purpose, Purpose::Reload);
        assert_eq!(job.source.mesh.as_deref(), Some(Path::new("/m/box.gltf")));
        assert_eq!(job.source.slots.height.as_deref(), Some(Path::new("/t/wall_n.png")));
        assert_eq!(job.source.slots.normal.as_deref(), Some(Path::new("/m/box_normal.png")));
        assert_eq!(job.done, "wall_n.png in the height map slot");
    }

    #[test]
    fn unopenable_drops_are_errors_naming_the_file() {
        let current = Source::default();
        let error = plan_open(&current, &paths(&["/a/notes.txt"]), None).unwrap_err();
        assert!(error.starts_with("/a/notes.txt: not a mesh"), "{error}");
        let error = plan_open(&current, &paths(&["/a.glb", "/b.obj"]), None).unwrap_err();
        assert!(error.contains("a.glb, b.obj"), "{error}");
        assert!(plan_open(&current, &[], None).is_err());
    }

    #[test]
    fn changes_to_the_mesh_its_folder_and_slot_files_count() {
        let source = Source {
            mesh: Some("/m/box.gltf".into()),
            slots: TextureSlots { color: Some("/t/paint.png".into()), ..Default::default() },
            ..Source::default()
        };
        assert!(source.is_affected_by(Path::new("/m/box.gltf")));
        assert!(source.is_affected_by(Path::new("/m/box.bin")));
        assert!(source.is_affected_by(Path::new("/m/box_normal.PNG")));
        assert!(source.is_affected_by(Path::new("/t/paint.png")));
        assert!(!source.is_affected_by(Path::new("/t/other.png")));
        assert!(!source.is_affected_by(Path::new("/m/.box.gltf.swp")));
        assert!(!source.is_affected_by(Path::new("/m/sub/box.bin")));
        assert!(!Source::default().is_affected_by(Path::new("/m/box.bin")));
    }

    #[test]
    fn recent_list_keeps_eight_newest_without_duplicates() {
        let mut recent = RecentFiles::default();
        for i in 0..10 {
            recent.push(Path::new(&format!("/f{i}.obj")));
        }
        recent.push(Path::new("/f5.obj"));
        recent.push(Path::new("/bad\nname.obj"));
        let names: Vec<_> = recent.paths().iter().map(|p| p.to_str().unwrap()).collect();
        assert_eq!(names, ["/f5.obj", "/f9.obj", "/f8.obj", "/f7.obj", "/f6.obj", "/f4.obj", "/f3.obj", "/f2.obj"]);
        assert_eq!(RecentFiles::parse(&recent.to_text()), recent);
    }

    #[test]
    fn recent_list_round_trips_through_an_atomic_write() {
        let dir = std::env::temp_dir().join(format!("bumpview-recent-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        let file = dir.join("sub").join("recent.txt");
        assert_eq!(RecentFiles::load(&file), RecentFiles::default(), "missing file: empty list");
        let mut recent = RecentFiles::default();
        recent.push(Path::new("/models/a b.gltf"));
        recent.push(Path::new("/models/wall_n.png"));
        recent.save(&file).unwrap();
        assert_eq!(RecentFiles::load(&file), recent);
        // Only the list is left in the folder: the temporary file was renamed over it.
        let entries: Vec<_> =
            std::fs::read_dir(file.parent().unwrap()).unwrap().map(|e| e.unwrap().file_name()).collect();
        assert_eq!(entries, ["recent.txt"]);
        // A broken file (not UTF-8) is an empty list, and saving over it works.
        std::fs::write(&file, [0xff, 0xfe, b'\n']).unwrap();
        assert_eq!(RecentFiles::load(&file), RecentFiles::default());
        recent.save(&file).unwrap();
        assert_eq!(RecentFiles::load(&file), recent);
        // An unwritable place is an error, not a panic, and leaves no temporary file.
        let blocked = dir.join("recent.txt");
        std::fs::write(&blocked, "x").unwrap();
        assert!(recent.save(&blocked.join("recent.txt")).is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn debouncer_fires_once_after_changes_settle() {
        let t0 = Instant::now();
        let mut debouncer = Debouncer::default();
        assert!(!debouncer.fire(t0));
        debouncer.changed(t0);
        debouncer.changed(t0 + Duration::from_millis(150));
        assert!(!debouncer.fire(t0 + Duration::from_millis(300)), "the second change restarts the wait");
        assert_eq!(debouncer.remaining(t0 + Duration::from_millis(300)), Some(Duration::from_millis(50)));
        assert!(debouncer.fire(t0 + Duration::from_millis(350)));
        assert!(!debouncer.fire(t0 + Duration::from_millis(400)));
        assert_eq!(debouncer.remaining(t0), None);
    }

    /// A fake loader: the built-in scene, an error for a mesh named `broken.obj`, a panic for
    /// `panic.obj`, and for a mesh named `slow.obj` it waits for a go from the test.
    fn fake_build(slow: mpsc::Receiver<()>) -> BuildFn {
        let slow = std::sync::Mutex::new(slow);
        Arc::new(move |source: &Source| {
            let name = source.mesh.as_deref().map(file_name).unwrap_or_default();
            if name == "slow.obj" {
                slow.lock().unwrap().recv().unwrap();
            }
            assert_ne!(name, "panic.obj", "a loader bug");
            if name == "broken.obj" {
                return Err(LoadError::new(Path::new("/m/broken.obj"), "the file holds no triangles to draw"));
            }
            let mut scene = teaching_scene_with_kernel(source.kernel);
            scene.meshes[0].name = name;
            Ok(scene)
        })
    }

    /// Polls until the loader's result is there (the fake is quick; 10 s is generous).
    fn wait(files: &mut Files) -> Finished {
        let start = Instant::now();
        loop {
            if let Some(finished) = files.loader.poll() {
                return finished;
            }
            assert!(start.elapsed() < Duration::from_secs(10), "no result");
            std::thread::sleep(Duration::from_millis(5));
        }
    }

    #[test]
    fn loading_succeeds_fails_and_supersedes() {
        let (go, slow) = mpsc::channel();
        let dir = std::env::temp_dir().join(format!("bumpview-files-{}", std::process::id()));
        let recent_file = dir.join("recent.txt");
        let mut files = Files::new(Source::default(), fake_build(slow), Some(recent_file.clone()));
        assert!(files.loader.busy().is_none());

        // Success: the source, recent list (saved) and status change; a new mesh is framed.
        files.open(&paths(&["/m/good.obj"]), None, || {});
        assert_eq!(files.loader.busy(), Some("good.obj"));
        let finished = wait(&mut files);
        let (scene, purpose) = files.finish(finished).unwrap();
        assert_eq!((scene.meshes[0].name.as_str(), purpose), ("good.obj", Purpose::Open));
        assert!(files.loader.busy().is_none());
        assert_eq!(files.source.mesh.as_deref(), Some(Path::new("/m/good.obj")));
        assert_eq!(files.status, Some(Status::Done("opened good.obj".into())));
        assert_eq!(RecentFiles::load(&recent_file).paths(), [PathBuf::from("/m/good.obj")]);

        // Failure: the message is the status; source and recent list stay.
        files.open(&paths(&["/m/broken.obj"]), None, || {});
        let finished = wait(&mut files);
        assert!(files.finish(finished).is_none());
        assert_eq!(files.status, Some(Status::Failed("/m/broken.obj: the file holds no triangles to draw".into())));
        assert_eq!(files.source.mesh.as_deref(), Some(Path::new("/m/good.obj")));
        assert_eq!(files.recent.paths().len(), 1);

        // A panicking loader is a message too.
        files.open(&paths(&["/m/panic.obj"]), None, || {});
        let finished = wait(&mut files);
        assert!(files.finish(finished).is_none());
        assert!(matches!(&files.status, Some(Status::Failed(m)) if m.contains("panic.obj: the loader failed (a bug)")));

        // A plan error never starts a job.
        files.open(&paths(&["/m/readme.md"]), None, || {});
        assert!(files.loader.busy().is_none());
        assert!(matches!(&files.status, Some(Status::Failed(m)) if m.contains("readme.md")));

        // A job started while another runs supersedes it: only the newer result arrives.
        files.open(&paths(&["/m/slow.obj"]), None, || {});
        files.reload(files.source.clone(), "reloaded".into(), || {});
        assert_eq!(files.loader.busy(), Some("good.obj"));
        let finished = wait(&mut files);
        assert_eq!(finished.job.purpose, Purpose::Reload);
        go.send(()).unwrap();
        std::thread::sleep(Duration::from_millis(50));
        assert!(files.loader.poll().is_none(), "the superseded result is dropped");
        let (scene, purpose) = files.finish(finished).unwrap();
        assert_eq!((scene.meshes[0].name.as_str(), purpose), ("good.obj", Purpose::Reload));
        assert_eq!(files.status, Some(Status::Done("reloaded".into())));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
