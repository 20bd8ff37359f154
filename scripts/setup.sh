#!/bin/sh
# Installs every Debian 12 package kiri builds, tests and benchmarks with.
# Idempotent: packages already present are skipped by apt, so re-running is cheap.
set -eu
PACKAGES="
cmake g++ make pkg-config ccache git
libopenmesh-dev libcgal-dev libgmp-dev libmpfr-dev libboost-dev libosd-dev libglm-dev
libglfw3-dev libepoxy-dev libegl-dev libegl-mesa0 libgl1-mesa-dri libgl-dev
libgdal-dev gdal-bin libstb-dev nlohmann-json3-dev libcli11-dev libtinygltf-dev
libopenvdb-dev libboost-iostreams-dev libtbb-dev libeigen3-dev libopenexr-dev zlib1g-dev
libgtest-dev libgmock-dev libbenchmark-dev libimgui-dev libxtst-dev
xvfb xauth gnuplot-nox clang libclang-rt-14-dev clang-format-14
"
missing=""
SUDO=""
[ "$(id -u)" -eq 0 ] || SUDO="sudo"
for p in $PACKAGES; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing="$missing $p"
done
if [ -n "$missing" ]; then
  echo "kiri setup: installing$missing"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq $missing
fi
# The glTF validator (npm); Node may come from the image rather than Debian.
if ! command -v npm >/dev/null 2>&1; then
  DEBIAN_FRONTEND=noninteractive ${SUDO:-} apt-get install -y -qq nodejs npm
fi
# The Khronos glTF validator (tests run it on exported .glb files), pinned in tools/gltf-validator.
VALIDATOR_DIR="$(dirname "$0")/../tools/gltf-validator"
if [ ! -f "$VALIDATOR_DIR/node_modules/gltf-validator/package.json" ]; then
  (cd "$VALIDATOR_DIR" && npm install --no-audit --no-fund --loglevel=error)
fi
