//! The last tessellation read back from the GPU, as meshes: for the probe, which picks and
//! shades the triangles drawn, and for the tests that hold the GPU's vertices to the CPU's.

use std::sync::Arc;

use glam::{Vec2, Vec3};

use super::{State, Tessellation};
use crate::prepare::PreparedScene;
use crate::scene::Mesh;

impl Tessellation {
    /// Each GPU-displaced mesh as the last tessellation made it (`(index in the prepared
    /// scene's meshes, mesh)`, indices from 0 within the mesh); empty before the first.
    pub fn read_back(&self, device: &wgpu::Device, queue: &wgpu::Queue) -> Result<Vec<(usize, Mesh)>, String> {
        let state = self.state.lock().expect("tessellation state");
        self.read_back_from(&state, device, queue)
    }

    /// `prepared` (the scene this tessellation displaces) with the GPU-displaced meshes as the
    /// last tessellation drew them, for the probe to pick and shade; read back once per
    /// tessellation. `prepared` itself where reading back failed or nothing was drawn yet.
    pub fn drawn_prepared(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        prepared: &Arc<PreparedScene>,
    ) -> Arc<PreparedScene> {
        let mut state = self.state.lock().expect("tessellation state");
        if let Some(drawn) = &state.drawn {
            return Arc::clone(drawn);
        }
        let Ok(meshes) = self.read_back_from(&state, device, queue) else { return Arc::clone(prepared) };
        if meshes.is_empty() {
            return Arc::clone(prepared);
        }
        let mut drawn = PreparedScene::clone(prepared);
        for (index, mesh) in meshes {
            drawn.meshes[index].mesh = mesh;
        }
        let drawn = Arc::new(drawn);
        state.drawn = Some(Arc::clone(&drawn));
        drawn
    }

    fn read_back_from(
        &self,
        state: &State,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
    ) -> Result<Vec<(usize, Mesh)>, String> {
        let (Some(pool), Some(plan)) = (state.pool.as_ref(), state.plan.as_ref()) else { return Ok(vec![]) };
        let streams = [
            (&pool.positions, u64::from(plan.vertices) * 12),
            (&pool.normals, u64::from(plan.vertices) * 12),
            (&pool.uvs, u64::from(plan.vertices) * 8),
            (&pool.indices, u64::from(plan.triangles) * 12),
        ];
        let mut encoder = device.create_command_encoder(&wgpu::CommandEncoderDescriptor { label: Some("read back") });
        let staging: Vec<wgpu::Buffer> = streams
            .iter()
            .map(|&(source, bytes)| {
                let staging = device.create_buffer(&wgpu::BufferDescriptor {
                    label: Some("GPU displacement read-back"),
                    size: bytes.max(4),
                    usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
                    mapped_at_creation: false,
                });
                encoder.copy_buffer_to_buffer(source, 0, &staging, 0, bytes);
                staging
            })
            .collect();
        queue.submit([encoder.finish()]);
        let (sender, receiver) = std::sync::mpsc::channel();
        for buffer in &staging {
            let sender = sender.clone();
            buffer.slice(..).map_async(wgpu::MapMode::Read, move |result| {
                let _ = sender.send(result);
            });
        }
        device.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| e.to_string())?;
        for _ in &staging {
            receiver.recv().map_err(|e| e.to_string())?.map_err(|e| e.to_string())?;
        }
        let read = |k: usize| -> Result<Vec<f32>, String> {
            let mapped = staging[k].slice(..).get_mapped_range().map_err(|e| e.to_string())?;
            Ok(bytemuck::cast_slice(&mapped[..streams[k].1 as usize]).to_vec())
        };
        let (positions, normals, uvs) = (read(0)?, read(1)?, read(2)?);
        let indices: Vec<u32> = read(3)?.into_iter().map(f32::to_bits).collect();
        let vec3 = |data: &[f32], i: usize| Vec3::from_slice(&data[3 * i..3 * i + 3]);
        let meshes = self.meshes.iter().zip(&plan.meshes).map(|(mesh, ranges)| {
            let vertices = ranges.first_vertex as usize..(ranges.first_vertex + ranges.vertices) as usize;
            let mut out = Mesh::empty(&mesh.base.name);
            out.positions = vertices.clone().map(|i| vec3(&positions, i)).collect();
            out.normals = vertices.clone().map(|i| vec3(&normals, i)).collect();
            out.uvs = vertices.map(|i| Vec2::new(uvs[2 * i], uvs[2 * i + 1])).collect();
            let triangles = ranges.first_index as usize..(ranges.first_index + ranges.indices) as usize;
            out.indices = indices[triangles].iter().map(|i| i - ranges.first_vertex).collect();
            (mesh.mesh, out)
        });
        Ok(meshes.collect())
    }
}
