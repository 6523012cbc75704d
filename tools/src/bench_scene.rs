//! The benches' scene, shared by the benches (`benches/shading.rs`,
//! `benches/renderers.rs`) and the `performance` tool (which measures the accuracy of the same
//! configuration), so both describe exactly the same work.

use glam::Vec3;

/// The point light's position.
pub const LIGHT_POS: Vec3 = Vec3::new(1.2, 1.0, 2.0);
/// The viewer's position.
pub const VIEW_POS: Vec3 = Vec3::new(0.0, 0.0, 3.0);
/// The light's attenuation `(constant, linear, quadratic)`: LearnOpenGL's 50-unit row.
pub const ATT: (f32, f32, f32) = (1.0, 0.09, 0.032);
/// The light's ambient colour.
pub const LA: Vec3 = Vec3::splat(0.2);
/// The light's diffuse colour.
pub const LD: Vec3 = Vec3::splat(0.5);
/// The light's specular colour.
pub const LS: Vec3 = Vec3::splat(1.0);
/// The material's ambient colour (LearnOpenGL's coral).
pub const KA: Vec3 = Vec3::new(1.0, 0.5, 0.31);
/// The material's diffuse colour (LearnOpenGL's coral).
pub const KD: Vec3 = Vec3::new(1.0, 0.5, 0.31);
/// The material's specular colour.
pub const KS: Vec3 = Vec3::splat(0.5);

// The tests' seeded generator (SplitMix64), so the workspace has one.
pub use crate::rng::Rng;

/// `n` random positions in a 4-unit box around the origin and random unit normals.
pub fn points(n: usize, seed: u64) -> (Vec<Vec3>, Vec<Vec3>) {
    let mut rng = Rng::new(seed);
    let mut p = Vec::with_capacity(n);
    let mut nn = Vec::with_capacity(n);
    for _ in 0..n {
        p.push(Vec3::new(
            rng.range_f32(-2.0, 2.0),
            rng.range_f32(-2.0, 2.0),
            rng.range_f32(-2.0, 2.0),
        ));
        let v = loop {
            let v = Vec3::new(
                rng.range_f32(-1.0, 1.0),
                rng.range_f32(-1.0, 1.0),
                rng.range_f32(-1.0, 1.0),
            );
            let l = v.length_squared();
            if l > 1e-4 && l <= 1.0 {
                break v.normalize();
            }
        };
        nn.push(v);
    }
    (p, nn)
}
