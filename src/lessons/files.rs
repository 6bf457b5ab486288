//! Lesson files a lecturer writes, read from disk: `bumpview slides --lesson FILE`,
//! `--lessons-dir DIR` and the viewer's `--lesson FILE`. A lesson file is the same TOML as a
//! built-in lesson (the format is in the module doc of [`crate::lessons`] and in
//! docs/lessons.md); its paths (the model and textures its preset names) are relative to the
//! lesson file's folder, as a preset's are.

use std::path::{Path, PathBuf};

use super::{Lesson, LessonError};
use crate::read::{FileKind, read_file};
use crate::state::preset::Preset;

/// What a lecturer writes for a lesson saved from the viewer: the title, the caption and the
/// claim (with `{changed}` where the measured share goes).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct LessonWords {
    pub title: String,
    pub caption: String,
    pub claim: String,
}

/// The text of a lesson file comparing the split view of `preset` (the viewer's whole state;
/// its two halves are the sides, labelled `labels`), with `words` and `preset`'s paths relative
/// to `folder` (where the file goes). Checked by reading it back as a lesson: a mistake (no
/// split view, no `{changed}` in the claim, an empty title) is the reader's one line.
pub fn lesson_file_text(
    words: &LessonWords,
    preset: &Preset,
    labels: &[String; 2],
    folder: &Path,
) -> Result<String, LessonError> {
    let fail = |message: String| LessonError { name: "the lesson".into(), message };
    if words.title.trim().is_empty() {
        return Err(fail("a lesson needs a title".into()));
    }
    if !preset.split.enabled {
        return Err(fail("a lesson compares two sides: turn the split view on (S) and choose what it compares".into()));
    }
    let stored = Preset { files: preset.files.relative_to(folder), ..preset.clone() };
    let mut file = toml::Table::new();
    file.insert("title".into(), words.title.trim().into());
    file.insert("caption".into(), words.caption.trim().into());
    file.insert("claim".into(), words.claim.trim().into());
    file.insert("labels".into(), toml::Value::Array(labels.iter().map(|l| l.as_str().into()).collect()));
    let preset = toml::Value::try_from(&stored).map_err(|e| fail(format!("the state as TOML: {e}")))?;
    file.insert("preset".into(), preset);
    let body = toml::to_string(&file).map_err(|e| fail(format!("the lesson as TOML: {e}")))?;
    let text = format!("# bumpview lesson (bumpview slides --lesson FILE; bumpview --lesson FILE)\n{body}");
    Lesson::parse("the lesson", &text).map_err(|e| fail(e.message))?;
    Ok(text)
}

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

    /// A lesson saved from a state reads back as that state's comparison, its files relative
    /// to the lesson's folder; without a split view or a `{changed}` it says why.
    #[test]
    fn a_saved_state_reads_back_as_its_lesson() {
        let dir = folder("saved");
        let mut preset = Preset::from_toml("[files]\nmesh = \"model/box.gltf\"\n[split]\nenabled = true\ndifference = \"strength\"\nstrengths = [0.5, 2.0]\n").unwrap();
        preset.files = preset.files.resolved(&dir);
        let words = LessonWords {
            title: "My box".into(),
            caption: "Two strengths.".into(),
            claim: "It changes {changed}.".into(),
        };
        let labels = ["strength 0.50".to_owned(), "strength 2.00".to_owned()];
        let text = lesson_file_text(&words, &preset, &labels, &dir).unwrap();
        std::fs::write(dir.join("box.toml"), &text).unwrap();
        let lesson = Lesson::load(&dir.join("box.toml")).unwrap();
        assert_eq!(
            (lesson.title.as_str(), lesson.sides.len(), lesson.sides[1].label.as_str()),
            ("My box", 2, "strength 2.00")
        );
        assert_eq!(lesson.preset.files, preset.files, "the paths come back as they were");
        assert!(text.contains("mesh = \"model/box.gltf\""), "relative in the file:\n{text}");
        assert_eq!(lesson.preset.split, preset.split);

        let no_number = LessonWords { claim: "It changes.".into(), ..words.clone() };
        let e = lesson_file_text(&no_number, &preset, &labels, &dir).unwrap_err();
        assert!(e.to_string().contains("{changed}"), "{e}");
        preset.split.enabled = false;
        let e = lesson_file_text(&words, &preset, &labels, &dir).unwrap_err();
        assert!(e.to_string().contains("turn the split view on"), "{e}");
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
