// language: metal2.1
#include <metal_stdlib>
#include <simd/simd.h>

using metal::uint;

struct Frame {
    metal::float4 camera_position;
    metal::uint4 resolution;
};
struct Stats {
    metal::atomic_uint pixels;
};
constant bool STATS = false;

struct marchInput {
};
[[max_total_threads_per_threadgroup(64)]] kernel void march(
  metal::uint3 id [[thread_position_in_grid]]
, constant Frame& frame [[user(fake0)]]
, metal::texture2d<float, metal::access::write> out_image [[user(fake0)]]
, device Stats& stats [[user(fake0)]]
) {
    metal::uint4 _e4 = frame.resolution;
    if (metal::any(id.xy >= _e4.xy)) {
        return;
    }
    if (STATS) {
        uint _e12 = metal::atomic_fetch_add_explicit(&stats.pixels, 1u, metal::memory_order_relaxed);
    }
    metal::uint4 _e20 = frame.resolution;
    metal::float2 uv = (static_cast<metal::float2>(id.xy) + metal::float2(0.5)) / static_cast<metal::float2>(_e20.xy);
    out_image.write(metal::float4(uv, 0.0, 1.0), metal::uint2(id.xy));
    return;
}
