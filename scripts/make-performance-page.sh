#!/usr/bin/env bash
# Regenerates docs/performance.md from one run of every benchmark: builds the
# benchmarks (Release) into BUILD_DIR, runs them one after another, keeps
# their outputs in RESULTS_DIR and renders the page from them alone
# (scripts/performance/render_page.py), so every figure on the page has its
# baseline from the same run, the command that made it and the CPU beside it.
#
#   scripts/make-performance-page.sh [BUILD_DIR]    # default build-bench; about 35 minutes (20 of soak)
#
# Environment:
#   QUICK=1        tiny sizes and times: checks that the pipeline works (CI), figures meaningless
#   OUTPUT=FILE    where the page goes (default docs/performance.md)
#   RESULTS=DIR    keep the raw outputs there (default: a temporary folder, removed)
#   REPETITIONS=N  Google Benchmark repetitions, medians reported (default 3)
#   SKIP_BUILD=1   use BUILD_DIR as it is
#   SOAK_SECONDS=N how long the soak runs (default 1200, the 20 minutes issue 20 asks for; QUICK: 8)
#   BEFORE_BENCH=DIR an earlier build's bench folder: the cold tiles run its cold_tile_latency
#                  beside this build's, ROUNDS times (default 3), taking turns going first
#   ONLY=cold_tiles run the cold tiles alone and put their section into OUTPUT, in place of
#                  the one there, as measured apart from the page's run (REASON=TEXT says why)
set -euo pipefail
cd "$(dirname "$0")/.."

build=${1:-build-bench}
output=${OUTPUT:-docs/performance.md}
quick=${QUICK:-0}
repetitions=${REPETITIONS:-3}
((quick)) && repetitions=1
if [[ -n ${RESULTS:-} ]]; then
  results=$RESULTS
  mkdir -p "$results"
else
  results=$(mktemp -d /tmp/scallop-performance-XXXXXX)
  trap 'rm -rf "$results"' EXIT
fi

only=${ONLY:-}
if [[ -n $only && $only != cold_tiles ]]; then
  echo "make-performance-page: ONLY takes cold_tiles" >&2
  exit 2
fi
tiles=400
((quick)) && tiles=10

targets=(samplers_bench field_bench plane_bench nearest_bench deterministic_math_bench
  follow_bench cold_tile_latency load_generator null_server scallopd delaunay_verifier_test
  http_tiles_bench nginx_tiles_bench wire_bench layers_bench soak_load warm_answer_bench)
[[ -n $only ]] && targets=(cold_tile_latency)
if [[ ${SKIP_BUILD:-0} != 1 ]]; then
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$build" -j2 --target "${targets[@]}"
fi

load_average() { cut -d' ' -f1-3 /proc/loadavg | sed 's/ /, /g'; }
load_before=$(load_average)
declare -A commands

# What the page says about the run: the machine, the code, the commands.
write_run_json() {
  local commands_json
  commands_json=$(for name in "${!commands[@]}"; do printf '%s\0%s\0' "$name" "${commands[$name]}"; done |
    python3 -c 'import json, sys
parts = sys.stdin.read().split("\0")[:-1]
print(json.dumps(dict(zip(parts[::2], parts[1::2]))))')
  python3 - "$results/run.json" <<EOF
import json, sys
json.dump({
    "commit": "$(git rev-parse --short HEAD)$(git diff --quiet HEAD -- core server client bench || echo ' with local changes')",
    "date": "$(date -u '+%Y-%m-%d %H:%M UTC')",
    "cpu": "$(lscpu | sed -n 's/^Model name: *//p' | head -1)",
    "cores": "$(nproc)",
    "load_before": "$load_before",
    "load_after": "$(load_average)",
    "repetitions": $repetitions,
    "commands": $commands_json,
}, open(sys.argv[1], "w"), indent=1)
EOF
}

# The engine alone on cold tiles, on one engine thread and two; with BEFORE_BENCH, beside an
# earlier build's, round by round.
cold_tiles() {
  local bench=$build/bench/cold_tile_latency
  echo "== cold_tile_latency" >&2
  commands[cold_tile_latency]="$bench $tiles 64; $bench $tiles 64 2"
  { "$bench" "$tiles" 64 && "$bench" "$tiles" 64 2; } >"$results/cold_tile_latency.txt"
  [[ -n ${BEFORE_BENCH:-} ]] || return 0
  local rounds=${ROUNDS:-3} round threads which order
  commands[cold_tile_pairs]="{before: $BEFORE_BENCH, after: $build/bench}/cold_tile_latency $tiles 64 {1, 2}, $rounds rounds"
  for ((round = 1; round <= rounds; ++round)); do
    order=(before after)
    ((round % 2 == 0)) && order=(after before)
    for threads in 1 2; do
      for which in "${order[@]}"; do
        bench=$build/bench/cold_tile_latency
        [[ $which == before ]] && bench=$BEFORE_BENCH/cold_tile_latency
        echo "$which $threads | $("$bench" "$tiles" 64 "$threads")"
      done
    done
  done >"$results/cold_tile_pairs.txt"
}

if [[ -n $only ]]; then
  cold_tiles
  write_run_json
  python3 scripts/performance/render_page.py "$results" --apart "Cold tiles" "$output" \
    "${REASON:-}" >"$results/page.md"
  cp "$results/page.md" "$output"
  echo "make-performance-page: wrote the cold tiles into $output, measured apart" >&2
  exit 0
fi

# bench NAME [ARGS...]: runs a Google Benchmark program into NAME.json (with the page's
# repetitions, unless ARGS set their own).
bench() {
  local name=$1
  shift
  local repeat=(--benchmark_repetitions="$repetitions")
  [[ " $* " == *" --benchmark_repetitions="* ]] && repeat=()
  local args=("${repeat[@]}" --benchmark_report_aggregates_only=true "$@")
  commands[$name]="$build/bench/$name ${args[*]}"
  echo "== $name" >&2
  "$build/bench/$name" "${args[@]}" --benchmark_out="$results/$name.json" \
    --benchmark_out_format=json >"$results/$name.console"
}

if ((quick)); then
  bench samplers_bench --benchmark_filter='/1000/' --benchmark_min_time=0.01
  bench field_bench --benchmark_filter=smoke --benchmark_min_time=0.01
  bench layers_bench --benchmark_filter=smoke --benchmark_min_time=0.01
  bench plane_bench --benchmark_min_time=0.01
  bench nearest_bench --benchmark_min_time=0.01
  bench deterministic_math_bench --benchmark_filter='Atan2' --benchmark_min_time=0.01
  FOLLOW_BENCH_WALK_D=64 bench follow_bench
  bench wire_bench --benchmark_min_time=0.01
  bench warm_answer_bench --benchmark_min_time=0.01
  load_env=(DURATION=1 REQUESTS=50 STREAMS=1 REPEATS=1 ENGINE_TILES=10 CACHE_MB=8)
  http_tiles_args=(0 2 1 1 1)
  nginx_tiles_args=(0 2 1 1)
  soak_seconds=8 soak_interval=1
else
  bench samplers_bench
  bench field_bench --benchmark_filter='1M|250k'
  bench layers_bench --benchmark_filter=250k --benchmark_enable_random_interleaving=true --benchmark_repetitions=5
  bench plane_bench
  bench nearest_bench --benchmark_enable_random_interleaving=true --benchmark_repetitions=9
  bench deterministic_math_bench
  bench follow_bench
  bench wire_bench --benchmark_min_time=0.2
  bench warm_answer_bench --benchmark_enable_random_interleaving=true
  load_env=(DURATION=10 STREAMS="1 4" REPEATS=3)
  http_tiles_args=(1 16 4 1 9)
  nginx_tiles_args=(1 16 4 7)
  soak_seconds=${SOAK_SECONDS:-1200} soak_interval=5
fi

cold_tiles

echo "== verifier" >&2
commands[verifier]="$build/tests/delaunay_verifier_test --gtest_filter=*MillionPoints*"
"$build/tests/delaunay_verifier_test" --gtest_filter='*MillionPoints*' >"$results/verifier.txt"

echo "== http_tiles_bench" >&2
commands[http_tiles]="$build/bench/http_tiles_bench ${http_tiles_args[*]}"
"$build/bench/http_tiles_bench" "${http_tiles_args[@]}" 2>/dev/null >"$results/http_tiles.txt"

echo "== nginx_tiles_bench" >&2
commands[nginx_tiles]="$build/bench/nginx_tiles_bench ${nginx_tiles_args[*]}"
"$build/bench/nginx_tiles_bench" "${nginx_tiles_args[@]}" 2>/dev/null >"$results/nginx_tiles.txt"

echo "== load" >&2
commands[load]="${load_env[*]} bench/run-load-benchmark.sh $build"
env "${load_env[@]}" bench/run-load-benchmark.sh "$build" >"$results/load.txt"

# Last, since it is long and measures resources, not speed. A failed soak stops the script:
# the page is not rewritten without it.
echo "== soak" >&2
commands[soak]="scripts/soak.sh $build $soak_seconds"
OUT="$results/soak-samples.tsv" INTERVAL=$soak_interval scripts/soak.sh "$build" "$soak_seconds" >"$results/soak.txt" 2>&1

write_run_json

python3 scripts/performance/render_page.py "$results" >"$output"
echo "make-performance-page: wrote $output" >&2
