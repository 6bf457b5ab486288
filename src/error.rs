//! Error types, one per fallible area.

use std::path::PathBuf;

/// Failures of the GPU side: no adapter, bad request, readback or file output.
#[derive(Debug, thiserror::Error)]
pub enum RenderError {
    #[error("no GPU adapter available (tried WGPU_BACKEND={backend}): {reason}")]
    NoAdapter { backend: String, reason: String },
    #[error("could not open the GPU device: {0}")]
    Device(String),
    #[error("viewport size {width}x{height} is empty: both sides must be at least 1 pixel")]
    EmptyViewport { width: u32, height: u32 },
    #[error("viewport size {width}x{height} exceeds the adapter's limit of {limit} pixels per side")]
    ViewportTooLarge { width: u32, height: u32, limit: u32 },
    #[error("export of {width}x{height} pixels is larger than the {limit} pixels an export may hold")]
    ExportTooLarge { width: u64, height: u64, limit: u64 },
    #[error("supersampling factor {factor} is out of range: 1 to {max}")]
    SupersampleFactor { factor: u32, max: u32 },
    #[error(
        "{width}x{height} supersampled {factor}× is {}x{} pixels, over the adapter's limit of {limit} pixels per side: use a smaller size or factor",
        width.saturating_mul(*factor),
        height.saturating_mul(*factor)
    )]
    SupersampleTooLarge { width: u32, height: u32, factor: u32, limit: u32 },
    #[error("the GPU could not draw {width}x{height} pixels (try a smaller size or factor): {reason}")]
    Gpu { width: u32, height: u32, reason: String },
    #[error("reading the rendered image back from the GPU failed: {0}")]
    Readback(String),
    #[error("waiting for the GPU to finish a frame failed: {0}")]
    Wait(String),
    #[error("no scene has been given to the renderer")]
    NoScene,
    #[error("could not write {path}: {reason}")]
    Write { path: PathBuf, reason: String },
}

/// A file that could not be loaded. The message always names the file (the one that failed:
/// the `.gltf`, its `.bin`, an image, an `.mtl`...) and the problem, on one line.
#[derive(Debug, thiserror::Error)]
#[error("{}: {problem}", path.display())]
pub struct LoadError {
    pub path: PathBuf,
    pub problem: String,
}

impl LoadError {
    pub fn new(path: &std::path::Path, problem: impl Into<String>) -> LoadError {
        LoadError { path: path.to_owned(), problem: problem.into() }
    }
}

/// Something a loader could not read or honour; the scene opened without it. Shown in the
/// viewer, printed by `render` (an error with `--strict`), reported by `check`.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LoadWarning {
    /// A texture that could not be read (missing, corrupt, unsupported, remote): its slot
    /// stays empty.
    #[error("{}: {problem}; opened without this texture", file.display())]
    UnreadableTexture { file: PathBuf, problem: String },
    /// A file the model refers to by an absolute path or a path that leaves the model's
    /// folder: it opens here, but not where the model is copied without it.
    #[error("{uri:?} ({}) lies outside the model's folder: the model is not portable", file.display())]
    NotPortable { uri: String, file: PathBuf },
    /// A texture that reads another set of texture coordinates than the mesh's one stream.
    #[error("material {material:?}: {texture} reads TEXCOORD_{wanted}; drawn with TEXCOORD_{drawn}")]
    TextureCoordinates { material: String, texture: String, wanted: u32, drawn: u32 },
    /// A triangle primitive with fewer than 3 indices (or vertices, without indices): it
    /// draws nothing and is left out.
    #[error("{mesh:?} has no whole triangle (fewer than 3 indices): left out")]
    EmptyPrimitive { mesh: String },
}

/// A preset could not be read, parsed, understood or written; the message says which key or
/// file and why, on one line.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{0}")]
pub struct PresetError(pub String);

/// A preset's scene could not be made: a setting it needs is wrong, or one of its files did
/// not load.
#[derive(Debug, thiserror::Error)]
pub enum PresetSceneError {
    #[error(transparent)]
    Preset(#[from] PresetError),
    #[error(transparent)]
    Load(#[from] LoadError),
}

/// `text` with every control character (ESC, newline, DEL, C1 controls…) and every
/// bidirectional formatting character (U+202A–U+202E embeddings and overrides such as the
/// right-to-left override, U+2066–U+2069 isolates, U+200E/U+200F/U+061C marks) written as Rust
/// escapes it, `\u{1b}`, `\u{202e}`: text from files (names, URIs, paths) printed to a
/// terminal, which would otherwise act on its escape sequences or show it reordered (a file
/// `gnp.exe` displayed as `exe.png`). Idempotent: the result has none of them.
pub fn escape_controls(text: &str) -> std::borrow::Cow<'_, str> {
    if !text.chars().any(needs_escape) {
        return std::borrow::Cow::Borrowed(text);
    }
    let escaped =
        text.chars().map(|c| if needs_escape(c) { format!("\\u{{{:x}}}", c as u32) } else { c.to_string() }).collect();
    std::borrow::Cow::Owned(escaped)
}

/// Whether [`escape_controls`] escapes `c`: a control or a bidirectional formatting character.
fn needs_escape(c: char) -> bool {
    c.is_control()
        || matches!(c, '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}' | '\u{200e}' | '\u{200f}' | '\u{61c}')
}

#[cfg(test)]
mod tests {
    use super::escape_controls;

    #[test]
    fn control_characters_are_escaped_and_the_rest_kept() {
        assert_eq!(escape_controls("a\u{1b}[31mred\nb\u{7f}\u{9b}é"), "a\\u{1b}[31mred\\u{a}b\\u{7f}\\u{9b}é");
        assert_eq!(escape_controls("plain ünïcode"), "plain ünïcode");
        assert_eq!(escape_controls("a\u{202e}gnp.exe\u{2066}x\u{200f}"), "a\\u{202e}gnp.exe\\u{2066}x\\u{200f}");
        let once = escape_controls("\u{1b}]0;title\u{7}").into_owned();
        assert_eq!(escape_controls(&once), once);
    }
}
