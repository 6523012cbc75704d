//! Every public function on adversarial input, each result checked against the promise its docs
//! make: a long-running fuzz campaign that CI runs briefly.
//!
//! ```text
//! cargo test --test fuzz_promises                       # CI: a short run (PHONG_FUZZ_EVALS default)
//! PHONG_FUZZ_EVALS=1000000000 cargo test --release --test fuzz_promises -- --nocapture
//! ```
//!
//! `PHONG_FUZZ_EVALS` is the number of public-function evaluations (a batch call counts one per
//! lane), split over `PHONG_FUZZ_THREADS` threads (default: every core), and `PHONG_FUZZ_SEED`
//! picks the inputs (default fixed, so a CI failure reproduces). The run prints, per function, how
//! many evaluations it made, and fails listing the first violations with their inputs.
//!
//! Inputs are biased to the classes where methods fail: zero, subnormal, tiny, huge (up to
//! `f32::MAX`), nearly parallel and nearly opposite vectors, slivers, singular matrices, grazing
//! angles, shininess ≤ 1 and huge, a light or viewer at the shaded point. Parameters go through the
//! checked constructors (so only documented-valid values reach shading), and in release builds also
//! through the unchecked ones with arbitrary values, which must sanitise.
//!
//! The promises checked (each from the item's docs): no NaN and no panic anywhere; unit-or-zero
//! directions; `face_forward` returns `±N`; the zero-direction cases; attenuation finite, `≥ 0` and
//! non-increasing; `cull_radius` never NaN and `≥ 0`; lobes finite, `≥ 0`, at most 1 unless
//! energy-normalised, 0 for a missing direction; `PowStrategy::lobe` within
//! `max_relative_error`; every shading term finite and `≥ 0`; the batch path inside its documented
//! range at every dispatch level, its 8-bit frame that output encoded (alpha 255), and the
//! array-of-structs entry point that output bit for bit;
//! colour conversions finite and in range.

use phong_tools::batch_range;
use phong_tools::{models, rng};

use std::collections::BTreeMap;
use std::sync::Mutex;
use std::time::Instant;

use glam::{Mat3, Vec3};
use phong::{
    Attenuation, BlinnPhong, DirectionalLight, GBuffer, Incidence, Level, Light, LightColors,
    Material, Model, Normalization, Phong, PointLight, PowStrategy, ReflectionModel, Scene, Shader,
    SoaRgb, SoaSurface, SoaVec3, SpecularGate, SpotCone, SpotLight, Surface, TileCulling, Viewer,
};

/// `v` rounded to `f32` with each component saturated to `±f32::MAX`: the generators' arithmetic
/// on huge inputs must stay finite, since the promises are made for finite input.
fn fin(v: glam::DVec3) -> Vec3 {
    v.clamp(
        glam::DVec3::splat(-(f32::MAX as f64)),
        glam::DVec3::splat(f32::MAX as f64),
    )
    .as_vec3()
}

/// `a + b · k` computed in `f64` and saturated (see [`fin`]).
fn offset(a: Vec3, b: Vec3, k: f32) -> Vec3 {
    fin(a.as_dvec3() + b.as_dvec3() * k as f64)
}

/// The tests' SplitMix64 (every stream reproducible from its seed), with the campaign's own
/// adversarial generators on top.
struct Rng(rng::Rng);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0.next_u64()
    }
    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }
    fn unit_f32(&mut self) -> f32 {
        self.0.unit_f32()
    }
    fn range(&mut self, lo: f32, hi: f32) -> f32 {
        self.0.range_f32(lo, hi)
    }
    fn coin(&mut self) -> bool {
        self.next() & 1 == 1
    }
    /// A magnitude `2^e · m` with `e` uniform in `[lo, hi]`.
    fn log_uniform(&mut self, lo: i32, hi: i32) -> f32 {
        let e = lo + self.below((hi - lo + 1) as u64) as i32;
        let m = 1.0 + self.unit_f32();
        let x = (m as f64) * 2f64.powi(e);
        x.min(f32::MAX as f64) as f32
    }
    /// A finite `f32` from one of the hard classes, either sign.
    fn hard(&mut self) -> f32 {
        let x = match self.below(10) {
            0 => 0.0,
            1 => f32::from_bits(1 + self.below(0x007f_ffff) as u32), // subnormal
            2 => self.log_uniform(-126, -60),                        // tiny
            3 => self.log_uniform(60, 127),                          // huge
            4 => f32::MAX,
            5 => f32::MIN_POSITIVE,
            6 => {
                // any finite bit pattern
                loop {
                    let x = f32::from_bits(self.next() as u32);
                    if x.is_finite() {
                        break x.abs();
                    }
                }
            }
            _ => self.range(0.0, 4.0),
        };
        if self.coin() { -x } else { x }
    }
    /// A finite, non-negative `f32` from the hard classes: a valid colour or coefficient.
    fn hard_nonneg(&mut self) -> f32 {
        self.hard().abs()
    }
    fn unit(&mut self) -> Vec3 {
        loop {
            let v = Vec3::new(
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
            );
            let l = v.length_squared();
            if l > 1e-3 && l <= 1.0 {
                return v / l.sqrt();
            }
        }
    }
    /// A vector from the hard classes: hard components, a scaled unit vector at a hard length, or
    /// zero.
    fn hard_vec(&mut self) -> Vec3 {
        match self.below(4) {
            0 => Vec3::new(self.hard(), self.hard(), self.hard()),
            1 => Vec3::ZERO,
            2 => self.unit() * self.hard_nonneg(),
            _ => self.unit() * self.range(0.01, 10.0),
        }
    }
    /// A vector nearly parallel (or, by coin, nearly opposite) to `v`: `±v` plus a tiny turn.
    fn near(&mut self, v: Vec3) -> Vec3 {
        let eps = self.log_uniform(-40, -3);
        let w = offset(v, self.unit(), eps * phong::length(v));
        if self.coin() { -w } else { w }
    }
    /// A unit (or zero) direction for the lobe functions, often grazing or opposite `other`.
    fn direction(&mut self, other: Vec3) -> Vec3 {
        match self.below(6) {
            0 => Vec3::ZERO,
            1 | 2 => phong::normalize_or_zero(self.near(other)),
            _ => self.unit(),
        }
    }
    fn shininess(&mut self) -> f32 {
        match self.below(6) {
            0 => 0.0,
            1 => self.range(0.0, 1.0),
            2 => self.hard_nonneg(),
            3 => self.below(2048) as f32,
            _ => self.range(1.0, 256.0),
        }
    }
    fn colour(&mut self) -> Vec3 {
        if self.below(4) == 0 {
            Vec3::new(self.hard_nonneg(), self.hard_nonneg(), self.hard_nonneg())
        } else {
            Vec3::new(self.unit_f32(), self.unit_f32(), self.unit_f32())
        }
    }
    fn attenuation(&mut self) -> Attenuation {
        let pos = |r: &mut Rng| loop {
            let x = r.hard_nonneg();
            if x >= f32::MIN_POSITIVE {
                break x;
            }
        };
        let a = match self.below(5) {
            0 => Attenuation::None,
            1 => Attenuation::Polynomial {
                constant: if self.coin() { 1.0 } else { self.hard_nonneg() },
                linear: self.hard_nonneg(),
                quadratic: self.hard_nonneg(),
            },
            2 => Attenuation::InverseSquare {
                power: self.hard_nonneg(),
                min_distance: pos(self),
            },
            3 => Attenuation::Unreal { radius: pos(self) },
            _ => Attenuation::Frostbite {
                radius: pos(self),
                min_distance: pos(self),
            },
        };
        a.validated().unwrap_or(Attenuation::None)
    }
    fn light_colors(&mut self) -> LightColors {
        LightColors::try_new(self.colour(), self.colour(), self.colour()).unwrap()
    }
    fn light(&mut self, near: Vec3) -> Light {
        let colors = self.light_colors();
        let position = match self.below(4) {
            0 => near, // at the shaded point
            1 => {
                let (u, k) = (self.unit(), self.log_uniform(-30, 0));
                offset(near, u, k)
            }
            _ => self.hard_vec(),
        };
        match self.below(3) {
            0 => DirectionalLight::try_new(self.hard_vec(), colors)
                .map(Light::from)
                .unwrap_or_else(|_| DirectionalLight::try_new(Vec3::Z, colors).unwrap().into()),
            1 => PointLight::try_new(position, self.attenuation(), colors)
                .unwrap()
                .into(),
            _ => {
                let cone = SpotCone {
                    cutoff: if self.below(8) == 0 {
                        core::f32::consts::PI
                    } else {
                        self.range(0.0, core::f32::consts::FRAC_PI_2)
                    },
                    exponent: self.shininess(),
                };
                SpotLight::try_with_cone(position, self.unit(), cone, self.attenuation(), colors)
                    .unwrap()
                    .into()
            }
        }
    }
    fn pow(&mut self) -> PowStrategy {
        let all: Vec<PowStrategy> = PowStrategy::ALL
            .iter()
            .copied()
            .chain([PowStrategy::Auto])
            .collect();
        all[self.below(all.len() as u64) as usize]
    }
    fn model(&mut self) -> Model {
        let gate =
            [SpecularGate::Step, SpecularGate::Cosine, SpecularGate::None][self.below(3) as usize];
        let normalization = [
            Normalization::None,
            Normalization::Energy,
            Normalization::EnergyExact,
        ][self.below(3) as usize];
        let pow = self.pow();
        // Lambert takes the drawn normalisation too (it used to be Lambert::default() only).
        models::assemble(self.below(3) as usize, gate, normalization, pow)
    }
    fn material(&mut self) -> Material {
        Material::try_new(
            self.colour(),
            self.colour(),
            self.colour(),
            self.shininess(),
        )
        .unwrap()
    }
}

/// Evaluation counts per function and the first violations, shared by the threads.
#[derive(Default)]
struct Log {
    counts: BTreeMap<&'static str, u64>,
    violations: Vec<String>,
    total_violations: u64,
}

/// One thread's view: local counts, flushed into the shared log at the end.
struct Check {
    counts: BTreeMap<&'static str, u64>,
    violations: Vec<String>,
    total_violations: u64,
}

impl Check {
    fn new() -> Self {
        Check {
            counts: BTreeMap::new(),
            violations: Vec::new(),
            total_violations: 0,
        }
    }
    fn count(&mut self, f: &'static str, n: u64) {
        *self.counts.entry(f).or_default() += n;
    }
    fn total(&self) -> u64 {
        self.counts.values().sum()
    }
    /// Records a violation of `f`'s promise unless `ok`.
    fn expect(&mut self, f: &'static str, ok: bool, what: impl FnOnce() -> String) {
        if !ok {
            self.total_violations += 1;
            if self.violations.len() < 20 || std::env::var_os("PHONG_FUZZ_ALL").is_some() {
                self.violations.push(format!("{f}: {}", what()));
            }
        }
    }
}

fn finite_nonneg(c: Vec3) -> bool {
    c.is_finite() && c.min_element() >= 0.0
}

fn unit_or_zero(v: Vec3) -> bool {
    // The crate's normalisations are exact to a few ulps (normalize_or_zero's docs).
    v.is_finite() && (v == Vec3::ZERO || (v.as_dvec3().length() - 1.0).abs() <= 4e-7)
}

fn geometry(r: &mut Rng, c: &mut Check) {
    let v = r.hard_vec();
    let n = phong::normalize_or_zero(v);
    c.count("normalize_or_zero", 1);
    c.expect(
        "normalize_or_zero",
        unit_or_zero(n) && ((n == Vec3::ZERO) == (v == Vec3::ZERO)),
        || format!("{v:?} -> {n:?}"),
    );

    let len = phong::length(v);
    let exact = v.as_dvec3().length().min(f32::MAX as f64);
    c.count("length", 1);
    c.expect(
        "length",
        // A few ulps relative, or half a subnormal step absolute when the length is subnormal.
        len.is_finite() && ((len as f64) - exact).abs() <= 2.5e-7 * exact + 2f64.powi(-150),
        || format!("{v:?} -> {len} (exact {exact})"),
    );

    let unit_n = r.unit();
    let l = if r.coin() {
        r.hard_vec()
    } else {
        r.near(unit_n)
    };
    let refl = phong::reflect(unit_n, l);
    c.count("reflect", 1);
    c.expect(
        "reflect",
        refl.is_finite() && (l != Vec3::ZERO || refl == Vec3::ZERO),
        || format!("reflect({unit_n:?}, {l:?}) = {refl:?}"),
    );

    let a = r.direction(Vec3::Z);
    let b = r.direction(a);
    let h = phong::halfway_or_zero(a, b);
    c.count("halfway_or_zero", 1);
    c.expect("halfway_or_zero", unit_or_zero(h), || {
        format!("halfway({a:?}, {b:?}) = {h:?}")
    });

    let nn = r.hard_vec();
    let vv = r.hard_vec();
    let nref = if r.coin() { r.hard_vec() } else { r.near(vv) };
    let ff = phong::face_forward(nn, vv, nref);
    c.count("face_forward", 1);
    c.expect("face_forward", ff == nn || ff == -nn, || {
        format!("face_forward({nn:?}, {vv:?}, {nref:?}) = {ff:?}")
    });

    // Triangles: random, slivers (a third vertex near the line of the other two) and repeats.
    let p0 = r.hard_vec();
    let p1 = if r.coin() { r.hard_vec() } else { r.near(p0) };
    let p2 = match r.below(3) {
        0 => r.hard_vec(),
        1 => {
            let (k, u, e) = (r.range(-2.0, 2.0), r.unit(), r.log_uniform(-60, -10));
            let on_line = p0.as_dvec3() + (p1.as_dvec3() - p0.as_dvec3()) * k as f64;
            fin(on_line + u.as_dvec3() * e as f64)
        }
        _ => p1,
    };
    let area = phong::triangle_area_normal(p0, p1, p2);
    let tn = phong::triangle_normal_or_zero(p0, p1, p2);
    let ttn = phong::try_triangle_normal(p0, p1, p2);
    c.count("triangle_area_normal", 1);
    c.count("triangle_normal_or_zero", 1);
    c.count("try_triangle_normal", 1);
    c.expect("triangle_area_normal", !area.is_nan(), || {
        format!("({p0:?}, {p1:?}, {p2:?}) -> {area:?}")
    });
    c.expect(
        "triangle_normal_or_zero",
        unit_or_zero(tn) && ttn.unwrap_or(Vec3::ZERO) == tn,
        || format!("({p0:?}, {p1:?}, {p2:?}) -> {tn:?} / {ttn:?}"),
    );
    // The unit normal points along the area vector (its rounding of the same exact vector), unless
    // the area vector saturated or underflowed (its direction is then approximate, as documented).
    c.expect(
        "triangle_normal_or_zero",
        tn == Vec3::ZERO
            || area == Vec3::ZERO
            || area.abs().max_element() == f32::MAX
            || area.abs().max_element() < f32::MIN_POSITIVE
            || tn.dot(phong::normalize_or_zero(area)) > 0.999,
        || format!("({p0:?}, {p1:?}, {p2:?}): normal {tn:?} vs area {area:?}"),
    );

    // Normal matrices: random, singular (a column repeated or scaled) and huge.
    let c0 = r.hard_vec();
    let c1 = r.hard_vec();
    let c2 = match r.below(3) {
        0 => r.hard_vec(),
        1 => fin(c0.as_dvec3() * [2.0, -0.5, 1.0, 0.0][r.below(4) as usize]),
        _ => fin(c0.as_dvec3() + c1.as_dvec3()),
    };
    let m = Mat3::from_cols(c0, c1, c2);
    let nm = phong::normal_matrix(m);
    c.count("normal_matrix", 1);
    c.expect("normal_matrix", nm.is_finite(), || {
        format!("{m:?} -> {nm:?}")
    });
    let tn2 = phong::transform_normal(nm, r.hard_vec());
    c.count("transform_normal", 1);
    c.expect("transform_normal", unit_or_zero(tn2), || {
        format!("{nm:?} -> {tn2:?}")
    });
}

fn mesh(r: &mut Rng, c: &mut Check) {
    let k = 3 + r.below(6) as usize;
    let positions: Vec<Vec3> = (0..k).map(|_| r.hard_vec()).collect();
    let triangles: Vec<[u32; 3]> = (0..k)
        .map(|_| [0, 1, 2].map(|_| r.below(k as u64) as u32))
        .collect();
    let mut normals = vec![Vec3::NAN; k];
    phong::vertex_normals(&positions, &triangles, &mut normals);
    c.count("vertex_normals", 1);
    c.expect(
        "vertex_normals",
        normals.iter().all(|n| unit_or_zero(*n)),
        || format!("{positions:?} {triangles:?} -> {normals:?}"),
    );
}

fn attenuation(r: &mut Rng, c: &mut Check) {
    let a = r.attenuation();
    let d1 = r.hard_nonneg();
    let d2 = if r.coin() {
        r.hard_nonneg()
    } else {
        d1 * r.range(1.0, 2.0)
    };
    let (lo, hi) = if d1 <= d2 { (d1, d2) } else { (d2, d1) };
    let (f_lo, f_hi) = (a.factor(lo), a.factor(hi));
    c.count("Attenuation::factor", 2);
    c.expect(
        "Attenuation::factor",
        f_lo.is_finite() && f_hi.is_finite() && f_lo >= 0.0 && f_hi >= 0.0,
        || format!("{a:?}: factor({lo}) = {f_lo}, factor({hi}) = {f_hi}"),
    );
    // Non-increasing: exactly for the monotone forms; within the windowed forms' rounding
    // (relative 2⁻¹⁹) for Unreal and Frostbite.
    let slack = match a {
        Attenuation::Unreal { .. } | Attenuation::Frostbite { .. } => 1.0 + 2f32.powi(-19),
        _ => 1.0,
    };
    c.expect("Attenuation::factor", f_hi <= f_lo * slack, || {
        format!("{a:?}: factor({lo}) = {f_lo} < factor({hi}) = {f_hi}")
    });
    let t = match r.below(3) {
        0 => a.factor(r.hard_nonneg()),
        1 => r.hard_nonneg(),
        _ => r.log_uniform(-40, 0),
    };
    let radius = a.cull_radius(t);
    c.count("Attenuation::cull_radius", 1);
    c.expect("Attenuation::cull_radius", radius >= 0.0, || {
        format!("{a:?}.cull_radius({t}) = {radius}")
    });
    // Safe: past the radius the factor is below the threshold (checked just past it and at a
    // random farther distance).
    if radius.is_finite() && t > 0.0 {
        let just_past = radius.next_up();
        let farther = (radius as f64 * (1.0 + r.unit_f32() as f64 * 4.0) + 1e-30) as f32;
        let (f1, f2) = (a.factor(just_past), a.factor(farther.max(just_past)));
        c.expect("Attenuation::cull_radius", f1 < t && f2 < t, || {
            format!("{a:?}.cull_radius({t}) = {radius}, but factor({just_past}) = {f1}, factor({farther}) = {f2}")
        });
    }
}

fn lobes(r: &mut Rng, c: &mut Check) {
    let around = r.unit();
    let n = r.direction(around);
    let l = r.direction(n);
    let toward = if r.coin() { l } else { n };
    let v = r.direction(toward);
    let g = Incidence::new(n, l, v);
    let model = r.model();
    let s = r.shininess();
    let (wd, ws) = (model.diffuse(&g), model.specular(&g, s));
    c.count("ReflectionModel::diffuse", 1);
    c.count("ReflectionModel::specular", 1);
    let normalized = !matches!(
        model,
        Model::Phong(Phong {
            normalization: Normalization::None,
            ..
        }) | Model::BlinnPhong(BlinnPhong {
            normalization: Normalization::None,
            ..
        }) | Model::Lambert(_)
    );
    // The cosines of unit vectors may exceed 1 by their rounding (a few ulps), and so may a lobe.
    let one = 1.0 + 4.0 * f32::EPSILON;
    let cap = if normalized { f32::MAX } else { one };
    c.expect(
        "ReflectionModel::diffuse",
        wd.is_finite() && (0.0..=one).contains(&wd),
        || format!("{model:?} {g:?} -> {wd}"),
    );
    c.expect(
        "ReflectionModel::specular",
        ws.is_finite() && (0.0..=cap).contains(&ws),
        || format!("{model:?} s={s} {g:?} -> {ws}"),
    );
    c.expect(
        "ReflectionModel::specular",
        (n != Vec3::ZERO && l != Vec3::ZERO && v != Vec3::ZERO) || ws == 0.0,
        || format!("{model:?}: a missing direction lit a lobe: {n:?} {l:?} {v:?} -> {ws}"),
    );

    // The pow strategies against their stated bound, on the lobe's domain.
    let p = r.pow();
    let x = match r.below(4) {
        0 => r.range(-2.0, 2.0),
        1 => 1.0 - r.log_uniform(-24, -1),
        2 => r.log_uniform(-126, 0).min(1.0),
        _ => r.unit_f32(),
    };
    let y = p.lobe(x, s);
    c.count("PowStrategy::lobe", 1);
    let exact = if x > 0.0 {
        (x.min(1.0) as f64).powf(s as f64)
    } else {
        0.0
    };
    let err = (y as f64 - exact).abs() / exact.max(PowStrategy::ERROR_FLOOR as f64);
    c.expect(
        "PowStrategy::lobe",
        y.is_finite() && (0.0..=1.0).contains(&y) && err <= p.max_relative_error() as f64,
        || format!("{p:?}.lobe({x}, {s}) = {y}, exact {exact}, err {err:e}"),
    );
}

fn colour(r: &mut Rng, c: &mut Check) {
    let x = r.hard();
    let e = phong::srgb_encode(x);
    let d = phong::srgb_decode(x);
    let gamma = r.range(0.1, 4.0);
    let ge = phong::gamma_encode(x, gamma);
    let gd = phong::gamma_decode(x, gamma);
    c.count("srgb_encode", 1);
    c.count("srgb_decode", 1);
    c.count("gamma_encode", 1);
    c.count("gamma_decode", 1);
    c.expect(
        "srgb_encode",
        e.is_finite() && (x < 0.0 || e >= 0.0),
        || format!("{x} -> {e}"),
    );
    c.expect(
        "srgb_decode",
        d.is_finite() && (x < 0.0 || d >= 0.0),
        || format!("{x} -> {d}"),
    );
    c.expect("gamma_encode", ge.is_finite() && ge >= 0.0, || {
        format!("({x}, {gamma}) -> {ge}")
    });
    c.expect("gamma_decode", gd.is_finite() && gd >= 0.0, || {
        format!("({x}, {gamma}) -> {gd}")
    });
    let rgb = Vec3::new(r.hard(), r.hard(), r.hard());
    let s = phong::saturate(rgb);
    c.count("saturate", 1);
    c.expect(
        "saturate",
        s.is_finite() && s.min_element() >= 0.0 && s.max_element() <= 1.0,
        || format!("{rgb:?} -> {s:?}"),
    );
    let _ = phong::linear_to_srgb8(rgb);
    let _ = phong::quantize_u8(x);
    c.count("linear_to_srgb8", 1);
    c.count("quantize_u8", 1);
}

/// The rest of the public surface: the checked constructors (an `Ok` is always a valid value, an
/// `Err` never a panic), the `try_` twins of the total functions, the cosine-form incidence, the
/// per-point surface helpers, the spot factor, the GPU mirrors and the `Terms` algebra.
fn rest(r: &mut Rng, c: &mut Check) {
    let v = r.hard_vec();
    let tn = phong::try_normalize(v);
    c.count("try_normalize", 1);
    c.expect(
        "try_normalize",
        tn.map_or(phong::normalize_or_zero(v) == Vec3::ZERO, |u| {
            u == phong::normalize_or_zero(v) && unit_or_zero(u)
        }),
        || format!("{v:?} -> {tn:?}"),
    );
    let (a, b) = (r.direction(Vec3::Z), r.unit());
    let b = if r.coin() { -a } else { b };
    let th = phong::try_halfway(a, b);
    c.count("try_halfway", 1);
    c.expect(
        "try_halfway",
        th.map_or(phong::halfway_or_zero(a, b) == Vec3::ZERO, |h| {
            h == phong::halfway_or_zero(a, b)
        }),
        || format!("({a:?}, {b:?}) -> {th:?}"),
    );

    // Cosines of unit vectors, possibly inconsistent (the caller's own rounding).
    let (nl, nv, lv) = (r.range(-1.0, 1.0), r.range(-1.0, 1.0), r.range(-1.0, 1.0));
    let g = Incidence::from_cosines(nl, nv, lv);
    let (rv, nh) = (g.r_dot_v(), g.n_dot_h_squared());
    c.count("Incidence::from_cosines", 1);
    c.count("Incidence::r_dot_v", 1);
    c.count("Incidence::n_dot_h_squared", 1);
    c.expect(
        "Incidence::from_cosines",
        rv.is_finite() && (-1.0..=1.0).contains(&rv) && nh.is_finite() && (0.0..=1.0).contains(&nh),
        || format!("({nl}, {nv}, {lv}) -> R·V {rv}, (N·H)² {nh}"),
    );
    let (n, l, vv) = (r.hard_vec(), r.hard_vec(), r.hard_vec());
    let gu = Incidence::from_unnormalized(n, l, vv);
    c.count("Incidence::from_unnormalized", 1);
    c.expect(
        "Incidence::from_unnormalized",
        gu.n_dot_l.is_finite() && gu.n_dot_v.is_finite() && gu.r_dot_v().is_finite(),
        || format!("({n:?}, {l:?}, {vv:?}) -> {gu:?}"),
    );

    // Checked constructors on hard values: Ok only for values in the domain.
    let (x, y, z, w) = (r.hard(), r.hard(), r.hard(), r.hard());
    let m = Material::try_new(Vec3::new(x, y, z), Vec3::splat(y), Vec3::splat(z), w);
    let lc = LightColors::try_from_strengths(Vec3::new(x, y, z), w, y, z);
    let lp = LightColors::try_from_power(Vec3::new(x, y, z), w);
    let at = Attenuation::try_polynomial(x, y, z);
    let spot = SpotLight::try_with_cone(
        Vec3::new(x, y, z),
        r.hard_vec(),
        SpotCone {
            cutoff: r.hard(),
            exponent: r.hard(),
        },
        Attenuation::None,
        LightColors::BLACK,
    );
    c.count("checked constructors", 5);
    let colour_ok = |v: Vec3| v.is_finite() && v.min_element() >= 0.0;
    c.expect(
        "checked constructors",
        // An error names the material's field it rejects (the messages themselves are pinned
        // in tests/totality.rs).
        m.is_err_and(|e| e.to_string().starts_with("material."))
            || m.is_ok_and(|m| {
                colour_ok(m.ambient()) && colour_ok(m.diffuse()) && m.shininess() >= 0.0
            }),
        || format!("Material::try_new -> {m:?}"),
    );
    c.expect(
        "checked constructors",
        [lc, lp].iter().all(|l| {
            l.is_err()
                || l.is_ok_and(|l| {
                    colour_ok(l.ambient()) && colour_ok(l.diffuse()) && colour_ok(l.specular())
                })
        }),
        || format!("LightColors -> {lc:?} / {lp:?}"),
    );
    c.expect(
        "checked constructors",
        at.is_err() || at.is_ok_and(|a| a.validated() == Ok(a) && a.factor(1.0).is_finite()),
        || format!("Attenuation::try_polynomial({x}, {y}, {z}) -> {at:?}"),
    );
    c.expect(
        "checked constructors",
        spot.is_err()
            || spot.is_ok_and(|s| {
                let f = s.spot_factor(r.unit());
                (0.0..=1.0).contains(&f) && unit_or_zero(s.axis())
            }),
        || format!("SpotLight::try_with_cone -> {spot:?}"),
    );
    c.count("SpotLight::spot_factor", 1);

    // Per-point surfaces and material overrides stay in their domains.
    let base = r.material();
    let (dt, st) = (r.colour(), r.colour());
    let tex = base.textured(dt, st);
    let surf = Surface::textured(dt, st, r.shininess()).with_occlusion(r.unit_f32());
    c.count("Material::textured", 1);
    c.count("Surface::textured", 1);
    c.count("Surface::with_occlusion", 1);
    c.count("Surface::of", 1);
    c.expect(
        "Surface::textured",
        surf.is_valid() && Surface::of(&tex).is_valid() && colour_ok(tex.diffuse()),
        || format!("{base:?} {dt:?} {st:?} -> {tex:?}, {surf:?}"),
    );

    // Terms algebra: sums and scalings of valid terms stay valid (saturated, never NaN).
    let t1 = phong::Terms {
        ambient: r.colour(),
        diffuse: r.colour(),
        specular: r.colour(),
        emission: r.colour(),
    };
    let k = r.hard_nonneg();
    let mut t2 = t1 + t1 * k;
    t2 += t1;
    c.count("Terms ops", 3);
    c.expect(
        "Terms ops",
        colour_ok(t2.total()) && colour_ok(t2.ambient) && colour_ok(t2.specular),
        || format!("{t1:?} * {k} -> {t2:?}"),
    );

    // GPU mirrors of valid parameters are finite.
    let light = r.light(Vec3::ZERO);
    let gl = phong::gpu::GpuLight::from(&light);
    let gm = phong::gpu::GpuMaterial::from(&base);
    let model = r.model();
    let gp = phong::gpu::GpuParams::new(&model, Viewer::Infinite(r.unit()), r.colour(), 1);
    c.count("gpu mirrors", 3);
    let finite = |b: &[u8]| {
        b.chunks_exact(4)
            .all(|w| !f32::from_ne_bytes([w[0], w[1], w[2], w[3]]).is_nan())
    };
    c.expect(
        "gpu mirrors",
        finite(bytemuck::bytes_of(&gm)) && finite(bytemuck::bytes_of(&gp)) && gl.kind <= 2,
        || format!("{light:?} -> {gl:?}; {base:?} -> {gm:?}"),
    );
}

/// A random scene around the point `p`: 1–4 lights of every kind, a viewer at, near or far from
/// the point, or infinitely far.
fn scene_parts(r: &mut Rng, p: Vec3) -> (Vec<Light>, Vec3, Viewer) {
    let k = 1 + r.below(4) as usize;
    let lights = (0..k).map(|_| r.light(p)).collect();
    let ambient = if r.coin() { Vec3::ZERO } else { r.colour() };
    let viewer = match r.below(4) {
        0 => Viewer::At(p),
        1 => Viewer::Infinite(r.hard_vec()),
        2 => {
            let (u, k) = (r.unit(), r.log_uniform(-30, 4));
            Viewer::At(offset(p, u, k))
        }
        _ => Viewer::At(r.hard_vec()),
    };
    (lights, ambient, viewer)
}

fn shading(r: &mut Rng, c: &mut Check) {
    let p = if r.coin() {
        r.hard_vec()
    } else {
        r.unit() * r.range(0.0, 4.0)
    };
    let (lights, ambient, viewer) = scene_parts(r, p);
    let scene = Scene {
        lights: &lights,
        ambient,
        viewer,
    };
    let model = r.model();
    let material = r.material();
    let normal = r.hard_vec();
    let t = phong::shade(&model, &material, &scene, p, normal);
    c.count("shade", 1);
    let ok = |t: &phong::Terms| {
        finite_nonneg(t.ambient)
            && finite_nonneg(t.diffuse)
            && finite_nonneg(t.specular)
            && finite_nonneg(t.emission)
            && finite_nonneg(t.total())
    };
    c.expect("shade", ok(&t), || {
        format!("{model:?} {material:?} {lights:?} {viewer:?} p={p:?} n={normal:?} -> {t:?}")
    });
    // shade lies in the batch's documented range too (outside the overflow regime).
    let range = batch_range::range(&model, &material, &scene, p, normal);
    c.expect("shade", range.saturated || range.holds(t.total()), || {
        format!(
            "{model:?} {material:?} {lights:?} {viewer:?} p={p:?} n={normal:?} -> {} outside {range:?}",
            t.total()
        )
    });

    // The prepared shader: with one directional or point light it takes the straight-line
    // one-light path, whose full-range normalisation can differ from `shade`'s range test in
    // the last places where a squared length under- or overflows, so it is checked on its own
    // against the documented range, and shadowing is compared within the same shader.
    let shader = Shader::new(model, &material, &scene);
    let tu = shader.shade(p, normal);
    c.count("Shader::shade", 1);
    c.expect(
        "Shader::shade",
        ok(&tu) && (range.saturated || range.holds(tu.total())),
        || {
            format!(
                "{model:?} {material:?} {lights:?} {viewer:?} p={p:?} n={normal:?} -> {tu:?} outside {range:?}"
            )
        },
    );
    let t = tu;
    let vis: Vec<f32> = lights
        .iter()
        .map(|_| match r.below(3) {
            0 => 0.0,
            1 => 1.0,
            _ => r.unit_f32(),
        })
        .collect();
    let tv = shader.shade_visible(p, normal, vis.as_slice());
    c.count("Shader::shade_visible", 1);
    c.expect(
        "Shader::shade_visible",
        ok(&tv) && tv.ambient == t.ambient && tv.diffuse.cmple(t.diffuse * 1.000001).all(),
        || format!("vis {vis:?}: {tv:?} vs unshadowed {t:?}"),
    );
    let surface = Surface {
        ambient: r.colour(),
        diffuse: r.colour(),
        specular: r.colour(),
        shininess: r.shininess(),
    };
    let ts = shader.shade_surface(p, normal, &surface, vis.as_slice());
    c.count("Shader::shade_surface", 1);
    c.expect("Shader::shade_surface", ok(&ts), || {
        format!("{surface:?} -> {ts:?}")
    });
    let dir = r.hard_vec();
    let tr = shader.with_viewer(Viewer::along_ray(dir)).shade(p, normal);
    c.count("Shader::with_viewer", 1);
    c.expect("Shader::with_viewer", ok(&tr), || {
        format!("ray {dir:?} -> {tr:?}")
    });
    if let Some((g, f)) = shader.incidence(p, normal, 0) {
        c.count("Shader::incidence", 1);
        c.expect(
            "Shader::incidence",
            f.is_finite() && f >= 0.0 && g.n_dot_l.is_finite() && g.n_dot_v.is_finite(),
            || format!("{g:?} {f}"),
        );
    }

    // The unchecked constructors sanitise whatever they are given (release builds only: debug
    // builds assert their domain, as documented).
    if !cfg!(debug_assertions) {
        let wild = |r: &mut Rng| {
            let x = r.hard();
            match r.below(6) {
                0 => f32::NAN,
                1 => f32::INFINITY,
                _ => x,
            }
        };
        let m = Material::new(
            Vec3::new(wild(r), wild(r), wild(r)),
            Vec3::new(wild(r), wild(r), wild(r)),
            Vec3::new(wild(r), wild(r), wild(r)),
            wild(r),
        );
        let lc = LightColors::new(
            Vec3::new(wild(r), wild(r), wild(r)),
            Vec3::splat(wild(r)),
            Vec3::splat(wild(r)),
        );
        let spot = SpotLight::new(
            offset(p, r.unit(), 1.0),
            Vec3::new(wild(r), wild(r), wild(r)),
            SpotCone {
                cutoff: wild(r),
                exponent: wild(r),
            },
            Attenuation::polynomial(wild(r), wild(r), wild(r)),
            lc,
        );
        let lights2 = [Light::from(spot), lights[0]];
        let scene2 = Scene {
            lights: &lights2,
            ..scene
        };
        let t2 = Shader::new(model, &m, &scene2).shade_visible(p, normal, [wild(r), wild(r)]);
        c.count("unchecked constructors + shade", 1);
        c.expect("unchecked constructors + shade", ok(&t2), || {
            format!("{m:?} {spot:?} -> {t2:?}")
        });
    }
}

fn batch(r: &mut Rng, c: &mut Check) {
    let n = 1 + r.below(40) as usize;
    let center = if r.coin() { Vec3::ZERO } else { r.hard_vec() };
    let (lights, ambient, viewer) = scene_parts(r, center);
    let scene = Scene {
        lights: &lights,
        ambient,
        viewer,
    };
    let model = r.model();
    let material = r.material();
    let p: Vec<Vec3> = (0..n)
        .map(|_| match r.below(3) {
            0 => center,
            1 => {
                let (u, k) = (r.unit(), r.log_uniform(-30, 2));
                offset(center, u, k)
            }
            _ => r.hard_vec(),
        })
        .collect();
    let nn: Vec<Vec3> = (0..n)
        .map(|_| {
            if r.below(8) == 0 {
                r.hard_vec()
            } else {
                r.unit()
            }
        })
        .collect();
    let col = |v: &[Vec3], k: usize| v.iter().map(|q| q[k]).collect::<Vec<f32>>();
    let (px, py, pz) = (col(&p, 0), col(&p, 1), col(&p, 2));
    let (nx, ny, nz) = (col(&nn, 0), col(&nn, 1), col(&nn, 2));
    // The array-of-structs entry point: the detected level's output, bit for bit.
    let mut aos = vec![Vec3::ZERO; n];
    phong::shade_batch_aos(&model, &material, &scene, &p, &nn, &mut aos);
    c.count("shade_batch_aos", n as u64);
    for level in Level::supported() {
        let (mut or, mut og, mut ob) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        phong::shade_batch_with_level(
            level,
            &model,
            &material,
            &scene,
            SoaVec3::new(&px, &py, &pz),
            SoaVec3::new(&nx, &ny, &nz),
            SoaRgb::new(&mut or, &mut og, &mut ob),
        )
        .unwrap();
        c.count("shade_batch_with_level", n as u64);
        // The 8-bit frame: the same level's output encoded, alpha 255.
        let mut rgba = vec![[0u8; 4]; n];
        phong::shade_batch_rgba8_with_level(
            level,
            &model,
            &material,
            &scene,
            SoaVec3::new(&px, &py, &pz),
            SoaVec3::new(&nx, &ny, &nz),
            &mut rgba,
        )
        .unwrap();
        c.count("shade_batch_rgba8_with_level", n as u64);
        for i in 0..n {
            let out = Vec3::new(or[i], og[i], ob[i]);
            let range = batch_range::range(&model, &material, &scene, p[i], nn[i]);
            c.expect("shade_batch_with_level", range.holds(out), || {
                format!(
                    "{level:?} {model:?} {material:?} {lights:?} {viewer:?} p={:?} n={:?} -> {out:?} outside {range:?}",
                    p[i], nn[i]
                )
            });
            if level == Level::detect() {
                let same = aos[i].to_array().map(f32::to_bits) == out.to_array().map(f32::to_bits);
                c.expect("shade_batch_aos", same, || {
                    format!("point {i}: {:?} against shade_batch's {out:?}", aos[i])
                });
            }
            let [r8, g8, b8] = phong::linear_to_srgb8(out);
            c.expect(
                "shade_batch_rgba8_with_level",
                rgba[i] == [r8, g8, b8, 255],
                || format!("{level:?} point {i}: {:?} against {out:?}", rgba[i]),
            );
        }
    }
}

/// `shade_gbuffer` with hard per-point surfaces and visibilities at every level: every channel
/// finite and `≥ 0` (the totality promise), and the 8-bit frame the same level's output encoded.
fn gbuffer(r: &mut Rng, c: &mut Check) {
    let n = 1 + r.below(40) as usize;
    let center = if r.coin() { Vec3::ZERO } else { r.hard_vec() };
    let (lights, ambient, viewer) = scene_parts(r, center);
    let scene = Scene {
        lights: &lights,
        ambient,
        viewer,
    };
    let model = r.model();
    let material = r.material();
    let mut v = |f: &mut dyn FnMut(&mut Rng) -> f32| (0..n).map(|_| f(r)).collect::<Vec<f32>>();
    let p: [Vec<f32>; 3] = [
        v(&mut |r| {
            if r.coin() {
                r.hard()
            } else {
                r.range(-4.0, 4.0)
            }
        }),
        v(&mut |r| r.range(-4.0, 4.0)),
        v(&mut |r| {
            if r.below(8) == 0 {
                r.hard()
            } else {
                r.range(-4.0, 4.0)
            }
        }),
    ];
    let q: [Vec<f32>; 3] = [
        v(&mut |r| r.range(-1.0, 1.0)),
        v(&mut |r| {
            if r.below(8) == 0 {
                0.0
            } else {
                r.range(-1.0, 1.0)
            }
        }),
        v(&mut |r| {
            if r.below(8) == 0 {
                r.hard()
            } else {
                r.range(-1.0, 1.0)
            }
        }),
    ];
    let k: Vec<Vec<f32>> = (0..9).map(|_| v(&mut |r| r.hard_nonneg())).collect();
    let s = v(&mut |r| r.shininess());
    // Each light's plane: 0, 1 or soft point by point, and for one light in four also dark
    // across every other run of 16 points, where the kernel skips all but the ambient part.
    let vis = {
        let planes = lights.len().max(1);
        let mut vis = Vec::with_capacity(planes * n);
        for _ in 0..planes {
            let dark_runs = r.below(4) == 0;
            for i in 0..n {
                vis.push(match r.below(3) {
                    _ if dark_runs && (i / 16) % 2 == 0 => 0.0,
                    0 => 0.0,
                    1 => 1.0,
                    _ => r.unit_f32(),
                });
            }
        }
        vis
    };
    let texels: Vec<[u8; 4]> = (0..n)
        .map(|_| [0; 4].map(|_: u8| r.below(256) as u8))
        .collect();
    let coverage: Vec<bool> = (0..n).map(|_| r.below(4) != 0).collect();
    let mut buffer = GBuffer::new(soa(&p), soa(&q))
        .with_surface(SoaSurface {
            ambient: soa(&k[0..3]),
            diffuse: soa(&k[3..6]),
            specular: soa(&k[6..9]),
            shininess: &s,
        })
        .with_visibility(&vis);
    if r.coin() {
        buffer = buffer.with_albedo_srgb8(&texels);
    }
    // Tile culling (which does not cull with visibility planes) over any image width, tile and
    // threshold, with a coverage mask half the time: covered points finite and ≥ 0, the others
    // untouched.
    let tiled = GBuffer {
        visibility: None,
        coverage: r.coin().then_some(&coverage[..]),
        ..buffer
    };
    let culling = TileCulling {
        width: 1 + r.below(n as u64 + 3) as usize,
        tile: 1 + r.below(9) as usize,
        threshold: match r.below(4) {
            0 => 0.0,
            1 => r.hard(),
            _ => r.range(0.0, 0.1),
        },
    };
    for level in Level::supported() {
        let (mut tr, mut tg, mut tb) = (vec![-1.0; n], vec![-1.0; n], vec![-1.0; n]);
        let mut scratch = lights.clone();
        phong::shade_gbuffer_tiled_with_level(
            level,
            &model,
            &material,
            &scene,
            &tiled,
            culling,
            &mut scratch,
            SoaRgb::new(&mut tr, &mut tg, &mut tb),
        )
        .unwrap();
        c.count("shade_gbuffer_tiled_with_level", n as u64);
        for i in 0..n {
            let out = Vec3::new(tr[i], tg[i], tb[i]);
            let ok = if tiled.coverage.is_none_or(|m| m[i]) {
                finite_nonneg(out)
            } else {
                out == Vec3::splat(-1.0)
            };
            c.expect("shade_gbuffer_tiled_with_level", ok, || {
                format!("{level:?} {model:?} {culling:?} {lights:?} point {i} -> {out:?}")
            });
        }
        let mut xrgb = vec![0u32; n];
        phong::shade_gbuffer_xrgb8_with_level(level, &model, &material, &scene, &buffer, &mut xrgb)
            .unwrap();
        c.count("shade_gbuffer_xrgb8_with_level", n as u64);
        let (mut or, mut og, mut ob) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        phong::shade_gbuffer_with_level(
            level,
            &model,
            &material,
            &scene,
            &buffer,
            SoaRgb::new(&mut or, &mut og, &mut ob),
        )
        .unwrap();
        c.count("shade_gbuffer_with_level", n as u64);
        let mut rgba = vec![[0u8; 4]; n];
        phong::shade_gbuffer_rgba8_with_level(level, &model, &material, &scene, &buffer, &mut rgba)
            .unwrap();
        c.count("shade_gbuffer_rgba8_with_level", n as u64);
        for i in 0..n {
            let out = Vec3::new(or[i], og[i], ob[i]);
            c.expect("shade_gbuffer_with_level", finite_nonneg(out), || {
                format!(
                    "{level:?} {model:?} {material:?} {lights:?} {viewer:?} point {i} -> {out:?}"
                )
            });
            let [r8, g8, b8] = phong::linear_to_srgb8(out);
            c.expect(
                "shade_gbuffer_rgba8_with_level",
                rgba[i] == [r8, g8, b8, 255],
                || format!("{level:?} point {i}: {:?} against {out:?}", rgba[i]),
            );
            let x = u32::from(r8) << 16 | u32::from(g8) << 8 | u32::from(b8);
            c.expect("shade_gbuffer_xrgb8_with_level", xrgb[i] == x, || {
                format!("{level:?} point {i}: {:#08x} against {out:?}", xrgb[i])
            });
        }
    }
}

fn soa(a: &[Vec<f32>]) -> SoaVec3<'_> {
    SoaVec3::new(&a[0], &a[1], &a[2])
}

fn advisor(r: &mut Rng, c: &mut Check) {
    let p0 = r.unit() * r.range(0.0, 4.0);
    let positions = [
        p0,
        p0 + r.unit() * r.log_uniform(-20, 0), // |p0| ≤ 4: no overflow
        p0 + r.unit() * r.log_uniform(-20, 0),
    ];
    let normals = [r.unit(), r.direction(Vec3::Z), r.unit()];
    let (lights, ambient, viewer) = scene_parts(r, p0);
    let scene = Scene {
        lights: &lights,
        ambient,
        viewer,
    };
    let model = r.model();
    let material = r.material();
    let b = phong::shading_rate::gouraud_error_bound(&model, &material, &scene, positions, normals);
    c.count("gouraud_error_bound", 1);
    c.expect("gouraud_error_bound", b.is_finite() && b >= 0.0, || {
        format!("{model:?} {material:?} {lights:?} {positions:?} {normals:?} -> {b}")
    });
}

/// One worker: `budget` evaluations from the stream `seed`.
fn work(seed: u64, budget: u64, log: &Mutex<Log>) {
    let mut r = Rng(rng::Rng::new(seed));
    let mut c = Check::new();
    while c.total() < budget {
        // Weights: the cheap functions often, shading and the batch less (they are heavier, and
        // count one evaluation per lane).
        match r.below(16) {
            0..=4 => geometry(&mut r, &mut c),
            5 => mesh(&mut r, &mut c),
            6..=7 => attenuation(&mut r, &mut c),
            8..=10 => lobes(&mut r, &mut c),
            11 => {
                if r.coin() {
                    colour(&mut r, &mut c)
                } else {
                    rest(&mut r, &mut c)
                }
            }
            12..=13 => shading(&mut r, &mut c),
            14 => {
                if r.below(4) == 0 {
                    gbuffer(&mut r, &mut c)
                } else {
                    batch(&mut r, &mut c)
                }
            }
            _ => {
                if r.below(8) == 0 {
                    advisor(&mut r, &mut c)
                } else {
                    shading(&mut r, &mut c)
                }
            }
        }
    }
    let mut log = log.lock().unwrap();
    for (k, v) in c.counts {
        *log.counts.entry(k).or_default() += v;
    }
    log.total_violations += c.total_violations;
    for v in c.violations {
        if log.violations.len() < 20 {
            log.violations.push(v);
        }
    }
}

/// `name` as a decimal or `0x` hexadecimal number (underscores allowed), or `default` when unset.
/// A value that does not parse is an error, not a silent default.
fn env_u64(name: &str, default: u64) -> u64 {
    let Ok(raw) = std::env::var(name) else {
        return default;
    };
    let s = raw.replace('_', "");
    let parsed = match s.strip_prefix("0x") {
        Some(hex) => u64::from_str_radix(hex, 16).ok(),
        None => s.parse().ok(),
    };
    parsed.unwrap_or_else(|| panic!("{name}={raw:?} is not a number"))
}

#[test]
fn every_public_function_keeps_its_promises_on_adversarial_input() {
    // CI's default: a few seconds at the test profile's opt-level.
    let evals = env_u64("PHONG_FUZZ_EVALS", 5_000_000);
    let threads = env_u64(
        "PHONG_FUZZ_THREADS",
        std::thread::available_parallelism().map_or(1, |n| n.get() as u64),
    )
    .max(1);
    let seed = env_u64("PHONG_FUZZ_SEED", 0x5eed_f022);
    let log = Mutex::new(Log::default());
    let start = Instant::now();
    std::thread::scope(|s| {
        for t in 0..threads {
            let log = &log;
            let share = evals / threads + u64::from(t < evals % threads);
            s.spawn(move || work(seed ^ (t.wrapping_mul(0x9e37_79b9_7f4a_7c15)), share, log));
        }
    });
    let secs = start.elapsed().as_secs_f64();
    let log = log.into_inner().unwrap();
    let total: u64 = log.counts.values().sum();
    println!(
        "fuzz_promises: {total} evaluations in {secs:.1} s on {threads} threads (seed {seed:#x}, {} build)",
        if cfg!(debug_assertions) {
            "debug"
        } else {
            "release"
        }
    );
    for (f, n) in &log.counts {
        println!("  {f:<34} {n:>12}");
    }
    println!("fuzz_promises: {} violations", log.total_violations);
    assert!(
        log.total_violations == 0,
        "{} promise violations; the first:\n{}",
        log.total_violations,
        log.violations.join("\n")
    );
    // Every public function named above was reached.
    assert!(
        log.counts.len() >= 30,
        "only {} functions reached",
        log.counts.len()
    );
}
