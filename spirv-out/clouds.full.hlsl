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

static const uint PHASE_HG = 0u;
static const uint PHASE_TWO_LOBE_HG = 1u;
static const uint PHASE_CORNETTE_SHANKS = 2u;
static const uint INTEGRATION_ANALYTIC = 0u;
static const uint INTEGRATION_RIEMANN = 1u;
static const uint HEIGHT_PARABOLA = 0u;
static const uint HEIGHT_CLOUD_TYPES = 1u;
static const uint FLAG_BEER_POWDER = 1u;
static const uint FLAG_JITTER = 2u;
static const float PI = 3.1415927;
static const uint MAX_VIEW_STEPS = 1024u;
static const uint RAY_MARCH = 0u;
static const uint RAY_MISSES_LAYER = 1u;
static const uint RAY_HITS_GROUND = 2u;
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
static const bool LIGHT_MARCH = true;
static const uint MAX_OCTAVES = 8u;
static const bool DETAIL = true;
static const bool CURL = true;
static const bool STATS = false;

cbuffer frame : register(b0) { Frame frame; }
Texture3D<float4> shape_tex : register(t1);
Texture3D<float4> detail_tex : register(t2);
Texture2D<float4> weather_tex : register(t3);
Texture2D<float4> curl_tex : register(t4);
SamplerState nagaSamplerHeap[2048]: register(s16, space0);
SamplerComparisonState nagaComparisonSamplerHeap[2048]: register(s17, space0);
StructuredBuffer<uint> nagaGroup0SamplerIndexArray : register(t18, space0);
static const SamplerState noise_sampler = nagaSamplerHeap[nagaGroup0SamplerIndexArray[5]];
RWTexture2D<float4> cloud_out : register(u6);
RWTexture2D<float> depth_out : register(u7);
RWByteAddressBuffer stats : register(u8);
Texture2D<float4> cloud_in : register(t9);
RWTexture2D<unorm float4> image_out : register(u10);

float saturate_(float x)
{
    return clamp(x, 0.0, 1.0);
}

float remap(float x_1, float lo0_, float hi0_, float lo1_, float hi1_)
{
    return (lo1_ + (((x_1 - lo0_) * (hi1_ - lo1_)) / (hi0_ - lo0_)));
}

uint pcg(uint v)
{
    uint state = ((v * 747796405u) + 2891336453u);
    uint word = (((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u);
    return ((word >> 22u) ^ word);
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
    float3 d_5 = ((_e26.xyz + (_e30.xyz * ((ndc.x * tan_half) * aspect))) - (_e39.xyz * (ndc.y * tan_half)));
    return normalize(d_5);
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
    float n = (((p.x * p.x) + (p.z * p.z)) + (p.y * (p.y + (2.0 * rp_1))));
    float3 q = float3(p.x, (p.y + rp_1), p.z);
    return (n / (length(q) + rp_1));
}

bool hits_ground(float3 p_1, float alt_1, float3 d_1)
{
    bool local = (bool)0;

    float rp_2 = frame.atmosphere.x;
    float b_2 = dot(d_1, float3(p_1.x, (p_1.y + rp_2), p_1.z));
    float c_2 = (alt_1 * (alt_1 + (2.0 * rp_2)));
    if ((b_2 < 0.0)) {
        local = ((b_2 * b_2) >= c_2);
    } else {
        local = false;
    }
    bool _e24 = local;
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
    bool local_1 = (bool)0;
    bool local_2 = (bool)0;
    bool local_3 = (bool)0;

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
                local_1 = (_e14.t0_ > 0.0);
            } else {
                local_1 = false;
            }
            bool _e40 = local_1;
            if (_e40) {
                float _e41 = end;
                end = min(_e41, _e14.t0_);
            }
        } else {
            if (!(!(_e15.hit))) {
                local_2 = (_e15.t1_ <= 0.0);
            } else {
                local_2 = true;
            }
            bool _e53 = local_2;
            if (_e53) {
                const Interval interval_1 = ConstructInterval(0.0, 0.0, 1u);
                return interval_1;
            }
            start = max(_e15.t0_, 0.0);
            end = _e15.t1_;
            if (_e14.hit) {
                local_3 = (_e14.t0_ > 0.0);
            } else {
                local_3 = false;
            }
            bool _e69 = local_3;
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

float cloud_density(float3 p_3, float alt_3, inout Counters counters_1)
{
    bool local_4 = (bool)0;
    bool local_5 = (bool)0;
    float base = (float)0;
    float density = (float)0;
    bool local_6 = (bool)0;
    bool local_7 = (bool)0;
    float3 detail_pos = (float3)0;

    float bottom_1 = frame.atmosphere.y;
    float top_1 = frame.atmosphere.z;
    float h_5 = ((alt_3 - bottom_1) / (top_1 - bottom_1));
    if (!((h_5 < 0.0))) {
        local_4 = (h_5 > 1.0);
    } else {
        local_4 = true;
    }
    bool _e22 = local_4;
    if (_e22) {
        return 0.0;
    }
    uint _e25 = counters_1.density;
    counters_1.density = (_e25 + 1u);
    const Weather _e28 = sample_weather(p_3);
    const float _e30 = height_signal(h_5, _e28.cloud_type);
    if (!((_e28.coverage <= 0.0))) {
        local_5 = (_e30 <= 0.0);
    } else {
        local_5 = true;
    }
    bool _e40 = local_5;
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
        local_6 = (strength > 0.0);
    } else {
        local_6 = false;
    }
    bool _e126 = local_6;
    if (_e126) {
        float _e129 = base;
        local_7 = (_e129 < threshold);
    } else {
        local_7 = false;
    }
    bool _e132 = local_7;
    if (_e132) {
        uint _e134 = counters_1.detail;
        counters_1.detail = (_e134 + 1u);
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

float sun_optical_depth(float3 rel, float3 p_4, inout Counters counters_2)
{
    float seg = (float)0;
    float dist = 0.0;
    float tau = 0.0;
    uint i_1 = 0u;
    bool local_8 = (bool)0;

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
            uint _e78 = i_1;
            i_1 = (_e78 + 1u);
        }
        loop_init = false;
        uint _e35 = i_1;
        if ((_e35 < steps_1)) {
        } else {
            break;
        }
        {
            float _e37 = dist;
            float _e38 = seg;
            float s_2 = (_e37 + (0.5 * _e38));
            float3 q_1 = (rel + (sun * s_2));
            const float _e44 = altitude_of(q_1);
            float _e48 = frame.atmosphere.z;
            if (!((_e44 > _e48))) {
                float _e56 = frame.atmosphere.y;
                local_8 = (_e44 < _e56);
            } else {
                local_8 = true;
            }
            bool _e59 = local_8;
            if (_e59) {
                break;
            }
            uint _e61 = counters_2.light;
            counters_2.light = (_e61 + 1u);
            float _e64 = tau;
            const float _e67 = cloud_density((p_4 + (sun * s_2)), _e44, counters_2);
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
    uint i_2 = 0u;

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
            uint _e54 = i_2;
            i_2 = (_e54 + 1u);
        }
        loop_init_1 = false;
        uint _e34 = i_2;
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

float3 scattered_light(float3 rel_1, float3 p_5, float alt_4, float density_1, float3 view, inout Counters counters_3)
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
            const float _e34 = sun_optical_depth(rel_1, p_5, counters_3);
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

void count(uint index, uint value)
{
    bool local_9 = (bool)0;

    if (STATS) {
        local_9 = (value != 0u);
    } else {
        local_9 = false;
    }
    bool _e8 = local_9;
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
    float x_3 = (sigma_t * dt);
    float f = ((x_3 < 0.001) ? (1.0 - (0.5 * x_3)) : ((1.0 - exp(-(x_3))) / x_3));
    return (source * (dt * f));
}

float3 sky_radiance(float3 d_3, float alt_5)
{
    float4 _e4 = frame.sun_direction;
    float3 sun_2 = _e4.xyz;
    float4 _e8 = frame.sun_illuminance;
    float3 e = _e8.xyz;
    const float _e15 = saturate_(((sun_2.y * 4.0) + 0.3));
    const bool _e19 = hits_ground(float3(0.0, alt_5, 0.0), alt_5, d_3);
    if (_e19) {
        float3 ground_albedo = float3(0.035, 0.035, 0.03);
        return (ground_albedo * (((e * max(sun_2.y, 0.0)) / (3.1415927).xxx) + ((0.05 * e) * _e15)));
    }
    float3 zenith = float3(0.018, 0.04, 0.1);
    float3 horizon = float3(0.07, 0.085, 0.11);
    const float _e45 = saturate_(d_3.y);
    float3 gradient_1 = lerp(horizon, zenith, sqrt(_e45));
    float3 sunset = (((1.0 - (_e15 * 0.8)) * pow((1.0 - _e45), 6.0)) * float3(0.25, 0.1, 0.0));
    const float _e64 = phase_hg(dot(d_3, sun_2), 0.76);
    float glow = (_e64 * 0.02);
    const float _e73 = saturate_(((sun_2.y * 10.0) + 1.0));
    return (e * (((gradient_1 * _e15) + (sunset * _e73)) + ((glow * _e15)).xxx));
}

float3 sun_disk(float3 d_4)
{
    float cos_r = frame.sun_direction.w;
    float4 _e7 = frame.sun_direction;
    if ((dot(d_4, _e7.xyz) < cos_r)) {
        return (0.0).xxx;
    }
    float4 _e15 = frame.sun_illuminance;
    return (_e15.xyz / ((6.2831855 * max((1.0 - cos_r), 1e-6))).xxx);
}

float3 aces_fitted(float3 x_2)
{
    return clamp(((x_2 * ((2.51 * x_2) + (0.03).xxx)) / ((x_2 * ((2.43 * x_2) + (0.59).xxx)) + (0.14).xxx)), (0.0).xxx, (1.0).xxx);
}

Counters ConstructCounters(uint arg0, uint arg1, uint arg2, uint arg3) {
    Counters ret = (Counters)0;
    ret.view_steps = arg0;
    ret.density = arg1;
    ret.detail = arg2;
    ret.light = arg3;
    return ret;
}

uint naga_f2u32(float value) {
    return uint(clamp(value, 0.0, 4294967000.0));
}

[numthreads(8, 8, 1)]
void march(uint3 id : SV_DispatchThreadID)
{
    Counters counters = ConstructCounters(0u, 0u, 0u, 0u);
    float3 radiance = (0.0).xxx;
    float transmittance = 1.0;
    float depth_sum = 0.0;
    uint steps = (uint)0;
    float jitter = 0.5;
    uint i = 0u;
    float depth = 0.0;

    uint4 _e4 = frame.counts;
    if (any((id.xy >= _e4.xy))) {
        return;
    }
    uint2 pixel_2 = id.xy;
    const float3 _e9 = view_ray(pixel_2);
    float cam_alt = frame.camera_position.y;
    float4 _e16 = frame.camera_position;
    float2 cam_xz = _e16.xz;
    count(STAT_PIXELS, 1u);
    const Interval _e33 = layer_interval(cam_alt, _e9);
    if ((_e33.kind == RAY_MISSES_LAYER)) {
        count(STAT_EXIT_MISSED, 1u);
    } else {
        if ((_e33.kind == RAY_HITS_GROUND)) {
            count(STAT_EXIT_GROUND, 1u);
        } else {
            count(STAT_MARCHED, 1u);
            uint _e49 = frame.counts.z;
            steps = _e49;
            float _e54 = frame.march.x;
            if ((_e54 > 0.0)) {
                float _e61 = frame.march.x;
                steps = clamp(naga_f2u32(ceil((_e33.length_ / _e61))), 1u, MAX_VIEW_STEPS);
            }
            uint _e69 = steps;
            float dt_1 = (_e33.length_ / float(_e69));
            uint _e77 = frame.modes.w;
            if (((_e77 & FLAG_JITTER) != 0u)) {
                uint _e85 = frame.misc.y;
                const float _e86 = hash_unit(pixel_2, _e85);
                jitter = _e86;
            }
            float _e90 = frame.extinction.x;
            float _e94 = frame.extinction.y;
            float sigma_e = (_e90 + _e94);
            uint2 loop_bound_2 = uint2(4294967295u, 4294967295u);
            bool loop_init_2 = true;
            while(true) {
                if (all(loop_bound_2 == uint2(0u, 0u))) { break; }
                loop_bound_2 -= uint2(loop_bound_2.y == 0u, 1u);
                if (!loop_init_2) {
                    uint _e157 = i;
                    i = (_e157 + 1u);
                }
                loop_init_2 = false;
                uint _e98 = i;
                uint _e99 = steps;
                if ((_e98 < _e99)) {
                } else {
                    break;
                }
                {
                    uint _e102 = counters.view_steps;
                    counters.view_steps = (_e102 + 1u);
                    uint _e106 = i;
                    float _e108 = jitter;
                    float t = (_e33.start + ((float(_e106) + _e108) * dt_1));
                    float3 rel_2 = ((_e9 * t) + float3(0.0, cam_alt, 0.0));
                    float3 p_6 = float3((rel_2.x + cam_xz.x), rel_2.y, (rel_2.z + cam_xz.y));
                    const float _e125 = altitude_of(rel_2);
                    const float _e126 = cloud_density(p_6, _e125, counters);
                    if ((_e126 <= 0.0)) {
                        continue;
                    }
                    float sigma_t_2 = (sigma_e * _e126);
                    const float3 _e130 = scattered_light(rel_2, p_6, _e125, _e126, _e9, counters);
                    float3 _e131 = radiance;
                    float _e132 = transmittance;
                    const float3 _e133 = step_integral(_e130, sigma_t_2, dt_1);
                    radiance = (_e131 + (_e132 * _e133));
                    float step_t = exp((-(sigma_t_2) * dt_1));
                    float _e139 = depth_sum;
                    float _e140 = transmittance;
                    depth_sum = (_e139 + ((t * _e140) * (1.0 - step_t)));
                    float _e146 = transmittance;
                    transmittance = (_e146 * step_t);
                    float _e148 = transmittance;
                    float _e152 = frame.march.w;
                    if ((_e148 < _e152)) {
                        count(STAT_EXIT_TRANSMITTANCE, 1u);
                        break;
                    }
                }
            }
        }
    }
    uint _e161 = counters.view_steps;
    count(STAT_VIEW_STEPS, _e161);
    uint _e164 = counters.density;
    count(STAT_DENSITY, _e164);
    uint _e167 = counters.detail;
    count(STAT_DETAIL, _e167);
    uint _e170 = counters.light;
    count(STAT_LIGHT, _e170);
    float _e173 = transmittance;
    if ((_e173 < 1.0)) {
        float _e176 = depth_sum;
        float _e177 = transmittance;
        depth = (_e176 / (1.0 - _e177));
    }
    float3 _e182 = radiance;
    float _e183 = transmittance;
    cloud_out[pixel_2] = float4(_e182, _e183);
    float _e186 = depth;
    depth_out[pixel_2] = float4(_e186, 0.0, 0.0, 0.0);
    return;
}

[numthreads(8, 8, 1)]
void composite(uint3 id_1 : SV_DispatchThreadID)
{
    float3 background = (float3)0;

    uint4 _e4 = frame.counts;
    if (any((id_1.xy >= _e4.xy))) {
        return;
    }
    uint2 pixel_3 = id_1.xy;
    const float3 _e9 = view_ray(pixel_3);
    float alt_6 = frame.camera_position.y;
    float4 cloud = cloud_in.Load(int3(pixel_3, int(0)));
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
    image_out[pixel_3] = float4(display, 1.0);
    return;
}
