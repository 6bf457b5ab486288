//! The legacy looks' frame-wide textures (group 0 of the mesh shader): DOT3's normalization
//! cube map and the emboss look's light map, both made by [`crate::chain::legacy`] and
//! uploaded on first use, dropped once no picture uses them; 1×1 placeholders stand in while
//! a picture needs neither. Also the frame bind groups that hold them.

use wgpu::util::DeviceExt;

use super::bindings;
use crate::chain::legacy::{LIGHT_MAP_SIZE, cube_map, light_map};
use crate::counters::WorkCounters;
use crate::frame::{LegacyLook, ShadingSettings};

/// The legacy textures one picture binds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct LegacyNeeds {
    /// DOT3's cube map face size.
    pub cube_map: Option<u32>,
    pub light_map: bool,
}

impl LegacyNeeds {
    /// What a picture drawn with `shading` binds (lit views only).
    pub fn of(shading: &ShadingSettings) -> LegacyNeeds {
        let lit = shading.view.is_lit();
        LegacyNeeds {
            cube_map: shading.legacy.cube_map_in_use().filter(|_| lit),
            light_map: lit && shading.legacy.look == LegacyLook::Emboss,
        }
    }
}

/// The uploaded legacy textures and the placeholders.
pub struct LegacyTextures {
    placeholder_cube: wgpu::TextureView,
    placeholder_map: wgpu::TextureView,
    cube_maps: Vec<(u32, wgpu::TextureView)>,
    light_map: Option<wgpu::TextureView>,
}

/// Uploads `texels` (RGBA8, linear) as a `size`×`size` texture of `layers` layers.
fn upload(
    device: &wgpu::Device,
    queue: &wgpu::Queue,
    label: &str,
    size: u32,
    layers: u32,
    texels: &[[u8; 4]],
) -> wgpu::TextureView {
    let texture = device.create_texture_with_data(
        queue,
        &wgpu::TextureDescriptor {
            label: Some(label),
            size: wgpu::Extent3d { width: size, height: size, depth_or_array_layers: layers },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: wgpu::TextureFormat::Rgba8Unorm,
            usage: wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        },
        wgpu::util::TextureDataOrder::LayerMajor,
        bytemuck::cast_slice(texels),
    );
    let dimension = if layers > 1 { wgpu::TextureViewDimension::D2Array } else { wgpu::TextureViewDimension::D2 };
    texture.create_view(&wgpu::TextureViewDescriptor { dimension: Some(dimension), ..Default::default() })
}

impl LegacyTextures {
    pub fn new(device: &wgpu::Device, queue: &wgpu::Queue) -> LegacyTextures {
        let black = [[0u8, 0, 0, 255]; 6];
        LegacyTextures {
            placeholder_cube: upload(device, queue, "cube map placeholder", 1, 6, &black),
            placeholder_map: upload(device, queue, "light map placeholder", 1, 1, &black[..1]),
            cube_maps: vec![],
            light_map: None,
        }
    }

    /// Keeps the textures `needs` ask for, uploading those missing, and drops the others.
    pub fn retain(
        &mut self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        needs: &[LegacyNeeds],
        counters: &mut WorkCounters,
    ) {
        self.cube_maps.retain(|(size, _)| needs.iter().any(|n| n.cube_map == Some(*size)));
        for size in needs.iter().filter_map(|n| n.cube_map) {
            if !self.cube_maps.iter().any(|(made, _)| *made == size) {
                let view = upload(device, queue, "normalization cube map", size, 6, &cube_map(size));
                counters.textures_uploaded += 1;
                self.cube_maps.push((size, view));
            }
        }
        if !needs.iter().any(|n| n.light_map) {
            self.light_map = None;
        } else if self.light_map.is_none() {
            self.light_map = Some(upload(device, queue, "emboss light map", LIGHT_MAP_SIZE, 1, light_map()));
            counters.textures_uploaded += 1;
        }
    }

    /// The frame bind group: `uniform` and the textures `needs` asks for (made by
    /// [`Self::retain`]), placeholders elsewhere.
    pub fn bind_group(
        &self,
        device: &wgpu::Device,
        layout: &wgpu::BindGroupLayout,
        uniform: &wgpu::Buffer,
        needs: LegacyNeeds,
    ) -> wgpu::BindGroup {
        let cube = needs
            .cube_map
            .and_then(|size| self.cube_maps.iter().find(|(made, _)| *made == size))
            .map_or(&self.placeholder_cube, |(_, view)| view);
        let map = self.light_map.as_ref().filter(|_| needs.light_map).unwrap_or(&self.placeholder_map);
        device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("frame"),
            layout,
            entries: &[
                bindings::FRAME.entry(uniform.as_entire_binding()),
                bindings::NORMALIZATION_CUBE_MAP.entry(wgpu::BindingResource::TextureView(cube)),
                bindings::EMBOSS_LIGHT_MAP.entry(wgpu::BindingResource::TextureView(map)),
            ],
        })
    }
}
