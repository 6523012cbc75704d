//! The measurement code behind `phong`'s documentation, shared by the crate's tests and benches
//! and by the two programs that write docs/:
//!
//! ```text
//! cargo run --release -p phong-tools --bin accuracy      # docs/accuracy.md, docs/stability.md
//! cargo run --release -p phong-tools --bin performance   # docs/performance.md and its chart
//! ```
//!
//! Not part of `phong`'s API and never published. Every module depends only on `glam` and the
//! public API of `phong`:
//!
//! - [`reference`]: every formula of the crate evaluated plainly in `f64`, the ruler;
//! - [`batch_range`]: the range of values the batch path's documented accuracy allows at a
//!   point, the check tests/batch.rs, tests/gbuffer.rs and the fuzz campaign apply;
//! - [`measure`]: the error of each `f32` function against that ruler (docs/accuracy.md);
//! - [`slivers`]: the thin-triangle study behind the triangle normal's method;
//! - [`stability_cases`]: the stability matrix (docs/stability.md);
//! - [`models`]: a model assembled from drawn parts, for the measurements and the proptest
//!   strategies;
//! - [`rng`]: the seeded generator (SplitMix64) every measurement, test and bench draws from;
//! - [`bench_scene`]: the benches' scene, which the `performance` tool measures the accuracy of.

pub mod batch_range;
pub mod bench_scene;
pub mod measure;
pub mod models;
pub mod reference;
pub mod rng;
pub mod slivers;
pub mod stability_cases;
