#!/usr/bin/env bash
# Runs one libFuzzer target for SECONDS from its corpus (CTest, label fuzz).
# New inputs go to a scratch folder, so the repository's corpus stays as it
# is; a crash, leak, timeout or failed invariant fails the run and leaves the
# input in the current folder (crash-*, leak-*, timeout-*) to replay with
#   TARGET crash-<hash>
#
#   fuzz/run-fuzzer.sh TARGET CORPUS SECONDS [DICTIONARY]
set -euo pipefail
if [[ $# -lt 3 || $# -gt 4 ]]; then
  echo "usage: $0 TARGET CORPUS SECONDS [DICTIONARY]" >&2
  exit 2
fi
target=$1 corpus=$2 seconds=$3 dictionary=${4:-}
scratch=$(mktemp -d /tmp/scallop-fuzz-XXXXXX)
trap 'rm -rf "$scratch"' EXIT
# -timeout is wall time: 30 s, since an instrumented A1 region is slow and a
# shared CI machine slower still (an input taking 0.35 s of CPU took 11 s
# with the load average at 16).
options=(-max_total_time="$seconds" -timeout=30 -rss_limit_mb=2048 -max_len=8192
         -print_final_stats=1)
[[ -z $dictionary ]] || options+=(-dict="$dictionary")
# One process, no forking: the run must fit the CI machine's share of cores.
"$target" "${options[@]}" "$scratch" "$corpus"
