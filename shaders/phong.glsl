#version 450
// phong.glsl: the `phong` crate's reflection models in GLSL 4.50, with the crate's conventions.
//
// The same structs, models, gates and attenuation as shaders/phong.wgsl and the Rust crate.
// Directions point away from the surface (L to the light, V to the viewer). Struct layouts mirror
// phong::gpu::{GpuMaterial, GpuLight, GpuParams} under std140/std430 (checked by tests/gpu_layout.rs).
// Note: GLSL's reflect(I, N) takes the incident direction I = -L; this file never builds R, it uses
// R.V = 2(N.L)(N.V) - L.V.

layout(local_size_x = 64) in;

struct Material {
    vec3 ambient;
    float shininess;
    vec3 diffuse;
    float _pad0;
    vec3 specular;
    float _pad1;
    vec3 emission;
    float _pad2;
};

struct Light {
    vec3 position;
    uint kind;               // 0 directional, 1 point, 2 spot
    vec3 direction;          // directional: toward the light; spot: cone axis
    float cos_cutoff;
    vec3 ambient;
    float spot_exponent;
    vec3 diffuse;
    uint attenuation_kind;   // 0 none, 1 polynomial, 2 inverse-square, 3 Unreal, 4 Frostbite
    vec3 specular;
    float _pad0;
    vec4 attenuation;
};

struct Params {
    vec3 viewer;
    uint viewer_kind;        // 0 at a point, 1 infinite
    vec3 ambient;
    uint light_count;
    uint model;              // 0 Lambert, 1 Phong, 2 Blinn-Phong
    uint gate;               // 0 step, 1 cosine, 2 none
    uint normalization;      // 0 none, 1 energy, 2 exact
    uint _pad0;
};

struct Terms {
    vec4 ambient;
    vec4 diffuse;
    vec4 specular;
    vec4 emission;
};

layout(std140, set = 0, binding = 0) uniform ParamsBlock { Params params; };
layout(std140, set = 0, binding = 1) uniform MaterialBlock { Material material; };
layout(std430, set = 0, binding = 2) readonly buffer LightBlock { Light lights[]; };
layout(std430, set = 0, binding = 3) readonly buffer PositionBlock { vec4 positions[]; };
layout(std430, set = 0, binding = 4) readonly buffer NormalBlock { vec4 normals[]; };
layout(std430, set = 0, binding = 5) buffer TermsBlock { Terms terms[]; };

const float PI = 3.14159265358979;
const float F32_MAX = 3.40282347e38;
const float MIN_DENOMINATOR = 1e-4;
const float F32_MIN_POSITIVE = 1.17549435e-38;

// v / |v| over the whole finite range; the zero vector for v = 0.
vec3 normalize_or_zero(vec3 v) {
    float l2 = dot(v, v);
    if (l2 >= 1e-30 && l2 <= 1e30) {
        return v * inversesqrt(l2);
    }
    float m = max(abs(v.x), max(abs(v.y), abs(v.z)));
    if (m == 0.0 || !(m <= F32_MAX)) {
        return vec3(0.0);
    }
    vec3 s = v / m;
    return s * inversesqrt(dot(s, s));
}

// x^s for a clamped cosine; 0 for x <= 0 (so 0^0 = 0).
float lobe_pow(float x, float s) {
    if (x > 0.0) {
        return clamp(pow(min(x, 1.0), max(s, 0.0)), 0.0, 1.0);
    }
    return 0.0;
}

float gate_weight(uint gate, float n_dot_l) {
    if (gate == 0u) {
        return n_dot_l > 0.0 ? 1.0 : 0.0;
    }
    if (gate == 1u) {
        return max(n_dot_l, 0.0);
    }
    return 1.0;
}

float diffuse_lobe(uint normalization, float n_dot_l) {
    float c = max(n_dot_l, 0.0);
    return normalization != 0u ? c * (1.0 / PI) : c;
}

// Phong: R.V = 2(N.L)(N.V) - L.V.
float phong_specular(uint gate, uint normalization, float nl, float nv, float lv, float s) {
    float rv = clamp(2.0 * nl * nv - lv, -1.0, 1.0);
    float lobe = lobe_pow(rv, s);
    if (normalization != 0u) {
        return min((max(s, 0.0) + 2.0) * (1.0 / (2.0 * PI)), F32_MAX) * lobe * max(nl, 0.0);
    }
    return lobe * gate_weight(gate, nl);
}

// Blinn-Phong: (N.H)^2 = max(N.(L+V), 0)^2 / |L+V|^2, raised to s/2. Computed from the vector
// L + V (not from 2 + 2 L.V, which cancels as L -> -V), exactly as the crate's Incidence::new.
float blinn_specular(uint gate, uint normalization, vec3 n, vec3 l, vec3 v, float nl, float s) {
    vec3 sum = l + v;
    float t = max(dot(n, sum), 0.0);
    float den = dot(sum, sum);
    float nh2 = den >= F32_MIN_POSITIVE ? min(t * t / den, 1.0) : 0.0;
    float lobe = lobe_pow(nh2, 0.5 * s);
    if (normalization == 1u) {
        return min((max(s, 0.0) + 8.0) * (1.0 / (8.0 * PI)), F32_MAX) * lobe * max(nl, 0.0);
    }
    if (normalization == 2u) {
        float ss = max(s, 0.0);
        float a = (ss + 2.0) * (1.0 / (8.0 * PI));
        float b = (ss + 4.0) / (pow(2.0, -0.5 * ss) + ss);
        return min(a * b, F32_MAX) * lobe * max(nl, 0.0);
    }
    return lobe * gate_weight(gate, nl);
}

float window_falloff(float d, float r) {
    if (d < r) {
        // (1 − x⁴) factored as (1 − x)(1 + x)(1 + x²), with 1 − x as (r − d)/r: no cancellation
        // near d = r, the same form as the CPU's Attenuation::factor. Capped at 1 as there.
        float x = d / r;
        float w = min(((r - d) / r) * (1.0 + x) * (1.0 + x * x), 1.0);
        return w * w;
    }
    return 0.0;
}

float attenuation_factor(uint kind, vec4 a, float d_in) {
    float d = clamp(d_in, 0.0, F32_MAX);
    float f = 1.0;
    if (kind == 1u) {
        f = 1.0 / max(a.x + d * (a.y + a.z * d), MIN_DENOMINATOR);
    } else if (kind == 2u) {
        float dd = max(d, a.y);
        f = a.x / max(dd * dd, F32_MIN_POSITIVE);
    } else if (kind == 3u) {
        f = window_falloff(d, a.x) / (d * d + 1.0);
    } else if (kind == 4u) {
        float dd = max(d, a.y);
        f = window_falloff(d, a.x) / max(dd * dd, F32_MIN_POSITIVE);
    }
    return clamp(f, 0.0, F32_MAX);
}

Terms shade_point(vec3 position, vec3 normal) {
    vec3 sat = vec3(F32_MAX);
    vec3 n = normalize_or_zero(normal);
    vec3 v = params.viewer_kind == 0u ? normalize_or_zero(params.viewer - position)
                                      : normalize_or_zero(params.viewer);
    bool lit = any(notEqual(n, vec3(0.0)));
    bool specular_on = params.model != 0u && lit && any(notEqual(v, vec3(0.0)));
    vec3 ambient_light = max(params.ambient, vec3(0.0));
    vec3 diffuse = vec3(0.0);
    vec3 specular = vec3(0.0);
    for (uint i = 0u; i < params.light_count; i++) {
        Light light = lights[i];
        vec3 l = light.direction;
        float f = 1.0;
        if (light.kind != 0u) {
            vec3 to_light = light.position - position;
            l = normalize_or_zero(to_light);
            f = attenuation_factor(light.attenuation_kind, light.attenuation, length(to_light));
            if (light.kind == 2u) {
                float c = -dot(l, light.direction);
                float spot = 0.0;
                if (any(notEqual(l, vec3(0.0))) && c >= light.cos_cutoff) {
                    spot = lobe_pow(min(c, 1.0), light.spot_exponent);
                }
                f = spot > 0.0 ? min(f * spot, F32_MAX) : 0.0;
            }
        }
        if (f == 0.0) {
            continue;
        }
        ambient_light += min(light.ambient * f, sat);
        if (!lit || all(equal(l, vec3(0.0)))) {
            continue;
        }
        float nl = dot(n, l);
        float nv = dot(n, v);
        float lv = dot(l, v);
        float wd = min(f * diffuse_lobe(params.normalization, nl), F32_MAX);
        diffuse += min(light.diffuse * wd, sat);
        if (specular_on) {
            float spec_lobe = params.model == 1u
                ? phong_specular(params.gate, params.normalization, nl, nv, lv, material.shininess)
                : blinn_specular(params.gate, params.normalization, n, l, v, nl, material.shininess);
            float ws = min(f * spec_lobe, F32_MAX);
            specular += min(light.specular * ws, sat);
        }
    }
    Terms t;
    t.ambient = vec4(min(min(ambient_light, sat) * material.ambient, sat), 0.0);
    // The material is applied once to each saturated light sum, as on the CPU.
    t.diffuse = vec4(min(min(diffuse, sat) * material.diffuse, sat), 0.0);
    t.specular = vec4(min(min(specular, sat) * material.specular, sat), 0.0);
    t.emission = vec4(material.emission, 0.0);
    return t;
}

// One invocation per surface point: positions[i].xyz and normals[i].xyz in, terms[i] out.
void main() {
    uint i = gl_GlobalInvocationID.x;
    if (i >= uint(positions.length())) {
        return;
    }
    terms[i] = shade_point(positions[i].xyz, normals[i].xyz);
}
