#!/usr/bin/env bash
# Runs the conformance suite on a machine with a real GPU and no cargo (the `device` machine),
# from the checkout's root there:
#
#   here:  cargo xtask device-bundle          # writes .device/bundle.tar.gz (ignored by git)
#   there: bash tests/device/run.sh           # with `.device` (and `.gl`) carried along
#
# `.gl` holds the Vulkan and EGL loaders as .deb files where the machine has none (the device
# tool's README says how to download them). The suite reads the goldens, snapshots and
# spirv-out/ of this checkout (INSTA_WORKSPACE_ROOT) and judges them by the device's class
# (tests/tests/conformance/report.rs, `DeviceClass`): on anything but lavapipe the goldens are
# held to the measured cross-device bounds and the counters to the cross-device model
# (tests/tests/conformance/spread.rs). The results table,
# the log and any failure images go to $OUT (the device tool brings that folder back), or to
# target/device-out.
set -uo pipefail
root=$(pwd)
# shellcheck source=tests/device/unpack.sh
source "$root/tests/device/unpack.sh" bundle device-bundle
export VK_LAYER_PATH="$bundle/layers"
export INSTA_WORKSPACE_ROOT="$root" INSTA_UPDATE=no
out="${OUT:-$root/target/device-out}"
mkdir -p "$out" "$root/target"
# A table or failure images left by an earlier run must not pass for this run's.
rm -rf "$root/target/conformance.md" "$root/target/conformance-failures"
"$bundle/bin/conformance" 2>&1 | tee "$out/conformance.log"
rc=${PIPESTATUS[0]}
cp "$root/target/conformance.md" "$out/" 2>/dev/null
if [ -d "$root/target/conformance-failures" ]; then
    tar czf "$out/conformance-failures.tar.gz" -C "$root/target" conformance-failures
fi
echo "conformance exit status $rc; results in $out"
exit "$rc"
