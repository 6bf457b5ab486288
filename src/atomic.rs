//! Atomic file writes: an interrupted save never leaves a broken file behind.

use std::io::Write;
use std::path::{Path, PathBuf};

/// Writes `path` through `write`, atomically: into a temporary file in the same folder
/// (`.<name>.<pid>.<n>.tmp`), synced, then renamed over `path`, so readers see the old file or
/// the complete new one. The temporary is created exclusively ([`create_temporary`]: a file
/// or symbolic link already at its name is never opened, followed or truncated; another name
/// is tried). An existing `path` that is not a regular file (a directory, device, FIFO,
/// socket, or a symbolic link to one) is refused before anything is written
/// ([`refuse_non_regular`]). The temporary file is removed when anything fails (a panic in
/// `write` included); those a killed run left beside `path` ([`remove_stale_temporaries`])
/// are removed first. The folder must exist.
pub fn write_atomically(
    path: &Path,
    write: impl FnOnce(&mut std::io::BufWriter<std::fs::File>) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let file_name =
        path.file_name().ok_or_else(|| std::io::Error::new(std::io::ErrorKind::InvalidInput, "not a file path"))?;
    if let Some(kind) = non_regular_kind(path) {
        let message = format!("is {kind}, not a regular file: refusing to write over it");
        return Err(std::io::Error::new(std::io::ErrorKind::InvalidInput, message));
    }
    remove_stale_temporaries(path);
    let (file, temporary_path) = create_temporary(path, file_name)?;
    let mut temporary = Temporary { path: temporary_path, renamed: false };
    let mut writer = std::io::BufWriter::new(file);
    write(&mut writer)?;
    writer.into_inner().map_err(|e| e.into_error())?.sync_all()?;
    std::fs::rename(&temporary.path, path)?;
    temporary.renamed = true;
    Ok(())
}

/// The most names [`create_temporary`] tries before giving up.
const TEMPORARY_TRIES: u32 = 64;

/// Creates a new temporary file beside `path`, `.<name>.<pid>.<n>.tmp` for the first free `n`:
/// opened with `create_new` (`O_CREAT | O_EXCL`, which by POSIX fails on any existing name, a
/// symbolic link included, dangling or not, so a link planted at the name is neither followed
/// nor truncated) and retried under the next name when one exists.
fn create_temporary(path: &Path, file_name: &std::ffi::OsStr) -> std::io::Result<(std::fs::File, PathBuf)> {
    let pid = std::process::id();
    for n in 0..TEMPORARY_TRIES {
        let candidate = path.with_file_name(temporary_name(file_name, pid, n));
        match std::fs::OpenOptions::new().write(true).create_new(true).open(&candidate) {
            Ok(file) => return Ok((file, candidate)),
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => continue,
            Err(e) => return Err(e),
        }
    }
    let message = format!("{TEMPORARY_TRIES} temporary names beside it are taken");
    Err(std::io::Error::new(std::io::ErrorKind::AlreadyExists, message))
}

/// What `path` is when it exists and is not a regular file, following a symbolic link:
/// "a directory", "a FIFO", "a device"... `None` for a regular file, a link to one, a dangling
/// link (renaming over a link replaces the link, not its target) or nothing at all.
pub fn non_regular_kind(path: &Path) -> Option<&'static str> {
    std::fs::symlink_metadata(path).ok()?;
    let kind = std::fs::metadata(path).ok()?.file_type();
    if kind.is_file() {
        return None;
    }
    if kind.is_dir() {
        return Some("a directory");
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if kind.is_fifo() {
            return Some("a FIFO");
        }
        if kind.is_socket() {
            return Some("a socket");
        }
        if kind.is_block_device() || kind.is_char_device() {
            return Some("a device");
        }
    }
    Some("not a regular file")
}

/// A temporary file, removed when dropped unless it was renamed into place (so on every
/// early return and on unwinding).
struct Temporary {
    path: PathBuf,
    renamed: bool,
}

impl Drop for Temporary {
    fn drop(&mut self) {
        if !self.renamed {
            let _ = std::fs::remove_file(&self.path);
        }
    }
}

/// The `n`th temporary file name of process `pid` writing `file_name`.
fn temporary_name(file_name: &std::ffi::OsStr, pid: u32, n: u32) -> String {
    format!(".{}.{pid}.{n}.tmp", file_name.to_string_lossy())
}

/// Removes the temporary files that runs killed while writing `path` left beside it:
/// `.<name>.<pid>.<n>.tmp` (or the older `.<name>.<pid>.tmp`) of a process that no longer runs (on Linux, no `/proc/<pid>`;
/// elsewhere, untouched for an hour). Best effort: a file that cannot be removed stays.
pub fn remove_stale_temporaries(path: &Path) {
    let (Some(folder), Some(file_name)) = (path.parent(), path.file_name()) else { return };
    let folder = if folder.as_os_str().is_empty() { Path::new(".") } else { folder };
    let prefix = format!(".{}.", file_name.to_string_lossy());
    let Ok(entries) = std::fs::read_dir(folder) else { return };
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        let pid = name.strip_prefix(&prefix).and_then(|rest| rest.strip_suffix(".tmp"));
        let pid = pid.map(|p| p.split_once('.').map_or(p, |(pid, n)| if n.parse::<u32>().is_ok() { pid } else { "" }));
        let Some(pid) = pid.and_then(|p| p.parse::<u32>().ok()) else { continue };
        if pid != std::process::id() && !running(pid, &entry.path()) {
            let _ = std::fs::remove_file(entry.path());
        }
    }
}

/// Whether process `pid`, which wrote `temporary`, may still be running.
fn running(pid: u32, temporary: &Path) -> bool {
    if cfg!(target_os = "linux") {
        return Path::new("/proc").join(pid.to_string()).exists();
    }
    let age = std::fs::metadata(temporary).and_then(|m| m.modified()).ok().and_then(|t| t.elapsed().ok());
    age.is_none_or(|age| age < std::time::Duration::from_secs(3600))
}

/// [`write_atomically`] of `bytes`.
pub fn write_bytes_atomically(path: &Path, bytes: &[u8]) -> std::io::Result<()> {
    write_atomically(path, |w| w.write_all(bytes))
}

/// Why a command may not write one of its outputs.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum OutputRefusal {
    /// The output is one of the command's inputs (the same file, by canonical path).
    #[error("{}: is also an input ({}): refusing to write over it, nothing was written", output.display(), input.display())]
    IsInput { output: PathBuf, input: PathBuf },
    /// Two of the command's outputs are one file (by canonical path).
    #[error("{}: is written twice (also as {}): give each output its own name, nothing was written", output.display(), other.display())]
    Twice { output: PathBuf, other: PathBuf },
    /// The output exists and is not a regular file ([`non_regular_kind`]); `--force` does not
    /// replace it.
    #[error("{}: is {kind}, not a regular file: refusing to write over it, even with --force", output.display())]
    NotRegular { output: PathBuf, kind: &'static str },
    /// The output exists and replacing it was not asked for.
    #[error("{}: exists and was kept: pass --force to replace it", output.display())]
    Exists { output: PathBuf },
}

/// Checks, before any work, every output a command will write: none is one of its inputs
/// (compared by canonical path, so `d/../d/a.png` or a symbolic link to an input is caught,
/// and on Unix by device and inode, so a hard link is too), no two are one file, none that
/// exists is anything but a regular file (a directory, device such as `/dev/null`, FIFO,
/// socket or a symbolic link to one, `force` or not), and, unless `force`, none exists yet.
/// Inputs that do not exist are skipped (reading them fails later with its own message).
pub fn check_outputs(inputs: &[&Path], outputs: &[&Path], force: bool) -> Result<(), OutputRefusal> {
    let inputs: Vec<(PathBuf, &Path)> =
        inputs.iter().filter_map(|&input| Some((std::fs::canonicalize(input).ok()?, input))).collect();
    let mut written: Vec<(PathBuf, &Path)> = Vec::with_capacity(outputs.len());
    for &output in outputs {
        let canonical = canonical_output(output);
        let same = |(c, input): &&(PathBuf, &Path)| canonical.as_ref() == Some(c) || same_file(output, input);
        if let Some((_, input)) = inputs.iter().find(same) {
            return Err(OutputRefusal::IsInput { output: output.to_owned(), input: input.to_path_buf() });
        }
        if let Some(kind) = non_regular_kind(output) {
            return Err(OutputRefusal::NotRegular { output: output.to_owned(), kind });
        }
        // An output whose folder does not exist yet is compared by its absolute path.
        let key =
            canonical.clone().unwrap_or_else(|| std::path::absolute(output).unwrap_or_else(|_| output.to_owned()));
        if let Some((_, other)) = written.iter().find(|(k, other)| *k == key || same_file(output, other)) {
            return Err(OutputRefusal::Twice { output: output.to_owned(), other: other.to_path_buf() });
        }
        if !force && std::fs::symlink_metadata(output).is_ok() {
            return Err(OutputRefusal::Exists { output: output.to_owned() });
        }
        written.push((key, output));
    }
    Ok(())
}

/// Whether `a` and `b` are one file (one device and inode; never on other systems).
fn same_file(a: &Path, b: &Path) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        let id = |p: &Path| std::fs::metadata(p).ok().map(|m| (m.dev(), m.ino()));
        id(a).is_some_and(|a| Some(a) == id(b))
    }
    #[cfg(not(unix))]
    {
        let _ = (a, b);
        false
    }
}

/// The canonical path `output` will be written at: its own when it exists, else its
/// folder's joined with its name (`None` when the folder does not exist either).
fn canonical_output(output: &Path) -> Option<PathBuf> {
    if let Ok(canonical) = std::fs::canonicalize(output) {
        return Some(canonical);
    }
    let folder = output.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    Some(std::fs::canonicalize(folder).ok()?.join(output.file_name()?))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn replaces_the_file_and_leaves_no_temporary_even_on_failure() {
        let dir = std::env::temp_dir().join(format!("bumpview-atomic-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("a.txt");
        write_bytes_atomically(&path, b"old").unwrap();
        write_bytes_atomically(&path, b"new").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"new");
        let failed = write_atomically(&path, |w| {
            w.write_all(b"half")?;
            Err(std::io::Error::other("interrupted"))
        });
        assert!(failed.is_err());
        assert_eq!(std::fs::read(&path).unwrap(), b"new");
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
        let panicked = std::panic::catch_unwind(|| {
            write_atomically(&path, |w| {
                w.write_all(b"half")?;
                panic!("a bug mid-write")
            })
        });
        assert!(panicked.is_err());
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1, "the temporary file is removed on a panic too");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// A run killed mid-write leaves `.a.txt.<pid>.tmp`; the next write of `a.txt` removes it
    /// (its process is gone), but not another file's temporary or a running process's.
    #[test]
    fn the_next_write_removes_temporaries_of_killed_runs() {
        let dir = std::env::temp_dir().join(format!("bumpview-atomic-stale-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("a.txt");
        let mut child = std::process::Command::new("true").spawn().unwrap();
        let gone = child.id();
        child.wait().unwrap();
        let stale = dir.join(temporary_name("a.txt".as_ref(), gone, 0));
        let other = dir.join(temporary_name("b.txt".as_ref(), gone, 0));
        let live = dir.join(temporary_name("a.txt".as_ref(), 1, 0));
        for file in [&stale, &other, &live] {
            std::fs::write(file, b"left behind").unwrap();
        }
        write_bytes_atomically(&path, b"new").unwrap();
        assert!(!stale.exists() && other.exists(), "stale {}, other {}", stale.exists(), other.exists());
        assert_eq!(live.exists(), cfg!(target_os = "linux"), "process 1 runs");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn outputs_over_inputs_are_refused_and_existing_ones_need_force() {
        let dir = std::env::temp_dir().join(format!("bumpview-atomic-outputs-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("d")).unwrap();
        let input = dir.join("d/a.png");
        std::fs::write(&input, b"input").unwrap();
        let through_dots = dir.join("d/../d/a.png");
        let refused = check_outputs(&[&input], &[&through_dots], true).unwrap_err();
        assert_eq!(refused, OutputRefusal::IsInput { output: through_dots.clone(), input: input.clone() });
        let existing = dir.join("d/old.png");
        std::fs::write(&existing, b"old").unwrap();
        let kept = check_outputs(&[&input], &[&existing], false).unwrap_err();
        assert_eq!(
            kept.to_string(),
            format!("{}: exists and was kept: pass --force to replace it", existing.display())
        );
        assert_eq!(check_outputs(&[&input], &[&existing], true), Ok(()));
        assert_eq!(check_outputs(&[&input], &[&dir.join("d/new.png")], false), Ok(()));
        #[cfg(unix)]
        {
            let link = dir.join("link.png");
            std::fs::hard_link(&input, &link).unwrap();
            assert!(matches!(check_outputs(&[&input], &[&link], true), Err(OutputRefusal::IsInput { .. })));
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
