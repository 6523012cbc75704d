//! Runs `shaders/phong.wgsl` as a compute shader through wgpu, so tests can compare the GPU's
//! numbers with `phong`'s CPU path. In CI the adapter is Mesa's software Vulkan driver (lavapipe,
//! Debian's `mesa-vulkan-drivers`, installed by `.ci/run`).

use phong::glam::Vec3;
use phong::gpu::{GpuLight, GpuMaterial, GpuParams};
use wgpu::util::DeviceExt;

/// The shader under test.
pub const WGSL: &str = include_str!("../../shaders/phong.wgsl");

/// One shaded point as the shader returns it.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GpuTerms {
    /// Ka ⊙ (Ia + Σ La·f)
    pub ambient: Vec3,
    /// Σ f·Kd⊙Ld·diffuse
    pub diffuse: Vec3,
    /// Σ f·Ks⊙Ls·specular
    pub specular: Vec3,
    /// Ke
    pub emission: Vec3,
}

/// A wgpu device with the compiled `shade_points` pipeline.
pub struct GpuShader {
    device: wgpu::Device,
    queue: wgpu::Queue,
    pipeline: wgpu::ComputePipeline,
    /// The adapter's name and driver, for test messages.
    pub adapter: String,
}

impl GpuShader {
    /// Opens the first adapter wgpu finds (any backend enabled in this crate: Vulkan), or `None`.
    pub fn new() -> Option<Self> {
        pollster::block_on(async {
            let instance = wgpu::Instance::new(wgpu::InstanceDescriptor {
                backends: wgpu::Backends::VULKAN,
                ..wgpu::InstanceDescriptor::new_without_display_handle()
            });
            let adapter = instance
                .request_adapter(&wgpu::RequestAdapterOptions::default())
                .await
                .ok()?;
            let info = adapter.get_info();
            let (device, queue) = adapter
                .request_device(&wgpu::DeviceDescriptor::default())
                .await
                .ok()?;
            let module = device.create_shader_module(wgpu::ShaderModuleDescriptor {
                label: Some("phong.wgsl"),
                source: wgpu::ShaderSource::Wgsl(WGSL.into()),
            });
            let pipeline = device.create_compute_pipeline(&wgpu::ComputePipelineDescriptor {
                label: Some("shade_points"),
                layout: None,
                module: &module,
                entry_point: Some("shade_points"),
                compilation_options: Default::default(),
                cache: None,
            });
            Some(GpuShader {
                device,
                queue,
                pipeline,
                adapter: format!("{} ({:?}, {})", info.name, info.backend, info.driver_info),
            })
        })
    }

    /// Shades `positions[i]`, `normals[i]` under one parameter set; returns one `GpuTerms` each.
    pub fn shade(
        &self,
        params: &GpuParams,
        material: &GpuMaterial,
        lights: &[GpuLight],
        positions: &[Vec3],
        normals: &[Vec3],
    ) -> Vec<GpuTerms> {
        assert_eq!(positions.len(), normals.len(), "one normal per position");
        let n = positions.len();
        let d = &self.device;
        let to4 =
            |v: &[Vec3]| -> Vec<[f32; 4]> { v.iter().map(|p| p.extend(0.0).to_array()).collect() };
        let init = |label, contents: &[u8], usage| {
            d.create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some(label),
                contents,
                usage,
            })
        };
        let storage = wgpu::BufferUsages::STORAGE;
        let uniform = wgpu::BufferUsages::UNIFORM;
        // An empty storage binding is invalid: always bind at least one light record.
        let light_data: Vec<GpuLight> = if lights.is_empty() {
            vec![GpuLight::default()]
        } else {
            lights.to_vec()
        };
        let b_params = init("params", bytemuck::bytes_of(params), uniform);
        let b_material = init("material", bytemuck::bytes_of(material), uniform);
        let b_lights = init("lights", bytemuck::cast_slice(&light_data), storage);
        let b_pos = init("positions", bytemuck::cast_slice(&to4(positions)), storage);
        let b_nrm = init("normals", bytemuck::cast_slice(&to4(normals)), storage);
        let out_size = (n * 64) as u64;
        let b_out = d.create_buffer(&wgpu::BufferDescriptor {
            label: Some("terms"),
            size: out_size,
            usage: storage | wgpu::BufferUsages::COPY_SRC,
            mapped_at_creation: false,
        });
        let b_read = d.create_buffer(&wgpu::BufferDescriptor {
            label: Some("readback"),
            size: out_size,
            usage: wgpu::BufferUsages::MAP_READ | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        let bind = d.create_bind_group(&wgpu::BindGroupDescriptor {
            label: None,
            layout: &self.pipeline.get_bind_group_layout(0),
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: b_params.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: b_material.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: b_lights.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 3,
                    resource: b_pos.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 4,
                    resource: b_nrm.as_entire_binding(),
                },
                wgpu::BindGroupEntry {
                    binding: 5,
                    resource: b_out.as_entire_binding(),
                },
            ],
        });
        let mut enc = d.create_command_encoder(&Default::default());
        {
            let mut pass = enc.begin_compute_pass(&Default::default());
            pass.set_pipeline(&self.pipeline);
            pass.set_bind_group(0, &bind, &[]);
            pass.dispatch_workgroups((n as u32).div_ceil(64), 1, 1);
        }
        enc.copy_buffer_to_buffer(&b_out, 0, &b_read, 0, out_size);
        self.queue.submit([enc.finish()]);
        let slice = b_read.slice(..);
        slice.map_async(wgpu::MapMode::Read, |r| r.expect("readback maps"));
        d.poll(wgpu::PollType::wait_indefinitely())
            .expect("device poll");
        let data = slice.get_mapped_range().expect("mapped range");
        let floats: &[[f32; 16]] = bytemuck::cast_slice(&data);
        floats
            .iter()
            .map(|t| GpuTerms {
                ambient: Vec3::new(t[0], t[1], t[2]),
                diffuse: Vec3::new(t[4], t[5], t[6]),
                specular: Vec3::new(t[8], t[9], t[10]),
                emission: Vec3::new(t[12], t[13], t[14]),
            })
            .collect()
    }
}
