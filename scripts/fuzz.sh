#!/bin/sh
# Builds the libFuzzer targets (clang, ASan + UBSan, kiri_geometry instrumented) and runs each
# for SECONDS (default 45). Crashes land in build/fuzz/findings/; every crash found becomes a
# case of the bad-input corpus in tests/. A longer run: sh scripts/fuzz.sh 3600.
set -eu
cd "$(dirname "$0")/.."
seconds=${1:-45}
# -O0 without debug info keeps the instrumented build short on CI's 2 cores (KIRI_FUZZ_OPT=-O1
# for more executions a second in a long run); to debug a finding, rebuild with
# -DCMAKE_BUILD_TYPE=RelWithDebInfo for line numbers.
CC=clang CXX=clang++ cmake -S . -B build/fuzz -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS="${KIRI_FUZZ_OPT:--O0}" -DKIRI_BUILD_FUZZERS=ON \
  -DKIRI_BUILD_RENDER=OFF -DKIRI_BUILD_APPS=OFF -DKIRI_BUILD_TESTS=OFF -DBUILD_SHARED_LIBS=OFF >/dev/null
cmake --build build/fuzz -j"$(nproc)"
mkdir -p build/fuzz/findings
for target in scene dem; do
  corpus=build/fuzz/corpus-$target
  mkdir -p "$corpus"
  echo "kiri fuzz: $target for $seconds s"
  ./build/fuzz/fuzz/${target}_fuzzer -max_total_time="$seconds" -max_len=65536 -rss_limit_mb=2048 \
    -print_final_stats=1 -artifact_prefix=build/fuzz/findings/$target- "$corpus" fuzz/corpus/$target 2>&1 |
    grep -E "^(Done|stat::number_of_executed_units|stat::peak_rss_mb|==[0-9]+==ERROR|SUMMARY|.*deadly signal)" || true
  if ls build/fuzz/findings/$target-* >/dev/null 2>&1; then
    echo "kiri fuzz: $target found crashes: $(ls build/fuzz/findings/$target-*)"
    exit 1
  fi
done
