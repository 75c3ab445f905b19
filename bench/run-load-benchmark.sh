#!/usr/bin/env bash
# The service load benchmark of issue 7 (docs/performance.md, "Service under
# load"). Builds nothing: give it a build folder holding scallopd,
# load_generator and null_server. It starts scallopd (with a cache budget)
# and the null server on free loopback ports, runs the load generator warm
# against both and cold against scallopd with each stream count, samples the
# servers' resident memory throughout, and prints a table with the ratio
# warm / null. All servers run side by side on this machine, in one run.
#
# A warm round is one load_generator run that drives every server in turns
# of SLICE seconds (A B B A A B ..., DURATION seconds each in all), so the
# machine's load drifts over all of them alike and each round's ratio is
# measured under one load; REPEATS rounds for each stream count.
#
# scallopd fixes glibc's malloc thresholds itself (server/malloc_tuning.h).
# With GLIBC_DEFAULTS=1 a second scallopd runs with glibc's own dynamic
# thresholds (any malloc tunable in GLIBC_TUNABLES turns the fix off), to
# show what the fix saves; see the performance notes.
#
# With BEFORE=PATH a second scallopd, that binary (an earlier commit's build),
# runs beside the first in every round, so a change is measured against what
# it replaced under the same background load. With the build's
# cold_tile_latency, the engine alone on as many threads is measured too
# before the cold runs: what of a cold call's latency is the engine's own,
# on the same work (one engine with a full cache of the same budget, the
# load generator's cold tiles; its cache mode).
#
#   bench/run-load-benchmark.sh build-load
#   CACHE_MB=64 DURATION=10 SLICE=1 STREAMS="1 4" REPEATS=3 bench/run-load-benchmark.sh build-load
set -euo pipefail

if [[ $# -ne 1 ]]; then
  echo "usage: $0 BUILD_DIR  (env: CACHE_MB DURATION SLICE REQUESTS STREAMS THREADS TILE" \
    "WARM_SIDE REPEATS GLIBC_DEFAULTS BEFORE ENGINE_TILES)" >&2
  exit 2
fi
build=$1
cache_mb=${CACHE_MB:-64}       # scallopd --cache-megabytes
duration=${DURATION:-10}       # seconds per run (each run also stops at REQUESTS)
slice=${SLICE:-1}              # seconds of a server's turn in a warm round
requests=${REQUESTS:-1000000}
streams_list=${STREAMS:-"1 4"}
threads=${THREADS:-2}          # scallopd --threads
tile=${TILE:-64}               # tile side in d
warm_side=${WARM_SIDE:-256}    # the warm square's side in d
repeats=${REPEATS:-1}          # warm rounds per stream count
glibc_defaults=${GLIBC_DEFAULTS:-0}
before=${BEFORE:-}             # another scallopd binary, run beside this one
engine_tiles=${ENGINE_TILES:-1000}  # cold tiles of the engine-alone baseline
# A malloc tunable at its default value: scallopd then leaves malloc alone.
tunables=glibc.malloc.perturb=0

scallopd=$build/server/scallopd
generator=$build/bench/load_generator
null_server=$build/bench/null_server
for binary in "$scallopd" "$generator" "$null_server" ${before:+"$before"}; do
  [[ -x $binary ]] || { echo "missing $binary (build scallopd load_generator null_server)" >&2; exit 2; }
done

work=$(mktemp -d /tmp/scallop-load-XXXXXX)
pids=()
cleanup() {
  local code=$?
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  wait 2>/dev/null || true
  if [[ $code -eq 0 ]]; then rm -rf "$work"; else echo "# failed; servers' logs kept in $work" >&2; fi
}
trap cleanup EXIT

declare -A address pid metrics idle_rss

# cpu_ticks PID: user + system CPU time of the process, in clock ticks.
cpu_ticks() { awk '{print $14 + $15}' "/proc/$1/stat"; }
ticks_per_second=$(getconf CLK_TCK)

rss_kib() { awk '/^VmRSS:/ {print $2}' "/proc/$1/status"; }
mib() { awk -v kib="$1" 'BEGIN { printf "%.1f", kib / 1024 }'; }

# wait_for_line FILE PREFIX: after up to 60 s, the HOST:PORT of the line
# "PREFIX HOST:PORT" in FILE, or nothing.
wait_for_line() {
  for _ in $(seq 600); do
    local found
    found=$(sed -n "s/^$2 //p" "$1" | head -1)
    if [[ -n $found ]]; then echo "$found"; return 0; fi
    sleep 0.1
  done
}

# start_server NAME PREFIX COMMAND...: runs it with stdout to $work/NAME.out
# and records its pid, address and (for scallopd) metrics address.
start_server() {
  local name=$1 prefix=$2
  shift 2
  "$@" >"$work/$name.out" 2>"$work/$name.err" &
  pid[$name]=$!
  pids+=($!)
  address[$name]=$(wait_for_line "$work/$name.out" "$prefix")
  if [[ -z ${address[$name]} ]]; then
    echo "$name did not start; its log:" >&2
    cat "$work/$name.err" >&2
    exit 1
  fi
  metrics[$name]=
  if [[ $* == *--metrics-listen* ]]; then
    metrics[$name]=$(wait_for_line "$work/$name.out" "scallopd metrics on")
  fi
  idle_rss[$name]=$(rss_kib "${pid[$name]}")
}

# cache_counter NAME COUNTER: that server's counter (scallop_cache_hits_total,
# ...), or 0 when it serves no metrics.
cache_counter() {
  [[ -n ${metrics[$1]} ]] || { echo 0; return; }
  curl -s --max-time 2 "http://${metrics[$1]}/metrics" | awk -v name="$2" '$1 == name {print $2}'
}

# sample_rss PID FILE: VmRSS in KiB every 0.1 s until killed.
sample_rss() {
  while kill -0 "$1" 2>/dev/null; do
    rss_kib "$1" >>"$2"
    sleep 0.1
  done
}

echo "# $(date -u '+%Y-%m-%d %H:%M UTC'), load at start:$(uptime | sed 's/.*load average://')"
# When scallopd serves metrics, its cache counters show that cold requests
# generate every region they touch and warm ones none.
scallopd_flags=(--listen 127.0.0.1:0 --threads "$threads" --cache-megabytes "$cache_mb")
if "$scallopd" --help | grep -q -- --metrics-listen; then
  scallopd_flags+=(--metrics-listen 127.0.0.1:0)
fi
start_server scallopd "scallopd listening on" "$scallopd" "${scallopd_flags[@]}"
servers=(scallopd)
if [[ $glibc_defaults == 1 ]]; then
  start_server glibc "scallopd listening on" env GLIBC_TUNABLES=$tunables "$scallopd" \
    "${scallopd_flags[@]}"
  servers+=(glibc)
fi
if [[ -n $before ]]; then
  start_server before "scallopd listening on" "$before" "${scallopd_flags[@]}"
  servers+=(before)
fi
start_server null "null_server listening on" "$null_server" --listen 127.0.0.1:0 --tile "$tile"
echo "# scallopd ${address[scallopd]} (--threads $threads --cache-megabytes $cache_mb)," \
  "glibc defaults ${address[glibc]:-off} (GLIBC_TUNABLES=$tunables), null server ${address[null]}"
[[ -n $before ]] && echo "# before: $before at ${address[before]}"
echo "# each run: at most $duration s and $requests requests; tile $tile d; warm square $warm_side d;" \
  "warm rounds in turns of $slice s"

rows=$work/rows.tsv
: >"$rows"
# watch SERVER SAMPLES: samples the server's resident memory into SAMPLES
# and notes its cache counters and CPU time, until its `record`.
declare -A sampler hits_before misses_before cpu_before
watch() {
  local name=$1 samples=$2
  : >"$samples"
  sample_rss "${pid[$name]}" "$samples" &
  sampler[$name]=$!
  hits_before[$name]=$(cache_counter "$name" scallop_cache_hits_total)
  misses_before[$name]=$(cache_counter "$name" scallop_cache_misses_total)
  cpu_before[$name]=$(cpu_ticks "${pid[$name]}")
}

# record SERVER ROW SAMPLES ROUND WHAT: ends watch's sampling (failing if the
# server died during WHAT) and appends to $rows the generator's ROW with the
# server's peak resident memory (MiB), cache hits and misses (regions
# generated) and CPU seconds since its watch.
record() {
  local name=$1 row=$2 samples=$3 round=$4 what=$5
  kill "${sampler[$name]}" 2>/dev/null || true
  wait "${sampler[$name]}" 2>/dev/null || true
  if ! kill -0 "${pid[$name]}" 2>/dev/null; then
    echo "$name exited during $what; its log ends:" >&2
    tail -5 "$work/$name.err" >&2
    exit 1
  fi
  local cpu=$(($(cpu_ticks "${pid[$name]}") - cpu_before[$name]))
  local hits=$(($(cache_counter "$name" scallop_cache_hits_total) - hits_before[$name]))
  local misses=$(($(cache_counter "$name" scallop_cache_misses_total) - misses_before[$name]))
  printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$name" "$row" "$(mib "$(sort -n "$samples" | tail -1)")" \
    "$hits" "$misses" "$(awk -v t="$cpu" -v hz="$ticks_per_second" 'BEGIN { print t / hz }')" \
    "$round" >>"$rows"
}

# run SERVER MODE STREAMS [ROUND]: one generator run against one server; its row in $rows.
run() {
  local name=$1 mode=$2 streams=$3 round=${4:-0}
  local samples=$work/rss-$name-$mode-$streams
  watch "$name" "$samples"
  local row
  row=$("$generator" --target "${address[$name]}" --mode "$mode" --streams "$streams" \
    --duration "$duration" --requests "$requests" --tile "$tile" --warm-side "$warm_side" \
    --output tsv) || echo "# $name $mode $streams: errors (see the row)" >&2
  record "$name" "$row" "$samples" "$round" "the $mode run with $streams streams"
}

# warm_round STREAMS ROUND NAME...: one load_generator run that drives the
# servers NAME... (null and every scallopd) in turns of $slice s (in that order, then reversed: A B B A
# ...), $duration s each; a row in $rows for each, as run's, with its peak
# resident memory, cache counters and CPU time over the whole round (a
# server is idle during the others' turns).
warm_round() {
  local streams=$1 round=$2
  shift 2
  local names=("$@") targets=() name
  for name in "${names[@]}"; do
    targets+=(--target "${address[$name]}")
    watch "$name" "$work/rss-$name-warm-$streams"
  done
  local out
  out=$("$generator" "${targets[@]}" --slice "$slice" --mode warm --streams "$streams" \
    --duration "$duration" --requests "$requests" --tile "$tile" --warm-side "$warm_side" \
    --output tsv) || echo "# warm round $round, $streams streams: errors (see the rows)" >&2
  local rows_out=() n
  mapfile -t rows_out <<<"$out"
  declare -A row
  for n in "${!names[@]}"; do row[${names[$n]}]=${rows_out[$n]:-}; done
  # The rows in the table's order (null, then the scallopds), whoever went first.
  for name in null "${servers[@]}"; do
    record "$name" "${row[$name]}" "$work/rss-$name-warm-$streams" "$round" \
      "warm round $round with $streams streams"
  done
}

# Null and warm in one round for each stream count, in turns, so the ratio
# compares them under the same background load. The order turns by one
# server a round: with three or more, the one in the middle of A B C C B A
# is entered twice as often as the others (each time with caches the others
# left), so each takes that place in turn.
for round in $(seq "$repeats"); do
  for streams in $streams_list; do
    order=(null "${servers[@]}")
    shift_by=$(((round - 1) % ${#order[@]}))
    order=("${order[@]:shift_by}" "${order[@]:0:shift_by}")
    warm_round "$streams" "$round" "${order[@]}"
  done
done
engine_cold=
if [[ -x $build/bench/cold_tile_latency ]]; then
  engine_cold=$("$build/bench/cold_tile_latency" "$engine_tiles" "$tile" "$threads" "$cache_mb")
fi
for streams in $streams_list; do
  for server in "${servers[@]}"; do run "$server" cold "$streams"; done
done

echo
printf '%-9s %-5s %7s %9s %10s %11s %7s %8s %8s %8s %8s %6s %8s %8s %8s %10s\n' server mode \
  streams requests requests/s points/s MB/s p50_ms p90_ms p99_ms max_ms errors rss_MiB \
  hits/req gen/req cpu_us/req
# Row columns: server, load_generator --tsv-header, RSS peak, hits, misses,
# server CPU seconds. CPU per request is the least noisy figure on a busy
# machine: other processes delay the server but do not add to its CPU time.
awk -F'\t' '{
  per = $4 + $5 > 0 ? 1 / ($4 + $5) : 0
  printf "%-9s %-5s %7d %9d %10.0f %11.3g %7.1f %8.3f %8.3f %8.3f %8.3f %6d %8.1f %8.1f %8.1f %10.0f\n",
    $1, $2, $3, $4, $7, $8, $9 / 1e6, $10, $11, $12, $13, $5, $14, $15 * per, $16 * per,
    $17 * 1e6 * per}' "$rows"

echo
# The issue's targets: warm at least 0.85x the null server in every round
# (each round's null and scallopd turns alternate, under one load), and a
# cold p99 for one stream of at most 5 ms.
awk -F'\t' '
  $2 == "warm" { rate[$1, $3] += $7; round_rate[$1, $3, $18] = $7; seen[$3] = 1; rounds[$18] = 1 }
  $2 == "cold" && $3 == 1 { cold_p99[$1] = $12 }
  END {
    for (s in seen) {
      split("scallopd glibc before", names, " ")
      for (n = 1; n <= 3; ++n) {
        name = names[n]
        if (!((name, s) in rate)) continue
        worst = 1e9; list = ""
        for (r = 1; (name, s, r) in round_rate; ++r) {
          x = round_rate[name, s, r] / round_rate["null", s, r]
          list = list sprintf("%s%.2f", r > 1 ? " " : "", x)
          if (x < worst) worst = x
        }
        printf "warm / null requests/s, %d streams, %s: %.2f over the rounds; by round %s; worst %.2f (target >= 0.85 in every round: %s)\n",
          s, name, rate[name, s] / rate["null", s], list, worst, (worst >= 0.85 ? "met" : "not met")
      }
    }
    for (server in cold_p99) printf "cold p99, 1 stream, %s: %.2f ms (target <= 5 ms: %s)\n", server,
      cold_p99[server], (cold_p99[server] <= 5 ? "met" : "not met")
  }' "$rows" | sort
if [[ -n $engine_cold ]]; then
  echo "engine alone (cold_tile_latency $engine_tiles $tile $threads $cache_mb): $engine_cold"
fi
for server in "${servers[@]}"; do
  hwm=$(awk '/^VmHWM:/ {print $2}' "/proc/${pid[$server]}/status")
  echo "$server resident memory: $(mib "${idle_rss[$server]}") MiB idle, $(mib "$hwm") MiB peak" \
    "(VmHWM); growth $(mib $((hwm - idle_rss[$server]))) MiB against a cache budget of $cache_mb MiB"
  if [[ -n ${metrics[$server]} ]]; then
    cache_bytes=$(cache_counter "$server" scallop_cache_bytes)
    echo "$server cache at the end: $(mib $((cache_bytes / 1024))) MiB by its own count," \
      "$(cache_counter "$server" scallop_cache_regions) regions," \
      "$(cache_counter "$server" scallop_cache_evictions_total) evicted so far"
  fi
done
echo "# load at end:$(uptime | sed 's/.*load average://')"
