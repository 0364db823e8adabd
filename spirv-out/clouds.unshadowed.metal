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
    metal::float4 previous_position;
    metal::float4 previous_forward;
    metal::float4 previous_right;
    metal::float4 previous_up;
    metal::uint4 temporal;
    metal::float4 layer1_;
    metal::float4 layer1_weather;
    metal::float4 layer2_;
    metal::float4 layer2_weather;
    metal::float4 layer3_;
    metal::float4 layer3_weather;
    metal::float4 air_rayleigh;
    metal::float4 air_mie;
    metal::float4 air_ozone;
    metal::float4 air_misc;
    metal::float4 moon;
    metal::float4 night;
    metal::float4 light_model;
    metal::float4 octave_direction;
    metal::float4 octave_depth;
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
struct Layer {
    float bottom;
    float top;
    float coverage;
    float density;
    float cloud_type;
    float precipitation;
    metal::float2 weather_offset;
};
struct AirSample {
    metal::packed_float3 rayleigh;
    float mie;
    metal::float3 extinction;
};
struct Scattered {
    metal::float3 radiance;
    metal::float3 transmittance;
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
struct SunScattering {
    float total;
    float octaves;
};
struct ScatteredLight {
    metal::float3 total;
    metal::float3 octaves;
};
struct type_18 {
    metal::atomic_uint inner[9];
};
struct Stats {
    type_18 counters;
};
struct MarchResult {
    metal::packed_float3 radiance;
    float transmittance;
    float depth;
    char _pad3[12];
};
struct MarchState {
    metal::packed_float3 radiance;
    float transmittance;
    float depth_sum;
    char _pad3[12];
    metal::float3 octaves;
};
struct Segments {
    metal::float2 a;
    metal::float2 b;
    uint count;
    char _pad3[4];
};
struct PhaseSample {
    metal::packed_float3 dir;
    float weight;
};
struct PathResult {
    metal::packed_float3 radiance;
    float transmittance;
    float depth;
    char _pad3[12];
};
struct type_21 {
    metal::float4 inner[32];
};
struct SpriteCell {
    metal::int2 index;
    float size;
    bool covered;
    char _pad3[3];
};
struct SpriteCandidate {
    metal::float2 xz;
    float alt;
    float h;
    float size_hash;
    float texture_hash;
    float rotation_hash;
    float density;
    float precipitation;
    char _pad8[4];
};
struct SpriteVertex {
    metal::float4 position;
    metal::float2 uv;
    uint tile;
    char _pad3[4];
    metal::float4 colour;
    float distance;
    char _pad5[12];
};
struct SpriteTargets {
    metal::float4 radiance;
    metal::float4 depth;
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
constant uint FLAG_DYNAMIC_STEP = 4u;
constant uint FLAG_CHECKERBOARD = 8u;
constant uint FLAG_EMPTY_SKIP = 16u;
constant uint FLAG_PHYSICAL_SKY = 32u;
constant uint FLAG_MOONLIT = 64u;
constant float PI = 3.1415927;
constant uint MAX_VIEW_STEPS = 1024u;
constant uint RAY_MARCH = 0u;
constant uint RAY_MISSES_LAYER = 1u;
constant uint RAY_HITS_GROUND = 2u;
constant uint MAX_LAYERS = 4u;
constant metal::uint2 TRANSMITTANCE_SIZE = metal::uint2(256u, 64u);
constant metal::uint2 MULTISCATTER_SIZE = metal::uint2(32u, 32u);
constant metal::uint2 SKY_VIEW_SIZE = metal::uint2(192u, 108u);
constant uint AERIAL_SLICES = 32u;
constant uint AERIAL_SIDE = 32u;
constant float AERIAL_SLICE_KM = 1.0;
constant uint TRANSMITTANCE_STEPS = 128u;
constant uint MULTISCATTER_DIRECTIONS = 64u;
constant uint MULTISCATTER_STEPS = 32u;
constant uint SKY_VIEW_STEPS = 48u;
constant uint AMBIENT_DIRECTIONS = 64u;
constant uint AMBIENT_STEPS = 24u;
constant uint SKY_AMBIENT_SUNS = 64u;
constant uint GROUND_IRRADIANCE_SIZE = 64u;
constant uint NO_LAYER = 4u;
constant uint COLUMN_STEPS = 3u;
constant float DECK_POWER = 8.0;
constant float FORWARD_LOBE_THIN = 0.1;
constant uint GROUND_IRRADIANCE_DIRECTIONS = 128u;
constant uint SHADOW_SIZE = 128u;
constant float SHADOW_HALF_EXTENT = 20000.0;
constant float SHADOW_FADE_START = 0.75;
constant uint SHADOW_STEPS = 16u;
constant uint OCCUPANCY_CELLS = 64u;
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
constant float HISTORY_SAMPLES = 16.0;
constant float HISTORY_SAMPLES_MOVING = 2.0;
constant float DISOCCLUSION_DEPTH = 0.5;
constant uint MAX_PATH_ORDERS = 16384u;
constant uint PATHS_PER_FRAME = 32u;
constant uint SPRITE_LEVELS = 4u;
constant int SPRITE_CELLS_PER_SIDE = 8;
constant uint SPRITES_PER_CELL = 16u;
constant uint SPRITE_COUNT = 4096u;
constant float SPRITE_CELL0_ = 1500.0;
constant float SPRITE_ALPHA = 0.7;
constant float SPRITE_MAX_DISTANCE = 131072.0;
constant uint ATLAS_TILE = 64u;
constant float SPRITE_C_MIN = 0.22;
constant float SPRITE_C_MED = 0.55;
constant float SPRITE_C_MAX = 1.0;
constant float SPRITE_SKY = 0.35;
constant metal::float3 SKY_LEVEL0_ = metal::float3(0.42, 0.46, 0.55);
constant metal::float3 SKY_LEVEL1_ = metal::float3(0.55, 0.59, 0.67);
constant metal::float3 SKY_LEVEL2_ = metal::float3(0.7, 0.73, 0.8);
constant metal::float3 SKY_LEVEL3_ = metal::float3(0.84, 0.86, 0.9);
constant metal::float3 SKY_LEVEL4_ = metal::float3(0.95, 0.96, 0.98);
constant float MOON_COS_RADIUS = 0.9999898;
constant uint STAR_CELLS = 96u;
constant float STAR_FAINTEST = 6.5;
constant bool LIGHT_MARCH = false;
constant uint MAX_OCTAVES = 0u;
constant bool DETAIL = false;
constant bool CURL = false;
constant bool STATS = false;

float saturate(
    float x_1
) {
    return metal::clamp(x_1, 0.0, 1.0);
}

float remap(
    float x_2,
    float lo0_,
    float hi0_,
    float lo1_,
    float hi1_
) {
    return lo1_ + (((x_2 - lo0_) * (hi1_ - lo1_)) / (hi0_ - lo0_));
}

uint pcg(
    uint v
) {
    uint state_2 = (v * 747796405u) + 2891336453u;
    uint word = ((state_2 >> ((state_2 >> 28u) + 4u)) ^ state_2) * 277803737u;
    return (word >> 22u) ^ word;
}

float van_der_corput(
    uint n
) {
    return static_cast<float>(metal::reverse_bits(n) >> 8u) * 0.000000059604645;
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
    metal::float2 size_1 = static_cast<metal::float2>(_e3.xy);
    metal::float2 ndc = (((static_cast<metal::float2>(pixel_1) + metal::float2(0.5)) / size_1) * 2.0) - metal::float2(1.0);
    float tan_half = frame.camera_position.w;
    float aspect = frame.camera_forward.w;
    metal::float4 _e26 = frame.camera_forward;
    metal::float4 _e30 = frame.camera_right;
    metal::float4 _e39 = frame.camera_up;
    metal::float3 d_21 = (_e26.xyz + (_e30.xyz * ((ndc.x * tan_half) * aspect))) - (_e39.xyz * (ndc.y * tan_half));
    return metal::normalize(d_21);
}

Roots solve_sphere(
    float b,
    float c
) {
    float disc = (b * b) - c;
    if (disc < 0.0) {
        return Roots {0.0, 0.0, false};
    }
    float s_3 = metal::sqrt(disc);
    float r0_1 = -((b + ((b >= 0.0) ? s_3 : -(s_3))));
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
    float b_3 = d.y * (alt + rp);
    float c_5 = (alt - radius_alt) * ((alt + radius_alt) + (2.0 * rp));
    Roots _e16 = solve_sphere(b_3, c_5);
    return _e16;
}

float altitude_of(
    metal::float3 p,
    constant Frame& frame
) {
    float rp_1 = frame.atmosphere.x;
    float n_3 = ((p.x * p.x) + (p.z * p.z)) + (p.y * (p.y + (2.0 * rp_1)));
    metal::float3 q_5 = metal::float3(p.x, p.y + rp_1, p.z);
    return n_3 / (metal::length(q_5) + rp_1);
}

bool hits_ground(
    metal::float3 p_1,
    float alt_1,
    metal::float3 d_1,
    constant Frame& frame
) {
    bool local_15 = {};
    float rp_2 = frame.atmosphere.x;
    float b_4 = metal::dot(d_1, metal::float3(p_1.x, p_1.y + rp_2, p_1.z));
    float c_6 = alt_1 * (alt_1 + (2.0 * rp_2));
    if (b_4 < 0.0) {
        local_15 = (b_4 * b_4) >= c_6;
    } else {
        local_15 = false;
    }
    bool _e24 = local_15;
    return _e24;
}

Interval shell_interval(
    float alt_2,
    metal::float3 d_2,
    float bottom,
    float top,
    constant Frame& frame
) {
    float start = 0.0;
    float end = 0.0;
    bool local_16 = {};
    bool local_17 = {};
    bool local_18 = {};
    float cutoff = frame.atmosphere.w;
    Roots _e8 = ray_shell(alt_2, d_2, bottom, frame);
    Roots _e9 = ray_shell(alt_2, d_2, top, frame);
    if (alt_2 < bottom) {
        bool _e18 = hits_ground(metal::float3(0.0, alt_2, 0.0), alt_2, d_2, frame);
        if (_e18) {
            return Interval {0.0, 0.0, 2u};
        }
        start = _e8.t1_;
        end = _e9.t1_;
    } else {
        if (alt_2 <= top) {
            end = _e9.t1_;
            if (_e8.hit) {
                local_16 = _e8.t0_ > 0.0;
            } else {
                local_16 = false;
            }
            bool _e34 = local_16;
            if (_e34) {
                float _e35 = end;
                end = metal::min(_e35, _e8.t0_);
            }
        } else {
            if (!(!(_e9.hit))) {
                local_17 = _e9.t1_ <= 0.0;
            } else {
                local_17 = true;
            }
            bool _e47 = local_17;
            if (_e47) {
                return Interval {0.0, 0.0, 1u};
            }
            start = metal::max(_e9.t0_, 0.0);
            end = _e9.t1_;
            if (_e8.hit) {
                local_18 = _e8.t0_ > 0.0;
            } else {
                local_18 = false;
            }
            bool _e63 = local_18;
            if (_e63) {
                float _e64 = end;
                end = metal::min(_e64, _e8.t0_);
            }
        }
    }
    float _e67 = end;
    float _e68 = start;
    float len = metal::min(_e67 - _e68, cutoff);
    if (!((len > 0.0))) {
        return Interval {0.0, 0.0, 1u};
    }
    float _e78 = start;
    return Interval {_e78, len, RAY_MARCH};
}

Interval layer_interval(
    float alt_3,
    metal::float3 d_3,
    Layer l,
    constant Frame& frame
) {
    Interval _e5 = shell_interval(alt_3, d_3, l.bottom, l.top, frame);
    return _e5;
}

uint layer_count(
    constant Frame& frame
) {
    uint _e4 = frame.misc.w;
    return 1u + metal::min(_e4, 3u);
}

Layer layer_from(
    metal::float4 g,
    metal::float4 w_1
) {
    return Layer {g.x, g.y, g.z, g.w, w_1.x, w_1.y, w_1.zw};
}

Layer cloud_layer(
    uint i_5,
    constant Frame& frame
) {
    if (i_5 == 1u) {
        metal::float4 _e5 = frame.layer1_;
        metal::float4 _e8 = frame.layer1_weather;
        Layer _e9 = layer_from(_e5, _e8);
        return _e9;
    } else {
        if (i_5 == 2u) {
            metal::float4 _e14 = frame.layer2_;
            metal::float4 _e17 = frame.layer2_weather;
            Layer _e18 = layer_from(_e14, _e17);
            return _e18;
        } else {
            if (i_5 == 3u) {
                metal::float4 _e23 = frame.layer3_;
                metal::float4 _e26 = frame.layer3_weather;
                Layer _e27 = layer_from(_e23, _e26);
                return _e27;
            }
        }
    }
    float _e31 = frame.atmosphere.y;
    float _e35 = frame.atmosphere.z;
    float _e39 = frame.clouds.x;
    float _e43 = frame.clouds.y;
    float _e47 = frame.clouds.z;
    float _e51 = frame.clouds.w;
    metal::float4 _e54 = frame.wind_offsets0_;
    return Layer {_e31, _e35, _e39, _e43, _e47, _e51, _e54.xy};
}

metal::float2 layers_span(
    constant Frame& frame
) {
    metal::float2 span = {};
    uint i_6 = 1u;
    metal::float4 _e2 = frame.atmosphere;
    span = _e2.yz;
    uint2 loop_bound = uint2(4294967295u);
    bool loop_init = true;
    while(true) {
        if (metal::all(loop_bound == uint2(0u))) { break; }
        loop_bound -= uint2(loop_bound.y == 0u, 1u);
        if (!loop_init) {
            uint _e22 = i_6;
            i_6 = _e22 + 1u;
        }
        loop_init = false;
        uint _e7 = i_6;
        uint _e8 = layer_count(frame);
        if (_e7 < _e8) {
        } else {
            break;
        }
        {
            uint _e10 = i_6;
            Layer _e11 = cloud_layer(_e10, frame);
            float _e13 = span.x;
            float _e17 = span.y;
            span = metal::float2(metal::min(_e13, _e11.bottom), metal::max(_e17, _e11.top));
        }
    }
    metal::float2 _e24 = span;
    return _e24;
}

Interval cloud_interval(
    float alt_4,
    metal::float3 d_4,
    constant Frame& frame
) {
    metal::float2 _e2 = layers_span(frame);
    Interval _e5 = shell_interval(alt_4, d_4, _e2.x, _e2.y, frame);
    return _e5;
}

Interval nearest_layer_interval(
    float alt_5,
    metal::float3 d_5,
    constant Frame& frame
) {
    Interval best = {};
    uint i_7 = 1u;
    bool local_19 = {};
    bool local_20 = {};
    Layer _e3 = cloud_layer(0u, frame);
    Interval _e4 = layer_interval(alt_5, d_5, _e3, frame);
    best = _e4;
    uint2 loop_bound_1 = uint2(4294967295u);
    bool loop_init_1 = true;
    while(true) {
        if (metal::all(loop_bound_1 == uint2(0u))) { break; }
        loop_bound_1 -= uint2(loop_bound_1.y == 0u, 1u);
        if (!loop_init_1) {
            uint _e35 = i_7;
            i_7 = _e35 + 1u;
        }
        loop_init_1 = false;
        uint _e8 = i_7;
        uint _e9 = layer_count(frame);
        if (_e8 < _e9) {
        } else {
            break;
        }
        {
            uint _e11 = i_7;
            Layer _e12 = cloud_layer(_e11, frame);
            Interval _e13 = layer_interval(alt_5, d_5, _e12, frame);
            if (_e13.kind == RAY_MARCH) {
                uint _e20 = best.kind;
                if (!((_e20 != RAY_MARCH))) {
                    float _e28 = best.start;
                    local_20 = _e13.start < _e28;
                } else {
                    local_20 = true;
                }
                bool _e31 = local_20;
                local_19 = _e31;
            } else {
                local_19 = false;
            }
            bool _e33 = local_19;
            if (_e33) {
                best = _e13;
            }
        }
    }
    Interval _e37 = best;
    return _e37;
}

Roots ray_shell_from(
    metal::float3 p_2,
    float alt_6,
    metal::float3 d_6,
    float radius_alt_1,
    constant Frame& frame
) {
    float rp_3 = frame.atmosphere.x;
    float b_5 = metal::dot(d_6, metal::float3(p_2.x, p_2.y + rp_3, p_2.z));
    float c_7 = (alt_6 - radius_alt_1) * ((alt_6 + radius_alt_1) + (2.0 * rp_3));
    Roots _e20 = solve_sphere(b_5, c_7);
    return _e20;
}

bool physical_sky(
    constant Frame& frame
) {
    uint _e3 = frame.modes.w;
    return (_e3 & FLAG_PHYSICAL_SKY) != 0u;
}

float air_bottom(
    constant Frame& frame
) {
    float _e3 = frame.atmosphere.x;
    return _e3 * 0.001;
}

float air_top(
    constant Frame& frame
) {
    float _e3 = frame.atmosphere.x;
    float _e7 = frame.air_misc.x;
    return (_e3 + _e7) * 0.001;
}

AirSample air_at(
    float h_km,
    constant Frame& frame
) {
    float h_11 = metal::max(h_km, 0.0) * 1000.0;
    float _e9 = frame.air_rayleigh.w;
    float rayleigh_density = metal::exp(-(h_11) / _e9);
    float _e16 = frame.air_mie.z;
    float mie_density = metal::exp(-(h_11) / _e16);
    float _e22 = frame.air_ozone.w;
    float _e28 = frame.air_misc.y;
    float ozone_density = metal::max(1.0 - (metal::abs(h_11 - _e22) / (0.5 * _e28)), 0.0);
    metal::float4 _e38 = frame.air_rayleigh;
    metal::float3 rayleigh = _e38.xyz * (rayleigh_density * 1000.0);
    float _e46 = frame.air_mie.x;
    float mie = (_e46 * mie_density) * 1000.0;
    float _e53 = frame.air_mie.x;
    float _e57 = frame.air_mie.y;
    float mie_extinction = ((_e53 + _e57) * mie_density) * 1000.0;
    metal::float4 _e64 = frame.air_ozone;
    metal::float3 ozone = _e64.xyz * (ozone_density * 1000.0);
    return AirSample {rayleigh, mie, (rayleigh + metal::float3(mie_extinction)) + ozone};
}

float sphere_discriminant(
    float r_2,
    float mu,
    float radius
) {
    return ((radius - r_2) * (radius + r_2)) + (((r_2 * r_2) * mu) * mu);
}

float distance_to_top(
    float r_3,
    float mu_1,
    constant Frame& frame
) {
    float _e4 = air_top(frame);
    float _e5 = sphere_discriminant(r_3, mu_1, _e4);
    return metal::max((-(r_3) * mu_1) + metal::sqrt(metal::max(_e5, 0.0)), 0.0);
}

bool meets_ground(
    float r_4,
    float mu_2,
    constant Frame& frame
) {
    bool local_21 = {};
    if (mu_2 < 0.0) {
        float _e6 = air_bottom(frame);
        float _e7 = sphere_discriminant(r_4, mu_2, _e6);
        local_21 = _e7 >= 0.0;
    } else {
        local_21 = false;
    }
    bool _e11 = local_21;
    return _e11;
}

float distance_to_ground(
    float r_5,
    float mu_3,
    constant Frame& frame
) {
    float _e4 = air_bottom(frame);
    float _e5 = sphere_discriminant(r_5, mu_3, _e4);
    return metal::max((-(r_5) * mu_3) - metal::sqrt(metal::max(_e5, 0.0)), 0.0);
}

float radius_after(
    float r_6,
    float mu_4,
    float t
) {
    return metal::sqrt(metal::max(((r_6 * r_6) + (t * t)) + (((2.0 * r_6) * mu_4) * t), 0.0));
}

metal::uint2 naga_f2u32(metal::float2 value) {
    return static_cast<metal::uint2>(metal::clamp(value, 0.0, 4294967000.0));
}

metal::float4 lut_bilinear(
    metal::texture2d<float, metal::access::sample> lut,
    metal::float2 x_3,
    metal::uint2 size
) {
    metal::float2 last = static_cast<metal::float2>(size - metal::uint2(1u));
    metal::float2 f_1 = metal::clamp(x_3, metal::float2(0.0), metal::float2(1.0)) * last;
    metal::uint2 i0_ = metal::min(naga_f2u32(metal::floor(f_1)), size - metal::uint2(1u));
    metal::uint2 i1_ = metal::min(i0_ + metal::uint2(1u), size - metal::uint2(1u));
    metal::float2 w_3 = f_1 - static_cast<metal::float2>(i0_);
    metal::float4 _e32 = lut.read(metal::uint2(metal::uint2(i0_.x, i0_.y)), 0);
    metal::float4 _e37 = lut.read(metal::uint2(metal::uint2(i1_.x, i0_.y)), 0);
    metal::float4 a_4 = metal::mix(_e32, _e37, w_3.x);
    metal::float4 _e44 = lut.read(metal::uint2(metal::uint2(i0_.x, i1_.y)), 0);
    metal::float4 _e49 = lut.read(metal::uint2(metal::uint2(i1_.x, i1_.y)), 0);
    metal::float4 b_6 = metal::mix(_e44, _e49, w_3.x);
    return metal::mix(a_4, b_6, w_3.y);
}

metal::float2 transmittance_coords(
    float r_7,
    float mu_5,
    constant Frame& frame
) {
    float _e2 = air_bottom(frame);
    float _e3 = air_top(frame);
    float h_12 = metal::sqrt(metal::max((_e3 - _e2) * (_e3 + _e2), 0.0));
    float rho = metal::sqrt(metal::max((r_7 - _e2) * (r_7 + _e2), 0.0));
    float _e16 = distance_to_top(r_7, mu_5, frame);
    float d_min = _e3 - r_7;
    float d_max = rho + h_12;
    return metal::float2((_e16 - d_min) / metal::max(d_max - d_min, 0.000001), rho / h_12);
}

metal::float2 transmittance_r_mu(
    metal::float2 x_4,
    constant Frame& frame
) {
    float mu_6 = 1.0;
    float _e1 = air_bottom(frame);
    float _e2 = air_top(frame);
    float h_13 = metal::sqrt(metal::max((_e2 - _e1) * (_e2 + _e1), 0.0));
    float rho_1 = h_13 * x_4.y;
    float r_14 = metal::sqrt((rho_1 * rho_1) + (_e1 * _e1));
    float d_min_1 = _e2 - r_14;
    float d_max_1 = rho_1 + h_13;
    float d_22 = d_min_1 + (x_4.x * (d_max_1 - d_min_1));
    if (d_22 > 0.0) {
        mu_6 = metal::clamp((((h_13 * h_13) - (rho_1 * rho_1)) - (d_22 * d_22)) / ((2.0 * r_14) * d_22), -1.0, 1.0);
    }
    float _e37 = mu_6;
    return metal::float2(r_14, _e37);
}

metal::float3 transmittance_to_top(
    float r_8,
    float mu_7,
    constant Frame& frame,
    metal::texture2d<float, metal::access::sample> transmittance_lut_in
) {
    metal::float2 _e3 = transmittance_coords(r_8, mu_7, frame);
    metal::float4 _e5 = lut_bilinear(transmittance_lut_in, _e3, TRANSMITTANCE_SIZE);
    return _e5.xyz;
}

metal::float3 sun_transmittance(
    float r_9,
    float mu_s,
    constant Frame& frame,
    metal::texture2d<float, metal::access::sample> transmittance_lut_in
) {
    bool _e2 = meets_ground(r_9, mu_s, frame);
    if (_e2) {
        return metal::float3(0.0);
    }
    metal::float3 _e5 = transmittance_to_top(r_9, mu_s, frame, transmittance_lut_in);
    return _e5;
}

metal::float3 multiscatter(
    float r_10,
    float mu_s_1,
    constant Frame& frame,
    metal::texture2d<float, metal::access::sample> multiscatter_lut_in
) {
    float _e6 = air_bottom(frame);
    float _e8 = air_top(frame);
    float _e9 = air_bottom(frame);
    metal::float2 x_6 = metal::float2((mu_s_1 * 0.5) + 0.5, (r_10 - _e6) / (_e8 - _e9));
    metal::float4 _e15 = lut_bilinear(multiscatter_lut_in, x_6, MULTISCATTER_SIZE);
    return _e15.xyz;
}

float phase_rayleigh(
    float cos_theta
) {
    return 0.059683103 * (1.0 + (cos_theta * cos_theta));
}

float phase_cornette_shanks_air(
    float cos_theta_1,
    float g_1
) {
    float g2_ = g_1 * g_1;
    return ((0.119366206 * (1.0 - g2_)) * (1.0 + (cos_theta_1 * cos_theta_1))) / ((2.0 + g2_) * metal::pow(metal::max((1.0 + g2_) - ((2.0 * g_1) * cos_theta_1), 0.000001), 1.5));
}

metal::float3 fibonacci_direction(
    uint k_5,
    uint n_1
) {
    float z_2 = 1.0 - (((2.0 * static_cast<float>(k_5)) + 1.0) / static_cast<float>(n_1));
    float s_4 = metal::sqrt(metal::max(1.0 - (z_2 * z_2), 0.0));
    float phi = 2.3999634 * static_cast<float>(k_5);
    return metal::float3(s_4 * metal::cos(phi), z_2, s_4 * metal::sin(phi));
}

metal::float3 ground_radiance_sun(
    float mu_s_2,
    constant Frame& frame,
    metal::texture2d<float, metal::access::sample> transmittance_lut_in
) {
    float _e4 = frame.air_misc.z;
    float _e10 = air_bottom(frame);
    metal::float3 _e13 = sun_transmittance(_e10 + 0.001, mu_s_2, frame, transmittance_lut_in);
    return ((_e4 / PI) * metal::max(mu_s_2, 0.0)) * _e13;
}

Scattered integrate_air(
    metal::float3 origin,
    metal::float3 d_7,
    float distance_km,
    uint steps,
    metal::float3 sun,
    constant Frame& frame,
    metal::texture2d<float, metal::access::sample> transmittance_lut_in,
    metal::texture2d<float, metal::access::sample> multiscatter_lut_in
) {
    metal::float3 radiance_1 = metal::float3(0.0);
    metal::float3 tau_3 = metal::float3(0.0);
    float t0_ = 0.0;
    uint i_8 = 0u;
    float cos_theta_8 = metal::dot(d_7, sun);
    float _e6 = phase_rayleigh(cos_theta_8);
    float _e10 = frame.air_mie.w;
    float _e11 = phase_cornette_shanks_air(cos_theta_8, _e10);
    uint2 loop_bound_2 = uint2(4294967295u);
    bool loop_init_2 = true;
    while(true) {
        if (metal::all(loop_bound_2 == uint2(0u))) { break; }
        loop_bound_2 -= uint2(loop_bound_2.y == 0u, 1u);
        if (!loop_init_2) {
            uint _e79 = i_8;
            i_8 = _e79 + 1u;
        }
        loop_init_2 = false;
        uint _e22 = i_8;
        if (_e22 < steps) {
        } else {
            break;
        }
        {
            uint _e24 = i_8;
            float s1_ = static_cast<float>(_e24 + 1u) / static_cast<float>(steps);
            float t1_ = (distance_km * s1_) * s1_;
            float _e32 = t0_;
            float dt_1 = t1_ - _e32;
            float _e34 = t0_;
            metal::float3 p_16 = origin + (d_7 * (0.5 * (_e34 + t1_)));
            float r_15 = metal::length(p_16);
            metal::float3 up = p_16 / metal::float3(r_15);
            float mu_s_5 = metal::dot(up, sun);
            float _e44 = air_bottom(frame);
            AirSample _e46 = air_at(r_15 - _e44, frame);
            metal::float3 _e47 = tau_3;
            metal::float3 t_view = metal::exp(-((_e47 + ((0.5 * _e46.extinction) * dt_1))));
            metal::float3 _e55 = sun_transmittance(r_15, mu_s_5, frame, transmittance_lut_in);
            metal::float3 _e56 = multiscatter(r_15, mu_s_5, frame, multiscatter_lut_in);
            metal::float3 inscatter = (_e55 * ((_e46.rayleigh * _e6) + metal::float3(_e46.mie * _e11))) + (_e56 * (_e46.rayleigh + metal::float3(_e46.mie)));
            metal::float3 _e70 = radiance_1;
            radiance_1 = _e70 + ((t_view * inscatter) * dt_1);
            metal::float3 _e74 = tau_3;
            tau_3 = _e74 + (_e46.extinction * dt_1);
            t0_ = t1_;
        }
    }
    metal::float3 _e81 = radiance_1;
    metal::float3 _e82 = tau_3;
    return Scattered {_e81, metal::exp(-(_e82))};
}

metal::float3 sky_irradiance(
    float mu_s_3,
    metal::texture2d<float, metal::access::sample> ground_irradiance_in
) {
    metal::float2 x_7 = metal::float2((mu_s_3 * 0.5) + 0.5, 0.0);
    metal::float4 _e11 = lut_bilinear(ground_irradiance_in, x_7, metal::uint2(64u, 1u));
    return _e11.xyz;
}

metal::float3 ground_radiance(
    float mu_s_4,
    constant Frame& frame,
    metal::texture2d<float, metal::access::sample> transmittance_lut_in,
    metal::texture2d<float, metal::access::sample> ground_irradiance_in
) {
    metal::float3 _e1 = ground_radiance_sun(mu_s_4, frame, transmittance_lut_in);
    float _e5 = frame.air_misc.z;
    metal::float3 _e8 = sky_irradiance(mu_s_4, ground_irradiance_in);
    return _e1 + ((_e5 / PI) * _e8);
}

metal::float3 with_ground(
    Scattered s,
    metal::float3 origin_1,
    metal::float3 d_8,
    float distance_km_1,
    metal::float3 sun_1,
    bool ground,
    constant Frame& frame,
    metal::texture2d<float, metal::access::sample> transmittance_lut_in,
    metal::texture2d<float, metal::access::sample> ground_irradiance_in
) {
    if (!(ground)) {
        return s.radiance;
    }
    metal::float3 end_1 = origin_1 + (d_8 * distance_km_1);
    metal::float3 _e14 = ground_radiance(metal::dot(metal::normalize(end_1), sun_1), frame, transmittance_lut_in, ground_irradiance_in);
    return s.radiance + (s.transmittance * _e14);
}

metal::float2 air_ray_end(
    metal::float3 origin_2,
    metal::float3 d_9,
    constant Frame& frame
) {
    float r_16 = metal::length(origin_2);
    float mu_9 = metal::dot(origin_2, d_9) / r_16;
    bool _e5 = meets_ground(r_16, mu_9, frame);
    if (_e5) {
        float _e6 = distance_to_ground(r_16, mu_9, frame);
        return metal::float2(_e6, 1.0);
    }
    float _e9 = air_top(frame);
    if (r_16 > _e9) {
        return metal::float2(0.0, 0.0);
    }
    float _e14 = distance_to_top(r_16, mu_9, frame);
    return metal::float2(_e14, 0.0);
}

metal::float3 camera_air_origin(
    constant Frame& frame
) {
    float _e0 = air_bottom(frame);
    float _e4 = frame.camera_position.y;
    return metal::float3(0.0, _e0 + (metal::max(_e4, 0.0) * 0.001), 0.0);
}

float sky_view_elevation(
    float v_1,
    float horizon
) {
    if (v_1 >= 0.5) {
        float a_5 = (2.0 * v_1) - 1.0;
        return horizon + (((1.5707964 - horizon) * a_5) * a_5);
    }
    float a_6 = 1.0 - (2.0 * v_1);
    return horizon - (((horizon + 1.5707964) * a_6) * a_6);
}

float sky_view_v(
    float elevation,
    float horizon_1
) {
    if (elevation >= horizon_1) {
        float _e7 = saturate((elevation - horizon_1) / (1.5707964 - horizon_1));
        return 0.5 + (0.5 * metal::sqrt(_e7));
    }
    float _e17 = saturate((horizon_1 - elevation) / (horizon_1 + 1.5707964));
    return 0.5 - (0.5 * metal::sqrt(_e17));
}

float horizon_elevation(
    float r_11,
    constant Frame& frame
) {
    float _e1 = air_bottom(frame);
    return -(metal::acos(metal::clamp(_e1 / r_11, -1.0, 1.0)));
}

float sun_azimuth(
    constant Frame& frame
) {
    metal::float4 _e2 = frame.sun_direction;
    metal::float3 s_5 = _e2.xyz;
    return metal::atan2(s_5.z, s_5.x);
}

metal::float3 sky_along(
    metal::float3 origin_3,
    metal::float3 d_10,
    constant Frame& frame,
    metal::texture2d<float, metal::access::sample> transmittance_lut_in,
    metal::texture2d<float, metal::access::sample> multiscatter_lut_in,
    metal::texture2d<float, metal::access::sample> ground_irradiance_in
) {
    metal::float2 _e2 = air_ray_end(origin_3, d_10, frame);
    metal::float4 _e5 = frame.sun_direction;
    metal::float3 sun_2 = _e5.xyz;
    Scattered _e9 = integrate_air(origin_3, d_10, _e2.x, SKY_VIEW_STEPS, sun_2, frame, transmittance_lut_in, multiscatter_lut_in);
    metal::float3 _e14 = with_ground(_e9, origin_3, d_10, _e2.x, sun_2, _e2.y > 0.5, frame, transmittance_lut_in, ground_irradiance_in);
    return _e14;
}

metal::float3 sky_from(
    metal::float3 rel,
    metal::float3 d_11,
    constant Frame& frame,
    metal::texture2d<float, metal::access::sample> transmittance_lut_in,
    metal::texture2d<float, metal::access::sample> multiscatter_lut_in,
    metal::texture2d<float, metal::access::sample> ground_irradiance_in
) {
    float _e7 = frame.atmosphere.x;
    metal::float3 _e13 = sky_along(metal::float3(rel.x, rel.y + _e7, rel.z) * 0.001, d_11, frame, transmittance_lut_in, multiscatter_lut_in, ground_irradiance_in);
    return _e13;
}

metal::float3 sky_view(
    metal::float3 d_12,
    constant Frame& frame,
    metal::texture2d<float, metal::access::sample> sky_view_in
) {
    float delta = {};
    metal::float3 _e1 = camera_air_origin(frame);
    float elevation_1 = metal::asin(metal::clamp(d_12.y, -1.0, 1.0));
    float _e10 = sun_azimuth(frame);
    delta = metal::atan2(d_12.z, d_12.x) - _e10;
    float _e13 = delta;
    float _e15 = delta;
    delta = metal::abs(_e13 - (6.2831855 * metal::rint(_e15 / 6.2831855)));
    float _e22 = delta;
    float _e26 = horizon_elevation(_e1.y, frame);
    float _e27 = sky_view_v(elevation_1, _e26);
    metal::float2 x_8 = metal::float2(_e22 / PI, _e27);
    metal::float4 _e31 = lut_bilinear(sky_view_in, x_8, SKY_VIEW_SIZE);
    return _e31.xyz;
}

metal::float3 aerial_ray(
    metal::uint2 c_1,
    constant Frame& frame
) {
    metal::float2 ndc_1 = (((static_cast<metal::float2>(c_1) + metal::float2(0.5)) / metal::float2(32.0)) * 2.0) - metal::float2(1.0);
    float tan_half_1 = frame.camera_position.w;
    float aspect_1 = frame.camera_forward.w;
    metal::float4 _e23 = frame.camera_forward;
    metal::float4 _e27 = frame.camera_right;
    metal::float4 _e36 = frame.camera_up;
    return metal::normalize((_e23.xyz + (_e27.xyz * ((ndc_1.x * tan_half_1) * aspect_1))) - (_e36.xyz * (ndc_1.y * tan_half_1)));
}

metal::float4 aerial_texel(
    metal::uint2 c0_,
    metal::uint2 c1_,
    metal::float2 w_2,
    uint z_1,
    metal::texture2d<float, metal::access::sample> aerial_in
) {
    uint o_1 = z_1 * AERIAL_SIDE;
    metal::float4 _e12 = aerial_in.read(metal::uint2(metal::uint2(o_1 + c0_.x, c0_.y)), 0);
    metal::float4 _e19 = aerial_in.read(metal::uint2(metal::uint2(o_1 + c1_.x, c0_.y)), 0);
    metal::float4 a_7 = metal::mix(_e12, _e19, w_2.x);
    metal::float4 _e28 = aerial_in.read(metal::uint2(metal::uint2(o_1 + c0_.x, c1_.y)), 0);
    metal::float4 _e35 = aerial_in.read(metal::uint2(metal::uint2(o_1 + c1_.x, c1_.y)), 0);
    metal::float4 b_7 = metal::mix(_e28, _e35, w_2.x);
    return metal::mix(a_7, b_7, w_2.y);
}

uint naga_f2u32(float value) {
    return static_cast<uint>(metal::clamp(value, 0.0, 4294967000.0));
}

metal::float4 aerial(
    metal::uint2 pixel_2,
    float depth_m,
    constant Frame& frame,
    metal::texture2d<float, metal::access::sample> aerial_in
) {
    metal::float4 near = metal::float4(0.0, 0.0, 0.0, 1.0);
    metal::float4 far = metal::float4(0.0, 0.0, 0.0, 1.0);
    metal::uint4 _e8 = frame.counts;
    metal::float2 uv_2 = (static_cast<metal::float2>(pixel_2) + metal::float2(0.5)) / static_cast<metal::float2>(_e8.xy);
    metal::float2 f_2 = metal::clamp((uv_2 * 32.0) - metal::float2(0.5), metal::float2(0.0), metal::float2(31.0));
    metal::uint2 c0_1 = metal::min(naga_f2u32(metal::floor(f_2)), metal::uint2(31u));
    metal::uint2 c1_1 = metal::min(c0_1 + metal::uint2(1u), metal::uint2(31u));
    metal::float2 w_4 = f_2 - static_cast<metal::float2>(c0_1);
    float s_6 = metal::clamp((depth_m * 0.001) / AERIAL_SLICE_KM, 0.0, 32.0);
    uint z1_ = metal::min(naga_f2u32(metal::ceil(s_6)), AERIAL_SLICES);
    uint z0_ = (z1_ > 0u) ? (z1_ - 1u) : 0u;
    float ws = s_6 - static_cast<float>(z0_);
    if (z0_ > 0u) {
        metal::float4 _e64 = aerial_texel(c0_1, c1_1, w_4, z0_ - 1u, aerial_in);
        near = _e64;
    }
    if (z1_ > 0u) {
        metal::float4 _e75 = aerial_texel(c0_1, c1_1, w_4, z1_ - 1u, aerial_in);
        far = _e75;
    }
    metal::float4 _e76 = near;
    metal::float4 _e77 = far;
    return metal::mix(_e76, _e77, ws);
}

metal::float3 sun_through_air(
    metal::float3 rel_1,
    constant Frame& frame,
    metal::texture2d<float, metal::access::sample> transmittance_lut_in
) {
    bool _e1 = physical_sky(frame);
    if (!(_e1)) {
        return metal::float3(1.0);
    }
    float _e10 = frame.atmosphere.x;
    metal::float3 q_6 = metal::float3(rel_1.x, rel_1.y + _e10, rel_1.z) * 0.001;
    float r_17 = metal::length(q_6);
    metal::float4 _e21 = frame.sun_direction;
    metal::float3 _e24 = sun_transmittance(r_17, metal::dot(q_6 / metal::float3(r_17), _e21.xyz), frame, transmittance_lut_in);
    return _e24;
}

float sky_ambient_x(
    float mu_8
) {
    return 0.5 + ((0.5 * metal::sign(mu_8)) * metal::sqrt(metal::abs(mu_8)));
}

metal::float3 sky_ambient_light(
    float h,
    metal::float3 rel_2,
    constant Frame& frame,
    metal::texture2d<float, metal::access::sample> sky_ambient_in
) {
    float _e7 = frame.atmosphere.x;
    metal::float3 q_7 = metal::float3(rel_2.x, rel_2.y + _e7, rel_2.z);
    metal::float4 _e14 = frame.sun_direction;
    float _e17 = sky_ambient_x(metal::dot(metal::normalize(q_7), _e14.xyz));
    metal::uint2 size_2 = metal::uint2(64u, 2u);
    metal::float4 _e24 = lut_bilinear(sky_ambient_in, metal::float2(_e17, 0.0), size_2);
    metal::float3 bottom_1 = _e24.xyz;
    metal::float4 _e29 = lut_bilinear(sky_ambient_in, metal::float2(_e17, 1.0), size_2);
    metal::float3 top_1 = _e29.xyz;
    metal::float4 _e34 = frame.sun_illuminance;
    float _e40 = frame.ambient_bottom.w;
    return (metal::mix(bottom_1, top_1, h) * _e34.xyz) * _e40;
}

float layer_height(
    Layer l_1,
    float alt_7
) {
    return (alt_7 - l_1.bottom) / (l_1.top - l_1.bottom);
}

uint layer_at(
    float alt_8,
    constant Frame& frame
) {
    uint i_9 = 0u;
    bool local_22 = {};
    uint2 loop_bound_3 = uint2(4294967295u);
    bool loop_init_3 = true;
    while(true) {
        if (metal::all(loop_bound_3 == uint2(0u))) { break; }
        loop_bound_3 -= uint2(loop_bound_3.y == 0u, 1u);
        if (!loop_init_3) {
            uint _e19 = i_9;
            i_9 = _e19 + 1u;
        }
        loop_init_3 = false;
        uint _e3 = i_9;
        uint _e4 = layer_count(frame);
        if (_e3 < _e4) {
        } else {
            break;
        }
        {
            uint _e6 = i_9;
            Layer _e7 = cloud_layer(_e6, frame);
            float _e8 = layer_height(_e7, alt_8);
            if (_e8 >= 0.0) {
                local_22 = _e8 <= 1.0;
            } else {
                local_22 = false;
            }
            bool _e16 = local_22;
            if (_e16) {
                uint _e17 = i_9;
                return _e17;
            }
        }
    }
    return NO_LAYER;
}

Weather sample_weather(
    metal::float3 p_3,
    Layer l_2,
    constant Frame& frame,
    metal::texture2d<float, metal::access::sample> weather_tex,
    metal::sampler noise_sampler
) {
    float _e8 = frame.periods.x;
    metal::float2 uv_3 = (p_3.xz - l_2.weather_offset) / metal::float2(_e8);
    metal::float4 w_5 = weather_tex.sample(noise_sampler, uv_3, metal::level(0.0));
    float _e22 = saturate(w_5.x + (2.0 * (l_2.coverage - 0.5)));
    float _e30 = saturate(l_2.cloud_type + ((w_5.z - 0.5) * 0.5));
    float _e35 = saturate(0.5 + w_5.y);
    float precipitation = l_2.precipitation * _e35;
    return Weather {_e22, _e30, precipitation};
}

float height_parabola(
    float h_1,
    float cloud_type
) {
    float height = metal::mix(0.35, 1.0, cloud_type);
    float _e11 = saturate((h_1 * (h_1 - height)) * (-4.0 / (height * height)));
    return _e11;
}

float gradient(
    float h_2,
    float r0_,
    float r1_,
    float f0_,
    float f1_
) {
    return metal::smoothstep(r0_, r1_, h_2) * (1.0 - metal::smoothstep(f0_, f1_, h_2));
}

float height_cloud_types(
    float h_3,
    float cloud_type_1
) {
    float _e6 = gradient(h_3, 0.0, 0.08, 0.15, 0.25);
    float _e11 = gradient(h_3, 0.0, 0.2, 0.4, 0.65);
    float _e16 = gradient(h_3, 0.0, 0.1, 0.6, 0.95);
    float _e19 = saturate(cloud_type_1 * 2.0);
    float lo = metal::mix(_e6, _e11, _e19);
    float _e25 = saturate((cloud_type_1 * 2.0) - 1.0);
    return metal::mix(lo, _e16, _e25);
}

float height_signal(
    float h_4,
    float cloud_type_2,
    constant Frame& frame
) {
    uint _e5 = frame.modes.z;
    if (_e5 == HEIGHT_CLOUD_TYPES) {
        float _e8 = height_cloud_types(h_4, cloud_type_2);
        return _e8;
    }
    float _e9 = height_parabola(h_4, cloud_type_2);
    return _e9;
}

float layer_density_with(
    metal::float3 p_4,
    float alt_9,
    Layer l_3,
    bool with_detail,
    thread Counters& counters_3,
    constant Frame& frame,
    metal::texture3d<float, metal::access::sample> shape_tex,
    metal::texture3d<float, metal::access::sample> detail_tex,
    metal::texture2d<float, metal::access::sample> weather_tex,
    metal::texture2d<float, metal::access::sample> curl_tex,
    metal::sampler noise_sampler
) {
    bool local_23 = {};
    bool local_24 = {};
    float base = {};
    float density = {};
    bool local_25 = {};
    bool local_26 = {};
    bool local_27 = {};
    metal::float3 detail_pos = {};
    float _e5 = layer_height(l_3, alt_9);
    if (!((_e5 < 0.0))) {
        local_23 = _e5 > 1.0;
    } else {
        local_23 = true;
    }
    bool _e14 = local_23;
    if (_e14) {
        return 0.0;
    }
    uint _e17 = counters_3.density;
    counters_3.density = _e17 + 1u;
    Weather _e20 = sample_weather(p_4, l_3, frame, weather_tex, noise_sampler);
    float _e22 = height_signal(_e5, _e20.cloud_type, frame);
    if (!((_e20.coverage <= 0.0))) {
        local_24 = _e22 <= 0.0;
    } else {
        local_24 = true;
    }
    bool _e32 = local_24;
    if (_e32) {
        return 0.0;
    }
    metal::float3 dims = static_cast<metal::float3>(metal::uint3(shape_tex.get_width(), shape_tex.get_height(), shape_tex.get_depth()));
    float _e40 = frame.periods.y;
    metal::float3 period = _e40 * metal::float3(1.0, dims.y / dims.x, 1.0);
    float _e52 = frame.wind_offsets0_.z;
    float _e58 = frame.wind_offsets0_.w;
    metal::float3 shape_pos = metal::float3(p_4.x - _e52, alt_9, p_4.z - _e58);
    metal::float4 s_7 = shape_tex.sample(noise_sampler, shape_pos / period, metal::level(0.0));
    float low_fbm = ((s_7.y * 0.625) + (s_7.z * 0.25)) + (s_7.w * 0.125);
    float _e83 = remap(s_7.x, low_fbm - 1.0, 1.0, 0.0, 1.0);
    float _e84 = saturate(_e83);
    base = _e84 * _e22;
    float _e87 = base;
    float _e94 = remap(_e87, 1.0 - _e20.coverage, 1.0, 0.0, 1.0);
    float _e95 = saturate(_e94);
    base = _e95 * _e20.coverage;
    float _e98 = base;
    if (_e98 <= 0.0) {
        return 0.0;
    }
    float _e102 = base;
    density = _e102;
    float strength = frame.erosion.x;
    float threshold = frame.erosion.y;
    if (DETAIL) {
        local_25 = with_detail;
    } else {
        local_25 = false;
    }
    bool _e116 = local_25;
    if (_e116) {
        local_26 = strength > 0.0;
    } else {
        local_26 = false;
    }
    bool _e122 = local_26;
    if (_e122) {
        float _e125 = base;
        local_27 = _e125 < threshold;
    } else {
        local_27 = false;
    }
    bool _e128 = local_27;
    if (_e128) {
        uint _e130 = counters_3.detail;
        counters_3.detail = _e130 + 1u;
        detail_pos = metal::float3(p_4.x, alt_9, p_4.z);
        if (CURL) {
            metal::float4 _e141 = frame.wind_offsets1_;
            float _e147 = frame.periods.w;
            metal::float2 cuv = (p_4.xz - _e141.zw) / metal::float2(_e147);
            metal::float4 _e153 = curl_tex.sample(noise_sampler, cuv, metal::level(0.0));
            metal::float2 curl = (_e153.xy * 2.0) - metal::float2(1.0);
            metal::float3 _e160 = detail_pos;
            float _e168 = frame.erosion.z;
            detail_pos = _e160 + (metal::float3(curl.x, 0.0, curl.y) * (_e168 * (1.0 - _e5)));
        }
        metal::float3 _e174 = detail_pos;
        float _e178 = frame.wind_offsets1_.x;
        float _e182 = frame.wind_offsets1_.y;
        detail_pos = _e174 - metal::float3(_e178, 0.0, _e182);
        metal::float3 _e188 = detail_pos;
        float _e192 = frame.periods.z;
        metal::float4 dn = detail_tex.sample(noise_sampler, _e188 / metal::float3(_e192), metal::level(0.0));
        float high_fbm = ((dn.x * 0.625) + (dn.y * 0.25)) + (dn.z * 0.125);
        float _e211 = frame.extinction.w;
        float _e216 = saturate(_e5 * 10.0);
        float _e218 = saturate((2.0 * _e211) * _e216);
        float shape = metal::mix(1.0 - high_fbm, high_fbm, _e218);
        float _e223 = base;
        float erosion = (strength * shape) * (1.0 - (_e223 / threshold));
        float _e228 = base;
        float _e232 = remap(_e228, erosion, 1.0, 0.0, 1.0);
        float _e233 = saturate(_e232);
        density = _e233;
    }
    float _e234 = density;
    float _e238 = frame.erosion.w;
    density = _e234 * metal::mix(1.0, _e5, _e238);
    float _e242 = density;
    density = (_e242 * l_3.density) * (1.0 + _e20.precipitation);
    float _e249 = density;
    return metal::clamp(_e249, 0.0, 1.0);
}

float layer_density(
    metal::float3 p_5,
    float alt_10,
    Layer l_4,
    thread Counters& counters_4,
    constant Frame& frame,
    metal::texture3d<float, metal::access::sample> shape_tex,
    metal::texture3d<float, metal::access::sample> detail_tex,
    metal::texture2d<float, metal::access::sample> weather_tex,
    metal::texture2d<float, metal::access::sample> curl_tex,
    metal::sampler noise_sampler
) {
    float _e5 = layer_density_with(p_5, alt_10, l_4, true, counters_4, frame, shape_tex, detail_tex, weather_tex, curl_tex, noise_sampler);
    return _e5;
}

float cloud_density(
    metal::float3 p_6,
    float alt_11,
    thread Counters& counters_5,
    constant Frame& frame,
    metal::texture3d<float, metal::access::sample> shape_tex,
    metal::texture3d<float, metal::access::sample> detail_tex,
    metal::texture2d<float, metal::access::sample> weather_tex,
    metal::texture2d<float, metal::access::sample> curl_tex,
    metal::sampler noise_sampler
) {
    uint _e3 = layer_at(alt_11, frame);
    if (_e3 == NO_LAYER) {
        return 0.0;
    }
    Layer _e7 = cloud_layer(_e3, frame);
    float _e8 = layer_density(p_6, alt_11, _e7, counters_5, frame, shape_tex, detail_tex, weather_tex, curl_tex, noise_sampler);
    return _e8;
}

float phase_hg(
    float cos_theta_2,
    float g_2
) {
    float g2_1 = g_2 * g_2;
    float denom = metal::max((1.0 + g2_1) - ((2.0 * g_2) * cos_theta_2), 0.000001);
    return (1.0 - g2_1) / ((12.566371 * denom) * metal::sqrt(denom));
}

float phase_cornette_shanks(
    float cos_theta_3,
    float g_3
) {
    float g2_2 = g_3 * g_3;
    float denom_1 = metal::max((1.0 + g2_2) - ((2.0 * g_3) * cos_theta_3), 0.000001);
    return ((3.0 * (1.0 - g2_2)) * (1.0 + (cos_theta_3 * cos_theta_3))) / (((25.132742 * (2.0 + g2_2)) * denom_1) * metal::sqrt(denom_1));
}

float phase(
    float cos_theta_4,
    float scale,
    constant Frame& frame
) {
    float _e5 = frame.phase.x;
    float g_5 = _e5 * scale;
    uint _e10 = frame.modes.x;
    switch(_e10) {
        case 1u: {
            float _e14 = frame.phase.y;
            float g2_3 = _e14 * scale;
            float _e16 = phase_hg(cos_theta_4, g_5);
            float _e17 = phase_hg(cos_theta_4, g2_3);
            float _e21 = frame.phase.z;
            return metal::mix(_e16, _e17, _e21);
        }
        case 2u: {
            float _e23 = phase_cornette_shanks(cos_theta_4, g_5);
            return _e23;
        }
        default: {
            float _e24 = phase_hg(cos_theta_4, g_5);
            return _e24;
        }
    }
}

float segment_optical_depth(
    metal::float3 rel_3,
    metal::float3 p_7,
    Layer l_5,
    metal::float3 d_13,
    float first,
    float growth,
    uint steps_1,
    bool with_detail_1,
    thread Counters& counters_6,
    constant Frame& frame,
    metal::texture3d<float, metal::access::sample> shape_tex,
    metal::texture3d<float, metal::access::sample> detail_tex,
    metal::texture2d<float, metal::access::sample> weather_tex,
    metal::texture2d<float, metal::access::sample> curl_tex,
    metal::sampler noise_sampler
) {
    float seg = {};
    float dist = 0.0;
    float tau_4 = 0.0;
    uint i_10 = 0u;
    bool local_28 = {};
    float _e12 = frame.extinction.x;
    float _e16 = frame.extinction.y;
    float sigma_t_1 = _e12 + _e16;
    seg = first;
    uint2 loop_bound_4 = uint2(4294967295u);
    bool loop_init_4 = true;
    while(true) {
        if (metal::all(loop_bound_4 == uint2(0u))) { break; }
        loop_bound_4 -= uint2(loop_bound_4.y == 0u, 1u);
        if (!loop_init_4) {
            uint _e62 = i_10;
            i_10 = _e62 + 1u;
        }
        loop_init_4 = false;
        uint _e25 = i_10;
        if (_e25 < steps_1) {
        } else {
            break;
        }
        {
            float _e27 = dist;
            float _e28 = seg;
            float s_8 = _e27 + (0.5 * _e28);
            float _e34 = altitude_of(rel_3 + (d_13 * s_8), frame);
            if (!((_e34 > l_5.top))) {
                local_28 = _e34 < l_5.bottom;
            } else {
                local_28 = true;
            }
            bool _e43 = local_28;
            if (_e43) {
                break;
            }
            uint _e45 = counters_6.light;
            counters_6.light = _e45 + 1u;
            float _e48 = tau_4;
            float _e51 = layer_density_with(p_7 + (d_13 * s_8), _e34, l_5, with_detail_1, counters_6, frame, shape_tex, detail_tex, weather_tex, curl_tex, noise_sampler);
            float _e53 = seg;
            tau_4 = _e48 + ((_e51 * sigma_t_1) * _e53);
            float _e56 = dist;
            float _e57 = seg;
            dist = _e56 + _e57;
            float _e59 = seg;
            seg = _e59 * growth;
        }
    }
    float _e64 = tau_4;
    return _e64;
}

float sun_optical_depth(
    metal::float3 rel_4,
    metal::float3 p_8,
    Layer l_6,
    thread Counters& counters_7,
    constant Frame& frame,
    metal::texture3d<float, metal::access::sample> shape_tex,
    metal::texture3d<float, metal::access::sample> detail_tex,
    metal::texture2d<float, metal::access::sample> weather_tex,
    metal::texture2d<float, metal::access::sample> curl_tex,
    metal::sampler noise_sampler
) {
    float tau_5 = {};
    uint j_1 = 0u;
    bool local_29 = {};
    bool local_30 = {};
    bool local_31 = {};
    metal::float4 _e6 = frame.sun_direction;
    metal::float3 sun_3 = _e6.xyz;
    float _e11 = frame.extinction.x;
    float _e15 = frame.extinction.y;
    float sigma_t_2 = _e11 + _e15;
    float _e20 = frame.march.z;
    float _e24 = frame.march.y;
    uint _e28 = frame.counts.w;
    float _e30 = segment_optical_depth(rel_4, p_8, l_6, sun_3, _e20, _e24, _e28, true, counters_7, frame, shape_tex, detail_tex, weather_tex, curl_tex, noise_sampler);
    tau_5 = _e30;
    float _e32 = altitude_of(rel_4, frame);
    uint2 loop_bound_5 = uint2(4294967295u);
    bool loop_init_5 = true;
    while(true) {
        if (metal::all(loop_bound_5 == uint2(0u))) { break; }
        loop_bound_5 -= uint2(loop_bound_5.y == 0u, 1u);
        if (!loop_init_5) {
            uint _e96 = j_1;
            j_1 = _e96 + 1u;
        }
        loop_init_5 = false;
        uint _e35 = j_1;
        uint _e36 = layer_count(frame);
        if (_e35 < _e36) {
        } else {
            break;
        }
        {
            uint _e38 = j_1;
            Layer _e39 = cloud_layer(_e38, frame);
            if (_e39.bottom <= l_6.top) {
                continue;
            }
            Roots _e44 = ray_shell_from(rel_4, _e32, sun_3, _e39.bottom, frame);
            Roots _e46 = ray_shell_from(rel_4, _e32, sun_3, _e39.top, frame);
            if (!(!(_e44.hit))) {
                local_29 = !(_e46.hit);
            } else {
                local_29 = true;
            }
            bool _e55 = local_29;
            if (!(_e55)) {
                local_30 = !((_e46.t1_ > _e44.t1_));
            } else {
                local_30 = true;
            }
            bool _e64 = local_30;
            if (!(_e64)) {
                local_31 = _e44.t1_ <= 0.0;
            } else {
                local_31 = true;
            }
            bool _e72 = local_31;
            if (_e72) {
                continue;
            }
            float s_9 = 0.5 * (_e44.t1_ + _e46.t1_);
            uint _e79 = counters_7.light;
            counters_7.light = _e79 + 1u;
            float _e82 = tau_5;
            float _e87 = altitude_of(rel_4 + (sun_3 * s_9), frame);
            float _e88 = layer_density(p_8 + (sun_3 * s_9), _e87, _e39, counters_7, frame, shape_tex, detail_tex, weather_tex, curl_tex, noise_sampler);
            tau_5 = _e82 + ((_e88 * sigma_t_2) * (_e46.t1_ - _e44.t1_));
        }
    }
    float _e98 = tau_5;
    return _e98;
}

float octave_optical_depth(
    metal::float3 rel_5,
    metal::float3 p_9,
    Layer l_7,
    float tau_6,
    thread Counters& counters_8,
    constant Frame& frame,
    metal::texture3d<float, metal::access::sample> shape_tex,
    metal::texture3d<float, metal::access::sample> detail_tex,
    metal::texture2d<float, metal::access::sample> weather_tex,
    metal::texture2d<float, metal::access::sample> curl_tex,
    metal::sampler noise_sampler
) {
    bool local_32 = {};
    bool local_33 = {};
    bool local_34 = {};
    float _e10 = saturate((l_7.coverage - 0.8) / 0.1);
    float _e14 = frame.octave_depth.x;
    float m_2 = _e14 * _e10;
    if (!((_e10 < 0.001))) {
        local_32 = m_2 <= 0.0;
    } else {
        local_32 = true;
    }
    bool _e24 = local_32;
    if (!(_e24)) {
        uint _e31 = frame.counts.w;
        local_33 = _e31 == 0u;
    } else {
        local_33 = true;
    }
    bool _e35 = local_33;
    if (_e35) {
        return tau_6;
    }
    float _e41 = frame.atmosphere.x;
    metal::float3 up_1 = metal::normalize(metal::float3(rel_5.x, rel_5.y + _e41, rel_5.z));
    float _e46 = altitude_of(rel_5, frame);
    Roots _e48 = ray_shell_from(rel_5, _e46, up_1, l_7.top, frame);
    if (_e48.hit) {
        local_34 = _e48.t1_ > 0.0;
    } else {
        local_34 = false;
    }
    bool _e57 = local_34;
    float len_1 = _e57 ? _e48.t1_ : 0.0;
    float _e65 = segment_optical_depth(rel_5, p_9, l_7, up_1, len_1 / 3.0, 1.0, COLUMN_STEPS, false, counters_8, frame, shape_tex, detail_tex, weather_tex, curl_tex, noise_sampler);
    float _e69 = frame.octave_depth.y;
    return metal::mix(tau_6, _e69 * _e65, m_2);
}

float far_optical_depth(
    metal::float3 rel_6,
    metal::float3 p_10,
    Layer l_8,
    constant Frame& frame,
    metal::texture2d<float, metal::access::sample> weather_tex,
    metal::sampler noise_sampler
) {
    bool local_35 = {};
    float reach = {};
    bool local_36 = {};
    float tau_7 = 0.0;
    uint i_11 = 0u;
    float chord = frame.light_model.z;
    if (!((chord <= 0.0))) {
        uint _e15 = frame.counts.w;
        local_35 = _e15 == 0u;
    } else {
        local_35 = true;
    }
    bool _e19 = local_35;
    if (_e19) {
        return 0.0;
    }
    float growth_1 = frame.march.y;
    uint _e28 = frame.counts.w;
    float steps_3 = static_cast<float>(_e28);
    float _e33 = frame.march.z;
    reach = _e33 * steps_3;
    if (growth_1 != 1.0) {
        float _e41 = frame.march.z;
        reach = (_e41 * (metal::pow(growth_1, steps_3) - 1.0)) / (growth_1 - 1.0);
    }
    metal::float4 _e51 = frame.sun_direction;
    metal::float3 sun_4 = _e51.xyz;
    float _e53 = altitude_of(rel_6, frame);
    Roots _e55 = ray_shell_from(rel_6, _e53, sun_4, l_8.top, frame);
    float _e57 = reach;
    float len_2 = _e55.t1_ - _e57;
    if (!(!(_e55.hit))) {
        local_36 = !((len_2 > 0.0));
    } else {
        local_36 = true;
    }
    bool _e68 = local_36;
    if (_e68) {
        return 0.0;
    }
    uint2 loop_bound_6 = uint2(4294967295u);
    bool loop_init_6 = true;
    while(true) {
        if (metal::all(loop_bound_6 == uint2(0u))) { break; }
        loop_bound_6 -= uint2(loop_bound_6.y == 0u, 1u);
        if (!loop_init_6) {
            uint _e110 = i_11;
            i_11 = _e110 + 1u;
        }
        loop_init_6 = false;
        uint _e74 = i_11;
        if (_e74 < 4u) {
        } else {
            break;
        }
        {
            float _e77 = reach;
            uint _e78 = i_11;
            float t_5 = _e77 + (((static_cast<float>(_e78) + 0.5) * 0.25) * len_2);
            float _e88 = altitude_of(rel_6 + (sun_4 * t_5), frame);
            float _e89 = layer_height(l_8, _e88);
            float _e90 = saturate(_e89);
            Weather _e93 = sample_weather(p_10 + (sun_4 * t_5), l_8, frame, weather_tex, noise_sampler);
            float cov = _e93.coverage;
            float _e96 = height_signal(_e90, l_8.cloud_type, frame);
            float f_3 = metal::min(cov * _e96, 0.95);
            float _e100 = tau_7;
            tau_7 = _e100 + (((0.25 * len_2) * f_3) / ((1.0 - f_3) * chord));
        }
    }
    float _e112 = tau_7;
    return _e112;
}

float diffuse_limb(
    float view_y,
    float coverage,
    constant Frame& frame
) {
    float k_12 = frame.light_model.w;
    float layer = (1.0 + (k_12 * metal::abs(view_y))) / (1.0 + ((2.0 * k_12) / 3.0));
    float _e17 = saturate(coverage);
    return metal::mix(1.0, layer, _e17);
}

float vertical_anisotropy(
    float view_y_1,
    float coverage_1,
    float h_5,
    constant Frame& frame
) {
    float _e6 = frame.octave_direction.z;
    float _e8 = saturate(coverage_1);
    float _e10 = saturate(h_5);
    return 1.0 + (((_e6 * view_y_1) * _e8) * (1.0 - _e10));
}

float deck_escape(
    float mu0_,
    float layer_coverage,
    constant Frame& frame
) {
    float e = frame.octave_direction.w;
    float _e6 = saturate(layer_coverage);
    return 1.0 + ((e * metal::pow(_e6, DECK_POWER)) * (mu0_ - 0.5));
}

float downward_dimming(
    float view_y_2,
    float coverage_2,
    float h_6,
    float tau_v,
    constant Frame& frame
) {
    float _e7 = frame.octave_depth.z;
    float _e12 = saturate(coverage_2);
    float _e14 = saturate(h_6);
    float k_13 = ((_e7 * metal::max(-(view_y_2), 0.0)) * _e12) * (1.0 - _e14);
    return metal::max(1.0 - ((k_13 * tau_v) / (tau_v + 1.0)), 0.0);
}

SunScattering sun_scattering(
    float cos_theta_5,
    float view_y_3,
    float tau_8,
    float tau_oct,
    float far_1,
    float build,
    float coverage_3,
    float h_7,
    float layer_coverage_1,
    constant Frame& frame
) {
    float octave_sum = 0.0;
    float ka = 1.0;
    float kb = 1.0;
    float kc = 1.0;
    uint i_12 = 0u;
    float feed = {};
    float octaves_part = {};
    float total = {};
    float a_8 = frame.multiple_scattering.x;
    float b_8 = frame.multiple_scattering.y;
    float c_8 = frame.multiple_scattering.z;
    uint _e24 = frame.misc.x;
    uint octaves = metal::min(_e24, MAX_OCTAVES);
    uint2 loop_bound_7 = uint2(4294967295u);
    bool loop_init_7 = true;
    while(true) {
        if (metal::all(loop_bound_7 == uint2(0u))) { break; }
        loop_bound_7 -= uint2(loop_bound_7.y == 0u, 1u);
        if (!loop_init_7) {
            uint _e57 = i_12;
            i_12 = _e57 + 1u;
        }
        loop_init_7 = false;
        uint _e37 = i_12;
        if (_e37 < octaves) {
        } else {
            break;
        }
        {
            float _e39 = ka;
            ka = _e39 * a_8;
            float _e41 = kb;
            kb = _e41 * b_8;
            float _e43 = kc;
            kc = _e43 * c_8;
            float _e45 = octave_sum;
            float _e46 = ka;
            float _e47 = kc;
            float _e48 = phase(cos_theta_5, _e47, frame);
            float _e50 = kb;
            octave_sum = _e45 + ((_e46 * _e48) / (1.0 + (_e50 * tau_oct)));
        }
    }
    float _e62 = frame.sun_direction.y;
    float _e63 = saturate(_e62);
    float _e70 = saturate(coverage_3);
    float side = (metal::sqrt(metal::max(1.0 - (_e63 * _e63), 0.0)) * (1.0 - _e70)) * metal::exp(-(far_1));
    float _e80 = frame.light_model.x;
    feed = _e63 + (_e80 * side);
    float _e87 = frame.light_model.y;
    if (_e87 > 0.0) {
        float _e90 = feed;
        float _e96 = frame.light_model.y;
        feed = _e90 * metal::pow(metal::max(coverage_3, 0.000001), _e96);
    }
    float _e99 = feed;
    float _e100 = diffuse_limb(view_y_3, coverage_3, frame);
    float _e101 = vertical_anisotropy(view_y_3, coverage_3, h_7, frame);
    float _e103 = deck_escape(_e63, layer_coverage_1, frame);
    feed = _e99 * ((_e100 * _e101) * _e103);
    float _e106 = feed;
    float _e108 = downward_dimming(view_y_3, coverage_3, h_7, tau_8 * _e63, frame);
    feed = _e106 * _e108;
    float _e110 = feed;
    float _e112 = octave_sum;
    octaves_part = (_e110 * build) * _e112;
    float _e116 = phase(cos_theta_5, 1.0, frame);
    float _e121 = octaves_part;
    total = (_e116 * metal::exp(-(tau_8) - far_1)) + _e121;
    uint _e127 = frame.modes.w;
    if ((_e127 & FLAG_BEER_POWDER) != 0u) {
        float _e135 = frame.phase.w;
        float powder = 1.0 - metal::exp(-(_e135) * tau_8);
        float _e141 = total;
        total = _e141 * powder;
        float _e143 = octaves_part;
        octaves_part = _e143 * powder;
    }
    float _e145 = total;
    float _e146 = octaves_part;
    return SunScattering {_e145, _e146};
}

float forward_lobe(
    float cos_theta_6,
    float transmittance,
    constant Frame& frame
) {
    float k_14 = frame.octave_direction.x;
    if (k_14 <= 0.0) {
        return 1.0;
    }
    float _e11 = saturate(transmittance / FORWARD_LOBE_THIN);
    float w_6 = k_14 * _e11;
    float _e17 = frame.octave_direction.y;
    float _e18 = phase_hg(cos_theta_6, _e17);
    return 1.0 + (w_6 * ((12.566371 * _e18) - 1.0));
}

float octave_buildup(
    float density_1,
    constant Frame& frame
) {
    float l_11 = frame.multiple_scattering.w;
    if (l_11 <= 0.0) {
        return 1.0;
    }
    float _e11 = frame.extinction.x;
    float _e15 = frame.extinction.y;
    return 1.0 - metal::exp((-((_e11 + _e15)) * density_1) * l_11);
}

metal::float3 ambient(
    float h_8,
    metal::float3 rel_7,
    constant Frame& frame,
    metal::texture2d<float, metal::access::sample> sky_ambient_in
) {
    bool _e2 = physical_sky(frame);
    if (_e2) {
        metal::float3 _e3 = sky_ambient_light(h_8, rel_7, frame, sky_ambient_in);
        return _e3;
    }
    metal::float4 _e6 = frame.ambient_bottom;
    metal::float4 _e10 = frame.ambient_top;
    float _e16 = frame.ambient_bottom.w;
    return metal::mix(_e6.xyz, _e10.xyz, h_8) * _e16;
}

float height_fraction(
    float alt_12,
    constant Frame& frame
) {
    uint _e1 = layer_at(alt_12, frame);
    Layer _e2 = cloud_layer(_e1, frame);
    float _e3 = layer_height(_e2, alt_12);
    float _e4 = saturate(_e3);
    return _e4;
}

ScatteredLight scattered_light(
    metal::float3 rel_8,
    metal::float3 p_11,
    float alt_13,
    float density_2,
    metal::float3 view,
    Layer l_9,
    thread Counters& counters_9,
    constant Frame& frame,
    metal::texture2d<float, metal::access::sample> transmittance_lut_in,
    metal::texture2d<float, metal::access::sample> sky_ambient_in,
    metal::texture3d<float, metal::access::sample> shape_tex,
    metal::texture3d<float, metal::access::sample> detail_tex,
    metal::texture2d<float, metal::access::sample> weather_tex,
    metal::texture2d<float, metal::access::sample> curl_tex,
    metal::sampler noise_sampler
) {
    metal::float3 sun_light = metal::float3(0.0);
    metal::float3 octave_light = metal::float3(0.0);
    float tau_9 = 0.0;
    float far_2 = 0.0;
    float tau_oct_1 = {};
    metal::float4 _e9 = frame.sun_direction;
    metal::float3 sun_5 = _e9.xyz;
    float _e11 = layer_height(l_9, alt_13);
    float _e12 = saturate(_e11);
    Weather _e19 = sample_weather(p_11, l_9, frame, weather_tex, noise_sampler);
    bool _e20 = hits_ground(rel_8, alt_13, sun_5, frame);
    if (!(_e20)) {
        if (LIGHT_MARCH) {
            float _e27 = sun_optical_depth(rel_8, p_11, l_9, counters_9, frame, shape_tex, detail_tex, weather_tex, curl_tex, noise_sampler);
            tau_9 = _e27;
            float _e28 = far_optical_depth(rel_8, p_11, l_9, frame, weather_tex, noise_sampler);
            far_2 = _e28;
        }
        float _e29 = tau_9;
        tau_oct_1 = _e29;
        if (LIGHT_MARCH) {
            float _e32 = tau_9;
            float _e33 = octave_optical_depth(rel_8, p_11, l_9, _e32, counters_9, frame, shape_tex, detail_tex, weather_tex, curl_tex, noise_sampler);
            tau_oct_1 = _e33;
        }
        float _e36 = tau_9;
        float _e37 = tau_oct_1;
        float _e38 = far_2;
        float _e39 = octave_buildup(density_2, frame);
        SunScattering _e42 = sun_scattering(metal::dot(view, sun_5), view.y, _e36, _e37, _e38, _e39, _e19.coverage, _e12, l_9.coverage, frame);
        metal::float4 _e45 = frame.sun_illuminance;
        metal::float3 _e47 = sun_through_air(rel_8, frame, transmittance_lut_in);
        metal::float3 lit = _e45.xyz * _e47;
        sun_light = lit * _e42.total;
        octave_light = lit * _e42.octaves;
    }
    float _e56 = frame.extinction.z;
    float _e64 = saturate(1.0 - ((_e56 * _e19.precipitation) * (1.0 - _e12)));
    float _e68 = frame.extinction.x;
    float k_15 = (_e68 * density_2) * _e64;
    metal::float3 _e71 = sun_light;
    metal::float3 _e72 = ambient(_e12, rel_8, frame, sky_ambient_in);
    metal::float3 _e75 = octave_light;
    return ScatteredLight {(_e71 + _e72) * k_15, _e75 * k_15};
}

metal::float3 shadow_ground_point(
    metal::uint2 c_2,
    constant Frame& frame
) {
    metal::float2 xz_1 = (((static_cast<metal::float2>(c_2) / metal::float2(127.0)) * 2.0) - metal::float2(1.0)) * SHADOW_HALF_EXTENT;
    float rp_4 = frame.atmosphere.x;
    float s2_ = metal::dot(xz_1, xz_1);
    float y_1 = -(s2_) / (metal::sqrt(metal::max((rp_4 * rp_4) - s2_, 0.0)) + rp_4);
    return metal::float3(xz_1.x, y_1, xz_1.y);
}

float ground_shadow(
    metal::float3 rel_9,
    metal::texture2d<float, metal::access::sample> cloud_shadow_in
) {
    float edge = metal::max(metal::abs(rel_9.x), metal::abs(rel_9.z)) / SHADOW_HALF_EXTENT;
    if (edge >= 1.0) {
        return 1.0;
    }
    metal::float2 x_9 = (rel_9.xz / metal::float2(40000.0)) + metal::float2(0.5);
    metal::float4 _e21 = lut_bilinear(cloud_shadow_in, x_9, metal::uint2(128u));
    float t_6 = _e21.x;
    return metal::mix(t_6, 1.0, metal::smoothstep(SHADOW_FADE_START, 1.0, edge));
}

metal::float3 ground_shadow_loss(
    metal::float3 view_1,
    float r_12,
    constant Frame& frame,
    metal::texture2d<float, metal::access::sample> transmittance_lut_in,
    metal::texture2d<float, metal::access::sample> cloud_shadow_in
) {
    float _e3 = distance_to_ground(r_12, view_1.y, frame);
    float _e7 = frame.camera_position.y;
    float cam_alt = metal::max(_e7, 0.0);
    float _e17 = ground_shadow((view_1 * (_e3 * 1000.0)) + metal::float3(0.0, cam_alt, 0.0), cloud_shadow_in);
    if (_e17 >= 1.0) {
        return metal::float3(0.0);
    }
    float _e22 = air_bottom(frame);
    float mu_g = metal::clamp(((r_12 * view_1.y) + _e3) / _e22, -1.0, 1.0);
    float _e33 = frame.sun_direction.y;
    metal::float4 _e37 = frame.sun_direction;
    float mu_s_6 = metal::clamp(((r_12 * _e33) + (_e3 * metal::dot(view_1, _e37.xyz))) / _e22, -1.0, 1.0);
    metal::float3 _e47 = transmittance_to_top(_e22, -(mu_g), frame, transmittance_lut_in);
    metal::float3 _e50 = transmittance_to_top(r_12, -(view_1.y), frame, transmittance_lut_in);
    metal::float3 t_view_1 = metal::min(_e47 / metal::max(_e50, metal::float3(0.00000000000000000001)), metal::float3(1.0));
    metal::float3 _e61 = ground_radiance_sun(mu_s_6, frame, transmittance_lut_in);
    return ((1.0 - _e17) * t_view_1) * _e61;
}

float empty_cell_exit(
    metal::float3 p_12,
    metal::float3 d_14,
    constant Frame& frame,
    metal::texture2d<float, metal::access::sample> occupancy_in
) {
    float exit = 1000000000000000000000000000000.0;
    metal::float4 _e6 = frame.wind_offsets0_;
    float _e12 = frame.periods.x;
    metal::float2 uv_4 = metal::fract((p_12.xz - _e6.xy) / metal::float2(_e12)) * 64.0;
    metal::uint2 cell_1 = metal::min(naga_f2u32(uv_4), metal::uint2(63u));
    metal::float4 _e23 = occupancy_in.read(metal::uint2(cell_1), 0);
    float m_3 = _e23.x;
    float _e28 = frame.clouds.x;
    if ((m_3 + (2.0 * (_e28 - 0.5))) > -0.003921569) {
        return 0.0;
    }
    float _e40 = frame.periods.x;
    float cell_m = _e40 / 64.0;
    metal::float2 inside = (uv_4 - static_cast<metal::float2>(cell_1)) * cell_m;
    if (d_14.x > 0.000001) {
        float _e50 = exit;
        exit = metal::min(_e50, (cell_m - inside.x) / d_14.x);
    } else {
        if (d_14.x < -0.000001) {
            float _e59 = exit;
            exit = metal::min(_e59, inside.x / -(d_14.x));
        }
    }
    if (d_14.z > 0.000001) {
        float _e68 = exit;
        exit = metal::min(_e68, (cell_m - inside.y) / d_14.z);
    } else {
        if (d_14.z < -0.000001) {
            float _e77 = exit;
            exit = metal::min(_e77, inside.y / -(d_14.z));
        }
    }
    float _e83 = exit;
    return metal::max(_e83, 0.0);
}

void count(
    uint index_1,
    uint value,
    device Stats& stats
) {
    bool local_37 = {};
    if (STATS) {
        local_37 = value != 0u;
    } else {
        local_37 = false;
    }
    bool _e8 = local_37;
    if (_e8) {
        uint _e12 = metal::atomic_fetch_add_explicit(&stats.counters.inner[index_1], value, metal::memory_order_relaxed);
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
    float x_10 = sigma_t * dt;
    float f_4 = (x_10 < 0.001) ? (1.0 - (0.5 * x_10)) : ((1.0 - metal::exp(-(x_10))) / x_10);
    return source * (dt * f_4);
}

uint naga_div(uint lhs, uint rhs) {
    return lhs / metal::select(rhs, 1u, rhs == 0u);
}

float start_offset(
    metal::uint2 pixel_3,
    constant Frame& frame
) {
    uint _e4 = frame.modes.w;
    bool jitter_1 = (_e4 & FLAG_JITTER) != 0u;
    uint k_16 = frame.temporal.x;
    if (k_16 <= 1u) {
        uint _e18 = frame.misc.y;
        float _e19 = hash_unit(pixel_3, _e18);
        return jitter_1 ? _e19 : 0.5;
    }
    float _e23 = hash_unit(pixel_3, 0u);
    float base_2 = jitter_1 ? _e23 : 0.5;
    uint _e29 = frame.misc.y;
    float _e32 = van_der_corput(naga_div(_e29, k_16 * k_16));
    return metal::fract(base_2 + _e32);
}

bool march_layer(
    metal::float3 view_2,
    Interval span_1,
    Layer l_10,
    float jitter,
    thread MarchState& state,
    thread Counters& counters_10,
    constant Frame& frame,
    metal::texture2d<float, metal::access::sample> transmittance_lut_in,
    metal::texture2d<float, metal::access::sample> sky_ambient_in,
    metal::texture3d<float, metal::access::sample> shape_tex,
    metal::texture3d<float, metal::access::sample> detail_tex,
    metal::texture2d<float, metal::access::sample> weather_tex,
    metal::texture2d<float, metal::access::sample> curl_tex,
    metal::sampler noise_sampler,
    metal::texture2d<float, metal::access::sample> occupancy_in
) {
    uint steps_2 = {};
    uint i_13 = 0u;
    uint stride = 1u;
    uint empty = 0u;
    bool local_38 = {};
    float cam_alt_1 = frame.camera_position.y;
    metal::float4 _e12 = frame.camera_position;
    metal::float2 cam_xz = _e12.xz;
    uint _e17 = frame.counts.z;
    steps_2 = _e17;
    float _e22 = frame.march.x;
    if (_e22 > 0.0) {
        float _e29 = frame.march.x;
        steps_2 = metal::clamp(naga_f2u32(metal::ceil(span_1.length / _e29)), 1u, MAX_VIEW_STEPS);
    }
    uint _e37 = steps_2;
    float dt_2 = span_1.length / static_cast<float>(_e37);
    float _e43 = frame.extinction.x;
    float _e47 = frame.extinction.y;
    float sigma_e = _e43 + _e47;
    uint _e52 = frame.modes.w;
    bool dynamic_step = (_e52 & FLAG_DYNAMIC_STEP) != 0u;
    uint _e60 = frame.modes.w;
    bool empty_skip = (_e60 & FLAG_EMPTY_SKIP) != 0u;
    uint2 loop_bound_8 = uint2(4294967295u);
    while(true) {
        if (metal::all(loop_bound_8 == uint2(0u))) { break; }
        loop_bound_8 -= uint2(loop_bound_8.y == 0u, 1u);
        uint _e71 = i_13;
        uint _e72 = steps_2;
        if (_e71 >= _e72) {
            break;
        }
        uint _e75 = counters_10.view_steps;
        counters_10.view_steps = _e75 + 1u;
        uint _e79 = i_13;
        float t_7 = span_1.start + ((static_cast<float>(_e79) + jitter) * dt_2);
        metal::float3 rel_12 = (view_2 * t_7) + metal::float3(0.0, cam_alt_1, 0.0);
        metal::float3 p_17 = metal::float3(rel_12.x + cam_xz.x, rel_12.y, rel_12.z + cam_xz.y);
        if (empty_skip) {
            float _e97 = empty_cell_exit(p_17, view_2, frame, occupancy_in);
            if (_e97 > 0.0) {
                uint _e106 = steps_2;
                uint next_1 = naga_f2u32(metal::clamp(metal::ceil((((t_7 + _e97) - span_1.start) / dt_2) - jitter), 0.0, static_cast<float>(_e106)));
                uint _e111 = i_13;
                i_13 = metal::max(_e111 + 1u, next_1);
                continue;
            }
        }
        float _e115 = altitude_of(rel_12, frame);
        float _e116 = layer_density(p_17, _e115, l_10, counters_10, frame, shape_tex, detail_tex, weather_tex, curl_tex, noise_sampler);
        if (_e116 <= 0.0) {
            uint _e119 = empty;
            empty = _e119 + 1u;
            if (dynamic_step) {
                uint _e124 = empty;
                local_38 = _e124 >= 8u;
            } else {
                local_38 = false;
            }
            bool _e128 = local_38;
            if (_e128) {
                stride = 2u;
            }
            uint _e130 = i_13;
            uint _e131 = stride;
            i_13 = _e130 + _e131;
            continue;
        }
        uint _e133 = stride;
        if (_e133 > 1u) {
            uint _e136 = i_13;
            uint _e137 = stride;
            i_13 = _e136 - (_e137 - 1u);
            stride = 1u;
            empty = 0u;
            continue;
        }
        empty = 0u;
        float sigma_t_3 = sigma_e * _e116;
        ScatteredLight _e145 = scattered_light(rel_12, p_17, _e115, _e116, view_2, l_10, counters_10, frame, transmittance_lut_in, sky_ambient_in, shape_tex, detail_tex, weather_tex, curl_tex, noise_sampler);
        float transmittance_2 = state.transmittance;
        metal::float3 _e149 = state.radiance;
        metal::float3 _e151 = step_integral(_e145.total, sigma_t_3, dt_2, frame);
        state.radiance = _e149 + (transmittance_2 * _e151);
        metal::float3 _e155 = state.octaves;
        metal::float3 _e157 = step_integral(_e145.octaves, sigma_t_3, dt_2, frame);
        state.octaves = _e155 + (transmittance_2 * _e157);
        float step_t = metal::exp(-(sigma_t_3) * dt_2);
        float _e164 = state.depth_sum;
        state.depth_sum = _e164 + ((t_7 * transmittance_2) * (1.0 - step_t));
        state.transmittance = transmittance_2 * step_t;
        float _e173 = state.transmittance;
        float _e177 = frame.march.w;
        if (_e173 < _e177) {
            return true;
        }
        uint _e180 = i_13;
        i_13 = _e180 + 1u;
    }
    return false;
}

MarchResult march_pixel(
    metal::uint2 pixel_4,
    constant Frame& frame,
    metal::texture2d<float, metal::access::sample> transmittance_lut_in,
    metal::texture2d<float, metal::access::sample> sky_ambient_in,
    metal::texture3d<float, metal::access::sample> shape_tex,
    metal::texture3d<float, metal::access::sample> detail_tex,
    metal::texture2d<float, metal::access::sample> weather_tex,
    metal::texture2d<float, metal::access::sample> curl_tex,
    metal::sampler noise_sampler,
    metal::texture2d<float, metal::access::sample> occupancy_in,
    device Stats& stats
) {
    Counters counters_11 = Counters {0u, 0u, 0u, 0u};
    MarchState state_1 = MarchState {metal::float3(0.0), 1.0, 0.0, {}, metal::float3(0.0)};
    bool marched = false;
    bool ground_1 = false;
    float last_start = -1.0;
    uint last_index = NO_LAYER;
    bool exited = false;
    uint k_6 = 0u;
    uint next = {};
    Interval span_2 = {};
    uint i_14 = {};
    bool local_39 = {};
    bool local_40 = {};
    bool local_41 = {};
    bool local_42 = {};
    bool local_43 = {};
    bool local_44 = {};
    float depth_1 = 0.0;
    metal::float3 _e1 = view_ray(pixel_4, frame);
    float cam_alt_2 = frame.camera_position.y;
    count(STAT_PIXELS, 1u, stats);
    float _e22 = start_offset(pixel_4, frame);
    uint _e23 = layer_count(frame);
    uint2 loop_bound_9 = uint2(4294967295u);
    bool loop_init_8 = true;
    while(true) {
        if (metal::all(loop_bound_9 == uint2(0u))) { break; }
        loop_bound_9 -= uint2(loop_bound_9.y == 0u, 1u);
        if (!loop_init_8) {
            uint _e121 = k_6;
            k_6 = _e121 + 1u;
        }
        loop_init_8 = false;
        uint _e36 = k_6;
        if (_e36 < _e23) {
        } else {
            break;
        }
        {
            next = NO_LAYER;
            span_2 = Interval {0.0, 0.0, 1u};
            i_14 = 0u;
            uint2 loop_bound_10 = uint2(4294967295u);
            bool loop_init_9 = true;
            while(true) {
                if (metal::all(loop_bound_10 == uint2(0u))) { break; }
                loop_bound_10 -= uint2(loop_bound_10.y == 0u, 1u);
                if (!loop_init_9) {
                    uint _e104 = i_14;
                    i_14 = _e104 + 1u;
                }
                loop_init_9 = false;
                uint _e47 = i_14;
                if (_e47 < _e23) {
                } else {
                    break;
                }
                {
                    uint _e49 = i_14;
                    Layer _e50 = cloud_layer(_e49, frame);
                    Interval _e51 = layer_interval(cam_alt_2, _e1, _e50, frame);
                    bool _e52 = ground_1;
                    if (!(_e52)) {
                        local_39 = _e51.kind == RAY_HITS_GROUND;
                    } else {
                        local_39 = true;
                    }
                    bool _e60 = local_39;
                    ground_1 = _e60;
                    float _e62 = last_start;
                    if (!((_e51.start > _e62))) {
                        float _e68 = last_start;
                        if (_e51.start == _e68) {
                            uint _e72 = i_14;
                            uint _e73 = last_index;
                            local_41 = _e72 > _e73;
                        } else {
                            local_41 = false;
                        }
                        bool _e76 = local_41;
                        local_40 = _e76;
                    } else {
                        local_40 = true;
                    }
                    bool after = local_40;
                    if (_e51.kind == RAY_MARCH) {
                        local_42 = after;
                    } else {
                        local_42 = false;
                    }
                    bool _e85 = local_42;
                    if (_e85) {
                        uint _e88 = next;
                        if (!((_e88 == NO_LAYER))) {
                            float _e96 = span_2.start;
                            local_44 = _e51.start < _e96;
                        } else {
                            local_44 = true;
                        }
                        bool _e99 = local_44;
                        local_43 = _e99;
                    } else {
                        local_43 = false;
                    }
                    bool _e101 = local_43;
                    if (_e101) {
                        uint _e102 = i_14;
                        next = _e102;
                        span_2 = _e51;
                    }
                }
            }
            uint _e106 = next;
            if (_e106 == NO_LAYER) {
                break;
            }
            marched = true;
            float _e111 = span_2.start;
            last_start = _e111;
            uint _e112 = next;
            last_index = _e112;
            Interval _e113 = span_2;
            uint _e114 = next;
            Layer _e115 = cloud_layer(_e114, frame);
            bool _e116 = march_layer(_e1, _e113, _e115, _e22, state_1, counters_11, frame, transmittance_lut_in, sky_ambient_in, shape_tex, detail_tex, weather_tex, curl_tex, noise_sampler, occupancy_in);
            if (_e116) {
                count(STAT_EXIT_TRANSMITTANCE, 1u, stats);
                exited = true;
                break;
            }
        }
    }
    bool _e123 = marched;
    if (_e123) {
        count(STAT_MARCHED, 1u, stats);
    } else {
        bool _e126 = ground_1;
        if (_e126) {
            count(STAT_EXIT_GROUND, 1u, stats);
        } else {
            count(STAT_EXIT_MISSED, 1u, stats);
        }
    }
    uint _e133 = counters_11.view_steps;
    count(STAT_VIEW_STEPS, _e133, stats);
    uint _e136 = counters_11.density;
    count(STAT_DENSITY, _e136, stats);
    uint _e139 = counters_11.detail;
    count(STAT_DETAIL, _e139, stats);
    uint _e142 = counters_11.light;
    count(STAT_LIGHT, _e142, stats);
    float _e146 = state_1.transmittance;
    if (_e146 < 1.0) {
        float _e150 = state_1.depth_sum;
        float _e152 = state_1.transmittance;
        depth_1 = _e150 / (1.0 - _e152);
    }
    float _e157 = state_1.transmittance;
    bool _e158 = exited;
    float transmittance_3 = _e158 ? 0.0 : _e157;
    metal::float4 _e163 = frame.sun_direction;
    float _e167 = state_1.transmittance;
    float _e168 = forward_lobe(metal::dot(_e1, _e163.xyz), _e167, frame);
    metal::float3 _e170 = state_1.radiance;
    metal::float3 _e172 = state_1.octaves;
    metal::float3 radiance_5 = _e170 + (_e172 * (_e168 - 1.0));
    float _e177 = depth_1;
    return MarchResult {radiance_5, transmittance_3, _e177};
}

metal::uint2 bayer2_(
    uint v_2
) {
    return metal::uint2((v_2 ^ (v_2 >> 1u)) & 1u, v_2 & 1u);
}

uint naga_mod(uint lhs, uint rhs) {
    return lhs % metal::select(rhs, 1u, rhs == 0u);
}

metal::uint2 block_offset(
    uint f,
    uint k_7
) {
    if (k_7 == 2u) {
        metal::uint2 _e6 = bayer2_(naga_mod(f, 4u));
        return _e6;
    }
    if (k_7 == 4u) {
        uint b_9 = naga_mod(f, 16u);
        metal::uint2 _e13 = bayer2_(b_9 >> 2u);
        metal::uint2 _e17 = bayer2_(b_9 & 3u);
        return _e13 + (2u * _e17);
    }
    return metal::uint2(0u);
}

metal::float2 reproject(
    metal::uint2 pixel_5,
    float depth_2,
    constant Frame& frame
) {
    bool local_45 = {};
    bool local_46 = {};
    bool local_47 = {};
    metal::float3 dir = {};
    metal::float4 _e4 = frame.previous_position;
    metal::float4 _e7 = frame.camera_position;
    if (metal::all(_e4 == _e7)) {
        metal::float4 _e14 = frame.previous_forward;
        metal::float4 _e17 = frame.camera_forward;
        local_45 = metal::all(_e14 == _e17);
    } else {
        local_45 = false;
    }
    bool _e21 = local_45;
    if (_e21) {
        metal::float4 _e26 = frame.previous_right;
        metal::float4 _e29 = frame.camera_right;
        local_46 = metal::all(_e26 == _e29);
    } else {
        local_46 = false;
    }
    bool _e33 = local_46;
    if (_e33) {
        metal::float4 _e38 = frame.previous_up;
        metal::float4 _e41 = frame.camera_up;
        local_47 = metal::all(_e38 == _e41);
    } else {
        local_47 = false;
    }
    bool same = local_47;
    if (same) {
        return static_cast<metal::float2>(pixel_5);
    }
    metal::float3 _e47 = view_ray(pixel_5, frame);
    dir = _e47;
    if (depth_2 > 0.0) {
        metal::float4 _e54 = frame.camera_position;
        metal::float4 _e58 = frame.previous_position;
        dir = (_e47 * depth_2) + (_e54.xyz - _e58.xyz);
    }
    metal::float3 _e62 = dir;
    metal::float4 _e65 = frame.previous_forward;
    float z_3 = metal::dot(_e62, _e65.xyz);
    if (z_3 <= 0.0) {
        return metal::float2(-1000000000.0);
    }
    float tan_half_2 = frame.previous_position.w;
    float aspect_2 = frame.previous_forward.w;
    metal::float3 _e80 = dir;
    metal::float4 _e83 = frame.previous_right;
    metal::float3 _e89 = dir;
    metal::float4 _e92 = frame.previous_up;
    metal::float2 ndc_2 = metal::float2(metal::dot(_e80, _e83.xyz) / ((z_3 * tan_half_2) * aspect_2), -(metal::dot(_e89, _e92.xyz)) / (z_3 * tan_half_2));
    metal::uint4 _e106 = frame.counts;
    return (((ndc_2 * 0.5) + metal::float2(0.5)) * static_cast<metal::float2>(_e106.xy)) - metal::float2(0.5);
}

bool on_screen(
    metal::float2 q,
    constant Frame& frame
) {
    bool local_48 = {};
    metal::uint4 _e3 = frame.counts;
    metal::float2 size_3 = static_cast<metal::float2>(_e3.xy);
    if (metal::all(q >= metal::float2(-0.5))) {
        local_48 = metal::all(q <= (size_3 - metal::float2(0.5)));
    } else {
        local_48 = false;
    }
    bool _e18 = local_48;
    return _e18;
}

metal::float4 catmull_rom(
    float t_1
) {
    return metal::float4(t_1 * (-0.5 + (t_1 * (1.0 - (0.5 * t_1)))), 1.0 + ((t_1 * t_1) * (-2.5 + (1.5 * t_1))), t_1 * (0.5 + (t_1 * (2.0 - (1.5 * t_1)))), (t_1 * t_1) * (-0.5 + (0.5 * t_1)));
}

metal::float4 history_row(
    metal::int2 base_1,
    int dy,
    metal::float4 wx,
    constant Frame& frame,
    metal::texture2d<float, metal::access::sample> history_in
) {
    metal::uint4 _e5 = frame.counts;
    metal::int2 size_4 = static_cast<metal::int2>(_e5.xy);
    int y_2 = metal::clamp(as_type<int>(as_type<uint>(base_1.y) + as_type<uint>(dy)), 0, as_type<int>(as_type<uint>(size_4.y) - as_type<uint>(1)));
    int x0_ = metal::clamp(as_type<int>(as_type<uint>(base_1.x) - as_type<uint>(1)), 0, as_type<int>(as_type<uint>(size_4.x) - as_type<uint>(1)));
    int x1_ = metal::clamp(base_1.x, 0, as_type<int>(as_type<uint>(size_4.x) - as_type<uint>(1)));
    int x2_ = metal::clamp(as_type<int>(as_type<uint>(base_1.x) + as_type<uint>(1)), 0, as_type<int>(as_type<uint>(size_4.x) - as_type<uint>(1)));
    int x3_ = metal::clamp(as_type<int>(as_type<uint>(base_1.x) + as_type<uint>(2)), 0, as_type<int>(as_type<uint>(size_4.x) - as_type<uint>(1)));
    metal::float4 _e48 = history_in.read(metal::uint2(metal::int2(x0_, y_2)), 0);
    metal::float4 _e54 = history_in.read(metal::uint2(metal::int2(x1_, y_2)), 0);
    metal::float4 _e61 = history_in.read(metal::uint2(metal::int2(x2_, y_2)), 0);
    metal::float4 _e68 = history_in.read(metal::uint2(metal::int2(x3_, y_2)), 0);
    return (((_e48 * wx.x) + (_e54 * wx.y)) + (_e61 * wx.z)) + (_e68 * wx.w);
}

metal::int2 naga_f2i32(metal::float2 value) {
    return static_cast<metal::int2>(metal::clamp(value, -2147483600.0, 2147483500.0));
}

metal::float4 history_at(
    metal::float2 q_1,
    constant Frame& frame,
    metal::texture2d<float, metal::access::sample> history_in
) {
    metal::uint4 _e3 = frame.counts;
    metal::int2 size_5 = static_cast<metal::int2>(_e3.xy);
    metal::float2 c_9 = metal::clamp(q_1, metal::float2(0.0), static_cast<metal::float2>(as_type<metal::int2>(as_type<metal::uint2>(size_5) - as_type<metal::uint2>(metal::int2(1)))));
    metal::int2 base_3 = naga_f2i32(metal::floor(c_9));
    metal::float2 f_5 = c_9 - static_cast<metal::float2>(base_3);
    metal::float4 _e18 = catmull_rom(f_5.x);
    metal::float4 _e20 = catmull_rom(f_5.y);
    metal::float4 _e22 = history_row(base_3, -1, _e18, frame, history_in);
    metal::float4 _e26 = history_row(base_3, 0, _e18, frame, history_in);
    metal::float4 _e31 = history_row(base_3, 1, _e18, frame, history_in);
    metal::float4 _e36 = history_row(base_3, 2, _e18, frame, history_in);
    metal::float4 sum_6 = (((_e22 * _e20.x) + (_e26 * _e20.y)) + (_e31 * _e20.z)) + (_e36 * _e20.w);
    float _e45 = saturate(sum_6.w);
    return metal::float4(metal::max(sum_6.xyz, metal::float3(0.0)), _e45);
}

metal::float4 history_nearest(
    metal::float2 q_2,
    constant Frame& frame,
    metal::texture2d<float, metal::access::sample> history_in
) {
    metal::uint4 _e3 = frame.counts;
    metal::int2 size_6 = static_cast<metal::int2>(_e3.xy);
    metal::int2 p_18 = metal::clamp(naga_f2i32(metal::rint(q_2)), metal::int2(0), as_type<metal::int2>(as_type<metal::uint2>(size_6) - as_type<metal::uint2>(metal::int2(1))));
    metal::float4 _e16 = history_in.read(metal::uint2(p_18), 0);
    return _e16;
}

metal::float4 meta_at(
    metal::float2 q_3,
    constant Frame& frame,
    metal::texture2d<float, metal::access::sample> meta_in
) {
    metal::uint4 _e3 = frame.counts;
    metal::int2 size_7 = static_cast<metal::int2>(_e3.xy);
    metal::int2 p_19 = metal::clamp(naga_f2i32(metal::rint(q_3)), metal::int2(0), as_type<metal::int2>(as_type<metal::uint2>(size_7) - as_type<metal::uint2>(metal::int2(1))));
    metal::float4 _e16 = meta_in.read(metal::uint2(p_19), 0);
    return _e16;
}

metal::uint2 naga_div(metal::uint2 lhs, metal::uint2 rhs) {
    return lhs / metal::select(rhs, 1u, rhs == 0u);
}

bool in_blocks(
    metal::uint2 id_19,
    constant Frame& frame
) {
    uint k_17 = frame.temporal.x;
    metal::uint4 _e7 = frame.counts;
    return metal::all(id_19 < naga_div((_e7.xy + metal::uint2(k_17)) - metal::uint2(1u), metal::uint2(k_17)));
}

metal::uint2 sparse_pixel(
    metal::uint2 id_20,
    constant Frame& frame
) {
    uint k_18 = frame.temporal.x;
    uint _e9 = frame.misc.y;
    metal::uint2 _e10 = block_offset(_e9, k_18);
    return (id_20 * k_18) + _e10;
}

void store_sparse(
    metal::uint2 id_21,
    MarchResult r_13,
    metal::texture2d<float, metal::access::write> cloud_out,
    metal::texture2d<float, metal::access::write> depth_out
) {
    cloud_out.write(metal::float4(r_13.radiance, r_13.transmittance), metal::uint2(id_21));
    depth_out.write(metal::float4(r_13.depth, 0.0, 0.0, 0.0), metal::uint2(id_21));
    return;
}

uint rng_seed(
    metal::uint2 pixel_6,
    uint path_index
) {
    uint _e4 = pcg(path_index);
    uint _e6 = pcg(pixel_6.y ^ _e4);
    uint _e8 = pcg(pixel_6.x ^ _e6);
    return _e8;
}

float rng_next(
    thread uint& rng_1
) {
    uint _e1 = rng_1;
    rng_1 = (_e1 * 747796405u) + 2891336453u;
    uint s_10 = rng_1;
    uint word_1 = ((s_10 >> ((s_10 >> 28u) + 4u)) ^ s_10) * 277803737u;
    return static_cast<float>(((word_1 >> 22u) ^ word_1) >> 8u) * 0.000000059604645;
}

float rng_exponential(
    thread uint& rng_2,
    float sigma
) {
    float _e2 = rng_next(rng_2);
    return -(metal::log(1.0 - _e2)) / sigma;
}

Segments layer_segments(
    metal::float3 p_13,
    float alt_14,
    metal::float3 d_15,
    constant Frame& frame
) {
    Segments s_1 = Segments {metal::float2(0.0), metal::float2(0.0), 0u};
    bool local_49 = {};
    metal::float2 a_1 = metal::float2(0.0);
    metal::float2 b_1 = metal::float2(0.0);
    uint n_2 = 0u;
    bool local_50 = {};
    bool local_51 = {};
    bool local_52 = {};
    bool local_53 = {};
    metal::float2 _e10 = layers_span(frame);
    float bottom_2 = _e10.x;
    Roots _e12 = ray_shell_from(p_13, alt_14, d_15, bottom_2, frame);
    Roots _e14 = ray_shell_from(p_13, alt_14, d_15, _e10.y, frame);
    bool _e15 = hits_ground(p_13, alt_14, d_15, frame);
    if (!(!(_e14.hit))) {
        local_49 = _e14.t1_ <= 0.0;
    } else {
        local_49 = true;
    }
    bool _e25 = local_49;
    if (_e25) {
        Segments _e26 = s_1;
        return _e26;
    }
    float entry = metal::max(_e14.t0_, 0.0);
    if (_e12.hit) {
        local_50 = _e12.t0_ > 0.0;
    } else {
        local_50 = false;
    }
    bool _e45 = local_50;
    if (_e45) {
        local_51 = alt_14 >= bottom_2;
    } else {
        local_51 = false;
    }
    bool _e50 = local_51;
    if (_e50) {
        uint _e51 = n_2;
        a_1[_e51] = entry;
        uint _e53 = n_2;
        b_1[_e53] = _e12.t0_;
        uint _e56 = n_2;
        n_2 = _e56 + static_cast<uint>(_e12.t0_ > entry);
        if (!(_e15)) {
            local_52 = _e14.t1_ > _e12.t1_;
        } else {
            local_52 = false;
        }
        bool _e68 = local_52;
        if (_e68) {
            uint _e69 = n_2;
            a_1[_e69] = metal::max(_e12.t1_, entry);
            uint _e73 = n_2;
            b_1[_e73] = _e14.t1_;
            uint _e76 = n_2;
            n_2 = _e76 + 1u;
        }
    } else {
        if (alt_14 < bottom_2) {
            if (!(_e15)) {
                local_53 = _e12.hit;
            } else {
                local_53 = false;
            }
            bool _e85 = local_53;
            if (_e85) {
                a_1.x = metal::max(_e12.t1_, 0.0);
                b_1.x = _e14.t1_;
                n_2 = 1u;
            }
        } else {
            a_1.x = entry;
            b_1.x = _e14.t1_;
            n_2 = 1u;
        }
    }
    metal::float2 _e98 = a_1;
    s_1.a = _e98;
    metal::float2 _e100 = b_1;
    s_1.b = _e100;
    uint _e102 = n_2;
    s_1.count = _e102;
    Segments _e103 = s_1;
    return _e103;
}

float density_at(
    metal::float3 rel_10,
    thread Counters& counters_12,
    constant Frame& frame,
    metal::texture3d<float, metal::access::sample> shape_tex,
    metal::texture3d<float, metal::access::sample> detail_tex,
    metal::texture2d<float, metal::access::sample> weather_tex,
    metal::texture2d<float, metal::access::sample> curl_tex,
    metal::sampler noise_sampler
) {
    float _e6 = frame.camera_position.x;
    float _e13 = frame.camera_position.z;
    metal::float3 p_20 = metal::float3(rel_10.x + _e6, rel_10.y, rel_10.z + _e13);
    float _e16 = altitude_of(rel_10, frame);
    float _e17 = cloud_density(p_20, _e16, counters_12, frame, shape_tex, detail_tex, weather_tex, curl_tex, noise_sampler);
    return _e17;
}

float empty_cell_skip(
    metal::float3 origin_4,
    metal::float3 dir_1,
    float t_2,
    constant Frame& frame,
    metal::texture2d<float, metal::access::sample> occupancy_in
) {
    uint _e3 = layer_count(frame);
    if (_e3 > 1u) {
        return 0.0;
    }
    metal::float3 rel_13 = origin_4 + (dir_1 * t_2);
    float _e13 = frame.camera_position.x;
    float _e20 = frame.camera_position.z;
    metal::float3 p_21 = metal::float3(rel_13.x + _e13, rel_13.y, rel_13.z + _e20);
    float _e23 = empty_cell_exit(p_21, dir_1, frame, occupancy_in);
    if (_e23 <= 0.0) {
        return 0.0;
    }
    return _e23 + 0.05;
}

float density_max(
    constant Frame& frame
) {
    float m_1 = 0.0;
    uint i_15 = 0u;
    uint2 loop_bound_11 = uint2(4294967295u);
    bool loop_init_10 = true;
    while(true) {
        if (metal::all(loop_bound_11 == uint2(0u))) { break; }
        loop_bound_11 -= uint2(loop_bound_11.y == 0u, 1u);
        if (!loop_init_10) {
            uint _e17 = i_15;
            i_15 = _e17 + 1u;
        }
        loop_init_10 = false;
        uint _e4 = i_15;
        uint _e5 = layer_count(frame);
        if (_e4 < _e5) {
        } else {
            break;
        }
        {
            uint _e7 = i_15;
            Layer _e8 = cloud_layer(_e7, frame);
            float _e9 = m_1;
            m_1 = metal::max(_e9, _e8.density * (1.0 + _e8.precipitation));
        }
    }
    float _e19 = m_1;
    return metal::clamp(_e19, 0.0, 1.0);
}

float free_flight(
    metal::float3 origin_5,
    metal::float3 dir_2,
    Segments segs,
    thread uint& rng_3,
    thread Counters& counters_13,
    constant Frame& frame,
    metal::texture3d<float, metal::access::sample> shape_tex,
    metal::texture3d<float, metal::access::sample> detail_tex,
    metal::texture2d<float, metal::access::sample> weather_tex,
    metal::texture2d<float, metal::access::sample> curl_tex,
    metal::sampler noise_sampler,
    metal::texture2d<float, metal::access::sample> occupancy_in
) {
    uint k_8 = 0u;
    float t_3 = {};
    float _e5 = density_max(frame);
    float _e9 = frame.extinction.x;
    float _e13 = frame.extinction.y;
    float majorant = (_e9 + _e13) * _e5;
    if (majorant <= 0.0) {
        return -1.0;
    }
    uint2 loop_bound_12 = uint2(4294967295u);
    bool loop_init_11 = true;
    while(true) {
        if (metal::all(loop_bound_12 == uint2(0u))) { break; }
        loop_bound_12 -= uint2(loop_bound_12.y == 0u, 1u);
        if (!loop_init_11) {
            uint _e60 = k_8;
            k_8 = _e60 + 1u;
        }
        loop_init_11 = false;
        uint _e21 = k_8;
        if (_e21 < segs.count) {
        } else {
            break;
        }
        {
            uint _e25 = k_8;
            t_3 = segs.a[_e25];
            uint2 loop_bound_13 = uint2(4294967295u);
            while(true) {
                if (metal::all(loop_bound_13 == uint2(0u))) { break; }
                loop_bound_13 -= uint2(loop_bound_13.y == 0u, 1u);
                float _e28 = t_3;
                float _e29 = empty_cell_skip(origin_5, dir_2, _e28, frame, occupancy_in);
                if (_e29 > 0.0) {
                    float _e32 = t_3;
                    t_3 = _e32 + _e29;
                    float _e34 = t_3;
                    uint _e36 = k_8;
                    if (_e34 >= segs.b[_e36]) {
                        break;
                    }
                    continue;
                }
                float _e39 = t_3;
                float _e40 = rng_exponential(rng_3, majorant);
                t_3 = _e39 + _e40;
                float _e42 = t_3;
                uint _e44 = k_8;
                if (_e42 >= segs.b[_e44]) {
                    break;
                }
                uint _e48 = counters_13.view_steps;
                counters_13.view_steps = _e48 + 1u;
                float _e51 = t_3;
                float _e54 = density_at(origin_5 + (dir_2 * _e51), counters_13, frame, shape_tex, detail_tex, weather_tex, curl_tex, noise_sampler);
                float _e55 = rng_next(rng_3);
                if ((_e55 * _e5) < _e54) {
                    float _e58 = t_3;
                    return _e58;
                }
            }
        }
    }
    return -1.0;
}

float transmittance_along(
    metal::float3 origin_6,
    metal::float3 dir_3,
    Segments segs_1,
    thread uint& rng_4,
    thread Counters& counters_14,
    constant Frame& frame,
    metal::texture3d<float, metal::access::sample> shape_tex,
    metal::texture3d<float, metal::access::sample> detail_tex,
    metal::texture2d<float, metal::access::sample> weather_tex,
    metal::texture2d<float, metal::access::sample> curl_tex,
    metal::sampler noise_sampler,
    metal::texture2d<float, metal::access::sample> occupancy_in
) {
    float tr = 1.0;
    uint k_9 = 0u;
    float t_4 = {};
    float _e8 = frame.extinction.x;
    float _e12 = frame.extinction.y;
    float sigma_t_4 = _e8 + _e12;
    float _e14 = density_max(frame);
    float majorant_1 = sigma_t_4 * _e14;
    if (majorant_1 <= 0.0) {
        return 1.0;
    }
    uint2 loop_bound_14 = uint2(4294967295u);
    bool loop_init_12 = true;
    while(true) {
        if (metal::all(loop_bound_14 == uint2(0u))) { break; }
        loop_bound_14 -= uint2(loop_bound_14.y == 0u, 1u);
        if (!loop_init_12) {
            uint _e78 = k_9;
            k_9 = _e78 + 1u;
        }
        loop_init_12 = false;
        uint _e23 = k_9;
        if (_e23 < segs_1.count) {
        } else {
            break;
        }
        {
            uint _e27 = k_9;
            t_4 = segs_1.a[_e27];
            uint2 loop_bound_15 = uint2(4294967295u);
            while(true) {
                if (metal::all(loop_bound_15 == uint2(0u))) { break; }
                loop_bound_15 -= uint2(loop_bound_15.y == 0u, 1u);
                float _e30 = t_4;
                float _e31 = empty_cell_skip(origin_6, dir_3, _e30, frame, occupancy_in);
                if (_e31 > 0.0) {
                    float _e34 = t_4;
                    t_4 = _e34 + _e31;
                    float _e36 = t_4;
                    uint _e38 = k_9;
                    if (_e36 >= segs_1.b[_e38]) {
                        break;
                    }
                    continue;
                }
                float _e41 = t_4;
                float _e42 = rng_exponential(rng_4, majorant_1);
                t_4 = _e41 + _e42;
                float _e44 = t_4;
                uint _e46 = k_9;
                if (_e44 >= segs_1.b[_e46]) {
                    break;
                }
                uint _e50 = counters_14.light;
                counters_14.light = _e50 + 1u;
                float _e53 = t_4;
                float _e56 = density_at(origin_6 + (dir_3 * _e53), counters_14, frame, shape_tex, detail_tex, weather_tex, curl_tex, noise_sampler);
                float _e57 = tr;
                tr = _e57 * (1.0 - ((sigma_t_4 * _e56) / majorant_1));
                float _e63 = tr;
                if (_e63 <= 0.0) {
                    return 0.0;
                }
                float _e67 = tr;
                if (_e67 < 0.01) {
                    float _e70 = rng_next(rng_4);
                    if (_e70 < 0.75) {
                        return 0.0;
                    }
                    float _e74 = tr;
                    tr = _e74 * 4.0;
                }
            }
        }
    }
    float _e80 = tr;
    return _e80;
}

float sample_hg_cos(
    float g_4,
    float u
) {
    if (metal::abs(g_4) < 0.0001) {
        return 1.0 - (2.0 * u);
    }
    float s_11 = (1.0 - (g_4 * g_4)) / ((1.0 - g_4) + ((2.0 * g_4) * u));
    return metal::clamp(((1.0 + (g_4 * g_4)) - (s_11 * s_11)) / (2.0 * g_4), -1.0, 1.0);
}

PhaseSample sample_phase(
    metal::float3 dir_4,
    thread uint& rng_5,
    constant Frame& frame
) {
    float cos_theta_7 = 0.0;
    float pdf = 0.0;
    float _e2 = rng_next(rng_5);
    float _e3 = rng_next(rng_5);
    float _e5 = rng_next(rng_5);
    float phi_1 = 6.2831855 * _e5;
    uint _e14 = frame.modes.x;
    if (_e14 == PHASE_TWO_LOBE_HG) {
        float _e20 = frame.phase.x;
        float _e24 = frame.phase.y;
        float _e28 = frame.phase.z;
        float g_6 = (_e2 < _e28) ? _e24 : _e20;
        float _e31 = sample_hg_cos(g_6, _e3);
        cos_theta_7 = _e31;
        float _e32 = cos_theta_7;
        float _e36 = frame.phase.x;
        float _e37 = phase_hg(_e32, _e36);
        float _e38 = cos_theta_7;
        float _e42 = frame.phase.y;
        float _e43 = phase_hg(_e38, _e42);
        float _e47 = frame.phase.z;
        pdf = metal::mix(_e37, _e43, _e47);
    } else {
        float _e52 = frame.phase.x;
        float _e53 = sample_hg_cos(_e52, _e3);
        cos_theta_7 = _e53;
        float _e54 = cos_theta_7;
        float _e58 = frame.phase.x;
        float _e59 = phase_hg(_e54, _e58);
        pdf = _e59;
    }
    float _e60 = cos_theta_7;
    float _e61 = cos_theta_7;
    float sin_theta = metal::sqrt(metal::max(1.0 - (_e60 * _e61), 0.0));
    float sign = (dir_4.z >= 0.0) ? 1.0 : -1.0;
    float a_9 = -1.0 / (sign + dir_4.z);
    float bb = (dir_4.x * dir_4.y) * a_9;
    metal::float3 t_8 = metal::float3(1.0 + (((sign * dir_4.x) * dir_4.x) * a_9), sign * bb, -(sign) * dir_4.x);
    metal::float3 b_10 = metal::float3(bb, sign + ((dir_4.y * dir_4.y) * a_9), -(dir_4.y));
    float _e109 = cos_theta_7;
    metal::float3 w_7 = metal::normalize(((t_8 * (sin_theta * metal::cos(phi_1))) + (b_10 * (sin_theta * metal::sin(phi_1)))) + (dir_4 * _e109));
    float _e113 = cos_theta_7;
    float _e115 = phase(_e113, 1.0, frame);
    float _e116 = pdf;
    float _e118 = pdf;
    return PhaseSample {w_7, (_e118 > 0.0) ? (_e115 / _e116) : 0.0};
}

metal::float3 environment(
    metal::float3 pos,
    metal::float3 d_16,
    float h_9,
    constant Frame& frame,
    metal::texture2d<float, metal::access::sample> transmittance_lut_in,
    metal::texture2d<float, metal::access::sample> multiscatter_lut_in,
    metal::texture2d<float, metal::access::sample> sky_ambient_in,
    metal::texture2d<float, metal::access::sample> ground_irradiance_in
) {
    bool _e3 = physical_sky(frame);
    if (_e3) {
        metal::float3 _e4 = sky_from(pos, d_16, frame, transmittance_lut_in, multiscatter_lut_in, ground_irradiance_in);
        metal::float4 _e7 = frame.sun_illuminance;
        float _e13 = frame.ambient_bottom.w;
        return (_e4 * _e7.xyz) * _e13;
    }
    metal::float3 _e15 = ambient(h_9, pos, frame, sky_ambient_in);
    return _e15;
}

PathResult trace_path(
    metal::float3 view_3,
    Interval span_3,
    thread uint& rng_6,
    thread Counters& counters_15,
    constant Frame& frame,
    metal::texture2d<float, metal::access::sample> transmittance_lut_in,
    metal::texture2d<float, metal::access::sample> multiscatter_lut_in,
    metal::texture2d<float, metal::access::sample> sky_ambient_in,
    metal::texture2d<float, metal::access::sample> ground_irradiance_in,
    metal::texture3d<float, metal::access::sample> shape_tex,
    metal::texture3d<float, metal::access::sample> detail_tex,
    metal::texture2d<float, metal::access::sample> weather_tex,
    metal::texture2d<float, metal::access::sample> curl_tex,
    metal::sampler noise_sampler,
    metal::texture2d<float, metal::access::sample> occupancy_in
) {
    PathResult out_2 = PathResult {metal::float3(0.0), 1.0, -1.0};
    bool local_54 = {};
    bool local_55 = {};
    bool local_56 = {};
    uint max_orders = MAX_PATH_ORDERS;
    metal::float3 pos_1 = {};
    metal::float3 dir_5 = {};
    float throughput = 1.0;
    uint order = 0u;
    bool local_57 = {};
    if (span_3.kind != RAY_MARCH) {
        PathResult _e13 = out_2;
        return _e13;
    }
    float _e17 = frame.camera_position.y;
    metal::float3 cam = metal::float3(0.0, _e17, 0.0);
    Segments primary = Segments {metal::float2(span_3.start, 0.0), metal::float2(span_3.start + span_3.length, 0.0), 1u};
    float _e32 = transmittance_along(cam, view_3, primary, rng_6, counters_15, frame, shape_tex, detail_tex, weather_tex, curl_tex, noise_sampler, occupancy_in);
    out_2.transmittance = _e32;
    float _e33 = free_flight(cam, view_3, primary, rng_6, counters_15, frame, shape_tex, detail_tex, weather_tex, curl_tex, noise_sampler, occupancy_in);
    if (_e33 < 0.0) {
        PathResult _e36 = out_2;
        return _e36;
    }
    out_2.depth = _e33;
    metal::float4 _e40 = frame.sun_direction;
    metal::float3 sun_6 = _e40.xyz;
    float _e45 = frame.extinction.x;
    float _e49 = frame.extinction.y;
    float sigma_t_5 = _e45 + _e49;
    float _e54 = frame.extinction.x;
    float albedo = (sigma_t_5 > 0.0) ? (_e54 / sigma_t_5) : 0.0;
    float _e63 = frame.ambient_bottom.w;
    if (_e63 > 0.0) {
        bool _e68 = physical_sky(frame);
        if (!(_e68)) {
            metal::float4 _e74 = frame.ambient_bottom;
            local_55 = metal::any(_e74.xyz > metal::float3(0.0));
        } else {
            local_55 = true;
        }
        bool _e81 = local_55;
        if (!(_e81)) {
            metal::float4 _e87 = frame.ambient_top;
            local_56 = metal::any(_e87.xyz > metal::float3(0.0));
        } else {
            local_56 = true;
        }
        bool _e94 = local_56;
        local_54 = _e94;
    } else {
        local_54 = false;
    }
    bool ambient_on = local_54;
    uint _e102 = frame.misc.z;
    if (_e102 > 0u) {
        uint _e108 = frame.misc.z;
        max_orders = metal::min(_e108, MAX_PATH_ORDERS);
    }
    pos_1 = cam + (view_3 * _e33);
    dir_5 = view_3;
    uint2 loop_bound_16 = uint2(4294967295u);
    while(true) {
        if (metal::all(loop_bound_16 == uint2(0u))) { break; }
        loop_bound_16 -= uint2(loop_bound_16.y == 0u, 1u);
        float _e119 = throughput;
        throughput = _e119 * albedo;
        uint _e121 = order;
        order = _e121 + 1u;
        metal::float3 _e124 = pos_1;
        float _e125 = altitude_of(_e124, frame);
        float _e126 = height_fraction(_e125, frame);
        metal::float3 _e127 = pos_1;
        bool _e128 = hits_ground(_e127, _e125, sun_6, frame);
        if (!(_e128)) {
            metal::float3 _e130 = pos_1;
            metal::float3 _e131 = pos_1;
            Segments _e132 = layer_segments(_e131, _e125, sun_6, frame);
            float _e133 = transmittance_along(_e130, sun_6, _e132, rng_6, counters_15, frame, shape_tex, detail_tex, weather_tex, curl_tex, noise_sampler, occupancy_in);
            metal::float3 _e135 = out_2.radiance;
            metal::float4 _e138 = frame.sun_illuminance;
            metal::float3 _e140 = pos_1;
            metal::float3 _e141 = sun_through_air(_e140, frame, transmittance_lut_in);
            float _e143 = throughput;
            metal::float3 _e144 = dir_5;
            float _e147 = phase(metal::dot(_e144, sun_6), 1.0, frame);
            out_2.radiance = _e135 + ((_e138.xyz * _e141) * ((_e143 * _e147) * _e133));
        }
        metal::float3 _e152 = dir_5;
        PhaseSample _e153 = sample_phase(_e152, rng_6, frame);
        metal::float3 _e154 = pos_1;
        metal::float3 _e156 = pos_1;
        Segments _e158 = layer_segments(_e156, _e125, _e153.dir, frame);
        float _e159 = free_flight(_e154, _e153.dir, _e158, rng_6, counters_15, frame, shape_tex, detail_tex, weather_tex, curl_tex, noise_sampler, occupancy_in);
        if (_e159 < 0.0) {
            if (ambient_on) {
                metal::float3 _e163 = out_2.radiance;
                metal::float3 _e164 = pos_1;
                metal::float3 _e166 = environment(_e164, _e153.dir, _e126, frame, transmittance_lut_in, multiscatter_lut_in, sky_ambient_in, ground_irradiance_in);
                float _e167 = throughput;
                out_2.radiance = _e163 + (_e166 * (_e167 * _e153.weight));
            }
            break;
        }
        uint _e172 = order;
        uint _e173 = max_orders;
        if (_e172 >= _e173) {
            break;
        }
        float _e175 = throughput;
        throughput = _e175 * _e153.weight;
        dir_5 = _e153.dir;
        uint _e179 = order;
        if (_e179 >= 3u) {
            float _e184 = throughput;
            local_57 = _e184 < 0.1;
        } else {
            local_57 = false;
        }
        bool _e188 = local_57;
        if (_e188) {
            float _e189 = rng_next(rng_6);
            float _e190 = throughput;
            if (_e189 >= (_e190 / 0.1)) {
                break;
            }
            throughput = 0.1;
        }
        float _e195 = throughput;
        if (_e195 <= 0.0) {
            break;
        }
        metal::float3 _e198 = pos_1;
        metal::float3 _e199 = dir_5;
        pos_1 = _e198 + (_e199 * _e159);
    }
    PathResult _e202 = out_2;
    return _e202;
}

bool camera_still(
    constant Frame& frame
) {
    bool local_58 = {};
    bool local_59 = {};
    bool local_60 = {};
    metal::float4 _e2 = frame.camera_position;
    metal::float4 _e5 = frame.previous_position;
    if (metal::all(_e2 == _e5)) {
        metal::float4 _e12 = frame.camera_forward;
        metal::float4 _e15 = frame.previous_forward;
        local_58 = metal::all(_e12 == _e15);
    } else {
        local_58 = false;
    }
    bool _e19 = local_58;
    if (_e19) {
        metal::float4 _e24 = frame.camera_right;
        metal::float4 _e28 = frame.previous_right;
        local_59 = metal::all(_e24.xyz == _e28.xyz);
    } else {
        local_59 = false;
    }
    bool _e33 = local_59;
    if (_e33) {
        metal::float4 _e38 = frame.camera_up;
        metal::float4 _e42 = frame.previous_up;
        local_60 = metal::all(_e38.xyz == _e42.xyz);
    } else {
        local_60 = false;
    }
    bool _e47 = local_60;
    return _e47;
}

float luminance(
    metal::float3 c_3
) {
    return metal::dot(c_3, metal::float3(0.2126, 0.7152, 0.0722));
}

float basic_sun_depth(
    metal::float3 rel_11,
    float alt_15,
    thread Counters& counters_16,
    constant Frame& frame,
    metal::texture3d<float, metal::access::sample> shape_tex,
    metal::texture3d<float, metal::access::sample> detail_tex,
    metal::texture2d<float, metal::access::sample> weather_tex,
    metal::texture2d<float, metal::access::sample> curl_tex,
    metal::sampler noise_sampler
) {
    float tau_10 = 0.0;
    uint i_16 = 1u;
    uint steps_4 = frame.counts.w;
    if (steps_4 == 0u) {
        return 0.0;
    }
    metal::float4 _e12 = frame.sun_direction;
    metal::float3 sun_7 = _e12.xyz;
    float rp_5 = frame.atmosphere.x;
    float top_2 = frame.atmosphere.z;
    float _e25 = frame.atmosphere.y;
    float thickness = top_2 - _e25;
    Roots _e39 = solve_sphere(metal::dot(sun_7, metal::float3(rel_11.x, rel_11.y + rp_5, rel_11.z)), (alt_15 - top_2) * ((alt_15 + top_2) + (2.0 * rp_5)));
    float length = metal::min(metal::max(_e39.t1_, 0.0), 3.0 * thickness);
    float dt_3 = length / static_cast<float>(steps_4);
    float _e51 = frame.extinction.x;
    float _e55 = frame.extinction.y;
    float sigma_t_6 = _e51 + _e55;
    metal::float4 _e59 = frame.camera_position;
    metal::float2 cam_xz_1 = _e59.xz;
    uint2 loop_bound_17 = uint2(4294967295u);
    bool loop_init_13 = true;
    while(true) {
        if (metal::all(loop_bound_17 == uint2(0u))) { break; }
        loop_bound_17 -= uint2(loop_bound_17.y == 0u, 1u);
        if (!loop_init_13) {
            uint _e90 = i_16;
            i_16 = _e90 + 1u;
        }
        loop_init_13 = false;
        uint _e65 = i_16;
        if (_e65 <= steps_4) {
        } else {
            break;
        }
        {
            uint _e68 = counters_16.light;
            counters_16.light = _e68 + 1u;
            uint _e71 = i_16;
            metal::float3 q_8 = rel_11 + (sun_7 * (static_cast<float>(_e71) * dt_3));
            metal::float3 p_22 = metal::float3(q_8.x + cam_xz_1.x, q_8.y, q_8.z + cam_xz_1.y);
            float _e84 = tau_10;
            float _e85 = altitude_of(q_8, frame);
            float _e86 = cloud_density(p_22, _e85, counters_16, frame, shape_tex, detail_tex, weather_tex, curl_tex, noise_sampler);
            tau_10 = _e84 + ((sigma_t_6 * _e86) * dt_3);
        }
    }
    float _e93 = tau_10;
    return _e93;
}

MarchResult basic_pixel(
    metal::uint2 pixel_7,
    constant Frame& frame,
    metal::texture3d<float, metal::access::sample> shape_tex,
    metal::texture3d<float, metal::access::sample> detail_tex,
    metal::texture2d<float, metal::access::sample> weather_tex,
    metal::texture2d<float, metal::access::sample> curl_tex,
    metal::sampler noise_sampler,
    device Stats& stats
) {
    Counters counters_17 = Counters {0u, 0u, 0u, 0u};
    metal::float3 radiance_2 = metal::float3(0.0);
    float transmittance_1 = 1.0;
    float depth_sum = 0.0;
    uint i_17 = 0u;
    float depth_3 = 0.0;
    metal::float3 _e1 = view_ray(pixel_7, frame);
    float cam_alt_3 = frame.camera_position.y;
    metal::float4 _e8 = frame.camera_position;
    metal::float2 cam_xz_2 = _e8.xz;
    count(STAT_PIXELS, 1u, stats);
    Interval _e25 = cloud_interval(cam_alt_3, _e1, frame);
    if (_e25.kind == RAY_MISSES_LAYER) {
        count(STAT_EXIT_MISSED, 1u, stats);
    } else {
        if (_e25.kind == RAY_HITS_GROUND) {
            count(STAT_EXIT_GROUND, 1u, stats);
        } else {
            count(STAT_MARCHED, 1u, stats);
            uint steps_5 = frame.counts.z;
            float dt_4 = _e25.length / static_cast<float>(steps_5);
            float sigma_s = frame.extinction.x;
            float _e52 = frame.extinction.y;
            float sigma_t_7 = sigma_s + _e52;
            metal::float4 _e56 = frame.sun_illuminance;
            metal::float4 _e60 = frame.sun_direction;
            float _e66 = frame.phase.x;
            float _e67 = phase_hg(metal::dot(_e1, _e60.xyz), _e66);
            metal::float3 sun_phase = _e56.xyz * _e67;
            uint2 loop_bound_18 = uint2(4294967295u);
            bool loop_init_14 = true;
            while(true) {
                if (metal::all(loop_bound_18 == uint2(0u))) { break; }
                loop_bound_18 -= uint2(loop_bound_18.y == 0u, 1u);
                if (!loop_init_14) {
                    uint _e131 = i_17;
                    i_17 = _e131 + 1u;
                }
                loop_init_14 = false;
                uint _e71 = i_17;
                if (_e71 < steps_5) {
                } else {
                    break;
                }
                {
                    uint _e74 = counters_17.view_steps;
                    counters_17.view_steps = _e74 + 1u;
                    uint _e78 = i_17;
                    float t_9 = _e25.start + (static_cast<float>(_e78) * dt_4);
                    metal::float3 rel_14 = (_e1 * t_9) + metal::float3(0.0, cam_alt_3, 0.0);
                    metal::float3 p_23 = metal::float3(rel_14.x + cam_xz_2.x, rel_14.y, rel_14.z + cam_xz_2.y);
                    float _e95 = altitude_of(rel_14, frame);
                    float _e96 = cloud_density(p_23, _e95, counters_17, frame, shape_tex, detail_tex, weather_tex, curl_tex, noise_sampler);
                    if (_e96 <= 0.0) {
                        continue;
                    }
                    float _e99 = basic_sun_depth(rel_14, _e95, counters_17, frame, shape_tex, detail_tex, weather_tex, curl_tex, noise_sampler);
                    float beer_powder = (2.0 * metal::exp(-(_e99))) * (1.0 - metal::exp(-2.0 * _e99));
                    metal::float3 _e110 = radiance_2;
                    float _e111 = transmittance_1;
                    radiance_2 = _e110 + (sun_phase * ((((beer_powder * _e111) * sigma_s) * _e96) * dt_4));
                    float step_t_1 = metal::exp((-(sigma_t_7) * _e96) * dt_4);
                    float _e122 = depth_sum;
                    float _e123 = transmittance_1;
                    depth_sum = _e122 + ((t_9 * _e123) * (1.0 - step_t_1));
                    float _e129 = transmittance_1;
                    transmittance_1 = _e129 * step_t_1;
                }
            }
        }
    }
    uint _e136 = counters_17.view_steps;
    count(STAT_VIEW_STEPS, _e136, stats);
    uint _e139 = counters_17.density;
    count(STAT_DENSITY, _e139, stats);
    uint _e142 = counters_17.detail;
    count(STAT_DETAIL, _e142, stats);
    uint _e145 = counters_17.light;
    count(STAT_LIGHT, _e145, stats);
    float _e148 = transmittance_1;
    if (_e148 < 1.0) {
        float _e151 = depth_sum;
        float _e152 = transmittance_1;
        depth_3 = _e151 / (1.0 - _e152);
    }
    metal::float3 _e156 = radiance_2;
    float _e157 = transmittance_1;
    float _e158 = depth_3;
    return MarchResult {_e156, _e157, _e158};
}

float atlas_hash(
    uint a_2,
    uint b_2
) {
    uint _e2 = pcg(b_2);
    uint _e4 = pcg(a_2 ^ _e2);
    return static_cast<float>(_e4 >> 8u) * 0.000000059604645;
}

float value_noise(
    metal::float2 p_14,
    uint seed
) {
    metal::uint2 i_19 = naga_f2u32(metal::floor(p_14));
    metal::float2 f_6 = metal::fract(p_14);
    metal::float2 s_12 = (f_6 * f_6) * (metal::float2(3.0) - (2.0 * f_6));
    uint h_14 = seed * 7919u;
    float _e17 = atlas_hash(i_19.x + h_14, i_19.y);
    float _e23 = atlas_hash((i_19.x + 1u) + h_14, i_19.y);
    float _e29 = atlas_hash(i_19.x + h_14, i_19.y + 1u);
    float _e37 = atlas_hash((i_19.x + 1u) + h_14, i_19.y + 1u);
    return metal::mix(metal::mix(_e17, _e23, s_12.x), metal::mix(_e29, _e37, s_12.x), s_12.y);
}

float value_fbm(
    metal::float2 p_15,
    uint seed_1
) {
    float sum_5 = 0.0;
    float weight = 0.5;
    metal::float2 q_4 = {};
    uint o = 0u;
    q_4 = p_15;
    uint2 loop_bound_19 = uint2(4294967295u);
    bool loop_init_15 = true;
    while(true) {
        if (metal::all(loop_bound_19 == uint2(0u))) { break; }
        loop_bound_19 -= uint2(loop_bound_19.y == 0u, 1u);
        if (!loop_init_15) {
            uint _e26 = o;
            o = _e26 + 1u;
        }
        loop_init_15 = false;
        uint _e9 = o;
        if (_e9 < 4u) {
        } else {
            break;
        }
        {
            float _e12 = sum_5;
            float _e13 = weight;
            metal::float2 _e14 = q_4;
            uint _e15 = o;
            float _e17 = value_noise(_e14, seed_1 + _e15);
            sum_5 = _e12 + (_e13 * _e17);
            metal::float2 _e20 = q_4;
            q_4 = _e20 * 2.0;
            float _e23 = weight;
            weight = _e23 * 0.5;
        }
    }
    float _e29 = sum_5;
    return _e29 / 0.9375;
}

float sprite_texture(
    uint tile_1,
    metal::float2 uv
) {
    float billow = 0.0;
    uint i_18 = 0u;
    metal::float2 at = {};
    float a_3 = {};
    metal::float2 c_10 = uv - metal::float2(0.5);
    float mask = metal::smoothstep(0.48, 0.36, metal::length(c_10));
    float _e16 = value_fbm((uv * 6.0) + metal::float2(static_cast<float>(tile_1) * 13.0), tile_1);
    if (tile_1 < 4u) {
        metal::float2 q_9 = c_10 * metal::float2(1.0, 3.2);
        float streak = 1.0 - metal::smoothstep(0.05, 0.45, metal::length(q_9));
        float _e40 = value_fbm((uv * metal::float2(3.0, 12.0)) + metal::float2(static_cast<float>(tile_1) * 5.0), tile_1 + 16u);
        float _e46 = saturate((_e40 * 1.6) - 0.3);
        return ((mask * streak) * _e46) * 0.8;
    }
    uint blobs = 5u + naga_mod(tile_1, 4u);
    uint2 loop_bound_20 = uint2(4294967295u);
    bool loop_init_16 = true;
    while(true) {
        if (metal::all(loop_bound_20 == uint2(0u))) { break; }
        loop_bound_20 -= uint2(loop_bound_20.y == 0u, 1u);
        if (!loop_init_16) {
            uint _e108 = i_18;
            i_18 = _e108 + 1u;
        }
        loop_init_16 = false;
        uint _e58 = i_18;
        if (_e58 < blobs) {
        } else {
            break;
        }
        {
            uint _e61 = i_18;
            float _e63 = atlas_hash(tile_1, 2u * _e61);
            uint _e65 = i_18;
            float _e69 = atlas_hash(tile_1, (2u * _e65) + 1u);
            metal::float2 centre_1 = metal::float2(_e63, _e69) - metal::float2(0.5);
            at = metal::float2(0.5) + (centre_1 * 0.34);
            if (tile_1 == 4u) {
                at.y = 0.5 + ((centre_1.y - 0.5) * 0.24);
            }
            uint _e91 = i_18;
            float _e93 = atlas_hash(tile_1, 100u + _e91);
            float r_18 = 0.14 + (0.1 * _e93);
            metal::float2 _e98 = at;
            float d_23 = metal::length(uv - _e98) / r_18;
            float _e102 = billow;
            float _e106 = saturate(1.0 - (d_23 * d_23));
            billow = metal::max(_e102, _e106);
        }
    }
    float _e111 = billow;
    float _e114 = saturate(_e111 * 1.5);
    a_3 = (mask * _e114) * (0.55 + (0.45 * _e16));
    if (tile_1 == 4u) {
        float _e124 = a_3;
        a_3 = _e124 * metal::smoothstep(0.62, 0.54, uv.y);
    }
    float _e130 = a_3;
    return _e130;
}

metal::float3 sprite_rel(
    metal::float2 xz,
    float alt_16,
    constant Frame& frame
) {
    float rp_6 = frame.atmosphere.x;
    metal::float4 _e8 = frame.camera_position;
    metal::float2 d_24 = xz - _e8.xz;
    float k_19 = (alt_16 * (alt_16 + (2.0 * rp_6))) - metal::dot(d_24, d_24);
    float y_3 = k_19 / (rp_6 + metal::sqrt(metal::max((rp_6 * rp_6) + k_19, 0.0)));
    return metal::float3(d_24.x, y_3, d_24.y);
}

SpriteCell sprite_cell(
    uint cell,
    constant Frame& frame
) {
    metal::int2 start_1 = {};
    uint k_10 = 3u;
    bool local_61 = {};
    bool local_62 = {};
    uint level_1 = naga_div(cell, 64u);
    metal::int2 local_66 = metal::int2(static_cast<int>(naga_mod(cell, 8u)), static_cast<int>(naga_mod(naga_div(cell, 8u), 8u)));
    metal::float4 _e15 = frame.camera_position;
    start_1 = as_type<metal::int2>(as_type<metal::uint2>(naga_f2i32(metal::floor(_e15.xz / metal::float2(12000.0)))) - as_type<metal::uint2>(metal::int2(4)));
    uint2 loop_bound_21 = uint2(4294967295u);
    bool loop_init_17 = true;
    while(true) {
        if (metal::all(loop_bound_21 == uint2(0u))) { break; }
        loop_bound_21 -= uint2(loop_bound_21.y == 0u, 1u);
        if (!loop_init_17) {
            uint _e35 = k_10;
            k_10 = _e35 - 1u;
        }
        loop_init_17 = false;
        uint _e27 = k_10;
        if (_e27 > level_1) {
        } else {
            break;
        }
        {
            metal::int2 _e29 = start_1;
            start_1 = as_type<metal::int2>(as_type<uint>(2) * as_type<metal::uint2>(as_type<metal::int2>(as_type<metal::uint2>(_e29) + as_type<metal::uint2>(metal::int2(2)))));
        }
    }
    if (level_1 > 0u) {
        local_61 = metal::all(local_66 >= metal::int2(2));
    } else {
        local_61 = false;
    }
    bool _e47 = local_61;
    if (_e47) {
        local_62 = metal::all(local_66 < metal::int2(6));
    } else {
        local_62 = false;
    }
    bool covered = local_62;
    metal::int2 _e56 = start_1;
    return SpriteCell {as_type<metal::int2>(as_type<metal::uint2>(_e56) + as_type<metal::uint2>(local_66)), SPRITE_CELL0_ * static_cast<float>(1u << level_1), covered};
}

SpriteCandidate sprite_candidate(
    SpriteCell c_4,
    uint level,
    uint s_2,
    thread Counters& counters_18,
    constant Frame& frame,
    metal::texture3d<float, metal::access::sample> shape_tex,
    metal::texture3d<float, metal::access::sample> detail_tex,
    metal::texture2d<float, metal::access::sample> weather_tex,
    metal::texture2d<float, metal::access::sample> curl_tex,
    metal::sampler noise_sampler
) {
    float density_3 = 0.0;
    uint _e10 = pcg(level);
    uint _e12 = pcg(as_type<uint>(c_4.index.y) ^ _e10);
    uint _e14 = pcg(as_type<uint>(c_4.index.x) ^ _e12);
    float _e17 = atlas_hash(_e14, 8u * s_2);
    float _e22 = atlas_hash(_e14, (8u * s_2) + 1u);
    float _e27 = atlas_hash(_e14, (8u * s_2) + 2u);
    float _e32 = atlas_hash(_e14, (8u * s_2) + 3u);
    metal::float4 u_1 = metal::float4(_e17, _e22, _e27, _e32);
    float _e38 = atlas_hash(_e14, (8u * s_2) + 4u);
    float _e43 = atlas_hash(_e14, (8u * s_2) + 5u);
    metal::float2 v_3 = metal::float2(_e38, _e43);
    metal::float2 xz_2 = (static_cast<metal::float2>(c_4.index) + u_1.xy) * c_4.size;
    Layer _e56 = cloud_layer(0u, frame);
    Weather _e57 = sample_weather(metal::float3(xz_2.x, 0.0, xz_2.y), _e56, frame, weather_tex, noise_sampler);
    float h_15 = 0.04 + (u_1.z * (metal::mix(0.3, 0.95, _e57.cloud_type) - 0.04));
    float _e71 = frame.atmosphere.y;
    float _e75 = frame.atmosphere.z;
    float _e79 = frame.atmosphere.y;
    float alt_18 = _e71 + (h_15 * (_e75 - _e79));
    if (!(c_4.covered)) {
        metal::float3 _e87 = sprite_rel(xz_2, alt_18, frame);
        float _e92 = cloud_density(metal::float3(xz_2.x, _e87.y, xz_2.y), alt_18, counters_18, frame, shape_tex, detail_tex, weather_tex, curl_tex, noise_sampler);
        density_3 = _e92;
    }
    float _e96 = density_3;
    return SpriteCandidate {xz_2, alt_18, h_15, u_1.w, v_3.x, v_3.y, _e96, _e57.precipitation};
}

metal::float3 sprite_sky_level(
    float h_10
) {
    float _e1 = saturate(h_10);
    float x_11 = _e1 * 4.0;
    if (x_11 < 1.0) {
        return metal::mix(SKY_LEVEL0_, SKY_LEVEL1_, x_11);
    }
    if (x_11 < 2.0) {
        return metal::mix(SKY_LEVEL1_, SKY_LEVEL2_, x_11 - 1.0);
    }
    if (x_11 < 3.0) {
        return metal::mix(SKY_LEVEL2_, SKY_LEVEL3_, x_11 - 2.0);
    }
    return metal::mix(SKY_LEVEL3_, SKY_LEVEL4_, x_11 - 3.0);
}

float sprite_sun_level(
    float cos_angle
) {
    if (cos_angle < 0.0) {
        return metal::mix(SPRITE_C_MIN, SPRITE_C_MED, cos_angle + 1.0);
    }
    return metal::mix(SPRITE_C_MED, SPRITE_C_MAX, cos_angle);
}

metal::float2 sprite_corner(
    uint k_11
) {
    bool local_63 = {};
    uint q_10 = (k_11 >= 3u) ? ((k_11 == 3u) ? 0u : (k_11 - 2u)) : k_11;
    if (!((q_10 == 1u))) {
        local_63 = q_10 == 2u;
    } else {
        local_63 = true;
    }
    bool _e18 = local_63;
    return metal::float2(_e18 ? 1.0 : -1.0, (q_10 >= 2u) ? 1.0 : -1.0);
}

metal::float3 sky_radiance(
    metal::float3 d_17,
    float alt_17,
    constant Frame& frame
) {
    metal::float4 _e4 = frame.sun_direction;
    metal::float3 sun_8 = _e4.xyz;
    metal::float4 _e8 = frame.sun_illuminance;
    metal::float3 e_1 = _e8.xyz;
    float _e15 = saturate((sun_8.y * 4.0) + 0.3);
    bool _e19 = hits_ground(metal::float3(0.0, alt_17, 0.0), alt_17, d_17, frame);
    if (_e19) {
        metal::float3 ground_albedo = metal::float3(0.035, 0.035, 0.03);
        return ground_albedo * (((e_1 * metal::max(sun_8.y, 0.0)) / metal::float3(3.1415927)) + ((0.05 * e_1) * _e15));
    }
    metal::float3 zenith = metal::float3(0.018, 0.04, 0.1);
    metal::float3 horizon_2 = metal::float3(0.07, 0.085, 0.11);
    float _e45 = saturate(d_17.y);
    metal::float3 gradient_1 = metal::mix(horizon_2, zenith, metal::sqrt(_e45));
    metal::float3 sunset = ((1.0 - (_e15 * 0.8)) * metal::pow(1.0 - _e45, 6.0)) * metal::float3(0.25, 0.1, 0.0);
    float _e64 = phase_hg(metal::dot(d_17, sun_8), 0.76);
    float glow = _e64 * 0.02;
    float _e73 = saturate((sun_8.y * 10.0) + 1.0);
    return e_1 * (((gradient_1 * _e15) + (sunset * _e73)) + metal::float3(glow * _e15));
}

metal::float3 sun_disk(
    metal::float3 d_18,
    constant Frame& frame
) {
    float cos_r = frame.sun_direction.w;
    metal::float4 _e7 = frame.sun_direction;
    if (metal::dot(d_18, _e7.xyz) < cos_r) {
        return metal::float3(0.0);
    }
    metal::float4 _e15 = frame.sun_illuminance;
    return _e15.xyz / metal::float3(6.2831855 * metal::max(1.0 - cos_r, 0.000001));
}

metal::float3 moon_disk(
    metal::float3 d_19,
    constant Frame& frame
) {
    bool local_64 = {};
    metal::float4 _e3 = frame.moon;
    metal::float3 m_4 = _e3.xyz;
    float c_11 = metal::dot(d_19, m_4);
    float _e9 = frame.moon.w;
    if (!((_e9 <= 0.0))) {
        local_64 = c_11 < MOON_COS_RADIUS;
    } else {
        local_64 = true;
    }
    bool _e18 = local_64;
    if (_e18) {
        return metal::float3(0.0);
    }
    metal::float3 offset = (d_19 - (m_4 * c_11)) / metal::float3(0.0045149517);
    float x2_1 = metal::min(metal::dot(offset, offset), 1.0);
    metal::float3 normal = offset - (m_4 * metal::sqrt(1.0 - x2_1));
    metal::float4 _e36 = frame.night;
    float lit_1 = metal::smoothstep(-0.02, 0.02, metal::dot(normal, _e36.xyz));
    float _e46 = frame.moon.w;
    return metal::float3((_e46 / 0.0000640407) * lit_1);
}

metal::float3 stars(
    metal::float3 d_20,
    constant Frame& frame
) {
    uint face = 0u;
    metal::float2 uv_1 = metal::float2(0.0);
    float major = 0.0;
    bool local_65 = {};
    metal::float3 star = metal::float3(0.0);
    float e0_ = frame.night.w;
    if (e0_ <= 0.0) {
        return metal::float3(0.0);
    }
    metal::float3 a_10 = metal::abs(d_20);
    if (a_10.x >= a_10.y) {
        local_65 = a_10.x >= a_10.z;
    } else {
        local_65 = false;
    }
    bool _e26 = local_65;
    if (_e26) {
        face = (d_20.x > 0.0) ? 0u : 1u;
        uv_1 = d_20.zy;
        major = a_10.x;
    } else {
        if (a_10.y >= a_10.z) {
            face = (d_20.y > 0.0) ? 2u : 3u;
            uv_1 = d_20.xz;
            major = a_10.y;
        } else {
            face = (d_20.z > 0.0) ? 4u : 5u;
            uv_1 = d_20.xy;
            major = a_10.z;
        }
    }
    metal::float2 _e54 = uv_1;
    float _e55 = major;
    metal::float2 st = metal::clamp(((_e54 / metal::float2(_e55)) * 0.5) + metal::float2(0.5), metal::float2(0.0), metal::float2(0.999999));
    metal::uint2 cell_2 = naga_f2u32(st * 96.0);
    uint _e71 = face;
    uint id_22 = (((_e71 * STAR_CELLS) + cell_2.y) * STAR_CELLS) + cell_2.x;
    uint _e85 = pcg(id_22 ^ 2654435769u);
    float h0_ = static_cast<float>(_e85 >> 8u) * 0.000000059604645;
    if (h0_ >= 0.15085077) {
        return metal::float3(0.0);
    }
    uint _e96 = pcg(id_22 ^ 2246822507u);
    float h1_ = static_cast<float>(_e96 >> 8u) * 0.000000059604645;
    uint _e104 = pcg(id_22 ^ 3266489909u);
    float h2_ = static_cast<float>(_e104 >> 8u) * 0.000000059604645;
    uint _e112 = pcg(id_22 ^ 668265263u);
    float h3_ = static_cast<float>(_e112 >> 8u) * 0.000000059604645;
    uint _e120 = pcg(id_22 ^ 374761393u);
    float h4_ = static_cast<float>(_e120 >> 8u) * 0.000000059604645;
    metal::float2 star_st = ((static_cast<metal::float2>(cell_2) + metal::float2(0.15)) + (0.7 * metal::float2(h1_, h2_))) / metal::float2(96.0);
    float _e142 = major;
    metal::float2 q_11 = ((star_st * 2.0) - metal::float2(1.0)) * _e142;
    uint _e147 = face;
    if (_e147 < 2u) {
        float _e150 = major;
        float _e152 = major;
        uint _e153 = face;
        star = metal::float3((_e153 == 0u) ? _e152 : -(_e150), q_11.y, q_11.x);
    } else {
        uint _e160 = face;
        if (_e160 < 4u) {
            float _e164 = major;
            float _e166 = major;
            uint _e167 = face;
            star = metal::float3(q_11.x, (_e167 == 2u) ? _e166 : -(_e164), q_11.y);
        } else {
            float _e175 = major;
            float _e177 = major;
            uint _e178 = face;
            star = metal::float3(q_11.x, q_11.y, (_e178 == 4u) ? _e177 : -(_e175));
        }
    }
    metal::float3 _e183 = star;
    star = metal::normalize(_e183);
    float magnitude = metal::max(STAR_FAINTEST + (metal::log(metal::max(h0_ / 0.15085077, 0.000001)) / 1.1052408), -1.5);
    float illuminance = e0_ * metal::pow(10.0, -0.4 * magnitude);
    float _e203 = frame.camera_position.w;
    uint _e209 = frame.counts.y;
    float pixel_angle = (2.0 * _e203) / static_cast<float>(_e209);
    metal::float3 _e212 = star;
    float dist_1 = metal::acos(metal::clamp(metal::dot(d_20, _e212), -1.0, 1.0)) / pixel_angle;
    float weight_1 = metal::exp((-(dist_1) * dist_1) / 0.5) / 1.5707964;
    metal::float3 tint = metal::mix(metal::float3(0.8, 0.9, 1.1), metal::float3(1.15, 0.95, 0.75), h3_ * h4_);
    return tint * ((illuminance * weight_1) / (pixel_angle * pixel_angle));
}

metal::float3 physical_composite(
    metal::uint2 pixel_8,
    metal::float3 view_4,
    metal::float4 cloud,
    constant Frame& frame,
    metal::texture2d<float, metal::access::sample> transmittance_lut_in,
    metal::texture2d<float, metal::access::sample> sky_view_in,
    metal::texture2d<float, metal::access::sample> aerial_in,
    metal::texture2d<float, metal::access::sample> cloud_shadow_in,
    metal::texture2d<float, metal::access::sample> depth_in
) {
    metal::float3 sky = {};
    metal::float3 space = {};
    metal::float3 radiance_3 = {};
    metal::float4 _e5 = frame.sun_illuminance;
    metal::float3 e_2 = _e5.xyz;
    metal::float3 _e7 = camera_air_origin(frame);
    float r_19 = _e7.y;
    metal::float3 _e9 = sky_view(view_4, frame, sky_view_in);
    sky = _e9 * e_2;
    bool _e13 = meets_ground(r_19, view_4.y, frame);
    if (_e13) {
        metal::float3 _e14 = sky;
        metal::float3 _e15 = ground_shadow_loss(view_4, r_19, frame, transmittance_lut_in, cloud_shadow_in);
        sky = metal::max(_e14 - (_e15 * e_2), metal::float3(0.0));
    } else {
        metal::float3 _e21 = moon_disk(view_4, frame);
        metal::float3 _e22 = stars(view_4, frame);
        space = _e21 + _e22;
        uint _e28 = frame.modes.w;
        if ((_e28 & FLAG_MOONLIT) == 0u) {
            metal::float3 _e33 = space;
            metal::float3 _e34 = sun_disk(view_4, frame);
            space = _e33 + _e34;
        }
        metal::float3 _e36 = sky;
        metal::float3 _e37 = space;
        metal::float3 _e39 = transmittance_to_top(r_19, view_4.y, frame, transmittance_lut_in);
        sky = _e36 + (_e37 * _e39);
    }
    metal::float3 _e42 = sky;
    radiance_3 = _e42 * cloud.w;
    if (cloud.w < 1.0) {
        metal::float4 _e51 = depth_in.read(metal::uint2(pixel_8), 0);
        metal::float4 _e53 = aerial(pixel_8, _e51.x, frame, aerial_in);
        metal::float3 _e54 = radiance_3;
        radiance_3 = _e54 + (((_e53.xyz * e_2) * (1.0 - cloud.w)) + (cloud.xyz * _e53.w));
    }
    metal::float3 _e66 = radiance_3;
    return _e66;
}

metal::float3 aces_fitted(
    metal::float3 x_5
) {
    return metal::clamp((x_5 * ((2.51 * x_5) + metal::float3(0.03))) / ((x_5 * ((2.43 * x_5) + metal::float3(0.59))) + metal::float3(0.14)), metal::float3(0.0), metal::float3(1.0));
}

void store_display(
    metal::uint2 pixel_9,
    metal::float3 radiance_4,
    constant Frame& frame,
    metal::texture2d<float, metal::access::write> image_out
) {
    float _e5 = frame.camera_right.w;
    metal::float3 exposed = radiance_4 * _e5;
    metal::float3 _e7 = aces_fitted(exposed);
    metal::float3 display = metal::pow(_e7, metal::float3(0.45454547));
    image_out.write(metal::float4(display, 1.0), metal::uint2(pixel_9));
    return;
}

struct transmittance_lutInput {
};
[[max_total_threads_per_threadgroup(64)]] kernel void transmittance_lut(
  metal::uint3 id [[thread_position_in_grid]]
, constant Frame& frame [[user(fake0)]]
, metal::texture2d<float, metal::access::write> transmittance_lut_out [[user(fake0)]]
) {
    metal::float3 sum = metal::float3(0.0);
    uint i = 0u;
    float w = {};
    bool local = {};
    if (metal::any(id.xy >= TRANSMITTANCE_SIZE)) {
        return;
    }
    metal::float2 _e11 = transmittance_r_mu(static_cast<metal::float2>(id.xy) / metal::float2(255.0, 63.0), frame);
    float _e14 = distance_to_top(_e11.x, _e11.y, frame);
    float dt_5 = _e14 / 128.0;
    uint2 loop_bound_22 = uint2(4294967295u);
    bool loop_init_18 = true;
    while(true) {
        if (metal::all(loop_bound_22 == uint2(0u))) { break; }
        loop_bound_22 -= uint2(loop_bound_22.y == 0u, 1u);
        if (!loop_init_18) {
            uint _e61 = i;
            i = _e61 + 1u;
        }
        loop_init_18 = false;
        uint _e22 = i;
        if (_e22 <= TRANSMITTANCE_STEPS) {
        } else {
            break;
        }
        {
            uint _e25 = i;
            w = ((_e25 & 1u) == 1u) ? 4.0 : 2.0;
            uint _e34 = i;
            if (!((_e34 == 0u))) {
                uint _e40 = i;
                local = _e40 == TRANSMITTANCE_STEPS;
            } else {
                local = true;
            }
            bool _e44 = local;
            if (_e44) {
                w = 1.0;
            }
            uint _e48 = i;
            float _e51 = radius_after(_e11.x, _e11.y, dt_5 * static_cast<float>(_e48));
            metal::float3 _e52 = sum;
            float _e53 = w;
            float _e54 = air_bottom(frame);
            AirSample _e56 = air_at(_e51 - _e54, frame);
            sum = _e52 + (_e53 * _e56.extinction);
        }
    }
    metal::float3 _e65 = sum;
    transmittance_lut_out.write(metal::float4(metal::exp(-(_e65) * (dt_5 / 3.0)), 1.0), metal::uint2(id.xy));
    return;
}


struct multiscatter_lutInput {
};
[[max_total_threads_per_threadgroup(64)]] kernel void multiscatter_lut(
  metal::uint3 id_1 [[thread_position_in_grid]]
, constant Frame& frame [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> transmittance_lut_in [[user(fake0)]]
, metal::texture2d<float, metal::access::write> multiscatter_lut_out [[user(fake0)]]
) {
    metal::float3 l2_ = metal::float3(0.0);
    metal::float3 f_ms = metal::float3(0.0);
    uint k = 0u;
    metal::float3 tau = {};
    uint i_1 = {};
    if (metal::any(id_1.xy >= MULTISCATTER_SIZE)) {
        return;
    }
    metal::float2 x_12 = static_cast<metal::float2>(id_1.xy) / metal::float2(31.0, 31.0);
    float mu_s_7 = (x_12.x * 2.0) - 1.0;
    float _e16 = air_bottom(frame);
    float _e18 = air_top(frame);
    float _e19 = air_bottom(frame);
    float r_20 = _e16 + (x_12.y * (_e18 - _e19));
    metal::float3 origin_7 = metal::float3(0.0, r_20, 0.0);
    metal::float3 sun_9 = metal::float3(metal::sqrt(metal::max(1.0 - (mu_s_7 * mu_s_7), 0.0)), mu_s_7, 0.0);
    uint2 loop_bound_23 = uint2(4294967295u);
    bool loop_init_19 = true;
    while(true) {
        if (metal::all(loop_bound_23 == uint2(0u))) { break; }
        loop_bound_23 -= uint2(loop_bound_23.y == 0u, 1u);
        if (!loop_init_19) {
            uint _e121 = k;
            k = _e121 + 1u;
        }
        loop_init_19 = false;
        uint _e43 = k;
        if (_e43 < MULTISCATTER_DIRECTIONS) {
        } else {
            break;
        }
        {
            uint _e46 = k;
            metal::float3 _e48 = fibonacci_direction(_e46, MULTISCATTER_DIRECTIONS);
            metal::float2 _e49 = air_ray_end(origin_7, _e48, frame);
            float dt_6 = _e49.x / 32.0;
            tau = metal::float3(0.0);
            i_1 = 0u;
            uint2 loop_bound_24 = uint2(4294967295u);
            bool loop_init_20 = true;
            while(true) {
                if (metal::all(loop_bound_24 == uint2(0u))) { break; }
                loop_bound_24 -= uint2(loop_bound_24.y == 0u, 1u);
                if (!loop_init_20) {
                    uint _e103 = i_1;
                    i_1 = _e103 + 1u;
                }
                loop_init_20 = false;
                uint _e58 = i_1;
                if (_e58 < MULTISCATTER_STEPS) {
                } else {
                    break;
                }
                {
                    uint _e61 = i_1;
                    metal::float3 p_24 = origin_7 + (_e48 * (dt_6 * (static_cast<float>(_e61) + 0.5)));
                    float rp_7 = metal::length(p_24);
                    float _e69 = air_bottom(frame);
                    AirSample _e71 = air_at(rp_7 - _e69, frame);
                    metal::float3 _e72 = tau;
                    metal::float3 t_10 = metal::exp(-((_e72 + ((0.5 * _e71.extinction) * dt_6))));
                    metal::float3 s_13 = _e71.rayleigh + metal::float3(_e71.mie);
                    metal::float3 _e84 = l2_;
                    metal::float3 _e90 = sun_transmittance(rp_7, metal::dot(p_24 / metal::float3(rp_7), sun_9), frame, transmittance_lut_in);
                    l2_ = _e84 + ((((t_10 * s_13) * 0.07957747) * _e90) * dt_6);
                    metal::float3 _e94 = f_ms;
                    f_ms = _e94 + ((t_10 * s_13) * dt_6);
                    metal::float3 _e98 = tau;
                    tau = _e98 + (_e71.extinction * dt_6);
                }
            }
            if (_e49.y > 0.5) {
                metal::float3 g_7 = origin_7 + (_e48 * _e49.x);
                metal::float3 _e111 = l2_;
                metal::float3 _e112 = tau;
                metal::float3 _e117 = ground_radiance_sun(metal::dot(metal::normalize(g_7), sun_9), frame, transmittance_lut_in);
                l2_ = _e111 + (metal::exp(-(_e112)) * _e117);
            }
        }
    }
    metal::float3 _e124 = l2_;
    metal::float3 _e128 = f_ms;
    metal::float3 psi = (_e124 * 0.015625) / metal::max(metal::float3(1.0) - (_e128 * 0.015625), metal::float3(0.000001));
    multiscatter_lut_out.write(metal::float4(psi, 1.0), metal::uint2(id_1.xy));
    return;
}


struct sky_view_lutInput {
};
[[max_total_threads_per_threadgroup(64)]] kernel void sky_view_lut(
  metal::uint3 id_2 [[thread_position_in_grid]]
, constant Frame& frame [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> transmittance_lut_in [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> multiscatter_lut_in [[user(fake0)]]
, metal::texture2d<float, metal::access::write> sky_view_out [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> ground_irradiance_in [[user(fake0)]]
) {
    if (metal::any(id_2.xy >= SKY_VIEW_SIZE)) {
        return;
    }
    metal::float2 x_13 = static_cast<metal::float2>(id_2.xy) / metal::float2(191.0, 107.0);
    metal::float3 _e11 = camera_air_origin(frame);
    float _e14 = horizon_elevation(_e11.y, frame);
    float _e15 = sky_view_elevation(x_13.y, _e14);
    float _e16 = sun_azimuth(frame);
    float phi_2 = _e16 + (x_13.x * PI);
    metal::float3 d_25 = metal::float3(metal::cos(_e15) * metal::cos(phi_2), metal::sin(_e15), metal::cos(_e15) * metal::sin(phi_2));
    metal::float3 _e31 = sky_along(_e11, d_25, frame, transmittance_lut_in, multiscatter_lut_in, ground_irradiance_in);
    sky_view_out.write(metal::float4(_e31, 1.0), metal::uint2(id_2.xy));
    return;
}


struct aerial_perspectiveInput {
};
[[max_total_threads_per_threadgroup(64)]] kernel void aerial_perspective(
  metal::uint3 id_3 [[thread_position_in_grid]]
, constant Frame& frame [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> transmittance_lut_in [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> multiscatter_lut_in [[user(fake0)]]
, metal::texture2d<float, metal::access::write> aerial_out [[user(fake0)]]
) {
    metal::float3 radiance = metal::float3(0.0);
    metal::float3 tau_1 = metal::float3(0.0);
    uint z = 0u;
    uint k_1 = {};
    if (metal::any(id_3.xy >= metal::uint2(32u))) {
        return;
    }
    metal::float3 _e7 = aerial_ray(id_3.xy, frame);
    metal::float3 _e8 = camera_air_origin(frame);
    metal::float2 _e9 = air_ray_end(_e8, _e7, frame);
    metal::float4 _e12 = frame.sun_direction;
    metal::float3 sun_10 = _e12.xyz;
    float cos_theta_9 = metal::dot(_e7, sun_10);
    float _e15 = phase_rayleigh(cos_theta_9);
    float _e19 = frame.air_mie.w;
    float _e20 = phase_cornette_shanks_air(cos_theta_9, _e19);
    uint2 loop_bound_25 = uint2(4294967295u);
    bool loop_init_21 = true;
    while(true) {
        if (metal::all(loop_bound_25 == uint2(0u))) { break; }
        loop_bound_25 -= uint2(loop_bound_25.y == 0u, 1u);
        if (!loop_init_21) {
            uint _e122 = z;
            z = _e122 + 1u;
        }
        loop_init_21 = false;
        uint _e30 = z;
        if (_e30 < AERIAL_SLICES) {
        } else {
            break;
        }
        {
            k_1 = 0u;
            uint2 loop_bound_26 = uint2(4294967295u);
            bool loop_init_22 = true;
            while(true) {
                if (metal::all(loop_bound_26 == uint2(0u))) { break; }
                loop_bound_26 -= uint2(loop_bound_26.y == 0u, 1u);
                if (!loop_init_22) {
                    uint _e99 = k_1;
                    k_1 = _e99 + 1u;
                }
                loop_init_22 = false;
                uint _e35 = k_1;
                if (_e35 < 4u) {
                } else {
                    break;
                }
                {
                    uint _e38 = z;
                    uint _e40 = k_1;
                    float t0_1 = AERIAL_SLICE_KM * (static_cast<float>(_e38) + (static_cast<float>(_e40) / 4.0));
                    float dt_7 = metal::max(metal::min(0.25, _e9.x - t0_1), 0.0);
                    metal::float3 p_25 = _e8 + (_e7 * (t0_1 + (0.5 * dt_7)));
                    float r_21 = metal::length(p_25);
                    float mu_s_8 = metal::dot(p_25 / metal::float3(r_21), sun_10);
                    float _e64 = air_bottom(frame);
                    AirSample _e66 = air_at(r_21 - _e64, frame);
                    metal::float3 _e67 = tau_1;
                    metal::float3 t_view_2 = metal::exp(-((_e67 + ((0.5 * _e66.extinction) * dt_7))));
                    metal::float3 _e75 = sun_transmittance(r_21, mu_s_8, frame, transmittance_lut_in);
                    metal::float3 _e83 = multiscatter(r_21, mu_s_8, frame, multiscatter_lut_in);
                    metal::float3 inscatter_1 = (_e75 * ((_e66.rayleigh * _e15) + metal::float3(_e66.mie * _e20))) + (_e83 * (_e66.rayleigh + metal::float3(_e66.mie)));
                    metal::float3 _e90 = radiance;
                    radiance = _e90 + ((t_view_2 * inscatter_1) * dt_7);
                    metal::float3 _e94 = tau_1;
                    tau_1 = _e94 + (_e66.extinction * dt_7);
                }
            }
            metal::float3 _e101 = tau_1;
            metal::float3 t_11 = metal::exp(-(_e101));
            uint _e105 = z;
            metal::float3 _e112 = radiance;
            aerial_out.write(metal::float4(_e112, ((t_11.x + t_11.y) + t_11.z) / 3.0), metal::uint2(metal::uint2((_e105 * AERIAL_SIDE) + id_3.x, id_3.y)));
        }
    }
    return;
}


struct sky_ambientInput {
};
[[max_total_threads_per_threadgroup(64)]] kernel void sky_ambient(
  metal::uint3 id_4 [[thread_position_in_grid]]
, constant Frame& frame [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> transmittance_lut_in [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> multiscatter_lut_in [[user(fake0)]]
, metal::texture2d<float, metal::access::write> sky_ambient_out [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> ground_irradiance_in [[user(fake0)]]
) {
    bool local_1 = {};
    metal::float3 sum_1 = metal::float3(0.0);
    float weights = 0.0;
    uint k_2 = {};
    if (!((id_4.x >= SKY_AMBIENT_SUNS))) {
        local_1 = id_4.y >= 2u;
    } else {
        local_1 = true;
    }
    bool _e11 = local_1;
    if (_e11) {
        return;
    }
    bool top_3 = id_4.y == 1u;
    float t_12 = ((static_cast<float>(id_4.x) / 63.0) * 2.0) - 1.0;
    float mu_s_9 = (metal::sign(t_12) * t_12) * t_12;
    metal::float3 sun_11 = metal::float3(metal::sqrt(metal::max(1.0 - (mu_s_9 * mu_s_9), 0.0)), mu_s_9, 0.0);
    float _e34 = air_bottom(frame);
    float _e38 = frame.atmosphere.y;
    metal::float3 origin_8 = metal::float3(0.0, _e34 + (_e38 * 0.001), 0.0);
    uint first_1 = top_3 ? 0u : 32u;
    k_2 = first_1;
    uint2 loop_bound_27 = uint2(4294967295u);
    bool loop_init_23 = true;
    while(true) {
        if (metal::all(loop_bound_27 == uint2(0u))) { break; }
        loop_bound_27 -= uint2(loop_bound_27.y == 0u, 1u);
        if (!loop_init_23) {
            uint _e77 = k_2;
            k_2 = _e77 + 1u;
        }
        loop_init_23 = false;
        uint _e54 = k_2;
        if (_e54 < (first_1 + 32u)) {
        } else {
            break;
        }
        {
            uint _e57 = k_2;
            metal::float3 _e59 = fibonacci_direction(_e57, AMBIENT_DIRECTIONS);
            metal::float2 _e60 = air_ray_end(origin_8, _e59, frame);
            Scattered _e63 = integrate_air(origin_8, _e59, _e60.x, AMBIENT_STEPS, sun_11, frame, transmittance_lut_in, multiscatter_lut_in);
            float w_8 = metal::abs(_e59.y);
            metal::float3 _e66 = sum_1;
            metal::float3 _e71 = with_ground(_e63, origin_8, _e59, _e60.x, sun_11, _e60.y > 0.5, frame, transmittance_lut_in, ground_irradiance_in);
            sum_1 = _e66 + (w_8 * _e71);
            float _e74 = weights;
            weights = _e74 + w_8;
        }
    }
    metal::float3 _e81 = sum_1;
    float _e82 = weights;
    sky_ambient_out.write(metal::float4(_e81 / metal::float3(_e82), 1.0), metal::uint2(id_4.xy));
    return;
}


struct ground_irradianceInput {
};
[[max_total_threads_per_threadgroup(64)]] kernel void ground_irradiance(
  metal::uint3 id_5 [[thread_position_in_grid]]
, constant Frame& frame [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> transmittance_lut_in [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> multiscatter_lut_in [[user(fake0)]]
, metal::texture2d<float, metal::access::write> ground_irradiance_out [[user(fake0)]]
) {
    bool local_2 = {};
    metal::float3 sum_2 = metal::float3(0.0);
    uint k_3 = 0u;
    if (!((id_5.x >= GROUND_IRRADIANCE_SIZE))) {
        local_2 = id_5.y >= 1u;
    } else {
        local_2 = true;
    }
    bool _e11 = local_2;
    if (_e11) {
        return;
    }
    float mu_s_10 = ((static_cast<float>(id_5.x) / 63.0) * 2.0) - 1.0;
    metal::float3 sun_12 = metal::float3(metal::sqrt(metal::max(1.0 - (mu_s_10 * mu_s_10), 0.0)), mu_s_10, 0.0);
    float _e28 = air_bottom(frame);
    metal::float3 origin_9 = metal::float3(0.0, _e28 + 0.001, 0.0);
    uint2 loop_bound_28 = uint2(4294967295u);
    bool loop_init_24 = true;
    while(true) {
        if (metal::all(loop_bound_28 == uint2(0u))) { break; }
        loop_bound_28 -= uint2(loop_bound_28.y == 0u, 1u);
        if (!loop_init_24) {
            uint _e58 = k_3;
            k_3 = _e58 + 1u;
        }
        loop_init_24 = false;
        uint _e39 = k_3;
        if (_e39 < GROUND_IRRADIANCE_DIRECTIONS) {
        } else {
            break;
        }
        {
            uint _e42 = k_3;
            metal::float3 _e44 = fibonacci_direction(_e42, GROUND_IRRADIANCE_DIRECTIONS);
            if (_e44.y <= 0.0) {
                continue;
            }
            metal::float2 _e48 = air_ray_end(origin_9, _e44, frame);
            metal::float3 _e49 = sum_2;
            Scattered _e52 = integrate_air(origin_9, _e44, _e48.x, AMBIENT_STEPS, sun_12, frame, transmittance_lut_in, multiscatter_lut_in);
            sum_2 = _e49 + (_e52.radiance * _e44.y);
        }
    }
    metal::float3 _e60 = sum_2;
    metal::float3 e_3 = _e60 * 0.09817477;
    ground_irradiance_out.write(metal::float4(e_3, 1.0), metal::uint2(id_5.xy));
    return;
}


struct cloud_shadowInput {
};
[[max_total_threads_per_threadgroup(64)]] kernel void cloud_shadow(
  metal::uint3 id_6 [[thread_position_in_grid]]
, constant Frame& frame [[user(fake0)]]
, metal::texture3d<float, metal::access::sample> shape_tex [[user(fake0)]]
, metal::texture3d<float, metal::access::sample> detail_tex [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> weather_tex [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> curl_tex [[user(fake0)]]
, metal::sampler noise_sampler [[user(fake0)]]
, metal::texture2d<float, metal::access::write> cloud_shadow_out [[user(fake0)]]
) {
    float tau_2 = 0.0;
    Counters counters = Counters {0u, 0u, 0u, 0u};
    uint i_2 = 0u;
    uint k_4 = {};
    if (metal::any(id_6.xy >= metal::uint2(128u))) {
        return;
    }
    metal::float3 _e7 = shadow_ground_point(id_6.xy, frame);
    metal::float4 _e10 = frame.sun_direction;
    metal::float3 sun_13 = _e10.xyz;
    float rp_8 = frame.atmosphere.x;
    metal::float3 up_2 = metal::normalize(metal::float3(_e7.x, _e7.y + rp_8, _e7.z));
    if (metal::dot(up_2, sun_13) > 0.0) {
        metal::float4 _e29 = frame.camera_position;
        metal::float2 cam_xz_3 = _e29.xz;
        uint2 loop_bound_29 = uint2(4294967295u);
        bool loop_init_25 = true;
        while(true) {
            if (metal::all(loop_bound_29 == uint2(0u))) { break; }
            loop_bound_29 -= uint2(loop_bound_29.y == 0u, 1u);
            if (!loop_init_25) {
                uint _e90 = i_2;
                i_2 = _e90 + 1u;
            }
            loop_init_25 = false;
            uint _e39 = i_2;
            uint _e40 = layer_count(frame);
            if (_e39 < _e40) {
            } else {
                break;
            }
            {
                uint _e42 = i_2;
                Layer _e43 = cloud_layer(_e42, frame);
                Roots _e46 = ray_shell_from(_e7, 0.0, sun_13, _e43.bottom, frame);
                float start_2 = metal::max(_e46.t1_, 0.0);
                Roots _e52 = ray_shell_from(_e7, 0.0, sun_13, _e43.top, frame);
                float end_2 = _e52.t1_;
                float dt_8 = (end_2 - start_2) / 16.0;
                if (!((dt_8 > 0.0))) {
                    continue;
                }
                k_4 = 0u;
                uint2 loop_bound_30 = uint2(4294967295u);
                bool loop_init_26 = true;
                while(true) {
                    if (metal::all(loop_bound_30 == uint2(0u))) { break; }
                    loop_bound_30 -= uint2(loop_bound_30.y == 0u, 1u);
                    if (!loop_init_26) {
                        uint _e87 = k_4;
                        k_4 = _e87 + 1u;
                    }
                    loop_init_26 = false;
                    uint _e62 = k_4;
                    if (_e62 < SHADOW_STEPS) {
                    } else {
                        break;
                    }
                    {
                        uint _e65 = k_4;
                        metal::float3 q_12 = _e7 + (sun_13 * (start_2 + ((static_cast<float>(_e65) + 0.5) * dt_8)));
                        metal::float3 p_26 = metal::float3(q_12.x + cam_xz_3.x, q_12.y, q_12.z + cam_xz_3.y);
                        float _e81 = tau_2;
                        float _e82 = altitude_of(q_12, frame);
                        float _e83 = layer_density(p_26, _e82, _e43, counters, frame, shape_tex, detail_tex, weather_tex, curl_tex, noise_sampler);
                        tau_2 = _e81 + (_e83 * dt_8);
                    }
                }
            }
        }
    }
    float _e95 = frame.extinction.x;
    float _e99 = frame.extinction.y;
    float sigma_t_8 = _e95 + _e99;
    float _e104 = tau_2;
    cloud_shadow_out.write(metal::float4(metal::exp(-(sigma_t_8) * _e104), 0.0, 0.0, 1.0), metal::uint2(id_6.xy));
    return;
}

metal::int2 naga_div(metal::int2 lhs, metal::int2 rhs) {
    return lhs / metal::select(rhs, 1, (lhs == (-2147483647 - 1) & rhs == -1) | (rhs == 0));
}

metal::int2 naga_mod(metal::int2 lhs, metal::int2 rhs) {
    metal::int2 divisor = metal::select(rhs, 1, (lhs == (-2147483647 - 1) & rhs == -1) | (rhs == 0));
    return lhs - (lhs / divisor) * divisor;
}


struct occupancyInput {
};
[[max_total_threads_per_threadgroup(64)]] kernel void occupancy(
  metal::uint3 id_7 [[thread_position_in_grid]]
, metal::texture2d<float, metal::access::sample> weather_tex [[user(fake0)]]
, metal::texture2d<float, metal::access::write> occupancy_out [[user(fake0)]]
) {
    float m = 0.0;
    int y = {};
    int x = {};
    if (metal::any(id_7.xy >= metal::uint2(64u))) {
        return;
    }
    metal::int2 size_8 = static_cast<metal::int2>(metal::uint2(weather_tex.get_width(), weather_tex.get_height()));
    metal::int2 lo_1 = as_type<metal::int2>(as_type<metal::uint2>(naga_div(as_type<metal::int2>(as_type<metal::uint2>(static_cast<metal::int2>(id_7.xy)) * as_type<metal::uint2>(size_8)), metal::int2(64))) - as_type<metal::uint2>(metal::int2(1)));
    metal::int2 hi = naga_div(as_type<metal::int2>(as_type<metal::uint2>(as_type<metal::int2>(as_type<metal::uint2>(static_cast<metal::int2>(id_7.xy)) + as_type<metal::uint2>(metal::int2(1)))) * as_type<metal::uint2>(size_8)), metal::int2(64));
    y = lo_1.y;
    uint2 loop_bound_31 = uint2(4294967295u);
    bool loop_init_27 = true;
    while(true) {
        if (metal::all(loop_bound_31 == uint2(0u))) { break; }
        loop_bound_31 -= uint2(loop_bound_31.y == 0u, 1u);
        if (!loop_init_27) {
            int _e54 = y;
            y = as_type<int>(as_type<uint>(_e54) + as_type<uint>(1));
        }
        loop_init_27 = false;
        int _e30 = y;
        if (_e30 <= hi.y) {
        } else {
            break;
        }
        {
            x = lo_1.x;
            uint2 loop_bound_32 = uint2(4294967295u);
            bool loop_init_28 = true;
            while(true) {
                if (metal::all(loop_bound_32 == uint2(0u))) { break; }
                loop_bound_32 -= uint2(loop_bound_32.y == 0u, 1u);
                if (!loop_init_28) {
                    int _e51 = x;
                    x = as_type<int>(as_type<uint>(_e51) + as_type<uint>(1));
                }
                loop_init_28 = false;
                int _e35 = x;
                if (_e35 <= hi.x) {
                } else {
                    break;
                }
                {
                    int _e38 = x;
                    int _e39 = y;
                    metal::int2 t_13 = naga_mod(as_type<metal::int2>(as_type<metal::uint2>(naga_mod(metal::int2(_e38, _e39), size_8)) + as_type<metal::uint2>(size_8)), size_8);
                    float _e44 = m;
                    metal::float4 _e47 = weather_tex.read(metal::uint2(t_13), 0);
                    m = metal::max(_e44, _e47.x);
                }
            }
        }
    }
    float _e58 = m;
    occupancy_out.write(metal::float4(_e58, 0.0, 0.0, 0.0), metal::uint2(id_7.xy));
    return;
}


struct marchInput {
};
[[max_total_threads_per_threadgroup(64)]] kernel void march(
  metal::uint3 id_8 [[thread_position_in_grid]]
, constant Frame& frame [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> transmittance_lut_in [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> sky_ambient_in [[user(fake0)]]
, metal::texture3d<float, metal::access::sample> shape_tex [[user(fake0)]]
, metal::texture3d<float, metal::access::sample> detail_tex [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> weather_tex [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> curl_tex [[user(fake0)]]
, metal::sampler noise_sampler [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> occupancy_in [[user(fake0)]]
, metal::texture2d<float, metal::access::write> cloud_out [[user(fake0)]]
, metal::texture2d<float, metal::access::write> depth_out [[user(fake0)]]
, device Stats& stats [[user(fake0)]]
) {
    metal::uint4 _e4 = frame.counts;
    if (metal::any(id_8.xy >= _e4.xy)) {
        return;
    }
    MarchResult _e9 = march_pixel(id_8.xy, frame, transmittance_lut_in, sky_ambient_in, shape_tex, detail_tex, weather_tex, curl_tex, noise_sampler, occupancy_in, stats);
    cloud_out.write(metal::float4(_e9.radiance, _e9.transmittance), metal::uint2(id_8.xy));
    depth_out.write(metal::float4(_e9.depth, 0.0, 0.0, 0.0), metal::uint2(id_8.xy));
    return;
}


struct march_sparseInput {
};
[[max_total_threads_per_threadgroup(64)]] kernel void march_sparse(
  metal::uint3 id_9 [[thread_position_in_grid]]
, constant Frame& frame [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> transmittance_lut_in [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> sky_ambient_in [[user(fake0)]]
, metal::texture3d<float, metal::access::sample> shape_tex [[user(fake0)]]
, metal::texture3d<float, metal::access::sample> detail_tex [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> weather_tex [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> curl_tex [[user(fake0)]]
, metal::sampler noise_sampler [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> occupancy_in [[user(fake0)]]
, metal::texture2d<float, metal::access::write> cloud_out [[user(fake0)]]
, metal::texture2d<float, metal::access::write> depth_out [[user(fake0)]]
, device Stats& stats [[user(fake0)]]
) {
    MarchResult r = MarchResult {metal::float3(0.0), 1.0, 0.0};
    bool _e2 = in_blocks(id_9.xy, frame);
    if (!(_e2)) {
        return;
    }
    metal::uint2 _e5 = sparse_pixel(id_9.xy, frame);
    metal::uint4 _e14 = frame.counts;
    if (metal::all(_e5 < _e14.xy)) {
        MarchResult _e18 = march_pixel(_e5, frame, transmittance_lut_in, sky_ambient_in, shape_tex, detail_tex, weather_tex, curl_tex, noise_sampler, occupancy_in, stats);
        r = _e18;
    }
    MarchResult _e20 = r;
    store_sparse(id_9.xy, _e20, cloud_out, depth_out);
    return;
}


struct march_sparse_checkerboardInput {
};
[[max_total_threads_per_threadgroup(64)]] kernel void march_sparse_checkerboard(
  metal::uint3 id_10 [[thread_position_in_grid]]
, constant Frame& frame [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> transmittance_lut_in [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> sky_ambient_in [[user(fake0)]]
, metal::texture3d<float, metal::access::sample> shape_tex [[user(fake0)]]
, metal::texture3d<float, metal::access::sample> detail_tex [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> weather_tex [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> curl_tex [[user(fake0)]]
, metal::sampler noise_sampler [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> occupancy_in [[user(fake0)]]
, metal::texture2d<float, metal::access::write> cloud_out [[user(fake0)]]
, metal::texture2d<float, metal::access::write> depth_out [[user(fake0)]]
, device Stats& stats [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> history_in [[user(fake0)]]
) {
    MarchResult r_1 = MarchResult {metal::float3(0.0), 1.0, 0.0};
    bool skip = {};
    bool local_3 = {};
    bool local_4 = {};
    bool local_5 = {};
    bool _e2 = in_blocks(id_10.xy, frame);
    if (!(_e2)) {
        return;
    }
    metal::uint2 _e5 = sparse_pixel(id_10.xy, frame);
    metal::uint4 _e14 = frame.counts;
    skip = metal::any(_e5 >= _e14.xy);
    bool _e19 = skip;
    if (!(_e19)) {
        uint _e26 = frame.temporal.y;
        local_3 = _e26 != 0u;
    } else {
        local_3 = false;
    }
    bool _e30 = local_3;
    if (_e30) {
        uint k_20 = frame.temporal.x;
        uint _e38 = frame.misc.y;
        uint turn = naga_div(_e38, k_20 * k_20);
        metal::float2 _e42 = reproject(_e5, 0.0, frame);
        if ((((id_10.x + id_10.y) + turn) & 1u) == 0u) {
            bool _e53 = on_screen(_e42, frame);
            local_4 = _e53;
        } else {
            local_4 = false;
        }
        bool _e55 = local_4;
        if (_e55) {
            metal::float4 _e58 = history_nearest(_e42, frame, history_in);
            local_5 = _e58.w >= 1.0;
        } else {
            local_5 = false;
        }
        bool _e63 = local_5;
        if (_e63) {
            skip = true;
        }
    }
    bool _e65 = skip;
    if (!(_e65)) {
        MarchResult _e67 = march_pixel(_e5, frame, transmittance_lut_in, sky_ambient_in, shape_tex, detail_tex, weather_tex, curl_tex, noise_sampler, occupancy_in, stats);
        r_1 = _e67;
    }
    MarchResult _e69 = r_1;
    store_sparse(id_10.xy, _e69, cloud_out, depth_out);
    return;
}


struct resolveInput {
};
[[max_total_threads_per_threadgroup(64)]] kernel void resolve(
  metal::uint3 id_11 [[thread_position_in_grid]]
, constant Frame& frame [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> transmittance_lut_in [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> sky_ambient_in [[user(fake0)]]
, metal::texture3d<float, metal::access::sample> shape_tex [[user(fake0)]]
, metal::texture3d<float, metal::access::sample> detail_tex [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> weather_tex [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> curl_tex [[user(fake0)]]
, metal::sampler noise_sampler [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> occupancy_in [[user(fake0)]]
, metal::texture2d<float, metal::access::write> cloud_out [[user(fake0)]]
, metal::texture2d<float, metal::access::write> depth_out [[user(fake0)]]
, device Stats& stats [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> history_in [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> meta_in [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> sparse_in [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> sparse_depth_in [[user(fake0)]]
, metal::texture2d<float, metal::access::write> history_out [[user(fake0)]]
, metal::texture2d<float, metal::access::write> meta_out [[user(fake0)]]
) {
    float depth = {};
    bool local_6 = {};
    bool valid = {};
    metal::float4 history = metal::float4(0.0, 0.0, 0.0, 1.0);
    metal::float4 past = metal::float4(0.0);
    bool local_7 = {};
    bool local_8 = {};
    bool local_9 = {};
    metal::float4 result = {};
    float samples = {};
    float out_depth = {};
    bool local_10 = {};
    metal::uint4 _e4 = frame.counts;
    if (metal::any(id_11.xy >= _e4.xy)) {
        return;
    }
    metal::uint2 pixel_10 = id_11.xy;
    uint k_21 = frame.temporal.x;
    metal::uint2 block = naga_div(pixel_10, metal::uint2(k_21));
    uint _e19 = frame.misc.y;
    metal::uint2 _e20 = block_offset(_e19, k_21);
    bool marched_1 = metal::all(pixel_10 == ((block * k_21) + _e20));
    metal::float4 current = sparse_in.read(metal::uint2(block), 0);
    metal::float4 _e29 = sparse_depth_in.read(metal::uint2(block), 0);
    float current_depth = _e29.x;
    depth = current_depth;
    float _e32 = depth;
    if (_e32 <= 0.0) {
        float _e38 = frame.camera_position.y;
        metal::float3 _e39 = view_ray(pixel_10, frame);
        Interval _e40 = nearest_layer_interval(_e38, _e39, frame);
        if (_e40.kind == RAY_MARCH) {
            depth = _e40.start + (0.5 * _e40.length);
        }
    }
    float _e49 = depth;
    metal::float2 _e50 = reproject(pixel_10, _e49, frame);
    uint _e54 = frame.temporal.y;
    if (_e54 != 0u) {
        bool _e59 = on_screen(_e50, frame);
        local_6 = _e59;
    } else {
        local_6 = false;
    }
    bool _e61 = local_6;
    valid = _e61;
    bool moving = metal::any(_e50 != static_cast<metal::float2>(pixel_10));
    bool _e75 = valid;
    if (_e75) {
        metal::float4 _e76 = history_at(_e50, frame, history_in);
        history = _e76;
        metal::float4 _e77 = meta_at(_e50, frame, meta_in);
        past = _e77;
        if (moving) {
            local_7 = current_depth > 0.0;
        } else {
            local_7 = false;
        }
        bool _e83 = local_7;
        if (_e83) {
            float _e87 = past.x;
            local_8 = _e87 > 0.0;
        } else {
            local_8 = false;
        }
        bool _e91 = local_8;
        if (_e91) {
            metal::float4 _e94 = frame.camera_position;
            metal::float3 _e96 = view_ray(pixel_10, frame);
            metal::float4 _e101 = frame.previous_position;
            float expected = metal::distance(_e94.xyz + (_e96 * current_depth), _e101.xyz);
            float _e105 = past.x;
            valid = metal::abs(_e105 - expected) <= (DISOCCLUSION_DEPTH * expected);
        }
    }
    bool _e111 = valid;
    if (_e111) {
        local_9 = moving;
    } else {
        local_9 = false;
    }
    bool _e115 = local_9;
    if (_e115) {
        metal::uint4 _e118 = frame.counts;
        metal::int2 blocks = static_cast<metal::int2>(naga_div((_e118.xy + metal::uint2(k_21)) - metal::uint2(1u), metal::uint2(k_21)));
        metal::int2 b_11 = static_cast<metal::int2>(block);
        int x0_1 = metal::max(as_type<int>(as_type<uint>(b_11.x) - as_type<uint>(1)), 0);
        int x2_2 = metal::min(as_type<int>(as_type<uint>(b_11.x) + as_type<uint>(1)), as_type<int>(as_type<uint>(blocks.x) - as_type<uint>(1)));
        int y0_ = metal::max(as_type<int>(as_type<uint>(b_11.y) - as_type<uint>(1)), 0);
        int y2_ = metal::min(as_type<int>(as_type<uint>(b_11.y) + as_type<uint>(1)), as_type<int>(as_type<uint>(blocks.y) - as_type<uint>(1)));
        metal::float4 s00_ = sparse_in.read(metal::uint2(metal::int2(x0_1, y0_)), 0);
        metal::float4 s10_ = sparse_in.read(metal::uint2(metal::int2(b_11.x, y0_)), 0);
        metal::float4 s20_ = sparse_in.read(metal::uint2(metal::int2(x2_2, y0_)), 0);
        metal::float4 s01_ = sparse_in.read(metal::uint2(metal::int2(x0_1, b_11.y)), 0);
        metal::float4 s11_ = sparse_in.read(metal::uint2(b_11), 0);
        metal::float4 s21_ = sparse_in.read(metal::uint2(metal::int2(x2_2, b_11.y)), 0);
        metal::float4 s02_ = sparse_in.read(metal::uint2(metal::int2(x0_1, y2_)), 0);
        metal::float4 s12_ = sparse_in.read(metal::uint2(metal::int2(b_11.x, y2_)), 0);
        metal::float4 s22_ = sparse_in.read(metal::uint2(metal::int2(x2_2, y2_)), 0);
        metal::float4 lo_2 = metal::min(metal::min(metal::min(s00_, s10_), metal::min(s20_, s01_)), metal::min(metal::min(s11_, s21_), metal::min(metal::min(s02_, s12_), s22_)));
        metal::float4 hi_1 = metal::max(metal::max(metal::max(s00_, s10_), metal::max(s20_, s01_)), metal::max(metal::max(s11_, s21_), metal::max(metal::max(s02_, s12_), s22_)));
        metal::float4 _e208 = history;
        history = metal::clamp(_e208, lo_2, hi_1);
    }
    if (marched_1) {
        bool _e213 = valid;
        if (_e213) {
            float _e215 = past.y;
            samples = metal::min(_e215 + 1.0, moving ? HISTORY_SAMPLES_MOVING : HISTORY_SAMPLES);
            metal::float4 _e222 = history;
            float _e223 = samples;
            result = metal::mix(_e222, current, 1.0 / _e223);
        } else {
            samples = 1.0;
            result = current;
        }
        float _e229 = past.x;
        if (!((current_depth > 0.0))) {
            bool _e235 = valid;
            local_10 = !(_e235);
        } else {
            local_10 = true;
        }
        bool _e238 = local_10;
        out_depth = _e238 ? current_depth : _e229;
    } else {
        bool _e240 = valid;
        if (_e240) {
            float _e242 = past.y;
            samples = moving ? 0.0 : _e242;
            metal::float4 _e245 = history;
            result = _e245;
            float _e247 = past.x;
            out_depth = _e247;
        } else {
            MarchResult _e248 = march_pixel(pixel_10, frame, transmittance_lut_in, sky_ambient_in, shape_tex, detail_tex, weather_tex, curl_tex, noise_sampler, occupancy_in, stats);
            samples = 1.0;
            result = metal::float4(_e248.radiance, _e248.transmittance);
            out_depth = _e248.depth;
        }
    }
    metal::float4 _e255 = result;
    history_out.write(_e255, metal::uint2(pixel_10));
    float _e257 = out_depth;
    float _e258 = samples;
    meta_out.write(metal::float4(_e257, _e258, 0.0, 0.0), metal::uint2(pixel_10));
    metal::float4 _e263 = result;
    cloud_out.write(_e263, metal::uint2(pixel_10));
    float _e265 = out_depth;
    depth_out.write(metal::float4(_e265, 0.0, 0.0, 0.0), metal::uint2(pixel_10));
    return;
}


struct pathtraceInput {
};
[[max_total_threads_per_threadgroup(32)]] kernel void pathtrace(
  metal::uint3 group [[threadgroup_position_in_grid]]
, uint lane [[thread_index_in_threadgroup]]
, constant Frame& frame [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> transmittance_lut_in [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> multiscatter_lut_in [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> sky_ambient_in [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> ground_irradiance_in [[user(fake0)]]
, metal::texture3d<float, metal::access::sample> shape_tex [[user(fake0)]]
, metal::texture3d<float, metal::access::sample> detail_tex [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> weather_tex [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> curl_tex [[user(fake0)]]
, metal::sampler noise_sampler [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> occupancy_in [[user(fake0)]]
, metal::texture2d<float, metal::access::write> cloud_out [[user(fake0)]]
, metal::texture2d<float, metal::access::write> depth_out [[user(fake0)]]
, device Stats& stats [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> history_in [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> meta_in [[user(fake0)]]
, metal::texture2d<float, metal::access::write> history_out [[user(fake0)]]
, metal::texture2d<float, metal::access::write> meta_out [[user(fake0)]]
, threadgroup type_21& lane_sums
, threadgroup type_21& lane_moments
) {
    if (lane == 0u) {
        lane_sums = {};
        lane_moments = {};
    }
    metal::threadgroup_barrier(metal::mem_flags::mem_threadgroup);
    Counters counters_1 = Counters {0u, 0u, 0u, 0u};
    uint rng = {};
    metal::float4 sum_3 = metal::float4(0.0);
    metal::float4 sum_moments = metal::float4(0.0);
    uint i_3 = 0u;
    metal::float4 mean = metal::float4(0.0);
    metal::float4 moments = metal::float4(0.0);
    bool local_11 = {};
    metal::uint4 _e5 = frame.counts;
    if (metal::any(group.xy >= _e5.xy)) {
        return;
    }
    metal::uint2 pixel_11 = group.xy;
    metal::float3 _e10 = view_ray(pixel_11, frame);
    float _e14 = frame.camera_position.y;
    Interval _e15 = cloud_interval(_e14, _e10, frame);
    if (lane == 0u) {
        count(STAT_PIXELS, 1u, stats);
        count(STAT_MARCHED, static_cast<uint>(_e15.kind == RAY_MARCH), stats);
        count(STAT_EXIT_MISSED, static_cast<uint>(_e15.kind == RAY_MISSES_LAYER), stats);
        count(STAT_EXIT_GROUND, static_cast<uint>(_e15.kind == RAY_HITS_GROUND), stats);
    }
    uint _e44 = frame.misc.y;
    uint _e48 = rng_seed(pixel_11, (_e44 * PATHS_PER_FRAME) + lane);
    rng = _e48;
    PathResult _e50 = trace_path(_e10, _e15, rng, counters_1, frame, transmittance_lut_in, multiscatter_lut_in, sky_ambient_in, ground_irradiance_in, shape_tex, detail_tex, weather_tex, curl_tex, noise_sampler, occupancy_in);
    float _e52 = luminance(_e50.radiance);
    bool hit = _e50.depth >= 0.0;
    lane_sums.inner[lane] = metal::float4(_e50.radiance, _e50.transmittance);
    lane_moments.inner[lane] = metal::float4(_e52 * _e52, hit ? _e50.depth : 0.0, hit ? 1.0 : 0.0, 0.0);
    metal::threadgroup_barrier(metal::mem_flags::mem_threadgroup);
    if (lane == 0u) {
        uint2 loop_bound_33 = uint2(4294967295u);
        bool loop_init_29 = true;
        while(true) {
            if (metal::all(loop_bound_33 == uint2(0u))) { break; }
            loop_bound_33 -= uint2(loop_bound_33.y == 0u, 1u);
            if (!loop_init_29) {
                uint _e98 = i_3;
                i_3 = _e98 + 1u;
            }
            loop_init_29 = false;
            uint _e82 = i_3;
            if (_e82 < PATHS_PER_FRAME) {
            } else {
                break;
            }
            {
                metal::float4 _e85 = sum_3;
                uint _e87 = i_3;
                metal::float4 _e89 = lane_sums.inner[_e87];
                sum_3 = _e85 + _e89;
                metal::float4 _e91 = sum_moments;
                uint _e93 = i_3;
                metal::float4 _e95 = lane_moments.inner[_e93];
                sum_moments = _e91 + _e95;
            }
        }
        uint _e109 = frame.temporal.y;
        if (_e109 == 1u) {
            bool _e114 = camera_still(frame);
            local_11 = _e114;
        } else {
            local_11 = false;
        }
        bool _e116 = local_11;
        if (_e116) {
            metal::float4 _e119 = history_in.read(metal::uint2(pixel_11), 0);
            mean = _e119;
            metal::float4 _e122 = meta_in.read(metal::uint2(pixel_11), 0);
            moments = _e122;
        }
        float _e125 = moments.y;
        float n_4 = _e125 + 32.0;
        metal::float4 _e127 = mean;
        metal::float4 _e128 = sum_3;
        metal::float4 _e129 = mean;
        mean = _e127 + ((_e128 - (32.0 * _e129)) / metal::float4(n_4));
        float _e136 = moments.z;
        float _e138 = sum_moments.x;
        float _e140 = moments.z;
        moments.z = _e136 + ((_e138 - (32.0 * _e140)) / n_4);
        float hits = sum_moments.z;
        if (hits > 0.0) {
            float _e150 = moments.w;
            moments.w = _e150 + hits;
            float _e153 = moments.x;
            float _e155 = sum_moments.y;
            float _e157 = moments.x;
            float _e161 = moments.w;
            moments.x = _e153 + ((_e155 - (hits * _e157)) / _e161);
        }
        moments.y = n_4;
        metal::float4 _e166 = mean;
        history_out.write(_e166, metal::uint2(pixel_11));
        metal::float4 _e168 = moments;
        meta_out.write(_e168, metal::uint2(pixel_11));
        metal::float4 _e170 = mean;
        cloud_out.write(_e170, metal::uint2(pixel_11));
        float _e173 = moments.x;
        depth_out.write(metal::float4(_e173, 0.0, 0.0, 0.0), metal::uint2(pixel_11));
    }
    uint _e180 = counters_1.view_steps;
    count(STAT_VIEW_STEPS, _e180, stats);
    uint _e183 = counters_1.density;
    count(STAT_DENSITY, _e183, stats);
    uint _e186 = counters_1.detail;
    count(STAT_DETAIL, _e186, stats);
    uint _e189 = counters_1.light;
    count(STAT_LIGHT, _e189, stats);
    return;
}


struct march_basicInput {
};
[[max_total_threads_per_threadgroup(64)]] kernel void march_basic(
  metal::uint3 id_12 [[thread_position_in_grid]]
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
    metal::uint4 _e4 = frame.counts;
    if (metal::any(id_12.xy >= _e4.xy)) {
        return;
    }
    MarchResult _e9 = basic_pixel(id_12.xy, frame, shape_tex, detail_tex, weather_tex, curl_tex, noise_sampler, stats);
    cloud_out.write(metal::float4(_e9.radiance, _e9.transmittance), metal::uint2(id_12.xy));
    depth_out.write(metal::float4(_e9.depth, 0.0, 0.0, 0.0), metal::uint2(id_12.xy));
    return;
}

metal::uint2 naga_mod(metal::uint2 lhs, metal::uint2 rhs) {
    return lhs % metal::select(rhs, 1u, rhs == 0u);
}


struct sprite_atlasInput {
};
[[max_total_threads_per_threadgroup(64)]] kernel void sprite_atlas(
  metal::uint3 id_13 [[thread_position_in_grid]]
, metal::texture2d<float, metal::access::write> sprite_atlas_out [[user(fake0)]]
) {
    uint tile_2 = (naga_div(id_13.y, ATLAS_TILE) * 4u) + naga_div(id_13.x, ATLAS_TILE);
    metal::float2 uv_5 = (static_cast<metal::float2>(naga_mod(id_13.xy, metal::uint2(64u))) + metal::float2(0.5)) / metal::float2(64.0);
    float _e21 = sprite_texture(tile_2, uv_5);
    sprite_atlas_out.write(metal::float4(_e21, _e21, _e21, _e21), metal::uint2(id_13.xy));
    return;
}


struct sprite_buildInput {
};
[[max_total_threads_per_threadgroup(64)]] kernel void sprite_build(
  metal::uint3 id_14 [[thread_position_in_grid]]
, constant Frame& frame [[user(fake0)]]
, metal::texture3d<float, metal::access::sample> shape_tex [[user(fake0)]]
, metal::texture3d<float, metal::access::sample> detail_tex [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> weather_tex [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> curl_tex [[user(fake0)]]
, metal::sampler noise_sampler [[user(fake0)]]
, device Stats& stats [[user(fake0)]]
, metal::texture2d<float, metal::access::write> sprites_out [[user(fake0)]]
) {
    Counters counters_2 = Counters {0u, 0u, 0u, 0u};
    metal::float4 sum_4 = metal::float4(0.0);
    SpriteCandidate me = {};
    uint i_4 = 0u;
    metal::float3 centre = {};
    uint tile = {};
    float rotation = {};
    bool local_12 = {};
    float key = 0.0;
    uint slot = id_14.x;
    uint cell_index = naga_div(slot, SPRITES_PER_CELL);
    uint level_2 = naga_div(cell_index, 64u);
    SpriteCell _e6 = sprite_cell(cell_index, frame);
    uint own = naga_mod(slot, SPRITES_PER_CELL);
    SpriteCandidate _e18 = sprite_candidate(_e6, level_2, own, counters_2, frame, shape_tex, detail_tex, weather_tex, curl_tex, noise_sampler);
    me = _e18;
    uint2 loop_bound_34 = uint2(4294967295u);
    bool loop_init_30 = true;
    while(true) {
        if (metal::all(loop_bound_34 == uint2(0u))) { break; }
        loop_bound_34 -= uint2(loop_bound_34.y == 0u, 1u);
        if (!loop_init_30) {
            uint _e38 = i_4;
            i_4 = _e38 + 1u;
        }
        loop_init_30 = false;
        uint _e22 = i_4;
        if (_e22 < SPRITES_PER_CELL) {
        } else {
            break;
        }
        {
            uint _e25 = i_4;
            SpriteCandidate _e26 = sprite_candidate(_e6, level_2, _e25, counters_2, frame, shape_tex, detail_tex, weather_tex, curl_tex, noise_sampler);
            metal::float4 _e27 = sum_4;
            sum_4 = _e27 + (metal::float4(_e26.xz.x, _e26.alt, _e26.xz.y, 1.0) * _e26.density);
        }
    }
    uint _e43 = counters_2.density;
    count(STAT_DENSITY, _e43, stats);
    uint _e46 = counters_2.detail;
    count(STAT_DETAIL, _e46, stats);
    float bottom_3 = frame.atmosphere.y;
    float _e54 = frame.atmosphere.z;
    float thickness_1 = _e54 - bottom_3;
    metal::float2 middle = (static_cast<metal::float2>(_e6.index) + metal::float2(0.5)) * _e6.size;
    centre = metal::float3(middle.x, bottom_3 + (0.4 * thickness_1), middle.y);
    float _e71 = sum_4.w;
    if (_e71 > 0.0) {
        metal::float4 _e74 = sum_4;
        float _e77 = sum_4.w;
        centre = _e74.xyz / metal::float3(_e77);
    }
    metal::float2 _e81 = me.xz;
    metal::float3 _e82 = centre;
    bool inner = metal::length(_e81 - _e82.xz) < (0.25 * _e6.size);
    float _e91 = me.density;
    float _e96 = me.density;
    float morph = inner ? metal::smoothstep(0.0, 0.06, _e96) : metal::smoothstep(0.03, 0.15, _e91);
    float alpha = SPRITE_ALPHA * morph;
    float _e107 = me.size_hash;
    float half_width = (0.5 * _e6.size) * (0.7 + (0.6 * _e107));
    float half_height = metal::min(half_width, 0.35 * thickness_1);
    float _e118 = me.texture_hash;
    tile = 5u + metal::min(naga_f2u32(_e118 * 11.0), 10u);
    float _e127 = me.rotation_hash;
    rotation = (_e127 * 2.0) * PI;
    float _e134 = me.h;
    if (_e134 < 0.12) {
        tile = 4u;
        float _e139 = me.rotation_hash;
        rotation = (_e139 - 0.5) * 0.17453294;
    } else {
        if (!(inner)) {
            float _e148 = me.density;
            local_12 = _e148 < 0.1;
        } else {
            local_12 = false;
        }
        bool _e152 = local_12;
        if (_e152) {
            float _e154 = me.texture_hash;
            tile = metal::min(naga_f2u32(_e154 * 4.0), 3u);
        }
    }
    if (alpha > 0.0) {
        metal::float2 _e165 = me.xz;
        float _e167 = me.alt;
        metal::float3 _e168 = sprite_rel(_e165, _e167, frame);
        float _e172 = frame.camera_position.y;
        metal::float3 rel_15 = _e168 - metal::float3(0.0, _e172, 0.0);
        float _e180 = saturate(metal::length(rel_15) / SPRITE_MAX_DISTANCE);
        key = 1048576.0 - metal::floor(_e180 * 1048575.0);
    }
    float _e191 = me.xz.x;
    float _e193 = me.alt;
    float _e196 = me.xz.y;
    sprites_out.write(metal::float4(_e191, _e193, _e196, half_width), metal::uint2(metal::uint2(slot, 0u)));
    metal::float3 _e201 = centre;
    sprites_out.write(metal::float4(_e201, alpha), metal::uint2(metal::uint2(slot, 1u)));
    float _e204 = me.precipitation;
    float colour_level = 1.0 / (1.0 + (6.0 * metal::max(_e204, 0.0)));
    uint _e216 = tile;
    float _e218 = rotation;
    sprites_out.write(metal::float4(static_cast<float>(_e216), _e218, half_height, colour_level), metal::uint2(metal::uint2(slot, 2u)));
    float _e223 = key;
    sprites_out.write(metal::float4(_e223, 0.0, 0.0, 0.0), metal::uint2(metal::uint2(slot, 3u)));
    return;
}


struct sprite_sortInput {
};
[[max_total_threads_per_threadgroup(64)]] kernel void sprite_sort(
  metal::uint3 id_15 [[thread_position_in_grid]]
, metal::texture2d<float, metal::access::sample> sprites_in [[user(fake0)]]
, metal::texture2d<float, metal::access::write> sprite_order_out [[user(fake0)]]
) {
    uint rank = 0u;
    uint j = 0u;
    bool local_13 = {};
    bool local_14 = {};
    uint slot_1 = id_15.x;
    metal::float4 _e6 = sprites_in.read(metal::uint2(metal::uint2(slot_1, 3u)), 0);
    float key_1 = _e6.x;
    uint2 loop_bound_35 = uint2(4294967295u);
    bool loop_init_31 = true;
    while(true) {
        if (metal::all(loop_bound_35 == uint2(0u))) { break; }
        loop_bound_35 -= uint2(loop_bound_35.y == 0u, 1u);
        if (!loop_init_31) {
            uint _e40 = j;
            j = _e40 + 1u;
        }
        loop_init_31 = false;
        uint _e12 = j;
        if (_e12 < SPRITE_COUNT) {
        } else {
            break;
        }
        {
            uint _e16 = j;
            metal::float4 _e20 = sprites_in.read(metal::uint2(metal::uint2(_e16, 3u)), 0);
            float other = _e20.x;
            uint _e22 = rank;
            if (!((other < key_1))) {
                if (other == key_1) {
                    uint _e32 = j;
                    local_14 = _e32 < slot_1;
                } else {
                    local_14 = false;
                }
                bool _e35 = local_14;
                local_13 = _e35;
            } else {
                local_13 = true;
            }
            bool _e37 = local_13;
            rank = _e22 + (_e37 ? 1u : 0u);
        }
    }
    uint _e44 = rank;
    sprite_order_out.write(metal::float4(static_cast<float>(slot_1), 0.0, 0.0, 0.0), metal::uint2(metal::uint2(_e44, 0u)));
    return;
}


struct sprite_vertexInput {
};
struct sprite_vertexOutput {
    metal::float4 position [[position]];
    metal::float2 uv [[user(loc0), center_perspective]];
    uint tile [[user(loc1), flat]];
    metal::float4 colour [[user(loc2), center_perspective]];
    float distance [[user(loc3), center_perspective]];
};
vertex sprite_vertexOutput sprite_vertex(
  uint index [[vertex_id]]
, constant Frame& frame [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> sprites_in [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> sprite_order_in [[user(fake0)]]
) {
    SpriteVertex out = {};
    metal::float3 right = {};
    metal::float4 _e8 = sprite_order_in.read(metal::uint2(metal::uint2(naga_div(index, 6u), 0u)), 0);
    uint slot_2 = naga_f2u32(_e8.x);
    metal::float4 a_11 = sprites_in.read(metal::uint2(metal::uint2(slot_2, 0u)), 0);
    metal::float4 b_12 = sprites_in.read(metal::uint2(metal::uint2(slot_2, 1u)), 0);
    metal::float4 c_12 = sprites_in.read(metal::uint2(metal::uint2(slot_2, 2u)), 0);
    if (b_12.w <= 0.0) {
        out.position = metal::float4(0.0, 0.0, -1.0, 1.0);
        SpriteVertex _e35 = out;
        const auto _tmp = _e35;
        return sprite_vertexOutput { _tmp.position, _tmp.uv, _tmp.tile, _tmp.colour, _tmp.distance };
    }
    float _e39 = frame.camera_position.y;
    metal::float3 cam_1 = metal::float3(0.0, _e39, 0.0);
    metal::float3 _e45 = sprite_rel(a_11.xz, a_11.y, frame);
    metal::float3 to_sprite = _e45 - cam_1;
    float distance = metal::length(to_sprite);
    float half_width_1 = a_11.w;
    float facing = metal::smoothstep(0.5 * half_width_1, half_width_1, distance);
    metal::float3 to_camera = -(to_sprite) / metal::float3(metal::max(distance, 0.001));
    metal::float4 _e59 = frame.camera_forward;
    metal::float3 n_5 = metal::normalize(metal::mix(-(_e59.xyz), to_camera, facing));
    float _e67 = frame.atmosphere.x;
    metal::float3 radial = metal::normalize(_e45 + metal::float3(0.0, _e67, 0.0));
    right = metal::cross(radial, n_5);
    metal::float3 _e75 = right;
    if (metal::length(_e75) < 0.001) {
        metal::float4 _e81 = frame.camera_right;
        right = _e81.xyz;
    }
    metal::float3 _e83 = right;
    right = metal::normalize(_e83);
    metal::float3 _e85 = right;
    metal::float3 up_3 = metal::cross(n_5, _e85);
    metal::float2 _e89 = sprite_corner(naga_mod(index, 6u));
    metal::float3 _e90 = right;
    metal::float3 offset_1 = (_e90 * (_e89.x * half_width_1)) + (up_3 * (_e89.y * c_12.z));
    metal::float3 vertex_ = to_sprite + offset_1;
    metal::float4 _e102 = frame.camera_right;
    float x_14 = metal::dot(vertex_, _e102.xyz);
    metal::float4 _e107 = frame.camera_up;
    float y_4 = metal::dot(vertex_, _e107.xyz);
    metal::float4 _e112 = frame.camera_forward;
    float z_4 = metal::dot(vertex_, _e112.xyz);
    float tan_half_3 = frame.camera_position.w;
    float _e123 = frame.camera_forward.w;
    out.position = metal::float4(x_14 / (tan_half_3 * _e123), y_4 / tan_half_3, 0.5 * z_4, z_4);
    metal::float2 cs = metal::float2(metal::cos(c_12.y), metal::sin(c_12.y));
    metal::float2 t_14 = metal::float2(_e89.x, -(_e89.y));
    out.uv = metal::float2((t_14.x * cs.x) - (t_14.y * cs.y), (t_14.x * cs.y) + (t_14.y * cs.x));
    out.tile = naga_f2u32(c_12.x);
    metal::float4 _e160 = frame.sun_direction;
    metal::float3 sun_14 = _e160.xyz;
    metal::float3 _e164 = sprite_rel(b_12.xz, b_12.y, frame);
    metal::float3 centre_2 = _e164 - cam_1;
    metal::float3 from_centre = vertex_ - centre_2;
    float cos_angle_1 = metal::dot(from_centre, sun_14) / metal::max(metal::length(from_centre), 0.001);
    float _e177 = saturate((sun_14.y * 4.0) + 0.3);
    float _e179 = altitude_of(vertex_ + cam_1, frame);
    float _e183 = frame.atmosphere.y;
    float _e188 = frame.atmosphere.z;
    float _e192 = frame.atmosphere.y;
    float _e195 = saturate((_e179 - _e183) / (_e188 - _e192));
    metal::float4 _e198 = frame.sun_illuminance;
    metal::float3 e_4 = _e198.xyz;
    metal::float3 _e200 = sprite_sky_level(_e195);
    float _e204 = sprite_sun_level(cos_angle_1);
    metal::float3 light = (e_4 * ((_e200 * (SPRITE_SKY * _e177)) + metal::float3(_e204))) * (c_12.w / PI);
    out.colour = metal::float4(light, b_12.w);
    out.distance = metal::length(vertex_);
    SpriteVertex _e217 = out;
    const auto _tmp_1 = _e217;
    return sprite_vertexOutput { _tmp_1.position, _tmp_1.uv, _tmp_1.tile, _tmp_1.colour, _tmp_1.distance };
}


struct sprite_fragmentInput {
    metal::float2 uv_2 [[user(loc0), center_perspective]];
    uint tile_2 [[user(loc1), flat]];
    metal::float4 colour [[user(loc2), center_perspective]];
    float distance [[user(loc3), center_perspective]];
};
struct sprite_fragmentOutput {
    metal::float4 radiance [[color(0)]];
    metal::float4 depth [[color(1)]];
};
fragment sprite_fragmentOutput sprite_fragment(
  sprite_fragmentInput varyings_18 [[stage_in]]
, metal::float4 position [[position]]
, metal::sampler noise_sampler [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> sprite_atlas_in [[user(fake0)]]
) {
    const SpriteVertex in = { position, varyings_18.uv_2, varyings_18.tile_2, {}, varyings_18.colour, varyings_18.distance };
    SpriteTargets out_1 = {};
    float a = 0.0;
    if (metal::all(metal::abs(in.uv) <= metal::float2(1.0))) {
        metal::float2 tile_3 = metal::float2(static_cast<float>(naga_mod(in.tile, 4u)), static_cast<float>(naga_div(in.tile, 4u)));
        metal::float2 uv_6 = ((tile_3 + metal::float2(0.5)) + (0.5 * in.uv)) * 0.25;
        metal::float4 _e31 = sprite_atlas_in.sample(noise_sampler, uv_6, metal::level(0.0));
        a = _e31.x * in.colour.w;
    }
    float _e39 = a;
    float _e41 = a;
    out_1.radiance = metal::float4(in.colour.xyz * _e39, _e41);
    float _e45 = a;
    float _e47 = a;
    out_1.depth = metal::float4(in.distance * _e45, 0.0, 0.0, _e47);
    SpriteTargets _e51 = out_1;
    const auto _tmp_2 = _e51;
    return sprite_fragmentOutput { _tmp_2.radiance, _tmp_2.depth };
}


struct sprite_resolveInput {
};
[[max_total_threads_per_threadgroup(64)]] kernel void sprite_resolve(
  metal::uint3 id_16 [[thread_position_in_grid]]
, constant Frame& frame [[user(fake0)]]
, metal::texture2d<float, metal::access::write> cloud_out [[user(fake0)]]
, metal::texture2d<float, metal::access::write> depth_out [[user(fake0)]]
, device Stats& stats [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> sprite_radiance_in [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> sprite_depth_in [[user(fake0)]]
) {
    metal::uint4 _e4 = frame.counts;
    if (metal::any(id_16.xy >= _e4.xy)) {
        return;
    }
    count(STAT_PIXELS, 1u, stats);
    metal::float4 c_13 = sprite_radiance_in.read(metal::uint2(id_16.xy), 0);
    metal::float4 d_26 = sprite_depth_in.read(metal::uint2(id_16.xy), 0);
    float _e19 = saturate(c_13.w);
    cloud_out.write(metal::float4(c_13.xyz, 1.0 - _e19), metal::uint2(id_16.xy));
    depth_out.write(metal::float4((d_26.w > 0.0001) ? (d_26.x / d_26.w) : 0.0, 0.0, 0.0, 0.0), metal::uint2(id_16.xy));
    return;
}


struct compositeInput {
};
[[max_total_threads_per_threadgroup(64)]] kernel void composite(
  metal::uint3 id_17 [[thread_position_in_grid]]
, constant Frame& frame [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> cloud_in [[user(fake0)]]
, metal::texture2d<float, metal::access::write> image_out [[user(fake0)]]
) {
    metal::float3 background = {};
    metal::uint4 _e4 = frame.counts;
    if (metal::any(id_17.xy >= _e4.xy)) {
        return;
    }
    metal::uint2 pixel_12 = id_17.xy;
    metal::float3 _e9 = view_ray(pixel_12, frame);
    float alt_19 = frame.camera_position.y;
    metal::float4 cloud_1 = cloud_in.read(metal::uint2(pixel_12), 0);
    metal::float3 _e17 = sky_radiance(_e9, alt_19, frame);
    background = _e17;
    bool _e22 = hits_ground(metal::float3(0.0, alt_19, 0.0), alt_19, _e9, frame);
    if (!(_e22)) {
        metal::float3 _e24 = background;
        metal::float3 _e25 = sun_disk(_e9, frame);
        background = _e24 + _e25;
    }
    metal::float3 _e27 = background;
    store_display(pixel_12, (_e27 * cloud_1.w) + cloud_1.xyz, frame, image_out);
    return;
}


struct composite_physicalInput {
};
[[max_total_threads_per_threadgroup(64)]] kernel void composite_physical(
  metal::uint3 id_18 [[thread_position_in_grid]]
, constant Frame& frame [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> transmittance_lut_in [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> sky_view_in [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> aerial_in [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> cloud_shadow_in [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> cloud_in [[user(fake0)]]
, metal::texture2d<float, metal::access::write> image_out [[user(fake0)]]
, metal::texture2d<float, metal::access::sample> depth_in [[user(fake0)]]
) {
    metal::uint4 _e4 = frame.counts;
    if (metal::any(id_18.xy >= _e4.xy)) {
        return;
    }
    metal::uint2 pixel_13 = id_18.xy;
    metal::float4 cloud_2 = cloud_in.read(metal::uint2(pixel_13), 0);
    metal::float3 _e12 = view_ray(pixel_13, frame);
    metal::float3 _e13 = physical_composite(pixel_13, _e12, cloud_2, frame, transmittance_lut_in, sky_view_in, aerial_in, cloud_shadow_in, depth_in);
    store_display(pixel_13, _e13, frame, image_out);
    return;
}
