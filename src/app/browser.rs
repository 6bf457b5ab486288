//! What the viewer asks of the browser in the web build (wasm32, docs/web.md): files the browser
//! gave held in memory ([`bumpview::read::hold_in_memory`]), downloads, and what the web build
//! does not have. A leaf: the controller, the dialog, the panel and the web start
//! ([`super::web`]) call it; it calls none of them.

use std::path::PathBuf;
use std::sync::Arc;

use bumpview::read::{MEMORY_FOLDER, hold_in_memory};
use wasm_bindgen::JsCast;

/// Holds the bytes of a file the browser gave (dropped or picked) in memory under
/// [`MEMORY_FOLDER`], and returns its path there.
pub fn hold(name: &str, bytes: Vec<u8>) -> PathBuf {
    let name = std::path::Path::new(name).file_name().map(PathBuf::from).unwrap_or_default();
    let path = PathBuf::from(MEMORY_FOLDER).join(name);
    hold_in_memory(path.clone(), Arc::from(bytes));
    path
}

/// What the panel says in the web build: the adapter (and so the backend, WebGPU or WebGL2) the
/// browser gave and what the web build does not have.
pub fn panel_note(ui: &mut egui::Ui, adapter: &str) {
    ui.small(format!(
        "In the browser on {adapter}: missing tangents by MikkTSpace (bevy_mikktspace; no meshoptimizer \
         here); one thread; files by drop or Open…; no hot reload; presets download; no screenshots \
         (their GPU read-back blocks)."
    ));
}

/// Why the web build makes no screenshots or tile exports.
pub const NO_CAPTURE: &str = "no screenshots or tile exports in the browser: their GPU read-back waits, \
                              which a page cannot (use the native build's `bumpview render`)";

/// Offers `bytes` to the user as a download named `name` (a screenshot, a preset).
pub fn download(name: &str, mime: &str, bytes: &[u8]) -> Result<(), String> {
    let failed = |what: &str| format!("download of {name}: {what}");
    let array = js_sys_array(bytes);
    let properties = web_sys::BlobPropertyBag::new();
    properties.set_type(mime);
    let blob =
        web_sys::Blob::new_with_u8_array_sequence_and_options(&array, &properties).map_err(|_| failed("no blob"))?;
    let url = web_sys::Url::create_object_url_with_blob(&blob).map_err(|_| failed("no object URL"))?;
    let document = web_sys::window().and_then(|w| w.document()).ok_or_else(|| failed("no document"))?;
    let anchor = document
        .create_element("a")
        .ok()
        .and_then(|e| e.dyn_into::<web_sys::HtmlAnchorElement>().ok())
        .ok_or_else(|| failed("no link"))?;
    anchor.set_href(&url);
    anchor.set_download(name);
    anchor.click();
    let _ = web_sys::Url::revoke_object_url(&url);
    Ok(())
}

/// `bytes` as the one-element sequence of `Uint8Array`s a `Blob` is made from.
fn js_sys_array(bytes: &[u8]) -> wasm_bindgen::JsValue {
    let array = js_sys::Array::new();
    array.push(&js_sys::Uint8Array::from(bytes));
    array.into()
}
