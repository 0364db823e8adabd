#version 450 core
#extension GL_ARB_compute_shader : require
layout(local_size_x = 8, local_size_y = 8, local_size_z = 1) in;

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
const bool LIGHT_MARCH = false;
const uint MAX_OCTAVES = 0u;
const bool DETAIL = false;
const bool CURL = false;
const bool STATS = true;

layout(binding = 3) uniform sampler2D _group_0_binding_3_cs;

layout(binding = 12,r32f) writeonly uniform image2D _group_0_binding_12_cs;


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

Layer layer_from(vec4 g, vec4 w_1) {
    return Layer(g.x, g.y, g.z, g.w, w_1.x, w_1.y, w_1.zw);
}

float sphere_discriminant(float r_2, float mu, float radius) {
    return (((radius - r_2) * (radius + r_2)) + (((r_2 * r_2) * mu) * mu));
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
    vec4 b_3 = mix(_e44, _e49, w_3.x);
    return mix(a_4, b_3, w_3.y);
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

float sky_ambient_x(float mu_8) {
    return (0.5 + ((0.5 * sign(mu_8)) * sqrt(abs(mu_8))));
}

float layer_height(Layer l_1, float alt_7) {
    return ((alt_7 - l_1.bottom) / (l_1.top - l_1.bottom));
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

uvec2 bayer2_(uint v_2) {
    return uvec2(((v_2 ^ (v_2 >> 1u)) & 1u), (v_2 & 1u));
}

uvec2 block_offset(uint f, uint k_7) {
    if ((k_7 == 2u)) {
        uvec2 _e6 = bayer2_((f % 4u));
        return _e6;
    }
    if ((k_7 == 4u)) {
        uint b_4 = (f % 16u);
        uvec2 _e13 = bayer2_((b_4 >> 2u));
        uvec2 _e17 = bayer2_((b_4 & 3u));
        return (_e13 + (2u * _e17));
    }
    return uvec2(0u);
}

vec4 catmull_rom(float t_1) {
    return vec4((t_1 * (-0.5 + (t_1 * (1.0 - (0.5 * t_1))))), (1.0 + ((t_1 * t_1) * (-2.5 + (1.5 * t_1)))), (t_1 * (0.5 + (t_1 * (2.0 - (1.5 * t_1))))), ((t_1 * t_1) * (-0.5 + (0.5 * t_1))));
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
    uint s_5 = rng_1;
    uint word_1 = (((s_5 >> ((s_5 >> 28u) + 4u)) ^ s_5) * 277803737u);
    return (float((((word_1 >> 22u) ^ word_1) >> 8u)) * 5.9604645e-8);
}

float rng_exponential(inout uint rng_2, float sigma) {
    float _e2 = rng_next(rng_2);
    return (-(log((1.0 - _e2))) / sigma);
}

float sample_hg_cos(float g_4, float u) {
    if ((abs(g_4) < 0.0001)) {
        return (1.0 - (2.0 * u));
    }
    float s_6 = ((1.0 - (g_4 * g_4)) / ((1.0 - g_4) + ((2.0 * g_4) * u)));
    return clamp((((1.0 + (g_4 * g_4)) - (s_6 * s_6)) / (2.0 * g_4)), -1.0, 1.0);
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
    vec2 f_2 = fract(p_14);
    vec2 s_7 = ((f_2 * f_2) * (vec2(3.0) - (2.0 * f_2)));
    uint h_11 = (seed * 7919u);
    float _e17 = atlas_hash((i_19.x + h_11), i_19.y);
    float _e23 = atlas_hash(((i_19.x + 1u) + h_11), i_19.y);
    float _e29 = atlas_hash((i_19.x + h_11), (i_19.y + 1u));
    float _e37 = atlas_hash(((i_19.x + 1u) + h_11), (i_19.y + 1u));
    return mix(mix(_e17, _e23, s_7.x), mix(_e29, _e37, s_7.x), s_7.y);
}

float value_fbm(vec2 p_15, uint seed_1) {
    float sum_5 = 0.0;
    float weight = 0.5;
    vec2 q_4 = vec2(0.0);
    uint o = 0u;
    q_4 = p_15;
    bool loop_init = true;
    while(true) {
        if (!loop_init) {
            uint _e26 = o;
            o = (_e26 + 1u);
        }
        loop_init = false;
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
    vec2 c_5 = (uv - vec2(0.5));
    float mask = smoothstep(0.48, 0.36, length(c_5));
    float _e16 = value_fbm(((uv * 6.0) + vec2((float(tile_1) * 13.0))), tile_1);
    if ((tile_1 < 4u)) {
        vec2 q_5 = (c_5 * vec2(1.0, 3.2));
        float streak = (1.0 - smoothstep(0.05, 0.45, length(q_5)));
        float _e40 = value_fbm(((uv * vec2(3.0, 12.0)) + vec2((float(tile_1) * 5.0))), (tile_1 + 16u));
        float _e46 = saturate(((_e40 * 1.6) - 0.3));
        return (((mask * streak) * _e46) * 0.8);
    }
    uint blobs = (5u + (tile_1 % 4u));
    bool loop_init_1 = true;
    while(true) {
        if (!loop_init_1) {
            uint _e108 = i_18;
            i_18 = (_e108 + 1u);
        }
        loop_init_1 = false;
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
            float r_14 = (0.14 + (0.1 * _e93));
            vec2 _e98 = at;
            float d_21 = (length((uv - _e98)) / r_14);
            float _e102 = billow;
            float _e106 = saturate((1.0 - (d_21 * d_21)));
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

vec3 sprite_sky_level(float h_10) {
    float _e1 = saturate(h_10);
    float x_6 = (_e1 * 4.0);
    if ((x_6 < 1.0)) {
        return mix(SKY_LEVEL0_, SKY_LEVEL1_, x_6);
    }
    if ((x_6 < 2.0)) {
        return mix(SKY_LEVEL1_, SKY_LEVEL2_, (x_6 - 1.0));
    }
    if ((x_6 < 3.0)) {
        return mix(SKY_LEVEL2_, SKY_LEVEL3_, (x_6 - 2.0));
    }
    return mix(SKY_LEVEL3_, SKY_LEVEL4_, (x_6 - 3.0));
}

float sprite_sun_level(float cos_angle) {
    if ((cos_angle < 0.0)) {
        return mix(SPRITE_C_MIN, SPRITE_C_MED, (cos_angle + 1.0));
    }
    return mix(SPRITE_C_MED, SPRITE_C_MAX, cos_angle);
}

vec2 sprite_corner(uint k_11) {
    bool local_63 = false;
    uint q_6 = ((k_11 >= 3u) ? ((k_11 == 3u) ? 0u : (k_11 - 2u)) : k_11);
    if (!((q_6 == 1u))) {
        local_63 = (q_6 == 2u);
    } else {
        local_63 = true;
    }
    bool _e18 = local_63;
    return vec2((_e18 ? 1.0 : -1.0), ((q_6 >= 2u) ? 1.0 : -1.0));
}

vec3 aces_fitted(vec3 x_5) {
    return clamp(((x_5 * ((2.51 * x_5) + vec3(0.03))) / ((x_5 * ((2.43 * x_5) + vec3(0.59))) + vec3(0.14))), vec3(0.0), vec3(1.0));
}

void main() {
    uvec3 id_7 = gl_GlobalInvocationID;
    float m = 0.0;
    int y = 0;
    int x = 0;
    if (any(greaterThanEqual(id_7.xy, uvec2(64u)))) {
        return;
    }
    ivec2 size_1 = ivec2(uvec2(textureSize(_group_0_binding_3_cs, 0).xy));
    ivec2 lo_1 = (((ivec2(id_7.xy) * size_1) / ivec2(64)) - ivec2(1));
    ivec2 hi = (((ivec2(id_7.xy) + ivec2(1)) * size_1) / ivec2(64));
    y = lo_1.y;
    bool loop_init_2 = true;
    while(true) {
        if (!loop_init_2) {
            int _e54 = y;
            y = (_e54 + 1);
        }
        loop_init_2 = false;
        int _e30 = y;
        if ((_e30 <= hi.y)) {
        } else {
            break;
        }
        {
            x = lo_1.x;
            bool loop_init_3 = true;
            while(true) {
                if (!loop_init_3) {
                    int _e51 = x;
                    x = (_e51 + 1);
                }
                loop_init_3 = false;
                int _e35 = x;
                if ((_e35 <= hi.x)) {
                } else {
                    break;
                }
                {
                    int _e38 = x;
                    int _e39 = y;
                    ivec2 t_5 = (((ivec2(_e38, _e39) % size_1) + size_1) % size_1);
                    float _e44 = m;
                    vec4 _e47 = texelFetch(_group_0_binding_3_cs, t_5, 0);
                    m = max(_e44, _e47.x);
                }
            }
        }
    }
    float _e58 = m;
    imageStore(_group_0_binding_12_cs, ivec2(id_7.xy), vec4(_e58, 0.0, 0.0, 0.0));
    return;
}

