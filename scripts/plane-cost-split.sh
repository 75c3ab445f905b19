#!/bin/sh
# Where a cold plane query's time goes, part by part (docs/design.md, "Where a cold query's
# time goes"): builds scallop_core of HEAD in a scratch directory with the cycle counters of
# scripts/plane-cost-split/counters.patch (which no build carries), and runs the driver beside
# it. The counters read the time-stamp counter, so run it on a quiet machine.
#
# Usage: scripts/plane-cost-split.sh [side in d = 1000] [queries = 2] [tiles = 0]
#   e.g. scripts/plane-cost-split.sh 64 0 300    # 300 cold 64 d tiles
set -eu
repo=$(git rev-parse --show-toplevel)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
git -C "$repo" archive HEAD | tar -x -C "$work"
patch -s -d "$work" -p1 < "$repo/scripts/plane-cost-split/counters.patch"
cmake -S "$work" -B "$work/build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DSCALLOP_BUILD_SERVICE=OFF \
  -DSCALLOP_BUILD_BENCH=OFF > /dev/null
cmake --build "$work/build" -j2 --target scallop_core > /dev/null
c++ -std=c++20 -O3 -DNDEBUG -ffp-contract=off -I"$work/core" \
  "$repo/scripts/plane-cost-split/driver.cc" "$work/build/core/libscallop_core.a" \
  -lpng -lfftw3 -lgmp -lmpfr -lpthread -o "$work/split"
"$work/split" "$@"
