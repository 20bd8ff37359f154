#!/bin/sh
# The GPU figures of docs/speed.md ("On a GPU"), on a machine with an NVIDIA GPU and none of
# kiri's packages: GL through glvnd from .gl/*.deb (libegl1, libglvnd0, libopengl0, libgl1,
# libglx0; the driver brings the rest), kiri from .gpu/kiri.tar.xz (scripts/gpu-bundle.sh).
# Run from the repository root; what it measures goes to $OUT (default /tmp/kiri-gpu):
#   smoke.png/.log      640x360 with the debug context on (any GL error is printed)
#   render1080.png/.log kiri render's cold start at 1920x1080, --timings
#   frame.log, frame.tgz  kiri bench --stage frame (1280x720 and 1920x1080, the CPU reference
#                       at 320x180), its frame.md and pictures
#   more.log, more.tgz  kiri bench --stage presets --stage end_to_end
# Times are taken with KIRI_GL_DEBUG=0 (no debug context).
set -u
OUT=${OUT:-/tmp/kiri-gpu}
mkdir -p "$OUT"
for f in .gl/*.deb; do dpkg -x "$f" /; done
ldconfig
K=/tmp/kiri-bundle
mkdir -p "$K"
tar xJf .gpu/kiri.tar.xz -C "$K"
vendor=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
if [ -f "$vendor" ] && ! ls /usr/share/glvnd/egl_vendor.d/*nvidia* >/dev/null 2>&1; then
  export __EGL_VENDOR_LIBRARY_FILENAMES="$vendor"
fi
nvidia-smi --query-gpu=name,driver_version,clocks.sm,clocks.mem,temperature.gpu --format=csv
ldd --version | head -1
nproc
export KIRI_DATA_DIR="$PWD/data"
scene=data/scenes/jacksboro.json
timeout 180 "$K/run" kiri render "$scene" -o "$OUT/smoke.png" --width 640 --height 360 --timings >"$OUT/smoke.log" 2>&1
cat "$OUT/smoke.log"
[ -s "$OUT/smoke.png" ] || { echo "gpu-bench: the smoke picture failed"; exit 1; }
export KIRI_GL_DEBUG=0
timeout 120 "$K/run" kiri render "$scene" -o "$OUT/render1080.png" --width 1920 --height 1080 --timings \
  >"$OUT/render1080.log" 2>&1
cat "$OUT/render1080.log"
timeout "${FRAME_TIMEOUT:-330}" "$K/run" kiri bench --stage frame -o /tmp/frame >"$OUT/frame.log" 2>&1
echo "bench exit $?"
tar czf "$OUT/frame.tgz" -C /tmp frame
cat /tmp/frame/frame.md 2>/dev/null || cat "$OUT/frame.log"
# The quality presets' cost and the cold start at every size, while the lease lasts.
timeout "${MORE_TIMEOUT:-150}" "$K/run" kiri bench --stage presets --stage end_to_end -o /tmp/more >"$OUT/more.log" 2>&1
echo "more exit $?"
tar czf "$OUT/more.tgz" -C /tmp more
tail -30 "$OUT/more.log"
