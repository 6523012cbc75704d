//! Placeholder; the real benches arrive with the batch path.
fn main() {}
