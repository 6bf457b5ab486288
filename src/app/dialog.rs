//! The native file dialog (the `rfd` crate), run on its own thread so the window keeps
//! drawing while it is open. In the web build it is the browser's file picker (rfd's async
//! dialog), whose file is read as bytes and held in memory ([`crate::app::browser::hold`]).

use std::path::PathBuf;
use std::sync::mpsc;

use bumpview::load::TextureSlot;

/// Mesh files the dialog offers.
const MESH_FILTER: [&str; 3] = ["gltf", "glb", "obj"];
/// Texture files the dialog offers.
const IMAGE_FILTER: [&str; 8] = ["png", "jpg", "jpeg", "tga", "bmp", "webp", "dds", "ktx2"];

/// At most one open dialog and where its answer arrives.
#[derive(Default)]
pub struct Dialog {
    /// The slot the open dialog is for (`None`: any mesh or texture), and its answer.
    open: Option<(Option<TextureSlot>, mpsc::Receiver<Option<PathBuf>>)>,
}

impl Dialog {
    /// Whether a dialog is showing.
    pub fn is_open(&self) -> bool {
        self.open.is_some()
    }

    /// Shows a dialog for a mesh or texture (`slot = None`) or for a texture for `slot`,
    /// starting in `folder`; `wake` is called from the dialog's thread when it closes. The
    /// error says why no dialog can be shown.
    pub fn show(
        &mut self,
        slot: Option<TextureSlot>,
        folder: Option<PathBuf>,
        wake: impl Fn() + Send + 'static,
    ) -> Result<(), String> {
        if self.is_open() {
            return Err("a file dialog is already open".into());
        }
        let (sender, answer) = mpsc::channel();
        pick(slot, folder, sender, wake)?;
        self.open = Some((slot, answer));
        Ok(())
    }

    /// The dialog's answer once it has closed: its slot and the chosen file (`None`:
    /// cancelled, or no dialog could be shown).
    pub fn poll(&mut self) -> Option<(Option<TextureSlot>, Option<PathBuf>)> {
        let (slot, answer) = self.open.as_ref()?;
        let chosen = match answer.try_recv() {
            Ok(chosen) => chosen,
            Err(mpsc::TryRecvError::Empty) => return None,
            Err(mpsc::TryRecvError::Disconnected) => None,
        };
        let slot = *slot;
        self.open = None;
        Some((slot, chosen))
    }
}

/// The builder of the dialog for a mesh or texture (`slot = None`) or for `slot`'s texture.
macro_rules! dialog {
    ($kind:ty, $slot:expr) => {
        match $slot {
            None => <$kind>::new()
                .set_title("Open a mesh or a texture")
                .add_filter("Meshes and textures", &[MESH_FILTER.as_slice(), &IMAGE_FILTER].concat())
                .add_filter("Meshes (glTF, OBJ)", &MESH_FILTER)
                .add_filter("Textures", &IMAGE_FILTER),
            Some(slot) => <$kind>::new()
                .set_title(format!("Open a texture for the {} slot", slot.label()))
                .add_filter("Textures", &IMAGE_FILTER),
        }
    };
}

/// Shows the native dialog on a thread of its own, which sends the chosen file.
#[cfg(not(target_arch = "wasm32"))]
fn pick(
    slot: Option<TextureSlot>,
    folder: Option<PathBuf>,
    sender: mpsc::Sender<Option<PathBuf>>,
    wake: impl Fn() + Send + 'static,
) -> Result<(), String> {
    available()?;
    let mut dialog = dialog!(rfd::FileDialog, slot);
    if let Some(folder) = folder {
        dialog = dialog.set_directory(folder);
    }
    std::thread::Builder::new()
        .name("bumpview-dialog".into())
        .spawn(move || {
            let _ = sender.send(dialog.pick_file());
            wake();
        })
        .map(drop)
        .map_err(|e| format!("could not start the file dialog: {e}"))
}

/// Shows the browser's file picker; the chosen file is read and held in memory, and its path
/// there sent. A browser has no folder to start in.
#[cfg(target_arch = "wasm32")]
fn pick(
    slot: Option<TextureSlot>,
    _folder: Option<PathBuf>,
    sender: mpsc::Sender<Option<PathBuf>>,
    wake: impl Fn() + Send + 'static,
) -> Result<(), String> {
    let dialog = dialog!(rfd::AsyncFileDialog, slot);
    wasm_bindgen_futures::spawn_local(async move {
        let chosen = match dialog.pick_file().await {
            Some(file) => Some(crate::app::browser::hold(&file.file_name(), file.read().await)),
            None => None,
        };
        let _ = sender.send(chosen);
        wake();
    });
    Ok(())
}

/// On Linux and the BSDs rfd asks the XDG desktop portal over the D-Bus session bus, then
/// falls back to `zenity`; with neither there is no dialog, and rfd would only log it.
#[cfg(all(unix, not(target_os = "macos"), not(target_arch = "wasm32")))]
fn available() -> Result<(), String> {
    let zenity = std::env::var_os("PATH")
        .is_some_and(|path| std::env::split_paths(&path).any(|dir| dir.join("zenity").is_file()));
    if zenity || std::env::var_os("DBUS_SESSION_BUS_ADDRESS").is_some() {
        Ok(())
    } else {
        Err("no file dialog here (no D-Bus session for the desktop portal and no zenity): drop the \
             file on the window or give it on the command line"
            .into())
    }
}

/// Windows and macOS always have their native dialogs.
#[cfg(not(any(all(unix, not(target_os = "macos")), target_arch = "wasm32")))]
fn available() -> Result<(), String> {
    Ok(())
}
