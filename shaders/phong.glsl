#version 450 core
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
#extension GL_ARB_compute_shader : require
#extension GL_ARB_shader_storage_buffer_object : require
layout(local_size_x = 64, local_size_y = 1, local_size_z = 1) in;

struct Material {
    vec3 ambient;
    float shininess;
    vec3 diffuse;
    float _pad0_;
    vec3 specular;
    float _pad1_;
    vec3 emission;
    float _pad2_;
};
struct Light {
    vec3 position;
    uint kind;
    vec3 direction;
    float cos_cutoff;
    vec3 ambient;
    float spot_exponent;
    vec3 diffuse;
    uint attenuation_kind;
    vec3 specular;
    float _pad0_;
    vec4 attenuation;
};
struct Params {
    vec3 viewer;
    uint viewer_kind;
    vec3 ambient;
    uint light_count;
    uint model;
    uint gate;
    uint normalization;
    uint _pad0_;
};
struct Terms {
    vec4 ambient;
    vec4 diffuse;
    vec4 specular;
    vec4 emission;
};
const float PI = 3.1415927;
const float F32_MAX = 3.4028235e38;
const float MIN_DENOMINATOR = 0.0001;
const float F32_MIN_POSITIVE = 1.1754944e-38;

layout(std430, binding = 2) readonly buffer type_5_block_0Compute { Light _group_0_binding_2_cs[]; };

layout(std140, binding = 0) uniform Params_block_1Compute { Params _group_0_binding_0_cs; };

layout(std140, binding = 1) uniform Material_block_2Compute { Material _group_0_binding_1_cs; };

layout(std430, binding = 3) readonly buffer type_6_block_3Compute { vec4 _group_0_binding_3_cs[]; };

layout(std430, binding = 4) readonly buffer type_6_block_4Compute { vec4 _group_0_binding_4_cs[]; };

layout(std430, binding = 5) buffer type_7_block_5Compute { Terms _group_0_binding_5_cs[]; };


vec3 normalize_or_zero(vec3 v) {
    bool local = false;
    bool local_1 = false;
    float l2_ = dot(v, v);
    if ((l2_ >= 1e-30)) {
        local = (l2_ <= 1e30);
    } else {
        local = false;
    }
    bool _e9 = local;
    if (_e9) {
        return (v * inversesqrt(l2_));
    }
    float m_1 = max(abs(v.x), max(abs(v.y), abs(v.z)));
    if (!((m_1 == 0.0))) {
        local_1 = !((m_1 <= F32_MAX));
    } else {
        local_1 = true;
    }
    bool _e29 = local_1;
    if (_e29) {
        return vec3(0.0);
    }
    vec3 s_3 = (v / vec3(m_1));
    return (s_3 * inversesqrt(dot(s_3, s_3)));
}

float lobe_pow(float x, float s) {
    if ((x > 0.0)) {
        return clamp(pow(min(x, 1.0), max(s, 0.0)), 0.0, 1.0);
    }
    return 0.0;
}

float gate_weight(uint gate, float n_dot_l) {
    if ((gate == 0u)) {
        return ((n_dot_l > 0.0) ? 1.0 : 0.0);
    }
    if ((gate == 1u)) {
        return max(n_dot_l, 0.0);
    }
    return 1.0;
}

float diffuse_lobe(uint normalization, float n_dot_l_1) {
    float c = max(n_dot_l_1, 0.0);
    return ((normalization != 0u) ? (c * 0.31830987) : c);
}

float phong_specular(Params p, float nl, float nv, float lv, float s_1) {
    float rv = clamp((((2.0 * nl) * nv) - lv), -1.0, 1.0);
    float _e12 = lobe_pow(rv, s_1);
    if ((p.normalization != 0u)) {
        return ((min(((max(s_1, 0.0) + 2.0) * 0.15915494), F32_MAX) * _e12) * max(nl, 0.0));
    }
    float _e29 = gate_weight(p.gate, nl);
    return (_e12 * _e29);
}

float blinn_specular(Params p_1, vec3 n, vec3 l, vec3 v_1, float nl_1, float s_2) {
    vec3 sum = (l + v_1);
    float t_1 = max(dot(n, sum), 0.0);
    float den = dot(sum, sum);
    float nh2_ = ((den >= F32_MIN_POSITIVE) ? min(((t_1 * t_1) / den), 1.0) : 0.0);
    float _e21 = lobe_pow(nh2_, (0.5 * s_2));
    if ((p_1.normalization == 1u)) {
        return ((min(((max(s_2, 0.0) + 8.0) * 0.039788734), F32_MAX) * _e21) * max(nl_1, 0.0));
    }
    if ((p_1.normalization == 2u)) {
        float ss = max(s_2, 0.0);
        float a_1 = ((ss + 2.0) * 0.039788734);
        float b = ((ss + 4.0) / (pow(2.0, (-0.5 * ss)) + ss));
        return ((min((a_1 * b), F32_MAX) * _e21) * max(nl_1, 0.0));
    }
    float _e62 = gate_weight(p_1.gate, nl_1);
    return (_e21 * _e62);
}

float window(float d, float r) {
    if ((d < r)) {
        float x_1 = (d / r);
        float w = min(((((r - d) / r) * (1.0 + x_1)) * (1.0 + (x_1 * x_1))), 1.0);
        return (w * w);
    }
    return 0.0;
}

float attenuation_factor(uint kind, vec4 a, float d_in) {
    float f = 1.0;
    float d_1 = clamp(d_in, 0.0, F32_MAX);
    if ((kind == 1u)) {
        f = (1.0 / max((a.x + (d_1 * (a.y + (a.z * d_1)))), MIN_DENOMINATOR));
    } else {
        if ((kind == 2u)) {
            float dd = max(d_1, a.y);
            f = (a.x / max((dd * dd), F32_MIN_POSITIVE));
        } else {
            if ((kind == 3u)) {
                float _e33 = window(d_1, a.x);
                f = (_e33 / ((d_1 * d_1) + 1.0));
            } else {
                if ((kind == 4u)) {
                    float dd_1 = max(d_1, a.y);
                    float _e43 = window(d_1, a.x);
                    f = (_e43 / max((dd_1 * dd_1), F32_MIN_POSITIVE));
                }
            }
        }
    }
    float _e48 = f;
    return clamp(_e48, 0.0, F32_MAX);
}

Terms shade_point(Params p_2, Material m, vec3 position, vec3 normal) {
    vec3 v_2 = vec3(0.0);
    bool local_2 = false;
    bool local_3 = false;
    vec3 ambient_light = vec3(0.0);
    vec3 diffuse = vec3(0.0);
    vec3 specular = vec3(0.0);
    uint i = 0u;
    vec3 l_1 = vec3(0.0);
    float f_1 = 0.0;
    float spot = 0.0;
    bool local_4 = false;
    bool local_5 = false;
    float spec_lobe = 0.0;
    Terms t = Terms(vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0));
    vec3 sat = vec3(3.4028235e38);
    vec3 _e6 = normalize_or_zero(normal);
    if ((p_2.viewer_kind == 0u)) {
        vec3 _e13 = normalize_or_zero((p_2.viewer - position));
        v_2 = _e13;
    } else {
        vec3 _e15 = normalize_or_zero(p_2.viewer);
        v_2 = _e15;
    }
    bool lit = any(notEqual(_e6, vec3(0.0)));
    if ((p_2.model != 0u)) {
        local_2 = lit;
    } else {
        local_2 = false;
    }
    bool _e26 = local_2;
    if (_e26) {
        vec3 _e29 = v_2;
        local_3 = any(notEqual(_e29, vec3(0.0)));
    } else {
        local_3 = false;
    }
    bool specular_on = local_3;
    ambient_light = max(p_2.ambient, vec3(0.0));
    bool loop_init = true;
    while(true) {
        if (!loop_init) {
            uint _e164 = i;
            i = (_e164 + 1u);
        }
        loop_init = false;
        uint _e49 = i;
        if ((_e49 < p_2.light_count)) {
        } else {
            break;
        }
        {
            uint _e53 = i;
            Light light = _group_0_binding_2_cs[_e53];
            l_1 = light.direction;
            f_1 = 1.0;
            if ((light.kind != 0u)) {
                vec3 to_light = (light.position - position);
                vec3 _e65 = normalize_or_zero(to_light);
                l_1 = _e65;
                float _e69 = attenuation_factor(light.attenuation_kind, light.attenuation, length(to_light));
                f_1 = _e69;
                if ((light.kind == 2u)) {
                    vec3 _e73 = l_1;
                    float c_1 = -(dot(_e73, light.direction));
                    spot = 0.0;
                    vec3 _e79 = l_1;
                    if (any(notEqual(_e79, vec3(0.0)))) {
                        local_4 = (c_1 >= light.cos_cutoff);
                    } else {
                        local_4 = false;
                    }
                    bool _e89 = local_4;
                    if (_e89) {
                        float _e93 = lobe_pow(min(c_1, 1.0), light.spot_exponent);
                        spot = _e93;
                    }
                    float _e94 = f_1;
                    float _e95 = spot;
                    float _e99 = spot;
                    f_1 = ((_e99 > 0.0) ? min((_e94 * _e95), F32_MAX) : 0.0);
                }
            }
            float _e104 = f_1;
            if ((_e104 == 0.0)) {
                continue;
            }
            vec3 _e107 = ambient_light;
            float _e109 = f_1;
            ambient_light = (_e107 + min((light.ambient * _e109), sat));
            if (!(!(lit))) {
                vec3 _e117 = l_1;
                local_5 = all(equal(_e117, vec3(0.0)));
            } else {
                local_5 = true;
            }
            bool _e123 = local_5;
            if (_e123) {
                continue;
            }
            vec3 _e124 = l_1;
            float nl_2 = dot(_e6, _e124);
            vec3 _e126 = v_2;
            float nv_1 = dot(_e6, _e126);
            vec3 _e128 = l_1;
            vec3 _e129 = v_2;
            float lv_1 = dot(_e128, _e129);
            float _e131 = f_1;
            float _e133 = diffuse_lobe(p_2.normalization, nl_2);
            float wd = min((_e131 * _e133), F32_MAX);
            vec3 _e137 = diffuse;
            diffuse = (_e137 + min((light.diffuse * wd), sat));
            if (specular_on) {
                spec_lobe = 0.0;
                if ((p_2.model == 1u)) {
                    float _e148 = phong_specular(p_2, nl_2, nv_1, lv_1, m.shininess);
                    spec_lobe = _e148;
                } else {
                    vec3 _e149 = l_1;
                    vec3 _e150 = v_2;
                    float _e152 = blinn_specular(p_2, _e6, _e149, _e150, nl_2, m.shininess);
                    spec_lobe = _e152;
                }
                float _e153 = f_1;
                float _e154 = spec_lobe;
                float ws = min((_e153 * _e154), F32_MAX);
                vec3 _e158 = specular;
                specular = (_e158 + min((light.specular * ws), sat));
            }
        }
    }
    vec3 _e168 = ambient_light;
    t.ambient = vec4(min((min(_e168, sat) * m.ambient), sat), 0.0);
    vec3 _e176 = diffuse;
    t.diffuse = vec4(min((min(_e176, sat) * m.diffuse), sat), 0.0);
    vec3 _e184 = specular;
    t.specular = vec4(min((min(_e184, sat) * m.specular), sat), 0.0);
    t.emission = vec4(m.emission, 0.0);
    Terms _e195 = t;
    return _e195;
}

void main() {
    uvec3 id = gl_GlobalInvocationID;
    uint i_1 = id.x;
    if ((i_1 >= uint(_group_0_binding_3_cs.length()))) {
        return;
    }
    Params _e8 = _group_0_binding_0_cs;
    Material _e10 = _group_0_binding_1_cs;
    vec4 _e13 = _group_0_binding_3_cs[i_1];
    vec4 _e17 = _group_0_binding_4_cs[i_1];
    Terms _e19 = shade_point(_e8, _e10, _e13.xyz, _e17.xyz);
    _group_0_binding_5_cs[i_1] = _e19;
    return;
}

