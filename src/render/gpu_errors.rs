//! The device's errors as values: out-of-memory and validation errors caught by error scopes
//! around the work that may raise them, on one line, instead of wgpu's uncaptured-error panic;
//! and buffers made with their contents without a mapping that panics when it fails.

/// Runs `make` inside out-of-memory and validation error scopes: its value, or the first error
/// the device raised meanwhile, on one line (what `make` made is then not to be used).
pub fn caught<T>(device: &wgpu::Device, make: impl FnOnce() -> T) -> Result<T, String> {
    let out_of_memory = device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
    let invalid = device.push_error_scope(wgpu::ErrorFilter::Validation);
    let made = make();
    let errors = [invalid.pop(), out_of_memory.pop()].map(popped_now);
    match errors.into_iter().flatten().next() {
        Some(error) => Err(one_line(&error)),
        None => Ok(made),
    }
}

/// The error and its causes, each by its first non-empty line, joined by ": ".
fn one_line(error: &wgpu::Error) -> String {
    let mut lines = vec![];
    let mut cause: Option<&dyn std::error::Error> = Some(error);
    while let Some(error) = cause {
        lines.extend(error.to_string().lines().map(str::trim).find(|line| !line.is_empty()).map(str::to_owned));
        cause = error.source();
    }
    lines.dedup();
    lines.join(": ")
}

/// A buffer of `usage` holding `contents` (padded to wgpu's 4-byte copy alignment, at least 4
/// bytes). As `DeviceExt::create_buffer_init`, but a mapping the device could not make leaves
/// the buffer unwritten, with the device's error raised for [`caught`], instead of panicking.
pub fn buffer_with(device: &wgpu::Device, label: &str, contents: &[u8], usage: wgpu::BufferUsages) -> wgpu::Buffer {
    let align = wgpu::COPY_BUFFER_ALIGNMENT;
    let size = (contents.len() as u64).div_ceil(align).max(1) * align;
    let buffer =
        device.create_buffer(&wgpu::BufferDescriptor { label: Some(label), size, usage, mapped_at_creation: true });
    if let Ok(mut mapped) = buffer.get_mapped_range_mut(..) {
        mapped.slice(..contents.len()).copy_from_slice(contents);
    }
    buffer.unmap();
    buffer
}

/// The error an error scope's pop resolved to, if it resolved at once (native backends do;
/// where it does not, as on the web, the error goes to the device's handler as before).
fn popped_now(popped: impl std::future::Future<Output = Option<wgpu::Error>>) -> Option<wgpu::Error> {
    let mut context = std::task::Context::from_waker(std::task::Waker::noop());
    match std::pin::pin!(popped).poll(&mut context) {
        std::task::Poll::Ready(error) => error,
        std::task::Poll::Pending => None,
    }
}
