//! A GPU device without a window, for the `render` command, benchmarks and tests.

use crate::error::RenderError;

/// Adapter, device and queue. The backend follows `WGPU_BACKEND` (e.g. `vulkan` for
/// Mesa's lavapipe, `gl` for llvmpipe) when set.
pub struct Gpu {
    pub adapter: wgpu::Adapter,
    pub device: wgpu::Device,
    pub queue: wgpu::Queue,
}

impl Gpu {
    pub fn headless() -> Result<Gpu, RenderError> {
        let instance = wgpu::Instance::new(wgpu::InstanceDescriptor::new_without_display_handle_from_env());
        let options = wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::from_env().unwrap_or_default(),
            ..Default::default()
        };
        let adapter = pollster::block_on(instance.request_adapter(&options)).map_err(|e| RenderError::NoAdapter {
            backend: std::env::var("WGPU_BACKEND").unwrap_or_else(|_| "unset".into()),
            reason: e.to_string(),
        })?;
        // The wireframe overlay needs line polygon mode; without it the overlay is skipped.
        // Timestamps inside encoders time the report's frames on the GPU where available. BC
        // sampling takes a DDS or KTX2 file's blocks as they are.
        let wanted = wgpu::Features::POLYGON_MODE_LINE
            | wgpu::Features::TIMESTAMP_QUERY
            | wgpu::Features::TIMESTAMP_QUERY_INSIDE_ENCODERS
            | wgpu::Features::TEXTURE_COMPRESSION_BC;
        let required_features = adapter.features() & wanted;
        let descriptor = wgpu::DeviceDescriptor {
            label: Some("bumpview"),
            required_features,
            required_limits: adapter.limits(),
            ..Default::default()
        };
        let (device, queue) =
            pollster::block_on(adapter.request_device(&descriptor)).map_err(|e| RenderError::Device(e.to_string()))?;
        Ok(Gpu { adapter, device, queue })
    }

    /// "name (backend)" of the adapter, for reports and messages.
    pub fn adapter_name(&self) -> String {
        adapter_name(&self.adapter)
    }
}

/// "name (backend)" of an adapter.
pub fn adapter_name(adapter: &wgpu::Adapter) -> String {
    let info = adapter.get_info();
    format!("{} ({:?})", info.name, info.backend)
}
