#!/bin/sh
# Quick start, command 1: set up, build (Release) and render the default scene to a PNG.
set -eu
cd "$(dirname "$0")/.."
sh scripts/setup.sh
cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release -DKIRI_BUILD_TESTS=OFF >/dev/null
cmake --build build/release -j"$(nproc)"
mkdir -p out
./build/release/apps/kiri/kiri render data/scenes/jacksboro.json -o out/jacksboro.png
