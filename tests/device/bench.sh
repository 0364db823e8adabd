#!/usr/bin/env bash
# The GPU benchmark on a machine with a real GPU and no cargo (the `device` machine), from the
# checkout's root there:
#
#   here:  cargo xtask device-bench [--peer-wgsl DIR]   # writes .device/bench.tar.gz (ignored)
#   there: bash tests/device/bench.sh [gpu-bench options]
#
# Runs `stratus gpu-bench` (every preset on wgpu and ash, temporal off, 1/4 and 1/16, at
# 1920x1080 and 3840x2160, unless the options given say otherwise; `stratus gpu-bench --help`)
# and, where the bundle holds the peer harness, the peer at 1920x1080 with its 12 view and 6
# light steps beside `stratus gpu-bench --presets cumulus-noon` at the same steps. The table
# (table.md), the JSON and the logs go to $OUT (the device tool brings that folder back), or
# to target/device-bench. `.gl` holds the Vulkan loader as .deb files where the machine has
# none (the device tool's README says how to download them).
set -uo pipefail
root=$(pwd)
# shellcheck source=tests/device/unpack.sh
source "$root/tests/device/unpack.sh" bench device-bench
out="${OUT:-$root/target/device-bench}"
mkdir -p "$out"
rm -f "$out/table.md" "$out/results.json"
stratus gpu-bench --out "$out" "$@" 2>&1 | tee "$out/gpu-bench.log"
rc=${PIPESTATUS[0]}
if [ "$rc" -ne 0 ]; then
    echo "gpu-bench failed (exit $rc); log in $out/gpu-bench.log" >&2
    exit "$rc"
fi
if [ -x "$bundle/bin/peer-bench" ] && [ -d "$bundle/peer-wgsl" ]; then
    # The peer at its defaults (12 view steps, 6 light steps), and Stratus's march at the
    # same steps on the same frame size: the comparison the peer-bench README describes.
    # PEER_SIZE, PEER_FRAMES and PEER_WARMUP change the defaults (a small trial run).
    size=${PEER_SIZE:-1920x1080} frames=${PEER_FRAMES:-120} warmup=${PEER_WARMUP:-30}
    peer-bench --wgsl-dir "$bundle/peer-wgsl" --out "$out/peer" --width "${size%x*}" --height "${size#*x}" \
        --frames "$frames" --warmup "$warmup" >"$out/peer.log" 2>&1 || { echo "peer-bench failed; see $out/peer.log" >&2; exit 1; }
    printf 'base = "cumulus-noon"\n[quality]\nview_steps = 12\nlight_steps = 6\n' >"$out/equal-steps.toml"
    stratus render --scene "$out/equal-steps.toml" --size "$size" --frames "$frames" --temporal off \
        --backend wgpu --stats "$out/stratus-equal-steps.json" --out "$out/stratus-equal-steps.png" \
        >"$out/stratus-equal-steps.log" 2>&1 || { echo "stratus at equal steps failed; see $out/stratus-equal-steps.log" >&2; exit 1; }
    peer_ms=$(grep -o 'update_gpu_median_ms=[0-9.]*' "$out/peer.log" | cut -d= -f2)
    march_ms=$(grep -o 'march [0-9.]* ms' "$out/stratus-equal-steps.log" | head -n 1 | cut -d' ' -f2)
    {
        echo
        echo "## Against the peer ($size, 12 view and 6 light steps, wgpu; medians of $frames frames, the peer's after $warmup more of warm-up)"
        echo
        echo "| | GPU ms/frame |"
        echo "|---|---|"
        echo "| evroon/bevy-volumetric-clouds \`update\` | ${peer_ms:-not measured} |"
        echo "| Stratus \`march\` (cumulus-noon at 12 and 6 steps) | ${march_ms:-not measured} |"
        if [ -n "$peer_ms" ] && [ -n "$march_ms" ]; then
            awk -v p="$peer_ms" -v s="$march_ms" 'BEGIN { printf "\nStratus is %.2fx the peer'"'"'s speed.\n", p / s }'
        fi
        echo
        grep '^SUMMARY' "$out/peer.log"
    } >>"$out/table.md"
else
    printf '\nThe peer was not packed (`cargo xtask device-bench --peer-wgsl DIR`).\n' >>"$out/table.md"
fi
echo "gpu-bench: table in $out/table.md"
