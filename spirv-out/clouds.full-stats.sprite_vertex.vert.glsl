#version 450 core
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
const bool DETAIL = true;
const bool CURL = true;
const bool STATS = true;

layout(std140, binding = 0) uniform Frame_block_0Vertex { Frame _group_0_binding_0_vs; };

layout(binding = 20) uniform sampler2D _group_0_binding_20_vs;

layout(binding = 22) uniform sampler2D _group_0_binding_22_vs;

layout(location = 0) smooth out vec2 _vs2fs_location0;
layout(location = 1) flat out uint _vs2fs_location1;
layout(location = 2) smooth out vec4 _vs2fs_location2;
layout(location = 3) smooth out float _vs2fs_location3;

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
    uvec4 _e3 = _group_0_binding_0_vs.counts;
    vec2 size_1 = vec2(_e3.xy);
    vec2 ndc = ((((vec2(pixel_1) + vec2(0.5)) / size_1) * 2.0) - vec2(1.0));
    float tan_half = _group_0_binding_0_vs.camera_position.w;
    float aspect = _group_0_binding_0_vs.camera_forward.w;
    vec4 _e26 = _group_0_binding_0_vs.camera_forward;
    vec4 _e30 = _group_0_binding_0_vs.camera_right;
    vec4 _e39 = _group_0_binding_0_vs.camera_up;
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
    float rp = _group_0_binding_0_vs.atmosphere.x;
    float b_3 = (d.y * (alt + rp));
    float c_5 = ((alt - radius_alt) * ((alt + radius_alt) + (2.0 * rp)));
    Roots _e16 = solve_sphere(b_3, c_5);
    return _e16;
}

float altitude_of(vec3 p) {
    float rp_1 = _group_0_binding_0_vs.atmosphere.x;
    float n_3 = (((p.x * p.x) + (p.z * p.z)) + (p.y * (p.y + (2.0 * rp_1))));
    vec3 q_5 = vec3(p.x, (p.y + rp_1), p.z);
    return (n_3 / (length(q_5) + rp_1));
}

bool hits_ground(vec3 p_1, float alt_1, vec3 d_1) {
    bool local_15 = false;
    float rp_2 = _group_0_binding_0_vs.atmosphere.x;
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
    float cutoff = _group_0_binding_0_vs.atmosphere.w;
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
    uint _e4 = _group_0_binding_0_vs.misc.w;
    return (1u + min(_e4, 3u));
}

Layer layer_from(vec4 g, vec4 w_1) {
    return Layer(g.x, g.y, g.z, g.w, w_1.x, w_1.y, w_1.zw);
}

Layer cloud_layer(uint i_5) {
    if ((i_5 == 1u)) {
        vec4 _e5 = _group_0_binding_0_vs.layer1_;
        vec4 _e8 = _group_0_binding_0_vs.layer1_weather;
        Layer _e9 = layer_from(_e5, _e8);
        return _e9;
    } else {
        if ((i_5 == 2u)) {
            vec4 _e14 = _group_0_binding_0_vs.layer2_;
            vec4 _e17 = _group_0_binding_0_vs.layer2_weather;
            Layer _e18 = layer_from(_e14, _e17);
            return _e18;
        } else {
            if ((i_5 == 3u)) {
                vec4 _e23 = _group_0_binding_0_vs.layer3_;
                vec4 _e26 = _group_0_binding_0_vs.layer3_weather;
                Layer _e27 = layer_from(_e23, _e26);
                return _e27;
            }
        }
    }
    float _e31 = _group_0_binding_0_vs.atmosphere.y;
    float _e35 = _group_0_binding_0_vs.atmosphere.z;
    float _e39 = _group_0_binding_0_vs.clouds.x;
    float _e43 = _group_0_binding_0_vs.clouds.y;
    float _e47 = _group_0_binding_0_vs.clouds.z;
    float _e51 = _group_0_binding_0_vs.clouds.w;
    vec4 _e54 = _group_0_binding_0_vs.wind_offsets0_;
    return Layer(_e31, _e35, _e39, _e43, _e47, _e51, _e54.xy);
}

vec2 layers_span() {
    vec2 span = vec2(0.0);
    uint i_6 = 1u;
    vec4 _e2 = _group_0_binding_0_vs.atmosphere;
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
    float rp_3 = _group_0_binding_0_vs.atmosphere.x;
    float b_5 = dot(d_6, vec3(p_2.x, (p_2.y + rp_3), p_2.z));
    float c_7 = ((alt_6 - radius_alt_1) * ((alt_6 + radius_alt_1) + (2.0 * rp_3)));
    Roots _e20 = solve_sphere(b_5, c_7);
    return _e20;
}

bool physical_sky() {
    uint _e3 = _group_0_binding_0_vs.modes.w;
    return ((_e3 & FLAG_PHYSICAL_SKY) != 0u);
}

float air_bottom() {
    float _e3 = _group_0_binding_0_vs.atmosphere.x;
    return (_e3 * 0.001);
}

float air_top() {
    float _e3 = _group_0_binding_0_vs.atmosphere.x;
    float _e7 = _group_0_binding_0_vs.air_misc.x;
    return ((_e3 + _e7) * 0.001);
}

AirSample air_at(float h_km) {
    float h_11 = (max(h_km, 0.0) * 1000.0);
    float _e9 = _group_0_binding_0_vs.air_rayleigh.w;
    float rayleigh_density = exp((-(h_11) / _e9));
    float _e16 = _group_0_binding_0_vs.air_mie.z;
    float mie_density = exp((-(h_11) / _e16));
    float _e22 = _group_0_binding_0_vs.air_ozone.w;
    float _e28 = _group_0_binding_0_vs.air_misc.y;
    float ozone_density = max((1.0 - (abs((h_11 - _e22)) / (0.5 * _e28))), 0.0);
    vec4 _e38 = _group_0_binding_0_vs.air_rayleigh;
    vec3 rayleigh = (_e38.xyz * (rayleigh_density * 1000.0));
    float _e46 = _group_0_binding_0_vs.air_mie.x;
    float mie = ((_e46 * mie_density) * 1000.0);
    float _e53 = _group_0_binding_0_vs.air_mie.x;
    float _e57 = _group_0_binding_0_vs.air_mie.y;
    float mie_extinction = (((_e53 + _e57) * mie_density) * 1000.0);
    vec4 _e64 = _group_0_binding_0_vs.air_ozone;
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

vec2 air_ray_end(vec3 origin_2, vec3 d_9) {
    float r_15 = length(origin_2);
    float mu_9 = (dot(origin_2, d_9) / r_15);
    bool _e5 = meets_ground(r_15, mu_9);
    if (_e5) {
        float _e6 = distance_to_ground(r_15, mu_9);
        return vec2(_e6, 1.0);
    }
    float _e9 = air_top();
    if ((r_15 > _e9)) {
        return vec2(0.0, 0.0);
    }
    float _e14 = distance_to_top(r_15, mu_9);
    return vec2(_e14, 0.0);
}

vec3 camera_air_origin() {
    float _e0 = air_bottom();
    float _e4 = _group_0_binding_0_vs.camera_position.y;
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
    vec4 _e2 = _group_0_binding_0_vs.sun_direction;
    vec3 s_5 = _e2.xyz;
    return atan(s_5.z, s_5.x);
}

vec3 aerial_ray(uvec2 c_1) {
    vec2 ndc_1 = ((((vec2(c_1) + vec2(0.5)) / vec2(32.0)) * 2.0) - vec2(1.0));
    float tan_half_1 = _group_0_binding_0_vs.camera_position.w;
    float aspect_1 = _group_0_binding_0_vs.camera_forward.w;
    vec4 _e23 = _group_0_binding_0_vs.camera_forward;
    vec4 _e27 = _group_0_binding_0_vs.camera_right;
    vec4 _e36 = _group_0_binding_0_vs.camera_up;
    return normalize(((_e23.xyz + (_e27.xyz * ((ndc_1.x * tan_half_1) * aspect_1))) - (_e36.xyz * (ndc_1.y * tan_half_1))));
}

float sky_ambient_x(float mu_8) {
    return (0.5 + ((0.5 * sign(mu_8)) * sqrt(abs(mu_8))));
}

float layer_height(Layer l_1, float alt_7) {
    return ((alt_7 - l_1.bottom) / (l_1.top - l_1.bottom));
}

uint layer_at(float alt_8) {
    uint i_9 = 0u;
    bool local_22 = false;
    bool loop_init_2 = true;
    while(true) {
        if (!loop_init_2) {
            uint _e19 = i_9;
            i_9 = (_e19 + 1u);
        }
        loop_init_2 = false;
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
    uint _e5 = _group_0_binding_0_vs.modes.z;
    if ((_e5 == HEIGHT_CLOUD_TYPES)) {
        float _e8 = height_cloud_types(h_4, cloud_type_2);
        return _e8;
    }
    float _e9 = height_parabola(h_4, cloud_type_2);
    return _e9;
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
    float _e5 = _group_0_binding_0_vs.phase.x;
    float g_5 = (_e5 * scale);
    uint _e10 = _group_0_binding_0_vs.modes.x;
    switch(_e10) {
        case 1u: {
            float _e14 = _group_0_binding_0_vs.phase.y;
            float g2_3 = (_e14 * scale);
            float _e16 = phase_hg(cos_theta_4, g_5);
            float _e17 = phase_hg(cos_theta_4, g2_3);
            float _e21 = _group_0_binding_0_vs.phase.z;
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

float diffuse_limb(float view_y, float coverage) {
    float k_12 = _group_0_binding_0_vs.light_model.w;
    float layer = ((1.0 + (k_12 * abs(view_y))) / (1.0 + ((2.0 * k_12) / 3.0)));
    float _e17 = saturate(coverage);
    return mix(1.0, layer, _e17);
}

float vertical_anisotropy(float view_y_1, float coverage_1, float h_5) {
    float _e6 = _group_0_binding_0_vs.octave_direction.z;
    float _e8 = saturate(coverage_1);
    float _e10 = saturate(h_5);
    return (1.0 + (((_e6 * view_y_1) * _e8) * (1.0 - _e10)));
}

float deck_escape(float mu0_, float layer_coverage) {
    float e = _group_0_binding_0_vs.octave_direction.w;
    float _e6 = saturate(layer_coverage);
    return (1.0 + ((e * pow(_e6, DECK_POWER)) * (mu0_ - 0.5)));
}

float downward_dimming(float view_y_2, float coverage_2, float h_6, float tau_v) {
    float _e7 = _group_0_binding_0_vs.octave_depth.z;
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
    float a_7 = _group_0_binding_0_vs.multiple_scattering.x;
    float b_7 = _group_0_binding_0_vs.multiple_scattering.y;
    float c_8 = _group_0_binding_0_vs.multiple_scattering.z;
    uint _e24 = _group_0_binding_0_vs.misc.x;
    uint octaves = min(_e24, MAX_OCTAVES);
    bool loop_init_3 = true;
    while(true) {
        if (!loop_init_3) {
            uint _e57 = i_12;
            i_12 = (_e57 + 1u);
        }
        loop_init_3 = false;
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
    float _e62 = _group_0_binding_0_vs.sun_direction.y;
    float _e63 = saturate(_e62);
    float _e70 = saturate(coverage_3);
    float side = ((sqrt(max((1.0 - (_e63 * _e63)), 0.0)) * (1.0 - _e70)) * exp(-(far_1)));
    float _e80 = _group_0_binding_0_vs.light_model.x;
    feed = (_e63 + (_e80 * side));
    float _e87 = _group_0_binding_0_vs.light_model.y;
    if ((_e87 > 0.0)) {
        float _e90 = feed;
        float _e96 = _group_0_binding_0_vs.light_model.y;
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
    uint _e127 = _group_0_binding_0_vs.modes.w;
    if (((_e127 & FLAG_BEER_POWDER) != 0u)) {
        float _e135 = _group_0_binding_0_vs.phase.w;
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
    float k_14 = _group_0_binding_0_vs.octave_direction.x;
    if ((k_14 <= 0.0)) {
        return 1.0;
    }
    float _e11 = saturate((transmittance / FORWARD_LOBE_THIN));
    float w_4 = (k_14 * _e11);
    float _e17 = _group_0_binding_0_vs.octave_direction.y;
    float _e18 = phase_hg(cos_theta_6, _e17);
    return (1.0 + (w_4 * ((12.566371 * _e18) - 1.0)));
}

float octave_buildup(float density_1) {
    float l_11 = _group_0_binding_0_vs.multiple_scattering.w;
    if ((l_11 <= 0.0)) {
        return 1.0;
    }
    float _e11 = _group_0_binding_0_vs.extinction.x;
    float _e15 = _group_0_binding_0_vs.extinction.y;
    return (1.0 - exp(((-((_e11 + _e15)) * density_1) * l_11)));
}

float height_fraction(float alt_12) {
    uint _e1 = layer_at(alt_12);
    Layer _e2 = cloud_layer(_e1);
    float _e3 = layer_height(_e2, alt_12);
    float _e4 = saturate(_e3);
    return _e4;
}

vec3 shadow_ground_point(uvec2 c_2) {
    vec2 xz_1 = ((((vec2(c_2) / vec2(127.0)) * 2.0) - vec2(1.0)) * SHADOW_HALF_EXTENT);
    float rp_4 = _group_0_binding_0_vs.atmosphere.x;
    float s2_ = dot(xz_1, xz_1);
    float y_1 = (-(s2_) / (sqrt(max(((rp_4 * rp_4) - s2_), 0.0)) + rp_4));
    return vec3(xz_1.x, y_1, xz_1.y);
}

vec3 step_integral(vec3 source, float sigma_t, float dt) {
    uint _e6 = _group_0_binding_0_vs.modes.y;
    if ((_e6 == INTEGRATION_RIEMANN)) {
        return (source * dt);
    }
    float x_6 = (sigma_t * dt);
    float f_2 = ((x_6 < 0.001) ? (1.0 - (0.5 * x_6)) : ((1.0 - exp(-(x_6))) / x_6));
    return (source * (dt * f_2));
}

float start_offset(uvec2 pixel_3) {
    uint _e4 = _group_0_binding_0_vs.modes.w;
    bool jitter_1 = ((_e4 & FLAG_JITTER) != 0u);
    uint k_15 = _group_0_binding_0_vs.temporal.x;
    if ((k_15 <= 1u)) {
        uint _e18 = _group_0_binding_0_vs.misc.y;
        float _e19 = hash_unit(pixel_3, _e18);
        return (jitter_1 ? _e19 : 0.5);
    }
    float _e23 = hash_unit(pixel_3, 0u);
    float base_2 = (jitter_1 ? _e23 : 0.5);
    uint _e29 = _group_0_binding_0_vs.misc.y;
    float _e32 = van_der_corput((_e29 / (k_15 * k_15)));
    return fract((base_2 + _e32));
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
    vec4 _e4 = _group_0_binding_0_vs.previous_position;
    vec4 _e7 = _group_0_binding_0_vs.camera_position;
    if (all(equal(_e4, _e7))) {
        vec4 _e14 = _group_0_binding_0_vs.previous_forward;
        vec4 _e17 = _group_0_binding_0_vs.camera_forward;
        local_45 = all(equal(_e14, _e17));
    } else {
        local_45 = false;
    }
    bool _e21 = local_45;
    if (_e21) {
        vec4 _e26 = _group_0_binding_0_vs.previous_right;
        vec4 _e29 = _group_0_binding_0_vs.camera_right;
        local_46 = all(equal(_e26, _e29));
    } else {
        local_46 = false;
    }
    bool _e33 = local_46;
    if (_e33) {
        vec4 _e38 = _group_0_binding_0_vs.previous_up;
        vec4 _e41 = _group_0_binding_0_vs.camera_up;
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
        vec4 _e54 = _group_0_binding_0_vs.camera_position;
        vec4 _e58 = _group_0_binding_0_vs.previous_position;
        dir = ((_e47 * depth_2) + (_e54.xyz - _e58.xyz));
    }
    vec3 _e62 = dir;
    vec4 _e65 = _group_0_binding_0_vs.previous_forward;
    float z_3 = dot(_e62, _e65.xyz);
    if ((z_3 <= 0.0)) {
        return vec2(-1000000000.0);
    }
    float tan_half_2 = _group_0_binding_0_vs.previous_position.w;
    float aspect_2 = _group_0_binding_0_vs.previous_forward.w;
    vec3 _e80 = dir;
    vec4 _e83 = _group_0_binding_0_vs.previous_right;
    vec3 _e89 = dir;
    vec4 _e92 = _group_0_binding_0_vs.previous_up;
    vec2 ndc_2 = vec2((dot(_e80, _e83.xyz) / ((z_3 * tan_half_2) * aspect_2)), (-(dot(_e89, _e92.xyz)) / (z_3 * tan_half_2)));
    uvec4 _e106 = _group_0_binding_0_vs.counts;
    return ((((ndc_2 * 0.5) + vec2(0.5)) * vec2(_e106.xy)) - vec2(0.5));
}

bool on_screen(vec2 q) {
    bool local_48 = false;
    uvec4 _e3 = _group_0_binding_0_vs.counts;
    vec2 size_2 = vec2(_e3.xy);
    if (all(greaterThanEqual(q, vec2(-0.5)))) {
        local_48 = all(lessThanEqual(q, (size_2 - vec2(0.5))));
    } else {
        local_48 = false;
    }
    bool _e18 = local_48;
    return _e18;
}

vec4 catmull_rom(float t_1) {
    return vec4((t_1 * (-0.5 + (t_1 * (1.0 - (0.5 * t_1))))), (1.0 + ((t_1 * t_1) * (-2.5 + (1.5 * t_1)))), (t_1 * (0.5 + (t_1 * (2.0 - (1.5 * t_1))))), ((t_1 * t_1) * (-0.5 + (0.5 * t_1))));
}

bool in_blocks(uvec2 id_19) {
    uint k_16 = _group_0_binding_0_vs.temporal.x;
    uvec4 _e7 = _group_0_binding_0_vs.counts;
    return all(lessThan(id_19, (((_e7.xy + uvec2(k_16)) - uvec2(1u)) / uvec2(k_16))));
}

uvec2 sparse_pixel(uvec2 id_20) {
    uint k_17 = _group_0_binding_0_vs.temporal.x;
    uint _e9 = _group_0_binding_0_vs.misc.y;
    uvec2 _e10 = block_offset(_e9, k_17);
    return ((id_20 * k_17) + _e10);
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
    uint s_6 = rng_1;
    uint word_1 = (((s_6 >> ((s_6 >> 28u) + 4u)) ^ s_6) * 277803737u);
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
    float bottom_1 = _e10.x;
    Roots _e12 = ray_shell_from(p_13, alt_14, d_15, bottom_1);
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
        local_51 = (alt_14 >= bottom_1);
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
        if ((alt_14 < bottom_1)) {
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

float density_max() {
    float m_1 = 0.0;
    uint i_15 = 0u;
    bool loop_init_4 = true;
    while(true) {
        if (!loop_init_4) {
            uint _e17 = i_15;
            i_15 = (_e17 + 1u);
        }
        loop_init_4 = false;
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

float sample_hg_cos(float g_4, float u) {
    if ((abs(g_4) < 0.0001)) {
        return (1.0 - (2.0 * u));
    }
    float s_7 = ((1.0 - (g_4 * g_4)) / ((1.0 - g_4) + ((2.0 * g_4) * u)));
    return clamp((((1.0 + (g_4 * g_4)) - (s_7 * s_7)) / (2.0 * g_4)), -1.0, 1.0);
}

PhaseSample sample_phase(vec3 dir_4, inout uint rng_5) {
    float cos_theta_7 = 0.0;
    float pdf = 0.0;
    float _e2 = rng_next(rng_5);
    float _e3 = rng_next(rng_5);
    float _e5 = rng_next(rng_5);
    float phi_1 = (6.2831855 * _e5);
    uint _e14 = _group_0_binding_0_vs.modes.x;
    if ((_e14 == PHASE_TWO_LOBE_HG)) {
        float _e20 = _group_0_binding_0_vs.phase.x;
        float _e24 = _group_0_binding_0_vs.phase.y;
        float _e28 = _group_0_binding_0_vs.phase.z;
        float g_6 = ((_e2 < _e28) ? _e24 : _e20);
        float _e31 = sample_hg_cos(g_6, _e3);
        cos_theta_7 = _e31;
        float _e32 = cos_theta_7;
        float _e36 = _group_0_binding_0_vs.phase.x;
        float _e37 = phase_hg(_e32, _e36);
        float _e38 = cos_theta_7;
        float _e42 = _group_0_binding_0_vs.phase.y;
        float _e43 = phase_hg(_e38, _e42);
        float _e47 = _group_0_binding_0_vs.phase.z;
        pdf = mix(_e37, _e43, _e47);
    } else {
        float _e52 = _group_0_binding_0_vs.phase.x;
        float _e53 = sample_hg_cos(_e52, _e3);
        cos_theta_7 = _e53;
        float _e54 = cos_theta_7;
        float _e58 = _group_0_binding_0_vs.phase.x;
        float _e59 = phase_hg(_e54, _e58);
        pdf = _e59;
    }
    float _e60 = cos_theta_7;
    float _e61 = cos_theta_7;
    float sin_theta = sqrt(max((1.0 - (_e60 * _e61)), 0.0));
    float sign_ = ((dir_4.z >= 0.0) ? 1.0 : -1.0);
    float a_8 = (-1.0 / (sign_ + dir_4.z));
    float bb = ((dir_4.x * dir_4.y) * a_8);
    vec3 t_5 = vec3((1.0 + (((sign_ * dir_4.x) * dir_4.x) * a_8)), (sign_ * bb), (-(sign_) * dir_4.x));
    vec3 b_9 = vec3(bb, (sign_ + ((dir_4.y * dir_4.y) * a_8)), -(dir_4.y));
    float _e109 = cos_theta_7;
    vec3 w_5 = normalize((((t_5 * (sin_theta * cos(phi_1))) + (b_9 * (sin_theta * sin(phi_1)))) + (dir_4 * _e109)));
    float _e113 = cos_theta_7;
    float _e115 = phase(_e113, 1.0);
    float _e116 = pdf;
    float _e118 = pdf;
    return PhaseSample(w_5, ((_e118 > 0.0) ? (_e115 / _e116) : 0.0));
}

bool camera_still() {
    bool local_58 = false;
    bool local_59 = false;
    bool local_60 = false;
    vec4 _e2 = _group_0_binding_0_vs.camera_position;
    vec4 _e5 = _group_0_binding_0_vs.previous_position;
    if (all(equal(_e2, _e5))) {
        vec4 _e12 = _group_0_binding_0_vs.camera_forward;
        vec4 _e15 = _group_0_binding_0_vs.previous_forward;
        local_58 = all(equal(_e12, _e15));
    } else {
        local_58 = false;
    }
    bool _e19 = local_58;
    if (_e19) {
        vec4 _e24 = _group_0_binding_0_vs.camera_right;
        vec4 _e28 = _group_0_binding_0_vs.previous_right;
        local_59 = all(equal(_e24.xyz, _e28.xyz));
    } else {
        local_59 = false;
    }
    bool _e33 = local_59;
    if (_e33) {
        vec4 _e38 = _group_0_binding_0_vs.camera_up;
        vec4 _e42 = _group_0_binding_0_vs.previous_up;
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

float atlas_hash(uint a_2, uint b_2) {
    uint _e2 = pcg(b_2);
    uint _e4 = pcg((a_2 ^ _e2));
    return (float((_e4 >> 8u)) * 5.9604645e-8);
}

float value_noise(vec2 p_14, uint seed) {
    uvec2 i_19 = uvec2(floor(p_14));
    vec2 f_3 = fract(p_14);
    vec2 s_8 = ((f_3 * f_3) * (vec2(3.0) - (2.0 * f_3)));
    uint h_14 = (seed * 7919u);
    float _e17 = atlas_hash((i_19.x + h_14), i_19.y);
    float _e23 = atlas_hash(((i_19.x + 1u) + h_14), i_19.y);
    float _e29 = atlas_hash((i_19.x + h_14), (i_19.y + 1u));
    float _e37 = atlas_hash(((i_19.x + 1u) + h_14), (i_19.y + 1u));
    return mix(mix(_e17, _e23, s_8.x), mix(_e29, _e37, s_8.x), s_8.y);
}

float value_fbm(vec2 p_15, uint seed_1) {
    float sum_5 = 0.0;
    float weight = 0.5;
    vec2 q_4 = vec2(0.0);
    uint o = 0u;
    q_4 = p_15;
    bool loop_init_5 = true;
    while(true) {
        if (!loop_init_5) {
            uint _e26 = o;
            o = (_e26 + 1u);
        }
        loop_init_5 = false;
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
    vec2 c_9 = (uv - vec2(0.5));
    float mask = smoothstep(0.48, 0.36, length(c_9));
    float _e16 = value_fbm(((uv * 6.0) + vec2((float(tile_1) * 13.0))), tile_1);
    if ((tile_1 < 4u)) {
        vec2 q_6 = (c_9 * vec2(1.0, 3.2));
        float streak = (1.0 - smoothstep(0.05, 0.45, length(q_6)));
        float _e40 = value_fbm(((uv * vec2(3.0, 12.0)) + vec2((float(tile_1) * 5.0))), (tile_1 + 16u));
        float _e46 = saturate(((_e40 * 1.6) - 0.3));
        return (((mask * streak) * _e46) * 0.8);
    }
    uint blobs = (5u + (tile_1 % 4u));
    bool loop_init_6 = true;
    while(true) {
        if (!loop_init_6) {
            uint _e108 = i_18;
            i_18 = (_e108 + 1u);
        }
        loop_init_6 = false;
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
            float r_16 = (0.14 + (0.1 * _e93));
            vec2 _e98 = at;
            float d_23 = (length((uv - _e98)) / r_16);
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
    float rp_5 = _group_0_binding_0_vs.atmosphere.x;
    vec4 _e8 = _group_0_binding_0_vs.camera_position;
    vec2 d_24 = (xz - _e8.xz);
    float k_18 = ((alt_16 * (alt_16 + (2.0 * rp_5))) - dot(d_24, d_24));
    float y_2 = (k_18 / (rp_5 + sqrt(max(((rp_5 * rp_5) + k_18), 0.0))));
    return vec3(d_24.x, y_2, d_24.y);
}

SpriteCell sprite_cell(uint cell) {
    ivec2 start_1 = ivec2(0);
    uint k_10 = 3u;
    bool local_61 = false;
    bool local_62 = false;
    uint level_1 = (cell / 64u);
    ivec2 local_66 = ivec2(int((cell % 8u)), int(((cell / 8u) % 8u)));
    vec4 _e15 = _group_0_binding_0_vs.camera_position;
    start_1 = (ivec2(floor((_e15.xz / vec2(12000.0)))) - ivec2(4));
    bool loop_init_7 = true;
    while(true) {
        if (!loop_init_7) {
            uint _e35 = k_10;
            k_10 = (_e35 - 1u);
        }
        loop_init_7 = false;
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

vec3 sprite_sky_level(float h_10) {
    float _e1 = saturate(h_10);
    float x_7 = (_e1 * 4.0);
    if ((x_7 < 1.0)) {
        return mix(SKY_LEVEL0_, SKY_LEVEL1_, x_7);
    }
    if ((x_7 < 2.0)) {
        return mix(SKY_LEVEL1_, SKY_LEVEL2_, (x_7 - 1.0));
    }
    if ((x_7 < 3.0)) {
        return mix(SKY_LEVEL2_, SKY_LEVEL3_, (x_7 - 2.0));
    }
    return mix(SKY_LEVEL3_, SKY_LEVEL4_, (x_7 - 3.0));
}

float sprite_sun_level(float cos_angle) {
    if ((cos_angle < 0.0)) {
        return mix(SPRITE_C_MIN, SPRITE_C_MED, (cos_angle + 1.0));
    }
    return mix(SPRITE_C_MED, SPRITE_C_MAX, cos_angle);
}

vec2 sprite_corner(uint k_11) {
    bool local_63 = false;
    uint q_7 = ((k_11 >= 3u) ? ((k_11 == 3u) ? 0u : (k_11 - 2u)) : k_11);
    if (!((q_7 == 1u))) {
        local_63 = (q_7 == 2u);
    } else {
        local_63 = true;
    }
    bool _e18 = local_63;
    return vec2((_e18 ? 1.0 : -1.0), ((q_7 >= 2u) ? 1.0 : -1.0));
}

vec3 sky_radiance(vec3 d_17, float alt_17) {
    vec4 _e4 = _group_0_binding_0_vs.sun_direction;
    vec3 sun_2 = _e4.xyz;
    vec4 _e8 = _group_0_binding_0_vs.sun_illuminance;
    vec3 e_1 = _e8.xyz;
    float _e15 = saturate(((sun_2.y * 4.0) + 0.3));
    bool _e19 = hits_ground(vec3(0.0, alt_17, 0.0), alt_17, d_17);
    if (_e19) {
        vec3 ground_albedo = vec3(0.035, 0.035, 0.03);
        return (ground_albedo * (((e_1 * max(sun_2.y, 0.0)) / vec3(3.1415927)) + ((0.05 * e_1) * _e15)));
    }
    vec3 zenith = vec3(0.018, 0.04, 0.1);
    vec3 horizon_2 = vec3(0.07, 0.085, 0.11);
    float _e45 = saturate(d_17.y);
    vec3 gradient_1 = mix(horizon_2, zenith, sqrt(_e45));
    vec3 sunset = (((1.0 - (_e15 * 0.8)) * pow((1.0 - _e45), 6.0)) * vec3(0.25, 0.1, 0.0));
    float _e64 = phase_hg(dot(d_17, sun_2), 0.76);
    float glow = (_e64 * 0.02);
    float _e73 = saturate(((sun_2.y * 10.0) + 1.0));
    return (e_1 * (((gradient_1 * _e15) + (sunset * _e73)) + vec3((glow * _e15))));
}

vec3 sun_disk(vec3 d_18) {
    float cos_r = _group_0_binding_0_vs.sun_direction.w;
    vec4 _e7 = _group_0_binding_0_vs.sun_direction;
    if ((dot(d_18, _e7.xyz) < cos_r)) {
        return vec3(0.0);
    }
    vec4 _e15 = _group_0_binding_0_vs.sun_illuminance;
    return (_e15.xyz / vec3((6.2831855 * max((1.0 - cos_r), 1e-6))));
}

vec3 moon_disk(vec3 d_19) {
    bool local_64 = false;
    vec4 _e3 = _group_0_binding_0_vs.moon;
    vec3 m_2 = _e3.xyz;
    float c_10 = dot(d_19, m_2);
    float _e9 = _group_0_binding_0_vs.moon.w;
    if (!((_e9 <= 0.0))) {
        local_64 = (c_10 < MOON_COS_RADIUS);
    } else {
        local_64 = true;
    }
    bool _e18 = local_64;
    if (_e18) {
        return vec3(0.0);
    }
    vec3 offset = ((d_19 - (m_2 * c_10)) / vec3(0.0045149517));
    float x2_ = min(dot(offset, offset), 1.0);
    vec3 normal = (offset - (m_2 * sqrt((1.0 - x2_))));
    vec4 _e36 = _group_0_binding_0_vs.night;
    float lit = smoothstep(-0.02, 0.02, dot(normal, _e36.xyz));
    float _e46 = _group_0_binding_0_vs.moon.w;
    return vec3(((_e46 / 6.40407e-5) * lit));
}

vec3 stars(vec3 d_20) {
    uint face = 0u;
    vec2 uv_1 = vec2(0.0);
    float major = 0.0;
    bool local_65 = false;
    vec3 star = vec3(0.0);
    float e0_ = _group_0_binding_0_vs.night.w;
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
    uvec2 cell_1 = uvec2((st * 96.0));
    uint _e71 = face;
    uint id_22 = ((((_e71 * STAR_CELLS) + cell_1.y) * STAR_CELLS) + cell_1.x);
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
    vec2 star_st = (((vec2(cell_1) + vec2(0.15)) + (0.7 * vec2(h1_, h2_))) / vec2(96.0));
    float _e142 = major;
    vec2 q_8 = (((star_st * 2.0) - vec2(1.0)) * _e142);
    uint _e147 = face;
    if ((_e147 < 2u)) {
        float _e150 = major;
        float _e152 = major;
        uint _e153 = face;
        star = vec3(((_e153 == 0u) ? _e152 : -(_e150)), q_8.y, q_8.x);
    } else {
        uint _e160 = face;
        if ((_e160 < 4u)) {
            float _e164 = major;
            float _e166 = major;
            uint _e167 = face;
            star = vec3(q_8.x, ((_e167 == 2u) ? _e166 : -(_e164)), q_8.y);
        } else {
            float _e175 = major;
            float _e177 = major;
            uint _e178 = face;
            star = vec3(q_8.x, q_8.y, ((_e178 == 4u) ? _e177 : -(_e175)));
        }
    }
    vec3 _e183 = star;
    star = normalize(_e183);
    float magnitude = max((STAR_FAINTEST + (log(max((h0_ / 0.15085077), 1e-6)) / 1.1052408)), -1.5);
    float illuminance = (e0_ * pow(10.0, (-0.4 * magnitude)));
    float _e203 = _group_0_binding_0_vs.camera_position.w;
    uint _e209 = _group_0_binding_0_vs.counts.y;
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
    uint index = uint(gl_VertexID);
    SpriteVertex out_ = SpriteVertex(vec4(0.0), vec2(0.0), 0u, vec4(0.0), 0.0);
    vec3 right = vec3(0.0);
    vec4 _e8 = texelFetch(_group_0_binding_22_vs, ivec2(uvec2((index / 6u), 0u)), 0);
    uint slot = uint(_e8.x);
    vec4 a_10 = texelFetch(_group_0_binding_20_vs, ivec2(uvec2(slot, 0u)), 0);
    vec4 b_10 = texelFetch(_group_0_binding_20_vs, ivec2(uvec2(slot, 1u)), 0);
    vec4 c_11 = texelFetch(_group_0_binding_20_vs, ivec2(uvec2(slot, 2u)), 0);
    if ((b_10.w <= 0.0)) {
        out_.position = vec4(0.0, 0.0, -1.0, 1.0);
        SpriteVertex _e35 = out_;
        gl_Position = _e35.position;
        _vs2fs_location0 = _e35.uv;
        _vs2fs_location1 = _e35.tile;
        _vs2fs_location2 = _e35.colour;
        _vs2fs_location3 = _e35.distance_;
        return;
    }
    float _e39 = _group_0_binding_0_vs.camera_position.y;
    vec3 cam = vec3(0.0, _e39, 0.0);
    vec3 _e45 = sprite_rel(a_10.xz, a_10.y);
    vec3 to_sprite = (_e45 - cam);
    float distance_ = length(to_sprite);
    float half_width = a_10.w;
    float facing = smoothstep((0.5 * half_width), half_width, distance_);
    vec3 to_camera = (-(to_sprite) / vec3(max(distance_, 0.001)));
    vec4 _e59 = _group_0_binding_0_vs.camera_forward;
    vec3 n_4 = normalize(mix(-(_e59.xyz), to_camera, facing));
    float _e67 = _group_0_binding_0_vs.atmosphere.x;
    vec3 radial = normalize((_e45 + vec3(0.0, _e67, 0.0)));
    right = cross(radial, n_4);
    vec3 _e75 = right;
    if ((length(_e75) < 0.001)) {
        vec4 _e81 = _group_0_binding_0_vs.camera_right;
        right = _e81.xyz;
    }
    vec3 _e83 = right;
    right = normalize(_e83);
    vec3 _e85 = right;
    vec3 up = cross(n_4, _e85);
    vec2 _e89 = sprite_corner((index % 6u));
    vec3 _e90 = right;
    vec3 offset_1 = ((_e90 * (_e89.x * half_width)) + (up * (_e89.y * c_11.z)));
    vec3 vertex = (to_sprite + offset_1);
    vec4 _e102 = _group_0_binding_0_vs.camera_right;
    float x_8 = dot(vertex, _e102.xyz);
    vec4 _e107 = _group_0_binding_0_vs.camera_up;
    float y_3 = dot(vertex, _e107.xyz);
    vec4 _e112 = _group_0_binding_0_vs.camera_forward;
    float z_4 = dot(vertex, _e112.xyz);
    float tan_half_3 = _group_0_binding_0_vs.camera_position.w;
    float _e123 = _group_0_binding_0_vs.camera_forward.w;
    out_.position = vec4((x_8 / (tan_half_3 * _e123)), (y_3 / tan_half_3), (0.5 * z_4), z_4);
    vec2 cs = vec2(cos(c_11.y), sin(c_11.y));
    vec2 t_6 = vec2(_e89.x, -(_e89.y));
    out_.uv = vec2(((t_6.x * cs.x) - (t_6.y * cs.y)), ((t_6.x * cs.y) + (t_6.y * cs.x)));
    out_.tile = uint(c_11.x);
    vec4 _e160 = _group_0_binding_0_vs.sun_direction;
    vec3 sun_3 = _e160.xyz;
    vec3 _e164 = sprite_rel(b_10.xz, b_10.y);
    vec3 centre_2 = (_e164 - cam);
    vec3 from_centre = (vertex - centre_2);
    float cos_angle_1 = (dot(from_centre, sun_3) / max(length(from_centre), 0.001));
    float _e177 = saturate(((sun_3.y * 4.0) + 0.3));
    float _e179 = altitude_of((vertex + cam));
    float _e183 = _group_0_binding_0_vs.atmosphere.y;
    float _e188 = _group_0_binding_0_vs.atmosphere.z;
    float _e192 = _group_0_binding_0_vs.atmosphere.y;
    float _e195 = saturate(((_e179 - _e183) / (_e188 - _e192)));
    vec4 _e198 = _group_0_binding_0_vs.sun_illuminance;
    vec3 e_2 = _e198.xyz;
    vec3 _e200 = sprite_sky_level(_e195);
    float _e204 = sprite_sun_level(cos_angle_1);
    vec3 light = ((e_2 * ((_e200 * (SPRITE_SKY * _e177)) + vec3(_e204))) * (c_11.w / PI));
    out_.colour = vec4(light, b_10.w);
    out_.distance_ = length(vertex);
    SpriteVertex _e217 = out_;
    gl_Position = _e217.position;
    _vs2fs_location0 = _e217.uv;
    _vs2fs_location1 = _e217.tile;
    _vs2fs_location2 = _e217.colour;
    _vs2fs_location3 = _e217.distance_;
    return;
}

