//! A model from drawn parts, shared by the proptest strategies (`tests/strategies`) and the
//! seeded measurements (`measure.rs`), which draw the parts their own ways.

use phong::{BlinnPhong, Lambert, Model, Normalization, Phong, PowStrategy, SpecularGate};

/// Model `kind` (0: Lambert, 1: Phong, otherwise Blinn-Phong) with the given parts; Lambert
/// takes the normalisation only.
pub fn assemble(
    kind: usize,
    gate: SpecularGate,
    normalization: Normalization,
    pow: PowStrategy,
) -> Model {
    match kind {
        0 => Model::Lambert(Lambert { normalization }),
        1 => Model::Phong(Phong {
            gate,
            normalization,
            pow,
        }),
        _ => Model::BlinnPhong(BlinnPhong {
            gate,
            normalization,
            pow,
        }),
    }
}
