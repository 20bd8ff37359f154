#!/bin/sh
# CI's hardening jobs (docs/hardening.md): the unit tests built with
# AddressSanitizer + UndefinedBehaviorSanitizer (any report fails), then a short run of each
# libFuzzer target (KIRI_FUZZ_SECONDS each, default 30). .ci/run calls this before
# scripts/test.sh, whose ctest summary stays the last thing CI prints.
set -eu
cd "$(dirname "$0")/.."
sh scripts/setup.sh
start=$(date +%s)
# The unit tests (geometry, no GL) against kiri_geometry instrumented at -O1 without debug info:
# the sanitizers need no more (docs/hardening.md has the figures). The GL and CLI tests under
# the sanitizers build everything: too slow for CI's 2 cores.
cmake -S . -B build/asan -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS="-O1" -DKIRI_SANITIZE=ON \
  -DKIRI_BUILD_RENDER=OFF -DKIRI_BUILD_APPS=OFF >/dev/null
cmake --build build/asan -j"$(nproc)"
ASAN_OPTIONS="detect_leaks=1:strict_string_checks=1:check_initialization_order=1" \
LSAN_OPTIONS="suppressions=$(pwd)/tests/sanitizer/lsan.supp:print_suppressions=0" \
UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1" \
  ctest --test-dir build/asan --output-on-failure -j"$(nproc)" -L unit
echo "kiri hardening: sanitizer build and tests in $(( $(date +%s) - start )) s"
start=$(date +%s)
sh scripts/fuzz.sh "${KIRI_FUZZ_SECONDS:-30}"
echo "kiri hardening: fuzzers in $(( $(date +%s) - start )) s"
