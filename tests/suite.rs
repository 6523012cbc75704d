//! The crate's integration tests, compiled as one test binary.
//!
//! Each file in tests/ is one module here, under its own name, so a test's path is
//! `file::test` (`cargo test --test suite properties::`) and its proptest regressions stay in the
//! file beside it (`tests/<file>.proptest-regressions`). One binary instead of twenty: each
//! integration-test crate compiled and linked the crate's generic code (the shader, the batch
//! kernel at every level) again, which made most of the test build in CI, and of the aarch64
//! build under qemu most of all. `fuzz_promises` stays a binary of its own: it is run on its own
//! with a budget of evaluations (docs/fuzz.md).

mod strategies;

#[path = "accuracy_bounds.rs"]
mod accuracy_bounds;
#[path = "batch.rs"]
mod batch;
#[path = "batch_parallel.rs"]
mod batch_parallel;
#[path = "change_of_coordinates.rs"]
mod change_of_coordinates;
#[path = "conformance.rs"]
mod conformance;
#[path = "gbuffer.rs"]
mod gbuffer;
#[path = "gpu_layout.rs"]
mod gpu_layout;
#[cfg(feature = "mint")]
#[path = "interop.rs"]
mod interop;
#[path = "promises_api.rs"]
mod promises_api;
#[path = "promises_attenuation.rs"]
mod promises_attenuation;
#[path = "promises_geometry.rs"]
mod promises_geometry;
#[path = "promises_numerics.rs"]
mod promises_numerics;
#[path = "properties.rs"]
mod properties;
#[cfg(feature = "serde")]
#[path = "serde.rs"]
mod serde_files;
#[path = "shader.rs"]
mod shader;
#[path = "shading_rate.rs"]
mod shading_rate;
#[path = "stability.rs"]
mod stability;
#[path = "stability_matrix.rs"]
mod stability_matrix;
#[path = "totality.rs"]
mod totality;
#[path = "unit_values.rs"]
mod unit_values;
