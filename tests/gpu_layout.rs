//! The GPU mirrors and the shaders agree: both shaders parse and validate with naga, naga's
//! struct sizes and member offsets equal the Rust mirrors' `size_of` and `offset_of!`, and the GLSL
//! is naga's translation of the current WGSL.

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

/// The comment the checked-in `shaders/phong.glsl` carries after its `#version` line; the rest of
/// the file is naga's GLSL for `phong.wgsl`, byte for byte.
const GLSL_HEADER: &str = "\
// phong.glsl: GENERATED from shaders/phong.wgsl by naga's GLSL backend; do not edit by hand.
// Regenerate: PHONG_BLESS_GLSL=1 cargo test -p phong --test suite gpu_layout::
// (tests/gpu_layout.rs checks that this file is current).
//
// The `phong` crate's reflection models as a GLSL 4.50 compute shader: the same structs, models,
// gates and attenuation as phong.wgsl, which gpu-check runs and compares with the CPU. Directions
// point away from the surface (L to the light, V to the viewer); GLSL's reflect(I, N) takes the
// incident direction I = -L, and the shader never builds R: R.V = 2(N.L)(N.V) - L.V. Bindings are
// phong.wgsl's: 0 Params (std140), 1 Material (std140), 2 lights, 3 positions, 4 normals (std430,
// read-only), 5 terms (std430). Struct layouts mirror phong::gpu::{GpuParams, GpuMaterial,
// GpuLight}; naga appends `_` to member names that end in a digit (`_pad0_`).
";

/// naga's GLSL 4.50 for `phong.wgsl`'s compute entry point, with the WGSL's binding numbers, and
/// [`GLSL_HEADER`] after the `#version` line: what `shaders/phong.glsl` must contain.
fn glsl_from_wgsl() -> String {
    let m = wgsl();
    let info = naga::valid::Validator::new(
        naga::valid::ValidationFlags::all(),
        naga::valid::Capabilities::all(),
    )
    .validate(&m)
    .expect("phong.wgsl validates");
    let mut binding_map = naga::back::glsl::BindingMap::default();
    for binding in 0..6u8 {
        let resource = naga::ResourceBinding {
            group: 0,
            binding: u32::from(binding),
        };
        binding_map.insert(resource, binding);
    }
    let options = naga::back::glsl::Options {
        version: naga::back::glsl::Version::Desktop(450),
        binding_map,
        ..Default::default()
    };
    let pipeline = naga::back::glsl::PipelineOptions {
        shader_stage: naga::ShaderStage::Compute,
        entry_point: "shade_points".to_string(),
        multiview: None,
    };
    let mut body = String::new();
    naga::back::glsl::Writer::new(
        &mut body,
        &m,
        &info,
        &options,
        &pipeline,
        naga::proc::BoundsCheckPolicies::default(),
    )
    .and_then(|mut w| w.write().map(|_| ()))
    .expect("naga writes GLSL for phong.wgsl");
    let (version, rest) = body.split_once('\n').expect("a #version line");
    format!("{version}\n{GLSL_HEADER}{rest}")
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
        // naga's GLSL writer appends `_` to a member name that ends in a digit (`_pad0_`).
        let (fields, span) = layout(&m, name);
        let fields = fields
            .into_iter()
            .map(|(n, offset)| match n.strip_suffix('_') {
                Some(base) if base.ends_with(|c: char| c.is_ascii_digit()) => {
                    (base.to_string(), offset)
                }
                _ => (n, offset),
            })
            .collect();
        assert_eq!(
            (fields, span),
            want,
            "GLSL struct {name} vs the Rust mirror"
        );
    }
}

/// `shaders/phong.glsl` is generated from `phong.wgsl`, the shader gpu-check runs, so the two
/// cannot drift apart: this fails when the WGSL (or naga) changed and the GLSL was not
/// regenerated. `PHONG_BLESS_GLSL=1` rewrites the file instead.
#[test]
fn glsl_is_generated_from_the_current_wgsl() {
    let want = glsl_from_wgsl();
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/shaders/phong.glsl");
    if std::env::var_os("PHONG_BLESS_GLSL").is_some() {
        std::fs::write(path, &want).expect("write shaders/phong.glsl");
        return;
    }
    let got = std::fs::read_to_string(path).expect("read shaders/phong.glsl");
    assert!(
        got == want,
        "shaders/phong.glsl is not naga's GLSL for the current phong.wgsl; regenerate it with \
         PHONG_BLESS_GLSL=1 cargo test -p phong --test suite gpu_layout::"
    );
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
