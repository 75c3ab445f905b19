#!/usr/bin/env bash
# Smoke run of the service load benchmark's programs (CTest, label
# bench-smoke): null_server and scallopd on free loopback ports, and
# load_generator against each with a few requests. Fails if one does not
# start or a request fails; asserts no timing.
#
#   bench/smoke-load.sh SCALLOPD NULL_SERVER LOAD_GENERATOR
set -euo pipefail

if [[ $# -ne 3 ]]; then
  echo "usage: $0 SCALLOPD NULL_SERVER LOAD_GENERATOR" >&2
  exit 2
fi
scallopd=$1 null_server=$2 generator=$3

work=$(mktemp -d /tmp/scallop-smoke-load-XXXXXX)
pids=()
cleanup() {
  for pid in "${pids[@]}"; do kill "$pid" 2>/dev/null || true; done
  wait 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT
# A failing step names itself and shows the servers' logs before cleanup removes them (a run
# in a full ctest once failed in 0.14 s with nothing to read).
trap 'echo "smoke-load: line $LINENO failed (exit $?); the servers said:" >&2
      tail -n 20 "$work"/*.out "$work"/*.err >&2 2>/dev/null || true' ERR

# start NAME PREFIX COMMAND...: runs it in the background and sets
# address[NAME] to the HOST:PORT of its "PREFIX HOST:PORT" line (waits up to
# 30 s). Not in a $(...) subshell, so that its pid reaches cleanup.
declare -A address
start() {
  local name=$1 prefix=$2
  shift 2
  "$@" >"$work/$name.out" 2>"$work/$name.err" &
  pids+=($!)
  for _ in $(seq 300); do
    address[$name]=$(sed -n "s/^$prefix //p" "$work/$name.out" | head -1)
    [[ -z ${address[$name]} ]] || return 0
    sleep 0.1
  done
  echo "$name did not start; its log:" >&2
  cat "$work/$name.err" >&2
  return 1
}

start null "null_server listening on" "$null_server" --listen 127.0.0.1:0 --tile 16
start scallopd "scallopd listening on" "$scallopd" --listen 127.0.0.1:0 --threads 1 \
  --cache-megabytes 16

# A fixed run seed: the same tiles every run.
common=(--streams 1 --requests 20 --duration 5 --tile 16 --seed 1 --output text)
"$generator" --target "${address[null]}" --mode warm --warm-side 32 "${common[@]}"
"$generator" --target "${address[scallopd]}" --mode warm --warm-side 32 "${common[@]}"
"$generator" --target "${address[scallopd]}" --mode cold "${common[@]}"
echo "load smoke: null_server and scallopd answered every request"
