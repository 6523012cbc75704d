//! The benches' scene, shared by `benches/shading.rs` and `examples/performance.rs` (which
//! measures the accuracy of the same configuration), so both describe exactly the same work.
#![allow(dead_code, reason = "each includer uses its own subset")]

use glam::Vec3;

pub(crate) const LIGHT_POS: Vec3 = Vec3::new(1.2, 1.0, 2.0);
pub(crate) const VIEW_POS: Vec3 = Vec3::new(0.0, 0.0, 3.0);
pub(crate) const ATT: (f32, f32, f32) = (1.0, 0.09, 0.032);
pub(crate) const LA: Vec3 = Vec3::splat(0.2);
pub(crate) const LD: Vec3 = Vec3::splat(0.5);
pub(crate) const LS: Vec3 = Vec3::splat(1.0);
pub(crate) const KA: Vec3 = Vec3::new(1.0, 0.5, 0.31);
pub(crate) const KD: Vec3 = Vec3::new(1.0, 0.5, 0.31);
pub(crate) const KS: Vec3 = Vec3::splat(0.5);

// The tests' seeded generator (SplitMix64), so the crate has one.
#[path = "../../tests/support/rng.rs"]
mod rng;
pub(crate) use rng::Rng;

/// `n` random positions in a 4-unit box around the origin and random unit normals.
pub(crate) fn points(n: usize, seed: u64) -> (Vec<Vec3>, Vec<Vec3>) {
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
