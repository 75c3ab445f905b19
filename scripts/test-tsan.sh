#!/usr/bin/env bash
# ThreadSanitizer on the tests that run threads (CTest label "threads":
# region cache, plane determinism with concurrent callers, thread counts and
# tilings, layered and radius-field worlds on engines of several threads,
# nearest lookups shared by two threads, scallopd's admission budget and rate
# limiter under four). Builds only those (GCC, into
# BUILD_DIR, default build-tsan) and fails on any report: each process writes
# its reports to a folder checked at the end.
#
# E2E=1 adds the gRPC end-to-end tests and a scallopd built with
# ThreadSanitizer. They are not clean, and cannot be with Debian's gRPC: it is
# not instrumented, so ThreadSanitizer misses the hand-offs inside it (a
# reactor armed on a request thread and destroyed in OnDone on a gRPC thread
# looks like a race) and reports thousands of them, most inside libgrpc and
# absl. A clean e2e run needs gRPC built with -fsanitize=thread
# (docs/quality.md, "ThreadSanitizer"). scripts/test.sh, and so CI, runs it
# without E2E.
#
#   scripts/test-tsan.sh [BUILD_DIR]            (env: E2E=1, JOBS=2)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build-tsan}
jobs=${JOBS:-2}
targets=(thread_tests)
labels=threads
if [[ -n ${E2E:-} ]]; then
  targets+=(e2e_tests scallopd)
  labels='threads|e2e'
fi

cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSCALLOP_WERROR=ON \
  -DSCALLOP_SANITIZE_THREAD=ON -DSCALLOP_BUILD_BENCH=OFF
cmake --build "$build" -j"$jobs" --target "${targets[@]}"

reports=$(mktemp -d /tmp/scallop-tsan-XXXXXX)
trap 'rm -rf "$reports"' EXIT
export TSAN_OPTIONS="log_path=$reports/tsan second_deadlock_stack=1 suppressions=$PWD/scripts/tsan-suppressions.txt"
status=0
# The e2e tests driven by shell scripts need the CLI too: they stay in the
# other builds. ThreadSanitizer runs 5-15 times slower: the timeout allows it.
ctest --test-dir "$build" --output-on-failure -j"$jobs" -L "$labels" --timeout 900 \
  -E '^(cli_remote|cli_secure|python_client|dockerfile|kubernetes_manifests)$' || status=$?
if compgen -G "$reports/tsan*" >/dev/null; then
  echo "test-tsan: ThreadSanitizer reports (first 200 lines):" >&2
  cat "$reports"/tsan* | head -200 >&2
  status=1
fi
exit "$status"
