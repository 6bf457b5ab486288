//! The URIs a glTF file refers to its buffers and images by: base64 `data:` URIs, files
//! relative to the glTF's folder (`%20` and other escapes decoded), absolute paths and `file:`
//! URIs (`file:///PATH` and `file://localhost/PATH` are `/PATH`; other hosts are refused). Remote
//! (`http:`, `https:`) and other schemes are never fetched. Files are read bounded
//! ([`crate::read`]).
//!
//! Files outside the model's folder (an absolute path, a path through `..`, or a path whose
//! symbolic links lead out) are read only where the user allowed it: inside
//! [`with_outside_files`] (how [`super::load_model`] loads for the command line and the
//! viewer), a refused file fails the load with one line naming it and the flag and preset
//! key that allow it ([`admit_file`]). [`super::load_scene`] alone reads them and warns.

use std::cell::RefCell;
use std::path::{Path, PathBuf};

use base64::Engine;

use crate::error::{LoadError, LoadWarning};
use crate::read::{FileKind, read_file};

/// Where a buffer or image URI points.
pub enum UriTarget {
    /// A base64 `data:` URI's bytes.
    Data(Vec<u8>),
    /// A file (a relative path from the glTF's folder, `%20` and other escapes decoded; an
    /// absolute path; or a `file:` URI), and whether it lies outside the glTF's folder.
    File { path: PathBuf, outside: bool },
}

/// Where `uri` points, or why it cannot be read here: a remote (`http:`, `https:`) or other
/// non-file URI is never fetched.
pub fn resolve_uri(uri: &str, base: &Path, gltf_path: &Path, what: &str) -> Result<UriTarget, LoadError> {
    if let Some(data) = uri.strip_prefix("data:") {
        let payload = data.split_once(";base64,").map(|(_, p)| p);
        let decoded = payload.and_then(|p| base64::engine::general_purpose::STANDARD.decode(p).ok());
        let bytes =
            decoded.ok_or_else(|| LoadError::new(gltf_path, format!("a {what} data URI is not valid base64")))?;
        return Ok(UriTarget::Data(bytes));
    }
    // A scheme is letters, digits, `+`, `-`, `.` before a colon; one letter is a Windows drive.
    let scheme = uri.split_once(':').map(|(s, _)| s).filter(|s| {
        s.len() > 1
            && s.starts_with(|c: char| c.is_ascii_alphabetic())
            && s.chars().all(|c| c.is_ascii_alphanumeric() || "+-.".contains(c))
    });
    let relative = match scheme.map(str::to_ascii_lowercase).as_deref() {
        None => uri,
        Some("file") => file_uri_path(&uri["file:".len()..]).ok_or_else(|| {
            let problem = format!("the {what} {uri:?} names a file on another host: only local files are read");
            LoadError::new(gltf_path, problem)
        })?,
        Some(remote @ ("http" | "https")) => {
            let problem = format!("the {what} {uri:?} is remote ({remote}): remote files are not fetched");
            return Err(LoadError::new(gltf_path, problem));
        }
        Some(other) => {
            let problem = format!("the {what} {uri:?} has the URI scheme {other:?}: only files and data URIs are read");
            return Err(LoadError::new(gltf_path, problem));
        }
    };
    let decoded = percent_encoding::percent_decode_str(relative).decode_utf8_lossy();
    let path =
        [base.join(&*decoded), base.join(relative)].into_iter().find(|p| p.is_file()).unwrap_or(base.join(&*decoded));
    let leaves = Path::new(&*decoded).components().any(|c| c == std::path::Component::ParentDir);
    let outside = Path::new(&*decoded).is_absolute() || leaves;
    Ok(UriTarget::File { path, outside })
}

/// The path of a `file:` URI after its scheme (RFC 8089): `//HOST/PATH` with an empty host or
/// `localhost` is the absolute `/PATH`; without `//` the rest is the path; `None` for another
/// host. (`file:///C:/x` on Windows is `C:/x`.)
fn file_uri_path(rest: &str) -> Option<&str> {
    let Some(authority_and_path) = rest.strip_prefix("//") else { return Some(rest) };
    let (host, path) = authority_and_path.split_at(authority_and_path.find('/').unwrap_or(authority_and_path.len()));
    if !(host.is_empty() || host.eq_ignore_ascii_case("localhost")) {
        return None;
    }
    let drive = path.get(1..3).is_some_and(|d| d.starts_with(|c: char| c.is_ascii_alphabetic()) && d.ends_with(':'));
    Some(if cfg!(windows) && drive { &path[1..] } else { path })
}

/// The note an error about a file outside the glTF's folder ends with.
pub const NOT_PORTABLE_NOTE: &str = "it lies outside the model's folder: the model is not portable";

/// The bytes a buffer or image URI points to (read as `kind`, [`read_file`]) and the file to
/// name in errors; a file outside the glTF's folder adds a [`LoadWarning::NotPortable`] to
/// `warnings`, and an error reading it ends with [`NOT_PORTABLE_NOTE`].
pub fn read_uri(
    uri: &str,
    base: &Path,
    gltf_path: &Path,
    kind: FileKind,
    warnings: &mut Vec<LoadWarning>,
) -> Result<(Vec<u8>, PathBuf), LoadError> {
    let what = kind.name();
    let (path, outside) = match resolve_uri(uri, base, gltf_path, what)? {
        UriTarget::Data(bytes) => return Ok((bytes, gltf_path.to_owned())),
        UriTarget::File { path, outside } => (path, outside),
    };
    let outside = admit_file(&path, gltf_path, what)? || outside;
    let bytes = read_file(&path, kind).map_err(|e| {
        let referrer = gltf_path.file_name().unwrap_or_default().to_string_lossy();
        let note = if outside { format!("; {NOT_PORTABLE_NOTE}") } else { String::new() };
        LoadError::new(&path, format!("could not read the {what} file that {referrer} refers to: {e}{note}"))
    })?;
    if outside {
        warnings.push(LoadWarning::NotPortable { uri: uri.to_owned(), file: path.clone() });
    }
    Ok((bytes, path))
}

/// What [`with_outside_files`] set for this thread's load: whether files outside the model's
/// folder may be read, that folder, and the first file refused.
struct OutsideRule {
    allowed: bool,
    folder: PathBuf,
    refused: Option<LoadError>,
}

thread_local! {
    /// The rule of the load running on this thread (`None`: outside files read with a warning).
    static RULE: RefCell<Option<OutsideRule>> = const { RefCell::new(None) };
}

/// The flag that allows files outside the model's folder, as the refusal names it.
pub const ALLOW_FLAG: &str = "--allow-outside-files";

/// The preset key that allows them (in `[files]`), as the refusal names it.
pub const ALLOW_KEY: &str = "allow_outside_files";

/// Runs `load` (the loading of the model `model`) with files outside `model`'s folder
/// `allowed` or not. When not, the first one the model names fails the load: its error is
/// returned whatever `load` made of it (a texture that could not be read is otherwise only a
/// warning), and nothing outside was read.
pub fn with_outside_files<T>(
    model: &Path,
    allowed: bool,
    load: impl FnOnce() -> Result<T, LoadError>,
) -> Result<T, LoadError> {
    let folder = model.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let rule = OutsideRule { allowed, folder: folder.to_owned(), refused: None };
    /// Puts back the rule of an enclosing load, also when `load` panics.
    struct Restore(Option<OutsideRule>);
    impl Drop for Restore {
        fn drop(&mut self) {
            RULE.with(|r| *r.borrow_mut() = self.0.take());
        }
    }
    let restore = Restore(RULE.with(|r| r.borrow_mut().replace(rule)));
    let loaded = load();
    let refused = RULE.with(|r| r.borrow_mut().as_mut().and_then(|rule| rule.refused.take()));
    drop(restore);
    match refused {
        Some(error) => Err(error),
        None => loaded,
    }
}

/// Whether `file` lies outside `folder`: as written (each made absolute, `.` and `..` folded,
/// so `a/../../x` is out), or once both are resolved (a symbolic link inside leading out).
fn lies_outside(file: &Path, folder: &Path) -> bool {
    let lexical = |path: &Path| {
        let absolute = std::path::absolute(path).unwrap_or_else(|_| path.to_owned());
        let mut folded = PathBuf::new();
        for component in absolute.components() {
            match component {
                std::path::Component::ParentDir => {
                    folded.pop();
                }
                std::path::Component::CurDir => {}
                other => folded.push(other),
            }
        }
        folded
    };
    let resolved = std::fs::canonicalize(file).ok().zip(std::fs::canonicalize(folder).ok());
    !lexical(file).starts_with(lexical(folder)) || resolved.is_some_and(|(file, folder)| !file.starts_with(folder))
}

/// Whether the model may read `file`, which `referrer` names as its `what`: `Ok(false)`
/// inside the model's folder ([`lies_outside`]); `Ok(true)` outside it where that is allowed
/// (or no rule is set: the caller warns that the model is not portable); an error naming the file and how to allow it where it is
/// not (the first such error is also kept for [`with_outside_files`]).
pub fn admit_file(file: &Path, referrer: &Path, what: &str) -> Result<bool, LoadError> {
    let local = referrer.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    RULE.with(|r| {
        let mut rule = r.borrow_mut();
        let folder = rule.as_ref().map_or(local, |rule| rule.folder.as_path());
        if !lies_outside(file, folder) {
            return Ok(false);
        }
        let Some(rule) = rule.as_mut().filter(|rule| !rule.allowed) else { return Ok(true) };
        let referrer = referrer.file_name().unwrap_or_default().to_string_lossy();
        let problem = format!(
            "the {what} that {referrer} names lies outside the model's folder ({}) and was not read: pass {ALLOW_FLAG} (or set {ALLOW_KEY} = true in a preset's [files]) to allow it",
            rule.folder.display()
        );
        let error = LoadError::new(file, problem);
        rule.refused.get_or_insert_with(|| LoadError::new(file, error.problem.clone()));
        Err(error)
    })
}
