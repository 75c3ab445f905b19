#!/usr/bin/env bash
# The full comparison of A1 with exhaustive dart throwing (docs/quality.md,
# "A1 is dart throwing"): the two tests of tests/sampler_distribution_test.cc
# that CI runs over 100 seeds, here over SEEDS (default 1000) seeds of each on
# the 40 d torus. A1 must agree with dart throwing in rho, the spread of the
# point count and every bin of g(r) within 3 standard errors; the paper's A1
# (new points only within r' = 2 d of the set) must not. Prints the figures
# docs/quality.md quotes. About 2 minutes at 1000 seeds.
#
#   scripts/a1-against-dart-throwing.sh [BUILD_DIR]    # default build (Release)
#   env: SEEDS (1000), SKIP_BUILD=1
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
if [[ -z ${SKIP_BUILD:-} ]]; then
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$build" -j2 --target sampler_distribution_test
fi
A1_SEEDS=${SEEDS:-1000} "$build/tests/sampler_distribution_test" \
  --gtest_filter='*A1IsDartThrowing:*A1ComparisonCatchesThePapersRestriction'
