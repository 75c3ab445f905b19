#!/usr/bin/env bash
# Installs what is missing, builds scallopd and the scallop CLI, and runs
# scallopd in the foreground on 127.0.0.1:50051 with its embedded default
# world (seed 1, d 1, A3) and one more named world, "coast". Ctrl-C stops it
# gracefully. Extra arguments go to scallopd (e.g. --listen 0.0.0.0:50051).
set -euo pipefail
cd "$(dirname "$0")/.."

bash scripts/install-deps.sh
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j2 --target scallopd scallop

cat <<'HELP'
scallopd is starting on 127.0.0.1:50051. In another terminal, try:

  ./build/client/scallop info   --server 127.0.0.1:50051
  ./build/client/scallop points --server 127.0.0.1:50051 --world default --rect 0,0,40,40
  ./build/client/scallop stream --server 127.0.0.1:50051 --seed 7 --rect -200,-200,200,200 --format none
  ./build/client/scallop points --server 127.0.0.1:50051 --world coast --rect -40,-40,40,40 \
      --format svg --seams > coast.svg
  ./build/client/scallop verify --server 127.0.0.1:50051 --seed 7 --algorithm a1 --rect -40,-40,40,40

Ctrl-C stops the server (health goes NOT_SERVING, in-flight calls finish).
HELP
exec ./build/server/scallopd --world coast:7:1:a3 "$@"
