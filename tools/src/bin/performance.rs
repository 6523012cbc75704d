//! Measures speed and accuracy of every pow strategy and model, and writes docs/performance.md and
//! docs/speed_vs_accuracy.svg.
//!
//! ```text
//! # first the baseline of commit 259b7f8 (see the "Dispatch levels" section it writes), because
//! # `--save-baseline` also overwrites `new/`: this tool refuses a `new/` equal to a baseline
//! cargo bench --bench shading -- --save-baseline first _1m   # an earlier run of the 1M groups
//! cargo bench --bench shading --bench renderers  # criterion: throughput, saved in target/criterion
//! cargo bench -p raster                         # the rasterizer's frame (raster_frame)
//! cargo run --release -p phong-tools --bin performance   # accuracy here, throughput read from criterion
//! ```
//!
//! Throughput comes only from criterion's saved estimates (`target/criterion/<group>/<function>/
//! new/estimates.json`, the median of the latest run; the 1M groups also from the baseline
//! `first`, an earlier run, because memory-bound results vary from run to run).
//! Accuracy is measured here on 2²⁰ random points of the benches' scene, against the same
//! equation evaluated in f64: the largest absolute error of a linear channel, and the rate of
//! 8-bit sRGB channels that differ from the f64 result (rounded to f32 and encoded by the crate's
//! own `linear_to_srgb8`, so only the shading differs). Every number in the outputs is measured;
//! none is typed in.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use glam::{DVec3, Vec3};
use phong::{
    Attenuation, BlinnPhong, GBuffer, Level, LightColors, Material, Phong, PointLight, PowStrategy,
    Scene, SoaRgb, SoaSurface, SoaVec3, Viewer,
};

use phong_tools::bench_scene::*;

const N: usize = 1 << 20;

#[derive(Clone, Copy, PartialEq, Debug)]
enum Kind {
    Phong,
    Blinn,
}
impl Kind {
    fn name(self) -> &'static str {
        match self {
            Kind::Phong => "phong",
            Kind::Blinn => "blinn",
        }
    }
}

/// The benches' equation in f64: step gate, classic lobes, polynomial attenuation.
fn reference(kind: Kind, s: f64, p: Vec3, n: Vec3) -> DVec3 {
    let k = [KA, KD, KS].map(|c| c.as_dvec3());
    reference_surface(kind, k, s, 1.0, p, n)
}

/// [`reference`] with the point's own reflectances `k = [Ka, Kd, Ks]`, shininess `s` and the
/// light's visibility `vis` (scaling its diffuse and specular parts).
fn reference_surface(kind: Kind, k: [DVec3; 3], s: f64, vis: f64, p: Vec3, n: Vec3) -> DVec3 {
    let (p, n) = (p.as_dvec3(), n.as_dvec3().normalize());
    let lp = LIGHT_POS.as_dvec3();
    let l = (lp - p).normalize();
    let v = (VIEW_POS.as_dvec3() - p).normalize();
    let nl = n.dot(l);
    let base = match kind {
        Kind::Phong => (2.0 * nl * n - l).dot(v).max(0.0),
        Kind::Blinn => n.dot((l + v).normalize()).max(0.0),
    };
    let spec = if nl > 0.0 && base > 0.0 {
        base.powf(s)
    } else {
        0.0
    };
    let d = (lp - p).length();
    let f = 1.0 / (ATT.0 as f64 + ATT.1 as f64 * d + ATT.2 as f64 * d * d);
    f * (LA.as_dvec3() * k[0]
        + vis * (LD.as_dvec3() * k[1] * nl.max(0.0) + LS.as_dvec3() * k[2] * spec))
}

/// `shade_gbuffer` on the accuracy points with a per-point textured surface (shininess uniform
/// in [2, 128]) and shadow factor, against [`reference_surface`].
fn gbuffer_accuracy(p: &[Vec3], nn: &[Vec3], soa: &[Vec<f32>; 6]) -> Accuracy {
    let n = p.len();
    // The benches' generator, with its own seed.
    let mut rng = Rng::new(0x6b75_6666_6572_0001);
    let mut next = || rng.unit_f32();
    let texel: [Vec<f32>; 3] = std::array::from_fn(|_| (0..n).map(|_| next()).collect());
    let strength: Vec<f32> = (0..n).map(|_| next()).collect();
    let shininess: Vec<f32> = (0..n).map(|_| 2.0 + 126.0 * next()).collect();
    let shadow: Vec<f32> = (0..n).map(|_| next()).collect();
    let lights = [scene_light()];
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(VIEW_POS),
    };
    let texels = SoaVec3::new(&texel[0], &texel[1], &texel[2]);
    let g = GBuffer::new(
        SoaVec3::new(&soa[0], &soa[1], &soa[2]),
        SoaVec3::new(&soa[3], &soa[4], &soa[5]),
    )
    .with_surface(SoaSurface {
        ambient: texels,
        diffuse: texels,
        specular: SoaVec3::new(&strength, &strength, &strength),
        shininess: &shininess,
    })
    .with_visibility(&shadow);
    let (mut r, mut gr, mut b) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let material = Material::try_from_color(Vec3::ONE, 20.5).unwrap();
    phong::shade_gbuffer(
        &Phong::default(),
        &material,
        &scene,
        &g,
        SoaRgb::new(&mut r, &mut gr, &mut b),
    );
    let out: Vec<Vec3> = (0..n).map(|i| Vec3::new(r[i], gr[i], b[i])).collect();
    let reference: Vec<DVec3> = (0..n)
        .map(|i| {
            let t = DVec3::new(texel[0][i] as f64, texel[1][i] as f64, texel[2][i] as f64);
            let k = [t, t, DVec3::splat(strength[i] as f64)];
            reference_surface(
                Kind::Phong,
                k,
                shininess[i] as f64,
                shadow[i] as f64,
                p[i],
                nn[i],
            )
        })
        .collect();
    compare(&out, &reference)
}

struct Accuracy {
    max_abs: f64,
    mismatch: f64,
}

fn compare(out: &[Vec3], reference: &[DVec3]) -> Accuracy {
    let mut max_abs = 0.0f64;
    let mut bad = 0usize;
    for (o, r) in out.iter().zip(reference) {
        max_abs = max_abs.max((o.as_dvec3() - *r).abs().max_element());
        let a = phong::linear_to_srgb8(*o);
        let b = phong::linear_to_srgb8(r.as_vec3());
        bad += a.iter().zip(&b).filter(|(x, y)| x != y).count();
    }
    Accuracy {
        max_abs,
        mismatch: bad as f64 / (3 * out.len()) as f64,
    }
}

fn scene_light() -> PointLight {
    PointLight::try_new(
        LIGHT_POS,
        Attenuation::try_polynomial(ATT.0, ATT.1, ATT.2).unwrap(),
        LightColors::try_new(LA, LD, LS).unwrap(),
    )
    .unwrap()
}

/// The batch path's output for one configuration.
fn batch_out(level: Level, kind: Kind, pow: PowStrategy, s: f32, soa: &[Vec<f32>; 6]) -> Vec<Vec3> {
    let lights = [scene_light()];
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(VIEW_POS),
    };
    let m = Material::try_new(KA, KD, KS, s).unwrap();
    let (mut r, mut g, mut b) = (vec![0.0; N], vec![0.0; N], vec![0.0; N]);
    let pos = SoaVec3::new(&soa[0], &soa[1], &soa[2]);
    let nor = SoaVec3::new(&soa[3], &soa[4], &soa[5]);
    let out = SoaRgb::new(&mut r, &mut g, &mut b);
    match kind {
        Kind::Phong => {
            let model = Phong {
                pow,
                ..Phong::default()
            };
            phong::shade_batch_with_level(level, &model, &m, &scene, pos, nor, out).unwrap();
        }
        Kind::Blinn => {
            let model = BlinnPhong {
                pow,
                ..BlinnPhong::default()
            };
            phong::shade_batch_with_level(level, &model, &m, &scene, pos, nor, out).unwrap();
        }
    }
    (0..N).map(|i| Vec3::new(r[i], g[i], b[i])).collect()
}

/// The scalar `phong::shade` with exact `powf`: the "exact f32 path".
fn scalar_exact(kind: Kind, s: f32, p: &[Vec3], n: &[Vec3]) -> Vec<Vec3> {
    let lights = [scene_light()];
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(VIEW_POS),
    };
    let m = Material::try_new(KA, KD, KS, s).unwrap();
    let pow = PowStrategy::Exact;
    let model: phong::Model = match kind {
        Kind::Phong => Phong {
            pow,
            ..Phong::default()
        }
        .into(),
        Kind::Blinn => BlinnPhong {
            pow,
            ..BlinnPhong::default()
        }
        .into(),
    };
    p.iter()
        .zip(n)
        .map(|(&p, &n)| phong::shade(&model, &m, &scene, p, n).total())
        .collect()
}

/// The prepared per-point path (`Shader`) with `PowStrategy::Auto`: squaring for a whole exponent,
/// `Poly7` otherwise.
fn scalar_auto(kind: Kind, s: f32, p: &[Vec3], n: &[Vec3]) -> Vec<Vec3> {
    let lights = [scene_light()];
    let scene = Scene {
        lights: &lights,
        ambient: Vec3::ZERO,
        viewer: Viewer::At(VIEW_POS),
    };
    let m = Material::try_new(KA, KD, KS, s).unwrap();
    let pow = PowStrategy::Auto;
    match kind {
        Kind::Phong => {
            let sh = phong::Shader::new(
                Phong {
                    pow,
                    ..Phong::default()
                },
                &m,
                &scene,
            );
            p.iter()
                .zip(n)
                .map(|(&p, &n)| sh.shade(p, n).total())
                .collect()
        }
        Kind::Blinn => {
            let sh = phong::Shader::new(
                BlinnPhong {
                    pow,
                    ..BlinnPhong::default()
                },
                &m,
                &scene,
            );
            p.iter()
                .zip(n)
                .map(|(&p, &n)| sh.shade(p, n).total())
                .collect()
        }
    }
}

/// Max relative error of `PowStrategy::lobe` against f64 where `x^s ≥ 2⁻²⁴`, over a grid.
fn pow_error(p: PowStrategy) -> f64 {
    let mut worst = 0.0f64;
    for s in [
        0.5f32, 1.0, 2.5, 7.0, 10.25, 16.0, 20.5, 32.0, 64.0, 100.7, 128.0, 256.0, 511.3,
    ] {
        for k in 1..=20_000 {
            let x = k as f32 / 20_000.0;
            let want = (x as f64).powf(s as f64);
            if want >= 2f64.powi(-24) {
                worst = worst.max((p.lobe(x, s) as f64 - want).abs() / want);
            }
        }
    }
    worst
}

/// A criterion median in ns per iteration: `which` is `"new"` (latest run) or a saved baseline.
///
/// Exits the tool when `new` is a copy of a saved baseline (see [`baseline_copied_to_new`]):
/// the tables would then compare a baseline with itself and call it this run.
fn median_ns(dir: &Path, which: &str) -> Option<f64> {
    if which == "new"
        && let Some(baseline) = baseline_copied_to_new(dir)
    {
        eprintln!(
            "error: {}/new holds the same estimates as the baseline `{baseline}`: the baseline \
             was run after this run and overwrote its result (`--save-baseline` writes `new/` \
             and then copies it). Run the baseline first, then `cargo bench --bench shading \
             --bench renderers` again, then this tool.",
            dir.display()
        );
        std::process::exit(1);
    }
    let text = std::fs::read_to_string(dir.join(which).join("estimates.json")).ok()?;
    let v: serde_json::Value = serde_json::from_str(&text).ok()?;
    v["median"]["point_estimate"].as_f64()
}

/// The median of a `paired_4096` row: a throughput ratio (`benches/support/paired_ratio.rs`).
fn paired(function: &str) -> Option<f64> {
    median_ns(&crit_dir().join("paired_4096").join(function), "new")
}

/// The targets' ratios again, each from one `paired_4096` row, where both sides are timed in
/// alternation within every sample instead of in windows of their own.
fn paired_table(md: &mut String) {
    let mut rows: Vec<(String, String, f64)> = Vec::new();
    for kind in [Kind::Phong, Kind::Blinn] {
        rows.push((
            format!("{}_scalar_over_naive_glam", kind.name()),
            format!("`scalar` ≥ 1× `naive_glam`, {}", kind.name()),
            1.0,
        ));
    }
    for (subject, baseline, goal) in [
        ("avx2", "avx512", 0.6),
        ("sse2", "avx512", 0.3),
        ("sse2", "portable", 1.0),
    ] {
        for kind in [Kind::Phong, Kind::Blinn] {
            for sh in [32.0f32, 20.5] {
                rows.push((
                    format!("levels_{subject}_over_{baseline}/{}_{sh}", kind.name()),
                    format!(
                        "`{subject}` ≥ {goal}× `{baseline}`, {} s = {sh}",
                        kind.name()
                    ),
                    goal,
                ));
            }
        }
    }
    for f in ["gbuffer_rgba8", "gbuffer_albedo8_rgba8"] {
        rows.push((
            format!("{f}_over_batch_frac"),
            format!("`{f}` ≥ 0.8× this build's `batch_frac`"),
            0.8,
        ));
    }
    let measured: Vec<_> = rows
        .into_iter()
        .filter_map(|(f, what, goal)| Some((f.clone(), what, goal, paired(&f)?)))
        .collect();
    if measured.is_empty() {
        return;
    }
    let _ = writeln!(
        md,
        "\n### The same ratios, paired (`paired_4096`)\n\n\
         Each row above compares two criterion rows, each timed in a two-second window of its \
         own. Where a host's speed changes over time (the Intel Xeon host of 2026-12-07 \
         switched between states about 35–40% apart, each lasting from half a second to several \
         seconds), the two windows of a ratio can fall in different states; the noise paragraph \
         above says how far apart they were in this run. A `paired_4096` row times both calls of \
         a ratio in alternation inside every one of criterion's samples (a few milliseconds), \
         so both sides of a sample see the same state, and its median is the median of those \
         per-sample ratios: the subject's throughput ÷ the baseline's \
         (`benches/support/paired_ratio.rs`). A slow state does not slow every kind of code \
         alike, so a paired ratio still moves between runs: by 1–17% a row across four runs on \
         that host (Phong's per-point row by under 1%), where the ordinary rows' ratios moved \
         by tens of percent. The comparison with 259b7f8 cannot be paired: one process holds \
         one build.\n"
    );
    let _ = writeln!(md, "| ratio | paired median | status |\n|---|---:|---|");
    for (_, what, goal, r) in measured {
        let _ = writeln!(
            md,
            "| {what} | {r:.3}× | {} |",
            status_at_least(Some(r), goal, "not measured")
        );
    }
}

/// The saved baseline, if any, whose `estimates.json` is byte for byte the one in `new/` of a
/// criterion benchmark directory `dir`.
///
/// Criterion's `--save-baseline NAME` writes a run's results to `new/` and then copies them to
/// `NAME/`, so a baseline run after the current one leaves `new/` holding the baseline's figures.
/// Two separate runs never give the same file: its bootstrap intervals and the median are
/// printed to every digit of an `f64`. (`base/` is criterion's own copy of the previous run and
/// `change/` and `report/` hold no estimates of a run, so they are not compared.)
fn baseline_copied_to_new(dir: &Path) -> Option<String> {
    let new = std::fs::read(dir.join("new").join("estimates.json")).ok()?;
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .ok()?
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|name| !matches!(name.as_str(), "new" | "base" | "change" | "report"))
        .collect();
    names.sort();
    names.into_iter().find(|name| {
        std::fs::read(dir.join(name).join("estimates.json")).is_ok_and(|saved| saved == new)
    })
}

/// The workspace root: this crate sits in tools/.
fn workspace_root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("tools/ has a parent")
}

fn crit_dir() -> PathBuf {
    std::env::var_os("CARGO_TARGET_DIR")
        .map_or_else(|| workspace_root().join("target"), PathBuf::from)
        .join("criterion")
}

/// Million points per second from the median of `group/function` (criterion's directory names).
/// The real-shaped groups' rows: (group, hand-written function, `phong` function).
const REAL_SHAPED: [(&str, &str, &str); 4] = [
    ("raytrace", "hand", "phong"),
    ("raytrace_one_light", "hand", "phong"),
    ("fragment", "hand", "phong"),
    ("fragment", "hand_callback", "phong_callback"),
];

fn mpts(group: &str, function: &str, n: usize, which: &str) -> Option<f64> {
    let t = median_ns(&crit_dir().join(group).join(function), which)?;
    Some(n as f64 / t * 1e3)
}

/// A targets-table status for a ratio that must reach `goal`: "met", or how far short it fell,
/// or `missing` where the run has no figure.
fn status_at_least(r: Option<f64>, goal: f64, missing: &str) -> String {
    match r {
        Some(r) if r >= goal => "met".to_string(),
        Some(r) => format!("missed by {:.1}%", (1.0 - r / goal) * 100.0),
        None => missing.to_string(),
    }
}

fn fmt_opt(x: Option<f64>, digits: usize) -> String {
    x.map_or("–".into(), |v| format!("{v:.digits$}"))
}

fn machine() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|c| {
            c.lines()
                .find(|l| l.starts_with("model name"))
                .map(|l| l.split(':').nth(1).unwrap_or("").trim().to_string())
        })
        .unwrap_or_else(|| "unknown".into());
    let field = |name: &str| {
        std::fs::read_to_string("/proc/cpuinfo")
            .ok()
            .and_then(|c| {
                c.lines()
                    .find(|l| l.split(':').next().map(str::trim) == Some(name))
                    .map(|l| l.split(':').nth(1).unwrap_or("").trim().to_string())
            })
            .unwrap_or_else(|| "?".into())
    };
    let cpu = format!(
        "{cpu} (cpu family {}, model {})",
        field("cpu family"),
        field("model")
    );
    let cores = std::thread::available_parallelism().map_or(0, |n| n.get());
    let flags = std::fs::read_to_string("/proc/cpuinfo").unwrap_or_default();
    let has = |f: &str| flags.split_whitespace().any(|w| w == f);
    format!(
        "{cpu}, {cores} logical cores; avx2={} fma={} avx512f={} avx512vl={}; best batch level: {}",
        has("avx2"),
        has("fma"),
        has("avx512f"),
        has("avx512vl"),
        Level::detect()
    )
}

fn now_utc() -> String {
    std::process::Command::new("date")
        .args(["-u", "+%Y-%m-%d %H:%M UTC"])
        .output()
        .ok()
        .and_then(|o| String::from_utf8(o.stdout).ok())
        .map_or("unknown".into(), |s| s.trim().to_string())
}

struct Point {
    label: String,
    mpts: f64,
    mismatch: f64,
    kind: Kind,
}

fn svg(points: &[Point], exact_rate: [f64; 2]) -> String {
    let (w, h) = (820.0, 520.0);
    let (left, right, top, bottom) = (80.0, 30.0, 40.0, 60.0);
    let xmax = points.iter().map(|p| p.mpts).fold(100.0, f64::max) * 1.1;
    let floor = 1e-7f64;
    let ymax = points
        .iter()
        .map(|p| p.mismatch)
        .fold(1e-3, f64::max)
        .log10()
        .ceil();
    let ymin = floor.log10();
    let x = |v: f64| left + v / xmax * (w - left - right);
    let y = |r: f64| {
        let l = r.max(floor).log10();
        top + (ymax - l) / (ymax - ymin) * (h - top - bottom)
    };
    let mut s = String::new();
    let _ = write!(
        s,
        r##"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="sans-serif" font-size="12">
<rect width="100%" height="100%" fill="white"/>
<text x="{}" y="22" text-anchor="middle" font-size="15">Batch shading, N = 4096, shininess 20.5: speed vs 8-bit accuracy</text>
<line x1="{left}" y1="{}" x2="{}" y2="{}" stroke="black"/>
<line x1="{left}" y1="{top}" x2="{left}" y2="{}" stroke="black"/>
<text x="{}" y="{}" text-anchor="middle">throughput (million points / s, criterion median, one core)</text>
<text x="18" y="{}" text-anchor="middle" transform="rotate(-90 18 {})">8-bit sRGB channels differing from f64 (log; 0 drawn at 1e-7)</text>
"##,
        w / 2.0,
        h - bottom,
        w - right,
        h - bottom,
        h - bottom,
        (left + w - right) / 2.0,
        h - 15.0,
        (top + h - bottom) / 2.0,
        (top + h - bottom) / 2.0
    );
    let mut e = ymin as i32;
    while e as f64 <= ymax {
        let yy = y(10f64.powi(e));
        let _ = writeln!(
            s,
            r##"<line x1="{left}" y1="{yy:.1}" x2="{}" y2="{yy:.1}" stroke="#ddd"/><text x="{}" y="{:.1}" text-anchor="end">1e{e}</text>"##,
            w - right,
            left - 6.0,
            yy + 4.0
        );
        e += 1;
    }
    let step = if xmax > 1500.0 { 200.0 } else { 100.0 };
    let mut t = 0.0;
    while t <= xmax {
        let xx = x(t);
        let _ = writeln!(
            s,
            r##"<line x1="{xx:.1}" y1="{top}" x2="{xx:.1}" y2="{}" stroke="#eee"/><text x="{xx:.1}" y="{}" text-anchor="middle">{t}</text>"##,
            h - bottom,
            h - bottom + 16.0
        );
        t += step;
    }
    for (k, rate) in [Kind::Phong, Kind::Blinn].iter().zip(exact_rate) {
        let yy = y(rate);
        let colour = if *k == Kind::Phong {
            "#1f77b4"
        } else {
            "#d62728"
        };
        let _ = writeln!(
            s,
            r##"<line x1="{left}" y1="{yy:.1}" x2="{}" y2="{yy:.1}" stroke="{colour}" stroke-dasharray="5,4"/><text x="{}" y="{:.1}" fill="{colour}" text-anchor="end">exact f32 scalar path ({})</text>"##,
            w - right,
            w - right - 4.0,
            yy - 4.0,
            k.name()
        );
    }
    for p in points {
        let colour = if p.kind == Kind::Phong {
            "#1f77b4"
        } else {
            "#d62728"
        };
        let (xx, yy) = (x(p.mpts), y(p.mismatch));
        let _ = writeln!(
            s,
            r##"<circle cx="{xx:.1}" cy="{yy:.1}" r="4" fill="{colour}"/><text x="{:.1}" y="{:.1}" fill="{colour}">{}</text>"##,
            xx + 6.0,
            yy - 6.0,
            p.label
        );
    }
    s.push_str("</svg>\n");
    s
}

fn main() {
    let (p, nn) = points(N, 0xacc);
    let soa: [Vec<f32>; 6] = [
        p.iter().map(|v| v.x).collect(),
        p.iter().map(|v| v.y).collect(),
        p.iter().map(|v| v.z).collect(),
        nn.iter().map(|v| v.x).collect(),
        nn.iter().map(|v| v.y).collect(),
        nn.iter().map(|v| v.z).collect(),
    ];
    let level = Level::detect();
    let mut md = String::new();
    let _ = writeln!(md, "# Performance: speed and accuracy of the batch path\n");
    let _ = writeln!(
        md,
        "Generated by tools/src/bin/performance.rs; every number below is measured, none typed in. \
         To reproduce (after the baseline of 259b7f8 in \
         \"Dispatch levels\" below, which must run first):\n\n```text\ncargo bench --bench shading -- --save-baseline first _1m\n\
         cargo bench --bench shading --bench renderers\ncargo bench -p raster\ncargo run --release -p phong-tools --bin performance\n```\n"
    );
    let _ = writeln!(md, "- **Machine:** {}", machine());
    let _ = writeln!(md, "- **Date:** {}", now_utc());
    let _ = writeln!(
        md,
        "- **Throughput:** criterion medians (`target/criterion/*/new/estimates.json`; the \
         earlier 1M run from the baseline `first/`), one thread. The host is shared: ratios within one run are \
         what to compare.\n- **Accuracy:** 2²⁰ random points of the benches' scene (one point \
         light, step gate, LearnOpenGL attenuation and colours) against the same equation in \
         f64. *Mismatch* = fraction of 8-bit sRGB channels that differ from the f64 result.\n"
    );

    // ---- Main groups.
    let _ = writeln!(md, "## The benchmark groups\n");
    let _ = writeln!(
        md,
        "| group | naive_glam | scalar | scalar_opaque | scalar_lone | shade | batch | batch_frac | scalar × naive | scalar_opaque × naive | scalar_lone × naive | shade × naive | batch × naive | batch_frac × naive |"
    );
    let _ = writeln!(
        md,
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
    );
    for (which, label) in [("new", "this run"), ("first", "earlier run")] {
        for (group, n) in [
            ("phong_4096", 4096usize),
            ("blinn_4096", 4096),
            ("phong_1m", 1 << 20),
            ("blinn_1m", 1 << 20),
        ] {
            if which == "first" && group.ends_with("4096") {
                continue;
            }
            let t: Vec<Option<f64>> = [
                "naive_glam",
                "scalar",
                "scalar_opaque",
                "scalar_lone",
                "shade",
                "batch",
                "batch_frac",
            ]
            .iter()
            .map(|f| mpts(group, f, n, which))
            .collect();
            let ratio = |k: usize| match (t[k], t[0]) {
                (Some(a), Some(b)) => Some(a / b),
                _ => None,
            };
            let cells: Vec<String> = (0..t.len())
                .map(|k| fmt_opt(t[k], 0))
                .chain((1..t.len()).map(|k| fmt_opt(ratio(k), 2)))
                .collect();
            let _ = writeln!(md, "| {group} ({label}) | {} |", cells.join(" | "));
        }
    }
    let _ = writeln!(
        md,
        "\nMillion points per second. `batch` is shininess 32 (`PowStrategy::Auto` → squaring), \
         `batch_frac` 20.5 (`Auto` → {:?} for Phong's exponent 20.5, {:?} for Blinn's 10.25). \
         `scalar` is the per-point API of the README: a `Shader` prepared once with the model's \
         defaults (`PowStrategy::Auto`: squaring for s = 32), then `shade(p, n).total()` per point, \
         with the scene built around its one light where the points are shaded, as the quick \
         start does (the compiler then sees one light, as it does in `naive_glam`, whose light is \
         written into its code; the light's values reach both at run time); `scalar_opaque` is \
         the same loop with each point passed through `black_box`, so that the compiler cannot \
         vectorise across points (one point per call, as a recursive ray tracer or a per-pixel \
         callback shades); `scalar_lone` is that loop with the shader's form for it, \
         `Shader::one_at_a_time` (the light loop, whose rare cases are branches); `shade` is the \
         free function per point, which prepares on every call and takes the light loop.\n",
        PowStrategy::cheapest_for_8bit(20.5),
        PowStrategy::cheapest_for_8bit(10.25)
    );

    // ---- Targets (issue 4), from the same run's medians.
    let _ = writeln!(md, "## Targets (ratios within this run)\n");
    let _ = writeln!(
        md,
        "| target | group | measured | status |\n|---|---|---:|---|"
    );
    for (group, n) in [
        ("phong_4096", 4096usize),
        ("blinn_4096", 4096),
        ("phong_1m", 1 << 20),
        ("blinn_1m", 1 << 20),
    ] {
        let naive = mpts(group, "naive_glam", n, "new");
        let want: &[(&str, f64)] = if n == 4096 {
            &[("batch", 10.0), ("batch_frac", 7.0), ("scalar", 1.0)]
        } else {
            &[("batch", 8.0)]
        };
        for &(f, goal) in want {
            let r = mpts(group, f, n, "new").zip(naive).map(|(a, b)| a / b);
            let status = status_at_least(r, goal, "not measured");
            let _ = writeln!(
                md,
                "| `{f}` ≥ {goal}× `naive_glam` | {group} | {}× | {status} |",
                fmt_opt(r, 2)
            );
        }
    }
    for (group, hand_fn, ours_fn) in REAL_SHAPED {
        let hand = mpts(group, hand_fn, 4096, "new");
        let ours = mpts(group, ours_fn, 4096, "new");
        // Time ratio phong / hand = throughput ratio hand / phong.
        let r = hand.zip(ours).map(|(h, o)| h / o);
        let status = match r {
            Some(r) if r <= 1.0 => "met".to_string(),
            Some(r) => format!("missed: {:.0}% slower", (r - 1.0) * 100.0),
            None => "not measured".to_string(),
        };
        let _ = writeln!(
            md,
            "| `{ours_fn}` time ≤ 1.0× `{hand_fn}` | {group} | {}× | {status} |",
            fmt_opt(r, 2)
        );
    }
    // The G-buffer's 8-bit output against `batch_frac`: this run's, and 259b7f8's (the issue's
    // "today's `batch_frac`", run just before this run as the baseline `b259`).
    let frac_now = mpts("gbuffer_4096", "batch_frac", 4096, "new");
    let frac_259 = mpts("phong_4096", "batch_frac", 4096, "b259");
    for (f, label) in [
        ("gbuffer_rgba8", "RGBA8"),
        ("gbuffer_albedo8_rgba8", "RGBA8, 8-bit albedo"),
    ] {
        let ours = mpts("gbuffer_4096", f, 4096, "new");
        for (base, which) in [(frac_now, "this run's"), (frac_259, "259b7f8's")] {
            let r = ours.zip(base).map(|(o, b)| o / b);
            let status = status_at_least(r, 0.8, "not measured");
            let _ = writeln!(
                md,
                "| `{f}` ({label}) ≥ 0.8× {which} `batch_frac` | gbuffer_4096 | {}× | {status} |",
                fmt_opt(r, 2)
            );
        }
    }
    // The levels (issue 11): AVX2 ≥ 0.6× and SSE2 ≥ 0.3× the AVX-512 level, SSE2 above
    // portable, and AVX-512 no slower than at 259b7f8 (`b259`), per model and shininess.
    for kind in [Kind::Phong, Kind::Blinn] {
        for sh in [32.0f32, 20.5] {
            let at = |lv: &str, base: &str| {
                mpts(
                    "levels_4096",
                    &format!("{}/{lv}_{sh}", kind.name()),
                    4096,
                    base,
                )
            };
            let top = at("avx512", "new");
            let rows = [
                (
                    "avx2",
                    "0.6× the AVX-512 level",
                    at("avx2", "new"),
                    top,
                    0.6,
                ),
                (
                    "sse2",
                    "0.3× the AVX-512 level",
                    at("sse2", "new"),
                    top,
                    0.3,
                ),
                (
                    "sse2",
                    "1× portable",
                    at("sse2", "new"),
                    at("portable", "new"),
                    1.0,
                ),
                (
                    "avx512",
                    "1× 259b7f8's AVX-512",
                    top,
                    at("avx512", "b259"),
                    1.0,
                ),
            ];
            for (lv, what, ours, base, goal) in rows {
                let r = ours.zip(base).map(|(o, b)| o / b);
                let status =
                    status_at_least(r, goal, "not measured (the level is missing on this host)");
                let _ = writeln!(
                    md,
                    "| `{lv}` ≥ {what}, {} s = {sh} | levels_4096 | {}× | {status} |",
                    kind.name(),
                    fmt_opt(r, 2)
                );
            }
        }
    }
    // The same call measured twice in this run: `batch` / `batch_frac` of `{kind}_4096` and the
    // best level's row of `levels_4096` run `shade_batch` at the same level on the same scene and
    // points. Their disagreement is this run's noise, which every ratio above carries.
    let best = Level::detect().name();
    let mut spread: Vec<String> = Vec::new();
    for kind in [Kind::Phong, Kind::Blinn] {
        for (function, sh) in [("batch", 32.0f32), ("batch_frac", 20.5)] {
            let group = format!("{}_4096", kind.name());
            let a = mpts(&group, function, 4096, "new");
            let b = mpts(
                "levels_4096",
                &format!("{}/{best}_{sh}", kind.name()),
                4096,
                "new",
            );
            if let (Some(a), Some(b)) = (a, b) {
                spread.push(format!(
                    "{} s = {sh}: {a:.0} and {b:.0} ({:+.0}%)",
                    kind.name(),
                    (b / a - 1.0) * 100.0
                ));
            }
        }
    }
    if !spread.is_empty() {
        let _ = writeln!(
            md,
            "\n**This run's noise.** The same call, `shade_batch` at the `{best}` level on the same \
             scene and points, is timed twice in this run: as `batch` / `batch_frac` of the \
             `*_4096` groups and as the `{best}` rows of `levels_4096` (M points/s, the second's \
             difference from the first): {}. A ratio above that is closer to its goal than these \
             differences does not say which side of it the code is on.",
            spread.join("; ")
        );
    }
    paired_table(&mut md);
    let _ = writeln!(
        md,
        "\n## Real-shaped groups (`cargo bench --bench renderers`; `raster_frame`: `cargo bench -p raster`)\n"
    );
    let _ = writeln!(
        md,
        "| group | rows | hand (Mpts/s) | phong (Mpts/s) | phong time ÷ hand time |\n|---|---|---:|---:|---:|"
    );
    for (group, hand_fn, ours_fn) in REAL_SHAPED {
        let hand = mpts(group, hand_fn, 4096, "new");
        let ours = mpts(group, ours_fn, 4096, "new");
        let _ = writeln!(
            md,
            "| {group} | `{hand_fn}`, `{ours_fn}` | {} | {} | {} |",
            fmt_opt(hand, 1),
            fmt_opt(ours, 1),
            fmt_opt(hand.zip(ours).map(|(h, o)| h / o), 2)
        );
    }
    let _ = writeln!(
        md,
        "\n- **raytrace**: 4096 recorded hits (position, normal, direction back along the ray), \
         three point lights, per-light visibility from shadow rays (a third blocked). `hand` is \
         LearnOpenGL's multiple-lights shader with glam; `phong` is \
         `Shader::with_viewer(..).shade_visible(..)` with `Phong::learnopengl()` (no gate, like \
         the hand code). `with_viewer` returns the one-at-a-time form of the shader.\n\
         - **raytrace_one_light**: the same hits under the first light alone. With one light \
         `Shader::new` prepares the branch-free form for vectorised loops; `with_viewer` returns \
         the one-at-a-time form (before 2026-11-27 the hits took the branch-free form: 1.8× \
         `hand`'s time in a probe of this loop).\n\
         - **fragment**: 4096 fragments with a diffuse texel, a specular strength, a shininess \
         uniform in [2, 128] and a filtered shadow factor, one point light, a camera at a point. \
         `phong` is `Shader::shade_surface(..)` in a loop over the fragments' arrays, which the \
         compiler vectorises on both sides. `hand_callback` and `phong_callback` shade the same \
         fragments one per call (each position read through `black_box` of a reference to it; \
         through `black_box` of the value, before 2026-11-30, the harness's stack round trip \
         became a failed store forward in the new light loop), as a rasterizer's per-fragment \
         callback does; `phong_callback` uses `Shader::one_at_a_time`.\n\
         - Every group asserts before timing that the two sides agree within 1e-4 on every input.\n"
    );
    let frame_ms =
        |f: &str| median_ns(&crit_dir().join("raster_frame").join(f), "new").map(|t| t / 1e6);
    let (fb, fp) = (frame_ms("batch"), frame_ms("point"));
    let _ = writeln!(
        md,
        "### A rasterizer's frame (`raster_frame`)\n\n\
         The workspace's `raster` crate draws a 400 × 400 frame of a 5120-triangle sphere, shaded \
         per pixel with Phong and one point light: the explorer's picture with \"per pixel\" and \
         4 subdivisions (`cargo run --release -p explorer`). `batch` is how `raster` shades now: \
         each visible fragment's attributes are kept and shaded 1024 at a time through \
         `shade_gbuffer`. `point` is the same draw with one `shade` per pixel, how `raster` and \
         so the explorer shaded before: the explorer's frame time before and after.\n\n\
         | `batch` (ms) | `point` (ms) | point ÷ batch |\n|---:|---:|---:|\n| {} | {} | {} |\n",
        fmt_opt(fb, 2),
        fmt_opt(fp, 2),
        fmt_opt(fp.zip(fb).map(|(p, b)| p / b), 2)
    );
    let _ = writeln!(
        md,
        "\nWhere a target is missed, the causes found while tuning (perf profiles on this \
         machine):\n\n\
         - **`scalar` against `naive_glam`.** Both loops are vectorised by LLVM, four points per \
         instruction (`mulps`, `sqrtps`, `divps` across points; `naive_glam` adds four scalar \
         `powf` calls): the one-light `Shader` path is straight-line code with no call, loop or \
         data branch (see `Shader`'s docs), and for one material a whole shininess skips the \
         `Poly7` form of `Auto` (the select on the material's exponent becomes a branch). What \
         remains is bound by its chains of dependent operations, not by its count of operations: \
         one iteration of the vectorised loop (four points, SSE2) runs about 370 instructions, \
         more than the processor's window of instructions in flight holds, so successive \
         iterations barely overlap and a cycle taken off the longest chain is a quarter of a cycle \
         a point. The work the baseline does not do, each item measured on this machine by taking \
         it out of a probe loop (DESIGN.md has the probes): full-range normalisation by \
         power-of-two scaling, where the baseline's `normalize` fails on huge and tiny vectors \
         (6.4 cycles a point for N, V and L together, before 2026-11-29 shortened its chain); the \
         squaring ladder of fixed length, whose tests on the exponent are branches (five plain \
         squarings were 2.2 cycles faster before the ladder's first product left the chain, \
         which took 0.6; on 2026-12-07, five plain squarings with neither the ladder's tests nor \
         `Auto`'s never-taken branch to the polynomial were 2.1 cycles a point faster, 1.03× \
         `naive_glam` in the probe, and either one removed alone gained nothing: the lobe's region \
         is fast only without a branch, and both are choices on the material's exponent, a \
         run-time value); the evaluation of an overflowing attenuation denominator on operands \
         scaled into range, which a vectorised loop computes beside the common one for every \
         point (about 1.2); the masks for missing directions, the visibility clamp, the gate and \
         the saturating subtraction. Already taken out of the common path, as branches on what \
         is the same at every point: the window and the second division of the forms that have \
         them, the saturation where the material's sums cannot reach `f32::MAX`, and the \
         zero-vector masks a step or cosine gate makes redundant (0.70× → 0.80× together). Tried \
         and measured slower or wrong: uniform selects on the falloff's form, or choosing between \
         both forms' quotients (slower), the ladder's selects as exact `max` arithmetic on \
         per-exponent constants (no branches, 14% slower), the overflowing denominator's division \
         in `f32` (no faster), colours premultiplied by the material (wrong where products pass \
         `f32::MAX` or underflow), a first `f32` formula for overflowing denominators (lost subnormal \
         factors the fuzz campaign checks; the one now used scales its operands), a ladder without its stop selects (subnormal \
         products, much slower). A loop the compiler cannot see into (a scene passed in, several \
         lights) is scalar: that is `raytrace` above, against scalar hand-written code.\n\
         - **`scalar_opaque`** and **`scalar_lone`**: the one-light form that `Shader::new` \
         prepares is written for a loop the compiler vectorises, and one point at a time it costs \
         about four times `naive_glam`: its full-range normalisations and fixed-length squaring \
         ladder are branch-free, which lengthens each point's chain of dependent operations, and \
         a lone point has no neighbours to overlap with. In this row it also waits for its \
         input: `black_box` writes each point to the stack as an 8-byte and a 4-byte store, \
         and since 2026-11-29's shorter normalisations the one-light form reads it back with an \
         8-byte load that straddles both, which the processor cannot forward from the stores \
         (in a probe, 158 cycles a point; the same loop reading each point through a reference, \
         103; the code before, with loads that matched the stores, 118). No single form found serves both shapes \
         (the range-tested normalisations of the light loop, tried in the one-light form, took \
         `scalar` from 0.87× to 0.69× in a probe), so there are two: `Shader::one_at_a_time` \
         (and `with_viewer`, a ray tracer's call per hit) takes the light loop, whose rare cases \
         are branches the processor predicts (`scalar_lone`). It still runs at a fraction of \
         `naive_glam`, which the compiler vectorises four points at a time; a one-point-per-call \
         caller's own code cannot be vectorised either (`raytrace_one_light`, `fragment`'s \
         callback rows). Shading many points from one place is the batch's job (`batch × naive` \
         in the first table).\n\
         - **`raytrace`, `raytrace_one_light`, `phong_callback`**: one point per call. About \
         half of all lobe bases are `≤ 0`, at random. Until 2026-11-28 the light loop evaluated \
         the power at every point and selected it away: for a textured fragment's own exponent \
         that is `Poly7`'s two dependent polynomials, and LLVM had paired the base's clamp with \
         the visibility's into a mask move and three data-dependent branches per light. Now a \
         Phong base `≤ 0` skips the power by a branch (Blinn-Phong, whose `(N·H)²` is exactly 0 \
         there, keeps a select marked unpredictable: the branch measured slower), and a light's \
         sample no longer clamps a distance it computed itself. On probes of these loops \
         (4096 points, tenth percentile of 2000 interleaved runs): three lights 1.17× → \
         0.92–0.98× the hand-written time, one light 1.09× → about 0.97×, the fragment callback \
         1.5× → 0.94–1.10×. With three lights the probe now runs 532 instructions a hit \
         against the hand-written loop's 535 (631 before): `phong` skips the ladder where the \
         base is `≤ 0` and its `powf` costs the hand-written loop more than the ladder, while \
         `phong` still does work the hand code does not: the normalisation of the viewer \
         direction `with_viewer` does (the hand code trusts its ray direction to be unit), the \
         squaring ladder's tests of the exponent's bits, the falloff's form, the colours widened \
         to `Vec3A` per light, and the saturating `min`s.\n\
         - **`fragment`**: a shininess per point is a per-lane value in the vectorised loop. \
         `Auto` now takes `Poly7` for a point's own exponent at every value (choosing squaring for \
         whole ones ran both forms at every point), and under a light whose sums are bounded a \
         per-point surface saturates its products only: together 177 → 130 instructions a point \
         (callgrind on a probe of this loop; the hand-written loop runs 100, `powf` included), \
         1.5× → 1.3× `hand`'s time. On 2026-11-27 the probe counted 121 against the hand-written \
         loop's 105 (36 of them in `powf`): LLVM vectorises the `phong` loop four points at a \
         time (483 instructions per four points, 104 of them register copies, spills and reloads \
         of SSE2's two-operand form), while the hand-written loop stays scalar around its `powf` \
         call. What remains is the guarantees' work listed for `scalar` \
         (full-range normalisation of N, V and L, the saturating subtractions, the scaled \
         evaluation of an overflowing denominator beside the common one, the clamps) and the \
         sanitising of each point's reflectances; the hand-written loop does none of it. As in \
         `scalar`, the vectorised loop waits on one chain per iteration: read off a trace of one \
         iteration (444 instructions for four fragments) with Zen 4's latencies, its longest \
         chain of dependent operations was about 176 cycles, against about 181 measured, so the \
         iterations barely overlap. About 60 of those cycles were the light direction's \
         full-range normalisation (N's and V's run beside it), 64 the per-point power from its \
         base (the clamp, `log2`, the exponent, `exp2`), and the rest the base, the specular \
         products and the sum (DESIGN.md). Since 2026-11-30 Phong's lobe for a point's own \
         exponent is `((R·V)²)^(s/2)`, the squared base formed from the vectors before their \
         normalisation, so the power no longer waits for the square roots and divisions: \
         45.3 → 40.9 cycles a fragment in the probe (the hand-written loop 42.5).\n\
         - **`batch_frac`** needs `Poly7` (degree 7 `log2`, degree 5 `exp2`) to stay as 8-bit \
         exact as `powf`; every cheaper strategy fails that criterion (table below), and Poly7's \
         two dependent polynomial chains cost about half as much again as the rest of the \
         kernel.\n\
         - **1M** points (24 MiB in, 12 MiB out) do not fit in cache, so memory bandwidth of \
         the shared host bounds the batch there and its ratios vary between runs (two runs \
         above).\n"
    );

    // ---- 8-bit output.
    let table = mpts("srgb8_4096", "linear_to_srgb8", 4096, "new");
    let pipeline = mpts("srgb8_4096", "encode_then_quantize", 4096, "new");
    let batch_f32 = mpts("srgb8_4096", "batch_f32", 4096, "new");
    let batch_rgba8 = mpts("srgb8_4096", "batch_rgba8", 4096, "new");
    let _ = writeln!(
        md,
        "## 8-bit output (`srgb8_4096`)\n\n\
         `linear_to_srgb8` finds each channel's level among the 255 level boundaries (one \
         entry of a 6.5 KiB table indexed by the value's exponent and top seven mantissa bits, \
         then one comparison); `quantize_u8(srgb_encode(x))` computes the same levels through `powf` \
         (they differ only within a few ulps of a boundary: tests in src/colour/srgb8.rs). Million \
         colours per second, 4096 random colours:\n\n\
         | `linear_to_srgb8` | `srgb_encode` + `quantize_u8` | ratio |\n|---:|---:|---:|\n| {} | {} | {} |\n\n\
         A frame shaded straight into 8-bit RGBA (`shade_batch_rgba8`: the kernel encodes each \
         colour in its vector lanes) against `shade_batch`'s linear `f32` output, the \
         benches' Phong scene at s = 32, best level, million points per second:\n\n\
         | `shade_batch` (`f32`) | `shade_batch_rgba8` | ratio |\n|---:|---:|---:|\n| {} | {} | {} |\n\n\
         The pixels are `linear_to_srgb8`'s, bit for bit, at every level \
         (src/batch/srgb8_lanes.rs and its tests). At AVX-512 and AVX2 the lanes compute \
         `255·srgb(x)` to within 9e-4 levels (a table of the binades held in registers, and a \
         polynomial of degree 5, in fixed point: 14 vector operations a channel) and round it \
         by truncating; a channel whose vector has a lane within 9.8e-4 of a rounding boundary \
         takes the table instead (about one in thirty), loaded by `vpgatherdd`. SSE2, NEON and portable load each lane's table \
         entry one by one. On the Zen 4 host of 2026-11 the 16-lane gathers were nearly the whole cost of 8-bit \
         output; DESIGN.md has the measurements. \
         At every level the kernel writes a chunk's pixels after shading the next chunk, so \
         the encoding's chain of dependent operations runs beside that shading. Per level, \
         million points per second:\n",
        fmt_opt(table, 0),
        fmt_opt(pipeline, 0),
        fmt_opt(table.zip(pipeline).map(|(t, p)| t / p), 2),
        fmt_opt(batch_f32, 0),
        fmt_opt(batch_rgba8, 0),
        fmt_opt(batch_f32.zip(batch_rgba8).map(|(f, e)| e / f), 2)
    );
    let _ = writeln!(
        md,
        "| level | `shade_batch` (`f32`) | `shade_batch_rgba8` | ratio |\n|---|---:|---:|---:|"
    );
    for lv in Level::supported() {
        let f = mpts(
            "srgb8_4096",
            &format!("batch_f32/{}", lv.name()),
            4096,
            "new",
        );
        let e = mpts(
            "srgb8_4096",
            &format!("batch_rgba8/{}", lv.name()),
            4096,
            "new",
        );
        let _ = writeln!(
            md,
            "| {} | {} | {} | {} |",
            lv.name(),
            fmt_opt(f, 0),
            fmt_opt(e, 0),
            fmt_opt(f.zip(e).map(|(f, e)| e / f), 2)
        );
    }
    let _ = writeln!(md);

    // ---- Array-of-structs input.
    let aos_row = |group: &str, n: usize| {
        let aos = mpts(group, "shade_batch_aos", n, "new");
        let aos4 = mpts(group, "shade_batch_aos_f32x4", n, "new");
        let copy = mpts(group, "copy_soa", n, "new");
        format!(
            "| {group} | {} | {} | {} | {} |",
            fmt_opt(aos, 0),
            fmt_opt(aos4, 0),
            fmt_opt(copy, 0),
            fmt_opt(aos.zip(copy).map(|(a, c)| a / c), 2)
        )
    };
    let _ = writeln!(
        md,
        "## Array-of-structs input (`aos_4096`, `aos_1m`)\n\n\
         A G-buffer's `&[Vec3]` positions and normals into `&mut [Vec3]` colours: \
         `shade_batch_aos` (1024 points at a time through stack arrays) against copying into \
         preallocated structure-of-arrays `Vec`s, one `shade_batch` call and copying back. The \
         benches' Phong scene at s = 32, best level, million points per second. The second \
         column reads the same points as four-wide `[f32; 4]` texels (`AosVec3`: the fourth \
         component ignored), the layout many G-buffers keep, in place:\n\n\
         | group | `shade_batch_aos` (`Vec3`) | (`[f32; 4]`) | copy + `shade_batch` | ratio (`Vec3`) |\n\
         |---|---:|---:|---:|---:|\n{}\n{}\n",
        aos_row("aos_4096", 4096),
        aos_row("aos_1m", 1 << 20)
    );

    // ---- G-buffer.
    let frac = mpts("gbuffer_4096", "batch_frac", 4096, "new");
    let gb_f32 = mpts("gbuffer_4096", "gbuffer_f32", 4096, "new");
    let gb_rgba8 = mpts("gbuffer_4096", "gbuffer_rgba8", 4096, "new");
    let gb_albedo8 = mpts("gbuffer_4096", "gbuffer_albedo8_rgba8", 4096, "new");
    let gb_terms = mpts("gbuffer_4096", "gbuffer_terms", 4096, "new");
    let gb_f32_tinted = mpts("gbuffer_4096", "gbuffer_f32_tinted", 4096, "new");
    let gb_rgba8_tinted = mpts("gbuffer_4096", "gbuffer_rgba8_tinted", 4096, "new");
    let gb_runs = mpts("gbuffer_4096", "gbuffer_rgba8_shadow_runs", 4096, "new");
    let gb_far = mpts("gbuffer_4096", "gbuffer_rgba8_far_side_runs", 4096, "new");
    let gb_acc = gbuffer_accuracy(&p, &nn, &soa);
    let _ = writeln!(
        md,
        "## G-buffer (`gbuffer_4096`)\n\n\
         Deferred shading through `shade_gbuffer`: per-point textured colours, a per-point \
         shininess uniform in [2, 128] (fractional), and a shadow factor per point, into linear \
         `f32` and into 8-bit RGBA (`shade_gbuffer_rgba8`), against `batch_frac` (`shade_batch`, \
         the same points under one material of shininess 20.5). Phong, one point light, best \
         level, million points per second. Every array of the group is carved from one buffer \
         at staggered 4 KiB offsets, as `batch_frac`'s are (until 2026-11-28 they were separate \
         `Vec`s that started 16 bytes apart within a page, and 4 KiB aliasing between their \
         loads and stores cost the G-buffer rows about a tenth in interleaved runs; a renderer \
         whose planes are separate page-aligned allocations meets the same aliasing):\n\n\
         | `batch_frac` | `shade_gbuffer` (`f32`) | ratio | `shade_gbuffer_rgba8` | ratio | \
         RGBA8 with 8-bit sRGB albedo | ratio | `shade_gbuffer_terms` | ratio | `batch_frac` at \
         `259b7f8` |\n\
         |---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n\
         | {} | {} | {} | {} | {} | {} | {} | {} | {} | {} |\n\n\
         The RGBA8-with-albedo pair reads the texels as a renderer keeps them, 8-bit sRGB \
         (`GBuffer::with_albedo_srgb8`, decoded in the kernel by a gather per channel from a \
         256-entry table), in place of \
         linear `f32` reflectances. The last pair writes the three terms apart (`SoaTerms`: nine \
         `f32` slices, 36 bytes a point against the total's 12).\n\n\
         The group's light is grey, as LearnOpenGL's are (`Vec3::splat` colours). Where every \
         light and the scene's ambient light are grey, the kernel keeps one light sum per term \
         instead of one per channel (the same bits: every channel's sums are the same \
         operations on the same values). Under a tinted light (diffuse colour × (1, 0.9, 0.8), \
         the `_tinted` rows) the same calls shade {} M points/s into `f32` ({}× `batch_frac`) \
         and {} into RGBA8 ({}×).\n\n\
         `259b7f8` is `batch_frac` as it was at that commit (`phong_4096`: the same scene, \
         shininess and number of points), from the baseline `b259` run just before this run: \
         the one-material speed the G-buffer target was set against. The targets table above \
         gives the 8-bit rows against both.\n\n\
         **Shadows in runs.** The group's shadow factors are drawn point by point (30% lit, 10% \
         soft, 60% dark), so no chunk of 16 points is dark throughout. A shadow map's dark \
         regions are contiguous; where a light's visibility is 0 across a whole chunk the kernel \
         adds that light's ambient part alone (the same bits as shading it). With the same \
         proportions in runs of 64 points (`gbuffer_rgba8_shadow_runs`), the RGBA8 call shades \
         {} M points/s ({}× `gbuffer_rgba8`). The test per light and chunk costs the rows \
         without dark chunks about 1–2% (interleaved runs on the Zen 4 host when it came in, \
         2026-11-29). The same skip takes a light that lies behind every point of a chunk \
         (N·L ≤ 0 in all 16 lanes, as across a lit sphere's far side), where the model's gate \
         zeroes the lobe behind the surface: with half the runs of 64 points turned away from \
         the light (`gbuffer_rgba8_far_side_runs`), {} M points/s ({}× `gbuffer_rgba8`).\n\n\
         Why it is slower than one material: the gap is the number of instructions, not their \
         rate (callgrind per kernel instance, DESIGN.md). A per-point surface is ten more \
         vectors to load and sanitise per chunk (five here, where `ambient` and `diffuse` are \
         one slice and the three `specular` planes another, which the kernel loads once); its \
         `Auto` pow is the polynomial in every lane (a point's own exponent, whole or not); it keeps the three light sums apart (three \
         accumulators here, where the light is grey, nine for coloured lights; then their \
         saturation and products with the surface at the end) instead of the one folded sum a \
         single material allows; each 16-lane vector is two of AVX2's sixteen \
         registers, so about a fifth of its instructions were moves to and from the stack \
         with nine accumulators (a seventh of `batch_frac`'s); and \
         the 8-bit encoding adds three table lookups a point at AVX2 and about 55 vector \
         operations a chunk at AVX-512 (section above). Eight lanes a step \
         at the AVX2 level, which halves the registers each vector takes, measured about a \
         quarter slower for both calls: the loop is bound by its dependency chains, and two \
         independent halves per vector are what hides their latency. Thirty-two lanes a step \
         at AVX-512 (two 512-bit registers per vector) gave no gain: there the chunk is bound \
         by its count of vector operations, about 290 (in a probe, each operation added to a \
         chunk cost most of a cycle, scalar ones almost nothing: DESIGN.md). \
         Every level runs its own instructions for these calls (the one kernel source).\n\n\
         Accuracy on the 2²⁰ accuracy points, each with its own random texel, specular strength, \
         shininess in [2, 128] and shadow factor in [0, 1], against the same equation in `f64`: \
         max abs error {:.1e}, 8-bit mismatch {:.2e}, to compare with the one-material batch \
         path's rows in the pow-strategy table below (`Poly7` at 20.5).\n",
        fmt_opt(frac, 0),
        fmt_opt(gb_f32, 0),
        fmt_opt(frac.zip(gb_f32).map(|(a, b)| b / a), 2),
        fmt_opt(gb_rgba8, 0),
        fmt_opt(frac.zip(gb_rgba8).map(|(a, b)| b / a), 2),
        fmt_opt(gb_albedo8, 0),
        fmt_opt(frac.zip(gb_albedo8).map(|(a, b)| b / a), 2),
        fmt_opt(gb_terms, 0),
        fmt_opt(frac.zip(gb_terms).map(|(a, b)| b / a), 2),
        fmt_opt(mpts("phong_4096", "batch_frac", 4096, "b259"), 0),
        fmt_opt(gb_f32_tinted, 0),
        fmt_opt(frac.zip(gb_f32_tinted).map(|(a, b)| b / a), 2),
        fmt_opt(gb_rgba8_tinted, 0),
        fmt_opt(frac.zip(gb_rgba8_tinted).map(|(a, b)| b / a), 2),
        fmt_opt(gb_runs, 0),
        fmt_opt(gb_rgba8.zip(gb_runs).map(|(a, b)| b / a), 2),
        fmt_opt(gb_far, 0),
        fmt_opt(gb_rgba8.zip(gb_far).map(|(a, b)| b / a), 2),
        gb_acc.max_abs,
        gb_acc.mismatch
    );

    // ---- Many cores.
    let serial = mpts("parallel_1m", "serial", 1 << 20, "new");
    let threaded = mpts("parallel_1m", "threads", 1 << 20, "new");
    let serial8 = mpts("parallel_1m", "serial_rgba8", 1 << 20, "new");
    let threaded8 = mpts("parallel_1m", "threads_rgba8", 1 << 20, "new");
    let _ = writeln!(
        md,
        "## Many cores (`parallel_1m`)\n\n\
         The batch module's recipe: 2²⁰ points in plain `Vec`s, one `shade_batch` call against one \
         part per core on scoped threads (bit-identical output: tests/batch_parallel.rs), into \
         linear `f32` (12 bytes a point) and into 8-bit RGBA (`shade_batch_rgba8`, 4 bytes). Phong, \
         s = 32, one point light; this machine has {} cores.\n\n\
         | output | serial (Mpts/s) | threads (Mpts/s) | threads ÷ serial |\n|---|---:|---:|---:|\n\
         | `f32` | {} | {} | {} |\n| RGBA8 | {} | {} | {} |\n",
        std::thread::available_parallelism().map_or(1, |t| t.get()),
        fmt_opt(serial, 0),
        fmt_opt(threaded, 0),
        fmt_opt(serial.zip(threaded).map(|(s, t)| t / s), 2),
        fmt_opt(serial8, 0),
        fmt_opt(threaded8, 0),
        fmt_opt(serial8.zip(threaded8).map(|(s, t)| t / s), 2)
    );

    // ---- Spot lights and other falloffs.
    let falloff_batch = mpts("falloff_4096", "batch", 4096, "new");
    let falloff_shade = mpts("falloff_4096", "shade", 4096, "new");
    let _ = writeln!(
        md,
        "## Spot lights and other falloffs (`falloff_4096`)\n\n\
         A spot light (60°, exponent 4.5, inverse-square falloff) and a point light with Unreal's \
         windowed falloff, Phong, s = 32, 4096 points: the batch kernel, which evaluates these \
         lights in vector arithmetic (direction, distance and falloff by the scalar path's own \
         operations, the spot cone's power by `PowStrategy::Auto`'s plan), against `shade` point \
         by point, which is how the batch shaded a call with such a light before (million points \
         per second). Until 2026-11-29 the kernel took these lights' factors lane by lane in \
         scalar code, with `powf` for the cone: 39–42 M points/s on the Zen 4 host in interleaved \
         runs, against 225–230 after the change.\n\n\
         | `batch` | `shade` | batch ÷ shade |\n|---:|---:|---:|\n| {} | {} | {} |\n",
        fmt_opt(falloff_batch, 0),
        fmt_opt(falloff_shade, 0),
        fmt_opt(falloff_batch.zip(falloff_shade).map(|(b, s)| b / s), 1)
    );

    // ---- Many lights: per-tile culling.
    let every = mpts("tiled_64_lights", "gbuffer", 256 * 128, "new");
    let culled = mpts("tiled_64_lights", "tiled", 256 * 128, "new");
    let _ = writeln!(
        md,
        "## Many lights: per-tile culling (`tiled_64_lights`)\n\n\
         64 point lights 2 units above a bumpy 128 × 64 floor seen as a 256 × 128 G-buffer, with \
         LearnOpenGL's falloff `1/(1 + 0.7d + 1.8d²)` (below 1e-3 past d ≈ 23), Phong, s = 32: every \
         light at every pixel (`shade_gbuffer`) against 16 × 16 tiles, each shaded with the lights \
         whose factor reaches 1e-3 somewhere in it (`shade_gbuffer_tiled`; the difference is \
         bounded in `TileCulling`'s docs and tested in tests/gbuffer.rs). Million points per second. \
         Until 2026-11-29 lights past the eighth were prepared for every chunk of 16 points and the \
         tiled call ran the kernel once per row of a tile; interleaved runs on the Zen 4 host before and \
         after those two changes: every light 4.9–6.3 → 10.2–10.9, tiled 13.4–17.1 → 35.1–37.1.\n\n\
         | every light | tiled | tiled ÷ every light |\n|---:|---:|---:|\n| {} | {} | {} |\n",
        fmt_opt(every, 1),
        fmt_opt(culled, 1),
        fmt_opt(every.zip(culled).map(|(e, t)| t / e), 2)
    );

    // ---- Other architectures.
    let _ = writeln!(
        md,
        "## aarch64: tested, not measured\n\n\
         On aarch64 (Apple silicon, Graviton, Raspberry Pi) the batch path runs the `Neon` level: \
         the one kernel source on four `float32x4_t` per 16 lanes, with fused multiply-adds and \
         NEON's inverse square root (`frsqrte` and two Newton steps by `frsqrts`) in place of a \
         square root and a division per lane. CI cross-compiles the crate's whole test suite for \
         `aarch64-unknown-linux-gnu` and runs it under qemu, so the batch-vs-scalar comparisons \
         run there at the `Portable` and `Neon` levels (with the earlier NEON loops, one Newton \
         step instead of two failed 8 of the 17 batch tests). Nothing here measures aarch64 speed: \
         qemu's timings say nothing about a real core. What qemu can count is executed \
         instructions: docs/instruction-counts.md gives them per point for each batch form at \
         the `Neon` and `Portable` levels, beside x86_64's portable, SSE2 and AVX2 counted by \
         valgrind (`bash scripts/count-instructions.sh` writes it).\n"
    );

    // ---- Strategies.
    let mut exact_rate = [0.0; 2];
    let mut chart = Vec::new();
    let _ = writeln!(md, "## Pow strategies\n");
    let _ = writeln!(
        md,
        "`x^s` alone, max relative error against f64 where `x^s ≥ 2⁻²⁴` (`s` from 0.5 to 511.3):\n"
    );
    let _ = writeln!(md, "| strategy | max relative error |\n|---|---:|");
    for &pw in PowStrategy::ALL {
        let _ = writeln!(md, "| {} | {:.2e} |", pw.name(), pow_error(pw));
    }
    let _ = writeln!(
        md,
        "\nWhole shading, batch path at level `{level}`, N = 4096 for speed, 2²⁰ points for \
         accuracy (`–`: not measured or not applicable; `squaring` at 20.5 falls back to `powf`):\n"
    );
    let _ = writeln!(
        md,
        "| model | s | strategy | Mpts/s | × naive | max abs error | 8-bit mismatch |"
    );
    let _ = writeln!(md, "|---|---:|---|---:|---:|---:|---:|");
    for (ki, kind) in [Kind::Phong, Kind::Blinn].into_iter().enumerate() {
        let naive = mpts(&format!("{}_4096", kind.name()), "naive_glam", 4096, "new");
        for s in [32.0f32, 20.5] {
            let reference: Vec<DVec3> = p
                .iter()
                .zip(&nn)
                .map(|(&p, &n)| reference(kind, s as f64, p, n))
                .collect();
            let ex = compare(&scalar_exact(kind, s, &p, &nn), &reference);
            if s == 20.5 {
                exact_rate[ki] = ex.mismatch;
            }
            let _ = writeln!(
                md,
                "| {} | {s} | scalar `shade`, exact powf | – | – | {:.1e} | {:.2e} |",
                kind.name(),
                ex.max_abs,
                ex.mismatch
            );
            let au = compare(&scalar_auto(kind, s, &p, &nn), &reference);
            let _ = writeln!(
                md,
                "| {} | {s} | scalar `Shader`, auto | – | – | {:.1e} | {:.2e} |",
                kind.name(),
                au.max_abs,
                au.mismatch
            );
            for pw in PowStrategy::ALL.iter().copied().chain([PowStrategy::Auto]) {
                let acc = compare(&batch_out(level, kind, pw, s, &soa), &reference);
                let speed = mpts(
                    "pow_4096",
                    &format!("{}/{}_{}", kind.name(), pw.name(), s),
                    4096,
                    "new",
                );
                let ratio = speed.zip(naive).map(|(a, b)| a / b);
                let _ = writeln!(
                    md,
                    "| {} | {s} | {} | {} | {} | {:.1e} | {:.2e} |",
                    kind.name(),
                    pw.name(),
                    fmt_opt(speed, 0),
                    fmt_opt(ratio, 2),
                    acc.max_abs,
                    acc.mismatch
                );
                if s == 20.5
                    && pw != PowStrategy::Squaring
                    && let Some(v) = speed
                {
                    chart.push(Point {
                        label: format!("{} {}", kind.name(), pw.name()),
                        mpts: v,
                        mismatch: acc.mismatch,
                        kind,
                    });
                }
            }
        }
    }

    // ---- Levels.
    let _ = writeln!(
        md,
        "\n## Dispatch levels\n\nThe batch path forced to each level this CPU runs \
         (`PowStrategy::Auto`, N = 4096 for speed, 2²⁰ points for accuracy). `÷ AVX-512` is the \
         level's throughput over the AVX-512 level's for the same model and shininess, in this \
         run. `259b7f8` is the same bench at commit 259b7f8 (the AVX-512 intrinsics kernel and \
         the auto-vectorised levels that the one kernel source replaced), run just before this \
         run on the same machine and saved as criterion baseline `b259`:\n\n\
         ```text\ngit worktree add /tmp/b259 259b7f8 && (cd /tmp/b259 && cargo bench --bench \
         shading --no-run)\n/tmp/b259/target/release/deps/shading-<hash> --bench \
         'levels_4096|phong_4096/batch_frac$' --save-baseline b259   # from this repository's \
         root\n```\n\nIt must run before this run's benches, not after: `--save-baseline` \
         writes its results to `new/` too, which this run's then replace. The tool refuses to \
         write these tables from a `new/` that is a copy of a baseline. Until 2026-12-06 the \
         tables of 2026-11-30 did that: the baseline had been run again after the benches, and \
         every row of this table and `phong_4096`'s `batch_frac` showed 259b7f8's figures as \
         this run's.\n"
    );
    if !Level::supported().any(|lv| lv == Level::Avx512) {
        let _ = writeln!(
            md,
            "**This CPU has no AVX-512**, so this run has no AVX-512 row and no `÷ AVX-512` \
             ratio: the levels' targets relative to AVX-512 are not measured here. An earlier run \
             on an AVX-512 machine is in this file's git history.\n"
        );
    }
    if cfg!(any(target_arch = "x86_64", target_arch = "aarch64")) {
        let _ = writeln!(
            md,
            "On this architecture `portable` runs only when forced, and it is compiled as the \
             kernel's one general form (no folded products, no instance for calls without \
             per-point inputs: `Level`'s docs), which keeps the build small. Its row is that form, \
             slower than the specialised portable kernel a target without vector levels runs, and \
             than this row at 259b7f8.\n"
        );
    }
    let _ = writeln!(
        md,
        "| level | model | s | Mpts/s | ÷ AVX-512 | 259b7f8 Mpts/s | max abs error | 8-bit mismatch |\n\
         |---|---|---:|---:|---:|---:|---:|---:|"
    );
    for lv in Level::supported() {
        for kind in [Kind::Phong, Kind::Blinn] {
            for s in [32.0f32, 20.5] {
                let reference: Vec<DVec3> = p
                    .iter()
                    .zip(&nn)
                    .map(|(&p, &n)| reference(kind, s as f64, p, n))
                    .collect();
                let acc = compare(&batch_out(lv, kind, PowStrategy::Auto, s, &soa), &reference);
                let speed = mpts(
                    "levels_4096",
                    &format!("{}/{}_{}", kind.name(), lv.name(), s),
                    4096,
                    "new",
                );
                let top = mpts(
                    "levels_4096",
                    &format!("{}/avx512_{}", kind.name(), s),
                    4096,
                    "new",
                );
                let before = mpts(
                    "levels_4096",
                    &format!("{}/{}_{}", kind.name(), lv.name(), s),
                    4096,
                    "b259",
                );
                let _ = writeln!(
                    md,
                    "| {lv} | {} | {s} | {} | {} | {} | {:.1e} | {:.2e} |",
                    kind.name(),
                    fmt_opt(speed, 0),
                    fmt_opt(speed.zip(top).map(|(a, b)| a / b), 2),
                    fmt_opt(before, 0),
                    acc.max_abs,
                    acc.mismatch
                );
            }
        }
    }

    let _ = writeln!(
        md,
        "\n## Chart\n\n![speed vs accuracy](speed_vs_accuracy.svg)\n\nEach point is one pow \
         strategy in the batch path at shininess 20.5 (criterion median at N = 4096 against the \
         8-bit mismatch rate on 2²⁰ points); the dashed lines are the exact f32 scalar path's own \
         rate. Lower right is better."
    );
    let docs = workspace_root().join("docs");
    std::fs::create_dir_all(&docs).expect("create docs/");
    std::fs::write(docs.join("speed_vs_accuracy.svg"), svg(&chart, exact_rate))
        .expect("write the chart");
    std::fs::write(docs.join("performance.md"), &md).expect("write the table");
    print!("{md}");
}

#[cfg(test)]
mod tests {
    use super::baseline_copied_to_new;
    use std::path::{Path, PathBuf};

    /// A criterion benchmark directory under the system's temporary directory, with the given
    /// `estimates.json` contents per subdirectory.
    fn bench_dir(tag: &str, files: &[(&str, &str)]) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("phong-performance-{tag}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        for (sub, text) in files {
            std::fs::create_dir_all(dir.join(sub)).unwrap();
            std::fs::write(dir.join(sub).join("estimates.json"), text).unwrap();
        }
        dir
    }

    fn check(dir: &Path) -> Option<String> {
        let found = baseline_copied_to_new(dir);
        std::fs::remove_dir_all(dir).unwrap();
        found
    }

    #[test]
    fn a_baseline_run_after_this_run_is_caught() {
        // What `--save-baseline b259` leaves when it runs last: `new` and `b259` the same file.
        let copied = r#"{"median":{"point_estimate":8234.567}}"#;
        let dir = bench_dir(
            "copied",
            &[("new", copied), ("b259", copied), ("base", copied)],
        );
        assert_eq!(check(&dir).as_deref(), Some("b259"));
    }

    #[test]
    fn separate_runs_and_criterion_own_copy_pass() {
        let dir = bench_dir(
            "separate",
            &[
                ("new", r#"{"median":{"point_estimate":8234.567}}"#),
                ("b259", r#"{"median":{"point_estimate":8310.002}}"#),
                // `base` is criterion's own bookkeeping, never a baseline the docs read.
                ("base", r#"{"median":{"point_estimate":8234.567}}"#),
            ],
        );
        assert_eq!(check(&dir), None);
        assert_eq!(check(&bench_dir("lonely", &[("new", "{}")])), None);
    }
}
