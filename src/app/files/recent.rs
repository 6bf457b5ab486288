//! The recent-files list: the last files opened, kept in a small text file between runs.

use std::path::{Path, PathBuf};

/// How many files the recent list keeps.
pub const RECENT_MAX: usize = 8;

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

#[cfg(test)]
mod tests {
    use super::*;

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
}
