// phong.wgsl: the `phong` crate's reflection models in WGSL, with the crate's conventions.
//
// Directions point away from the surface (L to the light, V to the viewer). Structs mirror
// phong::gpu::{GpuMaterial, GpuLight, GpuParams} byte for byte (checked by tests/gpu_layout.rs).
// Degenerate cases give the crate's documented answers: a zero normal gives ambient + emission only,
// a light at the point adds ambient only, a viewer at the point gives no specular, L = -V gives no
// Blinn-Phong specular, and pow(0, 0) is 0 (the s -> 0+ limit of the lobe).

struct Material {
    ambient: vec3<f32>,
    shininess: f32,
    diffuse: vec3<f32>,
    _pad0: f32,
    specular: vec3<f32>,
    _pad1: f32,
    emission: vec3<f32>,
    _pad2: f32,
}

struct Light {
    position: vec3<f32>,
    kind: u32,                 // 0 directional, 1 point, 2 spot
    direction: vec3<f32>,      // directional: toward the light; spot: cone axis
    cos_cutoff: f32,
    ambient: vec3<f32>,
    spot_exponent: f32,
    diffuse: vec3<f32>,
    attenuation_kind: u32,     // 0 none, 1 polynomial, 2 inverse-square, 3 Unreal, 4 Frostbite
    specular: vec3<f32>,
    _pad0: f32,
    attenuation: vec4<f32>,
}

struct Params {
    viewer: vec3<f32>,
    viewer_kind: u32,          // 0 at a point, 1 infinite (viewer = direction toward it)
    ambient: vec3<f32>,
    light_count: u32,
    model: u32,                // 0 Lambert, 1 Phong, 2 Blinn-Phong
    gate: u32,                 // 0 step, 1 cosine, 2 none
    normalization: u32,        // 0 none, 1 energy, 2 exact
    _pad0: u32,
}

struct Terms {
    ambient: vec4<f32>,
    diffuse: vec4<f32>,
    specular: vec4<f32>,
    emission: vec4<f32>,
}

const PI: f32 = 3.14159265358979;
const F32_MAX: f32 = 3.40282347e38;
const MIN_DENOMINATOR: f32 = 1e-4;
const F32_MIN_POSITIVE: f32 = 1.17549435e-38;

// v / |v| over the whole finite range; the zero vector for v = 0.
fn normalize_or_zero(v: vec3<f32>) -> vec3<f32> {
    let l2 = dot(v, v);
    if (l2 >= 1e-30 && l2 <= 1e30) {
        return v * inverseSqrt(l2);
    }
    let m = max(abs(v.x), max(abs(v.y), abs(v.z)));
    if (m == 0.0 || !(m <= F32_MAX)) {
        return vec3<f32>(0.0);
    }
    let s = v / m;
    return s * inverseSqrt(dot(s, s));
}

// x^s for a clamped cosine; 0 for x <= 0 (so 0^0 = 0).
fn lobe_pow(x: f32, s: f32) -> f32 {
    if (x > 0.0) {
        return clamp(pow(min(x, 1.0), max(s, 0.0)), 0.0, 1.0);
    }
    return 0.0;
}

fn gate_weight(gate: u32, n_dot_l: f32) -> f32 {
    if (gate == 0u) {
        return select(0.0, 1.0, n_dot_l > 0.0);
    }
    if (gate == 1u) {
        return max(n_dot_l, 0.0);
    }
    return 1.0;
}

fn diffuse_lobe(normalization: u32, n_dot_l: f32) -> f32 {
    let c = max(n_dot_l, 0.0);
    return select(c, c * (1.0 / PI), normalization != 0u);
}

// Phong: R.V = 2(N.L)(N.V) - L.V, no reflect vector built.
fn phong_specular(p: Params, nl: f32, nv: f32, lv: f32, s: f32) -> f32 {
    let rv = clamp(2.0 * nl * nv - lv, -1.0, 1.0);
    let lobe = lobe_pow(rv, s);
    if (p.normalization != 0u) {
        return min((max(s, 0.0) + 2.0) * (1.0 / (2.0 * PI)), F32_MAX) * lobe * max(nl, 0.0);
    }
    return lobe * gate_weight(p.gate, nl);
}

// Blinn-Phong: (N.H)^2 = max(N.(L+V), 0)^2 / |L+V|^2, raised to s/2. Computed from the vector
// L + V (not from 2 + 2 L.V, which cancels as L -> -V), exactly as the crate's Incidence::new.
fn blinn_specular(p: Params, n: vec3<f32>, l: vec3<f32>, v: vec3<f32>, nl: f32, s: f32) -> f32 {
    let sum = l + v;
    let t = max(dot(n, sum), 0.0);
    let den = dot(sum, sum);
    let nh2 = select(0.0, min(t * t / den, 1.0), den >= F32_MIN_POSITIVE);
    let lobe = lobe_pow(nh2, 0.5 * s);
    if (p.normalization == 1u) {
        return min((max(s, 0.0) + 8.0) * (1.0 / (8.0 * PI)), F32_MAX) * lobe * max(nl, 0.0);
    }
    if (p.normalization == 2u) {
        let ss = max(s, 0.0);
        let a = (ss + 2.0) * (1.0 / (8.0 * PI));
        let b = (ss + 4.0) / (pow(2.0, -0.5 * ss) + ss);
        return min(a * b, F32_MAX) * lobe * max(nl, 0.0);
    }
    return lobe * gate_weight(p.gate, nl);
}

fn window(d: f32, r: f32) -> f32 {
    if (d < r) {
        // (1 − x⁴) factored as (1 − x)(1 + x)(1 + x²), with 1 − x as (r − d)/r: no cancellation
        // near d = r, the same form as the CPU's Attenuation::factor. Capped at 1 as there.
        let x = d / r;
        let w = min(((r - d) / r) * (1.0 + x) * (1.0 + x * x), 1.0);
        return w * w;
    }
    return 0.0;
}

fn attenuation_factor(kind: u32, a: vec4<f32>, d_in: f32) -> f32 {
    let d = clamp(d_in, 0.0, F32_MAX);
    var f = 1.0;
    if (kind == 1u) {
        f = 1.0 / max(a.x + d * (a.y + a.z * d), MIN_DENOMINATOR);
    } else if (kind == 2u) {
        let dd = max(d, a.y);
        f = a.x / max(dd * dd, F32_MIN_POSITIVE);
    } else if (kind == 3u) {
        f = window(d, a.x) / (d * d + 1.0);
    } else if (kind == 4u) {
        let dd = max(d, a.y);
        f = window(d, a.x) / max(dd * dd, F32_MIN_POSITIVE);
    }
    return clamp(f, 0.0, F32_MAX);
}

fn shade_point(p: Params, m: Material, position: vec3<f32>, normal: vec3<f32>) -> Terms {
    let sat = vec3<f32>(F32_MAX);
    let n = normalize_or_zero(normal);
    var v: vec3<f32>;
    if (p.viewer_kind == 0u) {
        v = normalize_or_zero(p.viewer - position);
    } else {
        v = normalize_or_zero(p.viewer);
    }
    let lit = any(n != vec3<f32>(0.0));
    let specular_on = p.model != 0u && lit && any(v != vec3<f32>(0.0));
    var ambient_light = max(p.ambient, vec3<f32>(0.0));
    var diffuse = vec3<f32>(0.0);
    var specular = vec3<f32>(0.0);
    for (var i = 0u; i < p.light_count; i++) {
        let light = lights[i];
        var l = light.direction;
        var f = 1.0;
        if (light.kind != 0u) {
            let to_light = light.position - position;
            l = normalize_or_zero(to_light);
            f = attenuation_factor(light.attenuation_kind, light.attenuation, length(to_light));
            if (light.kind == 2u) {
                let c = -dot(l, light.direction);
                var spot = 0.0;
                if (any(l != vec3<f32>(0.0)) && c >= light.cos_cutoff) {
                    spot = lobe_pow(min(c, 1.0), light.spot_exponent);
                }
                f = select(0.0, min(f * spot, F32_MAX), spot > 0.0);
            }
        }
        if (f == 0.0) {
            continue;
        }
        ambient_light += min(light.ambient * f, sat);
        if (!lit || all(l == vec3<f32>(0.0))) {
            continue;
        }
        let nl = dot(n, l);
        let nv = dot(n, v);
        let lv = dot(l, v);
        let wd = min(f * diffuse_lobe(p.normalization, nl), F32_MAX);
        diffuse += min(light.diffuse * wd, sat);
        if (specular_on) {
            var spec_lobe: f32;
            if (p.model == 1u) {
                spec_lobe = phong_specular(p, nl, nv, lv, m.shininess);
            } else {
                spec_lobe = blinn_specular(p, n, l, v, nl, m.shininess);
            }
            let ws = min(f * spec_lobe, F32_MAX);
            specular += min(light.specular * ws, sat);
        }
    }
    var t: Terms;
    t.ambient = vec4<f32>(min(min(ambient_light, sat) * m.ambient, sat), 0.0);
    // The material is applied once to each saturated light sum, as on the CPU.
    t.diffuse = vec4<f32>(min(min(diffuse, sat) * m.diffuse, sat), 0.0);
    t.specular = vec4<f32>(min(min(specular, sat) * m.specular, sat), 0.0);
    t.emission = vec4<f32>(m.emission, 0.0);
    return t;
}

@group(0) @binding(0) var<uniform> params: Params;
@group(0) @binding(1) var<uniform> material: Material;
@group(0) @binding(2) var<storage, read> lights: array<Light>;
@group(0) @binding(3) var<storage, read> positions: array<vec4<f32>>;
@group(0) @binding(4) var<storage, read> normals: array<vec4<f32>>;
@group(0) @binding(5) var<storage, read_write> terms: array<Terms>;

// One invocation per surface point: positions[i].xyz and normals[i].xyz in, terms[i] out.
@compute @workgroup_size(64)
fn shade_points(@builtin(global_invocation_id) id: vec3<u32>) {
    let i = id.x;
    if (i >= arrayLength(&positions)) {
        return;
    }
    terms[i] = shade_point(params, material, positions[i].xyz, normals[i].xyz);
}
