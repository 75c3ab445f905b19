#!/usr/bin/env bash
# Same bits everywhere (docs/determinism.md): the pinned generator outputs
# (ctest -L golden) must hold in a Clang build, a GCC -O0 build and an
# aarch64 cross build run under qemu-user, and the CLI must print the same
# bytes in the Clang build as in the reference GCC -O3 build.
#
#   scripts/test-portability.sh [REFERENCE_BUILD]   # default: build (scripts/test.sh's)
#
# Builds only what it checks, -j2, into build-clang, build-O0 and
# build-aarch64 (BUILD_PREFIX=/tmp/x/build- puts them elsewhere). Needs the
# packages of scripts/install-deps.sh. The aarch64 build has no CLI: the CLI
# links gRPC, not cross-built yet (docs/determinism.md, "Not checked").
set -euo pipefail
cd "$(dirname "$0")/.."

reference=${1:-build}
prefix=${BUILD_PREFIX:-build-}
jobs=2
common=(-G Ninja -DSCALLOP_WERROR=ON -DSCALLOP_BUILD_BENCH=OFF
  -DCGAL_DO_NOT_WARN_ABOUT_CMAKE_BUILD_TYPE=TRUE)

step() { echo "== test-portability: $* ($(date -u +%T))"; }

# configure_build_test DIR TARGETS EXCLUDE CMAKE_ARGS...: configures DIR,
# builds the targets (a comma-separated list) and runs the golden tests in
# it but those matching the regex EXCLUDE (none if empty). A hang fails
# after 15 minutes instead of holding CI.
configure_build_test() {
  local dir=$1 targets=$2 exclude=$3
  shift 3
  cmake -S . -B "$dir" "${common[@]}" "$@"
  # shellcheck disable=SC2086
  cmake --build "$dir" -j"$jobs" --target ${targets//,/ }
  ctest --test-dir "$dir" -L golden ${exclude:+-E "$exclude"} --timeout 900 \
    --output-on-failure -j"$jobs"
}

step "reference: GCC -O3 in $reference"
cmake --build "$reference" -j"$jobs" --target scallop golden_tests

step "Clang, Release"
configure_build_test "${prefix}clang" golden_tests,scallop "" -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_CXX_COMPILER=clang++

step "GCC -O0"
# No -g: the point is the optimiser's absence, and debug info doubles the time.
# The core's goldens only, without the service (gRPC, the CLI): they pin every
# generator and Nearest, the code an optimiser could change, and the CLI
# build at -O0 cost CI minutes for no code of its own.
configure_build_test "${prefix}O0" golden_tests "" -DCMAKE_BUILD_TYPE=Debug \
  -DCMAKE_CXX_FLAGS_DEBUG=-O0 -DSCALLOP_BUILD_SERVICE=OFF

step "aarch64, cross-compiled, run under qemu-aarch64"
# Not run there: the trigonometry's accuracy sweeps, whose long double
# reference is software quad precision on aarch64 (hours under emulation);
# its pinned bits (GoldenValues) and every other golden test run.
configure_build_test "${prefix}aarch64" golden_tests AccuracyOnRandomInputs \
  -DCMAKE_BUILD_TYPE=Release \
  -DSCALLOP_BUILD_SERVICE=OFF -DCMAKE_TOOLCHAIN_FILE=cmake/aarch64-linux-gnu.cmake

step "CLI output: Clang against GCC -O3"
work=$(mktemp -d /tmp/scallop-portability-XXXXXX)
trap 'rm -rf "$work"' EXIT
# Positions across four regions' seams and far from the origin.
printf '%s\n' 0.5,0.25 -7.125,13.75 15.999,-0.001 -16,16 31.3,-40.7 100000.5,-299999.25 \
  >"$work/positions.csv"
commands=()
for algorithm in a1 a2 a3; do
  commands+=("plane --seed 7 --algorithm $algorithm --density 1.8 --rect -20,-12.5,30,17")
  commands+=("nearest --seed 7 --algorithm $algorithm --density 1.8 --input $work/positions.csv")
done
for algorithm in a1 a2 a3 dart best-candidate bridson; do
  commands+=("generate --seed 5 --algorithm $algorithm --domain -10,-5,30,25 --dart-failure-limit 5000")
  commands+=("generate --seed 5 --algorithm $algorithm --domain 0,0,24,20 --torus --format json --dart-failure-limit 5000")
done
failures=0
for command in "${commands[@]}"; do
  # Word splitting of $command is wanted: it is a list of arguments.
  # shellcheck disable=SC2086
  expected=$("$reference/client/scallop" $command | sha256sum)
  # shellcheck disable=SC2086
  actual=$("${prefix}clang/client/scallop" $command | sha256sum)
  if [[ $actual != "$expected" ]]; then
    echo "DIFFERENT: scallop $command in ${prefix}clang" >&2
    failures=$((failures + 1))
  fi
done
if ((failures)); then
  echo "test-portability: $failures CLI outputs differ from the GCC -O3 build's" >&2
  exit 1
fi
step "all builds agree (${#commands[@]} CLI commands, golden tests in 3 builds)"
