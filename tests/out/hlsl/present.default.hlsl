Texture2D<float4> image_in : register(t0);
Texture2D<float4> radiance_in : register(t1);

struct FragmentInput_present_fragment {
    float4 position_2 : SV_Position;
};

struct FragmentInput_hdr_fragment {
    float4 position_3 : SV_Position;
};

float4 present_vertex(uint i : SV_VertexID) : SV_Position
{
    float2 corner = float2(float(((i << 1u) & 2u)), float((i & 2u)));
    return float4(((corner * 2.0) - (1.0).xx), 0.0, 1.0);
}

uint2 naga_f2u32(float2 value) {
    return uint2(clamp(value, 0.0, 4294967000.0));
}

float4 present_fragment(FragmentInput_present_fragment fragmentinput_present_fragment) : SV_Target0
{
    float4 position = fragmentinput_present_fragment.position_2;
    float4 _e5 = image_in.Load(int3(naga_f2u32(position.xy), int(0)));
    return _e5;
}

float4 hdr_fragment(FragmentInput_hdr_fragment fragmentinput_hdr_fragment) : SV_Target0
{
    float4 position_1 = fragmentinput_hdr_fragment.position_3;
    float4 _e5 = radiance_in.Load(int3(naga_f2u32(position_1.xy), int(0)));
    return _e5;
}
