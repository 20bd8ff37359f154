#!/bin/sh
# Cross-checks kiri's light in the fog against Blender's Cycles (docs/medium.md, "Against a path
# tracer"): for each view, kiri's medium.vdb rendered by Cycles (scripts/cycles_medium.py) against
# `kiri render --mode path` (the path tracer) and `--mode reference` (the octave lighting model) of
# the same scene, all in a black world with a black ground (only the sun lights the fog), linear
# radiance at 160x90. Prints, per pair, the mean brightness ratio and the mean relative error of
# 4x4-pixel blocks.
#
#   sh scripts/crosscheck-cycles.sh [OUT_DIR]
#
# Views: a uniform 100 m slab (sigma_t 0.02 1/m, albedo 0.99, g 0.8, on flat ground, sun 30
# degrees up) seen from above and from inside towards the sun; the default scene
# data/scenes/jacksboro.json from its first camera, its Medium alone (medium.vdb holds no height
# fog, so the copy drops the froxel height fog). Environment: KIRI (the kiri executable; default
# build/test/apps/kiri/kiri), BLENDER (default blender), CYCLES_SAMPLES (default 512),
# KIRI_SAMPLES (default 1024), VIEWS (default "slab_above slab_inside jacksboro"). Without
# Blender it prints a message and exits 0 (the test suite never needs Blender).
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(dirname "$here")
KIRI=${KIRI:-$root/build/test/apps/kiri/kiri}
BLENDER=${BLENDER:-blender}
CYCLES_SAMPLES=${CYCLES_SAMPLES:-512}
KIRI_SAMPLES=${KIRI_SAMPLES:-1024}
VIEWS=${VIEWS:-slab_above slab_inside jacksboro}
out=${1:-${TMPDIR:-/tmp}/kiri-crosscheck}

if ! command -v "$BLENDER" >/dev/null 2>&1; then
  echo "crosscheck-cycles: Blender not found (Debian: apt-get install blender): skipped"
  exit 0
fi
if [ ! -x "$KIRI" ]; then
  echo "crosscheck-cycles: no kiri executable at $KIRI (build it, or set KIRI)" >&2
  exit 2
fi
mkdir -p "$out"

# The scenes: a flat 10 km terrain at z = 0 (an ESRI ASCII grid) filled with fog up to 100 m,
# uniform (top_density 1, no noise); and the default scene without its height fog.
python3 - "$out" "$root" <<'EOF'
import json, math, os, sys
out, root = sys.argv[1], sys.argv[2]
n, cell = 201, 50.0
with open(os.path.join(out, "flat.asc"), "w") as f:
    f.write("ncols %d\nnrows %d\nxllcorner 0\nyllcorner 0\ncellsize %g\nNODATA_value -9999\n" % (n, n, cell))
    for _ in range(n):
        f.write(" ".join(["0"] * n) + "\n")
e = math.radians(30.0)
sun = [-math.cos(e) / math.sqrt(2.0), math.cos(e) / math.sqrt(2.0), math.sin(e)]
inside = [0.0, 0.0, 50.0]
slab = {
    "terrain": {"path": "flat.asc"},
    "cameras": [
        {"name": "above", "position": [0, -400, 600], "target": [0, 0, 50], "fov": 40},
        {"name": "inside", "position": inside, "target": [inside[i] + 1000.0 * sun[i] for i in range(3)], "fov": 60},
    ],
    "sun": {"direction": sun, "color": [1, 1, 1], "intensity": 3.0, "ambient": [0, 0, 0]},
    "fog": {"fill": {"seeds": "all", "top": 100}},
    "layers": {"detail": 0},
    "medium": {"extinction": 0.02, "albedo": 0.99, "anisotropy": 0.8, "top_density": 1},
}
json.dump(slab, open(os.path.join(out, "slab.json"), "w"), indent=1)
scene = json.load(open(os.path.join(root, "data/scenes/jacksboro.json")))
scene["terrain"]["path"] = os.path.normpath(os.path.join(root, "data/scenes", scene["terrain"]["path"]))
scene.get("froxel", {}).pop("height_fog", None)
json.dump(scene, open(os.path.join(out, "jacksboro.json"), "w"), indent=1)
EOF

cycles() {
  "$BLENDER" -b --factory-startup --python "$here/cycles_medium.py" -- "$@" 2>&1 | grep -E "^(cycles_medium|mean)|rror" || true
}

authored=""
for view in $VIEWS; do
  case $view in
    slab_above) scene=slab; camera=above; ground="" ;;
    slab_inside) scene=slab; camera=inside; ground="" ;;
    jacksboro) scene=jacksboro; camera=default; ground="--ground" ;;
    *) echo "crosscheck-cycles: unknown view $view" >&2; exit 2 ;;
  esac
  dir="$out/$scene"
  case " $authored " in
    *" $scene "*) ;;
    *) "$KIRI" author "$out/$scene.json" -o "$dir" >/dev/null; authored="$authored $scene" ;;
  esac
  common="--width 160 --height 90 --camera $camera --no-sky --black-ground"
  "$KIRI" render "$out/$scene.json" -o "$dir/$view.path.exr" --mode path --samples "$KIRI_SAMPLES" $common \
    2>&1 | grep -E "standard error|mode path" || true
  "$KIRI" render "$out/$scene.json" -o "$dir/$view.reference.exr" --mode reference $common 2>&1 | grep "mode" || true
  start=$(date +%s)
  rm -f "$dir/$view.cycles.exr"
  cycles render "$out/$scene.json" "$dir" "$dir/$view.cycles.exr" --camera "$camera" --samples "$CYCLES_SAMPLES" $ground
  if [ ! -f "$dir/$view.cycles.exr" ]; then
    echo "crosscheck-cycles: $view: Cycles wrote no image" >&2
    exit 2
  fi
  echo "crosscheck-cycles: $view: Cycles took $(( $(date +%s) - start )) s"
  echo "== $view: kiri path tracer / Cycles"
  cycles compare "$dir/$view.path.exr" "$dir/$view.cycles.exr"
  echo "== $view: kiri reference (octaves) / Cycles"
  cycles compare "$dir/$view.reference.exr" "$dir/$view.cycles.exr"
  echo "== $view: kiri reference (octaves) / kiri path tracer"
  cycles compare "$dir/$view.reference.exr" "$dir/$view.path.exr"
done
