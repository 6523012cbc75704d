//! A small Whitted-style ray tracer whose lighting is `phong`.
//!
//! ```text
//! cargo run --release --example raytracer [-- --size 640x400 --out out/raytracer.png]
//! ```
//!
//! The recursive ray tracer of T. Whitted, "An Improved Illumination Model for Shaded Display"
//! (Communications of the ACM 23(6), 1980), cut down to what a first ray tracer has: spheres on a
//! checkered plane, three point lights, a shadow ray from every hit to every light, and one mirror
//! bounce. The colour of a hit is Whitted's sum of a local term and a reflected one,
//!
//! ```text
//! I = local + kr · I(reflected ray),   local = phong's ambient + Σᵢ visᵢ · (diffuseᵢ + specularᵢ)
//! ```
//!
//! with `visᵢ` 1 where the shadow ray reaches light `i` and 0 where something blocks it.
//!
//! The lighting is the part to copy, in `Tracer::shade`: a `phong::Shader` is prepared once per
//! material and scene; at each hit it gets the viewer back along the ray that hit
//! (`with_viewer(Viewer::along_ray(dir))`: for a reflected ray that is the mirror, not the camera)
//! and the shadow rays' answers (`shade_visible` with one visibility per light). The lights use
//! LearnOpenGL's point-light attenuation `1/(1 + 0.09 d + 0.032 d²)` ("Light casters"); the
//! `raytrace` group of `benches/renderers.rs` times the same shading call against LearnOpenGL's
//! code written by hand.

use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};
use std::time::Instant;

use glam::Vec3;
use phong::{
    Attenuation, LightColors, Material, Phong, PointLight, Scene, Shader, Viewer, linear_to_srgb8,
};

const USAGE: &str = "usage: raytracer [--size WIDTHxHEIGHT] [--out PATH]";

/// Samples per pixel along each axis: 2×2, so edges and the checkerboard are not jagged.
const AA: usize = 2;
/// The number of point lights, and so of shadow rays per hit.
const LIGHTS: usize = 3;
/// How far a secondary ray starts off the surface, so it does not hit the surface it leaves.
const EPSILON: f32 = 1e-3;

// ---------------------------------------------------------------------------------------------
// Geometry: rays, spheres and a plane
// ---------------------------------------------------------------------------------------------

#[derive(Clone, Copy)]
struct Ray {
    origin: Vec3,
    /// Unit direction of travel.
    dir: Vec3,
}

impl Ray {
    fn at(&self, t: f32) -> Vec3 {
        self.origin + t * self.dir
    }
}

#[derive(Clone, Copy)]
enum Shape {
    Sphere {
        center: Vec3,
        radius: f32,
    },
    /// The horizontal plane `y = height`, seen from above.
    Floor {
        height: f32,
    },
}

/// What a ray hits: a shape and how its surface looks.
struct Object {
    shape: Shape,
    finish: Finish,
}

#[derive(Clone, Copy)]
enum Finish {
    /// One material everywhere: an index into [`Tracer::looks`].
    Plain(usize),
    /// A checkerboard of two materials, one unit per square.
    Checker(usize, usize),
}

/// A ray's nearest intersection.
struct Hit {
    position: Vec3,
    /// Unit, outward.
    normal: Vec3,
    look: usize,
}

impl Shape {
    /// The distance along `ray` to the nearest intersection in `(EPSILON, t_max)`.
    fn intersect(&self, ray: &Ray, t_max: f32) -> Option<f32> {
        let t = match *self {
            Shape::Sphere { center, radius } => {
                // |o + t d − c|² = r², with |d| = 1: t² + 2 b t + c = 0.
                let oc = ray.origin - center;
                let b = oc.dot(ray.dir);
                let c = oc.length_squared() - radius * radius;
                let disc = b * b - c;
                if disc < 0.0 {
                    return None;
                }
                let root = disc.sqrt();
                let near = -b - root;
                if near > EPSILON { near } else { -b + root }
            }
            Shape::Floor { height } => (height - ray.origin.y) / ray.dir.y,
        };
        (t > EPSILON && t < t_max).then_some(t)
    }

    fn normal_at(&self, p: Vec3) -> Vec3 {
        match *self {
            Shape::Sphere { center, radius } => (p - center) / radius,
            Shape::Floor { .. } => Vec3::Y,
        }
    }
}

// ---------------------------------------------------------------------------------------------
// The scene
// ---------------------------------------------------------------------------------------------

/// A material as the tracer uses it: `phong`'s lighting, prepared, and Whitted's `kr`.
struct Look<'a> {
    shader: Shader<'a, Phong, PointLight>,
    /// The fraction of the reflected ray's colour added to the local lighting (0: not a mirror).
    reflectivity: f32,
}

struct Tracer<'a> {
    objects: Vec<Object>,
    lights: &'a [PointLight; LIGHTS],
    looks: Vec<Look<'a>>,
}

/// Three point lights: a warm key light at the front right, a cool fill at the left, a warm back
/// light behind the spheres (the positions of `benches/renderers.rs`'s ray-tracer lights), with
/// LearnOpenGL's attenuation for a range of about 50 units.
fn lights() -> Result<[PointLight; LIGHTS], phong::PhongError> {
    let attenuation = Attenuation::try_polynomial(1.0, 0.09, 0.032)?;
    let light = |position, color, specular| {
        PointLight::try_new(
            position,
            attenuation,
            LightColors::try_from_strengths(color, 0.05, 1.0, specular)?,
        )
    };
    Ok([
        light(Vec3::new(4.0, 5.0, 3.0), Vec3::new(2.6, 2.45, 2.3), 1.0)?,
        light(Vec3::new(-5.0, 3.0, 1.0), Vec3::new(0.6, 0.8, 1.6), 0.6)?,
        light(Vec3::new(0.0, 6.0, -4.0), Vec3::new(1.8, 1.1, 0.6), 0.8)?,
    ])
}

impl<'a> Tracer<'a> {
    fn new(lights: &'a [PointLight; LIGHTS]) -> Result<Self, phong::PhongError> {
        // The viewer here is a placeholder: every hit sets its own (`with_viewer` in `shade`).
        let scene = Scene {
            lights,
            ambient: Vec3::splat(0.03),
            viewer: Viewer::along_ray(Vec3::NEG_Z),
        };
        // Prepared once per material and scene: the model's lobe, the pow plan for the
        // shininess, the sanitised colours.
        let look = |material: Material, reflectivity| Look {
            shader: Shader::new(Phong::default(), &material, &scene),
            reflectivity,
        };
        let looks = vec![
            // 0, 1: the floor's light and dark squares, slightly glossy.
            look(
                Material::try_from_color(Vec3::new(0.8, 0.78, 0.72), 16.0)?,
                0.0,
            ),
            look(
                Material::try_from_color(Vec3::new(0.12, 0.13, 0.15), 16.0)?,
                0.0,
            ),
            // 2: red plastic.
            look(
                Material::try_new(
                    Vec3::new(0.7, 0.08, 0.06),
                    Vec3::new(0.7, 0.08, 0.06),
                    Vec3::splat(0.6),
                    48.0,
                )?,
                0.0,
            ),
            // 3: a mirror: little of its own colour, a sharp highlight, 85% reflected.
            look(
                Material::try_new(
                    Vec3::splat(0.03),
                    Vec3::splat(0.03),
                    Vec3::splat(0.8),
                    256.0,
                )?,
                0.85,
            ),
            // 4: blue plastic.
            look(
                Material::try_new(
                    Vec3::new(0.06, 0.2, 0.7),
                    Vec3::new(0.06, 0.2, 0.7),
                    Vec3::splat(0.5),
                    96.0,
                )?,
                0.0,
            ),
            // 5: matte green.
            look(
                Material::try_from_color(Vec3::new(0.15, 0.55, 0.15), 4.0)?,
                0.0,
            ),
        ];
        let sphere = |x, y, z, radius, look| Object {
            shape: Shape::Sphere {
                center: Vec3::new(x, y, z),
                radius,
            },
            finish: Finish::Plain(look),
        };
        let objects = vec![
            Object {
                shape: Shape::Floor { height: 0.0 },
                finish: Finish::Checker(0, 1),
            },
            sphere(-1.7, 0.8, 0.3, 0.8, 2),
            sphere(0.25, 1.1, -0.9, 1.1, 3),
            sphere(1.9, 0.6, 0.8, 0.6, 4),
            sphere(-0.1, 0.35, 1.6, 0.35, 5),
        ];
        Ok(Tracer {
            objects,
            lights,
            looks,
        })
    }

    /// The nearest hit along `ray` closer than `t_max`.
    fn intersect(&self, ray: &Ray, t_max: f32) -> Option<Hit> {
        let mut nearest: Option<(f32, &Object)> = None;
        for object in &self.objects {
            let limit = nearest.map_or(t_max, |(t, _)| t);
            if let Some(t) = object.shape.intersect(ray, limit) {
                nearest = Some((t, object));
            }
        }
        let (t, object) = nearest?;
        let position = ray.at(t);
        let look = match object.finish {
            Finish::Plain(look) => look,
            Finish::Checker(a, b) => {
                let square = position.x.floor() as i32 + position.z.floor() as i32;
                if square.rem_euclid(2) == 0 { a } else { b }
            }
        };
        Some(Hit {
            position,
            normal: object.shape.normal_at(position),
            look,
        })
    }

    /// The colour seen along `ray`; `bounces` is how many more mirror reflections may follow.
    fn trace(&self, ray: &Ray, bounces: u32) -> Vec3 {
        let Some(hit) = self.intersect(ray, f32::INFINITY) else {
            return sky(ray.dir);
        };
        let look = &self.looks[hit.look];
        let mut color = self.shade(look, ray, &hit);
        if look.reflectivity > 0.0 && bounces > 0 {
            // phong::reflect mirrors a direction pointing away from the surface: the reversed ray.
            let mirrored = Ray {
                origin: hit.position + EPSILON * hit.normal,
                dir: phong::reflect(hit.normal, -ray.dir),
            };
            color += look.reflectivity * self.trace(&mirrored, bounces - 1);
        }
        color
    }

    /// Whitted's local term at a hit: `phong`'s lighting with a shadow ray per light.
    fn shade(&self, look: &Look, ray: &Ray, hit: &Hit) -> Vec3 {
        // Shadow rays: light i counts (visibility 1) only if nothing lies between it and the hit.
        let origin = hit.position + EPSILON * hit.normal;
        let mut visibility = [1.0; LIGHTS];
        for (vis, light) in visibility.iter_mut().zip(self.lights) {
            let to_light = light.position() - origin;
            let distance = to_light.length();
            let shadow_ray = Ray {
                origin,
                dir: to_light / distance,
            };
            if self.intersect(&shadow_ray, distance).is_some() {
                *vis = 0.0;
            }
        }
        // The viewer is where the ray came from: the camera, or the mirror for a reflected ray.
        look.shader
            .with_viewer(Viewer::along_ray(ray.dir))
            .shade_visible(hit.position, hit.normal, visibility)
            .total()
    }
}

/// The background: a linear-light gradient from a pale horizon to a deeper blue overhead.
fn sky(dir: Vec3) -> Vec3 {
    let up = dir.y.clamp(0.0, 1.0);
    Vec3::new(0.55, 0.65, 0.8).lerp(Vec3::new(0.12, 0.25, 0.6), up.sqrt())
}

// ---------------------------------------------------------------------------------------------
// Camera, image, command line
// ---------------------------------------------------------------------------------------------

/// A pinhole camera at `eye` looking at `target`, `fov_y` degrees from the top of the picture to
/// the bottom.
struct Camera {
    eye: Vec3,
    forward: Vec3,
    right: Vec3,
    up: Vec3,
}

impl Camera {
    fn new(eye: Vec3, target: Vec3, fov_y: f32, aspect: f32) -> Self {
        let forward = (target - eye).normalize();
        let half_height = (fov_y.to_radians() / 2.0).tan();
        let right = forward.cross(Vec3::Y).normalize() * half_height * aspect;
        let up = right.cross(forward).normalize() * half_height;
        Camera {
            eye,
            forward,
            right,
            up,
        }
    }

    /// The ray through the picture at `(u, v)`, each from −1 (left, bottom) to 1 (right, top).
    fn ray(&self, u: f32, v: f32) -> Ray {
        Ray {
            origin: self.eye,
            dir: (self.forward + u * self.right + v * self.up).normalize(),
        }
    }
}

fn render(tracer: &Tracer, width: usize, height: usize) -> Vec<u8> {
    let camera = Camera::new(
        Vec3::new(0.0, 2.2, 7.0),
        Vec3::new(0.0, 0.7, 0.0),
        36.0,
        width as f32 / height as f32,
    );
    let mut pixels = Vec::with_capacity(width * height * 3);
    for y in 0..height {
        for x in 0..width {
            // Average AA×AA rays in linear light, then encode to sRGB once.
            let mut sum = Vec3::ZERO;
            for sy in 0..AA {
                for sx in 0..AA {
                    let px = x as f32 + (sx as f32 + 0.5) / AA as f32;
                    let py = y as f32 + (sy as f32 + 0.5) / AA as f32;
                    let u = 2.0 * px / width as f32 - 1.0;
                    let v = 1.0 - 2.0 * py / height as f32;
                    sum += tracer.trace(&camera.ray(u, v), 1);
                }
            }
            pixels.extend(linear_to_srgb8(sum / (AA * AA) as f32));
        }
    }
    pixels
}

fn write_png(path: &Path, width: usize, height: usize, rgb: &[u8]) -> std::io::Result<()> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)?;
    }
    let mut encoder = png::Encoder::new(
        BufWriter::new(File::create(path)?),
        width as u32,
        height as u32,
    );
    encoder.set_color(png::ColorType::Rgb);
    encoder.set_depth(png::BitDepth::Eight);
    encoder.set_source_srgb(png::SrgbRenderingIntent::Perceptual);
    let mut writer = encoder.write_header().map_err(std::io::Error::other)?;
    writer.write_image_data(rgb).map_err(std::io::Error::other)
}

struct Options {
    width: usize,
    height: usize,
    out: PathBuf,
}

fn parse_args() -> Result<Options, String> {
    let mut o = Options {
        width: 640,
        height: 400,
        out: PathBuf::from("out/raytracer.png"),
    };
    // `--flag value` and `--flag=value` both work.
    let mut args = std::env::args()
        .skip(1)
        .flat_map(|a| match a.split_once('=') {
            Some((f, v)) if f.starts_with("--") => vec![f.to_string(), v.to_string()],
            _ => vec![a],
        });
    while let Some(flag) = args.next() {
        if flag == "--help" || flag == "-h" {
            println!("{USAGE}");
            std::process::exit(0);
        }
        let value = args
            .next()
            .ok_or_else(|| format!("{flag} needs a value\n{USAGE}"))?;
        match flag.as_str() {
            "--size" => {
                let size = value.split_once('x').and_then(|(w, h)| {
                    let (w, h) = (w.parse().ok()?, h.parse().ok()?);
                    ((1..=8192).contains(&w) && (1..=8192).contains(&h)).then_some((w, h))
                });
                (o.width, o.height) = size.ok_or_else(|| {
                    format!("bad size {value:?}: WIDTHxHEIGHT, each 1 to 8192, e.g. 640x400")
                })?;
            }
            "--out" => o.out = PathBuf::from(value),
            _ => return Err(format!("unknown flag {flag}\n{USAGE}")),
        }
    }
    Ok(o)
}

fn main() {
    let opts = parse_args().unwrap_or_else(|e| {
        eprintln!("{e}");
        std::process::exit(2);
    });
    let lights = lights().expect("the scene's lights are valid");
    let tracer = Tracer::new(&lights).expect("the scene's materials are valid");
    let start = Instant::now();
    let pixels = render(&tracer, opts.width, opts.height);
    if let Err(e) = write_png(&opts.out, opts.width, opts.height, &pixels) {
        eprintln!("raytracer: cannot write {}: {e}", opts.out.display());
        std::process::exit(1);
    }
    let elapsed = start.elapsed();
    println!(
        "wrote {} ({}x{}, {} rays per pixel) in {:.2} s",
        opts.out.display(),
        opts.width,
        opts.height,
        AA * AA,
        elapsed.as_secs_f64()
    );
}
