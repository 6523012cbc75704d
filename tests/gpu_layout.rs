//! The GPU mirrors and the shaders agree: both shaders parse and validate with naga, and naga's
//! struct sizes and member offsets equal the Rust mirrors' `size_of` and `offset_of!`.

use std::mem::{offset_of, size_of};

use naga::{Module, TypeInner};
use phong::gpu::{GpuLight, GpuMaterial, GpuParams};

fn validate(module: &Module, what: &str) {
    naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::all(),
    )
    .validate(module)
    .unwrap_or_else(|e| panic!("{what} does not validate: {e:?}"));
}

fn wgsl() -> Module {
    let src = include_str!("../shaders/phong.wgsl");
    let m = naga::front::wgsl::parse_str(src)
        .unwrap_or_else(|e| panic!("phong.wgsl does not parse:\n{}", e.emit_to_string(src)));
    validate(&m, "phong.wgsl");
    m
}

fn glsl() -> Module {
    let src = include_str!("../shaders/phong.glsl");
    let m = naga::front::glsl::Frontend::default()
        .parse(
            &naga::front::glsl::Options::from(naga::ShaderStage::Compute),
            src,
        )
        .unwrap_or_else(|e| panic!("phong.glsl does not parse:\n{}", e.emit_to_string(src)));
    validate(&m, "phong.glsl");
    m
}

/// A struct's (member name, offset) pairs and its size in bytes.
type Layout = (Vec<(String, u32)>, u32);

/// The layout of the struct called `name`, as naga computed it.
fn layout(module: &Module, name: &str) -> Layout {
    for (_, ty) in module.types.iter() {
        if ty.name.as_deref() != Some(name) {
            continue;
        }
        if let TypeInner::Struct { members, span } = &ty.inner {
            let fields = members
                .iter()
                .map(|m| (m.name.clone().unwrap_or_default(), m.offset))
                .collect();
            return (fields, *span);
        }
    }
    panic!("no struct {name} in the module");
}

macro_rules! rust_layout {
    ($ty:ty { $($field:ident),* $(,)? }) => {
        (
            vec![$((stringify!($field).to_string(), offset_of!($ty, $field) as u32)),*],
            size_of::<$ty>() as u32,
        )
    };
}

fn expected() -> [(&'static str, Layout); 3] {
    [
        (
            "Material",
            rust_layout!(GpuMaterial {
                ambient,
                shininess,
                diffuse,
                _pad0,
                specular,
                _pad1,
                emission,
                _pad2
            }),
        ),
        (
            "Light",
            rust_layout!(GpuLight {
                position,
                kind,
                direction,
                cos_cutoff,
                ambient,
                spot_exponent,
                diffuse,
                attenuation_kind,
                specular,
                _pad0,
                attenuation
            }),
        ),
        (
            "Params",
            rust_layout!(GpuParams {
                viewer,
                viewer_kind,
                ambient,
                light_count,
                model,
                gate,
                normalization,
                _pad0
            }),
        ),
    ]
}

#[test]
fn wgsl_parses_validates_and_matches_the_rust_layouts() {
    let m = wgsl();
    for (name, want) in expected() {
        assert_eq!(
            layout(&m, name),
            want,
            "WGSL struct {name} vs the Rust mirror"
        );
    }
}

#[test]
fn glsl_parses_validates_and_matches_the_rust_layouts() {
    let m = glsl();
    for (name, want) in expected() {
        assert_eq!(
            layout(&m, name),
            want,
            "GLSL struct {name} vs the Rust mirror"
        );
    }
}

#[test]
fn a_mismatched_layout_would_be_caught() {
    // The check above is only worth something if naga's layout can differ from a Rust struct: a
    // struct with a vec3 followed by a vec3 has a 4-byte hole in std140 that #[repr(C)] lacks.
    let m = naga::front::wgsl::parse_str(
        "struct S { a: vec3<f32>, b: vec3<f32> } @group(0) @binding(0) var<uniform> s: S;",
    )
    .unwrap();
    let (fields, span) = layout(&m, "S");
    #[repr(C)]
    struct Packed {
        a: [f32; 3],
        b: [f32; 3],
    }
    assert_ne!(
        (fields, span),
        rust_layout!(Packed { a, b }),
        "naga must report the std140 hole"
    );
}
