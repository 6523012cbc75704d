//! GPU-layout mirrors of the shading parameters, for uniform and storage buffers.
//!
//! A renderer that shades on the GPU uploads these structs as they are: each is `#[repr(C)]`,
//! [`bytemuck::Pod`], and laid out by the std140 rules (which for these structs coincide with std430
//! and WGSL's uniform layout): every `vec3` starts on a 16-byte boundary and is followed by one
//! scalar that fills its fourth slot. `shaders/phong.wgsl` declares the same structs and implements
//! the same models, gates and attenuation with the crate's conventions, and `shaders/phong.glsl` is
//! naga's GLSL translation of it; `tests/gpu_layout.rs` checks with naga that both shaders parse and
//! validate, that their struct sizes and member offsets equal these (`size_of`, `offset_of!`), and
//! that the GLSL is the translation of the current WGSL.
//!
//! Enumerations travel as `u32` codes, listed on each field.

use glam::Vec3;

use crate::{
    Attenuation, BatchModel, BlinnPhong, Lambert, Light, LightSource, Material, Model,
    Normalization, Phong, SpecularGate, Viewer,
};

/// [`Material`] for a uniform buffer: 64 bytes.
///
/// | offset | field |
/// |---:|---|
/// | 0 | `ambient: vec3<f32>`, 12 `shininess: f32` |
/// | 16 | `diffuse: vec3<f32>`, 28 `_pad0` |
/// | 32 | `specular: vec3<f32>`, 44 `_pad1` |
/// | 48 | `emission: vec3<f32>`, 60 `_pad2` |
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
#[allow(missing_docs, reason = "fields mirror Material's accessors one to one")]
pub struct GpuMaterial {
    pub ambient: [f32; 3],
    pub shininess: f32,
    pub diffuse: [f32; 3],
    pub _pad0: f32,
    pub specular: [f32; 3],
    pub _pad1: f32,
    pub emission: [f32; 3],
    pub _pad2: f32,
}

/// One light for a storage buffer (`array<GpuLight>`): 96 bytes.
///
/// | offset | field |
/// |---:|---|
/// | 0 | `position: vec3<f32>`, 12 `kind: u32` (0 directional, 1 point, 2 spot) |
/// | 16 | `direction: vec3<f32>` (directional: toward the light; spot: the cone axis), 28 `cos_cutoff: f32` |
/// | 32 | `ambient: vec3<f32>`, 44 `spot_exponent: f32` |
/// | 48 | `diffuse: vec3<f32>`, 60 `attenuation_kind: u32` (0 none, 1 polynomial, 2 inverse-square, 3 Unreal, 4 Frostbite) |
/// | 64 | `specular: vec3<f32>`, 76 `_pad0` |
/// | 80 | `attenuation: vec4<f32>`: (c, l, q, 0), (P, ε, 0, 0), (r, 0, 0, 0) or (r, ε, 0, 0) |
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
#[allow(missing_docs, reason = "fields documented in the table above")]
pub struct GpuLight {
    pub position: [f32; 3],
    pub kind: u32,
    pub direction: [f32; 3],
    pub cos_cutoff: f32,
    pub ambient: [f32; 3],
    pub spot_exponent: f32,
    pub diffuse: [f32; 3],
    pub attenuation_kind: u32,
    pub specular: [f32; 3],
    pub _pad0: f32,
    pub attenuation: [f32; 4],
}

/// Per-draw shading state for a uniform buffer: 48 bytes.
///
/// | offset | field |
/// |---:|---|
/// | 0 | `viewer: vec3<f32>` (position, or direction toward the viewer), 12 `viewer_kind: u32` (0 at a point, 1 infinite) |
/// | 16 | `ambient: vec3<f32>` (scene ambient `Ia`), 28 `light_count: u32` |
/// | 32 | `model: u32` (0 Lambert, 1 Phong, 2 Blinn-Phong), 36 `gate: u32` (0 step, 1 cosine, 2 none), 40 `normalization: u32` (0 none, 1 energy, 2 exact), 44 `_pad0` |
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, bytemuck::Pod, bytemuck::Zeroable)]
#[allow(missing_docs, reason = "fields documented in the table above")]
pub struct GpuParams {
    pub viewer: [f32; 3],
    pub viewer_kind: u32,
    pub ambient: [f32; 3],
    pub light_count: u32,
    pub model: u32,
    pub gate: u32,
    pub normalization: u32,
    pub _pad0: u32,
}

// No padding: each size is the sum of its fields, so every byte is a field byte.
const _: () = assert!(core::mem::size_of::<GpuMaterial>() == 64);
const _: () = assert!(core::mem::size_of::<GpuLight>() == 96);
const _: () = assert!(core::mem::size_of::<GpuParams>() == 48);

impl From<&Material> for GpuMaterial {
    fn from(m: &Material) -> Self {
        GpuMaterial {
            ambient: m.ambient().to_array(),
            shininess: m.shininess(),
            diffuse: m.diffuse().to_array(),
            specular: m.specular().to_array(),
            emission: m.emission().to_array(),
            ..Default::default()
        }
    }
}

fn attenuation_code(a: Attenuation) -> (u32, [f32; 4]) {
    match a {
        Attenuation::None => (0, [0.0; 4]),
        Attenuation::Polynomial {
            constant,
            linear,
            quadratic,
        } => (1, [constant, linear, quadratic, 0.0]),
        Attenuation::InverseSquare {
            power,
            min_distance,
        } => (2, [power, min_distance, 0.0, 0.0]),
        Attenuation::Unreal { radius } => (3, [radius, 0.0, 0.0, 0.0]),
        Attenuation::Frostbite {
            radius,
            min_distance,
        } => (4, [radius, min_distance, 0.0, 0.0]),
    }
}

impl From<&Light> for GpuLight {
    fn from(light: &Light) -> Self {
        let c = light.colors();
        let mut g = GpuLight {
            ambient: c.ambient().to_array(),
            diffuse: c.diffuse().to_array(),
            specular: c.specular().to_array(),
            ..Default::default()
        };
        let att = match light {
            Light::Directional(d) => {
                g.kind = 0;
                g.direction = d.direction().to_array();
                Attenuation::None
            }
            Light::Point(p) => {
                g.kind = 1;
                g.position = p.position().to_array();
                p.attenuation()
            }
            // OpenGL's 180° cutoff is no cone: the shaders' point-light path is exactly that.
            Light::Spot(s) if s.cone().is_none() => {
                g.kind = 1;
                g.position = s.position().to_array();
                s.attenuation()
            }
            Light::Spot(s) => {
                g.kind = 2;
                g.position = s.position().to_array();
                g.direction = s.axis().to_array();
                g.cos_cutoff = s.cos_cutoff();
                g.spot_exponent = s.exponent();
                s.attenuation()
            }
        };
        (g.attenuation_kind, g.attenuation) = attenuation_code(att);
        g
    }
}

fn gate_code(g: SpecularGate) -> u32 {
    match g {
        SpecularGate::Step => 0,
        SpecularGate::Cosine => 1,
        SpecularGate::None => 2,
    }
}

fn normalization_code(n: Normalization) -> u32 {
    match n {
        Normalization::None => 0,
        Normalization::Energy => 1,
        Normalization::EnergyExact => 2,
    }
}

impl GpuParams {
    /// The shading state for `model`, a viewer, the scene ambient `Ia` and a light count.
    ///
    /// The model's [`PowStrategy`](crate::PowStrategy) does not travel: shaders use `pow`. A Lambert
    /// model is sent with the step gate and its normalisation.
    ///
    /// ```
    /// use glam::Vec3;
    /// use phong::{gpu::GpuParams, Phong, Viewer};
    /// let p = GpuParams::new(&Phong::learnopengl(), Viewer::At(Vec3::Z), Vec3::ZERO, 1);
    /// assert_eq!((p.model, p.gate, p.light_count), (1, 2, 1));
    /// let bytes: &[u8] = bytemuck::bytes_of(&p);
    /// assert_eq!(bytes.len(), 48);
    /// ```
    #[must_use]
    pub fn new<M: BatchModel>(
        model: &M,
        viewer: Viewer,
        scene_ambient: Vec3,
        light_count: u32,
    ) -> Self {
        let (model_code, gate, normalization) = match (*model).into() {
            Model::Lambert(Lambert { normalization }) => (0, SpecularGate::Step, normalization),
            Model::Phong(Phong {
                gate,
                normalization,
                ..
            }) => (1, gate, normalization),
            Model::BlinnPhong(BlinnPhong {
                gate,
                normalization,
                ..
            }) => (2, gate, normalization),
        };
        let (viewer, viewer_kind) = match viewer {
            Viewer::At(p) => (p, 0),
            Viewer::Infinite(d) => (d, 1),
        };
        GpuParams {
            viewer: viewer.to_array(),
            viewer_kind,
            ambient: scene_ambient.to_array(),
            light_count,
            model: model_code,
            gate: gate_code(gate),
            normalization: normalization_code(normalization),
            _pad0: 0,
        }
    }
}
