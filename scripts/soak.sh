#!/usr/bin/env bash
# Soak test: a real scallopd under a bounded mixed load (bench/soak_load.cc:
# GetPoints, StreamPoints, Follow, Nearest, NoiseGrid, cancellations, short
# deadlines, bad inputs) for DURATION seconds, sampling the server's resident
# memory, open files and threads every INTERVAL seconds. Fails when
#   - a call ends with a code its kind may not (shedding is allowed),
#   - resident memory ever exceeds the cache budget plus OVERHEAD_MB,
#   - open files or threads at any sample of the second half exceed the
#     largest count of the first half by more than FD_SLACK / THREAD_SLACK
#     (growth: leaked connections, calls or threads), or
#   - scallopd dies, or does not exit within its grace time on SIGTERM.
# The samples go to OUT (a TSV file) for docs/quality.md.
#
#   scripts/soak.sh BUILD_DIR [DURATION_SECONDS]       (default 1200: 20 minutes)
#   env: CACHE_MB (64), OVERHEAD_MB (192), WORKERS (6), INTERVAL (5), SEED (1),
#        THREADS (2: scallopd --threads), OUT (soak-samples.tsv in the build dir)
set -euo pipefail

if [[ $# -lt 1 || $# -gt 2 ]]; then
  echo "usage: $0 BUILD_DIR [DURATION_SECONDS]" >&2
  exit 2
fi
build=$1
duration=${2:-1200}
cache_mb=${CACHE_MB:-64}
overhead_mb=${OVERHEAD_MB:-192}
workers=${WORKERS:-6}
interval=${INTERVAL:-5}
seed=${SEED:-1}
threads=${THREADS:-2}
fd_slack=${FD_SLACK:-8}
thread_slack=${THREAD_SLACK:-4}
out=${OUT:-$build/soak-samples.tsv}
scallopd=$build/server/scallopd
soak_load=$build/bench/soak_load
for program in "$scallopd" "$soak_load"; do
  [[ -x $program ]] || { echo "soak: $program is not built" >&2; exit 2; }
done

work=$(mktemp -d /tmp/scallop-soak-XXXXXX)
server_pid='' load_pid=''
# A failed run keeps the server's and the load's logs beside OUT (OUT.logs/),
# since a rerun overwrites OUT and a flaky failure may not come back.
cleanup() {
  local status=$?
  for pid in $load_pid $server_pid; do kill "$pid" 2>/dev/null || true; done
  wait 2>/dev/null || true
  if ((status != 0)); then
    rm -rf "$out.logs" && mkdir -p "$out.logs" && cp "$work"/* "$out" "$out.logs/" 2>/dev/null
    echo "soak: failed (status $status); logs and samples kept in $out.logs" >&2
  fi
  rm -rf "$work"
}
trap cleanup EXIT

"$scallopd" --listen 127.0.0.1:0 --threads "$threads" --cache-megabytes "$cache_mb" \
  --log-level error --grace-seconds 5 >"$work/scallopd.out" 2>"$work/scallopd.err" &
server_pid=$!
address=''
for _ in $(seq 300); do
  address=$(sed -n 's/^scallopd listening on //p' "$work/scallopd.out" | head -1)
  [[ -z $address ]] || break
  sleep 0.1
done
if [[ -z $address ]]; then
  echo "soak: scallopd did not start; its log:" >&2
  cat "$work/scallopd.err" >&2
  exit 1
fi

"$soak_load" --target "$address" --duration "$duration" --workers "$workers" --seed "$seed" \
  >"$work/load.out" 2>"$work/load.err" &
load_pid=$!

# sample: one TSV row of seconds since start, RSS in MB, open files, threads.
start=$SECONDS
printf 'seconds\trss_mb\tfds\tthreads\n' >"$out"
sample() {
  local rss threads fds
  rss=$(awk '/^VmRSS:/ {printf "%.1f", $2 / 1024}' "/proc/$server_pid/status")
  threads=$(awk '/^Threads:/ {print $2}' "/proc/$server_pid/status")
  fds=$(find "/proc/$server_pid/fd" -mindepth 1 -maxdepth 1 | wc -l)
  printf '%d\t%s\t%d\t%d\n' $((SECONDS - start)) "$rss" "$fds" "$threads" >>"$out"
}
while kill -0 "$load_pid" 2>/dev/null; do
  if ! kill -0 "$server_pid" 2>/dev/null; then
    echo "soak: scallopd died during the load; its log:" >&2
    tail -20 "$work/scallopd.err" >&2
    exit 1
  fi
  sample
  sleep "$interval"
done
load_status=0
wait "$load_pid" || load_status=$?
load_pid=''
sample  # after the load: what the idle server keeps
cat "$work/load.out"
cat "$work/load.err" >&2

failed=0
if ((load_status != 0)); then
  echo "soak: FAIL: calls ended with codes other than the allowed ones and shedding" >&2
  failed=1
fi
# The checks over the samples, with the figures the report prints.
if ! awk -v budget=$((cache_mb + overhead_mb)) -v fd_slack="$fd_slack" \
  -v thread_slack="$thread_slack" -F'\t' '
  NR > 1 { n++; rss[n] = $2; fds[n] = $3; threads[n] = $4 }
  END {
    half = int(n / 2); bad = 0
    for (k = 1; k <= n; k++) {
      if (rss[k] > max_rss) max_rss = rss[k]
      if (k <= half) {
        if (fds[k] > fd_first) fd_first = fds[k]
        if (threads[k] > thread_first) thread_first = threads[k]
      } else {
        if (fds[k] > fd_second) fd_second = fds[k]
        if (threads[k] > thread_second) thread_second = threads[k]
      }
    }
    printf "soak: %d samples; peak RSS %.1f MB (limit %d MB); open files %d then %d; threads %d then %d (first half, then second half peaks)\n", n, max_rss, budget, fd_first, fd_second, thread_first, thread_second
    if (n < 4) { print "soak: FAIL: too few samples" > "/dev/stderr"; bad = 1 }
    if (max_rss > budget) { print "soak: FAIL: memory above the cache budget plus overhead" > "/dev/stderr"; bad = 1 }
    if (fd_second > fd_first + fd_slack) { print "soak: FAIL: open files grew" > "/dev/stderr"; bad = 1 }
    if (thread_second > thread_first + thread_slack) { print "soak: FAIL: threads grew" > "/dev/stderr"; bad = 1 }
    exit bad
  }' "$out"; then
  failed=1
fi

# A clean exit within the grace time (5 s) plus start-up slack.
kill -TERM "$server_pid"
for _ in $(seq 100); do
  kill -0 "$server_pid" 2>/dev/null || break
  sleep 0.1
done
if kill -0 "$server_pid" 2>/dev/null; then
  echo "soak: FAIL: scallopd still running 10 s after SIGTERM" >&2
  failed=1
else
  server_status=0
  wait "$server_pid" || server_status=$?
  if ((server_status != 0)); then
    echo "soak: FAIL: scallopd exited with status $server_status; its log:" >&2
    tail -20 "$work/scallopd.err" >&2
    failed=1
  fi
fi
server_pid=''
((failed == 0)) && echo "soak: passed ($duration s, samples in $out)"
exit "$failed"
