#!/usr/bin/env bash
# The Python example client (examples/python) against a real scallopd: stubs
# generated from our proto with Debian's tools, then its CSV compared byte for
# byte with `scallop plane` for paged, streamed, inline and named worlds and
# over mutual TLS with a token; a bad rectangle, a refused handshake and a
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
echo "python client: the comparisons with scallop plane (a noise field among them), the service config and 4 error cases passed"
