#version 450 core
#extension GL_ARB_compute_shader : require
#extension GL_ARB_shader_storage_buffer_object : require
layout(local_size_x = 32, local_size_y = 1, local_size_z = 1) in;

struct Frame {
    vec4 camera_position;
    vec4 camera_forward;
    vec4 camera_right;
    vec4 camera_up;
    vec4 sun_direction;
    vec4 sun_illuminance;
    vec4 atmosphere;
    vec4 clouds;
    vec4 erosion;
    vec4 periods;
    vec4 wind_offsets0_;
    vec4 wind_offsets1_;
    vec4 extinction;
    vec4 phase;
    vec4 multiple_scattering;
    vec4 ambient_bottom;
    vec4 ambient_top;
    vec4 march;
    uvec4 counts;
    uvec4 modes;
    uvec4 misc;
    vec4 previous_position;
    vec4 previous_forward;
    vec4 previous_right;
    vec4 previous_up;
    uvec4 temporal;
    vec4 layer1_;
    vec4 layer1_weather;
    vec4 layer2_;
    vec4 layer2_weather;
    vec4 layer3_;
    vec4 layer3_weather;
    vec4 air_rayleigh;
    vec4 air_mie;
    vec4 air_ozone;
    vec4 air_misc;
    vec4 moon;
    vec4 night;
    vec4 light_model;
    vec4 octave_direction;
    vec4 octave_depth;
};
struct Roots {
    float t0_;
    float t1_;
    bool hit;
};
struct Interval {
    float start;
    float length_;
    uint kind;
};
struct Layer {
    float bottom;
    float top;
    float coverage;
    float density;
    float cloud_type;
    float precipitation;
    vec2 weather_offset;
};
struct AirSample {
    vec3 rayleigh;
    float mie;
    vec3 extinction;
};
struct Scattered {
    vec3 radiance;
    vec3 transmittance;
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
    vec3 total;
    vec3 octaves;
};
struct Stats {
    uint counters[9];
};
struct MarchResult {
    vec3 radiance;
    float transmittance;
    float depth;
};
struct MarchState {
    vec3 radiance;
    float transmittance;
    float depth_sum;
    vec3 octaves;
};
struct Segments {
    vec2 a;
    vec2 b;
    uint count;
};
struct PhaseSample {
    vec3 dir;
    float weight;
};
struct PathResult {
    vec3 radiance;
    float transmittance;
    float depth;
};
struct SpriteCell {
    ivec2 index;
    float size;
    bool covered;
};
struct SpriteCandidate {
    vec2 xz;
    float alt;
    float h;
    float size_hash;
    float texture_hash;
    float rotation_hash;
    float density;
    float precipitation;
};
struct SpriteVertex {
    vec4 position;
    vec2 uv;
    uint tile;
    vec4 colour;
    float distance_;
};
struct SpriteTargets {
    vec4 radiance;
    vec4 depth;
};
const uint PHASE_HG = 0u;
const uint PHASE_TWO_LOBE_HG = 1u;
const uint PHASE_CORNETTE_SHANKS = 2u;
const uint INTEGRATION_ANALYTIC = 0u;
const uint INTEGRATION_RIEMANN = 1u;
const uint HEIGHT_PARABOLA = 0u;
const uint HEIGHT_CLOUD_TYPES = 1u;
const uint FLAG_BEER_POWDER = 1u;
const uint FLAG_JITTER = 2u;
const uint FLAG_DYNAMIC_STEP = 4u;
const uint FLAG_CHECKERBOARD = 8u;
const uint FLAG_EMPTY_SKIP = 16u;
const uint FLAG_PHYSICAL_SKY = 32u;
const uint FLAG_MOONLIT = 64u;
const float PI = 3.1415927;
const uint MAX_VIEW_STEPS = 1024u;
const uint RAY_MARCH = 0u;
const uint RAY_MISSES_LAYER = 1u;
const uint RAY_HITS_GROUND = 2u;
const uint MAX_LAYERS = 4u;
const uvec2 TRANSMITTANCE_SIZE = uvec2(256u, 64u);
const uvec2 MULTISCATTER_SIZE = uvec2(32u, 32u);
const uvec2 SKY_VIEW_SIZE = uvec2(192u, 108u);
const uint AERIAL_SLICES = 32u;
const uint AERIAL_SIDE = 32u;
const float AERIAL_SLICE_KM = 1.0;
const uint TRANSMITTANCE_STEPS = 128u;
const uint MULTISCATTER_DIRECTIONS = 64u;
const uint MULTISCATTER_STEPS = 32u;
const uint SKY_VIEW_STEPS = 48u;
const uint AMBIENT_DIRECTIONS = 64u;
const uint AMBIENT_STEPS = 24u;
const uint SKY_AMBIENT_SUNS = 64u;
const uint GROUND_IRRADIANCE_SIZE = 64u;
const uint NO_LAYER = 4u;
const uint COLUMN_STEPS = 3u;
const float DECK_POWER = 8.0;
const float FORWARD_LOBE_THIN = 0.1;
const uint GROUND_IRRADIANCE_DIRECTIONS = 128u;
const uint SHADOW_SIZE = 128u;
const float SHADOW_HALF_EXTENT = 20000.0;
const float SHADOW_FADE_START = 0.75;
const uint SHADOW_STEPS = 16u;
const uint OCCUPANCY_CELLS = 64u;
const uint STAT_PIXELS = 0u;
const uint STAT_MARCHED = 1u;
const uint STAT_VIEW_STEPS = 2u;
const uint STAT_DENSITY = 3u;
const uint STAT_DETAIL = 4u;
const uint STAT_LIGHT = 5u;
const uint STAT_EXIT_TRANSMITTANCE = 6u;
const uint STAT_EXIT_MISSED = 7u;
const uint STAT_EXIT_GROUND = 8u;
const uint STAT_COUNT = 9u;
const float HISTORY_SAMPLES = 16.0;
const float HISTORY_SAMPLES_MOVING = 2.0;
const float DISOCCLUSION_DEPTH = 0.5;
const uint MAX_PATH_ORDERS = 16384u;
const uint PATHS_PER_FRAME = 32u;
const uint SPRITE_LEVELS = 4u;
const int SPRITE_CELLS_PER_SIDE = 8;
const uint SPRITES_PER_CELL = 16u;
const uint SPRITE_COUNT = 4096u;
const float SPRITE_CELL0_ = 1500.0;
const float SPRITE_ALPHA = 0.7;
const float SPRITE_MAX_DISTANCE = 131072.0;
const uint ATLAS_TILE = 64u;
const float SPRITE_C_MIN = 0.22;
const float SPRITE_C_MED = 0.55;
const float SPRITE_C_MAX = 1.0;
const float SPRITE_SKY = 0.35;
const vec3 SKY_LEVEL0_ = vec3(0.42, 0.46, 0.55);
const vec3 SKY_LEVEL1_ = vec3(0.55, 0.59, 0.67);
const vec3 SKY_LEVEL2_ = vec3(0.7, 0.73, 0.8);
const vec3 SKY_LEVEL3_ = vec3(0.84, 0.86, 0.9);
const vec3 SKY_LEVEL4_ = vec3(0.95, 0.96, 0.98);
const float MOON_COS_RADIUS = 0.9999898;
const uint STAR_CELLS = 96u;
const float STAR_FAINTEST = 6.5;
const bool LIGHT_MARCH = true;
const uint MAX_OCTAVES = 8u;
const bool DETAIL = false;
const bool CURL = false;
const bool STATS = false;

layout(std140, binding = 0) uniform Frame_block_0Compute { Frame _group_0_binding_0_cs; };

layout(binding = 27) uniform sampler2D _group_0_binding_27_cs;

layout(binding = 28) uniform sampler2D _group_0_binding_28_cs;

layout(binding = 31) uniform sampler2D _group_0_binding_31_cs;

layout(binding = 38) uniform sampler2D _group_0_binding_38_cs;

layout(binding = 1) uniform sampler3D _group_0_binding_1_cs;

layout(binding = 2) uniform sampler3D _group_0_binding_2_cs;

layout(binding = 3) uniform sampler2D _group_0_binding_3_cs;

layout(binding = 4) uniform sampler2D _group_0_binding_4_cs;

layout(binding = 11) uniform sampler2D _group_0_binding_11_cs;

layout(binding = 6,rgba32f) writeonly uniform image2D _group_0_binding_6_cs;

layout(binding = 7,r32f) writeonly uniform image2D _group_0_binding_7_cs;

layout(std430, binding = 8) buffer Stats_block_1Compute { Stats _group_0_binding_8_cs; };

layout(binding = 13) uniform sampler2D _group_0_binding_13_cs;

layout(binding = 14) uniform sampler2D _group_0_binding_14_cs;

layout(binding = 17,rgba32f) writeonly uniform image2D _group_0_binding_17_cs;

layout(binding = 18,rgba32f) writeonly uniform image2D _group_0_binding_18_cs;

shared vec4 lane_sums[32];

shared vec4 lane_moments[32];


float saturate(float x_1) {
    return clamp(x_1, 0.0, 1.0);
}

float remap(float x_2, float lo0_, float hi0_, float lo1_, float hi1_) {
    return (lo1_ + (((x_2 - lo0_) * (hi1_ - lo1_)) / (hi0_ - lo0_)));
}

uint pcg(uint v) {
    uint state_2 = ((v * 747796405u) + 2891336453u);
    uint word = (((state_2 >> ((state_2 >> 28u) + 4u)) ^ state_2) * 277803737u);
    return ((word >> 22u) ^ word);
}

float van_der_corput(uint n) {
    return (float((bitfieldReverse(n) >> 8u)) * 5.9604645e-8);
}

float hash_unit(uvec2 pixel, uint frame_index) {
    uint _e4 = pcg(frame_index);
    uint _e6 = pcg((pixel.y ^ _e4));
    uint _e8 = pcg((pixel.x ^ _e6));
    return (float((_e8 >> 8u)) * 5.9604645e-8);
}

vec3 view_ray(uvec2 pixel_1) {
    uvec4 _e3 = _group_0_binding_0_cs.counts;
    vec2 size_1 = vec2(_e3.xy);
    vec2 ndc = ((((vec2(pixel_1) + vec2(0.5)) / size_1) * 2.0) - vec2(1.0));
    float tan_half = _group_0_binding_0_cs.camera_position.w;
    float aspect = _group_0_binding_0_cs.camera_forward.w;
    vec4 _e26 = _group_0_binding_0_cs.camera_forward;
    vec4 _e30 = _group_0_binding_0_cs.camera_right;
    vec4 _e39 = _group_0_binding_0_cs.camera_up;
    vec3 d_21 = ((_e26.xyz + (_e30.xyz * ((ndc.x * tan_half) * aspect))) - (_e39.xyz * (ndc.y * tan_half)));
    return normalize(d_21);
}

Roots solve_sphere(float b, float c) {
    float disc = ((b * b) - c);
    if ((disc < 0.0)) {
        return Roots(0.0, 0.0, false);
    }
    float s_3 = sqrt(disc);
    float r0_1 = -((b + ((b >= 0.0) ? s_3 : -(s_3))));
    if ((r0_1 == 0.0)) {
        return Roots(0.0, 0.0, true);
    }
    float r1_1 = (c / r0_1);
    return Roots(min(r0_1, r1_1), max(r0_1, r1_1), true);
}

Roots ray_shell(float alt, vec3 d, float radius_alt) {
    float rp = _group_0_binding_0_cs.atmosphere.x;
    float b_3 = (d.y * (alt + rp));
    float c_5 = ((alt - radius_alt) * ((alt + radius_alt) + (2.0 * rp)));
    Roots _e16 = solve_sphere(b_3, c_5);
    return _e16;
}

float altitude_of(vec3 p) {
    float rp_1 = _group_0_binding_0_cs.atmosphere.x;
    float n_3 = (((p.x * p.x) + (p.z * p.z)) + (p.y * (p.y + (2.0 * rp_1))));
    vec3 q_5 = vec3(p.x, (p.y + rp_1), p.z);
    return (n_3 / (length(q_5) + rp_1));
}

bool hits_ground(vec3 p_1, float alt_1, vec3 d_1) {
    bool local_15 = false;
    float rp_2 = _group_0_binding_0_cs.atmosphere.x;
    float b_4 = dot(d_1, vec3(p_1.x, (p_1.y + rp_2), p_1.z));
    float c_6 = (alt_1 * (alt_1 + (2.0 * rp_2)));
    if ((b_4 < 0.0)) {
        local_15 = ((b_4 * b_4) >= c_6);
    } else {
        local_15 = false;
    }
    bool _e24 = local_15;
    return _e24;
}

Interval shell_interval(float alt_2, vec3 d_2, float bottom, float top) {
    float start = 0.0;
    float end = 0.0;
    bool local_16 = false;
    bool local_17 = false;
    bool local_18 = false;
    float cutoff = _group_0_binding_0_cs.atmosphere.w;
    Roots _e8 = ray_shell(alt_2, d_2, bottom);
    Roots _e9 = ray_shell(alt_2, d_2, top);
    if ((alt_2 < bottom)) {
        bool _e18 = hits_ground(vec3(0.0, alt_2, 0.0), alt_2, d_2);
        if (_e18) {
            return Interval(0.0, 0.0, 2u);
        }
        start = _e8.t1_;
        end = _e9.t1_;
    } else {
        if ((alt_2 <= top)) {
            end = _e9.t1_;
            if (_e8.hit) {
                local_16 = (_e8.t0_ > 0.0);
            } else {
                local_16 = false;
            }
            bool _e34 = local_16;
            if (_e34) {
                float _e35 = end;
                end = min(_e35, _e8.t0_);
            }
        } else {
            if (!(!(_e9.hit))) {
                local_17 = (_e9.t1_ <= 0.0);
            } else {
                local_17 = true;
            }
            bool _e47 = local_17;
            if (_e47) {
                return Interval(0.0, 0.0, 1u);
            }
            start = max(_e9.t0_, 0.0);
            end = _e9.t1_;
            if (_e8.hit) {
                local_18 = (_e8.t0_ > 0.0);
            } else {
                local_18 = false;
            }
            bool _e63 = local_18;
            if (_e63) {
                float _e64 = end;
                end = min(_e64, _e8.t0_);
            }
        }
    }
    float _e67 = end;
    float _e68 = start;
    float len = min((_e67 - _e68), cutoff);
    if (!((len > 0.0))) {
        return Interval(0.0, 0.0, 1u);
    }
    float _e78 = start;
    return Interval(_e78, len, RAY_MARCH);
}

Interval layer_interval(float alt_3, vec3 d_3, Layer l) {
    Interval _e5 = shell_interval(alt_3, d_3, l.bottom, l.top);
    return _e5;
}

uint layer_count() {
    uint _e4 = _group_0_binding_0_cs.misc.w;
    return (1u + min(_e4, 3u));
}

Layer layer_from(vec4 g, vec4 w_1) {
    return Layer(g.x, g.y, g.z, g.w, w_1.x, w_1.y, w_1.zw);
}

Layer cloud_layer(uint i_5) {
    if ((i_5 == 1u)) {
        vec4 _e5 = _group_0_binding_0_cs.layer1_;
        vec4 _e8 = _group_0_binding_0_cs.layer1_weather;
        Layer _e9 = layer_from(_e5, _e8);
        return _e9;
    } else {
        if ((i_5 == 2u)) {
            vec4 _e14 = _group_0_binding_0_cs.layer2_;
            vec4 _e17 = _group_0_binding_0_cs.layer2_weather;
            Layer _e18 = layer_from(_e14, _e17);
            return _e18;
        } else {
            if ((i_5 == 3u)) {
                vec4 _e23 = _group_0_binding_0_cs.layer3_;
                vec4 _e26 = _group_0_binding_0_cs.layer3_weather;
                Layer _e27 = layer_from(_e23, _e26);
                return _e27;
            }
        }
    }
    float _e31 = _group_0_binding_0_cs.atmosphere.y;
    float _e35 = _group_0_binding_0_cs.atmosphere.z;
    float _e39 = _group_0_binding_0_cs.clouds.x;
    float _e43 = _group_0_binding_0_cs.clouds.y;
    float _e47 = _group_0_binding_0_cs.clouds.z;
    float _e51 = _group_0_binding_0_cs.clouds.w;
    vec4 _e54 = _group_0_binding_0_cs.wind_offsets0_;
    return Layer(_e31, _e35, _e39, _e43, _e47, _e51, _e54.xy);
}

vec2 layers_span() {
    vec2 span = vec2(0.0);
    uint i_6 = 1u;
    vec4 _e2 = _group_0_binding_0_cs.atmosphere;
    span = _e2.yz;
    bool loop_init = true;
    while(true) {
        if (!loop_init) {
            uint _e22 = i_6;
            i_6 = (_e22 + 1u);
        }
        loop_init = false;
        uint _e7 = i_6;
        uint _e8 = layer_count();
        if ((_e7 < _e8)) {
        } else {
            break;
        }
        {
            uint _e10 = i_6;
            Layer _e11 = cloud_layer(_e10);
            float _e13 = span.x;
            float _e17 = span.y;
            span = vec2(min(_e13, _e11.bottom), max(_e17, _e11.top));
        }
    }
    vec2 _e24 = span;
    return _e24;
}

Interval cloud_interval(float alt_4, vec3 d_4) {
    vec2 _e2 = layers_span();
    Interval _e5 = shell_interval(alt_4, d_4, _e2.x, _e2.y);
    return _e5;
}

Interval nearest_layer_interval(float alt_5, vec3 d_5) {
    Interval best = Interval(0.0, 0.0, 0u);
    uint i_7 = 1u;
    bool local_19 = false;
    bool local_20 = false;
    Layer _e3 = cloud_layer(0u);
    Interval _e4 = layer_interval(alt_5, d_5, _e3);
    best = _e4;
    bool loop_init_1 = true;
    while(true) {
        if (!loop_init_1) {
            uint _e35 = i_7;
            i_7 = (_e35 + 1u);
        }
        loop_init_1 = false;
        uint _e8 = i_7;
        uint _e9 = layer_count();
        if ((_e8 < _e9)) {
        } else {
            break;
        }
        {
            uint _e11 = i_7;
            Layer _e12 = cloud_layer(_e11);
            Interval _e13 = layer_interval(alt_5, d_5, _e12);
            if ((_e13.kind == RAY_MARCH)) {
                uint _e20 = best.kind;
                if (!((_e20 != RAY_MARCH))) {
                    float _e28 = best.start;
                    local_20 = (_e13.start < _e28);
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

Roots ray_shell_from(vec3 p_2, float alt_6, vec3 d_6, float radius_alt_1) {
    float rp_3 = _group_0_binding_0_cs.atmosphere.x;
    float b_5 = dot(d_6, vec3(p_2.x, (p_2.y + rp_3), p_2.z));
    float c_7 = ((alt_6 - radius_alt_1) * ((alt_6 + radius_alt_1) + (2.0 * rp_3)));
    Roots _e20 = solve_sphere(b_5, c_7);
    return _e20;
}

bool physical_sky() {
    uint _e3 = _group_0_binding_0_cs.modes.w;
    return ((_e3 & FLAG_PHYSICAL_SKY) != 0u);
}

float air_bottom() {
    float _e3 = _group_0_binding_0_cs.atmosphere.x;
    return (_e3 * 0.001);
}

float air_top() {
    float _e3 = _group_0_binding_0_cs.atmosphere.x;
    float _e7 = _group_0_binding_0_cs.air_misc.x;
    return ((_e3 + _e7) * 0.001);
}

AirSample air_at(float h_km) {
    float h_11 = (max(h_km, 0.0) * 1000.0);
    float _e9 = _group_0_binding_0_cs.air_rayleigh.w;
    float rayleigh_density = exp((-(h_11) / _e9));
    float _e16 = _group_0_binding_0_cs.air_mie.z;
    float mie_density = exp((-(h_11) / _e16));
    float _e22 = _group_0_binding_0_cs.air_ozone.w;
    float _e28 = _group_0_binding_0_cs.air_misc.y;
    float ozone_density = max((1.0 - (abs((h_11 - _e22)) / (0.5 * _e28))), 0.0);
    vec4 _e38 = _group_0_binding_0_cs.air_rayleigh;
    vec3 rayleigh = (_e38.xyz * (rayleigh_density * 1000.0));
    float _e46 = _group_0_binding_0_cs.air_mie.x;
    float mie = ((_e46 * mie_density) * 1000.0);
    float _e53 = _group_0_binding_0_cs.air_mie.x;
    float _e57 = _group_0_binding_0_cs.air_mie.y;
    float mie_extinction = (((_e53 + _e57) * mie_density) * 1000.0);
    vec4 _e64 = _group_0_binding_0_cs.air_ozone;
    vec3 ozone = (_e64.xyz * (ozone_density * 1000.0));
    return AirSample(rayleigh, mie, ((rayleigh + vec3(mie_extinction)) + ozone));
}

float sphere_discriminant(float r_2, float mu, float radius) {
    return (((radius - r_2) * (radius + r_2)) + (((r_2 * r_2) * mu) * mu));
}

float distance_to_top(float r_3, float mu_1) {
    float _e4 = air_top();
    float _e5 = sphere_discriminant(r_3, mu_1, _e4);
    return max(((-(r_3) * mu_1) + sqrt(max(_e5, 0.0))), 0.0);
}

bool meets_ground(float r_4, float mu_2) {
    bool local_21 = false;
    if ((mu_2 < 0.0)) {
        float _e6 = air_bottom();
        float _e7 = sphere_discriminant(r_4, mu_2, _e6);
        local_21 = (_e7 >= 0.0);
    } else {
        local_21 = false;
    }
    bool _e11 = local_21;
    return _e11;
}

float distance_to_ground(float r_5, float mu_3) {
    float _e4 = air_bottom();
    float _e5 = sphere_discriminant(r_5, mu_3, _e4);
    return max(((-(r_5) * mu_3) - sqrt(max(_e5, 0.0))), 0.0);
}

float radius_after(float r_6, float mu_4, float t) {
    return sqrt(max((((r_6 * r_6) + (t * t)) + (((2.0 * r_6) * mu_4) * t)), 0.0));
}

vec4 lut_bilinear(sampler2D lut, vec2 x_3, uvec2 size) {
    vec2 last = vec2((size - uvec2(1u)));
    vec2 f_1 = (clamp(x_3, vec2(0.0), vec2(1.0)) * last);
    uvec2 i0_ = min(uvec2(floor(f_1)), (size - uvec2(1u)));
    uvec2 i1_ = min((i0_ + uvec2(1u)), (size - uvec2(1u)));
    vec2 w_3 = (f_1 - vec2(i0_));
    vec4 _e32 = texelFetch(lut, ivec2(uvec2(i0_.x, i0_.y)), 0);
    vec4 _e37 = texelFetch(lut, ivec2(uvec2(i1_.x, i0_.y)), 0);
    vec4 a_4 = mix(_e32, _e37, w_3.x);
    vec4 _e44 = texelFetch(lut, ivec2(uvec2(i0_.x, i1_.y)), 0);
    vec4 _e49 = texelFetch(lut, ivec2(uvec2(i1_.x, i1_.y)), 0);
    vec4 b_6 = mix(_e44, _e49, w_3.x);
    return mix(a_4, b_6, w_3.y);
}

vec2 transmittance_coords(float r_7, float mu_5) {
    float _e2 = air_bottom();
    float _e3 = air_top();
    float h_12 = sqrt(max(((_e3 - _e2) * (_e3 + _e2)), 0.0));
    float rho = sqrt(max(((r_7 - _e2) * (r_7 + _e2)), 0.0));
    float _e16 = distance_to_top(r_7, mu_5);
    float d_min = (_e3 - r_7);
    float d_max = (rho + h_12);
    return vec2(((_e16 - d_min) / max((d_max - d_min), 1e-6)), (rho / h_12));
}

vec2 transmittance_r_mu(vec2 x_4) {
    float mu_6 = 1.0;
    float _e1 = air_bottom();
    float _e2 = air_top();
    float h_13 = sqrt(max(((_e2 - _e1) * (_e2 + _e1)), 0.0));
    float rho_1 = (h_13 * x_4.y);
    float r_14 = sqrt(((rho_1 * rho_1) + (_e1 * _e1)));
    float d_min_1 = (_e2 - r_14);
    float d_max_1 = (rho_1 + h_13);
    float d_22 = (d_min_1 + (x_4.x * (d_max_1 - d_min_1)));
    if ((d_22 > 0.0)) {
        mu_6 = clamp(((((h_13 * h_13) - (rho_1 * rho_1)) - (d_22 * d_22)) / ((2.0 * r_14) * d_22)), -1.0, 1.0);
    }
    float _e37 = mu_6;
    return vec2(r_14, _e37);
}

vec3 transmittance_to_top(float r_8, float mu_7) {
    vec2 _e3 = transmittance_coords(r_8, mu_7);
    vec4 _e5 = lut_bilinear(_group_0_binding_27_cs, _e3, TRANSMITTANCE_SIZE);
    return _e5.xyz;
}

vec3 sun_transmittance(float r_9, float mu_s) {
    bool _e2 = meets_ground(r_9, mu_s);
    if (_e2) {
        return vec3(0.0);
    }
    vec3 _e5 = transmittance_to_top(r_9, mu_s);
    return _e5;
}

vec3 multiscatter(float r_10, float mu_s_1) {
    float _e6 = air_bottom();
    float _e8 = air_top();
    float _e9 = air_bottom();
    vec2 x_6 = vec2(((mu_s_1 * 0.5) + 0.5), ((r_10 - _e6) / (_e8 - _e9)));
    vec4 _e15 = lut_bilinear(_group_0_binding_28_cs, x_6, MULTISCATTER_SIZE);
    return _e15.xyz;
}

float phase_rayleigh(float cos_theta) {
    return (0.059683103 * (1.0 + (cos_theta * cos_theta)));
}

float phase_cornette_shanks_air(float cos_theta_1, float g_1) {
    float g2_ = (g_1 * g_1);
    return (((0.119366206 * (1.0 - g2_)) * (1.0 + (cos_theta_1 * cos_theta_1))) / ((2.0 + g2_) * pow(max(((1.0 + g2_) - ((2.0 * g_1) * cos_theta_1)), 1e-6), 1.5)));
}

vec3 fibonacci_direction(uint k_5, uint n_1) {
    float z_2 = (1.0 - (((2.0 * float(k_5)) + 1.0) / float(n_1)));
    float s_4 = sqrt(max((1.0 - (z_2 * z_2)), 0.0));
    float phi = (2.3999634 * float(k_5));
    return vec3((s_4 * cos(phi)), z_2, (s_4 * sin(phi)));
}

vec3 ground_radiance_sun(float mu_s_2) {
    float _e4 = _group_0_binding_0_cs.air_misc.z;
    float _e10 = air_bottom();
    vec3 _e13 = sun_transmittance((_e10 + 0.001), mu_s_2);
    return (((_e4 / PI) * max(mu_s_2, 0.0)) * _e13);
}

Scattered integrate_air(vec3 origin, vec3 d_7, float distance_km, uint steps, vec3 sun) {
    vec3 radiance_1 = vec3(0.0);
    vec3 tau_3 = vec3(0.0);
    float t0_ = 0.0;
    uint i_8 = 0u;
    float cos_theta_8 = dot(d_7, sun);
    float _e6 = phase_rayleigh(cos_theta_8);
    float _e10 = _group_0_binding_0_cs.air_mie.w;
    float _e11 = phase_cornette_shanks_air(cos_theta_8, _e10);
    bool loop_init_2 = true;
    while(true) {
        if (!loop_init_2) {
            uint _e79 = i_8;
            i_8 = (_e79 + 1u);
        }
        loop_init_2 = false;
        uint _e22 = i_8;
        if ((_e22 < steps)) {
        } else {
            break;
        }
        {
            uint _e24 = i_8;
            float s1_ = (float((_e24 + 1u)) / float(steps));
            float t1_ = ((distance_km * s1_) * s1_);
            float _e32 = t0_;
            float dt_1 = (t1_ - _e32);
            float _e34 = t0_;
            vec3 p_16 = (origin + (d_7 * (0.5 * (_e34 + t1_))));
            float r_15 = length(p_16);
            vec3 up = (p_16 / vec3(r_15));
            float mu_s_5 = dot(up, sun);
            float _e44 = air_bottom();
            AirSample _e46 = air_at((r_15 - _e44));
            vec3 _e47 = tau_3;
            vec3 t_view = exp(-((_e47 + ((0.5 * _e46.extinction) * dt_1))));
            vec3 _e55 = sun_transmittance(r_15, mu_s_5);
            vec3 _e56 = multiscatter(r_15, mu_s_5);
            vec3 inscatter = ((_e55 * ((_e46.rayleigh * _e6) + vec3((_e46.mie * _e11)))) + (_e56 * (_e46.rayleigh + vec3(_e46.mie))));
            vec3 _e70 = radiance_1;
            radiance_1 = (_e70 + ((t_view * inscatter) * dt_1));
            vec3 _e74 = tau_3;
            tau_3 = (_e74 + (_e46.extinction * dt_1));
            t0_ = t1_;
        }
    }
    vec3 _e81 = radiance_1;
    vec3 _e82 = tau_3;
    return Scattered(_e81, exp(-(_e82)));
}

vec3 sky_irradiance(float mu_s_3) {
    vec2 x_7 = vec2(((mu_s_3 * 0.5) + 0.5), 0.0);
    vec4 _e11 = lut_bilinear(_group_0_binding_38_cs, x_7, uvec2(64u, 1u));
    return _e11.xyz;
}

vec3 ground_radiance(float mu_s_4) {
    vec3 _e1 = ground_radiance_sun(mu_s_4);
    float _e5 = _group_0_binding_0_cs.air_misc.z;
    vec3 _e8 = sky_irradiance(mu_s_4);
    return (_e1 + ((_e5 / PI) * _e8));
}

vec3 with_ground(Scattered s, vec3 origin_1, vec3 d_8, float distance_km_1, vec3 sun_1, bool ground) {
    if (!(ground)) {
        return s.radiance;
    }
    vec3 end_1 = (origin_1 + (d_8 * distance_km_1));
    vec3 _e14 = ground_radiance(dot(normalize(end_1), sun_1));
    return (s.radiance + (s.transmittance * _e14));
}

vec2 air_ray_end(vec3 origin_2, vec3 d_9) {
    float r_16 = length(origin_2);
    float mu_9 = (dot(origin_2, d_9) / r_16);
    bool _e5 = meets_ground(r_16, mu_9);
    if (_e5) {
        float _e6 = distance_to_ground(r_16, mu_9);
        return vec2(_e6, 1.0);
    }
    float _e9 = air_top();
    if ((r_16 > _e9)) {
        return vec2(0.0, 0.0);
    }
    float _e14 = distance_to_top(r_16, mu_9);
    return vec2(_e14, 0.0);
}

vec3 camera_air_origin() {
    float _e0 = air_bottom();
    float _e4 = _group_0_binding_0_cs.camera_position.y;
    return vec3(0.0, (_e0 + (max(_e4, 0.0) * 0.001)), 0.0);
}

float sky_view_elevation(float v_1, float horizon) {
    if ((v_1 >= 0.5)) {
        float a_5 = ((2.0 * v_1) - 1.0);
        return (horizon + (((1.5707964 - horizon) * a_5) * a_5));
    }
    float a_6 = (1.0 - (2.0 * v_1));
    return (horizon - (((horizon + 1.5707964) * a_6) * a_6));
}

float sky_view_v(float elevation, float horizon_1) {
    if ((elevation >= horizon_1)) {
        float _e7 = saturate(((elevation - horizon_1) / (1.5707964 - horizon_1)));
        return (0.5 + (0.5 * sqrt(_e7)));
    }
    float _e17 = saturate(((horizon_1 - elevation) / (horizon_1 + 1.5707964)));
    return (0.5 - (0.5 * sqrt(_e17)));
}

float horizon_elevation(float r_11) {
    float _e1 = air_bottom();
    return -(acos(clamp((_e1 / r_11), -1.0, 1.0)));
}

float sun_azimuth() {
    vec4 _e2 = _group_0_binding_0_cs.sun_direction;
    vec3 s_5 = _e2.xyz;
    return atan(s_5.z, s_5.x);
}

vec3 sky_along(vec3 origin_3, vec3 d_10) {
    vec2 _e2 = air_ray_end(origin_3, d_10);
    vec4 _e5 = _group_0_binding_0_cs.sun_direction;
    vec3 sun_2 = _e5.xyz;
    Scattered _e9 = integrate_air(origin_3, d_10, _e2.x, SKY_VIEW_STEPS, sun_2);
    vec3 _e14 = with_ground(_e9, origin_3, d_10, _e2.x, sun_2, (_e2.y > 0.5));
    return _e14;
}

vec3 sky_from(vec3 rel, vec3 d_11) {
    float _e7 = _group_0_binding_0_cs.atmosphere.x;
    vec3 _e13 = sky_along((vec3(rel.x, (rel.y + _e7), rel.z) * 0.001), d_11);
    return _e13;
}

vec3 aerial_ray(uvec2 c_1) {
    vec2 ndc_1 = ((((vec2(c_1) + vec2(0.5)) / vec2(32.0)) * 2.0) - vec2(1.0));
    float tan_half_1 = _group_0_binding_0_cs.camera_position.w;
    float aspect_1 = _group_0_binding_0_cs.camera_forward.w;
    vec4 _e23 = _group_0_binding_0_cs.camera_forward;
    vec4 _e27 = _group_0_binding_0_cs.camera_right;
    vec4 _e36 = _group_0_binding_0_cs.camera_up;
    return normalize(((_e23.xyz + (_e27.xyz * ((ndc_1.x * tan_half_1) * aspect_1))) - (_e36.xyz * (ndc_1.y * tan_half_1))));
}

vec3 sun_through_air(vec3 rel_1) {
    bool _e1 = physical_sky();
    if (!(_e1)) {
        return vec3(1.0);
    }
    float _e10 = _group_0_binding_0_cs.atmosphere.x;
    vec3 q_6 = (vec3(rel_1.x, (rel_1.y + _e10), rel_1.z) * 0.001);
    float r_17 = length(q_6);
    vec4 _e21 = _group_0_binding_0_cs.sun_direction;
    vec3 _e24 = sun_transmittance(r_17, dot((q_6 / vec3(r_17)), _e21.xyz));
    return _e24;
}

float sky_ambient_x(float mu_8) {
    return (0.5 + ((0.5 * sign(mu_8)) * sqrt(abs(mu_8))));
}

vec3 sky_ambient_light(float h, vec3 rel_2) {
    float _e7 = _group_0_binding_0_cs.atmosphere.x;
    vec3 q_7 = vec3(rel_2.x, (rel_2.y + _e7), rel_2.z);
    vec4 _e14 = _group_0_binding_0_cs.sun_direction;
    float _e17 = sky_ambient_x(dot(normalize(q_7), _e14.xyz));
    uvec2 size_2 = uvec2(64u, 2u);
    vec4 _e24 = lut_bilinear(_group_0_binding_31_cs, vec2(_e17, 0.0), size_2);
    vec3 bottom_1 = _e24.xyz;
    vec4 _e29 = lut_bilinear(_group_0_binding_31_cs, vec2(_e17, 1.0), size_2);
    vec3 top_1 = _e29.xyz;
    vec4 _e34 = _group_0_binding_0_cs.sun_illuminance;
    float _e40 = _group_0_binding_0_cs.ambient_bottom.w;
    return ((mix(bottom_1, top_1, h) * _e34.xyz) * _e40);
}

float layer_height(Layer l_1, float alt_7) {
    return ((alt_7 - l_1.bottom) / (l_1.top - l_1.bottom));
}

uint layer_at(float alt_8) {
    uint i_9 = 0u;
    bool local_22 = false;
    bool loop_init_3 = true;
    while(true) {
        if (!loop_init_3) {
            uint _e19 = i_9;
            i_9 = (_e19 + 1u);
        }
        loop_init_3 = false;
        uint _e3 = i_9;
        uint _e4 = layer_count();
        if ((_e3 < _e4)) {
        } else {
            break;
        }
        {
            uint _e6 = i_9;
            Layer _e7 = cloud_layer(_e6);
            float _e8 = layer_height(_e7, alt_8);
            if ((_e8 >= 0.0)) {
                local_22 = (_e8 <= 1.0);
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

Weather sample_weather(vec3 p_3, Layer l_2) {
    float _e8 = _group_0_binding_0_cs.periods.x;
    vec2 uv_2 = ((p_3.xz - l_2.weather_offset) / vec2(_e8));
    vec4 w_4 = textureLod(_group_0_binding_3_cs, vec2(uv_2), 0.0);
    float _e22 = saturate((w_4.x + (2.0 * (l_2.coverage - 0.5))));
    float _e30 = saturate((l_2.cloud_type + ((w_4.z - 0.5) * 0.5)));
    float _e35 = saturate((0.5 + w_4.y));
    float precipitation = (l_2.precipitation * _e35);
    return Weather(_e22, _e30, precipitation);
}

float height_parabola(float h_1, float cloud_type) {
    float height = mix(0.35, 1.0, cloud_type);
    float _e11 = saturate(((h_1 * (h_1 - height)) * (-4.0 / (height * height))));
    return _e11;
}

float gradient(float h_2, float r0_, float r1_, float f0_, float f1_) {
    return (smoothstep(r0_, r1_, h_2) * (1.0 - smoothstep(f0_, f1_, h_2)));
}

float height_cloud_types(float h_3, float cloud_type_1) {
    float _e6 = gradient(h_3, 0.0, 0.08, 0.15, 0.25);
    float _e11 = gradient(h_3, 0.0, 0.2, 0.4, 0.65);
    float _e16 = gradient(h_3, 0.0, 0.1, 0.6, 0.95);
    float _e19 = saturate((cloud_type_1 * 2.0));
    float lo = mix(_e6, _e11, _e19);
    float _e25 = saturate(((cloud_type_1 * 2.0) - 1.0));
    return mix(lo, _e16, _e25);
}

float height_signal(float h_4, float cloud_type_2) {
    uint _e5 = _group_0_binding_0_cs.modes.z;
    if ((_e5 == HEIGHT_CLOUD_TYPES)) {
        float _e8 = height_cloud_types(h_4, cloud_type_2);
        return _e8;
    }
    float _e9 = height_parabola(h_4, cloud_type_2);
    return _e9;
}

float layer_density_with(vec3 p_4, float alt_9, Layer l_3, bool with_detail, inout Counters counters_3) {
    bool local_23 = false;
    bool local_24 = false;
    float base = 0.0;
    float density = 0.0;
    bool local_25 = false;
    bool local_26 = false;
    bool local_27 = false;
    vec3 detail_pos = vec3(0.0);
    float _e5 = layer_height(l_3, alt_9);
    if (!((_e5 < 0.0))) {
        local_23 = (_e5 > 1.0);
    } else {
        local_23 = true;
    }
    bool _e14 = local_23;
    if (_e14) {
        return 0.0;
    }
    uint _e17 = counters_3.density;
    counters_3.density = (_e17 + 1u);
    Weather _e20 = sample_weather(p_4, l_3);
    float _e22 = height_signal(_e5, _e20.cloud_type);
    if (!((_e20.coverage <= 0.0))) {
        local_24 = (_e22 <= 0.0);
    } else {
        local_24 = true;
    }
    bool _e32 = local_24;
    if (_e32) {
        return 0.0;
    }
    vec3 dims = vec3(uvec3(textureSize(_group_0_binding_1_cs, 0).xyz));
    float _e40 = _group_0_binding_0_cs.periods.y;
    vec3 period = (_e40 * vec3(1.0, (dims.y / dims.x), 1.0));
    float _e52 = _group_0_binding_0_cs.wind_offsets0_.z;
    float _e58 = _group_0_binding_0_cs.wind_offsets0_.w;
    vec3 shape_pos = vec3((p_4.x - _e52), alt_9, (p_4.z - _e58));
    vec4 s_6 = textureLod(_group_0_binding_1_cs, vec3((shape_pos / period)), 0.0);
    float low_fbm = (((s_6.y * 0.625) + (s_6.z * 0.25)) + (s_6.w * 0.125));
    float _e83 = remap(s_6.x, (low_fbm - 1.0), 1.0, 0.0, 1.0);
    float _e84 = saturate(_e83);
    base = (_e84 * _e22);
    float _e87 = base;
    float _e94 = remap(_e87, (1.0 - _e20.coverage), 1.0, 0.0, 1.0);
    float _e95 = saturate(_e94);
    base = (_e95 * _e20.coverage);
    float _e98 = base;
    if ((_e98 <= 0.0)) {
        return 0.0;
    }
    float _e102 = base;
    density = _e102;
    float strength = _group_0_binding_0_cs.erosion.x;
    float threshold = _group_0_binding_0_cs.erosion.y;
    if (DETAIL) {
        local_25 = with_detail;
    } else {
        local_25 = false;
    }
    bool _e116 = local_25;
    if (_e116) {
        local_26 = (strength > 0.0);
    } else {
        local_26 = false;
    }
    bool _e122 = local_26;
    if (_e122) {
        float _e125 = base;
        local_27 = (_e125 < threshold);
    } else {
        local_27 = false;
    }
    bool _e128 = local_27;
    if (_e128) {
        uint _e130 = counters_3.detail;
        counters_3.detail = (_e130 + 1u);
        detail_pos = vec3(p_4.x, alt_9, p_4.z);
        if (CURL) {
            vec4 _e141 = _group_0_binding_0_cs.wind_offsets1_;
            float _e147 = _group_0_binding_0_cs.periods.w;
            vec2 cuv = ((p_4.xz - _e141.zw) / vec2(_e147));
            vec4 _e153 = textureLod(_group_0_binding_4_cs, vec2(cuv), 0.0);
            vec2 curl = ((_e153.xy * 2.0) - vec2(1.0));
            vec3 _e160 = detail_pos;
            float _e168 = _group_0_binding_0_cs.erosion.z;
            detail_pos = (_e160 + (vec3(curl.x, 0.0, curl.y) * (_e168 * (1.0 - _e5))));
        }
        vec3 _e174 = detail_pos;
        float _e178 = _group_0_binding_0_cs.wind_offsets1_.x;
        float _e182 = _group_0_binding_0_cs.wind_offsets1_.y;
        detail_pos = (_e174 - vec3(_e178, 0.0, _e182));
        vec3 _e188 = detail_pos;
        float _e192 = _group_0_binding_0_cs.periods.z;
        vec4 dn = textureLod(_group_0_binding_2_cs, vec3((_e188 / vec3(_e192))), 0.0);
        float high_fbm = (((dn.x * 0.625) + (dn.y * 0.25)) + (dn.z * 0.125));
        float _e211 = _group_0_binding_0_cs.extinction.w;
        float _e216 = saturate((_e5 * 10.0));
        float _e218 = saturate(((2.0 * _e211) * _e216));
        float shape = mix((1.0 - high_fbm), high_fbm, _e218);
        float _e223 = base;
        float erosion = ((strength * shape) * (1.0 - (_e223 / threshold)));
        float _e228 = base;
        float _e232 = remap(_e228, erosion, 1.0, 0.0, 1.0);
        float _e233 = saturate(_e232);
        density = _e233;
    }
    float _e234 = density;
    float _e238 = _group_0_binding_0_cs.erosion.w;
    density = (_e234 * mix(1.0, _e5, _e238));
    float _e242 = density;
    density = ((_e242 * l_3.density) * (1.0 + _e20.precipitation));
    float _e249 = density;
    return clamp(_e249, 0.0, 1.0);
}

float layer_density(vec3 p_5, float alt_10, Layer l_4, inout Counters counters_4) {
    float _e5 = layer_density_with(p_5, alt_10, l_4, true, counters_4);
    return _e5;
}

float cloud_density(vec3 p_6, float alt_11, inout Counters counters_5) {
    uint _e3 = layer_at(alt_11);
    if ((_e3 == NO_LAYER)) {
        return 0.0;
    }
    Layer _e7 = cloud_layer(_e3);
    float _e8 = layer_density(p_6, alt_11, _e7, counters_5);
    return _e8;
}

float phase_hg(float cos_theta_2, float g_2) {
    float g2_1 = (g_2 * g_2);
    float denom = max(((1.0 + g2_1) - ((2.0 * g_2) * cos_theta_2)), 1e-6);
    return ((1.0 - g2_1) / ((12.566371 * denom) * sqrt(denom)));
}

float phase_cornette_shanks(float cos_theta_3, float g_3) {
    float g2_2 = (g_3 * g_3);
    float denom_1 = max(((1.0 + g2_2) - ((2.0 * g_3) * cos_theta_3)), 1e-6);
    return (((3.0 * (1.0 - g2_2)) * (1.0 + (cos_theta_3 * cos_theta_3))) / (((25.132742 * (2.0 + g2_2)) * denom_1) * sqrt(denom_1)));
}

float phase(float cos_theta_4, float scale) {
    float _e5 = _group_0_binding_0_cs.phase.x;
    float g_5 = (_e5 * scale);
    uint _e10 = _group_0_binding_0_cs.modes.x;
    switch(_e10) {
        case 1u: {
            float _e14 = _group_0_binding_0_cs.phase.y;
            float g2_3 = (_e14 * scale);
            float _e16 = phase_hg(cos_theta_4, g_5);
            float _e17 = phase_hg(cos_theta_4, g2_3);
            float _e21 = _group_0_binding_0_cs.phase.z;
            return mix(_e16, _e17, _e21);
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

float segment_optical_depth(vec3 rel_3, vec3 p_7, Layer l_5, vec3 d_13, float first, float growth, uint steps_1, bool with_detail_1, inout Counters counters_6) {
    float seg = 0.0;
    float dist = 0.0;
    float tau_4 = 0.0;
    uint i_10 = 0u;
    bool local_28 = false;
    float _e12 = _group_0_binding_0_cs.extinction.x;
    float _e16 = _group_0_binding_0_cs.extinction.y;
    float sigma_t_1 = (_e12 + _e16);
    seg = first;
    bool loop_init_4 = true;
    while(true) {
        if (!loop_init_4) {
            uint _e62 = i_10;
            i_10 = (_e62 + 1u);
        }
        loop_init_4 = false;
        uint _e25 = i_10;
        if ((_e25 < steps_1)) {
        } else {
            break;
        }
        {
            float _e27 = dist;
            float _e28 = seg;
            float s_7 = (_e27 + (0.5 * _e28));
            float _e34 = altitude_of((rel_3 + (d_13 * s_7)));
            if (!((_e34 > l_5.top))) {
                local_28 = (_e34 < l_5.bottom);
            } else {
                local_28 = true;
            }
            bool _e43 = local_28;
            if (_e43) {
                break;
            }
            uint _e45 = counters_6.light;
            counters_6.light = (_e45 + 1u);
            float _e48 = tau_4;
            float _e51 = layer_density_with((p_7 + (d_13 * s_7)), _e34, l_5, with_detail_1, counters_6);
            float _e53 = seg;
            tau_4 = (_e48 + ((_e51 * sigma_t_1) * _e53));
            float _e56 = dist;
            float _e57 = seg;
            dist = (_e56 + _e57);
            float _e59 = seg;
            seg = (_e59 * growth);
        }
    }
    float _e64 = tau_4;
    return _e64;
}

float sun_optical_depth(vec3 rel_4, vec3 p_8, Layer l_6, inout Counters counters_7) {
    float tau_5 = 0.0;
    uint j_1 = 0u;
    bool local_29 = false;
    bool local_30 = false;
    bool local_31 = false;
    vec4 _e6 = _group_0_binding_0_cs.sun_direction;
    vec3 sun_3 = _e6.xyz;
    float _e11 = _group_0_binding_0_cs.extinction.x;
    float _e15 = _group_0_binding_0_cs.extinction.y;
    float sigma_t_2 = (_e11 + _e15);
    float _e20 = _group_0_binding_0_cs.march.z;
    float _e24 = _group_0_binding_0_cs.march.y;
    uint _e28 = _group_0_binding_0_cs.counts.w;
    float _e30 = segment_optical_depth(rel_4, p_8, l_6, sun_3, _e20, _e24, _e28, true, counters_7);
    tau_5 = _e30;
    float _e32 = altitude_of(rel_4);
    bool loop_init_5 = true;
    while(true) {
        if (!loop_init_5) {
            uint _e96 = j_1;
            j_1 = (_e96 + 1u);
        }
        loop_init_5 = false;
        uint _e35 = j_1;
        uint _e36 = layer_count();
        if ((_e35 < _e36)) {
        } else {
            break;
        }
        {
            uint _e38 = j_1;
            Layer _e39 = cloud_layer(_e38);
            if ((_e39.bottom <= l_6.top)) {
                continue;
            }
            Roots _e44 = ray_shell_from(rel_4, _e32, sun_3, _e39.bottom);
            Roots _e46 = ray_shell_from(rel_4, _e32, sun_3, _e39.top);
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
                local_31 = (_e44.t1_ <= 0.0);
            } else {
                local_31 = true;
            }
            bool _e72 = local_31;
            if (_e72) {
                continue;
            }
            float s_8 = (0.5 * (_e44.t1_ + _e46.t1_));
            uint _e79 = counters_7.light;
            counters_7.light = (_e79 + 1u);
            float _e82 = tau_5;
            float _e87 = altitude_of((rel_4 + (sun_3 * s_8)));
            float _e88 = layer_density((p_8 + (sun_3 * s_8)), _e87, _e39, counters_7);
            tau_5 = (_e82 + ((_e88 * sigma_t_2) * (_e46.t1_ - _e44.t1_)));
        }
    }
    float _e98 = tau_5;
    return _e98;
}

float octave_optical_depth(vec3 rel_5, vec3 p_9, Layer l_7, float tau_6, inout Counters counters_8) {
    bool local_32 = false;
    bool local_33 = false;
    bool local_34 = false;
    float _e10 = saturate(((l_7.coverage - 0.8) / 0.1));
    float _e14 = _group_0_binding_0_cs.octave_depth.x;
    float m_2 = (_e14 * _e10);
    if (!((_e10 < 0.001))) {
        local_32 = (m_2 <= 0.0);
    } else {
        local_32 = true;
    }
    bool _e24 = local_32;
    if (!(_e24)) {
        uint _e31 = _group_0_binding_0_cs.counts.w;
        local_33 = (_e31 == 0u);
    } else {
        local_33 = true;
    }
    bool _e35 = local_33;
    if (_e35) {
        return tau_6;
    }
    float _e41 = _group_0_binding_0_cs.atmosphere.x;
    vec3 up_1 = normalize(vec3(rel_5.x, (rel_5.y + _e41), rel_5.z));
    float _e46 = altitude_of(rel_5);
    Roots _e48 = ray_shell_from(rel_5, _e46, up_1, l_7.top);
    if (_e48.hit) {
        local_34 = (_e48.t1_ > 0.0);
    } else {
        local_34 = false;
    }
    bool _e57 = local_34;
    float len_1 = (_e57 ? _e48.t1_ : 0.0);
    float _e65 = segment_optical_depth(rel_5, p_9, l_7, up_1, (len_1 / 3.0), 1.0, COLUMN_STEPS, false, counters_8);
    float _e69 = _group_0_binding_0_cs.octave_depth.y;
    return mix(tau_6, (_e69 * _e65), m_2);
}

float far_optical_depth(vec3 rel_6, vec3 p_10, Layer l_8) {
    bool local_35 = false;
    float reach = 0.0;
    bool local_36 = false;
    float tau_7 = 0.0;
    uint i_11 = 0u;
    float chord = _group_0_binding_0_cs.light_model.z;
    if (!((chord <= 0.0))) {
        uint _e15 = _group_0_binding_0_cs.counts.w;
        local_35 = (_e15 == 0u);
    } else {
        local_35 = true;
    }
    bool _e19 = local_35;
    if (_e19) {
        return 0.0;
    }
    float growth_1 = _group_0_binding_0_cs.march.y;
    uint _e28 = _group_0_binding_0_cs.counts.w;
    float steps_3 = float(_e28);
    float _e33 = _group_0_binding_0_cs.march.z;
    reach = (_e33 * steps_3);
    if ((growth_1 != 1.0)) {
        float _e41 = _group_0_binding_0_cs.march.z;
        reach = ((_e41 * (pow(growth_1, steps_3) - 1.0)) / (growth_1 - 1.0));
    }
    vec4 _e51 = _group_0_binding_0_cs.sun_direction;
    vec3 sun_4 = _e51.xyz;
    float _e53 = altitude_of(rel_6);
    Roots _e55 = ray_shell_from(rel_6, _e53, sun_4, l_8.top);
    float _e57 = reach;
    float len_2 = (_e55.t1_ - _e57);
    if (!(!(_e55.hit))) {
        local_36 = !((len_2 > 0.0));
    } else {
        local_36 = true;
    }
    bool _e68 = local_36;
    if (_e68) {
        return 0.0;
    }
    bool loop_init_6 = true;
    while(true) {
        if (!loop_init_6) {
            uint _e110 = i_11;
            i_11 = (_e110 + 1u);
        }
        loop_init_6 = false;
        uint _e74 = i_11;
        if ((_e74 < 4u)) {
        } else {
            break;
        }
        {
            float _e77 = reach;
            uint _e78 = i_11;
            float t_5 = (_e77 + (((float(_e78) + 0.5) * 0.25) * len_2));
            float _e88 = altitude_of((rel_6 + (sun_4 * t_5)));
            float _e89 = layer_height(l_8, _e88);
            float _e90 = saturate(_e89);
            Weather _e93 = sample_weather((p_10 + (sun_4 * t_5)), l_8);
            float cov = _e93.coverage;
            float _e96 = height_signal(_e90, l_8.cloud_type);
            float f_2 = min((cov * _e96), 0.95);
            float _e100 = tau_7;
            tau_7 = (_e100 + (((0.25 * len_2) * f_2) / ((1.0 - f_2) * chord)));
        }
    }
    float _e112 = tau_7;
    return _e112;
}

float diffuse_limb(float view_y, float coverage) {
    float k_12 = _group_0_binding_0_cs.light_model.w;
    float layer = ((1.0 + (k_12 * abs(view_y))) / (1.0 + ((2.0 * k_12) / 3.0)));
    float _e17 = saturate(coverage);
    return mix(1.0, layer, _e17);
}

float vertical_anisotropy(float view_y_1, float coverage_1, float h_5) {
    float _e6 = _group_0_binding_0_cs.octave_direction.z;
    float _e8 = saturate(coverage_1);
    float _e10 = saturate(h_5);
    return (1.0 + (((_e6 * view_y_1) * _e8) * (1.0 - _e10)));
}

float deck_escape(float mu0_, float layer_coverage) {
    float e = _group_0_binding_0_cs.octave_direction.w;
    float _e6 = saturate(layer_coverage);
    return (1.0 + ((e * pow(_e6, DECK_POWER)) * (mu0_ - 0.5)));
}

float downward_dimming(float view_y_2, float coverage_2, float h_6, float tau_v) {
    float _e7 = _group_0_binding_0_cs.octave_depth.z;
    float _e12 = saturate(coverage_2);
    float _e14 = saturate(h_6);
    float k_13 = (((_e7 * max(-(view_y_2), 0.0)) * _e12) * (1.0 - _e14));
    return max((1.0 - ((k_13 * tau_v) / (tau_v + 1.0))), 0.0);
}

SunScattering sun_scattering(float cos_theta_5, float view_y_3, float tau_8, float tau_oct, float far_1, float build, float coverage_3, float h_7, float layer_coverage_1) {
    float octave_sum = 0.0;
    float ka = 1.0;
    float kb = 1.0;
    float kc = 1.0;
    uint i_12 = 0u;
    float feed = 0.0;
    float octaves_part = 0.0;
    float total = 0.0;
    float a_7 = _group_0_binding_0_cs.multiple_scattering.x;
    float b_7 = _group_0_binding_0_cs.multiple_scattering.y;
    float c_8 = _group_0_binding_0_cs.multiple_scattering.z;
    uint _e24 = _group_0_binding_0_cs.misc.x;
    uint octaves = min(_e24, MAX_OCTAVES);
    bool loop_init_7 = true;
    while(true) {
        if (!loop_init_7) {
            uint _e57 = i_12;
            i_12 = (_e57 + 1u);
        }
        loop_init_7 = false;
        uint _e37 = i_12;
        if ((_e37 < octaves)) {
        } else {
            break;
        }
        {
            float _e39 = ka;
            ka = (_e39 * a_7);
            float _e41 = kb;
            kb = (_e41 * b_7);
            float _e43 = kc;
            kc = (_e43 * c_8);
            float _e45 = octave_sum;
            float _e46 = ka;
            float _e47 = kc;
            float _e48 = phase(cos_theta_5, _e47);
            float _e50 = kb;
            octave_sum = (_e45 + ((_e46 * _e48) / (1.0 + (_e50 * tau_oct))));
        }
    }
    float _e62 = _group_0_binding_0_cs.sun_direction.y;
    float _e63 = saturate(_e62);
    float _e70 = saturate(coverage_3);
    float side = ((sqrt(max((1.0 - (_e63 * _e63)), 0.0)) * (1.0 - _e70)) * exp(-(far_1)));
    float _e80 = _group_0_binding_0_cs.light_model.x;
    feed = (_e63 + (_e80 * side));
    float _e87 = _group_0_binding_0_cs.light_model.y;
    if ((_e87 > 0.0)) {
        float _e90 = feed;
        float _e96 = _group_0_binding_0_cs.light_model.y;
        feed = (_e90 * pow(max(coverage_3, 1e-6), _e96));
    }
    float _e99 = feed;
    float _e100 = diffuse_limb(view_y_3, coverage_3);
    float _e101 = vertical_anisotropy(view_y_3, coverage_3, h_7);
    float _e103 = deck_escape(_e63, layer_coverage_1);
    feed = (_e99 * ((_e100 * _e101) * _e103));
    float _e106 = feed;
    float _e108 = downward_dimming(view_y_3, coverage_3, h_7, (tau_8 * _e63));
    feed = (_e106 * _e108);
    float _e110 = feed;
    float _e112 = octave_sum;
    octaves_part = ((_e110 * build) * _e112);
    float _e116 = phase(cos_theta_5, 1.0);
    float _e121 = octaves_part;
    total = ((_e116 * exp((-(tau_8) - far_1))) + _e121);
    uint _e127 = _group_0_binding_0_cs.modes.w;
    if (((_e127 & FLAG_BEER_POWDER) != 0u)) {
        float _e135 = _group_0_binding_0_cs.phase.w;
        float powder = (1.0 - exp((-(_e135) * tau_8)));
        float _e141 = total;
        total = (_e141 * powder);
        float _e143 = octaves_part;
        octaves_part = (_e143 * powder);
    }
    float _e145 = total;
    float _e146 = octaves_part;
    return SunScattering(_e145, _e146);
}

float forward_lobe(float cos_theta_6, float transmittance) {
    float k_14 = _group_0_binding_0_cs.octave_direction.x;
    if ((k_14 <= 0.0)) {
        return 1.0;
    }
    float _e11 = saturate((transmittance / FORWARD_LOBE_THIN));
    float w_5 = (k_14 * _e11);
    float _e17 = _group_0_binding_0_cs.octave_direction.y;
    float _e18 = phase_hg(cos_theta_6, _e17);
    return (1.0 + (w_5 * ((12.566371 * _e18) - 1.0)));
}

float octave_buildup(float density_1) {
    float l_11 = _group_0_binding_0_cs.multiple_scattering.w;
    if ((l_11 <= 0.0)) {
        return 1.0;
    }
    float _e11 = _group_0_binding_0_cs.extinction.x;
    float _e15 = _group_0_binding_0_cs.extinction.y;
    return (1.0 - exp(((-((_e11 + _e15)) * density_1) * l_11)));
}

vec3 ambient(float h_8, vec3 rel_7) {
    bool _e2 = physical_sky();
    if (_e2) {
        vec3 _e3 = sky_ambient_light(h_8, rel_7);
        return _e3;
    }
    vec4 _e6 = _group_0_binding_0_cs.ambient_bottom;
    vec4 _e10 = _group_0_binding_0_cs.ambient_top;
    float _e16 = _group_0_binding_0_cs.ambient_bottom.w;
    return (mix(_e6.xyz, _e10.xyz, h_8) * _e16);
}

float height_fraction(float alt_12) {
    uint _e1 = layer_at(alt_12);
    Layer _e2 = cloud_layer(_e1);
    float _e3 = layer_height(_e2, alt_12);
    float _e4 = saturate(_e3);
    return _e4;
}

ScatteredLight scattered_light(vec3 rel_8, vec3 p_11, float alt_13, float density_2, vec3 view, Layer l_9, inout Counters counters_9) {
    vec3 sun_light = vec3(0.0);
    vec3 octave_light = vec3(0.0);
    float tau_9 = 0.0;
    float far_2 = 0.0;
    float tau_oct_1 = 0.0;
    vec4 _e9 = _group_0_binding_0_cs.sun_direction;
    vec3 sun_5 = _e9.xyz;
    float _e11 = layer_height(l_9, alt_13);
    float _e12 = saturate(_e11);
    Weather _e19 = sample_weather(p_11, l_9);
    bool _e20 = hits_ground(rel_8, alt_13, sun_5);
    if (!(_e20)) {
        if (LIGHT_MARCH) {
            float _e27 = sun_optical_depth(rel_8, p_11, l_9, counters_9);
            tau_9 = _e27;
            float _e28 = far_optical_depth(rel_8, p_11, l_9);
            far_2 = _e28;
        }
        float _e29 = tau_9;
        tau_oct_1 = _e29;
        if (LIGHT_MARCH) {
            float _e32 = tau_9;
            float _e33 = octave_optical_depth(rel_8, p_11, l_9, _e32, counters_9);
            tau_oct_1 = _e33;
        }
        float _e36 = tau_9;
        float _e37 = tau_oct_1;
        float _e38 = far_2;
        float _e39 = octave_buildup(density_2);
        SunScattering _e42 = sun_scattering(dot(view, sun_5), view.y, _e36, _e37, _e38, _e39, _e19.coverage, _e12, l_9.coverage);
        vec4 _e45 = _group_0_binding_0_cs.sun_illuminance;
        vec3 _e47 = sun_through_air(rel_8);
        vec3 lit = (_e45.xyz * _e47);
        sun_light = (lit * _e42.total);
        octave_light = (lit * _e42.octaves);
    }
    float _e56 = _group_0_binding_0_cs.extinction.z;
    float _e64 = saturate((1.0 - ((_e56 * _e19.precipitation) * (1.0 - _e12))));
    float _e68 = _group_0_binding_0_cs.extinction.x;
    float k_15 = ((_e68 * density_2) * _e64);
    vec3 _e71 = sun_light;
    vec3 _e72 = ambient(_e12, rel_8);
    vec3 _e75 = octave_light;
    return ScatteredLight(((_e71 + _e72) * k_15), (_e75 * k_15));
}

vec3 shadow_ground_point(uvec2 c_2) {
    vec2 xz_1 = ((((vec2(c_2) / vec2(127.0)) * 2.0) - vec2(1.0)) * SHADOW_HALF_EXTENT);
    float rp_4 = _group_0_binding_0_cs.atmosphere.x;
    float s2_ = dot(xz_1, xz_1);
    float y_1 = (-(s2_) / (sqrt(max(((rp_4 * rp_4) - s2_), 0.0)) + rp_4));
    return vec3(xz_1.x, y_1, xz_1.y);
}

float empty_cell_exit(vec3 p_12, vec3 d_14) {
    float exit = 1e30;
    vec4 _e6 = _group_0_binding_0_cs.wind_offsets0_;
    float _e12 = _group_0_binding_0_cs.periods.x;
    vec2 uv_3 = (fract(((p_12.xz - _e6.xy) / vec2(_e12))) * 64.0);
    uvec2 cell_1 = min(uvec2(uv_3), uvec2(63u));
    vec4 _e23 = texelFetch(_group_0_binding_11_cs, ivec2(cell_1), 0);
    float m_3 = _e23.x;
    float _e28 = _group_0_binding_0_cs.clouds.x;
    if (((m_3 + (2.0 * (_e28 - 0.5))) > -0.003921569)) {
        return 0.0;
    }
    float _e40 = _group_0_binding_0_cs.periods.x;
    float cell_m = (_e40 / 64.0);
    vec2 inside = ((uv_3 - vec2(cell_1)) * cell_m);
    if ((d_14.x > 1e-6)) {
        float _e50 = exit;
        exit = min(_e50, ((cell_m - inside.x) / d_14.x));
    } else {
        if ((d_14.x < -1e-6)) {
            float _e59 = exit;
            exit = min(_e59, (inside.x / -(d_14.x)));
        }
    }
    if ((d_14.z > 1e-6)) {
        float _e68 = exit;
        exit = min(_e68, ((cell_m - inside.y) / d_14.z));
    } else {
        if ((d_14.z < -1e-6)) {
            float _e77 = exit;
            exit = min(_e77, (inside.y / -(d_14.z)));
        }
    }
    float _e83 = exit;
    return max(_e83, 0.0);
}

void count(uint index_1, uint value) {
    bool local_37 = false;
    if (STATS) {
        local_37 = (value != 0u);
    } else {
        local_37 = false;
    }
    bool _e8 = local_37;
    if (_e8) {
        uint _e12 = atomicAdd(_group_0_binding_8_cs.counters[index_1], value);
        return;
    } else {
        return;
    }
}

vec3 step_integral(vec3 source, float sigma_t, float dt) {
    uint _e6 = _group_0_binding_0_cs.modes.y;
    if ((_e6 == INTEGRATION_RIEMANN)) {
        return (source * dt);
    }
    float x_8 = (sigma_t * dt);
    float f_3 = ((x_8 < 0.001) ? (1.0 - (0.5 * x_8)) : ((1.0 - exp(-(x_8))) / x_8));
    return (source * (dt * f_3));
}

float start_offset(uvec2 pixel_3) {
    uint _e4 = _group_0_binding_0_cs.modes.w;
    bool jitter_1 = ((_e4 & FLAG_JITTER) != 0u);
    uint k_16 = _group_0_binding_0_cs.temporal.x;
    if ((k_16 <= 1u)) {
        uint _e18 = _group_0_binding_0_cs.misc.y;
        float _e19 = hash_unit(pixel_3, _e18);
        return (jitter_1 ? _e19 : 0.5);
    }
    float _e23 = hash_unit(pixel_3, 0u);
    float base_2 = (jitter_1 ? _e23 : 0.5);
    uint _e29 = _group_0_binding_0_cs.misc.y;
    float _e32 = van_der_corput((_e29 / (k_16 * k_16)));
    return fract((base_2 + _e32));
}

bool march_layer(vec3 view_2, Interval span_1, Layer l_10, float jitter, inout MarchState state, inout Counters counters_10) {
    uint steps_2 = 0u;
    uint i_13 = 0u;
    uint stride = 1u;
    uint empty = 0u;
    bool local_38 = false;
    float cam_alt = _group_0_binding_0_cs.camera_position.y;
    vec4 _e12 = _group_0_binding_0_cs.camera_position;
    vec2 cam_xz = _e12.xz;
    uint _e17 = _group_0_binding_0_cs.counts.z;
    steps_2 = _e17;
    float _e22 = _group_0_binding_0_cs.march.x;
    if ((_e22 > 0.0)) {
        float _e29 = _group_0_binding_0_cs.march.x;
        steps_2 = min(max(uint(ceil((span_1.length_ / _e29))), 1u), MAX_VIEW_STEPS);
    }
    uint _e37 = steps_2;
    float dt_2 = (span_1.length_ / float(_e37));
    float _e43 = _group_0_binding_0_cs.extinction.x;
    float _e47 = _group_0_binding_0_cs.extinction.y;
    float sigma_e = (_e43 + _e47);
    uint _e52 = _group_0_binding_0_cs.modes.w;
    bool dynamic_step = ((_e52 & FLAG_DYNAMIC_STEP) != 0u);
    uint _e60 = _group_0_binding_0_cs.modes.w;
    bool empty_skip = ((_e60 & FLAG_EMPTY_SKIP) != 0u);
    while(true) {
        uint _e71 = i_13;
        uint _e72 = steps_2;
        if ((_e71 >= _e72)) {
            break;
        }
        uint _e75 = counters_10.view_steps;
        counters_10.view_steps = (_e75 + 1u);
        uint _e79 = i_13;
        float t_6 = (span_1.start + ((float(_e79) + jitter) * dt_2));
        vec3 rel_12 = ((view_2 * t_6) + vec3(0.0, cam_alt, 0.0));
        vec3 p_17 = vec3((rel_12.x + cam_xz.x), rel_12.y, (rel_12.z + cam_xz.y));
        if (empty_skip) {
            float _e97 = empty_cell_exit(p_17, view_2);
            if ((_e97 > 0.0)) {
                uint _e106 = steps_2;
                uint next_1 = uint(clamp(ceil(((((t_6 + _e97) - span_1.start) / dt_2) - jitter)), 0.0, float(_e106)));
                uint _e111 = i_13;
                i_13 = max((_e111 + 1u), next_1);
                continue;
            }
        }
        float _e115 = altitude_of(rel_12);
        float _e116 = layer_density(p_17, _e115, l_10, counters_10);
        if ((_e116 <= 0.0)) {
            uint _e119 = empty;
            empty = (_e119 + 1u);
            if (dynamic_step) {
                uint _e124 = empty;
                local_38 = (_e124 >= 8u);
            } else {
                local_38 = false;
            }
            bool _e128 = local_38;
            if (_e128) {
                stride = 2u;
            }
            uint _e130 = i_13;
            uint _e131 = stride;
            i_13 = (_e130 + _e131);
            continue;
        }
        uint _e133 = stride;
        if ((_e133 > 1u)) {
            uint _e136 = i_13;
            uint _e137 = stride;
            i_13 = (_e136 - (_e137 - 1u));
            stride = 1u;
            empty = 0u;
            continue;
        }
        empty = 0u;
        float sigma_t_3 = (sigma_e * _e116);
        ScatteredLight _e145 = scattered_light(rel_12, p_17, _e115, _e116, view_2, l_10, counters_10);
        float transmittance_2 = state.transmittance;
        vec3 _e149 = state.radiance;
        vec3 _e151 = step_integral(_e145.total, sigma_t_3, dt_2);
        state.radiance = (_e149 + (transmittance_2 * _e151));
        vec3 _e155 = state.octaves;
        vec3 _e157 = step_integral(_e145.octaves, sigma_t_3, dt_2);
        state.octaves = (_e155 + (transmittance_2 * _e157));
        float step_t = exp((-(sigma_t_3) * dt_2));
        float _e164 = state.depth_sum;
        state.depth_sum = (_e164 + ((t_6 * transmittance_2) * (1.0 - step_t)));
        state.transmittance = (transmittance_2 * step_t);
        float _e173 = state.transmittance;
        float _e177 = _group_0_binding_0_cs.march.w;
        if ((_e173 < _e177)) {
            return true;
        }
        uint _e180 = i_13;
        i_13 = (_e180 + 1u);
    }
    return false;
}

MarchResult march_pixel(uvec2 pixel_4) {
    Counters counters_11 = Counters(0u, 0u, 0u, 0u);
    MarchState state_1 = MarchState(vec3(0.0), 1.0, 0.0, vec3(0.0));
    bool marched = false;
    bool ground_1 = false;
    float last_start = -1.0;
    uint last_index = NO_LAYER;
    bool exited = false;
    uint k_6 = 0u;
    uint next = 0u;
    Interval span_2 = Interval(0.0, 0.0, 0u);
    uint i_14 = 0u;
    bool local_39 = false;
    bool local_40 = false;
    bool local_41 = false;
    bool local_42 = false;
    bool local_43 = false;
    bool local_44 = false;
    float depth_1 = 0.0;
    vec3 _e1 = view_ray(pixel_4);
    float cam_alt_1 = _group_0_binding_0_cs.camera_position.y;
    count(STAT_PIXELS, 1u);
    float _e22 = start_offset(pixel_4);
    uint _e23 = layer_count();
    bool loop_init_8 = true;
    while(true) {
        if (!loop_init_8) {
            uint _e121 = k_6;
            k_6 = (_e121 + 1u);
        }
        loop_init_8 = false;
        uint _e36 = k_6;
        if ((_e36 < _e23)) {
        } else {
            break;
        }
        {
            next = NO_LAYER;
            span_2 = Interval(0.0, 0.0, 1u);
            i_14 = 0u;
            bool loop_init_9 = true;
            while(true) {
                if (!loop_init_9) {
                    uint _e104 = i_14;
                    i_14 = (_e104 + 1u);
                }
                loop_init_9 = false;
                uint _e47 = i_14;
                if ((_e47 < _e23)) {
                } else {
                    break;
                }
                {
                    uint _e49 = i_14;
                    Layer _e50 = cloud_layer(_e49);
                    Interval _e51 = layer_interval(cam_alt_1, _e1, _e50);
                    bool _e52 = ground_1;
                    if (!(_e52)) {
                        local_39 = (_e51.kind == RAY_HITS_GROUND);
                    } else {
                        local_39 = true;
                    }
                    bool _e60 = local_39;
                    ground_1 = _e60;
                    float _e62 = last_start;
                    if (!((_e51.start > _e62))) {
                        float _e68 = last_start;
                        if ((_e51.start == _e68)) {
                            uint _e72 = i_14;
                            uint _e73 = last_index;
                            local_41 = (_e72 > _e73);
                        } else {
                            local_41 = false;
                        }
                        bool _e76 = local_41;
                        local_40 = _e76;
                    } else {
                        local_40 = true;
                    }
                    bool after = local_40;
                    if ((_e51.kind == RAY_MARCH)) {
                        local_42 = after;
                    } else {
                        local_42 = false;
                    }
                    bool _e85 = local_42;
                    if (_e85) {
                        uint _e88 = next;
                        if (!((_e88 == NO_LAYER))) {
                            float _e96 = span_2.start;
                            local_44 = (_e51.start < _e96);
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
            if ((_e106 == NO_LAYER)) {
                break;
            }
            marched = true;
            float _e111 = span_2.start;
            last_start = _e111;
            uint _e112 = next;
            last_index = _e112;
            Interval _e113 = span_2;
            uint _e114 = next;
            Layer _e115 = cloud_layer(_e114);
            bool _e116 = march_layer(_e1, _e113, _e115, _e22, state_1, counters_11);
            if (_e116) {
                count(STAT_EXIT_TRANSMITTANCE, 1u);
                exited = true;
                break;
            }
        }
    }
    bool _e123 = marched;
    if (_e123) {
        count(STAT_MARCHED, 1u);
    } else {
        bool _e126 = ground_1;
        if (_e126) {
            count(STAT_EXIT_GROUND, 1u);
        } else {
            count(STAT_EXIT_MISSED, 1u);
        }
    }
    uint _e133 = counters_11.view_steps;
    count(STAT_VIEW_STEPS, _e133);
    uint _e136 = counters_11.density;
    count(STAT_DENSITY, _e136);
    uint _e139 = counters_11.detail;
    count(STAT_DETAIL, _e139);
    uint _e142 = counters_11.light;
    count(STAT_LIGHT, _e142);
    float _e146 = state_1.transmittance;
    if ((_e146 < 1.0)) {
        float _e150 = state_1.depth_sum;
        float _e152 = state_1.transmittance;
        depth_1 = (_e150 / (1.0 - _e152));
    }
    float _e157 = state_1.transmittance;
    bool _e158 = exited;
    float transmittance_3 = (_e158 ? 0.0 : _e157);
    vec4 _e163 = _group_0_binding_0_cs.sun_direction;
    float _e167 = state_1.transmittance;
    float _e168 = forward_lobe(dot(_e1, _e163.xyz), _e167);
    vec3 _e170 = state_1.radiance;
    vec3 _e172 = state_1.octaves;
    vec3 radiance_5 = (_e170 + (_e172 * (_e168 - 1.0)));
    float _e177 = depth_1;
    return MarchResult(radiance_5, transmittance_3, _e177);
}

uvec2 bayer2_(uint v_2) {
    return uvec2(((v_2 ^ (v_2 >> 1u)) & 1u), (v_2 & 1u));
}

uvec2 block_offset(uint f, uint k_7) {
    if ((k_7 == 2u)) {
        uvec2 _e6 = bayer2_((f % 4u));
        return _e6;
    }
    if ((k_7 == 4u)) {
        uint b_8 = (f % 16u);
        uvec2 _e13 = bayer2_((b_8 >> 2u));
        uvec2 _e17 = bayer2_((b_8 & 3u));
        return (_e13 + (2u * _e17));
    }
    return uvec2(0u);
}

vec2 reproject(uvec2 pixel_5, float depth_2) {
    bool local_45 = false;
    bool local_46 = false;
    bool local_47 = false;
    vec3 dir = vec3(0.0);
    vec4 _e4 = _group_0_binding_0_cs.previous_position;
    vec4 _e7 = _group_0_binding_0_cs.camera_position;
    if (all(equal(_e4, _e7))) {
        vec4 _e14 = _group_0_binding_0_cs.previous_forward;
        vec4 _e17 = _group_0_binding_0_cs.camera_forward;
        local_45 = all(equal(_e14, _e17));
    } else {
        local_45 = false;
    }
    bool _e21 = local_45;
    if (_e21) {
        vec4 _e26 = _group_0_binding_0_cs.previous_right;
        vec4 _e29 = _group_0_binding_0_cs.camera_right;
        local_46 = all(equal(_e26, _e29));
    } else {
        local_46 = false;
    }
    bool _e33 = local_46;
    if (_e33) {
        vec4 _e38 = _group_0_binding_0_cs.previous_up;
        vec4 _e41 = _group_0_binding_0_cs.camera_up;
        local_47 = all(equal(_e38, _e41));
    } else {
        local_47 = false;
    }
    bool same = local_47;
    if (same) {
        return vec2(pixel_5);
    }
    vec3 _e47 = view_ray(pixel_5);
    dir = _e47;
    if ((depth_2 > 0.0)) {
        vec4 _e54 = _group_0_binding_0_cs.camera_position;
        vec4 _e58 = _group_0_binding_0_cs.previous_position;
        dir = ((_e47 * depth_2) + (_e54.xyz - _e58.xyz));
    }
    vec3 _e62 = dir;
    vec4 _e65 = _group_0_binding_0_cs.previous_forward;
    float z_3 = dot(_e62, _e65.xyz);
    if ((z_3 <= 0.0)) {
        return vec2(-1000000000.0);
    }
    float tan_half_2 = _group_0_binding_0_cs.previous_position.w;
    float aspect_2 = _group_0_binding_0_cs.previous_forward.w;
    vec3 _e80 = dir;
    vec4 _e83 = _group_0_binding_0_cs.previous_right;
    vec3 _e89 = dir;
    vec4 _e92 = _group_0_binding_0_cs.previous_up;
    vec2 ndc_2 = vec2((dot(_e80, _e83.xyz) / ((z_3 * tan_half_2) * aspect_2)), (-(dot(_e89, _e92.xyz)) / (z_3 * tan_half_2)));
    uvec4 _e106 = _group_0_binding_0_cs.counts;
    return ((((ndc_2 * 0.5) + vec2(0.5)) * vec2(_e106.xy)) - vec2(0.5));
}

bool on_screen(vec2 q) {
    bool local_48 = false;
    uvec4 _e3 = _group_0_binding_0_cs.counts;
    vec2 size_3 = vec2(_e3.xy);
    if (all(greaterThanEqual(q, vec2(-0.5)))) {
        local_48 = all(lessThanEqual(q, (size_3 - vec2(0.5))));
    } else {
        local_48 = false;
    }
    bool _e18 = local_48;
    return _e18;
}

vec4 catmull_rom(float t_1) {
    return vec4((t_1 * (-0.5 + (t_1 * (1.0 - (0.5 * t_1))))), (1.0 + ((t_1 * t_1) * (-2.5 + (1.5 * t_1)))), (t_1 * (0.5 + (t_1 * (2.0 - (1.5 * t_1))))), ((t_1 * t_1) * (-0.5 + (0.5 * t_1))));
}

vec4 history_row(ivec2 base_1, int dy, vec4 wx) {
    uvec4 _e5 = _group_0_binding_0_cs.counts;
    ivec2 size_4 = ivec2(_e5.xy);
    int y_2 = min(max((base_1.y + dy), 0), (size_4.y - 1));
    int x0_ = min(max((base_1.x - 1), 0), (size_4.x - 1));
    int x1_ = min(max(base_1.x, 0), (size_4.x - 1));
    int x2_ = min(max((base_1.x + 1), 0), (size_4.x - 1));
    int x3_ = min(max((base_1.x + 2), 0), (size_4.x - 1));
    vec4 _e48 = texelFetch(_group_0_binding_13_cs, ivec2(x0_, y_2), 0);
    vec4 _e54 = texelFetch(_group_0_binding_13_cs, ivec2(x1_, y_2), 0);
    vec4 _e61 = texelFetch(_group_0_binding_13_cs, ivec2(x2_, y_2), 0);
    vec4 _e68 = texelFetch(_group_0_binding_13_cs, ivec2(x3_, y_2), 0);
    return ((((_e48 * wx.x) + (_e54 * wx.y)) + (_e61 * wx.z)) + (_e68 * wx.w));
}

vec4 history_at(vec2 q_1) {
    uvec4 _e3 = _group_0_binding_0_cs.counts;
    ivec2 size_5 = ivec2(_e3.xy);
    vec2 c_9 = clamp(q_1, vec2(0.0), vec2((size_5 - ivec2(1))));
    ivec2 base_3 = ivec2(floor(c_9));
    vec2 f_4 = (c_9 - vec2(base_3));
    vec4 _e18 = catmull_rom(f_4.x);
    vec4 _e20 = catmull_rom(f_4.y);
    vec4 _e22 = history_row(base_3, -1, _e18);
    vec4 _e26 = history_row(base_3, 0, _e18);
    vec4 _e31 = history_row(base_3, 1, _e18);
    vec4 _e36 = history_row(base_3, 2, _e18);
    vec4 sum_6 = ((((_e22 * _e20.x) + (_e26 * _e20.y)) + (_e31 * _e20.z)) + (_e36 * _e20.w));
    float _e45 = saturate(sum_6.w);
    return vec4(max(sum_6.xyz, vec3(0.0)), _e45);
}

vec4 history_nearest(vec2 q_2) {
    uvec4 _e3 = _group_0_binding_0_cs.counts;
    ivec2 size_6 = ivec2(_e3.xy);
    ivec2 p_18 = min(max(ivec2(roundEven(q_2)), ivec2(0)), (size_6 - ivec2(1)));
    vec4 _e16 = texelFetch(_group_0_binding_13_cs, p_18, 0);
    return _e16;
}

vec4 meta_at(vec2 q_3) {
    uvec4 _e3 = _group_0_binding_0_cs.counts;
    ivec2 size_7 = ivec2(_e3.xy);
    ivec2 p_19 = min(max(ivec2(roundEven(q_3)), ivec2(0)), (size_7 - ivec2(1)));
    vec4 _e16 = texelFetch(_group_0_binding_14_cs, p_19, 0);
    return _e16;
}

bool in_blocks(uvec2 id_19) {
    uint k_17 = _group_0_binding_0_cs.temporal.x;
    uvec4 _e7 = _group_0_binding_0_cs.counts;
    return all(lessThan(id_19, (((_e7.xy + uvec2(k_17)) - uvec2(1u)) / uvec2(k_17))));
}

uvec2 sparse_pixel(uvec2 id_20) {
    uint k_18 = _group_0_binding_0_cs.temporal.x;
    uint _e9 = _group_0_binding_0_cs.misc.y;
    uvec2 _e10 = block_offset(_e9, k_18);
    return ((id_20 * k_18) + _e10);
}

void store_sparse(uvec2 id_21, MarchResult r_13) {
    imageStore(_group_0_binding_6_cs, ivec2(id_21), vec4(r_13.radiance, r_13.transmittance));
    imageStore(_group_0_binding_7_cs, ivec2(id_21), vec4(r_13.depth, 0.0, 0.0, 0.0));
    return;
}

uint rng_seed(uvec2 pixel_6, uint path_index) {
    uint _e4 = pcg(path_index);
    uint _e6 = pcg((pixel_6.y ^ _e4));
    uint _e8 = pcg((pixel_6.x ^ _e6));
    return _e8;
}

float rng_next(inout uint rng_1) {
    uint _e1 = rng_1;
    rng_1 = ((_e1 * 747796405u) + 2891336453u);
    uint s_9 = rng_1;
    uint word_1 = (((s_9 >> ((s_9 >> 28u) + 4u)) ^ s_9) * 277803737u);
    return (float((((word_1 >> 22u) ^ word_1) >> 8u)) * 5.9604645e-8);
}

float rng_exponential(inout uint rng_2, float sigma) {
    float _e2 = rng_next(rng_2);
    return (-(log((1.0 - _e2))) / sigma);
}

Segments layer_segments(vec3 p_13, float alt_14, vec3 d_15) {
    Segments s_1 = Segments(vec2(0.0), vec2(0.0), 0u);
    bool local_49 = false;
    vec2 a_1 = vec2(0.0);
    vec2 b_1 = vec2(0.0);
    uint n_2 = 0u;
    bool local_50 = false;
    bool local_51 = false;
    bool local_52 = false;
    bool local_53 = false;
    vec2 _e10 = layers_span();
    float bottom_2 = _e10.x;
    Roots _e12 = ray_shell_from(p_13, alt_14, d_15, bottom_2);
    Roots _e14 = ray_shell_from(p_13, alt_14, d_15, _e10.y);
    bool _e15 = hits_ground(p_13, alt_14, d_15);
    if (!(!(_e14.hit))) {
        local_49 = (_e14.t1_ <= 0.0);
    } else {
        local_49 = true;
    }
    bool _e25 = local_49;
    if (_e25) {
        Segments _e26 = s_1;
        return _e26;
    }
    float entry = max(_e14.t0_, 0.0);
    if (_e12.hit) {
        local_50 = (_e12.t0_ > 0.0);
    } else {
        local_50 = false;
    }
    bool _e45 = local_50;
    if (_e45) {
        local_51 = (alt_14 >= bottom_2);
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
        n_2 = (_e56 + uint((_e12.t0_ > entry)));
        if (!(_e15)) {
            local_52 = (_e14.t1_ > _e12.t1_);
        } else {
            local_52 = false;
        }
        bool _e68 = local_52;
        if (_e68) {
            uint _e69 = n_2;
            a_1[_e69] = max(_e12.t1_, entry);
            uint _e73 = n_2;
            b_1[_e73] = _e14.t1_;
            uint _e76 = n_2;
            n_2 = (_e76 + 1u);
        }
    } else {
        if ((alt_14 < bottom_2)) {
            if (!(_e15)) {
                local_53 = _e12.hit;
            } else {
                local_53 = false;
            }
            bool _e85 = local_53;
            if (_e85) {
                a_1.x = max(_e12.t1_, 0.0);
                b_1.x = _e14.t1_;
                n_2 = 1u;
            }
        } else {
            a_1.x = entry;
            b_1.x = _e14.t1_;
            n_2 = 1u;
        }
    }
    vec2 _e98 = a_1;
    s_1.a = _e98;
    vec2 _e100 = b_1;
    s_1.b = _e100;
    uint _e102 = n_2;
    s_1.count = _e102;
    Segments _e103 = s_1;
    return _e103;
}

float density_at(vec3 rel_10, inout Counters counters_12) {
    float _e6 = _group_0_binding_0_cs.camera_position.x;
    float _e13 = _group_0_binding_0_cs.camera_position.z;
    vec3 p_20 = vec3((rel_10.x + _e6), rel_10.y, (rel_10.z + _e13));
    float _e16 = altitude_of(rel_10);
    float _e17 = cloud_density(p_20, _e16, counters_12);
    return _e17;
}

float empty_cell_skip(vec3 origin_4, vec3 dir_1, float t_2) {
    uint _e3 = layer_count();
    if ((_e3 > 1u)) {
        return 0.0;
    }
    vec3 rel_13 = (origin_4 + (dir_1 * t_2));
    float _e13 = _group_0_binding_0_cs.camera_position.x;
    float _e20 = _group_0_binding_0_cs.camera_position.z;
    vec3 p_21 = vec3((rel_13.x + _e13), rel_13.y, (rel_13.z + _e20));
    float _e23 = empty_cell_exit(p_21, dir_1);
    if ((_e23 <= 0.0)) {
        return 0.0;
    }
    return (_e23 + 0.05);
}

float density_max() {
    float m_1 = 0.0;
    uint i_15 = 0u;
    bool loop_init_10 = true;
    while(true) {
        if (!loop_init_10) {
            uint _e17 = i_15;
            i_15 = (_e17 + 1u);
        }
        loop_init_10 = false;
        uint _e4 = i_15;
        uint _e5 = layer_count();
        if ((_e4 < _e5)) {
        } else {
            break;
        }
        {
            uint _e7 = i_15;
            Layer _e8 = cloud_layer(_e7);
            float _e9 = m_1;
            m_1 = max(_e9, (_e8.density * (1.0 + _e8.precipitation)));
        }
    }
    float _e19 = m_1;
    return clamp(_e19, 0.0, 1.0);
}

float free_flight(vec3 origin_5, vec3 dir_2, Segments segs, inout uint rng_3, inout Counters counters_13) {
    uint k_8 = 0u;
    float t_3 = 0.0;
    float _e5 = density_max();
    float _e9 = _group_0_binding_0_cs.extinction.x;
    float _e13 = _group_0_binding_0_cs.extinction.y;
    float majorant = ((_e9 + _e13) * _e5);
    if ((majorant <= 0.0)) {
        return -1.0;
    }
    bool loop_init_11 = true;
    while(true) {
        if (!loop_init_11) {
            uint _e60 = k_8;
            k_8 = (_e60 + 1u);
        }
        loop_init_11 = false;
        uint _e21 = k_8;
        if ((_e21 < segs.count)) {
        } else {
            break;
        }
        {
            uint _e25 = k_8;
            t_3 = segs.a[_e25];
            while(true) {
                float _e28 = t_3;
                float _e29 = empty_cell_skip(origin_5, dir_2, _e28);
                if ((_e29 > 0.0)) {
                    float _e32 = t_3;
                    t_3 = (_e32 + _e29);
                    float _e34 = t_3;
                    uint _e36 = k_8;
                    if ((_e34 >= segs.b[_e36])) {
                        break;
                    }
                    continue;
                }
                float _e39 = t_3;
                float _e40 = rng_exponential(rng_3, majorant);
                t_3 = (_e39 + _e40);
                float _e42 = t_3;
                uint _e44 = k_8;
                if ((_e42 >= segs.b[_e44])) {
                    break;
                }
                uint _e48 = counters_13.view_steps;
                counters_13.view_steps = (_e48 + 1u);
                float _e51 = t_3;
                float _e54 = density_at((origin_5 + (dir_2 * _e51)), counters_13);
                float _e55 = rng_next(rng_3);
                if (((_e55 * _e5) < _e54)) {
                    float _e58 = t_3;
                    return _e58;
                }
            }
        }
    }
    return -1.0;
}

float transmittance_along(vec3 origin_6, vec3 dir_3, Segments segs_1, inout uint rng_4, inout Counters counters_14) {
    float tr = 1.0;
    uint k_9 = 0u;
    float t_4 = 0.0;
    float _e8 = _group_0_binding_0_cs.extinction.x;
    float _e12 = _group_0_binding_0_cs.extinction.y;
    float sigma_t_4 = (_e8 + _e12);
    float _e14 = density_max();
    float majorant_1 = (sigma_t_4 * _e14);
    if ((majorant_1 <= 0.0)) {
        return 1.0;
    }
    bool loop_init_12 = true;
    while(true) {
        if (!loop_init_12) {
            uint _e78 = k_9;
            k_9 = (_e78 + 1u);
        }
        loop_init_12 = false;
        uint _e23 = k_9;
        if ((_e23 < segs_1.count)) {
        } else {
            break;
        }
        {
            uint _e27 = k_9;
            t_4 = segs_1.a[_e27];
            while(true) {
                float _e30 = t_4;
                float _e31 = empty_cell_skip(origin_6, dir_3, _e30);
                if ((_e31 > 0.0)) {
                    float _e34 = t_4;
                    t_4 = (_e34 + _e31);
                    float _e36 = t_4;
                    uint _e38 = k_9;
                    if ((_e36 >= segs_1.b[_e38])) {
                        break;
                    }
                    continue;
                }
                float _e41 = t_4;
                float _e42 = rng_exponential(rng_4, majorant_1);
                t_4 = (_e41 + _e42);
                float _e44 = t_4;
                uint _e46 = k_9;
                if ((_e44 >= segs_1.b[_e46])) {
                    break;
                }
                uint _e50 = counters_14.light;
                counters_14.light = (_e50 + 1u);
                float _e53 = t_4;
                float _e56 = density_at((origin_6 + (dir_3 * _e53)), counters_14);
                float _e57 = tr;
                tr = (_e57 * (1.0 - ((sigma_t_4 * _e56) / majorant_1)));
                float _e63 = tr;
                if ((_e63 <= 0.0)) {
                    return 0.0;
                }
                float _e67 = tr;
                if ((_e67 < 0.01)) {
                    float _e70 = rng_next(rng_4);
                    if ((_e70 < 0.75)) {
                        return 0.0;
                    }
                    float _e74 = tr;
                    tr = (_e74 * 4.0);
                }
            }
        }
    }
    float _e80 = tr;
    return _e80;
}

float sample_hg_cos(float g_4, float u) {
    if ((abs(g_4) < 0.0001)) {
        return (1.0 - (2.0 * u));
    }
    float s_10 = ((1.0 - (g_4 * g_4)) / ((1.0 - g_4) + ((2.0 * g_4) * u)));
    return clamp((((1.0 + (g_4 * g_4)) - (s_10 * s_10)) / (2.0 * g_4)), -1.0, 1.0);
}

PhaseSample sample_phase(vec3 dir_4, inout uint rng_5) {
    float cos_theta_7 = 0.0;
    float pdf = 0.0;
    float _e2 = rng_next(rng_5);
    float _e3 = rng_next(rng_5);
    float _e5 = rng_next(rng_5);
    float phi_1 = (6.2831855 * _e5);
    uint _e14 = _group_0_binding_0_cs.modes.x;
    if ((_e14 == PHASE_TWO_LOBE_HG)) {
        float _e20 = _group_0_binding_0_cs.phase.x;
        float _e24 = _group_0_binding_0_cs.phase.y;
        float _e28 = _group_0_binding_0_cs.phase.z;
        float g_6 = ((_e2 < _e28) ? _e24 : _e20);
        float _e31 = sample_hg_cos(g_6, _e3);
        cos_theta_7 = _e31;
        float _e32 = cos_theta_7;
        float _e36 = _group_0_binding_0_cs.phase.x;
        float _e37 = phase_hg(_e32, _e36);
        float _e38 = cos_theta_7;
        float _e42 = _group_0_binding_0_cs.phase.y;
        float _e43 = phase_hg(_e38, _e42);
        float _e47 = _group_0_binding_0_cs.phase.z;
        pdf = mix(_e37, _e43, _e47);
    } else {
        float _e52 = _group_0_binding_0_cs.phase.x;
        float _e53 = sample_hg_cos(_e52, _e3);
        cos_theta_7 = _e53;
        float _e54 = cos_theta_7;
        float _e58 = _group_0_binding_0_cs.phase.x;
        float _e59 = phase_hg(_e54, _e58);
        pdf = _e59;
    }
    float _e60 = cos_theta_7;
    float _e61 = cos_theta_7;
    float sin_theta = sqrt(max((1.0 - (_e60 * _e61)), 0.0));
    float sign_ = ((dir_4.z >= 0.0) ? 1.0 : -1.0);
    float a_8 = (-1.0 / (sign_ + dir_4.z));
    float bb = ((dir_4.x * dir_4.y) * a_8);
    vec3 t_7 = vec3((1.0 + (((sign_ * dir_4.x) * dir_4.x) * a_8)), (sign_ * bb), (-(sign_) * dir_4.x));
    vec3 b_9 = vec3(bb, (sign_ + ((dir_4.y * dir_4.y) * a_8)), -(dir_4.y));
    float _e109 = cos_theta_7;
    vec3 w_6 = normalize((((t_7 * (sin_theta * cos(phi_1))) + (b_9 * (sin_theta * sin(phi_1)))) + (dir_4 * _e109)));
    float _e113 = cos_theta_7;
    float _e115 = phase(_e113, 1.0);
    float _e116 = pdf;
    float _e118 = pdf;
    return PhaseSample(w_6, ((_e118 > 0.0) ? (_e115 / _e116) : 0.0));
}

vec3 environment(vec3 pos, vec3 d_16, float h_9) {
    bool _e3 = physical_sky();
    if (_e3) {
        vec3 _e4 = sky_from(pos, d_16);
        vec4 _e7 = _group_0_binding_0_cs.sun_illuminance;
        float _e13 = _group_0_binding_0_cs.ambient_bottom.w;
        return ((_e4 * _e7.xyz) * _e13);
    }
    vec3 _e15 = ambient(h_9, pos);
    return _e15;
}

PathResult trace_path(vec3 view_3, Interval span_3, inout uint rng_6, inout Counters counters_15) {
    PathResult out_2 = PathResult(vec3(0.0), 1.0, -1.0);
    bool local_54 = false;
    bool local_55 = false;
    bool local_56 = false;
    uint max_orders = MAX_PATH_ORDERS;
    vec3 pos_1 = vec3(0.0);
    vec3 dir_5 = vec3(0.0);
    float throughput = 1.0;
    uint order = 0u;
    bool local_57 = false;
    if ((span_3.kind != RAY_MARCH)) {
        PathResult _e13 = out_2;
        return _e13;
    }
    float _e17 = _group_0_binding_0_cs.camera_position.y;
    vec3 cam = vec3(0.0, _e17, 0.0);
    Segments primary = Segments(vec2(span_3.start, 0.0), vec2((span_3.start + span_3.length_), 0.0), 1u);
    float _e32 = transmittance_along(cam, view_3, primary, rng_6, counters_15);
    out_2.transmittance = _e32;
    float _e33 = free_flight(cam, view_3, primary, rng_6, counters_15);
    if ((_e33 < 0.0)) {
        PathResult _e36 = out_2;
        return _e36;
    }
    out_2.depth = _e33;
    vec4 _e40 = _group_0_binding_0_cs.sun_direction;
    vec3 sun_6 = _e40.xyz;
    float _e45 = _group_0_binding_0_cs.extinction.x;
    float _e49 = _group_0_binding_0_cs.extinction.y;
    float sigma_t_5 = (_e45 + _e49);
    float _e54 = _group_0_binding_0_cs.extinction.x;
    float albedo = ((sigma_t_5 > 0.0) ? (_e54 / sigma_t_5) : 0.0);
    float _e63 = _group_0_binding_0_cs.ambient_bottom.w;
    if ((_e63 > 0.0)) {
        bool _e68 = physical_sky();
        if (!(_e68)) {
            vec4 _e74 = _group_0_binding_0_cs.ambient_bottom;
            local_55 = any(greaterThan(_e74.xyz, vec3(0.0)));
        } else {
            local_55 = true;
        }
        bool _e81 = local_55;
        if (!(_e81)) {
            vec4 _e87 = _group_0_binding_0_cs.ambient_top;
            local_56 = any(greaterThan(_e87.xyz, vec3(0.0)));
        } else {
            local_56 = true;
        }
        bool _e94 = local_56;
        local_54 = _e94;
    } else {
        local_54 = false;
    }
    bool ambient_on = local_54;
    uint _e102 = _group_0_binding_0_cs.misc.z;
    if ((_e102 > 0u)) {
        uint _e108 = _group_0_binding_0_cs.misc.z;
        max_orders = min(_e108, MAX_PATH_ORDERS);
    }
    pos_1 = (cam + (view_3 * _e33));
    dir_5 = view_3;
    while(true) {
        float _e119 = throughput;
        throughput = (_e119 * albedo);
        uint _e121 = order;
        order = (_e121 + 1u);
        vec3 _e124 = pos_1;
        float _e125 = altitude_of(_e124);
        float _e126 = height_fraction(_e125);
        vec3 _e127 = pos_1;
        bool _e128 = hits_ground(_e127, _e125, sun_6);
        if (!(_e128)) {
            vec3 _e130 = pos_1;
            vec3 _e131 = pos_1;
            Segments _e132 = layer_segments(_e131, _e125, sun_6);
            float _e133 = transmittance_along(_e130, sun_6, _e132, rng_6, counters_15);
            vec3 _e135 = out_2.radiance;
            vec4 _e138 = _group_0_binding_0_cs.sun_illuminance;
            vec3 _e140 = pos_1;
            vec3 _e141 = sun_through_air(_e140);
            float _e143 = throughput;
            vec3 _e144 = dir_5;
            float _e147 = phase(dot(_e144, sun_6), 1.0);
            out_2.radiance = (_e135 + ((_e138.xyz * _e141) * ((_e143 * _e147) * _e133)));
        }
        vec3 _e152 = dir_5;
        PhaseSample _e153 = sample_phase(_e152, rng_6);
        vec3 _e154 = pos_1;
        vec3 _e156 = pos_1;
        Segments _e158 = layer_segments(_e156, _e125, _e153.dir);
        float _e159 = free_flight(_e154, _e153.dir, _e158, rng_6, counters_15);
        if ((_e159 < 0.0)) {
            if (ambient_on) {
                vec3 _e163 = out_2.radiance;
                vec3 _e164 = pos_1;
                vec3 _e166 = environment(_e164, _e153.dir, _e126);
                float _e167 = throughput;
                out_2.radiance = (_e163 + (_e166 * (_e167 * _e153.weight)));
            }
            break;
        }
        uint _e172 = order;
        uint _e173 = max_orders;
        if ((_e172 >= _e173)) {
            break;
        }
        float _e175 = throughput;
        throughput = (_e175 * _e153.weight);
        dir_5 = _e153.dir;
        uint _e179 = order;
        if ((_e179 >= 3u)) {
            float _e184 = throughput;
            local_57 = (_e184 < 0.1);
        } else {
            local_57 = false;
        }
        bool _e188 = local_57;
        if (_e188) {
            float _e189 = rng_next(rng_6);
            float _e190 = throughput;
            if ((_e189 >= (_e190 / 0.1))) {
                break;
            }
            throughput = 0.1;
        }
        float _e195 = throughput;
        if ((_e195 <= 0.0)) {
            break;
        }
        vec3 _e198 = pos_1;
        vec3 _e199 = dir_5;
        pos_1 = (_e198 + (_e199 * _e159));
    }
    PathResult _e202 = out_2;
    return _e202;
}

bool camera_still() {
    bool local_58 = false;
    bool local_59 = false;
    bool local_60 = false;
    vec4 _e2 = _group_0_binding_0_cs.camera_position;
    vec4 _e5 = _group_0_binding_0_cs.previous_position;
    if (all(equal(_e2, _e5))) {
        vec4 _e12 = _group_0_binding_0_cs.camera_forward;
        vec4 _e15 = _group_0_binding_0_cs.previous_forward;
        local_58 = all(equal(_e12, _e15));
    } else {
        local_58 = false;
    }
    bool _e19 = local_58;
    if (_e19) {
        vec4 _e24 = _group_0_binding_0_cs.camera_right;
        vec4 _e28 = _group_0_binding_0_cs.previous_right;
        local_59 = all(equal(_e24.xyz, _e28.xyz));
    } else {
        local_59 = false;
    }
    bool _e33 = local_59;
    if (_e33) {
        vec4 _e38 = _group_0_binding_0_cs.camera_up;
        vec4 _e42 = _group_0_binding_0_cs.previous_up;
        local_60 = all(equal(_e38.xyz, _e42.xyz));
    } else {
        local_60 = false;
    }
    bool _e47 = local_60;
    return _e47;
}

float luminance(vec3 c_3) {
    return dot(c_3, vec3(0.2126, 0.7152, 0.0722));
}

float basic_sun_depth(vec3 rel_11, float alt_15, inout Counters counters_16) {
    float tau_10 = 0.0;
    uint i_16 = 1u;
    uint steps_4 = _group_0_binding_0_cs.counts.w;
    if ((steps_4 == 0u)) {
        return 0.0;
    }
    vec4 _e12 = _group_0_binding_0_cs.sun_direction;
    vec3 sun_7 = _e12.xyz;
    float rp_5 = _group_0_binding_0_cs.atmosphere.x;
    float top_2 = _group_0_binding_0_cs.atmosphere.z;
    float _e25 = _group_0_binding_0_cs.atmosphere.y;
    float thickness = (top_2 - _e25);
    Roots _e39 = solve_sphere(dot(sun_7, vec3(rel_11.x, (rel_11.y + rp_5), rel_11.z)), ((alt_15 - top_2) * ((alt_15 + top_2) + (2.0 * rp_5))));
    float length_ = min(max(_e39.t1_, 0.0), (3.0 * thickness));
    float dt_3 = (length_ / float(steps_4));
    float _e51 = _group_0_binding_0_cs.extinction.x;
    float _e55 = _group_0_binding_0_cs.extinction.y;
    float sigma_t_6 = (_e51 + _e55);
    vec4 _e59 = _group_0_binding_0_cs.camera_position;
    vec2 cam_xz_1 = _e59.xz;
    bool loop_init_13 = true;
    while(true) {
        if (!loop_init_13) {
            uint _e90 = i_16;
            i_16 = (_e90 + 1u);
        }
        loop_init_13 = false;
        uint _e65 = i_16;
        if ((_e65 <= steps_4)) {
        } else {
            break;
        }
        {
            uint _e68 = counters_16.light;
            counters_16.light = (_e68 + 1u);
            uint _e71 = i_16;
            vec3 q_8 = (rel_11 + (sun_7 * (float(_e71) * dt_3)));
            vec3 p_22 = vec3((q_8.x + cam_xz_1.x), q_8.y, (q_8.z + cam_xz_1.y));
            float _e84 = tau_10;
            float _e85 = altitude_of(q_8);
            float _e86 = cloud_density(p_22, _e85, counters_16);
            tau_10 = (_e84 + ((sigma_t_6 * _e86) * dt_3));
        }
    }
    float _e93 = tau_10;
    return _e93;
}

MarchResult basic_pixel(uvec2 pixel_7) {
    Counters counters_17 = Counters(0u, 0u, 0u, 0u);
    vec3 radiance_2 = vec3(0.0);
    float transmittance_1 = 1.0;
    float depth_sum = 0.0;
    uint i_17 = 0u;
    float depth_3 = 0.0;
    vec3 _e1 = view_ray(pixel_7);
    float cam_alt_2 = _group_0_binding_0_cs.camera_position.y;
    vec4 _e8 = _group_0_binding_0_cs.camera_position;
    vec2 cam_xz_2 = _e8.xz;
    count(STAT_PIXELS, 1u);
    Interval _e25 = cloud_interval(cam_alt_2, _e1);
    if ((_e25.kind == RAY_MISSES_LAYER)) {
        count(STAT_EXIT_MISSED, 1u);
    } else {
        if ((_e25.kind == RAY_HITS_GROUND)) {
            count(STAT_EXIT_GROUND, 1u);
        } else {
            count(STAT_MARCHED, 1u);
            uint steps_5 = _group_0_binding_0_cs.counts.z;
            float dt_4 = (_e25.length_ / float(steps_5));
            float sigma_s = _group_0_binding_0_cs.extinction.x;
            float _e52 = _group_0_binding_0_cs.extinction.y;
            float sigma_t_7 = (sigma_s + _e52);
            vec4 _e56 = _group_0_binding_0_cs.sun_illuminance;
            vec4 _e60 = _group_0_binding_0_cs.sun_direction;
            float _e66 = _group_0_binding_0_cs.phase.x;
            float _e67 = phase_hg(dot(_e1, _e60.xyz), _e66);
            vec3 sun_phase = (_e56.xyz * _e67);
            bool loop_init_14 = true;
            while(true) {
                if (!loop_init_14) {
                    uint _e131 = i_17;
                    i_17 = (_e131 + 1u);
                }
                loop_init_14 = false;
                uint _e71 = i_17;
                if ((_e71 < steps_5)) {
                } else {
                    break;
                }
                {
                    uint _e74 = counters_17.view_steps;
                    counters_17.view_steps = (_e74 + 1u);
                    uint _e78 = i_17;
                    float t_8 = (_e25.start + (float(_e78) * dt_4));
                    vec3 rel_14 = ((_e1 * t_8) + vec3(0.0, cam_alt_2, 0.0));
                    vec3 p_23 = vec3((rel_14.x + cam_xz_2.x), rel_14.y, (rel_14.z + cam_xz_2.y));
                    float _e95 = altitude_of(rel_14);
                    float _e96 = cloud_density(p_23, _e95, counters_17);
                    if ((_e96 <= 0.0)) {
                        continue;
                    }
                    float _e99 = basic_sun_depth(rel_14, _e95, counters_17);
                    float beer_powder = ((2.0 * exp(-(_e99))) * (1.0 - exp((-2.0 * _e99))));
                    vec3 _e110 = radiance_2;
                    float _e111 = transmittance_1;
                    radiance_2 = (_e110 + (sun_phase * ((((beer_powder * _e111) * sigma_s) * _e96) * dt_4)));
                    float step_t_1 = exp(((-(sigma_t_7) * _e96) * dt_4));
                    float _e122 = depth_sum;
                    float _e123 = transmittance_1;
                    depth_sum = (_e122 + ((t_8 * _e123) * (1.0 - step_t_1)));
                    float _e129 = transmittance_1;
                    transmittance_1 = (_e129 * step_t_1);
                }
            }
        }
    }
    uint _e136 = counters_17.view_steps;
    count(STAT_VIEW_STEPS, _e136);
    uint _e139 = counters_17.density;
    count(STAT_DENSITY, _e139);
    uint _e142 = counters_17.detail;
    count(STAT_DETAIL, _e142);
    uint _e145 = counters_17.light;
    count(STAT_LIGHT, _e145);
    float _e148 = transmittance_1;
    if ((_e148 < 1.0)) {
        float _e151 = depth_sum;
        float _e152 = transmittance_1;
        depth_3 = (_e151 / (1.0 - _e152));
    }
    vec3 _e156 = radiance_2;
    float _e157 = transmittance_1;
    float _e158 = depth_3;
    return MarchResult(_e156, _e157, _e158);
}

float atlas_hash(uint a_2, uint b_2) {
    uint _e2 = pcg(b_2);
    uint _e4 = pcg((a_2 ^ _e2));
    return (float((_e4 >> 8u)) * 5.9604645e-8);
}

float value_noise(vec2 p_14, uint seed) {
    uvec2 i_19 = uvec2(floor(p_14));
    vec2 f_5 = fract(p_14);
    vec2 s_11 = ((f_5 * f_5) * (vec2(3.0) - (2.0 * f_5)));
    uint h_14 = (seed * 7919u);
    float _e17 = atlas_hash((i_19.x + h_14), i_19.y);
    float _e23 = atlas_hash(((i_19.x + 1u) + h_14), i_19.y);
    float _e29 = atlas_hash((i_19.x + h_14), (i_19.y + 1u));
    float _e37 = atlas_hash(((i_19.x + 1u) + h_14), (i_19.y + 1u));
    return mix(mix(_e17, _e23, s_11.x), mix(_e29, _e37, s_11.x), s_11.y);
}

float value_fbm(vec2 p_15, uint seed_1) {
    float sum_5 = 0.0;
    float weight = 0.5;
    vec2 q_4 = vec2(0.0);
    uint o = 0u;
    q_4 = p_15;
    bool loop_init_15 = true;
    while(true) {
        if (!loop_init_15) {
            uint _e26 = o;
            o = (_e26 + 1u);
        }
        loop_init_15 = false;
        uint _e9 = o;
        if ((_e9 < 4u)) {
        } else {
            break;
        }
        {
            float _e12 = sum_5;
            float _e13 = weight;
            vec2 _e14 = q_4;
            uint _e15 = o;
            float _e17 = value_noise(_e14, (seed_1 + _e15));
            sum_5 = (_e12 + (_e13 * _e17));
            vec2 _e20 = q_4;
            q_4 = (_e20 * 2.0);
            float _e23 = weight;
            weight = (_e23 * 0.5);
        }
    }
    float _e29 = sum_5;
    return (_e29 / 0.9375);
}

float sprite_texture(uint tile_1, vec2 uv) {
    float billow = 0.0;
    uint i_18 = 0u;
    vec2 at = vec2(0.0);
    float a_3 = 0.0;
    vec2 c_10 = (uv - vec2(0.5));
    float mask = smoothstep(0.48, 0.36, length(c_10));
    float _e16 = value_fbm(((uv * 6.0) + vec2((float(tile_1) * 13.0))), tile_1);
    if ((tile_1 < 4u)) {
        vec2 q_9 = (c_10 * vec2(1.0, 3.2));
        float streak = (1.0 - smoothstep(0.05, 0.45, length(q_9)));
        float _e40 = value_fbm(((uv * vec2(3.0, 12.0)) + vec2((float(tile_1) * 5.0))), (tile_1 + 16u));
        float _e46 = saturate(((_e40 * 1.6) - 0.3));
        return (((mask * streak) * _e46) * 0.8);
    }
    uint blobs = (5u + (tile_1 % 4u));
    bool loop_init_16 = true;
    while(true) {
        if (!loop_init_16) {
            uint _e108 = i_18;
            i_18 = (_e108 + 1u);
        }
        loop_init_16 = false;
        uint _e58 = i_18;
        if ((_e58 < blobs)) {
        } else {
            break;
        }
        {
            uint _e61 = i_18;
            float _e63 = atlas_hash(tile_1, (2u * _e61));
            uint _e65 = i_18;
            float _e69 = atlas_hash(tile_1, ((2u * _e65) + 1u));
            vec2 centre_1 = (vec2(_e63, _e69) - vec2(0.5));
            at = (vec2(0.5) + (centre_1 * 0.34));
            if ((tile_1 == 4u)) {
                at.y = (0.5 + ((centre_1.y - 0.5) * 0.24));
            }
            uint _e91 = i_18;
            float _e93 = atlas_hash(tile_1, (100u + _e91));
            float r_18 = (0.14 + (0.1 * _e93));
            vec2 _e98 = at;
            float d_23 = (length((uv - _e98)) / r_18);
            float _e102 = billow;
            float _e106 = saturate((1.0 - (d_23 * d_23)));
            billow = max(_e102, _e106);
        }
    }
    float _e111 = billow;
    float _e114 = saturate((_e111 * 1.5));
    a_3 = ((mask * _e114) * (0.55 + (0.45 * _e16)));
    if ((tile_1 == 4u)) {
        float _e124 = a_3;
        a_3 = (_e124 * smoothstep(0.62, 0.54, uv.y));
    }
    float _e130 = a_3;
    return _e130;
}

vec3 sprite_rel(vec2 xz, float alt_16) {
    float rp_6 = _group_0_binding_0_cs.atmosphere.x;
    vec4 _e8 = _group_0_binding_0_cs.camera_position;
    vec2 d_24 = (xz - _e8.xz);
    float k_19 = ((alt_16 * (alt_16 + (2.0 * rp_6))) - dot(d_24, d_24));
    float y_3 = (k_19 / (rp_6 + sqrt(max(((rp_6 * rp_6) + k_19), 0.0))));
    return vec3(d_24.x, y_3, d_24.y);
}

SpriteCell sprite_cell(uint cell) {
    ivec2 start_1 = ivec2(0);
    uint k_10 = 3u;
    bool local_61 = false;
    bool local_62 = false;
    uint level_1 = (cell / 64u);
    ivec2 local_66 = ivec2(int((cell % 8u)), int(((cell / 8u) % 8u)));
    vec4 _e15 = _group_0_binding_0_cs.camera_position;
    start_1 = (ivec2(floor((_e15.xz / vec2(12000.0)))) - ivec2(4));
    bool loop_init_17 = true;
    while(true) {
        if (!loop_init_17) {
            uint _e35 = k_10;
            k_10 = (_e35 - 1u);
        }
        loop_init_17 = false;
        uint _e27 = k_10;
        if ((_e27 > level_1)) {
        } else {
            break;
        }
        {
            ivec2 _e29 = start_1;
            start_1 = (2 * (_e29 + ivec2(2)));
        }
    }
    if ((level_1 > 0u)) {
        local_61 = all(greaterThanEqual(local_66, ivec2(2)));
    } else {
        local_61 = false;
    }
    bool _e47 = local_61;
    if (_e47) {
        local_62 = all(lessThan(local_66, ivec2(6)));
    } else {
        local_62 = false;
    }
    bool covered = local_62;
    ivec2 _e56 = start_1;
    return SpriteCell((_e56 + local_66), (SPRITE_CELL0_ * float((1u << level_1))), covered);
}

SpriteCandidate sprite_candidate(SpriteCell c_4, uint level, uint s_2, inout Counters counters_18) {
    float density_3 = 0.0;
    uint _e10 = pcg(level);
    uint _e12 = pcg((uint(c_4.index.y) ^ _e10));
    uint _e14 = pcg((uint(c_4.index.x) ^ _e12));
    float _e17 = atlas_hash(_e14, (8u * s_2));
    float _e22 = atlas_hash(_e14, ((8u * s_2) + 1u));
    float _e27 = atlas_hash(_e14, ((8u * s_2) + 2u));
    float _e32 = atlas_hash(_e14, ((8u * s_2) + 3u));
    vec4 u_1 = vec4(_e17, _e22, _e27, _e32);
    float _e38 = atlas_hash(_e14, ((8u * s_2) + 4u));
    float _e43 = atlas_hash(_e14, ((8u * s_2) + 5u));
    vec2 v_3 = vec2(_e38, _e43);
    vec2 xz_2 = ((vec2(c_4.index) + u_1.xy) * c_4.size);
    Layer _e56 = cloud_layer(0u);
    Weather _e57 = sample_weather(vec3(xz_2.x, 0.0, xz_2.y), _e56);
    float h_15 = (0.04 + (u_1.z * (mix(0.3, 0.95, _e57.cloud_type) - 0.04)));
    float _e71 = _group_0_binding_0_cs.atmosphere.y;
    float _e75 = _group_0_binding_0_cs.atmosphere.z;
    float _e79 = _group_0_binding_0_cs.atmosphere.y;
    float alt_18 = (_e71 + (h_15 * (_e75 - _e79)));
    if (!(c_4.covered)) {
        vec3 _e87 = sprite_rel(xz_2, alt_18);
        float _e92 = cloud_density(vec3(xz_2.x, _e87.y, xz_2.y), alt_18, counters_18);
        density_3 = _e92;
    }
    float _e96 = density_3;
    return SpriteCandidate(xz_2, alt_18, h_15, u_1.w, v_3.x, v_3.y, _e96, _e57.precipitation);
}

vec3 sprite_sky_level(float h_10) {
    float _e1 = saturate(h_10);
    float x_9 = (_e1 * 4.0);
    if ((x_9 < 1.0)) {
        return mix(SKY_LEVEL0_, SKY_LEVEL1_, x_9);
    }
    if ((x_9 < 2.0)) {
        return mix(SKY_LEVEL1_, SKY_LEVEL2_, (x_9 - 1.0));
    }
    if ((x_9 < 3.0)) {
        return mix(SKY_LEVEL2_, SKY_LEVEL3_, (x_9 - 2.0));
    }
    return mix(SKY_LEVEL3_, SKY_LEVEL4_, (x_9 - 3.0));
}

float sprite_sun_level(float cos_angle) {
    if ((cos_angle < 0.0)) {
        return mix(SPRITE_C_MIN, SPRITE_C_MED, (cos_angle + 1.0));
    }
    return mix(SPRITE_C_MED, SPRITE_C_MAX, cos_angle);
}

vec2 sprite_corner(uint k_11) {
    bool local_63 = false;
    uint q_10 = ((k_11 >= 3u) ? ((k_11 == 3u) ? 0u : (k_11 - 2u)) : k_11);
    if (!((q_10 == 1u))) {
        local_63 = (q_10 == 2u);
    } else {
        local_63 = true;
    }
    bool _e18 = local_63;
    return vec2((_e18 ? 1.0 : -1.0), ((q_10 >= 2u) ? 1.0 : -1.0));
}

vec3 sky_radiance(vec3 d_17, float alt_17) {
    vec4 _e4 = _group_0_binding_0_cs.sun_direction;
    vec3 sun_8 = _e4.xyz;
    vec4 _e8 = _group_0_binding_0_cs.sun_illuminance;
    vec3 e_1 = _e8.xyz;
    float _e15 = saturate(((sun_8.y * 4.0) + 0.3));
    bool _e19 = hits_ground(vec3(0.0, alt_17, 0.0), alt_17, d_17);
    if (_e19) {
        vec3 ground_albedo = vec3(0.035, 0.035, 0.03);
        return (ground_albedo * (((e_1 * max(sun_8.y, 0.0)) / vec3(3.1415927)) + ((0.05 * e_1) * _e15)));
    }
    vec3 zenith = vec3(0.018, 0.04, 0.1);
    vec3 horizon_2 = vec3(0.07, 0.085, 0.11);
    float _e45 = saturate(d_17.y);
    vec3 gradient_1 = mix(horizon_2, zenith, sqrt(_e45));
    vec3 sunset = (((1.0 - (_e15 * 0.8)) * pow((1.0 - _e45), 6.0)) * vec3(0.25, 0.1, 0.0));
    float _e64 = phase_hg(dot(d_17, sun_8), 0.76);
    float glow = (_e64 * 0.02);
    float _e73 = saturate(((sun_8.y * 10.0) + 1.0));
    return (e_1 * (((gradient_1 * _e15) + (sunset * _e73)) + vec3((glow * _e15))));
}

vec3 sun_disk(vec3 d_18) {
    float cos_r = _group_0_binding_0_cs.sun_direction.w;
    vec4 _e7 = _group_0_binding_0_cs.sun_direction;
    if ((dot(d_18, _e7.xyz) < cos_r)) {
        return vec3(0.0);
    }
    vec4 _e15 = _group_0_binding_0_cs.sun_illuminance;
    return (_e15.xyz / vec3((6.2831855 * max((1.0 - cos_r), 1e-6))));
}

vec3 moon_disk(vec3 d_19) {
    bool local_64 = false;
    vec4 _e3 = _group_0_binding_0_cs.moon;
    vec3 m_4 = _e3.xyz;
    float c_11 = dot(d_19, m_4);
    float _e9 = _group_0_binding_0_cs.moon.w;
    if (!((_e9 <= 0.0))) {
        local_64 = (c_11 < MOON_COS_RADIUS);
    } else {
        local_64 = true;
    }
    bool _e18 = local_64;
    if (_e18) {
        return vec3(0.0);
    }
    vec3 offset = ((d_19 - (m_4 * c_11)) / vec3(0.0045149517));
    float x2_1 = min(dot(offset, offset), 1.0);
    vec3 normal = (offset - (m_4 * sqrt((1.0 - x2_1))));
    vec4 _e36 = _group_0_binding_0_cs.night;
    float lit_1 = smoothstep(-0.02, 0.02, dot(normal, _e36.xyz));
    float _e46 = _group_0_binding_0_cs.moon.w;
    return vec3(((_e46 / 6.40407e-5) * lit_1));
}

vec3 stars(vec3 d_20) {
    uint face = 0u;
    vec2 uv_1 = vec2(0.0);
    float major = 0.0;
    bool local_65 = false;
    vec3 star = vec3(0.0);
    float e0_ = _group_0_binding_0_cs.night.w;
    if ((e0_ <= 0.0)) {
        return vec3(0.0);
    }
    vec3 a_9 = abs(d_20);
    if ((a_9.x >= a_9.y)) {
        local_65 = (a_9.x >= a_9.z);
    } else {
        local_65 = false;
    }
    bool _e26 = local_65;
    if (_e26) {
        face = ((d_20.x > 0.0) ? 0u : 1u);
        uv_1 = d_20.zy;
        major = a_9.x;
    } else {
        if ((a_9.y >= a_9.z)) {
            face = ((d_20.y > 0.0) ? 2u : 3u);
            uv_1 = d_20.xz;
            major = a_9.y;
        } else {
            face = ((d_20.z > 0.0) ? 4u : 5u);
            uv_1 = d_20.xy;
            major = a_9.z;
        }
    }
    vec2 _e54 = uv_1;
    float _e55 = major;
    vec2 st = clamp((((_e54 / vec2(_e55)) * 0.5) + vec2(0.5)), vec2(0.0), vec2(0.999999));
    uvec2 cell_2 = uvec2((st * 96.0));
    uint _e71 = face;
    uint id_22 = ((((_e71 * STAR_CELLS) + cell_2.y) * STAR_CELLS) + cell_2.x);
    uint _e85 = pcg((id_22 ^ 2654435769u));
    float h0_ = (float((_e85 >> 8u)) * 5.9604645e-8);
    if ((h0_ >= 0.15085077)) {
        return vec3(0.0);
    }
    uint _e96 = pcg((id_22 ^ 2246822507u));
    float h1_ = (float((_e96 >> 8u)) * 5.9604645e-8);
    uint _e104 = pcg((id_22 ^ 3266489909u));
    float h2_ = (float((_e104 >> 8u)) * 5.9604645e-8);
    uint _e112 = pcg((id_22 ^ 668265263u));
    float h3_ = (float((_e112 >> 8u)) * 5.9604645e-8);
    uint _e120 = pcg((id_22 ^ 374761393u));
    float h4_ = (float((_e120 >> 8u)) * 5.9604645e-8);
    vec2 star_st = (((vec2(cell_2) + vec2(0.15)) + (0.7 * vec2(h1_, h2_))) / vec2(96.0));
    float _e142 = major;
    vec2 q_11 = (((star_st * 2.0) - vec2(1.0)) * _e142);
    uint _e147 = face;
    if ((_e147 < 2u)) {
        float _e150 = major;
        float _e152 = major;
        uint _e153 = face;
        star = vec3(((_e153 == 0u) ? _e152 : -(_e150)), q_11.y, q_11.x);
    } else {
        uint _e160 = face;
        if ((_e160 < 4u)) {
            float _e164 = major;
            float _e166 = major;
            uint _e167 = face;
            star = vec3(q_11.x, ((_e167 == 2u) ? _e166 : -(_e164)), q_11.y);
        } else {
            float _e175 = major;
            float _e177 = major;
            uint _e178 = face;
            star = vec3(q_11.x, q_11.y, ((_e178 == 4u) ? _e177 : -(_e175)));
        }
    }
    vec3 _e183 = star;
    star = normalize(_e183);
    float magnitude = max((STAR_FAINTEST + (log(max((h0_ / 0.15085077), 1e-6)) / 1.1052408)), -1.5);
    float illuminance = (e0_ * pow(10.0, (-0.4 * magnitude)));
    float _e203 = _group_0_binding_0_cs.camera_position.w;
    uint _e209 = _group_0_binding_0_cs.counts.y;
    float pixel_angle = ((2.0 * _e203) / float(_e209));
    vec3 _e212 = star;
    float dist_1 = (acos(clamp(dot(d_20, _e212), -1.0, 1.0)) / pixel_angle);
    float weight_1 = (exp(((-(dist_1) * dist_1) / 0.5)) / 1.5707964);
    vec3 tint = mix(vec3(0.8, 0.9, 1.1), vec3(1.15, 0.95, 0.75), (h3_ * h4_));
    return (tint * ((illuminance * weight_1) / (pixel_angle * pixel_angle)));
}

vec3 aces_fitted(vec3 x_5) {
    return clamp(((x_5 * ((2.51 * x_5) + vec3(0.03))) / ((x_5 * ((2.43 * x_5) + vec3(0.59))) + vec3(0.14))), vec3(0.0), vec3(1.0));
}

void main() {
    if (gl_LocalInvocationID == uvec3(0u)) {
        lane_sums = vec4[32](vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0));
        lane_moments = vec4[32](vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0), vec4(0.0));
    }
    memoryBarrierShared();
    barrier();
    uvec3 group = gl_WorkGroupID;
    uint lane = gl_LocalInvocationIndex;
    Counters counters_1 = Counters(0u, 0u, 0u, 0u);
    uint rng = 0u;
    vec4 sum_3 = vec4(0.0);
    vec4 sum_moments = vec4(0.0);
    uint i_3 = 0u;
    vec4 mean = vec4(0.0);
    vec4 moments = vec4(0.0);
    bool local_11 = false;
    uvec4 _e5 = _group_0_binding_0_cs.counts;
    if (any(greaterThanEqual(group.xy, _e5.xy))) {
        return;
    }
    uvec2 pixel_10 = group.xy;
    vec3 _e10 = view_ray(pixel_10);
    float _e14 = _group_0_binding_0_cs.camera_position.y;
    Interval _e15 = cloud_interval(_e14, _e10);
    if ((lane == 0u)) {
        count(STAT_PIXELS, 1u);
        count(STAT_MARCHED, uint((_e15.kind == RAY_MARCH)));
        count(STAT_EXIT_MISSED, uint((_e15.kind == RAY_MISSES_LAYER)));
        count(STAT_EXIT_GROUND, uint((_e15.kind == RAY_HITS_GROUND)));
    }
    uint _e44 = _group_0_binding_0_cs.misc.y;
    uint _e48 = rng_seed(pixel_10, ((_e44 * PATHS_PER_FRAME) + lane));
    rng = _e48;
    PathResult _e50 = trace_path(_e10, _e15, rng, counters_1);
    float _e52 = luminance(_e50.radiance);
    bool hit = (_e50.depth >= 0.0);
    lane_sums[lane] = vec4(_e50.radiance, _e50.transmittance);
    lane_moments[lane] = vec4((_e52 * _e52), (hit ? _e50.depth : 0.0), (hit ? 1.0 : 0.0), 0.0);
    memoryBarrierShared();
    barrier();
    if ((lane == 0u)) {
        bool loop_init_18 = true;
        while(true) {
            if (!loop_init_18) {
                uint _e98 = i_3;
                i_3 = (_e98 + 1u);
            }
            loop_init_18 = false;
            uint _e82 = i_3;
            if ((_e82 < PATHS_PER_FRAME)) {
            } else {
                break;
            }
            {
                vec4 _e85 = sum_3;
                uint _e87 = i_3;
                vec4 _e89 = lane_sums[_e87];
                sum_3 = (_e85 + _e89);
                vec4 _e91 = sum_moments;
                uint _e93 = i_3;
                vec4 _e95 = lane_moments[_e93];
                sum_moments = (_e91 + _e95);
            }
        }
        uint _e109 = _group_0_binding_0_cs.temporal.y;
        if ((_e109 == 1u)) {
            bool _e114 = camera_still();
            local_11 = _e114;
        } else {
            local_11 = false;
        }
        bool _e116 = local_11;
        if (_e116) {
            vec4 _e119 = texelFetch(_group_0_binding_13_cs, ivec2(pixel_10), 0);
            mean = _e119;
            vec4 _e122 = texelFetch(_group_0_binding_14_cs, ivec2(pixel_10), 0);
            moments = _e122;
        }
        float _e125 = moments.y;
        float n_4 = (_e125 + 32.0);
        vec4 _e127 = mean;
        vec4 _e128 = sum_3;
        vec4 _e129 = mean;
        mean = (_e127 + ((_e128 - (32.0 * _e129)) / vec4(n_4)));
        float _e136 = moments.z;
        float _e138 = sum_moments.x;
        float _e140 = moments.z;
        moments.z = (_e136 + ((_e138 - (32.0 * _e140)) / n_4));
        float hits = sum_moments.z;
        if ((hits > 0.0)) {
            float _e150 = moments.w;
            moments.w = (_e150 + hits);
            float _e153 = moments.x;
            float _e155 = sum_moments.y;
            float _e157 = moments.x;
            float _e161 = moments.w;
            moments.x = (_e153 + ((_e155 - (hits * _e157)) / _e161));
        }
        moments.y = n_4;
        vec4 _e166 = mean;
        imageStore(_group_0_binding_17_cs, ivec2(pixel_10), _e166);
        vec4 _e168 = moments;
        imageStore(_group_0_binding_18_cs, ivec2(pixel_10), _e168);
        vec4 _e170 = mean;
        imageStore(_group_0_binding_6_cs, ivec2(pixel_10), _e170);
        float _e173 = moments.x;
        imageStore(_group_0_binding_7_cs, ivec2(pixel_10), vec4(_e173, 0.0, 0.0, 0.0));
    }
    uint _e180 = counters_1.view_steps;
    count(STAT_VIEW_STEPS, _e180);
    uint _e183 = counters_1.density;
    count(STAT_DENSITY, _e183);
    uint _e186 = counters_1.detail;
    count(STAT_DETAIL, _e186);
    uint _e189 = counters_1.light;
    count(STAT_LIGHT, _e189);
    return;
}

