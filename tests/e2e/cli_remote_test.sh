#!/usr/bin/env bash
# End-to-end checks of the CLI's server commands against a real scallopd:
# `scallop points` and `scallop stream` print exactly what `scallop plane`
# prints (in every --encoding), the formats, and the exit codes (0 ok, 1
# server error, 2 bad args).
# Usage: cli_remote_test.sh path/to/scallop path/to/scallopd
set -euo pipefail

scallop=${1:?usage: cli_remote_test.sh path/to/scallop path/to/scallopd}
scallopd=${2:?usage: cli_remote_test.sh path/to/scallop path/to/scallopd}
# shellcheck source=../shell_checks.sh
source "$(dirname "$0")/../shell_checks.sh"

# Start on a free port (port 0) and read the address it prints.
start_scallopd server --listen 127.0.0.1:0 --world coast:7:1:a3
server_pid=$started_pid
server=$address

rect=-37.5,-20.25,41,50
run "$scallop" plane --seed 7 --rect "$rect"
cp "$work/out" "$work/plane.csv"
run "$scallop" points --server "$server" --seed 7 --rect "$rect"
expect_status 0 "points"
if cmp -s "$work/out" "$work/plane.csv"; then pass; else fail "points CSV differs from plane"; fi
run "$scallop" points --server "$server" --seed 7 --rect "$rect" --page-size 113
if cmp -s "$work/out" "$work/plane.csv"; then pass; else fail "paged points CSV differs from plane"; fi
run "$scallop" stream --server "$server" --seed 7 --rect "$rect"
expect_status 0 "stream"
if cmp -s "$work/out" "$work/plane.csv"; then pass; else fail "stream CSV differs from plane"; fi
run "$scallop" points --server "$server" --world coast --rect "$rect"
if cmp -s "$work/out" "$work/plane.csv"; then pass; else fail "named world differs from its inline twin"; fi
# gRPC targets: a name resolved by DNS, and a list of addresses balanced
# round_robin (here twice the same server).
run "$scallop" points --server "dns:///localhost:${server##*:}" --world coast --rect "$rect" --page-size 97
if cmp -s "$work/out" "$work/plane.csv"; then pass; else fail "dns:/// target: $(head -2 "$work/err")"; fi
run "$scallop" stream --server "ipv4:$server,$server" --world coast --rect "$rect"
if cmp -s "$work/out" "$work/plane.csv"; then pass; else fail "ipv4: target: $(head -2 "$work/err")"; fi
# At the default log level every call leaves a line.
if wait_for_log "$work/server.log" 'GetPoints world="seed=7 .* code=OK'; then pass; else
  fail "no request line at log level info: $(tail -3 "$work/server.log")"; fi

run "$scallop" plane --seed 7 --rect "$rect" --format json
cp "$work/out" "$work/plane.json"
run "$scallop" stream --server "$server" --seed 7 --rect "$rect" --format json
if cmp -s "$work/out" "$work/plane.json"; then pass; else fail "stream JSON differs from plane"; fi
run "$scallop" points --server "$server" --world coast --rect "$rect" --format svg --seams
expect_status 0 "svg"
if grep -q "<circle" "$work/out" && grep -q "<line" "$work/out"; then pass; else fail "svg lacks points or seams"; fi

run "$scallop" verify --server "$server" --seed 7 --rect -30,-30,30,30 --json
expect_status 0 "remote verify"
if grep -q '"passed":true' "$work/out"; then pass; else fail "remote verify did not pass"; fi
cp "$work/out" "$work/remote-verify.json"
run "$scallop" verify --seed 7 --rect -30,-30,30,30 --json
if cmp -s "$work/out" "$work/remote-verify.json"; then pass; else fail "remote verify report differs from local"; fi
run "$scallop" info --server "$server" --world coast
expect_status 0 "info"
if grep -q "SERVING" "$work/out" && grep -q "seed=7" "$work/out"; then pass; else fail "info output"; fi

# Server errors: exit 1, the code and message on stderr.
run "$scallop" points --server "$server" --seed 7 --rect 1e10,0,1.00001e10,10
expect_status 1 "beyond the precision range"
if grep -q "OUT_OF_RANGE: rect.x0" "$work/err"; then pass; else fail "OUT_OF_RANGE message: $(cat "$work/err")"; fi
run "$scallop" points --server "$server" --world atlantis --rect 0,0,1,1
expect_status 1 "unknown world"
if grep -q "NOT_FOUND: world_name" "$work/err"; then pass; else fail "NOT_FOUND message"; fi
run "$scallop" points --server "$server" --seed 7 --rect 0,0,5000,5000
expect_status 1 "area over the limit"
# Bad arguments: exit 2 without a call.
run "$scallop" points --server "$server" --seed 7 --rect 5,0,1,1
expect_status 2 "inverted rect"
run "$scallop" points --server "$server" --min-distance 0 --rect 0,0,1,1
expect_status 2 "zero d"
run "$scallop" points --rect 0,0,1,1
expect_status 2 "missing --server"
run "$scallop" points --server "$server" --world coast --seed 3 --rect 0,0,1,1
expect_status 2 "--world with --seed"
# An unreachable server is an error status (UNAVAILABLE), exit 1.
run "$scallop" points --server 127.0.0.1:1 --rect 0,0,1,1 --timeout 2
expect_status 1 "unreachable server"

# A YAML config: its worlds and limits are served; a bad one exits 2 naming the key.
cat >"$work/config.yaml" <<'YAML'
listen: 127.0.0.1:0
max_page_size: 500
default_world: dense
log_level: warn
worlds:
  dense: {seed: 9, min_distance: 0.5, algorithm: a1, density: 1.2}
YAML
start_scallopd server2 --config "$work/config.yaml"
config_pid=$started_pid
configured=$address
run "$scallop" info --server "$configured" --json
if grep -q '"default_world":"dense"' "$work/out" && grep -q '"max_page_size":500' "$work/out" &&
  grep -q 'density=1.2' "$work/out"; then pass; else fail "config file not applied: $(cat "$work/out")"; fi
# At log level warn successful calls leave no line, failed ones do.
run "$scallop" points --server "$configured" --rect 0,0,5,5
run "$scallop" points --server "$configured" --rect 0,0,100000,100000
if ! grep -q 'code=OK' "$work/server2.log" && grep -q 'GetPoints .*code=INVALID_ARGUMENT' "$work/server2.log"
then pass; else fail "log_level warn not applied: $(tail -3 "$work/server2.log")"; fi
kill -TERM "$config_pid"
wait "$config_pid" || fail "configured scallopd did not exit 0"
printf 'listen: 127.0.0.1:0\nmax_pages: 3\n' >"$work/bad.yaml"
run "$scallopd" --config "$work/bad.yaml"
expect_status 2 "bad config"
if grep -q "unknown setting 'max_pages'" "$work/err"; then pass; else fail "bad config message: $(cat "$work/err")"; fi
run "$scallopd" --log-level verbose
expect_status 2 "bad --log-level"
if grep -q "log_level: must be" "$work/err"; then pass; else fail "bad --log-level message: $(cat "$work/err")"; fi
run "$scallopd" --world "x:1:0:a3"
expect_status 2 "bad --world"
if grep -q "world.min_distance" "$work/err"; then pass; else fail "bad --world message: $(cat "$work/err")"; fi

# scallop follow: a step, a teleport, a return and a zoom. The union of its
# CSV is the union of `scallop plane` over the same rectangles; stderr has a
# line per step; a bad path line exits 2 naming it; a server error exits 1.
printf '%s\n' '# x0,y0,x1,y1' 0,0,40,30 3,1,43,31 1000,0,1040,30 '' 0,0,40,30 -20,-20,60,50 >"$work/path"
run "$scallop" follow --server "$server" --seed 7 --path "$work/path" --keep-margin 4
expect_status 0 "follow"
if [ "$(head -1 "$work/out")" = "id,x,y" ]; then pass; else fail "follow CSV header"; fi
tail -n +2 "$work/out" | sort -u >"$work/follow.sorted"
for rect in 0,0,40,30 3,1,43,31 1000,0,1040,30 -20,-20,60,50; do
  "$scallop" plane --seed 7 --rect "$rect" | tail -n +2
done | sort -u >"$work/plane.sorted"
if [ -s "$work/plane.sorted" ] && cmp -s "$work/follow.sorted" "$work/plane.sorted"; then pass; else fail "follow CSV differs from plane over the path"; fi
if [ "$(grep -c '^step [0-9]*: [0-9]* points, [0-9]* bytes, .* ms$' "$work/err")" -eq 5 ]; then pass; else fail "follow per-step report: $(cat "$work/err")"; fi
# --encoding: exact prints the same text for points, stream and follow (the
# library decodes it); quantised the same ids; an unknown name exits 2.
for command in "points --page-size 113" stream; do
  read -ra words <<<"$command"
  run "$scallop" "${words[@]}" --server "$server" --seed 7 --rect "$rect" --encoding exact
  if cmp -s "$work/out" "$work/plane.csv"; then pass; else fail "$command --encoding exact differs from plane"; fi
  run "$scallop" "${words[@]}" --server "$server" --seed 7 --rect "$rect" --encoding quantised
  if [ "$(cut -d, -f1 "$work/out")" = "$(cut -d, -f1 "$work/plane.csv")" ]; then pass; else fail "$command --encoding quantised: other ids"; fi
done
run "$scallop" follow --server "$server" --seed 7 --path "$work/path" --keep-margin 4 --encoding exact
if [ "$(tail -n +2 "$work/out" | sort -u)" = "$(cat "$work/follow.sorted")" ]; then pass; else fail "follow --encoding exact differs"; fi
run "$scallop" points --server "$server" --seed 7 --rect "$rect" --encoding zip
expect_status 2 "--encoding zip"
printf '0,0,10,10\n5,0,1,1\n' >"$work/bad-path"
run "$scallop" follow --server "$server" --seed 7 --path "$work/bad-path"
expect_status 2 "follow bad path line"
if grep -q -- "--path line 2: X0 must be less than X1" "$work/err"; then pass; else fail "follow bad path message: $(cat "$work/err")"; fi
printf '1e10,0,1.00001e10,10\n' >"$work/far-path"
run "$scallop" follow --server "$server" --seed 7 --path "$work/far-path"
expect_status 1 "follow beyond the precision range"
if grep -q "OUT_OF_RANGE: viewport.x0" "$work/err"; then pass; else fail "follow OUT_OF_RANGE message: $(cat "$work/err")"; fi

# scallop nearest and noise through scallopd: the same CSV and PNG as the
# local core, bit for bit; in batches of the server's max_nearest_batch (a
# server allowing 7 answers 101 positions in 15 calls); server errors exit 1.
awk 'BEGIN { srand(5); for (k = 0; k < 100; ++k) printf "%.17g,%.17g\n", rand() * 100 - 50, rand() * 100 - 50 }' >"$work/positions"
echo "16,-32" >>"$work/positions"
run "$scallop" nearest --seed 7 --input "$work/positions"
cp "$work/out" "$work/nearest.csv"
run "$scallop" nearest --server "$server" --seed 7 --input "$work/positions"
expect_status 0 "nearest --server"
if [ "$(wc -l <"$work/out")" -eq 102 ] && cmp -s "$work/out" "$work/nearest.csv"; then pass; else fail "nearest --server CSV differs from local"; fi
run "$scallop" nearest --server "$server" --world coast --input "$work/positions"
if cmp -s "$work/out" "$work/nearest.csv"; then pass; else fail "nearest --world coast differs from --seed 7"; fi
printf '0,0\n1e20,0\n' >"$work/far_positions"
run "$scallop" nearest --server "$server" --seed 7 --input "$work/far_positions"
expect_status 1 "nearest beyond the precision range"
if grep -q "OUT_OF_RANGE: positions\[1\].x" "$work/err"; then pass; else fail "nearest OUT_OF_RANGE message: $(cat "$work/err")"; fi
"$scallop" noise --seed 7 --rect -8,-4,24,12 --size 64x32 --channel f2-f1 --png "$work/local.png"
run "$scallop" noise --server "$server" --world coast --rect -8,-4,24,12 --size 64x32 --channel f2-f1 --png "$work/remote.png"
expect_status 0 "noise --server"
if cmp -s "$work/local.png" "$work/remote.png"; then pass; else fail "noise --server PNG differs from local"; fi

printf 'listen: 127.0.0.1:0\nmax_nearest_batch: 7\nmax_noise_grid_samples: 5000\n' >"$work/small.yaml"
start_scallopd server3 --config "$work/small.yaml"
small_pid=$started_pid
small=$address
run "$scallop" nearest --server "$small" --seed 7 --input "$work/positions"
expect_status 0 "nearest in batches of 7"
if cmp -s "$work/out" "$work/nearest.csv"; then pass; else fail "nearest in batches of 7 differs from local"; fi
if wait_for_log "$work/server3.log" Nearest 15 && [ "$(grep -c Nearest "$work/server3.log")" -eq 15 ]; then pass; else fail "nearest: want 15 calls of 7: $(grep -c Nearest "$work/server3.log")"; fi
run "$scallop" noise --server "$small" --seed 7 --rect 0,0,100,100 --size 100x100 --png "$work/big.png"
expect_status 1 "noise over max_noise_grid_samples"
if grep -q "INVALID_ARGUMENT: width \* height.*max_noise_grid_samples" "$work/err"; then pass; else fail "noise limit message: $(cat "$work/err")"; fi
kill -TERM "$small_pid"
wait "$small_pid" || fail "small scallopd did not exit 0"

kill -TERM "$server_pid"
wait "$server_pid" && server_status=0 || server_status=$?
server_pid=
if [ "$server_status" -eq 0 ]; then pass; else fail "scallopd exit $server_status on SIGTERM"; fi

report cli_remote_test
