//! The error measurements behind docs/accuracy.md: every `f32` function of `phong` against the
//! `f64` reference, on ordinary and adversarial input domains.
//!
//! `rows(n)` runs them all with `n` samples per row from fixed seeds. The `accuracy` tool calls it
//! with a large `n` and writes the tables; tests/accuracy_bounds.rs calls it with a small `n` and
//! asserts each row against a bound.

use glam::{DMat3, DVec3, Mat3, Vec3};
use phong::{
    Attenuation, BlinnPhong, Incidence, Lambert, Light, LightColors, Material, Model,
    Normalization, Phong, PointLight, PowStrategy, ReflectionModel, ResolvedModel, SpecularGate,
    SpotLight, Viewer,
};

use crate::reference as r;
use crate::rng::Rng;

use crate::models;

// ---------------------------------------------------------------------------------------------
// Error statistics

/// The spacing of `f32` values at `|x|` (the subnormal spacing below `f32::MIN_POSITIVE`).
pub fn ulp_f32(x: f64) -> f64 {
    let a = (x.abs() as f32).max(f32::MIN_POSITIVE);
    if !a.is_finite() {
        return f64::from(f32::MAX) * f64::EPSILON; // beyond the range: the last spacing, 2^104
    }
    let e = ((a.to_bits() >> 23) & 0xff) as i32 - 127;
    2f64.powi(e - 23)
}

/// Maximum errors over a sample.
#[derive(Clone, Debug, Default)]
pub struct Stats {
    /// Samples measured.
    pub n: usize,
    /// The largest absolute error.
    pub max_abs: f64,
    /// The largest relative error (against `max(|reference|, floor)`).
    pub max_rel: f64,
    /// The largest error in `f32` ulps of the reference.
    pub max_ulp: f64,
    /// Outputs that were NaN or infinite where the reference is finite.
    pub non_finite: usize,
    /// The input that gave the largest `ulp` (or `rel` when ulps are not meaningful), for reports.
    pub worst: String,
}

impl Stats {
    /// One scalar output. Relative error counts only where `|want| ≥ floor`.
    pub fn scalar(&mut self, got: f32, want: f64, floor: f64, input: impl FnOnce() -> String) {
        self.n += 1;
        if !got.is_finite() {
            if want.is_finite() {
                self.non_finite += 1;
                if self.non_finite == 1 {
                    self.worst = format!("{} -> {got}", input());
                }
            }
            return;
        }
        let err = (got as f64 - want).abs();
        // Ulps and relative error only where the reference is at least the floor and a normal
        // f32: below that (underflow, subnormals, 0) the absolute column judges the answer.
        let ulp = if want.abs() >= floor.max(f32::MIN_POSITIVE as f64) {
            err / ulp_f32(want)
        } else {
            0.0
        };
        self.max_abs = self.max_abs.max(err);
        if want.abs() >= floor.max(f32::MIN_POSITIVE as f64) {
            self.max_rel = self.max_rel.max(err / want.abs());
        }
        if ulp > self.max_ulp && self.non_finite == 0 {
            self.max_ulp = ulp;
            self.worst = format!("{} -> {got} (want {want})", input());
        }
    }

    /// One vector output: abs = largest component error, rel = ‖got − want‖/‖want‖ (where
    /// `‖want‖ ≥ floor`), ulp = largest component error in ulps of the largest component of `want`.
    pub fn vector(&mut self, got: Vec3, want: DVec3, floor: f64, input: impl FnOnce() -> String) {
        self.n += 1;
        if !got.is_finite() {
            if want.is_finite() {
                self.non_finite += 1;
                if self.non_finite == 1 {
                    self.worst = format!("{} -> {got}", input());
                }
            }
            return;
        }
        let d = got.as_dvec3() - want;
        let err = d.abs().max_element();
        let big = want.abs().max_element();
        let ulp = if big >= f32::MIN_POSITIVE as f64 {
            err / ulp_f32(big)
        } else {
            0.0 // judged by the absolute column
        };
        self.max_abs = self.max_abs.max(err);
        let wl = want.length();
        if wl >= floor && wl != 0.0 {
            self.max_rel = self.max_rel.max(d.length() / wl);
        }
        if ulp > self.max_ulp && self.non_finite == 0 {
            self.max_ulp = ulp;
            self.worst = format!("{} -> {got} (want {want})", input());
        }
    }

    /// One matrix output, by its columns (as [`vector`](Self::vector) on the stacked columns,
    /// relative to the largest entry).
    pub fn matrix(&mut self, got: Mat3, want: DMat3, floor: f64, input: impl FnOnce() -> String) {
        self.n += 1;
        if !got.is_finite() {
            self.non_finite += 1;
            return;
        }
        let d = got.as_dmat3() - want;
        let err = d.abs().to_cols_array().into_iter().fold(0.0, f64::max);
        let big = want.abs().to_cols_array().into_iter().fold(0.0, f64::max);
        let fro = |m: DMat3| m.to_cols_array().iter().map(|x| x * x).sum::<f64>().sqrt();
        self.max_abs = self.max_abs.max(err);
        if fro(want) >= floor {
            self.max_rel = self.max_rel.max(fro(d) / fro(want));
        }
        let ulp = if big == 0.0 { 0.0 } else { err / ulp_f32(big) };
        if ulp > self.max_ulp {
            self.max_ulp = ulp;
            self.worst = input();
        }
    }
}

/// One row of the accuracy tables.
#[derive(Clone, Debug)]
pub struct Row {
    /// The function (or group) measured.
    pub function: &'static str,
    /// `"ordinary"` or `"adversarial"`.
    pub kind: &'static str,
    /// The input domain, in words.
    pub domain: &'static str,
    /// Whether the ulp column is meaningful for this row.
    pub ulps: bool,
    /// The relative-error floor: outputs with a smaller reference are judged by absolute error.
    pub floor: f64,
    /// The measured errors.
    pub stats: Stats,
}

impl Row {
    /// The stable key the bounds test uses: `function | domain`.
    pub fn key(&self) -> String {
        format!("{} | {}", self.function, self.domain)
    }
}

const ORD: &str = "ordinary";
const MIN_NORMAL: f64 = f32::MIN_POSITIVE as f64;
const ADV: &str = "adversarial";

fn row(
    function: &'static str,
    kind: &'static str,
    domain: &'static str,
    ulps: bool,
    floor: f64,
    stats: Stats,
) -> Row {
    Row {
        function,
        kind,
        domain,
        ulps,
        floor,
        stats,
    }
}

/// How far from the cone's edge `cos cutoff` the `f32` cosine of a spot light may decide either
/// way: `c = −L·axis` in `f32` is within `γ₃·‖L‖‖axis‖ ≈ 3·2⁻²⁴` of the exact cosine of the
/// given `f32` vectors (three products and two sums, each rounded once; both vectors unit to
/// within a few `2⁻²⁴`), so `4·2⁻²⁴ = 2⁻²²` covers it with margin. Farther from the edge the
/// crate's decision must be the exact one.
pub const SPOT_EDGE_BAND: f64 = 1.0 / 4_194_304.0;

/// `2⁻⁶⁰`: repeated squaring reads a base whose power is below this as 0 (no subnormal products:
/// see `PowStrategy`'s docs), so its lobes are judged relatively only from here up, and by the
/// absolute column below.
pub const SQUARING_FLUSH: f64 = 8.673_617_379_884_035e-19;

/// `2⁻⁴⁸`: [`SQUARING_FLUSH`] times 4096, above the largest normalisation factor the lobe rows
/// apply (Phong's `(s + 2)/2π < 1600` at `s = 10⁴`): the models' specular rows are judged
/// relatively from here up, and by the absolute column below.
pub const LOBE_FLUSH: f64 = 3.552_713_678_800_501e-15;

// ---------------------------------------------------------------------------------------------
// Inputs

/// A random unit `N`, and `L`, `V` in its upper hemisphere.
fn hemisphere_triple(rng: &mut Rng) -> (Vec3, Vec3, Vec3) {
    let n = rng.unit_vec3();
    (n, rng.hemisphere(n), rng.hemisphere(n))
}

/// `N`, and `L`, `V` at grazing angles: between 1e-4 and 1e-1 rad above the tangent plane.
fn grazing_triple(rng: &mut Rng) -> (Vec3, Vec3, Vec3) {
    let n = rng.unit_vec3();
    let half_pi = core::f64::consts::FRAC_PI_2;
    let a = half_pi - rng.log_range(1e-4, 1e-1);
    let l = rng.at_angle(n, a);
    let b = half_pi - rng.log_range(1e-4, 1e-1);
    let v = rng.at_angle(n, b);
    (n, l, v)
}

/// `N`, `L` grazing, and `V` within a small angle of the mirror direction of `L`: the highlight.
fn grazing_highlight(rng: &mut Rng) -> (Vec3, Vec3, Vec3) {
    let n = rng.unit_vec3();
    let half_pi = core::f64::consts::FRAC_PI_2;
    let a = half_pi - rng.log_range(1e-4, 1e-1);
    let l = rng.at_angle(n, a);
    let rr = r::reflect(n.as_dvec3(), l.as_dvec3()).as_vec3();
    let d = rng.log_range(1e-6, 1e-2);
    let mut v = rng.at_angle(rr, d);
    if v.dot(n) <= 0.0 {
        v = rr;
    }
    (n, l, v)
}

/// `L` and `V` nearly opposite: `V = −L` turned by an angle in [1e-7, 1e-1] rad.
fn near_opposite(rng: &mut Rng) -> (Vec3, Vec3) {
    let l = rng.unit_vec3();
    let d = rng.log_range(1e-7, 1e-1);
    let v = rng.at_angle(-l, d);
    (l, v)
}

/// A shininess in `[0, 10⁴]`: 0 now and then, log-uniform otherwise.
fn wide_shininess(rng: &mut Rng) -> f32 {
    if rng.chance(0.05) {
        0.0
    } else {
        rng.log_range(1e-3, 1e4) as f32
    }
}

fn typical_shininess(rng: &mut Rng) -> f32 {
    rng.log_range(1.0, 256.0).round() as f32
}

fn random_attenuations(rng: &mut Rng) -> [Attenuation; 4] {
    [
        Attenuation::polynomial(
            rng.range(0.0, 1.5) as f32,
            rng.log_range(1e-3, 1.0) as f32,
            rng.log_range(1e-4, 2.0) as f32,
        ),
        Attenuation::try_inverse_square(rng.log_range(1e-2, 1e3) as f32).unwrap(),
        Attenuation::try_unreal(rng.log_range(0.5, 100.0) as f32).unwrap(),
        Attenuation::try_frostbite(rng.log_range(0.5, 100.0) as f32).unwrap(),
    ]
}

const ATT_NAMES: [&str; 4] = [
    "Attenuation::factor — Polynomial",
    "Attenuation::factor — InverseSquare",
    "Attenuation::factor — Unreal",
    "Attenuation::factor — Frostbite",
];
const CULL_NAMES: [&str; 4] = [
    "Attenuation::cull_radius — Polynomial",
    "Attenuation::cull_radius — InverseSquare",
    "Attenuation::cull_radius — Unreal",
    "Attenuation::cull_radius — Frostbite",
];

fn random_model(rng: &mut Rng) -> Model {
    let gate = [SpecularGate::Step, SpecularGate::Cosine, SpecularGate::None][rng.below(3)];
    let normalization = [
        Normalization::None,
        Normalization::Energy,
        Normalization::EnergyExact,
    ][rng.below(3)];
    let pow = [PowStrategy::Exact, PowStrategy::Squaring][rng.below(2)];
    // Lambert, Phong and Blinn-Phong weighted 1 : 2 : 2.
    let kind = [0, 1, 1, 2, 2][rng.below(5)];
    models::assemble(kind, gate, normalization, pow)
}

fn colour(rng: &mut Rng, hi: f64) -> Vec3 {
    Vec3::new(
        rng.range(0.0, hi) as f32,
        rng.range(0.0, hi) as f32,
        rng.range(0.0, hi) as f32,
    )
}

/// A scene as a renderer would set one up: 1–4 lights (directional, point, spot) a few units from
/// a point in the unit cube, a viewer 2–10 units away, plastic-like materials, s in [1, 256].
pub struct ShadeCase {
    /// The reflection model.
    pub model: Model,
    /// The surface's material.
    pub material: Material,
    /// The lights.
    pub lights: Vec<Light>,
    /// The scene's ambient light.
    pub ambient: Vec3,
    /// Where the viewer is.
    pub viewer: Viewer,
    /// The shaded point.
    pub position: Vec3,
    /// The surface normal there (unit).
    pub normal: Vec3,
}

fn light(rng: &mut Rng, p: Vec3, dist: f64, shininess_wide: bool) -> Light {
    let colors = LightColors::new(colour(rng, 0.2), colour(rng, 1.0), colour(rng, 1.0));
    let at = (p.as_dvec3() + dist * rng.unit_dvec3()).as_vec3();
    let att = random_attenuations(rng)[rng.below(4)];
    match rng.below(3) {
        0 => Light::Directional(phong::DirectionalLight::new(rng.unit_vec3(), colors)),
        1 => Light::Point(PointLight::new(at, att, colors)),
        _ => {
            // Aim roughly at the point so the cone matters.
            let axis =
                (p.as_dvec3() - at.as_dvec3()).normalize_or(DVec3::Z) + 0.3 * rng.unit_dvec3();
            let cutoff = rng.range(0.2, 1.5) as f32;
            let e = if shininess_wide {
                rng.range(0.0, 100.0)
            } else {
                rng.range(0.0, 8.0)
            } as f32;
            Light::Spot(SpotLight::try_new(at, axis.as_vec3(), cutoff, e, att, colors).unwrap())
        }
    }
}

/// An ordinary scene: a point in the unit cube, lights a few units away (see [`ShadeCase`]).
pub fn typical_scene(rng: &mut Rng) -> ShadeCase {
    let position = Vec3::new(
        rng.range(-1.0, 1.0) as f32,
        rng.range(-1.0, 1.0) as f32,
        rng.range(-1.0, 1.0) as f32,
    );
    let normal = (rng.unit_dvec3() * rng.range(0.5, 2.0)).as_vec3();
    let lights = (0..1 + rng.below(4))
        .map(|_| {
            let d = rng.range(1.0, 10.0);
            light(rng, position, d, false)
        })
        .collect();
    let eye = (position.as_dvec3() + rng.range(2.0, 10.0) * rng.unit_dvec3()).as_vec3();
    ShadeCase {
        model: random_model(rng),
        material: Material::new(
            colour(rng, 0.3),
            colour(rng, 1.0),
            colour(rng, 1.0),
            typical_shininess(rng),
        ),
        lights,
        ambient: colour(rng, 0.1),
        viewer: Viewer::At(eye),
        position,
        normal,
    }
}

/// Hard scenes: grazing normals, lights from 1e-6 to 1e6 away, far and near viewers, s in
/// [0, 10⁴], positions up to 1e4 from the origin.
pub fn hard_scene(rng: &mut Rng) -> ShadeCase {
    let position = (rng.log_range(1e-3, 1e4) * rng.unit_dvec3()).as_vec3();
    let lights: Vec<Light> = (0..1 + rng.below(4))
        .map(|_| {
            let d = rng.log_range(1e-6, 1e6);
            light(rng, position, d, true)
        })
        .collect();
    let eye_dist = rng.log_range(1e-3, 1e6);
    let eye = (position.as_dvec3() + eye_dist * rng.unit_dvec3()).as_vec3();
    // A normal nearly perpendicular to the direction of the first light or the viewer.
    let towards = match lights[0] {
        Light::Directional(l) => l.direction(),
        Light::Point(l) => (l.position() - position).normalize_or(Vec3::Z),
        Light::Spot(l) => (l.position() - position).normalize_or(Vec3::Z),
    };
    let towards = if rng.chance(0.5) {
        towards
    } else {
        (eye - position).normalize_or(Vec3::Z)
    };
    let half_pi = core::f64::consts::FRAC_PI_2;
    let tilt = half_pi + rng.range(-1e-2, 1e-2);
    let normal = rng.at_angle(towards, tilt) * rng.range(0.5, 2.0) as f32;
    ShadeCase {
        model: random_model(rng),
        material: Material::new(
            colour(rng, 0.3),
            colour(rng, 1.0),
            colour(rng, 1.0),
            wide_shininess(rng),
        ),
        lights,
        ambient: colour(rng, 0.1),
        viewer: if rng.chance(0.2) {
            Viewer::Infinite(rng.unit_vec3())
        } else {
            Viewer::At(eye)
        },
        position,
        normal,
    }
}

/// The shading result of the crate and of the reference. `per_point`: the crate shades the
/// material as a per-point surface (`Shader::shade_surface` with `Surface::of` the material),
/// the path of a textured renderer, whose shininess is a point's own (callers pair it with
/// [`with_auto`], the strategy that path changes).
pub fn shade_both(c: &ShadeCase, per_point: bool) -> (Vec3, DVec3) {
    let scene = phong::Scene {
        lights: &c.lights,
        ambient: c.ambient,
        viewer: c.viewer,
    };
    let got = if per_point {
        phong::Shader::new(c.model, &c.material, &scene)
            .shade_surface(
                c.position,
                c.normal,
                &phong::Surface::of(&c.material),
                phong::Unshadowed,
            )
            .total()
    } else {
        phong::shade(&c.model, &c.material, &scene, c.position, c.normal).total()
    };
    let want = r::shade(
        &c.model,
        &c.material,
        &c.lights,
        c.ambient,
        c.viewer,
        c.position,
        c.normal,
    )
    .total();
    (got, want)
}

/// `model` with `PowStrategy::Auto`, the default, whose polynomial serves a point's own
/// exponent (the scenes' models draw `Exact` and `Squaring`, whose errors are measured per
/// strategy elsewhere).
pub fn with_auto(model: Model) -> Model {
    match model {
        Model::Phong(m) => Model::Phong(phong::Phong {
            pow: phong::PowStrategy::Auto,
            ..m
        }),
        Model::BlinnPhong(m) => Model::BlinnPhong(phong::BlinnPhong {
            pow: phong::PowStrategy::Auto,
            ..m
        }),
        other => other,
    }
}

/// Shading error with the 8-bit sRGB comparison.
#[derive(Clone, Debug, Default)]
pub struct ShadeStats {
    /// The linear colour's errors.
    pub stats: Stats,
    /// Channels compared (three per sample).
    pub channels: usize,
    /// Channels whose 8-bit sRGB value differs from the reference's.
    pub srgb8_differ: usize,
    /// The largest such difference, in 8-bit levels.
    pub srgb8_max_levels: u8,
}

impl ShadeStats {
    /// The fraction of channels whose 8-bit value differs.
    pub fn fraction(&self) -> f64 {
        self.srgb8_differ as f64 / self.channels.max(1) as f64
    }
}

/// Shades `n` scenes (ordinary, or [`hard_scene`]s when `hard`) from `seed` with `phong` (as a
/// per-point surface under [`with_auto`]'s model when `per_point`, see [`shade_both`]) and with
/// the reference, and measures the difference.
pub fn measure_shading(n: usize, seed: u64, hard: bool, per_point: bool) -> ShadeStats {
    let mut rng = Rng::new(seed);
    let mut s = ShadeStats::default();
    for _ in 0..n {
        let c = if hard {
            hard_scene(&mut rng)
        } else {
            typical_scene(&mut rng)
        };
        let c = if per_point {
            ShadeCase {
                model: with_auto(c.model),
                ..c
            }
        } else {
            c
        };
        let (got, want) = shade_both(&c, per_point);
        s.stats.vector(got, want, 1e-3, || {
            format!("scene at {} n {}", c.position, c.normal)
        });
        let a = phong::linear_to_srgb8(got);
        let b = r::linear_to_srgb8(want);
        for i in 0..3 {
            s.channels += 1;
            if a[i] != b[i] {
                s.srgb8_differ += 1;
                s.srgb8_max_levels = s.srgb8_max_levels.max(a[i].abs_diff(b[i]));
            }
        }
    }
    s
}

// ---------------------------------------------------------------------------------------------
// The rows

/// Every row, `n` samples each, from fixed seeds (a row's seed does not depend on `n`).
pub fn rows(n: usize) -> Vec<Row> {
    let mut out = Vec::new();
    geometry(n, &mut out);
    attenuation(n, &mut out);
    batch_spot(n, &mut out);
    lobes(n, &mut out);
    colour_rows(n, &mut out);
    out
}

fn geometry(n: usize, out: &mut Vec<Row>) {
    // normalize_or_zero and length.
    for (kind, domain, seed) in [
        (ORD, "random directions, ‖v‖ in [1e-3, 1e3]", 1u64),
        (
            ADV,
            "components of independent magnitude over the whole f32 range, subnormals, zeros",
            2,
        ),
    ] {
        let mut rng = Rng::new(seed);
        let (mut nz, mut len, mut naive_nz, mut naive_len) = Default::default();
        for _ in 0..n {
            let v = if kind == ORD {
                (rng.unit_dvec3() * rng.log_range(1e-3, 1e3)).as_vec3()
            } else {
                rng.wild_vec3()
            };
            let dv = r::d3(v);
            let (sn, sl, snn, snl): (&mut Stats, &mut Stats, &mut Stats, &mut Stats) =
                (&mut nz, &mut len, &mut naive_nz, &mut naive_len);
            sn.vector(
                phong::normalize_or_zero(v),
                r::normalize_or_zero(dv),
                0.5,
                || format!("v = {v:?}"),
            );
            // `length` saturates at f32::MAX by contract; so does the reference here.
            let want_len = r::length(dv).min(f32::MAX as f64);
            sl.scalar(phong::length(v), want_len, MIN_NORMAL, || {
                format!("v = {v:?}")
            });
            // The naive forms for contrast; zero input is left out (NaN there is the stability
            // matrix's row, not an accuracy question).
            if v != Vec3::ZERO {
                snn.vector(v.normalize(), r::normalize_or_zero(dv), 0.5, || {
                    format!("v = {v:?}")
                });
                snl.scalar(v.length(), want_len, MIN_NORMAL, || format!("v = {v:?}"));
            }
        }
        out.push(row("normalize_or_zero", kind, domain, true, 0.5, nz));
        out.push(row("length", kind, domain, true, MIN_NORMAL, len));
        out.push(row(
            "naive: v.normalize()",
            kind,
            domain,
            true,
            0.5,
            naive_nz,
        ));
        out.push(row(
            "naive: v.length()",
            kind,
            domain,
            true,
            MIN_NORMAL,
            naive_len,
        ));
    }

    // Triangles: ordinary.
    {
        let mut rng = Rng::new(3);
        let (mut area, mut unit, mut naive) =
            (Stats::default(), Stats::default(), Stats::default());
        for _ in 0..n {
            let p = [(); 3].map(|_| (rng.unit_dvec3() * rng.range(0.0, 10.0)).as_vec3());
            let want = r::triangle_area_normal(p[0], p[1], p[2]);
            let input = || format!("{p:?}");
            area.vector(
                phong::triangle_area_normal(p[0], p[1], p[2]),
                want,
                1e-30,
                input,
            );
            unit.vector(
                phong::triangle_normal_or_zero(p[0], p[1], p[2]),
                r::normalize_or_zero(want),
                0.5,
                input,
            );
            naive.vector(
                (p[1] - p[0]).cross(p[2] - p[0]).normalize(),
                r::normalize_or_zero(want),
                0.5,
                input,
            );
        }
        let d = "random triangles in a ball of radius 10";
        out.push(row("triangle_area_normal", ORD, d, true, 1e-30, area));
        out.push(row("triangle_normal_or_zero", ORD, d, true, 0.5, unit));
        out.push(row(
            "naive: normalize((P1−P0)×(P2−P0))",
            ORD,
            d,
            true,
            0.5,
            naive,
        ));
    }
    // Triangles: the sliver set (every 7th triangle to keep the row cheap; the full set is in
    // the sliver study).
    {
        let mut rng = Rng::new(4);
        let per_cell = (n / 5000).clamp(1, 4);
        let (set, _) = crate::slivers::sliver_set(&mut rng, per_cell);
        let (mut area, mut unit, mut naive) =
            (Stats::default(), Stats::default(), Stats::default());
        for t in set.iter().step_by(7) {
            let [a, b, c] = t.p;
            let want = r::triangle_area_normal(a, b, c);
            let input = || format!("{:?}", t.p);
            area.vector(phong::triangle_area_normal(a, b, c), want, 0.0, input);
            unit.vector(
                phong::triangle_normal_or_zero(a, b, c),
                r::normalize_or_zero(want),
                0.5,
                input,
            );
            naive.vector(
                crate::slivers::naive(a, b, c).normalize(),
                r::normalize_or_zero(want),
                0.5,
                input,
            );
        }
        let d = "sliver set (needles and caps, aspect 1e-1…1e-5, size 1e-2…1, offset 1…1e5)";
        out.push(row("triangle_area_normal", ADV, d, true, 0.0, area));
        out.push(row("triangle_normal_or_zero", ADV, d, true, 0.5, unit));
        out.push(row(
            "naive: normalize((P1−P0)×(P2−P0))",
            ADV,
            d,
            true,
            0.5,
            naive,
        ));
    }

    // reflect
    for (kind, domain, seed) in [
        (ORD, "unit N, L in N's hemisphere", 5u64),
        (ADV, "unit N, L grazing (1e-4…1e-1 rad above the plane)", 6),
    ] {
        let mut rng = Rng::new(seed);
        let mut s = Stats::default();
        for _ in 0..n {
            let (nn, l, _) = if kind == ORD {
                hemisphere_triple(&mut rng)
            } else {
                grazing_triple(&mut rng)
            };
            s.vector(
                phong::reflect(nn, l),
                r::reflect(r::d3(nn), r::d3(l)),
                0.5,
                || format!("n = {nn:?}, l = {l:?}"),
            );
        }
        out.push(row("reflect", kind, domain, true, 0.5, s));
    }

    // halfway
    for (kind, domain, seed) in [
        (ORD, "unit L, V uniform on the sphere", 7u64),
        (ADV, "V = −L turned by 1e-7…1e-1 rad", 8),
    ] {
        let mut rng = Rng::new(seed);
        let (mut s, mut naive) = (Stats::default(), Stats::default());
        for _ in 0..n {
            let (l, v) = if kind == ORD {
                (rng.unit_vec3(), rng.unit_vec3())
            } else {
                near_opposite(&mut rng)
            };
            let want = r::halfway(r::d3(l), r::d3(v));
            s.vector(phong::halfway_or_zero(l, v), want, 0.5, || {
                format!("l = {l:?}, v = {v:?}")
            });
            if l + v != Vec3::ZERO {
                naive.vector((l + v).normalize(), want, 0.5, || {
                    format!("l = {l:?}, v = {v:?}")
                });
            }
        }
        out.push(row("halfway_or_zero", kind, domain, true, 0.5, s));
        out.push(row(
            "naive: normalize(L + V)",
            kind,
            domain,
            true,
            0.5,
            naive,
        ));
    }

    // face_forward: a sign decision. Error 2 (a flip) only where f32 rounds Nref·V to the wrong
    // sign; the adversarial set puts V within 1e-9…1e-3 rad of the plane ⟂ Nref.
    for (kind, domain, seed) in [
        (ORD, "random N, V, Nref (not unit)", 9u64),
        (ADV, "V within 1e-9…1e-3 rad of the plane ⟂ Nref", 10),
    ] {
        let mut rng = Rng::new(seed);
        let mut s = Stats::default();
        for _ in 0..n {
            let nn = rng.unit_vec3();
            let nref = (rng.unit_dvec3() * rng.range(0.1, 10.0)).as_vec3();
            let v = if kind == ORD {
                (rng.unit_dvec3() * rng.range(0.1, 10.0)).as_vec3()
            } else {
                let sgn = if rng.chance(0.5) { 1.0 } else { -1.0 };
                let t = core::f64::consts::FRAC_PI_2 + sgn * rng.log_range(1e-9, 1e-3);
                rng.at_angle(nref, t)
            };
            s.vector(
                phong::face_forward(nn, v, nref),
                r::face_forward(r::d3(nn), r::d3(v), r::d3(nref)),
                0.5,
                || format!("n = {nn:?}, v = {v:?}, nref = {nref:?}"),
            );
        }
        out.push(row("face_forward", kind, domain, false, 0.5, s));
    }

    // normal_matrix and transform_normal
    for (kind, domain, seed) in [
        (ORD, "random matrices, entries in [−2, 2]", 11u64),
        (
            ADV,
            "near-singular (a column 1e-6…1e-1 off the plane of the others), mirrored, scales 1e-6…1e6",
            12,
        ),
    ] {
        let mut rng = Rng::new(seed);
        let (mut nm, mut tn) = (Stats::default(), Stats::default());
        for _ in 0..n {
            let m = if kind == ORD {
                Mat3::from_cols_array(&[(); 9].map(|_| rng.range(-2.0, 2.0) as f32))
            } else {
                let a = rng.unit_dvec3() * rng.log_range(1e-6, 1e6);
                let b = rng.unit_dvec3() * rng.log_range(1e-6, 1e6);
                let c = (rng.range(-1.0, 1.0) * a.normalize()
                    + rng.range(-1.0, 1.0) * b.normalize()
                    + rng.log_range(1e-6, 1e-1) * rng.unit_dvec3())
                    * rng.log_range(1e-6, 1e6);
                let cols = [a, b, c].map(|x| x.as_vec3());
                let i = rng.below(3);
                let mut cols = [cols[i], cols[(i + 1) % 3], cols[(i + 2) % 3]];
                if rng.chance(0.5) {
                    cols[0] = -cols[0];
                }
                Mat3::from_cols(cols[0], cols[1], cols[2])
            };
            let dm = r::dm3(m);
            let want = r::normal_matrix(dm);
            nm.matrix(phong::normal_matrix(m), want, 0.0, || format!("M = {m:?}"));
            let nn = rng.unit_vec3();
            tn.vector(
                phong::transform_normal(phong::normal_matrix(m), nn),
                r::normalize_or_zero(want * r::d3(nn)),
                0.5,
                || format!("M = {m:?}, n = {nn:?}"),
            );
        }
        out.push(row("normal_matrix", kind, domain, true, 0.0, nm));
        out.push(row("transform_normal", kind, domain, true, 0.5, tn));
    }
}

fn attenuation(n: usize, out: &mut Vec<Row>) {
    for (kind, domain, seed) in [
        (ORD, "d in [0, 100], random valid parameters", 20u64),
        (ADV, "d = 0 or log-uniform in [1e-30, 1e30]", 21),
    ] {
        let mut rng = Rng::new(seed);
        let mut s: [Stats; 4] = Default::default();
        for _ in 0..n {
            let forms = random_attenuations(&mut rng);
            let d = if kind == ORD {
                rng.range(0.0, 100.0)
            } else if rng.chance(0.05) {
                0.0
            } else {
                rng.log_range(1e-30, 1e30)
            } as f32;
            for (i, a) in forms.iter().enumerate() {
                s[i].scalar(a.factor(d), r::attenuation(a, d as f64), 1e-30, || {
                    format!("{a:?}, d = {d:?}")
                });
            }
        }
        for (i, st) in s.into_iter().enumerate() {
            out.push(row(ATT_NAMES[i], kind, domain, true, 1e-30, st));
        }
    }
    for (kind, domain, seed) in [
        (
            ORD,
            "threshold in [1e-4, 0.1], random valid parameters",
            22u64,
        ),
        (ADV, "threshold log-uniform in [1e-9, 1e4]", 23),
    ] {
        let mut rng = Rng::new(seed);
        let mut s: [Stats; 4] = Default::default();
        for _ in 0..n / 4 {
            let forms = random_attenuations(&mut rng);
            let t = if kind == ORD {
                rng.log_range(1e-4, 0.1)
            } else {
                rng.log_range(1e-9, 1e4)
            } as f32;
            for (i, a) in forms.iter().enumerate() {
                s[i].scalar(a.cull_radius(t), r::cull_radius(a, t as f64), 1e-30, || {
                    format!("{a:?}, t = {t:?}")
                });
            }
        }
        for (i, st) in s.into_iter().enumerate() {
            out.push(row(CULL_NAMES[i], kind, domain, true, 1e-30, st));
        }
    }
    // Spot factor
    for (kind, domain, seed) in [
        (
            ORD,
            "random axis, cutoff, exponent in [0, 8]; L near the cone",
            24u64,
        ),
        (
            ADV,
            "exponent in [0, 1e4]; L within 1e-6 rad of the cone's edge (either side accepted within 2⁻²² of it)",
            25,
        ),
    ] {
        let mut rng = Rng::new(seed);
        let mut s = Stats::default();
        for _ in 0..n {
            let spot = random_spot(&mut rng, kind, LightColors::BLACK);
            let (axis, cutoff, e) = (spot.axis(), spot.cutoff(), spot.exponent());
            let theta = if kind == ORD {
                rng.range(0.0, cutoff as f64 * 1.2)
            } else {
                cutoff as f64 + rng.range(-1e-6, 1e-6)
            };
            // L points from the surface to the light: opposite the light's beam direction.
            let l = -rng.at_angle(spot.axis(), theta);
            let got = spot.spot_factor(l);
            let (c, cos_cutoff) = (-r::d3(l).dot(r::d3(spot.axis())), spot.cos_cutoff() as f64);
            let want = if (c - cos_cutoff).abs() <= SPOT_EDGE_BAND {
                // The f32 cosine may land on either side of the edge here; either answer is
                // right, and the one given must be right for its side.
                if got == 0.0 {
                    0.0
                } else {
                    r::lobe_pow(c, e as f64)
                }
            } else {
                r::spot_factor(r::d3(l), r::d3(spot.axis()), cos_cutoff, e as f64)
            };
            s.scalar(got, want, 1e-30, || {
                format!("axis = {axis:?}, cutoff = {cutoff}, e = {e}, l = {l:?}")
            });
        }
        // Near the cone's edge the factor steps from (cos cutoff)^e to 0: a decision, not ulps.
        out.push(row(
            "SpotLight::spot_factor",
            kind,
            domain,
            kind == ORD,
            1e-30,
            s,
        ));
    }
}

/// The spot factor as the batch kernel computes it (its own vector `pow` for the cone's `c^e`,
/// `PowStrategy::Auto`'s plan for `e`), read through a Lambert diffuse: one spot light at the
/// origin with unit diffuse colour and no falloff, `kd = 1`, and each point's normal pointing at
/// the light, so the output is `spot(c)·N·L`. Measured against the `f64` reference of the same
/// product from the same `f32` inputs, at every level this machine supports (the largest error
/// over the levels), 16 points per light so every lane of a chunk is used.
fn batch_spot(n: usize, out: &mut Vec<Row>) {
    for (kind, domain, seed) in [
        (
            ORD,
            "random axis, cutoff, exponent in [0, 8]; L near the cone; every level, N toward the light",
            26u64,
        ),
        (
            ADV,
            "exponent in [0, 1e4]; L within 1e-6 rad of the cone's edge (either side accepted within 2⁻²² of it); every level, N toward the light",
            27,
        ),
    ] {
        let mut s = Stats::default();
        for level in phong::Level::supported() {
            let mut rng = Rng::new(seed);
            for _ in 0..n.div_ceil(BATCH_SPOT_POINTS) {
                batch_spot_call(&mut rng, kind, level, &mut s);
            }
        }
        out.push(row(
            "shade_batch spot factor (Lambert, N·L ≈ 1)",
            kind,
            domain,
            kind == ORD,
            BATCH_SPOT_FLOOR,
            s,
        ));
    }
}

/// Points per light in [`batch_spot`]: one chunk of the widest level.
const BATCH_SPOT_POINTS: usize = 16;

/// The batch spot rows' relative-error floor, `2⁻²⁴`: the kernel's `pow` promises a relative
/// error against `max(c^e, 2⁻²⁴)` (the batch module's "Accuracy"), so smaller factors are judged
/// by the absolute column.
const BATCH_SPOT_FLOOR: f64 = 1.0 / 16_777_216.0;

/// A spot light at the origin for the spot rows, without falloff: a random axis, a cutoff in
/// `[0.05, 1.5]` rad, and an exponent in `[0, 8]` (`ORD`) or log-uniform in `[1e-3, 1e4]`.
fn random_spot(rng: &mut Rng, kind: &str, colors: LightColors) -> SpotLight {
    let axis = rng.unit_vec3();
    let cutoff = rng.range(0.05, 1.5) as f32;
    let e = if kind == ORD {
        rng.range(0.0, 8.0)
    } else {
        rng.log_range(1e-3, 1e4)
    } as f32;
    SpotLight::try_new(Vec3::ZERO, axis, cutoff, e, Attenuation::None, colors).unwrap()
}

fn batch_spot_call(rng: &mut Rng, kind: &str, level: phong::Level, s: &mut Stats) {
    let colors = LightColors::try_new(Vec3::ZERO, Vec3::ONE, Vec3::ZERO).unwrap();
    let spot = random_spot(rng, kind, colors);
    let (axis, cutoff, e) = (spot.axis(), spot.cutoff(), spot.exponent());
    let mut pos = [[0f32; BATCH_SPOT_POINTS]; 3];
    let mut nor = [[0f32; BATCH_SPOT_POINTS]; 3];
    for i in 0..BATCH_SPOT_POINTS {
        let theta = if kind == ORD {
            rng.range(0.0, cutoff as f64 * 1.2)
        } else {
            cutoff as f64 + rng.range(-1e-6, 1e-6)
        };
        // The point lies along the beam at angle `theta` from the axis; its normal is the unit
        // direction back to the light.
        let beam = rng.at_angle(spot.axis(), theta);
        let p = beam * rng.range(0.5, 20.0) as f32;
        for k in 0..3 {
            pos[k][i] = p[k];
            nor[k][i] = -beam[k];
        }
    }
    let material = Material::try_new(Vec3::ZERO, Vec3::ONE, Vec3::ZERO, 1.0).unwrap();
    let lights = [spot];
    let scene = phong::Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::Infinite(Vec3::Z),
    };
    let mut o = [[0f32; BATCH_SPOT_POINTS]; 3];
    let [ox, oy, oz] = &mut o;
    phong::shade_batch_with_level(
        level,
        &Lambert::default(),
        &material,
        &scene,
        phong::SoaVec3::new(&pos[0], &pos[1], &pos[2]),
        phong::SoaVec3::new(&nor[0], &nor[1], &nor[2]),
        phong::SoaRgb::new(ox, oy, oz),
    )
    .expect("a supported level");
    let cos_cutoff = spot.cos_cutoff() as f64;
    for i in 0..BATCH_SPOT_POINTS {
        let p = DVec3::new(pos[0][i] as f64, pos[1][i] as f64, pos[2][i] as f64);
        let nv = DVec3::new(nor[0][i] as f64, nor[1][i] as f64, nor[2][i] as f64).normalize();
        let l = -p.normalize();
        let c = -l.dot(r::d3(spot.axis()));
        let got = o[0][i];
        let factor = if (c - cos_cutoff).abs() <= SPOT_EDGE_BAND {
            // Either side of the edge is right here (see the `SpotLight::spot_factor` rows).
            if got == 0.0 {
                0.0
            } else {
                r::lobe_pow(c, e as f64)
            }
        } else {
            r::spot_factor(l, r::d3(spot.axis()), cos_cutoff, e as f64)
        };
        let want = factor * nv.dot(l).max(0.0);
        s.scalar(got, want, BATCH_SPOT_FLOOR, || {
            format!("{level}: axis = {axis:?}, cutoff = {cutoff}, e = {e}, p = {p:?}")
        });
        // The three channels are the same operations on the same values.
        assert!(o[1][i] == got && o[2][i] == got, "grey light, grey result");
    }
}

fn lobes(n: usize, out: &mut Vec<Row>) {
    type Gen = fn(&mut Rng) -> (Vec3, Vec3, Vec3);
    let domains: [(&str, &str, Gen, u64, bool); 4] = [
        (
            ORD,
            "unit N; L, V in its hemisphere; s in [1, 256]",
            hemisphere_triple,
            30,
            false,
        ),
        (
            ADV,
            "L, V grazing (1e-4…1e-1 rad above the plane); s in [0, 1e4]",
            grazing_triple,
            31,
            true,
        ),
        (
            ADV,
            "L grazing, V within 1e-6…1e-2 rad of R (the highlight); s in [0, 1e4]",
            grazing_highlight,
            32,
            true,
        ),
        (
            ADV,
            "L, V nearly opposite (V = −L turned by 1e-7…1e-1 rad), N random; s in [0, 1e4]",
            |rng: &mut Rng| {
                let (l, v) = near_opposite(rng);
                // A normal with N·L > 0 so the step gate lets the lobe through.
                let mut nn = rng.unit_vec3();
                if nn.dot(l) < 0.0 {
                    nn = -nn;
                }
                (nn, l, v)
            },
            33,
            true,
        ),
    ];
    // The specular lobes measured against the reference, in the order of the table's rows 2..8.
    let lobe_models: [Model; 6] = [
        Phong::default().into(),
        BlinnPhong::default().into(),
        Phong {
            normalization: Normalization::Energy,
            ..Phong::default()
        }
        .into(),
        BlinnPhong {
            normalization: Normalization::Energy,
            ..BlinnPhong::default()
        }
        .into(),
        BlinnPhong {
            normalization: Normalization::EnergyExact,
            ..BlinnPhong::default()
        }
        .into(),
        Phong {
            pow: PowStrategy::Squaring,
            ..Phong::default()
        }
        .into(),
    ];
    for (kind, domain, gen_, seed, wide) in domains {
        let mut rng = Rng::new(seed);
        let mut st: [Stats; 12] = Default::default();
        for _ in 0..n {
            let (nn, l, v) = gen_(&mut rng);
            let s = if wide {
                wide_shininess(&mut rng)
            } else {
                typical_shininess(&mut rng)
            };
            let (dn, dl, dv) = (r::d3(nn), r::d3(l), r::d3(v));
            let g = Incidence::new(nn, l, v);
            let input = || format!("n = {nn:?}, l = {l:?}, v = {v:?}, s = {s}");
            let sd = s as f64;
            // The cosines.
            let rv = r::reflect(dn, dl).dot(dv).clamp(-1.0, 1.0);
            st[0].scalar(g.r_dot_v(), rv, 1e-30, input);
            let h = r::halfway(dl, dv);
            let nh = dn.dot(h).max(0.0);
            st[1].scalar(g.n_dot_h_squared(), nh * nh, 1e-30, input);
            // The lobes, rows 2..8 in the order of `lobe_models`.
            for (k, m) in lobe_models.iter().enumerate() {
                let want = match m {
                    Model::Phong(p) => r::phong_specular(p, dn, dl, dv, sd),
                    Model::BlinnPhong(b) => r::blinn_specular(b, dn, dl, dv, sd),
                    Model::Lambert(_) => unreachable!("lobe_models has no Lambert"),
                };
                st[2 + k].scalar(m.specular(&g, s), want, LOBE_FLUSH, input);
            }
            let lam = Lambert::default();
            st[8].scalar(
                lam.diffuse(&g),
                r::diffuse(Normalization::None, dn.dot(dl)),
                1e-30,
                input,
            );
            // Naive GLSL-style code on the same vectors, step-gated like the default models.
            let gate = if nn.dot(l) > 0.0 { 1.0 } else { 0.0 };
            let naive_phong = (-l).reflect(nn).dot(v).max(0.0).powf(s) * gate;
            st[9].scalar(
                naive_phong,
                r::phong_specular(&Phong::default(), dn, dl, dv, sd),
                1e-30,
                input,
            );
            let naive_blinn = nn.dot((l + v).normalize()).max(0.0).powf(s) * gate;
            st[10].scalar(
                naive_blinn,
                r::blinn_specular(&BlinnPhong::default(), dn, dl, dv, sd),
                1e-30,
                input,
            );
            // The vector form of Blinn's lobe with the crate's own pieces (halfway, then pow).
            let vec_blinn = PowStrategy::Exact.lobe(nn.dot(phong::halfway_or_zero(l, v)), s) * gate;
            st[11].scalar(
                vec_blinn,
                r::blinn_specular(&BlinnPhong::default(), dn, dl, dv, sd),
                1e-30,
                input,
            );
        }
        let names = [
            "Incidence::r_dot_v",
            "Incidence::n_dot_h_squared",
            "Phong specular",
            "BlinnPhong specular",
            "Phong specular, Energy",
            "BlinnPhong specular, Energy",
            "BlinnPhong specular, EnergyExact",
            "Phong specular, PowStrategy::Squaring",
            "Lambert diffuse",
            "naive: pow(max(dot(reflect(−L,N),V),0),s)",
            "naive: pow(max(dot(N,normalize(L+V)),0),s)",
            "vector form: lobe(N·halfway(L,V), s)",
        ];
        for (i, s) in st.into_iter().enumerate() {
            let floor = if (2..8).contains(&i) {
                LOBE_FLUSH
            } else {
                1e-30
            };
            out.push(row(names[i], kind, domain, false, floor, s));
        }
    }

    // Normalisation factors and the pow strategies, on their own.
    {
        let mut rng = Rng::new(34);
        let mut st: [Stats; 6] = Default::default();
        let phong_energy = ResolvedModel::from(Phong {
            normalization: Normalization::Energy,
            ..Phong::default()
        });
        let blinn = |normalization| {
            ResolvedModel::from(BlinnPhong {
                normalization,
                ..BlinnPhong::default()
            })
        };
        let (blinn_energy, blinn_exact) = (
            blinn(Normalization::Energy),
            blinn(Normalization::EnergyExact),
        );
        for _ in 0..n {
            let s = if rng.chance(0.05) {
                0.0
            } else {
                rng.log_range(1e-3, 1e4) as f32
            };
            let sd = s as f64;
            let input = || format!("s = {s}");
            st[0].scalar(
                phong_energy.specular_scale(s),
                r::phong_factor(Normalization::Energy, sd),
                1e-30,
                input,
            );
            st[1].scalar(
                blinn_energy.specular_scale(s),
                r::blinn_factor(Normalization::Energy, sd),
                1e-30,
                input,
            );
            st[2].scalar(
                blinn_exact.specular_scale(s),
                r::blinn_factor(Normalization::EnergyExact, sd),
                1e-30,
                input,
            );
            let x = rng.range(0.0, 1.0) as f32;
            let si = s.round();
            let input = || format!("x = {x}, s = {s}");
            st[3].scalar(
                PowStrategy::Exact.lobe(x, s),
                r::lobe_pow(x as f64, sd),
                1e-30,
                input,
            );
            let input = || format!("x = {x}, s = {si}");
            st[4].scalar(
                PowStrategy::Squaring.lobe(x, si),
                r::lobe_pow(x as f64, si as f64),
                SQUARING_FLUSH,
                input,
            );
            let nl = rng.range(-1.0, 1.0) as f32;
            st[5].scalar(
                phong_energy.diffuse(nl),
                r::diffuse(Normalization::Energy, nl as f64),
                1e-30,
                || format!("n·l = {nl}"),
            );
        }
        let d = "s in [0, 1e4] (log-uniform, 0 now and then); x in [0, 1]";
        let names = [
            "ResolvedModel::specular_scale, Phong, Energy",
            "ResolvedModel::specular_scale, Blinn-Phong, Energy",
            "ResolvedModel::specular_scale, Blinn-Phong, EnergyExact",
            "PowStrategy::Exact.lobe",
            "PowStrategy::Squaring.lobe (integer s)",
            "ResolvedModel::diffuse, Energy (1/π)",
        ];
        for (i, s) in st.into_iter().enumerate() {
            let floor = if i == 4 { SQUARING_FLUSH } else { 1e-30 };
            out.push(row(names[i], ADV, d, true, floor, s));
        }
    }
}

fn colour_rows(n: usize, out: &mut Vec<Row>) {
    for (kind, domain, seed) in [
        (ORD, "x uniform in [0, 1]", 40u64),
        (
            ADV,
            "x log-uniform in [1e-30, 1e3], and around the knees ±1e-6",
            41,
        ),
    ] {
        let mut rng = Rng::new(seed);
        let mut st: [Stats; 4] = Default::default();
        for _ in 0..n {
            let x = if kind == ORD {
                rng.unit()
            } else if rng.chance(0.3) {
                [0.003_130_8, 0.040_45][rng.below(2)] + rng.range(-1e-6, 1e-6)
            } else {
                rng.log_range(1e-30, 1e3)
            } as f32;
            let xd = x as f64;
            let input = || format!("x = {x:?}");
            st[0].scalar(phong::srgb_encode(x), r::srgb_encode(xd), 1e-30, input);
            st[1].scalar(phong::srgb_decode(x), r::srgb_decode(xd), 1e-30, input);
            let gamma = if kind == ORD {
                2.2
            } else {
                rng.range(0.5, 3.0) as f32
            };
            let input = || format!("x = {x:?}, gamma = {gamma}");
            st[2].scalar(
                phong::gamma_encode(x, gamma),
                r::gamma_encode(xd, gamma as f64),
                1e-30,
                input,
            );
            st[3].scalar(
                phong::gamma_decode(x, gamma),
                r::gamma_decode(xd, gamma as f64),
                1e-30,
                input,
            );
        }
        let names = ["srgb_encode", "srgb_decode", "gamma_encode", "gamma_decode"];
        for (i, s) in st.into_iter().enumerate() {
            out.push(row(names[i], kind, domain, true, 1e-30, s));
        }
    }
    // linear_to_srgb8: 8-bit levels differing from the reference quantisation (error in levels).
    {
        let mut rng = Rng::new(42);
        let mut s = Stats::default();
        for _ in 0..n {
            let c = Vec3::new(rng.unit() as f32, rng.unit() as f32, rng.unit() as f32);
            let a = phong::linear_to_srgb8(c);
            let b = r::linear_to_srgb8(r::d3(c));
            for i in 0..3 {
                s.scalar(a[i] as f32, b[i] as f64, 1.0, || format!("c = {c:?}"));
            }
        }
        out.push(row(
            "linear_to_srgb8 (levels)",
            ORD,
            "linear channels uniform in [0, 1]",
            false,
            1.0,
            s,
        ));
    }
}

// ---------------------------------------------------------------------------------------------
// The 4× exponent rule

/// Phong's lobe `cos(θ)^s` against Blinn-Phong's `cos(θ/2)^(4s)` with `V` turned from `R` by `θ`
/// in the plane of incidence (where `angle(N, H) = θ/2` exactly): the largest absolute
/// difference over `θ ∈ [0, π/2]`, in `f64`, and the second-order prediction `e⁻²/s`.
pub fn four_times_rule_in_plane(s: f64) -> (f64, f64) {
    let mut worst: f64 = 0.0;
    let steps = 20_000;
    for i in 0..=steps {
        let t = core::f64::consts::FRAC_PI_2 * i as f64 / steps as f64;
        let phong = t.cos().max(0.0).powf(s);
        let blinn = (t / 2.0).cos().powf(4.0 * s);
        worst = worst.max((phong - blinn).abs());
    }
    (worst, (-2.0f64).exp() / s)
}

/// The same comparison with the crate's own `f32` lobes on actual vectors: `L` at incidence
/// `theta_i`, `V` turned from `R` by `θ` in the plane of incidence.
pub fn four_times_rule_crate(s: f32, theta_i: f64) -> f64 {
    let n = Vec3::Z;
    let l = DVec3::new(theta_i.sin(), 0.0, theta_i.cos());
    let mut worst: f64 = 0.0;
    let steps = 4000;
    for i in 0..=steps {
        let t = (core::f64::consts::FRAC_PI_2 - 0.01) * i as f64 / steps as f64;
        // R is at −θi in the xz-plane; V at −θi + t stays above the surface for θi ≥ 0.
        let a = -theta_i + t;
        let v = DVec3::new(a.sin(), 0.0, a.cos());
        let g = Incidence::new(n, l.as_vec3(), v.as_vec3());
        let p = Phong::default().specular(&g, s) as f64;
        let b = BlinnPhong::default().specular(&g, 4.0 * s) as f64;
        worst = worst.max((p - b).abs());
    }
    worst
}

/// The exponent ratio `s_Blinn / s_Phong` that makes both lobes fall to one half at the same
/// deviation `δ` of `V` from `R`, for `L` at incidence `theta_i`, with `V` turned in the plane of
/// incidence (`in_plane`) or perpendicular to it. Second order predicts 4 and `4 cos²θi`.
pub fn matching_ratio(s: f64, theta_i: f64, in_plane: bool) -> f64 {
    let n = DVec3::Z;
    let l = DVec3::new(theta_i.sin(), 0.0, theta_i.cos());
    let rr = r::reflect(n, l);
    // Phong falls to 1/2 where cos δ = 2^(−1/s).
    let delta = 0.5f64.powf(1.0 / s).acos();
    let axis = if in_plane {
        DVec3::Y // turning about y keeps V in the xz-plane of incidence
    } else {
        rr.cross(DVec3::Y).normalize() // turning about this axis moves V out of the plane
    };
    let v = glam::DQuat::from_axis_angle(axis, delta) * rr;
    let nh = n.dot(r::halfway(l, v));
    (0.5f64.ln() / nh.ln()) / s
}
