//! The explorer: `phong`'s reflection models behind sliders, rendered on the CPU by `raster`.
//!
//! [`App`] holds the state ([`Params`] and the last [`Frame`]); [`App::ui`] draws the panel and
//! the picture into any [`egui::Ui`] (eframe's window in `main.rs`, or egui_kittest's headless
//! harness in the tests); [`render::render`] turns parameters into an image without any UI.

pub mod render;

use std::collections::BTreeMap;
use std::time::Duration;

use egui::{Color32, ColorImage, Rect, TextureHandle, TextureOptions};
use phong::SpecularGate;
use raster::ShadingMode;

pub use render::{Encoding, Frame, ModelKind, Params, Shape, render, render_compared};

/// The explorer's state: the parameters, the last frame and its texture.
pub struct App {
    /// What the controls set.
    pub params: Params,
    /// Also render per pixel and show the largest difference (costs a second render).
    pub compare: bool,
    /// Render at the size the picture has on screen (the window) instead of `params.size`.
    pub fit_to_window: bool,
    /// The last rendered frame and the parameters it was rendered with.
    rendered: Option<(Params, bool, Frame)>,
    texture: Option<TextureHandle>,
    /// Print the screen rectangles of the controls to stdout when they change (for the Xvfb
    /// end-to-end script: `EXPLORER_PRINT_LAYOUT=1`).
    print_layout: bool,
    layout: BTreeMap<&'static str, [i32; 4]>,
    printed_layout: BTreeMap<&'static str, [i32; 4]>,
}

impl Default for App {
    fn default() -> Self {
        App::new(Params::default())
    }
}

impl App {
    /// An explorer starting at `params`.
    #[must_use]
    pub fn new(params: Params) -> Self {
        App {
            params,
            compare: false,
            fit_to_window: false,
            rendered: None,
            texture: None,
            print_layout: std::env::var_os("EXPLORER_PRINT_LAYOUT").is_some_and(|v| v != "0"),
            layout: BTreeMap::new(),
            printed_layout: BTreeMap::new(),
        }
    }

    /// The same explorer, rendering at the picture's size on screen (see
    /// [`fit_to_window`](Self::fit_to_window)).
    #[must_use]
    pub fn fitted_to_window(self) -> Self {
        App {
            fit_to_window: true,
            ..self
        }
    }

    /// The last rendered frame (after at least one [`ui`](Self::ui) or [`frame`](Self::frame)).
    #[must_use]
    pub fn last_frame(&self) -> Option<&Frame> {
        self.rendered.as_ref().map(|(_, _, f)| f)
    }

    /// The frame for the current parameters, rendering it if they changed since the last one.
    pub fn frame(&mut self) -> &Frame {
        let stale = match &self.rendered {
            Some((p, c, _)) => *p != self.params || *c != self.compare,
            None => true,
        };
        if stale {
            let frame = if self.compare {
                render_compared(&self.params)
            } else {
                render(&self.params)
            };
            self.rendered = Some((self.params, self.compare, frame));
            self.texture = None;
        }
        &self.rendered.as_ref().expect("rendered above").2
    }

    /// Draws the controls (a left panel) and the picture with its figures (the rest) into `ui`.
    pub fn ui(&mut self, ui: &mut egui::Ui) {
        self.layout.clear();
        egui::Panel::left("controls")
            .resizable(false)
            .exact_size(350.0)
            .show(ui, |ui| {
                egui::ScrollArea::vertical().show(ui, |ui| self.controls(ui));
            });
        egui::CentralPanel::default().show(ui, |ui| self.picture(ui));
        if self.print_layout && self.layout != self.printed_layout {
            let ppp = ui.ctx().pixels_per_point();
            for (name, [x, y, w, h]) in &self.layout {
                println!("layout {name} {x} {y} {w} {h} ppp={ppp}");
            }
            println!("layout-end");
            self.printed_layout = self.layout.clone();
        }
    }

    /// Records where a widget is, in physical pixels, for `EXPLORER_PRINT_LAYOUT`.
    fn remember(&mut self, ui: &egui::Ui, name: &'static str, rect: Rect) {
        if self.print_layout {
            let ppp = ui.ctx().pixels_per_point();
            let r = [rect.min.x, rect.min.y, rect.width(), rect.height()].map(|v| (v * ppp) as i32);
            self.layout.insert(name, r);
        }
    }

    /// Records a slider's rail (a slider's response also covers its value box and label).
    fn remember_slider(&mut self, ui: &egui::Ui, name: &'static str, rect: Rect) {
        let rail = Rect::from_min_size(
            rect.min,
            egui::vec2(ui.spacing().slider_width, rect.height()),
        );
        self.remember(ui, name, rail);
    }

    fn controls(&mut self, ui: &mut egui::Ui) {
        ui.spacing_mut().slider_width = 150.0;
        let p = &mut self.params;
        ui.heading("phong explorer");

        ui.label("Material and light");
        let r = ui.add(
            egui::Slider::new(&mut p.shininess, 0.5..=256.0)
                .logarithmic(true)
                .text("Shininess"),
        );
        self.remember_slider(ui, "shininess", r.rect);
        let p = &mut self.params;
        ui.add(egui::Slider::new(&mut p.ambient, 0.0..=1.0).text("Ambient strength"));
        ui.add(egui::Slider::new(&mut p.diffuse, 0.0..=2.0).text("Diffuse strength"));
        ui.add(egui::Slider::new(&mut p.specular, 0.0..=2.0).text("Specular strength"));

        ui.separator();
        ui.label("Light position");
        let r = ui.add(egui::Slider::new(&mut p.light.x, -4.0..=4.0).text("Light x"));
        self.remember_slider(ui, "light_x", r.rect);
        let p = &mut self.params;
        ui.add(egui::Slider::new(&mut p.light.y, -4.0..=4.0).text("Light y"));
        ui.add(egui::Slider::new(&mut p.light.z, -4.0..=4.0).text("Light z"));

        ui.separator();
        ui.label("Object rotation (degrees)");
        ui.add(egui::Slider::new(&mut p.rotation.x, -180.0..=180.0).text("Rotate x"));
        ui.add(egui::Slider::new(&mut p.rotation.y, -180.0..=180.0).text("Rotate y"));
        ui.add(egui::Slider::new(&mut p.rotation.z, -180.0..=180.0).text("Rotate z"));

        ui.separator();
        ui.label("Model");
        ui.horizontal(|ui| {
            ui.radio_value(&mut p.model, ModelKind::Lambert, "Lambert");
            ui.radio_value(&mut p.model, ModelKind::Phong, "Phong");
            ui.radio_value(&mut p.model, ModelKind::BlinnPhong, "Blinn-Phong");
        });
        ui.label("Specular gate (when N·L ≤ 0)");
        ui.add_enabled_ui(p.model != ModelKind::Lambert, |ui| {
            ui.horizontal(|ui| {
                ui.radio_value(&mut p.gate, SpecularGate::Step, "Step");
                ui.radio_value(&mut p.gate, SpecularGate::Cosine, "Cosine");
                ui.radio_value(&mut p.gate, SpecularGate::None, "No gate");
            });
        });

        ui.separator();
        ui.label("Shading frequency");
        ui.radio_value(
            &mut p.frequency,
            ShadingMode::PerVertex,
            "Per vertex (Gouraud)",
        );
        ui.radio_value(
            &mut p.frequency,
            ShadingMode::PerPixel,
            "Per pixel (Phong shading)",
        );
        ui.radio_value(
            &mut p.frequency,
            ShadingMode::Adaptive,
            "Adaptive (shading-rate advisor)",
        );
        ui.add_enabled(
            p.frequency == ShadingMode::Adaptive,
            egui::Slider::new(&mut p.tolerance_steps, 0.25..=32.0)
                .logarithmic(true)
                .text("Tolerance (/255)"),
        );
        ui.checkbox(&mut self.compare, "Measure error against per pixel");
        let p = &mut self.params;

        ui.separator();
        ui.label("Output encoding");
        ui.horizontal(|ui| {
            ui.radio_value(&mut p.encoding, Encoding::Srgb, "sRGB");
            ui.radio_value(&mut p.encoding, Encoding::Linear, "Linear");
        });

        ui.separator();
        ui.label("Object");
        ui.horizontal(|ui| {
            ui.radio_value(&mut p.shape, Shape::Sphere, "Sphere");
            ui.radio_value(&mut p.shape, Shape::Cube, "Cube");
        });
        ui.add_enabled(
            p.shape == Shape::Sphere,
            egui::Slider::new(&mut p.subdivisions, 0..=render::MAX_SUBDIVISIONS)
                .text("Sphere subdivisions"),
        );
        if ui.button("Reset").clicked() {
            let size = p.size;
            *p = Params {
                size,
                ..Params::default()
            };
        }
    }

    fn picture(&mut self, ui: &mut egui::Ui) {
        // Room for the picture above its two or three lines of figures.
        let room = ui.available_size() - egui::vec2(0.0, 70.0);
        if self.fit_to_window {
            // Square, in physical pixels, in steps of 16 so small resizes do not re-render.
            let ppp = ui.ctx().pixels_per_point();
            let side = (room.x.min(room.y) * ppp).clamp(64.0, 2048.0) as usize / 16 * 16;
            self.params.size = [side, side];
        }
        self.frame();
        let (_, _, frame) = self.rendered.as_ref().expect("rendered by frame()");
        let texture = self
            .texture
            .get_or_insert_with(|| {
                let img = &frame.image;
                let rgb: Vec<u8> = img.pixels.iter().flatten().copied().collect();
                let color = ColorImage::from_rgb([img.width, img.height], &rgb);
                ui.ctx()
                    .load_texture("explorer-render", color, TextureOptions::LINEAR)
            })
            .id();
        let (stats, elapsed, max_error_steps) = (frame.stats, frame.elapsed, frame.max_error_steps);
        let [w, h] = [frame.image.width as f32, frame.image.height as f32];
        // Fit the picture in the space left for it, keeping its aspect ratio, at most 2×.
        let scale = if self.fit_to_window {
            1.0 / ui.ctx().pixels_per_point()
        } else {
            (room.x / w).min(room.y / h).clamp(0.25, 2.0)
        };
        let r = ui.add(
            egui::Image::new((texture, egui::vec2(w * scale, h * scale)))
                .alt_text("The rendered object"),
        );
        self.remember(ui, "image", r.rect);

        let s = stats;
        ui.label(format!(
            "Frame time: {} ({} pixels drawn, {} points shaded)",
            format_duration(elapsed),
            s.pixels,
            s.shader_calls
        ));
        let pct = if s.triangles == 0 {
            0.0
        } else {
            100.0 * s.per_vertex as f32 / s.triangles as f32
        };
        let decided = match self.params.frequency {
            ShadingMode::PerVertex => "all per vertex",
            ShadingMode::PerPixel => "all per pixel",
            ShadingMode::Adaptive => "advisor's choice",
        };
        ui.label(format!(
            "Per vertex: {} of {} visible triangles ({pct:.0}%, {decided})",
            s.per_vertex, s.triangles
        ));
        if let Some(e) = max_error_steps {
            let colour = if self.params.frequency == ShadingMode::Adaptive
                && e > self.params.tolerance_steps
            {
                Color32::RED
            } else {
                ui.visuals().text_color()
            };
            ui.colored_label(
                colour,
                format!("Largest difference from per pixel: {e:.2}/255 (linear)"),
            );
        }
    }
}

fn format_duration(d: Duration) -> String {
    format!("{:.1} ms", d.as_secs_f64() * 1e3)
}

impl eframe::App for App {
    fn ui(&mut self, ui: &mut egui::Ui, _frame: &mut eframe::Frame) {
        App::ui(self, ui);
    }
}
