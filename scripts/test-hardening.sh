#!/bin/sh
# CI's hardening jobs (docs/hardening.md): the unit tests built with
# AddressSanitizer + UndefinedBehaviorSanitizer (any report fails), then a short run of each
# libFuzzer target (KIRI_FUZZ_SECONDS each, default 30). .ci/run calls this before
# scripts/test.sh, whose ctest summary stays the last thing CI prints.
set -eu
cd "$(dirname "$0")/.."
sh scripts/setup.sh
start=$(date +%s)
# One instrumented build (clang, -O1 without debug info: the sanitizers need no more) holds
# kiri_geometry, the unit tests (geometry, no GL) and the fuzzers: the library is compiled
# once for both jobs. The GL and CLI tests under the sanitizers build everything
# (docs/hardening.md): too slow for CI's 2 cores.
KIRI_FUZZ_TESTS=ON sh scripts/fuzz.sh build
ASAN_OPTIONS="detect_leaks=1:strict_string_checks=1:check_initialization_order=1" \
LSAN_OPTIONS="suppressions=$(pwd)/tests/sanitizer/lsan.supp:print_suppressions=0" \
UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1" \
  ctest --test-dir build/fuzz --output-on-failure -j"$(nproc)" -L unit
echo "kiri hardening: sanitizer build and tests in $(( $(date +%s) - start )) s"
start=$(date +%s)
KIRI_FUZZ_TESTS=ON sh scripts/fuzz.sh "${KIRI_FUZZ_SECONDS:-30}"
echo "kiri hardening: fuzzers in $(( $(date +%s) - start )) s"
