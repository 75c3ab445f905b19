#!/usr/bin/env bash
# The service load benchmark of issue 7 (docs/performance.md, "Service under
# load"). Builds nothing: give it a build folder holding scallopd,
# load_generator and null_server. It starts scallopd (with a cache budget)
# and the null server on free loopback ports, runs the load generator warm
# against both and cold against scallopd with each stream count, samples
# scallopd's resident memory throughout, and prints a table with the ratio
# warm / null. Both servers run side by side on this machine, in one run.
#
#   bench/run-load-benchmark.sh build-load
#   CACHE_MB=64 DURATION=10 STREAMS="1 4" bench/run-load-benchmark.sh build-load
set -euo pipefail

if [[ $# -ne 1 ]]; then
  echo "usage: $0 BUILD_DIR   (env: CACHE_MB DURATION REQUESTS STREAMS THREADS TILE WARM_SIDE)" >&2
  exit 2
fi
build=$1
cache_mb=${CACHE_MB:-64}       # scallopd --cache-megabytes
duration=${DURATION:-10}       # seconds per run (each run also stops at REQUESTS)
requests=${REQUESTS:-1000000}
streams_list=${STREAMS:-"1 4"}
threads=${THREADS:-2}          # scallopd --threads
tile=${TILE:-64}               # tile side in d
warm_side=${WARM_SIDE:-256}    # the warm square's side in d

scallopd=$build/server/scallopd
generator=$build/bench/load_generator
null_server=$build/bench/null_server
for binary in "$scallopd" "$generator" "$null_server"; do
  [[ -x $binary ]] || { echo "missing $binary (build scallopd load_generator null_server)" >&2; exit 2; }
done

work=$(mktemp -d /tmp/scallop-load-XXXXXX)
pids=()
cleanup() {
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  wait 2>/dev/null || true
}
trap cleanup EXIT

# start_server NAME PREFIX COMMAND...: runs it with stdout to $work/NAME.out,
# then waits up to 60 s for the line "PREFIX HOST:PORT" and prints HOST:PORT.
start_server() {
  local name=$1 prefix=$2
  shift 2
  "$@" >"$work/$name.out" 2>"$work/$name.err" &
  pids+=($!)
  echo $! >"$work/$name.pid"
  for _ in $(seq 600); do
    local address
    address=$(sed -n "s/^$prefix //p" "$work/$name.out" | head -1)
    if [[ -n $address ]]; then echo "$address"; return 0; fi
    sleep 0.1
  done
  echo "$name did not start; its log:" >&2
  cat "$work/$name.err" >&2
  return 1
}

rss_kib() { awk '/^VmRSS:/ {print $2}' "/proc/$1/status"; }
mib() { awk -v kib="$1" 'BEGIN { printf "%.1f", kib / 1024 }'; }

# sample_rss PID FILE: VmRSS in KiB every 0.1 s until killed.
sample_rss() {
  while kill -0 "$1" 2>/dev/null; do
    rss_kib "$1" >>"$2"
    sleep 0.1
  done
}

echo "# $(date -u '+%Y-%m-%d %H:%M UTC'), load at start:$(uptime | sed 's/.*load average://')"
scallopd_address=$(start_server scallopd "scallopd listening on" \
  "$scallopd" --listen 127.0.0.1:0 --threads "$threads" --cache-megabytes "$cache_mb")
null_address=$(start_server null_server "null_server listening on" \
  "$null_server" --listen 127.0.0.1:0 --tile "$tile")
scallopd_pid=$(cat "$work/scallopd.pid")
idle_rss=$(rss_kib "$scallopd_pid")
echo "# scallopd $scallopd_address (--threads $threads --cache-megabytes $cache_mb), null server $null_address"
echo "# each run: at most $duration s and $requests requests; tile $tile d; warm square $warm_side d"

rows=$work/rows.tsv
: >"$rows"
# run SERVER_NAME ADDRESS MODE STREAMS: one generator run, a row in $rows
# with scallopd's peak resident memory during it (MiB).
run() {
  local name=$1 address=$2 mode=$3 streams=$4
  local samples=$work/rss-$name-$mode-$streams
  : >"$samples"
  sample_rss "$scallopd_pid" "$samples" &
  local sampler=$!
  local row
  row=$("$generator" --target "$address" --mode "$mode" --streams "$streams" \
    --duration "$duration" --requests "$requests" --tile "$tile" --warm-side "$warm_side" \
    --output tsv) || echo "# $name $mode $streams: errors (see the row)" >&2
  kill "$sampler"
  wait "$sampler" 2>/dev/null || true
  local peak
  peak=$(sort -n "$samples" | tail -1)
  printf '%s\t%s\t%s\n' "$name" "$row" "$(mib "${peak:-0}")" >>"$rows"
}

# Null and warm side by side for each stream count, so the ratio compares
# runs seconds apart under the same background load.
for streams in $streams_list; do
  run null "$null_address" warm "$streams"
  run scallopd "$scallopd_address" warm "$streams"
done
for streams in $streams_list; do
  run scallopd "$scallopd_address" cold "$streams"
done

echo
printf '%-9s %-5s %7s %9s %10s %11s %7s %8s %8s %8s %8s %6s %9s\n' server mode streams \
  requests requests/s points/s MB/s p50_ms p90_ms p99_ms max_ms errors rss_MiB
# Row columns: server, then load_generator --tsv-header, then the RSS peak.
awk -F'\t' '{printf "%-9s %-5s %7d %9d %10.0f %11.3g %7.1f %8.3f %8.3f %8.3f %8.3f %6d %9.1f\n",
  $1, $2, $3, $4, $7, $8, $9 / 1e6, $10, $11, $12, $13, $5, $14}' "$rows"

echo
awk -F'\t' '
  $1 == "null" { null[$3] = $7 }
  $1 == "scallopd" && $2 == "warm" { warm[$3] = $7 }
  $1 == "scallopd" && $2 == "cold" && $3 == 1 { cold_p99 = $12 }
  END {
    for (s in warm) if (s in null)
      printf "warm / null requests/s, %d streams: %.2f (target >= 0.7)\n", s, warm[s] / null[s]
    if (cold_p99 != "") printf "cold p99, 1 stream: %.2f ms (target < 10 ms)\n", cold_p99
  }' "$rows"
peak_rss=$(cut -f14 "$rows" | sort -n | tail -1)
hwm=$(awk '/^VmHWM:/ {print $2}' "/proc/$scallopd_pid/status")
echo "scallopd resident memory: $(mib "$idle_rss") MiB idle, $peak_rss MiB peak sampled," \
  "$(mib "$hwm") MiB VmHWM; growth $(mib $((hwm - idle_rss))) MiB against a cache budget of" \
  "$cache_mb MiB"
echo "# load at end:$(uptime | sed 's/.*load average://')"
rm -rf "$work"
