#!/bin/sh
# Where a cold GetPoints' time goes through scallopd, stage by stage (docs/design.md,
# issue 23's "What remains", the cold tile): builds scallopd and the load generator of HEAD
# in a scratch directory with the probe of scripts/cold-call-split/probe.patch (which no
# build carries), runs one cold stream against `scallopd --threads 2 --cache-megabytes 64`
# and joins each call's client times with its server stages (scripts/cold-call-split/split.py).
# The cache fills after about 215 calls, so the first 300 are left out.
#
# On a shared machine, PRIORITY='chrt -r 1' runs both processes at real-time priority, so
# the other work does not preempt them (as on an idle machine); keep such runs short.
#
# Usage: [PRIORITY=...] scripts/cold-call-split.sh [seconds = 6]
set -eu
repo=$(git rev-parse --show-toplevel)
seconds=${1:-6}
work=$(mktemp -d)
server=
trap '[ -n "$server" ] && kill "$server" 2>/dev/null; rm -rf "$work"' EXIT
git -C "$repo" archive HEAD | tar -x -C "$work"
patch -s -d "$work" -p1 < "$repo/scripts/cold-call-split/probe.patch"
cmake -S "$work" -B "$work/build" -G Ninja -DCMAKE_BUILD_TYPE=Release > /dev/null
cmake --build "$work/build" -j2 --target scallopd load_generator > /dev/null
SCALLOP_PROBE_FILE="$work/server.probe" ${PRIORITY:-} "$work/build/server/scallopd" \
  --listen 127.0.0.1:0 --threads 2 --cache-megabytes 64 > "$work/scallopd.out" 2> /dev/null &
server=$!
address=
for _ in $(seq 300); do
  address=$(sed -n 's/^scallopd listening on //p' "$work/scallopd.out" | head -1)
  [ -n "$address" ] && break
  sleep 0.1
done
[ -n "$address" ] || { echo "cold-call-split: scallopd did not start" >&2; exit 1; }
echo "# $(date -u '+%Y-%m-%d %H:%M UTC'), load:$(uptime | sed 's/.*load average://')${PRIORITY:+, $PRIORITY}"
SCALLOP_PROBE_CLIENT="$work/client.probe" ${PRIORITY:-} "$work/build/bench/load_generator" \
  --target "$address" --mode cold --streams 1 --duration "$seconds" --output text
kill "$server"
wait "$server" || true
server=
python3 "$repo/scripts/cold-call-split/split.py" "$work/server.probe" "$work/client.probe" 300
