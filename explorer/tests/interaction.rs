//! The explorer driven headlessly by egui_kittest: move a slider or click a radio button through
//! the accessibility tree, then check the state and that the picture changed. No GPU or display
//! is needed (nothing here is rendered to pixels by egui).

use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable;
use explorer::{App, Encoding, ModelKind, Params, Shape};
use phong::SpecularGate;
use raster::{Image, ShadingMode};

/// A small picture keeps the tests fast in debug builds.
fn small() -> Params {
    Params {
        size: [120, 120],
        ..Params::default()
    }
}

fn harness(params: Params) -> Harness<'static, App> {
    Harness::builder()
        .with_size([900.0, 900.0])
        .build_ui_state(|ui, app: &mut App| app.ui(ui), App::new(params))
}

/// A slider by its label (its value box carries the same label, with another role).
fn slider<'a>(h: &'a Harness<'_, App>, label: &'a str) -> egui_kittest::Node<'a> {
    h.get_by_role_and_label(Role::Slider, label)
}

fn image(h: &Harness<'_, App>) -> Image {
    h.state()
        .last_frame()
        .expect("a frame was rendered")
        .image
        .clone()
}

fn mean_luma(img: &Image) -> f64 {
    let sum: u64 = img
        .pixels
        .iter()
        .map(|p| p.iter().map(|&c| u64::from(c)).sum::<u64>())
        .sum();
    sum as f64 / (3 * img.pixels.len()) as f64
}

fn changed_pixels(a: &Image, b: &Image) -> usize {
    assert_eq!((a.width, a.height), (b.width, b.height));
    a.pixels
        .iter()
        .zip(&b.pixels)
        .filter(|(x, y)| x != y)
        .count()
}

#[test]
fn shininess_slider_sets_the_state_and_changes_the_highlight() {
    let mut h = harness(small());
    let before = image(&h);
    slider(&h, "Shininess").set_value_accesskit(4.0);
    h.run();
    assert_eq!(h.state().params.shininess, 4.0);
    let after = image(&h);
    // A broad lobe: the highlight spreads over many pixels.
    assert!(
        changed_pixels(&before, &after) > 200,
        "{}",
        changed_pixels(&before, &after)
    );
}

#[test]
fn strength_sliders_brighten_and_darken() {
    let mut h = harness(small());
    let base = mean_luma(&image(&h));
    slider(&h, "Ambient strength").set_value_accesskit(0.8);
    h.run();
    assert_eq!(h.state().params.ambient, 0.8);
    let brighter = mean_luma(&image(&h));
    assert!(brighter > base + 5.0, "{base} → {brighter}");
    slider(&h, "Diffuse strength").set_value_accesskit(0.0);
    slider(&h, "Specular strength").set_value_accesskit(0.0);
    h.run();
    assert_eq!(h.state().params.diffuse, 0.0);
    assert_eq!(h.state().params.specular, 0.0);
    assert!(mean_luma(&image(&h)) < brighter);
}

#[test]
fn light_and_rotation_sliders_move_the_lighting() {
    let mut h = harness(Params {
        shape: Shape::Cube,
        ..small()
    });
    let start = image(&h);
    slider(&h, "Light x").set_value_accesskit(-3.0);
    h.run();
    assert_eq!(h.state().params.light.x, -3.0);
    let lit_left = image(&h);
    assert!(changed_pixels(&start, &lit_left) > 500);
    slider(&h, "Rotate y").set_value_accesskit(45.0);
    h.run();
    assert_eq!(h.state().params.rotation.y, 45.0);
    assert!(changed_pixels(&lit_left, &image(&h)) > 500);
}

#[test]
fn model_radio_buttons_switch_the_model() {
    let mut h = harness(small());
    let phong = image(&h);
    h.get_by_label("Blinn-Phong").click();
    h.run();
    assert_eq!(h.state().params.model, ModelKind::BlinnPhong);
    let blinn = image(&h);
    assert!(changed_pixels(&phong, &blinn) > 50);
    h.get_by_label("Lambert").click();
    h.run();
    assert_eq!(h.state().params.model, ModelKind::Lambert);
    // No specular term at all: darker on average.
    assert!(mean_luma(&image(&h)) < mean_luma(&blinn));
}

#[test]
fn gate_radio_buttons_show_the_back_face_halo() {
    // Light behind the sphere, viewer in front: only an ungated lobe lights the rim.
    let mut h = harness(Params {
        light: glam::Vec3::new(0.0, 0.0, -3.0),
        ambient: 0.0,
        shininess: 2.0,
        ..small()
    });
    let step = image(&h);
    h.get_by_label("No gate").click();
    h.run();
    assert_eq!(h.state().params.gate, SpecularGate::None);
    assert!(mean_luma(&image(&h)) > mean_luma(&step));
    h.get_by_label("Cosine").click();
    h.run();
    assert_eq!(h.state().params.gate, SpecularGate::Cosine);
}

#[test]
fn shading_frequency_radio_buttons_and_the_advisor() {
    let mut h = harness(small());
    // The default is adaptive: the advisor shades some, not all, triangles per vertex.
    let adaptive = h.state().last_frame().unwrap().stats;
    assert!(
        adaptive.per_vertex > 0 && adaptive.per_vertex < adaptive.triangles,
        "{adaptive:?}"
    );
    let adaptive_image = image(&h);

    h.get_by_label("Per vertex (Gouraud)").click();
    h.run();
    assert_eq!(h.state().params.frequency, ShadingMode::PerVertex);
    let s = h.state().last_frame().unwrap().stats;
    assert_eq!(s.per_vertex, s.triangles);
    assert!(changed_pixels(&adaptive_image, &image(&h)) > 20);
    // The figures are on screen.
    h.get_by_label(&format!(
        "Per vertex: {} of {} visible triangles (100%, all per vertex)",
        s.per_vertex, s.triangles
    ));
    h.get_by_label_contains("Frame time:");

    h.get_by_label("Per pixel (Phong shading)").click();
    h.run();
    assert_eq!(h.state().params.frequency, ShadingMode::PerPixel);
    assert_eq!(h.state().last_frame().unwrap().stats.per_vertex, 0);
}

#[test]
fn adaptive_mode_stays_within_its_tolerance() {
    let mut h = harness(small());
    h.get_by_label("Measure error against per pixel").click();
    h.run();
    let f = h.state().last_frame().unwrap();
    let e = f.max_error_steps.expect("compare mode measures the error");
    assert!(e <= h.state().params.tolerance_steps, "{e}");
    // A looser tolerance lets the advisor shade more triangles per vertex.
    let before = f.stats.per_vertex;
    slider(&h, "Tolerance (/255)").set_value_accesskit(16.0);
    h.run();
    let f = h.state().last_frame().unwrap();
    assert!(
        f.stats.per_vertex > before,
        "{} vs {before}",
        f.stats.per_vertex
    );
    assert!(f.max_error_steps.unwrap() <= 16.0);
}

#[test]
fn encoding_radio_buttons_switch_between_linear_and_srgb() {
    let mut h = harness(small());
    let srgb = mean_luma(&image(&h));
    h.get_by_label("Linear").click();
    h.run();
    assert_eq!(h.state().params.encoding, Encoding::Linear);
    // Linear values shown without encoding are darker.
    assert!(mean_luma(&image(&h)) < srgb);
}

#[test]
fn object_choice_and_reset() {
    let mut h = harness(small());
    h.get_by_label("Cube").click();
    h.run();
    assert_eq!(h.state().params.shape, Shape::Cube);
    assert_eq!(h.state().last_frame().unwrap().stats.triangles, 6);
    h.get_by_label("Sphere").click();
    slider(&h, "Sphere subdivisions").set_value_accesskit(1.0);
    h.run();
    assert_eq!(h.state().params.subdivisions, 1);
    h.get_by_label("Reset").click();
    h.run();
    // Reset keeps the render size and restores everything else.
    assert_eq!(h.state().params, small());
}

#[test]
fn no_rerender_without_a_change() {
    let mut h = harness(small());
    let first = h.state().last_frame().unwrap().elapsed;
    h.run();
    h.run();
    // The same frame (same timing) is kept while nothing changes.
    assert_eq!(h.state().last_frame().unwrap().elapsed, first);
}

#[test]
fn fitted_to_window_renders_at_the_pictures_size() {
    let h = Harness::builder()
        .with_size([700.0, 500.0])
        .with_pixels_per_point(1.0)
        .build_ui_state(
            |ui, app: &mut App| app.ui(ui),
            App::new(small()).fitted_to_window(),
        );
    let [w, hgt] = h.state().params.size;
    // Square, a multiple of 16, and filling the room left of the 350-point panel.
    assert_eq!(w, hgt);
    assert_eq!(w % 16, 0);
    assert!((256..=416).contains(&w), "{w}");
    assert_eq!(image(&h).width, w);
}
