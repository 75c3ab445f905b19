#!/usr/bin/env bash
# Long fuzzing runs (docs/fuzzing.md): builds the libFuzzer targets with Clang
# (into BUILD_DIR, default build-fuzz), runs each for SECONDS (default 3600)
# from its corpus in fuzz/corpus/, then merges what it found back into that
# corpus (-merge=1 keeps only inputs that add coverage, so the corpora stay
# small). A crash, leak, timeout or failed invariant stops the run, with the
# input left in the current folder. Prints a line per target passed, for
# docs/fuzzing.md: target, seconds run clean, executions, corpus size.
#
#   scripts/fuzz-long.sh [SECONDS] [TARGET...]      (default: every target)
#   env: BUILD_DIR (build-fuzz), JOBS (build jobs, 2), SKIP_BUILD=1
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-3600}
shift || true
build=${BUILD_DIR:-build-fuzz}
jobs=${JOBS:-2}

if [[ -z ${SKIP_BUILD:-} ]]; then
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSCALLOP_WERROR=ON \
    -DCMAKE_CXX_COMPILER=clang++ -DSCALLOP_BUILD_FUZZERS=ON -DSCALLOP_BUILD_BENCH=OFF
  cmake --build "$build" -j"$jobs" --target fuzzers
fi
targets=("$@")
if ((${#targets[@]} == 0)); then
  for source in fuzz/*_fuzzer.cc; do targets+=("$(basename "$source" .cc)"); done
fi

for target in "${targets[@]}"; do
  corpus=fuzz/corpus/$target
  found=$(mktemp -d /tmp/scallop-fuzz-long-XXXXXX)
  options=(-max_total_time="$seconds" -timeout=30 -rss_limit_mb=2048 -max_len=8192
           -print_final_stats=1)
  [[ ! -f fuzz/dictionaries/$target.dict ]] || options+=(-dict="fuzz/dictionaries/$target.dict")
  echo "fuzz-long: $target for $seconds s"
  "$build/fuzz/$target" "${options[@]}" "$found" "$corpus" 2>"$found.log" || {
    tail -60 "$found.log" >&2
    echo "fuzz-long: $target FAILED (input saved in $PWD)" >&2
    exit 1
  }
  executions=$(sed -n 's/^stat::number_of_executed_units: *//p' "$found.log")
  "$build/fuzz/$target" -merge=1 "$corpus" "$found" 2>/dev/null
  rm -rf "$found" "$found.log"
  echo "fuzz-long: $target $seconds s clean, $executions executions, corpus $(ls "$corpus" | wc -l) files"
done
