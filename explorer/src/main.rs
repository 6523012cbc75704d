//! Opens the explorer's window. All state and drawing are in the library (`explorer::App`).

fn main() -> eframe::Result {
    let options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_title("phong explorer")
            .with_inner_size([1040.0, 800.0]),
        ..Default::default()
    };
    eframe::run_native(
        "phong explorer",
        options,
        Box::new(|_cc| Ok(Box::new(explorer::App::default().fitted_to_window()))),
    )
}
