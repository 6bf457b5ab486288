//! `EXT_meshopt_compression`: buffer views whose bytes are meshoptimizer-compressed in another
//! buffer. Each such view is decoded (meshoptimizer's vertex, index and sequence codecs and its
//! filters, through the `meshopt` crate's bindings; native builds only) into its place in the
//! view's own buffer, the fallback buffer, so the accessors read it as any other view. A
//! fallback buffer that only stands in for compressed views (`"fallback": true`, no `uri`) is
//! made here, zeroed, after its length is charged to the load's [`Budget`].
//!
//! Everything the extension states is checked before it is used: the source range lies in its
//! buffer, the decoded range (`count · byteStride`) in the view, and mode, stride and filter
//! form a combination the codecs accept (their C asserts are never reached).
//!
//! The browser build has no meshoptimizer: there a file whose fallback buffers hold data is
//! read from them, and one that needs decoding is refused in one line.

use gltf::json::Value;

use super::budget::{Budget, try_vec};

/// The extension's name.
pub const EXTENSION: &str = "EXT_meshopt_compression";

/// Whether `buffer` is a fallback that holds no data of its own: no `uri` and the extension's
/// `"fallback": true`.
pub fn is_fallback(buffer: &gltf::Buffer) -> bool {
    let flagged = buffer.extension_value(EXTENSION).and_then(|e| e.get("fallback")).and_then(Value::as_bool);
    flagged == Some(true) && matches!(buffer.source(), gltf::buffer::Source::Bin)
}

/// Makes every fallback buffer (empty in `buffers`) its stated length, charged to `budget`,
/// then decodes every compressed view into its fallback buffer. The error is one line.
pub fn decompress_views(document: &gltf::Document, buffers: &mut [Vec<u8>], budget: &mut Budget) -> Result<(), String> {
    for buffer in document.buffers().filter(is_fallback) {
        let length = buffer.length();
        budget.charge(length as u64).map_err(|over| format!("fallback buffer {} {over}", buffer.index()))?;
        let mut zeroed = try_vec(length).ok_or_else(|| format!("no memory for fallback buffer {}", buffer.index()))?;
        zeroed.resize(length, 0);
        buffers[buffer.index()] = zeroed;
    }
    for view in document.views() {
        // The browser build cannot decode: a fallback that holds data is read as it is.
        if cfg!(target_arch = "wasm32") && !is_fallback(&view.buffer()) {
            continue;
        }
        if let Some(extension) = view.extension_value(EXTENSION) {
            decode_view(&view, extension, buffers)
                .map_err(|problem| format!("bufferView {}: {problem}", view.index()))?;
        }
    }
    Ok(())
}

/// What the extension object of one view states.
struct Compressed {
    buffer: usize,
    offset: usize,
    length: usize,
    stride: usize,
    count: usize,
    mode: String,
    filter: String,
}

fn read(extension: &Value) -> Result<Compressed, String> {
    let number = |key: &str| -> Result<usize, String> {
        let value = extension.get(key).and_then(Value::as_u64).ok_or_else(|| format!("{EXTENSION} has no {key}"))?;
        usize::try_from(value).map_err(|_| format!("{EXTENSION}'s {key} is too large"))
    };
    let text = |key: &str| extension.get(key).and_then(Value::as_str).map(str::to_owned);
    Ok(Compressed {
        buffer: number("buffer")?,
        offset: extension.get("byteOffset").map_or(Ok(0), |_| number("byteOffset"))?,
        length: number("byteLength")?,
        stride: number("byteStride")?,
        count: number("count")?,
        mode: text("mode").ok_or_else(|| format!("{EXTENSION} has no mode"))?,
        filter: text("filter").unwrap_or_else(|| "NONE".to_owned()),
    })
}

/// Decodes one view's compressed bytes into its place in its own buffer.
fn decode_view(view: &gltf::buffer::View, extension: &Value, buffers: &mut [Vec<u8>]) -> Result<(), String> {
    let c = read(extension)?;
    let source = buffers
        .get(c.buffer)
        .and_then(|b| b.get(c.offset..c.offset.checked_add(c.length)?))
        .ok_or_else(|| format!("the compressed bytes lie outside buffer {}", c.buffer))?
        .to_vec();
    let bytes = c.count.checked_mul(c.stride).filter(|&b| b <= view.length());
    let bytes = bytes.ok_or_else(|| format!("{} × {} decoded bytes do not fit the view", c.count, c.stride))?;
    let target = buffers[view.buffer().index()]
        .get_mut(view.offset()..view.offset() + bytes)
        .ok_or("the view lies outside its buffer")?;
    decode(&c, &source, target)
}

/// The codec and filter of `c` on `source` into `target` (`count · stride` bytes).
#[cfg(not(target_arch = "wasm32"))]
fn decode(c: &Compressed, source: &[u8], target: &mut [u8]) -> Result<(), String> {
    use meshopt::ffi;
    let (count, stride) = (c.count, c.stride);
    let valid = match (c.mode.as_str(), c.filter.as_str()) {
        ("ATTRIBUTES", "NONE") => stride.is_multiple_of(4) && stride <= 256,
        ("ATTRIBUTES", "OCTAHEDRAL") => stride == 4 || stride == 8,
        ("ATTRIBUTES", "QUATERNION") => stride == 8,
        ("ATTRIBUTES", "EXPONENTIAL") => stride.is_multiple_of(4) && stride <= 256,
        ("TRIANGLES", "NONE") => (stride == 2 || stride == 4) && count.is_multiple_of(3),
        ("INDICES", "NONE") => stride == 2 || stride == 4,
        _ => false,
    };
    if !valid || stride == 0 {
        return Err(format!("mode {} with filter {} and byteStride {stride} is not decodable", c.mode, c.filter));
    }
    let (out, src) = (target.as_mut_ptr().cast(), source.as_ptr());
    // SAFETY: `target` holds `count · stride` bytes, `source` is read within its length, and the
    // mode, stride and filter were checked above against what each codec asserts.
    let status = unsafe {
        match c.mode.as_str() {
            "ATTRIBUTES" => ffi::meshopt_decodeVertexBuffer(out, count, stride, src, source.len()),
            "TRIANGLES" => ffi::meshopt_decodeIndexBuffer(out, count, stride, src, source.len()),
            _ => ffi::meshopt_decodeIndexSequence(out, count, stride, src, source.len()),
        }
    };
    if status != 0 {
        return Err(format!("the meshopt {} stream does not decode (error {status})", c.mode));
    }
    // SAFETY: as above; the filters rewrite `count · stride` bytes in place.
    unsafe {
        match c.filter.as_str() {
            "OCTAHEDRAL" => ffi::meshopt_decodeFilterOct(out, count, stride),
            "QUATERNION" => ffi::meshopt_decodeFilterQuat(out, count, stride),
            "EXPONENTIAL" => ffi::meshopt_decodeFilterExp(out, count, stride),
            _ => {}
        }
    }
    Ok(())
}

/// The browser build has no meshoptimizer.
#[cfg(target_arch = "wasm32")]
fn decode(c: &Compressed, _: &[u8], _: &mut [u8]) -> Result<(), String> {
    Err(format!(
        "{EXTENSION} needs the native build to decode its {} views (filter {}): meshoptimizer is not in the browser build",
        c.mode, c.filter
    ))
}
