struct Frame {
    float4 camera_position;
    uint4 resolution;
};

struct Stats {
    uint pixels;
};

static const bool STATS = true;

cbuffer frame : register(b0) { Frame frame; }
RWTexture2D<float4> out_image : register(u1);
RWByteAddressBuffer stats : register(u2);

[numthreads(8, 8, 1)]
void march(uint3 id : SV_DispatchThreadID)
{
    uint4 _e4 = frame.resolution;
    if (any((id.xy >= _e4.xy))) {
        return;
    }
    if (STATS) {
        uint _e12; stats.InterlockedAdd(0, 1u, _e12);
    }
    uint4 _e20 = frame.resolution;
    float2 uv = ((float2(id.xy) + (0.5).xx) / float2(_e20.xy));
    out_image[id.xy] = float4(uv, 0.0, 1.0);
    return;
}
