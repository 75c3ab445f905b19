#!/usr/bin/env bash
# The full comparison of A1 worlds with bounded exact A1 (docs/quality.md, "A1 worlds are dart
# throwing"): tests/plane_a1_distribution_test.cc, which CI runs over 48 seeds, here over SEEDS
# (default 400) worlds and as many 40 d tori. Region interiors (4 d from every seam) must agree
# with the tori in rho and every bin of g(r) within 3 standard errors, and the density by signed
# distance to a seam must stay flat. Prints the figures docs/quality.md quotes. About 3 minutes
# of one core at 400 seeds.
#
#   scripts/a1-plane-against-bounded.sh [BUILD_DIR]    # default build (Release)
#   env: SEEDS (400), SKIP_BUILD=1
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
if [[ -z ${SKIP_BUILD:-} ]]; then
  cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$build" -j2 --target plane_a1_distribution_test
fi
PLANE_A1_SEEDS=${SEEDS:-400} "$build/tests/plane_a1_distribution_test"
