#!/bin/sh
# Quick start, command 2: set up, build everything and run the whole test suite through ctest.
# Extra arguments go to ctest, e.g. `sh scripts/test.sh -L unit`.
set -eu
cd "$(dirname "$0")/.."
sh scripts/setup.sh
cmake -S . -B build/test -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build/test -j"$(nproc)"
cd build/test
ctest --output-on-failure -j"$(nproc)" "$@"
