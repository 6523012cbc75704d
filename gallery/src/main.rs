//! The gallery: the pictures LearnOpenGL's lighting chapters (Basic Lighting, Lighting Maps, Light
//! Casters, Advanced Lighting, Gamma Correction) use to explain the Phong family, and a few more,
//! drawn by this crate.
//!
//! ```text
//! cargo run --release -p gallery [-- --model phong|blinn --shininess 32 --light x,y,z
//!                                           --size 256 --out out/gallery]
//! ```
//!
//! Writes one PNG per picture (each with a caption), a contact sheet (`contact_sheet.png`) and an
//! `index.html` into the output folder, and prints the adaptive shading-rate and light-culling
//! figures.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::time::Instant;

use glam::{Mat4, Quat, Vec2, Vec3};
use phong::{
    Attenuation, BlinnPhong, DirectionalLight, Light, LightColors, Material, Model, Phong,
    PointLight, Scene, SpecularGate, SpotLight, Viewer,
};
use raster::{
    Camera, DrawStats, Framebuffer, Image, Mesh, PhongShader, ShadingMode, SurfaceShader, Term,
    draw,
};

/// The command line: the model, shininess and light a lighting demo would put on sliders.
#[derive(Clone)]
struct Options {
    model: Model,
    model_name: &'static str,
    shininess: f32,
    light: Vec3,
    size: usize,
    out: PathBuf,
}

/// The default sun: from the side, so the sphere scenes show the terminator and the
/// adaptive shading-rate figures have a highlight and a shadow to deal with.
const DEFAULT_LIGHT: Vec3 = Vec3::new(-3.0, 2.0, 0.0);

const USAGE: &str = "usage: gallery [--model phong|blinn] [--shininess S] [--light X,Y,Z] \
                     [--size PIXELS] [--out DIR]";

fn parse_args() -> Result<Options, String> {
    let mut o = Options {
        model: Phong::default().into(),
        model_name: "Phong",
        shininess: 32.0,
        light: DEFAULT_LIGHT,
        size: 256,
        out: PathBuf::from("out/gallery"),
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
            "--model" => match value.to_ascii_lowercase().as_str() {
                "phong" => (o.model, o.model_name) = (Phong::default().into(), "Phong"),
                "blinn" | "blinn-phong" => {
                    (o.model, o.model_name) = (BlinnPhong::default().into(), "Blinn-Phong")
                }
                _ => return Err(format!("unknown model {value:?}: phong or blinn")),
            },
            "--shininess" => {
                o.shininess = value
                    .parse()
                    .ok()
                    .filter(|s: &f32| s.is_finite() && *s >= 0.0)
                    .ok_or_else(|| format!("bad shininess {value:?}"))?
            }
            "--light" => {
                let v: Vec<f32> = value
                    .split(',')
                    .map(|x| x.trim().parse::<f32>())
                    .collect::<Result<_, _>>()
                    .map_err(|_| format!("bad light position {value:?}: x,y,z"))?;
                match v[..] {
                    [x, y, z] if Vec3::new(x, y, z).length() > 1e-3 => o.light = Vec3::new(x, y, z),
                    _ => return Err(format!("bad light position {value:?}: x,y,z, not 0")),
                }
            }
            "--size" => {
                o.size = value
                    .parse()
                    .ok()
                    .filter(|s| (16..=4096).contains(s))
                    .ok_or_else(|| format!("bad size {value:?}: 16 to 4096"))?
            }
            "--out" => o.out = PathBuf::from(value),
            _ => return Err(format!("unknown flag {flag}\n{USAGE}")),
        }
    }
    Ok(o)
}

/// Writes captioned pictures and remembers them for the contact sheet and index.html.
struct Gallery {
    dir: PathBuf,
    rows: Vec<(String, Vec<Image>)>,
    html: String,
    count: usize,
}

impl Gallery {
    fn row(&mut self, title: &str) {
        self.rows.push((title.to_string(), Vec::new()));
        let _ = write!(self.html, "<h2>{title}</h2>\n<div class=row>\n");
    }

    fn add(&mut self, name: &str, caption: &str, image: &Image) {
        self.count += 1;
        let file = format!("{:02}_{name}.png", self.count);
        let labelled = image.labelled(caption);
        if let Err(e) = labelled.save_png(&self.dir.join(&file)) {
            eprintln!("gallery: cannot write {file}: {e}");
            std::process::exit(1);
        }
        let _ = writeln!(
            self.html,
            "<figure><img src=\"{file}\"><figcaption>{caption}</figcaption></figure>"
        );
        self.rows
            .last_mut()
            .expect("a row was started")
            .1
            .push(labelled);
    }

    fn end_row(&mut self) {
        self.html.push_str("</div>\n");
    }
}

fn colours(ambient: f32, diffuse: f32, specular: f32) -> LightColors {
    LightColors::try_from_strengths(Vec3::ONE, ambient, diffuse, specular).expect("valid strengths")
}

fn material(colour: Vec3, s: f32) -> Material {
    Material::try_from_color(colour, s).expect("valid material")
}

fn render(
    size: (usize, usize),
    camera: &Camera,
    parts: &[(&Mesh, Mat4)],
    shader: &impl SurfaceShader,
    mode: ShadingMode,
) -> (Framebuffer, DrawStats) {
    let mut fb = Framebuffer::new(size.0, size.1, Vec3::splat(0.02));
    let mut stats = DrawStats::default();
    for (mesh, model) in parts {
        stats += draw(&mut fb, camera, mesh, *model, shader, mode);
    }
    (fb, stats)
}

fn with_model(model: Model, gate: SpecularGate) -> Model {
    match model {
        Model::Phong(p) => Phong { gate, ..p }.into(),
        Model::BlinnPhong(b) => BlinnPhong { gate, ..b }.into(),
        m => m,
    }
}

/// One group of pictures.
type Step = fn(&Options, &mut Gallery);

const CORAL: Vec3 = Vec3::new(1.0, 0.5, 0.31);

fn main() {
    let opts = match parse_args() {
        Ok(o) => o,
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(2);
        }
    };
    if let Err(e) = std::fs::create_dir_all(&opts.out) {
        eprintln!("gallery: cannot create {}: {e}", opts.out.display());
        std::process::exit(1);
    }
    println!(
        "gallery: {} at shininess {}, light at {}, {}×{} px per picture, into {}",
        opts.model_name,
        opts.shininess,
        opts.light,
        opts.size,
        opts.size,
        opts.out.display()
    );
    let start = Instant::now();
    let mut g = Gallery {
        dir: opts.out.clone(),
        rows: Vec::new(),
        html: String::new(),
        count: 0,
    };
    let steps: [(&str, Step); 12] = [
        ("the terms apart", terms),
        ("Phong vs Blinn-Phong", phong_vs_blinn),
        ("shininess sweep", sweep),
        ("Gouraud vs Phong shading, adaptive", gouraud_vs_phong),
        ("attenuation and cull radius", attenuation),
        ("light culling", culling),
        ("linear vs sRGB", linear_vs_srgb),
        ("spot light", spot),
        ("specular gate", gate),
        ("lit cube", cube),
        ("diffuse and specular maps", textured),
        ("grazing angle", grazing),
    ];
    for (i, (name, step)) in steps.iter().enumerate() {
        let t = Instant::now();
        step(&opts, &mut g);
        println!(
            "[{:2}/{}] {name}: {:.0} ms",
            i + 1,
            steps.len(),
            t.elapsed().as_secs_f64() * 1e3
        );
    }
    write_sheet(&g, &opts.out);
    println!(
        "done: {} pictures, contact_sheet.png and index.html in {} ({:.2} s)",
        g.count,
        opts.out.display(),
        start.elapsed().as_secs_f64()
    );
}

fn write_sheet(g: &Gallery, dir: &Path) {
    let rows: Vec<Image> = g
        .rows
        .iter()
        .map(|(title, images)| Image::row(images, 6).labelled(title))
        .collect();
    let sheet = Image::column(&rows, 10);
    let html = format!(
        "<!doctype html><meta charset=utf-8><title>phong gallery</title>\n<style>body{{background:#111;color:#ddd;font-family:sans-serif}} .row{{display:flex;flex-wrap:wrap;gap:8px}} figure{{margin:0}} img{{image-rendering:pixelated}}</style>\n<h1>phong gallery</h1>\n<p><a href=contact_sheet.png>contact sheet</a></p>\n{}",
        g.html
    );
    let ok = sheet.save_png(&dir.join("contact_sheet.png")).is_ok()
        && std::fs::write(dir.join("index.html"), html).is_ok();
    if !ok {
        eprintln!("gallery: cannot write the contact sheet");
        std::process::exit(1);
    }
}

/// The sphere scenes' camera and sun (a directional light toward `--light`).
fn sphere_setup(opts: &Options) -> (Camera, Light, Viewer) {
    let camera = Camera::look_at(Vec3::new(0.0, 0.0, 4.2), Vec3::ZERO);
    let sun = DirectionalLight::try_new(opts.light, colours(0.1, 0.8, 0.5))
        .expect("non-zero light")
        .into();
    (camera, sun, Viewer::At(camera.eye))
}

fn terms(opts: &Options, g: &mut Gallery) {
    let (camera, sun, viewer) = sphere_setup(opts);
    let sphere = Mesh::icosphere(4);
    let lights = [sun];
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer,
    };
    let size = (opts.size, opts.size);
    g.row("The three terms apart and summed (smooth sphere, per pixel)");
    for (term, name) in [
        (Term::Ambient, "ambient"),
        (Term::Diffuse, "diffuse"),
        (Term::Specular, "specular"),
        (Term::Total, "sum"),
    ] {
        let shader =
            PhongShader::new(opts.model, material(CORAL, opts.shininess), scene).with_term(term);
        let (fb, _) = render(
            size,
            &camera,
            &[(&sphere, Mat4::IDENTITY)],
            &shader,
            ShadingMode::PerPixel,
        );
        g.add(
            &format!("terms_{name}"),
            &format!("{name} ({})", opts.model_name),
            &Image::from_linear(&fb),
        );
    }
    g.end_row();
}

/// LearnOpenGL's "Advanced Lighting" floor: a point light above a floor at y = −0.5, seen from
/// the front and above.
fn floor_scene() -> (Camera, Light) {
    let camera = Camera::look_at(Vec3::new(0.0, 1.2, 4.0), Vec3::new(0.0, -0.5, 0.0));
    let light = PointLight::try_new(
        Vec3::new(0.0, 0.5, 0.0),
        Attenuation::polynomial(1.0, 0.09, 0.032),
        colours(0.05, 0.5, 0.4),
    )
    .expect("valid light")
    .into();
    (camera, light)
}

fn phong_vs_blinn(opts: &Options, g: &mut Gallery) {
    let (camera, light) = floor_scene();
    let floor = Mesh::plane(10.0, 8);
    let place = Mat4::from_translation(Vec3::new(0.0, -0.5, 0.0));
    let lights = [light];
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(camera.eye),
    };
    let size = (opts.size, opts.size);
    let wood = Vec3::new(0.3, 0.2, 0.12);
    let shot = |model: Model, s: f32, term: Term| {
        let mut m = Material::try_new(wood, wood, Vec3::ONE, s).expect("valid material");
        m = m.try_with_shininess(s).expect("valid shininess");
        let shader = PhongShader::new(model, m, scene).with_term(term);
        let (fb, _) = render(
            size,
            &camera,
            &[(&floor, place)],
            &shader,
            ShadingMode::PerPixel,
        );
        Image::from_linear(&fb)
    };
    let phong: Model = Phong::default().into();
    let blinn: Model = BlinnPhong::default().into();
    g.row("Shininess 0.5: Phong's lobe is cut off where R.V = 0; Blinn-Phong's fades");
    g.add("s05_phong", "Phong s=0.5", &shot(phong, 0.5, Term::Total));
    g.add(
        "s05_blinn",
        "Blinn-Phong s=0.5",
        &shot(blinn, 0.5, Term::Total),
    );
    g.add(
        "s05_phong_spec",
        "Phong s=0.5 specular",
        &shot(phong, 0.5, Term::Specular),
    );
    g.add(
        "s05_blinn_spec",
        "Blinn s=0.5 specular",
        &shot(blinn, 0.5, Term::Specular),
    );
    g.end_row();
    let n = 8.0;
    g.row("The 4x rule: Blinn-Phong at 4n looks like Phong at n");
    g.add("rule_phong_n", "Phong s=8", &shot(phong, n, Term::Total));
    g.add(
        "rule_blinn_4n",
        "Blinn-Phong s=32",
        &shot(blinn, 4.0 * n, Term::Total),
    );
    g.add(
        "rule_blinn_n",
        "Blinn-Phong s=8",
        &shot(blinn, n, Term::Total),
    );
    g.end_row();
}

fn sweep(opts: &Options, g: &mut Gallery) {
    // The lobe's width is the point of this row, so the sun is turned toward the viewer (unless
    // --light was given): then the whole highlight sits on the visible face, not on the rim.
    let mut opts = opts.clone();
    if opts.light == DEFAULT_LIGHT {
        opts.light = Vec3::new(-1.0, 1.0, 1.5);
    }
    let (camera, sun, viewer) = sphere_setup(&opts);
    let sphere = Mesh::icosphere(3);
    let lights = [sun];
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer,
    };
    let small = (opts.size / 2).max(16);
    for (model, name) in [
        (Model::from(Phong::default()), "Phong"),
        (Model::from(BlinnPhong::default()), "Blinn-Phong"),
    ] {
        g.row(&format!("Shininess sweep, {name}"));
        for k in 1..=8 {
            let s = (1u32 << k) as f32;
            let shader = PhongShader::new(model, material(CORAL, s), scene);
            let (fb, _) = render(
                (small, small),
                &camera,
                &[(&sphere, Mat4::IDENTITY)],
                &shader,
                ShadingMode::PerPixel,
            );
            let tag = if name == "Phong" { "phong" } else { "blinn" };
            g.add(
                &format!("sweep_{tag}_{s}"),
                &format!("s={s}"),
                &Image::from_linear(&fb),
            );
        }
        g.end_row();
    }
}

/// The gallery's default low-poly sphere: an icosphere with 320 faces.
fn low_poly_sphere() -> Mesh {
    Mesh::icosphere(2)
}

fn gouraud_vs_phong(opts: &Options, g: &mut Gallery) {
    let (camera, sun, viewer) = sphere_setup(opts);
    let sphere = low_poly_sphere();
    let lights = [sun];
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer,
    };
    let mat = material(CORAL, opts.shininess);
    let shader = PhongShader::new(opts.model, mat, scene);
    let size = (opts.size, opts.size);
    let parts = [(&sphere, Mat4::IDENTITY)];
    // Each mode three times, keeping the fastest: the timings are for the report only.
    let timed = |mode: ShadingMode| {
        let mut best = f64::INFINITY;
        let mut out = None;
        for _ in 0..3 {
            let t = Instant::now();
            let r = render(size, &camera, &parts, &shader, mode);
            best = best.min(t.elapsed().as_secs_f64());
            out = Some(r);
        }
        let (fb, stats) = out.expect("rendered");
        (fb, stats, best)
    };
    let (pv, _, t_pv) = timed(ShadingMode::PerVertex);
    let (pp, _, t_pp) = timed(ShadingMode::PerPixel);
    let (ad, ad_stats, t_ad) = timed(ShadingMode::Adaptive);
    let tol = shader.tolerance;

    // Per triangle: the advisor's bound and the measured worst Gouraud error.
    let mut measured = vec![0.0f32; sphere.triangles.len()];
    for i in 0..pv.color.len() {
        let (a, b) = (pv.triangle[i], pp.triangle[i]);
        if a != 0 && a == b {
            let e = (pv.color[i] - pp.color[i]).abs().max_element();
            let m = &mut measured[a as usize - 1];
            *m = m.max(e);
        }
    }
    let mut chosen_bound = 0.0f32;
    let mut chosen_measured = 0.0f32;
    let mut ratios = Vec::new();
    for (t, tri) in sphere.triangles.iter().enumerate() {
        let p = tri.map(|i| sphere.positions[i as usize]);
        let n = tri.map(|i| sphere.normals[i as usize]);
        let facing = (p[1] - p[0]).cross(p[2] - p[0]).dot(camera.eye - p[0]) > 0.0;
        if !facing {
            continue;
        }
        let bound = phong::shading_rate::gouraud_error_bound(&shader.model, &mat, &scene, p, n);
        if bound <= tol {
            chosen_bound = chosen_bound.max(bound);
            chosen_measured = chosen_measured.max(measured[t]);
        }
        // Only visible errors: a ratio to a rounding-sized error says nothing.
        if measured[t] >= 0.5 / 255.0 {
            ratios.push(bound / measured[t]);
        }
    }
    ratios.sort_by(f32::total_cmp);
    let median = ratios.get(ratios.len() / 2).copied().unwrap_or(f32::NAN);
    let lowest = ratios.first().copied().unwrap_or(f32::NAN);
    let max_err = ad.max_difference(&pp);
    println!(
        "  adaptive (tolerance 2/255 = {tol:.5}): {}/{} front triangles per vertex ({:.0}%); \
         max error vs per pixel {max_err:.5} ({:.2}/255, within: {}); \
         per-pixel {:.2} ms, adaptive {:.2} ms, per-vertex {:.2} ms: saved {:.0}%",
        ad_stats.per_vertex,
        ad_stats.triangles,
        100.0 * ad_stats.per_vertex as f64 / ad_stats.triangles.max(1) as f64,
        max_err * 255.0,
        max_err <= tol,
        t_pp * 1e3,
        t_ad * 1e3,
        t_pv * 1e3,
        100.0 * (1.0 - t_ad / t_pp)
    );
    println!(
        "  bound vs measured: on the per-vertex triangles the largest bound is {chosen_bound:.5} \
         and the worst measured error {chosen_measured:.5} (ratio {:.1}); \
         per triangle, over the {} front triangles with an error of at least 0.5/255: \
         smallest ratio {lowest:.2}, median {median:.1}",
        chosen_bound / chosen_measured.max(f32::MIN_POSITIVE),
        ratios.len()
    );

    g.row("Gouraud vs Phong shading of the same 320-face sphere");
    g.add("gouraud", "per vertex (Gouraud)", &Image::from_linear(&pv));
    g.add(
        "phong_shading",
        "per pixel (Phong shading)",
        &Image::from_linear(&pp),
    );
    g.add(
        "gouraud_difference",
        "difference x8",
        &Image::from_linear(&pv.difference(&pp, 8.0)),
    );
    g.add(
        "adaptive",
        &format!("adaptive, max err {:.1}/255", max_err * 255.0),
        &Image::from_linear(&ad),
    );
    // Which triangles went per vertex (green) and per pixel (red).
    let mut map = ad.clone();
    for i in 0..map.color.len() {
        let t = map.triangle[i];
        if t == 0 {
            continue;
        }
        let tri = sphere.triangles[t as usize - 1];
        let p = tri.map(|k| sphere.positions[k as usize]);
        let n = tri.map(|k| sphere.normals[k as usize]);
        let ok = shader.per_vertex_ok(p, n);
        let shade = 0.3 + 0.7 * ad.color[i].max_element().min(1.0);
        map.color[i] = if ok {
            Vec3::new(0.0, shade, 0.1)
        } else {
            Vec3::new(shade, 0.05, 0.0)
        };
    }
    g.add(
        "adaptive_map",
        &format!(
            "green: per vertex {}/{}",
            ad_stats.per_vertex, ad_stats.triangles
        ),
        &Image::from_linear(&map),
    );
    g.end_row();
}

/// A culling threshold of half an 8-bit step, as [`Attenuation::cull_radius`] suggests.
const HALF_STEP: f32 = 0.5 / 255.0;

fn attenuation(opts: &Options, g: &mut Gallery) {
    let camera = Camera::look_at(Vec3::new(0.0, 17.0, 17.0), Vec3::new(0.0, 0.0, 0.5))
        .with_fov_degrees(62.0);
    let floor = Mesh::plane(18.0, 18);
    let height = 0.6;
    let at = Vec3::new(0.0, height, 0.0);
    let forms: [(&str, Attenuation); 5] = [
        ("none", Attenuation::None),
        (
            "polynomial 1,0.7,1.8",
            Attenuation::polynomial(1.0, 0.7, 1.8),
        ),
        (
            "inverse square",
            Attenuation::try_inverse_square(0.36).expect("valid"),
        ),
        ("Unreal r=6", Attenuation::try_unreal(6.0).expect("valid")),
        (
            "Frostbite r=6",
            Attenuation::try_frostbite(6.0).expect("valid"),
        ),
    ];
    let size = (opts.size, opts.size);
    let mat = material(Vec3::splat(0.8), opts.shininess);
    g.row("One point light, each falloff; yellow: cull radius at half an 8-bit step");
    for (name, att) in forms {
        // Scale the light so each form is 1 right under it.
        let k = 1.0 / att.factor(height);
        let light = PointLight::try_new(at, att, colours(0.0, k, 0.3 * k))
            .expect("valid light")
            .into();
        let lights = [light];
        let scene = Scene {
            lights: &lights,
            ambient: Vec3::ZERO,
            viewer: Viewer::At(camera.eye),
        };
        let shader = PhongShader::new(opts.model, mat, scene);
        let (fb, _) = render(
            size,
            &camera,
            &[(&floor, Mat4::IDENTITY)],
            &shader,
            ShadingMode::PerPixel,
        );
        let mut img = Image::from_linear(&fb);
        // The brightest channel a skipped light could change is k · 0.8 · (1 + 0.3).
        let r = att.cull_radius(HALF_STEP / (k * 0.8 * 1.3));
        let label = if r.is_finite() {
            // Where the sphere of radius r meets the floor.
            let on_floor = (r * r - height * height).max(0.0).sqrt();
            draw_circle(&mut img, &camera, at.with_y(0.0), on_floor);
            format!("{name}: r={r:.1}")
        } else {
            format!("{name}: never culled")
        };
        g.add(
            &format!("attenuation_{}", name.split(' ').next().unwrap_or(name)),
            &label,
            &img,
        );
    }
    g.end_row();
}

fn draw_circle(img: &mut Image, camera: &Camera, centre: Vec3, radius: f32) {
    let n = 720;
    for k in 0..n {
        let a = k as f32 / n as f32 * std::f32::consts::TAU;
        let p = centre + Vec3::new(a.cos(), 0.0, a.sin()) * radius;
        if let Some((x, y)) = camera.project(p, img.width, img.height) {
            for (dx, dy) in [(0, 0), (1, 0), (0, 1)] {
                img.put(x as i64 + dx, y as i64 + dy, [255, 220, 0]);
            }
        }
    }
}

fn culling(opts: &Options, g: &mut Gallery) {
    let camera = Camera::look_at(Vec3::new(0.0, 10.0, 10.0), Vec3::ZERO);
    let floor = Mesh::plane(8.0, 16);
    let sphere = Mesh::icosphere(3);
    let mut lights = Vec::new();
    for j in 0..5 {
        for i in 0..5 {
            let hue = Vec3::new(
                0.5 + 0.5 * (i as f32 * 1.3).sin(),
                0.5 + 0.5 * (j as f32 * 1.7 + 1.0).sin(),
                0.5 + 0.5 * ((i + j) as f32 * 0.9 + 2.0).sin(),
            );
            let p = Vec3::new(-6.0 + 3.0 * i as f32, 0.5, -6.0 + 3.0 * j as f32);
            let att = if (i + j) % 2 == 0 {
                Attenuation::polynomial(1.0, 0.7, 1.8)
            } else {
                Attenuation::try_frostbite(3.0).expect("valid")
            };
            let c = LightColors::try_new(hue * 0.02, hue * 0.9, hue * 0.5).expect("valid colours");
            lights.push(Light::from(
                PointLight::try_new(p, att, c).expect("valid light"),
            ));
        }
    }
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::splat(0.02),
        viewer: Viewer::At(camera.eye),
    };
    let mat = material(Vec3::splat(0.8), opts.shininess);
    let full = PhongShader::new(opts.model, mat, scene);
    let culled = PhongShader::new(opts.model, mat, scene).with_culling(HALF_STEP);
    let size = (opts.size, opts.size);
    let parts = [
        (&floor, Mat4::IDENTITY),
        (&sphere, Mat4::from_translation(Vec3::new(0.0, 1.0, 0.0))),
    ];
    let (a, _) = render(size, &camera, &parts, &full, ShadingMode::PerPixel);
    let (b, _) = render(size, &camera, &parts, &culled, ShadingMode::PerPixel);
    let (evaluated, skipped) = (culled.evaluations.get(), culled.skipped.get());
    let err = a.max_difference(&b);
    let (ia, ib) = (Image::from_linear(&a), Image::from_linear(&b));
    let err8 = ia
        .pixels
        .iter()
        .zip(&ib.pixels)
        .flat_map(|(p, q)| (0..3).map(move |k| p[k].abs_diff(q[k])))
        .max()
        .unwrap_or(0);
    println!(
        "  light culling ({} lights, threshold half an 8-bit step): {skipped} of {} light \
         evaluations skipped ({:.0}%); max error {err:.6} linear ({:.3}/255), {err8} step(s) in \
         8-bit sRGB",
        lights.len(),
        evaluated + skipped,
        100.0 * skipped as f64 / (evaluated + skipped).max(1) as f64,
        err * 255.0
    );
    g.row("25 point lights, with and without culling by cull radius");
    g.add("culling_off", "all lights", &ia);
    g.add(
        "culling_on",
        &format!(
            "culled: {:.0}% skipped",
            100.0 * skipped as f64 / (evaluated + skipped).max(1) as f64
        ),
        &ib,
    );
    g.add(
        "culling_difference",
        &format!("difference x100, max {:.2}/255", err * 255.0),
        &Image::from_linear(&a.difference(&b, 100.0)),
    );
    g.end_row();
}

fn linear_vs_srgb(opts: &Options, g: &mut Gallery) {
    let (camera, sun, viewer) = sphere_setup(opts);
    let sphere = Mesh::icosphere(4);
    let lights = [sun];
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer,
    };
    let shader = PhongShader::new(opts.model, material(CORAL, opts.shininess), scene);
    let (fb, _) = render(
        (opts.size, opts.size),
        &camera,
        &[(&sphere, Mat4::IDENTITY)],
        &shader,
        ShadingMode::PerPixel,
    );
    g.row("The same linear image, written raw and sRGB-encoded");
    g.add("linear_raw", "linear written raw", &Image::from_raw(&fb));
    g.add("srgb", "sRGB-encoded", &Image::from_linear(&fb));
    g.end_row();
}

fn spot(opts: &Options, g: &mut Gallery) {
    let camera = Camera::look_at(Vec3::new(0.0, 4.0, 6.0), Vec3::new(0.0, 0.0, 0.0));
    let floor = Mesh::plane(6.0, 12);
    let sphere = Mesh::icosphere(4);
    let pos = Vec3::new(1.5, 4.0, 1.5);
    let light = SpotLight::try_new(
        pos,
        Vec3::new(0.0, 0.0, -0.5) - pos,
        25f32.to_radians(),
        6.0,
        Attenuation::None,
        colours(0.05, 0.7, 0.5),
    )
    .expect("valid spot")
    .into();
    let lights = [light];
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::splat(0.03),
        viewer: Viewer::At(camera.eye),
    };
    let shader = PhongShader::new(
        opts.model,
        material(Vec3::splat(0.6), opts.shininess),
        scene,
    );
    let (fb, _) = render(
        (opts.size, opts.size),
        &camera,
        &[
            (&floor, Mat4::IDENTITY),
            (
                &sphere,
                Mat4::from_translation(Vec3::new(0.0, 0.7, -0.5))
                    * Mat4::from_scale(Vec3::splat(0.7)),
            ),
        ],
        &shader,
        ShadingMode::PerPixel,
    );
    g.row("A spot light: 25 degree cone, exponent 6");
    g.add("spot", "spot light", &Image::from_linear(&fb));
    g.end_row();
}

fn gate(opts: &Options, g: &mut Gallery) {
    let camera = Camera::look_at(Vec3::new(0.0, 0.0, 4.2), Vec3::ZERO);
    let sphere = Mesh::icosphere(4);
    // The light almost straight behind the sphere: L ≈ −V, so R·V → 1 at the silhouette.
    let light = DirectionalLight::try_new(Vec3::new(0.3, 0.4, -1.0), colours(0.05, 0.8, 1.0))
        .expect("valid light")
        .into();
    let lights = [light];
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(camera.eye),
    };
    let s = 8.0;
    g.row("Light behind the sphere: the specular gate (s=8)");
    for (gate, name) in [
        (SpecularGate::None, "no gate: back halo"),
        (SpecularGate::Step, "step gate"),
        (SpecularGate::Cosine, "cosine gate"),
    ] {
        let shader = PhongShader::new(with_model(opts.model, gate), material(CORAL, s), scene);
        let (fb, _) = render(
            (opts.size, opts.size),
            &camera,
            &[(&sphere, Mat4::IDENTITY)],
            &shader,
            ShadingMode::PerPixel,
        );
        g.add(
            &format!("gate_{}", name.split([' ', ':']).next().unwrap_or(name)),
            name,
            &Image::from_linear(&fb),
        );
    }
    g.end_row();
}

fn cube(opts: &Options, g: &mut Gallery) {
    // LearnOpenGL's "Basic Lighting" scene: a coral cube, a white point light near it, strengths
    // 0.1 / 1.0 / 0.5.
    let camera = Camera::look_at(Vec3::new(-0.9, 1.1, 2.8), Vec3::ZERO);
    let light = PointLight::try_new(
        Vec3::new(1.2, 1.0, 2.0),
        Attenuation::None,
        colours(0.1, 1.0, 0.5),
    )
    .expect("valid light")
    .into();
    let lights = [light];
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(camera.eye),
    };
    let shader = PhongShader::new(opts.model, material(CORAL, opts.shininess), scene);
    let cube = Mesh::cube();
    // Turn the front face toward the bisector of the eye and light directions, so its highlight
    // falls inside the face, between the vertices.
    let bisector = (camera.eye.normalize() + Vec3::new(1.2, 1.0, 2.0).normalize()).normalize();
    let model =
        Mat4::from_quat(Quat::from_rotation_arc(Vec3::Z, bisector)) * Mat4::from_rotation_z(0.3);
    g.row("The lit cube: per vertex misses the highlight inside each face");
    for (mode, name) in [
        (ShadingMode::PerVertex, "per vertex"),
        (ShadingMode::PerPixel, "per pixel"),
    ] {
        let (fb, _) = render(
            (opts.size, opts.size),
            &camera,
            &[(&cube, model)],
            &shader,
            mode,
        );
        g.add(
            &format!("cube_{}", name.replace(' ', "_")),
            name,
            &Image::from_linear(&fb),
        );
    }
    g.end_row();
}

/// Planks with a brass inlay: the diffuse map, and a specular map that is bright on the brass.
fn planks(uv: Vec2) -> (Vec3, Vec3) {
    let (u, v) = (uv.x * 6.0, uv.y * 6.0);
    let row = v.floor();
    let along = u + 0.37 * row;
    let grain = 0.5 + 0.5 * (along * 9.0 + (v * 17.0).sin() * 0.8).sin();
    let seam = (v.fract() < 0.04) || ((along * 0.5).fract() < 0.02);
    let wood = Vec3::new(0.45, 0.28, 0.13) * (0.75 + 0.25 * grain);
    let (fu, fv) = (u.fract(), v.fract());
    let inlay = (fu - 0.5).abs() < 0.2 && (fv - 0.5).abs() < 0.2;
    if inlay {
        (Vec3::new(0.35, 0.25, 0.08), Vec3::new(1.0, 0.85, 0.5))
    } else if seam {
        (Vec3::splat(0.05), Vec3::splat(0.02))
    } else {
        (phong::srgb_decode(0.9) * wood, Vec3::splat(0.08))
    }
}

fn textured(opts: &Options, g: &mut Gallery) {
    let (camera, _) = floor_scene();
    // A brighter specular light than the floor scene's, so the brass shines and the wood does not.
    let light = PointLight::try_new(
        Vec3::new(0.3, 0.6, -2.0),
        Attenuation::polynomial(1.0, 0.09, 0.032),
        colours(0.05, 0.8, 1.0),
    )
    .expect("valid light")
    .into();
    let floor = Mesh::plane(3.0, 8);
    let place = Mat4::from_translation(Vec3::new(0.0, -0.5, 0.0));
    let lights = [light];
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::splat(0.05),
        viewer: Viewer::At(camera.eye),
    };
    let mut shader = PhongShader::new(opts.model, material(Vec3::ONE, opts.shininess), scene);
    shader.texture = Some(planks);
    let (fb, _) = render(
        (opts.size, opts.size),
        &camera,
        &[(&floor, place)],
        &shader,
        ShadingMode::PerPixel,
    );
    // The maps themselves, for reference.
    let n = opts.size;
    let mut diffuse = Framebuffer::new(n, n, Vec3::ZERO);
    let mut specular = Framebuffer::new(n, n, Vec3::ZERO);
    for y in 0..n {
        for x in 0..n {
            let (d, s) = planks(Vec2::new(x as f32 / n as f32, y as f32 / n as f32));
            let i = diffuse.index(x, y);
            diffuse.color[i] = d;
            specular.color[i] = s;
        }
    }
    g.row("Diffuse and specular maps (Material::textured)");
    g.add("maps_diffuse", "diffuse map", &Image::from_linear(&diffuse));
    g.add(
        "maps_specular",
        "specular map",
        &Image::from_linear(&specular),
    );
    g.add("maps_lit", "lit plane", &Image::from_linear(&fb));
    g.end_row();
}

/// The grazing scene: a camera low over a large floor, the sun low ahead of it.
pub fn grazing_scene() -> (Camera, Light) {
    let camera = Camera::look_at(Vec3::new(0.0, 0.4, 0.0), Vec3::new(0.0, 0.0, -3.0));
    let e = 8f32.to_radians();
    let sun = DirectionalLight::try_new(Vec3::new(0.0, e.sin(), -e.cos()), colours(0.0, 0.3, 1.0))
        .expect("valid light")
        .into();
    (camera, sun)
}

fn grazing(opts: &Options, g: &mut Gallery) {
    let (camera, sun) = grazing_scene();
    let floor = Mesh::plane(40.0, 8);
    let lights = [sun];
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(camera.eye),
    };
    let n = 256.0;
    g.row("Grazing view: Phong's highlight stays round, Blinn-Phong's stretches");
    for (model, s, name) in [
        (Model::from(Phong::default()), n, "Phong s=256"),
        (
            Model::from(BlinnPhong::default()),
            4.0 * n,
            "Blinn-Phong s=1024",
        ),
    ] {
        let shader =
            PhongShader::new(model, material(Vec3::splat(0.6), s), scene).with_term(Term::Specular);
        let (fb, _) = render(
            (opts.size, opts.size),
            &camera,
            &[(&floor, Mat4::IDENTITY)],
            &shader,
            ShadingMode::PerPixel,
        );
        g.add(
            &format!("grazing_{}", if s == n { "phong" } else { "blinn" }),
            &format!("{name} specular"),
            &Image::from_linear(&fb),
        );
    }
    g.end_row();
}
