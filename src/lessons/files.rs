//! Lesson files a lecturer writes, read from disk: `bumpview slides --lesson FILE`,
//! `--lessons-dir DIR` and the viewer's `--lesson FILE`. A lesson file is the same TOML as a
//! built-in lesson (the format is in the module doc of [`crate::lessons`] and in
//! docs/lessons.md); its paths (the model and textures its preset names) are relative to the
//! lesson file's folder, as a preset's are.

use std::path::{Path, PathBuf};

use super::{Lesson, LessonError};
use crate::read::{FileKind, read_file};

impl Lesson {
    /// Reads and checks the lesson file at `path`; its name is the file's stem. Every error
    /// names the file (and, where the mistake is in the TOML, its line and key).
    pub fn load(path: &Path) -> Result<Lesson, LessonError> {
        let fail = |message: String| LessonError { name: path.display().to_string(), message };
        let bytes = read_file(path, FileKind::Preset).map_err(|e| fail(e.to_string()))?;
        let text = String::from_utf8(bytes).map_err(|_| fail("not UTF-8 text".into()))?;
        let name = path.file_stem().map_or_else(|| "lesson".into(), |stem| stem.to_string_lossy().into_owned());
        let mut lesson = Lesson::parse(&name, &text).map_err(|e| fail(e.message))?;
        let folder = path.parent().unwrap_or(Path::new(""));
        lesson.preset.files = lesson.preset.files.resolved(folder);
        for side in &mut lesson.sides {
            side.preset.files = side.preset.files.resolved(folder);
        }
        Ok(lesson)
    }
}

/// The lesson files (`*.toml`) in `folder`, in the order of their names; a folder without one
/// is an error, as is any file that does not read.
pub fn load_dir(folder: &Path) -> Result<Vec<Lesson>, LessonError> {
    let fail = |message: String| LessonError { name: folder.display().to_string(), message };
    let entries = std::fs::read_dir(folder).map_err(|e| fail(format!("could not list the folder: {e}")))?;
    let mut paths: Vec<PathBuf> = entries
        .filter_map(|entry| entry.ok().map(|e| e.path()))
        .filter(|path| path.extension().is_some_and(|ext| ext == "toml") && path.is_file())
        .collect();
    if paths.is_empty() {
        return Err(fail("no lesson files (*.toml) in this folder".into()));
    }
    paths.sort();
    paths.iter().map(|path| Lesson::load(path)).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn folder(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("bumpview-lesson-files-{name}-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn paths_are_relative_to_the_lesson_file() {
        let dir = folder("relative");
        let text = "title = \"t\"\ncaption = \"c\"\nclaim = \"{changed}\"\nlabels = [\"a\", \"b\"]\n\
                    [preset.files]\nmesh = \"model/box.gltf\"\n[preset.split]\nenabled = true\n";
        std::fs::write(dir.join("mine.toml"), text).unwrap();
        let lesson = Lesson::load(&dir.join("mine.toml")).unwrap();
        assert_eq!(lesson.name, "mine");
        assert_eq!(lesson.preset.files.mesh.as_deref(), Some(dir.join("model/box.gltf").as_path()));
        assert!(lesson.sides.iter().all(|s| s.preset.files.mesh == lesson.preset.files.mesh));
    }

    #[test]
    fn mistakes_name_the_file_the_line_and_the_key() {
        let dir = folder("mistakes");
        let path = dir.join("typo.toml");
        let text = "title = \"t\"\ncaption = \"c\"\nclaim = \"{changed}\"\n\n[preset.shading]\nstrenght = 2.0\n";
        std::fs::write(&path, text).unwrap();
        let message = Lesson::load(&path).unwrap_err().to_string();
        assert!(
            message.contains("typo.toml") && message.contains("line 6") && message.contains("strenght"),
            "{message}"
        );
        let tile = "title = \"t\"\ncaption = \"c\"\nclaim = \"{changed}\"\n[preset]\n[[tiles]]\nlabel = \"a\"\n\
                    [[tiles]]\nlabel = \"b\"\npreset.shading.veiw = \"lit\"\n";
        std::fs::write(&path, tile).unwrap();
        let message = Lesson::load(&path).unwrap_err().to_string();
        assert!(message.contains("line 9") && message.contains("veiw"), "{message}");
        let lesson_key = "title = \"t\"\ncaptoin = \"c\"\n";
        std::fs::write(&path, lesson_key).unwrap();
        let message = Lesson::load(&path).unwrap_err().to_string();
        assert!(message.contains("line 2") && message.contains("captoin"), "{message}");
        assert!(load_dir(&folder("empty")).unwrap_err().to_string().contains("no lesson files"));
    }
}
