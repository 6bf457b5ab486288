//! Hot reload: watches the folders of the scene's files for changes (the `notify` crate) and
//! waits for a burst of changes to settle ([`Debouncer`]).
//!
//! Folders, not the files themselves: editors and exporters often save by writing a new file
//! and renaming it over the old one, which would end a watch on the old file.
//!
//! The web build has no files to watch (they arrive as bytes): its [`Watcher`] says so and
//! reports nothing.

use std::time::Duration;

use web_time::Instant;

#[cfg(not(target_arch = "wasm32"))]
pub use native::Watcher;
#[cfg(target_arch = "wasm32")]
pub use web::Watcher;

/// Quiet time after the last change on disk before a hot reload: editors and exporters write
/// a file in several steps (truncate, write, rename), which must not each cause a load.
pub const RELOAD_DEBOUNCE: Duration = Duration::from_millis(200);

#[cfg(not(target_arch = "wasm32"))]
mod native {
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
}

#[cfg(target_arch = "wasm32")]
mod web {
    use std::path::{Path, PathBuf};

    /// No hot reload in the browser: files arrive as bytes, with nothing on disk to watch.
    pub struct Watcher;

    impl Watcher {
        /// The watcher that reports nothing, and why.
        pub fn new(_wake: impl Fn() + Send + 'static) -> (Watcher, Result<(), String>) {
            (Watcher, Err("no hot reload in the browser: drop the changed file again".into()))
        }

        /// Nothing to watch.
        pub fn watch(&mut self, _files: &[&Path]) -> Result<(), String> {
            Ok(())
        }

        /// Never any change.
        pub fn changes(&self) -> Vec<PathBuf> {
            Vec::new()
        }
    }
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

#[cfg(test)]
mod tests {
    use super::*;

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
}
