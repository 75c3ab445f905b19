#!/usr/bin/env bash
# The Python example client (examples/python) against a real scallopd: stubs
# generated from our proto with Debian's tools, then its CSV compared byte for
# byte with `scallop plane` for paged, streamed, inline and named worlds, in
# the compact encodings, and over mutual TLS with a token; a bad rectangle, a refused handshake and a
# missing or wrong token reported with exit 1.
# Usage: python_client_test.sh SCALLOP_CLI SCALLOPD SOURCE_DIR
set -euo pipefail
cli=$1 scallopd=$2 source_dir=$3
python=/usr/bin/python3  # Debian's, where python3-grpcio is installed
work=$(mktemp -d)
server_pid=
cleanup() {
  [ -n "$server_pid" ] && kill "$server_pid" 2>/dev/null && wait "$server_pid" 2>/dev/null
  rm -rf "$work"
}
trap cleanup EXIT

bash "$source_dir/examples/python/generate_stubs.sh" "$work/stubs"
"$scallopd" --listen 127.0.0.1:0 --world hills:11:0.5:a1 >"$work/address" 2>"$work/log" &
server_pid=$!
for _ in $(seq 100); do grep -q listening "$work/address" 2>/dev/null && break; sleep 0.1; done
address=$(sed -n 's/^scallopd listening on //p' "$work/address")
[ -n "$address" ] || { echo "scallopd did not start"; cat "$work/log"; exit 1; }

client() { PYTHONPATH="$work/stubs" "$python" "$source_dir/examples/python/scallop_points.py" --server "$address" "$@"; }
compare() {  # compare NAME "CLIENT ARGS" "PLANE ARGS"
  read -ra client_args <<<"$2"
  read -ra plane_args <<<"$3"
  client "${client_args[@]}" >"$work/python.csv"
  "$cli" plane "${plane_args[@]}" >"$work/plane.csv"
  if ! cmp -s "$work/python.csv" "$work/plane.csv"; then
    echo "python client, $1: differs from scallop plane"; diff "$work/python.csv" "$work/plane.csv" | head; exit 1
  fi
  [ "$(wc -l <"$work/plane.csv")" -gt 10 ] || { echo "$1: too few points to judge"; exit 1; }
}
compare "paged inline world" "--seed 7 --rect=-20,-20,30,30 --page-size 100" "--seed 7 --rect -20,-20,30,30"
compare "streamed named world" "--world hills --stream --rect=-40,5,35,61" \
  "--seed 11 --min-distance 0.5 --algorithm a1 --rect -40,5,35,61"
compare "A2 with density" "--seed 3 --algorithm a2 --density 1.5 --rect=100,100,140,150" \
  "--seed 3 --algorithm a2 --density 1.5 --rect 100,100,140,150"
compare "noise radius field" "--seed 5 --radius-noise 1,3,0.02 --radius-noise-seed 2 --rect=-20,-20,30,30" \
  "--seed 5 --radius-noise 1,3,0.02 --radius-noise-seed 2 --rect -20,-20,30,30"
# The compact encodings (docs/wire.md): exact is byte for byte the plain
# CSV, paged and streamed, at the origin (8-byte offsets, -0.0's region),
# at -1e9 and 1e9 and for a field world; quantised has the same ids and
# coordinates within 2^-13 d, and is byte for byte what the C++ library
# decodes from the same answer (so both follow the proto's formula).
compare "exact, paged" "--seed 7 --encoding exact --page-size 97 --rect=-20,-20,30,30" \
  "--seed 7 --rect -20,-20,30,30"
compare "exact, streamed, far" "--seed 7 --encoding exact --stream --rect=-1e9,1e9,-999999950,1000000040" \
  "--seed 7 --rect -1e9,1e9,-999999950,1000000040"
compare "exact, field world" "--seed 5 --radius-noise 1,3,0.02 --encoding exact --stream --rect=1e9,-30,1000000050,20" \
  "--seed 5 --radius-noise 1,3,0.02 --rect 1e9,-30,1000000050,20"
for rect in -20,-20,30,30 1e9,-1e9,1000000050,-999999950; do
  client --seed 7 --encoding quantised --page-size 50 --rect="$rect" >"$work/quantised.csv"
  "$cli" points --server "$address" --seed 7 --encoding quantised --rect "$rect" >"$work/cpp-quantised.csv"
  "$cli" plane --seed 7 --rect "$rect" >"$work/plane.csv"
  cmp -s "$work/quantised.csv" "$work/cpp-quantised.csv" ||
    { echo "python client, quantised $rect: differs from the C++ library's decoding"; exit 1; }
  "$python" - "$work/quantised.csv" "$work/plane.csv" <<'PYTHON'
import sys
rows = [[line.split(",") for line in open(path).read().split()[1:]] for path in sys.argv[1:]]
quantised, plane = rows
if [r[0] for r in quantised] != [r[0] for r in plane] or len(plane) < 100:
    sys.exit("python client, quantised: other ids than scallop plane")
worst = max(abs(float(a) - float(b)) for q, p in zip(quantised, plane) for a, b in zip(q[1:], p[1:]))
# 2^-13 d (d = 1), plus 2^-23 for the decoding sum's rounding at 1e9.
if worst > 2**-13 + 2**-22 or worst == 0:
    sys.exit(f"python client, quantised: worst error {worst}")
PYTHON
done

# gRPC targets: a name resolved by DNS, two addresses balanced round_robin.
port=${address##*:}
address="dns:///localhost:$port" compare "dns:/// target" "--seed 7 --rect=-20,-20,30,30" \
  "--seed 7 --rect -20,-20,30,30"
address="ipv4:127.0.0.1:$port,127.0.0.1:$port" compare "ipv4: target" \
  "--seed 7 --rect=-20,-20,30,30 --page-size 50" "--seed 7 --rect -20,-20,30,30"
# The example's service config is the C++ library's.
PYTHONPATH="$work/stubs:$source_dir/examples/python" "$python" - \
  "$source_dir/client/library/service_config.h" <<'PYTHON'
import json, re, sys
import scallop_points
header = open(sys.argv[1]).read()
cpp = json.loads(re.search(r'R"json\((.*)\)json"', header, re.S).group(1))
if cpp != scallop_points.SERVICE_CONFIG:
    sys.exit(f"python client: SERVICE_CONFIG differs from service_config.h:\n{cpp}")
PYTHON

status=0
client --rect=10,0,0,10 >/dev/null 2>"$work/err" || status=$?
if [ "$status" != 1 ] || ! grep -q "INVALID_ARGUMENT: rect" "$work/err"; then
  echo "python client, inverted rect: exit $status, stderr: $(cat "$work/err")"; exit 1
fi
# Over mutual TLS with a bearer token, certificates made here.
bash "$source_dir/tests/e2e/make_test_certificates.sh" "$work"
echo "python-test-token-0123456789" >"$work/tokens"
echo "wrong-test-token-0123456789" >"$work/wrong-token"
"$scallopd" --listen 127.0.0.1:0 --tls-cert "$work/server.crt" --tls-key "$work/server.key" \
  --tls-client-ca "$work/ca.crt" --auth-tokens "$work/tokens" >"$work/secure-address" 2>"$work/secure-log" &
secure_pid=$!
for _ in $(seq 100); do grep -q listening "$work/secure-address" 2>/dev/null && break; sleep 0.1; done
address=$(sed -n 's/^scallopd listening on //p' "$work/secure-address")
[ -n "$address" ] || { echo "TLS scallopd did not start"; cat "$work/secure-log"; exit 1; }
tls="--tls-ca $work/ca.crt --tls-cert $work/client.crt --tls-key $work/client.key"
SCALLOP_TOKEN=python-test-token-0123456789 compare "mutual TLS and a token" \
  "$tls --seed 7 --rect=-20,-20,30,30" "--seed 7 --rect -20,-20,30,30"
expect_failure() {  # expect_failure WHAT CODE CLIENT-ARGS...
  local what=$1 code=$2 status=0
  shift 2
  client "$@" --timeout 5 --seed 7 --rect=0,0,10,10 >/dev/null 2>"$work/err" || status=$?
  if [ "$status" != 1 ] || ! grep -q "$code" "$work/err"; then
    echo "python client, $what: exit $status, stderr: $(cat "$work/err")"; exit 1
  fi
}
read -ra tls_args <<<"$tls"
expect_failure "TLS without a client certificate" UNAVAILABLE --tls-ca "$work/ca.crt"
expect_failure "no token" UNAUTHENTICATED "${tls_args[@]}"
expect_failure "a wrong token" UNAUTHENTICATED "${tls_args[@]}" --token-file "$work/wrong-token"
kill "$secure_pid"
echo "python client: the comparisons with scallop plane (a noise field and the encodings among them), the service config and 4 error cases passed"
