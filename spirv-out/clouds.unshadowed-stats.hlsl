struct Frame {
    float4 camera_position;
    float4 camera_forward;
    float4 camera_right;
    float4 camera_up;
    float4 sun_direction;
    float4 sun_illuminance;
    float4 atmosphere;
    float4 clouds;
    float4 erosion;
    float4 periods;
    float4 wind_offsets0_;
    float4 wind_offsets1_;
    float4 extinction;
    float4 phase;
    float4 multiple_scattering;
    float4 ambient_bottom;
    float4 ambient_top;
    float4 march;
    uint4 counts;
    uint4 modes;
    uint4 misc;
    float4 previous_position;
    float4 previous_forward;
    float4 previous_right;
    float4 previous_up;
    uint4 temporal;
    float4 layer1_;
    float4 layer1_weather;
    float4 layer2_;
    float4 layer2_weather;
    float4 layer3_;
    float4 layer3_weather;
    float4 air_rayleigh;
    float4 air_mie;
    float4 air_ozone;
    float4 air_misc;
    float4 moon;
    float4 night;
    float4 light_model;
    float4 octave_direction;
    float4 octave_depth;
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
    float2 weather_offset;
};

struct AirSample {
    float3 rayleigh;
    float mie;
    float3 extinction;
    int _end_pad_0;
};

struct Scattered {
    float3 radiance;
    int _pad1_0;
    float3 transmittance;
    int _end_pad_0;
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
    float3 total;
    int _pad1_0;
    float3 octaves;
    int _end_pad_0;
};

struct Stats {
    uint counters[9];
};

struct MarchResult {
    float3 radiance;
    float transmittance;
    float depth;
    int _end_pad_0;
    int _end_pad_1;
    int _end_pad_2;
};

struct MarchState {
    float3 radiance;
    float transmittance;
    float depth_sum;
    int _pad3_0;
    int _pad3_1;
    int _pad3_2;
    float3 octaves;
    int _end_pad_0;
};

struct Segments {
    float2 a;
    float2 b;
    uint count;
    int _end_pad_0;
};

struct PhaseSample {
    float3 dir;
    float weight;
};

struct PathResult {
    float3 radiance;
    float transmittance;
    float depth;
    int _end_pad_0;
    int _end_pad_1;
    int _end_pad_2;
};

struct SpriteCell {
    int2 index;
    float size;
    bool covered;
};

struct SpriteCandidate {
    float2 xz;
    float alt;
    float h;
    float size_hash;
    float texture_hash;
    float rotation_hash;
    float density;
    float precipitation;
    int _end_pad_0;
};

struct SpriteVertex {
    float4 position : SV_Position;
    float2 uv : LOC0;
    nointerpolation uint tile : LOC1;
    float4 colour : LOC2;
    float distance_ : LOC3;
};

struct SpriteTargets {
    float4 radiance : SV_Target0;
    float4 depth : SV_Target1;
};

static const uint PHASE_HG = 0u;
static const uint PHASE_TWO_LOBE_HG = 1u;
static const uint PHASE_CORNETTE_SHANKS = 2u;
static const uint INTEGRATION_ANALYTIC = 0u;
static const uint INTEGRATION_RIEMANN = 1u;
static const uint HEIGHT_PARABOLA = 0u;
static const uint HEIGHT_CLOUD_TYPES = 1u;
static const uint FLAG_BEER_POWDER = 1u;
static const uint FLAG_JITTER = 2u;
static const uint FLAG_DYNAMIC_STEP = 4u;
static const uint FLAG_CHECKERBOARD = 8u;
static const uint FLAG_EMPTY_SKIP = 16u;
static const uint FLAG_PHYSICAL_SKY = 32u;
static const uint FLAG_MOONLIT = 64u;
static const float PI = 3.1415927;
static const uint MAX_VIEW_STEPS = 1024u;
static const uint RAY_MARCH = 0u;
static const uint RAY_MISSES_LAYER = 1u;
static const uint RAY_HITS_GROUND = 2u;
static const uint MAX_LAYERS = 4u;
static const uint2 TRANSMITTANCE_SIZE = uint2(256u, 64u);
static const uint2 MULTISCATTER_SIZE = uint2(32u, 32u);
static const uint2 SKY_VIEW_SIZE = uint2(192u, 108u);
static const uint AERIAL_SLICES = 32u;
static const uint AERIAL_SIDE = 32u;
static const float AERIAL_SLICE_KM = 1.0;
static const uint TRANSMITTANCE_STEPS = 128u;
static const uint MULTISCATTER_DIRECTIONS = 64u;
static const uint MULTISCATTER_STEPS = 32u;
static const uint SKY_VIEW_STEPS = 48u;
static const uint AMBIENT_DIRECTIONS = 64u;
static const uint AMBIENT_STEPS = 24u;
static const uint SKY_AMBIENT_SUNS = 64u;
static const uint GROUND_IRRADIANCE_SIZE = 64u;
static const uint NO_LAYER = 4u;
static const uint COLUMN_STEPS = 3u;
static const float DECK_POWER = 8.0;
static const float FORWARD_LOBE_THIN = 0.1;
static const uint GROUND_IRRADIANCE_DIRECTIONS = 128u;
static const uint SHADOW_SIZE = 128u;
static const float SHADOW_HALF_EXTENT = 20000.0;
static const float SHADOW_FADE_START = 0.75;
static const uint SHADOW_STEPS = 16u;
static const uint OCCUPANCY_CELLS = 64u;
static const uint STAT_PIXELS = 0u;
static const uint STAT_MARCHED = 1u;
static const uint STAT_VIEW_STEPS = 2u;
static const uint STAT_DENSITY = 3u;
static const uint STAT_DETAIL = 4u;
static const uint STAT_LIGHT = 5u;
static const uint STAT_EXIT_TRANSMITTANCE = 6u;
static const uint STAT_EXIT_MISSED = 7u;
static const uint STAT_EXIT_GROUND = 8u;
static const uint STAT_COUNT = 9u;
static const float HISTORY_SAMPLES = 16.0;
static const float HISTORY_SAMPLES_MOVING = 2.0;
static const float DISOCCLUSION_DEPTH = 0.5;
static const uint MAX_PATH_ORDERS = 16384u;
static const uint PATHS_PER_FRAME = 32u;
static const uint SPRITE_LEVELS = 4u;
static const int SPRITE_CELLS_PER_SIDE = int(8);
static const uint SPRITES_PER_CELL = 16u;
static const uint SPRITE_COUNT = 4096u;
static const float SPRITE_CELL0_ = 1500.0;
static const float SPRITE_ALPHA = 0.7;
static const float SPRITE_MAX_DISTANCE = 131072.0;
static const uint ATLAS_TILE = 64u;
static const float SPRITE_C_MIN = 0.22;
static const float SPRITE_C_MED = 0.55;
static const float SPRITE_C_MAX = 1.0;
static const float SPRITE_SKY = 0.35;
static const float3 SKY_LEVEL0_ = float3(0.42, 0.46, 0.55);
static const float3 SKY_LEVEL1_ = float3(0.55, 0.59, 0.67);
static const float3 SKY_LEVEL2_ = float3(0.7, 0.73, 0.8);
static const float3 SKY_LEVEL3_ = float3(0.84, 0.86, 0.9);
static const float3 SKY_LEVEL4_ = float3(0.95, 0.96, 0.98);
static const float MOON_COS_RADIUS = 0.9999898;
static const uint STAR_CELLS = 96u;
static const float STAR_FAINTEST = 6.5;
static const bool LIGHT_MARCH = false;
static const uint MAX_OCTAVES = 0u;
static const bool DETAIL = false;
static const bool CURL = false;
static const bool STATS = true;

cbuffer frame : register(b0) { Frame frame; }
Texture2D<float4> transmittance_lut_in : register(t27);
Texture2D<float4> multiscatter_lut_in : register(t28);
Texture2D<float4> sky_view_in : register(t29);
Texture2D<float4> aerial_in : register(t30);
Texture2D<float4> sky_ambient_in : register(t31);
RWTexture2D<float4> transmittance_lut_out : register(u32);
RWTexture2D<float4> multiscatter_lut_out : register(u33);
RWTexture2D<float4> sky_view_out : register(u34);
RWTexture2D<float4> aerial_out : register(u35);
RWTexture2D<float4> sky_ambient_out : register(u36);
Texture2D<float4> ground_irradiance_in : register(t38);
Texture3D<float4> shape_tex : register(t1);
Texture3D<float4> detail_tex : register(t2);
Texture2D<float4> weather_tex : register(t3);
Texture2D<float4> curl_tex : register(t4);
SamplerState nagaSamplerHeap[2048]: register(s32, space0);
SamplerComparisonState nagaComparisonSamplerHeap[2048]: register(s33, space0);
StructuredBuffer<uint> nagaGroup0SamplerIndexArray : register(t34, space0);
static const SamplerState noise_sampler = nagaSamplerHeap[nagaGroup0SamplerIndexArray[5]];
RWTexture2D<float4> ground_irradiance_out : register(u39);
Texture2D<float4> cloud_shadow_in : register(t40);
RWTexture2D<float> cloud_shadow_out : register(u41);
Texture2D<float4> occupancy_in : register(t11);
RWTexture2D<float> occupancy_out : register(u12);
RWTexture2D<float4> cloud_out : register(u6);
RWTexture2D<float> depth_out : register(u7);
RWByteAddressBuffer stats : register(u8);
Texture2D<float4> history_in : register(t13);
Texture2D<float4> meta_in : register(t14);
Texture2D<float4> sparse_in : register(t15);
Texture2D<float4> sparse_depth_in : register(t16);
RWTexture2D<float4> history_out : register(u17);
RWTexture2D<float4> meta_out : register(u18);
groupshared float4 lane_sums[32];
groupshared float4 lane_moments[32];
RWTexture2D<float4> sprites_out : register(u19);
Texture2D<float4> sprites_in : register(t20);
RWTexture2D<float> sprite_order_out : register(u21);
Texture2D<float4> sprite_order_in : register(t22);
RWTexture2D<unorm float4> sprite_atlas_out : register(u23);
Texture2D<float4> sprite_atlas_in : register(t24);
Texture2D<float4> sprite_radiance_in : register(t25);
Texture2D<float4> sprite_depth_in : register(t26);
Texture2D<float4> cloud_in : register(t9);
RWTexture2D<unorm float4> image_out : register(u10);
Texture2D<float4> depth_in : register(t37);

struct VertexOutput_sprite_vertex {
    float2 uv_2 : LOC0;
    nointerpolation uint tile_2 : LOC1;
    float4 colour : LOC2;
    float distance_ : LOC3;
    float4 position : SV_Position;
};

struct FragmentInput_sprite_fragment {
    float2 uv_3 : LOC0;
    nointerpolation uint tile_3 : LOC1;
    float4 colour_1 : LOC2;
    float distance_1 : LOC3;
    float4 position_1 : SV_Position;
};

float saturate_(float x_1)
{
    return clamp(x_1, 0.0, 1.0);
}

float remap(float x_2, float lo0_, float hi0_, float lo1_, float hi1_)
{
    return (lo1_ + (((x_2 - lo0_) * (hi1_ - lo1_)) / (hi0_ - lo0_)));
}

uint pcg(uint v)
{
    uint state_2 = ((v * 747796405u) + 2891336453u);
    uint word = (((state_2 >> ((state_2 >> 28u) + 4u)) ^ state_2) * 277803737u);
    return ((word >> 22u) ^ word);
}

float van_der_corput(uint n)
{
    return (float((reversebits(n) >> 8u)) * 5.9604645e-8);
}

float hash_unit(uint2 pixel, uint frame_index)
{
    const uint _e4 = pcg(frame_index);
    const uint _e6 = pcg((pixel.y ^ _e4));
    const uint _e8 = pcg((pixel.x ^ _e6));
    return (float((_e8 >> 8u)) * 5.9604645e-8);
}

float3 view_ray(uint2 pixel_1)
{
    uint4 _e3 = frame.counts;
    float2 size_1 = float2(_e3.xy);
    float2 ndc = ((((float2(pixel_1) + (0.5).xx) / size_1) * 2.0) - (1.0).xx);
    float tan_half = frame.camera_position.w;
    float aspect = frame.camera_forward.w;
    float4 _e26 = frame.camera_forward;
    float4 _e30 = frame.camera_right;
    float4 _e39 = frame.camera_up;
    float3 d_21 = ((_e26.xyz + (_e30.xyz * ((ndc.x * tan_half) * aspect))) - (_e39.xyz * (ndc.y * tan_half)));
    return normalize(d_21);
}

Roots ConstructRoots(float arg0, float arg1, bool arg2) {
    Roots ret = (Roots)0;
    ret.t0_ = arg0;
    ret.t1_ = arg1;
    ret.hit = arg2;
    return ret;
}

Roots solve_sphere(float b, float c)
{
    float disc = ((b * b) - c);
    if ((disc < 0.0)) {
        const Roots roots = ConstructRoots(0.0, 0.0, false);
        return roots;
    }
    float s_3 = sqrt(disc);
    float r0_1 = -((b + ((b >= 0.0) ? s_3 : -(s_3))));
    if ((r0_1 == 0.0)) {
        const Roots roots_1 = ConstructRoots(0.0, 0.0, true);
        return roots_1;
    }
    float r1_1 = (c / r0_1);
    const Roots roots_2 = ConstructRoots(min(r0_1, r1_1), max(r0_1, r1_1), true);
    return roots_2;
}

Roots ray_shell(float alt, float3 d, float radius_alt)
{
    float rp = frame.atmosphere.x;
    float b_3 = (d.y * (alt + rp));
    float c_5 = ((alt - radius_alt) * ((alt + radius_alt) + (2.0 * rp)));
    const Roots _e16 = solve_sphere(b_3, c_5);
    const Roots roots_3 = _e16;
    return roots_3;
}

float altitude_of(float3 p)
{
    float rp_1 = frame.atmosphere.x;
    float n_3 = (((p.x * p.x) + (p.z * p.z)) + (p.y * (p.y + (2.0 * rp_1))));
    float3 q_5 = float3(p.x, (p.y + rp_1), p.z);
    return (n_3 / (length(q_5) + rp_1));
}

bool hits_ground(float3 p_1, float alt_1, float3 d_1)
{
    bool local_15 = (bool)0;

    float rp_2 = frame.atmosphere.x;
    float b_4 = dot(d_1, float3(p_1.x, (p_1.y + rp_2), p_1.z));
    float c_6 = (alt_1 * (alt_1 + (2.0 * rp_2)));
    if ((b_4 < 0.0)) {
        local_15 = ((b_4 * b_4) >= c_6);
    } else {
        local_15 = false;
    }
    bool _e24 = local_15;
    return _e24;
}

Interval ConstructInterval(float arg0, float arg1, uint arg2) {
    Interval ret = (Interval)0;
    ret.start = arg0;
    ret.length_ = arg1;
    ret.kind = arg2;
    return ret;
}

Interval shell_interval(float alt_2, float3 d_2, float bottom, float top)
{
    float start = 0.0;
    float end = 0.0;
    bool local_16 = (bool)0;
    bool local_17 = (bool)0;
    bool local_18 = (bool)0;

    float cutoff = frame.atmosphere.w;
    const Roots _e8 = ray_shell(alt_2, d_2, bottom);
    const Roots _e9 = ray_shell(alt_2, d_2, top);
    if ((alt_2 < bottom)) {
        const bool _e18 = hits_ground(float3(0.0, alt_2, 0.0), alt_2, d_2);
        if (_e18) {
            const Interval interval = ConstructInterval(0.0, 0.0, 2u);
            return interval;
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
                const Interval interval_1 = ConstructInterval(0.0, 0.0, 1u);
                return interval_1;
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
        const Interval interval_2 = ConstructInterval(0.0, 0.0, 1u);
        return interval_2;
    }
    float _e78 = start;
    const Interval interval_3 = ConstructInterval(_e78, len, RAY_MARCH);
    return interval_3;
}

Interval layer_interval(float alt_3, float3 d_3, Layer l)
{
    const Interval _e5 = shell_interval(alt_3, d_3, l.bottom, l.top);
    const Interval interval_4 = _e5;
    return interval_4;
}

uint layer_count()
{
    uint _e4 = frame.misc.w;
    return (1u + min(_e4, 3u));
}

Layer ConstructLayer(float arg0, float arg1, float arg2, float arg3, float arg4, float arg5, float2 arg6) {
    Layer ret = (Layer)0;
    ret.bottom = arg0;
    ret.top = arg1;
    ret.coverage = arg2;
    ret.density = arg3;
    ret.cloud_type = arg4;
    ret.precipitation = arg5;
    ret.weather_offset = arg6;
    return ret;
}

Layer layer_from(float4 g, float4 w_1)
{
    const Layer layer = ConstructLayer(g.x, g.y, g.z, g.w, w_1.x, w_1.y, w_1.zw);
    return layer;
}

Layer cloud_layer(uint i_5)
{
    if ((i_5 == 1u)) {
        float4 _e5 = frame.layer1_;
        float4 _e8 = frame.layer1_weather;
        const Layer _e9 = layer_from(_e5, _e8);
        const Layer layer_1 = _e9;
        return layer_1;
    } else {
        if ((i_5 == 2u)) {
            float4 _e14 = frame.layer2_;
            float4 _e17 = frame.layer2_weather;
            const Layer _e18 = layer_from(_e14, _e17);
            const Layer layer_2 = _e18;
            return layer_2;
        } else {
            if ((i_5 == 3u)) {
                float4 _e23 = frame.layer3_;
                float4 _e26 = frame.layer3_weather;
                const Layer _e27 = layer_from(_e23, _e26);
                const Layer layer_3 = _e27;
                return layer_3;
            }
        }
    }
    float _e31 = frame.atmosphere.y;
    float _e35 = frame.atmosphere.z;
    float _e39 = frame.clouds.x;
    float _e43 = frame.clouds.y;
    float _e47 = frame.clouds.z;
    float _e51 = frame.clouds.w;
    float4 _e54 = frame.wind_offsets0_;
    const Layer layer_4 = ConstructLayer(_e31, _e35, _e39, _e43, _e47, _e51, _e54.xy);
    return layer_4;
}

float2 layers_span()
{
    float2 span = (float2)0;
    uint i_6 = 1u;

    float4 _e2 = frame.atmosphere;
    span = _e2.yz;
    uint2 loop_bound = uint2(4294967295u, 4294967295u);
    bool loop_init = true;
    while(true) {
        if (all(loop_bound == uint2(0u, 0u))) { break; }
        loop_bound -= uint2(loop_bound.y == 0u, 1u);
        if (!loop_init) {
            uint _e22 = i_6;
            i_6 = (_e22 + 1u);
        }
        loop_init = false;
        uint _e7 = i_6;
        const uint _e8 = layer_count();
        if ((_e7 < _e8)) {
        } else {
            break;
        }
        {
            uint _e10 = i_6;
            const Layer _e11 = cloud_layer(_e10);
            float _e13 = span.x;
            float _e17 = span.y;
            span = float2(min(_e13, _e11.bottom), max(_e17, _e11.top));
        }
    }
    float2 _e24 = span;
    return _e24;
}

Interval cloud_interval(float alt_4, float3 d_4)
{
    const float2 _e2 = layers_span();
    const Interval _e5 = shell_interval(alt_4, d_4, _e2.x, _e2.y);
    const Interval interval_5 = _e5;
    return interval_5;
}

Interval nearest_layer_interval(float alt_5, float3 d_5)
{
    Interval best = (Interval)0;
    uint i_7 = 1u;
    bool local_19 = (bool)0;
    bool local_20 = (bool)0;

    const Layer _e3 = cloud_layer(0u);
    const Interval _e4 = layer_interval(alt_5, d_5, _e3);
    best = _e4;
    uint2 loop_bound_1 = uint2(4294967295u, 4294967295u);
    bool loop_init_1 = true;
    while(true) {
        if (all(loop_bound_1 == uint2(0u, 0u))) { break; }
        loop_bound_1 -= uint2(loop_bound_1.y == 0u, 1u);
        if (!loop_init_1) {
            uint _e35 = i_7;
            i_7 = (_e35 + 1u);
        }
        loop_init_1 = false;
        uint _e8 = i_7;
        const uint _e9 = layer_count();
        if ((_e8 < _e9)) {
        } else {
            break;
        }
        {
            uint _e11 = i_7;
            const Layer _e12 = cloud_layer(_e11);
            const Interval _e13 = layer_interval(alt_5, d_5, _e12);
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
    const Interval interval_6 = _e37;
    return interval_6;
}

Roots ray_shell_from(float3 p_2, float alt_6, float3 d_6, float radius_alt_1)
{
    float rp_3 = frame.atmosphere.x;
    float b_5 = dot(d_6, float3(p_2.x, (p_2.y + rp_3), p_2.z));
    float c_7 = ((alt_6 - radius_alt_1) * ((alt_6 + radius_alt_1) + (2.0 * rp_3)));
    const Roots _e20 = solve_sphere(b_5, c_7);
    const Roots roots_4 = _e20;
    return roots_4;
}

bool physical_sky()
{
    uint _e3 = frame.modes.w;
    return ((_e3 & FLAG_PHYSICAL_SKY) != 0u);
}

float air_bottom()
{
    float _e3 = frame.atmosphere.x;
    return (_e3 * 0.001);
}

float air_top()
{
    float _e3 = frame.atmosphere.x;
    float _e7 = frame.air_misc.x;
    return ((_e3 + _e7) * 0.001);
}

AirSample ConstructAirSample(float3 arg0, float arg1, float3 arg2) {
    AirSample ret = (AirSample)0;
    ret.rayleigh = arg0;
    ret.mie = arg1;
    ret.extinction = arg2;
    return ret;
}

AirSample air_at(float h_km)
{
    float h_11 = (max(h_km, 0.0) * 1000.0);
    float _e9 = frame.air_rayleigh.w;
    float rayleigh_density = exp((-(h_11) / _e9));
    float _e16 = frame.air_mie.z;
    float mie_density = exp((-(h_11) / _e16));
    float _e22 = frame.air_ozone.w;
    float _e28 = frame.air_misc.y;
    float ozone_density = max((1.0 - (abs((h_11 - _e22)) / (0.5 * _e28))), 0.0);
    float4 _e38 = frame.air_rayleigh;
    float3 rayleigh = (_e38.xyz * (rayleigh_density * 1000.0));
    float _e46 = frame.air_mie.x;
    float mie = ((_e46 * mie_density) * 1000.0);
    float _e53 = frame.air_mie.x;
    float _e57 = frame.air_mie.y;
    float mie_extinction = (((_e53 + _e57) * mie_density) * 1000.0);
    float4 _e64 = frame.air_ozone;
    float3 ozone = (_e64.xyz * (ozone_density * 1000.0));
    const AirSample airsample = ConstructAirSample(rayleigh, mie, ((rayleigh + (mie_extinction).xxx) + ozone));
    return airsample;
}

float sphere_discriminant(float r_2, float mu, float radius)
{
    return (((radius - r_2) * (radius + r_2)) + (((r_2 * r_2) * mu) * mu));
}

float distance_to_top(float r_3, float mu_1)
{
    const float _e4 = air_top();
    const float _e5 = sphere_discriminant(r_3, mu_1, _e4);
    return max(((-(r_3) * mu_1) + sqrt(max(_e5, 0.0))), 0.0);
}

bool meets_ground(float r_4, float mu_2)
{
    bool local_21 = (bool)0;

    if ((mu_2 < 0.0)) {
        const float _e6 = air_bottom();
        const float _e7 = sphere_discriminant(r_4, mu_2, _e6);
        local_21 = (_e7 >= 0.0);
    } else {
        local_21 = false;
    }
    bool _e11 = local_21;
    return _e11;
}

float distance_to_ground(float r_5, float mu_3)
{
    const float _e4 = air_bottom();
    const float _e5 = sphere_discriminant(r_5, mu_3, _e4);
    return max(((-(r_5) * mu_3) - sqrt(max(_e5, 0.0))), 0.0);
}

float radius_after(float r_6, float mu_4, float t)
{
    return sqrt(max((((r_6 * r_6) + (t * t)) + (((2.0 * r_6) * mu_4) * t)), 0.0));
}

uint2 naga_f2u32(float2 value) {
    return uint2(clamp(value, 0.0, 4294967000.0));
}

float4 lut_bilinear(Texture2D<float4> lut, float2 x_3, uint2 size)
{
    float2 last = float2((size - (1u).xx));
    float2 f_1 = (clamp(x_3, (0.0).xx, (1.0).xx) * last);
    uint2 i0_ = min(naga_f2u32(floor(f_1)), (size - (1u).xx));
    uint2 i1_ = min((i0_ + (1u).xx), (size - (1u).xx));
    float2 w_3 = (f_1 - float2(i0_));
    float4 _e32 = lut.Load(int3(uint2(i0_.x, i0_.y), int(0)));
    float4 _e37 = lut.Load(int3(uint2(i1_.x, i0_.y), int(0)));
    float4 a_4 = lerp(_e32, _e37, w_3.x);
    float4 _e44 = lut.Load(int3(uint2(i0_.x, i1_.y), int(0)));
    float4 _e49 = lut.Load(int3(uint2(i1_.x, i1_.y), int(0)));
    float4 b_6 = lerp(_e44, _e49, w_3.x);
    return lerp(a_4, b_6, w_3.y);
}

float2 transmittance_coords(float r_7, float mu_5)
{
    const float _e2 = air_bottom();
    const float _e3 = air_top();
    float h_12 = sqrt(max(((_e3 - _e2) * (_e3 + _e2)), 0.0));
    float rho = sqrt(max(((r_7 - _e2) * (r_7 + _e2)), 0.0));
    const float _e16 = distance_to_top(r_7, mu_5);
    float d_min = (_e3 - r_7);
    float d_max = (rho + h_12);
    return float2(((_e16 - d_min) / max((d_max - d_min), 1e-6)), (rho / h_12));
}

float2 transmittance_r_mu(float2 x_4)
{
    float mu_6 = 1.0;

    const float _e1 = air_bottom();
    const float _e2 = air_top();
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
    return float2(r_14, _e37);
}

float3 transmittance_to_top(float r_8, float mu_7)
{
    const float2 _e3 = transmittance_coords(r_8, mu_7);
    const float4 _e5 = lut_bilinear(transmittance_lut_in, _e3, TRANSMITTANCE_SIZE);
    return _e5.xyz;
}

float3 sun_transmittance(float r_9, float mu_s)
{
    const bool _e2 = meets_ground(r_9, mu_s);
    if (_e2) {
        return (0.0).xxx;
    }
    const float3 _e5 = transmittance_to_top(r_9, mu_s);
    return _e5;
}

float3 multiscatter(float r_10, float mu_s_1)
{
    const float _e6 = air_bottom();
    const float _e8 = air_top();
    const float _e9 = air_bottom();
    float2 x_6 = float2(((mu_s_1 * 0.5) + 0.5), ((r_10 - _e6) / (_e8 - _e9)));
    const float4 _e15 = lut_bilinear(multiscatter_lut_in, x_6, MULTISCATTER_SIZE);
    return _e15.xyz;
}

float phase_rayleigh(float cos_theta)
{
    return (0.059683103 * (1.0 + (cos_theta * cos_theta)));
}

float phase_cornette_shanks_air(float cos_theta_1, float g_1)
{
    float g2_ = (g_1 * g_1);
    return (((0.119366206 * (1.0 - g2_)) * (1.0 + (cos_theta_1 * cos_theta_1))) / ((2.0 + g2_) * pow(max(((1.0 + g2_) - ((2.0 * g_1) * cos_theta_1)), 1e-6), 1.5)));
}

float3 fibonacci_direction(uint k_5, uint n_1)
{
    float z_2 = (1.0 - (((2.0 * float(k_5)) + 1.0) / float(n_1)));
    float s_4 = sqrt(max((1.0 - (z_2 * z_2)), 0.0));
    float phi = (2.3999634 * float(k_5));
    return float3((s_4 * cos(phi)), z_2, (s_4 * sin(phi)));
}

float3 ground_radiance_sun(float mu_s_2)
{
    float _e4 = frame.air_misc.z;
    const float _e10 = air_bottom();
    const float3 _e13 = sun_transmittance((_e10 + 0.001), mu_s_2);
    return (((_e4 / PI) * max(mu_s_2, 0.0)) * _e13);
}

Scattered ConstructScattered(float3 arg0, float3 arg1) {
    Scattered ret = (Scattered)0;
    ret.radiance = arg0;
    ret.transmittance = arg1;
    return ret;
}

Scattered integrate_air(float3 origin, float3 d_7, float distance_km, uint steps, float3 sun)
{
    float3 radiance_1 = (0.0).xxx;
    float3 tau_3 = (0.0).xxx;
    float t0_ = 0.0;
    uint i_8 = 0u;

    float cos_theta_8 = dot(d_7, sun);
    const float _e6 = phase_rayleigh(cos_theta_8);
    float _e10 = frame.air_mie.w;
    const float _e11 = phase_cornette_shanks_air(cos_theta_8, _e10);
    uint2 loop_bound_2 = uint2(4294967295u, 4294967295u);
    bool loop_init_2 = true;
    while(true) {
        if (all(loop_bound_2 == uint2(0u, 0u))) { break; }
        loop_bound_2 -= uint2(loop_bound_2.y == 0u, 1u);
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
            float3 p_16 = (origin + (d_7 * (0.5 * (_e34 + t1_))));
            float r_15 = length(p_16);
            float3 up = (p_16 / (r_15).xxx);
            float mu_s_5 = dot(up, sun);
            const float _e44 = air_bottom();
            const AirSample _e46 = air_at((r_15 - _e44));
            float3 _e47 = tau_3;
            float3 t_view = exp(-((_e47 + ((0.5 * _e46.extinction) * dt_1))));
            const float3 _e55 = sun_transmittance(r_15, mu_s_5);
            const float3 _e56 = multiscatter(r_15, mu_s_5);
            float3 inscatter = ((_e55 * ((_e46.rayleigh * _e6) + ((_e46.mie * _e11)).xxx)) + (_e56 * (_e46.rayleigh + (_e46.mie).xxx)));
            float3 _e70 = radiance_1;
            radiance_1 = (_e70 + ((t_view * inscatter) * dt_1));
            float3 _e74 = tau_3;
            tau_3 = (_e74 + (_e46.extinction * dt_1));
            t0_ = t1_;
        }
    }
    float3 _e81 = radiance_1;
    float3 _e82 = tau_3;
    const Scattered scattered = ConstructScattered(_e81, exp(-(_e82)));
    return scattered;
}

float3 sky_irradiance(float mu_s_3)
{
    float2 x_7 = float2(((mu_s_3 * 0.5) + 0.5), 0.0);
    const float4 _e11 = lut_bilinear(ground_irradiance_in, x_7, uint2(64u, 1u));
    return _e11.xyz;
}

float3 ground_radiance(float mu_s_4)
{
    const float3 _e1 = ground_radiance_sun(mu_s_4);
    float _e5 = frame.air_misc.z;
    const float3 _e8 = sky_irradiance(mu_s_4);
    return (_e1 + ((_e5 / PI) * _e8));
}

float3 with_ground(Scattered s, float3 origin_1, float3 d_8, float distance_km_1, float3 sun_1, bool ground)
{
    if (!(ground)) {
        return s.radiance;
    }
    float3 end_1 = (origin_1 + (d_8 * distance_km_1));
    const float3 _e14 = ground_radiance(dot(normalize(end_1), sun_1));
    return (s.radiance + (s.transmittance * _e14));
}

float2 air_ray_end(float3 origin_2, float3 d_9)
{
    float r_16 = length(origin_2);
    float mu_9 = (dot(origin_2, d_9) / r_16);
    const bool _e5 = meets_ground(r_16, mu_9);
    if (_e5) {
        const float _e6 = distance_to_ground(r_16, mu_9);
        return float2(_e6, 1.0);
    }
    const float _e9 = air_top();
    if ((r_16 > _e9)) {
        return float2(0.0, 0.0);
    }
    const float _e14 = distance_to_top(r_16, mu_9);
    return float2(_e14, 0.0);
}

float3 camera_air_origin()
{
    const float _e0 = air_bottom();
    float _e4 = frame.camera_position.y;
    return float3(0.0, (_e0 + (max(_e4, 0.0) * 0.001)), 0.0);
}

float sky_view_elevation(float v_1, float horizon)
{
    if ((v_1 >= 0.5)) {
        float a_5 = ((2.0 * v_1) - 1.0);
        return (horizon + (((1.5707964 - horizon) * a_5) * a_5));
    }
    float a_6 = (1.0 - (2.0 * v_1));
    return (horizon - (((horizon + 1.5707964) * a_6) * a_6));
}

float sky_view_v(float elevation, float horizon_1)
{
    if ((elevation >= horizon_1)) {
        const float _e7 = saturate_(((elevation - horizon_1) / (1.5707964 - horizon_1)));
        return (0.5 + (0.5 * sqrt(_e7)));
    }
    const float _e17 = saturate_(((horizon_1 - elevation) / (horizon_1 + 1.5707964)));
    return (0.5 - (0.5 * sqrt(_e17)));
}

float horizon_elevation(float r_11)
{
    const float _e1 = air_bottom();
    return -(acos(clamp((_e1 / r_11), -1.0, 1.0)));
}

float sun_azimuth()
{
    float4 _e2 = frame.sun_direction;
    float3 s_5 = _e2.xyz;
    return atan2(s_5.z, s_5.x);
}

float3 sky_along(float3 origin_3, float3 d_10)
{
    const float2 _e2 = air_ray_end(origin_3, d_10);
    float4 _e5 = frame.sun_direction;
    float3 sun_2 = _e5.xyz;
    const Scattered _e9 = integrate_air(origin_3, d_10, _e2.x, SKY_VIEW_STEPS, sun_2);
    const float3 _e14 = with_ground(_e9, origin_3, d_10, _e2.x, sun_2, (_e2.y > 0.5));
    return _e14;
}

float3 sky_from(float3 rel, float3 d_11)
{
    float _e7 = frame.atmosphere.x;
    const float3 _e13 = sky_along((float3(rel.x, (rel.y + _e7), rel.z) * 0.001), d_11);
    return _e13;
}

float3 sky_view(float3 d_12)
{
    float delta = (float)0;

    const float3 _e1 = camera_air_origin();
    float elevation_1 = asin(clamp(d_12.y, -1.0, 1.0));
    const float _e10 = sun_azimuth();
    delta = (atan2(d_12.z, d_12.x) - _e10);
    float _e13 = delta;
    float _e15 = delta;
    delta = abs((_e13 - (6.2831855 * round((_e15 / 6.2831855)))));
    float _e22 = delta;
    const float _e26 = horizon_elevation(_e1.y);
    const float _e27 = sky_view_v(elevation_1, _e26);
    float2 x_8 = float2((_e22 / PI), _e27);
    const float4 _e31 = lut_bilinear(sky_view_in, x_8, SKY_VIEW_SIZE);
    return _e31.xyz;
}

float3 aerial_ray(uint2 c_1)
{
    float2 ndc_1 = ((((float2(c_1) + (0.5).xx) / (32.0).xx) * 2.0) - (1.0).xx);
    float tan_half_1 = frame.camera_position.w;
    float aspect_1 = frame.camera_forward.w;
    float4 _e23 = frame.camera_forward;
    float4 _e27 = frame.camera_right;
    float4 _e36 = frame.camera_up;
    return normalize(((_e23.xyz + (_e27.xyz * ((ndc_1.x * tan_half_1) * aspect_1))) - (_e36.xyz * (ndc_1.y * tan_half_1))));
}

float4 aerial_texel(uint2 c0_, uint2 c1_, float2 w_2, uint z_1)
{
    uint o_1 = (z_1 * AERIAL_SIDE);
    float4 _e12 = aerial_in.Load(int3(uint2((o_1 + c0_.x), c0_.y), int(0)));
    float4 _e19 = aerial_in.Load(int3(uint2((o_1 + c1_.x), c0_.y), int(0)));
    float4 a_7 = lerp(_e12, _e19, w_2.x);
    float4 _e28 = aerial_in.Load(int3(uint2((o_1 + c0_.x), c1_.y), int(0)));
    float4 _e35 = aerial_in.Load(int3(uint2((o_1 + c1_.x), c1_.y), int(0)));
    float4 b_7 = lerp(_e28, _e35, w_2.x);
    return lerp(a_7, b_7, w_2.y);
}

uint naga_f2u32(float value) {
    return uint(clamp(value, 0.0, 4294967000.0));
}

float4 aerial(uint2 pixel_2, float depth_m)
{
    float4 near = float4(0.0, 0.0, 0.0, 1.0);
    float4 far = float4(0.0, 0.0, 0.0, 1.0);

    uint4 _e8 = frame.counts;
    float2 uv_4 = ((float2(pixel_2) + (0.5).xx) / float2(_e8.xy));
    float2 f_2 = clamp(((uv_4 * 32.0) - (0.5).xx), (0.0).xx, (31.0).xx);
    uint2 c0_1 = min(naga_f2u32(floor(f_2)), (31u).xx);
    uint2 c1_1 = min((c0_1 + (1u).xx), (31u).xx);
    float2 w_4 = (f_2 - float2(c0_1));
    float s_6 = clamp(((depth_m * 0.001) / AERIAL_SLICE_KM), 0.0, 32.0);
    uint z1_ = min(naga_f2u32(ceil(s_6)), AERIAL_SLICES);
    uint z0_ = ((z1_ > 0u) ? (z1_ - 1u) : 0u);
    float ws = (s_6 - float(z0_));
    if ((z0_ > 0u)) {
        const float4 _e64 = aerial_texel(c0_1, c1_1, w_4, (z0_ - 1u));
        near = _e64;
    }
    if ((z1_ > 0u)) {
        const float4 _e75 = aerial_texel(c0_1, c1_1, w_4, (z1_ - 1u));
        far = _e75;
    }
    float4 _e76 = near;
    float4 _e77 = far;
    return lerp(_e76, _e77, ws);
}

float3 sun_through_air(float3 rel_1)
{
    const bool _e1 = physical_sky();
    if (!(_e1)) {
        return (1.0).xxx;
    }
    float _e10 = frame.atmosphere.x;
    float3 q_6 = (float3(rel_1.x, (rel_1.y + _e10), rel_1.z) * 0.001);
    float r_17 = length(q_6);
    float4 _e21 = frame.sun_direction;
    const float3 _e24 = sun_transmittance(r_17, dot((q_6 / (r_17).xxx), _e21.xyz));
    return _e24;
}

float sky_ambient_x(float mu_8)
{
    return (0.5 + ((0.5 * sign(mu_8)) * sqrt(abs(mu_8))));
}

float3 sky_ambient_light(float h, float3 rel_2)
{
    float _e7 = frame.atmosphere.x;
    float3 q_7 = float3(rel_2.x, (rel_2.y + _e7), rel_2.z);
    float4 _e14 = frame.sun_direction;
    const float _e17 = sky_ambient_x(dot(normalize(q_7), _e14.xyz));
    uint2 size_2 = uint2(64u, 2u);
    const float4 _e24 = lut_bilinear(sky_ambient_in, float2(_e17, 0.0), size_2);
    float3 bottom_1 = _e24.xyz;
    const float4 _e29 = lut_bilinear(sky_ambient_in, float2(_e17, 1.0), size_2);
    float3 top_1 = _e29.xyz;
    float4 _e34 = frame.sun_illuminance;
    float _e40 = frame.ambient_bottom.w;
    return ((lerp(bottom_1, top_1, h) * _e34.xyz) * _e40);
}

float layer_height(Layer l_1, float alt_7)
{
    return ((alt_7 - l_1.bottom) / (l_1.top - l_1.bottom));
}

uint layer_at(float alt_8)
{
    uint i_9 = 0u;
    bool local_22 = (bool)0;

    uint2 loop_bound_3 = uint2(4294967295u, 4294967295u);
    bool loop_init_3 = true;
    while(true) {
        if (all(loop_bound_3 == uint2(0u, 0u))) { break; }
        loop_bound_3 -= uint2(loop_bound_3.y == 0u, 1u);
        if (!loop_init_3) {
            uint _e19 = i_9;
            i_9 = (_e19 + 1u);
        }
        loop_init_3 = false;
        uint _e3 = i_9;
        const uint _e4 = layer_count();
        if ((_e3 < _e4)) {
        } else {
            break;
        }
        {
            uint _e6 = i_9;
            const Layer _e7 = cloud_layer(_e6);
            const float _e8 = layer_height(_e7, alt_8);
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

Weather ConstructWeather(float arg0, float arg1, float arg2) {
    Weather ret = (Weather)0;
    ret.coverage = arg0;
    ret.cloud_type = arg1;
    ret.precipitation = arg2;
    return ret;
}

Weather sample_weather(float3 p_3, Layer l_2)
{
    float _e8 = frame.periods.x;
    float2 uv_5 = ((p_3.xz - l_2.weather_offset) / (_e8).xx);
    float4 w_5 = weather_tex.SampleLevel(noise_sampler, uv_5, 0.0);
    const float _e22 = saturate_((w_5.x + (2.0 * (l_2.coverage - 0.5))));
    const float _e30 = saturate_((l_2.cloud_type + ((w_5.z - 0.5) * 0.5)));
    const float _e35 = saturate_((0.5 + w_5.y));
    float precipitation = (l_2.precipitation * _e35);
    const Weather weather = ConstructWeather(_e22, _e30, precipitation);
    return weather;
}

float height_parabola(float h_1, float cloud_type)
{
    float height = lerp(0.35, 1.0, cloud_type);
    const float _e11 = saturate_(((h_1 * (h_1 - height)) * (-4.0 / (height * height))));
    return _e11;
}

float gradient(float h_2, float r0_, float r1_, float f0_, float f1_)
{
    return (smoothstep(r0_, r1_, h_2) * (1.0 - smoothstep(f0_, f1_, h_2)));
}

float height_cloud_types(float h_3, float cloud_type_1)
{
    const float _e6 = gradient(h_3, 0.0, 0.08, 0.15, 0.25);
    const float _e11 = gradient(h_3, 0.0, 0.2, 0.4, 0.65);
    const float _e16 = gradient(h_3, 0.0, 0.1, 0.6, 0.95);
    const float _e19 = saturate_((cloud_type_1 * 2.0));
    float lo = lerp(_e6, _e11, _e19);
    const float _e25 = saturate_(((cloud_type_1 * 2.0) - 1.0));
    return lerp(lo, _e16, _e25);
}

float height_signal(float h_4, float cloud_type_2)
{
    uint _e5 = frame.modes.z;
    if ((_e5 == HEIGHT_CLOUD_TYPES)) {
        const float _e8 = height_cloud_types(h_4, cloud_type_2);
        return _e8;
    }
    const float _e9 = height_parabola(h_4, cloud_type_2);
    return _e9;
}

uint3 NagaDimensions3D(Texture3D<float4> tex)
{
    uint4 ret;
    tex.GetDimensions(0, ret.x, ret.y, ret.z, ret.w);
    return ret.xyz;
}

float layer_density_with(float3 p_4, float alt_9, Layer l_3, bool with_detail, inout Counters counters_3)
{
    bool local_23 = (bool)0;
    bool local_24 = (bool)0;
    float base = (float)0;
    float density = (float)0;
    bool local_25 = (bool)0;
    bool local_26 = (bool)0;
    bool local_27 = (bool)0;
    float3 detail_pos = (float3)0;

    const float _e5 = layer_height(l_3, alt_9);
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
    const Weather _e20 = sample_weather(p_4, l_3);
    const float _e22 = height_signal(_e5, _e20.cloud_type);
    if (!((_e20.coverage <= 0.0))) {
        local_24 = (_e22 <= 0.0);
    } else {
        local_24 = true;
    }
    bool _e32 = local_24;
    if (_e32) {
        return 0.0;
    }
    float3 dims = float3(NagaDimensions3D(shape_tex));
    float _e40 = frame.periods.y;
    float3 period = (_e40 * float3(1.0, (dims.y / dims.x), 1.0));
    float _e52 = frame.wind_offsets0_.z;
    float _e58 = frame.wind_offsets0_.w;
    float3 shape_pos = float3((p_4.x - _e52), alt_9, (p_4.z - _e58));
    float4 s_7 = shape_tex.SampleLevel(noise_sampler, (shape_pos / period), 0.0);
    float low_fbm = (((s_7.y * 0.625) + (s_7.z * 0.25)) + (s_7.w * 0.125));
    const float _e83 = remap(s_7.x, (low_fbm - 1.0), 1.0, 0.0, 1.0);
    const float _e84 = saturate_(_e83);
    base = (_e84 * _e22);
    float _e87 = base;
    const float _e94 = remap(_e87, (1.0 - _e20.coverage), 1.0, 0.0, 1.0);
    const float _e95 = saturate_(_e94);
    base = (_e95 * _e20.coverage);
    float _e98 = base;
    if ((_e98 <= 0.0)) {
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
        detail_pos = float3(p_4.x, alt_9, p_4.z);
        if (CURL) {
            float4 _e141 = frame.wind_offsets1_;
            float _e147 = frame.periods.w;
            float2 cuv = ((p_4.xz - _e141.zw) / (_e147).xx);
            float4 _e153 = curl_tex.SampleLevel(noise_sampler, cuv, 0.0);
            float2 curl = ((_e153.xy * 2.0) - (1.0).xx);
            float3 _e160 = detail_pos;
            float _e168 = frame.erosion.z;
            detail_pos = (_e160 + (float3(curl.x, 0.0, curl.y) * (_e168 * (1.0 - _e5))));
        }
        float3 _e174 = detail_pos;
        float _e178 = frame.wind_offsets1_.x;
        float _e182 = frame.wind_offsets1_.y;
        detail_pos = (_e174 - float3(_e178, 0.0, _e182));
        float3 _e188 = detail_pos;
        float _e192 = frame.periods.z;
        float4 dn = detail_tex.SampleLevel(noise_sampler, (_e188 / (_e192).xxx), 0.0);
        float high_fbm = (((dn.x * 0.625) + (dn.y * 0.25)) + (dn.z * 0.125));
        float _e211 = frame.extinction.w;
        const float _e216 = saturate_((_e5 * 10.0));
        const float _e218 = saturate_(((2.0 * _e211) * _e216));
        float shape = lerp((1.0 - high_fbm), high_fbm, _e218);
        float _e223 = base;
        float erosion = ((strength * shape) * (1.0 - (_e223 / threshold)));
        float _e228 = base;
        const float _e232 = remap(_e228, erosion, 1.0, 0.0, 1.0);
        const float _e233 = saturate_(_e232);
        density = _e233;
    }
    float _e234 = density;
    float _e238 = frame.erosion.w;
    density = (_e234 * lerp(1.0, _e5, _e238));
    float _e242 = density;
    density = ((_e242 * l_3.density) * (1.0 + _e20.precipitation));
    float _e249 = density;
    return clamp(_e249, 0.0, 1.0);
}

float layer_density(float3 p_5, float alt_10, Layer l_4, inout Counters counters_4)
{
    const float _e5 = layer_density_with(p_5, alt_10, l_4, true, counters_4);
    return _e5;
}

float cloud_density(float3 p_6, float alt_11, inout Counters counters_5)
{
    const uint _e3 = layer_at(alt_11);
    if ((_e3 == NO_LAYER)) {
        return 0.0;
    }
    const Layer _e7 = cloud_layer(_e3);
    const float _e8 = layer_density(p_6, alt_11, _e7, counters_5);
    return _e8;
}

float phase_hg(float cos_theta_2, float g_2)
{
    float g2_1 = (g_2 * g_2);
    float denom = max(((1.0 + g2_1) - ((2.0 * g_2) * cos_theta_2)), 1e-6);
    return ((1.0 - g2_1) / ((12.566371 * denom) * sqrt(denom)));
}

float phase_cornette_shanks(float cos_theta_3, float g_3)
{
    float g2_2 = (g_3 * g_3);
    float denom_1 = max(((1.0 + g2_2) - ((2.0 * g_3) * cos_theta_3)), 1e-6);
    return (((3.0 * (1.0 - g2_2)) * (1.0 + (cos_theta_3 * cos_theta_3))) / (((25.132742 * (2.0 + g2_2)) * denom_1) * sqrt(denom_1)));
}

float phase(float cos_theta_4, float scale)
{
    float _e5 = frame.phase.x;
    float g_5 = (_e5 * scale);
    uint _e10 = frame.modes.x;
    switch(_e10) {
        case 1u: {
            float _e14 = frame.phase.y;
            float g2_3 = (_e14 * scale);
            const float _e16 = phase_hg(cos_theta_4, g_5);
            const float _e17 = phase_hg(cos_theta_4, g2_3);
            float _e21 = frame.phase.z;
            return lerp(_e16, _e17, _e21);
        }
        case 2u: {
            const float _e23 = phase_cornette_shanks(cos_theta_4, g_5);
            return _e23;
        }
        default: {
            const float _e24 = phase_hg(cos_theta_4, g_5);
            return _e24;
        }
    }
}

float segment_optical_depth(float3 rel_3, float3 p_7, Layer l_5, float3 d_13, float first, float growth, uint steps_1, bool with_detail_1, inout Counters counters_6)
{
    float seg = (float)0;
    float dist = 0.0;
    float tau_4 = 0.0;
    uint i_10 = 0u;
    bool local_28 = (bool)0;

    float _e12 = frame.extinction.x;
    float _e16 = frame.extinction.y;
    float sigma_t_1 = (_e12 + _e16);
    seg = first;
    uint2 loop_bound_4 = uint2(4294967295u, 4294967295u);
    bool loop_init_4 = true;
    while(true) {
        if (all(loop_bound_4 == uint2(0u, 0u))) { break; }
        loop_bound_4 -= uint2(loop_bound_4.y == 0u, 1u);
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
            float s_8 = (_e27 + (0.5 * _e28));
            const float _e34 = altitude_of((rel_3 + (d_13 * s_8)));
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
            const float _e51 = layer_density_with((p_7 + (d_13 * s_8)), _e34, l_5, with_detail_1, counters_6);
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

float sun_optical_depth(float3 rel_4, float3 p_8, Layer l_6, inout Counters counters_7)
{
    float tau_5 = (float)0;
    uint j_1 = 0u;
    bool local_29 = (bool)0;
    bool local_30 = (bool)0;
    bool local_31 = (bool)0;

    float4 _e6 = frame.sun_direction;
    float3 sun_3 = _e6.xyz;
    float _e11 = frame.extinction.x;
    float _e15 = frame.extinction.y;
    float sigma_t_2 = (_e11 + _e15);
    float _e20 = frame.march.z;
    float _e24 = frame.march.y;
    uint _e28 = frame.counts.w;
    const float _e30 = segment_optical_depth(rel_4, p_8, l_6, sun_3, _e20, _e24, _e28, true, counters_7);
    tau_5 = _e30;
    const float _e32 = altitude_of(rel_4);
    uint2 loop_bound_5 = uint2(4294967295u, 4294967295u);
    bool loop_init_5 = true;
    while(true) {
        if (all(loop_bound_5 == uint2(0u, 0u))) { break; }
        loop_bound_5 -= uint2(loop_bound_5.y == 0u, 1u);
        if (!loop_init_5) {
            uint _e96 = j_1;
            j_1 = (_e96 + 1u);
        }
        loop_init_5 = false;
        uint _e35 = j_1;
        const uint _e36 = layer_count();
        if ((_e35 < _e36)) {
        } else {
            break;
        }
        {
            uint _e38 = j_1;
            const Layer _e39 = cloud_layer(_e38);
            if ((_e39.bottom <= l_6.top)) {
                continue;
            }
            const Roots _e44 = ray_shell_from(rel_4, _e32, sun_3, _e39.bottom);
            const Roots _e46 = ray_shell_from(rel_4, _e32, sun_3, _e39.top);
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
            float s_9 = (0.5 * (_e44.t1_ + _e46.t1_));
            uint _e79 = counters_7.light;
            counters_7.light = (_e79 + 1u);
            float _e82 = tau_5;
            const float _e87 = altitude_of((rel_4 + (sun_3 * s_9)));
            const float _e88 = layer_density((p_8 + (sun_3 * s_9)), _e87, _e39, counters_7);
            tau_5 = (_e82 + ((_e88 * sigma_t_2) * (_e46.t1_ - _e44.t1_)));
        }
    }
    float _e98 = tau_5;
    return _e98;
}

float octave_optical_depth(float3 rel_5, float3 p_9, Layer l_7, float tau_6, inout Counters counters_8)
{
    bool local_32 = (bool)0;
    bool local_33 = (bool)0;
    bool local_34 = (bool)0;

    const float _e10 = saturate_(((l_7.coverage - 0.8) / 0.1));
    float _e14 = frame.octave_depth.x;
    float m_2 = (_e14 * _e10);
    if (!((_e10 < 0.001))) {
        local_32 = (m_2 <= 0.0);
    } else {
        local_32 = true;
    }
    bool _e24 = local_32;
    if (!(_e24)) {
        uint _e31 = frame.counts.w;
        local_33 = (_e31 == 0u);
    } else {
        local_33 = true;
    }
    bool _e35 = local_33;
    if (_e35) {
        return tau_6;
    }
    float _e41 = frame.atmosphere.x;
    float3 up_1 = normalize(float3(rel_5.x, (rel_5.y + _e41), rel_5.z));
    const float _e46 = altitude_of(rel_5);
    const Roots _e48 = ray_shell_from(rel_5, _e46, up_1, l_7.top);
    if (_e48.hit) {
        local_34 = (_e48.t1_ > 0.0);
    } else {
        local_34 = false;
    }
    bool _e57 = local_34;
    float len_1 = (_e57 ? _e48.t1_ : 0.0);
    const float _e65 = segment_optical_depth(rel_5, p_9, l_7, up_1, (len_1 / 3.0), 1.0, COLUMN_STEPS, false, counters_8);
    float _e69 = frame.octave_depth.y;
    return lerp(tau_6, (_e69 * _e65), m_2);
}

float far_optical_depth(float3 rel_6, float3 p_10, Layer l_8)
{
    bool local_35 = (bool)0;
    float reach = (float)0;
    bool local_36 = (bool)0;
    float tau_7 = 0.0;
    uint i_11 = 0u;

    float chord = frame.light_model.z;
    if (!((chord <= 0.0))) {
        uint _e15 = frame.counts.w;
        local_35 = (_e15 == 0u);
    } else {
        local_35 = true;
    }
    bool _e19 = local_35;
    if (_e19) {
        return 0.0;
    }
    float growth_1 = frame.march.y;
    uint _e28 = frame.counts.w;
    float steps_3 = float(_e28);
    float _e33 = frame.march.z;
    reach = (_e33 * steps_3);
    if ((growth_1 != 1.0)) {
        float _e41 = frame.march.z;
        reach = ((_e41 * (pow(growth_1, steps_3) - 1.0)) / (growth_1 - 1.0));
    }
    float4 _e51 = frame.sun_direction;
    float3 sun_4 = _e51.xyz;
    const float _e53 = altitude_of(rel_6);
    const Roots _e55 = ray_shell_from(rel_6, _e53, sun_4, l_8.top);
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
    uint2 loop_bound_6 = uint2(4294967295u, 4294967295u);
    bool loop_init_6 = true;
    while(true) {
        if (all(loop_bound_6 == uint2(0u, 0u))) { break; }
        loop_bound_6 -= uint2(loop_bound_6.y == 0u, 1u);
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
            const float _e88 = altitude_of((rel_6 + (sun_4 * t_5)));
            const float _e89 = layer_height(l_8, _e88);
            const float _e90 = saturate_(_e89);
            const Weather _e93 = sample_weather((p_10 + (sun_4 * t_5)), l_8);
            float cov = _e93.coverage;
            const float _e96 = height_signal(_e90, l_8.cloud_type);
            float f_3 = min((cov * _e96), 0.95);
            float _e100 = tau_7;
            tau_7 = (_e100 + (((0.25 * len_2) * f_3) / ((1.0 - f_3) * chord)));
        }
    }
    float _e112 = tau_7;
    return _e112;
}

float diffuse_limb(float view_y, float coverage)
{
    float k_12 = frame.light_model.w;
    float layer_5 = ((1.0 + (k_12 * abs(view_y))) / (1.0 + ((2.0 * k_12) / 3.0)));
    const float _e17 = saturate_(coverage);
    return lerp(1.0, layer_5, _e17);
}

float vertical_anisotropy(float view_y_1, float coverage_1, float h_5)
{
    float _e6 = frame.octave_direction.z;
    const float _e8 = saturate_(coverage_1);
    const float _e10 = saturate_(h_5);
    return (1.0 + (((_e6 * view_y_1) * _e8) * (1.0 - _e10)));
}

float deck_escape(float mu0_, float layer_coverage)
{
    float e = frame.octave_direction.w;
    const float _e6 = saturate_(layer_coverage);
    return (1.0 + ((e * pow(_e6, DECK_POWER)) * (mu0_ - 0.5)));
}

float downward_dimming(float view_y_2, float coverage_2, float h_6, float tau_v)
{
    float _e7 = frame.octave_depth.z;
    const float _e12 = saturate_(coverage_2);
    const float _e14 = saturate_(h_6);
    float k_13 = (((_e7 * max(-(view_y_2), 0.0)) * _e12) * (1.0 - _e14));
    return max((1.0 - ((k_13 * tau_v) / (tau_v + 1.0))), 0.0);
}

SunScattering ConstructSunScattering(float arg0, float arg1) {
    SunScattering ret = (SunScattering)0;
    ret.total = arg0;
    ret.octaves = arg1;
    return ret;
}

SunScattering sun_scattering(float cos_theta_5, float view_y_3, float tau_8, float tau_oct, float far_1, float build, float coverage_3, float h_7, float layer_coverage_1)
{
    float octave_sum = 0.0;
    float ka = 1.0;
    float kb = 1.0;
    float kc = 1.0;
    uint i_12 = 0u;
    float feed = (float)0;
    float octaves_part = (float)0;
    float total = (float)0;

    float a_8 = frame.multiple_scattering.x;
    float b_8 = frame.multiple_scattering.y;
    float c_8 = frame.multiple_scattering.z;
    uint _e24 = frame.misc.x;
    uint octaves = min(_e24, MAX_OCTAVES);
    uint2 loop_bound_7 = uint2(4294967295u, 4294967295u);
    bool loop_init_7 = true;
    while(true) {
        if (all(loop_bound_7 == uint2(0u, 0u))) { break; }
        loop_bound_7 -= uint2(loop_bound_7.y == 0u, 1u);
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
            ka = (_e39 * a_8);
            float _e41 = kb;
            kb = (_e41 * b_8);
            float _e43 = kc;
            kc = (_e43 * c_8);
            float _e45 = octave_sum;
            float _e46 = ka;
            float _e47 = kc;
            const float _e48 = phase(cos_theta_5, _e47);
            float _e50 = kb;
            octave_sum = (_e45 + ((_e46 * _e48) / (1.0 + (_e50 * tau_oct))));
        }
    }
    float _e62 = frame.sun_direction.y;
    const float _e63 = saturate_(_e62);
    const float _e70 = saturate_(coverage_3);
    float side = ((sqrt(max((1.0 - (_e63 * _e63)), 0.0)) * (1.0 - _e70)) * exp(-(far_1)));
    float _e80 = frame.light_model.x;
    feed = (_e63 + (_e80 * side));
    float _e87 = frame.light_model.y;
    if ((_e87 > 0.0)) {
        float _e90 = feed;
        float _e96 = frame.light_model.y;
        feed = (_e90 * pow(max(coverage_3, 1e-6), _e96));
    }
    float _e99 = feed;
    const float _e100 = diffuse_limb(view_y_3, coverage_3);
    const float _e101 = vertical_anisotropy(view_y_3, coverage_3, h_7);
    const float _e103 = deck_escape(_e63, layer_coverage_1);
    feed = (_e99 * ((_e100 * _e101) * _e103));
    float _e106 = feed;
    const float _e108 = downward_dimming(view_y_3, coverage_3, h_7, (tau_8 * _e63));
    feed = (_e106 * _e108);
    float _e110 = feed;
    float _e112 = octave_sum;
    octaves_part = ((_e110 * build) * _e112);
    const float _e116 = phase(cos_theta_5, 1.0);
    float _e121 = octaves_part;
    total = ((_e116 * exp((-(tau_8) - far_1))) + _e121);
    uint _e127 = frame.modes.w;
    if (((_e127 & FLAG_BEER_POWDER) != 0u)) {
        float _e135 = frame.phase.w;
        float powder = (1.0 - exp((-(_e135) * tau_8)));
        float _e141 = total;
        total = (_e141 * powder);
        float _e143 = octaves_part;
        octaves_part = (_e143 * powder);
    }
    float _e145 = total;
    float _e146 = octaves_part;
    const SunScattering sunscattering = ConstructSunScattering(_e145, _e146);
    return sunscattering;
}

float forward_lobe(float cos_theta_6, float transmittance)
{
    float k_14 = frame.octave_direction.x;
    if ((k_14 <= 0.0)) {
        return 1.0;
    }
    const float _e11 = saturate_((transmittance / FORWARD_LOBE_THIN));
    float w_6 = (k_14 * _e11);
    float _e17 = frame.octave_direction.y;
    const float _e18 = phase_hg(cos_theta_6, _e17);
    return (1.0 + (w_6 * ((12.566371 * _e18) - 1.0)));
}

float octave_buildup(float density_1)
{
    float l_11 = frame.multiple_scattering.w;
    if ((l_11 <= 0.0)) {
        return 1.0;
    }
    float _e11 = frame.extinction.x;
    float _e15 = frame.extinction.y;
    return (1.0 - exp(((-((_e11 + _e15)) * density_1) * l_11)));
}

float3 ambient(float h_8, float3 rel_7)
{
    const bool _e2 = physical_sky();
    if (_e2) {
        const float3 _e3 = sky_ambient_light(h_8, rel_7);
        return _e3;
    }
    float4 _e6 = frame.ambient_bottom;
    float4 _e10 = frame.ambient_top;
    float _e16 = frame.ambient_bottom.w;
    return (lerp(_e6.xyz, _e10.xyz, h_8) * _e16);
}

float height_fraction(float alt_12)
{
    const uint _e1 = layer_at(alt_12);
    const Layer _e2 = cloud_layer(_e1);
    const float _e3 = layer_height(_e2, alt_12);
    const float _e4 = saturate_(_e3);
    return _e4;
}

ScatteredLight ConstructScatteredLight(float3 arg0, float3 arg1) {
    ScatteredLight ret = (ScatteredLight)0;
    ret.total = arg0;
    ret.octaves = arg1;
    return ret;
}

ScatteredLight scattered_light(float3 rel_8, float3 p_11, float alt_13, float density_2, float3 view, Layer l_9, inout Counters counters_9)
{
    float3 sun_light = (0.0).xxx;
    float3 octave_light = (0.0).xxx;
    float tau_9 = 0.0;
    float far_2 = 0.0;
    float tau_oct_1 = (float)0;

    float4 _e9 = frame.sun_direction;
    float3 sun_5 = _e9.xyz;
    const float _e11 = layer_height(l_9, alt_13);
    const float _e12 = saturate_(_e11);
    const Weather _e19 = sample_weather(p_11, l_9);
    const bool _e20 = hits_ground(rel_8, alt_13, sun_5);
    if (!(_e20)) {
        if (LIGHT_MARCH) {
            const float _e27 = sun_optical_depth(rel_8, p_11, l_9, counters_9);
            tau_9 = _e27;
            const float _e28 = far_optical_depth(rel_8, p_11, l_9);
            far_2 = _e28;
        }
        float _e29 = tau_9;
        tau_oct_1 = _e29;
        if (LIGHT_MARCH) {
            float _e32 = tau_9;
            const float _e33 = octave_optical_depth(rel_8, p_11, l_9, _e32, counters_9);
            tau_oct_1 = _e33;
        }
        float _e36 = tau_9;
        float _e37 = tau_oct_1;
        float _e38 = far_2;
        const float _e39 = octave_buildup(density_2);
        const SunScattering _e42 = sun_scattering(dot(view, sun_5), view.y, _e36, _e37, _e38, _e39, _e19.coverage, _e12, l_9.coverage);
        float4 _e45 = frame.sun_illuminance;
        const float3 _e47 = sun_through_air(rel_8);
        float3 lit_ = (_e45.xyz * _e47);
        sun_light = (lit_ * _e42.total);
        octave_light = (lit_ * _e42.octaves);
    }
    float _e56 = frame.extinction.z;
    const float _e64 = saturate_((1.0 - ((_e56 * _e19.precipitation) * (1.0 - _e12))));
    float _e68 = frame.extinction.x;
    float k_15 = ((_e68 * density_2) * _e64);
    float3 _e71 = sun_light;
    const float3 _e72 = ambient(_e12, rel_8);
    float3 _e75 = octave_light;
    const ScatteredLight scatteredlight = ConstructScatteredLight(((_e71 + _e72) * k_15), (_e75 * k_15));
    return scatteredlight;
}

float3 shadow_ground_point(uint2 c_2)
{
    float2 xz_1 = ((((float2(c_2) / (127.0).xx) * 2.0) - (1.0).xx) * SHADOW_HALF_EXTENT);
    float rp_4 = frame.atmosphere.x;
    float s2_ = dot(xz_1, xz_1);
    float y_1 = (-(s2_) / (sqrt(max(((rp_4 * rp_4) - s2_), 0.0)) + rp_4));
    return float3(xz_1.x, y_1, xz_1.y);
}

float ground_shadow(float3 rel_9)
{
    float edge = (max(abs(rel_9.x), abs(rel_9.z)) / SHADOW_HALF_EXTENT);
    if ((edge >= 1.0)) {
        return 1.0;
    }
    float2 x_9 = ((rel_9.xz / (40000.0).xx) + (0.5).xx);
    const float4 _e21 = lut_bilinear(cloud_shadow_in, x_9, (128u).xx);
    float t_6 = _e21.x;
    return lerp(t_6, 1.0, smoothstep(SHADOW_FADE_START, 1.0, edge));
}

float3 ground_shadow_loss(float3 view_1, float r_12)
{
    const float _e3 = distance_to_ground(r_12, view_1.y);
    float _e7 = frame.camera_position.y;
    float cam_alt = max(_e7, 0.0);
    const float _e17 = ground_shadow(((view_1 * (_e3 * 1000.0)) + float3(0.0, cam_alt, 0.0)));
    if ((_e17 >= 1.0)) {
        return (0.0).xxx;
    }
    const float _e22 = air_bottom();
    float mu_g = clamp((((r_12 * view_1.y) + _e3) / _e22), -1.0, 1.0);
    float _e33 = frame.sun_direction.y;
    float4 _e37 = frame.sun_direction;
    float mu_s_6 = clamp((((r_12 * _e33) + (_e3 * dot(view_1, _e37.xyz))) / _e22), -1.0, 1.0);
    const float3 _e47 = transmittance_to_top(_e22, -(mu_g));
    const float3 _e50 = transmittance_to_top(r_12, -(view_1.y));
    float3 t_view_1 = min((_e47 / max(_e50, (1e-20).xxx)), (1.0).xxx);
    const float3 _e61 = ground_radiance_sun(mu_s_6);
    return (((1.0 - _e17) * t_view_1) * _e61);
}

float empty_cell_exit(float3 p_12, float3 d_14)
{
    float exit = 1e30;

    float4 _e6 = frame.wind_offsets0_;
    float _e12 = frame.periods.x;
    float2 uv_6 = (frac(((p_12.xz - _e6.xy) / (_e12).xx)) * 64.0);
    uint2 cell_1 = min(naga_f2u32(uv_6), (63u).xx);
    float4 _e23 = occupancy_in.Load(int3(cell_1, int(0)));
    float m_3 = _e23.x;
    float _e28 = frame.clouds.x;
    if (((m_3 + (2.0 * (_e28 - 0.5))) > -0.003921569)) {
        return 0.0;
    }
    float _e40 = frame.periods.x;
    float cell_m = (_e40 / 64.0);
    float2 inside = ((uv_6 - float2(cell_1)) * cell_m);
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

void count(uint index_1, uint value)
{
    bool local_37 = (bool)0;

    if (STATS) {
        local_37 = (value != 0u);
    } else {
        local_37 = false;
    }
    bool _e8 = local_37;
    if (_e8) {
        uint _e12; stats.InterlockedAdd(index_1*4+0, value, _e12);
        return;
    } else {
        return;
    }
}

float3 step_integral(float3 source, float sigma_t, float dt)
{
    uint _e6 = frame.modes.y;
    if ((_e6 == INTEGRATION_RIEMANN)) {
        return (source * dt);
    }
    float x_10 = (sigma_t * dt);
    float f_4 = ((x_10 < 0.001) ? (1.0 - (0.5 * x_10)) : ((1.0 - exp(-(x_10))) / x_10));
    return (source * (dt * f_4));
}

uint naga_div(uint lhs, uint rhs) {
    return lhs / (rhs == 0u ? 1u : rhs);
}

float start_offset(uint2 pixel_3)
{
    uint _e4 = frame.modes.w;
    bool jitter_1 = ((_e4 & FLAG_JITTER) != 0u);
    uint k_16 = frame.temporal.x;
    if ((k_16 <= 1u)) {
        uint _e18 = frame.misc.y;
        const float _e19 = hash_unit(pixel_3, _e18);
        return (jitter_1 ? _e19 : 0.5);
    }
    const float _e23 = hash_unit(pixel_3, 0u);
    float base_2 = (jitter_1 ? _e23 : 0.5);
    uint _e29 = frame.misc.y;
    const float _e32 = van_der_corput(naga_div(_e29, (k_16 * k_16)));
    return frac((base_2 + _e32));
}

bool march_layer(float3 view_2, Interval span_1, Layer l_10, float jitter, inout MarchState state, inout Counters counters_10)
{
    uint steps_2 = (uint)0;
    uint i_13 = 0u;
    uint stride = 1u;
    uint empty = 0u;
    bool local_38 = (bool)0;

    float cam_alt_1 = frame.camera_position.y;
    float4 _e12 = frame.camera_position;
    float2 cam_xz = _e12.xz;
    uint _e17 = frame.counts.z;
    steps_2 = _e17;
    float _e22 = frame.march.x;
    if ((_e22 > 0.0)) {
        float _e29 = frame.march.x;
        steps_2 = clamp(naga_f2u32(ceil((span_1.length_ / _e29))), 1u, MAX_VIEW_STEPS);
    }
    uint _e37 = steps_2;
    float dt_2 = (span_1.length_ / float(_e37));
    float _e43 = frame.extinction.x;
    float _e47 = frame.extinction.y;
    float sigma_e = (_e43 + _e47);
    uint _e52 = frame.modes.w;
    bool dynamic_step = ((_e52 & FLAG_DYNAMIC_STEP) != 0u);
    uint _e60 = frame.modes.w;
    bool empty_skip = ((_e60 & FLAG_EMPTY_SKIP) != 0u);
    uint2 loop_bound_8 = uint2(4294967295u, 4294967295u);
    while(true) {
        if (all(loop_bound_8 == uint2(0u, 0u))) { break; }
        loop_bound_8 -= uint2(loop_bound_8.y == 0u, 1u);
        uint _e71 = i_13;
        uint _e72 = steps_2;
        if ((_e71 >= _e72)) {
            break;
        }
        uint _e75 = counters_10.view_steps;
        counters_10.view_steps = (_e75 + 1u);
        uint _e79 = i_13;
        float t_7 = (span_1.start + ((float(_e79) + jitter) * dt_2));
        float3 rel_12 = ((view_2 * t_7) + float3(0.0, cam_alt_1, 0.0));
        float3 p_17 = float3((rel_12.x + cam_xz.x), rel_12.y, (rel_12.z + cam_xz.y));
        if (empty_skip) {
            const float _e97 = empty_cell_exit(p_17, view_2);
            if ((_e97 > 0.0)) {
                uint _e106 = steps_2;
                uint next_1 = naga_f2u32(clamp(ceil(((((t_7 + _e97) - span_1.start) / dt_2) - jitter)), 0.0, float(_e106)));
                uint _e111 = i_13;
                i_13 = max((_e111 + 1u), next_1);
                continue;
            }
        }
        const float _e115 = altitude_of(rel_12);
        const float _e116 = layer_density(p_17, _e115, l_10, counters_10);
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
        const ScatteredLight _e145 = scattered_light(rel_12, p_17, _e115, _e116, view_2, l_10, counters_10);
        float transmittance_2 = state.transmittance;
        float3 _e149 = state.radiance;
        const float3 _e151 = step_integral(_e145.total, sigma_t_3, dt_2);
        state.radiance = (_e149 + (transmittance_2 * _e151));
        float3 _e155 = state.octaves;
        const float3 _e157 = step_integral(_e145.octaves, sigma_t_3, dt_2);
        state.octaves = (_e155 + (transmittance_2 * _e157));
        float step_t = exp((-(sigma_t_3) * dt_2));
        float _e164 = state.depth_sum;
        state.depth_sum = (_e164 + ((t_7 * transmittance_2) * (1.0 - step_t)));
        state.transmittance = (transmittance_2 * step_t);
        float _e173 = state.transmittance;
        float _e177 = frame.march.w;
        if ((_e173 < _e177)) {
            return true;
        }
        uint _e180 = i_13;
        i_13 = (_e180 + 1u);
    }
    return false;
}

Counters ConstructCounters(uint arg0, uint arg1, uint arg2, uint arg3) {
    Counters ret = (Counters)0;
    ret.view_steps = arg0;
    ret.density = arg1;
    ret.detail = arg2;
    ret.light = arg3;
    return ret;
}

MarchState ConstructMarchState(float3 arg0, float arg1, float arg2, float3 arg3) {
    MarchState ret = (MarchState)0;
    ret.radiance = arg0;
    ret.transmittance = arg1;
    ret.depth_sum = arg2;
    ret.octaves = arg3;
    return ret;
}

MarchResult ConstructMarchResult(float3 arg0, float arg1, float arg2) {
    MarchResult ret = (MarchResult)0;
    ret.radiance = arg0;
    ret.transmittance = arg1;
    ret.depth = arg2;
    return ret;
}

MarchResult march_pixel(uint2 pixel_4)
{
    Counters counters_11 = ConstructCounters(0u, 0u, 0u, 0u);
    MarchState state_1 = ConstructMarchState((0.0).xxx, 1.0, 0.0, (0.0).xxx);
    bool marched = false;
    bool ground_1 = false;
    float last_start = -1.0;
    uint last_index = NO_LAYER;
    bool exited = false;
    uint k_6 = 0u;
    uint next = (uint)0;
    Interval span_2 = (Interval)0;
    uint i_14 = (uint)0;
    bool local_39 = (bool)0;
    bool local_40 = (bool)0;
    bool local_41 = (bool)0;
    bool local_42 = (bool)0;
    bool local_43 = (bool)0;
    bool local_44 = (bool)0;
    float depth_1 = 0.0;

    const float3 _e1 = view_ray(pixel_4);
    float cam_alt_2 = frame.camera_position.y;
    count(STAT_PIXELS, 1u);
    const float _e22 = start_offset(pixel_4);
    const uint _e23 = layer_count();
    uint2 loop_bound_9 = uint2(4294967295u, 4294967295u);
    bool loop_init_8 = true;
    while(true) {
        if (all(loop_bound_9 == uint2(0u, 0u))) { break; }
        loop_bound_9 -= uint2(loop_bound_9.y == 0u, 1u);
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
            span_2 = ConstructInterval(0.0, 0.0, 1u);
            i_14 = 0u;
            uint2 loop_bound_10 = uint2(4294967295u, 4294967295u);
            bool loop_init_9 = true;
            while(true) {
                if (all(loop_bound_10 == uint2(0u, 0u))) { break; }
                loop_bound_10 -= uint2(loop_bound_10.y == 0u, 1u);
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
                    const Layer _e50 = cloud_layer(_e49);
                    const Interval _e51 = layer_interval(cam_alt_2, _e1, _e50);
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
            const Layer _e115 = cloud_layer(_e114);
            const bool _e116 = march_layer(_e1, _e113, _e115, _e22, state_1, counters_11);
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
    float4 _e163 = frame.sun_direction;
    float _e167 = state_1.transmittance;
    const float _e168 = forward_lobe(dot(_e1, _e163.xyz), _e167);
    float3 _e170 = state_1.radiance;
    float3 _e172 = state_1.octaves;
    float3 radiance_5 = (_e170 + (_e172 * (_e168 - 1.0)));
    float _e177 = depth_1;
    const MarchResult marchresult = ConstructMarchResult(radiance_5, transmittance_3, _e177);
    return marchresult;
}

uint2 bayer2_(uint v_2)
{
    return uint2(((v_2 ^ (v_2 >> 1u)) & 1u), (v_2 & 1u));
}

uint naga_mod(uint lhs, uint rhs) {
    return lhs % (rhs == 0u ? 1u : rhs);
}

uint2 block_offset(uint f, uint k_7)
{
    if ((k_7 == 2u)) {
        const uint2 _e6 = bayer2_(naga_mod(f, 4u));
        return _e6;
    }
    if ((k_7 == 4u)) {
        uint b_9 = naga_mod(f, 16u);
        const uint2 _e13 = bayer2_((b_9 >> 2u));
        const uint2 _e17 = bayer2_((b_9 & 3u));
        return (_e13 + (2u * _e17));
    }
    return (0u).xx;
}

float2 reproject(uint2 pixel_5, float depth_2)
{
    bool local_45 = (bool)0;
    bool local_46 = (bool)0;
    bool local_47 = (bool)0;
    float3 dir = (float3)0;

    float4 _e4 = frame.previous_position;
    float4 _e7 = frame.camera_position;
    if (all((_e4 == _e7))) {
        float4 _e14 = frame.previous_forward;
        float4 _e17 = frame.camera_forward;
        local_45 = all((_e14 == _e17));
    } else {
        local_45 = false;
    }
    bool _e21 = local_45;
    if (_e21) {
        float4 _e26 = frame.previous_right;
        float4 _e29 = frame.camera_right;
        local_46 = all((_e26 == _e29));
    } else {
        local_46 = false;
    }
    bool _e33 = local_46;
    if (_e33) {
        float4 _e38 = frame.previous_up;
        float4 _e41 = frame.camera_up;
        local_47 = all((_e38 == _e41));
    } else {
        local_47 = false;
    }
    bool same = local_47;
    if (same) {
        return float2(pixel_5);
    }
    const float3 _e47 = view_ray(pixel_5);
    dir = _e47;
    if ((depth_2 > 0.0)) {
        float4 _e54 = frame.camera_position;
        float4 _e58 = frame.previous_position;
        dir = ((_e47 * depth_2) + (_e54.xyz - _e58.xyz));
    }
    float3 _e62 = dir;
    float4 _e65 = frame.previous_forward;
    float z_3 = dot(_e62, _e65.xyz);
    if ((z_3 <= 0.0)) {
        return (-1000000000.0).xx;
    }
    float tan_half_2 = frame.previous_position.w;
    float aspect_2 = frame.previous_forward.w;
    float3 _e80 = dir;
    float4 _e83 = frame.previous_right;
    float3 _e89 = dir;
    float4 _e92 = frame.previous_up;
    float2 ndc_2 = float2((dot(_e80, _e83.xyz) / ((z_3 * tan_half_2) * aspect_2)), (-(dot(_e89, _e92.xyz)) / (z_3 * tan_half_2)));
    uint4 _e106 = frame.counts;
    return ((((ndc_2 * 0.5) + (0.5).xx) * float2(_e106.xy)) - (0.5).xx);
}

bool on_screen(float2 q)
{
    bool local_48 = (bool)0;

    uint4 _e3 = frame.counts;
    float2 size_3 = float2(_e3.xy);
    if (all((q >= (-0.5).xx))) {
        local_48 = all((q <= (size_3 - (0.5).xx)));
    } else {
        local_48 = false;
    }
    bool _e18 = local_48;
    return _e18;
}

float4 catmull_rom(float t_1)
{
    return float4((t_1 * (-0.5 + (t_1 * (1.0 - (0.5 * t_1))))), (1.0 + ((t_1 * t_1) * (-2.5 + (1.5 * t_1)))), (t_1 * (0.5 + (t_1 * (2.0 - (1.5 * t_1))))), ((t_1 * t_1) * (-0.5 + (0.5 * t_1))));
}

float4 history_row(int2 base_1, int dy, float4 wx)
{
    uint4 _e5 = frame.counts;
    int2 size_4 = int2(_e5.xy);
    int y_2 = clamp(asint(asuint(base_1.y) + asuint(dy)), int(0), asint(asuint(size_4.y) - asuint(int(1))));
    int x0_ = clamp(asint(asuint(base_1.x) - asuint(int(1))), int(0), asint(asuint(size_4.x) - asuint(int(1))));
    int x1_ = clamp(base_1.x, int(0), asint(asuint(size_4.x) - asuint(int(1))));
    int x2_ = clamp(asint(asuint(base_1.x) + asuint(int(1))), int(0), asint(asuint(size_4.x) - asuint(int(1))));
    int x3_ = clamp(asint(asuint(base_1.x) + asuint(int(2))), int(0), asint(asuint(size_4.x) - asuint(int(1))));
    float4 _e48 = history_in.Load(int3(int2(x0_, y_2), int(0)));
    float4 _e54 = history_in.Load(int3(int2(x1_, y_2), int(0)));
    float4 _e61 = history_in.Load(int3(int2(x2_, y_2), int(0)));
    float4 _e68 = history_in.Load(int3(int2(x3_, y_2), int(0)));
    return ((((_e48 * wx.x) + (_e54 * wx.y)) + (_e61 * wx.z)) + (_e68 * wx.w));
}

int2 naga_f2i32(float2 value) {
    return int2(clamp(value, -2147483600.0, 2147483500.0));
}

float4 history_at(float2 q_1)
{
    uint4 _e3 = frame.counts;
    int2 size_5 = int2(_e3.xy);
    float2 c_9 = clamp(q_1, (0.0).xx, float2(asint(asuint(size_5) - asuint((int(1)).xx))));
    int2 base_3 = naga_f2i32(floor(c_9));
    float2 f_5 = (c_9 - float2(base_3));
    const float4 _e18 = catmull_rom(f_5.x);
    const float4 _e20 = catmull_rom(f_5.y);
    const float4 _e22 = history_row(base_3, int(-1), _e18);
    const float4 _e26 = history_row(base_3, int(0), _e18);
    const float4 _e31 = history_row(base_3, int(1), _e18);
    const float4 _e36 = history_row(base_3, int(2), _e18);
    float4 sum_6 = ((((_e22 * _e20.x) + (_e26 * _e20.y)) + (_e31 * _e20.z)) + (_e36 * _e20.w));
    const float _e45 = saturate_(sum_6.w);
    return float4(max(sum_6.xyz, (0.0).xxx), _e45);
}

float4 history_nearest(float2 q_2)
{
    uint4 _e3 = frame.counts;
    int2 size_6 = int2(_e3.xy);
    int2 p_18 = clamp(naga_f2i32(round(q_2)), (int(0)).xx, asint(asuint(size_6) - asuint((int(1)).xx)));
    float4 _e16 = history_in.Load(int3(p_18, int(0)));
    return _e16;
}

float4 meta_at(float2 q_3)
{
    uint4 _e3 = frame.counts;
    int2 size_7 = int2(_e3.xy);
    int2 p_19 = clamp(naga_f2i32(round(q_3)), (int(0)).xx, asint(asuint(size_7) - asuint((int(1)).xx)));
    float4 _e16 = meta_in.Load(int3(p_19, int(0)));
    return _e16;
}

uint2 naga_div(uint2 lhs, uint2 rhs) {
    return lhs / (rhs == 0u ? 1u : rhs);
}

bool in_blocks(uint2 id_19)
{
    uint k_17 = frame.temporal.x;
    uint4 _e7 = frame.counts;
    return all((id_19 < naga_div(((_e7.xy + (k_17).xx) - (1u).xx), (k_17).xx)));
}

uint2 sparse_pixel(uint2 id_20)
{
    uint k_18 = frame.temporal.x;
    uint _e9 = frame.misc.y;
    const uint2 _e10 = block_offset(_e9, k_18);
    return ((id_20 * k_18) + _e10);
}

void store_sparse(uint2 id_21, MarchResult r_13)
{
    cloud_out[id_21] = float4(r_13.radiance, r_13.transmittance);
    depth_out[id_21] = float4(r_13.depth, 0.0, 0.0, 0.0);
    return;
}

uint rng_seed(uint2 pixel_6, uint path_index)
{
    const uint _e4 = pcg(path_index);
    const uint _e6 = pcg((pixel_6.y ^ _e4));
    const uint _e8 = pcg((pixel_6.x ^ _e6));
    return _e8;
}

float rng_next(inout uint rng_1)
{
    uint _e1 = rng_1;
    rng_1 = ((_e1 * 747796405u) + 2891336453u);
    uint s_10 = rng_1;
    uint word_1 = (((s_10 >> ((s_10 >> 28u) + 4u)) ^ s_10) * 277803737u);
    return (float((((word_1 >> 22u) ^ word_1) >> 8u)) * 5.9604645e-8);
}

float rng_exponential(inout uint rng_2, float sigma)
{
    const float _e2 = rng_next(rng_2);
    return (-(log((1.0 - _e2))) / sigma);
}

Segments ConstructSegments(float2 arg0, float2 arg1, uint arg2) {
    Segments ret = (Segments)0;
    ret.a = arg0;
    ret.b = arg1;
    ret.count = arg2;
    return ret;
}

Segments layer_segments(float3 p_13, float alt_14, float3 d_15)
{
    Segments s_1 = ConstructSegments((0.0).xx, (0.0).xx, 0u);
    bool local_49 = (bool)0;
    float2 a_1 = (0.0).xx;
    float2 b_1 = (0.0).xx;
    uint n_2 = 0u;
    bool local_50 = (bool)0;
    bool local_51 = (bool)0;
    bool local_52 = (bool)0;
    bool local_53 = (bool)0;

    const float2 _e10 = layers_span();
    float bottom_2 = _e10.x;
    const Roots _e12 = ray_shell_from(p_13, alt_14, d_15, bottom_2);
    const Roots _e14 = ray_shell_from(p_13, alt_14, d_15, _e10.y);
    const bool _e15 = hits_ground(p_13, alt_14, d_15);
    if (!(!(_e14.hit))) {
        local_49 = (_e14.t1_ <= 0.0);
    } else {
        local_49 = true;
    }
    bool _e25 = local_49;
    if (_e25) {
        Segments _e26 = s_1;
        const Segments segments = _e26;
        return segments;
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
        a_1[min(uint(_e51), 1u)] = entry;
        uint _e53 = n_2;
        b_1[min(uint(_e53), 1u)] = _e12.t0_;
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
            a_1[min(uint(_e69), 1u)] = max(_e12.t1_, entry);
            uint _e73 = n_2;
            b_1[min(uint(_e73), 1u)] = _e14.t1_;
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
    float2 _e98 = a_1;
    s_1.a = _e98;
    float2 _e100 = b_1;
    s_1.b = _e100;
    uint _e102 = n_2;
    s_1.count = _e102;
    Segments _e103 = s_1;
    const Segments segments_1 = _e103;
    return segments_1;
}

float density_at(float3 rel_10, inout Counters counters_12)
{
    float _e6 = frame.camera_position.x;
    float _e13 = frame.camera_position.z;
    float3 p_20 = float3((rel_10.x + _e6), rel_10.y, (rel_10.z + _e13));
    const float _e16 = altitude_of(rel_10);
    const float _e17 = cloud_density(p_20, _e16, counters_12);
    return _e17;
}

float empty_cell_skip(float3 origin_4, float3 dir_1, float t_2)
{
    const uint _e3 = layer_count();
    if ((_e3 > 1u)) {
        return 0.0;
    }
    float3 rel_13 = (origin_4 + (dir_1 * t_2));
    float _e13 = frame.camera_position.x;
    float _e20 = frame.camera_position.z;
    float3 p_21 = float3((rel_13.x + _e13), rel_13.y, (rel_13.z + _e20));
    const float _e23 = empty_cell_exit(p_21, dir_1);
    if ((_e23 <= 0.0)) {
        return 0.0;
    }
    return (_e23 + 0.05);
}

float density_max()
{
    float m_1 = 0.0;
    uint i_15 = 0u;

    uint2 loop_bound_11 = uint2(4294967295u, 4294967295u);
    bool loop_init_10 = true;
    while(true) {
        if (all(loop_bound_11 == uint2(0u, 0u))) { break; }
        loop_bound_11 -= uint2(loop_bound_11.y == 0u, 1u);
        if (!loop_init_10) {
            uint _e17 = i_15;
            i_15 = (_e17 + 1u);
        }
        loop_init_10 = false;
        uint _e4 = i_15;
        const uint _e5 = layer_count();
        if ((_e4 < _e5)) {
        } else {
            break;
        }
        {
            uint _e7 = i_15;
            const Layer _e8 = cloud_layer(_e7);
            float _e9 = m_1;
            m_1 = max(_e9, (_e8.density * (1.0 + _e8.precipitation)));
        }
    }
    float _e19 = m_1;
    return clamp(_e19, 0.0, 1.0);
}

float free_flight(float3 origin_5, float3 dir_2, Segments segs, inout uint rng_3, inout Counters counters_13)
{
    uint k_8 = 0u;
    float t_3 = (float)0;

    const float _e5 = density_max();
    float _e9 = frame.extinction.x;
    float _e13 = frame.extinction.y;
    float majorant = ((_e9 + _e13) * _e5);
    if ((majorant <= 0.0)) {
        return -1.0;
    }
    uint2 loop_bound_12 = uint2(4294967295u, 4294967295u);
    bool loop_init_11 = true;
    while(true) {
        if (all(loop_bound_12 == uint2(0u, 0u))) { break; }
        loop_bound_12 -= uint2(loop_bound_12.y == 0u, 1u);
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
            t_3 = segs.a[min(uint(_e25), 1u)];
            uint2 loop_bound_13 = uint2(4294967295u, 4294967295u);
            while(true) {
                if (all(loop_bound_13 == uint2(0u, 0u))) { break; }
                loop_bound_13 -= uint2(loop_bound_13.y == 0u, 1u);
                float _e28 = t_3;
                const float _e29 = empty_cell_skip(origin_5, dir_2, _e28);
                if ((_e29 > 0.0)) {
                    float _e32 = t_3;
                    t_3 = (_e32 + _e29);
                    float _e34 = t_3;
                    uint _e36 = k_8;
                    if ((_e34 >= segs.b[min(uint(_e36), 1u)])) {
                        break;
                    }
                    continue;
                }
                float _e39 = t_3;
                const float _e40 = rng_exponential(rng_3, majorant);
                t_3 = (_e39 + _e40);
                float _e42 = t_3;
                uint _e44 = k_8;
                if ((_e42 >= segs.b[min(uint(_e44), 1u)])) {
                    break;
                }
                uint _e48 = counters_13.view_steps;
                counters_13.view_steps = (_e48 + 1u);
                float _e51 = t_3;
                const float _e54 = density_at((origin_5 + (dir_2 * _e51)), counters_13);
                const float _e55 = rng_next(rng_3);
                if (((_e55 * _e5) < _e54)) {
                    float _e58 = t_3;
                    return _e58;
                }
            }
        }
    }
    return -1.0;
}

float transmittance_along(float3 origin_6, float3 dir_3, Segments segs_1, inout uint rng_4, inout Counters counters_14)
{
    float tr = 1.0;
    uint k_9 = 0u;
    float t_4 = (float)0;

    float _e8 = frame.extinction.x;
    float _e12 = frame.extinction.y;
    float sigma_t_4 = (_e8 + _e12);
    const float _e14 = density_max();
    float majorant_1 = (sigma_t_4 * _e14);
    if ((majorant_1 <= 0.0)) {
        return 1.0;
    }
    uint2 loop_bound_14 = uint2(4294967295u, 4294967295u);
    bool loop_init_12 = true;
    while(true) {
        if (all(loop_bound_14 == uint2(0u, 0u))) { break; }
        loop_bound_14 -= uint2(loop_bound_14.y == 0u, 1u);
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
            t_4 = segs_1.a[min(uint(_e27), 1u)];
            uint2 loop_bound_15 = uint2(4294967295u, 4294967295u);
            while(true) {
                if (all(loop_bound_15 == uint2(0u, 0u))) { break; }
                loop_bound_15 -= uint2(loop_bound_15.y == 0u, 1u);
                float _e30 = t_4;
                const float _e31 = empty_cell_skip(origin_6, dir_3, _e30);
                if ((_e31 > 0.0)) {
                    float _e34 = t_4;
                    t_4 = (_e34 + _e31);
                    float _e36 = t_4;
                    uint _e38 = k_9;
                    if ((_e36 >= segs_1.b[min(uint(_e38), 1u)])) {
                        break;
                    }
                    continue;
                }
                float _e41 = t_4;
                const float _e42 = rng_exponential(rng_4, majorant_1);
                t_4 = (_e41 + _e42);
                float _e44 = t_4;
                uint _e46 = k_9;
                if ((_e44 >= segs_1.b[min(uint(_e46), 1u)])) {
                    break;
                }
                uint _e50 = counters_14.light;
                counters_14.light = (_e50 + 1u);
                float _e53 = t_4;
                const float _e56 = density_at((origin_6 + (dir_3 * _e53)), counters_14);
                float _e57 = tr;
                tr = (_e57 * (1.0 - ((sigma_t_4 * _e56) / majorant_1)));
                float _e63 = tr;
                if ((_e63 <= 0.0)) {
                    return 0.0;
                }
                float _e67 = tr;
                if ((_e67 < 0.01)) {
                    const float _e70 = rng_next(rng_4);
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

float sample_hg_cos(float g_4, float u)
{
    if ((abs(g_4) < 0.0001)) {
        return (1.0 - (2.0 * u));
    }
    float s_11 = ((1.0 - (g_4 * g_4)) / ((1.0 - g_4) + ((2.0 * g_4) * u)));
    return clamp((((1.0 + (g_4 * g_4)) - (s_11 * s_11)) / (2.0 * g_4)), -1.0, 1.0);
}

PhaseSample ConstructPhaseSample(float3 arg0, float arg1) {
    PhaseSample ret = (PhaseSample)0;
    ret.dir = arg0;
    ret.weight = arg1;
    return ret;
}

PhaseSample sample_phase(float3 dir_4, inout uint rng_5)
{
    float cos_theta_7 = 0.0;
    float pdf = 0.0;

    const float _e2 = rng_next(rng_5);
    const float _e3 = rng_next(rng_5);
    const float _e5 = rng_next(rng_5);
    float phi_1 = (6.2831855 * _e5);
    uint _e14 = frame.modes.x;
    if ((_e14 == PHASE_TWO_LOBE_HG)) {
        float _e20 = frame.phase.x;
        float _e24 = frame.phase.y;
        float _e28 = frame.phase.z;
        float g_6 = ((_e2 < _e28) ? _e24 : _e20);
        const float _e31 = sample_hg_cos(g_6, _e3);
        cos_theta_7 = _e31;
        float _e32 = cos_theta_7;
        float _e36 = frame.phase.x;
        const float _e37 = phase_hg(_e32, _e36);
        float _e38 = cos_theta_7;
        float _e42 = frame.phase.y;
        const float _e43 = phase_hg(_e38, _e42);
        float _e47 = frame.phase.z;
        pdf = lerp(_e37, _e43, _e47);
    } else {
        float _e52 = frame.phase.x;
        const float _e53 = sample_hg_cos(_e52, _e3);
        cos_theta_7 = _e53;
        float _e54 = cos_theta_7;
        float _e58 = frame.phase.x;
        const float _e59 = phase_hg(_e54, _e58);
        pdf = _e59;
    }
    float _e60 = cos_theta_7;
    float _e61 = cos_theta_7;
    float sin_theta = sqrt(max((1.0 - (_e60 * _e61)), 0.0));
    float sign_ = ((dir_4.z >= 0.0) ? 1.0 : -1.0);
    float a_9 = (-1.0 / (sign_ + dir_4.z));
    float bb = ((dir_4.x * dir_4.y) * a_9);
    float3 t_8 = float3((1.0 + (((sign_ * dir_4.x) * dir_4.x) * a_9)), (sign_ * bb), (-(sign_) * dir_4.x));
    float3 b_10 = float3(bb, (sign_ + ((dir_4.y * dir_4.y) * a_9)), -(dir_4.y));
    float _e109 = cos_theta_7;
    float3 w_7 = normalize((((t_8 * (sin_theta * cos(phi_1))) + (b_10 * (sin_theta * sin(phi_1)))) + (dir_4 * _e109)));
    float _e113 = cos_theta_7;
    const float _e115 = phase(_e113, 1.0);
    float _e116 = pdf;
    float _e118 = pdf;
    const PhaseSample phasesample = ConstructPhaseSample(w_7, ((_e118 > 0.0) ? (_e115 / _e116) : 0.0));
    return phasesample;
}

float3 environment(float3 pos, float3 d_16, float h_9)
{
    const bool _e3 = physical_sky();
    if (_e3) {
        const float3 _e4 = sky_from(pos, d_16);
        float4 _e7 = frame.sun_illuminance;
        float _e13 = frame.ambient_bottom.w;
        return ((_e4 * _e7.xyz) * _e13);
    }
    const float3 _e15 = ambient(h_9, pos);
    return _e15;
}

PathResult ConstructPathResult(float3 arg0, float arg1, float arg2) {
    PathResult ret = (PathResult)0;
    ret.radiance = arg0;
    ret.transmittance = arg1;
    ret.depth = arg2;
    return ret;
}

PathResult trace_path(float3 view_3, Interval span_3, inout uint rng_6, inout Counters counters_15)
{
    PathResult out_2 = ConstructPathResult((0.0).xxx, 1.0, -1.0);
    bool local_54 = (bool)0;
    bool local_55 = (bool)0;
    bool local_56 = (bool)0;
    uint max_orders = MAX_PATH_ORDERS;
    float3 pos_1 = (float3)0;
    float3 dir_5 = (float3)0;
    float throughput = 1.0;
    uint order = 0u;
    bool local_57 = (bool)0;

    if ((span_3.kind != RAY_MARCH)) {
        PathResult _e13 = out_2;
        const PathResult pathresult = _e13;
        return pathresult;
    }
    float _e17 = frame.camera_position.y;
    float3 cam = float3(0.0, _e17, 0.0);
    Segments primary = ConstructSegments(float2(span_3.start, 0.0), float2((span_3.start + span_3.length_), 0.0), 1u);
    const float _e32 = transmittance_along(cam, view_3, primary, rng_6, counters_15);
    out_2.transmittance = _e32;
    const float _e33 = free_flight(cam, view_3, primary, rng_6, counters_15);
    if ((_e33 < 0.0)) {
        PathResult _e36 = out_2;
        const PathResult pathresult_1 = _e36;
        return pathresult_1;
    }
    out_2.depth = _e33;
    float4 _e40 = frame.sun_direction;
    float3 sun_6 = _e40.xyz;
    float _e45 = frame.extinction.x;
    float _e49 = frame.extinction.y;
    float sigma_t_5 = (_e45 + _e49);
    float _e54 = frame.extinction.x;
    float albedo = ((sigma_t_5 > 0.0) ? (_e54 / sigma_t_5) : 0.0);
    float _e63 = frame.ambient_bottom.w;
    if ((_e63 > 0.0)) {
        const bool _e68 = physical_sky();
        if (!(_e68)) {
            float4 _e74 = frame.ambient_bottom;
            local_55 = any((_e74.xyz > (0.0).xxx));
        } else {
            local_55 = true;
        }
        bool _e81 = local_55;
        if (!(_e81)) {
            float4 _e87 = frame.ambient_top;
            local_56 = any((_e87.xyz > (0.0).xxx));
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
    if ((_e102 > 0u)) {
        uint _e108 = frame.misc.z;
        max_orders = min(_e108, MAX_PATH_ORDERS);
    }
    pos_1 = (cam + (view_3 * _e33));
    dir_5 = view_3;
    uint2 loop_bound_16 = uint2(4294967295u, 4294967295u);
    while(true) {
        if (all(loop_bound_16 == uint2(0u, 0u))) { break; }
        loop_bound_16 -= uint2(loop_bound_16.y == 0u, 1u);
        float _e119 = throughput;
        throughput = (_e119 * albedo);
        uint _e121 = order;
        order = (_e121 + 1u);
        float3 _e124 = pos_1;
        const float _e125 = altitude_of(_e124);
        const float _e126 = height_fraction(_e125);
        float3 _e127 = pos_1;
        const bool _e128 = hits_ground(_e127, _e125, sun_6);
        if (!(_e128)) {
            float3 _e130 = pos_1;
            float3 _e131 = pos_1;
            const Segments _e132 = layer_segments(_e131, _e125, sun_6);
            const float _e133 = transmittance_along(_e130, sun_6, _e132, rng_6, counters_15);
            float3 _e135 = out_2.radiance;
            float4 _e138 = frame.sun_illuminance;
            float3 _e140 = pos_1;
            const float3 _e141 = sun_through_air(_e140);
            float _e143 = throughput;
            float3 _e144 = dir_5;
            const float _e147 = phase(dot(_e144, sun_6), 1.0);
            out_2.radiance = (_e135 + ((_e138.xyz * _e141) * ((_e143 * _e147) * _e133)));
        }
        float3 _e152 = dir_5;
        const PhaseSample _e153 = sample_phase(_e152, rng_6);
        float3 _e154 = pos_1;
        float3 _e156 = pos_1;
        const Segments _e158 = layer_segments(_e156, _e125, _e153.dir);
        const float _e159 = free_flight(_e154, _e153.dir, _e158, rng_6, counters_15);
        if ((_e159 < 0.0)) {
            if (ambient_on) {
                float3 _e163 = out_2.radiance;
                float3 _e164 = pos_1;
                const float3 _e166 = environment(_e164, _e153.dir, _e126);
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
            const float _e189 = rng_next(rng_6);
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
        float3 _e198 = pos_1;
        float3 _e199 = dir_5;
        pos_1 = (_e198 + (_e199 * _e159));
    }
    PathResult _e202 = out_2;
    const PathResult pathresult_2 = _e202;
    return pathresult_2;
}

bool camera_still()
{
    bool local_58 = (bool)0;
    bool local_59 = (bool)0;
    bool local_60 = (bool)0;

    float4 _e2 = frame.camera_position;
    float4 _e5 = frame.previous_position;
    if (all((_e2 == _e5))) {
        float4 _e12 = frame.camera_forward;
        float4 _e15 = frame.previous_forward;
        local_58 = all((_e12 == _e15));
    } else {
        local_58 = false;
    }
    bool _e19 = local_58;
    if (_e19) {
        float4 _e24 = frame.camera_right;
        float4 _e28 = frame.previous_right;
        local_59 = all((_e24.xyz == _e28.xyz));
    } else {
        local_59 = false;
    }
    bool _e33 = local_59;
    if (_e33) {
        float4 _e38 = frame.camera_up;
        float4 _e42 = frame.previous_up;
        local_60 = all((_e38.xyz == _e42.xyz));
    } else {
        local_60 = false;
    }
    bool _e47 = local_60;
    return _e47;
}

float luminance(float3 c_3)
{
    return dot(c_3, float3(0.2126, 0.7152, 0.0722));
}

float basic_sun_depth(float3 rel_11, float alt_15, inout Counters counters_16)
{
    float tau_10 = 0.0;
    uint i_16 = 1u;

    uint steps_4 = frame.counts.w;
    if ((steps_4 == 0u)) {
        return 0.0;
    }
    float4 _e12 = frame.sun_direction;
    float3 sun_7 = _e12.xyz;
    float rp_5 = frame.atmosphere.x;
    float top_2 = frame.atmosphere.z;
    float _e25 = frame.atmosphere.y;
    float thickness = (top_2 - _e25);
    const Roots _e39 = solve_sphere(dot(sun_7, float3(rel_11.x, (rel_11.y + rp_5), rel_11.z)), ((alt_15 - top_2) * ((alt_15 + top_2) + (2.0 * rp_5))));
    float length_ = min(max(_e39.t1_, 0.0), (3.0 * thickness));
    float dt_3 = (length_ / float(steps_4));
    float _e51 = frame.extinction.x;
    float _e55 = frame.extinction.y;
    float sigma_t_6 = (_e51 + _e55);
    float4 _e59 = frame.camera_position;
    float2 cam_xz_1 = _e59.xz;
    uint2 loop_bound_17 = uint2(4294967295u, 4294967295u);
    bool loop_init_13 = true;
    while(true) {
        if (all(loop_bound_17 == uint2(0u, 0u))) { break; }
        loop_bound_17 -= uint2(loop_bound_17.y == 0u, 1u);
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
            float3 q_8 = (rel_11 + (sun_7 * (float(_e71) * dt_3)));
            float3 p_22 = float3((q_8.x + cam_xz_1.x), q_8.y, (q_8.z + cam_xz_1.y));
            float _e84 = tau_10;
            const float _e85 = altitude_of(q_8);
            const float _e86 = cloud_density(p_22, _e85, counters_16);
            tau_10 = (_e84 + ((sigma_t_6 * _e86) * dt_3));
        }
    }
    float _e93 = tau_10;
    return _e93;
}

MarchResult basic_pixel(uint2 pixel_7)
{
    Counters counters_17 = ConstructCounters(0u, 0u, 0u, 0u);
    float3 radiance_2 = (0.0).xxx;
    float transmittance_1 = 1.0;
    float depth_sum = 0.0;
    uint i_17 = 0u;
    float depth_3 = 0.0;

    const float3 _e1 = view_ray(pixel_7);
    float cam_alt_3 = frame.camera_position.y;
    float4 _e8 = frame.camera_position;
    float2 cam_xz_2 = _e8.xz;
    count(STAT_PIXELS, 1u);
    const Interval _e25 = cloud_interval(cam_alt_3, _e1);
    if ((_e25.kind == RAY_MISSES_LAYER)) {
        count(STAT_EXIT_MISSED, 1u);
    } else {
        if ((_e25.kind == RAY_HITS_GROUND)) {
            count(STAT_EXIT_GROUND, 1u);
        } else {
            count(STAT_MARCHED, 1u);
            uint steps_5 = frame.counts.z;
            float dt_4 = (_e25.length_ / float(steps_5));
            float sigma_s = frame.extinction.x;
            float _e52 = frame.extinction.y;
            float sigma_t_7 = (sigma_s + _e52);
            float4 _e56 = frame.sun_illuminance;
            float4 _e60 = frame.sun_direction;
            float _e66 = frame.phase.x;
            const float _e67 = phase_hg(dot(_e1, _e60.xyz), _e66);
            float3 sun_phase = (_e56.xyz * _e67);
            uint2 loop_bound_18 = uint2(4294967295u, 4294967295u);
            bool loop_init_14 = true;
            while(true) {
                if (all(loop_bound_18 == uint2(0u, 0u))) { break; }
                loop_bound_18 -= uint2(loop_bound_18.y == 0u, 1u);
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
                    float t_9 = (_e25.start + (float(_e78) * dt_4));
                    float3 rel_14 = ((_e1 * t_9) + float3(0.0, cam_alt_3, 0.0));
                    float3 p_23 = float3((rel_14.x + cam_xz_2.x), rel_14.y, (rel_14.z + cam_xz_2.y));
                    const float _e95 = altitude_of(rel_14);
                    const float _e96 = cloud_density(p_23, _e95, counters_17);
                    if ((_e96 <= 0.0)) {
                        continue;
                    }
                    const float _e99 = basic_sun_depth(rel_14, _e95, counters_17);
                    float beer_powder = ((2.0 * exp(-(_e99))) * (1.0 - exp((-2.0 * _e99))));
                    float3 _e110 = radiance_2;
                    float _e111 = transmittance_1;
                    radiance_2 = (_e110 + (sun_phase * ((((beer_powder * _e111) * sigma_s) * _e96) * dt_4)));
                    float step_t_1 = exp(((-(sigma_t_7) * _e96) * dt_4));
                    float _e122 = depth_sum;
                    float _e123 = transmittance_1;
                    depth_sum = (_e122 + ((t_9 * _e123) * (1.0 - step_t_1)));
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
    float3 _e156 = radiance_2;
    float _e157 = transmittance_1;
    float _e158 = depth_3;
    const MarchResult marchresult_1 = ConstructMarchResult(_e156, _e157, _e158);
    return marchresult_1;
}

float atlas_hash(uint a_2, uint b_2)
{
    const uint _e2 = pcg(b_2);
    const uint _e4 = pcg((a_2 ^ _e2));
    return (float((_e4 >> 8u)) * 5.9604645e-8);
}

float value_noise(float2 p_14, uint seed)
{
    uint2 i_19 = naga_f2u32(floor(p_14));
    float2 f_6 = frac(p_14);
    float2 s_12 = ((f_6 * f_6) * ((3.0).xx - (2.0 * f_6)));
    uint h_14 = (seed * 7919u);
    const float _e17 = atlas_hash((i_19.x + h_14), i_19.y);
    const float _e23 = atlas_hash(((i_19.x + 1u) + h_14), i_19.y);
    const float _e29 = atlas_hash((i_19.x + h_14), (i_19.y + 1u));
    const float _e37 = atlas_hash(((i_19.x + 1u) + h_14), (i_19.y + 1u));
    return lerp(lerp(_e17, _e23, s_12.x), lerp(_e29, _e37, s_12.x), s_12.y);
}

float value_fbm(float2 p_15, uint seed_1)
{
    float sum_5 = 0.0;
    float weight = 0.5;
    float2 q_4 = (float2)0;
    uint o = 0u;

    q_4 = p_15;
    uint2 loop_bound_19 = uint2(4294967295u, 4294967295u);
    bool loop_init_15 = true;
    while(true) {
        if (all(loop_bound_19 == uint2(0u, 0u))) { break; }
        loop_bound_19 -= uint2(loop_bound_19.y == 0u, 1u);
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
            float2 _e14 = q_4;
            uint _e15 = o;
            const float _e17 = value_noise(_e14, (seed_1 + _e15));
            sum_5 = (_e12 + (_e13 * _e17));
            float2 _e20 = q_4;
            q_4 = (_e20 * 2.0);
            float _e23 = weight;
            weight = (_e23 * 0.5);
        }
    }
    float _e29 = sum_5;
    return (_e29 / 0.9375);
}

float sprite_texture(uint tile_1, float2 uv)
{
    float billow = 0.0;
    uint i_18 = 0u;
    float2 at = (float2)0;
    float a_3 = (float)0;

    float2 c_10 = (uv - (0.5).xx);
    float mask = smoothstep(0.48, 0.36, length(c_10));
    const float _e16 = value_fbm(((uv * 6.0) + ((float(tile_1) * 13.0)).xx), tile_1);
    if ((tile_1 < 4u)) {
        float2 q_9 = (c_10 * float2(1.0, 3.2));
        float streak = (1.0 - smoothstep(0.05, 0.45, length(q_9)));
        const float _e40 = value_fbm(((uv * float2(3.0, 12.0)) + ((float(tile_1) * 5.0)).xx), (tile_1 + 16u));
        const float _e46 = saturate_(((_e40 * 1.6) - 0.3));
        return (((mask * streak) * _e46) * 0.8);
    }
    uint blobs = (5u + naga_mod(tile_1, 4u));
    uint2 loop_bound_20 = uint2(4294967295u, 4294967295u);
    bool loop_init_16 = true;
    while(true) {
        if (all(loop_bound_20 == uint2(0u, 0u))) { break; }
        loop_bound_20 -= uint2(loop_bound_20.y == 0u, 1u);
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
            const float _e63 = atlas_hash(tile_1, (2u * _e61));
            uint _e65 = i_18;
            const float _e69 = atlas_hash(tile_1, ((2u * _e65) + 1u));
            float2 centre_1 = (float2(_e63, _e69) - (0.5).xx);
            at = ((0.5).xx + (centre_1 * 0.34));
            if ((tile_1 == 4u)) {
                at.y = (0.5 + ((centre_1.y - 0.5) * 0.24));
            }
            uint _e91 = i_18;
            const float _e93 = atlas_hash(tile_1, (100u + _e91));
            float r_18 = (0.14 + (0.1 * _e93));
            float2 _e98 = at;
            float d_23 = (length((uv - _e98)) / r_18);
            float _e102 = billow;
            const float _e106 = saturate_((1.0 - (d_23 * d_23)));
            billow = max(_e102, _e106);
        }
    }
    float _e111 = billow;
    const float _e114 = saturate_((_e111 * 1.5));
    a_3 = ((mask * _e114) * (0.55 + (0.45 * _e16)));
    if ((tile_1 == 4u)) {
        float _e124 = a_3;
        a_3 = (_e124 * smoothstep(0.62, 0.54, uv.y));
    }
    float _e130 = a_3;
    return _e130;
}

float3 sprite_rel(float2 xz, float alt_16)
{
    float rp_6 = frame.atmosphere.x;
    float4 _e8 = frame.camera_position;
    float2 d_24 = (xz - _e8.xz);
    float k_19 = ((alt_16 * (alt_16 + (2.0 * rp_6))) - dot(d_24, d_24));
    float y_3 = (k_19 / (rp_6 + sqrt(max(((rp_6 * rp_6) + k_19), 0.0))));
    return float3(d_24.x, y_3, d_24.y);
}

SpriteCell ConstructSpriteCell(int2 arg0, float arg1, bool arg2) {
    SpriteCell ret = (SpriteCell)0;
    ret.index = arg0;
    ret.size = arg1;
    ret.covered = arg2;
    return ret;
}

SpriteCell sprite_cell(uint cell)
{
    int2 start_1 = (int2)0;
    uint k_10 = 3u;
    bool local_61 = (bool)0;
    bool local_62 = (bool)0;

    uint level_1 = naga_div(cell, 64u);
    int2 local_66 = int2(int(naga_mod(cell, 8u)), int(naga_mod(naga_div(cell, 8u), 8u)));
    float4 _e15 = frame.camera_position;
    start_1 = asint(asuint(naga_f2i32(floor((_e15.xz / (12000.0).xx)))) - asuint((int(4)).xx));
    uint2 loop_bound_21 = uint2(4294967295u, 4294967295u);
    bool loop_init_17 = true;
    while(true) {
        if (all(loop_bound_21 == uint2(0u, 0u))) { break; }
        loop_bound_21 -= uint2(loop_bound_21.y == 0u, 1u);
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
            int2 _e29 = start_1;
            start_1 = asint(asuint(int(2)) * asuint(asint(asuint(_e29) + asuint((int(2)).xx))));
        }
    }
    if ((level_1 > 0u)) {
        local_61 = all((local_66 >= (int(2)).xx));
    } else {
        local_61 = false;
    }
    bool _e47 = local_61;
    if (_e47) {
        local_62 = all((local_66 < (int(6)).xx));
    } else {
        local_62 = false;
    }
    bool covered = local_62;
    int2 _e56 = start_1;
    const SpriteCell spritecell = ConstructSpriteCell(asint(asuint(_e56) + asuint(local_66)), (SPRITE_CELL0_ * float((1u << level_1))), covered);
    return spritecell;
}

SpriteCandidate ConstructSpriteCandidate(float2 arg0, float arg1, float arg2, float arg3, float arg4, float arg5, float arg6, float arg7) {
    SpriteCandidate ret = (SpriteCandidate)0;
    ret.xz = arg0;
    ret.alt = arg1;
    ret.h = arg2;
    ret.size_hash = arg3;
    ret.texture_hash = arg4;
    ret.rotation_hash = arg5;
    ret.density = arg6;
    ret.precipitation = arg7;
    return ret;
}

SpriteCandidate sprite_candidate(SpriteCell c_4, uint level, uint s_2, inout Counters counters_18)
{
    float density_3 = 0.0;

    const uint _e10 = pcg(level);
    const uint _e12 = pcg((asuint(c_4.index.y) ^ _e10));
    const uint _e14 = pcg((asuint(c_4.index.x) ^ _e12));
    const float _e17 = atlas_hash(_e14, (8u * s_2));
    const float _e22 = atlas_hash(_e14, ((8u * s_2) + 1u));
    const float _e27 = atlas_hash(_e14, ((8u * s_2) + 2u));
    const float _e32 = atlas_hash(_e14, ((8u * s_2) + 3u));
    float4 u_1 = float4(_e17, _e22, _e27, _e32);
    const float _e38 = atlas_hash(_e14, ((8u * s_2) + 4u));
    const float _e43 = atlas_hash(_e14, ((8u * s_2) + 5u));
    float2 v_3 = float2(_e38, _e43);
    float2 xz_2 = ((float2(c_4.index) + u_1.xy) * c_4.size);
    const Layer _e56 = cloud_layer(0u);
    const Weather _e57 = sample_weather(float3(xz_2.x, 0.0, xz_2.y), _e56);
    float h_15 = (0.04 + (u_1.z * (lerp(0.3, 0.95, _e57.cloud_type) - 0.04)));
    float _e71 = frame.atmosphere.y;
    float _e75 = frame.atmosphere.z;
    float _e79 = frame.atmosphere.y;
    float alt_18 = (_e71 + (h_15 * (_e75 - _e79)));
    if (!(c_4.covered)) {
        const float3 _e87 = sprite_rel(xz_2, alt_18);
        const float _e92 = cloud_density(float3(xz_2.x, _e87.y, xz_2.y), alt_18, counters_18);
        density_3 = _e92;
    }
    float _e96 = density_3;
    const SpriteCandidate spritecandidate = ConstructSpriteCandidate(xz_2, alt_18, h_15, u_1.w, v_3.x, v_3.y, _e96, _e57.precipitation);
    return spritecandidate;
}

float3 sprite_sky_level(float h_10)
{
    const float _e1 = saturate_(h_10);
    float x_11 = (_e1 * 4.0);
    if ((x_11 < 1.0)) {
        return lerp(SKY_LEVEL0_, SKY_LEVEL1_, x_11);
    }
    if ((x_11 < 2.0)) {
        return lerp(SKY_LEVEL1_, SKY_LEVEL2_, (x_11 - 1.0));
    }
    if ((x_11 < 3.0)) {
        return lerp(SKY_LEVEL2_, SKY_LEVEL3_, (x_11 - 2.0));
    }
    return lerp(SKY_LEVEL3_, SKY_LEVEL4_, (x_11 - 3.0));
}

float sprite_sun_level(float cos_angle)
{
    if ((cos_angle < 0.0)) {
        return lerp(SPRITE_C_MIN, SPRITE_C_MED, (cos_angle + 1.0));
    }
    return lerp(SPRITE_C_MED, SPRITE_C_MAX, cos_angle);
}

float2 sprite_corner(uint k_11)
{
    bool local_63 = (bool)0;

    uint q_10 = ((k_11 >= 3u) ? ((k_11 == 3u) ? 0u : (k_11 - 2u)) : k_11);
    if (!((q_10 == 1u))) {
        local_63 = (q_10 == 2u);
    } else {
        local_63 = true;
    }
    bool _e18 = local_63;
    return float2((_e18 ? 1.0 : -1.0), ((q_10 >= 2u) ? 1.0 : -1.0));
}

float3 sky_radiance(float3 d_17, float alt_17)
{
    float4 _e4 = frame.sun_direction;
    float3 sun_8 = _e4.xyz;
    float4 _e8 = frame.sun_illuminance;
    float3 e_1 = _e8.xyz;
    const float _e15 = saturate_(((sun_8.y * 4.0) + 0.3));
    const bool _e19 = hits_ground(float3(0.0, alt_17, 0.0), alt_17, d_17);
    if (_e19) {
        float3 ground_albedo = float3(0.035, 0.035, 0.03);
        return (ground_albedo * (((e_1 * max(sun_8.y, 0.0)) / (3.1415927).xxx) + ((0.05 * e_1) * _e15)));
    }
    float3 zenith = float3(0.018, 0.04, 0.1);
    float3 horizon_2 = float3(0.07, 0.085, 0.11);
    const float _e45 = saturate_(d_17.y);
    float3 gradient_1 = lerp(horizon_2, zenith, sqrt(_e45));
    float3 sunset = (((1.0 - (_e15 * 0.8)) * pow((1.0 - _e45), 6.0)) * float3(0.25, 0.1, 0.0));
    const float _e64 = phase_hg(dot(d_17, sun_8), 0.76);
    float glow = (_e64 * 0.02);
    const float _e73 = saturate_(((sun_8.y * 10.0) + 1.0));
    return (e_1 * (((gradient_1 * _e15) + (sunset * _e73)) + ((glow * _e15)).xxx));
}

float3 sun_disk(float3 d_18)
{
    float cos_r = frame.sun_direction.w;
    float4 _e7 = frame.sun_direction;
    if ((dot(d_18, _e7.xyz) < cos_r)) {
        return (0.0).xxx;
    }
    float4 _e15 = frame.sun_illuminance;
    return (_e15.xyz / ((6.2831855 * max((1.0 - cos_r), 1e-6))).xxx);
}

float3 moon_disk(float3 d_19)
{
    bool local_64 = (bool)0;

    float4 _e3 = frame.moon;
    float3 m_4 = _e3.xyz;
    float c_11 = dot(d_19, m_4);
    float _e9 = frame.moon.w;
    if (!((_e9 <= 0.0))) {
        local_64 = (c_11 < MOON_COS_RADIUS);
    } else {
        local_64 = true;
    }
    bool _e18 = local_64;
    if (_e18) {
        return (0.0).xxx;
    }
    float3 offset = ((d_19 - (m_4 * c_11)) / (0.0045149517).xxx);
    float x2_1 = min(dot(offset, offset), 1.0);
    float3 normal = (offset - (m_4 * sqrt((1.0 - x2_1))));
    float4 _e36 = frame.night;
    float lit_1 = smoothstep(-0.02, 0.02, dot(normal, _e36.xyz));
    float _e46 = frame.moon.w;
    return (((_e46 / 6.40407e-5) * lit_1)).xxx;
}

float3 stars(float3 d_20)
{
    uint face = 0u;
    float2 uv_1 = (0.0).xx;
    float major = 0.0;
    bool local_65 = (bool)0;
    float3 star = (0.0).xxx;

    float e0_ = frame.night.w;
    if ((e0_ <= 0.0)) {
        return (0.0).xxx;
    }
    float3 a_10 = abs(d_20);
    if ((a_10.x >= a_10.y)) {
        local_65 = (a_10.x >= a_10.z);
    } else {
        local_65 = false;
    }
    bool _e26 = local_65;
    if (_e26) {
        face = ((d_20.x > 0.0) ? 0u : 1u);
        uv_1 = d_20.zy;
        major = a_10.x;
    } else {
        if ((a_10.y >= a_10.z)) {
            face = ((d_20.y > 0.0) ? 2u : 3u);
            uv_1 = d_20.xz;
            major = a_10.y;
        } else {
            face = ((d_20.z > 0.0) ? 4u : 5u);
            uv_1 = d_20.xy;
            major = a_10.z;
        }
    }
    float2 _e54 = uv_1;
    float _e55 = major;
    float2 st = clamp((((_e54 / (_e55).xx) * 0.5) + (0.5).xx), (0.0).xx, (0.999999).xx);
    uint2 cell_2 = naga_f2u32((st * 96.0));
    uint _e71 = face;
    uint id_22 = ((((_e71 * STAR_CELLS) + cell_2.y) * STAR_CELLS) + cell_2.x);
    const uint _e85 = pcg((id_22 ^ 2654435769u));
    float h0_ = (float((_e85 >> 8u)) * 5.9604645e-8);
    if ((h0_ >= 0.15085077)) {
        return (0.0).xxx;
    }
    const uint _e96 = pcg((id_22 ^ 2246822507u));
    float h1_ = (float((_e96 >> 8u)) * 5.9604645e-8);
    const uint _e104 = pcg((id_22 ^ 3266489909u));
    float h2_ = (float((_e104 >> 8u)) * 5.9604645e-8);
    const uint _e112 = pcg((id_22 ^ 668265263u));
    float h3_ = (float((_e112 >> 8u)) * 5.9604645e-8);
    const uint _e120 = pcg((id_22 ^ 374761393u));
    float h4_ = (float((_e120 >> 8u)) * 5.9604645e-8);
    float2 star_st = (((float2(cell_2) + (0.15).xx) + (0.7 * float2(h1_, h2_))) / (96.0).xx);
    float _e142 = major;
    float2 q_11 = (((star_st * 2.0) - (1.0).xx) * _e142);
    uint _e147 = face;
    if ((_e147 < 2u)) {
        float _e150 = major;
        float _e152 = major;
        uint _e153 = face;
        star = float3(((_e153 == 0u) ? _e152 : -(_e150)), q_11.y, q_11.x);
    } else {
        uint _e160 = face;
        if ((_e160 < 4u)) {
            float _e164 = major;
            float _e166 = major;
            uint _e167 = face;
            star = float3(q_11.x, ((_e167 == 2u) ? _e166 : -(_e164)), q_11.y);
        } else {
            float _e175 = major;
            float _e177 = major;
            uint _e178 = face;
            star = float3(q_11.x, q_11.y, ((_e178 == 4u) ? _e177 : -(_e175)));
        }
    }
    float3 _e183 = star;
    star = normalize(_e183);
    float magnitude = max((STAR_FAINTEST + (log(max((h0_ / 0.15085077), 1e-6)) / 1.1052408)), -1.5);
    float illuminance = (e0_ * pow(10.0, (-0.4 * magnitude)));
    float _e203 = frame.camera_position.w;
    uint _e209 = frame.counts.y;
    float pixel_angle = ((2.0 * _e203) / float(_e209));
    float3 _e212 = star;
    float dist_1 = (acos(clamp(dot(d_20, _e212), -1.0, 1.0)) / pixel_angle);
    float weight_1 = (exp(((-(dist_1) * dist_1) / 0.5)) / 1.5707964);
    float3 tint = lerp(float3(0.8, 0.9, 1.1), float3(1.15, 0.95, 0.75), (h3_ * h4_));
    return (tint * ((illuminance * weight_1) / (pixel_angle * pixel_angle)));
}

float3 physical_composite(uint2 pixel_8, float3 view_4, float4 cloud)
{
    float3 sky = (float3)0;
    float3 space = (float3)0;
    float3 radiance_3 = (float3)0;

    float4 _e5 = frame.sun_illuminance;
    float3 e_2 = _e5.xyz;
    const float3 _e7 = camera_air_origin();
    float r_19 = _e7.y;
    const float3 _e9 = sky_view(view_4);
    sky = (_e9 * e_2);
    const bool _e13 = meets_ground(r_19, view_4.y);
    if (_e13) {
        float3 _e14 = sky;
        const float3 _e15 = ground_shadow_loss(view_4, r_19);
        sky = max((_e14 - (_e15 * e_2)), (0.0).xxx);
    } else {
        const float3 _e21 = moon_disk(view_4);
        const float3 _e22 = stars(view_4);
        space = (_e21 + _e22);
        uint _e28 = frame.modes.w;
        if (((_e28 & FLAG_MOONLIT) == 0u)) {
            float3 _e33 = space;
            const float3 _e34 = sun_disk(view_4);
            space = (_e33 + _e34);
        }
        float3 _e36 = sky;
        float3 _e37 = space;
        const float3 _e39 = transmittance_to_top(r_19, view_4.y);
        sky = (_e36 + (_e37 * _e39));
    }
    float3 _e42 = sky;
    radiance_3 = (_e42 * cloud.w);
    if ((cloud.w < 1.0)) {
        float4 _e51 = depth_in.Load(int3(pixel_8, int(0)));
        const float4 _e53 = aerial(pixel_8, _e51.x);
        float3 _e54 = radiance_3;
        radiance_3 = (_e54 + (((_e53.xyz * e_2) * (1.0 - cloud.w)) + (cloud.xyz * _e53.w)));
    }
    float3 _e66 = radiance_3;
    return _e66;
}

float3 aces_fitted(float3 x_5)
{
    return clamp(((x_5 * ((2.51 * x_5) + (0.03).xxx)) / ((x_5 * ((2.43 * x_5) + (0.59).xxx)) + (0.14).xxx)), (0.0).xxx, (1.0).xxx);
}

void store_display(uint2 pixel_9, float3 radiance_4)
{
    float _e5 = frame.camera_right.w;
    float3 exposed = (radiance_4 * _e5);
    const float3 _e7 = aces_fitted(exposed);
    float3 display = pow(_e7, (0.45454547).xxx);
    image_out[pixel_9] = float4(display, 1.0);
    return;
}

[numthreads(8, 8, 1)]
void transmittance_lut(uint3 id : SV_DispatchThreadID)
{
    float3 sum = (0.0).xxx;
    uint i = 0u;
    float w = (float)0;
    bool local = (bool)0;

    if (any((id.xy >= TRANSMITTANCE_SIZE))) {
        return;
    }
    const float2 _e11 = transmittance_r_mu((float2(id.xy) / float2(255.0, 63.0)));
    const float _e14 = distance_to_top(_e11.x, _e11.y);
    float dt_5 = (_e14 / 128.0);
    uint2 loop_bound_22 = uint2(4294967295u, 4294967295u);
    bool loop_init_18 = true;
    while(true) {
        if (all(loop_bound_22 == uint2(0u, 0u))) { break; }
        loop_bound_22 -= uint2(loop_bound_22.y == 0u, 1u);
        if (!loop_init_18) {
            uint _e61 = i;
            i = (_e61 + 1u);
        }
        loop_init_18 = false;
        uint _e22 = i;
        if ((_e22 <= TRANSMITTANCE_STEPS)) {
        } else {
            break;
        }
        {
            uint _e25 = i;
            w = (((_e25 & 1u) == 1u) ? 4.0 : 2.0);
            uint _e34 = i;
            if (!((_e34 == 0u))) {
                uint _e40 = i;
                local = (_e40 == TRANSMITTANCE_STEPS);
            } else {
                local = true;
            }
            bool _e44 = local;
            if (_e44) {
                w = 1.0;
            }
            uint _e48 = i;
            const float _e51 = radius_after(_e11.x, _e11.y, (dt_5 * float(_e48)));
            float3 _e52 = sum;
            float _e53 = w;
            const float _e54 = air_bottom();
            const AirSample _e56 = air_at((_e51 - _e54));
            sum = (_e52 + (_e53 * _e56.extinction));
        }
    }
    float3 _e65 = sum;
    transmittance_lut_out[id.xy] = float4(exp((-(_e65) * (dt_5 / 3.0))), 1.0);
    return;
}

[numthreads(8, 8, 1)]
void multiscatter_lut(uint3 id_1 : SV_DispatchThreadID)
{
    float3 l2_ = (0.0).xxx;
    float3 f_ms = (0.0).xxx;
    uint k = 0u;
    float3 tau = (float3)0;
    uint i_1 = (uint)0;

    if (any((id_1.xy >= MULTISCATTER_SIZE))) {
        return;
    }
    float2 x_12 = (float2(id_1.xy) / float2(31.0, 31.0));
    float mu_s_7 = ((x_12.x * 2.0) - 1.0);
    const float _e16 = air_bottom();
    const float _e18 = air_top();
    const float _e19 = air_bottom();
    float r_20 = (_e16 + (x_12.y * (_e18 - _e19)));
    float3 origin_7 = float3(0.0, r_20, 0.0);
    float3 sun_9 = float3(sqrt(max((1.0 - (mu_s_7 * mu_s_7)), 0.0)), mu_s_7, 0.0);
    uint2 loop_bound_23 = uint2(4294967295u, 4294967295u);
    bool loop_init_19 = true;
    while(true) {
        if (all(loop_bound_23 == uint2(0u, 0u))) { break; }
        loop_bound_23 -= uint2(loop_bound_23.y == 0u, 1u);
        if (!loop_init_19) {
            uint _e121 = k;
            k = (_e121 + 1u);
        }
        loop_init_19 = false;
        uint _e43 = k;
        if ((_e43 < MULTISCATTER_DIRECTIONS)) {
        } else {
            break;
        }
        {
            uint _e46 = k;
            const float3 _e48 = fibonacci_direction(_e46, MULTISCATTER_DIRECTIONS);
            const float2 _e49 = air_ray_end(origin_7, _e48);
            float dt_6 = (_e49.x / 32.0);
            tau = (0.0).xxx;
            i_1 = 0u;
            uint2 loop_bound_24 = uint2(4294967295u, 4294967295u);
            bool loop_init_20 = true;
            while(true) {
                if (all(loop_bound_24 == uint2(0u, 0u))) { break; }
                loop_bound_24 -= uint2(loop_bound_24.y == 0u, 1u);
                if (!loop_init_20) {
                    uint _e103 = i_1;
                    i_1 = (_e103 + 1u);
                }
                loop_init_20 = false;
                uint _e58 = i_1;
                if ((_e58 < MULTISCATTER_STEPS)) {
                } else {
                    break;
                }
                {
                    uint _e61 = i_1;
                    float3 p_24 = (origin_7 + (_e48 * (dt_6 * (float(_e61) + 0.5))));
                    float rp_7 = length(p_24);
                    const float _e69 = air_bottom();
                    const AirSample _e71 = air_at((rp_7 - _e69));
                    float3 _e72 = tau;
                    float3 t_10 = exp(-((_e72 + ((0.5 * _e71.extinction) * dt_6))));
                    float3 s_13 = (_e71.rayleigh + (_e71.mie).xxx);
                    float3 _e84 = l2_;
                    const float3 _e90 = sun_transmittance(rp_7, dot((p_24 / (rp_7).xxx), sun_9));
                    l2_ = (_e84 + ((((t_10 * s_13) * 0.07957747) * _e90) * dt_6));
                    float3 _e94 = f_ms;
                    f_ms = (_e94 + ((t_10 * s_13) * dt_6));
                    float3 _e98 = tau;
                    tau = (_e98 + (_e71.extinction * dt_6));
                }
            }
            if ((_e49.y > 0.5)) {
                float3 g_7 = (origin_7 + (_e48 * _e49.x));
                float3 _e111 = l2_;
                float3 _e112 = tau;
                const float3 _e117 = ground_radiance_sun(dot(normalize(g_7), sun_9));
                l2_ = (_e111 + (exp(-(_e112)) * _e117));
            }
        }
    }
    float3 _e124 = l2_;
    float3 _e128 = f_ms;
    float3 psi = ((_e124 * 0.015625) / max(((1.0).xxx - (_e128 * 0.015625)), (1e-6).xxx));
    multiscatter_lut_out[id_1.xy] = float4(psi, 1.0);
    return;
}

[numthreads(8, 8, 1)]
void sky_view_lut(uint3 id_2 : SV_DispatchThreadID)
{
    if (any((id_2.xy >= SKY_VIEW_SIZE))) {
        return;
    }
    float2 x_13 = (float2(id_2.xy) / float2(191.0, 107.0));
    const float3 _e11 = camera_air_origin();
    const float _e14 = horizon_elevation(_e11.y);
    const float _e15 = sky_view_elevation(x_13.y, _e14);
    const float _e16 = sun_azimuth();
    float phi_2 = (_e16 + (x_13.x * PI));
    float3 d_25 = float3((cos(_e15) * cos(phi_2)), sin(_e15), (cos(_e15) * sin(phi_2)));
    const float3 _e31 = sky_along(_e11, d_25);
    sky_view_out[id_2.xy] = float4(_e31, 1.0);
    return;
}

[numthreads(8, 8, 1)]
void aerial_perspective(uint3 id_3 : SV_DispatchThreadID)
{
    float3 radiance = (0.0).xxx;
    float3 tau_1 = (0.0).xxx;
    uint z = 0u;
    uint k_1 = (uint)0;

    if (any((id_3.xy >= (32u).xx))) {
        return;
    }
    const float3 _e7 = aerial_ray(id_3.xy);
    const float3 _e8 = camera_air_origin();
    const float2 _e9 = air_ray_end(_e8, _e7);
    float4 _e12 = frame.sun_direction;
    float3 sun_10 = _e12.xyz;
    float cos_theta_9 = dot(_e7, sun_10);
    const float _e15 = phase_rayleigh(cos_theta_9);
    float _e19 = frame.air_mie.w;
    const float _e20 = phase_cornette_shanks_air(cos_theta_9, _e19);
    uint2 loop_bound_25 = uint2(4294967295u, 4294967295u);
    bool loop_init_21 = true;
    while(true) {
        if (all(loop_bound_25 == uint2(0u, 0u))) { break; }
        loop_bound_25 -= uint2(loop_bound_25.y == 0u, 1u);
        if (!loop_init_21) {
            uint _e122 = z;
            z = (_e122 + 1u);
        }
        loop_init_21 = false;
        uint _e30 = z;
        if ((_e30 < AERIAL_SLICES)) {
        } else {
            break;
        }
        {
            k_1 = 0u;
            uint2 loop_bound_26 = uint2(4294967295u, 4294967295u);
            bool loop_init_22 = true;
            while(true) {
                if (all(loop_bound_26 == uint2(0u, 0u))) { break; }
                loop_bound_26 -= uint2(loop_bound_26.y == 0u, 1u);
                if (!loop_init_22) {
                    uint _e99 = k_1;
                    k_1 = (_e99 + 1u);
                }
                loop_init_22 = false;
                uint _e35 = k_1;
                if ((_e35 < 4u)) {
                } else {
                    break;
                }
                {
                    uint _e38 = z;
                    uint _e40 = k_1;
                    float t0_1 = (AERIAL_SLICE_KM * (float(_e38) + (float(_e40) / 4.0)));
                    float dt_7 = max(min(0.25, (_e9.x - t0_1)), 0.0);
                    float3 p_25 = (_e8 + (_e7 * (t0_1 + (0.5 * dt_7))));
                    float r_21 = length(p_25);
                    float mu_s_8 = dot((p_25 / (r_21).xxx), sun_10);
                    const float _e64 = air_bottom();
                    const AirSample _e66 = air_at((r_21 - _e64));
                    float3 _e67 = tau_1;
                    float3 t_view_2 = exp(-((_e67 + ((0.5 * _e66.extinction) * dt_7))));
                    const float3 _e75 = sun_transmittance(r_21, mu_s_8);
                    const float3 _e83 = multiscatter(r_21, mu_s_8);
                    float3 inscatter_1 = ((_e75 * ((_e66.rayleigh * _e15) + ((_e66.mie * _e20)).xxx)) + (_e83 * (_e66.rayleigh + (_e66.mie).xxx)));
                    float3 _e90 = radiance;
                    radiance = (_e90 + ((t_view_2 * inscatter_1) * dt_7));
                    float3 _e94 = tau_1;
                    tau_1 = (_e94 + (_e66.extinction * dt_7));
                }
            }
            float3 _e101 = tau_1;
            float3 t_11 = exp(-(_e101));
            uint _e105 = z;
            float3 _e112 = radiance;
            aerial_out[uint2(((_e105 * AERIAL_SIDE) + id_3.x), id_3.y)] = float4(_e112, (((t_11.x + t_11.y) + t_11.z) / 3.0));
        }
    }
    return;
}

[numthreads(8, 8, 1)]
void sky_ambient(uint3 id_4 : SV_DispatchThreadID)
{
    bool local_1 = (bool)0;
    float3 sum_1 = (0.0).xxx;
    float weights = 0.0;
    uint k_2 = (uint)0;

    if (!((id_4.x >= SKY_AMBIENT_SUNS))) {
        local_1 = (id_4.y >= 2u);
    } else {
        local_1 = true;
    }
    bool _e11 = local_1;
    if (_e11) {
        return;
    }
    bool top_3 = (id_4.y == 1u);
    float t_12 = (((float(id_4.x) / 63.0) * 2.0) - 1.0);
    float mu_s_9 = ((sign(t_12) * t_12) * t_12);
    float3 sun_11 = float3(sqrt(max((1.0 - (mu_s_9 * mu_s_9)), 0.0)), mu_s_9, 0.0);
    const float _e34 = air_bottom();
    float _e38 = frame.atmosphere.y;
    float3 origin_8 = float3(0.0, (_e34 + (_e38 * 0.001)), 0.0);
    uint first_1 = (top_3 ? 0u : 32u);
    k_2 = first_1;
    uint2 loop_bound_27 = uint2(4294967295u, 4294967295u);
    bool loop_init_23 = true;
    while(true) {
        if (all(loop_bound_27 == uint2(0u, 0u))) { break; }
        loop_bound_27 -= uint2(loop_bound_27.y == 0u, 1u);
        if (!loop_init_23) {
            uint _e77 = k_2;
            k_2 = (_e77 + 1u);
        }
        loop_init_23 = false;
        uint _e54 = k_2;
        if ((_e54 < (first_1 + 32u))) {
        } else {
            break;
        }
        {
            uint _e57 = k_2;
            const float3 _e59 = fibonacci_direction(_e57, AMBIENT_DIRECTIONS);
            const float2 _e60 = air_ray_end(origin_8, _e59);
            const Scattered _e63 = integrate_air(origin_8, _e59, _e60.x, AMBIENT_STEPS, sun_11);
            float w_8 = abs(_e59.y);
            float3 _e66 = sum_1;
            const float3 _e71 = with_ground(_e63, origin_8, _e59, _e60.x, sun_11, (_e60.y > 0.5));
            sum_1 = (_e66 + (w_8 * _e71));
            float _e74 = weights;
            weights = (_e74 + w_8);
        }
    }
    float3 _e81 = sum_1;
    float _e82 = weights;
    sky_ambient_out[id_4.xy] = float4((_e81 / (_e82).xxx), 1.0);
    return;
}

[numthreads(8, 8, 1)]
void ground_irradiance(uint3 id_5 : SV_DispatchThreadID)
{
    bool local_2 = (bool)0;
    float3 sum_2 = (0.0).xxx;
    uint k_3 = 0u;

    if (!((id_5.x >= GROUND_IRRADIANCE_SIZE))) {
        local_2 = (id_5.y >= 1u);
    } else {
        local_2 = true;
    }
    bool _e11 = local_2;
    if (_e11) {
        return;
    }
    float mu_s_10 = (((float(id_5.x) / 63.0) * 2.0) - 1.0);
    float3 sun_12 = float3(sqrt(max((1.0 - (mu_s_10 * mu_s_10)), 0.0)), mu_s_10, 0.0);
    const float _e28 = air_bottom();
    float3 origin_9 = float3(0.0, (_e28 + 0.001), 0.0);
    uint2 loop_bound_28 = uint2(4294967295u, 4294967295u);
    bool loop_init_24 = true;
    while(true) {
        if (all(loop_bound_28 == uint2(0u, 0u))) { break; }
        loop_bound_28 -= uint2(loop_bound_28.y == 0u, 1u);
        if (!loop_init_24) {
            uint _e58 = k_3;
            k_3 = (_e58 + 1u);
        }
        loop_init_24 = false;
        uint _e39 = k_3;
        if ((_e39 < GROUND_IRRADIANCE_DIRECTIONS)) {
        } else {
            break;
        }
        {
            uint _e42 = k_3;
            const float3 _e44 = fibonacci_direction(_e42, GROUND_IRRADIANCE_DIRECTIONS);
            if ((_e44.y <= 0.0)) {
                continue;
            }
            const float2 _e48 = air_ray_end(origin_9, _e44);
            float3 _e49 = sum_2;
            const Scattered _e52 = integrate_air(origin_9, _e44, _e48.x, AMBIENT_STEPS, sun_12);
            sum_2 = (_e49 + (_e52.radiance * _e44.y));
        }
    }
    float3 _e60 = sum_2;
    float3 e_3 = (_e60 * 0.09817477);
    ground_irradiance_out[id_5.xy] = float4(e_3, 1.0);
    return;
}

[numthreads(8, 8, 1)]
void cloud_shadow(uint3 id_6 : SV_DispatchThreadID)
{
    float tau_2 = 0.0;
    Counters counters = ConstructCounters(0u, 0u, 0u, 0u);
    uint i_2 = 0u;
    uint k_4 = (uint)0;

    if (any((id_6.xy >= (128u).xx))) {
        return;
    }
    const float3 _e7 = shadow_ground_point(id_6.xy);
    float4 _e10 = frame.sun_direction;
    float3 sun_13 = _e10.xyz;
    float rp_8 = frame.atmosphere.x;
    float3 up_2 = normalize(float3(_e7.x, (_e7.y + rp_8), _e7.z));
    if ((dot(up_2, sun_13) > 0.0)) {
        float4 _e29 = frame.camera_position;
        float2 cam_xz_3 = _e29.xz;
        uint2 loop_bound_29 = uint2(4294967295u, 4294967295u);
        bool loop_init_25 = true;
        while(true) {
            if (all(loop_bound_29 == uint2(0u, 0u))) { break; }
            loop_bound_29 -= uint2(loop_bound_29.y == 0u, 1u);
            if (!loop_init_25) {
                uint _e90 = i_2;
                i_2 = (_e90 + 1u);
            }
            loop_init_25 = false;
            uint _e39 = i_2;
            const uint _e40 = layer_count();
            if ((_e39 < _e40)) {
            } else {
                break;
            }
            {
                uint _e42 = i_2;
                const Layer _e43 = cloud_layer(_e42);
                const Roots _e46 = ray_shell_from(_e7, 0.0, sun_13, _e43.bottom);
                float start_2 = max(_e46.t1_, 0.0);
                const Roots _e52 = ray_shell_from(_e7, 0.0, sun_13, _e43.top);
                float end_2 = _e52.t1_;
                float dt_8 = ((end_2 - start_2) / 16.0);
                if (!((dt_8 > 0.0))) {
                    continue;
                }
                k_4 = 0u;
                uint2 loop_bound_30 = uint2(4294967295u, 4294967295u);
                bool loop_init_26 = true;
                while(true) {
                    if (all(loop_bound_30 == uint2(0u, 0u))) { break; }
                    loop_bound_30 -= uint2(loop_bound_30.y == 0u, 1u);
                    if (!loop_init_26) {
                        uint _e87 = k_4;
                        k_4 = (_e87 + 1u);
                    }
                    loop_init_26 = false;
                    uint _e62 = k_4;
                    if ((_e62 < SHADOW_STEPS)) {
                    } else {
                        break;
                    }
                    {
                        uint _e65 = k_4;
                        float3 q_12 = (_e7 + (sun_13 * (start_2 + ((float(_e65) + 0.5) * dt_8))));
                        float3 p_26 = float3((q_12.x + cam_xz_3.x), q_12.y, (q_12.z + cam_xz_3.y));
                        float _e81 = tau_2;
                        const float _e82 = altitude_of(q_12);
                        const float _e83 = layer_density(p_26, _e82, _e43, counters);
                        tau_2 = (_e81 + (_e83 * dt_8));
                    }
                }
            }
        }
    }
    float _e95 = frame.extinction.x;
    float _e99 = frame.extinction.y;
    float sigma_t_8 = (_e95 + _e99);
    float _e104 = tau_2;
    cloud_shadow_out[id_6.xy] = float4(exp((-(sigma_t_8) * _e104)), 0.0, 0.0, 1.0);
    return;
}

int2 naga_div(int2 lhs, int2 rhs) {
    return lhs / (((lhs == int(-2147483647 - 1) & rhs == -1) | (rhs == 0)) ? 1 : rhs);
}

int2 naga_mod(int2 lhs, int2 rhs) {
    int2 divisor = ((lhs == int(-2147483647 - 1) & rhs == -1) | (rhs == 0)) ? 1 : rhs;
    return lhs - (lhs / divisor) * divisor;
}

uint2 NagaDimensions2D(Texture2D<float4> tex)
{
    uint4 ret;
    tex.GetDimensions(0, ret.x, ret.y, ret.z);
    return ret.xy;
}

[numthreads(8, 8, 1)]
void occupancy(uint3 id_7 : SV_DispatchThreadID)
{
    float m = 0.0;
    int y = (int)0;
    int x = (int)0;

    if (any((id_7.xy >= (64u).xx))) {
        return;
    }
    int2 size_8 = int2(NagaDimensions2D(weather_tex));
    int2 lo_1 = asint(asuint(naga_div(asint(asuint(int2(id_7.xy)) * asuint(size_8)), (int(64)).xx)) - asuint((int(1)).xx));
    int2 hi = naga_div(asint(asuint(asint(asuint(int2(id_7.xy)) + asuint((int(1)).xx))) * asuint(size_8)), (int(64)).xx);
    y = lo_1.y;
    uint2 loop_bound_31 = uint2(4294967295u, 4294967295u);
    bool loop_init_27 = true;
    while(true) {
        if (all(loop_bound_31 == uint2(0u, 0u))) { break; }
        loop_bound_31 -= uint2(loop_bound_31.y == 0u, 1u);
        if (!loop_init_27) {
            int _e54 = y;
            y = asint(asuint(_e54) + asuint(int(1)));
        }
        loop_init_27 = false;
        int _e30 = y;
        if ((_e30 <= hi.y)) {
        } else {
            break;
        }
        {
            x = lo_1.x;
            uint2 loop_bound_32 = uint2(4294967295u, 4294967295u);
            bool loop_init_28 = true;
            while(true) {
                if (all(loop_bound_32 == uint2(0u, 0u))) { break; }
                loop_bound_32 -= uint2(loop_bound_32.y == 0u, 1u);
                if (!loop_init_28) {
                    int _e51 = x;
                    x = asint(asuint(_e51) + asuint(int(1)));
                }
                loop_init_28 = false;
                int _e35 = x;
                if ((_e35 <= hi.x)) {
                } else {
                    break;
                }
                {
                    int _e38 = x;
                    int _e39 = y;
                    int2 t_13 = naga_mod(asint(asuint(naga_mod(int2(_e38, _e39), size_8)) + asuint(size_8)), size_8);
                    float _e44 = m;
                    float4 _e47 = weather_tex.Load(int3(t_13, int(0)));
                    m = max(_e44, _e47.x);
                }
            }
        }
    }
    float _e58 = m;
    occupancy_out[id_7.xy] = float4(_e58, 0.0, 0.0, 0.0);
    return;
}

[numthreads(8, 8, 1)]
void march(uint3 id_8 : SV_DispatchThreadID)
{
    uint4 _e4 = frame.counts;
    if (any((id_8.xy >= _e4.xy))) {
        return;
    }
    const MarchResult _e9 = march_pixel(id_8.xy);
    cloud_out[id_8.xy] = float4(_e9.radiance, _e9.transmittance);
    depth_out[id_8.xy] = float4(_e9.depth, 0.0, 0.0, 0.0);
    return;
}

[numthreads(8, 8, 1)]
void march_sparse(uint3 id_9 : SV_DispatchThreadID)
{
    MarchResult r = ConstructMarchResult((0.0).xxx, 1.0, 0.0);

    const bool _e2 = in_blocks(id_9.xy);
    if (!(_e2)) {
        return;
    }
    const uint2 _e5 = sparse_pixel(id_9.xy);
    uint4 _e14 = frame.counts;
    if (all((_e5 < _e14.xy))) {
        const MarchResult _e18 = march_pixel(_e5);
        r = _e18;
    }
    MarchResult _e20 = r;
    store_sparse(id_9.xy, _e20);
    return;
}

[numthreads(8, 8, 1)]
void march_sparse_checkerboard(uint3 id_10 : SV_DispatchThreadID)
{
    MarchResult r_1 = ConstructMarchResult((0.0).xxx, 1.0, 0.0);
    bool skip = (bool)0;
    bool local_3 = (bool)0;
    bool local_4 = (bool)0;
    bool local_5 = (bool)0;

    const bool _e2 = in_blocks(id_10.xy);
    if (!(_e2)) {
        return;
    }
    const uint2 _e5 = sparse_pixel(id_10.xy);
    uint4 _e14 = frame.counts;
    skip = any((_e5 >= _e14.xy));
    bool _e19 = skip;
    if (!(_e19)) {
        uint _e26 = frame.temporal.y;
        local_3 = (_e26 != 0u);
    } else {
        local_3 = false;
    }
    bool _e30 = local_3;
    if (_e30) {
        uint k_20 = frame.temporal.x;
        uint _e38 = frame.misc.y;
        uint turn = naga_div(_e38, (k_20 * k_20));
        const float2 _e42 = reproject(_e5, 0.0);
        if (((((id_10.x + id_10.y) + turn) & 1u) == 0u)) {
            const bool _e53 = on_screen(_e42);
            local_4 = _e53;
        } else {
            local_4 = false;
        }
        bool _e55 = local_4;
        if (_e55) {
            const float4 _e58 = history_nearest(_e42);
            local_5 = (_e58.w >= 1.0);
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
        const MarchResult _e67 = march_pixel(_e5);
        r_1 = _e67;
    }
    MarchResult _e69 = r_1;
    store_sparse(id_10.xy, _e69);
    return;
}

[numthreads(8, 8, 1)]
void resolve(uint3 id_11 : SV_DispatchThreadID)
{
    float depth = (float)0;
    bool local_6 = (bool)0;
    bool valid = (bool)0;
    float4 history = float4(0.0, 0.0, 0.0, 1.0);
    float4 past = (0.0).xxxx;
    bool local_7 = (bool)0;
    bool local_8 = (bool)0;
    bool local_9 = (bool)0;
    float4 result = (float4)0;
    float samples = (float)0;
    float out_depth = (float)0;
    bool local_10 = (bool)0;

    uint4 _e4 = frame.counts;
    if (any((id_11.xy >= _e4.xy))) {
        return;
    }
    uint2 pixel_10 = id_11.xy;
    uint k_21 = frame.temporal.x;
    uint2 block = naga_div(pixel_10, (k_21).xx);
    uint _e19 = frame.misc.y;
    const uint2 _e20 = block_offset(_e19, k_21);
    bool marched_1 = all((pixel_10 == ((block * k_21) + _e20)));
    float4 current = sparse_in.Load(int3(block, int(0)));
    float4 _e29 = sparse_depth_in.Load(int3(block, int(0)));
    float current_depth = _e29.x;
    depth = current_depth;
    float _e32 = depth;
    if ((_e32 <= 0.0)) {
        float _e38 = frame.camera_position.y;
        const float3 _e39 = view_ray(pixel_10);
        const Interval _e40 = nearest_layer_interval(_e38, _e39);
        if ((_e40.kind == RAY_MARCH)) {
            depth = (_e40.start + (0.5 * _e40.length_));
        }
    }
    float _e49 = depth;
    const float2 _e50 = reproject(pixel_10, _e49);
    uint _e54 = frame.temporal.y;
    if ((_e54 != 0u)) {
        const bool _e59 = on_screen(_e50);
        local_6 = _e59;
    } else {
        local_6 = false;
    }
    bool _e61 = local_6;
    valid = _e61;
    bool moving = any((_e50 != float2(pixel_10)));
    bool _e75 = valid;
    if (_e75) {
        const float4 _e76 = history_at(_e50);
        history = _e76;
        const float4 _e77 = meta_at(_e50);
        past = _e77;
        if (moving) {
            local_7 = (current_depth > 0.0);
        } else {
            local_7 = false;
        }
        bool _e83 = local_7;
        if (_e83) {
            float _e87 = past.x;
            local_8 = (_e87 > 0.0);
        } else {
            local_8 = false;
        }
        bool _e91 = local_8;
        if (_e91) {
            float4 _e94 = frame.camera_position;
            const float3 _e96 = view_ray(pixel_10);
            float4 _e101 = frame.previous_position;
            float expected = distance((_e94.xyz + (_e96 * current_depth)), _e101.xyz);
            float _e105 = past.x;
            valid = (abs((_e105 - expected)) <= (DISOCCLUSION_DEPTH * expected));
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
        uint4 _e118 = frame.counts;
        int2 blocks = int2(naga_div(((_e118.xy + (k_21).xx) - (1u).xx), (k_21).xx));
        int2 b_11 = int2(block);
        int x0_1 = max(asint(asuint(b_11.x) - asuint(int(1))), int(0));
        int x2_2 = min(asint(asuint(b_11.x) + asuint(int(1))), asint(asuint(blocks.x) - asuint(int(1))));
        int y0_ = max(asint(asuint(b_11.y) - asuint(int(1))), int(0));
        int y2_ = min(asint(asuint(b_11.y) + asuint(int(1))), asint(asuint(blocks.y) - asuint(int(1))));
        float4 s00_ = sparse_in.Load(int3(int2(x0_1, y0_), int(0)));
        float4 s10_ = sparse_in.Load(int3(int2(b_11.x, y0_), int(0)));
        float4 s20_ = sparse_in.Load(int3(int2(x2_2, y0_), int(0)));
        float4 s01_ = sparse_in.Load(int3(int2(x0_1, b_11.y), int(0)));
        float4 s11_ = sparse_in.Load(int3(b_11, int(0)));
        float4 s21_ = sparse_in.Load(int3(int2(x2_2, b_11.y), int(0)));
        float4 s02_ = sparse_in.Load(int3(int2(x0_1, y2_), int(0)));
        float4 s12_ = sparse_in.Load(int3(int2(b_11.x, y2_), int(0)));
        float4 s22_ = sparse_in.Load(int3(int2(x2_2, y2_), int(0)));
        float4 lo_2 = min(min(min(s00_, s10_), min(s20_, s01_)), min(min(s11_, s21_), min(min(s02_, s12_), s22_)));
        float4 hi_1 = max(max(max(s00_, s10_), max(s20_, s01_)), max(max(s11_, s21_), max(max(s02_, s12_), s22_)));
        float4 _e208 = history;
        history = clamp(_e208, lo_2, hi_1);
    }
    if (marched_1) {
        bool _e213 = valid;
        if (_e213) {
            float _e215 = past.y;
            samples = min((_e215 + 1.0), (moving ? HISTORY_SAMPLES_MOVING : HISTORY_SAMPLES));
            float4 _e222 = history;
            float _e223 = samples;
            result = lerp(_e222, current, (1.0 / _e223));
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
        out_depth = (_e238 ? current_depth : _e229);
    } else {
        bool _e240 = valid;
        if (_e240) {
            float _e242 = past.y;
            samples = (moving ? 0.0 : _e242);
            float4 _e245 = history;
            result = _e245;
            float _e247 = past.x;
            out_depth = _e247;
        } else {
            const MarchResult _e248 = march_pixel(pixel_10);
            samples = 1.0;
            result = float4(_e248.radiance, _e248.transmittance);
            out_depth = _e248.depth;
        }
    }
    float4 _e255 = result;
    history_out[pixel_10] = _e255;
    float _e257 = out_depth;
    float _e258 = samples;
    meta_out[pixel_10] = float4(_e257, _e258, 0.0, 0.0);
    float4 _e263 = result;
    cloud_out[pixel_10] = _e263;
    float _e265 = out_depth;
    depth_out[pixel_10] = float4(_e265, 0.0, 0.0, 0.0);
    return;
}

[numthreads(32, 1, 1)]
void pathtrace(uint3 group : SV_GroupID, uint lane : SV_GroupIndex)
{
    Counters counters_1 = ConstructCounters(0u, 0u, 0u, 0u);
    uint rng = (uint)0;
    float4 sum_3 = (0.0).xxxx;
    float4 sum_moments = (0.0).xxxx;
    uint i_3 = 0u;
    float4 mean = (0.0).xxxx;
    float4 moments = (0.0).xxxx;
    bool local_11 = (bool)0;

    uint4 _e5 = frame.counts;
    if (any((group.xy >= _e5.xy))) {
        return;
    }
    uint2 pixel_11 = group.xy;
    const float3 _e10 = view_ray(pixel_11);
    float _e14 = frame.camera_position.y;
    const Interval _e15 = cloud_interval(_e14, _e10);
    if ((lane == 0u)) {
        count(STAT_PIXELS, 1u);
        count(STAT_MARCHED, uint((_e15.kind == RAY_MARCH)));
        count(STAT_EXIT_MISSED, uint((_e15.kind == RAY_MISSES_LAYER)));
        count(STAT_EXIT_GROUND, uint((_e15.kind == RAY_HITS_GROUND)));
    }
    uint _e44 = frame.misc.y;
    const uint _e48 = rng_seed(pixel_11, ((_e44 * PATHS_PER_FRAME) + lane));
    rng = _e48;
    const PathResult _e50 = trace_path(_e10, _e15, rng, counters_1);
    const float _e52 = luminance(_e50.radiance);
    bool hit = (_e50.depth >= 0.0);
    lane_sums[min(uint(lane), 31u)] = float4(_e50.radiance, _e50.transmittance);
    lane_moments[min(uint(lane), 31u)] = float4((_e52 * _e52), (hit ? _e50.depth : 0.0), (hit ? 1.0 : 0.0), 0.0);
    GroupMemoryBarrierWithGroupSync();
    if ((lane == 0u)) {
        uint2 loop_bound_33 = uint2(4294967295u, 4294967295u);
        bool loop_init_29 = true;
        while(true) {
            if (all(loop_bound_33 == uint2(0u, 0u))) { break; }
            loop_bound_33 -= uint2(loop_bound_33.y == 0u, 1u);
            if (!loop_init_29) {
                uint _e98 = i_3;
                i_3 = (_e98 + 1u);
            }
            loop_init_29 = false;
            uint _e82 = i_3;
            if ((_e82 < PATHS_PER_FRAME)) {
            } else {
                break;
            }
            {
                float4 _e85 = sum_3;
                uint _e87 = i_3;
                float4 _e89 = lane_sums[min(uint(_e87), 31u)];
                sum_3 = (_e85 + _e89);
                float4 _e91 = sum_moments;
                uint _e93 = i_3;
                float4 _e95 = lane_moments[min(uint(_e93), 31u)];
                sum_moments = (_e91 + _e95);
            }
        }
        uint _e109 = frame.temporal.y;
        if ((_e109 == 1u)) {
            const bool _e114 = camera_still();
            local_11 = _e114;
        } else {
            local_11 = false;
        }
        bool _e116 = local_11;
        if (_e116) {
            float4 _e119 = history_in.Load(int3(pixel_11, int(0)));
            mean = _e119;
            float4 _e122 = meta_in.Load(int3(pixel_11, int(0)));
            moments = _e122;
        }
        float _e125 = moments.y;
        float n_4 = (_e125 + 32.0);
        float4 _e127 = mean;
        float4 _e128 = sum_3;
        float4 _e129 = mean;
        mean = (_e127 + ((_e128 - (32.0 * _e129)) / (n_4).xxxx));
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
        float4 _e166 = mean;
        history_out[pixel_11] = _e166;
        float4 _e168 = moments;
        meta_out[pixel_11] = _e168;
        float4 _e170 = mean;
        cloud_out[pixel_11] = _e170;
        float _e173 = moments.x;
        depth_out[pixel_11] = float4(_e173, 0.0, 0.0, 0.0);
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

[numthreads(8, 8, 1)]
void march_basic(uint3 id_12 : SV_DispatchThreadID)
{
    uint4 _e4 = frame.counts;
    if (any((id_12.xy >= _e4.xy))) {
        return;
    }
    const MarchResult _e9 = basic_pixel(id_12.xy);
    cloud_out[id_12.xy] = float4(_e9.radiance, _e9.transmittance);
    depth_out[id_12.xy] = float4(_e9.depth, 0.0, 0.0, 0.0);
    return;
}

uint2 naga_mod(uint2 lhs, uint2 rhs) {
    return lhs % (rhs == 0u ? 1u : rhs);
}

[numthreads(8, 8, 1)]
void sprite_atlas(uint3 id_13 : SV_DispatchThreadID)
{
    uint tile_4 = ((naga_div(id_13.y, ATLAS_TILE) * 4u) + naga_div(id_13.x, ATLAS_TILE));
    float2 uv_7 = ((float2(naga_mod(id_13.xy, (64u).xx)) + (0.5).xx) / (64.0).xx);
    const float _e21 = sprite_texture(tile_4, uv_7);
    sprite_atlas_out[id_13.xy] = float4(_e21, _e21, _e21, _e21);
    return;
}

[numthreads(64, 1, 1)]
void sprite_build(uint3 id_14 : SV_DispatchThreadID)
{
    Counters counters_2 = ConstructCounters(0u, 0u, 0u, 0u);
    float4 sum_4 = (0.0).xxxx;
    SpriteCandidate me = (SpriteCandidate)0;
    uint i_4 = 0u;
    float3 centre = (float3)0;
    uint tile = (uint)0;
    float rotation = (float)0;
    bool local_12 = (bool)0;
    float key = 0.0;

    uint slot = id_14.x;
    uint cell_index = naga_div(slot, SPRITES_PER_CELL);
    uint level_2 = naga_div(cell_index, 64u);
    const SpriteCell _e6 = sprite_cell(cell_index);
    uint own = naga_mod(slot, SPRITES_PER_CELL);
    const SpriteCandidate _e18 = sprite_candidate(_e6, level_2, own, counters_2);
    me = _e18;
    uint2 loop_bound_34 = uint2(4294967295u, 4294967295u);
    bool loop_init_30 = true;
    while(true) {
        if (all(loop_bound_34 == uint2(0u, 0u))) { break; }
        loop_bound_34 -= uint2(loop_bound_34.y == 0u, 1u);
        if (!loop_init_30) {
            uint _e38 = i_4;
            i_4 = (_e38 + 1u);
        }
        loop_init_30 = false;
        uint _e22 = i_4;
        if ((_e22 < SPRITES_PER_CELL)) {
        } else {
            break;
        }
        {
            uint _e25 = i_4;
            const SpriteCandidate _e26 = sprite_candidate(_e6, level_2, _e25, counters_2);
            float4 _e27 = sum_4;
            sum_4 = (_e27 + (float4(_e26.xz.x, _e26.alt, _e26.xz.y, 1.0) * _e26.density));
        }
    }
    uint _e43 = counters_2.density;
    count(STAT_DENSITY, _e43);
    uint _e46 = counters_2.detail;
    count(STAT_DETAIL, _e46);
    float bottom_3 = frame.atmosphere.y;
    float _e54 = frame.atmosphere.z;
    float thickness_1 = (_e54 - bottom_3);
    float2 middle = ((float2(_e6.index) + (0.5).xx) * _e6.size);
    centre = float3(middle.x, (bottom_3 + (0.4 * thickness_1)), middle.y);
    float _e71 = sum_4.w;
    if ((_e71 > 0.0)) {
        float4 _e74 = sum_4;
        float _e77 = sum_4.w;
        centre = (_e74.xyz / (_e77).xxx);
    }
    float2 _e81 = me.xz;
    float3 _e82 = centre;
    bool inner = (length((_e81 - _e82.xz)) < (0.25 * _e6.size));
    float _e91 = me.density;
    float _e96 = me.density;
    float morph = (inner ? smoothstep(0.0, 0.06, _e96) : smoothstep(0.03, 0.15, _e91));
    float alpha = (SPRITE_ALPHA * morph);
    float _e107 = me.size_hash;
    float half_width = ((0.5 * _e6.size) * (0.7 + (0.6 * _e107)));
    float half_height = min(half_width, (0.35 * thickness_1));
    float _e118 = me.texture_hash;
    tile = (5u + min(naga_f2u32((_e118 * 11.0)), 10u));
    float _e127 = me.rotation_hash;
    rotation = ((_e127 * 2.0) * PI);
    float _e134 = me.h;
    if ((_e134 < 0.12)) {
        tile = 4u;
        float _e139 = me.rotation_hash;
        rotation = ((_e139 - 0.5) * 0.17453294);
    } else {
        if (!(inner)) {
            float _e148 = me.density;
            local_12 = (_e148 < 0.1);
        } else {
            local_12 = false;
        }
        bool _e152 = local_12;
        if (_e152) {
            float _e154 = me.texture_hash;
            tile = min(naga_f2u32((_e154 * 4.0)), 3u);
        }
    }
    if ((alpha > 0.0)) {
        float2 _e165 = me.xz;
        float _e167 = me.alt;
        const float3 _e168 = sprite_rel(_e165, _e167);
        float _e172 = frame.camera_position.y;
        float3 rel_15 = (_e168 - float3(0.0, _e172, 0.0));
        const float _e180 = saturate_((length(rel_15) / SPRITE_MAX_DISTANCE));
        key = (1048576.0 - floor((_e180 * 1048575.0)));
    }
    float _e191 = me.xz.x;
    float _e193 = me.alt;
    float _e196 = me.xz.y;
    sprites_out[uint2(slot, 0u)] = float4(_e191, _e193, _e196, half_width);
    float3 _e201 = centre;
    sprites_out[uint2(slot, 1u)] = float4(_e201, alpha);
    float _e204 = me.precipitation;
    float colour_level = (1.0 / (1.0 + (6.0 * max(_e204, 0.0))));
    uint _e216 = tile;
    float _e218 = rotation;
    sprites_out[uint2(slot, 2u)] = float4(float(_e216), _e218, half_height, colour_level);
    float _e223 = key;
    sprites_out[uint2(slot, 3u)] = float4(_e223, 0.0, 0.0, 0.0);
    return;
}

[numthreads(64, 1, 1)]
void sprite_sort(uint3 id_15 : SV_DispatchThreadID)
{
    uint rank = 0u;
    uint j = 0u;
    bool local_13 = (bool)0;
    bool local_14 = (bool)0;

    uint slot_1 = id_15.x;
    float4 _e6 = sprites_in.Load(int3(uint2(slot_1, 3u), int(0)));
    float key_1 = _e6.x;
    uint2 loop_bound_35 = uint2(4294967295u, 4294967295u);
    bool loop_init_31 = true;
    while(true) {
        if (all(loop_bound_35 == uint2(0u, 0u))) { break; }
        loop_bound_35 -= uint2(loop_bound_35.y == 0u, 1u);
        if (!loop_init_31) {
            uint _e40 = j;
            j = (_e40 + 1u);
        }
        loop_init_31 = false;
        uint _e12 = j;
        if ((_e12 < SPRITE_COUNT)) {
        } else {
            break;
        }
        {
            uint _e16 = j;
            float4 _e20 = sprites_in.Load(int3(uint2(_e16, 3u), int(0)));
            float other = _e20.x;
            uint _e22 = rank;
            if (!((other < key_1))) {
                if ((other == key_1)) {
                    uint _e32 = j;
                    local_14 = (_e32 < slot_1);
                } else {
                    local_14 = false;
                }
                bool _e35 = local_14;
                local_13 = _e35;
            } else {
                local_13 = true;
            }
            bool _e37 = local_13;
            rank = (_e22 + (_e37 ? 1u : 0u));
        }
    }
    uint _e44 = rank;
    sprite_order_out[uint2(_e44, 0u)] = float4(float(slot_1), 0.0, 0.0, 0.0);
    return;
}

VertexOutput_sprite_vertex sprite_vertex(uint index : SV_VertexID)
{
    SpriteVertex out_ = (SpriteVertex)0;
    float3 right = (float3)0;

    float4 _e8 = sprite_order_in.Load(int3(uint2(naga_div(index, 6u), 0u), int(0)));
    uint slot_2 = naga_f2u32(_e8.x);
    float4 a_11 = sprites_in.Load(int3(uint2(slot_2, 0u), int(0)));
    float4 b_12 = sprites_in.Load(int3(uint2(slot_2, 1u), int(0)));
    float4 c_12 = sprites_in.Load(int3(uint2(slot_2, 2u), int(0)));
    if ((b_12.w <= 0.0)) {
        out_.position = float4(0.0, 0.0, -1.0, 1.0);
        SpriteVertex _e35 = out_;
        const SpriteVertex spritevertex = _e35;
        const VertexOutput_sprite_vertex spritevertex_1 = { spritevertex.uv, spritevertex.tile, spritevertex.colour, spritevertex.distance_, spritevertex.position };
        return spritevertex_1;
    }
    float _e39 = frame.camera_position.y;
    float3 cam_1 = float3(0.0, _e39, 0.0);
    const float3 _e45 = sprite_rel(a_11.xz, a_11.y);
    float3 to_sprite = (_e45 - cam_1);
    float distance_2 = length(to_sprite);
    float half_width_1 = a_11.w;
    float facing = smoothstep((0.5 * half_width_1), half_width_1, distance_2);
    float3 to_camera = (-(to_sprite) / (max(distance_2, 0.001)).xxx);
    float4 _e59 = frame.camera_forward;
    float3 n_5 = normalize(lerp(-(_e59.xyz), to_camera, facing));
    float _e67 = frame.atmosphere.x;
    float3 radial = normalize((_e45 + float3(0.0, _e67, 0.0)));
    right = cross(radial, n_5);
    float3 _e75 = right;
    if ((length(_e75) < 0.001)) {
        float4 _e81 = frame.camera_right;
        right = _e81.xyz;
    }
    float3 _e83 = right;
    right = normalize(_e83);
    float3 _e85 = right;
    float3 up_3 = cross(n_5, _e85);
    const float2 _e89 = sprite_corner(naga_mod(index, 6u));
    float3 _e90 = right;
    float3 offset_1 = ((_e90 * (_e89.x * half_width_1)) + (up_3 * (_e89.y * c_12.z)));
    float3 vertex = (to_sprite + offset_1);
    float4 _e102 = frame.camera_right;
    float x_14 = dot(vertex, _e102.xyz);
    float4 _e107 = frame.camera_up;
    float y_4 = dot(vertex, _e107.xyz);
    float4 _e112 = frame.camera_forward;
    float z_4 = dot(vertex, _e112.xyz);
    float tan_half_3 = frame.camera_position.w;
    float _e123 = frame.camera_forward.w;
    out_.position = float4((x_14 / (tan_half_3 * _e123)), (y_4 / tan_half_3), (0.5 * z_4), z_4);
    float2 cs = float2(cos(c_12.y), sin(c_12.y));
    float2 t_14 = float2(_e89.x, -(_e89.y));
    out_.uv = float2(((t_14.x * cs.x) - (t_14.y * cs.y)), ((t_14.x * cs.y) + (t_14.y * cs.x)));
    out_.tile = naga_f2u32(c_12.x);
    float4 _e160 = frame.sun_direction;
    float3 sun_14 = _e160.xyz;
    const float3 _e164 = sprite_rel(b_12.xz, b_12.y);
    float3 centre_2 = (_e164 - cam_1);
    float3 from_centre = (vertex - centre_2);
    float cos_angle_1 = (dot(from_centre, sun_14) / max(length(from_centre), 0.001));
    const float _e177 = saturate_(((sun_14.y * 4.0) + 0.3));
    const float _e179 = altitude_of((vertex + cam_1));
    float _e183 = frame.atmosphere.y;
    float _e188 = frame.atmosphere.z;
    float _e192 = frame.atmosphere.y;
    const float _e195 = saturate_(((_e179 - _e183) / (_e188 - _e192)));
    float4 _e198 = frame.sun_illuminance;
    float3 e_4 = _e198.xyz;
    const float3 _e200 = sprite_sky_level(_e195);
    const float _e204 = sprite_sun_level(cos_angle_1);
    float3 light = ((e_4 * ((_e200 * (SPRITE_SKY * _e177)) + (_e204).xxx)) * (c_12.w / PI));
    out_.colour = float4(light, b_12.w);
    out_.distance_ = length(vertex);
    SpriteVertex _e217 = out_;
    const SpriteVertex spritevertex_2 = _e217;
    const VertexOutput_sprite_vertex spritevertex_2_ = { spritevertex_2.uv, spritevertex_2.tile, spritevertex_2.colour, spritevertex_2.distance_, spritevertex_2.position };
    return spritevertex_2_;
}

SpriteTargets sprite_fragment(FragmentInput_sprite_fragment fragmentinput_sprite_fragment)
{
    SpriteVertex in_ = { fragmentinput_sprite_fragment.position_1, fragmentinput_sprite_fragment.uv_3, fragmentinput_sprite_fragment.tile_3, fragmentinput_sprite_fragment.colour_1, fragmentinput_sprite_fragment.distance_1 };
    SpriteTargets out_1 = (SpriteTargets)0;
    float a = 0.0;

    if (all((abs(in_.uv) <= (1.0).xx))) {
        float2 tile_5 = float2(float(naga_mod(in_.tile, 4u)), float(naga_div(in_.tile, 4u)));
        float2 uv_8 = (((tile_5 + (0.5).xx) + (0.5 * in_.uv)) * 0.25);
        float4 _e31 = sprite_atlas_in.SampleLevel(noise_sampler, uv_8, 0.0);
        a = (_e31.x * in_.colour.w);
    }
    float _e39 = a;
    float _e41 = a;
    out_1.radiance = float4((in_.colour.xyz * _e39), _e41);
    float _e45 = a;
    float _e47 = a;
    out_1.depth = float4((in_.distance_ * _e45), 0.0, 0.0, _e47);
    SpriteTargets _e51 = out_1;
    const SpriteTargets spritetargets = _e51;
    return spritetargets;
}

[numthreads(8, 8, 1)]
void sprite_resolve(uint3 id_16 : SV_DispatchThreadID)
{
    uint4 _e4 = frame.counts;
    if (any((id_16.xy >= _e4.xy))) {
        return;
    }
    count(STAT_PIXELS, 1u);
    float4 c_13 = sprite_radiance_in.Load(int3(id_16.xy, int(0)));
    float4 d_26 = sprite_depth_in.Load(int3(id_16.xy, int(0)));
    const float _e19 = saturate_(c_13.w);
    cloud_out[id_16.xy] = float4(c_13.xyz, (1.0 - _e19));
    depth_out[id_16.xy] = float4(((d_26.w > 0.0001) ? (d_26.x / d_26.w) : 0.0), 0.0, 0.0, 0.0);
    return;
}

[numthreads(8, 8, 1)]
void composite(uint3 id_17 : SV_DispatchThreadID)
{
    float3 background = (float3)0;

    uint4 _e4 = frame.counts;
    if (any((id_17.xy >= _e4.xy))) {
        return;
    }
    uint2 pixel_12 = id_17.xy;
    const float3 _e9 = view_ray(pixel_12);
    float alt_19 = frame.camera_position.y;
    float4 cloud_1 = cloud_in.Load(int3(pixel_12, int(0)));
    const float3 _e17 = sky_radiance(_e9, alt_19);
    background = _e17;
    const bool _e22 = hits_ground(float3(0.0, alt_19, 0.0), alt_19, _e9);
    if (!(_e22)) {
        float3 _e24 = background;
        const float3 _e25 = sun_disk(_e9);
        background = (_e24 + _e25);
    }
    float3 _e27 = background;
    store_display(pixel_12, ((_e27 * cloud_1.w) + cloud_1.xyz));
    return;
}

[numthreads(8, 8, 1)]
void composite_physical(uint3 id_18 : SV_DispatchThreadID)
{
    uint4 _e4 = frame.counts;
    if (any((id_18.xy >= _e4.xy))) {
        return;
    }
    uint2 pixel_13 = id_18.xy;
    float4 cloud_2 = cloud_in.Load(int3(pixel_13, int(0)));
    const float3 _e12 = view_ray(pixel_13);
    const float3 _e13 = physical_composite(pixel_13, _e12, cloud_2);
    store_display(pixel_13, _e13);
    return;
}
