// language: metal2.1
#include <metal_stdlib>
#include <simd/simd.h>

using metal::uint;


struct present_vertexInput {
};
struct present_vertexOutput {
    metal::float4 member [[position]];
};
vertex present_vertexOutput present_vertex(
  uint i [[vertex_id]]
) {
    metal::float2 corner = metal::float2(static_cast<float>((i << 1u) & 2u), static_cast<float>(i & 2u));
    return present_vertexOutput { metal::float4((corner * 2.0) - metal::float2(1.0), 0.0, 1.0) };
}

metal::uint2 naga_f2u32(metal::float2 value) {
    return static_cast<metal::uint2>(metal::clamp(value, 0.0, 4294967000.0));
}


struct present_fragmentInput {
};
struct present_fragmentOutput {
    metal::float4 member_1 [[color(0)]];
};
fragment present_fragmentOutput present_fragment(
  metal::float4 position [[position]]
, metal::texture2d<float, metal::access::sample> image_in [[user(fake0)]]
) {
    metal::float4 _e5 = image_in.read(metal::uint2(naga_f2u32(position.xy)), 0);
    return present_fragmentOutput { _e5 };
}


struct hdr_fragmentInput {
};
struct hdr_fragmentOutput {
    metal::float4 member_2 [[color(0)]];
};
fragment hdr_fragmentOutput hdr_fragment(
  metal::float4 position_1 [[position]]
, metal::texture2d<float, metal::access::sample> radiance_in [[user(fake0)]]
) {
    metal::float4 _e5 = radiance_in.read(metal::uint2(naga_f2u32(position_1.xy)), 0);
    return hdr_fragmentOutput { _e5 };
}
