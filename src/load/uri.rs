//! The URIs a glTF file refers to its buffers and images by: base64 `data:` URIs, files
//! relative to the glTF's folder (`%20` and other escapes decoded), absolute paths and `file:`
//! URIs (`file:///PATH` and `file://localhost/PATH` are `/PATH`; other hosts are refused). Remote
//! (`http:`, `https:`) and other schemes are never fetched. Files are read bounded
//! ([`crate::read`]).

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
