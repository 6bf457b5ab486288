//! Hot reload: watches the folders of the scene's files for changes (the `notify` crate).
//!
//! Folders, not the files themselves: editors and exporters often save by writing a new file
//! and renaming it over the old one, which would end a watch on the old file.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::sync::mpsc;

use notify::{EventKind, RecursiveMode, Watcher as _};

/// Reports files created or modified in the watched folders.
pub struct Watcher {
    /// `None` when the platform's watcher could not be started (see [`Watcher::new`]).
    inner: Option<notify::RecommendedWatcher>,
    changes: mpsc::Receiver<PathBuf>,
    /// The folders watched now.
    folders: BTreeSet<PathBuf>,
}

impl Watcher {
    /// A watcher that calls `wake` from its own thread whenever a change arrives (the viewer
    /// asks for a repaint). The error says why there is no hot reload; the watcher then
    /// reports nothing.
    pub fn new(wake: impl Fn() + Send + 'static) -> (Watcher, Result<(), String>) {
        let (sender, changes) = mpsc::channel();
        let handler = move |event: notify::Result<notify::Event>| {
            // Opening and reading (the loader's own accesses) and removals change nothing
            // yet; a removed file's replacement arrives as a create or a rename.
            let Ok(event) = event else { return };
            if matches!(event.kind, EventKind::Create(_) | EventKind::Modify(_)) {
                for path in event.paths {
                    let _ = sender.send(path);
                }
                wake();
            }
        };
        match notify::recommended_watcher(handler) {
            Ok(inner) => (Watcher { inner: Some(inner), changes, folders: BTreeSet::new() }, Ok(())),
            Err(e) => {
                let watcher = Watcher { inner: None, changes, folders: BTreeSet::new() };
                (watcher, Err(format!("no hot reload: could not watch files: {e}")))
            }
        }
    }

    /// Watches the folders holding `files` (and stops watching the others). The error names
    /// a folder that cannot be watched. Changes are reported with absolute paths.
    pub fn watch(&mut self, files: &[&Path]) -> Result<(), String> {
        let Some(inner) = &mut self.inner else { return Ok(()) };
        // Absolute folders: a relative file's parent may be empty, and changes then come back
        // with absolute paths.
        let folder = |f: &&Path| std::path::absolute(f).ok()?.parent().map(Path::to_owned);
        let wanted: BTreeSet<PathBuf> = files.iter().filter_map(folder).collect();
        for old in self.folders.difference(&wanted) {
            let _ = inner.unwatch(old);
        }
        let mut result = Ok(());
        for new in wanted.difference(&self.folders) {
            if let Err(e) = inner.watch(new, RecursiveMode::NonRecursive) {
                result = Err(format!("no hot reload for {}: {e}", new.display()));
            }
        }
        self.folders = wanted;
        result
    }

    /// The paths that changed since the last call.
    pub fn changes(&self) -> Vec<PathBuf> {
        self.changes.try_iter().collect()
    }
}
