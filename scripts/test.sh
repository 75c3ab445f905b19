#!/usr/bin/env bash
# Installs what is missing, builds everything with warnings as errors, and runs
# every test twice: in a Release build and under AddressSanitizer +
# UndefinedBehaviorSanitizer; the golden tests also with Clang, at -O0 and on
# aarch64 (scripts/test-portability.sh); the tests that run threads under
# ThreadSanitizer (scripts/test-tsan.sh); then each fuzz target for 15 s.
# Run from anywhere, as root on a fresh Debian 12.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/install-deps.sh

jobs=2
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DSCALLOP_WERROR=ON
cmake --build build -j"$jobs"
ctest --test-dir build --output-on-failure -j"$jobs"

# The same bits with Clang, at -O0 and on aarch64 (under qemu), against the
# Release build above (docs/determinism.md).
bash scripts/test-portability.sh build

# The sanitizer build skips the benchmarks: they test speed, not correctness.
cmake -S . -B build-sanitize -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSCALLOP_WERROR=ON \
  -DSCALLOP_SANITIZE=ON -DSCALLOP_BUILD_BENCH=OFF
cmake --build build-sanitize -j"$jobs"
ctest --test-dir build-sanitize --output-on-failure -j"$jobs"

# ThreadSanitizer on the tests labelled "threads" (the region cache, the plane
# engine's concurrent callers and schedules, layered and radius-field worlds on
# several threads, the shared nearest lookups, scallopd's client limits): it
# builds only the core and those tests, about 4 minutes in all.
JOBS=$jobs bash scripts/test-tsan.sh build-tsan

# The libFuzzer targets, 15 s each from their corpora (docs/fuzzing.md).
# Clang builds only them and what they link, with ASan and UBSan.
cmake -S . -B build-fuzz -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSCALLOP_WERROR=ON \
  -DCMAKE_CXX_COMPILER=clang++ -DSCALLOP_BUILD_FUZZERS=ON -DSCALLOP_BUILD_BENCH=OFF
cmake --build build-fuzz -j"$jobs" --target fuzzers
ctest --test-dir build-fuzz --output-on-failure -j"$jobs" -L fuzz
