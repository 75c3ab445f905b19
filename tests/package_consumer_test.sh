#!/usr/bin/env bash
# find_package(Scallop) from outside the tree: installs this build into a
# temporary prefix, builds tests/package_consumer against it, and checks its
# count of a world's points against `scallop plane` of the same build.
# Usage: package_consumer_test.sh BUILD_DIR SOURCE_DIR SCALLOP_CLI [extra CXX flags]
set -euo pipefail
build_dir=$1 source_dir=$2 cli=$3 extra_flags=${4:-}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

cmake --install "$build_dir" --prefix "$work/prefix" >"$work/install.log"
test -f "$work/prefix/lib/cmake/Scallop/ScallopConfig.cmake"
test -x "$work/prefix/bin/scallopd"

cmake -S "$source_dir/tests/package_consumer" -B "$work/consumer" -G Ninja \
  -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_CXX_FLAGS="$extra_flags" >"$work/configure.log" ||
  { cat "$work/configure.log"; exit 1; }
cmake --build "$work/consumer" >"$work/build.log" 2>&1 || { cat "$work/build.log"; exit 1; }

for rect in "0 0 50 50" "-300.5 17 -240 90"; do
  read -r x0 y0 x1 y1 <<<"$rect"
  got=$("$work/consumer/count_points" 9 "$x0" "$y0" "$x1" "$y1")
  want=$("$cli" plane --seed 9 --rect "$x0,$y0,$x1,$y1" | tail -n +2 | wc -l)
  if [ "$got" != "count=$want" ]; then
    echo "package consumer: rect $rect gave '$got', scallop plane gave $want points" >&2
    exit 1
  fi
done
echo "package consumer: built against the installed package; counts agree"
