//! The explorer's scene, rendered on the CPU with the `raster` crate and `phong`'s lighting.
//!
//! Everything here is a plain function of [`Params`], so it can be tested without a window.

use std::time::{Duration, Instant};

use glam::{EulerRot, Mat4, Vec3};
use phong::{
    Attenuation, BlinnPhong, Lambert, Light, LightColors, Material, Model, Phong, PointLight,
    Scene, SpecularGate, Viewer,
};
use raster::{Camera, DrawStats, Framebuffer, Image, Mesh, PhongShader, ShadingMode};

/// The object colour of LearnOpenGL's lit cube ("Basic Lighting": coral), linear RGB.
pub const OBJECT_COLOR: Vec3 = Vec3::new(1.0, 0.5, 0.31);
/// Where the eye is; it looks at the origin.
pub const EYE: Vec3 = Vec3::new(0.0, 0.0, 3.6);
/// The background, linear RGB.
pub const BACKGROUND: Vec3 = Vec3::new(0.02, 0.02, 0.025);

/// Which reflection model shades the object.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ModelKind {
    /// Diffuse only.
    Lambert,
    /// Phong's lobe around the mirror direction.
    Phong,
    /// Blinn's lobe around the halfway vector.
    BlinnPhong,
}

/// How the rendered linear colours become 8-bit pixels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Encoding {
    /// Linear values written straight to 8 bits (too dark on a display; shown for comparison).
    Linear,
    /// The sRGB transfer function, then 8 bits.
    Srgb,
}

/// What is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shape {
    /// An icosphere of radius 1 (low-poly at small subdivision counts).
    Sphere,
    /// LearnOpenGL's lit cube: flat faces of two triangles each.
    Cube,
}

/// Everything the sliders and radio buttons control.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Params {
    /// Specular exponent `s`.
    pub shininess: f32,
    /// The light's ambient strength (`La = strength · white`).
    pub ambient: f32,
    /// The light's diffuse strength.
    pub diffuse: f32,
    /// The light's specular strength.
    pub specular: f32,
    /// The point light's position (world space; the eye is at [`EYE`]).
    pub light: Vec3,
    /// The object's rotation in degrees about x, then y, then z.
    pub rotation: Vec3,
    /// The reflection model.
    pub model: ModelKind,
    /// The specular gate (ignored by Lambert).
    pub gate: SpecularGate,
    /// Shading frequency: per vertex, per pixel, or chosen per triangle by the advisor.
    pub frequency: ShadingMode,
    /// The advisor's tolerance in 8-bit steps (`tolerance / 255` in linear units).
    pub tolerance_steps: f32,
    /// Output encoding.
    pub encoding: Encoding,
    /// The object.
    pub shape: Shape,
    /// Icosphere subdivisions (`20·4ᵏ` triangles).
    pub subdivisions: u32,
    /// Render size in pixels (width, height).
    pub size: [usize; 2],
}

impl Default for Params {
    fn default() -> Self {
        Params {
            shininess: 32.0,
            ambient: 0.1,
            diffuse: 1.0,
            specular: 0.5,
            light: Vec3::new(1.2, 1.0, 2.0),
            rotation: Vec3::new(25.0, 30.0, 0.0),
            model: ModelKind::Phong,
            gate: SpecularGate::Step,
            frequency: ShadingMode::Adaptive,
            tolerance_steps: 2.0,
            encoding: Encoding::Srgb,
            shape: Shape::Sphere,
            subdivisions: 2,
            size: [400, 400],
        }
    }
}

impl Params {
    /// The `phong` model these parameters select.
    #[must_use]
    pub fn phong_model(&self) -> Model {
        match self.model {
            ModelKind::Lambert => Lambert::default().into(),
            ModelKind::Phong => Phong {
                gate: self.gate,
                ..Phong::default()
            }
            .into(),
            ModelKind::BlinnPhong => BlinnPhong {
                gate: self.gate,
                ..BlinnPhong::default()
            }
            .into(),
        }
    }

    /// The object-to-world transform: the rotation, and the cube scaled to about the sphere's
    /// size on screen.
    #[must_use]
    pub fn model_matrix(&self) -> Mat4 {
        let r = self.rotation * (std::f32::consts::PI / 180.0);
        let rotation = Mat4::from_euler(EulerRot::XYZ, r.x, r.y, r.z);
        match self.shape {
            Shape::Sphere => rotation,
            Shape::Cube => rotation * Mat4::from_scale(Vec3::splat(1.3)),
        }
    }

    /// The mesh these parameters draw.
    #[must_use]
    pub fn mesh(&self) -> Mesh {
        match self.shape {
            Shape::Sphere => Mesh::icosphere(self.subdivisions.min(MAX_SUBDIVISIONS)),
            Shape::Cube => Mesh::cube(),
        }
    }
}

/// The largest icosphere subdivision count offered (5120 triangles).
pub const MAX_SUBDIVISIONS: u32 = 4;

/// One rendered frame.
#[derive(Clone, Debug)]
pub struct Frame {
    /// The encoded image.
    pub image: Image,
    /// What the rasterizer did: visible triangles, how many were shaded per vertex, pixels.
    pub stats: DrawStats,
    /// Wall-clock time of the render (rasterizing, shading and encoding).
    pub elapsed: Duration,
    /// With [`render_compared`]: the largest per-channel difference from per-pixel shading, in
    /// 8-bit steps of the linear colour.
    pub max_error_steps: Option<f32>,
}

/// Renders the scene of `params`.
///
/// # Panics
/// Never for the parameter ranges the UI offers; checked constructors reject negative strengths or
/// a non-finite light position with a panic naming the field.
#[must_use]
pub fn render(params: &Params) -> Frame {
    let start = Instant::now();
    let (fb, stats) = draw(params, params.frequency);
    let image = encode(&fb, params.encoding);
    Frame {
        image,
        stats,
        elapsed: start.elapsed(),
        max_error_steps: None,
    }
}

/// Renders the scene and also a per-pixel reference, and reports the largest difference (in the
/// linear colour, before encoding). `elapsed` covers the first render only.
#[must_use]
pub fn render_compared(params: &Params) -> Frame {
    let start = Instant::now();
    let (fb, stats) = draw(params, params.frequency);
    let image = encode(&fb, params.encoding);
    let elapsed = start.elapsed();
    let (reference, _) = draw(params, ShadingMode::PerPixel);
    Frame {
        image,
        stats,
        elapsed,
        max_error_steps: Some(fb.max_difference(&reference) * 255.0),
    }
}

fn encode(fb: &Framebuffer, encoding: Encoding) -> Image {
    match encoding {
        Encoding::Linear => Image::from_raw(fb),
        Encoding::Srgb => Image::from_linear(fb),
    }
}

/// The linear framebuffer of `params` shaded at `mode`.
fn draw(params: &Params, mode: ShadingMode) -> (Framebuffer, DrawStats) {
    let [width, height] = params.size;
    let colors = LightColors::try_from_strengths(
        Vec3::ONE,
        params.ambient.max(0.0),
        params.diffuse.max(0.0),
        params.specular.max(0.0),
    )
    .expect("light strengths");
    let lamp = PointLight::try_new(params.light, Attenuation::None, colors).expect("light");
    let lights = [Light::Point(lamp)];
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(EYE),
    };
    let material =
        Material::try_from_color(OBJECT_COLOR, params.shininess.max(0.0)).expect("material");
    let mut shader = PhongShader::new(params.phong_model(), material, scene);
    shader.tolerance = params.tolerance_steps.max(0.0) / 255.0;
    let camera = Camera::look_at(EYE, Vec3::ZERO);
    let mut fb = Framebuffer::new(width.max(1), height.max(1), BACKGROUND);
    let stats = raster::draw(
        &mut fb,
        &camera,
        &params.mesh(),
        params.model_matrix(),
        &shader,
        mode,
    );
    (fb, stats)
}
