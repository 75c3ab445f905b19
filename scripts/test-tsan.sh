#!/usr/bin/env bash
# ThreadSanitizer on the tests that run threads: the engine and lookup tests
# of several threads at once (CTest label "threads": region cache, plane
# determinism, nearest lookup) and the gRPC end-to-end tests, whose scallopd
# is built with ThreadSanitizer too. Builds only those (GCC, into BUILD_DIR,
# default build-tsan) and fails on any report from any process: each writes
# its reports to a file in a folder checked at the end, so a race inside the
# scallopd an e2e test started fails the run even if the test passed.
#
#   scripts/test-tsan.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build-tsan}
jobs=${JOBS:-2}

cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSCALLOP_WERROR=ON \
  -DSCALLOP_SANITIZE_THREAD=ON -DSCALLOP_BUILD_BENCH=OFF
cmake --build "$build" -j"$jobs" --target thread_tests e2e_tests scallopd

reports=$(mktemp -d /tmp/scallop-tsan-XXXXXX)
trap 'rm -rf "$reports"' EXIT
suppressions=$PWD/scripts/tsan-suppressions.txt
export TSAN_OPTIONS="log_path=$reports/tsan second_deadlock_stack=1 suppressions=$suppressions"
status=0
# The e2e tests driven by shell scripts need the CLI too: they stay in the
# other builds. ThreadSanitizer runs 5-15 times slower: the timeouts allow it.
ctest --test-dir "$build" --output-on-failure -j"$jobs" -L 'threads|e2e' --timeout 900 \
  -E '^(cli_remote|cli_secure|python_client|dockerfile|kubernetes_manifests)$' || status=$?
if compgen -G "$reports/tsan*" >/dev/null; then
  echo "test-tsan: ThreadSanitizer reports:" >&2
  cat "$reports"/tsan* >&2
  status=1
fi
exit "$status"
