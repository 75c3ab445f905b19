#!/usr/bin/env bash
# Installs what is missing, builds, and runs Scallop's demo. Until scallopd
# exists (issue 4) the demo samples a domain with A3 and prints statistics.
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j2 --target scallop
./build/client/scallop generate --algorithm a3 --min-distance 1 --domain 0,0,200,200 \
  --format svg --stats > scallop-demo.svg
echo "Wrote scallop-demo.svg (about 34k points); try: ./build/client/scallop generate --help"
