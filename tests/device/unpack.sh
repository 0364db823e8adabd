# Sourced by run.sh and bench.sh on the device machine, from the checkout's root, with the
# bundle's name (`bundle` or `bench`) and the xtask that makes it: checks the bundle is there,
# installs the Vulkan and EGL loaders from `.gl` where the machine has none, unpacks the bundle
# into $bundle with its bin/ on the PATH, and points the loaders at NVIDIA's driver where it is
# installed.
name=$1 task=$2
if [ ! -f ".device/$name.tar.gz" ]; then
    echo "error: .device/$name.tar.gz is missing: run \`cargo xtask $task\` and carry .device" >&2
    exit 2
fi
shopt -s nullglob
# (grep without -q: with pipefail, -q's early exit would fail ldconfig with SIGPIPE.)
if [ -d .gl ] && ! ldconfig -p | grep libvulkan.so.1 >/dev/null; then
    for f in .gl/*.deb; do dpkg -x "$f" /; done
    ldconfig
fi
bundle=$(mktemp -d)
tar xzf ".device/$name.tar.gz" -C "$bundle" || exit 2
export PATH="$bundle/bin:$PATH"
export XDG_RUNTIME_DIR="${XDG_RUNTIME_DIR:-$(mktemp -d)}"
icd=/usr/local/nvidia/share/vulkan/icd.d/nvidia_icd.json
[ -f "$icd" ] && export VK_DRIVER_FILES="$icd"
egl=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
[ -f "$egl" ] && export __EGL_VENDOR_LIBRARY_FILENAMES="$egl"
