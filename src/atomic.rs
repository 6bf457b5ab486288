//! Atomic file writes: an interrupted save never leaves a broken file behind.

use std::io::Write;
use std::path::{Path, PathBuf};

/// Writes `path` through `write`, atomically: into a temporary file in the same folder
/// (`.<name>.<pid>.tmp`), synced, then renamed over `path`, so readers see the old file or
/// the complete new one. The temporary file is removed when anything fails (a panic in
/// `write` included); those a killed run left beside `path` ([`remove_stale_temporaries`])
/// are removed first. The folder must exist.
pub fn write_atomically(
    path: &Path,
    write: impl FnOnce(&mut std::io::BufWriter<std::fs::File>) -> std::io::Result<()>,
) -> std::io::Result<()> {
    let file_name =
        path.file_name().ok_or_else(|| std::io::Error::new(std::io::ErrorKind::InvalidInput, "not a file path"))?;
    remove_stale_temporaries(path);
    let mut temporary =
        Temporary { path: path.with_file_name(temporary_name(file_name, std::process::id())), renamed: false };
    let file = std::fs::File::create(&temporary.path)?;
    let mut writer = std::io::BufWriter::new(file);
    write(&mut writer)?;
    writer.into_inner().map_err(|e| e.into_error())?.sync_all()?;
    std::fs::rename(&temporary.path, path)?;
    temporary.renamed = true;
    Ok(())
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

/// The temporary file name of process `pid` writing `file_name`.
fn temporary_name(file_name: &std::ffi::OsStr, pid: u32) -> String {
    format!(".{}.{pid}.tmp", file_name.to_string_lossy())
}

/// Removes the temporary files that runs killed while writing `path` left beside it:
/// `.<name>.<pid>.tmp` of a process that no longer runs (on Linux, no `/proc/<pid>`;
/// elsewhere, untouched for an hour). Best effort: a file that cannot be removed stays.
pub fn remove_stale_temporaries(path: &Path) {
    let (Some(folder), Some(file_name)) = (path.parent(), path.file_name()) else { return };
    let folder = if folder.as_os_str().is_empty() { Path::new(".") } else { folder };
    let prefix = format!(".{}.", file_name.to_string_lossy());
    let Ok(entries) = std::fs::read_dir(folder) else { return };
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().into_owned();
        let pid = name.strip_prefix(&prefix).and_then(|rest| rest.strip_suffix(".tmp"));
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
    /// The output exists and replacing it was not asked for.
    #[error("{}: exists and was kept: pass --force to replace it", output.display())]
    Exists { output: PathBuf },
}

/// Checks, before any work, that no output of a command is one of its inputs (compared by
/// canonical path, so `d/../d/a.png` or a symbolic link to an input is caught, and on Unix by
/// device and inode, so a hard link is too) and, unless `force`, that no output exists yet.
/// Inputs that do not exist are skipped (reading them fails later with its own message).
pub fn check_outputs(inputs: &[&Path], outputs: &[&Path], force: bool) -> Result<(), OutputRefusal> {
    let inputs: Vec<(PathBuf, &Path)> =
        inputs.iter().filter_map(|&input| Some((std::fs::canonicalize(input).ok()?, input))).collect();
    for &output in outputs {
        let same = |(canonical, input): &&(PathBuf, &Path)| {
            canonical_output(output).is_some_and(|c| c == *canonical) || same_file(output, input)
        };
        if let Some((_, input)) = inputs.iter().find(same) {
            return Err(OutputRefusal::IsInput { output: output.to_owned(), input: input.to_path_buf() });
        }
        if !force && std::fs::symlink_metadata(output).is_ok() {
            return Err(OutputRefusal::Exists { output: output.to_owned() });
        }
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
        let stale = dir.join(temporary_name("a.txt".as_ref(), gone));
        let other = dir.join(temporary_name("b.txt".as_ref(), gone));
        let live = dir.join(temporary_name("a.txt".as_ref(), 1));
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
