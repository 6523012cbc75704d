//! Snapshot tests: the whole window (controls and picture) in a few fixed states, rendered by
//! egui's wgpu renderer through whatever adapter the machine has (Mesa's lavapipe in CI), compared
//! with the PNGs in `tests/snapshots/`. Update them with `UPDATE_SNAPSHOTS=1 cargo test -p explorer
//! --test snapshots` and look at the new PNGs before committing them.
//!
//! Without a GPU adapter the tests say so and pass, unless `PHONG_REQUIRE_GPU=1` (as in CI), which
//! makes a missing adapter a failure.

use egui_kittest::kittest::Queryable;
use egui_kittest::wgpu::WgpuTestRenderer;
use egui_kittest::{Harness, SnapshotResults};
use explorer::{App, Encoding, ModelKind, Params, Shape};
use phong::SpecularGate;
use raster::ShadingMode;

/// The wgpu renderer, or `None` (after saying why) when the machine has no adapter.
fn renderer() -> Option<WgpuTestRenderer> {
    // egui_kittest panics when it finds no adapter; turn that into a skip.
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let r = std::panic::catch_unwind(WgpuTestRenderer::new);
    std::panic::set_hook(hook);
    match r {
        Ok(r) => Some(r),
        Err(e) => {
            let why = e
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| e.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default();
            if std::env::var_os("PHONG_REQUIRE_GPU").is_some_and(|v| v != "0") {
                panic!("PHONG_REQUIRE_GPU is set but no wgpu adapter was found: {why}");
            }
            eprintln!("skipping snapshot test: no wgpu adapter ({why})");
            None
        }
    }
}

/// The window size of the snapshots, in points (and pixels).
const SIZE: [f32; 2] = [860.0, 800.0];

fn snapshot(results: &mut SnapshotResults, name: &str, params: Params) {
    let Some(renderer) = renderer() else { return };
    let mut h = Harness::builder()
        .with_size(SIZE)
        .with_pixels_per_point(1.0)
        .renderer(renderer)
        .build_ui_state(|ui, app: &mut App| app.ui(ui), App::new(params));
    h.run();
    // The frame time differs from run to run: cover its line up to the window's right edge (the
    // line's length changes with the number).
    let timing = h.get_by_label_contains("Frame time:").rect();
    h.mask(egui::Rect::from_min_max(
        timing.min,
        egui::pos2(SIZE[0], timing.max.y),
    ));
    results.add(h.try_snapshot(name));
}

fn base() -> Params {
    Params {
        size: [256, 256],
        ..Params::default()
    }
}

#[test]
fn snapshots_of_fixed_states() {
    let mut results = SnapshotResults::new();
    // The start-up state: Phong, adaptive shading on a low-poly sphere, sRGB.
    snapshot(&mut results, "default", base());
    // LearnOpenGL's lit cube, per vertex: the faces' two triangles miss the highlight.
    snapshot(
        &mut results,
        "cube_per_vertex",
        Params {
            shape: Shape::Cube,
            frequency: ShadingMode::PerVertex,
            ..base()
        },
    );
    // Blinn-Phong at low shininess without a gate, written linear.
    snapshot(
        &mut results,
        "blinn_linear_no_gate",
        Params {
            model: ModelKind::BlinnPhong,
            gate: SpecularGate::None,
            shininess: 4.0,
            encoding: Encoding::Linear,
            light: glam::Vec3::new(-2.0, 1.5, 1.0),
            ..base()
        },
    );
    // Lambert per pixel on a smooth sphere.
    snapshot(
        &mut results,
        "lambert_per_pixel",
        Params {
            model: ModelKind::Lambert,
            frequency: ShadingMode::PerPixel,
            subdivisions: 4,
            ..base()
        },
    );
}
