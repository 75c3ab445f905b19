#!/usr/bin/env bash
# End-to-end checks of the CLI against a scallopd on mutual TLS with bearer
# tokens, certificates made here: the same points as `scallop plane`,
# refusals without the right certificate or token, and scallopd refusing to
# start, with the file named, on bad TLS or token settings.
# Usage: cli_secure_test.sh path/to/scallop path/to/scallopd
set -euo pipefail

scallop=${1:?usage: cli_secure_test.sh path/to/scallop path/to/scallopd}
scallopd=${2:?usage: cli_secure_test.sh path/to/scallop path/to/scallopd}
# shellcheck source=../shell_checks.sh
source "$(dirname "$0")/../shell_checks.sh"
expect_err() {
  if grep -q -- "$1" "$work/err"; then pass; else fail "$2: stderr lacks '$1': $(cat "$work/err")"; fi
}

bash "$(dirname "$0")/make_test_certificates.sh" "$work"
tls_server=(--tls-cert "$work/server.crt" --tls-key "$work/server.key" --tls-client-ca "$work/ca.crt")
tls_client=(--tls-ca "$work/ca.crt" --tls-cert "$work/client.crt" --tls-key "$work/client.key")

printf '# test tokens\nall-worlds-token-0123456789\ncoast-only-token-0123456789 coast\n' >"$work/tokens"
echo all-worlds-token-0123456789 >"$work/token"
echo coast-only-token-0123456789 >"$work/coast-token"

mkfifo "$work/address"
"$scallopd" --listen 127.0.0.1:0 "${tls_server[@]}" --auth-tokens "$work/tokens" \
  --world coast:7:1:a3 >"$work/address" 2>"$work/server.log" &
server_pid=$!
read -r line <"$work/address"
server=${line#scallopd listening on }
# Health needs no token.
run "$scallop" health --server "$server" --timeout 20 "${tls_client[@]}"
expect_status 0 "health over mutual TLS"
tls_client+=(--token-file "$work/token")

rect=-10,-10,30,25
run "$scallop" plane --seed 7 --rect "$rect"
cp "$work/out" "$work/plane.csv"
run "$scallop" points --server "$server" --seed 7 --rect "$rect" "${tls_client[@]}"
expect_status 0 "points over mutual TLS"
if cmp -s "$work/out" "$work/plane.csv"; then pass; else fail "points over TLS differ from plane"; fi
run "$scallop" stream --server "$server" --seed 7 --rect "$rect" "${tls_client[@]}"
if cmp -s "$work/out" "$work/plane.csv"; then pass; else fail "stream over TLS differs from plane"; fi

# Tokens: missing, wrong, from SCALLOP_TOKEN, limited to a world.
run "$scallop" points --server "$server" --seed 7 --rect "$rect" "${tls_client[@]:0:6}"
expect_status 1 "points without a token"
expect_err "UNAUTHENTICATED" "points without a token"
run env SCALLOP_TOKEN=wrong-token-0123456789 "$scallop" points --server "$server" --seed 7 \
  --rect "$rect" "${tls_client[@]:0:6}"
expect_status 1 "points with a wrong token"
expect_err "UNAUTHENTICATED" "points with a wrong token"
run env SCALLOP_TOKEN=all-worlds-token-0123456789 "$scallop" points --server "$server" --seed 7 \
  --rect "$rect" "${tls_client[@]:0:6}"
expect_status 0 "points with SCALLOP_TOKEN"
if cmp -s "$work/out" "$work/plane.csv"; then pass; else fail "points with SCALLOP_TOKEN differ from plane"; fi
run "$scallop" points --server "$server" --world coast --rect "$rect" "${tls_client[@]:0:6}" \
  --token-file "$work/coast-token"
expect_status 0 "points of coast with the coast token"
if cmp -s "$work/out" "$work/plane.csv"; then pass; else fail "coast points differ from plane"; fi
run "$scallop" points --server "$server" --seed 7 --rect "$rect" "${tls_client[@]:0:6}" \
  --token-file "$work/coast-token"
expect_status 1 "an inline world with the coast token"
expect_err "PERMISSION_DENIED" "an inline world with the coast token"
# A --token-file wins over SCALLOP_TOKEN in the environment.
run env SCALLOP_TOKEN=all-worlds-token-0123456789 "$scallop" points --server "$server" --seed 7 \
  --rect "$rect" "${tls_client[@]:0:6}" --token-file "$work/coast-token"
expect_status 1 "--token-file over SCALLOP_TOKEN"
expect_err "PERMISSION_DENIED" "--token-file over SCALLOP_TOKEN"
run "$scallop" info --server "$server" "${tls_client[@]:0:6}" --token-file "$work/missing-token"
expect_status 2 "missing --token-file"
expect_err "--token-file: cannot read '$work/missing-token'" "missing --token-file"

# Refused: plaintext, no client certificate, a client certificate of another CA.
run "$scallop" info --server "$server" --timeout 5
expect_status 1 "info over plaintext to a TLS port"
run "$scallop" info --server "$server" --timeout 5 --tls-ca "$work/ca.crt"
expect_status 1 "info without a client certificate"
run "$scallop" info --server "$server" --timeout 5 --tls-ca "$work/ca.crt" \
  --tls-cert "$work/other-client.crt" --tls-key "$work/other-client.key"
expect_status 1 "info with a client certificate of another CA"
# Bad client files: exit 2 naming the flag, before any call.
run "$scallop" info --server "$server" --tls-ca "$work/missing.crt"
expect_status 2 "missing --tls-ca"
expect_err "--tls-ca: cannot read '$work/missing.crt'" "missing --tls-ca"
run "$scallop" info --server "$server" --tls-ca "$work/ca.key"
expect_status 2 "--tls-ca naming a key"
expect_err "--tls-ca: '$work/ca.key' holds no PEM CERTIFICATE" "--tls-ca naming a key"
run "$scallop" info --server "$server" --tls-cert "$work/client.crt"
expect_status 2 "--tls-cert without --tls-key"

kill -TERM "$server_pid"
wait "$server_pid" || fail "TLS scallopd did not exit 0"
server_pid=

# scallopd refuses to start on bad TLS settings, naming the setting and file.
run "$scallopd" --listen 127.0.0.1:0 --tls-cert "$work/server.crt"
expect_status 2 "--tls-cert without --tls-key"
expect_err "tls_cert and tls_key: give both" "--tls-cert without --tls-key"
run "$scallopd" --listen 127.0.0.1:0 --tls-cert "$work/missing.crt" --tls-key "$work/server.key"
expect_status 2 "missing --tls-cert"
expect_err "tls_cert: cannot read '$work/missing.crt'" "missing --tls-cert"
run "$scallopd" --listen 127.0.0.1:0 --tls-cert "$work/server.key" --tls-key "$work/server.key"
expect_status 2 "--tls-cert naming a key"
expect_err "tls_cert: '$work/server.key' holds no PEM certificate" "--tls-cert naming a key"
run "$scallopd" --listen 127.0.0.1:0 --tls-cert "$work/server.crt" --tls-key "$work/client.key"
expect_status 2 "--tls-key of another certificate"
expect_err "tls_key: '$work/client.key' is not the key of tls_cert" "--tls-key of another certificate"
run "$scallopd" --listen 127.0.0.1:0 "${tls_server[@]:0:4}" --tls-client-ca "$work/server.key"
expect_status 2 "--tls-client-ca naming a key"
expect_err "tls_client_ca: '$work/server.key' holds no PEM certificate" "--tls-client-ca naming a key"
run "$scallopd" --listen 127.0.0.1:0 --auth-tokens "$work/missing-tokens"
expect_status 2 "missing --auth-tokens"
expect_err "auth_tokens: cannot read '$work/missing-tokens'" "missing --auth-tokens"
run "$scallopd" --listen 127.0.0.1:0 --auth-tokens "$work/tokens"
expect_status 2 "a token limited to an unconfigured world"
expect_err "auth_tokens: $work/tokens:3: no configured world named 'coast'" "unconfigured world"

report cli_secure_test
