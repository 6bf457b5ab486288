//! Bounded file reads: the one way the library reads a file a user or a model names (meshes,
//! glTF buffers, images, material libraries, presets, bake inputs). Only regular files are read
//! (a device, FIFO or socket is refused by its type before it is opened, so `/dev/zero` or a
//! FIFO never hangs or fills memory), each kind of file up to its own size cap, and the read
//! itself stops one byte past the cap, so a file that grows after the check stays bounded.
//!
//! Files can also be held in memory under a path ([`hold_in_memory`]): the web build's dropped
//! and picked files arrive as bytes without a file on disk, and a glTF among them names its
//! `.bin` and textures by relative URIs, which resolve beside it to other held files.

use std::collections::BTreeMap;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

/// Bytes in a mebibyte.
const MIB: u64 = 1 << 20;

/// What a file is read as; each kind has its cap ([`FileKind::cap`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FileKind {
    /// A glTF (JSON or GLB) or OBJ file.
    Mesh,
    /// A glTF buffer (`.bin`).
    Buffer,
    /// An image: a texture or a bake input.
    Image,
    /// An OBJ's material library (`.mtl`).
    MaterialLibrary,
    /// A preset (TOML).
    Preset,
    /// A file of the web build that `slides --html` copies beside the deck.
    WebBuild,
}

impl FileKind {
    /// The largest file of this kind read, in bytes. Meshes, buffers and images: 1 GiB, above
    /// any model or texture this tool can draw (a 16384² RGBA8 BMP, the largest image a bake
    /// takes, is 1 GiB; a GLB states its length in 32 bits). Material libraries: 16 MiB (text
    /// naming a few textures per material). Presets: 1 MiB (the viewer writes about 2 KiB).
    /// Web build files: 256 MiB (its wasm is about 12 MiB).
    pub const fn cap(self) -> u64 {
        match self {
            FileKind::Mesh | FileKind::Buffer | FileKind::Image => 1024 * MIB,
            FileKind::WebBuild => 256 * MIB,
            FileKind::MaterialLibrary => 16 * MIB,
            FileKind::Preset => MIB,
        }
    }

    /// The kind's name in messages.
    pub const fn name(self) -> &'static str {
        match self {
            FileKind::Mesh => "mesh",
            FileKind::Buffer => "buffer",
            FileKind::Image => "image",
            FileKind::MaterialLibrary => "material library",
            FileKind::Preset => "preset",
            FileKind::WebBuild => "web build",
        }
    }
}

/// Why a file was not read, on one line.
#[derive(Debug, thiserror::Error)]
pub enum ReadError {
    /// Not a regular file: a directory, device, FIFO or socket (named).
    #[error("is {0}, not a regular file")]
    NotRegular(&'static str),
    /// Larger than the kind's cap.
    #[error("is larger than {cap_mib} MiB, the cap on {kind} files")]
    TooLarge { kind: &'static str, cap_mib: u64 },
    /// The operating system's error (missing, no permission...).
    #[error("{0}")]
    Io(#[from] std::io::Error),
}

/// Files held in memory, by path ([`hold_in_memory`]).
static MEMORY: Mutex<BTreeMap<PathBuf, Arc<[u8]>>> = Mutex::new(BTreeMap::new());

/// The folder the web build holds dropped and picked files in (see [`hold_in_memory`]).
pub const MEMORY_FOLDER: &str = "/memory";

/// Holds `bytes` as the file at `path` for this process: [`read_file`] of `path` gives them
/// (within the kind's cap) and never looks on disk for it. A file held again under the same path
/// replaces the old bytes. Held files stay until the process ends (a browser tab: until it
/// closes or reloads).
pub fn hold_in_memory(path: PathBuf, bytes: Arc<[u8]>) {
    MEMORY.lock().unwrap_or_else(|poisoned| poisoned.into_inner()).insert(path, bytes);
}

/// The bytes held for `path`, if any.
fn held(path: &Path) -> Option<Arc<[u8]>> {
    MEMORY.lock().unwrap_or_else(|poisoned| poisoned.into_inner()).get(path).cloned()
}

/// The bytes of the file at `path` (symbolic links followed), read as `kind`: refused when
/// the resolved file is not a regular file or is larger than [`FileKind::cap`]. A file held in
/// memory ([`hold_in_memory`]) is given from there.
pub fn read_file(path: &Path, kind: FileKind) -> Result<Vec<u8>, ReadError> {
    let too_large = || ReadError::TooLarge { kind: kind.name(), cap_mib: kind.cap() / MIB };
    if let Some(bytes) = held(path) {
        return if bytes.len() as u64 > kind.cap() { Err(too_large()) } else { Ok(bytes.to_vec()) };
    }
    // The type of the file the path resolves to, before opening it: opening a FIFO blocks.
    let metadata = std::fs::metadata(path)?;
    regular(&metadata)?;
    if metadata.len() > kind.cap() {
        return Err(too_large());
    }
    let file = std::fs::File::open(path)?;
    // The file opened may not be the one checked (the path changed in between).
    let metadata = file.metadata()?;
    regular(&metadata)?;
    let mut bytes = Vec::with_capacity(metadata.len().min(kind.cap()) as usize);
    file.take(kind.cap() + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > kind.cap() {
        return Err(too_large());
    }
    Ok(bytes)
}

/// Fails unless `metadata` is a regular file's, naming what it is instead.
fn regular(metadata: &std::fs::Metadata) -> Result<(), ReadError> {
    let file_type = metadata.file_type();
    if file_type.is_file() {
        return Ok(());
    }
    if file_type.is_dir() {
        return Err(ReadError::NotRegular("a directory"));
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        let what = if file_type.is_fifo() {
            "a FIFO (named pipe)"
        } else if file_type.is_char_device() {
            "a character device"
        } else if file_type.is_block_device() {
            "a block device"
        } else if file_type.is_socket() {
            "a socket"
        } else {
            "a special file"
        };
        Err(ReadError::NotRegular(what))
    }
    #[cfg(not(unix))]
    Err(ReadError::NotRegular("a special file"))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("bumpview-read-{}-{name}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn reads_a_regular_file_whole() {
        let dir = scratch("regular");
        let path = dir.join("a.bin");
        std::fs::write(&path, b"bytes").unwrap();
        assert_eq!(read_file(&path, FileKind::Buffer).unwrap(), b"bytes");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn refuses_a_file_over_its_cap() {
        let dir = scratch("cap");
        let path = dir.join("big.toml");
        std::fs::write(&path, vec![b'#'; FileKind::Preset.cap() as usize + 1]).unwrap();
        let error = read_file(&path, FileKind::Preset).unwrap_err();
        assert_eq!(error.to_string(), "is larger than 1 MiB, the cap on preset files");
        std::fs::write(&path, vec![b'#'; FileKind::Preset.cap() as usize]).unwrap();
        assert_eq!(read_file(&path, FileKind::Preset).unwrap().len() as u64, FileKind::Preset.cap());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn reads_held_files_from_memory_within_their_cap() {
        let path = Path::new(MEMORY_FOLDER).join("read-test").join("held.toml");
        assert!(read_file(&path, FileKind::Preset).is_err(), "not held yet, and not on disk");
        hold_in_memory(path.clone(), Arc::from(&b"first"[..]));
        assert_eq!(read_file(&path, FileKind::Preset).unwrap(), b"first");
        hold_in_memory(path.clone(), Arc::from(&b"second"[..]));
        assert_eq!(read_file(&path, FileKind::Preset).unwrap(), b"second");
        hold_in_memory(path.clone(), Arc::from(vec![b'#'; FileKind::Preset.cap() as usize + 1]));
        let error = read_file(&path, FileKind::Preset).unwrap_err();
        assert_eq!(error.to_string(), "is larger than 1 MiB, the cap on preset files");
    }

    #[cfg(unix)]
    #[test]
    fn refuses_devices_fifos_and_links_to_them_by_type() {
        let dir = scratch("special");
        let error = read_file(Path::new("/dev/zero"), FileKind::Image).unwrap_err();
        assert_eq!(error.to_string(), "is a character device, not a regular file");
        let link = dir.join("zero.png");
        std::os::unix::fs::symlink("/dev/zero", &link).unwrap();
        assert_eq!(read_file(&link, FileKind::Image).unwrap_err().to_string(), error.to_string());
        let fifo = dir.join("pipe.bin");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status().unwrap();
        assert!(made.success());
        // Opening the FIFO would block this test forever: it must be refused before.
        let error = read_file(&fifo, FileKind::Buffer).unwrap_err();
        assert_eq!(error.to_string(), "is a FIFO (named pipe), not a regular file");
        assert_eq!(read_file(&dir, FileKind::Mesh).unwrap_err().to_string(), "is a directory, not a regular file");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
