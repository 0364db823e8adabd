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
static const float PI = 3.1415927;
static const uint MAX_VIEW_STEPS = 1024u;
static const uint RAY_MARCH = 0u;
static const uint RAY_MISSES_LAYER = 1u;
static const uint RAY_HITS_GROUND = 2u;
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
static const bool LIGHT_MARCH = false;
static const uint MAX_OCTAVES = 0u;
static const bool DETAIL = false;
static const bool CURL = false;
static const bool STATS = true;

cbuffer frame : register(b0) { Frame frame; }
Texture3D<float4> shape_tex : register(t1);
Texture3D<float4> detail_tex : register(t2);
Texture2D<float4> weather_tex : register(t3);
Texture2D<float4> curl_tex : register(t4);
SamplerState nagaSamplerHeap[2048]: register(s32, space0);
SamplerComparisonState nagaComparisonSamplerHeap[2048]: register(s33, space0);
StructuredBuffer<uint> nagaGroup0SamplerIndexArray : register(t34, space0);
static const SamplerState noise_sampler = nagaSamplerHeap[nagaGroup0SamplerIndexArray[5]];
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
Texture2D<float4> cloud_in : register(t9);
RWTexture2D<unorm float4> image_out : register(u10);

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
    uint state = ((v * 747796405u) + 2891336453u);
    uint word = (((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u);
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
    float2 size = float2(_e3.xy);
    float2 ndc = ((((float2(pixel_1) + (0.5).xx) / size) * 2.0) - (1.0).xx);
    float tan_half = frame.camera_position.w;
    float aspect = frame.camera_forward.w;
    float4 _e26 = frame.camera_forward;
    float4 _e30 = frame.camera_right;
    float4 _e39 = frame.camera_up;
    float3 d_6 = ((_e26.xyz + (_e30.xyz * ((ndc.x * tan_half) * aspect))) - (_e39.xyz * (ndc.y * tan_half)));
    return normalize(d_6);
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
    float s = sqrt(disc);
    float r0_1 = -((b + ((b >= 0.0) ? s : -(s))));
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
    float b_1 = (d.y * (alt + rp));
    float c_1 = ((alt - radius_alt) * ((alt + radius_alt) + (2.0 * rp)));
    const Roots _e16 = solve_sphere(b_1, c_1);
    const Roots roots_3 = _e16;
    return roots_3;
}

float altitude_of(float3 p)
{
    float rp_1 = frame.atmosphere.x;
    float n_1 = (((p.x * p.x) + (p.z * p.z)) + (p.y * (p.y + (2.0 * rp_1))));
    float3 q_4 = float3(p.x, (p.y + rp_1), p.z);
    return (n_1 / (length(q_4) + rp_1));
}

bool hits_ground(float3 p_1, float alt_1, float3 d_1)
{
    bool local_8 = (bool)0;

    float rp_2 = frame.atmosphere.x;
    float b_2 = dot(d_1, float3(p_1.x, (p_1.y + rp_2), p_1.z));
    float c_2 = (alt_1 * (alt_1 + (2.0 * rp_2)));
    if ((b_2 < 0.0)) {
        local_8 = ((b_2 * b_2) >= c_2);
    } else {
        local_8 = false;
    }
    bool _e24 = local_8;
    return _e24;
}

Interval ConstructInterval(float arg0, float arg1, uint arg2) {
    Interval ret = (Interval)0;
    ret.start = arg0;
    ret.length_ = arg1;
    ret.kind = arg2;
    return ret;
}

Interval layer_interval(float alt_2, float3 d_2)
{
    float start = 0.0;
    float end = 0.0;
    bool local_9 = (bool)0;
    bool local_10 = (bool)0;
    bool local_11 = (bool)0;

    float bottom = frame.atmosphere.y;
    float top = frame.atmosphere.z;
    float cutoff = frame.atmosphere.w;
    const Roots _e14 = ray_shell(alt_2, d_2, bottom);
    const Roots _e15 = ray_shell(alt_2, d_2, top);
    if ((alt_2 < bottom)) {
        const bool _e24 = hits_ground(float3(0.0, alt_2, 0.0), alt_2, d_2);
        if (_e24) {
            const Interval interval = ConstructInterval(0.0, 0.0, 2u);
            return interval;
        }
        start = _e14.t1_;
        end = _e15.t1_;
    } else {
        if ((alt_2 <= top)) {
            end = _e15.t1_;
            if (_e14.hit) {
                local_9 = (_e14.t0_ > 0.0);
            } else {
                local_9 = false;
            }
            bool _e40 = local_9;
            if (_e40) {
                float _e41 = end;
                end = min(_e41, _e14.t0_);
            }
        } else {
            if (!(!(_e15.hit))) {
                local_10 = (_e15.t1_ <= 0.0);
            } else {
                local_10 = true;
            }
            bool _e53 = local_10;
            if (_e53) {
                const Interval interval_1 = ConstructInterval(0.0, 0.0, 1u);
                return interval_1;
            }
            start = max(_e15.t0_, 0.0);
            end = _e15.t1_;
            if (_e14.hit) {
                local_11 = (_e14.t0_ > 0.0);
            } else {
                local_11 = false;
            }
            bool _e69 = local_11;
            if (_e69) {
                float _e70 = end;
                end = min(_e70, _e14.t0_);
            }
        }
    }
    float _e73 = end;
    float _e74 = start;
    float len = min((_e73 - _e74), cutoff);
    if (!((len > 0.0))) {
        const Interval interval_2 = ConstructInterval(0.0, 0.0, 1u);
        return interval_2;
    }
    float _e84 = start;
    const Interval interval_3 = ConstructInterval(_e84, len, RAY_MARCH);
    return interval_3;
}

Weather ConstructWeather(float arg0, float arg1, float arg2) {
    Weather ret = (Weather)0;
    ret.coverage = arg0;
    ret.cloud_type = arg1;
    ret.precipitation = arg2;
    return ret;
}

Weather sample_weather(float3 p_2)
{
    float4 _e4 = frame.wind_offsets0_;
    float _e10 = frame.periods.x;
    float2 uv = ((p_2.xz - _e4.xy) / (_e10).xx);
    float4 w = weather_tex.SampleLevel(noise_sampler, uv, 0.0);
    float _e21 = frame.clouds.x;
    const float _e27 = saturate_((w.x + (2.0 * (_e21 - 0.5))));
    float _e31 = frame.clouds.z;
    const float _e38 = saturate_((_e31 + ((w.z - 0.5) * 0.5)));
    float _e42 = frame.clouds.w;
    const float _e46 = saturate_((0.5 + w.y));
    float precipitation = (_e42 * _e46);
    const Weather weather = ConstructWeather(_e27, _e38, precipitation);
    return weather;
}

float height_parabola(float h, float cloud_type)
{
    float height = lerp(0.35, 1.0, cloud_type);
    const float _e11 = saturate_(((h * (h - height)) * (-4.0 / (height * height))));
    return _e11;
}

float gradient(float h_1, float r0_, float r1_, float f0_, float f1_)
{
    return (smoothstep(r0_, r1_, h_1) * (1.0 - smoothstep(f0_, f1_, h_1)));
}

float height_cloud_types(float h_2, float cloud_type_1)
{
    const float _e6 = gradient(h_2, 0.0, 0.08, 0.15, 0.25);
    const float _e11 = gradient(h_2, 0.0, 0.2, 0.4, 0.65);
    const float _e16 = gradient(h_2, 0.0, 0.1, 0.6, 0.95);
    const float _e19 = saturate_((cloud_type_1 * 2.0));
    float lo = lerp(_e6, _e11, _e19);
    const float _e25 = saturate_(((cloud_type_1 * 2.0) - 1.0));
    return lerp(lo, _e16, _e25);
}

float height_signal(float h_3, float cloud_type_2)
{
    uint _e5 = frame.modes.z;
    if ((_e5 == HEIGHT_CLOUD_TYPES)) {
        const float _e8 = height_cloud_types(h_3, cloud_type_2);
        return _e8;
    }
    const float _e9 = height_parabola(h_3, cloud_type_2);
    return _e9;
}

uint3 NagaDimensions3D(Texture3D<float4> tex)
{
    uint4 ret;
    tex.GetDimensions(0, ret.x, ret.y, ret.z, ret.w);
    return ret.xyz;
}

float cloud_density(float3 p_3, float alt_3, inout Counters counters)
{
    bool local_12 = (bool)0;
    bool local_13 = (bool)0;
    float base = (float)0;
    float density = (float)0;
    bool local_14 = (bool)0;
    bool local_15 = (bool)0;
    float3 detail_pos = (float3)0;

    float bottom_1 = frame.atmosphere.y;
    float top_1 = frame.atmosphere.z;
    float h_5 = ((alt_3 - bottom_1) / (top_1 - bottom_1));
    if (!((h_5 < 0.0))) {
        local_12 = (h_5 > 1.0);
    } else {
        local_12 = true;
    }
    bool _e22 = local_12;
    if (_e22) {
        return 0.0;
    }
    uint _e25 = counters.density;
    counters.density = (_e25 + 1u);
    const Weather _e28 = sample_weather(p_3);
    const float _e30 = height_signal(h_5, _e28.cloud_type);
    if (!((_e28.coverage <= 0.0))) {
        local_13 = (_e30 <= 0.0);
    } else {
        local_13 = true;
    }
    bool _e40 = local_13;
    if (_e40) {
        return 0.0;
    }
    float3 dims = float3(NagaDimensions3D(shape_tex));
    float _e48 = frame.periods.y;
    float3 period = (_e48 * float3(1.0, (dims.y / dims.x), 1.0));
    float _e60 = frame.wind_offsets0_.z;
    float _e66 = frame.wind_offsets0_.w;
    float3 shape_pos = float3((p_3.x - _e60), alt_3, (p_3.z - _e66));
    float4 s_1 = shape_tex.SampleLevel(noise_sampler, (shape_pos / period), 0.0);
    float low_fbm = (((s_1.y * 0.625) + (s_1.z * 0.25)) + (s_1.w * 0.125));
    const float _e91 = remap(s_1.x, (low_fbm - 1.0), 1.0, 0.0, 1.0);
    const float _e92 = saturate_(_e91);
    base = (_e92 * _e30);
    float _e95 = base;
    const float _e102 = remap(_e95, (1.0 - _e28.coverage), 1.0, 0.0, 1.0);
    const float _e103 = saturate_(_e102);
    base = (_e103 * _e28.coverage);
    float _e106 = base;
    if ((_e106 <= 0.0)) {
        return 0.0;
    }
    float _e110 = base;
    density = _e110;
    float strength = frame.erosion.x;
    float threshold = frame.erosion.y;
    if (DETAIL) {
        local_14 = (strength > 0.0);
    } else {
        local_14 = false;
    }
    bool _e126 = local_14;
    if (_e126) {
        float _e129 = base;
        local_15 = (_e129 < threshold);
    } else {
        local_15 = false;
    }
    bool _e132 = local_15;
    if (_e132) {
        uint _e134 = counters.detail;
        counters.detail = (_e134 + 1u);
        detail_pos = float3(p_3.x, alt_3, p_3.z);
        if (CURL) {
            float4 _e145 = frame.wind_offsets1_;
            float _e151 = frame.periods.w;
            float2 cuv = ((p_3.xz - _e145.zw) / (_e151).xx);
            float4 _e157 = curl_tex.SampleLevel(noise_sampler, cuv, 0.0);
            float2 curl = ((_e157.xy * 2.0) - (1.0).xx);
            float3 _e164 = detail_pos;
            float _e172 = frame.erosion.z;
            detail_pos = (_e164 + (float3(curl.x, 0.0, curl.y) * (_e172 * (1.0 - h_5))));
        }
        float3 _e178 = detail_pos;
        float _e182 = frame.wind_offsets1_.x;
        float _e186 = frame.wind_offsets1_.y;
        detail_pos = (_e178 - float3(_e182, 0.0, _e186));
        float3 _e192 = detail_pos;
        float _e196 = frame.periods.z;
        float4 dn = detail_tex.SampleLevel(noise_sampler, (_e192 / (_e196).xxx), 0.0);
        float high_fbm = (((dn.x * 0.625) + (dn.y * 0.25)) + (dn.z * 0.125));
        float _e215 = frame.extinction.w;
        const float _e220 = saturate_((h_5 * 10.0));
        const float _e222 = saturate_(((2.0 * _e215) * _e220));
        float shape = lerp((1.0 - high_fbm), high_fbm, _e222);
        float _e227 = base;
        float erosion = ((strength * shape) * (1.0 - (_e227 / threshold)));
        float _e232 = base;
        const float _e236 = remap(_e232, erosion, 1.0, 0.0, 1.0);
        const float _e237 = saturate_(_e236);
        density = _e237;
    }
    float _e238 = density;
    float _e242 = frame.erosion.w;
    density = (_e238 * lerp(1.0, h_5, _e242));
    float _e246 = density;
    float _e250 = frame.clouds.y;
    density = ((_e246 * _e250) * (1.0 + _e28.precipitation));
    float _e256 = density;
    return clamp(_e256, 0.0, 1.0);
}

float phase_hg(float cos_theta, float g)
{
    float g2_ = (g * g);
    float denom = max(((1.0 + g2_) - ((2.0 * g) * cos_theta)), 1e-6);
    return ((1.0 - g2_) / ((12.566371 * denom) * sqrt(denom)));
}

float phase_cornette_shanks(float cos_theta_1, float g_1)
{
    float g2_1 = (g_1 * g_1);
    float denom_1 = max(((1.0 + g2_1) - ((2.0 * g_1) * cos_theta_1)), 1e-6);
    return (((3.0 * (1.0 - g2_1)) * (1.0 + (cos_theta_1 * cos_theta_1))) / (((25.132742 * (2.0 + g2_1)) * denom_1) * sqrt(denom_1)));
}

float phase(float cos_theta_2, float scale)
{
    float _e5 = frame.phase.x;
    float g_2 = (_e5 * scale);
    uint _e10 = frame.modes.x;
    switch(_e10) {
        case 1u: {
            float _e14 = frame.phase.y;
            float g2_2 = (_e14 * scale);
            const float _e16 = phase_hg(cos_theta_2, g_2);
            const float _e17 = phase_hg(cos_theta_2, g2_2);
            float _e21 = frame.phase.z;
            return lerp(_e16, _e17, _e21);
        }
        case 2u: {
            const float _e23 = phase_cornette_shanks(cos_theta_2, g_2);
            return _e23;
        }
        default: {
            const float _e24 = phase_hg(cos_theta_2, g_2);
            return _e24;
        }
    }
}

float sun_optical_depth(float3 rel, float3 p_4, inout Counters counters_1)
{
    float seg = (float)0;
    float dist = 0.0;
    float tau = 0.0;
    uint i = 0u;
    bool local_16 = (bool)0;

    float4 _e5 = frame.sun_direction;
    float3 sun = _e5.xyz;
    float _e10 = frame.extinction.x;
    float _e14 = frame.extinction.y;
    float sigma_t_1 = (_e10 + _e14);
    uint steps_1 = frame.counts.w;
    float growth = frame.march.y;
    float _e27 = frame.march.z;
    seg = _e27;
    uint2 loop_bound = uint2(4294967295u, 4294967295u);
    bool loop_init = true;
    while(true) {
        if (all(loop_bound == uint2(0u, 0u))) { break; }
        loop_bound -= uint2(loop_bound.y == 0u, 1u);
        if (!loop_init) {
            uint _e78 = i;
            i = (_e78 + 1u);
        }
        loop_init = false;
        uint _e35 = i;
        if ((_e35 < steps_1)) {
        } else {
            break;
        }
        {
            float _e37 = dist;
            float _e38 = seg;
            float s_2 = (_e37 + (0.5 * _e38));
            float3 q_5 = (rel + (sun * s_2));
            const float _e44 = altitude_of(q_5);
            float _e48 = frame.atmosphere.z;
            if (!((_e44 > _e48))) {
                float _e56 = frame.atmosphere.y;
                local_16 = (_e44 < _e56);
            } else {
                local_16 = true;
            }
            bool _e59 = local_16;
            if (_e59) {
                break;
            }
            uint _e61 = counters_1.light;
            counters_1.light = (_e61 + 1u);
            float _e64 = tau;
            const float _e67 = cloud_density((p_4 + (sun * s_2)), _e44, counters_1);
            float _e69 = seg;
            tau = (_e64 + ((_e67 * sigma_t_1) * _e69));
            float _e72 = dist;
            float _e73 = seg;
            dist = (_e72 + _e73);
            float _e75 = seg;
            seg = (_e75 * growth);
        }
    }
    float _e80 = tau;
    return _e80;
}

float sun_scattering(float cos_theta_3, float tau_1)
{
    float total = (float)0;
    float ka = 1.0;
    float kb = 1.0;
    float kc = 1.0;
    uint i_1 = 0u;

    float a = frame.multiple_scattering.x;
    float b_3 = frame.multiple_scattering.y;
    float c_3 = frame.multiple_scattering.z;
    uint _e17 = frame.misc.x;
    uint octaves = min(_e17, MAX_OCTAVES);
    const float _e21 = phase(cos_theta_3, 1.0);
    total = (_e21 * exp(-(tau_1)));
    uint2 loop_bound_1 = uint2(4294967295u, 4294967295u);
    bool loop_init_1 = true;
    while(true) {
        if (all(loop_bound_1 == uint2(0u, 0u))) { break; }
        loop_bound_1 -= uint2(loop_bound_1.y == 0u, 1u);
        if (!loop_init_1) {
            uint _e54 = i_1;
            i_1 = (_e54 + 1u);
        }
        loop_init_1 = false;
        uint _e34 = i_1;
        if ((_e34 < octaves)) {
        } else {
            break;
        }
        {
            float _e36 = ka;
            ka = (_e36 * a);
            float _e38 = kb;
            kb = (_e38 * b_3);
            float _e40 = kc;
            kc = (_e40 * c_3);
            float _e42 = total;
            float _e43 = ka;
            float _e44 = kc;
            const float _e45 = phase(cos_theta_3, _e44);
            float _e47 = kb;
            total = (_e42 + ((_e43 * _e45) * exp((-(_e47) * tau_1))));
        }
    }
    uint _e59 = frame.modes.w;
    if (((_e59 & FLAG_BEER_POWDER) != 0u)) {
        float _e64 = total;
        float _e68 = frame.phase.w;
        total = (_e64 * (1.0 - exp((-(_e68) * tau_1))));
    }
    float _e75 = total;
    return _e75;
}

float3 ambient(float h_4)
{
    float4 _e3 = frame.ambient_bottom;
    float4 _e7 = frame.ambient_top;
    float _e13 = frame.ambient_bottom.w;
    return (lerp(_e3.xyz, _e7.xyz, h_4) * _e13);
}

float3 scattered_light(float3 rel_1, float3 p_5, float alt_4, float density_1, float3 view, inout Counters counters_2)
{
    float3 sun_light = (0.0).xxx;
    float tau_2 = 0.0;

    float4 _e8 = frame.sun_direction;
    float3 sun_1 = _e8.xyz;
    float _e13 = frame.atmosphere.y;
    float _e18 = frame.atmosphere.z;
    float _e22 = frame.atmosphere.y;
    const float _e25 = saturate_(((alt_4 - _e13) / (_e18 - _e22)));
    const bool _e29 = hits_ground(rel_1, alt_4, sun_1);
    if (!(_e29)) {
        if (LIGHT_MARCH) {
            const float _e34 = sun_optical_depth(rel_1, p_5, counters_2);
            tau_2 = _e34;
        }
        float4 _e37 = frame.sun_illuminance;
        float _e40 = tau_2;
        const float _e41 = sun_scattering(dot(view, sun_1), _e40);
        sun_light = (_e37.xyz * _e41);
    }
    const Weather _e43 = sample_weather(p_5);
    float _e47 = frame.extinction.z;
    const float _e55 = saturate_((1.0 - ((_e47 * _e43.precipitation) * (1.0 - _e25))));
    float _e59 = frame.extinction.x;
    float3 _e61 = sun_light;
    const float3 _e62 = ambient(_e25);
    return (((_e59 * density_1) * (_e61 + _e62)) * _e55);
}

uint2 naga_f2u32(float2 value) {
    return uint2(clamp(value, 0.0, 4294967000.0));
}

float empty_cell_exit(float3 p_6, float3 d_3)
{
    float exit = 1e30;

    float4 _e6 = frame.wind_offsets0_;
    float _e12 = frame.periods.x;
    float2 uv_1 = (frac(((p_6.xz - _e6.xy) / (_e12).xx)) * 64.0);
    uint2 cell = min(naga_f2u32(uv_1), (63u).xx);
    float4 _e23 = occupancy_in.Load(int3(cell, int(0)));
    float m_1 = _e23.x;
    float _e28 = frame.clouds.x;
    if (((m_1 + (2.0 * (_e28 - 0.5))) > -0.003921569)) {
        return 0.0;
    }
    float _e40 = frame.periods.x;
    float cell_m = (_e40 / 64.0);
    float2 inside = ((uv_1 - float2(cell)) * cell_m);
    if ((d_3.x > 1e-6)) {
        float _e50 = exit;
        exit = min(_e50, ((cell_m - inside.x) / d_3.x));
    } else {
        if ((d_3.x < -1e-6)) {
            float _e59 = exit;
            exit = min(_e59, (inside.x / -(d_3.x)));
        }
    }
    if ((d_3.z > 1e-6)) {
        float _e68 = exit;
        exit = min(_e68, ((cell_m - inside.y) / d_3.z));
    } else {
        if ((d_3.z < -1e-6)) {
            float _e77 = exit;
            exit = min(_e77, (inside.y / -(d_3.z)));
        }
    }
    float _e83 = exit;
    return max(_e83, 0.0);
}

void count(uint index, uint value)
{
    bool local_17 = (bool)0;

    if (STATS) {
        local_17 = (value != 0u);
    } else {
        local_17 = false;
    }
    bool _e8 = local_17;
    if (_e8) {
        uint _e12; stats.InterlockedAdd(index*4+0, value, _e12);
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
    float x_4 = (sigma_t * dt);
    float f_1 = ((x_4 < 0.001) ? (1.0 - (0.5 * x_4)) : ((1.0 - exp(-(x_4))) / x_4));
    return (source * (dt * f_1));
}

uint naga_div(uint lhs, uint rhs) {
    return lhs / (rhs == 0u ? 1u : rhs);
}

float start_offset(uint2 pixel_2)
{
    uint _e4 = frame.modes.w;
    bool jitter = ((_e4 & FLAG_JITTER) != 0u);
    uint k_1 = frame.temporal.x;
    if ((k_1 <= 1u)) {
        uint _e18 = frame.misc.y;
        const float _e19 = hash_unit(pixel_2, _e18);
        return (jitter ? _e19 : 0.5);
    }
    const float _e23 = hash_unit(pixel_2, 0u);
    float base_2 = (jitter ? _e23 : 0.5);
    uint _e29 = frame.misc.y;
    const float _e32 = van_der_corput(naga_div(_e29, (k_1 * k_1)));
    return frac((base_2 + _e32));
}

Counters ConstructCounters(uint arg0, uint arg1, uint arg2, uint arg3) {
    Counters ret = (Counters)0;
    ret.view_steps = arg0;
    ret.density = arg1;
    ret.detail = arg2;
    ret.light = arg3;
    return ret;
}

MarchResult ConstructMarchResult(float3 arg0, float arg1, float arg2) {
    MarchResult ret = (MarchResult)0;
    ret.radiance = arg0;
    ret.transmittance = arg1;
    ret.depth = arg2;
    return ret;
}

uint naga_f2u32(float value) {
    return uint(clamp(value, 0.0, 4294967000.0));
}

MarchResult march_pixel(uint2 pixel_3)
{
    Counters counters_3 = ConstructCounters(0u, 0u, 0u, 0u);
    float3 radiance = (0.0).xxx;
    float transmittance = 1.0;
    float depth_sum = 0.0;
    uint steps = (uint)0;
    uint i_2 = 0u;
    uint stride = 1u;
    uint empty = 0u;
    bool local_18 = (bool)0;
    float depth_1 = 0.0;

    const float3 _e1 = view_ray(pixel_3);
    float cam_alt = frame.camera_position.y;
    float4 _e8 = frame.camera_position;
    float2 cam_xz = _e8.xz;
    count(STAT_PIXELS, 1u);
    const Interval _e25 = layer_interval(cam_alt, _e1);
    if ((_e25.kind == RAY_MISSES_LAYER)) {
        count(STAT_EXIT_MISSED, 1u);
    } else {
        if ((_e25.kind == RAY_HITS_GROUND)) {
            count(STAT_EXIT_GROUND, 1u);
        } else {
            count(STAT_MARCHED, 1u);
            uint _e41 = frame.counts.z;
            steps = _e41;
            float _e46 = frame.march.x;
            if ((_e46 > 0.0)) {
                float _e53 = frame.march.x;
                steps = clamp(naga_f2u32(ceil((_e25.length_ / _e53))), 1u, MAX_VIEW_STEPS);
            }
            uint _e61 = steps;
            float dt_1 = (_e25.length_ / float(_e61));
            const float _e64 = start_offset(pixel_3);
            float _e68 = frame.extinction.x;
            float _e72 = frame.extinction.y;
            float sigma_e = (_e68 + _e72);
            uint _e77 = frame.modes.w;
            bool dynamic_step = ((_e77 & FLAG_DYNAMIC_STEP) != 0u);
            uint _e85 = frame.modes.w;
            bool empty_skip = ((_e85 & FLAG_EMPTY_SKIP) != 0u);
            uint2 loop_bound_2 = uint2(4294967295u, 4294967295u);
            while(true) {
                if (all(loop_bound_2 == uint2(0u, 0u))) { break; }
                loop_bound_2 -= uint2(loop_bound_2.y == 0u, 1u);
                uint _e96 = i_2;
                uint _e97 = steps;
                if ((_e96 >= _e97)) {
                    break;
                }
                uint _e100 = counters_3.view_steps;
                counters_3.view_steps = (_e100 + 1u);
                uint _e104 = i_2;
                float t_1 = (_e25.start + ((float(_e104) + _e64) * dt_1));
                float3 rel_2 = ((_e1 * t_1) + float3(0.0, cam_alt, 0.0));
                float3 p_7 = float3((rel_2.x + cam_xz.x), rel_2.y, (rel_2.z + cam_xz.y));
                if (empty_skip) {
                    const float _e122 = empty_cell_exit(p_7, _e1);
                    if ((_e122 > 0.0)) {
                        uint _e131 = steps;
                        uint next = naga_f2u32(clamp(ceil(((((t_1 + _e122) - _e25.start) / dt_1) - _e64)), 0.0, float(_e131)));
                        uint _e136 = i_2;
                        i_2 = max((_e136 + 1u), next);
                        continue;
                    }
                }
                const float _e140 = altitude_of(rel_2);
                const float _e141 = cloud_density(p_7, _e140, counters_3);
                if ((_e141 <= 0.0)) {
                    uint _e144 = empty;
                    empty = (_e144 + 1u);
                    if (dynamic_step) {
                        uint _e149 = empty;
                        local_18 = (_e149 >= 8u);
                    } else {
                        local_18 = false;
                    }
                    bool _e153 = local_18;
                    if (_e153) {
                        stride = 2u;
                    }
                    uint _e155 = i_2;
                    uint _e156 = stride;
                    i_2 = (_e155 + _e156);
                    continue;
                }
                uint _e158 = stride;
                if ((_e158 > 1u)) {
                    uint _e161 = i_2;
                    uint _e162 = stride;
                    i_2 = (_e161 - (_e162 - 1u));
                    stride = 1u;
                    empty = 0u;
                    continue;
                }
                empty = 0u;
                float sigma_t_2 = (sigma_e * _e141);
                const float3 _e170 = scattered_light(rel_2, p_7, _e140, _e141, _e1, counters_3);
                float3 _e171 = radiance;
                float _e172 = transmittance;
                const float3 _e173 = step_integral(_e170, sigma_t_2, dt_1);
                radiance = (_e171 + (_e172 * _e173));
                float step_t = exp((-(sigma_t_2) * dt_1));
                float _e179 = depth_sum;
                float _e180 = transmittance;
                depth_sum = (_e179 + ((t_1 * _e180) * (1.0 - step_t)));
                float _e186 = transmittance;
                transmittance = (_e186 * step_t);
                float _e188 = transmittance;
                float _e192 = frame.march.w;
                if ((_e188 < _e192)) {
                    count(STAT_EXIT_TRANSMITTANCE, 1u);
                    break;
                }
                uint _e196 = i_2;
                i_2 = (_e196 + 1u);
            }
        }
    }
    uint _e201 = counters_3.view_steps;
    count(STAT_VIEW_STEPS, _e201);
    uint _e204 = counters_3.density;
    count(STAT_DENSITY, _e204);
    uint _e207 = counters_3.detail;
    count(STAT_DETAIL, _e207);
    uint _e210 = counters_3.light;
    count(STAT_LIGHT, _e210);
    float _e213 = transmittance;
    if ((_e213 < 1.0)) {
        float _e216 = depth_sum;
        float _e217 = transmittance;
        depth_1 = (_e216 / (1.0 - _e217));
    }
    float3 _e221 = radiance;
    float _e222 = transmittance;
    float _e223 = depth_1;
    const MarchResult marchresult = ConstructMarchResult(_e221, _e222, _e223);
    return marchresult;
}

uint2 bayer2_(uint v_1)
{
    return uint2(((v_1 ^ (v_1 >> 1u)) & 1u), (v_1 & 1u));
}

uint naga_mod(uint lhs, uint rhs) {
    return lhs % (rhs == 0u ? 1u : rhs);
}

uint2 block_offset(uint f, uint k)
{
    if ((k == 2u)) {
        const uint2 _e6 = bayer2_(naga_mod(f, 4u));
        return _e6;
    }
    if ((k == 4u)) {
        uint b_4 = naga_mod(f, 16u);
        const uint2 _e13 = bayer2_((b_4 >> 2u));
        const uint2 _e17 = bayer2_((b_4 & 3u));
        return (_e13 + (2u * _e17));
    }
    return (0u).xx;
}

float2 reproject(uint2 pixel_4, float depth_2)
{
    bool local_19 = (bool)0;
    bool local_20 = (bool)0;
    bool local_21 = (bool)0;
    float3 dir = (float3)0;

    float4 _e4 = frame.previous_position;
    float4 _e7 = frame.camera_position;
    if (all((_e4 == _e7))) {
        float4 _e14 = frame.previous_forward;
        float4 _e17 = frame.camera_forward;
        local_19 = all((_e14 == _e17));
    } else {
        local_19 = false;
    }
    bool _e21 = local_19;
    if (_e21) {
        float4 _e26 = frame.previous_right;
        float4 _e29 = frame.camera_right;
        local_20 = all((_e26 == _e29));
    } else {
        local_20 = false;
    }
    bool _e33 = local_20;
    if (_e33) {
        float4 _e38 = frame.previous_up;
        float4 _e41 = frame.camera_up;
        local_21 = all((_e38 == _e41));
    } else {
        local_21 = false;
    }
    bool same = local_21;
    if (same) {
        return float2(pixel_4);
    }
    const float3 _e47 = view_ray(pixel_4);
    dir = _e47;
    if ((depth_2 > 0.0)) {
        float4 _e54 = frame.camera_position;
        float4 _e58 = frame.previous_position;
        dir = ((_e47 * depth_2) + (_e54.xyz - _e58.xyz));
    }
    float3 _e62 = dir;
    float4 _e65 = frame.previous_forward;
    float z = dot(_e62, _e65.xyz);
    if ((z <= 0.0)) {
        return (-1000000000.0).xx;
    }
    float tan_half_1 = frame.previous_position.w;
    float aspect_1 = frame.previous_forward.w;
    float3 _e80 = dir;
    float4 _e83 = frame.previous_right;
    float3 _e89 = dir;
    float4 _e92 = frame.previous_up;
    float2 ndc_1 = float2((dot(_e80, _e83.xyz) / ((z * tan_half_1) * aspect_1)), (-(dot(_e89, _e92.xyz)) / (z * tan_half_1)));
    uint4 _e106 = frame.counts;
    return ((((ndc_1 * 0.5) + (0.5).xx) * float2(_e106.xy)) - (0.5).xx);
}

bool on_screen(float2 q)
{
    bool local_22 = (bool)0;

    uint4 _e3 = frame.counts;
    float2 size_1 = float2(_e3.xy);
    if (all((q >= (-0.5).xx))) {
        local_22 = all((q <= (size_1 - (0.5).xx)));
    } else {
        local_22 = false;
    }
    bool _e18 = local_22;
    return _e18;
}

float4 catmull_rom(float t)
{
    return float4((t * (-0.5 + (t * (1.0 - (0.5 * t))))), (1.0 + ((t * t) * (-2.5 + (1.5 * t)))), (t * (0.5 + (t * (2.0 - (1.5 * t))))), ((t * t) * (-0.5 + (0.5 * t))));
}

float4 history_row(int2 base_1, int dy, float4 wx)
{
    uint4 _e5 = frame.counts;
    int2 size_2 = int2(_e5.xy);
    int y_1 = clamp(asint(asuint(base_1.y) + asuint(dy)), int(0), asint(asuint(size_2.y) - asuint(int(1))));
    int x0_ = clamp(asint(asuint(base_1.x) - asuint(int(1))), int(0), asint(asuint(size_2.x) - asuint(int(1))));
    int x1_ = clamp(base_1.x, int(0), asint(asuint(size_2.x) - asuint(int(1))));
    int x2_ = clamp(asint(asuint(base_1.x) + asuint(int(1))), int(0), asint(asuint(size_2.x) - asuint(int(1))));
    int x3_ = clamp(asint(asuint(base_1.x) + asuint(int(2))), int(0), asint(asuint(size_2.x) - asuint(int(1))));
    float4 _e48 = history_in.Load(int3(int2(x0_, y_1), int(0)));
    float4 _e54 = history_in.Load(int3(int2(x1_, y_1), int(0)));
    float4 _e61 = history_in.Load(int3(int2(x2_, y_1), int(0)));
    float4 _e68 = history_in.Load(int3(int2(x3_, y_1), int(0)));
    return ((((_e48 * wx.x) + (_e54 * wx.y)) + (_e61 * wx.z)) + (_e68 * wx.w));
}

int2 naga_f2i32(float2 value) {
    return int2(clamp(value, -2147483600.0, 2147483500.0));
}

float4 history_at(float2 q_1)
{
    uint4 _e3 = frame.counts;
    int2 size_3 = int2(_e3.xy);
    float2 c_4 = clamp(q_1, (0.0).xx, float2(asint(asuint(size_3) - asuint((int(1)).xx))));
    int2 base_3 = naga_f2i32(floor(c_4));
    float2 f_2 = (c_4 - float2(base_3));
    const float4 _e18 = catmull_rom(f_2.x);
    const float4 _e20 = catmull_rom(f_2.y);
    const float4 _e22 = history_row(base_3, int(-1), _e18);
    const float4 _e26 = history_row(base_3, int(0), _e18);
    const float4 _e31 = history_row(base_3, int(1), _e18);
    const float4 _e36 = history_row(base_3, int(2), _e18);
    float4 sum = ((((_e22 * _e20.x) + (_e26 * _e20.y)) + (_e31 * _e20.z)) + (_e36 * _e20.w));
    const float _e45 = saturate_(sum.w);
    return float4(max(sum.xyz, (0.0).xxx), _e45);
}

float4 history_nearest(float2 q_2)
{
    uint4 _e3 = frame.counts;
    int2 size_4 = int2(_e3.xy);
    int2 p_8 = clamp(naga_f2i32(round(q_2)), (int(0)).xx, asint(asuint(size_4) - asuint((int(1)).xx)));
    float4 _e16 = history_in.Load(int3(p_8, int(0)));
    return _e16;
}

float4 meta_at(float2 q_3)
{
    uint4 _e3 = frame.counts;
    int2 size_5 = int2(_e3.xy);
    int2 p_9 = clamp(naga_f2i32(round(q_3)), (int(0)).xx, asint(asuint(size_5) - asuint((int(1)).xx)));
    float4 _e16 = meta_in.Load(int3(p_9, int(0)));
    return _e16;
}

uint2 naga_div(uint2 lhs, uint2 rhs) {
    return lhs / (rhs == 0u ? 1u : rhs);
}

bool in_blocks(uint2 id_6)
{
    uint k_2 = frame.temporal.x;
    uint4 _e7 = frame.counts;
    return all((id_6 < naga_div(((_e7.xy + (k_2).xx) - (1u).xx), (k_2).xx)));
}

uint2 sparse_pixel(uint2 id_7)
{
    uint k_3 = frame.temporal.x;
    uint _e9 = frame.misc.y;
    const uint2 _e10 = block_offset(_e9, k_3);
    return ((id_7 * k_3) + _e10);
}

void store_sparse(uint2 id_8, MarchResult r_2)
{
    cloud_out[id_8] = float4(r_2.radiance, r_2.transmittance);
    depth_out[id_8] = float4(r_2.depth, 0.0, 0.0, 0.0);
    return;
}

float3 sky_radiance(float3 d_4, float alt_5)
{
    float4 _e4 = frame.sun_direction;
    float3 sun_2 = _e4.xyz;
    float4 _e8 = frame.sun_illuminance;
    float3 e = _e8.xyz;
    const float _e15 = saturate_(((sun_2.y * 4.0) + 0.3));
    const bool _e19 = hits_ground(float3(0.0, alt_5, 0.0), alt_5, d_4);
    if (_e19) {
        float3 ground_albedo = float3(0.035, 0.035, 0.03);
        return (ground_albedo * (((e * max(sun_2.y, 0.0)) / (3.1415927).xxx) + ((0.05 * e) * _e15)));
    }
    float3 zenith = float3(0.018, 0.04, 0.1);
    float3 horizon = float3(0.07, 0.085, 0.11);
    const float _e45 = saturate_(d_4.y);
    float3 gradient_1 = lerp(horizon, zenith, sqrt(_e45));
    float3 sunset = (((1.0 - (_e15 * 0.8)) * pow((1.0 - _e45), 6.0)) * float3(0.25, 0.1, 0.0));
    const float _e64 = phase_hg(dot(d_4, sun_2), 0.76);
    float glow = (_e64 * 0.02);
    const float _e73 = saturate_(((sun_2.y * 10.0) + 1.0));
    return (e * (((gradient_1 * _e15) + (sunset * _e73)) + ((glow * _e15)).xxx));
}

float3 sun_disk(float3 d_5)
{
    float cos_r = frame.sun_direction.w;
    float4 _e7 = frame.sun_direction;
    if ((dot(d_5, _e7.xyz) < cos_r)) {
        return (0.0).xxx;
    }
    float4 _e15 = frame.sun_illuminance;
    return (_e15.xyz / ((6.2831855 * max((1.0 - cos_r), 1e-6))).xxx);
}

float3 aces_fitted(float3 x_3)
{
    return clamp(((x_3 * ((2.51 * x_3) + (0.03).xxx)) / ((x_3 * ((2.43 * x_3) + (0.59).xxx)) + (0.14).xxx)), (0.0).xxx, (1.0).xxx);
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
void occupancy(uint3 id : SV_DispatchThreadID)
{
    float m = 0.0;
    int y = (int)0;
    int x = (int)0;

    if (any((id.xy >= (64u).xx))) {
        return;
    }
    int2 size_6 = int2(NagaDimensions2D(weather_tex));
    int2 lo_1 = asint(asuint(naga_div(asint(asuint(int2(id.xy)) * asuint(size_6)), (int(64)).xx)) - asuint((int(1)).xx));
    int2 hi = naga_div(asint(asuint(asint(asuint(int2(id.xy)) + asuint((int(1)).xx))) * asuint(size_6)), (int(64)).xx);
    y = lo_1.y;
    uint2 loop_bound_3 = uint2(4294967295u, 4294967295u);
    bool loop_init_2 = true;
    while(true) {
        if (all(loop_bound_3 == uint2(0u, 0u))) { break; }
        loop_bound_3 -= uint2(loop_bound_3.y == 0u, 1u);
        if (!loop_init_2) {
            int _e54 = y;
            y = asint(asuint(_e54) + asuint(int(1)));
        }
        loop_init_2 = false;
        int _e30 = y;
        if ((_e30 <= hi.y)) {
        } else {
            break;
        }
        {
            x = lo_1.x;
            uint2 loop_bound_4 = uint2(4294967295u, 4294967295u);
            bool loop_init_3 = true;
            while(true) {
                if (all(loop_bound_4 == uint2(0u, 0u))) { break; }
                loop_bound_4 -= uint2(loop_bound_4.y == 0u, 1u);
                if (!loop_init_3) {
                    int _e51 = x;
                    x = asint(asuint(_e51) + asuint(int(1)));
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
                    int2 t_2 = naga_mod(asint(asuint(naga_mod(int2(_e38, _e39), size_6)) + asuint(size_6)), size_6);
                    float _e44 = m;
                    float4 _e47 = weather_tex.Load(int3(t_2, int(0)));
                    m = max(_e44, _e47.x);
                }
            }
        }
    }
    float _e58 = m;
    occupancy_out[id.xy] = float4(_e58, 0.0, 0.0, 0.0);
    return;
}

[numthreads(8, 8, 1)]
void march(uint3 id_1 : SV_DispatchThreadID)
{
    uint4 _e4 = frame.counts;
    if (any((id_1.xy >= _e4.xy))) {
        return;
    }
    const MarchResult _e9 = march_pixel(id_1.xy);
    cloud_out[id_1.xy] = float4(_e9.radiance, _e9.transmittance);
    depth_out[id_1.xy] = float4(_e9.depth, 0.0, 0.0, 0.0);
    return;
}

[numthreads(8, 8, 1)]
void march_sparse(uint3 id_2 : SV_DispatchThreadID)
{
    MarchResult r = ConstructMarchResult((0.0).xxx, 1.0, 0.0);

    const bool _e2 = in_blocks(id_2.xy);
    if (!(_e2)) {
        return;
    }
    const uint2 _e5 = sparse_pixel(id_2.xy);
    uint4 _e14 = frame.counts;
    if (all((_e5 < _e14.xy))) {
        const MarchResult _e18 = march_pixel(_e5);
        r = _e18;
    }
    MarchResult _e20 = r;
    store_sparse(id_2.xy, _e20);
    return;
}

[numthreads(8, 8, 1)]
void march_sparse_checkerboard(uint3 id_3 : SV_DispatchThreadID)
{
    MarchResult r_1 = ConstructMarchResult((0.0).xxx, 1.0, 0.0);
    bool skip = (bool)0;
    bool local = (bool)0;
    bool local_1 = (bool)0;
    bool local_2 = (bool)0;

    const bool _e2 = in_blocks(id_3.xy);
    if (!(_e2)) {
        return;
    }
    const uint2 _e5 = sparse_pixel(id_3.xy);
    uint4 _e14 = frame.counts;
    skip = any((_e5 >= _e14.xy));
    bool _e19 = skip;
    if (!(_e19)) {
        uint _e26 = frame.temporal.y;
        local = (_e26 != 0u);
    } else {
        local = false;
    }
    bool _e30 = local;
    if (_e30) {
        uint k_4 = frame.temporal.x;
        uint _e38 = frame.misc.y;
        uint turn = naga_div(_e38, (k_4 * k_4));
        const float2 _e42 = reproject(_e5, 0.0);
        if (((((id_3.x + id_3.y) + turn) & 1u) == 0u)) {
            const bool _e53 = on_screen(_e42);
            local_1 = _e53;
        } else {
            local_1 = false;
        }
        bool _e55 = local_1;
        if (_e55) {
            const float4 _e58 = history_nearest(_e42);
            local_2 = (_e58.w >= 1.0);
        } else {
            local_2 = false;
        }
        bool _e63 = local_2;
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
    store_sparse(id_3.xy, _e69);
    return;
}

[numthreads(8, 8, 1)]
void resolve(uint3 id_4 : SV_DispatchThreadID)
{
    float depth = (float)0;
    bool local_3 = (bool)0;
    bool valid = (bool)0;
    float4 history = float4(0.0, 0.0, 0.0, 1.0);
    float4 past = (0.0).xxxx;
    bool local_4 = (bool)0;
    bool local_5 = (bool)0;
    bool local_6 = (bool)0;
    float4 result = (float4)0;
    float samples = (float)0;
    float out_depth = (float)0;
    bool local_7 = (bool)0;

    uint4 _e4 = frame.counts;
    if (any((id_4.xy >= _e4.xy))) {
        return;
    }
    uint2 pixel_5 = id_4.xy;
    uint k_5 = frame.temporal.x;
    uint2 block = naga_div(pixel_5, (k_5).xx);
    uint _e19 = frame.misc.y;
    const uint2 _e20 = block_offset(_e19, k_5);
    bool marched = all((pixel_5 == ((block * k_5) + _e20)));
    float4 current = sparse_in.Load(int3(block, int(0)));
    float4 _e29 = sparse_depth_in.Load(int3(block, int(0)));
    float current_depth = _e29.x;
    depth = current_depth;
    float _e32 = depth;
    if ((_e32 <= 0.0)) {
        float _e38 = frame.camera_position.y;
        const float3 _e39 = view_ray(pixel_5);
        const Interval _e40 = layer_interval(_e38, _e39);
        if ((_e40.kind == RAY_MARCH)) {
            depth = (_e40.start + (0.5 * _e40.length_));
        }
    }
    float _e49 = depth;
    const float2 _e50 = reproject(pixel_5, _e49);
    uint _e54 = frame.temporal.y;
    if ((_e54 != 0u)) {
        const bool _e59 = on_screen(_e50);
        local_3 = _e59;
    } else {
        local_3 = false;
    }
    bool _e61 = local_3;
    valid = _e61;
    bool moving = any((_e50 != float2(pixel_5)));
    bool _e75 = valid;
    if (_e75) {
        const float4 _e76 = history_at(_e50);
        history = _e76;
        const float4 _e77 = meta_at(_e50);
        past = _e77;
        if (moving) {
            local_4 = (current_depth > 0.0);
        } else {
            local_4 = false;
        }
        bool _e83 = local_4;
        if (_e83) {
            float _e87 = past.x;
            local_5 = (_e87 > 0.0);
        } else {
            local_5 = false;
        }
        bool _e91 = local_5;
        if (_e91) {
            float4 _e94 = frame.camera_position;
            const float3 _e96 = view_ray(pixel_5);
            float4 _e101 = frame.previous_position;
            float expected = distance((_e94.xyz + (_e96 * current_depth)), _e101.xyz);
            float _e105 = past.x;
            valid = (abs((_e105 - expected)) <= (DISOCCLUSION_DEPTH * expected));
        }
    }
    bool _e111 = valid;
    if (_e111) {
        local_6 = moving;
    } else {
        local_6 = false;
    }
    bool _e115 = local_6;
    if (_e115) {
        uint4 _e118 = frame.counts;
        int2 blocks = int2(naga_div(((_e118.xy + (k_5).xx) - (1u).xx), (k_5).xx));
        int2 b_5 = int2(block);
        int x0_1 = max(asint(asuint(b_5.x) - asuint(int(1))), int(0));
        int x2_1 = min(asint(asuint(b_5.x) + asuint(int(1))), asint(asuint(blocks.x) - asuint(int(1))));
        int y0_ = max(asint(asuint(b_5.y) - asuint(int(1))), int(0));
        int y2_ = min(asint(asuint(b_5.y) + asuint(int(1))), asint(asuint(blocks.y) - asuint(int(1))));
        float4 s00_ = sparse_in.Load(int3(int2(x0_1, y0_), int(0)));
        float4 s10_ = sparse_in.Load(int3(int2(b_5.x, y0_), int(0)));
        float4 s20_ = sparse_in.Load(int3(int2(x2_1, y0_), int(0)));
        float4 s01_ = sparse_in.Load(int3(int2(x0_1, b_5.y), int(0)));
        float4 s11_ = sparse_in.Load(int3(b_5, int(0)));
        float4 s21_ = sparse_in.Load(int3(int2(x2_1, b_5.y), int(0)));
        float4 s02_ = sparse_in.Load(int3(int2(x0_1, y2_), int(0)));
        float4 s12_ = sparse_in.Load(int3(int2(b_5.x, y2_), int(0)));
        float4 s22_ = sparse_in.Load(int3(int2(x2_1, y2_), int(0)));
        float4 lo_2 = min(min(min(s00_, s10_), min(s20_, s01_)), min(min(s11_, s21_), min(min(s02_, s12_), s22_)));
        float4 hi_1 = max(max(max(s00_, s10_), max(s20_, s01_)), max(max(s11_, s21_), max(max(s02_, s12_), s22_)));
        float4 _e208 = history;
        history = clamp(_e208, lo_2, hi_1);
    }
    if (marched) {
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
            local_7 = !(_e235);
        } else {
            local_7 = true;
        }
        bool _e238 = local_7;
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
            const MarchResult _e248 = march_pixel(pixel_5);
            samples = 1.0;
            result = float4(_e248.radiance, _e248.transmittance);
            out_depth = _e248.depth;
        }
    }
    float4 _e255 = result;
    history_out[pixel_5] = _e255;
    float _e257 = out_depth;
    float _e258 = samples;
    meta_out[pixel_5] = float4(_e257, _e258, 0.0, 0.0);
    float4 _e263 = result;
    cloud_out[pixel_5] = _e263;
    float _e265 = out_depth;
    depth_out[pixel_5] = float4(_e265, 0.0, 0.0, 0.0);
    return;
}

[numthreads(8, 8, 1)]
void composite(uint3 id_5 : SV_DispatchThreadID)
{
    float3 background = (float3)0;

    uint4 _e4 = frame.counts;
    if (any((id_5.xy >= _e4.xy))) {
        return;
    }
    uint2 pixel_6 = id_5.xy;
    const float3 _e9 = view_ray(pixel_6);
    float alt_6 = frame.camera_position.y;
    float4 cloud = cloud_in.Load(int3(pixel_6, int(0)));
    const float3 _e17 = sky_radiance(_e9, alt_6);
    background = _e17;
    const bool _e22 = hits_ground(float3(0.0, alt_6, 0.0), alt_6, _e9);
    if (!(_e22)) {
        float3 _e24 = background;
        const float3 _e25 = sun_disk(_e9);
        background = (_e24 + _e25);
    }
    float3 _e27 = background;
    float3 radiance_1 = ((_e27 * cloud.w) + cloud.xyz);
    float _e35 = frame.camera_right.w;
    float3 exposed = (radiance_1 * _e35);
    const float3 _e37 = aces_fitted(exposed);
    float3 display = pow(_e37, (0.45454547).xxx);
    image_out[pixel_6] = float4(display, 1.0);
    return;
}
