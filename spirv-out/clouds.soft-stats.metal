// language: metal2.1
#include <metal_stdlib>
#include <simd/simd.h>

using metal::uint;

struct Frame {
    metal::float4 camera_position;
    metal::float4 camera_forward;
    metal::float4 camera_right;
    metal::float4 camera_up;
    metal::float4 sun_direction;
    metal::float4 sun_illuminance;
    metal::float4 atmosphere;
    metal::float4 clouds;
    metal::float4 erosion;
    metal::float4 periods;
    metal::float4 wind_offsets0_;
    metal::float4 wind_offsets1_;
    metal::float4 extinction;
    metal::float4 phase;
    metal::float4 multiple_scattering;
    metal::float4 ambient_bottom;
    metal::float4 ambient_top;
    metal::float4 march;
    metal::uint4 counts;
    metal::uint4 modes;
    metal::uint4 misc;
};
struct Roots {
    float t0_;
    float t1_;
    bool hit;
    char _pad3[3];
};
struct Interval {
    float start;
    float length;
    uint kind;
};
struct Counters {
    uint view_steps;
    uint density;
    uint detail;
    uint light;
};
struct Weather {
    float coverage;
    float cloud_type;
    float precipitation;
};
struct type_14 {
    metal::atomic_uint inner[9];
};
struct Stats {
    type_14 counters;
};
constant uint PHASE_HG = 0u;
constant uint PHASE_TWO_LOBE_HG = 1u;
constant uint PHASE_CORNETTE_SHANKS = 2u;
constant uint INTEGRATION_ANALYTIC = 0u;
constant uint INTEGRATION_RIEMANN = 1u;
constant uint HEIGHT_PARABOLA = 0u;
constant uint HEIGHT_CLOUD_TYPES = 1u;
constant uint FLAG_BEER_POWDER = 1u;
constant uint FLAG_JITTER = 2u;
constant float PI = 3.1415927;
constant uint MAX_VIEW_STEPS = 1024u;
constant uint RAY_MARCH = 0u;
constant uint RAY_MISSES_LAYER = 1u;
constant uint RAY_HITS_GROUND = 2u;
constant uint STAT_PIXELS = 0u;
constant uint STAT_MARCHED = 1u;
constant uint STAT_VIEW_STEPS = 2u;
constant uint STAT_DENSITY = 3u;
constant uint STAT_DETAIL = 4u;
constant uint STAT_LIGHT = 5u;
constant uint STAT_EXIT_TRANSMITTANCE = 6u;
constant uint STAT_EXIT_MISSED = 7u;
constant uint STAT_EXIT_GROUND = 8u;
constant uint STAT_COUNT = 9u;
constant bool LIGHT_MARCH = true;
constant uint MAX_OCTAVES = 8u;
constant bool DETAIL = false;
constant bool CURL = false;
constant bool STATS = true;

float saturate(
    float x
) {
    return metal::clamp(x, 0.0, 1.0);
}

float remap(
    float x_1,
    float lo0_,
    float hi0_,
    float lo1_,
    float hi1_
) {
    return lo1_ + (((x_1 - lo0_) * (hi1_ - lo1_)) / (hi0_ - lo0_));
}

uint pcg(
    uint v
) {
    uint state = (v * 747796405u) + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

float hash_unit(
    metal::uint2 pixel,
    uint frame_index
) {
    uint _e4 = pcg(frame_index);
    uint _e6 = pcg(pixel.y ^ _e4);
    uint _e8 = pcg(pixel.x ^ _e6);
    return static_cast<float>(_e8 >> 8u) * 0.000000059604645;
}

metal::float3 view_ray(
    metal::uint2 pixel_1,
    constant Frame& frame
) {
    metal::uint4 _e3 = frame.counts;
    metal::float2 size = static_cast<metal::float2>(_e3.xy);
    metal::float2 ndc = (((static_cast<metal::float2>(pixel_1) + metal::float2(0.5)) / size) * 2.0) - metal::float2(1.0);
    float tan_half = frame.camera_position.w;
    float aspect = frame.camera_forward.w;
    metal::float4 _e26 = frame.camera_forward;
    metal::float4 _e30 = frame.camera_right;
    metal::float4 _e39 = frame.camera_up;
    metal::float3 d_5 = (_e26.xyz + (_e30.xyz * ((ndc.x * tan_half) * aspect))) - (_e39.xyz * (ndc.y * tan_half));
    return metal::normalize(d_5);
}

Roots solve_sphere(
    float b,
    float c
) {
    float disc = (b * b) - c;
    if (disc < 0.0) {
        return Roots {0.0, 0.0, false};
    }
    float s = metal::sqrt(disc);
    float r0_1 = -((b + ((b >= 0.0) ? s : -(s))));
    if (r0_1 == 0.0) {
        return Roots {0.0, 0.0, true};
    }
    float r1_1 = c / r0_1;
    return Roots {metal::min(r0_1, r1_1), metal::max(r0_1, r1_1), true};
}

Roots ray_shell(
    float alt,
    metal::float3 d,
    float radius_alt,
    constant Frame& frame
) {
    float rp = frame.atmosphere.x;
    float b_1 = d.y * (alt + rp);
    float c_1 = (alt - radius_alt) * ((alt + radius_alt) + (2.0 * rp));
    Roots _e16 = solve_sphere(b_1, c_1);
    return _e16;
}

float altitude_of(
    metal::float3 p,
    constant Frame& frame
) {
    float rp_1 = frame.atmosphere.x;
    float n = ((p.x * p.x) + (p.z * p.z)) + (p.y * (p.y + (2.0 * rp_1)));
    metal::float3 q = metal::float3(p.x, p.y + rp_1, p.z);
    return n / (metal::length(q) + rp_1);
}

bool hits_ground(
    metal::float3 p_1,
    float alt_1,
    metal::float3 d_1,
    constant Frame& frame
) {
    bool local = {};
    float rp_2 = frame.atmosphere.x;
    float b_2 = metal::dot(d_1, metal::float3(p_1.x, p_1.y + rp_2, p_1.z));
    float c_2 = alt_1 * (alt_1 + (2.0 * rp_2));
    if (b_2 < 0.0) {
        local = (b_2 * b_2) >= c_2;
    } else {
        local = false;
    }
    bool _e24 = local;
    return _e24;
}

Interval layer_interval(
    float alt_2,
    metal::float3 d_2,
    constant Frame& frame
) {
    float start = 0.0;
    float end = 0.0;
    bool local_1 = {};
    bool local_2 = {};
    bool local_3 = {};
    float bottom = frame.atmosphere.y;
    float top = frame.atmosphere.z;
    float cutoff = frame.atmosphere.w;
    Roots _e14 = ray_shell(alt_2, d_2, bottom, frame);
    Roots _e15 = ray_shell(alt_2, d_2, top, frame);
    if (alt_2 < bottom) {
        bool _e24 = hits_ground(metal::float3(0.0, alt_2, 0.0), alt_2, d_2, frame);
        if (_e24) {
            return Interval {0.0, 0.0, 2u};
        }
        start = _e14.t1_;
        end = _e15.t1_;
    } else {
        if (alt_2 <= top) {
            end = _e15.t1_;
            if (_e14.hit) {
                local_1 = _e14.t0_ > 0.0;
            } else {
                local_1 = false;
            }
            bool _e40 = local_1;
            if (_e40) {
                float _e41 = end;
                end = metal::min(_e41, _e14.t0_);
            }
        } else {
            if (!(!(_e15.hit))) {
                local_2 = _e15.t1_ <= 0.0;
            } else {
                local_2 = true;
            }
            bool _e53 = local_2;
            if (_e53) {
                return Interval {0.0, 0.0, 1u};
            }
            start = metal::max(_e15.t0_, 0.0);
            end = _e15.t1_;
            if (_e14.hit) {
                local_3 = _e14.t0_ > 0.0;
            } else {
                local_3 = false;
            }
            bool _e69 = local_3;
            if (_e69) {
                float _e70 = end;
                end = metal::min(_e70, _e14.t0_);
            }
        }
    }
    float _e73 = end;
    float _e74 = start;
    float len = metal::min(_e73 - _e74, cutoff);
    if (!((len > 0.0))) {
        return Interval {0.0, 0.0, 1u};
    }
    float _e84 = start;
    return Interval {_e84, len, RAY_MARCH};
}

Weather sample_weather(
    metal::float3 p_2,
    constant Frame& frame,
    metal::texture2d<float, metal::access::sample> weather_tex,
    metal::sampler noise_sampler
) {
    metal::float4 _e4 = frame.wind_offsets0_;
    float _e10 = frame.periods.x;
    metal::float2 uv = (p_2.xz - _e4.xy) / metal::float2(_e10);
    metal::float4 w = weather_tex.sample(noise_sampler, uv, metal::level(0.0));
    float _e21 = frame.clouds.x;
    float _e27 = saturate(w.x + (2.0 * (_e21 - 0.5)));
    float _e31 = frame.clouds.z;
    float _e38 = saturate(_e31 + ((w.z - 0.5) * 0.5));
    float _e42 = frame.clouds.w;
    float _e46 = saturate(0.5 + w.y);
    float precipitation = _e42 * _e46;
    return Weather {_e27, _e38, precipitation};
}

float height_parabola(
    float h,
    float cloud_type
) {
    float height = metal::mix(0.35, 1.0, cloud_type);
    float _e11 = saturate((h * (h - height)) * (-4.0 / (height * height)));
    return _e11;
}

float gradient(
    float h_1,
    float r0_,
    float r1_,
    float f0_,
    float f1_
) {
    return metal::smoothstep(r0_, r1_, h_1) * (1.0 - metal::smoothstep(f0_, f1_, h_1));
}

float height_cloud_types(
    float h_2,
    float cloud_type_1
) {
    float _e6 = gradient(h_2, 0.0, 0.08, 0.15, 0.25);
    float _e11 = gradient(h_2, 0.0, 0.2, 0.4, 0.65);
    float _e16 = gradient(h_2, 0.0, 0.1, 0.6, 0.95);
    float _e19 = saturate(cloud_type_1 * 2.0);
    float lo = metal::mix(_e6, _e11, _e19);
    float _e25 = saturate((cloud_type_1 * 2.0) - 1.0);
    return metal::mix(lo, _e16, _e25);
}

float height_signal(
    float h_3,
    float cloud_type_2,
    constant Frame& frame
) {
    uint _e5 = frame.modes.z;
    if (_e5 == HEIGHT_CLOUD_TYPES) {
        float _e8 = height_cloud_types(h_3, cloud_type_2);
        return _e8;
    }
    float _e9 = height_parabola(h_3, cloud_type_2);
    return _e9;
}

float cloud_density(
    metal::float3 p_3,
    float alt_3,
    thread Counters& counters_1,
    constant Frame& frame,
    metal::texture3d<float, metal::access::sample> shape_tex,
    metal::texture3d<float, metal::access::sample> detail_tex,
    metal::texture2d<float, metal::access::sample> weather_tex,
    metal::texture2d<float, metal::access::sample> curl_tex,
    metal::sampler noise_sampler
) {
    bool local_4 = {};
    bool local_5 = {};
    float base = {};
    float density = {};
    bool local_6 = {};
    bool local_7 = {};
    metal::float3 detail_pos = {};
    float bottom_1 = frame.atmosphere.y;
    float top_1 = frame.atmosphere.z;
    float h_5 = (alt_3 - bottom_1) / (top_1 - bottom_1);
    if (!((h_5 < 0.0))) {
        local_4 = h_5 > 1.0;
    } else {
        local_4 = true;
    }
    bool _e22 = local_4;
    if (_e22) {
        return 0.0;
    }
    uint _e25 = counters_1.density;
    counters_1.density = _e25 + 1u;
    Weather _e28 = sample_weather(p_3, frame, weather_tex, noise_sampler);
    float _e30 = height_signal(h_5, _e28.cloud_type, frame);
    if (!((_e28.coverage <= 0.0))) {
        local_5 = _e30 <= 0.0;
    } else {
        local_5 = true;
    }
    bool _e40 = local_5;
    if (_e40) {
        return 0.0;
    }
    metal::float3 dims = static_cast<metal::float3>(metal::uint3(shape_tex.get_width(), shape_tex.get_height(), shape_tex.get_depth()));
    float _e48 = frame.periods.y;
    metal::float3 period = _e48 * metal::float3(1.0, dims.y / dims.x, 1.0);
    float _e60 = frame.wind_offsets0_.z;
    float _e66 = frame.wind_offsets0_.w;
    metal::float3 shape_pos = metal::float3(p_3.x - _e60, alt_3, p_3.z - _e66);
    metal::float4 s_1 = shape_tex.sample(noise_sampler, shape_pos / period, metal::level(0.0));
    float low_fbm = ((s_1.y * 0.625) + (s_1.z * 0.25)) + (s_1.w * 0.125);
    float _e91 = remap(s_1.x, low_fbm - 1.0, 1.0, 0.0, 1.0);
    float _e92 = saturate(_e91);
    base = _e92 * _e30;
    float _e95 = base;
    float _e102 = remap(_e95, 1.0 - _e28.coverage, 1.0, 0.0, 1.0);
    float _e103 = saturate(_e102);
    base = _e103 * _e28.coverage;
    float _e106 = base;
    if (_e106 <= 0.0) {
        return 0.0;
    }
    float _e110 = base;
    density = _e110;
    float strength = frame.erosion.x;
    float threshold = frame.erosion.y;
    if (DETAIL) {
        local_6 = strength > 0.0;
    } else {
        local_6 = false;
    }
    bool _e126 = local_6;
    if (_e126) {
        float _e129 = base;
        local_7 = _e129 < threshold;
    } else {
        local_7 = false;
    }
    bool _e132 = local_7;
    if (_e132) {
        uint _e134 = counters_1.detail;
        counters_1.detail = _e134 + 1u;
        detail_pos = metal::float3(p_3.x, alt_3, p_3.z);
        if (CURL) {
            metal::float4 _e145 = frame.wind_offsets1_;
            float _e151 = frame.periods.w;
            metal::float2 cuv = (p_3.xz - _e145.zw) / metal::float2(_e151);
            metal::float4 _e157 = curl_tex.sample(noise_sampler, cuv, metal::level(0.0));
            metal::float2 curl = (_e157.xy * 2.0) - metal::float2(1.0);
            metal::float3 _e164 = detail_pos;
            float _e172 = frame.erosion.z;
            detail_pos = _e164 + (metal::float3(curl.x, 0.0, curl.y) * (_e172 * (1.0 - h_5)));
        }
        metal::float3 _e178 = detail_pos;
        float _e182 = frame.wind_offsets1_.x;
        float _e186 = frame.wind_offsets1_.y;
        detail_pos = _e178 - metal::float3(_e182, 0.0, _e186);
        metal::float3 _e192 = detail_pos;
        float _e196 = frame.periods.z;
        metal::float4 dn = detail_tex.sample(noise_sampler, _e192 / metal::float3(_e196), metal::level(0.0));
        float high_fbm = ((dn.x * 0.625) + (dn.y * 0.25)) + (dn.z * 0.125);
        float _e215 = frame.extinction.w;
        float _e220 = saturate(h_5 * 10.0);
        float _e222 = saturate((2.0 * _e215) * _e220);
        float shape = metal::mix(1.0 - high_fbm, high_fbm, _e222);
        float _e227 = base;
        float erosion = (strength * shape) * (1.0 - (_e227 / threshold));
        float _e232 = base;
        float _e236 = remap(_e232, erosion, 1.0, 0.0, 1.0);
        float _e237 = saturate(_e236);
        density = _e237;
    }
    float _e238 = density;
    float _e242 = frame.erosion.w;
    density = _e238 * metal::mix(1.0, h_5, _e242);
    float _e246 = density;
    float _e250 = frame.clouds.y;
    density = (_e246 * _e250) * (1.0 + _e28.precipitation);
    float _e256 = density;
    return metal::clamp(_e256, 0.0, 1.0);
}

float phase_hg(
    float cos_theta,
    float g
) {
    float g2_ = g * g;
    float denom = metal::max((1.0 + g2_) - ((2.0 * g) * cos_theta), 0.000001);
    return (1.0 - g2_) / ((12.566371 * denom) * metal::sqrt(denom));
}

float phase_cornette_shanks(
    float cos_theta_1,
    float g_1
) {
    float g2_1 = g_1 * g_1;
    float denom_1 = metal::max((1.0 + g2_1) - ((2.0 * g_1) * cos_theta_1), 0.000001);
    return ((3.0 * (1.0 - g2_1)) * (1.0 + (cos_theta_1 * cos_theta_1))) / (((25.132742 * (2.0 + g2_1)) * denom_1) * metal::sqrt(denom_1));
}

float phase(
    float cos_theta_2,
    float scale,
    constant Frame& frame
) {
    float _e5 = frame.phase.x;
    float g_2 = _e5 * scale;
    uint _e10 = frame.modes.x;
    switch(_e10) {
        case 1u: {
            float _e14 = frame.phase.y;
            float g2_2 = _e14 * scale;
            float _e16 = phase_hg(cos_theta_2, g_2);
            float _e17 = phase_hg(cos_theta_2, g2_2);
            float _e21 = frame.phase.z;
            return metal::mix(_e16, _e17, _e21);
        }
        case 2u: {
            float _e23 = phase_cornette_shanks(cos_theta_2, g_2);
            return _e23;
        }
        default: {
            float _e24 = phase_hg(cos_theta_2, g_2);
            return _e24;
        }
    }
}

float sun_optical_depth(
    metal::float3 rel,
    metal::float3 p_4,
    thread Counters& counters_2,
    constant Frame& frame,
    metal::texture3d<float, metal::access::sample> shape_tex,
    metal::texture3d<float, metal::access::sample> detail_tex,
    metal::texture2d<float, metal::access::sample> weather_tex,
    metal::texture2d<float, metal::access::sample> curl_tex,
    metal::sampler noise_sampler
) {
    float seg = {};
    float dist = 0.0;
    float tau = 0.0;
    uint i_1 = 0u;
    bool local_8 = {};
    metal::float4 _e5 = frame.sun_direction;
    metal::float3 sun = _e5.xyz;
    float _e10 = frame.extinction.x;
    float _e14 = frame.extinction.y;
    float sigma_t_1 = _e10 + _e14;
    uint steps_1 = frame.counts.w;
    float growth = frame.march.y;
    float _e27 = frame.march.z;
    seg = _e27;
    uint2 loop_bound = uint2(4294967295u);
    bool loop_init = true;
    while(true) {
        if (metal::all(loop_bound == uint2(0u))) { break; }
        loop_bound -= uint2(loop_bound.y == 0u, 1u);
        if (!loop_init) {
            uint _e78 = i_1;
            i_1 = _e78 + 1u;
        }
        loop_init = false;
        uint _e35 = i_1;
        if (_e35 < steps_1) {
        } else {
            break;
        }
        {
            float _e37 = dist;
            float _e38 = seg;
            float s_2 = _e37 + (0.5 * _e38);
            metal::float3 q_1 = rel + (sun * s_2);
            float _e44 = altitude_of(q_1, frame);
            float _e48 = frame.atmosphere.z;
            if (!((_e44 > _e48))) {
                float _e56 = frame.atmosphere.y;
                local_8 = _e44 < _e56;
            } else {
                local_8 = true;
            }
            bool _e59 = local_8;
            if (_e59) {
                break;
            }
            uint _e61 = counters_2.light;
            counters_2.light = _e61 + 1u;
            float _e64 = tau;
            float _e67 = cloud_density(p_4 + (sun * s_2), _e44, counters_2, frame, shape_tex, detail_tex, weather_tex, curl_tex, noise_sampler);
            float _e69 = seg;
            tau = _e64 + ((_e67 * sigma_t_1) * _e69);
            float _e72 = dist;
            float _e73 = seg;
            dist = _e72 + _e73;
            float _e75 = seg;
            seg = _e75 * growth;
        }
    }
    float _e80 = tau;
    return _e80;
}

float sun_scattering(
    float cos_theta_3,
    float tau_1,
    constant Frame& frame
) {
    float total = {};
    float ka = 1.0;
    float kb = 1.0;
    float kc = 1.0;
    uint i_2 = 0u;
    float a = frame.multiple_scattering.x;
    float b_3 = frame.multiple_scattering.y;
    float c_3 = frame.multiple_scattering.z;
    uint _e17 = frame.misc.x;
    uint octaves = metal::min(_e17, MAX_OCTAVES);
    float _e21 = phase(cos_theta_3, 1.0, frame);
    total = _e21 * metal::exp(-(tau_1));
    uint2 loop_bound_1 = uint2(4294967295u);
    bool loop_init_1 = true;
    while(true) {
        if (metal::all(loop_bound_1 == uint2(0u))) { break; }
        loop_bound_1 -= uint2(loop_bound_1.y == 0u, 1u);
        if (!loop_init_1) {
            uint _e54 = i_2;
            i_2 = _e54 + 1u;
        }
        loop_init_1 = false;
        uint _e34 = i_2;
        if (_e34 < octaves) {
        } else {
            break;
        }
        {
            float _e36 = ka;
            ka = _e36 * a;
            float _e38 = kb;
            kb = _e38 * b_3;
            float _e40 = kc;
            kc = _e40 * c_3;
            float _e42 = total;
            float _e43 = ka;
            float _e44 = kc;
            float _e45 = phase(cos_theta_3, _e44, frame);
            float _e47 = kb;
            total = _e42 + ((_e43 * _e45) * metal::exp(-(_e47) * tau_1));
        }
    }
    uint _e59 = frame.modes.w;
    if ((_e59 & FLAG_BEER_POWDER) != 0u) {
        float _e64 = total;
        float _e68 = frame.phase.w;
        total = _e64 * (1.0 - metal::exp(-(_e68) * tau_1));
    }
    float _e75 = total;
    return _e75;
}

metal::float3 ambient(
    float h_4,
    constant Frame& frame
) {
    metal::float4 _e3 = frame.ambient_bottom;
    metal::float4 _e7 = frame.ambient_top;
    float _e13 = frame.ambient_bottom.w;
    return metal::mix(_e3.xyz, _e7.xyz, h_4) * _e13;
}

metal::float3 scattered_light(
    metal::float3 rel_1,
    metal::float3 p_5,
    float alt_4,
    float density_1,
    metal::float3 view,
    thread Counters& counters_3,
    constant Frame& frame,
    metal::texture3d<float, metal::access::sample> shape_tex,
    metal::texture3d<float, metal::access::sample> detail_tex,
    metal::texture2d<float, metal::access::sample> weather_tex,
    metal::texture2d<float, metal::access::sample> curl_tex,
    metal::sampler noise_sampler
) {
    metal::float3 sun_light = metal::float3(0.0);
    float tau_2 = 0.0;
    metal::float4 _e8 = frame.sun_direction;
    metal::float3 sun_1 = _e8.xyz;
    float _e13 = frame.atmosphere.y;
    float _e18 = frame.atmosphere.z;
    float _e22 = frame.atmosphere.y;
    float _e25 = saturate((alt_4 - _e13) / (_e18 - _e22));
    bool _e29 = hits_ground(rel_1, alt_4, sun_1, frame);
    if (!(_e29)) {
        if (LIGHT_MARCH) {
            float _e34 = sun_optical_depth(rel_1, p_5, counters_3, frame, shape_tex, detail_tex, weather_tex, curl_tex, noise_sampler);
            tau_2 = _e34;
        }
        metal::float4 _e37 = frame.sun_illuminance;
        float _e40 = tau_2;
        float _e41 = sun_scattering(metal::dot(view, sun_1), _e40, frame);
        sun_light = _e37.xyz * _e41;
    }
    Weather _e43 = sample_weather(p_5, frame, weather_tex, noise_sampler);
    float _e47 = frame.extinction.z;
    float _e55 = saturate(1.0 - ((_e47 * _e43.precipitation) * (1.0 - _e25)));
    float _e59 = frame.extinction.x;
    metal::float3 _e61 = sun_light;
    metal::float3 _e62 = ambient(_e25, frame);
    return ((_e59 * density_1) * (_e61 + _e62)) * _e55;
}

void count(
    uint index,
    uint value,
    device Stats& stats
) {
    bool local_9 = {};
    if (STATS) {
        local_9 = value != 0u;
    } else {
        local_9 = false;
    }
    bool _e8 = local_9;
    if (_e8) {
        uint _e12 = metal::atomic_fetch_add_explicit(&stats.counters.inner[index], value, metal::memory_order_relaxed);
        return;
    } else {
        return;
    }
}

metal::float3 step_integral(
    metal::float3 source,
    float sigma_t,
    float dt,
    constant Frame& frame
) {
    uint _e6 = frame.modes.y;
    if (_e6 == INTEGRATION_RIEMANN) {
        return source * dt;
    }
    float x_3 = sigma_t * dt;
    float f = (x_3 < 0.001) ? (1.0 - (0.5 * x_3)) : ((1.0 - metal::exp(-(x_3))) / x_3);
    return source * (dt * f);
}

metal::float3 sky_radiance(
    metal::float3 d_3,
    float alt_5,
    constant Frame& frame
) {
    metal::float4 _e4 = frame.sun_direction;
    metal::float3 sun_2 = _e4.xyz;
    metal::float4 _e8 = frame.sun_illuminance;
    metal::float3 e = _e8.xyz;
    float _e15 = saturate((sun_2.y * 4.0) + 0.3);
    bool _e19 = hits_ground(metal::float3(0.0, alt_5, 0.0), alt_5, d_3, frame);
    if (_e19) {
        metal::float3 ground_albedo = metal::float3(0.035, 0.035, 0.03);
        return ground_albedo * (((e * metal::max(sun_2.y, 0.0)) / metal::float3(3.1415927)) + ((0.05 * e) * _e15));
    }
    metal::float3 zenith = metal::float3(0.018, 0.04, 0.1);
    metal::float3 horizon = metal::float3(0.07, 0.085, 0.11);
    float _e45 = saturate(d_3.y);
    metal::float3 gradient_1 = metal::mix(horizon, zenith, metal::sqrt(_e45));
    metal::float3 sunset = ((1.0 - (_e15 * 0.8)) * metal::pow(1.0 - _e45, 6.0)) * metal::float3(0.25, 0.1, 0.0);
    float _e64 = phase_hg(metal::dot(d_3, sun_2), 0.76);
    float glow = _e64 * 0.02;
    float _e73 = saturate((sun_2.y * 10.0) + 1.0);
    return e * (((gradient_1 * _e15) + (sunset * _e73)) + metal::float3(glow * _e15));
}

metal::float3 sun_disk(
    metal::float3 d_4,
    constant Frame& frame
) {
    float cos_r = frame.sun_direction.w;
    metal::float4 _e7 = frame.sun_direction;
    if (metal::dot(d_4, _e7.xyz) < cos_r) {
        return metal::float3(0.0);
    }
    metal::float4 _e15 = frame.sun_illuminance;
    return _e15.xyz / metal::float3(6.2831855 * metal::max(1.0 - cos_r, 0.000001));
}

metal::float3 aces_fitted(
    metal::float3 x_2
) {
    return metal::clamp((x_2 * ((2.51 * x_2) + metal::float3(0.03))) / ((x_2 * ((2.43 * x_2) + metal::float3(0.59))) + metal::float3(0.14)), metal::float3(0.0), metal::float3(1.0));
}
uint naga_f2u32(float value) {
    return static_cast<uint>(metal::clamp(value, 0.0, 4294967000.0));
}


struct marchInput {
};
[[max_total_threads_per_threadgroup(64)]] kernel void march(
  metal::uint3 id [[thread_position_in_grid]]
, constant Frame& frame [[user(fake0)]]
, metal::texture3d<float, metal::access::sample> shape_tex [[user(fake0)]]
, metal::texture3d<float, metal::access::sample> detail_tex [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> weather_tex [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> curl_tex [[user(fake0)]]
, metal::sampler noise_sampler [[user(fake0)]]
, metal::texture2d<float, metal::access::write> cloud_out [[user(fake0)]]
, metal::texture2d<float, metal::access::write> depth_out [[user(fake0)]]
, device Stats& stats [[user(fake0)]]
) {
    Counters counters = Counters {0u, 0u, 0u, 0u};
    metal::float3 radiance = metal::float3(0.0);
    float transmittance = 1.0;
    float depth_sum = 0.0;
    uint steps = {};
    float jitter = 0.5;
    uint i = 0u;
    float depth = 0.0;
    metal::uint4 _e4 = frame.counts;
    if (metal::any(id.xy >= _e4.xy)) {
        return;
    }
    metal::uint2 pixel_2 = id.xy;
    metal::float3 _e9 = view_ray(pixel_2, frame);
    float cam_alt = frame.camera_position.y;
    metal::float4 _e16 = frame.camera_position;
    metal::float2 cam_xz = _e16.xz;
    count(STAT_PIXELS, 1u, stats);
    Interval _e33 = layer_interval(cam_alt, _e9, frame);
    if (_e33.kind == RAY_MISSES_LAYER) {
        count(STAT_EXIT_MISSED, 1u, stats);
    } else {
        if (_e33.kind == RAY_HITS_GROUND) {
            count(STAT_EXIT_GROUND, 1u, stats);
        } else {
            count(STAT_MARCHED, 1u, stats);
            uint _e49 = frame.counts.z;
            steps = _e49;
            float _e54 = frame.march.x;
            if (_e54 > 0.0) {
                float _e61 = frame.march.x;
                steps = metal::clamp(naga_f2u32(metal::ceil(_e33.length / _e61)), 1u, MAX_VIEW_STEPS);
            }
            uint _e69 = steps;
            float dt_1 = _e33.length / static_cast<float>(_e69);
            uint _e77 = frame.modes.w;
            if ((_e77 & FLAG_JITTER) != 0u) {
                uint _e85 = frame.misc.y;
                float _e86 = hash_unit(pixel_2, _e85);
                jitter = _e86;
            }
            float _e90 = frame.extinction.x;
            float _e94 = frame.extinction.y;
            float sigma_e = _e90 + _e94;
            uint2 loop_bound_2 = uint2(4294967295u);
            bool loop_init_2 = true;
            while(true) {
                if (metal::all(loop_bound_2 == uint2(0u))) { break; }
                loop_bound_2 -= uint2(loop_bound_2.y == 0u, 1u);
                if (!loop_init_2) {
                    uint _e157 = i;
                    i = _e157 + 1u;
                }
                loop_init_2 = false;
                uint _e98 = i;
                uint _e99 = steps;
                if (_e98 < _e99) {
                } else {
                    break;
                }
                {
                    uint _e102 = counters.view_steps;
                    counters.view_steps = _e102 + 1u;
                    uint _e106 = i;
                    float _e108 = jitter;
                    float t = _e33.start + ((static_cast<float>(_e106) + _e108) * dt_1);
                    metal::float3 rel_2 = (_e9 * t) + metal::float3(0.0, cam_alt, 0.0);
                    metal::float3 p_6 = metal::float3(rel_2.x + cam_xz.x, rel_2.y, rel_2.z + cam_xz.y);
                    float _e125 = altitude_of(rel_2, frame);
                    float _e126 = cloud_density(p_6, _e125, counters, frame, shape_tex, detail_tex, weather_tex, curl_tex, noise_sampler);
                    if (_e126 <= 0.0) {
                        continue;
                    }
                    float sigma_t_2 = sigma_e * _e126;
                    metal::float3 _e130 = scattered_light(rel_2, p_6, _e125, _e126, _e9, counters, frame, shape_tex, detail_tex, weather_tex, curl_tex, noise_sampler);
                    metal::float3 _e131 = radiance;
                    float _e132 = transmittance;
                    metal::float3 _e133 = step_integral(_e130, sigma_t_2, dt_1, frame);
                    radiance = _e131 + (_e132 * _e133);
                    float step_t = metal::exp(-(sigma_t_2) * dt_1);
                    float _e139 = depth_sum;
                    float _e140 = transmittance;
                    depth_sum = _e139 + ((t * _e140) * (1.0 - step_t));
                    float _e146 = transmittance;
                    transmittance = _e146 * step_t;
                    float _e148 = transmittance;
                    float _e152 = frame.march.w;
                    if (_e148 < _e152) {
                        count(STAT_EXIT_TRANSMITTANCE, 1u, stats);
                        break;
                    }
                }
            }
        }
    }
    uint _e161 = counters.view_steps;
    count(STAT_VIEW_STEPS, _e161, stats);
    uint _e164 = counters.density;
    count(STAT_DENSITY, _e164, stats);
    uint _e167 = counters.detail;
    count(STAT_DETAIL, _e167, stats);
    uint _e170 = counters.light;
    count(STAT_LIGHT, _e170, stats);
    float _e173 = transmittance;
    if (_e173 < 1.0) {
        float _e176 = depth_sum;
        float _e177 = transmittance;
        depth = _e176 / (1.0 - _e177);
    }
    metal::float3 _e182 = radiance;
    float _e183 = transmittance;
    cloud_out.write(metal::float4(_e182, _e183), metal::uint2(pixel_2));
    float _e186 = depth;
    depth_out.write(metal::float4(_e186, 0.0, 0.0, 0.0), metal::uint2(pixel_2));
    return;
}


struct compositeInput {
};
[[max_total_threads_per_threadgroup(64)]] kernel void composite(
  metal::uint3 id_1 [[thread_position_in_grid]]
, constant Frame& frame [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> cloud_in [[user(fake0)]]
, metal::texture2d<float, metal::access::write> image_out [[user(fake0)]]
) {
    metal::float3 background = {};
    metal::uint4 _e4 = frame.counts;
    if (metal::any(id_1.xy >= _e4.xy)) {
        return;
    }
    metal::uint2 pixel_3 = id_1.xy;
    metal::float3 _e9 = view_ray(pixel_3, frame);
    float alt_6 = frame.camera_position.y;
    metal::float4 cloud = cloud_in.read(metal::uint2(pixel_3), 0);
    metal::float3 _e17 = sky_radiance(_e9, alt_6, frame);
    background = _e17;
    bool _e22 = hits_ground(metal::float3(0.0, alt_6, 0.0), alt_6, _e9, frame);
    if (!(_e22)) {
        metal::float3 _e24 = background;
        metal::float3 _e25 = sun_disk(_e9, frame);
        background = _e24 + _e25;
    }
    metal::float3 _e27 = background;
    metal::float3 radiance_1 = (_e27 * cloud.w) + cloud.xyz;
    float _e35 = frame.camera_right.w;
    metal::float3 exposed = radiance_1 * _e35;
    metal::float3 _e37 = aces_fitted(exposed);
    metal::float3 display = metal::pow(_e37, metal::float3(0.45454547));
    image_out.write(metal::float4(display, 1.0), metal::uint2(pixel_3));
    return;
}
